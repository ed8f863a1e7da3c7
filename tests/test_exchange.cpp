// The finishing stage's vertex exchange (nmesh/finish/exchange.h): collapses where the surface is
// flat paired with splits where it bends away from the mesh; the count, the manifold and the
// genus kept; boundary vertices left alone.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "mesh_fixtures.h"
#include "nmesh/finish/cloud_surface.h"
#include "nmesh/finish/exchange.h"
#include "nmesh/geometry/closest_point.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/util/random.h"

using namespace nmesh;
using nmesh::test::icosphere;

namespace {

// A rounded cube: |x|^6 + |y|^6 + |z|^6 = 1. Nearly flat faces, bent tightly along its edges.
Vec3 on_cube(const Vec3& d) {
    const double r = std::pow(std::pow(std::fabs(d.x), 6.0) + std::pow(std::fabs(d.y), 6.0) +
                                  std::pow(std::fabs(d.z), 6.0),
                              1.0 / 6.0);
    return d * float(1.0 / r);
}

// n points on the rounded cube (directions uniform on the sphere, then moved out along them).
std::vector<Vec3> cube_points(std::size_t n, std::uint64_t seed) {
    Random rng(seed);
    std::vector<Vec3> p;
    while (p.size() < n) {
        const Vec3 d(float(2 * rng.uniform() - 1), float(2 * rng.uniform() - 1), float(2 * rng.uniform() - 1));
        const float l = norm(d);
        if (l < 0.1f || l > 1.0f) continue;
        p.push_back(on_cube(d));
    }
    return p;
}

// The icosphere's vertices moved out onto the rounded cube: spread by direction, not by the bend.
IndexedMesh cube_triangles(int levels) {
    IndexedMesh m = icosphere(levels);
    for (Vec3& p : m.positions) p = on_cube(p);
    return m;
}

// The mean distance from the points to the mesh, every triangle tried.
double mean_distance(const Mesh& mesh, const std::vector<Vec3>& points) {
    double sum = 0.0;
    for (const Vec3& x : points) {
        float best = std::numeric_limits<float>::infinity();
        for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
            if (mesh.is_removed(Face(f))) continue;
            const auto c = mesh.face_vertices(Face(f));
            const Vec3 y = closest_point_on_triangle_float(x, mesh.position(c[0]), mesh.position(c[1]),
                                                           mesh.position(c[2]));
            best = std::min(best, squared_distance(x, y));
        }
        sum += std::sqrt(double(best));
    }
    return sum / double(points.size());
}

// Vertices on the cube's bent edges: two coordinates beyond 0.8 in magnitude.
std::uint32_t edge_vertices(const Mesh& mesh) {
    std::uint32_t n = 0;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v) {
        if (mesh.is_removed(Vertex(v))) continue;
        const Vec3 p = mesh.position(Vertex(v));
        n += (std::fabs(p.x) > 0.8f) + (std::fabs(p.y) > 0.8f) + (std::fabs(p.z) > 0.8f) >= 2;
    }
    return n;
}

}  // namespace

TEST_CASE("the exchange moves vertices from a rounded cube's flat faces to its edges, the surface nearer the points") {
    const std::vector<Vec3> points = cube_points(3000, 11);
    Mesh mesh = Mesh::from_indexed(cube_triangles(3));  // 642 vertices
    const CloudSurface cloud(points, mesh);
    const std::uint32_t vertices = mesh.n_vertices();
    const std::uint32_t edges_before = edge_vertices(mesh);
    const double before = mean_distance(mesh, points);

    const ExchangeResult r = exchange_vertices(mesh, cloud, 10, 20.0f);
    const ManifoldCheck check = check_manifold(mesh);
    REQUIRE_MESSAGE(check.ok, check.error);
    CHECK(check.sphere());
    CHECK(mesh.n_vertices() == vertices);
    CHECK(r.exchanged > 0);
    CHECK(r.passes >= 1);
    const std::uint32_t edges_after = edge_vertices(mesh);
    const double after = mean_distance(mesh, points);
    MESSAGE("vertices on the edges " << edges_before << " -> " << edges_after << ", mean distance " << before << " -> " << after
                            << ", " << r.exchanged << " pairs in " << r.passes << " passes");
    CHECK(edges_after > edges_before + r.exchanged / 2);
    CHECK(after < 0.9 * before);
}

TEST_CASE("no pass leaves the mesh as it was; a sphere's even bend gives little to exchange") {
    const std::vector<Vec3> points = cube_points(3000, 11);
    Mesh mesh = Mesh::from_indexed(cube_triangles(3));
    const CloudSurface cloud(points, mesh);
    const auto faces = nmesh::test::face_set(mesh);
    const std::vector<Vec3> positions = mesh.positions();
    const ExchangeResult none = exchange_vertices(mesh, cloud, 0, 20.0f);
    CHECK(none.exchanged == 0);
    CHECK(nmesh::test::face_set(mesh) == faces);
    CHECK(mesh.positions() == positions);

    // The unit sphere and its icosphere: every face bends the same, so a collapse costs about what
    // a split gains and the margin keeps nearly all of them.
    Random rng(5);
    std::vector<Vec3> sphere;
    while (sphere.size() < 3000) {
        const Vec3 d(float(2 * rng.uniform() - 1), float(2 * rng.uniform() - 1), float(2 * rng.uniform() - 1));
        const float l = norm(d);
        if (l >= 0.1f && l <= 1.0f) sphere.push_back(d * (1.0f / l));
    }
    Mesh ball = Mesh::from_indexed(icosphere(3));
    const CloudSurface ball_cloud(sphere, ball);
    const ExchangeResult even = exchange_vertices(ball, ball_cloud, 10, 20.0f);
    REQUIRE(check_manifold(ball).sphere());
    MESSAGE("sphere: " << even.exchanged << " pairs");
    CHECK(even.exchanged < ball.n_vertices() / 50);
}

TEST_CASE("boundary vertices are neither collapsed nor moved, and the boundary keeps its edges") {
    const std::vector<Vec3> points = cube_points(3000, 11);
    IndexedMesh m = cube_triangles(3);
    // The faces of the lower half go: an open box.
    std::vector<std::array<std::uint32_t, 3>> upper;
    for (const auto& t : m.triangles)
        if (m.positions[t[0]].z + m.positions[t[1]].z + m.positions[t[2]].z > 0.0f) upper.push_back(t);
    m.triangles = upper;
    std::vector<std::uint8_t> used(m.positions.size(), 0);
    for (const auto& t : m.triangles)
        for (std::uint32_t v : t) used[v] = 1;
    IndexedMesh cup;
    std::vector<std::uint32_t> slot(m.positions.size(), 0);
    for (std::size_t i = 0; i < m.positions.size(); ++i)
        if (used[i]) {
            slot[i] = std::uint32_t(cup.positions.size());
            cup.positions.push_back(m.positions[i]);
        }
    for (const auto& t : m.triangles) cup.triangles.push_back({slot[t[0]], slot[t[1]], slot[t[2]]});
    Mesh mesh = Mesh::from_indexed(cup, true);
    REQUIRE(mesh.has_boundary());
    std::vector<std::pair<Vertex, Vec3>> rim;
    std::vector<Vertex> rim_next;  // along the boundary
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
        if (!mesh.is_removed(Vertex(v)) && mesh.is_boundary(Vertex(v))) {
            rim.push_back({Vertex(v), mesh.position(Vertex(v))});
            rim_next.push_back(mesh.to(mesh.halfedge(Vertex(v))));
        }
    const CloudSurface cloud(points, mesh);
    const std::uint32_t vertices = mesh.n_vertices();
    const ExchangeResult r = exchange_vertices(mesh, cloud, 10, 20.0f);
    const ManifoldCheck check = check_manifold(mesh);
    REQUIRE_MESSAGE(check.ok, check.error);
    CHECK(check.boundary_loops == 1);
    CHECK(mesh.n_vertices() == vertices);
    CHECK(r.exchanged > 0);
    for (std::size_t i = 0; i < rim.size(); ++i) {
        CHECK(!mesh.is_removed(rim[i].first));
        CHECK(mesh.is_boundary(rim[i].first));
        CHECK(mesh.position(rim[i].first) == rim[i].second);
        CHECK(mesh.to(mesh.halfedge(rim[i].first)) == rim_next[i]);
    }
}
