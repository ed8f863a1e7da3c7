#include "nmesh/geometry/delaunay_2d.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace nmesh {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

struct Tri {
    std::array<std::uint32_t, 3> v;  // counter-clockwise
    std::array<std::uint32_t, 3> n;  // n[i]: the triangle across the edge opposite v[i]
};

// The index along a Hilbert curve of the cell (x, y) of a 2^16 x 2^16 grid.
std::uint64_t hilbert(std::uint32_t x, std::uint32_t y) {
    std::uint64_t d = 0;
    for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
        const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
        d += std::uint64_t(s) * s * ((3 * rx) ^ ry);
        if (ry == 0) {
            if (rx == 1) {
                x = s - 1 - (x & (s - 1));
                y = s - 1 - (y & (s - 1));
            }
            std::swap(x, y);
        }
        x &= s - 1;
        y &= s - 1;
    }
    return d;
}

class Triangulation {
public:
    explicit Triangulation(std::vector<Point2d> p) : p_(std::move(p)) {}

    std::uint32_t add_triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        t_.push_back({{a, b, c}, {kNone, kNone, kNone}});
        return std::uint32_t(t_.size() - 1);
    }

    // Inserts point q; returns false when it equals a vertex (left out).
    bool insert(std::uint32_t q) {
        std::uint32_t t = last_;
        int edge = -1;
        // The walk: across an edge that has q strictly on its far side, the first edge tried
        // chosen at random each step (a stochastic walk, which cannot cycle).
        for (;;) {
            const Tri& tri = t_[t];
            rng_ = rng_ * 6364136223846793005ull + 1442695040888963407ull;
            const int start = int((rng_ >> 33) % 3);
            bool moved = false;
            int zeros = 0;
            edge = -1;
            for (int k = 0; k < 3; ++k) {
                const int i = (start + k) % 3;
                const int o = orient2d(p_[tri.v[std::size_t((i + 1) % 3)]], p_[tri.v[std::size_t((i + 2) % 3)]], p_[q]);
                if (o < 0) {
                    t = tri.n[std::size_t(i)];
                    moved = true;
                    break;
                }
                if (o == 0) ++zeros, edge = i;
            }
            if (moved) continue;
            if (zeros >= 2) return false;  // q is a vertex
            break;
        }
        stack_.clear();
        if (edge < 0) split_triangle(t, q);
        else split_edge(t, std::uint32_t(edge), q);
        // Lawson's flips round q.
        int flips = 0;
        while (!stack_.empty()) {
            const auto [s, i] = stack_.back();
            stack_.pop_back();
            if (flips < kMaxFlipsPerPoint && legalize(s, i)) ++flips;
        }
        return true;
    }

    const std::vector<Tri>& triangles() const { return t_; }

private:
    void relink(std::uint32_t tri, std::uint32_t from, std::uint32_t to) {
        if (tri == kNone) return;
        for (std::uint32_t& x : t_[tri].n)
            if (x == from) x = to;
    }

    // Triangle t = (a, b, c) into (a, b, q), (b, c, q), (c, a, q).
    void split_triangle(std::uint32_t t, std::uint32_t q) {
        const Tri old = t_[t];
        const std::uint32_t a = old.v[0], b = old.v[1], c = old.v[2];
        const std::uint32_t t1 = add_triangle(b, c, q), t2 = add_triangle(c, a, q);
        t_[t] = {{a, b, q}, {t1, t2, old.n[2]}};
        t_[t1].n = {t2, t, old.n[0]};
        t_[t2].n = {t, t1, old.n[1]};
        relink(old.n[0], t, t1);
        relink(old.n[1], t, t2);
        stack_.push_back({t, 2});
        stack_.push_back({t1, 2});
        stack_.push_back({t2, 2});
        last_ = t;
    }

    // q on the edge of t opposite t.v[i]: t = (a, x, y) and its neighbour u = (d, y, x) into
    // (a, x, q), (a, q, y), (d, y, q), (d, q, x).
    void split_edge(std::uint32_t t, std::uint32_t i, std::uint32_t q) {
        const Tri old_t = t_[t];
        const std::uint32_t a = old_t.v[i], x = old_t.v[(i + 1) % 3], y = old_t.v[(i + 2) % 3];
        const std::uint32_t u = old_t.n[i];
        const std::uint32_t A = old_t.n[(i + 1) % 3], B = old_t.n[(i + 2) % 3];
        const Tri old_u = t_[u];
        std::uint32_t j = 0;
        while (old_u.n[j] != t) ++j;
        const std::uint32_t d = old_u.v[j];
        const std::uint32_t C = old_u.n[(j + 1) % 3], D = old_u.n[(j + 2) % 3];
        const std::uint32_t t2 = add_triangle(a, q, y), u2 = add_triangle(d, q, x);
        t_[t] = {{a, x, q}, {u2, t2, B}};
        t_[t2].n = {u, A, t};
        t_[u] = {{d, y, q}, {t2, u2, D}};
        t_[u2].n = {t, C, u};
        relink(A, t, t2);
        relink(C, u, u2);
        stack_.push_back({t, 2});
        stack_.push_back({t2, 1});
        stack_.push_back({u, 2});
        stack_.push_back({u2, 1});
        last_ = t;
    }

    // The edge of s opposite s.v[i] (the new point): flipped when the point across it lies inside
    // s's circumcircle and the two triangles make a convex quadrilateral.
    bool legalize(std::uint32_t s, std::uint32_t i) {
        const std::uint32_t u = t_[s].n[i];
        if (u == kNone) return false;
        const std::uint32_t p = t_[s].v[i], x = t_[s].v[(i + 1) % 3], y = t_[s].v[(i + 2) % 3];
        std::uint32_t j = 0;
        while (t_[u].n[j] != s) ++j;
        const std::uint32_t q = t_[u].v[j];
        if (incircle_approx(p_[p], p_[x], p_[y], p_[q]) <= 0.0) return false;
        if (orient2d(p_[p], p_[x], p_[q]) <= 0 || orient2d(p_[p], p_[q], p_[y]) <= 0) return false;
        const std::uint32_t A = t_[s].n[(i + 1) % 3], B = t_[s].n[(i + 2) % 3];
        const std::uint32_t C = t_[u].n[(j + 1) % 3], D = t_[u].n[(j + 2) % 3];
        // s = (p, x, y), u = (q, y, x) -> s = (p, x, q), u = (p, q, y).
        t_[s] = {{p, x, q}, {C, u, B}};
        t_[u] = {{p, q, y}, {D, A, s}};
        relink(A, s, u);
        relink(C, u, s);
        stack_.push_back({s, 0});
        stack_.push_back({u, 0});
        last_ = s;
        return true;
    }

    std::vector<Point2d> p_;
    std::vector<Tri> t_;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack_;
    std::uint32_t last_ = 0;
    std::uint64_t rng_ = 1;  // the walk's choice of first edge (a fixed sequence: the same result each run)
};

}  // namespace

double incircle_approx(const Point2d& a, const Point2d& b, const Point2d& c, const Point2d& d) {
    const double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y, cdx = c.x - d.x,
                 cdy = c.y - d.y;
    return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) + (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

std::vector<std::array<std::uint32_t, 3>> delaunay_2d(const std::vector<Point2d>& points) {
    const std::uint32_t n = std::uint32_t(points.size());
    double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
    std::vector<std::uint32_t> order;
    for (std::uint32_t i = 0; i < n; ++i) {
        if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y)) continue;
        order.push_back(i);
        lo_x = std::min(lo_x, points[i].x), hi_x = std::max(hi_x, points[i].x);
        lo_y = std::min(lo_y, points[i].y), hi_y = std::max(hi_y, points[i].y);
    }
    if (order.size() < 3) return {};
    const double size = std::max({hi_x - lo_x, hi_y - lo_y, 1e-30});
    // Hilbert order, so that each walk starts near its point.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
    keyed.reserve(order.size());
    for (std::uint32_t i : order) {
        const auto cell = [&](double v, double lo) { return std::uint32_t(std::min(65535.0, (v - lo) / size * 65535.0)); };
        keyed.push_back({hilbert(cell(points[i].x, lo_x), cell(points[i].y, lo_y)), i});
    }
    std::sort(keyed.begin(), keyed.end());
    // The enclosing triangle: far enough that its in-circle tests barely differ from those of
    // points at infinity.
    std::vector<Point2d> all = points;
    const double cx = 0.5 * (lo_x + hi_x), cy = 0.5 * (lo_y + hi_y), r = 1e3 * size;
    all.push_back({cx - 2 * r, cy - r});
    all.push_back({cx + 2 * r, cy - r});
    all.push_back({cx, cy + 2 * r});
    Triangulation tri(std::move(all));
    tri.add_triangle(n, n + 1, n + 2);
    for (const auto& k : keyed) tri.insert(k.second);
    std::vector<std::array<std::uint32_t, 3>> out;
    for (const Tri& t : tri.triangles())
        if (t.v[0] < n && t.v[1] < n && t.v[2] < n) out.push_back(t.v);
    return out;
}

}  // namespace nmesh
