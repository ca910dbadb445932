// Exports: the leaf mesh (vertex sharing, positions at the leaves' corners, area-weighted
// vertex radiosity), the PLY bytes, and lightmap atlases that read back exactly as the leaf
// radiosity, with borders that never bleed black.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "hemirad/export.h"
#include "hemirad/hierarchy.h"
#include "hemirad/image.h"

using namespace hemirad;

namespace {

Scene quad_and_triangle() {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5, 0.25, 0.75), dvec3(0.0)});
    s.materials.push_back({"lamp", dvec3(0.5), dvec3(1.0)});
    s.groups = {"floor", "lamp shade"};
    add_polygon(s, {{0, 0, 0}, {3, 0, 0}, {2.5, 2, 0}, {0.2, 1.5, 0}}, 0, 0); // quad
    add_polygon(s, {{0, 0, 1}, {0.4, 1.7, 1}, {2, 0.3, 1}}, 1, 1);            // triangle
    add_polygon(s, {{4, 0, 0}, {5, 0, 0}, {5, 1, 0}, {4, 1, 0}}, 0, 0);       // small quad
    finish_scene(s, "test");
    return s;
}

// H of every node = a function of the node's centre, so every leaf differs.
void fill(Hierarchy& h) {
    const Scene& s = h.scene();
    for (std::uint32_t p = 0; p < s.polygons.size(); ++p)
        for (std::uint32_t l = 0; l <= std::uint32_t(h.depth(p)); ++l)
            for (std::uint32_t i = 0; i < (1u << (2 * l)); ++i) {
                const dvec3 c = patch_geometry(s.polygons[p], l, i).centre;
                h.node({p, l, i}).H = glm::vec3(1.0 + c.x, 2.0 + c.y * c.x, 0.5 + i % 7);
            }
}

Hierarchy make_hierarchy(const Scene& s, double patch_size) {
    HierarchyOptions o;
    o.patch_size = patch_size;
    Hierarchy h(s, discretise(s, o));
    fill(h);
    return h;
}

} // namespace

TEST(Export, LeafMeshSharesVerticesWithinPolygons) {
    const Scene s = quad_and_triangle();
    const Hierarchy h = make_hierarchy(s, 0.4);
    const LeafMesh m = leaf_mesh(h);
    std::size_t vertices = 0, triangles = 0;
    for (std::uint32_t p = 0; p < s.polygons.size(); ++p) {
        const std::size_t n = std::size_t(1) << h.depth(p);
        vertices += s.polygons[p].is_triangle() ? (n + 1) * (n + 2) / 2 : (n + 1) * (n + 1);
        triangles += s.polygons[p].is_triangle() ? n * n : 2 * n * n;
    }
    EXPECT_EQ(m.positions.size(), vertices);
    EXPECT_EQ(m.radiosity.size(), vertices);
    EXPECT_EQ(m.triangles.size(), triangles);
    // Every face's corners are corners of a leaf, and every face faces the polygon's way.
    std::size_t t = 0;
    for (std::uint32_t p = 0; p < s.polygons.size(); ++p) {
        const std::uint32_t l = std::uint32_t(h.depth(p));
        for (std::uint32_t i = 0; i < (1u << (2 * l)); ++i) {
            const PatchGeometry g = patch_geometry(s.polygons[p], l, i);
            const int faces = g.count == 4 ? 2 : 1;
            for (int f = 0; f < faces; ++f, ++t) {
                const auto& tri = m.triangles[t];
                const glm::dvec3 a(m.positions[tri[0]]), b(m.positions[tri[1]]),
                    c(m.positions[tri[2]]);
                EXPECT_GT(glm::dot(glm::cross(b - a, c - a), s.polygons[p].normal), 0);
                for (std::uint32_t v : tri) {
                    double best = 1e300;
                    for (int k = 0; k < g.count; ++k)
                        best =
                            std::min(best, glm::length(glm::dvec3(m.positions[v]) - g.corners[k]));
                    EXPECT_LT(best, 1e-5) << "polygon " << p << " leaf " << i;
                }
            }
        }
    }
    // A corner vertex of a polygon touches one leaf: its value is that leaf's B.
    const dvec3 B0 = h.radiosity({0, std::uint32_t(h.depth(0)), 0});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m.radiosity[0][c], B0[c], 1e-5 * B0[c]);
}

TEST(Export, PlyHeaderAndSize) {
    const Scene s = quad_and_triangle();
    const Hierarchy h = make_hierarchy(s, 0.5);
    const LeafMesh m = leaf_mesh(h);
    const std::string ply = ply_bytes(m);
    const std::string header_end = "end_header\n";
    const auto end = ply.find(header_end);
    ASSERT_NE(end, std::string::npos);
    const std::string header = ply.substr(0, end + header_end.size());
    EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
    EXPECT_NE(header.find("element vertex " + std::to_string(m.positions.size()) + "\n"),
              std::string::npos);
    EXPECT_NE(header.find("property float red\nproperty float green\nproperty float blue\n"),
              std::string::npos);
    EXPECT_NE(header.find("element face " + std::to_string(m.triangles.size()) + "\n"),
              std::string::npos);
    EXPECT_EQ(ply.size(), header.size() + m.positions.size() * 24 + m.triangles.size() * 13);
    float red = 0;
    std::memcpy(&red, ply.data() + header.size() + 12, 4);
    EXPECT_EQ(red, m.radiosity[0].x);
}

TEST(Export, LightmapTexelsAreLeafRadiosityAndBordersAreDilated) {
    const Scene s = quad_and_triangle();
    const Hierarchy h = make_hierarchy(s, 0.3);
    const std::string dir = std::string(HEMIRAD_BINARY_DIR) + "/export_test_lightmaps";
    std::filesystem::remove_all(dir);
    // Leaf texels only (the detail at discontinuities is tested in cie171_gl_test).
    const std::vector<std::string> files = export_lightmaps(dir, h, /*discontinuities=*/false);
    EXPECT_EQ(files.size(), 6u);
    EXPECT_TRUE(std::filesystem::exists(dir + "/floor.exr"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/lamp_shade.obj"));
    for (const auto& e : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();

    const Lightmap lm = build_lightmap(h, 0, "floor");
    const ImageRGB back = read_exr(dir + "/floor.exr");
    ASSERT_EQ(back.width, lm.atlas.width);
    ASSERT_EQ(back.height, lm.atlas.height);
    ASSERT_EQ(lm.charts.size(), 2u);
    for (const LightmapChart& c : lm.charts) {
        const std::uint32_t l = std::uint32_t(h.depth(c.polygon));
        ASSERT_EQ(c.n, 1 << l);
        // Exact: texel (x0 + i, y0 + j) is the float radiosity of leaf (i, j).
        for (int j = 0; j < c.n; ++j)
            for (int i = 0; i < c.n; ++i) {
                const glm::vec3 B(h.radiosity({c.polygon, l, std::uint32_t(j * c.n + i)}));
                const float* px = back.at(c.x0 + i, c.y0 + j);
                ASSERT_EQ(px[0], B.x);
                ASSERT_EQ(px[1], B.y);
                ASSERT_EQ(px[2], B.z);
            }
        // The border repeats the edge texels (no black under bilinear filtering).
        for (int j = -kLightmapPadding; j < c.n + kLightmapPadding; ++j)
            for (int i = -kLightmapPadding; i < c.n + kLightmapPadding; ++i) {
                const int ci = std::clamp(i, 0, c.n - 1), cj = std::clamp(j, 0, c.n - 1);
                const float* px = back.at(c.x0 + i, c.y0 + j);
                EXPECT_EQ(px[1], back.at(c.x0 + ci, c.y0 + cj)[1]);
                EXPECT_GT(px[1], 0.f);
            }
    }
    // Charts' bordered boxes do not overlap.
    const LightmapChart& a = lm.charts[0];
    const LightmapChart& b = lm.charts[1];
    const bool apart = a.x0 + a.n + kLightmapPadding <= b.x0 - kLightmapPadding ||
                       b.x0 + b.n + kLightmapPadding <= a.x0 - kLightmapPadding ||
                       a.y0 + a.n + kLightmapPadding <= b.y0 - kLightmapPadding ||
                       b.y0 + b.n + kLightmapPadding <= a.y0 - kLightmapPadding;
    EXPECT_TRUE(apart);
    // OBJ: 7 corners, UVs at the chart corners (t flipped: row 0 is the top).
    std::istringstream obj(lm.obj);
    std::string line;
    std::vector<glm::dvec2> vt;
    while (std::getline(obj, line))
        if (line.rfind("vt ", 0) == 0) {
            std::istringstream ls(line.substr(3));
            glm::dvec2 t;
            ls >> t.x >> t.y;
            vt.push_back(t);
        }
    ASSERT_EQ(vt.size(), 8u);
    EXPECT_NEAR(vt[0].x * lm.atlas.width, lm.charts[0].x0, 1e-6);
    EXPECT_NEAR((1 - vt[0].y) * lm.atlas.height, lm.charts[0].y0, 1e-6);
    EXPECT_NEAR(vt[2].x * lm.atlas.width, lm.charts[0].x0 + lm.charts[0].n, 1e-6);

    // A triangle chart: texels inside the triangle average the cell's leaves; no zeros.
    const Lightmap tl = build_lightmap(h, 1, "lamp_shade");
    ASSERT_EQ(tl.charts.size(), 1u);
    const LightmapChart& c = tl.charts[0];
    for (int j = -kLightmapPadding; j < c.n + kLightmapPadding; ++j)
        for (int i = -kLightmapPadding; i < c.n + kLightmapPadding; ++i)
            EXPECT_GT(tl.atlas.at(c.x0 + i, c.y0 + j)[0], 0.f);
    const std::uint32_t l = std::uint32_t(h.depth(1));
    const glm::vec3 up(h.radiosity({1, l, 0}));
    const glm::vec3 inv(h.radiosity({1, l, std::uint32_t(c.n * c.n - 1)}));
    EXPECT_NEAR(tl.atlas.at(c.x0, c.y0)[2], 0.5f * (up.z + inv.z), 1e-5f * up.z);
    std::filesystem::remove_all(dir);
}
