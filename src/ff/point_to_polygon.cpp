// Analytic form factor from a differential area to a polygon (Lambert/Nusselt contour
// integral; docs/design.md, "The method", step 3; paper 002's fragment program, here in
// double precision for the CPU reference path).
#include "hemirad/form_factors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "hemirad/error.h"

namespace hemirad {

namespace {

// Sutherland-Hodgman against the half-space d(x) = n.(x-p) >= 0. Writes the clipped polygon
// (at most count+1 corners) into `out` and returns its corner count. Signed distances within
// `eps` of 0 are taken as exactly 0 (the corner lies on the plane and is kept as it is), so
// no sliver corners are made next to it.
int clip_to_half_space(const dvec3& p, const dvec3& n, const dvec3* in, int count, double eps,
                       dvec3* out) {
    int m = 0;
    for (int k = 0; k < count; ++k) {
        const dvec3& a = in[k];
        const dvec3& b = in[(k + 1) % count];
        double da = glm::dot(n, a - p), db = glm::dot(n, b - p);
        if (std::abs(da) <= eps) da = 0;
        if (std::abs(db) <= eps) db = 0;
        if (da >= 0) out[m++] = a;
        if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
            const double t = da / (da - db); // in (0,1)
            out[m++] = a + t * (b - a);
        }
    }
    return m;
}

// F = (1/2pi) |sum_k gamma_k n.(R_k x R_k+1)/|R_k x R_k+1||, gamma_k = angle(R_k, R_k+1)
// taken as atan2(|R_k x R_k+1|, R_k.R_k+1), accurate for small angles where acos is not.
double contour_integral(const dvec3& p, const dvec3& n, const dvec3* c, int m, double scale) {
    if (m < 3) return 0.0;
    // A polygon whose plane contains p is seen edge-on: zero solid angle (this also covers p
    // on the polygon, on its edge, and a polygon lying in the receiver's tangent plane).
    dvec3 normal(0.0); // Newell: length = 2 * area
    for (int k = 1; k + 1 < m; ++k) normal += glm::cross(c[k] - c[0], c[k + 1] - c[0]);
    const double twice_area = glm::length(normal);
    if (!(twice_area > 1e-24 * scale * scale)) return 0.0;
    if (std::abs(glm::dot(normal / twice_area, c[0] - p)) <= 1e-12 * scale) return 0.0;
    double sum = 0.0;
    for (int k = 0; k < m; ++k) {
        const dvec3 a = c[k] - p, b = c[(k + 1) % m] - p;
        const dvec3 axb = glm::cross(a, b);
        const double s = glm::length(axb);
        if (!(s > 0)) continue; // zero-length edge or R_k parallel to R_k+1: no contribution
        sum += std::atan2(s, glm::dot(a, b)) * glm::dot(n, axb) / s;
    }
    return std::clamp(std::abs(sum) / (2.0 * std::numbers::pi), 0.0, 1.0);
}

} // namespace

double point_to_polygon_ff(const dvec3& p, const dvec3& n, const dvec3* corners, int count) {
    HEMIRAD_CHECK(count >= 3);
    double scale = 0;
    for (int k = 0; k < count; ++k) scale = std::max(scale, glm::length(corners[k] - p));
    if (!(scale > 0)) return 0.0;
    const double eps = 1e-12 * scale; // plane tolerance for corners [scene units]
    constexpr int kStack = 16;
    if (count < kStack) {
        std::array<dvec3, kStack> clipped;
        const int m = clip_to_half_space(p, n, corners, count, eps, clipped.data());
        return contour_integral(p, n, clipped.data(), m, scale);
    }
    std::vector<dvec3> clipped(std::size_t(count) + 1);
    const int m = clip_to_half_space(p, n, corners, count, eps, clipped.data());
    return contour_integral(p, n, clipped.data(), m, scale);
}

} // namespace hemirad

namespace hemirad {

double ClusterShooter::intensity(const dvec3& d) const {
    double i = 0;
    for (std::size_t k = 0; k < normals.size(); ++k)
        i += weights[k] * std::max(0.0, glm::dot(normals[k], d));
    return i / std::numbers::pi;
}

double ClusterShooter::share_in_front(const dvec3& x, const dvec3& n, double eps) const {
    if (planes.empty()) return 1.0;
    const dvec3 d = x - centre;
    const double len = glm::length(d);
    if (!(len > 0)) return 0.0;
    double all = 0, front = 0;
    for (std::size_t k = 0; k < normals.size(); ++k)
        all += weights[k] * std::max(0.0, glm::dot(normals[k], d) / len);
    const double receiver_plane = glm::dot(n, x);
    for (const Plane& p : planes) {
        const dvec3& normal = normals[p.lobe];
        if (!(glm::dot(normal, x) > p.offset + eps)) continue;
        // The box's farthest corner along n (the box may be empty: lo > hi).
        const dvec3 far = glm::max(n * p.lo, n * p.hi);
        if (!(far.x + far.y + far.z > receiver_plane + eps)) continue;
        front += p.weight * std::max(0.0, glm::dot(normal, d) / len);
    }
    return all > 0 ? std::min(front / all, 1.0) : 0.0;
}

void ClusterShooter::add_lobe_planes(std::uint32_t lobe, std::vector<Plane> polygons, double gap,
                                     std::size_t max_planes) {
    if (polygons.empty()) return;
    const auto absorb = [](Plane& into, const Plane& p) {
        into.weight += p.weight;
        into.lo = glm::min(into.lo, p.lo);
        into.hi = glm::max(into.hi, p.hi);
    };
    std::sort(polygons.begin(), polygons.end(),
              [](const Plane& a, const Plane& b) { return a.offset < b.offset; });
    // Runs of offsets, each within `gap` of the one before: the plane at a run's lowest
    // offset, `high` its highest.
    std::vector<Plane> runs;
    std::vector<double> high;
    for (const Plane& p : polygons) {
        if (runs.empty() || p.offset - high.back() > gap) {
            runs.push_back(p);
            runs.back().lobe = lobe;
            high.push_back(p.offset);
            continue;
        }
        absorb(runs.back(), p);
        high.back() = p.offset;
    }
    while (runs.size() > std::max<std::size_t>(max_planes, 1)) {
        std::size_t best = 1;
        for (std::size_t k = 2; k < runs.size(); ++k)
            if (runs[k].offset - high[k - 1] < runs[best].offset - high[best - 1]) best = k;
        absorb(runs[best - 1], runs[best]);
        high[best - 1] = high[best];
        runs.erase(runs.begin() + std::ptrdiff_t(best));
        high.erase(high.begin() + std::ptrdiff_t(best));
    }
    planes.insert(planes.end(), runs.begin(), runs.end());
}

double ClusterShooter::back_share() const {
    // A cosine lobe about n puts the share (1 - n.a)/2 of its power... exactly: the power of
    // max(0, n.d)/pi over the half space d.a < 0 is (1 - n.a)/2 (the projected solid angle
    // of the part of n's hemisphere below the plane of a, over pi).
    double s = 0;
    for (std::size_t k = 0; k < normals.size(); ++k)
        s += weights[k] * 0.5 * (1.0 - glm::dot(normals[k], axis));
    return std::clamp(s, 0.0, 1.0);
}

} // namespace hemirad
