// nmesh/point_grid.h — a static spatial index answering "which cloud point is nearest to q?".
//
// Built once over a point cloud and never modified. The learning loop asks it, on every edge swap,
// for the distance from a triangle centroid to the cloud (eq. 9 of the paper); the metrics ask it
// for the distance from surface samples to the cloud.
//
// Structure: a uniform grid over the cloud's bounding box. The points are counting-sorted into
// their cells, so the points of a cell are contiguous in a private copy of the cloud (each point
// stored with its index). Cells are numbered brick by brick (4x4x4 cells) so that neighbouring
// cells' points lie close in memory. Only occupied cells store where their points start: one
// occupancy word per brick (a bit per cell and the number of occupied cells before the brick) maps
// a cell to its slot. A pyramid of occupancy bits, each level halving the grid along every axis,
// lets queries far from the data skip the empty space.
//
// Answers are exact: the returned point minimizes nmesh::squared_distance(q, p) as computed in
// float, ties going to the smaller point index — the same answer as a brute-force scan.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/util/huge_page_allocator.h"
#include "nmesh/spatial/point_transform.h"
#include "nmesh/vec3.h"

namespace nmesh {

// The nearest cloud point to a query: its index in the cloud given to the PointGrid, and its
// squared distance to the query (in squared input units).
struct NearestPoint {
    std::uint32_t index = 0;
    float squared_distance = 0.0f;
};

class PointGrid {
public:
    // Builds the index over `points` (copied). O(n) time; 4 bytes per point of temporary memory.
    //
    // Cell size: sized for surface-like data, about kPointsPerCell points per occupied cell when
    // the points sample a surface whose area is near half the bounding box's surface area (for a
    // sphere in its cube the ratio is 1.05; for the bunny scan 7 points per occupied cell result),
    // with at most kMaxCellsPerPoint cells per point.
    //
    // Memory: the copy of the points (12 bytes per point) and, on top of it, 4 bytes per point for
    // their indices, 2 bits per cell rounded up to whole bricks (at most
    // kMaxCellsPerPoint / 4 bytes per point, plus brick padding), 4 bytes per occupied cell (at
    // most 4 bytes per point; about 0.5 for scanned surfaces) and the pyramid (about 0.3 bits per
    // cell). Measured: 5.1 bytes per point beyond the copy for the bunny scan (36k points), 7.0
    // for 3.6M points; memory_bytes() reports the exact figure.
    //
    // Throws InputError if `points` is empty, has more than 2^32 - 1 points, or contains a NaN or
    // infinite coordinate.
    //
    // `transform`: the index is built over transform(p) for the points p (no copy of the
    // transformed cloud is made besides the index's own); identity by default.
    explicit PointGrid(PointSpan points, const PointTransform& transform = {});
    // The same index when the caller already knows `bounds`, the bounding box of the transformed
    // points (all of them finite, as the caller has checked): the pass over the points that
    // finds the box and checks every coordinate is skipped (0.3 s for 36 million points).
    PointGrid(PointSpan points, const PointTransform& transform, const BoundingBox& bounds);

    // The nearest point to q, with ties going to the smaller index.
    // Precondition: q is finite, and squared distances from q to the points fit in a float
    // (coordinates below about 1e18 in magnitude).
    // Cost: the 3x3x3 cells around q when q is near the data (about 1000 instructions; measured
    // 150-250 ns on the bunny scan and 0.6-1 us on 3.6M points in random order, where cache misses
    // dominate). A query farther away climbs the pyramid, one level per doubling of its distance
    // to the data in cells, and scans the occupied cells within reach: tens of microseconds for
    // a query ten bounding-box diagonals from a 36k-point scan.
    NearestPoint find_nearest(const Vec3& q) const;
    std::uint32_t nearest(const Vec3& q) const { return find_nearest(q).index; }
    float nearest_squared_distance(const Vec3& q) const { return find_nearest(q).squared_distance; }

    // Number of points indexed.
    std::size_t size() const { return entries_.size(); }
    // Edge length of a grid cell, in input units.
    double cell_size() const { return cell_size_; }
    // Number of cells along x, y and z.
    std::array<std::uint32_t, 3> dimensions() const { return {dims_[0], dims_[1], dims_[2]}; }
    // Number of cells holding at least one point.
    std::size_t occupied_cells() const { return cell_start_.size() - 1; }
    // Bytes held by the index, including the sorted copy of the points.
    std::size_t memory_bytes() const;
    // The indexed points as the index holds them (transformed), in the order of their indices:
    // element i is the point find_nearest() names by index i. O(n); for a caller that needs the
    // points beside the index (the finishing stage) without keeping a copy of its own.
    std::vector<Vec3> indexed_points() const;

    // Target number of points per occupied cell for surface data: fewer cells per query to visit
    // against more distances per cell. Near queries cost the same from 2 to 8 (within 7%);
    // queries a few cells away from the data get cheaper up to 16 (30% fewer instructions at 8
    // than at 4).
    static constexpr double kPointsPerCell = 8.0;
    // Cap on cells per point, bounding the occupancy bits at 2 bytes per point when the surface
    // rule would ask for more cells (large clouds filling little of their bounding box).
    static constexpr double kMaxCellsPerPoint = 8.0;

private:
    // The construction once the box of the transformed points is known.
    void build(PointSpan points, const PointTransform& transform, const BoundingBox& box);

    // Occupancy of the 64 cells of a brick, and the number of occupied cells before the brick.
    struct OccupancyWord {
        std::uint64_t bits = 0;
        std::uint32_t rank = 0;
    };
    struct Scan;  // the state of one query, defined in the .cpp
    // The extent of a pyramid cell along one axis, seen from a query: the squared distance to it
    // in grid units, and whether it lies within the block of grid cells already scanned.
    struct Span {
        double g2;
        bool scanned;
    };

    // Cells are numbered brick by brick (4x4x4 cells, one occupancy word each), so that a cell's
    // neighbours usually share its occupancy word and their points lie close in memory.
    static constexpr std::uint32_t kBrick = 4;
    std::uint64_t cell_id(std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    // Bit of a pyramid cell of level >= 1 (x fastest, then y, then z).
    std::uint64_t pyramid_bit(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    void set_bit(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k);
    // Slot of cell `c` among the occupied cells, or -1 when it is empty.
    std::int64_t slot_of(std::uint64_t c) const;
    bool pyramid_occupied(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k) const;
    Span span(int axis, int level, std::uint32_t c, const Scan& s) const;
    void scan_cell(std::uint64_t c, Scan& s) const;
    void descend(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k, Scan& s) const;
    void search_level(int level, Scan& s) const;
    bool settled(const Scan& s) const;

    // A point and its index in the input, side by side so that a query reads both at once.
    struct Entry {
        Vec3 point;
        std::uint32_t index;
    };
    // The large arrays (hundreds of megabytes for tens of millions of points) on huge pages:
    // fewer page faults while they are filled, fewer TLB misses in the queries.
    HugePageVector<Entry> entries_;             // grouped by cell
    HugePageVector<OccupancyWord> occupancy_;   // one word per brick of 4x4x4 cells
    HugePageVector<std::uint32_t> cell_start_;  // per occupied cell, then the total count
    // pyramid_[l - 1] holds the occupancy bits of level l >= 1, whose cells are 2^l grid cells wide.
    std::vector<std::vector<std::uint64_t>> pyramid_;
    std::vector<std::array<std::uint32_t, 3>> level_dims_;  // cells per axis, level 0 first

    double origin_[3] = {0.0, 0.0, 0.0};  // the bounding box's minimum corner
    double cell_size_ = 1.0;
    double inv_cell_size_ = 1.0;
    std::uint32_t dims_[3] = {1, 1, 1};
    std::uint32_t bricks_[3] = {1, 1, 1};  // bricks along x, y and z
};

}  // namespace nmesh
