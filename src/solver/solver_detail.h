// Small helpers shared by the solver's translation units (solver.cpp, solver_round.cpp).
// Internal header.
#pragma once

#include <glm/glm.hpp>

#include "core/timer.h"

namespace hemirad::solver_detail {

using Clock = SteadyClock;
constexpr auto since = &seconds_since; ///< seconds since a time point (core/timer.h)

/// Sum of the RGB channels (a power or radiosity summed over the spectrum).
inline double sum(const glm::dvec3& v) {
    return v.x + v.y + v.z;
}

} // namespace hemirad::solver_detail
