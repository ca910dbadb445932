// hemirad-bench: timings of the solver on paper 002's scenes (§5), the Cornell box to a 1 %
// error bound (hierarchical vs flat shooting, hemicube vs analytic vs hybrid form factors),
// the per-shot breakdown, the bare hemicube cost, and scaling curves. Not a test: it prints
// a table and writes JSON (bench/README.md says what each experiment is).
//
// Every experiment runs in a child process (this program re-invoked with --child --only
// NAME), so that its peak memory (VmHWM) is its own; the child prints one "JSON {...}" line
// and one "ROW ..." line on stdout, which the parent collects.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glad/gl.h>

#include "cli/args.h"
#include "core/timer.h"
#include "hemirad/error.h"
#include "hemirad/gather.h"
#include "hemirad/gl/context.h"
#include "hemirad/json.h"
#include "hemirad/readout.h"
#include "hemirad/reference.h"
#include "hemirad/render.h"
#include "hemirad/report.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "hemirad/validation_scenes.h"
#include "incremental.h"
#include "mpi_scaling.h"
#include "point_stats.h"
#include "real_building.h"
#include "viewer_frames.h"

// The bare hemicube is measured with the renderer itself where the build exposes src/ to
// this tool (target_include_directories(hemirad-bench PRIVATE src)); otherwise from the
// provider's own render/readback phases of the same shots.
#if __has_include("gpu/hemicube.h")
#include "gpu/hemicube.h"
#define HEMIRAD_BENCH_BARE_RENDERER 1
#else
#define HEMIRAD_BENCH_BARE_RENDERER 0
#endif

using namespace hemirad;

namespace {

using Clock = SteadyClock;             // core/timer.h
constexpr auto since = &seconds_since; // [s]

// Peak resident set of this process [MiB] (VmHWM; ru_maxrss as the fallback).
double peak_rss_mib() {
    std::ifstream f("/proc/self/status");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_maxrss) / 1024.0;
}

std::uint64_t leaves_for(const Scene& scene, double patch_size, int max_depth) {
    HierarchyOptions ho;
    ho.patch_size = patch_size;
    ho.max_depth = max_depth;
    const Discretisation d = discretise(scene, ho);
    std::uint64_t n = 0;
    for (std::uint8_t depth : d.depth) n += std::uint64_t(1) << (2 * depth);
    return n;
}

// The patch size whose leaf count is nearest `target` (log scale), by bisection on log size.
double patch_size_for(const Scene& scene, double target, int max_depth) {
    double lo = 1e-4 * scene.bounds().diagonal(), hi = scene.bounds().diagonal();
    for (int i = 0; i < 60; ++i) {
        const double mid = std::sqrt(lo * hi);
        if (double(leaves_for(scene, mid, max_depth)) > target)
            lo = mid;
        else
            hi = mid;
    }
    // Leaf counts jump in factors of ~4 per polygon: take the nearer of the two sides.
    const double a = double(leaves_for(scene, lo, max_depth));
    const double b = double(leaves_for(scene, hi, max_depth));
    return std::abs(std::log(a / target)) < std::abs(std::log(b / target)) ? lo : hi;
}

struct Spec {
    std::string name, description;
    std::function<Scene()> scene;
    double target_leaves = 0; ///< leaf patches to aim for
    int max_depth = 8;
    long shots = 0; ///< fixed number of shots (0: solve to the tolerance)
    double tolerance = 0.01;
    double time_limit = 0; ///< [s], 0 = none
    std::string ff = "hybrid";
    bool flat = false;
    int resolution = 0; ///< fixed hemicube resolution (0 = adaptive)
    double paper_seconds = 0, goal_seconds = 0;
    bool overhead = false; ///< also measure the bare hemicube (shot_overhead_ratio)
    bool accuracy = false; ///< accuracy at points against `hemirad reference` instead
    bool soak = false;     ///< a long run: resident memory, GL objects, log (run_soak)
    /// Real sizes: the scene is written to an OBJ file first (not timed), and what is timed
    /// is loading that file as a user's would be; one 1024 x 768 view is rendered at the end.
    bool from_obj_file = false;
};

validation::BenchRoomOptions room402() {
    return {2, 6, 7, 0.6};
}
validation::BenchRoomOptions room3138() {
    return {17, 6, 28, 0.6};
}

std::vector<Spec> experiments() {
    std::vector<Spec> v;
    const auto room = [](validation::BenchRoomOptions o) {
        return [o] { return validation::make_bench_room(o); };
    };
    const auto cornell = [] { return make_builtin("cornell"); };
    v.push_back({"room402", "paper 002 Fig. 3(a): 402 polygons, >47,000 patches, 16 shots",
                 room(room402()), 47500, 6, 16, 0.01, 0, "hybrid", false, 0, 2.7, 1.0});
    v.push_back({"scene3138", "paper 002 Fig. 3(b): 3138 polygons, ~90,000 patches, 32 shots",
                 room(room3138()), 90000, 8, 32, 0.01, 0, "hybrid", false, 0, 9.0, 3.0});
    v.push_back({"shot_overhead", "room402, fixed resolution 256: whole shot vs bare hemicube",
                 room(room402()), 47500, 6, 64, 0.01, 0, "hybrid", false, 256, 0, 0, true});
    const double cornell_leaves = 50000;
    v.push_back({"cornell_hierarchical", "Cornell box, ~50k leaves, to a 1 % bound, hybrid",
                 cornell, cornell_leaves, 8, 0, 0.01, 60, "hybrid"});
    v.push_back({"cornell_flat", "as cornell_hierarchical, shooting from leaves only", cornell,
                 cornell_leaves, 8, 0, 0.01, 60, "hybrid", true});
    v.push_back({"cornell_hemicube", "as cornell_hierarchical, classic hemicube form factors",
                 cornell, cornell_leaves, 8, 0, 0.01, 60, "hemicube"});
    v.push_back({"cornell_analytic", "as cornell_hierarchical, analytic form factors", cornell,
                 cornell_leaves, 8, 0, 0.01, 60, "analytic"});
    // Accuracy at ~400 points on every surface against the path-traced reference, with the
    // default options and a few others (run_accuracy).
    Spec acc{"cornell_accuracy", "Cornell box: default solve + gather vs reference at 400 points",
             cornell};
    acc.accuracy = true;
    v.push_back(acc);
    acc.name = "room_accuracy";
    acc.description = "closed 1 m room, small light under the ceiling: as cornell_accuracy";
    acc.scene = [] { return make_builtin("room"); };
    v.push_back(acc);
    // Long runs: 10^5 shots on room402 (a solver that stops is rebuilt and carries on).
    Spec soak{"soak", "room402, 10^5 shots: resident memory every 1000 shots, GL objects, log",
              room(room402())};
    soak.target_leaves = 47500;
    soak.max_depth = 6;
    soak.shots = 100000;
    soak.soak = true;
    v.push_back(soak);
    // Parallel shooting on 1 and 2 MPI ranks (mpi_scaling.cpp, docs/scaling.md).
    Spec mpi{"mpi_scaling", "Cornell box to 0.1 %: alone, mpirun -np 1 and 2; bytes per round",
             cornell};
    v.push_back(mpi);
    // Real buildings (real_building.cpp): the courtyard and the office glb (lit by its bars,
    // then by point sources), default options, against the reference at random points.
    v.push_back({"real_building",
                 "courtyard (65,776 triangles, point sources) and the office glb (its bars; point "
                 "sources): default solve vs reference at random points",
                 cornell});
    // Incremental re-solving (incremental.cpp): the office walk-through converged, then one
    // downlight off and the spot halved, against a fresh solve of the edited project.
    v.push_back({"incremental",
                 "office.json to 0.1 %, D2 off and S1 halved: re-converge vs fresh solve, floor "
                 "12x8",
                 cornell});
    // The viewer's frame time while it solves a 1e5-triangle scene (viewer_frames.cpp).
    v.push_back({"viewer_frames",
                 "hemirad-view on a furnished floor of ~1e5 triangles: frame time while 40 "
                 "shots solve",
                 cornell});
    // Scaling: seconds per shot vs leaf patches at 402 polygons, at a fixed hemicube
    // resolution (256) so that the pixels shaded stay the same and what grows is the
    // geometry, the reduction and the update...
    for (int e = 3; e <= 6; ++e)
        v.push_back({"scale_patches_1e" + std::to_string(e),
                     "room402 at ~1e" + std::to_string(e) + " leaf patches, 16 shots, res 256",
                     room(room402()), std::pow(10.0, e), 11, 16, 0.01, 0, "hybrid", false, 256});
    // Real sizes (issue 11): a furnished floor of 1e5 and 1e6 triangles, loaded from an OBJ
    // file, ~2 leaves per triangle (big walls and the floor subdivide), 16 shots at res 256,
    // a rendered view.
    for (int e = 5; e <= 6; ++e) {
        const long triangles = std::lround(std::pow(10.0, e));
        Spec s{"scale_triangles_1e" + std::to_string(e),
               "furnished floor of ~1e" + std::to_string(e) +
                   " triangles from an OBJ file, 16 shots, res 256, one view",
               [triangles] { return validation::make_furnished_floor(triangles); },
               2.0 * double(triangles),
               4,
               16,
               0.01,
               0,
               "hybrid",
               false,
               256};
        s.from_obj_file = true;
        v.push_back(s);
    }
    // ...and vs polygons at ~100,000 leaf patches.
    const struct { int sets, cabinets; } poly[] = {{0, 7}, {2, 7}, {6, 12}, {17, 28}, {40, 40}};
    for (const auto& p : poly) {
        const validation::BenchRoomOptions o{p.sets, 6, p.cabinets, 0.6};
        v.push_back({"scale_polygons_" + std::to_string(validation::bench_room_polygons(o)),
                     "bench room of " + std::to_string(validation::bench_room_polygons(o)) +
                         " polygons at ~1e5 leaf patches, 16 shots, res 256",
                     room(o), 1e5, 11, 16, 0.01, 0, "hybrid", false, 256});
    }
    return v;
}

struct Sums {
    double select = 0, push_pull = 0, ff = 0, update = 0, render = 0, readback = 0, reduce = 0;
    double cull = 0, probe = 0;
    double links = 0, refined = 0, probes = 0, discarded = 0;
};

// The bare hemicube (shot_overhead): for each shot's shooter, the renderer alone at the
// same resolution in the same process, rendered (with a glFinish, so that the rasterisation
// is counted) and read back. The first shooter's is kept apart (the solver's first shot
// generates its shader code; this renderer's is generated in an untimed warm-up draw).
struct BareHemicube {
    double render = 0, readback = 0, first = 0;
#if HEMIRAD_BENCH_BARE_RENDERER
    BareHemicube(const Scene& scene, const Solver& solver, const Spec& spec)
        : scene_(scene), resolution_(spec.resolution) {
        if (!spec.overhead) return;
        renderer_.emplace(scene, solver.hierarchy().discretisation(), spec.resolution);
        layout_ = gpu::make_hemicube_layout(spec.resolution);
    }
    void measure(const ShotRecord& r) {
        Shooter s;
        s.address = r.shooter;
        const Polygon& poly = scene_.polygons[r.shooter.polygon];
        s.geometry = patch_geometry(poly, r.shooter.level, r.shooter.index);
        s.normal = poly.normal;
        s.unshot_power = r.shooter_power;
        if (!warm_) { // first-draw code generation
            renderer_->render(s, layout_, 0.0, 0);
            renderer_->read_back(layout_, rgba_);
            warm_ = true;
        }
        auto t0 = Clock::now();
        renderer_->render(s, layout_, 0.0, 0);
        glFinish();
        render += since(t0);
        t0 = Clock::now();
        renderer_->read_back(layout_, rgba_);
        readback += since(t0);
        if (first == 0) first = render + readback;
    }
    static const char* method() {
        return "HemicubeRenderer, after each shot";
    }

  private:
    const Scene& scene_;
    int resolution_;
    std::optional<gpu::HemicubeRenderer> renderer_;
    gpu::HemicubeLayout layout_;
    std::vector<float> rgba_;
    bool warm_ = false;
#else
    BareHemicube(const Scene&, const Solver&, const Spec&) {}
    void measure(const ShotRecord&) {}
    static const char* method() {
        return "provider_phases";
    }
#endif
};

using bench::luminance;
using bench::percentile;

// Accuracy at points: ~400 points on every surface (surface_points), the reference at 32768
// paths per point (sem ~0.3 % of E_Y), then for each setting: solve to 1e-3, read the points
// (final gather or leaves), relative error of E_Y. Points in the dark (reference under 1 % of
// the median) are left out and counted. One ROW per setting.
void run_accuracy(const Spec& spec) {
    auto context = gl::Context::create();
    const Scene scene = spec.scene();
    const std::vector<Probe> probes = surface_points(scene, 400);
    ReferenceOptions ro;
    ro.samples = 32768;
    const auto t_ref = Clock::now();
    const std::vector<ReferenceValue> ref = reference_irradiance(scene, probes, ro);
    const double ref_seconds = since(t_ref);
    std::vector<double> ys, sems;
    for (const ReferenceValue& r : ref)
        ys.push_back(luminance(r.E)), sems.push_back(luminance(r.sem));
    const double dark = 0.01 * percentile(ys, 0.5);
    std::vector<double> rel_sem;
    for (std::size_t k = 0; k < ys.size(); ++k)
        if (ys[k] > dark) rel_sem.push_back(sems[k] / ys[k]);

    struct Setting {
        const char* name;
        std::function<void(SolverOptions&, GatherOptions&, bool&)> apply;
    };
    const std::vector<Setting> settings = {
        {"default", [](SolverOptions&, GatherOptions&, bool&) {}},
        {"--gather off", [](SolverOptions&, GatherOptions&, bool& g) { g = false; }},
        {"--shooter-parallax 0",
         [](SolverOptions& o, GatherOptions&, bool&) { o.shooter_parallax = 0; }},
        {"--shooter-parallax 0 --gather off",
         [](SolverOptions& o, GatherOptions&, bool& g) { o.shooter_parallax = 0, g = false; }},
        {"--shooter-parallax 1e-3",
         [](SolverOptions& o, GatherOptions&, bool&) { o.shooter_parallax = 1e-3; }},
        {"--shooter-parallax 3e-3",
         [](SolverOptions& o, GatherOptions&, bool&) { o.shooter_parallax = 3e-3; }},
        {"--row-refine 0", [](SolverOptions& o, GatherOptions&, bool&) { o.row_refine = 0; }},
        {"--gather-rays 256", [](SolverOptions&, GatherOptions& g, bool&) { g.rays = 256; }},
        {"--gather-rays 4096", [](SolverOptions&, GatherOptions& g, bool&) { g.rays = 4096; }},
        {"--tolerance 3e-3", [](SolverOptions& o, GatherOptions&, bool&) { o.tolerance = 3e-3; }},
    };
    Json rows = Json::array();
    for (const Setting& set : settings) {
        SolverOptions so;
        so.tolerance = 1e-3;
        so.provider.gpu.use_current_context = true;
        GatherOptions go;
        bool gather = true;
        set.apply(so, go, gather);
        Solver solver(scene, so);
        while (solver.step()) {}
        const Hierarchy& h = solver.solution();
        const auto t_points = Clock::now();
        std::vector<dvec3> E(probes.size());
        if (gather) {
            std::vector<GatherPoint> q;
            for (const Probe& p : probes) {
                const auto sp = find_surface(scene, p.position, p.normal);
                q.push_back({p.position, p.normal, sp ? sp->polygon : GatherPoint::kNoSurface});
            }
            const std::vector<GatherValue> v = FinalGather(h, go).at(q);
            for (std::size_t k = 0; k < v.size(); ++k) E[k] = v[k].E();
        } else {
            for (std::size_t k = 0; k < probes.size(); ++k) {
                const auto sp = find_surface(scene, probes[k].position, probes[k].normal);
                if (sp) E[k] = irradiance_at(h, *sp);
            }
        }
        const double point_seconds = since(t_points);
        std::vector<double> err;
        double signed_sum = 0, mean_signed = 0;
        for (std::size_t k = 0; k < probes.size(); ++k) {
            if (ys[k] <= dark) continue;
            const double e = (luminance(E[k]) - ys[k]) / ys[k];
            err.push_back(std::abs(e));
            signed_sum += e;
        }
        Json r = Json::object();
        r["setting"] = set.name;
        r["shots"] = solver.shots();
        r["solve_seconds"] = solver.seconds();
        r["point_seconds"] = point_seconds;
        r["seconds"] = solver.seconds() + point_seconds;
        r["median"] = percentile(err, 0.5);
        r["p95"] = percentile(err, 0.95);
        r["max"] = percentile(err, 1.0);
        mean_signed = err.empty() ? 0.0 : signed_sum / double(err.size());
        r["mean_signed"] = mean_signed;
        rows.push_back(r);
        std::printf("ROW %-17s %-34s shots %5ld  solve %6.2f s  points %5.2f s  median %5.2f %%  "
                    "p95 %5.2f %%  max %6.2f %%  mean %+5.2f %%\n",
                    spec.name.c_str(), set.name, solver.shots(), solver.seconds(), point_seconds,
                    100 * percentile(err, 0.5), 100 * percentile(err, 0.95),
                    100 * percentile(err, 1.0), 100 * mean_signed);
        std::fflush(stdout);
    }
    Json j = Json::object();
    j["name"] = spec.name;
    j["description"] = spec.description;
    j["points"] = probes.size();
    j["dark_points"] = long(probes.size() - rel_sem.size());
    j["reference_samples"] = ro.samples;
    j["reference_seconds"] = ref_seconds;
    j["reference_median_relative_sem"] = percentile(rel_sem, 0.5);
    j["settings"] = rows;
    j["peak_rss_mib"] = peak_rss_mib();
    std::printf("JSON %s\n", j.dump(0).c_str());
}

// Resident set of this process now [MiB] (VmRSS).
double rss_mib() {
    std::ifstream f("/proc/self/status");
    std::string line;
    while (std::getline(f, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
    return 0;
}

// Live GL objects of the current context, by probing names 1..kNames with glIs* (Mesa hands
// out names from 1 up, so a leak shows as a growing count).
struct GlObjects {
    long buffers = 0, textures = 0, framebuffers = 0, renderbuffers = 0, vertex_arrays = 0,
         programs = 0, shaders = 0;
    long total() const {
        return buffers + textures + framebuffers + renderbuffers + vertex_arrays + programs +
               shaders;
    }
};
GlObjects count_gl_objects() {
    constexpr GLuint kNames = 4096;
    GlObjects o;
    for (GLuint n = 1; n <= kNames; ++n) {
        o.buffers += glIsBuffer(n);
        o.textures += glIsTexture(n);
        o.framebuffers += glIsFramebuffer(n);
        o.renderbuffers += glIsRenderbuffer(n);
        o.vertex_arrays += glIsVertexArray(n);
        o.programs += glIsProgram(n);
        o.shaders += glIsShader(n);
    }
    return o;
}
Json gl_json(const GlObjects& o) {
    Json j = Json::object();
    j["buffers"] = o.buffers;
    j["textures"] = o.textures;
    j["framebuffers"] = o.framebuffers;
    j["renderbuffers"] = o.renderbuffers;
    j["vertex_arrays"] = o.vertex_arrays;
    j["programs"] = o.programs;
    j["shaders"] = o.shaders;
    j["total"] = o.total();
    return j;
}

// Least-squares slope of y over x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = double(x.size());
    if (n < 2) return 0;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
        sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
    const double d = n * sxx - sx * sx;
    return d != 0 ? (n * sxy - sx * sy) / d : 0;
}

// The soak: spec.shots shots on spec.scene, resident memory (VmRSS) and live GL objects
// sampled every 1000 shots, one JSON line per shot streamed to a log file (flushed per line,
// as `hemirad solve --log` does; its size on disk is checked at each sample). A solver that
// stops (converged, nothing left to shoot) is rebuilt and carries on, so that construction
// and destruction are soaked too. The slope is fitted over the samples after the first 10 %
// (the first shots fill caches: hemicube layouts, shader variants, the allocator's pools).
void run_soak(const Spec& spec) {
    auto context = gl::Context::create();
    const Scene scene = spec.scene();
    SolverOptions so;
    so.tolerance = 1e-9;
    so.max_shots = spec.shots;
    so.hierarchy.max_depth = spec.max_depth;
    so.hierarchy.patch_size = patch_size_for(scene, spec.target_leaves, spec.max_depth);
    so.provider.gpu.use_current_context = true;
    const std::string log_path = (std::filesystem::temp_directory_path() /
                                  ("hemirad-soak-" + std::to_string(getpid()) + ".jsonl"))
                                     .string();
    std::ofstream log(log_path, std::ios::trunc);
    if (!log) throw RuntimeError("hemirad-bench: cannot write " + log_path);
    constexpr long kEvery = 1000;
    std::vector<double> at, rss;
    std::vector<long> gl_total;
    long done = 0, rebuilt = 0;
    std::uint64_t log_bytes = 0, max_unwritten = 0;
    GlObjects gl_start, gl_end;
    const auto t0 = Clock::now();
    auto solver = std::make_unique<Solver>(scene, so);
    gl_start = count_gl_objects();
    const std::uint64_t leaves = solver->hierarchy().leaf_count();
    while (done < spec.shots) {
        if (!solver->step()) {
            solver.reset(); // the old one's GL objects go first
            solver = std::make_unique<Solver>(scene, so);
            ++rebuilt;
            continue;
        }
        ++done;
        const ShotRecord& r = solver->last_shot();
        Json j = Json::object();
        j["shot"] = done;
        j["shooter_power"] = r.shooter_power;
        j["links"] = r.links;
        j["error_bound"] = r.error_bound;
        j["rss_mib"] = done % kEvery == 0 ? rss_mib() : -1.0;
        const std::string line = j.dump(0) + "\n";
        log << line << std::flush;
        log_bytes += line.size();
        if (done % kEvery == 0) {
            at.push_back(double(done));
            rss.push_back(rss_mib());
            gl_total.push_back(count_gl_objects().total());
            std::error_code ec;
            const std::uint64_t on_disk = std::filesystem::file_size(log_path, ec);
            max_unwritten = std::max(max_unwritten, log_bytes - std::min(log_bytes, on_disk));
            if (done % (10 * kEvery) == 0)
                std::fprintf(stderr, "    soak: %ld shots, %.1f s, RSS %.1f MiB, GL objects %ld\n",
                             done, since(t0), rss.back(), gl_total.back());
        }
    }
    gl_end = count_gl_objects();
    solver.reset();
    const GlObjects gl_after = count_gl_objects();
    const double seconds = since(t0);
    const std::size_t skip = at.size() / 10;
    const std::vector<double> x(at.begin() + long(skip), at.end());
    const std::vector<double> y(rss.begin() + long(skip), rss.end());
    const double per_shot = slope(x, y); // MiB per shot
    const auto [lo, hi] = std::minmax_element(y.begin(), y.end());

    Json j = Json::object();
    j["name"] = spec.name;
    j["description"] = spec.description;
    j["polygons"] = scene.polygons.size();
    j["leaf_patches"] = leaves;
    j["shots"] = done;
    j["solvers_rebuilt"] = rebuilt;
    j["seconds"] = seconds;
    j["seconds_per_shot"] = seconds / double(std::max(done, 1L));
    j["rss_sample_every"] = kEvery;
    j["rss_first_mib"] = rss.empty() ? 0.0 : rss.front();
    j["rss_last_mib"] = rss.empty() ? 0.0 : rss.back();
    j["rss_min_after_warmup_mib"] = y.empty() ? 0.0 : *lo;
    j["rss_max_after_warmup_mib"] = y.empty() ? 0.0 : *hi;
    j["rss_slope_kib_per_1000_shots"] = per_shot * 1024 * 1000;
    j["rss_slope_mib_per_1e5_shots"] = per_shot * 1e5;
    Json samples = Json::array();
    for (double v : rss) samples.push_back(v);
    j["rss_mib_samples"] = samples;
    j["gl_objects_start"] = gl_json(gl_start);
    j["gl_objects_end"] = gl_json(gl_end);
    j["gl_objects_after_solver"] = gl_json(gl_after);
    j["gl_objects_max_during"] =
        gl_total.empty() ? 0L : *std::max_element(gl_total.begin(), gl_total.end());
    j["log_bytes"] = log_bytes;
    j["log_max_bytes_not_on_disk"] = max_unwritten;
    j["peak_rss_mib"] = peak_rss_mib();
    std::printf("JSON %s\n", j.dump(0).c_str());
    std::printf("ROW %-22s %6zu %9llu %6ld %8.3f %8.2f  RSS %.1f -> %.1f MiB, slope %.2f KiB/1000 "
                "shots, GL objects %ld -> %ld (%ld after), log unwritten max %llu bytes\n",
                spec.name.c_str(), scene.polygons.size(), (unsigned long long)leaves, done, seconds,
                1e3 * seconds / double(std::max(done, 1L)), rss.empty() ? 0.0 : rss.front(),
                rss.empty() ? 0.0 : rss.back(), per_shot * 1024 * 1000, gl_start.total(),
                gl_end.total(), gl_after.total(), (unsigned long long)max_unwritten);
    std::fflush(stdout);
    std::remove(log_path.c_str());
}

// Runs one experiment in this process; prints "JSON ..." and "ROW ..." lines on stdout.
void run_child(const Spec& spec, const std::string& office) {
    if (spec.accuracy) return run_accuracy(spec);
    if (spec.soak) return run_soak(spec);
    if (spec.name == "mpi_scaling") return bench::run_mpi_scaling();
    if (spec.name == "real_building") return bench::run_real_building(office);
    if (spec.name == "incremental") return bench::run_incremental(HEMIRAD_BENCH_LIGHTING_OFFICE);
    if (spec.name == "viewer_frames") return bench::run_viewer_frames();
    auto context = gl::Context::create();
    std::string obj_path;
    std::uintmax_t obj_bytes = 0;
    if (spec.from_obj_file) {
        obj_path = (std::filesystem::temp_directory_path() /
                    ("hemirad-bench-" + std::to_string(getpid()) + ".obj"))
                       .string();
        write_obj(spec.scene(), obj_path);
        obj_bytes = std::filesystem::file_size(obj_path);
    }
    const auto t_scene = Clock::now();
    const Scene scene = spec.from_obj_file ? load_scene(obj_path) : spec.scene();
    const double peak_after_load = peak_rss_mib(), rss_after_load = rss_mib();
    if (spec.from_obj_file) {
        std::filesystem::remove(obj_path);
        std::filesystem::remove(std::filesystem::path(obj_path).replace_extension(".mtl"));
    }
    SolverOptions so;
    so.ff = spec.ff;
    so.flat = spec.flat;
    so.tolerance = spec.shots ? 1e-9 : spec.tolerance;
    so.max_shots = spec.shots ? spec.shots : 1000000;
    so.time_limit = spec.time_limit;
    so.hierarchy.max_depth = spec.max_depth;
    so.hierarchy.patch_size = patch_size_for(scene, spec.target_leaves, spec.max_depth);
    so.provider.gpu.use_current_context = true;
    so.provider.gpu.resolution = spec.resolution;
    const double scene_seconds = since(t_scene);
    const auto t_setup = Clock::now();
    Solver solver(scene, so);
    const double setup_seconds = since(t_setup);
    const double peak_after_setup = peak_rss_mib(), rss_after_setup = rss_mib();

    Sums sum;
    double first_shot_seconds = -1; // the first shot generates the renderer's shader code
    // The bare hemicube of each shot's shooter, rendered right after the shot (outside the
    // solver's clock): both sides are measured under the same load, so that the machine's
    // drift over a run does not show in their ratio.
    BareHemicube bare(scene, solver, spec);
    while (solver.step()) {
        if (first_shot_seconds < 0) first_shot_seconds = solver.seconds();
        const ShotRecord& r = solver.last_shot();
        sum.select += r.t_select;
        sum.push_pull += r.t_push_pull;
        sum.ff += r.t_form_factors;
        sum.update += r.t_update;
        sum.links += double(r.links);
        for (const auto& p : r.ff_phases) {
            if (!std::strcmp(p.phase, "render"))
                sum.render += p.seconds;
            else if (!std::strcmp(p.phase, "cull"))
                sum.cull += p.seconds;
            else if (!std::strcmp(p.phase, "readback"))
                sum.readback += p.seconds;
            else if (!std::strcmp(p.phase, "reduce"))
                sum.reduce += p.seconds;
            else if (!std::strcmp(p.phase, "probe"))
                sum.probe += p.seconds;
        }
        sum.refined += r.refined;
        sum.probes += r.probes;
        sum.discarded += r.discarded;
        if (spec.overhead && r.luminaire < 0) bare.measure(r);
    }
    const long shots = solver.shots();
    const double seconds = solver.seconds();
    double render_seconds = 0;
    const double peak_after_shots = peak_rss_mib();
    if (spec.from_obj_file) {
        const auto t_render = Clock::now();
        SolutionRenderer renderer(scene);
        RenderOptions ro;
        ro.width = 1024, ro.height = 768;
        const ImageRGB image = renderer.render(solver.hierarchy(), default_camera(scene), ro);
        render_seconds = since(t_render);
        HEMIRAD_CHECK(image.width == 1024);
    }

    Json j = Json::object();
    j["name"] = spec.name;
    j["description"] = spec.description;
    j["polygons"] = scene.polygons.size();
    j["triangles"] = scene.triangle_count();
    if (spec.from_obj_file) {
        j["obj_bytes"] = obj_bytes;
        j["load_seconds"] = scene_seconds;
        j["render_seconds"] = render_seconds;
        // Where the memory goes: resident after each phase, and the peak up to its end.
        j["rss_after_load_mib"] = rss_after_load;
        j["peak_after_load_mib"] = peak_after_load;
        j["rss_after_setup_mib"] = rss_after_setup;
        j["peak_after_setup_mib"] = peak_after_setup;
        j["peak_after_shots_mib"] = peak_after_shots;
    }
    j["leaf_patches"] = solver.hierarchy().leaf_count();
    j["shots"] = shots;
    j["seconds"] = seconds;
    j["error_bound"] = solver.error_bound();
    j["stop"] = to_string(solver.stop_reason());
    j["ff"] = spec.ff;
    j["flat"] = spec.flat;
    j["resolution"] = spec.resolution ? Json(spec.resolution) : Json("adaptive 64..256");
    j["patch_size"] = so.hierarchy.patch_size;
    j["max_depth"] = so.hierarchy.max_depth;
    j["seconds_per_shot"] = shots ? seconds / double(shots) : 0.0;
    j["setup_seconds"] = setup_seconds;
    j["scene_seconds"] = scene_seconds;
    j["links_per_shot"] = shots ? sum.links / double(shots) : 0.0;
    Json b = Json::object(); // totals over the shots [s]
    b["select"] = sum.select;
    b["push_pull"] = sum.push_pull;
    b["form_factors"] = sum.ff;
    b["ff_cull"] = sum.cull;
    b["ff_render"] = sum.render;
    b["ff_readback"] = sum.readback;
    b["ff_reduce"] = sum.reduce;
    b["ff_probe"] = sum.probe; // coarse hemicubes that decide whether a node may shoot
    j["refined_per_shot"] = shots ? sum.refined / double(shots) : 0.0;
    j["probes_per_shot"] = shots ? sum.probes / double(shots) : 0.0;
    j["discarded_per_shot"] = shots ? sum.discarded / double(shots) : 0.0; // full hemicubes
    b["update"] = sum.update;
    j["breakdown"] = b;
    if (spec.paper_seconds > 0) {
        j["paper002_seconds"] = spec.paper_seconds;
        j["paper002_hardware"] = "GeForce FX 5900";
        j["goal_seconds"] = spec.goal_seconds;
    }

    double ratio = 0;
    if (spec.overhead && shots > 0) {
        double bare_render = bare.render, bare_readback = bare.readback;
        const double bare_first = bare.first;
        const char* method = bare.method();
#if !HEMIRAD_BENCH_BARE_RENDERER
        bare_render = sum.render;
        bare_readback = sum.readback;
#endif
        // Per shot in the steady state: the first shot is left out of both sides (the bare
        // renderer's code generation happens in its untimed warm-up draw, the solver's in its
        // first shot: for the full hemicube and for the coarse view probe).
        const double bare = bare_render + bare_readback;
        const double with_first = seconds / bare;
        ratio = shots > 1 && bare > bare_first
                    ? (seconds - first_shot_seconds) / (bare - bare_first)
                    : with_first;
        Json o = Json::object();
        o["method"] = method;
        o["resolution"] = spec.resolution;
        o["bare_render_seconds"] = bare_render;
        o["bare_readback_seconds"] = bare_readback;
        o["bare_per_shot"] = (bare_render + bare_readback) / double(shots);
        o["shot_per_shot"] = seconds / double(shots);
        o["ratio"] = ratio;
        o["ratio_including_first_shot"] = with_first;
        o["first_shot_seconds"] = first_shot_seconds;
        j["overhead"] = o;
    }
    j["peak_rss_mib"] = peak_rss_mib();

    std::printf("JSON %s\n", j.dump(0).c_str());
    if (spec.overhead) std::printf("RATIO %.17g\n", ratio);
    const double n = shots ? double(shots) : 1.0;
    char note[160] = "";
    if (spec.paper_seconds > 0)
        std::snprintf(note, sizeof note, "paper %.1f s, goal %.1f s", spec.paper_seconds,
                      spec.goal_seconds);
    else if (spec.from_obj_file)
        std::snprintf(note, sizeof note, "%zu triangles, OBJ %.0f MB loaded in %.2f s, view %.2f s",
                      scene.triangle_count(), double(obj_bytes) / 1e6, scene_seconds,
                      render_seconds);
    std::printf("ROW %-22s %6zu %9llu %6ld %8.3f %8.2f %9.2e %6.1f %6.1f %6.1f %6.1f %6.1f %6.1f "
                "%6.1f %7.0f %s\n",
                spec.name.c_str(), scene.polygons.size(),
                (unsigned long long)solver.hierarchy().leaf_count(), shots, seconds,
                1e3 * seconds / n, solver.error_bound(), 1e3 * sum.select / n,
                1e3 * sum.push_pull / n, 1e3 * sum.render / n, 1e3 * sum.readback / n,
                1e3 * sum.reduce / n, 1e3 * sum.update / n, 1e3 * setup_seconds, peak_rss_mib(),
                note);
    std::fflush(stdout);
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

std::string self_path() {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0) throw RuntimeError("hemirad-bench: cannot read /proc/self/exe");
    buf[n] = 0;
    return buf;
}

const char* kHeader =
    "experiment             polys    leaves  shots  total s  ms/shot  err bound  sel/ms pp/ms "
    "rend/ms read/ms red/ms upd/ms setup/ms  RSS MiB";

int run(int argc, char** argv) {
    std::string out = "bench.json", only;
    bool quiet = false, child = false;
    ArgParser args("hemirad-bench", "hemirad-bench [options]",
                   "Benchmarks the solver (paper 002's scenes, the Cornell box, scaling).\n"
                   "Each experiment runs in its own process (peak memory per experiment).");
    args.option("--out", &out, "FILE", "write the results as JSON to FILE");
    args.option("--only", &only, "NAME,...", "run only these experiments (default: all but soak)");
    std::string office = HEMIRAD_BENCH_OFFICE_GLB;
    args.option("--office", &office, "FILE.glb",
                "real_building: the office exported from Blender (its doubleSided glTF); "
                "empty: the courtyard only");
    args.flag("--quiet", &quiet, "print nothing but errors");
    args.flag("--child", &child, "internal: run the experiments in this process");
    if (!args.parse(argc, argv)) return 0;

    const std::vector<Spec> all = experiments();
    std::vector<const Spec*> chosen;
    if (only.empty()) {
        for (const Spec& s : all)
            if (!s.soak) chosen.push_back(&s); // minutes long: only when asked for
    } else {
        for (const std::string& name : split(only)) {
            auto it =
                std::find_if(all.begin(), all.end(), [&](const Spec& s) { return s.name == name; });
            if (it == all.end()) {
                std::string names;
                for (const Spec& s : all) names += (names.empty() ? "" : ", ") + s.name;
                throw InputError("--only: unknown experiment '" + name + "' (known: " + names +
                                 ")");
            }
            chosen.push_back(&*it);
        }
    }
    if (child) {
        for (const Spec* s : chosen) run_child(*s, office);
        return 0;
    }

    if (!quiet) {
        auto context = gl::Context::create();
        std::fprintf(stderr, "hemirad-bench: OpenGL %s: %s (%s)\n", context->backend_name().c_str(),
                     context->renderer().c_str(), context->vendor().c_str());
    }
    const std::string self = self_path();
    std::vector<std::string> jsons, rows;
    double ratio = 0;
    const auto t_all = Clock::now();
    for (std::size_t i = 0; i < chosen.size(); ++i) {
        const Spec& s = *chosen[i];
        if (!quiet)
            std::fprintf(stderr, "[%zu/%zu] %s: %s ...\n", i + 1, chosen.size(), s.name.c_str(),
                         s.description.c_str());
        const auto t0 = Clock::now();
        if (office.find('\'') != std::string::npos)
            throw InputError("--office: a path with a quote (') is not supported: " + office);
        const std::string cmd =
            "'" + self + "' --child --only " + s.name + " --office '" + office + "'";
        FILE* p = popen(cmd.c_str(), "r");
        if (!p) throw RuntimeError("hemirad-bench: cannot run " + cmd);
        char line[1 << 16];
        bool got = false;
        while (std::fgets(line, sizeof line, p)) {
            std::string l(line);
            while (!l.empty() && (l.back() == '\n' || l.back() == '\r')) l.pop_back();
            if (l.rfind("JSON ", 0) == 0)
                jsons.push_back(l.substr(5)), got = true;
            else if (l.rfind("RATIO ", 0) == 0)
                ratio = std::atof(l.c_str() + 6);
            else if (l.rfind("ROW ", 0) == 0) {
                rows.push_back(l.substr(4));
                if (!quiet) std::fprintf(stderr, "    %s\n", l.c_str() + 4);
            }
        }
        const int status = pclose(p);
        if (status != 0 || !got)
            throw RuntimeError("hemirad-bench: experiment " + s.name + " failed (status " +
                               std::to_string(status) + ")");
        if (!quiet)
            std::fprintf(stderr, "    done in %.1f s (%.0f s so far)\n", since(t0), since(t_all));
    }
    std::string doc = "{\n  \"program\": \"hemirad-bench\",\n  \"shot_overhead_ratio\": ";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", ratio);
    doc += ratio > 0 ? buf : "null";
    doc += ",\n  \"experiments\": [\n";
    for (std::size_t i = 0; i < jsons.size(); ++i)
        doc += "    " + jsons[i] + (i + 1 < jsons.size() ? ",\n" : "\n");
    doc += "  ]\n}\n";
    std::ofstream f(out, std::ios::trunc);
    if (!(f << doc)) throw RuntimeError("hemirad-bench: cannot write " + out);
    if (!quiet) {
        std::printf("%s\n", kHeader);
        for (const std::string& r : rows) std::printf("%s\n", r.c_str());
        if (ratio > 0) std::printf("shot_overhead_ratio %.3f\n", ratio);
        std::printf("wrote %s (%.0f s)\n", out.c_str(), since(t_all));
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const InputError& e) {
        std::fprintf(stderr, "hemirad-bench: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hemirad-bench: %s\n", e.what());
        return 1;
    }
}
