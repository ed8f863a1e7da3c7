// nmesh/simd.h — whether the hot loops use SSE2 intrinsics and GCC/Clang vector types.
//
// Every such path has a plain C++ twin that computes the same bits (the same operations in the
// same order, lane by lane). Defining NMESH_NO_SIMD (-DNMESH_NO_SIMD=1 in CMAKE_CXX_FLAGS) selects
// the twins everywhere, so that they are built and tested on any machine; CI checks that both
// give the same mesh. Set it for the library and for code that includes its headers alike.
#pragma once

#if (defined(__GNUC__) || defined(__clang__)) && !defined(NMESH_NO_SIMD)
#define NMESH_VECTOR_TYPES 1  // __attribute__((vector_size)), __builtin_shuffle / shufflevector
#else
#define NMESH_VECTOR_TYPES 0
#endif

#if NMESH_VECTOR_TYPES && defined(__SSE2__)
#define NMESH_SSE2 1  // <emmintrin.h> intrinsics, __builtin_ctz
#include <emmintrin.h>
#else
#define NMESH_SSE2 0
#endif
