// nmesh/mesh_check.h — the whole-mesh validator: the test suite's oracle.
#pragma once

#include <string>

#include "nmesh/mesh/mesh.h"

namespace nmesh {

struct ManifoldCheck {
    bool ok = true;
    std::string error;  // the first violation found, precisely; empty when ok
    explicit operator bool() const { return ok; }
};

// Checks that `mesh` is a valid closed, connected, genus-0 triangle 2-manifold in half-edge form:
//   - element counts match the alive slots, and each free list visits exactly the free slots;
//   - every alive half-edge has an alive twin, next, face and target; next() cycles have length 3
//     and stay in one face; no half-edge is a loop; orientation is consistent (a half-edge runs
//     opposite to its twin);
//   - every alive face's half-edge belongs to it; no alive element refers to a free slot;
//   - every alive vertex's stored half-edge leaves it; its outgoing half-edges form one single
//     rotation cycle; its valence is at least 3 and its neighbours are distinct (no duplicate
//     edges);
//   - the mesh is connected and V - E + F = 2.
// A mesh without its face index (Mesh::drop_faces) is checked the same way except for what
// names faces: its triangles are its next() cycles.
// O(V + E + F) time and memory.
ManifoldCheck check_manifold(const Mesh& mesh);

// Aborts with the check's message when the mesh is invalid; `after` names the operation just done.
// Used after every topology operation when nmesh is built with NMESH_CHECK_INVARIANTS.
void assert_manifold(const Mesh& mesh, const char* after);

}  // namespace nmesh
