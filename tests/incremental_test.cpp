// Incremental re-solving (solver.h, "Incremental re-solving"; scene_edit.h), on the CPU
// reference provider in a small closed grey room with two point luminaires and an emitting
// panel:
//  - a converged solution, edited (a luminaire's multiplier, a group's reflectance, a group's
//    emission) and re-converged, equals a fresh solve of the edited scene within the error
//    bounds of the two;
//  - a multiplier of 0 removes a light completely;
//  - the energy balance closes across an edit; bad edits are refused naming the value;
//  - with light layers (light_layers.h), a luminaire's multiplier edit is exact at once: the
//    solution equals a fresh solve's with (nearly) no shot, also through a solution file.
#include <gtest/gtest.h>

#include <cmath>

#include "hemirad/error.h"
#include "hemirad/gather.h"
#include "hemirad/report.h"
#include "hemirad/scene_edit.h"
#include "hemirad/solution_file.h"
#include "hemirad/solver.h"

using namespace hemirad;

namespace {

constexpr double W = 4, H = 3, D = 4; // the room [m]

Luminaire candela(const std::string& name, double I, const dvec3& position) {
    Luminaire l;
    l.name = name;
    l.kind = "candela";
    l.distribution = isotropic_distribution(I);
    l.position = position;
    l.orient();
    return l;
}

// A closed room [0,W] x [0,H] x [0,D]: groups floor (rho 0.5), ceiling (0.7), walls (0.6), and
// panel, a 0.5 m square emitter under the ceiling (Ke 0.2, black); luminaires A and B.
Scene room(bool panel = true, bool b = true) {
    Scene s;
    s.source = "test:room";
    s.materials = {{"floor", dvec3(0.5), dvec3(0.0)},
                   {"ceiling", dvec3(0.7), dvec3(0.0)},
                   {"walls", dvec3(0.6, 0.6, 0.5), dvec3(0.0)},
                   {"panel", dvec3(0.0), dvec3(0.2)}};
    s.groups = {"floor", "ceiling", "walls", "panel"};
    // Corners o, o+u, o+u+v, o+v: the normal is u x v.
    const auto quad = [&](dvec3 o, dvec3 u, dvec3 v, std::uint32_t m) {
        add_polygon(s, {o, o + u, o + u + v, o + v}, m, m);
    };
    quad({0, 0, 0}, {0, 0, D}, {W, 0, 0}, 0);
    quad({0, H, 0}, {W, 0, 0}, {0, 0, D}, 1);
    quad({0, 0, 0}, {0, H, 0}, {0, 0, D}, 2);
    quad({W, 0, 0}, {0, 0, D}, {0, H, 0}, 2);
    quad({0, 0, 0}, {W, 0, 0}, {0, H, 0}, 2);
    quad({0, 0, D}, {0, H, 0}, {W, 0, 0}, 2);
    if (panel) quad({2.75, H - 0.01, 0.75}, {0.5, 0, 0}, {0, 0, 0.5}, 3);
    s.luminaires.push_back(candela("A", 100, {1, 2.5, 1}));
    if (b) s.luminaires.push_back(candela("B", 60, {3, 2.5, 3}));
    finish_scene(s, s.source);
    return s;
}

// Shooting from the leaves (flat): both solves then converge to the same discrete solution B*
// (the same form factors), and each is within its error bound of it. Light layers off by
// default: the tests below then check the shooting of differences; "on" the layers.
SolverOptions options(double tolerance, const char* layers = "off") {
    SolverOptions o;
    o.light_layers = layers;
    o.ff = "reference";
    o.tolerance = tolerance;
    o.flat = true;
    o.hierarchy.max_depth = 2;
    o.hierarchy.patch_size = 1e-9; // always the maximum depth
    return o;
}

// sum over leaves of |B_a - B_b| A (per channel, the largest) and the largest relative
// difference of a leaf's radiosity (to the mean radiosity of the scene).
struct Difference {
    double l1 = 0, leaf = 0;
};
Difference difference(Solver& a, Solver& b) {
    const Hierarchy& ha = a.solution();
    const Hierarchy& hb = b.solution();
    dvec3 l1(0.0), sum(0.0);
    double area = 0, worst = 0;
    std::vector<std::pair<dvec3, dvec3>> leaves;
    for (std::uint32_t p = 0; p < ha.scene().polygons.size(); ++p) {
        const auto level = std::uint32_t(ha.depth(p));
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) {
            const PatchAddress addr{p, level, i};
            const double A = ha.node(addr).area;
            const dvec3 Ba = ha.radiosity(addr), Bb = hb.radiosity(addr);
            l1 += glm::abs(Ba - Bb) * A;
            sum += Bb * A;
            area += A;
            leaves.emplace_back(Ba, Bb);
        }
    }
    const dvec3 mean = sum / area;
    for (const auto& [Ba, Bb] : leaves)
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(Ba[c] - Bb[c]) / mean[c]);
    return {std::max({l1.x, l1.y, l1.z}), worst};
}

void solve(Solver& s) {
    while (s.step()) {}
    ASSERT_TRUE(s.converged()) << to_string(s.stop_reason()) << " after " << s.shots();
}

struct EditCase {
    const char* name;
    void (*solver_edit)(Solver&);
    void (*scene_edit)(Scene&);
    bool luminaires_only = false; ///< light layers make the edit exact, with no shot
};

class IncrementalEqualsFresh : public ::testing::TestWithParam<EditCase> {};

// The bound: ||B - B*||_1 <= tol Phi for each (paper 001 eq. 27 with the solver's error bound
// <= tol), so ||B_incremental - B_fresh||_1 <= 2 tol Phi, Phi the edited scene's emitted
// power (the error bound is relative to it). Per leaf the worst case is that budget on one
// leaf (1/97 of the area): 2 tol Phi / A_leaf, about 1 % of the mean radiosity here (whose
// power, B_mean A, is of the order of Phi in this closed room). Measured: the L1 difference
// 1-2 % of its bound, leaves within 1e-5 of the mean.
//
// With light layers the same bounds hold, and an edit of luminaires' multipliers only takes at
// most a twentieth of a fresh solve's shots: the layers' residual unshot power is rescaled with
// them, so the bound moves only as the share of the rest (here the panel's) in the emitted
// power does (measured: no shot for "multiplier" and "raise"). The "all" edit's luminaire is
// rescaled too, but its reflectance and emission edits are shot.
void edit_and_compare(const EditCase& c, const char* layers) {
    SCOPED_TRACE(std::string(c.name) + ", light layers " + layers);
    const double tol = 1e-4;
    Scene base = room();
    Solver inc(base, options(tol, layers));
    ASSERT_EQ(inc.has_light_layers(), std::string(layers) == "on");
    solve(inc);
    const long base_shots = inc.shots();
    c.solver_edit(inc);
    if (!inc.has_light_layers() || !c.luminaires_only)
        EXPECT_FALSE(inc.converged()) << "an edit must leave unshot power";
    solve(inc);
    Scene edited = room();
    c.scene_edit(edited);
    Solver fresh(edited, options(tol));
    solve(fresh);
    if (inc.has_light_layers() && c.luminaires_only)
        EXPECT_LE(20 * (inc.shots() - base_shots), fresh.shots());
    const double phi =
        std::max({edited.emitted_power().x, edited.emitted_power().y, edited.emitted_power().z});
    const Difference d = difference(inc, fresh);
    EXPECT_LE(d.l1, 2 * tol * phi) << c.name;
    EXPECT_LE(d.leaf, 0.01) << c.name;
    // Re-converging costs fewer shots than solving again.
    EXPECT_LT(inc.shots() - base_shots, fresh.shots()) << c.name;
    // Energy: emitted = absorbed + escaped + unshot (signed) still closes after the edit
    // (float node values: to 1e-4 of the power).
    dvec3 unshot = inc.hierarchy().total_unshot_power();
    for (const dvec3& u : inc.luminaire_unshot()) unshot += u;
    const dvec3 balance = inc.emitted_power() - inc.absorbed_power() - inc.escaped_power();
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(balance[ch], unshot[ch], 1e-4 * phi) << c.name;
}

TEST_P(IncrementalEqualsFresh, WithinBothErrorBounds) {
    edit_and_compare(GetParam(), "off");
}

TEST_P(IncrementalEqualsFresh, WithLightLayers) {
    edit_and_compare(GetParam(), "on");
}

INSTANTIATE_TEST_SUITE_P(
    Edits, IncrementalEqualsFresh,
    ::testing::Values(
        EditCase{"multiplier", [](Solver& s) { s.set_luminaire_multiplier("A", 0.3); },
                 [](Scene& s) { set_luminaire_multiplier(s, "A", 0.3); }, true},
        EditCase{"raise", [](Solver& s) { s.set_luminaire_multiplier("B", 2.5); },
                 [](Scene& s) { set_luminaire_multiplier(s, "B", 2.5); }, true},
        EditCase{"both_dimmed",
                 [](Solver& s) {
                     s.set_luminaire_multiplier("A", 0.6);
                     s.set_luminaire_multiplier("B", 0.5);
                 },
                 [](Scene& s) {
                     set_luminaire_multiplier(s, "A", 0.6);
                     set_luminaire_multiplier(s, "B", 0.5);
                 },
                 true},
        EditCase{"reflectance", [](Solver& s) { s.set_reflectance("walls", dvec3(0.2, 0.8, 0.4)); },
                 [](Scene& s) { set_group_reflectance(s, "walls", dvec3(0.2, 0.8, 0.4)); }},
        EditCase{"emission", [](Solver& s) { s.set_emission("panel", dvec3(0.05, 0.6, 0.2)); },
                 [](Scene& s) { set_group_emission(s, "panel", dvec3(0.05, 0.6, 0.2)); }},
        EditCase{"all",
                 [](Solver& s) {
                     s.set_luminaire_multiplier("A", 0);
                     s.set_reflectance("floor", dvec3(0.0));
                     s.set_emission("walls", dvec3(0.01));
                 },
                 [](Scene& s) {
                     set_luminaire_multiplier(s, "A", 0);
                     set_group_reflectance(s, "floor", dvec3(0.0));
                     set_group_emission(s, "walls", dvec3(0.01));
                 }}),
    [](const ::testing::TestParamInfo<EditCase>& info) { return std::string(info.param.name); });

// The only light switched off: after re-converging, the floor's irradiance by final gather
// (its direct light from the luminaire at the current multiplier, its indirect from the
// solution) is what the error bound leaves: the residual radiosity is at most tol Phi in the
// L1 norm (Phi the power emitted before: nothing emits now), so E at a point is of the order
// of tol E_before; 1 % of E_before is ten times that.
TEST(IncrementalOff, MultiplierZeroRemovesTheLight) {
    const double tol = 1e-3;
    Scene scene = room(false, false);
    Solver s(scene, options(tol));
    solve(s);
    const std::vector<Probe> probes = {{{1, 0, 1}, {0, 1, 0}}, {{3, 0, 3}, {0, 1, 0}}};
    const auto gathered = [&](Solver& solver) {
        const Hierarchy& h = solver.solution();
        const FinalGather gather(h);
        std::vector<double> E;
        for (const ProbeValue& v : evaluate_probes(probes, h, &gather)) E.push_back(v.E->x);
        return E;
    };
    const std::vector<double> before = gathered(s);
    ASSERT_GT(before[0], 0.02); // direct under A: 100 cd / (2.5 m)^2 / 683 = 0.023 W m^-2
    s.set_luminaire_multiplier("A", 0);
    EXPECT_EQ(s.emitted_power(), dvec3(0.0));
    EXPECT_FALSE(s.converged()) << "the light's power is still to be taken out";
    solve(s);
    const std::vector<double> after = gathered(s);
    for (std::size_t k = 0; k < probes.size(); ++k)
        EXPECT_LT(std::abs(after[k]), 0.01 * before[k]) << "probe " << k;
    // And every leaf's irradiance (no gather) is down to the same residual.
    const Hierarchy& h = s.solution();
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
        EXPECT_LT(std::abs(h.irradiance({p, 0, 0}).x), 0.01 * before[1]) << "polygon " << p;
}

// Light layers through edits that they cannot rescale and a solution file:
//  - a luminaire switched off and on again (from 0, its light is shot, into its layer), then
//    dimmed (rescaled), after a reflectance edit (every layer's share reflected anew);
//  - the same state saved to bytes and resumed in a new solver, then dimmed there: the layers
//    come back with the file, so the dimming takes no shot either.
// Each against a fresh solve of the edited scene, within the bounds of WithinBothErrorBounds.
TEST(LightLayers, OffOnDimmedAndResumedEqualFresh) {
    const double tol = 1e-4;
    Scene scene = room();
    Solver s(scene, options(tol, "on"));
    solve(s);
    s.set_luminaire_multiplier("A", 0);
    s.set_reflectance("walls", dvec3(0.3));
    solve(s);
    s.set_luminaire_multiplier("A", 1);
    EXPECT_FALSE(s.converged()) << "from off, A's light must be shot";
    solve(s);
    const std::string bytes = solution_bytes(s);
    const long shots = s.shots();
    s.set_luminaire_multiplier("A", 0.4);
    EXPECT_EQ(s.rescaled_luminaires(), 2); // A to 0, then to 0.4; not 0 -> 1
    solve(s);
    EXPECT_LE(20 * (s.shots() - shots), shots);

    Scene edited = room();
    set_group_reflectance(edited, "walls", dvec3(0.3));
    set_luminaire_multiplier(edited, "A", 0.4);
    Solver fresh(edited, options(tol));
    solve(fresh);
    const double phi =
        std::max({edited.emitted_power().x, edited.emitted_power().y, edited.emitted_power().z});
    Difference d = difference(s, fresh);
    EXPECT_LE(d.l1, 2 * tol * phi);
    EXPECT_LE(d.leaf, 0.01);

    // Resumed from the bytes saved before the dimming, in a scene with A at 0.4 already.
    Scene resumed_scene = room();
    set_group_reflectance(resumed_scene, "walls", dvec3(0.3));
    set_luminaire_multiplier(resumed_scene, "A", 0.4);
    Solver resumed(resumed_scene, options(tol, "on"));
    const SolutionFile file = parse_solution(bytes, "test.sol");
    ASSERT_EQ(file.state.layers.size(), 2u);
    const ResumeEdits edits = resume_solution(resumed, file, "test.sol");
    EXPECT_EQ(edits.luminaires, 1u);
    EXPECT_EQ(edits.rescaled, 1u);
    solve(resumed);
    EXPECT_LE(20 * (resumed.shots() - shots), shots);
    d = difference(resumed, fresh);
    EXPECT_LE(d.l1, 2 * tol * phi);
    EXPECT_LE(d.leaf, 0.01);
    // A solver without layers resumes the same file and shoots the dimming instead.
    Solver plain(resumed_scene, options(tol, "off"));
    EXPECT_EQ(resume_solution(plain, file, "test.sol").rescaled, 0u);
    EXPECT_FALSE(plain.converged());
}

// A luminaire moved and re-aimed: its light leaves the old place at once (its layer), and is
// shot from the new one; the re-converged solution equals a fresh solve of the moved scene
// within the bounds above. Without light layers the move is refused; bad values are named.
TEST(LightLayers, MovedLuminaireEqualsFresh) {
    const double tol = 1e-4;
    const dvec3 position(2.2, 2.0, 1.4), aim(0.3, -1, 0.2);
    Scene scene = room();
    Solver s(scene, options(tol, "on"));
    solve(s);
    s.place_luminaire("A", position, aim);
    EXPECT_FALSE(s.converged());
    solve(s);
    Scene moved = room();
    set_luminaire_placement(moved, "A", position, aim);
    EXPECT_NE(moved.geometry_hash(), room().geometry_hash());
    EXPECT_EQ(scene.geometry_hash(), moved.geometry_hash()); // the solver's scene moved it too
    Solver fresh(moved, options(tol));
    solve(fresh);
    const double phi =
        std::max({moved.emitted_power().x, moved.emitted_power().y, moved.emitted_power().z});
    const Difference d = difference(s, fresh);
    EXPECT_LE(d.l1, 2 * tol * phi);
    EXPECT_LE(d.leaf, 0.01);
    const dvec3 balance = s.emitted_power() - s.absorbed_power() - s.escaped_power();
    dvec3 unshot = s.hierarchy().total_unshot_power();
    for (const dvec3& u : s.luminaire_unshot()) unshot += u;
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(balance[ch], unshot[ch], 1e-4 * phi);

    Scene other = room();
    Solver plain(other, options(tol, "off"));
    const auto message = [](auto&& f) -> std::string {
        try {
            f();
        } catch (const InputError& e) {
            return e.what();
        }
        return "(no error)";
    };
    EXPECT_NE(message([&] { plain.place_luminaire("A", position, aim); }).find("light layers"),
              std::string::npos);
    EXPECT_NE(message([&] { s.place_luminaire("A", position, dvec3(0.0)); }).find("luminaire A"),
              std::string::npos);
    EXPECT_NE(message([&] { s.place_luminaire("Z", position, aim); }).find("no luminaire named"),
              std::string::npos);
    EXPECT_NE(message([&] { s.place_luminaire("A", dvec3(NAN), aim); }).find("finite"),
              std::string::npos);
    EXPECT_EQ(scene.luminaires[0].position, position) << "a refused move changes nothing";
}

TEST(IncrementalEdits, BadEditsNameTheValue) {
    Scene scene = room();
    Solver s(scene, options(1e-2));
    const auto message = [&](auto edit) {
        try {
            edit();
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message([&] { s.set_luminaire_multiplier("Z", 1); }).find("no luminaire named 'Z'"),
              std::string::npos);
    EXPECT_NE(message([&] { s.set_luminaire_multiplier("A", -1); }).find("A=-1"),
              std::string::npos);
    EXPECT_NE(message([&] { s.set_luminaire_multiplier("A", NAN); }).find("A=nan"),
              std::string::npos);
    EXPECT_NE(message([&] { s.set_reflectance("walls", dvec3(1.2)); }).find("walls=1.2"),
              std::string::npos);
    EXPECT_NE(message([&] { s.set_reflectance("roof", dvec3(0.2)); }).find("no surface group"),
              std::string::npos);
    EXPECT_NE(message([&] { s.set_emission("panel", dvec3(-1)); }).find("panel=-1"),
              std::string::npos);
    // A solver of a const scene cannot edit it.
    const Scene fixed = room();
    Solver c(fixed, options(1e-2));
    EXPECT_NE(message([&] { c.set_luminaire_multiplier("A", 0); }).find("const Scene"),
              std::string::npos);
    // Parsing the command line's NAME=F and GROUP=R,G,B.
    EXPECT_EQ(parse_scene_edit("--reflectance", "walls=0.1,0.2,0.3", 3).second,
              dvec3(0.1, 0.2, 0.3));
    EXPECT_NE(message([] { parse_scene_edit("--luminaire-multiplier", "D2", 1); }).find("'D2'"),
              std::string::npos);
    EXPECT_NE(message([] { parse_scene_edit("--luminaire-multiplier", "D2=x", 1); }).find("'x'"),
              std::string::npos);
}

// Geometry and photometry hash apart: an edit changes the content hash, not the geometry's.
TEST(IncrementalEdits, GeometryHashIgnoresPhotometry) {
    Scene a = room(), b = room();
    set_luminaire_multiplier(b, "A", 0.5);
    set_group_reflectance(b, "walls", dvec3(0.3));
    EXPECT_NE(a.content_hash(), b.content_hash());
    EXPECT_EQ(a.geometry_hash(), b.geometry_hash());
    Scene c = room();
    c.luminaires[0].position.x += 0.1;
    EXPECT_NE(a.geometry_hash(), c.geometry_hash());
}

} // namespace
