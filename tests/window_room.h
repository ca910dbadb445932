// The window room of the sun and glazing tests: a 3 x 2.5 x 3 m room of one material with a
// 1 m square window in its south wall (z = 3, sill at 1 m, x in [1, 2]), and the pane that
// glazes it (glazing.h).
#pragma once

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "hemirad/scene.h"

namespace window_room {

using hemirad::dvec3;

inline constexpr double kWidth = 3, kHeight = 2.5, kDepth = 3;

// A quad with corners c whose front faces along `facing` (the order flipped if needed).
inline void quad(hemirad::Scene& s, std::vector<dvec3> c, const dvec3& facing, std::uint32_t m) {
    if (glm::dot(glm::cross(c[1] - c[0], c[2] - c[0]), facing) < 0) std::swap(c[1], c[3]);
    ASSERT_EQ(hemirad::add_polygon(s, c, m, 0).added, 1);
}

inline hemirad::Scene empty_scene(double rho) {
    hemirad::Scene s;
    s.source = "builtin:sun-test";
    s.materials.push_back(hemirad::Material{"m", dvec3(rho), dvec3(0.0)});
    s.groups.push_back("g");
    return s;
}

/// The room, unfinished (add the lights, then finish_scene).
inline hemirad::Scene room(double rho) {
    hemirad::Scene scene = empty_scene(rho);
    const double W = kWidth, H = kHeight, D = kDepth;
    quad(scene, {{0, 0, 0}, {W, 0, 0}, {W, 0, D}, {0, 0, D}}, {0, 1, 0}, 0);  // floor
    quad(scene, {{0, H, 0}, {W, H, 0}, {W, H, D}, {0, H, D}}, {0, -1, 0}, 0); // ceiling
    quad(scene, {{0, 0, 0}, {0, H, 0}, {0, H, D}, {0, 0, D}}, {1, 0, 0}, 0);  // west
    quad(scene, {{W, 0, 0}, {W, H, 0}, {W, H, D}, {W, 0, D}}, {-1, 0, 0}, 0); // east
    quad(scene, {{0, 0, 0}, {W, 0, 0}, {W, H, 0}, {0, H, 0}}, {0, 0, 1}, 0);  // north
    // The south wall around the window x in [1, 2], y in [1, 2].
    quad(scene, {{0, 0, D}, {W, 0, D}, {W, 1, D}, {0, 1, D}}, {0, 0, -1}, 0);
    quad(scene, {{0, 2, D}, {W, 2, D}, {W, H, D}, {0, H, D}}, {0, 0, -1}, 0);
    quad(scene, {{0, 1, D}, {1, 1, D}, {1, 2, D}, {0, 2, D}}, {0, 0, -1}, 0);
    quad(scene, {{2, 1, D}, {W, 1, D}, {W, 2, D}, {2, 2, D}}, {0, 0, -1}, 0);
    return scene;
}

/// Glazes the window with a pane of normal-incidence transmittance tau.
inline void glaze(hemirad::Scene& scene, double tau, bool angular) {
    hemirad::GlazingPane pane;
    pane.polygon.count = 4;
    pane.polygon.v = {dvec3(1, 1, kDepth), dvec3(2, 1, kDepth), dvec3(2, 2, kDepth),
                      dvec3(1, 2, kDepth)};
    pane.polygon.normal = {0, 0, 1};
    pane.polygon.area = 1;
    pane.transmittance = hemirad::make_pane_transmittance(tau, angular);
    scene.glazing.push_back(pane);
}

} // namespace window_room
