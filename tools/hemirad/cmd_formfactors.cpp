// hemirad formfactors: the form factor from one surface group to every group (paper 000).
#include <cstdio>
#include <iostream>

#include "cli/cli_options.h"
#include "commands.h"
#include "hemirad/error.h"
#include "hemirad/hierarchy.h"
#include "hemirad/json.h"
#include "hemirad/provider.h"
#include "hemirad/solver.h"

namespace hemirad::cli {

int cmd_formfactors(int argc, char** argv) {
    std::string scene_name, from;
    bool json = false, leaves = false;
    SolverOptions so; // the options this command shares with hemirad solve, from its table
    so.hierarchy.max_depth = 0;
    BuiltinOptions builtin;
    ObjOptions obj;
    ArgParser args("hemirad formfactors", "hemirad formfactors SCENE --from GROUP [options]",
                   "Shoots from every leaf patch of every polygon of GROUP and reports the form\n"
                   "factor from GROUP to every group, F(GROUP -> G) = sum over shooters of\n"
                   "A_s F(s -> G) / A_GROUP, and the row sum (1 in a closed scene).");
    args.positional("SCENE", &scene_name, "OBJ or glTF file, SCENE.json or built-in scene");
    args.option("--from", &from, "GROUP", "the shooting surface group");
    add_solver_option(args, so, "--ff");
    add_solver_option(args, so, "--max-depth", "receiver and shooter quadtree depth (0..11)");
    add_solver_option(args, so, "--patch-size");
    args.flag("--leaves", &leaves, "link receivers at their leaves (no adaptive linking)");
    add_solver_option(args, so, "--resolution", "GPU: hemicube resolution (0 = 512)");
    for (const char* flag : {"--lod-bias", "--builtin-acos", "--atan-angle", "--backend",
                             "--sr-rays", "--sr-points", "--gauss-order"})
        add_solver_option(args, so, flag);
    args.flag("--json", &json, "print JSON");
    add_scene_options(args, builtin, obj);
    if (!args.parse(argc, argv, 2)) return 0;
    if (from.empty()) throw InputError("--from GROUP is required");
    ProviderOptions& po = so.provider;
    const HierarchyOptions& ho = so.hierarchy;
    const std::string& ff = so.ff;
    if (po.gpu.resolution == 0) po.gpu.resolution = 512;

    const Scene scene = load_scene(scene_name, builtin, obj);
    const int g_from = scene.find_group(from);
    if (g_from < 0) {
        std::string names;
        for (const std::string& g : scene.groups) names += (names.empty() ? "" : ", ") + g;
        throw InputError("no surface group '" + from + "' in " + scene.source +
                         " (groups: " + names + ")");
    }
    const Discretisation disc = discretise(scene, ho);
    auto provider = make_provider(ff, scene, disc, po);
    provider->set_link_at_leaves(leaves);
    const GroupFormFactors r = group_form_factors(scene, disc, *provider, std::uint32_t(g_from));
    const std::vector<double>& to = r.to;
    const double row = r.row_sum, seconds = r.seconds;
    if (json) {
        Json j = Json::object();
        j["from"] = from;
        j["ff"] = ff;
        j["max_depth"] = ho.max_depth;
        Json t = Json::object();
        for (std::size_t g = 0; g < to.size(); ++g) t[scene.groups[g]] = to[g];
        j["to"] = t;
        j["row_sum"] = row;
        j["seconds"] = seconds;
        std::cout << j.dump() << "\n";
        return 0;
    }
    std::printf("form factors from '%s' (%s, max depth %d)\n", from.c_str(), ff.c_str(),
                ho.max_depth);
    for (std::size_t g = 0; g < to.size(); ++g)
        std::printf("  -> %-16s %.7f\n", scene.groups[g].c_str(), to[g]);
    std::printf("  row sum            %.7f\n  seconds            %.3f\n", row, seconds);
    return 0;
}

} // namespace hemirad::cli
