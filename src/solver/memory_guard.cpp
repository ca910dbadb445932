// The memory guard (see memory_guard.h for what is counted).
#include "hemirad/memory_guard.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/parse.h"
#include "hemirad/error.h"
#include "hemirad/hierarchy.h"
#include "hemirad/provider.h"
#include "hemirad/solver.h"

namespace hemirad {

namespace {

constexpr std::uint64_t kNodeBytes = sizeof(Hierarchy::Node) + 1; // + Solver's view code
constexpr std::uint64_t kGpuNodeBytes = 5 * 4; // pixel_sum_, analytic_, area_, seen_, below_seen_
/// hybrid and analytic: the scene's polygons in a BVH (ff/bvh.h: a primitive of 128 bytes, about
/// half a node of 56, a 4-byte index), whose ray casts check the centres of polygons no pixel
/// shows.
constexpr std::uint64_t kBvhPolygonBytes = 160;

/// First number on the line of /proc/meminfo that starts with `key` [bytes], or 0.
std::uint64_t meminfo(const char* key) {
    std::ifstream in("/proc/meminfo");
    std::string line;
    const std::string k = std::string(key) + ":";
    while (std::getline(in, line))
        if (line.rfind(k, 0) == 0) {
            unsigned long long kib = 0; // "MemAvailable:   16384 kB"
            read_unsigned(line.data() + k.size(), line.data() + line.size(), kib);
            return kib * 1024;
        }
    return 0;
}

/// The whole content of a small file as an unsigned number; `ok` false if unreadable or
/// not a number ("max").
std::uint64_t read_number(const char* path, bool& ok) {
    std::ifstream in(path);
    std::string s;
    ok = bool(in >> s) && !s.empty() && std::isdigit(static_cast<unsigned char>(s[0]));
    unsigned long long v = 0;
    if (ok) read_unsigned(s.data(), s.data() + s.size(), v);
    return v;
}

} // namespace

MemoryEstimate estimate_memory(const Scene& scene, const Discretisation& disc,
                               const SolverOptions& options) {
    MemoryEstimate e;
    for (std::uint8_t d : disc.depth) {
        e.nodes += tree_size(d);
        e.leaves += std::uint64_t(1) << (2 * d);
        e.deepest = std::max(e.deepest, int(d));
    }
    e.hierarchy = e.nodes * kNodeBytes;
    if (is_gpu_provider(options.ff)) {
        e.provider = e.nodes * kGpuNodeBytes;
        if (options.ff != "hemicube") e.provider += scene.polygons.size() * kBvhPolygonBytes;
        const std::uint64_t side = std::uint64_t(1) << e.deepest;
        e.gl = side * side * 8 * 4 / 3; // RGBA16UI patch IDs with mipmaps
        const GpuProviderOptions& g = options.provider.gpu;
        const std::uint64_t r =
            std::uint64_t(std::max(g.resolution ? g.resolution : g.max_resolution, 0));
        const std::uint64_t pixels = (2 * r) * (r + r / 2);
        e.gl += pixels * (16 + 4 + 16); // colour, depth, read-back
    }
    return e;
}

std::uint64_t available_memory(std::string* source) {
    std::uint64_t avail = meminfo("MemAvailable");
    std::string from = "MemAvailable in /proc/meminfo";
    // cgroup v2, then v1: the limit minus what the group already uses.
    const std::pair<const char*, const char*> groups[] = {
        {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current"},
        {"/sys/fs/cgroup/memory/memory.limit_in_bytes",
         "/sys/fs/cgroup/memory/memory.usage_in_bytes"},
    };
    for (const auto& [max_path, current_path] : groups) {
        bool ok_max = false, ok_cur = false;
        const std::uint64_t max = read_number(max_path, ok_max);
        const std::uint64_t cur = read_number(current_path, ok_cur);
        if (!ok_max || !ok_cur) continue;
        const std::uint64_t left = max > cur ? max - cur : 0;
        if (avail == 0 || left < avail) {
            avail = left;
            from = std::string("the cgroup limit (") + max_path + " minus usage)";
        }
        break;
    }
    if (source) *source = from;
    return avail;
}

std::string bytes_text(std::uint64_t b) {
    const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    if (b < 1024) return std::to_string(b) + " bytes";
    double x = double(b);
    int u = -1;
    while (x >= 1024 && u < 5) x /= 1024, ++u;
    char buf[32];
    std::snprintf(buf, sizeof buf, x < 10 ? "%.1f %s" : "%.0f %s", x, units[u]);
    return buf;
}

std::uint64_t parse_memory_size(const std::string& text, const std::string& option) {
    const auto bad = [&] {
        return InputError(option + " '" + text +
                          "': expected a size in bytes or with K, M, G, T (e.g. 512M, 4G; 0 = "
                          "the memory available)");
    };
    if (text.empty() || text.size() > 64) throw bad();
    const char* b = text.data();
    double x = 0;
    const NumberRead r = read_double(b, b + text.size(), x);
    if (!r.found(b) || r.range_error || !std::isfinite(x) || x < 0 ||
        !std::isdigit(static_cast<unsigned char>(*b)))
        throw bad();
    std::string unit(r.end, b + text.size());
    for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
    double scale = 1;
    if (!unit.empty() && unit != "B") {
        const std::string prefixes = "KMGT";
        const std::size_t k = prefixes.find(unit[0]);
        const std::string rest = unit.substr(1);
        if (k == std::string::npos || !(rest.empty() || rest == "B" || rest == "IB")) throw bad();
        scale = std::pow(1024.0, double(k + 1));
    }
    const double bytes = x * scale;
    if (!(bytes < 1.8e19)) throw bad(); // beyond 2^64
    return std::uint64_t(bytes);
}

void check_memory(const Scene& scene, const Discretisation& disc, const SolverOptions& options) {
    const MemoryEstimate e = estimate_memory(scene, disc, options);
    std::string source = "--memory-limit";
    std::uint64_t limit = options.memory_limit;
    if (limit == 0) limit = available_memory(&source);
    if (limit == 0 || e.total() <= limit) return; // nothing known, or it fits
    // The largest --max-depth that fits, with the same patch size.
    int fits = -1;
    for (int d = std::min(options.hierarchy.max_depth, int(e.deepest)) - 1; d >= 0; --d) {
        HierarchyOptions h = options.hierarchy;
        h.max_depth = d;
        if (estimate_memory(scene, discretise(scene, h), options).total() <= limit) {
            fits = d;
            break;
        }
    }
    std::string msg = "the discretisation needs about " + bytes_text(e.total()) + " (" +
                      std::to_string(e.nodes) + " nodes, " + std::to_string(e.leaves) +
                      " leaf patches, quadtrees up to depth " + std::to_string(e.deepest) +
                      ": hierarchy " + bytes_text(e.hierarchy);
    if (e.provider) msg += ", form factors " + bytes_text(e.provider);
    if (e.gl) msg += ", GL " + bytes_text(e.gl);
    msg += "), but " + bytes_text(limit) + " is available (" + source + "); ";
    if (fits >= 0)
        msg += "--max-depth " + std::to_string(fits) + " would fit (now " +
               std::to_string(options.hierarchy.max_depth) + "), or a larger --patch-size";
    else
        msg += "use a larger --patch-size or a smaller --max-depth";
    if (e.gl > e.total() / 2) msg += " or --max-resolution";
    msg += " (or --memory-limit SIZE to allow more)";
    throw InputError(msg);
}

} // namespace hemirad
