// nmesh/learn/simplify.h — a closed mesh simplified by edge collapses: the solid's outer surface
// made coarse enough to be the learning's start (solid_start.h).
#pragma once

#include <cstdint>

#include "nmesh/mesh/mesh.h"

namespace nmesh {

// Simplifies a closed mesh (with or without its face index) to `n` vertices by edge collapses,
// each to its midpoint: in passes over the shortest quarter of the edges, shortest first, no two
// collapses of a pass on one ring, skipping those the link condition refuses, that would turn a
// triangle over or leave a vertex with more than 10 neighbours. Keeps the genus. Returns false
// when it stops above n (no collapse left).
bool simplify(Mesh& mesh, std::uint32_t n);

}  // namespace nmesh
