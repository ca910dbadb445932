// hemirad-preview: solves a scene headless and writes a frame of the converging solution every
// N shots (or T seconds), then a contact sheet, a convergence plot and a CSV of the run. Same
// scene loading, Solver loop and SolutionRenderer as `hemirad solve`; one GL context, shared
// by the GPU form-factor provider and the renderer.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "cli/cli_options.h"
#include "cli/tool_main.h"
#include "hemirad/draw.h"
#include "hemirad/error.h"
#include "hemirad/gl/context.h"
#include "hemirad/image.h"
#include "hemirad/render.h"
#include "hemirad/solver.h"

namespace hemirad::tool {
namespace {

constexpr const char* kTool = "hemirad-preview";

struct Options {
    std::string scene, out;
    long every = 0;           ///< a frame every N shots (0: not by shots)
    double every_seconds = 0; ///< a frame every T seconds of solving (0: not by time)
    int width = 256, height = 256;
    std::string camera; ///< "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov"; empty: scene default
    bool no_ambient = false, flat = false, exr = false, quiet = false;
    bool two_sided = false; ///< draw the backs of polygons (black) instead of culling
    double exposure = 0;    ///< [stops] on top of each frame's auto exposure
    int sheet_frames = 24;  ///< at most this many frames on the contact sheet
    int sheet_columns = 6;
};

struct Sample {
    long shot;
    double seconds, unshot_fraction, error_bound;
};

struct Frame {
    long shot;
    double error_bound;
    std::string png;
};

std::string frame_name(long shot, const char* ext) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "frame_%05ld.%s", shot, ext);
    return buf;
}

std::string format_seconds(double s) {
    char buf[32];
    if (!std::isfinite(s) || s < 0) return "?";
    if (s < 10)
        std::snprintf(buf, sizeof buf, "%.1f s", s);
    else if (s < 60)
        std::snprintf(buf, sizeof buf, "%.0f s", s);
    else if (s < 3600)
        std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    else
        std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, int(s) % 3600 / 60);
    return buf;
}

/// Progress towards the nearest stop criterion, in [0, 1]: the largest of shots / max_shots,
/// seconds / time_limit and log(b0 / b) / log(b0 / tolerance) (the error bound falls about
/// geometrically, so its logarithm progresses about linearly).
double progress(const Solver& s, double first_bound) {
    const SolverOptions& o = s.options();
    double f = 0;
    if (o.max_shots > 0) f = std::max(f, double(s.shots()) / double(o.max_shots));
    if (o.time_limit > 0) f = std::max(f, s.seconds() / o.time_limit);
    const double b = s.error_bound();
    if (first_bound > o.tolerance && b > 0 && b < first_bound)
        f = std::max(f, std::log(first_bound / b) / std::log(first_bound / o.tolerance));
    return std::clamp(f, 0.0, 1.0);
}

class Progress {
  public:
    Progress(bool tty, bool quiet) : tty_(tty && !quiet), quiet_(quiet) {}

    /// Terminal: a bar with ETA, at most 4 times a second.
    void update(const Solver& s, double first_bound, long frames) {
        if (!tty_) return;
        const auto now = std::chrono::steady_clock::now();
        if (now - last_ < std::chrono::milliseconds(250)) return;
        last_ = now;
        const double f = progress(s, first_bound);
        const double elapsed = s.seconds();
        const double eta = f > 1e-3 ? elapsed * (1 - f) / f : -1;
        constexpr int kBar = 24;
        std::string bar(kBar, '.');
        std::fill_n(bar.begin(), int(std::lround(f * kBar)), '#');
        std::fprintf(stderr, "\r[%s] %3.0f%%  shot %ld  bound %.2e  frames %ld  %s  ETA %s   ",
                     bar.c_str(), 100 * f, s.shots(), s.error_bound(), frames,
                     format_seconds(elapsed).c_str(), format_seconds(eta).c_str());
        shown_ = true;
    }
    /// Not a terminal: one plain line per frame written.
    void frame(const Solver& s, const std::string& name) {
        if (tty_ || quiet_) return;
        std::fprintf(stderr, "%s: %s  shot %ld  unshot %.3e  bound %.3e  %.2f s\n", kTool,
                     name.c_str(), s.shots(), s.unshot_fraction(), s.error_bound(), s.seconds());
    }
    void clear() {
        if (shown_) std::fprintf(stderr, "\r%*s\r", 100, "");
        shown_ = false;
    }

  private:
    bool tty_, quiet_, shown_ = false;
    std::chrono::steady_clock::time_point last_{};
};

volatile sig_atomic_t g_interrupted = 0;
extern "C" void on_signal(int) {
    g_interrupted = 1;
}

void validate(const Options& o, const ArgParser& args) {
    if (o.out.empty()) throw InputError("--out DIR is required");
    if (o.every < 0 || (args.given("--every") && o.every == 0))
        throw InputError("--every " + std::to_string(o.every) + " must be > 0");
    if (!(o.every_seconds >= 0) || !std::isfinite(o.every_seconds) ||
        (args.given("--every-seconds") && o.every_seconds == 0))
        throw InputError("--every-seconds " + std::to_string(o.every_seconds) + " must be > 0");
    if (o.every == 0 && o.every_seconds == 0)
        throw InputError("--every N (shots, N > 0) or --every-seconds T (T > 0) is required");
    if (o.width < 16 || o.width > 8192 || o.height < 16 || o.height > 8192)
        throw InputError("--width/--height " + std::to_string(o.width) + "x" +
                         std::to_string(o.height) + " must be in 16..8192");
    if (!std::isfinite(o.exposure)) throw InputError("--exposure must be finite");
    if (o.sheet_frames < 1) throw InputError("--sheet-frames must be >= 1");
    if (o.sheet_columns < 1) throw InputError("--sheet-columns must be >= 1");
}

void make_directory(const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(dir, ec)) return;
    if (fs::exists(dir, ec)) throw InputError("--out " + dir + ": exists and is not a directory");
    fs::create_directories(dir, ec);
    if (ec) throw RuntimeError("cannot create directory " + dir + ": " + ec.message());
}

/// Up to `n` of the frames, evenly spread, always the first and the last.
std::vector<const Frame*> pick_frames(const std::vector<Frame>& frames, int n) {
    std::vector<const Frame*> out;
    const int count = int(frames.size());
    if (count <= n) {
        for (const Frame& f : frames) out.push_back(&f);
        return out;
    }
    for (int i = 0; i < n; ++i)
        out.push_back(&frames[std::size_t(std::lround(double(i) * (count - 1) / (n - 1)))]);
    return out;
}

void write_csv(const std::string& path, const std::vector<Sample>& samples) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::trunc);
        if (!f) throw RuntimeError("cannot write " + tmp);
        f << "shot,seconds,unshot_fraction,error_bound\n";
        char line[160];
        for (const Sample& s : samples) {
            std::snprintf(line, sizeof line, "%ld,%.6f,%.9g,%.9g\n", s.shot, s.seconds,
                          s.unshot_fraction, s.error_bound);
            f << line;
        }
        f.close();
        if (!f) throw RuntimeError("error writing " + tmp);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw RuntimeError("cannot rename " + tmp + " to " + path + ": " + ec.message());
}

/// Error bound and unshot fraction against shots (left) and seconds (right), log y.
Image8 convergence_plot(const std::vector<Sample>& samples, double tolerance) {
    PlotSeries bound{"error bound", {}, {}, plot_palette(0)};
    PlotSeries unshot{"unshot fraction", {}, {}, plot_palette(1)};
    PlotSeries tol{"tolerance", {}, {}, plot_palette(3)};
    PlotSeries bound_t = bound, unshot_t = unshot, tol_t = tol;
    for (const Sample& s : samples) {
        bound.x.push_back(double(s.shot));
        bound.y.push_back(s.error_bound);
        unshot.x.push_back(double(s.shot));
        unshot.y.push_back(s.unshot_fraction);
        bound_t.x.push_back(s.seconds);
        bound_t.y.push_back(s.error_bound);
        unshot_t.x.push_back(s.seconds);
        unshot_t.y.push_back(s.unshot_fraction);
    }
    if (!samples.empty()) {
        tol.x = {double(samples.front().shot), double(samples.back().shot)};
        tol_t.x = {samples.front().seconds, samples.back().seconds};
        tol.y = tol_t.y = {tolerance, tolerance};
    }
    constexpr int kW = 480, kH = 340;
    const Image8 left = plot_lines({bound, unshot, tol}, "convergence vs shots", "shots",
                                   "relative to emitted power", true, kW, kH);
    const Image8 right =
        plot_lines({bound_t, unshot_t, tol_t}, "convergence vs time", "seconds of solving",
                   "relative to emitted power", true, kW, kH);
    Image8 out(2 * kW, kH, {255, 255, 255});
    blit(out, left, 0, 0);
    blit(out, right, kW, 0);
    return out;
}

int run(int argc, char** argv) {
    Options o;
    SolverOptions so;
    BuiltinOptions builtin;
    ObjOptions obj;
    ArgParser args(kTool, "hemirad-preview SCENE --out DIR --every N [options]",
                   "Solves a scene by progressive shooting and writes a frame of the solution\n"
                   "every N shots (or T seconds) as DIR/frame_SHOT.png, then\n"
                   "DIR/contact_sheet.png, DIR/convergence.png and DIR/convergence.csv.");
    args.positional(
        "SCENE", &o.scene,
        std::string("OBJ or glTF (.gltf, .glb) file, SCENE.json (OBJ or glTF files, luminaires, "
                    "cameras) or built-in scene (") +
            builtin_names() + ")");
    args.section("frames");
    args.option("--out", &o.out, "DIR", "output directory (created if missing)");
    args.option("--every", &o.every, "N", "write a frame every N shots (0 = only by time)");
    args.option("--every-seconds", &o.every_seconds, "T",
                "write a frame every T seconds of solving (0 = only by shots)");
    args.option("--width", &o.width, "W", "frame width [pixels]");
    args.option("--height", &o.height, "H", "frame height [pixels]");
    args.option("--camera", &o.camera, "E,T,U,FOV",
                "eye x,y,z, target x,y,z, up x,y,z, vertical fov [deg] (default: the scene's)");
    args.flag("--no-ambient", &o.no_ambient,
              "render without the ambient term (unshot light then shows as black)");
    args.flag("--flat-shading", &o.flat, "one colour per patch instead of smooth shading");
    args.flag("--two-sided", &o.two_sided,
              "draw the backs of polygons (black) instead of culling them");
    args.option("--exposure", &o.exposure, "STOPS", "added to each frame's automatic exposure");
    args.flag("--exr", &o.exr, "also write each frame as linear EXR (frame_SHOT.exr)");
    args.option("--sheet-frames", &o.sheet_frames, "N",
                "at most N frames (evenly spread) on the contact sheet");
    args.option("--sheet-columns", &o.sheet_columns, "N", "columns of the contact sheet");
    args.flag("--quiet", &o.quiet, "print nothing but errors");
    add_solver_options(args, so);
    add_scene_options(args, builtin, obj);
    if (!args.parse(argc, argv)) return 0;
    validate(o, args);
    // Parse everything the user gave before any slow work.
    std::optional<Camera> user_camera;
    if (!o.camera.empty()) user_camera = parse_camera(o.camera);
    const gl::Backend backend = gl::parse_backend(so.provider.gpu.backend);
    make_directory(o.out);
    const std::filesystem::path dir(o.out);

    const Scene scene = load_scene(o.scene, builtin, obj);
    print_scene_warnings(kTool, scene, o.quiet);
    const Camera camera = user_camera ? *user_camera : default_camera(scene);

    // One GL context for the run, shared by the provider and the renderer.
    gl::ContextOptions co;
    co.backend = backend;
    co.device = so.provider.gpu.device;
    std::unique_ptr<gl::Context> context = gl::Context::create(co);
    so.provider.gpu.use_current_context = true;
    if (!o.quiet)
        std::fprintf(stderr, "%s: OpenGL %s: %s (%s)\n", kTool, context->backend_name().c_str(),
                     context->renderer().c_str(), context->vendor().c_str());
    Solver solver(scene, so);
    SolutionRenderer renderer(scene);
    if (!o.quiet)
        std::fprintf(stderr, "%s: %s: %zu polygons, %llu leaf patches, form factors: %s\n", kTool,
                     scene.source.c_str(), scene.polygons.size(),
                     (unsigned long long)solver.hierarchy().leaf_count(),
                     solver.provider().name().c_str());

    RenderOptions ro;
    ro.width = o.width;
    ro.height = o.height;
    ro.ambient = !o.no_ambient;
    ro.shading = o.flat ? RenderOptions::Shading::Flat : RenderOptions::Shading::Smooth;
    ro.two_sided = o.two_sided;
    ToneMap tm;
    tm.exposure = o.exposure;

    std::vector<Sample> samples;
    std::vector<Frame> frames;
    Progress bar(isatty(2) != 0, o.quiet);
    auto write_frame = [&] {
        const ImageRGB image = renderer.render(solver.solution(), camera, ro);
        const std::string png = (dir / frame_name(solver.shots(), "png")).string();
        write_png(png, tone_map(image, tm));
        if (o.exr) write_exr((dir / frame_name(solver.shots(), "exr")).string(), image);
        frames.push_back({solver.shots(), solver.error_bound(), png});
        bar.frame(solver, frame_name(solver.shots(), "png"));
    };
    auto sample = [&] {
        samples.push_back(
            {solver.shots(), solver.seconds(), solver.unshot_fraction(), solver.error_bound()});
    };

    sample();
    write_frame(); // shot 0: only the emitters (and the ambient estimate)
    const double first_bound = solver.error_bound();
    double next_time = o.every_seconds;
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    while (!g_interrupted && solver.step()) {
        sample();
        bool due = o.every > 0 && solver.shots() % o.every == 0;
        if (o.every_seconds > 0 && solver.seconds() >= next_time) {
            due = true;
            while (next_time <= solver.seconds()) next_time += o.every_seconds;
        }
        if (due) write_frame();
        bar.update(solver, first_bound, long(frames.size()));
    }
    if (frames.back().shot != solver.shots()) write_frame(); // the final state
    bar.clear();

    write_csv((dir / "convergence.csv").string(), samples);
    write_png((dir / "convergence.png").string(), convergence_plot(samples, so.tolerance));
    std::vector<Image8> sheet;
    std::vector<std::string> captions;
    for (const Frame* f : pick_frames(frames, o.sheet_frames)) {
        sheet.push_back(read_png(f->png));
        char caption[64];
        std::snprintf(caption, sizeof caption, "shot %ld  bound %.2g", f->shot, f->error_bound);
        captions.push_back(caption);
    }
    write_png((dir / "contact_sheet.png").string(),
              contact_sheet(sheet, captions, std::min(o.sheet_columns, int(sheet.size()))));
    if (!o.quiet)
        std::fprintf(stderr,
                     "%s: %s after %ld shots in %.2f s: error bound %.3e (tolerance %.3g); "
                     "%zu frames, contact_sheet.png, convergence.png, convergence.csv in %s\n",
                     kTool, g_interrupted ? "interrupted" : to_string(solver.stop_reason()),
                     solver.shots(), solver.seconds(), solver.error_bound(), so.tolerance,
                     frames.size(), o.out.c_str());
    return g_interrupted ? 130 : 0;
}

} // namespace
} // namespace hemirad::tool

int main(int argc, char** argv) {
    return hemirad::run_tool(hemirad::tool::kTool, [&] { return hemirad::tool::run(argc, argv); });
}
