// Reading the text of photometric files (IES LM-63: ies_reader.cpp; EULUMDAT:
// eulumdat_reader.cpp): the file's lines, and a reader of the numbers that follow a header, each
// with its line for messages.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/parse.h"
#include "hemirad/error.h"

namespace hemirad::photometric {

/// The whole file; InputError naming `what` ("IES file") when it cannot be opened.
inline std::string read_text(const std::string& path, const char* what) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, std::string("cannot open ") + what);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The lines of `text` without their CR LF or LF, a UTF-8 byte order mark dropped.
inline std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    std::string l;
    while (std::getline(in, l)) {
        if (!l.empty() && l.back() == '\r') l.pop_back();
        lines.push_back(l);
    }
    if (!lines.empty() && lines[0].rfind("\xEF\xBB\xBF", 0) == 0) lines[0].erase(0, 3);
    return lines;
}

inline std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return "";
    const auto b = s.find_last_not_of(" \t\r\n");
    return s.substr(a, b - a + 1);
}

inline std::string upper(std::string s) {
    for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

/// A number for messages, as short as "%g" but to 10 digits (180, not 1.8e+02).
inline std::string format_number(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", x);
    return buf;
}

/// "path:line: " (line 0: "path: "), the start of a warning.
inline std::string where(const std::string& path, int line) {
    std::string s = path;
    if (line > 0) {
        s += ':';
        s += std::to_string(line);
    }
    s += ": ";
    return s;
}

[[noreturn]] inline void fail(const std::string& path, int line, const std::string& what,
                              const std::string& value, const std::string& why) {
    throw InputError(path, line, what + " " + value + ": " + why);
}

struct Token {
    std::string text;
    int line = 0; ///< 1-based
};

/// The blank-separated values of lines [first, end) of `lines` (also separated by commas
/// when `comma_separates`).
inline std::vector<Token> tokens(const std::vector<std::string>& lines, std::size_t first,
                                 bool comma_separates) {
    std::vector<Token> out;
    for (std::size_t i = first; i < lines.size(); ++i) {
        std::string l = lines[i];
        for (char& c : l)
            if ((comma_separates && c == ',') || c == '\t' || c == '\r') c = ' ';
        std::istringstream in(l);
        std::string t;
        while (in >> t) out.push_back({t, int(i) + 1});
    }
    return out;
}

/// Reads finite numbers from a list of tokens; every message names the file and the line.
class Reader {
  public:
    /// `decimal_comma`: "0,5" is 0.5 (EULUMDAT files written in a European locale).
    Reader(std::vector<Token> tokens, const std::string& path, int last_line,
           bool decimal_comma = false)
        : tokens_(std::move(tokens)), path_(path), last_line_(last_line),
          decimal_comma_(decimal_comma) {}

    /// The next value as a finite number; `what` names it in messages.
    double number(const std::string& what, int& line) {
        if (next_ >= tokens_.size())
            throw InputError(path_, last_line_, "the file ends where " + what + " was expected");
        const Token& t = tokens_[next_++];
        line = t.line;
        return parse(t, what);
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
                             what + ": expected a whole number, got '" + last_text() + "'");
        return int(x);
    }
    int integer(const std::string& what) {
        int line;
        return integer(what, line);
    }
    /// `t` as a finite number (InputError naming `what` otherwise).
    double parse(const Token& t, const std::string& what) const {
        std::string s = t.text;
        if (decimal_comma_)
            for (char& c : s)
                if (c == ',') c = '.';
        double x = 0; // out of range: inf (refused) or 0, as strtod reads it
        const char* b = s.data();
        const NumberRead r = read_double(b, b + s.size(), x);
        if (!r.found(b) || r.end != b + s.size() || !std::isfinite(x))
            throw InputError(path_, t.line, what + ": expected a number, got '" + t.text + "'");
        return x;
    }
    const std::string& last_text() const { return tokens_[next_ - 1].text; }
    bool done() const { return next_ >= tokens_.size(); }
    std::size_t remaining() const { return tokens_.size() - next_; }
    const Token& peek() const { return tokens_[next_]; }

  private:
    std::vector<Token> tokens_;
    std::size_t next_ = 0;
    std::string path_;
    int last_line_;
    bool decimal_comma_;
};

/// Reads a table of rows x cols values >= 0, row-major, each times `scale`; `label(row, col)`
/// names a value in messages ("candela value 3 of plane 2 (C = 90)"), `what` ("candela value")
/// a negative one.
template <class Label>
std::vector<double> read_table(Reader& r, const std::string& path, int rows, int cols, double scale,
                               const char* what, const Label& label) {
    std::vector<double> out;
    // Memory bounded by the file: a table larger than what is left ends in an error anyway.
    out.reserve(std::min(std::size_t(rows) * std::size_t(cols), r.remaining()));
    int line = 0;
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            const double x = r.number(label(i, j), line);
            if (x < 0) fail(path, line, what, r.last_text(), "must be >= 0");
            out.push_back(x * scale);
        }
    return out;
}

/// InputError at the first value after the table, if any: "'x' after the last of the N
/// `values` (`shape`): the counts do not match the table".
inline void expect_end(const Reader& r, const std::string& path, const std::string& values,
                       const std::string& shape) {
    if (!r.done())
        throw InputError(path, r.peek().line,
                         "'" + r.peek().text + "' after the last of the " + values + " (" + shape +
                             "): the counts do not match the table");
}

} // namespace hemirad::photometric
