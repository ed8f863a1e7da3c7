// The orientation of a one-sided cloud's normals (nmesh/finish/cloud_normals.h): on a curved
// sheet every normal ends on one side; parts that do not touch are each oriented and turned to
// the largest's side; the check used here fails on the normals as they come (random signs).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "nmesh/finish/cloud_normals.h"
#include "nmesh/finish/cloud_rim.h"
#include "nmesh/util/random.h"

using namespace nmesh;

namespace {

// Points on a quarter of the unit cylinder's side (x = cos u, y = sin u), spacing about 0.02,
// shifted by `offset` along x.
std::vector<Vec3> quarter_cylinder(int n, std::uint64_t seed, float offset = 0.0f) {
    Random rng(seed);
    std::vector<Vec3> out;
    for (int i = 0; i < n; ++i) {
        const double u = 1.5 * rng.uniform(), v = 2.0 * rng.uniform();
        out.push_back({float(std::cos(u)) + offset, float(std::sin(u)), float(v)});
    }
    return out;
}

// The share of the normals pointing away from the cylinder axis through (offset, 0).
double outward_share(const std::vector<Vec3>& points, const std::vector<Vec3>& normals, std::size_t from,
                     std::size_t to, float offset) {
    std::size_t out = 0;
    for (std::size_t i = from; i < to; ++i)
        out += std::size_t(dot(normals[i], Vec3{points[i].x - offset, points[i].y, 0.0f}) > 0.0f);
    return double(out) / double(to - from);
}

}  // namespace

TEST_CASE("orient_normals: a curved sheet's normals all on one side") {
    const std::vector<Vec3> points = quarter_cylinder(10000, 4);
    const float spacing = 0.02f;
    std::vector<Vec3> normals = cloud_rim(points, spacing).normal;
    // The normals as the rim gives them: of either sign, so the check below fails on them.
    const double before = outward_share(points, normals, 0, points.size(), 0.0f);
    CHECK(before > 0.05);
    CHECK(before < 0.95);
    const Orientation o = orient_normals(points, normals, spacing);
    const double after = outward_share(points, normals, 0, points.size(), 0.0f);
    CHECK((after > 0.999 || after < 0.001));
    // The view direction: the mean normal, along the quarter's middle (45 degrees), either way.
    CHECK(std::fabs(dot(o.direction, normalized(Vec3{1, 1, 0}))) > 0.95f);
    for (std::uint32_t p : o.part) CHECK(p == 0);
}

TEST_CASE("orient_normals: two parts apart, each on the largest's side") {
    std::vector<Vec3> points = quarter_cylinder(8000, 5);
    const std::vector<Vec3> second = quarter_cylinder(3000, 6, 3.0f);  // 3 apart: no neighbours across
    points.insert(points.end(), second.begin(), second.end());
    const float spacing = 0.02f;
    std::vector<Vec3> normals = cloud_rim(points, spacing).normal;
    const Orientation o = orient_normals(points, normals, spacing);
    const double first = outward_share(points, normals, 0, 8000, 0.0f);
    const double other = outward_share(points, normals, 8000, points.size(), 3.0f);
    CHECK((first > 0.999 || first < 0.001));
    // The same side as the first: outward there, outward here (the two quarters face the same way).
    CHECK(std::fabs(other - first) < 0.002);
    CHECK(o.part[0] != o.part[8000]);
    CHECK(o.part[0] == o.part[7999]);
}
