#include "nmesh/learn/solid_start.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <iterator>
#include <tuple>
#include <unordered_map>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/learn/cloud_splats.h"
#include "nmesh/learn/solid_core.h"
#include "nmesh/spatial/sorted_cells.h"
#include "nmesh/util/parallel.h"

namespace nmesh {

namespace solid_detail {

// Where each cell stops being outside: the largest v such that a 6-connected path of cells whose
// distances are all at least v joins the cell to the grid's border (the widest path, found by a
// flood from the border in order of decreasing v, one bucket per distance value). At an offset
// of r cells the outside is the cells whose level exceeds r^2 (a path of cells beyond the shell
// reaches them), and the shell is the cells whose distance is at most r^2: one flood serves
// every offset. O(cells).
std::vector<std::uint8_t> outside_levels(const std::array<std::uint32_t, 3>& dims, const std::vector<std::uint8_t>& dist) {
    const std::uint32_t nx = dims[0], ny = dims[1], nz = dims[2];
    std::vector<std::uint8_t> level(dist.size(), 0);
    std::vector<char> done(dist.size(), 0);
    std::array<std::vector<std::uint32_t>, 256> bucket;
    // The border layer is outside at every level (the padding keeps the shell off it); the flood
    // starts from the cells next to it, so that every cell it pops has its six neighbours in the
    // grid.
    for (std::uint32_t z = 0; z < nz; ++z)
        for (std::uint32_t y = 0; y < ny; ++y)
            for (std::uint32_t x = 0; x < nx; ++x) {
                const std::uint32_t i = (z * ny + y) * nx + x;
                if (x == 0 || y == 0 || z == 0 || x + 1 == nx || y + 1 == ny || z + 1 == nz) {
                    level[i] = dist[i];
                    done[i] = 1;
                } else if (x == 1 || y == 1 || z == 1 || x + 2 == nx || y + 2 == ny || z + 2 == nz) {
                    level[i] = dist[i];
                    bucket[dist[i]].push_back(i);
                }
            }
    const std::uint32_t step[6] = {1, std::uint32_t(-1), nx, std::uint32_t(-std::int64_t(nx)), nx * ny,
                                   std::uint32_t(-std::int64_t(nx) * ny)};
    for (int v = 255; v >= 0; --v) {
        std::vector<std::uint32_t>& here = bucket[std::size_t(v)];
        while (!here.empty()) {
            const std::uint32_t i = here.back();
            here.pop_back();
            if (done[i] || level[i] != v) continue;  // finished, or pushed again at a higher level
            done[i] = 1;
            for (const std::uint32_t s : step) {
                const std::uint32_t j = i + s;
                const std::uint8_t w = std::min(level[i], dist[j]);
                if (done[j] || w <= level[j]) continue;
                level[j] = w;
                bucket[w].push_back(j);
            }
        }
        here.shrink_to_fit();
    }
    return level;
}

}  // namespace solid_detail

namespace {

using solid_detail::outside_levels;

// The median distance from a point to its nearest other point, over up to 4096 of them (every
// k-th), found among the points of its cell and the 26 round it. 0 when no sampled point has a
// distinct neighbour there.
float median_spacing(const std::vector<Vec3>& p, const BoundingBox& box) {
    const std::size_t n = p.size();
    if (n < 2) return 0.0f;
    // Cells of about twice the spacing of a surface sample as large as the box allows.
    const float cell = float(2.0 * box.diagonal() / std::sqrt(double(n)));
    if (!(cell > 0.0f)) return 0.0f;
    const SortedCells cells(p, box.min, cell);
    const std::size_t stride = std::max<std::size_t>(1, n / 4096);
    std::vector<float> nearest;
    for (std::size_t i = 0; i < n; i += stride) {
        const auto c = cells.coords(p[i]);
        float best = std::numeric_limits<float>::max();
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz)
                    cells.for_each_in(c[0] + dx, c[1] + dy, c[2] + dz, [&](std::uint32_t j) {
                        const float d2 = squared_distance(p[i], p[j]);
                        if (d2 > 0.0f) best = std::min(best, d2);
                        return false;
                    });
        if (best < std::numeric_limits<float>::max()) nearest.push_back(std::sqrt(best));
    }
    if (nearest.empty()) return 0.0f;
    std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
    return nearest[nearest.size() / 2];
}

// A voxel grid over the cloud: cell states and the linear index of (x, y, z).
struct Grid {
    Vec3 origin;
    float h = 0.0f;
    std::array<std::uint32_t, 3> dims{};
    std::uint64_t size() const { return std::uint64_t(dims[0]) * dims[1] * dims[2]; }
    std::uint32_t index(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return (z * dims[1] + y) * dims[0] + x;
    }
    Vec3 centre(std::uint32_t i) const {
        const std::uint32_t x = i % dims[0], y = (i / dims[0]) % dims[1], z = i / (dims[0] * dims[1]);
        return origin + Vec3{float(x), float(y), float(z)} * h;
    }
};

// The squared distance, in cells, from each cell's centre to the nearest point's splat
// (cloud_splats.h): exact in every cell whose value is within `reach` (in the points' units),
// that or 255 in the others. The grid's layers are independent: `threads` share them.
std::vector<std::uint8_t> distances(const Grid& g, const std::vector<Splat>& splats, float reach, std::uint32_t threads) {
    return splat_distances(splats, g.origin, g.h, g.dims, reach / g.h, threads);
}

enum : std::uint8_t { kFree = 0, kShell = 1, kOutside = 2 };

// The shell (cells within `radius` cells of a point's splat), the outside (the other cells joined to the
// grid's border by a path outside the shell) and the rest, kFree, the solid's inside, from the
// cells' distances and outside levels. Returns the counts of shell and inside cells.
std::pair<std::uint64_t, std::uint64_t> classify(const std::vector<std::uint8_t>& dist,
                                                 const std::vector<std::uint8_t>& level, float radius,
                                                 std::vector<std::uint8_t>& state) {
    const float r2 = radius * radius;
    state.resize(dist.size());
    std::uint64_t shell = 0, inside = 0;
    for (std::size_t i = 0; i < state.size(); ++i) {
        const bool in_shell = float(dist[i]) <= r2;
        const bool outside = !in_shell && float(level[i]) > r2;
        state[i] = in_shell ? kShell : outside ? kOutside : kFree;
        shell += in_shell;
        inside += !in_shell && !outside;
    }
    return {shell, inside};
}

// The order in which the genus-0 core takes the solid's cells (solid_core.h): the inside first,
// then the shell from the points outwards, so that the cuts fall where the shell is farthest from
// the points, in a gap it closes between two parts; 0 off the solid.
std::vector<std::uint16_t> core_ranks(const std::vector<std::uint8_t>& state, const std::vector<std::uint8_t>& dist) {
    std::vector<std::uint16_t> rank(state.size());
    for (std::size_t i = 0; i < state.size(); ++i)
        rank[i] = state[i] == kOutside ? 0 : state[i] == kFree ? 257 : std::uint16_t(256 - dist[i]);
    return rank;
}

// The handles the offset made between two parts (solid_core.h: without_false_handles) taken out
// of the solid `state` (their cuts' cells made outside). Returns how many.
std::uint32_t drop_false_handles(const Grid& g, const std::vector<std::uint8_t>& dist, std::vector<std::uint8_t>& state) {
    const std::vector<std::uint16_t> rank = core_ranks(state, dist);
    const FalseHandles f = without_false_handles(g.dims, rank, genus_zero_core(g.dims, rank), dist);
    if (f.cuts > 0)
        for (std::size_t i = 0; i < state.size(); ++i)
            if (!f.solid[i]) state[i] = kOutside;
    return f.cuts;
}

// The components and the genus of the solid's outer surface (the marching tetrahedra surface of
// outer_surface()), counted on the grid without building it: its vertices are the Kuhn edges
// between the solid and the outside, its faces one per tetrahedron with one corner apart from the
// other three and two per tetrahedron split two and two (E = 3F / 2 on a closed surface); its
// components are the solid's, joined along the Kuhn edges (the solid has no cavity: whatever the
// outside does not reach is solid).
std::pair<std::uint32_t, int> surface_topology(const Grid& g, const std::vector<std::uint8_t>& state) {
    auto solid = [&](std::uint32_t i) { return state[i] != kOutside; };
    // The cubes with a solid corner lie within the solid cells' box grown by one cell below. Each
    // Kuhn edge belongs to the cube at its lower corner (those of the grid's last layers join
    // outside cells: the padding keeps the solid off the border).
    std::uint32_t lo[3] = {g.dims[0], g.dims[1], g.dims[2]}, hi[3] = {0, 0, 0};
    for (std::uint32_t i = 0; i < g.size(); ++i) {
        if (!solid(i)) continue;
        const std::uint32_t c[3] = {i % g.dims[0], (i / g.dims[0]) % g.dims[1], i / (g.dims[0] * g.dims[1])};
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
    if (lo[0] > hi[0]) return {0, 0};
    std::int64_t vertices = 0, faces = 0;
    for (std::uint32_t z = std::max(lo[2], 1u) - 1; z <= std::min(hi[2], g.dims[2] - 2); ++z)
        for (std::uint32_t y = std::max(lo[1], 1u) - 1; y <= std::min(hi[1], g.dims[1] - 2); ++y)
            for (std::uint32_t x = std::max(lo[0], 1u) - 1; x <= std::min(hi[0], g.dims[0] - 2); ++x) {
                bool in[8];
                int count = 0;
                for (int k = 0; k < 8; ++k) count += in[k] = solid(g.index(x + (k & 1), y + (k >> 1 & 1), z + (k >> 2 & 1)));
                if (count == 0 || count == 8) continue;
                // The seven Kuhn edges from corner 0: to corners 1, 2, 4 (the axes), 3, 5, 6 (the
                // face diagonals) and 7 (the cube's).
                for (const int k : {1, 2, 4, 3, 5, 6, 7}) vertices += in[0] != in[k];
                for (const auto& t : kTets) {
                    const int n = in[t[0]] + in[t[1]] + in[t[2]] + in[t[3]];
                    faces += n == 2 ? 2 : (n == 1 || n == 3) ? 1 : 0;
                }
            }
    // Components of the solid along the Kuhn edges, both ways (a solid cell's neighbours are all
    // in the grid: the padding keeps the solid two cells off the border).
    const std::array<std::int64_t, 14> step = kuhn_steps(g.dims);
    std::vector<char> seen(g.size(), 0);
    std::vector<std::uint32_t> stack;
    std::uint32_t components = 0;
    for (std::uint32_t i = 0; i < g.size(); ++i) {
        if (seen[i] || !solid(i)) continue;
        ++components;
        seen[i] = 1;
        stack.assign(1, i);
        while (!stack.empty()) {
            const std::uint32_t j = stack.back();
            stack.pop_back();
            for (const std::int64_t s : step) {
                const std::uint32_t k = std::uint32_t(std::int64_t(j) + s);
                if (!seen[k] && solid(k)) seen[k] = 1, stack.push_back(k);
            }
        }
    }
    const std::int64_t euler = vertices - faces / 2;  // V - E + F with E = 3F / 2
    return {components, int((2 * std::int64_t(components) - euler) / 2)};
}

// Marching tetrahedra on the cells' centres, the solid (not outside) against the outside: the
// outer surface, its vertices at the midpoints of the grid edges it crosses, faces outward. A
// piecewise linear level set at a value no corner takes, on the Kuhn triangulation of the grid
// (six tetrahedra round each cube's diagonal, matching across the cubes' faces), so a closed
// 2-manifold.
IndexedMesh outer_surface(const Grid& g, const std::vector<std::uint8_t>& state) {
    IndexedMesh m;
    std::unordered_map<std::uint64_t, std::uint32_t> at;
    auto vertex = [&](std::uint32_t a, std::uint32_t b) {
        const std::uint64_t k = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
        const auto [it, added] = at.emplace(k, std::uint32_t(m.positions.size()));
        if (added) m.positions.push_back((g.centre(a) + g.centre(b)) * 0.5f);
        return it->second;
    };
    auto emit = [&](std::uint32_t p, std::uint32_t q, std::uint32_t r, const Vec3& outward) {
        const Vec3& a = m.positions[p];
        if (dot(cross(m.positions[q] - a, m.positions[r] - a), outward) < 0.0f) std::swap(q, r);
        m.triangles.push_back({p, q, r});
    };
    for (std::uint32_t z = 0; z + 1 < g.dims[2]; ++z)
        for (std::uint32_t y = 0; y + 1 < g.dims[1]; ++y)
            for (std::uint32_t x = 0; x + 1 < g.dims[0]; ++x) {
                std::uint32_t corner[8];
                bool in[8];
                int count = 0;
                for (int c = 0; c < 8; ++c) {
                    corner[c] = g.index(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
                    in[c] = state[corner[c]] != kOutside;
                    count += in[c];
                }
                if (count == 0 || count == 8) continue;
                for (const auto& t : kTets) {
                    std::uint32_t ins[4], outs[4];
                    int ni = 0, no = 0;
                    Vec3 ci, co;
                    for (int k = 0; k < 4; ++k) {
                        const std::uint32_t v = corner[t[k]];
                        if (in[t[k]])
                            ins[ni++] = v, ci += g.centre(v);
                        else
                            outs[no++] = v, co += g.centre(v);
                    }
                    if (ni == 0 || no == 0) continue;
                    const Vec3 outward = co * (1.0f / float(no)) - ci * (1.0f / float(ni));
                    if (ni == 1 || no == 1) {
                        const std::uint32_t lone = ni == 1 ? ins[0] : outs[0];
                        const std::uint32_t* rest = ni == 1 ? outs : ins;
                        emit(vertex(lone, rest[0]), vertex(lone, rest[1]), vertex(lone, rest[2]), outward);
                    } else {
                        const std::uint32_t a = vertex(ins[0], outs[0]), b = vertex(ins[0], outs[1]),
                                            c = vertex(ins[1], outs[1]), d = vertex(ins[1], outs[0]);
                        emit(a, b, c, outward);
                        emit(a, c, d, outward);
                    }
                }
            }
    return m;
}

// The grid over `box` with cells `h` across (padded by the largest offset and two cells).
Grid grid_over(const BoundingBox& box, float h, float pad) {
    Grid g;
    g.h = h;
    g.origin = box.min - Vec3{pad, pad, pad};
    const Vec3 extent = box.extent() + Vec3{2 * pad, 2 * pad, 2 * pad};
    g.dims = {std::uint32_t(extent.x / h) + 2, std::uint32_t(extent.y / h) + 2, std::uint32_t(extent.z / h) + 2};
    return g;
}

// The grid of the readings: cells kVoxel d across over `box` (transformed points), padded by the
// largest offset and two cells, with larger cells when it would exceed kMaxVoxels.
Grid base_grid(const BoundingBox& box, float d) {
    const float largest = kOffsets[std::size(kOffsets) - 1] * d;
    Grid g = grid_over(box, kVoxel * d, largest + 2.0f * kVoxel * d);
    while (g.size() > kMaxVoxels) g = grid_over(box, g.h * 1.25f, largest + 2.0f * g.h * 1.25f);
    return g;
}

// The points through `transform`, their box and d.
struct Transformed {
    std::vector<Vec3> p;
    BoundingBox box;
    float d = 0.0f;
};
Transformed transformed(PointSpan points, const PointTransform& transform) {
    Transformed t;
    t.p.resize(points.size());
    for (std::size_t i = 0; i < t.p.size(); ++i) t.box.extend(t.p[i] = transform(points[i]));
    t.d = median_spacing(t.p, t.box);
    return t;
}

}  // namespace

namespace solid_detail {

GridReading read_grid(PointSpan points, const PointTransform& transform, float offset, int shift) {
    GridReading r;
    const Transformed t = transformed(points, transform);
    if (!(t.d > 0.0f)) return r;
    Grid g = base_grid(t.box, t.d);
    g.origin = g.origin + kGridShifts[shift] * g.h;
    const float largest = kOffsets[std::size(kOffsets) - 1] * t.d;
    const std::vector<std::uint8_t> dist = distances(g, cloud_splats(t.p, t.d, 1), largest, 1);
    std::vector<std::uint8_t> state;
    const auto [shell, inside] = classify(dist, outside_levels(g.dims, dist), offset * t.d / g.h, state);
    r.walled = double(inside) >= kMinInside * double(shell);
    if (r.walled) std::tie(r.components, r.genus) = surface_topology(g, state);
    return r;
}

}  // namespace solid_detail


SolidSurface solid_surface(PointSpan points, const PointTransform& transform, std::uint32_t threads) {
    SolidSurface out;
    const Transformed t = transformed(points, transform);
    const std::vector<Vec3>& p = t.p;
    const BoundingBox& box = t.box;
    const float d = t.d;
    if (!(d > 0.0f)) return out;
    out.spacing = d;
    const float largest = kOffsets[std::size(kOffsets) - 1] * d;
    const Grid g = base_grid(box, d);
    const std::vector<Splat> splats = cloud_splats(p, d, threads);
    // The distances up to `reach` (in the points' units): at an offset r no more than the reach,
    // a cell farther than the reach (255) is beyond the shell and on the outside's side of it as
    // it would be with its distance, and the reading is the same. The splats' boxes grow as the
    // reach's cube: a grid is computed to kFirstReach, and again farther only when the reading
    // goes beyond it (the offsets of the five shared clouds and most of the corpus's are at most
    // 6 d: docs/algorithm.md).
    auto grid_distances = [&](const Grid& q, float reach) { return distances(q, splats, reach, threads); };
    // The grids, each shifted by a fraction of a cell: a tunnel between two cells' corners (the
    // grid's own) comes and goes as the grid moves, a handle of the object does not.
    constexpr int kGrids = int(std::size(kGridShifts));
    std::array<Grid, kGrids> grids;
    std::array<std::vector<std::uint8_t>, kGrids> dist, level;
    // Per grid, the cells counted by (distance, outside level): whether an offset walls round is
    // read from them without a pass over the cells. A grid is prepared when first asked for.
    std::array<std::vector<std::uint32_t>, kGrids> counts;
    std::array<float, kGrids> reached{};  // the reach each grid's distances were computed to, in d
    const auto prepare = [&](int k, float offset) {
        if (!counts[k].empty() && offset <= reached[k]) return;
        // Beyond the first reach, in steps of a third (6, 8, 10.7, 12 d): each step costs about
        // what the ones before it did together.
        float reach = kFirstReach;
        constexpr float kLast = kOffsets[std::size(kOffsets) - 1];
        while (reach < offset && reach < kLast) reach = std::min(kLast, reach * (4.0f / 3.0f));
        reached[k] = std::max(reach, offset);
        grids[k] = g;
        grids[k].origin = g.origin + kGridShifts[k] * g.h;
        dist[k] = grid_distances(grids[k], reached[k] * d);
        level[k] = outside_levels(grids[k].dims, dist[k]);
        counts[k].assign(256 * 256, 0);
        for (std::size_t i = 0; i < dist[k].size(); ++i) ++counts[k][std::size_t(dist[k][i]) * 256 + level[k][i]];
    };
    // The shell (distance at most r^2) and the inside (beyond the shell, outside level at most r^2)
    // of grid k at an offset of r cells.
    const auto walled_round = [&](int k, float offset) {
        prepare(k, offset);
        const float r = offset * d / g.h, r2 = r * r;
        std::uint64_t shell = 0, inside = 0;
        for (int dv = 0; dv < 256; ++dv)
            for (int lv = 0; lv < 256; ++lv) {
                const std::uint32_t n = counts[k][std::size_t(dv) * 256 + std::size_t(lv)];
                if (float(dv) <= r2) shell += n;
                else if (float(lv) <= r2) inside += n;
            }
        return double(inside) >= kMinInside * double(shell);
    };
    // The reading at each offset, smallest first: what the grids agree on (a majority of them
    // walled round, one component, the same genus), until two offsets in a row agree on the same
    // genus. A genus that holds over a range of offsets is the object's (persistence); one that
    // holds at a single offset is the sampling's (the gaps closing) or the grid's.
    std::vector<std::uint8_t> state;
    // A genus of 0 has no handle to doubt: read at the first offset at which the first grid walls
    // round, it is taken as it is (the other grids and offsets are there to refuse handles that
    // are the grid's own or the sampling's). The clouds of genus 0 read it so, at the same offset
    // as with the votes (docs/algorithm.md), for a third of the work.
    for (const float offset : kOffsets) {
        if (!walled_round(0, offset)) continue;
        classify(dist[0], level[0], offset * d / g.h, state);
        if (surface_topology(grids[0], state) == std::make_pair(std::uint32_t(1), 0)) {
            out.walled = out.stable = true;
            out.offset = offset;
            out.components = 1;
            out.genus = 0;
        }
        break;
    }
    int previous = -1;  // the genus agreed at the previous offset, -1 when none
    float previous_offset = 0.0f;
    for (const float offset : kOffsets) {
        if (out.stable) break;
        // A genus read beyond twice the offset that first walls round would be that of a solid
        // closing gaps twice as wide as the sampling's own: not the object's.
        if (out.walled && offset > 2.0f * out.offset) break;
        int genera[kGrids];
        int walled = 0;
        for (int k = 0; k < kGrids; ++k) genera[k] = -1;
        for (int k = 0; k < kGrids; ++k) {
            // Two grids that agree are a majority already.
            if (k == 2 && genera[0] >= 0 && genera[0] == genera[1]) break;
            if (!walled_round(k, offset)) continue;
            classify(dist[k], level[k], offset * d / g.h, state);
            ++walled;
            const auto [components, genus] = surface_topology(grids[k], state);
            genera[k] = components == 1 ? genus : -2;  // -2: several components
            if (!out.walled || components != 1) out.components = components;
        }
        if (walled > 0 && !out.walled) {
            out.walled = true;
            out.offset = offset;
        }
        int agreed = -1;
        for (int k = 0; k < kGrids && agreed < 0; ++k) {
            if (genera[k] < 0) continue;
            int votes = 0;
            for (int j = 0; j < kGrids; ++j) votes += genera[j] == genera[k];
            if (2 * votes > kGrids) agreed = genera[k];
        }
        if (agreed >= 0 && agreed == previous) {
            out.stable = true;
            out.genus = agreed;
            out.components = 1;
            out.offset = previous_offset;
            break;
        }
        previous = agreed;
        previous_offset = offset;
    }
    if (!out.stable) {
        // No genus persists: where the solid walls round as close as a genus-0 start's
        // (kMaxShapeOffset) in one component, its genus-0 core is the start (solid_core.h), on
        // the larger cells when they hold one component too; the fine cells' core gives the
        // points' sides, as the fine surface does.
        if (!out.walled || out.offset > kMaxShapeOffset) return out;
        // The first offset from there to kMaxShapeOffset at which the first grid (or its larger
        // cells) walls the solid round itself: another grid may be what walled the first one.
        const Grid coarse = grid_over(box, 2.0f * g.h, largest + 4.0f * g.h);
        for (const float offset : kOffsets) {
            if (offset < out.offset || offset > kMaxShapeOffset || out.core) continue;
            const std::vector<std::uint8_t> coarse_dist = grid_distances(coarse, offset * d);
            prepare(0, offset);
            for (const Grid* q : {&coarse, static_cast<const Grid*>(&grids[0])}) {
                const bool fine = q != &coarse;
                const std::vector<std::uint8_t>& qd = fine ? dist[0] : coarse_dist;
                const auto [shell, inside] =
                    classify(qd, fine ? level[0] : outside_levels(q->dims, qd), offset * d / q->h, state);
                // Walled round in one component.
                if (double(inside) < kMinInside * double(shell) || surface_topology(*q, state).first != 1) continue;
                const std::vector<std::uint8_t> core = genus_zero_core(q->dims, core_ranks(state, qd));
                for (std::size_t i = 0; i < state.size(); ++i) state[i] = core[i] ? kFree : kOutside;
                assert(surface_topology(*q, state) == std::make_pair(std::uint32_t(1), 0));  // a ball's surface
                (fine ? out.fine_surface : out.surface) = outer_surface(*q, state);
                out.core = true;
            }
            if (out.core) out.offset = offset;
        }
        if (out.surface.triangles.empty()) out.surface = out.fine_surface;
        return out;
    }
    // Handles the offset made between two parts (their cuts cross no point's splat) are not the
    // object's: read on the first grid, the genus is that of the solid without them, and they are
    // taken out of every surface built below.
    if (out.genus > 0) {
        prepare(0, out.offset);
        classify(dist[0], level[0], out.offset * d / g.h, state);
        if (surface_topology(grids[0], state) == std::make_pair(std::uint32_t(1), out.genus) &&
            drop_false_handles(grids[0], dist[0], state) > 0) {
            const auto [components, genus] = surface_topology(grids[0], state);
            if (components == 1) out.false_handles = out.genus - genus, out.genus = genus;
        }
    }
    const auto solid_of = [&](const Grid& q, const std::vector<std::uint8_t>& qd) {
        if (out.false_handles > 0) drop_false_handles(q, qd, state);
        return surface_topology(q, state) == std::make_pair(std::uint32_t(1), out.genus);
    };
    if (out.genus == 0 && out.offset > kMaxShapeOffset) return out;  // no start: no surface to build
    // The start's surface: from cells twice as large (the unshifted grid's) when those give the
    // same topology at that offset or the next (a quarter of the triangles to simplify, and a
    // smoother start: from the fine cells' surface the ball on thin legs of the tests, 1,000
    // vertices, ended with crossings on 35 of seeds 1-40, from the coarse cells' on none), else
    // from the fine surface. A reading holds at two offsets, so the next one exists. The fine
    // surface, the first grid's that reads the agreed genus at the offset, is the sides' (header).
    const float* next = std::find(std::begin(kOffsets), std::end(kOffsets), out.offset) + 1;
    {
        const Grid coarse = grid_over(box, 2.0f * g.h, largest + 4.0f * g.h);
        const std::vector<std::uint8_t> coarse_dist = grid_distances(coarse, (next != std::end(kOffsets) ? *next : out.offset) * d);
        const std::vector<std::uint8_t> coarse_level = outside_levels(coarse.dims, coarse_dist);
        for (const float offset : {out.offset, next != std::end(kOffsets) ? *next : out.offset}) {
            classify(coarse_dist, coarse_level, offset * d / coarse.h, state);
            if (!solid_of(coarse, coarse_dist)) continue;
            out.surface = outer_surface(coarse, state);
            break;
        }
    }
    for (int k = 0; k < kGrids && out.fine_surface.triangles.empty(); ++k) {
        prepare(k, out.offset);
        classify(dist[k], level[k], out.offset * d / g.h, state);
        if (solid_of(grids[k], dist[k])) out.fine_surface = outer_surface(grids[k], state);
    }
    if (out.surface.triangles.empty()) out.surface = out.fine_surface;
    return out;
}

SolidStart solid_start(PointSpan points, const PointTransform& transform, std::uint32_t target,
                       std::uint32_t threads) {
    SolidStart out;
    const SolidSurface solid = solid_surface(points, transform, threads);
    const bool read = solid.walled && solid.components == 1 && solid.stable;
    if (!read && !solid.core) return out;
    if (read) out.solid_genus = solid.genus;
    if (solid.surface.triangles.empty()) return out;  // a genus-0 solid walled round too far out
    Mesh mesh = Mesh::from_indexed(solid.surface);
    out.core = solid.core;
    out.surface = solid.fine_surface.triangles.empty() ? solid.surface : solid.fine_surface;
    out.reach = (solid.offset + kSideMargin) * solid.spacing;
    mesh.drop_faces();
    if (!simplify(mesh, start_vertices(target))) return out;
    // Dense slots: the engine's per-vertex arrays are sized by them.
    out.mesh = Mesh::from_indexed(mesh.to_indexed());
    return out;
}

}  // namespace nmesh
