// hemirad-bench experiment incremental: re-converging an edited lighting project from its
// solution against solving it again.
#include "incremental.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hemirad/gather.h"
#include "hemirad/gl/context.h"
#include "hemirad/grid.h"
#include "hemirad/json.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "point_stats.h"

namespace hemirad::bench {

namespace {

struct Run {
    long shots = 0;
    double seconds = 0;
    GridResult floor;
};

SolverOptions options(const char* layers = "auto") {
    SolverOptions so; // the defaults, as `hemirad solve ... --tolerance 0.001`
    so.tolerance = 1e-3;
    so.light_layers = layers;
    so.provider.gpu.use_current_context = true;
    return so;
}

/// Steps to convergence; the shots and seconds of these steps.
Run converge(Solver& s) {
    const long shots = s.shots();
    const double seconds = s.seconds();
    while (s.step()) {}
    if (!s.converged())
        throw std::runtime_error(std::string("incremental: stopped: ") +
                                 to_string(s.stop_reason()));
    return {s.shots() - shots, s.seconds() - seconds, {}};
}

GridResult floor_grid(Solver& s) {
    const Hierarchy& h = s.solution();
    const FinalGather gather(h, GatherOptions{});
    return evaluate_grid(h, parse_grid_spec("floor:12x8"), &gather);
}

/// The edit with light layers as `layers` says ("auto": each luminaire's share apart, the
/// edit a rescaling; "off": the edit shot as negative light).
void measure(const std::string& office_json, const char* layers) {
    Scene project = load_scene(office_json);
    Solver solver(project, options(layers));
    Run base = converge(solver);
    base.floor = floor_grid(solver);
    // The edit: D2 off, S1 at half its intensity; the solution re-converges from the last.
    solver.set_luminaire_multiplier("D2", 0);
    const double s1 = [&] {
        for (const Luminaire& l : project.luminaires)
            if (l.name == "S1") return l.multiplier;
        throw std::runtime_error("incremental: no S1 in " + office_json);
    }();
    solver.set_luminaire_multiplier("S1", 0.5 * s1);
    const double bound_after_edit = solver.error_bound();
    Run incremental = converge(solver);
    incremental.floor = floor_grid(solver);

    // A fresh solve of the edited project: D2 removed, S1 halved.
    Scene edited = load_scene(office_json);
    edited.luminaires.erase(std::remove_if(edited.luminaires.begin(), edited.luminaires.end(),
                                           [](const Luminaire& l) { return l.name == "D2"; }),
                            edited.luminaires.end());
    for (Luminaire& l : edited.luminaires)
        if (l.name == "S1") l.multiplier *= 0.5;
    Solver fresh_solver(edited, options());
    Run fresh = converge(fresh_solver);
    fresh.floor = floor_grid(fresh_solver);

    double worst = 0, worst_of_max = 0, y_max = 0;
    for (const GridPoint& p : fresh.floor.points) y_max = std::max(y_max, luminance(p.E));
    for (std::size_t k = 0; k < fresh.floor.points.size(); ++k) {
        const double a = luminance(incremental.floor.points[k].E);
        const double b = luminance(fresh.floor.points[k].E);
        if (!fresh.floor.points[k].on_surface || !(b > 0)) continue;
        worst = std::max(worst, std::abs(a / b - 1));
        worst_of_max = std::max(worst_of_max, std::abs(a - b) / y_max);
    }
    constexpr double kLux = 683; // lm/W: the grid's E_Y in lux (the office is in metres)
    Json j = Json::object();
    j["name"] = "incremental";
    j["description"] = "office.json converged, D2 off and S1 halved: re-converge vs fresh solve";
    j["scene"] = office_json;
    j["light_layers"] = layers;
    j["has_light_layers"] = solver.has_light_layers();
    j["tolerance"] = 1e-3;
    j["base_shots"] = base.shots;
    j["base_seconds"] = base.seconds;
    j["error_bound_after_edit"] = bound_after_edit;
    j["incremental_shots"] = incremental.shots;
    j["incremental_seconds"] = incremental.seconds;
    j["incremental_shots_of_base"] = double(incremental.shots) / double(base.shots);
    j["fresh_shots"] = fresh.shots;
    j["fresh_seconds"] = fresh.seconds;
    j["floor_grid"] = "floor:12x8";
    j["floor_avg_lux_base"] = kLux * base.floor.Y_avg;
    j["floor_avg_lux_incremental"] = kLux * incremental.floor.Y_avg;
    j["floor_avg_lux_fresh"] = kLux * fresh.floor.Y_avg;
    j["max_grid_difference"] = worst;
    j["max_grid_difference_of_max"] = worst_of_max;
    std::printf("JSON %s\n", j.dump(0).c_str());
    std::printf("ROW incremental  layers %-4s base %ld shots %.1f s  edit: bound %.3g, %ld shots "
                "(%.1f %% of base) %.1f s  fresh %ld shots %.1f s  floor 12x8 max diff %.2f %% "
                "(Eavg %.1f -> %.1f lx)\n",
                layers, base.shots, base.seconds, bound_after_edit, incremental.shots,
                100.0 * double(incremental.shots) / double(base.shots), incremental.seconds,
                fresh.shots, fresh.seconds, 100 * worst, kLux * base.floor.Y_avg,
                kLux * incremental.floor.Y_avg);
    std::fflush(stdout);
}

} // namespace

void run_incremental(const std::string& office_json) {
    auto context = gl::Context::create();
    measure(office_json, "auto");
    measure(office_json, "off");
}

} // namespace hemirad::bench
