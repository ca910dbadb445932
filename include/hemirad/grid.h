// Calculation grids (lighting engineering): incident irradiance E on a regular NX x NY grid of
// points over a planar surface group, with minimum, average, maximum and uniformity U0.
//
// The grid lies in the group's plane (all its polygons must be coplanar and face the same way)
// and covers the group's bounding rectangle in that plane: axis u along the first edge of the
// group's first polygon, axis v = normal x u; the points are the centres of the NX x NY cells
// of that rectangle, point (i, j) at origin + (i + 0.5)/NX * width * u + (j + 0.5)/NY * height * v.
// A point that falls on none of the group's polygons (an L-shaped room, a gap) is skipped: it
// is listed in the CSV without values and left out of the statistics.
//
// Photometric values (--lux): E_v = 683 lm/W * (0.2126 E_r + 0.7152 E_g + 0.0722 E_b), i.e. the
// RGB channels are taken as radiometric irradiance [W m^-2] and weighted by their Rec. 709
// luminance coefficients times the maximum luminous efficacy 683 lm/W. Lux needs a scene in
// metres (irradiance per scene unit^2 is then W m^-2).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hemirad/gather.h"
#include "hemirad/hierarchy.h"
#include "hemirad/image.h"
#include "hemirad/json.h"
#include "hemirad/photometry.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// Most points in one grid (NX * NY).
inline constexpr long kMaxGridPoints = 4'000'000;

struct GridSpec {
    std::string group;  ///< surface-group name
    int nx = 0, ny = 0; ///< points along u and v, each 1..10000
};

/// Parses "GROUP:NXxNY" (also "GROUP:NX×NY"; the group name may contain ':', the last one
/// separates; NX, NY in 1..10000, NX*NY <= kMaxGridPoints). Throws InputError quoting the text.
HEMIRAD_API GridSpec parse_grid_spec(const std::string& text);

struct GridPoint {
    int i = 0, j = 0;          ///< cell along u, v
    dvec3 position{0.0};       ///< in the group's plane
    bool on_surface = false;   ///< false: on no polygon of the group, skipped
    std::uint32_t polygon = 0; ///< the polygon it lies on (if on_surface)
    dvec3 E{0.0};              ///< incident irradiance, RGB [W unit^-2]
};

struct GridResult {
    GridSpec spec;
    dvec3 origin{0.0}, axis_u{0.0}, axis_v{0.0}, normal{0.0}; ///< unit axes
    double width = 0, height = 0;                             ///< of the bounding rectangle [unit]
    std::vector<GridPoint> points;                            ///< nx*ny, row-major: index j*nx + i
    long evaluated = 0, skipped = 0;
    /// Statistics over the evaluated points. Luminance Y = 0.2126 R + 0.7152 G + 0.0722 B.
    double Y_min = 0, Y_avg = 0, Y_max = 0;
    double U0 = 0;                            ///< Y_min / Y_avg (0 when Y_avg is 0)
    double min_over_max = 0;                  ///< Y_min / Y_max, "Emin/Emax" (0 when Y_max is 0)
    dvec3 E_min{0.0}, E_avg{0.0}, E_max{0.0}; ///< per channel
};

/// The polygons of the grid's surface group, after checking that the group exists (else
/// InputError listing the groups) and is planar (else InputError). Call it before solving so
/// that a bad --grid is refused before any output is written.
HEMIRAD_API std::vector<std::uint32_t> grid_polygons(const Scene& scene, const GridSpec& spec);

/// Evaluates the grid on a push-pulled hierarchy (Solver::solution()): by final gather at each
/// point when `gather` is given (gather.h), else interpolated between the leaves. Throws
/// InputError for an unknown group (listing the groups) or a group whose polygons are not
/// coplanar.
HEMIRAD_API GridResult evaluate_grid(const Hierarchy& h, const GridSpec& spec,
                                     const FinalGather* gather = nullptr);

/// The report entry: {group, nx, ny, points, skipped, E_min, E_avg, E_max (luminance,
/// W unit^-2), U0 = Emin/Eavg, "Emin/Emax", E_rgb {min, avg, max}, and with lux:
/// lux {min, avg, max}}.
/// With a daylight reference E_h > 0 [lux] (`--daylight-factor`, the sky's horizontal
/// illuminance) also "DF": {avg, min, median, max, "share_ge_1", "share_ge_2", "share_ge_3"}:
/// daylight factors DF = 100 * 683 * Y / E_h [%] over the evaluated points, and the fractions of
/// those points (0..1) with DF >= 1, 2, 3 %.
HEMIRAD_API Json grid_json(const GridResult& g, bool lux, double daylight_lux = 0);

/// The daylight factors 100 * 683 * Y / E_h [%] of a grid's evaluated points, in point order.
HEMIRAD_API std::vector<double> daylight_factors(const GridResult& g, double daylight_lux);

/// One line for people: "floor 9x9: Emin 96.2 lx, Eavg 161.9 lx, Emax 243 lx, U0 = Emin/Eavg
/// 0.594, Emin/Emax 0.396" (in W/unit² without lux).
/// With a daylight reference E_h > 0 [lux]: ", DF avg 2.31 %, min 0.52 %, median 1.9 %".
HEMIRAD_API std::string grid_summary(const GridResult& g, bool lux, double daylight_lux = 0);

/// A false-colour plan view of a grid (`hemirad solve --grid-png DIR`): one cell per point, to
/// scale, seen from the front of the surface (u to the right, v up), coloured by its value
/// (viridis, 0 to the grid's maximum) with the value printed in it when the cell is large
/// enough; points on no polygon grey; the positions of the luminaires in front of the plane
/// within the grid marked with a cross and their name; a title with Emin, Eavg, Emax, U0 and
/// Emin/Emax and a colour legend. Values in lux with `lux`, else W/unit².
/// With a daylight reference E_h > 0 [lux] the title also has the DF summary (grid_summary)
/// and the cells and the legend show the daylight factor DF = 100 E / E_h %.
HEMIRAD_API Image8 grid_plan_image(const GridResult& g, bool lux,
                                   const std::vector<Luminaire>& luminaires,
                                   double daylight_lux = 0);

/// CSV of all grids: group,i,j,x,y,z,E_r,E_g,E_b,E_Y[,lux][,DF]; a skipped point has empty
/// values. DF [%] with a daylight reference E_h > 0 [lux] (grid_json).
HEMIRAD_API std::string grids_csv(const std::vector<GridResult>& grids, bool lux,
                                  double daylight_lux = 0);

} // namespace hemirad
