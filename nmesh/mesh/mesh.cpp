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
        throw ParameterError("mesh: reserve: n = " + std::to_string(n) + " vertices; a mesh holds at most " +
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
        throw ParameterError("mesh: drop_faces: the mesh has boundaries, which the face index tells apart");
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

// ---- slots and free lists -----------------------------------------------------------------------
// A head and the links it leads to are all marked (slot | kFreeBit), so a pop is a mask and a
// load, a push two stores and an or, with no branch on the list's end: kInvalidIndex has the bit.

Vertex Mesh::new_vertex(const Vec3& p) {
    ++n_vertices_;
    if (vfree_ != kInvalidIndex) {
        const std::uint32_t v = vfree_ & ~kFreeBit;
        vfree_ = vhe_[v];
        vpos_[v] = p;
        vhe_[v] = kInvalidIndex;
        return Vertex(v);
    }
    vpos_.push_back(p);
    vhe_.push_back(kInvalidIndex);
    return Vertex(std::uint32_t(vpos_.size() - 1));
}

Face Mesh::new_face() {
    ++n_faces_;
    if (!faces_) return Face();
    if (ffree_ != kInvalidIndex) {
        const std::uint32_t f = ffree_ & ~kFreeBit;
        ffree_ = fhe_[f];
        fhe_[f] = kInvalidIndex;
        return Face(f);
    }
    fhe_.push_back(kInvalidIndex);
    return Face(std::uint32_t(fhe_.size() - 1));
}

Edge Mesh::new_edge() {
    ++n_edges_;
    if (efree_ != kInvalidIndex) {
        const std::uint32_t e = efree_ & ~kFreeBit;
        efree_ = he_[2 * e].next;
        return Edge(e);
    }
    // The callers that can grow the mesh (split, from_indexed) checked the limit before
    // changing anything, so that a refusal leaves the mesh as it was.
    assert(he_.size() + 2 <= kMaxHalfedges);
    for (int i = 0; i < 2; ++i) {
        he_.push_back({kInvalidIndex, kInvalidIndex});
        if (faces_) he_face_.push_back(kInvalidIndex);
    }
    return Edge(std::uint32_t(he_.size() / 2 - 1));
}

void Mesh::delete_vertex(Vertex v) {
    --n_vertices_;
    vhe_[v.idx] = vfree_;
    vfree_ = v.idx | kFreeBit;
}

void Mesh::delete_face(Face f) {
    --n_faces_;
    if (!faces_) return;
    fhe_[f.idx] = ffree_;
    ffree_ = f.idx | kFreeBit;
}

void Mesh::delete_edge(Edge e) {
    --n_edges_;
    // Only the first half-edge's next carries the mark; the pair's other fields keep stale
    // values nobody reads (every reader asks is_removed first).
    he_[2 * e.idx].next = efree_;
    efree_ = e.idx | kFreeBit;
}

void Mesh::link_face(Face f, Halfedge h0, Halfedge h1, Halfedge h2) {
    he_[h0.idx].next = h1.idx;
    he_[h1.idx].next = h2.idx;
    he_[h2.idx].next = h0.idx;
    if (!faces_) return;
    he_face_[h0.idx] = he_face_[h1.idx] = he_face_[h2.idx] = f.idx;
    fhe_[f.idx] = h0.idx;
}

void Mesh::replace_in_face(Halfedge old, Halfedge by) {
    const Halfedge p = prev(old), n = next(old);
    he_[p.idx].next = by.idx;
    he_[by.idx].next = n.idx;
    if (!faces_) return;
    const Face f = face(old);
    he_face_[by.idx] = f.idx;
    if (fhe_[f.idx] == old.idx) fhe_[f.idx] = by.idx;
}

// ---- queries ------------------------------------------------------------------------------------

// Both clockwise: one load per step, and valid next to a boundary.
Halfedge Mesh::find_halfedge(Vertex a, Vertex b) const {
    const Halfedge start = halfedge(a);
    Halfedge h = start;
    do {
        if (to(h) == b) return h;
        h = cw_rotated(h);
    } while (h != start);
    return Halfedge();
}

std::uint32_t Mesh::valence(Vertex v) const {
    std::uint32_t n = 0;
    for_each_outgoing_cw(v, [&](Halfedge) { ++n; });
    return n;
}

Halfedge Mesh::prev_on_boundary(Halfedge h) const {
    assert(is_boundary(h));
    // The incoming boundary half-edge of from(h) is the twin of one of its outgoing half-edges.
    Halfedge g = h;
    do {
        if (is_boundary(twin(g))) return twin(g);
        g = cw_rotated(g);
    } while (g != h);
    assert(false);
    return Halfedge();
}

std::uint32_t Mesh::loop_length(Halfedge h) const {
    std::uint32_t n = 0;
    Halfedge g = h;
    do {
        ++n;
        g = next(g);
    } while (g != h);
    return n;
}

Vec3 Mesh::face_normal(Face f) const {
    const Halfedge h = halfedge(f);
    const Vec3& p0 = position(from(h));
    const Vec3& p1 = position(to(h));
    const Vec3& p2 = position(to(next(h)));
    return normalized(cross(p1 - p0, p2 - p0));
}

float Mesh::face_area(Face f) const {
    const Halfedge h = halfedge(f);
    const Vec3& p0 = position(from(h));
    return 0.5f * norm(cross(position(to(h)) - p0, position(to(next(h))) - p0));
}

Vec3 Mesh::centroid_from(Halfedge h) const {
    return (position(from(h)) + position(to(h)) + position(to(next(h)))) * (1.0f / 3.0f);
}

Vec3 Mesh::face_centroid(Face f) const { return centroid_from(halfedge(f)); }

Vec3 Mesh::triangle_centroid(Halfedge h) const { return centroid_from(first_of_triangle(h)); }

Vec3 Mesh::vertex_normal(Vertex v) const {
    // The cross product of a face's two edges at v is twice its area times its unit normal, so
    // their sum is the area-weighted normal sum.
    const Vec3& p = position(v);
    Vec3 n;
    for_each_outgoing_cw(v, [&](Halfedge h) {
        if (!is_boundary(h)) n += cross(position(to(h)) - p, position(to(next(h))) - p);
    });
    return normalized(n);
}

// ---- vertex split -------------------------------------------------------------------------------

bool Mesh::can_split(Halfedge to_c, Halfedge to_d) const {
    if (!to_c.valid() || !to_d.valid() || to_c == to_d) return false;
    if (to_c.idx >= halfedge_capacity() || to_d.idx >= halfedge_capacity()) return false;
    if (is_removed(to_c) || is_removed(to_d)) return false;
    if (from(to_c) != from(to_d)) return false;
    return !is_boundary(from(to_c));  // a boundary vertex is not split
}

Vertex Mesh::split(Halfedge to_c, Halfedge to_d, const Vec3& p) {
    assert(can_split(to_c, to_d));
    // The only operation that grows the mesh; the limit is checked before anything changes. The
    // arrays grow only when every slot is in use, so the edge slots after the split number the
    // larger of those before (within the limit) and the alive edges after it: the test on the
    // alive count is exact. One load, a compare with a constant and a branch never taken.
    if (n_edges_ > kMaxHalfedges / 2 - 3) throw_too_many_halfedges(2 * (std::uint64_t(n_edges_) + 3), "split");
    const Vertex b = from(to_c);
    const Vertex c = to(to_c), d = to(to_d);

    // New elements: vertex a, edges a-b (h, t), b-c (hn, on) and d-b (tp, op), faces f0, f1.
    const Vertex a = new_vertex(p);
    const Edge e_ab = new_edge(), e_bc = new_edge(), e_db = new_edge();
    const Halfedge h = halfedge(e_ab, 0), t = halfedge(e_ab, 1);
    const Halfedge hn = halfedge(e_bc, 0), on = halfedge(e_bc, 1);
    const Halfedge tp = halfedge(e_db, 0), op = halfedge(e_db, 1);
    const Face f0 = new_face(), f1 = new_face();

    // Hand the outgoing half-edges to_c ... to_d (counter-clockwise) over to a. Rotation reads
    // only next(), so retargeting the twins while walking is safe.
    for (Halfedge o = to_c;; o = ccw_rotated(o)) {
        he_[twin(o).idx].to = a.idx;
        if (o == to_d) break;
    }

    // The old half-edges c -> b (now c -> a) and b -> d (now a -> d) move into the new faces;
    // fresh half-edges take their places in the faces they leave.
    const Halfedge hp = twin(to_c), tn = to_d;
    he_[on.idx].to = b.idx;
    replace_in_face(hp, on);
    he_[op.idx].to = d.idx;
    replace_in_face(tn, op);

    // f0 = (a, b, c), f1 = (b, a, d).
    he_[h.idx].to = b.idx;
    he_[hn.idx].to = c.idx;
    link_face(f0, h, hn, hp);
    he_[t.idx].to = a.idx;
    he_[tp.idx].to = b.idx;
    link_face(f1, t, tn, tp);

    vhe_[a.idx] = h.idx;
    if (from(halfedge(b)) != b) vhe_[b.idx] = t.idx;  // b's stored half-edge moved to a
#ifdef NMESH_CHECK_INVARIANTS
    assert_manifold_after(*this, "split", {a, b});
#endif
    return a;
}

// ---- edge collapse ------------------------------------------------------------------------------

bool Mesh::can_collapse(Halfedge h) const {
    if (!h.valid() || h.idx >= halfedge_capacity() || is_removed(h)) return false;
    if (n_vertices_ <= 4) return false;  // a tetrahedron is the smallest closed manifold
    const Vertex a = from(h), b = to(h);
    // Next to a boundary only edges between two interior vertices collapse: their faces, ring
    // walks and link condition are those of a closed mesh.
    if (n_boundary_ != 0 && (is_boundary(a) || is_boundary(b))) return false;
    const Vertex c = to(next(h)), d = to(next(twin(h)));
    const std::uint32_t va = valence(a), vb = valence(b);
    if (va + vb < 4 + 3) return false;                     // b would end below valence 3
    if (valence(c) <= 3 || valence(d) <= 3) return false;  // c and d each lose one neighbour
    // Link condition: the neighbours a and b share are exactly c and d.
    std::uint32_t shared = 0;
    bool ok = true;
    for_each_neighbor(a, [&](Vertex x) {
        if (x == b) return;
        for_each_neighbor(b, [&](Vertex y) {
            if (x == y) {
                ++shared;
                if (x != c && x != d) ok = false;
            }
        });
    });
    return ok && shared == 2;
}

void Mesh::collapse(Halfedge h) {
    assert(can_collapse(h));
    // Faces f0 = (a, b, c) and f1 = (b, a, d) around h = a -> b disappear, with edges a-b, b-c
    // and d-b; the edges c-a and a-d survive as c-b and b-d.
    const Halfedge hn = next(h), hp = next(hn);
    const Halfedge t = twin(h), tn = next(t), tp = next(tn);
    const Vertex a = from(h), b = to(h), c = to(hn), d = to(tn);
    const Face f0 = face_if_any(h), f1 = face_if_any(t);
    const Halfedge on = twin(hn), op = twin(tp);

    // Everything that pointed to a now points to b.
    for_each_outgoing(a, [&](Halfedge o) { he_[twin(o).idx].to = b.idx; });

    replace_in_face(on, hp);  // hp = c -> b takes the place of the dying c -> b
    replace_in_face(op, tn);  // tn = b -> d takes the place of the dying b -> d

    vhe_[b.idx] = twin(hp).idx;
    if (vhe_[c.idx] == on.idx) vhe_[c.idx] = hp.idx;
    if (vhe_[d.idx] == tp.idx) vhe_[d.idx] = twin(tn).idx;

    delete_face(f0);
    delete_face(f1);
    delete_edge(edge(h));
    delete_edge(edge(hn));
    delete_edge(edge(tp));
    delete_vertex(a);
#ifdef NMESH_CHECK_INVARIANTS
    assert_manifold_after(*this, "collapse", {b});
#endif
}

// ---- edge flip ----------------------------------------------------------------------------------

bool Mesh::can_flip(Halfedge h) const {
    if (!h.valid() || h.idx >= halfedge_capacity() || is_removed(h)) return false;
    if (n_boundary_ != 0 && is_boundary(edge(h))) return false;  // a boundary edge has one face
    const Vertex a = from(h), b = to(h);
    const Vertex c = to(next(h)), d = to(next(twin(h)));
    if (c == d) return false;
    if (valence(a) <= 3 || valence(b) <= 3) return false;  // a and b each lose one neighbour
    return !find_halfedge(c, d).valid();                   // c-d must not exist already
}

FlipRecord Mesh::flip(Halfedge h) {
    assert(can_flip(h));
    // Before: f0 = [h: a->b, hn: b->c, hp: c->a], f1 = [t: b->a, tn: a->d, tp: d->b].
    // After:  f0 = [h: d->c, hp, tn],              f1 = [t: c->d, tp, hn].
    const Halfedge hn = next(h), hp = next(hn);
    const Halfedge t = twin(h), tn = next(t), tp = next(tn);
    const Vertex a = from(h), b = to(h);
    const Face f0 = face_if_any(h), f1 = face_if_any(t);
    FlipRecord r{h, halfedge(a), halfedge(b), {}};
    if (faces_) r.old_face_he[0] = halfedge(f0), r.old_face_he[1] = halfedge(f1);

    he_[h.idx].to = he_[hn.idx].to;  // c
    he_[t.idx].to = he_[tn.idx].to;  // d
    link_face(f0, h, hp, tn);
    link_face(f1, t, tp, hn);
    if (vhe_[a.idx] == h.idx) vhe_[a.idx] = tn.idx;
    if (vhe_[b.idx] == t.idx) vhe_[b.idx] = hn.idx;
#ifdef NMESH_CHECK_INVARIANTS
    assert_manifold_after(*this, "flip", {from(h), to(h)});
#endif
    return r;
}

void Mesh::unflip(const FlipRecord& r) {
    // The mirror image of flip(): with the current f0 = [h, x, y] and f1 = [t, u, w], the old
    // faces were [h, w, x] and [t, y, u].
    const Halfedge h = r.h, t = twin(h);
    const Halfedge x = next(h), y = next(x);
    const Halfedge u = next(t), w = next(u);
    const Face f0 = face_if_any(h), f1 = face_if_any(t);
    he_[h.idx].to = he_[u.idx].to;  // b
    he_[t.idx].to = he_[x.idx].to;  // a
    link_face(f0, h, w, x);
    link_face(f1, t, y, u);
    vhe_[from(h).idx] = r.old_out_from.idx;
    vhe_[to(h).idx] = r.old_out_to.idx;
    if (faces_) {
        fhe_[f0.idx] = r.old_face_he[0].idx;
        fhe_[f1.idx] = r.old_face_he[1].idx;
    }
#ifdef NMESH_CHECK_INVARIANTS
    assert_manifold_after(*this, "unflip", {from(h), to(h)});
#endif
}

// ---- face removal -------------------------------------------------------------------------------

bool Mesh::can_remove_face(Face f) const {
    if (!faces_ || !f.valid() || f.idx >= face_capacity() || is_removed(f)) return false;
    const Halfedge h0 = halfedge(f), h1 = next(h0), h2 = next(h1);
    const Halfedge hs[3] = {h0, h1, h2};
    int on_boundary = 0, which = 0;
    for (int i = 0; i < 3; ++i)
        if (is_boundary(twin(hs[i]))) ++on_boundary, which = i;
    if (on_boundary == 0) return !is_boundary(from(h0)) && !is_boundary(from(h1)) && !is_boundary(from(h2));
    // The vertex opposite the boundary edge would get a second gap if it is on a boundary. An
    // ear's middle vertex has f as its only face (one gap, on both sides of f).
    if (on_boundary == 1) return !is_boundary(to(next(hs[which])));
    return on_boundary == 2;
}

Vertex Mesh::remove_face(Face f) {
    assert(can_remove_face(f));
    const Halfedge h0 = halfedge(f);
    int on_boundary = 0;
    for (Halfedge h = h0;;) {
        on_boundary += is_boundary(twin(h));
        if ((h = next(h)) == h0) break;
    }
    Vertex removed;
    if (on_boundary == 0) {
        // A new loop of three: f's own next cycle, now without a face.
        for (Halfedge h = h0;;) {
            he_face_[h.idx] = kInvalidIndex;
            vhe_[from(h).idx] = h.idx;  // a boundary vertex stores its outgoing boundary half-edge
            ++n_boundary_;
            if ((h = next(h)) == h0) break;
        }
    } else if (on_boundary == 1) {
        Halfedge hi = h0;  // f's half-edge along the boundary
        while (!is_boundary(twin(hi))) hi = next(hi);
        // f = [hi: u -> w, hn: w -> o, hp: o -> u] beside the loop ... pb -> bt -> nb ..., bt = w -> u:
        // the loop becomes ... pb -> hn -> hp -> nb ..., and the edge u - w goes.
        const Halfedge bt = twin(hi), hn = next(hi), hp = next(hn);
        const Halfedge pb = prev_on_boundary(bt), nb = next(bt);
        const Vertex w = to(hi), o = to(hn);
        he_[pb.idx].next = hn.idx;
        he_[hp.idx].next = nb.idx;
        he_face_[hn.idx] = he_face_[hp.idx] = kInvalidIndex;
        vhe_[w.idx] = hn.idx;  // w's outgoing boundary half-edge was bt
        vhe_[o.idx] = hp.idx;
        n_boundary_ += 1;  // hn and hp in, bt out
        delete_edge(edge(hi));
    } else {
        // An ear f = [hi: u -> v, hn: v -> w, hp: w -> u] with u - v and v - w on the loop
        // ... pb -> (w -> v) -> (v -> u) -> nb ...: the loop becomes ... pb -> hp -> nb ..., and v goes
        // with its two edges.
        Halfedge hi = h0;
        while (!(is_boundary(twin(hi)) && is_boundary(twin(next(hi))))) hi = next(hi);
        const Halfedge hn = next(hi), hp = next(hn);
        const Halfedge wv = twin(hn), vu = twin(hi);
        const Halfedge pb = prev_on_boundary(wv), nb = next(vu);
        const Vertex w = to(hn);
        removed = to(hi);
        he_[pb.idx].next = hp.idx;
        he_[hp.idx].next = nb.idx;
        he_face_[hp.idx] = kInvalidIndex;
        vhe_[w.idx] = hp.idx;  // w's outgoing boundary half-edge was w -> v
        // u's was nb, which stays.
        n_boundary_ -= 1;  // hp in, w -> v and v -> u out
        delete_edge(edge(hi));
        delete_edge(edge(hn));
        delete_vertex(removed);
    }
    delete_face(f);
#ifdef NMESH_CHECK_INVARIANTS
    assert_manifold(*this, "remove_face");
#endif
    return removed;
}

// ---- joining two loops ----------------------------------------------------------------------------

Mesh::JoinPlan Mesh::plan_join(Halfedge a, Halfedge b) const {
    JoinPlan plan;
    for (Halfedge h = a;;) {  // p_i = from(a_i), a_i = p_i -> p_i+1
        plan.p.push_back(from(h).idx);
        plan.p_he.push_back(h.idx);
        h = next(h);
        if (h == a) break;
    }
    for (Halfedge h = b;;) {  // q_k = to(b_k), b_k = q_k+1 -> q_k, walking b's loop backwards
        plan.q.push_back(to(h).idx);
        plan.q_he.push_back(h.idx);
        h = prev_on_boundary(h);
        if (h == b) break;
    }
    const std::size_t m = plan.p.size(), n = plan.q.size();
    auto dist2 = [&](std::uint32_t u, std::uint32_t v) { return squared_norm(vpos_[u] - vpos_[v]); };
    // The zip is a staircase from (0, 0) to (m, n) on the grid of edges p_i - q_k, whose far
    // sides wrap round: (i, n) is the edge (i, 0) and (m, k) the edge (0, k). So a step may not
    // reach (i, n) when the zip began along p past i, nor (m, k) when it began along q past k;
    // only (m, n), the first edge again, closes it. One of the two steps is always allowed.
    std::size_t i = 0, k = 0, p_run = 0, q_run = 0;  // the first edges along p / q: (p_run, 0) ...
    auto repeats = [&](std::size_t ni, std::size_t nk) {
        return (nk == n && ni < m && ni <= p_run) || (ni == m && nk < n && nk <= q_run);
    };
    while (i < m || k < n) {
        // Along p the new edge is p_i+1 - q_k; along q it is p_i - q_k+1.
        bool along_p;
        if (i == m || (k < n && repeats(i + 1, k)))
            along_p = false;
        else if (k == n || repeats(i, k + 1))
            along_p = true;
        else
            along_p = dist2(plan.p[(i + 1) % m], plan.q[k]) <= dist2(plan.p[i], plan.q[(k + 1) % n]);
        plan.along_p.push_back(along_p);
        if (along_p) {
            if (k == 0) p_run = i + 1;
            ++i;
        } else {
            if (i == 0) q_run = k + 1;
            ++k;
        }
    }
    return plan;
}

bool Mesh::can_join_loops(Halfedge a, Halfedge b) const {
    if (!faces_ || !a.valid() || !b.valid() || a.idx >= halfedge_capacity() || b.idx >= halfedge_capacity())
        return false;
    if (is_removed(a) || is_removed(b) || !is_boundary(a) || !is_boundary(b)) return false;
    for (Halfedge h = next(a); h != a; h = next(h))
        if (h == b) return false;  // one loop
    if (std::uint64_t(n_edges_) + loop_length(a) + loop_length(b) > kMaxHalfedges / 2) return false;
    const JoinPlan plan = plan_join(a, b);
    // Every new edge p_i - q_k must be new: the two loops share no vertex (a vertex has one gap),
    // so only an existing edge between them can repeat one.
    const std::size_t m = plan.p.size(), n = plan.q.size();
    std::size_t i = 0, k = 0;
    for (const char along_p : plan.along_p) {
        if (find_halfedge(Vertex(plan.p[i % m]), Vertex(plan.q[k % n])).valid()) return false;
        along_p ? ++i : ++k;
    }
    return true;
}

void Mesh::join_loops(Halfedge a, Halfedge b) {
    assert(can_join_loops(a, b));
    const JoinPlan plan = plan_join(a, b);
    const std::size_t m = plan.p.size(), n = plan.q.size();
    // Each step makes one face from a boundary half-edge and two edges p - q: the step's first
    // edge, run q -> p, and its last, run p -> q (its half-edges 0: p -> q and 1: q -> p); the
    // last step's last edge is the first step's first.
    auto new_rung = [&](std::uint32_t p, std::uint32_t q) {
        const Edge e = new_edge();
        he_[halfedge(e, 0).idx].to = q;
        he_[halfedge(e, 1).idx].to = p;
        return e;
    };
    const Edge first = new_rung(plan.p[0], plan.q[0]);
    Edge current = first;
    std::size_t i = 0, k = 0;
    for (std::size_t s = 0; s < plan.along_p.size(); ++s) {
        const bool along_p = plan.along_p[s];
        const std::size_t ni = along_p ? i + 1 : i, nk = along_p ? k : k + 1;
        const bool last = s + 1 == plan.along_p.size();
        const Edge end = last ? first : new_rung(plan.p[ni % m], plan.q[nk % n]);
        const Face f = new_face();
        if (along_p)  // (p_i, p_i+1, q_k)
            link_face(f, Halfedge(plan.p_he[i]), halfedge(end, 0), halfedge(current, 1));
        else  // (q_k+1, q_k, p_i)
            link_face(f, Halfedge(plan.q_he[k]), halfedge(current, 1), halfedge(end, 0));
        current = end;
        i = ni;
        k = nk;
    }
    n_boundary_ -= std::uint32_t(m + n);
    // The loops' vertices keep their stored half-edges: still outgoing, now inside faces.
#ifdef NMESH_CHECK_INVARIANTS
    assert_manifold(*this, "join_loops");
#endif
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
