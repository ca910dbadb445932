// `hemirad solve` edits of the scene's light given on the command line (scene_edit.h):
// --luminaire-multiplier NAME=F and --reflectance GROUP=R|R,G,B, applied to the loaded scene
// before it is solved; with --resume, the solution re-converges from the saved one.
#pragma once

#include <string>
#include <vector>

#include "cli/args.h"
#include "hemirad/scene.h"

namespace hemirad::cli {

struct SceneEdits {
    std::vector<std::string> multipliers;  ///< --luminaire-multiplier NAME=F, repeatable
    std::vector<std::string> reflectances; ///< --reflectance GROUP=R or GROUP=R,G,B, repeatable
    bool empty() const { return multipliers.empty() && reflectances.empty(); }
};
void add_scene_edit_options(ArgParser& args, SceneEdits& e);
/// Checks the spelling of every edit (NAME=number), before the scene is loaded. InputError.
void validate_scene_edits(const SceneEdits& e);
/// Applies the edits in command-line order (a later one of the same name wins). Throws
/// InputError naming the flag and the value (unknown luminaire or group, out of range).
void apply_scene_edits(const SceneEdits& e, Scene& scene);

} // namespace hemirad::cli
