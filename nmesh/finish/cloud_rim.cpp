#include "nmesh/finish/cloud_rim.h"

#include "nmesh/spatial/neighbour_grid.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace nmesh {

float largest_gap(const Vec3& centre, const std::vector<Vec3>& around, const Vec3& u, const Vec3& v) {
    constexpr float kTwoPi = 6.28318531f;
    std::vector<float> angles;
    angles.reserve(around.size());
    for (const Vec3& p : around) {
        const Vec3 d = p - centre;
        const float x = dot(d, u), y = dot(d, v);
        if (x != 0.0f || y != 0.0f) angles.push_back(std::atan2(y, x));
    }
    if (angles.empty()) return kTwoPi;
    std::sort(angles.begin(), angles.end());
    float gap = angles.front() + kTwoPi - angles.back();  // across the cut at +-pi
    for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, angles[i] - angles[i - 1]);
    return gap;
}

CloudRim cloud_rim(const std::vector<Vec3>& points, float spacing) {
    CloudRim out;
    out.rim.assign(points.size(), 0);
    out.spacing.assign(points.size(), spacing);
    out.flat.assign(points.size(), 0);
    out.normal.assign(points.size(), Vec3{});
    if (points.empty() || !(spacing > 0.0f)) return out;
    // Points hashed in cells of two spacings.
    const NeighbourGrid grid(points, 2.0f * spacing);
    std::vector<std::pair<float, std::uint32_t>> found;
    std::vector<Vec3> near;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const Vec3 p = points[i];
        grid.nearest(i, kRimNeighbours, kRimMaxRings, found);
        near.clear();
        for (const auto& f : found) near.push_back(points[f.second]);
        if (near.size() < std::size_t(kRimMinNeighbours)) {
            out.rim[i] = 1;  // a stray point, or a sparse fringe
            continue;
        }
        // The local spacing: for k points uniformly in a disc of radius r, r sqrt(pi / k).
        const float r = std::sqrt(squared_distance(near.back(), p));
        out.spacing[i] = r * std::sqrt(3.14159265f / float(near.size()));
        // The tangent plane: the two larger principal directions of the neighbourhood round p.
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (const Vec3& q : near) {
            const Eigen::Vector3d d(q.x - p.x, q.y - p.y, q.z - p.z);
            cov += d * d.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
        solver.computeDirect(cov);
        const Eigen::Vector3d a = solver.eigenvectors().col(2), b = solver.eigenvectors().col(1);
        const Vec3 u{float(a.x()), float(a.y()), float(a.z())}, v{float(b.x()), float(b.y()), float(b.z())};
        const Eigen::Vector3d n = solver.eigenvectors().col(0);
        out.normal[i] = {float(n.x()), float(n.y()), float(n.z())};
        // A crease or a corner (neighbours on two or more planes) is not an edge of the sampled
        // surface, however one-sided its tangent plane makes it look.
        const Eigen::Vector3d lambda = solver.eigenvalues();  // ascending
        const bool flat = lambda(0) <= double(kRimFlatness) * lambda(1);
        out.rim[i] = largest_gap(p, near, u, v) > kRimGapRadians;
        out.flat[i] = flat;
    }
    return out;
}

}  // namespace nmesh
