// nmesh/finish/repair.h — step 2 of the finishing stage: the repair of folds and self-intersections.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh {

// Every pair of triangles that intersect as nmesh::faces_intersect decides (exactly; pairs that
// share a vertex or an edge by what else they share), each pair once, smaller face first,
// sorted; degenerate triangles are skipped, as the metrics do. Expected O(F) through a hash grid
// of the triangles' bounding boxes.
std::vector<std::pair<Face, Face>> find_self_intersections(const Mesh& mesh);

// Edges whose two triangles' normals differ by more than `dihedral_deg`, and edges of degenerate
// (zero-area) triangles.
std::vector<Edge> find_folded_edges(const Mesh& mesh, float dihedral_deg = 120.0f);

// Splits the edge of h at its midpoint (Mesh::split): the new vertex has valence 4 and the four
// new triangles cover exactly the two old ones. Returns the new vertex.
Vertex split_edge(Mesh& mesh, Halfedge h);  // invalid when both ends are on a boundary

// The repair is for local defects. A mesh with more than this share of its triangles in crossing
// pairs or on folded edges is not a surface with defects but the wrong surface, a closed mesh
// wrapped round an open sheet, and the repair is not tried (RepairResult::declined): smoothing
// it only draws the two layers into each other until the Hausdorff guard undoes everything, at
// several times the learning's time. Choice: 8%. Measured after the regularisation, seeds 1-6
// at 1,000 / 3,000 / 10,000 vertices (and the rocker arm at 5,000, seeds 1-20): at most 3.8%
// on the closed clouds (the bunny at 1,000 vertices, seed 1), at least 13% on the single view
// bunny_scan090 at 1,000 to 10,000 vertices (docs/algorithm.md).
inline constexpr float kRepairMaxDefectShare = 0.08f;

struct RepairResult {
    std::size_t intersecting_pairs_before = 0;
    std::size_t folded_edges_before = 0;
    std::size_t intersecting_pairs = 0;  // left (as before when reverted)
    std::size_t folded_edges = 0;
    std::uint32_t rounds = 0;
    bool reverted = false;  // the mesh was put back as it came
    bool declined = false;  // not tried: more than max_defect_share of the triangles defective
    // When the repair removed every defect and was undone only for the surface it moved off the
    // cloud (by more than half the mean edge length, at most kAbandonEdges): that repaired mesh,
    // and the rise of the estimated Hausdorff distance in mean edge lengths. The stage takes it
    // when it has nothing valid otherwise.
    std::optional<Mesh> off_cloud;
    float off_cloud_rise = 0.0f;
};

// Step 2 of the stage (see repair.cpp for the details). With `cloud`, the smoothed vertices are
// pulled back towards it, and the repair is undone if it raises the (estimated) Hausdorff distance
// to the cloud by more than half the mean edge length. Keeps the vertex count; all or nothing.
// `seconds_limit` (0: none) stops the rounds once that much wall time has passed since the call;
// `on_round` (may be empty) is called after each round with the rounds done. A mesh with more
// than `max_defect_share` of its triangles defective is declined (kRepairMaxDefectShare).
// `threads` (0: the machine's cores) search the whole mesh for its defects at the start: the same
// repair for any count.
RepairResult repair_folds_and_intersections(Mesh& mesh, int max_rounds = 40, float fold_dihedral_deg = 120.0f,
                                            const CloudSurface* cloud = nullptr, double seconds_limit = 0.0,
                                            const std::function<void(int rounds)>& on_round = {},
                                            float max_defect_share = kRepairMaxDefectShare, std::uint32_t threads = 1);

}  // namespace nmesh
