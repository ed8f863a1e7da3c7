#include "nmesh/mesh/mesh_check.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace nmesh {
namespace {

struct Checker {
    const Mesh& m;
    std::ostringstream err;
    bool failed = false;
    std::uint32_t loops = 0;
    std::int64_t euler = 0;

    template <class... T>
    bool fail(const T&... parts) {
        if (!failed) {
            failed = true;
            (err << ... << parts);
        }
        return false;
    }

    bool vertex_ok(std::uint32_t v) const { return v < m.vertex_capacity() && !m.is_removed(Vertex(v)); }
    bool face_ok(std::uint32_t f) const { return f < m.face_capacity() && !m.is_removed(Face(f)); }
    bool halfedge_ok(std::uint32_t h) const { return h < m.halfedge_capacity() && !m.is_removed(Halfedge(h)); }

    // Walks a free list; every slot on it must be free, and it must hold all free slots.
    template <class Removed, class Next>
    bool free_list(const char* what, std::uint32_t head, std::uint32_t capacity, std::uint32_t alive, Removed removed,
                   Next next_free) {
        std::uint32_t count = 0;
        for (std::uint32_t s = head; s != kInvalidIndex; s = next_free(s)) {
            if (s >= capacity) return fail(what, " free list: slot ", s, " is out of range");
            if (!removed(s)) return fail(what, " free list: slot ", s, " is alive");
            if (++count > capacity) return fail(what, " free list has a cycle");
        }
        if (count + alive != capacity)
            return fail(what, " free list holds ", count, " slots but ", capacity - alive, " are free");
        return true;
    }

    bool counts() {
        std::uint32_t v = 0, f = 0, e = 0;
        for (std::uint32_t i = 0; i < m.vertex_capacity(); ++i) v += !m.is_removed(Vertex(i));
        for (std::uint32_t i = 0; i < m.face_capacity(); ++i) f += !m.is_removed(Face(i));
        for (std::uint32_t i = 0; i < m.edge_capacity(); ++i) e += !m.is_removed(Edge(i));
        if (v != m.n_vertices()) return fail("vertex count ", m.n_vertices(), " but ", v, " alive slots");
        if (m.has_faces() && f != m.n_faces()) return fail("face count ", m.n_faces(), " but ", f, " alive slots");
        if (e != m.n_edges()) return fail("edge count ", m.n_edges(), " but ", e, " alive slots");
        return free_list(
                   "vertex", m.free_vertex_head(), m.vertex_capacity(), v,
                   [&](std::uint32_t s) { return m.is_removed(Vertex(s)); },
                   [&](std::uint32_t s) { return m.next_free_vertex(s); }) &&
               free_list(
                   "face", m.free_face_head(), m.face_capacity(), f,
                   [&](std::uint32_t s) { return m.is_removed(Face(s)); },
                   [&](std::uint32_t s) { return m.next_free_face(s); }) &&
               free_list(
                   "edge", m.free_edge_head(), m.edge_capacity(), e,
                   [&](std::uint32_t s) { return m.is_removed(Edge(s)); },
                   [&](std::uint32_t s) { return m.next_free_edge(s); });
    }

    // Half-edges without a face: boundary half-edges (only with the face index).
    bool faceless(std::uint32_t h) const { return m.has_faces() && m.face(Halfedge(h)).idx == kInvalidIndex; }

    bool halfedges() {
        // Without the face index (Mesh::drop_faces) the next cycles are checked alone.
        const bool named = m.has_faces();
        std::uint32_t boundary = 0;
        std::vector<std::uint8_t> has_prev(m.halfedge_capacity(), 0);
        for (std::uint32_t i = 0; i < m.halfedge_capacity(); ++i) {
            const Halfedge h(i);
            if (m.is_removed(h)) continue;
            const std::uint32_t to = m.to(h).idx, nx = m.next(h).idx;
            if (!vertex_ok(to)) return fail("half-edge ", i, " points to vertex ", to, ", which is not alive");
            if (!halfedge_ok(nx)) return fail("half-edge ", i, ": next ", nx, " is not alive");
            if (nx == i) return fail("half-edge ", i, " is its own next");
            if (has_prev[nx]++) return fail("half-edge ", nx, " follows two half-edges (next is not a permutation)");
            const std::uint32_t origin = m.to(Mesh::twin(h)).idx;
            if (origin == to) return fail("half-edge ", i, " is a loop at vertex ", to);
            if (faceless(i)) {
                ++boundary;
                if (faceless(i ^ 1u)) return fail("edge ", i / 2, " has no face on either side");
                if (!faceless(nx)) return fail("boundary half-edge ", i, ": its next ", nx, " has a face");
                if (m.to(Mesh::twin(Halfedge(nx))).idx != to)
                    return fail("boundary half-edge ", i, ": its next does not leave its target ", to);
                continue;
            }
            const std::uint32_t f = named ? m.face(h).idx : 0;
            if (named && !face_ok(f)) return fail("half-edge ", i, ": face ", f, " is not alive");
            const Halfedge n2 = m.next(Halfedge(nx));
            if (!halfedge_ok(n2.idx) || m.next(n2).idx != i)
                return fail("half-edge ", i, ": the next cycle does not close after 3 steps");
            if (named && (m.face(Halfedge(nx)).idx != f || m.face(n2).idx != f))
                return fail("half-edge ", i, ": its next cycle spans several faces");
            if (m.to(n2).idx != origin)  // the target of prev
                return fail("half-edge ", i, ": inconsistent orientation (twin ends at ", origin,
                            ", previous half-edge ends at ", m.to(n2).idx, ")");
        }
        if (boundary != m.n_boundary_halfedges())
            return fail("boundary half-edge count ", m.n_boundary_halfedges(), " but ", boundary, " without a face");
        // The loops, each walked once.
        std::vector<std::uint8_t> seen(m.halfedge_capacity(), 0);
        for (std::uint32_t i = 0; i < m.halfedge_capacity(); ++i) {
            if (m.is_removed(Halfedge(i)) || !faceless(i) || seen[i]) continue;
            std::uint32_t length = 0;
            for (std::uint32_t h = i; !seen[h]; h = m.next(Halfedge(h)).idx) seen[h] = 1, ++length;
            if (length < 3) return fail("boundary loop at half-edge ", i, " has ", length, " half-edges");
            ++loops;
        }
        return true;
    }

    bool faces() {
        // Without the face index (face_capacity() 0) only the count is checked: 3F half-edges.
        for (std::uint32_t f = 0; f < m.face_capacity(); ++f) {
            if (m.is_removed(Face(f))) continue;
            const std::uint32_t h = m.halfedge(Face(f)).idx;
            if (!halfedge_ok(h)) return fail("face ", f, ": half-edge ", h, " is not alive");
            if (m.face(Halfedge(h)).idx != f)
                return fail("face ", f, ": its half-edge ", h, " belongs to face ", m.face(Halfedge(h)).idx);
        }
        if (2 * std::uint64_t(m.n_edges()) != 3 * std::uint64_t(m.n_faces()) + m.n_boundary_halfedges())
            return fail("2E != 3F + B (E = ", m.n_edges(), ", F = ", m.n_faces(), ", B = ", m.n_boundary_halfedges(),
                        ")");
        return true;
    }

    bool vertices() {
        std::vector<std::uint32_t> out_degree(m.vertex_capacity(), 0), out_boundary(m.vertex_capacity(), 0);
        for (std::uint32_t i = 0; i < m.halfedge_capacity(); ++i) {
            if (m.is_removed(Halfedge(i))) continue;
            ++out_degree[m.from(Halfedge(i)).idx];
            if (faceless(i)) ++out_boundary[m.from(Halfedge(i)).idx];
        }
        std::vector<std::uint32_t> stamp(m.vertex_capacity(), kInvalidIndex);
        for (std::uint32_t v = 0; v < m.vertex_capacity(); ++v) {
            if (m.is_removed(Vertex(v))) continue;
            const Halfedge start = m.halfedge(Vertex(v));
            if (!halfedge_ok(start.idx)) return fail("vertex ", v, ": half-edge ", start.idx, " is not alive");
            if (m.from(start).idx != v)
                return fail("vertex ", v, ": its half-edge ", start.idx, " leaves vertex ", m.from(start).idx);
            if (out_boundary[v] > 1)
                return fail("vertex ", v, " has ", out_boundary[v], " boundary gaps (a bow-tie vertex)");
            if (out_boundary[v] == 1 && !faceless(start.idx))
                return fail("vertex ", v, ": on a boundary, but its stored half-edge ", start.idx, " has a face");
            std::uint32_t ring = 0;
            Halfedge h = start;
            do {
                const std::uint32_t u = m.to(h).idx;
                if (stamp[u] == v) return fail("vertex ", v, ": neighbour ", u, " appears twice (duplicate edge)");
                stamp[u] = v;
                if (++ring > out_degree[v]) break;
                h = m.cw_rotated(h);
            } while (h != start);
            if (ring != out_degree[v])
                return fail("vertex ", v, ": its one-ring is not a single cycle (", ring,
                            " half-edges in the rotation, ", out_degree[v], " leave the vertex)");
            if (ring < 3 - out_boundary[v]) return fail("vertex ", v, " has valence ", ring);
        }
        return true;
    }

    bool topology() {
        if (m.n_vertices() == 0) return fail("the mesh is empty");
        std::vector<std::uint8_t> seen(m.vertex_capacity(), 0);
        std::vector<std::uint32_t> stack;
        std::uint32_t first = 0;
        while (m.is_removed(Vertex(first))) ++first;
        stack.push_back(first);
        seen[first] = 1;
        std::uint32_t reached = 1;
        while (!stack.empty()) {
            const Vertex v(stack.back());
            stack.pop_back();
            m.for_each_outgoing_cw(v, [&](Halfedge h) {
                const Vertex u = m.to(h);
                if (!seen[u.idx]) {
                    seen[u.idx] = 1;
                    ++reached;
                    stack.push_back(u.idx);
                }
            });
        }
        if (reached != m.n_vertices())
            return fail("the mesh is not connected (", reached, " of ", m.n_vertices(), " vertices reachable)");
        euler = std::int64_t(m.n_vertices()) - m.n_edges() + m.n_faces();
        const std::int64_t twice_genus = 2 - euler - std::int64_t(loops);
        if (twice_genus < 0 || twice_genus % 2 != 0)
            return fail("Euler characteristic V - E + F = ", euler, " with ", loops,
                        " boundary loops gives no whole genus");
        return true;
    }
};

// The one-ring of vertex v, as check_around describes; appends v's neighbours to `neighbours`.
template <class Fail>
bool ring_ok(const Mesh& m, std::uint32_t v, std::vector<std::uint32_t>& neighbours, Fail fail) {
    const auto halfedge_ok = [&](std::uint32_t h) { return h < m.halfedge_capacity() && !m.is_removed(Halfedge(h)); };
    const bool named = m.has_faces();
    const auto faceless = [&](Halfedge h) { return named && m.face(h).idx == kInvalidIndex; };
    if (v >= m.vertex_capacity() || m.is_removed(Vertex(v))) return fail("vertex ", v, " is not alive");
    const Halfedge start = m.halfedge(Vertex(v));
    if (!halfedge_ok(start.idx)) return fail("vertex ", v, ": half-edge ", start.idx, " is not alive");
    const std::size_t first = neighbours.size();
    std::uint32_t gaps = 0;
    Halfedge h = start;
    do {
        if (!halfedge_ok(h.idx)) return fail("vertex ", v, ": its rotation reaches half-edge ", h.idx, ", not alive");
        if (m.from(h).idx != v)
            return fail("vertex ", v, ": its rotation reaches half-edge ", h.idx, ", which leaves vertex ", m.from(h).idx);
        const std::uint32_t u = m.to(h).idx;
        if (u >= m.vertex_capacity() || m.is_removed(Vertex(u)))
            return fail("half-edge ", h.idx, " points to vertex ", u, ", which is not alive");
        if (u == v) return fail("half-edge ", h.idx, " is a loop at vertex ", v);
        for (std::size_t i = first; i < neighbours.size(); ++i)
            if (neighbours[i] == u) return fail("vertex ", v, ": neighbour ", u, " appears twice (duplicate edge)");
        neighbours.push_back(u);
        if (neighbours.size() - first > m.halfedge_capacity())
            return fail("vertex ", v, ": its rotation does not come back to its stored half-edge");
        if (faceless(h)) {
            ++gaps;
            if (faceless(Mesh::twin(h))) return fail("edge ", h.idx / 2, " has no face on either side");
        } else {
            const Halfedge n1 = m.next(h);
            const Halfedge n2 = halfedge_ok(n1.idx) ? m.next(n1) : Halfedge();
            if (!halfedge_ok(n1.idx) || !halfedge_ok(n2.idx) || m.next(n2) != h)
                return fail("half-edge ", h.idx, ": the next cycle does not close after 3 steps");
            // Each half-edge of the cycle leaves the vertex its predecessor ends at (where it
            // leaves: its twin's target), and the cycle comes back to v.
            const Halfedge cycle[3] = {h, n1, n2};
            for (int i = 0; i < 3; ++i) {
                const Halfedge x = cycle[i], y = cycle[(i + 1) % 3];
                if (m.to(x) != m.from(y))
                    return fail("half-edge ", x.idx, ": inconsistent orientation (it ends at ", m.to(x).idx,
                                ", its next half-edge leaves ", m.from(y).idx, ")");
            }
            if (named) {
                const std::uint32_t f = m.face(h).idx;
                if (f >= m.face_capacity() || m.is_removed(Face(f)))
                    return fail("half-edge ", h.idx, ": face ", f, " is not alive");
                if (m.face(n1).idx != f || m.face(n2).idx != f)
                    return fail("half-edge ", h.idx, ": its next cycle spans several faces");
                const Halfedge fh = m.halfedge(Face(f));
                if (fh != h && fh != n1 && fh != n2)
                    return fail("face ", f, ": its half-edge ", fh.idx, " is not in its next cycle");
            }
        }
        h = m.cw_rotated(h);
    } while (h != start);
    if (gaps > 1) return fail("vertex ", v, " has ", gaps, " boundary gaps (a bow-tie vertex)");
    if (gaps == 1 && !faceless(start))
        return fail("vertex ", v, ": on a boundary, but its stored half-edge ", start.idx, " has a face");
    const std::size_t valence = neighbours.size() - first;
    if (valence < 3 - gaps) return fail("vertex ", v, " has valence ", valence);
    return true;
}

}  // namespace

ManifoldCheck check_around(const Mesh& mesh, std::initializer_list<Vertex> centres) {
    std::ostringstream err;
    bool failed = false;
    const auto fail = [&](const auto&... parts) {
        failed = true;
        (err << ... << parts);
        return false;
    };
    std::vector<std::uint32_t> ring, scratch;
    for (const Vertex c : centres) {
        ring.clear();
        if (!ring_ok(mesh, c.idx, ring, fail)) break;
        bool ok = true;
        for (const std::uint32_t u : ring) {
            scratch.clear();
            if (!(ok = ring_ok(mesh, u, scratch, fail))) break;
        }
        if (!ok) break;
    }
    ManifoldCheck r;
    r.ok = !failed;
    r.error = err.str();
    return r;
}

ManifoldCheck check_manifold(const Mesh& mesh) {
    Checker c{mesh, {}, false};
    // Each stage relies on the previous ones (e.g. the rotation walk needs valid next cycles).
    const bool ok = c.counts() && c.halfedges() && c.faces() && c.vertices() && c.topology();
    ManifoldCheck r;
    r.ok = ok;
    if (!ok) {
        r.error = c.err.str();
        return r;
    }
    r.euler = c.euler;
    r.boundary_loops = c.loops;
    r.genus = int((2 - c.euler - std::int64_t(c.loops)) / 2);
    return r;
}

namespace {

void abort_if_invalid(const ManifoldCheck& r, const char* after) {
    if (!r.ok) {
        std::fprintf(stderr, "nmesh: invalid mesh after %s: %s\n", after, r.error.c_str());
        std::abort();
    }
}

}  // namespace

void assert_manifold(const Mesh& mesh, const char* after) { abort_if_invalid(check_manifold(mesh), after); }

void assert_manifold_after(const Mesh& mesh, const char* after, std::initializer_list<Vertex> centres) {
    abort_if_invalid(check_around(mesh, centres), after);
    // The whole check's schedule, per thread (operations on several meshes share it: each
    // operation still has its local check). The whole check walks every slot, free ones too: its
    // cost is the arrays' capacity, not the alive count (a mesh simplified from 50,000 vertices
    // to 150 keeps its slots, and was checked whole after nearly every collapse). 256 slots per
    // operation: with 4,096 the whole checks of a solid's surface simplified from 28,000
    // vertices took 85% of a sanitized run (docs/internals.md).
    constexpr std::uint64_t kEarnedPerOperation = 256;
    thread_local std::uint64_t earned = 0;
    earned += kEarnedPerOperation;
    const std::uint64_t cost =
        std::uint64_t(mesh.halfedge_capacity()) + mesh.vertex_capacity() + mesh.face_capacity();
    if (earned >= cost) {
        earned = 0;
        abort_if_invalid(check_manifold(mesh), after);
    }
}

}  // namespace nmesh
