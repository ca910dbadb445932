#include "hemirad/readout.h"

#include "ff/bvh.h"

#include <algorithm>
#include <cmath>

namespace hemirad {

namespace {

// Two in-plane axes of a polygon for 2D work.
void plane_axes(const Polygon& p, dvec3& e1, dvec3& e2) {
    e1 = glm::normalize(p.v[1] - p.v[0]);
    e2 = glm::cross(p.normal, e1);
}

} // namespace

bool polygon_uv(const Polygon& poly, const dvec3& p, double& u, double& v, double slack) {
    dvec3 e1, e2;
    plane_axes(poly, e1, e2);
    const auto to2 = [&](const dvec3& x) {
        const dvec3 d = x - poly.v[0];
        return glm::dvec2(glm::dot(d, e1), glm::dot(d, e2));
    };
    const glm::dvec2 q = to2(p);
    if (poly.is_triangle()) {
        const glm::dvec2 a = to2(poly.v[1]), b = to2(poly.v[2]);
        const double det = a.x * b.y - a.y * b.x;
        u = (q.x * b.y - q.y * b.x) / det;
        v = (a.x * q.y - a.y * q.x) / det;
        return u >= -slack && v >= -slack && u + v <= 1 + slack;
    }
    inverse_bilinear_unclamped(poly.v[0], poly.v[1], poly.v[2], poly.v[3], poly.normal, p, u, v);
    return u >= -slack && v >= -slack && u <= 1 + slack && v <= 1 + slack;
}

std::optional<SurfacePoint> find_surface(const Scene& scene, const dvec3& point,
                                         const dvec3& normal, double max_distance) {
    const double len = glm::length(normal);
    if (!(len > 0)) return std::nullopt;
    const dvec3 n = normal / len;
    if (max_distance <= 0) max_distance = 1e-3 * scene.bounds().diagonal();
    std::optional<SurfacePoint> best;
    for (std::uint32_t i = 0; i < scene.polygons.size(); ++i) {
        const Polygon& p = scene.polygons[i];
        if (glm::dot(p.normal, n) < 0.5) continue;
        const double d = glm::dot(point - p.v[0], p.normal);
        if (std::abs(d) > max_distance) continue;
        if (best && std::abs(d) >= best->distance) continue;
        double u, v;
        if (!polygon_uv(p, point - d * p.normal, u, v, 1e-6)) continue;
        best = SurfacePoint{i, std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0), std::abs(d)};
    }
    return best;
}

dvec3 irradiance_at(const Hierarchy& h, const SurfacePoint& sp) {
    const std::uint32_t level = std::uint32_t(h.depth(sp.polygon));
    return interpolate_leaves(h, sp, [&](std::uint32_t index) {
        return h.irradiance({sp.polygon, level, index});
    });
}

GroupIrradiance group_irradiance(const Hierarchy& h, std::uint32_t group) {
    GroupIrradiance g;
    g.E_min = dvec3(1e300);
    g.E_max = dvec3(-1e300);
    dvec3 weighted(0.0);
    const Scene& scene = h.scene();
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        if (scene.polygons[p].group != group) continue;
        const std::uint32_t level = std::uint32_t(h.depth(p));
        const std::uint32_t n = 1u << (2 * level);
        for (std::uint32_t i = 0; i < n; ++i) {
            const PatchAddress a{p, level, i};
            const dvec3 E = h.irradiance(a);
            const double area = double(h.node(a).area);
            g.area += area;
            weighted += E * area;
            g.E_min = glm::min(g.E_min, E);
            g.E_max = glm::max(g.E_max, E);
        }
    }
    if (g.area > 0)
        g.E_avg = weighted / g.area;
    else
        g.E_min = g.E_max = dvec3(0.0);
    return g;
}

} // namespace hemirad
