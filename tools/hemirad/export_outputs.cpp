#include "export_outputs.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <set>

#include "hemirad/error.h"
#include "hemirad/export.h"
#include "hemirad/image.h"
#include "hemirad/report.h"

namespace hemirad::cli {

void add_export_options(ArgParser& args, ExportOptions& o) {
    args.section("grids, exports, save and resume");
    args.multi("--grid", &o.grids, "GROUP:NXxNY",
               "irradiance on NXxNY points over a planar surface group (repeatable; x or ×)");
    args.option("--grid-out", &o.grid_out, "FILE.csv",
                "all grid points: group,i,j,x,y,z,E_r,E_g,E_b,E_Y[,lux][,DF]");
    args.option("--grid-png", &o.grid_png, "DIR",
                "per grid, DIR/GROUP.png: a false-colour plan with the value of every point, "
                "Emin, Eavg, Emax, U0 and Emin/Emax (lux with --lux) and the luminaires");
    // --lux is registered once, with the image options (it also sets the false-colour unit);
    // cmd_solve copies it into ExportOptions::lux.
    args.option("--export-ply", &o.ply, "FILE.ply",
                "leaf-level mesh with per-vertex radiosity (binary PLY)");
    args.option("--export-lightmaps", &o.lightmaps, "DIR",
                "per surface group: DIR/GROUP.exr atlas of leaf radiosity + GROUP.obj with UVs");
    args.option("--save-solution", &o.save_solution, "FILE",
                "save the solver state at the end (also when interrupted)");
    args.option("--resume", &o.resume, "FILE",
                "continue from a saved state: same scene; options not given take the saved "
                "values, given ones must match; --time-limit counts the saved run's time");
    args.section("point read-outs (probes, grids)");
    args.option("--gather", &o.gather, "on|off",
                "final gather at each point: direct light from the emitters with their area "
                "visibility sampled, indirect from the solution by rays (off: interpolate the "
                "leaf patches around the point)");
    args.flag("--daylight-factor", &o.daylight_factor,
              "probes, grids, grid plans and the report also in daylight factor DF = 100 E / "
              "E_h % (column DF; per grid DF avg, min, median, share >= 1, 2, 3 %), E_h the "
              "sky's horizontal illuminance; needs a \"sky\" in the SCENE.json");
    args.option("--gather-rays", &o.gather_options.rays, "N",
                "final gather: cosine rays per point for the indirect light (16..65536)");
    args.option("--gather-error", &o.gather_options.indirect_error, "E",
                "final gather: a point whose indirect estimate has a relative standard error "
                "above E is gathered again with up to 16 times the rays [0, 1); 0 = never");
    args.option("--gather-angle", &o.gather_options.emitter_angle, "A",
                "final gather: widest emitter cell seen from a point, radians (0..1]");
    args.option("--gather-bright", &o.gather_options.bright_factor, "F",
                "final gather: the indirect rays also sample the leaf patches brighter than F "
                "times the scene's mean (a lamp's shade, the ceiling over an uplight), by "
                "multiple importance sampling; 0 or [1, 1e6]; 0 = cosine rays alone");
}

std::vector<GridSpec> validate_export_options(const ExportOptions& o) {
    std::vector<GridSpec> specs;
    for (const std::string& g : o.grids) specs.push_back(parse_grid_spec(g));
    if (!o.grid_out.empty() && specs.empty())
        throw InputError("--grid-out needs at least one --grid GROUP:NXxNY");
    if (!o.grid_png.empty() && specs.empty())
        throw InputError("--grid-png needs at least one --grid GROUP:NXxNY");
    if (o.gather != "on" && o.gather != "off")
        throw InputError("--gather '" + o.gather + "' must be on or off");
    validate_gather_options(o.gather_options);
    return specs;
}

std::unique_ptr<FinalGather> make_gather(const ExportOptions& o, const Hierarchy& h) {
    if (o.gather != "on") return nullptr;
    return std::make_unique<FinalGather>(h, o.gather_options);
}

std::optional<SolutionFile> prepare_resume(const ExportOptions& o, const ArgParser& args,
                                           const Scene& scene, const std::string& scene_name,
                                           SolverOptions& so) {
    if (o.resume.empty()) return std::nullopt;
    SolutionFile f = read_solution(o.resume);
    check_solution_scene(f, o.resume, scene, scene_name);
    const std::vector<SolutionOption> now = solution_options(so);
    for (const SolutionOption& saved : f.options) {
        if (!args.given(saved.first)) {
            apply_solution_option(so, saved, o.resume);
            continue;
        }
        for (const SolutionOption& given : now)
            if (given.first == saved.first && given.second != saved.second)
                throw InputError(o.resume + ": the solution was saved with " + saved.first + " " +
                                 saved.second + ", but the command line gives " + given.first +
                                 " " + given.second +
                                 " (leave it out to resume with the saved value)");
    }
    return f;
}

void write_solution_file(const ExportOptions& o, const Solver& solver, bool quiet) {
    if (o.save_solution.empty()) return;
    save_solution(o.save_solution, solver);
    if (!quiet)
        std::fprintf(stderr, "hemirad: saved the solver state after %ld shots to %s\n",
                     solver.shots(), o.save_solution.c_str());
}

std::vector<GridResult> evaluate_grids(const std::vector<GridSpec>& specs, const Hierarchy& h,
                                       const FinalGather* gather, bool quiet) {
    std::vector<GridResult> grids;
    for (const GridSpec& s : specs) {
        grids.push_back(evaluate_grid(h, s, gather));
        const GridResult& g = grids.back();
        if (!quiet && g.skipped > 0)
            std::fprintf(stderr,
                         "hemirad: grid %s:%dx%d: %ld of %ld points lie on no polygon of the "
                         "group and were skipped\n",
                         s.group.c_str(), s.nx, s.ny, g.skipped, long(g.points.size()));
    }
    return grids;
}

void write_export_outputs(const ExportOptions& o, const std::vector<GridResult>& grids,
                          const Hierarchy& h, bool quiet) {
    if (!o.grid_out.empty()) write_text_file(o.grid_out, grids_csv(grids, o.lux, o.daylight_lux));
    if (!o.grid_png.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(o.grid_png, ec);
        if (ec) throw RuntimeError("--grid-png: cannot create " + o.grid_png + ": " + ec.message());
        std::set<std::string> used;
        for (const GridResult& g : grids) {
            std::string name;
            for (char c : g.spec.group)
                name +=
                    std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' ? c : '_';
            if (name.empty() || name[0] == '.') name.insert(0, "grid");
            if (!used.insert(name).second)
                name.append("-")
                    .append(std::to_string(g.spec.nx))
                    .append("x")
                    .append(std::to_string(g.spec.ny));
            used.insert(name);
            const std::string path = (std::filesystem::path(o.grid_png) / (name + ".png")).string();
            write_png(path, grid_plan_image(g, o.lux, h.scene().luminaires, o.daylight_lux));
            if (!quiet) std::fprintf(stderr, "hemirad: wrote %s (grid plan)\n", path.c_str());
        }
    }
    if (!o.ply.empty()) export_ply(o.ply, h);
    if (!o.lightmaps.empty()) {
        const std::vector<std::string> files = export_lightmaps(o.lightmaps, h, o.discontinuities);
        if (!quiet)
            std::fprintf(stderr, "hemirad: wrote %zu lightmap files to %s\n", files.size(),
                         o.lightmaps.c_str());
    }
}

} // namespace hemirad::cli
