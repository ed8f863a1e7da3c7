// The finishing stage (nmesh/finish/finish.h). Choice beyond the paper, which stops when the mesh has
// its target size: the learnt mesh is regularised and its folds and self-intersections repaired;
// Parameters::finish = false switches the stage off and gives the paper's plain algorithm.
#include "nmesh/finish/finish.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "nmesh/finish/cover.h"
#include "nmesh/finish/exchange.h"
#include "nmesh/finish/mesh_queries.h"
#include "nmesh/geometry/flatness.h"

namespace nmesh {

using namespace finish_detail;

FinishReport finish_mesh(Mesh& mesh, const std::vector<Vec3>& cloud, const FinishOptions& options,
                         const PointGrid* cloud_index, const std::function<void(double fraction)>& progress) {
    const auto start = std::chrono::steady_clock::now();
    FinishReport report;
    mesh.build_faces();  // the learnt mesh comes without its face index (NeuralMesh::mesh)
    if (is_flat(cloud)) {
        report.skipped_flat = true;
        return report;
    }
    const Mesh learnt = options.repair_max_rounds > 0 ? mesh : Mesh();
    // The cloud's point normals come from the learnt mesh, before any pass.
    std::unique_ptr<CloudSurface> surface;
    if (options.project) surface = std::make_unique<CloudSurface>(cloud, mesh, cloud_index, options.point_sides);
    const CloudSurface* pull = surface.get();
    // Progress over the stage's round budget: the regularisation and fit rounds, then the repair's.
    const double budget = double(options.rounds + options.fit_rounds + std::max(options.repair_max_rounds, 0) +
                                 std::max(options.surface_fit_rounds, 0));
    double done = 0.0;
    const auto step = [&](double rounds) {
        done += rounds;
        if (progress && budget > 0.0) progress(std::min(1.0, done / budget));
    };
    const auto seconds_left = [&] {
        if (options.seconds_limit <= 0.0) return 0.0;
        const double used = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return std::max(1e-3, options.seconds_limit - used);  // > 0: a limit, however small
    };
    // The regularisation may use half of a time limit, the repair the rest: half of it for the
    // repair of the regularised mesh, the remainder for the fallback on the learnt one.
    const auto regularisation_over = [&] {
        return options.seconds_limit > 0.0 &&
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
                   0.5 * options.seconds_limit;
    };
    // Where the learning left the vertices on the scan (within kAnchorSupport of a mean edge of a
    // point): the relaxation keeps those places covered (relax_tangentially). A vertex the learning
    // left off the scan (a spike, the rim of a fold) has no anchor to keep.
    Anchors anchors;
    if (pull && options.rounds > 0) {
        anchors.at = mesh.positions();
        anchors.held.assign(mesh.vertex_capacity(), 0);
        const float support = kAnchorSupport * mean_edge_length(mesh);
        for (const Vertex v : alive_vertices(mesh))
            anchors.held[v.idx] = pull->index().nearest_squared_distance(mesh.position(v)) <= support * support;
        // Nor has a vertex within two rings of a folded edge: the relaxation is what untangles
        // the fold, and the repair starts from what it leaves.
        std::vector<std::uint8_t> near_fold(mesh.vertex_capacity(), 0);
        std::vector<Vertex> frontier, last;
        const auto reach = [&](Vertex v) {
            if (near_fold[v.idx]) return;
            near_fold[v.idx] = 1;
            anchors.held[v.idx] = 0;
            frontier.push_back(v);
        };
        for (const Edge e : find_folded_edges(mesh, options.fold_dihedral_deg)) {
            reach(mesh.from(Mesh::halfedge(e, 0)));
            reach(mesh.to(Mesh::halfedge(e, 0)));
        }
        for (int ring = 0; ring < 2; ++ring) {
            last.swap(frontier);
            frontier.clear();
            for (const Vertex v : last) mesh.for_each_outgoing_cw(v, [&](Halfedge h) { reach(mesh.to(h)); });
        }
    }
    for (int r = 0; r < options.rounds && !regularisation_over(); ++r) {
        report.flips += flip_to_delaunay(mesh, options.flip_max_dihedral_deg);
        relax_tangentially(mesh, pull, pull ? &anchors : nullptr, options.threads);
        ++report.relax_passes;
        step(1);
    }
    // Step 2, the vertices exchanged towards where the shape bends (exchange.h), measured on the
    // mesh fitted to the points (the learnt vertices sit inside a bend; fitted, what is left of a
    // face's offset from its points is its chord).
    std::optional<Mesh> unexchanged;  // the mesh before the exchange (and its fit), for the repair's fallback
    if (pull && options.exchange_passes > 0 && !regularisation_over()) {
        unexchanged = mesh;
        if (options.surface_fit_rounds > 0) {
            SurfaceFitOptions fit;
            fit.rounds = options.surface_fit_rounds;
            fit.fold_dihedral_deg = options.fold_dihedral_deg;
            fit.threads = options.threads;
            fit_surface(mesh, *pull, fit);
        }
        report.exchanged =
            exchange_vertices(mesh, *pull, options.exchange_passes, options.flip_max_dihedral_deg).exchanged;
    }
    // The centroid fit's rounds, then a last flip pass (on the exchange's fallback too).
    const auto fit_centroid_rounds = [&](Mesh& m, bool count) {
        for (int r = 0; r < options.fit_rounds; ++r) {
            fit_centroids(m, cloud, options.fit_weight);
            report.flips += flip_to_delaunay(m, options.flip_max_dihedral_deg);
            if (count) step(1);
        }
        if (options.rounds > 0 || options.fit_rounds > 0)
            report.flips += flip_to_delaunay(m, options.flip_max_dihedral_deg);
    };
    fit_centroid_rounds(mesh, true);
    if (options.repair_max_rounds > 0) {
        int last_rounds = 0;
        const auto on_round = [&](int rounds) {
            step(0.5 * double(rounds - last_rounds));  // two repairs may share the budget
            last_rounds = rounds;
        };
        RepairResult r = repair_folds_and_intersections(mesh, options.repair_max_rounds, options.fold_dihedral_deg,
                                                        pull, 0.5 * seconds_left(), on_round,
                                                        options.repair_max_defect_share, options.threads);
        report.repair_rounds = r.rounds;
        // When the repair leaves intersecting pairs, it is tried on the learnt mesh as well, and
        // the mesh with fewer of them is kept (the regularised one on a tie): the stage never
        // returns more of them than the learnt mesh had. Folded edges alone do not call for it:
        // with no pair left the regularised mesh wins any tie, so the second repair could only
        // cost time (the knot at 10,000 vertices, seed 18, the same mesh: the whole run 0.60 times
        // as long, docs/performance.md).
        std::optional<Mesh> off_cloud = std::move(r.off_cloud);
        float off_cloud_rise = r.off_cloud_rise;
        // Another mesh repaired in place of this one: its off-cloud repair kept if it rose less, and
        // the mesh itself taken when it is left with fewer crossing pairs (this one on a tie) or
        // when `taken_anyway`.
        const auto repair_instead = [&](Mesh alternative, double seconds, bool taken_anyway) {
            last_rounds = 0;
            RepairResult ra = repair_folds_and_intersections(alternative, options.repair_max_rounds,
                                                             options.fold_dihedral_deg, pull, seconds, on_round,
                                                             options.repair_max_defect_share, options.threads);
            report.repair_rounds += ra.rounds;
            if (ra.off_cloud && (!off_cloud || ra.off_cloud_rise < off_cloud_rise)) {
                off_cloud = std::move(ra.off_cloud);
                off_cloud_rise = ra.off_cloud_rise;
            }
            if (!taken_anyway && !(ra.intersecting_pairs < r.intersecting_pairs)) return false;
            mesh = std::move(alternative);
            r = std::move(ra);
            return true;
        };
        // A repair that fails after the exchange, or is declined, is tried on the mesh before it,
        // as though there had been no exchange (a collapse can bring a triangle through a nearby
        // sheet, which the repair is not always able to take out; on a thin limb a chain of them
        // can pass the repair's defect share: the horse at 1,000 vertices, seed 2, 191 crossing
        // pairs against 137 before the exchange, declined). The mesh before it is taken whatever
        // its count, so that the exchange never leaves the stage with more pairs than without it.
        if (r.intersecting_pairs > 0 && unexchanged) {
            fit_centroid_rounds(*unexchanged, false);
            repair_instead(std::move(*unexchanged), 0.5 * seconds_left(), true);
            report.exchange_undone = true;
        }
        // The repair's report is that of the regularised mesh which went on (after an undone
        // exchange, the mesh before it), whatever the learnt mesh's fallback below gives.
        report.intersecting_pairs_before = r.intersecting_pairs_before;
        report.folded_edges_before = r.folded_edges_before;
        report.repair_reverted = r.reverted;
        report.repair_declined = r.declined;
        // A mesh too defective to repair (kRepairMaxDefectShare) is not tried again as learnt: on
        // the single view the learnt mesh has more defects than the regularised one, not fewer.
        if (r.intersecting_pairs > 0 && !r.declined && (options.rounds > 0 || options.fit_rounds > 0) &&
            repair_instead(learnt, seconds_left(), false))
            report.fallback =
                r.reverted ? FinishReport::Fallback::learnt_mesh : FinishReport::Fallback::repaired_learnt_mesh;
        // The last resort, when neither mesh came out without crossing pairs: a repair that
        // removed every defect but moved the surface off the cloud (by less than the two mean
        // edges at which a repair is abandoned), the one that moved it least. A valid surface
        // comes first; the fidelity lost is local (the horse at 30,000 vertices, seed 19: 22
        // crossing pairs left otherwise, a rise of 0.55 mean edges taken; docs/algorithm.md).
        if (r.intersecting_pairs > 0 && off_cloud && options.off_cloud_last_resort) {
            mesh = std::move(*off_cloud);
            r.intersecting_pairs = 0;
            r.folded_edges = 0;
            report.fallback = FinishReport::Fallback::off_cloud_repair;
        }
        report.intersecting_pairs_after = r.intersecting_pairs;
        report.folded_edges_after = r.folded_edges;
        // Step 3, on a mesh the repair left without crossing pairs. A fold it left steeper than the
        // cover's limit (above the repair's) stays as it is: the corners of its triangles do not
        // move (one such fold at the triceratops's tail tip held back the cover of its horns).
        if (pull && report.intersecting_pairs_after == 0 && options.fold_dihedral_deg <= kCoverFoldDeg) {
            const std::vector<Edge> steep =
                report.folded_edges_after == 0 ? std::vector<Edge>() : find_folded_edges(mesh, kCoverFoldDeg);
            report.cover_moves = cover_uncovered_points(mesh, *pull, options.cover_iterations, 0.5f, steep).moves;
        }
    }
    // The surface fit, last, on whatever the repair left: the corners of a defect left stay, and no move that
    // makes a new one is kept. Known clean when the repair left none at its fold limit.
    if (pull && options.surface_fit_rounds > 0) {
        SurfaceFitOptions fit;
        fit.rounds = options.surface_fit_rounds;
        fit.fold_dihedral_deg = options.fold_dihedral_deg;
        fit.threads = options.threads;
        fit.known_clean =
            options.repair_max_rounds > 0 && report.intersecting_pairs_after == 0 && report.folded_edges_after == 0;
        report.surface_fit = fit_surface(mesh, *pull, fit);
        step(options.surface_fit_rounds);
    }
    if (progress) progress(1.0);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace nmesh
