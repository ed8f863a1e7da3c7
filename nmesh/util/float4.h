// nmesh/float4.h — four float lanes (x, y, z and an unused one) for the learning loop's
// smoothing arithmetic: one SIMD instruction per operation where the compiler offers vector types
// (GCC, Clang), plain lanes elsewhere.
//
// Each lane computes exactly what the Vec3 operations compute, in the same order (a component of
// a cross product is still a.y * b.z - a.z * b.y), so the results are the same bits as with Vec3;
// only the instruction count falls. Internal to the library's .cpp files. Defining
// NMESH_NO_SIMD selects the plain lanes (nmesh/simd.h).
#pragma once

#include "nmesh/util/simd.h"
#include "nmesh/vec3.h"

namespace nmesh {
namespace float4 {

#if NMESH_VECTOR_TYPES
typedef float F4 __attribute__((vector_size(16)));
typedef int I4 __attribute__((vector_size(16)));
#if NMESH_SSE2
// x and y in one 8-byte load, z in a 4-byte one: three instructions where the element-wise
// initialiser below takes five (the smoothing step loads about 45 positions per iteration).
inline F4 load(const Vec3& p) {
    const __m128 xy = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&p.x)));
    return F4(_mm_movelh_ps(xy, _mm_load_ss(&p.z)));
}
#else
inline F4 load(const Vec3& p) { return F4{p.x, p.y, p.z, 0.0f}; }
#endif
// The lanes rotated: (y, z, x, w) and (z, x, y, w).
#if defined(__clang__)
inline F4 yzx(F4 a) { return __builtin_shufflevector(a, a, 1, 2, 0, 3); }
inline F4 zxy(F4 a) { return __builtin_shufflevector(a, a, 2, 0, 1, 3); }
#else
inline F4 yzx(F4 a) { return __builtin_shuffle(a, I4{1, 2, 0, 3}); }
inline F4 zxy(F4 a) { return __builtin_shuffle(a, I4{2, 0, 1, 3}); }
#endif
inline F4 cross(F4 a, F4 b) { return yzx(a) * zxy(b) - zxy(a) * yzx(b); }
// dot(a, c) and dot(b, c) at once: the lanes of a * c and b * c interleaved, so that each
// addition sums both, in dot()'s order ((x + y) + z): the same bits, 9 fewer instructions per
// smoothed vertex than two dot() calls.
inline void dot2(F4 a, F4 b, F4 c, float& ac, float& bc) {
    const F4 p = a * c, q = b * c;
#if defined(__clang__)
    const F4 xy = __builtin_shufflevector(p, q, 0, 4, 1, 5), z = __builtin_shufflevector(p, q, 2, 6, 3, 7);
    const F4 s = xy + __builtin_shufflevector(xy, xy, 2, 3, 2, 3) + z;
#else
    const F4 xy = __builtin_shuffle(p, q, I4{0, 4, 1, 5}), z = __builtin_shuffle(p, q, I4{2, 6, 3, 7});
    const F4 s = xy + __builtin_shuffle(xy, I4{2, 3, 2, 3}) + z;
#endif
    ac = s[0];
    bc = s[1];
}
#else
struct F4 {
    float v[4];
    float operator[](int i) const { return v[i]; }
};
inline F4 load(const Vec3& p) { return {{p.x, p.y, p.z, 0.0f}}; }
inline F4 operator+(F4 a, F4 b) { return {{a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2], 0.0f}}; }
inline F4 operator-(F4 a, F4 b) { return {{a.v[0] - b.v[0], a.v[1] - b.v[1], a.v[2] - b.v[2], 0.0f}}; }
inline F4 operator*(F4 a, float s) { return {{a.v[0] * s, a.v[1] * s, a.v[2] * s, 0.0f}}; }
inline F4 operator*(F4 a, F4 b) { return {{a.v[0] * b.v[0], a.v[1] * b.v[1], a.v[2] * b.v[2], 0.0f}}; }
inline F4 yzx(F4 a) { return {{a.v[1], a.v[2], a.v[0], 0.0f}}; }
inline F4 cross(F4 a, F4 b) {
    return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2], a.v[0] * b.v[1] - a.v[1] * b.v[0],
             0.0f}};
}
#endif
// cross(a, b) with its lanes in the order (z, x, y), from a, b and their rotations ra = yzx(a),
// rb = yzx(b): each lane is the same difference of the same two products as in cross(), so
// yzx(cross_zxy(a, ra, b, rb)) is cross(a, b) bit for bit, and yzx() of a sum of such terms is
// the same sum of cross products. A running sum over consecutive vectors thus rotates each vector
// once and the sum once, where cross() rotates both operands twice.
inline F4 cross_zxy(F4 a, F4 ra, F4 b, F4 rb) { return a * rb - ra * b; }
inline Vec3 to_vec3(F4 a) { return {a[0], a[1], a[2]}; }
inline float dot(F4 a, F4 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
#if !NMESH_VECTOR_TYPES
inline void dot2(F4 a, F4 b, F4 c, float& ac, float& bc) {
    ac = dot(a, c);
    bc = dot(b, c);
}
#endif

}  // namespace float4
}  // namespace nmesh
