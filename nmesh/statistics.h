// nmesh/statistics.h — the counts and timings of one reconstruction (Result::stats, --stats).
#pragma once

#include <cstdint>

namespace nmesh {

// Counts and timings of one run.
struct Statistics {
    std::uint64_t iterations = 0;         // steps 1-6 executed (learning + settling)
    std::uint64_t settle_iterations = 0;  // of which in the settling phase
    std::uint64_t splits = 0;             // step 7
    std::uint64_t collapses = 0;          // step 8
    std::uint64_t collapses_refused = 0;  // inactive vertices with no legal collapse (kept)
    std::uint64_t removal_passes = 0;     // step 8 passes
    std::uint64_t swaps_tried = 0;        // edge swap: flips attempted (legal)
    std::uint64_t swaps_kept = 0;         //   kept: the new edge deviates less
    std::uint64_t swaps_undone = 0;       //   undone: it did not
    std::uint64_t swaps_illegal = 0;      //   the worst edge could not be flipped
    std::uint64_t moves_shortened = 0;    // step 3 moves shortened: they would fold the winner's fan
    std::uint64_t folds_undone = 0;       // folded winners moved towards their ring's centroid instead
    std::uint64_t side_skips = 0;         // samples not learnt: their winner faced away from their side
    // The learning's checkpoints against twists (topology closed and open, reconstruct()):
    // checks made, retries from the last checkpoint because the mesh had turned partly inside
    // out, and checkpoints passed with the region still there after every retry.
    std::uint64_t twist_checks = 0;
    std::uint64_t twist_retries = 0;
    std::uint64_t twists_kept = 0;
    // Outputs of a small target (at most 4,096 vertices) with crossing triangles or inward faces,
    // learnt again from the last checkpoint before the target.
    std::uint64_t output_retries = 0;
    // The learning's start (topology closed and open, nmesh/learn/solid_start.h): the genus of
    // the solid the cloud walls round, when it walls one (-1 when it does not), and the start
    // mesh's vertices (4: the tetrahedron; more: the solid's surface, when its genus is above 0).
    int solid_genus = -1;
    // The start was the solid's genus-0 core (its genus not read: solid_core.h); the handle
    // search stayed on.
    bool start_core = false;
    // Starts whose learning stopped growing before the target and was begun again from the next
    // start (reconstruct(): the solid's surface, the tetrahedron, the paper's learning).
    std::uint64_t start_retries = 0;
    // Points left out as stray before the learning (Parameters::stray_ratio).
    std::uint64_t stray_points = 0;
    // Topology closed and sphere: the parts far apart the cloud is in (nmesh/pipeline/cloud_parts.h),
    // each with at least 1% of the points; and whether each got a surface of its own
    // (nmesh/pipeline/parts.h: the counts above and below are then the parts' sums). Above 1
    // part without that, the one closed surface joins them.
    std::uint32_t cloud_parts = 1;
    bool parts_apart = false;
    std::uint64_t start_vertices = 4;
    // Topology learning (Parameters::topology closed, nmesh/learn/handles.h): searches made,
    // cap-like unsupported patches found over them, handles made, faces cut out for them.
    std::uint64_t topology_checks = 0;
    std::uint64_t membrane_patches = 0;
    std::uint64_t handles = 0;
    std::uint64_t membrane_faces_removed = 0;
    // Bridges (nmesh/learn/bridges.h): parts reached across a thin unsupported neck taken away,
    // and their vertices (and their necks') removed, at the same searches.
    std::uint64_t bridges = 0;
    std::uint64_t bridge_vertices_removed = 0;
    // Topology open (nmesh/finish/open_surface.h): faces taken off as the second sheet of a
    // double layer (facing away from a partial view), faces taken off as far from every point,
    // and faces taken off with the crossing pairs left at the end.
    std::uint64_t layer_faces_removed = 0;
    std::uint64_t open_faces_removed = 0;
    std::uint64_t crossing_faces_removed = 0;
    // and the vertices given back after those cuts (midpoint splits of the longest edges,
    // nmesh/finish/vertex_top_up.h), so that the result has the vertex count asked for.
    std::uint64_t open_vertices_added = 0;
    std::uint64_t indexed_points = 0;  // points in the nearest-point index (0 when none was built)
    std::uint64_t index_bytes = 0;     //   its memory (PointGrid::memory_bytes)
    double seconds = 0.0;              // learning time, wall clock (normalisation included)
    double seconds_finish = 0.0;       // the finishing stage (Parameters::finish), wall clock
    bool finished = false;             // the finishing stage ran and its mesh was returned
    // The finishing stage's repair was not tried: too many of the triangles crossed or folded
    // (nmesh/finish/repair.h, kRepairMaxDefectShare), as where a closed mesh wraps an open sheet.
    bool repair_declined = false;
    // The output checked (reconstruct() does it for every mesh it returns): the triangles were
    // reversed to face outward (negative signed volume), crossing triangle pairs by the exact
    // test, faces pointing inward. A valid surface has no crossing pair and no inward face.
    bool reoriented = false;
    int genus = 0;                     // of the output (-1 should it not be a manifold)
    std::uint64_t boundary_loops = 0;  // of the output: 0 for a closed surface
    std::uint64_t crossing_pairs = 0;
    std::uint64_t inward_faces = 0;
    // Time split by phase, filled only when Callbacks::profile is set (timing costs time).
    double seconds_winner = 0.0, seconds_update = 0.0, seconds_split = 0.0, seconds_collapse = 0.0, seconds_swap = 0.0;
};

}  // namespace nmesh
