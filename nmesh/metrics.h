// nmesh/metrics.h — quality metrics of a reconstruction (an IndexedMesh) against its point cloud.
//
// Distances are in the units of the cloud. Each distance is also reported relative to the cloud's
// bounding-box diagonal (the *_rel fields), so that results on clouds of different scale compare.
//
//   DM(X,T)            the paper's measure, eq. (10)-(11): the mean over the cloud points of the
//                      distance to the nearest triangle centroid.
//   point-to-surface   each cloud point to the nearest point of the surface (exact point-triangle
//                      distance): mean, RMS, max.
//   surface-to-cloud   the surface to the nearest cloud point: the mean over points sampled
//                      uniformly by area, and the max, exact to within 1e-5 of the larger of the
//                      cloud's and the mesh's bounding-box diagonals (branch and bound over each
//                      triangle). Both depend on the triangles' corners only, not on the order
//                      they are listed in, their first corners or the vertex numbering.
//   Hausdorff          max(point-to-surface max, surface-to-cloud max).
//   topology           closed, manifold, Euler characteristic, genus, components, boundary loops,
//                      edges and length, self-intersections (exact), degenerate triangles.
//   orientation        signed volume, faces pointing inward.
//   triangle quality   the smallest angle of each triangle: min, mean, share under 10 degrees.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/point_span.h"
#include "nmesh/vec3.h"

namespace nmesh {

struct EvalOptions {
    // Surface samples for the surface-to-cloud distance. 200,000 spaces them about 0.2% of the
    // diagonal apart on the bunny (0.5 mm on its 0.057 m^2), finer than its scan spacing.
    std::size_t surface_samples = 200000;
    // Seed of the sampling; fixed so that two evaluations of the same mesh agree exactly.
    std::uint64_t seed = 1;
    // Called with the share of the cloud's points measured so far (0 to 1), about every 2^18
    // points and once at the end of that pass, which is most of the work on a large cloud: one
    // exact nearest-triangle search per point. May be empty.
    std::function<void(double fraction)> progress;
    // Threads for the per-point and per-face work (the nearest triangles, the surface samples'
    // distances, the crossing and inward faces): 0, the machine's cores, or 1 to 1024. The report
    // is the same, bit for bit, for every count: sums are taken in the points' order. progress is
    // called on the calling thread.
    std::uint32_t threads = 0;
};

// The topology of a triangle mesh, over the vertices used by at least one triangle. A boundary
// edge lies in exactly one triangle.
struct MeshTopology {
    // Every edge lies in exactly two triangles (no boundary edge, no edge shared by three or more).
    bool closed = false;
    // A surface, with or without boundary: every edge lies in one or two triangles, two triangles
    // on one edge run it in opposite directions (consistently oriented, hence orientable), no
    // triangle repeats a vertex, and the triangles around every vertex form a single fan, linked
    // through shared edges (no bow-tie vertex, where fans meet only at their tip).
    bool manifold = false;
    long long euler = 0;  // the Euler characteristic chi = V - E + F
    // The number of handles: the sum over components of (2 - chi - b) / 2, with chi and b the
    // component's Euler characteristic and boundary loops (0 for a sphere, a disc or a tube, 1 for
    // a torus with or without holes). -1 unless manifold.
    int genus = -1;
    std::size_t components = 0;         // connected through shared vertices
    std::size_t isolated_vertices = 0;  // positions used by no triangle
    // Boundary edges fall into loops: at each vertex, the boundary edges of the triangles of one
    // fan there are in one loop. On a manifold each boundary vertex has one boundary edge in and
    // one out, and each loop is a closed polygon, a hole's rim. Elsewhere a loop may branch or
    // stop short: two triangles sharing only a corner have a loop each, and a loop ends where it
    // meets an edge of three or more triangles.
    std::size_t boundary_loops = 0;  // 0 when closed
    std::size_t boundary_edges = 0;
    double boundary_length = 0.0;  // the boundary edges' total length, in the mesh's units
};

struct QualityReport {
    // Sizes.
    std::size_t vertices = 0;  // positions in the mesh, referenced or not
    std::size_t faces = 0;
    double bbox_diagonal = 0.0;  // of the cloud; the unit of the *_rel fields

    // Distances (cloud units) and the same relative to bbox_diagonal (NaN when it is 0).
    double dm_x_t = 0.0, dm_x_t_rel = 0.0;
    double p2s_mean = 0.0, p2s_mean_rel = 0.0;
    double p2s_rms = 0.0, p2s_rms_rel = 0.0;
    double p2s_max = 0.0, p2s_max_rel = 0.0;
    double s2p_mean = 0.0, s2p_mean_rel = 0.0;
    double s2p_max = 0.0, s2p_max_rel = 0.0;
    double hausdorff = 0.0, hausdorff_rel = 0.0;

    // Topology: the fields of MeshTopology (see there), the boundary's length also relative to
    // bbox_diagonal.
    bool closed = false;                // every edge in exactly two triangles
    bool manifold = false;              // a surface with or without boundary, oriented, no bow-tie vertex
    long long euler = 0;                // V - E + F
    int genus = -1;                     // handles, summed over components; -1 unless manifold
    std::size_t components = 0;         // connected through shared vertices
    std::size_t isolated_vertices = 0;  // positions used by no triangle
    std::size_t boundary_loops = 0;     // holes' rims (0 when closed)
    std::size_t boundary_edges = 0;     // edges in exactly one triangle
    double boundary_length = 0.0, boundary_length_rel = 0.0;
    std::size_t degenerate_triangles = 0;  // a repeated vertex or zero area
    // Pairs of non-degenerate triangles that intersect, by an exact test: triangles sharing no
    // vertex that have any point in common, triangles sharing one vertex that meet anywhere else
    // (a fold round that vertex), triangles sharing an edge that overlap beyond it (folded flat
    // onto each other).
    std::size_t self_intersections = 0;
    // Orientation. The signed volume is positive when a closed mesh faces outward; a face points
    // inward when the point just off it along its normal is inside the surface (a nonzero
    // winding number), which marks a part turned inside out (0 unless closed).
    double signed_volume = 0.0;
    std::size_t inward_faces = 0;

    // Triangle quality, from the smallest angle of each triangle (0 for degenerate ones).
    double min_angle_min_deg = 0.0;
    double min_angle_mean_deg = 0.0;
    double share_under_10deg = 0.0;  // fraction in [0, 1]
};

// Computes every metric. Cost for n points, F triangles and S samples: O(n log F + S + F log F),
// plus the pairs of triangles whose boxes overlap, plus the pieces the surface-to-cloud maximum
// cuts its triangles into (few: only near the farthest parts of the surface; at most 256 per
// triangle, beyond which it returns the largest distance found so far) — about 0.3 s for the
// bunny scan (36k points) against its 69k-triangle mesh.
// Throws InputError if `points` is empty, if a point or a mesh vertex has a NaN or infinite
// coordinate, if the mesh has no triangle, or if a triangle refers to a vertex that does not
// exist; ParameterError if options.surface_samples is 0 or options.threads above 1024.
QualityReport evaluate(PointSpan points, const IndexedMesh& mesh, const EvalOptions& options = {});

// The topology of `mesh`, as evaluate() reports it, without a cloud (for `nmesh info`).
// O(F log F) for F triangles. Throws InputError if a triangle refers to a vertex that does not
// exist. Coordinates matter only to boundary_length (not finite when a boundary vertex is not).
MeshTopology mesh_topology(const IndexedMesh& mesh);

// The report as one flat JSON object, keys named as the fields above (genus when -1 and undefined
// relative values are written as null). No trailing newline.
void write_json(std::ostream& out, const QualityReport& report);
// The report as aligned "name: value" lines, for people.
void write_text(std::ostream& out, const QualityReport& report);

// DM(X,T), eq. (10)-(11) of the paper: the mean over the points x of the distance from x to the
// nearest triangle centroid (a + b + c) / 3, centroids computed in float. The paper writes the
// normalisation as 1 / size(T) but sums over the cloud points and calls the measure "the mean
// error between the set of points X and the centroids"; this divides by the number of points.
// O(n + F) expected. Throws InputError as evaluate() does.
double dm_cloud_to_centroids(PointSpan points, const IndexedMesh& mesh);

// Distance from each mesh position to the nearest point of `cloud` (for colouring an error map).
// O(V) queries.
std::vector<float> vertex_distances_to_cloud(PointSpan cloud, const IndexedMesh& mesh);

// Squared distance from p to the triangle abc (its closest point may lie inside, on an edge or at
// a vertex), computed in double. Degenerate triangles are handled (distance to a segment or point).
double point_triangle_squared_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// Whether the closed triangles abc and def share at least one point (touching counts), coplanar
// pairs included, decided exactly from the float coordinates (adaptive-precision orientation
// signs). Both triangles must be non-degenerate.
bool triangles_intersect(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e, const Vec3& f);

// The smallest interior angle of the triangle abc, in degrees (0 for a degenerate triangle).
double min_angle_deg(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace nmesh
