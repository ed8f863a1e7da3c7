// The smallest useful program on nmesh: point cloud file in, closed mesh file out.
//
//     reconstruct_minimal INPUT.ply|xyz OUTPUT.ply|obj|off [VERTICES]
#include <cstdio>
#include <cstdlib>

#include "nmesh/error.h"
#include "nmesh/io.h"
#include "nmesh/reconstruct.h"

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s INPUT OUTPUT [VERTICES]\n", argv[0]);
        return 2;
    }
    try {
        const nmesh::PointCloud cloud = nmesh::read_points(argv[1]);
        nmesh::Parameters params;  // Table 2 of the Neural Meshes ES paper
        params.target_vertices = argc > 3 ? std::uint32_t(std::strtoul(argv[3], nullptr, 10)) : 5000;
        const nmesh::Result result = nmesh::reconstruct(cloud, params);
        nmesh::write_mesh(argv[2], result.mesh);
        std::printf("%zu vertices, %zu triangles in %.2f s\n", result.mesh.positions.size(),
                    result.mesh.triangles.size(), result.stats.seconds);
    } catch (const nmesh::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
