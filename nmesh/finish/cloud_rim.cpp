#include "nmesh/finish/cloud_rim.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

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
    if (points.empty() || !(spacing > 0.0f)) return out;
    // Points hashed in cells of two spacings; a query widens ring by ring until its k nearest
    // are certain (within the widened block's inner radius), up to kRimMaxRings rings.
    const float cell_size = 2.0f * spacing;
    auto cell = [&](float x) { return std::int64_t(std::floor(x / cell_size)); };
    auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
        return (std::uint64_t(i & 0x1fffff) << 42) | (std::uint64_t(j & 0x1fffff) << 21) | std::uint64_t(k & 0x1fffff);
    };
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
    for (std::uint32_t i = 0; i < points.size(); ++i)
        cells[key(cell(points[i].x), cell(points[i].y), cell(points[i].z))].push_back(i);
    constexpr std::size_t k = kRimNeighbours;
    std::vector<std::pair<float, std::uint32_t>> found;
    std::vector<Vec3> near;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const Vec3 p = points[i];
        const std::int64_t ci = cell(p.x), cj = cell(p.y), ck = cell(p.z);
        float certain = 0.0f;
        for (int rings = 1; rings <= kRimMaxRings; ++rings) {
            found.clear();
            for (std::int64_t x = ci - rings; x <= ci + rings; ++x)
                for (std::int64_t y = cj - rings; y <= cj + rings; ++y)
                    for (std::int64_t z = ck - rings; z <= ck + rings; ++z) {
                        const auto it = cells.find(key(x, y, z));
                        if (it == cells.end()) continue;
                        for (std::uint32_t j : it->second)
                            if (j != i) found.push_back({squared_distance(points[j], p), j});
                    }
            // Every point within `certain` of p lies in the block.
            certain = float(rings) * cell_size;
            std::size_t inside = 0;
            for (const auto& f : found) inside += std::size_t(f.first <= certain * certain);
            if (inside >= k) break;
        }
        const std::size_t n = std::min(k, found.size());
        std::partial_sort(found.begin(), found.begin() + std::ptrdiff_t(n), found.end());
        near.clear();
        for (std::size_t j = 0; j < n && found[j].first <= certain * certain; ++j)
            near.push_back(points[found[j].second]);
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
