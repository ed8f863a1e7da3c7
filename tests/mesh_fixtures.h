// Tiny named meshes for the tests, each with the reason it exists.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh::test {

// The octahedron: every vertex has valence 4, so every edge can be flipped or collapsed once.
inline Mesh octahedron() {
    IndexedMesh m;
    m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    return Mesh::from_indexed(m);
}

// The icosahedron as a triangle list: 12 vertices on the unit sphere, counter-clockwise seen from
// outside.
inline IndexedMesh icosahedron_triangles() {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    IndexedMesh m;
    m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& p : m.positions) p = normalized(p);
    m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                   {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    return m;
}

// The icosahedron: 12 vertices of valence 5 on the unit sphere; a roomier start than a tetrahedron.
inline Mesh icosahedron() { return Mesh::from_indexed(icosahedron_triangles()); }

// The triangular bipyramid (5 vertices): the equator vertices 0, 1, 2 share three neighbours
// pairwise, so collapsing an equator edge breaks the link condition; the apexes 3 and 4 have
// valence 3, so no edge at an apex can be flipped.
inline Mesh bipyramid() {
    IndexedMesh m;
    m.positions = {{1, 0, 0}, {-0.5f, 0.866f, 0}, {-0.5f, -0.866f, 0}, {0, 0, 1}, {0, 0, -1}};
    m.triangles = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {1, 0, 4}, {2, 1, 4}, {0, 2, 4}};
    return Mesh::from_indexed(m);
}

// The icosphere: the icosahedron above with each triangle split in 4, `levels` times, the new
// vertices pushed onto the unit sphere, then moved by `center`. Closed, genus 0, counter-clockwise
// seen from outside, 10 * 4^levels + 2 vertices; its triangles approach equilateral.
inline IndexedMesh icosphere(int levels, const Vec3& center = {0, 0, 0}) {
    IndexedMesh m = icosahedron_triangles();
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
        const auto mid = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto it = middle.find(key);
            if (it != middle.end()) return it->second;
            const auto v = std::uint32_t(m.positions.size());
            m.positions.push_back(normalized(m.positions[a] + m.positions[b]));
            middle.emplace(key, v);
            return v;
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        for (const auto& f : m.triangles) {
            const std::uint32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        m.triangles = next;
    }
    for (Vec3& p : m.positions) p += center;
    return m;
}

// The faces as vertex-slot triples, each rotated to start at its smallest slot (orientation
// kept), sorted: two meshes with the same combinatorics give the same list.
inline std::vector<std::array<std::uint32_t, 3>> face_set(const Mesh& mesh) {
    std::vector<std::array<std::uint32_t, 3>> faces;
    for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
        if (mesh.is_removed(Face(f))) continue;
        const Halfedge h = mesh.halfedge(Face(f));
        std::array<std::uint32_t, 3> t{mesh.from(h).idx, mesh.to(h).idx, mesh.to(mesh.next(h)).idx};
        std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
        faces.push_back(t);
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

}  // namespace nmesh::test
