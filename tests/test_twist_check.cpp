// The learning's checkpoints against twists (reconstruct(), topology closed and open): the
// largest region of inward faces against a brute-force count, on meshes with and without an
// inside-out part, and the checkpoints' effect on learnt meshes of the bundled bunny.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "cloud_fixtures.h"
#include "engine_checks.h"
#include "mesh_fixtures.h"
#include "sanitized.h"
#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/learn/neural_mesh.h"
#include "nmesh/learn/twist_check.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/reconstruct.h"
#include "nmesh/util/random.h"

using namespace nmesh;
using namespace nmesh::test;

namespace {

// The largest region of inward faces by flood fill over every pair of faces (two faces are
// neighbours when they share two vertices). O(F^2).
std::size_t brute_force_region(const IndexedMesh& m) {
    const std::vector<std::uint8_t> inward = inward_face_flags(m, TriangleBvh(m));
    const std::size_t f = m.triangles.size();
    const auto shared = [&](std::size_t a, std::size_t b) {
        int n = 0;
        for (std::uint32_t u : m.triangles[a])
            for (std::uint32_t v : m.triangles[b]) n += u == v;
        return n;
    };
    std::vector<bool> seen(f, false);
    std::size_t largest = 0;
    for (std::size_t s = 0; s < f; ++s) {
        if (!inward[s] || seen[s]) continue;
        std::vector<std::size_t> stack{s};
        seen[s] = true;
        std::size_t size = 0;
        while (!stack.empty()) {
            const std::size_t a = stack.back();
            stack.pop_back();
            ++size;
            for (std::size_t b = 0; b < f; ++b)
                if (inward[b] && !seen[b] && shared(a, b) == 2) {
                    seen[b] = true;
                    stack.push_back(b);
                }
        }
        largest = std::max(largest, size);
    }
    return largest;
}

// A unit sphere whose cap above z = 0.7 is pushed down by 2.2, through the bottom: below the
// sphere it hangs as a bag turned inside out (the faces of the cap and of the bag's wall there
// face its inside).
IndexedMesh pushed_through_sphere() {
    IndexedMesh m = icosphere(3);
    for (Vec3& p : m.positions)
        if (p.z > 0.7f) p.z -= 2.2f;
    return m;
}

// The seeds a test learns: all of them, or the first alone in the sanitizer build (sanitized.h).
std::vector<std::uint64_t> seeds_to_learn(std::vector<std::uint64_t> all) {
    if (kSanitized) all.resize(1);
    return all;
}

// Parameters for a run of the bundled clouds at 1,000 vertices.
Parameters thousand_vertices(std::uint64_t seed) {
    Parameters p;
    p.target_vertices = 1000;
    p.seed = seed;
    return p;
}

}  // namespace

TEST_CASE("the largest inward region: none on a sphere, the inside-out bag of a pushed-through one") {
    const IndexedMesh sphere = icosphere(3);
    CHECK(largest_inward_region(Mesh::from_indexed(sphere)) == 0);
    CHECK(brute_force_region(sphere) == 0);

    const IndexedMesh pushed = pushed_through_sphere();
    const std::size_t region = largest_inward_region(Mesh::from_indexed(pushed));
    CHECK(region == brute_force_region(pushed));
    // The cap alone has 10% of the faces, all of them inward.
    CHECK(region >= pushed.triangles.size() / 10);
    CHECK(region < pushed.triangles.size() / 2);
}

TEST_CASE("the largest inward region equals a brute-force flood fill on randomly folded spheres") {
    Random rng(11);
    int with_inward = 0;
    for (int trial = 0; trial < 12; ++trial) {
        IndexedMesh m = icosphere(2);
        // Pull random vertices far through the sphere: folds and tangles of every size.
        const int moved = 1 + trial;
        for (int i = 0; i < moved; ++i) {
            Vec3& p = m.positions[rng.below(std::uint32_t(m.positions.size()))];
            p = p * float(-0.2 - rng.uniform());
        }
        const std::size_t region = largest_inward_region(Mesh::from_indexed(m));
        CHECK(region == brute_force_region(m));
        with_inward += region > 0;
    }
    CHECK(with_inward >= 6);  // the comparison saw defects
}

TEST_CASE("checkpoints: the learnt mesh keeps no inward region above the tolerance; sphere mode has none") {
    // Seeds of the bundled bunny at 1,000 vertices whose learning, left alone, turns a region
    // inside out before the target (found with --stats twist_retries).
    const PointCloud bunny = bundled_bunny();
    std::uint64_t retries = 0;
    std::size_t unchecked_largest = 0;
    const std::vector<std::uint64_t> seeds = seeds_to_learn({3, 6, 19});
    for (std::uint64_t seed : seeds) {
        Parameters p = thousand_vertices(seed);
        p.finish = false;
        p.solid_start = false;  // grown from the tetrahedron, where the twists form
        const Result closed = reconstruct(bunny.points, p);
        retries += closed.stats.twist_retries;
        CHECK(closed.stats.twist_checks >= 7);  // 16 ... 512 and the target
        CHECK(closed.stats.twists_kept == 0);
        // The last checkpoint is the target: what it accepted is what comes out.
        CHECK(largest_inward_region(Mesh::from_indexed(closed.mesh)) <= 3);

        p.topology = Topology::sphere;
        const Result sphere = reconstruct(bunny.points, p);
        CHECK(sphere.stats.twist_checks == 0);
        unchecked_largest = std::max(unchecked_largest, largest_inward_region(Mesh::from_indexed(sphere.mesh)));
    }
    CHECK(retries >= seeds.size());
    CHECK(unchecked_largest > 3);  // without the checkpoints the test above would fail (seed 3: 6)
}

TEST_CASE("a compact checkpoint assigned back learns the same bits; a reseeded one another mesh") {
    const PointCloud cloud = sphere_cloud(4000, 1.0f, {0.5f, 0, 0});
    Parameters p;
    p.target_vertices = 600;
    const BoundingBox box = bounding_box(cloud.points);
    NeuralMesh engine(cloud.points, box, p);
    while (engine.mesh().n_vertices() < 150) engine.iterate();
    NeuralMesh saved = engine;
    saved.compact();
    nmesh::test::require_engine_valid(saved);
    NeuralMesh other = saved;
    other.reseed(1);
    const auto learn_on = [&](NeuralMesh& e) {
        for (int i = 0; i < 20000; ++i) e.iterate();
        nmesh::test::require_engine_valid(e);
        return e.mesh().to_indexed();
    };
    const IndexedMesh straight = learn_on(engine);
    engine = saved;  // back to the checkpoint
    const IndexedMesh again = learn_on(engine);
    CHECK(again.positions == straight.positions);
    CHECK(again.triangles == straight.triangles);
    // The compact copy itself, grown without the reserved room, learns the same too.
    const IndexedMesh from_copy = learn_on(saved);
    CHECK(from_copy.positions == straight.positions);
    const IndexedMesh reseeded = learn_on(other);
    CHECK(reseeded.positions != straight.positions);
}

TEST_CASE("a small target whose output is not valid is learnt again from the checkpoint before it") {
    // The thin-walled ring at 3,000 vertices: seeds 2, 4 and 5 finish with crossing triangles
    // where a sheet turns round the wall's end on their first path (found with --stats
    // output_retries; the ball on thin legs at 1,000 vertices, which did before the solid's
    // splats, now finishes valid on every seed of 1-40).
    const PointCloud ring = test::thin_ring_cloud(20000, 0.02f);
    int retried_valid = 0;
    for (std::uint64_t seed : seeds_to_learn({4, 2, 5})) {
        Parameters p = thousand_vertices(seed);
        p.target_vertices = 3000;
        const Result r = reconstruct(ring.points, p);
        INFO("seed " << seed);
        CHECK(r.mesh.positions.size() == 3000);
        const bool valid = r.stats.crossing_pairs == 0 && r.stats.inward_faces == 0;
        // An invalid output only after every retry, or once the checkpoints have stopped.
        if (!valid) CHECK((r.stats.output_retries == 3 || r.stats.twists_kept > 0));
        if (valid && r.stats.output_retries > 0) ++retried_valid;
        if (seed == 4 && !kSanitized) {
            const Result again = reconstruct(ring.points, p);
            CHECK(again.mesh.positions == r.mesh.positions);
            CHECK(again.stats.output_retries == r.stats.output_retries);
        }
        // Without the finishing stage the learnt mesh is returned as it is, never retried.
        p.finish = false;
        CHECK(reconstruct(ring.points, p).stats.output_retries == 0);
    }
    CHECK(retried_valid >= (kSanitized ? 1 : 2));
}
