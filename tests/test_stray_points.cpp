// Stray points (nmesh/pipeline/stray_points.h): against a brute-force reading of the same rule,
// none on a clean sample, and left out of the reconstruction as if they had never been there.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cloud_fixtures.h"
#include "nmesh/pipeline/stray_points.h"
#include "nmesh/reconstruct.h"
#include "nmesh/util/random.h"

using namespace nmesh;
using nmesh::test::sphere_cloud;

namespace {

// A unit sphere sample with `n_air` more points spread through the cube [-1.5, 1.5]^3.
std::vector<Vec3> sphere_with_air(std::size_t n, std::size_t n_air, std::uint64_t seed) {
    std::vector<Vec3> p = sphere_cloud(n, 1.0f, {}, seed).points;
    Random rng(seed + 100);
    for (std::size_t i = 0; i < n_air; ++i)
        p.push_back({float(rng.uniform() * 3 - 1.5), float(rng.uniform() * 3 - 1.5), float(rng.uniform() * 3 - 1.5)});
    return p;
}

// The rule read by brute force: the 8th nearest neighbour of every point, their median over
// every point, and the points beyond `ratio` times it.
std::vector<std::uint32_t> brute_force(const std::vector<Vec3>& p, float ratio) {
    std::vector<float> kth(p.size());
    std::vector<float> d2;
    for (std::size_t i = 0; i < p.size(); ++i) {
        d2.clear();
        for (std::size_t j = 0; j < p.size(); ++j)
            if (j != i) d2.push_back(squared_distance(p[j], p[i]));
        std::nth_element(d2.begin(), d2.begin() + (kStrayNeighbours - 1), d2.end());
        kth[i] = d2[kStrayNeighbours - 1];
    }
    std::vector<float> sorted = kth;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    const float reach = ratio * std::sqrt(sorted[sorted.size() / 2]);
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (kth[i] > reach * reach) out.push_back(std::uint32_t(i));
    return out;
}

}  // namespace

TEST_CASE("the stray points are those the rule finds by brute force") {
    // At most 4,096 points: the median is read from every point, as the brute force reads it.
    for (const std::uint64_t seed : {1, 2, 3}) {
        CAPTURE(seed);
        const std::vector<Vec3> p = sphere_with_air(3000, 60, seed);
        for (const float ratio : {2.0f, 6.0f}) {
            CAPTURE(ratio);
            const std::vector<std::uint32_t> found = stray_points(p, ratio * median_neighbour_distance(p), 1);
            CHECK(found == brute_force(p, ratio));
            CHECK(found == stray_points(p, ratio * median_neighbour_distance(p), 2));  // the same for any thread count
        }
        // At 6 times the median, the points in the air farthest from the sphere and none of the
        // sphere's (the 8th neighbour of a point in the air lies about as far as 6 times the
        // sphere's: those near the sphere are not far from it).
        const std::vector<std::uint32_t> found = stray_points(p, 6.0f * median_neighbour_distance(p), 1);
        CHECK(std::all_of(found.begin(), found.end(), [](std::uint32_t i) { return i >= 3000; }));
        CHECK(found.size() >= 10);
    }
}

TEST_CASE("a clean sample has no stray point; the rule can be turned off; a tiny cloud is not read") {
    const std::vector<Vec3> clean = sphere_cloud(20000, 1.0f, {}, 5).points;
    CHECK(stray_points(clean, 6.0f * median_neighbour_distance(clean), 0).empty());
    const std::vector<Vec3> p = sphere_with_air(3000, 60, 4);
    CHECK(stray_points(p, 0.0f, 0).empty());
    // Fewer than 8 k points are not read; from 8 k on, a far point is found.
    std::vector<Vec3> tiny(p.begin(), p.begin() + 8 * kStrayNeighbours - 2);
    tiny.push_back({100.0f, 100.0f, 100.0f});
    CHECK(median_neighbour_distance(tiny) == 0.0f);
    CHECK(stray_points(tiny, 6.0f * median_neighbour_distance(tiny), 0).empty());
    tiny.push_back({1.0f, 0.0f, 0.0f});
    CHECK(median_neighbour_distance(tiny) > 0.0f);
    CHECK(stray_points(tiny, 6.0f * median_neighbour_distance(tiny), 0) ==
          std::vector<std::uint32_t>{std::uint32_t(tiny.size() - 2)});
}

TEST_CASE("without_points keeps the others in order") {
    const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    CHECK(without_points(p, {}) == p);
    CHECK(without_points(p, {0, 2}) == std::vector<Vec3>{{1, 0, 0}, {3, 0, 0}});
    CHECK(without_points(p, {3}) == std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
}

TEST_CASE("the reconstruction leaves the stray points out, as if they had never been there") {
    const std::vector<Vec3> p = sphere_with_air(8000, 200, 6);
    const std::vector<std::uint32_t> strays = stray_points(p, 6.0f * median_neighbour_distance(p), 0);
    REQUIRE(strays.size() >= 100);
    Parameters params;
    params.target_vertices = 1500;
    const Result with = reconstruct(p, params);
    CHECK(with.stats.stray_points == strays.size());
    CHECK(with.stats.crossing_pairs == 0);
    CHECK(with.stats.inward_faces == 0);
    params.stray_ratio = 0.0f;
    const Result clean = reconstruct(without_points(p, strays), params);
    CHECK(clean.stats.stray_points == 0);
    CHECK(clean.mesh.positions == with.mesh.positions);
    CHECK(clean.mesh.triangles == with.mesh.triangles);
    // Kept, the points in the air far from it draw spikes off the sphere.
    const Result kept = reconstruct(p, params);
    float worst_with = 0.0f, worst_kept = 0.0f;
    for (const Vec3& v : with.mesh.positions) worst_with = std::max(worst_with, std::fabs(norm(v) - 1.0f));
    for (const Vec3& v : kept.mesh.positions) worst_kept = std::max(worst_kept, std::fabs(norm(v) - 1.0f));
    CAPTURE(worst_with);
    CAPTURE(worst_kept);
    CHECK(worst_with < 0.25f);  // the points in the air near the sphere stay, and pull a little
    CHECK(worst_kept > 2.0f * worst_with);
}
