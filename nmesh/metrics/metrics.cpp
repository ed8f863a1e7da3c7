#include "nmesh/metrics.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <locale>
#include <numeric>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <utility>

#include "nmesh/bounding_box.h"
#include "nmesh/error.h"
#include "nmesh/util/math_constants.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

namespace {

using Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Triangles whose smallest angle is below this are counted as poorly shaped (a common threshold
// in meshing; 60 degrees is the equilateral optimum).
constexpr double kSmallAngleDeg = 10.0;
// Triangles per leaf of the triangle hierarchy: few enough that a leaf's distances are cheap,
// enough that the tree stays shallow.
constexpr std::uint32_t kLeafSize = 4;

Vector3d to_eigen(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }


// ---- geometric predicates -----------------------------------------------------------------------

// Six times the signed volume of the tetrahedron abcd; its sign tells on which side of the plane
// of abc the point d lies (0: on it).
double orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vector3d ad = to_eigen(a) - to_eigen(d);
    const Vector3d bd = to_eigen(b) - to_eigen(d);
    const Vector3d cd = to_eigen(c) - to_eigen(d);
    return ad.dot(bd.cross(cd));
}

int sign(double x) { return (x > 0.0) - (x < 0.0); }

// Twice the signed area of the 2D triangle abc.
double orient2d(const double a[2], const double b[2], const double c[2]) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// Whether c, known to be collinear with the segment ab, lies on it.
bool on_segment_2d(const double a[2], const double b[2], const double c[2]) {
    return std::min(a[0], b[0]) <= c[0] && c[0] <= std::max(a[0], b[0]) &&
           std::min(a[1], b[1]) <= c[1] && c[1] <= std::max(a[1], b[1]);
}

// Whether the closed 2D segments pq and rs meet.
bool segments_meet_2d(const double p[2], const double q[2], const double r[2], const double s[2]) {
    const int d1 = sign(orient2d(r, s, p)), d2 = sign(orient2d(r, s, q));
    const int d3 = sign(orient2d(p, q, r)), d4 = sign(orient2d(p, q, s));
    if (d1 * d2 < 0 && d3 * d4 < 0) return true;
    return (d1 == 0 && on_segment_2d(r, s, p)) || (d2 == 0 && on_segment_2d(r, s, q)) ||
           (d3 == 0 && on_segment_2d(p, q, r)) || (d4 == 0 && on_segment_2d(p, q, s));
}

// Whether p lies in the closed 2D triangle abc (of either orientation, non-degenerate).
bool inside_triangle_2d(const double p[2], const double a[2], const double b[2], const double c[2]) {
    const int s1 = sign(orient2d(a, b, p)), s2 = sign(orient2d(b, c, p)), s3 = sign(orient2d(c, a, p));
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Two coplanar triangles: project them on the coordinate plane most parallel to theirs and test
// edge crossings and containment.
bool coplanar_triangles_intersect(const Vec3 t1[3], const Vec3 t2[3]) {
    const Vector3d n = (to_eigen(t1[1]) - to_eigen(t1[0])).cross(to_eigen(t1[2]) - to_eigen(t1[0]));
    int drop = 0;
    n.cwiseAbs().maxCoeff(&drop);
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    double p[3][2], q[3][2];
    for (int i = 0; i < 3; ++i) {
        p[i][0] = t1[i][u];
        p[i][1] = t1[i][v];
        q[i][0] = t2[i][u];
        q[i][1] = t2[i][v];
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (segments_meet_2d(p[i], p[(i + 1) % 3], q[j], q[(j + 1) % 3])) return true;
    return inside_triangle_2d(p[0], q[0], q[1], q[2]) || inside_triangle_2d(q[0], p[0], p[1], p[2]);
}

// Whether the segment pq, whose ends lie on opposite sides of the plane of abc (or on it, but not
// both), meets the triangle abc: the line pq must pass on the same side of all three edges.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const int s1 = sign(orient3d(p, q, a, b)), s2 = sign(orient3d(p, q, b, c));
    const int s3 = sign(orient3d(p, q, c, a));
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Whether the triangle `t` crosses the plane of `other` through one of its edges; `side[i]` is the
// side of the plane of `other` on which t[i] lies.
bool edges_cross_triangle(const Vec3 t[3], const int side[3], const Vec3 other[3]) {
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        if (side[i] * side[j] > 0 || (side[i] == 0 && side[j] == 0)) continue;
        if (segment_crosses_triangle(t[i], t[j], other[0], other[1], other[2])) return true;
    }
    return false;
}

// ---- the triangle hierarchy ---------------------------------------------------------------------

// A bounding-volume hierarchy over the triangles of a mesh, split at the median centroid along the
// widest axis: O(F log F) to build, about O(log F) per nearest-triangle query.
class TriangleBvh {
public:
    explicit TriangleBvh(const IndexedMesh& mesh) : mesh_(mesh) {
        const std::size_t f = mesh.triangles.size();
        boxes_.resize(f);
        centroids_.resize(f);
        order_.resize(f);
        for (std::uint32_t t = 0; t < f; ++t) {
            const auto& tri = mesh.triangles[t];
            BoundingBox b;
            b.min = b.max = mesh.positions[tri[0]];
            b = united(b, BoundingBox{mesh.positions[tri[1]], mesh.positions[tri[1]]});
            b = united(b, BoundingBox{mesh.positions[tri[2]], mesh.positions[tri[2]]});
            boxes_[t] = b;
            centroids_[t] = b.center();
            order_[t] = t;
        }
        nodes_.reserve(2 * (f / kLeafSize + 1));
        nodes_.emplace_back();
        build(0, 0, std::uint32_t(f));
    }

    // Squared distance from p to the nearest triangle, given an upper bound on it (kInf if none).
    double nearest_squared_distance(const Vec3& p, double bound) const {
        double best = bound;
        // Each entry keeps its box's distance, computed when it was pushed: on popping, the best
        // may since have dropped below it.
        struct Entry {
            std::uint32_t node;
            double box_distance;
        };
        Entry stack[64];
        int top = 0;
        stack[top++] = {0, box_squared_distance(nodes_[0].box, p)};
        while (top > 0) {
            const Entry e = stack[--top];
            if (e.box_distance > best) continue;
            const Node& n = nodes_[e.node];
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                    // A triangle whose box is farther than the best cannot be nearer.
                    if (box_squared_distance(boxes_[order_[i]], p) > best) continue;
                    const auto& t = mesh_.triangles[order_[i]];
                    const double d = point_triangle_squared_distance(
                        p, mesh_.positions[t[0]], mesh_.positions[t[1]], mesh_.positions[t[2]]);
                    best = std::min(best, d);
                }
                continue;
            }
            // Children: the nearer is pushed last, so it is searched first.
            const std::uint32_t l = n.first, r = n.first + 1;
            const double dl = box_squared_distance(nodes_[l].box, p);
            const double dr = box_squared_distance(nodes_[r].box, p);
            assert(top + 2 <= 64);
            if (dl <= dr) {
                if (dr <= best) stack[top++] = {r, dr};
                if (dl <= best) stack[top++] = {l, dl};
            } else {
                if (dl <= best) stack[top++] = {l, dl};
                if (dr <= best) stack[top++] = {r, dr};
            }
        }
        return best;
    }

    // Calls visit(s, t) once for every unordered pair of distinct triangles whose boxes overlap.
    template <class Visit>
    void for_each_overlapping_pair(Visit&& visit) const {
        self_pairs(0, visit);
    }

private:
    struct Node {
        BoundingBox box;
        std::uint32_t first = 0;  // leaf: first entry of order_; inner: index of the left child
        std::uint32_t count = 0;  // leaf: number of triangles; 0 for an inner node
    };

    static double box_squared_distance(const BoundingBox& b, const Vec3& p) {
        double d2 = 0.0;
        for (int a = 0; a < 3; ++a) {
            const double x = double(p[a]);
            const double g = x < double(b.min[a]) ? double(b.min[a]) - x
                                                  : (x > double(b.max[a]) ? x - double(b.max[a]) : 0.0);
            d2 += g * g;
        }
        return d2;
    }

    static bool boxes_overlap(const BoundingBox& a, const BoundingBox& b) {
        return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
               a.min.z <= b.max.z && b.min.z <= a.max.z;
    }

    // Builds the subtree of `node` over order_[first, last) and sets its box.
    void build(std::uint32_t node, std::uint32_t first, std::uint32_t last) {
        if (last - first <= kLeafSize) {
            BoundingBox box = boxes_[order_[first]];
            for (std::uint32_t i = first + 1; i < last; ++i) box = united(box, boxes_[order_[i]]);
            nodes_[node].box = box;
            nodes_[node].first = first;
            nodes_[node].count = last - first;
            return;
        }
        Vec3 lo = centroids_[order_[first]], hi = lo;
        for (std::uint32_t i = first + 1; i < last; ++i) {
            const Vec3& c = centroids_[order_[i]];
            for (int a = 0; a < 3; ++a) {
                lo[a] = c[a] < lo[a] ? c[a] : lo[a];
                hi[a] = c[a] > hi[a] ? c[a] : hi[a];
            }
        }
        const Vec3 e = hi - lo;
        const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        const std::uint32_t mid = first + (last - first) / 2;
        std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + last,
                         [&](std::uint32_t s, std::uint32_t t) {
                             return centroids_[s][axis] < centroids_[t][axis];
                         });
        const std::uint32_t left = std::uint32_t(nodes_.size());
        nodes_.emplace_back();
        nodes_.emplace_back();
        nodes_[node].first = left;
        nodes_[node].count = 0;
        build(left, first, mid);
        build(left + 1, mid, last);
        nodes_[node].box = united(nodes_[left].box, nodes_[left + 1].box);
    }

    static BoundingBox united(const BoundingBox& a, const BoundingBox& b) {
        BoundingBox u;
        for (int i = 0; i < 3; ++i) {
            u.min[i] = a.min[i] < b.min[i] ? a.min[i] : b.min[i];
            u.max[i] = a.max[i] > b.max[i] ? a.max[i] : b.max[i];
        }
        return u;
    }

    template <class Visit>
    void leaf_pairs(const Node& a, const Node& b, Visit& visit) const {
        for (std::uint32_t i = a.first; i < a.first + a.count; ++i)
            for (std::uint32_t j = b.first; j < b.first + b.count; ++j)
                if (boxes_overlap(boxes_[order_[i]], boxes_[order_[j]])) visit(order_[i], order_[j]);
    }

    template <class Visit>
    void self_pairs(std::uint32_t node, Visit& visit) const {
        const Node& n = nodes_[node];
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
                for (std::uint32_t j = i + 1; j < n.first + n.count; ++j)
                    if (boxes_overlap(boxes_[order_[i]], boxes_[order_[j]])) visit(order_[i], order_[j]);
            return;
        }
        self_pairs(n.first, visit);
        self_pairs(n.first + 1, visit);
        cross_pairs(n.first, n.first + 1, visit);
    }

    template <class Visit>
    void cross_pairs(std::uint32_t a, std::uint32_t b, Visit& visit) const {
        const Node& na = nodes_[a];
        const Node& nb = nodes_[b];
        if (!boxes_overlap(na.box, nb.box)) return;
        if (na.count > 0 && nb.count > 0) {
            leaf_pairs(na, nb, visit);
        } else if (na.count > 0) {
            cross_pairs(a, nb.first, visit);
            cross_pairs(a, nb.first + 1, visit);
        } else {
            cross_pairs(na.first, b, visit);
            cross_pairs(na.first + 1, b, visit);
        }
    }

    const IndexedMesh& mesh_;
    std::vector<BoundingBox> boxes_;  // per triangle
    std::vector<Vec3> centroids_;     // per triangle, of its box
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
};

// ---- topology -----------------------------------------------------------------------------------

class UnionFind {
public:
    explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
    std::uint32_t find(std::uint32_t x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<std::uint32_t> parent_;
};

bool has_repeated_vertex(const std::array<std::uint32_t, 3>& t) {
    return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
}

bool is_degenerate(const IndexedMesh& mesh, const std::array<std::uint32_t, 3>& t) {
    if (has_repeated_vertex(t)) return true;
    const Vector3d a = to_eigen(mesh.positions[t[0]]);
    const Vector3d n = (to_eigen(mesh.positions[t[1]]) - a).cross(to_eigen(mesh.positions[t[2]]) - a);
    return n.squaredNorm() == 0.0;
}

// Fills the topology fields of the report.
void analyze_topology(const IndexedMesh& mesh, QualityReport& r) {
    const std::size_t nv = mesh.positions.size(), nf = mesh.triangles.size();

    // Each directed edge of each triangle, grouped by undirected edge.
    struct HalfEdge {
        std::uint64_t key;  // (smaller vertex << 32) | larger vertex
        std::uint32_t face;
        std::uint8_t corner;  // the edge runs from corner `corner` to the next corner of `face`
    };
    std::vector<HalfEdge> half_edges;
    half_edges.reserve(3 * nf);
    bool manifold = true;
    for (std::uint32_t f = 0; f < nf; ++f) {
        const auto& t = mesh.triangles[f];
        if (has_repeated_vertex(t)) manifold = false;  // an edge from a vertex to itself
        for (std::uint8_t i = 0; i < 3; ++i) {
            const std::uint32_t u = t[i], w = t[(i + 1) % 3];
            if (u == w) continue;
            half_edges.push_back({(std::uint64_t(std::min(u, w)) << 32) | std::max(u, w), f, i});
        }
    }
    std::sort(half_edges.begin(), half_edges.end(),
              [](const HalfEdge& a, const HalfEdge& b) { return a.key < b.key; });

    // Edges: closed when all are shared by two triangles; manifold needs at most two, running in
    // opposite directions. Corners around a vertex are linked through the edges they share, so
    // that each vertex's fans can be counted.
    bool closed = true;
    std::size_t edges = 0;
    UnionFind corners(3 * nf);
    const auto from = [&](const HalfEdge& h) { return mesh.triangles[h.face][h.corner]; };
    for (std::size_t i = 0; i < half_edges.size();) {
        std::size_t j = i;
        while (j < half_edges.size() && half_edges[j].key == half_edges[i].key) ++j;
        ++edges;
        const std::size_t count = j - i;
        if (count != 2) closed = false;
        if (count > 2) manifold = false;
        if (count == 2) {
            const HalfEdge &a = half_edges[i], &b = half_edges[i + 1];
            if (from(a) == from(b)) manifold = false;  // both triangles run the edge the same way
            // a runs u -> w; b runs w -> u (or u -> w when inconsistent): link the corners at u
            // and at w of the two triangles.
            const std::uint32_t a_from = 3 * a.face + a.corner, a_to = 3 * a.face + (a.corner + 1) % 3;
            const std::uint32_t b_from = 3 * b.face + b.corner, b_to = 3 * b.face + (b.corner + 1) % 3;
            if (from(a) == from(b)) {
                corners.unite(a_from, b_from);
                corners.unite(a_to, b_to);
            } else {
                corners.unite(a_from, b_to);
                corners.unite(a_to, b_from);
            }
        }
        i = j;
    }
    // One fan per vertex: all corners of a vertex in one linked group.
    if (manifold) {
        std::vector<std::uint32_t> fan(nv, std::numeric_limits<std::uint32_t>::max());
        for (std::uint32_t c = 0; c < 3 * nf && manifold; ++c) {
            const std::uint32_t v = mesh.triangles[c / 3][c % 3];
            const std::uint32_t root = corners.find(c);
            if (fan[v] == std::numeric_limits<std::uint32_t>::max()) fan[v] = root;
            else if (fan[v] != root) manifold = false;
        }
    }

    // Components through shared vertices, and the Euler characteristic of each.
    std::vector<char> used(nv, 0);
    UnionFind vertices(nv);
    for (const auto& t : mesh.triangles) {
        used[t[0]] = used[t[1]] = used[t[2]] = 1;
        vertices.unite(t[0], t[1]);
        vertices.unite(t[1], t[2]);
    }
    std::vector<long long> chi(nv, 0);  // indexed by component root
    std::size_t referenced = 0, components = 0;
    for (std::uint32_t v = 0; v < nv; ++v) {
        if (!used[v]) continue;
        ++referenced;
        const std::uint32_t root = vertices.find(v);
        if (root == v) ++components;
        ++chi[root];
    }
    for (std::size_t i = 0; i < half_edges.size(); ++i)
        if (i == 0 || half_edges[i].key != half_edges[i - 1].key)
            --chi[vertices.find(std::uint32_t(half_edges[i].key >> 32))];
    for (const auto& t : mesh.triangles) ++chi[vertices.find(t[0])];

    r.closed = closed;
    r.manifold = manifold;
    r.euler = (long long)referenced - (long long)edges + (long long)nf;
    r.components = components;
    r.isolated_vertices = nv - referenced;
    r.genus = -1;
    if (closed && manifold) {
        long long genus = 0;
        for (std::uint32_t v = 0; v < nv; ++v)
            if (used[v] && vertices.find(v) == v) genus += (2 - chi[v]) / 2;
        r.genus = int(genus);
    }
}

// ---- sampling -----------------------------------------------------------------------------------

// A double uniform in [0, 1) from the top 53 bits of a 64-bit draw (the same on every platform,
// unlike std::uniform_real_distribution).
double unit_uniform(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

void check_inputs(PointSpan points, const IndexedMesh& mesh) {
    if (points.empty()) throw InputError("metrics: the point cloud is empty");
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!is_finite(points[i]))
            throw InputError("metrics: cloud point " + std::to_string(i) +
                             " has a NaN or infinite coordinate");
    if (mesh.triangles.empty()) throw InputError("metrics: the mesh has no triangles");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (!is_finite(mesh.positions[i]))
            throw InputError("metrics: mesh vertex " + std::to_string(i) +
                             " has a NaN or infinite coordinate");
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
        for (std::uint32_t v : mesh.triangles[f])
            if (v >= mesh.positions.size())
                throw InputError("metrics: triangle " + std::to_string(f) + " refers to vertex " +
                                 std::to_string(v) + " of " + std::to_string(mesh.positions.size()));
}

// A triangle by the positions of its corners.
using Corners = std::array<Vec3, 3>;

bool position_less(const Vec3& a, const Vec3& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

// The triangles as corner positions in an order that depends only on the surface: each rotated
// to start at its smallest corner (x, then y, then z; the orientation kept), then sorted by
// their corners in that order. Another order of the triangles, another first corner or another
// numbering of the vertices give the same list.
std::vector<Corners> surface_order(const IndexedMesh& mesh) {
    std::vector<Corners> tris;
    tris.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        Corners c{mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
        int first = 0;
        for (int i = 1; i < 3; ++i)
            if (position_less(c[std::size_t(i)], c[std::size_t(first)])) first = i;
        std::rotate(c.begin(), c.begin() + first, c.end());
        tris.push_back(c);
    }
    std::sort(tris.begin(), tris.end(), [](const Corners& a, const Corners& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), position_less);
    });
    return tris;
}

// The largest distance from the surface to the cloud, found to within `tol` of the true value
// by branch and bound over each triangle. For a piece of a triangle with centroid g, corners c_i
// and q the cloud point nearest to g, every point x of the piece is within max_i |c_i - q| of q
// (|x - q| is convex in x, so it peaks at a corner), and within d(g) + max_i |c_i - g| of the
// cloud (the distance to the cloud is 1-Lipschitz); the smaller bound is taken. A piece whose
// bound passes the largest distance found so far by more than tol is cut in four at its edge
// midpoints. A piece of circumradius at most tol never is (its Lipschitz bound is within tol of
// its centroid's distance), so the cuts end. `found`: a distance already measured on the
// surface (the samples' largest). Safety valve: after kMaxPiecesPerTriangle pieces per triangle
// on average (plus a fixed allowance), no piece is cut any more and the largest distance found
// is returned; on a surface at a near-constant distance from a sparse cloud the cuts could
// otherwise run to (area / tol^2) pieces.
double surface_to_cloud_max(const std::vector<Corners>& tris, PointSpan points, const PointGrid& cloud,
                            double found, double tol) {
    constexpr std::size_t kMaxPiecesPerTriangle = 256;
    const std::size_t budget = kMaxPiecesPerTriangle * tris.size() + (std::size_t(1) << 22);
    struct Piece {
        Vector3d a, b, c;
    };
    std::vector<Piece> stack;
    std::size_t pieces = 0;
    double best = found;
    for (const Corners& t : tris) {
        stack.push_back({to_eigen(t[0]), to_eigen(t[1]), to_eigen(t[2])});
        while (!stack.empty()) {
            const Piece s = stack.back();
            stack.pop_back();
            ++pieces;
            const Vector3d g = (s.a + s.b + s.c) / 3.0;
            const NearestPoint n = cloud.find_nearest(Vec3(float(g.x()), float(g.y()), float(g.z())));
            const double d = std::sqrt(double(n.squared_distance));
            best = std::max(best, d);
            const Vector3d q = to_eigen(points[n.index]);
            const double lipschitz = d + std::sqrt(std::max({(s.a - g).squaredNorm(), (s.b - g).squaredNorm(), (s.c - g).squaredNorm()}));
            const double convex = std::sqrt(std::max({(s.a - q).squaredNorm(), (s.b - q).squaredNorm(), (s.c - q).squaredNorm()}));
            if (std::min(lipschitz, convex) <= best + tol || pieces > budget) continue;
            const Vector3d ab = (s.a + s.b) * 0.5, bc = (s.b + s.c) * 0.5, ca = (s.c + s.a) * 0.5;
            stack.push_back({s.a, ab, ca});
            stack.push_back({ab, s.b, bc});
            stack.push_back({ca, bc, s.c});
            stack.push_back({ab, bc, ca});
        }
    }
    return best;
}

std::vector<Vec3> centroids(const IndexedMesh& mesh) {
    std::vector<Vec3> c;
    c.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles)
        c.push_back((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0f);
    return c;
}

}  // namespace

// ---- geometric primitives -----------------------------------------------------------------------

bool triangles_intersect(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                         const Vec3& f) {
    const Vec3 t1[3] = {a, b, c}, t2[3] = {d, e, f};
    // Sides of each triangle's vertices with respect to the other's plane.
    int side2[3], side1[3];
    for (int i = 0; i < 3; ++i) {
        side2[i] = sign(orient3d(a, b, c, t2[i]));
        side1[i] = sign(orient3d(d, e, f, t1[i]));
    }
    const auto one_side = [](const int s[3]) {
        return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
    };
    if (one_side(side2) || one_side(side1)) return false;
    const auto all_zero = [](const int s[3]) { return s[0] == 0 && s[1] == 0 && s[2] == 0; };
    if (all_zero(side2) || all_zero(side1)) return coplanar_triangles_intersect(t1, t2);
    // Not coplanar: the intersection, if any, is a segment whose ends lie on edges of the two
    // triangles, so some edge of one meets the other.
    return edges_cross_triangle(t2, side2, t1) || edges_cross_triangle(t1, side1, t2);
}

double min_angle_deg(const Vec3& a_in, const Vec3& b_in, const Vec3& c_in) {
    const Vector3d p[3] = {to_eigen(a_in), to_eigen(b_in), to_eigen(c_in)};
    double smallest = kInf;
    for (int i = 0; i < 3; ++i) {
        const Vector3d u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
        smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
    }
    return smallest * (180.0 / kPi);
}

// ---- metrics ------------------------------------------------------------------------------------

double dm_cloud_to_centroids(PointSpan points, const IndexedMesh& mesh) {
    check_inputs(points, mesh);
    const PointGrid index(centroids(mesh));
    double sum = 0.0;
    for (const Vec3& p : points) sum += std::sqrt(double(index.nearest_squared_distance(p)));
    return sum / double(points.size());
}

std::vector<float> vertex_distances_to_cloud(PointSpan points, const IndexedMesh& mesh) {
    const PointGrid cloud(points);
    std::vector<float> d;
    d.reserve(mesh.positions.size());
    for (const Vec3& v : mesh.positions) d.push_back(std::sqrt(cloud.nearest_squared_distance(v)));
    return d;
}

QualityReport evaluate(PointSpan points, const IndexedMesh& mesh, const EvalOptions& options) {
    check_inputs(points, mesh);
    if (options.surface_samples == 0) throw ParameterError("metrics: surface_samples must be at least 1");
    QualityReport r;
    r.vertices = mesh.positions.size();
    r.faces = mesh.triangles.size();
    r.bbox_diagonal = bounding_box(points).diagonal();

    // DM(X,T) and point-to-surface. The triangle with the nearest centroid gives each point an
    // upper bound that lets the hierarchy search prune from the start.
    const PointGrid centroid_index(centroids(mesh));
    const TriangleBvh bvh(mesh);
    double dm_sum = 0.0, p2s_sum = 0.0, p2s_sq_sum = 0.0, p2s_max = 0.0;
    constexpr std::size_t kProgressMask = (std::size_t(1) << 18) - 1;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (options.progress && (i & kProgressMask) == 0 && i > 0) options.progress(double(i) / double(points.size()));
        const Vec3& p = points[i];
        const NearestPoint c = centroid_index.find_nearest(p);
        dm_sum += std::sqrt(double(c.squared_distance));
        const auto& t = mesh.triangles[c.index];
        const double bound = point_triangle_squared_distance(p, mesh.positions[t[0]], mesh.positions[t[1]],
                                                             mesh.positions[t[2]]);
        const double d2 = bvh.nearest_squared_distance(p, bound);
        const double d = std::sqrt(d2);
        p2s_sum += d;
        p2s_sq_sum += d2;
        p2s_max = std::max(p2s_max, d);
    }
    if (options.progress) options.progress(1.0);
    const double n = double(points.size());
    r.dm_x_t = dm_sum / n;
    r.p2s_mean = p2s_sum / n;
    r.p2s_rms = std::sqrt(p2s_sq_sum / n);
    r.p2s_max = p2s_max;

    // Surface-to-cloud. Systematic sampling by area: the samples sit at evenly spaced positions,
    // with a random offset, along the triangles' cumulated areas, so each is uniform over the
    // surface and their spread is even; within its triangle each sample is uniform. The
    // triangles are taken in an order that depends on the surface only (surface_order), so that
    // the same triangles listed otherwise give the same samples.
    {
        const std::size_t count = options.surface_samples;
        const std::vector<Corners> tris = surface_order(mesh);
        std::vector<double> cumulative(tris.size());
        double total = 0.0;
        for (std::size_t f = 0; f < tris.size(); ++f) {
            const Vector3d a = to_eigen(tris[f][0]);
            const Vector3d n = (to_eigen(tris[f][1]) - a).cross(to_eigen(tris[f][2]) - a);
            total += 0.5 * n.norm();
            cumulative[f] = total;
        }
        const PointGrid cloud(points);
        std::mt19937_64 rng(options.seed);
        const double offset = unit_uniform(rng);
        double sum = 0.0, worst = 0.0;
        std::size_t f = 0;
        for (std::size_t i = 0; i < count; ++i) {
            if (total > 0.0) {
                const double at = (offset + double(i)) / double(count) * total;
                while (f + 1 < cumulative.size() && cumulative[f] <= at) ++f;
            } else {  // every triangle has zero area: take them in turn
                f = i % tris.size();
            }
            const double root = std::sqrt(unit_uniform(rng)), w = unit_uniform(rng);
            const Corners& t = tris[f];
            const Vector3d q = (1.0 - root) * to_eigen(t[0]) + root * (1.0 - w) * to_eigen(t[1]) +
                               root * w * to_eigen(t[2]);
            const Vec3 sample(float(q.x()), float(q.y()), float(q.z()));
            const double d = std::sqrt(double(cloud.nearest_squared_distance(sample)));
            sum += d;
            worst = std::max(worst, d);
        }
        r.s2p_mean = sum / double(count);
        // The largest distance, exact to within 1e-5 of the larger of the cloud's and the mesh's
        // bounding-box diagonals, the samples' largest as the starting point.
        const double extent = std::max(r.bbox_diagonal, bounding_box(mesh.positions).diagonal());
        r.s2p_max = surface_to_cloud_max(tris, points, cloud, worst, 1e-5 * extent);
    }
    r.hausdorff = std::max(r.p2s_max, r.s2p_max);

    // Relative values.
    const auto rel = [&](double d) {
        return r.bbox_diagonal > 0.0 ? d / r.bbox_diagonal : std::numeric_limits<double>::quiet_NaN();
    };
    r.dm_x_t_rel = rel(r.dm_x_t);
    r.p2s_mean_rel = rel(r.p2s_mean);
    r.p2s_rms_rel = rel(r.p2s_rms);
    r.p2s_max_rel = rel(r.p2s_max);
    r.s2p_mean_rel = rel(r.s2p_mean);
    r.s2p_max_rel = rel(r.s2p_max);
    r.hausdorff_rel = rel(r.hausdorff);

    // Topology.
    analyze_topology(mesh, r);
    std::vector<char> degenerate(mesh.triangles.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        degenerate[f] = is_degenerate(mesh, mesh.triangles[f]);
        r.degenerate_triangles += std::size_t(degenerate[f]);
    }
    bvh.for_each_overlapping_pair([&](std::uint32_t s, std::uint32_t t) {
        const auto &u = mesh.triangles[s], &v = mesh.triangles[t];
        if (degenerate[s] || degenerate[t]) return;
        for (std::uint32_t i : u)
            if (i == v[0] || i == v[1] || i == v[2]) return;  // adjacent
        const auto& x = mesh.positions;
        if (triangles_intersect(x[u[0]], x[u[1]], x[u[2]], x[v[0]], x[v[1]], x[v[2]])) ++r.self_intersections;
    });

    // Triangle quality.
    double angle_sum = 0.0, angle_min = kInf;
    std::size_t small = 0;
    for (const auto& t : mesh.triangles) {
        const double angle = min_angle_deg(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
        angle_sum += angle;
        angle_min = std::min(angle_min, angle);
        small += angle < kSmallAngleDeg;
    }
    r.min_angle_min_deg = angle_min;
    r.min_angle_mean_deg = angle_sum / double(mesh.triangles.size());
    r.share_under_10deg = double(small) / double(mesh.triangles.size());
    return r;
}

// ---- output -------------------------------------------------------------------------------------

namespace {

// Calls f(key, text) for every field, in the documented order, values already formatted as JSON.
template <class F>
void for_each_field(const QualityReport& r, F&& f) {
    const auto number = [](double x) {
        if (!std::isfinite(x)) return std::string("null");
        std::ostringstream s;
        s.imbue(std::locale::classic());
        s.precision(10);
        s << x;
        return s.str();
    };
    const auto integer = [](long long x) { return std::to_string(x); };
    const auto boolean = [](bool b) { return std::string(b ? "true" : "false"); };
    f("vertices", integer((long long)r.vertices));
    f("faces", integer((long long)r.faces));
    f("bbox_diagonal", number(r.bbox_diagonal));
    f("dm_x_t", number(r.dm_x_t));
    f("dm_x_t_rel", number(r.dm_x_t_rel));
    f("p2s_mean", number(r.p2s_mean));
    f("p2s_mean_rel", number(r.p2s_mean_rel));
    f("p2s_rms", number(r.p2s_rms));
    f("p2s_rms_rel", number(r.p2s_rms_rel));
    f("p2s_max", number(r.p2s_max));
    f("p2s_max_rel", number(r.p2s_max_rel));
    f("s2p_mean", number(r.s2p_mean));
    f("s2p_mean_rel", number(r.s2p_mean_rel));
    f("s2p_max", number(r.s2p_max));
    f("s2p_max_rel", number(r.s2p_max_rel));
    f("hausdorff", number(r.hausdorff));
    f("hausdorff_rel", number(r.hausdorff_rel));
    f("closed", boolean(r.closed));
    f("manifold", boolean(r.manifold));
    f("euler", integer(r.euler));
    f("genus", r.genus < 0 ? std::string("null") : integer(r.genus));
    f("components", integer((long long)r.components));
    f("isolated_vertices", integer((long long)r.isolated_vertices));
    f("degenerate_triangles", integer((long long)r.degenerate_triangles));
    f("self_intersections", integer((long long)r.self_intersections));
    f("min_angle_min_deg", number(r.min_angle_min_deg));
    f("min_angle_mean_deg", number(r.min_angle_mean_deg));
    f("share_under_10deg", number(r.share_under_10deg));
}

}  // namespace

void write_json(std::ostream& out, const QualityReport& report) {
    std::string text = "{";
    bool first = true;
    for_each_field(report, [&](const char* key, const std::string& value) {
        text += first ? "\n  \"" : ",\n  \"";
        text += key;
        text += "\": ";
        text += value;
        first = false;
    });
    text += "\n}";
    out << text;
}

void write_text(std::ostream& out, const QualityReport& report) {
    std::string text;
    for_each_field(report, [&](const char* key, const std::string& value) {
        std::string line = key;
        line += ':';
        line.resize(std::max<std::size_t>(line.size() + 1, 22), ' ');
        text += line + (value == "null" ? "-" : value) + "\n";
    });
    out << text;
}

}  // namespace nmesh
