#include "nmesh/learn/cloud_splats.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <utility>

#include "nmesh/spatial/neighbour_grid.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

std::vector<Splat> cloud_splats(const std::vector<Vec3>& points, float spacing, std::uint32_t threads) {
    std::vector<Splat> out(points.size());
    if (points.empty() || !(spacing > 0.0f)) {
        for (std::size_t i = 0; i < points.size(); ++i) out[i].centre = points[i];
        return out;
    }
    // Cells of 3 d, two rings: every point within 6 d is searched, where 16 neighbours lie (a
    // point holds about 4.5 d^2 of the surface); cells of 2 d took a third ring for most points.
    const NeighbourGrid grid(points, 3.0f * spacing);
    for_chunks(points.size(), 1024, threads, [&](std::size_t begin, std::size_t end) {
        std::vector<std::pair<float, std::uint32_t>> found;
        for (std::size_t i = begin; i < end; ++i) {
            Splat& s = out[i];
            s.centre = points[i];
            grid.nearest(std::uint32_t(i), kSplatNeighbours, 2, found);
            if (found.size() < 5) continue;
            Eigen::Vector3d mean = Eigen::Vector3d(points[i].x, points[i].y, points[i].z);
            for (const auto& f : found)
                mean += Eigen::Vector3d(points[f.second].x, points[f.second].y, points[f.second].z);
            const double n = double(found.size() + 1);
            mean /= n;
            Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
            auto add = [&](const Vec3& q) {
                const Eigen::Vector3d d = Eigen::Vector3d(q.x, q.y, q.z) - mean;
                cov += d * d.transpose();
            };
            add(points[i]);
            for (const auto& f : found) add(points[f.second]);
            cov /= n;
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
            solver.computeDirect(cov);
            const Eigen::Vector3d lambda = solver.eigenvalues();  // ascending
            const Eigen::Vector3d normal = solver.eigenvectors().col(0);
            // The radius of curvature the spread off the plane stands for (see the header).
            const double rho2 = 2.0 * (lambda(1) + lambda(2));
            const double off = std::sqrt(std::max(lambda(0), 0.0));
            const double limit = double(kMaxStretch) * 2.0 * double(spacing);  // a at which s reaches its largest
            const double a = off > 0.0 ? rho2 / (std::sqrt(48.0) * off) : limit;
            s.stretch = float(std::clamp(a / (2.0 * double(spacing)), 1.0, double(kMaxStretch)));
            s.normal = Vec3{float(normal.x()), float(normal.y()), float(normal.z())};
        }
    });
    return out;
}

std::vector<std::uint8_t> splat_distances(const std::vector<Splat>& splats, const Vec3& origin, float h,
                                          const std::array<std::uint32_t, 3>& dims, float reach,
                                          std::uint32_t threads) {
    const std::uint64_t nx = dims[0], ny = dims[1], nz = dims[2];
    std::vector<std::uint8_t> dist(nx * ny * nz, 255);
    if (splats.empty() || !(h > 0.0f)) return dist;
    // The splats in cell units, in order of their layer, so that a slab of layers finds those
    // that reach it by two binary searches.
    struct Local {
        float x, y, z, nx, ny, nz, k;  // centre, normal, s^2 - 1
    };
    std::vector<Local> local(splats.size());
    for (std::size_t i = 0; i < splats.size(); ++i) {
        const Vec3 c = (splats[i].centre - origin) * (1.0f / h);
        const Splat& s = splats[i];
        local[i] = {c.x, c.y, c.z, s.normal.x, s.normal.y, s.normal.z, s.stretch * s.stretch - 1.0f};
    }
    std::sort(local.begin(), local.end(), [](const Local& a, const Local& b) { return a.z < b.z; });
    // Every cell whose rounded value is at most reach^2: a reading at an offset within the reach
    // is the same as with a larger reach.
    const float r2 = reach * reach + 0.5f;
    reach = std::sqrt(r2);
    constexpr std::size_t kLayers = 4;
    for_chunks(nz, kLayers, threads, [&](std::size_t z_begin, std::size_t z_end) {
        const auto first = std::lower_bound(local.begin(), local.end(), float(z_begin) - reach,
                                            [](const Local& a, float z) { return a.z < z; });
        const auto last = std::upper_bound(local.begin(), local.end(), float(z_end) + reach,
                                           [](float z, const Local& a) { return z < a.z; });
        for (auto it = first; it != last; ++it) {
            const Local& s = *it;
            const float a = 1.0f + s.k * s.nz * s.nz;
            const std::int64_t x0 = std::max<std::int64_t>(0, std::int64_t(std::ceil(s.x - reach)));
            const std::int64_t x1 = std::min<std::int64_t>(std::int64_t(nx) - 1, std::int64_t(std::floor(s.x + reach)));
            const std::int64_t y0 = std::max<std::int64_t>(0, std::int64_t(std::ceil(s.y - reach)));
            const std::int64_t y1 = std::min<std::int64_t>(std::int64_t(ny) - 1, std::int64_t(std::floor(s.y + reach)));
            for (std::int64_t y = y0; y <= y1; ++y)
                for (std::int64_t x = x0; x <= x1; ++x) {
                    // m(dz) = a dz^2 + b dz + c, at most r2 between the roots.
                    const float dx = float(x) - s.x, dy = float(y) - s.y;
                    const float t = s.nx * dx + s.ny * dy;
                    const float b = 2.0f * s.k * s.nz * t;
                    const float c = dx * dx + dy * dy + s.k * t * t;
                    const float disc = b * b - 4.0f * a * (c - r2);
                    if (disc < 0.0f) continue;
                    const float root = std::sqrt(disc);
                    const std::int64_t lo = std::max<std::int64_t>(
                        std::int64_t(z_begin), std::int64_t(std::ceil(s.z + (-b - root) / (2.0f * a))));
                    const std::int64_t hi = std::min<std::int64_t>(
                        std::int64_t(z_end) - 1, std::int64_t(std::floor(s.z + (-b + root) / (2.0f * a))));
                    for (std::int64_t z = lo; z <= hi; ++z) {
                        const float dz = float(z) - s.z;
                        const float m = (a * dz + b) * dz + c;
                        const float v = std::min(std::nearbyint(std::max(m, 0.0f)), 254.0f);
                        std::uint8_t& cell = dist[(std::uint64_t(z) * ny + std::uint64_t(y)) * nx + std::uint64_t(x)];
                        if (v < float(cell)) cell = std::uint8_t(v);
                    }
                }
        }
    });
    return dist;
}

}  // namespace nmesh
