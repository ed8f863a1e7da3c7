// nmesh/spatial/sorted_cells.h — the points of a cloud sorted by the cubic cell they lie in: the
// cloud's points near a place, without a hash map (the solid's spacing, the stray points, the
// cloud's parts).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "nmesh/point_span.h"

namespace nmesh {

// The points sorted by the key of their cubic cell: a cell's points are a run of the array, found
// by binary search. Keys keep 21 bits of each cell coordinate; cells whose coordinates agree in
// those bits share a run, which costs distance checks, never a wrong answer.
class SortedCells {
public:
    // `cell` > 0; O(n log n).
    SortedCells(PointSpan points, const Vec3& origin, float cell) : origin_(origin), cell_(cell) {
        entries_.resize(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) {
            const auto c = coords(points[i]);
            entries_[i] = {key(c[0], c[1], c[2]), std::uint32_t(i)};
        }
        std::sort(entries_.begin(), entries_.end());
    }

    std::array<std::int64_t, 3> coords(const Vec3& p) const {
        return {std::int64_t(std::floor((p.x - origin_.x) / cell_)),
                std::int64_t(std::floor((p.y - origin_.y) / cell_)),
                std::int64_t(std::floor((p.z - origin_.z) / cell_))};
    }

    // f(j) for every point j of cell (x, y, z) (and of the cells sharing its key); stops when f
    // returns true, and returns whether it did.
    template <class F>
    bool for_each_in(std::int64_t x, std::int64_t y, std::int64_t z, F&& f) const {
        const std::uint64_t k = key(x, y, z);
        auto it = std::lower_bound(entries_.begin(), entries_.end(), std::make_pair(k, std::uint32_t(0)));
        for (; it != entries_.end() && it->first == k; ++it)
            if (f(it->second)) return true;
        return false;
    }

    float cell() const { return cell_; }
    // (key, point) for every point, by key.
    const std::vector<std::pair<std::uint64_t, std::uint32_t>>& entries() const { return entries_; }
    static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
        return (std::uint64_t(x & 0x1fffff) << 42) | (std::uint64_t(y & 0x1fffff) << 21) | std::uint64_t(z & 0x1fffff);
    }

private:
    Vec3 origin_;
    float cell_;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> entries_;
};

}  // namespace nmesh
