#include "script.h"

#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/line_reader.h"
#include "core/parse.h"
#include "hemirad/error.h"

namespace hemirad::view {

const char* const kScriptHelp =
    "  shots N                       solve N more shots (fewer once converged)\n"
    "  luminaire NAME multiplier F   a luminaire's multiplier (0 = off), re-solved incrementally\n"
    "  luminaire NAME position X Y Z move a luminaire (scene units); its light is taken out and\n"
    "                                shot again from there (needs light layers)\n"
    "  luminaire NAME aim X Y Z      aim it (its photometric nadir), likewise\n"
    "  reflectance GROUP R [G B]     a surface group's reflectance (each in [0, 1))\n"
    "  pick X Y                      window pixel (origin top left): prints to stdout\n"
    "                                'pick X Y: x y z nx ny nz GROUP E UNIT', E by final gather\n"
    "                                (as hemirad solve --probes), in lx when in lux (--units)\n"
    "  screenshot FILE.png           save the window as drawn now\n"
    "  quit                          end the script and close the window\n"
    "  Blank lines and # comments are ignored; the window is drawn after every command.";

namespace {

constexpr long kMaxShots = 100000000; ///< one `shots` command

std::vector<std::string> split_words(const std::string& line) {
    std::vector<std::string> words;
    std::istringstream in(line);
    std::string w;
    while (in >> w) words.push_back(w);
    return words;
}

} // namespace

std::vector<ScriptCommand> read_script(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError(path, 0, "is a directory, not a script");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, "cannot open the script");
    constexpr std::size_t kMaxLine = 64 * 1024;
    std::vector<ScriptCommand> commands;
    std::string line;
    int number = 0;
    bool too_long = false, has_nul = false;
    while (read_bounded_line(in, line, kMaxLine, too_long, has_nul)) {
        if (number == INT_MAX) throw InputError(path, number, "too many lines");
        ++number;
        if (too_long) throw InputError(path, number, "line longer than 64 KiB (not a script?)");
        if (has_nul) throw InputError(path, number, "NUL byte in the line (not a text file?)");
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::vector<std::string> w = split_words(line);
        if (w.empty() || w[0][0] == '#') continue;
        const auto fail = [&](const std::string& message) {
            throw InputError(path, number, "'" + quoted_excerpt(line) + "': " + message);
        };
        const auto arguments = [&](std::size_t n, const char* usage) {
            if (w.size() != n + 1) fail(std::string("expected ") + usage);
        };
        const auto number_of = [&](const std::string& text, const char* what) {
            const std::optional<double> v = parse_double(text);
            if (!v || !std::isfinite(*v))
                fail(std::string(what) + " '" + quoted_excerpt(text) + "' is not a finite number");
            return *v;
        };
        ScriptCommand c;
        c.line = number;
        const std::string& verb = w[0];
        if (verb == "shots") {
            c.kind = ScriptCommand::Kind::Shots;
            arguments(1, "shots N");
            const std::optional<long long> n = parse_integer(w[1]);
            if (!n || *n < 0 || *n > kMaxShots)
                fail("N '" + quoted_excerpt(w[1]) + "' must be an integer in 0.." +
                     std::to_string(kMaxShots));
            c.shots = long(*n);
        } else if (verb == "luminaire") {
            c.kind = ScriptCommand::Kind::Luminaire;
            constexpr const char* kUsage =
                "luminaire NAME multiplier F, luminaire NAME position X Y Z or luminaire NAME aim "
                "X Y Z";
            if (w.size() < 3) fail(std::string("expected ") + kUsage);
            c.name = w[1];
            c.property = w[2];
            if (c.property == "multiplier") {
                arguments(3, "luminaire NAME multiplier F");
                c.multiplier = number_of(w[3], "multiplier");
                if (c.multiplier < 0) fail("the multiplier must be >= 0 (0 = off)");
            } else if (c.property == "position" || c.property == "aim") {
                arguments(5, c.property == "aim" ? "luminaire NAME aim X Y Z"
                                                 : "luminaire NAME position X Y Z");
                for (int k = 0; k < 3; ++k) c.xyz[k] = number_of(w[3 + k], c.property.c_str());
                if (c.property == "aim" && c.xyz == dvec3(0.0))
                    fail("the aim must be a non-zero direction");
            } else {
                fail("unknown luminaire property '" + quoted_excerpt(w[2]) +
                     "' (expected: " + kUsage + ")");
            }
        } else if (verb == "reflectance") {
            c.kind = ScriptCommand::Kind::Reflectance;
            if (w.size() != 3 && w.size() != 5) fail("expected reflectance GROUP R or R G B");
            c.name = w[1];
            for (int k = 0; k < 3; ++k) {
                const double v = number_of(w[w.size() == 3 ? 2 : 2 + k], "reflectance");
                if (!(v >= 0 && v < 1))
                    fail("reflectance " + quoted_excerpt(w[w.size() == 3 ? 2 : 2 + k]) +
                         " must be in [0, 1)");
                c.rho[k] = v;
            }
        } else if (verb == "pick") {
            c.kind = ScriptCommand::Kind::Pick;
            arguments(2, "pick X Y (window pixel, origin top left)");
            const std::optional<long long> x = parse_integer(w[1]), y = parse_integer(w[2]);
            if (!x || !y || *x < 0 || *y < 0 || *x > 65535 || *y > 65535)
                fail("X Y must be pixel coordinates, integers >= 0");
            c.x = int(*x);
            c.y = int(*y);
        } else if (verb == "screenshot") {
            c.kind = ScriptCommand::Kind::Screenshot;
            arguments(1, "screenshot FILE.png");
            c.name = w[1];
            if (c.name.size() < 5 || c.name.substr(c.name.size() - 4) != ".png")
                fail("expected a .png file name");
        } else if (verb == "quit") {
            c.kind = ScriptCommand::Kind::Quit;
            arguments(0, "quit (no arguments)");
        } else {
            fail("unknown command '" + quoted_excerpt(verb) +
                 "' (commands: shots, luminaire, reflectance, pick, screenshot, quit)");
        }
        commands.push_back(c);
    }
    if (in.bad()) throw InputError(path, 0, "cannot read the script");
    return commands;
}

} // namespace hemirad::view
