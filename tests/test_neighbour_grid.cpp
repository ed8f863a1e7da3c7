// Tests of NeighbourGrid: every answer is compared with a brute-force scan over the same cloud, on
// a surface, a volume, clusters with sparse stragglers and duplicates, for several k and ring
// limits (a point with few neighbours near gets fewer than k).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "nmesh/spatial/neighbour_grid.h"

using nmesh::NeighbourGrid;
using nmesh::Vec3;

namespace {

using Found = std::vector<std::pair<float, std::uint32_t>>;

// The reference: every other point by (squared distance, index); the first k when at least k lie
// within max_rings cells of the point (so the k nearest are certain), else all that lie there.
Found brute_force(const std::vector<Vec3>& points, std::uint32_t i, std::size_t k, int max_rings, float cell) {
    Found all;
    for (std::uint32_t j = 0; j < points.size(); ++j)
        if (j != i) all.push_back({nmesh::squared_distance(points[j], points[i]), j});
    std::sort(all.begin(), all.end());
    const float certain = float(max_rings) * cell;
    std::size_t inside = 0;
    while (inside < all.size() && all[inside].first <= certain * certain) ++inside;
    all.resize(std::min(inside, k));
    return all;
}

std::size_t mismatches(const std::vector<Vec3>& points, float cell, std::size_t k, int max_rings) {
    const NeighbourGrid grid(points, cell);
    Found found;
    std::size_t bad = 0;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        grid.nearest(i, k, max_rings, found);
        bad += found != brute_force(points, i, k, max_rings, cell);
    }
    return bad;
}

std::vector<Vec3> sphere_surface(std::size_t n, std::mt19937& rng) {
    std::normal_distribution<float> g(0.0f, 1.0f);
    std::vector<Vec3> out;
    while (out.size() < n) {
        const Vec3 v{g(rng), g(rng), g(rng)};
        const float r = std::sqrt(nmesh::squared_norm(v));
        if (r > 1e-3f) out.push_back(v * (1.0f / r));
    }
    return out;
}

}  // namespace

TEST_CASE("NeighbourGrid: the k nearest as a brute-force scan finds them, on a surface and in a volume") {
    std::mt19937 rng(3);
    const std::vector<Vec3> surface = sphere_surface(800, rng);
    // About 0.12 between points on the unit sphere: cells of two spacings, and of other sizes.
    for (const float cell : {0.25f, 0.08f, 0.6f})
        for (const std::size_t k : {std::size_t(1), std::size_t(8), std::size_t(24), std::size_t(60)})
            for (const int rings : {1, 3}) CHECK(mismatches(surface, cell, k, rings) == 0);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Vec3> volume;
    for (int i = 0; i < 700; ++i) volume.push_back({u(rng), u(rng), u(rng)});
    for (const std::size_t k : {std::size_t(8), std::size_t(24)}) CHECK(mismatches(volume, 0.2f, k, 3) == 0);
}

TEST_CASE("NeighbourGrid: clusters, stray points and duplicates get what lies within their rings") {
    std::mt19937 rng(5);
    std::normal_distribution<float> g(0.0f, 0.02f);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    std::vector<Vec3> points;
    for (const Vec3 c : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1.5f, 0}})
        for (int i = 0; i < 200; ++i) points.push_back(c + Vec3{g(rng), g(rng), g(rng)});
    for (int i = 0; i < 40; ++i) points.push_back({u(rng), u(rng), u(rng)});  // stragglers: fewer than k near
    for (int i = 0; i < 10; ++i) points.push_back(points[std::size_t(i) * 7]);  // duplicates: ties by index
    std::size_t short_answers = 0;
    const NeighbourGrid grid(points, 0.05f);
    Found found;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        grid.nearest(i, 24, 3, found);
        short_answers += found.size() < 24;
    }
    CHECK(short_answers >= 40);  // the stragglers' answers are cut at three rings
    for (const std::size_t k : {std::size_t(6), std::size_t(24)})
        for (const int rings : {1, 2, 3}) CHECK(mismatches(points, 0.05f, k, rings) == 0);
}
