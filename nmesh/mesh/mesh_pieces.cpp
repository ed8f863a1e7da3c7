#include "nmesh/mesh/mesh_pieces.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <utility>

namespace nmesh {

namespace {
constexpr std::uint32_t kNone = 0xffffffffu;
}  // namespace

std::vector<MeshPiece> split_pieces(const IndexedMesh& mesh) {
    const std::uint32_t nf = std::uint32_t(mesh.triangles.size());
    // Union-find over the triangles, joined across each undirected edge.
    std::vector<std::uint32_t> parent(nf);
    std::iota(parent.begin(), parent.end(), 0u);
    auto find = [&](std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
    edges.reserve(3 * std::size_t(nf));
    for (std::uint32_t t = 0; t < nf; ++t)
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = mesh.triangles[t][std::size_t(i)], b = mesh.triangles[t][std::size_t((i + 1) % 3)];
            edges.push_back({(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b), t});
        }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 1; i < edges.size(); ++i)
        if (edges[i].first == edges[i - 1].first) parent[find(edges[i].second)] = find(edges[i - 1].second);
    std::vector<MeshPiece> pieces;
    std::vector<std::uint32_t> piece_of_root(nf, kNone);
    std::vector<std::uint32_t> local(mesh.positions.size(), kNone), local_piece(mesh.positions.size(), kNone);
    for (std::uint32_t t = 0; t < nf; ++t) {
        const std::uint32_t root = find(t);
        if (piece_of_root[root] == kNone) {
            piece_of_root[root] = std::uint32_t(pieces.size());
            pieces.emplace_back();
        }
        const std::uint32_t id = piece_of_root[root];
        MeshPiece& p = pieces[id];
        std::array<std::uint32_t, 3> tri{};
        for (std::size_t i = 0; i < 3; ++i) {
            const std::uint32_t v = mesh.triangles[t][i];
            if (local_piece[v] != id) {
                local_piece[v] = id;
                local[v] = std::uint32_t(p.mesh.positions.size());
                p.mesh.positions.push_back(mesh.positions[v]);
            }
            tri[i] = local[v];
        }
        p.mesh.triangles.push_back(tri);
        p.triangle.push_back(t);
    }
    return pieces;
}

IndexedMesh join_pieces(const std::vector<IndexedMesh>& pieces) {
    IndexedMesh out;
    for (const IndexedMesh& p : pieces) {
        const std::uint32_t base = std::uint32_t(out.positions.size());
        out.positions.insert(out.positions.end(), p.positions.begin(), p.positions.end());
        for (auto t : p.triangles) {
            for (std::uint32_t& v : t) v += base;
            out.triangles.push_back(t);
        }
    }
    return out;
}

}  // namespace nmesh
