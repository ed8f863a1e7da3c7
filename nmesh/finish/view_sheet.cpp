#include "nmesh/finish/view_sheet.h"

#include <algorithm>
#include <cmath>

#include "nmesh/finish/cloud_normals.h"
#include "nmesh/finish/mesh_pieces.h"
#include "nmesh/geometry/delaunay_2d.h"

namespace nmesh {

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
    for (std::uint32_t i = 0; i < mesh.vertex_capacity(); ++i)
        if (!mesh.is_removed(Vertex(i))) positions.push_back(mesh.position(Vertex(i)));
    // 3. The triangles over no data marked, and cut off.
    auto far = [&](const Vec3& p) {
        const NearestPoint q = cloud.find_nearest(p);
        const float limit = std::max(kOpenEdges * typical, kOpenSpacings * view.rim.spacing[q.index]);
        return q.squared_distance > limit * limit;
    };
    auto over_gap = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        const float longest = std::max({distance(a, b), distance(b, c), distance(c, a)});
        return longest > kSheetMaxEdges * typical || far((a + b + c) * (1.0f / 3.0f)) || far((a + b) * 0.5f) ||
               far((b + c) * 0.5f) || far((c + a) * 0.5f);
    };
    // Passes: the vertices no kept triangle of the earlier passes uses are triangulated again on
    // their own (a part seen through a gap, which overlaps the part in front across the view).
    std::vector<char> used(positions.size(), 0);
    std::vector<IndexedMesh> sheets;
    std::vector<std::uint32_t> members;
    std::vector<Point2d> plane;
    for (int pass = 0; pass < kSheetPasses; ++pass) {
        IndexedMesh sub;
        members.clear();
        plane.clear();
        for (std::uint32_t i = 0; i < positions.size(); ++i) {
            if (used[i]) continue;
            members.push_back(i);
            sub.positions.push_back(positions[i]);
            plane.push_back({double(dot(positions[i], u)), double(dot(positions[i], v))});
        }
        if (members.size() < 3) break;
        sub.triangles = delaunay_2d(plane);
        std::vector<char> marked(sub.triangles.size(), 0);
        std::size_t kept = 0;
        for (std::size_t t = 0; t < sub.triangles.size(); ++t) {
            const auto& tri = sub.triangles[t];
            marked[t] = over_gap(sub.positions[tri[0]], sub.positions[tri[1]], sub.positions[tri[2]]);
            if (marked[t]) continue;
            ++kept;
            for (std::uint32_t x : tri) used[members[x]] = 1;
        }
        if (kept < kOpenMinFaces) break;
        std::uint32_t removed = 0;
        sheets.push_back(cut_faces(sub, marked, removed));
    }
    IndexedMesh out = join_pieces(sheets);
    report.removed_layer = mesh.n_faces() > out.triangles.size() ? std::uint32_t(mesh.n_faces() - out.triangles.size()) : 0;
    return out;
}

}  // namespace nmesh
