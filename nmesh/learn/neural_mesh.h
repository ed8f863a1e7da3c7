// nmesh/neural_mesh.h — the learning engine: the Neural Meshes algorithm (steps 1-9 of section 3
// of the Neural Meshes ES paper) and the edge swap of section 4, on the parts built for it:
// the half-edge Mesh, the VertexGrid (winner search), the ActivityIndex (signal counters), the
// RingCache (the one-rings the smoothing reads) and, for the edge swap, a PointGrid over the cloud
// (or over its sample, Parameters::index_points_per_vertex).
//
// Most callers want reconstruct() (nmesh/reconstruct.h), which normalises the cloud, runs this
// engine and maps the mesh back. The engine is public so tests can drive it step by step.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "nmesh/learn/activity_index.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/spatial/point_transform.h"
#include "nmesh/util/random.h"
#include "nmesh/parameters.h"
#include "nmesh/statistics.h"
#include "nmesh/learn/ring_cache.h"
#include "nmesh/spatial/vertex_grid.h"

namespace nmesh {

class NeuralMesh {
public:
    // The engine reserves room for the target plus this margin in its mesh, grid, activity index
    // and ring cache, so the largest target is the mesh's limit less the margin
    // (Parameters::validate refuses more).
    static constexpr std::uint32_t kReserveSlack = 16;
    static constexpr std::uint32_t kMaxTargetVertices = Mesh::kMaxVertices - kReserveSlack;
    // The fold guard of step 3 (Parameters::fold_guard) runs while the mesh has fewer vertices
    // than this: the folds that grow into inside-out parts start while the mesh is coarse against
    // the shape, and the guard costs a sixth more instructions per iteration. Choice: 4096, which
    // left the same runs defective as the guard at every size (docs/algorithm.md).
    static constexpr std::uint32_t kFoldGuardBelow = 4096;
    // Parameters::adaptivity weighs the signals from this many vertices on (the size of the first
    // topology search), once the coarse mesh has settled on the shape.
    static constexpr std::uint32_t kAdaptiveFrom = 512;

    // The engine learns `transform(p)` for the points p of `points`, which must outlive it.
    // The transformed points should be normalised (reconstruct() centres them and scales them
    // into a box of diagonal at most 1), finite, and `bounds` is their exact bounding box (the
    // nearest-point index is laid out on it). `params` must be valid.
    NeuralMesh(PointSpan points, const BoundingBox& bounds, const Parameters& params,
               const PointTransform& transform = {});
    // The same engine starting from `start` (a closed mesh in the transformed space, with
    // faces or not) instead of the tetrahedron: topology closed's start from the solid's surface
    // (solid_start.h).
    NeuralMesh(PointSpan points, const BoundingBox& bounds, const Parameters& params, const PointTransform& transform,
               Mesh start);

    // One iteration of steps 1-6, followed by step 7 or 8 when it is due.
    void iterate();
    // Steps 1-6 only (the settling phase).
    void adapt();
    // Steps 2-6 for a given sample x instead of a random one (for tests).
    void adapt_to(const Vec3& x);
    // Step 7: a vertex split of the most active vertex.
    void split_most_active();
    // Step 8: every inactive vertex removed by an edge collapse (and, with edge_swap, step 1-3 of
    // the edge swap around each collapse's remaining vertex).
    void remove_inactive();
    // Section 4: the edge swap around vertex v.
    void swap_around(Vertex v);
    // Beyond the paper (Parameters::topology closed and open): the topology searches. First each
    // part of the mesh that reaches its data only across a thin neck of unsupported faces is
    // taken away by edge collapses, for the learning to grow it again from the body
    // (nmesh/learn/bridges.h); then a handle is made for each pair of membranes that spans a
    // through-hole of the cloud (nmesh/learn/handles.h). The vertices removed leave the grid and
    // the activity index too, and the rings that changed are refreshed. Returns the handles made.
    // O(n log n), plus O(P) when a bridge is found.
    std::uint32_t learn_topology();
    // Parameters::adaptivity applies from here on: the start (the solid's surface or its genus-0
    // core, solid_start.h) has the shape's parts, which a growth from the tetrahedron finds by the
    // density of the samples alone.
    void start_has_shape() { adaptive_ = params_.adaptivity > 0.0; }
    // The handle search off from here on (the bridges stay): for a start whose genus the cloud's
    // solid already gave (solid_start.h), where a search would only add handles.
    void keep_genus() { search_handles_ = false; }
    // Beyond the paper: the side of the surface each point was taken from, a unit normal per
    // point (in the transformed space) or 0 where it is not known (sample_sides.h). From here on a
    // sample whose winner's fan faces away from its side is not learnt (Statistics::side_skips):
    // on a part thinner than an edge the nearest vertex may lie on the other sheet, and a sample
    // that pulls it there drags the two sheets through each other. `sides` (one per point) must
    // outlive the engine; null turns the rule off.
    void set_sample_sides(const Vec3* sides) { sides_ = sides; }
    // Caches the rings of vertices with at most n neighbours only (RingCache::set_limit); the
    // others are read from the half-edge mesh. The results are the same bits either way; for
    // tests of both paths. O(n).
    void limit_ring_cache(std::uint32_t n);
    // adapt() looks one sample ahead from n vertices on (default 65,536). The results are the
    // same bits either way; for tests of both paths.
    void look_ahead_from(std::uint32_t n) { lookahead_from_ = n; }
    // Time each phase into Statistics::seconds_* from now on (costs a clock read per phase).
    void set_profiling(bool on) { profiling_ = on; }

    // The mesh as learnt so far. It has no face index (Mesh::has_faces): Mesh::build_faces() on
    // a copy, or on the mesh taken out, gives one.
    const Mesh& mesh() const { return mesh_; }
    // Moves the mesh out, for when the learning is over: the engine is then only fit to be
    // destroyed (which frees its grid, activity index, ring cache and cloud index before the
    // caller builds more from the mesh).
    Mesh take_mesh() { return std::move(mesh_); }
    // Moves the nearest-point index over the (transformed) cloud or its sample out (index_cloud),
    // or null when the engine has none (it builds one only for the edge swap); the same
    // conditions as take_mesh().
    std::shared_ptr<PointGrid> take_cloud_index() { return std::move(cloud_index_); }
    // Draws the samples from here on from a new random stream, derived from the seed and
    // `stream` (for the learning's checkpoints: a retry from a checkpoint takes another path).
    void reseed(std::uint64_t stream);
    // Gives back the room the engine keeps for the target's vertices in its grid and activity
    // index, so that a copy kept as a checkpoint costs memory for the vertices it has, not for
    // the target. A checkpoint assigned back to the engine finds the room still there (vector
    // assignment keeps the capacity); reserve_target() makes it again in another copy. O(n).
    void compact();
    // Makes room for the target's vertices (and kReserveSlack more) in the mesh, grid, activity
    // index and ring cache, so that the learning allocates nothing more (the constructor does it).
    void reserve_target();
    const VertexGrid& grid() const { return grid_; }
    const ActivityIndex& activity() const { return activity_; }
    const RingCache& rings() const { return rings_; }
    const Statistics& stats() const { return stats_; }
    Statistics& stats() { return stats_; }
    std::uint64_t iteration() const { return iteration_; }

    // Checks that the grid and the activity index hold exactly the mesh's alive vertices at
    // their positions and that the ring cache matches the mesh; returns an empty string or the
    // first mismatch. O(n); for tests.
    std::string check_consistency() const;

private:
    Vec3 next_sample();
    void move_winner(Vertex w, const Vec3& x, const std::uint32_t* ring, std::uint32_t k);
    Vec3 guard_fold(const Vec3& p, const Vec3& q, const std::uint32_t* ring, std::uint32_t k);
    void prefetch_neighbourhood(const std::uint32_t* ring, std::uint32_t k) const;
    void smooth_neighbourhood(const std::uint32_t* ring, std::uint32_t k, bool prefetched);
    void update(Vertex w, const Vec3& x, const std::uint32_t* ring, std::uint32_t k, bool prefetched);
    const std::uint32_t* ring_of(Vertex v, std::vector<std::uint32_t>& scratch, std::uint32_t& count);
    const std::uint32_t* walk_ring(Vertex v, std::vector<std::uint32_t>& scratch, std::uint32_t& count);
    float face_deviation(Halfedge h) const;
    float edge_deviation(Halfedge h) const;
    void set_position(Vertex v, const Vec3& p);
    void adapt_to(const Vec3& x, bool sampled);
    void look_ahead();
    bool faces_side(Vertex w, const Vec3& side, const std::uint32_t* ring, std::uint32_t k) const;
    std::uint32_t early_winner(const Vec3& x) const;

    PointSpan points_;
    PointTransform transform_;
    Parameters params_;
    Mesh mesh_;
    VertexGrid grid_;
    ActivityIndex activity_;
    RingCache rings_;
    // Eq. (9); built only for the edge swap and the handle search. Shared by the copies of the
    // engine (a copy is a checkpoint to go back to, see reconstruct()): the learning only reads it.
    std::shared_ptr<PointGrid> cloud_index_;
    Random rng_;
    Vec3 ahead_[2];                  // the next two samples, normalised
    std::uint32_t ahead_ids_[2] = {};  // their indices in the cloud
    std::uint32_t sample_id_ = 0;      // the index of the sample next_sample() returned last
    const Vec3* sides_ = nullptr;      // set_sample_sides
    bool adaptive_ = false;            // keep_genus with Parameters::adaptivity above 0
    float mean_d2_ = 0.0f;             // Parameters::adaptivity: the running mean of the squared
                                       // winner distances, over about the last 1 / kMeanRate
    static constexpr float kMeanRate = 1.0f / 1024.0f;
    std::uint32_t ahead_index_ = 0;  // the index of the one after them, drawn in advance
    std::uint64_t ahead_cell_ = 0;   // ahead_[1]'s grid cell (VertexGrid::prefetch_query)
    // From this many vertices on, where the mesh no longer fits in the cache, each iteration
    // looks one sample ahead (look_ahead; docs/performance.md has the measurements). The results
    // are the same bit for bit either way.
    std::uint32_t lookahead_from_ = 65536;

    // The look-ahead winner search of large meshes (look_ahead): the next sample's nearest
    // vertex found before this iteration moves anything, its squared distance then, and the
    // vertices this iteration moved (the winner and its ring).
    bool early_valid_ = false;
    bool search_handles_ = true;  // learn_topology() runs the handle search (keep_genus())
    std::uint32_t early_ = 0;
    float early_d2_ = 0.0f;
    std::uint32_t n_moved_ = 0;
    std::uint32_t moved_[RingCache::kCapacity + 1] = {};
    Statistics stats_;
    bool profiling_ = false;
    double swap_seconds_before_ = 0.0;  // stats_.seconds_swap at the end of the last step 8
    std::uint64_t iteration_ = 0;
    std::uint64_t next_removal_ = 0;  // iteration of the next step 8
    std::uint64_t period_start_ = 0;  // activity mark at the start of the current step-8 period
    // Scratch space reused across iterations (no allocation in steady state).
    std::vector<std::uint32_t> ring_;  // the ring of a vertex not in the ring cache
    std::vector<std::uint32_t> ring2_;
    std::vector<Vec3> updated_;  // step 4's new positions
    std::vector<std::uint32_t> inactive_;
    std::vector<Halfedge> swap_ring_;
    std::vector<float> swap_dm_;
};

}  // namespace nmesh
