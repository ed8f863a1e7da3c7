// nmesh/mesh/face_regions.h — the edge-connected regions of a set of faces: the flood fill the
// handle and bridge searches and the open-surface cut share.
#pragma once

#include <cstdint>
#include <vector>

#include "nmesh/mesh/mesh.h"

namespace nmesh {

// Calls visit(region) for each edge-connected region of the alive faces f for which member(f)
// holds (the mesh needs its face index). Regions come in the order of their lowest face slot; a
// region lists its faces in the order of a depth-first walk from that face, neighbours taken
// round each face's half-edges from Mesh::halfedge(f). `region` is valid during the call only.
template <class Member, class Visit>
void for_each_face_region(const Mesh& mesh, Member&& member, Visit&& visit) {
    const std::uint32_t nf = mesh.face_capacity();
    std::vector<char> seen(nf, 0);
    std::vector<std::uint32_t> region, stack;
    for (std::uint32_t f = 0; f < nf; ++f) {
        if (seen[f] || mesh.is_removed(Face(f)) || !member(f)) continue;
        region.clear();
        stack.assign(1, f);
        seen[f] = 1;
        while (!stack.empty()) {
            const std::uint32_t x = stack.back();
            stack.pop_back();
            region.push_back(x);
            for (Halfedge h = mesh.halfedge(Face(x)), s = h;;) {
                const Face u = mesh.face(Mesh::twin(h));
                if (u.valid() && !seen[u.idx] && member(u.idx)) seen[u.idx] = 1, stack.push_back(u.idx);
                if ((h = mesh.next(h)) == s) break;
            }
        }
        visit(static_cast<const std::vector<std::uint32_t>&>(region));
    }
}

}  // namespace nmesh
