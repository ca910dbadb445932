// Shadow edges inside leaves, re-evaluated per pixel (render.h, resolve_discontinuities).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>
#include <unordered_map>

#include "ff/bvh.h"
#include "hemirad/gather.h"
#include "hemirad/readout.h"
#include "hemirad/render.h"

namespace hemirad {

namespace {

constexpr double kJump = 0.2;       ///< relative difference that flags a pair of leaves
constexpr double kFloor = 0.01;     ///< ...when also above this share of the 95th percentile

double luminance(const dvec3& e) { return 0.2126 * e.x + 0.7152 * e.y + 0.0722 * e.z; }

// Parameter-space centre of a leaf (inverse of the polygon's map at the patch centre).
bool leaf_uv(const Polygon& poly, const PatchGeometry& g, double& u, double& v) {
    return polygon_uv(poly, g.centre, u, v, 1e-6);
}

} // namespace

DiscontinuityStats resolve_discontinuities(ImageRGB& image, const Hierarchy& h,
                                           const Camera& camera, const RenderOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    DiscontinuityStats stats;
    // Diagnostic views of the leaves themselves are left as they are.
    if (o.patch_edges || o.shading == RenderOptions::Shading::Flat) return stats;
    const Scene& scene = h.scene();
    // 1. Flag leaves: compare each leaf with the leaves one leaf-width away in u and v.
    std::vector<double> all;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const std::uint32_t level = std::uint32_t(h.depth(p));
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i)
            all.push_back(luminance(h.irradiance({p, level, i})));
    }
    if (all.empty()) return stats;
    std::vector<double> sorted = all;
    const std::size_t k95 = std::size_t(0.95 * double(sorted.size() - 1));
    std::nth_element(sorted.begin(), sorted.begin() + long(k95), sorted.end());
    const double floor = kFloor * sorted[k95];
    // Flagged leaves, keyed by (polygon << 32 | index).
    std::vector<std::uint64_t> flagged;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        const std::uint32_t level = std::uint32_t(h.depth(p));
        const std::uint32_t count = 1u << (2 * level);
        const double step = 1.0 / double(1u << level);
        for (std::uint32_t i = 0; i < count; ++i) {
            const double y = luminance(h.irradiance({p, level, i}));
            const PatchGeometry g = patch_geometry(poly, level, i);
            double u, v;
            if (!leaf_uv(poly, g, u, v)) continue;
            bool jump = false;
            const double du[4] = {step, -step, 0, 0}, dv[4] = {0, 0, step, -step};
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
            if (jump) flagged.push_back((std::uint64_t(p) << 32) | i);
        }
    }
    stats.leaves = flagged.size();
    if (flagged.empty() || image.empty()) return stats;

    GatherOptions go;
    go.threads = 1;     // this pass runs its own threads
    go.jitter = false;       // no noise from pixel to pixel
    go.coarse_test = false;  // no step where a coarse ray first meets an occluder
    const FinalGather gather(h, go);
    go.coarse_test = true; // leaf means: whole-emitter shortcut where all is visible
    const FinalGather mean_gather(h, go);
    // 2. Direct light at the centres of the flagged leaves and of their neighbours (the
    //    interpolation stencil of any point on a flagged leaf).
    std::unordered_map<std::uint64_t, dvec3> centre_direct;
    for (const std::uint64_t key : flagged) {
        const std::uint32_t p = std::uint32_t(key >> 32), i = std::uint32_t(key);
        const Polygon& poly = scene.polygons[p];
        const std::uint32_t level = std::uint32_t(h.depth(p));
        const double step = 1.0 / double(1u << level);
        double u, v;
        if (!leaf_uv(poly, patch_geometry(poly, level, i), u, v)) continue;
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const double nu = std::clamp(u + di * step, 0.0, 1.0);
                const double nv = std::clamp(v + dj * step, 0.0, 1.0);
                const std::uint32_t n = patch_at(poly, level, nu, nv);
                const std::uint64_t nk = (std::uint64_t(p) << 32) | n;
                if (centre_direct.count(nk)) continue;
                // The leaf's mean direct light (what its H holds): at the centres of its 4
                // children (16 grandchildren measured no better in the shadow-edge test).
                dvec3 sum(0.0);
                for (std::uint32_t c : patch_children(poly.is_triangle(), level, n)) {
                    const PatchGeometry g = patch_geometry(poly, level + 1, c);
                    sum += mean_gather.direct_at({g.centre, poly.normal, p}, nk);
                }
                centre_direct[nk] = sum / 4.0;
            }
    }
    const std::unordered_map<std::uint64_t, char> is_flagged = [&] {
        std::unordered_map<std::uint64_t, char> m;
        for (const std::uint64_t k : flagged) m[k] = 1;
        return m;
    }();

    // 3. Pixels: the camera ray of each pixel centre, as the GL projection of render(). On a
    //    flagged leaf the image gets the detail the leaves cannot hold: the direct light at
    //    the point less the same interpolation of the leaf-centre direct light that the
    //    image's smooth field is made of, times rho (irradiance: not times rho).
    const Bvh bvh(scene);
    const dvec3 forward = glm::normalize(camera.target - camera.eye);
    const dvec3 right = glm::normalize(glm::cross(forward, camera.up));
    const dvec3 up = glm::cross(right, forward);
    const double ty = std::tan(0.5 * glm::radians(camera.fov_y_deg));
    const double tx = ty * double(image.width) / double(image.height);
    const bool irradiance = o.quantity == RenderOptions::Quantity::Irradiance;
    std::atomic<int> next_row{0};
    std::atomic<std::size_t> pixels{0};
    const auto work = [&] {
        for (int y; (y = next_row.fetch_add(1)) < image.height;) {
            for (int x = 0; x < image.width; ++x) {
                const double sx = (2.0 * (x + 0.5) / image.width - 1.0) * tx;
                const double sy = (1.0 - 2.0 * (y + 0.5) / image.height) * ty;
                const dvec3 dir = forward + sx * right + sy * up;
                Hit hit;
                if (!bvh.intersect(camera.eye, dir, 1e300, hit) || !hit.front) continue;
                const std::uint32_t p = hit.polygon;
                const Polygon& poly = scene.polygons[p];
                const std::uint32_t level = std::uint32_t(h.depth(p));
                const std::uint32_t leaf = patch_at(poly, level, hit.u, hit.v);
                if (!is_flagged.count((std::uint64_t(p) << 32) | leaf)) continue;
                // D~: the leaves' mean direct light reconstructed as the renderer does (nodal
                // averages at the leaf's corners, linear over its two triangles c0 c1 c2 and
                // c0 c2 c3); triangles: the leaf's own value.
                bool complete = true;
                const auto mean_direct = [&](std::uint32_t n) {
                    const auto it = centre_direct.find((std::uint64_t(p) << 32) | n);
                    if (it != centre_direct.end()) return it->second;
                    complete = false;
                    return dvec3(0.0);
                };
                dvec3 smooth(0.0);
                if (poly.is_triangle()) {
                    smooth = mean_direct(leaf);
                } else {
                    const int n = 1 << level, lx = int(leaf) % n, ly = int(leaf) / n;
                    const auto node = [&](int i, int j) {
                        dvec3 sum(0.0);
                        int count = 0;
                        for (int b = j - 1; b <= j; ++b)
                            for (int a = i - 1; a <= i; ++a)
                                if (a >= 0 && b >= 0 && a < n && b < n)
                                    sum += mean_direct(std::uint32_t(b * n + a)), ++count;
                        return sum / double(count);
                    };
                    const double a = std::clamp(hit.u * n - lx, 0.0, 1.0);
                    const double b = std::clamp(hit.v * n - ly, 0.0, 1.0);
                    const dvec3 v00 = node(lx, ly), v10 = node(lx + 1, ly),
                                v11 = node(lx + 1, ly + 1), v01 = node(lx, ly + 1);
                    smooth = a >= b ? v00 + a * (v10 - v00) + b * (v11 - v10)
                                    : v00 + a * (v11 - v01) + b * (v01 - v00);
                }
                if (!complete) continue;
                const dvec3 point = camera.eye + hit.t * dir;
                const std::uint64_t index =
                    (std::uint64_t(1) << 48) + std::uint64_t(y) * std::uint64_t(image.width) + x;
                const dvec3 detail = gather.direct_at({point, poly.normal, p}, index) - smooth;
                const Material& m = scene.material_of(poly);
                const dvec3 floor_value = irradiance ? dvec3(0.0) : m.exitance();
                float* px = image.at(x, y);
                for (int c = 0; c < 3; ++c) {
                    const double add = irradiance ? detail[c] : m.rho[c] * detail[c];
                    px[c] = float(std::max(double(px[c]) + add, floor_value[c]));
                }
                pixels.fetch_add(1);
            }
        }
    };
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    stats.pixels = pixels.load();
    stats.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

} // namespace hemirad
