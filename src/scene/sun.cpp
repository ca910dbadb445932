// The sun's conventions and position (sun.h).
#include "hemirad/sun.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hemirad/error.h"
#include "hemirad/photometry.h"

namespace hemirad {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

bool leap(int year) {
    return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

} // namespace

double Sun::normal_irradiance() const {
    return altitude_deg > 0 ? illuminance / kLumensPerWatt : 0.0;
}

double Sun::irradiance(const glm::dvec3& n) const {
    return normal_irradiance() * std::max(0.0, glm::dot(n, direction));
}

glm::dvec3 SkyFrame::east() const {
    return glm::cross(north, up);
}

glm::dvec3 SkyFrame::direction(double altitude_deg, double azimuth_deg) const {
    const double alt = altitude_deg * kDeg, az = azimuth_deg * kDeg;
    return std::cos(alt) * (std::cos(az) * north + std::sin(az) * east()) + std::sin(alt) * up;
}

void SkyFrame::angles(const glm::dvec3& d, double& altitude_deg, double& azimuth_deg) const {
    altitude_deg = std::asin(std::clamp(glm::dot(d, up), -1.0, 1.0)) / kDeg;
    const double x = glm::dot(d, north), y = glm::dot(d, east());
    azimuth_deg = x == 0 && y == 0 ? 0.0 : std::atan2(y, x) / kDeg;
    if (azimuth_deg < 0) azimuth_deg += 360;
}

SolarPosition solar_position(double latitude_deg, double longitude_deg, int year, int month,
                             int day, double hours_local, double utc_offset_hours) {
    static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (year < 1 || year > 9999)
        throw InputError("year " + std::to_string(year) + " must be in 1..9999");
    if (month < 1 || month > 12)
        throw InputError("month " + std::to_string(month) + " must be in 1..12");
    const int days_in_month = kDays[month - 1] + (month == 2 && leap(year) ? 1 : 0);
    if (day < 1 || day > days_in_month)
        throw InputError("day " + std::to_string(day) + " must be in 1.." +
                         std::to_string(days_in_month));
    if (!(hours_local >= 0 && hours_local <= 24))
        throw InputError("time " + num(hours_local) + " h must be in 0..24");
    // NOAA Solar Calculator (after Meeus, Astronomical Algorithms, ch. 25, low accuracy):
    // the Julian day and centuries since J2000.0 of the instant (UTC) ...
    const double hours_utc = hours_local - utc_offset_hours;
    const int Y = month <= 2 ? year - 1 : year, M = month <= 2 ? month + 12 : month;
    const int A = Y / 100, B = 2 - A + A / 4;
    const double jd = std::floor(365.25 * (Y + 4716)) + std::floor(30.6001 * (M + 1)) + day + B -
                      1524.5 + hours_utc / 24;
    const double T = (jd - 2451545.0) / 36525.0;
    // ... the sun's geometric mean longitude and anomaly [deg], the orbit's eccentricity ...
    const double L0 = std::fmod(280.46646 + T * (36000.76983 + T * 0.0003032), 360.0);
    const double Ma = 357.52911 + T * (35999.05029 - 0.0001537 * T);
    const double e = 0.016708634 - T * (0.000042037 + 0.0000001267 * T);
    // ... its equation of centre, apparent longitude and the obliquity of the ecliptic ...
    const double C = std::sin(Ma * kDeg) * (1.914602 - T * (0.004817 + 0.000014 * T)) +
                     std::sin(2 * Ma * kDeg) * (0.019993 - 0.000101 * T) +
                     std::sin(3 * Ma * kDeg) * 0.000289;
    const double omega = (125.04 - 1934.136 * T) * kDeg;
    const double lambda = (L0 + C - 0.00569 - 0.00478 * std::sin(omega)) * kDeg;
    const double eps0 =
        23 + (26 + (21.448 - T * (46.815 + T * (0.00059 - T * 0.001813))) / 60) / 60;
    const double eps = (eps0 + 0.00256 * std::cos(omega)) * kDeg;
    // ... the declination [rad] and the equation of time [minutes].
    const double decl = std::asin(std::sin(eps) * std::sin(lambda));
    const double y = std::pow(std::tan(eps / 2), 2);
    const double l = L0 * kDeg, m = Ma * kDeg;
    const double eqtime =
        4 / kDeg *
        (y * std::sin(2 * l) - 2 * e * std::sin(m) + 4 * e * y * std::sin(m) * std::cos(2 * l) -
         0.5 * y * y * std::sin(4 * l) - 1.25 * e * e * std::sin(2 * m));
    // True solar time [minutes] and the hour angle [rad], 0 at solar noon, negative mornings.
    const double tst = hours_utc * 60 + eqtime + 4 * longitude_deg;
    const double ha = (tst / 4 - 180) * kDeg;
    const double lat = latitude_deg * kDeg;
    const double sin_alt =
        std::sin(lat) * std::sin(decl) + std::cos(lat) * std::cos(decl) * std::cos(ha);
    SolarPosition p;
    p.altitude_deg = std::asin(std::clamp(sin_alt, -1.0, 1.0)) / kDeg;
    // Azimuth from south towards west, atan2(sin H, cos H sin lat - tan decl cos lat), + 180.
    const double from_south =
        std::atan2(std::sin(ha), std::cos(ha) * std::sin(lat) - std::tan(decl) * std::cos(lat));
    p.azimuth_deg = std::fmod(from_south / kDeg + 180 + 360, 360.0);
    return p;
}

} // namespace hemirad
