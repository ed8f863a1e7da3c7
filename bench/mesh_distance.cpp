// bench/mesh_distance.cpp — one measurement for every mesh of the peer benchmarks
// (bench/run_peers.sh), whichever program made it: the distance to a reference surface both ways,
// the distance from the cloud, the triangles' shape and the topology.
//
//   mesh_distance CLOUD REFERENCE MESH... [--samples N] [--header]
//
// One CSV row per MESH on stdout (--header: the column names first):
//   mesh, vertices (used by a triangle), faces,
//   to_ref, from_ref: the mean distance from samples drawn uniformly by area on the mesh (seed 11)
//     to the reference's nearest triangle, and from samples on the reference (seed 7) to the
//     mesh's nearest triangle (N samples each, default 100,000; bench/surface_distance.h, as the
//     corpus sweep measures);
//   chamfer: the mean of the two;
//   p2s: the mean distance from the cloud's points to the mesh's nearest triangle;
//   hausdorff: between the mesh and the cloud (nmesh::evaluate);
//   under_10deg: the share of triangles whose smallest angle is under 10 degrees;
//   closed, manifold, genus (-1 unless manifold), components, boundary_loops, crossing_pairs.
// Distances are relative to the cloud's bounding-box diagonal.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/cli/arguments.h"
#include "nmesh/io.h"
#include "nmesh/metrics.h"
#include "surface_distance.h"

int main(int argc, char** argv) {
    std::vector<std::string> paths;
    std::size_t samples = 100000;
    bool header = false;
    try {
        const nmesh::cli::Arguments args(argc, argv, 1, {"--header"}, {"--samples"});
        paths = args.positional();
        samples = args.count("--samples", 100000);
        header = args.has("--header");
        if (paths.size() < 3) throw nmesh::cli::UsageError("give a cloud, a reference mesh and at least one mesh");
        if (samples == 0) throw nmesh::cli::UsageError("--samples must be positive");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\nusage: %s CLOUD REFERENCE MESH... [--samples N] [--header]\n", e.what(), argv[0]);
        return 2;
    }
    try {
        const nmesh::PointCloud cloud = nmesh::read_points(paths[0]);
        const nmesh::BoundingBox box = nmesh::bounding_box(cloud.points);
        const double diagonal = double(nmesh::norm(box.max - box.min));
        const nmesh::IndexedMesh reference = nmesh::read_mesh(paths[1]);
        const std::vector<nmesh::Vec3> reference_samples = nmesh::bench::sample_surface(reference, samples, 7);
        if (header)
            std::printf(
                "mesh,vertices,faces,to_ref,from_ref,chamfer,p2s,hausdorff,under_10deg,closed,manifold,genus,"
                "components,boundary_loops,crossing_pairs\n");
        for (std::size_t i = 2; i < paths.size(); ++i) {
            const nmesh::IndexedMesh mesh = nmesh::read_mesh(paths[i]);
            const nmesh::QualityReport q = nmesh::evaluate(cloud.points, mesh);
            const double to = nmesh::bench::distances(nmesh::bench::sample_surface(mesh, samples, 11), reference).mean;
            const double from = nmesh::bench::distances(reference_samples, mesh).mean;
            std::printf("%s,%zu,%zu,%.4e,%.4e,%.4e,%.4e,%.4e,%.4e,%d,%d,%d,%zu,%zu,%zu\n", paths[i].c_str(),
                        q.vertices - q.isolated_vertices, q.faces, to / diagonal, from / diagonal,
                        0.5 * (to + from) / diagonal, q.p2s_mean_rel, q.hausdorff_rel, q.share_under_10deg,
                        int(q.closed), int(q.manifold), q.genus, q.components, q.boundary_loops, q.self_intersections);
            std::fflush(stdout);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
