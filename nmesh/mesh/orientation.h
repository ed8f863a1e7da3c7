// nmesh/mesh/orientation.h — which way a closed mesh faces: its signed volume, and the faces
// that point into the solid it bounds instead of out of it. The learning's checkpoints ask it
// (nmesh/learn/twist_check.h), and so do the output check and the metrics above them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/indexed_mesh.h"

namespace nmesh {

// The signed volume enclosed by the triangles (positive when a closed mesh is oriented outward,
// counter-clockwise seen from outside), in double.
double signed_volume(const IndexedMesh& mesh);

// The number of non-degenerate faces that point inward: the point just off the face's centroid
// along its normal (a thousandth of its longest edge away) lies inside the surface, its winding
// number nonzero. The winding number is counted along a ray in +x, each crossed triangle adding
// the sign of its normal's x component, through `bvh` (a hierarchy over `mesh`): O(log F) per
// face. Meaningful for closed meshes; a face on a fold or in a tangle may count either way. The
// faces are tested on `threads` threads (0: the machine's cores), with the same answer for any number.
std::size_t inward_faces(const IndexedMesh& mesh, const TriangleBvh& bvh, std::uint32_t threads = 1);
// The same test face by face: 1 for a face that points inward, 0 otherwise.
std::vector<std::uint8_t> inward_face_flags(const IndexedMesh& mesh, const TriangleBvh& bvh, std::uint32_t threads = 1);

// The most faces in one edge-connected patch of the `flagged` ones (one flag per triangle): for
// the inward faces, a fold turns a few triangles over, a twist (part of the surface inside out)
// a whole region. Edge-connected as split_pieces (nmesh/mesh/mesh_pieces.h) has it. O(F log F).
std::size_t largest_patch(const IndexedMesh& mesh, const std::vector<std::uint8_t>& flagged);

// Reverses every triangle when the signed volume is negative, so that a closed mesh faces
// outward; returns whether it did.
bool orient_outward(IndexedMesh& mesh);

}  // namespace nmesh
