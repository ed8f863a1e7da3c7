// nmesh/point_span.h — a read-only view of points stored contiguously, without a copy: a
// PointCloud's, a std::vector<Vec3>'s, or an array of float triples the caller owns.
#pragma once

#include <cstddef>
#include <vector>

#include "nmesh/vec3.h"

namespace nmesh {

class PointSpan {
public:
    constexpr PointSpan() = default;
    constexpr PointSpan(const Vec3* data, std::size_t size) : data_(data), size_(size) {}
    PointSpan(const std::vector<Vec3>& points)
        : data_(points.data()), size_(points.size()) {}  // NOLINT: implicit by design

    constexpr const Vec3* data() const { return data_; }
    constexpr std::size_t size() const { return size_; }
    constexpr bool empty() const { return size_ == 0; }
    constexpr const Vec3& operator[](std::size_t i) const { return data_[i]; }
    constexpr const Vec3* begin() const { return data_; }
    constexpr const Vec3* end() const { return data_ + size_; }

private:
    const Vec3* data_ = nullptr;
    std::size_t size_ = 0;
};

}  // namespace nmesh
