#include "nmesh/finish/cloud_layers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

namespace nmesh {

float multi_layer_share(const std::vector<Vec3>& points, float spacing) {
    if (points.size() < 2 || !(spacing > 0.0f)) return 1.0f;
    const float gap = 2.0f * spacing;
    float best = 1.0f;
    // (cell key, depth) per point, sorted: the points of a cell together, by depth.
    std::vector<std::pair<std::uint64_t, float>> cells(points.size());
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z) {
                // One of each pair of opposite directions.
                if (std::make_tuple(x, y, z) <= std::make_tuple(0, 0, 0)) continue;
                const Vec3 v = normalized(Vec3{float(x), float(y), float(z)});
                const Vec3 u = normalized(cross(v, std::abs(v.x) < 0.9f ? Vec3{1.0f, 0.0f, 0.0f} : Vec3{0.0f, 1.0f, 0.0f}));
                const Vec3 w = cross(v, u);
                for (std::size_t i = 0; i < points.size(); ++i) {
                    const auto a = std::int64_t(std::floor(dot(points[i], u) / spacing));
                    const auto b = std::int64_t(std::floor(dot(points[i], w) / spacing));
                    cells[i] = {(std::uint64_t(a) << 32) ^ std::uint64_t(std::uint32_t(b)), dot(points[i], v)};
                }
                std::sort(cells.begin(), cells.end());
                std::size_t occupied = 0, layered = 0;
                for (std::size_t i = 0; i < cells.size();) {
                    std::size_t j = i + 1;
                    bool split = false;
                    for (; j < cells.size() && cells[j].first == cells[i].first; ++j)
                        split = split || cells[j].second - cells[j - 1].second > gap;
                    ++occupied;
                    layered += split;
                    i = j;
                }
                best = std::min(best, float(double(layered) / double(occupied)));
            }
    return best;
}

}  // namespace nmesh
