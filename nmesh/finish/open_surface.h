// nmesh/finish/open_surface.h — Parameters::topology open: the second sheet of a one-sided scan
// taken off, and the closed result opened where the cloud has no data.
//
// The learning makes a closed surface; these two steps cut it open, each keeping a manifold with
// boundary, without bow-ties. reconstruct() runs the first on the learnt mesh, so that the finishing stage polishes one sheet instead of untangling two, and the
// second on the finished mesh, whose surface lies on the cloud (the learnt mesh's folds and
// stray vertices would read as holes).
// A partial view: a cloud with at least kViewRimShare of its points on its rim where the cloud
// is flat (nmesh/finish/cloud_rim.h; creases and corners read as rim). Measured: 3.3% for the single view bunny_scan090; at most 0.73% for
// the shared closed clouds and the bunny with its five base holes (the rocker arm 0.73%, the
// bunny 0.29%, the knot 0.14%, the horse 0.12%, the eight 0.09%).
//  1. Double layers (remove_double_layers), on a partial view only. A closed mesh learnt from an
//     open sheet (one range image) wraps the sheet in two layers of opposite orientation lying on the same points. A face whose opposite-facing
//     neighbour (a face within kLayerReach mean edge lengths whose normal points the other way)
//     lies less than kLayerGap point spacings behind or in front of it is in a double layer: the
//     data cannot tell two sheets apart there. Of the two layers, the faces facing away from the
//     cloud's own side go: its thinnest direction (the least-variance axis of the points), taken
//     with the sign the mesh's faces agree with by area. A thin but real part (an ear) is two
//     sheets more than kLayerGap spacings apart and stays, and only regions of at least
//     kLayerMinShare of the faces count (the folds of a learnt mesh are a few faces each).
//  2. Unsupported faces (cut_unsupported), on the finished mesh. A face whose centroid is
//     farther from every cloud point than kOpenEdges typical edge lengths (the median over the
//     faces) and kOpenSpacings local point spacings (nmesh/finish/cloud_rim.h, so a sparse part
//     of a scan is not shredded) has no data. An edge-connected region of such faces goes when it
//     is a hole in the scan or lies beyond the scan's end, told by its depth (the distance of its
//     deepest face to the cloud, in limits: the larger of kOpenEdges typical edges and
//     kOpenSpacings global spacings) and by the cloud's rim (the points at the edge of the
//     sampled surface) within kOpenRimReach depths of the deepest face:
//     - a hole: the rim points surround the deepest face (seen along its normal, no free sector
//       of kOpenSurroundGap or more) and the depth is at least kOpenHoleDepth;
//     - an end, on a partial view only: the depth is at least kOpenEndDepth and at least
//       kOpenRimShare of the points in reach are on the rim (the balloon a closed mesh wraps round
//       the edge of a single view).
//     Any other region is the reconstruction's own (a web between two parts, a cap over a
//     through-hole the learning has not opened: no rim near) or a gap in the sampling (a part
//     of the cloud where the points are sparse: the horse, sampled from a mesh with large
//     triangles, has such gaps surrounded by rim points, up to 2.5 limits deep, where the bunny's
//     base holes are from 2.9 deep at 30,000 vertices), and stays: a closed cloud keeps a closed
//     mesh. A face with a point near stays: no hole opens where there are points. The faces go
//     all at once (cut_faces), and the result may have several components: the sheets a single
//     view sees apart.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

struct OpenReport {
    std::uint32_t double_layer_faces = 0;  // faces found in double layers
    std::uint32_t removed_layer = 0;       // of which removed (the second layer)
    std::uint32_t unsupported_faces = 0;   // faces far from every point
    std::uint32_t removed_unsupported = 0;
    float rim_share = 0.0f;  // the share of the cloud's points on its rim where it is flat
};

inline constexpr float kViewRimShare = 0.02f;
inline constexpr float kLayerReach = 1.5f;
inline constexpr float kLayerGap = 1.0f;
inline constexpr float kLayerMinShare = 0.02f;
inline constexpr std::size_t kOpenMinFaces = 20;  // a smaller piece left by the cut goes
inline constexpr float kOpenRimReach = 2.0f;
inline constexpr float kOpenSurroundGap = 1.5707964f;  // 90 degrees
inline constexpr float kOpenHoleDepth = 2.75f;
inline constexpr float kOpenEndDepth = 5.0f;
inline constexpr float kOpenRimShare = 0.05f;
inline constexpr float kOpenEdges = 1.2f;
inline constexpr float kOpenSpacings = 1.5f;

// `mesh`: with its face index; `cloud`: the nearest-point index over the same points the mesh was
// learnt from. Each fills its part of the report. O(F log F) and, for the rim, O(n k) for n
// points with k neighbours each.
OpenReport remove_double_layers(Mesh& mesh, const PointGrid& cloud);
// The mesh without its unsupported faces (the same as mesh.to_indexed() when there are none).
IndexedMesh cut_unsupported(const Mesh& mesh, const PointGrid& cloud, OpenReport& report);

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

}  // namespace nmesh
