// tests/engine_checks.h — the whole-state check of a learning engine, for tests that drive one, and
// the check of a reconstruction's result.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "nmesh/indexed_mesh.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_check.h"
#include "nmesh/learn/neural_mesh.h"

namespace nmesh::test {

// The mesh passes the validator (any genus, boundaries allowed); its check, for the counts.
inline ManifoldCheck require_valid_mesh(const Mesh& m) {
    const ManifoldCheck c = check_manifold(m);
    INFO(c.error);
    REQUIRE(c.ok);
    return c;
}

// The mesh is a closed 2-manifold and the grid and activity index hold exactly its vertices.
inline void require_engine_valid(const NeuralMesh& engine) {
    const ManifoldCheck c = check_manifold(engine.mesh());
    INFO(c.error);
    REQUIRE(c.sphere());
    const std::string consistency = engine.check_consistency();
    INFO(consistency);
    REQUIRE(consistency.empty());
}

// A reconstruction result must be a closed genus-0 2-manifold: rebuild the half-edge form
// (which rejects anything else) and run the validator.
inline void require_closed_manifold(const IndexedMesh& m) {
    REQUIRE(m.positions.size() >= 4);
    const Mesh mesh = Mesh::from_indexed(m);  // throws unless closed, oriented, genus 0
    const ManifoldCheck c = check_manifold(mesh);
    INFO(c.error);
    REQUIRE(c.sphere());
    CHECK(m.triangles.size() == 2 * m.positions.size() - 4);
}

}  // namespace nmesh::test
