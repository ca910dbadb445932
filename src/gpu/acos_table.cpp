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

float table_acos(const std::vector<float>& table, float x) {
    const float ax = std::min(std::abs(x), 1.0f);
    const float s = std::sqrt(1.0f - ax) * float(table.size() - 1);
    const int i = std::min(int(s), int(table.size()) - 2);
    const float f = s - float(i);
    const float a = table[std::size_t(i)] + f * (table[std::size_t(i) + 1] - table[std::size_t(i)]);
    return x >= 0 ? a : float(std::numbers::pi) - a;
}

} // namespace hemirad::gpu
