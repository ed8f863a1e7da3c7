// nmesh/finish/cloud_normals.h — one orientation for the normals of a cloud seen from one side.
//
// A partial view (one range image) is seen from one side, so its points' normals can be turned
// to face that side, and a mesh learnt round it told apart: the faces that face the same way are
// the view's sheet, the others the back of the closed mesh (nmesh/finish/open_surface.h).
// Choice: the propagation of Hoppe et al. (1992, "Surface reconstruction from unorganized
// points"): over the graph of each point's kOrientNeighbours nearest neighbours, the orientation
// spreads from one point, always next across the pair whose normals are most nearly parallel
// (Prim's order, weight |n_i . n_j|), so that it crosses a sharp bend last, where a wrong turn
// would do the least harm. The graph of a single view falls apart where one part hid another
// from the scanner; each connected part is oriented on its own, then turned as a whole to agree
// with the largest part's mean normal (every part faces the scanner).
#pragma once

#include <cstdint>
#include <vector>

#include "nmesh/vec3.h"

namespace nmesh {

inline constexpr int kOrientNeighbours = 8;

struct Orientation {
    Vec3 direction;                  // the largest part's mean normal, normalised (zero if none)
    std::vector<std::uint32_t> part;  // per point: its connected part, kNoPart for one left out
};
inline constexpr std::uint32_t kNoPart = 0xffffffffu;

// `normals`: one per point, of either sign (zero for a point without one: left out); turned in
// place. `spacing`: the cloud's typical point spacing. O(n k log(n k)).
Orientation orient_normals(const std::vector<Vec3>& points, std::vector<Vec3>& normals, float spacing);

}  // namespace nmesh
