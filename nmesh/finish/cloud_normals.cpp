#include "nmesh/finish/cloud_normals.h"

#include <cmath>
#include <cstdint>
#include <queue>
#include <utility>

#include "nmesh/finish/cloud_rim.h"
#include "nmesh/spatial/neighbour_grid.h"

namespace nmesh {

Orientation orient_normals(const std::vector<Vec3>& points, std::vector<Vec3>& normals, float spacing) {
    const std::uint32_t n = std::uint32_t(points.size());
    Orientation out;
    out.part.assign(n, kNoPart);
    if (n == 0 || !(spacing > 0.0f)) return out;
    // The symmetric neighbour graph, in compressed rows.
    std::vector<std::uint32_t> start(n + 1, 0), to;
    {
        const NeighbourGrid grid(points, 2.0f * spacing);
        std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
        std::vector<std::pair<float, std::uint32_t>> found;
        for (std::uint32_t i = 0; i < n; ++i) {
            if (squared_norm(normals[i]) == 0.0f) continue;
            grid.nearest(i, kOrientNeighbours, kRimMaxRings, found);
            for (const auto& f : found)
                if (squared_norm(normals[f.second]) != 0.0f) pairs.push_back({i, f.second}), pairs.push_back({f.second, i});
        }
        for (const auto& p : pairs) ++start[p.first + 1];
        for (std::uint32_t i = 0; i < n; ++i) start[i + 1] += start[i];
        to.resize(pairs.size());
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (const auto& p : pairs) to[fill[p.first]++] = p.second;
    }
    // Prim's order within each connected part.
    constexpr std::uint32_t kNone = kNoPart;
    std::vector<std::uint32_t>& part = out.part;
    std::vector<Vec3> sums;
    std::vector<std::uint32_t> sizes;
    struct Step {
        float weight;
        std::uint32_t from, to;
        bool operator<(const Step& o) const { return weight < o.weight; }
    };
    std::priority_queue<Step> heap;
    for (std::uint32_t s = 0; s < n; ++s) {
        if (part[s] != kNone || squared_norm(normals[s]) == 0.0f) continue;
        const std::uint32_t id = std::uint32_t(sums.size());
        sums.push_back({});
        sizes.push_back(0);
        heap.push({2.0f, s, s});
        while (!heap.empty()) {
            const Step st = heap.top();
            heap.pop();
            if (part[st.to] != kNone) continue;
            part[st.to] = id;
            if (dot(normals[st.from], normals[st.to]) < 0.0f) normals[st.to] = normals[st.to] * -1.0f;
            sums[id] = sums[id] + normals[st.to];
            ++sizes[id];
            for (std::uint32_t e = start[st.to]; e < start[st.to + 1]; ++e)
                if (part[to[e]] == kNone) heap.push({std::fabs(dot(normals[st.to], normals[to[e]])), st.to, to[e]});
        }
    }
    if (sums.empty()) return out;
    std::uint32_t largest = 0;
    for (std::uint32_t p = 1; p < sizes.size(); ++p)
        if (sizes[p] > sizes[largest]) largest = p;
    const Vec3 view = normalized(sums[largest]);
    for (std::uint32_t i = 0; i < n; ++i)
        if (part[i] != kNone && dot(sums[part[i]], view) < 0.0f) normals[i] = normals[i] * -1.0f;
    out.direction = view;
    return out;
}

}  // namespace nmesh
