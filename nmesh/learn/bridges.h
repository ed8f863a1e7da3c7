// nmesh/learn/bridges.h — topology learning (Parameters::topology closed and open): a part of
// the mesh that reaches its data only across a thin neck of faces far from every cloud point (a
// bridge) is taken away, so that the learning grows it again from where the data goes on.
//
// On a coarse mesh the nearest vertices to the samples of a thin part (a horse's hoof) can lie on
// a neighbouring part (the other hoof): the mesh stretches across the gap and covers the part
// from there, and the part's own leg ends blind beside it. The thin tube across the gap stays
// however fine the mesh grows, since no split, collapse or flip changes how the surface is
// connected: the horse's seeds whose Hausdorff distance stays at 5-6% of the diagonal at every
// size (docs/algorithm.md, "Bridges").
//
// Choices:
//   - faces are unsupported as in the handle search (handles.h: farther from the cloud than
//     kUnsupportedEdges mean longest edges and kUnsupportedSpacings point spacings);
//   - the supported faces fall into edge-connected components; the largest is the body, and a
//     smaller one is the far end of a bridge (a sac) when it is a disc (Euler characteristic 1)
//     bounded by at most kMaxNeckEdges edges (the neck), has at least kMinSacFaces faces and at
//     most kMaxSacShare of the mesh's (a larger part regrew across a bridge again, or elsewhere,
//     in the horse's runs where one was taken away; one that large was, in other runs, a coarse
//     part that filled out by itself), is
//     closed off like a sack (its vector area at most kMaxSacFlatness of its area: it wraps a
//     part, where an island of data in a membrane is flat), and the unsupported faces connected
//     to it (the neck) are no more than its own faces (not a membrane round an island);
//   - the neck crosses empty space: the cloud does not wall its middle round within kNeckReach
//     unsupported distances (walled_round, across the line from the neck to the sac). A coarse
//     thin part inside its data (a leg whose mesh is still a thin tube within it) is walled round
//     and fills out as the mesh grows;
//   - the sac's data must be reachable from the body's through the cloud itself (cells of the
//     unsupported distance holding points, 26-connected): where it is not (two separate objects)
//     the tube is the only way a connected mesh can cover both, and it stays;
//   - the vertices of the sac and of its neck go, but for those of the body's faces, by edge
//     collapses (collapse_flagged); the learning regrows the part from the body.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "nmesh/learn/face_support.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

inline constexpr std::uint32_t kMaxNeckEdges = 6;
inline constexpr std::uint32_t kMinSacFaces = 6;
inline constexpr double kMaxSacShare = 0.025;
inline constexpr float kMaxSacFlatness = 0.15f;
inline constexpr float kNeckReach = 4.0f;

struct BridgeSearch {
    std::uint32_t bridges = 0;        // sacs found
    std::vector<char> flagged;        // per vertex slot: to be removed
    std::uint32_t flagged_count = 0;  // vertices flagged
};

// `mesh`: closed, with its face index; `cloud`: the nearest-point index over the same
// (normalised) points the mesh learns; `support`: face_support(mesh, cloud). Changes nothing.
// O(F log F), plus O(P) for the cloud's cells when a candidate sac is found.
BridgeSearch find_bridges(const Mesh& mesh, const PointGrid& cloud, const FaceSupport& support);

// Removes the vertices flagged in `flagged` by edge collapses, each along its shortest legal edge
// to an unflagged neighbour when it has one, to a flagged one otherwise (that one goes later),
// in passes until none is left or none can go. collapsed(gone, kept) is called after each
// collapse. Returns the flagged vertices left (their collapses refused). The mesh needs no face
// index.
std::uint32_t collapse_flagged(Mesh& mesh, const std::vector<char>& flagged,
                               const std::function<void(Vertex gone, Vertex kept)>& collapsed);

}  // namespace nmesh
