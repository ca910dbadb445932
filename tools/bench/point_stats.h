// Statistics of errors at points, shared by hemirad-bench's accuracy experiments.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "hemirad/scene.h"

namespace hemirad::bench {

/// Rec. 709 luminance of an RGB irradiance (what the accuracy tables compare).
inline double luminance(const dvec3& e) {
    return 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z;
}

/// The q-quantile of v (0 <= q <= 1), linearly interpolated between order statistics; 0 for
/// an empty v.
inline double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const double k = q * double(v.size() - 1);
    const std::size_t lo = std::size_t(k), hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (v[hi] - v[lo]) * (k - double(lo));
}

} // namespace hemirad::bench
