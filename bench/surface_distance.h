// bench/surface_distance.h — the distance between two surfaces as the benchmarks measure it:
// samples drawn uniformly by area on one mesh (seeded), each sample's distance to the other mesh's
// nearest triangle. Used by corpus_sweep.cpp and mesh_distance.cpp, so that every table measures
// alike.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "nmesh/geometry/triangle_bvh.h"
#include "nmesh/indexed_mesh.h"
#include "nmesh/util/random.h"
#include "nmesh/vec3.h"

namespace nmesh::bench {

inline double triangle_area(const IndexedMesh& m, std::size_t t) {
    const auto& f = m.triangles[t];
    return 0.5 * double(nmesh::norm(
                     nmesh::cross(m.positions[f[1]] - m.positions[f[0]], m.positions[f[2]] - m.positions[f[0]])));
}

inline double area(const IndexedMesh& m) {
    double a = 0.0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) a += triangle_area(m, t);
    return a;
}

// n points drawn uniformly by area on the mesh (seeded, so every run is measured at the same
// reference samples).
inline std::vector<Vec3> sample_surface(const IndexedMesh& m, std::size_t n, std::uint64_t seed) {
    std::vector<double> cumulative(m.triangles.size());
    double total = 0.0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) cumulative[t] = total += triangle_area(m, t);
    nmesh::Random rng(seed);
    std::vector<Vec3> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n && total > 0.0; ++i) {
        const double r = rng.uniform() * total;
        const std::size_t t = std::min<std::size_t>(
            m.triangles.size() - 1,
            std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), r) - cumulative.begin()));
        const auto& f = m.triangles[t];
        const double s = std::sqrt(rng.uniform()), u = rng.uniform();
        const Vec3 a = m.positions[f[0]], b = m.positions[f[1]], c = m.positions[f[2]];
        out.push_back(a * float(1.0 - s) + b * float(s * (1.0 - u)) + c * float(s * u));
    }
    return out;
}

struct Distances {
    double mean = 0.0, max = 0.0;
};

// The mean and the largest distance from the samples to the nearest triangle of `to` (zeros when
// either is empty).
inline Distances distances(const std::vector<Vec3>& samples, const IndexedMesh& to) {
    Distances d;
    if (samples.empty() || to.triangles.empty()) return d;
    const nmesh::TriangleBvh bvh(to);
    for (const Vec3& p : samples) {
        const double x = std::sqrt(bvh.nearest_squared_distance(p, std::numeric_limits<double>::infinity()));
        d.mean += x;
        d.max = std::max(d.max, x);
    }
    d.mean /= double(samples.size());
    return d;
}

}  // namespace nmesh::bench
