// nmesh/pipeline/stray_points.h — the points a scan recorded off the scanned surface, left out
// before the learning (Parameters::stray_ratio).
//
// A stray point, out in the air in front of the surface or behind it, is a sample like any other
// to the learning: every time it is drawn it pulls its winner off the surface (eq. 2), and the
// finishing stage then has a spike to repair. A unit sphere sampled with 20,000 points and 400
// more spread through the cube round it came out with 266 crossing pairs and 119 inward faces
// after three output retries; without the 400, valid at once (docs/algorithm.md, "Stray points").
//
// The rule: a point is stray when its kStrayNeighbours-th nearest neighbour lies farther than
// R = Parameters::stray_ratio times the median of that distance over the cloud. On a surface
// sampled at random, that distance varies little (at most 1.7-2.5 times its median on the
// corpus's sampled clouds); in the sparse parts of a real scan up to 4.1 (the horse's, the rocker
// arm's 4.0); a point in the air, or a clump of fewer than kStrayNeighbours, lies many times
// farther from its neighbours.
#pragma once

#include <cstdint>
#include <vector>

#include "nmesh/point_span.h"

namespace nmesh {

inline constexpr std::uint32_t kStrayNeighbours = 8;

// The median over the cloud of the distance from a point to its kStrayNeighbours-th nearest
// neighbour, read from up to 4,096 points (every k-th); 0 when the cloud has fewer than 8
// kStrayNeighbours points (too few to tell) or the median is 0 (points repeated). O(n log n).
float median_neighbour_distance(PointSpan cloud);

// The indices of the points of `cloud` that have fewer than kStrayNeighbours others within
// `reach` (the stray points at ratio R: reach = R * median_neighbour_distance), ascending; none
// when `reach` is 0 or the cloud has fewer than 8 kStrayNeighbours points. `threads` share the
// points (0: the machine's cores): the same answer for every count. O(n log n).
std::vector<std::uint32_t> stray_points(PointSpan cloud, float reach, std::uint32_t threads);

// `cloud` without the points at `strays` (ascending indices), in order.
std::vector<Vec3> without_points(PointSpan cloud, const std::vector<std::uint32_t>& strays);

}  // namespace nmesh
