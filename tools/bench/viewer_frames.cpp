// viewer_frames: is hemirad-view's window responsive while a 1e5-triangle scene solves? Runs
// the hemirad-view beside this hemirad-bench on validation::make_furnished_floor(100000) (as
// an OBJ file) with --after-shots 40, under xvfb-run when no display is set, and reads the
// "frame-time:" line it prints when it closes (time per frame drawn: the wait for the shot
// under way, rendering, overlays, panels, swap).
#include "viewer_frames.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/timer.h"
#include "hemirad/error.h"
#include "hemirad/json.h"
#include "hemirad/scene_io.h"
#include "hemirad/validation_scenes.h"
#include "sibling.h"

namespace hemirad::bench {

namespace {

namespace fs = std::filesystem;

constexpr long kTriangles = 100000;
constexpr int kShots = 40;

struct FrameTimes {
    long frames = -1;
    double mean_ms = 0, median_ms = 0, max_ms = 0;
};

} // namespace

void run_viewer_frames() {
    const std::string view = sibling_tool("hemirad-view", "viewer_frames");
    const bool display = std::getenv("DISPLAY") && *std::getenv("DISPLAY");
    if (!display && std::system("command -v xvfb-run > /dev/null") != 0)
        throw RuntimeError("viewer_frames: no DISPLAY and no xvfb-run (Debian: xvfb)");
    const fs::path dir = fs::temp_directory_path() / ("hemirad-frames-" + std::to_string(getpid()));
    fs::create_directories(dir);
    const fs::path obj = dir / "floor.obj";
    const Scene scene = validation::make_furnished_floor(kTriangles);
    write_obj(scene, obj.string());
    std::string cmd = display ? "" : "xvfb-run -a -s '-screen 0 1280x1024x24' ";
    cmd += "'" + view + "' '" + obj.string() + "' --width 960 --height 720 --after-shots " +
           std::to_string(kShots) + " --screenshot '" + (dir / "last.png").string() + "' 2>&1";
    const auto t0 = SteadyClock::now();
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) throw RuntimeError("viewer_frames: cannot run " + cmd);
    FrameTimes ft;
    std::string output;
    char line[1024];
    while (std::fgets(line, sizeof line, p)) {
        output += line;
        // "[hemirad-view: ]frame-time: N frames drawn, mean M ms, median D ms, max X ms"
        if (const char* f = std::strstr(line, "frame-time: "))
            std::sscanf(f, "frame-time: %ld frames drawn, mean %lf ms, median %lf ms, max %lf ms",
                        &ft.frames, &ft.mean_ms, &ft.median_ms, &ft.max_ms);
    }
    const int status = pclose(p);
    const double seconds = seconds_since(t0);
    fs::remove_all(dir);
    if (status != 0 || ft.frames < 0)
        throw RuntimeError("viewer_frames: hemirad-view failed (" + cmd + "):\n" + output);
    Json j = Json::object();
    j["name"] = "viewer_frames";
    j["description"] = "hemirad-view on a furnished floor of ~1e5 triangles, 40 shots solved on "
                       "the solver's thread while drawing at 960x720";
    j["triangles"] = scene.triangle_count() + 2 * scene.quad_count();
    j["polygons"] = scene.polygons.size();
    j["shots"] = kShots;
    j["seconds"] = seconds;
    j["frames"] = ft.frames;
    j["frame_ms_mean"] = ft.mean_ms;
    j["frame_ms_median"] = ft.median_ms;
    j["frame_ms_max"] = ft.max_ms;
    std::printf("JSON %s\n", j.dump(0).c_str());
    std::printf("ROW viewer_frames  %zu polygons  %d shots in %.1f s (window open to close)  %ld "
                "frames: median %.0f ms, mean %.0f ms, max %.0f ms\n",
                scene.polygons.size(), kShots, seconds, ft.frames, ft.median_ms, ft.mean_ms,
                ft.max_ms);
    std::fflush(stdout);
}

} // namespace hemirad::bench
