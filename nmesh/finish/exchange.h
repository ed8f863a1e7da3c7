// nmesh/finish/exchange.h — vertices moved to where the shape needs them, at a fixed count: edge
// collapses where the surface is flat paired with edge splits where it bends away from the mesh.
#pragma once

#include <cstdint>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh {

// Why: the learning places the vertices where the samples are dense (the paper's signal counter):
// a flat side gets as many as an ear or a crease. At a fixed vertex count the surface is nearer
// the scan when the flat parts give up vertices to the bent ones, which is what a quadric
// decimation of a dense mesh does. Here the exchange is made on the finished mesh's vertices, a
// collapse for every split:
//   - a collapse's cost is the quadric error of Garland and Heckbert ("Surface simplification using
//     quadric error metrics", SIGGRAPH 1997) of moving a vertex onto its neighbour: the sum, over
//     the vertex's triangles, of the area times the squared distance of the neighbour to the
//     triangle's plane (area x length^2), the cheaper direction of the edge;
//   - a split's gain is the area of the edge's two triangles times their squared bias (the same
//     units): a triangle's bias is the mean signed distance of the points nearest its centroid from
//     its plane, which a chord under a bend has and the noise of a few points averages out of; the
//     share of the squared mean that the noise alone gives (the scatter round the biases, pooled
//     over the triangles, over each triangle's count of points) is taken off. Each triangle counts
//     with weight (edge / its longest edge)^2: splitting its longest edge is what halves it.
//     The new vertex goes to the edge's midpoint moved along the normal by the bias.
// One pass pairs the cheapest collapses with the largest gains while a gain is more than
// kExchangeMargin times its collapse's cost, at most kExchangeShare of the vertices, no two
// operations touching one ring; a collapse that would turn a triangle by more than
// kExchangeTurnDeg or leave a vertex with more than kExchangeMaxValence neighbours is skipped.
// Boundary vertices take part in nothing. The passes are separated by angle-improving flips
// (flip_to_delaunay). The caller fits the mesh to the points first (finish_mesh): a learnt
// vertex sits inside a bend, and a triangle's bias would then be its vertices' offset rather than
// its chord. The constants were chosen on the equal-budget rows (docs/algorithm.md, the finishing
// stage: margin 2, 4 and 8; 2%, 3% and 4% a pass; 5, 10 and 20 passes).

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
