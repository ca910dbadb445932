// Direct light from a distant source (the sun, sun_light.h; the sky, sky_light.h) handed to
// the leaf patches before the first shot. Internal header.
#pragma once

#include <cstdint>
#include <vector>

#include "hemirad/hierarchy.h"

namespace hemirad {

/// What a distant source delivered to the leaves, per RGB channel [W].
struct LeafDelivery {
    dvec3 power{0.0};    ///< sum over leaves of E * A: the source's emitted power for the scene
    dvec3 absorbed{0.0}; ///< sum of (1 - rho) E A; the rest, rho E A, is the leaves' unshot power
    std::uint64_t rays = 0; ///< rays cast
};

/// Hands leaf k of polygon p the irradiance leaf_E[p][k] (equal RGB; Hierarchy::receive, none
/// where it is not above 0) and counts what was delivered, with `rays[p]` rays cast for p.
inline LeafDelivery receive_at_leaves(Hierarchy& hierarchy,
                                      const std::vector<std::vector<double>>& leaf_E,
                                      const std::vector<std::uint64_t>& rays) {
    LeafDelivery out;
    for (std::uint32_t p = 0; p < leaf_E.size(); ++p) {
        out.rays += rays[p];
        const auto level = std::uint32_t(hierarchy.depth(p));
        for (std::uint32_t k = 0; k < leaf_E[p].size(); ++k) {
            const double E = leaf_E[p][k];
            if (!(E > 0)) continue;
            const PatchAddress a{p, level, k};
            const dvec3 irradiance(E);
            const double area = double(hierarchy.node(a).area);
            hierarchy.receive(a, irradiance);
            out.power += irradiance * area;
            out.absorbed += (dvec3(1.0) - hierarchy.reflectance(a)) * irradiance * area;
        }
    }
    return out;
}

} // namespace hemirad
