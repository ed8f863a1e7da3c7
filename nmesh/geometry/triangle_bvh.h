// nmesh/geometry/triangle_bvh.h — a bounding-volume hierarchy over the triangles of a mesh: the
// nearest triangle to a point, and every pair of triangles whose boxes overlap.
#pragma once

#include <algorithm>
#include <array>
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
        nodes_.reserve(2 * (f / kLeafSize + 1));
        nodes_.emplace_back();
        build(0, 0, std::uint32_t(f));
    }

    // Squared distance from p to the nearest triangle, given an upper bound on it (infinity if none).
    double nearest_squared_distance(const Vec3& p, double bound) const {
        double best = bound;
        // Each entry keeps its box's distance, computed when it was pushed: on popping, the best
        // may since have dropped below it.
        struct Entry {
            std::uint32_t node;
            double box_distance;
        };
        Entry stack[64];
        int top = 0;
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
                    const double d = point_triangle_squared_distance(
                        p, mesh_.positions[t[0]], mesh_.positions[t[1]], mesh_.positions[t[2]]);
                    best = std::min(best, d);
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

    // Calls visit(s, t) once for every unordered pair of distinct triangles whose boxes overlap.
    template <class Visit>
    void for_each_overlapping_pair(Visit&& visit) const {
        self_pairs(0, visit);
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
            const double g = x < double(b.min[a]) ? double(b.min[a]) - x
                                                  : (x > double(b.max[a]) ? x - double(b.max[a]) : 0.0);
            d2 += g * g;
        }
        return d2;
    }

    static bool boxes_overlap(const BoundingBox& a, const BoundingBox& b) {
        return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
               a.min.z <= b.max.z && b.min.z <= a.max.z;
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
                         [&](std::uint32_t s, std::uint32_t t) {
                             return centroids_[s][axis] < centroids_[t][axis];
                         });
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

    template <class Visit>
    void leaf_pairs(const Node& a, const Node& b, Visit& visit) const {
        for (std::uint32_t i = a.first; i < a.first + a.count; ++i)
            for (std::uint32_t j = b.first; j < b.first + b.count; ++j)
                if (boxes_overlap(boxes_[order_[i]], boxes_[order_[j]])) visit(order_[i], order_[j]);
    }

    template <class Visit>
    void self_pairs(std::uint32_t node, Visit& visit) const {
        const Node& n = nodes_[node];
        if (n.count > 0) {
            for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
                for (std::uint32_t j = i + 1; j < n.first + n.count; ++j)
                    if (boxes_overlap(boxes_[order_[i]], boxes_[order_[j]])) visit(order_[i], order_[j]);
            return;
        }
        self_pairs(n.first, visit);
        self_pairs(n.first + 1, visit);
        cross_pairs(n.first, n.first + 1, visit);
    }

    template <class Visit>
    void cross_pairs(std::uint32_t a, std::uint32_t b, Visit& visit) const {
        const Node& na = nodes_[a];
        const Node& nb = nodes_[b];
        if (!boxes_overlap(na.box, nb.box)) return;
        if (na.count > 0 && nb.count > 0) {
            leaf_pairs(na, nb, visit);
        } else if (na.count > 0) {
            cross_pairs(a, nb.first, visit);
            cross_pairs(a, nb.first + 1, visit);
        } else {
            cross_pairs(na.first, b, visit);
            cross_pairs(na.first + 1, b, visit);
        }
    }

    const IndexedMesh& mesh_;
    std::vector<BoundingBox> boxes_;  // per triangle
    std::vector<Vec3> centroids_;     // per triangle, of its box
    std::vector<std::uint32_t> order_;
    std::vector<Node> nodes_;
};

}  // namespace nmesh
