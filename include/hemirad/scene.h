// Scene model: planar convex polygons (triangles and quads) with diffuse materials.
// Conventions (docs/design.md, "Conventions for results"): lengths in scene units; Ke is emitted
// radiance per channel, emitted radiosity (exitance) is pi*Ke; Kd is reflectance rho in [0,1).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hemirad/glazing.h"
#include "hemirad/photometry.h"
#include "hemirad/sky.h"
#include "hemirad/sun.h"
#include "hemirad/texture.h"
#include "hemirad/visibility.h"

namespace hemirad {

using dvec3 = glm::dvec3;

struct HEMIRAD_API Material {
    std::string name;
    dvec3 rho{0.0}; ///< diffuse reflectance per RGB channel, each in [0, 1)
    dvec3 Ke{0.0};  ///< emitted radiance per channel [W sr^-1 unit^-2]; exitance = pi*Ke
    /// Index into Scene::textures, or -1: the reflectance at a point is then rho times the
    /// texel there (rho is the multiplier: OBJ Kd, glTF baseColorFactor); a leaf patch's is rho
    /// times the texels' mean over the leaf (patch_reflectance(), patch.h).
    int texture = -1;
    /// Both sides of its polygons are surfaces (glTF doubleSided): make_two_sided() gives each
    /// polygon a back-to-back twin.
    bool two_sided = false;
    dvec3 exitance() const; ///< emitted radiosity Be = pi*Ke [W unit^-2]
    bool emits() const { return Ke.x > 0 || Ke.y > 0 || Ke.z > 0; } ///< some channel of Ke > 0
};

/// Polygon::twin of a one-sided polygon.
inline constexpr std::uint32_t kNoTwin = 0xFFFFFFFFu;

/// A planar convex polygon: 3 or 4 corners, counter-clockwise seen from the front (normal side).
struct HEMIRAD_API Polygon {
    std::array<dvec3, 4> v{};   ///< corners; v[3] unused for triangles
    int count = 0;              ///< 3 or 4
    dvec3 normal{0.0};          ///< unit normal, front side
    double area = 0.0;          ///< [unit^2]
    std::uint32_t material = 0; ///< index into Scene::materials
    std::uint32_t group = 0;    ///< index into Scene::groups
    /// A two-sided surface is two polygons back to back (make_two_sided()): each receives and
    /// shoots on its own side; `twin` is the other one, kNoTwin for a one-sided polygon (whose
    /// back is black and occludes).
    std::uint32_t twin = kNoTwin;
    bool is_triangle() const { return count == 3; }
    dvec3 centroid() const;
};

/// A window pane (glazing.h; SCENE.json "glazing"): a polygon of a glazing group, taken out of
/// Scene::polygons, that transmits light crossing it.
struct GlazingPane {
    Polygon polygon; ///< its corners, normal, area and group
    PaneTransmittance transmittance;
};

/// Texture coordinates of a polygon's corners (texture.h: (0, 0) the image's top-left, t down),
/// in the order of Polygon::v; [3] unused for triangles.
using TexCoords = std::array<glm::vec2, 4>;

struct Camera {
    std::string name = "default";
    dvec3 eye{0.0, 0.0, 1.0};
    dvec3 target{0.0};
    dvec3 up{0.0, 1.0, 0.0};
    double fov_y_deg = 40.0; ///< vertical field of view [degrees]
};

struct Bounds {
    dvec3 lo{1e300}, hi{-1e300};
    void extend(const dvec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    double diagonal() const { return glm::length(hi - lo); }
};

struct HEMIRAD_API Scene {
    std::string source; ///< file path or "builtin:NAME"
    std::vector<Polygon> polygons;
    std::vector<Material> materials;
    std::vector<std::string> groups; ///< surface-group names (OBJ g/o, else material name)
    /// cameras[0] is the default view; without one, default_camera() (render.h) frames the scene
    std::vector<Camera> cameras;
    /// Point-source luminaires (photometry.h; from a SCENE.json file): shot by the solver like
    /// emitting polygons, their direct light gathered exactly at points.
    std::vector<Luminaire> luminaires;
    /// The sun (sun.h; SCENE.json "sun"), a parallel source: its direct light is delivered to
    /// every leaf patch before the first shot (solver/sun_light.h) and gathered exactly at
    /// points. Not in emitted_power(): what it delivers depends on the geometry.
    std::optional<Sun> sun;
    /// The sky (sky.h; SCENE.json "sky"), a distant luminous hemisphere with the ground below
    /// the horizon: what it sends to every leaf patch is delivered before the first shot
    /// (solver/sky_light.h) and gathered at points. Not in emitted_power().
    std::optional<Sky> sky;
    /// Window panes (glazing.h): not surfaces; every light path that crosses one is attenuated
    /// by its transmittance (ff/glazing_tracer.h). Empty without "glazing".
    std::vector<GlazingPane> glazing;
    std::vector<std::string> warnings; ///< things the loader fixed or dropped, for reports
    /// Reflectance textures (Material::texture); empty in an untextured scene.
    std::vector<Texture> textures;
    /// Per polygon (parallel to `polygons`), or empty when no polygon has texture coordinates.
    std::vector<TexCoords> texcoords;

    const Material& material_of(const Polygon& p) const { return materials[p.material]; }
    /// The texture of polygon `polygon`'s material, or null (untextured, or no coordinates).
    const Texture* texture_of(std::uint32_t polygon) const;
    /// Everything emitted [W]: surface_power() + luminaire_power().
    dvec3 emitted_power() const;
    dvec3 surface_power() const;   ///< of the polygons: sum of pi*Ke*area [W]
    dvec3 luminaire_power() const; ///< of the luminaires: sum of lumens/683, equal RGB [W]
    double total_area() const;
    /// Max over materials in use and channels; a textured material's rho times its texture's
    /// largest texel.
    double max_reflectance() const;
    /// Of the polygons (luminaires left out: the automatic patch size derives from it).
    Bounds bounds() const;
    std::size_t triangle_count() const;
    std::size_t quad_count() const;
    /// Index of the group named `name`, or -1.
    int find_group(const std::string& name) const;
    /// FNV-1a hash of the geometry and materials, for checking saved solutions.
    std::uint64_t content_hash() const;
    /// FNV-1a hash of the geometry alone (scene_edit.h): polygons, groups, textures and the
    /// luminaires' placement and distributions, not the materials' reflectance and emission
    /// nor the luminaires' multipliers. A solution resumes incrementally across a photometry
    /// edit, not across a change of geometry.
    std::uint64_t geometry_hash() const;
};

/// Adds a polygon after validating it: non-finite corners throw InputError; a degenerate
/// polygon (zero area, repeated corners) returns false and is not added; a non-planar or
/// concave quad is split into two triangles (returns true, and `split` is set).
/// With `uv` (one per corner), the texture coordinates follow the corners into the polygons
/// made (Scene::texcoords is then kept parallel to the polygons, zeros for those without).
struct AddResult {
    int added = 0;      ///< polygons added (0, 1 or 2)
    bool split = false; ///< a quad was split into triangles
    bool degenerate = false;
};
HEMIRAD_API AddResult add_polygon(Scene& scene, const std::vector<dvec3>& corners,
                                  std::uint32_t material, std::uint32_t group,
                                  double planarity_tolerance = 1e-6,
                                  const std::vector<glm::dvec2>* uv = nullptr);

/// Drops every polygon whose corners (in any order) are those of an earlier polygon facing the
/// same side: the hemicube shows one of the two and the other is linked all the same, so the
/// surface would take its light twice (a glTF with an object exported twice; the OBJ loader
/// drops such faces as it reads them, naming their lines). Of two, one that emits stays (a
/// lamp's face laid on a ceiling's), else the first. Back to back, both stay. Keeps
/// Scene::texcoords parallel; for a scene without twins. Returns how many were dropped and
/// sets `first_group`, if given, to the group of the first of them.
HEMIRAD_API std::size_t drop_coincident_polygons(Scene& scene,
                                                 std::uint32_t* first_group = nullptr);

/// Makes the polygons for which pick(index) is true two-sided: appends to each a twin with
/// the same corners in reverse order (the opposite normal), the same material and group, and
/// the texture coordinates that go with its corners, and links the two (Polygon::twin).
/// Polygons that have a twin already are left alone. A picked polygon whose back face is in
/// the scene already (another polygon without a twin, with the same corners and the opposite
/// normal: a board modelled by both its faces) is linked to that one instead, since a twin
/// would lie on it and take its light a second time; `paired`, if given, is set to how many
/// were. Returns how many twins were added.
HEMIRAD_API std::size_t make_two_sided(Scene& scene, const std::function<bool(std::uint32_t)>& pick,
                                       std::size_t* paired = nullptr);

/// Cuts every polygon that another polygon passes through (a wall face that reaches below the
/// floor, a jar sunk into a shelf, a floor running on into a wall slab), along the line where
/// they meet, so that the part on each side is a polygon of its own (split_intersections.cpp:
/// otherwise leaf patches straddle the two sides and carry light into closed cavities).
/// A polygon that another only touches from its front with an edge (a box standing on a floor,
/// a wall under a ceiling that runs on over the next room) is cut along that edge's line too:
/// the part under the box is then a polygon no shooter sees, where as one polygon its leaves
/// straddle the contact line and the visibility test at their centres lets light under it.
/// Touching from behind, or only at a corner, cuts nothing. A meeting line
/// shorter than a tenth of the polygon's longest edge is not cut; at most 16 lines a polygon
/// (the longest); pieces keep the polygon's material, group and texture coordinates. For a
/// scene without twins (before make_two_sided). Deterministic.
struct SplitStats {
    std::size_t polygons_cut = 0; ///< polygons replaced by pieces
    std::size_t pieces = 0;       ///< polygons made of them
};
HEMIRAD_API SplitStats split_intersections(Scene& scene);

/// For faces of a textured material that carry no texture coordinates: the index of a copy of
/// `material` with its reflectance times the texture's mean and no texture (named "NAME
/// (texture mean)"), appended to scene.materials the first time; `cache` remembers the copies
/// made (textured material -> its copy).
HEMIRAD_API std::uint32_t untextured_material(Scene& scene, std::uint32_t material,
                                              std::map<std::uint32_t, std::uint32_t>& cache);

/// The warning finish_scene() adds when nothing emits (its start, for filtering).
inline constexpr const char* kNoEmitterWarning = "no surface emits light";

/// Checks a finished scene: at least one polygon (else InputError naming `origin`); adds a
/// warning when nothing emits. Called by every loader. Adds no camera.
HEMIRAD_API void finish_scene(Scene& scene, const std::string& origin);

} // namespace hemirad
