// Tests of the quality metrics: geometric primitives on hand-computed cases, distances against
// brute force and closed forms, topology on small meshes whose answers are known, and the report's
// JSON form.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/metrics.h"
#include "nmesh/metrics/orientation.h"
#include "nmesh/reconstruct.h"
#include "cloud_fixtures.h"
#include "mesh_fixtures.h"

using nmesh::EvalOptions;
using nmesh::IndexedMesh;
using nmesh::QualityReport;
using nmesh::Vec3;
using nmesh::test::icosphere;

namespace {

using Triangle = std::array<std::uint32_t, 3>;

// ---- fixtures -----------------------------------------------------------------------------------

// Turns each triangle of a mesh that is star-shaped around `center` to face away from it.
void orient_outward(IndexedMesh& m, const Vec3& center) {
    for (Triangle& t : m.triangles) {
        const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
        if (nmesh::dot(nmesh::cross(b - a, c - a), (a + b + c) / 3.0f - center) < 0.0f) std::swap(t[1], t[2]);
    }
}

// A regular tetrahedron (edge 2 * sqrt(2)): the smallest closed surface; all angles 60 degrees.
IndexedMesh tetrahedron(const Vec3& offset = {0, 0, 0}) {
    IndexedMesh m;
    m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    for (Vec3& p : m.positions) p += offset;
    m.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    orient_outward(m, offset);
    return m;
}

// The unit cube [0, 1]^3 as 12 triangles: flat faces, so point-to-surface distances are simple.
IndexedMesh unit_cube() {
    IndexedMesh m;
    for (int i = 0; i < 8; ++i) m.positions.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
    m.triangles = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                   {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
    orient_outward(m, {0.5f, 0.5f, 0.5f});
    return m;
}

// A torus (major radius R, minor r) as a u-by-v grid of quads split in two: genus 1.
IndexedMesh torus(float R, float r, int nu, int nv, const Vec3& center = {0, 0, 0}) {
    IndexedMesh m;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const float u = 6.2831853f * float(i) / float(nu), v = 6.2831853f * float(j) / float(nv);
            m.positions.push_back(center + Vec3{(R + r * std::cos(v)) * std::cos(u),
                                                (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
        }
    const auto id = [&](int i, int j) { return std::uint32_t(((i + nu) % nu) * nv + (j + nv) % nv); };
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return m;
}

// Two meshes as one (the second's indices shifted).
IndexedMesh merged(const IndexedMesh& a, const IndexedMesh& b) {
    IndexedMesh m = a;
    const std::uint32_t shift = std::uint32_t(a.positions.size());
    m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
    for (Triangle t : b.triangles) m.triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
    return m;
}

QualityReport quick_evaluate(const IndexedMesh& mesh, const std::vector<Vec3>& points = {}) {
    EvalOptions o;
    o.surface_samples = 2000;
    return nmesh::evaluate(points.empty() ? mesh.positions : points, mesh, o);
}

// ---- references ---------------------------------------------------------------------------------

Vec3 centroid(const IndexedMesh& m, const Triangle& t) {
    return (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3.0f;
}

double brute_force_dm(const std::vector<Vec3>& points, const IndexedMesh& m) {
    double sum = 0.0;
    for (const Vec3& p : points) {
        float best = std::numeric_limits<float>::infinity();
        for (const Triangle& t : m.triangles) best = std::min(best, nmesh::squared_distance(p, centroid(m, t)));
        sum += std::sqrt(double(best));
    }
    return sum / double(points.size());
}

double brute_force_p2s(const Vec3& p, const IndexedMesh& m) {
    double best = std::numeric_limits<double>::infinity();
    for (const Triangle& t : m.triangles)
        best = std::min(
            best, nmesh::point_triangle_squared_distance(p, m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]));
    return std::sqrt(best);
}

bool intersect(const IndexedMesh& m, std::uint32_t s, std::uint32_t t) {
    const Triangle &u = m.triangles[s], &v = m.triangles[t];
    const auto& x = m.positions;
    return nmesh::triangles_intersect(x[u[0]], x[u[1]], x[u[2]], x[v[0]], x[v[1]], x[v[2]]);
}

// Self-intersections by testing every pair of triangles sharing no vertex.
std::size_t brute_force_self_intersections(const IndexedMesh& m) {
    std::size_t count = 0;
    for (std::uint32_t s = 0; s < m.triangles.size(); ++s)
        for (std::uint32_t t = s + 1; t < m.triangles.size(); ++t) {
            bool adjacent = false;
            for (std::uint32_t i : m.triangles[s])
                for (std::uint32_t j : m.triangles[t]) adjacent = adjacent || i == j;
            if (!adjacent && intersect(m, s, t)) ++count;
        }
    return count;
}

Vec3 random_unit_vector(std::mt19937& rng) {
    std::normal_distribution<float> g(0.0f, 1.0f);
    for (;;) {
        const Vec3 v{g(rng), g(rng), g(rng)};
        if (nmesh::norm(v) > 1e-3f) return nmesh::normalized(v);
    }
}

// The value of `key` in a flat JSON object, as text ("" when missing); fails if it appears twice.
std::string json_value(const std::string& json, const std::string& key) {
    const std::string quoted = "\"" + key + "\": ";
    const std::size_t at = json.find(quoted);
    if (at == std::string::npos) return "";
    CHECK(json.find(quoted, at + 1) == std::string::npos);
    const std::size_t start = at + quoted.size();
    return json.substr(start, json.find_first_of(",\n}", start) - start);
}

}  // namespace

// ---- primitives ---------------------------------------------------------------------------------

TEST_CASE("point_triangle_squared_distance in every Voronoi region of a triangle") {
    const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
    const auto d2 = [&](const Vec3& p) { return nmesh::point_triangle_squared_distance(p, a, b, c); };
    CHECK(d2({0.25f, 0.25f, 2}) == doctest::Approx(4.0));    // face (above)
    CHECK(d2({0.25f, 0.25f, -3}) == doctest::Approx(9.0));   // face (below)
    CHECK(d2({0.2f, 0.3f, 0}) == doctest::Approx(0.0));      // in the triangle
    CHECK(d2({-1, -2, 1}) == doctest::Approx(6.0));          // vertex a
    CHECK(d2({2, -1, 0}) == doctest::Approx(2.0));           // vertex b
    CHECK(d2({-1, 3, 0}) == doctest::Approx(5.0));           // vertex c
    CHECK(d2({0.5f, -2, 1}) == doctest::Approx(5.0));        // edge ab, foot (0.5, 0, 0)
    CHECK(d2({-3, 0.5f, 0}) == doctest::Approx(9.0));        // edge ca, foot (0, 0.5, 0)
    CHECK(d2({1, 1, 3}) == doctest::Approx(9.5));            // edge bc, foot (0.5, 0.5, 0)
    CHECK(d2({0.75f, 0.75f, 0}) == doctest::Approx(0.125));  // edge bc, in the plane
    // The answer does not depend on the order of the vertices.
    CHECK(nmesh::point_triangle_squared_distance({1, 1, 3}, c, a, b) == doctest::Approx(9.5));
    CHECK(nmesh::point_triangle_squared_distance({1, 1, 3}, b, a, c) == doctest::Approx(9.5));
}

TEST_CASE("point_triangle_squared_distance matches dense sampling of random triangles") {
    // The exact distance is a lower bound of the distance to any sample of the triangle, and the
    // samples come within the sampling step of it.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int trial = 0; trial < 200; ++trial) {
        const Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
        const Vec3 p = Vec3{u(rng), u(rng), u(rng)} * 2.0f;
        const double exact = std::sqrt(nmesh::point_triangle_squared_distance(p, a, b, c));
        double sampled = std::numeric_limits<double>::infinity();
        const int steps = 60;
        for (int i = 0; i <= steps; ++i)
            for (int j = 0; i + j <= steps; ++j) {
                const float s = float(i) / steps, t = float(j) / steps;
                sampled = std::min(sampled, double(nmesh::distance(p, a + (b - a) * s + (c - a) * t)));
            }
        const double step = (nmesh::distance(a, b) + nmesh::distance(a, c)) / steps;
        CHECK(exact <= sampled + 1e-6);
        CHECK(sampled <= exact + step);
    }
}

TEST_CASE("point_triangle_squared_distance on degenerate triangles") {
    // Collinear: the distance to the segment (0,0,0)-(2,0,0).
    const auto d2 = nmesh::point_triangle_squared_distance;
    CHECK(d2({1, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}) == doctest::Approx(1.0));
    CHECK(d2({3, 0, 1}, {0, 0, 0}, {2, 0, 0}, {1, 0, 0}) == doctest::Approx(2.0));
    // A point.
    CHECK(d2({1, 2, 2}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}) == doctest::Approx(9.0));
}

TEST_CASE("triangles_intersect on hand-built configurations") {
    const Vec3 a{0, 0, 0}, b{4, 0, 0}, c{0, 4, 0};  // in the plane z = 0
    const auto both_ways = [&](const Vec3& d, const Vec3& e, const Vec3& f) {
        const bool r = nmesh::triangles_intersect(a, b, c, d, e, f);
        CHECK(nmesh::triangles_intersect(d, e, f, a, b, c) == r);  // symmetric
        CHECK(nmesh::triangles_intersect(b, c, a, f, d, e) == r);  // vertex order does not matter
        CHECK(nmesh::triangles_intersect(a, c, b, d, f, e) == r);  // nor orientation
        return r;
    };
    CHECK(both_ways({1, 1, -1}, {1, 1, 1}, {2, 0.5f, 1}));          // pierces the interior
    CHECK_FALSE(both_ways({1, 1, 1}, {2, 1, 1}, {1, 2, 2}));        // above
    CHECK_FALSE(both_ways({3, 3, -1}, {3, 3, 1}, {5, 5, 0}));       // crosses the plane beside abc
    CHECK(both_ways({1, 1, 0}, {1, 1, 2}, {2, 1, 2}));              // a vertex on the interior
    CHECK(both_ways({2, -1, 0}, {2, 1, 0}, {2, 0, 3}));             // an edge lying across abc
    CHECK(both_ways({-1, 2, 1}, {1, 2, -1}, {-2, 2, 0}));           // an edge touching edge ca
    CHECK(both_ways({1, 1, 0}, {5, 1, 0}, {1, 5, 0}));              // coplanar, overlapping
    CHECK(both_ways({0.5f, 0.5f, 0}, {1, 0.5f, 0}, {0.5f, 1, 0}));  // coplanar, nested
    CHECK(both_ways({4, 0, 0}, {6, 0, 0}, {6, 2, 0}));              // coplanar, sharing a corner
    CHECK_FALSE(both_ways({3, 3, 0}, {6, 3, 0}, {3, 6, 0}));        // coplanar, apart
    CHECK_FALSE(both_ways({5, 0, 0}, {6, 0, 0}, {5, 1, 0}));        // coplanar, beside b
}

TEST_CASE("min_angle_deg") {
    const float h = std::sqrt(3.0f) / 2;
    CHECK(nmesh::min_angle_deg({0, 0, 0}, {1, 0, 0}, {0.5f, h, 0}) == doctest::Approx(60.0).epsilon(1e-5));
    CHECK(nmesh::min_angle_deg({0, 0, 0}, {1, 0, 0}, {0, 1, 0}) == doctest::Approx(45.0));
    CHECK(nmesh::min_angle_deg({0, 0, 0}, {1, 0, 0}, {1, 1, 0}) == doctest::Approx(45.0));
    const double thin = std::atan(0.1) * 180 / 3.14159265358979;
    CHECK(nmesh::min_angle_deg({0, 0, 0}, {10, 0, 0}, {0, 1, 0}) == doctest::Approx(thin));
    CHECK(nmesh::min_angle_deg({0, 0, 0}, {1, 0, 0}, {2, 0, 0}) == 0.0);  // collinear
    CHECK(nmesh::min_angle_deg({0, 0, 0}, {0, 0, 0}, {2, 0, 0}) == 0.0);  // repeated point
}

// ---- distances ----------------------------------------------------------------------------------

TEST_CASE("DM(X,T) matches a brute-force computation") {
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    const IndexedMesh sphere = icosphere(2);
    std::vector<Vec3> points;
    for (int i = 0; i < 1500; ++i) points.push_back({u(rng), u(rng), u(rng)});
    const double want = brute_force_dm(points, sphere);
    CHECK(nmesh::dm_cloud_to_centroids(points, sphere) == doctest::Approx(want).epsilon(1e-12));
    CHECK(quick_evaluate(sphere, points).dm_x_t == doctest::Approx(want).epsilon(1e-12));
    // One point per centroid: zero.
    std::vector<Vec3> at_centroids;
    for (const Triangle& t : sphere.triangles) at_centroids.push_back(centroid(sphere, t));
    CHECK(nmesh::dm_cloud_to_centroids(at_centroids, sphere) == 0.0);
}

TEST_CASE("point-to-surface distances match brute force and closed forms") {
    SUBCASE("unit cube, points at known distances") {
        // The centre is 0.5 from every face, (2, .5, .5) is 1 from the face x = 1, (2, 2, 2) is
        // sqrt(3) from the corner (1, 1, 1).
        const std::vector<Vec3> points = {{0.5f, 0.5f, 0.5f}, {2, 0.5f, 0.5f}, {2, 2, 2}};
        const QualityReport r = quick_evaluate(unit_cube(), points);
        CHECK(r.p2s_mean == doctest::Approx((0.5 + 1.0 + std::sqrt(3.0)) / 3.0));
        CHECK(r.p2s_rms == doctest::Approx(std::sqrt((0.25 + 1.0 + 3.0) / 3.0)));
        CHECK(r.p2s_max == doctest::Approx(std::sqrt(3.0)));
        const double diagonal = std::sqrt(3.0) * 1.5;  // the cloud's box is [0.5, 2]^3
        CHECK(r.bbox_diagonal == doctest::Approx(diagonal));
        CHECK(r.p2s_max_rel == doctest::Approx(std::sqrt(3.0) / diagonal));
    }
    SUBCASE("random points around a torus") {
        std::mt19937 rng(22);
        std::uniform_real_distribution<float> u(-2.0f, 2.0f);
        const IndexedMesh t = torus(1.0f, 0.4f, 24, 12);
        std::vector<Vec3> points;
        for (int i = 0; i < 400; ++i) points.push_back({u(rng), u(rng), u(rng) * 0.5f});
        double sum = 0, sq = 0, worst = 0;
        for (const Vec3& p : points) {
            const double d = brute_force_p2s(p, t);
            sum += d;
            sq += d * d;
            worst = std::max(worst, d);
        }
        const QualityReport r = quick_evaluate(t, points);
        // The same distances in the same order: the same sums, bit for bit.
        CHECK(r.p2s_mean == sum / 400);
        CHECK(r.p2s_rms == doctest::Approx(std::sqrt(sq / 400)).epsilon(1e-9));
        CHECK(r.p2s_max == worst);
    }
    SUBCASE("points near a finely tessellated torus (a deep hierarchy)") {
        std::mt19937 rng(24);
        std::uniform_real_distribution<float> u(-1.6f, 1.6f);
        const IndexedMesh t = torus(1.0f, 0.4f, 96, 48);  // 9,216 triangles
        std::vector<Vec3> points;
        for (int i = 0; i < 2000; ++i) points.push_back({u(rng), u(rng), u(rng) * 0.4f});
        double sum = 0, worst = 0;
        for (const Vec3& p : points) {
            const double d = brute_force_p2s(p, t);
            sum += d;
            worst = std::max(worst, d);
        }
        const QualityReport r = quick_evaluate(t, points);
        CHECK(r.p2s_mean == sum / 2000);
        CHECK(r.p2s_max == worst);
    }
    SUBCASE("points on a sphere are within the sagitta of its icosphere") {
        // Every unit-sphere point lies outside the inscribed polyhedron, within 1 - (the smallest
        // distance from the centre to a face plane) of it.
        const IndexedMesh s = icosphere(3);
        double sagitta = 0.0;
        for (const Triangle& t : s.triangles) {
            const Vec3 a = s.positions[t[0]], b = s.positions[t[1]], c = s.positions[t[2]];
            const Vec3 n = nmesh::normalized(nmesh::cross(b - a, c - a));
            sagitta = std::max(sagitta, 1.0 - double(nmesh::dot(n, a)));
        }
        std::mt19937 rng(23);
        std::vector<Vec3> points;
        for (int i = 0; i < 3000; ++i) points.push_back(random_unit_vector(rng));
        const QualityReport r = quick_evaluate(s, points);
        CHECK(r.p2s_max <= sagitta + 1e-6);
        CHECK(r.p2s_max >= 0.5 * sagitta);  // some points fall near face centres
        CHECK(r.p2s_mean > 0.0);
        CHECK(r.p2s_mean < sagitta);
        CHECK(r.euler == 2);
        CHECK(r.genus == 0);
    }
}

TEST_CASE("surface-to-cloud samples are uniform by area") {
    // The unit square split into four triangles of unequal areas around (0.8, 0.3), against a
    // single cloud point above the corner (0, 0): the mean distance is the integral of
    // sqrt(x^2 + y^2 + 1) over the square, and the largest is sqrt(3), at the far corner.
    IndexedMesh square;
    square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.8f, 0.3f, 0}};
    square.triangles = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    const std::vector<Vec3> cloud = {{0, 0, 1}};
    double integral = 0.0;
    const int steps = 400;
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            const double x = (i + 0.5) / steps, y = (j + 0.5) / steps;
            integral += std::sqrt(x * x + y * y + 1.0);
        }
    integral /= steps * steps;

    const QualityReport r = nmesh::evaluate(cloud, square);  // default options: 200,000 samples
    CHECK(r.s2p_mean == doctest::Approx(integral).epsilon(0.002));
    // The largest is found exactly (to 1e-5 of the mesh's diagonal, the cloud having none).
    CHECK(r.s2p_max <= std::sqrt(3.0) + 1e-6);
    CHECK(r.s2p_max >= std::sqrt(3.0) - 1e-5 * std::sqrt(2.0));
    CHECK(r.p2s_max == doctest::Approx(1.0));
    CHECK(r.hausdorff == r.s2p_max);
    CHECK(std::isnan(r.hausdorff_rel));  // a single point has no extent
    CHECK_FALSE(r.closed);

    // The same seed gives the same samples; another seed, other samples.
    CHECK(nmesh::evaluate(cloud, square).s2p_mean == r.s2p_mean);
    EvalOptions other;
    other.seed = 2;
    const double m2 = nmesh::evaluate(cloud, square, other).s2p_mean;
    CHECK(m2 != r.s2p_mean);
    CHECK(m2 == doctest::Approx(integral).epsilon(0.002));
}

TEST_CASE("the surface-to-cloud figures depend on the surface, not on how its triangles are listed") {
    // A sphere of 1,280 triangles against a cloud off its surface, listed three more ways: the
    // triangles shuffled, each started at another corner, and the vertices renumbered. The
    // samples are the same, so the figures are the same bits.
    const IndexedMesh sphere = icosphere(3);
    std::mt19937 rng(7);
    std::vector<Vec3> cloud;
    for (int i = 0; i < 300; ++i) cloud.push_back(random_unit_vector(rng) * 1.05f);
    const QualityReport ref = quick_evaluate(sphere, cloud);

    IndexedMesh shuffled = sphere;
    std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), rng);
    IndexedMesh rotated = sphere;
    for (std::size_t f = 0; f < rotated.triangles.size(); ++f) {
        Triangle& t = rotated.triangles[f];
        std::rotate(t.begin(), t.begin() + long(f % 3), t.end());
    }
    IndexedMesh renumbered = sphere;
    std::vector<std::uint32_t> slot(sphere.positions.size());
    std::iota(slot.begin(), slot.end(), 0u);
    std::shuffle(slot.begin(), slot.end(), rng);
    for (std::size_t v = 0; v < slot.size(); ++v) renumbered.positions[slot[v]] = sphere.positions[v];
    for (Triangle& t : renumbered.triangles)
        for (std::uint32_t& v : t) v = slot[v];
    for (const IndexedMesh* m : {&shuffled, &rotated, &renumbered}) {
        REQUIRE(m->triangles != sphere.triangles);
        const QualityReport r = quick_evaluate(*m, cloud);
        CHECK(r.s2p_mean == ref.s2p_mean);
        CHECK(r.s2p_max == ref.s2p_max);
        CHECK(r.hausdorff == ref.hausdorff);
        CHECK(r.p2s_mean == doctest::Approx(ref.p2s_mean).epsilon(1e-6));
    }
    // What is measured is still the surface: the samples stay within the sphere's distance range.
    CHECK(ref.s2p_max <= 2.05);
    CHECK(ref.s2p_mean > 0.05);
}

TEST_CASE("the surface-to-cloud maximum is exact where samples miss it") {
    // The right triangle (0,0,0), (1,0,0), (0,1,0) against a cloud of its three corners: the
    // distance to the nearest corner peaks at the circumcentre (0.5, 0.5, 0), on the hypotenuse,
    // at sqrt(0.5). A handful of samples lands nowhere near it; the search still finds it.
    IndexedMesh tri;
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.triangles = {{0, 1, 2}};
    EvalOptions few;
    few.surface_samples = 3;
    const QualityReport r = nmesh::evaluate(tri.positions, tri, few);
    const double tol = 1e-5 * std::sqrt(2.0);
    CHECK(r.s2p_max <= std::sqrt(0.5) + 1e-6);
    CHECK(r.s2p_max >= std::sqrt(0.5) - tol);
    CHECK(r.hausdorff == r.s2p_max);

    // Against brute force: a sphere of 80 triangles and 200 points scattered around it. The
    // reference is the largest distance, over a dense barycentric grid on every triangle, to the
    // nearest point by a full scan; the exact search may only find more, by less than the grid's
    // spacing (the distance is 1-Lipschitz), and never more than the truth, which lies within
    // the tolerance above the reference's bound.
    const IndexedMesh sphere = icosphere(1);
    std::mt19937 rng(5);
    std::vector<Vec3> cloud;
    std::uniform_real_distribution<float> radius(0.8f, 1.3f);
    for (int i = 0; i < 200; ++i) cloud.push_back(random_unit_vector(rng) * radius(rng));
    const int steps = 60;
    double reference = 0.0, longest_edge = 0.0;
    for (const Triangle& t : sphere.triangles) {
        const Vec3 a = sphere.positions[t[0]], b = sphere.positions[t[1]], c = sphere.positions[t[2]];
        longest_edge = std::max({longest_edge, double(norm(b - a)), double(norm(c - b)), double(norm(a - c))});
        for (int i = 0; i <= steps; ++i)
            for (int j = 0; i + j <= steps; ++j) {
                const float u = float(i) / steps, v = float(j) / steps;
                const Vec3 x = a + (b - a) * u + (c - a) * v;
                double nearest = std::numeric_limits<double>::max();
                for (const Vec3& p : cloud) nearest = std::min(nearest, double(norm(x - p)));
                reference = std::max(reference, nearest);
            }
    }
    const QualityReport s = quick_evaluate(sphere, cloud);
    CHECK(s.s2p_max >= reference - 1e-6);
    CHECK(s.s2p_max <= reference + longest_edge / steps);
    INFO("exact " << s.s2p_max << ", dense grid " << reference);
}

TEST_CASE("vertex_distances_to_cloud matches brute force") {
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    std::vector<Vec3> cloud;
    for (int i = 0; i < 500; ++i) cloud.push_back({u(rng), u(rng), u(rng)});
    const IndexedMesh mesh = icosphere(2);
    const std::vector<float> d = nmesh::vertex_distances_to_cloud(cloud, mesh);
    REQUIRE(d.size() == mesh.positions.size());
    for (std::size_t v = 0; v < d.size(); ++v) {
        float best = std::numeric_limits<float>::infinity();
        for (const Vec3& p : cloud) best = std::min(best, nmesh::squared_distance(mesh.positions[v], p));
        CHECK(d[v] == std::sqrt(best));
    }
}

// ---- topology -----------------------------------------------------------------------------------

TEST_CASE("topology of closed surfaces") {
    SUBCASE("regular tetrahedron") {
        const QualityReport r = quick_evaluate(tetrahedron());
        CHECK(r.closed);
        CHECK(r.manifold);
        CHECK(r.euler == 2);
        CHECK(r.genus == 0);
        CHECK(r.components == 1);
        CHECK(r.self_intersections == 0);
        CHECK(r.degenerate_triangles == 0);
        CHECK(r.min_angle_min_deg == doctest::Approx(60.0));
        CHECK(r.min_angle_mean_deg == doctest::Approx(60.0));
        CHECK(r.share_under_10deg == 0.0);
        CHECK(r.p2s_max == 0.0);  // the cloud is the vertices
        CHECK(r.vertices == 4);
        CHECK(r.faces == 4);
    }
    SUBCASE("unit cube") {
        const QualityReport r = quick_evaluate(unit_cube());
        CHECK(r.closed);
        CHECK(r.manifold);
        CHECK(r.euler == 2);
        CHECK(r.genus == 0);
        CHECK(r.self_intersections == 0);
        CHECK(r.min_angle_min_deg == doctest::Approx(45.0));
    }
    SUBCASE("icosphere") {
        const QualityReport r = quick_evaluate(icosphere(3));
        CHECK(r.faces == 1280);
        CHECK(r.closed);
        CHECK(r.manifold);
        CHECK(r.euler == 2);
        CHECK(r.genus == 0);
        CHECK(r.self_intersections == 0);
        CHECK(r.min_angle_min_deg > 50.0);
    }
    SUBCASE("torus") {
        const QualityReport r = quick_evaluate(torus(1.0f, 0.3f, 32, 12));
        CHECK(r.closed);
        CHECK(r.manifold);
        CHECK(r.euler == 0);
        CHECK(r.genus == 1);
        CHECK(r.components == 1);
        CHECK(r.self_intersections == 0);
    }
    SUBCASE("genus adds up over components") {
        // A torus and a sphere: chi = 0 + 2, so (2 - chi) / 2 over the whole would say 0.
        const QualityReport r = quick_evaluate(merged(torus(1.0f, 0.3f, 16, 8), icosphere(1, {5, 0, 0})));
        CHECK(r.components == 2);
        CHECK(r.euler == 2);
        CHECK(r.genus == 1);
        const IndexedMesh tori = merged(torus(1.0f, 0.3f, 16, 8), torus(1.0f, 0.3f, 16, 8, {4, 0, 0}));
        CHECK(quick_evaluate(tori).genus == 2);
    }
    SUBCASE("two disjoint tetrahedra") {
        const QualityReport r = quick_evaluate(merged(tetrahedron(), tetrahedron({10, 0, 0})));
        CHECK(r.closed);
        CHECK(r.manifold);
        CHECK(r.components == 2);
        CHECK(r.euler == 4);
        CHECK(r.genus == 0);
        CHECK(r.self_intersections == 0);
    }
}

TEST_CASE("topology of defective meshes") {
    SUBCASE("open: a tetrahedron without one face") {
        IndexedMesh m = tetrahedron();
        m.triangles.pop_back();
        const QualityReport r = quick_evaluate(m);
        CHECK_FALSE(r.closed);
        CHECK(r.manifold);  // a disc: open fans are fine
        CHECK(r.euler == 1);
        CHECK(r.genus == -1);
        CHECK(r.isolated_vertices == 0);
    }
    SUBCASE("three triangles on one edge") {
        IndexedMesh m;
        m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
        m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
        const QualityReport r = quick_evaluate(m);
        CHECK_FALSE(r.closed);
        CHECK_FALSE(r.manifold);
        CHECK(r.components == 1);
        CHECK(r.euler == 5 - 7 + 3);
    }
    SUBCASE("one face turned inside out") {
        IndexedMesh m = tetrahedron();
        std::swap(m.triangles[0][1], m.triangles[0][2]);
        const QualityReport r = quick_evaluate(m);
        CHECK(r.closed);
        CHECK_FALSE(r.manifold);
        CHECK(r.genus == -1);
    }
    SUBCASE("two tetrahedra sharing a vertex (two fans at it)") {
        // The second tetrahedron's vertex 3 (index 7) lands on the first's vertex 0, at (1, 1, 1);
        // welding them there leaves the two tetrahedra touching at one vertex with two fans.
        IndexedMesh m = merged(tetrahedron(), tetrahedron({2, 2, 0}));
        REQUIRE(m.positions[7] == m.positions[0]);
        for (Triangle& t : m.triangles)
            for (std::uint32_t& v : t)
                if (v == 7) v = 0;
        const QualityReport r = quick_evaluate(m);
        CHECK(r.closed);  // every edge still has two triangles
        CHECK_FALSE(r.manifold);
        CHECK(r.components == 1);
        CHECK(r.isolated_vertices == 1);
        CHECK(r.euler == 7 - 12 + 8);
    }
    SUBCASE("degenerate triangles") {
        IndexedMesh m = unit_cube();
        m.positions.push_back({2, 0, 0});
        m.triangles.push_back({0, 1, 8});  // collinear: (0,0,0), (1,0,0), (2,0,0)
        m.triangles.push_back({3, 3, 5});  // a repeated vertex
        const QualityReport r = quick_evaluate(m);
        CHECK(r.degenerate_triangles == 2);
        CHECK_FALSE(r.manifold);
        CHECK(r.min_angle_min_deg == 0.0);
        CHECK(r.share_under_10deg == doctest::Approx(2.0 / 14.0));
    }
}

TEST_CASE("self-intersections") {
    SUBCASE("one known crossing pair") {
        IndexedMesh m;
        m.positions = {{0, 0, 0},    {4, 0, 0},    {0, 4, 0},      // in the plane z = 0
                       {1, 1, -1},   {1, 1, 1},    {2, 0.5f, 1},   // pierces the first
                       {10, 10, 10}, {11, 10, 10}, {10, 11, 10}};  // far away
        m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
        CHECK(quick_evaluate(m).self_intersections == 1);
        m.positions[3].z = 0.5f;  // lift the second above the first
        CHECK(quick_evaluate(m).self_intersections == 0);
    }
    SUBCASE("triangles sharing a vertex count when they meet anywhere else") {
        IndexedMesh m;
        m.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, -1}, {1, 1, 1}};
        m.triangles = {{0, 1, 2}, {0, 3, 4}};  // the second passes through the first's interior
        CHECK(quick_evaluate(m).self_intersections == 1);
        m.positions[3] = {1, 1, 0.5f};  // now it leaves the shared vertex above the first
        CHECK(quick_evaluate(m).self_intersections == 0);
    }
    SUBCASE("triangles sharing an edge count when folded flat onto each other") {
        IndexedMesh m;
        m.positions = {{0, 0, 0}, {4, 0, 0}, {1, 3, 0}, {2, 2, 0}};
        m.triangles = {{0, 1, 2}, {1, 0, 3}};  // both opposite vertices on one side of the edge
        CHECK(quick_evaluate(m).self_intersections == 1);
        m.positions[3] = {2, -2, 0};  // a flat pair, one on each side: no overlap
        CHECK(quick_evaluate(m).self_intersections == 0);
        m.positions[3] = {2, 2, 1};  // bent along the edge: they meet only on it
        CHECK(quick_evaluate(m).self_intersections == 0);
    }
    SUBCASE("two overlapping spheres: as many as brute force finds") {
        const IndexedMesh m = merged(icosphere(2), icosphere(2, {0.7f, 0.2f, 0.1f}));
        const std::size_t want = brute_force_self_intersections(m);
        CHECK(want > 20);
        CHECK(quick_evaluate(m).self_intersections == want);
    }
}

// ---- the report ---------------------------------------------------------------------------------

TEST_CASE("write_json writes every key once, with the report's values") {
    IndexedMesh m = tetrahedron();
    m.triangles.pop_back();  // open, so genus is null
    const QualityReport r = quick_evaluate(m, {{0, 0, 0}, {1, 1, 1}, {3, 0, 0}});
    std::ostringstream out;
    nmesh::write_json(out, r);
    const std::string json = out.str();
    CHECK(json.front() == '{');
    CHECK(json.back() == '}');
    const std::pair<const char*, double> numbers[] = {{"dm_x_t", r.dm_x_t},
                                                      {"dm_x_t_rel", r.dm_x_t_rel},
                                                      {"p2s_mean", r.p2s_mean},
                                                      {"p2s_mean_rel", r.p2s_mean_rel},
                                                      {"p2s_rms", r.p2s_rms},
                                                      {"p2s_rms_rel", r.p2s_rms_rel},
                                                      {"p2s_max", r.p2s_max},
                                                      {"p2s_max_rel", r.p2s_max_rel},
                                                      {"s2p_mean", r.s2p_mean},
                                                      {"s2p_mean_rel", r.s2p_mean_rel},
                                                      {"s2p_max", r.s2p_max},
                                                      {"s2p_max_rel", r.s2p_max_rel},
                                                      {"hausdorff", r.hausdorff},
                                                      {"hausdorff_rel", r.hausdorff_rel},
                                                      {"euler", double(r.euler)},
                                                      {"components", double(r.components)},
                                                      {"self_intersections", double(r.self_intersections)},
                                                      {"min_angle_min_deg", r.min_angle_min_deg},
                                                      {"min_angle_mean_deg", r.min_angle_mean_deg},
                                                      {"share_under_10deg", r.share_under_10deg},
                                                      {"vertices", 4.0},
                                                      {"faces", 3.0},
                                                      {"bbox_diagonal", r.bbox_diagonal},
                                                      {"degenerate_triangles", 0.0},
                                                      {"isolated_vertices", 0.0}};
    for (const auto& [key, value] : numbers) {
        CAPTURE(key);
        const std::string text = json_value(json, key);
        REQUIRE_FALSE(text.empty());
        CHECK(std::strtod(text.c_str(), nullptr) == doctest::Approx(value).epsilon(1e-9));
    }
    CHECK(json_value(json, "closed") == "false");
    CHECK(json_value(json, "manifold") == "true");
    CHECK(json_value(json, "genus") == "null");
    CHECK(r.p2s_max > 0.0);

    std::ostringstream out_text;
    nmesh::write_text(out_text, r);
    const std::string text = out_text.str();
    CHECK(text.find("genus:") != std::string::npos);
    CHECK(std::count(text.begin(), text.end(), '\n') == 30);
}

TEST_CASE("orientation: the signed volume and the faces that point inward") {
    const IndexedMesh sphere = icosphere(3);
    const QualityReport out = quick_evaluate(sphere);
    // The icosphere's volume approaches 4/3 pi from below; it faces outward everywhere.
    CHECK(out.signed_volume > 0.95 * 4.18879);
    CHECK(out.signed_volume < 4.18879);
    CHECK(out.inward_faces == 0);

    IndexedMesh inverted = sphere;  // every triangle reversed: inside out as a whole
    for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
    const QualityReport in = quick_evaluate(inverted);
    CHECK(in.signed_volume == doctest::Approx(-out.signed_volume));
    CHECK(in.inward_faces == inverted.triangles.size());

    // Half of the sphere reversed in place: a mesh whose halves face opposite ways, as a twisted
    // learning leaves it. The reversed half points inward; the other half still outward.
    IndexedMesh half = sphere;
    std::size_t reversed = 0;
    for (auto& t : half.triangles) {
        const Vec3 c = (half.positions[t[0]] + half.positions[t[1]] + half.positions[t[2]]) * (1.0f / 3.0f);
        if (c.z > 0.0f) {
            std::swap(t[1], t[2]);
            ++reversed;
        }
    }
    const QualityReport h = quick_evaluate(half);
    CHECK(reversed > 0);
    CHECK(h.inward_faces > 0);
    CHECK(h.inward_faces <= reversed);
    CHECK(h.inward_faces >= reversed * 9 / 10);
    CHECK(std::abs(h.signed_volume) < 0.5 * out.signed_volume);
}

TEST_CASE("orient_outward reverses an inside-out closed mesh and leaves an outward one alone") {
    IndexedMesh m = icosphere(2);
    const IndexedMesh outward = m;
    CHECK_FALSE(nmesh::metrics_detail::orient_outward(m));
    CHECK(m.triangles == outward.triangles);
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    CHECK(nmesh::metrics_detail::orient_outward(m));
    CHECK(m.triangles == outward.triangles);
    CHECK(quick_evaluate(m).signed_volume > 0.0);
}

TEST_CASE("reconstruct() faces every output outward and records its check") {
    nmesh::Parameters p;
    p.target_vertices = 400;
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        p.seed = seed;
        const nmesh::Result r = nmesh::reconstruct(nmesh::test::sphere_cloud(4000, 1.0f, {0.3f, 0.1f, -0.2f}, seed), p);
        const QualityReport q = quick_evaluate(r.mesh);
        CHECK(q.signed_volume > 0.0);
        CHECK(r.stats.crossing_pairs == q.self_intersections);
        CHECK(r.stats.inward_faces == q.inward_faces);
    }
}

TEST_CASE("evaluate rejects inputs it cannot measure") {
    const IndexedMesh m = tetrahedron();
    CHECK_THROWS_AS(nmesh::evaluate({}, m), nmesh::InputError);
    CHECK_THROWS_AS(nmesh::evaluate(std::vector<Vec3>{{0, 0, 0}}, IndexedMesh{m.positions, {}}), nmesh::InputError);
    IndexedMesh bad = m;
    bad.triangles[2][1] = 4;
    CHECK_THROWS_AS(nmesh::evaluate(m.positions, bad), nmesh::InputError);
    CHECK_THROWS_AS(nmesh::dm_cloud_to_centroids(m.positions, bad), nmesh::InputError);
    CHECK_THROWS_AS(nmesh::evaluate(std::vector<Vec3>{{0, std::numeric_limits<float>::quiet_NaN(), 0}}, m),
                    nmesh::InputError);
    EvalOptions none;
    none.surface_samples = 0;
    CHECK_THROWS_AS(nmesh::evaluate(m.positions, m, none), nmesh::ParameterError);
}

TEST_CASE("a learnt bunny opened round three vertices, against its own vertices") {
    // The mesh of the bundled bunny at 3,000 vertices, without the faces round three vertices far
    // apart: those three vertices are left unused and each removed fan leaves a hole bounded by
    // the vertex's link, so the mesh is a sphere with 3 holes (Euler characteristic 2 - 3). The
    // cloud is the mesh's own positions: every used vertex is at distance 0, the unused ones lie
    // within one ring's size of the surface.
    nmesh::Parameters params;
    params.target_vertices = 3000;
    params.finish = false;
    IndexedMesh mesh = nmesh::reconstruct(nmesh::test::bundled_bunny(), params).mesh;
    const std::vector<Vec3> points = mesh.positions;
    std::vector<std::uint32_t> removed;
    std::vector<bool> near_removed(mesh.positions.size(), false);
    for (std::uint32_t v = 0; v < mesh.positions.size() && removed.size() < 3; v += 997) {
        if (near_removed[v]) continue;
        removed.push_back(v);
        for (const Triangle& t : mesh.triangles)  // the removed vertex's ring and the next ring out
            if (t[0] == v || t[1] == v || t[2] == v)
                for (std::uint32_t u : t)
                    for (const Triangle& s : mesh.triangles)
                        if (s[0] == u || s[1] == u || s[2] == u)
                            near_removed[s[0]] = near_removed[s[1]] = near_removed[s[2]] = true;
    }
    REQUIRE(removed.size() == 3);
    float ring = 0.0f;  // the largest distance from a removed vertex to its neighbours
    mesh.triangles.erase(
        std::remove_if(mesh.triangles.begin(), mesh.triangles.end(),
                       [&](const Triangle& t) {
                           for (std::uint32_t v : removed)
                               for (int k = 0; k < 3; ++k)
                                   if (t[k] == v) {
                                       ring = std::max(
                                           {ring, nmesh::distance(mesh.positions[v], mesh.positions[t[(k + 1) % 3]]),
                                            nmesh::distance(mesh.positions[v], mesh.positions[t[(k + 2) % 3]])});
                                       return true;
                                   }
                           return false;
                       }),
        mesh.triangles.end());
    EvalOptions o;
    o.surface_samples = 50000;
    const QualityReport r = nmesh::evaluate(points, mesh, o);
    std::ostringstream json;
    nmesh::write_json(json, r);
    MESSAGE(json.str());

    CHECK(r.isolated_vertices == 3);
    CHECK(r.p2s_max > 0.0);
    CHECK(r.p2s_max <= ring);
    CHECK(r.p2s_mean <= r.p2s_max * 3.0 / double(points.size()));
    CHECK_FALSE(r.closed);
    CHECK(r.manifold);
    CHECK(r.genus == -1);
    CHECK(r.components == 1);
    CHECK(r.euler == 2 - 3);
    // The mesh's vertices are the cloud: the DM is the mean distance from a vertex to the
    // centroid of its nearest triangle, a fraction of the edge length.
    CHECK(r.dm_x_t > 0.0);
    CHECK(r.dm_x_t < ring);
    CHECK(r.s2p_max < ring);
}

TEST_CASE("evaluate reports the share of the cloud measured, and the same figures with or without it") {
    // 300,000 points: one report at 2^18 points, one at the end.
    const std::vector<Vec3> points = nmesh::test::sphere_cloud(300000, 1.01f).points;
    const IndexedMesh mesh = icosphere(2);
    EvalOptions quiet;
    quiet.surface_samples = 20000;
    EvalOptions reported = quiet;
    std::vector<double> fractions;
    reported.progress = [&](double f) { fractions.push_back(f); };
    const QualityReport a = nmesh::evaluate(points, mesh, quiet), b = nmesh::evaluate(points, mesh, reported);
    CHECK(fractions == std::vector<double>{262144.0 / 300000.0, 1.0});
    CHECK(a.dm_x_t == b.dm_x_t);
    CHECK(a.p2s_mean == b.p2s_mean);
    CHECK(a.p2s_max == b.p2s_max);
    CHECK(a.s2p_mean == b.s2p_mean);
    CHECK(a.hausdorff == b.hausdorff);
}
