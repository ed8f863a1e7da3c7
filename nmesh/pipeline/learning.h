// nmesh/pipeline/learning.h — the pipeline's learning stage: steps 1-9 of the engine
// (nmesh/learn/neural_mesh.h) to the target size, with the handle and bridge searches on the way,
// the snapshots, and the checkpoints the learning goes back to when part of the mesh turns
// inside out; then the optional settling.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "nmesh/error.h"
#include "nmesh/learn/neural_mesh.h"
#include "nmesh/parameters.h"
#include "nmesh/pipeline/normalization.h"
#include "nmesh/pipeline/reporter.h"
#include "nmesh/reconstruct.h"
#include "nmesh/statistics.h"

namespace nmesh::pipeline {

// Beyond the paper (topology closed and open): the learning's checkpoints against twists.
// On a coarse mesh a thin part (a horse's leg) is a flat fin of two sheets; samples from one
// side can pull the other sheet through, and the part comes out inside out, a region that grows
// with the mesh and that no later polish undoes. At each checkpoint (16, 32, ... vertices and
// the target, up to kLastCheckpoint) the largest region of faces pointing inward is measured
// (largest_inward_region: the exact winding-number test of the output check); when it is larger
// than the tolerance, the learning goes back to the last checkpoint and takes another random
// path from there (NeuralMesh::reseed), up to kRetries times, after which the attempt with the
// smallest region goes on and the checkpoints stop. A checkpoint is the engine copied (O(n)
// memory, twice). The streams are numbered in order, so the same seed still gives the same
// mesh. docs/algorithm.md has the measurements.
constexpr std::uint32_t kFirstCheckpoint = 16;
constexpr std::uint32_t kLastCheckpoint = 4096;
constexpr std::uint32_t kRetries = 8;
// A target whose output still has crossing triangles or inward faces is learnt again from the
// last checkpoint before it, on another stream, up to kOutputRetries times (reconstruct()).
constexpr std::uint32_t kOutputRetries = 3;

// Topology closed or open: the bridge and handle searches each time the mesh grows by half, from
// kFirstHandleSearch vertices up to kLastHandleSearchPercent % of the target, and at that size
// itself (where the steps stop short of it), so that a handle made has the rest of the growth to
// learn its wall.
constexpr std::uint32_t kFirstHandleSearch = 512;
constexpr std::uint64_t kLastHandleSearchPercent = 50;

// What the learning loop has done, restored with the engine at a checkpoint.
struct LoopState {
    std::size_t next_snapshot = 0;
    std::uint32_t largest = 0;
    std::uint64_t largest_pass = 0;  // removal pass count when `largest` was reached
    std::uint32_t next_handle_search = kFirstHandleSearch;
    std::uint32_t next_checkpoint = kFirstCheckpoint;
};

// The checkpoints of one run, kept across the learning and the output check.
struct Checkpoints {
    struct Saved {
        NeuralMesh engine;  // compact (NeuralMesh::compact)
        LoopState at;
        std::size_t inward = 0;
    };
    bool on = false;
    LoopState at;                     // the loop's own state
    std::optional<Saved> last, best;  // the last checkpoint passed; the best failed attempt
    std::uint32_t retries = 0;        // at the current checkpoint
    std::uint64_t streams = 0;        // random streams used
    Statistics counts;                // twist_checks, twist_retries, twists_kept, output_retries

    Checkpoints(const NeuralMesh& engine, const Parameters& params) : on(params.topology != Topology::sphere) {
        at.largest = engine.mesh().n_vertices();
        if (on) last = save(engine, 0);
    }
    Saved save(const NeuralMesh& engine, std::size_t inward) const {
        Saved c{engine, at, inward};
        c.engine.compact();
        return c;
    }
    // Back to `c`, on a new random stream.
    void restore(NeuralMesh& engine, const Saved& c) {
        engine = c.engine;
        at = c.at;
        engine.reseed(++streams);
    }
};

// Steps 1-9 until the target size (or a cancellation), with the snapshots on the way.
// Choice: a run that cannot reach the target stops with an error instead of going on forever.
// Vertices that win no signal in a step-8 period are removed, so a cloud of P points carries a
// limited number of vertices (53,458 for the bunny's 35,947 points with Table 2's Cec and Cvs),
// and any cloud carries few when Cec is small against Cvs. A growing mesh reaches a new largest
// size in every step-8 period (Cec * n / Cvs splits per period against a few removals);
// kStallPeriods periods in a row without one mean the mesh has stopped growing: Stalled, whose
// message names the size reached (reconstruct() tries another start before it reports one).
struct Stalled : InputError {
    using InputError::InputError;
};
void learn_to_target(NeuralMesh& engine, std::size_t cloud_size, const Parameters& params, const Callbacks& callbacks,
                     const Normalization& norm, Reporter& reporter, Checkpoints& cp);

// The optional settling phase: steps 1-6 only, settle * n iterations.
void settle(NeuralMesh& engine, const Parameters& params, Reporter& reporter);

}  // namespace nmesh::pipeline
