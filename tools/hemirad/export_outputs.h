// `hemirad solve` options for results people use: calculation grids, exports (PLY,
// lightmaps), and saving/resuming the solver state.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/args.h"
#include "hemirad/gather.h"
#include "hemirad/grid.h"
#include "hemirad/solution_file.h"
#include "hemirad/solver.h"

namespace hemirad::cli {

struct ExportOptions {
    std::vector<std::string> grids; ///< --grid GROUP:NXxNY, repeatable
    std::string grid_out;           ///< --grid-out FILE.csv: every grid's points, one file
    std::string grid_png;           ///< --grid-png DIR: a false-colour plan per grid
    bool lux = false;               ///< --lux (shared with the images): grids also in lux
    bool daylight_factor = false;   ///< --daylight-factor: probes and grids also in DF %
    double daylight_lux = 0;        ///< E_h [lux] of the scene's sky, set by cmd_solve
    std::string ply;                ///< --export-ply FILE.ply
    std::string lightmaps;          ///< --export-lightmaps DIR
    std::string save_solution;      ///< --save-solution FILE: solver state at the end
    std::string resume;             ///< --resume FILE: continue from a saved state
    std::string gather = "on";      ///< --gather on|off: probes and grids by final gather
    bool discontinuities = true;    ///< --discontinuities (an image option): lightmap detail
    GatherOptions gather_options;   ///< --gather-rays, --gather-error, --gather-angle, ...
};
void add_export_options(ArgParser& args, ExportOptions& o);
/// Checks combinations and parses the grid specs. Throws InputError.
std::vector<GridSpec> validate_export_options(const ExportOptions& o);

/// With --resume: reads the file, checks that it was saved for `scene` (loaded from
/// `scene_name`), refuses options given on the command line that differ from the saved ones
/// (naming the option) and takes the saved value of those not given. Nothing without --resume.
std::optional<SolutionFile> prepare_resume(const ExportOptions& o, const ArgParser& args,
                                           const Scene& scene, const std::string& scene_name,
                                           SolverOptions& so);

/// Writes --save-solution (call after the last step, before Solver::solution()).
void write_solution_file(const ExportOptions& o, const Solver& solver, bool quiet);

/// The final gather for probes and grids (nullptr with --gather off), on the push-pulled
/// solution.
std::unique_ptr<FinalGather> make_gather(const ExportOptions& o, const Hierarchy& h);

/// Evaluates the grids on the push-pulled solution (by final gather when `gather` is given).
std::vector<GridResult> evaluate_grids(const std::vector<GridSpec>& specs, const Hierarchy& h,
                                       const FinalGather* gather, bool quiet);
/// Writes --grid-out, --grid-png, --export-ply and --export-lightmaps.
void write_export_outputs(const ExportOptions& o, const std::vector<GridResult>& grids,
                          const Hierarchy& h, bool quiet);

} // namespace hemirad::cli
