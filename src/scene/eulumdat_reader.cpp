// EULUMDAT photometric files, .ldt (photometry.h; Stockmar 1990, "EULUMDAT - ein
// Leuchtendatenformat für den europäischen Beleuchtungsplaner", Licht '90, pp. 641-644). One
// field a line:
//
//    1  company / data bank / version             14  width of the luminaire [mm]
//    2  Ityp: type indicator 0..3                 15  height of the luminaire [mm]
//    3  Isym: symmetry indicator 0..4             16  length/diameter of the luminous area
//    4  Mc: number of C planes over 0..360        17  width of the luminous area [mm]
//    5  Dc: their spacing [deg] (0: uneven)       18-21  height of the luminous area at
//    6  Ng: intensities per C plane                      C0, C90, C180, C270 [mm]
//    7  Dg: their spacing [deg] (0: uneven)       22  DFF: downward flux fraction [%]
//    8  measurement report number                 23  LORL: light output ratio [%]
//    9  luminaire name                            24  conversion factor for the intensities
//   10  luminaire number                          25  tilt during measurement [deg]
//   11  file name                                 26  n: number of lamp sets, then per set
//   12  date / user                                   26a lamps, 26b type, 26c total flux [lm],
//   13  length/diameter of the luminaire [mm]         26d colour, 26e rendering, 26f watts
//   27  direct ratios for the room indices 0.6 .. 5 (10 values)
//   28  the Mc C angles [deg]; 29 the Ng gamma angles [deg]
//   30  intensities [cd/klm], Ng for each C plane the symmetry stores (Mc1 .. Mc2):
//         Isym 0: all Mc;  1: one;  2: C0 .. C180 (Mc/2 + 1);  4: C0 .. C90 (Mc/4 + 1);
//         3: C270 .. C360 = C0 .. C90 (Mc/2 + 1, from plane 3 Mc/4 + 1 round the circle).
//
// Lines 1-26f are read one a line (text fields may be empty); from line 27 on the values are
// separated by blanks or line breaks, and a decimal comma is read as a point. The C-gamma
// system is type C, as IES's: gamma 0 is the nadir, C = 0 the luminaire's length axis, C
// counterclockwise seen from above, so the table maps onto CandelaDistribution as it is.
#include <cmath>

#include "hemirad/error.h"
#include "hemirad/photometry.h"
#include "scene/photometric_text.h"

namespace hemirad {

namespace {

using photometric::fail;
using photometric::format_number;
using photometric::Reader;
using photometric::Token;
using photometric::trim;

/// Most lamp sets read (the format's own limit is 20; some writers add more).
constexpr int kMaxLampSets = 1000;

/// The header of a EULUMDAT file, lines 1-26f: one field a line, read in order.
class Lines {
  public:
    Lines(const std::vector<std::string>& lines, const std::string& path)
        : lines_(lines), path_(path) {}
    int number() const { return int(next_); } // 1-based line of the last field read
    /// The next line as text (trimmed).
    std::string text(const std::string& what) {
        if (next_ >= lines_.size())
            throw InputError(path_, int(lines_.size()),
                             "the file ends where " + what + " was expected (line " +
                                 std::to_string(next_ + 1) + ")");
        return trim(lines_[next_++]);
    }
    /// The next line as one number.
    double value(const std::string& what) {
        const std::string t = text(what);
        return reader_.parse(Token{t, int(next_)}, what);
    }
    int integer(const std::string& what) {
        const double x = value(what);
        if (x != std::floor(x) || std::abs(x) > 1e6)
            throw InputError(path_, int(next_),
                             what + ": expected a whole number, got '" + trim(lines_[next_ - 1]) +
                                 "'");
        return int(x);
    }
    std::size_t next() const { return next_; }

  private:
    const std::vector<std::string>& lines_;
    std::string path_;
    std::size_t next_ = 0;
    Reader reader_{{}, path_, 0, true};
};

} // namespace

EulumdatFile parse_eulumdat(const std::string& text, const std::string& path) {
    EulumdatFile f;
    f.path = path;
    const std::vector<std::string> lines = photometric::split_lines(text);
    if (lines.empty()) throw InputError(path, 0, "empty file (not a EULUMDAT photometric file)");
    Lines in(lines, path);
    const auto bad = [&](const std::string& what, const std::string& why) {
        fail(path, in.number(), what, "'" + trim(lines[std::size_t(in.number()) - 1]) + "'", why);
    };

    f.company = in.text("the company identification (line 1)");
    f.type = in.integer("Ityp (type indicator)");
    if (f.type < 0 || f.type > 3) bad("Ityp (type indicator)", "must be 0, 1, 2 or 3");
    f.symmetry = in.integer("Isym (symmetry indicator)");
    if (f.symmetry < 0 || f.symmetry > 4) bad("Isym (symmetry indicator)", "must be 0..4");
    f.planes = in.integer("Mc (number of C planes)");
    if (f.planes < 1 || f.planes > 3600) bad("Mc (number of C planes)", "must be in 1..3600");
    if ((f.symmetry == 2 && f.planes % 2) || ((f.symmetry == 3 || f.symmetry == 4) && f.planes % 4))
        bad("Mc (number of C planes)", "must be a multiple of " +
                                           std::string(f.symmetry == 2 ? "2" : "4") + " for Isym " +
                                           std::to_string(f.symmetry));
    in.value("Dc (C plane spacing)");
    f.gammas = in.integer("Ng (intensities per C plane)");
    if (f.gammas < 2 || f.gammas > 3600) bad("Ng (intensities per C plane)", "must be in 2..3600");
    in.value("Dg (gamma spacing)");
    f.report = in.text("the measurement report number");
    f.name = in.text("the luminaire name");
    f.number = in.text("the luminaire number");
    f.file_name = in.text("the file name");
    f.date = in.text("the date / user");
    f.length = in.value("the luminaire's length");
    f.width = in.value("the luminaire's width");
    f.height = in.value("the luminaire's height");
    f.area_length = in.value("the luminous area's length");
    f.area_width = in.value("the luminous area's width");
    f.area_heights[0] = in.value("the luminous area's height at C0");
    f.area_heights[1] = in.value("the luminous area's height at C90");
    f.area_heights[2] = in.value("the luminous area's height at C180");
    f.area_heights[3] = in.value("the luminous area's height at C270");
    f.downward_fraction = in.value("DFF (downward flux fraction)");
    f.light_output_ratio = in.value("LORL (light output ratio)");
    if (!(f.light_output_ratio >= 0)) bad("LORL (light output ratio)", "must be >= 0 %");
    f.conversion_factor = in.value("the conversion factor for luminous intensities");
    if (!(f.conversion_factor > 0))
        bad("the conversion factor for luminous intensities", "must be > 0");
    f.tilt = in.value("the tilt during measurement");
    const int sets = in.integer("the number of lamp sets");
    if (sets < 1 || sets > kMaxLampSets)
        bad("the number of lamp sets", "must be in 1.." + std::to_string(kMaxLampSets) +
                                           " (the intensities are per 1000 lm of the lamps)");
    for (int s = 0; s < sets; ++s) {
        const std::string set = "lamp set " + std::to_string(s + 1) + ": ";
        EulumdatLamps l;
        l.count = in.integer(set + "number of lamps");
        if (l.count == 0) bad(set + "number of lamps", "must not be 0");
        l.type = in.text(set + "type of lamps");
        l.total_lumens = in.value(set + "total luminous flux");
        if (!(l.total_lumens > 0)) bad(set + "total luminous flux", "must be > 0 lm");
        l.colour = in.text(set + "colour appearance");
        l.rendering = in.text(set + "colour rendering");
        l.watts = in.value(set + "wattage including ballast");
        f.lamps.push_back(l);
    }
    const int first_numbers = int(in.next()) + 1;
    if (sets > 1)
        f.warnings.push_back(photometric::where(path, first_numbers - 6 * sets - 1) +
                             std::to_string(sets) + " lamp sets: the first (" +
                             format_number(f.lamps[0].total_lumens) +
                             " lm) scales the intensities, the others are alternatives");

    // Line 27 on: numbers separated by blanks or line breaks.
    Reader r(photometric::tokens(lines, in.next(), false), path, int(lines.size()), true);
    for (double& dr : f.direct_ratios) dr = r.number("a direct ratio (line 27)");
    int line = 0;
    const auto angles = [&](int n, const char* what, std::vector<double>& a,
                            std::vector<int>& at_line) {
        for (int i = 0; i < n; ++i) {
            a.push_back(r.number(std::string(what) + " angle " + std::to_string(i + 1) + " of " +
                                     std::to_string(n),
                                 line));
            at_line.push_back(line);
            if (i > 0 && !(a[std::size_t(i)] > a[std::size_t(i) - 1]))
                fail(path, line, std::string(what) + " angle", r.last_text(),
                     std::string(what) + " angles must increase");
        }
    };
    std::vector<int> c_line, g_line;
    std::vector<double> gamma;
    angles(f.planes, "C", f.c_angles, c_line);
    angles(f.gammas, "gamma", gamma, g_line);
    if (gamma.front() < 0 || gamma.back() > 180)
        fail(path, gamma.front() < 0 ? g_line.front() : g_line.back(), "gamma angle",
             format_number(gamma.front() < 0 ? gamma.front() : gamma.back()), "must be in 0..180");
    const std::vector<double>& C = f.c_angles;
    const int mc = f.planes;
    // Where the stored planes must lie for the symmetry: (index into C, angle).
    const auto expect = [&](int index, double angle) {
        if (C[std::size_t(index)] != angle)
            fail(path, c_line[std::size_t(index)], "C angle " + std::to_string(index + 1),
                 format_number(C[std::size_t(index)]),
                 "must be " + format_number(angle) + " for Isym " + std::to_string(f.symmetry) +
                     " with Mc " + std::to_string(mc));
    };
    if (f.symmetry != 1) {
        expect(0, 0);
        if (C.back() >= 360)
            fail(path, c_line.back(), "C angle " + std::to_string(mc), format_number(C.back()),
                 "must be < 360 (C = 360 is C = 0)");
    }
    if (f.symmetry == 2) expect(mc / 2, 180);
    if (f.symmetry == 3) expect(3 * mc / 4, 270), expect(mc / 4, 90);
    if (f.symmetry == 4) expect(mc / 4, 90);
    const int stored = f.symmetry == 0   ? mc
                       : f.symmetry == 1 ? 1
                       : f.symmetry == 4 ? mc / 4 + 1
                                         : mc / 2 + 1;
    const int ng = f.gammas;
    const double scale = f.conversion_factor * f.rated_lumens() / 1000.0;
    const std::vector<double> table =
        photometric::read_table(r, path, stored, ng, scale, "intensity", [&](int p, int g) {
            const int index = f.symmetry == 3 ? (3 * mc / 4 + p) % mc : p;
            return "intensity " + std::to_string(g + 1) + " of C plane " +
                   format_number(C[std::size_t(index)]) + " (cd/klm)";
        });
    photometric::expect_end(r, path, std::to_string(stored * ng) + " intensities",
                            std::to_string(stored) + " C planes for Isym " +
                                std::to_string(f.symmetry) + " x " + std::to_string(ng) +
                                " gamma angles");

    CandelaDistribution& d = f.distribution;
    d.gamma = gamma;
    const auto plane = [&](int p) {
        return std::vector<double>(table.begin() + long(p) * ng, table.begin() + long(p + 1) * ng);
    };
    switch (f.symmetry) {
    case 0: // every plane, and C = 360 closing the circle with C = 0's values
        d.symmetry = HorizontalSymmetry::None;
        d.c = C;
        d.c.push_back(360);
        d.candela = table;
        d.candela.insert(d.candela.end(), table.begin(), table.begin() + ng);
        break;
    case 1:
        d.symmetry = HorizontalSymmetry::Axial;
        d.c = {0.0};
        d.candela = table;
        break;
    case 2:
        d.symmetry = HorizontalSymmetry::Bilateral;
        d.c.assign(C.begin(), C.begin() + mc / 2 + 1);
        d.candela = table;
        break;
    case 3:
        // Stored C270 .. C90 through C0; mirrored about the C90-C270 plane (C -> 180 - C) they
        // are the table of C = 90 .. 270 that Bilateral90 holds, in reverse order.
        d.symmetry = HorizontalSymmetry::Bilateral90;
        for (int j = 0; j < stored; ++j) {
            const int p = stored - 1 - j;
            double a = C[std::size_t((3 * mc / 4 + p) % mc)];
            if (a >= 270) a -= 360; // -90 .. 90
            d.c.push_back(180 - a);
            const std::vector<double> row = plane(p);
            d.candela.insert(d.candela.end(), row.begin(), row.end());
        }
        break;
    default: // 4
        d.symmetry = HorizontalSymmetry::Quadrant;
        d.c.assign(C.begin(), C.begin() + mc / 4 + 1);
        d.candela = table;
        break;
    }
    return f;
}

EulumdatFile read_eulumdat(const std::string& path) {
    return parse_eulumdat(photometric::read_text(path, "EULUMDAT file"), path);
}

} // namespace hemirad
