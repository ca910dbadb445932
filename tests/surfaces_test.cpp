// Finishing a scene's surfaces (scene.h, scene_io.h finish_surfaces): two-sided surfaces
// (make_two_sided; glTF doubleSided, SCENE.json "two_sided", ObjOptions::two_sided_surfaces)
// and polygons cut where others pass through them (split_intersections). Every expectation is
// geometry worked out by hand from the corners the test builds: twins' corners and normals,
// areas of the pieces (x extents times z extents), which polygons a meeting line crosses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <unistd.h>

#include "hemirad/error.h"
#include "hemirad/patch.h"
#include "hemirad/readout.h"
#include "hemirad/scene.h"
#include "hemirad/scene_io.h"
#include "solver/plane_cuts.h"

using namespace hemirad;
namespace fs = std::filesystem;

namespace {

// A scene of one material and the given groups, polygons added with add_polygon().
struct Builder {
    Scene scene;
    Builder() {
        scene.materials.push_back(Material{"grey", dvec3(0.5), dvec3(0.0)});
        scene.materials.push_back(Material{"lamp", dvec3(0.5), dvec3(1.0)});
    }
    std::uint32_t group(const std::string& name) {
        const int g = scene.find_group(name);
        if (g >= 0) return std::uint32_t(g);
        scene.groups.push_back(name);
        return std::uint32_t(scene.groups.size() - 1);
    }
    void quad(const std::vector<dvec3>& c, const std::string& g, std::uint32_t material = 0,
              const std::vector<glm::dvec2>* uv = nullptr) {
        ASSERT_EQ(add_polygon(scene, c, material, group(g), 1e-6, uv).added, 1);
    }
    // Horizontal quad at height y facing up: [x0, x1] x [z0, z1].
    void floor(double x0, double x1, double z0, double z1, double y, const std::string& g) {
        quad({{x0, y, z0}, {x0, y, z1}, {x1, y, z1}, {x1, y, z0}}, g);
    }
    // Vertical quad in the plane z = z, [x0, x1] x [y0, y1], facing +z.
    void wall_z(double x0, double x1, double y0, double y1, double z, const std::string& g) {
        quad({{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, g);
    }
    // Closed box [lo, hi], faces outwards, group g.
    void box(const dvec3& lo, const dvec3& hi, const std::string& g) {
        quad({{lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}}, g);
        quad({{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}}, g);
        quad({{lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}}, g);
        quad({{hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}}, g);
        quad({{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z}}, g);
        quad({{lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}}, g);
    }
};

std::size_t count_in(const Scene& s, const std::string& group) {
    const int g = s.find_group(group);
    return std::size_t(std::count_if(s.polygons.begin(), s.polygons.end(),
                                     [&](const Polygon& p) { return int(p.group) == g; }));
}

double area_of(const Scene& s, const std::string& group) {
    const int g = s.find_group(group);
    double a = 0;
    for (const Polygon& p : s.polygons)
        if (int(p.group) == g) a += p.area;
    return a;
}

void expect_near(const dvec3& a, const dvec3& b, const std::string& what) {
    EXPECT_LT(glm::length(a - b), 1e-9) << what << ": (" << a.x << ", " << a.y << ", " << a.z
                                        << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

class Files : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("hemirad_surfaces_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& text) {
        const fs::path p = dir_ / name;
        std::ofstream(p) << text;
        return p.string();
    }
    fs::path dir_;
};

// The end of a glTF whose accessor 0 holds the unit quad [0, 1] x {0} x [0, 1] facing up
// (four corners) and accessor 1 its two triangles' indices, as a data URI.
const char* kUnitQuadBuffers = R"(
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAAAAAAAAAAAAAIA/AACAPwAAAAAAAIA/AACAPwAAAAAAAAAAAAABAAIAAAACAAMA"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 0, 1]},
                {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]
})";

// Two unit quads facing up, "floor" at y = 0 and "shelf" at y = 1, each its own group.
const char* kTwoQuadsMtl = "newmtl white\nKd 0.5 0.5 0.5\n";
const char* kTwoQuadsObj = "mtllib m.mtl\nusemtl white\n"
                           "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\n"
                           "v 0 1 0\nv 0 1 1\nv 1 1 1\nv 1 1 0\n"
                           "g floor\nf 1 2 3 4\ng shelf\nf 5 6 7 8\n";

} // namespace

// --- make_two_sided -----------------------------------------------------------------------

TEST(TwoSided, TwinHasReversedCornersOppositeNormalSameMaterialAndGroup) {
    Builder b;
    b.floor(0, 2, 0, 1, 0, "floor"); // quad 0
    ASSERT_EQ(add_polygon(b.scene, {{0, 1, 0}, {1, 1, 0}, {0, 2, 0}}, 1, b.group("tri")).added,
              1);                    // triangle 1, facing +z, the emitting material
    b.floor(0, 1, 0, 1, 3, "other"); // quad 2, not picked
    const std::size_t added = make_two_sided(b.scene, [](std::uint32_t p) { return p != 2; });
    ASSERT_EQ(added, 2u);
    const Scene& s = b.scene;
    ASSERT_EQ(s.polygons.size(), 5u);
    EXPECT_EQ(s.polygons[2].twin, kNoTwin);
    for (std::uint32_t p : {0u, 1u}) {
        const Polygon& a = s.polygons[p];
        ASSERT_NE(a.twin, kNoTwin) << p;
        ASSERT_LT(a.twin, s.polygons.size());
        const Polygon& t = s.polygons[a.twin];
        EXPECT_EQ(t.twin, p) << "the link goes both ways";
        EXPECT_EQ(t.count, a.count);
        EXPECT_EQ(t.material, a.material);
        EXPECT_EQ(t.group, a.group);
        EXPECT_NEAR(t.area, a.area, 1e-12);
        expect_near(t.normal, -a.normal, "normal");
        // The same corners, in the opposite order (the twin's winding is reversed).
        for (int k = 0; k < a.count; ++k)
            expect_near(t.v[std::size_t(k)], a.v[std::size_t((a.count - k) % a.count)],
                        "corner " + std::to_string(k));
        // Counter-clockwise about its own normal: the normal of its corners' cross product.
        expect_near(glm::normalize(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0])), t.normal,
                    "winding");
    }
    expect_near(s.polygons[0].normal, {0, 1, 0}, "floor faces up");
    expect_near(s.polygons[s.polygons[0].twin].normal, {0, -1, 0}, "its twin faces down");
    // Emission doubles with the area: the twin emits from its own side.
    EXPECT_NEAR(s.surface_power().x, 2 * 0.5 * std::numbers::pi, 1e-12);
}

TEST(TwoSided, AlreadyTwinnedPolygonsAreLeftAloneTwinsAreNotTwinnedAgain) {
    Builder b;
    b.floor(0, 1, 0, 1, 0, "a");
    b.floor(0, 1, 0, 1, 1, "b");
    ASSERT_EQ(make_two_sided(b.scene, [](std::uint32_t p) { return p == 0; }), 1u);
    const auto before = b.scene.polygons.size();
    // Everything picked: only polygon 1 is still one-sided (0 and its twin 2 are left alone).
    EXPECT_EQ(make_two_sided(b.scene, [](std::uint32_t) { return true; }), 1u);
    EXPECT_EQ(b.scene.polygons.size(), before + 1);
    EXPECT_EQ(make_two_sided(b.scene, [](std::uint32_t) { return true; }), 0u);
    for (std::uint32_t p = 0; p < b.scene.polygons.size(); ++p)
        EXPECT_EQ(b.scene.polygons[b.scene.polygons[p].twin].twin, p);
}

// A board modelled by both its faces, each two-sided (the office glb's desk parts): each
// face's twin would lie on the other face, facing its way, and take the same light again (a
// patch 10 cm from such a board sent 1.45 of its light: hemicube_gl_test, TwoSidedBoard).
// The faces are paired instead, and no twin is added.
TEST(TwoSided, ABoardModelledByBothFacesIsPairedNotTwinned) {
    Builder b;
    b.floor(0, 1, 0, 1, 0, "top");                                  // 0, facing up
    b.quad({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, "bottom"); // 1, facing down
    b.floor(0, 1, 0, 1, 2, "shelf");                                // 2, elsewhere
    ASSERT_LT(b.scene.polygons[1].normal.y, -0.99);
    std::size_t paired = 99;
    EXPECT_EQ(make_two_sided(
                  b.scene, [](std::uint32_t) { return true; }, &paired),
              1u);
    EXPECT_EQ(paired, 1u);
    const Scene& s = b.scene;
    ASSERT_EQ(s.polygons.size(), 4u) << "only the shelf gets a twin";
    EXPECT_EQ(s.polygons[0].twin, 1u);
    EXPECT_EQ(s.polygons[1].twin, 0u);
    EXPECT_EQ(s.polygons[2].twin, 3u);
    // Picked one at a time, the same: the second face is the first's back.
    Builder one;
    one.floor(0, 1, 0, 1, 0, "top");
    one.quad({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, "bottom");
    EXPECT_EQ(make_two_sided(
                  one.scene, [](std::uint32_t p) { return p == 0; }, &paired),
              0u);
    EXPECT_EQ(paired, 1u);
    EXPECT_EQ(one.scene.polygons[1].twin, 0u);
}

// drop_coincident_polygons: a quad repeated with its corners in another order on the same
// side is dropped (its texture coordinates with it), unless it emits and the first does not;
// the same quad turned over stays.
TEST(CoincidentPolygons, ARepeatOnTheSameSideIsDroppedABackToBackOneStays) {
    Builder b;
    const std::vector<glm::dvec2> uv0{{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    const std::vector<glm::dvec2> uv1{{0.5, 0}, {0.5, 1}, {1, 1}, {1, 0}};
    b.quad({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, "a", 0, &uv0); // 0, facing up
    b.quad({{1, 0, 1}, {1, 0, 0}, {0, 0, 0}, {0, 0, 1}}, "b", 0, &uv1); // 1, the same, rotated
    b.quad({{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, "c");          // 2, turned over
    b.floor(0, 1, 0, 1, 2, "d");                                        // 3, elsewhere
    ASSERT_GT(b.scene.polygons[1].normal.y, 0.99);
    ASSERT_LT(b.scene.polygons[2].normal.y, -0.99);
    std::uint32_t group = 99;
    EXPECT_EQ(drop_coincident_polygons(b.scene, &group), 1u);
    EXPECT_EQ(b.scene.groups[group], "b");
    ASSERT_EQ(b.scene.polygons.size(), 3u);
    ASSERT_EQ(b.scene.texcoords.size(), 3u);
    EXPECT_EQ(b.scene.groups[b.scene.polygons[0].group], "a");
    EXPECT_EQ(b.scene.groups[b.scene.polygons[1].group], "c");
    EXPECT_EQ(b.scene.groups[b.scene.polygons[2].group], "d");
    EXPECT_FLOAT_EQ(b.scene.texcoords[0][0].x, 0.f);
    EXPECT_EQ(drop_coincident_polygons(b.scene), 0u);
    // A lamp's face laid on the ceiling's (the same corners, the same side, after it): the
    // lamp's stays, wherever it comes.
    Builder lamp;
    lamp.floor(0, 1, 0, 1, 2, "ceiling");
    ASSERT_EQ(
        add_polygon(lamp.scene, {{0, 2, 0}, {0, 2, 1}, {1, 2, 1}, {1, 2, 0}}, 1, lamp.group("lamp"))
            .added,
        1);
    EXPECT_EQ(drop_coincident_polygons(lamp.scene, &group), 1u);
    EXPECT_EQ(lamp.scene.groups[group], "ceiling");
    ASSERT_EQ(lamp.scene.polygons.size(), 1u);
    EXPECT_EQ(lamp.scene.groups[lamp.scene.polygons[0].group], "lamp");
    EXPECT_GT(lamp.scene.material_of(lamp.scene.polygons[0]).Ke.x, 0);
}

TEST(TwoSided, TexCoordsFollowTheCorners) {
    Builder b;
    const std::vector<glm::dvec2> uv{{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    b.quad({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, "uv", 0, &uv);
    ASSERT_EQ(make_two_sided(b.scene, [](std::uint32_t) { return true; }), 1u);
    ASSERT_EQ(b.scene.texcoords.size(), b.scene.polygons.size());
    const Polygon& a = b.scene.polygons[0];
    const Polygon& t = b.scene.polygons[1];
    // Each corner keeps its coordinates: the texcoord of the twin's corner at point x is the
    // original's at x.
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j)
            if (glm::length(t.v[std::size_t(k)] - a.v[std::size_t(j)]) < 1e-12) {
                EXPECT_EQ(b.scene.texcoords[1][std::size_t(k)],
                          b.scene.texcoords[0][std::size_t(j)])
                    << "corner " << k;
            }
}

TEST_F(Files, ObjTwoSidedSurfacesTwinsEveryPolygon) {
    write("m.mtl", kTwoQuadsMtl);
    const std::string obj = write("two.obj", kTwoQuadsObj);
    const Scene one = load_obj(obj);
    ASSERT_EQ(one.polygons.size(), 2u);
    for (const Polygon& p : one.polygons) EXPECT_EQ(p.twin, kNoTwin);
    ObjOptions o;
    o.two_sided_surfaces = true;
    const Scene two = load_obj(obj, o);
    ASSERT_EQ(two.polygons.size(), 4u);
    for (const Polygon& p : two.polygons) ASSERT_NE(p.twin, kNoTwin);
    EXPECT_NEAR(two.total_area(), 2 * one.total_area(), 1e-12);
    // Facing down under the shelf: the shelf's twin, found where the one-sided scene has none.
    EXPECT_FALSE(find_surface(one, {0.5, 1, 0.5}, {0, -1, 0}, 1e-6).has_value());
    const auto under = find_surface(two, {0.5, 1, 0.5}, {0, -1, 0}, 1e-6);
    ASSERT_TRUE(under.has_value());
    EXPECT_EQ(two.groups[two.polygons[under->polygon].group], "shelf");
    EXPECT_LT(glm::dot(two.polygons[under->polygon].normal, dvec3(0, 1, 0)), -0.999);
}

TEST_F(Files, SceneJsonTwoSidedGroupsOnly) {
    write("m.mtl", kTwoQuadsMtl);
    write("two.obj", kTwoQuadsObj);
    const Scene s =
        load_scene_json(write("scene.json", R"({"include": ["two.obj"], "two_sided": ["shelf"]})"));
    ASSERT_EQ(s.polygons.size(), 3u);
    EXPECT_EQ(count_in(s, "shelf"), 2u);
    EXPECT_EQ(count_in(s, "floor"), 1u);
    for (const Polygon& p : s.polygons)
        EXPECT_EQ(p.twin != kNoTwin, s.groups[p.group] == "shelf") << s.groups[p.group];
}

TEST_F(Files, SceneJsonTwoSidedUnknownGroupIsAnErrorNamingIt) {
    write("m.mtl", kTwoQuadsMtl);
    write("two.obj", kTwoQuadsObj);
    const std::string path =
        write("scene.json", R"({"include": ["two.obj"], "two_sided": ["shelf", "Glas"]})");
    try {
        load_scene_json(path);
        FAIL() << "an unknown group was accepted";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("Glas"), std::string::npos) << m;
        EXPECT_NE(m.find("scene.json"), std::string::npos) << m;
        EXPECT_NE(m.find("two_sided"), std::string::npos) << m;
    }
}

// An object exported twice at the same place (one quad's mesh used by two nodes, neither
// moved): each surface would take its light twice, since the hemicube shows one of the two
// copies and the other is linked all the same (a patch near such a board sent 1.75 of its
// light: hemicube_gl_test, TwoSidedBoard). The second copy's polygons are dropped, with a
// warning naming its group; a copy back to back (the same quad turned over) would stay.
TEST_F(Files, GltfObjectExportedTwiceIsKeptOnce) {
    const std::string gltf = std::string(R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"name": "first", "mesh": 0}, {"name": "copy", "mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
)") + kUnitQuadBuffers;
    const Scene s = load_gltf(write("twice.gltf", gltf));
    EXPECT_EQ(count_in(s, "copy"), 0u);
    EXPECT_GT(count_in(s, "first"), 0u);
    EXPECT_NEAR(area_of(s, "first"), 1.0, 1e-6);
    bool warned = false;
    for (const std::string& w : s.warnings)
        warned = warned ||
                 (w.find("dropped 2 polygon(s) that repeat the corners") != std::string::npos &&
                  w.find("'copy'") != std::string::npos);
    EXPECT_TRUE(warned) << "a warning names the dropped copy's group";
}

TEST_F(Files, GltfDoubleSidedMaterialsAreTwoSided) {
    // One quad (two triangles, facing up) used by two nodes: "plate" at y = 1 with a
    // doubleSided material, "floor" at y = 0 with a one-sided one.
    const std::string gltf = std::string(R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"name": "plate", "mesh": 0, "translation": [0, 1, 0]},
            {"name": "floor", "mesh": 1}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]},
             {"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 1}]}],
  "materials": [{"name": "thin", "doubleSided": true,
                 "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}},
                {"name": "solid",
                 "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}],
)") + kUnitQuadBuffers;
    const Scene s = load_gltf(write("plate.gltf", gltf));
    const std::size_t plate = count_in(s, "plate"), floor = count_in(s, "floor");
    ASSERT_GT(floor, 0u);
    EXPECT_EQ(plate, 2 * floor) << "the plate's polygons and their twins";
    EXPECT_NEAR(area_of(s, "plate"), 2.0, 1e-6);
    EXPECT_NEAR(area_of(s, "floor"), 1.0, 1e-6);
    for (const Polygon& p : s.polygons) {
        const bool is_plate = s.groups[p.group] == "plate";
        EXPECT_EQ(p.twin != kNoTwin, is_plate);
        EXPECT_EQ(s.material_of(p).two_sided, is_plate);
        if (is_plate) {
            EXPECT_EQ(s.polygons[p.twin].group, p.group);
        }
    }
    // Up and down, both faces of the plate are surfaces; the floor's underside is not.
    EXPECT_TRUE(find_surface(s, {0.5, 1, 0.5}, {0, 1, 0}, 1e-6).has_value());
    EXPECT_TRUE(find_surface(s, {0.5, 1, 0.5}, {0, -1, 0}, 1e-6).has_value());
    EXPECT_FALSE(find_surface(s, {0.5, 0, 0.5}, {0, -1, 0}, 1e-6).has_value());
}

// --- split_intersections ------------------------------------------------------------------

// Two quads crossing in a plus shape: "a" in the plane y = 0 ([-1, 1] x [-1, 1]), "b" in the
// plane z = 0 (x in [-0.8, 0.8], y in [-1, 1]). Each passes through the other's middle, so
// each is cut in two along the meeting line (z = 0 in a, y = 0 in b).
TEST(SplitIntersections, PlusShapeCutsBothAlongTheMeetingLineAreasKept) {
    Builder b;
    b.floor(-1, 1, -1, 1, 0, "a");
    b.wall_z(-0.8, 0.8, -1, 1, 0, "b");
    Scene s = b.scene;
    const SplitStats st = split_intersections(s);
    EXPECT_EQ(st.polygons_cut, 2u);
    EXPECT_EQ(st.pieces, 4u);
    ASSERT_EQ(s.polygons.size(), 4u);
    EXPECT_EQ(count_in(s, "a"), 2u);
    EXPECT_EQ(count_in(s, "b"), 2u);
    EXPECT_NEAR(area_of(s, "a"), 4.0, 1e-12);
    EXPECT_NEAR(area_of(s, "b"), 3.2, 1e-12);
    for (const Polygon& p : s.polygons) {
        const bool in_a = s.groups[p.group] == "a";
        // Each piece lies wholly on one side of the other quad's plane: half of the original.
        double lo = 1e300, hi = -1e300;
        for (int k = 0; k < p.count; ++k) {
            const double d = in_a ? p.v[std::size_t(k)].z : p.v[std::size_t(k)].y;
            lo = std::min(lo, d), hi = std::max(hi, d);
        }
        EXPECT_TRUE((lo > -1e-12 && hi > 0.5) || (hi < 1e-12 && lo < -0.5))
            << (in_a ? "a" : "b") << " piece spans " << lo << " .. " << hi;
        EXPECT_NEAR(p.area, in_a ? 2.0 : 1.6, 1e-12);
        EXPECT_EQ(p.material, 0u);
        EXPECT_EQ(p.twin, kNoTwin);
        expect_near(p.normal, in_a ? dvec3(0, 1, 0) : dvec3(0, 0, 1), "normal kept");
    }
}

// A box standing on a floor: its four sides touch the floor's front along their bottom edges,
// and the floor is cut along those lines (3 x 3 pieces, the middle one exactly the box's
// footprint, which no shooter outside the box sees); the box itself is not cut (the floor
// meets its sides only on their edges). The same box under the floor (touching its back), or
// standing on one corner edge outside the floor, cuts nothing.
TEST(SplitIntersections, BoxStandingOnAFloorCutsTheFloorAlongItsFootprint) {
    Builder b;
    b.floor(-2, 2, -2, 2, 0, "floor");
    b.box({-0.5, 0, -0.5}, {0.5, 1, 0.5}, "box"); // bottom face in the floor's plane
    Scene s = b.scene;
    const SplitStats st = split_intersections(s);
    EXPECT_EQ(st.polygons_cut, 1u);
    EXPECT_EQ(count_in(s, "floor"), 9u);
    EXPECT_EQ(count_in(s, "box"), 6u);
    EXPECT_NEAR(area_of(s, "floor"), 16.0, 1e-12);
    const auto under = find_surface(s, {0.2, 0, 0.1}, {0, 1, 0}, 1e-9);
    ASSERT_TRUE(under.has_value());
    EXPECT_NEAR(s.polygons[under->polygon].area, 1.0, 1e-12) << "the footprint";
}

TEST(SplitIntersections, BoxTouchingAFloorFromBehindIsNotCut) {
    Builder b;
    b.floor(-2, 2, -2, 2, 0, "floor");
    b.box({-0.5, -1, -0.5}, {0.5, 0, 0.5}, "box"); // hangs under the floor, top in its plane
    Scene s = b.scene;
    const SplitStats st = split_intersections(s);
    EXPECT_EQ(st.polygons_cut, 0u);
    EXPECT_EQ(s.content_hash(), b.scene.content_hash()) << "nothing changed";
}

// The same box sunk half into the floor: the floor is cut along the four side faces' lines
// (3 x 3 pieces, the middle one under the box), each side face along y = 0.
TEST(SplitIntersections, BoxSunkIntoAFloorCutsTheFloorAndItsSides) {
    Builder b;
    b.floor(-2, 2, -2, 2, 0, "floor");
    b.box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, "box");
    Scene s = b.scene;
    const SplitStats st = split_intersections(s);
    EXPECT_EQ(st.polygons_cut, 5u); // the floor and four sides; top and bottom are parallel
    EXPECT_EQ(count_in(s, "floor"), 9u);
    EXPECT_EQ(count_in(s, "box"), 2u + 4u * 2u);
    EXPECT_NEAR(area_of(s, "floor"), 16.0, 1e-12);
    EXPECT_NEAR(area_of(s, "box"), 6.0, 1e-12);
    // The piece under the box is exactly its footprint.
    const auto under = find_surface(s, {0, 0, 0}, {0, 1, 0}, 1e-9);
    ASSERT_TRUE(under.has_value());
    EXPECT_NEAR(s.polygons[under->polygon].area, 1.0, 1e-12);
}

// A thin post (0.2 wide, from y = -0.5 to 0.5) through a 4 x 4 floor: the meeting line in the
// floor is 0.2 long, under a tenth of the floor's longest edge (0.4), so the floor stays
// whole; in the post the line is the full width 0.2, over a tenth of its longest edge (1.0),
// so the post is cut.
TEST(SplitIntersections, MeetingLineUnderATenthOfTheLongestEdgeIsNotCut) {
    Builder b;
    b.floor(-2, 2, -2, 2, 0, "floor");
    b.wall_z(-0.1, 0.1, -0.5, 0.5, 0, "post");
    Scene s = b.scene;
    const SplitStats st = split_intersections(s);
    EXPECT_EQ(st.polygons_cut, 1u);
    EXPECT_EQ(count_in(s, "floor"), 1u);
    EXPECT_EQ(count_in(s, "post"), 2u);
    EXPECT_NEAR(area_of(s, "post"), 0.2, 1e-12);
}

// A desk's leg, as modelled in the office glb: a closed slab 0.1 thick and 2 long sunk 5 cm
// through a 4 x 4 floor, each end face two triangles. The long sides' meeting lines (2, over a
// tenth of the floor's longest edge, 0.4) cut the floor into three strips, along their whole
// lines; the ends' (0.1, in two pieces, one from each triangle, taken as one segment) are
// short, and cut only the piece that they cross from side to side: the middle strip, so that
// the leg's footprint is a polygon of its own (the strip as one polygon reached out from
// under the leg, and its leaves carried the light of the floor in front into the leg). The
// rest of the floor is not cut along the ends' lines.
TEST(SplitIntersections, ShortMeetingLineCutsThePieceItCrosses) {
    Builder b;
    b.floor(-2, 2, -2, 2, 0, "floor");
    const double x0 = 0.2, x1 = 0.3, y0 = -0.05, y1 = 1, z0 = -1, z1 = 1;
    b.quad({{x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}}, "leg"); // top
    b.quad({{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}, "leg"); // bottom
    b.quad({{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}}, "leg"); // side -x
    b.quad({{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}, "leg"); // side +x
    // The ends, facing -z and +z, each split along a diagonal.
    b.quad({{x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}}, "leg");
    b.quad({{x0, y0, z0}, {x1, y1, z0}, {x1, y0, z0}}, "leg");
    b.quad({{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}}, "leg");
    b.quad({{x0, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}, "leg");
    Scene s = b.scene;
    split_intersections(s);
    EXPECT_NEAR(area_of(s, "floor"), 16.0, 1e-12);
    EXPECT_EQ(count_in(s, "floor"), 5u) << "two strips beside, three pieces of the middle one";
    const auto under = find_surface(s, {0.25, 0, 0.3}, {0, 1, 0}, 1e-9);
    ASSERT_TRUE(under.has_value());
    EXPECT_NEAR(s.polygons[under->polygon].area, (x1 - x0) * (z1 - z0), 1e-12) << "the footprint";
    for (double z : {-1.5, 1.5}) {
        const auto beyond = find_surface(s, {0.25, 0, z}, {0, 1, 0}, 1e-9);
        ASSERT_TRUE(beyond.has_value());
        EXPECT_NEAR(s.polygons[beyond->polygon].area, (x1 - x0) * 1.0, 1e-12) << "z " << z;
    }
}

// 20 walls through a 21 x 12 floor, each crossing its full depth (a meeting line of 12, over
// a tenth of the longest edge, 2.1): at most 16 cuts, so 17 pieces, not 21.
TEST(SplitIntersections, AtMostSixteenCutsAPolygon) {
    Builder b;
    b.floor(0, 21, -6, 6, 0, "floor");
    for (int k = 1; k <= 20; ++k) {
        // The wall at x = k, in the plane x = k, facing +x; spans z in [-7, 7].
        b.quad({{double(k), -1, -7}, {double(k), 1, -7}, {double(k), 1, 7}, {double(k), -1, 7}},
               "walls");
    }
    Scene s = b.scene;
    split_intersections(s);
    EXPECT_EQ(count_in(s, "floor"), 17u);
    EXPECT_NEAR(area_of(s, "floor"), 252.0, 1e-9);
    EXPECT_EQ(count_in(s, "walls"), 40u); // every wall cut once, by the floor
}

TEST(SplitIntersections, TexCoordsAreInterpolatedAlongTheCut) {
    Builder b;
    // uv = (x + 1) / 2, (z + 1) / 2 at the corners: linear in the position.
    const auto uv_of = [](const dvec3& x) { return glm::dvec2((x.x + 1) / 2, (x.z + 1) / 2); };
    const std::vector<dvec3> c{{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    std::vector<glm::dvec2> uv;
    for (const dvec3& x : c) uv.push_back(uv_of(x));
    b.quad(c, "a", 0, &uv);
    b.wall_z(-0.8, 0.8, -1, 1, 0.2, "b"); // cuts "a" at z = 0.2
    Scene s = b.scene;
    split_intersections(s);
    ASSERT_EQ(s.texcoords.size(), s.polygons.size());
    std::size_t checked = 0;
    for (std::size_t p = 0; p < s.polygons.size(); ++p) {
        const Polygon& P = s.polygons[p];
        if (s.groups[P.group] != "a") continue;
        for (int k = 0; k < P.count; ++k) {
            const glm::dvec2 want = uv_of(P.v[std::size_t(k)]);
            const glm::vec2 got = s.texcoords[p][std::size_t(k)];
            // Stored as float: 1e-6 of a unit range.
            EXPECT_NEAR(got.x, want.x, 1e-6) << "piece " << p << " corner " << k;
            EXPECT_NEAR(got.y, want.y, 1e-6) << "piece " << p << " corner " << k;
            ++checked;
        }
    }
    EXPECT_EQ(checked, 8u); // two quads
}

TEST(SplitIntersections, DeterministicAndStableWhenRunAgain) {
    Builder b;
    b.floor(-2, 2, -2, 2, 0, "floor");
    b.box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, "box");
    b.wall_z(-1.5, 1.5, -1, 1, 1.2, "wall");
    Scene first = b.scene, second = b.scene;
    split_intersections(first);
    split_intersections(second);
    EXPECT_EQ(first.content_hash(), second.content_hash());
    // The pieces meet only along their edges: nothing passes through anything any more.
    Scene again = first;
    const SplitStats st = split_intersections(again);
    EXPECT_EQ(st.polygons_cut, 0u);
    EXPECT_EQ(again.content_hash(), first.content_hash());
}

TEST_F(Files, LoadersCutByDefaultWithAWarningAndNotWhenOff) {
    write("m.mtl", kTwoQuadsMtl);
    const std::string obj = write("plus.obj", "mtllib m.mtl\nusemtl white\n"
                                              "v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\n"
                                              "v -0.8 -1 0\nv 0.8 -1 0\nv 0.8 1 0\nv -0.8 1 0\n"
                                              "g a\nf 1 2 3 4\ng b\nf 5 6 7 8\n");
    const Scene cut = load_obj(obj);
    EXPECT_EQ(cut.polygons.size(), 4u);
    bool warned = false;
    for (const std::string& w : cut.warnings)
        warned |= w.find("cut 2 polygon(s)") != std::string::npos;
    EXPECT_TRUE(warned) << "no warning about the cut";
    ObjOptions o;
    o.split_intersections = false;
    const Scene whole = load_obj(obj, o);
    EXPECT_EQ(whole.polygons.size(), 2u);
    EXPECT_NEAR(whole.total_area(), cut.total_area(), 1e-12);
    // Cut and then two-sided: every piece gets its twin.
    o.split_intersections = true;
    o.two_sided_surfaces = true;
    const Scene both = load_obj(obj, o);
    EXPECT_EQ(both.polygons.size(), 8u);
}

// --- plane cuts (solver/plane_cuts.h) ------------------------------------------------------

// A wall z = 0 (1 x 1, facing +z) and a plate floating in front of it at height 0.5, 0.3 to
// 0.7 from it, facing down: the plate's plane y = 0.5 cuts the wall through the middle.
TEST(PlaneCuts, APlateFloatingBesideAWallCutsItsMiddle) {
    Builder b;
    b.wall_z(0, 1, 0, 1, 0, "wall");
    b.quad({{0.3, 0.5, 0.3}, {0.7, 0.5, 0.3}, {0.7, 0.5, 0.7}, {0.3, 0.5, 0.7}}, "plate");
    ASSERT_LT(b.scene.polygons[1].normal.y, 0); // facing down
    const PlaneCuts cuts(b.scene, 1.0);
    EXPECT_EQ(cuts.polygons_cut(), 1u); // the wall; the wall's plane does not cut the plate
    const Polygon& wall = b.scene.polygons[0];
    // The whole wall: the plate is 0.3 from its centre, 0.4 x 0.4: share A / (pi d^2) with d
    // from the wall's centre (0.5, 0.5, 0) to the plate's (0.5, 0.5, 0.5).
    const double whole = cuts.cut_share(0, patch_geometry(wall, 0, 0));
    EXPECT_NEAR(whole, 0.16 / (std::numbers::pi * 0.25), 1e-9);
    // Its four quarters end at y = 0.5: none is cut (the plane only touches them).
    for (std::uint32_t i = 0; i < 4; ++i)
        EXPECT_EQ(cuts.cut_share(0, patch_geometry(wall, 1, i)), 0.0) << i;
    // The plate's plane does not cut the plate, nor does anything else.
    EXPECT_EQ(cuts.cut_share(1, patch_geometry(b.scene.polygons[1], 0, 0)), 0.0);
}

// Only polygons within reach (reach times the shooter's size) and in front of it count.
TEST(PlaneCuts, FarOrBehindPolygonsDoNotCut) {
    Builder b;
    b.wall_z(0, 1, 0, 1, 0, "wall");
    // The same plate 5 from the wall (beyond reach 1 x size 1), and one behind the wall.
    b.quad({{0.3, 0.5, 5.3}, {0.7, 0.5, 5.3}, {0.7, 0.5, 5.7}, {0.3, 0.5, 5.7}}, "far");
    b.quad({{0.3, 0.5, -0.7}, {0.7, 0.5, -0.7}, {0.7, 0.5, -0.3}, {0.3, 0.5, -0.3}}, "behind");
    const PlaneCuts cuts(b.scene, 1.0);
    EXPECT_EQ(cuts.cut_share(0, patch_geometry(b.scene.polygons[0], 0, 0)), 0.0);
    EXPECT_EQ(cuts.polygons_cut(), 0u);
}
