#include "nmesh/spatial/neighbour_grid.h"

#include <algorithm>
#include <cmath>

namespace nmesh {

NeighbourGrid::NeighbourGrid(const std::vector<Vec3>& points, float cell_size) : points_(points), cell_size_(cell_size) {
    for (std::uint32_t i = 0; i < points.size(); ++i)
        cells_[key(cell(points[i].x), cell(points[i].y), cell(points[i].z))].push_back(i);
}

std::int64_t NeighbourGrid::cell(float x) const { return std::int64_t(std::floor(x / cell_size_)); }

std::uint64_t NeighbourGrid::key(std::int64_t i, std::int64_t j, std::int64_t k) {
    return (std::uint64_t(i & 0x1fffff) << 42) | (std::uint64_t(j & 0x1fffff) << 21) | std::uint64_t(k & 0x1fffff);
}

void NeighbourGrid::nearest(std::uint32_t i, std::size_t k, int max_rings,
                            std::vector<std::pair<float, std::uint32_t>>& out) const {
    const Vec3 p = points_[i];
    const std::int64_t ci = cell(p.x), cj = cell(p.y), ck = cell(p.z);
    float certain = 0.0f;
    // With cells of about two spacings, a block of r rings is certain within a disc holding about
    // pi (2 r)^2 points of a surface: start at the first r where that reaches k (2 rings for 24
    // neighbours). Fewer rings would be searched only to be searched again; the answer is the same
    // (the k nearest, all within the certain radius, or what max_rings holds).
    int first = 1;
    while (first < max_rings && 12.566f * float(first * first) < float(k)) ++first;
    for (int rings = first; rings <= max_rings; ++rings) {
        out.clear();
        for (std::int64_t x = ci - rings; x <= ci + rings; ++x)
            for (std::int64_t y = cj - rings; y <= cj + rings; ++y)
                for (std::int64_t z = ck - rings; z <= ck + rings; ++z) {
                    const auto it = cells_.find(key(x, y, z));
                    if (it == cells_.end()) continue;
                    for (std::uint32_t j : it->second)
                        if (j != i) out.push_back({squared_distance(points_[j], p), j});
                }
        // Every point within `certain` of p lies in the block.
        certain = float(rings) * cell_size_;
        std::size_t inside = 0;
        for (const auto& f : out) inside += std::size_t(f.first <= certain * certain);
        if (inside >= k) break;
    }
    const std::size_t n = std::min(k, out.size());
    // The n smallest, then sorted: linear selection rather than partial_sort's heap over every
    // candidate (a block holds several times k). Pairs compare fully, so the order is the same.
    if (n < out.size()) std::nth_element(out.begin(), out.begin() + std::ptrdiff_t(n), out.end());
    std::sort(out.begin(), out.begin() + std::ptrdiff_t(n));
    std::size_t kept = 0;
    while (kept < n && out[kept].first <= certain * certain) ++kept;
    out.resize(kept);
}

}  // namespace nmesh
