#include "nmesh/finish/view_sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

#include "nmesh/finish/cloud_normals.h"
#include "nmesh/geometry/delaunay_2d.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/mesh_pieces.h"

namespace nmesh {

namespace {

// For each of `subset` (indices into the vertices), whether another of `subset` hides it: within
// `radius` of it across the view, nearer the scanner by more than `gap`, and with no data between
// the two (`far` at their midpoint): another part of the surface in front, not a steep stretch of
// the same part. A uniform grid over the plane across the view, cells of `radius`.
template <class Far>
std::vector<char> hidden_vertices(const std::vector<Vec3>& positions, const std::vector<float>& depth,
                                  const std::vector<Point2d>& across, const std::vector<std::uint32_t>& subset,
                                  float radius, float gap, const Far& far) {
    std::vector<char> hidden(subset.size(), 0);
    if (subset.empty() || !(radius > 0.0f)) return hidden;
    double lo_x = across[subset[0]].x, lo_y = across[subset[0]].y, hi_x = lo_x, hi_y = lo_y;
    for (std::uint32_t i : subset) {
        lo_x = std::min(lo_x, across[i].x), hi_x = std::max(hi_x, across[i].x);
        lo_y = std::min(lo_y, across[i].y), hi_y = std::max(hi_y, across[i].y);
    }
    const double cell = double(radius);
    const auto nx = std::int64_t((hi_x - lo_x) / cell) + 1, ny = std::int64_t((hi_y - lo_y) / cell) + 1;
    if (nx * ny > std::int64_t(8 * subset.size() + 64)) return hidden;  // degenerate spread: no test
    const auto cell_of = [&](const Point2d& p) {
        return std::make_pair(std::int64_t((p.x - lo_x) / cell), std::int64_t((p.y - lo_y) / cell));
    };
    // Counting sort of the subset by cell.
    std::vector<std::uint32_t> start(std::size_t(nx * ny) + 1, 0), order(subset.size());
    for (std::uint32_t i : subset) {
        const auto [cx, cy] = cell_of(across[i]);
        ++start[std::size_t(cy * nx + cx) + 1];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t k = 0; k < subset.size(); ++k) {
        const auto [cx, cy] = cell_of(across[subset[k]]);
        order[fill[std::size_t(cy * nx + cx)]++] = subset[k];
    }
    const double r2 = cell * cell;
    for (std::size_t k = 0; k < subset.size(); ++k) {
        const std::uint32_t i = subset[k];
        const auto [cx, cy] = cell_of(across[i]);
        for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min(cy + 1, ny - 1) && !hidden[k]; ++y)
            for (std::int64_t x = std::max<std::int64_t>(cx - 1, 0); x <= std::min(cx + 1, nx - 1) && !hidden[k]; ++x)
                for (std::uint32_t s = start[std::size_t(y * nx + x)]; s < start[std::size_t(y * nx + x) + 1]; ++s) {
                    const std::uint32_t j = order[s];
                    const double dx = across[j].x - across[i].x, dy = across[j].y - across[i].y;
                    if (depth[j] - depth[i] <= gap || dx * dx + dy * dy > r2) continue;
                    if (far((positions[i] + positions[j]) * 0.5f)) {
                        hidden[k] = 1;
                        break;
                    }
                }
    }
    return hidden;
}

}  // namespace

IndexedMesh view_sheet(const Mesh& mesh, const PointGrid& cloud, const CloudView& view, OpenReport& report) {
    if (!view.partial || view.normals.size() != cloud.size() || !mesh.has_faces()) return mesh.to_indexed();
    // 1. The typical edge: the median of the faces' mean edges.
    std::vector<float> edges;
    for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
        if (mesh.is_removed(Face(f))) continue;
        const Halfedge h = mesh.halfedge(Face(f));
        const Vec3 a = mesh.position(mesh.from(h)), b = mesh.position(mesh.to(h)), c = mesh.position(mesh.to(mesh.next(h)));
        edges.push_back((distance(a, b) + distance(b, c) + distance(c, a)) / 3.0f);
    }
    if (edges.empty()) return {};
    std::nth_element(edges.begin(), edges.begin() + std::ptrdiff_t(edges.size() / 2), edges.end());
    const float typical = edges[edges.size() / 2];
    // 2. Projected across the view and triangulated.
    const Vec3 d = view.direction;
    const Vec3 u = normalized(cross(d, std::fabs(d.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0})), v = cross(d, u);
    std::vector<Vec3> positions;
    std::vector<std::uint32_t> index_of(mesh.vertex_capacity(), UINT32_MAX);  // per mesh vertex
    for (std::uint32_t i = 0; i < mesh.vertex_capacity(); ++i) {
        if (mesh.is_removed(Vertex(i))) continue;
        index_of[i] = std::uint32_t(positions.size());
        positions.push_back(mesh.position(Vertex(i)));
    }
    // 3. The triangles over no data marked, and cut off; 4. the passes.
    auto far = [&](const Vec3& p) { return no_data(cloud.find_nearest(p), view, typical); };
    auto over_gap = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        const float longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
        if (longest > kSheetSparseEdges * typical) return true;
        // Longer than kSheetMaxEdges typical edges: kept only in a sparse part of the scan, where
        // it is shorter than kSheetMaxSpacings local spacings (and kSheetSparseEdges typical edges).
        const NearestPoint near = cloud.find_nearest((a + b + c) * (1.0f / 3.0f));
        if (longest > kSheetMaxEdges * typical && longest > kSheetMaxSpacings * view.rim.spacing[near.index])
            return true;
        return no_data(near, view, typical) || far((a + b) * 0.5f) || far((b + c) * 0.5f) || far((c + a) * 0.5f);
    };
    std::vector<float> depth(positions.size());
    std::vector<Point2d> across(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
        depth[i] = dot(positions[i], d);
        across[i] = {double(dot(positions[i], u)), double(dot(positions[i], v))};
    }
    // A learnt vertex off the cloud (on the closed mesh's tube round a sheet's edge, or sagging
    // between two layers) is not on the surface and is never triangulated: it counts as used.
    std::vector<char> used(positions.size(), 0);
    for (std::size_t i = 0; i < positions.size(); ++i) used[i] = far(positions[i]);
    // One triangulation: `plane` the members' positions across a direction. Returns the sheet,
    // cut (empty when fewer than kOpenMinFaces triangles are kept), and marks its vertices used.
    const auto triangulate = [&](const std::vector<std::uint32_t>& members, const std::vector<Point2d>& plane) {
        IndexedMesh sub;
        if (members.size() < 3) return sub;
        for (std::uint32_t i : members) sub.positions.push_back(positions[i]);
        sub.triangles = delaunay_2d(plane);
        std::vector<char> marked(sub.triangles.size(), 0);
        std::size_t kept = 0;
        for (std::size_t t = 0; t < sub.triangles.size(); ++t) {
            const auto& tri = sub.triangles[t];
            marked[t] = over_gap(sub.positions[tri[0]], sub.positions[tri[1]], sub.positions[tri[2]]);
            kept += !marked[t];
        }
        if (kept < kOpenMinFaces) return IndexedMesh();
        std::uint32_t removed = 0;
        IndexedMesh sheet = cut_faces(sub, marked, removed);
        // Used: the vertices of what the cut kept (it drops pieces, and the vertices only they
        // used, which a later pass may triangulate better).
        std::vector<std::pair<Vec3, std::uint32_t>> by_position;
        for (std::uint32_t i : members) by_position.push_back({positions[i], i});
        const auto less = [](const std::pair<Vec3, std::uint32_t>& a, const std::pair<Vec3, std::uint32_t>& b) {
            return std::tie(a.first.x, a.first.y, a.first.z, a.second) < std::tie(b.first.x, b.first.y, b.first.z, b.second);
        };
        std::sort(by_position.begin(), by_position.end(), less);
        for (const Vec3& q : sheet.positions) {
            auto it = std::lower_bound(by_position.begin(), by_position.end(), std::make_pair(q, std::uint32_t(0)), less);
            for (; it != by_position.end() && it->first == q; ++it) used[it->second] = 1;
        }
        return sheet;
    };
    // Passes, front layer first: each triangulates the vertices no kept triangle of an earlier pass
    // uses and no other such vertex hides (hidden_vertices).
    std::vector<IndexedMesh> sheets;
    std::vector<std::uint32_t> remaining, members;
    std::vector<Point2d> plane;
    for (int pass = 0; pass < kSheetPasses; ++pass) {
        remaining.clear();
        for (std::uint32_t i = 0; i < positions.size(); ++i)
            if (!used[i]) remaining.push_back(i);
        const std::vector<char> hidden =
            hidden_vertices(positions, depth, across, remaining, kPeelRadiusEdges * typical, kPeelDepthEdges * typical, far);
        members.clear();
        plane.clear();
        for (std::size_t k = 0; k < remaining.size(); ++k) {
            if (hidden[k]) continue;
            members.push_back(remaining[k]);
            plane.push_back(across[remaining[k]]);
        }
        IndexedMesh sheet = triangulate(members, plane);
        if (sheet.triangles.empty()) break;
        sheets.push_back(std::move(sheet));
    }
    // 5. What is still unused, in groups joined by the learnt mesh's edges, each triangulated
    // across its own mean normal (a wall seen at a grazing angle, squeezed across the view), and
    // without the faces that cross an earlier sheet.
    std::vector<std::uint32_t> group(positions.size());
    for (std::uint32_t i = 0; i < group.size(); ++i) group[i] = i;
    const auto root = [&](std::uint32_t x) {
        while (group[x] != x) x = group[x] = group[group[x]];
        return x;
    };
    for (std::uint32_t f = 0; f < mesh.face_capacity(); ++f) {
        if (mesh.is_removed(Face(f))) continue;
        Halfedge h = mesh.halfedge(Face(f));
        for (int k = 0; k < 3; ++k, h = mesh.next(h)) {
            const std::uint32_t a = index_of[mesh.from(h).idx], b = index_of[mesh.to(h).idx];
            if (!used[a] && !used[b]) group[root(a)] = root(b);
        }
    }
    std::vector<std::vector<std::uint32_t>> groups(positions.size());
    for (std::uint32_t i = 0; i < positions.size(); ++i)
        if (!used[i]) groups[root(i)].push_back(i);
    std::vector<IndexedMesh> local;
    for (const std::vector<std::uint32_t>& g : groups) {
        if (g.size() < kOpenMinFaces / 2 + 2) continue;  // too few vertices for kOpenMinFaces faces
        Vec3 n{};
        for (std::uint32_t i : g) n += view.normals[cloud.find_nearest(positions[i]).index];
        if (!(norm(n) > 0.5f * float(g.size()))) continue;  // no common side to project across
        // Turned to the scanner's side (a small part's normals may be oriented the other way).
        n = normalized(dot(n, d) < 0.0f ? -n : n);
        const Vec3 gu = normalized(cross(n, std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0})), gv = cross(n, gu);
        plane.clear();
        for (std::uint32_t i : g) plane.push_back({double(dot(positions[i], gu)), double(dot(positions[i], gv))});
        IndexedMesh sheet = triangulate(g, plane);
        if (!sheet.triangles.empty()) local.push_back(std::move(sheet));
    }
    if (!local.empty()) {
        const std::size_t before = [&] {
            std::size_t f = 0;
            for (const IndexedMesh& m : sheets) f += m.triangles.size();
            return f;
        }();
        IndexedMesh all = join_pieces(sheets), extra = join_pieces(local);
        const std::uint32_t offset = std::uint32_t(all.positions.size());
        all.positions.insert(all.positions.end(), extra.positions.begin(), extra.positions.end());
        for (auto t : extra.triangles) all.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        std::vector<char> marked(extra.triangles.size(), 0);
        for (const auto& [a, b] : self_intersecting_pairs(all)) {
            if (a >= before) marked[a - before] = 1;
            if (b >= before) marked[b - before] = 1;
        }
        std::uint32_t removed = 0;
        sheets.push_back(cut_faces(extra, marked, removed));
    }
    IndexedMesh out = join_pieces(sheets);
    report.removed_layer = mesh.n_faces() > out.triangles.size() ? std::uint32_t(mesh.n_faces() - out.triangles.size()) : 0;
    return out;
}

IndexedMesh cut_turned(const IndexedMesh& sheet, const PointGrid& cloud, const CloudView& view, OpenReport& report) {
    if (view.normals.size() != cloud.size()) return sheet;
    std::vector<char> marked(sheet.triangles.size(), 0);
    bool any = false;
    for (std::size_t t = 0; t < sheet.triangles.size(); ++t) {
        const auto& tri = sheet.triangles[t];
        const Vec3 a = sheet.positions[tri[0]], b = sheet.positions[tri[1]], c = sheet.positions[tri[2]];
        const Vec3 n = cross(b - a, c - a);
        marked[t] = dot(n, view.direction) < 0.0f &&
                    dot(n, view.normals[cloud.find_nearest((a + b + c) * (1.0f / 3.0f)).index]) < 0.0f;
        any = any || marked[t];
    }
    if (!any) return sheet;
    std::uint32_t removed = 0;
    IndexedMesh out = cut_faces(sheet, marked, removed);
    report.removed_layer += removed;
    return out;
}

}  // namespace nmesh
