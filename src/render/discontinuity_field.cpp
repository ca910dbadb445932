// Leaves that straddle a discontinuity of the direct light (discontinuity_field.h).
#include "render/discontinuity_field.h"

#include <algorithm>
#include <cmath>

#include "hemirad/readout.h"

namespace hemirad {

namespace {

constexpr double kJump = 0.2;   ///< relative difference that flags a pair of leaves
constexpr double kFloor = 0.01; ///< ...when also above this share of the 95th percentile

double luminance(const dvec3& e) {
    return 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z;
}

} // namespace

DiscontinuityField::DiscontinuityField(const Hierarchy& h) : h_(&h) {
    const Scene& scene = h.scene();
    std::vector<double> all;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const std::uint32_t level = std::uint32_t(h.depth(p));
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i)
            all.push_back(luminance(h.irradiance({p, level, i})));
    }
    if (all.empty()) return;
    const std::size_t k95 = std::size_t(0.95 * double(all.size() - 1));
    std::nth_element(all.begin(), all.begin() + long(k95), all.end());
    const double floor = kFloor * all[k95];

    // Leaf centres in parameter space, and the leaf one step away (or the leaf itself).
    const auto centre_uv = [&](std::uint32_t p, std::uint32_t level, std::uint32_t i, double& u,
                               double& v) {
        const Polygon& poly = scene.polygons[p];
        return polygon_uv(poly, patch_geometry(poly, level, i).centre, u, v, 1e-6);
    };
    std::vector<std::uint64_t> flagged;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        const std::uint32_t level = std::uint32_t(h.depth(p));
        const double step = 1.0 / double(1u << level);
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) {
            double u, v;
            if (!centre_uv(p, level, i, u, v)) continue;
            const double y = luminance(h.irradiance({p, level, i}));
            const double du[4] = {step, -step, 0, 0}, dv[4] = {0, 0, step, -step};
            bool jump = false;
            for (int k = 0; k < 4 && !jump; ++k) {
                const double nu = u + du[k], nv = v + dv[k];
                if (nu < 0 || nv < 0 || nu > 1 || nv > 1) continue;
                if (poly.is_triangle() && nu + nv > 1) continue;
                const std::uint32_t n = patch_at(poly, level, nu, nv);
                if (n == i) continue;
                const double yn = luminance(h.irradiance({p, level, n}));
                const double d = std::abs(y - yn);
                jump = d > kJump * std::max(y, yn) && d > floor;
            }
            if (jump) flagged.push_back(key(p, i)), flagged_[key(p, i)] = 1;
        }
    }
    if (flagged.empty()) return;

    GatherOptions go;
    go.threads = 1;
    go.jitter = false;      // no noise from point to point
    go.coarse_test = false; // no step where a coarse ray first meets an occluder
    go.bright_factor = 0;   // direct light only: no indirect rays to steer
    point_ = std::make_unique<FinalGather>(h, go);
    go.coarse_test = true; // leaf means: the whole-emitter shortcut where all is visible
    const FinalGather mean(h, go);
    for (const std::uint64_t k : flagged) {
        const std::uint32_t p = std::uint32_t(k >> 32), i = std::uint32_t(k);
        const Polygon& poly = scene.polygons[p];
        const std::uint32_t level = std::uint32_t(h.depth(p));
        const double step = 1.0 / double(1u << level);
        double u, v;
        if (!centre_uv(p, level, i, u, v)) continue;
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const std::uint32_t n = patch_at(poly, level, std::clamp(u + di * step, 0.0, 1.0),
                                                 std::clamp(v + dj * step, 0.0, 1.0));
                const std::uint64_t nk = key(p, n);
                if (mean_direct_.count(nk)) continue;
                // 16 grandchildren measured no better than 4 children in the shadow-edge test.
                dvec3 sum(0.0);
                for (std::uint32_t c : patch_children(poly.is_triangle(), level, n)) {
                    const PatchGeometry g = patch_geometry(poly, level + 1, c);
                    sum += mean.direct_at({g.centre, poly.normal, p}, nk);
                }
                mean_direct_[nk] = sum / 4.0;
            }
    }
}

bool DiscontinuityField::detail(std::uint32_t p, double u, double v, const dvec3& x,
                                std::uint64_t index, Reconstruction r, dvec3& out) const {
    const Polygon& poly = h_->scene().polygons[p];
    const std::uint32_t level = std::uint32_t(h_->depth(p));
    const std::uint32_t leaf = patch_at(poly, level, u, v);
    if (!flagged(p, leaf)) return false;
    bool complete = true;
    const auto mean = [&](std::uint32_t n) {
        const auto it = mean_direct_.find(key(p, n));
        if (it != mean_direct_.end()) return it->second;
        complete = false;
        return dvec3(0.0);
    };
    dvec3 smooth(0.0);
    if (r == Reconstruction::Leaf || poly.is_triangle()) {
        smooth = mean(leaf);
    } else {
        // As the renderer: nodal averages at the leaf's corners, linear over its two
        // triangles c0 c1 c2 and c0 c2 c3.
        const int n = 1 << level, lx = int(leaf) % n, ly = int(leaf) / n;
        const auto node = [&](int i, int j) {
            dvec3 sum(0.0);
            int count = 0;
            for (int b = j - 1; b <= j; ++b)
                for (int a = i - 1; a <= i; ++a)
                    if (a >= 0 && b >= 0 && a < n && b < n)
                        sum += mean(std::uint32_t(b * n + a)), ++count;
            return sum / double(count);
        };
        const double a = std::clamp(u * n - lx, 0.0, 1.0), b = std::clamp(v * n - ly, 0.0, 1.0);
        const dvec3 v00 = node(lx, ly), v10 = node(lx + 1, ly), v11 = node(lx + 1, ly + 1),
                    v01 = node(lx, ly + 1);
        smooth = a >= b ? v00 + a * (v10 - v00) + b * (v11 - v10)
                        : v00 + a * (v11 - v01) + b * (v01 - v00);
    }
    if (!complete) return false;
    out = point_->direct_at({x, poly.normal, p}, index) - smooth;
    return true;
}

} // namespace hemirad
