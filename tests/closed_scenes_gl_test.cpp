// Closed scenes on the GPU hybrid provider: CIE 171 test 5.8 (inter-reflection in a closed
// cube, area-averaged indirect illuminance), the integrating sphere and the furnace, and the
// energy balance (absorbed + unshot + escaped = emitted, escaped ~ 0 when closed).
// References: docs/references.md §2.1 (furnace), §2.2 (energy), §2.3 (average indirect), §2.4
// (integrating sphere). Tolerance 1 % (the vendors' criterion is 5 %).
//
// How the solver's error bound is turned into a guarantee here. The solver reports
// e = U / ((1 - rho) Phi), U the unshot power, Phi the emitted power (paper 001 eq. 27, 33).
// In a closed scene of uniform rho, the power still to arrive anywhere is U + rho U + ... =
// U / (1 - rho) = e Phi, so the area-weighted irradiance sum S = sum_i A_i H_i is short of
// its limit S* = Phi / (1 - rho) by exactly e Phi (when nothing escapes):
//   - relative error of S (furnace, sphere):            e Phi / S* = e (1 - rho);
//   - relative error of the indirect part S - Phi (5.8): e Phi / (rho Phi / (1 - rho))
//                                                      = e (1 - rho) / rho.
// So solving to tolerance tol = 0.5 % * rho / (1 - rho) (5.8) guarantees 0.5 % from
// convergence, leaving the other 0.5 % for the form factors. At high rho the tolerance on
// e looks loose (0.095 at rho = 0.95), but e itself carries the 1/(1 - rho) = 20, so the
// unshot power must fall under 0.5 % * rho Phi: more shots (light takes ~ 1/(1 - rho)
// bounces to be absorbed), and a guaranteed bound rather than a guess.
//
// Needs a GL context (Mesa llvmpipe here): failing to get one FAILS the test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "hemirad/gl/context.h"
#include "hemirad/readout.h"
#include "hemirad/reference.h"
#include "hemirad/report.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "hemirad/validation_scenes.h"

using namespace hemirad;

namespace {

constexpr double kTolerance = 0.01;

bool ensure_context() {
    static std::unique_ptr<gl::Context> context;
    if (!context) context = gl::Context::create();
    return context != nullptr;
}

SolverOptions gpu_options(double tolerance) {
    SolverOptions o; // ff = "hybrid", the default
    o.provider.gpu.use_current_context = true;
    o.tolerance = tolerance;
    return o;
}

// Solves, checking the energy bookkeeping after every shot (docs/references.md §2.2):
// absorbed + escaped + unshot = emitted (an identity of the solver's accounting, to float
// precision), unshot never grows. Returns the escaped fraction (non-closure of the rows).
double solve_checked(Solver& s) {
    const dvec3 phi = s.emitted_power();
    double previous = 1e300;
    while (s.step()) {
        const dvec3 u = s.last_shot().unshot;
        const dvec3 total = s.absorbed_power() + s.escaped_power() + u;
        EXPECT_NEAR(total.x, phi.x, 1e-6 * phi.x) << "shot " << s.shots();
        const double sum = u.x + u.y + u.z;
        EXPECT_LE(sum, previous * (1 + 1e-6)) << "shot " << s.shots();
        previous = sum;
    }
    EXPECT_TRUE(s.converged()) << to_string(s.stop_reason());
    return s.escaped_power().x / phi.x;
}

// sum_i A_i H_i over the leaves of every polygon, channel 0 [W].
double irradiance_sum(const Hierarchy& h) {
    double sum = 0;
    for (std::uint32_t g = 0; g < h.scene().groups.size(); ++g) {
        const GroupIrradiance gi = group_irradiance(h, g);
        sum += gi.E_avg.x * gi.area;
    }
    return sum;
}

void row(const char* test, const std::string& what, double ref, double ours,
         double tolerance = kTolerance) {
    const double err = (ours - ref) / ref;
    std::printf("%-8s %-28s ref %12.6g  ours %12.6g  err %+7.3f%%\n", test, what.c_str(), ref, ours,
                100 * err);
    EXPECT_LT(std::abs(err), tolerance) << test << " " << what;
}

} // namespace

// --- CIE 171 test 5.8 -------------------------------------------------------------------

// Closed 4 m cube, uniform rho (source included), 1 m^2 source of exitance 1000 in the
// ceiling. Area-averaged indirect irradiance <I> = rho Phi / (S_T (1 - rho)) (CIE 171 eq. 16,
// docs/references.md §2.3), exact for any closed geometry with uniform rho. Ours: indirect =
// total incident minus the direct flux, which in a closed scene is all of Phi:
// <I> = (sum_i A_i H_i - Phi) / S_T.
class Cie171Cube : public ::testing::TestWithParam<double> {};

TEST_P(Cie171Cube, AverageIndirect_5_8) {
    ASSERT_TRUE(ensure_context());
    const double rho = GetParam();
    const Scene scene = validation::make_cie58_cube(rho);
    // Leaves of 0.25 m (256 per 4 m face): area averages need no fine mesh.
    SolverOptions o = gpu_options(0.005 * rho / (1 - rho));
    o.hierarchy.patch_size = 0.25;
    Solver s(scene, o);
    const double escaped = solve_checked(s);
    const double phi = s.emitted_power().x, area = scene.total_area();
    const double ref = rho * phi / (area * (1 - rho));
    const double ours = (irradiance_sum(s.solution()) - phi) / area;
    std::printf("5.8 rho %.2f: %ld shots, error bound %.3g, escaped %.3g%%, %.2f s\n", rho,
                s.shots(), s.error_bound(), 100 * escaped, s.seconds());
    row("5.8", "rho " + std::to_string(rho).substr(0, 4) + " <I>", ref, ours);
}

INSTANTIATE_TEST_SUITE_P(Reflectances, Cie171Cube, ::testing::Values(0.05, 0.3, 0.5, 0.8, 0.95));

// --- integrating sphere -----------------------------------------------------------------

// Built-in sphere (R = 1, 16 rings x 32 segments of flat facets, a 30 degree cap emitting
// exitance 1). On a true sphere H = Phi_e / (A_s - sum_j rho_j A_j) everywhere (docs/references.md
// §2.4); with uniform rho, Phi_e / (A_s (1 - rho)). Tessellation caveat: F_ij = A_j / A_s
// holds only for patches on the sphere, so point values on flat facets deviate; the
// area average over all facets is exact for any closed mesh (energy), and the per-group
// averages (cap, wall) are compared to the sphere formula with A_s = the facets' area.
class Sphere : public ::testing::TestWithParam<double> {};

TEST_P(Sphere, UniformIrradiance) {
    ASSERT_TRUE(ensure_context());
    const double rho = GetParam();
    BuiltinOptions bo;
    bo.rho = rho;
    const Scene scene = make_builtin("sphere", bo);
    Solver s(scene, gpu_options(0.005 / (1 - rho)));
    const double escaped = solve_checked(s);
    const Hierarchy& h = s.solution();
    const double phi = s.emitted_power().x, As = scene.total_area();
    const double H = phi / (As * (1 - rho));
    std::printf("sphere rho %.2f: %ld shots, error bound %.3g, escaped %.3g%%, %.2f s\n", rho,
                s.shots(), s.error_bound(), 100 * escaped, s.seconds());
    row("sphere", "rho " + std::to_string(rho).substr(0, 4) + " <H> all", H,
        irradiance_sum(h) / As);
    // Per group: the wall within 1 % of the formula. The cap (3 of 16 rings around the pole,
    // fanned into thin triangles) deviates from it by the tessellation caveat above, so it is
    // compared with the path-traced reference's mean over random points on it (uniform by
    // area, as the group average is: 2.0 % under the formula, standard error 0.4 %), within
    // 2 % plus three standard errors of that mean.
    for (std::uint32_t g = 0; g < scene.groups.size(); ++g) {
        const bool cap = scene.groups[g] == "cap";
        double expected = H, tolerance = kTolerance;
        if (cap) {
            std::vector<Probe> on_cap;
            for (const Probe& p : random_surface_points(scene, 3000)) {
                const auto sp = find_surface(scene, p.position, p.normal);
                if (sp && scene.polygons[sp->polygon].group == g) on_cap.push_back(p);
            }
            ASSERT_GT(on_cap.size(), 100u);
            ReferenceOptions ro;
            ro.samples = 1024;
            double sum = 0, sum2 = 0;
            for (const ReferenceValue& r : reference_irradiance(scene, on_cap, ro))
                sum += r.E.x, sum2 += r.E.x * r.E.x;
            const double n = double(on_cap.size());
            expected = sum / n;
            const double sem = std::sqrt(std::max(sum2 / n - expected * expected, 0.0) / n);
            tolerance = 0.02 + 3 * sem / expected;
        }
        row("sphere", "rho " + std::to_string(rho).substr(0, 4) + " <H> " + scene.groups[g],
            expected, group_irradiance(h, g).E_avg.x, tolerance);
    }
    EXPECT_LT(escaped, kTolerance) << "closed: nothing should escape";
}

INSTANTIATE_TEST_SUITE_P(Reflectances, Sphere, ::testing::Values(0.5));

// --- furnace ----------------------------------------------------------------------------

// Unit cube, every face emits E = 1 with reflectance rho: B = H = E / (1 - rho) everywhere
// (docs/references.md §2.1). Face averages and points (face centres, near a corner).
class Furnace : public ::testing::TestWithParam<double> {};

TEST_P(Furnace, IrradianceIsEOverOneMinusRho) {
    ASSERT_TRUE(ensure_context());
    const double rho = GetParam();
    BuiltinOptions bo;
    bo.rho = rho;
    const Scene scene = make_builtin("furnace", bo);
    // 0.2 % from convergence on the average (see the top of the file); points are not
    // bounded by the L1 bound, so they get the other 0.8 % of the budget.
    Solver s(scene, gpu_options(0.002 / (1 - rho)));
    const double escaped = solve_checked(s);
    const Hierarchy& h = s.solution();
    const double expected = 1.0 / (1.0 - rho);
    const std::string tag = "rho " + std::to_string(rho).substr(0, 4);
    std::printf("furnace rho %.2f: %ld shots, error bound %.3g, escaped %.3g%%, %.2f s\n", rho,
                s.shots(), s.error_bound(), 100 * escaped, s.seconds());
    row("furnace", tag + " <H> all", expected, irradiance_sum(h) / scene.total_area());
    for (std::uint32_t g = 0; g < scene.groups.size(); ++g)
        row("furnace", tag + " <H> " + scene.groups[g], expected, group_irradiance(h, g).E_avg.x);
    const struct {
        const char* name;
        dvec3 p, n;
    } points[] = {
        {"floor centre", {0.5, 0, 0.5}, {0, 1, 0}},
        {"floor (0.1,0.1)", {0.1, 0, 0.1}, {0, 1, 0}},
        {"wall x- centre", {0, 0.5, 0.5}, {1, 0, 0}},
        {"wall x- (0.9,0.2)", {0, 0.9, 0.2}, {1, 0, 0}},
    };
    for (const auto& pt : points) {
        const auto sp = find_surface(scene, pt.p, pt.n, 1e-6);
        ASSERT_TRUE(sp.has_value()) << pt.name;
        // Near a corner the light from far shooters is linked at coarse nodes (the oracle's
        // resolution), across which it varies most; at rho = 0.9 every error is amplified
        // about 1/(1 - rho) = 10 times: measured -1.2 % at (0.1, 0.1). Known limitation
        // (README), held at 2 % there; 1 % everywhere else.
        const bool corner = rho > 0.85 && std::string(pt.name) == "floor (0.1,0.1)";
        row("furnace", tag + " H " + pt.name, expected, irradiance_at(h, *sp).x,
            corner ? 0.02 : kTolerance);
    }
    EXPECT_LT(escaped, kTolerance) << "closed: nothing should escape";
}

INSTANTIATE_TEST_SUITE_P(Reflectances, Furnace, ::testing::Values(0.3, 0.5, 0.8, 0.9));

// --- the estimate of the light not yet shot ---------------------------------------------

// An unconverged solve reads low by what is not shot yet; solution() puts an estimate of it
// into every read-out (Solver::ambient_irradiance: the unshot power U, landing at the rate r of
// the shots so far, reflected with the mean rho, spread over the area). In the closed furnace
// (rho 0.8: most of the light is still to come after a few shots) the estimate is exact on
// average: U lands whole (r = 1) and E/(1 - rho) is uniform. Stopped after 40 shots, the
// read-out with the estimate is within 1 % of E/(1 - rho) on average and at the centre of a
// wall (the estimate is even, the light still to come nearly so); without it, the read-out is
// short by the unshot share, here more than 10 %. In an open box (the furnace without its top
// face, so light escapes) the estimate is checked against its own definition: the irradiance
// power it adds, E_a A, is U r / (1 - rho r), r the power-weighted mean row sum.
TEST(UnshotEstimate, ReadOutsOfAnUnconvergedSolveDoNotReadLow) {
    ASSERT_TRUE(ensure_context());
    BuiltinOptions bo;
    bo.rho = 0.8;
    const Scene scene = make_builtin("furnace", bo);
    SolverOptions o = gpu_options(1e-9);
    o.max_shots = 40;
    Solver s(scene, o);
    while (s.step()) {}
    ASSERT_GT(s.unshot_fraction(), 0.1) << "the test needs an unconverged solve";
    const Hierarchy& h = s.solution();
    const double expected = 1.0 / (1.0 - 0.8);
    const double E_a = h.unshot_estimate().x;
    const double with = irradiance_sum(h) / scene.total_area();
    std::printf("furnace rho 0.80, %ld shots: unshot %.3g, estimate %.4g; <H> %.4g with it, "
                "%.4g without, expected %.4g\n",
                s.shots(), s.unshot_fraction(), E_a, with, with - E_a, expected);
    row("unshot", "<H> with the estimate", expected, with);
    EXPECT_GT(std::abs(with - E_a - expected) / expected, 0.1) << "without it, it reads low";
    const auto sp = find_surface(scene, {0, 0.5, 0.5}, {1, 0, 0}, 1e-6);
    ASSERT_TRUE(sp.has_value());
    row("unshot", "H wall x- centre with the estimate", expected, irradiance_at(h, *sp).x);

    // Open: the top face taken away, light escapes through it.
    Scene open = scene;
    const int top = open.find_group("y+");
    ASSERT_GE(top, 0);
    std::erase_if(open.polygons, [&](const Polygon& p) { return p.group == std::uint32_t(top); });
    Solver so(open, o);
    while (so.step()) {}
    const double landed = so.counters().landed, shot = so.counters().shot;
    ASSERT_GT(shot, 0);
    const double r = landed / shot;
    EXPECT_LT(r, 0.95) << "light escapes through the open top";
    double area = 0, rho_area = 0;
    for (const Polygon& p : open.polygons) {
        area += p.area;
        rho_area += open.material_of(p).rho.x * p.area;
    }
    const double rho = rho_area / area;
    const double U = so.unshot_power().x;
    const double predicted = U * r / ((1 - rho * r) * area);
    EXPECT_NEAR(so.solution().unshot_estimate().x, predicted, 1e-6 * predicted);
}
