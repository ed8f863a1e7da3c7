// Indexed meshes of known topology for the boundary, handle and bridge tests: tori, tubes, disks
// and closed surfaces of revolution.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "nmesh/indexed_mesh.h"

namespace nmesh::test {

// A grid of nu x nv quads on the torus of radii (2, 0.7) or, with `closed_v` false, on an open
// tube (a cylinder without caps: two boundary loops), each quad split into two triangles that
// face outward.
inline IndexedMesh torus_grid(std::uint32_t nu, std::uint32_t nv, bool closed_v = true) {
    IndexedMesh m;
    const float two_pi = 6.2831853f;
    const std::uint32_t rows = closed_v ? nv : nv + 1;
    for (std::uint32_t j = 0; j < rows; ++j)
        for (std::uint32_t i = 0; i < nu; ++i) {
            const float u = two_pi * float(i) / float(nu);
            if (closed_v) {
                const float v = two_pi * float(j) / float(nv);
                const float r = 2.0f + 0.7f * std::cos(v);
                m.positions.push_back({r * std::cos(u), r * std::sin(u), 0.7f * std::sin(v)});
            } else {
                m.positions.push_back({std::cos(u), std::sin(u), float(j) / float(nv)});
            }
        }
    auto id = [&](std::uint32_t i, std::uint32_t j) { return (j % rows) * nu + i % nu; };
    for (std::uint32_t j = 0; j < nv; ++j)
        for (std::uint32_t i = 0; i < nu; ++i) {
            const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            m.triangles.push_back({a, b, c});
            m.triangles.push_back({a, c, d});
        }
    return m;
}

// A flat disk: a centre and `n` rim vertices (n triangles, one boundary loop of n edges).
inline IndexedMesh fan_disk(std::uint32_t n) {
    IndexedMesh m;
    m.positions.push_back({0, 0, 0});
    for (std::uint32_t i = 0; i < n; ++i) {
        const float a = 6.2831853f * float(i) / float(n);
        m.positions.push_back({std::cos(a), std::sin(a), 0});
    }
    for (std::uint32_t i = 0; i < n; ++i) m.triangles.push_back({0, 1 + i, 1 + (i + 1) % n});
    return m;
}

// A ring of a surface of revolution about the z axis: its height, radius and vertex count.
struct Ring {
    float z, r;
    std::uint32_t n;
};

// The closed surface of revolution through `rings` (bottom to top), with a pole below the first
// at `z_bottom` and one above the last at `z_top`; rings of different counts are zipped by angle.
// Faces point outward.
inline IndexedMesh revolution(const std::vector<Ring>& rings, float z_bottom, float z_top) {
    IndexedMesh m;
    const float two_pi = 6.2831853f;
    m.positions.push_back({0, 0, z_bottom});
    std::vector<std::uint32_t> first;
    for (const Ring& g : rings) {
        first.push_back(std::uint32_t(m.positions.size()));
        for (std::uint32_t i = 0; i < g.n; ++i) {
            const float a = two_pi * float(i) / float(g.n);
            m.positions.push_back({g.r * std::cos(a), g.r * std::sin(a), g.z});
        }
    }
    const std::uint32_t top = std::uint32_t(m.positions.size());
    m.positions.push_back({0, 0, z_top});
    const Ring& r0 = rings.front();
    for (std::uint32_t i = 0; i < r0.n; ++i) m.triangles.push_back({0, first[0] + (i + 1) % r0.n, first[0] + i});
    for (std::size_t k = 0; k + 1 < rings.size(); ++k) {
        const std::uint32_t na = rings[k].n, nb = rings[k + 1].n, a0 = first[k], b0 = first[k + 1];
        std::uint32_t i = 0, j = 0;
        while (i < na || j < nb) {
            // Advance on the ring whose next vertex comes first by angle.
            const bool on_a = j == nb || (i < na && float(i + 1) / float(na) <= float(j + 1) / float(nb));
            if (on_a) {
                m.triangles.push_back({a0 + i % na, a0 + (i + 1) % na, b0 + j % nb});
                ++i;
            } else {
                m.triangles.push_back({a0 + i % na, b0 + (j + 1) % nb, b0 + j % nb});
                ++j;
            }
        }
    }
    const Ring& rl = rings.back();
    const std::uint32_t l0 = first.back();
    for (std::uint32_t i = 0; i < rl.n; ++i) m.triangles.push_back({top, l0 + i, l0 + (i + 1) % rl.n});
    return m;
}

}  // namespace nmesh::test
