// Reflectance textures (texture.h) and per-leaf reflectance (patch.h, hierarchy.h): decoding
// PNG and JPEG, sRGB to linear, the box mipmap against hand-computed means, a missing texture's
// warning and fallback, the leaf mean of a checkerboard against its analytic mean, and a 50 %
// grey texture solving like an untextured rho 0.5.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <stb_image_write.h>

#include "core/colour.h"
#include "hemirad/error.h"
#include "hemirad/export.h"
#include "hemirad/hierarchy.h"
#include "hemirad/scene_io.h"
#include "hemirad/solver.h"
#include "hemirad/texture.h"

using namespace hemirad;
namespace fs = std::filesystem;

namespace {

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    const auto* b = static_cast<const unsigned char*>(data);
    out->insert(out->end(), b, b + size);
}

/// An encoded image of w x h RGB bytes (row 0 the top) as PNG or JPEG (quality 100).
std::vector<unsigned char> encode(const std::vector<unsigned char>& rgb, int w, int h, bool jpeg) {
    std::vector<unsigned char> out;
    const int ok = jpeg ? stbi_write_jpg_to_func(append_bytes, &out, w, h, 3, rgb.data(), 100)
                        : stbi_write_png_to_func(append_bytes, &out, w, h, 3, rgb.data(), w * 3);
    EXPECT_NE(ok, 0);
    return out;
}

fs::path scratch(const std::string& name) {
    const fs::path dir =
        fs::temp_directory_path() / ("hemirad-texture-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

void write_bytes(const fs::path& p, const std::vector<unsigned char>& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream(p) << text;
}

} // namespace

TEST(Srgb, TransferFunctionAtKnownPoints) {
    EXPECT_EQ(srgb_decode(0.0), 0.0);
    EXPECT_NEAR(srgb_decode(1.0), 1.0, 1e-12);
    EXPECT_NEAR(srgb_decode(0.04045), 0.04045 / 12.92, 1e-12); // the linear segment's end
    EXPECT_NEAR(srgb_decode(0.5), 0.214041, 1e-6);             // ((0.5+0.055)/1.055)^2.4
    EXPECT_NEAR(srgb_decode(188 / 255.0), 0.5029, 1e-4);       // "50 %" grey in 8 bits
}

TEST(TextureDecode, PngTexelsAreSrgbDecodedInRowOrder) {
    // 2 x 2: top row (255, 0, 0), (0, 128, 0); bottom row (0, 0, 64), (10, 20, 30).
    const std::vector<unsigned char> rgb = {255, 0, 0, 0, 128, 0, 0, 0, 64, 10, 20, 30};
    const std::vector<unsigned char> png = encode(rgb, 2, 2, false);
    const Texture t = decode_texture("t.png", png.data(), png.size());
    ASSERT_EQ(t.width(), 2);
    ASSERT_EQ(t.height(), 2);
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(t.levels[0].texels[std::size_t(i)][c],
                        srgb_decode(rgb[std::size_t(3 * i + c)] / 255.0), 1e-6)
                << "texel " << i << " channel " << c;
    EXPECT_NEAR(t.max.r, 1.0, 1e-6);
    EXPECT_NEAR(t.fetch(0, {0.75, 0.25}).g, srgb_decode(128 / 255.0), 1e-6); // top right
    EXPECT_NEAR(t.fetch(0, {1.75, -0.25}).b, srgb_decode(30 / 255.0), 1e-6) << "repeat";
}

TEST(TextureDecode, JpegOfOneColourDecodesToThatColour) {
    // JPEG is lossy: a flat colour at quality 100 comes back within a couple of code values.
    constexpr unsigned char colour[3] = {200, 100, 50};
    std::vector<unsigned char> rgb(16 * 16 * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = colour[i % 3];
    const std::vector<unsigned char> jpg = encode(rgb, 16, 16, true);
    const Texture t = decode_texture("t.jpg", jpg.data(), jpg.size());
    ASSERT_EQ(t.width(), 16);
    const glm::dvec3 mean = t.mean();
    EXPECT_NEAR(mean.r, srgb_decode(200 / 255.0), 0.01);
    EXPECT_NEAR(mean.g, srgb_decode(100 / 255.0), 0.005);
    EXPECT_NEAR(mean.b, srgb_decode(50 / 255.0), 0.003);
}

TEST(TextureDecode, GarbageAndEmptyAreInputErrorsNamingTheFile) {
    const unsigned char junk[] = "not an image at all";
    try {
        decode_texture("junk.png", junk, sizeof junk);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("junk.png: cannot decode the image"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(decode_texture("empty.png", junk, 0), InputError);
    EXPECT_THROW(load_texture("/nonexistent/x.png"), InputError);
}

TEST(TextureMip, BoxFilterMatchesHandComputedMeans) {
    // 4 x 2 texels: level 1 is 2 x 1 (means of 2 x 2 blocks), level 2 is 1 x 1.
    std::vector<glm::vec3> v = {{0.f, 0, 0},  {0.4f, 0, 0}, {0.8f, 0, 0}, {0.2f, 0, 0},
                                {0.2f, 0, 0}, {0.6f, 0, 0}, {1.0f, 0, 0}, {0.6f, 0, 0}};
    const Texture t = make_texture("m", 4, 2, v);
    ASSERT_EQ(t.levels.size(), 3u);
    ASSERT_EQ(t.levels[1].width, 2);
    ASSERT_EQ(t.levels[1].height, 1);
    EXPECT_NEAR(t.levels[1].texels[0].r, (0 + 0.4 + 0.2 + 0.6) / 4, 1e-6);
    EXPECT_NEAR(t.levels[1].texels[1].r, (0.8 + 0.2 + 1.0 + 0.6) / 4, 1e-6);
    EXPECT_NEAR(t.levels[2].texels[0].r, 3.8 / 8, 1e-6);
    EXPECT_NEAR(t.mean().r, 3.8 / 8, 1e-6);
    EXPECT_EQ(t.level_for(0.5), 0);
    EXPECT_EQ(t.level_for(2.0), 1);
    EXPECT_EQ(t.level_for(3.9), 1);
    EXPECT_EQ(t.level_for(100.0), 2) << "clamped to the last level";
}

TEST(TextureObj, MapKdIsReadAndKdMultipliesIt) {
    const std::vector<unsigned char> rgb(2 * 2 * 3, 255);
    write_bytes(scratch("white.png"), encode(rgb, 2, 2, false));
    write_text(scratch("tex.mtl"), "newmtl a\nKd 0.5 0.25 0.5\nmap_Kd white.png\n"
                                   "newmtl b\nmap_Kd white.png\nKe 1 1 1\n");
    write_text(scratch("tex.obj"), "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                   "usemtl a\nf 1/1 2/2 3/3 4/4\nusemtl b\nf 4 3 2 1\n");
    const Scene s = load_obj(scratch("tex.obj").string());
    ASSERT_EQ(s.textures.size(), 1u) << "one file, read once";
    EXPECT_EQ(s.materials.at(0).texture, 0);
    EXPECT_EQ(s.materials.at(0).rho, dvec3(0.5, 0.25, 0.5));
    ASSERT_EQ(s.texcoords.size(), s.polygons.size());
    // vt (u, v) becomes (u, 1 - v): the image's top-left is (0, 0).
    EXPECT_EQ(s.texcoords[0][0], glm::vec2(0, 1));
    EXPECT_EQ(s.texcoords[0][2], glm::vec2(1, 0));
    EXPECT_NEAR(s.max_reflectance(), 0.98, 1e-12); // material b's copy, 0.98 x white
    // Material b: no Kd (the texture alone, as Kd 1 clamped), and its face has no vt: a copy
    // with rho times the texture's mean, untextured.
    const Material& b = s.material_of(s.polygons[1]);
    EXPECT_EQ(b.texture, -1);
    EXPECT_NEAR(b.rho.x, 0.98, 1e-6);
    bool warned = false;
    for (const std::string& w : s.warnings)
        warned |=
            w.find("without texture coordinates: Kd times the texture's mean") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(TextureObj, MissingTextureWarnsNamingTheMtlLineAndFallsBackToKd) {
    write_text(scratch("miss.mtl"), "newmtl a\nKd 0.3 0.4 0.5\nmap_Kd nowhere.png\n");
    write_text(scratch("miss.obj"), "mtllib miss.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\n"
                                    "vt 1 0\nvt 1 1\nusemtl a\nf 1/1 2/2 3/3\n");
    const Scene s = load_obj(scratch("miss.obj").string());
    EXPECT_EQ(s.materials.at(0).texture, -1);
    EXPECT_EQ(s.materials.at(0).rho, dvec3(0.3, 0.4, 0.5));
    EXPECT_EQ(s.texture_of(0), nullptr);
    bool warned = false;
    for (const std::string& w : s.warnings)
        warned |= w.find("miss.mtl:3: texture not read (") != std::string::npos &&
                  w.find("nowhere.png") != std::string::npos;
    EXPECT_TRUE(warned);
}

namespace {

/// A 1 x 1 plate (quad, or the triangle of its lower-left half) with a texture over [0,1]^2.
Scene plate(bool triangle, Texture texture, dvec3 rho) {
    Scene s;
    s.source = "plate";
    s.materials.push_back(Material{"plate", rho, dvec3(0.0)});
    s.materials[0].texture = 0;
    s.textures.push_back(std::move(texture));
    s.groups.push_back("plate");
    std::vector<dvec3> c = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<glm::dvec2> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    if (triangle) {
        c = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
        uv = {{0, 0}, {1, 0}, {0, 1}};
    }
    add_polygon(s, c, 0, 0, 1e-6, &uv);
    return s;
}

/// size x size texels, squares of `cell` texels alternating a and b (a at the top-left).
Texture checker(int size, int cell, glm::vec3 a, glm::vec3 b) {
    std::vector<glm::vec3> v;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) v.push_back(((x / cell + y / cell) % 2) ? b : a);
    return make_texture("checker", size, size, v);
}

} // namespace

TEST(LeafReflectance, CheckerboardLeafMeansAreTheAnalyticMeans) {
    const glm::vec3 a(0.8f, 0.6f, 0.4f), b(0.1f, 0.2f, 0.3f);
    const dvec3 kd(0.9, 0.5, 1.0);
    // 64 x 64 texels in squares of 8: a leaf of depth 2 (16 x 16 texels) holds 2 x 2 squares,
    // mean (a + b)/2; a leaf of depth 3 is one square, a or b exactly.
    const Scene s = plate(false, checker(64, 8, a, b), kd);
    for (std::uint32_t i = 0; i < 16; ++i) {
        const dvec3 r = patch_reflectance(s, 0, 2, i);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(r[c], kd[c] * (a[c] + b[c]) / 2, 1e-6) << "leaf " << i << " channel " << c;
    }
    for (std::uint32_t i = 0; i < 64; ++i) {
        const std::uint32_t x = i % 8, y = i / 8;
        const glm::vec3 expect = (x + y) % 2 ? b : a;
        EXPECT_NEAR(patch_reflectance(s, 0, 3, i).x, kd.x * expect.x, 1e-6) << "leaf " << i;
    }
    // The hierarchy holds the leaf values and their area-weighted means above.
    Discretisation d;
    d.depth = {3};
    const Hierarchy h(s, d);
    EXPECT_NEAR(h.reflectance({0, 3, 1}).x, kd.x * b.x, 1e-6);
    EXPECT_NEAR(h.reflectance({0, 0, 0}).y, kd.y * (a.y + b.y) / 2, 1e-6);
    // Triangle u + v <= 1 over 2 x 2 squares: a on a quarter of the square's area, b on two
    // halves of quarters: mean (a + b)/2; its midpoint sub-triangles never straddle a square.
    const Scene t = plate(true, checker(2, 1, a, b), dvec3(1.0));
    EXPECT_NEAR(patch_reflectance(t, 0, 0, 0).x, (a.x + b.x) / 2, 1e-6);
    // Level-1 patches of the triangle: the corner ones lie in one square each.
    EXPECT_NEAR(patch_reflectance(t, 0, 1, 0).x, a.x, 1e-6); // (0,0) corner: square a
    EXPECT_NEAR(patch_reflectance(t, 0, 1, 1).x, b.x, 1e-6); // (1,0) corner: square b
}

TEST(LeafReflectance, FineTextureIsBoxFilteredThroughItsMipmap) {
    // 256 x 256 texels of 1-texel checks on a depth-1 plate: a leaf spans 128 texels, sampled
    // 8 x 8 from the level of 16-texel texels, each the mean (a + b)/2.
    const glm::vec3 a(1.f), b(0.f);
    const Scene s = plate(false, checker(256, 1, a, b), dvec3(0.5));
    for (std::uint32_t i = 0; i < 4; ++i) EXPECT_NEAR(patch_reflectance(s, 0, 1, i).x, 0.25, 1e-6);
}

TEST(LeafReflectance, HalfGreyTextureSolvesLikeRhoOneHalf) {
    // Cube room, every face textured 50 % grey (rho 1 times texel 0.5) vs untextured rho 0.5:
    // the same solution within float rounding (the per-leaf reflectance is stored in float).
    BuiltinOptions bo;
    bo.rho = 0.5;
    bo.subdiv = 2;
    const Scene plain = make_builtin("cube", bo);
    Scene textured = plain;
    textured.textures.push_back(
        make_texture("grey", 4, 4, std::vector<glm::vec3>(16, glm::vec3(0.5f))));
    for (Material& m : textured.materials) {
        m.rho = dvec3(1.0);
        m.texture = 0;
    }
    textured.texcoords.assign(
        textured.polygons.size(),
        TexCoords{glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)});
    EXPECT_NEAR(textured.max_reflectance(), 0.5, 1e-12);
    SolverOptions o;
    o.ff = "reference";
    o.tolerance = 1e-3;
    o.hierarchy.max_depth = 2;
    o.hierarchy.patch_size = 1e-9;
    Solver a(plain, o), b(textured, o);
    while (a.step()) {}
    while (b.step()) {}
    EXPECT_EQ(a.shots(), b.shots());
    const Hierarchy &ha = a.solution(), &hb = b.solution();
    double worst = 0;
    for (std::uint32_t p = 0; p < plain.polygons.size(); ++p)
        for (std::uint32_t i = 0; i < 16; ++i) {
            const dvec3 ba = ha.radiosity({p, 2, i}), bb = hb.radiosity({p, 2, i});
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(bb[c] / ba[c] - 1));
        }
    EXPECT_LT(worst, 1e-5);
}

TEST(TexturedLightmap, QuadChartsHoldTexelTimesIrradiance) {
    // A depth-1 plate over a 16 x 16 checker of 4-texel squares, irradiance 1 everywhere: the
    // chart gets 8 texels per leaf side (one per texture texel, the most), each rho times its
    // texel, so both colours show (a leaf's mean alone would be their average).
    const glm::vec3 a(0.8f), b(0.2f);
    const Scene s = plate(false, checker(16, 4, a, b), dvec3(0.5));
    Discretisation d;
    d.depth = {1};
    Hierarchy h(s, d);
    h.receive({0, 0, 0}, dvec3(1.0));
    h.push_pull(0);
    const Lightmap lm = build_lightmap(h, 0, "plate");
    ASSERT_EQ(lm.charts.size(), 1u);
    const LightmapChart& c = lm.charts[0];
    ASSERT_EQ(c.n, 16);
    for (int j = 0; j < c.n; ++j)
        for (int i = 0; i < c.n; ++i) {
            // Chart texel (i, j) is parameter ((i + 0.5)/16, (j + 0.5)/16): texture texel (i, j).
            const float expect = 0.5f * (((i / 4 + j / 4) % 2) ? b.x : a.x);
            EXPECT_NEAR(lm.atlas.at(c.x0 + i, c.y0 + j)[0], expect, 1e-6) << i << ", " << j;
        }
}
