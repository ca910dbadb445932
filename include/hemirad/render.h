// Rendering a solution through a camera (OpenGL, in the current context): each polygon shows
// its leaf radiosity, reconstructed smoothly or flat per patch, into a linear float image.
// Used by `hemirad solve -o`, the preview tool and the viewer alike.
//
// Pixel values are the displayed quantity itself, unscaled: radiosity B [W unit^-2] (or
// irradiance E [W unit^-2] with Quantity::Irradiance). The radiance of a diffuse surface is
// B / pi; we keep B so that an image pixel and a report number are the same quantity.
// The back of a polygon emits and reflects nothing: it is culled by default, so that a camera
// outside a closed room sees into it; with RenderOptions::two_sided it is drawn black (0).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "hemirad/hierarchy.h"
#include "hemirad/image.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

struct RenderOptions {
    int width = 512, height = 512; ///< image size [pixels] (16..8192); render() only
    /// Smooth (default): area-weighted nodal averaging, interpolated (see solution_renderer.cpp).
    /// Flat: every leaf patch shows its own value.
    enum class Shading { Smooth, Flat } shading = Shading::Smooth;
    bool patch_edges = false; ///< overlay the leaf patch edges (darkened, ~1 pixel wide)
    /// Include the estimate of the light not yet shot (Hierarchy::unshot_estimate(), set by
    /// Solver::solution(): an ambient term after Cohen et al. 1988), as every read-out does;
    /// off: what the shots delivered so far alone (the viewer's key B).
    bool ambient = true;
    enum class Quantity { Radiosity, Irradiance } quantity = Quantity::Radiosity;
    dvec3 background{0.0}; ///< where no surface is (written as is, not scaled)
    /// Draw the backs of polygons (as 0, black: they leave no light) instead of culling them
    /// (default: culled, so that what is behind them shows).
    bool two_sided = false;
    /// Display helpers for draw() into a window (the viewer); render() for files keeps the
    /// defaults, which give physical values. Every value is multiplied by `scale` (> 0,
    /// default 1); then, if `tone_map`, extended Reinhard on luminance (white point
    /// kReinhardWhite, as tone_map() in image.h) and the sRGB transfer function are applied
    /// in the shader, for an 8-bit non-sRGB window framebuffer.
    double scale = 1.0;
    bool tone_map = false;
    /// Mark one patch (the viewer's current shooter, Solver::last_shot().shooter): a
    /// translucent tint and a 2-pixel outline in `highlight_colour`, drawn after the scene
    /// and always on top (no depth test: a shooter behind a wall shows through it). The
    /// colour is written as is (not scaled, not tone-mapped). Default: none. An address that
    /// is not a patch of the scene draws nothing.
    std::optional<PatchAddress> highlight;
    dvec3 highlight_colour{1.0, 0.1, 0.9}; ///< display RGB in [0,1] (default magenta)
};

/// Shadow edges inside leaves, in a rendered image (discontinuities.cpp). A leaf whose
/// irradiance differs from a neighbour's (on the same polygon) by more than 20 % of the larger
/// (and by more than 1 % of the scene's 95th-percentile leaf) straddles a discontinuity: a
/// shadow edge, a contact line, a light's footprint; interpolated, it shows a leaf-sized soft
/// block. Every pixel whose camera ray lands on the front of such a leaf gets the detail the
/// leaves cannot hold: rho * (D(x) - D~(x)), with D(x) the direct light at the point itself
/// (the final gather's: emitter cells and shadow rays, gather.h) and D~(x) the same leaf-centre
/// interpolation (readout.h, interpolate_leaves) of the direct light at the leaf centres, so
/// that where the direct light is smooth nothing changes. With Quantity::Irradiance the
/// detail is added without rho. `image` must be render()'s output for this camera and options
/// (row 0 the top); flat shading and patch edges (views of the leaves themselves) are left
/// as they are.
struct DiscontinuityStats {
    std::size_t leaves = 0; ///< leaves flagged as straddling a discontinuity
    std::size_t pixels = 0; ///< pixels re-evaluated
    double seconds = 0;
};
HEMIRAD_API DiscontinuityStats resolve_discontinuities(ImageRGB& image, const Hierarchy& h,
                                                       const Camera& camera,
                                                       const RenderOptions& options);

/// Parses "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov" (fov: vertical, degrees, in (0, 180)). Throws
/// InputError naming the bad value (wrong count, not a number, eye == target, up parallel to
/// the view direction, fov out of range).
HEMIRAD_API Camera parse_camera(const std::string& text);

/// The scene's default view: scene.cameras[0], or, if it has none, frame_scene(scene).
HEMIRAD_API Camera default_camera(const Scene& scene);

/// A view that shows the scene's lit surfaces, for a scene without a camera (default_view.cpp):
/// the bounding box framed from outside, from the side that shows most lit front faces with
/// nothing in front of them (the open side of a box), or, where every side shows only the
/// backs of walls (a closed room), a view from inside across the room. Named "default".
/// Casts 32 x 32 rays from each of 10 candidate cameras (a BVH of the scene is built).
HEMIRAD_API Camera frame_scene(const Scene& scene);

/// GL resources for drawing one scene's solution; needs a current GL 4.5 context (create a
/// gl::Context first, or run inside the viewer's window). The scene must outlive it.
///
/// The leaf geometry (corner positions of every leaf patch, welded across polygons for the
/// smooth reconstruction) is built and uploaded at the first call, and again only when the
/// hierarchy's discretisation changes; each call then computes and uploads the colours only
/// (one float RGB per welded vertex, or per leaf in flat mode), so the viewer may call draw()
/// every frame.
class HEMIRAD_API SolutionRenderer {
  public:
    explicit SolutionRenderer(const Scene& scene);
    ~SolutionRenderer();
    SolutionRenderer(const SolutionRenderer&) = delete;
    SolutionRenderer& operator=(const SolutionRenderer&) = delete;

    /// Renders into an offscreen float framebuffer (RGBA32F + 32-bit depth, one sample per
    /// pixel) and reads it back (row 0 = top). Restores the GL state it changes.
    ImageRGB render(const Hierarchy& h, const Camera& camera, const RenderOptions& options);
    /// Draws into the currently bound framebuffer and viewport (the viewer's window): clears
    /// its colour (to options.background) and depth, then draws. The aspect ratio is
    /// viewport_width / viewport_height. Restores the GL state it changes.
    void draw(const Hierarchy& h, const Camera& camera, const RenderOptions& options,
              int viewport_width, int viewport_height);
    /// Draws only the highlight of `patch` (as RenderOptions::highlight, on top, no depth
    /// test) into the currently bound framebuffer and viewport: for a view drawn otherwise,
    /// e.g. the viewer's CPU false-colour image. Restores the GL state it changes.
    void draw_highlight(const Camera& camera, const PatchAddress& patch, const dvec3& colour,
                        int viewport_width, int viewport_height);

    /// Statistics of the current geometry (after the first render/draw).
    struct Stats {
        std::size_t leaves = 0;    ///< leaf patches drawn
        std::size_t vertices = 0;  ///< leaf-grid vertices (per polygon)
        std::size_t nodes = 0;     ///< welded vertices (smooth values computed per node)
        std::size_t triangles = 0; ///< triangles drawn
    };
    Stats stats() const;

  private:
    struct HEMIRAD_LOCAL Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace hemirad
