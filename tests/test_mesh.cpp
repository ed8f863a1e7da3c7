// Hand-built cases for the half-edge mesh: construction, circulators, geometry, and each
// operation and each refusal on a mesh small enough to reason about.
#include <doctest/doctest.h>

#include <cmath>
#include <set>

#include "error_fixtures.h"
#include "mesh_fixtures.h"
#include "nmesh/error.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"

using namespace nmesh;
using nmesh::test::bipyramid;
using nmesh::test::face_set;
using nmesh::test::icosahedron;
using nmesh::test::octahedron;

namespace {
std::set<std::uint32_t> neighbours(const Mesh& m, Vertex v) {
    std::set<std::uint32_t> s;
    m.for_each_neighbor(v, [&](Vertex u) { s.insert(u.idx); });
    return s;
}
}  // namespace

TEST_CASE("a default handle is invalid") {
    CHECK_FALSE(Vertex().valid());
    CHECK_FALSE(Halfedge().valid());
    CHECK(Face(3).valid());
    CHECK(sizeof(Vertex) == 4);
}

TEST_CASE("the tetrahedron is a valid closed manifold with outward faces") {
    const Vec3 center{1, 2, 3};
    const Mesh m = Mesh::tetrahedron(center, 2.0f);
    REQUIRE(check_manifold(m).sphere());
    CHECK(m.n_vertices() == 4);
    CHECK(m.n_edges() == 6);
    CHECK(m.n_faces() == 4);
    for (std::uint32_t v = 0; v < 4; ++v) {
        CHECK(m.valence(Vertex(v)) == 3);
        CHECK(distance(m.position(Vertex(v)), center) == doctest::Approx(2.0f).epsilon(1e-5));
        // The area-weighted normal of a regular tetrahedron's corner points away from the center.
        const Vec3 out = normalized(m.position(Vertex(v)) - center);
        CHECK(dot(m.vertex_normal(Vertex(v)), out) == doctest::Approx(1.0f).epsilon(1e-5));
    }
    // Edge length of a regular tetrahedron inscribed in radius r is r * sqrt(8/3).
    const float edge = 2.0f * std::sqrt(8.0f / 3.0f);
    for (std::uint32_t f = 0; f < 4; ++f) {
        CHECK(m.face_area(Face(f)) == doctest::Approx(std::sqrt(3.0f) / 4 * edge * edge).epsilon(1e-4));
        const Vec3 c = m.face_centroid(Face(f));
        CHECK(dot(m.face_normal(Face(f)), normalized(c - center)) == doctest::Approx(1.0f).epsilon(1e-5));
    }
}

TEST_CASE("a tetrahedron from four points faces outward in either input order") {
    const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
    for (const Mesh& m : {Mesh::tetrahedron(a, b, c, d), Mesh::tetrahedron(a, c, b, d)}) {
        REQUIRE(check_manifold(m).sphere());
        const Vec3 center = (a + b + c + d) * 0.25f;
        for (std::uint32_t f = 0; f < 4; ++f)
            CHECK(dot(m.face_normal(Face(f)), m.face_centroid(Face(f)) - center) > 0.0f);
    }
}

TEST_CASE("circulators visit the one-ring counter-clockwise, once each") {
    const Mesh m = octahedron();
    // Vertex 4 is (0, 0, 1); seen from above its neighbours 0 (+x), 2 (+y), 1 (-x), 3 (-y) are
    // counter-clockwise in that order.
    std::vector<std::uint32_t> ring;
    m.for_each_neighbor(Vertex(4), [&](Vertex u) { ring.push_back(u.idx); });
    REQUIRE(ring.size() == 4);
    const std::vector<std::uint32_t> order{0, 2, 1, 3};
    const auto start = std::find(order.begin(), order.end(), ring[0]) - order.begin();
    for (std::size_t i = 0; i < 4; ++i) CHECK(ring[i] == order[(start + i) % 4]);
    std::set<std::uint32_t> faces;
    m.for_each_face_around(Vertex(4), [&](Face f) { faces.insert(f.idx); });
    CHECK(faces.size() == 4);
    std::size_t outgoing = 0;
    m.for_each_outgoing(Vertex(4), [&](Halfedge h) {
        CHECK(m.from(h) == Vertex(4));
        ++outgoing;
    });
    CHECK(outgoing == 4);
    CHECK(m.find_halfedge(Vertex(4), Vertex(5)).valid() == false);
    CHECK(m.to(m.find_halfedge(Vertex(4), Vertex(2))) == Vertex(2));
}

TEST_CASE("from_indexed rejects what is not a closed manifold") {
    IndexedMesh open;
    open.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    open.triangles = {{0, 1, 2}};
    CHECK_THROWS_AS(Mesh::from_indexed(open), InputError);
    IndexedMesh flipped = octahedron().to_indexed();
    std::swap(flipped.triangles[0][0], flipped.triangles[0][1]);
    CHECK_THROWS_AS(Mesh::from_indexed(flipped), InputError);
    IndexedMesh bad_index = octahedron().to_indexed();
    bad_index.triangles[2][1] = 17;
    CHECK_THROWS_AS(Mesh::from_indexed(bad_index), InputError);
}

TEST_CASE("to_indexed and from_indexed round trip") {
    const Mesh m = icosahedron();
    const IndexedMesh dense = m.to_indexed();
    CHECK(dense.positions.size() == 12);
    CHECK(dense.triangles.size() == 20);
    const Mesh back = Mesh::from_indexed(dense);
    CHECK(face_set(back) == face_set(m));
}

TEST_CASE("the collapse floor: a tetrahedron cannot shrink") {
    Mesh m = Mesh::tetrahedron();
    const Mesh before = m;
    for (std::uint32_t h = 0; h < m.halfedge_capacity(); ++h) {
        CHECK_FALSE(m.can_collapse(Halfedge(h)));
        CHECK_FALSE(m.try_collapse(Halfedge(h)));
    }
    CHECK(m.same_arrays(before));
}

TEST_CASE("no edge of a tetrahedron can be flipped (the opposite vertices are adjacent)") {
    Mesh m = Mesh::tetrahedron();
    const Mesh before = m;
    for (std::uint32_t h = 0; h < m.halfedge_capacity(); ++h) CHECK_FALSE(m.try_flip(Halfedge(h)));
    CHECK(m.same_arrays(before));
}

TEST_CASE("the link condition refuses a collapse that would pinch the surface") {
    Mesh m = bipyramid();
    const Mesh before = m;
    // Equator edge 0-1: 0 and 1 share the apexes 3, 4 and the third equator vertex 2.
    const Halfedge h = m.find_halfedge(Vertex(0), Vertex(1));
    REQUIRE(h.valid());
    CHECK_FALSE(m.can_collapse(h));
    CHECK_FALSE(m.try_collapse(h));
    CHECK(m.same_arrays(before));
    // An apex edge 3 -> 0 passes the link condition, but 3's other neighbours 1 and 2 have
    // valence 4 and 0 would end with valence 3 + 4 - 4 = 3: allowed, and it leaves a tetrahedron.
    const Halfedge apex = m.find_halfedge(Vertex(3), Vertex(0));
    REQUIRE(m.can_collapse(apex));
    m.collapse(apex);
    REQUIRE(check_manifold(m).sphere());
    CHECK(m.n_vertices() == 4);
    CHECK(m.is_removed(Vertex(3)));
}

TEST_CASE("a second link-condition case: a bipyramid made from an octahedron") {
    // On a closed manifold with more than four vertices the link condition already implies that
    // no vertex drops below valence 3, so this is the refusal a learning run meets in practice.
    Mesh m = octahedron();
    // Collapse 5 -> 0: 0 takes 5's neighbours; 2 and 3 drop to valence 3 and become apexes.
    REQUIRE(m.try_collapse(m.find_halfedge(Vertex(5), Vertex(0))));
    REQUIRE(check_manifold(m).sphere());
    CHECK(m.valence(Vertex(2)) == 3);
    CHECK(m.valence(Vertex(3)) == 3);
    // 0 and 4 now share 1, 2 and 3.
    const Mesh before = m;
    CHECK_FALSE(m.try_collapse(m.find_halfedge(Vertex(0), Vertex(4))));
    CHECK(m.same_arrays(before));
}

TEST_CASE("a flip that would leave a valence-2 vertex is refused") {
    Mesh m = bipyramid();
    const Mesh before = m;
    // Edges at the valence-3 apexes cannot flip.
    for (std::uint32_t apex : {3u, 4u})
        m.for_each_outgoing(Vertex(apex), [&](Halfedge h) { CHECK_FALSE(m.can_flip(h)); });
    Halfedge h = m.find_halfedge(Vertex(0), Vertex(3));
    CHECK_FALSE(m.try_flip(h));
    CHECK(m.same_arrays(before));
    // An equator edge can: it becomes the apex-to-apex edge 3-4.
    h = m.find_halfedge(Vertex(0), Vertex(1));
    REQUIRE(m.try_flip(h));
    REQUIRE(check_manifold(m).sphere());
    CHECK(((m.from(h) == Vertex(3) && m.to(h) == Vertex(4)) || (m.from(h) == Vertex(4) && m.to(h) == Vertex(3))));
    CHECK(m.find_halfedge(Vertex(0), Vertex(1)).valid() == false);
}

TEST_CASE("flip then unflip restores every array bit for bit") {
    Mesh m = icosahedron();
    for (std::uint32_t h = 0; h < m.halfedge_capacity(); ++h) {
        const Mesh before = m;
        FlipRecord r;
        REQUIRE(m.try_flip(Halfedge(h), &r));
        REQUIRE(check_manifold(m).sphere());
        CHECK_FALSE(m.same_arrays(before));
        m.unflip(r);
        CHECK(m.same_arrays(before));
    }
}

TEST_CASE("vertex split divides the ring as asked, and collapse undoes it") {
    Mesh m = icosahedron();
    const auto faces_before = face_set(m);
    const Vertex b(0);
    const auto ring_before = neighbours(m, b);
    // Take neighbours c and d two steps apart: a gets c, the one between, and d.
    const Halfedge to_c = m.halfedge(b);
    const Halfedge to_d = m.ccw_rotated(m.ccw_rotated(to_c));
    const Vertex c = m.to(to_c), mid = m.to(m.ccw_rotated(to_c)), d = m.to(to_d);
    const Vec3 p{0.1f, 0.2f, 0.3f};
    const Vertex a = m.split(to_c, to_d, p);
    REQUIRE(check_manifold(m).sphere());
    CHECK(m.n_vertices() == 13);
    CHECK(m.position(a) == p);
    CHECK(neighbours(m, a) == std::set<std::uint32_t>{b.idx, c.idx, mid.idx, d.idx});
    auto expect_b = ring_before;
    expect_b.erase(mid.idx);
    expect_b.insert(a.idx);
    CHECK(neighbours(m, b) == expect_b);
    CHECK(m.valence(c) == 6);
    CHECK(m.valence(d) == 6);
    CHECK(m.find_halfedge(a, b).valid());
    // Collapsing the new edge a -> b restores the combinatorics.
    REQUIRE(m.try_collapse(m.find_halfedge(a, b)));
    REQUIRE(check_manifold(m).sphere());
    CHECK(face_set(m) == faces_before);
}

TEST_CASE("split refusals and extremes") {
    Mesh m = Mesh::tetrahedron();
    const Halfedge h = m.halfedge(Vertex(0));
    const Mesh before = m;
    CHECK_FALSE(m.try_split(h, h, {}).valid());                      // same half-edge
    CHECK_FALSE(m.try_split(h, m.halfedge(Vertex(1)), {}).valid());  // different vertices
    CHECK_FALSE(m.try_split(Halfedge(), h, {}).valid());
    CHECK(m.same_arrays(before));
    // Moving the whole ring but one: b keeps only a, c and d (valence 3).
    const Halfedge to_d = m.cw_rotated(h);
    const Vertex a = m.split(h, to_d, {});
    REQUIRE(check_manifold(m).sphere());
    CHECK(m.valence(Vertex(0)) == 3);
    CHECK(m.valence(a) == 4);
}

TEST_CASE("free slots are reused before the arrays grow") {
    Mesh m = octahedron();
    const std::uint32_t vcap = m.vertex_capacity(), ecap = m.edge_capacity(), fcap = m.face_capacity();
    REQUIRE(m.try_collapse(m.find_halfedge(Vertex(5), Vertex(0))));
    CHECK(m.free_vertex_head() == 5);
    const Halfedge to_c = m.halfedge(Vertex(0));
    const Vertex a = m.split(to_c, m.ccw_rotated(to_c), {});
    CHECK(a == Vertex(5));
    CHECK(m.vertex_capacity() == vcap);
    CHECK(m.edge_capacity() == ecap);
    CHECK(m.face_capacity() == fcap);
    CHECK(check_manifold(m).sphere());
}

namespace nmesh {
// Damages meshes on purpose so that each of the validator's checks is seen to fire.
struct MeshTestAccess {
    static std::uint32_t& to(Mesh& m, std::uint32_t h) { return m.he_[h].to; }
    static std::uint32_t& next(Mesh& m, std::uint32_t h) { return m.he_[h].next; }
    static std::vector<std::uint32_t>& vhe(Mesh& m) { return m.vhe_; }
    static std::vector<std::uint32_t>& fhe(Mesh& m) { return m.fhe_; }
    // The dead mark is the top bit of a slot's own field; the heads are marked the same way.
    static void set_free_vertex_head(Mesh& m, std::uint32_t v) { m.vfree_ = v | Mesh::kFreeBit; }
    static void mark_face_free(Mesh& m, std::uint32_t f) { m.fhe_[f] |= Mesh::kFreeBit; }
    static void mark_edge_free(Mesh& m, std::uint32_t e) { m.he_[2 * e].next |= Mesh::kFreeBit; }
    static void unmark_vertex(Mesh& m, std::uint32_t v) { m.vhe_[v] &= ~Mesh::kFreeBit; }
    // The alive-edge count split() checks the size limit against: a small mesh can pose as a
    // huge one without 16 GiB of half-edges.
    static std::uint32_t& n_edges(Mesh& m) { return m.n_edges_; }
    // Opens a face into a loop of three without asking can_remove_face (to make bow-ties).
    static void open_face_unchecked(Mesh& m, std::uint32_t f) {
        const std::uint32_t h0 = m.fhe_[f];
        for (std::uint32_t h = h0;;) {
            m.he_face_[h] = kInvalidIndex;
            m.vhe_[m.he_[h ^ 1u].to] = h;
            ++m.n_boundary_;
            if ((h = m.he_[h].next) == h0) break;
        }
        m.fhe_[f] = m.ffree_;
        m.ffree_ = f | Mesh::kFreeBit;
        --m.n_faces_;
    }
    static std::vector<std::uint32_t>& he_face(Mesh& m) { return m.he_face_; }
    static std::uint32_t& n_boundary(Mesh& m) { return m.n_boundary_; }
};
}  // namespace nmesh

TEST_CASE("freed slots are reused last freed first, the free-list links plain slot numbers") {
    Mesh m = icosahedron();
    // Two collapses. Each frees, in this order, the faces of h and of its twin, the edges of h,
    // next(h) and prev(twin(h)), and the vertex from(h).
    struct Freed {
        std::uint32_t v, f[2], e[3];
    };
    auto collapse = [&](Vertex a, Vertex b) {
        const Halfedge h = m.find_halfedge(a, b);
        REQUIRE(h.valid());
        const Freed r{a.idx,
                      {m.face(h).idx, m.face(Mesh::twin(h)).idx},
                      {Mesh::edge(h).idx, Mesh::edge(m.next(h)).idx, Mesh::edge(m.prev(Mesh::twin(h))).idx}};
        REQUIRE(m.try_collapse(h));
        REQUIRE(check_manifold(m).sphere());
        return r;
    };
    const Freed first = collapse(Vertex(0), Vertex(1));
    const Freed second = collapse(Vertex(3), Vertex(2));  // 3 is not a neighbour of 0
    for (std::uint32_t v : {first.v, second.v}) CHECK(m.is_removed(Vertex(v)));
    // Each list runs from the last slot freed to the first, and ends at kInvalidIndex.
    auto walk = [](std::uint32_t head, auto next) {
        std::vector<std::uint32_t> list;
        for (std::uint32_t s = head; s != kInvalidIndex && list.size() < 100; s = next(s)) list.push_back(s);
        return list;
    };
    CHECK(walk(m.free_vertex_head(), [&](std::uint32_t s) { return m.next_free_vertex(s); }) ==
          std::vector<std::uint32_t>{second.v, first.v});
    CHECK(walk(m.free_face_head(), [&](std::uint32_t s) { return m.next_free_face(s); }) ==
          std::vector<std::uint32_t>{second.f[1], second.f[0], first.f[1], first.f[0]});
    CHECK(walk(m.free_edge_head(), [&](std::uint32_t s) { return m.next_free_edge(s); }) ==
          std::vector<std::uint32_t>{second.e[2], second.e[1], second.e[0], first.e[2], first.e[1], first.e[0]});
    // Each split takes the vertex, then the edges a-b, b-c, d-b, then the faces (a, b, c) and
    // (b, a, d) from the heads.
    const std::uint32_t vcap = m.vertex_capacity(), ecap = m.edge_capacity(), fcap = m.face_capacity();
    for (const Freed& expect : {second, first}) {
        const Vertex b = Vertex(5);
        const Halfedge to_c = m.halfedge(b);
        const Halfedge to_d = m.ccw_rotated(m.ccw_rotated(to_c));
        const Vertex c = m.to(to_c), d = m.to(to_d);
        const Vertex a = m.split(to_c, to_d, {});
        REQUIRE(check_manifold(m).sphere());
        CHECK(a.idx == expect.v);
        CHECK_FALSE(m.is_removed(a));
        const Halfedge ab = Mesh::halfedge(Edge(expect.e[2]), 0);
        CHECK(m.from(ab) == a);
        CHECK(m.to(ab) == b);
        CHECK(m.from(Mesh::halfedge(Edge(expect.e[1]), 0)) == b);
        CHECK(m.to(Mesh::halfedge(Edge(expect.e[1]), 0)) == c);
        CHECK(m.from(Mesh::halfedge(Edge(expect.e[0]), 0)) == d);
        CHECK(m.to(Mesh::halfedge(Edge(expect.e[0]), 0)) == b);
        CHECK(m.face(ab).idx == expect.f[1]);
        CHECK(m.face(Mesh::twin(ab)).idx == expect.f[0]);
    }
    CHECK(m.free_vertex_head() == kInvalidIndex);
    CHECK(m.free_face_head() == kInvalidIndex);
    CHECK(m.free_edge_head() == kInvalidIndex);
    CHECK(m.vertex_capacity() == vcap);
    CHECK(m.edge_capacity() == ecap);
    CHECK(m.face_capacity() == fcap);
}

TEST_CASE("the size limit: 2^31 half-edges") {
    // Every half-edge index must stay below the dead mark's bit.
    CHECK(std::uint64_t(Mesh::kMaxHalfedges) == std::uint64_t(1) << 31);
    // kMaxVertices is the largest V whose closed genus-0 mesh (6V - 12 half-edges) fits.
    CHECK(6 * std::uint64_t(Mesh::kMaxVertices) - 12 <= Mesh::kMaxHalfedges);
    CHECK(6 * std::uint64_t(Mesh::kMaxVertices + 1) - 12 > Mesh::kMaxHalfedges);
    CHECK_NOTHROW(Mesh::check_halfedge_count(Mesh::kMaxHalfedges, "test"));
    CHECK_THROWS_WITH_AS(Mesh::check_halfedge_count(std::uint64_t(Mesh::kMaxHalfedges) + 1, "test"),
                         doctest::Contains("mesh: test: 2147483649 half-edges"), InputError);
    Mesh empty;
    CHECK(nmesh::test::refused_parameter([&] { empty.reserve(Mesh::kMaxVertices + 1); }) == "n");
    CHECK_THROWS_WITH_AS(empty.reserve(0xffffffffu), doctest::Contains("357913943"), ParameterError);
}

TEST_CASE("split refuses to pass the size limit and leaves the mesh as it was") {
    using A = MeshTestAccess;
    // Posing as a mesh of 2^30 - 2 alive edges: a split's three new edges would need 2^31 + 2
    // half-edges. (A split that succeeds under a posed count cannot be shown: the invariant
    // build validates the mesh after it, and the count is false.)
    Mesh m = icosahedron();
    A::n_edges(m) = Mesh::kMaxHalfedges / 2 - 2;
    const Mesh before = m;
    const Halfedge h = m.halfedge(Vertex(0));
    CHECK_THROWS_WITH_AS(m.split(h, m.ccw_rotated(m.ccw_rotated(h)), {}),
                         doctest::Contains("mesh: split: 2147483650 half-edges"), InputError);
    CHECK(m.same_arrays(before));
    A::n_edges(m) = 30;  // the true count again: the refused split changed nothing
    CHECK(check_manifold(m).sphere());
}

namespace {
void expect_error(const Mesh& m, const char* fragment) {
    const ManifoldCheck r = check_manifold(m);
    CHECK_FALSE(r.ok);
    INFO("message: " << r.error);
    CHECK(r.error.find(fragment) != std::string::npos);
}
}  // namespace

TEST_CASE("the validator names the first violation") {
    using A = MeshTestAccess;
    CHECK(check_manifold(icosahedron()).sphere());
    CHECK(check_manifold(icosahedron()).error.empty());
    expect_error(Mesh(), "empty");
    {
        Mesh m = icosahedron();  // a half-edge retargeted: its twin no longer runs opposite
        A::to(m, 0) = (A::to(m, 0) + 1) % 12;
        expect_error(m, "half-edge");
    }
    {
        Mesh m = icosahedron();  // a next cycle of length 2
        const std::uint32_t n = A::next(m, 0);
        A::next(m, n) = 0;
        expect_error(m, "half-edge");
    }
    {
        Mesh m = icosahedron();  // a vertex whose stored half-edge does not leave it
        A::vhe(m)[0] = A::vhe(m)[0] ^ 1u;
        expect_error(m, "vertex 0");
    }
    {
        Mesh m = icosahedron();  // a face pointing at another face's half-edge
        A::fhe(m)[0] = A::fhe(m)[1];
        expect_error(m, "face 0");
    }
    {
        Mesh m = icosahedron();  // an alive face marked free: elements refer to a freed slot
        A::mark_face_free(m, 3);
        CHECK(m.is_removed(Face(3)));
        expect_error(m, "face count");
    }
    {
        Mesh m = icosahedron();  // an alive edge marked free (the mark is in its first next)
        A::mark_edge_free(m, 7);
        CHECK(m.is_removed(Edge(7)));
        CHECK(m.is_removed(Halfedge(15)));
        expect_error(m, "edge count");
    }
    {
        Mesh m = octahedron();  // a free vertex whose mark is lost: a dead slot counted alive
        REQUIRE(m.try_collapse(m.find_halfedge(Vertex(5), Vertex(0))));
        REQUIRE(check_manifold(m).sphere());
        A::unmark_vertex(m, 5);
        CHECK_FALSE(m.is_removed(Vertex(5)));
        expect_error(m, "vertex count");
    }
    {
        Mesh m = icosahedron();  // without the face index, a broken next cycle is still found
        m.drop_faces();
        REQUIRE(check_manifold(m).sphere());
        const std::uint32_t n = A::next(m, 0);
        A::next(m, n) = 0;
        expect_error(m, "half-edge");
    }
    {
        Mesh m = icosahedron();  // a free list that points at an alive slot
        A::set_free_vertex_head(m, 2);
        CHECK(m.free_vertex_head() == 2);
        expect_error(m, "free list");
    }
    {
        // Two tetrahedra in one vertex array are disconnected.
        IndexedMesh two = Mesh::tetrahedron().to_indexed();
        const IndexedMesh one = two;
        for (const Vec3& p : one.positions) two.positions.push_back(p + Vec3{5, 0, 0});
        for (auto t : one.triangles) two.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
        CHECK_THROWS_WITH_AS(Mesh::from_indexed(two), doctest::Contains("not connected"), InputError);
    }
    {
        // A torus-like handle would have V - E + F = 0; a pinched vertex (two cones sharing an
        // apex) is caught by the one-ring check.
        IndexedMesh pinch;
        pinch.positions = {{0, 0, 0},   {1, 0, 1},    {-1, 1, 1}, {-1, -1, 1}, {1, 0, -1},
                           {-1, 1, -1}, {-1, -1, -1}, {0, 0, 2},  {0, 0, -2}};
        // Apex 0 joins two closed cones: (0,1,2,3 + cap 7) and (0,4,5,6 + cap 8).
        pinch.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 7, 2}, {2, 7, 3}, {3, 7, 1},
                           {0, 5, 4}, {0, 6, 5}, {0, 4, 6}, {4, 5, 8}, {5, 6, 8}, {6, 4, 8}};
        CHECK_THROWS_WITH_AS(Mesh::from_indexed(pinch), doctest::Contains("one-ring"), InputError);
    }
}

TEST_CASE("the local check sees a defect within a ring of the vertices it is given") {
    // check_around is what the invariant build runs after every operation, with the whole check
    // only every few operations on a large mesh: each defect the operations could leave near
    // their vertices is found from the vertex itself and from a neighbour of it.
    using A = MeshTestAccess;
    const auto expect_around = [](const Mesh& m, Vertex centre, const char* fragment) {
        const ManifoldCheck r = check_around(m, {centre});
        CHECK_FALSE(r.ok);
        INFO("message: " << r.error);
        CHECK(r.error.find(fragment) != std::string::npos);
    };
    const Mesh valid = icosahedron();
    for (std::uint32_t v = 0; v < 12; ++v) CHECK(check_around(valid, {Vertex(v)}).ok);
    // A neighbour of vertex v, for the defect to be one ring away from the centre.
    const auto neighbour = [](const Mesh& m, std::uint32_t v) { return m.to(m.halfedge(Vertex(v))); };
    for (const bool from_neighbour : {false, true}) {
        INFO("from a neighbour: " << from_neighbour);
        const auto centre = [&](const Mesh& m, std::uint32_t v) { return from_neighbour ? neighbour(m, v) : Vertex(v); };
        {
            Mesh m = icosahedron();  // a half-edge retargeted
            const std::uint32_t v = m.from(Halfedge(0)).idx;
            A::to(m, 0) = (A::to(m, 0) + 1) % 12;
            expect_around(m, centre(m, v), "half-edge");
        }
        {
            Mesh m = icosahedron();  // a next cycle of length 2
            const std::uint32_t v = m.from(Halfedge(0)).idx;
            A::next(m, A::next(m, 0)) = 0;
            expect_around(m, centre(m, v), "half-edge");
        }
        {
            Mesh m = icosahedron();  // a vertex whose stored half-edge does not leave it
            const Vertex c = centre(m, 0);
            A::vhe(m)[0] = A::vhe(m)[0] ^ 1u;
            expect_around(m, c, "vertex 0");
        }
        {
            Mesh m = icosahedron();  // a face pointing at another face's half-edge
            const std::uint32_t v = m.from(m.halfedge(Face(0))).idx;
            A::fhe(m)[0] = A::fhe(m)[1];
            expect_around(m, centre(m, v), "face 0");
        }
        {
            Mesh m = icosahedron();  // two holes meeting at vertex 0 only: a bow-tie
            const Vertex c = centre(m, 0);
            A::open_face_unchecked(m, m.face(m.find_halfedge(Vertex(0), Vertex(11))).idx);
            REQUIRE(check_around(m, {c}).ok);
            A::open_face_unchecked(m, m.face(m.find_halfedge(Vertex(0), Vertex(1))).idx);
            expect_around(m, c, "bow-tie");
        }
    }
    {
        Mesh m = icosahedron();  // what only the whole check sees: a free list, the counts
        A::set_free_vertex_head(m, 2);
        CHECK(check_around(m, {Vertex(2)}).ok);
        CHECK_FALSE(check_manifold(m).ok);
    }
}

TEST_CASE("the validator sees bow-ties and broken boundaries") {
    using A = MeshTestAccess;
    auto face_at = [](const Mesh& m, std::uint32_t a, std::uint32_t b) {
        return m.face(m.find_halfedge(Vertex(a), Vertex(b))).idx;
    };
    {
        Mesh m = icosahedron();  // two holes meeting at vertex 0 only: a bow-tie
        A::open_face_unchecked(m, face_at(m, 0, 11));
        REQUIRE(check_manifold(m).ok);
        A::open_face_unchecked(m, face_at(m, 0, 1));  // the face (0, 1, 7)
        expect_error(m, "bow-tie");
    }
    {
        Mesh m = icosahedron();  // a boundary vertex that stores an interior half-edge
        A::open_face_unchecked(m, face_at(m, 0, 11));
        A::vhe(m)[0] = m.find_halfedge(Vertex(0), Vertex(1)).idx;
        expect_error(m, "stored half-edge");
    }
    {
        Mesh m = icosahedron();  // a loop that the count does not know
        A::open_face_unchecked(m, face_at(m, 0, 11));
        A::n_boundary(m) = 0;
        expect_error(m, "boundary half-edge count");
    }
    {
        Mesh m = icosahedron();  // counted, but its next still has a face
        A::he_face(m)[0] = kInvalidIndex;
        A::n_boundary(m) = 1;
        expect_error(m, "has a face");
    }
    {
        Mesh m = icosahedron();  // an edge with no face on either side
        A::open_face_unchecked(m, face_at(m, 0, 11));
        const std::uint32_t h = m.find_halfedge(Vertex(11), Vertex(0)).idx;
        A::he_face(m)[h] = kInvalidIndex;
        ++A::n_boundary(m);
        expect_error(m, "no face on either side");
    }
}

TEST_CASE("the face index: dropped and built again") {
    Mesh m = icosahedron();
    // Operations with faces first, so that face slots are reused and no longer start at their
    // smallest half-edge.
    REQUIRE(m.try_flip(m.find_halfedge(Vertex(0), Vertex(5))));
    const Vertex a =
        m.split(m.halfedge(Vertex(3)), m.ccw_rotated(m.ccw_rotated(m.halfedge(Vertex(3)))), {0.1f, 0.2f, 0.3f});
    REQUIRE(m.try_collapse(m.find_halfedge(a, Vertex(3))));
    REQUIRE(check_manifold(m).sphere());
    // The centroid from any of a triangle's half-edges: the same bits.
    for (std::uint32_t f = 0; f < m.face_capacity(); ++f) {
        if (m.is_removed(Face(f))) continue;
        const Halfedge h = m.halfedge(Face(f));
        const Vec3 c = m.triangle_centroid(h);
        CHECK(m.triangle_centroid(m.next(h)) == c);
        CHECK(m.triangle_centroid(m.prev(h)) == c);
        CHECK(norm(c - m.face_centroid(Face(f))) <= 1e-6f);
        const Halfedge first = m.first_of_triangle(h);
        CHECK(first.idx == std::min({h.idx, m.next(h).idx, m.prev(h).idx}));
    }

    Mesh bare = m;
    bare.drop_faces();
    CHECK_FALSE(bare.has_faces());
    CHECK(bare.face_capacity() == 0);
    CHECK(bare.n_faces() == m.n_faces());
    CHECK(check_manifold(bare).sphere());
    // The same triangles, listed by smallest half-edge.
    const IndexedMesh listed = bare.to_indexed();
    CHECK(listed.positions == m.to_indexed().positions);
    CHECK(nmesh::test::face_set(Mesh::from_indexed(listed)) == nmesh::test::face_set(m));

    Mesh built = bare;
    built.build_faces();
    CHECK(built.has_faces());
    CHECK(check_manifold(built).sphere());
    CHECK(built.face_capacity() == m.n_faces());  // dense: no free face slots
    CHECK(built.free_face_head() == kInvalidIndex);
    // Numbered in the order of their smallest half-edge, each starting at it.
    for (std::uint32_t f = 0; f < built.face_capacity(); ++f) {
        const Halfedge h = built.halfedge(Face(f));
        CHECK(built.first_of_triangle(h) == h);
        if (f > 0) CHECK(built.halfedge(Face(f - 1)).idx < h.idx);
        CHECK(built.face_centroid(Face(f)) == built.triangle_centroid(built.next(h)));
    }
    // Building the index changes nothing else, and no output.
    const IndexedMesh again = built.to_indexed();
    CHECK(again.positions == listed.positions);
    CHECK(again.triangles == listed.triangles);
    Mesh built_twice = built;
    built_twice.build_faces();  // a no-op with an index
    CHECK(built_twice.same_arrays(built));
    // A mesh built from its own output numbers its faces the same way.
    CHECK(Mesh::from_indexed(again).to_indexed().triangles == again.triangles);
}
