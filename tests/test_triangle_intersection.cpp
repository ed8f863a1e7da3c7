// Tests of the exact triangle intersection tests and of the mesh self-intersection search.
//
// The reference is independent of orientation signs: on small integer coordinates it computes
// the actual common part of two triangles by exact rational clipping (the first triangle clipped
// to the plane of the second, then by the half-spaces of the second's edges; in homogeneous
// integer coordinates), and reads the verdict off that set. The mesh search is compared with the
// quadratic brute force over faces_intersect.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/geometry/exact_predicates.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/vec3.h"
#include "mesh_fixtures.h"

using nmesh::faces_intersect;
using nmesh::IndexedMesh;
using nmesh::segment_intersects_triangle;
using nmesh::triangle_degenerate;
using nmesh::triangles_intersect_exact;
using nmesh::Vec3;
using nmesh::test::icosphere;

namespace {

using Face = std::array<std::uint32_t, 3>;
using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// ---- the reference: exact clipping on integer points -------------------------------------------

__extension__ typedef __int128 Int;

// Overflow-checked arithmetic: the reference must never be silently wrong.
Int mul(Int a, Int b) {
    Int r;
    if (__builtin_mul_overflow(a, b, &r)) throw std::overflow_error("reference: overflow");
    return r;
}
Int add(Int a, Int b) {
    Int r;
    if (__builtin_add_overflow(a, b, &r)) throw std::overflow_error("reference: overflow");
    return r;
}
Int sub(Int a, Int b) {
    Int r;
    if (__builtin_sub_overflow(a, b, &r)) throw std::overflow_error("reference: overflow");
    return r;
}
Int gcd(Int a, Int b) {
    if (a < 0) a = -a;
    if (b < 0) b = -b;
    while (b != 0) {
        const Int t = a % b;
        a = b;
        b = t;
    }
    return a;
}

struct IPoint {
    std::int64_t x, y, z;
};

// The rational point (x, y, z) / w, w > 0, in lowest terms.
struct HPoint {
    Int x, y, z, w;
};

HPoint normalized(HPoint p) {
    if (p.w < 0) p = {-p.x, -p.y, -p.z, -p.w};
    const Int g = gcd(gcd(p.x, p.y), gcd(p.z, p.w));
    if (g > 1) p = {p.x / g, p.y / g, p.z / g, p.w / g};
    return p;
}

HPoint lift(const IPoint& p) { return {p.x, p.y, p.z, 1}; }

// The affine function x -> c . x + c0.
struct Affine {
    Int c[3], c0;
};

// The affine function's value at p, times p.w (so of its sign).
Int value(const Affine& g, const HPoint& p) {
    return add(add(add(mul(g.c[0], p.x), mul(g.c[1], p.y)), mul(g.c[2], p.z)), mul(g.c0, p.w));
}

Affine negated(const Affine& g) { return {{-g.c[0], -g.c[1], -g.c[2]}, -g.c0}; }

// Sutherland-Hodgman: the convex polygon (a list of vertices; a segment or a point are polygons of
// two and one) clipped to g >= 0. The result's convex hull is exactly the polygon's part in the
// closed half-space; vertices may repeat.
std::vector<HPoint> clip(const std::vector<HPoint>& polygon, const Affine& g) {
    std::vector<HPoint> out;
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
        const HPoint& a = polygon[i];
        const HPoint& b = polygon[(i + 1) % n];
        const Int ga = value(g, a), gb = value(g, b);
        if (ga >= 0) out.push_back(a);
        if ((ga > 0 && gb < 0) || (ga < 0 && gb > 0)) {
            // The point (ga b - gb a) / (ga - gb) with the homogeneous values: g vanishes there.
            out.push_back(normalized({sub(mul(ga, b.x), mul(gb, a.x)), sub(mul(ga, b.y), mul(gb, a.y)),
                                      sub(mul(ga, b.z), mul(gb, a.z)), sub(mul(ga, b.w), mul(gb, a.w))}));
        }
    }
    return out;
}

IPoint minus(const IPoint& a, const IPoint& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
IPoint cross(const IPoint& a, const IPoint& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
std::int64_t dot(const IPoint& a, const IPoint& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

bool reference_degenerate(const IPoint& a, const IPoint& b, const IPoint& c) {
    const IPoint n = cross(minus(b, a), minus(c, a));
    return n.x == 0 && n.y == 0 && n.z == 0;
}

// The part of the convex polygon (here a triangle, a segment or a point) that lies in the
// non-degenerate triangle def, as a list of points whose convex hull it is.
std::vector<HPoint> common_part(const std::vector<IPoint>& polygon, const IPoint& d, const IPoint& e, const IPoint& f) {
    std::vector<HPoint> part;
    for (const IPoint& p : polygon) part.push_back(lift(p));
    const IPoint n = cross(minus(e, d), minus(f, d));
    const Affine plane{{n.x, n.y, n.z}, -dot(n, d)};
    part = clip(clip(part, plane), negated(plane));
    // In the plane, def is where the three edge functions (n x edge) . (x - start), which are
    // positive at the opposite corner, are all >= 0.
    const IPoint corners[3] = {d, e, f};
    for (int i = 0; i < 3; ++i) {
        const IPoint& s = corners[i];
        const IPoint m = cross(n, minus(corners[(i + 1) % 3], s));
        part = clip(part, Affine{{m.x, m.y, m.z}, -dot(m, s)});
    }
    return part;
}

bool same_point(const HPoint& p, const IPoint& v) {
    return p.x == mul(v.x, p.w) && p.y == mul(v.y, p.w) && p.z == mul(v.z, p.w);
}

// Whether p lies on the closed segment ab (a != b).
bool on_segment(const HPoint& p, const IPoint& a, const IPoint& b) {
    const Int rx = sub(p.x, mul(a.x, p.w)), ry = sub(p.y, mul(a.y, p.w)), rz = sub(p.z, mul(a.z, p.w));
    const IPoint ab = minus(b, a);
    if (sub(mul(ry, ab.z), mul(rz, ab.y)) != 0 || sub(mul(rz, ab.x), mul(rx, ab.z)) != 0 ||
        sub(mul(rx, ab.y), mul(ry, ab.x)) != 0)
        return false;
    const Int along = add(add(mul(rx, ab.x), mul(ry, ab.y)), mul(rz, ab.z));
    return along >= 0 && along <= mul(p.w, dot(ab, ab));
}

bool reference_segment_meets_triangle(const IPoint& p, const IPoint& q, const IPoint& a, const IPoint& b,
                                      const IPoint& c) {
    return !common_part({p, q}, a, b, c).empty();
}

// faces_intersect's rule, read off the common part.
bool reference_faces_intersect(const std::vector<IPoint>& points, const Face& t, const Face& u) {
    const auto degenerate = [&](const Face& f) {
        return f[0] == f[1] || f[1] == f[2] || f[2] == f[0] ||
               reference_degenerate(points[f[0]], points[f[1]], points[f[2]]);
    };
    if (degenerate(t) || degenerate(u)) return false;
    std::vector<std::uint32_t> shared;
    for (std::uint32_t v : t)
        if (std::find(u.begin(), u.end(), v) != u.end()) shared.push_back(v);
    if (shared.size() == 3) return true;
    const std::vector<HPoint> part =
        common_part({points[t[0]], points[t[1]], points[t[2]]}, points[u[0]], points[u[1]], points[u[2]]);
    for (const HPoint& p : part) {
        if (shared.empty()) return true;
        if (shared.size() == 1 && !same_point(p, points[shared[0]])) return true;
        if (shared.size() == 2 && !on_segment(p, points[shared[0]], points[shared[1]])) return true;
    }
    return false;
}

// ---- helpers -----------------------------------------------------------------------------------

using Rng = std::mt19937_64;

int uniform_int(Rng& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

Vec3 to_vec3(const IPoint& p) { return {float(p.x), float(p.y), float(p.z)}; }

std::vector<Vec3> to_vec3(const std::vector<IPoint>& points) {
    std::vector<Vec3> r;
    for (const IPoint& p : points) r.push_back(to_vec3(p));
    return r;
}

// The face rotated by r and, if flip, reversed: the same triangle written otherwise.
Face rewritten(Face f, int r, bool flip) {
    std::rotate(f.begin(), f.begin() + r, f.end());
    if (flip) std::swap(f[1], f[2]);
    return f;
}

// Both the library and the reference on faces of integer points.
struct Verdict {
    bool exact, reference;
};

Verdict judge(const std::vector<IPoint>& points, const Face& t, const Face& u) {
    const std::vector<Vec3> positions = to_vec3(points);
    return {faces_intersect(positions.data(), t, u), reference_faces_intersect(points, t, u)};
}

// Random integer points of one of several kinds, chosen per configuration: a tiny grid (many
// coincidences, touchings and collinear edges), a larger grid, or points in one plane
// (coplanar configurations: the plane z = 0, a tilted plane, or a plane x = const).
struct PointSource {
    int kind;
    IPoint operator()(Rng& rng) const {
        switch (kind) {
            case 0:
                return {uniform_int(rng, -2, 2), uniform_int(rng, -2, 2), uniform_int(rng, -2, 2)};
            case 1:
                return {uniform_int(rng, -6, 6), uniform_int(rng, -6, 6), uniform_int(rng, -6, 6)};
            case 2:
                return {uniform_int(rng, -3, 3), uniform_int(rng, -3, 3), 0};
            case 3: {
                const int x = uniform_int(rng, -3, 3), y = uniform_int(rng, -3, 3);
                return {x, y, x - y};
            }
            default:
                return {1, uniform_int(rng, -4, 4), uniform_int(rng, -4, 4)};
        }
    }
};

IndexedMesh make_mesh(const std::vector<Vec3>& positions, const std::vector<Face>& faces) {
    IndexedMesh m;
    m.positions = positions;
    m.triangles = faces;
    return m;
}

// The quadratic brute force over faces_intersect.
Pairs brute_force_pairs(const IndexedMesh& mesh) {
    Pairs r;
    for (std::uint32_t s = 0; s < mesh.triangles.size(); ++s)
        for (std::uint32_t t = s + 1; t < mesh.triangles.size(); ++t)
            if (faces_intersect(mesh.positions.data(), mesh.triangles[s], mesh.triangles[t])) r.emplace_back(s, t);
    return r;
}

// An octahedron |x| + |y| + |z| = n with each face cut into n^2 triangles on the integer grid:
// closed, counter-clockwise from outside, and with many coplanar neighbouring faces.
IndexedMesh subdivided_octahedron(int n) {
    IndexedMesh m;
    std::map<std::array<int, 3>, std::uint32_t> index;
    const auto vertex = [&](int x, int y, int z) {
        const std::array<int, 3> key{x, y, z};
        const auto it = index.find(key);
        if (it != index.end()) return it->second;
        const std::uint32_t v = std::uint32_t(m.positions.size());
        m.positions.push_back({float(x), float(y), float(z)});
        index.emplace(key, v);
        return v;
    };
    for (const int sx : {1, -1})
        for (const int sy : {1, -1})
            for (const int sz : {1, -1}) {
                // Points i ex + j ey + k ez with i + j + k = n on the face of signs (sx, sy, sz).
                const auto at = [&](int i, int j) { return vertex(sx * i, sy * j, sz * (n - i - j)); };
                const bool flip = sx * sy * sz < 0;  // keeps the outward orientation
                const auto add_face = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
                    m.triangles.push_back(flip ? Face{a, c, b} : Face{a, b, c});
                };
                for (int i = 0; i < n; ++i)
                    for (int j = 0; i + j < n; ++j) {
                        add_face(at(i, j), at(i + 1, j), at(i, j + 1));
                        if (i + j + 1 < n) add_face(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    }
            }
    return m;
}

// A torus of major radius 1 and minor radius 0.4, as an `around` x `across` grid of quads split
// into two triangles each.
IndexedMesh torus(int around, int across) {
    IndexedMesh m;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < around; ++i)
        for (int j = 0; j < across; ++j) {
            const double u = 2 * pi * i / around, v = 2 * pi * j / across;
            const double r = 1.0 + 0.4 * std::cos(v);
            m.positions.push_back({float(r * std::cos(u)), float(r * std::sin(u)), float(0.4 * std::sin(v))});
        }
    const auto at = [&](int i, int j) { return std::uint32_t((i % around) * across + (j % across)); };
    for (int i = 0; i < around; ++i)
        for (int j = 0; j < across; ++j) {
            m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    return m;
}

// The faces that use vertex v.
std::vector<std::uint32_t> faces_around(const IndexedMesh& mesh, std::uint32_t v) {
    std::vector<std::uint32_t> r;
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f)
        if (std::find(mesh.triangles[f].begin(), mesh.triangles[f].end(), v) != mesh.triangles[f].end()) r.push_back(f);
    return r;
}

}  // namespace

// ---- the reference on its own ------------------------------------------------------------------

TEST_CASE("triangle intersection: the clipping reference on hand-computed sets") {
    const IPoint a{0, 0, 0}, b{4, 0, 0}, c{0, 4, 0};
    // A segment piercing the triangle: the common part is the single point (1, 1, 0).
    std::vector<HPoint> part = common_part({{1, 1, -2}, {1, 1, 2}}, a, b, c);
    REQUIRE(!part.empty());
    for (const HPoint& p : part) CHECK(same_point(p, {1, 1, 0}));
    // A triangle standing on the plane through the middle: the part is a segment of the line
    // x = 1 from y = 0 to y = 3 (clipped by the hypotenuse x + y = 4).
    part = common_part({{1, -1, 0}, {1, 5, 0}, {1, 2, 3}}, a, b, c);
    REQUIRE(part.size() >= 2);
    bool low = false, high = false;
    for (const HPoint& p : part) {
        CHECK(on_segment(p, {1, 0, 0}, {1, 3, 0}));
        low = low || same_point(p, {1, 0, 0});
        high = high || same_point(p, {1, 3, 0});
    }
    CHECK(low);
    CHECK(high);
    // A rational crossing: the edge from (0, 0, -1) to (3, 1, 2) meets z = 0 at (1, 1/3, 0).
    part = common_part({{0, 0, -1}, {3, 1, 2}}, a, b, c);
    REQUIRE(part.size() >= 1);
    CHECK(part[0].w == 3);
    CHECK(part[0].x == 3);
    CHECK(part[0].y == 1);
    CHECK(part[0].z == 0);
    // Disjoint.
    CHECK(common_part({{5, 5, -1}, {5, 5, 1}}, a, b, c).empty());
    CHECK(common_part({{1, 1, 1}, {2, 1, 1}, {1, 2, 3}}, a, b, c).empty());
}

// ---- hand-made cases ---------------------------------------------------------------------------

TEST_CASE("triangle intersection: hand-made configurations, library and reference agree") {
    struct Case {
        const char* name;
        std::vector<IPoint> points;
        Face t, u;
        bool expected;
    };
    // clang-format off
    const std::vector<Case> cases = {
        // One shared vertex 0.
        {"two faces round one vertex that cross", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, -2}, {1, 1, 2}},
         {0, 1, 2}, {0, 3, 4}, true},
        {"one shared vertex, touching nowhere else", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 2}, {-1, 2, 3}},
         {0, 1, 2}, {0, 3, 4}, false},
        {"one shared vertex, coplanar, apart", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {-4, 0, 0}, {0, -4, 0}},
         {0, 1, 2}, {0, 3, 4}, false},
        {"one shared vertex, coplanar, the other corner on the first face's edge",
         {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {2, 2, 0}, {4, -4, 0}}, {0, 1, 2}, {0, 3, 4}, true},
        {"one shared vertex, coplanar, overlapping", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {4, 4, 0}, {4, -4, 0}},
         {0, 1, 2}, {0, 3, 4}, true},
        {"one shared vertex, edges along one line, coplanar", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {2, 0, 0}, {1, -3, 0}},
         {0, 1, 2}, {0, 3, 4}, true},
        {"one shared vertex, edges along one line, out of plane",
         {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {2, 0, 0}, {1, -3, 5}},
         {0, 1, 2}, {0, 3, 4}, true},
        {"one shared vertex, the other edge touching the first face",
         {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0}, {1, 1, 3}},
         {0, 1, 2}, {0, 3, 4}, true},
        // A shared edge 0-1.
        {"fold along a shared edge (coplanar, same side)", {{0, 0, 0}, {4, 0, 0}, {1, 2, 0}, {3, 1, 0}},
         {0, 1, 2}, {1, 0, 3}, true},
        {"fold, the opposite vertex on the other face", {{0, 0, 0}, {4, 0, 0}, {1, 2, 0}, {1, 1, 0}},
         {0, 1, 2}, {1, 0, 3}, true},
        {"flat pair (coplanar, opposite sides)", {{0, 0, 0}, {4, 0, 0}, {1, 2, 0}, {3, -1, 0}},
         {0, 1, 2}, {1, 0, 3}, false},
        {"dihedral pair (not coplanar)", {{0, 0, 0}, {4, 0, 0}, {1, 2, 0}, {2, 1, 3}},
         {0, 1, 2}, {1, 0, 3}, false},
        {"sharp dihedral pair", {{0, 0, 0}, {4, 0, 0}, {1, 2, 0}, {2, 2, 1}},
         {0, 1, 2}, {1, 0, 3}, false},
        // No shared index.
        {"coplanar overlap", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0}, {5, 1, 0}, {1, 5, 0}},
         {0, 1, 2}, {3, 4, 5}, true},
        {"one inside the other (coplanar)", {{0, 0, 0}, {6, 0, 0}, {0, 6, 0}, {1, 1, 0}, {2, 1, 0}, {1, 2, 0}},
         {0, 1, 2}, {3, 4, 5}, true},
        {"coplanar, apart", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {3, 3, 0}, {5, 1, 0}, {5, 5, 0}},
         {0, 1, 2}, {3, 4, 5}, false},
        {"coplanar, touching edge to edge", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {2, 2, 0}, {5, 1, 0}, {5, 5, 0}},
         {0, 1, 2}, {3, 4, 5}, true},
        {"touching at one point, a corner on an edge",
         {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {2, 0, 0}, {2, -3, 1}, {3, -3, -1}},
         {0, 1, 2}, {3, 4, 5}, true},
        {"touching at one point, corner on corner (no shared index)",
         {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {4, 0, 0}, {5, -3, 1}, {6, -1, -1}}, {0, 1, 2}, {3, 4, 5}, true},
        {"crossing through the middle", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, -1}, {1, 1, 1}, {-3, -3, 0}},
         {0, 1, 2}, {3, 4, 5}, true},
        {"one edge in the other's plane, inside it", {{0, 0, 0}, {6, 0, 0}, {0, 6, 0}, {1, 1, 0}, {2, 1, 0}, {1, 1, 4}},
         {0, 1, 2}, {3, 4, 5}, true},
        {"parallel planes", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 1}, {4, 0, 1}, {0, 4, 1}},
         {0, 1, 2}, {3, 4, 5}, false},
        {"near miss across the hypotenuse", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {3, 2, -1}, {3, 2, 1}, {5, 5, 0}},
         {0, 1, 2}, {3, 4, 5}, false},
        // Three shared indices.
        {"the same face twice", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, {0, 1, 2}, {1, 2, 0}, true},
        {"the same face twice, reversed", {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}}, {0, 1, 2}, {0, 2, 1}, true},
    };
    // clang-format on
    for (const Case& c : cases) {
        INFO(c.name);
        for (int r = 0; r < 3; ++r)
            for (const bool flip : {false, true}) {
                const Verdict v = judge(c.points, rewritten(c.t, r, flip), rewritten(c.u, (r + 1) % 3, !flip));
                CHECK(v.reference == c.expected);
                CHECK(v.exact == c.expected);
                const Verdict w = judge(c.points, rewritten(c.u, r, flip), rewritten(c.t, 2 - r, flip));
                CHECK(w.exact == c.expected);
            }
    }
}

TEST_CASE("triangle intersection: hand-made segments, library and reference agree") {
    struct Case {
        const char* name;
        IPoint p, q;
        bool expected;
    };
    const IPoint a{0, 0, 0}, b{4, 0, 0}, c{0, 4, 0};
    const std::vector<Case> cases = {
        {"piercing the inside", {1, 1, -1}, {1, 1, 1}, true},
        {"piercing beyond the hypotenuse", {3, 3, -1}, {3, 3, 1}, false},
        {"ending on the face", {1, 1, 0}, {1, 1, 5}, true},
        {"ending on an edge", {2, 0, 0}, {2, -3, 5}, true},
        {"ending just short of the face", {1, 1, 1}, {1, 1, 5}, false},
        {"in the plane, crossing", {-1, 1, 0}, {5, 1, 0}, true},
        {"in the plane, inside", {1, 1, 0}, {2, 1, 0}, true},
        {"in the plane, grazing a corner", {-2, 2, 0}, {2, -2, 0}, true},
        {"in the plane, missing a corner", {-2, 1, 0}, {1, -2, 0}, false},
        {"in the plane, along an edge", {-2, 0, 0}, {6, 0, 0}, true},
        {"in the plane, on an edge's line beyond it", {5, 0, 0}, {7, 0, 0}, false},
        {"in the plane, touching a corner end to end", {4, 0, 0}, {6, 1, 0}, true},
        {"in the plane, parallel to an edge, outside", {-1, -1, 0}, {5, -1, 0}, false},
        {"a point inside", {1, 2, 0}, {1, 2, 0}, true},
        {"a point on an edge", {2, 2, 0}, {2, 2, 0}, true},
        {"a point outside in the plane", {3, 3, 0}, {3, 3, 0}, false},
        {"a point off the plane", {1, 1, 1}, {1, 1, 1}, false},
        {"through a corner, out of the plane", {-1, -1, -1}, {1, 1, 1}, true},
        {"through an edge's middle, out of the plane", {2, -1, -1}, {2, 1, 1}, true},
    };
    for (const Case& k : cases) {
        INFO(k.name);
        CHECK(reference_segment_meets_triangle(k.p, k.q, a, b, c) == k.expected);
        CHECK(segment_intersects_triangle(to_vec3(k.p), to_vec3(k.q), to_vec3(a), to_vec3(b), to_vec3(c)) ==
              k.expected);
        CHECK(segment_intersects_triangle(to_vec3(k.q), to_vec3(k.p), to_vec3(b), to_vec3(c), to_vec3(a)) ==
              k.expected);
        CHECK(segment_intersects_triangle(to_vec3(k.p), to_vec3(k.q), to_vec3(a), to_vec3(c), to_vec3(b)) ==
              k.expected);
    }
}

TEST_CASE("triangle intersection: degenerate faces are recognised and not judged") {
    const std::vector<Vec3> p = {{0, 0, 0}, {4, 0, 0},  {8, 0, 0}, {0, 4, 0},
                                 {2, 0, 0}, {1, 1, -1}, {1, 1, 1}, {0, 0, 0}};
    CHECK(triangle_degenerate(p[0], p[1], p[2]));  // collinear
    CHECK(triangle_degenerate(p[0], p[0], p[3]));  // a repeated corner
    CHECK(triangle_degenerate(p[0], p[7], p[3]));  // two indices at one position
    CHECK(!triangle_degenerate(p[0], p[1], p[3]));
    // Nearly collinear floats: off the line by one float ulp is not degenerate.
    const Vec3 a{1.0f, 1.0f, 1.0f}, b{3.0f, 5.0f, 7.0f};
    const Vec3 m{2.0f, 3.0f, 4.0f};
    CHECK(triangle_degenerate(a, b, m));
    CHECK(!triangle_degenerate(a, b, {2.0f, 3.0f, std::nextafter(4.0f, 5.0f)}));
    // A degenerate face crossing a real one is not reported by the rule.
    CHECK(!faces_intersect(p.data(), {0, 1, 2}, {3, 5, 6}));
    CHECK(!faces_intersect(p.data(), {5, 5, 6}, {0, 1, 3}));
    CHECK(!faces_intersect(p.data(), {0, 7, 3}, {0, 1, 3}));
    // The same real faces do cross.
    CHECK(faces_intersect(p.data(), {0, 1, 3}, {5, 6, 4}));
}

TEST_CASE("triangle intersection: nearly coplanar floats that a double evaluation misjudges") {
    // Integer float coordinates of up to about 2^23: exact in float, but the determinant's terms
    // reach 2^70, beyond double. Points exactly on a plane z = x + 2 y - 3: exact orientation 0,
    // which a double evaluation often reports as nonzero. An __int128 determinant is the truth.
    __extension__ typedef __int128 Wide;
    const auto truth = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
        const Wide m[3][3] = {{Wide(a.x - d.x), Wide(a.y - d.y), Wide(a.z - d.z)},
                              {Wide(b.x - d.x), Wide(b.y - d.y), Wide(b.z - d.z)},
                              {Wide(c.x - d.x), Wide(c.y - d.y), Wide(c.z - d.z)}};
        const Wide det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        return (det > 0) - (det < 0);
    };
    const auto naive = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
        const double adx = double(a.x) - d.x, ady = double(a.y) - d.y, adz = double(a.z) - d.z;
        const double bdx = double(b.x) - d.x, bdy = double(b.y) - d.y, bdz = double(b.z) - d.z;
        const double cdx = double(c.x) - d.x, cdy = double(c.y) - d.y, cdz = double(c.z) - d.z;
        const double det =
            adx * (bdy * cdz - bdz * cdy) - ady * (bdx * cdz - bdz * cdx) + adz * (bdx * cdy - bdy * cdx);
        return (det > 0) - (det < 0);
    };
    Rng rng(11);
    const auto on_plane = [&](int lo, int hi) {
        const int x = uniform_int(rng, lo, hi), y = uniform_int(rng, lo, hi);
        return Vec3{float(x), float(y), float(x + 2 * y - 3)};  // |z| < 2^24: exact
    };
    int touch_misjudged = 0, fold_misjudged = 0, cases = 0;
    for (int i = 0; i < 4000; ++i) {
        // A large face, and a face standing on it with one corner on its plane inside it: they touch.
        const Vec3 a = on_plane(-2500000, -2000000), b = on_plane(2000000, 2500000);
        const Vec3 c{float(-500000), float(2500000), float(-500000 + 2 * 2500000 - 3)};
        const Vec3 d{-500000.0f, 1000000.0f, 1499997.0f};  // on the plane, inside abc
        REQUIRE(nmesh::orient2d({a.x, a.y}, {b.x, b.y}, {d.x, d.y}) ==
                nmesh::orient2d({a.x, a.y}, {b.x, b.y}, {c.x, c.y}));
        REQUIRE(nmesh::orient2d({b.x, b.y}, {c.x, c.y}, {d.x, d.y}) ==
                nmesh::orient2d({b.x, b.y}, {c.x, c.y}, {a.x, a.y}));
        REQUIRE(nmesh::orient2d({c.x, c.y}, {a.x, a.y}, {d.x, d.y}) ==
                nmesh::orient2d({c.x, c.y}, {a.x, a.y}, {b.x, b.y}));
        const Vec3 e = d + Vec3{0.0f, 0.0f, 4096.0f}, f = d + Vec3{4096.0f, 0.0f, 8192.0f + 4096.0f};
        REQUIRE(truth(a, b, c, d) == 0);
        REQUIRE(truth(a, b, c, e) != 0);
        REQUIRE(truth(a, b, c, e) == truth(a, b, c, f));
        const std::vector<Vec3> positions = {a, b, c, d, e, f};
        ++cases;
        CHECK(faces_intersect(positions.data(), {0, 1, 2}, {3, 4, 5}));
        CHECK(triangles_intersect_exact(a, b, c, d, e, f));
        // A double evaluation that puts d strictly on e's side sees all of def on one side.
        if (naive(a, b, c, d) == truth(a, b, c, e)) ++touch_misjudged;
        // A fold: faces pqa and pqb sharing the edge pq, all four points on the plane, a and b on
        // the same side of pq: counted. A double evaluation that finds the four points not
        // coplanar would pass it as a dihedral pair.
        const Vec3 p = on_plane(-3000000, 3000000), q = on_plane(-3000000, 3000000);
        const Vec3 s = on_plane(-3000000, 3000000), g = on_plane(-3000000, 3000000);
        if (triangle_degenerate(p, q, s) || triangle_degenerate(p, q, g)) continue;
        const std::vector<Vec3> quad = {p, q, s, g};
        const bool same_side =
            nmesh::orient2d({p.x, p.y}, {q.x, q.y}, {s.x, s.y}) == nmesh::orient2d({p.x, p.y}, {q.x, q.y}, {g.x, g.y});
        CHECK(faces_intersect(quad.data(), {0, 1, 2}, {1, 0, 3}) == same_side);
        CHECK(nmesh::orient3d(p, q, s, g) == 0);
        if (same_side && naive(p, q, s, g) != 0) ++fold_misjudged;
    }
    INFO("touching misjudged " << touch_misjudged << ", folds misjudged " << fold_misjudged << " of " << cases);
    CHECK(touch_misjudged > 0);
    CHECK(fold_misjudged > 0);
}

// ---- random comparisons with the reference -----------------------------------------------------

TEST_CASE("triangle intersection: random pairs in every sharing class against the exact reference") {
    Rng rng(12);
    // Tallies per sharing class (0, 1, 2 shared vertices): cases, intersecting, coplanar.
    int cases[3] = {0, 0, 0}, hits[3] = {0, 0, 0}, coplanar[3] = {0, 0, 0}, mismatches = 0;
    int degenerate_checked = 0, degenerate_mismatches = 0;
    for (int i = 0; i < 60000; ++i) {
        const int shared = i % 3;
        const PointSource source{uniform_int(rng, 0, 4)};
        const int count = 6 - shared;
        std::vector<IPoint> points;
        for (int k = 0; k < count; ++k) points.push_back(source(rng));
        // Sometimes a point repeats another's position under a different index (touching corners).
        if (shared == 0 && uniform_int(rng, 0, 3) == 0) points[std::size_t(uniform_int(rng, 3, 5))] = points[0];
        Face t{0, 1, 2};
        Face u = shared == 0 ? Face{3, 4, 5} : (shared == 1 ? Face{0, 3, 4} : Face{1, 0, 3});
        const Face t2 = rewritten(t, uniform_int(rng, 0, 2), uniform_int(rng, 0, 1) == 1);
        const Face u2 = rewritten(u, uniform_int(rng, 0, 2), uniform_int(rng, 0, 1) == 1);
        for (const Face& f : {t2, u2}) {
            ++degenerate_checked;
            const std::vector<Vec3> v = to_vec3(points);
            if (triangle_degenerate(v[f[0]], v[f[1]], v[f[2]]) !=
                reference_degenerate(points[f[0]], points[f[1]], points[f[2]]))
                ++degenerate_mismatches;
        }
        if (reference_degenerate(points[0], points[1], points[2]) ||
            reference_degenerate(points[u[0]], points[u[1]], points[u[2]]))
            continue;
        const Verdict v = judge(points, t2, u2);
        ++cases[shared];
        if (v.reference) ++hits[shared];
        const IPoint n = cross(minus(points[1], points[0]), minus(points[2], points[0]));
        if (dot(n, minus(points[u[0]], points[0])) == 0 && dot(n, minus(points[u[1]], points[0])) == 0 &&
            dot(n, minus(points[u[2]], points[0])) == 0)
            ++coplanar[shared];
        if (v.exact != v.reference) {
            ++mismatches;
            if (mismatches <= 5) {
                std::string s;
                for (const IPoint& p : points)
                    s += "(" + std::to_string(p.x) + "," + std::to_string(p.y) + "," + std::to_string(p.z) + ") ";
                MESSAGE("mismatch: shared " << shared << " points " << s << " reference " << v.reference);
            }
        }
        // Without shared vertices, the closed test itself.
        if (shared == 0) {
            const std::vector<Vec3> p = to_vec3(points);
            if (triangles_intersect_exact(p[t2[0]], p[t2[1]], p[t2[2]], p[u2[0]], p[u2[1]], p[u2[2]]) != v.reference)
                ++mismatches;
        }
    }
    INFO("cases " << cases[0] << "/" << cases[1] << "/" << cases[2] << ", intersecting " << hits[0] << "/" << hits[1]
                  << "/" << hits[2] << ", coplanar " << coplanar[0] << "/" << coplanar[1] << "/" << coplanar[2]);
    CHECK(mismatches == 0);
    CHECK(degenerate_mismatches == 0);
    for (int s = 0; s < 3; ++s) {
        // Every class is well represented, with both verdicts and coplanar configurations.
        CHECK(cases[s] > 10000);
        CHECK(hits[s] > cases[s] / 20);
        CHECK(hits[s] < cases[s] - cases[s] / 20);
        CHECK(coplanar[s] > cases[s] / 10);
    }
}

TEST_CASE("triangle intersection: random segments against the exact reference") {
    Rng rng(13);
    int cases = 0, hits = 0, in_plane = 0, mismatches = 0;
    for (int i = 0; i < 40000; ++i) {
        const PointSource source{uniform_int(rng, 0, 4)};
        const IPoint a = source(rng), b = source(rng), c = source(rng);
        if (reference_degenerate(a, b, c)) continue;
        const IPoint p = source(rng);
        IPoint q = i % 10 == 0 ? p : source(rng);                            // some single points
        if (i % 10 == 1) q = {2 * a.x - p.x, 2 * a.y - p.y, 2 * a.z - p.z};  // through the corner a
        ++cases;
        const bool reference = reference_segment_meets_triangle(p, q, a, b, c);
        if (reference) ++hits;
        const IPoint n = cross(minus(b, a), minus(c, a));
        if (dot(n, minus(p, a)) == 0 && dot(n, minus(q, a)) == 0) ++in_plane;
        if (segment_intersects_triangle(to_vec3(p), to_vec3(q), to_vec3(a), to_vec3(b), to_vec3(c)) != reference)
            ++mismatches;
        if (segment_intersects_triangle(to_vec3(q), to_vec3(p), to_vec3(c), to_vec3(b), to_vec3(a)) != reference)
            ++mismatches;
    }
    INFO("cases " << cases << ", meeting " << hits << ", in the plane " << in_plane);
    CHECK(mismatches == 0);
    CHECK(hits > cases / 10);
    CHECK(in_plane > cases / 10);
}

// ---- the mesh search ---------------------------------------------------------------------------

TEST_CASE("self-intersections: random small meshes equal the brute force") {
    Rng rng(14);
    std::size_t total_pairs = 0, total_degenerate = 0;
    for (int m = 0; m < 300; ++m) {
        const PointSource source{uniform_int(rng, 0, 4)};
        const int point_count = uniform_int(rng, 5, 25);
        std::vector<Vec3> positions;
        for (int k = 0; k < point_count; ++k) positions.push_back(to_vec3(source(rng)));
        // Some meshes in float coordinates of unequal sizes, for the grid.
        if (m % 4 == 3)
            for (Vec3& p : positions) p = p * float(std::ldexp(1.0, uniform_int(rng, -3, 3))) + Vec3{0.1f, -0.2f, 0.3f};
        std::vector<Face> faces;
        const int face_count = uniform_int(rng, 2, 80);
        for (int f = 0; f < face_count; ++f) {
            const auto v = [&] { return std::uint32_t(uniform_int(rng, 0, point_count - 1)); };
            faces.push_back({v(), v(), v()});
            if (triangle_degenerate(positions[faces.back()[0]], positions[faces.back()[1]], positions[faces.back()[2]]))
                ++total_degenerate;
        }
        const IndexedMesh mesh = make_mesh(positions, faces);
        const Pairs expected = brute_force_pairs(mesh);
        const Pairs found = nmesh::self_intersecting_pairs(mesh);
        CHECK(found == expected);
        CHECK(nmesh::count_self_intersections(mesh) == expected.size());
        // A limit keeps the first pairs of the sorted list.
        const std::size_t limit = std::size_t(uniform_int(rng, 0, 5));
        const Pairs limited = nmesh::self_intersecting_pairs(mesh, limit);
        CHECK(limited == Pairs(expected.begin(), expected.begin() + std::ptrdiff_t(std::min(limit, expected.size()))));
        total_pairs += expected.size();
    }
    CHECK(total_pairs > 1000);
    CHECK(total_degenerate > 100);
}

TEST_CASE("self-intersections: a random soup of small floats equals the brute force") {
    Rng rng(15);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), small(-0.06f, 0.06f);
    std::vector<Vec3> positions;
    std::vector<Face> faces;
    for (std::uint32_t f = 0; f < 1500; ++f) {
        const Vec3 c{unit(rng), unit(rng), unit(rng)};
        for (int k = 0; k < 3; ++k) positions.push_back(c + Vec3{small(rng), small(rng), small(rng)});
        faces.push_back({3 * f, 3 * f + 1, 3 * f + 2});
    }
    // A few large faces across the whole box.
    positions.push_back({0, 0, 0});
    positions.push_back({1, 0, 1});
    positions.push_back({0, 1, 1});
    faces.push_back({4500, 4501, 4502});
    const IndexedMesh mesh = make_mesh(positions, faces);
    const Pairs expected = brute_force_pairs(mesh);
    CHECK(expected.size() > 100);
    CHECK(nmesh::self_intersecting_pairs(mesh) == expected);
}

TEST_CASE("self-intersections: a sparse soup of tiny faces (a coarsened grid) equals the brute force") {
    // Faces a thousandth of the box wide, scattered in 3D: cells that wide would number about a
    // billion, so the grid must coarsen. Every tenth face gets a crossing partner.
    Rng rng(16);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), tiny(-0.001f, 0.001f);
    std::vector<Vec3> positions;
    std::vector<Face> faces;
    for (std::uint32_t f = 0; f < 1000; ++f) {
        const Vec3 c{unit(rng), unit(rng), unit(rng)};
        const std::uint32_t base = std::uint32_t(positions.size());
        positions.push_back(c + Vec3{0.001f, 0, 0});
        positions.push_back(c + Vec3{0, 0.001f, 0});
        positions.push_back(c + Vec3{-0.001f, -0.001f, tiny(rng)});
        faces.push_back({base, base + 1, base + 2});
        if (f % 10 == 0) {
            positions.push_back(c + Vec3{0, 0, -0.001f});
            positions.push_back(c + Vec3{0, 0, 0.001f});
            positions.push_back(c + Vec3{0.0005f, 0.0005f, 0});
            faces.push_back({base + 3, base + 4, base + 5});
        }
    }
    const IndexedMesh mesh = make_mesh(positions, faces);
    const Pairs expected = brute_force_pairs(mesh);
    CHECK(expected.size() >= 100);
    CHECK(nmesh::self_intersecting_pairs(mesh) == expected);
}

TEST_CASE("self-intersections: closed meshes have none until a vertex is pushed through") {
    SUBCASE("subdivided octahedron (integer, many coplanar neighbours)") {
        IndexedMesh mesh = subdivided_octahedron(6);
        REQUIRE(mesh.triangles.size() == 8 * 36);
        CHECK(brute_force_pairs(mesh).empty());
        CHECK(nmesh::self_intersecting_pairs(mesh).empty());
        // The top vertex pushed down through the bottom: its faces cross the lower faces.
        const std::uint32_t top = std::uint32_t(std::find(mesh.positions.begin(), mesh.positions.end(), Vec3{0, 0, 6}) -
                                                mesh.positions.begin());
        REQUIRE(top < mesh.positions.size());
        mesh.positions[top] = {0, 0, -9};
        const Pairs expected = brute_force_pairs(mesh);
        CHECK(expected.size() >= 8);
        CHECK(nmesh::self_intersecting_pairs(mesh) == expected);
        // Pushed just onto the bottom vertex's position: the faces touch the bottom at a point.
        mesh.positions[top] = {0, 0, -6};
        // Inside the octahedron but for that point, each of the top's 4 faces touches each of the
        // bottom's 4 faces there.
        const Pairs touching = brute_force_pairs(mesh);
        CHECK(touching.size() == 16);
        CHECK(nmesh::self_intersecting_pairs(mesh) == touching);
    }
    SUBCASE("icosphere (floats on the unit sphere)") {
        IndexedMesh mesh = icosphere(3);
        REQUIRE(mesh.triangles.size() == 1280);
        CHECK(brute_force_pairs(mesh).empty());
        CHECK(nmesh::self_intersecting_pairs(mesh).empty());
        mesh.positions[0] = mesh.positions[0] * -0.5f;  // through the centre, inside the far side
        Pairs expected = brute_force_pairs(mesh);
        CHECK(nmesh::self_intersecting_pairs(mesh) == expected);
        mesh.positions[0] = mesh.positions[0] * 4.0f;  // beyond the far side
        expected = brute_force_pairs(mesh);
        CHECK(expected.size() >= 5);
        CHECK(nmesh::self_intersecting_pairs(mesh) == expected);
    }
    SUBCASE("a face duplicated, and two interpenetrating closed meshes") {
        IndexedMesh mesh = subdivided_octahedron(2);
        mesh.triangles.push_back(rewritten(mesh.triangles[5], 1, true));
        const Pairs dup = nmesh::self_intersecting_pairs(mesh);
        REQUIRE(!dup.empty());
        CHECK(dup == brute_force_pairs(mesh));
        CHECK(std::find(dup.begin(), dup.end(), std::make_pair(5u, std::uint32_t(mesh.triangles.size() - 1))) !=
              dup.end());

        IndexedMesh two = subdivided_octahedron(2);
        const std::uint32_t offset = std::uint32_t(two.positions.size());
        const std::size_t faces = two.triangles.size();
        for (std::size_t v = 0; v < offset; ++v) two.positions.push_back(two.positions[v] + Vec3{1, 1, 0});
        for (std::size_t f = 0; f < faces; ++f) {
            const Face g = two.triangles[f];
            two.triangles.push_back({g[0] + offset, g[1] + offset, g[2] + offset});
        }
        const Pairs expected = brute_force_pairs(two);
        CHECK(expected.size() > 5);
        CHECK(nmesh::self_intersecting_pairs(two) == expected);
    }
}

TEST_CASE("self-intersections: a 60,000-face torus, intact and with a vertex pushed through") {
    IndexedMesh mesh = torus(200, 150);
    REQUIRE(mesh.triangles.size() == 60000);
    CHECK(nmesh::self_intersecting_pairs(mesh).empty());
    // A vertex on the outer equator pushed across the tube: every pair now involves one of its
    // faces, so the brute force over those faces against all others is complete.
    const std::uint32_t v = 0;  // u = 0, v = 0: the point (1.4, 0, 0)
    mesh.positions[v] = {0.45f, 0.0f, 0.0f};
    const std::vector<std::uint32_t> moved = faces_around(mesh, v);
    REQUIRE(moved.size() == 6);
    Pairs expected;
    for (std::uint32_t s : moved)
        for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
            if (t != s && faces_intersect(mesh.positions.data(), mesh.triangles[s], mesh.triangles[t]))
                expected.emplace_back(std::min(s, t), std::max(s, t));
    std::sort(expected.begin(), expected.end());
    expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
    CHECK(expected.size() >= 6);
    CHECK(nmesh::self_intersecting_pairs(mesh) == expected);
    CHECK(nmesh::count_self_intersections(mesh) == expected.size());
}

TEST_CASE("self-intersections: bad input") {
    IndexedMesh mesh = subdivided_octahedron(1);
    CHECK(nmesh::self_intersecting_pairs(mesh).empty());
    // Faces with a non-finite corner are skipped.
    IndexedMesh nan_mesh = mesh;
    nan_mesh.positions.push_back({std::nanf(""), 0, 0});
    nan_mesh.triangles.push_back({0, 1, std::uint32_t(nan_mesh.positions.size() - 1)});
    CHECK(nmesh::self_intersecting_pairs(nan_mesh).empty());
    // An index past the positions is an input error.
    mesh.triangles.push_back({0, 1, 99});
    CHECK_THROWS_AS(nmesh::self_intersecting_pairs(mesh), nmesh::InputError);
    CHECK_THROWS_AS(nmesh::count_self_intersections(mesh), nmesh::InputError);
    // Nothing to compare.
    CHECK(nmesh::self_intersecting_pairs(IndexedMesh{}).empty());
}
