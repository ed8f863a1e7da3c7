// A triangle list in pieces (nmesh/mesh/mesh_pieces.h): split and joined again gives the same
// triangles; pieces are edge-connected, a bow-tie vertex is copied into each of its pieces.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "mesh_fixtures.h"
#include "nmesh/mesh/mesh_pieces.h"
#include "nmesh/metrics.h"

using namespace nmesh;

namespace {

// The triangles as position triples (comparable across re-indexing), sorted.
std::vector<std::array<float, 9>> triangle_set(const IndexedMesh& m) {
    std::vector<std::array<float, 9>> out;
    for (const auto& t : m.triangles) {
        std::array<float, 9> k{};
        for (std::size_t i = 0; i < 3; ++i) {
            const Vec3 p = m.positions[t[i]];
            k[3 * i] = p.x, k[3 * i + 1] = p.y, k[3 * i + 2] = p.z;
        }
        out.push_back(k);
    }
    std::sort(out.begin(), out.end());
    return out;
}

IndexedMesh shifted(IndexedMesh m, float dx) {
    for (Vec3& p : m.positions) p.x += dx;
    return m;
}

}  // namespace

TEST_CASE("split_pieces and join_pieces: two spheres and a bow-tie") {
    const IndexedMesh a = test::icosphere(1), b = shifted(test::icosphere(2), 5.0f);
    IndexedMesh both = join_pieces({a, b});
    CHECK(both.triangles.size() == a.triangles.size() + b.triangles.size());
    std::vector<MeshPiece> pieces = split_pieces(both);
    REQUIRE(pieces.size() == 2);
    CHECK(triangle_set(pieces[0].mesh) == triangle_set(a));
    CHECK(triangle_set(pieces[1].mesh) == triangle_set(b));
    CHECK(pieces[0].mesh.positions.size() == a.positions.size());  // only the vertices it uses
    // The triangle map points back at the same triangles.
    for (const MeshPiece& p : pieces)
        for (std::size_t t = 0; t < p.mesh.triangles.size(); ++t)
            for (std::size_t i = 0; i < 3; ++i)
                CHECK(p.mesh.positions[p.mesh.triangles[t][i]] == both.positions[both.triangles[p.triangle[t]][i]]);
    std::vector<IndexedMesh> meshes;
    for (const MeshPiece& p : pieces) meshes.push_back(p.mesh);
    CHECK(triangle_set(join_pieces(meshes)) == triangle_set(both));
    // Two triangles sharing only a vertex: two pieces, the vertex in each.
    IndexedMesh bow;
    bow.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    bow.triangles = {{0, 1, 2}, {0, 3, 4}};
    pieces = split_pieces(bow);
    REQUIRE(pieces.size() == 2);
    CHECK(pieces[0].mesh.positions.size() == 3);
    CHECK(pieces[1].mesh.positions.size() == 3);
    CHECK(split_pieces(IndexedMesh{}).empty());
}
