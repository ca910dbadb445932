// Textured scenes end to end (GL): the textured OBJ room and the glTF room of assets/ solve on
// the GPU and render with their textures. Rendered radiosity is B(x) = Be + texel(x) rho E(x)
// (solution_renderer.cpp): on the floor (Be = 0) the ratio of a radiosity image to an
// irradiance image of the same view is rho times the texel's linear reflectance, pixel by
// pixel. Seen from above, the checkerboard's two colours must both show, each at its own
// value: 0.9 x sRGB-decoded (230, 220, 200) and (120, 80, 50) (tools/make_texture_assets.py).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/colour.h"
#include "hemirad/gl/context.h"
#include "hemirad/render.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "hemirad/texture.h"

#include "shared_gl_context.h"

using namespace hemirad;

namespace {

class TextureGLTest : public SharedGlContextTest {};

struct FloorCheck {
    double dark_fraction = 0, light_fraction = 0; ///< pixels at each colour (within 2 %)
    double pixels = 0;
};

/// Solves `file` on the GPU, renders radiosity and irradiance looking straight down at
/// (x, z) of the floor from `height` above it, and counts the pixels whose B/E ratio (every
/// channel) is the dark or the light checker colour times 0.9, within 2 %.
FloorCheck check_floor(const std::string& file, double x, double z, double height) {
    const Scene scene = load_scene(std::string(HEMIRAD_SOURCE_DIR) + "/assets/" + file);
    SolverOptions so;
    so.tolerance = 0.05;
    // Leaves of 0.5 m and more: each holds several squares, so the leaves alone (their mean
    // reflectance) would show neither colour; only texture detail per pixel does.
    so.hierarchy.max_depth = 3;
    so.provider.gpu.use_current_context = true;
    Solver solver(scene, so);
    while (solver.step()) {}
    SolutionRenderer r(scene);
    RenderOptions o;
    o.width = o.height = 128;
    Camera cam;
    cam.eye = dvec3(x, height, z);
    cam.target = dvec3(x, 0, z);
    cam.up = dvec3(0, 0, 1);
    cam.fov_y_deg = 40;
    const ImageRGB B = r.render(solver.solution(), cam, o);
    o.quantity = RenderOptions::Quantity::Irradiance;
    const ImageRGB E = r.render(solver.solution(), cam, o);
    const auto lin = [](int v) { return 0.9 * srgb_decode(v / 255.0); };
    const dvec3 dark(lin(120), lin(80), lin(50)), light(lin(230), lin(220), lin(200));
    FloorCheck f;
    for (int y = 0; y < o.height; ++y)
        for (int px = 0; px < o.width; ++px) {
            const float* b = B.at(px, y);
            const float* e = E.at(px, y);
            if (!(e[0] > 0 && e[1] > 0 && e[2] > 0)) continue;
            const dvec3 ratio(b[0] / e[0], b[1] / e[1], b[2] / e[2]);
            const auto near = [&](const dvec3& c) {
                for (int k = 0; k < 3; ++k)
                    if (std::abs(ratio[k] / c[k] - 1) > 0.02) return false;
                return true;
            };
            f.pixels += 1;
            f.dark_fraction += near(dark);
            f.light_fraction += near(light);
        }
    f.dark_fraction /= std::max(f.pixels, 1.0);
    f.light_fraction /= std::max(f.pixels, 1.0);
    return f;
}

} // namespace

TEST_F(TextureGLTest, TexturedObjRoomShowsItsCheckerboard) {
    // Above the middle of the 4 x 4 m floor (under the light): 0.25 m squares, about 6.7 of
    // them across the view, each 19 pixels wide: all but the bilinear edges are one colour.
    const FloorCheck f = check_floor("textured_room.obj", 2.0, 2.0, 2.3);
    EXPECT_GT(f.pixels, 128 * 128 * 0.99);
    EXPECT_GT(f.dark_fraction, 0.35);
    EXPECT_GT(f.light_fraction, 0.35);
    // Magnified, GL filters the texture bilinearly: across each edge of a square (8 texels)
    // one texel's width blends the two colours, so about (7/8)^2 = 77 % of pixels are pure.
    EXPECT_GT(f.dark_fraction + f.light_fraction, 0.7);
}

TEST_F(TextureGLTest, GltfRoomShowsItsBaseColorTexture) {
    // A free part of the 5 x 4 m floor (no block in view), 1.2 m above it.
    const FloorCheck f = check_floor("gltf_room.gltf", 2.85, 3.2, 1.2);
    EXPECT_GT(f.pixels, 128 * 128 * 0.99);
    EXPECT_GT(f.dark_fraction, 0.3);
    EXPECT_GT(f.light_fraction, 0.3);
    // Magnified, GL filters the texture bilinearly: across each edge of a square (8 texels)
    // one texel's width blends the two colours, so about (7/8)^2 = 77 % of pixels are pure.
    EXPECT_GT(f.dark_fraction + f.light_fraction, 0.7);
}
