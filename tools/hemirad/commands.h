// The hemirad command-line program: one function per subcommand.
#pragma once

#include <string>

#include "cli/args.h"
#include "cli/cli_options.h"
#include "hemirad/scene_io.h"

namespace hemirad::cli {

int cmd_info(int argc, char** argv);
int cmd_scene(int argc, char** argv);
int cmd_solve(int argc, char** argv);
int cmd_batch(int argc, char** argv);
int cmd_formfactors(int argc, char** argv);
int cmd_reference(int argc, char** argv);

/// Prints "hemirad: warning: ..." for each scene warning unless quiet.
void print_warnings(const Scene& scene, bool quiet);

} // namespace hemirad::cli
