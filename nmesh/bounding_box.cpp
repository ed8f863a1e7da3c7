#include "nmesh/bounding_box.h"

#include <cmath>

namespace nmesh {

double BoundingBox::diagonal() const {
    if (empty()) return 0.0;
    const double dx = double(max.x) - double(min.x);
    const double dy = double(max.y) - double(min.y);
    const double dz = double(max.z) - double(min.z);
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

BoundingBox bounding_box(const std::vector<Vec3>& points) {
    BoundingBox box;
    for (const Vec3& p : points) box.extend(p);
    return box;
}

}  // namespace nmesh
