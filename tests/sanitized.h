// Whether the suite runs in the sanitizer build. CI's sanitizer build also runs the whole-mesh
// check after every topology operation, which makes a run to n vertices cost O(n^2): tests that
// learn many meshes run fewer or smaller ones there.
#pragma once

#if defined(NMESH_TEST_SANITIZED)
// Given on the command line: the sanitizer build's sizes in a plain build.
#elif defined(__SANITIZE_ADDRESS__)
#define NMESH_TEST_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define NMESH_TEST_SANITIZED 1
#endif
#endif

namespace nmesh::test {
#ifdef NMESH_TEST_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif
}  // namespace nmesh::test
