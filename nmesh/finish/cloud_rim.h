// nmesh/finish/cloud_rim.h — the rim of a point cloud: the points at the edge of the sampled
// surface (where a scan ends, round a hole the scanner did not see, at the edge of a part another
// part hid from it).
//
// A point is on the rim when its kRimNeighbours nearest neighbours, seen in their own tangent
// plane (the plane of least variance of the neighbourhood), leave an empty sector wider than
// kRimGapRadians round it: inside a sampled surface the neighbours surround the point, at an edge
// they lie on one side (a gap of about 180 degrees on a straight edge). Nearest neighbours rather
// than a radius, so that the test follows the local density (a sparser part of a scan is not its
// rim). Choice: 120 degrees and 24 neighbours: with n neighbours scattered uniformly round an
// interior point, a gap that wide has a probability of about n (2/3)^(n-1), 0.2% for 24 (90
// degrees, the usual threshold, would give 3%; a random sphere sample of 20,000 points has 48).
// A point with fewer than kRimMinNeighbours neighbours within kRimMaxRings cells of two spacings
// (a stray point) is on the rim. A neighbourhood is flat when its least variance is at most
// kRimFlatness of the middle one; a crease or a corner (neighbours on two or more planes) is not,
// and its poorly fitted tangent plane can make it look one-sided: 3.5% of the rocker arm's points
// are on the rim, 0.7% on the rim where the neighbourhood is flat.
#pragma once

#include <vector>

#include "nmesh/vec3.h"

namespace nmesh {

inline constexpr int kRimNeighbours = 24;
inline constexpr float kRimGapRadians = 2.0943951f;  // 120 degrees
inline constexpr int kRimMinNeighbours = 6;
inline constexpr int kRimMaxRings = 3;
inline constexpr float kRimFlatness = 0.02f;

struct CloudRim {
    std::vector<char> rim;       // per point: 1 on the rim
    std::vector<char> flat;      // per point: 1 where the neighbourhood is flat
    std::vector<float> spacing;  // per point: the local point spacing, from its neighbours
    // Per point: the unit normal of its neighbourhood's least-variance plane, of either sign; zero
    // for a point with fewer than kRimMinNeighbours neighbours.
    std::vector<Vec3> normal;
};

// `spacing`: the cloud's typical point spacing (the cells' size is two of them). O(n k) for k
// neighbours per point, with a hashed grid.
CloudRim cloud_rim(const std::vector<Vec3>& points, float spacing);

// The largest empty angle round `centre` left by the directions `around` (unit vectors in a plane,
// or any vectors: they are taken in the plane spanned by `u` and `v`, two orthonormal vectors).
// 2 pi for no direction. The brute-force reference of the tests compares every pair.
float largest_gap(const Vec3& centre, const std::vector<Vec3>& around, const Vec3& u, const Vec3& v);

}  // namespace nmesh
