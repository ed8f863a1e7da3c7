// nmesh/finish/surface_fit.cpp — the least-squares fit of the vertices to the scan points, the last step of
// the finishing stage (nmesh/finish/surface_fit.h).
#include "nmesh/finish/surface_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

#include "nmesh/finish/defect_tracker.h"
#include "nmesh/finish/mesh_queries.h"
#include "nmesh/geometry/closest_point.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/util/math_constants.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

using namespace finish_detail;

namespace {

// The conjugate gradients stop at this residual, relative to the right-hand side's, or after
// kMaxIterations; they start from zero, the no-move solution.
constexpr double kTolerance = 1e-6;
constexpr int kMaxIterations = 500;
// The points a thread takes at a time (their nearest triangles and feet).
constexpr std::size_t kPointsPerChunk = 1024;
// The search for a point's nearest triangle walks at most this many steps from its start.
constexpr int kWalkSteps = 6;
// The moves at a new defect: halved this many times, then undone.
constexpr int kHalvings = 2;

// Barycentric coordinates of q, a point of the triangle abc (its closest point to a scan point),
// clamped into the triangle against rounding.
std::array<float, 3> barycentric(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 v0 = b - a, v1 = c - a, v2 = q - a;
    const float d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1);
    const float d20 = dot(v2, v0), d21 = dot(v2, v1);
    const float denom = d00 * d11 - d01 * d01;
    if (!(denom > 0.0f)) return {1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f};
    float v = std::clamp((d11 * d20 - d01 * d21) / denom, 0.0f, 1.0f);
    float w = std::clamp((d00 * d21 - d01 * d20) / denom, 0.0f, 1.0f);
    if (v + w > 1.0f) {
        const float s = v + w;
        v /= s;
        w /= s;
    }
    return {1.0f - v - w, v, w};
}

// The mesh as the rounds see it: live vertices and triangles in compact order, the triangles round
// each vertex, the matrix's pattern (each vertex with its neighbours), which the rounds do not
// change, and the geometry, which each round sets again (set_geometry).
struct Frame {
    std::vector<Vertex> verts;
    std::vector<std::uint32_t> slot;                      // by vertex id: index into verts
    std::vector<std::array<std::uint32_t, 3>> triangle;   // corners, as slots
    std::vector<std::uint32_t> ring_start, ring;          // by slot: the triangles round it (CSR)
    std::vector<std::uint32_t> adjacent_start, adjacent;  // by slot: itself and its neighbours, sorted
    std::vector<Vec3> position;                           // of verts
    std::vector<Vec3> vertex_normal;                      // unit (area-weighted), or zero
    std::vector<float> vertex_edge;                       // mean length of each vertex's edges
    std::vector<Vec3> face_normal;                        // unit, zero for a degenerate triangle
    std::vector<float> face_edge;                         // mean edge length of each triangle
};

Frame frame_of(const Mesh& mesh) {
    Frame f;
    f.verts = alive_vertices(mesh);
    const std::size_t nv = f.verts.size();
    f.slot.assign(mesh.vertex_capacity(), kInvalidIndex);
    for (std::uint32_t i = 0; i < nv; ++i) f.slot[f.verts[i].idx] = i;
    std::vector<std::uint32_t> face_slot(mesh.face_capacity(), kInvalidIndex);
    for (const Face face : alive_faces(mesh)) {
        face_slot[face.idx] = std::uint32_t(f.triangle.size());
        const auto c = corners(mesh, face);
        f.triangle.push_back({f.slot[c[0].idx], f.slot[c[1].idx], f.slot[c[2].idx]});
    }
    f.ring_start.assign(nv + 1, 0);
    f.adjacent_start.assign(nv + 1, 0);
    for (std::uint32_t i = 0; i < nv; ++i) {
        const std::size_t first = f.adjacent.size();
        f.adjacent.push_back(i);
        mesh.for_each_outgoing(f.verts[i], [&](Halfedge h) {
            f.adjacent.push_back(f.slot[mesh.to(h).idx]);
            if (!mesh.is_boundary(h)) f.ring.push_back(face_slot[mesh.face(h).idx]);
        });
        std::sort(f.adjacent.begin() + std::ptrdiff_t(first), f.adjacent.end());
        f.ring_start[i + 1] = std::uint32_t(f.ring.size());
        f.adjacent_start[i + 1] = std::uint32_t(f.adjacent.size());
    }
    return f;
}

void set_geometry(Frame& f, const Mesh& mesh) {
    const std::size_t nv = f.verts.size();
    f.position.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) f.position[i] = mesh.position(f.verts[i]);
    f.vertex_normal.assign(nv, Vec3());
    f.face_normal.resize(f.triangle.size());
    f.face_edge.resize(f.triangle.size());
    for (std::size_t t = 0; t < f.triangle.size(); ++t) {
        const auto& c = f.triangle[t];
        const Vec3 &a = f.position[c[0]], &b = f.position[c[1]], &d = f.position[c[2]];
        const Vec3 x = cross(b - a, d - a);  // twice the area, along the normal
        for (const std::uint32_t k : c) f.vertex_normal[k] += x;
        const float area2 = norm(x);
        f.face_normal[t] = area2 > 0.0f ? x * (1.0f / area2) : Vec3();
        f.face_edge[t] = (distance(a, b) + distance(b, d) + distance(d, a)) / 3.0f;
    }
    f.vertex_edge.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) {
        const float l = norm(f.vertex_normal[i]);
        f.vertex_normal[i] = l > 0.0f ? f.vertex_normal[i] * (1.0f / l) : Vec3();
        float sum = 0.0f;
        for (std::uint32_t k = f.adjacent_start[i]; k < f.adjacent_start[i + 1]; ++k)
            sum += distance(f.position[i], f.position[f.adjacent[k]]);
        const std::uint32_t n = f.adjacent_start[i + 1] - f.adjacent_start[i] - 1;
        f.vertex_edge[i] = n ? sum / float(n) : 0.0f;
    }
}

// The cosine of the smallest angle of the triangle abc (1 for a degenerate one): the larger, the
// thinner the triangle.
float thinness(const Vec3& a, const Vec3& b, const Vec3& c) {
    float most = -1.0f;
    for (const auto& [p, q, r] : {std::array<const Vec3*, 3>{&a, &b, &c}, std::array<const Vec3*, 3>{&b, &c, &a},
                                  std::array<const Vec3*, 3>{&c, &a, &b}}) {
        const Vec3 u = *q - *p, v = *r - *p;
        const float l = norm(u) * norm(v);
        if (!(l > 0.0f)) return 1.0f;
        most = std::max(most, dot(u, v) / l);
    }
    return most;
}

float thinness(const Mesh& mesh, const Frame& f, std::size_t t) {
    const auto& c = f.triangle[t];
    return thinness(mesh.position(f.verts[c[0]]), mesh.position(f.verts[c[1]]), mesh.position(f.verts[c[2]]));
}

float squared_distance_to(const Frame& f, std::uint32_t t, const Vec3& x) {
    const auto& c = f.triangle[t];
    return squared_distance(x,
                            closest_point_on_triangle_float(x, f.position[c[0]], f.position[c[1]], f.position[c[2]]));
}

// The triangle nearest to x found by walking from `t`: to the nearest of the triangles round the
// current one's corners, while that is nearer (each corner's triangles looked at once).
std::uint32_t walk_to_nearest(const Frame& f, std::uint32_t t, const Vec3& x) {
    float best = squared_distance_to(f, t, x);
    std::array<std::uint32_t, 3 * kWalkSteps> seen;
    std::size_t n_seen = 0;
    for (int step = 0; step < kWalkSteps; ++step) {
        const std::uint32_t from = t;
        for (const std::uint32_t c : f.triangle[from]) {
            if (std::find(seen.begin(), seen.begin() + std::ptrdiff_t(n_seen), c) !=
                seen.begin() + std::ptrdiff_t(n_seen))
                continue;
            seen[n_seen++] = c;
            for (std::uint32_t k = f.ring_start[c]; k < f.ring_start[c + 1]; ++k) {
                const std::uint32_t u = f.ring[k];
                if (u == t) continue;
                const float d = squared_distance_to(f, u, x);
                if (d < best) best = d, t = u;
            }
        }
        if (t == from) break;
    }
    return t;
}

// The cells of a coarse grid that some triangle, grown by its reach, overlaps: a point in any other
// cell is out of every triangle's reach, which it tells without a nearest-neighbour query (a query
// far from the data costs tens of microseconds: a stray point, a point where the open mode cut the
// surface away).
class Reachable {
public:
    Reachable(const Frame& f, float reach) {
        if (f.triangle.empty()) return;
        std::vector<std::pair<Vec3, Vec3>> boxes(f.triangle.size());
        double edges = 0.0;
        for (std::size_t t = 0; t < f.triangle.size(); ++t) {
            const auto& c = f.triangle[t];
            const Vec3 grow(reach * f.face_edge[t], reach * f.face_edge[t], reach * f.face_edge[t]);
            boxes[t] = {min(min(f.position[c[0]], f.position[c[1]]), f.position[c[2]]) - grow,
                        max(max(f.position[c[0]], f.position[c[1]]), f.position[c[2]]) + grow};
            lo_ = t == 0 ? boxes[t].first : min(lo_, boxes[t].first);
            hi_ = t == 0 ? boxes[t].second : max(hi_, boxes[t].second);
            edges += double(f.face_edge[t]);
        }
        // Cells of two mean edges, at most 8 per triangle.
        cell_ = std::max(2.0f * float(edges / double(f.triangle.size())), 1e-30f);
        const double limit = 8.0 * double(f.triangle.size()) + 64.0;
        for (;;) {
            double cells = 1.0;
            for (int a = 0; a < 3; ++a) cells *= std::floor(double(hi_[a] - lo_[a]) / double(cell_)) + 1.0;
            if (cells <= limit) break;
            cell_ *= 1.25f;
        }
        for (int a = 0; a < 3; ++a) dims_[a] = std::size_t((hi_[a] - lo_[a]) / cell_) + 1;
        marked_.assign(dims_[0] * dims_[1] * dims_[2], 0);
        for (const auto& [b0, b1] : boxes) {
            const auto from = cell(b0), to = cell(b1);
            for (std::size_t z = from[2]; z <= to[2]; ++z)
                for (std::size_t y = from[1]; y <= to[1]; ++y)
                    for (std::size_t x = from[0]; x <= to[0]; ++x) marked_[(z * dims_[1] + y) * dims_[0] + x] = 1;
        }
    }
    bool maybe(const Vec3& x) const {
        if (marked_.empty()) return false;
        for (int a = 0; a < 3; ++a)
            if (!(x[a] >= lo_[a] && x[a] <= hi_[a])) return false;
        const auto c = cell(x);
        return marked_[(c[2] * dims_[1] + c[1]) * dims_[0] + c[0]] != 0;
    }

private:
    std::array<std::size_t, 3> cell(const Vec3& x) const {
        std::array<std::size_t, 3> c{};
        for (int a = 0; a < 3; ++a) c[a] = std::min(dims_[a] - 1, std::size_t(std::max(0.0f, (x[a] - lo_[a]) / cell_)));
        return c;
    }
    Vec3 lo_, hi_;
    float cell_ = 1.0f;
    std::array<std::size_t, 3> dims_{};
    std::vector<std::uint8_t> marked_;
};

// The symmetric matrix over the unknowns, with the pattern of the frame's adjacency: for each
// unknown, its own column and its unknown neighbours', sorted.
struct System {
    std::vector<int> start, index;
    std::vector<double> value;
    Eigen::MatrixXd rhs;  // one column (along the normals) or three (x, y, z)

    System(const Frame& f, const std::vector<std::int32_t>& unknown, std::int32_t n, int columns)
        : rhs(Eigen::MatrixXd::Zero(n, columns)) {
        start.reserve(std::size_t(n) + 1);
        start.push_back(0);
        for (std::size_t i = 0; i < f.verts.size(); ++i) {
            if (unknown[i] < 0) continue;
            for (std::uint32_t k = f.adjacent_start[i]; k < f.adjacent_start[i + 1]; ++k)
                if (unknown[f.adjacent[k]] >= 0) index.push_back(unknown[f.adjacent[k]]);
            start.push_back(int(index.size()));
        }
        value.assign(index.size(), 0.0);
    }
    // The entry (row, col), which the pattern holds.
    double& at(std::int32_t row, std::int32_t col) {
        int k = start[std::size_t(row)];
        while (index[std::size_t(k)] != col) ++k;
        return value[std::size_t(k)];
    }
};

// One round: the moves that best fit the points (none for a vertex that is no unknown), each at
// most step_limit of its vertex's mean edge. `so_far`: each vertex's move since the fit began (the
// membrane is on the whole move, so that the rounds converge to the fit with the fairness term,
// not to the one without). `near`: each point's triangle from the previous round (kInvalidIndex:
// out of reach), or empty.
// Returns the number of pulling points.
std::uint64_t solve_round(const Frame& f, const std::vector<Vec3>& points, const std::vector<Vec3>& sides,
                          const std::vector<std::int32_t>& unknown, std::int32_t n_unknowns,
                          const SurfaceFitOptions& options, const std::vector<Vec3>& so_far,
                          std::vector<std::uint32_t>& near, std::vector<Vec3>& move) {
    if (near.size() != points.size()) {
        std::vector<Vec3> centroids(f.triangle.size());
        for (std::size_t t = 0; t < f.triangle.size(); ++t) {
            const auto& c = f.triangle[t];
            centroids[t] = (f.position[c[0]] + f.position[c[1]] + f.position[c[2]]) * (1.0f / 3.0f);
        }
        const PointGrid index(centroids);
        const Reachable reachable(f, options.reach);
        near.resize(points.size());
        for_chunks(points.size(), kPointsPerChunk, options.threads, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i)
                near[i] = reachable.maybe(points[i]) ? index.nearest(points[i]) : kInvalidIndex;
        });
    }
    // Each point's nearest triangle (walked to from the last round's), its foot there and whether
    // it pulls: independent point by point, on the threads.
    struct Foot {
        Vec3 q;                 // the foot
        std::array<float, 3> w;  // its barycentric weights
        bool pulls = false;
    };
    std::vector<Foot> feet(points.size());
    for_chunks(points.size(), kPointsPerChunk, options.threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            if (near[i] == kInvalidIndex) continue;
            const Vec3& x = points[i];
            const std::uint32_t t = near[i] = walk_to_nearest(f, near[i], x);
            const auto& tri = f.triangle[t];
            const Vec3 &a = f.position[tri[0]], &b = f.position[tri[1]], &c = f.position[tri[2]];
            Foot& foot = feet[i];
            foot.q = closest_point_on_triangle_float(x, a, b, c);
            const float reach = options.reach * f.face_edge[t];
            if (squared_distance(x, foot.q) > reach * reach) continue;
            if (!(dot(sides[i], f.face_normal[t]) > 0.0f)) continue;  // faces away, or a degenerate triangle
            foot.w = barycentric(foot.q, a, b, c);
            foot.pulls = true;
        }
    });
    // The normal equations, summed in the points' order.
    System system(f, unknown, n_unknowns, options.normal_only ? 1 : 3);
    std::uint64_t used = 0;
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const Foot& foot = feet[i];
        if (!foot.pulls) continue;
        const Vec3& x = points[i];
        const std::uint32_t t = near[i];
        const auto& tri = f.triangle[t];
        const Vec3& q = foot.q;
        const std::array<float, 3>& w = foot.w;
        const Vec3& m = f.face_normal[t];
        const double r = double(dot(x - q, m));
        std::array<double, 3> coef{};
        std::array<std::int32_t, 3> col{};
        for (int k = 0; k < 3; ++k) {
            col[k] = unknown[tri[k]];
            coef[k] = col[k] < 0            ? 0.0
                      : options.normal_only ? double(w[k]) * double(dot(f.vertex_normal[tri[k]], m))
                                            : double(w[k]);
        }
        for (int k = 0; k < 3; ++k) {
            if (col[k] < 0) continue;
            if (options.normal_only) {
                system.rhs(col[k], 0) += coef[k] * r;
            } else {
                const Vec3 e = x - q;
                for (int a = 0; a < 3; ++a) system.rhs(col[k], a) += coef[k] * double(e[a]);
            }
            for (int l = 0; l < 3; ++l)
                if (col[l] >= 0) system.at(col[k], col[l]) += coef[k] * coef[l];
        }
        ++used;
    }
    if (used == 0) return 0;
    // The membrane on the moves (a vertex that is no unknown does not move) and the damping, both
    // weighed in points (a point's term has weight 1).
    const double lambda = double(options.smoothness);
    const double eps = double(kFitDamping);
    for (std::size_t i = 0; i < f.verts.size(); ++i) {
        const std::int32_t row = unknown[i];
        if (row < 0) continue;
        const std::uint32_t neighbours = f.adjacent_start[i + 1] - f.adjacent_start[i] - 1;
        system.at(row, row) += lambda * double(neighbours) + eps;
        Vec3 pull;  // the membrane's pull back on the move so far
        for (std::uint32_t k = f.adjacent_start[i]; k < f.adjacent_start[i + 1]; ++k) {
            const std::uint32_t j = f.adjacent[k];
            pull += so_far[j] - so_far[i];
            const std::int32_t col = unknown[j];
            if (col >= 0 && col != row) system.at(row, col) -= lambda;
        }
        if (options.normal_only) {
            system.rhs(row, 0) += lambda * double(dot(pull, f.vertex_normal[i]));
        } else {
            for (int a = 0; a < 3; ++a) system.rhs(row, a) += lambda * double(pull[a]);
        }
    }
    const Eigen::Map<Eigen::SparseMatrix<double>> matrix(n_unknowns, n_unknowns, int(system.value.size()),
                                                         system.start.data(), system.index.data(), system.value.data());
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> solver;
    solver.setTolerance(kTolerance);
    solver.setMaxIterations(kMaxIterations);
    solver.compute(matrix);
    const Eigen::MatrixXd d = solver.solve(system.rhs);
    move.assign(f.verts.size(), Vec3());
    for (std::size_t i = 0; i < f.verts.size(); ++i) {
        const std::int32_t k = unknown[i];
        if (k < 0) continue;
        move[i] = options.normal_only ? f.vertex_normal[i] * float(d(k, 0))
                                      : Vec3(float(d(k, 0)), float(d(k, 1)), float(d(k, 2)));
        const float limit = options.step_limit * f.vertex_edge[i];
        const float l = norm(move[i]);
        if (l > limit) move[i] = move[i] * (limit / l);
    }
    return used;
}

}  // namespace

SurfaceFitResult fit_surface(Mesh& mesh, const CloudSurface& cloud, const SurfaceFitOptions& options) {
    SurfaceFitResult result;
    if (options.rounds <= 0 || mesh.n_faces() == 0 || cloud.points().empty()) return result;
    const float cos_limit = std::cos(options.fold_dihedral_deg * kPiF / 180.0f);
    // The corners of the triangles in a defect before the fit stay where they are: every defect
    // after it then either was there before, among unmoved triangles, or touches a moved vertex,
    // whose move is taken back.
    std::vector<std::uint8_t> held(mesh.vertex_capacity(), 0);
    if (!options.known_clean) {
        const DefectTracker before(mesh, cos_limit, false, options.threads);
        for (const Face f : before.defective_faces())
            for (const Vertex v : corners(mesh, f)) held[v.idx] = 1;
    }
    const std::vector<Vec3> origin = mesh.positions();
    // The points, at most kFitPointsPerVertex per vertex (every k-th of a denser cloud), with
    // their normals, looked up once for all rounds.
    const std::vector<Vec3>& all = cloud.points();
    const std::size_t most = std::size_t(kFitPointsPerVertex) * mesh.n_vertices();
    const std::size_t stride = std::max<std::size_t>(1, (all.size() + most - 1) / most);
    std::vector<Vec3> points, sides;
    points.reserve(all.size() / stride + 1);
    sides.reserve(all.size() / stride + 1);
    for (std::size_t i = 0; i < all.size(); i += stride) {
        points.push_back(all[i]);
        sides.push_back(cloud.normal(std::uint32_t(i)));
    }
    std::vector<std::uint32_t> near;
    Frame frame = frame_of(mesh);
    const std::size_t nv = frame.verts.size();
    std::vector<float> thin_before(frame.triangle.size());
    for (std::size_t t = 0; t < frame.triangle.size(); ++t) thin_before[t] = thinness(mesh, frame, t);
    const float thin_limit = std::cos(kFitMinAngleDeg * kPiF / 180.0f);
    for (int round = 0; round < options.rounds; ++round) {
        set_geometry(frame, mesh);
        std::vector<std::int32_t> unknown(nv, -1);
        std::int32_t n_unknowns = 0;
        for (std::size_t i = 0; i < nv; ++i) {
            const Vertex v = frame.verts[i];
            if (!held[v.idx] && !mesh.is_boundary(v) && frame.vertex_edge[i] > 0.0f &&
                squared_norm(frame.vertex_normal[i]) > 0.5f)
                unknown[i] = n_unknowns++;
        }
        if (n_unknowns == 0) break;
        std::vector<Vec3> so_far(nv), move;
        for (std::size_t i = 0; i < nv; ++i) so_far[i] = frame.position[i] - origin[frame.verts[i].idx];
        const std::uint64_t used = solve_round(frame, points, sides, unknown, n_unknowns, options, so_far, near, move);
        if (used == 0) break;
        result.points_used += used;
        for (std::size_t i = 0; i < nv; ++i)
            if (unknown[i] >= 0) mesh.set_position(frame.verts[i], frame.position[i] + move[i]);
        ++result.rounds;
    }
    // The check, once for all rounds: the moves at a defect, or at a triangle made thinner than
    // kFitMinAngleDeg (or thinner still), halved, twice, then undone, until none touches a moved
    // vertex (an undone vertex may leave its neighbour's move at a new one). From the third pass
    // on, each pass puts at least one vertex back for good, so the passes end.
    std::vector<Vertex> moved;
    for (const Vertex v : frame.verts)
        if (mesh.position(v) != origin[v.idx]) moved.push_back(v);
    if (moved.empty()) return result;
    DefectTracker tracker(mesh, cos_limit, false, options.threads);
    std::vector<std::uint8_t> touched(mesh.vertex_capacity(), 0);  // 1: halved, 2: undone
    // The triangles to look at for thinness: all of them, then those round the vertices last put
    // back or halved.
    std::vector<std::uint32_t> look(frame.triangle.size());
    for (std::uint32_t t = 0; t < look.size(); ++t) look[t] = t;
    for (int pass = 0;; ++pass) {
        std::vector<Vertex> bad;
        const auto is_moved = [&](Vertex v) { return mesh.position(v) != origin[v.idx]; };
        for (const Face f : tracker.defective_faces())
            for (const Vertex v : corners(mesh, f))
                if (is_moved(v)) bad.push_back(v);
        for (const std::uint32_t t : look) {
            const float thin = thinness(mesh, frame, t);
            if (thin > thin_limit && thin > thin_before[t])
                for (const std::uint32_t k : frame.triangle[t])
                    if (is_moved(frame.verts[k])) bad.push_back(frame.verts[k]);
        }
        if (bad.empty()) break;
        std::sort(bad.begin(), bad.end());
        bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
        look.clear();
        for (const Vertex v : bad) {
            if (pass < kHalvings) {
                mesh.set_position(v, (mesh.position(v) + origin[v.idx]) * 0.5f);
                touched[v.idx] = 1;
            } else {
                mesh.set_position(v, origin[v.idx]);
                touched[v.idx] = 2;
            }
            tracker.changed(v);
            const std::uint32_t k = frame.slot[v.idx];
            look.insert(look.end(), frame.ring.begin() + frame.ring_start[k],
                        frame.ring.begin() + frame.ring_start[k + 1]);
        }
        std::sort(look.begin(), look.end());
        look.erase(std::unique(look.begin(), look.end()), look.end());
        tracker.check();
    }
    double sum = 0.0;
    for (const Vertex v : moved) {
        if (touched[v.idx] == 2) {
            ++result.undone;
            continue;
        }
        ++(touched[v.idx] == 1 ? result.halved : result.moves);
        sum += double(distance(mesh.position(v), origin[v.idx]));
    }
    const std::uint64_t kept = result.moves + result.halved;
    result.mean_move = kept ? sum / double(kept) : 0.0;
    return result;
}

}  // namespace nmesh
