#include "nmesh/pipeline/cloud_parts.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/spatial/sorted_cells.h"

namespace nmesh {

namespace {

std::uint32_t root(std::vector<std::uint32_t>& parent, std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
}

}  // namespace

std::uint32_t cloud_parts(PointSpan cloud, float link, double min_share) {
    if (cloud.empty() || !(link > 0.0f)) return cloud.empty() ? 0 : 1;
    BoundingBox box;
    for (const Vec3& p : cloud) box.extend(p);
    const SortedCells cells(cloud, box.min, link);
    const auto& entries = cells.entries();
    // The occupied cells (their keys, sorted) and a point of each.
    std::vector<std::uint64_t> keys;
    std::vector<std::uint32_t> first, count;
    for (const auto& [key, point] : entries) {
        if (keys.empty() || keys.back() != key) {
            keys.push_back(key);
            first.push_back(point);
            count.push_back(0);
        }
        ++count.back();
    }
    std::vector<std::uint32_t> parent(keys.size());
    std::iota(parent.begin(), parent.end(), 0u);
    for (std::uint32_t c = 0; c < keys.size(); ++c) {
        const auto at = cells.coords(cloud[first[c]]);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const std::uint64_t k = SortedCells::key(at[0] + dx, at[1] + dy, at[2] + dz);
                    const auto it = std::lower_bound(keys.begin(), keys.end(), k);
                    if (it != keys.end() && *it == k) {
                        const std::uint32_t a = root(parent, c), b = root(parent, std::uint32_t(it - keys.begin()));
                        if (a != b) parent[std::max(a, b)] = std::min(a, b);
                    }
                }
    }
    std::vector<std::uint64_t> points(keys.size(), 0);
    for (std::uint32_t c = 0; c < keys.size(); ++c) points[root(parent, c)] += count[c];
    const double least = min_share * double(cloud.size());
    return std::uint32_t(
        std::count_if(points.begin(), points.end(), [&](std::uint64_t n) { return n > 0 && double(n) >= least; }));
}

}  // namespace nmesh
