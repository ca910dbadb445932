// A luminaire's photometric file, IES or EULUMDAT, told apart by content (photometry.h).
#include "hemirad/photometry.h"

#include <algorithm>
#include <cmath>

#include "scene/photometric_text.h"

namespace hemirad {

bool is_eulumdat_text(const std::string& text) {
    // An IES file opens with its format line (IESNA..., IES:LM-63-2019) or, LM-63-1986, with
    // keywords or free text up to a TILT= line; a EULUMDAT file has neither (its line 1 is a
    // company name, then numbers one a line).
    const std::vector<std::string> lines = photometric::split_lines(text);
    const std::string first = lines.empty() ? "" : photometric::upper(photometric::trim(lines[0]));
    if (first.rfind("IESNA", 0) == 0 || first.rfind("IES:", 0) == 0) return false;
    for (const std::string& l : lines) {
        const std::string t = photometric::upper(photometric::trim(l));
        if (t.rfind("TILT", 0) == 0 && t.find('=') != std::string::npos) return false;
    }
    return true;
}

double LuminousOpening::size() const {
    return std::max({length, width, height});
}

std::vector<glm::dvec3> LuminousOpening::points(const glm::dvec3& c0, const glm::dvec3& c90,
                                                int per_side) const {
    if (!(length > 0 || width > 0)) return {glm::dvec3(0.0)};
    const int k = std::max(1, per_side);
    const double w = round ? length : width;
    std::vector<glm::dvec3> out;
    for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
            const double a = (i + 0.5) / k - 0.5, b = (j + 0.5) / k - 0.5; // in (-1/2, 1/2)
            if (round && a * a + b * b > 0.25) continue;
            out.push_back(a * length * c0 + b * w * c90);
        }
    if (out.empty()) out.push_back(glm::dvec3(0.0));
    return out;
}

namespace {

/// LM-63's opening: in feet (units 1) or metres; a negative width is a round opening of that
/// diameter (a negative length too, by the 2019 edition's table; taken the same way).
LuminousOpening ies_opening(const IesFile& f) {
    const double unit = f.units == 1 ? 0.3048 : 1.0;
    LuminousOpening o;
    o.round = f.width < 0 || f.length < 0;
    o.width = std::abs(f.width) * unit;
    o.length = std::abs(f.length) * unit;
    o.height = std::abs(f.height) * unit;
    if (o.round) o.length = o.width = std::max(o.length, o.width);
    return o;
}

/// EULUMDAT's luminous area [mm]: length (or diameter) along C0-C180, width along C90-C270,
/// 0 for a round one; heights at C0, C90, C180, C270.
LuminousOpening ldt_opening(const EulumdatFile& f) {
    LuminousOpening o;
    o.length = std::abs(f.area_length) / 1000;
    o.width = std::abs(f.area_width) / 1000;
    o.round = o.width == 0 && o.length > 0;
    if (o.round) o.width = o.length;
    for (const double h : f.area_heights) o.height = std::max(o.height, std::abs(h) / 1000);
    return o;
}

} // namespace

PhotometricFile read_photometric_file(const std::string& path) {
    const std::string text = photometric::read_text(path, "photometric file");
    PhotometricFile out;
    if (is_eulumdat_text(text)) {
        EulumdatFile f = parse_eulumdat(text, path);
        out.format = "ldt";
        out.distribution = std::move(f.distribution);
        out.rated_lumens = f.rated_lumens();
        out.opening = ldt_opening(f);
        out.warnings = std::move(f.warnings);
    } else {
        IesFile f = parse_ies(text, path);
        out.format = "ies";
        out.distribution = std::move(f.distribution);
        out.rated_lumens = f.rated_lumens();
        out.opening = ies_opening(f);
        out.warnings = std::move(f.warnings);
    }
    return out;
}

} // namespace hemirad
