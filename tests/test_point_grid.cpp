// Tests of PointGrid: every answer is compared with a brute-force scan over the same cloud, on
// clouds chosen to stress the grid (surface, volume, clusters, duplicates, flat and tiny clouds),
// for queries near and far from the data.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/error.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/spatial/point_transform.h"
#include "cloud_fixtures.h"

using nmesh::BoundingBox;
using nmesh::NearestPoint;
using nmesh::PointGrid;
using nmesh::PointTransform;
using nmesh::Vec3;

namespace {

// The reference answer: a scan of every point, ties to the smaller index.
NearestPoint brute_force_nearest(const std::vector<Vec3>& points, const Vec3& q) {
    NearestPoint best{0, std::numeric_limits<float>::infinity()};
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const float d = nmesh::squared_distance(q, points[i]);
        if (d < best.squared_distance) best = {i, d};
    }
    return best;
}

// Checks every query against the brute force; returns the number of mismatches.
int count_mismatches(const PointGrid& grid, const std::vector<Vec3>& points, const std::vector<Vec3>& queries) {
    int bad = 0;
    for (const Vec3& q : queries) {
        const NearestPoint want = brute_force_nearest(points, q);
        const NearestPoint got = grid.find_nearest(q);
        if (got.index != want.index || got.squared_distance != want.squared_distance) {
            if (bad < 5)
                MESSAGE("query (" << q.x << ", " << q.y << ", " << q.z << "): got " << got.index << " at "
                                  << got.squared_distance << ", want " << want.index << " at "
                                  << want.squared_distance);
            ++bad;
        }
        if (grid.nearest(q) != got.index || grid.nearest_squared_distance(q) != got.squared_distance) ++bad;
    }
    return bad;
}

float uniform(std::mt19937& rng, float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }

Vec3 random_in_box(std::mt19937& rng, const Vec3& lo, const Vec3& hi) {
    return {uniform(rng, lo.x, hi.x), uniform(rng, lo.y, hi.y), uniform(rng, lo.z, hi.z)};
}

Vec3 random_unit_vector(std::mt19937& rng) {
    std::normal_distribution<float> g(0.0f, 1.0f);
    for (;;) {
        const Vec3 v{g(rng), g(rng), g(rng)};
        if (nmesh::norm(v) > 1e-3f) return nmesh::normalized(v);
    }
}

// Queries of every kind for a cloud: on the points, jittered near them, inside the bounding box,
// and far outside it (10 and 1000 diagonals away, and at 1e6 units).
std::vector<Vec3> mixed_queries(const std::vector<Vec3>& points, std::mt19937& rng, int count) {
    Vec3 lo = points[0], hi = points[0];
    for (const Vec3& p : points) {
        lo = nmesh::min(lo, p);
        hi = nmesh::max(hi, p);
    }
    const float diag = std::max(nmesh::distance(lo, hi), 1e-6f);
    const Vec3 mid = (lo + hi) * 0.5f;
    std::vector<Vec3> q;
    std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
    for (int i = 0; i < count; ++i) {
        switch (i % 6) {
            case 0:
                q.push_back(points[pick(rng)]);
                break;
            case 1:
                q.push_back(points[pick(rng)] + random_unit_vector(rng) * (0.01f * diag));
                break;
            case 2:
                q.push_back(random_in_box(rng, lo, hi));
                break;
            case 3:
                q.push_back(mid + random_unit_vector(rng) * (10.0f * diag));
                break;
            case 4:
                q.push_back(mid + random_unit_vector(rng) * (1000.0f * diag));
                break;
            default:
                q.push_back(random_unit_vector(rng) * 1e6f);
                break;
        }
    }
    return q;
}

// Whether two indexes give the same answers, bit for bit, to every query.
bool same_answers(const PointGrid& a, const PointGrid& b, const std::vector<Vec3>& queries) {
    for (const Vec3& q : queries) {
        const NearestPoint x = a.find_nearest(q), y = b.find_nearest(q);
        if (x.index != y.index || x.squared_distance != y.squared_distance) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("PointGrid matches brute force on a surface sample (sphere and torus)") {
    std::mt19937 rng(1);
    std::vector<Vec3> points;
    for (int i = 0; i < 6000; ++i) points.push_back(random_unit_vector(rng) * 2.0f);
    for (int i = 0; i < 6000; ++i) {
        const float u = uniform(rng, 0.0f, 6.2831853f), v = uniform(rng, 0.0f, 6.2831853f);
        const float r = 1.0f + 0.3f * std::cos(v);
        points.push_back({5.0f + r * std::cos(u), r * std::sin(u), 0.3f * std::sin(v)});
    }
    const PointGrid grid(points);
    CHECK(grid.size() == points.size());
    CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 1200)) == 0);
}

TEST_CASE("PointGrid matches brute force on a uniform volume") {
    std::mt19937 rng(2);
    std::vector<Vec3> points;
    for (int i = 0; i < 8000; ++i) points.push_back(random_in_box(rng, {-1, -2, -3}, {1, 2, 3}));
    const PointGrid grid(points);
    CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 1200)) == 0);
}

TEST_CASE("PointGrid matches brute force on tight clusters far apart, with outliers") {
    // Most cells are empty and the clusters are much smaller than a cell: the fast path rarely
    // settles and the pyramid does the work.
    std::mt19937 rng(3);
    std::normal_distribution<float> g(0.0f, 1e-3f);
    std::vector<Vec3> points;
    for (int c = 0; c < 8; ++c) {
        const Vec3 center = random_in_box(rng, {-100, -100, -100}, {100, 100, 100});
        for (int i = 0; i < 1000; ++i) points.push_back(center + Vec3{g(rng), g(rng), g(rng)});
    }
    for (int i = 0; i < 20; ++i) points.push_back(random_in_box(rng, {-100, -100, -100}, {100, 100, 100}));
    const PointGrid grid(points);
    CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 1200)) == 0);
}

TEST_CASE("PointGrid breaks ties by the smaller index") {
    SUBCASE("exact duplicates") {
        // Each location is repeated with scattered indices; a query at a duplicated location must
        // return the first copy.
        std::mt19937 rng(4);
        std::vector<Vec3> locations;
        for (int i = 0; i < 300; ++i) locations.push_back(random_in_box(rng, {0, 0, 0}, {1, 1, 1}));
        std::vector<Vec3> points;
        for (int copy = 0; copy < 5; ++copy)
            for (const Vec3& p : locations) points.push_back(p);
        const PointGrid grid(points);
        for (std::uint32_t i = 0; i < locations.size(); ++i) {
            CHECK(grid.nearest(locations[i]) == i);
            CHECK(grid.nearest_squared_distance(locations[i]) == 0.0f);
        }
        CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 600)) == 0);
    }
    SUBCASE("equidistant lattice points") {
        // Integer lattice points queried at half-integer positions: up to 8 points at the same
        // distance, lying on cell boundaries.
        std::vector<Vec3> points;
        for (int z = 0; z < 12; ++z)
            for (int y = 0; y < 12; ++y)
                for (int x = 0; x < 12; ++x) points.push_back({float(x), float(y), float(z)});
        std::mt19937 rng(5);
        std::vector<Vec3> queries;
        std::uniform_int_distribution<int> half(-3, 25);
        for (int i = 0; i < 800; ++i) queries.push_back({half(rng) * 0.5f, half(rng) * 0.5f, half(rng) * 0.5f});
        const PointGrid grid(points);
        CHECK(count_mismatches(grid, points, queries) == 0);
        // (0.5, 0.5, 0.5) is equidistant from the 8 corners of the first cube; (0,0,0) is index 0.
        CHECK(grid.nearest({0.5f, 0.5f, 0.5f}) == 0);
    }
}

TEST_CASE("PointGrid handles flat, collinear, single-point and offset clouds") {
    std::mt19937 rng(6);
    SUBCASE("planar") {
        std::vector<Vec3> points;
        for (int i = 0; i < 3000; ++i) points.push_back({uniform(rng, 0, 4), uniform(rng, 0, 1), 2.0f});
        const PointGrid grid(points);
        CHECK(grid.dimensions()[2] == 1);
        CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 600)) == 0);
    }
    SUBCASE("collinear") {
        std::vector<Vec3> points;
        for (int i = 0; i < 2000; ++i) points.push_back({1.0f, uniform(rng, -5, 5), -1.0f});
        const PointGrid grid(points);
        CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 600)) == 0);
    }
    SUBCASE("one point") {
        const std::vector<Vec3> points = {{1, 2, 3}};
        const PointGrid grid(points);
        CHECK(grid.nearest({-50, 0, 9}) == 0);
        CHECK(grid.nearest_squared_distance({1, 2, 4}) == 1.0f);
    }
    SUBCASE("tiny extent far from the origin") {
        // Spacing near the float resolution at 1000: cell assignment must stay consistent.
        std::vector<Vec3> points;
        for (int i = 0; i < 2000; ++i)
            points.push_back(Vec3{1000, 1000, 1000} + random_in_box(rng, {0, 0, 0}, {0.01f, 0.01f, 0.01f}));
        const PointGrid grid(points);
        CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 600)) == 0);
    }
    SUBCASE("microscopic scale") {
        std::vector<Vec3> points;
        for (int i = 0; i < 2000; ++i) points.push_back(random_unit_vector(rng) * 1e-12f);
        const PointGrid grid(points);
        std::vector<Vec3> queries;
        for (int i = 0; i < 300; ++i) queries.push_back(random_unit_vector(rng) * uniform(rng, 0, 3e-12f));
        CHECK(count_mismatches(grid, points, queries) == 0);
    }
}

TEST_CASE("PointGrid matches brute force on the bunny scan, within its memory budget") {
    const std::vector<Vec3> points = nmesh::test::read_scan(std::string(NMESH_SOURCE_DIR) + "/examples/data/bunny.ply");
    REQUIRE(points.size() == 35947);
    const PointGrid grid(points);
    std::mt19937 rng(7);
    CHECK(count_mismatches(grid, points, mixed_queries(points, rng, 600)) == 0);

    // Every point's nearest point is the first point at the same place (itself, or an earlier
    // duplicate).
    const auto key = [](const Vec3& p) { return std::array<float, 3>{p.x, p.y, p.z}; };
    std::map<std::array<float, 3>, std::uint32_t> first;
    for (std::uint32_t i = 0; i < points.size(); ++i) first.emplace(key(points[i]), i);
    int wrong = 0;
    for (std::uint32_t i = 0; i < points.size(); ++i) wrong += grid.nearest(points[i]) != first.at(key(points[i]));
    CHECK(wrong == 0);

    // At most 8 bytes per point on top of the sorted copy of the points.
    const double overhead = double(grid.memory_bytes()) - 12.0 * double(points.size());
    MESSAGE("bunny: " << grid.occupied_cells() << " occupied cells, " << overhead / double(points.size())
                      << " bytes per point on top of the copy");
    CHECK(overhead <= 8.0 * double(points.size()));
    // Sized for a surface: a few points per occupied cell.
    const double per_cell = double(points.size()) / double(grid.occupied_cells());
    CHECK(per_cell >= 1.5);
    CHECK(per_cell <= 12.0);
}

TEST_CASE("componentwise min and max agree with std::fmin and std::fmax, NaN included") {
    // The grid's bounding box is built with nmesh::min / nmesh::max, written out to inline.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const float values[] = {-3.5f, 0.0f, 2.0f, 1e30f, -inf, inf, nan};
    for (const float a : values)
        for (const float b : values) {
            const Vec3 lo = nmesh::min(Vec3{a, b, a}, Vec3{b, a, b}), hi = nmesh::max(Vec3{a, b, a}, Vec3{b, a, b});
            for (int k = 0; k < 3; ++k) {
                const float x = k == 1 ? b : a, y = k == 1 ? a : b;
                const float want_lo = std::fmin(x, y), want_hi = std::fmax(x, y);
                CHECK((lo[k] == want_lo || (std::isnan(lo[k]) && std::isnan(want_lo))));
                CHECK((hi[k] == want_hi || (std::isnan(hi[k]) && std::isnan(want_hi))));
            }
        }
    BoundingBox box;
    box.extend({1, 2, 3});
    box.extend({nan, -1, 5});
    CHECK(box.min == Vec3{1, -1, 3});
    CHECK(box.max == Vec3{1, 2, 5});
}

TEST_CASE("bounding_box is the box extended point by point, bit for bit") {
    // bounding_box runs on SSE2's minps and maxps where it can, whose rules for NaN and for
    // equal values (0 == -0) must match nmesh::min and max: zeros of both signs, NaN and
    // infinities are mixed in, at every count from 0 to 40 (the last point is read apart).
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const float specials[] = {0.0f, -0.0f, nan, inf, -inf, 1.0f, -1.0f};
    std::mt19937 rng(21);
    std::uniform_int_distribution<int> pick(0, 9);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    const auto same_bits = [](float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    int compared = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const std::size_t n = std::size_t(trial % 41);
        std::vector<Vec3> points(n);
        for (Vec3& p : points)
            for (int a = 0; a < 3; ++a) {
                const int k = pick(rng);
                // Zero-heavy trials make zero the smallest or largest value on some axes.
                p[a] = k < 7 && trial % 3 != 0 ? specials[k] : (trial % 3 == 0 ? u(rng) : std::abs(u(rng)));
            }
        BoundingBox want;
        for (const Vec3& p : points) want.extend(p);
        const BoundingBox got = nmesh::bounding_box(points);
        for (int a = 0; a < 3; ++a) {
            INFO("trial " << trial << ", axis " << a);
            CHECK(same_bits(got.min[a], want.min[a]));
            CHECK(same_bits(got.max[a], want.max[a]));
            ++compared;
        }
    }
    CHECK(compared == 1200);
}

TEST_CASE("PointGrid over transformed points answers as over a transformed copy") {
    // reconstruct() builds the index over (p - center) * scale without copying the cloud: the
    // answers (indices and distances) must be those of an index over the transformed copy, and
    // of a brute force over that copy.
    std::mt19937 rng(9);
    std::vector<Vec3> points;
    for (int i = 0; i < 5000; ++i) points.push_back(random_unit_vector(rng) * 40.0f + Vec3{300.0f, -20.0f, 7.0f});
    PointTransform t;
    t.center = {300.0f, -20.0f, 7.0f};
    t.scale = 1.0f / 128.0f;
    std::vector<Vec3> copy;
    for (const Vec3& p : points) copy.push_back(t(p));
    const PointGrid on_the_fly(points, t), from_copy(copy);
    CHECK(on_the_fly.cell_size() == from_copy.cell_size());
    CHECK(on_the_fly.memory_bytes() == from_copy.memory_bytes());
    const std::vector<Vec3> queries = mixed_queries(copy, rng, 800);
    CHECK(count_mismatches(on_the_fly, copy, queries) == 0);
    CHECK(same_answers(on_the_fly, from_copy, queries));
    // A transform that overflows a coordinate is refused like a non-finite point.
    PointTransform huge;
    huge.scale = 1e38f;
    CHECK_THROWS_AS(PointGrid(points, huge), nmesh::InputError);
}

TEST_CASE("PointGrid with the transformed points' box given is the same index") {
    // reconstruct() hands the engine the normalised box as the transforms of the input box's
    // corners, not from a pass over the normalised points: each coordinate of (p - c) * s
    // is non-decreasing in p for s > 0, so both boxes are the same bits. Checked here on clouds
    // far from the origin, with scales that are and are not powers of two.
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int trial = 0; trial < 20; ++trial) {
        const Vec3 offset{u(rng) * 1e4f, u(rng) * 10.0f, u(rng) * 1e-3f};
        const float spread = std::ldexp(1.0f, trial % 7 - 3);
        std::vector<Vec3> points;
        for (int i = 0; i < 2000; ++i) points.push_back(offset + Vec3{u(rng), u(rng), u(rng)} * spread);
        const BoundingBox box = nmesh::bounding_box(points);
        PointTransform t;
        t.center = box.center();
        t.scale = trial % 2 == 0 ? std::ldexp(1.0f, -(trial % 5)) : 0.3f + 0.1f * float(trial);
        BoundingBox from_corners;
        from_corners.extend(t(box.min));
        from_corners.extend(t(box.max));
        BoundingBox from_points;
        for (const Vec3& p : points) from_points.extend(t(p));
        REQUIRE(from_corners.min == from_points.min);
        REQUIRE(from_corners.max == from_points.max);

        const PointGrid found(points, t), given(points, t, from_corners);
        CHECK(found.cell_size() == given.cell_size());
        CHECK(found.dimensions() == given.dimensions());
        CHECK(found.memory_bytes() == given.memory_bytes());
        std::vector<Vec3> copy;
        for (const Vec3& p : points) copy.push_back(t(p));
        const std::vector<Vec3> queries = mixed_queries(copy, rng, 100);
        CHECK(count_mismatches(given, copy, queries) == 0);
        CHECK(same_answers(found, given, queries));
    }
}

TEST_CASE("PointGrid rejects clouds it cannot index") {
    CHECK_THROWS_AS(PointGrid(std::vector<Vec3>{}), nmesh::InputError);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    CHECK_THROWS_AS(PointGrid(std::vector<Vec3>{{0, 0, 0}, {nan, 0, 0}}), nmesh::InputError);
    CHECK_THROWS_AS(PointGrid(std::vector<Vec3>{{0, 0, -inf}, {1, 1, 1}}), nmesh::InputError);
}
