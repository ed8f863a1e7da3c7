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

CloudParts cloud_parts(PointSpan cloud, float link, double min_share) {
    CloudParts out;
    if (cloud.empty()) {
        out.count = 0;
        return out;
    }
    if (!(link > 0.0f)) {
        out.part.assign(cloud.size(), 0);
        out.size = {cloud.size()};
        return out;
    }
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
    // The parts large enough, by size; a root is the smallest cell of its part, so ties go by it.
    const double least = min_share * double(cloud.size());
    std::vector<std::uint32_t> roots;
    for (std::uint32_t c = 0; c < keys.size(); ++c)
        if (points[c] > 0 && double(points[c]) >= least) roots.push_back(c);
    std::stable_sort(roots.begin(), roots.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return points[a] > points[b]; });
    std::vector<std::uint32_t> number(keys.size(), kNoPart);
    for (std::uint32_t i = 0; i < roots.size(); ++i) {
        number[roots[i]] = i;
        out.size.push_back(points[roots[i]]);
    }
    out.count = std::uint32_t(roots.size());
    out.part.assign(cloud.size(), kNoPart);
    for (std::size_t e = 0, c = 0; e < entries.size(); ++e) {
        if (e > 0 && entries[e].first != entries[e - 1].first) ++c;
        out.part[entries[e].second] = number[root(parent, std::uint32_t(c))];
    }
    return out;
}

}  // namespace nmesh
