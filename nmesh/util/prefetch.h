// nmesh/prefetch.h — a portable software prefetch hint.
//
// The learning loop knows some of its memory accesses an iteration ahead (its random samples are
// drawn in advance); asking the cache for them early overlaps their latency with the current
// iteration's work. A hint only: it changes no result, and compiles to nothing where the compiler
// offers no prefetch built-in.
#pragma once

namespace nmesh {

inline void prefetch_for_read(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 0, 3);
#else
    (void)p;
#endif
}

}  // namespace nmesh
