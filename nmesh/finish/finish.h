// nmesh/finish.h — the finishing stage: a few passes over the learnt mesh once it has reached its
// target size, for the shape of its triangles and a clean embedding (no folds, no
// self-intersections). A choice beyond the paper, on by default (Parameters::finish).
//
// The learning leaves defects that no step of the paper's algorithm removes: thin triangles (the
// connectivity is whatever the splits, collapses and swaps left), small folds (adjacent triangles
// turned back onto each other where a vertex overshot) and, in places such as a tightly bent ear,
// tangles whose triangles cross one another. The stage runs on the engine's final mesh and the
// (normalised) cloud:
//   1. regularisation, a few rounds of: angle-improving (Delaunay) edge flips restricted to nearly
//      coplanar pairs; a tangential relaxation of every vertex towards the area-weighted centroid
//      of its triangles, the vertex then pulled along its normal towards the plane through its
//      nearest cloud point (CloudSurface::pull: at most a quarter of an edge per round, only
//      towards a point facing the same way; a vertex that would end more than an edge from the
//      cloud, farther than it was, stays where it is);
//   2. repair of folds and self-intersections: local smoothing, collapses of very short and splits
//      of very long edges around each defect until none is left, then the smoothed vertices are
//      pulled back towards the cloud wherever that creates no new defect. The repair is all or
//      nothing: if a defect is left, or the estimated Hausdorff distance to the cloud would grow
//      by more than half an edge, the mesh is put back as the regularisation left it.
// When the repair does not succeed, the stage never returns a mesh with more intersecting
// triangle pairs than the learnt one (see FinishReport::fallback).
// The vertex count never changes (collapses and splits are balanced at once) and every
// topology operation is taken only when the mesh allows it (Mesh::can_flip, can_collapse), so the
// result is a closed genus-0 2-manifold with exactly the vertices asked for.
// Each pass is O(n) for a mesh of n vertices (the repair is local to the defects), whatever the
// size of the cloud: a cloud larger than the mesh is read in full only by is_flat() and by the
// nearest-point index (see CloudSurface and estimate_hausdorff for how the rest follows the
// mesh), and reconstruct() gives it no more than 64 points per vertex (the stratified sample of
// nmesh/cloud_sample.h, with the engine's index over it). About 0.30 s for the 30,000-vertex
// bunny, against 1.3 s of learning; 0.55 s for 30,000 vertices from 36 million points on a
// sphere through reconstruct() (26 s when every point had its own normal and its own term in
// the repair's estimate, 2.1 s when the stage still worked on every point).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

struct FinishOptions {
    // Regularisation rounds (flips, then relaxation). 0 skips step 1. Each round makes the
    // triangles more regular and moves the vertices further off the scan points the learning left
    // them on; ten is the default (docs/algorithm.md, Finishing stage).
    int rounds = 10;
    // Flips only between triangles whose normals differ by less than this, before and after.
    float flip_max_dihedral_deg = 20.0f;
    // Pull the relaxed vertices towards the cloud (otherwise the relaxation is purely tangential,
    // and the repair has neither its pull-back nor its Hausdorff guard).
    bool project = true;
    // Repair (step 2): at most this many rounds; 0 skips the repair. The rounds run only while
    // defects remain, so the limit changes only the repairs that need more. How many a repair
    // needs depends on the face numbering (a round treats the defective triangles in face order).
    int repair_max_rounds = 80;
    // An edge is folded when the normals of its two triangles differ by more than this.
    float fold_dihedral_deg = 120.0f;
    // Centroid fit, off by default: each round moves every vertex so that the centroids of its
    // triangles approach the mean of the cloud points that have them as nearest centroid (a damped
    // Lloyd step of the quantiser that DM(X,T) measures), then flips. It lowers DM(X,T) on the
    // cloud it is fitted to, but not the distance to other samples of the same surface: a fit to
    // the measure, not a better surface; hence off.
    int fit_rounds = 0;
    float fit_weight = 0.3f;
};

struct FinishReport {
    bool skipped_flat = false;                  // a flat cloud: the stage did nothing
    std::uint64_t flips = 0;                    // all flip passes together
    std::uint32_t relax_passes = 0;
    std::size_t intersecting_pairs_before = 0;  // at the start of the repair
    std::size_t folded_edges_before = 0;
    std::size_t intersecting_pairs_after = 0;   // at the end (as before when reverted)
    std::size_t folded_edges_after = 0;
    std::uint32_t repair_rounds = 0;
    bool repair_reverted = false;               // the repair did not succeed and was undone
    // When the repair of the regularised mesh fails and that mesh has more intersecting pairs than
    // the learnt one, the stage falls back on the learnt mesh, repaired if possible.
    enum class Fallback { none, repaired_learnt_mesh, learnt_mesh };
    Fallback fallback = Fallback::none;
    double seconds = 0.0;
};

// Runs the stage on `mesh` (positions in the same frame as `cloud`, which must not be empty),
// first building its face index when it has none (Mesh::build_faces); the passes below, used
// alone, need a mesh that has one.
// A flat cloud (is_flat) is left alone: its mesh is two coinciding sheets, every triangle touching
// one of the other sheet, and no normal tells the sides apart.
// `cloud_index`: a nearest-point index over exactly the points of `cloud`, in the same order and
// frame (for instance the learning engine's, built over the same points through a
// PointTransform), which then is not built again; null: the stage builds its own.
FinishReport finish_mesh(Mesh& mesh, const std::vector<Vec3>& cloud, const FinishOptions& options = {},
                         const PointGrid* cloud_index = nullptr);

// Whether all the points lie in one plane (up to 1e-6 of their extent).
bool is_flat(const std::vector<Vec3>& cloud);

// ---- the passes, also usable alone ----------------------------------------------------------------

// Flips every edge whose two opposite angles sum to more than 180 degrees (it is not locally
// Delaunay) when its two triangles are nearly coplanar before and after the flip (normals within
// max_dihedral_deg of each other, the new triangles facing the old ones' side) and Mesh::can_flip
// allows it, until no such edge is left (at most 8 flips per edge). Only the connectivity
// changes. Returns the number of flips.
std::uint64_t flip_to_delaunay(Mesh& mesh, float max_dihedral_deg = 20.0f);

// The cloud as the surface the relaxation pulls vertices towards. Each point has a normal, that
// of its nearest vertex in `mesh` (the learnt mesh), which tells the two sides of a part thinner
// than a triangle apart.
// Choice: for a cloud of more than kStoredNormalsPerVertex points per mesh vertex, a point's normal
// is looked up when a pull needs it (its nearest vertex found in an index over the learnt mesh's
// vertices, whose normals are computed once) instead of being stored for every point, so that
// the stage's cost and memory follow the mesh, not the cloud: 36 million points and 30,000
// vertices would otherwise take 36 million nearest-vertex queries and 430 MB of normals, for the
// few hundred thousand pulls of the stage. A smaller cloud keeps them all, computed at once, which
// costs less than a query per pull. Either way a point's normal is the same.
class CloudSurface {
public:
    static constexpr std::size_t kStoredNormalsPerVertex = 8;

    // `points` (and `index`, a nearest-point index over exactly those points, or null to build
    // one) must outlive the object. O(m) for a mesh of m vertices, O(n) more for n points when
    // their normals are stored; plus building `index` when none is given.
    CloudSurface(const std::vector<Vec3>& points, const Mesh& mesh, const PointGrid* index = nullptr);
    // q moved along the unit normal n towards the plane through its nearest cloud point (normal
    // n), by at most `limit`; q itself when that point faces the other way (its normal against n)
    // or lies farther than `reach` from q (q is over a hole in the scan).
    Vec3 pull(const Vec3& q, const Vec3& n, float limit, float reach) const;
    // The same with the nearest cloud point to q already known.
    Vec3 pull(const Vec3& q, const Vec3& n, float limit, float reach, const NearestPoint& near) const;
    const std::vector<Vec3>& points() const { return points_; }
    const PointGrid& index() const { return *index_; }
    // The normal of cloud point i: that of its nearest vertex in the learnt mesh.
    const Vec3& normal(std::uint32_t i) const {
        return point_normals_.empty() ? vertex_normals_[vertex_index_->nearest(points_[i])] : point_normals_[i];
    }
    // Whether every point's normal was computed at construction (a cloud of at most
    // kStoredNormalsPerVertex points per mesh vertex).
    bool stores_point_normals() const { return !point_normals_.empty(); }

private:
    const std::vector<Vec3>& points_;
    std::unique_ptr<PointGrid> own_index_;  // when none was given
    const PointGrid* index_;
    std::unique_ptr<PointGrid> vertex_index_;  // over the learnt mesh's vertices
    std::vector<Vec3> vertex_normals_;         // their normals, in the index's order
    std::vector<Vec3> point_normals_;          // per cloud point, or empty (see the choice above)
};

// One round of tangential relaxation (all vertices moved from their old positions): every vertex
// moves to the area-weighted centroid of its triangles' centroids, minus the normal component of
// that move; with `cloud`, it is then pulled towards the cloud by at most a quarter of its mean
// edge length (CloudSurface::pull, reach: its mean edge length), and a vertex whose move would end
// farther from the cloud than the mesh's mean edge length, and farther than it was, stays.
void relax_tangentially(Mesh& mesh, const CloudSurface* cloud = nullptr);

// The Hausdorff distance between `mesh` and the cloud of `surface` as the repair estimates it, to
// refuse a repair that would move the surface away from the cloud: the larger of (a) the distance
// from each measured cloud point to the triangles around its nearest vertex and (b) the surface's
// largest distance to the cloud, measured to within an eighth of the mean edge length. Every cloud point is
// measured up to 16 points per mesh vertex; beyond, every s-th point, s the smallest stride that
// leaves at most 16 per vertex, so that the cost follows the mesh. O(m) for m vertices.
float estimate_hausdorff(const Mesh& mesh, const CloudSurface& surface);

// One damped Lloyd step of the centroids towards the cloud (see FinishOptions::fit_rounds).
void fit_centroids(Mesh& mesh, const std::vector<Vec3>& cloud, float weight);

// Every pair of triangles that share no vertex and intersect (touching counts), as
// nmesh::triangles_intersect decides, each pair once, smaller face first, sorted; degenerate
// triangles are skipped, as the metrics do. Expected O(F) through a hash grid of the triangles'
// bounding boxes.
std::vector<std::pair<Face, Face>> find_self_intersections(const Mesh& mesh);

// Edges whose two triangles' normals differ by more than `dihedral_deg`, and edges of degenerate
// (zero-area) triangles.
std::vector<Edge> find_folded_edges(const Mesh& mesh, float dihedral_deg = 120.0f);

// Splits the edge of h at its midpoint (Mesh::split): the new vertex has valence 4 and the four
// new triangles cover exactly the two old ones. Returns the new vertex.
Vertex split_edge(Mesh& mesh, Halfedge h);

struct RepairResult {
    std::size_t intersecting_pairs_before = 0;
    std::size_t folded_edges_before = 0;
    std::size_t intersecting_pairs = 0;  // left (as before when reverted)
    std::size_t folded_edges = 0;
    std::uint32_t rounds = 0;
    bool reverted = false;  // the mesh was put back as it came
};

// Step 2 of the stage (see finish.cpp for the details). With `cloud`, the smoothed vertices are
// pulled back towards it, and the repair is undone if it raises the (estimated) Hausdorff distance
// to the cloud by more than half the mean edge length. Keeps the vertex count; all or nothing.
RepairResult repair_folds_and_intersections(Mesh& mesh, int max_rounds = 40, float fold_dihedral_deg = 120.0f,
                                            const CloudSurface* cloud = nullptr);

}  // namespace nmesh
