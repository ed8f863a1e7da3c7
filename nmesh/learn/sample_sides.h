// nmesh/learn/sample_sides.h — which side of the surface each point of a cloud was taken from.
//
// A closed mesh wraps a part thinner than its edges (a sheet-metal wall, an ear) in two sheets a
// fraction of an edge apart. The winner of a sample is the nearest vertex, which there is as
// likely on the far sheet as on the near one: samples from both faces pull both sheets, and the
// sheets cross each other (docs/algorithm.md, "Thin walls"). The solid the cloud walls round
// (solid_start.h) says which face a point lies on: its outer surface runs at the offset outside
// every face, and a point's nearest point of that surface lies off its own face (on a wall of
// thickness t, the surface beyond the point's face is t nearer than the one beyond the other
// face). The direction to it is the outward normal of the point's face, smoothed over the offset;
// NeuralMesh::set_sample_sides then lets a sample pull only a vertex whose fan faces that way.
//
// Choice: the nearest vertex of the outer surface (marching tetrahedra on cells of kVoxel d,
// vertices about d apart) stands for its nearest point: a point's direction to it is off by the
// surface's own roughness, and the search is a nearest-point query in a PointGrid (0.02-0.1 s for
// the corpus's 30,000-point clouds, against 0.15-0.35 s through a hierarchy of the triangles;
// the rotor ring's thin wall learnt as well either way: docs/algorithm.md).
#pragma once

#include <cstdint>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/point_span.h"
#include "nmesh/spatial/point_transform.h"
#include "nmesh/vec3.h"

namespace nmesh {

// Per point of `points` (through `transform`, the space `surface` lies in): the unit direction
// from the point to its nearest vertex of `surface`, the outer surface of the solid the points
// wall round; 0 for a point farther from it than `reach` (the offset the surface was built at,
// and a cell): a point in a tunnel the solid fills (a handle narrower than the offset) has no
// face that surface runs beyond, and its sample is learnt by any winner. Empty when the surface
// is. O(V + P) expected. The points are taken on `threads` threads (0: the machine's cores).
std::vector<Vec3> sample_sides(PointSpan points, const PointTransform& transform, const IndexedMesh& surface,
                               float reach, std::uint32_t threads = 1);

}  // namespace nmesh
