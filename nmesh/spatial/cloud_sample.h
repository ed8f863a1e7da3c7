// nmesh/cloud_sample.h — a stratified random sample of a point cloud.
//
// The edge swap's deviation (eq. 9 of the paper: the distance from a triangle's centroid to the
// nearest cloud point) and the finishing stage need a nearest-point index over the cloud. Its
// build reads every point (2.0 s and 18 bytes per point for 36 million points), while the mesh
// only needs the cloud as densely as its own triangles. reconstruct() therefore indexes a sample
// of at most Parameters::index_points_per_vertex points per target vertex (see there for the
// choice), drawn here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/spatial/point_transform.h"
#include "nmesh/parameters.h"
#include "nmesh/statistics.h"
#include "nmesh/vec3.h"

namespace nmesh {

// `count` points of `points`: the index range is cut into `count` runs of consecutive indices,
// as equal as whole indices allow (run j is [floor(j n / count), floor((j + 1) n / count))), and
// one point is drawn uniformly from each run, in order, with the seeded generator of
// nmesh/random.h. Scans list their points along scan lines, so consecutive indices lie close
// together: the sample covers the whole scan, at an even density, where a plain random sample
// would leave gaps and clumps. The same seed gives the same sample.
// Requires 0 < count <= points.size(); O(count) time, whatever the size of the cloud.
std::vector<Vec3> stratified_sample(PointSpan points, std::size_t count, std::uint64_t seed);

// The number of cloud points reconstruct() indexes for `params` (its target and
// index_points_per_vertex) out of a cloud of n points.
std::size_t index_point_count(std::size_t n, const Parameters& params);

// The nearest-point index over transform(p) for the points p of `points` when they are at most
// index_point_count(); otherwise over that many of them, stratified_sample() drawn with a seed
// derived from params.seed (a stream apart from the learning's samples). `bounds`: the box of all
// the transformed points (it holds the sample's too). The index names a point by its place in
// the sample (PointGrid::indexed_points() gives them in that order).
std::unique_ptr<PointGrid> index_cloud(PointSpan points, const PointTransform& transform, const BoundingBox& bounds,
                                       const Parameters& params);

// Statistics::indexed_points and index_bytes for `index`.
void record_index(const PointGrid& index, Statistics& stats);

}  // namespace nmesh
