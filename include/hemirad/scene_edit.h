// Edits of a scene's light that leave its geometry alone (issue 21, incremental re-solving):
// a luminaire's multiplier, a surface group's reflectance or emission. A solver re-converges
// from its solution after such an edit (Solver::set_luminaire_multiplier() and friends, and
// `hemirad solve --resume` of an edited scene) instead of starting again.
//
// What counts as geometry and what as photometry (Scene::geometry_hash()): polygons, groups,
// textures and the luminaires' placement and candela distributions are geometry; materials'
// reflectance and emission and luminaires' multipliers are photometry.
#pragma once

#include <string>
#include <vector>

#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// Sets the multiplier of the luminaire named `name` (Luminaire::multiplier; 0 = off).
/// Returns its index. Throws InputError naming the luminaire and the value for an unknown name
/// or a multiplier that is negative or not finite.
HEMIRAD_API std::size_t set_luminaire_multiplier(Scene& scene, const std::string& name,
                                                 double multiplier);
/// Moves and aims the luminaire named `name`: its position [scene units] and its aim (the
/// photometric nadir; normalised, Luminaire::orient()). A change of the scene's geometry
/// (Scene::geometry_hash()): a solver follows it with Solver::place_luminaire(). Returns its
/// index. Throws InputError naming the luminaire for an unknown name, a position that is not
/// finite, or an aim that is zero or not finite.
HEMIRAD_API std::size_t set_luminaire_placement(Scene& scene, const std::string& name,
                                                const dvec3& position, const dvec3& aim);
/// Sets the reflectance of every polygon of surface group `group` (each channel in [0, 1)):
/// a material used only by the group is changed, one shared with other groups is copied for
/// the group (named "MATERIAL [GROUP]"). Throws InputError for an unknown group, a value out
/// of range, or a textured polygon in the group (its reflectance varies per patch).
HEMIRAD_API void set_group_reflectance(Scene& scene, const std::string& group, const dvec3& rho);
/// Sets the emitted radiance Ke [W sr^-1 unit^-2] (each channel >= 0, finite) of every polygon
/// of surface group `group`, as set_group_reflectance() does the reflectance.
HEMIRAD_API void set_group_emission(Scene& scene, const std::string& group, const dvec3& Ke);

/// The photometry of a scene, per polygon and per luminaire: what an edit changes and a
/// solver needs to know to turn the change into unshot power (Solver::apply_photometry()).
struct HEMIRAD_API Photometry {
    std::vector<dvec3> rho;        ///< per polygon, its material's reflectance
    std::vector<dvec3> exitance;   ///< per polygon, its emitted radiosity pi*Ke [W unit^-2]
    std::vector<dvec3> luminaires; ///< per luminaire, its power (multiplier applied) [W]
};
HEMIRAD_API Photometry photometry(const Scene& scene);

/// Parses a command-line edit "NAME=F" (--luminaire-multiplier) or "GROUP=R" / "GROUP=R,G,B"
/// (--reflectance; `channels` 3 allows both forms): the name and the values. Throws InputError
/// naming `flag` and the text when there is no '=', no name, or a value is not a number.
HEMIRAD_API std::pair<std::string, dvec3> parse_scene_edit(const std::string& flag,
                                                           const std::string& text, int channels);

} // namespace hemirad
