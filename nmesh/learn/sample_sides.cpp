#include "nmesh/learn/sample_sides.h"

#include "nmesh/spatial/point_grid.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

std::vector<Vec3> sample_sides(PointSpan points, const PointTransform& transform, const IndexedMesh& surface,
                               float reach, std::uint32_t threads) {
    std::vector<Vec3> sides;
    if (surface.positions.empty()) return sides;
    sides.resize(points.size());
    const PointGrid grid{PointSpan(surface.positions)};
    for_chunks(points.size(), 4096, threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Vec3 p = transform(points[i]);
            const Vec3 q = surface.positions[grid.nearest(p)];
            const float length = norm(q - p);
            sides[i] = length > 0.0f && length <= reach ? (q - p) * (1.0f / length) : Vec3{};
        }
    });
    return sides;
}

}  // namespace nmesh
