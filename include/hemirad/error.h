// Error channels (docs/design.md, "Error channels"): InputError for bad input (files, options,
// scene content), HEMIRAD_CHECK for broken invariants (prints the values and aborts).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

#include "hemirad/visibility.h"

namespace hemirad {

/// A number as a user wrote it, for messages: shortest round-trip form (0.5, not 0.500000).
inline std::string num(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    for (int precision = 1; precision < 17; ++precision) {
        char shorter[32];
        std::snprintf(shorter, sizeof shorter, "%.*g", precision, x);
        if (std::strtod(shorter, nullptr) == x) return shorter;
    }
    return buf;
}

/// Bad input: a file, an option or scene content that the user can fix. The message names
/// the file, line and value where they are known. Reported once, at the tool's edge.
class HEMIRAD_API InputError : public std::runtime_error {
  public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
    /// "file:line: message" (line 0 means the whole file).
    InputError(const std::string& file, int line, const std::string& message)
        : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ": " + message
                                      : file + ": " + message) {}
};

/// A failure of the environment (no GL context, a write that failed) rather than of input.
class HEMIRAD_API RuntimeError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

namespace detail {
[[noreturn]] inline void check_failed(const char* file, int line, const std::string& what) {
    std::fprintf(stderr, "%s:%d: internal check failed: %s\n", file, line, what.c_str());
    std::abort();
}
template <class A, class B>
std::string check_values(const char* a_text, const char* op, const char* b_text, const A& a,
                         const B& b) {
    std::ostringstream s;
    s << a_text << " " << op << " " << b_text << " (" << a << " vs " << b << ")";
    return s.str();
}
} // namespace detail

} // namespace hemirad

#define HEMIRAD_CHECK(cond)                                                                        \
    do {                                                                                           \
        if (!(cond)) ::hemirad::detail::check_failed(__FILE__, __LINE__, #cond);                   \
    } while (0)

#define HEMIRAD_CHECK_OP(a, op, b)                                                                 \
    do {                                                                                           \
        const auto& hemirad_a_ = (a);                                                              \
        const auto& hemirad_b_ = (b);                                                              \
        if (!(hemirad_a_ op hemirad_b_))                                                           \
            ::hemirad::detail::check_failed(                                                       \
                __FILE__, __LINE__,                                                                \
                ::hemirad::detail::check_values(#a, #op, #b, hemirad_a_, hemirad_b_));             \
    } while (0)

#define HEMIRAD_CHECK_EQ(a, b) HEMIRAD_CHECK_OP(a, ==, b)
#define HEMIRAD_CHECK_LT(a, b) HEMIRAD_CHECK_OP(a, <, b)
#define HEMIRAD_CHECK_LE(a, b) HEMIRAD_CHECK_OP(a, <=, b)
