// hemirad-bench experiment incremental (incremental.cpp).
#pragma once

#include <string>

namespace hemirad::bench {

/// Incremental re-solving (issue 21) on the office walk-through (`office_json`,
/// assets/lighting/office.json): the scene converged to a 0.1 % bound, then downlight D2
/// switched off and spot S1 halved (Solver::set_luminaire_multiplier) and re-converged, against
/// a fresh solve of the edited project (D2 removed from the scene, S1's multiplier halved):
/// shots and seconds of each, and the largest difference of the 12x8 floor grid (final
/// gather) between the two. Prints its "JSON ..." and "ROW ..." lines.
void run_incremental(const std::string& office_json);

} // namespace hemirad::bench
