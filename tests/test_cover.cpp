// Step 3 of the finishing stage (nmesh/finish/cover.h): vertices drawn out to the scan points the
// surface leaves uncovered, never into a crossing or a fold, and not by a stray point.
#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "mesh_fixtures.h"
#include "nmesh/finish/cloud_surface.h"
#include "nmesh/finish/cover.h"
#include "nmesh/finish/finish.h"
#include "nmesh/finish/repair.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/util/random.h"

using namespace nmesh;
using nmesh::test::icosphere;

namespace {

float uniform(Random& rng, float a, float b) { return a + (b - a) * float(rng.uniform()); }

// The unit icosphere (level 2: 162 vertices, edges about 0.25), and a cloud of its vertices and
// triangle centroids (all on the surface), plus `extra`.
struct Case {
    Mesh mesh;
    std::vector<Vec3> cloud;
};

Case sphere_case(const std::vector<Vec3>& extra) {
    Case c{Mesh::from_indexed(icosphere(2)), {}};
    c.cloud = c.mesh.positions();
    for (std::uint32_t f = 0; f < c.mesh.face_capacity(); ++f) c.cloud.push_back(c.mesh.face_centroid(Face(f)));
    c.cloud.insert(c.cloud.end(), extra.begin(), extra.end());
    return c;
}

// The vertex of the icosphere nearest to the direction d.
Vertex vertex_towards(const Mesh& mesh, const Vec3& d) {
    Vertex best;
    float most = -2.0f;
    for (std::uint32_t v = 0; v < mesh.vertex_capacity(); ++v)
        if (dot(mesh.position(Vertex(v)), d) > most) most = dot(mesh.position(Vertex(v)), d), best = Vertex(v);
    return best;
}

// `n` points round `at`, within `r` of it.
std::vector<Vec3> cluster(const Vec3& at, int n, float r, std::uint64_t seed) {
    Random rng(seed);
    std::vector<Vec3> p;
    for (int i = 0; i < n; ++i)
        p.push_back(at + Vec3(uniform(rng, -r, r), uniform(rng, -r, r), uniform(rng, -r, r)));
    return p;
}

// A closed slab over [-1, 1]^2: its top an n x n grid at z = top (vertex i + n j at
// (-1 + 2i/(n-1), -1 + 2j/(n-1))), its bottom the square's two triangles at z = bottom, each side
// a fan from the top's edge to the bottom's two corners. Outward-facing.
IndexedMesh slab(std::uint32_t n, float top, float bottom) {
    IndexedMesh m;
    const auto t = [n](std::uint32_t i, std::uint32_t j) { return i + n * j; };
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i)
            m.positions.emplace_back(-1.0f + 2.0f * float(i) / float(n - 1), -1.0f + 2.0f * float(j) / float(n - 1), top);
    const std::uint32_t b = n * n;  // the bottom's corners, counter-clockwise seen from above
    m.positions.insert(m.positions.end(), {{-1, -1, bottom}, {1, -1, bottom}, {1, 1, bottom}, {-1, 1, bottom}});
    for (std::uint32_t j = 0; j + 1 < n; ++j)
        for (std::uint32_t i = 0; i + 1 < n; ++i) {
            m.triangles.push_back({t(i, j), t(i + 1, j), t(i + 1, j + 1)});
            m.triangles.push_back({t(i, j), t(i + 1, j + 1), t(i, j + 1)});
        }
    m.triangles.push_back({b, b + 2, b + 1});
    m.triangles.push_back({b, b + 3, b + 2});
    // The top's rim, counter-clockwise seen from above, side by side from corner to corner.
    for (std::uint32_t side = 0; side < 4; ++side) {
        std::vector<std::uint32_t> path;
        for (std::uint32_t k = 0; k < n; ++k) {
            const std::uint32_t r = n - 1 - k;
            path.push_back(side == 0 ? t(k, 0) : side == 1 ? t(n - 1, k) : side == 2 ? t(r, n - 1) : t(0, r));
        }
        const std::uint32_t c0 = b + side, c1 = b + (side + 1) % 4, half = (n - 1) / 2;
        for (std::uint32_t k = 0; k + 1 < n; ++k) m.triangles.push_back({path[k + 1], path[k], k < half ? c0 : c1});
        m.triangles.push_back({path[half], c0, c1});
    }
    return m;
}

std::size_t moved_vertices(const Mesh& a, const Mesh& b) {
    std::size_t n = 0;
    for (std::uint32_t v = 0; v < a.vertex_capacity(); ++v)
        if (a.position(Vertex(v)) != b.position(Vertex(v))) ++n;
    return n;
}

}  // namespace

TEST_CASE("the cover draws the nearest vertex out to a cluster of points beyond the surface") {
    const Vec3 tip(0.0f, 1.0f, 0.0f);
    Case c = sphere_case(cluster(tip * 1.4f, 12, 0.02f, 1));
    const Mesh before = c.mesh;
    const Vertex v = vertex_towards(c.mesh, tip);
    const CloudSurface surface(c.cloud, c.mesh);
    const CoverResult r = cover_uncovered_points(c.mesh, surface);
    // Half of the way at each iteration, 1 + 0.4 * (1/2 + 1/4) along the axis, after which the
    // points are within half an edge (edges of about 0.25) of its triangles.
    CHECK(r.moves == 2);
    CHECK(r.undone == 0);
    CHECK(moved_vertices(before, c.mesh) == 1);
    CHECK(norm(c.mesh.position(v)) == doctest::Approx(1.3).epsilon(0.01));
    CHECK(find_self_intersections(c.mesh).empty());
    CHECK(check_manifold(c.mesh).sphere());
}

TEST_CASE("the cover leaves a covered cloud and a few stray points alone") {
    for (const int stray : {0, 1, 2}) {
        CAPTURE(stray);
        Case c = sphere_case(cluster(Vec3(0.0f, 0.0f, 1.5f), stray, 0.02f, 2));
        const Mesh before = c.mesh;
        const CloudSurface surface(c.cloud, c.mesh);
        const CoverResult r = cover_uncovered_points(c.mesh, surface);
        CHECK(r.moves == 0);
        CHECK(moved_vertices(before, c.mesh) == 0);
    }
    // Three make a cluster (kCoverMinPoints).
    Case c = sphere_case(cluster(Vec3(0.0f, 0.0f, 1.5f), 3, 0.02f, 2));
    const CloudSurface surface(c.cloud, c.mesh);
    CHECK(cover_uncovered_points(c.mesh, surface).moves > 0);
}

TEST_CASE("the cover stops a move short of a wall it would cross") {
    // A slab: its top a fine grid at z = 0.1, its bottom two large triangles at z = `bottom`.
    // Points below the bottom under the top's middle vertex, whose nearest vertex that is (the
    // bottom's are its far corners): drawn towards them, it would pierce a thin slab's bottom.
    for (const float bottom : {0.0f, -2.0f}) {
        CAPTURE(bottom);
        Mesh mesh = Mesh::from_indexed(slab(9, 0.1f, bottom));
        REQUIRE(find_self_intersections(mesh).empty());
        const Vertex middle(4 * 9 + 4);
        REQUIRE(mesh.position(middle) == Vec3(0.0f, 0.0f, 0.1f));
        std::vector<Vec3> cloud = mesh.positions();
        const std::vector<Vec3> below = cluster(Vec3(0.05f, 0.05f, -0.3f), 12, 0.02f, 3);
        cloud.insert(cloud.end(), below.begin(), below.end());
        const CloudSurface surface(cloud, mesh);
        const CoverResult r = cover_uncovered_points(mesh, surface);
        const float z = mesh.position(middle).z;
        CHECK(find_self_intersections(mesh).empty());
        CHECK(check_manifold(mesh).sphere());
        CHECK(r.moves > 0);
        if (bottom == 0.0f) {  // halved until it stays inside (undone where two halvings do not)
            CHECK(z > 0.0f);
            CHECK(z < 0.1f);
            CHECK(r.undone > 0);
        } else {
            CHECK(z < -0.05f);
        }
    }
}

TEST_CASE("the cover never leaves a crossing or a fold, on random clusters round a jittered sphere") {
    Random rng(11);
    int trials = 0;
    std::uint32_t moves = 0, undone = 0;
    for (int trial = 0; trial < 40; ++trial) {
        CAPTURE(trial);
        IndexedMesh m = icosphere(2);
        for (Vec3& p : m.positions) p = p * uniform(rng, 0.9f, 1.1f);
        Mesh mesh = Mesh::from_indexed(m);
        if (!find_self_intersections(mesh).empty() || !find_folded_edges(mesh, kCoverFoldDeg).empty()) continue;
        std::vector<Vec3> cloud = mesh.positions();
        for (int k = 0; k < 6; ++k) {
            const Vec3 d = normalized(Vec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)));
            const std::vector<Vec3> cl = cluster(d * uniform(rng, 0.3f, 1.8f), 4 + int(uniform(rng, 0, 12)), 0.1f, rng.next());
            cloud.insert(cloud.end(), cl.begin(), cl.end());
        }
        const CloudSurface surface(cloud, mesh);
        const CoverResult r = cover_uncovered_points(mesh, surface);
        ++trials;
        moves += r.moves;
        undone += r.undone;
        CHECK(find_self_intersections(mesh).empty());
        CHECK(find_folded_edges(mesh, kCoverFoldDeg).empty());
        CHECK(check_manifold(mesh).sphere());
    }
    // The clusters inside the sphere draw vertices across it: the guard has work to do.
    CHECK(trials >= 30);
    CHECK(moves > 0);
    CHECK(undone > 0);
}

TEST_CASE("the finishing stage covers a tip the mesh left short, and reports the moves") {
    const Vec3 tip(0.0f, 1.0f, 0.0f);
    Case c = sphere_case(cluster(tip * 1.4f, 12, 0.02f, 4));
    FinishOptions o;
    o.rounds = 0;
    const FinishReport with = finish_mesh(c.mesh, c.cloud, o);
    CHECK(with.cover_moves == 2);
    CHECK(norm(c.mesh.position(vertex_towards(c.mesh, tip))) > 1.25f);
    Case d = sphere_case(cluster(tip * 1.4f, 12, 0.02f, 4));
    o.cover_iterations = 0;
    const FinishReport without = finish_mesh(d.mesh, d.cloud, o);
    CHECK(without.cover_moves == 0);
    CHECK(norm(d.mesh.position(vertex_towards(d.mesh, tip))) == doctest::Approx(1.0f));
}

TEST_CASE("a fold steeper than the cover's limit keeps its corners and holds back no other move") {
    // A fin: two neighbouring vertices of the icosphere drawn out to three times the radius, so
    // that their triangles fold back to back (beyond kCoverFoldDeg), with a cluster beyond its
    // tip; and a tip left short on the other side.
    const Vec3 fin(1.0f, 0.2f, 0.1f), tip = -normalized(fin);
    const auto make = [&] {
        Case c = sphere_case({});
        const Vertex a = vertex_towards(c.mesh, fin);
        Vertex b;
        float most = -2.0f;
        c.mesh.for_each_outgoing_cw(a, [&](Halfedge h) {
            const Vertex u = c.mesh.to(h);
            if (dot(c.mesh.position(u), fin) > most) most = dot(c.mesh.position(u), fin), b = u;
        });
        c.mesh.set_position(a, c.mesh.position(a) * 3.0f);
        c.mesh.set_position(b, c.mesh.position(b) * 3.0f);
        const std::vector<Vec3> beyond = cluster(c.mesh.position(a) * 1.2f, 12, 0.02f, 5);
        const std::vector<Vec3> short_tip = cluster(tip * 1.4f, 12, 0.02f, 6);
        c.cloud = c.mesh.positions();
        c.cloud.insert(c.cloud.end(), beyond.begin(), beyond.end());
        c.cloud.insert(c.cloud.end(), short_tip.begin(), short_tip.end());
        return std::make_pair(c, std::make_pair(a, b));
    };
    auto [c, fin_ends] = make();
    REQUIRE(find_self_intersections(c.mesh).empty());
    const std::vector<Edge> steep = find_folded_edges(c.mesh, kCoverFoldDeg);
    REQUIRE(!steep.empty());
    const Mesh before = c.mesh;
    const CloudSurface surface(c.cloud, c.mesh);
    const CoverResult r = cover_uncovered_points(c.mesh, surface, 3, 0.5f, steep);
    CHECK(r.moves == 2);
    CHECK(r.undone == 0);
    CHECK(c.mesh.position(fin_ends.first) == before.position(fin_ends.first));
    CHECK(c.mesh.position(fin_ends.second) == before.position(fin_ends.second));
    CHECK(norm(c.mesh.position(vertex_towards(c.mesh, tip))) == doctest::Approx(1.3).epsilon(0.01));
    CHECK(find_self_intersections(c.mesh).empty());
    CHECK(find_folded_edges(c.mesh, kCoverFoldDeg) == steep);
    // Not told of the fold, the cover draws the fin's tip out, the fold stays, and every move
    // of the iteration is undone: the short tip stays short.
    auto [d, unused] = make();
    const CloudSurface surface_d(d.cloud, d.mesh);
    const CoverResult rd = cover_uncovered_points(d.mesh, surface_d, 3, 0.5f);
    CHECK(rd.moves == 0);
    CHECK(norm(d.mesh.position(vertex_towards(d.mesh, tip))) == doctest::Approx(1.0f));
}
