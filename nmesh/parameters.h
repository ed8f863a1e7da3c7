// nmesh/parameters.h — the parameters of a reconstruction.
//
// The defaults are Table 2 of the Neural Meshes ES paper (its settings for the 30,000-vertex
// bunny), except the target size, which a caller should choose. docs/algorithm.md explains each
// choice made beyond the paper.
#pragma once

#include <cstdint>

namespace nmesh {

// What topology the learning may give the surface (Parameters::topology).
enum class Topology {
    sphere,  // the paper's algorithm: the tetrahedron's genus 0, bit for bit as it always was (with
             // stray_ratio 0 on a cloud with stray points; a cloud in parts gets a surface each)
    closed,  // the cloud's genus: its solid's (nmesh/learn/solid_start.h), or handles learnt from the
             // data as the mesh grows (nmesh/learn/handles.h); a closed surface of that genus
    open,    // as closed, then opened where the cloud has no data (nmesh/finish/open_surface.h)
};
// "sphere" / "closed" / "open", and back; parse_topology throws ParameterError naming the choices.
const char* topology_name(Topology t);
Topology parse_topology(const char* name);

struct Parameters {
    std::uint32_t target_vertices = 10000;  // step 9: stop at this many vertices (>= 4, and at
                                            // most 357,913,927, the mesh's limit less a margin)
    double alpha_w = 0.08;                  // eq. (2): learning rate of the winner vertex, in (0, 1]
    double alpha_n = 0.01;                  // eq. (3): learning rate of the winner's neighbours, in [0, 1]
    double alpha = 0.95;                    // eq. (7): signal counter decay per iteration, in (0, 1)
    std::uint32_t cvs = 100;                // step 7: a vertex split every Cvs iterations (>= 1)
    std::uint32_t cec = 20;                 // step 8: inactive vertices removed every Cec * n iterations (>= 1)
    bool edge_swap = true;                  // Neural Meshes ES; false gives the basic Neural Meshes algorithm
    // Choice beyond the paper: step 3 may not fold the winner's triangles back against its fan,
    // and a winner found folded moves to its ring's centroid instead (NeuralMesh::guard_fold).
    // Without it, folds of the coarse early mesh grow into inside-out parts. Off by itself for a
    // flat cloud, whose closed mesh must fold flat. false, with finish false, topology sphere and
    // stray_ratio 0, gives the paper's plain algorithm, bit for bit.
    bool fold_guard = true;
    // Beyond the paper: whether the learning opens handles where the data has through-holes
    // (closed, the default; docs/algorithm.md, "Topology") and leaves the scan's holes open
    // (open). sphere is the paper's algorithm.
    Topology topology = Topology::closed;
    // Beyond the paper, topology closed and open: when the cloud walls a solid round, the
    // learning starts from its outer surface, with its genus and shape (solid_start.h), instead
    // of growing from a tetrahedron with the handle search. false: always the tetrahedron.
    bool solid_start = true;
    // Topology open: the smallest hole in the scan to open, as the distance from its middle to the
    // nearest point, in local point spacings (nmesh/finish/open_surface.h), in [0, 1000]. 0: the
    // default rule, which opens holes deeper than 2.75 times the larger of 1.2 typical edges and
    // 1.5 spacings, and keeps closed the sampling's own gaps (a scan's sparse parts) as well as
    // holes a few spacings across (the bunny's three small base holes). A smaller value opens
    // smaller holes, and sparse parts of a scan with them.
    float min_hole = 0.0f;
    // Beyond the paper: a point whose 8th nearest neighbour lies farther than this many times the
    // cloud's median of that distance is a stray sample (a scanner's point in the air) and is left
    // out before the learning (nmesh/pipeline/stray_points.h), in [0, 1000]; 0 keeps every point.
    // A surface sampled at random reaches about 2, the sparse parts of a real scan 4.
    float stray_ratio = 6.0f;
    // Beyond the paper, topology closed and open from the solid's start: how much a win counts by
    // the winner's distance to the sample (step 5: tau_w += 1 + adaptivity * d^2 / mean d^2), in
    // [0, 100]. 0 is the paper's signal counter, whose splits follow the density of the samples;
    // above 0, the vertices nearest to the samples the mesh reaches worst (tips, tails, sharp
    // bends) split sooner. A growth from the tetrahedron keeps the paper's counter: it finds the
    // shape's parts by the density. Off by default: 0.5 brought the corpus's tips nearer (the
    // triceratops' Hausdorff distance 2.16 to 1.80 times its reference's, the femur's 1.35 to
    // 1.08) but left the farthest vertex of a sphere sample 10% farther from the sphere
    // (docs/algorithm.md, "Adaptivity").
    double adaptivity = 0.0;
    std::uint64_t seed = 1;  // the same seed and input give a bit-identical mesh
    // Iterations of steps 1-6 (no splits or collapses) run after the target size is reached, so
    // the last vertices settle onto the surface; in units of the final vertex count n
    // (settle * n iterations), in [0, 1e6]. 0 disables the phase.
    double settle = 0.0;
    // The finishing stage (nmesh/finish/finish.h) once the target size is reached:
    // angle-improving flips and a tangential relaxation onto the cloud, then the repair of folds
    // and self-intersections, keeping the vertex count.
    bool finish = true;
    // The finishing stage's regularisation rounds, in [0, 1000]. 0 leaves only the repair.
    std::uint32_t finish_rounds = 10;
    // Rounds of the finishing stage's centroid fit, in [0, 100]: each moves the vertices so that
    // the triangles' centroids approach their nearest cloud points. It lowers DM(X,T) at the very
    // points it is measured at, not the distance to the scanned surface; off by default. Needs
    // the finishing stage.
    std::uint32_t fit_rounds = 0;
    // Rounds of the finishing stage's surface fit, in [0, 100] (nmesh/finish/surface_fit.h): the
    // vertices moved along their normals to where the triangles best match the cloud's points
    // (a least-squares fit), keeping every guarantee of the stage. 0 leaves the stage as it was
    // before the fit. Ignored without the finishing stage.
    std::uint32_t surface_fit_rounds = 4;
    // Passes of the finishing stage's vertex exchange, in [0, 100] (nmesh/finish/exchange.h): edge
    // collapses where the surface is flat paired with splits where it bends away from the mesh,
    // at most 2% of the vertices each, the count kept. 0 leaves the vertices where the learning's
    // sample density put them (the paper's behaviour); more passes move more of them to where the
    // shape needs them (10, the default, measured best at equal budget, docs/algorithm.md).
    // Ignored without the finishing stage.
    std::uint32_t exchange_passes = 10;
    // The nearest-point index behind eq. (9) (the edge swap's deviation) and the finishing stage
    // holds at most this many cloud points per target vertex: the whole cloud up to that size,
    // else a stratified sample of it, so that its cost follows the mesh rather than the cloud.
    // The learning still draws its samples from the whole cloud, and the metrics measure against
    // the whole cloud. 0 indexes every point.
    std::uint32_t index_points_per_vertex = 64;
    // Threads for the independent work of the stages around the learning (the solid's reading,
    // the samples' sides, the finishing stage's relaxation, surface fit and defect search, the
    // output check): 0, the machine's cores (std::thread::hardware_concurrency()), or 1 to 1024.
    // The learning runs on one. Every count gives the same mesh and statistics, bit for bit.
    std::uint32_t threads = 0;

    // Throws ParameterError naming the first parameter out of range.
    void validate() const;
};

}  // namespace nmesh
