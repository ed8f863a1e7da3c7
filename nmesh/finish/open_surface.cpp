#include "nmesh/finish/open_surface.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace nmesh {
namespace {

struct FaceGeometry {
    Vec3 centroid, normal;  // unit normal (zero for a degenerate face)
    float area = 0.0f, mean_edge = 0.0f;
};

FaceGeometry geometry(const Mesh& m, Face f) {
    const Halfedge h = m.halfedge(f);
    const Vec3 a = m.position(m.from(h)), b = m.position(m.to(h)), c = m.position(m.to(m.next(h)));
    FaceGeometry g;
    g.centroid = (a + b + c) * (1.0f / 3.0f);
    const Vec3 n = cross(b - a, c - a);
    g.area = 0.5f * norm(n);
    g.normal = normalized(n);
    g.mean_edge = (distance(a, b) + distance(b, c) + distance(c, a)) / 3.0f;
    return g;
}

// The least-variance axis of the points: the direction a sheet of them is thinnest in, its sign
// fixed so that its largest component is positive.
Vec3 thinnest_axis(const std::vector<Vec3>& points) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Vec3& p : points) mean += Eigen::Vector3d(p.x, p.y, p.z);
    mean /= double(std::max<std::size_t>(points.size(), 1));
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& p : points) {
        const Eigen::Vector3d d = Eigen::Vector3d(p.x, p.y, p.z) - mean;
        cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    Eigen::Vector3d axis = solver.eigenvectors().col(0);  // eigenvalues ascending
    int largest = 0;
    for (int i = 1; i < 3; ++i)
        if (std::fabs(axis[i]) > std::fabs(axis[largest])) largest = i;
    if (axis[largest] < 0) axis = -axis;
    return {float(axis.x()), float(axis.y()), float(axis.z())};
}

// Removes the marked faces, region by region: each region from its face of largest `priority`,
// then pass after pass every marked face beside a hole that can go. Returns the faces removed.
std::uint32_t remove_marked(Mesh& m, std::vector<char>& marked, const std::vector<float>& priority) {
    std::vector<std::uint32_t> order;
    for (std::uint32_t f = 0; f < marked.size(); ++f)
        if (marked[f]) order.push_back(f);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return priority[a] != priority[b] ? priority[a] > priority[b] : a < b;
    });
    std::uint32_t removed = 0;
    for (bool progress = true; progress;) {
        progress = false;
        // Widen the holes first, so that a region is opened once, from its farthest face.
        for (int opening = 0; opening < 2; ++opening)
            for (std::uint32_t f : order) {
                const Face face(f);
                if (m.is_removed(face)) continue;
                if (m.beside_boundary(face) == bool(opening) || !m.can_remove_face(face)) continue;
                m.remove_face(face);
                ++removed;
                progress = true;
                if (opening) break;  // one new hole, then widen it
            }
    }
    for (std::uint32_t f : order) marked[f] = !m.is_removed(Face(f));
    return removed;
}

// Unmarks the edge-connected regions of marked faces that have fewer than `least` faces, unless
// one of their faces has a `value` of at least `enough` (given values); returns the faces left
// marked.
std::uint32_t keep_large_regions(const Mesh& mesh, std::vector<char>& marked, std::size_t least,
                                 const std::vector<float>* value = nullptr, float enough = 0.0f) {
    const std::uint32_t nf = mesh.face_capacity();
    std::vector<char> seen(nf, 0);
    std::vector<std::uint32_t> region, stack;
    std::uint32_t kept = 0;
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (!marked[f] || seen[f]) continue;
        region.clear();
        stack.assign(1, f);
        seen[f] = 1;
        while (!stack.empty()) {
            const std::uint32_t x = stack.back();
            stack.pop_back();
            region.push_back(x);
            for (Halfedge h = mesh.halfedge(Face(x)), s = h;;) {
                const Face u = mesh.face(Mesh::twin(h));
                if (u.valid() && marked[u.idx] && !seen[u.idx]) seen[u.idx] = 1, stack.push_back(u.idx);
                if ((h = mesh.next(h)) == s) break;
            }
        }
        bool strong = false;
        for (std::uint32_t x : region) strong = strong || (value && (*value)[x] >= enough);
        if (region.size() < least && !strong)
            for (std::uint32_t x : region) marked[x] = 0;
        else
            kept += std::uint32_t(region.size());
    }
    return kept;
}

// The faces' geometry and the scales both parts measure against.
struct Scales {
    std::vector<FaceGeometry> g;
    float mean_edge = 0.0f, typical_edge = 0.0f, spacing = 0.0f;
};

Scales measure(const Mesh& mesh, const PointGrid& cloud) {
    Scales sc;
    const std::uint32_t nf = mesh.face_capacity();
    sc.g.resize(nf);
    std::vector<FaceGeometry>& g = sc.g;
    double area = 0.0, edges = 0.0;
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (mesh.is_removed(Face(f))) continue;
        g[f] = geometry(mesh, Face(f));
        area += g[f].area;
        edges += g[f].mean_edge;
    }
    sc.mean_edge = float(edges / mesh.n_faces());
    // The typical edge: the median of the faces' mean edges (the big faces spanning a hole, which
    // no sample refines, do not count more than their number).
    std::vector<float> sizes;
    for (std::uint32_t f = 0; f < nf; ++f)
        if (!mesh.is_removed(Face(f))) sizes.push_back(g[f].mean_edge);
    std::nth_element(sizes.begin(), sizes.begin() + std::ptrdiff_t(sizes.size() / 2), sizes.end());
    sc.typical_edge = sizes[sizes.size() / 2];
    sc.spacing = float(std::sqrt(area / double(cloud.size())));
    return sc;
}

}  // namespace

OpenReport remove_double_layers(Mesh& mesh, const PointGrid& cloud) {
    OpenReport out;
    if (!mesh.has_faces() || cloud.size() == 0 || mesh.n_faces() == 0) return out;
    const std::uint32_t nf = mesh.face_capacity();
    const Scales sc = measure(mesh, cloud);
    const std::vector<FaceGeometry>& g = sc.g;
    const float mean_edge = sc.mean_edge, spacing = sc.spacing;
    // Face centroids hashed in cells of the reach.
    const float reach = kLayerReach * mean_edge, gap = kLayerGap * spacing;
    const float cell = std::max(reach, 1e-12f);
    auto key_of = [&](const Vec3& p, int dx, int dy, int dz) {
        const auto k = [&](float v, int d) { return std::int64_t(std::floor(v / cell)) + d; };
        return (std::uint64_t(k(p.x, dx) & 0x1fffff) << 42) | (std::uint64_t(k(p.y, dy) & 0x1fffff) << 21) |
               std::uint64_t(k(p.z, dz) & 0x1fffff);
    };
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
    for (std::uint32_t f = 0; f < nf; ++f)
        if (!mesh.is_removed(Face(f))) cells[key_of(g[f].centroid, 0, 0, 0)].push_back(f);
    std::vector<char> layered(nf, 0);
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (mesh.is_removed(Face(f)) || g[f].area == 0.0f) continue;
        for (int d = 0; d < 27 && !layered[f]; ++d) {
            const auto it = cells.find(key_of(g[f].centroid, d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1));
            if (it == cells.end()) continue;
            for (std::uint32_t u : it->second) {
                if (u == f || dot(g[f].normal, g[u].normal) > -0.7f) continue;
                const Vec3 off = g[u].centroid - g[f].centroid;
                if (squared_norm(off) > reach * reach || std::fabs(dot(off, g[f].normal)) > gap) continue;
                layered[f] = 1;
                break;
            }
        }
    }
    // Only sheets: edge-connected regions of at least kLayerMinShare of the faces (a fold of the
    // learnt mesh, or the two sides of a thin part touching, is a few faces).
    out.double_layer_faces =
        keep_large_regions(mesh, layered, std::max<std::size_t>(64, std::size_t(kLayerMinShare * mesh.n_faces())));
    if (out.double_layer_faces > 0) {
        // Which layer goes: the faces facing away from the thinnest axis, the decision smoothed by
        // three rounds of majority among each face and its double-layer neighbours.
        const Vec3 axis = thinnest_axis(cloud.indexed_points());
        std::vector<char> drop(nf, 0), next(nf, 0);
        for (std::uint32_t f = 0; f < nf; ++f) drop[f] = layered[f] && dot(g[f].normal, axis) < 0.0f;
        for (int round = 0; round < 3; ++round) {
            for (std::uint32_t f = 0; f < nf; ++f) {
                if (!layered[f]) continue;
                int votes = drop[f] ? 1 : -1;
                for (Halfedge h = mesh.halfedge(Face(f)), s = h;;) {
                    const Face u = mesh.face(Mesh::twin(h));  // none across a boundary
                    if (u.valid() && layered[u.idx]) votes += drop[u.idx] ? 1 : -1;
                    if ((h = mesh.next(h)) == s) break;
                }
                next[f] = votes > 0;
            }
            drop.swap(next);
        }
        std::vector<float> priority(nf, 0.0f);
        for (std::uint32_t f = 0; f < nf; ++f) priority[f] = -dot(g[f].normal, axis);
        out.removed_layer = remove_marked(mesh, drop, priority);
    }

    return out;
}

OpenReport open_unsupported(Mesh& mesh, const PointGrid& cloud) {
    OpenReport out;
    if (!mesh.has_faces() || cloud.size() == 0 || mesh.n_faces() == 0) return out;
    const std::uint32_t nf = mesh.face_capacity();
    const Scales sc = measure(mesh, cloud);
    const float typical_edge = sc.typical_edge, spacing = sc.spacing;
    std::vector<char> far(nf, 0);
    std::vector<float> away(nf, 0.0f);
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (mesh.is_removed(Face(f))) continue;
        const Vec3 c = sc.g[f].centroid;
        away[f] = std::sqrt(cloud.nearest_squared_distance(c));
        far[f] = away[f] > std::max(kOpenEdges * typical_edge, kOpenSpacings * spacing);
    }
    // A hole is a region of kOpenMinFaces or more, or one reaching kOpenDeep times the limit from
    // the cloud (a face or two just off the cloud is a defect of the reconstruction, not a hole).
    const float limit = std::max(kOpenEdges * typical_edge, kOpenSpacings * spacing);
    out.unsupported_faces = keep_large_regions(mesh, far, kOpenMinFaces, &away, kOpenDeep * limit);
    out.removed_unsupported = remove_marked(mesh, far, away);
    return out;
}

}  // namespace nmesh
