// Reading a solution: irradiance at points (probes) and per surface group.
#pragma once

#include <algorithm>
#include <optional>

#include "hemirad/hierarchy.h"
#include "hemirad/scene.h"
#include "hemirad/visibility.h"

namespace hemirad {

struct SurfacePoint {
    std::uint32_t polygon = 0;
    double u = 0, v = 0; ///< parameters on the polygon (patch.h)
    double distance = 0; ///< from the query point to the polygon's plane [unit]
};

/// Parameters (u,v) of a point in the polygon's plane (inverse of polygon_point). Returns
/// false if the point lies outside the polygon by more than `slack` in parameter space.
HEMIRAD_API bool polygon_uv(const Polygon& polygon, const dvec3& p, double& u, double& v,
                            double slack = 1e-6);

/// The nearest polygon facing the direction `normal` (normals within 60 degrees), with the
/// point's projection inside it, at most `max_distance` from its plane (0 = 1e-3 of the
/// scene diagonal). Nothing if no surface is there.
HEMIRAD_API std::optional<SurfacePoint> find_surface(const Scene& scene, const dvec3& point,
                                                     const dvec3& normal, double max_distance = 0);

/// Irradiance [W unit^-2] at a surface point, interpolated bilinearly between the centres of
/// the leaf patches around it (quads; triangles take the leaf that holds the point). The
/// hierarchy should be push-pulled (Solver::solution()).
HEMIRAD_API dvec3 irradiance_at(const Hierarchy& h, const SurfacePoint& sp);

/// The same interpolation of any per-leaf field: `leaf(index)` gives the value of the leaf
/// patch `index` of sp.polygon at its leaf level.
template <class LeafValue>
dvec3 interpolate_leaves(const Hierarchy& h, const SurfacePoint& sp, LeafValue leaf) {
    const Polygon& poly = h.scene().polygons[sp.polygon];
    const std::uint32_t level = std::uint32_t(h.depth(sp.polygon));
    if (poly.is_triangle()) return leaf(patch_at(poly, level, sp.u, sp.v));
    const int n = 1 << level;
    // Leaf centres sit at (i + 0.5)/n; interpolate between the four around (u,v).
    const double x = std::clamp(sp.u * n - 0.5, 0.0, double(n - 1));
    const double y = std::clamp(sp.v * n - 0.5, 0.0, double(n - 1));
    const int x0 = std::min(int(x), n - 1), y0 = std::min(int(y), n - 1);
    const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
    const double fx = x - x0, fy = y - y0;
    const auto at = [&](int i, int j) { return dvec3(leaf(std::uint32_t(j * n + i))); };
    return (1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x1, y0) +
           (1 - fx) * fy * at(x0, y1) + fx * fy * at(x1, y1);
}

/// Leaf-level irradiance statistics of one surface group, per channel.
struct GroupIrradiance {
    double area = 0;
    dvec3 E_avg{0.0}, E_min{0.0}, E_max{0.0};
};
HEMIRAD_API GroupIrradiance group_irradiance(const Hierarchy& h, std::uint32_t group);

} // namespace hemirad
