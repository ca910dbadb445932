// Command-line options shared by hemirad's tools (hemirad solve, hemirad-preview,
// hemirad-view): the solver, form-factor and built-in scene options, with one spelling, one
// default and one help text each, so that the tools solve a scene the same way.
#pragma once

#include <string>

#include "cli/args.h"
#include "hemirad/scene.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"

namespace hemirad {

/// --ff, --tolerance, --max-shots, ..., --resolution, --lod-bias, --backend, ...
void add_solver_options(ArgParser& args, SolverOptions& so);

/// --subdiv, --rho, --rings.
void add_builtin_scene_options(ArgParser& args, BuiltinOptions& o);

/// --max-reflectance.
void add_obj_scene_options(ArgParser& args, ObjOptions& o);

/// Prints "TOOL: warning: SOURCE: ..." for each scene warning unless quiet.
void print_scene_warnings(const char* tool, const Scene& scene, bool quiet);

} // namespace hemirad
