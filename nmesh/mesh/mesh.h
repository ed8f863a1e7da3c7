// nmesh/mesh.h — an index-based half-edge mesh for triangle 2-manifolds, closed or with boundaries.
//
// Storage (arrays only, no node-based containers):
//   - half-edges come in pairs: edge e owns half-edges 2e and 2e+1, so twin(h) = h ^ 1;
//   - per half-edge: the vertex it points to, the next half-edge in its face, its face;
//   - per vertex: position and one outgoing half-edge; per face: one half-edge;
//   - a dead slot's own connectivity field (vertex -> outgoing half-edge, face -> half-edge,
//     edge -> next of its first half-edge) holds the next free slot with the top bit set
//     (slot | kFreeBit; the list's end, kInvalidIndex, has it set too): a free list and a dead
//     mark at no memory cost. An alive slot's field holds a half-edge index, below 2^31, so the
//     bit tells dead from alive: is_removed() loads the word the connectivity itself lives in,
//     and no separate flag arrays (6 bytes per vertex: 1 per vertex, 3 per vertex for its ~3
//     edges, 2 for its ~2 faces) are stored or written. The heads are kept in the same form, so
//     deleting stores the head into the slot and creation pops it with one mask, in O(1), last
//     freed first. A slot just created reads as removed until the operation links it.
//   - about 96 bytes per vertex in all (12 position, 4 outgoing half-edge, 6 x 12 half-edge
//     links and face, 2 x 4 face half-edge).
//
// Faces are an index beside the connectivity: the next() cycles alone describe the triangles,
// and the face of each half-edge (he_face_) and the half-edge of each face (fhe_) only name them.
// drop_faces() frees that index (32 bytes per vertex: 64 instead of 96) and build_faces() makes
// it again, in O(half-edges). Without it, the operations keep the same connectivity, half-edge,
// edge and vertex slots and counts (n_faces() included), the triangles can be read through
// next() and to_indexed(), and only the Face handles are unavailable (face(), halfedge(Face),
// is_removed(Face), face_normal/area/centroid; face_capacity() is 0). The learning loop, which
// needs no face names, runs without it; the finishing stage builds it. Built
// faces are numbered by their smallest half-edge, each starting at it: the order to_indexed()
// gives the triangles in without the index, so that building it changes no output.
//
// Size limit: alive fields must stay below the bit, so a mesh holds at most 2^31 half-edges
// (kMaxHalfedges), about 358 million vertices (kMaxVertices; a closed genus-0 mesh of V vertices
// has 6V - 12 half-edges). from_indexed, reserve and split throw before going past it. Vertex
// and face slots, fewer than half-edges, stay far below 2^31 - 1 too, so a marked free slot
// never reads as the list's end.
//
// The mesh core knows topology only. Each topology operation has a named predicate
// (can_split, can_collapse, can_flip, can_remove_face, can_join_loops) and asserts it; the
// learning algorithm adds its own rules on top. Split, collapse and flip keep the genus and the
// boundary loops; remove_face opens or widens a boundary; join_loops closes two loops with a tube.
//
// Boundaries: a boundary half-edge is an alive half-edge without a face, the twin of a face's
// half-edge; the boundary half-edges of a hole are linked by next() into one cycle (its loop, of
// any length >= 3) that runs opposite to the faces around it. Boundaries need the face index
// (a boundary half-edge is one whose face is kInvalidIndex), so a mesh with boundaries keeps it:
// drop_faces() refuses. A boundary vertex has exactly one gap (no bow-tie): one outgoing and one
// incoming boundary half-edge, and its stored half-edge is the outgoing one, so is_boundary(v)
// is one load. On a closed mesh every boundary test is a compare of a zero counter.
// Rotation next to a boundary: cw_rotated() (next(twin(h))) passes through the gap in one step;
// ccw_rotated() walks round the vertex once to cross it (prev(h) is next(next(h)) only inside a
// triangle). A loop over a vertex's triangles skips the gap (for_each_corner).
//
// Orientation: faces are counter-clockwise seen from outside; next() walks a face CCW; the
// outgoing half-edges of a vertex are visited CCW by ccw_rotated(h) = twin(prev(h)).
#pragma once

#include <array>
#include <cassert>
#include <cstdint>
#include <limits>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/vec3.h"

namespace nmesh {

inline constexpr std::uint32_t kInvalidIndex = std::numeric_limits<std::uint32_t>::max();

// Typed 4-byte handles; default-constructed handles are invalid.
template <class Tag>
struct Handle {
    std::uint32_t idx = kInvalidIndex;
    constexpr Handle() = default;
    constexpr explicit Handle(std::uint32_t i) : idx(i) {}
    constexpr bool valid() const { return idx != kInvalidIndex; }
    constexpr bool operator==(Handle o) const { return idx == o.idx; }
    constexpr bool operator!=(Handle o) const { return idx != o.idx; }
    constexpr bool operator<(Handle o) const { return idx < o.idx; }
};
using Vertex = Handle<struct VertexTag>;
using Halfedge = Handle<struct HalfedgeTag>;
using Face = Handle<struct FaceTag>;
using Edge = Handle<struct EdgeTag>;

// What flip() changed, so that unflip() can restore the mesh bit for bit.
struct FlipRecord {
    Halfedge h;             // the flipped half-edge (same slot before and after)
    Halfedge old_out_from;  // outgoing half-edge stored at the old edge's endpoints before
    Halfedge old_out_to;
    Halfedge old_face_he[2];  // half-edge stored at face(h) and face(twin(h)) before (with faces)
};

class Mesh {
public:
    Mesh() = default;

    // A regular tetrahedron inscribed in the sphere (center, radius), faces oriented outward.
    static Mesh tetrahedron(const Vec3& center = {}, float radius = 1.0f);
    // A tetrahedron on four given points; the orientation is fixed so faces point outward
    // (the points must not be coplanar).
    static Mesh tetrahedron(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
    // Builds the half-edge form of a dense mesh. Throws InputError unless the triangles form a
    // consistently oriented, connected 2-manifold of any genus using every vertex, closed unless
    // `allow_boundary` (then without bow-tie vertices). O(F log F).
    static Mesh from_indexed(const IndexedMesh& in, bool allow_boundary = false);

    // ---- sizes ------------------------------------------------------------------------------
    std::uint32_t n_vertices() const { return n_vertices_; }  // alive
    std::uint32_t n_faces() const { return n_faces_; }
    std::uint32_t n_edges() const { return n_edges_; }
    // Slot counts (alive + free): every handle index is below these; per-element arrays kept by
    // an algorithm are sized by them.
    std::uint32_t vertex_capacity() const { return std::uint32_t(vpos_.size()); }
    std::uint32_t face_capacity() const { return std::uint32_t(fhe_.size()); }  // 0 without faces
    std::uint32_t edge_capacity() const { return std::uint32_t(he_.size() / 2); }
    std::uint32_t halfedge_capacity() const { return std::uint32_t(he_.size()); }
    // Reserve room for n vertices (and the ~2n faces and ~3n edges that come with them).
    // Throws ParameterError when n > kMaxVertices.
    void reserve(std::uint32_t n);

    // The size limit (see the top of this file): every half-edge index stays below 2^31.
    static constexpr std::uint32_t kMaxHalfedges = std::uint32_t(1) << 31;
    static constexpr std::uint32_t kMaxVertices = (kMaxHalfedges + 12) / 6;  // 357,913,943
    // Throws InputError, naming `what`, when `halfedges` half-edges would not fit. from_indexed
    // checks through it, split makes the same test on its alive edge count, both before changing
    // anything.
    static void check_halfedge_count(std::uint64_t halfedges, const char* what) {
        if (halfedges > kMaxHalfedges) throw_too_many_halfedges(halfedges, what);
    }

    // The face index (see the top of this file). A new mesh has it.
    bool has_faces() const { return faces_; }
    // Frees the face index: the Face handles are gone until build_faces(). O(1). Throws
    // ParameterError on a mesh with boundaries (they are told apart by the index).
    void drop_faces();
    // Makes the face index, when there is none: faces numbered 0 .. n_faces() - 1 in the order
    // of their smallest half-edge, which is also the one halfedge(Face) returns; no free face
    // slots. O(half-edges).
    void build_faces();

    // Dead or alive: the top bit of the slot's own connectivity field (one load and a mask).
    bool is_removed(Vertex v) const { return (vhe_[v.idx] & kFreeBit) != 0; }
    bool is_removed(Face f) const {  // needs faces
        assert(faces_);
        return (fhe_[f.idx] & kFreeBit) != 0;
    }
    bool is_removed(Edge e) const { return (he_[2 * e.idx].next & kFreeBit) != 0; }
    bool is_removed(Halfedge h) const { return (he_[h.idx & ~1u].next & kFreeBit) != 0; }

    // ---- connectivity -----------------------------------------------------------------------
    Vertex to(Halfedge h) const { return Vertex(he_[h.idx].to); }
    Vertex from(Halfedge h) const { return to(twin(h)); }
    Halfedge next(Halfedge h) const { return Halfedge(he_[h.idx].next); }
    Halfedge prev(Halfedge h) const {  // faces are triangles; see prev_on_boundary()
        assert(!is_boundary(h));
        return next(next(h));
    }
    static Halfedge twin(Halfedge h) { return Halfedge(h.idx ^ 1u); }
    static Edge edge(Halfedge h) { return Edge(h.idx >> 1); }
    static Halfedge halfedge(Edge e, int i) { return Halfedge((e.idx << 1) | std::uint32_t(i)); }
    Face face(Halfedge h) const {  // needs faces; an invalid handle for a boundary half-edge
        assert(faces_);
        return Face(he_face_[h.idx]);
    }
    Halfedge halfedge(Vertex v) const { return Halfedge(vhe_[v.idx]); }  // an outgoing one
    Halfedge halfedge(Face f) const {                                    // needs faces
        assert(faces_);
        return Halfedge(fhe_[f.idx]);
    }
    // The smallest of the three half-edges of h's triangle: the triangle's name without the face
    // index (right after build_faces(), halfedge(face(h)) is this one).
    Halfedge first_of_triangle(Halfedge h) const {
        const std::uint32_t a = h.idx, b = he_[a].next, c = he_[b].next;
        const std::uint32_t ab = a < b ? a : b;
        return Halfedge(ab < c ? ab : c);
    }
    // Next outgoing half-edge of from(h), counter-clockwise / clockwise. Counter-clockwise past
    // a boundary gap costs a walk round the vertex (prev_on_boundary); on a closed mesh the test
    // is a compare of a zero counter.
    Halfedge ccw_rotated(Halfedge h) const { return twin(is_boundary(h) ? prev_on_boundary(h) : prev(h)); }
    Halfedge cw_rotated(Halfedge h) const { return next(twin(h)); }
    // The half-edge a -> b, or an invalid handle when a and b are not adjacent. O(valence(a)).
    Halfedge find_halfedge(Vertex a, Vertex b) const;
    std::uint32_t valence(Vertex v) const;  // neighbours, boundary ones included

    // ---- boundaries -------------------------------------------------------------------------
    std::uint32_t n_boundary_halfedges() const { return n_boundary_; }
    bool has_boundary() const { return n_boundary_ != 0; }
    bool is_boundary(Halfedge h) const { return n_boundary_ != 0 && he_face_[h.idx] == kInvalidIndex; }
    bool is_boundary(Vertex v) const { return is_boundary(halfedge(v)); }
    bool is_boundary(Edge e) const { return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1)); }
    // Whether an edge of f is on a boundary (needs faces).
    bool beside_boundary(Face f) const {
        const Halfedge h0 = halfedge(f), h1 = next(h0), h2 = next(h1);
        return is_boundary(twin(h0)) || is_boundary(twin(h1)) || is_boundary(twin(h2));
    }
    // The boundary half-edge before h in its loop (the one ending at from(h)). O(valence).
    Halfedge prev_on_boundary(Halfedge h) const;
    // The number of half-edges in h's loop. O(length).
    std::uint32_t loop_length(Halfedge h) const;

    // ---- circulators ------------------------------------------------------------------------
    // Visit the one-ring of v counter-clockwise: f(Halfedge outgoing) / f(Vertex) / f(Face).
    template <class F>
    void for_each_outgoing(Vertex v, F&& f) const {
        const Halfedge start = halfedge(v);
        Halfedge h = start;
        do {
            f(h);
            h = ccw_rotated(h);
        } while (h != start);
    }
    // The same half-edges clockwise: one memory access per step instead of two, for loops that
    // do not care about the order (sums over the ring).
    template <class F>
    void for_each_outgoing_cw(Vertex v, F&& f) const {
        const Halfedge start = halfedge(v);
        Halfedge h = start;
        do {
            f(h);
            h = cw_rotated(h);
        } while (h != start);
    }
    template <class F>
    void for_each_neighbor(Vertex v, F&& f) const {
        for_each_outgoing(v, [&](Halfedge h) { f(to(h)); });
    }
    // The faces round v (a boundary gap has none and is skipped).
    template <class F>
    void for_each_face_around(Vertex v, F&& f) const {
        for_each_outgoing(v, [&](Halfedge h) {
            if (!is_boundary(h)) f(face(h));
        });
    }
    // The outgoing half-edges of v that have a face, counter-clockwise: v's corners, each the
    // triangle (v, to(h), to(next(h))).
    template <class F>
    void for_each_corner(Vertex v, F&& f) const {
        for_each_outgoing(v, [&](Halfedge h) {
            if (!is_boundary(h)) f(h);
        });
    }

    // ---- geometry ---------------------------------------------------------------------------
    const Vec3& position(Vertex v) const { return vpos_[v.idx]; }
    void set_position(Vertex v, const Vec3& p) { vpos_[v.idx] = p; }
    const std::vector<Vec3>& positions() const { return vpos_; }  // indexed by slot
    Vec3 face_normal(Face f) const;                               // unit (zero for a degenerate face)
    float face_area(Face f) const;
    Vec3 face_centroid(Face f) const;
    // The three corners of f, from halfedge(f) round (needs the face index).
    std::array<Vertex, 3> face_vertices(Face f) const {
        const Halfedge h = halfedge(f);
        return {from(h), to(h), to(next(h))};
    }
    // The centroid of h's triangle, with or without the face index: summed from its smallest
    // half-edge, so the same bits from any of the three (and the same as face_centroid(face(h))
    // after build_faces()).
    Vec3 triangle_centroid(Halfedge h) const;
    Vec3 vertex_normal(Vertex v) const;  // area-weighted mean of the incident face normals, unit

    // ---- topology operations ----------------------------------------------------------------
    // Vertex split. `to_c` and `to_d` are two different outgoing half-edges of the same vertex b
    // (towards neighbours c and d). The outgoing half-edges from `to_c` counter-clockwise up to
    // `to_d`, both included, move to a new vertex a at position p; the new faces (a, b, c) and
    // (b, a, d) close the gap. a gets valence k+1 (k = moved half-edges, 2 <= k <= valence(b)),
    // b ends with valence(b) - k + 3, c and d gain one. Returns a. Inverse: collapse(a -> b).
    // Throws InputError, the mesh unchanged, when the new edges would pass kMaxHalfedges.
    bool can_split(Halfedge to_c, Halfedge to_d) const;
    Vertex split(Halfedge to_c, Halfedge to_d, const Vec3& p);

    // Edge collapse of h = (a -> b): a is removed and its neighbours join b (b keeps its
    // position; the caller moves it if it wants). Allowed when the mesh has more than four
    // vertices, the link condition holds (a and b share exactly the two neighbours opposite h),
    // and no vertex would be left with valence below 3.
    bool can_collapse(Halfedge h) const;
    void collapse(Halfedge h);

    // Edge flip: the edge of h, between faces (a, b, c) and (b, a, d), becomes the edge c-d.
    // Allowed when c and d are not already adjacent and a and b keep valence >= 3.
    // The half-edge slot h becomes d -> c. unflip(flip(h)) restores every array bit for bit.
    bool can_flip(Halfedge h) const;
    FlipRecord flip(Halfedge h);
    void unflip(const FlipRecord& r);

    // Face removal: f's half-edges join the boundary. With no edge of f on a boundary, a new loop
    // of three opens (allowed when no vertex of f is on a boundary); with one, the loop widens
    // across it and that edge goes (allowed when the vertex opposite it is not on a boundary);
    // with two, f is an ear: its vertex between them, in no other face, goes with both edges
    // (returned; otherwise an invalid handle). Never with three (a lone triangle). So no bow-tie
    // vertex and no vertex without a face, and the mesh stays connected. Needs the face index.
    bool can_remove_face(Face f) const;
    Vertex remove_face(Face f);

    // Join two boundary loops with a tube of new faces (a handle when both lie on one component).
    // `a` and `b` are boundary half-edges of different loops, of lengths m and n; the tube starts
    // with the edge from(a) - to(b), runs along a's loop forwards and b's loop backwards, and at
    // each step takes the shorter of the two possible new edges (a greedy zip). Adds m + n faces
    // and m + n edges; both loops disappear. Allowed when a and b lie on different loops and no
    // new edge joins two vertices that are already adjacent. O(m n) for the predicate.
    bool can_join_loops(Halfedge a, Halfedge b) const;
    void join_loops(Halfedge a, Halfedge b);

    // Each operation behind its predicate: a refused operation returns false (an invalid vertex
    // for try_split) and leaves the mesh untouched.
    Vertex try_split(Halfedge to_c, Halfedge to_d, const Vec3& p) {
        return can_split(to_c, to_d) ? split(to_c, to_d, p) : Vertex();
    }
    bool try_collapse(Halfedge h) {
        if (!can_collapse(h)) return false;
        collapse(h);
        return true;
    }
    bool try_flip(Halfedge h, FlipRecord* record = nullptr) {
        if (!can_flip(h)) return false;
        const FlipRecord r = flip(h);
        if (record) *record = r;
        return true;
    }
    bool try_remove_face(Face f, Vertex* removed = nullptr) {
        if (!can_remove_face(f)) return false;
        const Vertex v = remove_face(f);
        if (removed) *removed = v;
        return true;
    }
    bool try_join_loops(Halfedge a, Halfedge b) {
        if (!can_join_loops(a, b)) return false;
        join_loops(a, b);
        return true;
    }

    // ---- export -----------------------------------------------------------------------------
    // Dense arrays of the alive elements. Vertex order follows the slot order, face order the
    // face slots (without the face index, the order of each triangle's smallest half-edge, which
    // build_faces() would give them); `vertex_map` (if given) receives, per slot, the dense index
    // or kInvalidIndex for a free slot.
    IndexedMesh to_indexed(std::vector<std::uint32_t>* vertex_map = nullptr) const;

    // Raw access for the validator and for bit-for-bit comparisons in tests.
    bool same_arrays(const Mesh& o) const;

    // Free-list heads (kInvalidIndex when empty); for the validator. Plain slot indices: the
    // dead mark is taken off.
    std::uint32_t free_vertex_head() const { return plain(vfree_); }
    std::uint32_t free_face_head() const { return plain(ffree_); }
    std::uint32_t free_edge_head() const { return plain(efree_); }
    // The next slot after a free one (its connectivity field holds it), or kInvalidIndex.
    std::uint32_t next_free_vertex(std::uint32_t v) const { return plain(vhe_[v]); }
    std::uint32_t next_free_face(std::uint32_t f) const { return plain(fhe_[f]); }
    std::uint32_t next_free_edge(std::uint32_t e) const { return plain(he_[2 * e].next); }

private:
    friend struct MeshTestAccess;  // defined by the test suite only, to damage meshes on purpose

    // Set in a free slot's connectivity field and in the free-list heads: slot | kFreeBit.
    static constexpr std::uint32_t kFreeBit = std::uint32_t(1) << 31;
    // A free-list link as a slot index (the list's end stays kInvalidIndex).
    static constexpr std::uint32_t plain(std::uint32_t link) {
        return link == kInvalidIndex ? kInvalidIndex : link & ~kFreeBit;
    }
    [[noreturn]] static void throw_too_many_halfedges(std::uint64_t halfedges, const char* what);
    // face(h) with the face index, an invalid handle without it (the operations then skip the
    // index's updates).
    Face face_if_any(Halfedge h) const { return faces_ ? Face(he_face_[h.idx]) : Face(); }
    // The centroid of h's triangle, summed from(h), to(h), to(next(h)) in that order.
    Vec3 centroid_from(Halfedge h) const;

    // New slots come from the free lists first. Their connectivity field is left marked (a
    // reused edge) or set to kInvalidIndex (which has the bit too): the caller links them.
    Vertex new_vertex(const Vec3& p);
    Face new_face();
    Edge new_edge();
    void delete_vertex(Vertex v);
    void delete_face(Face f);
    void delete_edge(Edge e);
    // Make the half-edges (h0, h1, h2) one face f, pointing to (v0, v1, v2).
    void link_face(Face f, Halfedge h0, Halfedge h1, Halfedge h2);
    // Put `by` where `old` is in old's face (same face, same neighbours in the cycle).
    void replace_in_face(Halfedge old, Halfedge by);
    // The zip join_loops() makes: the vertices of a's loop forwards from from(a), of b's loop
    // backwards from to(b), the boundary half-edges along them, and per step whether it
    // advances along a's loop.
    struct JoinPlan {
        std::vector<std::uint32_t> p, q, p_he, q_he;
        std::vector<char> along_p;
    };
    JoinPlan plan_join(Halfedge a, Halfedge b) const;

    std::vector<Vec3> vpos_;
    std::vector<std::uint32_t> vhe_;  // outgoing half-edge, or next free vertex | kFreeBit
    // A half-edge's target and next side by side: the one-ring walks read both (one cache line).
    struct HalfedgeLinks {
        std::uint32_t to;
        std::uint32_t next;  // for edge e's first half-edge: next free edge | kFreeBit if e is dead
        bool operator==(const HalfedgeLinks& o) const { return to == o.to && next == o.next; }
    };
    std::vector<HalfedgeLinks> he_;
    std::vector<std::uint32_t> he_face_;
    std::vector<std::uint32_t> fhe_;  // a half-edge of the face, or next free face | kFreeBit
    // Free-list heads, marked like the links (slot | kFreeBit, or kInvalidIndex when empty).
    std::uint32_t vfree_ = kInvalidIndex, ffree_ = kInvalidIndex, efree_ = kInvalidIndex;
    std::uint32_t n_vertices_ = 0, n_faces_ = 0, n_edges_ = 0;
    std::uint32_t n_boundary_ = 0;  // alive half-edges without a face
    bool faces_ = true;             // he_face_, fhe_ and ffree_ are kept
};

}  // namespace nmesh
