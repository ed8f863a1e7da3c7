// Tests of the cloud's stratified sample (nmesh/cloud_sample.h) and of the nearest-point index that
// reconstruct() builds over it (Parameters::index_points_per_vertex).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "nmesh/spatial/cloud_sample.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/spatial/point_transform.h"
#include "nmesh/reconstruct.h"
#include "cloud_fixtures.h"
#include "engine_checks.h"

using nmesh::BoundingBox;
using nmesh::Parameters;
using nmesh::PointCloud;
using nmesh::PointTransform;
using nmesh::Vec3;
using nmesh::test::sphere_cloud;

namespace {

// Points whose x coordinate is their index (exact in float below 2^24).
std::vector<Vec3> numbered(std::size_t n) {
    std::vector<Vec3> points(n);
    for (std::size_t i = 0; i < n; ++i) points[i] = {float(i), float(i % 7), 1.0f};
    return points;
}

std::vector<std::size_t> indices_of(const std::vector<Vec3>& sample) {
    std::vector<std::size_t> idx;
    for (const Vec3& p : sample) idx.push_back(std::size_t(p.x));
    return idx;
}

}  // namespace

TEST_CASE("a stratified sample takes one point from each run of consecutive indices, in order") {
    const std::vector<Vec3> points = numbered(1000);
    for (const std::size_t count : {std::size_t(1), std::size_t(7), std::size_t(300), std::size_t(999)}) {
        CAPTURE(count);
        const std::vector<std::size_t> idx = indices_of(nmesh::stratified_sample(points, count, 11));
        REQUIRE(idx.size() == count);
        for (std::size_t j = 0; j < count; ++j) {
            const std::size_t lo = j * 1000 / count, hi = (j + 1) * 1000 / count;
            CHECK(idx[j] >= lo);
            CHECK(idx[j] < hi);
            CHECK(points[idx[j]] == nmesh::stratified_sample(points, count, 11)[j]);
        }
    }
    // The whole cloud when every run is one point long.
    CHECK(nmesh::stratified_sample(points, 1000, 3) == points);
    // The same seed, the same sample; another seed, another one.
    CHECK(nmesh::stratified_sample(points, 100, 5) == nmesh::stratified_sample(points, 100, 5));
    CHECK(nmesh::stratified_sample(points, 100, 5) != nmesh::stratified_sample(points, 100, 6));
}

TEST_CASE("each point of a run is drawn equally often") {
    // One run of 10 points, 20,000 seeds: each point expected 2,000 times (standard deviation
    // 42); a draw that could not reach the run's last point, or reached past it, fails.
    const std::vector<Vec3> points = numbered(10);
    std::map<std::size_t, int> seen;
    for (std::uint64_t seed = 0; seed < 20000; ++seed) ++seen[indices_of(nmesh::stratified_sample(points, 1, seed))[0]];
    REQUIRE(seen.size() == 10);
    for (const auto& [i, k] : seen) {
        CAPTURE(i);
        CHECK(i < 10);
        CHECK(k > 1800);
        CHECK(k < 2200);
    }
}

TEST_CASE("the index holds the whole cloud up to the budget of points per vertex, a sample beyond") {
    Parameters p;
    p.target_vertices = 100;
    p.index_points_per_vertex = 64;
    CHECK(nmesh::index_point_count(5000, p) == 5000);
    CHECK(nmesh::index_point_count(6400, p) == 6400);
    CHECK(nmesh::index_point_count(6401, p) == 6400);
    CHECK(nmesh::index_point_count(100000000, p) == 6400);
    p.index_points_per_vertex = 0;  // every point
    CHECK(nmesh::index_point_count(100000000, p) == 100000000);
    p.index_points_per_vertex = 0xffffffffu;  // no overflow of the budget
    p.target_vertices = 0xffffffffu;
    CHECK(nmesh::index_point_count(100000000, p) == 100000000);

    const PointCloud cloud = sphere_cloud(5000, 2.0f, {1.0f, 2.0f, 3.0f}, 9);
    PointTransform t;
    t.center = {1.0f, 2.0f, 3.0f};
    t.scale = 0.25f;
    std::vector<Vec3> transformed;
    for (const Vec3& q : cloud.points) transformed.push_back(t(q));
    const BoundingBox box = nmesh::bounding_box(transformed);

    p = Parameters{};
    p.target_vertices = 100;  // 6,400 points allowed: the whole cloud, in its order
    CHECK(nmesh::index_cloud(cloud.points, t, box, p)->indexed_points() == transformed);

    p.index_points_per_vertex = 8;  // 800 of the 5,000
    const auto index = nmesh::index_cloud(cloud.points, t, box, p);
    const std::vector<Vec3> sample = index->indexed_points();
    REQUIRE(sample.size() == 800);
    // Each indexed point is a transformed cloud point from its own run of the cloud's indices.
    for (std::size_t j = 0; j < sample.size(); ++j) {
        const std::size_t lo = j * 5000 / 800, hi = (j + 1) * 5000 / 800;
        CHECK(std::find(transformed.begin() + long(lo), transformed.begin() + long(hi), sample[j]) !=
              transformed.begin() + long(hi));
    }
    // The queries answer for the sample, as a brute-force scan of it does.
    for (const Vec3& q : {Vec3{0.1f, 0.2f, 0.3f}, Vec3{-0.4f, 0.0f, 0.1f}, Vec3{2.0f, 2.0f, 2.0f}}) {
        float best = INFINITY;
        for (const Vec3& s : sample) best = std::min(best, nmesh::squared_distance(q, s));
        CHECK(index->nearest_squared_distance(q) == best);
    }
    // Seeded by Parameters::seed.
    CHECK(nmesh::index_cloud(cloud.points, t, box, p)->indexed_points() == sample);
    p.seed = 2;
    CHECK(nmesh::index_cloud(cloud.points, t, box, p)->indexed_points() != sample);
}

TEST_CASE("reconstruct() indexes a sample of a cloud much denser than the mesh, and still closes it") {
    const PointCloud cloud = sphere_cloud(20000, 1.0f, {}, 31);
    Parameters p;
    p.target_vertices = 300;
    p.index_points_per_vertex = 16;  // 4,800 of the 20,000 points
    struct Case {
        bool edge_swap, finish;
        nmesh::Topology topology;
        std::uint64_t indexed;  // the handle search (topology closed) needs the index too
    };
    for (const Case c : {Case{true, true, nmesh::Topology::closed, 4800}, Case{true, false, nmesh::Topology::closed, 4800},
                         Case{false, true, nmesh::Topology::closed, 4800}, Case{false, false, nmesh::Topology::closed, 4800},
                         Case{false, false, nmesh::Topology::sphere, 0}}) {
        CAPTURE(c.edge_swap);
        CAPTURE(c.finish);
        CAPTURE(nmesh::topology_name(c.topology));
        p.edge_swap = c.edge_swap;
        p.finish = c.finish;
        p.topology = c.topology;
        const nmesh::Result r = nmesh::reconstruct(cloud, p);
        CHECK(r.stats.indexed_points == c.indexed);
        CHECK((r.stats.index_bytes > 0) == (c.indexed > 0));
        CHECK(r.stats.finished == c.finish);
        nmesh::test::require_closed_manifold(r.mesh);
        REQUIRE(r.mesh.positions.size() == 300);
        // On the sphere: every vertex near it (a vertex of a mesh this coarse, left as the
        // learning places it, may lie a few hundredths inside), and most on it.
        float worst = 0.0f, sum = 0.0f;
        for (const Vec3& v : r.mesh.positions) {
            worst = std::max(worst, std::fabs(nmesh::norm(v) - 1.0f));
            sum += std::fabs(nmesh::norm(v) - 1.0f);
        }
        CHECK(worst < (c.finish ? 0.03f : 0.08f));
        CHECK(sum / 300.0f < 0.01f);
    }
    p.edge_swap = true;
    p.finish = true;
    p.index_points_per_vertex = 0;  // every point
    CHECK(nmesh::reconstruct(cloud, p).stats.indexed_points == 20000);
}
