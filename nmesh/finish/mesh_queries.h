// nmesh/finish/mesh_queries.h — the small questions the finishing stage's passes ask of a mesh (its live
// elements, corners, normals, edge lengths, folds, a vertex's relaxed position).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/geometry/closest_point.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh::finish_detail {

// The relaxation pulls a vertex towards the cloud by at most this share of its mean edge length
// per round: where the surface is thinner than a triangle, a larger pull could cross to the
// other side.
constexpr float kPullLimit = 0.25f;
// Pull-back iterations after a successful repair.
constexpr int kRefitIterations = 3;

inline std::vector<Vertex> alive_vertices(const Mesh& mesh) {
    std::vector<Vertex> v;
    v.reserve(mesh.n_vertices());
    for (std::uint32_t i = 0; i < mesh.vertex_capacity(); ++i)
        if (!mesh.is_removed(Vertex(i))) v.push_back(Vertex(i));
    return v;
}

inline std::vector<Face> alive_faces(const Mesh& mesh) {
    std::vector<Face> f;
    f.reserve(mesh.n_faces());
    for (std::uint32_t i = 0; i < mesh.face_capacity(); ++i)
        if (!mesh.is_removed(Face(i))) f.push_back(Face(i));
    return f;
}

// A nearest-point index over the positions of `verts`: index i names verts[i].
inline std::unique_ptr<PointGrid> position_index(const Mesh& mesh, const std::vector<Vertex>& verts) {
    std::vector<Vec3> pos(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) pos[i] = mesh.position(verts[i]);
    return std::make_unique<PointGrid>(pos);
}

inline std::array<Vertex, 3> corners(const Mesh& mesh, Face f) { return mesh.face_vertices(f); }

// Twice the area of a face, along its normal.
inline Vec3 area_vector(const Mesh& mesh, Face f) {
    const auto c = corners(mesh, f);
    const Vec3& p = mesh.position(c[0]);
    return cross(mesh.position(c[1]) - p, mesh.position(c[2]) - p);
}

inline float length(const Mesh& mesh, Halfedge h) {
    return distance(mesh.position(mesh.from(h)), mesh.position(mesh.to(h)));
}

inline float mean_edge_length(const Mesh& mesh) {
    double sum = 0.0;
    std::uint32_t n = 0;
    for (std::uint32_t e = 0; e < mesh.edge_capacity(); ++e) {
        if (mesh.is_removed(Edge(e))) continue;
        sum += length(mesh, Mesh::halfedge(Edge(e), 0));
        ++n;
    }
    return n ? float(sum / n) : 0.0f;
}

// cot of the angle at c of the triangle (a, b, c); +-infinity for a degenerate triangle (the sign
// of the cosine: an angle of 0 or of 180 degrees).
inline float cot_at(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 u = a - c, v = b - c;
    const float d = dot(u, v);
    const float s = norm(cross(u, v));
    if (s == 0.0f) return d >= 0.0f ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
    return d / s;
}

inline bool edge_folded(const Mesh& mesh, Halfedge h, float cos_limit) {
    if (mesh.is_boundary(Mesh::edge(h))) return false;  // one triangle: nothing to fold against
    const Vec3 n0 = area_vector(mesh, mesh.face(h)), n1 = area_vector(mesh, mesh.face(Mesh::twin(h)));
    const float l0 = squared_norm(n0), l1 = squared_norm(n1);
    if (l0 == 0.0f || l1 == 0.0f) return true;  // a degenerate triangle
    return dot(n0, n1) < cos_limit * std::sqrt(l0) * std::sqrt(l1);
}

// Where tangential relaxation takes a vertex: towards the area-weighted centroid of its triangles'
// centroids, without the normal component of the move, then (with a cloud) pulled towards it.
// A boundary vertex stays: relaxation would draw the boundary inwards.
inline Vec3 relaxed_position(const Mesh& mesh, Vertex v, const CloudSurface* cloud, float mean_edge) {
    const Vec3 p = mesh.position(v);
    if (mesh.is_boundary(v)) return p;
    Vec3 centroid, normal;
    float area = 0.0f, ring_length = 0.0f;
    std::uint32_t valence = 0;
    mesh.for_each_corner(v, [&](Halfedge h) {
        const Vec3& q1 = mesh.position(mesh.to(h));
        const Vec3& q2 = mesh.position(mesh.to(mesh.next(h)));
        const Vec3 x = cross(q1 - p, q2 - p);  // twice the area, along the normal
        const float a = norm(x);
        centroid += (p + q1 + q2) * (a / 3.0f);
        area += a;
        normal += x;
        ring_length += distance(p, q1);
        ++valence;
    });
    if (!(area > 0.0f)) return p;
    const Vec3 n = normalized(normal);
    const Vec3 d = centroid * (1.0f / area) - p;
    const Vec3 q = p + (d - n * dot(d, n));
    if (!cloud) return q;
    const float edge = ring_length / float(valence);
    // A move that would take the vertex more than a (mesh-wide mean) edge length away from the
    // cloud, and farther than it was, is no slide along the scanned surface (it happens over holes
    // in the scan, where the big triangles spanning the hole would draw the vertices around it
    // inwards): the vertex stays.
    const NearestPoint near = cloud->index().find_nearest(q);
    const float d2 = near.squared_distance;
    if (d2 > mean_edge * mean_edge && d2 > cloud->index().nearest_squared_distance(p)) return p;
    return cloud->pull(q, n, kPullLimit * edge, edge, near);
}

// Distance from x to the triangles around v (an upper bound of its distance to the surface, and
// close to it when v is the vertex nearest to x).
inline float distance_to_ring(const Mesh& mesh, Vertex v, const Vec3& x) {
    float best = std::numeric_limits<float>::infinity();
    const Vec3& a = mesh.position(v);
    mesh.for_each_corner(v, [&](Halfedge h) {
        const Vec3 y =
            closest_point_on_triangle_float(x, a, mesh.position(mesh.to(h)), mesh.position(mesh.to(mesh.next(h))));
        best = std::min(best, squared_distance(x, y));
    });
    return std::sqrt(best);
}

}  // namespace nmesh::finish_detail
