// nmesh/indexed_mesh.h — a dense triangle mesh: positions plus index triples.
//
// This is what the library hands out (the half-edge Mesh compacts itself into one) and what the
// writers, the metrics and the renderer take. Triangles are counter-clockwise seen from outside.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "nmesh/vec3.h"

namespace nmesh {

struct IndexedMesh {
    std::vector<Vec3> positions;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

}  // namespace nmesh
