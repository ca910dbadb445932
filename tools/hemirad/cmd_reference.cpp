// hemirad reference: unbiased Monte-Carlo irradiance at probe points (reference.h), the
// yardstick for the solver's probe values.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "commands.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "hemirad/error.h"
#include "hemirad/reference.h"

namespace hemirad::cli {

int cmd_reference(int argc, char** argv) {
    std::string scene_name, probes_in, probes_out;
    bool quiet = false;
    long seed = 1;
    ReferenceOptions ro;
    BuiltinOptions builtin;
    ObjOptions obj;
    ArgParser args(
        "hemirad reference",
        "hemirad reference SCENE --probes IN.csv --probe-out OUT.csv [options]",
        "Estimates the irradiance at points by unbiased Monte-Carlo path tracing (next-event\n"
        "estimation with MIS, Russian roulette, every bounce), independently of the solver.\n"
        "A probe on a surface gets that surface's irradiance about its normal, as in\n"
        "'hemirad solve --probe-out'; other probes get the free-space irradiance about their\n"
        "normal. OUT.csv has the columns of 'hemirad solve --probe-out' and the standard\n"
        "errors of the means: x,y,z,nx,ny,nz,E_r,E_g,E_b,polygon,group,sem_r,sem_g,sem_b.");
    args.positional(
        "SCENE", &scene_name,
        std::string("OBJ or glTF (.gltf, .glb) file, SCENE.json (OBJ or glTF files, luminaires, "
                    "cameras) or built-in scene (") +
            builtin_names() + ")");
    args.option("--probes", &probes_in, "IN.csv", "points x,y,z,nx,ny,nz to evaluate (required)");
    args.option("--probe-out", &probes_out, "OUT.csv",
                "irradiance and its standard error at the points (required)");
    args.option("--samples", &ro.samples, "N",
                "paths per point (>= 1; the error falls as 1/sqrt(N))");
    args.option("--seed", &seed, "S", "random seed (>= 0); same seed, same output");
    args.option("--threads", &ro.threads, "N", "worker threads (0 = all cores)");
    args.option("--max-bounces", &ro.max_bounces, "K",
                "count light reflected at most K times (0 = unlimited, unbiased)");
    args.flag("--quiet", &quiet, "print nothing but errors");
    add_scene_options(args, builtin, obj);
    if (!args.parse(argc, argv, 2)) return 0;
    if (probes_in.empty()) throw InputError("--probes IN.csv is required");
    if (probes_out.empty()) throw InputError("--probe-out OUT.csv is required");
    if (seed < 0) throw InputError("--seed " + std::to_string(seed) + " must be >= 0");
    ro.seed = std::uint64_t(seed);
    validate_options(ro);

    const Scene scene = load_scene(scene_name, builtin, obj);
    print_warnings(scene, quiet);
    const std::vector<Probe> probes = read_probes(probes_in);
    const unsigned threads = thread_count(ro.threads);
    if (!quiet)
        std::fprintf(stderr, "hemirad: %s: %zu polygons, %zu points x %ld samples, %u threads\n",
                     scene.source.c_str(), scene.polygons.size(), probes.size(), ro.samples,
                     threads);

    const bool tty = isatty(2) && !quiet;
    const auto start = SteadyClock::now();
    auto last_print = start;
    ReferenceProgress progress;
    if (tty)
        progress = [&](std::size_t done, std::size_t total) {
            const auto now = SteadyClock::now();
            if (now - last_print < std::chrono::milliseconds(250)) return;
            last_print = now;
            std::fprintf(stderr, "\rpoint %zu / %zu  %.1f s   ", done, total, seconds_since(start));
        };
    const std::vector<ReferenceValue> values = reference_irradiance(scene, probes, ro, progress);
    const double seconds = seconds_since(start);
    if (tty) std::fprintf(stderr, "\r%*s\r", 79, "");

    write_text_file(probes_out, reference_csv(scene, probes, values));
    if (!quiet) {
        std::fprintf(stderr,
                     "hemirad: reference: %zu points x %ld samples in %.2f s; median relative "
                     "standard error %.3g %%\n",
                     probes.size(), ro.samples, seconds, 100 * median_relative_sem(values));
        std::fprintf(stderr, "hemirad: wrote %s (irradiance at %zu probes)\n", probes_out.c_str(),
                     probes.size());
    }
    return 0;
}

} // namespace hemirad::cli
