// nmesh/geometry/triangle_intersection.h — exact intersection tests between triangles, and the
// self-intersections of a triangle mesh.
//
// Every decision is made from exact orientation signs (nmesh/geometry/exact_predicates.h) on the
// float positions, so the answers are those of the real geometry of the given coordinates, with
// no tolerance: touching counts as meeting. Positions must be finite.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/vec3.h"

namespace nmesh {

// Whether the triangle abc has zero area exactly: its corners are collinear or coincide (all
// three of its projections on the coordinate planes are degenerate).
bool triangle_degenerate(const Vec3& a, const Vec3& b, const Vec3& c);

// Whether the closed segment pq meets the closed triangle abc, which must not be degenerate.
// pq may lie in the plane of abc, or be a single point (p == q).
bool segment_intersects_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

// Whether the closed triangles abc and def, neither degenerate, have a point in common: touching
// at a point or along a segment counts, and coplanar triangles are handled.
bool triangles_intersect_exact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e,
                               const Vec3& f);

// Whether two faces of a mesh, given by vertex indices into `positions`, intersect as a defect of
// the mesh, judged by the indices they share:
//   - none: any common point, touching included (distinct faces of a mesh that touch are a
//     defect even if they do not cross: the surface is not embedded there);
//   - one vertex: a common point other than that vertex;
//   - an edge: a common point off that edge; that is, the two faces lie in one plane folded onto
//     each other (their opposite vertices on the same side of the edge);
//   - all three (the same face twice): always.
// Faces that are degenerate (a repeated index, or zero area) are not judged by this rule: the
// result is false.
bool faces_intersect(const Vec3* positions, std::array<std::uint32_t, 3> t, std::array<std::uint32_t, 3> u);

// The pairs (s, t), s < t, of non-degenerate faces of `mesh` that intersect by faces_intersect,
// sorted. At most max_pairs are returned: the first max_pairs of the full sorted list. Faces with
// a non-finite corner are skipped like degenerate ones. Throws InputError if a triangle refers
// to a missing position.
// A uniform grid over the faces' bounding boxes finds the candidate pairs (boxes that overlap or
// touch), each tested exactly once: about O(F) for a mesh whose faces are of similar size.
std::vector<std::pair<std::uint32_t, std::uint32_t>> self_intersecting_pairs(const IndexedMesh& mesh,
                                                                             std::size_t max_pairs = SIZE_MAX);

// The number of pairs self_intersecting_pairs would return without a limit. The faces' searches
// run on `threads` threads (0: the machine's cores); the count is the same for any number.
std::size_t count_self_intersections(const IndexedMesh& mesh, std::uint32_t threads = 1);

}  // namespace nmesh
