// Small drawing helpers on 8-bit images, no GL: a built-in bitmap font, rectangles and lines,
// a false-colour map with its legend, contact sheets and line plots. Everything clips to the
// image, so callers may draw partly or wholly outside it. Coordinates are pixels, x to the
// right, y down, (0, 0) the top-left pixel. Output is deterministic (no anti-aliasing).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "hemirad/image.h"
#include "hemirad/visibility.h"

namespace hemirad {

// --- text ------------------------------------------------------------------------------------
// A 5x8 pixel font of our own (cap height 7, 1 row of descender) for printable ASCII 32..126,
// plus ° ² ³ µ · × ρ π (UTF-8). Other characters draw as a hollow box. '\n' starts a new line.

inline constexpr int kGlyphWidth = 5;   ///< glyph cell width [pixels at scale 1]
inline constexpr int kGlyphHeight = 8;  ///< glyph cell height, descender included
inline constexpr int kGlyphAdvance = 6; ///< horizontal step between characters
inline constexpr int kLineAdvance = 10; ///< vertical step between lines

/// Width in pixels of the widest line of `text` at `scale` (>= 1): n characters take
/// (6 n - 1) * scale; 0 for an empty text. Every pixel draw_text sets lies in [x, x + width).
HEMIRAD_API int text_width(std::string_view text, int scale = 1);
/// Height in pixels: (10 (lines - 1) + 8) * scale; 0 for an empty text.
HEMIRAD_API int text_height(std::string_view text, int scale = 1);
/// Draws `text` with its top-left corner at (x, y); each font pixel is a scale x scale square.
HEMIRAD_API void draw_text(Image8& image, int x, int y, std::string_view text, Rgb8 colour,
                           int scale = 1);
/// Draws `text` rotated 90 degrees anticlockwise (reading upwards) with the bottom-left corner
/// of its (rotated) box at (x, y): it covers x .. x + text_height - 1, y - text_width + 1 .. y.
HEMIRAD_API void draw_text_vertical(Image8& image, int x, int y, std::string_view text, Rgb8 colour,
                                    int scale = 1);

// --- shapes ----------------------------------------------------------------------------------

HEMIRAD_API void fill_rect(Image8& image, int x, int y, int w, int h, Rgb8 colour);
/// One-pixel outline of the rectangle [x, x + w) x [y, y + h).
HEMIRAD_API void draw_rect(Image8& image, int x, int y, int w, int h, Rgb8 colour);
/// Bresenham line from (x0, y0) to (x1, y1), both ends included; thickness (>= 1) draws a
/// thickness x thickness square at every step, centred (rounded up-left for even values).
HEMIRAD_API void draw_line(Image8& image, int x0, int y0, int x1, int y1, Rgb8 colour,
                           int thickness = 1);
/// Copies `src` into `dst` with its top-left corner at (x, y), clipped.
HEMIRAD_API void blit(Image8& dst, const Image8& src, int x, int y);

// --- false colour ----------------------------------------------------------------------------

/// Viridis (van der Walt & Smith, matplotlib; CC0), 17 samples of the 256-entry table with
/// linear interpolation. t in [0, 1] (clamped; NaN gives the t = 0 colour): 0 is dark purple
/// (68, 1, 84), 1 is yellow (253, 231, 37). Perceptually uniform and readable in grey.
HEMIRAD_API Rgb8 false_colour(double t);

/// Range of a false-colour scale.
struct ColourRange {
    double lo = 0, hi = 1;
};

/// False colour of a quantity per pixel: the Rec. 709 luminance of `image` (times
/// `unit_scale`, e.g. 683 for lux) through viridis; linear over 0..max, or logarithmic over at
/// most 3 decades under the maximum. Pixels whose red value is negative (no surface there)
/// are grey. The range used is returned in `range`, for the legend.
HEMIRAD_API Image8 false_colour_luminance(const ImageRGB& image, double unit_scale, bool log_scale,
                                          ColourRange& range);
/// Position in [0, 1] of `value` on a colour scale from lo to hi, linear or log10 (clamped;
/// values <= 0 on a log scale map to 0). Use with false_colour() and draw_colour_legend().
HEMIRAD_API double colour_scale_position(double value, double lo, double hi, bool log_scale);
/// A colour bar filling [x, x + w) x [y, y + h) with tick marks and labels outside it: vertical
/// when h >= w (lo at the bottom, labels right of the bar, within about 60 pixels), else
/// horizontal (lo at the left, labels below, within 14 pixels). `unit` is written above the
/// bar (10 pixels). log_scale: ticks at decades (and 2, 5 within a short range); lo must be > 0,
/// else lo = hi / 1000 is used. Text and ticks are drawn in `ink`.
HEMIRAD_API void draw_colour_legend(Image8& image, int x, int y, int w, int h, double lo, double hi,
                                    const std::string& unit, bool log_scale, Rgb8 ink = {0, 0, 0});

// --- contact sheet ---------------------------------------------------------------------------

/// Frames on a grid of `columns` (>= 1) columns, left to right then top to bottom, each in a
/// cell the size of the largest frame (smaller ones centred), with its caption (if any; cut to
/// the cell's width) under it, on a dark grey background. With cw, ch the largest frame width
/// and height, n frames, c = min(columns, n) columns and r = ceil(n / c) rows:
///   width = c (cw + 8) + 8, height = r (ch + caption + 8) + 8,
/// caption = 12 pixels if any caption is non-empty, else 0. No frames: an empty Image8.
/// `captions` may be shorter than `frames` (the rest have none).
HEMIRAD_API Image8 contact_sheet(const std::vector<Image8>& frames,
                                 const std::vector<std::string>& captions, int columns);
inline constexpr int kContactSheetPad = 8;      ///< gap between and around cells [pixels]
inline constexpr int kContactSheetCaption = 12; ///< caption strip under a frame [pixels]

// --- line plots ------------------------------------------------------------------------------

struct PlotSeries {
    std::string label;        ///< legend entry; empty: not in the legend
    std::vector<double> x, y; ///< points in order; the shorter length is used
    Rgb8 colour{31, 119, 180};
};

/// Where plot_lines() put the axes: the plot area is [left, right] x [top, bottom] (pixels,
/// inclusive); x0..x1 and y0..y1 the axis ranges (y on a log10 scale when log_y).
struct HEMIRAD_API PlotFrame {
    int left = 0, top = 0, right = 0, bottom = 0;
    double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    bool log_y = false;
    double px(double x) const; ///< pixel column of data x (not rounded)
    double py(double y) const; ///< pixel row of data y (not rounded; NaN for y <= 0 if log_y)
};

/// The i-th colour of a categorical palette (Tableau 10), cycling.
HEMIRAD_API Rgb8 plot_palette(int index);

/// A line plot on white: title on top, axes with ticks, tick labels and grid, axis labels, and
/// a legend in the top-right corner of the plot area. Points with a non-finite coordinate, or
/// y <= 0 when log_y, are skipped, and lines are not drawn across them. The x range is that of
/// the data; y is rounded out to ticks (to whole decades when log_y). width, height >= 64.
/// `frame`, if given, receives the layout (for annotations and tests).
HEMIRAD_API Image8 plot_lines(const std::vector<PlotSeries>& series, const std::string& title,
                              const std::string& xlabel, const std::string& ylabel, bool log_y,
                              int width, int height, PlotFrame* frame = nullptr);

} // namespace hemirad
