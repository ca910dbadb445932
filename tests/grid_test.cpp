// Calculation grids: spec parsing, points over a planar group, skipped points, statistics
// (luminance-weighted min/avg/max and U0), lux, and refusal of non-planar groups.
#include <gtest/gtest.h>

#include "hemirad/draw.h"
#include "hemirad/error.h"
#include "hemirad/grid.h"
#include "hemirad/hierarchy.h"

using namespace hemirad;

namespace {

// An L-shaped floor (three unit squares of a 2x2 block) and a wall, z = 0 and x = 0 planes.
Scene l_room() {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    s.groups = {"floor", "wall"};
    add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0, 0);
    add_polygon(s, {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}, 0, 0);
    add_polygon(s, {{0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, 0, 0);
    add_polygon(s, {{0, 0, 0}, {0, 2, 0}, {0, 2, 1}, {0, 0, 1}}, 0, 1);
    finish_scene(s, "l_room");
    return s;
}

// Sets every node's irradiance H of polygon p to f(centre of the node).
template <class F> void set_irradiance(Hierarchy& h, std::uint32_t p, F f) {
    const Polygon& poly = h.scene().polygons[p];
    for (std::uint32_t l = 0; l <= std::uint32_t(h.depth(p)); ++l)
        for (std::uint32_t i = 0; i < (1u << (2 * l)); ++i)
            h.node({p, l, i}).H = glm::vec3(f(patch_geometry(poly, l, i).centre));
}

} // namespace

TEST(Grid, ParsesSpecs) {
    GridSpec g = parse_grid_spec("floor:20x10");
    EXPECT_EQ(g.group, "floor");
    EXPECT_EQ(g.nx, 20);
    EXPECT_EQ(g.ny, 10);
    g = parse_grid_spec("desk:a:3\xc3\x97"
                        "4"); // U+00D7, group name with ':'
    EXPECT_EQ(g.group, "desk:a");
    EXPECT_EQ(g.nx, 3);
    EXPECT_EQ(g.ny, 4);
    for (const char* bad :
         {"floor", "floor:", ":3x3", "floor:3", "floor:0x3", "floor:3x-1", "floor:3x", "floor:x3",
          "floor:3y3", "floor:100000x1", "floor:5000x5000"})
        EXPECT_THROW(parse_grid_spec(bad), InputError) << bad;
}

TEST(Grid, UniformIrradianceGivesUniformityOne) {
    const Scene s = l_room();
    HierarchyOptions ho;
    ho.patch_size = 0.25;
    Hierarchy h(s, discretise(s, ho));
    for (std::uint32_t p = 0; p < 3; ++p)
        set_irradiance(h, p, [](dvec3) { return dvec3(2, 1, 4); });
    const GridResult r = evaluate_grid(h, {"floor", 4, 4});
    EXPECT_NEAR(r.width, 2, 1e-12);
    EXPECT_NEAR(r.height, 2, 1e-12);
    ASSERT_EQ(r.points.size(), 16u);
    // The missing square (x, y in [1, 2]) holds 4 of the 16 cell centres.
    EXPECT_EQ(r.skipped, 4);
    EXPECT_EQ(r.evaluated, 12);
    for (const GridPoint& p : r.points)
        EXPECT_EQ(p.on_surface, !(p.position.x > 1 && p.position.y > 1)) << p.position.x;
    const double Y = 0.2126 * 2 + 0.7152 * 1 + 0.0722 * 4;
    EXPECT_NEAR(r.Y_avg, Y, 1e-6);
    EXPECT_NEAR(r.Y_min, Y, 1e-6);
    EXPECT_NEAR(r.U0, 1.0, 1e-9);
    EXPECT_NEAR(r.E_avg.z, 4.0, 1e-6);
    const Json j = grid_json(r, true);
    const std::string text = j.dump();
    EXPECT_NE(text.find("\"lux\""), std::string::npos);
    const std::string csv = grids_csv({r}, true);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 17); // header + 16 points
    EXPECT_NE(csv.find(",,,,\n"), std::string::npos);        // a skipped point: empty values
}

TEST(Grid, LinearIrradianceStatistics) {
    const Scene s = l_room();
    HierarchyOptions ho;
    ho.patch_size = 1.0 / 64;
    ho.max_depth = 8;
    Hierarchy h(s, discretise(s, ho));
    // E grows linearly with x: bilinear interpolation of leaf centres reproduces it inside.
    for (std::uint32_t p = 0; p < 3; ++p)
        set_irradiance(h, p, [](dvec3 c) { return dvec3(1.0 + c.x); });
    const GridResult r = evaluate_grid(h, {"floor", 8, 8});
    // Points x = (i + 0.5)/4, i < 4 on all 8 rows, i >= 4 on the lower 4 rows only.
    double sum = 0;
    int count = 0;
    for (const GridPoint& p : r.points) {
        if (!p.on_surface) continue;
        EXPECT_NEAR(p.E.x, 1.0 + p.position.x, 1e-5);
        sum += 1.0 + p.position.x;
        ++count;
    }
    EXPECT_EQ(count, 48);
    EXPECT_NEAR(r.Y_avg, sum / count, 1e-5);
    EXPECT_NEAR(r.Y_min, 1.125, 1e-5);
    EXPECT_NEAR(r.Y_max, 2.875, 1e-5);
    EXPECT_NEAR(r.U0, r.Y_min / r.Y_avg, 1e-12);
    EXPECT_NEAR(r.min_over_max, r.Y_min / r.Y_max, 1e-12);
    const std::string line = grid_summary(r, false);
    EXPECT_NE(line.find("floor 8x8: Emin 1.125 W/unit²"), std::string::npos) << line;
    EXPECT_NE(line.find("Emin/Emax 0.391"), std::string::npos) << line;
    EXPECT_NE(grid_json(r, true).dump().find("\"Emin/Emax\": 0.39"), std::string::npos);

    // The plan: the L's missing quarter grey, the brightest cell viridis' top colour, a
    // luminaire over the grid marked in red.
    Luminaire l;
    l.name = "L1";
    l.position = {0.5, 0.5, 1};
    const Image8 img = grid_plan_image(r, false, {l});
    ASSERT_FALSE(img.empty());
    // A pixel near the top-left corner of cell (i, j): 2 x 2 units in 8 x 8 cells of 720 / 8
    // = 90 pixels, capped to 72, from (10, 34); row j = 0 at the bottom.
    const auto cell = [&](int i, int j) { return img.get(10 + i * 72 + 3, 34 + (7 - j) * 72 + 3); };
    EXPECT_EQ(cell(6, 6), (Rgb8{170, 170, 170}));                      // x, y in (1, 2): no polygon
    EXPECT_EQ(cell(7, 0), false_colour(1.0));                          // x = 1.9375: the maximum
    EXPECT_EQ(img.get(10 + 72 * 2, 34 + 72 * 6), (Rgb8{228, 26, 28})); // the cross at (0.5, 0.5)
}

TEST(Grid, RefusesUnknownAndNonPlanarGroups) {
    Scene s = l_room();
    s.polygons[3].group = 0; // the wall joins the floor group
    Hierarchy h(s, discretise(s, {}));
    try {
        evaluate_grid(h, {"floor", 2, 2});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("'floor'"), std::string::npos) << e.what();
    }
    EXPECT_THROW(evaluate_grid(h, {"ceiling", 2, 2}), InputError);
}

// A board's two faces modelled in two groups ("top" first, "bottom" after it), both picked
// two-sided: make_two_sided pairs them (each the other's back), so the bottom face's twin
// index is lower than its own. A grid on either group lies on that group's face: it used to
// take only polygons whose twin came after them, and found none in "bottom".
TEST(Grid, AGroupPairedWithABackInAnotherGroupKeepsItsPolygons) {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    s.groups = {"top", "bottom"};
    add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0, 0); // facing +z
    add_polygon(s, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, 0, 1); // facing -z
    ASSERT_EQ(make_two_sided(s, [](std::uint32_t) { return true; }), 0u);
    finish_scene(s, "board");
    ASSERT_EQ(s.polygons[1].twin, 0u);
    EXPECT_EQ(grid_polygons(s, {"top", 2, 2}), std::vector<std::uint32_t>{0});
    EXPECT_EQ(grid_polygons(s, {"bottom", 2, 2}), std::vector<std::uint32_t>{1});
}

TEST(Grid, UnlitGroupHasNoNaN) {
    const Scene s = l_room();
    Hierarchy h(s, discretise(s, {}));
    const GridResult r = evaluate_grid(h, {"wall", 3, 2});
    EXPECT_EQ(r.evaluated, 6);
    EXPECT_EQ(r.U0, 0.0);
    EXPECT_EQ(r.Y_avg, 0.0);
}

TEST(Grid, ManyTilesEachPointOnItsTile) {
    // A 2 x 1.5 floor of 40 x 30 tiles: every point lands on the tile that holds it.
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    s.groups = {"floor"};
    const int tx = 40, ty = 30;
    for (int j = 0; j < ty; ++j)
        for (int i = 0; i < tx; ++i) {
            const double x0 = 0.05 * i, y0 = 0.05 * j;
            add_polygon(
                s, {{x0, y0, 0}, {x0 + 0.05, y0, 0}, {x0 + 0.05, y0 + 0.05, 0}, {x0, y0 + 0.05, 0}},
                0, 0);
        }
    finish_scene(s, "tiles");
    Hierarchy h(s, discretise(s, {}));
    for (std::uint32_t p = 0; p < s.polygons.size(); ++p)
        set_irradiance(h, p, [p](dvec3) { return dvec3(1.0 + p); });
    const GridResult r = evaluate_grid(h, {"floor", 96, 88}); // no point on a tile edge
    EXPECT_EQ(r.evaluated, 96 * 88);
    for (const GridPoint& gp : r.points) {
        const int i = int(gp.position.x / 0.05), j = int(gp.position.y / 0.05);
        ASSERT_EQ(gp.polygon, std::uint32_t(j * tx + i)) << gp.position.x << " " << gp.position.y;
        ASSERT_NEAR(gp.E.x, 1.0 + gp.polygon, 1e-5);
    }
}

// Daylight factors (--daylight-factor): DF = 100 * 683 * Y / E_h over the evaluated points; a
// hand-made grid of five grey points with DF 0.5, 1, 2, 2.5, 4 % under E_h = 10000 lx (and one
// skipped point): avg 2, min 0.5, median 2, max 4, shares >= 1, 2, 3 %: 4/5, 3/5, 1/5.
TEST(Grid, DaylightFactorStatistics) {
    GridResult g;
    g.spec = {"floor", 3, 2};
    for (double df : {0.5, 1.0, 2.0, 2.5, 4.0}) {
        GridPoint p;
        p.on_surface = true;
        p.E = dvec3(df / 100 * 10000 / 683.0);
        g.points.push_back(p);
    }
    g.points.push_back(GridPoint{}); // skipped
    const std::vector<double> df = daylight_factors(g, 10000);
    ASSERT_EQ(df.size(), 5u);
    EXPECT_NEAR(df[2], 2.0, 1e-12);
    const std::string j = grid_json(g, false, 10000).dump();
    const auto value = [&](const std::string& key) { // the number after "key": in j's "DF"
        const auto at = j.find("\"" + key + "\": ", j.find("\"DF\""));
        return at == std::string::npos ? -1.0 : std::stod(j.substr(at + key.size() + 4));
    };
    const std::pair<const char*, double> expected[] = {
        {"avg", 2},          {"min", 0.5},        {"median", 2},      {"max", 4},
        {"share_ge_1", 0.8}, {"share_ge_2", 0.6}, {"share_ge_3", 0.2}};
    for (const auto& [key, v] : expected) EXPECT_NEAR(value(key), v, 1e-9) << key << " in " << j;
    EXPECT_EQ(grid_json(g, false).dump().find("DF"), std::string::npos); // only when asked
    const std::string line = grid_summary(g, false, 10000);
    EXPECT_NE(line.find("DF avg 2 %, min 0.5 %, median 2 %"), std::string::npos) << line;
    const std::string csv = grids_csv({g}, false, 10000);
    EXPECT_NE(csv.find("E_Y,DF\n"), std::string::npos) << csv;
    EXPECT_NE(csv.find(",,,,\n"), std::string::npos) << csv; // the skipped point
}
