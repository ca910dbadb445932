// The sky's direct light on surfaces and at points (sky_light.h).
#include "solver/sky_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/parallel.h"
#include "core/sampling.h"
#include "ff/bvh.h"
#include "ff/glazing_tracer.h"
#include "hemirad/patch.h"

namespace hemirad {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kForever = std::numeric_limits<double>::infinity();
/// Cells across which the sky's radiance changes by more than this fraction are split (their
/// neighbouring pilots, kPilot to a cell, differing by more than kSteep / kPilot).
constexpr double kSteep = 0.25;
/// Pilot rays per cell along each axis of the unit square (sky_irradiance).
constexpr int kPilot = 2;

/// What a sky ray sees: a polygon, the sky, or the ground (the same as a polygon when the
/// ground is black).
enum class Seen : unsigned char { Polygon, Sky, Ground };

} // namespace

bool sky_escapes(const Bounds& b, const Bvh& bvh, const dvec3& origin, const dvec3& w,
                 std::uint32_t self) {
    // A segment to beyond the scene's bounds: an any-hit test, cheaper than the nearest hit.
    const double reach = 2 * (b.diagonal() + glm::length(origin - 0.5 * (b.lo + b.hi))) + 1;
    return !bvh.occluded(origin, origin + reach * w, self, kNoPolygon);
}

SkyDelivery deliver_skylight(const Scene& scene, const Bvh& bvh, const GlazingTracer& glazing,
                             Hierarchy& hierarchy, int threads) {
    if (!scene.sky) return {};
    const Sky& sky = *scene.sky;
    if (!(sky.scale > 0 || sky.ground_luminance() > 0)) return {};
    const Bounds bounds = scene.bounds();
    const double offset = 1e-9 * bounds.diagonal();
    const auto count = std::uint32_t(scene.polygons.size());
    constexpr int m = kSkyLeafRays;
    std::vector<std::vector<double>> leaf_E(count);
    std::vector<std::uint64_t> rays(count, 0);
    parallel_for(count, threads, [&](std::size_t i) {
        const auto p = std::uint32_t(i);
        const Polygon& poly = scene.polygons[p];
        const auto level = std::uint32_t(hierarchy.depth(p));
        const std::uint32_t leaves = 1u << (2 * level);
        leaf_E[p].assign(leaves, 0.0);
        dvec3 t, b;
        orthonormal_basis(poly.normal, t, b);
        Rng rng(splitmix64(0x5ca1ab1eull ^ splitmix64(p)));
        for (std::uint32_t k = 0; k < leaves; ++k) {
            const PatchGeometry g = patch_geometry(poly, level, k);
            double sum = 0;
            for (int j = 0; j < m; ++j)
                for (int q = 0; q < m; ++q) {
                    const double pick = rng.uniform(), a1 = rng.uniform(), a2 = rng.uniform();
                    const dvec3 x =
                        area_point(g.corners.data(), g.count, pick, a1, a2) + offset * poly.normal;
                    const double u1 = (q + rng.uniform()) / m, u2 = (j + rng.uniform()) / m;
                    const dvec3 w = cosine_direction(poly.normal, t, b, u1, u2);
                    if (sky_escapes(bounds, bvh, x, w, p))
                        sum += sky.radiance(w) * glazing.along(x, w, kForever);
                }
            rays[p] += std::uint64_t(m * m);
            leaf_E[p][k] = kPi * sum / double(m * m);
        }
    });
    return receive_at_leaves(hierarchy, leaf_E, rays);
}

dvec3 sky_irradiance(const Sky& sky, const Bounds& bounds, const Bvh& bvh, const dvec3& x,
                     const dvec3& n, std::uint32_t self, double offset, Rng& rng, int coarse,
                     int fine, std::uint64_t* rays, const GlazingTracer* glazing) {
    const bool ground = sky.ground_luminance() > 0;
    dvec3 t, b;
    orthonormal_basis(n, t, b);
    const dvec3 origin = x + offset * n;
    std::uint64_t cast = 0;
    // One ray from the origin through cell (i, j) of an m x m grid at jittered (a1, a2): what
    // it sees and the radiance it brings [W sr^-1 m^-2].
    const auto trace = [&](double u1, double u2, double& L) {
        const dvec3 w = cosine_direction(n, t, b, u1, u2);
        ++cast;
        L = 0;
        if (!sky_escapes(bounds, bvh, origin, w, self)) return Seen::Polygon;
        L = sky.radiance(w) * (glazing ? glazing->along(origin, w, kForever) : 1.0);
        if (glm::dot(w, sky.up) > 0) return Seen::Sky;
        return ground ? Seen::Ground : Seen::Polygon;
    };
    const int m = coarse;
    // The pilots: rays through the centres of a (kPilot m)^2 grid, kPilot^2 in each cell. They
    // only decide which cells are split, so that decision does not depend on the random samples
    // that estimate the cells (a decision taken from the estimates themselves would bias them).
    // A cell is split when one of its pilots sees another thing than one of its 4 neighbouring
    // pilots, or sky more than kSteep / kPilot brighter or darker (the circumsolar peak).
    const int pm = kPilot * m;
    std::vector<Seen> seen(std::size_t(pm * pm));
    std::vector<double> value(std::size_t(pm * pm));
    for (int j = 0; j < pm; ++j)
        for (int i = 0; i < pm; ++i)
            seen[std::size_t(j * pm + i)] =
                trace((i + 0.5) / pm, (j + 0.5) / pm, value[std::size_t(j * pm + i)]);
    const auto differs = [&](std::size_t a, std::size_t o) {
        if (seen[o] != seen[a]) return true;
        return seen[a] != Seen::Polygon &&
               std::abs(value[o] - value[a]) > kSteep / kPilot * std::max(value[o], value[a]);
    };
    std::vector<char> split(std::size_t(m * m), 0);
    const auto mark = [&](int i, int j) { split[std::size_t((j / kPilot) * m + i / kPilot)] = 1; };
    for (int j = 0; j < pm; ++j)
        for (int i = 0; i < pm; ++i) {
            const std::size_t a = std::size_t(j * pm + i);
            // u1 (the radius) is clamped at 0 and 1; u2 (the azimuth) wraps.
            if (i + 1 < pm && differs(a, a + 1)) {
                mark(i, j);
                mark(i + 1, j);
            }
            const int j2 = (j + 1) % pm;
            if (differs(a, std::size_t(j2 * pm + i))) {
                mark(i, j);
                mark(i, j2);
            }
        }
    double sum = 0;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
            if (!split[std::size_t(j * m + i)]) { // one jittered ray
                double L = 0;
                trace((i + rng.uniform()) / m, (j + rng.uniform()) / m, L);
                sum += L;
                continue;
            }
            double cell = 0;
            for (int fj = 0; fj < fine; ++fj)
                for (int fi = 0; fi < fine; ++fi) {
                    const double u1 = (i + (fi + rng.uniform()) / fine) / m;
                    const double u2 = (j + (fj + rng.uniform()) / fine) / m;
                    double L = 0;
                    trace(u1, u2, L);
                    cell += L;
                }
            sum += cell / double(fine * fine);
        }
    if (rays) *rays += cast;
    return dvec3(kPi * sum / double(m * m));
}

} // namespace hemirad
