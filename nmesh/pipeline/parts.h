// nmesh/pipeline/parts.h — a cloud in parts far apart (cloud_parts.h) reconstructed part by part:
// a closed surface each, the vertices asked for shared by their points, the results joined.
//
// One connected surface round two objects apart joins them with a tube through the empty space
// between them (two unit spheres 3 apart: 8.7% of the diagonal from every point), which no check
// of the output sees. Choices: each part gets the share of the vertices its share of the points
// gives (largest remainders, so that the total is exactly the count asked for; the learning
// follows the density of the samples, and so does this share), at least kMinPartVertices, or the
// cloud is reconstructed whole (with the warning); the parts run one after the other, each with
// the caller's parameters and seed; the progress reports count the vertices and the seconds of
// the parts done; no snapshots are taken (a part's sizes are not the mesh's).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "nmesh/pipeline/cloud_parts.h"
#include "nmesh/point_span.h"
#include "nmesh/reconstruct.h"

namespace nmesh::pipeline {

inline constexpr std::uint32_t kMinPartVertices = 64;

// The vertices of each part: in proportion to its points (largest remainders), summing to
// `target`; empty when a part would get fewer than kMinPartVertices.
std::vector<std::uint32_t> part_budgets(const CloudParts& parts, std::uint32_t target);

// The counters of `part` added to `total` (the sum of the parts' work and time; a flag set when
// set in any part; solid_genus summed when every part read one, else -1).
void add_part_statistics(Statistics& total, const Statistics& part);

// Each part of `cloud` (its points in `parts`, those in no counted part left out) reconstructed
// by `one` with `budgets[i]` vertices, the meshes joined in the parts' order, the statistics
// added. Stops after a part that was cancelled (Result::cancelled). The output check of the
// joined mesh is the caller's.
using ReconstructOne = std::function<Result(PointSpan, const Parameters&, const Callbacks&)>;
Result reconstruct_parts(PointSpan cloud, const CloudParts& parts, const std::vector<std::uint32_t>& budgets,
                         const Parameters& params, const Callbacks& callbacks, const ReconstructOne& one);

}  // namespace nmesh::pipeline
