// Solvers that each own a GL context (GpuProviderOptions::use_current_context off, as the
// Python module and a program with several solvers make them): one stepping after another was
// made, stepped and destroyed gets the same solution as a solver alone in its process. Before
// the fix the destroyed solver's context took the display down with it (eglTerminate) and the
// survivor rendered with no context: wrong form factors.
//
// Needs a GL context (Mesa llvmpipe here): failing to get one FAILS the test.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "hemirad/scene_io.h"
#include "hemirad/solver.h"

using namespace hemirad;

namespace {

SolverOptions own_context_options() {
    SolverOptions o; // its own context: use_current_context is off by default
    o.max_shots = 40;
    o.tolerance = 1e-6; // not reached in 40 shots
    return o;
}

// The irradiance of every polygon's root node, in polygon order.
std::vector<dvec3> roots(Solver& s) {
    Hierarchy& h = s.solution();
    std::vector<dvec3> E;
    for (std::uint32_t p = 0; p < h.scene().polygons.size(); ++p)
        E.push_back(h.irradiance({p, 0, 0}));
    return E;
}

// The same shots on the same scene: the float sums in the same order, equal to rounding.
void expect_same(const std::vector<dvec3>& a, const std::vector<dvec3>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(a[i][c], b[i][c], 1e-6 * std::max(std::abs(b[i][c]), 1e-3))
                << "polygon " << i << " channel " << c;
}

TEST(SolverContexts, ASolverOutlivingAnotherGetsTheSolutionOfOneAlone) {
    const Scene scene = load_scene("cornell");
    std::vector<dvec3> alone;
    {
        Solver s(scene, own_context_options());
        while (s.step()) {}
        EXPECT_EQ(s.shots(), 40);
        alone = roots(s);
    }
    Solver first(scene, own_context_options());
    first.step();
    {
        Solver second(scene, own_context_options()); // made current on creation
        for (int i = 0; i < 5; ++i) second.step();
    } // destroyed: its context, not the first's
    while (first.step()) {}
    EXPECT_EQ(first.shots(), 40);
    expect_same(roots(first), alone);
}

TEST(SolverContexts, TwoSolversSteppedInTurnEachGetTheSolutionOfOneAlone) {
    const Scene scene = load_scene("cornell");
    std::vector<dvec3> alone;
    {
        Solver s(scene, own_context_options());
        while (s.step()) {}
        alone = roots(s);
    }
    Solver a(scene, own_context_options()), b(scene, own_context_options());
    for (bool more = true; more;) more = a.step() | b.step();
    expect_same(roots(a), alone);
    expect_same(roots(b), alone);
}

} // namespace
