// nmesh/finish/regularise.h — step 1 of the finishing stage: angle-improving flips, tangential relaxation
// towards the cloud, and the optional centroid fit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh {

// Flips every edge whose two opposite angles sum to more than 180 degrees (it is not locally
// Delaunay) when its two triangles are nearly coplanar before and after the flip (normals within
// max_dihedral_deg of each other, the new triangles facing the old ones' side) and Mesh::can_flip
// allows it, until no such edge is left (at most 8 flips per edge). Only the connectivity
// changes. Returns the number of flips.
std::uint64_t flip_to_delaunay(Mesh& mesh, float max_dihedral_deg = 20.0f);

// One round of tangential relaxation (all vertices moved from their old positions): every vertex
// moves to the area-weighted centroid of its triangles' centroids, minus the normal component of
// that move; with `cloud`, it is then pulled towards the cloud by at most a quarter of its mean
// edge length (CloudSurface::pull, reach: its mean edge length), and a vertex whose move would end
// farther from the cloud than the mesh's mean edge length, and farther than it was, stays.
// With `anchors`, a vertex that has one also stays where its move would leave the anchor more
// than kAnchorReach of its mean edge length off its triangles, unless one of its triangles faces
// against their mean normal (a fold, which the relaxation is there to smooth). Choice: at a tip or
// a sharp ridge of a coarse mesh the relaxation slides the vertices down the sides round by
// round, and the pull towards the cloud cannot bring them back up (a horse's ear at 1,000
// vertices: its tip 3.0% of the diagonal from the finished mesh against 2.0% from the learnt
// one); elsewhere a tangential slide keeps the anchor on the triangles, and the vertex moves as
// before (docs/algorithm.md, Finishing stage).
inline constexpr float kAnchorReach = 0.1f;
// A vertex has an anchor when the learning left it within this share of the mean edge length of
// a scan point (finish_mesh): a vertex off the scan (a spike, the rim of a fold) is not kept out.
inline constexpr float kAnchorSupport = 0.25f;
struct Anchors {
    std::vector<Vec3> at;             // by vertex id
    std::vector<std::uint8_t> held;   // by vertex id: whether the vertex has an anchor
};
// Each vertex's new position is found from the mesh as it was (on `threads`, 0: the machine's
// cores, vertex by vertex), then all are moved: the same result for any count.
void relax_tangentially(Mesh& mesh, const CloudSurface* cloud = nullptr, const Anchors* anchors = nullptr,
                        std::uint32_t threads = 1);

// One damped Lloyd step of the centroids towards the cloud (see FinishOptions::fit_rounds).
void fit_centroids(Mesh& mesh, const std::vector<Vec3>& cloud, float weight);

}  // namespace nmesh
