// Topology open (nmesh/finish/open_surface.h) and boundaries in the finishing stage: a scan with
// a missing cap gets one boundary loop there and none where there are points; a closed scan stays
// closed; the finishing stage keeps a boundary where it is; a one-sided sheet loses one of the
// two layers a closed mesh wraps round it.
#include <doctest/doctest.h>

#include <cmath>

#include "cloud_fixtures.h"
#include "engine_checks.h"
#include "mesh_fixtures.h"
#include "nmesh/finish/finish.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/reconstruct.h"
#include "sanitized.h"

using namespace nmesh;

namespace {

ManifoldCheck require_valid(const Mesh& m) { return test::require_valid_mesh(m); }

double area(const IndexedMesh& m) {
    double a = 0.0;
    for (const auto& t : m.triangles)
        a += 0.5 * double(norm(cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]])));
    return a;
}

PointCloud capless_sphere(std::size_t n) {
    PointCloud all = test::sphere_cloud(2 * n, 1.0f, {}, 11), out;
    for (const Vec3& p : all.points)
        if (p.z < 0.6f && out.points.size() < n) out.points.push_back(p);
    return out;
}

}  // namespace

TEST_CASE("topology open: a scan without its cap gets one boundary loop there, none where there are points") {
    const PointCloud cloud = capless_sphere(20000);
    Parameters p;
    const std::uint32_t n = test::kSanitized ? 800 : 2000;  // sanitized.h
    p.target_vertices = n;
    p.topology = Topology::open;
    const Result r = reconstruct(cloud, p);
    const Mesh m = Mesh::from_indexed(r.mesh, true);
    const ManifoldCheck c = require_valid(m);
    CHECK(c.boundary_loops == 1);
    CHECK(c.genus == 0);
    CHECK(r.stats.boundary_loops == 1);
    CHECK(r.stats.open_faces_removed > 0);
    CHECK(r.stats.crossing_pairs == 0);
    // The vertices inside the hole go with its faces; the rest stay.
    CHECK(r.mesh.positions.size() <= n);
    CHECK(r.mesh.positions.size() > n - n / 20);
    // The boundary runs round the cut (z = 0.6), not through the sampled part below it.
    for (std::uint32_t v = 0; v < m.vertex_capacity(); ++v)
        if (!m.is_removed(Vertex(v)) && m.is_boundary(Vertex(v))) CHECK(m.position(Vertex(v)).z > 0.4f);
}

TEST_CASE("topology open on a closed scan: no boundary, the closed mode's mesh") {
    const PointCloud cloud = test::sphere_cloud(8000);
    Parameters p;
    p.target_vertices = test::kSanitized ? 600 : 2000;
    p.topology = Topology::closed;
    const Result closed = reconstruct(cloud, p);
    p.topology = Topology::open;
    const Result open = reconstruct(cloud, p);
    CHECK(open.stats.boundary_loops == 0);
    CHECK(open.stats.open_faces_removed == 0);
    CHECK(open.stats.layer_faces_removed == 0);
    CHECK(open.mesh.triangles == closed.mesh.triangles);
}

TEST_CASE("the finishing stage keeps a boundary where it is") {
    Mesh m = Mesh::from_indexed(test::icosphere(3));
    // A hole of a few faces round one vertex.
    const Vertex centre(0);
    std::vector<Face> around;
    m.for_each_face_around(centre, [&](Face f) { around.push_back(f); });
    for (Face f : around) m.try_remove_face(f);
    ManifoldCheck c = require_valid(m);
    REQUIRE(c.boundary_loops == 1);
    // Noise, so that there is something to regularise and repair.
    std::vector<Vec3> cloud;
    for (std::uint32_t v = 0; v < m.vertex_capacity(); ++v) {
        if (m.is_removed(Vertex(v))) continue;
        cloud.push_back(m.position(Vertex(v)));
        const float wiggle = 0.01f * std::sin(float(v) * 12.9898f);
        if (!m.is_boundary(Vertex(v))) m.set_position(Vertex(v), m.position(Vertex(v)) * (1.0f + wiggle));
    }
    std::vector<std::pair<std::uint32_t, Vec3>> rim;
    for (std::uint32_t v = 0; v < m.vertex_capacity(); ++v)
        if (!m.is_removed(Vertex(v)) && m.is_boundary(Vertex(v))) rim.push_back({v, m.position(Vertex(v))});
    REQUIRE(rim.size() >= 3);
    const std::uint32_t vertices = m.n_vertices();
    finish_mesh(m, cloud);
    c = require_valid(m);
    CHECK(c.boundary_loops == 1);
    CHECK(c.genus == 0);
    CHECK(m.n_vertices() == vertices);
    for (const auto& [v, p] : rim) {
        REQUIRE_FALSE(m.is_removed(Vertex(v)));
        CHECK(m.is_boundary(Vertex(v)));
        CHECK(m.position(Vertex(v)) == p);
    }
}

TEST_CASE("topology open on a one-sided sheet takes one of the two layers off") {
    // A quarter of a cylinder's side, sampled on one side only, as one range image sees it.
    Random rng(5);
    PointCloud sheet;
    for (int i = 0; i < 20000; ++i) {
        const double u = 1.5 * rng.uniform(), v = 2.0 * rng.uniform();
        sheet.points.push_back({float(std::cos(u)), float(std::sin(u)), float(v)});
    }
    Parameters p;
    p.target_vertices = test::kSanitized ? 1200 : 3000;
    p.topology = Topology::open;
    const Result open = reconstruct(sheet, p);
    CHECK(open.stats.layer_faces_removed > 0);
    CHECK(open.stats.boundary_loops > 0);
    const ManifoldCheck c = require_valid(Mesh::from_indexed(open.mesh, true));
    CHECK(c.genus == 0);
    // One layer: not more area than the sheet's (1.5 x 2; two layers would have twice that), and
    // fewer crossings than the closed mesh's tangle.
    const double a = area(open.mesh);
    CHECK(a < 1.2 * 3.0);
    CHECK(a > 0.5 * 3.0);
    if (test::kSanitized) return;  // the closed mesh's tangle is slow to finish there
    p.topology = Topology::closed;
    const Result closed = reconstruct(sheet, p);
    CHECK(open.stats.crossing_pairs < closed.stats.crossing_pairs);
}
