#include "scene_edits.h"

#include "hemirad/scene_edit.h"

namespace hemirad::cli {

void add_scene_edit_options(ArgParser& args, SceneEdits& e) {
    args.section("edits of the scene's light (also with --resume: re-converges incrementally)");
    args.multi("--luminaire-multiplier", &e.multipliers, "NAME=F",
               "scale luminaire NAME's intensity by F (>= 0; 0 = off; repeatable)");
    args.multi("--reflectance", &e.reflectances, "GROUP=R",
               "set surface group GROUP's reflectance to R or R,G,B (each in [0, 1); "
               "untextured groups; repeatable)");
}

void validate_scene_edits(const SceneEdits& e) {
    for (const std::string& m : e.multipliers) parse_scene_edit("--luminaire-multiplier", m, 1);
    for (const std::string& r : e.reflectances) parse_scene_edit("--reflectance", r, 3);
}

void apply_scene_edits(const SceneEdits& e, Scene& scene) {
    for (const std::string& m : e.multipliers) {
        const auto [name, f] = parse_scene_edit("--luminaire-multiplier", m, 1);
        set_luminaire_multiplier(scene, name, f.x);
    }
    for (const std::string& r : e.reflectances) {
        const auto [group, rho] = parse_scene_edit("--reflectance", r, 3);
        set_group_reflectance(scene, group, rho);
    }
}

} // namespace hemirad::cli
