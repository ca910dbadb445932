// The sun as a parallel light source (SCENE.json "sun"): a direction towards the sun and its
// normal illuminance E_n [lux]. The 0.533 degree disc is taken as a point in the sky (a
// parallel source), which indoors moves a shadow's edge by at most 0.0047 x its distance from
// the occluder. Conventions (docs/design.md): 1 lux = 1/683 W m^-2 in each RGB channel
// (photometry.h), so the sun's irradiance on a surface with unit normal n is
// E_n/683 * max(0, n.s) where it is not in shadow.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "hemirad/visibility.h"

namespace hemirad {

struct HEMIRAD_API Sun {
    glm::dvec3 direction{0.0, 1.0, 0.0}; ///< unit vector from the scene towards the sun, s
    double illuminance = 0;              ///< E_n: normal illuminance [lux], >= 0
    double altitude_deg = 90;            ///< above the horizon [degrees], in [-90, 90]
    double azimuth_deg = 0;              ///< from north, clockwise seen from above [degrees]
    /// Normal irradiance E_n/683 per RGB channel [W m^-2]; 0 for a sun below the horizon.
    double normal_irradiance() const;
    /// The unshadowed irradiance on a surface with unit normal n: normal_irradiance() *
    /// max(0, n.s) [W m^-2].
    double irradiance(const glm::dvec3& n) const;
};

/// The scene's frame for directions in the sky: `up` (the zenith) and `north`, both unit, at
/// right angles (SCENE.json "up", "north"; defaults +y and -z, so that east is +x).
struct HEMIRAD_API SkyFrame {
    glm::dvec3 up{0.0, 1.0, 0.0};
    glm::dvec3 north{0.0, 0.0, -1.0};
    /// east = north x up: +x for the defaults (azimuth 90 degrees).
    glm::dvec3 east() const;
    /// The unit direction of altitude, azimuth [degrees]:
    /// cos(alt) (cos(az) north + sin(az) east) + sin(alt) up.
    glm::dvec3 direction(double altitude_deg, double azimuth_deg) const;
    /// The inverse: altitude and azimuth [degrees] of a unit direction (azimuth in [0, 360);
    /// 0 at the zenith and nadir).
    void angles(const glm::dvec3& direction, double& altitude_deg, double& azimuth_deg) const;
};

/// Where the sun stands: altitude and azimuth [degrees] (azimuth from north, clockwise).
struct SolarPosition {
    double altitude_deg = 0;
    double azimuth_deg = 0;
};

/// The sun's position seen from latitude, longitude [degrees, north and east positive] at local
/// clock time on a Gregorian date, the clock utc_offset hours ahead of UTC (e.g. +1 for CET).
/// NOAA's Solar Calculator algorithm (Meeus, Astronomical Algorithms, ch. 25, low accuracy:
/// the declination and the equation of time from the sun's apparent longitude), about 0.01
/// degrees from 1900 to 2100; no refraction.
/// Throws InputError for a date or time out of range (year 1..9999, month 1..12, day 1..31,
/// hour 0..24).
HEMIRAD_API SolarPosition solar_position(double latitude_deg, double longitude_deg, int year,
                                         int month, int day, double hours_local,
                                         double utc_offset_hours);

} // namespace hemirad
