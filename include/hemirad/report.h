// Reports on a solution: the JSON summary, probe points, text outputs written atomically.
#pragma once

#include <string>
#include <vector>

#include "hemirad/grid.h"
#include "hemirad/json.h"
#include "hemirad/solver.h"

namespace hemirad {

/// The JSON report of `hemirad solve --report` (keys: polygons, leaf_patches, shots, seconds,
/// emitted_power, unshot_fraction, error_bound, converged, row_sum{min,mean,max}, groups[...]
/// with name, area, E_avg, E_min, E_max — incident irradiance, RGB).
Json solve_report(Solver& solver);
/// The same with calculation grids (grid.h): adds `grids: [grid_json(...)]`, and with `lux`
/// photometric values (lux, for scenes in metres; weighting in grid.h).
Json solve_report(Solver& solver, const std::vector<GridResult>& grids, bool lux);

struct Probe {
    dvec3 position{0.0}, normal{0.0};
};
/// Reads CSV rows x,y,z,nx,ny,nz (a header line is optional; '#' comments allowed). Throws
/// InputError naming the file and line of a malformed row.
std::vector<Probe> read_probes(const std::string& path);
/// CSV x,y,z,nx,ny,nz,E_r,E_g,E_b,polygon,group; a point on no surface gets empty E columns
/// and "none" as its group.
std::string probes_csv(const std::vector<Probe>& probes, const Hierarchy& h);

/// Writes a whole file atomically (temporary file, then rename): never a partial file.
void write_text_file(const std::string& path, const std::string& contents);

} // namespace hemirad
