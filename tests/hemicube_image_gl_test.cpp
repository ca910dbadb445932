// FormFactorProvider::last_hemicube() (the viewer's hemicube inset): after one shot of the GPU
// provider at a fixed resolution the image has the layout's size (2 res x 1.5 res) and shows
// what a shooter inside a closed cube must see: surfaces everywhere, with positive analytic
// form factors. CPU providers have no hemicube.
#include <gtest/gtest.h>

#include <memory>

#include "hemirad/gl/context.h"
#include "hemirad/hierarchy.h"
#include "hemirad/provider.h"
#include "hemirad/scene_io.h"

using namespace hemirad;

namespace {

Shooter whole_polygon_shooter(const Scene& s, std::uint32_t p) {
    Shooter sh;
    sh.address = {p, 0, 0};
    sh.geometry = patch_geometry(s.polygons[p], 0, 0);
    sh.normal = s.polygons[p].normal;
    sh.unshot_power = 1;
    return sh;
}

TEST(HemicubeImage, LastShotOfTheCube) {
    // No context is a failure, not a skip.
    const std::unique_ptr<gl::Context> context = gl::Context::create();
    ASSERT_TRUE(context);
    const Scene scene = make_builtin("cube");
    ASSERT_FALSE(scene.polygons.empty());
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    ProviderOptions o;
    o.gpu.use_current_context = true;
    o.gpu.resolution = 64;
    const std::unique_ptr<FormFactorProvider> provider = make_provider("hybrid", scene, disc, o);
    EXPECT_EQ(provider->last_hemicube().rgba, nullptr) << "an image before any shot";

    std::vector<Link> links;
    provider->shoot(whole_polygon_shooter(scene, 0), links);
    EXPECT_FALSE(links.empty());
    const FormFactorProvider::HemicubeImage img = provider->last_hemicube();
    ASSERT_NE(img.rgba, nullptr);
    EXPECT_EQ(img.width, 128);
    EXPECT_EQ(img.height, 96);

    const long n = long(img.width) * img.height;
    long surface = 0, positive = 0;
    for (long i = 0; i < n; ++i) {
        const float* p = img.rgba + 4 * i;
        if (p[2] <= 0.5f) continue;
        ++surface;
        positive += p[3] > 0;
        EXPECT_NE(std::uint32_t(p[2]) - 1, 0u) << "pixel " << i << " shows the shooter's polygon";
        EXPECT_LT(std::uint32_t(p[2]) - 1, scene.polygons.size()) << "pixel " << i;
    }
    // Inside a closed cube every hemicube pixel sees one of the other five faces (a few at
    // the edges may fall between them).
    EXPECT_GT(surface, n * 95 / 100) << surface << " of " << n << " pixels show a surface";
    EXPECT_EQ(positive, surface) << "surface pixels with a form factor <= 0";
}

TEST(HemicubeImage, CpuProvidersHaveNone) {
    const Scene scene = make_builtin("cube");
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    const std::unique_ptr<FormFactorProvider> provider =
        make_provider("reference", scene, disc, ProviderOptions{});
    std::vector<Link> links;
    provider->shoot(whole_polygon_shooter(scene, 0), links);
    EXPECT_EQ(provider->last_hemicube().rgba, nullptr);
    EXPECT_EQ(provider->last_hemicube().width, 0);
}

} // namespace
