// Visibility read from a hemicube's patch IDs (gpu/hemicube_visibility.h) on images made
// here by casting each pixel's centre ray into a few quads: no GL needed. The searches
// compare neighbours 64 pixels at a time, so the faces are wider than one block of 64.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <set>
#include <vector>

#include "gpu/hemicube.h"
#include "gpu/hemicube_visibility.h"
#include "gpu/pixel_runs.h"

using namespace hemirad;

namespace {

constexpr int kRes = 160; // faces 160 pixels wide: two blocks of 64 and a part block

// A square shooter at the origin facing +z: the top face looks up.
Shooter upward_shooter() {
    Shooter s;
    s.geometry.count = 4;
    s.geometry.corners = {dvec3(-0.01, -0.01, 0), dvec3(0.01, -0.01, 0), dvec3(0.01, 0.01, 0),
                          dvec3(-0.01, 0.01, 0)};
    s.geometry.area = 4e-4;
    s.normal = dvec3(0, 0, 1);
    return s;
}

// A horizontal rectangle at height z facing down (towards the eye below it).
void add_ceiling(Scene& scene, double x0, double x1, double y0, double y1, double z) {
    ASSERT_EQ(add_polygon(scene, {{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}}, 0, 0).added,
              1);
}

Scene scene_with_material() {
    Scene s;
    s.materials.push_back({"m", dvec3(0.5), dvec3(0.0)});
    s.groups.push_back("g");
    return s;
}

struct TopFace {
    gpu::HemicubeLayout layout = gpu::make_hemicube_layout(kRes);
    gpu::HemicubeFrame frame = gpu::hemicube_frame(upward_shooter());
    std::vector<float> rgba = std::vector<float>(
        4 * std::size_t(layout.width) * std::size_t(layout.height), 0.f); // nothing anywhere
    const gpu::HemicubeLayout::Face& face() const { return layout.faces[0]; }
    std::size_t at(int i, int j) const {
        return std::size_t(face().y + j) * std::size_t(layout.width) + std::size_t(face().x + i);
    }
    // Where pixel (i, j)'s centre ray meets the plane z = 1.
    dvec3 at_height_1(int i, int j) const {
        const dvec3 u = gpu::hemicube_direction(layout, frame, 0, i, j);
        return u / u.z;
    }
    void show(int i, int j, std::uint32_t polygon) { rgba[4 * at(i, j) + 2] = float(polygon + 1); }
    long shown(int i, int j) const { return long(rgba[4 * at(i, j) + 2]) - 1; }
    std::vector<float> ids() const {
        std::vector<float> out(rgba.size() / 4);
        for (std::size_t k = 0; k < out.size(); ++k) out[k] = rgba[4 * k + 2];
        return out;
    }
};

} // namespace

// The mask of unequal IDs is the plain comparison, for every length up to a block.
TEST(UnequalIds, MatchAPlainComparison) {
    std::uint64_t state = 99;
    std::vector<float> a(64), b(64);
    for (std::size_t n = 0; n <= 64; ++n) {
        for (std::size_t k = 0; k < 64; ++k) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            a[k] = float(state >> 62);        // 0..3
            b[k] = float((state >> 40) & 3u); // 0..3
        }
        std::uint64_t expected = 0;
        for (std::size_t k = 0; k < n; ++k)
            if (a[k] != b[k]) expected |= std::uint64_t(1) << k;
        EXPECT_EQ(gpu::unequal_ids(a.data(), b.data(), n), expected) << "n " << n;
    }
}

// A small quad under a large one: the large one's pixels beside the small one's are where
// it goes on behind it (marked); the small one's edge is a true silhouette (not marked).
TEST(OcclusionEdges, MarkThePixelsBesideANearerPolygon) {
    Scene scene = scene_with_material();
    add_ceiling(scene, -50, 50, -50, 50, 2);       // 0: far, covers the face
    add_ceiling(scene, -0.31, 0.27, -0.4, 0.2, 1); // 1: near, small
    TopFace top;
    for (int j = 0; j < top.face().h; ++j)
        for (int i = 0; i < top.face().w; ++i) {
            const dvec3 x = top.at_height_1(i, j);
            const bool in_near = x.x > -0.31 && x.x < 0.27 && x.y > -0.4 && x.y < 0.2;
            top.show(i, j, in_near ? 1u : 0u);
        }
    std::set<std::size_t> expected;
    std::size_t near_pixels = 0;
    for (int j = 0; j < top.face().h; ++j)
        for (int i = 0; i < top.face().w; ++i) {
            if (top.shown(i, j) == 1) {
                ++near_pixels;
                continue;
            }
            const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
            for (int k = 0; k < 4; ++k) {
                const int i2 = i + di[k], j2 = j + dj[k];
                if (i2 >= 0 && i2 < top.face().w && j2 >= 0 && j2 < top.face().h &&
                    top.shown(i2, j2) == 1)
                    expected.insert(top.at(i, j));
            }
        }
    ASSERT_GT(near_pixels, 100u);
    const std::vector<float> ids = top.ids();
    const gpu::HemicubeVisibility vis(scene, top.layout, top.frame, top.rgba.data(), dvec3(0.0),
                                      ids.data());
    std::set<std::size_t> marked;
    vis.occlusion_edges(0, [&](std::size_t i) { marked.insert(i); });
    EXPECT_EQ(marked, expected);
}

// Two coplanar quads meet along a line through the centres of one column of pixels, which
// shows the quad behind them (a crack, as rasterisation leaves along shared edges): each
// pixel of that column takes a neighbour's value; no other pixel changes.
TEST(FillCracks, ACrackAlongASharedEdgeIsFilled) {
    TopFace top;
    const int crack = 100; // in the second block of 64
    const double seam = top.at_height_1(crack, 0).x;
    const double left = top.at_height_1(crack - 1, 0).x; // the side of the pixels before it
    Scene scene = scene_with_material();
    add_ceiling(scene, -50, 50, -50, 50, 2); // 0: behind
    if (left < seam) {
        add_ceiling(scene, -50, seam, -50, 50, 1); // 1: the pixels before the crack
        add_ceiling(scene, seam, 50, -50, 50, 1);  // 2: after it
    } else {
        add_ceiling(scene, seam, 50, -50, 50, 1);
        add_ceiling(scene, -50, seam, -50, 50, 1);
    }
    for (int j = 0; j < top.face().h; ++j)
        for (int i = 0; i < top.face().w; ++i)
            top.show(i, j, i < crack ? 1u : i == crack ? 0u : 2u);
    const std::vector<float> before = top.rgba;
    std::vector<float> ids;
    const std::size_t filled =
        gpu::fill_cracks(scene, top.layout, top.frame, top.rgba.data(), dvec3(0.0), ids);
    EXPECT_EQ(filled, std::size_t(top.face().h));
    for (int j = 0; j < top.face().h; ++j)
        for (int i = 0; i < top.face().w; ++i) {
            const long p = top.shown(i, j);
            if (i == crack)
                EXPECT_TRUE(p == 1 || p == 2) << "row " << j << " shows " << p;
            else
                EXPECT_EQ(p, long(before[4 * top.at(i, j) + 2]) - 1) << i << ", " << j;
        }
    EXPECT_EQ(ids, top.ids()); // the IDs apart, after the filling
}

// A point on a polygon smaller than a pixel (linked whole where the depth map shows it seen),
// behind a panel whose edge passes a third of a pixel from the centre of the point's pixel:
// the pixel's centre ray passes beside the panel and shows nothing, the point's own ray
// crosses the panel. Hidden: the panel is shown in the pixels around. A point as far from
// the panel is seen.
TEST(VisibleInDepthMap, NothingBesideASilhouetteDoesNotSeeThroughIt) {
    TopFace top;
    const int column = 100, row = 80;
    const dvec3 centre_ray = top.at_height_1(column, row);
    const double step = top.at_height_1(column + 1, row).x - centre_ray.x; // a pixel at z = 1
    const double edge = centre_ray.x + 0.3 * step; // the panel: from here away from the centre
    Scene scene = scene_with_material();
    if (step > 0)
        add_ceiling(scene, edge, 50, -50, 50, 1); // 0: the panel
    else
        add_ceiling(scene, -50, edge, -50, 50, 1);
    // 1 and 2: small polygons at z = 2, around points whose rays cross z = 1 at 0.4 pixel
    // from the column's centre (0.1 pixel inside the panel) and ten pixels away from it.
    const dvec3 hidden = 2.0 * dvec3(centre_ray.x + 0.4 * step, centre_ray.y, 1);
    const dvec3 seen = 2.0 * dvec3(centre_ray.x - 10 * step, centre_ray.y, 1);
    const double r = 0.05 * std::abs(step);
    for (const dvec3& x : {hidden, seen}) add_ceiling(scene, x.x - r, x.x + r, x.y - r, x.y + r, 2);
    for (int j = 0; j < top.face().h; ++j)
        for (int i = 0; i < top.face().w; ++i) {
            const double x = top.at_height_1(i, j).x;
            if (step > 0 ? x > edge : x < edge) top.show(i, j, 0); // else nothing
        }
    ASSERT_EQ(top.shown(column, row), -1) << "the point's pixel shows nothing";
    ASSERT_EQ(top.shown(column + 1, row), 0) << "its neighbour shows the panel";
    const std::vector<float> ids = top.ids();
    const gpu::HemicubeVisibility vis(scene, top.layout, top.frame, top.rgba.data(), dvec3(0.0),
                                      ids.data());
    EXPECT_FALSE(vis.visible_in_depth_map(hidden, 1));
    EXPECT_TRUE(vis.visible_in_depth_map(seen, 2));
}
