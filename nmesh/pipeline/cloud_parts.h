// nmesh/pipeline/cloud_parts.h — whether a cloud is in several parts far apart (two objects in
// one scan), which one connected surface can only join (a warning, reconstruct()).
#pragma once

#include <cstdint>

#include "nmesh/point_span.h"

namespace nmesh {

// reconstruct() links the points within this many times the cloud's median distance to the 8th
// nearest neighbour (median_neighbour_distance, stray_points.h): the reach at which a point of
// the default stray ratio has its 8 neighbours; and counts the parts holding at least kPartShare
// of the points.
inline constexpr float kPartLink = 6.0f;
inline constexpr double kPartShare = 0.01;

// The cloud's parts: its points joined through cubic cells `link` wide that hold points and
// touch (by a face, an edge or a corner). Two points closer than `link` are in one part; two
// parts are farther apart than `link` everywhere (and may be up to 2 sqrt(3) `link` apart and
// still be one). Returns the number of parts holding at least `min_share` of the points. O(n log n).
std::uint32_t cloud_parts(PointSpan cloud, float link, double min_share);

}  // namespace nmesh
