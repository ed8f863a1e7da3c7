// Threads (Parameters::threads): the parallel helper's chunks, its exceptions and its inline
// single thread; the parameter's range; the output check's counts for any thread count.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cloud_fixtures.h"
#include "mesh_fixtures.h"
#include "nmesh/error.h"
#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/geometry/triangle_intersection.h"
#include "nmesh/mesh/orientation.h"
#include "nmesh/reconstruct.h"
#include "nmesh/util/parallel.h"

using namespace nmesh;
using nmesh::test::icosphere;
using nmesh::test::sphere_cloud;

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
