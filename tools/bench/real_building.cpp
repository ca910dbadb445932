// hemirad-bench experiment real_building: the default solve of buildings others modelled (or
// made as they model them), against the path-traced reference at random surface points.
#include "real_building.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <unistd.h>

#include "core/timer.h"
#include "hemirad/gather.h"
#include "hemirad/gl/context.h"
#include "hemirad/json.h"
#include "hemirad/reference.h"
#include "hemirad/report.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "hemirad/validation_scenes.h"
#include "output/atomic_file.h"
#include "point_stats.h"

namespace hemirad::bench {

namespace {

struct Building {
    std::string name;
    std::function<Scene()> scene;
    std::size_t points;    ///< random surface points
    std::uint64_t samples; ///< reference paths per point
    std::uint64_t seed;    ///< of the points
    /// Paths per point for a second reference pass over the points the first found lit (0:
    /// none): where the first leaves the lit points too noisy to read the solve's error.
    std::uint64_t lit_samples = 0;
};

// The office glb lit by three isotropic point sources of 500 cd, at 2.2 to 3 m above its
// floor, loaded through a SCENE.json as a user would write it (in the temporary directory,
// removed once read).
Scene office_with_point_sources(const std::string& office_glb) {
    Json j = Json::object();
    j["include"] = Json::array({std::filesystem::absolute(office_glb).string()});
    Json lights = Json::array();
    const dvec3 at[3] = {{0, 3.0, 0}, {-2.5, 2.2, 2.5}, {2.5, 2.6, -2.5}};
    for (int k = 0; k < 3; ++k) {
        Json l = Json::object();
        l["name"] = "P" + std::to_string(k + 1);
        l["candela"] = 500;
        l["position"] = at[k];
        lights.push_back(l);
    }
    j["luminaires"] = lights;
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("hemirad-bench-office-" + std::to_string(::getpid()) + ".json"))
                                 .string();
    write_file_atomically(path, j.dump(1));
    struct Remove {
        const std::string& path;
        ~Remove() {
            std::error_code ignored;
            std::filesystem::remove(path, ignored);
        }
    } remove{path};
    return load_scene(path);
}

// The median of the reference's lit points (a point under 1 % of it is dark).
double median_lit(const std::vector<ReferenceValue>& ref) {
    std::vector<double> lit;
    for (const ReferenceValue& r : ref)
        if (luminance(r.E) > 0) lit.push_back(luminance(r.E));
    return percentile(lit, 0.5);
}

// Traces the points k that picked(k) again with `samples` paths each, replacing their
// reference values; returns how many.
template <class Picked>
std::size_t trace_again(const Scene& scene, const std::vector<Probe>& probes,
                        const ReferenceOptions& ro, std::uint64_t samples,
                        std::vector<ReferenceValue>& ref, Picked&& picked) {
    std::vector<std::size_t> again;
    std::vector<Probe> again_probes;
    for (std::size_t k = 0; k < probes.size(); ++k)
        if (picked(k)) again.push_back(k), again_probes.push_back(probes[k]);
    if (again.empty()) return 0;
    ReferenceOptions more = ro;
    more.samples = samples;
    const std::vector<ReferenceValue> precise = reference_irradiance(scene, again_probes, more);
    for (std::size_t i = 0; i < again.size(); ++i) ref[again[i]] = precise[i];
    return again.size();
}

// Solve with the default options (as `hemirad solve SCENE --probes P --probe-out O`), read
// the points with the default final gather, and compare with the reference.
Json measure(const Building& b) {
    const auto t_load = SteadyClock::now();
    const Scene scene = b.scene();
    const double load_seconds = seconds_since(t_load);
    const std::vector<Probe> probes = random_surface_points(scene, b.points, b.seed);

    ReferenceOptions ro;
    ro.samples = b.samples;
    const auto t_ref = SteadyClock::now();
    std::vector<ReferenceValue> ref = reference_irradiance(scene, probes, ro);
    if (b.lit_samples > b.samples) {
        // Again, with more paths, at the points the first pass saw lit (a point it saw dark
        // stays as it was: the leak test needs only that it is dark).
        const double dark = 0.01 * median_lit(ref);
        trace_again(scene, probes, ro, b.lit_samples, ref,
                    [&](std::size_t k) { return luminance(ref[k].E) > dark; });
    }
    const double ref_seconds = seconds_since(t_ref);

    SolverOptions so;
    so.provider.gpu.use_current_context = true;
    Solver solver(scene, so);
    while (solver.step()) {}
    const Hierarchy& h = solver.solution();
    const auto t_points = SteadyClock::now();
    const FinalGather gather(h, GatherOptions{});
    const std::vector<ProbeValue> values = evaluate_probes(probes, h, &gather);
    const double point_seconds = seconds_since(t_points);

    // Dark: the reference under 1 % of the median of the points it sees lit (the back of an
    // outer wall, the inside of a slab). A dark point leaks when the solve reads it above 1 %
    // of that median and above the reference plus three standard errors.
    const double lit_median = median_lit(ref), dark = 0.01 * lit_median;
    // Before a dark point that the solve reads lit is called a leak, the reference traces it
    // again with at least 16 times the paths: where light comes through a gap (behind a
    // whiteboard, between a desk's side and the wall), few paths find it, and a short run
    // reads the point low with a standard error as low. In the office glb, two such points
    // read 0.22 and 0.36 % of the lit median with 65,536 paths, 2.68 and 1.05 % (standard
    // errors 0.12 and 0.06 %) with 16,777,216; the solve read them 2.75 and 1.03 %.
    const std::size_t doubtful = trace_again(
        scene, probes, ro, std::max(b.lit_samples, 16 * b.samples), ref, [&](std::size_t k) {
            return values[k].E && luminance(ref[k].E) <= dark && luminance(*values[k].E) > dark;
        });
    std::vector<double> err, signed_err, rel_sem;
    long dark_points = 0, leaking = 0, unread = 0;
    double worst_leak = 0;
    for (std::size_t k = 0; k < probes.size(); ++k) {
        const double y = luminance(ref[k].E), sem = luminance(ref[k].sem);
        if (!values[k].E) {
            ++unread;
            continue;
        }
        const double s = luminance(*values[k].E);
        if (y <= dark) {
            ++dark_points;
            if (s > dark && s > y + 3 * sem) {
                ++leaking;
                worst_leak = std::max(worst_leak, s / lit_median);
            }
            continue;
        }
        err.push_back(std::abs(s - y) / y);
        signed_err.push_back((s - y) / y);
        rel_sem.push_back(sem / y);
    }

    const Solver::RowSumStats rows = solver.row_sums();
    Json j = Json::object();
    j["building"] = b.name;
    j["polygons"] = scene.polygons.size();
    j["triangles"] = scene.triangle_count();
    j["leaf_patches"] = h.leaf_count();
    j["load_seconds"] = load_seconds;
    j["shots"] = solver.shots();
    j["solve_seconds"] = solver.seconds();
    j["point_seconds"] = point_seconds;
    j["error_bound"] = solver.error_bound();
    j["stop"] = to_string(solver.stop_reason());
    j["guarded_rows"] = rows.guarded;
    j["worst_row_sum"] = rows.max;
    j["points"] = probes.size();
    j["lit_points"] = err.size();
    j["dark_points"] = dark_points;
    j["leaking_dark_points"] = leaking;
    j["worst_leak_of_lit_median"] = worst_leak;
    j["dark_points_traced_again"] = doubtful;
    j["points_on_no_surface"] = unread;
    j["median"] = percentile(err, 0.5);
    j["p95"] = percentile(err, 0.95);
    j["median_signed"] = percentile(signed_err, 0.5);
    j["reference_samples"] = b.samples;
    j["reference_lit_samples"] = b.lit_samples;
    j["reference_seconds"] = ref_seconds;
    j["reference_median_relative_sem"] = percentile(rel_sem, 0.5);
    std::printf("ROW real_building %-10s %6zu tri  shots %5ld  solve %6.1f s  points %5.1f s  "
                "bound %.3g  guarded %ld  worst row %.4f  median %5.2f %%  p95 %5.2f %%  "
                "signed %+5.2f %%  dark %ld (leaking %ld; %zu traced again)  ref sem %.2f %%\n",
                b.name.c_str(), scene.triangle_count(), solver.shots(), solver.seconds(),
                point_seconds, solver.error_bound(), rows.guarded, rows.max,
                100 * percentile(err, 0.5), 100 * percentile(err, 0.95),
                100 * percentile(signed_err, 0.5), dark_points, leaking, doubtful,
                100 * percentile(rel_sem, 0.5));
    std::fflush(stdout);
    return j;
}

} // namespace

void run_real_building(const std::string& office_glb) {
    auto context = gl::Context::create();
    // Reference noise: 65,536 paths give a median relative standard error of ~0.5 % on the
    // courtyard (its points are lit by point sources, next-event estimated), well under the
    // 2 % median asked of the solve. The office's light comes from thin emissive bars, mostly
    // after a bounce: 65,536 paths leave ~6 % a point, so it gets 1000 points (about 320
    // of them lit; the rest are the backs of its two-sided walls, outside the room), and the
    // lit ones are traced again with 4,194,304 paths (median standard error about 1.2 %;
    // about 10 minutes on two cores). With 2,097,152 (1.7 %) the reference's noise alone made
    // a median error of about 1.15 %, over half the 2 % asked of the solve.
    std::vector<Building> buildings = {
        {"courtyard", [] { return validation::make_courtyard(); }, 400, 65536, 7},
    };
    if (!office_glb.empty() && std::filesystem::exists(office_glb)) {
        buildings.push_back(
            {"office", [office_glb] { return load_scene(office_glb); }, 1000, 65536, 7, 4194304});
        // The same office lit as the test building is, by point sources (three of
        // 500 cd in the room's air, 27.6 W against its bars' 2.4 W), through a SCENE.json as a
        // user would write it: a third-party building in the case the issue judges. Its
        // points are lit directly, next-event estimated: 65,536 paths give a median standard
        // error of 0.25 %.
        buildings.push_back({"office-pt",
                             [office_glb] { return office_with_point_sources(office_glb); }, 1000,
                             65536, 7});
    } else
        std::fprintf(stderr, "real_building: no office glb (%s): the courtyard only\n",
                     office_glb.empty() ? "not given" : office_glb.c_str());
    Json rows = Json::array();
    for (const Building& b : buildings) rows.push_back(measure(b));
    Json j = Json::object();
    j["name"] = "real_building";
    j["description"] = "default solve of real buildings vs hemirad reference at random points";
    j["buildings"] = rows;
    std::printf("JSON %s\n", j.dump(0).c_str());
}

} // namespace hemirad::bench
