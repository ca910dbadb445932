// Command-line parsing for hemirad's tools: typed options bound to variables whose initial
// values are the defaults shown by --help (column-aligned, pbrt style).
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace hemirad {

class ArgParser {
  public:
    ArgParser(std::string program, std::string usage, std::string description);

    void flag(const std::string& name, bool* out, const std::string& help);
    /// A flag that turns a default-on setting off (e.g. --no-row-guard): sets *out = false.
    void flag_off(const std::string& name, bool* out, const std::string& help);
    void option(const std::string& name, std::string* out, const std::string& metavar,
                const std::string& help);
    void option(const std::string& name, double* out, const std::string& metavar,
                const std::string& help);
    void option(const std::string& name, int* out, const std::string& metavar,
                const std::string& help);
    void option(const std::string& name, long* out, const std::string& metavar,
                const std::string& help);
    /// An option whose value `set` parses (throwing InputError); `default_text` for --help.
    void custom(const std::string& name, std::function<void(const std::string&)> set,
                const std::string& metavar, const std::string& help,
                const std::string& default_text = "");
    /// Repeatable option; every occurrence appends.
    void multi(const std::string& name, std::vector<std::string>* out, const std::string& metavar,
               const std::string& help);
    /// Positional arguments, in order.
    void positional(const std::string& name, std::string* out, const std::string& help,
                    bool required = true);
    /// A heading between groups of options in --help.
    void section(const std::string& title);

    /// Parses argv[first..argc). Returns false if --help was given (help printed to stdout).
    /// Throws InputError for an unknown option, a missing or malformed value.
    bool parse(int argc, char** argv, int first = 1);
    /// True if the option was given on the command line.
    bool given(const std::string& name) const;
    std::string help() const;

  private:
    struct Opt {
        std::string name, metavar, help, default_text;
        std::function<void(const std::string&)> set; // null for flags
        bool* flag = nullptr;
        bool flag_value = true; ///< the value a given flag stores
        bool is_section = false;
    };
    struct Pos {
        std::string name, help;
        std::string* out;
        bool required;
    };
    std::string program_, usage_, description_;
    std::vector<Opt> opts_;
    std::vector<Pos> pos_;
    std::vector<std::string> given_;
};

} // namespace hemirad
