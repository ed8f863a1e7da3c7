#include "nmesh/util/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace nmesh {

unsigned resolve_threads(std::uint32_t threads) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    return std::min(threads, kMaxThreads);
}

namespace parallel_detail {

void run_tasks(std::size_t count, unsigned threads, void (*task)(void*, std::size_t), void* context) {
    const std::size_t workers = std::min<std::size_t>(std::max(1u, threads), count);
    if (workers <= 1) {
        for (std::size_t k = 0; k < count; ++k) task(context, k);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex mutex;
    std::exception_ptr error;
    std::size_t error_at = count;
    const auto work = [&] {
        for (;;) {
            if (failed.load(std::memory_order_relaxed)) return;
            const std::size_t k = next.fetch_add(1, std::memory_order_relaxed);
            if (k >= count) return;
            try {
                task(context, k);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(mutex);
                if (k < error_at) error_at = k, error = std::current_exception();
                failed.store(true, std::memory_order_relaxed);
            }
        }
    };
    std::vector<std::thread> started;
    started.reserve(workers - 1);
    for (std::size_t i = 1; i < workers; ++i) {
        try {
            started.emplace_back(work);
        } catch (...) {
            break;  // no more threads to be had: those started and the caller do the work
        }
    }
    work();
    for (std::thread& t : started) t.join();
    if (error) std::rethrow_exception(error);
}

}  // namespace parallel_detail

}  // namespace nmesh
