// Loading scenes: OBJ/MTL files and the built-in scenes.
#pragma once

#include <functional>
#include <string>

#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

/// Options of the built-in scenes (ignored where they do not apply).
struct BuiltinOptions {
    int subdiv = 1;        ///< cube/furnace: each face split into subdiv x subdiv quads (1..1000)
    double rho = -1.0;     ///< reflectance of every surface; <0 = the scene's own default
    int sphere_rings = 16; ///< sphere: latitude rings (>= 4); longitude segments = 2x rings
};

/// Options of OBJ/MTL files.
struct ObjOptions {
    /// Reflectance used for a Kd channel of 1 or more (a surface can't reflect all the light it
    /// receives; exporters write Kd 1 for white), in (0, 1). Kd values under 1 are kept as given.
    double max_reflectance = 0.98;
    /// Every polygon of the scene's files is two-sided (`--two-sided-surfaces`: make_two_sided;
    /// glTF materials marked doubleSided are two-sided whatever this says).
    bool two_sided_surfaces = false;
    /// Cut polygons where others pass through them (split_intersections,
    /// `--split-intersections on|off`).
    bool split_intersections = true;
    /// The loaders finish the surfaces (finish_surfaces()) before they return; the SCENE.json
    /// reader turns this off for the files it includes and finishes them once, merged.
    bool finish_surfaces = true;
};

/// The last step of loading a file: cuts the polygons where others pass through them
/// (options.split_intersections; a warning says how many), then makes the two-sided surfaces
/// two-sided (make_two_sided): every polygon with options.two_sided_surfaces, else those of
/// materials marked two_sided (glTF doubleSided) and those for which `also(index)` is true.
HEMIRAD_API void finish_surfaces(Scene& scene, const ObjOptions& options,
                                 const std::function<bool(std::uint32_t)>& also = {});

/// Loads "NAME" (a built-in scene), a path to an OBJ file, a glTF 2.0 file (a path ending in
/// .gltf or .glb: load_gltf) or a SCENE.json project file (a path ending in .json:
/// load_scene_json). The one place that dispatches by extension. Throws InputError on bad input.
HEMIRAD_API Scene load_scene(const std::string& name_or_path, const BuiltinOptions& builtin = {},
                             const ObjOptions& obj = {});

/// A SCENE.json project file assembles a scene (paths relative to the JSON file's folder):
///
///   {"include": ["room.obj"],                 geometry: OBJ or glTF files, at least one
///    "luminaires": [                                    point sources (photometry.h)
///      {"ies": "downlight.ies", "position": [2, 2.8, 2], "aim": [0, -1, 0],
///       "rotation": 0, "multiplier": 1, "name": "D1"},
///      {"ldt": "wallwasher.ldt", "position": [0, 2, 3]},  EULUMDAT (either key takes either
///                                                          format: told apart by content)
///      {"candela": 500, "position": [1, 2, 1]},         isotropic, I [cd]
///      {"spot": {"candela": 2000, "cone": 20, "falloff": 10}, "position": [...], "aim": [...]}],
///    "cameras": [{"name": "door", "eye": [0, 1.6, 0], "target": [2, 1, 2], "up": [0, 1, 0],
///                 "fov": 60}],
///    "two_sided": ["Glass", "Curtain"]}       surface groups whose polygons are two-sided
///
/// A luminaire is exactly one of `ies`, `ldt`, `candela`, `spot`; `position` is required; `aim`
/// (the nadir, gamma = 0; default straight down, [0, -1, 0]), `rotation` (of the C planes about the
/// aim, degrees, counterclockwise seen from above; default 0), `multiplier` (> 0, default 1)
/// and `name` (default L1, L2, ...) are optional. A spot has `candela` within `cone` degrees
/// of the aim, falling linearly to 0 over `falloff` more degrees (default 0). A camera needs
/// `eye` and `target`; `up` defaults to [0, 1, 0], `fov` (vertical, degrees) to 40; the first
/// camera is the default view. Groups of the same name in several files are one group; the
/// included glTF files' lights come first among the luminaires.
/// Unknown keys are errors naming the key; every error names the file and the line. Lengths
/// are in the OBJ's units, which must be metres for lux.
HEMIRAD_API Scene load_scene_json(const std::string& path, const ObjOptions& obj = {});
/// Whether a scene argument names a SCENE.json file (ends in .json, any case).
HEMIRAD_API bool is_scene_json(const std::string& path);

/// Loads a glTF 2.0 file, `.gltf` (JSON, with its .bin buffers and images beside it or as data
/// URIs) or `.glb` (binary), with Debian's TinyGLTF (gltf_loader.cpp):
///  - the node tree of the default scene (else scene 0; a file without scenes: every root
///    node), each node's `matrix` or `translation` x `rotation` x `scale` composed from the root
///    down; a transform that mirrors flips the winding back (glTF 3.7.4);
///  - mesh primitives of mode 4 (triangles; other modes are warned and skipped), POSITION and,
///    for a textured material, TEXCOORD_0, indices of any component type (or none);
///  - materials: `baseColorFactor` (linear RGB) is the reflectance rho (a channel of 1 or more
///    becomes ObjOptions::max_reflectance: quietly under a texture, else with a warning),
///    `baseColorTexture` multiplies it (texture.h; through TEXCOORD_0); `emissiveFactor` times
///    `KHR_materials_emissive_strength.emissiveStrength` is the emitted radiance Ke, as OBJ's Ke
///    (exitance pi Ke). Metallic, roughness, normal and occlusion maps, emissiveTexture and
///    alpha are not used (the last two warned); a primitive without a material gets 'default';
///  - perspective cameras (a node's -z is the view direction, +y up, yfov vertical): the first
///    in the order the node tree is walked is the default view;
///  - surface groups: a mesh node's name, else its material's name, else "node N";
///  - KHR_lights_punctual point and spot lights: luminaires (photometry.h) at the node's world
///    position, `intensity` in candela times the luminance of `color` (warned when not white),
///    a spot down the node's -z with gltf_spot_distribution(inner, outer); `range` ignored;
///    directional lights warned and skipped. Named by the light, else the node, else light<k>.
/// Units: glTF lengths are metres, and hemirad takes them as its scene unit: irradiance is per
/// m², `--lux` applies. Errors name the file and the element ("accessor 3", "node 5"):
/// accessors or views outside their buffers, indices outside the vertices, non-finite numbers,
/// a node that is its own ancestor; TinyGLTF's own messages are passed on. A texture that
/// cannot be read is a warning (the material keeps baseColorFactor alone).
HEMIRAD_API Scene load_gltf(const std::string& path, const ObjOptions& options = {});
/// Whether a scene argument names a glTF file (ends in .gltf or .glb, any case).
HEMIRAD_API bool is_gltf(const std::string& path);

/// Loads an OBJ file and the MTL files it names (obj_loader.cpp lists what is tolerated, with a
/// warning each, and what is an error). Throws InputError naming file, line and value.
HEMIRAD_API Scene load_obj(const std::string& path, const ObjOptions& options = {});

/// A scene as the text of an OBJ file and its MTL (named `mtl_name` in `mtllib`): each distinct
/// polygon corner once as `v` (shortest decimal that reads back to the same double), faces in
/// polygon order with `g` and `usemtl` where they change, every material with its Kd (and Ke
/// if not 0); cameras as comments. load_obj() of the files gives the same scene: the same
/// content_hash() once groups are numbered alike (a file numbers them in order of first use),
/// as long as group and material names are unique and free of line breaks.
struct ObjText {
    std::string obj, mtl;
};
HEMIRAD_API ObjText scene_obj_text(const Scene& scene, const std::string& mtl_name);

/// Writes the scene to `obj_path` (ending in .obj) and its MTL beside it (same name, .mtl),
/// atomically. Returns the MTL's path. Throws InputError for a bad name, RuntimeError when a
/// file cannot be written.
HEMIRAD_API std::string write_obj(const Scene& scene, const std::string& obj_path);

/// Built-in scenes: "cornell", "cube", "furnace", "sphere", "room" (make_light_room); the CIE 171
/// rooms "cie53", "cie56", "cie57", "cie58" (options.rho, default 0.5) and paper 002's benchmark
/// rooms "room402", "scene3138" (validation_scenes.h). Throws InputError for other names.
HEMIRAD_API Scene make_builtin(const std::string& name, const BuiltinOptions& options = {});
HEMIRAD_API bool is_builtin(const std::string& name);
HEMIRAD_API const char*
builtin_names(); ///< "cornell, cube, furnace, sphere, room, cie53, ..., scene3138"

} // namespace hemirad
