// nmesh/finish/hausdorff_estimate.h — the Hausdorff distance between a mesh and the cloud, as the repair estimates
// it to refuse a repair that would move the surface away from the cloud.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/finish/mesh_queries.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh {

namespace finish_detail {

// The Hausdorff distance between a mesh and the cloud, estimated from both sides: each cloud point
// measured against the triangles around its nearest vertex (never below its true distance to the
// surface), and the surface's largest distance to the cloud (see surface_side below). Taken once
// over a whole mesh, then, after the mesh has changed, only where it changed: elsewhere every term
// is what it was, so the larger of the new terms and the old estimate is the new estimate. O(n)
// for the whole mesh.
// Choice: for a cloud of more than kPointsPerVertex points per mesh vertex, the cloud's side
// measures every stride-th point only, the stride being the smallest that leaves at most
// kPointsPerVertex per vertex. The estimate guards the repair against moving the surface half an
// edge away from the cloud, which 16 points per vertex (about 8 per triangle) all around a change
// still see; the repair's cost then follows the mesh, not the cloud (36 million points would
// otherwise mean two passes of 36 million nearest-vertex queries). Up to that density every point
// is measured.
class HausdorffEstimate {
public:
    static constexpr std::size_t kPointsPerVertex = 16;
    // The surface's side is sampled finely enough to be within this many mean edge lengths of its
    // true value (see surface_side).
    static constexpr float kSurfaceTolerance = 0.125f;

    // `mean_edge`: the mesh's mean edge length.
    HausdorffEstimate(const Mesh& mesh, const CloudSurface& cloud, float mean_edge)
        : cloud_(cloud), tolerance_(kSurfaceTolerance * mean_edge) {
        const std::vector<Vertex> verts = alive_vertices(mesh);
        const std::unique_ptr<PointGrid> index = position_index(mesh, verts);
        const std::vector<Vec3>& points = cloud.points();
        const std::size_t most = kPointsPerVertex * std::max<std::size_t>(verts.size(), 1);
        stride_ = std::max<std::size_t>(1, (points.size() + most - 1) / most);
        nearest_.reserve(points.size() / stride_ + 1);
        for (std::size_t i = 0; i < points.size(); i += stride_) {
            const Vertex v = verts[index->nearest(points[i])];
            nearest_.push_back(v.idx);
            value_ = std::max(value_, distance_to_ring(mesh, v, points[i]));
        }
        // Each vertex's distance once, rather than once per triangle round it.
        std::vector<float> at_vertex(mesh.vertex_capacity(), 0.0f);
        for (const Vertex v : verts) at_vertex[v.idx] = to_cloud(mesh.position(v));
        value_ = surface_side(mesh, alive_faces(mesh), value_, &at_vertex);
    }

    float value() const { return value_; }

    // The estimate for `mesh`, which differs from the mesh given to the constructor only in the
    // triangles `changed` (and in triangles that no longer exist).
    float after(const Mesh& mesh, const std::vector<Face>& changed) const {
        // The changed triangles' corners, each with its distance to the cloud measured once (a
        // corner has about six triangles round it).
        std::vector<std::uint8_t> affected(mesh.vertex_capacity(), 0);
        std::vector<float> at_vertex(mesh.vertex_capacity(), 0.0f);
        for (const Face f : changed)
            if (!mesh.is_removed(f))
                for (const Vertex v : corners(mesh, f))
                    if (!affected[v.idx]) {
                        affected[v.idx] = 1;
                        at_vertex[v.idx] = to_cloud(mesh.position(v));
                    }
        float value = surface_side(mesh, changed, value_, &at_vertex);
        const std::vector<Vertex> verts = alive_vertices(mesh);
        const std::unique_ptr<PointGrid> index = position_index(mesh, verts);
        const std::vector<Vec3>& points = cloud_.points();
        for (std::size_t i = 0, k = 0; i < points.size(); i += stride_, ++k) {
            const Vertex v = verts[index->nearest(points[i])];
            // Unchanged: the same nearest vertex, with the same triangles around it.
            if (v.idx == nearest_[k] && !affected[v.idx]) continue;
            value = std::max(value, distance_to_ring(mesh, v, points[i]));
        }
        return value;
    }

private:
    // The largest distance to the cloud of the triangles `faces` (removed ones skipped), or
    // `value` if that is larger, within tolerance_ below the true figure (unless a triangle is
    // more than 2^16 tolerances long). The distance to the cloud changes by at most as much as the
    // point moves, so a triangle comes no farther than a bound from its corners' distances and its
    // longest edge; it is passed over when that does not exceed the largest distance found so far,
    // and cut up (sample_if_farther) otherwise. Most triangles are passed over after their
    // corners; the few that are cut up lie over holes in the scan.
    // Choice: measuring to a tolerance, not at fixed points (corners, edge midpoints, centroids),
    // makes the figure the same for the same surface however it is triangulated. A split of a
    // long edge at its midpoint, which leaves the surface as it was, used to raise the old figure
    // by finding a farther point on a triangle over a hole, and so to undo a repair that had
    // removed every defect (the bunny, 30,000 vertices, seed 9: 210 intersecting pairs kept).
    // `at_vertex`: the vertices' distances to the cloud, by vertex id, when already known.
    float surface_side(const Mesh& mesh, const std::vector<Face>& faces, float value,
                       const std::vector<float>* at_vertex = nullptr) const {
        for (const Face f : faces) {
            if (mesh.is_removed(f)) continue;
            const std::array<Vertex, 3> c = corners(mesh, f);
            float d[3];
            for (int k = 0; k < 3; ++k)
                value = std::max(value, d[k] = at_vertex ? (*at_vertex)[c[k].idx] : to_cloud(mesh.position(c[k])));
            value = sample_if_farther(mesh, c, d, value);
        }
        return value;
    }
    // The triangle with corners c, at distances d from the cloud, for surface_side: the largest
    // distance found on it, or `value` if that is larger. Branch and bound: a triangle whose
    // bound does not exceed `value` is passed over; any other is cut into four at its edges'
    // midpoints (which are measured), down to triangles whose edges are at most tolerance_
    // (every point of those lies within tolerance_ of a measured corner).
    float sample_if_farther(const Mesh& mesh, const std::array<Vertex, 3>& c, const float (&d)[3], float value) const {
        struct Piece {
            Vec3 p[3];
            float d[3];
            int depth;
        };
        constexpr int kMaxDepth = 16;  // also bounds the pieces pending: 3 per level, plus 4
        Piece stack[3 * kMaxDepth + 4];
        int top = 0;
        stack[top++] = {{mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])}, {d[0], d[1], d[2]}, 0};
        while (top > 0) {
            const Piece t = stack[--top];
            const float longest =
                std::sqrt(std::max({squared_distance(t.p[0], t.p[1]), squared_distance(t.p[1], t.p[2]),
                                    squared_distance(t.p[2], t.p[0])}));
            // A point of the triangle lies within `longest` of every corner, and within
            // longest / sqrt(3) of the nearest one; the distance to the cloud grows by at most as
            // much as the point moves.
            const float bound = std::min(std::min({t.d[0], t.d[1], t.d[2]}) + longest,
                                         std::max({t.d[0], t.d[1], t.d[2]}) + longest * 0.57736f);
            if (bound <= value || longest <= tolerance_ || t.depth == kMaxDepth) continue;
            Vec3 m[3];
            float dm[3];
            for (int k = 0; k < 3; ++k) {
                m[k] = (t.p[k] + t.p[(k + 1) % 3]) * 0.5f;
                value = std::max(value, dm[k] = to_cloud(m[k]));
            }
            // m[k] is the midpoint of the edge from corner k to corner k + 1.
            stack[top++] = {{t.p[0], m[0], m[2]}, {t.d[0], dm[0], dm[2]}, t.depth + 1};
            stack[top++] = {{m[0], t.p[1], m[1]}, {dm[0], t.d[1], dm[1]}, t.depth + 1};
            stack[top++] = {{m[2], m[1], t.p[2]}, {dm[2], dm[1], t.d[2]}, t.depth + 1};
            stack[top++] = {{m[0], m[1], m[2]}, {dm[0], dm[1], dm[2]}, t.depth + 1};
        }
        return value;
    }
    float to_cloud(const Vec3& p) const { return std::sqrt(cloud_.index().nearest_squared_distance(p)); }

    const CloudSurface& cloud_;
    float tolerance_;
    std::size_t stride_ = 1;
    std::vector<std::uint32_t> nearest_;  // per measured cloud point, its nearest vertex
    float value_ = 0.0f;
};

}  // namespace finish_detail

// The Hausdorff distance between `mesh` and the cloud of `surface` as the repair estimates it, to
// refuse a repair that would move the surface away from the cloud: the larger of (a) the distance
// from each measured cloud point to the triangles around its nearest vertex and (b) the surface's
// largest distance to the cloud, measured to within an eighth of the mean edge length. Every cloud point is
// measured up to 16 points per mesh vertex; beyond, every s-th point, s the smallest stride that
// leaves at most 16 per vertex, so that the cost follows the mesh. O(m) for m vertices.
float estimate_hausdorff(const Mesh& mesh, const CloudSurface& surface);

}  // namespace nmesh
