// nmesh/geometry/delaunay_2d.h — the Delaunay triangulation of points in the plane.
//
// Used for the sheet a single view sees (nmesh/finish/view_sheet.h): a range image sees every
// point of its surface from one side, so the surface projects one to one onto the plane across
// the view, and a triangulation of the projected points is a sheet that cannot fold or cross
// itself.
// Incremental: the points in the order of a Hilbert curve, each found by a walk from the previous
// one (exact orient2d, nmesh/geometry/exact_predicates.h) and inserted by splitting its triangle
// (or the two triangles of the edge it lies on), then Lawson's edge flips restore the empty-circle
// property. The in-circle test is plain double arithmetic: a rounding error can only leave an
// edge unflipped that should be flipped, or the reverse, and a flip is taken only where the
// exact orientation tests find the quadrilateral convex, so the result is always a valid
// triangulation (each flip also stops a cycle: an edge is flipped at most kMaxFlipsPerPoint times
// per insertion). Three far points enclose the input and are dropped at the end, with their
// triangles: the result covers the convex hull except, possibly, slivers along it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "nmesh/geometry/exact_predicates.h"

namespace nmesh {

inline constexpr int kMaxFlipsPerPoint = 1000;

// The triangles, as indices into `points`, each counter-clockwise. A point equal to an earlier one
// is left out (no triangle uses it). Non-finite points are left out too. O(n log n) expected.
std::vector<std::array<std::uint32_t, 3>> delaunay_2d(const std::vector<Point2d>& points);

// The in-circle determinant's sign in double arithmetic: > 0 when d lies inside the circle
// through a, b, c (counter-clockwise), < 0 outside.
double incircle_approx(const Point2d& a, const Point2d& b, const Point2d& c, const Point2d& d);

}  // namespace nmesh
