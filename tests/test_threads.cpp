// Threads (Parameters::threads, EvalOptions::threads): the parallel helper's chunks, its
// exceptions and its inline single thread; and the same meshes, statistics and metrics, bit for
// bit, for every thread count.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cloud_fixtures.h"
#include "mesh_fixtures.h"
#include "nmesh/error.h"
#include "nmesh/finish/defect_tracker.h"
#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/learn/sample_sides.h"
#include "nmesh/learn/solid_start.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/metrics.h"
#include "nmesh/reconstruct.h"
#include "nmesh/util/parallel.h"

using namespace nmesh;
using nmesh::test::bundled_bunny;
using nmesh::test::icosphere;
using nmesh::test::sphere_cloud;
using nmesh::test::torus_cloud;

namespace {

// Whether two floats have the same bits (NaN included).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_mesh(const IndexedMesh& a, const IndexedMesh& b) {
    return a.positions.size() == b.positions.size() && a.triangles == b.triangles &&
           (a.positions.empty() ||
            std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(Vec3)) == 0);
}

// The statistics' counts (not the seconds) of two runs agree.
void check_same_counts(const Statistics& a, const Statistics& b) {
    CHECK(a.iterations == b.iterations);
    CHECK(a.settle_iterations == b.settle_iterations);
    CHECK(a.splits == b.splits);
    CHECK(a.collapses == b.collapses);
    CHECK(a.collapses_refused == b.collapses_refused);
    CHECK(a.swaps_tried == b.swaps_tried);
    CHECK(a.swaps_kept == b.swaps_kept);
    CHECK(a.side_skips == b.side_skips);
    CHECK(a.twist_checks == b.twist_checks);
    CHECK(a.twist_retries == b.twist_retries);
    CHECK(a.output_retries == b.output_retries);
    CHECK(a.start_retries == b.start_retries);
    CHECK(a.start_vertices == b.start_vertices);
    CHECK(a.solid_genus == b.solid_genus);
    CHECK(a.start_core == b.start_core);
    CHECK(a.handles == b.handles);
    CHECK(a.bridges == b.bridges);
    CHECK(a.open_faces_removed == b.open_faces_removed);
    CHECK(a.open_vertices_added == b.open_vertices_added);
    CHECK(a.finished == b.finished);
    CHECK(a.reoriented == b.reoriented);
    CHECK(a.genus == b.genus);
    CHECK(a.boundary_loops == b.boundary_loops);
    CHECK(a.crossing_pairs == b.crossing_pairs);
    CHECK(a.inward_faces == b.inward_faces);
}

// write_json at full precision: every field of the report, each double to its last bit.
std::string report_text(const QualityReport& q) {
    std::ostringstream out;
    out.precision(17);
    write_json(out, q);
    return out.str();
}

}  // namespace

TEST_CASE("for_chunks calls each fixed chunk once, whatever the thread count") {
    for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(1000), std::size_t(1001)})
        for (const std::size_t chunk : {std::size_t(1), std::size_t(3), std::size_t(64), std::size_t(5000)})
            for (const std::uint32_t threads : {1u, 2u, 4u, 0u}) {
                std::vector<int> calls(n, 0);
                std::mutex mutex;
                std::set<std::pair<std::size_t, std::size_t>> chunks;
                for_chunks(n, chunk, threads, [&](std::size_t begin, std::size_t end) {
                    for (std::size_t i = begin; i < end; ++i) ++calls[i];  // disjoint chunks: no race
                    const std::lock_guard<std::mutex> lock(mutex);
                    chunks.insert({begin, end});
                });
                CHECK(std::all_of(calls.begin(), calls.end(), [](int c) { return c == 1; }));
                // The chunks are [k chunk, min(n, (k + 1) chunk)): fixed by n and chunk alone.
                std::set<std::pair<std::size_t, std::size_t>> expected;
                for (std::size_t b = 0; b < n; b += chunk) expected.insert({b, std::min(n, b + chunk)});
                CHECK(chunks == expected);
            }
    // A chunk of 0 is a chunk of 1.
    std::atomic<int> count{0};
    for_chunks(5, 0, 2, [&](std::size_t begin, std::size_t end) { count += int(end - begin == 1); });
    CHECK(count == 5);
}

TEST_CASE("one thread runs the chunks inline, in order, on the caller's thread") {
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<std::size_t> order;
    bool inline_only = true;
    for_chunks(100, 7, 1, [&](std::size_t begin, std::size_t) {
        inline_only = inline_only && std::this_thread::get_id() == caller;
        order.push_back(begin);
    });
    CHECK(inline_only);
    CHECK(std::is_sorted(order.begin(), order.end()));
    CHECK(order.size() == 15);
    // One chunk needs no other thread either.
    bool one_inline = false;
    for_chunks(5, 10, 8, [&](std::size_t, std::size_t) { one_inline = std::this_thread::get_id() == caller; });
    CHECK(one_inline);
}

TEST_CASE("several threads do run at once") {
    // Four chunks that each wait for all four to have started: they finish only if four threads
    // run them side by side (the wait is bounded, so that a failure cannot hang the suite).
    std::atomic<int> started{0};
    std::atomic<int> saw_all{0};
    for_chunks(4, 1, 4, [&](std::size_t, std::size_t) {
        ++started;
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (started.load() < 4 && std::chrono::steady_clock::now() < until) std::this_thread::yield();
        saw_all += started.load() == 4;
    });
    CHECK(saw_all == 4);
}

TEST_CASE("an exception in a chunk reaches the caller: the first chunk's, as one thread would throw it") {
    for (const std::uint32_t threads : {1u, 2u, 4u}) {
        CHECK_THROWS_WITH_AS(for_chunks(1000, 10, threads,
                                        [](std::size_t begin, std::size_t) {
                                            if (begin == 500) throw std::runtime_error("chunk 50");
                                        }),
                             "chunk 50", std::runtime_error);
        // Several chunks throw: the smallest one's exception, for any thread count.
        CHECK_THROWS_WITH_AS(for_chunks(1000, 10, threads,
                                        [](std::size_t begin, std::size_t) {
                                            if (begin >= 300 && begin % 100 == 0)
                                                throw std::runtime_error("chunk " + std::to_string(begin / 10));
                                        }),
                             "chunk 30", std::runtime_error);
        // Every thread is joined before it is rethrown: the work is over when the caller sees it.
        std::atomic<int> running{0};
        std::atomic<int> after{0};
        try {
            for_chunks(64, 1, threads, [&](std::size_t begin, std::size_t) {
                ++running;
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
                if (begin == 3) {
                    --running;
                    throw std::logic_error("three");
                }
                --running;
            });
        } catch (const std::logic_error&) {
            after = running.load();
        }
        CHECK(after == 0);
    }
}

TEST_CASE("resolve_threads: 0 is the machine's cores, a count itself, at most kMaxThreads") {
    CHECK(resolve_threads(0) >= 1);
    CHECK(resolve_threads(0) <= kMaxThreads);
    CHECK(resolve_threads(1) == 1);
    CHECK(resolve_threads(3) == 3);
    CHECK(resolve_threads(kMaxThreads + 1) == kMaxThreads);
}

TEST_CASE("threads out of range are refused, naming the parameter") {
    const PointCloud cloud = sphere_cloud(100);
    Parameters p;
    p.threads = kMaxThreads + 1;
    CHECK_THROWS_WITH_AS(reconstruct(cloud, p), doctest::Contains("invalid parameter threads: "), ParameterError);
    try {
        p.validate();
    } catch (const ParameterError& e) {
        CHECK(e.parameter() == std::string("threads"));
    }
    p.threads = kMaxThreads;
    CHECK_NOTHROW(p.validate());
    EvalOptions options;
    options.threads = kMaxThreads + 1;
    const IndexedMesh sphere = icosphere(1);
    CHECK_THROWS_AS(evaluate(sphere.positions, sphere, options), ParameterError);
}

TEST_CASE("the bunny and a sphere: the same mesh and statistics for 1, 2 and 4 threads, closed and open") {
    const PointCloud bunny = bundled_bunny();
    REQUIRE(bunny.size() == 35947);
    const PointCloud sphere = sphere_cloud(6000);
    struct Case {
        const PointCloud* cloud;
        std::uint32_t vertices;
        Topology topology;
    };
    for (const Case& c : {Case{&bunny, 1000, Topology::closed}, Case{&bunny, 1000, Topology::open},
                          Case{&sphere, 800, Topology::closed}, Case{&sphere, 800, Topology::open}}) {
        Parameters p;
        p.target_vertices = c.vertices;
        p.topology = c.topology;
        p.threads = 1;
        const Result one = reconstruct(*c.cloud, p);
        REQUIRE(!one.mesh.triangles.empty());
        if (c.cloud == &bunny) CHECK(one.stats.solid_genus == 0);  // the solid was read
        for (const std::uint32_t threads : {2u, 4u}) {
            CAPTURE(threads);
            CAPTURE(topology_name(c.topology));
            p.threads = threads;
            const Result more = reconstruct(*c.cloud, p);
            CHECK(same_mesh(one.mesh, more.mesh));
            check_same_counts(one.stats, more.stats);
        }
    }
}

TEST_CASE("evaluate gives the same report, bit for bit, for 1, 2 and 4 threads") {
    // More points and samples than one block of the measuring (65,536), so that the sums run over
    // several blocks; a mesh with crossing pairs and inward faces, so that both counts are at work.
    // The cloud samples both spheres of the mesh (the surface-to-cloud maximum's search stays short).
    PointCloud cloud = sphere_cloud(40000);
    for (const Vec3& v : sphere_cloud(30000, 0.9f, {0.27f, 0.0f, 0.0f}).points) cloud.points.push_back(v);
    IndexedMesh mesh = icosphere(4);
    const IndexedMesh inner = icosphere(3, {0.3f, 0.0f, 0.0f});
    const std::uint32_t offset = std::uint32_t(mesh.positions.size());
    for (const Vec3& v : inner.positions) mesh.positions.push_back(v * 0.9f);
    for (const auto& t : inner.triangles) mesh.triangles.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
    EvalOptions options;
    options.threads = 1;
    const QualityReport one = evaluate(cloud.points, mesh, options);
    CHECK(one.self_intersections > 0);
    for (const std::uint32_t threads : {2u, 4u}) {
        CAPTURE(threads);
        options.threads = threads;
        const QualityReport more = evaluate(cloud.points, mesh, options);
        CHECK(report_text(more) == report_text(one));
        CHECK(same_bits(more.p2s_mean, one.p2s_mean));
        CHECK(same_bits(more.p2s_rms, one.p2s_rms));
        CHECK(same_bits(more.dm_x_t, one.dm_x_t));
        CHECK(same_bits(more.s2p_mean, one.s2p_mean));
        CHECK(same_bits(more.hausdorff, one.hausdorff));
        CHECK(more.self_intersections == one.self_intersections);
    }
    // The learnt bunny, closed: its inward faces counted on the threads as well.
    Parameters p;
    p.target_vertices = 1000;
    const PointCloud bunny = bundled_bunny();
    const Result r = reconstruct(bunny, p);
    options.threads = 1;
    const QualityReport b1 = evaluate(bunny.points, r.mesh, options);
    options.threads = 3;
    CHECK(report_text(evaluate(bunny.points, r.mesh, options)) == report_text(b1));
}

TEST_CASE("the output check's counts and the inward flags are the same for any thread count") {
    // An icosphere with half its faces reversed (inward faces) and a vertex pushed through the
    // opposite side (crossing pairs).
    IndexedMesh mesh = icosphere(4);
    for (auto& t : mesh.triangles)
        if (mesh.positions[t[0]].z > 0.5f) std::swap(t[1], t[2]);
    mesh.positions[0] = mesh.positions[0] * -1.5f;
    const TriangleBvh bvh(mesh);
    const std::vector<std::uint8_t> flags = inward_face_flags(mesh, bvh, 1);
    const std::size_t pairs = self_intersecting_pairs(mesh).size();
    CHECK(pairs > 0);
    CHECK(std::count(flags.begin(), flags.end(), std::uint8_t(1)) > 0);
    for (const std::uint32_t threads : {1u, 2u, 4u, 0u}) {
        CAPTURE(threads);
        CHECK(inward_face_flags(mesh, bvh, threads) == flags);
        CHECK(inward_faces(mesh, bvh, threads) == std::size_t(std::count(flags.begin(), flags.end(), std::uint8_t(1))));
        CHECK(count_self_intersections(mesh, threads) == pairs);
    }
}

TEST_CASE("the finishing stage's search for defects finds the same pairs and folds for any thread count") {
    // An icosphere whose vertices are moved by up to about an edge (0.038) each way: crossing
    // pairs and folds all over it, between small triangles (every bucket range of the grid has
    // some), and a vertex pushed through the opposite side (a triangle kept apart as large).
    IndexedMesh shape = icosphere(5);
    std::uint32_t state = 12345;
    const auto noise = [&] {
        state = state * 1664525u + 1013904223u;
        return (float(state >> 8) / float(1u << 24) - 0.5f) * 0.06f;
    };
    for (Vec3& v : shape.positions) v = v + Vec3(noise(), noise(), noise());
    shape.positions[0] = shape.positions[0] * -1.2f;
    Mesh mesh = Mesh::from_indexed(shape);
    const finish_detail::DefectTracker one(mesh, std::cos(2.0f), false, 1);
    CHECK(one.pairs().size() > 1000);
    // The pairs of the whole grid in one pass, as the search was before it was split.
    const std::vector<Face> faces = finish_detail::alive_faces(mesh);
    const finish_detail::FaceGrid grid(mesh, faces, finish_detail::grid_cell(mesh, faces));
    std::vector<std::pair<Face, Face>> all;
    grid.for_each_pair([&](Face f, Face g) {
        if (finish_detail::mesh_faces_intersect(mesh, f, g)) all.emplace_back(f, g);
    });
    finish_detail::sort_unique(all);
    CHECK(one.pairs() == all);
    CHECK(!one.folds().empty());
    for (const std::uint32_t threads : {2u, 4u, 0u}) {
        CAPTURE(threads);
        const finish_detail::DefectTracker more(mesh, std::cos(2.0f), false, threads);
        CHECK(more.pairs() == one.pairs());
        CHECK(more.folds() == one.folds());
    }
}

TEST_CASE("the solid's reading and the samples' sides are the same for any thread count") {
    // A torus (its grids' distance transforms shared among the threads) and the bunny (read from
    // its first grid alone).
    const PointCloud torus = torus_cloud(20000);
    const PointCloud bunny = bundled_bunny();
    for (const PointCloud* cloud : {&torus, &bunny}) {
        const BoundingBox box = cloud->bounds();
        const PointTransform transform{box.center(), float(1.0 / box.diagonal())};
        const SolidStart one = solid_start(PointSpan(cloud->points), transform, 2000, 1);
        const std::vector<Vec3> sides = sample_sides(PointSpan(cloud->points), transform, one.surface, one.reach, 1);
        if (cloud == &torus) {
            CHECK(one.solid_genus == 1);
            REQUIRE(one.mesh);
        }
        for (const std::uint32_t threads : {2u, 3u, 4u}) {
            CAPTURE(threads);
            const SolidStart more = solid_start(PointSpan(cloud->points), transform, 2000, threads);
            CHECK(more.solid_genus == one.solid_genus);
            CHECK(same_bits(more.reach, one.reach));
            CHECK(same_mesh(more.surface, one.surface));
            CHECK(more.mesh.has_value() == one.mesh.has_value());
            if (more.mesh && one.mesh) CHECK(same_mesh(more.mesh->to_indexed(), one.mesh->to_indexed()));
            const std::vector<Vec3> more_sides =
                sample_sides(PointSpan(cloud->points), transform, more.surface, more.reach, threads);
            REQUIRE(more_sides.size() == sides.size());
            CHECK((sides.empty() || std::memcmp(sides.data(), more_sides.data(), sides.size() * sizeof(Vec3)) == 0));
        }
    }
}
