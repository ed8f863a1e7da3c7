// The pipeline's learning stage (nmesh/pipeline/learning.h).
#include "nmesh/pipeline/learning.h"

#include <algorithm>
#include <string>
#include <vector>

#include "nmesh/error.h"
#include "nmesh/learn/twist_check.h"

namespace nmesh::pipeline {

namespace {

// The largest region of inward faces a checkpoint accepts at n vertices: the learning's
// scattered folds (the finishing stage removes them) are regions of one or a few faces, and
// about n / 400 at the checkpoints of the horse that the finishing stage repaired; a twist that
// stays is 6-8 faces at 256 vertices and doubles with the mesh.
std::size_t twist_tolerance(std::uint32_t n) { return std::max<std::size_t>(2, n / 256); }

}  // namespace

void learn_to_target(NeuralMesh& engine, std::size_t cloud_size, const Parameters& params, const Callbacks& callbacks,
                     const Normalization& norm, Reporter& reporter, Checkpoints& cp) {
    constexpr std::uint64_t kStallPeriods = 8;
    std::vector<std::uint32_t> snapshots = callbacks.snapshot_vertices;
    std::sort(snapshots.begin(), snapshots.end());
    LoopState& at = cp.at;
    const std::uint32_t last_search = std::uint32_t(kLastHandleSearchPercent * params.target_vertices / 100);
    while (engine.mesh().n_vertices() < params.target_vertices) {
        engine.iterate();
        const std::uint32_t n = engine.mesh().n_vertices();
        if (params.topology != Topology::sphere && n >= at.next_handle_search) {
            if (n <= last_search) engine.learn_topology();
            const std::uint32_t next = at.next_handle_search + at.next_handle_search / 2;
            at.next_handle_search = at.next_handle_search < last_search && next > last_search ? last_search : next;
        }
        if (n > at.largest) {
            at.largest = n;
            at.largest_pass = engine.stats().removal_passes;
        } else if (engine.stats().removal_passes - at.largest_pass >= kStallPeriods) {
            throw Stalled("the mesh stopped growing at " + std::to_string(at.largest) + " vertices (" +
                          std::to_string(engine.stats().removal_passes - at.largest_pass) +
                          " removal periods without a larger mesh, " + std::to_string(engine.iteration()) +
                          " iterations): " + std::to_string(cloud_size) + " points cannot carry " +
                          std::to_string(params.target_vertices) + " vertices with Cvs " + std::to_string(params.cvs) +
                          " and Cec " + std::to_string(params.cec) + "; ask for at most about " +
                          std::to_string(at.largest) + " vertices, or a larger Cec");
        }
        // A checkpoint at each power of two and at the target, up to kLastCheckpoint.
        if (cp.on && at.next_checkpoint <= kLastCheckpoint &&
            n >= std::min(at.next_checkpoint, params.target_vertices)) {
            const std::size_t inward = largest_inward_region(engine.mesh());
            ++cp.counts.twist_checks;
            if (inward > twist_tolerance(n) && cp.retries < kRetries) {
                // Back to the last checkpoint, on another random path.
                if (!cp.best || inward < cp.best->inward) cp.best = cp.save(engine, inward);
                ++cp.retries;
                ++cp.counts.twist_retries;
                cp.restore(engine, *cp.last);
                continue;
            }
            if (inward > twist_tolerance(n)) {
                // Every retry twisted too: the attempt with the smallest region goes on.
                if (cp.best && cp.best->inward < inward) {
                    engine = cp.best->engine;
                    at = cp.best->at;
                }
                ++cp.counts.twists_kept;
                // A cloud whose learning twists whatever the path (an open sheet, whose closed
                // mesh is two layers through each other) is not checked again.
                cp.on = false;
            }
            cp.best.reset();
            cp.retries = 0;
            at.next_checkpoint *= 2;
            // The check at the target keeps the checkpoint before it, for the output check.
            if (cp.on && n < params.target_vertices) cp.last = cp.save(engine, 0);
        }
        while (at.next_snapshot < snapshots.size() && engine.mesh().n_vertices() >= snapshots[at.next_snapshot]) {
            if (callbacks.on_snapshot)
                callbacks.on_snapshot(snapshots[at.next_snapshot], norm.to_input(engine.mesh().to_indexed()));
            ++at.next_snapshot;
        }
        if (!reporter.keep_going(false)) break;
    }
    engine.stats().twist_checks = cp.counts.twist_checks;
    engine.stats().twist_retries = cp.counts.twist_retries;
    engine.stats().twists_kept = cp.counts.twists_kept;
    if (reporter.cancelled()) return;
    // Choice: a target of 4 is the initial tetrahedron, reached before any iteration; it still
    // learns, with steps 1-6 for Cvs iterations per vertex (4 Cvs in all), so that it is fitted
    // to the cloud rather than returned as placed. A run to 8 or more vertices takes at least
    // that many iterations anyway (a split every Cvs iterations); smaller ones are topped up.
    const std::uint64_t minimum = 4 * std::uint64_t(params.cvs);
    while (engine.iteration() < minimum) {
        engine.adapt();
        if (!reporter.keep_going(false)) return;
    }
}

void settle(NeuralMesh& engine, const Parameters& params, Reporter& reporter) {
    const std::uint64_t iterations = std::uint64_t(params.settle * engine.mesh().n_vertices());
    for (std::uint64_t i = 0; i < iterations; ++i) {
        engine.adapt();
        ++engine.stats().settle_iterations;
        if (!reporter.keep_going(true)) return;
    }
}

}  // namespace nmesh::pipeline
