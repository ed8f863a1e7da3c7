// nmesh/vertex_grid.h — an incremental spatial hash over the mesh vertices, answering the winner
// query of eq. (1) of the paper: which vertex is nearest to a sample?
//
// The learning loop asks one nearest query per iteration and moves a few vertices, so every
// operation is O(1) (expected, amortised) and allocation-free once the structure has grown:
//
//   - a uniform grid of cubic cells, addressed by packed 21-bit-per-axis integer keys in a
//     power-of-two open-addressing table (linear probing, at most half full, deletion by backward
//     shift so no tombstones accumulate). A dense array of cells is not used: the vertices lie near
//     a surface, so only about (cells per axis)^2 of the (cells per axis)^3 cells are occupied (at
//     10^6 vertices on a sphere, 1 in 45: a dense array would take 6 times the table's memory),
//     and a dense array could not hold the vertices that stray outside the domain;
//   - each occupied cell stores its vertices' positions inline, with their ids, in a chain of
//     64-byte blocks (4 entries, one cache line each, as structure of arrays: 4 x, 4 y, 4 z and
//     4 ids, so that a query computes 4 distances with one SIMD instruction per operation) taken
//     from a pooled free list, so a query scans contiguous memory and a cell change recycles
//     blocks instead of allocating;
//   - a move that stays inside its cell only rewrites the stored position.
//
// The cell size follows the vertices: the grid is rebuilt, with a cell size aiming at
// kVerticesPerCell vertices per occupied cell, whenever the vertex count has doubled or halved
// since the last rebuild, or when, after at least n/2 moves to another cell, the vertices have
// spread or gathered so that the mean occupancy is a factor 3 off target. Each rebuild is O(n)
// after Omega(n) operations: amortised O(1).
//
// Answers are exact: nearest(q) minimises nmesh::squared_distance(q, p) as computed in float, ties
// going to the smaller id — the same answer as a brute-force scan over the vertices.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/util/prefetch.h"
#include "nmesh/util/simd.h"
#include "nmesh/vec3.h"

namespace nmesh {

class VertexGrid {
public:
    // Returned by nearest() when the grid is empty.
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

    // Target mean number of vertices per occupied cell, right after a rebuild (it drifts by up to
    // a factor 2 either way before the next one). A query scans its own cell and those
    // neighbours that could hold a closer vertex: fewer vertices per cell mean more cells to probe
    // in the table, more mean more distances to compute. 2 to 6 cost within 15% of each other on a
    // sphere of 30k vertices; 4 is in the middle and fills the 4-entry blocks well.
    static constexpr double kVerticesPerCell = 4.0;

    // `domain`: the region where the vertices are expected to live (the engine normalises it to
    // about the unit cube). It fixes the grid origin and the first cell size; vertices and queries
    // outside it are handled exactly, only more slowly far from it (beyond 2^20 cells, at least 16
    // domain widths, they share the grid's outermost cells).
    // Throws ParameterError if `domain` is empty or has a NaN or infinite bound.
    explicit VertexGrid(const BoundingBox& domain);

    // Makes room for ids below `n` and for `n` vertices, so that inserts and moves up to that size
    // allocate nothing (except when a rebuild wants a larger cell table). O(n).
    void reserve(std::size_t n);
    // Gives back the room for ids from `n` on, none of which may be in the grid (for a compact
    // copy; reserve() makes it again). O(n).
    void shrink_ids(std::size_t n);

    // Adds vertex `id` at `p`. Amortised O(1).
    // Preconditions: id != kNone, !contains(id), p finite.
    void insert(std::uint32_t id, const Vec3& p);

    // Moves vertex `id` to `p`. O(1): just a key computation and a store when p stays in the same
    // cell, a removal and an insertion (expected O(1), no allocation in steady state) otherwise.
    // Preconditions: contains(id), p finite.
    void move(std::uint32_t id, const Vec3& p) {
        Slot& slot = slots_[id];
        const std::uint64_t key = cell_key(p);
        if (key == slot.key()) {
            set_entry_position(slot.entry, p);
            return;
        }
        move_to_cell(id, p, key);
    }

    // Removes vertex `id`; the id may later be inserted again. Amortised O(1).
    // Precondition: contains(id).
    void remove(std::uint32_t id);

    // The vertex nearest to q (smallest squared_distance(q, p) in float; ties: the smaller id), or
    // kNone when the grid is empty. Precondition: q finite, coordinates below about 1e18.
    // Cost: q's cell, then the cells around it that may hold a closer vertex than the best found
    // so far, in growing shells: a handful of cells near the vertices (about 200 ns at 30k
    // vertices on a sphere, 500-800 ns at 10^6, where the cells no longer fit in cache). When the
    // nearest vertex is many cells away (a query far from the surface, or a sparse grid) the
    // shells would cost more than a pass over all occupied cells, and that pass (pruned by cell
    // distance) is done instead, so a query never costs more than about twice a brute-force scan.
    std::uint32_t nearest(const Vec3& q) const;

    // Hints that start loading memory a later call will need; no effect on any answer. The
    // learning loop knows its next sample, and the vertices it is about to move, ahead of time.
    // prefetch_query(q): the table slot of q's cell, which it returns; prefetch_cell(cell), best
    // called once that slot is in the cache: the first block of the cell's vertices, when the
    // cell is occupied (after a rebuild in between, some other cell's, or none).
    std::uint64_t prefetch_query(const Vec3& q) const {
        const std::uint64_t key = cell_key(q);
        prefetch_for_read(&table_[home(key)]);
        return key;
    }
    void prefetch_cell(std::uint64_t cell) const {
        const std::uint32_t s = find_cell(cell);
        if (s != kNone) prefetch_for_read(&blocks_[table_[s].head]);
    }
    void prefetch_move(std::uint32_t id) const { prefetch_for_read(&slots_[id]); }

    // The order nearest() ranks vertices in: the float bits of the squared distance, then the id
    // (for non-negative floats the bits order like the values), so the smallest rank is the
    // answer. For callers that narrow an earlier answer down to a few candidates themselves.
    static std::uint64_t rank(float squared_distance, std::uint32_t id) {
        std::uint32_t bits;
        std::memcpy(&bits, &squared_distance, sizeof bits);
        return std::uint64_t(bits) << 32 | id;
    }

    std::size_t size() const { return size_; }
    bool contains(std::uint32_t id) const { return id < slots_.size() && slots_[id].entry != kNone; }
    // The stored position of vertex `id`. Precondition: contains(id).
    Vec3 position(std::uint32_t id) const { return entry_position(slots_[id].entry); }

    // Edge length of the cells, in the units of the positions.
    double cell_size() const { return cell_size_; }
    // Number of rebuilds (re-bucketings of all vertices) so far; for tests and diagnostics.
    std::size_t rebuild_count() const { return rebuild_count_; }

private:
    // Cell coordinates are 21-bit unsigned integers per axis, packed into a 63-bit key, with the
    // domain centre at 2^20; coordinates beyond the range are clamped into the outermost cells.
    static constexpr int kIndexBits = 21;
    static constexpr std::uint32_t kMaxIndex = (1u << kIndexBits) - 1;
    static constexpr double kIndexBias = double(1u << (kIndexBits - 1));
    static constexpr std::uint64_t kEmptyKey = ~std::uint64_t(0);  // not a valid packed key
    static constexpr std::uint32_t kBlockEntries = 4;              // 4 x 16 bytes: one cache line

    // kBlockEntries entries, lane by lane; the lanes past a cell's count hold stale values.
    struct alignas(64) Block {
        float x[kBlockEntries], y[kBlockEntries], z[kBlockEntries];
        std::uint32_t id[kBlockEntries];
    };
    static_assert(sizeof(Block) == 64, "a block must fill exactly one cache line");
    // A table slot: an occupied cell (key != kEmptyKey) with its block chain. The head block is the
    // only partly filled one: it holds entries [0, (count - 1) % kBlockEntries].
    struct Cell {
        std::uint64_t key;
        std::uint32_t head;
        std::uint32_t count;
    };
    // Per vertex id: its cell key and its entry (block * kBlockEntries + lane), kNone when absent.
    // The key is kept as two 32-bit halves so that a slot takes 12 bytes, not 16 (a uint64
    // member would pad it to its 8-byte alignment): 4 bytes less per vertex.
    struct Slot {
        std::uint32_t key_lo = std::uint32_t(kEmptyKey), key_hi = std::uint32_t(kEmptyKey >> 32);
        std::uint32_t entry = kNone;
        Slot() = default;
        Slot(std::uint64_t key, std::uint32_t e)
            : key_lo(std::uint32_t(key)), key_hi(std::uint32_t(key >> 32)), entry(e) {}
        std::uint64_t key() const { return std::uint64_t(key_hi) << 32 | key_lo; }
    };
    static_assert(sizeof(Slot) == 12, "a slot is three 32-bit words");
    // Bounding box of the cell coordinates occupied since the last rebuild (a superset of the
    // occupied cells, which lets queries skip empty space outside it).
    struct IndexBox {
        std::uint32_t lo[3];
        std::uint32_t hi[3];
    };

    std::uint32_t axis_index(float x, int axis) const {
        const double t = (double(x) - origin_[axis]) * inv_cell_size_ + kIndexBias;
        if (!(t >= 0.0)) return 0;  // also maps NaN to 0, keeping the conversion defined
        return t < double(kMaxIndex) ? std::uint32_t(t) : kMaxIndex;
    }
#if NMESH_SSE2
    // axis_index() for the three axes at once, x and y in the two lanes of one register: the same
    // operations on the same doubles, so the same key (max(t, 0) with t first gives 0 for a NaN t,
    // as axis_index() does). A vertex move computes one key: with this one it takes 59 instructions
    // instead of 72.
    std::uint64_t cell_key(const Vec3& p) const {
        const __m128d lo = _mm_setzero_pd(), hi = _mm_set1_pd(double(kMaxIndex));
        const __m128d inv = _mm_set1_pd(inv_cell_size_), bias = _mm_set1_pd(kIndexBias);
        const __m128 xy = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&p.x)));
        __m128d txy = _mm_add_pd(_mm_mul_pd(_mm_sub_pd(_mm_cvtps_pd(xy), _mm_loadu_pd(origin_)), inv), bias);
        __m128d tz = _mm_add_sd(
            _mm_mul_sd(_mm_sub_sd(_mm_cvtss_sd(lo, _mm_load_ss(&p.z)), _mm_load_sd(&origin_[2])), inv), bias);
        txy = _mm_min_pd(_mm_max_pd(txy, lo), hi);
        tz = _mm_min_sd(_mm_max_sd(tz, lo), hi);
        const __m128i ixy = _mm_cvttpd_epi32(txy);
        const std::uint32_t x = std::uint32_t(_mm_cvtsi128_si32(ixy));
        const std::uint32_t y = std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(ixy, 1)));
        const std::uint32_t z = std::uint32_t(_mm_cvttsd_si32(tz));
        return std::uint64_t(x) << (2 * kIndexBits) | std::uint64_t(y) << kIndexBits | z;
    }
#else
    std::uint64_t cell_key(const Vec3& p) const {
        return (std::uint64_t(axis_index(p.x, 0)) << (2 * kIndexBits)) |
               (std::uint64_t(axis_index(p.y, 1)) << kIndexBits) | std::uint64_t(axis_index(p.z, 2));
    }
#endif
    static std::uint32_t key_axis(std::uint64_t key, int axis) {
        return std::uint32_t(key >> (kIndexBits * (2 - axis))) & kMaxIndex;
    }
    // Entry e is lane e % kBlockEntries of block e / kBlockEntries.
    Vec3 entry_position(std::uint32_t e) const {
        const Block& b = blocks_[e / kBlockEntries];
        const std::uint32_t k = e % kBlockEntries;
        return {b.x[k], b.y[k], b.z[k]};
    }
    std::uint32_t entry_id(std::uint32_t e) const { return blocks_[e / kBlockEntries].id[e % kBlockEntries]; }
    void set_entry_position(std::uint32_t e, const Vec3& p) {
        Block& b = blocks_[e / kBlockEntries];
        const std::uint32_t k = e % kBlockEntries;
        b.x[k] = p.x;
        b.y[k] = p.y;
        b.z[k] = p.z;
    }
    void set_entry(std::uint32_t e, const Vec3& p, std::uint32_t id) {
        set_entry_position(e, p);
        blocks_[e / kBlockEntries].id[e % kBlockEntries] = id;
    }

    void move_to_cell(std::uint32_t id, const Vec3& p, std::uint64_t key);
    void add_to_cell(std::uint32_t id, const Vec3& p, std::uint64_t key);
    void remove_from_cell(std::uint32_t id);
    void rebuild();
    void pack_entries();
    void reinsert(std::size_t n);
    void set_cell_size(double h);
    void reset_table(std::size_t expected_cells);

    // The home slot of a cell: a Fibonacci hash of its (x, y) column, plus z. The z-neighbours
    // that a query visits together then share cache lines (30% faster queries at 10^6 vertices).
    std::size_t home(std::uint64_t key) const {
        const std::uint64_t column = ((key >> kIndexBits) * 0x9e3779b97f4a7c15ull) >> table_shift_;
        return std::size_t(column + (key & kMaxIndex)) & (table_.size() - 1);
    }
    std::uint32_t find_cell(std::uint64_t key) const;
    std::uint32_t find_or_add_cell(std::uint64_t key);
    void erase_cell(std::uint32_t slot);
    void grow_table();
    std::uint32_t allocate_block();
    void free_block(std::uint32_t b);

    // The query's pieces (see vertex_grid.cpp).
    struct Query;
    double face(int axis, std::int64_t i) const;
    void scan_cell(const Cell& cell, Query& query) const;
    bool visit_cell(std::uint64_t key, Query& query) const;
    void visit_near(Query& query) const;
    void visit_ring(std::int64_t r, Query& query) const;
    void scan_all_cells(Query& query) const;

    double origin_[3] = {0.0, 0.0, 0.0};  // the domain centre: position of cell coordinate 2^20
    double domain_extent_ = 1.0;          // largest side of the domain
    double cell_size_ = 1.0;
    double inv_cell_size_ = 1.0;
    double ring2_bound2_ = 0.0;  // a lower bound on the squared distance to ring 2 (visit_near), shrunk

    std::vector<Cell> table_;
    int table_shift_ = 64;
    std::size_t occupied_cells_ = 0;
    IndexBox index_box_{};

    std::vector<Block> blocks_;
    std::vector<std::uint32_t> block_next_;  // the next block of a chain, or of the free list
    std::uint32_t free_blocks_ = kNone;

    std::vector<Slot> slots_;
    std::size_t size_ = 0;
    std::size_t size_at_rebuild_ = 0;
    std::size_t cell_changes_ = 0;  // moves to another cell since the last rebuild
    std::size_t rebuild_count_ = 0;
};

}  // namespace nmesh
