// Projections for GL: reversed Z with an infinite far plane, the one depth convention of the
// renderer (render/solution_renderer.cpp) and the hemicube (gpu/hemicube.cpp). With
// glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), a cleared depth of 0 and glDepthFunc(GL_GREATER),
// depth = near / distance: 1 at the near plane, 0 at infinity. Float depth then spends its
// precision evenly in log distance, so that the Cornell light 0.8 mm under the ceiling never
// fights it.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace hemirad {

/// The frustum whose cross-section at distance `near` spans [l, r] x [b, t] (eye space,
/// looking down -z).
inline glm::mat4 reversed_z_frustum(double l, double r, double b, double t, double near) {
    glm::dmat4 m(0.0);
    m[0][0] = 2 * near / (r - l);
    m[1][1] = 2 * near / (t - b);
    m[2][0] = (r + l) / (r - l);
    m[2][1] = (t + b) / (t - b);
    m[3][2] = near;
    m[2][3] = -1;
    return glm::mat4(m);
}

/// The symmetric frustum of a camera: vertical field of view `fov_y_rad` [rad], aspect =
/// width / height.
inline glm::mat4 reversed_z_perspective(double fov_y_rad, double aspect, double near) {
    const double f = 1.0 / std::tan(0.5 * fov_y_rad);
    glm::dmat4 m(0.0);
    m[0][0] = f / aspect;
    m[1][1] = f;
    m[3][2] = near;
    m[2][3] = -1;
    return glm::mat4(m);
}

} // namespace hemirad
