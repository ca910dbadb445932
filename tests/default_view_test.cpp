// The default view of scenes without a camera (frame_scene, default_view.cpp): an open box is
// framed from its open side whichever way it faces, a closed room from inside, a lit floor from
// above; scenes with a camera keep it. CPU only (rays through a BVH).
#include <gtest/gtest.h>

#include <string>

#include "hemirad/render.h"
#include "hemirad/scene_io.h"

using namespace hemirad;

namespace {

std::string data(const std::string& name) {
    return std::string(HEMIRAD_TEST_DATA) + "/" + name;
}

dvec3 view_direction(const Camera& c) {
    return glm::normalize(c.target - c.eye);
}

bool inside(const Bounds& b, const dvec3& p) {
    return glm::all(glm::greaterThan(p, b.lo)) && glm::all(glm::lessThan(p, b.hi));
}

/// A unit box whose side facing `open` (a unit axis, not +-y) is missing, walls facing in, a
/// small light under the ceiling facing down.
Scene open_box(const dvec3& open) {
    Scene s;
    s.materials = {{"wall", dvec3(0.7), dvec3(0.0)}, {"light", dvec3(0.8), dvec3(5.0)}};
    s.groups = {"walls", "light"};
    const dvec3 c(0.5);
    for (int axis = 0; axis < 3; ++axis)
        for (int sign : {-1, 1}) {
            dvec3 n(0.0);
            n[axis] = sign;
            if (n == open) continue;
            // The face at c + n/2, its corners counter-clockwise seen from inside (along -n).
            const dvec3 u = axis == 1 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
            const dvec3 v = glm::cross(-n, u);
            const dvec3 o = c + 0.5 * n;
            add_polygon(s,
                        {o - 0.5 * u - 0.5 * v, o + 0.5 * u - 0.5 * v, o + 0.5 * u + 0.5 * v,
                         o - 0.5 * u + 0.5 * v},
                        0, 0);
        }
    add_polygon(s, {{0.4, 0.99, 0.4}, {0.6, 0.99, 0.4}, {0.6, 0.99, 0.6}, {0.4, 0.99, 0.6}}, 1, 1);
    finish_scene(s, "open box");
    for (const Polygon& p : s.polygons) EXPECT_GT(glm::dot(p.normal, c - p.centroid()), 0);
    return s;
}

TEST(DefaultView, OpenBoxFileFacingPlusZIsSeenThroughItsOpening) {
    const Scene s = load_obj(data("scenes/open_box/obj/open_box.obj"));
    ASSERT_TRUE(s.cameras.empty());
    const Camera c = default_camera(s);
    EXPECT_EQ(c.name, "default");
    EXPECT_GT(c.eye.z, s.bounds().hi.z);
    EXPECT_GT(glm::dot(view_direction(c), dvec3(0, 0, -1)), 0.99);
}

class OpenBoxSides : public ::testing::TestWithParam<dvec3> {};

TEST_P(OpenBoxSides, FramedFromTheOpenSide) {
    const dvec3 open = GetParam();
    const Scene s = open_box(open);
    const Camera c = frame_scene(s);
    EXPECT_GT(glm::dot(view_direction(c), -open), 0.99)
        << "eye " << c.eye.x << " " << c.eye.y << " " << c.eye.z;
    EXPECT_FALSE(inside(s.bounds(), c.eye));
}

INSTANTIATE_TEST_SUITE_P(DefaultView, OpenBoxSides,
                         ::testing::Values(dvec3(0, 0, 1), dvec3(0, 0, -1), dvec3(1, 0, 0),
                                           dvec3(-1, 0, 0)));

TEST(DefaultView, ClosedRoomIsSeenFromInside) {
    const Scene s = load_obj(std::string(HEMIRAD_SOURCE_DIR) + "/assets/cube_room.obj");
    const Camera c = default_camera(s);
    EXPECT_TRUE(inside(s.bounds(), c.eye)) << c.eye.x << " " << c.eye.y << " " << c.eye.z;
}

TEST(DefaultView, LitFloorIsSeenFromItsFrontSide) {
    Scene s;
    s.materials = {{"floor", dvec3(0.5), dvec3(0.0)}, {"light", dvec3(0.5), dvec3(1.0)}};
    s.groups = {"floor", "light"};
    add_polygon(s, {{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}}, 0, 0); // faces up
    add_polygon(s, {{1, 2, 1}, {3, 2, 1}, {3, 2, 3}, {1, 2, 3}}, 1, 1); // faces down
    finish_scene(s, "floor");
    ASSERT_GT(s.polygons[0].normal.y, 0);
    // Not from below (the floor's back) nor from the side (edge-on); from above the light its
    // back hides a quarter of the floor, so the view from under it (inside the bounds) wins.
    const Camera c = frame_scene(s);
    EXPECT_GT(c.eye.y, 0.5);
    EXPECT_LE(view_direction(c).y, 0.0);
}

TEST(DefaultView, SceneCamerasAreKept) {
    const Scene s = make_builtin("cornell");
    const Camera c = default_camera(s);
    EXPECT_EQ(c.eye, dvec3(278, 273, -800));
    EXPECT_EQ(c.target, dvec3(278, 273, 0));
}

} // namespace
