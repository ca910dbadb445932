// Type C intensity distributions and point-source luminaires (photometry.h).
#include "hemirad/photometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hemirad/error.h"

namespace hemirad {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// The interval [a[k], a[k+1]] holding x (clamped to the table) and the weight of a[k+1].
void bracket(const std::vector<double>& a, double x, std::size_t& k, double& t) {
    if (a.size() < 2 || x <= a.front()) {
        k = 0;
        t = 0;
        return;
    }
    if (x >= a.back()) {
        k = a.size() - 2;
        t = 1;
        return;
    }
    k = std::size_t(std::upper_bound(a.begin(), a.end(), x) - a.begin()) - 1;
    t = (x - a[k]) / (a[k + 1] - a[k]);
}

// Maps a horizontal angle in [0, 360) into the range the table covers.
double fold(HorizontalSymmetry s, double c) {
    switch (s) {
    case HorizontalSymmetry::Axial:
        return 0;
    case HorizontalSymmetry::Quadrant:
        if (c > 180) c = 360 - c;
        return c > 90 ? 180 - c : c;
    case HorizontalSymmetry::Bilateral:
        return c > 180 ? 360 - c : c;
    case HorizontalSymmetry::Bilateral90:
        // Mirror about the 90-270 plane: C -> 180 - C (mod 360).
        if (c < 90) return 180 - c;
        if (c > 270) return 540 - c;
        return c;
    case HorizontalSymmetry::None:
        return c;
    }
    return c;
}

// Integral over [a, b] (radians) of f(g) sin(g) dg for f linear from fa to fb:
//   fa (cos a - cos b) + (fb - fa)/(b - a) (sin b - sin a - (b - a) cos b).
double linear_sin_integral(double a, double b, double fa, double fb) {
    const double h = b - a;
    if (!(h > 0)) return 0;
    return fa * (std::cos(a) - std::cos(b)) +
           (fb - fa) / h * (std::sin(b) - std::sin(a) - h * std::cos(b));
}

} // namespace

const char* to_string(HorizontalSymmetry s) {
    switch (s) {
    case HorizontalSymmetry::Axial:
        return "axial (0)";
    case HorizontalSymmetry::Quadrant:
        return "quadrant (0-90)";
    case HorizontalSymmetry::Bilateral:
        return "bilateral (0-180)";
    case HorizontalSymmetry::Bilateral90:
        return "bilateral (90-270)";
    case HorizontalSymmetry::None:
        return "none (0-360)";
    }
    return "?";
}

double CandelaDistribution::intensity(double gamma_deg, double c_deg) const {
    const std::size_t ng = gamma.size();
    if (ng == 0 || c.empty()) return 0;
    if (gamma_deg < gamma.front() || gamma_deg > gamma.back()) return 0;
    std::size_t j;
    double tg;
    bracket(gamma, gamma_deg, j, tg);
    const auto row = [&](std::size_t i) {
        const double* r = &candela[i * ng];
        return ng == 1 ? r[0] : (1 - tg) * r[j] + tg * r[j + 1];
    };
    if (c.size() == 1 || symmetry == HorizontalSymmetry::Axial) return row(0);
    double cc = std::fmod(c_deg, 360.0);
    if (cc < 0) cc += 360;
    cc = fold(symmetry, cc);
    std::size_t i;
    double tc;
    bracket(c, cc, i, tc);
    return (1 - tc) * row(i) + tc * row(i + 1);
}

double CandelaDistribution::lumens() const {
    const std::size_t ng = gamma.size();
    if (ng < 2 || c.empty()) return 0;
    // Per C plane, the integral over gamma of I sin(gamma) (piecewise linear I: exact).
    std::vector<double> g(c.size(), 0.0);
    for (std::size_t i = 0; i < c.size(); ++i)
        for (std::size_t j = 0; j + 1 < ng; ++j)
            g[i] += linear_sin_integral(gamma[j] * kDeg, gamma[j + 1] * kDeg, candela[i * ng + j],
                                        candela[i * ng + j + 1]);
    if (c.size() == 1 || symmetry == HorizontalSymmetry::Axial) return 2 * kPi * g[0];
    // Linear in C between planes: the trapezoid rule is exact; the table covers 1/copies of
    // the circle.
    double sum = 0;
    for (std::size_t i = 0; i + 1 < c.size(); ++i)
        sum += 0.5 * (c[i + 1] - c[i]) * kDeg * (g[i] + g[i + 1]);
    double copies = 1;
    switch (symmetry) {
    case HorizontalSymmetry::Quadrant:
        copies = 4;
        break;
    case HorizontalSymmetry::Bilateral:
    case HorizontalSymmetry::Bilateral90:
        copies = 2;
        break;
    default:
        break;
    }
    return copies * sum;
}

double CandelaDistribution::max_candela() const {
    double m = 0;
    for (double v : candela) m = std::max(m, v);
    return m;
}

CandelaDistribution isotropic_distribution(double candela) {
    CandelaDistribution d;
    d.gamma = {0.0, 180.0};
    d.c = {0.0};
    d.candela = {candela, candela};
    return d;
}

CandelaDistribution spot_distribution(double candela, double cone, double falloff) {
    if (!(cone > 0 && cone <= 180))
        throw InputError("spot cone " + num(cone) + " must be in (0, 180] degrees");
    if (!(falloff >= 0 && cone + falloff <= 180))
        throw InputError("spot falloff " + num(falloff) +
                         " must be >= 0 with cone + falloff <= "
                         "180 degrees");
    if (cone >= 180) return isotropic_distribution(candela);
    CandelaDistribution d;
    d.c = {0.0};
    // A falloff of 0 is a hard edge: a jump over a millionth of a degree.
    const double edge = cone + std::max(falloff, 1e-6);
    if (edge >= 180) {
        d.gamma = {0.0, cone, 180.0};
        d.candela = {candela, candela, 0.0};
    } else {
        d.gamma = {0.0, cone, edge, 180.0};
        d.candela = {candela, candela, 0.0, 0.0};
    }
    return d;
}

CandelaDistribution gltf_spot_distribution(double candela, double inner, double outer) {
    if (!(inner >= 0 && inner <= outer && outer > 0 && outer <= 180))
        throw InputError("spot cone angles inner " + num(inner) + ", outer " + num(outer) +
                         " must satisfy 0 <= inner <= outer <= 180 degrees, outer > 0");
    if (outer - inner < 1e-6) return spot_distribution(candela, outer, 0);
    // KHR_lights_punctual's angular attenuation: t^2, t linear in cos(gamma) from 1 at the inner
    // cone to 0 at the outer; 32 steps across the band.
    constexpr int kSteps = 32;
    CandelaDistribution d;
    d.c = {0.0};
    const double ci = std::cos(inner * kDeg), co = std::cos(outer * kDeg);
    if (inner > 0) d.gamma.push_back(0), d.candela.push_back(candela);
    for (int k = 0; k <= kSteps; ++k) {
        const double g = inner + (outer - inner) * k / kSteps;
        const double t = std::clamp((std::cos(g * kDeg) - co) / (ci - co), 0.0, 1.0);
        d.gamma.push_back(g);
        d.candela.push_back(candela * t * t);
    }
    if (outer < 180) d.gamma.push_back(180), d.candela.push_back(0);
    return d;
}

void Luminaire::orient() {
    const double len = glm::length(aim);
    if (!(len > 0) || !std::isfinite(len))
        throw InputError("luminaire " + name + ": aim must be a non-zero direction");
    aim /= len;
    const glm::dvec3 ref =
        std::abs(aim.x) > std::cos(25 * kDeg) ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    glm::dvec3 x = ref - glm::dot(ref, aim) * aim;
    x = glm::normalize(x);
    const glm::dvec3 y = glm::cross(x, aim);
    const double r = rotation * kDeg;
    c0 = std::cos(r) * x + std::sin(r) * y;
    c90 = glm::cross(c0, aim);
}

double Luminaire::intensity(const glm::dvec3& d) const {
    const double along = std::clamp(glm::dot(d, aim), -1.0, 1.0);
    const double gamma = std::acos(along) / kDeg;
    double c = std::atan2(glm::dot(d, c90), glm::dot(d, c0)) / kDeg;
    if (c < 0) c += 360;
    return multiplier * distribution.intensity(gamma, c);
}

double Luminaire::irradiance_from(const glm::dvec3& y, const glm::dvec3& x,
                                  const glm::dvec3& n) const {
    const glm::dvec3 d = x - y;
    const double r2 = glm::dot(d, d);
    if (!(r2 > 0)) return 0;
    const glm::dvec3 w = d / std::sqrt(r2);
    const double cos_theta = -glm::dot(n, w);
    if (!(cos_theta > 0)) return 0;
    return intensity(w) * cos_theta / (kLumensPerWatt * r2);
}

} // namespace hemirad
