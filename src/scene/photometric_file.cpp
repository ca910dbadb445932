// A luminaire's photometric file, IES or EULUMDAT, told apart by content (photometry.h).
#include "hemirad/photometry.h"
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

PhotometricFile read_photometric_file(const std::string& path) {
    const std::string text = photometric::read_text(path, "photometric file");
    PhotometricFile out;
    if (is_eulumdat_text(text)) {
        EulumdatFile f = parse_eulumdat(text, path);
        out.format = "ldt";
        out.distribution = std::move(f.distribution);
        out.rated_lumens = f.rated_lumens();
        out.warnings = std::move(f.warnings);
    } else {
        IesFile f = parse_ies(text, path);
        out.format = "ies";
        out.distribution = std::move(f.distribution);
        out.rated_lumens = f.rated_lumens();
        out.warnings = std::move(f.warnings);
    }
    return out;
}

} // namespace hemirad
