// The pipeline's finishing stage (nmesh/pipeline/finishing.h).
#include "nmesh/pipeline/finishing.h"

#include "nmesh/finish/finish.h"
#include "nmesh/learn/sample_sides.h"
#include "nmesh/spatial/cloud_sample.h"

namespace nmesh::pipeline {

// One default for the finishing stage's rounds, whether it is run through reconstruct() or alone.
static_assert(FinishOptions{}.rounds == int(Parameters{}.finish_rounds), "two defaults for the finishing rounds");
static_assert(FinishOptions{}.fit_rounds == int(Parameters{}.fit_rounds), "two defaults for the centroid fit");
static_assert(FinishOptions{}.surface_fit_rounds == int(Parameters{}.surface_fit_rounds),
              "two defaults for the surface fit");
static_assert(FinishOptions{}.exchange_passes == int(Parameters{}.exchange_passes),
              "two defaults for the vertex exchange");

const PointGrid& cloud_index_of(std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud, const Normalization& norm,
                                const Parameters& params, Statistics& stats) {
    if (!cloud_index) {
        cloud_index = index_cloud(cloud, norm.transform, norm.bounds, params);
        record_index(*cloud_index, stats);
    }
    return *cloud_index;
}

bool finish_stage(const Mesh& learnt, std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud,
                  const Normalization& norm, const Parameters& params, Reporter& reporter, Statistics& stats,
                  Mesh& mesh, double progress_from, double progress_share, bool repair, bool last_resort,
                  const SolidStart* solid) {
    const PointGrid& index = cloud_index_of(cloud_index, cloud, norm, params, stats);
    mesh = learnt;
    FinishOptions options;
    options.rounds = int(params.finish_rounds);
    options.fit_rounds = int(params.fit_rounds);
    options.surface_fit_rounds = int(params.surface_fit_rounds);
    options.exchange_passes = int(params.exchange_passes);
    options.threads = params.threads;
    if (!repair) options.repair_max_rounds = 0;
    options.off_cloud_last_resort = last_resort;
    const std::vector<Vec3> points = index.indexed_points();
    std::vector<Vec3> sides;
    if (solid != nullptr && !solid->surface.positions.empty()) {
        sides = sample_sides(PointSpan(points), PointTransform{}, solid->surface, solid->reach, params.threads);
        options.point_sides = &sides;
    }
    const FinishReport report =
        finish_mesh(mesh, points, options, &index,
                    [&](double fraction) { reporter.report_finishing(progress_from + progress_share * fraction); });
    stats.repair_declined = stats.repair_declined || report.repair_declined;
    return mesh.n_vertices() == learnt.n_vertices();
}

}  // namespace nmesh::pipeline
