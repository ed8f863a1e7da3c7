#include "nmesh/finish/open_surface.h"

#include "nmesh/finish/cloud_layers.h"

#include "nmesh/finish/cloud_normals.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/face_regions.h"
#include "nmesh/mesh/mesh_pieces.h"

#include <algorithm>
#include <array>
#include <cmath>
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

// Unmarks the edge-connected regions of marked faces that `keep(region)` refuses; returns the
// faces left marked.
template <class Keep>
std::uint32_t keep_regions(const Mesh& mesh, std::vector<char>& marked, Keep&& keep) {
    std::uint32_t kept = 0;
    for_each_face_region(mesh, [&](std::uint32_t f) { return marked[f] != 0; },
                         [&](const std::vector<std::uint32_t>& region) {
                             if (keep(region))
                                 kept += std::uint32_t(region.size());
                             else
                                 for (std::uint32_t x : region) marked[x] = 0;
                         });
    return kept;
}

// The share of the points on the rim where the cloud is flat: the measure of a partial view.
float flat_rim_share(const CloudRim& cr) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < cr.rim.size(); ++i) n += std::size_t(cr.rim[i] && cr.flat[i]);
    return cr.rim.empty() ? 0.0f : float(n) / float(cr.rim.size());
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
    for_each_face_region(m, [&](std::uint32_t f) { return !gone[f]; }, [&](const std::vector<std::uint32_t>& piece) {
        if (piece.size() < kOpenMinFaces)
            for (std::uint32_t x : piece) gone[x] = 1;
    });
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

IndexedMesh cut_faces(const IndexedMesh& mesh, const std::vector<char>& marked, std::uint32_t& removed) {
    removed = 0;
    if (std::find(marked.begin(), marked.end(), char(1)) == marked.end()) return mesh;
    std::vector<IndexedMesh> kept;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> corner;  // directed edge -> triangle
    for (MeshPiece& piece : split_pieces(mesh)) {
        const Mesh m = [&] {
            Mesh built = Mesh::from_indexed(piece.mesh, true);
            built.build_faces();
            return built;
        }();
        // Each face of m by one of its directed edges (from_indexed keeps the vertex numbers).
        corner.clear();
        for (std::uint32_t t = 0; t < piece.mesh.triangles.size(); ++t)
            for (std::size_t i = 0; i < 3; ++i) {
                const auto& tri = piece.mesh.triangles[t];
                corner.push_back({(std::uint64_t(tri[i]) << 32) | tri[(i + 1) % 3], t});
            }
        std::sort(corner.begin(), corner.end());
        std::vector<char> marks(m.face_capacity(), 0);
        for (std::uint32_t f = 0; f < m.face_capacity(); ++f) {
            if (m.is_removed(Face(f))) continue;
            const Halfedge h = m.halfedge(Face(f));
            const std::uint64_t k = (std::uint64_t(m.from(h).idx) << 32) | m.to(h).idx;
            const auto it = std::lower_bound(corner.begin(), corner.end(), std::make_pair(k, 0u));
            marks[f] = marked[piece.triangle[it->second]];
        }
        std::uint32_t gone = 0;
        kept.push_back(cut_faces(m, marks, gone));
        removed += gone;
    }
    return join_pieces(kept);
}

float typical_edge(const IndexedMesh& mesh) {
    std::vector<float> sizes;
    sizes.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) {
        const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
        sizes.push_back((distance(a, b) + distance(b, c) + distance(c, a)) / 3.0f);
    }
    if (sizes.empty()) return 0.0f;
    std::nth_element(sizes.begin(), sizes.begin() + std::ptrdiff_t(sizes.size() / 2), sizes.end());
    return sizes[sizes.size() / 2];
}

CloudView view_cloud(const PointGrid& cloud, float spacing) {
    CloudView view;
    view.points = cloud.indexed_points();
    view.rim = cloud_rim(view.points, spacing);
    view.spacing = spacing;
    if (!view.rim.spacing.empty()) {
        std::vector<float> local = view.rim.spacing;
        std::nth_element(local.begin(), local.begin() + std::ptrdiff_t(local.size() / 2), local.end());
        view.spacing = local[local.size() / 2];
    }
    view.rim_share = flat_rim_share(view.rim);
    view.layer_share = multi_layer_share(view.points, view.spacing);
    view.partial = view.layer_share < kViewLayerShare;
    if (view.partial) {
        view.normals = view.rim.normal;
        Orientation o = orient_normals(view.points, view.normals, spacing);
        view.direction = o.direction;
        view.part = std::move(o.part);
    }
    return view;
}

IndexedMesh cut_unsupported(const Mesh& mesh, const PointGrid& cloud, const CloudView& view, float typical,
                            OpenReport& report) {
    if (!mesh.has_faces() || cloud.size() == 0 || mesh.n_faces() == 0) return mesh.to_indexed();
    const std::uint32_t nf = mesh.face_capacity();
    const float limit = std::max(kOpenEdges * typical, kOpenSpacings * view.spacing);
    const std::vector<Vec3>& points = view.points;
    const std::vector<char>& rim = view.rim.rim;
    std::vector<FaceGeometry> g(nf);
    std::vector<char> far(nf, 0);
    std::vector<float> away(nf, 0.0f);
    std::vector<std::uint32_t> nearest(nf, 0);
    std::vector<Vec3> rim_at;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (rim[i]) rim_at.push_back(points[i]);
    report.rim_share = view.rim_share;
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (mesh.is_removed(Face(f))) continue;
        g[f] = geometry(mesh, Face(f));
        const NearestPoint p = cloud.find_nearest(g[f].centroid);
        away[f] = std::sqrt(p.squared_distance);
        nearest[f] = p.index;
        far[f] = no_data(p, view, typical);
    }
    // Which regions of far faces are holes in the scan (see open_surface.h): measured round the
    // region's deepest face, within kOpenRimReach times its distance to the cloud.
    report.unsupported_faces += keep_regions(mesh, far, [&](const std::vector<std::uint32_t>& region) {
        std::uint32_t deepest = region.front();
        for (std::uint32_t f : region)
            if (away[f] > away[deepest]) deepest = f;
        const float depth = away[deepest] / limit;
        // With a smallest hole given: its depth in local spacings, at the deepest face.
        const bool given = view.hole_spacings > 0.0f;
        const bool deep_hole = given ? away[deepest] >= view.hole_spacings * view.rim.spacing[nearest[deepest]]
                                     : depth >= kOpenHoleDepth;
        if (!deep_hole && depth < kOpenEndDepth) return false;
        const Vec3 c = g[deepest].centroid;
        const float reach = kOpenRimReach * away[deepest] + limit;
        std::vector<Vec3> ring;  // the rim points in reach
        for (const Vec3& p : rim_at)
            if (squared_distance(p, c) <= reach * reach) ring.push_back(p);
        if (ring.empty()) return false;
        std::size_t all = 0;
        for (const Vec3& p : points) all += std::size_t(squared_distance(p, c) <= reach * reach);
        // Round the face: the largest angle the rim points leave free, seen along its normal.
        const Vec3 n = g[deepest].normal;
        const Vec3 u = normalized(cross(n, std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
        const bool surrounded = largest_gap(c, ring, u, cross(n, u)) < kOpenSurroundGap;
        const bool hole = surrounded && deep_hole;
        const bool end = view.partial && depth >= kOpenEndDepth && float(ring.size()) >= kOpenRimShare * float(all);
        return hole || end;
    });
    // The rim of each opening: a face next to a face that goes, whose centroid has data near but
    // one of its edges spans the hole (the learning leaves few, long triangles round a hole in the
    // scan, where no samples drew vertices), goes too when an edge's midpoint or a corner has no
    // data by the same test (a corner left over the hole: the bunny at 30,000 vertices, seed 2,
    // kept a boundary vertex 4.2 mm from every point, 1.66% of the diagonal); and so on outwards,
    // until every face at the opening's edge is supported along its edges and at its corners.
    std::vector<std::uint32_t> trim;
    for (std::uint32_t f = 0; f < nf; ++f)
        if (far[f]) trim.push_back(f);
    while (!trim.empty()) {
        const std::uint32_t f = trim.back();
        trim.pop_back();
        Halfedge h = mesh.halfedge(Face(f));
        for (int i = 0; i < 3; ++i, h = mesh.next(h)) {
            const Halfedge t = Mesh::twin(h);
            if (mesh.is_boundary(t)) continue;
            const std::uint32_t g2 = mesh.face(t).idx;
            if (far[g2]) continue;
            Halfedge k = t;
            bool spans = false;
            for (int j = 0; j < 3 && !spans; ++j, k = mesh.next(k))
                spans = no_data(cloud.find_nearest((mesh.position(mesh.from(k)) + mesh.position(mesh.to(k))) * 0.5f),
                                view, typical) ||
                        no_data(cloud.find_nearest(mesh.position(mesh.from(k))), view, typical);
            if (!spans) continue;
            far[g2] = 1;
            ++report.unsupported_faces;
            trim.push_back(g2);
        }
    }
    std::uint32_t removed = 0;
    IndexedMesh out = cut_faces(mesh, far, removed);
    report.removed_unsupported += removed;
    return out;
}

IndexedMesh cut_crossings(const IndexedMesh& mesh, std::uint32_t& removed) {
    removed = 0;
    IndexedMesh out = mesh;
    for (int round = 0; round < kCrossingRounds; ++round) {
        const auto pairs = self_intersecting_pairs(out);
        if (pairs.empty()) break;
        std::vector<char> crossing(out.triangles.size(), 0);
        for (const auto& [s, t] : pairs) crossing[s] = crossing[t] = 1;
        std::uint32_t gone = 0;
        out = cut_faces(out, crossing, gone);
        removed += gone;
    }
    return out;
}

}  // namespace nmesh
