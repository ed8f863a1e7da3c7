// The half-edge mesh (nmesh/mesh/mesh.h): its slots and free lists, its queries, and the three
// operations the learning makes (vertex split, edge collapse, edge flip). Construction and
// export are in mesh_build.cpp, the operations at a boundary (face removal, loop joining) in
// mesh_boundary.cpp.
#include "nmesh/mesh/mesh.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "nmesh/mesh/mesh_check.h"

namespace nmesh {

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

}  // namespace nmesh
