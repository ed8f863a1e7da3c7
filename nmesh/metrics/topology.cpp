// nmesh/metrics/topology.cpp — the topology of an indexed mesh: edges, fans, components, boundary
// loops, Euler characteristic and genus.
#include "nmesh/metrics/topology.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "nmesh/error.h"

namespace nmesh::metrics_detail {
namespace {

using Eigen::Vector3d;
Vector3d to_eigen(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
    std::uint32_t find(std::uint32_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<std::uint32_t> parent_;
};

bool has_repeated_vertex(const std::array<std::uint32_t, 3>& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

}  // namespace

bool is_degenerate(const IndexedMesh& mesh, const std::array<std::uint32_t, 3>& t) {
    if (has_repeated_vertex(t)) return true;
    const Vector3d a = to_eigen(mesh.positions[t[0]]);
    const Vector3d n = (to_eigen(mesh.positions[t[1]]) - a).cross(to_eigen(mesh.positions[t[2]]) - a);
    return n.squaredNorm() == 0.0;
}

void analyze_topology(const IndexedMesh& mesh, QualityReport& r) {
    const MeshTopology t = mesh_topology(mesh);
    r.closed = t.closed;
    r.manifold = t.manifold;
    r.euler = t.euler;
    r.genus = t.genus;
    r.components = t.components;
    r.isolated_vertices = t.isolated_vertices;
    r.boundary_loops = t.boundary_loops;
    r.boundary_edges = t.boundary_edges;
    r.boundary_length = t.boundary_length;
}

}  // namespace nmesh::metrics_detail

namespace nmesh {

MeshTopology mesh_topology(const IndexedMesh& mesh) {
    using metrics_detail::has_repeated_vertex;
    using metrics_detail::to_eigen;
    using metrics_detail::UnionFind;
    const std::size_t nv = mesh.positions.size(), nf = mesh.triangles.size();
    for (std::size_t f = 0; f < nf; ++f)
        for (std::uint32_t v : mesh.triangles[f])
            if (v >= nv)
                throw InputError("topology: triangle " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                 " of " + std::to_string(nv));
    // Each directed edge of each triangle, grouped by undirected edge.
    struct HalfEdge {
        std::uint64_t key;  // (smaller vertex << 32) | larger vertex
        std::uint32_t face;
        std::uint8_t corner;  // the edge runs from corner `corner` to the next corner of `face`
    };
    std::vector<HalfEdge> half_edges;
    half_edges.reserve(3 * nf);
    bool manifold = true;
    for (std::uint32_t f = 0; f < nf; ++f) {
        const auto& t = mesh.triangles[f];
        if (has_repeated_vertex(t)) manifold = false;  // an edge from a vertex to itself
        for (std::uint8_t i = 0; i < 3; ++i) {
            const std::uint32_t u = t[i], w = t[(i + 1) % 3];
            if (u == w) continue;
            half_edges.push_back({(std::uint64_t(std::min(u, w)) << 32) | std::max(u, w), f, i});
        }
    }
    std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& a, const HalfEdge& b) { return a.key < b.key; });

    // Edges: closed when all are shared by two triangles; manifold needs at most two, running in
    // opposite directions. Corners around a vertex are linked through the edges they share, so
    // that each vertex's fans can be counted.
    bool closed = true;
    std::size_t edges = 0;
    UnionFind corners(3 * nf);
    const auto from = [&](const HalfEdge& h) { return mesh.triangles[h.face][h.corner]; };
    for (std::size_t i = 0; i < half_edges.size();) {
        std::size_t j = i;
        while (j < half_edges.size() && half_edges[j].key == half_edges[i].key) ++j;
        ++edges;
        const std::size_t count = j - i;
        if (count != 2) closed = false;
        if (count > 2) manifold = false;
        if (count == 2) {
            const HalfEdge &a = half_edges[i], &b = half_edges[i + 1];
            if (from(a) == from(b)) manifold = false;  // both triangles run the edge the same way
            // a runs u -> w; b runs w -> u (or u -> w when inconsistent): link the corners at u
            // and at w of the two triangles.
            const std::uint32_t a_from = 3 * a.face + a.corner, a_to = 3 * a.face + (a.corner + 1) % 3;
            const std::uint32_t b_from = 3 * b.face + b.corner, b_to = 3 * b.face + (b.corner + 1) % 3;
            if (from(a) == from(b)) {
                corners.unite(a_from, b_from);
                corners.unite(a_to, b_to);
            } else {
                corners.unite(a_from, b_to);
                corners.unite(a_to, b_from);
            }
        }
        i = j;
    }
    // One fan per vertex: all corners of a vertex in one linked group.
    if (manifold) {
        std::vector<std::uint32_t> fan(nv, std::numeric_limits<std::uint32_t>::max());
        for (std::uint32_t c = 0; c < 3 * nf && manifold; ++c) {
            const std::uint32_t v = mesh.triangles[c / 3][c % 3];
            const std::uint32_t root = corners.find(c);
            if (fan[v] == std::numeric_limits<std::uint32_t>::max())
                fan[v] = root;
            else if (fan[v] != root)
                manifold = false;
        }
    }

    // Components through shared vertices, and the Euler characteristic of each.
    std::vector<char> used(nv, 0);
    UnionFind vertices(nv);
    for (const auto& t : mesh.triangles) {
        used[t[0]] = used[t[1]] = used[t[2]] = 1;
        vertices.unite(t[0], t[1]);
        vertices.unite(t[1], t[2]);
    }
    std::vector<long long> chi(nv, 0);  // indexed by component root
    std::size_t referenced = 0, components = 0;
    for (std::uint32_t v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        ++referenced;
        const std::uint32_t root = vertices.find(v);
        if (root == v) ++components;
        ++chi[root];
    }
    for (std::size_t i = 0; i < half_edges.size(); ++i)
        if (i == 0 || half_edges[i].key != half_edges[i - 1].key)
            --chi[vertices.find(std::uint32_t(half_edges[i].key >> 32))];
    for (const auto& t : mesh.triangles) ++chi[vertices.find(t[0])];

    // Boundary loops. A boundary edge ties the fan at its start to the fan at its end (the fans
    // being the groups of linked corners, now complete): the loops are the groups they tie
    // together. Tying them only now keeps them out of the fan count above.
    std::size_t boundary_edges = 0;
    double boundary_length = 0.0;
    std::vector<std::uint32_t> loop_corners;  // the starting corner of each boundary edge
    for (std::size_t i = 0; i < half_edges.size(); ++i) {
        const bool alone = (i == 0 || half_edges[i].key != half_edges[i - 1].key) &&
                           (i + 1 == half_edges.size() || half_edges[i].key != half_edges[i + 1].key);
        if (!alone) continue;
        const HalfEdge& h = half_edges[i];
        const std::uint32_t start = 3 * h.face + h.corner, end = 3 * h.face + (h.corner + 1) % 3;
        corners.unite(start, end);
        loop_corners.push_back(start);
        ++boundary_edges;
        const Vec3 &a = mesh.positions[h.key >> 32], &b = mesh.positions[std::uint32_t(h.key)];
        boundary_length += (to_eigen(a) - to_eigen(b)).norm();
    }
    for (std::uint32_t& c : loop_corners) c = corners.find(c);
    std::sort(loop_corners.begin(), loop_corners.end());
    loop_corners.erase(std::unique(loop_corners.begin(), loop_corners.end()), loop_corners.end());
    std::vector<std::uint32_t> loops(nv, 0);  // indexed by component root
    for (const std::uint32_t c : loop_corners) ++loops[vertices.find(mesh.triangles[c / 3][c % 3])];

    MeshTopology r;
    r.closed = closed;
    r.manifold = manifold;
    r.euler = (long long)referenced - (long long)edges + (long long)nf;
    r.components = components;
    r.isolated_vertices = nv - referenced;
    r.boundary_loops = loop_corners.size();
    r.boundary_edges = boundary_edges;
    r.boundary_length = boundary_length;
    // On an oriented manifold 2 - chi - b is even and not negative in every component.
    if (manifold) {
        long long genus = 0;
        for (std::uint32_t v = 0; v < nv; ++v)
            if (used[v] && vertices.find(v) == v) genus += (2 - chi[v] - loops[v]) / 2;
        r.genus = int(genus);
    }
    return r;
}

}  // namespace nmesh
