// Small helpers shared by the solver's translation units (solver.cpp, solver_round.cpp).
// Internal header.
#pragma once

#include <chrono>

#include <glm/glm.hpp>

namespace hemirad::solver_detail {

using Clock = std::chrono::steady_clock;

/// Seconds since t0.
inline double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Sum of the RGB channels (a power or radiosity summed over the spectrum).
inline double sum(const glm::dvec3& v) {
    return v.x + v.y + v.z;
}

} // namespace hemirad::solver_detail
