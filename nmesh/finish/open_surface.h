// nmesh/finish/open_surface.h — Parameters::topology open: the second sheet of a one-sided scan
// taken off, and the closed result opened where the cloud has no data.
//
// The learning makes a closed surface; these two steps cut it open (Mesh::remove_face, so every
// step keeps a manifold with boundary, without bow-ties). reconstruct() runs the first on the
// learnt mesh, so that the finishing stage polishes one sheet instead of untangling two, and the
// second on the finished mesh, whose surface lies on the cloud (the learnt mesh's folds and
// stray vertices would read as holes).
//  1. Double layers (remove_double_layers). A closed mesh learnt from an open sheet (one range image) wraps the sheet in
//     two layers of opposite orientation lying on the same points. A face whose opposite-facing
//     neighbour (a face within kLayerReach mean edge lengths whose normal points the other way)
//     lies less than kLayerGap point spacings behind or in front of it is in a double layer: the
//     data cannot tell two sheets apart there. Of the two layers, the faces facing away from the
//     cloud's own side go: its thinnest direction (the least-variance axis of the points), taken
//     with the sign the mesh's faces agree with by area. A thin but real part (an ear) is two
//     sheets more than kLayerGap spacings apart and stays, and only regions of at least
//     kLayerMinShare of the faces count (the folds of a learnt mesh are a few faces each).
//  2. Unsupported faces (open_unsupported). A face whose centroid is farther from every cloud point than
//     kOpenEdges typical edge lengths (the median over the faces) and kOpenSpacings point
//     spacings goes: it spans a
//     hole in the scan (the spacing is the square root of the mesh area per point, so a sparse
//     scan is not shredded). A face with a point that near stays: no hole opens where there are
//     points.
// Faces are removed region by region from the face farthest in; a face whose removal would
// pinch a vertex (a second gap) stays. A closed cloud without holes keeps a closed mesh.
#pragma once

#include <cstddef>
#include <cstdint>

#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

struct OpenReport {
    std::uint32_t double_layer_faces = 0;  // faces found in double layers
    std::uint32_t removed_layer = 0;       // of which removed (the second layer)
    std::uint32_t unsupported_faces = 0;   // faces far from every point
    std::uint32_t removed_unsupported = 0;
};

inline constexpr float kLayerReach = 1.5f;
inline constexpr float kLayerGap = 1.0f;
inline constexpr float kLayerMinShare = 0.02f;
inline constexpr std::size_t kOpenMinFaces = 20;
inline constexpr float kOpenDeep = 3.0f;
inline constexpr float kOpenEdges = 1.2f;
inline constexpr float kOpenSpacings = 1.5f;

// `mesh`: with its face index; `cloud`: the nearest-point index over the same points the mesh was
// learnt from. Each fills its part of the report. O(F log F).
OpenReport remove_double_layers(Mesh& mesh, const PointGrid& cloud);
OpenReport open_unsupported(Mesh& mesh, const PointGrid& cloud);

}  // namespace nmesh
