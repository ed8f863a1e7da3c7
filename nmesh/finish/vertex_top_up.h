// nmesh/finish/vertex_top_up.h — the vertex count an open result lost, given back.
//
// The open steps (open_surface.h) take away the faces over the scan's holes and beyond a view's
// edge, and the vertices inside them go too: the result would have fewer vertices than asked. The
// count is the library's first promise, so the missing vertices come back as midpoint splits of
// the longest edges: each adds one vertex and two triangles that cover exactly the two it
// replaces, so the surface, its boundary and its validity stay as they were (no new crossing,
// fold or distance), and the longest edges are the ones a finer mesh would have split first.
#pragma once

#include <cstdint>

#include "nmesh/indexed_mesh.h"

namespace nmesh {

// `mesh` (one or more pieces, each a manifold with or without boundary) with its longest edges
// split at their midpoints, longest first, until it uses `target` vertices or no listed edge is
// left to split (an edge with both ends on a boundary is not split: Mesh::can_split). `added`
// receives the vertices added. `mesh` itself when it uses `target` vertices already; otherwise
// the vertices no triangle uses are dropped. O(E log E).
IndexedMesh top_up_vertices(const IndexedMesh& mesh, std::uint32_t target, std::uint32_t& added);

}  // namespace nmesh
