// Photometry: luminous intensity distributions (type C), IES LM-63 photometric files, and
// point-source luminaires.
//
// Units. A luminaire's intensity I is in candela; hemirad's light is radiometric RGB, and one
// candela is taken as 1/683 W/sr in each of the three channels (equal RGB), so that the
// luminance-weighted irradiance times 683 lm/W (`--lux`, grid.h) is the illuminance in lux
// exactly: a point at distance r [m] whose normal makes an angle theta with the direction to
// the luminaire receives E_v = I(direction) cos(theta) / r^2 lux. Lux needs a scene in metres.
//
// Type C photometry (LM-63-2002 §3, "photometric web"): the polar axis is the luminaire's
// nadir, `aim`; the vertical angle gamma (0..180 degrees) is measured from the nadir, the
// horizontal angle C (0..360 degrees) counterclockwise seen from above (looking along the
// nadir) about it, C = 0 being the luminaire's length axis:
//
//     direction(gamma, C) = cos(gamma) aim + sin(gamma) (cos(C) c0 + sin(C) c90),
//     c90 = c0 x aim.
//
// Between the tabulated angles the intensity is interpolated bilinearly in (gamma, C); outside
// the vertical range of the table (a downlight's table ends at 90 degrees) it is 0.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "hemirad/visibility.h"

namespace hemirad {

/// Luminous efficacy that converts radiometric watts to lumens here [lm/W]: 1 cd = 1/683 W/sr.
inline constexpr double kLumensPerWatt = 683.0;

/// How the horizontal angles of a type C table cover the full circle (LM-63-2002 §5.13; the
/// last tabulated angle says which).
enum class HorizontalSymmetry {
    Axial,       ///< one plane, C = 0: the same in every plane
    Quadrant,    ///< C in 0..90: symmetric in each quadrant
    Bilateral,   ///< C in 0..180: symmetric about the 0-180 plane
    Bilateral90, ///< C in 90..270: symmetric about the 90-270 plane (LM-63-1995)
    None,        ///< C in 0..360: no symmetry
};
HEMIRAD_API const char* to_string(HorizontalSymmetry s);

/// A type C luminous intensity distribution I(gamma, C) [cd] tabulated on a grid of angles.
struct HEMIRAD_API CandelaDistribution {
    std::vector<double> gamma;   ///< vertical angles [deg], strictly increasing, in [0, 180]
    std::vector<double> c;       ///< horizontal angles [deg], strictly increasing (symmetry)
    std::vector<double> candela; ///< [cd], one row per C plane: candela[i * gamma.size() + j]
                                 ///< = I(gamma[j], c[i])
    HorizontalSymmetry symmetry = HorizontalSymmetry::Axial;

    /// Intensity [cd] at vertical angle gamma and horizontal angle C [deg] (any C: the table's
    /// symmetry maps it into the tabulated range), bilinear between the tabulated angles, 0
    /// outside the vertical range.
    double intensity(double gamma_deg, double c_deg) const;
    /// Total flux [lm]: the integral of the interpolated intensity over the sphere,
    /// sum over cells of the exact integral of the bilinear interpolant times sin(gamma).
    double lumens() const;
    double max_candela() const;
};

/// The same intensity `candela` in every direction (lumens = 4 pi candela).
HEMIRAD_API CandelaDistribution isotropic_distribution(double candela);
/// A spot: `candela` within `cone` degrees of the nadir, falling linearly in gamma to 0 at
/// cone + falloff degrees, 0 beyond. Requires cone in (0, 180], falloff >= 0, cone + falloff
/// <= 180 (InputError otherwise).
HEMIRAD_API CandelaDistribution spot_distribution(double candela, double cone_deg,
                                                  double falloff_deg);

/// An IES LM-63 photometric file (1986, 1991, 1995, 2002), type C, TILT=NONE.
struct HEMIRAD_API IesFile {
    std::string path;
    std::string format; ///< "LM-63-2002", "LM-63-1995", "LM-63-1991" or "LM-63-1986"
    std::vector<std::pair<std::string, std::string>> keywords; ///< [KEYWORD] value lines
    int lamps = 1;
    double lumens_per_lamp = -1; ///< rated lamp lumens; -1: absolute photometry
    double candela_multiplier = 1;
    int photometric_type = 1;                 ///< 1 = C (the only one read)
    int units = 2;                            ///< of the luminous opening: 1 feet, 2 metres
    double width = 0, length = 0, height = 0; ///< luminous opening (not used: a point source)
    double ballast_factor = 1;
    double ballast_lamp_factor = 1; ///< 1991/1995 only ("future use" in 2002, ignored)
    double input_watts = 0;
    /// The candela table with candela_multiplier * ballast_factor * ballast_lamp_factor
    /// applied.
    CandelaDistribution distribution;

    /// Rated lamp lumens, lamps * lumens_per_lamp (0 for absolute photometry).
    double rated_lumens() const { return lumens_per_lamp > 0 ? lamps * lumens_per_lamp : 0; }
    /// A keyword's value ("" if absent), e.g. keyword("LUMINAIRE").
    std::string keyword(const std::string& name) const;
};

/// Parses the text of an IES file; `path` names it in messages. Throws InputError naming the
/// file, the line and the value for: TILT other than NONE, photometric types A and B, counts,
/// angles or factors out of range, angles not increasing, a horizontal range that is none of
/// the symmetries, a missing or non-numeric value, values left over after the table.
HEMIRAD_API IesFile parse_ies(const std::string& text, const std::string& path);
/// Reads and parses an IES file. Throws InputError (also for a missing file).
HEMIRAD_API IesFile read_ies(const std::string& path);

/// A point-source luminaire placed in a scene (SCENE.json "luminaires", scene_json.h).
struct HEMIRAD_API Luminaire {
    std::string name;               ///< for reports ("L1", or the "name" given)
    std::string kind;               ///< "ies", "candela" or "spot"
    std::string file;               ///< the IES file as given (kind "ies"), else ""
    glm::dvec3 position{0.0};       ///< [scene units; metres for lux]
    glm::dvec3 aim{0.0, -1.0, 0.0}; ///< the photometric nadir (gamma = 0), unit (orient())
    double rotation = 0;   ///< turns the C planes about the aim, counterclockwise from above [deg]
    double multiplier = 1; ///< scales the intensity (and lumens), >= 0 (0 = off)
    double rated_lumens = 0; ///< lamp lumens of the IES file times multiplier (0: none stated)
    CandelaDistribution distribution; ///< [cd], multiplier not applied
    /// Derived by orient(): the C = 0 and C = 90 directions, unit, perpendicular to aim.
    glm::dvec3 c0{1.0, 0.0, 0.0}, c90{0.0, 0.0, -1.0};

    /// Normalises aim and sets c0, c90: C = 0 is the scene's +x axis projected onto the plane
    /// perpendicular to aim (+z when aim is within 25 degrees of the x axis), turned by
    /// `rotation`. Throws InputError for a zero or non-finite aim.
    void orient();
    /// Intensity [cd] towards the unit direction `d` (from the luminaire), multiplier applied.
    double intensity(const glm::dvec3& d) const;
    /// Total flux [lm], multiplier applied.
    double lumens() const { return multiplier * distribution.lumens(); }
    /// Radiometric power per RGB channel [W]: lumens / 683.
    double power() const { return lumens() / kLumensPerWatt; }
    /// Irradiance per RGB channel [W unit^-2] at point x with unit normal n, unoccluded:
    /// I(d) cos(theta) / (683 r^2); 0 behind the surface.
    double irradiance(const glm::dvec3& x, const glm::dvec3& n) const;
};

} // namespace hemirad
