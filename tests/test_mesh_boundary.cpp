// Boundaries and handles in the half-edge mesh: meshes with holes built and checked, face
// removal and loop joining with each of their refusals, the closed-mesh operations refused next
// to a boundary, and random sequences of all five operations under the validator, its counts of
// loops and genus checked against a brute-force count from the triangles.
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <utility>

#include "engine_checks.h"
#include "mesh_fixtures.h"
#include "nmesh/error.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "topology_fixtures.h"

using namespace nmesh;
using nmesh::test::fan_disk;
using nmesh::test::icosahedron;
using nmesh::test::torus_grid;

namespace {

ManifoldCheck require_valid(const Mesh& m) { return test::require_valid_mesh(m); }

// Loops and genus from the triangles alone: boundary edges are those in one triangle, chained
// through their vertices (one outgoing boundary edge per vertex on a manifold).
struct BruteTopology {
    long long euler = 0;
    std::uint32_t loops = 0;
    int genus = 0;
};
BruteTopology brute_topology(const IndexedMesh& m) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const auto& t : m.triangles)
        for (int i = 0; i < 3; ++i) ++directed[{t[i], t[(i + 1) % 3]}];
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::map<std::uint32_t, std::uint32_t> boundary_next;  // boundary edge b -> a, keyed by b
    for (const auto& [e, n] : directed) {
        edges.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
        if (!directed.count({e.second, e.first})) boundary_next[e.second] = e.first;
    }
    BruteTopology r;
    std::set<std::uint32_t> seen;
    for (const auto& [start, unused] : boundary_next) {
        (void)unused;
        if (seen.count(start)) continue;
        ++r.loops;
        for (std::uint32_t v = start; !seen.count(v); v = boundary_next.at(v)) seen.insert(v);
    }
    r.euler = (long long)m.positions.size() - (long long)edges.size() + (long long)m.triangles.size();
    r.genus = int((2 - r.euler - r.loops) / 2);
    return r;
}

void check_against_brute(const Mesh& m) {
    const ManifoldCheck c = require_valid(m);
    const BruteTopology b = brute_topology(m.to_indexed());
    CHECK(c.euler == b.euler);
    CHECK(c.boundary_loops == b.loops);
    CHECK(c.genus == b.genus);
}

// The face with the given corners (any rotation), or an invalid handle.
Face find_face(const Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Halfedge h = m.find_halfedge(Vertex(a), Vertex(b));
    if (!h.valid() || m.is_boundary(h) || m.to(m.next(h)) != Vertex(c)) return Face();
    return m.face(h);
}

// The boundary half-edge leaving v (v is on a boundary).
Halfedge boundary_out(const Mesh& m, std::uint32_t v) {
    REQUIRE(m.is_boundary(Vertex(v)));
    return m.halfedge(Vertex(v));
}

}  // namespace

TEST_CASE("from_indexed: tori, tubes and disks, and what it refuses") {
    const Mesh torus = Mesh::from_indexed(torus_grid(8, 6));
    ManifoldCheck c = require_valid(torus);
    CHECK(c.genus == 1);
    CHECK(c.boundary_loops == 0);
    CHECK(c.euler == 0);
    CHECK_FALSE(c.sphere());

    CHECK_THROWS_WITH_AS(Mesh::from_indexed(torus_grid(8, 4, false)), doctest::Contains("only one triangle"),
                         InputError);
    const Mesh tube = Mesh::from_indexed(torus_grid(8, 4, false), true);
    c = require_valid(tube);
    CHECK(c.genus == 0);
    CHECK(c.boundary_loops == 2);
    CHECK(tube.n_boundary_halfedges() == 16);
    CHECK(tube.loop_length(boundary_out(tube, 0)) == 8);

    const Mesh disk = Mesh::from_indexed(fan_disk(7), true);
    c = require_valid(disk);
    CHECK(c.genus == 0);
    CHECK(c.boundary_loops == 1);
    CHECK_FALSE(disk.is_boundary(Vertex(0)));
    for (std::uint32_t v = 1; v <= 7; ++v) {
        CHECK(disk.is_boundary(Vertex(v)));
        CHECK(disk.valence(Vertex(v)) == 3);
        // The boundary before the one leaving v ends at v.
        CHECK(disk.to(disk.prev_on_boundary(disk.halfedge(Vertex(v)))) == Vertex(v));
    }

    // Two disks sharing one rim vertex: a bow-tie.
    IndexedMesh bow = fan_disk(5);
    const IndexedMesh one = fan_disk(5);
    const std::uint32_t base = std::uint32_t(bow.positions.size());
    for (const Vec3& p : one.positions) bow.positions.push_back(p + Vec3{2, 0, 0});
    for (auto t : one.triangles) {
        for (auto& i : t) i = (i == 3) ? 1 : i + base;  // the second disk's vertex 3 is the first's 1
        bow.triangles.push_back(t);
    }
    CHECK_THROWS_WITH_AS(Mesh::from_indexed(bow, true), doctest::Contains("bow-tie"), InputError);
}

TEST_CASE("the face index stays while a mesh has boundaries") {
    Mesh disk = Mesh::from_indexed(fan_disk(5), true);
    CHECK_THROWS_AS(disk.drop_faces(), ParameterError);
    CHECK(disk.has_faces());
    Mesh m = icosahedron();
    REQUIRE(m.try_remove_face(Face(0)));
    CHECK_THROWS_AS(m.drop_faces(), ParameterError);
}

TEST_CASE("remove_face opens a loop, widens it, removes ears, and refuses bow-ties") {
    Mesh m = icosahedron();
    const Face f = find_face(m, 0, 11, 5);
    REQUIRE(f.valid());
    REQUIRE(m.can_remove_face(f));
    m.remove_face(f);
    ManifoldCheck c = require_valid(m);
    CHECK(c.boundary_loops == 1);
    CHECK(c.genus == 0);
    CHECK(m.n_faces() == 19);
    CHECK(m.n_boundary_halfedges() == 3);
    CHECK(m.is_removed(f));
    for (std::uint32_t v : {0u, 11u, 5u}) CHECK(m.is_boundary(Vertex(v)));
    CHECK_FALSE(m.is_boundary(Vertex(1)));

    // A face touching the hole at a vertex only (0, 5, 1 shares edge 0-5: allowed; 0, 1, 7
    // touches at 0 alone: refused, it would give vertex 0 a second gap).
    const Face corner = find_face(m, 0, 1, 7);
    REQUIRE(corner.valid());
    CHECK_FALSE(m.can_remove_face(corner));
    const Face beside = find_face(m, 0, 5, 1);
    REQUIRE(beside.valid());
    REQUIRE(m.try_remove_face(beside));  // widens the loop across edge 0-5, which goes
    c = require_valid(m);
    CHECK(c.boundary_loops == 1);
    CHECK(m.n_boundary_halfedges() == 4);
    CHECK_FALSE(m.find_halfedge(Vertex(0), Vertex(5)).valid());
    CHECK(m.loop_length(boundary_out(m, 1)) == 4);

    // Now 0, 1, 7 has its edge 0-1 on the boundary; its opposite vertex 7 is interior.
    REQUIRE(m.try_remove_face(find_face(m, 0, 1, 7)));
    require_valid(m);
    // (0, 7, 10) has edge 0-7 on the boundary and 10 interior: allowed; then (0, 10, 11) has two
    // edges on the boundary (0-10 and 11-0): an ear, whose removal takes vertex 0 with it.
    REQUIRE(m.try_remove_face(find_face(m, 0, 7, 10)));
    require_valid(m);
    const Face ear = find_face(m, 0, 10, 11);
    REQUIRE(ear.valid());
    CHECK(m.valence(Vertex(0)) == 2);
    Vertex gone;
    REQUIRE(m.try_remove_face(ear, &gone));
    CHECK(gone == Vertex(0));
    CHECK(m.is_removed(Vertex(0)));
    c = require_valid(m);
    CHECK(c.boundary_loops == 1);
    CHECK(m.n_vertices() == 11);
    CHECK(m.loop_length(boundary_out(m, 11)) == 5);  // 11, 5, 1, 7, 10
    check_against_brute(m);
    // A lone triangle is never removed (it would leave no face).
    IndexedMesh lone;
    lone.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    lone.triangles = {{0, 1, 2}};
    CHECK_FALSE(Mesh::from_indexed(lone, true).can_remove_face(Face(0)));
    // Every face is classified by brute force: one boundary edge and all three vertices on the
    // boundary (the opposite one would be pinched) or no boundary edge but a vertex on it: refused;
    // no boundary vertex at all, one boundary edge and an interior opposite vertex, or two
    // boundary edges (an ear): allowed.
    std::uint32_t pinching = 0;
    for (std::uint32_t fi = 0; fi < m.face_capacity(); ++fi) {
        const Face g(fi);
        if (m.is_removed(g)) continue;
        const Halfedge h0 = m.halfedge(g);
        int rim_edges = 0, rim_vertices = 0;
        for (Halfedge h = h0;;) {
            rim_edges += m.is_boundary(Mesh::twin(h));
            rim_vertices += m.is_boundary(m.from(h));
            if ((h = m.next(h)) == h0) break;
        }
        if (rim_edges == 1 && rim_vertices == 3) {
            ++pinching;
            CHECK_FALSE(m.can_remove_face(g));
        }
        if (rim_edges == 0 && rim_vertices > 0) CHECK_FALSE(m.can_remove_face(g));
        if ((rim_edges <= 1 && rim_vertices == 2 * rim_edges) || rim_edges == 2) CHECK(m.can_remove_face(g));
    }
    // A one-row tube: each triangle has an edge on one rim and its third vertex on the other.
    const Mesh tube = Mesh::from_indexed(torus_grid(8, 1, false), true);
    for (std::uint32_t fi = 0; fi < tube.face_capacity(); ++fi) CHECK_FALSE(tube.can_remove_face(Face(fi)));
    CHECK(pinching == 0);  // none of those on the icosahedron's single hole
    check_against_brute(m);
    CHECK_FALSE(m.can_remove_face(Face()));
    CHECK_FALSE(m.can_remove_face(f));  // already gone
}

TEST_CASE("split, collapse and flip are refused on a boundary, and work beside it") {
    Mesh m = icosahedron();
    REQUIRE(m.try_remove_face(find_face(m, 0, 11, 5)));
    // The boundary edge 0-11 cannot flip; the interior edge 0-1 has boundary vertex 0 (refused
    // to collapse) but flips.
    CHECK_FALSE(m.can_flip(m.find_halfedge(Vertex(0), Vertex(11))));
    CHECK_FALSE(m.can_flip(m.find_halfedge(Vertex(11), Vertex(0))));
    CHECK_FALSE(m.can_collapse(m.find_halfedge(Vertex(0), Vertex(1))));
    CHECK_FALSE(m.can_collapse(m.find_halfedge(Vertex(1), Vertex(0))));
    CHECK_FALSE(m.can_collapse(m.find_halfedge(Vertex(0), Vertex(11))));
    const Halfedge out0 = m.halfedge(Vertex(0));
    CHECK_FALSE(m.can_split(out0, m.cw_rotated(m.cw_rotated(out0))));
    // Interior edges away from the hole behave as on a closed mesh.
    REQUIRE(m.try_flip(m.find_halfedge(Vertex(3), Vertex(9))));
    require_valid(m);
    const Halfedge out3 = m.halfedge(Vertex(3));
    const Vertex a = m.try_split(out3, m.cw_rotated(m.cw_rotated(out3)), {1, -1, 0});
    REQUIRE(a.valid());
    require_valid(m);
    REQUIRE(m.try_collapse(m.find_halfedge(a, Vertex(3))));
    check_against_brute(m);
    // An interior edge with both ends on the hole's rim (0-5 after removing (0, 5, 1) is a
    // boundary edge; 11-5 borders (11, 4, 5) and the hole): flips of interior edges at rim
    // vertices keep the rim.
    const Halfedge h_rim = m.find_halfedge(Vertex(5), Vertex(1));
    REQUIRE(h_rim.valid());
    REQUIRE(m.try_flip(h_rim));
    check_against_brute(m);
    CHECK(m.n_boundary_halfedges() == 3);
}

TEST_CASE("join_loops makes a handle of two holes, and refuses one loop or an existing edge") {
    Mesh m = icosahedron();
    // Two antipodal faces: no vertex of one is adjacent to a vertex of the other.
    REQUIRE(m.try_remove_face(find_face(m, 0, 11, 5)));
    REQUIRE(m.try_remove_face(find_face(m, 3, 6, 8)));
    ManifoldCheck c = require_valid(m);
    CHECK(c.boundary_loops == 2);
    const Halfedge a = boundary_out(m, 0), b = boundary_out(m, 3);
    CHECK_FALSE(m.can_join_loops(a, m.next(a)));              // one loop
    CHECK_FALSE(m.can_join_loops(a, m.halfedge(Vertex(1))));  // not a boundary half-edge
    const Mesh before = m;
    REQUIRE(m.can_join_loops(a, b));
    m.join_loops(a, b);
    c = require_valid(m);
    CHECK(c.boundary_loops == 0);
    CHECK(c.genus == 1);
    CHECK(m.n_faces() == 18 + 6);
    CHECK_FALSE(m.has_boundary());
    check_against_brute(m);
    // The closed result goes through the indexed form and back, and keeps its genus.
    const ManifoldCheck back = require_valid(Mesh::from_indexed(m.to_indexed()));
    CHECK(back.genus == 1);

    // Holes whose rims are joined by an edge already: (0, 11, 5) and (1, 9, 8)? 5-1 and 5-9 are
    // edges, so the zip meets an existing edge and is refused.
    Mesh n = before;
    n = icosahedron();
    REQUIRE(n.try_remove_face(find_face(n, 0, 11, 5)));
    REQUIRE(n.try_remove_face(find_face(n, 9, 8, 1)));
    CHECK_FALSE(n.can_join_loops(boundary_out(n, 0), boundary_out(n, 9)));
    require_valid(n);
}

TEST_CASE("a torus from joining keeps its genus under random split, collapse and flip") {
    std::uint64_t ops = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        CAPTURE(seed);
        Mesh m = Mesh::from_indexed(torus_grid(10, 8));
        std::mt19937_64 rng(seed);
        for (int step = 0; step < 3000; ++step) {
            const Halfedge h(std::uint32_t(rng() % m.halfedge_capacity()));
            if (m.is_removed(h)) continue;
            switch (rng() % 3) {
                case 0: {
                    Halfedge d = h;
                    const std::uint32_t k = 2 + std::uint32_t(rng() % 3);
                    for (std::uint32_t i = 0; i < k; ++i) d = m.cw_rotated(d);
                    if (d != h && m.try_split(h, d, m.position(m.from(h)) * 1.01f).valid()) ++ops;
                    break;
                }
                case 1:
                    ops += m.try_collapse(h);
                    break;
                default:
                    ops += m.try_flip(h);
            }
            if (step % 50 == 0) {
                const ManifoldCheck c = require_valid(m);
                REQUIRE(c.genus == 1);
                REQUIRE(c.boundary_loops == 0);
            }
        }
        const ManifoldCheck c = require_valid(m);
        CHECK(c.genus == 1);
    }
    CHECK(ops > 5000);
}

TEST_CASE("random removals, joins, splits, collapses and flips keep a valid manifold, counted right") {
    std::uint64_t removals = 0, joins = 0, others = 0, refused = 0;
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        CAPTURE(seed);
        Mesh m = seed % 2 ? icosahedron() : Mesh::from_indexed(torus_grid(9, 7));
        std::mt19937_64 rng(seed);
        // Grow first, so that holes have room.
        for (int i = 0; i < 200; ++i) {
            const Halfedge h(std::uint32_t(rng() % m.halfedge_capacity()));
            if (m.is_removed(h) || m.is_boundary(h)) continue;
            const Halfedge d = m.cw_rotated(m.cw_rotated(h));
            m.try_split(h, d, m.position(m.from(h)) * 1.001f);
        }
        int expected_genus = require_valid(m).genus;
        for (int step = 0; step < 1500; ++step) {
            const std::uint32_t kind = std::uint32_t(rng() % 10);
            bool done = false;
            if (kind < 3) {
                const Face f(std::uint32_t(rng() % m.face_capacity()));
                done = !m.is_removed(f) && m.try_remove_face(f);
                removals += done;
            } else if (kind == 3 && m.n_boundary_halfedges() > 0) {
                // Two random boundary half-edges.
                std::vector<Halfedge> bs;
                for (std::uint32_t h = 0; h < m.halfedge_capacity(); ++h)
                    if (!m.is_removed(Halfedge(h)) && m.is_boundary(Halfedge(h))) bs.push_back(Halfedge(h));
                const Halfedge a = bs[rng() % bs.size()], b = bs[rng() % bs.size()];
                done = m.try_join_loops(a, b);
                if (done) ++expected_genus;  // one component: every join makes a handle
                joins += done;
            } else {
                const Halfedge h(std::uint32_t(rng() % m.halfedge_capacity()));
                if (m.is_removed(h)) continue;
                if (kind < 6)
                    done = m.try_flip(h);
                else if (kind < 8)
                    done = m.try_collapse(h);
                else
                    done = m.try_split(h, m.cw_rotated(m.cw_rotated(h)), m.position(m.from(h)) * 0.999f).valid();
                others += done;
            }
            refused += !done;
            if (!done) continue;
            CAPTURE(step);
            CAPTURE(kind);
            const ManifoldCheck c = require_valid(m);
            REQUIRE(c.genus == expected_genus);
            if (step % 25 == 0) check_against_brute(m);
        }
    }
    std::printf("boundary operations: %llu removals, %llu joins, %llu others, %llu refused\n",
                (unsigned long long)removals, (unsigned long long)joins, (unsigned long long)others,
                (unsigned long long)refused);
    CHECK(removals > 500);
    CHECK(joins > 20);
    CHECK(others > 2000);
}
