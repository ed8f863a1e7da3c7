// nmesh/learn/solid_start.h — topology closed and open: the solid a cloud walls round, and its
// outer surface as the learning's start.
//
// A mesh grown from a tetrahedron is a sphere, and the handle search (handles.h) turns it into a
// surface of another genus only by local surgery, which a shape like a knotted tube defeats (a
// seam where the growth met itself round the tube, a web where two strands cross:
// docs/algorithm.md, "The solid's surface"). The cloud itself says what the genus is when it
// walls an inside round: every cell of a voxel grid within an offset of the points is the
// shell; the cells reached from the grid's border without crossing it are the outside; the rest
// is the solid. Its outer surface (marching tetrahedra on the grid) has the genus of the object
// when the offset closes the gaps between samples and not those between parts. Its shape is the
// object's too: a start with the horse's four legs already there, where the growth from a
// tetrahedron has to find each thin part and is led astray by some seeds (a leg grown inside
// the body, a mesh that is half inside out before the fold guard undoes it).
//
// Choices:
//   - lengths are in units of d, the median distance from a point to its nearest other point
//     (measured on up to 4,096 points): the cells are kVoxel d across, and the offsets tried
//     are kOffsets d, smallest first; the shell at an offset r is the cells within r of a point
//     along the surface and within r / s across it (the point's splat, cloud_splats.h: two
//     parts of the object closer than 2r stay apart while farther than 2r / s);
//   - an offset leaks when the solid is no more than its shell (its inside, the cells of the
//     solid outside the shell, fewer than kMinInside of the shell's): the outside came in through
//     a hole of the scan (the bunny's base) or between samples;
//   - the genus is read where it persists: at each offset the grids shifted by kGridShifts agree
//     when most of them wall a solid of one component round and count the same genus; the
//     reading is the first genus agreed at two offsets in a row, at the smaller of the two. The
//     gaps between random samples close over a narrow range of offsets, and while they close the
//     genus jumps; a tunnel between two cells' corners (the grid's own) comes and goes as the
//     grid moves; a handle of the object holds while the offset is smaller than the hole. When
//     no genus persists, the solid is not read: where it walls round within kMaxShapeOffset in
//     one component, its genus-0 core (solid_core.h) is the start, the handles left to the
//     learning's search; otherwise the learning starts from the tetrahedron;
//   - a handle whose cut in the solid's genus-0 core crosses no point's splat was made by the
//     offset between two parts: the genus is read, and the surfaces built, without it
//     (solid_core.h: without_false_handles);
//   - the start is the outer surface simplified to start_vertices(target) vertices (simplify);
//   - the grid has at most kMaxVoxels cells (larger voxels for a cloud that would need more):
//     one byte each for the distances, the states and the components' flood, 50 MB at most
//     per grid (a grid is made when a reading first needs it: a genus-0 cloud reads one).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/learn/simplify.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/point_span.h"
#include "nmesh/spatial/point_transform.h"

namespace nmesh {

// Random samples leave spots up to about 4 d from every point (a smaller offset leaks); the
// knot's strands cross 13.6 d apart (a larger offset than 4 d closes its crossings); the rocker
// arm, sampled unevenly, walls round at 6 d and the bunny over its base holes at 8 d. The steps
// are those at which squared cell distances (sums of three squares) change at cells kVoxel d
// across: 1.5, 1.75, 2, 2.25, 2.5, 3, 3.5, 4, 5 and 6 cells. An offset is measured along the
// surface; across it the shell reaches offset / s (cloud_splats.h).
inline constexpr float kOffsets[] = {3.0f, 3.5f, 4.0f, 4.5f, 5.0f, 6.0f, 7.0f, 8.0f, 10.0f, 12.0f};
// A grid's distances are computed up to this many d first, and farther only when the reading
// needs an offset beyond (solid_surface: the same reading, the splats' boxes an eighth of the
// largest offset's).
inline constexpr float kFirstReach = 6.0f;
// The grids that vote on a genus: shifted by these fractions of a cell.
inline constexpr Vec3 kGridShifts[] = {{0.0f, 0.0f, 0.0f}, {0.5f, 0.5f, 0.5f}, {0.25f, 0.5f, 0.75f}};
// Cells 2 d across: a quarter of the cells of d, and the knot's crossings still 3 cells open at 4 d.
inline constexpr float kVoxel = 2.0f;
// A leak leaves at most 0.3% of the shell inside on the shared clouds; a thin part walled round
// keeps 4.4% (the rocker arm at 6 d), a thick one 49-77%.
inline constexpr double kMinInside = 0.02;
// A solid of genus 0 is a start only when walled round at most this offset, where it closes no
// more than the gaps between random samples: the horse at 4 d. At 8 d (the bunny, over its base
// holes) it is a plumper shape than the object: the bunny's learning to 30,000 vertices removed
// 4,218 inactive vertices from it against 2,007 from the tetrahedron and took 0.45 s longer
// (+22%), and at 1,000 vertices its Hausdorff distance median was 3.74% against 3.57%.
inline constexpr float kMaxShapeOffset = 4.0f;
inline constexpr std::uint64_t kMaxVoxels = std::uint64_t(1) << 24;
// A point's side (sample_sides.h) is trusted up to this many d beyond the offset from the
// surface: a point in a concave part lies farther from the offset surface than the offset (the
// 99th percentile over the points, on the shared and corpus clouds that start from their solid:
// 0.4-4.3 d beyond it; the rotor ring's median 0.9 d), a point in a tunnel the solid fills up to
// 18 d (the femur's 99.9th percentile; its 99th, 6 d). Chosen over 3, 4, 5 and 6 d on the femur and the rotor ring, 5,000 vertices, seeds
// 1-3 (docs/algorithm.md, "Thin walls").
inline constexpr float kSideMargin = 5.0f;

struct SolidSurface {
    bool walled = false;        // an offset that does not leak was found
    float offset = 0.0f;        // the first offset that walls round, or the one the genus is read at (stable)
    float spacing = 0.0f;       // d, in transformed units
    std::uint32_t components = 0;
    int genus = -1;             // of the outer surface (summed over its components)
    // The genus can be trusted: the shifted grids agree on it at `offset` and the next offset.
    bool stable = false;
    // The outer surface (faces outward), when stable and, for genus 0, walled round at an offset
    // of at most kMaxShapeOffset (solid_start's condition for a start): on cells 2 kVoxel d
    // across when those read the same topology (the start's), and on cells kVoxel d across at
    // `offset` (empty when none of the shifted grids reads the genus there). Across the surface
    // the shell reaches offset / s, under the larger cells' size: the fine surface is the one
    // within about a cell of every point, the points' sides are read from it (sample_sides.h).
    IndexedMesh surface;
    IndexedMesh fine_surface;
    // Not stable, and `surface` and `fine_surface` are the outer surfaces of the genus-0 core
    // (solid_core.h) of the solid at `offset`: a start with the object's shape, whose handles are
    // not known.
    bool core = false;
    // Handles of the solid that are not the object's (solid_core.h: without_false_handles),
    // taken out: `genus` and the surfaces are the solid's without them.
    int false_handles = 0;
};

// The solid `points` (through `transform`) wall round, and its outer surface. O(P + voxels).
// `threads` (0: the machine's cores) share each grid's layers: the same result for every count.
SolidSurface solid_surface(PointSpan points, const PointTransform& transform, std::uint32_t threads = 1);

// The learning's start for topology closed and open: the solid's outer surface simplified to
// start_vertices(target) vertices, when `points` wall a solid round (one component, a genus that
// can be trusted; for genus 0, an offset of at most kMaxShapeOffset), or its genus-0 core when
// no genus can be trusted (SolidSurface::core); no mesh otherwise (the learning starts from the
// tetrahedron, as the paper's).
struct SolidStart {
    int solid_genus = -1;       // of the solid, when the points wall one round (one component)
    std::optional<Mesh> mesh;   // the start, dense slots, faces outward
    // The start is the solid's genus-0 core: the genus is not known, the handle search stays on.
    bool core = false;
    // The solid's outer surface on the fine cells (SolidSurface::fine_surface, else the start's
    // before its simplification).
    IndexedMesh surface;
    // How far from its nearest vertex of `surface` a point's side is trusted (sample_sides.h):
    // the offset and kSideMargin d.
    float reach = 0.0f;
};
SolidStart solid_start(PointSpan points, const PointTransform& transform, std::uint32_t target,
                       std::uint32_t threads = 1);
// Half the target, at most kMaxStart: a start coarse enough for the learning to shape, with the
// second half of the growth to fit it (the knot's tube is about 11 edges round at 2,000).
inline constexpr std::uint32_t kMaxStart = 2000;
inline std::uint32_t start_vertices(std::uint32_t target) { return std::min(target / 2, kMaxStart); }


namespace solid_detail {
// For each cell of a grid of `dims` cells (x fastest) with distances `dist` (squared, in cells,
// clamped at 255) to the nearest point's splat: the largest v such that a 6-connected path
// of cells whose distances are all at least v joins the cell to the grid's border, the border
// layer excluded from the paths' insides (its cells keep their own distance). At an offset of r
// cells, the cells of level above r^2 are the outside: one flood (a bucket queue in order of
// decreasing level) serves every offset. Precondition: every dimension at least 3. O(cells).
std::vector<std::uint8_t> outside_levels(const std::array<std::uint32_t, 3>& dims, const std::vector<std::uint8_t>& dist);
// One grid's reading at one offset (in units of d), on the grid solid_surface() builds, shifted
// by kGridShifts[shift]: whether it walls round, and then its solid's components and genus.
struct GridReading {
    bool walled = false;
    std::uint32_t components = 0;
    int genus = -1;
};
GridReading read_grid(PointSpan points, const PointTransform& transform, float offset, int shift);
}  // namespace solid_detail

}  // namespace nmesh
