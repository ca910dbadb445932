// The options table (hemirad/solver_options.h) against the structs it describes and the
// places derived from it: every field of SolverOptions (and the nested HierarchyOptions,
// GpuProviderOptions, CpuProviderOptions) is one option; every option set to a value other
// than its default comes back the same through the command line (ArgParser with
// add_solver_options) and, where it changes results, through a solution file. Python's
// keywords are checked by tests/cli/python.sh. A new field without an entry fails here (and
// in the static_assert of src/solver/solver_options.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "cli/args.h"
#include "cli/cli_options.h"
#include "core/aggregate.h"
#include "hemirad/error.h"
#include "hemirad/provider.h"
#include "hemirad/solution_file.h"
#include "hemirad/solver.h"
#include "hemirad/solver_options.h"

using namespace hemirad;

namespace {

const std::vector<SolverOption>& table() {
    return solver_option_table();
}

/// A value of `option` other than its default, as the command line writes it ("" for a
/// switch, which is given or not).
std::string other_value(const SolverOption& option) {
    SolverOptions o;
    const SolverOption::Field f = option.field(o);
    if (auto p = std::get_if<std::string*>(&f)) return **p == "pdm" ? "sr" : "pdm";
    if (auto p = std::get_if<double*>(&f)) return num(**p + 0.375);
    if (auto p = std::get_if<int*>(&f)) return std::to_string(**p + 2);
    if (auto p = std::get_if<long*>(&f)) return std::to_string(**p + 2);
    if (std::holds_alternative<bool*>(f)) return "";
    return std::to_string(*std::get<std::uint64_t*>(f) + 4096);
}

/// Options with every option at other_value().
SolverOptions all_other() {
    SolverOptions o;
    for (const SolverOption& option : table()) {
        const std::string v = other_value(option);
        EXPECT_TRUE(option.set_text(o, v.empty() ? "1" : v)) << option.flag << " " << v;
    }
    return o;
}

TEST(SolverOptions, EveryFieldIsAnOption) {
    // Fields of the structs, less the nested structs themselves and the one field that is a
    // program's choice (GpuProviderOptions::use_current_context, the viewer's).
    const std::size_t fields = field_count<SolverOptions>() - 2 + field_count<HierarchyOptions>() +
                               field_count<ProviderOptions>() - 2 +
                               field_count<GpuProviderOptions>() - 1 +
                               field_count<CpuProviderOptions>();
    EXPECT_EQ(fields, table().size())
        << "a field of the solver's options has no entry in the options table "
           "(src/solver/solver_options.cpp), or an entry has no field";
    // Each option its own field, inside SolverOptions.
    SolverOptions o;
    std::set<const void*> addresses;
    for (const SolverOption& option : table()) {
        const void* p =
            std::visit([](auto* q) { return static_cast<const void*>(q); }, option.field(o));
        EXPECT_GE(p, static_cast<const void*>(&o)) << option.flag;
        EXPECT_LT(p, static_cast<const void*>(&o + 1)) << option.flag;
        EXPECT_TRUE(addresses.insert(p).second) << option.flag << " shares a field";
    }
    // Names: flags and keys unique, keys the flags' snake_case.
    std::set<std::string> flags, keys;
    for (const SolverOption& option : table()) {
        EXPECT_TRUE(flags.insert(option.flag).second) << option.flag;
        EXPECT_TRUE(keys.insert(option.key()).second) << option.key();
        std::string spelled = "--" + option.key();
        std::replace(spelled.begin(), spelled.end(), '_', '-');
        EXPECT_EQ(spelled, option.flag);
        EXPECT_EQ(find_solver_option(option.flag), &option);
        EXPECT_EQ(find_solver_option(option.key()), &option);
    }
    EXPECT_EQ(find_solver_option("shooter_parallax")->flag, std::string("--shooter-parallax"));
    EXPECT_EQ(find_solver_option("--no-such-option"), nullptr);
}

TEST(SolverOptions, EachOptionSetsItsOwnField) {
    const SolverOptions defaults;
    for (const SolverOption& option : table()) {
        SolverOptions o;
        const std::string v = other_value(option);
        ASSERT_TRUE(option.set_text(o, v.empty() ? "1" : v)) << option.flag;
        EXPECT_NE(option.text(o), option.text(defaults)) << option.flag << " changed nothing";
        for (const SolverOption& other : table()) {
            if (&other == &option) continue;
            EXPECT_EQ(other.text(o), other.text(defaults))
                << option.flag << " changed " << other.flag;
        }
    }
}

TEST(SolverOptions, CommandLineSetsEveryOption) {
    std::vector<std::string> words{"test"};
    for (const SolverOption& option : table()) {
        words.push_back(option.flag);
        const std::string v = other_value(option);
        if (!v.empty()) words.push_back(v);
    }
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    SolverOptions parsed;
    ArgParser args("test", "test [options]", "");
    add_solver_options(args, parsed);
    ASSERT_TRUE(args.parse(int(argv.size()), argv.data()));
    const SolverOptions expected = all_other();
    for (const SolverOption& option : table())
        EXPECT_EQ(option.text(parsed), option.text(expected)) << option.flag;
    // --help shows every option with its default.
    const std::string help = args.help();
    for (const SolverOption& option : table())
        EXPECT_NE(help.find(std::string("  ") + option.flag), std::string::npos) << option.flag;
    EXPECT_NE(help.find("(Default: 0.0003)"), std::string::npos) << "--shooter-parallax";
}

TEST(SolverOptions, SolutionFilesKeepEveryOptionThatChangesResults) {
    const SolverOptions expected = all_other();
    const std::vector<SolutionOption> saved = solution_options(expected);
    SolverOptions back;
    for (const SolutionOption& s : saved) apply_solution_option(back, s, "test.bin");
    std::set<std::string> not_saved;
    for (const SolverOption& option : table()) {
        if (option.saved)
            EXPECT_EQ(option.text(back), option.text(expected)) << option.flag;
        else
            not_saved.insert(option.flag);
    }
    // Free to change on resume: the stop criteria, where the solve runs, and whether light
    // layers are kept (the solution is the same; the file's state holds the layers or not).
    EXPECT_EQ(not_saved,
              (std::set<std::string>{"--tolerance", "--max-shots", "--time-limit", "--memory-limit",
                                     "--backend", "--device", "--light-layers"}));
    // The spelling of the files saved so far: the command line's, values exact.
    const SolverOptions defaults;
    const std::vector<SolutionOption> d = solution_options(defaults);
    ASSERT_FALSE(d.empty());
    EXPECT_EQ(d.front(), (SolutionOption{"--ff", "hybrid"}));
    bool parallax = false;
    for (const SolutionOption& s : d)
        if (s.first == "--shooter-parallax") parallax = s.second == "0x1.3a92a30553261p-12";
    EXPECT_TRUE(parallax) << "3e-4 in hexadecimal";
    EXPECT_THROW(apply_solution_option(back, {"--tolerance", "0x1p-7"}, "f"), InputError);
    EXPECT_THROW(apply_solution_option(back, {"--no-such", "1"}, "f"), InputError);
    EXPECT_THROW(apply_solution_option(back, {"--max-depth", "4.5"}, "f"), InputError);
    EXPECT_THROW(apply_solution_option(back, {"--flat", "yes"}, "f"), InputError);
}

// The messages the checks gave before the table: scripts and tests match on them.
std::string message(SolverOptions o) {
    try {
        validate_options(o);
        if (o.ff == "reference") (void)make_cpu_provider("reference", Scene{}, {}, o.provider.cpu);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(SolverOptions, ChecksTheRangesWithTheirMessages) {
    const auto with = [](auto set) {
        SolverOptions o;
        set(o);
        return message(o);
    };
    EXPECT_EQ(with([](SolverOptions& o) { o.tolerance = 2; }), "--tolerance 2 must be in (0, 1)");
    EXPECT_EQ(with([](SolverOptions& o) { o.max_shots = -1; }), "--max-shots -1 must be >= 0");
    EXPECT_EQ(
        with([](SolverOptions& o) { o.time_limit = std::numeric_limits<double>::infinity(); }), "")
        << "inf: no limit";
    EXPECT_EQ(with([](SolverOptions& o) { o.shooter_power_fraction = 0; }),
              "--shooter-power 0 must be in (0, 1]");
    EXPECT_EQ(with([](SolverOptions& o) { o.shooter_parallax = -1; }),
              "--shooter-parallax -1 must be >= 0 (0 = never refine for parallax)");
    EXPECT_NE(with([](SolverOptions& o) {
                  o.shooter_parallax = std::numeric_limits<double>::infinity();
              }),
              "");
    EXPECT_EQ(with([](SolverOptions& o) { o.hierarchy.max_depth = 12; }),
              "--max-depth 12 must be in 0..11");
    EXPECT_EQ(with([](SolverOptions& o) { o.provider.gpu.resolution = 17; }),
              "--resolution 17 must be an even number in 16..4096");
    EXPECT_EQ(with([](SolverOptions& o) { o.provider.gpu.min_resolution = 512; }),
              "--min-resolution 512 exceeds --max-resolution 256");
    EXPECT_EQ(with([](SolverOptions& o) { o.provider.gpu.lod_bias = 17; }),
              "--lod-bias 17 must be in -16..16");
    EXPECT_EQ(with([](SolverOptions& o) { o.provider.gpu.resolution = 0; }), "") << "adaptive";
    EXPECT_EQ(with([](SolverOptions& o) {
                  o.ff = "hemicube-not-checked-here";
                  o.provider.gpu.resolution = 17;
              }),
              "")
        << "GPU options are checked for GPU providers only";
    EXPECT_EQ(with([](SolverOptions& o) {
                  o.ff = "reference";
                  o.provider.cpu.link_angle = 2;
              }),
              "form-factor option link_angle = 2 is out of range (0, 1]");
    EXPECT_EQ(with([](SolverOptions& o) {
                  o.ff = "reference";
                  o.provider.cpu.sr_points = 0;
              }),
              "form-factor option sr_points = 0 is out of range >= 1");
}

} // namespace
