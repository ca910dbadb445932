// Scenes for validation (CIE 171:2006 test cases that apply to a diffuse radiosity engine)
// and for benchmarks (paper 002 §5's rooms), built in code so that tests and the benchmark
// need no files. The geometry is exposed as constants so that a test computes its reference
// from the same numbers the scene was built from.
//
// Frame of the CIE rooms: y is up; the room is [0, W] x [0, H] x [0, D] (x, y, z) in metres;
// every surface faces into the room.
#pragma once

#include <string>
#include <vector>

#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad::validation {

/// An axis-aligned rectangle in a plane of constant y: [x0, x1] x [z0, z1] at height y.
struct HorizontalRect {
    double x0, x1, z0, z1, y;
};

/// The CIE 171 test room (reconstructed: 4 m x 4 m floor, 3 m high).
struct CieRoom {
    static constexpr double width = 4.0;  ///< along x [m]
    static constexpr double depth = 4.0;  ///< along z [m]
    static constexpr double height = 3.0; ///< along y [m]
};

/// CIE 171 test 5.3: a 1 m x 1 m Lambertian area source centred in the ceiling, flush with
/// it (the ceiling is built as a frame of four rectangles around it, so nothing overlaps).
/// Every surface is black (rho = 0): only direct light. The source emits `exitance`
/// [W m^-2, or lm m^-2 for illuminance in lux]. Groups: floor, ceiling, wall_x0, wall_x1,
/// wall_z0, wall_z1, source.
constexpr HorizontalRect kCie53Source{1.5, 2.5, 1.5, 2.5, CieRoom::height};
HEMIRAD_API Scene make_cie53_area_source(double exitance = 1000.0);

/// The CIE 171 room lit by point-source luminaires (photometry.h) only: every surface of
/// reflectance `rho` (0: black, for direct light only), the ceiling whole; the luminaires are
/// oriented (Luminaire::orient). Groups: floor, wall_x0, wall_x1, wall_z0, wall_z1, ceiling.
HEMIRAD_API Scene make_cie_room(double rho, const std::vector<Luminaire>& luminaires);

/// CIE 171 tests 5.6 and 5.7: light reflected from a uniformly lit diffuse floor. The
/// floor's reflected exitance rho*E_floor is modelled as emission (a Lambertian emitter of
/// exitance `floor_exitance`), every other surface black, so a point on a wall or the
/// ceiling receives floor_exitance * F(point -> visible floor).
/// With `obstruction` (test 5.7): a black horizontal square plate (zero thickness, facing
/// up; its back occludes as well) at kCie57Plate, between the floor and the measurement
/// points. Groups as in 5.3 without the source, plus "plate".
constexpr double kCie56FloorReflectance = 0.30;
constexpr double kCie56FloorIlluminance = 500.0; ///< E_floor [lx]; exitance = rho*E = 150
constexpr HorizontalRect kCie57Plate{1.5, 2.5, 1.5, 2.5, 1.0};
HEMIRAD_API Scene make_cie56_lit_floor(double floor_exitance, bool obstruction);

/// CIE 171 test 5.8: inter-reflection in a closed cube of side `side` [m], every surface of
/// reflectance `rho` (the source too), with a 1 m x 1 m source of `exitance` centred in the
/// ceiling (flush: the ceiling is a frame around it). Groups: floor, ceiling, walls, source.
HEMIRAD_API Scene make_cie58_cube(double rho, double side = 4.0, double exitance = 1000.0);

/// A closed room of side `side` (every surface reflectance `rho`) lit by a small square light
/// (side/5 wide, exitance `exitance`, facing down) hanging side/1000 under the centre of the
/// ceiling: the light's footprint on the ceiling is a sharp shadow edge right next to it, the
/// hardest case for a leaf-based read-out. Groups: floor, wall_x0, wall_x1, wall_z0, wall_z1,
/// ceiling, light. The built-in scene "room" (1 m, rho 0.5).
HEMIRAD_API Scene make_light_room(double rho = 0.5, double side = 1.0, double exitance = 1.0);

/// Closed cavities in a lit room, for leak tests: light must not reach where no light can go.
/// The room is make_light_room's (side kCavityRoomSide, every surface reflectance `rho`, the
/// small light under the middle of the ceiling, exitance 1), the floor one polygon from wall to
/// wall, and in it:
///   - "slab": a thick wall slab, a closed box (faces outwards) standing on the floor, which
///     runs on underneath it (the floor under the slab is a closed cavity);
///   - "sunk": a closed box sunk half into the floor (its faces below the floor and the floor
///     inside it are in the dark);
///   - "hollow": a closed box (faces outwards) floating above the floor, with "inner", a
///     smaller box inside it whose faces point inwards (a closed, unlit room in a closed box).
/// With `split` the polygons that others pass through are cut where they meet
/// (split_intersections, as the loaders do by default). Groups: floor, wall_x0, wall_x1,
/// wall_z0, wall_z1, ceiling, light, slab, sunk, hollow, inner. Metres, y up.
struct CavityRoom {
    static constexpr double side = 2.0; ///< the room is [0, side]^3
    static constexpr dvec3 slab_lo{0.3, 0.0, 0.4}, slab_hi{0.5, 1.2, 1.6};
    static constexpr dvec3 sunk_lo{1.3, -0.25, 0.3}, sunk_hi{1.7, 0.25, 0.7};
    static constexpr dvec3 hollow_lo{1.2, 0.3, 1.2}, hollow_hi{1.7, 0.8, 1.7};
    static constexpr dvec3 inner_lo{1.3, 0.4, 1.3}, inner_hi{1.6, 0.7, 1.6};
};
HEMIRAD_API Scene make_cavity_room(double rho = 0.5, bool split = true);

/// A furnished room in the manner of paper 002 §5 (Figure 3): walls, floor, ceiling,
/// rectangular lights under the ceiling, and "sets" of one table (top + 4 legs) with four
/// chairs (seat, back, 4 legs), each part a box of 6 quads, plus `cabinets` extra boxes
/// along the walls. Polygons = 6 + lights + 174*sets + 6*cabinets; deterministic.
///   room402:  sets = 2,  lights = 6, cabinets = 7   -> 402 polygons
///   scene3138: sets = 17, lights = 6, cabinets = 28 -> 3138 polygons
struct BenchRoomOptions {
    int sets = 2;     ///< table-and-chairs sets (>= 0)
    int lights = 6;   ///< ceiling lights (>= 1)
    int cabinets = 7; ///< extra boxes along the walls (>= 0)
    double rho = 0.6; ///< reflectance of walls, ceiling and furniture (floor 0.3)
};
HEMIRAD_API Scene make_bench_room(const BenchRoomOptions& options = {});
/// Polygon count that make_bench_room(options) produces.
HEMIRAD_API int bench_room_polygons(const BenchRoomOptions& options);

/// A furnished open-plan floor of about `triangles` triangles (>= 1000), for the scale
/// benchmarks (hemirad-bench scale_triangles_1e5, _1e6): make_bench_room with as many
/// table-and-chair sets as it takes (a 4 m grid; one ceiling light per 4 sets, at least 6; one
/// cabinet per 8 sets, at least 7), every quad split into two triangles, as an exporter that
/// writes only triangles would. Deterministic; groups and materials as make_bench_room.
HEMIRAD_API Scene make_furnished_floor(long triangles);

/// A real-building stand-in in the manner of the Sponza atrium (Dabrovic 2001), for the
/// hemirad-bench experiment real_building and the built-in scene "courtyard": a courtyard
/// open to the sky (24 m x 10 m, walls 10 m high), with a two-storey gallery along each long
/// side behind an arcade of round columns and semicircular arches, a balustrade of small
/// balusters on the upper storey. Everything is triangles, as exporters write them: floors and
/// walls tessellated into cells of about `cell` metres, columns into `segments` facets around
/// and rings along, arches into `segments` steps. The columns stand sunk 0.3 m into the floor
/// and their capitals touch the arcade walls (contact and interpenetration, as in real
/// models). Every surface has reflectance `rho`; three isotropic point sources (courtyard
/// 3000 cd at 7 m, one 1000 cd in each ground-floor gallery). Metres, y up.
/// Groups: courtyard_floor, gallery_floors, gallery_ceilings, walls, arcades, columns,
/// balustrades, slab_edges.
struct CourtyardOptions {
    double rho = 0.5;  ///< reflectance of every surface, [0, 1)
    double cell = 0.3; ///< tessellation of floors and walls [m], > 0
    int segments = 32; ///< facets around a column and steps along an arch, >= 6
};
Scene make_courtyard(const CourtyardOptions& options = {});

} // namespace hemirad::validation
