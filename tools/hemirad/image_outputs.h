// Image outputs of `hemirad solve`: rendered views (-o FILE.exr / FILE.png) and the
// false-colour irradiance view.
#pragma once

#include <string>
#include <vector>

#include "hemirad/args.h"
#include "hemirad/solver.h"

namespace hemirad::cli {

struct ImageOutputOptions {
    std::vector<std::string> files; ///< -o FILE.exr / FILE.png (repeatable)
};
void add_image_options(ArgParser& args, ImageOutputOptions& o);
void validate_image_options(const ImageOutputOptions& o);
bool image_outputs_need_gl(const ImageOutputOptions& o);
/// Writes every image asked for, from the solver's current solution (GL context current).
void write_image_outputs(const ImageOutputOptions& o, Solver& solver, bool quiet);

} // namespace hemirad::cli
