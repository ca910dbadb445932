// The Monte-Carlo irradiance reference (reference.h) against closed forms only — never against
// hemirad's own form factors: Howell's point-to-rectangle factors (docs/references.md §1(c1)) for
// direct light, the furnace (§2.1) for every bounce and Russian roulette, exact zeros for
// occlusion, backs and emitters facing away, and the honesty of the reported standard error.
//
// Tolerances: a Monte-Carlo mean is checked as |E - exact| <= 4 sem + 1e-9 exact, i.e. within
// 4 standard errors (a correct estimator fails it with probability ~6e-5 per check; the seeds
// are fixed, so the outcome is deterministic). Each check also requires sem to be small
// (relative sem below a stated bound), so that the 4-sem window actually tests something.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <ostream>
#include <string>
#include <vector>

#include "core/sampling.h"
#include "hemirad/error.h"
#include "hemirad/reference.h"
#include "hemirad/scene_io.h"

using namespace hemirad;

namespace {

constexpr double kPi = std::numbers::pi;

// Howell B-3: element parallel to an a x b rectangle at distance c, its normal through a
// corner. X = a/c, Y = b/c.
double howell_b3(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * kPi);
}

// Howell B-4: element at the origin, normal +z; rectangle in the plane y = d facing it,
// 0 <= x <= L, 0 <= z <= H.
double howell_b4(double H, double d, double L) {
    const double s = std::sqrt(H * H + d * d);
    return (std::atan(L / d) - d / s * std::atan(L / s)) / (2 * kPi);
}

// A scene built in code: materials, one group per material, quads facing a given way.
struct Builder {
    Scene scene;
    std::uint32_t material(const std::string& name, dvec3 rho, dvec3 Ke = dvec3(0.0)) {
        scene.materials.push_back(Material{name, rho, Ke});
        scene.groups.push_back(name);
        return std::uint32_t(scene.materials.size() - 1);
    }
    // A quad whose front faces along `facing` (corner order flipped if needed).
    void quad(std::vector<dvec3> c, const dvec3& facing, std::uint32_t m) {
        if (glm::dot(glm::cross(c[1] - c[0], c[2] - c[0]), facing) < 0)
            std::reverse(c.begin(), c.end());
        ASSERT_EQ(add_polygon(scene, c, m, m).added, 1);
    }
    // Rectangle [x0,x1] x [y0,y1] in the plane z.
    void rect_z(double x0, double x1, double y0, double y1, double z, const dvec3& facing,
                std::uint32_t m) {
        quad({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, facing, m);
    }
    // Closed box [lo, hi], faces outwards.
    void box(const dvec3& lo, const dvec3& hi, std::uint32_t m) {
        rect_z(lo.x, hi.x, lo.y, hi.y, lo.z, {0, 0, -1}, m);
        rect_z(lo.x, hi.x, lo.y, hi.y, hi.z, {0, 0, 1}, m);
        quad({{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}},
             {0, -1, 0}, m);
        quad({{lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}},
             {0, 1, 0}, m);
        quad({{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {lo.x, lo.y, hi.z}},
             {-1, 0, 0}, m);
        quad({{hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}},
             {1, 0, 0}, m);
    }
    Scene finish() {
        finish_scene(scene, "test");
        return scene;
    }
};

ReferenceOptions with_samples(long samples, std::uint64_t seed = 1) {
    ReferenceOptions o;
    o.samples = samples;
    o.seed = seed;
    return o;
}

// |E - exact| <= 4 sem + 1e-9 exact per channel, and sem <= max_rel * exact.
void expect_estimate(const ReferenceValue& v, const dvec3& exact, double max_rel,
                     const std::string& what) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_LE(std::abs(v.E[c] - exact[c]), 4 * v.sem[c] + 1e-9 * exact[c])
            << what << " channel " << c << ": E " << v.E[c] << " exact " << exact[c] << " sem "
            << v.sem[c];
        EXPECT_LE(v.sem[c], max_rel * exact[c]) << what << " channel " << c;
    }
}

// --- direct light against Howell's factors ---------------------------------------------

const dvec3 kKe(1.0, 2.0, 0.5); // emitted radiance of the test emitters [W sr^-1 unit^-2]

struct DirectCase {
    std::string name;
    std::vector<dvec3> emitter; ///< corners
    dvec3 facing;               ///< the emitter's front
    double F;                   ///< closed form: E = pi Ke F at the origin, normal +z
    double howell;              ///< the catalogue's 6-digit value, to check the formula
};
void PrintTo(const DirectCase& c, std::ostream* os) {
    *os << c.name;
}

std::vector<DirectCase> direct_cases() {
    return {
        // 1x1 square centred over the point at c = 1: four B-3 corners of 0.5 x 0.5.
        {"square_centre",
         {{-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1}},
         {0, 0, -1},
         4 * howell_b3(0.5, 0.5, 1),
         0.239456},
        {"b3_2x1_corner",
         {{0, 0, 1}, {2, 0, 1}, {2, 1, 1}, {0, 1, 1}},
         {0, 0, -1},
         howell_b3(2, 1, 1),
         0.167375},
        {"b4_perpendicular",
         {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}},
         {0, -1, 0},
         howell_b4(1, 1, 1),
         0.055734},
    };
}

class Direct : public ::testing::TestWithParam<DirectCase> {};

TEST_P(Direct, MatchesHowell) {
    const DirectCase& c = GetParam();
    ASSERT_NEAR(c.F, c.howell, 6e-7) << "closed form vs catalogue";
    const dvec3 exact = kPi * kKe * c.F;
    // Free space: only the emitter; rho = 0, so E is the direct irradiance alone.
    {
        Builder b;
        b.quad(c.emitter, c.facing, b.material("light", dvec3(0.0), kKe));
        const Scene scene = b.finish();
        const auto v =
            reference_irradiance(scene, {Probe{{0, 0, 0}, {0, 0, 2}}}, with_samples(1 << 18));
        EXPECT_FALSE(v[0].on_surface);
        expect_estimate(v[0], exact, 0.002, c.name + " in free space");
    }
    // The same point on a black floor (the probe's polygon is ignored by its own rays).
    {
        Builder b;
        b.quad(c.emitter, c.facing, b.material("light", dvec3(0.0), kKe));
        b.rect_z(-2, 2, -2, 2, 0, {0, 0, 1}, b.material("floor", dvec3(0.0)));
        const Scene scene = b.finish();
        const auto v =
            reference_irradiance(scene, {Probe{{0, 0, 0}, {0, 0, 1}}}, with_samples(1 << 18, 7));
        EXPECT_TRUE(v[0].on_surface);
        EXPECT_EQ(v[0].polygon, 1u);
        expect_estimate(v[0], exact, 0.002, c.name + " on a floor");
    }
}

INSTANTIATE_TEST_SUITE_P(Howell, Direct, ::testing::ValuesIn(direct_cases()),
                         [](const auto& info) { return info.param.name; });

// --- exact zeros and partial occlusion --------------------------------------------------

Scene square_light_with(const std::function<void(Builder&)>& extra) {
    Builder b;
    b.rect_z(-0.5, 0.5, -0.5, 0.5, 1, {0, 0, -1}, b.material("light", dvec3(0.0), kKe));
    extra(b);
    return b.finish();
}

TEST(ReferenceOcclusion, BlockerBetweenPointAndEmitterGivesZero) {
    for (const double facing : {-1.0, 1.0}) { // one-sided surfaces block from either side
        const Scene scene = square_light_with([&](Builder& b) {
            b.rect_z(-2, 2, -2, 2, 0.5, {0, 0, facing}, b.material("blocker", dvec3(0.0)));
        });
        const auto v =
            reference_irradiance(scene, {Probe{{0, 0, 0}, {0, 0, 1}}}, with_samples(4096));
        EXPECT_EQ(v[0].E, dvec3(0.0)) << "blocker facing " << facing;
        EXPECT_EQ(v[0].sem, dvec3(0.0));
    }
}

TEST(ReferenceOcclusion, HalfBlockedEmitterGivesHalf) {
    // A black half-plane x > 0 at z = 0.5 hides exactly half of the square (by symmetry about
    // x = 0 seen from the origin: the square's points with x > 0 project through x > 0).
    const Scene scene = square_light_with([](Builder& b) {
        b.rect_z(0, 3, -3, 3, 0.5, {0, 0, -1}, b.material("blocker", dvec3(0.0)));
    });
    const auto v =
        reference_irradiance(scene, {Probe{{0, 0, 0}, {0, 0, 1}}}, with_samples(1 << 18));
    expect_estimate(v[0], 0.5 * kPi * kKe * (4 * howell_b3(0.5, 0.5, 1)), 0.002, "half blocked");
}

TEST(ReferenceOneSided, EmitterFacingAwayGivesZero) {
    Builder b;
    b.rect_z(-0.5, 0.5, -0.5, 0.5, 1, {0, 0, 1}, b.material("light", dvec3(0.0), kKe));
    const Scene scene = b.finish();
    const auto v = reference_irradiance(scene, {Probe{{0, 0, 0}, {0, 0, 1}}}, with_samples(4096));
    EXPECT_EQ(v[0].E, dvec3(0.0));
}

TEST(ReferenceOneSided, BackOfALitReflectorGivesZero) {
    // A white plate at z = 1 shows the point its back; an emitter above lights its front.
    // Backs reflect nothing, and the plate hides the emitter: E = 0 exactly.
    Builder b;
    b.rect_z(-0.5, 0.5, -0.5, 0.5, 2, {0, 0, -1}, b.material("light", dvec3(0.0), kKe));
    b.rect_z(-3, 3, -3, 3, 1, {0, 0, 1}, b.material("white", dvec3(0.9)));
    const Scene scene = b.finish();
    const auto v = reference_irradiance(scene, {Probe{{0, 0, 0}, {0, 0, 1}}}, with_samples(4096));
    EXPECT_EQ(v[0].E, dvec3(0.0));
}

TEST(ReferenceOneSided, PointBelowTheHorizonOfAnEmitterSeesNothing) {
    // The emitter lies in the half-space behind the point's normal.
    Builder b;
    b.rect_z(-0.5, 0.5, -0.5, 0.5, -1, {0, 0, 1}, b.material("light", dvec3(0.0), kKe));
    const Scene scene = b.finish();
    const auto v = reference_irradiance(scene, {Probe{{0, 0, 0}, {0, 0, 1}}}, with_samples(4096));
    EXPECT_EQ(v[0].E, dvec3(0.0));
}

// --- furnace: every bounce ---------------------------------------------------------------

// Points on the inside of the unit box, away from and near edges and corners (the last is
// 1e-3 from two faces: the MIS estimator's variance stays finite there).
std::vector<Probe> furnace_probes() {
    return {
        {{0.5, 0.0, 0.5}, {0, 1, 0}},   {{0.0, 0.3, 0.7}, {1, 0, 0}},
        {{0.2, 1.0, 0.9}, {0, -1, 0}},  {{0.6, 0.4, 1.0}, {0, 0, -1}},
        {{1.0, 0.5, 0.03}, {-1, 0, 0}}, {{0.001, 0.0, 0.001}, {0, 1, 0}},
    };
}

struct FurnaceCase {
    int subdiv;
    dvec3 rho;
};
void PrintTo(const FurnaceCase& c, std::ostream* os) {
    *os << "subdiv " << c.subdiv << " rho " << c.rho.x << "," << c.rho.y << "," << c.rho.z;
}
class ReferenceFurnace : public ::testing::TestWithParam<FurnaceCase> {};

// Closed box, every face Be = pi Ke = 1 and reflectance rho: E = Be / (1 - rho) everywhere
// (docs/references.md §2.1), per channel. Paths end by Russian roulette only, so this checks that
// the roulette and the per-channel weights rho/q are unbiased. subdiv 1: 6 emitters, all
// sampled at every vertex; subdiv 3: 54 emitters, one picked by power, and coplanar
// neighbours whose shared edges rays must not leak through.
TEST_P(ReferenceFurnace, IrradianceIsBeOverOneMinusRho) {
    const FurnaceCase& c = GetParam();
    BuiltinOptions bo;
    bo.subdiv = c.subdiv;
    Scene scene = make_builtin("furnace", bo);
    for (Material& m : scene.materials) m.rho = c.rho;
    const dvec3 exact = 1.0 / (1.0 - c.rho);
    const auto values = reference_irradiance(scene, furnace_probes(), with_samples(16384));
    for (std::size_t i = 0; i < values.size(); ++i) {
        EXPECT_TRUE(values[i].on_surface) << "point " << i;
        expect_estimate(values[i], exact, 0.01, "point " + std::to_string(i));
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, ReferenceFurnace,
                         ::testing::Values(FurnaceCase{1, dvec3(0.5)},
                                           FurnaceCase{1, dvec3(0.2, 0.5, 0.8)},
                                           FurnaceCase{3, dvec3(0.5)}),
                         [](const auto& info) {
                             return std::string(info.param.rho.x == info.param.rho.z ? "grey"
                                                                                     : "coloured") +
                                    "_subdiv" + std::to_string(info.param.subdiv);
                         });

// A furnace with a box inside it (same emission and reflectance, faces outwards): still
// E = Be/(1 - rho) on every front, now with occlusion, and the inner box's backs never seen.
TEST(ReferenceFurnace, BoxInsideAFurnaceStaysUniform) {
    Scene scene = make_builtin("furnace");
    const double rho = scene.materials[0].rho.x;
    Builder b;
    b.scene = scene;
    b.box({0.3, 0.1, 0.3}, {0.7, 0.4, 0.6}, scene.polygons[0].material);
    scene = b.finish();
    const std::vector<Probe> probes = {
        {{0.5, 0.4, 0.45}, {0, 1, 0}},   // top of the inner box
        {{0.3, 0.25, 0.45}, {-1, 0, 0}}, // its side
        {{0.2, 0.0, 0.45}, {0, 1, 0}},   // floor next to it
        {{0.5, 1.0, 0.45}, {0, -1, 0}},  // ceiling above it
    };
    const auto values = reference_irradiance(scene, probes, with_samples(4096));
    for (std::size_t i = 0; i < values.size(); ++i) {
        EXPECT_TRUE(values[i].on_surface) << "point " << i;
        expect_estimate(values[i], dvec3(1.0 / (1.0 - rho)), 0.02, "point " + std::to_string(i));
    }
}

// max_bounces = k: light reflected at most k times; in the furnace, Be (1 + rho + ... + rho^k).
TEST(ReferenceFurnace, MaxBouncesTruncatesTheSeries) {
    const Scene scene = make_builtin("furnace"); // rho 0.5
    for (const int k : {1, 2}) {
        ReferenceOptions o = with_samples(4096);
        o.max_bounces = k;
        const auto v = reference_irradiance(scene, {Probe{{0.5, 0, 0.5}, {0, 1, 0}}}, o);
        const double exact = k == 1 ? 1.5 : 1.75;
        expect_estimate(v[0], dvec3(exact), 0.01, "max_bounces " + std::to_string(k));
    }
}

// --- the reported standard error is honest -----------------------------------------------

// 64 independent estimates (one per point index, the same point) of a known value: the
// z-scores (E - exact)/sem should be standard normal, so mean z^2 should be 1 with a
// standard deviation of sqrt(2/64) = 0.18. [0.45, 1.75] is about 3 of them either way; a
// sem that is 2x too small or too large fails it.
TEST(ReferenceSem, ZScoresHaveUnitVariance) {
    const Scene scene = make_builtin("furnace"); // rho 0.5, E = 2
    const std::vector<Probe> probes(64, Probe{{0.3, 0.0, 0.6}, {0, 1, 0}});
    const auto values = reference_irradiance(scene, probes, with_samples(512));
    double z2 = 0;
    for (const ReferenceValue& v : values) z2 += std::pow((v.E.x - 2.0) / v.sem.x, 2);
    z2 /= double(values.size());
    EXPECT_GT(z2, 0.45);
    EXPECT_LT(z2, 1.75);
}

// --- energy balance in a closed box with a different reflectance on every face ----------------

// In a closed enclosure absorbed = emitted, per channel (docs/references.md §2.2):
// sum_i A_i (1 - rho_i) H_i = Phi = sum_i A_i Be_i, for any reflectances. Here a unit box,
// lit by its ceiling (Be = 1, so Phi = 1), with other reflectances per face and per channel:
// the irradiance is far from uniform and every bounce matters. The left side is an area
// integral over the box's surface, estimated at M points uniform by area (X_k = S (1 - rho)
// E_k with S = 6 the total area): its mean is unbiased and its standard error is the sample
// standard deviation of the X_k / sqrt(M) (the points and their paths are independent).
TEST(ReferenceEnergy, AbsorbedEqualsEmittedInAClosedBox) {
    Builder b;
    const dvec3 rho[6] = {{0.2, 0.5, 0.8}, {0.8, 0.5, 0.2}, {0.5, 0.5, 0.5},
                          {0.3, 0.3, 0.3}, {0.7, 0.1, 0.4}, {0.4, 0.6, 0.9}};
    std::uint32_t m[6];
    for (int f = 0; f < 6; ++f)
        m[f] =
            b.material("face" + std::to_string(f), rho[f], f == 3 ? dvec3(1.0 / kPi) : dvec3(0.0));
    // Faces facing inwards: x = 0, x = 1, y = 0, y = 1 (the light), z = 0, z = 1.
    for (int f = 0; f < 6; ++f) {
        const int axis = f / 2;
        const double at = f % 2;
        std::vector<dvec3> c(4, dvec3(at));
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const double uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int k = 0; k < 4; ++k) {
            c[k][u] = uv[k][0];
            c[k][v] = uv[k][1];
        }
        dvec3 inward(0.0);
        inward[axis] = at == 0 ? 1 : -1;
        b.quad(c, inward, m[f]);
    }
    const Scene scene = b.finish();
    // Points uniform by area, from a generator of their own.
    Rng rng(2024);
    std::vector<Probe> probes;
    std::vector<int> face;
    constexpr int M = 4000;
    for (int k = 0; k < M; ++k) {
        const int f = std::min(5, int(rng.uniform() * 6));
        const int axis = f / 2;
        dvec3 p(rng.uniform(), rng.uniform(), rng.uniform()), n(0.0);
        p[axis] = f % 2;
        n[axis] = f % 2 == 0 ? 1 : -1;
        probes.push_back({p, n});
        face.push_back(f);
    }
    const auto values = reference_irradiance(scene, probes, with_samples(16));
    dvec3 sum(0.0), sum2(0.0);
    for (int k = 0; k < M; ++k) {
        ASSERT_TRUE(values[k].on_surface) << "point " << k;
        ASSERT_EQ(values[k].polygon, std::uint32_t(face[k])) << "point " << k;
        const dvec3 X = 6.0 * (1.0 - rho[face[k]]) * values[k].E;
        sum += X;
        sum2 += X * X;
    }
    const dvec3 mean = sum / double(M);
    const dvec3 sem = glm::sqrt((sum2 / double(M) - mean * mean) / double(M - 1));
    ReferenceValue absorbed;
    absorbed.E = mean;
    absorbed.sem = sem;
    expect_estimate(absorbed, dvec3(1.0), 0.02, "absorbed power");
}

// --- determinism and options ---------------------------------------------------------------

TEST(ReferenceDeterminism, SameResultWithOneAndTwoThreads) {
    const Scene scene = make_builtin("cornell");
    const std::vector<Probe> probes = {
        {{278, 0, 280}, {0, 1, 0}},      {{0, 274, 280}, {1, 0, 0}},
        {{278, 548.8, 100}, {0, -1, 0}}, {{278, 274, 559.2}, {0, 0, -1}},
        {{200, 165, 170}, {0, 1, 0}},    {{278, 274, 280}, {0, 1, 0}}, // free space
    };
    ReferenceOptions o = with_samples(256, 42);
    o.threads = 1;
    const auto one = reference_irradiance(scene, probes, o);
    o.threads = 2;
    const auto two = reference_irradiance(scene, probes, o);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
        EXPECT_EQ(one[i].E, two[i].E) << "point " << i;
        EXPECT_EQ(one[i].sem, two[i].sem) << "point " << i;
        EXPECT_EQ(one[i].on_surface, i != 5) << "point " << i;
        EXPECT_GT(one[i].E.x, 0) << "point " << i;
    }
    // A point's value does not depend on the others: the same point alone (index 0).
    const auto alone = reference_irradiance(scene, {probes[0]}, o);
    EXPECT_EQ(alone[0].E, one[0].E);
    // Another seed, other numbers.
    o.seed = 43;
    EXPECT_NE(reference_irradiance(scene, {probes[0]}, o)[0].E, one[0].E);
}

TEST(ReferenceOptions, OutOfRangeValuesNameTheOption) {
    const Scene scene = make_builtin("cube");
    const std::vector<Probe> probes = {{{0.5, 0, 0.5}, {0, 1, 0}}};
    const auto message = [&](ReferenceOptions o) {
        try {
            reference_irradiance(scene, probes, o);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    ReferenceOptions o;
    o.samples = 0;
    EXPECT_NE(message(o).find("--samples 0"), std::string::npos) << message(o);
    o = {};
    o.threads = -1;
    EXPECT_NE(message(o).find("--threads -1"), std::string::npos) << message(o);
    o = {};
    o.max_bounces = -2;
    EXPECT_NE(message(o).find("--max-bounces -2"), std::string::npos) << message(o);
}

TEST(ReferenceOptions, ProbeWithoutANormalIsAnInputError) {
    const Scene scene = make_builtin("cube");
    const std::vector<Probe> probes = {{{0.5, 0, 0.5}, {0, 1, 0}}, {{0.5, 0, 0.5}, {0, 0, 0}}};
    EXPECT_THROW(reference_irradiance(scene, probes, with_samples(4)), InputError);
}

TEST(ReferenceOptions, OneSampleHasNoStandardError) {
    const Scene scene = make_builtin("cube");
    const auto v = reference_irradiance(scene, {Probe{{0.5, 0, 0.5}, {0, 1, 0}}}, with_samples(1));
    EXPECT_TRUE(std::isnan(v[0].sem.x));
    EXPECT_EQ(median_relative_sem(v), 0.0);
}

TEST(ReferenceCsv, ColumnsOfSolvePlusStandardErrors) {
    const Scene scene = make_builtin("cube");
    const std::vector<Probe> probes = {{{0.5, 0, 0.5}, {0, 1, 0}}, {{0.5, 0.5, 0.5}, {0, 1, 0}}};
    const auto v = reference_irradiance(scene, probes, with_samples(16));
    const std::string csv = reference_csv(scene, probes, v);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "x,y,z,nx,ny,nz,E_r,E_g,E_b,polygon,group,sem_r,sem_g,sem_b");
    EXPECT_NE(csv.find(",y-,"), std::string::npos) << csv;    // on the floor
    EXPECT_NE(csv.find(",,none,"), std::string::npos) << csv; // in free space
}

} // namespace
