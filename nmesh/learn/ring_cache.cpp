#include "nmesh/learn/ring_cache.h"

#include <sstream>

namespace nmesh {

void RingCache::refresh(const Mesh& mesh, Vertex v) {
    if (v.idx >= lines_.size()) lines_.resize(std::size_t(v.idx) + 1);
    Line& line = lines_[v.idx];
    std::uint32_t k = 0;
    const Halfedge first = mesh.halfedge(v);
    Halfedge h = first;
    do {
        if (k == limit_) {  // too many to cache: count 0 sends callers to the mesh
            line.count = 0;
            return;
        }
        line.ids[k++] = mesh.to(h).idx;
        h = mesh.cw_rotated(h);
    } while (h != first);
    line.count = k;
}

void RingCache::refresh_around(const Mesh& mesh, Vertex v) {
    refresh(mesh, v);
    mesh.for_each_outgoing_cw(v, [&](Halfedge h) { refresh(mesh, mesh.to(h)); });
}

std::string RingCache::check(const Mesh& mesh) const {
    std::ostringstream err;
    std::vector<std::uint32_t> ring;
    for (std::uint32_t vi = 0; vi < mesh.vertex_capacity(); ++vi) {
        const Vertex v(vi);
        if (mesh.is_removed(v)) continue;
        ring.clear();
        mesh.for_each_outgoing_cw(v, [&](Halfedge h) { ring.push_back(mesh.to(h).idx); });
        if (vi >= lines_.size()) {
            err << "vertex " << vi << " has no ring";
            return err.str();
        }
        const Line& line = lines_[vi];
        if (line.count == 0) {
            if (ring.size() <= limit_) {
                err << "vertex " << vi << " of valence " << ring.size() << " is marked as not cached";
                return err.str();
            }
            continue;
        }
        bool same = line.count == ring.size();
        std::size_t shift = 0;
        while (same && shift < ring.size() && ring[shift] != line.ids[0]) ++shift;
        same = same && shift < ring.size();
        for (std::size_t i = 0; same && i < ring.size(); ++i) same = line.ids[i] == ring[(i + shift) % ring.size()];
        if (!same) {
            err << "vertex " << vi << ": the cached ring differs from the mesh's";
            return err.str();
        }
    }
    return {};
}

}  // namespace nmesh
