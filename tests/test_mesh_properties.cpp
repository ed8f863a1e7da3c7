// Property tests of manifoldness: long seeded random sequences of split / collapse / flip on
// meshes that grow and shrink, with the whole-mesh validator after every operation; and the same
// kind of sequences checked slot by slot against a brute-force model of what is alive and of the
// free lists' order.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "mesh_fixtures.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"

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
        if (!r.sphere()) FAIL("invalid mesh after " << after << ": " << r.error);
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
        if (r < grow)
            split();
        else if (r < grow + 5)
            split_and_undo();
        else if (r < grow + 5 + (growing ? 20 : 55))
            collapse();
        else
            flip();
    }
};

}  // namespace

namespace {

// A brute-force model of one kind of slot, kept by the test beside the mesh: which slots are
// alive, and the free slots as a stack (back = the next one reused).
struct SlotModel {
    std::vector<std::uint8_t> alive;
    std::vector<std::uint32_t> free;

    explicit SlotModel(std::uint32_t n) : alive(n, 1) {}
    std::uint32_t take() {
        if (free.empty()) {
            alive.push_back(1);
            return std::uint32_t(alive.size() - 1);
        }
        const std::uint32_t s = free.back();
        free.pop_back();
        alive[s] = 1;
        return s;
    }
    void release(std::uint32_t s) {
        REQUIRE(alive[s] == 1);
        alive[s] = 0;
        free.push_back(s);
    }
    std::uint32_t count() const { return std::uint32_t(std::count(alive.begin(), alive.end(), 1)); }
    // The free list as the mesh should link it: from its head, the last slot freed, down.
    std::vector<std::uint32_t> list() const { return {free.rbegin(), free.rend()}; }
};

template <class Next>
std::vector<std::uint32_t> walk_free_list(std::uint32_t head, std::size_t capacity, Next next) {
    std::vector<std::uint32_t> list;
    for (std::uint32_t s = head; s != kInvalidIndex && list.size() <= capacity; s = next(s)) list.push_back(s);
    return list;
}

struct ModelWalker {
    Mesh mesh;
    std::mt19937_64 rng;
    SlotModel v{mesh.vertex_capacity()}, e{mesh.edge_capacity()}, f{mesh.face_capacity()};
    std::uint64_t splits = 0, collapses = 0, flips = 0;

    std::uint32_t below(std::uint32_t n) { return std::uint32_t(rng() % n); }
    // A random alive slot, chosen by the model (not by is_removed, which is under test).
    static std::uint32_t pick(const SlotModel& m, std::uint32_t r) {
        std::vector<std::uint32_t> alive;
        for (std::uint32_t s = 0; s < m.alive.size(); ++s)
            if (m.alive[s]) alive.push_back(s);
        return alive[r % alive.size()];
    }
    Halfedge random_halfedge() { return Mesh::halfedge(Edge(pick(e, below(1u << 30))), int(below(2))); }

    // The mesh and the model agree on every slot, the counts, the capacities and the free lists.
    void require_agreement(const char* after) {
        INFO("after " << after);
        REQUIRE(mesh.vertex_capacity() == v.alive.size());
        REQUIRE(mesh.edge_capacity() == e.alive.size());
        REQUIRE(mesh.face_capacity() == f.alive.size());
        // The first slot where is_removed disagrees with the model, or kInvalidIndex.
        auto first_wrong = [](const SlotModel& m, auto removed) {
            for (std::uint32_t s = 0; s < m.alive.size(); ++s)
                if (removed(s) != !m.alive[s]) return s;
            return kInvalidIndex;
        };
        CHECK(first_wrong(v, [&](std::uint32_t s) { return mesh.is_removed(Vertex(s)); }) == kInvalidIndex);
        CHECK(first_wrong(f, [&](std::uint32_t s) { return mesh.is_removed(Face(s)); }) == kInvalidIndex);
        CHECK(first_wrong(e, [&](std::uint32_t s) { return mesh.is_removed(Edge(s)); }) == kInvalidIndex);
        CHECK(first_wrong(e, [&](std::uint32_t s) { return mesh.is_removed(Mesh::halfedge(Edge(s), 0)); }) ==
              kInvalidIndex);
        CHECK(first_wrong(e, [&](std::uint32_t s) { return mesh.is_removed(Mesh::halfedge(Edge(s), 1)); }) ==
              kInvalidIndex);
        REQUIRE(mesh.n_vertices() == v.count());
        REQUIRE(mesh.n_edges() == e.count());
        REQUIRE(mesh.n_faces() == f.count());
        REQUIRE(walk_free_list(mesh.free_vertex_head(), v.alive.size(),
                               [&](std::uint32_t s) { return mesh.next_free_vertex(s); }) == v.list());
        REQUIRE(walk_free_list(mesh.free_edge_head(), e.alive.size(),
                               [&](std::uint32_t s) { return mesh.next_free_edge(s); }) == e.list());
        REQUIRE(walk_free_list(mesh.free_face_head(), f.alive.size(),
                               [&](std::uint32_t s) { return mesh.next_free_face(s); }) == f.list());
    }

    // The slots a split takes, in this order: vertex a; edges a-b, b-c, d-b; faces (a, b, c),
    // (b, a, d); each from its free list's head, else a new slot.
    void split() {
        const Vertex b(pick(v, below(1u << 30)));
        const std::uint32_t n = mesh.valence(b);
        Halfedge to_c = mesh.halfedge(b);
        for (std::uint32_t i = below(n); i > 0; --i) to_c = mesh.ccw_rotated(to_c);
        Halfedge to_d = to_c;
        for (std::uint32_t i = 1 + below(n - 1); i > 0; --i) to_d = mesh.ccw_rotated(to_d);
        const Vertex c = mesh.to(to_c), d = mesh.to(to_d);
        REQUIRE(mesh.can_split(to_c, to_d));
        const std::uint32_t a = v.take(), ab = e.take(), bc = e.take(), db = e.take(), f0 = f.take(), f1 = f.take();
        REQUIRE(mesh.split(to_c, to_d, mesh.position(b)).idx == a);
        const Halfedge h = Mesh::halfedge(Edge(ab), 0);
        REQUIRE((mesh.from(h) == Vertex(a) && mesh.to(h) == b));
        REQUIRE((mesh.from(Mesh::halfedge(Edge(bc), 0)) == b && mesh.to(Mesh::halfedge(Edge(bc), 0)) == c));
        REQUIRE((mesh.from(Mesh::halfedge(Edge(db), 0)) == d && mesh.to(Mesh::halfedge(Edge(db), 0)) == b));
        REQUIRE((mesh.face(h).idx == f0 && mesh.face(Mesh::twin(h)).idx == f1));
        ++splits;
        require_agreement("split");
    }

    // The slots a collapse of h frees, in this order: faces of h and of twin(h); edges of h,
    // next(h), prev(twin(h)); vertex from(h).
    void collapse() {
        const Halfedge h = random_halfedge();
        if (!mesh.can_collapse(h)) return;
        const Halfedge t = Mesh::twin(h);
        const std::uint32_t fh = mesh.face(h).idx, ft = mesh.face(t).idx;
        const std::uint32_t eh = Mesh::edge(h).idx, en = Mesh::edge(mesh.next(h)).idx,
                            ep = Mesh::edge(mesh.prev(t)).idx;
        const std::uint32_t a = mesh.from(h).idx;
        mesh.collapse(h);
        f.release(fh);
        f.release(ft);
        e.release(eh);
        e.release(en);
        e.release(ep);
        v.release(a);
        ++collapses;
        require_agreement("collapse");
    }

    void flip() {
        const Halfedge h = random_halfedge();
        if (!mesh.can_flip(h)) return;
        const Mesh before = mesh;
        const FlipRecord r = mesh.flip(h);
        ++flips;
        require_agreement("flip");
        if (below(4) == 0) {
            mesh.unflip(r);
            REQUIRE(mesh.same_arrays(before));
        }
    }

    void step(bool growing) {
        const std::uint32_t r = below(100);
        if (r < (growing ? 50u : 15u))
            split();
        else if (r < 75)
            collapse();
        else
            flip();
    }
};

}  // namespace

TEST_CASE("is_removed and the free lists agree with a brute-force model after random operations") {
    std::uint64_t splits = 0, collapses = 0, flips = 0;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        CAPTURE(seed);
        ModelWalker w{seed % 2 ? Mesh::tetrahedron() : nmesh::test::icosahedron(), std::mt19937_64(seed)};
        w.require_agreement("construction");
        const std::uint32_t high = seed % 4 == 0 ? 20 : 80;
        for (int cycle = 0; cycle < 6; ++cycle) {
            while (w.mesh.n_vertices() < high) w.step(/*growing=*/true);
            while (w.mesh.n_vertices() > 6) w.step(/*growing=*/false);
        }
        REQUIRE(check_manifold(w.mesh).sphere());
        splits += w.splits;
        collapses += w.collapses;
        flips += w.flips;
    }
    std::printf("is_removed model: %llu splits, %llu collapses, %llu flips checked\n", (unsigned long long)splits,
                (unsigned long long)collapses, (unsigned long long)flips);
    // Enough of each for the free lists to fill, empty and reorder many times.
    CHECK(splits > 1000);
    CHECK(collapses > 1000);
    CHECK(flips > 1000);
}

namespace {

// Every half-edge, edge and vertex field of two meshes, ignoring the face index: a mesh without
// it must keep the same connectivity, slot for slot, as one with it.
void require_same_connectivity(const Mesh& with, const Mesh& without, const char* after) {
    INFO("after " << after);
    REQUIRE(with.halfedge_capacity() == without.halfedge_capacity());
    REQUIRE(with.vertex_capacity() == without.vertex_capacity());
    REQUIRE((with.n_vertices() == without.n_vertices() && with.n_edges() == without.n_edges() &&
             with.n_faces() == without.n_faces()));
    REQUIRE(with.free_vertex_head() == without.free_vertex_head());
    REQUIRE(with.free_edge_head() == without.free_edge_head());
    for (std::uint32_t h = 0; h < with.halfedge_capacity(); ++h) {
        REQUIRE(with.is_removed(Halfedge(h)) == without.is_removed(Halfedge(h)));
        if (with.is_removed(Halfedge(h))) continue;
        REQUIRE(
            (with.to(Halfedge(h)) == without.to(Halfedge(h)) && with.next(Halfedge(h)) == without.next(Halfedge(h))));
    }
    for (std::uint32_t v = 0; v < with.vertex_capacity(); ++v) {
        REQUIRE(with.is_removed(Vertex(v)) == without.is_removed(Vertex(v)));
        if (!with.is_removed(Vertex(v))) REQUIRE(with.halfedge(Vertex(v)) == without.halfedge(Vertex(v)));
    }
}

}  // namespace

TEST_CASE("without the face index, random operations keep the same connectivity and a valid manifold") {
    std::uint64_t ops = 0, builds = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        CAPTURE(seed);
        std::mt19937_64 rng(seed);
        Mesh with = seed % 2 ? Mesh::tetrahedron() : nmesh::test::icosahedron();
        Mesh without = with;
        without.drop_faces();
        auto below = [&](std::uint32_t n) { return std::uint32_t(rng() % n); };
        auto random_halfedge = [&] {
            for (;;) {
                const Halfedge h(below(with.halfedge_capacity()));
                if (!with.is_removed(h)) return h;
            }
        };
        for (int cycle = 0; cycle < 4; ++cycle) {
            for (const bool growing : {true, false}) {
                while (growing ? with.n_vertices() < 120 : with.n_vertices() > 6) {
                    const std::uint32_t r = below(100);
                    const char* what = "flip";
                    if (r < (growing ? 45u : 10u)) {
                        what = "split";
                        const Halfedge to_c = random_halfedge();
                        Halfedge to_d = to_c;
                        for (std::uint32_t i = 1 + below(with.valence(with.from(to_c)) - 1); i > 0; --i)
                            to_d = with.ccw_rotated(to_d);
                        const Vec3 p{float(below(1000)), 0.5f, -0.25f};
                        REQUIRE(with.split(to_c, to_d, p) == without.split(to_c, to_d, p));
                    } else if (r < 75) {
                        what = "collapse";
                        const Halfedge h = random_halfedge();
                        REQUIRE(with.can_collapse(h) == without.can_collapse(h));
                        if (with.can_collapse(h)) {
                            with.collapse(h);
                            without.collapse(h);
                        }
                    } else {
                        const Halfedge h = random_halfedge();
                        REQUIRE(with.can_flip(h) == without.can_flip(h));
                        if (with.can_flip(h)) {
                            with.flip(h);
                            const Mesh before = without;
                            const FlipRecord rec = without.flip(h);
                            if (below(4) == 0) {  // undone and done again: every array restored
                                without.unflip(rec);
                                REQUIRE(without.same_arrays(before));
                                without.flip(h);
                            }
                        }
                    }
                    ++ops;
                    require_same_connectivity(with, without, what);
                    const ManifoldCheck c = check_manifold(without);
                    if (!c.sphere()) FAIL("invalid mesh without faces after " << what << ": " << c.error);
                    if (below(16) == 0) {
                        // The index built at any time: valid, and the same triangles as tracked.
                        Mesh built = without;
                        built.build_faces();
                        REQUIRE(check_manifold(built).sphere());
                        REQUIRE(nmesh::test::face_set(built) == nmesh::test::face_set(with));
                        REQUIRE(built.to_indexed().triangles == without.to_indexed().triangles);
                        ++builds;
                    }
                }
            }
        }
    }
    std::printf("face index: %llu operations without it, %llu builds checked\n", (unsigned long long)ops,
                (unsigned long long)builds);
    CHECK(ops > 2000);
    CHECK(builds > 100);
}

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
    std::printf(
        "mesh properties: %llu operations checked (%llu splits, %llu collapses, %llu flips, %llu unflips, "
        "%llu split+collapse round trips, %llu refused)\n",
        (unsigned long long)tally.total(), (unsigned long long)tally.splits, (unsigned long long)tally.collapses,
        (unsigned long long)tally.flips, (unsigned long long)tally.unflips, (unsigned long long)tally.undone_splits,
        (unsigned long long)tally.refused);
    CHECK(tally.total() >= 100000);
    CHECK(tally.refused > 0);
    CHECK(tally.collapses > 1000);
    CHECK(tally.flips > 1000);
}
