#include "cli/args.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "core/parse.h"
#include "hemirad/error.h"

namespace hemirad {

namespace {

// A whole decimal integer in [lo, hi], else InputError naming the option and the value.
long integer_value(const std::string& name, const std::string& v, long lo, long hi) {
    const std::optional<long long> x = parse_integer(v);
    if (!x || *x < lo || *x > hi) throw InputError(name + ": '" + v + "' is not an integer");
    return long(*x);
}

std::string shortest(double x) {
    std::ostringstream s;
    s << x;
    return s.str();
}

} // namespace

ArgParser::ArgParser(std::string program, std::string usage, std::string description)
    : program_(std::move(program)), usage_(std::move(usage)), description_(std::move(description)) {
}

void ArgParser::section(const std::string& title) {
    Opt o;
    o.name = title;
    o.is_section = true;
    opts_.push_back(o);
}

void ArgParser::flag(const std::string& name, bool* out, const std::string& help) {
    Opt o;
    o.name = name;
    o.help = help;
    o.flag = out;
    opts_.push_back(o);
}

void ArgParser::flag_off(const std::string& name, bool* out, const std::string& help) {
    Opt o;
    o.name = name;
    o.help = help;
    o.flag = out;
    o.flag_value = false;
    opts_.push_back(o);
}

void ArgParser::option(const std::string& name, std::string* out, const std::string& metavar,
                       const std::string& help) {
    Opt o{name, metavar, help, out->empty() ? "" : *out, nullptr};
    o.set = [out](const std::string& v) { *out = v; };
    opts_.push_back(o);
}

void ArgParser::option(const std::string& name, double* out, const std::string& metavar,
                       const std::string& help) {
    Opt o{name, metavar, help, shortest(*out), nullptr};
    o.set = [out, name](const std::string& v) {
        const std::optional<double> x = parse_double(v); // out of range: not one either
        if (!x || !std::isfinite(*x))
            throw InputError(name + ": '" + v + "' is not a finite number");
        *out = *x;
    };
    opts_.push_back(o);
}

void ArgParser::option(const std::string& name, long* out, const std::string& metavar,
                       const std::string& help) {
    Opt o{name, metavar, help, std::to_string(*out), nullptr};
    o.set = [out, name](const std::string& v) {
        *out = integer_value(name, v, LONG_MIN, LONG_MAX);
    };
    opts_.push_back(o);
}

void ArgParser::option(const std::string& name, int* out, const std::string& metavar,
                       const std::string& help) {
    Opt o{name, metavar, help, std::to_string(*out), nullptr};
    o.set = [out, name](const std::string& v) {
        *out = int(integer_value(name, v, INT_MIN, INT_MAX));
    };
    opts_.push_back(o);
}

void ArgParser::custom(const std::string& name, std::function<void(const std::string&)> set,
                       const std::string& metavar, const std::string& help,
                       const std::string& default_text) {
    Opt o{name, metavar, help, default_text, std::move(set)};
    opts_.push_back(o);
}

void ArgParser::multi(const std::string& name, std::vector<std::string>* out,
                      const std::string& metavar, const std::string& help) {
    Opt o{name, metavar, help, "", nullptr};
    o.set = [out](const std::string& v) { out->push_back(v); };
    opts_.push_back(o);
}

void ArgParser::positional(const std::string& name, std::string* out, const std::string& help,
                           bool required) {
    pos_.push_back({name, help, out, required});
}

bool ArgParser::given(const std::string& name) const {
    return std::find(given_.begin(), given_.end(), name) != given_.end();
}

bool ArgParser::parse(int argc, char** argv, int first) {
    std::size_t next_pos = 0;
    for (int i = first; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(help().c_str(), stdout);
            return false;
        }
        if (a.size() > 1 && a[0] == '-' && !(a.size() > 1 && (std::isdigit(a[1]) || a[1] == '.'))) {
            std::string value;
            bool has_value = false;
            const auto eq = a.find('=');
            if (eq != std::string::npos) {
                value = a.substr(eq + 1);
                a = a.substr(0, eq);
                has_value = true;
            }
            auto it = std::find_if(opts_.begin(), opts_.end(),
                                   [&](const Opt& o) { return !o.is_section && o.name == a; });
            if (it == opts_.end())
                throw InputError("unknown option '" + a + "' (see " + program_ + " --help)");
            given_.push_back(a);
            if (it->flag) {
                if (has_value) throw InputError(a + " takes no value");
                *it->flag = it->flag_value;
                continue;
            }
            if (!has_value) {
                if (i + 1 >= argc) throw InputError(a + " needs a value (" + it->metavar + ")");
                value = argv[++i];
            }
            it->set(value);
            continue;
        }
        if (next_pos >= pos_.size())
            throw InputError("unexpected argument '" + a + "' (see " + program_ + " --help)");
        *pos_[next_pos++].out = a;
    }
    for (std::size_t k = next_pos; k < pos_.size(); ++k)
        if (pos_[k].required)
            throw InputError("missing " + pos_[k].name + " (see " + program_ + " --help)");
    return true;
}

std::string ArgParser::help() const {
    std::ostringstream s;
    s << "usage: " << usage_ << "\n\n" << description_ << "\n";
    std::size_t width = 0;
    std::vector<std::string> heads;
    for (const Pos& p : pos_) width = std::max(width, p.name.size());
    for (const Opt& o : opts_)
        if (!o.is_section)
            width = std::max(width, o.name.size() + (o.metavar.empty() ? 0 : o.metavar.size() + 1));
    width += 2;
    if (!pos_.empty()) {
        s << "\narguments:\n";
        for (const Pos& p : pos_)
            s << "  " << p.name << std::string(width - p.name.size(), ' ') << p.help << "\n";
    }
    s << "\noptions:\n";
    for (const Opt& o : opts_) {
        if (o.is_section) {
            s << "\n" << o.name << ":\n";
            continue;
        }
        std::string head = o.name + (o.metavar.empty() ? "" : " " + o.metavar);
        s << "  " << head << std::string(width - head.size(), ' ') << o.help;
        if (!o.flag && !o.default_text.empty()) s << " (Default: " << o.default_text << ")";
        s << "\n";
    }
    s << "  --help" << std::string(width - 6, ' ') << "print this help and exit\n";
    return s.str();
}

} // namespace hemirad
