// nmesh/finish/regularise.cpp — flips, tangential relaxation and the centroid fit (step 1 of the stage).
#include "nmesh/finish/regularise.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "nmesh/finish/mesh_queries.h"
#include "nmesh/geometry/closest_point.h"
#include "nmesh/util/math_constants.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

using namespace finish_detail;

std::uint64_t flip_to_delaunay(Mesh& mesh, float max_dihedral_deg) {
    const float cos_max = std::cos(max_dihedral_deg * kPiF / 180.0f);
    std::vector<Edge> stack;
    std::vector<std::uint8_t> queued(mesh.edge_capacity(), 0);
    for (std::uint32_t e = mesh.edge_capacity(); e-- > 0;)
        if (!mesh.is_removed(Edge(e))) {
            stack.push_back(Edge(e));
            queued[e] = 1;
        }
    std::uint64_t flips = 0;
    const std::uint64_t limit = 8ull * mesh.n_edges();
    while (!stack.empty() && flips < limit) {
        const Edge e = stack.back();
        stack.pop_back();
        queued[e.idx] = 0;
        if (mesh.is_boundary(e)) continue;  // a boundary edge has one triangle and stays
        const Halfedge h = Mesh::halfedge(e, 0);
        const Vertex a = mesh.from(h), b = mesh.to(h);
        const Vertex c = mesh.to(mesh.next(h)), d = mesh.to(mesh.next(Mesh::twin(h)));
        const Vec3 &pa = mesh.position(a), &pb = mesh.position(b), &pc = mesh.position(c), &pd = mesh.position(d);
        // Not locally Delaunay: the angles opposite the edge sum to more than 180 degrees, that is
        // cot(c) + cot(d) < 0 (with a margin, so that cocircular quads do not flip back and forth).
        if (!(cot_at(pa, pb, pc) + cot_at(pa, pb, pd) < -1e-4f)) continue;
        // Nearly coplanar before and after, the new triangles facing the old ones' side: the flip
        // must not cut across a ridge or fold the surface.
        const Vec3 n0 = normalized(cross(pb - pa, pc - pa)), n1 = normalized(cross(pa - pb, pd - pb));
        if (dot(n0, n1) < cos_max) continue;
        const Vec3 m0 = normalized(cross(pc - pd, pa - pd)), m1 = normalized(cross(pd - pc, pb - pc));
        if (dot(m0, m1) < cos_max) continue;
        const Vec3 side = n0 + n1;
        if (dot(m0, side) <= 0.0f || dot(m1, side) <= 0.0f) continue;
        if (!mesh.can_flip(h)) continue;
        mesh.flip(h);
        ++flips;
        // The four edges of the quad may have stopped being locally Delaunay.
        const Halfedge t = Mesh::twin(h);
        for (const Halfedge g : {mesh.next(h), mesh.next(mesh.next(h)), mesh.next(t), mesh.next(mesh.next(t))}) {
            const Edge ge = Mesh::edge(g);
            if (!queued[ge.idx]) {
                queued[ge.idx] = 1;
                stack.push_back(ge);
            }
        }
    }
    return flips;
}

namespace {

// The relaxation's chunk of vertices for a thread: large enough that handing it out costs nothing.
constexpr std::size_t kVerticesPerChunk = 512;

// Whether moving v to q keeps `anchor` within kAnchorReach of v's mean edge length of v's
// triangles (with v at q, its neighbours where they are), or v's triangles fold.
bool keeps_anchor(const Mesh& mesh, Vertex v, const Vec3& q, const Vec3& anchor) {
    const Vec3& p = mesh.position(v);
    Vec3 normal;
    float ring = 0.0f, nearest2 = std::numeric_limits<float>::infinity();
    std::uint32_t valence = 0;
    mesh.for_each_corner(v, [&](Halfedge h) {
        const Vec3 &q1 = mesh.position(mesh.to(h)), &q2 = mesh.position(mesh.to(mesh.next(h)));
        normal += cross(q1 - p, q2 - p);
        ring += distance(p, q1);
        ++valence;
        nearest2 = std::min(nearest2, squared_distance(anchor, closest_point_on_triangle_float(anchor, q, q1, q2)));
    });
    const float reach = kAnchorReach * ring / float(std::max<std::uint32_t>(valence, 1));
    if (nearest2 <= reach * reach) return true;
    bool folded = false;
    mesh.for_each_corner(v, [&](Halfedge h) {
        const Vec3 &q1 = mesh.position(mesh.to(h)), &q2 = mesh.position(mesh.to(mesh.next(h)));
        folded = folded || dot(cross(q1 - p, q2 - p), normal) <= 0.0f;
    });
    return folded;
}

}  // namespace

void relax_tangentially(Mesh& mesh, const CloudSurface* cloud, const Anchors* anchors, std::uint32_t threads) {
    const std::vector<Vertex> verts = alive_vertices(mesh);
    std::vector<Vec3> next(verts.size());
    const float mean_edge = mean_edge_length(mesh);
    const Mesh& before = mesh;
    for_chunks(verts.size(), kVerticesPerChunk, threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Vertex v = verts[i];
            next[i] = relaxed_position(before, v, cloud, mean_edge);
            if (anchors && anchors->held[v.idx] && !keeps_anchor(before, v, next[i], anchors->at[v.idx]))
                next[i] = before.position(v);
        }
    });
    for (std::size_t i = 0; i < verts.size(); ++i) mesh.set_position(verts[i], next[i]);
}

void fit_centroids(Mesh& mesh, const std::vector<Vec3>& cloud, float weight) {
    const std::vector<Vertex> verts = alive_vertices(mesh);
    const std::vector<Face> faces = alive_faces(mesh);
    std::vector<Vec3> centroids(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) centroids[i] = mesh.face_centroid(faces[i]);
    const PointGrid index(centroids);
    std::vector<Vec3> pull(mesh.face_capacity());
    std::vector<std::uint32_t> count(mesh.face_capacity(), 0);
    for (const Vec3& x : cloud) {
        const std::uint32_t j = index.nearest(x);
        pull[faces[j].idx] += x - centroids[j];
        ++count[faces[j].idx];
    }
    std::vector<Vec3> next(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) {
        const Vertex v = verts[i];
        const Vec3 p = mesh.position(v);
        Vec3 centroid, normal, sum;
        float area = 0.0f;
        std::uint32_t n_points = 0;
        mesh.for_each_corner(v, [&](Halfedge h) {
            const Vec3& q1 = mesh.position(mesh.to(h));
            const Vec3& q2 = mesh.position(mesh.to(mesh.next(h)));
            const Vec3 x = cross(q1 - p, q2 - p);
            const float a = norm(x);
            centroid += (p + q1 + q2) * (a / 3.0f);
            area += a;
            normal += x;
            sum += pull[mesh.face(h).idx];
            n_points += count[mesh.face(h).idx];
        });
        const Vec3 n = normalized(normal);
        Vec3 move;
        if (area > 0.0f) move += (centroid * (1.0f / area) - p) * weight;
        if (n_points > 0) move += sum * (weight / float(n_points));
        next[i] = mesh.is_boundary(v) ? p : p + (move - n * dot(move, n));  // a boundary stays
    }
    for (std::size_t i = 0; i < verts.size(); ++i) mesh.set_position(verts[i], next[i]);
}

}  // namespace nmesh
