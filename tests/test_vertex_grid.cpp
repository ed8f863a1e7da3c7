// VertexGrid: every answer is compared with a brute-force scan over a plain array of vertices.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "error_fixtures.h"
#include "nmesh/bounding_box.h"
#include "nmesh/error.h"
#include "nmesh/util/random.h"
#include "nmesh/vec3.h"
#include "nmesh/spatial/vertex_grid.h"

using nmesh::BoundingBox;
using nmesh::Random;
using nmesh::Vec3;
using nmesh::VertexGrid;

namespace {

constexpr std::uint32_t kNone = VertexGrid::kNone;
constexpr double kPi = 3.14159265358979323846;

BoundingBox unit_cube() {
    BoundingBox box;
    box.extend({0.0f, 0.0f, 0.0f});
    box.extend({1.0f, 1.0f, 1.0f});
    return box;
}

// The reference: positions by id, with a flag for presence, and an O(n) nearest.
struct Reference {
    std::vector<Vec3> position;
    std::vector<char> alive;
    std::vector<std::uint32_t> ids;  // the alive ids, in no particular order
    std::vector<std::uint32_t> where;

    bool contains(std::uint32_t id) const { return id < alive.size() && alive[id]; }
    void insert(std::uint32_t id, const Vec3& p) {
        if (id >= alive.size()) {
            position.resize(id + 1);
            alive.resize(id + 1, 0);
            where.resize(id + 1);
        }
        position[id] = p;
        alive[id] = 1;
        where[id] = std::uint32_t(ids.size());
        ids.push_back(id);
    }
    void remove(std::uint32_t id) {
        alive[id] = 0;
        const std::uint32_t last = ids.back();
        ids[where[id]] = last;
        where[last] = where[id];
        ids.pop_back();
    }
    std::uint32_t nearest(const Vec3& q) const {
        std::uint32_t best = kNone;
        float best_d2 = 0.0f;
        for (std::uint32_t id : ids) {
            const float d2 = nmesh::squared_distance(q, position[id]);
            if (best == kNone || d2 < best_d2 || (d2 == best_d2 && id < best)) {
                best = id;
                best_d2 = d2;
            }
        }
        return best;
    }
};

// Point distributions of the property test.
enum class Shape { cube, sphere, clusters, grid_points };

Vec3 random_point(Random& rng, Shape shape) {
    auto u = [&] { return float(rng.uniform()); };
    switch (shape) {
        case Shape::cube:
            return {u(), u(), u()};
        case Shape::sphere: {
            // Uniform on the sphere of radius 0.5 centred in the cube (Archimedes' projection).
            const double z = 2.0 * rng.uniform() - 1.0, phi = 2.0 * kPi * rng.uniform();
            const double r = std::sqrt(1.0 - z * z);
            return {float(0.5 + 0.5 * r * std::cos(phi)), float(0.5 + 0.5 * r * std::sin(phi)), float(0.5 + 0.5 * z)};
        }
        case Shape::clusters: {
            // Eight tight clusters at the cube's corners: most cells empty, neighbours far apart.
            const std::uint32_t c = rng.below(8);
            const float s = 0.002f;
            return {float(c & 1) + s * u(), float((c >> 1) & 1) + s * u(), float((c >> 2) & 1) + s * u()};
        }
        case Shape::grid_points:
            // A coarse lattice: many exactly equal positions and equal distances, so ties decide.
            return {float(rng.below(5)) * 0.25f, float(rng.below(5)) * 0.25f, float(rng.below(5)) * 0.25f};
    }
    return {};
}

// Queries: mostly near the points, some far outside the domain (up to 1000 domain widths).
Vec3 random_query(Random& rng, Shape shape) {
    const std::uint32_t kind = rng.below(10);
    if (kind < 6) {
        const Vec3 p = random_point(rng, shape);
        const float j = 0.01f;
        return p + Vec3{j * float(rng.uniform() - 0.5), j * float(rng.uniform() - 0.5), j * float(rng.uniform() - 0.5)};
    }
    if (kind < 8) return {float(rng.uniform() * 3 - 1), float(rng.uniform() * 3 - 1), float(rng.uniform() * 3 - 1)};
    const float far = kind == 8 ? 20.0f : 1000.0f;
    return {far * float(rng.uniform() - 0.5), far * float(rng.uniform() - 0.5), far * float(rng.uniform() - 0.5)};
}

void check_same_state(const VertexGrid& grid, const Reference& ref, std::uint32_t id) {
    REQUIRE(grid.size() == ref.ids.size());
    REQUIRE(grid.contains(id) == ref.contains(id));
    if (ref.contains(id)) REQUIRE(grid.position(id) == ref.position[id]);
}

// One random run: inserts (with id reuse), moves (small and large), removes and queries, every
// answer checked against the reference.
void run_random_sequence(Shape shape, std::uint64_t seed, int steps, std::uint32_t max_vertices) {
    Random rng(seed);
    VertexGrid grid(unit_cube());
    Reference ref;
    std::vector<std::uint32_t> free_ids;
    std::uint32_t next_id = 0;
    for (int step = 0; step < steps; ++step) {
        const std::uint32_t op = rng.below(100);
        const bool grow = ref.ids.size() < 4 || (op < 30 && ref.ids.size() < max_vertices);
        if (grow) {
            std::uint32_t id;
            if (!free_ids.empty() && rng.below(2) == 0) {
                id = free_ids.back();
                free_ids.pop_back();
            } else {
                id = next_id++;
            }
            const Vec3 p = random_point(rng, shape);
            grid.insert(id, p);
            ref.insert(id, p);
            check_same_state(grid, ref, id);
        } else if (op < 45) {
            const std::uint32_t id = ref.ids[rng.below(std::uint32_t(ref.ids.size()))];
            grid.remove(id);
            ref.remove(id);
            free_ids.push_back(id);
            check_same_state(grid, ref, id);
        } else if (op < 75) {
            const std::uint32_t id = ref.ids[rng.below(std::uint32_t(ref.ids.size()))];
            // Half the moves are learning-sized nudges (mostly within a cell), half are jumps.
            Vec3 p = random_point(rng, shape);
            if (rng.below(2) == 0) p = ref.position[id] + (p - ref.position[id]) * 0.01f;
            grid.move(id, p);
            ref.position[id] = p;
            check_same_state(grid, ref, id);
        } else {
            const Vec3 q = random_query(rng, shape);
            const std::uint32_t expected = ref.nearest(q);
            const std::uint32_t got = grid.nearest(q);
            if (got != expected) {
                INFO("query " << q.x << " " << q.y << " " << q.z << " step " << step << " size " << ref.ids.size());
                REQUIRE(got == expected);
            }
        }
    }
}

}  // namespace

TEST_CASE("VertexGrid: an empty grid answers kNone, and a single vertex answers every query") {
    VertexGrid grid(unit_cube());
    CHECK(grid.size() == 0);
    CHECK(grid.nearest({0.5f, 0.5f, 0.5f}) == kNone);
    CHECK_FALSE(grid.contains(0));
    grid.insert(7, {0.25f, 0.5f, 0.75f});
    CHECK(grid.contains(7));
    CHECK_FALSE(grid.contains(6));
    CHECK(grid.position(7) == Vec3{0.25f, 0.5f, 0.75f});
    CHECK(grid.nearest({0.9f, 0.1f, 0.3f}) == 7);
    CHECK(grid.nearest({1e6f, -1e6f, 3e5f}) == 7);  // far outside the domain
    grid.remove(7);
    CHECK(grid.nearest({0.5f, 0.5f, 0.5f}) == kNone);
    CHECK_FALSE(grid.contains(7));
}

TEST_CASE("VertexGrid: equal distances go to the smaller id") {
    VertexGrid grid(unit_cube());
    // Ids 5 and 3 share a position; ids 9 and 1 are symmetric about the query.
    grid.insert(5, {0.5f, 0.5f, 0.5f});
    grid.insert(3, {0.5f, 0.5f, 0.5f});
    CHECK(grid.nearest({0.5f, 0.5f, 0.6f}) == 3);
    grid.insert(9, {0.0f, 0.5f, 0.5f});
    grid.insert(1, {1.0f, 0.5f, 0.5f});
    grid.remove(3);
    grid.remove(5);
    CHECK(grid.nearest({0.5f, 0.5f, 0.5f}) == 1);
    grid.move(1, {0.0f, 0.5f, 0.5f});  // now 1 and 9 coincide
    CHECK(grid.nearest({0.1f, 0.5f, 0.5f}) == 1);

    // A tie across a cell face: with few vertices the cells of a unit-cube domain are unit cubes
    // with faces at 0.5 + k, so vertex 2 sits on the face of the cell next to the query's, exactly
    // as far as vertex 5 in the query's own cell. The neighbour must still be visited.
    VertexGrid faces(unit_cube());
    faces.insert(5, {0.0f, 0.0f, 0.0f});
    faces.insert(2, {0.5f, 0.0f, 0.0f});
    CHECK(faces.nearest({0.25f, 0.0f, 0.0f}) == 2);
    CHECK(faces.nearest({0.25f, 0.0f, 1e-7f}) == 2);
}

TEST_CASE("VertexGrid: vertices and queries on cell faces and at the ring-2 distance, still exact") {
    // The query prunes neighbour cells, and stops after ring 1, on lower bounds computed from the
    // cell faces. Here those bounds are as tight as they get: a plane of vertices on a lattice of
    // half a cell, lying on cell faces (the domain centre 0.5 is a face), queried on faces, a hair
    // to either side of them, halfway between lattice points (many equal distances), and about one
    // cell above the plane (the nearest vertex then lies at the ring-2 bound).
    VertexGrid grid(unit_cube());
    Reference ref;
    Random rng(23);
    std::uint32_t id = 0;
    for (; id < 2000; ++id) {  // a plane of random vertices sets the cell size
        const Vec3 p{float(rng.uniform()), float(rng.uniform()), 0.5f};
        grid.insert(id, p);
        ref.insert(id, p);
    }
    const double h = grid.cell_size();
    const std::size_t rebuilds = grid.rebuild_count();
    const int side = int(0.5 / (h / 2.0));
    id = 0;
    for (int i = -side; i < side && id < 2000; ++i) {
        for (int j = -side; j < side && id < 2000; ++j, ++id) {
            const Vec3 p{float(0.5 + i * h / 2.0), float(0.5 + j * h / 2.0), 0.5f};
            grid.move(id, p);
            ref.position[id] = p;
        }
    }
    const float offsets[] = {0.0f, 1e-7f, -1e-7f, float(h / 4.0), float(h / 2.0)};
    const float heights[] = {0.0f, 1e-7f, float(h / 2.0), float(h), float(h * (1.0 - 1e-6)), float(h * (1.0 + 1e-6))};
    for (int k = 0; k < 3000; ++k) {
        const Vec3 base = ref.position[rng.below(id)];
        const Vec3 q{base.x + offsets[rng.below(5)], base.y + offsets[rng.below(5)],
                     base.z + (rng.below(2) ? 1.0f : -1.0f) * heights[rng.below(6)]};
        REQUIRE(grid.nearest(q) == ref.nearest(q));
    }
    CHECK(grid.cell_size() == h);  // the lattice kept the cells the queries were built for
    CHECK(grid.rebuild_count() == rebuilds);

    // The stop after ring 1: a query just inside the lower x face of its cell, a little more than
    // a cell above the plane (the plane is in ring 1, at distance d), and one more vertex at the
    // query's height, a little more than a cell away along -x: in ring 2, yet nearer than d.
    // The extra vertex takes an id none of the 2000 has (the lattice may have moved fewer).
    const double e = h * 1e-4;
    const std::uint32_t extra = 2000;
    for (int k = 0; k < 50; ++k) {
        const Vec3 below = ref.position[rng.below(id)];  // a lattice vertex: on x and z faces
        const Vec3 q{float(below.x + e), below.y, float(below.z + h + 10.0 * e)};
        const Vec3 side{float(q.x - h - e), q.y, q.z};
        REQUIRE_FALSE(grid.contains(extra));
        grid.insert(extra, side);
        ref.insert(extra, side);
        REQUIRE(ref.nearest(q) == extra);
        REQUIRE(grid.nearest(q) == extra);
        grid.remove(extra);
        ref.remove(extra);
    }
}

TEST_CASE("VertexGrid: vertices and queries far outside the domain, still exact") {
    Random rng(11);
    auto far_point = [&](double max_scale) {
        const float scale = float(std::pow(10.0, rng.uniform() * std::log10(max_scale)));
        return Vec3{scale * float(rng.uniform() - 0.5), scale * float(rng.uniform() - 0.5),
                    scale * float(rng.uniform() - 0.5)};
    };
    SUBCASE("four vertices, far apart") {
        // Their cells are far apart: the shells would have to cross most of the grid.
        VertexGrid grid(unit_cube());
        Reference ref;
        const Vec3 points[] = {{0.5f, 0.5f, 0.5f}, {1e5f, 0.0f, 0.0f}, {-3e4f, 2e4f, -1e5f}, {0.5f, 0.5f, 40.0f}};
        for (std::uint32_t i = 0; i < 4; ++i) {
            grid.insert(i, points[i]);
            ref.insert(i, points[i]);
        }
        for (int i = 0; i < 2000; ++i) {
            const Vec3 q = far_point(1e6);
            REQUIRE(grid.nearest(q) == ref.nearest(q));
        }
    }
    SUBCASE("a fine grid on a sphere, plus vertices clamped into its outermost cells") {
        // 3000 vertices make the cells small (about 0.03), so the 2^21 cells per axis end at about
        // 3e4: the far vertices share the outermost cells, which extend to infinity.
        VertexGrid grid(unit_cube());
        Reference ref;
        std::uint32_t id = 0;
        for (; id < 3000; ++id) {
            const Vec3 p = random_point(rng, Shape::sphere);
            grid.insert(id, p);
            ref.insert(id, p);
        }
        for (; id < 3012; ++id) {
            const Vec3 p = far_point(1e8);
            grid.insert(id, p);
            ref.insert(id, p);
        }
        for (int i = 0; i < 3000; ++i) {
            const Vec3 q = i % 3 == 0 ? random_query(rng, Shape::sphere) : far_point(1e9);
            REQUIRE(grid.nearest(q) == ref.nearest(q));
            if (i % 10 == 0) {  // move a far vertex somewhere else far away
                const std::uint32_t m = 3000 + rng.below(12);
                const Vec3 p = far_point(1e8);
                grid.move(m, p);
                ref.position[m] = p;
            }
        }
    }
}

TEST_CASE("VertexGrid: heavy cell churn keeps the cell table consistent") {
    // Vertices jump between random points of a region 100 domain widths across, so each is alone
    // in its cell: every move erases a cell and creates one, and the table's probe runs (including
    // those that wrap around the end of the table, frequent with few vertices) are rearranged.
    for (std::uint32_t n : {12u, 200u, 3000u}) {
        CAPTURE(n);
        Random rng(5 + n);
        VertexGrid grid(unit_cube());
        Reference ref;
        auto jump = [&] {
            return Vec3{float(rng.uniform() * 100 - 50), float(rng.uniform() * 100 - 50),
                        float(rng.uniform() * 100 - 50)};
        };
        for (std::uint32_t id = 0; id < n; ++id) {
            const Vec3 p = random_point(rng, Shape::cube);
            grid.insert(id, p);
            ref.insert(id, p);
        }
        const int moves = n < 100 ? 40000 : 8000;
        for (int i = 0; i < moves; ++i) {
            const std::uint32_t id = rng.below(n);
            const Vec3 p = jump();
            grid.move(id, p);
            ref.position[id] = p;
            const Vec3 q = jump();
            REQUIRE(grid.nearest(q) == ref.nearest(q));
        }
        for (std::uint32_t id = 0; id < n; ++id) REQUIRE(grid.position(id) == ref.position[id]);
    }
}

TEST_CASE("VertexGrid: random operations agree with a brute-force reference") {
    const Shape shapes[] = {Shape::cube, Shape::sphere, Shape::clusters, Shape::grid_points};
    const char* names[] = {"cube", "sphere", "clusters", "lattice"};
    for (int s = 0; s < 4; ++s) {
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            CAPTURE(names[s]);
            CAPTURE(seed);
            run_random_sequence(shapes[s], seed, 6000, 600);
        }
    }
}

TEST_CASE("VertexGrid: growth from 4 to 50k vertices and back re-buckets both ways") {
    Random rng(2024);
    VertexGrid grid(unit_cube());
    Reference ref;
    constexpr std::uint32_t kPeak = 50000;
    std::vector<double> sizes;  // cell size after each growth step
    auto check_queries = [&](int count) {
        for (int i = 0; i < count; ++i) {
            const Vec3 q = random_query(rng, Shape::sphere);
            REQUIRE(grid.nearest(q) == ref.nearest(q));
        }
    };
    for (std::uint32_t id = 0; id < kPeak; ++id) {
        const Vec3 p = random_point(rng, Shape::sphere);
        grid.insert(id, p);
        ref.insert(id, p);
        // A move per insert, like the learning loop's neighbourhood updates.
        const std::uint32_t m = ref.ids[rng.below(std::uint32_t(ref.ids.size()))];
        const Vec3 target = random_point(rng, Shape::sphere);
        const Vec3 moved = ref.position[m] + (target - ref.position[m]) * 0.002f;
        grid.move(m, moved);
        ref.position[m] = moved;
        if ((id & (id + 1)) == 0) {  // at sizes 2^k: record the cell size, check a few queries
            sizes.push_back(grid.cell_size());
            check_queries(16);
        }
        if (id % 997 == 0) check_queries(2);
    }
    const double peak_cell = grid.cell_size();
    const std::size_t rebuilds_up = grid.rebuild_count();
    // From 4 to 50k the count doubles 13 times; each doubling must have rebuilt the grid, and on
    // a sphere the cell size shrinks about as 1/sqrt(n): by about 100x over the growth.
    CHECK(rebuilds_up >= 13);
    CHECK(sizes[2] > 20 * peak_cell);
    for (std::uint32_t id = 0; id < kPeak; ++id) REQUIRE(grid.position(id) == ref.position[id]);

    // Back down to 4 vertices, removing in random order.
    while (ref.ids.size() > 4) {
        const std::uint32_t id = ref.ids[rng.below(std::uint32_t(ref.ids.size()))];
        grid.remove(id);
        ref.remove(id);
        REQUIRE(grid.size() == ref.ids.size());
        if (ref.ids.size() % 1009 == 0 || ref.ids.size() < 64) check_queries(2);
    }
    CHECK(grid.rebuild_count() >= rebuilds_up + 13);
    CHECK(grid.cell_size() > 20 * peak_cell);
    check_queries(500);
    for (std::uint32_t id : ref.ids) CHECK(grid.position(id) == ref.position[id]);
}

TEST_CASE("VertexGrid: vertices gathering or spreading at a constant count resize the cells") {
    // 4000 vertices on the unit-diameter sphere move onto a sphere ten times smaller, then back
    // out: the cells must follow (else a query would scan a hundred vertices per cell).
    Random rng(77);
    VertexGrid grid(unit_cube());
    Reference ref;
    constexpr std::uint32_t kCount = 4000;
    for (std::uint32_t id = 0; id < kCount; ++id) {
        const Vec3 p = random_point(rng, Shape::sphere);
        grid.insert(id, p);
        ref.insert(id, p);
    }
    const double sphere_cell = grid.cell_size();
    const std::size_t rebuilds = grid.rebuild_count();
    const Vec3 centre{0.5f, 0.5f, 0.5f};
    auto relocate = [&](float scale) {
        for (int round = 0; round < 3; ++round) {
            for (std::uint32_t id = 0; id < kCount; ++id) {
                const Vec3 p = centre + (random_point(rng, Shape::sphere) - centre) * scale;
                grid.move(id, p);
                ref.position[id] = p;
            }
            for (int i = 0; i < 200; ++i) {
                const Vec3 q = centre + (random_query(rng, Shape::sphere) - centre) * scale;
                REQUIRE(grid.nearest(q) == ref.nearest(q));
            }
        }
    };
    relocate(0.1f);
    CHECK(grid.rebuild_count() > rebuilds);
    const double small_cell = grid.cell_size();
    INFO("cell size on the sphere " << sphere_cell << ", on the small sphere " << small_cell);
    CHECK(small_cell < sphere_cell / 4);
    relocate(1.0f);
    INFO("cell size back on the sphere " << grid.cell_size());
    CHECK(grid.cell_size() > sphere_cell / 3);
    CHECK(grid.cell_size() < sphere_cell * 3);
}

TEST_CASE("VertexGrid: ids far beyond the current size, and reserve, behave like any other") {
    VertexGrid grid(unit_cube());
    grid.reserve(1000);
    grid.insert(999, {0.1f, 0.1f, 0.1f});
    grid.insert(100000, {0.9f, 0.9f, 0.9f});
    CHECK(grid.nearest({0.0f, 0.0f, 0.0f}) == 999);
    CHECK(grid.nearest({1.0f, 1.0f, 1.0f}) == 100000);
    CHECK_FALSE(grid.contains(500));
    CHECK_FALSE(grid.contains(4000000000u));
}

TEST_CASE("VertexGrid: rejects an empty or non-finite domain, accepts a single point") {
    CHECK(nmesh::test::refused_parameter([] { VertexGrid(BoundingBox{}); }) == "domain");
    BoundingBox inf_box;
    inf_box.extend({0.0f, 0.0f, 0.0f});
    inf_box.extend({INFINITY, 1.0f, 1.0f});
    CHECK(nmesh::test::refused_parameter([&] { VertexGrid{inf_box}; }) == "domain");
    BoundingBox point;
    point.extend({2.0f, 3.0f, 4.0f});
    VertexGrid grid(point);
    grid.insert(0, {2.0f, 3.0f, 4.0f});
    grid.insert(1, {2.5f, 3.0f, 4.0f});
    CHECK(grid.nearest({2.4f, 3.0f, 4.0f}) == 1);
}
