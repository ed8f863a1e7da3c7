// nmesh/pipeline/cloud_parts.h — whether a cloud is in several parts far apart (two objects in
// one scan), which one connected surface could only join: reconstruct() gives each its own
// (nmesh/pipeline/parts.h).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "nmesh/point_span.h"

namespace nmesh {

// reconstruct() links the points within this many times the cloud's median distance to the 8th
// nearest neighbour (median_neighbour_distance, stray_points.h): the reach at which a point of
// the default stray ratio has its 8 neighbours; and counts the parts holding at least kPartShare
// of the points.
inline constexpr float kPartLink = 6.0f;
inline constexpr double kPartShare = 0.01;

inline constexpr std::uint32_t kNoPart = std::numeric_limits<std::uint32_t>::max();

struct CloudParts {
    std::uint32_t count = 1;          // the parts holding at least the share of the points
    std::vector<std::uint32_t> part;  // per point: its part, 0 the largest; kNoPart in a smaller one
    std::vector<std::uint64_t> size;  // per part: its points
};

// The cloud's parts: its points joined through cubic cells `link` wide that hold points and
// touch (by a face, an edge or a corner). Two points closer than `link` are in one part; two
// parts are farther apart than `link` everywhere (and may be up to 2 sqrt(3) `link` apart and
// still be one). Counted are the parts holding at least `min_share` of the points, numbered by
// size (ties by their first point). An empty cloud has none; a `link` of 0 reads one part.
// O(n log n).
CloudParts cloud_parts(PointSpan cloud, float link, double min_share);

}  // namespace nmesh
