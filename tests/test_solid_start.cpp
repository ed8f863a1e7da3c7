// The solid a cloud walls round (nmesh/learn/solid_start.h): its genus against clouds of known
// topology, the leaks and the grid's own tunnels it refuses, the simplification that keeps the
// genus, and the learning that starts from it.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <utility>

#include "cloud_fixtures.h"
#include "mesh_fixtures.h"
#include "sanitized.h"
#include "topology_fixtures.h"
#include "nmesh/bounding_box.h"
#include "nmesh/error.h"
#include "nmesh/learn/solid_start.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/reconstruct.h"
#include "nmesh/util/random.h"

using namespace nmesh;

namespace {

// The solid of `cloud` in the frame reconstruct() learns in (centred, diagonal 1).
SolidSurface solid_of(const PointCloud& cloud) {
    const BoundingBox box = bounding_box(PointSpan(cloud.points));
    return solid_surface(PointSpan(cloud.points), PointTransform{box.center(), float(1.0 / box.diagonal())});
}

// Six times the signed volume of a closed mesh (positive when its faces point outward).
double signed_volume(const IndexedMesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles) v += dot(m.positions[t[0]], cross(m.positions[t[1]], m.positions[t[2]]));
    return v / 6.0;
}

// The genus of a closed mesh, through the validator (which requires one component).
int genus_of(const IndexedMesh& m) {
    const ManifoldCheck c = check_manifold(Mesh::from_indexed(m));
    INFO(c.error);
    REQUIRE(c.ok);
    REQUIRE(c.boundary_loops == 0);
    return c.genus;
}

// A ball with a thin tail along it, as the camel's along its body: a tube of radius 0.015 on an
// arc round a sphere of radius 0.3 whose gap to the sphere waves round `gap` (by 0.015 either
// way; a point spacing is about 0.004), so that the offsets that wall the sphere round fuse the
// tail to the body at several places. At a gap of 0.025 their number changes with the offset and
// the grid (no genus persists); at 0.03 some seeds hold a number of them over two offsets.
PointCloud tailed_ball(std::uint64_t seed, float gap0 = 0.025f) {
    PointCloud c = test::sphere_cloud(20000, 0.3f, {}, seed);
    Random rng(seed + 100);
    constexpr float kTube = 0.015f;
    while (c.points.size() < 22000) {
        const float t = float(-1.4 + 2.8 * rng.uniform()), phi = float(6.283185307 * rng.uniform());
        const float gap = gap0 + 0.015f * std::cos(5.0f * t) * (1.0f - 0.3f * t);
        const float r = 0.3f + kTube + gap;
        const Vec3 radial{std::cos(t), 0.0f, std::sin(t)};
        c.points.push_back(radial * r + radial * (kTube * std::cos(phi)) + Vec3{0.0f, kTube * std::sin(phi), 0.0f});
    }
    return c;
}

}  // namespace

TEST_CASE("a torus sample walls a solid of genus 1 round, a sphere sample one of genus 0") {
    const SolidSurface torus = solid_of(test::torus_cloud(20000));
    CHECK(torus.walled);
    CHECK(torus.components == 1);
    CHECK(torus.genus == 1);
    CHECK(torus.stable);
    // The surface counted on the grid is the one built: a closed manifold of that genus, round
    // the torus (its box a little larger than the data's: the offset).
    REQUIRE_FALSE(torus.surface.triangles.empty());
    CHECK(genus_of(torus.surface) == 1);

    const SolidSurface sphere = solid_of(test::sphere_cloud(20000));
    CHECK(sphere.walled);
    CHECK(sphere.components == 1);
    CHECK(sphere.genus == 0);
    CHECK(sphere.stable);  // no handle to doubt
    REQUIRE_FALSE(sphere.surface.triangles.empty());
    CHECK(genus_of(sphere.surface) == 0);
}

TEST_CASE("a genus-0 solid is a start only when it hugs the samples (kMaxShapeOffset)") {
    // A sphere sample with a scanner's hole a few point spacings wide: the small offsets leak
    // through it, a larger one walls the solid round, as the bunny's base holes do at 8 d. That
    // solid has genus 0 but is no start; the whole sphere, walled round at 3-4 d, is one.
    const PointCloud sphere = test::sphere_cloud(20000);
    PointCloud holed;
    for (const Vec3& p : sphere.points)
        if (p.z < 0.996f) holed.points.push_back(p);  // walled round at 8 d (4 d: below 0.999)
    const SolidSurface s = solid_of(holed);
    REQUIRE(s.walled);
    CHECK(s.genus == 0);
    CHECK(s.offset > kMaxShapeOffset);
    CHECK(s.surface.triangles.empty());
    const SolidSurface whole = solid_of(sphere);
    CHECK(whole.offset <= kMaxShapeOffset);
    CHECK_FALSE(whole.surface.triangles.empty());
    for (const PointCloud* c : {static_cast<const PointCloud*>(&holed), &sphere}) {
        const BoundingBox box = bounding_box(PointSpan(c->points));
        const SolidStart start =
            solid_start(PointSpan(c->points), PointTransform{box.center(), float(1.0 / box.diagonal())}, 2000);
        CHECK(start.solid_genus == 0);
        CHECK(start.mesh.has_value() == (c == &sphere));
    }
}

TEST_CASE("the torus's genus is read at every sampling density, the shifted grids agreeing") {
    // At 3,000 and 5,000 points both shifted grids leak at the offset that walls the first grid
    // round, and agree at the next.
    for (const std::size_t n : {2000u, 3000u, 5000u, 8000u}) {
        CAPTURE(n);
        const SolidSurface s = solid_of(test::torus_cloud(n));
        CHECK(s.walled);
        CHECK(s.genus == 1);
        CHECK(s.stable);
    }
}

TEST_CASE("two objects are two components; an open sheet leaks and walls nothing round") {
    PointCloud two = test::sphere_cloud(8000, 0.3f, {-0.5f, 0, 0});
    const PointCloud other = test::sphere_cloud(8000, 0.3f, {0.5f, 0, 0}, 11);
    two.points.insert(two.points.end(), other.points.begin(), other.points.end());
    const SolidSurface s = solid_of(two);
    CHECK(s.walled);
    CHECK(s.components == 2);
    const BoundingBox box = bounding_box(PointSpan(two.points));
    const SolidStart start =
        solid_start(PointSpan(two.points), PointTransform{box.center(), float(1.0 / box.diagonal())}, 2000);
    CHECK_FALSE(start.mesh.has_value());  // the engine learns one connected surface
    CHECK(start.solid_genus == -1);

    // A hemisphere: the outside comes in under it at every offset.
    PointCloud cap = test::sphere_cloud(20000);
    cap.points.erase(std::remove_if(cap.points.begin(), cap.points.end(), [](const Vec3& p) { return p.z < 0.0f; }),
                     cap.points.end());
    CHECK_FALSE(solid_of(cap).walled);
}

TEST_CASE("the ball on thin legs reads genus 0: no tunnel where the legs meet the ball") {
    // Distances to the cells holding a point read tunnels of the grid's own where the legs meet
    // the ball, at the first offset that walls it round; distances to the points' splats
    // (cloud_splats.h) read none on any grid that walls it round at that offset.
    const PointCloud table = test::table_cloud();
    const BoundingBox box = bounding_box(PointSpan(table.points));
    const PointTransform transform{box.center(), float(1.0 / box.diagonal())};
    const SolidSurface s = solid_surface(PointSpan(table.points), transform);
    CHECK(s.walled);
    CHECK(s.stable);
    CHECK(s.genus == 0);
    for (int shift = 0; shift < int(std::size(kGridShifts)); ++shift) {
        CAPTURE(shift);
        const solid_detail::GridReading r = solid_detail::read_grid(PointSpan(table.points), transform, s.offset, shift);
        CHECK((r.walled || shift > 0));  // the first grid walls it round: the reading's own
        if (!r.walled) continue;
        CHECK(r.components == 1);
        CHECK(r.genus == 0);
    }
    const SolidStart start = solid_start(PointSpan(table.points), transform, 2000);
    CHECK(start.solid_genus == 0);
}

TEST_CASE("the outside levels give the outside a flood from the border finds, at every offset") {
    // Random grids of distances, some cells near the points (small values), the rest far; the
    // border layer far, as the padding makes it. At every squared radius v the cells outside the
    // shell (distance > v) that a 6-connected flood from the border reaches through such cells are
    // exactly those whose level exceeds v.
    std::mt19937 rng(5);
    for (int trial = 0; trial < 40; ++trial) {
        const std::array<std::uint32_t, 3> dims{std::uint32_t(3 + rng() % 10), std::uint32_t(3 + rng() % 10), std::uint32_t(3 + rng() % 10)};
        const std::uint32_t nx = dims[0], ny = dims[1], nz = dims[2];
        std::vector<std::uint8_t> dist(std::size_t(nx) * ny * nz);
        const int spread = 1 + int(rng() % 60);
        for (std::uint32_t z = 0; z < nz; ++z)
            for (std::uint32_t y = 0; y < ny; ++y)
                for (std::uint32_t x = 0; x < nx; ++x) {
                    const bool border = x == 0 || y == 0 || z == 0 || x + 1 == nx || y + 1 == ny || z + 1 == nz;
                    dist[(z * ny + y) * nx + x] = border ? 255 : std::uint8_t(rng() % 4 == 0 ? 255 : rng() % spread);
                }
        const std::vector<std::uint8_t> level = solid_detail::outside_levels(dims, dist);
        for (int v = 0; v < 256; v += 1 + int(rng() % 7)) {
            std::vector<char> out(dist.size(), 0);
            std::vector<std::uint32_t> stack;
            for (std::uint32_t z = 0; z < nz; ++z)
                for (std::uint32_t y = 0; y < ny; ++y)
                    for (std::uint32_t x = 0; x < nx; ++x)
                        if (x == 0 || y == 0 || z == 0 || x + 1 == nx || y + 1 == ny || z + 1 == nz)
                            out[(z * ny + y) * nx + x] = 1, stack.push_back((z * ny + y) * nx + x);
            while (!stack.empty()) {
                const std::uint32_t i = stack.back();
                stack.pop_back();
                const std::uint32_t x = i % nx, y = (i / nx) % ny, z = i / (nx * ny);
                const std::int64_t around[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
                for (const auto& a : around) {
                    const std::int64_t u = x + a[0], w = y + a[1], t = z + a[2];
                    if (u < 0 || w < 0 || t < 0 || u >= nx || w >= ny || t >= nz) continue;
                    const std::uint32_t j = std::uint32_t((t * ny + w) * nx + u);
                    if (!out[j] && dist[j] > v) out[j] = 1, stack.push_back(j);
                }
            }
            for (std::size_t i = 0; i < dist.size(); ++i)
                if (dist[i] > v) REQUIRE(bool(out[i]) == (level[i] > v));
        }
    }
}

TEST_CASE("simplify keeps the genus and reaches the vertex count, every face still facing out") {
    for (const auto& [name, indexed] : {std::pair<const char*, IndexedMesh>{"torus", test::torus_grid(40, 30)},
                                        {"sphere", test::icosahedron().to_indexed()}}) {
        CAPTURE(name);
        Mesh m = Mesh::from_indexed(indexed);
        const int genus = check_manifold(m).genus;
        const std::uint32_t target = std::string(name) == "torus" ? 200 : 8;
        const double volume_before = signed_volume(m.to_indexed());
        m.drop_faces();
        REQUIRE(simplify(m, target));
        CHECK(m.n_vertices() == target);
        m.build_faces();
        const ManifoldCheck c = check_manifold(m);
        INFO(c.error);
        REQUIRE(c.ok);
        CHECK(c.genus == genus);
        CHECK(signed_volume(m.to_indexed()) > 0.5 * volume_before);
    }
    // Below what the link condition allows (a tetrahedron is the smallest closed mesh), it stops.
    Mesh small = test::icosahedron();
    small.drop_faces();
    CHECK_FALSE(simplify(small, 3));
    CHECK(small.n_vertices() >= 4);
}

TEST_CASE("topology closed starts a torus sample from its solid's surface: genus 1 on every seed") {
    // The sanitizer build checks the whole mesh after every collapse of the simplification:
    // a sparser sample there, whose solid's surface has about 4,000 vertices instead of 30,000.
    const PointCloud torus = test::torus_cloud(test::kSanitized ? 2000 : 20000);
    const std::uint32_t target = test::kSanitized ? 1000 : 3000;
    const std::uint64_t seeds = test::kSanitized ? 1 : 4;
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
        CAPTURE(seed);
        Parameters p;
        p.target_vertices = target;
        p.seed = seed;
        const Result r = reconstruct(torus, p);
        CHECK(r.stats.solid_genus == 1);
        CHECK(r.stats.start_vertices == start_vertices(target));
        CHECK(genus_of(r.mesh) == 1);
        CHECK(r.stats.handles == 0);  // the start has the handle; the search makes no other
        CHECK(r.stats.crossing_pairs == 0);
        CHECK(r.stats.inward_faces == 0);
        CHECK(r.mesh.positions.size() == target);
    }
    // The sphere mode never looks at the solid: the paper's tetrahedron.
    Parameters p;
    p.target_vertices = 1000;
    p.topology = Topology::sphere;
    const Result sphere = reconstruct(torus, p);
    CHECK(sphere.stats.solid_genus == -1);
    CHECK(sphere.stats.start_vertices == 4);
    CHECK(genus_of(sphere.mesh) == 0);
}

TEST_CASE("adaptivity weighs the signals from the solid's start only; 0 is the paper's counter") {
    const PointCloud torus = test::torus_cloud(test::kSanitized ? 8000 : 20000);
    Parameters p;
    p.target_vertices = test::kSanitized ? 1200 : 3000;
    const Result plain = reconstruct(torus, p);
    REQUIRE(plain.stats.start_vertices > 4);  // from the solid
    p.adaptivity = 0.5;
    const Result weighed = reconstruct(torus, p);
    CHECK(weighed.stats.start_vertices == plain.stats.start_vertices);
    CHECK_FALSE(weighed.mesh.positions == plain.mesh.positions);  // the splits went elsewhere
    CHECK(genus_of(weighed.mesh) == 1);
    CHECK(weighed.stats.crossing_pairs == 0);
    // From the tetrahedron (sphere mode) the counter is the paper's whatever the parameter.
    p.topology = Topology::sphere;
    const Result sphere_weighed = reconstruct(torus, p);
    p.adaptivity = 0.0;
    const Result sphere_plain = reconstruct(torus, p);
    CHECK(sphere_weighed.mesh.positions == sphere_plain.mesh.positions);
    CHECK(sphere_weighed.mesh.triangles == sphere_plain.mesh.triangles);
    // The range.
    p.adaptivity = -0.1;
    CHECK_THROWS_AS(p.validate(), ParameterError);
    p.adaptivity = 101.0;
    CHECK_THROWS_AS(p.validate(), ParameterError);
}

TEST_CASE("where no genus persists, the start is the solid's genus-0 core") {
    // The tail fuses with the ball at a few places, a different number at each offset and on each
    // grid: no reading, and before the core the learning grew from the tetrahedron.
    const PointCloud cloud = tailed_ball(7);
    const SolidSurface s = solid_of(cloud);
    REQUIRE(s.walled);
    CHECK(s.offset <= kMaxShapeOffset);
    CHECK_FALSE(s.stable);
    CHECK(s.core);
    // The core's surfaces are spheres round the whole shape, the tail included (the box).
    REQUIRE_FALSE(s.surface.triangles.empty());
    REQUIRE_FALSE(s.fine_surface.triangles.empty());
    CHECK(genus_of(s.surface) == 0);
    CHECK(genus_of(s.fine_surface) == 0);
    const BoundingBox cloud_box = bounding_box(PointSpan(cloud.points));
    const BoundingBox box = bounding_box(PointSpan(cloud.points));
    const PointTransform frame{box.center(), float(1.0 / box.diagonal())};
    BoundingBox fine;
    for (const Vec3& p : s.fine_surface.positions) fine.extend(p);
    CHECK(fine.max.x > frame(cloud_box.max).x - 0.01f);  // the tail's far side (x, scaled to diagonal 1)
    const SolidStart start = solid_start(PointSpan(cloud.points), frame, 2000);
    REQUIRE(start.mesh.has_value());
    CHECK(start.core);
    CHECK(start.solid_genus == -1);
    CHECK_FALSE(start.surface.triangles.empty());  // the points' sides
    // Seeds whose first walled offset (3.5 d) is walled on a shifted grid only: the core is taken
    // at the next offset the first grid walls round itself.
    for (const std::uint64_t seed : {1u, 8u}) {
        const SolidSurface other = solid_of(tailed_ball(seed));
        CHECK(other.core);
        CHECK(other.offset == 4.0f);
    }

    if (test::kSanitized) return;  // the reconstruction's checks run in the plain build
    Parameters p;
    p.target_vertices = 3000;
    const Result r = reconstruct(cloud, p);
    CHECK(r.stats.start_core);
    CHECK(r.stats.solid_genus == -1);
    CHECK(r.stats.start_vertices == start_vertices(3000));
    CHECK(genus_of(r.mesh) == 0);
    CHECK(r.stats.crossing_pairs == 0);
    CHECK(r.stats.inward_faces == 0);
    // The core has the shape's parts: adaptivity weighs the signals from it, as from a read solid.
    p.adaptivity = 0.5;
    const Result weighed = reconstruct(cloud, p);
    CHECK(weighed.stats.start_core);
    CHECK_FALSE(weighed.mesh.positions == r.mesh.positions);
}

TEST_CASE("handles the offset makes between two parts are not read: their cuts cross no point") {
    // The tail fused with the ball at five places, over two offsets: a persisting genus 5 before
    // the false handles were told apart. Each cut of the solid's genus-0 core there crosses only
    // the gap between tail and ball; a handle of the object is cut across its material.
    const PointCloud cloud = tailed_ball(2, 0.03f);
    const SolidSurface s = solid_of(cloud);
    REQUIRE(s.stable);
    CHECK(s.false_handles == 5);
    CHECK(s.genus == 0);
    // A real handle is kept: the torus and the thin ring read genus 1 with none taken out.
    const PointCloud torus = test::torus_cloud(20000), ring = test::thin_ring_cloud(30000);
    for (const PointCloud* c : {&torus, &ring}) {
        const SolidSurface t = solid_of(*c);
        CHECK(t.genus == 1);
        CHECK(t.false_handles == 0);
    }
    if (test::kSanitized) return;
    Parameters p;
    p.target_vertices = 3000;
    const Result r = reconstruct(cloud, p);
    CHECK(r.stats.solid_genus == 0);
    CHECK(genus_of(r.mesh) == 0);
    CHECK(r.stats.crossing_pairs == 0);
    CHECK(r.stats.inward_faces == 0);
}
