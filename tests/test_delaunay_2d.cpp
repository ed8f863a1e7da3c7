// The planar Delaunay triangulation (nmesh/geometry/delaunay_2d.h): against a brute-force
// reference on random points, and a valid triangulation (counter-clockwise, covering the hull,
// each point used once) on degenerate input: a grid (collinear and cocircular points) and
// duplicates.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "nmesh/geometry/delaunay_2d.h"
#include "nmesh/util/random.h"

using namespace nmesh;

namespace {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

// Rotated to start at the smallest index, sorted.
Triangles canonical(Triangles t) {
    for (auto& x : t)
        while (x[0] > x[1] || x[0] > x[2]) x = {x[1], x[2], x[0]};
    std::sort(t.begin(), t.end());
    return t;
}

// Every counter-clockwise triple with no other point inside or on its circumcircle.
Triangles brute_force(const std::vector<Point2d>& p) {
    Triangles out;
    const std::uint32_t n = std::uint32_t(p.size());
    for (std::uint32_t a = 0; a < n; ++a)
        for (std::uint32_t b = 0; b < n; ++b)
            for (std::uint32_t c = 0; c < n; ++c) {
                if (a >= b || a >= c || b == c || orient2d(p[a], p[b], p[c]) <= 0) continue;  // each once
                bool empty = true;
                for (std::uint32_t d = 0; d < n && empty; ++d)
                    if (d != a && d != b && d != c && incircle_approx(p[a], p[b], p[c], p[d]) >= 0.0) empty = false;
                if (empty) out.push_back({a, b, c});
            }
    return canonical(out);
}

double area(const std::vector<Point2d>& p, const std::array<std::uint32_t, 3>& t) {
    const Point2d a = p[t[0]], b = p[t[1]], c = p[t[2]];
    return 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

// Each directed edge once, and each interior edge with its reverse.
bool edges_consistent(const Triangles& t) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (const auto& x : t)
        for (int i = 0; i < 3; ++i)
            if (++directed[{x[std::size_t(i)], x[std::size_t((i + 1) % 3)]}] > 1) return false;
    return true;
}

}  // namespace

TEST_CASE("delaunay_2d equals the brute-force Delaunay triangulation of random points") {
    Random rng(3);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<Point2d> p;
        const int n = 5 + int(rng.below(40));
        for (int i = 0; i < n; ++i) p.push_back({rng.uniform(), rng.uniform()});
        const Triangles got = canonical(delaunay_2d(p));
        CAPTURE(trial);
        const Triangles ref = brute_force(p);
        CAPTURE(got.size());
        CAPTURE(ref.size());
        CHECK(got == ref);
        for (const auto& t : got) CHECK(orient2d(p[t[0]], p[t[1]], p[t[2]]) > 0);
    }
}

TEST_CASE("delaunay_2d on a grid with duplicates: a valid triangulation of the whole square") {
    std::vector<Point2d> p;
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) p.push_back({double(i), double(j)});
    p.push_back({3.0, 4.0});  // a duplicate
    p.push_back({std::nan(""), 0.0});
    const Triangles t = delaunay_2d(p);
    double total = 0.0;
    std::vector<int> used(p.size(), 0);
    for (const auto& x : t) {
        CHECK(orient2d(p[x[0]], p[x[1]], p[x[2]]) > 0);
        total += area(p, x);
        for (std::uint32_t v : x) used[v] = 1;
    }
    CHECK(total == doctest::Approx(81.0));
    CHECK(t.size() == 2 * 81);
    CHECK(edges_consistent(t));
    for (std::size_t i = 0; i < 100; ++i) CHECK(used[i] == 1);
    CHECK(used[100] == 0);  // the duplicate
    CHECK(used[101] == 0);  // the non-finite point
}

TEST_CASE("delaunay_2d on many points: counter-clockwise, consistent, covering the hull") {
    Random rng(8);
    std::vector<Point2d> p;
    for (int i = 0; i < 20000; ++i) {
        const double r = std::sqrt(rng.uniform()), a = 6.283185307179586 * rng.uniform();
        p.push_back({r * std::cos(a), r * std::sin(a)});
    }
    const Triangles t = delaunay_2d(p);
    double total = 0.0;
    for (const auto& x : t) {
        CHECK(orient2d(p[x[0]], p[x[1]], p[x[2]]) > 0);
        total += area(p, x);
    }
    CHECK(edges_consistent(t));
    CHECK(total > 0.99 * 3.14159265);  // the hull of 20,000 points in the unit disc
    CHECK(total < 3.14159265);
}
