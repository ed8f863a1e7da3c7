// nmesh/reconstruct.h — the library's entry point: point cloud in, closed triangle mesh out.
//
//     nmesh::PointCloud cloud = nmesh::read_points("bunny.ply");
//     nmesh::Parameters params;              // Table 2 of the paper
//     params.target_vertices = 30000;
//     nmesh::Result r = nmesh::reconstruct(cloud, params);
//     nmesh::write_mesh("bunny_mesh.ply", r.mesh);
//
// The algorithm is Neural Meshes (Ivrissimtzis, Jeong and Seidel 2003) with the edge swap of
// Neural Meshes ES (Mari et al.); see nmesh/learn/neural_mesh.cpp for the steps, nmesh/pipeline/ for
// the stages around the learning, and docs/algorithm.md for the choices made where the papers
// leave room.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/parameters.h"
#include "nmesh/point_cloud.h"
#include "nmesh/statistics.h"

namespace nmesh {

// Reported to the progress callback about every 2^16 iterations, once when the learning ends,
// then during the finishing stage.
struct Progress {
    std::uint32_t vertices = 0;
    std::uint32_t target_vertices = 0;
    std::uint64_t iterations = 0;
    double seconds = 0.0;        // since reconstruct() began
    double setup_seconds = 0.0;  // the part of `seconds` before the first iteration (normalising
                                 // the cloud, building its nearest-point index)
    bool settling = false;
    // The finishing stage, after the learning: its share done (0 to 1). The stage's reports come
    // with `finishing` set, at most every 0.1 s; returning false from them changes nothing (the
    // stage keeps the vertex count and its rounds are bounded).
    bool finishing = false;
    double finish_fraction = 0.0;
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
    // A count below the start's (the solid's surface, Statistics::start_vertices) is handed the
    // start itself, with its own vertex count.
    std::vector<std::uint32_t> snapshot_vertices;
    std::function<void(std::uint32_t vertices, const IndexedMesh& mesh)> on_snapshot;
    // Measure the time of each phase (Statistics::seconds_*); slows learning a little.
    bool profile = false;
};

struct Result {
    IndexedMesh mesh;  // a 2-manifold facing outward (closed unless topology open), in the input's coordinates
    Statistics stats;
    bool cancelled = false;
};

// Reconstructs a closed triangle mesh with params.target_vertices vertices from the cloud.
// Throws ParameterError for invalid parameters and InputError for a cloud that cannot be
// reconstructed (fewer than 4 distinct points, or all points on one line) or that cannot carry
// the target size (the mesh stopped growing below it: no larger mesh in 8 step-8 periods).
// The cloud's stray points (Parameters::stray_ratio) are left out first, and the rest is
// normalised internally (centre and a power-of-two scale), so the result does not depend on the
// cloud's units.
Result reconstruct(PointSpan cloud, const Parameters& params = {}, const Callbacks& callbacks = {});
inline Result reconstruct(const PointCloud& cloud, const Parameters& params = {}, const Callbacks& callbacks = {}) {
    return reconstruct(PointSpan(cloud.points), params, callbacks);
}

}  // namespace nmesh
