// The half-edge mesh (nmesh/mesh/mesh.h): construction (the tetrahedron, from a triangle list),
// the face index dropped and built again, and the export to a triangle list.
#include "nmesh/mesh/mesh.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>
#include <utility>

#include "nmesh/error.h"
#include "nmesh/mesh/mesh_check.h"

namespace nmesh {

// ---- construction -------------------------------------------------------------------------------

Mesh Mesh::tetrahedron(const Vec3& center, float radius) {
    // Vertices of a regular tetrahedron: alternate corners of the cube [-1, 1]^3, scaled so they
    // lie on the sphere of the given radius.
    const float s = radius / std::sqrt(3.0f);
    return tetrahedron(center + Vec3{s, s, s}, center + Vec3{s, -s, -s}, center + Vec3{-s, s, -s},
                       center + Vec3{-s, -s, s});
}

Mesh Mesh::tetrahedron(const Vec3& a, const Vec3& b_in, const Vec3& c_in, const Vec3& d) {
    Vec3 b = b_in, c = c_in;
    // With det(b-a, c-a, d-a) > 0 the faces (a,c,b), (a,b,d), (a,d,c), (b,c,d) face outward;
    // otherwise swapping b and c makes it so.
    if (dot(cross(b - a, c - a), d - a) < 0.0f) std::swap(b, c);

    Mesh m;
    m.reserve(4);
    const Vertex v[4] = {m.new_vertex(a), m.new_vertex(b), m.new_vertex(c), m.new_vertex(d)};
    const std::uint32_t tri[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    // The six edges and, for each, which half-edge runs i -> j (the first of the pair runs from
    // the lower to the higher vertex number).
    Edge e[4][4];
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) e[i][j] = e[j][i] = m.new_edge();
    auto he = [&](std::uint32_t i, std::uint32_t j) { return halfedge(e[i][j], i < j ? 0 : 1); };
    for (const auto& t : tri) {
        const Face f = m.new_face();
        m.he_[he(t[0], t[1]).idx].to = v[t[1]].idx;
        m.he_[he(t[1], t[2]).idx].to = v[t[2]].idx;
        m.he_[he(t[2], t[0]).idx].to = v[t[0]].idx;
        m.link_face(f, he(t[0], t[1]), he(t[1], t[2]), he(t[2], t[0]));
    }
    for (std::uint32_t i = 0; i < 4; ++i) m.vhe_[v[i].idx] = he(i, (i + 1) % 4).idx;
    return m;
}

Mesh Mesh::from_indexed(const IndexedMesh& in, bool allow_boundary) {
    // The limit before anything is built: a closed genus-0 mesh of T triangles has 3T half-edges
    // and T / 2 + 2 vertices, so a valid input within the limit has at most kMaxVertices.
    check_halfedge_count(3 * std::uint64_t(in.triangles.size()), "from_indexed");
    if (in.positions.size() > kMaxVertices)
        throw InputError("mesh: from_indexed: " + std::to_string(in.positions.size()) +
                         " vertices; a mesh holds at most " + std::to_string(kMaxVertices) + " (2^31 half-edges)");
    const std::uint32_t nv = std::uint32_t(in.positions.size());
    Mesh m;
    m.reserve(nv);
    for (const Vec3& p : in.positions) m.new_vertex(p);
    // Directed edge (a, b) -> half-edge, found by binary search in a sorted table.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> directed;
    directed.reserve(in.triangles.size() * 3);
    auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
    for (std::size_t t = 0; t < in.triangles.size(); ++t) {
        const auto& tri = in.triangles[t];
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t a = tri[i], b = tri[(i + 1) % 3];
            if (a >= nv || b >= nv || a == b)
                throw InputError("mesh: triangle " + std::to_string(t) + " has an invalid or repeated vertex index");
            directed.push_back({key(a, b), std::uint32_t(t * 3 + i)});
        }
    }
    std::sort(directed.begin(), directed.end());
    for (std::size_t i = 1; i < directed.size(); ++i)
        if (directed[i].first == directed[i - 1].first)
            throw InputError("mesh: the directed edge " + std::to_string(directed[i].first >> 32) + " -> " +
                             std::to_string(directed[i].first & 0xffffffffu) +
                             " appears twice (non-manifold or inconsistently oriented)");
    auto find = [&](std::uint32_t a, std::uint32_t b) -> std::uint32_t {
        const auto it = std::lower_bound(directed.begin(), directed.end(), std::make_pair(key(a, b), 0u));
        return (it != directed.end() && it->first == key(a, b)) ? it->second : kInvalidIndex;
    };
    // Corner slot (t * 3 + i) -> half-edge; each undirected edge gets one pair. An edge with one
    // triangle gets a boundary half-edge, remembered per origin vertex to link the loops below.
    std::vector<std::uint32_t> he_of(directed.size(), kInvalidIndex);
    std::vector<std::uint32_t> boundary_out;  // per vertex: its outgoing boundary half-edge
    for (std::size_t t = 0; t < in.triangles.size(); ++t) {
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t c = std::uint32_t(t * 3 + i);
            if (he_of[c] != kInvalidIndex) continue;
            const std::uint32_t a = in.triangles[t][i], b = in.triangles[t][(i + 1) % 3];
            const std::uint32_t opposite = find(b, a);
            if (opposite == kInvalidIndex && !allow_boundary)
                throw InputError("mesh: the edge " + std::to_string(a) + " - " + std::to_string(b) +
                                 " has only one triangle (the mesh is not closed)");
            const Edge e = m.new_edge();
            he_of[c] = halfedge(e, 0).idx;
            m.he_[halfedge(e, 0).idx].to = b;
            m.he_[halfedge(e, 1).idx].to = a;
            if (opposite != kInvalidIndex) {
                he_of[opposite] = halfedge(e, 1).idx;
                continue;
            }
            if (boundary_out.empty()) boundary_out.assign(nv, kInvalidIndex);
            if (boundary_out[b] != kInvalidIndex)
                throw InputError("mesh: vertex " + std::to_string(b) + " has two boundary gaps (a bow-tie vertex)");
            boundary_out[b] = halfedge(e, 1).idx;  // b -> a, without a face
            ++m.n_boundary_;
        }
    }
    for (std::size_t t = 0; t < in.triangles.size(); ++t) {
        const Face f = m.new_face();
        m.link_face(f, Halfedge(he_of[t * 3]), Halfedge(he_of[t * 3 + 1]), Halfedge(he_of[t * 3 + 2]));
        for (int i = 0; i < 3; ++i) m.vhe_[in.triangles[t][i]] = he_of[t * 3 + i];
    }
    // Boundary loops: each boundary half-edge continues with the one leaving its target, which is
    // also the target's stored half-edge.
    for (std::uint32_t v = 0; v < std::uint32_t(boundary_out.size()); ++v) {
        const std::uint32_t h = boundary_out[v];
        if (h == kInvalidIndex) continue;
        m.vhe_[v] = h;
        m.he_[h].next = boundary_out[m.he_[h].to];  // the loop's next; it exists as every
                                                    // boundary edge ends where another begins
    }
    for (std::uint32_t v = 0; v < nv; ++v)
        if (m.vhe_[v] == kInvalidIndex) throw InputError("mesh: vertex " + std::to_string(v) + " is in no triangle");
    const ManifoldCheck check = check_manifold(m);
    if (!check.ok) throw InputError("mesh: not a connected 2-manifold: " + check.error);
    return m;
}

void Mesh::reserve(std::uint32_t n) {
    if (n > kMaxVertices)
        throw ParameterError("n", "mesh: reserve: n = " + std::to_string(n) + " vertices; a mesh holds at most " +
                             std::to_string(kMaxVertices) + " (2^31 half-edges)");
    vpos_.reserve(n);
    vhe_.reserve(n);
    const std::size_t nh = std::size_t(n) * 6, nf = std::size_t(n) * 2;
    he_.reserve(nh);
    if (faces_) {
        he_face_.reserve(nh);
        fhe_.reserve(nf);
    }
}

void Mesh::drop_faces() {
    if (n_boundary_ != 0)
        throw ParameterError("mesh", "mesh: drop_faces: the mesh has boundaries, which the face index tells apart");
    std::vector<std::uint32_t>().swap(he_face_);  // the memory itself goes, not just the size
    std::vector<std::uint32_t>().swap(fhe_);
    ffree_ = kInvalidIndex;
    faces_ = false;
}

void Mesh::build_faces() {
    if (faces_) return;
    he_face_.assign(he_.size(), kInvalidIndex);  // dead half-edges keep kInvalidIndex
    fhe_.reserve(n_faces_);
    // Visited in increasing order, a triangle is met first at its smallest half-edge.
    for (std::uint32_t h = 0; h < he_.size(); ++h) {
        if (he_face_[h] != kInvalidIndex || is_removed(Halfedge(h))) continue;
        const std::uint32_t f = std::uint32_t(fhe_.size());
        const std::uint32_t h1 = he_[h].next, h2 = he_[h1].next;
        he_face_[h] = he_face_[h1] = he_face_[h2] = f;
        fhe_.push_back(h);
    }
    assert(fhe_.size() == n_faces_);
    faces_ = true;
}

void Mesh::throw_too_many_halfedges(std::uint64_t halfedges, const char* what) {
    throw InputError(std::string("mesh: ") + what + ": " + std::to_string(halfedges) +
                     " half-edges; a mesh holds at most 2^31 (" + std::to_string(kMaxVertices) + " vertices)");
}

// ---- export -------------------------------------------------------------------------------------

IndexedMesh Mesh::to_indexed(std::vector<std::uint32_t>* vertex_map) const {
    IndexedMesh out;
    std::vector<std::uint32_t> local;
    std::vector<std::uint32_t>& map = vertex_map ? *vertex_map : local;
    map.assign(vertex_capacity(), kInvalidIndex);
    out.positions.reserve(n_vertices_);
    for (std::uint32_t v = 0; v < vertex_capacity(); ++v) {
        if (is_removed(Vertex(v))) continue;
        map[v] = std::uint32_t(out.positions.size());
        out.positions.push_back(vpos_[v]);
    }
    out.triangles.reserve(n_faces_);
    auto add = [&](Halfedge h) { out.triangles.push_back({map[from(h).idx], map[to(h).idx], map[to(next(h)).idx]}); };
    if (faces_) {
        for (std::uint32_t f = 0; f < face_capacity(); ++f)
            if (!is_removed(Face(f))) add(halfedge(Face(f)));
    } else {
        for (std::uint32_t h = 0; h < halfedge_capacity(); ++h)
            if (!is_removed(Halfedge(h)) && first_of_triangle(Halfedge(h)).idx == h) add(Halfedge(h));
    }
    return out;
}

bool Mesh::same_arrays(const Mesh& o) const {
    // The dead marks and free lists live in vhe_, he_ and fhe_ and the heads.
    return vhe_ == o.vhe_ && he_ == o.he_ && he_face_ == o.he_face_ && fhe_ == o.fhe_ && vfree_ == o.vfree_ &&
           ffree_ == o.ffree_ && efree_ == o.efree_ && n_vertices_ == o.n_vertices_ && n_faces_ == o.n_faces_ &&
           n_edges_ == o.n_edges_ && n_boundary_ == o.n_boundary_ && faces_ == o.faces_ &&
           vpos_.size() == o.vpos_.size() &&
           std::equal(vpos_.begin(), vpos_.end(), o.vpos_.begin(), [](const Vec3& p, const Vec3& q) { return p == q; });
}

}  // namespace nmesh
