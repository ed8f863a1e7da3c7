// nmesh/vec3.h — the 3-component float vector used for every position in nmesh.
//
// A plain 12-byte aggregate (no alignment padding), so arrays of points cost 12 bytes each and
// the public headers stay free of third-party types.
#pragma once

#include <cmath>

namespace nmesh {

struct Vec3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;

    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}

    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
    Vec3& operator+=(const Vec3& o) {
        x += o.x;
        y += o.y;
        z += o.z;
        return *this;
    }
    Vec3& operator-=(const Vec3& o) {
        x -= o.x;
        y -= o.y;
        z -= o.z;
        return *this;
    }
    Vec3& operator*=(float s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr bool operator==(const Vec3& o) const { return x == o.x && y == o.y && z == o.z; }
    constexpr bool operator!=(const Vec3& o) const { return !(*this == o); }
};

static_assert(sizeof(Vec3) == 12, "Vec3 must be three packed floats");

constexpr Vec3 operator*(float s, const Vec3& v) { return v * s; }
constexpr float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr float squared_norm(const Vec3& v) { return dot(v, v); }
inline float norm(const Vec3& v) { return std::sqrt(squared_norm(v)); }
constexpr float squared_distance(const Vec3& a, const Vec3& b) { return squared_norm(a - b); }
inline float distance(const Vec3& a, const Vec3& b) { return std::sqrt(squared_distance(a, b)); }
// Whether every coordinate is finite (no NaN, no infinity).
inline bool is_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
// v / |v|, or the zero vector when |v| is 0 (no NaN escapes).
inline Vec3 normalized(const Vec3& v) {
    const float n = norm(v);
    return n > 0.0f ? v / n : Vec3{};
}
// Componentwise minimum and maximum. As std::fmin and std::fmax, a NaN component loses to a
// number (a box extended by a NaN point keeps its bounds), but written out so that they inline
// (the library calls behind std::fmin cost a bounding box of a large cloud several times over).
inline float min_ignoring_nan(float a, float b) { return (b < a || a != a) ? b : a; }
inline float max_ignoring_nan(float a, float b) { return (b > a || a != a) ? b : a; }
inline Vec3 min(const Vec3& a, const Vec3& b) {
    return {min_ignoring_nan(a.x, b.x), min_ignoring_nan(a.y, b.y), min_ignoring_nan(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
    return {max_ignoring_nan(a.x, b.x), max_ignoring_nan(a.y, b.y), max_ignoring_nan(a.z, b.z)};
}

}  // namespace nmesh
