// The cloud's parts (nmesh/pipeline/cloud_parts.h): between the single-linkage parts at the link
// and at 2 sqrt(3) times it, by brute force; and reported by the reconstruction.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "cloud_fixtures.h"
#include "nmesh/pipeline/cloud_parts.h"
#include "nmesh/pipeline/parts.h"
#include "nmesh/metrics.h"
#include "nmesh/pipeline/stray_points.h"
#include "nmesh/reconstruct.h"
#include "nmesh/util/random.h"

using namespace nmesh;
using nmesh::test::sphere_cloud;

namespace {

// The parts of the points joined by every pair closer than `link`, by brute force.
std::uint32_t single_linkage_parts(const std::vector<Vec3>& p, float link) {
    std::vector<std::uint32_t> part(p.size());
    std::iota(part.begin(), part.end(), 0u);
    const auto root = [&](std::uint32_t a) {
        while (part[a] != a) a = part[a];
        return a;
    };
    for (std::uint32_t i = 0; i < p.size(); ++i)
        for (std::uint32_t j = i + 1; j < p.size(); ++j)
            if (squared_distance(p[i], p[j]) < link * link) {
                const std::uint32_t a = root(i), b = root(j);
                if (a != b) part[std::max(a, b)] = std::min(a, b);
            }
    std::uint32_t n = 0;
    for (std::uint32_t i = 0; i < p.size(); ++i) n += std::uint32_t(root(i) == i);
    return n;
}

}  // namespace

TEST_CASE("the cloud's parts lie between the single-linkage parts at the link and at 2 sqrt(3) times it") {
    Random rng(9);
    int split = 0;
    for (int trial = 0; trial < 30; ++trial) {
        CAPTURE(trial);
        // Clumps of 20-60 points, 0.05 across, at random places in a box of 1.
        std::vector<Vec3> p;
        const int clumps = 2 + int(rng.below(6));
        for (int c = 0; c < clumps; ++c) {
            const Vec3 at(float(rng.uniform()), float(rng.uniform()), float(rng.uniform()));
            const int n = 20 + int(rng.below(40));
            for (int i = 0; i < n; ++i)
                p.push_back(at + Vec3(float(rng.uniform()), float(rng.uniform()), float(rng.uniform())) * 0.05f);
        }
        const float link = 0.05f + 0.1f * float(rng.uniform());
        const std::uint32_t parts = cloud_parts(p, link, 0.0).count;
        CHECK(parts <= single_linkage_parts(p, link));
        CHECK(parts >= single_linkage_parts(p, 2.0f * std::sqrt(3.0f) * link));
        split += int(parts > 1);
    }
    CHECK(split > 5);  // the clouds were not all one part
}

TEST_CASE("parts under the share are not counted; an empty cloud has none") {
    std::vector<Vec3> p = sphere_cloud(5000, 1.0f, {}, 1).points;
    for (int i = 0; i < 40; ++i) p.push_back(Vec3(5.0f, 0.0f, 0.0f) + Vec3(0.0f, 0.001f * float(i), 0.0f));
    const CloudParts all = cloud_parts(p, 0.2f, 0.0);
    CHECK(all.count == 2);
    CHECK(all.size == std::vector<std::uint64_t>{5000, 40});  // the largest first
    CHECK(std::count(all.part.begin(), all.part.end(), 1u) == 40);
    CHECK(all.part.back() == 1);
    const CloudParts counted = cloud_parts(p, 0.2f, 0.01);  // 40 of 5,040 points: under the share
    CHECK(counted.count == 1);
    CHECK(std::count(counted.part.begin(), counted.part.end(), kNoPart) == 40);
    CHECK(cloud_parts(std::vector<Vec3>(), 0.2f, 0.01).count == 0);
}

TEST_CASE("the vertices are shared by the parts' points, exactly, or not at all") {
    CloudParts parts;
    parts.count = 3;
    parts.size = {5000, 3000, 2000};
    CHECK(pipeline::part_budgets(parts, 1000) == std::vector<std::uint32_t>{500, 300, 200});
    const std::vector<std::uint32_t> odd = pipeline::part_budgets(parts, 1001);
    CHECK(std::accumulate(odd.begin(), odd.end(), 0u) == 1001);
    CHECK(odd == std::vector<std::uint32_t>{501, 300, 200});  // the largest remainder: 0.5 of part 0
    // Part 2's 20% of 300 is under kMinPartVertices: no sharing.
    CHECK(pipeline::part_budgets(parts, 300).empty());
}

TEST_CASE("a cloud in parts far apart gets a closed surface each, with the vertex count asked for") {
    std::vector<Vec3> two = sphere_cloud(6000, 1.0f, {}, 2).points;
    const std::vector<Vec3> other = sphere_cloud(3000, 0.7f, {3.0f, 0.0f, 0.0f}, 3).points;
    two.insert(two.end(), other.begin(), other.end());
    // And a clump of 30 points far from both: under 1% of the points, left out.
    for (int i = 0; i < 30; ++i)
        two.push_back(Vec3(0.0f, 4.0f, 0.0f) + Vec3(0.01f * float(i % 5), 0.01f * float(i / 5), 0.0f));
    for (const Topology topology : {Topology::closed, Topology::sphere}) {
        CAPTURE(topology_name(topology));
        Parameters params;
        params.topology = topology;
        params.target_vertices = 1200;
        std::uint32_t last = 0;
        bool monotone = true;
        Callbacks callbacks;
        callbacks.progress = [&](const Progress& p) {
            monotone = monotone && p.vertices >= last && p.target_vertices == 1200;
            last = p.vertices;
            return true;
        };
        const Result r = reconstruct(two, params, callbacks);
        CHECK(r.stats.cloud_parts == 2);
        CHECK(r.stats.parts_apart);
        CHECK(r.stats.stray_points == 30);
        CHECK(r.mesh.positions.size() == 1200);
        CHECK(monotone);
        CHECK(last == 1200);
        const MeshTopology t = mesh_topology(r.mesh);
        CHECK(t.closed);
        CHECK(t.components == 2);
        CHECK(t.genus == 0);
        CHECK(r.stats.crossing_pairs == 0);
        CHECK(r.stats.inward_faces == 0);
        // 800 vertices on the first sphere, 400 on the second, each near its own.
        std::size_t first = 0;
        float worst = 0.0f;
        for (const Vec3& v : r.mesh.positions) {
            const float a = std::fabs(norm(v) - 1.0f), b = std::fabs(norm(v - Vec3(3.0f, 0.0f, 0.0f)) - 0.7f);
            first += std::size_t(a < b);
            worst = std::max(worst, std::min(a, b));
        }
        CHECK(first == 800);
        CHECK(worst < 0.03f);
    }
    // Too few vertices to go round (64 each at least): one surface, joining them; the caller is
    // told by the count.
    Parameters params;
    params.target_vertices = 150;
    const Result joined = reconstruct(two, params);
    CHECK(joined.stats.cloud_parts == 2);
    CHECK_FALSE(joined.stats.parts_apart);
    CHECK(mesh_topology(joined.mesh).components == 1);
}

TEST_CASE("the reconstruction counts the parts of a closed result's cloud") {
    std::vector<Vec3> two = sphere_cloud(6000, 1.0f, {}, 2).points;
    const std::vector<Vec3> other = sphere_cloud(6000, 1.0f, {3.0f, 0.0f, 0.0f}, 3).points;
    two.insert(two.end(), other.begin(), other.end());
    Parameters params;
    params.target_vertices = 800;
    CHECK(reconstruct(two, params).stats.cloud_parts == 2);
    // Touching spheres (a gap of a tenth of their spacing) are one part.
    std::vector<Vec3> touching = sphere_cloud(6000, 1.0f, {}, 2).points;
    const std::vector<Vec3> near = sphere_cloud(6000, 1.0f, {2.005f, 0.0f, 0.0f}, 3).points;
    touching.insert(touching.end(), near.begin(), near.end());
    params.topology = Topology::closed;
    CHECK(reconstruct(touching, params).stats.cloud_parts == 1);
    // An open result may hold pieces: not counted.
    params.topology = Topology::open;
    CHECK(reconstruct(two, params).stats.cloud_parts == 1);
}
