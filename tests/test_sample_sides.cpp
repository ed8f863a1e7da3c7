// The side of the surface each point was taken from (nmesh/learn/sample_sides.h), and the
// learning that lets a sample pull only a vertex facing its side (NeuralMesh::set_sample_sides):
// on a wall thinner than the mesh's edges the two sheets stay apart.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "cloud_fixtures.h"
#include "sanitized.h"
#include "nmesh/bounding_box.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/learn/neural_mesh.h"
#include "nmesh/learn/sample_sides.h"
#include "nmesh/learn/solid_start.h"
#include "nmesh/reconstruct.h"

using namespace nmesh;

namespace {

// reconstruct()'s frame: centred, a power-of-two scale.
PointTransform frame_of(const PointCloud& cloud) {
    const BoundingBox box = bounding_box(PointSpan(cloud.points));
    return PointTransform{box.center(), float(std::ldexp(1.0, -std::ilogb(box.diagonal()) - 1))};
}

constexpr float kWall = 0.02f;  // the ring's wall: about 2 median spacings at 20,000 points

}  // namespace

TEST_CASE("a point's side is its own face's outward normal, on both faces of a thin wall") {
    const PointCloud ring = test::thin_ring_cloud(20000, kWall);
    const PointTransform frame = frame_of(ring);
    const SolidStart start = solid_start(PointSpan(ring.points), frame, 3000);
    REQUIRE(start.solid_genus == 1);
    REQUIRE_FALSE(start.surface.triangles.empty());
    const std::vector<Vec3> sides = sample_sides(PointSpan(ring.points), frame, start.surface, start.reach);
    REQUIRE(sides.size() == ring.points.size());
    std::size_t wall = 0, right = 0;
    for (std::size_t i = 0; i < ring.points.size(); ++i) {
        const Vec3 p = ring.points[i];
        const float r = std::sqrt(p.x * p.x + p.y * p.y);
        // The cylinders' points only, away from the ends and the boss.
        if (p.z < 0.05f || p.z > 0.45f || p.x > 0.8f) continue;
        const Vec3 radial{p.x / r, p.y / r, 0.0f};
        const float outward = r > 1.0f + 0.5f * kWall ? 1.0f : -1.0f;  // the outer face's, or the inner's
        CHECK(std::abs(norm(sides[i]) - 1.0f) < 1e-4f);
        ++wall;
        right += dot(sides[i], radial) * outward > 0.0f;
    }
    REQUIRE(wall > 5000);
    INFO(right << " of " << wall << " points on the walls have their face's side");
    CHECK(double(right) >= 0.98 * double(wall));
    // No surface, no sides.
    CHECK(sample_sides(PointSpan(ring.points), frame, IndexedMesh{}, 1.0f).empty());
}

// The crossing pairs of `mesh` (in `frame`) between a face of the wall's inner sheet and one of
// its outer sheet, on the cylinders away from the ends and the boss (the two sheets by the
// radius of their centres, the wall's middle between them).
std::size_t sheet_crossings(const IndexedMesh& mesh, const PointTransform& frame) {
    auto centre = [&](std::uint32_t t) {
        Vec3 c{0.0f, 0.0f, 0.0f};
        for (std::uint32_t v : mesh.triangles[t]) c = c + (mesh.positions[v] * (1.0f / frame.scale) + frame.center);
        return c * (1.0f / 3.0f);
    };
    auto sheet = [&](std::uint32_t t) {  // 0 inner, 1 outer, -1 neither
        const Vec3 c = centre(t);
        if (c.z < 0.05f || c.z > 0.45f || c.x > 0.8f) return -1;
        return std::sqrt(c.x * c.x + c.y * c.y) > 1.0f + 0.5f * kWall ? 1 : 0;
    };
    std::size_t n = 0;
    for (const auto& [s, t] : self_intersecting_pairs(mesh)) {
        const int a = sheet(s), b = sheet(t);
        n += a >= 0 && b >= 0 && a != b;
    }
    return n;
}

TEST_CASE("with the samples' sides the two sheets of a thin wall learn without crossing each other") {
    const PointCloud ring = test::thin_ring_cloud(20000, kWall);
    const PointTransform frame = frame_of(ring);
    BoundingBox bounds;
    for (const Vec3& p : ring.points) bounds.extend(frame(p));
    const SolidStart start = solid_start(PointSpan(ring.points), frame, 3000);
    REQUIRE(start.mesh.has_value());
    const std::vector<Vec3> sides = sample_sides(PointSpan(ring.points), frame, start.surface, start.reach);
    for (const std::uint64_t seed : {1, 2, 3}) {
        if (test::kSanitized && seed > 1) break;
        Parameters params;
        params.target_vertices = 3000;
        params.seed = seed;
        // The learning from the solid's surface (two sheets on every wall), with and without sides.
        std::size_t crossing[2] = {0, 0}, between[2] = {0, 0};
        std::uint64_t skipped[2] = {0, 0};
        for (const bool with_sides : {true, false}) {
            NeuralMesh engine(PointSpan(ring.points), bounds, params, frame, *start.mesh);
            engine.keep_genus();
            if (with_sides) engine.set_sample_sides(sides.data());
            while (engine.mesh().n_vertices() < params.target_vertices) engine.iterate();
            CHECK(engine.check_consistency().empty());
            Mesh learnt = engine.take_mesh();
            learnt.build_faces();
            const IndexedMesh indexed = learnt.to_indexed();
            crossing[with_sides] = count_self_intersections(indexed);
            between[with_sides] = sheet_crossings(indexed, frame);
            skipped[with_sides] = engine.stats().side_skips;
        }
        INFO("seed " << seed << ": crossing pairs with sides " << crossing[1] << " (" << between[1]
                     << " between the sheets), without " << crossing[0] << " (" << between[0] << ")");
        CHECK(between[0] > 100);  // the defect the sides are there for
        CHECK(between[1] == 0);
        // What remains are folds of one sheet where it turns round the wall's ends (2-15 pairs on
        // seeds 1-8), which the finishing stage and the output check take out: the whole
        // reconstruction below.
        CHECK(crossing[1] * 50 < crossing[0]);
        CHECK(skipped[1] > 0);
        CHECK(skipped[0] == 0);
    }
}

TEST_CASE("the thin-walled ring reconstructs with its genus and no crossing pair") {
    const PointCloud ring = test::thin_ring_cloud(20000, kWall);
    for (const std::uint64_t seed : {1, 2}) {
        if (test::kSanitized && seed > 1) break;
        Parameters params;
        params.target_vertices = 3000;
        params.seed = seed;
        const Result r = reconstruct(ring.points, params);
        INFO("seed " << seed);
        CHECK(r.stats.solid_genus == 1);
        CHECK(r.stats.crossing_pairs == 0);
        CHECK(r.stats.inward_faces == 0);
        CHECK(r.stats.genus == 1);
    }
}
