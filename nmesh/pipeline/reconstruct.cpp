// reconstruct(): the pipeline's stages in their order. The cloud is checked, its stray points
// left out (stray_points.h) and the rest normalised (normalization.h); the learning starts from
// the solid the cloud walls round or from the tetrahedron (nmesh/learn/solid_start.h); it learns
// to the target size with its checkpoints (learning.h); the learnt mesh is finished
// (finishing.h), or, with topology open, finished and cut open where the cloud has no data
// (opening.h); the output is turned outward and checked (output_check.h), and an output that is
// not valid is learnt again from the last checkpoint.
#include "nmesh/reconstruct.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "nmesh/geometry/flatness.h"
#include "nmesh/learn/neural_mesh.h"
#include "nmesh/learn/sample_sides.h"
#include "nmesh/learn/solid_start.h"
#include "nmesh/pipeline/cloud_parts.h"
#include "nmesh/pipeline/finishing.h"
#include "nmesh/pipeline/learning.h"
#include "nmesh/pipeline/normalization.h"
#include "nmesh/pipeline/opening.h"
#include "nmesh/pipeline/parts.h"
#include "nmesh/pipeline/output_check.h"
#include "nmesh/pipeline/reporter.h"
#include "nmesh/pipeline/stray_points.h"

namespace nmesh {

double estimated_seconds_left(const Progress& p) {
    if (p.settling || p.target_vertices == 0 || p.vertices == 0) return -1.0;
    const double fraction = std::min(1.0, double(p.vertices) / double(p.target_vertices));
    const double loop = std::max(0.0, p.seconds - p.setup_seconds);
    return loop * (1.0 - fraction) / fraction;
}

using namespace pipeline;

namespace {

// The learning from `solid`'s surface (the tetrahedron when it has none), to the target size, and
// what follows it: finishing, opening, the output check, the output retries. `learning`: the
// parameters of the engine, its checkpoints and its searches; `params`: the caller's, which decide
// the output's stages. Throws Stalled when the mesh stops growing.
Result learn_from(PointSpan cloud, const Parameters& params, const Parameters& learning, const Callbacks& callbacks,
                  const Normalization& norm, Clock::time_point start, SolidStart& solid) {
    const std::uint64_t start_vertices = solid.mesh ? solid.mesh->n_vertices() : 4;
    // On the heap, so that it can be destroyed, and its memory freed, as soon as the learning ends.
    std::unique_ptr<NeuralMesh> engine =
        solid.mesh ? std::make_unique<NeuralMesh>(cloud, norm.bounds, learning, norm.transform, *solid.mesh)
                   : std::make_unique<NeuralMesh>(cloud, norm.bounds, learning, norm.transform);
    // From the solid's surface the learning has both sheets of every thin part: the samples'
    // sides keep them apart (sample_sides.h).
    std::vector<Vec3> sides;
    if (solid.mesh) {
        engine->start_has_shape();
        if (!solid.core) engine->keep_genus();
        sides = sample_sides(cloud, norm.transform, solid.surface, solid.reach, params.threads);
        engine->set_sample_sides(sides.data());
    }
    engine->set_profiling(callbacks.profile);
    Reporter reporter(callbacks, engine, params.target_vertices, start);

    Checkpoints checkpoints(*engine, learning);
    // Output retries, with the finishing stage (without it the learnt mesh is wanted as it is), at
    // any target: from the last checkpoint (kLastCheckpoint vertices at most), another path learns
    // the rest again. Only an output that fails the check pays for it; above twice the last
    // checkpoint, where a retry learns most of the mesh again, the finishing stage's last resort
    // comes first on every attempt, so that an output valid without retries stays as it was.
    // Over the corpus sweep (seeds 1-10, 15,000 vertices) the five closed runs that ended with
    // crossings (the femur's seeds 1, 5 and 9, the camel's 7, the triceratops's 10) were not
    // retried before: docs/algorithm.md has what the retries make of them.
    const std::uint32_t output_retries = checkpoints.on && params.finish ? kOutputRetries : 0;
    Result result;
    double finish_seconds = 0.0;  // the finishing stage's time over the attempts
    for (std::uint32_t attempt = 0;; ++attempt) {
        learn_to_target(*engine, cloud.size(), learning, callbacks, norm, reporter, checkpoints);
        if (!reporter.cancelled()) settle(*engine, params, reporter);
        const double learnt_at = reporter.elapsed();

        result = Result();
        result.cancelled = reporter.cancelled();
        result.stats = engine->stats();
        result.stats.solid_genus = solid.solid_genus;
        result.stats.start_core = solid.core && solid.mesh.has_value();
        result.stats.start_vertices = start_vertices;
        // The last progress report: the learning is over.
        if (!result.cancelled) reporter.report(params.settle > 0.0);
        const bool finish = !result.cancelled && params.finish;
        // The learnt mesh and the cloud's index leave the engine, which is destroyed: what
        // follows does not add to the memory of the grid, activity index and ring cache.
        Mesh learnt = engine->take_mesh();
        const bool open = !result.cancelled && params.topology == Topology::open;
        std::shared_ptr<PointGrid> cloud_index = finish || open ? engine->take_cloud_index() : nullptr;
        engine.reset();

        // No output retry left, or a target whose retry learns most of it again: the finishing
        // stage may take its last resort (a repair that leaves the cloud a little) first.
        const bool last = attempt >= output_retries || !checkpoints.on || !checkpoints.last ||
                          params.target_vertices > 2 * kLastCheckpoint;
        if (open) {
            open_output(learnt, finish, last, cloud_index, cloud, norm, params, reporter, result);
        } else {
            Mesh finished;
            result.stats.finished = finish && finish_stage(learnt, cloud_index, cloud, norm, params, reporter,
                                                           result.stats, finished, 0.0, 1.0, true, last,
                                                           &solid);
            if (result.stats.finished) learnt = Mesh();  // freed before the output mesh is built
            result.mesh = (result.stats.finished ? finished : learnt).to_indexed();
        }
        cloud_index.reset();
        result.mesh = norm.to_input(result.mesh);
        // The learning's time leaves out the finishing of earlier attempts.
        const double finishing = finish ? reporter.elapsed() - learnt_at : 0.0;
        result.stats.seconds = learnt_at - finish_seconds;
        finish_seconds += finishing;
        result.stats.seconds_finish = finish_seconds;
        check_output(result, params.threads);
        result.stats.output_retries = checkpoints.counts.output_retries;
        const bool valid = result.stats.crossing_pairs == 0 && result.stats.inward_faces == 0;
        if (valid || result.cancelled || attempt >= output_retries || !checkpoints.on || !checkpoints.last) break;
        // The output check failed: the learning again from its last checkpoint, on another
        // path, in a new engine with the room for the target.
        ++checkpoints.counts.output_retries;
        engine = std::make_unique<NeuralMesh>(checkpoints.last->engine);
        engine->reserve_target();
        checkpoints.restore(*engine, *checkpoints.last);
    }
    return result;
}

// One cloud (the whole, or a part of it far from the others: parts.h), from its normalisation
// on.
Result reconstruct_cloud(PointSpan cloud, const Parameters& params, const Callbacks& callbacks,
                         Clock::time_point start) {
    const Normalization norm(require_reconstructible(cloud));
    // The fold guard is off for a flat cloud: its closed mesh must fold flat, two coinciding sheets.
    Parameters learning = params;
    learning.fold_guard = params.fold_guard && !is_flat(cloud);
    // Topology closed and open: from the solid's surface when the cloud walls a solid round
    // (solid_start.h), its genus kept (the handle search off: a handle the solid's offset closes
    // is narrower than a few point spacings); otherwise, and in sphere mode, from the
    // tetrahedron, with the handle search.
    SolidStart solid;
    if (params.topology != Topology::sphere && params.solid_start)
        solid = solid_start(cloud, norm.transform, params.target_vertices, params.threads);
    // Choice: a learning whose mesh stops growing is tried again from the next start: from the
    // solid's surface, then from the tetrahedron with the searches (as --no-solid-start), then the
    // paper's learning (as topology sphere: no checkpoints, no searches; its output still opened
    // in topology open). A start that leads the learning astray (a solid's surface far outside a
    // scan with many holes, where the vertices the samples reach are too few to grow) is not the
    // cloud's limit; the error, naming the size reached, is reported only when every start stalls.
    std::uint64_t stalled = 0;
    for (;;) {
        try {
            Result r = learn_from(cloud, params, learning, callbacks, norm, start, solid);
            r.stats.start_retries = stalled;
            return r;
        } catch (const Stalled& e) {
            ++stalled;
            if (solid.mesh) {
                solid = SolidStart();
            } else if (learning.topology != Topology::sphere) {
                learning.topology = Topology::sphere;
            } else {
                if (stalled == 1) throw;
                throw InputError(std::string(e.what()) + " (from each of the " + std::to_string(stalled) +
                                 " starts tried: " + (stalled == 3 ? "the solid's surface, " : "") +
                                 "the tetrahedron, and the paper's learning)");
            }
        }
    }
}

}  // namespace

Result reconstruct(PointSpan input, const Parameters& params, const Callbacks& callbacks) {
    params.validate();
    const auto start = Clock::now();
    require_reconstructible(input);
    // The scan's stray points are left out (stray_points.h); the rest is the cloud from here on.
    // Every point stays when none is stray.
    const float neighbour = median_neighbour_distance(input);
    const std::vector<std::uint32_t> strays = stray_points(input, params.stray_ratio * neighbour, params.threads);
    const std::vector<Vec3> kept = strays.empty() ? std::vector<Vec3>() : without_points(input, strays);
    const PointSpan cloud = strays.empty() ? input : PointSpan(kept);
    // A closed surface round a cloud in parts far apart would join them (cloud_parts.h): each
    // part gets a surface of its own when the vertices asked for go round (parts.h), otherwise
    // the caller is warned. An open result may hold several pieces: read whole.
    const CloudParts parts = params.topology == Topology::open
                                 ? CloudParts()
                                 : cloud_parts(cloud, kPartLink * neighbour, kPartShare);
    const std::vector<std::uint32_t> budgets =
        parts.count > 1 ? part_budgets(parts, params.target_vertices) : std::vector<std::uint32_t>();
    Result r;
    if (budgets.empty()) {
        r = reconstruct_cloud(cloud, params, callbacks, start);
    } else {
        // Each part's times from its own start (its progress reports add the parts' before).
        const auto one = [](PointSpan part, const Parameters& p, const Callbacks& c) {
            return reconstruct_cloud(part, p, c, Clock::now());
        };
        r = reconstruct_parts(cloud, parts, budgets, params, callbacks, one);
        check_output(r, params.threads);
        r.stats.parts_apart = true;
        // The points of the parts too small to count are left out with the strays.
        for (const std::uint32_t part : parts.part) r.stats.stray_points += std::uint64_t(part == kNoPart);
    }
    r.stats.stray_points += strays.size();
    r.stats.cloud_parts = parts.count;
    return r;
}

}  // namespace nmesh
