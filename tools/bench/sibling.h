// The tools built beside hemirad-bench (hemirad, hemirad-view), which some experiments run.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

#include "hemirad/error.h"

namespace hemirad::bench {

/// The path of the tool `name` in hemirad-bench's own folder; RuntimeError naming `who` when
/// it is not there.
inline std::string sibling_tool(const std::string& name, const std::string& who) {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0) throw RuntimeError(who + ": cannot read /proc/self/exe");
    buf[n] = 0;
    const std::filesystem::path p = std::filesystem::path(buf).parent_path() / name;
    if (!std::filesystem::exists(p))
        throw RuntimeError(who + ": no " + name + " next to hemirad-bench: " + p.string());
    return p.string();
}

} // namespace hemirad::bench
