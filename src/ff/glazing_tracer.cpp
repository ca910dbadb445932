// Transmittance along rays through the window panes (glazing_tracer.h).
#include "ff/glazing_tracer.h"

#include <cmath>

#include "ff/bvh.h"

namespace hemirad {

namespace {

/// At most this many panes along one ray (a ray grazing along a glass façade, or a stack of
/// coincident panes, would otherwise be followed far).
constexpr int kMaxPanes = 16;

Scene pane_scene(const Scene& scene) {
    Scene s;
    for (const GlazingPane& g : scene.glazing) {
        s.polygons.push_back(g.polygon);
        s.polygons.back().twin = kNoTwin;
    }
    return s;
}

} // namespace

GlazingTracer::GlazingTracer(const Scene& scene) : panes_(scene.glazing) {
    if (!panes_.empty()) bvh_ = std::make_unique<Bvh>(pane_scene(scene));
}

GlazingTracer::~GlazingTracer() = default;

double GlazingTracer::along(const dvec3& origin, const dvec3& dir, double tmax) const {
    if (panes_.empty()) return 1.0;
    const double length = glm::length(dir);
    if (!(length > 0)) return 1.0;
    const dvec3 w = dir / length;
    double T = 1, left = tmax;
    dvec3 o = origin;
    std::uint32_t last = kNoPolygon;
    for (int k = 0; k < kMaxPanes && T > 0 && left > 0; ++k) {
        Hit hit;
        if (!bvh_->intersect(o, dir, left, hit, last)) break;
        const GlazingPane& pane = panes_[hit.polygon];
        T *= pane.transmittance.at(glm::dot(w, pane.polygon.normal));
        o += hit.t * dir;
        left -= hit.t;
        last = hit.polygon;
    }
    return T;
}

double GlazingTracer::between(const dvec3& from, const dvec3& to) const {
    if (panes_.empty()) return 1.0;
    constexpr double kEnd = 1e-7;
    const dvec3 d = to - from;
    return along(from + kEnd * d, d, 1 - 2 * kEnd);
}

} // namespace hemirad
