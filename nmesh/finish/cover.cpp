// nmesh/finish/cover.cpp — vertices drawn out to the uncovered scan points (step 3 of the stage).
#include "nmesh/finish/cover.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "nmesh/finish/defect_tracker.h"
#include "nmesh/finish/mesh_queries.h"
#include "nmesh/util/math_constants.h"

namespace nmesh {

using namespace finish_detail;

CoverResult cover_uncovered_points(Mesh& mesh, const CloudSurface& cloud, int iterations, float weight,
                                   const std::vector<Edge>& steep_folds) {
    CoverResult result;
    if (iterations <= 0 || mesh.n_faces() == 0) return result;
    std::vector<std::uint8_t> fixed(mesh.vertex_capacity(), 0);
    for (const Edge e : steep_folds) {
        const Halfedge h = Mesh::halfedge(e, 0);
        for (const Face f : {mesh.face(h), mesh.face(Mesh::twin(h))})
            for (const Vertex v : corners(mesh, f)) fixed[v.idx] = 1;
    }
    DefectTracker tracker(mesh, std::cos(kCoverFoldDeg * kPiF / 180.0f), true);
    const float reach = kCoverReach * mean_edge_length(mesh);
    const std::vector<Vec3>& points = cloud.points();
    std::vector<Vec3> sum(mesh.vertex_capacity());
    std::vector<std::uint32_t> count(mesh.vertex_capacity(), 0);
    std::vector<std::uint32_t> slot(mesh.vertex_capacity(), kInvalidIndex);
    std::vector<Vertex> moved;
    std::vector<Vec3> before;
    std::vector<Vertex> at_defect;
    std::vector<std::uint32_t> uncovered;  // indices into `points`
    for (int it = 0; it < iterations; ++it) {
        // Each uncovered point, to its nearest vertex. The first iteration looks at every point,
        // the later ones at those uncovered before (the moves draw the surface out towards them,
        // so the others stay covered, but for a rare point near a moved vertex).
        const std::vector<Vertex> verts = alive_vertices(mesh);
        const std::unique_ptr<PointGrid> index = position_index(mesh, verts);
        const std::size_t n = it == 0 ? points.size() : uncovered.size();
        std::size_t kept = 0;
        for (std::size_t k = 0; k < n; ++k) {
            const std::uint32_t i = it == 0 ? std::uint32_t(k) : uncovered[k];
            const Vertex v = verts[index->nearest(points[i])];
            if (mesh.is_boundary(v) || fixed[v.idx] || distance_to_ring(mesh, v, points[i]) <= reach) continue;
            sum[v.idx] += points[i] - mesh.position(v);
            ++count[v.idx];
            if (it == 0)
                uncovered.push_back(i);
            else
                uncovered[kept++] = i;
        }
        if (it > 0) uncovered.resize(kept);
        // The moves.
        moved.clear();
        before.clear();
        for (const Vertex v : verts) {
            if (count[v.idx] >= kCoverMinPoints) {
                slot[v.idx] = std::uint32_t(moved.size());
                moved.push_back(v);
                before.push_back(mesh.position(v));
                mesh.set_position(v, mesh.position(v) + sum[v.idx] * (weight / float(count[v.idx])));
                tracker.changed(v);
            }
            sum[v.idx] = Vec3();
            count[v.idx] = 0;
        }
        if (moved.empty()) break;
        tracker.check();
        // The moves at the defects' corners halved, twice, then undone.
        std::uint32_t undone = 0;
        for (int pass = 0; pass < 3 && !tracker.clean(); ++pass) {
            at_defect.clear();
            for (const Face f : tracker.defective_faces())
                for (const Vertex v : corners(mesh, f))
                    if (slot[v.idx] != kInvalidIndex && mesh.position(v) != before[slot[v.idx]]) at_defect.push_back(v);
            std::sort(at_defect.begin(), at_defect.end());
            at_defect.erase(std::unique(at_defect.begin(), at_defect.end()), at_defect.end());
            for (const Vertex v : at_defect) {
                const std::uint32_t i = slot[v.idx];
                if (pass < 2) {
                    mesh.set_position(v, (mesh.position(v) + before[i]) * 0.5f);
                } else {
                    mesh.set_position(v, before[i]);
                    ++undone;
                }
                tracker.changed(v);
            }
            tracker.check();
        }
        const bool clean = tracker.clean();
        if (!clean) {
            for (std::size_t i = 0; i < moved.size(); ++i) {
                mesh.set_position(moved[i], before[i]);
                tracker.changed(moved[i]);
            }
            tracker.check();
            undone = std::uint32_t(moved.size());
        }
        for (const Vertex v : moved) slot[v.idx] = kInvalidIndex;
        result.moves += std::uint32_t(moved.size()) - undone;
        result.undone += undone;
        if (!clean) break;
    }
    return result;
}

}  // namespace nmesh
