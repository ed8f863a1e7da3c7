#include "nmesh/pipeline/stray_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "nmesh/bounding_box.h"
#include "nmesh/spatial/sorted_cells.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

namespace {

// The median is read from up to this many points (every k-th).
constexpr std::size_t kMedianSample = 4096;

// The squared distance from point i to its k-th nearest other point, when the cells within
// `rings` of its own hold k points within rings cells of it; infinity otherwise.
float kth_squared(PointSpan points, const SortedCells& cells, std::uint32_t i, std::uint32_t k, int rings,
                  std::vector<float>& d2) {
    const Vec3 p = points[i];
    const auto c = cells.coords(p);
    d2.clear();
    for (std::int64_t x = c[0] - rings; x <= c[0] + rings; ++x)
        for (std::int64_t y = c[1] - rings; y <= c[1] + rings; ++y)
            for (std::int64_t z = c[2] - rings; z <= c[2] + rings; ++z)
                cells.for_each_in(x, y, z, [&](std::uint32_t j) {
                    if (j != i) d2.push_back(squared_distance(points[j], p));
                    return false;
                });
    const float certain = float(rings) * cells.cell();
    if (d2.size() < k) return std::numeric_limits<float>::infinity();
    std::nth_element(d2.begin(), d2.begin() + (k - 1), d2.end());
    return d2[k - 1] <= certain * certain ? d2[k - 1] : std::numeric_limits<float>::infinity();
}

}  // namespace

float median_neighbour_distance(PointSpan cloud) {
    const std::size_t n = cloud.size();
    if (n < 8 * kStrayNeighbours) return 0.0f;
    BoundingBox box;
    for (const Vec3& p : cloud) box.extend(p);
    // Cells of about twice the spacing of a surface sample as large as the box: the k-th
    // neighbour of most points within one ring, of nearly all within two.
    const float cell = float(2.0 * box.diagonal() / std::sqrt(double(n)));
    if (!(cell > 0.0f) || !std::isfinite(cell)) return 0.0f;
    const std::size_t stride = std::max<std::size_t>(1, n / kMedianSample);
    std::vector<float> kth;
    const SortedCells cells(cloud, box.min, cell);
    std::vector<float> d2;
    for (std::size_t i = 0; i < n; i += stride) {
        float k2 = kth_squared(cloud, cells, std::uint32_t(i), kStrayNeighbours, 1, d2);
        if (!std::isfinite(k2)) k2 = kth_squared(cloud, cells, std::uint32_t(i), kStrayNeighbours, 2, d2);
        kth.push_back(k2);
    }
    std::nth_element(kth.begin(), kth.begin() + std::ptrdiff_t(kth.size() / 2), kth.end());
    const float median = std::sqrt(kth[kth.size() / 2]);
    // A median of 0 (most points repeated 8 times over) or of nothing found tells nothing.
    return median > 0.0f && std::isfinite(median) ? median : 0.0f;
}

std::vector<std::uint32_t> stray_points(PointSpan cloud, float reach, std::uint32_t threads) {
    const std::size_t n = cloud.size();
    if (!(reach > 0.0f) || !std::isfinite(reach) || n < 8 * kStrayNeighbours) return {};
    BoundingBox box;
    for (const Vec3& p : cloud) box.extend(p);
    // Cells as wide as the reach: the k points within it of a point that is not stray lie in its
    // cell and the 26 round it, most of them in its own, which is searched first.
    const SortedCells cells(cloud, box.min, reach);
    std::vector<std::uint8_t> stray(n, 0);
    for_chunks(n, 4096, threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Vec3 p = cloud[i];
            const auto c = cells.coords(p);
            std::uint32_t near = 0;
            const auto count = [&](std::uint32_t j) {
                near += std::uint32_t(j != i && squared_distance(cloud[j], p) <= reach * reach);
                return near >= kStrayNeighbours;
            };
            bool enough = cells.for_each_in(c[0], c[1], c[2], count);
            for (int dx = -1; dx <= 1 && !enough; ++dx)
                for (int dy = -1; dy <= 1 && !enough; ++dy)
                    for (int dz = -1; dz <= 1 && !enough; ++dz)
                        if (dx != 0 || dy != 0 || dz != 0)
                            enough = cells.for_each_in(c[0] + dx, c[1] + dy, c[2] + dz, count);
            stray[i] = !enough;
        }
    });
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < n; ++i)
        if (stray[i]) out.push_back(std::uint32_t(i));
    return out;
}

std::vector<Vec3> without_points(PointSpan cloud, const std::vector<std::uint32_t>& strays) {
    std::vector<Vec3> kept;
    kept.reserve(cloud.size() - std::min(cloud.size(), strays.size()));
    std::size_t next = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        if (next < strays.size() && strays[next] == i) {
            ++next;
            continue;
        }
        kept.push_back(cloud[i]);
    }
    return kept;
}

}  // namespace nmesh
