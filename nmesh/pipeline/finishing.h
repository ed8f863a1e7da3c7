// nmesh/pipeline/finishing.h — the pipeline's finishing stage: the finishing stage of
// nmesh/finish/finish.h run on the learnt mesh, with the cloud index the learning built.
#pragma once

#include <memory>

#include "nmesh/learn/solid_start.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/parameters.h"
#include "nmesh/pipeline/normalization.h"
#include "nmesh/pipeline/reporter.h"
#include "nmesh/point_span.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/statistics.h"

namespace nmesh::pipeline {

// The finishing stage (nmesh/finish/finish.h) on a copy of the learnt mesh, with the cloud the
// engine's nearest-point index holds (all of it, or the sample of
// Parameters::index_points_per_vertex, normalised), or a new index when the engine has none
// (it builds one only for the edge swap). Returns false, leaving `mesh` alone, should the stage
// ever fail to keep the vertex count.
// Choice: the stage runs without a time limit (FinishOptions::seconds_limit 0), so that the same
// input, parameters and seed give the same mesh on any machine: a limit in seconds would make the
// number of repair rounds, and so the mesh, depend on the machine's speed. Its rounds are bounded
// (FinishOptions::repair_max_rounds). `solid`: the solid the learning started from, or null: the
// points' sides come from its surface as in the learning (nmesh/learn/sample_sides.h).
bool finish_stage(const Mesh& learnt, std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud,
                  const Normalization& norm, const Parameters& params, Reporter& reporter, Statistics& stats,
                  Mesh& mesh, double progress_from = 0.0, double progress_share = 1.0, bool repair = true,
                  bool last_resort = true, const SolidStart* solid = nullptr);

// The cloud index of the learning, or a new one when the engine has none (it builds one only
// for the edge swap).
const PointGrid& cloud_index_of(std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud, const Normalization& norm,
                                const Parameters& params, Statistics& stats);

}  // namespace nmesh::pipeline
