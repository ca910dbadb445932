// Rendering a solution through a camera (OpenGL, in the current context): each polygon shows
// its leaf radiosity, reconstructed smoothly or flat per patch, into a linear float image.
// Used by `hemirad solve -o`, the preview tool and the viewer alike.
#pragma once

#include <memory>
#include <string>

#include "hemirad/hierarchy.h"
#include "hemirad/image.h"
#include "hemirad/scene.h"

namespace hemirad {

struct RenderOptions {
    int width = 512, height = 512;  ///< image size [pixels] (16..8192)
    enum class Shading { Smooth, Flat } shading = Shading::Smooth; ///< Smooth: see render.cpp
    bool patch_edges = false;       ///< overlay the leaf patch edges
    /// Add rho * ambient to the radiosity (Cohen et al. 1988), for unconverged solutions.
    bool ambient = false;
    dvec3 ambient_irradiance{0.0};  ///< Solver::ambient_irradiance(), used when ambient is on
    enum class Quantity { Radiosity, Irradiance } quantity = Quantity::Radiosity;
    dvec3 background{0.0};          ///< where no surface is
};

/// Parses "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov" (fov: vertical, degrees). InputError if malformed.
Camera parse_camera(const std::string& text);

/// GL resources for drawing one scene's solution; needs a current GL 4.5 context (create a
/// gl::Context first, or run inside the viewer's window).
class SolutionRenderer {
public:
    explicit SolutionRenderer(const Scene& scene);
    ~SolutionRenderer();
    SolutionRenderer(const SolutionRenderer&) = delete;
    SolutionRenderer& operator=(const SolutionRenderer&) = delete;

    /// Renders into an offscreen float framebuffer and reads it back (row 0 = top).
    ImageRGB render(const Hierarchy& h, const Camera& camera, const RenderOptions& options);
    /// Draws into the currently bound framebuffer and viewport (the viewer's window).
    void draw(const Hierarchy& h, const Camera& camera, const RenderOptions& options,
              int viewport_width, int viewport_height);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace hemirad
