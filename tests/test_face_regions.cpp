// The edge-connected regions of a face set (nmesh/mesh/face_regions.h): equal to a brute-force
// union-find over shared edges on random sets, each face once, regions in the order of their lowest
// face, a removed face never asked about, and regions split at a boundary.
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "mesh_fixtures.h"
#include "topology_fixtures.h"
#include "nmesh/mesh/face_regions.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/util/random.h"

using namespace nmesh;

namespace {

// The regions of the member faces of `m` by union-find over the edges two member faces share,
// each as its sorted face list, in the order of their lowest face.
std::vector<std::vector<std::uint32_t>> brute_regions(const IndexedMesh& m, const std::vector<char>& member) {
    std::vector<std::uint32_t> parent(m.triangles.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto root = [&](std::uint32_t f) {
        while (parent[f] != f) f = parent[f] = parent[parent[f]];
        return f;
    };
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> first;
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f) {
        if (!member[f]) continue;
        for (int i = 0; i < 3; ++i) {
            const auto e = std::minmax(m.triangles[f][i], m.triangles[f][(i + 1) % 3]);
            const auto it = first.find(e);
            if (it == first.end())
                first.emplace(e, f);
            else
                parent[root(f)] = root(it->second);
        }
    }
    std::map<std::uint32_t, std::vector<std::uint32_t>> by_root;
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
        if (member[f]) by_root[root(f)].push_back(f);
    std::vector<std::vector<std::uint32_t>> out;
    for (auto& [r, faces] : by_root) out.push_back(faces);
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::vector<std::uint32_t>> regions_of(const Mesh& mesh, const std::vector<char>& member) {
    std::vector<std::vector<std::uint32_t>> out;
    for_each_face_region(mesh, [&](std::uint32_t f) { return member[f] != 0; },
                         [&](const std::vector<std::uint32_t>& region) { out.push_back(region); });
    return out;
}

}  // namespace

TEST_CASE("face regions equal a brute-force union-find over shared edges, on random face sets") {
    const IndexedMesh sphere = test::icosphere(3);
    Mesh mesh = Mesh::from_indexed(sphere);
    mesh.build_faces();
    Random rng(9);
    for (int trial = 0; trial < 50; ++trial) {
        CAPTURE(trial);
        const double share = 0.2 + 0.6 * rng.uniform();
        std::vector<char> member(sphere.triangles.size(), 0);
        for (char& m : member) m = rng.uniform() < share ? 1 : 0;
        auto got = regions_of(mesh, member);
        // In the order of their lowest face, each face once.
        for (std::size_t i = 1; i < got.size(); ++i)
            CHECK(*std::min_element(got[i - 1].begin(), got[i - 1].end()) <
                  *std::min_element(got[i].begin(), got[i].end()));
        for (auto& r : got) {
            CHECK(r.front() == *std::min_element(r.begin(), r.end()));  // the walk starts at the lowest
            std::sort(r.begin(), r.end());
            CHECK(std::adjacent_find(r.begin(), r.end()) == r.end());
        }
        std::sort(got.begin(), got.end());
        CHECK(got == brute_regions(sphere, member));
    }
}

TEST_CASE("face regions: removed faces are never asked about, and a boundary splits nothing it should not") {
    // An open tube: two boundary loops; every face a member gives one region of all faces.
    const IndexedMesh tube = test::torus_grid(12, 6, false);
    Mesh mesh = Mesh::from_indexed(tube, true);
    mesh.build_faces();
    std::vector<char> all(tube.triangles.size(), 1);
    CHECK(regions_of(mesh, all).size() == 1);
    CHECK(regions_of(mesh, all)[0].size() == tube.triangles.size());
    // A face removed: the member test is not called for it.
    REQUIRE(mesh.can_remove_face(Face(0)));
    mesh.remove_face(Face(0));
    bool asked = false;
    for_each_face_region(
        mesh, [&](std::uint32_t f) { asked = asked || f == 0; return true; }, [](const std::vector<std::uint32_t>&) {});
    CHECK(!asked);
}
