// The genus-0 core of a voxel solid (nmesh/learn/solid_core.h): the simple-cell table against
// cases worked by hand, and the core's topology against a brute-force count of the Euler
// characteristic of the Kuhn complex it spans, on solids with handles, a cavity, and ranks that
// say where to cut.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <set>
#include <vector>

#include "nmesh/learn/solid_core.h"

using namespace nmesh;

namespace {

using Dims = std::array<std::uint32_t, 3>;

std::uint32_t bit_of(int x, int y, int z) {
    for (int e = 0; e < 7; ++e) {
        if (x == kKuhnEdges[e][0] && y == kKuhnEdges[e][1] && z == kKuhnEdges[e][2]) return 1u << (2 * e);
        if (x == -kKuhnEdges[e][0] && y == -kKuhnEdges[e][1] && z == -kKuhnEdges[e][2]) return 1u << (2 * e + 1);
    }
    FAIL("not a Kuhn neighbour");
    return 0;
}

// The Euler characteristic and the components of the Kuhn complex on the cells `in` holds: every
// vertex, edge, triangle and tetrahedron of the grid's Kuhn triangulation whose corners all lie
// in it, enumerated from the tetrahedra (and the vertices), counted once each.
struct ComplexTopology {
    long euler = 0;
    int components = 0;
};
ComplexTopology kuhn_topology(const Dims& dims, const std::vector<std::uint8_t>& in) {
    const std::uint32_t nx = dims[0], ny = dims[1], nz = dims[2];
    auto index = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) { return (z * ny + y) * nx + x; };
    std::set<std::vector<std::uint32_t>> simplices;
    std::vector<int> parent(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) parent[i] = int(i);
    std::function<int(int)> root = [&](int i) { return parent[std::size_t(i)] == i ? i : parent[std::size_t(i)] = root(parent[std::size_t(i)]); };
    long vertices = 0;
    for (std::size_t i = 0; i < in.size(); ++i) vertices += in[i] != 0;
    for (std::uint32_t z = 0; z + 1 < nz; ++z)
        for (std::uint32_t y = 0; y + 1 < ny; ++y)
            for (std::uint32_t x = 0; x + 1 < nx; ++x)
                for (const auto& t : kTets) {
                    std::vector<std::uint32_t> c;
                    for (const int k : t) {
                        const std::uint32_t v = index(x + std::uint32_t(k & 1), y + std::uint32_t(k >> 1 & 1), z + std::uint32_t(k >> 2 & 1));
                        if (in[v]) c.push_back(v);
                    }
                    std::sort(c.begin(), c.end());
                    // Every face of the part of the tetrahedron in the set, with two corners or more.
                    for (std::uint32_t mask = 1; mask < (1u << c.size()); ++mask) {
                        std::vector<std::uint32_t> s;
                        for (std::size_t k = 0; k < c.size(); ++k)
                            if (mask >> k & 1u) s.push_back(c[k]);
                        if (s.size() >= 2) simplices.insert(s);
                        if (s.size() == 2) parent[std::size_t(root(int(s[0])))] = root(int(s[1]));
                    }
                }
    ComplexTopology t;
    t.euler = vertices;
    for (const auto& s : simplices) t.euler += (s.size() % 2 == 0) ? -1 : 1;
    for (std::size_t i = 0; i < in.size(); ++i) t.components += in[i] && root(int(i)) == int(i);
    return t;
}

// A grid of n^3 cells with a rank per cell from `f` (0: off the solid; the border layer kept off).
std::vector<std::uint16_t> ranks(std::uint32_t n, const std::function<std::uint16_t(int, int, int)>& f) {
    std::vector<std::uint16_t> r(std::size_t(n) * n * n, 0);
    for (std::uint32_t z = 1; z + 1 < n; ++z)
        for (std::uint32_t y = 1; y + 1 < n; ++y)
            for (std::uint32_t x = 1; x + 1 < n; ++x) r[(z * n + y) * n + x] = f(int(x), int(y), int(z));
    return r;
}

std::vector<std::uint8_t> solid_of(const std::vector<std::uint16_t>& r) {
    std::vector<std::uint8_t> s(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) s[i] = r[i] != 0;
    return s;
}

std::size_t count(const std::vector<std::uint8_t>& v) { return std::size_t(std::count(v.begin(), v.end(), std::uint8_t(1))); }

// A solid torus round the z axis through the grid's middle: radius R to the tube's centre line,
// tube radius a, in cells.
bool in_torus(int x, int y, int z, double c, double R, double a) {
    const double dx = x - c, dy = y - c, dz = z - c;
    const double q = std::sqrt(dx * dx + dy * dy) - R;
    return q * q + dz * dz <= a * a;
}

}  // namespace

TEST_CASE("a simple cell: its neighbours in the part form one contractible piece of its link") {
    CHECK_FALSE(simple_cell(0));                      // an isolated cell would be a new component
    CHECK(simple_cell(bit_of(1, 0, 0)));              // one neighbour: a cell added to a part
    CHECK_FALSE(simple_cell(0x3fff));                 // every neighbour: it would fill a cavity
    // Two opposite neighbours, not joined in the link: the cell would join two pieces (a handle
    // when they are one part elsewhere).
    CHECK_FALSE(simple_cell(bit_of(1, 0, 0) | bit_of(-1, 0, 0)));
    // Two neighbours joined by a link edge (a Kuhn edge between them: (1,0,0) to (1,1,0)).
    CHECK(simple_cell(bit_of(1, 0, 0) | bit_of(1, 1, 0)));
    // Every neighbour but one: a disc round the missing one's place on the link sphere.
    for (int b = 0; b < 14; ++b) CHECK(simple_cell(0x3fffu & ~(1u << b)));
    // A ring of the link round an axis without its inside: the four face neighbours across x and
    // y, with the diagonals between them in the link, and not the two along z... worked from
    // the table's definition: a ring has Euler characteristic 0 and is refused.
    const std::uint32_t ring = bit_of(1, 0, 0) | bit_of(1, 1, 0) | bit_of(0, 1, 0) | bit_of(-1, 0, 0) |
                               bit_of(-1, -1, 0) | bit_of(0, -1, 0);
    CHECK_FALSE(simple_cell(ring));
}

TEST_CASE("the core of a ball is the ball; of a solid torus, a ball cut once across the tube") {
    const std::uint32_t n = 24;
    const double c = (n - 1) / 2.0;
    const auto ball = ranks(n, [&](int x, int y, int z) {
        const double dx = x - c, dy = y - c, dz = z - c;
        return std::uint16_t(dx * dx + dy * dy + dz * dz <= 8.0 * 8.0 ? 1 : 0);
    });
    const Dims dims{n, n, n};
    const auto ball_core = genus_zero_core(dims, ball);
    CHECK(ball_core == solid_of(ball));
    const ComplexTopology b = kuhn_topology(dims, ball_core);
    CHECK(b.euler == 1);
    CHECK(b.components == 1);

    const auto torus = ranks(n, [&](int x, int y, int z) { return std::uint16_t(in_torus(x, y, z, c, 7.0, 3.0) ? 1 : 0); });
    const ComplexTopology t = kuhn_topology(dims, solid_of(torus));
    REQUIRE(t.euler == 0);  // the checker sees the handle
    REQUIRE(t.components == 1);
    const auto core = genus_zero_core(dims, torus);
    const ComplexTopology k = kuhn_topology(dims, core);
    CHECK(k.euler == 1);
    CHECK(k.components == 1);
    // The cut is one thin slice across the tube: a few percent of the cells.
    const std::size_t cells = count(solid_of(torus)), kept = count(core);
    CHECK(kept < cells);
    CHECK(double(cells - kept) < 0.1 * double(cells));
    for (std::size_t i = 0; i < core.size(); ++i) CHECK_MESSAGE(!(core[i] && !torus[i]), "a core cell off the solid");
}

TEST_CASE("the core cuts a handle where the rank is lowest, and leaves a cavity open") {
    const std::uint32_t n = 24;
    const double c = (n - 1) / 2.0;
    const Dims dims{n, n, n};
    // A torus whose cells on the side x > c + 5 rank lower (a contact between two parts, where
    // the shell is farthest from the points): the cut lies there, or where it meets the rest (a
    // cut across a tube in the Kuhn triangulation is a diagonal staircase: within two cells of it).
    const auto torus = ranks(n, [&](int x, int y, int z) {
        if (!in_torus(x, y, z, c, 7.0, 3.0)) return std::uint16_t(0);
        return std::uint16_t(x > c + 5.0 ? 10 : 200);
    });
    const auto core = genus_zero_core(dims, torus);
    CHECK(kuhn_topology(dims, core).euler == 1);
    std::size_t cut = 0, high = 0;
    for (std::uint32_t i = 0; i < core.size(); ++i)
        if (torus[i] && !core[i]) {
            ++cut;
            high += torus[i] == 200;
            CHECK(double(i % n) > c + 3.0);
        }
    CHECK(cut > 0);
    CHECK(4 * high <= cut);
    // Ranked the other way round, the cut leaves the low side.
    const auto flipped = ranks(n, [&](int x, int y, int z) {
        if (!in_torus(x, y, z, c, 7.0, 3.0)) return std::uint16_t(0);
        return std::uint16_t(x < c - 5.0 ? 10 : 200);
    });
    const auto core_flipped = genus_zero_core(dims, flipped);
    CHECK(kuhn_topology(dims, core_flipped).euler == 1);
    for (std::uint32_t i = 0; i < core.size(); ++i)
        if (flipped[i] && !core_flipped[i]) CHECK(double(i % n) < c - 3.0);

    // Two tori side by side joined through a block: genus 2, cut twice.
    const auto two = ranks(n + 12, [&](int x, int y, int z) {
        const bool a = in_torus(x, y, z, c, 6.0, 2.5), b = in_torus(x - 12, y, z, c, 6.0, 2.5);
        return std::uint16_t(a || b || (x >= 15 && x <= 21 && std::abs(y - c) < 2.0 && std::abs(z - c) < 2.0) ? 1 : 0);
    });
    const Dims wide{n + 12, n + 12, n + 12};
    const ComplexTopology t2 = kuhn_topology(wide, solid_of(two));
    REQUIRE(t2.components == 1);
    REQUIRE(t2.euler == -1);
    const auto core2 = genus_zero_core(wide, two);
    CHECK(kuhn_topology(wide, core2).euler == 1);
    CHECK(kuhn_topology(wide, core2).components == 1);

    // A hollow ball (a shell round a cavity): its complex has Euler characteristic 2; the core
    // stops short of closing it.
    const auto hollow = ranks(n, [&](int x, int y, int z) {
        const double r2 = (x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c);
        return std::uint16_t(r2 <= 9.0 * 9.0 && r2 >= 6.0 * 6.0 ? 1 : 0);
    });
    REQUIRE(kuhn_topology(dims, solid_of(hollow)).euler == 2);
    const auto core3 = genus_zero_core(dims, hollow);
    CHECK(kuhn_topology(dims, core3).euler == 1);
    CHECK(count(core3) < count(solid_of(hollow)));
}

TEST_CASE("a cut that crosses no point's splat is a false handle, one across points a real one") {
    const std::uint32_t n = 24;
    const double c = (n - 1) / 2.0;
    const Dims dims{n, n, n};
    const auto torus = ranks(n, [&](int x, int y, int z) { return std::uint16_t(in_torus(x, y, z, c, 7.0, 3.0) ? 1 : 0); });
    const auto core = genus_zero_core(dims, torus);
    // Points everywhere on the solid (every cell on a splat): the cut crosses material, the
    // handle is the object's and stays.
    const std::vector<std::uint8_t> on_points(torus.size(), 0);
    const FalseHandles real = without_false_handles(dims, torus, core, on_points);
    CHECK(real.cuts == 0);
    CHECK(real.solid == solid_of(torus));
    CHECK(kuhn_topology(dims, real.solid).euler == 0);
    // No point near the cut: a gap the offset closed; the handle goes.
    std::vector<std::uint8_t> off_points(torus.size(), 0);
    std::size_t cut = 0;
    for (std::size_t i = 0; i < torus.size(); ++i)
        if (torus[i] && !core[i]) off_points[i] = 4, ++cut;
    REQUIRE(cut > 0);
    const FalseHandles fake = without_false_handles(dims, torus, core, off_points);
    CHECK(fake.cuts == 1);
    CHECK(count(fake.solid) == count(solid_of(torus)) - cut);
    CHECK(kuhn_topology(dims, fake.solid).euler == 1);
    // One cell of the cut on a point is enough to keep it.
    for (std::size_t i = 0; i < torus.size(); ++i)
        if (off_points[i]) {
            off_points[i] = 0;
            break;
        }
    CHECK(without_false_handles(dims, torus, core, off_points).cuts == 0);
}
