// Image outputs of `hemirad solve`: rendered views (-o FILE.exr / FILE.png) and the
// false-colour irradiance view (--false-colour FILE.png).
#pragma once

#include <string>
#include <vector>

#include "cli/args.h"
#include "hemirad/solver.h"

namespace hemirad::cli {

struct ImageOutputOptions {
    std::vector<std::string> files; ///< -o FILE.exr / FILE.png (repeatable)
    /// --camera: "" (scene.cameras[0]), a camera name of the scene, or
    /// "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov" (fov vertical, degrees)
    std::string camera;
    int width = 512, height = 512;      ///< [pixels] (16..8192)
    std::string shading = "smooth";     ///< smooth | flat
    bool patch_edges = false;           ///< overlay leaf patch edges
    bool two_sided = false;             ///< draw the backs of polygons (black) instead of culling
    std::string discontinuities = "on"; ///< --discontinuities on|off (render.h)
    bool ambient = false;               ///< add rho * ambient irradiance (display only)
    bool exr_float = false;             ///< EXR with 32-bit floats (default: half)
    /// PNG exposure: "auto" (default: 95th luminance percentile -> 1), "auto+S" / "auto-S"
    /// (S stops from auto), or a number S: fixed scale 2^S (radiosity 2^-S W unit^-2 -> 1).
    std::string exposure = "auto";
    std::string false_colour;               ///< --false-colour FILE.png (irradiance view)
    std::string false_colour_scale = "log"; ///< log | linear
    bool lux = false;                       ///< false colour in lux: E * 683 lm/W (assumes metres)
};
void add_image_options(ArgParser& args, ImageOutputOptions& o);
/// Checks everything that needs no scene (extensions, sizes, camera syntax); InputError.
void validate_image_options(const ImageOutputOptions& o);
bool image_outputs_need_gl(const ImageOutputOptions& o);
/// Checks what needs the scene (a --camera NAME it has), before solving; InputError.
void check_image_camera(const ImageOutputOptions& o, const Scene& scene);
/// Writes every image asked for, from the solver's current solution (GL context current).
void write_image_outputs(const ImageOutputOptions& o, Solver& solver, bool quiet);

} // namespace hemirad::cli
