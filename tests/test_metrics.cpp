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
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/metrics.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/reconstruct.h"
#include "cloud_fixtures.h"
#include "error_fixtures.h"
#include "mesh_fixtures.h"

using nmesh::EvalOptions;
using nmesh::IndexedMesh;
using nmesh::MeshTopology;
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

// A band of quads split in two round the z axis: ring j, of `around` vertices, at radius
// radii[j] and height heights[j]. Rings of one radius at several heights make a tube open at both
// ends, two rings of different radii in one plane a flat annulus: either way genus 0 with two
// boundary loops, each a regular polygon.
IndexedMesh ring_strip(int around, const std::vector<float>& radii, const std::vector<float>& heights) {
    IndexedMesh m;
    for (std::size_t j = 0; j < radii.size(); ++j)
        for (int i = 0; i < around; ++i) {
            const float u = 6.2831853f * float(i) / float(around);
            m.positions.push_back({radii[j] * std::cos(u), radii[j] * std::sin(u), heights[j]});
        }
    const auto id = [&](int i, std::size_t j) {
        return std::uint32_t(j * std::size_t(around) + std::size_t(i % around));
    };
    for (std::size_t j = 0; j + 1 < radii.size(); ++j)
        for (int i = 0; i < around; ++i) {
            m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return m;
}

// The perimeter of a regular polygon of `sides` sides inscribed in a circle of radius r.
double polygon_perimeter(int sides, double r) { return 2.0 * sides * r * std::sin(3.14159265358979323846 / sides); }

// The length of the edge from a to b, in double.
double edge_length(const IndexedMesh& m, std::uint32_t a, std::uint32_t b) {
    const Vec3 &p = m.positions[a], &q = m.positions[b];
    const double dx = double(p.x) - q.x, dy = double(p.y) - q.y, dz = double(p.z) - q.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double perimeter(const IndexedMesh& m, const Triangle& t) {
    return edge_length(m, t[0], t[1]) + edge_length(m, t[1], t[2]) + edge_length(m, t[2], t[0]);
}

// torus() with its first quad (triangles 0 and 1) removed: a torus with a square hole. kRim lists
// the hole's corners in the order the removed quad ran them: (0, 0), (1, 0), (1, 1), (0, 1) of the
// grid, for the tori below (nv = 8).
constexpr int kHoleTorusAcross = 8;
constexpr std::array<std::uint32_t, 4> kRim = {0, kHoleTorusAcross, kHoleTorusAcross + 1, 1};
IndexedMesh torus_with_hole(const Vec3& center = {0, 0, 0}) {
    IndexedMesh m = torus(1.0f, 0.3f, 12, kHoleTorusAcross, center);
    m.triangles.erase(m.triangles.begin(), m.triangles.begin() + 2);
    return m;
}

// Two tori with holes welded along the holes' rims: their connected sum, a closed surface of
// genus 2. The second torus's rim vertices give way to the first's (and are left unused), rim
// vertex k to the first's rim vertex {1, 0, 3, 2}[k], so that each welded edge is run one way by
// the triangles of one torus and the other way by the other's. Only its topology is meant: the
// welded triangles stretch from one torus to the other.
IndexedMesh double_torus() {
    IndexedMesh m = merged(torus_with_hole(), torus_with_hole({3, 0, 0}));
    const std::uint32_t shift = std::uint32_t(m.positions.size() / 2);
    constexpr int partner[4] = {1, 0, 3, 2};
    for (Triangle& t : m.triangles)
        for (std::uint32_t& v : t)
            for (int k = 0; k < 4; ++k)
                if (v == shift + kRim[k]) {
                    v = kRim[partner[k]];
                    break;
                }
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
        CHECK(r.boundary_loops == 0);
        CHECK(r.boundary_edges == 0);
        CHECK(r.boundary_length == 0.0);
        CHECK(r.self_intersections == 0);
        const MeshTopology small = nmesh::mesh_topology(torus(1.0f, 0.3f, 8, 6));
        CHECK(small.closed);
        CHECK(small.manifold);
        CHECK(small.euler == 0);
        CHECK(small.genus == 1);
        CHECK(small.boundary_loops == 0);
    }
    SUBCASE("double torus") {
        const MeshTopology t = nmesh::mesh_topology(double_torus());
        CHECK(t.closed);
        CHECK(t.manifold);
        CHECK(t.components == 1);
        CHECK(t.euler == -2);
        CHECK(t.genus == 2);
        CHECK(t.boundary_loops == 0);
        CHECK(t.isolated_vertices == 4);  // the second torus's rim, welded to the first's
    }
    SUBCASE("genus adds up over components") {
        // A torus and a sphere: chi = 0 + 2, so (2 - chi) / 2 over the whole would say 0.
        const QualityReport r = quick_evaluate(merged(torus(1.0f, 0.3f, 16, 8), icosphere(1, {5, 0, 0})));
        CHECK(r.components == 2);
        CHECK(r.euler == 2);
        CHECK(r.genus == 1);
        const QualityReport tori =
            quick_evaluate(merged(torus(1.0f, 0.3f, 16, 8), torus(1.0f, 0.3f, 16, 8, {4, 0, 0})));
        CHECK(tori.components == 2);
        CHECK(tori.euler == 0);
        CHECK(tori.genus == 2);
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
    SUBCASE("three triangles on one edge") {
        IndexedMesh m;
        m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
        m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
        const QualityReport r = quick_evaluate(m);
        CHECK_FALSE(r.closed);
        CHECK_FALSE(r.manifold);
        CHECK(r.genus == -1);
        CHECK(r.components == 1);
        CHECK(r.euler == 5 - 7 + 3);
        // Each triangle's two other edges are boundary edges; no fan reaches across the shared
        // edge, so each triangle's rim is a loop of its own.
        CHECK(r.boundary_edges == 6);
        CHECK(r.boundary_loops == 3);
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
        CHECK(r.genus == -1);
        CHECK(r.components == 1);
        CHECK(r.isolated_vertices == 1);
        CHECK(r.euler == 7 - 12 + 8);
        CHECK(r.boundary_loops == 0);
        CHECK(r.boundary_edges == 0);
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

TEST_CASE("topology of surfaces with boundaries") {
    SUBCASE("a tetrahedron without one face: a disc") {
        IndexedMesh m = tetrahedron();
        const Triangle gone = m.triangles.back();
        m.triangles.pop_back();
        const QualityReport r = quick_evaluate(m);
        CHECK_FALSE(r.closed);
        CHECK(r.manifold);  // open fans are fine
        CHECK(r.euler == 1);
        CHECK(r.genus == 0);
        CHECK(r.components == 1);
        CHECK(r.isolated_vertices == 0);
        CHECK(r.boundary_loops == 1);
        CHECK(r.boundary_edges == 3);
        CHECK(r.boundary_length == doctest::Approx(3 * 2 * std::sqrt(2.0)));
        CHECK(r.boundary_length == doctest::Approx(perimeter(m, gone)).epsilon(1e-12));
        CHECK(r.boundary_length_rel == doctest::Approx(r.boundary_length / r.bbox_diagonal));
    }
    SUBCASE("an icosphere without one face, without two apart, without two side by side") {
        const IndexedMesh sphere = icosphere(2);
        IndexedMesh one = sphere;
        one.triangles.erase(one.triangles.begin() + 17);
        const MeshTopology a = nmesh::mesh_topology(one);
        CHECK(a.manifold);
        CHECK(a.genus == 0);
        CHECK(a.euler == 1);
        CHECK(a.boundary_loops == 1);
        CHECK(a.boundary_edges == 3);
        CHECK(a.boundary_length == doctest::Approx(perimeter(sphere, sphere.triangles[17])).epsilon(1e-12));

        // Two faces sharing no vertex: two holes, an annulus (chi 0).
        const Triangle& first = sphere.triangles[0];
        std::size_t apart = 1;
        const auto shares_a_vertex = [&](const Triangle& t) {
            return std::any_of(t.begin(), t.end(), [&](std::uint32_t v) {
                return std::find(first.begin(), first.end(), v) != first.end();
            });
        };
        while (shares_a_vertex(sphere.triangles[apart])) ++apart;
        IndexedMesh two = sphere;
        two.triangles.erase(two.triangles.begin() + std::ptrdiff_t(apart));
        two.triangles.erase(two.triangles.begin());
        const MeshTopology b = nmesh::mesh_topology(two);
        CHECK(b.manifold);
        CHECK(b.genus == 0);
        CHECK(b.euler == 0);
        CHECK(b.boundary_loops == 2);
        CHECK(b.boundary_edges == 6);
        CHECK(b.boundary_length ==
              doctest::Approx(perimeter(sphere, first) + perimeter(sphere, sphere.triangles[apart])).epsilon(1e-12));

        // Two faces sharing an edge: one hole, a rim of four edges.
        std::size_t beside = 1;
        while (std::count_if(sphere.triangles[beside].begin(), sphere.triangles[beside].end(), [&](std::uint32_t v) {
                   return std::find(first.begin(), first.end(), v) != first.end();
               }) != 2)
            ++beside;
        IndexedMesh pair = sphere;
        pair.triangles.erase(pair.triangles.begin() + std::ptrdiff_t(beside));
        pair.triangles.erase(pair.triangles.begin());
        const MeshTopology c = nmesh::mesh_topology(pair);
        CHECK(c.manifold);
        CHECK(c.genus == 0);
        CHECK(c.boundary_loops == 1);
        CHECK(c.boundary_edges == 4);
    }
    SUBCASE("a tube open at both ends") {
        const QualityReport r = quick_evaluate(ring_strip(16, {1, 1, 1, 1}, {0, 0.5f, 1, 1.5f}));
        CHECK_FALSE(r.closed);
        CHECK(r.manifold);
        CHECK(r.components == 1);
        CHECK(r.euler == 0);
        CHECK(r.genus == 0);
        CHECK(r.boundary_loops == 2);
        CHECK(r.boundary_edges == 32);
        CHECK(r.boundary_length == doctest::Approx(2 * polygon_perimeter(16, 1.0)).epsilon(1e-6));
    }
    SUBCASE("a flat annulus") {
        const QualityReport r = quick_evaluate(ring_strip(12, {1, 2}, {0, 0}));
        CHECK(r.manifold);
        CHECK(r.euler == 0);
        CHECK(r.genus == 0);
        CHECK(r.boundary_loops == 2);
        CHECK(r.boundary_edges == 24);
        CHECK(r.boundary_length ==
              doctest::Approx(polygon_perimeter(12, 1.0) + polygon_perimeter(12, 2.0)).epsilon(1e-6));
    }
    SUBCASE("a torus with a hole keeps its handle") {
        const IndexedMesh m = torus_with_hole();
        const QualityReport r = quick_evaluate(m);
        CHECK_FALSE(r.closed);
        CHECK(r.manifold);
        CHECK(r.euler == -1);
        CHECK(r.genus == 1);
        CHECK(r.boundary_loops == 1);
        CHECK(r.boundary_edges == 4);
        double rim = 0.0;
        for (int k = 0; k < 4; ++k) rim += edge_length(m, kRim[std::size_t(k)], kRim[std::size_t((k + 1) % 4)]);
        CHECK(r.boundary_length == doctest::Approx(rim).epsilon(1e-12));
    }
    SUBCASE("genus and loops add up per component") {
        // A disc and a torus: chi = 1 + 0 and b = 1, so (2 - chi - b) / 2 over the whole would be
        // 0; per component it is 0 + 1.
        IndexedMesh disc = tetrahedron({5, 0, 0});
        disc.triangles.pop_back();
        const MeshTopology t = nmesh::mesh_topology(merged(torus(1.0f, 0.3f, 16, 8), disc));
        CHECK(t.manifold);
        CHECK(t.components == 2);
        CHECK(t.euler == 1);
        CHECK(t.boundary_loops == 1);
        CHECK(t.genus == 1);
        const MeshTopology u = nmesh::mesh_topology(merged(torus_with_hole(), ring_strip(8, {1, 1}, {5, 6})));
        CHECK(u.components == 2);
        CHECK(u.boundary_loops == 3);
        CHECK(u.euler == -1);
        CHECK(u.genus == 1);
    }
    SUBCASE("a Moebius strip is no oriented surface") {
        // A band of 10 quads whose ends are joined with a half twist: no orientation of its
        // triangles agrees across every edge. Its rim is one loop, twice the band's length.
        IndexedMesh m;
        constexpr int n = 10;
        for (int i = 0; i < n; ++i) {
            const float u = 6.2831853f * float(i) / float(n), w = 0.2f;
            const float c = std::cos(u / 2), d = std::sin(u / 2);
            m.positions.push_back({(1 + w * c) * std::cos(u), (1 + w * c) * std::sin(u), w * d});
            m.positions.push_back({(1 - w * c) * std::cos(u), (1 - w * c) * std::sin(u), -w * d});
        }
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t a = 2 * i, b = 2 * i + 1;
            // After the last quad the two sides of the band change places.
            const std::uint32_t c = i + 1 < n ? 2 * i + 2 : 1, d = i + 1 < n ? 2 * i + 3 : 0;
            m.triangles.push_back({a, c, d});
            m.triangles.push_back({a, d, b});
        }
        const MeshTopology t = nmesh::mesh_topology(m);
        CHECK_FALSE(t.closed);
        CHECK_FALSE(t.manifold);
        CHECK(t.genus == -1);
        CHECK(t.euler == 0);
        CHECK(t.boundary_loops == 1);
        CHECK(t.boundary_edges == 2 * n);
    }
}

TEST_CASE("topology: bow-tie vertices, where fans meet only at their tip, are not manifold") {
    SUBCASE("two triangles sharing one vertex") {
        IndexedMesh m;
        m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
        m.triangles = {{0, 1, 2}, {0, 3, 4}};
        const QualityReport r = quick_evaluate(m);
        CHECK_FALSE(r.closed);
        CHECK_FALSE(r.manifold);
        CHECK(r.genus == -1);
        CHECK(r.components == 1);
        CHECK(r.euler == 5 - 6 + 2);
        CHECK(r.boundary_edges == 6);
        CHECK(r.boundary_loops == 2);  // each fan at the shared vertex has its own rim
        // Apart, the same two triangles are two discs.
        m.positions.push_back(m.positions[0]);
        m.triangles[1][0] = 5;
        const QualityReport apart = quick_evaluate(m);
        CHECK(apart.manifold);
        CHECK(apart.genus == 0);
        CHECK(apart.components == 2);
        CHECK(apart.boundary_loops == 2);
    }
    SUBCASE("two open pyramids joined at their apex") {
        // Two fans of four triangles round one apex, one above it and one below.
        IndexedMesh m;
        m.positions = {{0, 0, 0}};
        for (const float z : {1.0f, -1.0f})
            for (int i = 0; i < 4; ++i) {
                const float u = 1.5707963f * float(i);
                m.positions.push_back({std::cos(u), std::sin(u), z});
            }
        for (std::uint32_t k = 0; k < 2; ++k)
            for (std::uint32_t i = 0; i < 4; ++i) m.triangles.push_back({0, 1 + 4 * k + i, 1 + 4 * k + (i + 1) % 4});
        const QualityReport r = quick_evaluate(m);
        CHECK_FALSE(r.manifold);
        CHECK(r.genus == -1);
        CHECK(r.components == 1);
        CHECK(r.boundary_loops == 2);
        CHECK(r.boundary_edges == 8);
        CHECK(r.boundary_length == doctest::Approx(2 * polygon_perimeter(4, 1.0)).epsilon(1e-6));
        // One pyramid alone is a disc.
        m.triangles.resize(4);
        const QualityReport one = quick_evaluate(m);
        CHECK(one.manifold);
        CHECK(one.genus == 0);
        CHECK(one.boundary_loops == 1);
        CHECK(one.isolated_vertices == 4);
    }
    SUBCASE("an icosphere without two faces that share one vertex") {
        const IndexedMesh sphere = icosphere(1);
        const Triangle& first = sphere.triangles[0];
        std::size_t tip = 1;
        while (std::count_if(sphere.triangles[tip].begin(), sphere.triangles[tip].end(), [&](std::uint32_t v) {
                   return std::find(first.begin(), first.end(), v) != first.end();
               }) != 1)
            ++tip;
        IndexedMesh m = sphere;
        m.triangles.erase(m.triangles.begin() + std::ptrdiff_t(tip));
        m.triangles.erase(m.triangles.begin());
        const MeshTopology t = nmesh::mesh_topology(m);
        CHECK_FALSE(t.closed);
        CHECK_FALSE(t.manifold);  // the shared vertex keeps two fans
        CHECK(t.genus == -1);
        CHECK(t.boundary_edges == 6);
        CHECK(t.boundary_loops == 1);  // one rim, through the shared vertex twice
    }
}

namespace {

// The most fans at any vertex, by brute force: the triangles round each vertex, linked when they
// share an edge at it.
std::size_t most_fans(const IndexedMesh& m) {
    std::size_t most = 0;
    for (std::uint32_t v = 0; v < m.positions.size(); ++v) {
        std::vector<Triangle> round;
        for (const Triangle& t : m.triangles)
            if (std::find(t.begin(), t.end(), v) != t.end()) round.push_back(t);
        std::vector<std::size_t> fan(round.size());
        std::iota(fan.begin(), fan.end(), 0);
        for (bool changed = true; changed;) {
            changed = false;
            for (std::size_t i = 0; i < round.size(); ++i)
                for (std::size_t j = 0; j < round.size(); ++j) {
                    std::size_t shared = 0;
                    for (std::uint32_t a : round[i])
                        shared += std::find(round[j].begin(), round[j].end(), a) != round[j].end();
                    if (i != j && shared == 2 && fan[j] > fan[i]) {
                        fan[j] = fan[i];
                        changed = true;
                    }
                }
        }
        std::sort(fan.begin(), fan.end());
        most = std::max<std::size_t>(most, std::size_t(std::unique(fan.begin(), fan.end()) - fan.begin()));
    }
    return most;
}

// The rims of a part of a consistently oriented closed surface, walked: a boundary edge u -> w is
// one whose reverse no triangle runs; from w the walk takes w's only such edge. Returns the
// loops, and the boundary edges in `edges`; 0 loops and 0 edges if a vertex has two.
std::size_t walked_loops(const IndexedMesh& m, std::size_t& edges) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const Triangle& t : m.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{t[std::size_t(k)], t[std::size_t((k + 1) % 3)]}];
    std::map<std::uint32_t, std::uint32_t> next;
    for (const auto& [e, count] : directed)
        if (!directed.count({e.second, e.first})) {
            if (next.count(e.first)) return edges = 0;
            next[e.first] = e.second;
        }
    edges = next.size();
    std::size_t loops = 0;
    std::map<std::uint32_t, bool> seen;
    for (const auto& [start, unused] : next) {
        if (seen[start]) continue;
        ++loops;
        for (std::uint32_t v = start; !seen[v]; v = next.at(v)) seen[v] = true;
    }
    return loops;
}

}  // namespace

TEST_CASE("an icosphere with faces removed at random: genus 0, and the rims a walk finds") {
    // Any part of a sphere is a sphere with holes, or several; where the removed faces leave a
    // vertex with two fans the mesh is no surface. Both happen here, scattered faces or patches.
    const IndexedMesh sphere = icosphere(2);  // 320 faces
    std::mt19937 rng(11);
    int surfaces = 0, bow_ties = 0;
    for (int trial = 0; trial < 120; ++trial) {
        CAPTURE(trial);
        IndexedMesh m = sphere;
        std::shuffle(m.triangles.begin(), m.triangles.end(), rng);
        const std::size_t remove = 1 + std::size_t(trial) % 30 * std::size_t(trial % 2 ? 1 : 5);
        if (trial % 2) {
            m.triangles.resize(m.triangles.size() - remove);  // scattered
        } else {
            // A patch grown from one face through shared edges.
            std::vector<char> gone(m.triangles.size(), 0);
            gone[0] = 1;
            for (std::size_t count = 1; count < remove;) {
                const std::size_t f = std::uniform_int_distribution<std::size_t>(0, m.triangles.size() - 1)(rng);
                if (gone[f]) continue;
                bool touches = false;
                for (std::size_t g = 0; g < m.triangles.size() && !touches; ++g) {
                    if (!gone[g]) continue;
                    std::size_t shared = 0;
                    for (std::uint32_t a : m.triangles[f])
                        shared += std::find(m.triangles[g].begin(), m.triangles[g].end(), a) != m.triangles[g].end();
                    touches = shared == 2;
                }
                if (touches) {
                    gone[f] = 1;
                    ++count;
                }
            }
            std::vector<Triangle> kept;
            for (std::size_t f = 0; f < m.triangles.size(); ++f)
                if (!gone[f]) kept.push_back(m.triangles[f]);
            m.triangles = kept;
        }
        const MeshTopology t = nmesh::mesh_topology(m);
        const bool surface = most_fans(m) == 1;
        CHECK(t.manifold == surface);
        CHECK_FALSE(t.closed);
        std::size_t edges = 0;
        const std::size_t loops = walked_loops(m, edges);
        if (surface) {
            ++surfaces;
            CHECK(t.genus == 0);
            CHECK(t.boundary_edges == edges);
            CHECK(t.boundary_loops == loops);
            CHECK(t.euler == 2 * (long long)t.components - (long long)t.boundary_loops);
        } else {
            ++bow_ties;
            CHECK(t.genus == -1);
        }
    }
    CHECK(surfaces >= 20);
    CHECK(bow_ties >= 20);
}

TEST_CASE("mesh_topology is evaluate's topology, and checks the indices") {
    IndexedMesh m = torus_with_hole();
    const QualityReport r = quick_evaluate(m);
    const MeshTopology t = nmesh::mesh_topology(m);
    CHECK(t.closed == r.closed);
    CHECK(t.manifold == r.manifold);
    CHECK(t.euler == r.euler);
    CHECK(t.genus == r.genus);
    CHECK(t.components == r.components);
    CHECK(t.isolated_vertices == r.isolated_vertices);
    CHECK(t.boundary_loops == r.boundary_loops);
    CHECK(t.boundary_edges == r.boundary_edges);
    CHECK(t.boundary_length == r.boundary_length);
    // No cloud needed, and coordinates matter only to the boundary's length.
    m.positions[20].x = std::numeric_limits<float>::quiet_NaN();
    const MeshTopology nan = nmesh::mesh_topology(m);
    CHECK(nan.genus == 1);
    CHECK(nan.boundary_length == t.boundary_length);  // vertex 20 is not on the rim
    m.triangles[3][1] = std::uint32_t(m.positions.size());
    CHECK_THROWS_AS(nmesh::mesh_topology(m), nmesh::InputError);
    CHECK(nmesh::mesh_topology(IndexedMesh{}).components == 0);
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
    m.triangles.pop_back();  // open: a disc with one boundary loop
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
                                                      {"isolated_vertices", 0.0},
                                                      {"genus", 0.0},
                                                      {"boundary_loops", 1.0},
                                                      {"boundary_edges", 3.0},
                                                      {"boundary_length", r.boundary_length},
                                                      {"boundary_length_rel", r.boundary_length_rel}};
    for (const auto& [key, value] : numbers) {
        CAPTURE(key);
        const std::string text = json_value(json, key);
        REQUIRE_FALSE(text.empty());
        CHECK(std::strtod(text.c_str(), nullptr) == doctest::Approx(value).epsilon(1e-9));
    }
    CHECK(json_value(json, "closed") == "false");
    CHECK(json_value(json, "manifold") == "true");
    CHECK(r.p2s_max > 0.0);
    CHECK(r.boundary_length == doctest::Approx(3 * 2 * std::sqrt(2.0)));
    CHECK(r.boundary_length_rel > 0.0);

    // No genus when the mesh is not manifold: null.
    IndexedMesh flipped = tetrahedron();
    std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
    std::ostringstream flipped_json;
    nmesh::write_json(flipped_json, quick_evaluate(flipped));
    CHECK(json_value(flipped_json.str(), "genus") == "null");
    CHECK(json_value(flipped_json.str(), "boundary_loops") == "0");

    std::ostringstream out_text;
    nmesh::write_text(out_text, r);
    const std::string text = out_text.str();
    CHECK(text.find("genus:") != std::string::npos);
    CHECK(text.find("boundary_loops:       1\n") != std::string::npos);
    CHECK(std::count(text.begin(), text.end(), '\n') == 34);
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

TEST_CASE("orientation: the largest edge-connected patch of flagged faces") {
    // A cap of the sphere (z > 0.7) and three single faces far from it and from each other: the
    // cap is the largest patch; two faces that share only a vertex are two patches; the inward
    // test finds the reversed cap as one patch.
    IndexedMesh sphere = icosphere(3);
    std::vector<std::uint8_t> flags(sphere.triangles.size(), 0);
    std::size_t cap = 0;
    std::vector<std::uint32_t> singles;
    for (std::uint32_t t = 0; t < sphere.triangles.size(); ++t) {
        const auto& tri = sphere.triangles[t];
        const Vec3 c = (sphere.positions[tri[0]] + sphere.positions[tri[1]] + sphere.positions[tri[2]]) * (1.0f / 3.0f);
        if (c.z > 0.7f) {
            flags[t] = 1;
            ++cap;
        } else if (singles.size() < 3 && c.z < -0.5f &&
                   std::all_of(singles.begin(), singles.end(), [&](std::uint32_t s) {
                       const auto& u = sphere.triangles[s];
                       for (std::uint32_t a : tri)
                           for (std::uint32_t b : u)
                               if (a == b) return false;
                       return true;
                   })) {
            flags[t] = 1;
            singles.push_back(t);
        }
    }
    REQUIRE(singles.size() == 3);
    REQUIRE(cap > 10);
    CHECK(nmesh::largest_patch(sphere, flags) == cap);
    std::vector<std::uint8_t> only_singles(flags.size(), 0);
    for (const std::uint32_t s : singles) only_singles[s] = 1;
    CHECK(nmesh::largest_patch(sphere, only_singles) == 1);
    CHECK(nmesh::largest_patch(sphere, std::vector<std::uint8_t>(flags.size(), 0)) == 0);
    CHECK(nmesh::largest_patch(sphere, std::vector<std::uint8_t>(flags.size(), 1)) == flags.size());
    // Two faces sharing only a vertex: two patches of one.
    IndexedMesh fan = icosphere(1);
    std::vector<std::uint8_t> two(fan.triangles.size(), 0);
    for (std::uint32_t t = 1; t < fan.triangles.size(); ++t) {
        const auto& a = fan.triangles[0];
        const auto& b = fan.triangles[t];
        int shared = 0;
        for (std::uint32_t x : a)
            for (std::uint32_t y : b) shared += x == y;
        if (shared == 1) {
            two[0] = two[t] = 1;
            break;
        }
    }
    REQUIRE(std::count(two.begin(), two.end(), std::uint8_t(1)) == 2);
    CHECK(nmesh::largest_patch(fan, two) == 1);
    // The cap reversed: the inward test flags it, one patch.
    for (std::uint32_t t = 0; t < sphere.triangles.size(); ++t)
        if (flags[t] && std::find(singles.begin(), singles.end(), t) == singles.end())
            std::swap(sphere.triangles[t][1], sphere.triangles[t][2]);
    const nmesh::TriangleBvh bvh(sphere);
    const auto inward = nmesh::inward_face_flags(sphere, bvh);
    const std::size_t flagged = std::size_t(std::count(inward.begin(), inward.end(), std::uint8_t(1)));
    CHECK(flagged <= cap);
    CHECK(flagged >= cap * 9 / 10);  // a face at the cap's edge may count either way
    CHECK(nmesh::largest_patch(sphere, inward) >= cap * 9 / 10);
}

TEST_CASE("orient_outward reverses an inside-out closed mesh and leaves an outward one alone") {
    IndexedMesh m = icosphere(2);
    const IndexedMesh outward = m;
    CHECK_FALSE(nmesh::orient_outward(m));
    CHECK(m.triangles == outward.triangles);
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    CHECK(nmesh::orient_outward(m));
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
    CHECK(nmesh::test::refused_parameter([&] { nmesh::evaluate(m.positions, m, none); }) == "surface_samples");
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
    const std::size_t faces_before = mesh.triangles.size();
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
    CHECK(r.genus == 0);
    CHECK(r.components == 1);
    CHECK(r.euler == 2 - 3);
    CHECK(r.boundary_loops == 3);
    CHECK(r.boundary_edges == faces_before - mesh.triangles.size());  // a removed fan's rim: one edge per face
    CHECK(r.boundary_length > 0.0);
    CHECK(r.boundary_length_rel == doctest::Approx(r.boundary_length / r.bbox_diagonal));
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
