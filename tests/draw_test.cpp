// Drawing helpers: font, shapes, false colour, legend, contact sheet, line plots.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include "core/colour.h"
#include "hemirad/draw.h"
#include "hemirad/image.h"

namespace fs = std::filesystem;
using namespace hemirad;

namespace {

constexpr Rgb8 kBlack{0, 0, 0}, kWhite{255, 255, 255};

struct Box {
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
    int count = 0;
};

/// Bounding box of the pixels that differ from `background`.
Box ink_box(const Image8& image, Rgb8 background) {
    Box b;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (!(image.get(x, y) == background)) {
                b.x0 = std::min(b.x0, x);
                b.y0 = std::min(b.y0, y);
                b.x1 = std::max(b.x1, x);
                b.y1 = std::max(b.y1, y);
                ++b.count;
            }
    return b;
}

/// Rows of column x where the pixel is `colour`.
std::vector<int> rows_of(const Image8& image, int x, Rgb8 colour) {
    std::vector<int> rows;
    for (int y = 0; y < image.height; ++y)
        if (image.get(x, y) == colour) rows.push_back(y);
    return rows;
}

double srgb_luminance(Rgb8 c) {
    return luminance(srgb_decode(c.r / 255.0), srgb_decode(c.g / 255.0), srgb_decode(c.b / 255.0));
}

} // namespace

// --- text ------------------------------------------------------------------------------------

class DrawTextBounds : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(DrawTextBounds, InkStaysInsideTheReportedBox) {
    const auto& [text, scale] = GetParam();
    Image8 image(400, 120);
    const int x = 7, y = 5;
    draw_text(image, x, y, text, kWhite, scale);
    const Box b = ink_box(image, kBlack);
    ASSERT_GT(b.count, 0);
    EXPECT_GE(b.x0, x);
    EXPECT_LT(b.x1, x + text_width(text, scale));
    EXPECT_GE(b.y0, y);
    EXPECT_LT(b.y1, y + text_height(text, scale));
    // ...and the box is tight to a character cell's column.
    EXPECT_GE(b.x1, x + text_width(text, scale) - kGlyphAdvance * scale);
}

INSTANTIATE_TEST_SUITE_P(Font, DrawTextBounds,
                         ::testing::Values(std::make_tuple("Hello, World!", 1),
                                           std::make_tuple("gjpqy_|", 1),
                                           std::make_tuple("E = 12.5 W/m\xC2\xB2", 1),
                                           std::make_tuple("0123456789", 2),
                                           std::make_tuple("two\nlines, the second longer", 1),
                                           std::make_tuple("rho \xCF\x81 = 0.5, 45\xC2\xB0", 3)));

TEST(DrawText, WidthAndHeightFollowTheCellSizes) {
    EXPECT_EQ(text_width(""), 0);
    EXPECT_EQ(text_height(""), 0);
    EXPECT_EQ(text_width("a"), 5);
    EXPECT_EQ(text_width("abc"), 17);
    EXPECT_EQ(text_width("abc", 2), 34);
    EXPECT_EQ(text_width("W/m\xC2\xB2"), 23); // 4 characters: UTF-8 counts as one
    EXPECT_EQ(text_width("ab\nabcd\nc"), 23);
    EXPECT_EQ(text_height("x"), 8);
    EXPECT_EQ(text_height("x\ny", 2), 36);
}

TEST(DrawText, EveryPrintableAsciiGlyphHasInkExceptSpace) {
    for (int c = 32; c <= 126; ++c) {
        Image8 image(8, 10);
        draw_text(image, 1, 1, std::string(1, char(c)), kWhite);
        const Box b = ink_box(image, kBlack);
        if (c == ' ')
            EXPECT_EQ(b.count, 0);
        else
            EXPECT_GT(b.count, 0) << "character " << char(c);
    }
    // Distinct glyphs for look-alikes.
    const auto bitmap = [](const char* s) {
        Image8 image(8, 10);
        draw_text(image, 1, 1, s, kWhite);
        return image.rgb;
    };
    EXPECT_NE(bitmap("0"), bitmap("O"));
    EXPECT_NE(bitmap("1"), bitmap("l"));
    EXPECT_NE(bitmap("5"), bitmap("S"));
    EXPECT_EQ(bitmap("\xE2\x98\x83"), bitmap("\xEF\xBF\xBD")); // unknown: the same box
}

TEST(DrawText, VerticalTextStaysInItsRotatedBox) {
    Image8 image(40, 200);
    const std::string text = "Irradiance E [W/m\xC2\xB2]";
    draw_text_vertical(image, 10, 150, text, kWhite);
    const Box b = ink_box(image, kBlack);
    ASSERT_GT(b.count, 0);
    EXPECT_GE(b.x0, 10);
    EXPECT_LT(b.x1, 10 + text_height(text));
    EXPECT_LE(b.y1, 150);
    EXPECT_GT(b.y0, 150 - text_width(text));
}

TEST(DrawText, ClipsAtTheImageEdges) {
    Image8 image(10, 10);
    draw_text(image, -3, -4, "WWW", kWhite, 2);
    draw_text(image, 8, 8, "WWW", kWhite, 2);
    draw_text(image, -1000000, 1000000, "x", kWhite);
    EXPECT_GT(ink_box(image, kBlack).count, 0);
}

// --- shapes ----------------------------------------------------------------------------------

TEST(DrawShapes, LineIncludesBothEndsAndIsConnected) {
    Image8 image(50, 50);
    draw_line(image, 3, 40, 45, 7, kWhite);
    EXPECT_EQ(image.get(3, 40), kWhite);
    EXPECT_EQ(image.get(45, 7), kWhite);
    const Box b = ink_box(image, kBlack);
    EXPECT_EQ(b.count, 43); // one pixel per column of the major axis
    Image8 h(20, 5);
    draw_line(h, 18, 2, 1, 2, kWhite, 3);
    const Box hb = ink_box(h, kBlack);
    EXPECT_EQ(hb.x0, 0);
    EXPECT_EQ(hb.x1, 19);
    EXPECT_EQ(hb.y0, 1);
    EXPECT_EQ(hb.y1, 3);
}

TEST(DrawShapes, FarAwayLinesAreClippedQuickly) {
    Image8 image(20, 20);
    draw_line(image, -2000000000, 10, 2000000000, 10, kWhite);
    draw_line(image, -50, -50, -10, -70, kWhite);
    const Box b = ink_box(image, kBlack);
    EXPECT_EQ(b.count, 20);
    EXPECT_EQ(b.y0, 10);
}

TEST(DrawShapes, RectanglesClip) {
    Image8 image(10, 10);
    fill_rect(image, -5, -5, 8, 8, kWhite);
    EXPECT_EQ(ink_box(image, kBlack).count, 9);
    Image8 outline(10, 10);
    draw_rect(outline, 2, 2, 5, 4, kWhite);
    EXPECT_EQ(ink_box(outline, kBlack).count, 14);
}

// --- false colour ----------------------------------------------------------------------------

TEST(DrawFalseColour, EndpointsAreViridis) {
    EXPECT_EQ(false_colour(0.0), (Rgb8{68, 1, 84}));
    EXPECT_EQ(false_colour(1.0), (Rgb8{253, 231, 37}));
    EXPECT_EQ(false_colour(-3.0), false_colour(0.0));
    EXPECT_EQ(false_colour(7.0), false_colour(1.0));
    EXPECT_EQ(false_colour(std::nan("")), false_colour(0.0));
    EXPECT_EQ(false_colour(128.0 / 255.0), (Rgb8{33, 145, 140})); // viridis entry 128
}

TEST(DrawFalseColour, LuminanceIncreasesAlongTheMap) {
    double previous = -1.0;
    for (int i = 0; i <= 64; ++i) {
        const double l = srgb_luminance(false_colour(i / 64.0));
        EXPECT_GT(l, previous) << i;
        previous = l;
    }
}

TEST(DrawFalseColour, ScalePositions) {
    EXPECT_DOUBLE_EQ(colour_scale_position(5.0, 0.0, 10.0, false), 0.5);
    EXPECT_DOUBLE_EQ(colour_scale_position(10.0, 1.0, 100.0, true), 0.5);
    EXPECT_EQ(colour_scale_position(0.0, 1.0, 100.0, true), 0.0);
    EXPECT_EQ(colour_scale_position(1e9, 1.0, 100.0, true), 1.0);
    EXPECT_EQ(colour_scale_position(std::nan(""), 1.0, 100.0, false), 0.0);
}

TEST(DrawFalseColour, LegendBarRunsFromLoToHi) {
    Image8 image(160, 240, kWhite);
    draw_colour_legend(image, 20, 30, 20, 180, 0.01, 1000.0, "E [lux]", true);
    EXPECT_EQ(image.get(30, 30 + 179), false_colour(0.5 / 180)); // bottom row: lo
    EXPECT_EQ(image.get(30, 30), false_colour(1.0 - 0.5 / 180)); // top row: hi
    // Labels to the right of the bar, the unit above it.
    Box right;
    for (int y = 0; y < image.height; ++y)
        for (int x = 42; x < image.width; ++x)
            if (!(image.get(x, y) == kWhite)) right.count++;
    EXPECT_GT(right.count, 0);
    const Box above = ink_box(image, kWhite);
    EXPECT_LT(above.y0, 30 - 1);

    Image8 h(300, 60, kWhite);
    draw_colour_legend(h, 10, 20, 280, 12, 0.0, 250.0, "B", false);
    EXPECT_EQ(h.get(10, 25), false_colour(0.5 / 280));
    EXPECT_EQ(h.get(289, 25), false_colour(1.0 - 0.5 / 280));
    EXPECT_LT(ink_box(h, kWhite).y1, 20 + 12 + 16);
}

// --- contact sheet ---------------------------------------------------------------------------

TEST(DrawContactSheet, DimensionsAndPlacement) {
    std::vector<Image8> frames = {Image8(30, 20, {200, 0, 0}), Image8(40, 10, {0, 200, 0}),
                                  Image8(25, 25, {0, 0, 200})};
    const Image8 sheet = contact_sheet(frames, {"red", "green", "blue"}, 2);
    const int pad = kContactSheetPad, cap = kContactSheetCaption;
    EXPECT_EQ(sheet.width, 2 * (40 + pad) + pad);
    EXPECT_EQ(sheet.height, 2 * (25 + cap + pad) + pad);
    // Frame 0 centred in cell (0, 0); frame 2 in cell (0, 1).
    EXPECT_EQ(sheet.get(pad + 5, pad + 2), (Rgb8{200, 0, 0}));
    EXPECT_EQ(sheet.get(pad + 5 + 29, pad + 2 + 19), (Rgb8{200, 0, 0}));
    EXPECT_NE(sheet.get(pad + 4, pad + 2), (Rgb8{200, 0, 0}));
    EXPECT_EQ(sheet.get(pad + 40 + pad + 0, pad + 7), (Rgb8{0, 200, 0}));
    const int row1 = pad + 25 + cap + pad;
    EXPECT_EQ(sheet.get(pad + 7, row1), (Rgb8{0, 0, 200}));

    const Image8 no_captions = contact_sheet(frames, {}, 5);
    EXPECT_EQ(no_captions.width, 3 * (40 + pad) + pad);
    EXPECT_EQ(no_captions.height, 25 + 2 * pad);
    EXPECT_TRUE(contact_sheet({}, {}, 3).empty());
}

TEST(DrawContactSheet, LongCaptionsAreCutToTheCell) {
    std::vector<Image8> frames = {Image8(40, 20, kWhite), Image8(40, 20, kWhite)};
    const Image8 sheet = contact_sheet(frames, {"a caption much longer than forty pixels", ""}, 2);
    // Nothing drawn into the second cell's caption strip.
    const int x0 = kContactSheetPad + 40 + kContactSheetPad;
    for (int y = kContactSheetPad + 20; y < sheet.height; ++y)
        for (int x = x0; x < x0 + 40; ++x) ASSERT_EQ(sheet.get(x, y), (Rgb8{40, 40, 40}));
}

// --- plots -----------------------------------------------------------------------------------

TEST(DrawPlot, HorizontalLineOnLogAxesLandsOnItsRow) {
    // y from 1.5 to 90: the axis is rounded out to the decades 1 .. 100, so y = 10 is the
    // middle of the plot area.
    const Rgb8 red{214, 39, 40};
    std::vector<PlotSeries> series = {
        {"ten", {0, 10}, {10, 10}, red},
        {"low", {0, 10}, {1.5, 1.5}, plot_palette(0)},
        {"high", {0, 10}, {90, 90}, plot_palette(2)},
    };
    PlotFrame f;
    const Image8 image = plot_lines(series, "Log plot", "x", "y", true, 400, 300, &f);
    EXPECT_EQ(image.width, 400);
    EXPECT_EQ(image.height, 300);
    EXPECT_DOUBLE_EQ(f.y0, 1.0);
    EXPECT_DOUBLE_EQ(f.y1, 100.0);
    EXPECT_DOUBLE_EQ(f.x0, 0.0);
    EXPECT_DOUBLE_EQ(f.x1, 10.0);
    const double middle = 0.5 * (f.top + f.bottom);
    for (double x : {1.0, 2.5, 4.0}) { // left of the legend
        const int col = int(std::lround(f.px(x)));
        const std::vector<int> rows = rows_of(image, col, red);
        ASSERT_EQ(rows.size(), 1u) << x;
        EXPECT_NEAR(rows[0], middle, 1.0) << x;
    }
    // The decade tick at 10 is drawn on the axis at the same row.
    const std::vector<int> ticks = rows_of(image, f.left - 2, kBlack);
    EXPECT_NE(std::find_if(ticks.begin(), ticks.end(),
                           [&](int r) { return std::abs(r - middle) <= 1.0; }),
              ticks.end());
}

TEST(DrawPlot, LinearAxesMapTheEnds) {
    const Rgb8 c = plot_palette(1);
    PlotFrame f;
    const Image8 image =
        plot_lines({{"", {0, 1, 2, 3, 4}, {0, 2, 4, 6, 8}, c}}, "", "", "", false, 300, 200, &f);
    EXPECT_DOUBLE_EQ(f.y0, 0.0);
    EXPECT_DOUBLE_EQ(f.y1, 8.0);
    EXPECT_EQ(image.get(f.left + 1, f.bottom - 1), c);
    EXPECT_EQ(image.get(f.right - 1, f.top + 1), c);
    EXPECT_EQ(image.get(f.left + 1, f.top + 1), kWhite);
}

TEST(DrawPlot, NonFiniteAndNonPositiveValuesAreSkippedOnLogAxes) {
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    const Rgb8 c = plot_palette(3);
    PlotFrame f;
    const PlotSeries s{
        "residual", {0, 1, 2, 3, 4, 5, 6}, {1e-1, 0.0, -1.0, nan, inf, 1e-3, 1e-4}, c};
    const Image8 image = plot_lines({s}, "Convergence", "shot", "bound", true, 320, 240, &f);
    EXPECT_DOUBLE_EQ(f.y0, 1e-4);
    EXPECT_DOUBLE_EQ(f.y1, 1e-1);
    EXPECT_DOUBLE_EQ(f.x1, 6.0);
    // Points 5 and 6 are joined; point 0 stands alone (a dot), nothing between 0 and 5.
    const int col = int(std::lround(f.px(2.5)));
    EXPECT_TRUE(rows_of(image, col, c).empty());
    EXPECT_FALSE(rows_of(image, int(std::lround(f.px(5.5))), c).empty());
    // The dot at (0, 0.1) sits on the top-left corner of the frame: its inner pixel shows.
    EXPECT_EQ(image.get(f.left + 1, f.top + 1), c);
}

TEST(DrawPlot, EmptyAndDegenerateInputsStillDrawAxes) {
    PlotFrame f;
    Image8 image = plot_lines({}, "nothing", "x", "y", true, 200, 150, &f);
    EXPECT_LT(f.left, f.right);
    EXPECT_LT(f.top, f.bottom);
    image = plot_lines({{"one", {3}, {5}, plot_palette(0)}}, "", "", "", false, 200, 150, &f);
    EXPECT_LT(f.x0, 3.0);
    EXPECT_GT(f.x1, 3.0);
    EXPECT_LT(f.y0, 5.0);
    EXPECT_GT(f.y1, 5.0);
    EXPECT_EQ(image.get(int(std::lround(f.px(3))), int(std::lround(f.py(5)))), plot_palette(0));
}

// --- samples for a person to look at ---------------------------------------------------------

TEST(DrawDemo, WritesASampleContactSheetAndPlot) {
    const char* env = std::getenv("HEMIRAD_DRAW_DEMO_DIR");
    const fs::path dir = env ? fs::path(env) : fs::temp_directory_path() / "hemirad_draw_demo";
    fs::create_directories(dir);

    // Frames: a synthetic "render" (a lit floor with a bright light), tone mapped each way,
    // and a false-colour view of the same values with its legend.
    const int w = 160, h = 120;
    ImageRGB render(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double dx = (x - 80.0) / 60.0, dy = (y - 20.0) / 60.0;
            const double e = 1.0 / std::pow(1.0 + dx * dx + dy * dy, 2.0);
            float* p = render.at(x, y);
            const bool light = std::abs(x - 80) < 12 && y < 6;
            p[0] = float(light ? 50.0 : 0.9 * e);
            p[1] = float(light ? 50.0 : 0.6 * e);
            p[2] = float(light ? 50.0 : 0.4 * e);
        }
    std::vector<Image8> frames;
    std::vector<std::string> captions;
    for (auto [op, name] : {std::pair{ToneMap::Clamp, "clamp"},
                            {ToneMap::Reinhard, "reinhard"},
                            {ToneMap::Aces, "aces"}}) {
        ToneMap tm;
        tm.op = op;
        frames.push_back(tone_map(render, tm));
        captions.push_back(std::string("tone map: ") + name);
    }
    Image8 fc(w, h, kWhite);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w - 50; ++x) {
            const float* p = render.at(x, y);
            const double l = luminance(p[0], p[1], p[2]);
            fc.set(x, y, false_colour(colour_scale_position(l, 0.01, 100.0, true)));
        }
    draw_colour_legend(fc, w - 46, 14, 10, h - 24, 0.01, 100.0, "W/m\xC2\xB2", true);
    frames.push_back(fc);
    captions.push_back("false colour, log");
    Image8 font(w, h, {20, 20, 20});
    draw_text(font, 4, 4,
              " !\"#$%&'()*+,-./\n0123456789:;<=>?\n@ABCDEFGHIJKLMNO\nPQRSTUVWXYZ[\\]^_", kWhite);
    draw_text(font, 4, 46,
              "`abcdefghijklmno\npqrstuvwxyz{|}~\n\xC2\xB0\xC2\xB2\xC2\xB3\xC2\xB5"
              "\xC2\xB7\xC3\x97\xCF\x81\xCF\x80 \xE2\x98\x83",
              {255, 220, 120});
    draw_text(font, 4, 82, "Scale 2", {120, 200, 255}, 2);
    frames.push_back(font);
    captions.push_back("the built-in font");
    Image8 legend(w, h, kWhite);
    draw_colour_legend(legend, 10, 30, w - 20, 14, 0.0, 250.0, "E [lux]", false);
    draw_colour_legend(legend, 10, 80, w - 20, 14, 0.5, 20.0, "short log range", true);
    frames.push_back(legend);
    captions.push_back("horizontal legends");
    const Image8 sheet = contact_sheet(frames, captions, 3);
    write_png((dir / "contact_sheet.png").string(), sheet);

    // A convergence plot: three error bounds falling over shots, on log axes.
    std::vector<PlotSeries> series;
    const char* names[] = {"bound, rho 0.5", "bound, rho 0.8", "residual (measured)"};
    for (int s = 0; s < 3; ++s) {
        PlotSeries p;
        p.label = names[s];
        p.colour = plot_palette(s);
        for (int i = 0; i <= 400; ++i) {
            p.x.push_back(i);
            const double rate = s == 0 ? 0.02 : s == 1 ? 0.008 : 0.012;
            p.y.push_back(3.0 * std::exp(-rate * i) * (1 + 0.2 * std::sin(i * 0.3 + s)));
        }
        series.push_back(p);
    }
    const Image8 plot =
        plot_lines(series, "Error bound per shot", "shot", "||B - B*||1 bound [W]", true, 640, 400);
    write_png((dir / "plot_log.png").string(), plot);
    const Image8 lin = plot_lines(
        {{"row sum", {0, 1, 2, 3, 4, 5}, {0.98, 1.01, 0.995, 1.0, 0.97, 1.02}, plot_palette(4)}},
        "Row sums", "shot", "sum F A / A_S", false, 480, 300);
    write_png((dir / "plot_linear.png").string(), lin);
    EXPECT_EQ(read_png((dir / "plot_log.png").string()).rgb, plot.rgb);
    EXPECT_EQ(read_png((dir / "contact_sheet.png").string()).width, sheet.width);
}
