// What `hemirad solve` writes after solving, and its signal handling.
#pragma once

#include <string>
#include <vector>

#include "cli/args.h"
#include "hemirad/report.h"
#include "hemirad/solver.h"
#include "image_outputs.h"

namespace hemirad::cli {

/// Image and export outputs of a solve.
struct OutputOptions {
    ImageOutputOptions images;
    bool needs_gl() const { return image_outputs_need_gl(images); }
};
void add_output_options(ArgParser& args, OutputOptions& o);
void validate_output_options(const OutputOptions& o);
void write_outputs(const OutputOptions& o, Solver& solver, bool quiet);

/// The JSON report; `resume`, unless null, goes in as its "resume" key (hemirad solve --resume:
/// file, shots_before, shots_this_run, incremental, luminaires_changed, luminaires_rescaled,
/// polygons_changed).
void write_report(const std::string& path, Solver& solver, const Scene& scene,
                  const std::vector<GridResult>& grids = {}, bool lux = false,
                  double daylight_lux = 0, const Json* resume = nullptr);

/// SIGINT/SIGTERM set a flag: the solve finishes its shot, writes its outputs, exits non-zero.
void install_interrupt_handler();
bool interrupted();

} // namespace hemirad::cli
