// The sRGB transfer function and its inverse (IEC 61966-2-1): the one pair in the tree, used
// by tone mapping (8-bit PNG output, image.cpp) and by texture decoding (texture.cpp).
#pragma once

#include <cmath>

namespace hemirad {

/// Linear [0, 1] -> sRGB-encoded [0, 1], exact: 12.92 v below 0.0031308, else
/// 1.055 v^(1/2.4) - 0.055. Input is clamped to [0, 1] (NaN gives 0).
inline double srgb_encode(double v) {
    if (!(v > 0.0)) return 0.0;
    if (v >= 1.0) return 1.0;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

/// sRGB-encoded [0, 1] -> linear [0, 1]: e / 12.92 up to 0.04045, else ((e + 0.055) / 1.055)^2.4.
/// Input is clamped to [0, 1] (NaN gives 0).
inline double srgb_decode(double e) {
    if (!(e > 0.0)) return 0.0;
    if (e >= 1.0) return 1.0;
    return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

} // namespace hemirad
