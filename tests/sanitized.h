// Whether the suite runs in the sanitizer build. CI's sanitizer build also checks the mesh after
// every topology operation (mesh_check.h), and runs several times slower: tests that learn many
// meshes run fewer or smaller ones there.
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
