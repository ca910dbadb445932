// The options table (solver_options.h): every user option of SolverOptions, in --help order.
// A new option of the solver or a provider is one entry here (and its field in the struct);
// the command line, solution files, Python and validation take it from here.
#include "hemirad/solver_options.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/aggregate.h"
#include "core/parse.h"
#include "hemirad/error.h"
#include "hemirad/patch.h"
#include "hemirad/provider.h"
#include "hemirad/solver.h"

namespace hemirad {

namespace {

using Check = SolverOption::Check;
using Range = SolverOption::Range;

constexpr const char* kSolver = "solver";
constexpr const char* kFormFactors = "form factors";

// The field of SolverOptions at `path` (o.path).
#define HEMIRAD_FIELD(path) [](SolverOptions& o) -> SolverOption::Field { return &o.path; }

const SolverOption kTable[] = {
    // --- solver ---------------------------------------------------------------------
    {.flag = "--ff",
     .metavar = "METHOD",
     .unit = "",
     .help = "form factors: hybrid, analytic, hemicube (GPU); reference, pdm, sr (CPU)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(ff)}, // make_provider() checks the name
    {.flag = "--tolerance",
     .metavar = "T",
     .unit = "",
     .help = "stop when the error bound is under T times the emitted power",
     .section = kSolver,
     .field = HEMIRAD_FIELD(tolerance),
     .saved = false,
     .check = Check::Solver,
     .range = {.lo = 0, .hi = 1, .lo_open = true, .hi_open = true}},
    {.flag = "--max-shots",
     .metavar = "N",
     .unit = "shots",
     .help = "stop after N shots",
     .section = kSolver,
     .field = HEMIRAD_FIELD(max_shots),
     .saved = false,
     .check = Check::Solver,
     .range = {.lo = 0}},
    {.flag = "--time-limit",
     .metavar = "S",
     .unit = "s",
     .help = "stop after S seconds (0 = no limit)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(time_limit),
     .saved = false,
     .check = Check::Solver,
     .range = {.lo = 0}},
    {.flag = "--patch-size",
     .metavar = "S",
     .unit = "scene units",
     .help = "leaf patch size in scene units (0 = scene diagonal / 64)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(hierarchy.patch_size)},
    {.flag = "--max-depth",
     .metavar = "D",
     .unit = "",
     .help = "deepest quadtree level (0..11)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(hierarchy.max_depth),
     .check = Check::Solver,
     .range = {.lo = 0, .hi = kMaxDepth}},
    {.flag = "--shooter-power",
     .metavar = "F",
     .unit = "",
     .help = "shooter descent stops before a child with less than F of the unshot power",
     .section = kSolver,
     .field = HEMIRAD_FIELD(shooter_power_fraction),
     .check = Check::Solver,
     .range = {.lo = 0, .hi = 1, .lo_open = true}},
    {.flag = "--shooter-size",
     .metavar = "S",
     .unit = "scene units",
     .help = "shooter descent stops before a child smaller than S (0 = half a leaf)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(shooter_min_size),
     .check = Check::Solver,
     .range = {.lo = 0}},
    {.flag = "--shooter-max-size",
     .metavar = "S",
     .unit = "scene units",
     .help = "shooter descent always goes below nodes larger than S (0 = no limit)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(shooter_max_size),
     .check = Check::Solver,
     .range = {.lo = 0}},
    {.flag = "--flat",
     .metavar = "",
     .unit = "",
     .help = "shoot from leaf patches only (no hierarchy)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(flat)},
    {.flag = "--no-row-guard",
     .metavar = "",
     .unit = "",
     .help = "keep form-factor rows that sum above 1 (by default they are rescaled to 1)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(row_guard),
     .inverted = true},
    {.flag = "--enclosed-fraction",
     .metavar = "F",
     .unit = "",
     .help = "shoot the children of a shooter whose hemisphere is more than F backs of "
             "polygons",
     .section = kSolver,
     .field = HEMIRAD_FIELD(enclosed_fraction),
     .check = Check::Solver,
     .range = {.lo = 0, .hi = 1, .lo_open = true}},
    {.flag = "--shooter-parallax",
     .metavar = "F",
     .unit = "",
     .help = "shoot a node's children instead of the node when its view changes across "
             "its area by more than this share of its form factor (0 = never)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(shooter_parallax),
     .check = Check::Solver,
     .range = {.lo = 0, .finite = true, .note = " (0 = never refine for parallax)"}},
    {.flag = "--row-refine",
     .metavar = "E",
     .unit = "",
     .help = "shoot a node's children (a leaf: its quarters) instead of the node when its form "
             "factors sum to more than 1 + E with surfaces nearer than its size in view "
             "(0 = never)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(row_refine),
     .check = Check::Solver,
     .range = {.lo = 0, .finite = true, .note = " (0 = never refine for the row sum)"}},
    {.flag = "--clusters",
     .metavar = "auto|on|off",
     .unit = "",
     .help = "shoot groups of nearby polygons at once when their power is spread over many "
             "small polygons (GPU form factors): each shoots as one point, or a flat one as the "
             "rectangle around it; auto: in scenes of more than 4096 polygons",
     .section = kSolver,
     .field = HEMIRAD_FIELD(clusters),
     .check = Check::Solver,
     .choices = "auto|on|off"},
    {.flag = "--cluster-parallax",
     .metavar = "F",
     .unit = "",
     .help = "shoot a cluster's two halves instead of the cluster when the share of its light "
             "it misplaces (parallax, light it sends close to itself) times its power exceeds F "
             "times the emitted power (0 = never)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(cluster_parallax),
     .check = Check::Solver,
     .range = {.lo = 0, .finite = true, .note = " (0 = never refine clusters)"}},
    {.flag = "--light-layers",
     .metavar = "auto|on|off",
     .unit = "",
     .help = "keep each luminaire's share of the solution apart, so that dimming or switching "
             "off a luminaire later (--luminaire-multiplier, with --resume) needs no shot; "
             "auto: for 1 to 16 luminaires whose layers fit in 256 MB, without clusters",
     .section = kSolver,
     .field = HEMIRAD_FIELD(light_layers),
     .saved = false, // a saved solution's layers are in its state (solution_file.h)
     .check = Check::Solver,
     .choices = "auto|on|off"},
    {.flag = "--memory-limit",
     .metavar = "SIZE",
     .unit = "bytes",
     .help = "refuse a discretisation whose estimated memory exceeds SIZE (bytes, or 512M, "
             "4G, ...; 0 = the memory available: MemAvailable, or the cgroup limit if "
             "lower)",
     .section = kSolver,
     .field = HEMIRAD_FIELD(memory_limit),
     .size = true,
     .saved = false}, // the memory guard, memory_guard.h
    // --- form factors ---------------------------------------------------------------
    {.flag = "--resolution",
     .metavar = "N",
     .unit = "pixels",
     .help = "GPU: fixed hemicube resolution (0 = adaptive)",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.resolution),
     .check = Check::Gpu,
     .range = {.lo = 16, .hi = 4096, .even = true, .zero_ok = true}},
    {.flag = "--min-resolution",
     .metavar = "N",
     .unit = "pixels",
     .help = "GPU: adaptive resolution for the weakest shooters",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.min_resolution),
     .check = Check::Gpu,
     .range = {.lo = 16, .hi = 4096, .even = true}},
    {.flag = "--max-resolution",
     .metavar = "N",
     .unit = "pixels",
     .help = "GPU: adaptive resolution for the strongest shooters",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.max_resolution),
     .check = Check::Gpu,
     .range = {.lo = 16, .hi = 4096, .even = true}},
    {.flag = "--lod-bias",
     .metavar = "B",
     .unit = "mip levels",
     .help = "GPU: mip LOD bias (+1 links patches twice as large)",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.lod_bias),
     .check = Check::Gpu,
     .range = {.lo = -16, .hi = 16}},
    {.flag = "--atan-angle",
     .metavar = "",
     .unit = "",
     .help = "GPU: GLSL atan(|a x b|, a.b) for angles (most precise)",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.atan_angle)},
    {.flag = "--builtin-acos",
     .metavar = "",
     .unit = "",
     .help = "GPU: GLSL acos instead of the 2048-entry lookup table",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.builtin_acos)},
    {.flag = "--backend",
     .metavar = "NAME",
     .unit = "",
     .help = "GL backend: auto, egl, osmesa",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.backend),
     .saved = false}, // gl::parse_backend() checks the name
    {.flag = "--device",
     .metavar = "N",
     .unit = "",
     .help = "EGL device index (-1 = default)",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.gpu.device),
     .saved = false},
    {.flag = "--link-angle",
     .metavar = "A",
     .unit = "rad",
     .help = "CPU: refine receivers while size/distance exceeds A",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.cpu.link_angle),
     .check = Check::Cpu,
     .range = {.lo = 0, .hi = 1, .lo_open = true}},
    {.flag = "--visibility-samples",
     .metavar = "N",
     .unit = "",
     .help = "reference: NxN shooter points for ray-cast visibility",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.cpu.visibility_samples),
     .check = Check::Cpu,
     .range = {.lo = 1, .hi = 16}},
    {.flag = "--gauss-order",
     .metavar = "N",
     .unit = "",
     .help = "pdm: Gauss-Legendre order",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.cpu.gauss_order),
     .check = Check::Cpu,
     .range = {.lo = 1, .hi = 16}},
    {.flag = "--sr-rays",
     .metavar = "N",
     .unit = "rays",
     .help = "sr: rays per sample point",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.cpu.sr_rays),
     .check = Check::Cpu,
     .range = {.lo = 1}},
    {.flag = "--sr-points",
     .metavar = "N",
     .unit = "points",
     .help = "sr: sample points per shooter",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.cpu.sr_points),
     .check = Check::Cpu,
     .range = {.lo = 1}},
    {.flag = "--seed",
     .metavar = "S",
     .unit = "",
     .help = "sr: random seed (reproducible)",
     .section = kFormFactors,
     .field = HEMIRAD_FIELD(provider.cpu.seed)},
};

#undef HEMIRAD_FIELD

// Every field of the options structs is an option of the table, but for the nested structs
// themselves and GpuProviderOptions::use_current_context (a program's choice, not a user's):
// a field added without an entry fails to compile here.
constexpr std::size_t kOptionFields = field_count<SolverOptions>() - 2 // provider, hierarchy
                                      + field_count<HierarchyOptions>() +
                                      field_count<ProviderOptions>() - 2      // cpu, gpu
                                      + field_count<GpuProviderOptions>() - 1 // current context
                                      + field_count<CpuProviderOptions>();
static_assert(kOptionFields == sizeof(kTable) / sizeof(kTable[0]),
              "a field of SolverOptions, HierarchyOptions, GpuProviderOptions or "
              "CpuProviderOptions has no entry in the options table (kTable in "
              "src/solver/solver_options.cpp): add one there");

const std::vector<SolverOption>& table() {
    static const std::vector<SolverOption> t(std::begin(kTable), std::end(kTable));
    return t;
}

std::string hex(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%a", v);
    return buf;
}

bool is_integer_field(const SolverOption::Field& f) {
    return std::holds_alternative<int*>(f) || std::holds_alternative<long*>(f);
}

/// The option's value as a double (numbers only), for range checks and messages.
double number(const SolverOption::Field& f) {
    if (auto p = std::get_if<double*>(&f)) return **p;
    if (auto p = std::get_if<int*>(&f)) return **p;
    if (auto p = std::get_if<long*>(&f)) return double(**p);
    if (auto p = std::get_if<std::uint64_t*>(&f)) return double(**p);
    return 0;
}

std::string bound(double x) {
    return num(x);
}

} // namespace

std::string SolverOption::key() const {
    std::string k = flag;
    if (k.rfind("--", 0) == 0) k = k.substr(2);
    for (char& c : k)
        if (c == '-') c = '_';
    return k;
}

std::string SolverOption::text(const SolverOptions& o) const {
    const Field f = field(const_cast<SolverOptions&>(o));
    if (auto p = std::get_if<std::string*>(&f)) return **p;
    if (auto p = std::get_if<double*>(&f)) return hex(**p);
    if (auto p = std::get_if<int*>(&f)) return std::to_string(**p);
    if (auto p = std::get_if<long*>(&f)) return std::to_string(**p);
    if (auto p = std::get_if<bool*>(&f)) return (**p != inverted) ? "1" : "0";
    return std::to_string(*std::get<std::uint64_t*>(f));
}

bool SolverOption::set_text(SolverOptions& o, const std::string& text) const {
    const Field f = field(o);
    if (auto p = std::get_if<std::string*>(&f)) {
        **p = text;
    } else if (auto p = std::get_if<double*>(&f)) {
        const std::optional<double> v = parse_double(text);
        if (!v || !std::isfinite(*v)) return false;
        **p = *v;
    } else if (is_integer_field(f)) {
        const std::optional<long long> v = parse_integer(text);
        if (!v) return false;
        if (auto pi = std::get_if<int*>(&f))
            **pi = int(*v);
        else
            *std::get<long*>(f) = long(*v);
    } else if (auto p = std::get_if<bool*>(&f)) {
        if (text != "0" && text != "1") return false;
        **p = (text == "1") != inverted;
    } else {
        const std::optional<unsigned long long> v = parse_unsigned(text);
        if (!v) return false;
        *std::get<std::uint64_t*>(f) = *v;
    }
    return true;
}

std::string SolverOption::range_text() const {
    const bool has_lo = range.lo > -Range::kNone, has_hi = range.hi < Range::kNone;
    if (has_lo && has_hi) {
        if (!range.lo_open && !range.hi_open) return bound(range.lo) + ".." + bound(range.hi);
        return std::string(range.lo_open ? "(" : "[") + bound(range.lo) + ", " + bound(range.hi) +
               (range.hi_open ? ")" : "]");
    }
    if (has_lo) return std::string(range.lo_open ? "> " : ">= ") + bound(range.lo);
    if (has_hi) return std::string(range.hi_open ? "< " : "<= ") + bound(range.hi);
    return "any value";
}

void SolverOption::validate(const SolverOptions& o) const {
    if (check == Check::None) return;
    const Field f = field(const_cast<SolverOptions&>(o));
    if (const std::string* const* text = std::get_if<std::string*>(&f)) {
        const std::string all = std::string("|") + choices + "|";
        if (*choices && all.find("|" + **text + "|") == std::string::npos)
            throw InputError(std::string(flag) + " '" + **text + "' must be one of " + choices);
        return;
    }
    const double x = number(f);
    if (range.zero_ok && x == 0) return;
    bool ok = (range.lo_open ? x > range.lo : x >= range.lo) &&
              (range.hi_open ? x < range.hi : x <= range.hi) && (!range.finite || std::isfinite(x));
    if (range.even && is_integer_field(f)) ok = ok && std::fmod(x, 2.0) == 0;
    if (ok) return;
    if (check == Check::Cpu) { // the providers' own wording, by the field's name
        std::ostringstream m;
        m << "form-factor option " << key() << " = " << x << " is out of range " << range_text();
        throw InputError(m.str());
    }
    const std::string value = is_integer_field(f) ? std::to_string((long long)x) : num(x);
    const bool both = range.lo > -Range::kNone && range.hi < Range::kNone;
    const std::string what = range.even ? "an even number in " + range_text()
                             : both     ? "in " + range_text()
                                        : range_text();
    throw InputError(std::string(flag) + " " + value + " must be " + what + range.note);
}

const std::vector<SolverOption>& solver_option_table() {
    return table();
}

const SolverOption* find_solver_option(std::string_view name) {
    for (const SolverOption& o : table())
        if (name == o.flag || name == o.key()) return &o;
    return nullptr;
}

void validate_solver_options(const SolverOptions& o, SolverOption::Check check) {
    for (const SolverOption& opt : table())
        if (opt.check == check) opt.validate(o);
}

void validate_gpu_options(const GpuProviderOptions& options) {
    SolverOptions o;
    o.provider.gpu = options;
    validate_solver_options(o, Check::Gpu);
    if (options.min_resolution > options.max_resolution) {
        const SolverOption& lo = *find_solver_option("min_resolution");
        const SolverOption& hi = *find_solver_option("max_resolution");
        throw InputError(std::string(lo.flag) + " " + std::to_string(options.min_resolution) +
                         " exceeds " + hi.flag + " " + std::to_string(options.max_resolution));
    }
}

} // namespace hemirad
