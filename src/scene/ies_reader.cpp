// IES LM-63 photometric files (photometry.h). The layout (LM-63-2002 §5; 1986-1995 alike):
//
//   IESNA:LM-63-2002            format line (1991: "IESNA91"; 1986: none)
//   [KEYWORD] value ...          keyword lines (1986: free text)
//   TILT=NONE                    (INCLUDE or a file name: tilt data, refused here)
//   lamps  lumens/lamp  multiplier  #vertical  #horizontal  type  units  width length height
//   ballast-factor  future-use (1991/1995: ballast-lamp factor)  input-watts
//   vertical angles, horizontal angles, then the candela values plane by plane (all the
//   vertical angles of the first horizontal angle, then the next plane, ...)
//
// After TILT= the values are separated by blanks, commas or line breaks, anywhere.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/parse.h"
#include "hemirad/error.h"
#include "hemirad/photometry.h"

namespace hemirad {

namespace {

struct Token {
    std::string text;
    int line = 0;
};

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return "";
    const auto b = s.find_last_not_of(" \t\r\n");
    return s.substr(a, b - a + 1);
}

std::string upper(std::string s) {
    for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

class Reader {
  public:
    Reader(std::vector<Token> tokens, const std::string& path, int last_line)
        : tokens_(std::move(tokens)), path_(path), last_line_(last_line) {}

    /// The next value as a finite number; `what` names it in messages.
    double number(const std::string& what, int& line) {
        if (next_ >= tokens_.size())
            throw InputError(path_, last_line_, "the file ends where " + what + " was expected");
        const Token& t = tokens_[next_++];
        line = t.line;
        double x = 0; // out of range: inf (refused) or 0, as strtod reads it
        const char* b = t.text.data();
        const NumberRead r = read_double(b, b + t.text.size(), x);
        if (!r.found(b) || r.end != b + t.text.size() || !std::isfinite(x))
            throw InputError(path_, t.line, what + ": expected a number, got '" + t.text + "'");
        return x;
    }
    double number(const std::string& what) {
        int line;
        return number(what, line);
    }
    /// A whole number (written as one, e.g. "3" or "3.0").
    int integer(const std::string& what, int& line) {
        const double x = number(what, line);
        if (x != std::floor(x) || std::abs(x) > 1e6)
            throw InputError(path_, line,
                             what + ": expected a whole number, got '" + tokens_[next_ - 1].text +
                                 "'");
        return int(x);
    }
    const std::string& last_text() const { return tokens_[next_ - 1].text; }
    bool done() const { return next_ >= tokens_.size(); }
    const Token& peek() const { return tokens_[next_]; }

  private:
    std::vector<Token> tokens_;
    std::size_t next_ = 0;
    std::string path_;
    int last_line_;
};

[[noreturn]] void fail(const std::string& path, int line, const std::string& what,
                       const std::string& value, const std::string& why) {
    throw InputError(path, line, what + " " + value + ": " + why);
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
    std::vector<std::string> lines;
    {
        std::istringstream in(text);
        std::string l;
        while (std::getline(in, l)) {
            if (!l.empty() && l.back() == '\r') l.pop_back();
            lines.push_back(l);
        }
    }
    if (lines.empty()) throw InputError(path, 0, "empty file (not an IES photometric file)");

    // Header: format line, keywords, up to TILT=.
    std::size_t k = 0;
    std::string first = trim(lines[0]);
    if (first.size() >= 3 && static_cast<unsigned char>(first[0]) == 0xEF) first = first.substr(3);
    const std::string head = upper(first);
    if (head.rfind("IESNA:LM-63-2002", 0) == 0)
        f.format = "LM-63-2002", k = 1;
    else if (head.rfind("IESNA:LM-63-1995", 0) == 0)
        f.format = "LM-63-1995", k = 1;
    else if (head.rfind("IESNA91", 0) == 0)
        f.format = "LM-63-1991", k = 1;
    else if (head.rfind("IESNA", 0) == 0)
        throw InputError(path, 1,
                         "unknown format line '" + first +
                             "' (expected IESNA:LM-63-2002, IESNA:LM-63-1995 or IESNA91)");
    else
        f.format = "LM-63-1986";
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
    if (upper(tilt) != "NONE")
        throw InputError(path, int(tilt_line) + 1,
                         "TILT=" + tilt +
                             ": only TILT=NONE is supported (tilt data, which "
                             "changes the output with the lamp's inclination, is not read)");

    std::vector<Token> tokens;
    for (std::size_t i = tilt_line + 1; i < lines.size(); ++i) {
        std::string l = lines[i];
        for (char& c : l)
            if (c == ',' || c == '\t' || c == '\r') c = ' ';
        std::istringstream in(l);
        std::string t;
        while (in >> t) tokens.push_back({t, int(i) + 1});
    }
    Reader r(std::move(tokens), path, int(lines.size()));

    int line = 0;
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
    if (f.photometric_type != 1) {
        const char* name = f.photometric_type == 2   ? " (type B)"
                           : f.photometric_type == 3 ? " (type A)"
                                                     : "";
        fail(path, line, "photometric type", r.last_text() + name, "only type C (1) is supported");
    }
    f.units = r.integer("units type", line);
    if (f.units != 1 && f.units != 2)
        fail(path, line, "units type", r.last_text(), "must be 1 (feet) or 2 (metres)");
    f.width = r.number("luminous opening width");
    f.length = r.number("luminous opening length");
    f.height = r.number("luminous opening height");
    f.ballast_factor = r.number("ballast factor", line);
    if (!(f.ballast_factor > 0)) fail(path, line, "ballast factor", r.last_text(), "must be > 0");
    const double blp = r.number(
        f.format == "LM-63-2002" ? "future use value" : "ballast-lamp photometric factor", line);
    if (f.format != "LM-63-2002") {
        if (!(blp > 0))
            fail(path, line, "ballast-lamp photometric factor", r.last_text(), "must be > 0");
        f.ballast_lamp_factor = blp;
    }
    f.input_watts = r.number("input watts");

    CandelaDistribution& d = f.distribution;
    d.gamma.resize(std::size_t(nv));
    int first_v_line = 0, last_v_line = 0;
    std::string first_v, last_v; // as written
    std::string prev;
    for (int i = 0; i < nv; ++i) {
        if (i > 0) prev = r.last_text();
        d.gamma[i] =
            r.number("vertical angle " + std::to_string(i + 1) + " of " + std::to_string(nv), line);
        if (i == 0) first_v_line = line, first_v = r.last_text();
        last_v_line = line, last_v = r.last_text();
        if (i > 0 && !(d.gamma[i] > d.gamma[i - 1]))
            fail(path, line, "vertical angle", r.last_text(),
                 "vertical angles must increase (the one before is " + prev + ")");
    }
    if (d.gamma.front() != 0 && d.gamma.front() != 90)
        fail(path, first_v_line, "first vertical angle", first_v,
             "must be 0 or 90 for type C photometry");
    if (d.gamma.back() != 90 && d.gamma.back() != 180)
        fail(path, last_v_line, "last vertical angle", last_v,
             "must be 90 or 180 for type C photometry");
    d.c.resize(std::size_t(nh));
    int first_h_line = 0, last_h_line = 0;
    std::string first_h, last_h;     // as written
    std::vector<std::string> h_text; // every horizontal angle as written
    for (int i = 0; i < nh; ++i) {
        if (i > 0) prev = r.last_text();
        d.c[i] = r.number("horizontal angle " + std::to_string(i + 1) + " of " + std::to_string(nh),
                          line);
        h_text.push_back(r.last_text());
        if (i == 0) first_h_line = line, first_h = r.last_text();
        last_h_line = line, last_h = r.last_text();
        if (i > 0 && !(d.c[i] > d.c[i - 1]))
            fail(path, line, "horizontal angle", r.last_text(),
                 "horizontal angles must increase (the one before is " + prev + ")");
    }
    const double c_first = d.c.front(), c_last = d.c.back();
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
        fail(path, first_h_line, "first horizontal angle", first_h,
             "must be 0 (or 90, with 270 as the last) for type C photometry");
    else
        fail(path, last_h_line, "last horizontal angle", last_h,
             "must be 0, 90, 180 or 360 (the symmetry of the distribution; 270 after a first "
             "angle of 90)");

    const double scale = f.candela_multiplier * f.ballast_factor * f.ballast_lamp_factor;
    d.candela.resize(std::size_t(nv) * std::size_t(nh));
    for (int h = 0; h < nh; ++h)
        for (int v = 0; v < nv; ++v) {
            const double x = r.number("candela value " + std::to_string(v + 1) + " of plane " +
                                          std::to_string(h + 1) + " (C = " + h_text[h] + ")",
                                      line);
            if (x < 0) fail(path, line, "candela value", r.last_text(), "must be >= 0");
            d.candela[std::size_t(h) * nv + v] = x * scale;
        }
    if (!r.done())
        throw InputError(path, r.peek().line,
                         "'" + r.peek().text + "' after the last of the " +
                             std::to_string(nv * nh) + " candela values (" + std::to_string(nv) +
                             " vertical x " + std::to_string(nh) +
                             " horizontal angles): the counts do not match the table");
    return f;
}

IesFile read_ies(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open IES file");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_ies(s.str(), path);
}

} // namespace hemirad
