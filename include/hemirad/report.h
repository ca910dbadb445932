// Reports on a solution: the JSON summary, probe points, text outputs written atomically.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hemirad/gather.h"
#include "hemirad/grid.h"
#include "hemirad/json.h"
#include "hemirad/solver.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// The JSON report of `hemirad solve --report` (keys: polygons, leaf_patches, shots, seconds,
/// emitted_power, unshot_fraction, error_bound, converged, row_sum{min,mean,max}, groups[...]
/// with name, area, E_avg, E_min, E_max — incident irradiance, RGB — and flux (E times area,
/// RGB, W) and lumens (683 x its luminance: the lumens reaching the group); with luminaires,
/// installed_lumens and the luminaire schedule, luminaires[...] (luminaire_json)).
HEMIRAD_API Json solve_report(Solver& solver);
/// The same with calculation grids (grid.h): adds `grids: [grid_json(...)]`, and with `lux`
/// photometric values (lux, for scenes in metres; weighting in grid.h).
/// With a daylight reference E_h > 0 [lux] (`--daylight-factor`) each grid has its daylight
/// factors (grid_json) and the report "daylight_factor": {"E_h": E_h}.
HEMIRAD_API Json solve_report(Solver& solver, const std::vector<GridResult>& grids, bool lux,
                              double daylight_lux = 0);

/// A luminaire's schedule entry: name, kind (ies, candela, spot), file (ies), position, aim,
/// rotation [deg], multiplier, lumens (integrated from the distribution, multiplier applied),
/// rated_lumens (the IES file's lamp lumens times multiplier; absent for absolute photometry and
/// other kinds), max_candela, symmetry.
HEMIRAD_API Json luminaire_json(const Luminaire& l);
/// {installed_lumens, luminaires: [luminaire_json...]} of a scene (both present, possibly 0/[]).
HEMIRAD_API Json luminaire_schedule(const Scene& scene);

struct Probe {
    dvec3 position{0.0}, normal{0.0};
};
/// About `count` points spread over every polygon of the scene, for accuracy studies: each
/// polygon gets a share proportional to its area (at least `min_per_polygon`), placed by
/// jittered stratification of its parameter square (a triangle folds the square's upper half),
/// kept 1e-3 of the parameter range away from the edges; the normal is the polygon's.
/// Deterministic for a given scene, count and seed.
HEMIRAD_API std::vector<Probe> surface_points(const Scene& scene, std::size_t count,
                                              std::uint64_t seed = 1, int min_per_polygon = 2);
/// `count` points drawn at random, uniformly by area over all the scene's surfaces (a
/// polygon is drawn with probability area / total area, the point uniformly on it), for
/// accuracy studies that should weigh every square metre alike (hemirad-bench
/// real_building). The normal is the polygon's. Deterministic for a given scene, count and
/// seed.
HEMIRAD_API std::vector<Probe> random_surface_points(const Scene& scene, std::size_t count,
                                                     std::uint64_t seed = 1);
/// CSV rows x,y,z,nx,ny,nz with a header (the input of --probes).
HEMIRAD_API std::string probe_points_csv(const std::vector<Probe>& probes);

/// Reads CSV rows x,y,z,nx,ny,nz (a header line is optional; '#' comments allowed). Throws
/// InputError naming the file and line of a malformed row.
HEMIRAD_API std::vector<Probe> read_probes(const std::string& path);
/// Irradiance at one probe: E [W unit^-2], RGB, and the polygon the point lies on.
struct ProbeValue {
    std::optional<dvec3> E;               ///< empty: on no surface, and no gather
    std::optional<std::uint32_t> polygon; ///< empty: on no surface (find_surface)
};
/// The values of probes_csv(): without a gather E is interpolated between the leaves around
/// the point (nothing for a point on no surface); with a final gather (gather.h), point k is
/// gathered at the point itself with random stream k (deterministic for given options).
HEMIRAD_API std::vector<ProbeValue> evaluate_probes(const std::vector<Probe>& probes,
                                                    const Hierarchy& h,
                                                    const FinalGather* gather = nullptr);
/// CSV x,y,z,nx,ny,nz,E_r,E_g,E_b,polygon,group. Without a gather E is interpolated between
/// the leaves around the point and a point on no surface gets empty E columns; with a final
/// gather (gather.h) E is evaluated at the point itself, also in free space (polygon empty).
/// Either way a point on no surface has "none" as its group. With a daylight reference
/// E_h > 0 [lux] (`--daylight-factor`) a last column DF = 100 * 683 * Y / E_h [%], Y the
/// luminance-weighted E (grid.h).
HEMIRAD_API std::string probes_csv(const std::vector<Probe>& probes, const Hierarchy& h,
                                   const FinalGather* gather = nullptr, double daylight_lux = 0);

/// Writes a whole file atomically (temporary file, then rename): never a partial file.
HEMIRAD_API void write_text_file(const std::string& path, const std::string& contents);

} // namespace hemirad
