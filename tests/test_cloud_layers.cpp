// The multi-layer share (nmesh/finish/cloud_layers.h): one layer for a range image, two for a
// closed object seen from any direction, at any scale.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "cloud_fixtures.h"
#include "nmesh/finish/cloud_layers.h"
#include "nmesh/util/random.h"

using namespace nmesh;

namespace {

// A height field z = f(x, y) over the unit square, tilted: what a scanner sees of a bumpy wall,
// n points at random, with a part hidden behind a ridge (a fold over the field for x > 0.8).
std::vector<Vec3> range_image(std::size_t n) {
    Random rng(4);
    std::vector<Vec3> out;
    const Vec3 tilt_u = normalized(Vec3{1.0f, 0.0f, 0.3f}), tilt_w = normalized(Vec3{0.0f, 1.0f, 0.2f});
    const Vec3 tilt_v = normalized(cross(tilt_u, tilt_w));
    while (out.size() < n) {
        const float x = float(rng.uniform()), y = float(rng.uniform());
        const float z = 0.1f * std::sin(6.0f * x) * std::cos(5.0f * y);
        out.push_back(tilt_u * x + tilt_w * y + tilt_v * z);
    }
    return out;
}

}  // namespace

TEST_CASE("a range image is one layer, a closed object two, whatever the scale") {
    const std::vector<Vec3> view = range_image(20000);
    const float view_spacing = std::sqrt(1.0f / 20000.0f);
    const float view_share = multi_layer_share(view, view_spacing);
    CHECK(view_share < 0.5f * kViewLayerShare);
    // A sphere and a torus: two layers over most of their outline along any direction.
    const std::vector<Vec3> sphere = test::sphere_cloud(20000).points;
    const float sphere_spacing = std::sqrt(12.566f / 20000.0f);
    const float sphere_share = multi_layer_share(sphere, sphere_spacing);
    CHECK(sphere_share > 2.0f * kViewLayerShare);
    CHECK(multi_layer_share(test::torus_cloud(20000).points, std::sqrt(13.8f / 20000.0f)) > 2.0f * kViewLayerShare);
    // The same clouds scaled by 1,000 (spacing with them) read the same.
    std::vector<Vec3> big = sphere;
    for (Vec3& p : big) p = p * 1000.0f;
    CHECK(std::abs(multi_layer_share(big, 1000.0f * sphere_spacing) - sphere_share) < 0.02f);
    // Degenerate input: no layers to count.
    CHECK(multi_layer_share({}, 1.0f) == 1.0f);
    CHECK(multi_layer_share(view, 0.0f) == 1.0f);
}
