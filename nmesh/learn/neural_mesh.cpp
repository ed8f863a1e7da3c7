// The Neural Meshes learning loop, step by step as section 3 of the Neural Meshes ES paper lists
// it, plus the edge swap of section 4. Where the papers leave a choice open, the choice is named
// "Choice:" here and listed in docs/algorithm.md.
#include "nmesh/learn/neural_mesh.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <sstream>

#include "nmesh/learn/bridges.h"
#include "nmesh/learn/handles.h"
#include "nmesh/spatial/cloud_sample.h"
#include "nmesh/util/float4.h"
#include "nmesh/util/prefetch.h"

namespace nmesh {
namespace {

// Adds the wall time of its scope to *slot; does nothing (reads no clock) when slot is null, as
// it is unless profiling is on (NeuralMesh::set_profiling).
class PhaseTimer {
public:
    using Clock = std::chrono::steady_clock;
    explicit PhaseTimer(double* slot) : slot_(slot) {
        if (slot_) start_ = Clock::now();
    }
    ~PhaseTimer() {
        if (slot_) *slot_ += std::chrono::duration<double>(Clock::now() - start_).count();
    }
    PhaseTimer(const PhaseTimer&) = delete;
    PhaseTimer& operator=(const PhaseTimer&) = delete;

private:
    double* slot_;
    Clock::time_point start_;
};

}  // namespace

// Choice: the initial tetrahedron is regular, centred on the cloud's bounding box, with a
// circumradius of a quarter of the box's diagonal: inside the data for a closed scan, and large
// enough that all four vertices win signals from the start.
NeuralMesh::NeuralMesh(PointSpan points, const BoundingBox& bounds, const Parameters& params,
                       const PointTransform& transform)
    : NeuralMesh(points, bounds, params, transform,
                 Mesh::tetrahedron(bounds.center(), float(bounds.diagonal() * 0.25))) {}

NeuralMesh::NeuralMesh(PointSpan points, const BoundingBox& bounds, const Parameters& params,
                       const PointTransform& transform, Mesh start)
    : points_(points),
      transform_(transform),
      params_(params),
      grid_(bounds),
      activity_(params.alpha),
      rng_(params.seed) {
    mesh_ = std::move(start);
    // The loop names no faces (the swap finds a triangle by its half-edges), so the mesh keeps
    // no face index while it learns: 32 of its 96 bytes per vertex (Mesh::drop_faces).
    if (mesh_.has_faces()) mesh_.drop_faces();
    reserve_target();
    for (std::uint32_t v = 0; v < mesh_.vertex_capacity(); ++v) {
        if (mesh_.is_removed(Vertex(v))) continue;
        grid_.insert(v, mesh_.position(Vertex(v)));
        activity_.add(v, 0.0);
    }
    if (params_.edge_swap || params_.topology != Topology::sphere) {
        // Eq. (9) against the cloud, or against the stratified sample that stands for a cloud
        // much denser than the mesh (Parameters::index_points_per_vertex); the handle search
        // measures against it too.
        cloud_index_ = index_cloud(points_, transform_, bounds, params_);
        record_index(*cloud_index_, stats_);
    }
    next_removal_ = std::uint64_t(params_.cec) * mesh_.n_vertices();
    for (int i = 0; i < 2; ++i) {
        ahead_ids_[i] = rng_.below(std::uint32_t(points_.size()));
        ahead_[i] = transform_(points_[ahead_ids_[i]]);
    }
    ahead_index_ = rng_.below(std::uint32_t(points_.size()));
    ahead_cell_ = grid_.prefetch_query(ahead_[1]);
    ring_.reserve(64);
    ring2_.reserve(64);
    updated_.resize(16);
    for (std::uint32_t v = 0; v < mesh_.vertex_capacity(); ++v)
        if (!mesh_.is_removed(Vertex(v))) rings_.refresh(mesh_, Vertex(v));
    swap_ring_.reserve(64);
    swap_dm_.reserve(64);
}

inline void NeuralMesh::set_position(Vertex v, const Vec3& p) {
    mesh_.set_position(v, p);
    grid_.move(v.idx, p);
}

// Step 1: a random sample x from the cloud.
// The samples are drawn three iterations ahead (the sequence is the same; only the time of the
// draw moves), and what the winner search will read is fetched in stages, each from memory the
// previous stage brought into the cache: the sample three ahead from the cloud, the grid cell
// slot of the one two ahead, and the vertex block of the next one's cell.
Vec3 NeuralMesh::next_sample() {
    const Vec3 x = ahead_[0];
    sample_id_ = ahead_ids_[0];
    ahead_[0] = ahead_[1];
    ahead_ids_[0] = ahead_ids_[1];
    ahead_[1] = transform_(points_[ahead_index_]);  // each sample is normalised once
    ahead_ids_[1] = ahead_index_;
    ahead_index_ = rng_.below(std::uint32_t(points_.size()));
    prefetch_for_read(&points_[ahead_index_]);
    grid_.prefetch_cell(ahead_cell_);  // ahead_[0]'s cell, found when it was ahead_[1]
    ahead_cell_ = grid_.prefetch_query(ahead_[1]);
    return x;
}

// Step 3, eq. (2): v'_w = (1 - alpha_w) v_w + alpha_w x, unless it folds w's fan (guard_fold).
// `ring` holds w's k neighbours (ring_of).
void NeuralMesh::move_winner(Vertex w, const Vec3& x, const std::uint32_t* ring, std::uint32_t k) {
    const float aw = float(params_.alpha_w);
    const Vec3 p = mesh_.position(w);
    const Vec3 q = p * (1.0f - aw) + x * aw;
    set_position(w, params_.fold_guard && mesh_.n_vertices() < kFoldGuardBelow ? guard_fold(p, q, ring, k) : q);
}

// v's neighbours, clockwise: from the ring cache, or walked on the mesh into `scratch` when v has
// more neighbours than the cache holds (then `scratch` grows to the largest valence seen).
inline const std::uint32_t* NeuralMesh::ring_of(Vertex v, std::vector<std::uint32_t>& scratch, std::uint32_t& count) {
    count = rings_.count(v);
    return count != 0 ? rings_.neighbours(v) : walk_ring(v, scratch, count);
}

const std::uint32_t* NeuralMesh::walk_ring(Vertex v, std::vector<std::uint32_t>& scratch, std::uint32_t& count) {
    scratch.clear();
    mesh_.for_each_outgoing_cw(v, [&](Halfedge h) { scratch.push_back(mesh_.to(h).idx); });
    count = std::uint32_t(scratch.size());
    return scratch.data();
}

// Starts loading what the smoothing of a vertex with these k neighbours reads first: their ring
// lines, positions and grid slots, all at once, so that the cache misses of a large mesh overlap
// instead of following one another.
void NeuralMesh::prefetch_neighbourhood(const std::uint32_t* ring, std::uint32_t k) const {
    const Vec3* pos = mesh_.positions().data();
    for (std::uint32_t i = 0; i < k; ++i) {
        rings_.prefetch(Vertex(ring[i]));
        prefetch_for_read(&pos[ring[i]]);
        grid_.prefetch_move(ring[i]);
    }
}

// Step 4, eq. (3)-(5): tangential Laplacian smoothing of the winner's one-ring, its k neighbours in
// `ring`.
// v'_n = v_n + alpha_n L_t,  L_t = L - (L . n) n,  L = mean over the ring of (v_k - v_n),
// with n the vertex's approximated (area-weighted) normal.
// Choice: all neighbours are moved from the positions they had before this step (a Jacobi
// update), so the result does not depend on the order of the ring.
void NeuralMesh::smooth_neighbourhood(const std::uint32_t* ring, std::uint32_t k, bool prefetched) {
    using namespace float4;  // F4, load, yzx, cross_zxy, dot2, to_vec3
    const float an = float(params_.alpha_n);
    if (an == 0.0f) return;
    if (updated_.size() < k) updated_.resize(k);  // grows to the largest valence seen, then never
    Vec3* updated = updated_.data();
    const Vec3* pos = mesh_.positions().data();  // read only until every new position is known
    // What this step reads first is known from w's ring: ask for all of it at once, unless the
    // previous iteration already did, having looked ahead to w (adapt_ahead). (Asking for the
    // positions of the ring's own neighbours as well, once the lines arrive, cost more than it
    // saved: 13% slower at 30,000 vertices, 7-25% at 100,000, no clear difference at 300,000.)
    if (!prefetched) prefetch_neighbourhood(ring, k);
    for (std::uint32_t i = 0; i < k; ++i) {
        const std::uint32_t v = ring[i];
        const F4 p = load(pos[v]);
        // One pass over v's own ring gives both the Laplacian (eq. 5) and the area-weighted normal
        // (the sum of the cross products of consecutive ring edges, closing the ring). Both sums
        // go round the ring in the order it is stored, from wherever it starts: the ring includes
        // w, whose position step 3 has already updated.
        std::uint32_t m = 0;
        const std::uint32_t* r = ring_of(Vertex(v), ring2_, m);
        // The cross products are summed with their lanes rotated (float4::cross_zxy), and the sum
        // rotated back once: the same bits as summing cross().
        const F4 first = load(pos[r[0]]) - p, rfirst = yzx(first);
        F4 sum = first, rotated = F4{}, prev = first, rprev = rfirst;
        for (std::uint32_t j = 1; j < m; ++j) {
            const F4 a = load(pos[r[j]]) - p, ra = yzx(a);
            sum = sum + a;
            rotated = rotated + cross_zxy(a, ra, prev, rprev);
            prev = a;
            rprev = ra;
        }
        rotated = rotated + cross_zxy(first, rfirst, prev, rprev);  // closes the ring
        const F4 normal = yzx(rotated);
        const F4 laplacian = sum * (1.0f / float(m));  // eq. (5)
        float nn, ln;                                  // n . n and L . n
        dot2(normal, laplacian, normal, nn, ln);
        const F4 tangential = nn > 0.0f ? laplacian - normal * (ln / nn) : laplacian;  // eq. (4)
        updated[i] = to_vec3(p + tangential * an);                                     // eq. (3)
    }
    for (std::uint32_t i = 0; i < k; ++i) set_position(Vertex(ring[i]), updated[i]);
}

// Steps 3-6 for the winner w of sample x. `ring` holds w's k neighbours (ring_of), whose
// neighbourhood is already being fetched when `prefetched`.
void NeuralMesh::update(Vertex w, const Vec3& x, const std::uint32_t* ring, std::uint32_t k, bool prefetched) {
    move_winner(w, x, ring, k);                 // step 3
    smooth_neighbourhood(ring, k, prefetched);  // step 4
    if (adaptive_) {
        // Beyond the paper (Parameters::adaptivity, from a start that has the shape: start_has_shape):
        // the signal weighs the winner's distance to the sample (after step 3) against its
        // running mean, so that the vertices nearest to samples the mesh does not reach yet (a
        // tip, a tail, a sharp bend) split sooner; from kAdaptiveFrom vertices on.
        const float d2 = squared_distance(x, mesh_.position(w));
        mean_d2_ += (d2 - mean_d2_) * kMeanRate;
        const double error = mesh_.n_vertices() >= kAdaptiveFrom ? double(d2 / std::max(mean_d2_, 1e-30f)) : 0.0;
        activity_.signal(w.idx, 1.0 + params_.adaptivity * error);  // step 5, eq. (6), weighted
    } else {
        activity_.signal(w.idx);  // step 5, eq. (6): tau_w += 1
    }
    activity_.decay();                          // step 6, eq. (7): tau_v *= alpha for all v
    ++iteration_;
    ++stats_.iterations;
}

// The nearest vertex to x, the sample the previous iteration looked ahead to: its early answer
// still holds for every vertex that iteration did not move (their distances are unchanged and
// were not smaller), so only the moved ones need comparing; if the early answer itself moved
// away from x, anything could now be nearer, and the grid is asked again.
std::uint32_t NeuralMesh::early_winner(const Vec3& x) const {
    const Vec3* pos = mesh_.positions().data();
    const float early_d2 = squared_distance(x, pos[early_]);
    std::uint64_t best = VertexGrid::rank(early_d2, early_);
    bool early_moved = false;
    for (std::uint32_t i = 0; i < n_moved_; ++i) {
        early_moved |= moved_[i] == early_;
        const std::uint64_t r = VertexGrid::rank(squared_distance(x, pos[moved_[i]]), moved_[i]);
        best = r < best ? r : best;
    }
    if (early_moved && early_d2 > early_d2_) return grid_.nearest(x);
    return std::uint32_t(best);
}

// Steps 1-6 for a random sample.
void NeuralMesh::adapt() { adapt_to(next_sample(), true); }

void NeuralMesh::adapt_to(const Vec3& x) { adapt_to(x, false); }

// Steps 2-6 for sample x. `sampled`: x is the sample next_sample() drew, so the winner the previous
// iteration found for it in advance can be used (early_winner()). From lookahead_from_ vertices
// on, this iteration does the same for the next sample: its winner is found before this
// iteration's smoothing, and its neighbourhood fetched while the smoothing runs, instead of at the
// start of the next iteration. The winners are the same either way; only the time of the memory
// accesses changes.
void NeuralMesh::adapt_to(const Vec3& x, bool sampled) {
    const bool was_early = sampled && early_valid_;
    Vertex w;
    {
        PhaseTimer timer(profiling_ ? &stats_.seconds_winner : nullptr);
        w = Vertex(was_early ? early_winner(x) : grid_.nearest(x));  // step 2, eq. (1)
    }
    PhaseTimer timer(profiling_ ? &stats_.seconds_update : nullptr);
    const bool prefetched = was_early && w.idx == early_;
    const bool ahead = mesh_.n_vertices() >= lookahead_from_;
    if (ahead) look_ahead();
    // w's record is needed at step 5: let it load during steps 3-4 (a looked-ahead winner's was
    // asked for a whole iteration ago).
    if (!prefetched) activity_.prefetch(w.idx);
    std::uint32_t k = 0;
    const std::uint32_t* ring = ring_of(w, ring_, k);
    if (sides_ != nullptr && sampled && !faces_side(w, sides_[sample_id_], ring, k)) {
        // A sample from the other side of a thin part: it is not this sheet's to learn.
        ++stats_.side_skips;
        activity_.decay();  // step 6: the counters still age
        ++iteration_;
        ++stats_.iterations;
        early_valid_ = false;
        return;
    }
    update(w, x, ring, k, prefetched);
    early_valid_ = ahead && k <= RingCache::kCapacity;
    if (early_valid_) {
        // What moved, for the next iteration's check (the winner and its ring), then the next
        // winner's neighbourhood (an uncached ring, count 0, is not fetched: the smoothing will
        // walk it).
        moved_[0] = w.idx;
        for (std::uint32_t i = 0; i < k; ++i) moved_[i + 1] = ring[i];
        n_moved_ = k + 1;
        prefetch_neighbourhood(rings_.neighbours(Vertex(early_)), rings_.count(Vertex(early_)));
    }
}

// The next sample's winner, on the vertices as they are before this iteration moves them, and
// the memory its iteration will touch first.
void NeuralMesh::look_ahead() {
    early_ = grid_.nearest(ahead_[0]);
    early_d2_ = squared_distance(ahead_[0], mesh_.position(Vertex(early_)));
    rings_.prefetch(Vertex(early_));
    grid_.prefetch_move(early_);  // its slot, for its move at step 3
    activity_.prefetch(early_);   // its record, for its signal at step 5
}

void NeuralMesh::iterate() {
    adapt();
    // Step 7: every Cvs iterations, split the most active vertex.
    if (iteration_ % params_.cvs == 0) {
        PhaseTimer timer(profiling_ ? &stats_.seconds_split : nullptr);
        split_most_active();
    }
    // Step 8: every Cec * n iterations, remove the inactive vertices. n changes as the mesh
    // grows, so the next pass is scheduled Cec * n iterations after this one, with the n of now.
    if (iteration_ >= next_removal_) {
        {
            // The collapses, the swaps among them timed apart (swap_around).
            PhaseTimer timer(profiling_ ? &stats_.seconds_collapse : nullptr);
            remove_inactive();
        }
        stats_.seconds_collapse -= stats_.seconds_swap - swap_seconds_before_;
        swap_seconds_before_ = stats_.seconds_swap;
        next_removal_ = iteration_ + std::uint64_t(params_.cec) * mesh_.n_vertices();
    }
}

// Step 7. Choice (after the original Neural Meshes): the split vertex v keeps one half of its
// ring and a new vertex takes the other half, centred on v's longest edge (v, w); the new vertex
// sits at the midpoint of that edge, and v's signal counter is shared equally between the two.
// Halving the ring keeps both valences near the mesh's average (valence k + 1 and n - k + 3).
void NeuralMesh::split_most_active() {
    early_valid_ = false;
    const Vertex v(activity_.most_active());
    const Vec3 p = mesh_.position(v);
    Halfedge longest = mesh_.halfedge(v);
    float longest_d2 = -1.0f;
    std::uint32_t valence = 0;
    mesh_.for_each_outgoing(v, [&](Halfedge h) {
        const float d2 = squared_distance(p, mesh_.position(mesh_.to(h)));
        if (d2 > longest_d2) {
            longest_d2 = d2;
            longest = h;
        }
        ++valence;
    });
    const std::uint32_t k = valence / 2 + 1;  // half-edges handed to the new vertex, 2 <= k <= valence
    Halfedge to_c = longest;
    for (std::uint32_t i = 0; i < (k - 1) / 2; ++i) to_c = mesh_.cw_rotated(to_c);
    Halfedge to_d = to_c;
    for (std::uint32_t i = 0; i + 1 < k; ++i) to_d = mesh_.ccw_rotated(to_d);
    const Vec3 q = (p + mesh_.position(mesh_.to(longest))) * 0.5f;
    const Vertex a = mesh_.split(to_c, to_d, q);
    const double half = activity_.counter(v.idx) * 0.5;
    activity_.set_counter(v.idx, half);
    activity_.add(a.idx, half);
    grid_.insert(a.idx, q);
    // The rings that changed: a's, v's, and those of a's neighbours (they had v in their rings,
    // or, for the two opposite the new edge, gained a). v's other neighbours kept their rings.
    rings_.refresh_around(mesh_, a);
    rings_.refresh(mesh_, v);
    ++stats_.splits;
}

// Step 8. A vertex is inactive when it won no signal during the period since the last pass
// (vertices created during the period count as active until the next pass).
// Choice: an inactive vertex v is collapsed into the neighbour u nearest to it, u keeping its
// position; when the link condition forbids that edge, the next nearest neighbour is tried; when
// no edge of v can collapse, v stays (counted in collapses_refused) and is tried again at the
// next pass.
void NeuralMesh::remove_inactive() {
    early_valid_ = false;
    ++stats_.removal_passes;
    inactive_.clear();
    activity_.collect_inactive(period_start_, inactive_);
    // Periods are bounded by decays (iterations): the new one starts at this iteration's decay,
    // so a vertex that this iteration's split added counts as created during it, and first faces
    // the pass after next (hence clock_mark(), not mark()).
    period_start_ = activity_.clock_mark();
    for (const std::uint32_t vi : inactive_) {
        const Vertex v(vi);
        if (mesh_.is_removed(v)) continue;
        // The legal collapse v -> u along the shortest edge.
        const Vec3 p = mesh_.position(v);
        Halfedge best;
        float best_d2 = 0.0f;
        mesh_.for_each_outgoing(v, [&](Halfedge h) {
            const float d2 = squared_distance(p, mesh_.position(mesh_.to(h)));
            if ((!best.valid() || d2 < best_d2) && mesh_.can_collapse(h)) {
                best = h;
                best_d2 = d2;
            }
        });
        if (!best.valid()) {
            ++stats_.collapses_refused;
            continue;
        }
        const Vertex u = mesh_.to(best);
        mesh_.collapse(best);
        rings_.refresh_around(mesh_, u);  // v's neighbours now have u in their rings
        grid_.remove(vi);
        activity_.remove(vi);
        ++stats_.collapses;
        if (params_.edge_swap) {
            PhaseTimer timer(profiling_ ? &stats_.seconds_swap : nullptr);
            swap_around(u);
        }
    }
}

// Eq. (9): DM(t, X), the distance from the centroid of t, the triangle of half-edge h, to the
// nearest cloud point (the same for each of t's three half-edges: Mesh::triangle_centroid).
float NeuralMesh::face_deviation(Halfedge h) const {
    return std::sqrt(cloud_index_->nearest_squared_distance(mesh_.triangle_centroid(h)));
}

// Eq. (8): Dev(e) = DM(t1, X) + DM(t2, X) for the two triangles of e.
float NeuralMesh::edge_deviation(Halfedge h) const { return face_deviation(h) + face_deviation(Mesh::twin(h)); }

// Section 4, after an edge collapse with remaining vertex v:
//  1. among the edges incident to v take the edge e with the largest Dev(e), eq. (8);
//  2. swap (flip) it;
//  3. keep the swap if the new edge's deviation is smaller, otherwise undo it.
// Choice: when the worst edge cannot be flipped (its flip would break the manifold or leave a
// vertex of valence < 3), nothing is swapped (counted in swaps_illegal).
void NeuralMesh::swap_around(Vertex v) {
    assert(cloud_index_);
    swap_ring_.clear();
    swap_dm_.clear();
    mesh_.for_each_outgoing(v, [&](Halfedge h) {
        swap_ring_.push_back(h);
        swap_dm_.push_back(face_deviation(h));
    });
    // Edge i lies between the triangles of h_i and h_{i-1}: the triangles of consecutive outgoing
    // half-edges around v share the edge between them.
    const std::size_t n = swap_ring_.size();
    std::size_t worst = 0;
    float worst_dev = -1.0f;
    for (std::size_t i = 0; i < n; ++i) {
        const float dev = swap_dm_[i] + swap_dm_[(i + n - 1) % n];
        if (dev > worst_dev) {
            worst_dev = dev;
            worst = i;
        }
    }
    const Halfedge e = swap_ring_[worst];
    if (!mesh_.can_flip(e)) {
        ++stats_.swaps_illegal;
        return;
    }
    // The four vertices whose rings the flip changes: the edge's ends and the two opposite it.
    const Vertex ends[4] = {v, mesh_.to(e), mesh_.to(mesh_.next(e)), mesh_.to(mesh_.next(Mesh::twin(e)))};
    const FlipRecord record = mesh_.flip(e);
    ++stats_.swaps_tried;
    if (edge_deviation(e) < worst_dev) {
        ++stats_.swaps_kept;
        for (const Vertex x : ends) rings_.refresh(mesh_, x);
    } else {
        mesh_.unflip(record);  // every mesh array as before: the cached rings still hold
        ++stats_.swaps_undone;
    }
}

void NeuralMesh::limit_ring_cache(std::uint32_t n) {
    rings_.set_limit(n);
    for (std::uint32_t v = 0; v < mesh_.vertex_capacity(); ++v)
        if (!mesh_.is_removed(Vertex(v))) rings_.refresh(mesh_, Vertex(v));
}

std::string NeuralMesh::check_consistency() const {
    std::ostringstream err;
    std::uint32_t alive = 0;
    for (std::uint32_t v = 0; v < mesh_.vertex_capacity(); ++v) {
        const bool in_mesh = !mesh_.is_removed(Vertex(v));
        alive += in_mesh;
        if (in_mesh != grid_.contains(v)) {
            err << "vertex " << v << (in_mesh ? " is missing from" : " is stale in") << " the grid";
            return err.str();
        }
        if (in_mesh != activity_.contains(v)) {
            err << "vertex " << v << (in_mesh ? " is missing from" : " is stale in") << " the activity index";
            return err.str();
        }
        if (in_mesh && !(grid_.position(v) == mesh_.position(Vertex(v)))) {
            err << "vertex " << v << " is at a different position in the grid";
            return err.str();
        }
    }
    const std::string rings = rings_.check(mesh_);
    if (!rings.empty()) return "ring cache: " + rings;
    if (grid_.size() != alive || activity_.size() != alive) {
        err << "sizes differ: mesh " << alive << ", grid " << grid_.size() << ", activity " << activity_.size();
        return err.str();
    }
    return {};
}

void NeuralMesh::reserve_target() {
    const std::uint32_t room = params_.target_vertices + kReserveSlack;
    mesh_.reserve(room);
    grid_.reserve(room);
    activity_.reserve(room);
    rings_.reserve(room);
}

void NeuralMesh::compact() {
    grid_.shrink_ids(mesh_.vertex_capacity());
    activity_.shrink_ids(mesh_.vertex_capacity());
}

void NeuralMesh::reseed(std::uint64_t stream) {
    // An odd multiplier spreads the streams of one seed apart; Random's own seed expansion
    // (splitmix64) makes them unrelated.
    rng_ = Random(params_.seed ^ (stream * 0xd1b54a32d192ed03ull));
}

// The searches need the face index, which the loop does without; it is built for them and
// dropped after them (the mesh is closed again either way). The face support is computed once
// for both, and again only when the bridges' collapses changed the mesh.
std::uint32_t NeuralMesh::learn_topology() {
    if (!cloud_index_) return 0;
    mesh_.build_faces();
    FaceSupport support = face_support(mesh_, *cloud_index_);
    const BridgeSearch bridges = find_bridges(mesh_, *cloud_index_, support);
    if (bridges.bridges > 0) {
        mesh_.drop_faces();
        const std::uint32_t refused = collapse_flagged(mesh_, bridges.flagged, [&](Vertex gone, Vertex kept) {
            rings_.refresh_around(mesh_, kept);
            grid_.remove(gone.idx);
            activity_.remove(gone.idx);
        });
        stats_.bridges += bridges.bridges;
        stats_.bridge_vertices_removed += bridges.flagged_count - refused;
        mesh_.build_faces();
        support = face_support(mesh_, *cloud_index_);
    }
    const HandleSearch found = search_handles_ ? open_handles(mesh_, *cloud_index_, support) : HandleSearch();
    mesh_.drop_faces();
    for (std::uint32_t v : found.removed_vertices) {
        grid_.remove(v);
        activity_.remove(v);
    }
    for (std::uint32_t v : found.touched_vertices) rings_.refresh(mesh_, Vertex(v));
    early_valid_ = false;  // the look-ahead's winner may be gone
    ++stats_.topology_checks;
    stats_.membrane_patches += found.patches;
    stats_.handles += found.handles;
    stats_.membrane_faces_removed += found.faces_removed;
    return found.handles;
}

}  // namespace nmesh
