#include "nmesh/finish/vertex_top_up.h"

#include <algorithm>
#include <tuple>
#include <vector>

#include "nmesh/finish/repair.h"
#include "nmesh/mesh/mesh.h"
#include "nmesh/mesh/mesh_pieces.h"

namespace nmesh {

IndexedMesh top_up_vertices(const IndexedMesh& mesh, std::uint32_t target, std::uint32_t& added) {
    added = 0;
    std::vector<char> is_used(mesh.positions.size(), 0);
    for (const auto& t : mesh.triangles)
        for (const std::uint32_t v : t) is_used[v] = 1;
    std::size_t used = std::size_t(std::count(is_used.begin(), is_used.end(), char(1)));
    if (used >= target) return mesh;
    const std::vector<MeshPiece> split = split_pieces(mesh);
    std::vector<Mesh> pieces;
    for (const MeshPiece& p : split) pieces.push_back(Mesh::from_indexed(p.mesh, true));
    // Every edge of every piece, longest first (ties: piece, then edge, for the same mesh on
    // every machine).
    std::vector<std::tuple<float, std::uint32_t, std::uint32_t>> edges;
    for (std::uint32_t k = 0; k < pieces.size(); ++k)
        for (std::uint32_t e = 0; e < pieces[k].edge_capacity(); ++e) {
            if (pieces[k].is_removed(Edge(e))) continue;
            const Halfedge h = Mesh::halfedge(Edge(e), 0);
            edges.emplace_back(-squared_distance(pieces[k].position(pieces[k].from(h)), pieces[k].position(pieces[k].to(h))),
                               k, e);
        }
    std::sort(edges.begin(), edges.end());
    for (const auto& [minus_length2, k, e] : edges) {
        if (used + added >= target) break;
        const Halfedge h = Mesh::halfedge(Edge(e), 0);
        if (pieces[k].is_boundary(pieces[k].from(h)) && pieces[k].is_boundary(pieces[k].to(h))) continue;
        if (split_edge(pieces[k], h).valid()) ++added;
    }
    std::vector<IndexedMesh> shapes;
    for (Mesh& p : pieces) {
        p.build_faces();
        shapes.push_back(p.to_indexed());
    }
    return join_pieces(shapes);
}

}  // namespace nmesh
