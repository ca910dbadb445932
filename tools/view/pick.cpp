#include "pick.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "hemirad/gather.h"
#include "hemirad/image.h"
#include "hemirad/photometry.h"
#include "hemirad/report.h"

namespace hemirad::view {

double PickResult::luminance() const {
    return hemirad::luminance(E.r, E.g, E.b);
}

double PickResult::lux() const {
    return kLumensPerWatt * luminance();
}

Picker::Picker(const Scene& scene) : bvh_(scene) {}

Picker::~Picker() = default;

PickResult Picker::pick(const Hierarchy& h, const Camera& camera, int width, int height, int x,
                        int y) const {
    // The same ray as the renderer's projection (discontinuities.cpp): through the pixel centre.
    const dvec3 forward = glm::normalize(camera.target - camera.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, camera.up));
    const dvec3 up = glm::cross(right, forward);
    const double ty = std::tan(0.5 * glm::radians(camera.fov_y_deg));
    const double tx = ty * double(width) / double(height);
    const double sx = (2.0 * (x + 0.5) / width - 1.0) * tx;
    const double sy = (1.0 - 2.0 * (y + 0.5) / height) * ty;
    const dvec3 dir = forward + sx * right + sy * up;
    PickResult r;
    Hit hit;
    if (!bvh_.intersect(camera.eye, dir, 1e300, hit) || !hit.front) return r;
    const Scene& scene = h.scene();
    const Polygon& poly = scene.polygons[hit.polygon];
    r.hit = true;
    r.position = camera.eye + hit.t * dir;
    r.normal = poly.normal;
    r.group = scene.groups[poly.group];
    // One probe through the code path of `hemirad solve --probes` (default gather options):
    // point 0 of a probe file gets the same random stream.
    if (!gather_ || gathered_ != &h) {
        gather_ = std::make_unique<FinalGather>(h, GatherOptions{});
        gathered_ = &h;
    }
    const std::vector<ProbeValue> v =
        evaluate_probes({Probe{r.position, r.normal}}, h, gather_.get());
    if (v[0].E) r.E = *v[0].E;
    if (v[0].polygon) r.group = scene.groups[scene.polygons[*v[0].polygon].group];
    return r;
}

std::string pick_line(int x, int y, const PickResult& r, bool lux) {
    char text[512];
    if (!r.hit) {
        std::snprintf(text, sizeof text, "pick %d %d: none", x, y);
        return text;
    }
    // + 0.0 turns -0 into 0.
    const auto c = [](double v) { return std::abs(v) < 5e-13 ? 0.0 : v + 0.0; };
    std::snprintf(text, sizeof text, "pick %d %d: %.6g %.6g %.6g %.4g %.4g %.4g %s ", x, y,
                  c(r.position.x), c(r.position.y), c(r.position.z), c(r.normal.x), c(r.normal.y),
                  c(r.normal.z), r.group.c_str());
    std::string line = text;
    if (lux)
        std::snprintf(text, sizeof text, "%.1f lx", r.lux());
    else
        std::snprintf(text, sizeof text, "%.5g W/unit^2", r.luminance());
    return line + text;
}

} // namespace hemirad::view
