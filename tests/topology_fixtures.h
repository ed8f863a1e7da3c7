// Indexed meshes of known topology for the boundary and handle tests: tori, tubes and disks.
#pragma once

#include <cmath>
#include <cstdint>

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

}  // namespace nmesh::test
