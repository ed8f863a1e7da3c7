// The finishing stage's surface fit (nmesh/finish/surface_fit.h): the vertices moved to where the
// mesh best matches the points; never into a crossing, a fold or a thin triangle, never a
// boundary vertex, never by points of the other side of a thin part.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "mesh_fixtures.h"
#include "nmesh/error.h"
#include "nmesh/finish/cloud_surface.h"
#include "nmesh/finish/finish.h"
#include "nmesh/finish/repair.h"
#include "nmesh/finish/surface_fit.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/metrics.h"
#include "nmesh/parameters.h"
#include "nmesh/util/random.h"

using namespace nmesh;
using nmesh::test::icosphere;

namespace {

// n points drawn uniformly on the sphere of radius r round the origin, each moved along the
// radius by Gaussian noise of deviation sigma.
std::vector<Vec3> noisy_sphere(std::size_t n, float r, float sigma, std::uint64_t seed) {
    Random rng(seed);
    std::vector<Vec3> p;
    while (p.size() < n) {
        const Vec3 d(float(2 * rng.uniform() - 1), float(2 * rng.uniform() - 1), float(2 * rng.uniform() - 1));
        const float l = norm(d);
        if (l < 0.1f || l > 1.0f) continue;
        const double u1 = std::max(rng.uniform(), 1e-12), u2 = rng.uniform();
        const float g = float(std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2));
        p.push_back(d * ((r + sigma * g) / l));
    }
    return p;
}

double mean_radius_error(const Mesh& mesh) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v) {
        if (mesh.is_removed(Vertex(v))) continue;
        sum += std::fabs(double(norm(mesh.position(Vertex(v)))) - 1.0);
        ++n;
    }
    return sum / double(n);
}

// Every pair of live faces tested: the crossing pairs by brute force.
std::size_t crossing_pairs(const Mesh& mesh) {
    std::vector<Face> faces;
    for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f)
        if (!mesh.is_removed(Face(f))) faces.push_back(Face(f));
    std::size_t n = 0;
    for (std::size_t i = 0; i < faces.size(); ++i)
        for (std::size_t j = i + 1; j < faces.size(); ++j) {
            const auto a = mesh.face_vertices(faces[i]), b = mesh.face_vertices(faces[j]);
            n += faces_intersect(mesh.positions().data(), {a[0].idx, a[1].idx, a[2].idx},
                                 {b[0].idx, b[1].idx, b[2].idx});
        }
    return n;
}

// Triangles whose smallest angle is under 10 degrees.
std::size_t thin_triangles(const Mesh& mesh) {
    std::size_t n = 0;
    for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
        if (mesh.is_removed(Face(f))) continue;
        const auto c = mesh.face_vertices(Face(f));
        for (int k = 0; k < 3; ++k) {
            const Vec3 u = mesh.position(c[(k + 1) % 3]) - mesh.position(c[k]);
            const Vec3 v = mesh.position(c[(k + 2) % 3]) - mesh.position(c[k]);
            if (dot(u, v) > std::cos(10.0f * 3.14159265f / 180.0f) * norm(u) * norm(v)) {
                ++n;
                break;
            }
        }
    }
    return n;
}

// A closed box over [-1, 1]^2, thin: its top an n x n grid at z = +h facing up, its bottom one at
// z = -h facing down, their rims joined by a band of quads. Vertex i + n j of the top (and
// n^2 + i + n j of the bottom) at (-1 + 2i/(n-1), -1 + 2j/(n-1)).
IndexedMesh thin_box(std::uint32_t n, float h) {
    IndexedMesh m;
    const auto at = [n](std::uint32_t s, std::uint32_t i, std::uint32_t j) { return s * n * n + i + n * j; };
    for (const float z : {h, -h})
        for (std::uint32_t j = 0; j < n; ++j)
            for (std::uint32_t i = 0; i < n; ++i)
                m.positions.emplace_back(-1.0f + 2.0f * float(i) / float(n - 1), -1.0f + 2.0f * float(j) / float(n - 1),
                                         z);
    for (std::uint32_t j = 0; j + 1 < n; ++j)
        for (std::uint32_t i = 0; i + 1 < n; ++i) {
            m.triangles.push_back({at(0, i, j), at(0, i + 1, j), at(0, i + 1, j + 1)});
            m.triangles.push_back({at(0, i, j), at(0, i + 1, j + 1), at(0, i, j + 1)});
            m.triangles.push_back({at(1, i, j), at(1, i + 1, j + 1), at(1, i + 1, j)});
            m.triangles.push_back({at(1, i, j), at(1, i, j + 1), at(1, i + 1, j + 1)});
        }
    // The rim, counter-clockwise seen from above.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> rim;
    for (std::uint32_t k = 0; k + 1 < n; ++k) rim.emplace_back(k, 0);
    for (std::uint32_t k = 0; k + 1 < n; ++k) rim.emplace_back(n - 1, k);
    for (std::uint32_t k = 0; k + 1 < n; ++k) rim.emplace_back(n - 1 - k, n - 1);
    for (std::uint32_t k = 0; k + 1 < n; ++k) rim.emplace_back(0, n - 1 - k);
    for (std::size_t k = 0; k < rim.size(); ++k) {
        const auto [i0, j0] = rim[k];
        const auto [i1, j1] = rim[(k + 1) % rim.size()];
        m.triangles.push_back({at(0, i1, j1), at(0, i0, j0), at(1, i0, j0)});
        m.triangles.push_back({at(0, i1, j1), at(1, i0, j0), at(1, i1, j1)});
    }
    return m;
}

// A grid of points over [-0.8, 0.8]^2 at height z.
std::vector<Vec3> plane_points(float z) {
    std::vector<Vec3> p;
    for (int j = 0; j <= 40; ++j)
        for (int i = 0; i <= 40; ++i) p.emplace_back(-0.8f + 0.04f * float(i), -0.8f + 0.04f * float(j), z);
    return p;
}

}  // namespace

TEST_CASE("the fit moves the vertices of a shrunken sphere onto a noisy sample of the sphere") {
    // The icosphere (642 vertices, edges about 0.1) inside the unit sphere by 3% of the radius,
    // as a mesh whose vertices settled at the mean of their samples lies inside a curved surface;
    // 10,000 points on the unit sphere with noise of 0.5% of the radius.
    IndexedMesh shrunk = icosphere(3);
    for (Vec3& p : shrunk.positions) p = p * 0.97f;
    Mesh mesh = Mesh::from_indexed(shrunk);
    REQUIRE(thin_triangles(mesh) == 0);
    const std::vector<Vec3> cloud = noisy_sphere(10000, 1.0f, 0.005f, 3);
    const double before = mean_radius_error(mesh);
    CHECK(before == doctest::Approx(0.03).epsilon(0.01));
    const CloudSurface surface(cloud, mesh);
    SurfaceFitOptions options;
    options.rounds = 3;
    const SurfaceFitResult r = fit_surface(mesh, surface, options);
    const double after = mean_radius_error(mesh);
    MESSAGE("mean |r - 1| " << before << " -> " << after);
    CHECK(after < 0.1 * before);
    CHECK(r.rounds == 3);
    CHECK(r.points_used == 30000);
    CHECK(r.undone == 0);
    CHECK(crossing_pairs(mesh) == 0);
    CHECK(check_manifold(mesh).sphere());
    // The mean distance from the points to the mesh falls with it.
    const double p2s_before = evaluate(cloud, shrunk).p2s_mean;
    const double p2s_after = evaluate(cloud, mesh.to_indexed()).p2s_mean;
    CHECK(p2s_after < 0.5 * p2s_before);
}

TEST_CASE("the fit keeps no move that makes a crossing, a fold or a thin triangle") {
    // Wild moves: few points with noise of a third of the radius, no fairness, moves up to five
    // edges a round. Whatever the solve asks, no crossing pair, folded edge or triangle under 10
    // degrees is left, and some moves had to be halved or undone for it.
    for (const std::uint64_t seed : {1, 2, 3}) {
        CAPTURE(seed);
        Mesh mesh = Mesh::from_indexed(icosphere(2));
        const std::vector<Vec3> cloud = noisy_sphere(300, 1.0f, 0.3f, seed);
        const CloudSurface surface(cloud, mesh);
        SurfaceFitOptions options;
        options.rounds = 3;
        options.smoothness = 0.0f;
        options.step_limit = 5.0f;
        options.reach = 10.0f;
        const SurfaceFitResult r = fit_surface(mesh, surface, options);
        CHECK(r.halved + r.undone > 0);
        CHECK(crossing_pairs(mesh) == 0);
        CHECK(find_folded_edges(mesh).empty());
        CHECK(thin_triangles(mesh) == 0);
        CHECK(check_manifold(mesh).sphere());
    }
}

TEST_CASE("the fit leaves the corners of a defect it was given where they are, and adds none") {
    // One vertex of the icosphere pushed through the far side: its triangles cross others. The
    // fit moves the rest onto a sample of the sphere, but neither those corners nor the number of
    // crossing pairs.
    const IndexedMesh sphere = icosphere(2);
    Mesh mesh = Mesh::from_indexed(sphere);
    const Vertex pushed(0);
    mesh.set_position(pushed, mesh.position(pushed) * -1.3f);
    const std::size_t pairs = crossing_pairs(mesh);
    REQUIRE(pairs > 0);
    const Mesh before = mesh;
    const std::vector<Vec3> cloud = noisy_sphere(5000, 1.02f, 0.0f, 4);
    const CloudSurface surface(cloud, mesh);
    const SurfaceFitResult r = fit_surface(mesh, surface);
    CHECK(r.moves > 100);
    CHECK(crossing_pairs(mesh) <= pairs);
    CHECK(mesh.position(pushed) == before.position(pushed));
    for (const auto& [f, g] : find_self_intersections(before))
        for (const Face face : {f, g})
            for (const Vertex v : before.face_vertices(face)) CHECK(mesh.position(v) == before.position(v));
}

TEST_CASE("the fit keeps the boundary of an open surface where it is") {
    // An open 9 x 9 grid over [-1, 1]^2 at z = 0 and points at z = 0.05 over its middle: the
    // inside vertices rise, the rim's stay.
    IndexedMesh grid = thin_box(9, 0.0f);
    grid.positions.resize(81);  // the top sheet alone
    std::vector<std::array<std::uint32_t, 3>> top;
    for (const auto& t : grid.triangles)
        if (t[0] < 81 && t[1] < 81 && t[2] < 81) top.push_back(t);
    grid.triangles = top;
    Mesh mesh = Mesh::from_indexed(grid, true);
    REQUIRE(mesh.has_boundary());
    const Mesh before = mesh;
    const std::vector<Vec3> cloud = plane_points(0.05f);
    const CloudSurface surface(cloud, mesh);
    const SurfaceFitResult r = fit_surface(mesh, surface);
    CHECK(r.moves > 0);
    std::size_t rim = 0, risen = 0;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v) {
        if (mesh.is_boundary(Vertex(v))) {
            ++rim;
            CHECK(mesh.position(Vertex(v)) == before.position(Vertex(v)));
        } else {
            risen += mesh.position(Vertex(v)).z > 0.02f;
        }
    }
    CHECK(rim == 32);
    CHECK(risen >= 25);
}

TEST_CASE("points of the other side of a thin part do not pull it") {
    // A closed box 0.02 thick (edges 0.25). Points taken from the top side (their side +z) that
    // lie nearer to the bottom sheet than to the top one (noise larger than the wall): the bottom
    // sheet faces away from them, and nothing moves. The same points taken from the bottom side
    // (their side -z) pull the bottom sheet up to them.
    const IndexedMesh box = thin_box(9, 0.01f);
    const std::vector<Vec3> cloud = plane_points(-0.006f);
    for (const float side : {1.0f, -1.0f}) {
        CAPTURE(side);
        Mesh mesh = Mesh::from_indexed(box);
        const Mesh before = mesh;
        const std::vector<Vec3> sides(cloud.size(), Vec3(0.0f, 0.0f, side));
        const CloudSurface surface(cloud, mesh, nullptr, &sides);
        const SurfaceFitResult r = fit_surface(mesh, surface);
        std::size_t moved = 0;
        for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v) {
            const Vec3 p = mesh.position(Vertex(v)), q = before.position(Vertex(v));
            moved += p != q;
            if (side > 0.0f) CHECK(p == q);
            if (side < 0.0f && q.z < 0.0f && std::fabs(q.x) < 0.5f && std::fabs(q.y) < 0.5f)
                CHECK(p.z == doctest::Approx(-0.006f).epsilon(0.05));
        }
        CHECK((side > 0.0f ? r.points_used == 0 : r.points_used > 1000));
        CHECK((side > 0.0f ? moved == 0 : moved > 20));
        CHECK(crossing_pairs(mesh) == 0);
    }
}

TEST_CASE("the finishing stage runs the fit last, its rounds from the options") {
    // The stage with the fit off and on, on a shrunken sphere: the fit's rounds are reported and
    // bring the vertices out onto the sample; off, the report is empty.
    IndexedMesh shrunk = icosphere(3);
    for (Vec3& p : shrunk.positions) p = p * 0.97f;
    const std::vector<Vec3> cloud = noisy_sphere(10000, 1.0f, 0.002f, 5);
    double error[2] = {0.0, 0.0};
    for (const int rounds : {0, 2}) {
        CAPTURE(rounds);
        Mesh mesh = Mesh::from_indexed(shrunk);
        FinishOptions options;
        options.rounds = 0;
        options.cover_iterations = 0;
        options.surface_fit_rounds = rounds;
        const FinishReport report = finish_mesh(mesh, cloud, options);
        CHECK(report.surface_fit.rounds == std::uint32_t(rounds));
        CHECK(report.intersecting_pairs_after == 0);
        error[rounds > 0] = mean_radius_error(mesh);
    }
    CHECK(error[1] < 0.2 * error[0]);
    REQUIRE(FinishOptions{}.surface_fit_rounds == int(Parameters{}.surface_fit_rounds));
}

TEST_CASE("Parameters::surface_fit_rounds is refused out of range, and ignored without the stage") {
    Parameters p;
    p.surface_fit_rounds = 101;
    try {
        p.validate();
        FAIL("validate() accepted surface_fit_rounds 101");
    } catch (const ParameterError& e) {
        CHECK(e.parameter() == "surface_fit_rounds");
        CHECK(std::string(e.what()).find("invalid parameter surface_fit_rounds: must be in [0, 100]") == 0);
    }
    p.surface_fit_rounds = 100;
    CHECK_NOTHROW(p.validate());
    // The default with the stage off: the paper's algorithm, no refusal.
    Parameters paper;
    paper.finish = false;
    REQUIRE(paper.surface_fit_rounds > 0);
    CHECK_NOTHROW(paper.validate());
}
