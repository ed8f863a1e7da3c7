// nmesh/finish/repair.cpp — the repair of folds and self-intersections (step 2 of the stage).
#include "nmesh/finish/repair.h"

#include <algorithm>
#include <chrono>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "nmesh/finish/defect_tracker.h"
#include "nmesh/finish/face_grid.h"
#include "nmesh/finish/hausdorff_estimate.h"
#include "nmesh/finish/mesh_queries.h"
#include "nmesh/util/math_constants.h"

namespace nmesh {

using namespace finish_detail;

std::vector<std::pair<Face, Face>> find_self_intersections(const Mesh& mesh) {
    const std::vector<Face> faces = alive_faces(mesh);
    const FaceGrid grid(mesh, faces, grid_cell(mesh, faces));
    std::vector<std::pair<Face, Face>> pairs;
    grid.for_each_pair([&](Face f, Face g) {
        if (mesh_faces_intersect(mesh, f, g)) pairs.emplace_back(f, g);
    });
    sort_unique(pairs);
    return pairs;
}

std::vector<Edge> find_folded_edges(const Mesh& mesh, float dihedral_deg) {
    const float cos_limit = std::cos(dihedral_deg * kPiF / 180.0f);
    std::vector<Edge> edges;
    for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e)
        if (!mesh.is_removed(Edge(e)) && edge_folded(mesh, Mesh::halfedge(Edge(e), 0), cos_limit))
            edges.push_back(Edge(e));
    return edges;
}

Vertex split_edge(Mesh& mesh, Halfedge h) {
    // From the other end when from(h) is on a boundary (Mesh::can_split); an invalid handle when
    // both ends are.
    if (mesh.is_boundary(mesh.from(h))) h = Mesh::twin(h);
    // Mesh::split of b = from(h) hands the new vertex the half-edges towards x = to(h) and its
    // two ring neighbours c and d; the triangles (a, x, .) replace (b, x, .) and (a, b, c),
    // (b, a, d) fill the rest: with a at the midpoint, the two old triangles, subdivided.
    const Vec3 mid = (mesh.position(mesh.from(h)) + mesh.position(mesh.to(h))) * 0.5f;
    return mesh.try_split(mesh.cw_rotated(h), mesh.ccw_rotated(h), mid);
}

// Choice: folds and intersections are removed locally, by smoothing and, where smoothing alone
// does not untangle the triangles, by collapsing short edges and splitting long ones. Each round:
//   1. collapses the shortest edge of each defective triangle when it is shorter than a limit
//      (half the mean edge length, growing by a quarter every second round, so that a tangle that
//      smoothing does not undo loses vertices until it does; the remaining vertex at the midpoint);
//   2. splits the longest edge of each defective triangle when it is longer than twice the mean;
//   3. restores the vertex count at once (midpoint splits of the longest edges, or collapses of
//      the shortest, among the triangles changed so far, then anywhere if that is not enough);
//   4. smooths: the corners of the defective triangles move halfway to the mean of their
//      neighbours (twice, Jacobi), the `rings` rings around them the same but only tangentially,
//      so that the surface around a defect does not shrink; the rings grow by one every fourth
//      round, up to kMaxRings;
//   5. tests the changed triangles again (DefectTracker).
// Once no defect is left, the vertices the smoothing moved are pulled back towards the cloud
// (kRefitIterations rounds of relaxed_position), each move kept only where it creates no defect.
// If the repair raises the Hausdorff distance between mesh and cloud (as estimated by
// HausdorffEstimate) by more than half the mean edge length, or leaves defects after max_rounds
// without having reduced them, the mesh is put back as it came. Undoing a tangle may cost some
// fidelity where the tangle was (it followed the data, badly), but only locally.
RepairResult repair_folds_and_intersections(Mesh& mesh, int max_rounds, float fold_dihedral_deg,
                                            const CloudSurface* cloud, double seconds_limit,
                                            const std::function<void(int rounds)>& on_round, float max_defect_share,
                                            std::uint32_t threads) {
    const auto start = std::chrono::steady_clock::now();
    const auto out_of_time = [&] {
        return seconds_limit > 0.0 &&
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >= seconds_limit;
    };
    RepairResult result;
    DefectTracker tracker(mesh, std::cos(fold_dihedral_deg * kPiF / 180.0f), false, threads);
    result.intersecting_pairs_before = tracker.pairs().size();
    result.folded_edges_before = tracker.folds().size();
    result.intersecting_pairs = result.intersecting_pairs_before;
    result.folded_edges = result.folded_edges_before;
    if (tracker.clean()) return result;
    if (float(tracker.defective_faces().size()) > max_defect_share * float(mesh.n_faces())) {
        result.declined = true;
        return result;
    }

    const Mesh original = mesh;
    std::unique_ptr<HausdorffEstimate> estimate;
    const float mean_len = mean_edge_length(mesh);
    if (cloud) estimate = std::make_unique<HausdorffEstimate>(mesh, *cloud, mean_len);
    const std::uint32_t target = mesh.n_vertices();
    std::vector<std::uint8_t> level;     // per vertex: 0 outside the region, 1 ring, 2 core
    std::vector<std::uint8_t> smoothed;  // per vertex: moved by a smoothing
    auto grow = [&](std::vector<std::uint8_t>& v) {
        if (v.size() < mesh.vertex_capacity()) v.resize(mesh.vertex_capacity(), 0);
    };
    std::vector<Vertex> region, ring_start, seeds;
    std::vector<Vec3> next;
    // The repair is abandoned, and undone, when every kFidelityEvery rounds the estimated
    // Hausdorff distance has risen by more than kAbandonEdges mean edges: four times what the end
    // allows, so the pull-back towards the cloud cannot bring it back (an open sheet's two layers
    // smoothed into each other). It only saves the time of a repair that would be undone anyway
    // (docs/algorithm.md has the measurements).
    constexpr int kFidelityEvery = 8;
    constexpr float kAbandonEdges = 2.0f;
    // The rings of tangential smoothing round the defects grow to at most kMaxRings (round 20):
    // with 18 (round 70) the validity sweep had its defects in the same runs, and a round's cost
    // grows with the region (docs/algorithm.md).
    constexpr int kMaxRings = 6;
    bool abandoned = false;
    for (int round = 0; round < max_rounds && !tracker.clean() && !out_of_time(); ++round) {
        ++result.rounds;
        const std::vector<Face> defective = tracker.defective_faces();
        seeds.clear();
        // 1. Collapses of short edges.
        const float collapse_below = mean_len * (0.5f + 0.25f * float(round / 2));
        for (const Face f : defective) {
            if (mesh.is_removed(f)) continue;
            Halfedge best;
            float best_len = collapse_below;
            Halfedge h = mesh.halfedge(f);
            for (int i = 0; i < 3; ++i, h = mesh.next(h)) {
                const float l = length(mesh, h);
                if (l >= best_len) continue;
                if (mesh.can_collapse(h))
                    best = h, best_len = l;
                else if (mesh.can_collapse(Mesh::twin(h)))
                    best = Mesh::twin(h), best_len = l;
            }
            if (!best.valid()) continue;
            const Vertex b = mesh.to(best);
            const Vec3 mid = (mesh.position(mesh.from(best)) + mesh.position(b)) * 0.5f;
            mesh.collapse(best);
            mesh.set_position(b, mid);
            tracker.changed(b);
            seeds.push_back(b);
        }
        // 2. Splits of long edges.
        for (const Face f : defective) {
            if (mesh.is_removed(f)) continue;
            Halfedge best;
            float best_len = 2.0f * mean_len;
            Halfedge h = mesh.halfedge(f);
            for (int i = 0; i < 3; ++i, h = mesh.next(h)) {
                const float l = length(mesh, h);
                if (l > best_len) best = h, best_len = l;
            }
            if (!best.valid()) continue;
            const Vertex a = split_edge(mesh, best);
            if (!a.valid()) continue;
            tracker.changed(a);
            seeds.push_back(a);
        }
        // 3. The vertex count, at once (a split can expose two triangles that met at the vertex it
        // moves away from, so its triangles are tested in this round too).
        restore_vertex_count(mesh, target, tracker.changed_faces(), [&](Vertex v) { tracker.changed(v); });
        // 4. The region and the smoothing.
        grow(level);
        grow(smoothed);
        region.clear();
        auto add = [&](Vertex v, std::uint8_t l) {
            if (!level[v.idx]) {
                level[v.idx] = l;
                region.push_back(v);
            }
        };
        for (const Vertex v : seeds)
            if (!mesh.is_removed(v)) add(v, 2);
        for (const Face f : defective)
            if (!mesh.is_removed(f))
                for (const Vertex v : corners(mesh, f)) add(v, 2);
        const int rings = std::min(1 + round / 4, kMaxRings);
        for (int r = 0; r < rings; ++r) {
            ring_start = region;
            for (const Vertex v : ring_start) mesh.for_each_neighbor(v, [&](Vertex u) { add(u, 1); });
        }
        std::sort(region.begin(), region.end());
        next.resize(region.size());
        for (int it = 0; it < 2; ++it) {
            for (std::size_t i = 0; i < region.size(); ++i) {
                Vec3 c;
                std::uint32_t k = 0;
                mesh.for_each_neighbor(region[i], [&](Vertex u) {
                    c += mesh.position(u);
                    ++k;
                });
                const Vec3 p = mesh.position(region[i]);
                if (mesh.is_boundary(region[i])) {  // a boundary stays
                    next[i] = p;
                    continue;
                }
                Vec3 d = (c * (1.0f / float(k)) - p) * 0.5f;
                if (level[region[i].idx] == 1) {
                    const Vec3 n = mesh.vertex_normal(region[i]);
                    d = d - n * dot(d, n);
                }
                next[i] = p + d;
            }
            for (std::size_t i = 0; i < region.size(); ++i) mesh.set_position(region[i], next[i]);
        }
        for (const Vertex v : region) {
            level[v.idx] = 0;
            smoothed[v.idx] = 1;
            tracker.changed(v);
        }
        // 5. Test again.
        tracker.check();
        if (cloud && round % kFidelityEvery == kFidelityEvery - 1 &&
            estimate->after(mesh, tracker.changed_faces()) > estimate->value() + kAbandonEdges * mean_len) {
            abandoned = true;
            break;
        }
        if (on_round) on_round(result.rounds);
    }
    const bool counted = mesh.n_vertices() == target;
    bool ok = tracker.clean() && counted;

    // The pull back towards the cloud, guarded.
    if (ok && cloud) {
        std::vector<Vertex> moved;
        for (std::uint32_t v = 0; v < smoothed.size(); ++v)
            if (smoothed[v] && !mesh.is_removed(Vertex(v))) moved.push_back(Vertex(v));
        std::vector<Vec3> before(moved.size());
        for (int it = 0; it < kRefitIterations && !moved.empty(); ++it) {
            for (std::size_t i = 0; i < moved.size(); ++i) before[i] = mesh.position(moved[i]);
            next.resize(moved.size());
            for (std::size_t i = 0; i < moved.size(); ++i) next[i] = relaxed_position(mesh, moved[i], cloud, mean_len);
            for (std::size_t i = 0; i < moved.size(); ++i) {
                mesh.set_position(moved[i], next[i]);
                tracker.changed(moved[i]);
            }
            tracker.check();
            // Undo the moves of the defects' corners until none is left (at worst all of them,
            // which gives back the clean mesh of the previous iteration).
            std::vector<std::uint32_t> slot(mesh.vertex_capacity(), kInvalidIndex);
            for (std::size_t i = 0; i < moved.size(); ++i) slot[moved[i].idx] = std::uint32_t(i);
            for (int undo = 0; undo < 8 && !tracker.clean(); ++undo) {
                for (const Face f : tracker.defective_faces())
                    for (const Vertex v : corners(mesh, f))
                        if (slot[v.idx] != kInvalidIndex) {
                            mesh.set_position(v, before[slot[v.idx]]);
                            tracker.changed(v);
                        }
                tracker.check();
            }
            if (!tracker.clean()) {
                for (std::size_t i = 0; i < moved.size(); ++i) {
                    mesh.set_position(moved[i], before[i]);
                    tracker.changed(moved[i]);
                }
                tracker.check();
                break;
            }
        }
        ok = tracker.clean();
    }
    const float rise = cloud ? (estimate->after(mesh, tracker.changed_faces()) - estimate->value()) / mean_len : 0.0f;
    const bool near_cloud = !abandoned && rise <= 0.5f;
    // A repair that leaves defects is kept when it leaves fewer intersecting pairs than it found
    // (and no more folded edges), so that the defects it could not remove do not undo those it
    // did; the mesh is put back otherwise.
    const bool better = counted && tracker.pairs().size() < result.intersecting_pairs_before &&
                        tracker.folds().size() <= result.folded_edges_before;
    if (abandoned || !near_cloud || !(ok || better)) {
        if (ok && !abandoned && !near_cloud && rise <= kAbandonEdges) {
            result.off_cloud = mesh;
            result.off_cloud_rise = rise;
        }
        mesh = original;
        result.reverted = true;
        return result;
    }
    result.intersecting_pairs = ok ? 0 : tracker.pairs().size();
    result.folded_edges = ok ? 0 : tracker.folds().size();
    return result;
}

}  // namespace nmesh
