#include "nmesh/finish/open_surface.h"

#include "nmesh/finish/cloud_rim.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
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

// Removes the marked faces one at a time, each behind Mesh::can_remove_face, so that the mesh
// stays connected: each region from its face of largest `priority`, then pass after pass every
// marked face beside a hole that can go (a face that cannot stays). Returns the faces removed.
std::uint32_t remove_one_by_one(Mesh& m, std::vector<char>& marked, const std::vector<float>& priority) {
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

// Unmarks the edge-connected regions of marked faces that `keep(region)` refuses; returns the
// faces left marked.
template <class Keep>
std::uint32_t keep_regions(const Mesh& mesh, std::vector<char>& marked, Keep&& keep) {
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
        if (keep(region))
            kept += std::uint32_t(region.size());
        else
            for (std::uint32_t x : region) marked[x] = 0;
    }
    return kept;
}

// The share of the points on the rim where the cloud is flat: the measure of a partial view.
float flat_rim_share(const CloudRim& cr) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < cr.rim.size(); ++i) n += std::size_t(cr.rim[i] && cr.flat[i]);
    return cr.rim.empty() ? 0.0f : float(n) / float(cr.rim.size());
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

IndexedMesh cut_faces(const Mesh& m, const std::vector<char>& marked, std::uint32_t& removed) {
    removed = 0;
    const std::uint32_t nf = m.face_capacity(), nv = m.vertex_capacity();
    std::vector<char> gone(nf, 0);
    bool any = false;
    for (std::uint32_t f = 0; f < nf; ++f) {
        gone[f] = !m.is_removed(Face(f)) && marked[f];
        any = any || gone[f];
    }
    if (!any) return m.to_indexed();
    // The closure: vertex by vertex, until no vertex has two kept fans.
    std::vector<std::uint32_t> ring;  // the faces round a vertex, clockwise; kInvalidIndex for a gap
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (bool changed = true; changed;) {
        changed = false;
        for (std::uint32_t v = 0; v < nv; ++v) {
            if (m.is_removed(Vertex(v))) continue;
            ring.clear();
            bool touched = false;
            m.for_each_outgoing_cw(Vertex(v), [&](Halfedge h) {
                const Face f = m.face(h);
                ring.push_back(f.valid() ? f.idx : kInvalidIndex);
                touched = touched || (f.valid() && gone[f.idx]);
            });
            if (!touched) continue;
            // The runs of kept faces, cyclically, starting after a face that is not kept.
            const std::size_t k = ring.size();
            auto kept = [&](std::size_t i) { return ring[i % k] != kInvalidIndex && !gone[ring[i % k]]; };
            std::size_t first = 0;
            while (first < k && kept(first)) ++first;
            runs.clear();
            for (std::size_t i = first + 1; i <= first + k; ++i) {
                if (!kept(i)) continue;
                const std::size_t begin = i;
                while (i <= first + k && kept(i)) ++i;
                runs.push_back({begin, i});
            }
            if (runs.size() < 2) continue;
            std::size_t longest = 0;
            for (std::size_t r = 1; r < runs.size(); ++r)
                if (runs[r].second - runs[r].first > runs[longest].second - runs[longest].first) longest = r;
            for (std::size_t r = 0; r < runs.size(); ++r)
                if (r != longest)
                    for (std::size_t i = runs[r].first; i < runs[r].second; ++i) gone[ring[i % k]] = 1;
            changed = true;
        }
    }
    // The edge-connected pieces of the kept faces; the small ones go.
    std::vector<char> seen(nf, 0);
    std::vector<std::uint32_t> piece, stack;
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (m.is_removed(Face(f)) || gone[f] || seen[f]) continue;
        piece.clear();
        seen[f] = 1;
        stack.assign(1, f);
        while (!stack.empty()) {
            const std::uint32_t x = stack.back();
            stack.pop_back();
            piece.push_back(x);
            for (Halfedge h = m.halfedge(Face(x)), s = h;;) {
                const Face u = m.face(Mesh::twin(h));
                if (u.valid() && !gone[u.idx] && !seen[u.idx]) seen[u.idx] = 1, stack.push_back(u.idx);
                if ((h = m.next(h)) == s) break;
            }
        }
        if (piece.size() < kOpenMinFaces)
            for (std::uint32_t x : piece) gone[x] = 1;
    }
    IndexedMesh out;
    std::vector<std::uint32_t> index(nv, kInvalidIndex);
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (m.is_removed(Face(f))) continue;
        if (gone[f]) {
            ++removed;
            continue;
        }
        std::array<std::uint32_t, 3> t{};
        Halfedge h = m.halfedge(Face(f));
        for (int i = 0; i < 3; ++i, h = m.next(h)) {
            const std::uint32_t v = m.from(h).idx;
            if (index[v] == kInvalidIndex) {
                index[v] = std::uint32_t(out.positions.size());
                out.positions.push_back(m.position(Vertex(v)));
            }
            t[std::size_t(i)] = index[v];
        }
        out.triangles.push_back(t);
    }
    return out;
}

OpenReport remove_double_layers(Mesh& mesh, const PointGrid& cloud) {
    OpenReport out;
    if (!mesh.has_faces() || cloud.size() == 0 || mesh.n_faces() == 0) return out;
    const std::uint32_t nf = mesh.face_capacity();
    const Scales sc = measure(mesh, cloud);
    const std::vector<FaceGeometry>& g = sc.g;
    const float mean_edge = sc.mean_edge, spacing = sc.spacing;
    const std::vector<Vec3> points = cloud.indexed_points();
    const CloudRim cr = cloud_rim(points, spacing);
    out.rim_share = flat_rim_share(cr);
    // Only on a partial view: a closed object's thin parts and the learning's own folds are two
    // opposite sheets close together too.
    if (out.rim_share < kViewRimShare) return out;
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
    const std::size_t least = std::max<std::size_t>(64, std::size_t(kLayerMinShare * mesh.n_faces()));
    out.double_layer_faces =
        keep_regions(mesh, layered, [&](const std::vector<std::uint32_t>& region) { return region.size() >= least; });
    if (out.double_layer_faces > 0) {
        // Which layer goes: the faces facing away from the thinnest axis, the decision smoothed by
        // three rounds of majority among each face and its double-layer neighbours.
        const Vec3 axis = thinnest_axis(points);
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
        out.removed_layer = remove_one_by_one(mesh, drop, priority);
    }

    return out;
}

IndexedMesh cut_unsupported(const Mesh& mesh, const PointGrid& cloud, OpenReport& report) {
    if (!mesh.has_faces() || cloud.size() == 0 || mesh.n_faces() == 0) return mesh.to_indexed();
    const std::uint32_t nf = mesh.face_capacity();
    const Scales sc = measure(mesh, cloud);
    const float limit = std::max(kOpenEdges * sc.typical_edge, kOpenSpacings * sc.spacing);
    const std::vector<Vec3> points = cloud.indexed_points();
    const CloudRim cr = cloud_rim(points, sc.spacing);
    const std::vector<char>& rim = cr.rim;
    std::vector<char> far(nf, 0);
    std::vector<float> away(nf, 0.0f);
    std::vector<Vec3> rim_at;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (rim[i]) rim_at.push_back(points[i]);
    report.rim_share = flat_rim_share(cr);
    const bool view = report.rim_share >= kViewRimShare;
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (mesh.is_removed(Face(f))) continue;
        const NearestPoint p = cloud.find_nearest(sc.g[f].centroid);
        away[f] = std::sqrt(p.squared_distance);
        far[f] = away[f] > std::max(kOpenEdges * sc.typical_edge, kOpenSpacings * cr.spacing[p.index]);
    }
    // Which regions of far faces are holes in the scan (see open_surface.h): measured round the
    // region's deepest face, within kOpenRimReach times its distance to the cloud.
    report.unsupported_faces = keep_regions(mesh, far, [&](const std::vector<std::uint32_t>& region) {
        std::uint32_t deepest = region.front();
        for (std::uint32_t f : region)
            if (away[f] > away[deepest]) deepest = f;
        const float depth = away[deepest] / limit;
        if (depth < std::min(kOpenHoleDepth, kOpenEndDepth)) return false;
        const Vec3 c = sc.g[deepest].centroid;
        const float reach = kOpenRimReach * away[deepest] + limit;
        std::vector<Vec3> ring;  // the rim points in reach
        for (const Vec3& p : rim_at)
            if (squared_distance(p, c) <= reach * reach) ring.push_back(p);
        if (ring.empty()) return false;
        std::size_t all = 0;
        for (const Vec3& p : points) all += std::size_t(squared_distance(p, c) <= reach * reach);
        // Round the face: the largest angle the rim points leave free, seen along its normal.
        const Vec3 n = sc.g[deepest].normal;
        const Vec3 u = normalized(cross(n, std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
        const bool surrounded = largest_gap(c, ring, u, cross(n, u)) < kOpenSurroundGap;
        const bool hole = surrounded && depth >= kOpenHoleDepth;
        const bool end = view && depth >= kOpenEndDepth && float(ring.size()) >= kOpenRimShare * float(all);
        return hole || end;
    });
    return cut_faces(mesh, far, report.removed_unsupported);
}

}  // namespace nmesh
