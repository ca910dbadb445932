#include "cli/cli_options.h"

#include <cstdio>

#include "hemirad/memory_guard.h"

namespace hemirad {

void add_solver_options(ArgParser& args, SolverOptions& so) {
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
    args.option("--shooter-max-size", &so.shooter_max_size, "S",
                "shooter descent always goes below nodes larger than S (0 = no limit)");
    args.flag("--flat", &so.flat, "shoot from leaf patches only (no hierarchy)");
    args.flag_off("--no-row-guard", &so.row_guard,
                  "keep form-factor rows that sum above 1 (by default they are rescaled to 1)");
    args.option("--enclosed-fraction", &so.enclosed_fraction, "F",
                "shoot the children of a shooter whose hemisphere is more than F backs of "
                "polygons");
    args.option("--shooter-parallax", &so.shooter_parallax, "F",
                "shoot a node's children instead of the node when its view changes across "
                "its area by more than this share of its form factor (0 = never)");
    std::uint64_t* limit = &so.memory_limit;
    args.custom(
        "--memory-limit",
        [limit](const std::string& v) { *limit = parse_memory_size(v, "--memory-limit"); }, "SIZE",
        "refuse a discretisation whose estimated memory exceeds SIZE (bytes, or 512M, 4G, ...; "
        "0 = the memory available: MemAvailable, or the cgroup limit if lower)",
        "0");
    args.section("form factors");
    args.option("--resolution", &so.provider.gpu.resolution, "N",
                "GPU: fixed hemicube resolution (0 = adaptive)");
    args.option("--min-resolution", &so.provider.gpu.min_resolution, "N",
                "GPU: adaptive resolution for the weakest shooters");
    args.option("--max-resolution", &so.provider.gpu.max_resolution, "N",
                "GPU: adaptive resolution for the strongest shooters");
    args.option("--lod-bias", &so.provider.gpu.lod_bias, "B",
                "GPU: mip LOD bias (+1 links patches twice as large)");
    args.flag("--atan-angle", &so.provider.gpu.atan_angle,
              "GPU: GLSL atan(|a x b|, a.b) for angles (most precise)");
    args.flag("--builtin-acos", &so.provider.gpu.builtin_acos,
              "GPU: GLSL acos instead of the 2048-entry lookup table");
    args.option("--backend", &so.provider.gpu.backend, "NAME", "GL backend: auto, egl, osmesa");
    args.option("--device", &so.provider.gpu.device, "N", "EGL device index (-1 = default)");
    args.option("--link-angle", &so.provider.cpu.link_angle, "A",
                "CPU: refine receivers while size/distance exceeds A");
    args.option("--visibility-samples", &so.provider.cpu.visibility_samples, "N",
                "reference: NxN shooter points for ray-cast visibility");
}

void add_builtin_scene_options(ArgParser& args, BuiltinOptions& o) {
    args.section("built-in scenes");
    args.option("--subdiv", &o.subdiv, "N",
                "cube, furnace: split each face into NxN polygons (1..1000)");
    args.option("--rho", &o.rho, "R",
                "cornell, cube, furnace, sphere, cie58: reflectance of every surface, in [0,1); "
                "negative = the scene's own (cie58: 0.5)");
    args.option("--rings", &o.sphere_rings, "N", "sphere: latitude rings (4..512)");
}

void add_obj_scene_options(ArgParser& args, ObjOptions& o) {
    args.section("scene files");
    args.option("--max-reflectance", &o.max_reflectance, "R",
                "OBJ/MTL: reflectance used for a Kd channel of 1 or more, in (0,1) (a surface "
                "can't reflect all the light it receives)");
}

void print_scene_warnings(const char* tool, const Scene& scene, bool quiet) {
    if (quiet) return;
    for (const std::string& w : scene.warnings) {
        // A warning that names a place in the scene file itself needs no second file name.
        const bool placed = w.rfind(scene.source + ":", 0) == 0;
        std::fprintf(stderr, "%s: warning: %s%s%s\n", tool, placed ? "" : scene.source.c_str(),
                     placed ? "" : ": ", w.c_str());
    }
}

} // namespace hemirad
