// Reading numbers from text: the one number parser of the tree, on std::from_chars (no
// locale, no errno, no terminating NUL needed). It reads what std::strtod and std::strtoll
// read in the "C" locale, so that every reader (command line, OBJ, MTL, IES, CSV, solution
// files, sizes) accepts the same spellings it always did: leading white space, a sign,
// decimal digits with an optional exponent, 0x and hexadecimal digits with an optional binary
// exponent (what printf's %a writes), inf, infinity, nan.
#pragma once

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <system_error>

namespace hemirad {

/// Where a number read at the start of a text ended.
struct NumberRead {
    const char* end = nullptr; ///< just after the number; the text's start if there was none
    /// Out of range (as strtod's ERANGE): the value was too large (read as +-inf, or the
    /// integer's limit) or too small (read as 0, or rounded to a subnormal double).
    bool range_error = false;
    bool found(const char* first) const { return end != first; }
};

namespace parse_detail {

inline bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}
inline bool is_hex_digit(char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

/// Skips white space and one sign; false if a second sign follows (strtod reads nothing).
inline bool skip_space_and_sign(const char*& p, const char* last, bool& negative) {
    while (p != last && is_space(*p)) ++p;
    negative = false;
    if (p != last && (*p == '+' || *p == '-')) {
        negative = *p == '-';
        ++p;
        if (p != last && (*p == '+' || *p == '-')) return false;
    }
    return true;
}

} // namespace parse_detail

/// Reads a double at the start of [first, last) as std::strtod does. Returns where it ended
/// (`first`, and `out` untouched, when there is no number). Out of range, `out` is what strtod
/// gives: +-inf for too large, 0 (or the subnormal) for too small.
inline NumberRead read_double(const char* first, const char* last, double& out) {
    using namespace parse_detail;
    const char* p = first;
    bool negative = false;
    if (!skip_space_and_sign(p, last, negative)) return {first, false};
    double v = 0;
    const bool hex = last - p >= 2 && p[0] == '0' && (p[1] == 'x' || p[1] == 'X') &&
                     ((last - p > 2 && is_hex_digit(p[2])) ||
                      (last - p > 3 && p[2] == '.' && is_hex_digit(p[3])));
    const std::from_chars_result r = hex ? std::from_chars(p + 2, last, v, std::chars_format::hex)
                                         : std::from_chars(p, last, v, std::chars_format::general);
    if (r.ec == std::errc::invalid_argument) return {first, false};
    NumberRead result{r.ptr, false};
    if (r.ec == std::errc::result_out_of_range) {
        // from_chars leaves the value alone; strtod gives inf or 0. Which one: read again with
        // the wider long double, or, beyond even that, by the exponent's sign.
        long double w = 0;
        const auto wide = std::from_chars(
            hex ? p + 2 : p, last, w, hex ? std::chars_format::hex : std::chars_format::general);
        if (wide.ec == std::errc()) {
            v = double(w);
        } else {
            bool small = false;
            for (const char* q = p; q != r.ptr; ++q)
                if ((*q == 'e' || *q == 'E' || *q == 'p' || *q == 'P') && q + 1 != r.ptr)
                    small = q[1] == '-';
            v = small ? 0.0 : HUGE_VAL;
        }
        result.range_error = true;
    } else if (!hex && v != 0 && std::abs(v) < DBL_MIN) {
        // A subnormal from decimal digits is rounded (inexact): strtod says ERANGE. One from
        // hexadecimal digits (printf's %a) is exact, and strtod does not.
        result.range_error = true;
    }
    out = negative ? -v : v;
    return result;
}

/// Reads a decimal integer at the start of [first, last) as std::strtoll does (white space, a
/// sign, digits). Out of range, `out` is the limit on that side (strtoll saturates too).
inline NumberRead read_integer(const char* first, const char* last, long long& out) {
    using namespace parse_detail;
    const char* p = first;
    bool negative = false;
    if (!skip_space_and_sign(p, last, negative)) return {first, false};
    // Read the digits as unsigned, so that the most negative value fits, then apply the sign.
    unsigned long long u = 0;
    const auto r = std::from_chars(p, last, u, 10);
    if (r.ec == std::errc::invalid_argument) return {first, false};
    constexpr unsigned long long kMax = std::numeric_limits<long long>::max();
    if (r.ec == std::errc::result_out_of_range || u > kMax + (negative ? 1 : 0)) {
        out = negative ? std::numeric_limits<long long>::min()
                       : std::numeric_limits<long long>::max();
        return {r.ptr, true};
    }
    out = negative ? (u == kMax + 1 ? std::numeric_limits<long long>::min() : -(long long)(u))
                   : (long long)(u);
    return {r.ptr, false};
}

/// Reads an unsigned decimal integer at the start of [first, last): white space, an optional
/// '+', digits (no '-': a negative count is an error, not a wrapped-around one).
inline NumberRead read_unsigned(const char* first, const char* last, unsigned long long& out) {
    using namespace parse_detail;
    const char* p = first;
    while (p != last && is_space(*p)) ++p;
    if (p != last && *p == '+') ++p;
    const auto r = std::from_chars(p, last, out, 10);
    if (r.ec == std::errc::invalid_argument) return {first, false};
    if (r.ec == std::errc::result_out_of_range) {
        out = std::numeric_limits<unsigned long long>::max();
        return {r.ptr, true};
    }
    return {r.ptr, false};
}

/// The whole of `text` as one double (read_double, and nothing after it). nullopt when it is
/// not a number, has anything after the number, or is out of range; inf and nan are numbers
/// here (callers that want finite values check).
inline std::optional<double> parse_double(std::string_view text) {
    double v = 0;
    const char* first = text.data();
    const char* last = first + text.size();
    const NumberRead r = read_double(first, last, v);
    if (!r.found(first) || r.end != last || r.range_error) return std::nullopt;
    return v;
}

/// The whole of `text` as one decimal integer (read_integer, and nothing after it): nullopt
/// when it is not one, has anything after it, or does not fit in a long long.
inline std::optional<long long> parse_integer(std::string_view text) {
    long long v = 0;
    const char* first = text.data();
    const char* last = first + text.size();
    const NumberRead r = read_integer(first, last, v);
    if (!r.found(first) || r.end != last || r.range_error) return std::nullopt;
    return v;
}

/// The whole of `text` as one unsigned decimal integer (read_unsigned, nothing after it).
inline std::optional<unsigned long long> parse_unsigned(std::string_view text) {
    unsigned long long v = 0;
    const char* first = text.data();
    const char* last = first + text.size();
    const NumberRead r = read_unsigned(first, last, v);
    if (!r.found(first) || r.end != last || r.range_error) return std::nullopt;
    return v;
}

} // namespace hemirad
