// nmesh/finish/exchange.h — vertices moved to where the shape needs them, at a fixed count: edge
// collapses where the surface is flat paired with edge splits where it bends away from the mesh.
#pragma once

#include <cstdint>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh {

// Why: the learning places the vertices where the samples are dense (the paper's signal counter):
// a flat side gets as many as an ear. At a fixed vertex count the surface is nearer the scan when
// the flat parts give up vertices to the bent ones, which is what a quadric decimation of a dense
// mesh does. Here the exchange is made on the learnt mesh, a collapse for every split:
//   - a collapse's cost is the quadric error of Garland and Heckbert ("Surface simplification using
//     quadric error metrics", SIGGRAPH 1997) of moving a vertex onto its neighbour: the sum, over
//     the vertex's triangles, of the area times the squared distance of the neighbour to the
//     triangle's plane (area x length^2);
//   - a split's gain is the area of the edge's two triangles times the squared distance of the
//     edge's midpoint from the scan (the plane of its nearest point, CloudSurface::pull; the
//     same units): what a new vertex there, moved onto the scan, takes away.
// One pass pairs the cheapest collapses with the largest gains while a gain is more than
// kExchangeMargin times its collapse's cost, at most kExchangeShare of the vertices, no two
// operations touching one ring; a collapse that would turn a triangle by more than
// kExchangeTurnDeg or leave a vertex with more than kExchangeMaxValence neighbours is skipped.
// The new vertex goes onto the scan. Boundary vertices take part in nothing. The passes are
// separated by angle-improving flips (flip_to_delaunay). The repair, the cover and the fit that
// follow in the finishing stage see the result as they would the learnt mesh.

inline constexpr float kExchangeMargin = 4.0f;
inline constexpr float kExchangeShare = 0.02f;
inline constexpr float kExchangeTurnDeg = 30.0f;
inline constexpr std::uint32_t kExchangeMaxValence = 9;

struct ExchangeResult {
    std::uint32_t passes = 0;
    std::uint64_t exchanged = 0;  // collapse-split pairs made
};

// Runs up to `passes` passes (stops early when a pass finds no pair) on `mesh` (with its face
// index). The vertex count is unchanged.
ExchangeResult exchange_vertices(Mesh& mesh, const CloudSurface& cloud, int passes, float flip_max_dihedral_deg);

}  // namespace nmesh
