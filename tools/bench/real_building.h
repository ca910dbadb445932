// hemirad-bench experiment real_building (real_building.cpp).
#pragma once

#include <string>

namespace hemirad::bench {

/// Buildings as users bring them, solved with the default options: the built-in courtyard (a
/// two-storey colonnade of 65,776 triangles lit by three point sources) and, when the file is
/// there, the office exported from Blender (`office_glb`, doubleSided materials; skipped
/// when empty or missing), lit by its emissive bars and again, through a SCENE.json, by three
/// point sources (`office-pt`). For each: shots, seconds, guarded rows, the worst row sum, and
/// the irradiance at random surface points (random_surface_points) read as `hemirad solve
/// --probes` reads them, against `hemirad reference`. Prints its "JSON ..." and "ROW ..."
/// lines.
void run_real_building(const std::string& office_glb);

} // namespace hemirad::bench
