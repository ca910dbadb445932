// hemirad solve: progressive radiosity to a tolerance, with reports, logs and probes.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include "cli/cli_options.h"
#include "commands.h"
#include "core/timer.h"
#include "export_outputs.h"
#include "hemirad/error.h"
#include "hemirad/gl/context.h"
#include "hemirad/grid.h"
#include "hemirad/json.h"
#include "hemirad/memory_guard.h"
#include "hemirad/readout.h"
#include "hemirad/solver.h"
#include "parallel/world.h"
#include "scene_edits.h"
#include "solve_outputs.h"

namespace hemirad::cli {

namespace {

Json address_json(const PatchAddress& a) {
    Json j = Json::object();
    j["polygon"] = a.polygon;
    j["level"] = a.level;
    j["index"] = a.index;
    return j;
}

Json shot_json(const ShotRecord& r) {
    Json j = Json::object();
    j["shot"] = r.shot;
    if (r.luminaire >= 0) {
        j["luminaire"] = r.luminaire;
    } else if (r.cluster >= 0) {
        j["cluster"] = r.cluster;
        j["cluster_polygons"] = r.cluster_polygons;
    } else {
        j["shooter"] = address_json(r.shooter);
    }
    j["shooter_power"] = r.shooter_power;
    j["links"] = r.links;
    if (r.refined) j["refined"] = r.refined;
    if (r.probes) j["probes"] = r.probes;
    if (r.discarded) j["discarded"] = r.discarded;
    if (r.parts) j["parts"] = r.parts;
    if (r.parallax >= 0) j["parallax"] = r.parallax;
    Json t = Json::object();
    t["select"] = r.t_select;
    t["push_pull"] = r.t_push_pull;
    t["form_factors"] = r.t_form_factors;
    t["update"] = r.t_update;
    for (const auto& p : r.ff_phases) t[std::string("ff_") + p.phase] = p.seconds;
    j["time"] = t;
    j["unshot"] = r.unshot;
    j["unshot_fraction"] = r.unshot_fraction;
    j["error_bound"] = r.error_bound;
    j["row_sum"] = r.row_sum;
    if (r.row_guarded) j["row_guarded"] = true;
    if (r.round > 0) {
        j["round"] = r.round;
        j["rank"] = r.rank;
    }
    return j;
}

/// The EGL device of this rank: --device when given, else the rank on this machine when the
/// machine has several devices (one GPU per rank), else the default.
int rank_device(const ArgParser& args, int device, const parallel::World& world) {
    if (args.given("--device") || world.local_size() < 2) return device;
    const std::size_t devices = gl::Context::egl_devices().size();
    return devices >= 2 ? int(std::size_t(world.local_rank()) % devices) : device;
}

} // namespace

int cmd_solve(int argc, char** argv) {
    std::string scene_name, report, log, probes_in, probes_out;
    bool quiet = false;
    SolverOptions so;
    BuiltinOptions builtin;
    ObjOptions obj;
    OutputOptions out;
    ExportOptions exports;
    SceneEdits edits;
    ArgParser args("hemirad solve", "hemirad solve SCENE [options]",
                   "Solves the radiosity of a scene by progressive shooting until the error\n"
                   "bound falls under the tolerance, then writes what was asked for.\n"
                   "Launched by mpirun -np N, each round shoots N shooters, one per rank;\n"
                   "rank 0 prints and writes (docs/scaling.md).");
    args.positional(
        "SCENE", &scene_name,
        std::string("OBJ or glTF (.gltf, .glb) file, SCENE.json (OBJ or glTF files, luminaires, "
                    "cameras) or built-in scene (") +
            builtin_names() + ")");
    add_solver_options(args, so);
    args.section("output");
    args.option("--report", &report, "FILE.json", "write a JSON report");
    args.option("--log", &log, "FILE.jsonl", "write one JSON line per shot");
    args.option("--probes", &probes_in, "IN.csv", "points x,y,z,nx,ny,nz to evaluate");
    args.option("--probe-out", &probes_out, "OUT.csv", "irradiance at the probe points");
    add_output_options(args, out);
    add_export_options(args, exports);
    add_scene_edit_options(args, edits);
    args.flag("--quiet", &quiet, "print nothing but errors");
    add_scene_options(args, builtin, obj);
    if (!args.parse(argc, argv, 2)) return 0;
    // Launched by mpirun: every rank solves, rank 0 alone prints and writes (docs/scaling.md).
    parallel::World& world = parallel::world();
    const bool lead = world.rank() == 0;
    if (!lead) quiet = true;
    if (world.size() == 1 && parallel::World::launched_size() > 1 && !quiet)
        std::fprintf(stderr,
                     "hemirad: warning: launched as one of %d processes, but built "
                     "without MPI (HEMIRAD_MPI=OFF): this process solves alone\n",
                     parallel::World::launched_size());
    if (!probes_in.empty() && probes_out.empty())
        throw InputError("--probes needs --probe-out OUT.csv");
    validate_options(so);
    validate_output_options(out);
    exports.lux = out.images.lux; // one --lux flag: false colour and grids
    exports.discontinuities = out.images.discontinuities == "on"; // images and lightmaps
    const std::vector<GridSpec> grid_specs = validate_export_options(exports);
    validate_scene_edits(edits);

    // From here on SIGINT/SIGTERM end the solve at the end of a shot (or before the first),
    // with every requested output written.
    install_interrupt_handler();
    Scene scene = load_scene(scene_name, builtin, obj);
    apply_scene_edits(edits, scene); // the solver edits no further: one scene throughout
    if (exports.daylight_factor) {
        if (!scene.sky)
            throw InputError("--daylight-factor needs a sky: " + scene_name +
                             " has no \"sky\" (SCENE.json \"sky\": {\"model\": "
                             "\"cie-overcast\", \"illuminance\": 10000})");
        if (!(scene.sky->illuminance > 0))
            throw InputError("--daylight-factor needs a sky with \"illuminance\" > 0 lux");
        exports.daylight_lux = scene.sky->illuminance;
    }
    print_warnings(scene, quiet);
    // Everything that needs only the scene is checked before the first output is opened.
    for (const GridSpec& g : grid_specs) grid_polygons(scene, g);
    check_image_camera(out.images, scene);
    // Before the solver is built: a resumed run takes the saved options it was not given.
    const std::optional<SolutionFile> resumed =
        prepare_resume(exports, args, scene, scene_name, so);
    const std::vector<Probe> probes =
        probes_in.empty() ? std::vector<Probe>{} : read_probes(probes_in);
    // The memory guard, before GL starts (the Solver checks again: memory_guard.h).
    check_memory(scene, discretise(scene, so.hierarchy), so);
    // One GL context for the whole run: the GPU provider and the image outputs share it.
    std::unique_ptr<gl::Context> context;
    if (is_gpu_provider(so.ff) || (lead && out.needs_gl())) {
        gl::ContextOptions co;
        co.backend = gl::parse_backend(so.provider.gpu.backend);
        co.device = rank_device(args, so.provider.gpu.device, world);
        context = gl::Context::create(co);
        so.provider.gpu.use_current_context = true;
        if (!quiet)
            std::fprintf(stderr, "hemirad: OpenGL %s: %s (%s)\n", context->backend_name().c_str(),
                         context->renderer().c_str(), context->vendor().c_str());
    }
    Solver solver(scene, so);
    if (world.size() > 1) solver.set_collective(&world);
    long shots_before = 0;     // of the resumed solution
    double seconds_before = 0; // [s]
    ResumeEdits resume_edits;
    if (resumed) {
        resume_edits = resume_solution(solver, *resumed, exports.resume);
        shots_before = solver.shots();
        seconds_before = solver.seconds();
        if (!quiet && resume_edits.any())
            std::fprintf(stderr,
                         "hemirad: resumed incrementally from %s after %ld shots: %zu "
                         "luminaires (%zu rescaled by their light layers) and %zu polygons "
                         "changed, error bound now %.3e\n",
                         exports.resume.c_str(), solver.shots(), resume_edits.luminaires,
                         resume_edits.rescaled, resume_edits.polygons, solver.error_bound());
        else if (!quiet)
            std::fprintf(stderr, "hemirad: resumed from %s after %ld shots\n",
                         exports.resume.c_str(), solver.shots());
    }
    if (!quiet) {
        std::fprintf(stderr, "hemirad: %s: %zu polygons, %llu leaf patches, form factors: %s\n",
                     scene.source.c_str(), scene.polygons.size(),
                     (unsigned long long)solver.hierarchy().leaf_count(),
                     solver.provider().name().c_str());
        if (world.size() > 1)
            std::fprintf(stderr,
                         "hemirad: %d MPI ranks, %d on this machine: up to %d shots a "
                         "round\n",
                         world.size(), world.local_size(), world.size());
        if (!scene.luminaires.empty()) {
            double total = 0;
            for (const Luminaire& l : scene.luminaires) total += l.lumens();
            std::fprintf(stderr, "hemirad: %zu luminaires, %.6g lm installed:\n",
                         scene.luminaires.size(), total);
            for (const Luminaire& l : scene.luminaires)
                std::fprintf(stderr,
                             "hemirad:   %-10s %-7s %9.6g lm at (%g, %g, %g), %g cd max%s%s\n",
                             l.name.c_str(), l.kind.c_str(), l.lumens(), l.position.x, l.position.y,
                             l.position.z, l.multiplier * l.distribution.max_candela(),
                             l.file.empty() ? "" : "  ", l.file.c_str());
        }
    }
    std::ofstream log_file;
    if (!log.empty() && lead) {
        log_file.open(log, std::ios::trunc);
        if (!log_file) throw RuntimeError("cannot write " + log);
    }
    const bool tty = isatty(2) && !quiet;
    auto last_print = SteadyClock::now();
    // A signal on any rank stops every rank at the same round.
    const auto signalled = [&] {
        return world.size() > 1 ? world.any(interrupted()) : interrupted();
    };
    while (!signalled() && solver.step()) {
        const ShotRecord& r = solver.last_shot();
        if (log_file.is_open()) {
            for (const ShotRecord& s : solver.last_round())
                log_file << shot_json(s).dump(0) << "\n";
            log_file << std::flush;
        }
        const auto now = SteadyClock::now();
        if (tty && now - last_print > std::chrono::milliseconds(250)) {
            std::fprintf(stderr, "\rshot %ld  unshot %.3e  error bound %.3e / %.3g  %.1f s   ",
                         r.shot, r.unshot_fraction, r.error_bound, so.tolerance, solver.seconds());
            last_print = now;
        }
    }
    if (tty) std::fprintf(stderr, "\r%*s\r", 79, "");
    if (log_file.is_open()) {
        log_file.close();
        if (!log_file) throw RuntimeError("error writing " + log);
    }
    const bool was_interrupted = signalled();
    if (world.size() > 1) {
        // Every rank must hold the bit-identical solution (docs/scaling.md): compare hashes.
        const std::uint64_t sum = solver.state_checksum();
        const auto* p = reinterpret_cast<const std::uint8_t*>(&sum);
        for (const auto& other : world.all_gather(std::vector<std::uint8_t>(p, p + sizeof sum)))
            if (other != std::vector<std::uint8_t>(p, p + sizeof sum))
                throw RuntimeError("the ranks' solutions differ after " +
                                   std::to_string(solver.shots()) + " shots (a bug)");
        if (!quiet)
            std::fprintf(stderr, "hemirad: the %d ranks hold the bit-identical solution\n",
                         world.size());
    }
    // Every rank holds the same solution: rank 0 alone writes it.
    if (!lead) return was_interrupted ? 130 : 0;
    // The state is saved before solution(), whose push-pull would change later float sums:
    // a resumed run then ends bit-identical to an uninterrupted one.
    write_solution_file(exports, solver, quiet);
    Hierarchy& h = solver.solution();
    if (!quiet)
        std::fprintf(stderr,
                     "hemirad: %s after %ld shots in %.2f s: error bound %.3e (tolerance %.3g), "
                     "row sum %.4f..%.4f (%ld above 1 rescaled)\n",
                     was_interrupted ? "interrupted" : to_string(solver.stop_reason()),
                     solver.shots(), solver.seconds(), solver.error_bound(), so.tolerance,
                     solver.row_sums().min, solver.row_sums().max, solver.row_sums().guarded);
    if (!quiet && resumed)
        std::fprintf(stderr, "hemirad: this run took %ld shots in %.2f s (%s from %ld)\n",
                     solver.shots() - shots_before, solver.seconds() - seconds_before,
                     resume_edits.any() ? "resumed incrementally" : "resumed", shots_before);
    if (!quiet && solver.unshot_fraction() >= 1e-3) {
        const dvec3 a = h.unshot_estimate();
        std::fprintf(stderr,
                     "hemirad: %.2g %% of the power is not shot yet: read-outs include the "
                     "estimate of its light, E_a = (%.4g, %.4g, %.4g) W/unit² everywhere\n",
                     100 * solver.unshot_fraction(), a.r, a.g, a.b);
    }

    // Point read-outs: by final gather unless --gather off.
    std::unique_ptr<FinalGather> gather;
    if (!grid_specs.empty() || !probes.empty()) gather = make_gather(exports, h);
    const Stopwatch points_timer;
    const std::vector<GridResult> grids = evaluate_grids(grid_specs, h, gather.get(), quiet);
    std::string probe_text;
    if (!probes_out.empty()) probe_text = probes_csv(probes, h, gather.get(), exports.daylight_lux);
    if (gather && !quiet) {
        std::size_t points = probes.size();
        for (const GridResult& g : grids) points += std::size_t(g.evaluated);
        const double s = points_timer.seconds();
        std::fprintf(stderr, "hemirad: final gather at %zu points in %.2f s (%.2f ms a point)\n",
                     points, s, points ? 1e3 * s / double(points) : 0.0);
    }
    if (!quiet)
        for (const GridResult& g : grids)
            std::fprintf(stderr, "hemirad: grid %s\n",
                         grid_summary(g, exports.lux, exports.daylight_lux).c_str());
    if (!report.empty()) {
        Json resume = Json::object();
        if (resumed) {
            resume["file"] = exports.resume;
            resume["shots_before"] = shots_before;
            resume["shots_this_run"] = solver.shots() - shots_before;
            resume["seconds_this_run"] = solver.seconds() - seconds_before;
            resume["incremental"] = resume_edits.any();
            resume["luminaires_changed"] = resume_edits.luminaires;
            resume["luminaires_rescaled"] = resume_edits.rescaled;
            resume["polygons_changed"] = resume_edits.polygons;
        }
        write_report(report, solver, scene, grids, exports.lux, exports.daylight_lux,
                     resumed ? &resume : nullptr);
        if (!quiet) std::fprintf(stderr, "hemirad: wrote %s (JSON report)\n", report.c_str());
    }
    if (!probes_out.empty()) {
        write_text_file(probes_out, probe_text);
        if (!quiet)
            std::fprintf(stderr, "hemirad: wrote %s (irradiance at %zu probes)\n",
                         probes_out.c_str(), probes.size());
    }
    write_export_outputs(exports, grids, h, quiet);
    write_outputs(out, solver, quiet);
    if (was_interrupted) {
        std::fprintf(stderr, "hemirad: interrupted by a signal; wrote the outputs of the current "
                             "solution\n");
        return 130;
    }
    return 0;
}

} // namespace hemirad::cli
