// bench/summary.h — the median, minimum and maximum of a benchmark's repeated measurements.
#pragma once

#include <algorithm>
#include <vector>

namespace nmesh::bench {

struct Summary {
    double median = 0, min = 0, max = 0;
};

// Precondition: v not empty. The median of an even count is the mean of the middle two.
inline Summary summarize(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v.front(), v.back()};
}

}  // namespace nmesh::bench
