// Scene loading: every bad input gets an InputError naming file, line and value; fixes are
// warned about; the built-in scenes hold what they promise.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"

using namespace hemirad;
namespace fs = std::filesystem;

namespace {

class ObjFiles : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("hemirad_loader_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string write(const std::string& name, const std::string& text) {
        const fs::path p = dir_ / name;
        std::ofstream(p) << text;
        return p.string();
    }
    // Expects an InputError whose message contains every one of `parts`.
    void expect_error(const std::string& path, std::initializer_list<std::string> parts) {
        try {
            load_obj(path);
            FAIL() << "no error for " << path;
        } catch (const InputError& e) {
            const std::string m = e.what();
            for (const std::string& part : parts)
                EXPECT_NE(m.find(part), std::string::npos) << "'" << part << "' not in: " << m;
        }
    }
    fs::path dir_;
};

const char* kMtl = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.2 0.2 0.2\nKe 1 1 1\n";
const char* kQuad = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng floor\nusemtl white\n"
                    "f 1 2 3 4\n";

TEST_F(ObjFiles, LoadsQuadWithMaterialAndGroup) {
    write("m.mtl", kMtl);
    const Scene s = load_obj(write("a.obj", kQuad));
    ASSERT_EQ(s.polygons.size(), 1u);
    EXPECT_EQ(s.polygons[0].count, 4);
    EXPECT_DOUBLE_EQ(s.polygons[0].area, 1.0);
    EXPECT_EQ(s.groups.at(s.polygons[0].group), "floor");
    EXPECT_EQ(s.materials.at(s.polygons[0].material).name, "white");
    // No emitter: a warning, not an error.
    ASSERT_FALSE(s.warnings.empty());
    EXPECT_NE(s.warnings.back().find("no surface emits"), std::string::npos);
}

TEST_F(ObjFiles, MissingFile) { expect_error((dir_ / "nope.obj").string(), {"nope.obj", "no such file"}); }

TEST_F(ObjFiles, UnparsableVertexNamesLine) {
    expect_error(write("a.obj", "v 0 0 0\nv 1 zero 0\n"), {"a.obj:2:", "'zero'"});
}

TEST_F(ObjFiles, NonFiniteCoordinateNamesLine) {
    expect_error(write("a.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n"), {"a.obj:3:", "nan"});
    expect_error(write("b.obj", "v inf 0 0\n"), {"b.obj:1:", "inf", "finite"});
}

TEST_F(ObjFiles, FaceIndexOutOfRange) {
    expect_error(write("a.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n"), {"a.obj:4:", "7"});
}

TEST_F(ObjFiles, UnknownStatement) {
    expect_error(write("a.obj", "v 0 0 0\nbogus 1 2\n"), {"a.obj:2:", "bogus"});
}

TEST_F(ObjFiles, ReflectanceOutOfRangeNamesMtlLine) {
    write("m.mtl", "newmtl white\nKd 0.5 1.0 0.5\n");
    expect_error(write("a.obj", kQuad), {"m.mtl:2:", "Kd 1.0", "white", "[0, 1)"});
    write("m.mtl", "newmtl white\nKd -0.1 0.5 0.5\n");
    expect_error(write("a.obj", kQuad), {"m.mtl:2:", "-0.1"});
}

TEST_F(ObjFiles, MissingMaterialLibrary) {
    expect_error(write("a.obj", kQuad), {"a.obj", "m.mtl", "not found"});
}

TEST_F(ObjFiles, EmptyScene) {
    expect_error(write("a.obj", "# nothing\nv 0 0 0\n"), {"a.obj", "no polygons"});
}

TEST_F(ObjFiles, DegeneratePolygonsDroppedWithCount) {
    write("m.mtl", kMtl);
    const Scene s = load_obj(write("a.obj", std::string(kQuad) +
                                                "f 1 1 2\nf 1 2 2 1\nv 2 0 0\nf 1 2 5\n"));
    EXPECT_EQ(s.polygons.size(), 1u);
    bool found = false;
    for (const std::string& w : s.warnings) found |= w.find("dropped 3 degenerate") != std::string::npos;
    EXPECT_TRUE(found);
}

TEST_F(ObjFiles, NonPlanarQuadIsSplitWithWarning) {
    write("m.mtl", kMtl);
    const Scene s = load_obj(write("a.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0.3\nv 0 1 0\n"
                                            "usemtl lamp\ng bent\nf 1 2 3 4\n"));
    ASSERT_EQ(s.polygons.size(), 2u);
    EXPECT_TRUE(s.polygons[0].is_triangle() && s.polygons[1].is_triangle());
    bool found = false;
    for (const std::string& w : s.warnings) found |= w.find("'bent'") != std::string::npos;
    EXPECT_TRUE(found);
    EXPECT_GT(s.emitted_power().x, 0.0);
}

TEST_F(ObjFiles, ConcaveQuadIsSplit) {
    write("m.mtl", kMtl);
    const Scene s = load_obj(
        write("a.obj", "mtllib m.mtl\nv 0 0 0\nv 2 0 0\nv 0.5 0.5 0\nv 0 2 0\nf 1 2 3 4\n"));
    ASSERT_EQ(s.polygons.size(), 2u);
    EXPECT_NEAR(s.total_area(), 1.0, 1e-12); // two triangles of area 0.5
}

TEST(Builtin, CornellLightPowerAndGroups) {
    const Scene s = make_builtin("cornell");
    EXPECT_EQ(s.groups.size(), 8u);
    EXPECT_GE(s.find_group("light"), 0);
    // Light: 130 x 105 mm with Ke (17, 12, 4): power pi * Ke * area.
    const double area = 130.0 * 105.0;
    const dvec3 p = s.emitted_power();
    EXPECT_NEAR(p.x, std::numbers::pi * 17 * area, 1e-6 * p.x);
    EXPECT_NEAR(p.z, std::numbers::pi * 4 * area, 1e-6 * p.z);
    // The non-planar left wall became two triangles.
    EXPECT_EQ(s.triangle_count(), 2u);
    // Every polygon faces the inside of the box, or away from a block's centre.
    const dvec3 inside(278, 274, 280);
    for (const Polygon& q : s.polygons) {
        if (s.groups[q.group].find("block") == std::string::npos) {
            EXPECT_GT(glm::dot(q.normal, inside - q.centroid()), 0) << s.groups[q.group];
        }
    }
}

TEST(Builtin, CubeFacesAndSubdivision) {
    BuiltinOptions o;
    o.subdiv = 13;
    const Scene s = make_builtin("cube", o);
    EXPECT_EQ(s.polygons.size(), 6u * 13 * 13);
    for (const char* g : {"x-", "x+", "y-", "y+", "z-", "z+"}) EXPECT_GE(s.find_group(g), 0) << g;
    EXPECT_NEAR(s.total_area(), 6.0, 1e-12);
    for (const Polygon& q : s.polygons) // inward
        EXPECT_GT(glm::dot(q.normal, dvec3(0.5) - q.centroid()), 0);
}

TEST(Builtin, FurnaceAndSphere) {
    const Scene f = make_builtin("furnace");
    EXPECT_NEAR(f.emitted_power().x, 6.0, 1e-12); // exitance 1 on 6 unit faces
    const Scene s = make_builtin("sphere");
    for (const Polygon& q : s.polygons) EXPECT_LT(glm::dot(q.normal, q.centroid()), 0); // inward
    EXPECT_GT(s.emitted_power().x, 0.0);
}

TEST(Builtin, BadOptionsAndNames) {
    BuiltinOptions o;
    o.rho = 1.0;
    EXPECT_THROW(make_builtin("cube", o), InputError);
    o.rho = 0.5;
    o.subdiv = 0;
    EXPECT_THROW(make_builtin("cube", o), InputError);
    EXPECT_THROW(make_builtin("teapot"), InputError);
    EXPECT_THROW(load_scene("no_such_file.obj"), InputError);
}

} // namespace
