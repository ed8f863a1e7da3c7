// tests/engine_checks.h — the whole-state check of a learning engine, for tests that drive one.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "nmesh/mesh_check.h"
#include "nmesh/neural_mesh.h"

namespace nmesh::test {

// The mesh is a closed 2-manifold and the grid and activity index hold exactly its vertices.
inline void require_engine_valid(const NeuralMesh& engine) {
    const ManifoldCheck c = check_manifold(engine.mesh());
    INFO(c.error);
    REQUIRE(c.ok);
    const std::string consistency = engine.check_consistency();
    INFO(consistency);
    REQUIRE(consistency.empty());
}

}  // namespace nmesh::test
