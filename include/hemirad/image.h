// Images: linear float RGB (renders, EXR) and 8-bit sRGB (PNG, plots), their file formats,
// and the tone mapping from one to the other.
//
// Every writer here is atomic (STYLE: "no partial output file, ever"): the bytes are encoded in
// memory, written to `PATH.tmp-XXXXXX` beside the target and renamed over it only when complete.
// Failures throw RuntimeError with the path and the reason; the target is then left untouched.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hemirad/visibility.h"

namespace hemirad {

/// Linear RGB, 3 floats per pixel, row-major, row 0 at the top. Values are in whatever unit the
/// producer says (radiosity W unit^-2, irradiance, ...); nothing here assumes a range.
struct ImageRGB {
    int width = 0, height = 0;
    std::vector<float> pixels; ///< size 3 * width * height

    ImageRGB() = default;
    /// w x h black pixels (negative sizes count as 0).
    ImageRGB(int w, int h)
        : width(w > 0 ? w : 0), height(h > 0 ? h : 0),
          pixels(std::size_t(width) * std::size_t(height) * 3, 0.0f) {}

    /// Pointer to the 3 floats of pixel (x, y); 0 <= x < width, 0 <= y < height (unchecked).
    float* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * 3]; }
    const float* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * 3]; }
    bool empty() const { return width <= 0 || height <= 0; }
};

/// An 8-bit colour, sRGB-encoded when it is in an Image8.
struct Rgb8 {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb8&, const Rgb8&) = default;
};

/// 8-bit RGB, sRGB-encoded, 3 bytes per pixel, row-major, row 0 at the top.
struct Image8 {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgb; ///< size 3 * width * height

    Image8() = default;
    /// w x h pixels of `fill` (negative sizes count as 0).
    Image8(int w, int h, Rgb8 fill = {})
        : width(w > 0 ? w : 0), height(h > 0 ? h : 0),
          rgb(std::size_t(width) * std::size_t(height) * 3) {
        for (std::size_t i = 0; i < rgb.size(); i += 3) {
            rgb[i] = fill.r;
            rgb[i + 1] = fill.g;
            rgb[i + 2] = fill.b;
        }
    }

    /// Pointer to the 3 bytes of pixel (x, y); 0 <= x < width, 0 <= y < height (unchecked).
    std::uint8_t* at(int x, int y) { return &rgb[(std::size_t(y) * width + x) * 3]; }
    const std::uint8_t* at(int x, int y) const { return &rgb[(std::size_t(y) * width + x) * 3]; }
    Rgb8 get(int x, int y) const {
        const std::uint8_t* p = at(x, y);
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, Rgb8 c) {
        std::uint8_t* p = at(x, y);
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
    }
    bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
    bool empty() const { return width <= 0 || height <= 0; }
};

// --- files -----------------------------------------------------------------------------------

/// Writes an OpenEXR file with channels R, G, B (linear, scan lines, ZIP compression).
/// half = true stores 16-bit floats (about 3 significant digits; finite values beyond +-65504
/// are clamped to +-65504 rather than becoming infinite); false stores 32-bit floats.
/// Atomic; throws RuntimeError naming the path.
HEMIRAD_API void write_exr(const std::string& path, const ImageRGB& image, bool half = true);

/// Reads the R, G, B channels of an OpenEXR file (any pixel type, as float). A missing channel
/// reads as 0; a luminance-only file (Y) is read as grey. Throws RuntimeError naming the path.
HEMIRAD_API ImageRGB read_exr(const std::string& path);

/// Writes an 8-bit RGB PNG tagged sRGB (sRGB + gAMA chunks, no time or text chunks: the bytes
/// depend only on the pixels). Atomic; throws RuntimeError naming the path.
HEMIRAD_API void write_png(const std::string& path, const Image8& image);

/// Reads a PNG as 8-bit RGB (grey, palette and 16-bit files are converted; alpha is dropped).
/// Throws RuntimeError naming the path.
HEMIRAD_API Image8 read_png(const std::string& path);

// --- tone mapping ----------------------------------------------------------------------------

/// Rec. 709 / sRGB luminance of linear RGB: 0.2126 R + 0.7152 G + 0.0722 B.
inline double luminance(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

/// Linear float image -> 8-bit sRGB, in this order, per pixel:
///   1. scale by k = (auto_exposure ? auto_exposure_scale(image) : 1) * 2^exposure;
///   2. the operator (below) maps scaled linear RGB to display-linear [0, 1];
///   3. the exact sRGB transfer function; 4. round to nearest 8-bit value (no dithering).
/// NaN and negative channels display as 0, +inf as full intensity.
struct ToneMap {
    enum Operator {
        Clamp,    ///< clamp each channel to [0, 1]; scaled 1.0 is white
        Reinhard, ///< extended Reinhard on luminance (Reinhard et al. 2002, eq. 4), white point
                  ///< kReinhardWhite: L' = L (1 + L / W^2) / (1 + L); RGB scaled by L'/L, then
                  ///< each channel clamped to 1. Keeps hue; compresses highlights smoothly.
        Aces,     ///< per-channel ACES filmic fit (Narkowicz 2015):
                  ///< x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]
    };
    double exposure = 0.0;     ///< [stops] added to the automatic exposure; any finite value
    bool auto_exposure = true; ///< true: start from auto_exposure_scale(); false: from k = 1
    Operator op = Reinhard;    ///< default: Reinhard
};

/// Reinhard white point in scaled units: a scaled luminance of 4 (four times the auto-exposure
/// reference, e.g. a light source in view) and above displays as white.
inline constexpr double kReinhardWhite = 4.0;
/// Auto exposure: the percentile of luminance (over the pixels of finite, positive luminance,
/// so that a black background does not count) that is mapped to scaled luminance 1.
inline constexpr double kAutoExposurePercentile = 0.95;

/// Scale k such that the kAutoExposurePercentile (95th) percentile of luminance, over pixels of
/// finite positive luminance, maps to 1. Robust to a light source in view as long as it covers
/// less than 5% of the lit pixels. Returns 1 for an image with no such pixel.
HEMIRAD_API double auto_exposure_scale(const ImageRGB& image);

/// Tone maps a linear image to 8-bit sRGB (see ToneMap for the steps).
HEMIRAD_API Image8 tone_map(const ImageRGB& image, const ToneMap& options = {});

} // namespace hemirad
