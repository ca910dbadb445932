// Command-line options shared by hemirad's tools (hemirad solve, hemirad-preview,
// hemirad-view): the solver, form-factor and built-in scene options, with one spelling, one
// default and one help text each, so that the tools solve a scene the same way.
#pragma once

#include <string>

#include "cli/args.h"
#include "hemirad/scene.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "hemirad/solver_options.h"

namespace hemirad {

/// Every option of the options table (hemirad/solver_options.h), in its sections: --ff,
/// --tolerance, --max-shots, ..., --resolution, --lod-bias, --backend, ... Each sets its field
/// of `so`, whose values are the defaults --help shows.
void add_solver_options(ArgParser& args, SolverOptions& so);
/// One option of the table, for a command that takes only some (hemirad formfactors); `help`
/// replaces the table's text where the command gives the option another meaning or default.
void add_solver_option(ArgParser& args, SolverOptions& so, const SolverOption& option,
                       const char* help = nullptr);
/// The same, by its flag ("--max-depth").
void add_solver_option(ArgParser& args, SolverOptions& so, const std::string& flag,
                       const char* help = nullptr);

/// --subdiv, --rho, --rings.
void add_builtin_scene_options(ArgParser& args, BuiltinOptions& o);

/// --max-reflectance.
void add_obj_scene_options(ArgParser& args, ObjOptions& o);

/// Both: the options that select and shape a scene (built-in scenes' parameters, OBJ/MTL
/// reading).
void add_scene_options(ArgParser& args, BuiltinOptions& builtin, ObjOptions& obj);

/// Prints "TOOL: warning: SOURCE: ..." for each scene warning unless quiet.
void print_scene_warnings(const char* tool, const Scene& scene, bool quiet);

} // namespace hemirad
