// The half-edge mesh (nmesh/mesh/mesh.h): the operations at a boundary, face removal (a hole
// opened or widened) and the joining of two boundary loops by a tube.
#include "nmesh/mesh/mesh.h"

#include <algorithm>
#include <cassert>
#include <utility>

#include "nmesh/mesh/mesh_check.h"

namespace nmesh {

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

}  // namespace nmesh
