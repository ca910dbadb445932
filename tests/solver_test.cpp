// The progressive solver on the CPU reference provider: analytic whole-solution cases
// (docs/references.md §2), energy bookkeeping on every shot, and agreement with the matrix solver.
#include <gtest/gtest.h>

#include <cmath>

#include "ff/bvh.h"
#include "hemirad/provider.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "solver/cluster_tree.h"
#include "solver/matrix_solver.h"

using namespace hemirad;

namespace {

SolverOptions cpu_options(double tolerance, int max_depth) {
    SolverOptions o;
    o.ff = "reference";
    o.tolerance = tolerance;
    o.hierarchy.max_depth = max_depth;
    o.hierarchy.patch_size = 1e-9; // always the maximum depth
    return o;
}

// Furnace (closed box, every face E = 1 and rho): B = E/(1 - rho) exactly for row sums of 1.
// The bound guarantees |B - B*|_1 <= tol * Phi: with tol 1e-3 every leaf must be within a
// few 1e-3 (the leaves near edges carry the largest form-factor error of the midpoint rule).
class Furnace : public ::testing::TestWithParam<double> {};

TEST_P(Furnace, ConvergesToEOverOneMinusRho) {
    const double rho = GetParam();
    BuiltinOptions bo;
    bo.rho = rho;
    const Scene scene = make_builtin("furnace", bo);
    Solver s(scene, cpu_options(1e-3, 2));
    while (s.step()) {}
    ASSERT_TRUE(s.converged());
    const Hierarchy& h = s.solution();
    const double expected = 1.0 / (1.0 - rho);
    double worst = 0, weighted = 0, area = 0;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
        for (std::uint32_t i = 0; i < 16; ++i) {
            const PatchAddress a{p, 2, i};
            const double B = h.radiosity(a).x;
            worst = std::max(worst, std::abs(B / expected - 1));
            weighted += B * h.node(a).area;
            area += h.node(a).area;
        }
    EXPECT_LT(std::abs(weighted / area / expected - 1), 0.005) << "area-average radiosity";
    EXPECT_LT(worst, 0.01) << "worst leaf";
}

INSTANTIATE_TEST_SUITE_P(Reflectances, Furnace, ::testing::Values(0.3, 0.5, 0.8));

// Energy: after every shot absorbed + escaped + unshot = emitted, and unshot never grows.
TEST(SolverEnergy, BalancedAfterEveryShotAndUnshotDecreases) {
    BuiltinOptions bo;
    bo.rho = 0.7;
    bo.subdiv = 2;
    const Scene scene = make_builtin("cube", bo);
    Solver s(scene, cpu_options(1e-4, 2));
    const dvec3 phi = s.emitted_power();
    double previous = 1e300;
    int shots = 0;
    while (s.step() && shots < 300) {
        ++shots;
        const dvec3 u = s.last_shot().unshot;
        const dvec3 total = s.absorbed_power() + s.escaped_power() + u;
        EXPECT_NEAR(total.x, phi.x, 1e-5 * phi.x) << "shot " << shots;
        const double sum = u.x + u.y + u.z;
        EXPECT_LE(sum, previous * (1 + 1e-9)) << "shot " << shots;
        previous = sum;
        // Closed cube: the reference provider's rows sum to 1 within its midpoint-rule error.
        EXPECT_NEAR(s.last_shot().row_sum, 1.0, 0.02) << "shot " << shots;
    }
    EXPECT_GT(shots, 10);
    // Closed scene: (almost) nothing escapes.
    EXPECT_LT(s.escaped_power().x, 0.01 * phi.x);
}

// Progressive shooting with leaf-to-leaf links solves the same linear system as the matrix
// solver; it must agree within the bound it reports: |B - B*|_1 <= bound * Phi.
TEST(SolverVsMatrix, ProgressiveAgreesWithGaussSeidelWithinItsBound) {
    BuiltinOptions bo;
    bo.subdiv = 2;
    bo.rho = 0.6;
    const Scene scene = make_builtin("cube", bo);
    SolverOptions o = cpu_options(1e-4, 1);
    o.flat = true;
    o.row_guard = false; // the matrix solver uses the form factors as they are
    const Discretisation disc = discretise(scene, o.hierarchy);
    auto provider = make_provider("reference", scene, disc, o.provider);
    provider->set_link_at_leaves(true);
    Solver s(scene, o, std::move(provider));
    while (s.step()) {}
    ASSERT_TRUE(s.converged());
    const Hierarchy& h = s.solution();
    auto reference = make_provider("reference", scene, disc, o.provider);
    const MatrixSolution m = solve_matrix(scene, disc, *reference, 1e-12);
    ASSERT_LT(m.residual, 1e-10);
    double diff = 0;
    for (std::size_t k = 0; k < m.leaves.size(); ++k) {
        const dvec3 d = h.radiosity(m.leaves[k]) - m.B[k];
        diff += (std::abs(d.x) + std::abs(d.y) + std::abs(d.z)) / 3 * h.node(m.leaves[k]).area;
    }
    const double bound = s.error_bound() * s.emitted_power().x;
    EXPECT_LE(diff, bound) << "L1 difference " << diff << " vs bound " << bound;
    EXPECT_GT(diff, 0.0); // the progressive solution is not yet exact: the bound is tested
}

// The hierarchy (greedy shooting from coarse nodes, adaptive linking) converges to the same
// solution as leaf-level shooting, up to its discretisation error (a few percent locally).
TEST(SolverVsMatrix, HierarchicalShootingIsCloseToMatrixSolution) {
    BuiltinOptions bo;
    bo.subdiv = 1;
    bo.rho = 0.5;
    const Scene scene = make_builtin("cube", bo);
    SolverOptions o = cpu_options(1e-4, 3);
    Solver s(scene, o);
    while (s.step()) {}
    const Hierarchy& h = s.solution();
    const Discretisation disc = discretise(scene, o.hierarchy);
    auto reference = make_provider("reference", scene, disc, o.provider);
    const MatrixSolution m = solve_matrix(scene, disc, *reference, 1e-12);
    double diff = 0, total = 0;
    for (std::size_t k = 0; k < m.leaves.size(); ++k) {
        diff += std::abs(h.radiosity(m.leaves[k]).x - m.B[k].x) * h.node(m.leaves[k]).area;
        total += m.B[k].x * h.node(m.leaves[k]).area;
    }
    EXPECT_LT(diff / total, 0.02);
}

TEST(SolverOptions, BadValuesAreInputErrors) {
    const Scene scene = make_builtin("furnace");
    SolverOptions o = cpu_options(0.01, 1);
    o.tolerance = 0;
    EXPECT_ANY_THROW(Solver(scene, o));
    o = cpu_options(0.01, 1);
    o.ff = "magic";
    EXPECT_ANY_THROW(Solver(scene, o));
    o = cpu_options(0.01, 1);
    o.shooter_power_fraction = 2;
    EXPECT_ANY_THROW(Solver(scene, o));
}

TEST(SolverStops, MaxShotsAndNoEmitter) {
    const Scene scene = make_builtin("cornell");
    SolverOptions o = cpu_options(1e-6, 2);
    o.max_shots = 3;
    Solver s(scene, o);
    int n = 0;
    while (s.step()) ++n;
    EXPECT_EQ(n, 3);
    EXPECT_EQ(s.stop_reason(), StopReason::MaxShots);
}

// in_thin_gap: a cluster's centre inside a 20 cm wall slab (its two faces among the cluster's
// polygons) is in a thin gap, as it is with the slab's faces two-sided (the twins back to
// back with them do not count as a second side); the air of the room beside it, a point
// beyond the slab's edge, or a gap wider than asked, is not.
TEST(ClusterCentre, InsideAWallSlabIsInAThinGap) {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    s.groups.push_back("g");
    add_polygon(s, {{4.9, 0, 0}, {4.9, 0, 3}, {4.9, 3, 3}, {4.9, 3, 0}}, 0, 0); // faces -x
    add_polygon(s, {{5.1, 0, 0}, {5.1, 3, 0}, {5.1, 3, 3}, {5.1, 0, 3}}, 0, 0); // faces +x
    add_polygon(s, {{0, 0, 0}, {0, 0, 3}, {4.9, 0, 3}, {4.9, 0, 0}}, 0, 0);     // floor
    finish_scene(s, "slab");
    ASSERT_EQ(s.polygons.size(), 3u);
    ASSERT_NEAR(s.polygons[0].normal.x, -1, 1e-12);
    ASSERT_NEAR(s.polygons[1].normal.x, 1, 1e-12);
    const std::vector<std::uint32_t> all = {0, 1, 2};
    EXPECT_TRUE(in_thin_gap(s, all, {4.95, 1.5, 1.5}, 0.5));
    EXPECT_FALSE(in_thin_gap(s, all, {4.95, 1.5, 1.5}, 0.15)) << "the gap is 0.2";
    EXPECT_FALSE(in_thin_gap(s, all, {4.7, 1.5, 1.5}, 0.5)) << "in the room";
    EXPECT_FALSE(in_thin_gap(s, all, {4.95, 1.5, 3.5}, 0.5)) << "beyond the slab's edge";
    EXPECT_FALSE(in_thin_gap(s, {0, 2}, {4.95, 1.5, 1.5}, 0.5)) << "one face only";
    make_two_sided(s, [](std::uint32_t) { return true; });
    ASSERT_EQ(s.polygons.size(), 6u);
    EXPECT_TRUE(in_thin_gap(s, {0, 1, 2, 3, 4, 5}, {4.95, 1.5, 1.5}, 0.5)) << "two-sided";
    EXPECT_FALSE(in_thin_gap(s, {0, 3}, {4.95, 1.5, 1.5}, 0.5)) << "a face and its twin";
    EXPECT_FALSE(in_thin_gap(s, {0, 1, 2, 3, 4, 5}, {4.7, 1.5, 1.5}, 0.5)) << "two-sided room";
}

// light_hidden_from_centre, on the office glb's case: a bookshelf board's underside (0.5 x 3 m,
// 40 cm in front of a 20 cm wall slab) in a cluster with the inner face of the slab's far
// side (3 x 3 m). Their area-weighted centre lies in the slab (x = 5.02); the board's points
// see it only through the slab's room face, so all of the board's light is hidden from it,
// while the slab's inner face sees it. From the air under the board nothing is hidden. The
// slab two-sided (its faces' twins back to back with them) changes nothing; a polygon
// without power is not judged.
TEST(ClusterCentre, LightBehindAWallIsHiddenFromTheCentre) {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    s.groups.push_back("g");
    add_polygon(s, {{4.9, 0, 0}, {4.9, 0, 3}, {4.9, 3, 3}, {4.9, 3, 0}}, 0, 0); // room face, -x
    add_polygon(s, {{5.1, 0, 0}, {5.1, 0, 3}, {5.1, 3, 3}, {5.1, 3, 0}}, 0, 0); // inner face, -x
    add_polygon(s, {{4.3, 1.5, 0}, {4.8, 1.5, 0}, {4.8, 1.5, 3}, {4.3, 1.5, 3}}, 0, 0); // board, -y
    finish_scene(s, "slab");
    ASSERT_NEAR(s.polygons[0].normal.x, -1, 1e-12);
    ASSERT_NEAR(s.polygons[1].normal.x, -1, 1e-12);
    ASSERT_NEAR(s.polygons[2].normal.y, -1, 1e-12);
    const std::vector<std::uint32_t> cluster = {2, 1};
    const dvec3 centre = (s.polygons[2].area * s.polygons[2].centroid() +
                          s.polygons[1].area * s.polygons[1].centroid()) /
                         (s.polygons[2].area + s.polygons[1].area);
    ASSERT_GT(centre.x, 4.9);
    ASSERT_LT(centre.x, 5.1);
    for (int two_sided = 0; two_sided < 2; ++two_sided) {
        if (two_sided) make_two_sided(s, [](std::uint32_t) { return true; });
        const Bvh bvh(s);
        std::vector<double> h = light_hidden_from_centre(s, bvh, cluster, {1, 1}, centre, 1e-4);
        EXPECT_EQ(h[0], 1.0) << "the board, through the slab's room face";
        EXPECT_EQ(h[1], 0.0) << "the slab's inner face";
        h = light_hidden_from_centre(s, bvh, cluster, {1, 1}, {4.55, 1.0, 1.5}, 1e-4);
        EXPECT_EQ(h[0], 0.0) << "under the board";
        EXPECT_EQ(h[1], 1.0) << "the inner face, from the room";
        h = light_hidden_from_centre(s, bvh, cluster, {1, 0}, centre, 1e-4);
        EXPECT_EQ(h[1], 0.0) << "no power, not judged";
    }
}

// cluster_sources, on a jar: a point cluster's centre inside a closed jar (its outer faces
// face away from it), a lining inside the jar facing the centre, a board outside facing the
// jar, and a polygon without power. Brightest first, shares of the total; the outer faces are
// hidden (the centre is behind them), the board too (the jar's wall blocks it), however
// little of the light it holds (0.07 %: past the 99 % that light_hidden_from_centre judges
// by rays), while the lining sees the centre.
TEST(ClusterCentre, SourcesThatDoNotSeeTheCentreAreMarked) {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    s.groups.push_back("g");
    add_polygon(s, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}, 0, 0);         // jar's top, +y
    add_polygon(s, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, 0, 0);         // jar's side, +x
    add_polygon(s, {{0.9, 0, 0}, {0.9, 0, 1}, {0.9, 1, 1}, {0.9, 1, 0}}, 0, 0); // lining, -x
    add_polygon(s, {{2, 0, 0}, {2, 0, 1}, {2, 1, 1}, {2, 1, 0}}, 0, 0);         // board, -x
    add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, 0, 0);         // jar's floor
    finish_scene(s, "jar");
    ASSERT_NEAR(s.polygons[0].normal.y, 1, 1e-12);
    ASSERT_NEAR(s.polygons[1].normal.x, 1, 1e-12);
    ASSERT_NEAR(s.polygons[2].normal.x, -1, 1e-12);
    ASSERT_NEAR(s.polygons[3].normal.x, -1, 1e-12);
    const Bvh bvh(s);
    const std::vector<double> power = {1, 2, 4, 0.005, 0};
    const double total = 7.005;
    const std::vector<ClusterShooter::Source> sources =
        cluster_sources(s, bvh, {0, 1, 2, 3, 4}, power, total, {0.5, 0.5, 0.5}, 1e-4);
    ASSERT_EQ(sources.size(), 4u) << "the polygon without power is no source";
    const std::uint32_t order[] = {2, 1, 0, 3};
    const bool hidden[] = {false, true, true, true};
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(sources[k].polygon, order[k]) << k;
        EXPECT_DOUBLE_EQ(sources[k].share, power[order[k]] / total) << k;
        EXPECT_EQ(sources[k].hidden_from_centre, hidden[k]) << "polygon " << order[k];
    }
    // From outside the jar, in front of the board, only the lining and the jar's top (both
    // with the point behind their planes) are hidden.
    const std::vector<ClusterShooter::Source> outside =
        cluster_sources(s, bvh, {0, 1, 2, 3, 4}, power, total, {1.5, 0.5, 0.5}, 1e-4);
    ASSERT_EQ(outside.size(), 4u);
    const bool hidden_outside[] = {true, false, true, false};
    for (std::size_t k = 0; k < 4; ++k)
        EXPECT_EQ(outside[k].hidden_from_centre, hidden_outside[k]) << "polygon " << order[k];
    // At most kMaxSources.
    const std::vector<std::uint32_t> many(40, 2);
    EXPECT_EQ(cluster_sources(s, bvh, many, std::vector<double>(40, 1.0), 40, {0.5, 0.5, 0.5}, 1e-4)
                  .size(),
              ClusterShooter::kMaxSources);
}

// light_off_centre, on the office glb's case: a bar of an LED light (1.4 x 86 cm, at x = 0)
// in a cluster with two faces of a bookshelf 1.5 m away (1.3 x 0.62 m, at x = 1.5). Their
// area-weighted centre lies 1 cm from the shelf (radius 2.12 m, to the bar's far corner).
// Lit alike per unit area, the light leaves around that centre; with the bar's power 50
// times each face's, its centroid is 1.94 m away, 0.92 of the radius: off centre at half the
// radius, not at 0.95 of it. Zero power anywhere is never off centre.
TEST(ClusterCentre, LightAwayFromTheCentreIsOffCentre) {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    s.groups.push_back("g");
    add_polygon(s, {{0, 0.05, -2.9}, {0, 0.05, -2.886}, {0, 0.91, -2.886}, {0, 0.91, -2.9}}, 0, 0);
    add_polygon(s, {{1.5, 0.1, -3.6}, {1.5, 0.1, -4.9}, {1.5, 0.72, -4.9}, {1.5, 0.72, -3.6}}, 0,
                0);
    add_polygon(s, {{1.5, 0.72, -3.6}, {1.5, 0.72, -4.9}, {1.5, 1.34, -4.9}, {1.5, 1.34, -3.6}}, 0,
                0);
    finish_scene(s, "bar and shelf");
    ASSERT_EQ(s.polygons.size(), 3u);
    const std::vector<std::uint32_t> all = {0, 1, 2};
    dvec3 centre(0.0);
    double area = 0;
    for (std::uint32_t p : all) {
        centre += s.polygons[p].area * s.polygons[p].centroid();
        area += s.polygons[p].area;
    }
    centre /= area;
    double radius = 0;
    for (std::uint32_t p : all)
        for (int k = 0; k < s.polygons[p].count; ++k)
            radius = std::max(radius, glm::length(s.polygons[p].v[std::size_t(k)] - centre));
    ASSERT_LT(std::abs(centre.x - 1.5), 0.02) << "the shelf's area dominates";
    std::vector<double> alike;
    for (std::uint32_t p : all) alike.push_back(s.polygons[p].area); // the same exitance
    EXPECT_FALSE(light_off_centre(s, all, alike, centre, 0.5 * radius));
    const std::vector<double> bar_bright = {50, 1, 1};
    EXPECT_TRUE(light_off_centre(s, all, bar_bright, centre, 0.5 * radius));
    EXPECT_FALSE(light_off_centre(s, all, bar_bright, centre, 0.95 * radius)) << "0.92 R";
    EXPECT_FALSE(light_off_centre(s, all, {0, 0, 0}, centre, 0.5 * radius)) << "no light";
    EXPECT_FALSE(light_off_centre(s, all, {0, 1, 1}, centre, 0.5 * radius)) << "the shelf only";
}

} // namespace
