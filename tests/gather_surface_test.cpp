// The final gather's shadow rays from a point on a surface (gather.h, FinalGather::lifted). A
// point on a surface lies on it only to rounding, or to the digits of a probe file; when it is
// just behind its plane, a ray towards a light near that plane (an LED bar passing through the
// surface, a luminaire at grazing incidence) used to be blocked by the surface's two-sided twin,
// and the gather read nothing there (the office glb: a PC's face beside a bar read 0.029 W m^-2
// against the reference's 0.559). The rays start lifted off the surface by the gather's offset.
//
// A black two-sided floor (y = 0, its twin facing down); an emitting bar 1 cm beside the point,
// standing through the floor (8 mm deep, 0.8 m long, facing the point, cut at the floor as the
// loader cuts polygons that pass through others: split_intersections); a point luminaire 1 cm
// away, 1 mm above the floor's plane. The point lies 1e-10 m below the plane, on the floor. Its
// direct irradiance must be the bar's upper half's exact form factor times its exitance, plus
// the luminaire's I cos / (683 r^2): to 1e-6 (both are exact, and nothing else is seen).
#include <gtest/gtest.h>

#include "hemirad/form_factors.h"
#include "hemirad/gather.h"
#include "hemirad/photometry.h"

using namespace hemirad;

TEST(GatherSurfacePoint, RaysToLightsNearItsPlaneAreNotBlockedByItsTwin) {
    Scene scene;
    scene.source = "test:bar-through-floor";
    scene.materials = {{"floor", dvec3(0.0), dvec3(0.0)}, {"led", dvec3(0.0), dvec3(1.0)}};
    scene.groups = {"floor", "led"};
    ASSERT_EQ(add_polygon(scene, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, 0, 0).added, 1);
    // The bar's face at x = 0.01 facing -x (corners o, o+u, o+u+v, o+v, normal u x v), cut at
    // y = 0 into its upper and lower halves.
    const double x = 0.01, h = 0.004, l = 0.4;
    const std::vector<dvec3> upper = {{x, 0, -l}, {x, 0, l}, {x, h, l}, {x, h, -l}};
    const std::vector<dvec3> lower = {{x, -h, -l}, {x, -h, l}, {x, 0, l}, {x, 0, -l}};
    ASSERT_EQ(add_polygon(scene, upper, 1, 1).added, 1);
    ASSERT_EQ(add_polygon(scene, lower, 1, 1).added, 1);
    ASSERT_LT(scene.polygons[1].normal.x, 0); // facing the point
    Luminaire lamp;
    lamp.name = "L";
    lamp.kind = "candela";
    lamp.distribution = isotropic_distribution(0.1);
    lamp.position = {-0.01, 0.001, 0};
    lamp.orient();
    scene.luminaires.push_back(lamp);
    make_two_sided(scene, [](std::uint32_t p) { return p == 0; }); // the floor
    finish_scene(scene, scene.source);
    ASSERT_NE(scene.polygons[0].twin, kNoTwin);

    const dvec3 p(0, -1e-10, 0), n(0, 1, 0);
    const double expected = point_to_polygon_ff(p, n, upper.data(), 4) *
                                scene.material_of(scene.polygons[1]).exitance().x +
                            lamp.irradiance(p, n);
    ASSERT_GT(point_to_polygon_ff(p, n, upper.data(), 4), 0.03); // the bar: 3.6 % of the view
    Hierarchy h_(scene, discretise(scene, HierarchyOptions{}));
    const FinalGather gather(h_);
    const double direct = gather.direct_at({p, n, 0}, 0).x;
    EXPECT_NEAR(direct, expected, 1e-6 * expected);
}
