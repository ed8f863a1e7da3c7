#include "nmesh/reconstruct.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "nmesh/spatial/cloud_sample.h"
#include "nmesh/error.h"
#include "nmesh/finish/finish.h"
#include "nmesh/geometry/flatness.h"
#include "nmesh/mesh/mesh_pieces.h"
#include "nmesh/finish/open_surface.h"
#include "nmesh/finish/view_sheet.h"
#include "nmesh/metrics.h"
#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/learn/neural_mesh.h"
#include "nmesh/learn/solid_start.h"
#include "nmesh/learn/twist_check.h"

namespace nmesh {

// One default for the finishing stage's rounds, whether it is run through reconstruct() or alone.
static_assert(FinishOptions{}.rounds == int(Parameters{}.finish_rounds), "two defaults for the finishing rounds");
static_assert(FinishOptions{}.fit_rounds == int(Parameters{}.fit_rounds), "two defaults for the centroid fit");

namespace {

// The cloud, centred on its bounding box and scaled by a power of two so that its diagonal is
// at most 1. A power-of-two scale is exact in floating point: a cloud and the same cloud scaled
// by 2^k normalise to the same bits, and so give the same mesh up to that scale. The normalised
// points are not stored: the engine applies the transform to each sample as it draws it.
struct Normalization {
    PointTransform transform;  // normalised = (p - center) * scale
    BoundingBox bounds;        // of the normalised points

    // `box`: the bounding box of the cloud.
    explicit Normalization(const BoundingBox& box) {
        transform.center = box.center();
        const double diag = box.diagonal();
        transform.scale = diag > 0.0 ? float(std::ldexp(1.0, -std::ilogb(diag) - 1)) : 1.0f;
        // The box of the normalised points, without another pass over them: each coordinate of
        // transform(p) = (p - center) * scale is a non-decreasing function of the same coordinate
        // of p (float subtraction and multiplication by a positive number round monotonically),
        // so the smallest and largest are the transforms of the input box's corners.
        bounds.extend(transform(box.min));
        bounds.extend(transform(box.max));
    }
    IndexedMesh to_input(IndexedMesh m) const {
        const float inv = 1.0f / transform.scale;
        for (Vec3& p : m.positions) p = p * inv + transform.center;
        return m;
    }
};

// Throws InputError unless the cloud has four affinely independent points (a tetrahedron's
// worth); a flat but not collinear cloud is accepted (the mesh is then a flattened closed
// surface). Returns the cloud's bounding box. Two passes over the cloud (the box; the point
// farthest from the first), then passes that stop at the first point off the line and at the
// fourth distinct point. A non-finite coordinate shows as an infinite box or a NaN distance.
BoundingBox require_reconstructible(PointSpan pts) {
    if (pts.size() < 4)
        throw InputError("the point cloud has " + std::to_string(pts.size()) +
                         " points; at least 4 distinct points are needed");
    const BoundingBox box = bounding_box(pts);
    const Vec3 a = pts[0];
    Vec3 b = a;
    float best = 0.0f;
    bool nan = false;
    for (const Vec3& p : pts) {
        const float d = squared_distance(a, p);
        nan = nan || d != d;
        if (d > best) best = d, b = p;
    }
    if (nan || !is_finite(box.min) || !is_finite(box.max))
        throw InputError("the point cloud holds a non-finite coordinate");
    if (best == 0.0f) throw InputError("all points of the cloud are identical");
    // A point off the line through a and b, the point farthest from a.
    const Vec3 dir = b - a;
    const float off_line = 1e-12f * squared_norm(dir) * squared_norm(dir);
    if (std::none_of(pts.begin(), pts.end(), [&](const Vec3& p) { return squared_norm(cross(p - a, dir)) > off_line; }))
        throw InputError("all points of the cloud lie on one line");
    // At least four distinct points.
    Vec3 distinct[4] = {a};
    int count = 1;
    for (const Vec3& p : pts) {
        bool seen = false;
        for (int i = 0; i < count; ++i) seen = seen || distinct[i] == p;
        if (!seen) distinct[count++] = p;
        if (count == 4) return box;
    }
    throw InputError("the point cloud has only " + std::to_string(count) + " distinct points; at least 4 are needed");
}

}  // namespace

double estimated_seconds_left(const Progress& p) {
    if (p.settling || p.target_vertices == 0 || p.vertices == 0) return -1.0;
    const double fraction = std::min(1.0, double(p.vertices) / double(p.target_vertices));
    const double loop = std::max(0.0, p.seconds - p.setup_seconds);
    return loop * (1.0 - fraction) / fraction;
}

namespace {

using Clock = std::chrono::steady_clock;

// The progress callback, asked about every 2^16 iterations and once when the learning ends; it
// remembers a cancellation.
class Reporter {
public:
    // `engine` is the engine of the moment (an output retry makes a new one).
    Reporter(const Callbacks& callbacks, const std::unique_ptr<NeuralMesh>& engine, std::uint32_t target,
             Clock::time_point start)
        : callbacks_(callbacks), engine_(engine), start_(start) {
        progress_.target_vertices = target;
        progress_.setup_seconds = elapsed();
    }
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
    double setup_seconds() const { return progress_.setup_seconds; }
    // After each iteration: false once the caller has cancelled.
    bool keep_going(bool settling) {
        constexpr std::uint64_t kReportMask = (1u << 16) - 1;  // a callback every 65,536 iterations
        if ((engine_->iteration() & kReportMask) == 0 && !report(settling)) cancelled_ = true;
        return !cancelled_;
    }
    bool report(bool settling) {
        if (!callbacks_.progress) return true;
        progress_.vertices = engine_->mesh().n_vertices();
        progress_.iterations = engine_->iteration();
        progress_.seconds = elapsed();
        progress_.settling = settling;
        progress_.finishing = false;  // learning (again, after an output retry)
        progress_.finish_fraction = 0.0;
        return callbacks_.progress(progress_);
    }
    // The finishing stage's progress, at most every 0.1 s and at its end.
    void report_finishing(double fraction) {
        if (!callbacks_.progress) return;
        const double now = elapsed();
        if (fraction < 1.0 && now - last_finish_report_ < 0.1) return;
        last_finish_report_ = now;
        progress_.seconds = now;
        progress_.finishing = true;
        progress_.finish_fraction = fraction;
        callbacks_.progress(progress_);
    }
    bool cancelled() const { return cancelled_; }

private:
    const Callbacks& callbacks_;
    const std::unique_ptr<NeuralMesh>& engine_;
    Clock::time_point start_;
    Progress progress_;
    bool cancelled_ = false;
    double last_finish_report_ = -1.0;
};

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
// A target of at most twice kLastCheckpoint vertices whose output still has crossing triangles
// or inward faces is learnt again from the checkpoint before it, on another stream, up to
// kOutputRetries times (reconstruct()).
constexpr std::uint32_t kOutputRetries = 3;

// The largest region of inward faces a checkpoint accepts at n vertices: the learning's
// scattered folds (the finishing stage removes them) are regions of one or a few faces, and
// about n / 400 at the checkpoints of the horse that the finishing stage repaired; a twist that
// stays is 6-8 faces at 256 vertices and doubles with the mesh.
std::size_t twist_tolerance(std::uint32_t n) { return std::max<std::size_t>(2, n / 256); }

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
// kStallPeriods periods in a row without one mean the mesh has stopped growing.
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
            throw InputError("the mesh stopped growing at " + std::to_string(at.largest) + " vertices (" +
                             std::to_string(engine.stats().removal_passes - at.largest_pass) +
                             " removal periods without a larger mesh, " + std::to_string(engine.iteration()) +
                             " iterations): " + std::to_string(cloud_size) + " points cannot carry " +
                             std::to_string(params.target_vertices) + " vertices with Cvs " +
                             std::to_string(params.cvs) + " and Cec " + std::to_string(params.cec) +
                             "; ask for at most about " + std::to_string(at.largest) + " vertices, or a larger Cec");
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

// The optional settling phase: steps 1-6 only, settle * n iterations.
void settle(NeuralMesh& engine, const Parameters& params, Reporter& reporter) {
    const std::uint64_t iterations = std::uint64_t(params.settle * engine.mesh().n_vertices());
    for (std::uint64_t i = 0; i < iterations; ++i) {
        engine.adapt();
        ++engine.stats().settle_iterations;
        if (!reporter.keep_going(true)) return;
    }
}

// The finishing stage (nmesh/finish/finish.h) on a copy of the learnt mesh, with the cloud the
// engine's nearest-point index holds (all of it, or the sample of
// Parameters::index_points_per_vertex, normalised), or a new index when the engine has none
// (it builds one only for the edge swap). Returns false, leaving `mesh` alone, should the stage
// ever fail to keep the vertex count.
// Choice: the stage runs without a time limit (FinishOptions::seconds_limit 0), so that the same
// input, parameters and seed give the same mesh on any machine: a limit in seconds would make the
// number of repair rounds, and so the mesh, depend on the machine's speed. Its rounds are bounded
// (FinishOptions::repair_max_rounds).
bool finish_stage(const Mesh& learnt, std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud,
                  const Normalization& norm, const Parameters& params, Reporter& reporter, Statistics& stats,
                  Mesh& mesh, double progress_from = 0.0, double progress_share = 1.0, bool repair = true,
                  bool last_resort = true) {
    if (!cloud_index) {
        cloud_index = index_cloud(cloud, norm.transform, norm.bounds, params);
        record_index(*cloud_index, stats);
    }
    mesh = learnt;
    FinishOptions options;
    options.rounds = int(params.finish_rounds);
    options.fit_rounds = int(params.fit_rounds);
    if (!repair) options.repair_max_rounds = 0;
    options.off_cloud_last_resort = last_resort;
    const FinishReport report =
        finish_mesh(mesh, cloud_index->indexed_points(), options, cloud_index.get(),
                    [&](double fraction) { reporter.report_finishing(progress_from + progress_share * fraction); });
    stats.repair_declined = stats.repair_declined || report.repair_declined;
    return mesh.n_vertices() == learnt.n_vertices();
}

// Topology open (nmesh/finish/open_surface.h): the cloud index of the learning, or a new one.
const PointGrid& open_index(std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud, const Normalization& norm,
                            const Parameters& params, Statistics& stats) {
    if (!cloud_index) {
        cloud_index = index_cloud(cloud, norm.transform, norm.bounds, params);
        record_index(*cloud_index, stats);
    }
    return *cloud_index;
}

// Topology open (nmesh/finish/open_surface.h): on a partial view, the view's sheet made again
// from the learnt vertices (nmesh/finish/view_sheet.h); then each piece finished (when `finish`), cut where the cloud has no data, and the
// pieces joined without the faces of crossing pairs. Sets result.mesh and the open counts, and
// stats.finished when every piece was finished. Unless `last` (no output retry left), crossings
// on a closed object's mesh are left for the output check, so that the learning tries another
// path from its checkpoint before any face is cut; a view's sheet is cut at once (its crossings
// come from the finishing stage's relaxation, not from the path the learning took).
void open_output(Mesh& learnt, bool finish, bool last, std::shared_ptr<PointGrid>& cloud_index, PointSpan cloud,
                 const Normalization& norm, const Parameters& params, Reporter& reporter, Result& result) {
    Statistics& stats = result.stats;
    learnt.build_faces();
    const PointGrid& index = open_index(cloud_index, cloud, norm, params, stats);
    double area = 0.0;
    for (std::uint32_t f = 0; f < learnt.face_capacity(); ++f) {
        if (learnt.is_removed(Face(f))) continue;
        const Halfedge h = learnt.halfedge(Face(f));
        const Vec3 a = learnt.position(learnt.from(h)), b = learnt.position(learnt.to(h));
        area += 0.5 * double(nmesh::norm(cross(b - a, learnt.position(learnt.to(learnt.next(h))) - a)));
    }
    // The spacing guess: the mesh's area shared among the points (twice the sheet's on a view).
    const CloudView view = view_cloud(index, float(std::sqrt(area / double(std::max<std::size_t>(index.size(), 1)))));
    OpenReport report;
    std::vector<Mesh> pieces;
    if (view.partial) {
        const IndexedMesh side = view_sheet(learnt, index, view, report);
        learnt = Mesh();
        for (const MeshPiece& p : split_pieces(side)) pieces.push_back(Mesh::from_indexed(p.mesh, true));
    } else {
        pieces.push_back(std::move(learnt));
    }
    std::size_t faces = 0, done = 0;
    for (const Mesh& p : pieces) faces += p.n_faces();
    stats.finished = finish;
    std::vector<IndexedMesh> shapes;
    for (Mesh& piece : pieces) {
        if (finish) {
            Mesh finished;
            const double from = double(done) / double(faces), share = double(piece.n_faces()) / double(faces);
            done += piece.n_faces();
            // A view's sheet without the repair: its few crossings are cut at the end instead
            // (the repair's rounds on them take seconds and then fall back on the sheet as it was).
            if (finish_stage(piece, cloud_index, cloud, norm, params, reporter, stats, finished, from, share, !view.partial,
                             last))
                piece = std::move(finished);
            else
                stats.finished = false;
        }
        piece.build_faces();
        shapes.push_back(piece.to_indexed());
    }
    if (view.partial) {
        // The finished sheet without the faces its relaxation turned against the view.
        const IndexedMesh sheet = cut_turned(join_pieces(shapes), index, view, report);
        pieces.clear();
        for (const MeshPiece& p : split_pieces(sheet)) pieces.push_back(Mesh::from_indexed(p.mesh, true));
    }
    const float typical = typical_edge(join_pieces(shapes));
    shapes.clear();
    for (const Mesh& piece : pieces) shapes.push_back(cut_unsupported(piece, index, view, typical, report));
    pieces.clear();
    std::uint32_t crossing = 0;
    result.mesh = last || view.partial ? cut_crossings(join_pieces(shapes), crossing) : join_pieces(shapes);
    report.removed_crossing += crossing;
    stats.layer_faces_removed = report.removed_layer;
    stats.open_faces_removed = report.removed_unsupported;
    stats.crossing_faces_removed = report.removed_crossing;
}

// Every closed output faces outward (its triangles reversed when the learning turned the whole
// surface inside out), and its validity is measured: crossing pairs and, for a closed one, inward
// faces; its genus and boundary loops are counted.
void check_output(Result& result) {
    const MeshTopology t = mesh_topology(result.mesh);
    result.stats.genus = t.genus;
    result.stats.boundary_loops = t.boundary_loops;
    if (t.closed) {
        result.stats.reoriented = orient_outward(result.mesh);
        result.stats.inward_faces = inward_faces(result.mesh, TriangleBvh(result.mesh));
    }
    result.stats.crossing_pairs = count_self_intersections(result.mesh);
}

}  // namespace

Result reconstruct(PointSpan cloud, const Parameters& params, const Callbacks& callbacks) {
    params.validate();
    const auto start = Clock::now();
    const Normalization norm(require_reconstructible(cloud));
    // The fold guard is off for a flat cloud: its closed mesh must fold flat, two coinciding sheets.
    Parameters learning = params;
    learning.fold_guard = params.fold_guard && !is_flat(cloud);
    // On the heap, so that it can be destroyed, and its memory freed, as soon as the learning ends.
    // Topology closed and open: from the solid's surface when the cloud walls a solid round
    // (solid_start.h), its genus kept (the handle search off: a handle the solid's offset closes
    // is narrower than a few point spacings); otherwise, and in sphere mode, from the
    // tetrahedron, with the handle search.
    SolidStart solid;
    if (params.topology != Topology::sphere && params.solid_start)
        solid = solid_start(cloud, norm.transform, params.target_vertices);
    const std::uint64_t start_vertices = solid.mesh ? solid.mesh->n_vertices() : 4;
    std::unique_ptr<NeuralMesh> engine =
        solid.mesh ? std::make_unique<NeuralMesh>(cloud, norm.bounds, learning, norm.transform, std::move(*solid.mesh))
                   : std::make_unique<NeuralMesh>(cloud, norm.bounds, learning, norm.transform);
    if (solid.mesh) engine->keep_genus();
    solid.mesh.reset();
    engine->set_profiling(callbacks.profile);
    Reporter reporter(callbacks, engine, params.target_vertices, start);

    Checkpoints checkpoints(*engine, params);
    // Output retries, for a target up to twice the last checkpoint (which is then at least half
    // the learning) and with the finishing stage (without it the learnt mesh is wanted as it is).
    // A larger target is not retried: its last checkpoint is most of the learning back, and the
    // defects left there come from before it (the eight at 10,000 vertices, seed 18: a spurious
    // handle made at 3,888 vertices).
    const std::uint32_t output_retries =
        checkpoints.on && params.finish && params.target_vertices <= 2 * kLastCheckpoint ? kOutputRetries : 0;
    Result result;
    double finish_seconds = 0.0;  // the finishing stage's time over the attempts
    for (std::uint32_t attempt = 0;; ++attempt) {
        learn_to_target(*engine, cloud.size(), params, callbacks, norm, reporter, checkpoints);
        if (!reporter.cancelled()) settle(*engine, params, reporter);
        const double learnt_at = reporter.elapsed();

        result = Result();
        result.cancelled = reporter.cancelled();
        result.stats = engine->stats();
        result.stats.solid_genus = solid.solid_genus;
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

        // No output retry left: the finishing stage may take its last resort.
        const bool last = attempt >= output_retries || !checkpoints.on || !checkpoints.last;
        if (open) {
            open_output(learnt, finish, last, cloud_index, cloud, norm, params, reporter, result);
        } else {
            Mesh finished;
            result.stats.finished = finish && finish_stage(learnt, cloud_index, cloud, norm, params, reporter,
                                                           result.stats, finished, 0.0, 1.0, true, last);
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
        check_output(result);
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

}  // namespace nmesh
