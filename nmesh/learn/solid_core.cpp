#include "nmesh/learn/solid_core.h"

#include <queue>
#include <utility>

namespace nmesh {

namespace {

// The link of a grid vertex in the Kuhn triangulation, on the 14 neighbours (bits as in
// simple_cell): the triangles opposite the vertex in the 24 tetrahedra round it, and their edges.
struct Link {
    std::vector<std::array<int, 3>> triangles;
    std::vector<std::array<int, 2>> edges;
};

int neighbour_bit(int x, int y, int z) {
    for (int e = 0; e < 7; ++e) {
        if (x == kKuhnEdges[e][0] && y == kKuhnEdges[e][1] && z == kKuhnEdges[e][2]) return 2 * e;
        if (x == -kKuhnEdges[e][0] && y == -kKuhnEdges[e][1] && z == -kKuhnEdges[e][2]) return 2 * e + 1;
    }
    return -1;
}

Link kuhn_link() {
    Link link;
    // The eight cubes that have the origin as a corner, each cube's six tetrahedra.
    for (int o = 0; o < 8; ++o) {
        const int ox = -(o & 1), oy = -(o >> 1 & 1), oz = -(o >> 2 & 1);
        for (const auto& t : kTets) {
            std::array<int, 3> tri{};
            int n = 0;
            bool has_origin = false;
            for (const int c : t) {
                const int x = ox + (c & 1), y = oy + (c >> 1 & 1), z = oz + (c >> 2 & 1);
                if (x == 0 && y == 0 && z == 0)
                    has_origin = true;
                else if (n < 3)
                    tri[std::size_t(n++)] = neighbour_bit(x, y, z);
            }
            if (!has_origin) continue;
            link.triangles.push_back(tri);
            for (int a = 0; a < 3; ++a) {
                std::array<int, 2> e{tri[std::size_t(a)], tri[std::size_t((a + 1) % 3)]};
                if (e[0] > e[1]) std::swap(e[0], e[1]);
                bool known = false;
                for (const auto& f : link.edges) known = known || f == e;
                if (!known) link.edges.push_back(e);
            }
        }
    }
    return link;
}

std::vector<char> simple_table() {
    const Link link = kuhn_link();
    std::vector<char> table(std::size_t(1) << 14, 0);
    for (std::uint32_t set = 0; set < table.size(); ++set) {
        auto in = [&](int b) { return (set >> b & 1u) != 0; };
        int vertices = 0, edges = 0, triangles = 0;
        int parent[14];
        for (int b = 0; b < 14; ++b) parent[b] = b, vertices += in(b);
        auto root = [&](int b) {
            while (parent[b] != b) b = parent[b] = parent[parent[b]];
            return b;
        };
        for (const auto& e : link.edges)
            if (in(e[0]) && in(e[1])) ++edges, parent[root(e[0])] = root(e[1]);
        for (const auto& t : link.triangles) triangles += in(t[0]) && in(t[1]) && in(t[2]);
        int components = 0;
        for (int b = 0; b < 14; ++b) components += in(b) && root(b) == b;
        table[set] = components == 1 && vertices - edges + triangles == 1;
    }
    return table;
}

}  // namespace

bool simple_cell(std::uint32_t neighbours) {
    static const std::vector<char> table = simple_table();
    return table[neighbours & 0x3fffu] != 0;
}

std::array<std::int64_t, 14> kuhn_steps(const std::array<std::uint32_t, 3>& dims) {
    std::array<std::int64_t, 14> step{};
    for (std::size_t e = 0; e < 7; ++e) {
        step[2 * e] = kKuhnEdges[e][0] + std::int64_t(dims[0]) * (kKuhnEdges[e][1] + std::int64_t(dims[1]) * kKuhnEdges[e][2]);
        step[2 * e + 1] = -step[2 * e];
    }
    return step;
}

std::vector<std::uint8_t> genus_zero_core(const std::array<std::uint32_t, 3>& dims, const std::vector<std::uint16_t>& rank) {
    auto solid = [&](std::size_t i) { return rank[i] != 0; };
    const std::array<std::int64_t, 14> step = kuhn_steps(dims);
    const std::size_t n = rank.size();
    // Depth: Kuhn-edge steps from the nearest cell off the solid (a breadth-first search from
    // them). The solid keeps off the border layer, so a solid cell's neighbours are in the grid.
    std::vector<std::uint16_t> depth(n, 0);
    std::vector<std::uint32_t> front, next;
    for (std::uint32_t i = 0; i < n; ++i)
        if (solid(i)) {
            bool edge = false;
            for (const std::int64_t s : step) edge = edge || !solid(std::size_t(std::int64_t(i) + s));
            if (edge) depth[i] = 1, front.push_back(i);
        }
    for (std::uint16_t level = 2; !front.empty(); ++level) {
        next.clear();
        for (const std::uint32_t i : front)
            for (const std::int64_t s : step) {
                const std::size_t j = std::size_t(std::int64_t(i) + s);
                if (solid(j) && depth[j] == 0) depth[j] = level, next.push_back(std::uint32_t(j));
            }
        front.swap(next);
        if (level == 0xffff) break;
    }
    std::vector<std::uint8_t> core(n, 0);
    auto key = [&](std::size_t i) { return std::uint32_t(rank[i]) << 16 | depth[i]; };
    std::uint32_t seed = 0;
    bool any = false;
    for (std::uint32_t i = 0; i < n; ++i)
        if (solid(i) && (!any || key(i) > key(seed))) seed = i, any = true;
    if (!any) return core;
    // The highest rank first, then the deepest, then the smaller index (the same core on every
    // run). A cell that is not simple when it comes up waits: a neighbour that joins later queues
    // it again (a cell is in the queue at most once).
    using Entry = std::pair<std::uint32_t, std::uint32_t>;
    auto later = [](const Entry& a, const Entry& b) { return a.first != b.first ? a.first < b.first : a.second > b.second; };
    std::priority_queue<Entry, std::vector<Entry>, decltype(later)> queue(later);
    std::vector<std::uint8_t> queued(n, 0);
    auto join = [&](std::uint32_t i) {
        core[i] = 1;
        for (const std::int64_t s : step) {
            const std::uint32_t j = std::uint32_t(std::int64_t(i) + s);
            if (solid(j) && !core[j] && !queued[j]) queued[j] = 1, queue.push({key(j), j});
        }
    };
    join(seed);
    while (!queue.empty()) {
        const std::uint32_t i = queue.top().second;
        queue.pop();
        queued[i] = 0;
        std::uint32_t neighbours = 0;
        for (int b = 0; b < 14; ++b) neighbours |= std::uint32_t(core[std::size_t(std::int64_t(i) + step[std::size_t(b)])] != 0) << b;
        if (simple_cell(neighbours)) join(i);
    }
    return core;
}

FalseHandles without_false_handles(const std::array<std::uint32_t, 3>& dims, const std::vector<std::uint16_t>& rank,
                                   const std::vector<std::uint8_t>& core, const std::vector<std::uint8_t>& dist) {
    const std::array<std::int64_t, 14> step = kuhn_steps(dims);
    FalseHandles out;
    out.solid.resize(rank.size());
    for (std::size_t i = 0; i < rank.size(); ++i) out.solid[i] = rank[i] != 0;
    std::vector<std::uint8_t> seen(rank.size(), 0);
    std::vector<std::uint32_t> piece, stack;
    for (std::uint32_t i = 0; i < rank.size(); ++i) {
        if (!rank[i] || core[i] || seen[i]) continue;
        piece.clear();
        stack.assign(1, i);
        seen[i] = 1;
        bool on_points = false;
        while (!stack.empty()) {
            const std::uint32_t j = stack.back();
            stack.pop_back();
            piece.push_back(j);
            on_points = on_points || dist[j] == 0;
            for (const std::int64_t s : step) {
                const std::uint32_t k = std::uint32_t(std::int64_t(j) + s);
                if (rank[k] && !core[k] && !seen[k]) seen[k] = 1, stack.push_back(k);
            }
        }
        if (on_points) continue;
        ++out.cuts;
        for (const std::uint32_t j : piece) out.solid[j] = 0;
    }
    return out;
}

}  // namespace nmesh
