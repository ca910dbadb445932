#include "hemirad/draw.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "hemirad/error.h"

namespace hemirad {

// =============================================================================================
// Font
// =============================================================================================

namespace {

/// One glyph: 8 rows of 5 columns, '#' set, '.' clear, rows separated by one space.
struct GlyphDef {
    char32_t code;
    const char* rows;
};

// clang-format off
constexpr GlyphDef kGlyphs[] = {
    {U' ',  "..... ..... ..... ..... ..... ..... ..... ....."},
    {U'!',  "..#.. ..#.. ..#.. ..#.. ..#.. ..... ..#.. ....."},
    {U'"',  ".#.#. .#.#. .#.#. ..... ..... ..... ..... ....."},
    {U'#',  ".#.#. .#.#. ##### .#.#. ##### .#.#. .#.#. ....."},
    {U'$',  "..#.. .#### #.#.. .###. ..#.# ####. ..#.. ....."},
    {U'%',  "##... ##..# ...#. ..#.. .#... #..## ...## ....."},
    {U'&',  ".##.. #..#. #.#.. .#... #.#.# #..#. .##.# ....."},
    {U'\'', "..#.. ..#.. .#... ..... ..... ..... ..... ....."},
    {U'(',  "...#. ..#.. .#... .#... .#... ..#.. ...#. ....."},
    {U')',  ".#... ..#.. ...#. ...#. ...#. ..#.. .#... ....."},
    {U'*',  "..... ..#.. #.#.# .###. #.#.# ..#.. ..... ....."},
    {U'+',  "..... ..#.. ..#.. ##### ..#.. ..#.. ..... ....."},
    {U',',  "..... ..... ..... ..... ..... .##.. ..#.. .#..."},
    {U'-',  "..... ..... ..... ##### ..... ..... ..... ....."},
    {U'.',  "..... ..... ..... ..... ..... .##.. .##.. ....."},
    {U'/',  "..... ....# ...#. ..#.. .#... #.... ..... ....."},
    {U'0',  ".###. #...# #..## #.#.# ##..# #...# .###. ....."},
    {U'1',  "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###. ....."},
    {U'2',  ".###. #...# ....# ...#. ..#.. .#... ##### ....."},
    {U'3',  "##### ...#. ..#.. ...#. ....# #...# .###. ....."},
    {U'4',  "...#. ..##. .#.#. #..#. ##### ...#. ...#. ....."},
    {U'5',  "##### #.... ####. ....# ....# #...# .###. ....."},
    {U'6',  "..##. .#... #.... ####. #...# #...# .###. ....."},
    {U'7',  "##### ....# ...#. ..#.. .#... .#... .#... ....."},
    {U'8',  ".###. #...# #...# .###. #...# #...# .###. ....."},
    {U'9',  ".###. #...# #...# .#### ....# ...#. .##.. ....."},
    {U':',  "..... .##.. .##.. ..... .##.. .##.. ..... ....."},
    {U';',  "..... .##.. .##.. ..... .##.. ..#.. .#... ....."},
    {U'<',  "...#. ..#.. .#... #.... .#... ..#.. ...#. ....."},
    {U'=',  "..... ..... ##### ..... ##### ..... ..... ....."},
    {U'>',  ".#... ..#.. ...#. ....# ...#. ..#.. .#... ....."},
    {U'?',  ".###. #...# ....# ...#. ..#.. ..... ..#.. ....."},
    {U'@',  ".###. #...# ....# .##.# #.#.# #.#.# .###. ....."},
    {U'A',  ".###. #...# #...# ##### #...# #...# #...# ....."},
    {U'B',  "####. #...# #...# ####. #...# #...# ####. ....."},
    {U'C',  ".###. #...# #.... #.... #.... #...# .###. ....."},
    {U'D',  "###.. #..#. #...# #...# #...# #..#. ###.. ....."},
    {U'E',  "##### #.... #.... ####. #.... #.... ##### ....."},
    {U'F',  "##### #.... #.... ####. #.... #.... #.... ....."},
    {U'G',  ".###. #...# #.... #.### #...# #...# .#### ....."},
    {U'H',  "#...# #...# #...# ##### #...# #...# #...# ....."},
    {U'I',  ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###. ....."},
    {U'J',  "..### ...#. ...#. ...#. ...#. #..#. .##.. ....."},
    {U'K',  "#...# #..#. #.#.. ##... #.#.. #..#. #...# ....."},
    {U'L',  "#.... #.... #.... #.... #.... #.... ##### ....."},
    {U'M',  "#...# ##.## #.#.# #.#.# #...# #...# #...# ....."},
    {U'N',  "#...# #...# ##..# #.#.# #..## #...# #...# ....."},
    {U'O',  ".###. #...# #...# #...# #...# #...# .###. ....."},
    {U'P',  "####. #...# #...# ####. #.... #.... #.... ....."},
    {U'Q',  ".###. #...# #...# #...# #.#.# #..#. .##.# ....."},
    {U'R',  "####. #...# #...# ####. #.#.. #..#. #...# ....."},
    {U'S',  ".#### #.... #.... .###. ....# ....# ####. ....."},
    {U'T',  "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ....."},
    {U'U',  "#...# #...# #...# #...# #...# #...# .###. ....."},
    {U'V',  "#...# #...# #...# #...# #...# .#.#. ..#.. ....."},
    {U'W',  "#...# #...# #...# #.#.# #.#.# #.#.# .#.#. ....."},
    {U'X',  "#...# #...# .#.#. ..#.. .#.#. #...# #...# ....."},
    {U'Y',  "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#.. ....."},
    {U'Z',  "##### ....# ...#. ..#.. .#... #.... ##### ....."},
    {U'[',  ".###. .#... .#... .#... .#... .#... .###. ....."},
    {U'\\', "..... #.... .#... ..#.. ...#. ....# ..... ....."},
    {U']',  ".###. ...#. ...#. ...#. ...#. ...#. .###. ....."},
    {U'^',  "..#.. .#.#. #...# ..... ..... ..... ..... ....."},
    {U'_',  "..... ..... ..... ..... ..... ..... ..... #####"},
    {U'`',  ".#... ..#.. ...#. ..... ..... ..... ..... ....."},
    {U'a',  "..... ..... .###. ....# .#### #...# .#### ....."},
    {U'b',  "#.... #.... #.##. ##..# #...# #...# ####. ....."},
    {U'c',  "..... ..... .###. #.... #.... #...# .###. ....."},
    {U'd',  "....# ....# .##.# #..## #...# #...# .#### ....."},
    {U'e',  "..... ..... .###. #...# ##### #.... .###. ....."},
    {U'f',  "..##. .#..# .#... ###.. .#... .#... .#... ....."},
    {U'g',  "..... ..... .#### #...# #...# .#### ....# .###."},
    {U'h',  "#.... #.... #.##. ##..# #...# #...# #...# ....."},
    {U'i',  "..#.. ..... .##.. ..#.. ..#.. ..#.. .###. ....."},
    {U'j',  "...#. ..... ..##. ...#. ...#. ...#. #..#. .##.."},
    {U'k',  "#.... #.... #..#. #.#.. ##... #.#.. #..#. ....."},
    {U'l',  ".##.. ..#.. ..#.. ..#.. ..#.. ..#.. .###. ....."},
    {U'm',  "..... ..... ##.#. #.#.# #.#.# #...# #...# ....."},
    {U'n',  "..... ..... #.##. ##..# #...# #...# #...# ....."},
    {U'o',  "..... ..... .###. #...# #...# #...# .###. ....."},
    {U'p',  "..... ..... ####. #...# #...# ####. #.... #...."},
    {U'q',  "..... ..... .#### #...# #...# .#### ....# ....#"},
    {U'r',  "..... ..... #.##. ##..# #.... #.... #.... ....."},
    {U's',  "..... ..... .###. #.... .###. ....# ####. ....."},
    {U't',  ".#... .#... ###.. .#... .#... .#..# ..##. ....."},
    {U'u',  "..... ..... #...# #...# #...# #..## .##.# ....."},
    {U'v',  "..... ..... #...# #...# #...# .#.#. ..#.. ....."},
    {U'w',  "..... ..... #...# #...# #.#.# #.#.# .#.#. ....."},
    {U'x',  "..... ..... #...# .#.#. ..#.. .#.#. #...# ....."},
    {U'y',  "..... ..... #...# #...# #...# .#### ....# .###."},
    {U'z',  "..... ..... ##### ...#. ..#.. .#... ##### ....."},
    {U'{',  "...#. ..#.. ..#.. .#... ..#.. ..#.. ...#. ....."},
    {U'|',  "..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ..#.. ....."},
    {U'}',  ".#... ..#.. ..#.. ...#. ..#.. ..#.. .#... ....."},
    {U'~',  "..... ..... .#... #.#.# ...#. ..... ..... ....."},
    // Beyond ASCII: units and symbols that reports use.
    {U'°',  ".##.. #..#. #..#. .##.. ..... ..... ..... ....."},
    {U'²',  ".##.. ...#. ..#.. .###. ..... ..... ..... ....."},
    {U'³',  ".##.. ...#. ..##. ...#. .##.. ..... ..... ....."},
    {U'µ',  "..... ..... #...# #...# #...# ##..# #.##. #...."},
    {U'μ',  "..... ..... #...# #...# #...# ##..# #.##. #...."},
    {U'·',  "..... ..... ..... ..#.. ..... ..... ..... ....."},
    {U'×',  "..... ..... .#.#. ..#.. .#.#. ..... ..... ....."},
    {U'ρ',  "..... ..... .###. #...# #...# ####. #.... #...."},
    {U'π',  "..... ..... ##### .#.#. .#.#. .#.#. .#..# ....."},
};
constexpr GlyphDef kBoxGlyph = {0, "##### #...# #...# #...# #...# #...# ##### ....."};
// clang-format on

constexpr bool glyph_well_formed(const GlyphDef& g) {
    for (int i = 0; i < 47; ++i) {
        const char c = g.rows[i];
        if (i % 6 == 5 ? c != ' ' : (c != '#' && c != '.')) return false;
    }
    return g.rows[47] == '\0';
}
constexpr bool all_glyphs_well_formed() {
    for (const GlyphDef& g : kGlyphs)
        if (!glyph_well_formed(g)) return false;
    for (int i = 0; i < 95; ++i)
        if (kGlyphs[i].code != char32_t(32 + i)) return false; // ASCII in order
    return glyph_well_formed(kBoxGlyph);
}
static_assert(all_glyphs_well_formed(), "a glyph row is not 5 of '#'/'.' or ASCII is out of order");

/// Bitmap of one glyph: bit (4 - col) of row r set = pixel (col, r) on.
using GlyphBits = std::array<std::uint8_t, kGlyphHeight>;

constexpr GlyphBits bits_of(const GlyphDef& g) {
    GlyphBits b{};
    for (int r = 0; r < kGlyphHeight; ++r)
        for (int c = 0; c < kGlyphWidth; ++c)
            if (g.rows[r * 6 + c] == '#') b[r] |= std::uint8_t(1u << (kGlyphWidth - 1 - c));
    return b;
}

const GlyphBits& glyph(char32_t code) {
    static const auto table = [] {
        std::array<GlyphBits, std::size(kGlyphs) + 1> t{};
        for (std::size_t i = 0; i < std::size(kGlyphs); ++i) t[i] = bits_of(kGlyphs[i]);
        t.back() = bits_of(kBoxGlyph);
        return t;
    }();
    if (code >= 32 && code <= 126) return table[code - 32];
    for (std::size_t i = 95; i < std::size(kGlyphs); ++i)
        if (kGlyphs[i].code == code) return table[i];
    return table.back();
}

/// Decodes one UTF-8 code point at s[i] and advances i; malformed input gives U+FFFD.
char32_t next_code_point(std::string_view s, std::size_t& i) {
    const auto b0 = static_cast<unsigned char>(s[i++]);
    if (b0 < 0x80) return b0;
    int extra = b0 >= 0xF0 && b0 < 0xF8 ? 3 : b0 >= 0xE0 ? 2 : b0 >= 0xC0 ? 1 : -1;
    if (extra < 0) return 0xFFFD;
    char32_t cp = b0 & (0x3F >> extra);
    for (; extra > 0; --extra) {
        if (i >= s.size() || (static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) return 0xFFFD;
        cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
    }
    return cp;
}

/// Calls fn(column, line, code point) for each character of `text` (column and line in cells).
template <class Fn> void for_each_char(std::string_view text, Fn&& fn) {
    int col = 0, line = 0;
    for (std::size_t i = 0; i < text.size();) {
        const char32_t cp = next_code_point(text, i);
        if (cp == U'\n') {
            col = 0;
            ++line;
            continue;
        }
        fn(col++, line, cp);
    }
}

inline void put(Image8& image, int x, int y, Rgb8 c) {
    if (image.contains(x, y)) image.set(x, y, c);
}

} // namespace

int text_width(std::string_view text, int scale) {
    int widest = 0;
    for_each_char(text, [&](int col, int, char32_t) { widest = std::max(widest, col + 1); });
    return widest > 0 ? (kGlyphAdvance * widest - 1) * std::max(1, scale) : 0;
}

int text_height(std::string_view text, int scale) {
    if (text.empty()) return 0;
    const int lines = 1 + int(std::count(text.begin(), text.end(), '\n'));
    return (kLineAdvance * (lines - 1) + kGlyphHeight) * std::max(1, scale);
}

void draw_text(Image8& image, int x, int y, std::string_view text, Rgb8 colour, int scale) {
    scale = std::max(1, scale);
    for_each_char(text, [&](int col, int line, char32_t cp) {
        const GlyphBits& g = glyph(cp);
        const int gx = x + col * kGlyphAdvance * scale, gy = y + line * kLineAdvance * scale;
        for (int r = 0; r < kGlyphHeight; ++r)
            for (int c = 0; c < kGlyphWidth; ++c)
                if (g[r] >> (kGlyphWidth - 1 - c) & 1)
                    fill_rect(image, gx + c * scale, gy + r * scale, scale, scale, colour);
    });
}

void draw_text_vertical(Image8& image, int x, int y, std::string_view text, Rgb8 colour,
                        int scale) {
    scale = std::max(1, scale);
    // Unrotated pixel (u along the text, v down) lands at (x + v, y - u).
    for_each_char(text, [&](int col, int line, char32_t cp) {
        const GlyphBits& g = glyph(cp);
        const int u0 = col * kGlyphAdvance * scale, v0 = line * kLineAdvance * scale;
        for (int r = 0; r < kGlyphHeight; ++r)
            for (int c = 0; c < kGlyphWidth; ++c)
                if (g[r] >> (kGlyphWidth - 1 - c) & 1) {
                    const int u = u0 + c * scale, v = v0 + r * scale;
                    fill_rect(image, x + v, y - u - scale + 1, scale, scale, colour);
                }
    });
}

// =============================================================================================
// Shapes
// =============================================================================================

namespace {

struct Rect { // inclusive pixel bounds
    int x0, y0, x1, y1;
};

/// Liang-Barsky: clips the segment to r (grown by `margin`); false if nothing is left.
bool clip_segment(double& x0, double& y0, double& x1, double& y1, const Rect& r, int margin) {
    const double dx = x1 - x0, dy = y1 - y0;
    double t0 = 0.0, t1 = 1.0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {x0 - (r.x0 - margin), (r.x1 + margin) - x0, y0 - (r.y0 - margin),
                         (r.y1 + margin) - y0};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return false;
        } else {
            const double t = q[i] / p[i];
            if (p[i] < 0.0)
                t0 = std::max(t0, t);
            else
                t1 = std::min(t1, t);
        }
    }
    if (t0 > t1) return false;
    const double ax = x0 + t0 * dx, ay = y0 + t0 * dy;
    x1 = x0 + t1 * dx;
    y1 = y0 + t1 * dy;
    x0 = ax;
    y0 = ay;
    return true;
}

void line_in(Image8& image, int x0, int y0, int x1, int y1, Rgb8 colour, int thickness,
             const Rect& clip) {
    thickness = std::max(1, thickness);
    const auto inside = [&](int x, int y) {
        return x >= clip.x0 - thickness && x <= clip.x1 + thickness && y >= clip.y0 - thickness &&
               y <= clip.y1 + thickness;
    };
    if (!inside(x0, y0) || !inside(x1, y1)) { // keep the loop short for far-away ends
        double a = x0, b = y0, c = x1, d = y1;
        if (!clip_segment(a, b, c, d, clip, thickness)) return;
        x0 = int(std::lround(a));
        y0 = int(std::lround(b));
        x1 = int(std::lround(c));
        y1 = int(std::lround(d));
    }
    const int lo = -(thickness / 2), hi = thickness - 1 - thickness / 2;
    const auto plot = [&](int x, int y) {
        for (int v = y + lo; v <= y + hi; ++v)
            for (int u = x + lo; u <= x + hi; ++u)
                if (u >= clip.x0 && u <= clip.x1 && v >= clip.y0 && v <= clip.y1)
                    put(image, u, v, colour);
    };
    // Bresenham, all octants.
    const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
    const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    for (;;) {
        plot(x0, y0);
        if (x0 == x1 && y0 == y1) break;
        const int e2 = 2 * err;
        if (e2 >= dy) {
            err += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            err += dx;
            y0 += sy;
        }
    }
}

Rect bounds_of(const Image8& image) {
    return {0, 0, image.width - 1, image.height - 1};
}

} // namespace

void fill_rect(Image8& image, int x, int y, int w, int h, Rgb8 colour) {
    const int xa = std::max(0, x), ya = std::max(0, y);
    const int xb = std::min(image.width, x + w), yb = std::min(image.height, y + h);
    for (int v = ya; v < yb; ++v)
        for (int u = xa; u < xb; ++u) image.set(u, v, colour);
}

void draw_rect(Image8& image, int x, int y, int w, int h, Rgb8 colour) {
    if (w <= 0 || h <= 0) return;
    fill_rect(image, x, y, w, 1, colour);
    fill_rect(image, x, y + h - 1, w, 1, colour);
    fill_rect(image, x, y, 1, h, colour);
    fill_rect(image, x + w - 1, y, 1, h, colour);
}

void draw_line(Image8& image, int x0, int y0, int x1, int y1, Rgb8 colour, int thickness) {
    if (image.empty()) return;
    line_in(image, x0, y0, x1, y1, colour, thickness, bounds_of(image));
}

void blit(Image8& dst, const Image8& src, int x, int y) {
    for (int v = std::max(0, -y); v < src.height && y + v < dst.height; ++v)
        for (int u = std::max(0, -x); u < src.width && x + u < dst.width; ++u)
            dst.set(x + u, y + v, src.get(u, v));
}

// =============================================================================================
// False colour
// =============================================================================================

namespace {

/// matplotlib's viridis (CC0) at entries 0, 16, 32, ..., 240 and 255 of its 256.
constexpr double kViridis[17][3] = {
    {0.267004, 0.004874, 0.329415}, {0.282327, 0.094955, 0.417331}, {0.278826, 0.175490, 0.483397},
    {0.258965, 0.251537, 0.524736}, {0.229739, 0.322361, 0.545706}, {0.199430, 0.387607, 0.554642},
    {0.172719, 0.448791, 0.557885}, {0.149039, 0.508051, 0.557250}, {0.127568, 0.566949, 0.550556},
    {0.120638, 0.625828, 0.533488}, {0.157851, 0.683765, 0.501686}, {0.246070, 0.738910, 0.452024},
    {0.369214, 0.788888, 0.382914}, {0.515992, 0.831158, 0.294279}, {0.678489, 0.863742, 0.189503},
    {0.845561, 0.887322, 0.099702}, {0.993248, 0.906157, 0.143936},
};

inline std::uint8_t to_byte(double v) {
    return static_cast<std::uint8_t>(std::clamp(v, 0.0, 1.0) * 255.0 + 0.5);
}

} // namespace

Rgb8 false_colour(double t) {
    if (!(t > 0.0)) t = 0.0; // also NaN
    t = std::min(t, 1.0);
    // Sample k sits at table index 16 k (k < 16) and 255 (k = 16), i.e. at t = index / 255.
    const double index = t * 255.0;
    const int k = std::min(15, int(index / 16.0));
    const double i0 = 16.0 * k, i1 = k == 15 ? 255.0 : 16.0 * (k + 1);
    const double f = std::clamp((index - i0) / (i1 - i0), 0.0, 1.0);
    const double* a = kViridis[k];
    const double* b = kViridis[k + 1];
    return {to_byte(a[0] + f * (b[0] - a[0])), to_byte(a[1] + f * (b[1] - a[1])),
            to_byte(a[2] + f * (b[2] - a[2]))};
}

double colour_scale_position(double value, double lo, double hi, bool log_scale) {
    if (std::isnan(value)) return 0.0;
    if (log_scale) {
        if (!(lo > 0.0)) lo = hi / 1000.0;
        if (!(value > 0.0)) return 0.0;
        value = std::log10(value);
        lo = std::log10(lo);
        hi = std::log10(hi);
    }
    if (!(hi > lo)) return value >= hi ? 1.0 : 0.0;
    return std::clamp((value - lo) / (hi - lo), 0.0, 1.0);
}

// =============================================================================================
// Ticks
// =============================================================================================

namespace {

struct Tick {
    double value;
    std::string label; ///< empty: a minor tick
};

/// 1, 2 or 5 times a power of ten, at least range / max_ticks.
double nice_step(double range, int max_ticks) {
    const double raw = range / std::max(1, max_ticks);
    if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * mag >= raw * (1 - 1e-9)) return m * mag;
    return 10.0 * mag;
}

std::string format_linear(double v, double step) {
    if (std::abs(v) < step * 1e-6) v = 0.0;
    char buf[64];
    const double a = std::max(std::abs(v), step);
    if (a >= 1e5 || step < 1e-3) {
        const int digits = std::clamp(
            int(std::floor(std::log10(a)) - std::floor(std::log10(step) + 1e-9)) + 1, 1, 6);
        std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    } else {
        const int decimals = std::max(0, -int(std::floor(std::log10(step) + 1e-9)));
        std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    }
    return buf;
}

/// Labels of log-axis ticks: decades as 0.001 ... 10000, beyond as 1e-5, 1e6; others %g.
std::string format_log(double v) {
    char buf[64];
    const double k = std::round(std::log10(v));
    if (std::abs(v / std::pow(10.0, k) - 1.0) < 1e-9 && (k < -3 || k > 4))
        std::snprintf(buf, sizeof buf, "1e%d", int(k));
    else
        std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

std::vector<Tick> linear_ticks(double lo, double hi, int max_labels) {
    std::vector<Tick> ticks;
    const double step = nice_step(hi - lo, max_labels);
    for (double i = std::ceil(lo / step - 1e-9); i * step <= hi + step * 1e-9; i += 1.0) {
        const double v = std::abs(i) < 0.5 ? 0.0 : i * step;
        ticks.push_back({v, format_linear(v, step)});
        if (ticks.size() > 1000) break;
    }
    return ticks;
}

/// Ticks for a log axis on [lo, hi] (lo > 0): decades (every n-th labelled so that at most
/// max_labels are), minor ticks at 2..9 when there is room; within a short range 1-2-5
/// multiples; within a very short one, linear ticks.
std::vector<Tick> log_ticks(double lo, double hi, int max_labels) {
    std::vector<Tick> ticks;
    const int k0 = int(std::ceil(std::log10(lo) - 1e-9));
    const int k1 = int(std::floor(std::log10(hi) + 1e-9));
    const int decades = k1 - k0 + 1;
    if (decades >= 2) {
        const int stride = std::max(1, (decades + max_labels - 1) / std::max(1, max_labels));
        const bool minor = decades <= max_labels;
        for (int k = k0 - 1; k <= k1; ++k) {
            const double d = std::pow(10.0, k);
            if (k >= k0) ticks.push_back({d, (k - k0) % stride == 0 ? format_log(d) : ""});
            if (minor)
                for (int m = 2; m <= 9; ++m)
                    if (m * d >= lo * (1 - 1e-9) && m * d <= hi * (1 + 1e-9))
                        ticks.push_back({m * d, ""});
        }
        std::sort(ticks.begin(), ticks.end(),
                  [](const Tick& a, const Tick& b) { return a.value < b.value; });
        return ticks;
    }
    for (int k = int(std::floor(std::log10(lo))); k <= int(std::ceil(std::log10(hi))); ++k)
        for (double m : {1.0, 2.0, 5.0}) {
            const double v = m * std::pow(10.0, k);
            if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back({v, format_log(v)});
        }
    if (ticks.size() >= 2) return ticks;
    return linear_ticks(lo, hi, max_labels);
}

std::vector<Tick> axis_ticks(double lo, double hi, bool log_scale, int max_labels) {
    return log_scale ? log_ticks(lo, hi, max_labels) : linear_ticks(lo, hi, max_labels);
}

} // namespace

void draw_colour_legend(Image8& image, int x, int y, int w, int h, double lo, double hi,
                        const std::string& unit, bool log_scale, Rgb8 ink) {
    if (w <= 0 || h <= 0) return;
    if (log_scale && !(lo > 0.0)) lo = hi / 1000.0;
    const bool vertical = h >= w;
    // The bar: one false_colour() per row (vertical, lo at the bottom) or column.
    if (vertical) {
        for (int r = 0; r < h; ++r)
            fill_rect(image, x, y + r, w, 1, false_colour(1.0 - (r + 0.5) / h));
    } else {
        for (int c = 0; c < w; ++c) fill_rect(image, x + c, y, 1, h, false_colour((c + 0.5) / w));
    }
    draw_rect(image, x - 1, y - 1, w + 2, h + 2, ink);
    if (!unit.empty()) draw_text(image, x, y - 1 - 3 - kGlyphHeight, unit, ink);
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return;

    const int max_labels = vertical ? std::max(2, h / 24) : std::max(2, w / 48);
    for (const Tick& tick : axis_ticks(lo, hi, log_scale, max_labels)) {
        const double t = colour_scale_position(tick.value, lo, hi, log_scale);
        const int len = tick.label.empty() ? 2 : 4;
        if (vertical) {
            const int row = y + int(std::lround((1.0 - t) * (h - 1)));
            fill_rect(image, x + w + 1, row, len, 1, ink);
            if (!tick.label.empty()) draw_text(image, x + w + 7, row - 3, tick.label, ink);
        } else {
            const int col = x + int(std::lround(t * (w - 1)));
            fill_rect(image, col, y + h + 1, 1, len, ink);
            if (!tick.label.empty())
                draw_text(image, col - text_width(tick.label) / 2, y + h + 7, tick.label, ink);
        }
    }
}

// =============================================================================================
// Contact sheet
// =============================================================================================

namespace {

/// `text` cut (at a character boundary, with "..") to at most `width` pixels at scale 1.
std::string fit_text(const std::string& text, int width) {
    if (text_width(text) <= width) return text;
    const int max_chars = std::max(0, (width + 1) / kGlyphAdvance - 2);
    std::string out;
    int n = 0;
    for (std::size_t i = 0; i < text.size() && n < max_chars;) {
        const std::size_t start = i;
        next_code_point(text, i);
        if (text[start] == '\n') break;
        out.append(text, start, i - start);
        ++n;
    }
    return max_chars > 0 ? out + ".." : "";
}

} // namespace

Image8 contact_sheet(const std::vector<Image8>& frames, const std::vector<std::string>& captions,
                     int columns) {
    if (frames.empty()) return {};
    HEMIRAD_CHECK(columns >= 1);
    int cw = 0, ch = 0;
    for (const Image8& f : frames) {
        cw = std::max(cw, f.width);
        ch = std::max(ch, f.height);
    }
    const bool any_caption = std::any_of(captions.begin(), captions.end(),
                                         [](const std::string& s) { return !s.empty(); });
    const int caption_h = any_caption ? kContactSheetCaption : 0;
    const int n = int(frames.size());
    const int cols = std::min(columns, n), rows = (n + cols - 1) / cols;
    const int pad = kContactSheetPad;
    Image8 sheet(cols * (cw + pad) + pad, rows * (ch + caption_h + pad) + pad, {40, 40, 40});
    for (int i = 0; i < n; ++i) {
        const int cx = pad + (i % cols) * (cw + pad);
        const int cy = pad + (i / cols) * (ch + caption_h + pad);
        const Image8& f = frames[std::size_t(i)];
        blit(sheet, f, cx + (cw - f.width) / 2, cy + (ch - f.height) / 2);
        if (std::size_t(i) < captions.size() && !captions[std::size_t(i)].empty()) {
            const std::string text = fit_text(captions[std::size_t(i)], cw);
            draw_text(sheet, cx + (cw - text_width(text)) / 2, cy + ch + 3, text, {230, 230, 230});
        }
    }
    return sheet;
}

// =============================================================================================
// Line plots
// =============================================================================================

double PlotFrame::px(double x) const {
    return left + (x - x0) / (x1 - x0) * (right - left);
}

double PlotFrame::py(double y) const {
    if (log_y) {
        if (!(y > 0.0)) return std::numeric_limits<double>::quiet_NaN();
        return bottom - (std::log10(y) - std::log10(y0)) / (std::log10(y1) - std::log10(y0)) *
                            (bottom - top);
    }
    return bottom - (y - y0) / (y1 - y0) * (bottom - top);
}

Rgb8 plot_palette(int index) {
    static constexpr Rgb8 kTableau10[10] = {
        {31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
        {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207},
    };
    return kTableau10[((index % 10) + 10) % 10];
}

Image8 plot_lines(const std::vector<PlotSeries>& series, const std::string& title,
                  const std::string& xlabel, const std::string& ylabel, bool log_y, int width,
                  int height, PlotFrame* frame_out) {
    HEMIRAD_CHECK(width >= 64 && height >= 64);
    constexpr Rgb8 kWhite{255, 255, 255}, kBlack{0, 0, 0}, kGrid{225, 225, 225},
        kMinorGrid{242, 242, 242}, kBorder{160, 160, 160};
    Image8 image(width, height, kWhite);

    const auto valid = [&](double x, double y) {
        return std::isfinite(x) && std::isfinite(y) && (!log_y || y > 0.0);
    };
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (const PlotSeries& s : series)
        for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
            if (valid(s.x[i], s.y[i])) {
                xmin = std::min(xmin, s.x[i]);
                xmax = std::max(xmax, s.x[i]);
                ymin = std::min(ymin, s.y[i]);
                ymax = std::max(ymax, s.y[i]);
            }
    if (!(xmin <= xmax)) { // no data
        xmin = 0.0;
        xmax = 1.0;
        ymin = log_y ? 1.0 : 0.0;
        ymax = log_y ? 10.0 : 1.0;
    }
    if (xmax == xmin) {
        xmin -= 0.5;
        xmax += 0.5;
    }

    PlotFrame f;
    f.log_y = log_y;
    f.x0 = xmin;
    f.x1 = xmax;
    // Vertical layout first: it does not depend on the labels' widths.
    const int title_scale = text_width(title, 2) <= width - 20 ? 2 : 1;
    f.top = title.empty() ? 10 : 8 + text_height(title, title_scale) + 8;
    f.bottom = height - 1 - (6 + 4 + kGlyphHeight + (xlabel.empty() ? 0 : 6 + kGlyphHeight) + 6);
    f.bottom = std::max(f.bottom, f.top + 16);

    // y range and ticks.
    const int max_ylabels = std::max(2, (f.bottom - f.top) / 28);
    if (log_y) {
        double d0 = std::floor(std::log10(ymin)), d1 = std::ceil(std::log10(ymax));
        if (d1 <= d0) d1 = d0 + 1;
        f.y0 = std::pow(10.0, d0);
        f.y1 = std::pow(10.0, d1);
    } else {
        if (ymax == ymin) {
            const double d = ymin == 0.0 ? 1.0 : 0.1 * std::abs(ymin);
            ymin -= d;
            ymax += d;
        }
        const double step = nice_step(ymax - ymin, max_ylabels);
        f.y0 = std::floor(ymin / step + 1e-9) * step;
        f.y1 = std::ceil(ymax / step - 1e-9) * step;
    }
    const std::vector<Tick> yticks = axis_ticks(f.y0, f.y1, log_y, max_ylabels);
    int ylabel_w = 0;
    for (const Tick& t : yticks) ylabel_w = std::max(ylabel_w, text_width(t.label));
    f.left = 6 + (ylabel.empty() ? 0 : kGlyphHeight + 6) + ylabel_w + 4 + 4;

    // x ticks: as many as fit with their labels.
    f.right = width - 1 - 16;
    std::vector<Tick> xticks;
    for (int max_xlabels = std::max(2, (f.right - f.left) / 60); max_xlabels >= 2; --max_xlabels) {
        xticks = linear_ticks(f.x0, f.x1, max_xlabels);
        int widest = 0;
        for (const Tick& t : xticks) widest = std::max(widest, text_width(t.label));
        const int room = (f.right - f.left) / std::max<int>(1, int(xticks.size()));
        if (widest + 10 <= room) break;
    }
    if (!xticks.empty()) // the last label, centred on its tick, stays inside the image
        f.right = std::min(f.right, width - 2 - text_width(xticks.back().label) / 2);
    f.right = std::max(f.right, f.left + 16);

    // Grid, then data, then axes and labels on top.
    for (const Tick& t : yticks) {
        const int row = int(std::lround(f.py(t.value)));
        if (row > f.top && row < f.bottom)
            fill_rect(image, f.left + 1, row, f.right - f.left - 1, 1,
                      t.label.empty() ? kMinorGrid : kGrid);
    }
    for (const Tick& t : xticks) {
        const int col = int(std::lround(f.px(t.value)));
        if (col > f.left && col < f.right)
            fill_rect(image, col, f.top + 1, 1, f.bottom - f.top - 1, kGrid);
    }

    const Rect area{f.left, f.top, f.right, f.bottom};
    for (const PlotSeries& s : series) {
        const std::size_t n = std::min(s.x.size(), s.y.size());
        for (std::size_t i = 0; i < n; ++i) {
            if (!valid(s.x[i], s.y[i])) continue;
            const int xa = int(std::lround(f.px(s.x[i]))), ya = int(std::lround(f.py(s.y[i])));
            const bool next = i + 1 < n && valid(s.x[i + 1], s.y[i + 1]);
            const bool prev = i > 0 && valid(s.x[i - 1], s.y[i - 1]);
            if (next) {
                const int xb = int(std::lround(f.px(s.x[i + 1])));
                const int yb = int(std::lround(f.py(s.y[i + 1])));
                line_in(image, xa, ya, xb, yb, s.colour, 1, area);
            } else if (!prev) { // an isolated point
                for (int v = ya - 1; v <= ya + 1; ++v)
                    for (int u = xa - 1; u <= xa + 1; ++u)
                        if (u >= area.x0 && u <= area.x1 && v >= area.y0 && v <= area.y1)
                            image.set(u, v, s.colour);
            }
        }
    }

    draw_rect(image, f.left, f.top, f.right - f.left + 1, f.bottom - f.top + 1, kBlack);
    for (const Tick& t : yticks) {
        const int row = int(std::lround(f.py(t.value)));
        if (row < f.top || row > f.bottom) continue;
        fill_rect(image, f.left - (t.label.empty() ? 2 : 4), row, t.label.empty() ? 2 : 4, 1,
                  kBlack);
        if (!t.label.empty())
            draw_text(image, f.left - 8 - text_width(t.label), row - 3, t.label, kBlack);
    }
    for (const Tick& t : xticks) {
        const int col = int(std::lround(f.px(t.value)));
        if (col < f.left || col > f.right) continue;
        fill_rect(image, col, f.bottom + 1, 1, 4, kBlack);
        draw_text(image, col - text_width(t.label) / 2, f.bottom + 8, t.label, kBlack);
    }
    if (!title.empty())
        draw_text(image, (width - text_width(title, title_scale)) / 2, 8, title, kBlack,
                  title_scale);
    if (!xlabel.empty())
        draw_text(image, (f.left + f.right - text_width(xlabel)) / 2,
                  f.bottom + 8 + kGlyphHeight + 6, xlabel, kBlack);
    if (!ylabel.empty())
        draw_text_vertical(image, 6, (f.top + f.bottom + text_width(ylabel)) / 2, ylabel, kBlack);

    // Legend, top right inside the plot area.
    std::vector<const PlotSeries*> entries;
    int label_w = 0;
    for (const PlotSeries& s : series)
        if (!s.label.empty()) {
            entries.push_back(&s);
            label_w = std::max(label_w, text_width(s.label));
        }
    if (!entries.empty()) {
        const int row_h = kLineAdvance + 2;
        const int bw = 6 + 16 + 5 + label_w + 6, bh = 5 + row_h * int(entries.size()) + 1;
        const int bx = f.right - 6 - bw, by = f.top + 6;
        fill_rect(image, bx, by, bw, bh, kWhite);
        draw_rect(image, bx, by, bw, bh, kBorder);
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const int ty = by + 5 + row_h * int(i);
            fill_rect(image, bx + 6, ty + 3, 16, 2, entries[i]->colour);
            draw_text(image, bx + 6 + 16 + 5, ty, entries[i]->label, kBlack);
        }
    }
    if (frame_out) *frame_out = f;
    return image;
}

Image8 false_colour_luminance(const ImageRGB& image, double unit_scale, bool log_scale,
                              ColourRange& range) {
    std::vector<double> lum(std::size_t(image.width) * image.height, -1.0);
    double hi = 0.0, lo_positive = HUGE_VAL;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float* p = image.at(x, y);
            if (p[0] < 0) continue; // no surface
            const double L = unit_scale * luminance(p[0], p[1], p[2]);
            if (!std::isfinite(L)) continue;
            lum[std::size_t(y) * image.width + x] = L;
            hi = std::max(hi, L);
            if (L > 0) lo_positive = std::min(lo_positive, L);
        }
    if (!(hi > 0)) hi = 1.0;
    range.hi = hi;
    range.lo = !log_scale                   ? 0.0
               : std::isfinite(lo_positive) ? std::max(lo_positive, hi / 1000.0)
                                            : hi / 1000.0;
    Image8 out(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double L = lum[std::size_t(y) * image.width + x];
            out.set(x, y,
                    L < 0 ? Rgb8{128, 128, 128}
                          : false_colour(colour_scale_position(L, range.lo, range.hi, log_scale)));
        }
    return out;
}

} // namespace hemirad
