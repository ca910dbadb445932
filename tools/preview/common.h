// Option wiring shared by hemirad-preview and hemirad-view: the solver, form-factor and
// built-in scene options of `hemirad solve`, with the same names, defaults and help, so that
// the three tools solve a scene the same way. Header-only (each tool folder is its own
// executable); a candidate for a shared tools/common/ library next to tools/hemirad's copy.
#pragma once

#include <cstdio>
#include <string>

#include "hemirad/args.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"

namespace hemirad::tool {

/// Solver and form-factor options, as `hemirad solve` spells them.
inline void add_solver_options(ArgParser& args, SolverOptions& so) {
    args.section("solver");
    args.option("--ff", &so.ff, "METHOD",
                "form factors: hybrid, analytic, hemicube (GPU); reference, pdm, sr (CPU)");
    args.option("--tolerance", &so.tolerance, "T",
                "stop when the error bound is under T times the emitted power");
    args.option("--max-shots", &so.max_shots, "N", "stop after N shots");
    args.option("--time-limit", &so.time_limit, "S", "stop after S seconds (0 = no limit)");
    args.option("--patch-size", &so.hierarchy.patch_size, "S",
                "leaf patch size in scene units (0 = scene diagonal / 64)");
    args.option("--max-depth", &so.hierarchy.max_depth, "D", "deepest quadtree level (0..11)");
    args.option("--shooter-power", &so.shooter_power_fraction, "F",
                "shooter descent stops before a child with less than F of the unshot power");
    args.option("--shooter-size", &so.shooter_min_size, "S",
                "shooter descent stops before a child smaller than S (0 = half a leaf)");
    args.flag("--flat", &so.flat, "shoot from leaf patches only (no hierarchy)");
    args.flag("--row-guard", &so.row_guard, "rescale a shot whose form-factor row sum exceeds 1");
    args.option("--enclosed-fraction", &so.enclosed_fraction, "F",
                "shoot the children of a shooter whose hemisphere is more than F backs of "
                "polygons");
    args.section("form factors");
    args.option("--resolution", &so.provider.gpu.resolution, "N",
                "GPU: fixed hemicube resolution (0 = adaptive)");
    args.option("--min-resolution", &so.provider.gpu.min_resolution, "N",
                "GPU: adaptive resolution for the weakest shooters");
    args.option("--max-resolution", &so.provider.gpu.max_resolution, "N",
                "GPU: adaptive resolution for the strongest shooters");
    args.option("--lod-bias", &so.provider.gpu.lod_bias, "B",
                "GPU: mip LOD bias (+1 links patches twice as large)");
    args.flag("--builtin-acos", &so.provider.gpu.builtin_acos,
              "GPU: GLSL acos instead of the 2048-entry lookup table");
    args.option("--link-angle", &so.provider.cpu.link_angle, "A",
                "CPU: refine receivers while size/distance exceeds A");
    args.option("--visibility-samples", &so.provider.cpu.visibility_samples, "N",
                "reference: NxN shooter points for ray-cast visibility");
}

/// Built-in scene parameters, as `hemirad solve` spells them.
inline void add_builtin_scene_options(ArgParser& args, BuiltinOptions& o) {
    args.section("built-in scenes");
    args.option("--subdiv", &o.subdiv, "N",
                "cube, furnace: split each face into NxN polygons (1..1000)");
    args.option("--rho", &o.rho, "R",
                "reflectance of every surface, in [0,1); negative = the scene's own");
    args.option("--rings", &o.sphere_rings, "N", "sphere: latitude rings (4..512)");
}

/// Prints "TOOL: warning: SOURCE: ..." for each scene warning unless quiet.
inline void print_scene_warnings(const char* tool, const Scene& scene, bool quiet) {
    if (quiet) return;
    for (const std::string& w : scene.warnings)
        std::fprintf(stderr, "%s: warning: %s: %s\n", tool, scene.source.c_str(), w.c_str());
}

} // namespace hemirad::tool
