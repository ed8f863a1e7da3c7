#include "nmesh/spatial/vertex_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

#include "nmesh/error.h"

namespace nmesh {

namespace {

// Below this many vertices a query scans them all at little cost: no rebuild for spreading.
constexpr std::size_t kMinVerticesToResize = 64;
// A rebuild re-buckets again (at most kMaxRefinements passes in all, so a rebuild stays O(n))
// while the occupancy is more than kRefineRatio off target: at coarse scales a surface does not
// yet fill cells in proportion to their area, and one correction falls short.
constexpr int kMaxRefinements = 5;
constexpr double kRefineRatio = 1.5;
// Smallest cell relative to the domain: keeps the domain, with 15 domain widths of margin on
// every side, inside the 2^21 cells per axis (and 1e6 vertices on the unit sphere need only
// about L / 200).
constexpr double kMinCellFraction = 1.0 / 65536.0;

// A cell's bounds are computed in double from its integer coordinate while a position's
// coordinate was computed from the position; the two agree to about 2^-31 cell. Shrinking every
// cell gap by 2^-20 cell keeps the lower bounds below the true distances.
constexpr double kGapMargin = 1.0 / 1048576.0;
// squared_distance() in float is within a few ulps (2^-22 relative) of the exact value; scaling
// the lower bounds down by 2^-20 keeps them below the float distances they are compared with.
constexpr double kBoundShrink = 1.0 - 1.0 / 1048576.0;

}  // namespace

// The state of one nearest query: the query point, its cell, the best vertex so far.
struct VertexGrid::Query {
    Vec3 q;
    std::int64_t cell[3];
    // Distances from q to the lower and upper faces of its own cell (less the margin), and the
    // cell size: the cells d steps away along an axis are at least gap(axis, d) away from q.
    double to_lower[3], to_upper[3];
    double cell_size;
    // The best vertex so far as (float bits of its squared distance) << 32 | id: for non-negative
    // floats the bits order like the values, so the smallest key is the nearest vertex with ties
    // going to the smaller id. Starts at (+infinity, kNone).
    std::uint64_t best = std::uint64_t(0x7f800000u) << 32 | kNone;

    float best_d2() const {
        const std::uint32_t bits = std::uint32_t(best >> 32);
        float d2;
        std::memcpy(&d2, &bits, sizeof d2);
        return d2;
    }
    double gap(int axis, std::int64_t d) const {
        const double g = d > 0   ? to_upper[axis] + double(d - 1) * cell_size
                         : d < 0 ? to_lower[axis] + double(-d - 1) * cell_size
                                 : 0.0;
        return g > 0.0 ? g : 0.0;
    }
    // Whether a vertex at a squared distance >= lower_bound2 (a double lower bound) can still be
    // the answer. Not strict: an equal distance can win the tie on the id.
    bool may_beat(double lower_bound2) const { return lower_bound2 * kBoundShrink <= double(best_d2()); }
};

// --- construction and sizing ---------------------------------------------------------------

VertexGrid::VertexGrid(const BoundingBox& domain) {
    if (domain.empty()) throw ParameterError("domain", "VertexGrid: the domain box is empty");
    domain_extent_ = 0.0;
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(domain.min[a]) || !std::isfinite(domain.max[a]))
            throw ParameterError("domain", "VertexGrid: the domain box has a non-finite bound");
        origin_[a] = 0.5 * (double(domain.min[a]) + double(domain.max[a]));
        domain_extent_ = std::max(domain_extent_, double(domain.max[a]) - double(domain.min[a]));
    }
    if (!(domain_extent_ > 0.0)) domain_extent_ = 1.0;  // a single point: any scale will do
    set_cell_size(domain_extent_);
    reset_table(0);
}

void VertexGrid::reserve(std::size_t n) {
    if (n > slots_.size()) slots_.resize(n);
    const std::size_t blocks = n / 2 + 16;  // surface data needs about n / 3 (chains 3/4 full)
    blocks_.reserve(blocks);
    block_next_.reserve(blocks);
    std::size_t cap = 16;
    while (cap < 2 * std::size_t(double(n) / kVerticesPerCell) + 2) cap *= 2;
    table_.reserve(cap);
}

void VertexGrid::shrink_ids(std::size_t n) {
    if (n < slots_.size()) slots_.resize(n);
    slots_.shrink_to_fit();
}

void VertexGrid::set_cell_size(double h) {
    h = std::clamp(h, domain_extent_ * kMinCellFraction, domain_extent_);
    cell_size_ = h;
    inv_cell_size_ = 1.0 / h;
    // Beyond ring 1 every cell is at least h - 2 margins away from a query inside its own cell
    // (a gap to ring 2 is the gap to ring 1, at least -margin, plus h); 2^-19 h covers both.
    const double ring2 = h * (1.0 - 1.0 / 524288.0);
    ring2_bound2_ = ring2 * ring2 * kBoundShrink;
}

void VertexGrid::reset_table(std::size_t expected_cells) {
    // Half full at most (grown when the cells exceed that).
    std::size_t cap = 16;
    int shift = 64 - 4;
    while (cap < 2 * expected_cells) {
        cap *= 2;
        --shift;
    }
    table_.assign(cap, Cell{kEmptyKey, kNone, 0});
    table_shift_ = shift;
    occupied_cells_ = 0;
    for (int a = 0; a < 3; ++a) {
        index_box_.lo[a] = kMaxIndex;
        index_box_.hi[a] = 0;
    }
}

// Cell size: on a surface, the vertices per occupied cell grow as the square of the cell size,
// so the size that gives kVerticesPerCell is the current size times sqrt(target / measured),
// measured on the current cells. The first cell is the whole domain, and the mesh grows from a
// few vertices, so the size is refined at every doubling. The measurement also adapts to sets
// that are not surfaces (on a curve or in a volume the correction over- or under-shoots, and the
// next rebuilds converge).
//
// The vertices are re-bucketed in place, without a copy of them: pack_entries() moves them to
// the front of the block array, then reinsert() puts them into the new cells, reading the packed
// blocks in order and handing each one to the allocator once it is read. A copy (16 bytes per
// vertex) was the largest piece of the grid's memory after its cells.
void VertexGrid::rebuild() {
    const std::size_t n = size_;
    // Up to kMaxRefinements passes, while the occupancy is more than a factor kRefineRatio off.
    for (int pass = 0; pass < kMaxRefinements; ++pass) {
        const double per_cell = double(n) / double(occupied_cells_);
        if (pass > 0 && per_cell < kRefineRatio * kVerticesPerCell && per_cell * kRefineRatio > kVerticesPerCell) break;
        const double old_size = cell_size_;
        set_cell_size(cell_size_ * std::sqrt(kVerticesPerCell / per_cell));
        if (pass > 0 && cell_size_ == old_size) break;  // clamped: nothing to refine
        pack_entries();
        reset_table(std::size_t(double(n) / kVerticesPerCell) + 1);
        reinsert(n);
    }
    size_at_rebuild_ = n;
    cell_changes_ = 0;
    ++rebuild_count_;
}

// Moves the size_ entries to entries [0, size_), block by block in index order, and leaves the
// cells and the free list undefined (the caller resets them). Each block's count of entries in use
// is first written over its link (block_next_): 0 for the free blocks, the cell's fill for a head
// block, kBlockEntries for the others. Entry i is then written only after every entry at or below
// i has been read, so the packing overwrites nothing it still needs. O(blocks).
void VertexGrid::pack_entries() {
    for (std::uint32_t b = free_blocks_; b != kNone;) {
        const std::uint32_t next = block_next_[b];
        block_next_[b] = 0;
        b = next;
    }
    for (const Cell& cell : table_) {
        if (cell.key == kEmptyKey) continue;
        std::uint32_t fill = (cell.count - 1) % kBlockEntries + 1;
        for (std::uint32_t b = cell.head; b != kNone; fill = kBlockEntries) {
            const std::uint32_t next = block_next_[b];
            block_next_[b] = fill;
            b = next;
        }
    }
    std::uint32_t out = 0;
    for (std::uint32_t b = 0; b < std::uint32_t(blocks_.size()); ++b)
        for (std::uint32_t k = 0; k < block_next_[b]; ++k, ++out) {
            const std::uint32_t e = b * kBlockEntries + k;
            if (out != e) set_entry(out, entry_position(e), entry_id(e));
        }
    assert(out == size_);
    free_blocks_ = kNone;
}

// Adds the n packed entries [0, n) to the (empty) cell table under the current cell size. Packed
// block j is put on the free list once its last entry has been read, so the new chains reuse the
// packed blocks as they are read; the block array grows only by the difference (new chains are
// about 3/4 full, the packed blocks full).
void VertexGrid::reinsert(std::size_t n) {
    const std::uint32_t packed_blocks = std::uint32_t((n + kBlockEntries - 1) / kBlockEntries);
    blocks_.resize(packed_blocks);
    block_next_.resize(packed_blocks);
    for (std::uint32_t i = 0; i < std::uint32_t(n); ++i) {
        const Vec3 p = entry_position(i);
        const std::uint32_t id = entry_id(i);
        if (i % kBlockEntries == kBlockEntries - 1 || i + 1 == n) free_block(i / kBlockEntries);
        add_to_cell(id, p, cell_key(p));
    }
}

// --- updates -------------------------------------------------------------------------------

void VertexGrid::insert(std::uint32_t id, const Vec3& p) {
    assert(id != kNone && !contains(id));
    assert(is_finite(p));
    if (id >= slots_.size()) slots_.resize(std::max<std::size_t>(std::size_t(id) + 1, 2 * slots_.size()));
    add_to_cell(id, p, cell_key(p));
    ++size_;
    if (size_ >= 2 * size_at_rebuild_) rebuild();
}

void VertexGrid::remove(std::uint32_t id) {
    assert(contains(id));
    remove_from_cell(id);
    --size_;
    if (size_ > 0 && 2 * size_ <= size_at_rebuild_) rebuild();
}

void VertexGrid::move_to_cell(std::uint32_t id, const Vec3& p, std::uint64_t key) {
    assert(contains(id));
    assert(is_finite(p));
    remove_from_cell(id);
    add_to_cell(id, p, key);
    // After n/2 cell changes, resize the cells if the vertices have spread or gathered so much
    // that the mean occupancy is a factor 3 off target (beyond the factor 2 that count changes
    // cause).
    if (2 * ++cell_changes_ >= size_ && size_ >= kMinVerticesToResize) {
        const double per_cell = double(size_) / double(occupied_cells_);
        if (per_cell > 3.0 * kVerticesPerCell || 3.0 * per_cell < kVerticesPerCell) rebuild();
    }
}

void VertexGrid::add_to_cell(std::uint32_t id, const Vec3& p, std::uint64_t key) {
    Cell& cell = table_[find_or_add_cell(key)];
    const std::uint32_t lane = cell.count % kBlockEntries;
    if (lane == 0) {  // the head block is full (or there is none): chain a new one in front
        const std::uint32_t b = allocate_block();
        block_next_[b] = cell.head;
        cell.head = b;
    }
    set_entry(cell.head * kBlockEntries + lane, p, id);
    slots_[id] = Slot{key, cell.head * kBlockEntries + lane};
    ++cell.count;
}

// Fills the vertex's entry with the cell's last entry (in the head block) and drops the head
// block when it empties, so a cell's entries stay packed.
void VertexGrid::remove_from_cell(std::uint32_t id) {
    Slot& slot = slots_[id];
    const std::uint32_t s = find_cell(slot.key());
    assert(s != kNone);
    Cell& cell = table_[s];
    const std::uint32_t last_lane = (cell.count - 1) % kBlockEntries;
    const std::uint32_t last = cell.head * kBlockEntries + last_lane;
    if (slot.entry != last) {
        const std::uint32_t moved = entry_id(last);
        set_entry(slot.entry, entry_position(last), moved);
        slots_[moved].entry = slot.entry;
    }
    slot = Slot{};
    --cell.count;
    if (last_lane == 0) {
        const std::uint32_t b = cell.head;
        cell.head = block_next_[b];
        free_block(b);
    }
    if (cell.count == 0) erase_cell(s);
}

// --- the cell table ------------------------------------------------------------------------

std::uint32_t VertexGrid::find_cell(std::uint64_t key) const {
    const std::size_t mask = table_.size() - 1;
    for (std::size_t i = home(key);; i = (i + 1) & mask) {
        if (table_[i].key == key) return std::uint32_t(i);
        if (table_[i].key == kEmptyKey) return kNone;
    }
}

std::uint32_t VertexGrid::find_or_add_cell(std::uint64_t key) {
    const std::uint32_t found = find_cell(key);
    if (found != kNone) return found;
    if (2 * (occupied_cells_ + 1) > table_.size()) grow_table();
    const std::size_t mask = table_.size() - 1;
    std::size_t i = home(key);
    while (table_[i].key != kEmptyKey) i = (i + 1) & mask;
    table_[i] = Cell{key, kNone, 0};
    ++occupied_cells_;
    for (int a = 0; a < 3; ++a) {
        const std::uint32_t c = key_axis(key, a);
        index_box_.lo[a] = std::min(index_box_.lo[a], c);
        index_box_.hi[a] = std::max(index_box_.hi[a], c);
    }
    return std::uint32_t(i);
}

// Backward-shift deletion: the following entries of the probe run move back into the hole when
// their home allows it, so the table never holds tombstones.
void VertexGrid::erase_cell(std::uint32_t slot) {
    const std::size_t mask = table_.size() - 1;
    std::size_t hole = slot;
    for (std::size_t j = (hole + 1) & mask; table_[j].key != kEmptyKey; j = (j + 1) & mask) {
        const std::size_t k = home(table_[j].key);
        // The entry at j may fill the hole unless its home lies cyclically in (hole, j].
        const bool home_after_hole = hole <= j ? (hole < k && k <= j) : (hole < k || k <= j);
        if (!home_after_hole) {
            table_[hole] = table_[j];
            hole = j;
        }
    }
    table_[hole].key = kEmptyKey;
    --occupied_cells_;
}

void VertexGrid::grow_table() {
    std::vector<Cell> old;
    old.swap(table_);
    table_.assign(old.size() * 2, Cell{kEmptyKey, kNone, 0});
    --table_shift_;
    const std::size_t mask = table_.size() - 1;
    for (const Cell& cell : old) {
        if (cell.key == kEmptyKey) continue;
        std::size_t i = home(cell.key);
        while (table_[i].key != kEmptyKey) i = (i + 1) & mask;
        table_[i] = cell;
    }
}

std::uint32_t VertexGrid::allocate_block() {
    if (free_blocks_ != kNone) {
        const std::uint32_t b = free_blocks_;
        free_blocks_ = block_next_[b];
        return b;
    }
    blocks_.emplace_back();
    block_next_.push_back(kNone);
    return std::uint32_t(blocks_.size() - 1);
}

void VertexGrid::free_block(std::uint32_t b) {
    block_next_[b] = free_blocks_;
    free_blocks_ = b;
}

// --- the nearest query ---------------------------------------------------------------------

// The lower face of cell coordinate i along `axis`.
inline double VertexGrid::face(int axis, std::int64_t i) const {
    return origin_[axis] + (double(i) - kIndexBias) * cell_size_;
}

// Four distances at a time, each computed as squared_distance(q, p) computes it (same operations
// in the same order, so the same bits); the lanes that may beat the best vertex so far (rarely
// more than one per block once a near vertex is known) are then folded into its key.
void VertexGrid::scan_cell(const Cell& cell, Query& query) const {
    std::uint64_t best = query.best;
    std::uint32_t fill = (cell.count - 1) % kBlockEntries + 1;
    std::uint32_t blocks = (cell.count + kBlockEntries - 1) / kBlockEntries;
#if NMESH_SSE2
    const __m128 qx = _mm_set1_ps(query.q.x), qy = _mm_set1_ps(query.q.y), qz = _mm_set1_ps(query.q.z);
    for (std::uint32_t b = cell.head;; b = block_next_[b], fill = kBlockEntries) {
        const Block& block = blocks_[b];
        const __m128 dx = _mm_sub_ps(qx, _mm_load_ps(block.x));
        const __m128 dy = _mm_sub_ps(qy, _mm_load_ps(block.y));
        const __m128 dz = _mm_sub_ps(qz, _mm_load_ps(block.z));
        const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
        // The lanes past the cell's count get all bits set: a key above any vertex's.
        const __m128i unused = _mm_cmplt_epi32(_mm_set_epi32(3, 2, 1, 0), _mm_set1_epi32(int(fill)));
        alignas(16) std::uint32_t bits[kBlockEntries];
        _mm_store_si128(reinterpret_cast<__m128i*>(bits),
                        _mm_or_si128(_mm_castps_si128(d2), _mm_xor_si128(unused, _mm_set1_epi32(-1))));
        for (std::uint32_t k = 0; k < kBlockEntries; ++k) {
            const std::uint64_t key = std::uint64_t(bits[k]) << 32 | block.id[k];
            best = key < best ? key : best;
        }
        if (--blocks == 0) break;  // counted, so the end of the chain costs no memory access
    }
#else
    for (std::uint32_t b = cell.head;; b = block_next_[b], fill = kBlockEntries) {
        for (std::uint32_t k = 0; k < fill; ++k) {
            const std::uint64_t key =
                rank(squared_distance(query.q, entry_position(b * kBlockEntries + k)), blocks_[b].id[k]);
            best = key < best ? key : best;
        }
        if (--blocks == 0) break;
    }
#endif
    query.best = best;
}

// Scans the cell of `key` if it is occupied; returns whether it was.
inline bool VertexGrid::visit_cell(std::uint64_t key, Query& query) const {
    const std::size_t mask = table_.size() - 1;
    for (std::size_t i = home(key);; i = (i + 1) & mask) {
        if (table_[i].key == key) {
            scan_cell(table_[i], query);
            return true;
        }
        if (table_[i].key == kEmptyKey) return false;
    }
}

// Rings 0 and 1 when the query's cell is inside the index box and not at the edge of the
// coordinate range: the query's cell, then those of its 26 neighbours that are nearer than the
// best vertex found (near a surface, a few of them). The squared gaps are scaled by kBoundShrink
// once, and the best distance is read back only after a cell was scanned, so that the test of a
// neighbour is an addition and a comparison.
void VertexGrid::visit_near(Query& query) const {
    const std::uint64_t x = std::uint64_t(query.cell[0]), y = std::uint64_t(query.cell[1]),
                        z = std::uint64_t(query.cell[2]);
    visit_cell(x << (2 * kIndexBits) | y << kIndexBits | z, query);
    double limit = double(query.best_d2());
    double g2[3][3];  // squared gap to the cells at offsets -1, 0, +1 along each axis, times kBoundShrink
    for (int a = 0; a < 3; ++a) {
        const double lo = query.gap(a, -1), hi = query.gap(a, 1);
        g2[a][0] = lo * lo * kBoundShrink;
        g2[a][1] = 0.0;
        g2[a][2] = hi * hi * kBoundShrink;
    }
    // Usually only the side of each axis whose face is nearer to q can hold a closer vertex: the
    // candidates are then the 7 cells on those sides, tested nearest first (faces, edges, corner).
    double near2[3], far2[3];
    std::uint64_t step[3];  // to the neighbour on the near side (no carry: the cell is not at an edge)
    // Without branches: which side is nearer is a coin toss, and a mispredicted branch per axis
    // cost more than the rest of this loop.
    for (int a = 0; a < 3; ++a) {
        const std::uint64_t unit = std::uint64_t(1) << (kIndexBits * (2 - a));
        const std::uint64_t negate = 0 - std::uint64_t(g2[a][0] <= g2[a][2]);  // all ones: lower side
        step[a] = (unit ^ negate) - negate;
#if NMESH_SSE2
        const __m128d lo = _mm_set_sd(g2[a][0]), hi = _mm_set_sd(g2[a][2]);
        near2[a] = _mm_cvtsd_f64(_mm_min_sd(lo, hi));
        far2[a] = _mm_cvtsd_f64(_mm_max_sd(lo, hi));
#else
        near2[a] = std::min(g2[a][0], g2[a][2]);
        far2[a] = std::max(g2[a][0], g2[a][2]);
#endif
    }
    if (far2[0] > limit && far2[1] > limit && far2[2] > limit) {
        const std::uint64_t key = x << (2 * kIndexBits) | y << kIndexBits | z;
        const auto try_cell = [&](double gap2, std::uint64_t k) {
            if (gap2 <= limit && visit_cell(k, query)) limit = double(query.best_d2());
        };
        try_cell(near2[0], key + step[0]);
        try_cell(near2[1], key + step[1]);
        try_cell(near2[2], key + step[2]);
        try_cell(near2[0] + near2[1], key + step[0] + step[1]);
        try_cell(near2[0] + near2[2], key + step[0] + step[2]);
        try_cell(near2[1] + near2[2], key + step[1] + step[2]);
        try_cell(near2[0] + near2[1] + near2[2], key + step[0] + step[1] + step[2]);
        return;
    }
    for (int dx = -1; dx <= 1; ++dx) {
        const double gx = g2[0][dx + 1];
        if (gx > limit) continue;
        const std::uint64_t kx = (x + std::uint64_t(dx)) << (2 * kIndexBits);
        for (int dy = -1; dy <= 1; ++dy) {
            const double gxy = gx + g2[1][dy + 1];
            if (gxy > limit) continue;
            const std::uint64_t kxy = kx | (y + std::uint64_t(dy)) << kIndexBits;
            for (int dz = -1; dz <= 1; ++dz) {
                if ((dx | dy | dz) == 0 || gxy + g2[2][dz + 1] > limit) continue;
                if (visit_cell(kxy | (z + std::uint64_t(dz)), query)) limit = double(query.best_d2());
            }
        }
    }
}

// Visits the cells at Chebyshev distance exactly r from the query's cell, inside the index box,
// skipping those whose lower bound already loses to the best vertex. Along each axis the gap to
// the query grows with the offset, so the offsets worth visiting form an interval, found first:
// near the surface that leaves a few cells of the 26 around the query's.
void VertexGrid::visit_ring(std::int64_t r, Query& query) const {
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::max(-r, std::int64_t(index_box_.lo[a]) - query.cell[a]);
        hi[a] = std::min(r, std::int64_t(index_box_.hi[a]) - query.cell[a]);
        auto worth = [&](std::int64_t d) {
            const double g = query.gap(a, d);
            return query.may_beat(g * g);
        };
        while (lo[a] < 0 && lo[a] <= hi[a] && !worth(lo[a])) ++lo[a];
        while (hi[a] > 0 && hi[a] >= lo[a] && !worth(hi[a])) --hi[a];
        if (lo[a] > hi[a] || (lo[a] > 0 && !worth(lo[a])) || (hi[a] < 0 && !worth(hi[a]))) return;
    }
    for (std::int64_t dx = lo[0]; dx <= hi[0]; ++dx) {
        const double gx = query.gap(0, dx);
        const std::uint64_t kx = std::uint64_t(query.cell[0] + dx) << (2 * kIndexBits);
        for (std::int64_t dy = lo[1]; dy <= hi[1]; ++dy) {
            const double gy = query.gap(1, dy);
            const double gxy = gx * gx + gy * gy;
            if (!query.may_beat(gxy)) continue;
            const std::uint64_t kxy = kx | std::uint64_t(query.cell[1] + dy) << kIndexBits;
            // Off the ring's x and y faces, only the two z faces belong to the ring.
            const bool whole_column = dx == -r || dx == r || dy == -r || dy == r;
            const std::int64_t step = whole_column ? 1 : 2 * r;
            for (std::int64_t dz = whole_column ? lo[2] : -r; dz <= hi[2]; dz += step) {
                if (dz < lo[2]) continue;
                const double gz = query.gap(2, dz);
                if (!query.may_beat(gxy + gz * gz)) continue;
                visit_cell(kxy | std::uint64_t(query.cell[2] + dz), query);
            }
        }
    }
}

void VertexGrid::scan_all_cells(Query& query) const {
    for (const Cell& cell : table_) {
        if (cell.key == kEmptyKey) continue;
        double lb2 = 0.0;
        for (int a = 0; a < 3; ++a) {
            const double g = query.gap(a, std::int64_t(key_axis(cell.key, a)) - query.cell[a]);
            lb2 += g * g;
        }
        if (query.may_beat(lb2)) scan_cell(cell, query);
    }
}

std::uint32_t VertexGrid::nearest(const Vec3& q) const {
    if (size_ == 0) return kNone;
    Query query;
    query.q = q;
    query.cell_size = cell_size_;
    const double margin = kGapMargin * cell_size_;
    for (int a = 0; a < 3; ++a) {
        const std::int64_t c = axis_index(q[a], a);
        query.cell[a] = c;
        query.to_lower[a] = double(q[a]) - face(a, c) - margin;
        query.to_upper[a] = face(a, c + 1) - double(q[a]) - margin;
    }
    const IndexBox& box = index_box_;

    // Number of cells of the index box within Chebyshev distance r of the query's cell.
    auto cells_within = [&](std::int64_t r) -> std::int64_t {
        std::int64_t count = 1;
        for (int a = 0; a < 3; ++a) {
            const std::int64_t lo = std::max(query.cell[a] - r, std::int64_t(box.lo[a]));
            const std::int64_t hi = std::min(query.cell[a] + r, std::int64_t(box.hi[a]));
            if (hi < lo) return 0;
            count *= hi - lo + 1;
        }
        return count;
    };

    // Shells nearer than the index box are empty: start at the first one that reaches it.
    std::int64_t r = 0;
    for (int a = 0; a < 3; ++a) {
        r = std::max(r, std::int64_t(box.lo[a]) - query.cell[a]);
        r = std::max(r, query.cell[a] - std::int64_t(box.hi[a]));
    }
    // Beyond this many cells considered, one pass over the table is cheaper than more shells.
    const std::int64_t budget = std::int64_t(table_.size());
    bool near_path = r == 0;
    for (int a = 0; a < 3; ++a) near_path = near_path && query.cell[a] > 0 && query.cell[a] < std::int64_t(kMaxIndex);
    if (near_path) {
        visit_near(query);
        // Most queries end here: the best vertex is nearer than any cell beyond ring 1 can be.
        if (double(query.best_d2()) < ring2_bound2_) return std::uint32_t(query.best);
        r = 1;
    } else if (r > 1 && cells_within(r) > budget) {
        scan_all_cells(query);
        return std::uint32_t(query.best);
    } else {
        visit_ring(r, query);
    }
    for (;;) {
        // Every unvisited cell lies beyond one of the faces of the visited cube (where the index
        // box extends beyond it): the nearest such face bounds their distance from below.
        double bound = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
            const std::int64_t c = query.cell[a];
            if (c - r > std::int64_t(box.lo[a])) bound = std::min(bound, query.gap(a, -r - 1));
            if (c + r < std::int64_t(box.hi[a])) bound = std::min(bound, query.gap(a, r + 1));
        }
        if (bound == std::numeric_limits<double>::infinity()) break;  // the index box is covered
        if (!query.may_beat(bound * bound)) break;
        ++r;
        if (r > 1 && cells_within(r) > budget) {
            scan_all_cells(query);
            break;
        }
        visit_ring(r, query);
    }
    return std::uint32_t(query.best);
}

}  // namespace nmesh
