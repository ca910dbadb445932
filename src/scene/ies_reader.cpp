// IES LM-63 photometric files (photometry.h). The layout (LM-63-2002 §5; 1986-2019 alike):
//
//   IESNA:LM-63-2002            format line (1991: "IESNA91"; 2019: "IES:LM-63-2019"; 1986: none)
//   [KEYWORD] value ...          keyword lines (1986: free text)
//   TILT=NONE                    (INCLUDE: a tilt block follows; or a tilt file's name)
//   lamps  lumens/lamp  multiplier  #vertical  #horizontal  type  units  width length height
//   ballast-factor  future-use (1991/1995: ballast-lamp factor)  input-watts
//   vertical angles, horizontal angles, then the candela values plane by plane (all the
//   vertical angles of the first horizontal angle, then the next plane, ...)
//
// After TILT= the values are separated by blanks, commas or line breaks, anywhere.
//
// Read with a warning, as files in the wild have them: a format line that is none of the
// standard ones ("IESNA95", Radiance's examples: read as LM-63-1995); TILT=INCLUDE (the tilt
// block is read and not applied) or a tilt file (not read); photometric type B (floodlights),
// converted to type C by resampling (type_b_to_c below).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "hemirad/error.h"
#include "hemirad/photometry.h"
#include "scene/photometric_text.h"

namespace hemirad {

namespace {

using photometric::fail;
using photometric::Reader;
using photometric::trim;
using photometric::upper;
using photometric::where;

constexpr double kDeg = std::numbers::pi / 180.0;

// A type B table: I(H, V) bilinear on the tabulated angles, mirrored where a range starts at
// 0 (symmetric), 0 outside the ranges.
struct TypeB {
    std::vector<double> v, h; // [deg], increasing
    std::vector<double> cd;   // cd[ih * v.size() + iv]

    static double lookup(const std::vector<double>& a, double x, std::size_t& k) {
        k = std::size_t(std::upper_bound(a.begin(), a.end(), x) - a.begin());
        k = std::clamp<std::size_t>(k, 1, a.size() - 1) - 1;
        return std::clamp((x - a[k]) / (a[k + 1] - a[k]), 0.0, 1.0);
    }
    double operator()(double H, double V) const {
        if (h.front() == 0) H = std::abs(H);
        if (v.front() == 0) V = std::abs(V);
        if (V < v.front() || V > v.back() || (h.size() > 1 && (H < h.front() || H > h.back())))
            return 0;
        std::size_t iv, ih = 0;
        const double tv = lookup(v, V, iv);
        const double th = h.size() > 1 ? lookup(h, H, ih) : 0;
        const auto row = [&](std::size_t i) {
            const double* r = &cd[i * v.size()];
            return (1 - tv) * r[iv] + tv * r[iv + 1];
        };
        return h.size() > 1 ? (1 - th) * row(ih) + th * row(ih + 1) : row(0);
    }
};

// Type B to type C. Type B's polar axis is the luminaire's horizontal (tilt) axis: a direction
// at vertical angle V (the plane through that axis, turned up or down) and horizontal angle H
// (from that plane towards the axis) is cos H (cos V beam + sin V up) + sin H left. Here the beam
// (H = V = 0) is the type C nadir (the luminaire's aim), "up" (V > 0) is C = 0 and "left"
// (H > 0) is C = 90:
//   sin H = sin(gamma) sin(C),  tan V = tan(gamma) cos(C).
// Type B covers the hemisphere about the beam, gamma <= 90, resampled every 0.5 degrees in gamma
// and 1 degree in C (the bilinear interpolant of the B table, sampled: lumens within 0.1 % of
// the B table's own for tables of 1-5 degree steps).
CandelaDistribution type_b_to_c(const TypeB& b) {
    CandelaDistribution d;
    d.symmetry = HorizontalSymmetry::None;
    for (int j = 0; j <= 180; ++j) d.gamma.push_back(0.5 * j);
    for (int i = 0; i <= 360; ++i) d.c.push_back(i);
    d.candela.reserve(d.gamma.size() * d.c.size());
    for (double C : d.c)
        for (double g : d.gamma) {
            const double sg = std::sin(g * kDeg), cg = std::cos(g * kDeg);
            const double H = std::asin(std::clamp(sg * std::sin(C * kDeg), -1.0, 1.0)) / kDeg;
            const double V = std::atan2(sg * std::cos(C * kDeg), cg) / kDeg;
            d.candela.push_back(b(H, V));
        }
    return d;
}

} // namespace

std::string IesFile::keyword(const std::string& name) const {
    for (const auto& [k, v] : keywords)
        if (k == name) return v;
    return "";
}

IesFile parse_ies(const std::string& text, const std::string& path) {
    IesFile f;
    f.path = path;
    const std::vector<std::string> lines = photometric::split_lines(text);
    if (lines.empty()) throw InputError(path, 0, "empty file (not an IES photometric file)");

    // Header: format line, keywords, up to TILT=.
    std::size_t k = 1;
    const std::string first = trim(lines[0]);
    const std::string head = upper(first);
    if (head.rfind("IESNA:LM-63-2002", 0) == 0) {
        f.format = "LM-63-2002";
    } else if (head.rfind("IES:LM-63-2019", 0) == 0) {
        f.format = "LM-63-2019";
    } else if (head.rfind("IESNA:LM-63-1995", 0) == 0) {
        f.format = "LM-63-1995";
    } else if (head.rfind("IESNA91", 0) == 0) {
        f.format = "LM-63-1991";
    } else if (head.rfind("IES", 0) == 0) {
        // "IESNA95" (Radiance's examples), "IESNA:LM-63-1999", ...: the 1995 layout, whose
        // ballast-lamp factor is applied (2002 made it "future use", always 1 in practice).
        f.format = "LM-63-1995";
        f.warnings.push_back(where(path, 1) + "format line '" + first +
                             "' is none of LM-63's (IESNA:LM-63-2002, IESNA:LM-63-1995, "
                             "IESNA91, IES:LM-63-2019): read as LM-63-1995");
    } else {
        f.format = "LM-63-1986"; // no format line: keywords or free text up to TILT=
        k = 0;
    }
    std::size_t tilt_line = lines.size();
    for (; k < lines.size(); ++k) {
        const std::string l = trim(lines[k]);
        if (upper(l).rfind("TILT", 0) == 0 && l.find('=') != std::string::npos) {
            tilt_line = k;
            break;
        }
        if (!l.empty() && l[0] == '[') {
            const auto close = l.find(']');
            if (close != std::string::npos) {
                const std::string key = l.substr(1, close - 1);
                const std::string value = trim(l.substr(close + 1));
                if (key == "MORE" && !f.keywords.empty())
                    f.keywords.back().second += " " + value;
                else
                    f.keywords.emplace_back(key, value);
            }
        }
    }
    if (tilt_line == lines.size())
        throw InputError(path, 0, "no TILT= line (not an IES photometric file?)");
    const std::string tilt_text = trim(lines[tilt_line]);
    const std::string tilt = trim(tilt_text.substr(tilt_text.find('=') + 1));
    const int tilt_at = int(tilt_line) + 1;

    Reader r(photometric::tokens(lines, tilt_line + 1, true), path, int(lines.size()));
    int line = 0;
    if (upper(tilt) == "INCLUDE") {
        // LM-63-2002 §5.5: lamp-to-luminaire geometry, the number of angles, the angles, the
        // multiplying factors. Read (so that the table after them is found) and not applied.
        const int geometry = r.integer("TILT=INCLUDE lamp-to-luminaire geometry", line);
        if (geometry < 1 || geometry > 3)
            fail(path, line, "TILT=INCLUDE lamp-to-luminaire geometry", r.last_text(),
                 "must be 1, 2 or 3");
        const int n = r.integer("TILT=INCLUDE number of tilt angles", line);
        if (n < 0 || n > 100000)
            fail(path, line, "TILT=INCLUDE number of tilt angles", r.last_text(),
                 "must be in 0..100000");
        for (int i = 0; i < 2 * n; ++i)
            r.number(std::string(i < n ? "tilt angle " : "tilt multiplying factor ") +
                     std::to_string(i % n + 1) + " of " + std::to_string(n));
        f.warnings.push_back(where(path, tilt_at) + "TILT=INCLUDE: the " + std::to_string(n) +
                             " tilt factors (lamp output against the luminaire's inclination) "
                             "are not applied: the distribution is the one measured");
    } else if (upper(tilt) != "NONE") {
        f.warnings.push_back(where(path, tilt_at) + "TILT=" + tilt +
                             ": the tilt file is not read (its factors are not applied: the "
                             "distribution is the one measured)");
    }

    f.lamps = r.integer("number of lamps", line);
    if (f.lamps < 1)
        fail(path, line, "number of lamps", r.last_text(), "must be a whole number >= 1");
    f.lumens_per_lamp = r.number("lumens per lamp", line);
    if (!(f.lumens_per_lamp > 0 || f.lumens_per_lamp == -1))
        fail(path, line, "lumens per lamp", r.last_text(),
             "must be > 0, or -1 for absolute photometry");
    f.candela_multiplier = r.number("candela multiplier", line);
    if (!(f.candela_multiplier > 0))
        fail(path, line, "candela multiplier", r.last_text(), "must be > 0");
    const int nv = r.integer("number of vertical angles", line);
    if (nv < 2 || nv > 100000)
        fail(path, line, "number of vertical angles", r.last_text(), "must be in 2..100000");
    const int nh = r.integer("number of horizontal angles", line);
    if (nh < 1 || nh > 100000)
        fail(path, line, "number of horizontal angles", r.last_text(), "must be in 1..100000");
    f.photometric_type = r.integer("photometric type", line);
    const int type_line = line;
    if (f.photometric_type != 1 && f.photometric_type != 2) {
        const char* name = f.photometric_type == 3 ? " (type A)" : "";
        fail(path, line, "photometric type", r.last_text() + name,
             "only types C (1) and B (2) are supported");
    }
    const bool type_b = f.photometric_type == 2;
    f.units = r.integer("units type", line);
    if (f.units != 1 && f.units != 2)
        fail(path, line, "units type", r.last_text(), "must be 1 (feet) or 2 (metres)");
    f.width = r.number("luminous opening width");
    f.length = r.number("luminous opening length");
    f.height = r.number("luminous opening height");
    f.ballast_factor = r.number("ballast factor", line);
    if (!(f.ballast_factor > 0)) fail(path, line, "ballast factor", r.last_text(), "must be > 0");
    const bool future_use = f.format == "LM-63-2002" || f.format == "LM-63-2019";
    const double blp =
        r.number(future_use ? "future use value" : "ballast-lamp photometric factor", line);
    if (!future_use) {
        if (!(blp > 0))
            fail(path, line, "ballast-lamp photometric factor", r.last_text(), "must be > 0");
        f.ballast_lamp_factor = blp;
    }
    f.input_watts = r.number("input watts");

    // The angles as written, for messages, with their lines.
    const auto read_angles = [&](int n, const char* what, std::vector<double>& a,
                                 std::vector<std::string>& text, std::vector<int>& at_line) {
        a.resize(std::size_t(n));
        for (int i = 0; i < n; ++i) {
            a[std::size_t(i)] = r.number(std::string(what) + " angle " + std::to_string(i + 1) +
                                             " of " + std::to_string(n),
                                         line);
            text.push_back(r.last_text());
            at_line.push_back(line);
            if (i > 0 && !(a[std::size_t(i)] > a[std::size_t(i) - 1]))
                fail(path, line, std::string(what) + " angle", r.last_text(),
                     std::string(what) + " angles must increase (the one before is " +
                         text[std::size_t(i) - 1] + ")");
        }
    };
    std::vector<double> va, ha;
    std::vector<std::string> v_text, h_text;
    std::vector<int> v_line, h_line;
    read_angles(nv, "vertical", va, v_text, v_line);
    read_angles(nh, "horizontal", ha, h_text, h_line);

    CandelaDistribution& d = f.distribution;
    if (type_b) {
        // LM-63-2002 §5.18-5.19: type B vertical angles -90 (or 0: symmetric) to 90,
        // horizontal angles -90 (or 0: laterally symmetric) to 90.
        if (va.front() != -90 && va.front() != 0)
            fail(path, v_line.front(), "first vertical angle", v_text.front(),
                 "must be -90 or 0 for type B photometry");
        if (va.back() != 90)
            fail(path, v_line.back(), "last vertical angle", v_text.back(),
                 "must be 90 for type B photometry");
        if (nh > 1 && ha.front() != -90 && ha.front() != 0)
            fail(path, h_line.front(), "first horizontal angle", h_text.front(),
                 "must be -90 or 0 for type B photometry");
        if (nh > 1 && ha.back() != 90)
            fail(path, h_line.back(), "last horizontal angle", h_text.back(),
                 "must be 90 for type B photometry");
        if (nh == 1 && ha.front() != 0)
            fail(path, h_line.front(), "horizontal angle", h_text.front(),
                 "a single horizontal angle must be 0");
    } else {
        if (va.front() != 0 && va.front() != 90)
            fail(path, v_line.front(), "first vertical angle", v_text.front(),
                 "must be 0 or 90 for type C photometry");
        if (va.back() != 90 && va.back() != 180)
            fail(path, v_line.back(), "last vertical angle", v_text.back(),
                 "must be 90 or 180 for type C photometry");
        const double c_first = ha.front(), c_last = ha.back();
        if (c_first == 0 && c_last == 0)
            d.symmetry = HorizontalSymmetry::Axial;
        else if (c_first == 0 && c_last == 90)
            d.symmetry = HorizontalSymmetry::Quadrant;
        else if (c_first == 0 && c_last == 180)
            d.symmetry = HorizontalSymmetry::Bilateral;
        else if (c_first == 90 && c_last == 270)
            d.symmetry = HorizontalSymmetry::Bilateral90;
        else if (c_first == 0 && c_last == 360)
            d.symmetry = HorizontalSymmetry::None;
        else if (c_first != 0 && c_first != 90)
            fail(path, h_line.front(), "first horizontal angle", h_text.front(),
                 "must be 0 (or 90, with 270 as the last) for type C photometry");
        else
            fail(path, h_line.back(), "last horizontal angle", h_text.back(),
                 "must be 0, 90, 180 or 360 (the symmetry of the distribution; 270 after a "
                 "first angle of 90)");
    }

    const double scale = f.candela_multiplier * f.ballast_factor * f.ballast_lamp_factor;
    std::vector<double> candela =
        photometric::read_table(r, path, nh, nv, scale, "candela value", [&](int h, int v) {
            return "candela value " + std::to_string(v + 1) + " of plane " + std::to_string(h + 1) +
                   " (" + (type_b ? "H = " : "C = ") + h_text[std::size_t(h)] + ")";
        });
    photometric::expect_end(r, path, std::to_string(nv * nh) + " candela values",
                            std::to_string(nv) + " vertical x " + std::to_string(nh) +
                                " horizontal angles");
    if (type_b) {
        d = type_b_to_c(TypeB{va, ha, std::move(candela)});
        f.warnings.push_back(
            where(path, type_line) +
            "photometric type B: converted to type C (resampled every 0.5 degrees in gamma, 1 "
            "in C): the beam axis (H = V = 0) is the aim, V turns towards C = 0, H towards C = "
            "90");
    } else {
        d.gamma = std::move(va);
        d.c = std::move(ha);
        d.candela = std::move(candela);
    }
    return f;
}

IesFile read_ies(const std::string& path) {
    return parse_ies(photometric::read_text(path, "IES file"), path);
}

} // namespace hemirad
