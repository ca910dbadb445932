// hemirad's public API, in one header. Link with hemirad::core (CMake: find_package(hemirad))
// or `pkg-config --cflags --libs hemirad`.
//
//     #include <hemirad/hemirad.h>
//
//     hemirad::Scene scene = hemirad::load_scene("cornell");   // built-in, OBJ or SCENE.json
//     hemirad::SolverOptions options;                           // solver.h: every default
//     options.tolerance = 1e-3;
//     hemirad::Solver solver(scene, options);                   // starts its own GL context
//     while (solver.step()) {}                                  // one shot per step
//     const hemirad::Hierarchy& h = solver.solution();          // push-pulled solution
//     hemirad::GroupIrradiance g = hemirad::group_irradiance(h, 0);
//
// What is where:
//   scene.h, scene_io.h     the scene (polygons, groups, luminaires, cameras); loading OBJ,
//                           SCENE.json, glTF 2.0 and the built-in scenes; writing OBJ
//   texture.h               textures (PNG, JPEG: map_Kd, glTF baseColorTexture) as reflectance
//   photometry.h            luminaires: IES files, point sources, spots
//   solver.h                SolverOptions, Solver (the loop), ShotRecord (the shot log)
//   solver_options.h        the options table: every option's name, default, range, help
//   collective.h            what a solve across MPI ranks needs (rank, size, all-gather)
//   provider.h              form-factor methods (hybrid, analytic, hemicube; reference, pdm, sr)
//   hierarchy.h, patch.h    the patch quadtrees that hold the solution
//   readout.h, gather.h     irradiance at points (interpolated, or by final gather), per group
//   report.h                probes, the JSON report, probe CSVs
//   grid.h                  calculation grids (average, minimum, uniformity; lux)
//   render.h, image.h       images of the solution (GL), EXR/PNG, tone mapping
//   draw.h                  text, shapes, false colour, contact sheets and plots on images
//   export.h                PLY meshes and lightmap atlases
//   solution_file.h         saving and resuming a solve
//   reference.h             the Monte-Carlo reference (path tracer) at points
//   gl/context.h            the headless GL context (EGL or OSMesa), for callers who want
//                           their own (then set options.provider.gpu.use_current_context)
//   error.h                 InputError (bad input, names file/line/value), RuntimeError
//   version.h               HEMIRAD_VERSION
#pragma once

#include "hemirad/collective.h"
#include "hemirad/draw.h"
#include "hemirad/error.h"
#include "hemirad/export.h"
#include "hemirad/form_factors.h"
#include "hemirad/gather.h"
#include "hemirad/gl/context.h"
#include "hemirad/glazing.h"
#include "hemirad/grid.h"
#include "hemirad/hierarchy.h"
#include "hemirad/image.h"
#include "hemirad/json.h"
#include "hemirad/memory_guard.h"
#include "hemirad/patch.h"
#include "hemirad/photometry.h"
#include "hemirad/provider.h"
#include "hemirad/readout.h"
#include "hemirad/reference.h"
#include "hemirad/render.h"
#include "hemirad/report.h"
#include "hemirad/scene.h"
#include "hemirad/scene_io.h"
#include "hemirad/sky.h"
#include "hemirad/solution_file.h"
#include "hemirad/solver.h"
#include "hemirad/solver_options.h"
#include "hemirad/sun.h"
#include "hemirad/texture.h"
#include "hemirad/validation_scenes.h"
#include "hemirad/version.h"
