// nmesh/mesh/mesh_pieces.h — a triangle list of several pieces, one piece at a time.
//
// The half-edge mesh (nmesh/mesh/mesh.h) holds one connected surface. Once the open mode cuts a
// mesh (nmesh/finish/open_surface.h), the result may fall into pieces: the parts of a single view
// that one hid from another. What follows the cut (the finishing stage, the later cuts) runs on
// each piece as a half-edge mesh of its own.
#pragma once

#include <cstdint>
#include <vector>

#include "nmesh/indexed_mesh.h"

namespace nmesh {

struct MeshPiece {
    IndexedMesh mesh;                     // the piece, with only the vertices it uses
    std::vector<std::uint32_t> triangle;  // per triangle of the piece: its index in the whole
};

// The edge-connected pieces of `mesh` (two triangles are connected when they share an edge, in
// either direction), in the order of their first triangles; a vertex that two pieces share (a
// bow-tie) is copied into each. O(F log F).
std::vector<MeshPiece> split_pieces(const IndexedMesh& mesh);

// The pieces as one triangle list, in order.
IndexedMesh join_pieces(const std::vector<IndexedMesh>& pieces);

}  // namespace nmesh
