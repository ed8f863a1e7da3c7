// nmesh/finish/finish.h — the finishing stage: a few passes over the learnt mesh once it has reached its
// target size, for the shape of its triangles and a clean embedding (no folds, no
// self-intersections). A choice beyond the paper, on by default (Parameters::finish).
//
// The learning leaves defects that no step of the paper's algorithm removes: thin triangles (the
// connectivity is whatever the splits, collapses and swaps left), small folds (adjacent triangles
// turned back onto each other where a vertex overshot) and, in places such as a tightly bent ear,
// tangles whose triangles cross one another. The stage runs on the engine's final mesh and the
// (normalised) cloud:
//   1. regularisation, a few rounds of: angle-improving (Delaunay) edge flips restricted to nearly
//      coplanar pairs; a tangential relaxation of every vertex towards the area-weighted centroid
//      of its triangles, the vertex then pulled along its normal towards the plane through its
//      nearest cloud point (CloudSurface::pull: at most a quarter of an edge per round, only
//      towards a point facing the same way; a vertex that would end more than an edge from the
//      cloud, farther than it was, stays where it is; so does a vertex whose move would leave the
//      place the learning left it on the scan uncovered: a tip, a sharp ridge, relax_tangentially);
//      then the vertex exchange: collapses where the surface is flat paired with splits where it
//      bends away from the mesh, measured on the mesh fitted to the points (exchange.h);
//   2. repair of folds and self-intersections: local smoothing, collapses of very short and splits
//      of very long edges around each defect until none is left, then the smoothed vertices are
//      pulled back towards the cloud wherever that creates no new defect. The repair is all or
//      nothing: if a defect is left, or the estimated Hausdorff distance to the cloud would grow
//      by more than half an edge, the mesh is put back as the regularisation left it;
//   3. cover: vertices drawn out to the scan points the surface leaves uncovered (cover.h);
//   4. surface fit: the vertices moved along their normals to where the triangles best match the
//      scan points, a least-squares fit with a membrane on the moves (surface_fit.h), no move kept
//      that makes a crossing or a fold.
// When the repair does not succeed, the stage never returns a mesh with more intersecting
// triangle pairs than the learnt one (see FinishReport::fallback).
// The vertex count never changes (collapses and splits are balanced at once) and every
// topology operation is taken only when the mesh allows it (Mesh::can_flip, can_collapse), so the
// result is a closed genus-0 2-manifold with exactly the vertices asked for.
// Each pass is O(n) for a mesh of n vertices (the repair is local to the defects), whatever the
// size of the cloud: a cloud larger than the mesh is read in full only by is_flat() and by the
// nearest-point index (see CloudSurface and estimate_hausdorff for how the rest follows the
// mesh), and reconstruct() gives it no more than 64 points per vertex (the stratified sample of
// nmesh/spatial/cloud_sample.h, with the engine's index over it). About 0.30 s for the 30,000-vertex
// bunny, against 1.3 s of learning; 0.55 s for 30,000 vertices from 36 million points on a
// sphere through reconstruct() (26 s when every point had its own normal and its own term in
// the repair's estimate, 2.1 s when the stage still worked on every point).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/finish/hausdorff_estimate.h"
#include "nmesh/finish/regularise.h"
#include "nmesh/finish/repair.h"
#include "nmesh/finish/surface_fit.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

struct FinishOptions {
    // Regularisation rounds (flips, then relaxation). 0 skips step 1. Each round makes the
    // triangles more regular and moves the vertices further off the scan points the learning left
    // them on; ten is the default (docs/algorithm.md, Finishing stage).
    int rounds = 10;
    // Flips only between triangles whose normals differ by less than this, before and after.
    float flip_max_dihedral_deg = 20.0f;
    // Pull the relaxed vertices towards the cloud (otherwise the relaxation is purely tangential,
    // and the repair has neither its pull-back nor its Hausdorff guard).
    bool project = true;
    // Repair (step 2): at most this many rounds; 0 skips the repair. The rounds run only while
    // defects remain, so the limit changes only the repairs that need more. How many a repair
    // needs depends on the face numbering (a round treats the defective triangles in face order).
    int repair_max_rounds = 80;
    // The repair declines a mesh with more than this share of its triangles defective
    // (kRepairMaxDefectShare, nmesh/finish/repair.h); 1 tries every mesh.
    float repair_max_defect_share = kRepairMaxDefectShare;
    // An edge is folded when the normals of its two triangles differ by more than this.
    float fold_dihedral_deg = 120.0f;
    // Centroid fit, off by default: each round moves every vertex so that the centroids of its
    // triangles approach the mean of the cloud points that have them as nearest centroid (a damped
    // Lloyd step of the quantiser that DM(X,T) measures), then flips. It lowers DM(X,T) on the
    // cloud it is fitted to, but not the distance to other samples of the same surface: a fit to
    // the measure, not a better surface; hence off.
    int fit_rounds = 0;
    float fit_weight = 0.3f;
    // Wall-clock limit of the stage in seconds, 0 for none. The repair stops its rounds once the
    // limit is reached and keeps what it has achieved when that is an improvement
    // (repair_folds_and_intersections). reconstruct() sets none: with a limit in seconds the
    // mesh depends on the machine's speed.
    double seconds_limit = 0.0;
    // When neither repair leaves the mesh without crossing pairs, take a repair that removed
    // every defect but moved the surface off the cloud (finish.cpp). reconstruct() asks for it
    // only when no output retry is left: another path of the learning may give a valid mesh
    // without that loss.
    bool off_cloud_last_resort = true;
    // Cover (step 3): iterations of cover_uncovered_points (nmesh/finish/cover.h), which draws
    // vertices out to the scan points the surface leaves more than half an edge away (a tip the
    // learning left short or the repair took back); only on a mesh the repair left without
    // crossing pairs, and only with `project`. 0 skips it. Each iteration moves a vertex half way
    // to its uncovered points: 8 reach a horn tip left about an edge short (3 left the
    // triceratops's brow horns 1.4% of the diagonal short at 5,000 vertices; docs/algorithm.md).
    int cover_iterations = 8;
    // Surface fit (the last step): rounds of fit_surface (nmesh/finish/surface_fit.h), which moves the
    // vertices to where the triangles best match the scan points (a least-squares fit); only with
    // `project`. 0 skips it.
    int surface_fit_rounds = 4;
    // Vertex exchange (after the regularisation, only with `project`): passes of exchange_vertices
    // (nmesh/finish/exchange.h) on the mesh first fitted to the points (surface_fit_rounds rounds of
    // the fit). 0 skips it.
    int exchange_passes = 10;
    // Threads (0: the machine's cores) for the work that is independent vertex by vertex or point
    // by point: the relaxation's new positions and the surface fit's nearest triangles. The
    // results are combined in the same order for any count: the same mesh, bit for bit.
    std::uint32_t threads = 1;
    // The side of the surface each cloud point was taken from (one unit normal per point of the
    // stage's cloud, in its order; nmesh/learn/sample_sides.h), or null: the points' normals then
    // come from the learnt mesh (CloudSurface).
    const std::vector<Vec3>* point_sides = nullptr;
};

struct FinishReport {
    bool skipped_flat = false;  // a flat cloud: the stage did nothing
    std::uint64_t flips = 0;    // all flip passes together
    std::uint32_t relax_passes = 0;
    std::size_t intersecting_pairs_before = 0;  // at the start of the repair
    std::size_t folded_edges_before = 0;
    std::size_t intersecting_pairs_after = 0;  // at the end (as before when reverted)
    std::size_t folded_edges_after = 0;
    std::uint32_t repair_rounds = 0;
    bool repair_reverted = false;  // the repair did not succeed and was undone
    bool repair_declined = false;  // not tried: too many defects for a repair (kRepairMaxDefectShare)
    std::uint32_t cover_moves = 0;  // vertex moves of step 3 kept
    std::uint64_t exchanged = 0;    // collapse-split pairs of the vertex exchange
    bool exchange_undone = false;   // its repair failed, and the mesh before it was repaired instead
    SurfaceFitResult surface_fit;   // the last step
    // When the repair of the regularised mesh fails and that mesh has more intersecting pairs than
    // the learnt one, the stage falls back on the learnt mesh, repaired if possible.
    // Which mesh the stage returns: the regularised one (repaired if need be), the learnt one
    // repaired or as it was, or a repair that moved the surface off the cloud (the last resort).
    enum class Fallback { none, repaired_learnt_mesh, learnt_mesh, off_cloud_repair };
    Fallback fallback = Fallback::none;
    double seconds = 0.0;
};

// Runs the stage on `mesh` (positions in the same frame as `cloud`, which must not be empty),
// first building its face index when it has none (Mesh::build_faces); the passes below, used
// alone, need a mesh that has one.
// A flat cloud (is_flat, nmesh/geometry/flatness.h) is left alone: its mesh is two coinciding
// sheets, every triangle touching one of the other sheet, and no normal tells the sides apart.
// `cloud_index`: a nearest-point index over exactly the points of `cloud`, in the same order and
// frame (for instance the learning engine's, built over the same points through a
// PointTransform), which then is not built again; null: the stage builds its own.
// `progress` (may be empty) is called after each round with the share of the stage's round
// budget done (0 to 1), and with 1 at the end.
FinishReport finish_mesh(Mesh& mesh, const std::vector<Vec3>& cloud, const FinishOptions& options = {},
                         const PointGrid* cloud_index = nullptr,
                         const std::function<void(double fraction)>& progress = {});

}  // namespace nmesh
