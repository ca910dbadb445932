// Loading scenes: OBJ/MTL files and the built-in scenes.
#pragma once

#include <string>

#include "hemirad/scene.h"

namespace hemirad {

/// Options of the built-in scenes (ignored where they do not apply).
struct BuiltinOptions {
    int subdiv = 1;         ///< cube/furnace: each face split into subdiv x subdiv quads (1..1000)
    double rho = -1.0;      ///< reflectance of every surface; <0 = the scene's own default
    int sphere_rings = 16;  ///< sphere: latitude rings (>= 4); longitude segments = 2x rings
};

/// Options of OBJ/MTL files.
struct ObjOptions {
    /// Reflectance used for a Kd channel of 1 or more (a surface can't reflect all the light it
    /// receives; exporters write Kd 1 for white), in (0, 1). Kd values under 1 are kept as given.
    double max_reflectance = 0.98;
};

/// Loads "NAME" (a built-in scene) or a path to an OBJ file. Throws InputError on bad input.
Scene load_scene(const std::string& name_or_path, const BuiltinOptions& builtin = {},
                 const ObjOptions& obj = {});

/// Loads an OBJ file and the MTL files it names (obj_loader.cpp lists what is tolerated, with a
/// warning each, and what is an error). Throws InputError naming file, line and value.
Scene load_obj(const std::string& path, const ObjOptions& options = {});

/// Built-in scenes: "cornell", "cube", "furnace", "sphere". Throws InputError for other names.
Scene make_builtin(const std::string& name, const BuiltinOptions& options = {});
bool is_builtin(const std::string& name);
const char* builtin_names(); ///< "cornell, cube, furnace, sphere"

} // namespace hemirad
