// nmesh/reconstruct.h — the library's entry point: point cloud in, closed triangle mesh out.
//
//     nmesh::PointCloud cloud = nmesh::read_points("bunny.ply");
//     nmesh::Parameters params;              // Table 2 of the paper
//     params.target_vertices = 30000;
//     nmesh::Result r = nmesh::reconstruct(cloud, params);
//     nmesh::write_mesh("bunny_mesh.ply", r.mesh);
//
// The algorithm is Neural Meshes (Ivrissimtzis, Jeong and Seidel 2003) with the edge swap of
// Neural Meshes ES (Mari et al.); see nmesh/neural_mesh.cpp for the steps and README.md for the
// choices made where the papers leave room.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/point_cloud.h"

namespace nmesh {

// The learning parameters. Defaults are Table 2 of the Neural Meshes ES paper (its settings for
// the 30,000-vertex bunny), except the target size, which a caller should choose.
struct Parameters {
    std::uint32_t target_vertices = 10000;  // step 9: stop at this many vertices (>= 4, and at
                                            // most NeuralMesh::kMaxTargetVertices, 357,913,927)
    double alpha_w = 0.08;   // eq. (2): learning rate of the winner vertex, in (0, 1]
    double alpha_n = 0.01;   // eq. (3): learning rate of the winner's neighbours, in [0, 1]
    double alpha = 0.95;     // eq. (7): signal counter decay per iteration, in (0, 1)
    std::uint32_t cvs = 100; // step 7: a vertex split every Cvs iterations (>= 1)
    std::uint32_t cec = 20;  // step 8: inactive vertices removed every Cec * n iterations (>= 1)
    bool edge_swap = true;   // Neural Meshes ES; false gives the basic Neural Meshes algorithm
    std::uint64_t seed = 1;  // the same seed and input give a bit-identical mesh
    // Iterations of steps 1-6 (no splits or collapses) run after the target size is reached, so
    // the last vertices settle onto the surface; in units of the final vertex count n
    // (settle_iterations = settle * n). 0 disables the phase.
    double settle = 0.0;
    // Choice beyond the paper: the finishing stage of nmesh/finish.h runs once the target size is
    // reached (angle-improving flips and a tangential relaxation onto the cloud, then the repair
    // of folds and self-intersections; same vertex count). false gives the paper's plain
    // algorithm, bit for bit.
    bool finish = true;
    // The finishing stage's regularisation rounds (FinishOptions::rounds, in [0, 1000]): each
    // makes the triangles more regular, at about 17 ms per 30,000 vertices. 0 leaves only the
    // repair of folds and self-intersections.
    std::uint32_t finish_rounds = 10;
    // Rounds of the finishing stage's centroid fit (FinishOptions::fit_rounds, in [0, 100]):
    // each moves the vertices so that the triangles' centroids approach the cloud points nearest
    // to them, which lowers the paper's DM(X,T) at those points (the bunny at 30,000 vertices:
    // 0.000447 with none, 0.000413 with one, 0.000391 with two) but not the distance to other
    // samples of the same surface (points held out of the learning come out farther, points
    // sampled on the scanned object's surface as far). Choice: 0, a fit to the measure rather
    // than a better surface. Needs the finishing stage (finish).
    std::uint32_t fit_rounds = 0;
    // Choice beyond the paper: the nearest-point index behind eq. (9)'s deviation DM(t, X) and
    // behind the finishing stage holds at most this many cloud points per target vertex: all of a
    // cloud up to that size, otherwise a stratified sample of it (nmesh/cloud_sample.h), so that
    // its cost follows the mesh, not the cloud (36 million points: 1 byte per point instead of
    // 18, 0.25 s of setup instead of 2.0 s). The learning still draws its samples (step 1) from
    // the whole cloud, and the metrics measure against the whole cloud. 0 indexes every point.
    // Choice: 64. The bunny with 100 points per scan point (3.6 million) to 30,000 vertices: the
    // learnt meshes are as close to the cloud with 16 points per vertex as with all of them; the
    // finishing stage, which pulls each vertex towards the plane of its nearest indexed point,
    // leaves them farther with fewer points: mean point-to-surface distance +0.6% at 64 (five
    // seeds), +1.9% at 32, +3% at 16, +6.5% at 4, against the whole cloud; DM(X,T) +0.13% at
    // 64. The bunny itself (35,947 points for 30,000 vertices) is indexed whole.
    std::uint32_t index_points_per_vertex = 64;

    // Throws ParameterError naming the first parameter out of range.
    void validate() const;
};

// Counts and timings of one run.
struct Statistics {
    std::uint64_t iterations = 0;        // steps 1-6 executed (learning + settling)
    std::uint64_t settle_iterations = 0; // of which in the settling phase
    std::uint64_t splits = 0;            // step 7
    std::uint64_t collapses = 0;         // step 8
    std::uint64_t collapses_refused = 0; // inactive vertices with no legal collapse (kept)
    std::uint64_t removal_passes = 0;    // step 8 passes
    std::uint64_t swaps_tried = 0;       // edge swap: flips attempted (legal)
    std::uint64_t swaps_kept = 0;        //   kept: the new edge deviates less
    std::uint64_t swaps_undone = 0;      //   undone: it did not
    std::uint64_t swaps_illegal = 0;     //   the worst edge could not be flipped
    std::uint64_t indexed_points = 0;    // points in the nearest-point index (0 when none was built)
    std::uint64_t index_bytes = 0;       //   its memory (PointGrid::memory_bytes)
    double seconds = 0.0;                // learning time, wall clock (normalisation included)
    double seconds_finish = 0.0;         // the finishing stage (Parameters::finish), wall clock
    bool finished = false;               // the finishing stage ran and its mesh was returned
    // Time split by phase, filled only when Callbacks::profile is set (timing costs time).
    double seconds_winner = 0.0, seconds_update = 0.0, seconds_split = 0.0,
           seconds_collapse = 0.0, seconds_swap = 0.0;
};

// Reported to the progress callback about every 2^16 iterations, and once when the learning
// ends (before the finishing stage, which reports no progress).
struct Progress {
    std::uint32_t vertices = 0;
    std::uint32_t target_vertices = 0;
    std::uint64_t iterations = 0;
    double seconds = 0.0;        // since reconstruct() began
    double setup_seconds = 0.0;  // the part of `seconds` before the first iteration (normalising
                                 // the cloud, building its nearest-point index)
    bool settling = false;
};

// The learning time left, in seconds, extrapolated from the progress so far: the iterations per
// vertex are fixed (a split every Cvs), so the loop's time grows with the vertices; the setup,
// which can be most of the early time on a cloud of millions of points, is left out.
// Negative when unknown (no vertex gained yet, or settling).
double estimated_seconds_left(const Progress& progress);

struct Callbacks {
    // Return false to stop: reconstruct() then returns the mesh reached so far, with
    // Result::cancelled set.
    std::function<bool(const Progress&)> progress;
    // Vertex counts at which a copy of the mesh is handed to on_snapshot (in input coordinates).
    std::vector<std::uint32_t> snapshot_vertices;
    std::function<void(std::uint32_t vertices, const IndexedMesh& mesh)> on_snapshot;
    // Measure the time of each phase (Statistics::seconds_*); slows learning a little.
    bool profile = false;
};

struct Result {
    IndexedMesh mesh;  // a closed genus-0 2-manifold, in the input's coordinates
    Statistics stats;
    bool cancelled = false;
};

// Reconstructs a closed triangle mesh with params.target_vertices vertices from the cloud.
// Throws ParameterError for invalid parameters and InputError for a cloud that cannot be
// reconstructed (fewer than 4 distinct points, or all points on one line) or that cannot carry
// the target size (the mesh stopped growing below it: no larger mesh in 8 step-8 periods).
// The cloud is normalised internally (centre and a power-of-two scale), so the result does not
// depend on the cloud's units.
Result reconstruct(const PointCloud& cloud, const Parameters& params = {}, const Callbacks& callbacks = {});

}  // namespace nmesh
