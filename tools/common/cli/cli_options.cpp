#include "cli/cli_options.h"

#include <cstdio>
#include <optional>
#include <variant>

#include "core/parse.h"
#include "hemirad/error.h"
#include "hemirad/memory_guard.h"
#include "hemirad/solver_options.h"

namespace hemirad {

void add_solver_option(ArgParser& args, SolverOptions& so, const SolverOption& option,
                       const char* help) {
    const std::string flag = option.flag;
    const std::string text = help ? help : option.help;
    const SolverOption::Field field = option.field(so);
    if (auto p = std::get_if<std::string*>(&field)) {
        args.option(flag, *p, option.metavar, text);
    } else if (auto p = std::get_if<double*>(&field)) {
        args.option(flag, *p, option.metavar, text);
    } else if (auto p = std::get_if<int*>(&field)) {
        args.option(flag, *p, option.metavar, text);
    } else if (auto p = std::get_if<long*>(&field)) {
        args.option(flag, *p, option.metavar, text);
    } else if (auto p = std::get_if<bool*>(&field)) {
        if (option.inverted)
            args.flag_off(flag, *p, text);
        else
            args.flag(flag, *p, text);
    } else {
        std::uint64_t* out = std::get<std::uint64_t*>(field);
        const bool size = option.size;
        args.custom(
            flag,
            [out, flag, size](const std::string& v) {
                if (size) {
                    *out = parse_memory_size(v, flag);
                    return;
                }
                const std::optional<unsigned long long> n = parse_unsigned(v);
                if (!n) throw InputError(flag + ": '" + v + "' is not an integer");
                *out = *n;
            },
            option.metavar, text, std::to_string(*out));
    }
}

void add_solver_options(ArgParser& args, SolverOptions& so) {
    std::string section;
    for (const SolverOption& option : solver_option_table()) {
        if (section != option.section) args.section(section = option.section);
        add_solver_option(args, so, option);
    }
}

void add_solver_option(ArgParser& args, SolverOptions& so, const std::string& flag,
                       const char* help) {
    const SolverOption* option = find_solver_option(flag);
    HEMIRAD_CHECK(option != nullptr && option->flag == flag);
    add_solver_option(args, so, *option, help);
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
    args.flag("--two-sided-surfaces", &o.two_sided_surfaces,
              "every polygon of the scene files is two-sided: each side receives and reflects "
              "light on its own (a back-to-back twin); glTF materials marked doubleSided are "
              "two-sided anyway");
    args.custom(
        "--split-intersections",
        [&o](const std::string& v) {
            if (v != "on" && v != "off")
                throw InputError("--split-intersections '" + v + "' must be on or off");
            o.split_intersections = v == "on";
        },
        "on|off",
        "cut polygons where other polygons pass through them (a wall reaching below the floor, "
        "an object sunk into another), so that no patch carries light from one side into the "
        "other (Default: on)");
}

void add_scene_options(ArgParser& args, BuiltinOptions& builtin, ObjOptions& obj) {
    add_builtin_scene_options(args, builtin);
    add_obj_scene_options(args, obj);
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
