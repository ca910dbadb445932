// hemirad-view's Dear ImGui panels (issue 21): luminaires (on/off, dimmer, position and aim:
// Solver::place_luminaire, with light layers), surface groups
// (reflectance, live irradiance statistics), the solver's progress and error bound, and the
// view (exposure, false colour, ambient term). Every edit goes to the solver's incremental
// re-solving (Solver::set_luminaire_multiplier(), set_reflectance()) and the solve continues.
// Built only when Dear ImGui (Debian libimgui-dev) is found (HEMIRAD_VIEWER_PANELS).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hemirad/readout.h"
#include "hemirad/solver.h"

struct GLFWwindow;

namespace hemirad::view {

/// The view settings the panels show and change (the window's state, owned by the caller).
struct PanelView {
    bool* false_colour;
    bool* ambient;
    bool* paused;
    double* exposure; ///< [stops]
};

/// What the panels show besides the solver.
struct PanelStats {
    double shots_per_second = 0;
    double frame_ms = 0; ///< drawing time of the last frame [ms]
    bool lux = false;    ///< read-outs in lux (scene in metres), else W/unit^2
};

class Panels {
  public:
    /// Creates the ImGui context and its GLFW and OpenGL 3 backends on `window` (its context
    /// current). The GLFW backend chains the callbacks installed before it.
    Panels(GLFWwindow* window, const Scene& scene);
    ~Panels();
    Panels(const Panels&) = delete;
    Panels& operator=(const Panels&) = delete;

    /// Whether ImGui wants the mouse or keyboard now (then the viewer ignores them).
    static bool wants_mouse();
    static bool wants_keyboard();

    /// Builds and draws the panels into the default framebuffer. Edits are applied to
    /// `solver`; returns true when one was (the solver then runs again).
    bool draw(Solver& solver, const PanelView& view, const PanelStats& stats);

  private:
    struct Luminaire {
        std::string name;
        double base = 1; ///< the scene's multiplier at the start (1 if it was 0)
        bool on = true;
        float dimmer = 1;   ///< fraction of `base`, [0, 1]
        double applied = 1; ///< the multiplier the panel last saw or set
        float position[3] = {0, 0, 0}, aim[3] = {0, -1, 0}; ///< as edited
        dvec3 placed{0.0}, aimed{0.0}; ///< the placement the panel last saw or set
    };
    struct Group {
        std::string name;
        float rho[3] = {0, 0, 0};
        dvec3 applied{0.0};              ///< the reflectance the panel last saw or set
        std::uint32_t first_polygon = 0; ///< whose material gives the group's reflectance
        bool textured = false;
        GroupIrradiance stats;
    };
    std::vector<Luminaire> luminaires_;
    std::vector<Group> groups_;
    double stats_time_ = -1; ///< when the group statistics were computed [s since start]
    std::string error_;      ///< the last edit's error, shown until the next edit

    /// Follows edits made elsewhere (a script, keys): the scene's multipliers and reflectances.
    void sync(const Scene& scene);
};

} // namespace hemirad::view
