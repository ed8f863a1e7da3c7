// nmesh/point_cloud.h — an unorganized set of 3D points (the input of a reconstruction).
//
// Points are stored as 12-byte float triples. Readers produce a PointCloud (see point_reader.h).
#pragma once

#include <cstddef>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/vec3.h"

namespace nmesh {

struct PointCloud {
    std::vector<Vec3> points;

    std::size_t size() const { return points.size(); }
    bool empty() const { return points.empty(); }
    BoundingBox bounds() const { return bounding_box(points); }
};

}  // namespace nmesh
