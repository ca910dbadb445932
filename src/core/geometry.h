// Small geometry helpers shared by the scene readers and the scene's own checks.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace hemirad {

/// Newell's method: the normal of a polygon, unnormalised, of length twice its area; robust
/// for nearly degenerate and slightly non-planar polygons (corners in order, any winding).
inline glm::dvec3 newell_normal(const std::vector<glm::dvec3>& c) {
    glm::dvec3 n(0.0);
    for (std::size_t i = 0; i < c.size(); ++i) {
        const glm::dvec3& a = c[i];
        const glm::dvec3& b = c[(i + 1) % c.size()];
        n += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x),
                        (a.x - b.x) * (a.y + b.y));
    }
    return n;
}

} // namespace hemirad
