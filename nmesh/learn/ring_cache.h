// nmesh/ring_cache.h — each vertex's one-ring as a list of neighbour ids in one cache line.
//
// The smoothing step (eq. 3-5) reads the ring of the winner and the ring of every vertex in it:
// about 40 neighbours per iteration. Walking them on the half-edge mesh is a chain of dependent
// loads (half-edge -> twin's next -> target -> position), each a cache miss once the mesh
// outgrows the cache. Here a vertex's neighbours sit side by side in one 64-byte line, so an
// iteration loads the winner's line, then its neighbours' lines (independent of each other,
// fetched in parallel), then the positions: three rounds of memory latency instead of dozens.
//
// The cache is derived data: the half-edge Mesh stays the one description of the connectivity.
// Whoever changes the mesh refreshes the vertices whose neighbour lists changed (O(valence)
// each). A vertex with more than kCapacity (or limit()) neighbours is marked as not cached;
// callers then walk the mesh for it. check() compares the whole cache with the mesh (for tests).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "nmesh/mesh/mesh.h"
#include "nmesh/util/prefetch.h"

namespace nmesh {

class RingCache {
public:
    // Neighbours stored per vertex: 15 ids and a count fill one cache line. Valences above 15 are
    // rare in a learnt mesh (35 of the 30,000 vertices of the learnt bunny; the mean is 6).
    static constexpr std::uint32_t kCapacity = 15;

    // Makes room for vertex ids below n.
    void reserve(std::size_t n) { lines_.reserve(n); }
    // Caches rings of at most `n` <= kCapacity neighbours from the next refresh() on (default
    // kCapacity). A smaller limit sends more vertices to the mesh walk: for testing that path.
    void set_limit(std::uint32_t n) { limit_ = n < kCapacity ? n : kCapacity; }
    std::uint32_t limit() const { return limit_; }

    // Re-reads v's neighbours from the mesh: clockwise (Mesh::cw_rotated), starting at the target
    // of mesh.halfedge(v). O(valence).
    void refresh(const Mesh& mesh, Vertex v);
    // refresh() for v and for each of its neighbours: what a vertex split or an edge collapse
    // changes around its remaining vertex.
    void refresh_around(const Mesh& mesh, Vertex v);

    // v's neighbour count, or 0 when v has more than limit() neighbours (walk the mesh instead).
    std::uint32_t count(Vertex v) const { return lines_[v.idx].count; }
    // v's neighbours, clockwise; count(v) of them.
    const std::uint32_t* neighbours(Vertex v) const { return lines_[v.idx].ids; }
    // Starts loading v's line into the cache (a hint; no effect on any result).
    void prefetch(Vertex v) const { prefetch_for_read(&lines_[v.idx]); }

    // An empty string when every alive vertex of `mesh` is cached with its current neighbours in
    // clockwise order (any starting point) or marked as not cached with a valence above
    // limit(); otherwise the first difference. O(n).
    std::string check(const Mesh& mesh) const;

    std::size_t memory_bytes() const { return lines_.capacity() * sizeof(Line); }

private:
    struct alignas(64) Line {
        std::uint32_t count;
        std::uint32_t ids[kCapacity];
    };
    static_assert(sizeof(Line) == 64, "a ring must fill exactly one cache line");
    std::vector<Line> lines_;
    std::uint32_t limit_ = kCapacity;
};

}  // namespace nmesh
