// The Neural Meshes learning loop, step by step as section 3 of the Neural Meshes ES paper lists
// it, plus the edge swap of section 4. Where the papers leave a choice open, the choice is named
// "Choice:" here and listed in README.md.
#include "nmesh/neural_mesh.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <sstream>

namespace nmesh {
namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

NeuralMesh::NeuralMesh(const std::vector<Vec3>& points, const BoundingBox& bounds, const Parameters& params)
    : points_(points), params_(params), grid_(bounds), activity_(params.alpha), rng_(params.seed) {
    // Choice: the initial tetrahedron is regular, centred on the cloud's bounding box, with a
    // circumradius of a quarter of the box's diagonal: inside the data for a closed scan, and
    // large enough that all four vertices win signals from the start.
    mesh_ = Mesh::tetrahedron(bounds.center(), float(bounds.diagonal() * 0.25));
    mesh_.reserve(params.target_vertices + 16);
    grid_.reserve(params.target_vertices + 16);
    activity_.reserve(params.target_vertices + 16);
    for (std::uint32_t v = 0; v < 4; ++v) {
        grid_.insert(v, mesh_.position(Vertex(v)));
        activity_.add(v, 0.0);
    }
    if (params_.edge_swap) cloud_index_ = std::make_unique<PointGrid>(points_);
    next_removal_ = std::uint64_t(params_.cec) * mesh_.n_vertices();
    grow_scratch(64);
    swap_ring_.reserve(64);
    swap_dm_.reserve(64);
}

void NeuralMesh::set_position(Vertex v, const Vec3& p) {
    mesh_.set_position(v, p);
    grid_.move(v.idx, p);
}

// Steps 1-2: a random sample x and the vertex nearest to it, eq. (1).
Vertex NeuralMesh::sample_and_find_winner(Vec3& x) {
    x = points_[rng_.below(std::uint32_t(points_.size()))];
    return Vertex(grid_.nearest(x));
}

// Step 3, eq. (2): v'_w = (1 - alpha_w) v_w + alpha_w x.
void NeuralMesh::move_winner(Vertex w, const Vec3& x) {
    const float aw = float(params_.alpha_w);
    set_position(w, mesh_.position(w) * (1.0f - aw) + x * aw);
}

// Step 4, eq. (3)-(5): tangential Laplacian smoothing of the winner's one-ring.
// v'_n = v_n + alpha_n L_t,  L_t = L - (L . n) n,  L = mean over the ring of (v_k - v_n),
// with n the vertex's approximated (area-weighted) normal.
// Choice: all neighbours are moved from the positions they had before this step (a Jacobi
// update), so the result does not depend on the order of the ring.
void NeuralMesh::smooth_neighbourhood(Vertex w) {
    const float an = float(params_.alpha_n);
    if (an == 0.0f) return;
    // w's ring, clockwise: ring_[i] = to(out_[i]) with out_[i + 1] = cw_rotated(out_[i]).
    // The scratch arrays are written by index (they only grow, to the largest valence seen), so
    // the hot path has no push_back bookkeeping.
    std::size_t k = 0;
    const Halfedge first = mesh_.halfedge(w);
    Halfedge h = first;
    do {
        if (k == ring_.size()) grow_scratch(2 * k + 16);
        out_[k] = h;
        const Vertex v = mesh_.to(h);
        ring_[k] = v;
        new_positions_[k] = mesh_.position(v);
        ++k;
        h = mesh_.cw_rotated(h);
    } while (h != first);
    const Vec3* old = new_positions_.data();  // positions before this step (Jacobi update)
    Vec3* updated = scratch_.data();
    const Vec3 pw = mesh_.position(w);
    for (std::size_t i = 0; i < k; ++i) {
        const Vec3 p = old[i];
        // One clockwise pass over ring_[i]'s own ring gives both the Laplacian (eq. 5) and the
        // area-weighted normal (the sum of the cross products of consecutive ring edges). The
        // pass starts at the half-edge to w, whose clockwise predecessor and successor in that
        // ring are w's ring neighbours ring_[i + 1] and ring_[i - 1]: no lookup needed for them.
        const Vec3 a0 = pw - p;
        const Vec3 a1 = old[i == 0 ? k - 1 : i - 1] - p;
        Vec3 sum = a0 + a1;
        Vec3 normal = cross(a0, old[i + 1 == k ? 0 : i + 1] - p) + cross(a1, a0);
        Vec3 prev = a1;  // the walk ends at ring_[i + 1], closing the cycle of cross products
        std::uint32_t valence = 2;
        const Halfedge stop = Mesh::twin(out_[i]);  // ring_[i] -> w, where the pass began
        for (Halfedge g = mesh_.cw_rotated(mesh_.next(out_[i])); g != stop; g = mesh_.cw_rotated(g)) {
            const Vec3 a = mesh_.position(mesh_.to(g)) - p;
            sum += a;
            normal += cross(a, prev);
            prev = a;
            ++valence;
        }
        const Vec3 laplacian = sum * (1.0f / float(valence));  // eq. (5)
        const float nn = squared_norm(normal);
        const Vec3 tangential = nn > 0.0f ? laplacian - normal * (dot(laplacian, normal) / nn)  // eq. (4)
                                          : laplacian;
        updated[i] = p + tangential * an;  // eq. (3)
    }
    for (std::size_t i = 0; i < k; ++i) set_position(ring_[i], updated[i]);
}

void NeuralMesh::grow_scratch(std::size_t n) {
    ring_.resize(n);
    out_.resize(n);
    new_positions_.resize(n);
    scratch_.resize(n);
}

void NeuralMesh::adapt() {
    if (profiling_) return adapt_profiled();
    Vec3 x;
    const Vertex w = sample_and_find_winner(x);  // steps 1-2
    move_winner(w, x);                           // step 3
    smooth_neighbourhood(w);                     // step 4
    activity_.signal(w.idx);                     // step 5, eq. (6): tau_w += 1
    activity_.decay();                           // step 6, eq. (7): tau_v *= alpha for all v
    ++iteration_;
    ++stats_.iterations;
}

// The same as adapt(), timing the winner search (steps 1-2) and the updates (steps 3-6).
void NeuralMesh::adapt_profiled() {
    Vec3 x;
    const auto t0 = Clock::now();
    const Vertex w = sample_and_find_winner(x);
    const auto t1 = Clock::now();
    move_winner(w, x);
    smooth_neighbourhood(w);
    activity_.signal(w.idx);
    activity_.decay();
    stats_.seconds_winner += std::chrono::duration<double>(t1 - t0).count();
    stats_.seconds_update += seconds_since(t1);
    ++iteration_;
    ++stats_.iterations;
}

void NeuralMesh::iterate() {
    adapt();
    // Step 7: every Cvs iterations, split the most active vertex.
    if (iteration_ % params_.cvs == 0) {
        if (profiling_) {
            const auto t = Clock::now();
            split_most_active();
            stats_.seconds_split += seconds_since(t);
        } else {
            split_most_active();
        }
    }
    // Step 8: every Cec * n iterations, remove the inactive vertices. n changes as the mesh
    // grows, so the next pass is scheduled Cec * n iterations after this one, with the n of now.
    if (iteration_ >= next_removal_) {
        const auto t = Clock::now();
        remove_inactive();
        if (profiling_) stats_.seconds_collapse += seconds_since(t);
        next_removal_ = iteration_ + std::uint64_t(params_.cec) * mesh_.n_vertices();
    }
}

// Step 7. Choice (after the original Neural Meshes): the split vertex v keeps one half of its
// ring and a new vertex takes the other half, centred on v's longest edge (v, w); the new vertex
// sits at the midpoint of that edge, and v's signal counter is shared equally between the two.
// Halving the ring keeps both valences near the mesh's average (valence k + 1 and n - k + 3).
void NeuralMesh::split_most_active() {
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
    ++stats_.splits;
}

// Step 8. A vertex is inactive when it won no signal during the period since the last pass
// (vertices created during the period count as active until the next pass).
// Choice: an inactive vertex v is collapsed into the neighbour u nearest to it, u keeping its
// position; when the link condition forbids that edge, the next nearest neighbour is tried; when
// no edge of v can collapse, v stays (counted in collapses_refused) and is tried again at the
// next pass.
void NeuralMesh::remove_inactive() {
    ++stats_.removal_passes;
    inactive_.clear();
    activity_.collect_inactive(period_start_, inactive_);
    period_start_ = activity_.now();
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
        grid_.remove(vi);
        activity_.remove(vi);
        ++stats_.collapses;
        if (params_.edge_swap) {
            if (profiling_) {
                const auto t = Clock::now();
                swap_around(u);
                const double dt = seconds_since(t);
                stats_.seconds_swap += dt;
                stats_.seconds_collapse -= dt;  // reported apart from the collapses
            } else {
                swap_around(u);
            }
        }
    }
}

// Eq. (9): DM(t, X), the distance from the centroid of t to the nearest cloud point.
float NeuralMesh::face_deviation(Face f) const {
    return std::sqrt(cloud_index_->nearest_squared_distance(mesh_.face_centroid(f)));
}

// Eq. (8): Dev(e) = DM(t1, X) + DM(t2, X) for the two triangles of e.
float NeuralMesh::edge_deviation(Halfedge h) const {
    return face_deviation(mesh_.face(h)) + face_deviation(mesh_.face(Mesh::twin(h)));
}

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
        swap_dm_.push_back(face_deviation(mesh_.face(h)));
    });
    // Edge i lies between face(h_i) and face(h_{i-1}): the faces of consecutive outgoing
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
    const FlipRecord record = mesh_.flip(e);
    ++stats_.swaps_tried;
    if (edge_deviation(e) < worst_dev) {
        ++stats_.swaps_kept;
    } else {
        mesh_.unflip(record);
        ++stats_.swaps_undone;
    }
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
    if (grid_.size() != alive || activity_.size() != alive) {
        err << "sizes differ: mesh " << alive << ", grid " << grid_.size() << ", activity " << activity_.size();
        return err.str();
    }
    return {};
}

}  // namespace nmesh
