// Property tests of manifoldness: long seeded random sequences of split / collapse / flip on
// meshes that grow and shrink, with the whole-mesh validator after every operation.
#include <doctest/doctest.h>

#include <cstdio>
#include <random>

#include "mesh_fixtures.h"
#include "nmesh/mesh.h"
#include "nmesh/mesh_check.h"

using namespace nmesh;
using nmesh::test::face_set;

namespace {

struct Tally {
    std::uint64_t splits = 0, collapses = 0, flips = 0, unflips = 0, refused = 0, undone_splits = 0;
    std::uint64_t total() const { return splits + collapses + flips + unflips + refused + undone_splits; }
};

Tally g_tally;  // summed over the suite and printed by the last test case

struct Walker {
    Mesh mesh;
    std::mt19937_64 rng;
    Tally& tally;
    std::uint32_t peak = 0;  // the most vertices alive at once

    std::uint32_t below(std::uint32_t n) { return std::uint32_t(rng() % n); }

    Vertex random_vertex() {
        for (;;) {
            const Vertex v(below(mesh.vertex_capacity()));
            if (!mesh.is_removed(v)) return v;
        }
    }
    Halfedge random_halfedge() {
        for (;;) {
            const Halfedge h(below(mesh.halfedge_capacity()));
            if (!mesh.is_removed(h)) return h;
        }
    }
    Halfedge rotate(Halfedge h, std::uint32_t steps) {
        while (steps--) h = mesh.ccw_rotated(h);
        return h;
    }

    void require_valid(const char* after) {
        const ManifoldCheck r = check_manifold(mesh);
        if (!r.ok) FAIL("invalid mesh after " << after << ": " << r.error);
        peak = std::max(peak, mesh.n_vertices());
    }

    void split() {
        const Vertex b = random_vertex();
        const std::uint32_t n = mesh.valence(b);
        const Halfedge to_c = rotate(mesh.halfedge(b), below(n));
        const Halfedge to_d = rotate(to_c, 1 + below(n - 1));  // any other outgoing half-edge
        const Vec3 p = mesh.position(b) + Vec3{0.01f, 0.02f, 0.03f};
        REQUIRE(mesh.can_split(to_c, to_d));
        const Vertex a = mesh.split(to_c, to_d, p);
        ++tally.splits;
        require_valid("split");
        CHECK(mesh.position(a) == p);
    }

    void split_and_undo() {
        const auto before = face_set(mesh);
        const Vertex b = random_vertex();
        const std::uint32_t n = mesh.valence(b);
        const Halfedge to_c = rotate(mesh.halfedge(b), below(n));
        const Vertex a = mesh.split(to_c, rotate(to_c, 1 + below(n - 1)), mesh.position(b));
        require_valid("split");
        const Halfedge ab = mesh.find_halfedge(a, b);
        REQUIRE(mesh.can_collapse(ab));  // always legal right after the split
        mesh.collapse(ab);
        require_valid("collapse undoing a split");
        CHECK(face_set(mesh) == before);
        ++tally.undone_splits;
    }

    void collapse() {
        const Halfedge h = random_halfedge();
        if (!mesh.can_collapse(h)) return refused(h, false);
        mesh.collapse(h);
        ++tally.collapses;
        require_valid("collapse");
    }

    void flip() {
        const Halfedge h = random_halfedge();
        if (!mesh.can_flip(h)) return refused(h, true);
        const Mesh before = (rng() % 8 == 0) ? mesh : Mesh();
        const FlipRecord r = mesh.flip(h);
        ++tally.flips;
        require_valid("flip");
        if (before.n_vertices() != 0) {  // now and then: undo and compare every array
            mesh.unflip(r);
            ++tally.unflips;
            require_valid("unflip");
            CHECK(mesh.same_arrays(before));
        }
    }

    // A refused operation must leave the mesh bit for bit as it was.
    void refused(Halfedge h, bool is_flip) {
        const Mesh before = mesh;
        const bool done = is_flip ? mesh.try_flip(h) : mesh.try_collapse(h);
        CHECK_FALSE(done);
        CHECK(mesh.same_arrays(before));
        ++tally.refused;
    }

    // Grows to `high` vertices, shrinks to `low`, `cycles` times; the operation mix depends on
    // the phase so the size oscillates and free slots are reused.
    void run(std::uint32_t low, std::uint32_t high, int cycles) {
        for (int c = 0; c < cycles; ++c) {
            while (mesh.n_vertices() < high) step(/*growing=*/true);
            while (mesh.n_vertices() > low) step(/*growing=*/false);
        }
    }

    void step(bool growing) {
        const std::uint32_t r = below(100);
        const std::uint32_t grow = growing ? 45 : 10;
        if (r < grow) split();
        else if (r < grow + 5) split_and_undo();
        else if (r < grow + 5 + (growing ? 20 : 55)) collapse();
        else flip();
    }
};

}  // namespace

TEST_CASE("random split/collapse/flip sequences keep a valid closed manifold") {
    Tally tally;
    for (std::uint64_t seed = 1; seed <= 24; ++seed) {
        CAPTURE(seed);
        Walker w{seed % 2 ? Mesh::tetrahedron() : nmesh::test::icosahedron(), std::mt19937_64(seed), tally};
        // Small meshes exercise the tetrahedron floor and the link condition; larger ones the
        // free lists over many cycles.
        const std::uint32_t high = seed % 3 == 0 ? 12 : (seed % 3 == 1 ? 60 : 150);
        w.peak = w.mesh.n_vertices();
        w.run(4, high, seed % 3 == 0 ? 60 : 8);
        // Free-list reuse: the arrays only grow when no slot is free, so they hold exactly as many
        // slots as the most vertices (and faces) ever alive at once.
        CHECK(w.mesh.vertex_capacity() == w.peak);
        CHECK(w.mesh.face_capacity() == 2 * w.peak - 4);
    }
    g_tally.splits += tally.splits;
    g_tally.collapses += tally.collapses;
    g_tally.flips += tally.flips;
    g_tally.unflips += tally.unflips;
    g_tally.refused += tally.refused;
    g_tally.undone_splits += tally.undone_splits;
    std::printf("mesh properties: %llu operations checked (%llu splits, %llu collapses, %llu flips, %llu unflips, "
                "%llu split+collapse round trips, %llu refused)\n",
                (unsigned long long)tally.total(), (unsigned long long)tally.splits,
                (unsigned long long)tally.collapses, (unsigned long long)tally.flips,
                (unsigned long long)tally.unflips, (unsigned long long)tally.undone_splits,
                (unsigned long long)tally.refused);
    CHECK(tally.total() >= 100000);
    CHECK(tally.refused > 0);
    CHECK(tally.collapses > 1000);
    CHECK(tally.flips > 1000);
}
