#include "nmesh/spatial/cloud_sample.h"

#include <cassert>

#include "nmesh/util/random.h"

namespace nmesh {

std::vector<Vec3> stratified_sample(PointSpan points, std::size_t count, std::uint64_t seed) {
    const std::size_t n = points.size();
    assert(count > 0 && count <= n && n <= 0xffffffffu);
    Random rng(seed);
    std::vector<Vec3> sample(count);
    // Run j starts at floor(j n / count); the products fit in 64 bits (n < 2^32, count <= n).
    std::size_t begin = 0;
    for (std::size_t j = 0; j < count; ++j) {
        const std::size_t end = std::size_t((std::uint64_t(j) + 1) * n / count);
        sample[j] = points[begin + rng.below(std::uint32_t(end - begin))];
        begin = end;
    }
    return sample;
}

std::size_t index_point_count(std::size_t n, const Parameters& params) {
    if (params.index_points_per_vertex == 0) return n;
    const std::uint64_t budget = std::uint64_t(params.index_points_per_vertex) * params.target_vertices;
    return budget < n ? std::size_t(budget) : n;
}

std::unique_ptr<PointGrid> index_cloud(PointSpan points, const PointTransform& transform, const BoundingBox& bounds,
                                       const Parameters& params) {
    const std::size_t count = index_point_count(points.size(), params);
    if (count == points.size()) return std::make_unique<PointGrid>(points, transform, bounds);
    // Any fixed odd constant would do: it only keeps the sample's stream apart from the engine's.
    const std::vector<Vec3> sample = stratified_sample(points, count, params.seed ^ 0x5851f42d4c957f2dull);
    return std::make_unique<PointGrid>(sample, transform, bounds);
}

void record_index(const PointGrid& index, Statistics& stats) {
    stats.indexed_points = index.size();
    stats.index_bytes = index.memory_bytes();
}

}  // namespace nmesh
