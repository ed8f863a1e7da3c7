// nmesh/huge_page_allocator.h — an allocator for large arrays that asks Linux for 2 MiB pages.
//
// A fresh array of hundreds of megabytes (the nearest-point index of a 36-million-point cloud
// holds 576 MB) costs a page fault per 4 KiB page when it is first written, and its random reads
// miss the TLB. Transparent huge pages cut both by 512, but where the kernel gives them only on request
// (/sys/kernel/mm/transparent_hugepage/enabled set to "madvise", a common default), an array has
// to ask: this allocator aligns blocks of at least kMinBytes to 2 MiB and marks them with
// madvise(MADV_HUGEPAGE). Smaller blocks, and every block on other systems, come from operator
// new as with std::allocator (over-aligned types included). The request is a hint: where huge
// pages are unavailable the memory behaves as any other. A block's last huge page is resident
// as a whole once touched: up to 2 MiB more per large array than with 4 KiB pages.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace nmesh {

template <class T>
struct HugePageAllocator {
    using value_type = T;

    static constexpr std::size_t kPageBytes = std::size_t(1) << 21;
    static constexpr std::size_t kMinBytes = std::size_t(4) << 20;

    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T) - kPageBytes) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        if (bytes >= kMinBytes) {
            const std::size_t rounded = (bytes + kPageBytes - 1) / kPageBytes * kPageBytes;
            void* p = std::aligned_alloc(kPageBytes, rounded);
            if (p == nullptr) throw std::bad_alloc();
            (void)madvise(p, rounded, MADV_HUGEPAGE);  // a hint; failure leaves ordinary pages
            return static_cast<T*>(p);
        }
#endif
        if constexpr (alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__)
            return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
        else
            return static_cast<T*>(::operator new(bytes));
    }

    void deallocate(T* p, std::size_t n) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        if (n * sizeof(T) >= kMinBytes) {
            std::free(p);
            return;
        }
#endif
        if constexpr (alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__)
            ::operator delete(p, std::align_val_t(alignof(T)));
        else
            ::operator delete(p);
    }
};

// A std::vector whose large blocks are on huge pages.
template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

template <class T, class U>
bool operator==(const HugePageAllocator<T>&, const HugePageAllocator<U>&) noexcept {
    return true;
}
template <class T, class U>
bool operator!=(const HugePageAllocator<T>&, const HugePageAllocator<U>&) noexcept {
    return false;
}

}  // namespace nmesh
