// nmesh/spatial/neighbour_grid.h — the k nearest neighbours of the points of a cloud.
//
// The points are hashed in cubic cells; a query for point i widens ring by ring round its cell
// until its k nearest are certain (every point within the searched block's inner radius has been
// seen), or until a given number of rings. Used by the open mode's analysis of the cloud (its rim
// and its normals, nmesh/finish/cloud_rim.h), which asks once per point: a hash map suffices.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "nmesh/vec3.h"

namespace nmesh {

class NeighbourGrid {
public:
    // `cell_size` > 0: about twice the point spacing keeps the blocks small. O(n).
    NeighbourGrid(const std::vector<Vec3>& points, float cell_size);

    // The up to k nearest points to points[i], i itself left out, nearest first, as (squared
    // distance, index); only those within `max_rings` rings of cells that are certain (within
    // max_rings cell sizes of the point), so a point with few neighbours near gets fewer than k.
    // `out` is overwritten. O(points in the block) per query.
    void nearest(std::uint32_t i, std::size_t k, int max_rings, std::vector<std::pair<float, std::uint32_t>>& out) const;

private:
    std::int64_t cell(float x) const;
    static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k);

    const std::vector<Vec3>& points_;
    float cell_size_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace nmesh
