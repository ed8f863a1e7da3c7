// The pipeline's output check (nmesh/pipeline/output_check.h).
#include "nmesh/pipeline/output_check.h"

#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/metrics.h"

namespace nmesh::pipeline {

void check_output(Result& result, std::uint32_t threads) {
    const MeshTopology t = mesh_topology(result.mesh);
    result.stats.genus = t.genus;
    result.stats.boundary_loops = t.boundary_loops;
    if (t.closed) {
        result.stats.reoriented = orient_outward(result.mesh);
        result.stats.inward_faces = inward_faces(result.mesh, TriangleBvh(result.mesh), threads);
    }
    result.stats.crossing_pairs = count_self_intersections(result.mesh, threads);
}

}  // namespace nmesh::pipeline
