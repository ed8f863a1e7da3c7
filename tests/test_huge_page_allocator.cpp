// The allocator behind the nearest-point index's large arrays: small and large blocks hold what
// is written to them, through growth and copies; large blocks are aligned to the 2 MiB page on
// Linux (where they are marked for huge pages), and the allocator refuses sizes it cannot hold.
#include <doctest/doctest.h>

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "nmesh/util/huge_page_allocator.h"

using nmesh::HugePageAllocator;

namespace {

template <class T>
using Array = std::vector<T, HugePageAllocator<T>>;

std::uint32_t pattern(std::size_t i) { return std::uint32_t(i * 2654435761u + 7u); }

}  // namespace

TEST_CASE("HugePageAllocator keeps what is written, small and large, through growth and copies") {
    constexpr std::size_t kLargeCount = HugePageAllocator<std::uint32_t>::kMinBytes / sizeof(std::uint32_t);
    for (const std::size_t n : {std::size_t(1), std::size_t(1000), kLargeCount - 1, kLargeCount, 3 * kLargeCount + 5}) {
        INFO("elements " << n);
        Array<std::uint32_t> a(n);
        for (std::size_t i = 0; i < n; ++i) a[i] = pattern(i);
        const Array<std::uint32_t> copy = a;  // a block of the same size class
        a.push_back(1);                       // growth: a new block, the old one released
        a.resize(2 * n + 3, 5);
        bool same = copy.size() == n;
        for (std::size_t i = 0; i < n; ++i) same = same && a[i] == pattern(i) && copy[i] == pattern(i);
        CHECK(same);
        CHECK(a[n] == 1);
        CHECK(a.back() == 5);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        if (a.capacity() * sizeof(std::uint32_t) >= HugePageAllocator<std::uint32_t>::kMinBytes)
            CHECK(reinterpret_cast<std::uintptr_t>(a.data()) % HugePageAllocator<std::uint32_t>::kPageBytes == 0);
#endif
    }
}

TEST_CASE("HugePageAllocator aligns over-aligned types, small and large blocks alike") {
    struct alignas(64) Line {
        std::uint32_t words[16];
    };
    for (const std::size_t n : {std::size_t(1), std::size_t(3), std::size_t(100000)}) {
        INFO("lines " << n);
        Array<Line> lines(n);
        CHECK(reinterpret_cast<std::uintptr_t>(lines.data()) % 64 == 0);
        for (std::size_t i = 0; i < n; ++i) lines[i].words[15] = pattern(i);
        bool same = true;
        for (std::size_t i = 0; i < n; ++i) same = same && lines[i].words[15] == pattern(i);
        CHECK(same);
    }
}

TEST_CASE("HugePageAllocator refuses a size that cannot be held") {
    HugePageAllocator<std::uint64_t> alloc;
    CHECK_THROWS_AS((void)alloc.allocate(std::size_t(-1) / 4), std::bad_array_new_length);
    CHECK(alloc == HugePageAllocator<char>());
    CHECK_FALSE(alloc != HugePageAllocator<char>());
}
