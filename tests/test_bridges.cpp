// The bridge search (nmesh/learn/bridges.h): a small sac reached across a thin unsupported neck
// is found when its data joins the body's through the cloud and nothing walls the neck round,
// and is left alone otherwise; the collapses that take it away leave a valid closed mesh with the
// body as it was.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "sanitized.h"
#include "topology_fixtures.h"
#include "nmesh/learn/bridges.h"
#include "nmesh/learn/face_support.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/util/random.h"

using namespace nmesh;

namespace {

// A dumbbell standing on the z axis: a body (the sphere of radius 0.5 about (0, 0, -0.5)), a
// neck (a five-sided tube of radius 0.03 from z = 0 to z = 1) and a sac (the sphere of radius
// 0.15 about (0, 0, 1.15)). The neck's five edges bound the sac's side.
constexpr float kNeckTop = 1.0f, kSacRadius = 0.15f;
IndexedMesh dumbbell() {
    std::vector<test::Ring> rings;
    const float pi = 3.14159265f;
    // The body, from its south pole up to a ring of radius 0.03.
    const float top = std::asin(0.03f / 0.5f);
    for (int k = 1; k <= 48; ++k) {
        const float t = pi - (pi - top) * float(k) / 48.0f;  // polar angle from +z
        rings.push_back({-0.5f + 0.5f * std::cos(t), 0.5f * std::sin(t), 128});
    }
    for (int k = 0; k <= 10; ++k) rings.push_back({0.01f + (kNeckTop - 0.02f) * float(k) / 10.0f, 0.03f, 5});
    // The sac, from a ring of radius 0.03 to its north pole.
    const float start = pi - std::asin(0.03f / kSacRadius);
    for (int k = 0; k < 10; ++k) {
        const float t = start * (1.0f - float(k) / 10.0f);
        rings.push_back({kNeckTop + kSacRadius + kSacRadius * std::cos(t), kSacRadius * std::sin(t), 12});
    }
    return test::revolution(rings, -1.0f, kNeckTop + 2.0f * kSacRadius);
}

void sample_sphere(std::vector<Vec3>& out, std::size_t n, const Vec3& centre, float radius, Random& rng) {
    for (std::size_t i = 0; i < n; ++i) {
        const float z = 2.0f * float(rng.uniform()) - 1.0f, a = 6.2831853f * float(rng.uniform());
        const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
        out.push_back(centre + Vec3{s * std::cos(a), s * std::sin(a), z} * radius);
    }
}

// The points of the body and the sac; with `rod`, a line of points beside the neck from the body
// to the sac, so that the sac's data joins the body's (a leg beside the mesh's bridge); with
// `sleeve`, a cylinder of points of radius `sleeve` round the neck (a thin part's data round its
// still thin mesh); with `neck`, points on the neck itself.
std::vector<Vec3> dumbbell_cloud(bool rod, float sleeve, bool neck) {
    Random rng(11);
    std::vector<Vec3> p;
    sample_sphere(p, 60000, {0, 0, -0.5f}, 0.5f, rng);
    sample_sphere(p, 6000, {0, 0, kNeckTop + kSacRadius}, kSacRadius, rng);
    if (rod) {
        const Vec3 a{0.45f, 0, -0.3f}, b{0.14f, 0, kNeckTop + kSacRadius};
        for (int i = 0; i <= 400; ++i) p.push_back(a + (b - a) * (float(i) / 400.0f));
    }
    if (sleeve > 0.0f)
        for (int i = 0; i < 8000; ++i) {
            const float a = 6.2831853f * float(rng.uniform()), z = 0.1f + 0.8f * float(rng.uniform());
            p.push_back({sleeve * std::cos(a), sleeve * std::sin(a), z});
        }
    if (neck)
        for (int i = 0; i < 4000; ++i) {
            const float a = 6.2831853f * float(rng.uniform()), z = kNeckTop * float(rng.uniform());
            p.push_back({0.03f * std::cos(a), 0.03f * std::sin(a), z});
        }
    return p;
}

struct Found {
    BridgeSearch search;
    float far = 0.0f;
    std::uint32_t unsupported = 0;
};

Found search(const Mesh& mesh, const std::vector<Vec3>& cloud) {
    const PointGrid index{PointSpan(cloud)};
    Found f;
    const FaceSupport s = face_support(mesh, index);
    f.far = s.far;
    for (const char u : s.unsupported) f.unsupported += u ? 1u : 0u;
    f.search = find_bridges(mesh, index, s);
    return f;
}

std::uint32_t flagged_above(const Mesh& mesh, const BridgeSearch& s, float z) {
    std::uint32_t n = 0;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
        if (s.flagged[v] && mesh.position(Vertex(v)).z > z) ++n;
    return n;
}

}  // namespace

TEST_CASE("the dumbbell fixture: a closed genus-0 manifold facing outward, its neck unsupported by the data") {
    const IndexedMesh shape = dumbbell();
    const Mesh mesh = Mesh::from_indexed(shape);
    const ManifoldCheck c = check_manifold(mesh);
    INFO(c.error);
    REQUIRE(c.sphere());
    // Facing outward: the signed volume is about the body's and the sac's, positive.
    double volume = 0.0;
    for (const auto& t : shape.triangles)
        volume += double(dot(shape.positions[t[0]], cross(shape.positions[t[1]], shape.positions[t[2]]))) / 6.0;
    const double spheres = 4.0 / 3.0 * 3.14159265 * (0.125 + double(kSacRadius) * kSacRadius * kSacRadius);
    CHECK(volume > 0.95 * spheres);
    CHECK(volume < 1.05 * spheres);
    const Found f = search(mesh, dumbbell_cloud(true, 0.0f, false));
    // The setting the other cases rely on: the support distance well below the neck's length and
    // the rod's distance from the neck, and part of the neck unsupported.
    CHECK(f.far > 0.01f);
    CHECK(f.far < 0.1f);
    CHECK(f.unsupported >= 50);
    CHECK(f.unsupported <= 100);
}

TEST_CASE("a sac across an unsupported neck, its data joined to the body's, is a bridge: it and its neck are flagged") {
    Mesh mesh = Mesh::from_indexed(dumbbell());
    const std::uint32_t before = mesh.n_vertices();
    const Found f = search(mesh, dumbbell_cloud(true, 0.0f, false));
    CHECK(f.search.bridges == 1);
    // Every vertex above the neck's unsupported part is flagged, none of the body's.
    std::uint32_t above = 0;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
        if (mesh.position(Vertex(v)).z > kNeckTop) ++above;
    CHECK(flagged_above(mesh, f.search, kNeckTop) == above);
    CHECK(flagged_above(mesh, f.search, -0.01f) == f.search.flagged_count);
    CHECK(f.search.flagged_count > above);  // and the neck's

    // Taken away by collapses: a valid closed genus-0 mesh, the body's vertices where they were.
    std::uint32_t collapses = 0;
    const std::uint32_t left = collapse_flagged(mesh, f.search.flagged, [&](Vertex gone, Vertex kept) {
        CHECK(f.search.flagged[gone.idx]);
        CHECK(!mesh.is_removed(kept));
        ++collapses;
    });
    CHECK(left == 0);
    CHECK(collapses == f.search.flagged_count);
    CHECK(mesh.n_vertices() == before - f.search.flagged_count);
    const ManifoldCheck c = check_manifold(mesh);
    INFO(c.error);
    REQUIRE(c.sphere());
    float highest = -1.0f;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
        if (!mesh.is_removed(Vertex(v))) highest = std::max(highest, mesh.position(Vertex(v)).z);
    CHECK(highest < 0.05f);  // at most the neck's foot, on the body
}

TEST_CASE("no bridge where the sac's data is apart from the body's (two objects: the neck is the only way)") {
    const Mesh mesh = Mesh::from_indexed(dumbbell());
    const Found f = search(mesh, dumbbell_cloud(false, 0.0f, false));
    CHECK(f.unsupported >= 50);
    CHECK(f.search.bridges == 0);
    CHECK(f.search.flagged_count == 0);
}

TEST_CASE("no bridge where the data walls the neck round (a thin part's mesh inside its data)") {
    const Mesh mesh = Mesh::from_indexed(dumbbell());
    const Found plain = search(mesh, dumbbell_cloud(true, 0.0f, false));
    // A sleeve of data farther from the neck than the support distance and within the reach.
    const float sleeve = 0.03f + 2.0f * plain.far;
    REQUIRE(sleeve < 0.03f + kNeckReach * plain.far);
    const Found f = search(mesh, dumbbell_cloud(true, sleeve, false));
    CHECK(f.unsupported >= 50);  // the neck is still unsupported
    CHECK(f.search.bridges == 0);
}

TEST_CASE("no bridge where the neck has data") {
    const Mesh mesh = Mesh::from_indexed(dumbbell());
    const Found f = search(mesh, dumbbell_cloud(true, 0.0f, true));
    CHECK(f.search.bridges == 0);
}

TEST_CASE("collapse_flagged on the dumbbell: a random flagged set goes, the mesh stays valid, refusals are counted") {
    Mesh mesh = Mesh::from_indexed(dumbbell());
    Random rng(5);
    std::vector<char> flagged(mesh.vertex_capacity(), 0);
    std::uint32_t n = 0;
    // 30% of the vertices; 3% in the sanitizer build, which checks the whole mesh after every
    // collapse (sanitized.h).
    const double share = test::kSanitized ? 0.03 : 0.3;
    for (std::uint32_t v = 0; v < flagged.size(); ++v)
        if (rng.uniform() < share) flagged[v] = 1, ++n;
    const std::uint32_t before = mesh.n_vertices();
    std::uint32_t collapses = 0;
    const std::uint32_t left = collapse_flagged(mesh, flagged, [&](Vertex, Vertex) { ++collapses; });
    CHECK(collapses + left == n);
    CHECK(mesh.n_vertices() == before - collapses);
    CHECK(left < n / 10);
    const ManifoldCheck c = check_manifold(mesh);
    INFO(c.error);
    REQUIRE(c.sphere());
}
