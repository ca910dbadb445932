// CIE 171:2006 analytic test cases that apply to a diffuse radiosity engine (5.3 area source,
// 5.6 light reflected from a lit floor, 5.7 the same with an obstruction), solved with the
// GPU hybrid provider (paper 002) and checked point by point against references computed
// here from the stated geometry:
//  - closed forms: Howell B-3 (element parallel to a rectangle, normal through a corner) and
//    B-4 (element perpendicular to a rectangle), combined by form-factor algebra for a point
//    in general position (docs/references.md §1 (c1));
//  - cross-checked against the double-precision point-to-polygon kernel point_to_polygon_ff
//    (Lambert/Nusselt contour integral, itself tested against Howell in ff_kernel_test).
// The CIE publication tabulates values for its own geometry (not reproduced here, and its
// 5.7 table is wrong per Ian Ashdown's errata): the references below are ours, for the room
// of validation_scenes.h. Tolerance: 1 % per point (the vendors' criterion is 5 %).
//
// Needs a GL context (Mesa llvmpipe here): failing to get one FAILS the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "hemirad/export.h"
#include "hemirad/form_factors.h"
#include "hemirad/gather.h"
#include "hemirad/gl/context.h"
#include "hemirad/readout.h"
#include "hemirad/render.h"
#include "hemirad/solver.h"
#include "hemirad/validation_scenes.h"
#include "render/discontinuity_field.h"

using namespace hemirad;
using namespace hemirad::validation;

namespace {

constexpr double kTolerance = 0.01; // relative, per point

// One GL context for the whole binary: every provider renders in it (shader programs are
// compiled per provider; contexts are not recreated per test).
bool ensure_context() {
    static std::unique_ptr<gl::Context> context;
    if (!context) context = gl::Context::create();
    return context != nullptr;
}

// --- Howell's closed forms -----------------------------------------------------------------

// B-3: element parallel to an a x b rectangle at distance c, its normal through one corner.
// F = 1/(2 pi) [ X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2)) ].
double howell_b3(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * std::numbers::pi);
}

// B-4: element at the origin with normal +n; rectangle in the perpendicular plane at
// distance d, spanning [0, H] along n and [0, L] across:
// F = 1/(2 pi) [ atan(L/d) - d/sqrt(H^2+d^2) atan(L/sqrt(H^2+d^2)) ].
double howell_b4(double H, double d, double L) {
    const double s = std::sqrt(H * H + d * d);
    return (std::atan(L / d) - d / s * std::atan(L / s)) / (2 * std::numbers::pi);
}

// Form-factor algebra. Both corner forms are odd in each in-plane offset when extended by
// sign, so a rectangle [u0,u1] x [v0,v1] (offsets from the foot of the normal) is
// G(u1,v1) - G(u0,v1) - G(u1,v0) + G(u0,v0).
double sgn(double x) {
    return x < 0 ? -1.0 : 1.0;
}

// Element facing a parallel rectangle [u0,u1] x [v0,v1] at distance c.
double parallel_rect(double u0, double u1, double v0, double v1, double c) {
    const auto G = [c](double u, double v) {
        if (u == 0 || v == 0) return 0.0;
        return sgn(u) * sgn(v) * howell_b3(std::abs(u), std::abs(v), c);
    };
    return G(u1, v1) - G(u0, v1) - G(u1, v0) + G(u0, v0);
}

// Element facing a perpendicular rectangle at distance d, spanning [h0,h1] (h >= 0) along the
// element's normal and [l0,l1] across (offsets from the element).
double perpendicular_rect(double h0, double h1, double l0, double l1, double d) {
    const auto G = [d](double h, double l) {
        if (h <= 0 || l == 0) return 0.0;
        return sgn(l) * howell_b4(h, d, std::abs(l));
    };
    return G(h1, l1) - G(h1, l0) - G(h0, l1) + G(h0, l0);
}

// The kernel, for cross-checking: F(dA at p, normal n -> horizontal rectangle).
double kernel_rect(const dvec3& p, const dvec3& n, const HorizontalRect& r) {
    const dvec3 c[4] = {{r.x0, r.y, r.z0}, {r.x1, r.y, r.z0}, {r.x1, r.y, r.z1}, {r.x0, r.y, r.z1}};
    return point_to_polygon_ff(p, n, c, 4);
}

// F from a probe to a horizontal rectangle, by the closed forms. Probes lie on the floor or
// ceiling (normal +-y: B-3) or on the wall x = 0 (normal +x: B-4).
double closed_form_rect(const dvec3& p, const dvec3& n, const HorizontalRect& r) {
    if (std::abs(n.y) > 0.5)
        return parallel_rect(r.x0 - p.x, r.x1 - p.x, r.z0 - p.z, r.z1 - p.z, std::abs(r.y - p.y));
    EXPECT_EQ(p.x, 0.0) << "wall probes lie on x = 0";
    return perpendicular_rect(r.x0, r.x1, r.z0 - p.z, r.z1 - p.z, std::abs(r.y - p.y));
}

// Reference form factor: closed form, asserted equal to the kernel.
double reference_ff(const dvec3& p, const dvec3& n, const HorizontalRect& r) {
    const double closed = closed_form_rect(p, n, r), kernel = kernel_rect(p, n, r);
    EXPECT_NEAR(closed, kernel, 1e-12)
        << "Howell algebra vs kernel at " << p.x << "," << p.y << "," << p.z;
    return closed;
}

// --- solving and reading ---------------------------------------------------------------

struct Point {
    const char* name;
    dvec3 p, n;
};

// Default options: the product's answer, as `hemirad solve --probes` gives it (final gather
// at each point, gather.h). Only the GL context is shared between the tests.
SolverOptions gpu_options() {
    SolverOptions o; // ff = "hybrid", the default
    o.provider.gpu.use_current_context = true;
    o.tolerance = 1e-3;
    return o;
}

double probe(const Scene& scene, const Hierarchy& h, const Point& pt) {
    const auto sp = find_surface(scene, pt.p, pt.n, 1e-6);
    EXPECT_TRUE(sp.has_value()) << pt.name << ": no surface";
    if (!sp) return 0.0;
    const FinalGather gather(h);
    return gather.at({pt.p, pt.n, sp->polygon}, 0).E().x;
}

void report(const char* test, const Point& pt, double ref, double ours) {
    const double err = (ours - ref) / ref;
    std::printf("%-5s %-16s (%4.2f,%4.2f,%4.2f)  ref %10.4f  ours %10.4f  err %+7.3f%%\n", test,
                pt.name, pt.p.x, pt.p.y, pt.p.z, ref, ours, 100 * err);
    EXPECT_LT(std::abs(err), kTolerance)
        << test << " " << pt.name << ": ref " << ref << ", ours " << ours;
}

const dvec3 kUp(0, 1, 0), kDown(0, -1, 0), kIntoRoom(1, 0, 0);

} // namespace

// 5.3: 1 m x 1 m source of exitance M centred in the ceiling; black room. E(p) = M F(p->S).
TEST(Cie171, AreaSource_5_3) {
    ASSERT_TRUE(ensure_context());
    constexpr double M = 1000.0;
    const Scene scene = make_cie53_area_source(M);
    Solver s(scene, gpu_options());
    while (s.step()) {}
    ASSERT_TRUE(s.converged());
    const Hierarchy& h = s.solution();
    const Point points[] = {
        {"floor centre", {2, 0, 2}, kUp},         {"floor (1,1)", {1, 0, 1}, kUp},
        {"floor (0.5,2)", {0.5, 0, 2}, kUp},      {"floor (3.5,3.5)", {3.5, 0, 3.5}, kUp},
        {"floor (2,0.25)", {2, 0, 0.25}, kUp},    {"wall y0.5", {0, 0.5, 2}, kIntoRoom},
        {"wall y1.5", {0, 1.5, 2}, kIntoRoom},    {"wall y2.5", {0, 2.5, 2}, kIntoRoom},
        {"wall (1.5,1)", {0, 1.5, 1}, kIntoRoom}, {"wall (2.75,3.5)", {0, 2.75, 3.5}, kIntoRoom},
    };
    for (const Point& pt : points)
        report("5.3", pt, M * reference_ff(pt.p, pt.n, kCie53Source), probe(scene, h, pt));
}

// 5.6: the floor (rho 0.3, E 500 lx) reflects exitance M = rho E, modelled as emission; all
// else black. E(p) = M F(p -> floor) on the wall x = 0 and the ceiling.
TEST(Cie171, LitFloor_5_6) {
    ASSERT_TRUE(ensure_context());
    const double M = kCie56FloorReflectance * kCie56FloorIlluminance;
    const Scene scene = make_cie56_lit_floor(M, false);
    Solver s(scene, gpu_options());
    while (s.step()) {}
    ASSERT_TRUE(s.converged());
    const Hierarchy& h = s.solution();
    const HorizontalRect floor{0, CieRoom::width, 0, CieRoom::depth, 0};
    const Point points[] = {
        {"ceiling centre", {2, 3, 2}, kDown},      {"ceiling (1,1)", {1, 3, 1}, kDown},
        {"ceiling (0.25,2)", {0.25, 3, 2}, kDown}, {"ceiling (3.5,0.5)", {3.5, 3, 0.5}, kDown},
        {"wall y0.5", {0, 0.5, 2}, kIntoRoom},     {"wall y1.5", {0, 1.5, 2}, kIntoRoom},
        {"wall y2.5", {0, 2.5, 2}, kIntoRoom},     {"wall (1.5,0.5)", {0, 1.5, 0.5}, kIntoRoom},
    };
    for (const Point& pt : points)
        report("5.6", pt, M * reference_ff(pt.p, pt.n, floor), probe(scene, h, pt));
}

// 5.7: 5.6 with a black horizontal plate kCie57Plate (1 m x 1 m at height 1 m, centred)
// between the floor and the measurement points. From a probe p above the plate (p_y > 1),
// the plate's shadow on the floor is the central projection of the plate from p, a
// rectangle scaled by k = p_y / (p_y - h) about p's foot. The visible floor is the floor
// minus that shadow (clipped to the floor), so by form-factor algebra
//   E(p) = M [ F(p -> floor) - F(p -> shadow ∩ floor) ],
// exact, each term by Howell's closed forms (checked against the kernel).
TEST(Cie171, LitFloorObstructed_5_7) {
    ASSERT_TRUE(ensure_context());
    const double M = kCie56FloorReflectance * kCie56FloorIlluminance;
    const Scene scene = make_cie56_lit_floor(M, true);
    // Default options: the plate's shadow is resolved by the final gather's area visibility of
    // the emitting floor at each point (before it, the floor's shooters saw the plate from
    // their centres and needed --shooter-max-size 0.125 for 1 %).
    const SolverOptions o = gpu_options();
    Solver s(scene, o);
    while (s.step()) {}
    ASSERT_TRUE(s.converged());
    const Hierarchy& h = s.solution();
    const HorizontalRect floor{0, CieRoom::width, 0, CieRoom::depth, 0};
    const HorizontalRect& P = kCie57Plate;
    const Point points[] = {
        {"ceiling centre", {2, 3, 2}, kDown},     {"ceiling (1,1)", {1, 3, 1}, kDown},
        {"ceiling (1,2)", {1, 3, 2}, kDown},      {"ceiling (3.5,0.5)", {3.5, 3, 0.5}, kDown},
        {"wall y2", {0, 2, 2}, kIntoRoom},        {"wall y2.5", {0, 2.5, 2}, kIntoRoom},
        {"wall (2.5,1)", {0, 2.5, 1}, kIntoRoom}, {"wall y1.5", {0, 1.5, 2}, kIntoRoom},
    };
    for (const Point& pt : points) {
        const double k = pt.p.y / (pt.p.y - P.y);
        HorizontalRect shadow{pt.p.x + k * (P.x0 - pt.p.x), pt.p.x + k * (P.x1 - pt.p.x),
                              pt.p.z + k * (P.z0 - pt.p.z), pt.p.z + k * (P.z1 - pt.p.z), 0};
        shadow.x0 = std::max(shadow.x0, 0.0), shadow.x1 = std::min(shadow.x1, CieRoom::width);
        shadow.z0 = std::max(shadow.z0, 0.0), shadow.z1 = std::min(shadow.z1, CieRoom::depth);
        double F = reference_ff(pt.p, pt.n, floor);
        if (shadow.x0 < shadow.x1 && shadow.z0 < shadow.z1) F -= reference_ff(pt.p, pt.n, shadow);
        report("5.7", pt, M * F, probe(scene, h, pt));
    }
}

// A shadow edge inside leaves, in a rendered image (render.h, resolve_discontinuities): a
// 0.2 m square source 1 m over a black floor, and a plate 0.1 m over the floor, so that its
// shadow's penumbra (0.02 m) is narrower than a leaf (0.03 m). The floor's irradiance image
// is compared pixel by pixel, in a window across the shadow's edge, with the exact value:
// the source less the plate's central projection from the point onto the source's plane,
// E = M [F(p -> source) - F(p -> source ∩ projection)], by Howell's closed forms. Errors are
// relative to the unshadowed value at the pixel. Measured: leaves interpolated, rms 0.126 and
// max 0.32 (a soft block two leaves wide); with the pass, rms 0.024 and max 0.087 (what is
// left: the solver's own leaf values next to the edge, and steps of one fine emitter cell).
// The floor's lightmap likewise: one texel per leaf, rms 0.106; 4 x 4 texels per flagged
// leaf with the detail, rms 0.038.
TEST(Discontinuities, ShadowEdgeWithinALeaf) {
    ASSERT_TRUE(ensure_context());
    constexpr double M = 1000.0, kPlate = 0.1;
    const HorizontalRect source{0.9, 1.1, 0.9, 1.1, 1.0}, plate{0.7, 1.0, 0.7, 1.3, kPlate};
    Scene scene;
    // The floor reflects (rho 0.5, for the lightmap's radiosity), but nothing else does, so
    // its irradiance is the direct light alone.
    constexpr double kRho = 0.5;
    scene.materials = {Material{"black", dvec3(0.0), dvec3(0.0)},
                       Material{"light", dvec3(0.0), dvec3(M / std::numbers::pi)},
                       Material{"grey", dvec3(kRho), dvec3(0.0)}};
    scene.groups = {"floor", "light", "plate"};
    const auto rect = [&](const HorizontalRect& r, bool up, std::uint32_t m, std::uint32_t g) {
        std::vector<dvec3> c = {
            {r.x0, r.y, r.z0}, {r.x0, r.y, r.z1}, {r.x1, r.y, r.z1}, {r.x1, r.y, r.z0}};
        if (!up) std::reverse(c.begin(), c.end());
        add_polygon(scene, c, m, g);
    };
    rect({0, 2, 0, 2, 0}, true, 2, 0);
    rect(source, false, 1, 1);
    rect(plate, true, 0, 2);
    finish_scene(scene, "test:shadow-edge");
    Solver s(scene, gpu_options());
    while (s.step()) {}
    const Hierarchy& h = s.solution();

    Camera cam;
    cam.eye = {1.3, 0.8, 1.0};
    cam.target = {1.0, 0.0, 1.0};
    cam.up = {0, 0, 1};
    cam.fov_y_deg = 30;
    RenderOptions o;
    o.width = o.height = 128;
    o.quantity = RenderOptions::Quantity::Irradiance;
    SolutionRenderer renderer(scene);
    const ImageRGB plain = renderer.render(h, cam, o);
    ImageRGB sharp = plain;
    const DiscontinuityStats d = resolve_discontinuities(sharp, h, cam, o);
    EXPECT_GT(d.pixels, 0u);

    // The exact irradiance on the floor at p.
    const auto exact = [&](const dvec3& p, double& open) {
        const double k = 1.0 / kPlate; // projection from p through the plate to y = 1
        HorizontalRect shadow{p.x + k * (plate.x0 - p.x), p.x + k * (plate.x1 - p.x),
                              p.z + k * (plate.z0 - p.z), p.z + k * (plate.z1 - p.z), 1.0};
        shadow.x0 = std::max(shadow.x0, source.x0), shadow.x1 = std::min(shadow.x1, source.x1);
        shadow.z0 = std::max(shadow.z0, source.z0), shadow.z1 = std::min(shadow.z1, source.z1);
        open = M * closed_form_rect(p, kUp, source);
        double E = open;
        if (shadow.x0 < shadow.x1 && shadow.z0 < shadow.z1)
            E -= M * closed_form_rect(p, kUp, shadow);
        return E;
    };

    // The floor's lightmap (export.h): with detail, a chart of 4 x 4 texels per leaf; each
    // texel against the exact radiosity rho E at its centre, in the same window; without,
    // the leaf's one texel at the same points.
    const DiscontinuityField field(h);
    const Lightmap fine = build_lightmap(h, 0, "floor", &field);
    const Lightmap coarse = build_lightmap(h, 0, "floor");
    ASSERT_EQ(fine.charts.size(), 1u);
    const LightmapChart &fc = fine.charts[0], &cc = coarse.charts[0];
    ASSERT_EQ(fc.n, 4 * cc.n);
    double lm_fine = 0, lm_coarse = 0;
    int lm_n = 0;
    for (int j = 0; j < fc.n; ++j)
        for (int i = 0; i < fc.n; ++i) {
            const double u = (i + 0.5) / fc.n, v = (j + 0.5) / fc.n;
            const dvec3 p = polygon_point(scene.polygons[0], u, v);
            if (p.x < 0.9 || p.x > 1.1 || p.z < 0.8 || p.z > 1.2) continue;
            if (p.x >= plate.x0 && p.x <= plate.x1 && p.z >= plate.z0 && p.z <= plate.z1 &&
                p.x < 0.98)
                continue; // deep under the plate: umbra, both exact
            double open;
            const double B = kRho * exact(p, open);
            const double ef = (fine.atlas.at(fc.x0 + i, fc.y0 + j)[0] - B) / (kRho * open);
            const double ec =
                (coarse.atlas.at(cc.x0 + i / 4, cc.y0 + j / 4)[0] - B) / (kRho * open);
            lm_fine += ef * ef, lm_coarse += ec * ec, ++lm_n;
        }
    ASSERT_GT(lm_n, 50);
    std::printf("shadow edge, lightmap, %d texels: leaf texels rms %.4f; 4 x 4 with detail rms "
                "%.4f\n",
                lm_n, std::sqrt(lm_coarse / lm_n), std::sqrt(lm_fine / lm_n));
    EXPECT_LT(std::sqrt(lm_fine / lm_n), 0.5 * std::sqrt(lm_coarse / lm_n));

    const dvec3 f = glm::normalize(cam.target - cam.eye);
    const dvec3 r = glm::normalize(glm::cross(f, cam.up)), u = glm::cross(r, f);
    const double ty = std::tan(0.5 * glm::radians(cam.fov_y_deg));
    double sum_plain = 0, sum_sharp = 0, max_plain = 0, max_sharp = 0;
    int n = 0;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            const dvec3 dir = f + (2.0 * (x + 0.5) / o.width - 1.0) * ty * r +
                              (1.0 - 2.0 * (y + 0.5) / o.height) * ty * u;
            const dvec3 p = cam.eye - cam.eye.y / dir.y * dir; // on the floor, y = 0
            const dvec3 at_plate = cam.eye + (cam.eye.y - kPlate) / -dir.y * dir;
            if (at_plate.x >= plate.x0 && at_plate.x <= plate.x1 && at_plate.z >= plate.z0 &&
                at_plate.z <= plate.z1)
                continue; // the camera sees the plate here
            if (p.x < 0.9 || p.x > 1.1 || p.z < 0.8 || p.z > 1.2) continue;
            double open;
            const double E = exact(p, open);
            const double e_plain = std::abs(plain.at(x, y)[0] - E) / open;
            const double e_sharp = std::abs(sharp.at(x, y)[0] - E) / open;
            sum_plain += e_plain * e_plain, sum_sharp += e_sharp * e_sharp;
            max_plain = std::max(max_plain, e_plain), max_sharp = std::max(max_sharp, e_sharp);
            ++n;
        }
    ASSERT_GT(n, 500);
    const double rms_plain = std::sqrt(sum_plain / n), rms_sharp = std::sqrt(sum_sharp / n);
    std::printf("shadow edge, %d pixels: leaves rms %.4f max %.3f; at the point rms %.4f max "
                "%.3f (%zu leaves flagged)\n",
                n, rms_plain, max_plain, rms_sharp, max_sharp, d.leaves);
    EXPECT_LT(rms_sharp, 0.03);
    EXPECT_LT(max_sharp, 0.15);
    EXPECT_LT(rms_sharp, 0.25 * rms_plain);
}
