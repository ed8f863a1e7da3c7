// nmesh/bounding_box.h — axis-aligned bounding boxes.
#pragma once

#include <cstddef>
#include <limits>
#include "nmesh/point_span.h"
#include "nmesh/vec3.h"

namespace nmesh {

struct BoundingBox {
    // An empty box: min > max, so extending it by any point gives that point.
    Vec3 min{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
    Vec3 max{-std::numeric_limits<float>::max(), -std::numeric_limits<float>::max(),
             -std::numeric_limits<float>::max()};

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void extend(const Vec3& p) {
        min = nmesh::min(min, p);
        max = nmesh::max(max, p);
    }
    Vec3 center() const { return (min + max) * 0.5f; }
    Vec3 extent() const { return empty() ? Vec3{} : max - min; }
    // Length of the box's diagonal (0 for an empty box); computed in double for accuracy.
    double diagonal() const;
};

// The bounding box of a set of points; O(n).
BoundingBox bounding_box(PointSpan points);

}  // namespace nmesh
