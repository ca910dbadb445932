// The sky (Scene::sky, sky.h) in the solver and the read-outs: an unobstructed floor takes E_h
// under every model (leaves and gathered points); unobstructed vertical plates take the closed
// forms (uniform E_h/2, overcast 0.396 E_h, plus the ground's rho_g E_h/2); and a side-lit room
// under the overcast sky agrees with the path tracer (reference.h), whose sky is its own code
// (it shares only the scene and the BVH with the solver).
//
// Needs a GL context (Mesa llvmpipe here): failing to get one FAILS the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "hemirad/gather.h"
#include "hemirad/readout.h"
#include "hemirad/reference.h"
#include "hemirad/solver.h"
#include "shared_gl_context.h"

using namespace hemirad;

namespace {

constexpr double kPi = std::numbers::pi;

class SkyLight : public SharedGlContextTest {};

SolverOptions gpu_options() {
    SolverOptions o; // the defaults: ff = "hybrid", tolerance, ...
    o.provider.gpu.use_current_context = true;
    return o;
}

// A quad with corners c whose front faces along `facing` (the order flipped if needed).
void quad(Scene& s, std::vector<dvec3> c, const dvec3& facing, std::uint32_t m) {
    if (glm::dot(glm::cross(c[1] - c[0], c[2] - c[0]), facing) < 0) std::swap(c[1], c[3]);
    ASSERT_EQ(add_polygon(s, c, m, 0).added, 1);
}

Scene empty_scene(double rho) {
    Scene s;
    s.source = "builtin:sky-test";
    s.materials.push_back(Material{"m", dvec3(rho), dvec3(0.0)});
    s.groups.push_back("g");
    return s;
}

Sun sun_at(double altitude, double azimuth) {
    Sun sun;
    sun.altitude_deg = altitude;
    sun.azimuth_deg = azimuth;
    sun.direction = SkyFrame().direction(altitude, azimuth);
    sun.illuminance = 0; // the sky alone
    return sun;
}

struct Point {
    const char* name;
    dvec3 p, n;
    bool surface = true; ///< on a polygon (else a free-space work-plane point)
};

std::vector<GatherValue> gather(const Scene& scene, Hierarchy& h, const std::vector<Point>& pts) {
    std::vector<GatherPoint> q;
    for (const Point& pt : pts) {
        const auto sp = pt.surface ? find_surface(scene, pt.p, pt.n, 1e-6) : std::nullopt;
        if (pt.surface) {
            EXPECT_TRUE(sp.has_value()) << pt.name;
        }
        q.push_back({pt.p, pt.n, sp ? sp->polygon : GatherPoint::kNoSurface});
    }
    return FinalGather(h).at(q);
}

dvec3 leaf(const Scene& scene, const Hierarchy& h, const Point& pt) {
    const auto sp = find_surface(scene, pt.p, pt.n, 1e-6);
    EXPECT_TRUE(sp.has_value()) << pt.name;
    return sp ? irradiance_at(h, *sp) : dvec3(-1.0);
}

} // namespace

// A black 4 m floor under each sky (10000 lx): every gathered point takes E_h/683 (0.3 %:
// 1024 stratified jittered rays over a smooth sky, measured within 0.1 %; 0.5 % under a
// circumsolar peak: the clear sky's reads +0.39 % at the centre with the horizon blend, a
// sample of the estimator's noise there, not a bias: sky_test's 16 seeds average to 0.1 %);
// every leaf E_h/683
// within 0.5 % under the overcast and uniform skies, 4 % under the clear and intermediate ones
// (256 rays from jittered points of the leaf; their circumsolar peak, up to 11 x the mean,
// falls in a few strata: measured up to 2.8 % at a corner, whose read-out extrapolates two
// leaves); the emitted power is E_h/683 times the area within 0.5 % (the leaves' errors
// average out).
TEST_F(SkyLight, UnobstructedFloorTakesEh) {
    for (SkyModel m : {SkyModel::CieOvercast, SkyModel::CieClear, SkyModel::CieIntermediate,
                       SkyModel::Uniform}) {
        Scene scene = empty_scene(0.0);
        quad(scene, {{0, 0, 0}, {4, 0, 0}, {4, 0, 4}, {0, 0, 4}}, {0, 1, 0}, 0);
        scene.sky = make_sky(m, 10000, 0, {0, 1, 0}, sun_at(30, 200));
        const double E = 10000 / 683.0;
        const bool peaked = sky_needs_sun(m); // a circumsolar peak: noisier leaves
        Solver s(scene, gpu_options());
        while (s.step()) {}
        EXPECT_NEAR(s.emitted_power().x, E * 16, 5e-3 * E * 16) << sky_model_name(m);
        Hierarchy& h = s.solution();
        const std::vector<Point> pts = {{"centre", {2, 0, 2}, {0, 1, 0}},
                                        {"corner", {0.01, 0, 3.99}, {0, 1, 0}},
                                        {"edge", {4, 0, 1.3}, {0, 1, 0}}};
        const auto g = gather(scene, h, pts);
        for (std::size_t k = 0; k < pts.size(); ++k) {
            EXPECT_NEAR(leaf(scene, h, pts[k]).x, E, (peaked ? 0.04 : 0.005) * E)
                << sky_model_name(m) << " " << pts[k].name;
            EXPECT_NEAR(g[k].direct.x, E, (peaked ? 5e-3 : 3e-3) * E)
                << sky_model_name(m) << " " << pts[k].name;
            EXPECT_EQ(g[k].indirect.x, 0.0) << pts[k].name;
        }
    }
}

// A black 1 m vertical plate facing +x, alone: under the uniform sky with ground reflectance
// 0.3 it takes E_h/2 + 0.3 E_h/2; under the overcast sky (3/14 + 4/(7 pi)) E_h + 0.3 E_h/2
// (sky_test.cpp derives it). Gathered at its centre within 0.5 % (the horizon crosses the
// hemisphere: its cells are split).
TEST_F(SkyLight, VerticalPlateTakesClosedForms) {
    const double overcast = 3.0 / 14.0 + 4.0 / (7.0 * kPi);
    for (const auto& [m, ratio] :
         {std::pair{SkyModel::Uniform, 0.5}, std::pair{SkyModel::CieOvercast, overcast}}) {
        Scene scene = empty_scene(0.0);
        quad(scene, {{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, {1, 0, 0}, 0);
        scene.sky = make_sky(m, 10000, 0.3, {0, 1, 0}, std::nullopt, false); // sharp horizon
        Solver s(scene, gpu_options());
        while (s.step()) {}
        const double E = (ratio + 0.15) * 10000 / 683.0;
        const auto g = gather(scene, s.solution(), {{"centre", {0, 0.5, 0.5}, {1, 0, 0}}});
        EXPECT_NEAR(g[0].E().x, E, 5e-3 * E) << sky_model_name(m);
        EXPECT_NEAR(leaf(scene, s.solution(), {"centre", {0, 0.5, 0.5}, {1, 0, 0}}).x, E, 0.03 * E)
            << sky_model_name(m);
    }
}

// tests/data/sky/window_room.json's room built here: 5 x 3 x 4 m (floor 0.3, walls 0.6,
// ceiling 0.8), a 2 x 1.2 m window opening (sill 0.9 m) in the south wall (z = 4), under the
// CIE overcast sky of 10000 lx, black ground. Work-plane points (0.85 m, free space) along
// the room's depth and surface points: solver (default options) and final gather against the
// path tracer, |ours - ref| <= 5 % ref + 4 sem on every point, and the median |err| <= 2 %
// (the target). Measured: median 1.5 %, max 2.9 %, mostly the reference's own noise
// (131072 paths: sem 0.5-2.4 %); README's 1M-path comparison of 280 points gives median
// 0.4-0.7 %. The sky's direct part is gathered to ~0.3 %; the rest is the gather's indirect
// noise (1024 rays), as in sun_gl_test.
TEST_F(SkyLight, WindowRoomAgreesWithTheReference) {
    Scene scene = empty_scene(0.6);
    scene.materials.push_back(Material{"floor", dvec3(0.3), dvec3(0.0)});
    scene.materials.push_back(Material{"ceiling", dvec3(0.8), dvec3(0.0)});
    const double W = 5, H = 3, D = 4, sill = 0.9, head = 2.1, x0 = 1.5, x1 = 3.5;
    quad(scene, {{0, 0, 0}, {W, 0, 0}, {W, 0, D}, {0, 0, D}}, {0, 1, 0}, 1);  // floor
    quad(scene, {{0, H, 0}, {W, H, 0}, {W, H, D}, {0, H, D}}, {0, -1, 0}, 2); // ceiling
    quad(scene, {{0, 0, 0}, {0, H, 0}, {0, H, D}, {0, 0, D}}, {1, 0, 0}, 0);  // west
    quad(scene, {{W, 0, 0}, {W, H, 0}, {W, H, D}, {W, 0, D}}, {-1, 0, 0}, 0); // east
    quad(scene, {{0, 0, 0}, {W, 0, 0}, {W, H, 0}, {0, H, 0}}, {0, 0, 1}, 0);  // north
    // The south wall around the window.
    quad(scene, {{0, 0, D}, {W, 0, D}, {W, sill, D}, {0, sill, D}}, {0, 0, -1}, 0);
    quad(scene, {{0, head, D}, {W, head, D}, {W, H, D}, {0, H, D}}, {0, 0, -1}, 0);
    quad(scene, {{0, sill, D}, {x0, sill, D}, {x0, head, D}, {0, head, D}}, {0, 0, -1}, 0);
    quad(scene, {{x1, sill, D}, {W, sill, D}, {W, head, D}, {x1, head, D}}, {0, 0, -1}, 0);
    scene.sky = make_sky(SkyModel::CieOvercast, 10000, 0, {0, 1, 0}, std::nullopt);
    finish_scene(scene, scene.source);

    std::vector<Point> all;
    const dvec3 up(0, 1, 0);
    all.push_back({"work plane z 3.5", {2.5, 0.85, 3.5}, up, false});
    all.push_back({"work plane z 2.5", {2.5, 0.85, 2.5}, up, false});
    all.push_back({"work plane z 1.5", {2.5, 0.85, 1.5}, up, false});
    all.push_back({"work plane z 0.5", {2.5, 0.85, 0.5}, up, false});
    all.push_back({"work plane west", {0.7, 0.85, 2.0}, up, false});
    all.push_back({"floor centre", {2.5, 0, 2}, up});
    all.push_back({"ceiling centre", {2.5, H, 2}, {0, -1, 0}});
    all.push_back({"north wall", {2.5, 1.5, 0}, {0, 0, 1}});
    all.push_back({"west wall", {0, 1.5, 3}, {1, 0, 0}});
    all.push_back({"south wall by window", {1.0, 1.5, D}, {0, 0, -1}});
    std::vector<Probe> probes;
    for (const Point& pt : all) probes.push_back({pt.p, pt.n});
    ReferenceOptions ro;
    ro.samples = 131072;
    const auto ref = reference_irradiance(scene, probes, ro);
    Solver s(scene, gpu_options());
    while (s.step()) {}
    std::printf("sky room: %ld shots, %.2f s, error bound %.2g\n", s.shots(), s.seconds(),
                s.error_bound());
    const auto ours = gather(scene, s.solution(), all);
    std::vector<double> errors;
    for (std::size_t k = 0; k < all.size(); ++k) {
        const double E = ref[k].E.x, sem = ref[k].sem.x, mine = ours[k].E().x;
        std::printf("%-22s DF ref %7.4f %% +- %6.4f  ours %7.4f %%  err %+6.2f%%\n", all[k].name,
                    100 * 683 * E / 10000, 100 * 683 * sem / 10000, 100 * 683 * mine / 10000,
                    100 * (mine - E) / E);
        EXPECT_LE(std::abs(mine - E), 0.05 * E + 4 * sem) << all[k].name;
        errors.push_back(std::abs(mine - E) / E);
    }
    std::sort(errors.begin(), errors.end());
    const double median = 0.5 * (errors[errors.size() / 2 - 1] + errors[errors.size() / 2]);
    std::printf("sky room: median |err| %.2f %%, max %.2f %%\n", 100 * median, 100 * errors.back());
    EXPECT_LE(median, 0.02);
}
