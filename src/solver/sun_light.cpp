// The sun's direct light on surfaces (sun_light.h).
#include "solver/sun_light.h"

#include <cmath>
#include <limits>
#include <vector>

#include "core/parallel.h"
#include "ff/bvh.h"
#include "hemirad/patch.h"

namespace hemirad {

namespace {

/// Shadow-ray grids over a leaf: kCoarse x kCoarse first, kFine x kFine where that is mixed.
constexpr int kCoarse = 4, kFine = 8;

/// Is the ray from x + offset n along s blocked by a polygon other than `self`?
bool in_shadow(const Bvh& bvh, const dvec3& s, const dvec3& x, const dvec3& n, std::uint32_t self,
               double offset) {
    Hit hit;
    return bvh.intersect(x + offset * n, s, std::numeric_limits<double>::infinity(), hit, self);
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

/// The fraction of an m x m grid of cell centres over the leaf that sees the sun.
double visible_fraction(const Bvh& bvh, const dvec3& s, const PatchGeometry& g, const dvec3& n,
                        std::uint32_t self, double offset, int m, std::uint64_t& rays) {
    int seen = 0;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i)
            seen += in_shadow(bvh, s, leaf_point(g, (i + 0.5) / m, (j + 0.5) / m), n, self, offset)
                        ? 0
                        : 1;
    rays += std::uint64_t(m * m);
    return double(seen) / double(m * m);
}

double ray_offset(const Scene& scene) {
    return 1e-9 * scene.bounds().diagonal();
}

} // namespace

SunDelivery deliver_sunlight(const Scene& scene, Hierarchy& hierarchy, int threads) {
    if (!scene.sun || !(scene.sun->normal_irradiance() > 0)) return {};
    const Sun& sun = *scene.sun;
    const Bvh bvh(scene);
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
            double v =
                visible_fraction(bvh, sun.direction, g, poly.normal, p, offset, kCoarse, rays[p]);
            if (v > 0 && v < 1)
                v = visible_fraction(bvh, sun.direction, g, poly.normal, p, offset, kFine, rays[p]);
            leaf_E[p][k] = E * v;
        }
    });
    return receive_at_leaves(hierarchy, leaf_E, rays);
}

dvec3 sun_irradiance(const Scene& scene, const Bvh& bvh, const dvec3& x, const dvec3& n,
                     std::uint32_t self, double offset) {
    if (!scene.sun) return dvec3(0.0);
    const double E = scene.sun->irradiance(n);
    if (!(E > 0) || in_shadow(bvh, scene.sun->direction, x, n, self, offset)) return dvec3(0.0);
    return dvec3(E);
}

} // namespace hemirad
