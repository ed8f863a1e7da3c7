#include "nmesh/spatial/point_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>

#include "nmesh/bounding_box.h"
#include "nmesh/error.h"

namespace nmesh {

namespace {

// Pruning must never discard a cell holding the answer, so its bounds are made slightly
// conservative. A float squared distance undershoots the true one by at most ~3e-7 relative.
constexpr double kRelativeSlack = 1e-6;
// Positions in grid units are computed in double; below 2^30 cells their rounding error stays
// under 1e-7 cells, and bounds are lowered by this much along each axis.
constexpr double kGridSlack = 1e-6;
// Cells per axis are kept below 2^30 so cell coordinates fit in 32 bits with room to spare.
constexpr double kMaxDimension = double(1u << 30);
// The pyramid then has at most 31 levels; a depth-first search holds at most 8 nodes per level.
constexpr int kMaxStack = 8 * 32;

int popcount64(std::uint64_t x) {
    x = x - ((x >> 1) & 0x5555555555555555ull);
    x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return int((x * 0x0101010101010101ull) >> 56);
}

// Index of the lowest set bit; x must not be 0.
int lowest_bit(std::uint64_t x) {
    assert(x != 0);
    return popcount64((x & (~x + 1)) - 1);
}

// Distance along one axis from u to the interval [lo, hi], less the assignment slack.
double axis_gap(double u, double lo, double hi) {
    const double g = u < lo ? lo - u : (u > hi ? u - hi : 0.0);
    return std::max(0.0, g - kGridSlack);
}

// The cell size for n points spread over a box with extents e (see the header for the rule).
double choose_cell_size(const double e[3], double n) {
    const double half_area = e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
    const double longest = std::max({e[0], e[1], e[2]});
    double h = 1.0;  // all points equal: any size works
    if (half_area > 0.0) {
        h = std::sqrt(half_area * PointGrid::kPointsPerCell / n);
    } else if (longest > 0.0) {  // collinear points
        h = longest * PointGrid::kPointsPerCell / n;
    }
    // Cells for a given size; infinite when an axis would need more than kMaxDimension cells.
    const auto cells = [&](double size) {
        double c = 1.0;
        for (int a = 0; a < 3; ++a) {
            const double d = std::max(1.0, std::ceil(e[a] / size));
            if (d > kMaxDimension) return std::numeric_limits<double>::infinity();
            c *= d;
        }
        return c;
    };
    const double max_cells = PointGrid::kMaxCellsPerPoint * n;
    for (double c = cells(h); c > max_cells; c = cells(h))
        h *= std::isinf(c) ? 2.0 : std::max(1.01, std::cbrt(c / max_cells));
    return h;
}

// Throws InputError unless n points can be indexed (at least one, and 32-bit indices).
void require_indexable(std::size_t n) {
    if (n == 0) throw InputError("PointGrid: the point cloud is empty");
    if (n > std::numeric_limits<std::uint32_t>::max())
        throw InputError("PointGrid: more than 2^32 - 1 points (" + std::to_string(n) + ")");
}

}  // namespace

// ---- construction -------------------------------------------------------------------------------

PointGrid::PointGrid(PointSpan points, const PointTransform& transform) {
    const std::size_t n = points.size();
    require_indexable(n);
    // One pass: finiteness and the bounding box of the transformed points.
    BoundingBox box;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 p = transform(points[i]);
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw InputError("PointGrid: point " + std::to_string(i) + " has a NaN or infinite coordinate");
        box.extend(p);
    }
    build(points, transform, box);
}

PointGrid::PointGrid(PointSpan points, const PointTransform& transform, const BoundingBox& bounds) {
    require_indexable(points.size());
    build(points, transform, bounds);
}

void PointGrid::build(PointSpan points, const PointTransform& transform, const BoundingBox& box) {
    const std::size_t n = points.size();
    // Grid geometry.
    double extent[3];
    for (int a = 0; a < 3; ++a) {
        origin_[a] = double(box.min[a]);
        extent[a] = double(box.max[a]) - origin_[a];
    }
    cell_size_ = choose_cell_size(extent, double(n));
    inv_cell_size_ = 1.0 / cell_size_;
    for (int a = 0; a < 3; ++a) dims_[a] = std::uint32_t(std::max(1.0, std::ceil(extent[a] * inv_cell_size_)));
    for (int a = 0; a < 3; ++a) bricks_[a] = (dims_[a] + kBrick - 1) / kBrick;
    level_dims_.push_back({dims_[0], dims_[1], dims_[2]});
    while (level_dims_.back() != std::array<std::uint32_t, 3>{1, 1, 1}) {
        const std::array<std::uint32_t, 3>& d = level_dims_.back();
        level_dims_.push_back({(d[0] + 1) / 2, (d[1] + 1) / 2, (d[2] + 1) / 2});
    }
    pyramid_.resize(level_dims_.size() - 1);
    for (std::size_t l = 1; l < level_dims_.size(); ++l) {
        const std::array<std::uint32_t, 3>& d = level_dims_[l];
        pyramid_[l - 1].assign(std::size_t((std::uint64_t(d[0]) * d[1] * d[2] + 63) / 64), 0);
    }

    // Occupancy bits of the grid and of the pyramid's first level, then the running count of
    // occupied cells per word. The points' cells are recomputed in the next pass rather than kept:
    // reading the points again costs less than writing and reading 8 bytes per point.
    const auto cell_of = [&](const Vec3& p, std::uint32_t(&c3)[3]) {
        for (int a = 0; a < 3; ++a) {
            const double u = (double(p[a]) - origin_[a]) * inv_cell_size_;
            c3[a] = std::min(std::uint32_t(u), dims_[a] - 1);  // u >= 0: truncation is floor
        }
        return cell_id(c3[0], c3[1], c3[2]);
    };
    occupancy_.assign(std::size_t(std::uint64_t(bricks_[0]) * bricks_[1] * bricks_[2]), OccupancyWord{});
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t c3[3];
        const std::uint64_t c = cell_of(transform(points[i]), c3);
        occupancy_[std::size_t(c >> 6)].bits |= std::uint64_t(1) << (c & 63);
        if (!pyramid_.empty()) set_bit(1, c3[0] / 2, c3[1] / 2, c3[2] / 2);
    }
    std::uint32_t occupied = 0;
    for (OccupancyWord& w : occupancy_) {
        w.rank = occupied;
        occupied += std::uint32_t(popcount64(w.bits));
    }

    // Counting sort of the points into their cells (stable, so each cell lists its points by
    // increasing index). Each point's slot (its cell's rank among the occupied cells) is kept
    // between the two passes: 4 bytes per point of temporary memory.
    HugePageVector<std::uint32_t> slot_of_point(n);
    cell_start_.assign(std::size_t(occupied) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t c3[3];
        const std::uint32_t slot = std::uint32_t(slot_of(cell_of(transform(points[i]), c3)));
        slot_of_point[i] = slot;
        ++cell_start_[std::size_t(slot) + 1];
    }
    for (std::size_t s = 0; s < occupied; ++s) cell_start_[s + 1] += cell_start_[s];
    std::vector<std::uint32_t> cursor(cell_start_.begin(), cell_start_.end() - 1);
    entries_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t pos = cursor[slot_of_point[i]]++;
        entries_[pos] = {transform(points[i]), std::uint32_t(i)};
    }

    // The rest of the pyramid: a cell of level l + 1 is occupied when one of its 8 children is.
    for (int l = 1; l + 1 < int(level_dims_.size()); ++l) {
        const std::array<std::uint32_t, 3>& d = level_dims_[std::size_t(l)];
        const std::vector<std::uint64_t>& bits = pyramid_[std::size_t(l - 1)];
        for (std::size_t w = 0; w < bits.size(); ++w)
            for (std::uint64_t word = bits[w]; word != 0; word &= word - 1) {
                const std::uint64_t c = std::uint64_t(w) * 64 + std::uint64_t(lowest_bit(word));
                const std::uint64_t i = c % d[0], j = (c / d[0]) % d[1], k = c / (std::uint64_t(d[0]) * d[1]);
                set_bit(l + 1, std::uint32_t(i / 2), std::uint32_t(j / 2), std::uint32_t(k / 2));
            }
    }
}

std::vector<Vec3> PointGrid::indexed_points() const {
    std::vector<Vec3> points(entries_.size());
    for (const Entry& e : entries_) points[e.index] = e.point;
    return points;
}

std::size_t PointGrid::memory_bytes() const {
    std::size_t bytes = sizeof(*this);
    bytes += entries_.capacity() * sizeof(Entry);
    bytes += occupancy_.capacity() * sizeof(OccupancyWord);
    bytes += cell_start_.capacity() * sizeof(std::uint32_t);
    bytes += pyramid_.capacity() * sizeof(std::vector<std::uint64_t>);
    for (const auto& level : pyramid_) bytes += level.capacity() * sizeof(std::uint64_t);
    bytes += level_dims_.capacity() * sizeof(std::array<std::uint32_t, 3>);
    return bytes;
}

// ---- queries ------------------------------------------------------------------------------------
//
// A query scans the 3x3x3 block of cells around the cell nearest to q, the home cell first. When
// the best point so far could still be beaten by a point outside the block, it moves one pyramid
// level up and scans the 3x3x3 block of level-1 cells around q (6x6x6 grid cells), then level 2,
// and so on, until no cell outside the scanned block can hold a closer point. Within a block the
// cells of coarser levels are searched depth-first, nearest child first, and boxes farther than the
// best point, or already scanned, are skipped.

struct PointGrid::Scan {
    Vec3 q;
    double u[3] = {0.0, 0.0, 0.0};         // q in grid units (cell edge 1, origin at the grid corner)
    std::uint32_t home[3] = {0, 0, 0};     // the grid cell nearest to q
    std::uint32_t done_lo[3] = {1, 1, 1};  // the block of grid cells scanned so far, inclusive
    std::uint32_t done_hi[3] = {0, 0, 0};  // (empty at first)
    double scale = 0.0;                    // squared grid units -> squared input units, made conservative
    float best_sq = std::numeric_limits<float>::infinity();
    std::uint32_t best = std::numeric_limits<std::uint32_t>::max();  // index of the best point

    // True when a box at squared grid distance g2 cannot hold a point closer than the best so far
    // (nor an equally close one, which might have a smaller index).
    bool pruned(double g2) const { return g2 * scale > double(best_sq); }
};

std::uint64_t PointGrid::cell_id(std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
    const std::uint64_t brick = (std::uint64_t(k / kBrick) * bricks_[1] + j / kBrick) * bricks_[0] + i / kBrick;
    return brick * 64 + (k % kBrick) * 16 + (j % kBrick) * 4 + i % kBrick;
}

std::uint64_t PointGrid::pyramid_bit(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
    const std::array<std::uint32_t, 3>& d = level_dims_[std::size_t(level)];
    return (std::uint64_t(k) * d[1] + j) * d[0] + i;
}

void PointGrid::set_bit(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k) {
    const std::uint64_t c = pyramid_bit(level, i, j, k);
    pyramid_[std::size_t(level - 1)][std::size_t(c >> 6)] |= std::uint64_t(1) << (c & 63);
}

std::int64_t PointGrid::slot_of(std::uint64_t c) const {
    const OccupancyWord& w = occupancy_[std::size_t(c >> 6)];
    const std::uint64_t bit = std::uint64_t(1) << (c & 63);
    if ((w.bits & bit) == 0) return -1;
    return std::int64_t(w.rank) + popcount64(w.bits & (bit - 1));
}

bool PointGrid::pyramid_occupied(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k) const {
    if (level == 0) {
        const std::uint64_t c = cell_id(i, j, k);
        return (occupancy_[std::size_t(c >> 6)].bits >> (c & 63)) & 1;
    }
    const std::uint64_t c = pyramid_bit(level, i, j, k);
    return (pyramid_[std::size_t(level - 1)][std::size_t(c >> 6)] >> (c & 63)) & 1;
}

void PointGrid::scan_cell(std::uint64_t c, Scan& s) const {
    const std::int64_t slot = slot_of(c);
    if (slot < 0) return;
    const std::uint32_t end = cell_start_[std::size_t(slot) + 1];
    for (std::uint32_t p = cell_start_[std::size_t(slot)]; p < end; ++p) {
        const Entry& e = entries_[p];
        const float d = squared_distance(s.q, e.point);
        if (d < s.best_sq || (d == s.best_sq && e.index < s.best)) {
            s.best_sq = d;
            s.best = e.index;
        }
    }
}

PointGrid::Span PointGrid::span(int axis, int level, std::uint32_t c, const Scan& s) const {
    // Cells per axis stay below 2^30, so these fit in 32 bits.
    const std::uint32_t first = c << level;
    const std::uint32_t last = std::min(first + (std::uint32_t(1) << level), dims_[axis]) - 1;
    const double g = axis_gap(s.u[axis], double(first), double(last) + 1.0);
    return {g * g, first >= s.done_lo[axis] && last <= s.done_hi[axis]};
}

void PointGrid::descend(int level, std::uint32_t i, std::uint32_t j, std::uint32_t k, Scan& s) const {
    struct Node {
        double g2;  // squared grid distance from q to the node's box
        std::uint32_t c[3];
        int level;
    };
    Node stack[kMaxStack];
    int top = 0;
    stack[top++] = {0.0, {i, j, k}, level};
    while (top > 0) {
        const Node n = stack[--top];
        if (s.pruned(n.g2)) continue;
        if (n.level == 0) {
            scan_cell(cell_id(n.c[0], n.c[1], n.c[2]), s);
            continue;
        }
        // The (up to) two children along each axis, then the children themselves, pushed in
        // order of decreasing distance so that the nearest is searched first.
        const int down = n.level - 1;
        const std::array<std::uint32_t, 3>& d = level_dims_[std::size_t(down)];
        Span spans[3][2];
        int halves[3];
        for (int a = 0; a < 3; ++a) {
            halves[a] = 2 * n.c[a] + 1 < d[a] ? 2 : 1;
            for (int h = 0; h < halves[a]; ++h) spans[a][h] = span(a, down, 2 * n.c[a] + h, s);
        }
        const int base = top;
        for (int hk = 0; hk < halves[2]; ++hk)
            for (int hj = 0; hj < halves[1]; ++hj)
                for (int hi = 0; hi < halves[0]; ++hi) {
                    const Span &x = spans[0][hi], &y = spans[1][hj], &z = spans[2][hk];
                    if (x.scanned && y.scanned && z.scanned) continue;
                    const double g2 = x.g2 + y.g2 + z.g2;
                    if (s.pruned(g2)) continue;
                    const std::uint32_t c[3] = {2 * n.c[0] + hi, 2 * n.c[1] + hj, 2 * n.c[2] + hk};
                    if (!pyramid_occupied(down, c[0], c[1], c[2])) continue;
                    assert(top < kMaxStack);
                    int at = top++;
                    for (; at > base && stack[at - 1].g2 < g2; --at) stack[at] = stack[at - 1];
                    stack[at] = {g2, {c[0], c[1], c[2]}, down};
                }
    }
}

void PointGrid::search_level(int level, Scan& s) const {
    struct Candidate {
        double g2;
        std::uint32_t c[3];
    };
    const std::array<std::uint32_t, 3>& d = level_dims_[std::size_t(level)];
    std::uint32_t lo[3], hi[3];
    Span spans[3][3];
    for (int a = 0; a < 3; ++a) {
        const std::uint32_t h = s.home[a] >> level;
        lo[a] = h > 0 ? h - 1 : 0;
        hi[a] = std::min(h + 1, d[a] - 1);
        for (std::uint32_t c = lo[a]; c <= hi[a]; ++c) spans[a][c - lo[a]] = span(a, level, c, s);
    }
    // The occupied cells of the block that are neither scanned nor too far, nearest first.
    Candidate candidates[27];
    int count = 0;
    for (std::uint32_t k = lo[2]; k <= hi[2]; ++k)
        for (std::uint32_t j = lo[1]; j <= hi[1]; ++j)
            for (std::uint32_t i = lo[0]; i <= hi[0]; ++i) {
                const Span &x = spans[0][i - lo[0]], &y = spans[1][j - lo[1]], &z = spans[2][k - lo[2]];
                if (x.scanned && y.scanned && z.scanned) continue;
                const double g2 = x.g2 + y.g2 + z.g2;
                if (s.pruned(g2) || !pyramid_occupied(level, i, j, k)) continue;
                int at = count++;
                while (at > 0 && candidates[at - 1].g2 > g2) {
                    candidates[at] = candidates[at - 1];
                    --at;
                }
                candidates[at] = {g2, {i, j, k}};
            }
    for (int c = 0; c < count; ++c)
        if (!s.pruned(candidates[c].g2)) descend(level, candidates[c].c[0], candidates[c].c[1], candidates[c].c[2], s);

    for (int a = 0; a < 3; ++a) {
        s.done_lo[a] = lo[a] << level;
        s.done_hi[a] = std::uint32_t(std::min((std::uint64_t(hi[a]) + 1) << level, std::uint64_t(dims_[a])) - 1);
    }
}

bool PointGrid::settled(const Scan& s) const {
    // Every cell outside the scanned block is at least `outside` grid units from q along some axis.
    double outside = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (s.done_lo[a] > 0) outside = std::min(outside, s.u[a] - double(s.done_lo[a]));
        if (s.done_hi[a] + 1 < dims_[a]) outside = std::min(outside, double(s.done_hi[a]) + 1.0 - s.u[a]);
    }
    if (outside == std::numeric_limits<double>::infinity()) return true;  // the whole grid
    const double g = std::max(0.0, outside - kGridSlack);
    return s.pruned(g * g);
}

NearestPoint PointGrid::find_nearest(const Vec3& q) const {
    assert(is_finite(q));
    Scan s;
    s.q = q;
    s.scale = cell_size_ * cell_size_ * (1.0 - kRelativeSlack);
    for (int a = 0; a < 3; ++a) {
        s.u[a] = (double(q[a]) - origin_[a]) * inv_cell_size_;
        s.home[a] = std::uint32_t(std::clamp(std::floor(s.u[a]), 0.0, double(dims_[a] - 1)));
    }

    // Level 0, the common case: the home cell, then those of its 26 neighbours that can still
    // hold a closer point. Along each axis a neighbouring layer is kept only if its distance along
    // that axis alone is within reach; the combinations are then checked in full.
    scan_cell(cell_id(s.home[0], s.home[1], s.home[2]), s);
    std::uint32_t layer[3][3];
    double layer_g2[3][3];
    int layers[3];
    for (int a = 0; a < 3; ++a) {
        const std::uint32_t h = s.home[a];
        layer[a][0] = h;
        layer_g2[a][0] = 0.0;
        layers[a] = 1;
        const auto add = [&](std::uint32_t c) {
            const double g = axis_gap(s.u[a], double(c), double(c) + 1.0);
            if (s.pruned(g * g)) return;
            layer[a][layers[a]] = c;
            layer_g2[a][layers[a]++] = g * g;
        };
        if (h > 0) add(h - 1);
        if (h + 1 < dims_[a]) add(h + 1);
        s.done_lo[a] = h > 0 ? h - 1 : 0;  // layers left out are out of reach: count them as done
        s.done_hi[a] = std::min(h + 1, dims_[a] - 1);
    }
    for (int lk = 0; lk < layers[2]; ++lk)
        for (int lj = 0; lj < layers[1]; ++lj) {
            const double g2_jk = layer_g2[2][lk] + layer_g2[1][lj];
            for (int li = (lk == 0 && lj == 0) ? 1 : 0; li < layers[0]; ++li)
                if (!s.pruned(g2_jk + layer_g2[0][li])) scan_cell(cell_id(layer[0][li], layer[1][lj], layer[2][lk]), s);
        }

    // Coarser levels until nothing outside the scanned block can be closer.
    for (int level = 1; !settled(s); ++level) {
        assert(level < int(level_dims_.size()));
        search_level(level, s);
    }
    assert(s.best < size());
    return {s.best, s.best_sq};
}

}  // namespace nmesh
