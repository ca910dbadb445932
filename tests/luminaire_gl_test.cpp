// Point-source luminaires (photometry.h) shot by the GPU hemicube provider and read out by the
// final gather, checked against closed forms:
//  - the inverse-square-cosine law E = I(gamma) cos(theta) / r^2 on a black plane at every
//    point of a grid, for an isotropic source and for IES distributions (1 %);
//  - a point shot's row sum (the fraction of the flux that reaches a square) against the
//    square's solid angle (isotropic) or the Howell B-3 form factor (a Lambertian downlight);
//  - energy balance at every shot (emitted = absorbed + escaped + unshot) in a closed grey room;
//  - a point source in the CIE 171 room (black; references from the stated geometry);
//  - hard shadows, and the path-traced reference (reference.h) against the gather.
//  - each group of the courtyard takes its exact direct flux from the luminaire shots.
// Units: 1 cd = 1/683 W/sr per channel, so E [W m^-2] * 683 is lux.
//
// Needs a GL context (Mesa llvmpipe here): failing to get one FAILS the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>

#include "gltf_lights_scene.h"
#include "hemirad/gather.h"
#include "hemirad/gl/context.h"
#include "hemirad/grid.h"
#include "hemirad/patch.h"
#include "hemirad/provider.h"
#include "hemirad/readout.h"
#include "hemirad/reference.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "hemirad/validation_scenes.h"

using namespace hemirad;

namespace {

constexpr double kPi = std::numbers::pi;
const std::string kIes = std::string(HEMIRAD_TEST_DATA) + "/ies/";

bool ensure_context() {
    static std::unique_ptr<gl::Context> context;
    if (!context) context = gl::Context::create();
    return context != nullptr;
}

SolverOptions gpu_options() {
    SolverOptions o; // hybrid
    o.provider.gpu.use_current_context = true;
    o.tolerance = 1e-3;
    return o;
}

// For the grey room (rho 0.5): a coarser bound and hemicube, to keep the test short.
SolverOptions room_options() {
    SolverOptions o = gpu_options();
    o.tolerance = 0.02;
    o.provider.gpu.max_resolution = 128;
    return o;
}

Luminaire candela(double I, const dvec3& position) {
    Luminaire l;
    l.name = "point";
    l.kind = "candela";
    l.distribution = isotropic_distribution(I);
    l.position = position;
    l.orient();
    return l;
}

Luminaire ies(const std::string& file, const dvec3& position, double rotation = 0) {
    Luminaire l;
    l.name = file;
    l.kind = "ies";
    l.file = kIes + file;
    l.distribution = read_ies(l.file).distribution;
    l.position = position;
    l.rotation = rotation;
    l.orient();
    return l;
}

// A black square [-a, a]^2 at y = 0 facing up (group "floor"), split into n x n quads.
Scene black_plane(double a, int n, const std::vector<Luminaire>& luminaires) {
    Scene s;
    s.source = "test:black_plane";
    s.materials.push_back({"black", dvec3(0.0), dvec3(0.0)});
    s.groups.push_back("floor");
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x0 = -a + 2 * a * i / n, x1 = -a + 2 * a * (i + 1) / n;
            const double z0 = -a + 2 * a * j / n, z1 = -a + 2 * a * (j + 1) / n;
            add_polygon(s, {{x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}, {x0, 0, z0}}, 0, 0);
        }
    s.luminaires = luminaires;
    finish_scene(s, s.source);
    return s;
}

double howell_b3(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * kPi);
}

struct LawCase {
    const char* name;
    Luminaire luminaire;
    // The analytic intensity [cd] at (gamma, C) in degrees, independent of the table.
    double (*intensity)(double gamma, double c);
    double tolerance; // relative, per point (the table's interpolation of the function)
};

double cosd(double d) {
    return std::cos(d * kPi / 180);
}

} // namespace

// E = I(gamma) cos(theta) / r^2 at every point of a 9 x 9 grid on a black floor, for an
// isotropic source, a Lambertian IES downlight (cosine.ies) and an asymmetric IES distribution
// turned by 30 degrees (bilateral_0_180.ies: I = 1000 cos(gamma) (1 + 0.3 cos C)). The
// reference is the analytic function, not the table: the test also checks the frame (gamma
// from the aim, C counterclockwise from above, the rotation). Also the solver's own leaves.
TEST(Luminaire, InverseSquareCosineLawOnABlackPlane) {
    ASSERT_TRUE(ensure_context());
    const dvec3 at(0.3, 2.8, -0.2);
    const LawCase cases[] = {
        {"isotropic 500 cd", candela(500, at), [](double, double) { return 500.0; }, 1e-9},
        {"cosine.ies", ies("cosine.ies", at), [](double g, double) { return 1000 * cosd(g); },
         2e-3},
        {"bilateral_0_180.ies rotated 30", ies("bilateral_0_180.ies", at, 30),
         [](double g, double c) { return 1000 * cosd(g) * (1 + 0.3 * cosd(c - 30)); }, 5e-3},
    };
    for (const LawCase& c : cases) {
        const Scene scene = black_plane(2.0, 2, {c.luminaire});
        Solver s(scene, gpu_options());
        while (s.step()) {}
        ASSERT_TRUE(s.converged()) << c.name;
        EXPECT_EQ(s.shots(), 1) << c.name << ": one shot, the luminaire's";
        const Hierarchy& h = s.solution();
        const FinalGather gather(h);
        const GridResult g = evaluate_grid(h, {"floor", 9, 9}, &gather);
        ASSERT_EQ(g.evaluated, 81);
        double worst = 0, worst_leaf = 0;
        for (const GridPoint& p : g.points) {
            const dvec3 d = p.position - at;
            const double r = glm::length(d);
            const double gamma = std::acos(-d.y / r) * 180 / kPi;
            // C counterclockwise seen from above, from +x: +x -> -z.
            double C = std::atan2(-d.z, d.x) * 180 / kPi;
            const double lux = c.intensity(gamma, C) * (at.y / r) / (r * r);
            const double ours = kLumensPerWatt * p.E.y;
            EXPECT_NEAR(ours, lux, c.tolerance * lux)
                << c.name << " at " << p.position.x << "," << p.position.z;
            worst = std::max(worst, std::abs(ours / lux - 1));
            const double leaf =
                kLumensPerWatt *
                irradiance_at(h, *find_surface(scene, p.position, dvec3(0, 1, 0))).y;
            worst_leaf = std::max(worst_leaf, std::abs(leaf / lux - 1));
            EXPECT_NEAR(p.E.x, p.E.y, 1e-12 * p.E.y) << "equal RGB";
        }
        std::printf("%-32s gather: worst %.2e   leaves (interpolated): worst %.2f %%\n", c.name,
                    worst, 100 * worst_leaf);
        // The solver's own answer, leaves interpolated (no gather): the linking samples each
        // node at its centre. A few percent on this smooth field.
        EXPECT_LT(worst_leaf, 0.03) << c.name;
    }
}

// A spot aimed obliquely (cone 20, falloff 10 degrees, 2000 cd): the gather gives
// I(gamma) cos(theta) / r^2 with gamma measured from the aim, full inside the cone, linear in
// the falloff band, nothing beyond; the luminaire's lumens are the spot's closed form.
TEST(Luminaire, SpotLight) {
    ASSERT_TRUE(ensure_context());
    Luminaire spot;
    spot.name = "S1";
    spot.kind = "spot";
    spot.distribution = spot_distribution(2000, 20, 10);
    spot.position = {0, 2, 0};
    spot.aim = {0.5, -1, 0.2};
    spot.orient();
    const Scene scene = black_plane(3.0, 2, {spot});
    Solver s(scene, gpu_options());
    while (s.step()) {}
    const Hierarchy& h = s.solution();
    const FinalGather gather(h);
    const GridResult g = evaluate_grid(h, {"floor", 15, 15}, &gather);
    int inside = 0, band = 0, dark = 0;
    for (const GridPoint& p : g.points) {
        const dvec3 d = p.position - spot.position;
        const double r = glm::length(d);
        const double gamma = std::acos(glm::dot(d / r, spot.aim)) * 180 / kPi;
        const double I = gamma <= 20 ? 2000 : gamma < 30 ? 2000 * (30 - gamma) / 10 : 0;
        const double lux = I * (2 / r) / (r * r);
        EXPECT_NEAR(kLumensPerWatt * p.E.y, lux, 1e-9 * 2000) << gamma;
        (gamma <= 20 ? inside : gamma < 30 ? band : dark) += 1;
    }
    EXPECT_GT(inside, 3);
    EXPECT_GT(band, 3);
    EXPECT_GT(dark, 3);
    // Flux: 2 pi I [(1 - cos 20) + int_20^30 (30 - g)/10 sin g dg], the latter in closed form.
    const double a = 20 * kPi / 180, b = 30 * kPi / 180;
    const double fall = (std::cos(a) - (std::sin(b) - std::sin(a)) / (b - a));
    EXPECT_NEAR(spot.lumens(), 2 * kPi * 2000 * (1 - std::cos(a) + fall), 1e-9 * spot.lumens());
}

// A point shot's row sum, sum_j ff_j A_j: the fraction of the flux that reaches a square of
// side 2a at distance h below the source. Isotropic: the square's solid angle / 4 pi,
// 4 asin(a^2 / (a^2 + h^2)) / (4 pi). Lambertian downlight (I = I0 cos gamma, flux pi I0): the
// form factor from a downward element to the square, 4 B-3(a, a, h). The GPU provider (hybrid,
// analytic, hemicube) and the CPU reference provider.
TEST(Luminaire, PointShotRowSumIsTheFractionReceived) {
    ASSERT_TRUE(ensure_context());
    const double a = 2.0, h = 1.5;
    const Luminaire iso = candela(100, {0, h, 0});
    const Luminaire down = ies("cosine.ies", {0, h, 0});
    const double want_iso = 4 * std::asin(a * a / (a * a + h * h)) / (4 * kPi);
    const double want_down = 4 * howell_b3(a, a, h);
    for (const char* ff : {"hybrid", "analytic", "hemicube", "reference"}) {
        for (const auto& [l, want] : {std::pair{iso, want_iso}, std::pair{down, want_down}}) {
            const Scene scene = black_plane(a, 3, {l});
            const Discretisation disc = discretise(scene, HierarchyOptions{});
            ProviderOptions po;
            po.gpu.use_current_context = true;
            const std::unique_ptr<FormFactorProvider> p = make_provider(ff, scene, disc, po);
            std::vector<Link> links;
            p->shoot_point(scene.luminaires[0], links);
            ASSERT_FALSE(links.empty()) << ff;
            double row = 0;
            const double P = l.power();
            for (const Link& k : links) {
                const PatchGeometry g = patch_geometry(scene.polygons[k.receiver.polygon],
                                                       k.receiver.level, k.receiver.index);
                row += double(k.ff) * g.area;
                // The analytic value is the luminaire's irradiance at the node's centre.
                EXPECT_NEAR(k.ff_analytic * P, l.irradiance(g.centre, dvec3(0, 1, 0)),
                            1e-5 * k.ff_analytic * P);
            }
            std::printf("%-9s %-10s row sum %.6f, exact %.6f (%+.3f %%), %zu links\n", ff,
                        l.kind.c_str(), row, want, 100 * (row / want - 1), links.size());
            EXPECT_NEAR(row, want, 0.01 * want) << ff << " " << l.kind;
        }
    }
}

// Energy balance: in a closed grey room lit by an IES downlight and an isotropic source, every
// shot keeps emitted = absorbed + escaped + unshot (1e-6), the emitted power is the
// luminaires' lumens / 683, and the error bound counts the luminaires until they shoot.
TEST(Luminaire, EnergyBalance) {
    ASSERT_TRUE(ensure_context());
    Luminaire down = ies("cosine.ies", {1.2, 2.9, 2.0});
    Luminaire bulb = candela(200, {3.0, 1.5, 1.0});
    const Scene scene = validation::make_cie_room(0.5, {down, bulb});
    const double watts = (down.lumens() + bulb.lumens()) / kLumensPerWatt;
    EXPECT_NEAR(scene.emitted_power().x, watts, 1e-12 * watts);
    Solver s(scene, room_options());
    EXPECT_NEAR(s.error_bound(), 1 / (1 - 0.5), 1e-12) << "nothing shot: all unshot";
    int luminaire_shots = 0;
    while (s.step()) {
        const ShotRecord& r = s.last_shot();
        if (r.luminaire >= 0) {
            ++luminaire_shots;
            EXPECT_LE(r.shot, 2) << "the luminaires hold the most power: they shoot first";
            EXPECT_EQ(s.luminaire_unshot()[std::size_t(r.luminaire)], dvec3(0.0));
        }
        const dvec3 balance = s.absorbed_power() + s.escaped_power() + s.unshot_power();
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(balance[c], s.emitted_power()[c], 1e-6 * s.emitted_power()[c])
                << "shot " << r.shot;
    }
    EXPECT_EQ(luminaire_shots, 2);
    EXPECT_TRUE(s.converged());
    // Closed room: what escapes is only the form factors' shortfall (rows under 1).
    EXPECT_LT(s.escaped_power().x, 0.02 * watts);
    std::printf("closed room: %ld shots, escaped %.3f %% of %.4f W\n", s.shots(),
                100 * s.escaped_power().x / watts, watts);
}

// A point source at the centre of the CIE 171 room's ceiling (4 x 4 x 3 m, black: direct light
// only; 1000 cd isotropic, 5 cm under the ceiling), in the manner of CIE 171's point-source
// cases: E = I cos(theta) / r^2 at points on the floor and a wall, from the stated geometry.
TEST(Luminaire, Cie171RoomPointSource) {
    ASSERT_TRUE(ensure_context());
    const dvec3 at(2, 2.95, 2);
    const Scene scene = validation::make_cie_room(0.0, {candela(1000, at)});
    Solver s(scene, gpu_options());
    while (s.step()) {}
    const Hierarchy& h = s.solution();
    const FinalGather gather(h);
    const struct {
        const char* name;
        dvec3 p, n;
    } points[] = {
        {"floor centre", {2, 0, 2}, {0, 1, 0}},    {"floor (1,1)", {1, 0, 1}, {0, 1, 0}},
        {"floor (0.5,3)", {0.5, 0, 3}, {0, 1, 0}}, {"floor corner", {0.1, 0, 0.1}, {0, 1, 0}},
        {"wall y0.5", {0, 0.5, 2}, {1, 0, 0}},     {"wall y1.5", {0, 1.5, 2}, {1, 0, 0}},
        {"wall y2.5", {0, 2.5, 1}, {1, 0, 0}},     {"wall y2.9", {0, 2.9, 2}, {1, 0, 0}},
    };
    for (const auto& pt : points) {
        const dvec3 d = pt.p - at;
        const double r2 = glm::dot(d, d);
        const double lux = 1000 * glm::dot(pt.n, -d) / std::sqrt(r2) / r2;
        const auto sp = find_surface(scene, pt.p, pt.n, 1e-6);
        ASSERT_TRUE(sp) << pt.name;
        const double ours = kLumensPerWatt * gather.at({pt.p, pt.n, sp->polygon}, 0).E().y;
        const double leaf = kLumensPerWatt * irradiance_at(h, *sp).y;
        std::printf("CIE room point source  %-14s ref %9.3f lx  gather %9.3f (%+.1e)  leaves "
                    "%9.3f (%+.2f %%)\n",
                    pt.name, lux, ours, ours / lux - 1, leaf, 100 * (leaf / lux - 1));
        EXPECT_NEAR(ours, lux, 0.01 * lux) << pt.name;
    }
}

// A point source casts hard shadows: under a black plate the floor gets nothing (gather and
// leaves), beside it the exact value.
TEST(Luminaire, HardShadow) {
    ASSERT_TRUE(ensure_context());
    Scene scene = black_plane(2.0, 2, {candela(1000, {0, 2, 0})});
    // A plate facing up at 1 m over [-0.5, 0.5]^2 (its back occludes too).
    add_polygon(scene, {{-0.5, 1, 0.5}, {0.5, 1, 0.5}, {0.5, 1, -0.5}, {-0.5, 1, -0.5}}, 0, 0);
    Solver s(scene, gpu_options());
    while (s.step()) {}
    const Hierarchy& h = s.solution();
    const FinalGather gather(h);
    // The shadow is [-1, 1]^2 on the floor (central projection from 2 m of a plate at 1 m).
    for (const dvec3& p : {dvec3(0, 0, 0), dvec3(0.7, 0, -0.6), dvec3(-0.9, 0, 0.9)}) {
        const auto sp = find_surface(scene, p, dvec3(0, 1, 0), 1e-6);
        ASSERT_TRUE(sp);
        EXPECT_EQ(gather.at({p, {0, 1, 0}, sp->polygon}, 0).E().y, 0.0);
        if (std::abs(p.x) < 0.7) {
            EXPECT_EQ(irradiance_at(h, *sp).y, 0.0) << p.x;
        }
    }
    const dvec3 lit(1.5, 0, 0.2);
    const auto sp = find_surface(scene, lit, dvec3(0, 1, 0), 1e-6);
    const double r2 = glm::dot(lit - dvec3(0, 2, 0), lit - dvec3(0, 2, 0));
    EXPECT_NEAR(kLumensPerWatt * gather.at({lit, {0, 1, 0}, sp->polygon}, 0).E().y,
                1000 * 2 / std::sqrt(r2) / r2, 1e-9);
}

// `hemirad reference` stays a valid cross-check with luminaires: the path tracer's next-event
// estimation of point lights against the final gather, in the grey CIE room with a downlight
// (direct exact in both; the indirect part from the radiosity solution): within 3 % + 4
// standard errors per point.
TEST(Luminaire, ReferenceAgreesWithTheGather) {
    ASSERT_TRUE(ensure_context());
    const Scene scene = validation::make_cie_room(0.5, {ies("bilateral_0_180.ies", {2, 2.9, 2})});
    Solver s(scene, room_options());
    while (s.step()) {}
    const Hierarchy& h = s.solution();
    const FinalGather gather(h);
    const std::vector<Probe> probes = {
        {{2, 0, 2}, {0, 1, 0}},  {{0.5, 0, 1}, {0, 1, 0}}, {{0, 1, 2}, {1, 0, 0}},
        {{4, 2, 1}, {-1, 0, 0}}, {{1, 3, 1}, {0, -1, 0}},  {{3, 1.5, 0}, {0, 0, 1}},
    };
    ReferenceOptions ro;
    ro.samples = 2048;
    const std::vector<ReferenceValue> ref = reference_irradiance(scene, probes, ro);
    for (std::size_t i = 0; i < probes.size(); ++i) {
        const auto sp = find_surface(scene, probes[i].position, probes[i].normal, 1e-6);
        ASSERT_TRUE(sp);
        const double ours = gather.at({probes[i].position, probes[i].normal, sp->polygon}, i).E().y;
        const double want = ref[i].E.y, sem = ref[i].sem.y;
        std::printf("reference %zu: %.5f +- %.5f, gather %.5f (%+.2f %%)\n", i, want, sem, ours,
                    100 * (ours / want - 1));
        EXPECT_NEAR(ours, want, 0.03 * want + 4 * sem) << "probe " << i;
    }
}

// A glTF point light (KHR_lights_punctual) of I = 400 cd at h = 1.6 m over a black 4 x 4 m
// plane, its node under a translated parent: one shot, the luminaire's, and the final gather's
// irradiance at the foot point is I / h^2 lux. The gather adds a luminaire's direct light in
// closed form (one shadow ray) and the black plane reflects nothing, so the only error is
// rounding: 1e-9. The solver's own leaf there (interpolated) within 1 %.
TEST(Luminaire, GltfPointLightOverAPlane) {
    ASSERT_TRUE(ensure_context());
    const double I = 400, h = 1.6;
    const double rig[3] = {0.5, 0.25, -1};
    const std::string file = test::write_gltf_lights(
        std::filesystem::path(testing::TempDir()) / "gltf_point_light", "point", 2, rig,
        {{"{\"type\": \"point\", \"intensity\": " + num(I) + "}",
          "\"name\": \"bulb\", \"translation\": [-0.5, " + num(h - 0.25) + ", 1]"}});
    const Scene scene = load_gltf(file);
    ASSERT_EQ(scene.luminaires.size(), 1u);
    EXPECT_LT(glm::length(scene.luminaires[0].position - dvec3(0, h, 0)), 1e-12);
    Solver s(scene, gpu_options());
    while (s.step()) {}
    ASSERT_TRUE(s.converged());
    EXPECT_EQ(s.shots(), 1);
    const Hierarchy& hier = s.solution();
    const FinalGather gather(hier);
    const GridResult g = evaluate_grid(hier, {"floor", 9, 9}, &gather);
    ASSERT_EQ(g.evaluated, 81);
    const GridPoint& foot = g.points[40]; // the centre of the 9 x 9 grid
    EXPECT_LT(glm::length(foot.position - dvec3(0, 0, 0)), 1e-9);
    EXPECT_NEAR(kLumensPerWatt * foot.E.y, I / (h * h), 1e-9 * I / (h * h));
    const double leaf =
        kLumensPerWatt * irradiance_at(hier, *find_surface(scene, foot.position, dvec3(0, 1, 0))).y;
    EXPECT_NEAR(leaf, I / (h * h), 0.01 * I / (h * h));
    std::printf("glTF point light: foot point %.6f lx (gather), %.6f lx (leaf), I/h^2 = %.6f\n",
                kLumensPerWatt * foot.E.y, leaf, I / (h * h));
}

// A point's light goes to each group of surfaces as the exact direct light does. The
// courtyard (three point sources over columns, balustrades and galleries) after its three
// luminaire shots: each group's flux in the leaves, against the gather's direct light (exact
// I cos / r^2 with a shadow ray per luminaire, independent of the linking) averaged over 16
// points a leaf, on every fifth polygon. Hybrid's analytic values alone gave the balustrades
// 12.9 % too little and the gallery floors (mostly in shadow) 24.5 % too much; with each
// polygon's links matched to its pixels the worst group is within 7 % (the slab edges, 30 cm
// strips seen nearly edge-on, -6.9 % as in `hemicube`), the others within 4.4 %.
TEST(Luminaire, EachGroupTakesItsDirectFlux) {
    ASSERT_TRUE(ensure_context());
    const Scene scene = make_builtin("courtyard");
    SolverOptions o = gpu_options();
    o.max_shots = 3;
    Solver s(scene, o);
    while (s.step()) {}
    ASSERT_EQ(s.shots(), 3);
    const Hierarchy& h = s.solution();
    const FinalGather gather(h);
    std::map<std::string, std::array<double, 2>> flux; // delivered, exact
    std::uint64_t k = 0;
    for (std::uint32_t p = 0; p < scene.polygons.size(); p += 5) {
        const Polygon& poly = scene.polygons[p];
        const int d = h.depth(p);
        for (std::uint32_t i = 0; i < (1u << (2 * d)); ++i) {
            const PatchAddress a{p, std::uint32_t(d), i};
            const double area = patch_geometry(poly, d, i).area;
            std::vector<std::uint32_t> parts{i};
            for (int l = 0; l < 2; ++l) {
                std::vector<std::uint32_t> next;
                for (std::uint32_t c : parts)
                    for (std::uint32_t q : patch_children(poly.is_triangle(), d + l, c))
                        next.push_back(q);
                parts = next;
            }
            double exact = 0;
            for (std::uint32_t c : parts) {
                GatherPoint q;
                q.position = patch_centre(poly, d + 2, c);
                q.normal = poly.normal;
                q.polygon = p;
                exact += gather.direct_at(q, k++).y;
            }
            std::array<double, 2>& f = flux[scene.groups[poly.group]];
            f[0] += h.irradiance_shot(a).y * area;
            f[1] += exact / double(parts.size()) * area;
        }
    }
    ASSERT_GE(flux.size(), 7u);
    for (const auto& [group, f] : flux) {
        ASSERT_GT(f[1], 0) << group;
        std::printf("%-18s delivered / exact %.4f\n", group.c_str(), f[0] / f[1]);
        EXPECT_NEAR(f[0] / f[1], 1.0, 0.08) << group;
    }
}
