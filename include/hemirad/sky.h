// The sky as a distant luminous hemisphere (SCENE.json "sky"), and the ground below the horizon.
//
// A direction w seen from the scene has zenith angle Z (cos Z = w.up) and angle chi from the
// sun (cos chi = w.s). Above the horizon the sky's luminance is L(w) = k * shape(w) [cd m^-2],
// the shape one of
//   cie-overcast      the CIE standard overcast sky (Moon & Spencer 1942; CIE S 011, ISO
//                     15469): (1 + 2 cos Z) / 3; as in Radiance gensky -c
//   cie-clear         CIE S 011 general sky type 12 (CIE standard clear sky, low turbidity):
//                     phi(Z) f(chi) with a = -1, b = -0.32, c = 10, d = -3, e = 0.45
//   cie-intermediate  CIE S 011 general sky type 7 (partly cloudy, no gradation towards the
//                     zenith, brighter circumsolar region): a = 0, b = -1, c = 5, d = -2.5,
//                     e = 0.30 (not Radiance's gensky -i formula)
//   uniform           1
// with the gradation phi(Z) = 1 + a exp(b / cos Z) (1 at the horizon) and the indicatrix
// f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi, chi in radians (CIE S 011, eqs. 1-3).
// k makes the unobstructed horizontal illuminance of the sky alone E_h = integral over the
// upper hemisphere of L cos Z dw equal `illuminance` (analytically 7 pi/9 Lz for overcast,
// pi Lz for uniform; numerically for the others).
//
// Below the horizon rays see a uniform diffuse ground: L_g = rho_g (E_h + E_n sin(alt)) / pi,
// the sun's term only when there is a sun above the horizon (as gensky's -g).
//
// Horizon blend (default, "horizon_blend": true): as Radiance's skybright.cal, which gensky's
// skies use, sky and ground meet smoothly: L = (a L_sky + L_g / a) / (a + 1 / a) with
// a = (cos Z + 1.01)^10, on both sides of the horizon: at the horizon the sky is 0.55 of the
// model's luminance (with a black ground), 0.87 at 5 degrees, 0.97 at 10, and the ground just
// below it takes the sky's share. Without it ("horizon_blend": false) the models are the CIE
// distributions as written, up to a sharp horizon. Either way k normalises the sky's
// horizontal illuminance to E_h (the blend alone would lower it by 0.23 % under an overcast
// sky and a black ground; gensky keeps the unblended normalisation).
//
// Conventions as for the sun (sun.h): 1 lux = 1/683 W m^-2 per RGB channel, so the radiance is
// L / 683 [W sr^-1 m^-2] in each channel.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "hemirad/sun.h"
#include "hemirad/visibility.h"

namespace hemirad {

enum class SkyModel { CieOvercast, CieClear, CieIntermediate, Uniform };

/// "cie-overcast", "cie-clear", "cie-intermediate", "uniform".
HEMIRAD_API const char* sky_model_name(SkyModel m);
/// The inverse of sky_model_name(); false for an unknown name.
HEMIRAD_API bool parse_sky_model(const std::string& name, SkyModel& m);
/// Does the model's luminance depend on where the sun is (clear, intermediate)?
HEMIRAD_API bool sky_needs_sun(SkyModel m);

struct HEMIRAD_API Sky {
    SkyModel model = SkyModel::CieOvercast;
    double illuminance = 0;        ///< E_h: unobstructed horizontal illuminance [lux], >= 0
    double ground_reflectance = 0; ///< rho_g in [0, 1] (0: a black ground)
    glm::dvec3 up{0.0, 1.0, 0.0};  ///< the zenith, unit
    glm::dvec3 sun{0.0, 1.0, 0.0}; ///< unit direction towards the sun (clear, intermediate)
    /// The sun's horizontal illuminance E_n sin(alt) [lux] for the ground (0: none).
    double sun_horizontal = 0;
    double scale = 0;          ///< k [cd m^-2]: set by normalise()
    bool horizon_blend = true; ///< sky and ground blended near the horizon (as Radiance)

    /// The model's relative luminance shape(w) above the horizon (w unit, w.up > 0).
    double shape(const glm::dvec3& w) const;
    /// Sets `scale` so that the horizontal illuminance of the sky is `illuminance`.
    void normalise();
    /// The luminance L(w) [cd m^-2] of the sky (w.up > 0) or the ground (w.up <= 0); w unit.
    double luminance(const glm::dvec3& w) const;
    /// The ground's luminance rho_g (E_h + E_sun,h) / pi [cd m^-2].
    double ground_luminance() const;
    /// luminance(w) / 683: the radiance per RGB channel [W sr^-1 m^-2].
    double radiance(const glm::dvec3& w) const;
};

/// A sky of `model` with horizontal illuminance E_h [lux], normalised; the sun (may be absent
/// for overcast and uniform skies) gives its position and the ground's sun term.
/// Throws InputError when the model needs the sun's position and there is none.
HEMIRAD_API Sky make_sky(SkyModel model, double illuminance, double ground_reflectance,
                         const glm::dvec3& up, const std::optional<Sun>& sun,
                         bool horizon_blend = true);

} // namespace hemirad
