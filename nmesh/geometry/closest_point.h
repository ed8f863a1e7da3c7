// nmesh/geometry/closest_point.h — the point of a triangle closest to a point, in float and in
// double.
#pragma once

#include "nmesh/vec3.h"

namespace nmesh {

// Declared in nmesh/metrics.h (public): the squared distance from p to the triangle abc, in
// double, degenerate triangles included.
double point_triangle_squared_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

// The closest point of the triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5), in
// float: the finishing stage's distances, on its float positions. Its double twin,
// point_triangle_squared_distance (nmesh/metrics.h, closest_point.cpp), serves the metrics, which
// must not lose accuracy to rounding; both stay, side by side, because the stage's results are
// the float ones.
inline Vec3 closest_point_on_triangle_float(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) return a;
    const Vec3 bp = p - b;
    const float d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + ab * (d1 / (d1 - d3));
    const Vec3 cp = p - c;
    const float d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && d4 - d3 >= 0.0f && d5 - d6 >= 0.0f) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float sum = va + vb + vc;
    if (!(sum > 0.0f)) return a;  // a degenerate triangle
    return a + ab * (vb / sum) + ac * (vc / sum);
}

}  // namespace nmesh
