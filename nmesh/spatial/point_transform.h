// nmesh/point_transform.h — a similarity transform applied to points as they are read.
//
// reconstruct() normalises the caller's cloud (centred on its bounding box, scaled into a box of
// diagonal at most 1) without copying it: the learning engine and the cloud's nearest-point index
// apply this transform to each point they read. The default is the identity, exactly: (p - 0) * 1
// is p, bit for bit.
#pragma once

#include "nmesh/vec3.h"

namespace nmesh {

struct PointTransform {
    Vec3 center;
    float scale = 1.0f;
    Vec3 operator()(const Vec3& p) const { return (p - center) * scale; }
};

}  // namespace nmesh
