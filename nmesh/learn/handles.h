// nmesh/learn/handles.h — topology learning (Parameters::topology closed): handles made where
// the learnt surface spans a through-hole of the data.
//
// A genus-0 mesh learning a shape with a through-hole (a bore, a ring) can only cap it: a
// membrane across each end of the hole, or two sheets pressed together inside it. Either way
// the hole shows as two patches of faces far from every cloud point, facing away from each other
// with the inside of the mesh between them and no data on the way from one to the other. This
// rule finds such pairs, cuts each patch out (Mesh::remove_face) and joins the two rims with a
// tube (Mesh::join_loops): a handle, whose wall the learning then pulls onto the hole's wall.
//
// Choices (docs/algorithm.md, "Topology"):
//   - a face is unsupported as face_support.h says (farther from the cloud than a mean longest
//     edge and two point spacings, about), so a coarse mesh or a sparse scan is not taken for a
//     hole;
//   - a patch counts when it has at least kMinFaces faces, is cap-like (its vector area at least
//     kMinFlatness of its area: a fold or a web between two legs, which faces both ways, is not
//     a cap) and spans a disc of radius at least kMinHoleRadius of the mesh's bounding-box
//     diagonal (the gap between two legs that nearly touch makes small patches; a bore that
//     small is not learnt);
//   - two patches pair when each lies behind the other (their mean normals point away from each
//     other, the segment between their centres passes through the inside), the segment meets
//     no other face, no cloud point comes near its inner part, and the cloud walls it round
//     (points across its middle in every one of 8 directions, within 4 patch radii): a hole
//     through the data, not the gap between two legs;
//   - each patch is cut out from its face nearest the centre, one ring of faces away from the
//     other patch (so that no edge joins the two rims already), and the rims are zipped from a
//     vertex and the other rim's nearest one, with up to 8 other starts when an edge would repeat;
//   - all or nothing per pair: if the cut or the join is refused, the mesh is left as it was.
#pragma once

#include <cstdint>
#include <vector>

#include "nmesh/learn/face_support.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/spatial/point_grid.h"

namespace nmesh {

struct HandleSearch {
    std::uint32_t handles = 0;                    // tubes made
    std::uint32_t faces_removed = 0;              // faces cut out of the membranes
    std::uint32_t patches = 0;                    // cap-like unsupported patches found
    std::vector<std::uint32_t> removed_vertices;  // vertex slots deleted with the cut
    std::vector<std::uint32_t> touched_vertices;  // alive vertices whose one-ring changed
};

inline constexpr std::uint32_t kMinFaces = 6;
inline constexpr float kMinFlatness = 0.5f;
inline constexpr float kMinHoleRadius = 0.03f;

// `mesh`: closed, with its face index; `cloud`: the nearest-point index over the same (normalised)
// points the mesh learns; `support`: face_support(mesh, cloud), as the mesh is. O(F log F + pairs x F).
HandleSearch open_handles(Mesh& mesh, const PointGrid& cloud, const FaceSupport& support);

}  // namespace nmesh
