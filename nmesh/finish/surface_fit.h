// nmesh/finish/surface_fit.h — the last step of the finishing stage: the vertices moved to where the mesh best
// matches the scan points, a least-squares fit after Hoppe, DeRose, Duchamp, McDonald and Stuetzle,
// "Mesh optimization" (SIGGRAPH 1993), with a membrane on the moves instead of springs.
#pragma once

#include <cstdint>

#include "nmesh/finish/cloud_surface.h"
#include "nmesh/mesh/mesh.h"

namespace nmesh {

// Why: each vertex the learning leaves settles at the mean of the samples it wins, which on a
// curved patch lies below them: the surface sits inside the points wherever it bends (the
// bunny's ears, the tips), and the regularisation's pull towards the nearest point, one point per
// vertex, does not remove that bias. The fit asks where the whole triangles best match the
// points instead.
//
// One round: every scan point (of the stage's cloud) finds its nearest triangle (a walk over the
// triangles from the one with the nearest centroid) and the foot of its perpendicular there,
// barycentric weights b_i; each vertex k moves by D_k, and the D minimise
//     sum_i |sum_k b_ik (V_k + D_k) - x_i|^2 + lambda sum_edges |D_a - D_b|^2 + eps sum_k |D_k|^2,
// Hoppe's distance energy with the feet held at their barycentric places, and a membrane on the
// displacements instead of Hoppe's springs on the positions: a smooth correction costs nothing, so
// the surface does not shrink where it bends (springs pull every vertex towards its neighbours'
// centroid), and the triangles keep the shape the regularisation gave them, while the membrane ties
// together the vertices whose points alone do not determine them (a vertex with no point, or with
// points only at its triangles' far corners). One sparse symmetric positive definite matrix of one
// row per vertex, three right-hand sides (x, y, z), solved by conjugate gradients (Eigen). The feet
// are found again at each round (a Gauss-Newton iteration): a point beyond a triangle's edge (at a
// crease, a tip) pulls the edge's vertices towards it, along the surface as well as across, so
// that the vertices gather where the surface bends.
//
// Points that do not pull: farther than kFitReach of their triangle's mean edge from the mesh (a
// stray point, a point across a scanner hole's rim; the cover, step 3, has drawn the surface out
// to the uncovered ones), and points whose nearest triangle faces away from them (their normal,
// CloudSurface::normal, against the triangle's: the other side of a part thinner than a triangle).
// Vertices that stay: boundary vertices (an open surface keeps its rim), the corners of triangles
// that are in a defect (a crossing pair, a folded edge) before the fit.
//
// Validity: after the rounds the mesh is searched once, exactly, for crossing pairs and folded
// edges (DefectTracker), and for triangles made thin (kFitMinAngleDeg); a move at either is
// halved, twice, then undone, until none touches a moved vertex, so the fit never adds a crossing
// pair, a folded edge or a triangle under 10 degrees.

// Points farther than this many mean edge lengths of their nearest triangle from it do not pull.
inline constexpr float kFitReach = 1.0f;
// A vertex moves at most this share of its mean edge length per round.
inline constexpr float kFitStepLimit = 0.5f;
// The membrane's weight per edge, lambda, in points (each point's term has weight 1): a prior
// worth a tenth of a point per edge, whatever the cloud's density. Where a vertex has many points
// (a coarse mesh of a dense cloud) they decide its move; where it has about one (the bunny at
// 30,000 vertices) the membrane does, and the fit does not follow the scan's noise. Chosen on every
// closed cloud at points / 10 and points / 3 vertices (docs/algorithm.md), against a weight in
// proportion to the points per vertex.
inline constexpr float kFitSmoothness = 0.1f;
// The fit uses at most this many of the cloud's points per vertex (every k-th point of a denser
// cloud), so that its cost follows the mesh, not the cloud.
inline constexpr std::uint32_t kFitPointsPerVertex = 16;
// No move is kept that leaves a triangle's smallest angle under this many degrees, or smaller
// than it was when it was under already: the fit does not add thin triangles.
inline constexpr float kFitMinAngleDeg = 10.0f;
// The damping eps per vertex, in points: only there so that a region without points (over a
// scanner hole) has a unique solution.
inline constexpr float kFitDamping = 1e-3f;

struct SurfaceFitOptions {
    int rounds = 4;
    float reach = kFitReach;
    float step_limit = kFitStepLimit;
    float smoothness = kFitSmoothness;
    // Moves along the vertex normals only (the point-to-plane linearisation, one right-hand side);
    // false, the choice: free moves (docs/algorithm.md: closer on every cloud measured).
    bool normal_only = false;
    // An edge is folded when the normals of its two triangles differ by more than this.
    float fold_dihedral_deg = 120.0f;
    // The caller knows the mesh has no crossing pair and no folded edge (the repair's result):
    // the search for the defects before the fit (whose corners stay) is skipped.
    bool known_clean = false;
    // Threads (0: the machine's cores) for each point's nearest triangle and foot; the normal
    // equations are summed on the calling thread in the points' order: the same fit for any count.
    std::uint32_t threads = 1;
};

struct SurfaceFitResult {
    std::uint32_t rounds = 0;       // rounds run
    std::uint64_t points_used = 0;  // pulling points, over the rounds
    std::uint64_t moves = 0;        // vertices moved, their moves kept whole
    std::uint64_t halved = 0;       // vertices whose moves were halved (once or twice) at a defect
    std::uint64_t undone = 0;       // vertices whose moves were undone
    double mean_move = 0.0;         // mean length of the kept moves
};

// Runs `options.rounds` rounds of the fit on `mesh` (with its face index; positions in the frame
// of `cloud`'s points), then the check. O(points + V) per round plus the solve (a few tens of conjugate-gradient
// iterations over a matrix with the mesh's sparsity), and one search of the mesh for defects.
SurfaceFitResult fit_surface(Mesh& mesh, const CloudSurface& cloud, const SurfaceFitOptions& options = {});

}  // namespace nmesh
