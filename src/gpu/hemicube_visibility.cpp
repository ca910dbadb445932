// Visibility read from a rendered hemicube's patch IDs (hemicube_visibility.h).
#include "gpu/hemicube_visibility.h"

#include <cmath>

namespace hemirad::gpu {

namespace {

// Is p (in q's plane) inside the convex polygon q, away from its edges by a small relative
// margin (a point on a shared edge is in neither polygon)?
bool inside(const Polygon& q, const dvec3& p) {
    for (int k = 0; k < q.count; ++k) {
        const dvec3& a = q.v[k];
        const dvec3 e = q.v[(k + 1) % q.count] - a;
        if (glm::dot(glm::cross(e, p - a), q.normal) <= 1e-7 * glm::dot(e, e)) return false;
    }
    return true;
}

// Ray parameter (in units of u, from `from`) where the ray meets q's plane, or -1.
double plane_hit(const Polygon& q, const dvec3& from, const dvec3& u) {
    const double denom = glm::dot(u, q.normal);
    if (denom == 0) return -1;
    return glm::dot(q.v[0] - from, q.normal) / denom;
}

} // namespace

bool segment_crosses(const Polygon& q, const dvec3& from, const dvec3& d) {
    const double t = plane_hit(q, from, d);
    if (!(t > 1e-9 && t < 1 - 1e-6)) return false;
    return inside(q, from + t * d);
}

HemicubeVisibility::HemicubeVisibility(const Scene& scene, const HemicubeLayout& layout,
                                       const HemicubeFrame& frame, const float* rgba,
                                       const dvec3& eye)
    : scene_(&scene), layout_(&layout), frame_(frame), rgba_(rgba), eye_(eye) {}

long HemicubeVisibility::shown(std::size_t at) const {
    const float id = rgba_[4 * at + 2];
    if (id > -0.5f && id < 0.5f) return -1;
    return long(std::lround(std::abs(id))) - 1;
}

dvec3 HemicubeVisibility::ray(int f, int i, int j) const {
    const double d = 2.0 / layout_->res;
    const double x = -1 + (i + 0.5) * d;
    const double y = f == 0 ? -1 + (j + 0.5) * d : (j + 0.5) * d;
    const dvec3 screen_x = glm::cross(frame_.dir[f], frame_.up[f]);
    return frame_.dir[f] + x * screen_x + y * frame_.up[f];
}

bool HemicubeVisibility::hides(int f, int i, int j, std::uint32_t p) const {
    const HemicubeLayout::Face& face = layout_->faces[f];
    const long q =
        shown(std::size_t(face.y + j) * std::size_t(layout_->width) + std::size_t(face.x + i));
    if (q < 0) return false; // nothing there: nothing hides p along that ray
    const dvec3 u = ray(f, i, j);
    const Polygon& P = scene_->polygons[p];
    const double tp = plane_hit(P, eye_, u);
    if (!(tp > 0) || !inside(P, eye_ + tp * u)) return false; // p does not go on there
    const double tq = plane_hit(scene_->polygons[std::size_t(q)], eye_, u);
    return tq > 0 && tq < tp * (1 - 1e-6);
}

bool HemicubeVisibility::visible(const dvec3& x, std::uint32_t own) const {
    const dvec3 d = x - eye_;
    const long pixel = hemicube_pixel(*layout_, frame_, d);
    if (pixel < 0) return false;
    const long q = shown(std::size_t(pixel));
    if (q < 0 || std::uint32_t(q) == own) return true;
    return !segment_crosses(scene_->polygons[std::size_t(q)], eye_, d);
}

bool HemicubeVisibility::visible_in_depth_map(const dvec3& x, std::uint32_t own) const {
    const dvec3 d = x - eye_;
    const long pixel = hemicube_pixel(*layout_, frame_, d);
    if (pixel < 0) return false;
    const long q = shown(std::size_t(pixel));
    if (q < 0 || std::uint32_t(q) == own) return true;
    const double t = plane_hit(scene_->polygons[std::size_t(q)], eye_, d);
    return !(t < 1 - 1e-6);
}

} // namespace hemirad::gpu
