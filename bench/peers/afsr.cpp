// bench/peers/afsr.cpp — the advancing-front peer of the benchmarks: CGAL's
// advancing_front_surface_reconstruction with its default parameters (radius ratio bound 5,
// beta 0.52), from a point cloud to a triangle mesh. A benchmark-only program, built by
// bench/run_peers.sh from bench/peers/CMakeLists.txt; the library never links CGAL.
//
//   afsr INPUT.ply OUTPUT.ply
//
// Reads any point PLY CGAL reads (x, y, z), writes a binary little-endian PLY of float x, y, z
// (every input point, in input order: the facets index them) and list uchar int vertex_indices.
// Prints one line to stderr: points, facets, and the seconds of reading, reconstructing, writing.
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/read_points.h>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Facet = std::array<std::size_t, 3>;

bool write_ply(const std::string& path, const std::vector<Point>& points, const std::vector<Facet>& facets) {
    std::ofstream out(path, std::ios::binary);
    if (!out) return false;
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << points.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << facets.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const Point& p : points) {
        const float xyz[3] = {float(p.x()), float(p.y()), float(p.z())};
        out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
    }
    for (const Facet& f : facets) {
        const unsigned char three = 3;
        const std::int32_t abc[3] = {std::int32_t(f[0]), std::int32_t(f[1]), std::int32_t(f[2])};
        out.write(reinterpret_cast<const char*>(&three), 1);
        out.write(reinterpret_cast<const char*>(abc), sizeof abc);
    }
    return bool(out);
}

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s INPUT.ply OUTPUT.ply\n", argv[0]);
        return 2;
    }
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Point> points;
    if (!CGAL::IO::read_points(argv[1], std::back_inserter(points)) || points.empty()) {
        std::fprintf(stderr, "%s: cannot read points\n", argv[1]);
        return 1;
    }
    const double read = since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    std::vector<Facet> facets;
    CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(facets));
    const double reconstruct = since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    if (!write_ply(argv[2], points, facets)) {
        std::fprintf(stderr, "%s: cannot write\n", argv[2]);
        return 1;
    }
    std::fprintf(stderr, "afsr: %zu points, %zu facets; read %.3f s, reconstruct %.3f s, write %.3f s\n", points.size(),
                 facets.size(), read, reconstruct, since(t2));
    return 0;
}
