// nmesh/learn/solid_core.h — the genus-0 core of a voxel solid: its cells grown from one of them
// in a ranked order, each only while adding it keeps the grown part a ball.
//
// A solid walled round by an offset closes the gaps between samples and, where two parts of the
// object lie closer than twice the offset (the camel's tail along its body), the gaps between
// those parts too: handles that are not the object's, which come and go as the grid shifts and
// the offset grows, so that no genus persists (solid_start.h) and the learning would start from
// a tetrahedron. The core keeps the solid's shape and cuts each of its handles where the loop
// round it is the least the object's: the growth goes in an order the caller ranks (solid_start:
// the inside first, then the shell from the points outwards), the deepest cells first among
// equals (depth: Kuhn-edge steps to the nearest cell off the solid), so two fronts meeting round
// a handle meet where the shell is farthest from the points, in a gap it closes between two
// parts, rather than across a part, whose cut would hold points.
//
// The grid is triangulated as solid_start's surfaces are (the Kuhn triangulation: six
// tetrahedra round each cube's diagonal from corner 0 to corner 7); a part of the grid stands
// for the simplices all of whose corners it holds, and its marching-tetrahedra surface bounds a
// neighbourhood of that complex. A cell can join the grown part without changing its topology
// (a simple cell) exactly when the part's cells among its 14 Kuhn neighbours, with the link's
// edges and triangles between them, form a contractible complex: on the link (a triangulated
// sphere, 14 vertices, 36 edges, 24 triangles) that is one component of Euler characteristic 1.
// A part grown from one cell by simple cells is contractible, and its surface a sphere.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace nmesh {

// The Kuhn triangulation of a grid: six tetrahedra round each cube's diagonal from corner 0 to
// corner 7 (corner c at (c & 1, c >> 1 & 1, c >> 2 & 1)); they match across the cubes' faces. Its
// edges are the lattice edges along the seven directions below (and their opposites).
inline constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
inline constexpr int kKuhnEdges[7][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};

// The index steps from a cell to its 14 Kuhn neighbours on a grid of `dims` cells (x fastest), in
// the order of simple_cell's bits.
std::array<std::int64_t, 14> kuhn_steps(const std::array<std::uint32_t, 3>& dims);

// Whether a cell whose Kuhn neighbours in the part are the set bits of `neighbours` (bit 2e: the
// neighbour at +kKuhnEdges[e], bit 2e + 1: at -kKuhnEdges[e]) joins the part without changing its
// topology (see above). A table of the 2^14 sets, made on the first call.
bool simple_cell(std::uint32_t neighbours);

// The genus-0 core of a solid given by `rank` (per cell, x fastest, of a grid of `dims` cells: 0
// off the solid, else the larger the earlier the cell joins; no solid cell on the grid's border
// layer): the cells grown from the solid cell of the highest rank, and among those the deepest,
// in that order, each while simple. One flag per cell; the cells of the seed's component that are
// left out are the cuts across its handles (and, round a cavity, the cells that would close it).
// O(cells log cells).
std::vector<std::uint8_t> genus_zero_core(const std::array<std::uint32_t, 3>& dims, const std::vector<std::uint16_t>& rank);

// The handles an offset made between two parts of an object, told from the object's own: the
// core's cuts (the solid's cells left out of `core`), in pieces joined along Kuhn edges. A cut
// across a handle of the object crosses its material, so some cell of the piece lies on a
// point's splat (`dist` 0: solid_start's squared cell distances); a piece none of whose cells
// does crosses only a gap the offset closed (measured: every cut of the shared and corpus clouds'
// handles holds such a cell; docs/algorithm.md). Returns the flags of the solid's cells less
// those pieces, and how many pieces there were.
struct FalseHandles {
    std::vector<std::uint8_t> solid;
    std::uint32_t cuts = 0;
};
FalseHandles without_false_handles(const std::array<std::uint32_t, 3>& dims, const std::vector<std::uint16_t>& rank,
                                   const std::vector<std::uint8_t>& core, const std::vector<std::uint8_t>& dist);

}  // namespace nmesh
