// The ring cache against the half-edge mesh it is derived from: the rings it holds, their
// refresh after each kind of topology operation, vertices above its capacity, and its check().
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh_fixtures.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/util/random.h"
#include "nmesh/learn/ring_cache.h"

using namespace nmesh;

namespace {

std::vector<std::uint32_t> walked_ring(const Mesh& m, Vertex v) {
    std::vector<std::uint32_t> ring;
    m.for_each_outgoing_cw(v, [&](Halfedge h) { ring.push_back(m.to(h).idx); });
    return ring;
}

void refresh_all(RingCache& cache, const Mesh& m) {
    for (std::uint32_t v = 0; v < m.vertex_capacity(); ++v)
        if (!m.is_removed(Vertex(v))) cache.refresh(m, Vertex(v));
}

// A bipyramid over an n-gon: two apexes of valence n, equator vertices of valence 4.
Mesh bipyramid(std::uint32_t n) {
    IndexedMesh m;
    for (std::uint32_t i = 0; i < n; ++i) {
        const float a = 6.2831853f * float(i) / float(n);
        m.positions.push_back({std::cos(a), std::sin(a), 0.0f});
    }
    m.positions.push_back({0, 0, 1});   // n: top
    m.positions.push_back({0, 0, -1});  // n + 1: bottom
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t j = (i + 1) % n;
        m.triangles.push_back({i, j, n});
        m.triangles.push_back({j, i, n + 1});
    }
    return Mesh::from_indexed(m);
}

}  // namespace

TEST_CASE("the cache holds each vertex's neighbours clockwise from its stored half-edge") {
    const Mesh m = nmesh::test::icosahedron();
    RingCache cache;
    refresh_all(cache, m);
    CHECK(cache.check(m).empty());
    for (std::uint32_t v = 0; v < m.n_vertices(); ++v) {
        const std::vector<std::uint32_t> ring = walked_ring(m, Vertex(v));
        REQUIRE(cache.count(Vertex(v)) == ring.size());
        CHECK(std::vector<std::uint32_t>(cache.neighbours(Vertex(v)), cache.neighbours(Vertex(v)) + ring.size()) ==
              ring);
    }
}

TEST_CASE("vertices with more neighbours than the cache holds are marked, not truncated") {
    const Mesh m = bipyramid(RingCache::kCapacity + 5);  // apexes of valence 20
    RingCache cache;
    refresh_all(cache, m);
    const Vertex top(RingCache::kCapacity + 5), bottom(RingCache::kCapacity + 6);
    CHECK(cache.count(top) == 0);
    CHECK(cache.count(bottom) == 0);
    CHECK(cache.count(Vertex(0)) == 4);
    CHECK(cache.check(m).empty());
    // Exactly at the capacity: still cached.
    const Mesh full = bipyramid(RingCache::kCapacity);
    RingCache cache2;
    refresh_all(cache2, full);
    CHECK(cache2.count(Vertex(RingCache::kCapacity)) == RingCache::kCapacity);
    // A lower limit marks the equator's valence-4 vertices too.
    cache2.set_limit(3);
    refresh_all(cache2, full);
    CHECK(cache2.count(Vertex(0)) == 0);
    CHECK(cache2.check(full).empty());
}

TEST_CASE("check() finds a stale ring, a ring marked wrongly and a missing vertex") {
    Mesh m = nmesh::test::icosahedron();
    RingCache cache;
    refresh_all(cache, m);
    // A flip changes four rings; without a refresh the cache no longer matches.
    const Halfedge h = m.halfedge(Vertex(0));
    REQUIRE(m.can_flip(h));
    m.flip(h);
    CHECK(!cache.check(m).empty());
    refresh_all(cache, m);
    CHECK(cache.check(m).empty());
    // Valence 5 marked as not cached although the limit allows it.
    cache.set_limit(4);
    cache.refresh(m, Vertex(3));
    cache.set_limit(RingCache::kCapacity);
    CHECK(cache.check(m).find("marked as not cached") != std::string::npos);
    RingCache empty;
    CHECK(empty.check(m).find("has no ring") != std::string::npos);
}

TEST_CASE("refreshing what each operation changes keeps the cache equal to the mesh") {
    // Random splits, collapses and flips; after each, the refresh the learning engine does:
    // around the new vertex of a split and the split vertex itself, around the remaining vertex
    // of a collapse, the four vertices of a flip. The whole cache is compared with the mesh every time.
    Mesh m = nmesh::test::icosahedron();
    RingCache cache;
    refresh_all(cache, m);
    Random rng(17);
    int splits = 0, collapses = 0, flips = 0;
    for (int step = 0; step < 3000; ++step) {
        const Halfedge h(rng.below(m.halfedge_capacity()));
        if (m.is_removed(h)) continue;
        const std::uint32_t op = rng.below(3);
        if (op == 0 || m.n_vertices() < 20) {
            // Split from(h): hand over the half-edges from h to 2 or 3 steps counter-clockwise.
            Halfedge to_d = m.ccw_rotated(h);
            if (rng.below(2) == 1) to_d = m.ccw_rotated(to_d);
            const Vertex b = m.from(h);
            const Vertex a = m.try_split(h, to_d, (m.position(b) + m.position(m.to(h))) * 0.5f);
            if (!a.valid()) continue;
            cache.refresh_around(m, a);
            cache.refresh(m, b);
            ++splits;
        } else if (op == 1) {
            const Vertex b = m.to(h);
            if (!m.try_collapse(h)) continue;
            cache.refresh_around(m, b);
            ++collapses;
        } else {
            const Vertex ends[4] = {m.from(h), m.to(h), m.to(m.next(h)), m.to(m.next(Mesh::twin(h)))};
            if (!m.try_flip(h)) continue;
            for (const Vertex v : ends) cache.refresh(m, v);
            ++flips;
        }
        const std::string err = cache.check(m);
        INFO("step " << step << ": " << err);
        REQUIRE(err.empty());
    }
    CHECK(check_manifold(m).sphere());
    CHECK(splits > 100);
    CHECK(collapses > 100);
    CHECK(flips > 100);
}
