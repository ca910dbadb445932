#include "gpu/acos_table.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hemirad::gpu {

std::vector<float> make_acos_table(int size) {
    std::vector<float> t(static_cast<std::size_t>(size));
    for (int i = 0; i < size; ++i) {
        const double s = double(i) / double(size - 1);
        t[std::size_t(i)] = float(std::acos(1.0 - s * s));
    }
    return t;
}

float table_angle(const std::vector<float>& table, const float a[3], const float b[3]) {
    const float x = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const float sign = x >= 0 ? -1.0f : 1.0f;
    const float d0 = a[0] + sign * b[0], d1 = a[1] + sign * b[1], d2 = a[2] + sign * b[2];
    const float s = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2) * 0.70710678f;
    const float t = std::min(s, 1.0f) * float(table.size() - 1);
    const int i = std::min(int(t), int(table.size()) - 2);
    const float f = t - float(i);
    const float angle =
        table[std::size_t(i)] + f * (table[std::size_t(i) + 1] - table[std::size_t(i)]);
    return x >= 0 ? angle : float(std::numbers::pi) - angle;
}

} // namespace hemirad::gpu
