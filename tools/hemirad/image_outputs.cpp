#include "image_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <vector>

#include "core/parse.h"
#include "hemirad/draw.h"
#include "hemirad/error.h"
#include "hemirad/image.h"
#include "hemirad/photometry.h"
#include "hemirad/render.h"

namespace hemirad::cli {

namespace {

std::string extension_of(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string e = path.substr(dot);
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

/// Parses --exposure: "auto", "auto+S", "auto-S" or a number S. Returns (auto?, stops).
std::pair<bool, double> parse_exposure(const std::string& text) {
    std::string rest = text;
    bool automatic = false;
    if (rest.rfind("auto", 0) == 0) {
        automatic = true;
        rest = rest.substr(4);
        if (rest.empty()) return {true, 0.0};
        if (rest[0] == '+') rest = rest.substr(1);
    }
    double stops = 0;
    const NumberRead r = read_double(rest.data(), rest.data() + rest.size(), stops);
    if (rest.empty() || r.end != rest.data() + rest.size() || !std::isfinite(stops))
        throw InputError("--exposure '" + text +
                         "': expected auto, auto+S, auto-S or a number of stops S");
    return {automatic, stops};
}

bool is_camera_list(const std::string& text) {
    return text.find(',') != std::string::npos;
}

Camera choose_camera(const std::string& text, const Scene& scene) {
    if (text.empty()) return default_camera(scene);
    if (is_camera_list(text)) return parse_camera(text);
    std::string names;
    for (const Camera& c : scene.cameras) {
        if (c.name == text) return c;
        names += (names.empty() ? "" : ", ") + c.name;
    }
    // A scene without cameras has the framed view, named "default".
    if (scene.cameras.empty() && text == "default") return default_camera(scene);
    if (scene.cameras.empty()) names = "default";
    throw InputError("--camera '" + text + "': the scene has no camera of that name (" +
                     (names.empty() ? std::string("it has none") : "it has: " + names) +
                     "); give eye,target,up,fov for another view");
}

RenderOptions render_options(const ImageOutputOptions& o, Solver& solver) {
    RenderOptions r;
    r.width = o.width;
    r.height = o.height;
    r.shading = o.shading == "flat" ? RenderOptions::Shading::Flat : RenderOptions::Shading::Smooth;
    r.patch_edges = o.patch_edges;
    r.two_sided = o.two_sided;
    (void)solver;
    return r; // the estimate of the light not yet shot is in by default (RenderOptions::ambient)
}

/// The false-colour image: the luminance of E per pixel mapped through viridis, with a legend
/// panel on the right. Pixels where no surface is (marked by a negative background) are grey.
Image8 false_colour_view(const ImageRGB& E, bool log_scale, bool lux, double* lo_out,
                         double* hi_out) {
    ColourRange range;
    const Image8 view = false_colour_luminance(E, lux ? kLumensPerWatt : 1.0, log_scale, range);
    const double lo = range.lo, hi = range.hi;
    *lo_out = lo;
    *hi_out = hi;

    constexpr int kPanel = 130; // legend panel width [pixels]
    Image8 out(E.width + kPanel, std::max(E.height, 120), Rgb8{255, 255, 255});
    blit(out, view, 0, 0);
    const std::string unit = lux ? "lux (assumes metres)" : "E, W/unit²";
    const int bar_top = 28, bar_h = std::max(out.height - 48, 40);
    draw_colour_legend(out, E.width + 14, bar_top, 16, bar_h, lo, hi, unit, log_scale);
    return out;
}

} // namespace

void add_image_options(ArgParser& args, ImageOutputOptions& o) {
    args.section("images");
    args.multi("-o", &o.files, "FILE",
               "write a view of the radiosity: .exr (linear, W/unit²) or .png (tone-mapped "
               "sRGB); repeatable");
    args.option("--camera", &o.camera, "E,T,U,FOV|NAME",
                "view: eye,target,up (x,y,z each) and vertical fov in degrees, or the name of "
                "a camera of the scene (empty: the scene's first camera, or for a scene without "
                "one a view framing its lit surfaces)");
    args.option("--width", &o.width, "W", "image width [pixels] (16..8192)");
    args.option("--height", &o.height, "H", "image height [pixels] (16..8192)");
    args.option("--shading", &o.shading, "MODE",
                "smooth (area-weighted vertex averages, interpolated) or flat (per patch)");
    args.flag("--patch-edges", &o.patch_edges, "draw the leaf patch edges as dark lines");
    args.option("--discontinuities", &o.discontinuities, "on|off",
                "images and lightmaps: leaves that straddle a shadow edge or contact line get "
                "the direct light's detail inside them (off: the leaves only)");
    args.flag("--two-sided", &o.two_sided,
              "draw the backs of polygons (black) instead of culling them (by default a view "
              "from outside a closed room sees into it)");
    args.flag("--ambient", &o.ambient,
              "kept for scripts: images (like every read-out) include the estimate of the light "
              "not yet shot anyway");
    args.flag("--exr-float", &o.exr_float, "write EXR with 32-bit floats (default: half)");
    args.option("--exposure", &o.exposure, "auto|auto+S|S",
                "PNG exposure: auto (95th percentile of luminance -> 1), S stops from auto, or a "
                "fixed scale 2^S");
    args.option("--false-colour", &o.false_colour, "FILE.png",
                "write a false-colour view of the irradiance E (luminance) with a legend");
    args.option("--false-colour-scale", &o.false_colour_scale, "SCALE",
                "false-colour scale: log (3 decades under the maximum) or linear (0..maximum)");
    args.flag("--lux", &o.lux, "false colour in lux: E * 683 lm/W (assumes metres)");
}

void validate_image_options(const ImageOutputOptions& o) {
    if (o.discontinuities != "on" && o.discontinuities != "off")
        throw InputError("--discontinuities '" + o.discontinuities + "' must be on or off");
    for (const std::string& f : o.files) {
        const std::string e = extension_of(f);
        if (e != ".exr" && e != ".png")
            throw InputError("-o " + f + ": unknown image type '" +
                             (e.empty() ? std::string("(no extension)") : e) +
                             "' (expected .exr or .png)");
    }
    if (!o.false_colour.empty() && extension_of(o.false_colour) != ".png")
        throw InputError("--false-colour " + o.false_colour + ": expected a .png file");
    if (o.width < 16 || o.width > 8192)
        throw InputError("--width " + std::to_string(o.width) + " must be in 16..8192");
    if (o.height < 16 || o.height > 8192)
        throw InputError("--height " + std::to_string(o.height) + " must be in 16..8192");
    if (o.shading != "smooth" && o.shading != "flat")
        throw InputError("--shading '" + o.shading + "': expected smooth or flat");
    if (o.false_colour_scale != "log" && o.false_colour_scale != "linear")
        throw InputError("--false-colour-scale '" + o.false_colour_scale +
                         "': expected log or linear");
    parse_exposure(o.exposure);
    if (is_camera_list(o.camera)) parse_camera(o.camera);
}

void check_image_camera(const ImageOutputOptions& o, const Scene& scene) {
    if (image_outputs_need_gl(o) && !o.camera.empty()) choose_camera(o.camera, scene);
}

bool image_outputs_need_gl(const ImageOutputOptions& o) {
    return !o.files.empty() || !o.false_colour.empty();
}

void write_image_outputs(const ImageOutputOptions& o, Solver& solver, bool quiet) {
    if (!image_outputs_need_gl(o)) return;
    const Scene& scene = solver.scene();
    const Camera camera = choose_camera(o.camera, scene);
    const Hierarchy& h = solver.solution();
    SolutionRenderer renderer(scene);
    const RenderOptions ro = render_options(o, solver);
    (void)quiet;
    const char* shading = o.shading.c_str();
    if (!o.files.empty()) {
        ImageRGB image = renderer.render(h, camera, ro);
        if (o.discontinuities == "on") {
            const DiscontinuityStats d = resolve_discontinuities(image, h, camera, ro);
            if (!quiet && d.pixels > 0)
                std::fprintf(stderr,
                             "hemirad: %zu leaves straddle a shadow edge; %zu pixels evaluated "
                             "at the point (%.2f s)\n",
                             d.leaves, d.pixels, d.seconds);
        }
        const auto [automatic, stops] = parse_exposure(o.exposure);
        for (const std::string& f : o.files) {
            if (extension_of(f) == ".exr") {
                write_exr(f, image, !o.exr_float);
                if (!quiet)
                    std::fprintf(stderr,
                                 "hemirad: wrote %s (%dx%d, %s-float EXR, radiosity W/unit², "
                                 "%s, camera %s)\n",
                                 f.c_str(), image.width, image.height,
                                 o.exr_float ? "32-bit" : "half", shading, camera.name.c_str());
            } else {
                ToneMap tm;
                tm.auto_exposure = automatic;
                tm.exposure = stops;
                const double k = (automatic ? auto_exposure_scale(image) : 1.0) * std::exp2(stops);
                write_png(f, tone_map(image, tm));
                if (!quiet)
                    std::fprintf(stderr,
                                 "hemirad: wrote %s (%dx%d, sRGB PNG, exposure scale %.4g%s, "
                                 "%s, camera %s)\n",
                                 f.c_str(), image.width, image.height, k,
                                 automatic ? " (auto)" : "", shading, camera.name.c_str());
            }
        }
    }
    if (!o.false_colour.empty()) {
        RenderOptions fo = ro;
        fo.quantity = RenderOptions::Quantity::Irradiance;
        fo.patch_edges = false;      // the edges would change the values shown
        fo.background = dvec3(-1.0); // marks "no surface" for false_colour_view
        ImageRGB E = renderer.render(h, camera, fo);
        if (o.discontinuities == "on") resolve_discontinuities(E, h, camera, fo);
        double lo = 0, hi = 0;
        const Image8 view = false_colour_view(E, o.false_colour_scale == "log", o.lux, &lo, &hi);
        write_png(o.false_colour, view);
        if (!quiet)
            std::fprintf(stderr,
                         "hemirad: wrote %s (false colour of irradiance luminance, %s scale "
                         "%.4g..%.4g %s)\n",
                         o.false_colour.c_str(), o.false_colour_scale.c_str(), lo, hi,
                         o.lux ? "lux (assumes metres)" : "W/unit²");
    }
}

} // namespace hemirad::cli
