// nmesh/finish/view_sheet.h — Parameters::topology open on a partial view: the one sheet the view
// sees, from the closed mesh learnt round it.
//
// A closed mesh learnt from an open sheet (one range image) wraps the sheet in two layers of
// opposite orientation lying on the same points. They do not stay apart: where one layer wins the
// samples its vertices multiply and the other's faces grow (bunny_scan090 at 30,000 vertices:
// three quarters of the faces face the view), and the two cross and fold into each other at the
// scale of an edge (17,000 crossing pairs). So no set of the learnt faces is the sheet.
// The vertices are the learning's, and lie on the surface; the connectivity is made again:
//  1. every vertex of the learnt mesh (both layers: together they sample the surface at about the
//     density asked for, so the sheet keeps about the vertex count asked for);
//  2. projected onto the plane across the view direction (the mean normal of the cloud's largest
//     part, oriented, nmesh/finish/cloud_normals.h) and triangulated there (Delaunay,
//     nmesh/geometry/delaunay_2d.h). A range image sees each point of its surface from one side,
//     so where its rays are about parallel to that direction the surface projects one to one and
//     the triangles, counter-clockwise seen from the scanner, face it and cannot fold or cross;
//  3. the triangles over no data go: those with an edge longer than kSheetMaxEdges typical edges
//     where the scan is not sparse (below), or the centroid or an edge's midpoint farther from
//     every point than kOpenEdges typical edges and kOpenSpacings local spacings (the gaps where
//     one part hid another from the scanner, the hull across the sheet's concave outline). What is
//     left is cut as cut_faces cuts (a manifold with boundary, no piece under kOpenMinFaces). A
//     learnt vertex that far from the points (on the closed mesh's tube round a sheet's edge) is
//     never triangulated;
//  4. front layer first, up to kSheetPasses passes: the scanner's rays are not all parallel to the
//     view's direction, so a part it saw past the edge of a nearer one can lie behind it across
//     the view (bunny_scan090's ear tips: vertices 5 cm apart in depth within 2 mm of each other
//     across). A pass leaves for the next the vertices another remaining vertex hides (nearer the
//     scanner, close across the view, no data between the two), and the next pass takes the
//     vertices no kept triangle uses;
//  5. what is still unused, in groups joined by the learnt mesh's edges, each triangulated across
//     its own mean normal (a wall seen at a grazing angle is squeezed across the view), without
//     the faces that cross an earlier sheet.
// Choice: a new triangulation rather than a choice among the learnt faces. Keeping the faces that
// face the view (a face's normal against its nearest point's oriented normal) left the bunny's
// single view shredded: 13% of its area gone once its crossing faces were cut (docs/algorithm.md,
// Open surfaces).
#pragma once

#include "nmesh/finish/open_surface.h"

namespace nmesh {

// A triangle with an edge longer than kSheetMaxEdges typical edges spans a gap (the hull's
// triangles across the outline's bays), unless the scan is sparse there: such an edge stays when
// it is shorter than kSheetMaxSpacings local spacings (at the point nearest the centroid). A wall
// seen at a grazing angle is sampled a few typical edges apart, and the learning puts few vertices
// on it: without this, no triangle there was short enough and the sheet lost it (bunny_scan090 at
// 30,000 vertices: the scan's triangulation up to 4.9% of the diagonal from the sheet). Choice,
// measured over seeds 1-12 (docs/algorithm.md): 6 spacings; 8 kept more of that wall but let
// triangles stray from the scan's surface. An edge longer than kSheetSparseEdges typical edges
// spans a gap without asking the cloud (asking is slow that far from the points).
inline constexpr float kSheetMaxEdges = 8.0f;
inline constexpr float kSheetMaxSpacings = 6.0f;
inline constexpr float kSheetSparseEdges = 32.0f;
inline constexpr int kSheetPasses = 3;
// A vertex waits for a later pass when another vertex within kPeelRadiusEdges typical edges of it
// across the view lies more than kPeelDepthEdges typical edges nearer the scanner, with no data
// between the two. One edge: inside a layer's footprint a vertex of it is always that near (at
// most 0.58 edges in an equilateral mesh); 2 edges also held back a ring round a nearer part's
// outline, and small sheets lost most of their area to the rings (tests/test_open_surface.cpp's
// squares at 1,000 vertices: the near one down to 0.04 of its 0.36 in 1 of 20 runs).
inline constexpr float kPeelRadiusEdges = 1.0f;
inline constexpr float kPeelDepthEdges = 3.0f;

// `mesh`: the learnt mesh with its face index; `view`: a partial view (view.partial; otherwise
// the mesh is returned as it is). The sheet, as triangles, in one or more pieces; sets
// report.removed_layer to the learnt faces it has fewer. O(V log V + F) per pass.
IndexedMesh view_sheet(const Mesh& mesh, const PointGrid& cloud, const CloudView& view, OpenReport& report);

// The sheet without the faces turned against the view: a face whose normal points away from the
// view's direction and from the oriented normal of the point nearest its centroid. (A range image
// sees each of its surfaces from the scanner's side; either test alone would take faces on a wall
// seen at a grazing angle, or a small part whose point normals are oriented the other way.) The
// finishing stage's relaxation, which runs without the repair on a view's sheet, can fold a sliver
// at a sheet's edge over (seen once in 40 runs of the overlapping squares of
// tests/test_open_surface.cpp). Cut as cut_faces cuts; adds the faces removed to
// report.removed_layer. O(F) nearest-point queries.
IndexedMesh cut_turned(const IndexedMesh& sheet, const PointGrid& cloud, const CloudView& view, OpenReport& report);

}  // namespace nmesh
