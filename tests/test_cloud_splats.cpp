// The shell of flattened balls round a cloud's points (nmesh/learn/cloud_splats.h): the distances
// against a brute-force minimum, the stretch read from the data, and the gap between two parts it
// keeps open where balls close it.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "cloud_fixtures.h"
#include "nmesh/bounding_box.h"
#include "nmesh/learn/cloud_splats.h"
#include "nmesh/learn/solid_start.h"

using namespace nmesh;

TEST_CASE("splat distances equal the brute-force minimum over the splats, for any thread count") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 20; ++trial) {
        CAPTURE(trial);
        const std::array<std::uint32_t, 3> dims{std::uint32_t(4 + rng() % 12), std::uint32_t(4 + rng() % 12), std::uint32_t(4 + rng() % 12)};
        const Vec3 origin{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f};
        const float h = 0.1f + u(rng);
        const float reach = 1.0f + 5.0f * u(rng);
        std::vector<Splat> splats(1 + rng() % 30);
        for (Splat& s : splats) {
            s.centre = origin + Vec3{u(rng) * float(dims[0]), u(rng) * float(dims[1]), u(rng) * float(dims[2])} * h;
            const Vec3 n{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f};
            s.normal = rng() % 4 == 0 ? Vec3{} : n * (1.0f / std::sqrt(dot(n, n)));
            s.stretch = 1.0f + 2.0f * u(rng);
        }
        const std::vector<std::uint8_t> one = splat_distances(splats, origin, h, dims, reach, 1);
        CHECK(splat_distances(splats, origin, h, dims, reach, 3) == one);
        // With a larger reach, the same reading at every offset within this one's.
        const std::vector<std::uint8_t> wider = splat_distances(splats, origin, h, dims, reach + 2.0f, 1);
        const float r2 = reach * reach;
        for (std::size_t i = 0; i < one.size(); ++i) {
            if (float(wider[i]) <= r2) CHECK(one[i] == wider[i]);
            else CHECK(float(one[i]) > r2);
        }
        for (std::uint32_t z = 0; z < dims[2]; ++z)
            for (std::uint32_t y = 0; y < dims[1]; ++y)
                for (std::uint32_t x = 0; x < dims[0]; ++x) {
                    // The brute force: the least rounded value over every splat, and whether one
                    // of them lies within float rounding of the reach's edge.
                    float best = 255.0f;
                    bool edge = false;
                    for (const Splat& s : splats) {
                        const Vec3 d = (origin + Vec3{float(x), float(y), float(z)} * h - s.centre) * (1.0f / h);
                        const float across = dot(d, s.normal);
                        const float m = dot(d, d) + (s.stretch * s.stretch - 1.0f) * across * across;
                        best = std::min(best, std::min(std::nearbyint(m), 254.0f));
                        edge = edge || std::abs(m - (r2 + 0.5f)) < 1e-3f * r2 || std::abs(m - std::nearbyint(m)) > 0.499f;
                    }
                    const std::uint8_t got = one[(std::size_t(z) * dims[1] + y) * dims[0] + x];
                    if (edge) continue;
                    // Every cell whose value is within the reach has it; the others hold their
                    // value or 255.
                    if (best <= r2) CHECK(float(got) == best);
                    else CHECK((float(got) == best || got == 255));
                }
    }
}

TEST_CASE("the stretch is the largest on a flat patch and follows the bend of a tube") {
    // A plane sampled on a jittered grid: no spread off the plane.
    std::vector<Vec3> plane;
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> j(-0.3f, 0.3f);
    for (int y = 0; y < 60; ++y)
        for (int x = 0; x < 60; ++x) plane.push_back({float(x) + j(rng), float(y) + j(rng), 0.0f});
    const std::vector<Splat> flat = cloud_splats(plane, 1.0f);
    int largest = 0;
    for (const Splat& s : flat) {
        largest += s.stretch == kMaxStretch;
        CHECK(std::abs(std::abs(s.normal.z) - 1.0f) < 1e-3f);
    }
    CHECK(largest == int(flat.size()));
    // Tubes of radius a round the x axis (spacing d = 0.5): the stretch follows a / (2 d) between
    // 1 and the largest, within 20% (the reading assumes a sphere's bend; a tube bends one way).
    for (const float a : {1.0f, 1.5f, 2.0f, 3.0f, 5.0f}) {
        CAPTURE(a);
        std::vector<Vec3> tube;
        const int ring = int(a * 6.2831853f / 0.5f);
        for (int i = 0; i < 200; ++i)
            for (int k = 0; k < ring; ++k) {
                const float angle = (float(k) + 0.5f * float(i % 2)) * 6.2831853f / float(ring);
                tube.push_back({float(i) * 0.5f, a * std::cos(angle), a * std::sin(angle)});
            }
        std::vector<float> stretch;
        for (const Splat& s : cloud_splats(tube, 0.5f)) stretch.push_back(s.stretch);
        std::sort(stretch.begin(), stretch.end());
        const float expected = std::clamp(a / (2.0f * 0.5f), 1.0f, kMaxStretch);
        CHECK(stretch.back() <= 1.2f * expected);
        CHECK(stretch[stretch.size() / 2] >= 0.8f * expected);
    }
}

TEST_CASE("two parts closer than two offsets, farther than two half-thicknesses, stay two") {
    // Two spheres 8 d apart. One sphere's sample walls round at 3.5 d; the reading goes on to
    // larger offsets while the two parts are two components, up to twice that. Balls join the
    // parts at 4.5 d (9 d across two of them) and the genus 0 of the one solid is read there;
    // discs of the largest stretch are at most 3.5 d thick either side up to 7 d, and the
    // parts stay two.
    const PointCloud a = test::sphere_cloud(20000, 0.3f, {}, 7);
    const BoundingBox box = bounding_box(PointSpan(a.points));
    const SolidSurface one =
        solid_surface(PointSpan(a.points), PointTransform{box.center(), float(1.0 / box.diagonal())});
    REQUIRE(one.walled);
    REQUIRE(one.offset <= 3.5f);
    // d in the cloud's own units (the transform scales by 1 / diagonal).
    const float d = one.spacing * box.diagonal();
    const float gap = 8.0f * d;
    PointCloud two = a;
    const PointCloud b = test::sphere_cloud(20000, 0.3f, {0.6f + gap, 0.0f, 0.0f}, 11);
    two.points.insert(two.points.end(), b.points.begin(), b.points.end());
    const BoundingBox both = bounding_box(PointSpan(two.points));
    const SolidSurface s =
        solid_surface(PointSpan(two.points), PointTransform{both.center(), float(1.0 / both.diagonal())});
    CHECK(s.walled);
    CHECK(s.components == 2);
}
