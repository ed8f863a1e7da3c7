// nmesh/mesh_check.h — the whole-mesh validator: the test suite's oracle.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>

#include "nmesh/mesh/mesh.h"

namespace nmesh {

struct ManifoldCheck {
    bool ok = true;
    std::string error;  // the first violation found, precisely; empty when ok
    // The topology, when ok: V - E + F, the boundary loops and the genus (2 - chi - b) / 2 of the
    // one component.
    long long euler = 0;
    std::uint32_t boundary_loops = 0;
    int genus = -1;
    // ok, closed and of genus 0: what split, collapse and flip keep from a tetrahedron.
    bool sphere() const { return ok && boundary_loops == 0 && genus == 0; }
    explicit operator bool() const { return ok; }
};

// Checks that `mesh` is a valid connected triangle 2-manifold, closed or with boundaries, of any
// genus, in half-edge form:
//   - element counts match the alive slots, and each free list visits exactly the free slots;
//   - every alive half-edge has an alive twin, next and target; a half-edge with a face is in a
//     next() cycle of length 3 within that face; one without (only with the face index) is a
//     boundary half-edge: its twin has a face, its next() is a boundary half-edge leaving its
//     target, and its loop has at least 3 half-edges; next() is a permutation; no half-edge is
//     a loop; orientation is consistent (a half-edge runs opposite to its twin);
//   - every alive face's half-edge belongs to it; no alive element refers to a free slot;
//     2E = 3F + (boundary half-edges);
//   - every alive vertex's stored half-edge leaves it; its outgoing half-edges form one single
//     rotation cycle (clockwise, through the gap); a boundary vertex has exactly one outgoing
//     boundary half-edge (no bow-tie) and stores it; the valence is at least 3 (2 on a
//     boundary) and the neighbours are distinct (no duplicate edges);
//   - the mesh is connected and not empty, and V - E + F + (boundary loops) is even and at most 2.
// A mesh without its face index (Mesh::drop_faces) is checked the same way except for what
// names faces: its triangles are its next() cycles.
// O(V + E + F) time and memory.
ManifoldCheck check_manifold(const Mesh& mesh);

// Checks what a local operation can have broken: the one-ring of each of `centres` and of each of
// their neighbours. Around each such vertex: it is alive and its stored half-edge leaves it; the
// rotation from that half-edge comes back to it, every half-edge on the way alive, leaving the
// vertex, paired with its twin, and (with a face) in a next() cycle of 3 within one alive face
// whose stored half-edge is in the cycle, oriented against its twin; no neighbour twice; at most
// one boundary gap, which the stored half-edge opens; valence at least 3 (2 on a boundary). It
// sees neither the free lists, the counts, the connectivity nor the genus: check_manifold does.
// O(sum over the centres of their neighbours' valences).
ManifoldCheck check_around(const Mesh& mesh, std::initializer_list<Vertex> centres);

// Aborts with the check's message when the mesh is invalid; `after` names the operation just done.
void assert_manifold(const Mesh& mesh, const char* after);

// What nmesh built with NMESH_CHECK_INVARIANTS runs after every local operation (split,
// collapse, flip, unflip): check_around(centres), and check_manifold whenever the operations
// since the last whole check have earned it. Each operation earns 256 slots of checking, and
// the whole check costs the mesh's slots (half-edges, vertices and faces, free ones included,
// about 9 per vertex): a mesh of up to about 28 vertices is checked whole after every operation,
// a larger one every few, so that a run to n vertices costs O(n) checking rather than O(n^2).
// Aborts with the message on a violation.
void assert_manifold_after(const Mesh& mesh, const char* after, std::initializer_list<Vertex> centres);

}  // namespace nmesh
