#include "nmesh/metrics.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <locale>
#include <numeric>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>

#include "nmesh/bounding_box.h"
#include "nmesh/error.h"
#include "nmesh/util/math_constants.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/metrics/topology.h"
#include "nmesh/util/parallel.h"
#include "nmesh/util/random.h"

namespace nmesh {

using metrics_detail::analyze_topology;
using metrics_detail::is_degenerate;

namespace {

using Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Triangles whose smallest angle is below this are counted as poorly shaped (a common threshold
// in meshing; 60 degrees is the equilateral optimum).
constexpr double kSmallAngleDeg = 10.0;
// The points and samples measured at a time (their distances kept until summed in order), and
// the chunks of a block the threads take.
constexpr std::size_t kBlock = std::size_t(1) << 16;
constexpr std::size_t kChunk = 1024;

Vector3d to_eigen(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

// ---- sampling -----------------------------------------------------------------------------------

// A double uniform in [0, 1) from the top 53 bits of a 64-bit draw (the same on every platform,
// unlike std::uniform_real_distribution).

void check_inputs(PointSpan points, const IndexedMesh& mesh) {
    if (points.empty()) throw InputError("metrics: the point cloud is empty");
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!is_finite(points[i]))
            throw InputError("metrics: cloud point " + std::to_string(i) + " has a NaN or infinite coordinate");
    if (mesh.triangles.empty()) throw InputError("metrics: the mesh has no triangles");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        if (!is_finite(mesh.positions[i]))
            throw InputError("metrics: mesh vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
        for (std::uint32_t v : mesh.triangles[f])
            if (v >= mesh.positions.size())
                throw InputError("metrics: triangle " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                                 " of " + std::to_string(mesh.positions.size()));
}

// A triangle by the positions of its corners.
using Corners = std::array<Vec3, 3>;

bool position_less(const Vec3& a, const Vec3& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

// The triangles as corner positions in an order that depends only on the surface: each rotated
// to start at its smallest corner (x, then y, then z; the orientation kept), then sorted by
// their corners in that order. Another order of the triangles, another first corner or another
// numbering of the vertices give the same list.
std::vector<Corners> surface_order(const IndexedMesh& mesh) {
    std::vector<Corners> tris;
    tris.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        Corners c{mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
        int first = 0;
        for (int i = 1; i < 3; ++i)
            if (position_less(c[std::size_t(i)], c[std::size_t(first)])) first = i;
        std::rotate(c.begin(), c.begin() + first, c.end());
        tris.push_back(c);
    }
    std::sort(tris.begin(), tris.end(), [](const Corners& a, const Corners& b) {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end(), position_less);
    });
    return tris;
}

// The largest distance from the surface to the cloud, found to within `tol` of the true value
// by branch and bound over each triangle. For a piece of a triangle with centroid g, corners c_i
// and q the cloud point nearest to g, every point x of the piece is within max_i |c_i - q| of q
// (|x - q| is convex in x, so it peaks at a corner), and within d(g) + max_i |c_i - g| of the
// cloud (the distance to the cloud is 1-Lipschitz); the smaller bound is taken. A piece whose
// bound passes the largest distance found so far by more than tol is cut in four at its edge
// midpoints. A piece of circumradius at most tol never is (its Lipschitz bound is within tol of
// its centroid's distance), so the cuts end. `found`: a distance already measured on the
// surface (the samples' largest). Safety valve: after kMaxPiecesPerTriangle pieces per triangle
// on average (plus a fixed allowance), no piece is cut any more and the largest distance found
// is returned; on a surface at a near-constant distance from a sparse cloud the cuts could
// otherwise run to (area / tol^2) pieces.
double surface_to_cloud_max(const std::vector<Corners>& tris, PointSpan points, const PointGrid& cloud, double found,
                            double tol) {
    constexpr std::size_t kMaxPiecesPerTriangle = 256;
    const std::size_t budget = kMaxPiecesPerTriangle * tris.size() + (std::size_t(1) << 22);
    struct Piece {
        Vector3d a, b, c;
    };
    std::vector<Piece> stack;
    std::size_t pieces = 0;
    double best = found;
    for (const Corners& t : tris) {
        stack.push_back({to_eigen(t[0]), to_eigen(t[1]), to_eigen(t[2])});
        while (!stack.empty()) {
            const Piece s = stack.back();
            stack.pop_back();
            ++pieces;
            const Vector3d g = (s.a + s.b + s.c) / 3.0;
            const NearestPoint n = cloud.find_nearest(Vec3(float(g.x()), float(g.y()), float(g.z())));
            const double d = std::sqrt(double(n.squared_distance));
            best = std::max(best, d);
            const Vector3d q = to_eigen(points[n.index]);
            const double lipschitz =
                d + std::sqrt(std::max({(s.a - g).squaredNorm(), (s.b - g).squaredNorm(), (s.c - g).squaredNorm()}));
            const double convex =
                std::sqrt(std::max({(s.a - q).squaredNorm(), (s.b - q).squaredNorm(), (s.c - q).squaredNorm()}));
            if (std::min(lipschitz, convex) <= best + tol || pieces > budget) continue;
            const Vector3d ab = (s.a + s.b) * 0.5, bc = (s.b + s.c) * 0.5, ca = (s.c + s.a) * 0.5;
            stack.push_back({s.a, ab, ca});
            stack.push_back({ab, s.b, bc});
            stack.push_back({ca, bc, s.c});
            stack.push_back({ab, bc, ca});
        }
    }
    return best;
}

std::vector<Vec3> centroids(const IndexedMesh& mesh) {
    std::vector<Vec3> c;
    c.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles)
        c.push_back((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0f);
    return c;
}

}  // namespace

// ---- geometric primitives -----------------------------------------------------------------------

bool triangles_intersect(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e, const Vec3& f) {
    return triangles_intersect_exact(a, b, c, d, e, f);
}

double min_angle_deg(const Vec3& a_in, const Vec3& b_in, const Vec3& c_in) {
    const Vector3d p[3] = {to_eigen(a_in), to_eigen(b_in), to_eigen(c_in)};
    double smallest = kInf;
    for (int i = 0; i < 3; ++i) {
        const Vector3d u = p[(i + 1) % 3] - p[i], v = p[(i + 2) % 3] - p[i];
        smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
    }
    return smallest * (180.0 / kPi);
}

// ---- metrics ------------------------------------------------------------------------------------

double dm_cloud_to_centroids(PointSpan points, const IndexedMesh& mesh) {
    check_inputs(points, mesh);
    const PointGrid index(centroids(mesh));
    double sum = 0.0;
    for (const Vec3& p : points) sum += std::sqrt(double(index.nearest_squared_distance(p)));
    return sum / double(points.size());
}

std::vector<float> vertex_distances_to_cloud(PointSpan points, const IndexedMesh& mesh) {
    const PointGrid cloud(points);
    std::vector<float> d;
    d.reserve(mesh.positions.size());
    for (const Vec3& v : mesh.positions) d.push_back(std::sqrt(cloud.nearest_squared_distance(v)));
    return d;
}

QualityReport evaluate(PointSpan points, const IndexedMesh& mesh, const EvalOptions& options) {
    check_inputs(points, mesh);
    if (options.surface_samples == 0) throw ParameterError("surface_samples", "metrics: surface_samples must be at least 1");
    if (options.threads > kMaxThreads)
        throw ParameterError("threads", "metrics: threads must be in [0, " + std::to_string(kMaxThreads) + "], got " +
                                            std::to_string(options.threads));
    const std::uint32_t threads = options.threads;
    QualityReport r;
    r.vertices = mesh.positions.size();
    r.faces = mesh.triangles.size();
    r.bbox_diagonal = bounding_box(points).diagonal();

    // DM(X,T) and point-to-surface. The triangle with the nearest centroid gives each point an
    // upper bound that lets the hierarchy search prune from the start.
    // The points are measured a block at a time, each block's points on the threads, and the
    // sums taken in the points' order: the same bits for any number of threads.
    const PointGrid centroid_index(centroids(mesh));
    const TriangleBvh bvh(mesh);
    double dm_sum = 0.0, p2s_sum = 0.0, p2s_sq_sum = 0.0, p2s_max = 0.0;
    constexpr std::size_t kProgressMask = (std::size_t(1) << 18) - 1;
    std::vector<double> dm(std::min(kBlock, points.size())), p2s(dm.size());
    for (std::size_t first = 0; first < points.size(); first += kBlock) {
        if (options.progress && (first & kProgressMask) == 0 && first > 0)
            options.progress(double(first) / double(points.size()));
        const std::size_t count = std::min(kBlock, points.size() - first);
        for_chunks(count, kChunk, threads, [&](std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                const Vec3& p = points[first + k];
                const NearestPoint c = centroid_index.find_nearest(p);
                dm[k] = std::sqrt(double(c.squared_distance));
                const auto& t = mesh.triangles[c.index];
                const double bound =
                    point_triangle_squared_distance(p, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
                p2s[k] = bvh.nearest_squared_distance(p, bound);
            }
        });
        for (std::size_t k = 0; k < count; ++k) {
            dm_sum += dm[k];
            const double d2 = p2s[k];
            const double d = std::sqrt(d2);
            p2s_sum += d;
            p2s_sq_sum += d2;
            p2s_max = std::max(p2s_max, d);
        }
    }
    if (options.progress) options.progress(1.0);
    const double n = double(points.size());
    r.dm_x_t = dm_sum / n;
    r.p2s_mean = p2s_sum / n;
    r.p2s_rms = std::sqrt(p2s_sq_sum / n);
    r.p2s_max = p2s_max;

    // Surface-to-cloud. Systematic sampling by area: the samples sit at evenly spaced positions,
    // with a random offset, along the triangles' cumulated areas, so each is uniform over the
    // surface and their spread is even; within its triangle each sample is uniform. The
    // triangles are taken in an order that depends on the surface only (surface_order), so that
    // the same triangles listed otherwise give the same samples.
    {
        const std::size_t count = options.surface_samples;
        const std::vector<Corners> tris = surface_order(mesh);
        std::vector<double> cumulative(tris.size());
        double total = 0.0;
        for (std::size_t f = 0; f < tris.size(); ++f) {
            const Vector3d a = to_eigen(tris[f][0]);
            const Vector3d n = (to_eigen(tris[f][1]) - a).cross(to_eigen(tris[f][2]) - a);
            total += 0.5 * n.norm();
            cumulative[f] = total;
        }
        const PointGrid cloud(points);
        Random rng(options.seed);
        const double offset = rng.uniform();
        double sum = 0.0, worst = 0.0;
        std::size_t f = 0;
        // A block of samples drawn in turn, their distances found on the threads, summed in order.
        std::vector<Vec3> samples(std::min(kBlock, count));
        std::vector<double> distance(samples.size());
        for (std::size_t first = 0; first < count; first += kBlock) {
            const std::size_t block = std::min(kBlock, count - first);
            for (std::size_t k = 0; k < block; ++k) {
                const std::size_t i = first + k;
                if (total > 0.0) {
                    const double at = (offset + double(i)) / double(count) * total;
                    while (f + 1 < cumulative.size() && cumulative[f] <= at) ++f;
                } else {  // every triangle has zero area: take them in turn
                    f = i % tris.size();
                }
                const double root = std::sqrt(rng.uniform()), w = rng.uniform();
                const Corners& t = tris[f];
                const Vector3d q =
                    (1.0 - root) * to_eigen(t[0]) + root * (1.0 - w) * to_eigen(t[1]) + root * w * to_eigen(t[2]);
                samples[k] = Vec3(float(q.x()), float(q.y()), float(q.z()));
            }
            for_chunks(block, kChunk, threads, [&](std::size_t begin, std::size_t end) {
                for (std::size_t k = begin; k < end; ++k)
                    distance[k] = std::sqrt(double(cloud.nearest_squared_distance(samples[k])));
            });
            for (std::size_t k = 0; k < block; ++k) {
                sum += distance[k];
                worst = std::max(worst, distance[k]);
            }
        }
        r.s2p_mean = sum / double(count);
        // The largest distance, exact to within 1e-5 of the larger of the cloud's and the mesh's
        // bounding-box diagonals, the samples' largest as the starting point.
        const double extent = std::max(r.bbox_diagonal, bounding_box(mesh.positions).diagonal());
        r.s2p_max = surface_to_cloud_max(tris, points, cloud, worst, 1e-5 * extent);
    }
    r.hausdorff = std::max(r.p2s_max, r.s2p_max);

    // Relative values.
    const auto rel = [&](double d) {
        return r.bbox_diagonal > 0.0 ? d / r.bbox_diagonal : std::numeric_limits<double>::quiet_NaN();
    };
    r.dm_x_t_rel = rel(r.dm_x_t);
    r.p2s_mean_rel = rel(r.p2s_mean);
    r.p2s_rms_rel = rel(r.p2s_rms);
    r.p2s_max_rel = rel(r.p2s_max);
    r.s2p_mean_rel = rel(r.s2p_mean);
    r.s2p_max_rel = rel(r.s2p_max);
    r.hausdorff_rel = rel(r.hausdorff);

    // Topology.
    analyze_topology(mesh, r);
    r.boundary_length_rel = rel(r.boundary_length);
    std::vector<char> degenerate(mesh.triangles.size());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        degenerate[f] = is_degenerate(mesh, mesh.triangles[f]);
        r.degenerate_triangles += std::size_t(degenerate[f]);
    }
    r.self_intersections = count_self_intersections(mesh, threads);
    // Orientation: meaningful for a closed mesh only.
    r.signed_volume = signed_volume(mesh);
    r.inward_faces = r.closed ? inward_faces(mesh, bvh, threads) : 0;

    // Triangle quality.
    double angle_sum = 0.0, angle_min = kInf;
    std::size_t small = 0;
    for (const auto& t : mesh.triangles) {
        const double angle = min_angle_deg(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
        angle_sum += angle;
        angle_min = std::min(angle_min, angle);
        small += angle < kSmallAngleDeg;
    }
    r.min_angle_min_deg = angle_min;
    r.min_angle_mean_deg = angle_sum / double(mesh.triangles.size());
    r.share_under_10deg = double(small) / double(mesh.triangles.size());
    return r;
}

}  // namespace nmesh
