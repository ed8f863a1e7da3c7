// nmesh/learn/face_support.h — which faces of a learning mesh the cloud supports, and whether the
// cloud walls a line round: the tests the handle search (handles.h) and the bridge search
// (bridges.h) share.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

// A face is unsupported when its centroid is farther from the cloud than kUnsupportedEdges times
// the faces' mean longest edge and kUnsupportedSpacings point spacings (the spacing: the square
// root of the mesh area per cloud point), so that a coarse mesh or a sparse scan is not taken for
// a hole.
inline constexpr float kUnsupportedEdges = 0.8f;
inline constexpr float kUnsupportedSpacings = 2.0f;

struct FaceData {
    Vec3 centroid;
    Vec3 vector_area;
    float longest_edge = 0.0f;
};

inline FaceData face_data(const Mesh& m, Face f) {
    const Halfedge h = m.halfedge(f);
    const Vec3 a = m.position(m.from(h)), b = m.position(m.to(h)), c = m.position(m.to(m.next(h)));
    FaceData d;
    d.centroid = (a + b + c) * (1.0f / 3.0f);
    d.vector_area = cross(b - a, c - a) * 0.5f;
    d.longest_edge = std::sqrt(std::max({squared_distance(a, b), squared_distance(b, c), squared_distance(c, a)}));
    return d;
}

struct FaceSupport {
    std::vector<FaceData> data;      // per face slot (removed slots: zero)
    std::vector<char> unsupported;   // per face slot
    float far = 0.0f;                // the distance beyond which a face is unsupported
    std::uint32_t alive = 0;         // faces
};

// `mesh` with its face index; `cloud` non-empty. O(F) nearest-point queries.
inline FaceSupport face_support(const Mesh& mesh, const PointGrid& cloud) {
    FaceSupport s;
    const std::uint32_t nf = mesh.face_capacity();
    s.data.resize(nf);
    s.unsupported.assign(nf, 0);
    double area = 0.0, edges = 0.0;
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (mesh.is_removed(Face(f))) continue;
        s.data[f] = face_data(mesh, Face(f));
        area += norm(s.data[f].vector_area);
        edges += s.data[f].longest_edge;
        ++s.alive;
    }
    if (s.alive == 0) return s;
    const float mean_edge = float(edges / s.alive);
    const float spacing = float(std::sqrt(area / double(cloud.size())));
    s.far = std::max(kUnsupportedEdges * mean_edge, kUnsupportedSpacings * spacing);
    const float far2 = s.far * s.far;
    for (std::uint32_t f = 0; f < nf; ++f)
        if (!mesh.is_removed(Face(f))) s.unsupported[f] = cloud.nearest_squared_distance(s.data[f].centroid) > far2;
    return s;
}

// Whether the cloud surrounds the line through `middle` along `axis` (unit): in each of
// kDirections directions across it, a cloud point within `gap` of the ray within `reach`.
// A bore or a ring's hole is walled all round; the gap between two legs or two strands of a knot
// is open on two sides.
inline bool walled_round(const PointGrid& cloud, const Vec3& middle, const Vec3& axis, float reach, float gap) {
    constexpr int kDirections = 8;
    const Vec3 helper = std::fabs(axis.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 e1 = normalized(cross(axis, helper)), e2 = cross(axis, e1);
    const float gap2 = gap * gap;
    for (int k = 0; k < kDirections; ++k) {
        const float angle = 6.2831853f * float(k) / float(kDirections);
        const Vec3 dir = e1 * std::cos(angle) + e2 * std::sin(angle);
        bool hit = false;
        for (float t = gap; t <= reach && !hit; t += gap)
            hit = cloud.nearest_squared_distance(middle + dir * t) <= gap2;
        if (!hit) return false;
    }
    return true;
}

}  // namespace nmesh
