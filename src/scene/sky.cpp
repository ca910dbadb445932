// The sky's luminance distributions (sky.h).
#include "hemirad/sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hemirad/error.h"
#include "hemirad/photometry.h"

namespace hemirad {

namespace {

constexpr double kPi = std::numbers::pi;

/// CIE S 011 gradation and indicatrix parameters of one general sky type.
struct CieParameters {
    double a, b, c, d, e;
};
constexpr CieParameters kType12{-1.0, -0.32, 10.0, -3.0, 0.45}; ///< CIE standard clear sky
constexpr CieParameters kType7{0.0, -1.0, 5.0, -2.5, 0.30};     ///< partly cloudy (intermediate)

/// phi(Z) f(chi) (CIE S 011 eqs. 1-3), cos Z > 0; chi [rad] from the sun.
double cie_general(const CieParameters& p, double cos_z, double chi) {
    const double gradation = 1 + p.a * std::exp(p.b / cos_z);
    const double cos_chi = std::cos(chi);
    const double indicatrix =
        1 + p.c * (std::exp(p.d * chi) - std::exp(p.d * kPi / 2)) + p.e * cos_chi * cos_chi;
    return gradation * indicatrix;
}

/// Cells of the midpoint rule over the cosine-weighted unit square that normalise() uses:
/// E_h = pi * mean of L over (u1, u2) in [0, 1)^2 with w = (sqrt(u1) cos 2 pi u2,
/// sqrt(u1) sin 2 pi u2, sqrt(1 - u1)) (the map of core/sampling.h cosine_direction).
constexpr int kNormaliseU1 = 512, kNormaliseU2 = 1024;

/// The sky's weight in the horizon blend (sky.h; Radiance's skybright.cal): a / (a + 1/a) with
/// a = (cos Z + 1.01)^10; the ground has the rest.
double sky_weight(double cos_z) {
    const double a2 = std::pow(cos_z + 1.01, 20);
    return a2 / (a2 + 1);
}

} // namespace

const char* sky_model_name(SkyModel m) {
    switch (m) {
    case SkyModel::CieOvercast:
        return "cie-overcast";
    case SkyModel::CieClear:
        return "cie-clear";
    case SkyModel::CieIntermediate:
        return "cie-intermediate";
    case SkyModel::Uniform:
        return "uniform";
    }
    return "?";
}

bool parse_sky_model(const std::string& name, SkyModel& m) {
    for (SkyModel k :
         {SkyModel::CieOvercast, SkyModel::CieClear, SkyModel::CieIntermediate, SkyModel::Uniform})
        if (name == sky_model_name(k)) {
            m = k;
            return true;
        }
    return false;
}

bool sky_needs_sun(SkyModel m) {
    return m == SkyModel::CieClear || m == SkyModel::CieIntermediate;
}

double Sky::shape(const glm::dvec3& w) const {
    const double cos_z = glm::dot(w, up);
    switch (model) {
    case SkyModel::CieOvercast:
        return (1 + 2 * cos_z) / 3;
    case SkyModel::Uniform:
        return 1;
    case SkyModel::CieClear:
    case SkyModel::CieIntermediate: {
        const double chi = std::acos(std::clamp(glm::dot(w, sun), -1.0, 1.0));
        return cie_general(model == SkyModel::CieClear ? kType12 : kType7, std::max(cos_z, 1e-9),
                           chi);
    }
    }
    return 0;
}

void Sky::normalise() {
    double integral = 0;        // of shape cos Z over the hemisphere, up to the factor pi
    double ground_integral = 0; // of the ground's weight cos Z there (the blend), the same
    if (horizon_blend) {
        // Midpoint rule in the cosine-weighted square, as below.
        glm::dvec3 t = glm::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        t = glm::normalize(t - glm::dot(t, up) * up);
        const glm::dvec3 b = glm::cross(up, t);
        const bool symmetric = !sky_needs_sun(model); // no azimuth to integrate over
        const int n2 = symmetric ? 1 : kNormaliseU2;
        double sum = 0, ground = 0;
        for (int i = 0; i < kNormaliseU1; ++i) {
            const double u1 = (i + 0.5) / kNormaliseU1;
            const double r = std::sqrt(u1), z = std::sqrt(1 - u1);
            const double w = sky_weight(z);
            double row = 0;
            for (int j = 0; j < n2; ++j) {
                const double phi = 2 * kPi * (j + 0.5) / n2;
                row += shape(r * std::cos(phi) * t + r * std::sin(phi) * b + z * up);
            }
            sum += w * row / n2;
            ground += 1 - w;
        }
        integral = sum / kNormaliseU1;
        ground_integral = ground / kNormaliseU1;
        const double sky_part = illuminance / kPi - ground_luminance() * ground_integral;
        scale = illuminance > 0 && sky_part > 0 ? sky_part / integral : 0.0;
        return;
    }
    switch (model) {
    case SkyModel::CieOvercast:
        integral = 7.0 / 9.0;
        break; // 2 pi (1/2 + 2/3) / 3 = 7 pi/9
    case SkyModel::Uniform:
        integral = 1;
        break;
    default: {
        // Midpoint rule in the cosine-weighted square (kNormaliseU1 x kNormaliseU2 cells).
        glm::dvec3 t = glm::abs(up.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        t = glm::normalize(t - glm::dot(t, up) * up);
        const glm::dvec3 b = glm::cross(up, t);
        double sum = 0;
        for (int i = 0; i < kNormaliseU1; ++i) {
            const double u1 = (i + 0.5) / kNormaliseU1;
            const double r = std::sqrt(u1), z = std::sqrt(1 - u1);
            double row = 0;
            for (int j = 0; j < kNormaliseU2; ++j) {
                const double phi = 2 * kPi * (j + 0.5) / kNormaliseU2;
                row += shape(r * std::cos(phi) * t + r * std::sin(phi) * b + z * up);
            }
            sum += row;
        }
        integral = sum / (double(kNormaliseU1) * kNormaliseU2);
    }
    }
    scale = illuminance > 0 ? illuminance / (kPi * integral) : 0.0;
}

double Sky::ground_luminance() const {
    return ground_reflectance * (illuminance + sun_horizontal) / kPi;
}

double Sky::luminance(const glm::dvec3& w) const {
    const double cos_z = glm::dot(w, up);
    if (!horizon_blend) return cos_z > 0 ? scale * shape(w) : ground_luminance();
    const double sky_w = sky_weight(cos_z);
    return sky_w * scale * std::max(shape(w), 0.0) + (1 - sky_w) * ground_luminance();
}

double Sky::radiance(const glm::dvec3& w) const {
    return luminance(w) / kLumensPerWatt;
}

Sky make_sky(SkyModel model, double illuminance, double ground_reflectance, const glm::dvec3& up,
             const std::optional<Sun>& sun, bool horizon_blend) {
    Sky s;
    s.model = model;
    s.horizon_blend = horizon_blend;
    s.illuminance = illuminance;
    s.ground_reflectance = ground_reflectance;
    s.up = glm::normalize(up);
    if (sky_needs_sun(model) && !sun)
        throw InputError(std::string("the ") + sky_model_name(model) +
                         " sky needs the sun's position: add \"sun\"");
    if (sun) {
        s.sun = sun->direction;
        s.sun_horizontal = sun->normal_irradiance() * kLumensPerWatt *
                           std::max(0.0, glm::dot(sun->direction, s.up));
    }
    s.normalise();
    return s;
}

} // namespace hemirad
