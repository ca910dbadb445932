// Points spread over a scene's surfaces for accuracy studies (report.h, surface_points).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/sampling.h"
#include "hemirad/report.h"

namespace hemirad {

std::vector<Probe> surface_points(const Scene& scene, std::size_t count, std::uint64_t seed,
                                  int min_per_polygon) {
    std::vector<Probe> out;
    const double total = scene.total_area();
    if (!(total > 0)) return out;
    constexpr double kInset =
        1e-3; // keep points off the edges, where a polygon's side is ambiguous
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& poly = scene.polygons[p];
        const long share =
            std::max<long>(min_per_polygon, std::lround(double(count) * poly.area / total));
        const int m = std::max(1, int(std::ceil(std::sqrt(double(share)))));
        Rng rng(splitmix64(seed ^ splitmix64(p)));
        // Jittered m x m strata, `share` of them taken in a fixed scrambled order.
        std::vector<int> strata(std::size_t(m) * m);
        for (std::size_t k = 0; k < strata.size(); ++k) strata[k] = int(k);
        for (std::size_t k = strata.size(); k > 1; --k)
            std::swap(strata[k - 1], strata[std::size_t(rng.next() % k)]);
        for (long k = 0; k < share; ++k) {
            const int cell = strata[std::size_t(k) % strata.size()];
            double u = (cell % m + rng.uniform()) / m, v = (cell / m + rng.uniform()) / m;
            if (poly.is_triangle() && u + v > 1) u = 1 - u, v = 1 - v;
            u = std::clamp(u, kInset, 1 - kInset);
            v = std::clamp(v, kInset, 1 - kInset);
            if (poly.is_triangle() && u + v > 1 - kInset) {
                const double s = (1 - kInset) / (u + v);
                u *= s, v *= s;
            }
            out.push_back({polygon_point(poly, u, v), poly.normal});
        }
    }
    return out;
}

std::vector<Probe> random_surface_points(const Scene& scene, std::size_t count,
                                         std::uint64_t seed) {
    std::vector<double> cdf;
    cdf.reserve(scene.polygons.size());
    double total = 0;
    for (const Polygon& poly : scene.polygons) cdf.push_back(total += poly.area);
    std::vector<Probe> out;
    if (!(total > 0)) return out;
    Rng rng(splitmix64(seed));
    for (std::size_t k = 0; k < count; ++k) {
        const double x = rng.uniform() * total;
        const std::size_t p = std::min<std::size_t>(
            std::size_t(std::upper_bound(cdf.begin(), cdf.end(), x) - cdf.begin()), cdf.size() - 1);
        const Polygon& poly = scene.polygons[p];
        const double pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        out.push_back({area_point(poly.v.data(), poly.count, pick, u1, u2), poly.normal});
    }
    return out;
}

std::string probe_points_csv(const std::vector<Probe>& probes) {
    std::ostringstream s;
    s.precision(12);
    s << "x,y,z,nx,ny,nz\n";
    for (const Probe& p : probes)
        s << p.position.x << "," << p.position.y << "," << p.position.z << "," << p.normal.x << ","
          << p.normal.y << "," << p.normal.z << "\n";
    return s.str();
}

} // namespace hemirad
