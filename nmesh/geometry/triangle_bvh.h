// nmesh/geometry/triangle_bvh.h — a bounding-volume hierarchy over the triangles of a mesh: the
// nearest triangle to a point, and the triangles along a ray.
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/geometry/closest_point.h"
#include "nmesh/indexed_mesh.h"

namespace nmesh {

// A bounding-volume hierarchy over the triangles of a mesh, split at the median centroid along the
// widest axis: O(F log F) to build, about O(log F) per nearest-triangle query.
class TriangleBvh {
public:
    // Triangles per leaf: few enough that a leaf's distances are cheap, enough that the tree
    // stays shallow.
    static constexpr std::uint32_t kLeafSize = 4;

    explicit TriangleBvh(const IndexedMesh& mesh) : mesh_(mesh) {
        const std::size_t f = mesh.triangles.size();
        boxes_.resize(f);
        centroids_.resize(f);
        order_.resize(f);
        for (std::uint32_t t = 0; t < f; ++t) {
            const auto& tri = mesh.triangles[t];
            BoundingBox b;
            b.min = b.max = mesh.positions[tri[0]];
            b = united(b, BoundingBox{mesh.positions[tri[1]], mesh.positions[tri[1]]});
            b = united(b, BoundingBox{mesh.positions[tri[2]], mesh.positions[tri[2]]});
            boxes_[t] = b;
            centroids_[t] = b.center();
            order_[t] = t;
        }
        if (f == 0) return;  // no triangle: every query finds none
        nodes_.reserve(2 * (f / kLeafSize + 1));
        nodes_.emplace_back();
        build(0, 0, std::uint32_t(f));
    }

    // Squared distance from p to the nearest triangle, given an upper bound on it (infinity if none).
    double nearest_squared_distance(const Vec3& p, double bound) const {
        std::uint32_t unused;
        return nearest(p, bound, unused);
    }
    // The same, and the nearest triangle in `triangle` (unchanged when none is nearer than bound;
    // ties go to the triangle met first).
    double nearest(const Vec3& p, double bound, std::uint32_t& triangle) const {
        double best = bound;
        // Each entry keeps its box's distance, computed when it was pushed: on popping, the best
        // may since have dropped below it.
        struct Entry {
            std::uint32_t node;
            double box_distance;
        };
        Entry stack[64];
        int top = 0;
        if (nodes_.empty()) return best;
        stack[top++] = {0, box_squared_distance(nodes_[0].box, p)};
        while (top > 0) {
            const Entry e = stack[--top];
            if (e.box_distance > best) continue;
            const Node& n = nodes_[e.node];
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
                    // A triangle whose box is farther than the best cannot be nearer.
                    if (box_squared_distance(boxes_[order_[i]], p) > best) continue;
                    const auto& t = mesh_.triangles[order_[i]];
                    const double d = point_triangle_squared_distance(p, mesh_.positions[t[0]], mesh_.positions[t[1]],
                                                                     mesh_.positions[t[2]]);
                    if (d < best) best = d, triangle = order_[i];
                }
                continue;
            }
            // Children: the nearer is pushed last, so it is searched first.
            const std::uint32_t l = n.first, r = n.first + 1;
            const double dl = box_squared_distance(nodes_[l].box, p);
            const double dr = box_squared_distance(nodes_[r].box, p);
            assert(top + 2 <= 64);
            if (dl <= dr) {
                if (dr <= best) stack[top++] = {r, dr};
                if (dl <= best) stack[top++] = {l, dl};
            } else {
                if (dl <= best) stack[top++] = {l, dl};
                if (dr <= best) stack[top++] = {r, dr};
            }
        }
        return best;
    }

    // Calls visit(t) for every triangle whose box the ray from `origin` along +x meets (a superset
    // of the triangles the ray crosses).
    template <class Visit>
    void for_each_on_ray_x(const Vec3& origin, Visit&& visit) const {
        if (nodes_.empty() || mesh_.triangles.empty()) return;
        std::uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        const auto meets = [&](const BoundingBox& b) {
            return b.max.x >= origin.x && b.min.y <= origin.y && origin.y <= b.max.y && b.min.z <= origin.z &&
                   origin.z <= b.max.z;
        };
        while (top > 0) {
            const Node& n = nodes_[stack[--top]];
            if (!meets(n.box)) continue;
            if (n.count > 0) {
                for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
                    if (meets(boxes_[order_[i]])) visit(order_[i]);
                continue;
            }
            assert(top + 2 <= 64);
            stack[top++] = n.first;
            stack[top++] = n.first + 1;
        }
    }

private:
    struct Node {
        BoundingBox box;
        std::uint32_t first = 0;  // leaf: first entry of order_; inner: index of the left child
        std::uint32_t count = 0;  // leaf: number of triangles; 0 for an inner node
    };

    static double box_squared_distance(const BoundingBox& b, const Vec3& p) {
        double d2 = 0.0;
        for (int a = 0; a < 3; ++a) {
            const double x = double(p[a]);
            const double g =
                x < double(b.min[a]) ? double(b.min[a]) - x : (x > double(b.max[a]) ? x - double(b.max[a]) : 0.0);
            d2 += g * g;
        }
        return d2;
    }

    // Builds the subtree of `node` over order_[first, last) and sets its box.
    void build(std::uint32_t node, std::uint32_t first, std::uint32_t last) {
        if (last - first <= kLeafSize) {
            BoundingBox box = boxes_[order_[first]];
            for (std::uint32_t i = first + 1; i < last; ++i) box = united(box, boxes_[order_[i]]);
            nodes_[node].box = box;
            nodes_[node].first = first;
            nodes_[node].count = last - first;
            return;
        }
        Vec3 lo = centroids_[order_[first]], hi = lo;
        for (std::uint32_t i = first + 1; i < last; ++i) {
            const Vec3& c = centroids_[order_[i]];
            for (int a = 0; a < 3; ++a) {
                lo[a] = c[a] < lo[a] ? c[a] : lo[a];
                hi[a] = c[a] > hi[a] ? c[a] : hi[a];
            }
        }
        const Vec3 e = hi - lo;
        const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
        const std::uint32_t mid = first + (last - first) / 2;
        std::nth_element(order_.begin() + first, order_.begin() + mid, order_.begin() + last,
                         [&](std::uint32_t s, std::uint32_t t) { return centroids_[s][axis] < centroids_[t][axis]; });
        const std::uint32_t left = std::uint32_t(nodes_.size());
        nodes_.emplace_back();
        nodes_.emplace_back();
        nodes_[node].first = left;
        nodes_[node].count = 0;
        build(left, first, mid);
        build(left + 1, mid, last);
        nodes_[node].box = united(nodes_[left].box, nodes_[left + 1].box);
    }

    static BoundingBox united(const BoundingBox& a, const BoundingBox& b) {
        BoundingBox u;
        for (int i = 0; i < 3; ++i) {
            u.min[i] = a.min[i] < b.min[i] ? a.min[i] : b.min[i];
            u.max[i] = a.max[i] > b.max[i] ? a.max[i] : b.max[i];
        }
        return u;
    }

    const IndexedMesh& mesh_;
    std::vector<BoundingBox> boxes_;  // per triangle
    std::vector<Vec3> centroids_;     // per triangle, of its box
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
};

}  // namespace nmesh
