// The patch hierarchy: lazy push-pull conserves power, unshot power is tracked exactly.
#include <gtest/gtest.h>

#include "hemirad/hierarchy.h"
#include "hemirad/scene_io.h"

using namespace hemirad;

namespace {

Scene two_polygons() {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5, 0.25, 0.75), dvec3(0.0)});
    s.groups.push_back("g");
    add_polygon(s, {{0, 0, 0}, {3, 0, 0}, {2.5, 2, 0}, {0.2, 1.5, 0}}, 0, 0); // quad
    add_polygon(s, {{0, 0, 1}, {0.4, 1.7, 1}, {2, 0.3, 1}}, 0, 0);            // triangle
    finish_scene(s, "test");
    return s;
}

TEST(Hierarchy, DepthFollowsPatchSizeWithCap) {
    const Scene s = two_polygons();
    HierarchyOptions o;
    o.patch_size = 0.4;
    o.max_depth = 10;
    const Discretisation d = discretise(s, o);
    // Quad's longest edge is 3.0: 3/2^3 = 0.375 <= 0.4 < 0.75.
    EXPECT_EQ(d.depth[0], 3);
    o.max_depth = 2;
    EXPECT_EQ(discretise(s, o).depth[0], 2);
    o.max_depth = 12;
    EXPECT_ANY_THROW(discretise(s, o));
}

TEST(Hierarchy, PushPullConservesPowerAndTracksUnshot) {
    const Scene s = two_polygons();
    HierarchyOptions o;
    o.patch_size = 0.3;
    Hierarchy h(s, discretise(s, o));
    EXPECT_EQ(h.total_unshot_power(), dvec3(0.0));
    // Deliver irradiance at assorted levels of the quad.
    const dvec3 e1(1.0, 2.0, 3.0), e2(0.5, 0.5, 0.5), e3(4.0, 0.0, 1.0);
    h.receive({0, 0, 0}, e1);
    h.receive({0, 1, 2}, e2);
    h.receive({0, 3, 17}, e3);
    const auto area = [&](std::uint32_t l, std::uint32_t i) {
        return double(h.node({0, l, i}).area);
    };
    const dvec3 rho = s.materials[0].rho;
    const dvec3 expected_power = rho * (e1 * area(0, 0) + e2 * area(1, 2) + e3 * area(3, 17));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(h.unshot_power(0)[c], expected_power[c], 1e-9);
    EXPECT_TRUE(h.needs_push_pull(0));
    h.push_pull(0);
    EXPECT_FALSE(h.needs_push_pull(0));
    // After push-pull the root's dB*A is the same power (float node storage: 1e-6).
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(h.unshot_power(0)[c], expected_power[c], 1e-6 * expected_power[c]);
    // Irradiance received, integrated over the leaves, equals what was delivered.
    const std::uint32_t L = std::uint32_t(h.depth(0));
    dvec3 leaf_power(0.0);
    for (std::uint32_t i = 0; i < (1u << (2 * L)); ++i)
        leaf_power += dvec3(h.node({0, L, i}).H) * double(h.node({0, L, i}).area);
    const dvec3 delivered = e1 * area(0, 0) + e2 * area(1, 2) + e3 * area(3, 17);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(leaf_power[c], delivered[c], 1e-6 * delivered[c]);
    // The node that got e3 directly has at least e1 + e3 in every channel.
    EXPECT_GE(double(h.node({0, 3, 17}).H.x), e1.x + e3.x - 1e-5);
}

TEST(Hierarchy, ClearUnshotRemovesExactlyTheSubtreePower) {
    const Scene s = two_polygons();
    HierarchyOptions o;
    o.patch_size = 0.3;
    Hierarchy h(s, discretise(s, o));
    h.receive({1, 0, 0}, dvec3(1.0));
    h.push_pull(1);
    const dvec3 before = h.unshot_power(1);
    const auto& child = h.node({1, 1, 3});
    const dvec3 child_power = dvec3(child.dB) * double(child.area);
    h.clear_unshot({1, 1, 3});
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(h.unshot_power(1)[c], before[c] - child_power[c], 1e-6 * before[c]);
    EXPECT_NEAR(h.unshot_power(1).x, 0.75 * before.x, 1e-6); // triangle children: equal areas
}

TEST(Hierarchy, EmittersStartWithUnshotExitance) {
    BuiltinOptions bo;
    bo.subdiv = 2;
    const Scene s = make_builtin("furnace", bo);
    Hierarchy h(s, discretise(s, {}));
    EXPECT_NEAR(h.total_unshot_power().x, 6.0, 1e-5);
    EXPECT_NEAR(h.radiosity({0, 0, 0}).x, 1.0, 1e-12);
}

} // namespace
