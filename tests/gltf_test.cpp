// glTF 2.0 input (scene_io.h, load_gltf): node transforms composed down the tree against
// hand-computed positions, .gltf and .glb of one scene load alike, materials (reflectance,
// emissive strength), cameras, groups; bad files give errors naming the file and the element.
// The files are written by tests/data/gltf/make_gltf.py.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "gltf_lights_scene.h"
#include "hemirad/error.h"
#include "hemirad/scene_io.h"

using namespace hemirad;

namespace {

std::string data(const std::string& name) {
    return std::string(HEMIRAD_TEST_DATA) + "/gltf/" + name;
}

void expect_near(const dvec3& a, const dvec3& b, const char* what) {
    EXPECT_LT(glm::length(a - b), 1e-6) << what << ": (" << a.x << ", " << a.y << ", " << a.z
                                        << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")";
}

std::string error_of(const std::string& file) {
    try {
        load_gltf(data(file));
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

bool has_warning(const Scene& s, const std::string& part) {
    for (const std::string& w : s.warnings)
        if (w.find(part) != std::string::npos) return true;
    return false;
}

} // namespace

TEST(Gltf, NodeTransformsComposeFromTheRootDown) {
    // Read raw: the three primitives hold one triangle each, which finishing the surfaces
    // (below) keeps once.
    ObjOptions raw;
    raw.finish_surfaces = false;
    const Scene s = load_gltf(data("nodes.gltf"), raw);
    // Three primitives (indices u8, u16, u32) of one triangle under root (T 1,2,3) > turned
    // (R z 90 degrees, S 2) > leaf (matrix: T 0,0,1); then three untransformed under "plain".
    ASSERT_EQ(s.polygons.size(), 6u);
    // p -> p + (0,0,1) -> 2p -> (x,y,z) to (-y,x,z) -> + (1,2,3):
    // (0,0,0) -> (1,2,5); (1,0,0) -> (1,4,5); (0,1,0) -> (-1,2,5).
    for (int k = 0; k < 3; ++k) {
        const Polygon& p = s.polygons[std::size_t(k)];
        ASSERT_EQ(p.count, 3);
        expect_near(p.v[0], {1, 2, 5}, "corner 0");
        expect_near(p.v[1], {1, 4, 5}, "corner 1");
        expect_near(p.v[2], {-1, 2, 5}, "corner 2");
        expect_near(p.normal, {0, 0, 1}, "normal");
        EXPECT_NEAR(p.area, 2.0, 1e-9); // scaled by 2: area 0.5 * 4
        EXPECT_EQ(s.groups[p.group], "leaf");
    }
    for (int k = 3; k < 6; ++k) {
        const Polygon& p = s.polygons[std::size_t(k)];
        expect_near(p.v[1], {1, 0, 0}, "untransformed corner");
        EXPECT_EQ(s.groups[p.group], "plain");
    }
    // Finished (as every loader returns a scene by default), a triangle that repeats another's
    // corners on the same side is dropped: one of each three stays, with a warning.
    const Scene finished = load_gltf(data("nodes.gltf"));
    ASSERT_EQ(finished.polygons.size(), 2u);
    EXPECT_EQ(finished.groups[finished.polygons[0].group], "leaf");
    EXPECT_EQ(finished.groups[finished.polygons[1].group], "plain");
    EXPECT_TRUE(has_warning(finished, "dropped 4 polygon(s) that repeat the corners"));
}

TEST(Gltf, GltfAndGlbOfTheSameSceneLoadIdentically) {
    const Scene a = load_gltf(data("nodes.gltf"));
    const Scene b = load_gltf(data("nodes.glb"));
    EXPECT_EQ(a.content_hash(), b.content_hash());
    ASSERT_EQ(a.cameras.size(), b.cameras.size());
    EXPECT_EQ(a.groups, b.groups);
    // And through the one dispatch by extension.
    EXPECT_EQ(load_scene(data("nodes.glb")).content_hash(), a.content_hash());
}

TEST(Gltf, MaterialsReflectanceAndEmissiveStrength) {
    ObjOptions raw; // the three primitives' one triangle each, all kept
    raw.finish_surfaces = false;
    const Scene s = load_gltf(data("nodes.gltf"), raw);
    const Material& grey = s.material_of(s.polygons[0]);
    EXPECT_EQ(grey.name, "grey");
    EXPECT_EQ(grey.rho, dvec3(0.5, 0.25, 0.125));
    EXPECT_EQ(grey.Ke, dvec3(0.0));
    const Material& glow = s.material_of(s.polygons[2]);
    EXPECT_EQ(glow.name, "glow");
    // emissiveFactor (0.5, 1, 0) x emissiveStrength 4: radiance; exitance pi times it.
    expect_near(glow.Ke, {2, 4, 0}, "Ke");
    EXPECT_NEAR(s.surface_power().y, std::acos(-1.0) * 4 * (2.0 + 0.5), 1e-9)
        << "two glowing triangles: areas 2 and 0.5";
}

TEST(Gltf, CamerasInTreeOrderTheFirstIsTheDefault) {
    const Scene s = load_gltf(data("nodes.gltf"));
    ASSERT_EQ(s.cameras.size(), 2u);
    const Camera& c = s.cameras[0];
    EXPECT_EQ(c.name, "first");
    // Under root > turned > leaf: eye at (1,2,3) + R S (0,0,1) = (1,2,5), looking down -z,
    // up = R (0,1,0) = (-1,0,0).
    expect_near(c.eye, {1, 2, 5}, "eye");
    expect_near(glm::normalize(c.target - c.eye), {0, 0, -1}, "view direction");
    expect_near(c.up, {-1, 0, 0}, "up");
    EXPECT_NEAR(c.fov_y_deg, 0.8 * 180 / std::acos(-1.0), 1e-9);
    expect_near(s.cameras[1].eye, {0, 0, 5}, "second eye");
}

TEST(Gltf, BadFilesAreErrorsNamingFileAndElement) {
    struct Case {
        const char* file;
        std::vector<std::string> parts;
    };
    const std::vector<Case> cases = {
        {"bad_accessor.gltf", {"bad_accessor.gltf", "accessor 0", "reaches outside buffer view 0"}},
        {"bad_index.gltf", {"bad_index.gltf", "mesh 0 primitive 0", "index 7", "accessor 1"}},
        {"cycle.gltf", {"cycle.gltf", "node 0 is its own ancestor"}},
        {"bad_mesh.gltf", {"bad_mesh.gltf", "node 4", "mesh 9", "does not exist"}},
        {"not_json.gltf", {"not_json.gltf", "cannot read the glTF file"}},
        {"missing_bin.gltf", {"missing_bin.gltf", "cannot read the glTF file", "missing.bin"}},
        {"no_such_file.glb", {"no_such_file.glb", "no such file"}},
    };
    for (const Case& c : cases) {
        const std::string e = error_of(c.file);
        for (const std::string& part : c.parts)
            EXPECT_NE(e.find(part), std::string::npos)
                << c.file << ": '" << part << "' not in: " << e;
    }
}

TEST(Gltf, UnsupportedModesAndMissingImagesAreWarnings) {
    ObjOptions raw; // (finished, the two instances' repeated triangles are kept once)
    raw.finish_surfaces = false;
    const Scene lines = load_gltf(data("lines.gltf"), raw);
    EXPECT_EQ(lines.polygons.size(), 4u) << "the lines primitive skipped (in both instances)";
    EXPECT_TRUE(has_warning(lines, "mesh 0 primitive 0: mode 1"));
    EXPECT_FALSE(has_warning(lines, "extensions not read")) << "emissive strength is read";
    EXPECT_FALSE(has_warning(load_gltf(data("lights.gltf")), "extensions not read"))
        << "KHR_lights_punctual is read (this file lists it and holds no light)";
    const Scene img = load_gltf(data("missing_image.gltf"));
    ASSERT_EQ(img.polygons.size(), 2u);
    EXPECT_EQ(img.materials.at(0).texture, -1);
    EXPECT_EQ(img.materials.at(0).rho, dvec3(0.5));
    EXPECT_EQ(img.materials.at(0).Ke, dvec3(1.0)) << "no extension: strength 1";
    EXPECT_TRUE(has_warning(img, "could not be read: its materials use baseColorFactor alone"));
}

TEST(Gltf, AssetRoomLoadsWithTextureCameraAndLight) {
    const Scene s = load_scene(std::string(HEMIRAD_SOURCE_DIR) + "/assets/gltf_room.gltf");
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].width(), 64);
    ASSERT_FALSE(s.cameras.empty());
    EXPECT_EQ(s.cameras[0].name, "door");
    expect_near(s.cameras[0].eye, {2.5, 2.2, 0.2}, "camera eye");
    // The 1 m^2 panel: exitance 1000 W/m^2 (emissiveStrength 1000/pi).
    EXPECT_NEAR(s.surface_power().x, 1000.0, 1e-6);
    // The root node scales the room by 0.5: 5 x 3 x 4 m.
    const Bounds b = s.bounds();
    expect_near(b.hi - b.lo, {5, 3, 4}, "room size");
    EXPECT_GE(s.find_group("block_a"), 0);
    EXPECT_GE(s.find_group("floor"), 0);
}

// KHR_lights_punctual: point and spot lights become luminaires at their nodes' world
// positions (the parent's transform composed), a spot aimed down its node's -z with the
// extension's cone; names from the light, else the node, else light<k>; colour scales by its
// luminance with a warning; the first directional light becomes the sun.
TEST(Gltf, PunctualLightsBecomeLuminaires) {
    const double rig[3] = {1, 0, -2};
    const std::string half_turn_x = "\"rotation\": [1, 0, 0, 0]"; // 180 degrees about x
    const std::string file = test::write_gltf_lights(
        std::filesystem::path(testing::TempDir()) / "gltf_lights", "lights", 2, rig,
        {{"{\"type\": \"point\", \"intensity\": 300, \"name\": \"bulb\"}",
          "\"name\": \"n0\", \"translation\": [-1, 2.5, 2]"},
         {"{\"type\": \"point\", \"intensity\": 100, \"color\": [1, 0.5, 0.25]}",
          "\"name\": \"n1\", \"translation\": [0, 1, 0]"},
         {"{\"type\": \"spot\", \"intensity\": 1000, \"spot\": {\"innerConeAngle\": 0.2, "
          "\"outerConeAngle\": 0.4}}",
          "\"translation\": [0, 3, 0], \"rotation\": [-0.7071067811865476, 0, 0, "
          "0.7071067811865476]"},
         {"{\"type\": \"directional\", \"intensity\": 5000, \"name\": \"sun\"}",
          "\"rotation\": [-0.3826834323650898, 0, 0, 0.9238795325112867]"},
         {"{\"type\": \"directional\", \"intensity\": 9, \"name\": \"moon\"}", half_turn_x}});
    const Scene s = load_gltf(file);
    ASSERT_EQ(s.luminaires.size(), 3u);
    const Luminaire& bulb = s.luminaires[0];
    EXPECT_EQ(bulb.name, "bulb");
    EXPECT_EQ(bulb.kind, "point");
    expect_near(bulb.position, {0, 2.5, 0}, "bulb: rig (1, 0, -2) + node (-1, 2.5, 2)");
    EXPECT_NEAR(bulb.intensity({0.6, -0.8, 0}), 300, 1e-12);
    EXPECT_NEAR(bulb.lumens(), 4 * std::numbers::pi * 300, 1e-9);
    EXPECT_EQ(s.luminaires[1].name, "n1");
    EXPECT_NEAR(s.luminaires[1].intensity({0, 1, 0}), 100 * (0.2126 + 0.7152 * 0.5 + 0.0722 * 0.25),
                1e-9);
    EXPECT_TRUE(has_warning(s, "light 1 ('n1'): color (1, 0.5, 0.25) is not modelled"));
    const Luminaire& spot = s.luminaires[2];
    EXPECT_EQ(spot.name, "light2");
    EXPECT_EQ(spot.kind, "spot");
    expect_near(spot.position, {1, 3, -2}, "spot");
    // -90 degrees about x turns -z into -y: straight down.
    expect_near(spot.aim, {0, -1, 0}, "spot aim");
    const double deg = 180 / std::numbers::pi;
    const auto towards = [](double gamma_deg) {
        const double g = gamma_deg / (180 / std::numbers::pi);
        return dvec3(std::sin(g), -std::cos(g), 0);
    };
    EXPECT_NEAR(spot.intensity(towards(0.1 * deg)), 1000, 1e-9); // inside the inner cone
    EXPECT_NEAR(spot.intensity(towards(0.2 * deg)), 1000, 1e-3); // its edge (acos rounding)
    EXPECT_EQ(spot.intensity(towards(0.41 * deg)), 0.0);         // beyond the outer
    // Between: (t)^2 with t linear in cos(gamma), within the tabulation's 0.05 %.
    const double t = (std::cos(0.3) - std::cos(0.4)) / (std::cos(0.2) - std::cos(0.4));
    EXPECT_NEAR(spot.intensity(towards(0.3 * deg)), 1000 * t * t, 0.5);
    // The first directional light is the sun: -45 degrees about x turns +z (towards the sun)
    // to (0, sin 45, cos 45): altitude 45 due south (+z); 5000 lux. The second is warned.
    ASSERT_TRUE(s.sun.has_value());
    expect_near(s.sun->direction, {0, std::sqrt(0.5), std::sqrt(0.5)}, "sun");
    EXPECT_NEAR(s.sun->altitude_deg, 45, 1e-9);
    EXPECT_NEAR(s.sun->azimuth_deg, 180, 1e-9);
    EXPECT_EQ(s.sun->illuminance, 5000);
    EXPECT_TRUE(has_warning(s, "light 4 ('moon'): a second directional light is ignored"));
    EXPECT_FALSE(has_warning(s, "extensions not read"));
}

TEST(Gltf, BadLightsAreErrorsNamingTheElement) {
    const double rig[3] = {0, 0, 0};
    const auto error_with = [&](const std::string& light, const std::string& name) {
        const std::string file =
            test::write_gltf_lights(std::filesystem::path(testing::TempDir()) / "gltf_bad_lights",
                                    name, 1, rig, {{light, "\"translation\": [0, 1, 0]"}});
        try {
            load_gltf(file);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_NE(error_with("{\"type\": \"point\", \"intensity\": -1}", "negative")
                  .find("negative.gltf: light 0 ('light0'): intensity -1 must be >= 0"),
              std::string::npos);
    EXPECT_NE(error_with("{\"type\": \"spot\", \"spot\": {\"innerConeAngle\": 0.5, "
                         "\"outerConeAngle\": 0.4}}",
                         "cone")
                  .find("cone.gltf: light 0 ('light0'): innerConeAngle 0.5 and outerConeAngle "
                        "0.4 must satisfy"),
              std::string::npos);
    EXPECT_NE(error_with("{\"type\": \"area\"}", "area").find("unknown type 'area'"),
              std::string::npos);
}
