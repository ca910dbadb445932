// hemirad-view: an interactive GLFW window on a scene that solves progressively between frames
// and shows the solution as it converges. Same scene loading, Solver and SolutionRenderer as
// `hemirad solve`; the GPU form-factor provider renders its hemicubes in the window's context.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glad/gl.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_options.h"
#include "cli/tool_main.h"
#include "ff/bvh.h"
#include "hemirad/draw.h"
#include "hemirad/error.h"
#include "hemirad/gather.h"
#include "hemirad/image.h"
#include "hemirad/photometry.h"
#include "hemirad/render.h"
#include "hemirad/report.h"
#include "hemirad/solver.h"
#include "orbit_camera.h"
#include "overlay.h"
#if HEMIRAD_VIEWER_PANELS
#include "panels.h"
#endif
#include "pick.h"
#include "script.h"
#include "solve_thread.h"

namespace hemirad::view {
namespace {

constexpr const char* kTool = "hemirad-view";
using Clock = std::chrono::steady_clock;

#if HEMIRAD_VIEWER_PANELS
constexpr bool kPanels = true;
bool ui_wants_mouse() {
    return Panels::wants_mouse();
}
bool ui_wants_keyboard() {
    return Panels::wants_keyboard();
}
#else
constexpr bool kPanels = false;
bool ui_wants_mouse() {
    return false;
}
bool ui_wants_keyboard() {
    return false;
}
#endif

const char* kHelp = "mouse   left drag: orbit    right/middle drag: pan    wheel: zoom\n"
                    "W S / Up Down: fly forward/back    A D / Left Right: sideways\n"
                    "PgUp PgDn: fly up/down    (hold Shift: 4x faster)\n"
                    "R  reset view             F  frame the scene\n"
                    "Space  pause/resume       N  one shot (while paused)\n"
                    "1 / 2  smooth / flat      G  patch edges (grid)\n"
                    "C  false colour (legend)  L  last shooter  I  hemicube\n"
                    "B  ambient term           + / -  exposure up/down (1/2 stop)\n"
                    "O  status line, panels    H / F1  this help\n"
                    "T  backs of polygons      P  panels    Esc / Q  quit";

struct Options {
    std::string scene;
    int width = 960, height = 720;
    double budget_ms = 30;  ///< while solving, at most a frame every budget_ms [ms]
    std::string camera;     ///< empty: the scene's default
    std::string screenshot; ///< FILE.png: save one frame and exit
    long after_shots = -1;  ///< screenshot (or exit) once this many shots are done
    long frames = -1;       ///< screenshot (or exit) at this frame
    bool no_ambient = false, no_overlay = false, flat = false, edges = false, paused = false;
    bool false_colour = false, show_help = false, quiet = false, no_panels = false;
    bool highlight = false, inset = false;
    bool two_sided = false;     ///< draw the backs of polygons (black) instead of culling
    double exposure = 0;        ///< [stops]
    std::string script;         ///< FILE: commands, one a line (script.h)
    std::string units = "auto"; ///< pick values: auto, lux or W
};

/// Everything the input callbacks change.
struct ViewState {
    OrbitCamera camera;
    Bounds bounds;
    bool flat = false, edges = false, false_colour = false, ambient = true;
    bool paused = false, step_once = false, help = false, status = true;
    bool panels = true;     ///< the Dear ImGui panels (key P), shown with the status line (key O)
    bool highlight = false; ///< outline the last shot's shooter (key L)
    bool inset = false;     ///< the last hemicube's IDs and form factors (key I)
    bool two_sided = false; ///< draw the backs of polygons (key T); default: culled
    double exposure = 0;
    int drag_button = -1; ///< GLFW mouse button held, -1 none
    double last_x = 0, last_y = 0;
    bool dirty = true; ///< something changed: draw again
    int fb_height = 1, fb_width = 1;
};

ViewState& state_of(GLFWwindow* w) {
    return *static_cast<ViewState*>(glfwGetWindowUserPointer(w));
}

void on_key(GLFWwindow* w, int key, int, int action, int) {
    ViewState& s = state_of(w);
    s.dirty = true;
    if (ui_wants_keyboard()) return; // typing into a panel
    if (action != GLFW_PRESS && !(action == GLFW_REPEAT && (key == GLFW_KEY_N))) return;
    switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
        glfwSetWindowShouldClose(w, GLFW_TRUE);
        break;
    case GLFW_KEY_R:
        s.camera.reset();
        break;
    case GLFW_KEY_F:
        s.camera.frame(s.bounds, double(s.fb_width) / std::max(s.fb_height, 1));
        break;
    case GLFW_KEY_SPACE:
        s.paused = !s.paused;
        break;
    case GLFW_KEY_N:
        s.paused = true;
        s.step_once = true;
        break;
    case GLFW_KEY_1:
        s.flat = false;
        break;
    case GLFW_KEY_2:
        s.flat = true;
        break;
    case GLFW_KEY_G:
        s.edges = !s.edges;
        break;
    case GLFW_KEY_C:
        s.false_colour = !s.false_colour;
        break;
    case GLFW_KEY_B:
        s.ambient = !s.ambient;
        break;
    case GLFW_KEY_L:
        s.highlight = !s.highlight;
        break;
    case GLFW_KEY_I:
        s.inset = !s.inset;
        break;
    case GLFW_KEY_T:
        s.two_sided = !s.two_sided;
        break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
        s.exposure += 0.5;
        break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
        s.exposure -= 0.5;
        break;
    case GLFW_KEY_O:
        s.status = !s.status;
        break;
    case GLFW_KEY_P:
        s.panels = !s.panels;
        break;
    case GLFW_KEY_H:
    case GLFW_KEY_F1:
        s.help = !s.help;
        break;
    default:
        break;
    }
}

void on_mouse_button(GLFWwindow* w, int button, int action, int) {
    ViewState& s = state_of(w);
    s.dirty = true;
    if (action == GLFW_PRESS && s.drag_button < 0 && !ui_wants_mouse()) {
        s.drag_button = button;
        glfwGetCursorPos(w, &s.last_x, &s.last_y);
    } else if (action == GLFW_RELEASE && button == s.drag_button) {
        s.drag_button = -1;
    }
}

void on_cursor(GLFWwindow* w, double x, double y) {
    ViewState& s = state_of(w);
    if (kPanels && s.panels && s.status) s.dirty = true; // hovering a panel redraws it
    if (s.drag_button < 0) return;
    int ww = 1, wh = 1;
    glfwGetWindowSize(w, &ww, &wh);
    const double dx = x - s.last_x, dy = y - s.last_y;
    s.last_x = x;
    s.last_y = y;
    if (s.drag_button == GLFW_MOUSE_BUTTON_LEFT)
        s.camera.orbit(dx, dy, wh);
    else
        s.camera.pan(dx, dy, wh);
    s.dirty = true;
}

void on_scroll(GLFWwindow* w, double, double yoffset) {
    ViewState& s = state_of(w);
    s.dirty = true;
    if (ui_wants_mouse()) return;
    s.camera.zoom(yoffset);
    s.dirty = true;
}

void on_resize(GLFWwindow* w, int width, int height) {
    ViewState& s = state_of(w);
    s.fb_width = width;
    s.fb_height = height;
    s.dirty = true;
}

volatile sig_atomic_t g_interrupted = 0;
extern "C" void on_signal(int) {
    g_interrupted = 1;
}

std::string g_glfw_error;
void on_glfw_error(int code, const char* text) {
    g_glfw_error = text ? text : ("GLFW error " + std::to_string(code));
}

/// Fly with held keys: `dt` seconds of motion at a quarter of the scene size per second.
void fly(GLFWwindow* w, ViewState& s, double dt) {
    auto down = [w](int key) { return glfwGetKey(w, key) == GLFW_PRESS; };
    const double f = (down(GLFW_KEY_W) || down(GLFW_KEY_UP) ? 1 : 0) -
                     (down(GLFW_KEY_S) || down(GLFW_KEY_DOWN) ? 1 : 0);
    const double r = (down(GLFW_KEY_D) || down(GLFW_KEY_RIGHT) ? 1 : 0) -
                     (down(GLFW_KEY_A) || down(GLFW_KEY_LEFT) ? 1 : 0);
    const double u = (down(GLFW_KEY_PAGE_UP) ? 1 : 0) - (down(GLFW_KEY_PAGE_DOWN) ? 1 : 0);
    if (f == 0 && r == 0 && u == 0) return;
    const bool fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
    const double k = 0.25 * std::min(dt, 0.1) * (fast ? 4 : 1);
    s.camera.fly(f * k, r * k, u * k);
    s.dirty = true;
}

/// The false-colour view of the irradiance, as `hemirad solve --false-colour` draws it: the
/// luminance of E through viridis on a log scale over at most three decades under the
/// maximum; where no surface is (background marked -1) grey. Returns the range, for the legend.
using ColourScale = ColourRange;
Image8 false_colour_image(const ImageRGB& irr, ColourScale& scale) {
    return false_colour_luminance(irr, 1.0, true, scale);
}

Image8 legend_panel(const ColourScale& scale) {
    Image8 img(96, 220, {245, 245, 245});
    draw_colour_legend(img, 8, 18, 16, 190, scale.lo, scale.hi, "E [W/unit\xc2\xb2]", true);
    return img;
}

/// A colour for a patch id: the hue from a 32-bit integer hash (the "lowbias32" finaliser) of
/// the polygon, so that polygons stand apart; the brightness (60..100%) from a hash of the
/// patch (level, index), so that the patches the oracle chose show as a fine mosaic. Every
/// channel stays above 38, unlike the black background and the dark grey backs.
std::uint32_t hash32(std::uint32_t h) {
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}
Rgb8 id_colour(std::uint32_t polygon, std::uint32_t level, std::uint32_t index) {
    const std::uint32_t hp = hash32(polygon + 1), hq = hash32(index * 16 + level + 0x9e3779b9u);
    const double k = (0.6 + 0.4 * (hq & 0xff) / 255.0) / 255.0;
    const auto channel = [&](int shift) {
        return std::uint8_t(std::lround((64 + ((hp >> shift) & 0xff) * 191 / 255) * k * 255));
    };
    return {channel(0), channel(8), channel(16)};
}

/// The last hemicube (FormFactorProvider::last_hemicube()) as two panels side by side, each
/// scaled (nearest pixel) to `panel_w` x `panel_h`: left the patch IDs false-coloured
/// (id_colour; nothing black, backs of polygons dark grey), right the analytic form factor
/// (alpha) through viridis on a log scale over 3 decades under its maximum. Captioned. The
/// hemicube's rows are bottom-up (GL): flipped here.
Image8 hemicube_inset(const FormFactorProvider::HemicubeImage& cube, int panel_w, int panel_h) {
    constexpr int pad = 4;
    const int caption = text_height("X") + 2;
    Image8 img(2 * panel_w + 3 * pad, panel_h + caption + 2 * pad, {24, 24, 28});
    double hi = 0;
    const std::size_t n = std::size_t(cube.width) * cube.height;
    for (std::size_t i = 0; i < n; ++i)
        if (cube.rgba[4 * i + 2] > 0.5f && std::isfinite(cube.rgba[4 * i + 3]))
            hi = std::max(hi, double(cube.rgba[4 * i + 3]));
    if (!(hi > 0)) hi = 1;
    const double lo = hi / 1000;
    const int top = pad + caption;
    for (int y = 0; y < panel_h; ++y) {
        const int cy = cube.height - 1 - std::min(cube.height - 1, y * cube.height / panel_h);
        for (int x = 0; x < panel_w; ++x) {
            const int cx = std::min(cube.width - 1, x * cube.width / panel_w);
            const float* p = &cube.rgba[4 * (std::size_t(cy) * cube.width + cx)];
            Rgb8 id{0, 0, 0}, ff{0, 0, 0};
            if (p[2] > 0.5f) {
                id = id_colour(std::uint32_t(p[2]) - 1, std::uint32_t(p[1]), std::uint32_t(p[0]));
                ff = false_colour(colour_scale_position(std::max(double(p[3]), 0.0), lo, hi, true));
            } else if (p[2] < -0.5f) {
                id = ff = {64, 64, 64};
            }
            img.set(pad + x, top + y, id);
            img.set(2 * pad + panel_w + x, top + y, ff);
        }
    }
    char text[64];
    std::snprintf(text, sizeof text, "F %.0e..%.0e", lo, hi);
    if (text_width(text) > panel_w) std::snprintf(text, sizeof text, "F (log)");
    draw_text(img, pad, pad, "patch IDs", {235, 235, 235});
    draw_text(img, 2 * pad + panel_w, pad, text, {235, 235, 235});
    return img;
}

Image8 read_back_buffer(int width, int height) {
    Image8 img(width, height);
    std::vector<std::uint8_t> rows(std::size_t(width) * height * 3);
    GLint alignment = 4;
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
    glPixelStorei(GL_PACK_ALIGNMENT, alignment);
    const std::size_t stride = std::size_t(width) * 3;
    for (int y = 0; y < height; ++y) // GL row 0 is the bottom
        std::copy_n(&rows[std::size_t(height - 1 - y) * stride], stride, img.at(0, y));
    return img;
}

void validate(const Options& o, const ArgParser& args) {
    if (o.width < 16 || o.width > 8192 || o.height < 16 || o.height > 8192)
        throw InputError("--width/--height " + std::to_string(o.width) + "x" +
                         std::to_string(o.height) + " must be in 16..8192");
    if (!(o.budget_ms > 0 && o.budget_ms <= 10000))
        throw InputError("--budget " + std::to_string(o.budget_ms) + " must be in (0, 10000] ms");
    if (args.given("--after-shots") && o.after_shots < 0)
        throw InputError("--after-shots " + std::to_string(o.after_shots) + " must be >= 0");
    if (args.given("--frames") && o.frames < 1)
        throw InputError("--frames " + std::to_string(o.frames) + " must be >= 1");
    if (!o.screenshot.empty() &&
        (o.screenshot.size() < 4 || o.screenshot.substr(o.screenshot.size() - 4) != ".png"))
        throw InputError("--screenshot " + o.screenshot + ": expected a .png file name");
    if (!std::isfinite(o.exposure)) throw InputError("--exposure must be finite");
    if (o.units != "auto" && o.units != "lux" && o.units != "W")
        throw InputError("--units '" + o.units + "' must be auto, lux or W");
    if (!o.script.empty() &&
        (!o.screenshot.empty() || args.given("--after-shots") || args.given("--frames")))
        throw InputError("--script cannot be combined with --screenshot, --after-shots or "
                         "--frames (use the script's shots and screenshot commands)");
}

/// Shots and frames per second over the last second or so.
class Rate {
  public:
    void add(long n, Clock::time_point now) {
        count_ += n;
        const double dt = std::chrono::duration<double>(now - start_).count();
        if (dt >= 1.0) {
            rate_ = count_ / dt;
            count_ = 0;
            start_ = now;
        }
    }
    double rate() const { return rate_; }

  private:
    Clock::time_point start_ = Clock::now();
    long count_ = 0;
    double rate_ = 0;
};

/// Time per frame drawn [ms]: waiting for the solving thread's shot in progress, then
/// rendering, overlays, panels and the swap.
class FrameTimes {
  public:
    void add(Clock::duration d) {
        last_ = std::chrono::duration<double, std::milli>(d).count();
        all_.push_back(last_);
    }
    double last_ms() const { return last_; }
    /// "frame-time: N frames drawn, mean M ms, median D ms, max X ms".
    std::string summary() const {
        if (all_.empty()) return "frame-time: no frames drawn";
        std::vector<double> v = all_;
        std::sort(v.begin(), v.end());
        double sum = 0;
        for (double t : v) sum += t;
        char text[160];
        std::snprintf(text, sizeof text,
                      "frame-time: %zu frames drawn, mean %.1f ms, median %.1f ms, max %.1f ms",
                      v.size(), sum / double(v.size()), v[v.size() / 2], v.back());
        return text;
    }

  private:
    std::vector<double> all_;
    double last_ = 0;
};

/// Runs a script command on the solver: shots and edits (the rest is the caller's: pick,
/// screenshot and quit need the window). Edits throw InputError for an unknown name.
void run_command(const ScriptCommand& c, SolveThread& solve, bool quiet) {
    switch (c.kind) {
    case ScriptCommand::Kind::Shots: {
        const long before = solve.shots();
        solve.shoot(c.shots); // on the solving thread; waits
        auto l = solve.lock();
        const Solver& solver = solve.solver();
        if (!quiet)
            std::fprintf(stderr, "%s: shots %ld: %ld shots done (%ld in all), error bound %.3e%s\n",
                         kTool, c.shots, solver.shots() - before, solver.shots(),
                         solver.error_bound(), solve.stopped() ? " (solver stopped)" : "");
        break;
    }
    case ScriptCommand::Kind::Luminaire: {
        auto l = solve.lock();
        Solver& solver = solve.solver();
        if (c.property == "multiplier") {
            solver.set_luminaire_multiplier(c.name, c.multiplier);
        } else {
            const std::vector<Luminaire>& lums = solver.scene().luminaires;
            const auto it = std::find_if(lums.begin(), lums.end(),
                                         [&](const Luminaire& x) { return x.name == c.name; });
            const bool found = it != lums.end();
            const dvec3 position = c.property == "position" ? c.xyz
                                   : found                  ? it->position
                                                            : dvec3(0.0);
            const dvec3 aim = c.property == "aim" ? c.xyz : found ? it->aim : dvec3(0, -1, 0);
            solver.place_luminaire(c.name, position, aim); // an unknown name: InputError
        }
        solve.edited();
        break;
    }
    case ScriptCommand::Kind::Reflectance: {
        auto l = solve.lock();
        solve.solver().set_reflectance(c.name, c.rho);
        solve.edited();
        break;
    }
    default:
        break;
    }
}

int run(int argc, char** argv) {
    Options o;
    SolverOptions so;
    BuiltinOptions builtin;
    ObjOptions obj;
    ArgParser args(kTool, "hemirad-view SCENE [options]",
                   "Opens a window on a scene, solves it progressively between frames and\n"
                   "shows the solution as it converges. Press H in the window for the keys.\n"
                   "With --screenshot, --after-shots or --frames it saves a frame and exits.\n"
                   "With --script FILE it runs FILE's commands, one a line, drawing the window\n"
                   "after each, and exits at the end (the solver shoots only on 'shots'):\n" +
                       std::string(kScriptHelp) +
                       (kPanels ? "\nPanels (Dear ImGui; key P): luminaires (on/off, dimmer), "
                                  "surface groups\n(reflectance, E_avg/E_min/E_max), the solver's "
                                  "progress and error bound,\nexposure and false colour; each "
                                  "edit re-solves incrementally."
                                : "\nThis build has no panels: Dear ImGui (libimgui-dev) was "
                                  "not found at configure time."));
    args.positional(
        "SCENE", &o.scene,
        std::string("OBJ or glTF (.gltf, .glb) file, SCENE.json (OBJ or glTF files, luminaires, "
                    "cameras) or built-in scene (") +
            builtin_names() + ")");
    args.section("window");
    args.option("--width", &o.width, "W", "window width [pixels]");
    args.option("--height", &o.height, "H", "window height [pixels]");
    args.option("--budget", &o.budget_ms, "MS",
                "while solving (on its own thread), a frame at most every MS, and after at "
                "least as long as the last frame took (the solver waits while one is drawn)");
    args.option("--camera", &o.camera, "E,T,U,FOV",
                "eye x,y,z, target x,y,z, up x,y,z, vertical fov [deg] (default: the scene's)");
    args.flag("--no-ambient", &o.no_ambient, "start with the ambient term off (key B)");
    args.flag("--flat-shading", &o.flat, "start with flat shading (key 2)");
    args.flag("--edges", &o.edges, "start with patch edges shown (key G)");
    args.flag("--two-sided", &o.two_sided,
              "start with the backs of polygons drawn (black) instead of culled (key T)");
    args.flag("--false-colour", &o.false_colour, "start with false-colour irradiance (key C)");
    args.option("--exposure", &o.exposure, "STOPS", "start exposure (keys + and -)");
    args.flag("--no-overlay", &o.no_overlay,
              "start with the status line and the panels hidden (key O)");
    args.flag("--no-panels", &o.no_panels,
              kPanels ? "start with the Dear ImGui panels hidden (key P)"
                      : "no effect: this build has no panels (no Dear ImGui at configure time)");
    args.flag("--highlight", &o.highlight, "start with the last shooter outlined (key L)");
    args.flag("--inset", &o.inset, "start with the last hemicube shown as an inset (key I)");
    args.flag("--paused", &o.paused, "start paused (Space resumes, N steps)");
    args.flag("--show-help", &o.show_help, "start with the key help shown (key H)");
    args.section("scripted runs");
    args.option("--screenshot", &o.screenshot, "FILE.png",
                "save the window (back buffer) as PNG and exit");
    args.option("--after-shots", &o.after_shots, "N",
                "... once N shots are done (solving stops there)");
    args.option("--frames", &o.frames, "K", "... at frame K (without --screenshot: exit)");
    args.option("--script", &o.script, "FILE",
                "run FILE's commands (above), one a line; pick lines and, at the end, a "
                "'frame-time:' summary (drawing time per frame) go to standard output");
    args.option("--units", &o.units, "auto|lux|W",
                "pick values in lux (scene in metres) or W/unit^2; auto: lux when the scene "
                "has luminaires (their photometry is in metres)");
    args.flag("--quiet", &o.quiet, "print nothing but errors");
    add_solver_options(args, so);
    add_scene_options(args, builtin, obj);
    if (!args.parse(argc, argv)) return 0;
    validate(o, args);
    std::optional<Camera> user_camera;
    if (!o.camera.empty()) user_camera = parse_camera(o.camera);
    const bool script_mode = !o.script.empty();
    const bool scripted =
        !o.screenshot.empty() || o.after_shots >= 0 || o.frames > 0 || script_mode;

    // Load the scene and the script before opening a window: bad input is an error message,
    // not a window. The scene is not const: the script's edits change its photometry.
    Scene scene = load_scene(o.scene, builtin, obj);
    print_scene_warnings(kTool, scene, o.quiet);
    const std::vector<ScriptCommand> script =
        script_mode ? read_script(o.script) : std::vector<ScriptCommand>{};
    const bool lux = o.units == "lux" || (o.units == "auto" && !scene.luminaires.empty());

    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit())
        throw RuntimeError("cannot initialise GLFW: " + g_glfw_error +
                           " (no display? headless, run under xvfb-run -a)");
    struct GlfwTerminate {
        ~GlfwTerminate() { glfwTerminate(); }
    } terminate_glfw;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_DEPTH_BITS, 0); // the scene is drawn into a SceneTarget
    if (scripted) glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    const std::string title = std::string("hemirad-view: ") + scene.source;
    GLFWwindow* window = glfwCreateWindow(o.width, o.height, title.c_str(), nullptr, nullptr);
    if (!window) throw RuntimeError("no OpenGL 4.5 core window: " + g_glfw_error);
    struct WindowDestroy {
        GLFWwindow* w;
        ~WindowDestroy() { glfwDestroyWindow(w); }
    } destroy_window{window};
    glfwMakeContextCurrent(window);
    if (gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress)) == 0)
        throw RuntimeError("gladLoadGL found no OpenGL entry points in the GLFW context");
    glfwSwapInterval(scripted ? 0 : 1);
    const auto* gl_renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string renderer_name = gl_renderer ? gl_renderer : "?";
    if (!o.quiet)
        std::fprintf(stderr, "%s: OpenGL glfw: %s (%s)\n", kTool, renderer_name.c_str(),
                     reinterpret_cast<const char*>(glGetString(GL_VENDOR)));

    // GL objects (provider, renderer, overlay) live in this scope, inside the window's life.
    {
        // The solver shoots on its own thread, in the GL context of a hidden window (created
        // here: GLFW creates windows on the main thread only); destroyed after the thread.
        glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
        GLFWwindow* solver_window =
            glfwCreateWindow(16, 16, "hemirad-view: solver", nullptr, nullptr);
        if (!solver_window)
            throw RuntimeError("no OpenGL 4.5 core context for the solving thread: " +
                               g_glfw_error);
        WindowDestroy destroy_solver_window{solver_window};
        SolveThread solve(solver_window, scene, so);
        Solver& solver = solve.solver(); // only under solve.lock() once the worker runs
        SolutionRenderer renderer(scene);
        Overlay overlay;
        SceneTarget target;
        if (!o.quiet)
            std::fprintf(stderr, "%s: %s: %zu polygons, %llu leaf patches, form factors: %s\n",
                         kTool, scene.source.c_str(), scene.polygons.size(),
                         (unsigned long long)solver.hierarchy().leaf_count(),
                         solver.provider().name().c_str());

        int fbw = 0, fbh = 0;
        glfwGetFramebufferSize(window, &fbw, &fbh);
        const Camera start = user_camera ? *user_camera : default_camera(scene);
        ViewState s{OrbitCamera(start, std::max(scene.bounds().diagonal(), 1e-9)), scene.bounds()};
        s.flat = o.flat;
        s.edges = o.edges;
        s.false_colour = o.false_colour;
        s.ambient = !o.no_ambient;
        s.paused = o.paused;
        s.status = !o.no_overlay;
        s.panels = !o.no_panels;
        s.exposure = o.exposure;
        s.help = o.show_help;
        s.highlight = o.highlight;
        s.inset = o.inset;
        s.two_sided = o.two_sided;
        s.fb_width = fbw;
        s.fb_height = fbh;
        glfwSetWindowUserPointer(window, &s);
        glfwSetKeyCallback(window, on_key);
        glfwSetMouseButtonCallback(window, on_mouse_button);
        glfwSetCursorPosCallback(window, on_cursor);
        glfwSetScrollCallback(window, on_scroll);
        glfwSetFramebufferSizeCallback(window, on_resize);
#if HEMIRAD_VIEWER_PANELS
        // After the viewer's callbacks: ImGui's GLFW backend chains them.
        Panels panels(window, scene);
#endif

        bool reported_stop = false; // the solver's stop was printed
        long drawn_shots = -1;      // shots in the last frame drawn
        long rate_shots = 0;        // shots counted by shot_rate
        auto last_frame = Clock::now();
        long frames = 0;
        std::size_t next_command = 0;   // in `script`
        std::string pending_screenshot; // a script's screenshot, taken after this frame
        bool quit = false;              // the script ended
        std::optional<Picker> picker;   // built on the first pick (a BVH of the scene)
        FrameTimes frame_times;
        Rate shot_rate, frame_rate;
        auto last = Clock::now();
        const double frame_interval = o.budget_ms / 1000; // while solving [s]
        // Ctrl-C in the terminal closes the window as the close button does.
        signal(SIGINT, on_signal);
        signal(SIGTERM, on_signal);
        while (!glfwWindowShouldClose(window) && !g_interrupted) {
            solve.check(); // an error on the solving thread ends the viewer
            // The solving thread's orders (a script gives its own, by command).
            if (!script_mode) {
                if (s.step_once) {
                    solve.shoot(1);
                    s.step_once = false;
                    s.dirty = true;
                } else if (s.paused) {
                    solve.pause();
                } else {
                    solve.run(o.after_shots >= 0 ? o.after_shots : LONG_MAX);
                }
            }
            const bool solving = solve.busy();
            // While solving, a frame is due `gap` after the last one ended: --budget, and at
            // least as long as that frame took, so that the solving thread (which waits while a
            // frame is drawn) gets at least half the time.
            const double gap = std::max(frame_interval, frame_times.last_ms() / 1000);
            const double since_frame =
                std::chrono::duration<double>(Clock::now() - last_frame).count();
            // Idle (paused, converged, minimised): wait for input instead of spinning; while
            // solving, for input or until the next frame is due.
            if (scripted)
                glfwPollEvents();
            else if (s.dirty)
                glfwPollEvents();
            else if (solving) // until the frame is due, then in steps of 5 ms for a new shot
                glfwWaitEventsTimeout(std::max(gap - since_frame, 0.005));
            else
                glfwWaitEventsTimeout(0.25);
            const auto now = Clock::now();
            fly(window, s, std::chrono::duration<double>(now - last).count());
            last = now;

            if (script_mode) {
                if (next_command < script.size()) {
                    const ScriptCommand& c = script[next_command++];
                    // An edit's or a pick's bad value (an unknown name): at the script's line.
                    try {
                        run_command(c, solve, o.quiet);
                        if (c.kind == ScriptCommand::Kind::Pick) {
                            auto l = solve.lock();
                            int ww = 1, wh = 1;
                            glfwGetWindowSize(window, &ww, &wh);
                            if (c.x >= ww || c.y >= wh)
                                throw InputError("pixel " + std::to_string(c.x) + " " +
                                                 std::to_string(c.y) + " is outside the " +
                                                 std::to_string(ww) + "x" + std::to_string(wh) +
                                                 " window");
                            if (!picker) picker.emplace(scene);
                            const PickResult r = picker->pick(solver.solution(), s.camera.camera(),
                                                              ww, wh, c.x, c.y);
                            std::printf("%s\n", pick_line(c.x, c.y, r, lux).c_str());
                            std::fflush(stdout);
                        }
                    } catch (const InputError& e) {
                        throw InputError(o.script, c.line, e.what());
                    }
                    if (c.kind == ScriptCommand::Kind::Screenshot) pending_screenshot = c.name;
                    if (c.kind == ScriptCommand::Kind::Quit) quit = true;
                } else {
                    quit = true;
                }
                s.dirty = true;
            }

            const long shots_now = solve.shots();
            shot_rate.add(shots_now - rate_shots, Clock::now());
            rate_shots = shots_now;
            // New shots: draw them, when the next frame is due (a scripted run draws as soon as
            // there are new shots, and whenever the solver is idle).
            const bool new_shots = shots_now != drawn_shots;
            const bool due =
                std::chrono::duration<double>(Clock::now() - last_frame).count() >= gap;
            if (new_shots && (due || scripted)) s.dirty = true;
            if (scripted && !solve.busy()) s.dirty = true;
            if (scripted && !s.dirty) { // solving, no new shot yet
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
                continue;
            }

            glfwGetFramebufferSize(window, &fbw, &fbh);
            s.fb_width = fbw;
            s.fb_height = fbh;
            if (fbw <= 0 || fbh <= 0) { // minimised: nothing to draw into
                if (quit) break;
                if (!solving) glfwWaitEventsTimeout(0.1);
                continue;
            }
            if (!s.dirty) continue;
            s.dirty = false;
            const auto draw_start = Clock::now();
            // The solution is read (and edited by the panels) under the lock: the solving
            // thread finishes its shot in progress first.
            auto solver_lock = solve.lock();
            const bool running = !solve.stopped();
            drawn_shots = solver.shots();
            if (!running && !reported_stop && !o.quiet)
                std::fprintf(stderr, "%s: %s after %ld shots in %.2f s: error bound %.3e\n", kTool,
                             to_string(solver.stop_reason()), solver.shots(), solver.seconds(),
                             solver.error_bound());
            reported_stop = !running;

            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, fbw, fbh);
            glClearColor(0, 0, 0, 1);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            RenderOptions ro;
            ro.shading = s.flat ? RenderOptions::Shading::Flat : RenderOptions::Shading::Smooth;
            ro.patch_edges = s.edges;
            ro.two_sided = s.two_sided;
            ro.ambient = s.ambient;
            const Camera cam = s.camera.camera();
            // The shooter of the last shot, on top of the scene (not depth-tested).
            std::optional<PatchAddress> shooter;
            if (s.highlight && solver.shots() > 0 && solver.last_shot().luminaire < 0)
                shooter = solver.last_shot().shooter;
            ColourScale scale;
            Hierarchy& h = solver.solution();
            if (s.false_colour) {
                // The shader has no colour map: render E, map it on the CPU, blit it.
                ro.width = fbw;
                ro.height = fbh;
                ro.quantity = RenderOptions::Quantity::Irradiance;
                ro.patch_edges = false;
                ro.background = dvec3(-1.0);
                overlay.blit(false_colour_image(renderer.render(h, cam, ro), scale), 0, 0, fbw,
                             fbh);
                if (shooter) renderer.draw_highlight(cam, *shooter, ro.highlight_colour, fbw, fbh);
            } else {
                // Automatic exposure as for files (auto_exposure_scale: 95th percentile of
                // luminance -> 1), from an offscreen render: full size for a screenshot, so
                // that it matches `hemirad solve -o`, else at most 256 pixels wide.
                const double shrink = scripted ? 1.0 : std::min(1.0, 256.0 / fbw);
                RenderOptions eo = ro;
                eo.patch_edges = false;
                eo.width = std::max(16, int(std::lround(fbw * shrink)));
                eo.height = std::max(16, int(std::lround(fbh * shrink)));
                ro.scale = auto_exposure_scale(renderer.render(h, cam, eo)) * std::exp2(s.exposure);
                ro.tone_map = true;
                ro.highlight = shooter;
                target.bind(fbw, fbh);
                renderer.draw(h, cam, ro, fbw, fbh);
                target.present();
            }

            frame_rate.add(1, Clock::now());
            if (s.status) {
                char line[512];
                std::snprintf(
                    line, sizeof line,
                    "shots %ld  unshot %.2e  bound %.2e  %.1f shots/s  %.0f FPS  draw %.0f ms  "
                    "exp %+.1f%s%s%s",
                    solver.shots(), solver.unshot_fraction(), solver.error_bound(),
                    shot_rate.rate(), frame_rate.rate(), frame_times.last_ms(), s.exposure,
                    s.ambient && !s.false_colour ? "  ambient" : "", s.paused ? "  [paused]" : "",
                    running ? ""
                            : (std::string("  [") + to_string(solver.stop_reason()) + "]").c_str());
                std::string text = line;
                // The GL renderer on the same line if it fits, else on a line of its own.
                const std::string same = text + "  |  " + renderer_name;
                text = text_width(same) + 8 <= fbw ? same : text + "\n" + renderer_name;
                const Image8 panel = text_panel(text);
                overlay.blit(panel, 0, fbh - panel.height, fbw, fbh);
            }
            int right = fbw; // left edge of the panels in the top right corner
            if (s.false_colour) {
                const Image8 legend = legend_panel(scale);
                overlay.blit(legend, fbw - legend.width - 4, 4, fbw, fbh);
                right -= legend.width + 4;
            }
            if (s.inset) {
                // Top right, at most ~45% of the window wide and 40% high, the cube's 4:3 kept.
                const FormFactorProvider::HemicubeImage cube = solver.provider().last_hemicube();
                if (cube.rgba && cube.width > 0 && cube.height > 0) {
                    int pw = std::min(cube.width, std::max(16, (right - 16) / 2));
                    pw = std::min(pw, std::max(16, int(0.45 * fbw / 2)));
                    int ph = std::max(12, pw * cube.height / cube.width);
                    if (ph > int(0.4 * fbh)) {
                        ph = std::max(12, int(0.4 * fbh));
                        pw = std::max(16, ph * cube.width / cube.height);
                    }
                    const Image8 inset = hemicube_inset(cube, pw, ph);
                    overlay.blit(inset, right - inset.width - 4, 4, fbw, fbh);
                } else {
                    const Image8 note = text_panel(
                        solver.shots() > 0 ? "no hemicube (CPU form factors)" : "no hemicube yet");
                    overlay.blit(note, right - note.width - 4, 4, fbw, fbh);
                }
            }
            if (s.help)
                overlay.blit(text_panel(kHelp, 1, 8), 8, 8, fbw, fbh);
            else if (s.status && !scripted)
                overlay.blit(text_panel("H: help"), 4, 4, fbw, fbh);

#if HEMIRAD_VIEWER_PANELS
            if (s.panels && s.status) {
                const PanelView pv{&s.false_colour, &s.ambient, &s.paused, &s.exposure};
                const PanelStats ps{shot_rate.rate(), frame_times.last_ms(), lux};
                if (panels.draw(solver, pv, ps)) solve.edited(); // an edit: solve again
                if (ui_wants_mouse()) s.dirty = true;
            }
#endif
            ++frames;
            if (script_mode) {
                if (!pending_screenshot.empty()) {
                    glFinish();
                    write_png(pending_screenshot, read_back_buffer(fbw, fbh));
                    if (!o.quiet)
                        std::fprintf(stderr, "%s: wrote %s (%dx%d) after %ld shots\n", kTool,
                                     pending_screenshot.c_str(), fbw, fbh, solver.shots());
                    pending_screenshot.clear();
                }
                if (quit) break;
                solve.release(solver_lock);
                glfwSwapBuffers(window);
                last_frame = Clock::now();
                frame_times.add(last_frame - draw_start);
                continue;
            }
            const bool shots_done =
                o.after_shots < 0 || solver.shots() >= o.after_shots || !running;
            const bool frames_done = o.frames <= 0 || frames >= o.frames;
            if (scripted && shots_done && frames_done &&
                (o.after_shots >= 0 || o.frames > 0 || frames >= 1)) {
                if (!o.screenshot.empty()) {
                    glFinish();
                    write_png(o.screenshot, read_back_buffer(fbw, fbh));
                    if (!o.quiet)
                        std::fprintf(stderr, "%s: wrote %s (%dx%d) after %ld shots, frame %ld\n",
                                     kTool, o.screenshot.c_str(), fbw, fbh, solver.shots(), frames);
                }
                break;
            }
            solve.release(solver_lock);
            glfwSwapBuffers(window);
            last_frame = Clock::now();
            frame_times.add(last_frame - draw_start);
        }
        // A script's summary of the drawing (frames drawn between its commands) on standard
        // output; otherwise on standard error.
        if (script_mode)
            std::printf("%s\n", frame_times.summary().c_str());
        else if (!o.quiet)
            std::fprintf(stderr, "%s: %s\n", kTool, frame_times.summary().c_str());
    }
    return 0;
}

} // namespace
} // namespace hemirad::view

int main(int argc, char** argv) {
    return hemirad::run_tool(hemirad::view::kTool, [&] { return hemirad::view::run(argc, argv); });
}
