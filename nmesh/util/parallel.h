// nmesh/util/parallel.h — independent work on several threads, with the same result on any number.
//
// Parameters::threads asks for a number of threads; the work that runs on them is independent
// per item (a face's test, a point's distance, one grid of the solid's reading), and whatever is
// combined from the items is combined in their order on the calling thread, never in the order
// the threads finish: the same input gives the same bits with 1 thread or 64.
//
// No pool: each call starts its threads (std::thread, tens of microseconds each) and joins them
// before it returns, so a call is worth making for work of a millisecond or more. One thread runs
// everything inline, on the caller's thread, and starts none.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace nmesh {

// The largest thread count Parameters::threads and EvalOptions::threads accept.
inline constexpr std::uint32_t kMaxThreads = 1024;

// The number of threads a count asks for: `threads` itself, or for 0 the machine's cores
// (std::thread::hardware_concurrency(), 1 when it does not say), at most kMaxThreads.
unsigned resolve_threads(std::uint32_t threads);

namespace parallel_detail {
// Calls task(context, k) once for every k in [0, count), on up to `threads` threads, the caller's
// among them (k handed out in increasing order). Every thread is joined before it returns. An
// exception from a task stops the handing out; the one from the smallest k is rethrown (the one a
// single thread would have thrown: every k below it was handed out, and finishes or throws).
// A thread that cannot be started leaves its share to the others.
void run_tasks(std::size_t count, unsigned threads, void (*task)(void*, std::size_t), void* context);
}  // namespace parallel_detail

// Calls f(begin, end) for each chunk [k * chunk, min(n, (k + 1) * chunk)) of [0, n), on up to
// `threads` threads (0: the machine's cores, as resolve_threads). The chunks are fixed by n and
// `chunk` alone, not by the thread count: a caller that keeps one result per chunk and combines
// them in chunk order gets the same result for every thread count. f must be safe to call from
// several threads at once on different chunks. chunk 0 is taken as 1.
template <class F>
void for_chunks(std::size_t n, std::size_t chunk, std::uint32_t threads, F&& f) {
    if (n == 0) return;
    if (chunk == 0) chunk = 1;
    const std::size_t count = (n - 1) / chunk + 1;
    struct Context {
        std::size_t n, chunk;
        std::remove_reference_t<F>* f;
    } context{n, chunk, &f};
    parallel_detail::run_tasks(
        count, resolve_threads(threads),
        [](void* c, std::size_t k) {
            const Context& x = *static_cast<const Context*>(c);
            const std::size_t begin = k * x.chunk;
            (*x.f)(begin, begin + x.chunk < x.n ? begin + x.chunk : x.n);
        },
        &context);
}

// Calls f(k) for each k in [0, n), each a task of its own, on up to `threads` threads.
template <class F>
void for_each_task(std::size_t n, std::uint32_t threads, F&& f) {
    for_chunks(n, 1, threads, [&](std::size_t begin, std::size_t) { f(begin); });
}

}  // namespace nmesh
