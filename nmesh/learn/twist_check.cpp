#include "nmesh/learn/twist_check.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <vector>

#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/mesh/orientation.h"

namespace nmesh {

std::size_t largest_inward_region(const Mesh& mesh) {
    const IndexedMesh m = mesh.to_indexed();
    const std::vector<std::uint8_t> inward = inward_face_flags(m, TriangleBvh(m));
    // The edges of the inward faces, sorted by their end points: a run of one edge joins the
    // faces on its two sides (union-find).
    std::vector<std::array<std::uint32_t, 3>> edges;  // {smaller end, larger end, face}
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f) {
        if (!inward[f]) continue;
        const auto& t = m.triangles[f];
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = t[i], b = t[(i + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), f});
        }
    }
    if (edges.empty()) return 0;
    std::sort(edges.begin(), edges.end());
    std::vector<std::uint32_t> parent(m.triangles.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto root = [&](std::uint32_t f) {
        while (parent[f] != f) f = parent[f] = parent[parent[f]];
        return f;
    };
    for (std::size_t i = 1; i < edges.size(); ++i)
        if (edges[i][0] == edges[i - 1][0] && edges[i][1] == edges[i - 1][1])
            parent[root(edges[i][2])] = root(edges[i - 1][2]);
    std::vector<std::uint32_t> size(m.triangles.size(), 0);
    std::size_t largest = 0;
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
        if (inward[f]) largest = std::max<std::size_t>(largest, ++size[root(f)]);
    return largest;
}

}  // namespace nmesh
