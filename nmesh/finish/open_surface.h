// nmesh/finish/open_surface.h — Parameters::topology open: the closed result opened where the
// cloud has no data, the one sheet of a partial view, and no crossing triangles.
//
// The learning makes a closed surface; these steps cut it open, each keeping a manifold with
// boundary, without bow-ties. The cloud is read once (view_cloud): its rim (nmesh/finish/
// cloud_rim.h), its local spacing, and whether it is a partial view: one layer of points seen
// from some direction (nmesh/finish/cloud_layers.h). reconstruct() then runs:
//  1. on a partial view only, the view's sheet in place of the learnt mesh (view_sheet,
//     nmesh/finish/view_sheet.h), in one or more pieces (nmesh/mesh/mesh_pieces.h), each
//     finished as a mesh of its own;
//  2. Unsupported faces (cut_unsupported), on the finished mesh (each piece of it). A face whose
//     centroid is farther from every cloud point than kOpenEdges typical edge lengths (the median over the
//     faces) and kOpenSpacings local point spacings (nmesh/finish/cloud_rim.h, so a sparse part
//     of a scan is not shredded) has no data. An edge-connected region of such faces goes when it
//     is a hole in the scan or lies beyond the scan's end, told by its depth (the distance of its
//     deepest face to the cloud, in limits: the larger of kOpenEdges typical edges and
//     kOpenSpacings global spacings) and by the cloud's rim (the points at the edge of the
//     sampled surface) within kOpenRimReach depths of the deepest face:
//     - a hole: the rim points surround the deepest face (seen along its normal, no free sector
//       of kOpenSurroundGap or more) and the depth is at least kOpenHoleDepth; or, with the
//       smallest hole to open given (Parameters::min_hole, in local spacings), the deepest face
//       lies at least that many local spacings from every point (a face then has no data beyond
//       half of it, when that is less than the limit);
//     - an end, on a partial view only: the depth is at least kOpenEndDepth and at least
//       kOpenRimShare of the points in reach are on the rim (the balloon a closed mesh wraps round
//       the edge of a single view).
//     Any other region is the reconstruction's own (a web between two parts, a cap over a
//     through-hole the learning has not opened: no rim near) or a gap in the sampling (a part
//     of the cloud where the points are sparse: the horse, sampled from a mesh with large
//     triangles, has such gaps surrounded by rim points, up to 2.5 limits deep, where the bunny's
//     base holes are from 2.9 deep at 30,000 vertices), and stays: a closed cloud keeps a closed
//     mesh. A face with a point near stays: no hole opens where there are points. From each
//     region that opens, outwards, a face whose edge midpoint or corner has no data by the same
//     test goes too (the long triangles the learning leaves round a hole, an edge across it or a
//     corner over it). The faces go all at once (cut_faces), and the result may have several
//     components: the sheets a single view sees apart.
//  3. Crossing faces (cut_crossings), last: the faces of every pair of crossing triangles the
//     finishing stage left go, with what the cut takes for a manifold (a surface with a hole is
//     valid, one that crosses itself is not). On a view's sheet the finishing stage runs without
//     its repair, and this cut takes the few crossings its relaxation makes (bunny_scan090 at
//     30,000 vertices, seed 1: 101 faces; the repair took 7 s there and then fell back on the
//     sheet as it was).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nmesh/finish/cloud_rim.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

struct OpenReport {
    std::uint32_t removed_layer = 0;       // partial views: the learnt faces the view's sheet has fewer
    std::uint32_t unsupported_faces = 0;   // faces far from every point, in regions that open
    std::uint32_t removed_unsupported = 0;
    std::uint32_t removed_crossing = 0;    // faces removed with the crossing pairs
    float rim_share = 0.0f;  // the share of the cloud's points on its rim where it is flat
};

inline constexpr std::size_t kOpenMinFaces = 20;  // a smaller piece left by the cut goes
inline constexpr float kOpenRimReach = 2.0f;
inline constexpr float kOpenSurroundGap = 1.5707964f;  // 90 degrees
inline constexpr float kOpenHoleDepth = 2.75f;
inline constexpr float kOpenEndDepth = 5.0f;
inline constexpr float kOpenRimShare = 0.05f;
inline constexpr float kOpenEdges = 1.2f;
inline constexpr float kOpenSpacings = 1.5f;
// With a smallest hole given, a face has no data beyond at least this many local spacings: the
// faces' centroids lie within it of a point for 89-99.7% of the faces of the horse's, the bull's,
// knot1's, the fandisk's, the camel's and the hand's meshes at points / 2 and points / 6
// vertices, so that the rest is told apart by the rim round a region (its surround test).
inline constexpr float kOpenMinSpacings = 1.0f;
inline constexpr int kCrossingRounds = 3;  // a cut makes no new crossing: one round suffices

// What the open steps know of the cloud: its indexed points, their rim (nmesh/finish/cloud_rim.h),
// whether it is a partial view and, if so, its normals turned to the view's side.
struct CloudView {
    std::vector<Vec3> points;  // the nearest-point index's points, in its order
    CloudRim rim;
    float spacing = 0.0f;    // the median of the points' local spacings
    float rim_share = 0.0f;    // the share of the points on the rim where the cloud is flat
    float layer_share = 1.0f;  // the cloud's multi-layer share (nmesh/finish/cloud_layers.h)
    bool partial = false;      // layer_share < kViewLayerShare: one layer seen from some direction
    std::vector<Vec3> normals;  // on a partial view: per point, oriented (cloud_normals.h)
    Vec3 direction;             //   the direction towards the scanner (orient_normals)
    std::vector<std::uint32_t> part;  // and per point its connected part (orient_normals)
    // Parameters::min_hole: the smallest hole to open, as the distance from its middle to the
    // nearest point in local spacings; 0 for the rule of open_surface.h (kOpenHoleDepth limits).
    float hole_spacings = 0.0f;
};

// Whether a place whose nearest cloud point is `near` has no data: farther from it than
// kOpenEdges typical edges and kOpenSpacings local spacings (the spacing at that point); with a
// smallest hole given (CloudView::hole_spacings), farther than half of it or kOpenMinSpacings,
// the larger, when that is less.
inline bool no_data(const NearestPoint& near, const CloudView& view, float typical_edge) {
    const float spacing = view.rim.spacing[near.index];
    float limit = std::max(kOpenEdges * typical_edge, kOpenSpacings * spacing);
    if (view.hole_spacings > 0.0f)
        limit = std::min(limit, std::max(0.5f * view.hole_spacings, kOpenMinSpacings) * spacing);
    return near.squared_distance > limit * limit;
}

// `cloud`: the nearest-point index over the points the mesh was learnt from; `spacing`: a first
// guess of their spacing (the size of the rim's cells). O(n k) for n points with k neighbours.
CloudView view_cloud(const PointGrid& cloud, float spacing);

// `mesh`: with its face index; `typical_edge`: the median of the faces' mean edge lengths over
// the whole output (typical_edge()), of which `mesh` may be one piece. The mesh without its
// unsupported faces (the same as mesh.to_indexed() when there are none). Adds to the report's
// counts. O(F log F) and the rim points near each region that is deep enough.
IndexedMesh cut_unsupported(const Mesh& mesh, const PointGrid& cloud, const CloudView& view, float typical_edge,
                            OpenReport& report);

// The mesh without the faces of its crossing pairs (see open_surface.h). `removed` receives the
// faces removed. O(F) per round for faces of similar size (self_intersecting_pairs).
IndexedMesh cut_crossings(const IndexedMesh& mesh, std::uint32_t& removed);

// The median over the faces of their mean edge length; 0 without faces.
float typical_edge(const IndexedMesh& mesh);

// The mesh without the `marked` faces (one flag per face slot), as triangles: all at once, so that
// no removal order can get stuck (one face at a time, a strip of marked faces bridging a hole, or
// an island in it, cannot go without a bow-tie on the way). The set is first closed so that what
// is kept is a manifold with boundary: wherever the kept faces round a vertex fall into two or
// more fans, every fan but the largest goes too (a kept fan between two removed ones would make
// the vertex a bow-tie). Of what is left, the edge-connected pieces of fewer than kOpenMinFaces
// faces go (an island or a bridge left inside a hole); the pieces the cut separates stay (the
// parts of a single view that one hid from another are separate sheets). Unused vertices go.
// `removed` receives the number of faces removed; with none, the result is mesh.to_indexed().
// Needs the face index. O(F + V valence) per round of the closure (one or two rounds in practice).
IndexedMesh cut_faces(const Mesh& mesh, const std::vector<char>& marked, std::uint32_t& removed);
// The same on a triangle list of one or more pieces, each a manifold with boundary (the output of
// a cut), `marked` holding one flag per triangle: each piece is cut as a half-edge mesh.
IndexedMesh cut_faces(const IndexedMesh& mesh, const std::vector<char>& marked, std::uint32_t& removed);

}  // namespace nmesh
