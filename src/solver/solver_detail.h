// Small helpers shared by the solver's translation units (solver.cpp, solver_round.cpp,
// incremental.cpp).
// Internal header.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "core/timer.h"
#include "hemirad/form_factors.h"
#include "hemirad/hierarchy.h"
#include "hemirad/photometry.h"

namespace hemirad::solver_detail {

using Clock = SteadyClock;
constexpr auto since = &seconds_since; ///< seconds since a time point (core/timer.h)

/// Sum of the RGB channels (a power or radiosity summed over the spectrum).
inline double sum(const glm::dvec3& v) {
    return v.x + v.y + v.z;
}

/// Sum of the channels' magnitudes: how much unshot power or radiosity there is to shoot,
/// also where an edit made it negative (incremental.cpp).
inline double magnitude(const glm::dvec3& v) {
    return std::abs(v.x) + std::abs(v.y) + std::abs(v.z);
}
inline bool has_negative(const glm::dvec3& v) {
    return v.x < 0 || v.y < 0 || v.z < 0;
}

/// A node's unshot power by magnitude, summed over RGB [W] (the sum in float, as the node
/// holds it: for non-negative values, bit for bit the sum of the channels).
inline double node_power(const Hierarchy::Node& n) {
    return double(std::abs(n.dB.x) + std::abs(n.dB.y) + std::abs(n.dB.z)) * double(n.area);
}

/// The luminaire a shot of luminaire `l` renders: itself, or, switched off by an edit
/// (multiplier 0), a copy at multiplier 1 in `spare`: the form factors are per watt emitted,
/// and its negative unshot power must still go out.
inline const Luminaire& shooting_luminaire(const Luminaire& l, Luminaire& spare) {
    if (l.multiplier > 0) return l;
    spare = l;
    spare.multiplier = 1;
    return spare;
}

/// A shot of unshot radiosity dB from a shooter of area `area_s` into `h`: each link's
/// receiver gets the irradiance ff * scale * dB. Adds to `absorbed` what the receivers absorb,
/// (1 - rho) E A, and to `escaped` the part of dB * area_s that no receiver took. The solver's
/// hierarchy and each light layer receive their shots through this one loop.
inline void deliver_links(Hierarchy& h, const std::vector<Link>& links, const glm::dvec3& dB,
                          double area_s, double scale, glm::dvec3& absorbed, glm::dvec3& escaped) {
    glm::dvec3 received(0.0);
    for (const Link& l : links) {
        const glm::dvec3 irradiance = double(l.ff) * scale * dB;
        const double a = double(h.node(l.receiver).area);
        const glm::dvec3 rho = h.reflectance(l.receiver); // per leaf where textured
        h.receive(l.receiver, irradiance);
        received += irradiance * a;
        absorbed += (glm::dvec3(1.0) - rho) * irradiance * a;
    }
    escaped += dB * area_s - received;
}

} // namespace hemirad::solver_detail
