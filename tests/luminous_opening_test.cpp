// A luminaire's luminous opening (photometry.h LuminousOpening): read from an IES file's
// width and length, and, near the luminaire, its light taken as from an area source. A 0.6 m
// square Lambertian opening (I = I0 cos gamma, absolute photometry) facing down has luminance
// L = I0 / A; under it a point facing up takes E = L pi F / 683 W m^-2, F the exact form factor
// to the square (Lambert's contour integral). The final gather must give that within 1 % down
// to half the opening's size away (its points no farther apart than an eighth of the distance:
// measured 0.45 % at most), and the path tracer, with its own random points over the opening,
// within 4 of its standard errors. A point source would read 130 % high 0.3 m below the centre.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "hemirad/form_factors.h"
#include "hemirad/gather.h"
#include "hemirad/photometry.h"
#include "hemirad/reference.h"

using namespace hemirad;

namespace {

constexpr double kI0 = 1000, kSide = 0.6;

// An IES file (LM-63-2002, absolute photometry, metres) of I0 cos gamma, gamma every degree,
// with a kSide square opening.
std::string lambertian_ies() {
    std::ostringstream t;
    t << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 91 1 1 2 " << kSide << " " << kSide << " 0\n"
      << "1 1 10\n";
    for (int g = 0; g <= 90; ++g) t << g << (g < 90 ? " " : "\n");
    t << "0\n";
    for (int g = 0; g <= 90; ++g) t << kI0 * std::cos(g * M_PI / 180) << (g < 90 ? " " : "\n");
    return t.str();
}

} // namespace

TEST(LuminousOpening, FromTheIesFile) {
    const IesFile f = parse_ies(lambertian_ies(), "lambertian.ies");
    EXPECT_EQ(f.width, kSide);
    EXPECT_EQ(f.length, kSide);
    // A round opening: a negative width is its diameter; feet are converted.
    LuminousOpening o;
    o.length = o.width = 0.5;
    o.round = true;
    const auto pts = o.points({1, 0, 0}, {0, 0, 1}, 8);
    EXPECT_LT(pts.size(), 64u); // the corners' cells are left out
    for (const dvec3& p : pts) EXPECT_LE(glm::length(p), 0.25);
}

TEST(LuminousOpening, NearPointsSeeAnAreaSource) {
    const IesFile ies = parse_ies(lambertian_ies(), "lambertian.ies");
    Scene scene;
    scene.source = "builtin:opening-test";
    scene.materials.push_back(Material{"black", dvec3(0.0), dvec3(0.0)});
    scene.groups.push_back("floor");
    ASSERT_EQ(add_polygon(scene, {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}}, 0, 0).added, 1);
    const double h = 2.5;
    Luminaire l;
    l.name = "panel";
    l.kind = "ies";
    l.distribution = ies.distribution;
    l.opening.length = l.opening.width = kSide;
    l.position = {0, h, 0};
    l.orient();
    scene.luminaires.push_back(l);
    finish_scene(scene, scene.source);

    const double L = kI0 / (kSide * kSide);
    const double s = kSide / 2;
    std::vector<Probe> probes;
    std::vector<double> exact;
    for (const double d : {0.3, 0.6, 1.2, 2.4}) { // below the opening's centre, then off it
        for (const double x : {0.0, 0.4}) {
            const dvec3 p(x, h - d, 0);
            const std::vector<dvec3> square = {{-s, h, -s}, {s, h, -s}, {s, h, s}, {-s, h, s}};
            probes.push_back({p, {0, 1, 0}});
            exact.push_back(L * M_PI * point_to_polygon_ff(p, {0, 1, 0}, square.data(), 4) /
                            kLumensPerWatt);
        }
    }
    Hierarchy hier(scene, discretise(scene, HierarchyOptions{}));
    const FinalGather gather(hier);
    ReferenceOptions ro;
    ro.samples = 65536;
    const auto ref = reference_irradiance(scene, probes, ro);
    for (std::size_t k = 0; k < probes.size(); ++k) {
        const double ours =
            gather.direct_at({probes[k].position, probes[k].normal, GatherPoint::kNoSurface}, k).x;
        const double point = l.irradiance(probes[k].position, probes[k].normal);
        std::printf("%.1f m below, %.1f m aside: exact %.5g, gather %+.2f %%, reference %+.2f %% "
                    "(s.e. %.2f %%), point source %+.1f %%\n",
                    h - probes[k].position.y, probes[k].position.x, exact[k],
                    100 * (ours / exact[k] - 1), 100 * (ref[k].E.x / exact[k] - 1),
                    100 * ref[k].sem.x / exact[k], 100 * (point / exact[k] - 1));
        EXPECT_NEAR(ours, exact[k], 0.01 * exact[k]) << k;
        EXPECT_NEAR(ref[k].E.x, exact[k], 4 * ref[k].sem.x + 1e-3 * exact[k]) << k;
    }
}
