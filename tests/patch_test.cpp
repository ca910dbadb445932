// Patch addressing: the quadtree over triangles and quads is consistent (children, parents,
// areas, point location, neighbours) — the same addressing the GPU's patch-ID texture uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "hemirad/patch.h"
#include "hemirad/scene.h"

using namespace hemirad;

namespace {

Polygon make(std::vector<dvec3> v) {
    Scene s;
    s.materials.push_back({"m", dvec3(0.5), dvec3(0.0)});
    s.groups.push_back("g");
    add_polygon(s, v, 0, 0);
    return s.polygons.at(0);
}

// A planar but non-parallelogram quad and a scalene triangle.
Polygon quad() {
    return make({{0, 0, 0}, {3, 0, 0}, {2.5, 2, 0}, {0.2, 1.5, 0}});
}
Polygon tri() {
    return make({{0, 0, 0}, {2, 0.3, 0}, {0.4, 1.7, 0}});
}

class PatchTreeTest : public ::testing::TestWithParam<bool> {
  protected:
    Polygon poly() const { return GetParam() ? tri() : quad(); }
};

TEST_P(PatchTreeTest, ChildrenAreDistinctAndTheirParentIsTheNode) {
    const bool t = GetParam();
    for (std::uint32_t level = 0; level < 5; ++level) {
        std::set<std::uint32_t> all;
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i)
            for (std::uint32_t c : patch_children(t, level, i)) {
                EXPECT_TRUE(patch_valid(level + 1, c));
                EXPECT_EQ(patch_parent(t, level + 1, c), i) << "level " << level << " node " << i;
                all.insert(c);
            }
        EXPECT_EQ(all.size(), std::size_t(1) << (2 * (level + 1))) << "children cover the level";
    }
}

TEST_P(PatchTreeTest, ChildAreasSumToParentAndLevelsToPolygon) {
    const Polygon p = poly();
    const bool t = GetParam();
    for (std::uint32_t level = 0; level < 4; ++level) {
        double level_sum = 0;
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) {
            const double a = patch_geometry(p, level, i).area;
            level_sum += a;
            double children = 0;
            for (std::uint32_t c : patch_children(t, level, i))
                children += patch_geometry(p, level + 1, c).area;
            EXPECT_NEAR(children, a, 1e-12 * p.area);
        }
        EXPECT_NEAR(level_sum, p.area, 1e-12 * p.area);
    }
}

// patch_area() is the area of the patch's corners (a planar polygon's shoelace sum, computed
// here), and the patches of a quad that is no parallelogram differ in area: a mean over them
// must weight them (the provider's near-receiver means).
TEST_P(PatchTreeTest, PatchAreaIsTheAreaOfItsCorners) {
    const Polygon p = poly();
    for (std::uint32_t level = 0; level < 4; ++level) {
        double smallest = 1e300, largest = 0;
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) {
            const PatchGeometry g = patch_geometry(p, level, i);
            dvec3 twice(0.0);
            for (int k = 0; k < g.count; ++k)
                twice += glm::cross(g.corners[std::size_t(k)],
                                    g.corners[std::size_t((k + 1) % g.count)]);
            const double a = patch_area(p, level, i);
            EXPECT_NEAR(a, 0.5 * glm::length(twice), 1e-12 * p.area) << level << "/" << i;
            EXPECT_EQ(a, g.area);
            smallest = std::min(smallest, a);
            largest = std::max(largest, a);
        }
        if (level > 0 && !GetParam()) EXPECT_GT(largest / smallest, 1.1) << "level " << level;
    }
}

// patch_centre() stands in for patch_geometry().centre where only the centre is needed (the
// provider's near test and visibility samples): it must give the very same point, or a node
// could be averaged or sampled at one place and linked at another.
TEST_P(PatchTreeTest, CentreAloneIsTheGeometrysCentre) {
    const Polygon p = poly();
    for (std::uint32_t level = 0; level < 6; ++level)
        for (std::uint32_t i = 0; i < (1u << (2 * level)); ++i) {
            const dvec3 c = patch_centre(p, level, i), g = patch_geometry(p, level, i).centre;
            ASSERT_EQ(c.x, g.x) << "level " << level << " index " << i;
            ASSERT_EQ(c.y, g.y) << "level " << level << " index " << i;
            ASSERT_EQ(c.z, g.z) << "level " << level << " index " << i;
        }
}

TEST_P(PatchTreeTest, PointLocationFindsThePatchOfItsCentre) {
    const Polygon p = poly();
    for (std::uint32_t level = 0; level < 5; ++level) {
        const std::uint32_t n = 1u << level;
        for (std::uint32_t i = 0; i < n * n; ++i) {
            // Parametric centre of the patch, from its geometry's corner parameters.
            double u, v;
            if (p.is_triangle()) {
                const std::uint32_t x = i % n, y = i / n;
                const bool inverted = x + y > n - 1;
                const double ci = inverted ? n - 1 - x : x, cj = inverted ? n - 1 - y : y;
                const double o = inverted ? 2.0 / 3.0 : 1.0 / 3.0;
                u = (ci + o) / n, v = (cj + o) / n;
            } else {
                u = (i % n + 0.5) / n, v = (i / n + 0.5) / n;
            }
            EXPECT_EQ(patch_at(p, level, u, v), i) << "level " << level;
            const dvec3 c = patch_geometry(p, level, i).centre;
            EXPECT_NEAR(glm::length(polygon_point(p, u, v) - c), 0.0, 1e-12);
        }
    }
}

TEST_P(PatchTreeTest, NeighboursAreSymmetricAndShareAnEdge) {
    const Polygon p = poly();
    const bool t = GetParam();
    const std::uint32_t level = 3;
    for (std::uint32_t i = 0; i < 64; ++i)
        for (std::uint32_t nb : patch_neighbours(t, level, i)) {
            if (nb == UINT32_MAX) continue;
            const auto back = patch_neighbours(t, level, nb);
            EXPECT_NE(std::find(back.begin(), back.end(), i), back.end()) << i << " " << nb;
            // Two shared corners.
            const PatchGeometry a = patch_geometry(p, level, i), b = patch_geometry(p, level, nb);
            int shared = 0;
            for (int x = 0; x < a.count; ++x)
                for (int y = 0; y < b.count; ++y)
                    shared += glm::length(a.corners[x] - b.corners[y]) < 1e-12;
            EXPECT_EQ(shared, 2) << i << " " << nb;
        }
}

INSTANTIATE_TEST_SUITE_P(TrianglesAndQuads, PatchTreeTest, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "triangle" : "quad"; });

TEST(PatchLayout, LevelOffsets) {
    EXPECT_EQ(level_offset(0), 0u);
    EXPECT_EQ(level_offset(1), 1u);
    EXPECT_EQ(level_offset(2), 5u);
    EXPECT_EQ(tree_size(2), 21u);
}

} // namespace
