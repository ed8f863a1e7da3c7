// nmesh/geometry/exact_predicates.h — exact orientation predicates (2D and 3D) on double
// coordinates.
//
// Each predicate returns the exact sign of its determinant: a floating-point evaluation decides
// when its error bound allows (almost always); otherwise the same evaluation with its rounding
// errors computed decides if they are all zero (inputs of few significant bits, such as integer
// coordinates), and an exact evaluation in floating-point expansion arithmetic decides the rest.
// No heap allocation.
//
// Exact for finite inputs whose every coordinate is 0 or of magnitude in [2^-256, 2^256]: then no
// intermediate value overflows or underflows. Every finite float lies in that range, so the Vec3
// overload is exact for all finite positions. Requires IEEE-754 double arithmetic rounding to
// nearest (no x87 extended precision, no -ffast-math or other reassociation).
#pragma once

#include "nmesh/vec3.h"

namespace nmesh {

struct Point2d {
    double x = 0.0, y = 0.0;
};

struct Point3d {
    double x = 0.0, y = 0.0, z = 0.0;
};

// A float position as a double point (exact).
constexpr Point3d to_point3d(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

// The sign (+1, 0, -1) of | a-c ; b-c | = (a.x-c.x)(b.y-c.y) - (a.y-c.y)(b.x-c.x): +1 when a, b,
// c turn counter-clockwise (x to the right, y up), -1 clockwise, 0 collinear. Shewchuk's
// convention for orient2d.
int orient2d(const Point2d& a, const Point2d& b, const Point2d& c);

// The sign (+1, 0, -1) of the 3x3 determinant | a-d ; b-d ; c-d |: +1 when d lies below the plane
// through a, b, c, "below" being the side from which a, b, c appear clockwise (seen from above
// they turn counter-clockwise); -1 above; 0 when the four points are coplanar. Shewchuk's
// convention for orient3d: for a = (0,0,0), b = (1,0,0), c = (0,1,0) the sign is +1 for
// d = (0,0,-1).
int orient3d(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d);

inline int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return orient3d(to_point3d(a), to_point3d(b), to_point3d(c), to_point3d(d));
}

}  // namespace nmesh
