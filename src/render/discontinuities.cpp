// Shadow edges inside leaves, re-evaluated per pixel (render.h, resolve_discontinuities).
#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/parallel.h"
#include "core/timer.h"
#include "ff/bvh.h"
#include "hemirad/render.h"
#include "render/discontinuity_field.h"

namespace hemirad {

DiscontinuityStats resolve_discontinuities(ImageRGB& image, const Hierarchy& h,
                                           const Camera& camera, const RenderOptions& o) {
    const Stopwatch timer;
    DiscontinuityStats stats;
    // Diagnostic views of the leaves themselves are left as they are.
    if (o.patch_edges || o.shading == RenderOptions::Shading::Flat || image.empty()) return stats;
    const DiscontinuityField field(h);
    stats.leaves = field.flagged_count();
    if (stats.leaves == 0) return stats;
    const Scene& scene = h.scene();

    // The camera ray of each pixel centre, as the GL projection of render(). On a flagged
    // leaf the image gets rho * detail (irradiance: the detail itself).
    const Bvh bvh(scene);
    const dvec3 forward = glm::normalize(camera.target - camera.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, camera.up));
    const dvec3 up = glm::cross(right, forward);
    const double ty = std::tan(0.5 * glm::radians(camera.fov_y_deg));
    const double tx = ty * double(image.width) / double(image.height);
    const bool irradiance = o.quantity == RenderOptions::Quantity::Irradiance;
    std::atomic<std::size_t> pixels{0};
    parallel_for(std::size_t(image.height), 0, [&](std::size_t row) {
        const int y = int(row);
        for (int x = 0; x < image.width; ++x) {
            const double sx = (2.0 * (x + 0.5) / image.width - 1.0) * tx;
            const double sy = (1.0 - 2.0 * (y + 0.5) / image.height) * ty;
            const dvec3 dir = forward + sx * right + sy * up;
            Hit hit;
            if (!bvh.intersect(camera.eye, dir, 1e300, hit) || !hit.front) continue;
            dvec3 detail;
            const std::uint64_t index = std::uint64_t(y) * std::uint64_t(image.width) + x;
            if (!field.detail(hit.polygon, hit.u, hit.v, camera.eye + hit.t * dir, index,
                              DiscontinuityField::Reconstruction::Smooth, detail))
                continue;
            const Material& m = scene.material_of(scene.polygons[hit.polygon]);
            const dvec3 floor_value = irradiance ? dvec3(0.0) : m.exitance();
            const dvec3 rho = reflectance_at(scene, hit.polygon, hit.u, hit.v); // texel
            float* px = image.at(x, y);
            for (int c = 0; c < 3; ++c) {
                const double add = irradiance ? detail[c] : rho[c] * detail[c];
                px[c] = float(std::max(double(px[c]) + add, floor_value[c]));
            }
            pixels.fetch_add(1);
        }
    });
    stats.pixels = pixels.load();
    stats.seconds = timer.seconds();
    return stats;
}

} // namespace hemirad
