// nmesh/learn/cloud_splats.h — the shell a cloud's samples span: a flattened ball round each
// point, thin across the surface and wide along it.
//
// The solid a cloud walls round (solid_start.h) is the cells within an offset of the points and
// what they enclose. A ball of radius r round every point closes the gaps between random samples
// (spots up to about 4 d from every point, d the median spacing) only at r of about 4 d, and at
// that offset it also closes every gap narrower than 2r between two parts of the object: a
// camel's two legs 6 d apart become one leg, the fingers of a hand a mitten, and the learning
// that starts there never opens them again. The gaps between samples lie along the surface, the
// gaps between parts across it; so each point's ball is flattened along its normal (the least
// principal direction of its neighbours) by a stretch s: the cells within r of the point in the
// metric |D|^2 + (s^2 - 1) (n . D)^2, a disc r wide and r / s thick.
//
// Choices:
//   - s is read from the data, per point. The disc must still hold the surface where it bends
//     away from its tangent plane: at a distance r along it, a surface of radius of curvature a
//     is r^2 / (2a) off the plane, within the disc's half-thickness r / s while s <= 2a / r, at
//     r = 4 d (the offset that closes the sampling's gaps) s <= a / (2 d). The radius a is read
//     from the neighbourhood's spread off its plane: kSplatNeighbours points spread uniformly
//     over a disc of radius rho (rho^2 = 2 (lambda1 + lambda2), the two larger variances) on a
//     sphere of radius a are spread with a variance rho^4 / (48 a^2) off it, and noise adds to it
//     (a noisy flat patch reads as a bent one: a thicker disc, never a leaking one);
//   - s is at most kMaxStretch: the grid's cells are 2 d across, and a disc thinner than about a
//     cell lets the outside through between the cells' centres (at 4 d and s = 2, the disc is 2 d
//     thick either side: a cell);
//   - a point with fewer than 5 neighbours is a ball (s = 1).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "nmesh/vec3.h"

namespace nmesh {

inline constexpr int kSplatNeighbours = 16;
inline constexpr float kMaxStretch = 2.0f;

struct Splat {
    Vec3 centre;
    Vec3 normal;          // unit, or zero for a ball
    float stretch = 1.0f;  // s >= 1
};

// One splat per point; `spacing` is d. O(n k) for the neighbours. The points are shared by
// `threads` threads (0: the machine's cores): the same splats for every count.
std::vector<Splat> cloud_splats(const std::vector<Vec3>& points, float spacing, std::uint32_t threads = 1);

// Per cell of the grid (cells `h` across, cell (x, y, z) centred at origin + (x, y, z) h, x
// fastest), the smallest splat distance to a splat centre, in squared cells, rounded (254 for
// any value above): every cell whose value is at most reach^2 (`reach` in cells) has it, any
// other holds its value or 255. So a reading at an offset within the reach (the cells at most
// offset^2) is the same for any larger reach. `threads` share the grid's layers: the same
// result for every count.
std::vector<std::uint8_t> splat_distances(const std::vector<Splat>& splats, const Vec3& origin, float h,
                                          const std::array<std::uint32_t, 3>& dims, float reach,
                                          std::uint32_t threads);

}  // namespace nmesh
