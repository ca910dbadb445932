// Glazing in the solver and the read-outs (glazing.h): a pane whose transmittance does not
// depend on the angle passes tau of everything that comes in through it. In a room whose only
// light enters through its window (an overcast sky, and a lamp outside shining in), glazing
// the window with such a pane must scale the whole solution by tau: the sky's rays, the lamp's
// links and shadow rays, and so every gathered point. The direct light scales exactly (the
// same rays); the rest within 2e-3: the solves stop at the error bound 0.01 of the emitted
// power, which counts the lamp's whole flux in both, so not after the same shots (measured:
// 0.11 % at most). The lamp brings about a tenth of the light, so links not attenuated would
// put the ratio near 0.73.
//
// Needs a GL context (Mesa llvmpipe here): failing to get one FAILS the test.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "hemirad/gather.h"
#include "hemirad/readout.h"
#include "hemirad/solver.h"
#include "shared_gl_context.h"
#include "window_room.h"

using namespace hemirad;

namespace {

class Glazing : public SharedGlContextTest {};

// The room lit by a CIE overcast sky of 10000 lx and an isotropic 200 cd lamp 1 m outside
// the window; glazed with a pane of tau (angle-independent) when tau < 1.
Scene lit_room(double tau) {
    Scene scene = window_room::room(0.5);
    if (tau < 1) window_room::glaze(scene, tau, false);
    Luminaire l;
    l.name = "outside";
    l.kind = "candela";
    l.distribution = isotropic_distribution(200);
    l.position = {1.5, 1.5, window_room::kDepth + 1};
    l.orient();
    scene.luminaires.push_back(l);
    scene.sky = make_sky(SkyModel::CieOvercast, 10000, 0, {0, 1, 0}, std::nullopt);
    finish_scene(scene, scene.source);
    return scene;
}

struct Result {
    long shots = 0;
    std::vector<GatherValue> values;
};

Result solve(const Scene& scene, const std::vector<GatherPoint>& points) {
    SolverOptions o;
    o.provider.gpu.use_current_context = true;
    Solver s(scene, o);
    while (s.step()) {}
    return {s.shots(), FinalGather(s.solution()).at(points)};
}

} // namespace

TEST_F(Glazing, AnAngleIndependentPaneScalesTheSolution) {
    const double H = window_room::kHeight, D = window_room::kDepth;
    const std::vector<GatherPoint> points = {
        {{1.5, 0.8, 1.5}, {0, 1, 0}, GatherPoint::kNoSurface}, // the work plane
        {{0.5, 0.8, 2.5}, {0, 1, 0}, GatherPoint::kNoSurface},
        {{1.5, 0, 0.5}, {0, 1, 0}, 0},   // the floor
        {{1.5, H, 1.5}, {0, -1, 0}, 1},  // the ceiling
        {{1.5, 1.2, 0}, {0, 0, 1}, 4},   // the north wall, facing the window
        {{0.5, 1.5, D}, {0, 0, -1}, 7}}; // beside the window
    const double tau = 0.7;
    const Result open = solve(lit_room(1.0), points);
    const Result glazed = solve(lit_room(tau), points);
    std::printf("shots: open %ld, glazed %ld\n", open.shots, glazed.shots);
    for (std::size_t k = 0; k < points.size(); ++k) {
        const double o = open.values[k].E().x, g = glazed.values[k].E().x;
        std::printf("point %zu: open %.6g, glazed %.6g, ratio %.6f\n", k, o, g, g / o);
        ASSERT_GT(o, 0);
        EXPECT_NEAR(g / o, tau, 2e-3 * tau) << k;
        EXPECT_NEAR(glazed.values[k].direct.x, tau * open.values[k].direct.x,
                    1e-9 * open.values[k].direct.x)
            << k;
    }
}
