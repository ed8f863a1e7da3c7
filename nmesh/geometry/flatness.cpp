// Whether a cloud lies in one plane (nmesh/geometry/flatness.h).
#include "nmesh/geometry/flatness.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace nmesh {

bool is_flat(PointSpan cloud) {
    if (cloud.size() < 4) return true;
    // The plane through three far-apart points, then whether any point lies off it.
    // Choice: the two far points are searched among every stride-th point only (about a million
    // of them at most), so that a large cloud costs a fraction of a pass, plus the test, which
    // stops at the first point off the plane; when those points are all on one line, among all
    // points, as for a cloud of up to 2^21 points.
    const Vec3 a = cloud[0];
    for (std::size_t stride = std::max<std::size_t>(1, cloud.size() >> 20);; stride = 1) {
        Vec3 b = a, c = a;
        float best = -1.0f;
        for (std::size_t i = 0; i < cloud.size(); i += stride)
            if (squared_distance(a, cloud[i]) > best) best = squared_distance(a, cloud[i]), b = cloud[i];
        best = -1.0f;
        for (std::size_t i = 0; i < cloud.size(); i += stride) {
            const float d = squared_norm(cross(cloud[i] - a, b - a));
            if (d > best) best = d, c = cloud[i];
        }
        const Vec3 n = normalized(cross(b - a, c - a));
        if (squared_norm(n) == 0.0f) {
            if (stride == 1) return true;
            continue;
        }
        const float limit = 1e-6f * distance(a, b);
        for (const Vec3& p : cloud)
            if (std::fabs(dot(p - a, n)) > limit) return false;
        return true;
    }
}

}  // namespace nmesh
