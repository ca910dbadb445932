// The final gather's traced paths (gather.h, FinalGather::reflected and direct_sample) in a
// furnace: the unit cube, every face emitting exitance M = 1 and reflecting rho = 0.3, each face
// cut into 8 x 8 emitter polygons (384 of them). The irradiance anywhere inside is exactly
// M / (1 - rho): M from the walls' own light, and rho of it again at each bounce.
//
// The hierarchy is not solved (its leaves hold nothing), and each polygon is one leaf (0.125
// wide, so that every hit in the cube lies within the gather's 30 leaf sizes): everything the
// gather finds beyond the point's own direct light comes from its traced paths: 8 bounces,
// then Russian roulette (kept with probability rho, weighted by 1 / rho), exact in
// expectation (at most 256 bounces). At each traced hit about 8 of the emitter
// polygons get a shadow ray and the rest are left to Russian roulette; with the roulette's
// weights left out, E reads 22-26 % low.
//
// Tolerance: 1 % of E. The direct part is exact (all of every emitter is seen); the indirect
// part, 30 % of E, has the roulette's and the stratified rays' noise: over 16 seeds, E's
// standard deviation at these points is 0.17-0.23 % of E (the largest error 0.61 %), their
// means -0.11, -0.11 and -0.01 %.
//
// The second test lights a 4 x 4 block of the ceiling's polygons in the solution alone (their
// leaves receive 1000 times the walls' exitance; nothing else changes): they become the
// gather's bright leaves (bright_leaves.h), sampled besides the cosine rays and weighted by
// multiple importance sampling. Since every hit is traced, the solution only steers where the
// samples go: the expected E stays M / (1 - rho), and an error in the weights shows. Without
// the cosine rays' weight (the block's light counted twice) E reads 1.7-3.6 % high, without the
// bright samples' weight 71-75 % high. Same tolerance: over 8 seeds E's standard deviation is
// about 0.4 % of E (the largest error 0.8 %).
#include <gtest/gtest.h>

#include "hemirad/gather.h"
#include "hemirad/scene_io.h"

using namespace hemirad;

namespace {

constexpr double kRho = 0.3;

Scene furnace(double rho = kRho) {
    BuiltinOptions bo;
    bo.subdiv = 8;
    bo.rho = rho;
    return make_builtin("furnace", bo);
}

Hierarchy unsolved(const Scene& scene) {
    HierarchyOptions ho;
    ho.max_depth = 0;
    return Hierarchy(scene, discretise(scene, ho));
}

/// The furnace's irradiance M / (1 - rho) at points on the floor's plane (y = 0, normal +y)
/// away from and near the walls, and one inside the box facing +x; all given as points in free
/// space (no polygon).
void expect_furnace_irradiance(const Hierarchy& h, double rho = kRho, double tolerance = 0.01) {
    const Scene& scene = h.scene();
    ASSERT_GE(scene.polygons.size(), 384u); // the furnace's (first) and any outside it
    const double M = scene.material_of(scene.polygons[0]).exitance().x;
    ASSERT_NEAR(M, 1.0, 1e-12);

    GatherOptions go;
    go.indirect_error = 0; // one pass of 1024 rays: the test is on the mean, not the re-gather
    const FinalGather gather(h, go);
    const double expected = M / (1 - rho);
    const std::vector<GatherPoint> points = {
        {dvec3(0.5, 0.0, 0.5), dvec3(0, 1, 0), GatherPoint::kNoSurface},
        {dvec3(0.07, 0.0, 0.93), dvec3(0, 1, 0), GatherPoint::kNoSurface},
        {dvec3(0.3, 0.6, 0.4), dvec3(1, 0, 0), GatherPoint::kNoSurface},
    };
    for (std::size_t k = 0; k < points.size(); ++k) {
        const GatherValue v = gather.at(points[k], k);
        EXPECT_NEAR(v.direct.x, M, 1e-6) << "point " << k;
        EXPECT_NEAR(v.E().x, expected, tolerance * expected) << "point " << k;
    }
}

} // namespace

TEST(GatherPaths, AFurnaceOfManyEmitterPolygonsIsGatheredWithoutBias) {
    const Scene scene = furnace();
    expect_furnace_irradiance(unsolved(scene));
}

TEST(GatherPaths, SamplingTheSolutionsBrightLeavesLeavesTheFurnaceUnbiased) {
    const Scene scene = furnace();
    Hierarchy h = unsolved(scene);
    int lit = 0;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& P = scene.polygons[p];
        dvec3 centre(0.0);
        for (int k = 0; k < P.count; ++k) centre += P.v[k] / double(P.count);
        if (P.normal.y < -0.5 && std::abs(centre.x - 0.5) < 0.25 &&
            std::abs(centre.z - 0.5) < 0.25) {
            h.receive({p, 0, 0}, dvec3(1000.0));
            ++lit;
        }
    }
    h.push_pull_all();
    ASSERT_EQ(lit, 16);
    expect_furnace_irradiance(h);
}

// A furnace of reflectance 0.9: nine tenths of E comes after a bounce, and 39 % of it (0.9^9)
// after more than 8. The paths go on by Russian roulette (from their second bounce), so E
// stays exact in expectation; stopped after 8 bounces and reading the (empty) solution, E
// reads 39 % low (measured). Tolerance 8 %: over 24 seeds E's standard deviation is 1.9-2.7 %
// of E at the three points (the largest error 6.4 %; the means within 0.8 %, their standard
// errors 0.4-0.6 %).
constexpr double kBrightFurnaceTolerance = 0.08;

TEST(GatherPaths, ABrightFurnaceIsGatheredPastEightBounces) {
    const Scene scene = furnace(0.9);
    expect_furnace_irradiance(unsolved(scene), 0.9, kBrightFurnaceTolerance);
}

// The same bright furnace with one bright leaf outside it: a 10 cm patch 3 m above its top,
// facing it, whose leaf holds 1000 in the solution (the scene's only light in the solution).
// The gather samples it from every hit, and from inside the furnace it is always hidden. When
// a traced path took either a cosine ray or a bright leaf at each hit, with even odds and a
// weight of 2, its weight doubled at every bounce (the bright leaf never found), and the paths
// here run for tens of bounces: E read 11.4, 7.6 and 6.0 for 10 at the three points (most
// paths die early, one in 2^k carries 2^k times the light). Past the first hit a far bright
// leaf is now sampled beside the cosine ray, which goes on with a weight of 1 where it meets
// no bright leaf.
TEST(GatherPaths, ABrightLeafHiddenFromAFurnaceLeavesItsPathsWeightsAlone) {
    Scene scene = furnace(0.9);
    const std::uint32_t grey = std::uint32_t(scene.materials.size());
    scene.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    const std::uint32_t patch = std::uint32_t(scene.polygons.size());
    add_polygon(scene, {{0.45, 4, 0.45}, {0.55, 4, 0.45}, {0.55, 4, 0.55}, {0.45, 4, 0.55}}, grey,
                0);
    finish_scene(scene, "furnace and patch");
    ASSERT_EQ(scene.polygons.size(), 385u);
    ASSERT_LT(scene.polygons[patch].normal.y, -0.99);
    Hierarchy h = unsolved(scene);
    h.receive({patch, 0, 0}, dvec3(1000.0));
    h.push_pull_all();
    expect_furnace_irradiance(h, 0.9, kBrightFurnaceTolerance);
}
