#include "nmesh/learn/simplify.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace nmesh {

bool simplify(Mesh& mesh, std::uint32_t n) {
    // A collapse that would leave a vertex with more neighbours than this waits: the simplified
    // mesh keeps triangles of even shape (a vertex that absorbs its neighbours one by one grows
    // a fan of slivers).
    constexpr std::uint32_t kMaxValence = 10;
    // Whether moving v to p turns one of its triangles over (the triangles with `skip` stay out:
    // they go with the collapse).
    auto turns = [&](Vertex v, Vertex skip, const Vec3& p) {
        bool bad = false;
        mesh.for_each_outgoing_cw(v, [&](Halfedge h) {
            const Vertex x = mesh.to(h), y = mesh.to(mesh.next(h));
            if (bad || x == skip || y == skip) return;
            const Vec3 &a = mesh.position(v), &b = mesh.position(x), &c = mesh.position(y);
            const Vec3 before = cross(b - a, c - a), after = cross(b - p, c - p);
            bad = dot(before, after) <= 0.1f * std::sqrt(dot(before, before) * dot(after, after));
        });
        return bad;
    };
    // Passes over the edges, shortest first; a collapse keeps the other collapses of its pass
    // off the kept vertex's ring, so that each pass thins the mesh evenly.
    std::vector<std::pair<float, std::uint32_t>> edges;
    std::vector<char> busy;
    while (mesh.n_vertices() > n) {
        edges.clear();
        for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e)
            if (!mesh.is_removed(Edge(e))) {
                const Halfedge h = Mesh::halfedge(Edge(e), 0);
                edges.push_back({squared_distance(mesh.position(mesh.from(h)), mesh.position(mesh.to(h))), h.idx});
            }
        // The shortest quarter, in order: the rest waits for a later pass.
        const auto quarter = edges.begin() + std::ptrdiff_t(edges.size() / 4 + 1);
        std::nth_element(edges.begin(), quarter, edges.end());
        edges.erase(quarter, edges.end());
        std::sort(edges.begin(), edges.end());
        busy.assign(mesh.vertex_capacity(), 0);
        bool progress = false;
        for (const auto& [length2, index] : edges) {
            if (mesh.n_vertices() <= n) break;
            Halfedge h(index);
            if (mesh.is_removed(h) || busy[mesh.from(h).idx] || busy[mesh.to(h).idx]) continue;
            if (!mesh.can_collapse(h)) {
                h = Mesh::twin(h);
                if (!mesh.can_collapse(h)) continue;
            }
            const Vertex a = mesh.from(h), b = mesh.to(h);
            if (mesh.valence(a) + mesh.valence(b) > kMaxValence + 4) continue;
            const Vec3 mid = (mesh.position(a) + mesh.position(b)) * 0.5f;
            if (turns(a, b, mid) || turns(b, a, mid)) continue;
            mesh.collapse(h);
            mesh.set_position(b, mid);
            busy[b.idx] = 1;
            mesh.for_each_outgoing_cw(b, [&](Halfedge g) { busy[mesh.to(g).idx] = 1; });
            progress = true;
        }
        if (!progress) return false;
    }
    return true;
}

}  // namespace nmesh
