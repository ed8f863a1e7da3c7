// nmesh/finish/cover.h — step 3 of the finishing stage: vertices drawn out to the scan points the
// surface leaves uncovered (a tip that the learning left short, or that the repair of a tangle
// took back).
#pragma once

#include <cstdint>
#include <vector>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh {

// A scan point is uncovered when it is farther than kCoverReach mean edge lengths from the
// triangles round its nearest vertex.
inline constexpr float kCoverReach = 0.5f;
// A vertex is drawn out only by at least this many uncovered points: a stray point alone draws
// no spike.
inline constexpr std::uint32_t kCoverMinPoints = 3;
// The moves may sharpen a crease up to this angle between the normals of two triangles, more
// than the repair's fold limit (120 degrees): the tip of a part thinner than an edge, drawn out
// to its points, is such a crease (the bunny's ear at 1,000 vertices). No move may make
// triangles cross.
inline constexpr float kCoverFoldDeg = 150.0f;

struct CoverResult {
    std::uint32_t moves = 0;   // vertex moves kept, over the iterations
    std::uint32_t undone = 0;  // moves undone because they made a fold or a crossing
};

// `iterations` times: each vertex that is the nearest vertex of kCoverMinPoints or more uncovered
// points of `cloud` moves `weight` of the way to their mean (the first iteration looks at every
// point, the later ones at the points still uncovered). A move after which a triangle of the
// vertex crosses another one, or folds (kCoverFoldDeg), is halved, twice, then undone; if that
// does not clear the mesh, all of the iteration's moves are undone and the iterations stop. A
// boundary vertex stays.
// `steep_folds`: the edges folded beyond kCoverFoldDeg that the repair left (a tail's tip folded
// flat); the corners of their triangles stay, so that the folds stay as they are and the moves
// elsewhere are judged on their own.
// Precondition: `mesh` has no crossing triangles and no edge folded beyond kCoverFoldDeg but
// `steep_folds`; it is not searched for them. O(points + vertices) per iteration (the cloud
// surface holds at most Parameters::index_points_per_vertex points per target vertex), plus the
// checks of the moved triangles.
CoverResult cover_uncovered_points(Mesh& mesh, const CloudSurface& cloud, int iterations = 3, float weight = 0.5f,
                                   const std::vector<Edge>& steep_folds = {});

}  // namespace nmesh
