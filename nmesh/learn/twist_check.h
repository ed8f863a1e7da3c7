// nmesh/learn/twist_check.h — how far a learning mesh has turned inside out: the largest region
// of faces pointing inward, for the learning's checkpoints (reconstruct(), Topology closed and
// open).
#pragma once

#include <cstddef>

#include "nmesh/mesh/mesh.h"

namespace nmesh {

// The number of faces in the largest edge-connected region of faces that point inward (the
// output check's exact winding-number test, inward_face_flags in nmesh/mesh/orientation.h), 0
// when none does. A closed mesh only. A twist, a part of the surface pulled through itself, is such a
// region, and grows with the mesh; the learning's small folds are scattered faces. O(F log F).
std::size_t largest_inward_region(const Mesh& mesh);

}  // namespace nmesh
