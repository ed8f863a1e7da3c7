// Point clouds for the tests: seeded synthetic samples and the real scans.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nmesh/point_cloud.h"
#include "nmesh/util/random.h"

namespace nmesh::test {

// n points uniformly distributed on the sphere (center, radius).
inline PointCloud sphere_cloud(std::size_t n, float radius = 1.0f, Vec3 center = {}, std::uint64_t seed = 7) {
    Random rng(seed);
    PointCloud c;
    c.points.reserve(n);
    while (c.points.size() < n) {
        const Vec3 p{float(rng.uniform() * 2 - 1), float(rng.uniform() * 2 - 1), float(rng.uniform() * 2 - 1)};
        const float r2 = squared_norm(p);
        if (r2 > 1.0f || r2 < 1e-6f) continue;
        c.points.push_back(center + p * (radius / std::sqrt(r2)));
    }
    return c;
}

// n points uniformly distributed on the torus of radii (big, small) round the z axis: a shape
// with a through-hole of radius big - small.
inline PointCloud torus_cloud(std::size_t n, float big = 1.0f, float small = 0.35f, std::uint64_t seed = 3) {
    Random rng(seed);
    PointCloud c;
    c.points.reserve(n);
    const double two_pi = 6.283185307179586;
    while (c.points.size() < n) {
        const double u = two_pi * rng.uniform(), v = two_pi * rng.uniform();
        // Rejection by the area element (big + small cos v) makes the sample uniform in area.
        if (rng.uniform() * (big + small) > big + small * std::cos(v)) continue;
        const double r = big + small * std::cos(v);
        c.points.push_back({float(r * std::cos(u)), float(r * std::sin(u)), float(small * std::sin(v))});
    }
    return c;
}

// About n points uniformly distributed on a thin-walled ring round the z axis (a short tube of
// inner radius 1, wall `thickness`, height 0.5, with its two annular ends) with a ball of radius
// 0.2 on its outside, as a pipe with a boss: a genus-1 shape whose wall is thinner than the edges
// of a mesh of a few thousand vertices, as a sheet-metal part's, and whose boss walls a solid
// round (a wall alone is all shell at every offset: solid_start.h).
inline PointCloud thin_ring_cloud(std::size_t n, float thickness = 0.01f, std::uint64_t seed = 9) {
    Random rng(seed);
    PointCloud c;
    c.points.reserve(n);
    const double two_pi = 6.283185307179586, height = 0.5, r0 = 1.0, r1 = 1.0 + thickness, ball = 0.2;
    const Vec3 centre{float(r1 + 0.1), 0.0f, 0.25f};
    const double inner = two_pi * r0 * height, outer = two_pi * r1 * height, end = 0.5 * two_pi * (r1 * r1 - r0 * r0);
    const double sphere = 2.0 * two_pi * ball * ball, total = inner + outer + 2.0 * end + sphere;
    const auto in_ball = [&](const Vec3& p) { return squared_distance(p, centre) < float(ball * ball); };
    const auto in_wall = [&](const Vec3& p) {
        const double r = std::sqrt(double(p.x) * p.x + double(p.y) * p.y);
        return r > r0 && r < r1 && p.z > 0.0f && p.z < float(height);
    };
    for (std::size_t i = 0; i < n; ++i) {
        const double pick = rng.uniform() * total, u = two_pi * rng.uniform();
        Vec3 p;
        if (pick < inner + outer) {
            const double r = pick < inner ? r0 : r1, z = height * rng.uniform();
            p = {float(r * std::cos(u)), float(r * std::sin(u)), float(z)};
        } else if (pick < inner + outer + 2.0 * end) {
            // Uniform on the annulus: the radius from the area's inverse.
            const double r = std::sqrt(r0 * r0 + rng.uniform() * (r1 * r1 - r0 * r0));
            const double z = pick < inner + outer + end ? 0.0 : height;
            p = {float(r * std::cos(u)), float(r * std::sin(u)), float(z)};
        } else {
            const double z = 2.0 * rng.uniform() - 1.0, s = std::sqrt(1.0 - z * z);
            p = centre + Vec3{float(s * std::cos(u)), float(s * std::sin(u)), float(z)} * float(ball);
            if (in_wall(p)) continue;
        }
        if (pick < inner + outer + 2.0 * end && in_ball(p)) continue;
        c.points.push_back(p);
    }
    return c;
}

// A ball (radius 1) standing on four thin legs (radius 0.06, 1.6 long, with their end discs),
// sampled at one density, about 14,000 points: thin parts like a horse's legs, where a coarse
// mesh twists and folds.
inline PointCloud table_cloud(std::uint64_t seed = 5) {
    Random rng(seed);
    PointCloud c;
    const double two_pi = 6.283185307179586, r = 0.06, length = 1.6, top = -0.6;
    const double density = 12000.0 / (2.0 * two_pi);  // points per unit area
    const double legs[4][2] = {{0.45, 0.45}, {0.45, -0.45}, {-0.45, 0.45}, {-0.45, -0.45}};
    const auto in_leg = [&](double x, double z) {
        for (const auto& l : legs)
            if ((x - l[0]) * (x - l[0]) + (z - l[1]) * (z - l[1]) < r * r) return true;
        return false;
    };
    for (const Vec3& p : sphere_cloud(12000, 1.0f, {}, seed).points)
        if (p.y > 0.0f || !in_leg(p.x, p.z)) c.points.push_back(p);
    for (const auto& l : legs) {
        const double bottom = top - length, ball = -std::sqrt(std::max(0.0, 1.0 - l[0] * l[0] - l[1] * l[1]));
        for (int i = 0; i < int(density * two_pi * r * length); ++i) {
            const double t = two_pi * rng.uniform(), y = bottom + length * rng.uniform();
            if (y < ball) c.points.push_back({float(l[0] + r * std::cos(t)), float(y), float(l[1] + r * std::sin(t))});
        }
        for (int i = 0; i < int(density * 0.5 * two_pi * r * r); ++i) {
            const double t = two_pi * rng.uniform(), q = r * std::sqrt(rng.uniform());
            c.points.push_back({float(l[0] + q * std::cos(t)), float(bottom), float(l[1] + q * std::sin(t))});
        }
    }
    return c;
}

// Reads a binary little-endian PLY with exactly the float properties x, y, z (the format of the
// bundled bunny), without the library's readers, so that tests of other parts do not depend on
// them. Returns an empty vector when the file is missing or short.
inline std::vector<Vec3> read_scan(const std::string& path) {
    std::vector<Vec3> points;
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return points;
    char line[256];
    std::size_t n = 0;
    while (std::fgets(line, sizeof line, f)) {
        std::sscanf(line, "element vertex %zu", &n);
        if (std::string(line) == "end_header\n") break;
    }
    points.resize(n);
    if (std::fread(points.data(), sizeof(Vec3), n, f) != n) points.clear();
    std::fclose(f);
    return points;
}

// The bundled bunny (examples/data/bunny.ply, 35,947 points).
inline PointCloud bundled_bunny() {
    return PointCloud{read_scan(std::string(NMESH_SOURCE_DIR) + "/examples/data/bunny.ply")};
}

}  // namespace nmesh::test
