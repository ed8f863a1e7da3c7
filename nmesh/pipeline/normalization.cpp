// The pipeline's first stage (nmesh/pipeline/normalization.h): a cloud that can be reconstructed.
#include "nmesh/pipeline/normalization.h"

#include <algorithm>
#include <string>

#include "nmesh/error.h"

namespace nmesh::pipeline {

BoundingBox require_reconstructible(PointSpan pts) {
    if (pts.size() < 4)
        throw InputError("the point cloud has " + std::to_string(pts.size()) +
                         " points; at least 4 distinct points are needed");
    const BoundingBox box = bounding_box(pts);
    const Vec3 a = pts[0];
    Vec3 b = a;
    float best = 0.0f;
    bool nan = false;
    for (const Vec3& p : pts) {
        const float d = squared_distance(a, p);
        nan = nan || d != d;
        if (d > best) best = d, b = p;
    }
    if (nan || !is_finite(box.min) || !is_finite(box.max))
        throw InputError("the point cloud holds a non-finite coordinate");
    if (best == 0.0f) throw InputError("all points of the cloud are identical");
    // A point off the line through a and b, the point farthest from a.
    const Vec3 dir = b - a;
    const float off_line = 1e-12f * squared_norm(dir) * squared_norm(dir);
    if (std::none_of(pts.begin(), pts.end(), [&](const Vec3& p) { return squared_norm(cross(p - a, dir)) > off_line; }))
        throw InputError("all points of the cloud lie on one line");
    // At least four distinct points.
    Vec3 distinct[4] = {a};
    int count = 1;
    for (const Vec3& p : pts) {
        bool seen = false;
        for (int i = 0; i < count; ++i) seen = seen || distinct[i] == p;
        if (!seen) distinct[count++] = p;
        if (count == 4) return box;
    }
    throw InputError("the point cloud has only " + std::to_string(count) + " distinct points; at least 4 are needed");
}

}  // namespace nmesh::pipeline
