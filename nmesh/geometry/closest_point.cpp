#include "nmesh/geometry/closest_point.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>

namespace nmesh {

namespace {
using Vector3d = Eigen::Vector3d;
Vector3d to_eigen(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
}  // namespace

double point_triangle_squared_distance(const Vec3& p_in, const Vec3& a_in, const Vec3& b_in, const Vec3& c_in) {
    // The closest point by Voronoi region of the triangle (Ericson, Real-Time Collision Detection,
    // section 5.1.5): vertex regions, then edge regions, then the face.
    const Vector3d p = to_eigen(p_in), a = to_eigen(a_in), b = to_eigen(b_in), c = to_eigen(c_in);
    const Vector3d ab = b - a, ac = c - a, ap = p - a;
    if (ab.cross(ac).squaredNorm() == 0.0) {  // degenerate: the nearest of the three segments
        const auto segment = [&p](const Vector3d& s, const Vector3d& t) {
            const Vector3d st = t - s;
            const double len2 = st.squaredNorm();
            const double u = len2 > 0.0 ? std::clamp((p - s).dot(st) / len2, 0.0, 1.0) : 0.0;
            return (p - (s + u * st)).squaredNorm();
        };
        return std::min({segment(a, b), segment(b, c), segment(c, a)});
    }
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return ap.squaredNorm();  // vertex a
    const Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return bp.squaredNorm();  // vertex b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)  // edge ab
        return (p - (a + (d1 / (d1 - d3)) * ab)).squaredNorm();
    const Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return cp.squaredNorm();  // vertex c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)  // edge ac
        return (p - (a + (d2 / (d2 - d6)) * ac)).squaredNorm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)  // edge bc
        return (p - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b))).squaredNorm();
    const double denom = 1.0 / (va + vb + vc);  // the face
    return (p - (a + ab * (vb * denom) + ac * (vc * denom))).squaredNorm();
}

}  // namespace nmesh
