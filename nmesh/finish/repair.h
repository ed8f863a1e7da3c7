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

struct RepairResult {
    std::size_t intersecting_pairs_before = 0;
    std::size_t folded_edges_before = 0;
    std::size_t intersecting_pairs = 0;  // left (as before when reverted)
    std::size_t folded_edges = 0;
    std::uint32_t rounds = 0;
    bool reverted = false;  // the mesh was put back as it came
    // When the repair removed every defect and was undone only for the surface it moved off the
    // cloud (by more than half the mean edge length, at most kAbandonEdges): that repaired mesh,
    // and the rise of the estimated Hausdorff distance in mean edge lengths. The stage takes it
    // when it has nothing valid otherwise.
    std::optional<Mesh> off_cloud;
    float off_cloud_rise = 0.0f;
};

// Step 2 of the stage (see finish.cpp for the details). With `cloud`, the smoothed vertices are
// pulled back towards it, and the repair is undone if it raises the (estimated) Hausdorff distance
// to the cloud by more than half the mean edge length. Keeps the vertex count; all or nothing.
// `seconds_limit` (0: none) stops the rounds once that much wall time has passed since the call;
// `on_round` (may be empty) is called after each round with the rounds done.
RepairResult repair_folds_and_intersections(Mesh& mesh, int max_rounds = 40, float fold_dihedral_deg = 120.0f,
                                            const CloudSurface* cloud = nullptr, double seconds_limit = 0.0,
                                            const std::function<void(int rounds)>& on_round = {});

}  // namespace nmesh
