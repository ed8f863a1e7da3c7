// nmesh/metrics/topology.h — the topology fields of a QualityReport, from an indexed mesh.
#pragma once

#include <array>
#include <cstdint>

#include "nmesh/indexed_mesh.h"
#include "nmesh/metrics.h"

namespace nmesh::metrics_detail {

// Whether the triangle repeats a vertex or has zero area.
bool is_degenerate(const IndexedMesh& mesh, const std::array<std::uint32_t, 3>& t);

// Fills the topology fields of the report from mesh_topology(): closed, manifold, euler, genus,
// components, isolated_vertices, boundary_loops, boundary_edges and boundary_length (not
// boundary_length_rel, which needs bbox_diagonal). The triangles' indices must be in range.
void analyze_topology(const IndexedMesh& mesh, QualityReport& r);

}  // namespace nmesh::metrics_detail
