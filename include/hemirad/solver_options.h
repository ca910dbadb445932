// The options table: every option of SolverOptions that a user sets, once, with its name,
// type, default, range, unit and help (after pbrt-v4's src/pbrt/options.h). Everything that
// names an option is derived from it:
//
//   - the command line: `--shooter-parallax F` (hemirad solve, batch, the preview and the
//     viewer; tools/common/cli/cli_options.cpp), with the help text and the default;
//   - solution files: the options that change results, saved under the same spelling
//     (solution_file.h), and read back by it;
//   - Python: `hemirad.Solver(scene, shooter_parallax=...)`, the flag's snake_case;
//   - validation: validate_options() and the providers check the ranges given here, and name
//     the option as the command line spells it.
//
// Adding an option is one field in SolverOptions (or HierarchyOptions, GpuProviderOptions,
// CpuProviderOptions) and one entry in the table (src/solver/solver_options.cpp); a test
// (tests/solver_options_test.cpp) fails when a field has no entry.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "hemirad/visibility.h"

namespace hemirad {

struct SolverOptions;

/// One user option of SolverOptions.
struct HEMIRAD_API SolverOption {
    /// Where the option's value lives: a pointer to its field of a SolverOptions. Switches
    /// are bool fields (see `inverted`), Bytes an std::uint64_t (--memory-limit: 512M, 4G).
    using Field = std::variant<std::string*, double*, int*, long*, bool*, std::uint64_t*>;
    /// Who checks the range: validate_options() (Solver), validate_gpu_options() (Gpu, for the
    /// GPU providers), make_cpu_provider() (Cpu), or nobody (None: checked where the value is
    /// used, e.g. --ff, --backend, --memory-limit).
    enum class Check { None, Solver, Gpu, Cpu };
    /// The values allowed, for Check != None: lo..hi, each end open or closed.
    struct Range {
        static constexpr double kNone = std::numeric_limits<double>::infinity();
        double lo = -kNone, hi = kNone; ///< -inf, +inf: no bound on that side
        bool lo_open = false, hi_open = false;
        bool finite = false;   ///< also refuse +-inf (where no upper bound would)
        bool even = false;     ///< integers: even ones only
        bool zero_ok = false;  ///< 0 is allowed outside the range ("0 = adaptive")
        const char* note = ""; ///< appended to the message, e.g. " (0 = never ...)"
    };

    const char* flag;    ///< the command line's and solution files' name: "--shooter-parallax"
    const char* metavar; ///< the value in --help ("F"); "" for a switch
    const char* unit;    ///< of the value: "scene units", "s", "bytes", "pixels"; "" if none
    const char* help;    ///< the --help text (the parser appends the default)
    const char* section; ///< the --help heading: "solver" or "form factors"
    Field (*field)(SolverOptions&); ///< the field the option sets
    /// A switch that turns its field off (--no-row-guard): the option's value is !field.
    bool inverted = false;
    /// An std::uint64_t given as a size: bytes, or with K, M, G, T (parse_memory_size).
    bool size = false;
    /// Saved in solution files (it changes results). Not saved: the stop criteria and where a
    /// solve runs, free to change on resume.
    bool saved = true;
    Check check = Check::None;
    Range range = {};
    /// A text option's values, separated by '|' ("auto|on|off"); "" for any text. Checked
    /// like a range (Check != None).
    const char* choices = "";

    /// The Python keyword: the flag without "--", '-' as '_' ("shooter_parallax").
    std::string key() const;
    /// The option's value in `o`, exactly, as solution files hold it: doubles in hexadecimal
    /// (%a), integers in decimal, switches "0" or "1", text as it is.
    std::string text(const SolverOptions& o) const;
    /// Sets the option in `o` from text() form. Returns false (and leaves `o` alone) if `text`
    /// is not a value of this option's type.
    bool set_text(SolverOptions& o, const std::string& text) const;
    /// The range in messages: "(0, 1]", "0..11", ">= 0".
    std::string range_text() const;
    /// Throws InputError if the value in `o` is outside the range, naming the option as the
    /// command line spells it: "--tolerance 2 must be in (0, 1)". Nothing for Check::None.
    void validate(const SolverOptions& o) const;
};

/// Every user option, in the order of --help.
HEMIRAD_API const std::vector<SolverOption>& solver_option_table();
/// The option spelled `name`, as a flag ("--shooter-parallax") or a key ("shooter_parallax");
/// nullptr if there is none.
HEMIRAD_API const SolverOption* find_solver_option(std::string_view name);
/// Checks every option of `o` whose Check is `check` (validate_options() and the providers
/// call it). Throws InputError for the first, in table order, that is out of range.
HEMIRAD_API void validate_solver_options(const SolverOptions& o, SolverOption::Check check);

} // namespace hemirad
