// Reading text files line by line with a bound on each line, so that a file that is not text
// (a binary, /dev/zero, a 100 MB line) is refused with a message instead of filling memory.
#pragma once

#include <cstddef>
#include <istream>
#include <string>

namespace hemirad {

/// Reads one line (without its '\n') into `line`. Returns false at the end of the input with
/// nothing read. Sets `too_long` (and stops reading that line) when it exceeds `max_bytes`;
/// `has_nul` when it holds a NUL byte.
inline bool read_bounded_line(std::istream& in, std::string& line, std::size_t max_bytes,
                              bool& too_long, bool& has_nul) {
    line.clear();
    too_long = has_nul = false;
    std::streambuf* sb = in.rdbuf();
    bool any = false;
    for (;;) {
        const int c = sb->sbumpc();
        if (c == std::char_traits<char>::eof()) {
            in.setstate(std::ios::eofbit);
            return any;
        }
        any = true;
        if (c == '\n') return true;
        if (c == '\0') has_nul = true;
        if (line.size() >= max_bytes) {
            too_long = true;
            return true;
        }
        line.push_back(char(c));
    }
}

/// A value from a file for a message: at most 60 bytes, control bytes as \xNN.
inline std::string quoted_excerpt(const std::string& s) {
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (std::size_t i = 0; i < s.size() && i < 60; ++i) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        if (c < 0x20 || c == 0x7f) {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else {
            out += char(c);
        }
    }
    if (s.size() > 60) out += "...";
    return out;
}

} // namespace hemirad
