// bench/resample_mesh.cpp — a cloud drawn from a mesh, as the corpus's clouds were made
// (../shared/data/corpus/README.md): points uniformly by area on the triangles, then Gaussian
// noise of sigma = NOISE × the mesh's bounding-box diagonal per coordinate. The peer benchmarks
// (bench/run_peers.sh) make their large cloud with it.
//
//   resample_mesh MESH N OUT.ply [--seed S] [--noise F]     (defaults: seed 7, noise 0.0005)
//
// OUT.ply: binary little-endian PLY of float x, y, z, the format of the shared clouds. The same
// arguments give the same file (nmesh::Random; the noise by Box-Muller from a second stream).
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/cli/arguments.h"
#include "nmesh/io.h"
#include "nmesh/util/random.h"
#include "surface_distance.h"

int main(int argc, char** argv) {
    std::string mesh_path, out_path;
    std::size_t n = 0;
    std::uint64_t seed = 7;
    double noise = 0.0005;
    try {
        const nmesh::cli::Arguments args(argc, argv, 1, {}, {"--seed", "--noise"});
        if (args.positional().size() != 3) throw nmesh::cli::UsageError("give a mesh, a point count and an output");
        mesh_path = args.positional()[0];
        n = std::stoull(args.positional()[1]);
        out_path = args.positional()[2];
        seed = args.count("--seed", 7);
        noise = args.number("--noise", 0.0005);
        if (n == 0 || !(noise >= 0.0)) throw nmesh::cli::UsageError("N must be positive and the noise not negative");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\nusage: %s MESH N OUT.ply [--seed S] [--noise F]\n", e.what(), argv[0]);
        return 2;
    }
    try {
        const nmesh::IndexedMesh mesh = nmesh::read_mesh(mesh_path);
        const nmesh::BoundingBox box = nmesh::bounding_box(mesh.positions);
        const double sigma = noise * double(nmesh::norm(box.max - box.min));
        std::vector<nmesh::Vec3> points = nmesh::bench::sample_surface(mesh, n, seed);
        nmesh::Random gauss(seed + 1);
        const double two_pi = 6.283185307179586;
        for (nmesh::Vec3& p : points) {
            for (int axis = 0; axis < 3; ++axis) {
                const double u1 = 1.0 - gauss.uniform(), u2 = gauss.uniform();  // u1 in (0, 1]
                p[axis] += float(sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(two_pi * u2));
            }
        }
        nmesh::write_file_atomically(out_path, [&](std::ostream& out) {
            out << "ply\nformat binary_little_endian 1.0\nelement vertex " << points.size()
                << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
            for (const nmesh::Vec3& p : points) {
                const float xyz[3] = {p[0], p[1], p[2]};
                out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
            }
        });
        std::fprintf(stderr, "%s: %zu points from %s (seed %llu, noise %g of the diagonal)\n", out_path.c_str(),
                     points.size(), mesh_path.c_str(), (unsigned long long)seed, noise);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
