// Photometry: luminous intensity distributions (type C), photometric files (IES LM-63 and
// EULUMDAT), and point-source luminaires.
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
/// A glTF KHR_lights_punctual spot: `candela` within `inner` degrees of the nadir, 0 beyond
/// `outer`, and between them the extension's angular attenuation t^2 with
/// t = (cos(gamma) - cos(outer)) / (cos(inner) - cos(outer)), tabulated every
/// (outer - inner)/32 (linear between: within 0.05 % of `candela` of it). inner == outer is a hard
/// edge. Requires 0 <= inner <= outer <= 180 and outer > 0 (InputError otherwise).
HEMIRAD_API CandelaDistribution gltf_spot_distribution(double candela, double inner_deg,
                                                       double outer_deg);

/// An IES LM-63 photometric file (1986, 1991, 1995, 2002, 2019), types C and B.
struct HEMIRAD_API IesFile {
    std::string path;
    /// "LM-63-2019", "LM-63-2002", "LM-63-1995", "LM-63-1991" or "LM-63-1986"
    std::string format;
    std::vector<std::pair<std::string, std::string>> keywords; ///< [KEYWORD] value lines
    int lamps = 1;
    double lumens_per_lamp = -1; ///< rated lamp lumens; -1: absolute photometry
    double candela_multiplier = 1;
    int photometric_type = 1; ///< 1 = C; 2 = B (converted to C: ies_reader.cpp)
    int units = 2;            ///< of the luminous opening: 1 feet, 2 metres
    /// The luminous opening in `units` (negative width: round, diameter |width|); the
    /// luminaire's LuminousOpening in metres (read_photometric_file).
    double width = 0, length = 0, height = 0;
    double ballast_factor = 1;
    double ballast_lamp_factor = 1; ///< 1991/1995 only ("future use" in 2002, ignored)
    double input_watts = 0;
    /// The candela table with candela_multiplier * ballast_factor * ballast_lamp_factor
    /// applied (type B: resampled as type C).
    CandelaDistribution distribution;
    /// What was read with a warning ("file:line: ..."): an unusual format line, tilt data
    /// ignored, type B converted.
    std::vector<std::string> warnings;

    /// Rated lamp lumens, lamps * lumens_per_lamp (0 for absolute photometry).
    double rated_lumens() const { return lumens_per_lamp > 0 ? lamps * lumens_per_lamp : 0; }
    /// A keyword's value ("" if absent), e.g. keyword("LUMINAIRE").
    std::string keyword(const std::string& name) const;
};

/// Parses the text of an IES file; `path` names it in messages. Throws InputError naming the
/// file, the line and the value for: photometric type A, counts, angles or factors out of
/// range, angles not increasing, a horizontal range that is none of the symmetries, a missing
/// or non-numeric value, values left over after the table. Warns (IesFile::warnings) for a
/// format line other than the standard ones, TILT=INCLUDE or a tilt file (not applied), type B
/// (converted).
HEMIRAD_API IesFile parse_ies(const std::string& text, const std::string& path);
/// Reads and parses an IES file. Throws InputError (also for a missing file).
HEMIRAD_API IesFile read_ies(const std::string& path);

/// One lamp set of a EULUMDAT file (lines 26a-26f).
struct HEMIRAD_API EulumdatLamps {
    int count = 0;           ///< number of lamps (negative in some files: its magnitude)
    std::string type;        ///< free text
    double total_lumens = 0; ///< total luminous flux of the set's lamps [lm]
    std::string colour;      ///< colour appearance / temperature, free text
    std::string rendering;   ///< colour rendering group / CRI, free text
    double watts = 0;        ///< wattage including ballast [W]
};

/// A EULUMDAT (.ldt) photometric file (Stockmar 1990; eulumdat_reader.cpp lists the lines).
struct HEMIRAD_API EulumdatFile {
    std::string path;
    std::string company; ///< line 1
    int type = 1;        ///< Ityp, line 2: 0..3
    int symmetry = 0;    ///< Isym, line 3: 0 none, 1 axial, 2 C0-C180, 3 C90-C270, 4 both
    int planes = 0;      ///< Mc, line 4: C planes over the full circle
    int gammas = 0;      ///< Ng, line 6: intensities per C plane
    std::string report, name, number, file_name, date; ///< lines 8-12
    double length = 0, width = 0, height = 0;          ///< luminaire [mm], lines 13-15
    double area_length = 0, area_width = 0;            ///< luminous area [mm], lines 16-17
    double area_heights[4] = {0, 0, 0, 0};             ///< at C0, C90, C180, C270 [mm]
    double downward_fraction = 0;                      ///< DFF [%], line 22
    double light_output_ratio = 100;                   ///< LORL [%], line 23
    double conversion_factor = 1;                      ///< line 24: multiplies the intensities
    double tilt = 0;                  ///< during measurement [deg], line 25 (not applied)
    std::vector<EulumdatLamps> lamps; ///< line 26 and 26a-f, at least one set
    double direct_ratios[10] = {};    ///< line 27, room indices 0.6 .. 5
    std::vector<double> c_angles;     ///< line 28, all Mc of them [deg]
    /// The intensities [cd], as type C (the same convention: gamma 0 is the nadir, C = 0 the
    /// luminaire's length axis, counterclockwise from above), every symmetry mapped onto
    /// HorizontalSymmetry: cd/klm x conversion_factor x lamps[0].total_lumens / 1000.
    CandelaDistribution distribution;
    std::vector<std::string> warnings; ///< "file:line: ..."

    /// The first lamp set's total flux [lm], what the intensities are relative to.
    double rated_lumens() const { return lamps.empty() ? 0 : lamps[0].total_lumens; }
    /// The luminaire's flux the file states: rated_lumens() x LORL / 100 [lm].
    double stated_lumens() const { return rated_lumens() * light_output_ratio / 100; }
};

/// Parses the text of a EULUMDAT file; `path` names it in messages. Throws InputError naming
/// the file, the line and the value for a missing or non-numeric value, counts out of range,
/// Isym outside 0..4, angles not increasing or not spanning what the symmetry stores, no lamp
/// set or a non-positive flux, negative intensities, values left over after the table.
HEMIRAD_API EulumdatFile parse_eulumdat(const std::string& text, const std::string& path);
HEMIRAD_API EulumdatFile read_eulumdat(const std::string& path);

/// A luminaire's luminous opening (IES LM-63 width, length, height; EULUMDAT lines 16-17), in
/// metres: flat, in the plane across the luminaire's aim, its length along C = 0 and its width
/// along C = 90, or a disc of diameter `length` when `round`. Read-outs nearer than five times
/// its size take the luminaire's light from points spread over it (gather.h), as from an area
/// source; the solver's shots stay from its centre.
struct HEMIRAD_API LuminousOpening {
    double length = 0, width = 0, height = 0; ///< [m]; all 0: a point
    bool round = false;
    /// The largest of the three [m] (0: a point source).
    double size() const;
    /// The points that stand for it, about `per_side` across (at least 1): the centres of a
    /// grid of equal cells over the rectangle, or those within the disc, relative to the
    /// luminaire's position, given its c0 and c90 axes. One point (the centre) for a point.
    std::vector<glm::dvec3> points(const glm::dvec3& c0, const glm::dvec3& c90, int per_side) const;
};

/// What a luminaire takes from a photometric file of either format.
struct HEMIRAD_API PhotometricFile {
    std::string format; ///< "ies" or "ldt"
    CandelaDistribution distribution;
    double rated_lumens = 0; ///< lamp lumens (0: absolute photometry)
    LuminousOpening opening; ///< from the file's dimensions [m]
    std::vector<std::string> warnings;
};
/// Whether `text` is a EULUMDAT file rather than an IES file, by content: an IES file starts
/// with "IESNA" or "IES:" or has a TILT= line; anything else is read as EULUMDAT.
HEMIRAD_API bool is_eulumdat_text(const std::string& text);
/// Reads an IES or EULUMDAT file, told apart by content (is_eulumdat_text). Throws InputError.
HEMIRAD_API PhotometricFile read_photometric_file(const std::string& path);

/// A point-source luminaire placed in a scene (SCENE.json "luminaires", scene_json.h).
struct HEMIRAD_API Luminaire {
    std::string name;         ///< for reports ("L1", or the "name" given)
    std::string kind;         ///< "ies", "ldt", "candela", "spot" or "point" (a glTF point light)
    std::string file;         ///< the photometric file as given (ies, ldt), else ""
    glm::dvec3 position{0.0}; ///< [scene units; metres for lux]
    glm::dvec3 aim{0.0, -1.0, 0.0}; ///< the photometric nadir (gamma = 0), unit (orient())
    double rotation = 0;   ///< turns the C planes about the aim, counterclockwise from above [deg]
    double multiplier = 1; ///< scales the intensity (and lumens), >= 0 (0 = off)
    double rated_lumens = 0; ///< lamp lumens of the IES file times multiplier (0: none stated)
    CandelaDistribution distribution; ///< [cd], multiplier not applied
    LuminousOpening opening;          ///< from the photometric file (a point for the others)
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
    double irradiance(const glm::dvec3& x, const glm::dvec3& n) const {
        return irradiance_from(position, x, n);
    }
    /// The same with the light leaving from point y instead of `position` (a point of its
    /// luminous opening, which stands for the whole luminaire: callers divide by their count).
    double irradiance_from(const glm::dvec3& y, const glm::dvec3& x, const glm::dvec3& n) const;
};

} // namespace hemirad
