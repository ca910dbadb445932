// The edge of a tool, where errors are reported once (docs/design.md, "Error channels"):
// "TOOL: message" on stderr, exit status 2 for bad input (InputError), 1 for a failure of the
// environment or anything else. (hemirad itself does this in its main(), across MPI ranks.)
#pragma once

#include <cstdio>
#include <exception>

#include "hemirad/error.h"

namespace hemirad {

/// Returns what `run()` returns, or the exit status of the error it threw, reported.
template <class Run> int run_tool(const char* tool, Run&& run) {
    try {
        return run();
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s: %s\n", tool, e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", tool, e.what());
        return 1;
    }
}

} // namespace hemirad
