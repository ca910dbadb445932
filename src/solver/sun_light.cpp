// The sun's direct light on surfaces (sun_light.h).
#include "solver/sun_light.h"

#include <cmath>
#include <limits>
#include <vector>

#include "core/parallel.h"
#include "ff/bvh.h"
#include "ff/glazing_tracer.h"
#include "hemirad/patch.h"

namespace hemirad {

namespace {

/// Shadow-ray grids over a leaf: kCoarse x kCoarse first, kFine x kFine where that is mixed.
constexpr int kCoarse = 4, kFine = 8;

/// What reaches x + offset n along s: 0 where a polygon other than `self` blocks the ray,
/// else the transmittance of the window panes it crosses (1 without).
double sun_reaches(const Bvh& bvh, const GlazingTracer* glazing, const dvec3& s, const dvec3& x,
                   const dvec3& n, std::uint32_t self, double offset) {
    Hit hit;
    const dvec3 o = x + offset * n;
    if (bvh.intersect(o, s, std::numeric_limits<double>::infinity(), hit, self)) return 0.0;
    return glazing ? glazing->along(o, s, std::numeric_limits<double>::infinity()) : 1.0;
}

/// The point of a leaf at (a, b) in [0, 1]^2: bilinear over a quad's corners; over a triangle
/// the area-preserving map (1 - sqrt a) c0 + sqrt a ((1 - b) c1 + b c2).
dvec3 leaf_point(const PatchGeometry& g, double a, double b) {
    const auto& c = g.corners;
    if (g.count == 4)
        return (1 - a) * (1 - b) * c[0] + a * (1 - b) * c[1] + a * b * c[2] + (1 - a) * b * c[3];
    const double r = std::sqrt(a);
    return (1 - r) * c[0] + r * ((1 - b) * c[1] + b * c[2]);
}

/// The mean over an m x m grid of cell centres over the leaf of what reaches them of the sun
/// (sun_reaches); `mixed`: they differ.
double visible_fraction(const Bvh& bvh, const GlazingTracer& glazing, const dvec3& s,
                        const PatchGeometry& g, const dvec3& n, std::uint32_t self, double offset,
                        int m, std::uint64_t& rays, bool& mixed) {
    double seen = 0, first = -1;
    mixed = false;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
            const double v = sun_reaches(
                bvh, &glazing, s, leaf_point(g, (i + 0.5) / m, (j + 0.5) / m), n, self, offset);
            if (first < 0) first = v;
            mixed = mixed || v != first;
            seen += v;
        }
    rays += std::uint64_t(m * m);
    return seen / double(m * m);
}

double ray_offset(const Scene& scene) {
    return 1e-9 * scene.bounds().diagonal();
}

} // namespace

SunDelivery deliver_sunlight(const Scene& scene, const Bvh& bvh, const GlazingTracer& glazing,
                             Hierarchy& hierarchy, int threads) {
    if (!scene.sun || !(scene.sun->normal_irradiance() > 0)) return {};
    const Sun& sun = *scene.sun;
    const double offset = ray_offset(scene);
    const auto count = std::uint32_t(scene.polygons.size());
    // Per polygon, the irradiance of each leaf (computed in parallel, received in order).
    std::vector<std::vector<double>> leaf_E(count);
    std::vector<std::uint64_t> rays(count, 0);
    parallel_for(count, threads, [&](std::size_t i) {
        const auto p = std::uint32_t(i);
        const Polygon& poly = scene.polygons[p];
        const double E = sun.irradiance(poly.normal);
        if (!(E > 0)) return;
        const auto level = std::uint32_t(hierarchy.depth(p));
        const std::uint32_t leaves = 1u << (2 * level);
        leaf_E[p].assign(leaves, 0.0);
        for (std::uint32_t k = 0; k < leaves; ++k) {
            const PatchGeometry g = patch_geometry(poly, level, k);
            bool mixed = false;
            double v = visible_fraction(bvh, glazing, sun.direction, g, poly.normal, p, offset,
                                        kCoarse, rays[p], mixed);
            if (mixed)
                v = visible_fraction(bvh, glazing, sun.direction, g, poly.normal, p, offset, kFine,
                                     rays[p], mixed);
            leaf_E[p][k] = E * v;
        }
    });
    return receive_at_leaves(hierarchy, leaf_E, rays);
}

dvec3 sun_irradiance(const Scene& scene, const Bvh& bvh, const dvec3& x, const dvec3& n,
                     std::uint32_t self, double offset, const GlazingTracer* glazing) {
    if (!scene.sun) return dvec3(0.0);
    const double E = scene.sun->irradiance(n);
    if (!(E > 0)) return dvec3(0.0);
    return dvec3(E * sun_reaches(bvh, glazing, scene.sun->direction, x, n, self, offset));
}

} // namespace hemirad
