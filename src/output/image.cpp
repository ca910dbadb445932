// Tone mapping: linear float RGB -> 8-bit sRGB. The choices (operator, auto exposure) are
// documented in hemirad/image.h.
#include "hemirad/image.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/colour.h"
#include "hemirad/error.h"

namespace hemirad {

namespace {

/// A channel as the operators see it: NaN and negative values are 0; +inf stays.
inline double clean(double v) {
    return v > 0.0 ? v : 0.0;
}

inline double pixel_luminance(const float* p) {
    return luminance(clean(p[0]), clean(p[1]), clean(p[2]));
}

inline std::uint8_t quantise(double display_linear) {
    return static_cast<std::uint8_t>(srgb_encode(display_linear) * 255.0 + 0.5);
}

/// Narkowicz 2015, "ACES Filmic Tone Mapping Curve"; input >= 0, output in [0, 1].
inline double aces(double x) {
    if (std::isinf(x)) return 1.0;
    const double y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return std::clamp(y, 0.0, 1.0);
}

} // namespace

double auto_exposure_scale(const ImageRGB& image) {
    std::vector<float> lum;
    lum.reserve(std::size_t(std::max(0, image.width)) * std::max(0, image.height));
    for (std::size_t i = 0; i + 2 < image.pixels.size(); i += 3) {
        const double l = pixel_luminance(&image.pixels[i]);
        if (l > 0.0 && std::isfinite(l)) lum.push_back(static_cast<float>(l));
    }
    if (lum.empty()) return 1.0;
    // Nearest-rank percentile: the smallest value with at least p*n values at or below it.
    const double rank = std::ceil(kAutoExposurePercentile * double(lum.size()));
    const std::size_t index = std::min(lum.size() - 1, std::size_t(std::max(1.0, rank)) - 1);
    std::nth_element(lum.begin(), lum.begin() + std::ptrdiff_t(index), lum.end());
    return 1.0 / double(lum[index]);
}

Image8 tone_map(const ImageRGB& image, const ToneMap& options) {
    if (!std::isfinite(options.exposure))
        throw InputError("tone map: exposure must be a finite number of stops");
    HEMIRAD_CHECK_EQ(image.pixels.size(), std::size_t(image.width) * image.height * 3);
    const double k =
        (options.auto_exposure ? auto_exposure_scale(image) : 1.0) * std::exp2(options.exposure);
    constexpr double inv_white2 = 1.0 / (kReinhardWhite * kReinhardWhite);

    Image8 out(image.width, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); i += 3) {
        double c[3];
        for (int j = 0; j < 3; ++j) c[j] = clean(k * double(image.pixels[i + j]));
        switch (options.op) {
        case ToneMap::Clamp:
            for (double& v : c) v = std::min(v, 1.0);
            break;
        case ToneMap::Aces:
            for (double& v : c) v = aces(v);
            break;
        case ToneMap::Reinhard: {
            // Reinhard et al. 2002, eq. 4, on luminance; the ratio L'/L scales the colour.
            const double l = luminance(c[0], c[1], c[2]);
            if (std::isinf(l)) {
                c[0] = c[1] = c[2] = 1.0;
            } else if (l > 0.0) {
                const double s = (1.0 + l * inv_white2) / (1.0 + l);
                for (double& v : c) v = std::min(v * s, 1.0);
            }
            break;
        }
        }
        for (int j = 0; j < 3; ++j) out.rgb[i + j] = quantise(c[j]);
    }
    return out;
}

} // namespace hemirad
