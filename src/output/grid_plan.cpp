// A calculation grid as a false-colour plan with its values printed (grid.h, grid_plan_image).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hemirad/draw.h"
#include "hemirad/grid.h"

namespace hemirad {

namespace {

std::string format_value(double v) {
    char buf[32];
    if (v >= 1000)
        std::snprintf(buf, sizeof buf, "%.0f", v);
    else if (v >= 100)
        std::snprintf(buf, sizeof buf, "%.0f", v);
    else if (v >= 10)
        std::snprintf(buf, sizeof buf, "%.1f", v);
    else if (v >= 0.01 || v == 0)
        std::snprintf(buf, sizeof buf, "%.2f", v);
    else
        std::snprintf(buf, sizeof buf, "%.1e", v);
    return buf;
}

} // namespace

Image8 grid_plan_image(const GridResult& g, bool lux, const std::vector<Luminaire>& luminaires,
                       double daylight_lux) {
    const int nx = g.spec.nx, ny = g.spec.ny;
    // Daylight factor DF = 100 E / E_h % in the cells when daylight_lux (E_h) is given.
    const bool df = daylight_lux > 0;
    const double k = df ? 100 * kLumensPerWatt / daylight_lux : lux ? kLumensPerWatt : 1.0;
    const double hi = k * g.Y_max > 0 ? k * g.Y_max : 1.0;
    // Cells to scale (720 pixels for the longer side), each 3..72 pixels.
    const double longer = std::max({g.width, g.height, 1e-300});
    const double px = 720 / longer; // pixels per scene unit
    const int cw = std::clamp(int(std::lround(px * g.width / nx)), 3, 72);
    const int ch = std::clamp(int(std::lround(px * g.height / ny)), 3, 72);
    const int plan_w = nx * cw, plan_h = ny * ch;
    const std::string title = "grid " + g.spec.group + " " + std::to_string(nx) + "x" +
                              std::to_string(ny) + " (" + std::to_string(g.evaluated) +
                              " points), plan seen from the front: u right, v up";
    const std::string summary = grid_summary(g, lux, daylight_lux);
    constexpr int kLeft = 10, kTop = 34, kPanel = 130, kBottom = 12;
    const int width = std::max(kLeft + plan_w + kPanel,
                               kLeft + std::max(text_width(title), text_width(summary)) + 10);
    const int height = kTop + std::max(plan_h, 120) + kBottom;
    Image8 img(width, height, Rgb8{255, 255, 255});
    const Rgb8 ink{0, 0, 0};
    draw_text(img, kLeft, 6, title, ink);
    draw_text(img, kLeft, 18, summary, ink);

    for (const GridPoint& p : g.points) {
        const int x = kLeft + p.i * cw, y = kTop + (ny - 1 - p.j) * ch;
        if (!p.on_surface) {
            fill_rect(img, x, y, cw, ch, Rgb8{170, 170, 170});
            continue;
        }
        const double v = k * luminance(p.E.x, p.E.y, p.E.z);
        const Rgb8 c = false_colour(colour_scale_position(v, 0, hi, false));
        fill_rect(img, x, y, cw, ch, c);
        const std::string text = format_value(v);
        if (ch >= 10 && text_width(text) <= cw - 2) {
            const bool light = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b > 128;
            draw_text(img, x + (cw - text_width(text)) / 2, y + (ch - text_height(text)) / 2, text,
                      light ? Rgb8{0, 0, 0} : Rgb8{255, 255, 255});
        }
    }
    if (cw >= 6)
        for (int i = 0; i <= nx; ++i)
            fill_rect(img, kLeft + i * cw, kTop, 1, plan_h, Rgb8{255, 255, 255});
    if (ch >= 6)
        for (int j = 0; j <= ny; ++j)
            fill_rect(img, kLeft, kTop + j * ch, plan_w, 1, Rgb8{255, 255, 255});
    draw_rect(img, kLeft - 1, kTop - 1, plan_w + 2, plan_h + 2, ink);

    // Luminaires in front of the plane, over the grid: a cross and the name.
    for (const Luminaire& l : luminaires) {
        const dvec3 d = l.position - g.origin;
        if (!(glm::dot(d, g.normal) > 0) || !(g.width > 0) || !(g.height > 0)) continue;
        const double u = glm::dot(d, g.axis_u) / g.width, v = glm::dot(d, g.axis_v) / g.height;
        if (u < 0 || u > 1 || v < 0 || v > 1) continue;
        const int x = kLeft + int(std::lround(u * plan_w));
        const int y = kTop + int(std::lround((1 - v) * plan_h));
        const Rgb8 red{228, 26, 28};
        draw_line(img, x - 5, y - 5, x + 5, y + 5, red, 2);
        draw_line(img, x - 5, y + 5, x + 5, y - 5, red, 2);
        fill_rect(img, x + 7, y - 5, text_width(l.name) + 2, 10, Rgb8{255, 255, 255});
        draw_text(img, x + 8, y - 4, l.name, red);
    }
    draw_colour_legend(img, kLeft + plan_w + 24, kTop + 12, 16, std::max(plan_h - 24, 80), 0, hi,
                       df    ? "DF %"
                       : lux ? "lux"
                             : "E, W/unit²",
                       false);
    return img;
}

} // namespace hemirad
