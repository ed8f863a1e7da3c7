// The rim of a point cloud (nmesh/finish/cloud_rim.h): the largest empty angle against a
// brute-force reference; a sheet's edge is its rim and its inside is not; a closed surface has
// none; a missing cap's rim runs round the cut; a change of density is not a rim, and the local
// spacing follows it; a stray point is on the rim.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cloud_fixtures.h"
#include "nmesh/finish/cloud_rim.h"
#include "nmesh/util/random.h"

using namespace nmesh;

namespace {

constexpr float kPi = 3.14159265f;

// The largest gap by brute force: from each direction, the angle to the next one counter-clockwise.
float brute_gap(const std::vector<float>& angles) {
    if (angles.empty()) return 2 * kPi;
    float best = 0.0f;
    for (float a : angles) {
        float next = 2 * kPi;  // to itself, all the way round
        for (float b : angles) {
            float d = b - a;
            while (d <= 0.0f) d += 2 * kPi;
            if (d < 2 * kPi - 1e-6f || angles.size() == 1) next = std::min(next, d);
        }
        best = std::max(best, next);
    }
    return best;
}

// A jittered grid on the square [0, n) x [0, n) of the plane z = 0, spacing 1.
std::vector<Vec3> sheet(int n, std::uint64_t seed, float density_right = 1.0f) {
    Random rng(seed);
    std::vector<Vec3> out;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 p{float(i) + 0.8f * float(rng.uniform()) - 0.4f, float(j) + 0.8f * float(rng.uniform()) - 0.4f,
                         0.0f};
            // On the right half only one point in `density_right` is kept.
            if (p.x > 0.5f * float(n) && rng.uniform() * double(density_right) >= 1.0) continue;
            out.push_back(p);
        }
    return out;
}

}  // namespace

TEST_CASE("largest_gap equals a brute-force reference on random directions") {
    Random rng(3);
    const Vec3 u{1, 0, 0}, v{0, 1, 0};
    for (int trial = 0; trial < 200; ++trial) {
        const int n = int(rng.below(12));
        std::vector<Vec3> around;
        std::vector<float> angles;
        for (int i = 0; i < n; ++i) {
            // Directions in a half-plane sometimes, so that wide gaps occur.
            const float a = float((trial % 2 ? 1.0 : 2.0) * kPi * rng.uniform()) - kPi;
            const float r = 0.1f + float(rng.uniform());
            // Off the plane too: only the projection counts.
            around.push_back({r * std::cos(a), r * std::sin(a), float(rng.uniform()) - 0.5f});
            angles.push_back(std::atan2(std::sin(a), std::cos(a)));
        }
        CHECK(largest_gap({0, 0, 0}, around, u, v) == doctest::Approx(brute_gap(angles)).epsilon(1e-4));
    }
    CHECK(largest_gap({0, 0, 0}, {}, u, v) == doctest::Approx(2 * kPi));
}

TEST_CASE("a sheet's rim is its edge: every point of the outer row, none inside") {
    const int n = 60;
    const std::vector<Vec3> pts = sheet(n, 1);
    const CloudRim r = cloud_rim(pts, 1.0f);
    REQUIRE(r.rim.size() == pts.size());
    std::size_t edge = 0, edge_rim = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const float margin =
            std::min(std::min(pts[i].x, pts[i].y), std::min(float(n - 1) - pts[i].x, float(n - 1) - pts[i].y));
        if (margin > 3.0f) CHECK_MESSAGE(!r.rim[i], "inside point " << i << " on the rim");
        if (margin < 0.0f) {
            ++edge;
            edge_rim += std::size_t(r.rim[i]);
        }
        if (margin > 3.0f) CHECK(r.spacing[i] == doctest::Approx(1.0).epsilon(0.25));
    }
    REQUIRE(edge > 100);
    CHECK(double(edge_rim) >= 0.95 * double(edge));
}

TEST_CASE("a closed surface has no rim; one without its cap has it round the cut") {
    const PointCloud ball = test::sphere_cloud(20000, 1.0f, {}, 4);
    const float spacing = std::sqrt(4 * kPi / 20000.0f);
    const CloudRim closed = cloud_rim(ball.points, spacing);
    // The gap test's chance on a uniform random sample: about 0.2% (cloud_rim.h).
    CHECK(std::count(closed.rim.begin(), closed.rim.end(), 1) <= 100);
    std::vector<Vec3> capless;
    for (const Vec3& p : ball.points)
        if (p.z < 0.6f) capless.push_back(p);
    const CloudRim cut = cloud_rim(capless, spacing);
    std::size_t near_cut = 0, rim_near_cut = 0, below = 0, rim_below = 0;
    for (std::size_t i = 0; i < capless.size(); ++i) {
        if (capless[i].z < 0.6f - 3 * spacing) ++below, rim_below += std::size_t(cut.rim[i]);
        if (capless[i].z > 0.6f - 0.5f * spacing) ++near_cut, rim_near_cut += std::size_t(cut.rim[i]);
    }
    REQUIRE(near_cut > 20);
    CHECK(double(rim_near_cut) >= 0.9 * double(near_cut));
    CHECK(double(rim_below) <= 0.005 * double(below));  // only the gap test's chance away from the cut
}

TEST_CASE("a change of density is not a rim, and the local spacing follows it; a stray point is") {
    const int n = 60;
    std::vector<Vec3> pts = sheet(n, 2, 4.0f);  // the right half four times sparser
    pts.push_back({30.0f, 30.0f, 20.0f});       // a stray point, far off the sheet
    const CloudRim r = cloud_rim(pts, 1.0f);
    std::vector<float> left, right;
    std::size_t inside = 0, inside_rim = 0, border = 0, border_rim = 0;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
        const float margin =
            std::min(std::min(pts[i].x, pts[i].y), std::min(float(n - 1) - pts[i].x, float(n - 1) - pts[i].y));
        if (margin < 6.0f) continue;  // the sheet's own edge (wider on the sparse side)
        ++inside, inside_rim += std::size_t(r.rim[i]);
        if (std::fabs(pts[i].x - 0.5f * float(n)) < 3.0f) ++border, border_rim += std::size_t(r.rim[i]);
        (pts[i].x < 0.5f * float(n) - 3.0f   ? left
         : pts[i].x > 0.5f * float(n) + 6.0f ? right
                                             : left)
            .push_back(r.spacing[i]);
    }
    // No more than the gap test's chance (cloud_rim.h), inside and along the change of density.
    REQUIRE(border > 50);
    CHECK(double(inside_rim) <= 0.01 * double(inside));
    CHECK(double(border_rim) <= 0.03 * double(border));
    std::sort(left.begin(), left.end());
    std::sort(right.begin(), right.end());
    REQUIRE(!left.empty());
    REQUIRE(!right.empty());
    // Four times sparser: twice the spacing.
    CHECK(right[right.size() / 2] / left[left.size() / 2] == doctest::Approx(2.0).epsilon(0.2));
    CHECK(r.rim.back() == 1);
}
