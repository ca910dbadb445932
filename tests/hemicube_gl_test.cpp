// The GPU hemicube provider (paper 002) on llvmpipe: the accuracy bar on paper 000's cube,
// the shader's point-to-polygon values against Howell's closed forms, the patch-ID encoding
// round trip, the LOD clamp, and the hybrid clamp in an occluded configuration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "gpu/hemicube.h"
#include "hemirad/gl/context.h"
#include "hemirad/provider.h"
#include "hemirad/readout.h"
#include "hemirad/scene_io.h"

using namespace hemirad;

namespace {

// One context for the whole file (program code generation costs ~100 ms per program on
// llvmpipe). Failing to create it fails every test: no skipping.
gl::Context& context() {
    static std::unique_ptr<gl::Context> ctx = gl::Context::create();
    return *ctx;
}

std::unique_ptr<FormFactorProvider> gpu_provider(const std::string& mode, const Scene& scene,
                                                 const Discretisation& disc, int res, int angle = 0,
                                                 double bias = 0) {
    context();
    ProviderOptions o;
    o.gpu.resolution = res;
    o.gpu.use_current_context = true;
    o.gpu.builtin_acos = angle == 1;
    o.gpu.atan_angle = angle == 2;
    o.gpu.lod_bias = bias;
    return make_provider(mode, scene, disc, o);
}

Scene make_scene(const std::vector<std::vector<dvec3>>& polygons,
                 const std::vector<std::string>& groups) {
    Scene s;
    s.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    for (std::size_t i = 0; i < polygons.size(); ++i) {
        s.groups.push_back(groups[i]);
        add_polygon(s, polygons[i], 0, std::uint32_t(i));
    }
    finish_scene(s, "test");
    return s;
}

Shooter whole_polygon_shooter(const Scene& s, std::uint32_t p) {
    Shooter sh;
    sh.address = {p, 0, 0};
    sh.geometry = patch_geometry(s.polygons[p], 0, 0);
    sh.normal = s.polygons[p].normal;
    sh.unshot_power = 1;
    return sh;
}

// Each polygon one node.
Discretisation whole_polygons(const Scene& scene) {
    HierarchyOptions ho;
    ho.max_depth = 0;
    ho.patch_size = 1;
    return discretise(scene, ho);
}

// The hybrid links of one shot at resolution res, each polygon one node.
std::vector<Link> hybrid_links(const Scene& scene, const Shooter& shooter, int res) {
    const Discretisation disc = whole_polygons(scene);
    auto provider = gpu_provider("hybrid", scene, disc, res);
    std::vector<Link> links;
    provider->shoot(shooter, links);
    return links;
}

// A closed box [0, size] of six polygons facing in, group 0, the floor (y = 0) first; a scene
// with a grey material and the groups `groups` (the box's first).
Scene closed_box(const dvec3& size, const std::vector<std::string>& groups) {
    Scene scene;
    scene.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    scene.groups = groups;
    dvec3 c[8];
    for (int k = 0; k < 8; ++k)
        c[k] = dvec3(k & 1 ? size.x : 0, k & 2 ? size.y : 0, k & 4 ? size.z : 0);
    const int faces[6][4] = {{0, 1, 5, 4}, {0, 1, 3, 2}, {4, 5, 7, 6},
                             {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto& f : faces) { // each wound to face in
        std::vector<dvec3> v{c[f[0]], c[f[1]], c[f[2]], c[f[3]]};
        const dvec3 centroid = 0.25 * (v[0] + v[1] + v[2] + v[3]);
        if (glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), 0.5 * size - centroid) < 0)
            std::swap(v[1], v[3]);
        add_polygon(scene, v, 0, 0);
    }
    return scene;
}

// Adds quad v (material 0) wound so that its normal is `normal`.
void add_facing(Scene& scene, std::vector<dvec3> v, const dvec3& normal, std::uint32_t group) {
    if (glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), normal) < 0) std::swap(v[1], v[3]);
    add_polygon(scene, v, 0, group);
}

// A grey scene holding the box [-e, e] x [0, 1] x [-e, e] facing in, group 0, without its
// floor (y = 0), which the test lays in pieces; the groups `groups` (the box's first).
Scene box_without_floor(double e, const std::vector<std::string>& groups) {
    Scene scene;
    scene.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    scene.groups = groups;
    add_facing(scene, {{-e, 1, -e}, {e, 1, -e}, {e, 1, e}, {-e, 1, e}}, {0, -1, 0}, 0);
    add_facing(scene, {{-e, 0, -e}, {e, 0, -e}, {e, 1, -e}, {-e, 1, -e}}, {0, 0, 1}, 0);
    add_facing(scene, {{-e, 0, e}, {e, 0, e}, {e, 1, e}, {-e, 1, e}}, {0, 0, -1}, 0);
    add_facing(scene, {{-e, 0, -e}, {-e, 0, e}, {-e, 1, e}, {-e, 1, -e}}, {1, 0, 0}, 0);
    add_facing(scene, {{e, 0, -e}, {e, 0, e}, {e, 1, e}, {e, 1, -e}}, {-1, 0, 0}, 0);
    return scene;
}

// A shot's links' flux over the shooter's area: F(S -> j) for each (A_j F(j -> S) / A_S), or
// per watt for a cluster (area_s 1).
double link_share(const Scene& scene, const Link& l, double area_s) {
    const Polygon& q = scene.polygons[l.receiver.polygon];
    return double(l.ff) * patch_geometry(q, l.receiver.level, l.receiver.index).area / area_s;
}

// Polygon `shooter` of a finished scene shot whole (hybrid, 256^2): its row (the sum of
// F(S -> j)) and the part of it on the polygons that `counted` picks.
template <class Counted>
std::pair<double, double> whole_polygon_row(const Scene& scene, std::uint32_t shooter,
                                            Counted&& counted) {
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    std::vector<Link> links;
    gpu_provider("hybrid", scene, disc, 256)->shoot(whole_polygon_shooter(scene, shooter), links);
    double row = 0, part = 0;
    for (const Link& l : links) {
        const double f = link_share(scene, l, scene.polygons[shooter].area);
        row += f;
        if (counted(l.receiver.polygon)) part += f;
    }
    return {row, part};
}

// --- accuracy bar: paper 000's cube, 13 x 13 polygons per face ------------------------------
constexpr double kParallel = 0.199824895698; // Howell C-11 (1,1,1)
constexpr double kAdjacent = 0.200043776075; // Howell C-14 (1,1,1)

struct CubeCase {
    const char* mode;
    int depth;
    double bar; // relative, every face-to-face factor and the row sum (issue: 0.15 %, 0.05 %)
};

class CubeAccuracy : public ::testing::TestWithParam<CubeCase> {};

TEST_P(CubeAccuracy, FaceToFaceFormFactorsMeetTheBar) {
    const CubeCase c = GetParam();
    BuiltinOptions bo;
    bo.subdiv = 13;
    const Scene scene = make_builtin("cube", bo);
    HierarchyOptions ho;
    ho.max_depth = c.depth;
    ho.patch_size = 1e-9;
    const Discretisation disc = discretise(scene, ho);
    // 512: at 256, polygons seen edge-on near the shooter fall between pixel centres.
    auto provider = gpu_provider(c.mode, scene, disc, 512);
    const auto from = std::uint32_t(scene.find_group("y-"));
    const GroupFormFactors r = group_form_factors(scene, disc, *provider, from);
    for (const char* g : {"x-", "x+", "z-", "z+"})
        EXPECT_NEAR(r.to[scene.find_group(g)] / kAdjacent - 1, 0, c.bar) << g;
    EXPECT_NEAR(r.to[scene.find_group("y+")] / kParallel - 1, 0, c.bar) << "y+";
    EXPECT_NEAR(r.row_sum, 1.0, c.bar) << "row sum";
    // The analytic mode evaluates the same midpoint rule as the CPU reference (double
    // precision, exact visibility here): they must agree to float error, not just the bar.
    // (Measured: equal to 1e-7 at depth 0.) Hybrid averages the kernel over parts of the
    // receivers near the shooter instead (measured: +0.045 % at depth 0, +0.021 % at depth 1
    // against the closed forms, where the midpoint rule is -0.022 % and -0.006 %): the bar.
    if (std::string(c.mode) == "analytic") {
        auto reference = make_provider("reference", scene, disc, {});
        const GroupFormFactors ref = group_form_factors(scene, disc, *reference, from);
        for (std::size_t g = 0; g < r.to.size(); ++g)
            EXPECT_NEAR(r.to[g], ref.to[g], 2e-4 * ref.to[g] + 1e-9) << scene.groups[g];
    }
}

INSTANTIATE_TEST_SUITE_P(
    Paper000Cube, CubeAccuracy,
    // No occluder in the cube: hybrid differs from analytic only by its quadrature of near
    // receivers. Depth 1 is 676 hemicubes of 512: ~40 s here.
    ::testing::Values(CubeCase{"hybrid", 0, 0.0015}, CubeCase{"hybrid", 1, 0.0005},
                      CubeCase{"analytic", 0, 0.0015}),
    [](const auto& info) {
        return std::string(info.param.mode) + "_depth" + std::to_string(info.param.depth);
    });

// --- receivers as close to the shooter as they are large ------------------------------------
// The hybrid row of polygon 0 (the lamp, its own group) at resolution 256, each polygon one
// node.
double lamp_row(const Scene& scene) {
    const Discretisation disc = whole_polygons(scene);
    auto provider = gpu_provider("hybrid", scene, disc, 256);
    return group_form_factors(scene, disc, *provider, 0).row_sum;
}

// A 2 cm lamp 1 cm under a 50 cm panel of 5 cm polygons (a lamp in its housing, as in the
// office glb): the kernel F(x->S) peaks over the lamp within a width of about 2 cm, so the
// values at the panel polygons' centres alone read F(S->panel) = 3.54.
// Hybrid averages the kernel over parts of such receivers. Closed form: parallel rectangles
// (Hottel and Sarofim 1967; the corner sum of Ehlert and Smith 1993), 0.998645.
TEST(NearReceivers, LampUnderAPanelMatchesTheClosedForm) {
    std::vector<std::vector<dvec3>> polygons{
        {{0.015, 0.015, 0}, {0.035, 0.015, 0}, {0.035, 0.035, 0}, {0.015, 0.035, 0}}};
    std::vector<std::string> groups{"lamp"};
    const double w = 0.05, z = 0.01;
    for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 10; ++i) {
            const double x = -0.25 + i * w, y = -0.25 + j * w;
            polygons.push_back({{x, y, z}, {x, y + w, z}, {x + w, y + w, z}, {x + w, y, z}});
            groups.push_back("panel");
        }
    const double row = lamp_row(make_scene(polygons, groups));
    // Measured 0.998658 (+0.001 %; 0.998669 when the parts went by the distance to the lamp's
    // centre).
    EXPECT_NEAR(row, 0.998645, 0.002);
}

// F(A1 -> A2) between parallel rectangles in planes c apart, sides along the axes: A1 =
// [x1, x2] x [y1, y2], A2 = [u1, u2] x [v1, v2] (Hottel and Sarofim 1967; the corner sum of
// Ehlert and Smith 1993).
double parallel_rectangles(double x1, double x2, double y1, double y2, double u1, double u2,
                           double v1, double v2, double c) {
    const auto g = [c](double x, double y) {
        const double ry = std::sqrt(y * y + c * c), rx = std::sqrt(x * x + c * c);
        return x * ry * std::atan(x / ry) + y * rx * std::atan(y / rx) -
               0.5 * c * c * std::log(x * x + y * y + c * c);
    };
    const double xs[2] = {x1, x2}, ys[2] = {y1, y2}, us[2] = {u1, u2}, vs[2] = {v1, v2};
    double sum = 0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k)
                for (int l = 0; l < 2; ++l)
                    sum += ((i + j + k + l) % 2 ? -1.0 : 1.0) * g(us[k] - xs[i], vs[l] - ys[j]);
    return sum / (2 * M_PI * (x2 - x1) * (y2 - y1));
}

// A strip 3.6 mm x 12.3 cm 3.3 mm in front of a panel 14.5 mm x 21.4 mm cut along its diagonal
// into two slivers (the office glb's LED bar face, whose nodes are such slivers, across a gap
// from a strip of the PC's case). The strip's kernel varies over the gap's width; a part of a
// sliver was split while the square root of its area exceeded the gap, so that parts 27 mm
// long stood for the kernel at their centres (in the office, nodes 2-14 % high and rows up to
// 1.044; here the row read 0.8937 against the closed form 0.9060, 1.4 % low). Split while half
// its longest edge exceeds the gap: 0.9030 (-0.33 %). The bar is 0.5 %.
TEST(NearReceivers, SliversAcrossAGapFromAStripMatchTheClosedForm) {
    EXPECT_NEAR(parallel_rectangles(0.015, 0.035, 0.015, 0.035, -0.25, 0.25, -0.25, 0.25, 0.01),
                0.998645, 1e-5); // the formula, against the lamp under a panel above
    const double w = 0.0036, l = 0.123, gap = 0.0033;
    const double u0 = -0.0055, u1 = 0.009, v0 = -0.045, v1 = 0.169; // the panel
    const std::vector<dvec3> strip{{0, 0, 0}, {w, 0, 0}, {w, l, 0}, {0, l, 0}};
    const std::vector<dvec3> sliver_a{{u0, v0, gap}, {u1, v1, gap}, {u1, v0, gap}};
    const std::vector<dvec3> sliver_b{{u0, v0, gap}, {u0, v1, gap}, {u1, v1, gap}};
    const Scene scene = make_scene({strip, sliver_a, sliver_b}, {"lamp", "panel", "panel"});
    ASSERT_NEAR(scene.polygons[0].normal.z, 1.0, 1e-12);
    ASSERT_NEAR(scene.polygons[1].normal.z, -1.0, 1e-12);
    ASSERT_NEAR(scene.polygons[2].normal.z, -1.0, 1e-12);
    const double expected = parallel_rectangles(0, w, 0, l, u0, u1, v0, v1, gap);
    const double row = lamp_row(scene);
    std::printf("strip across a gap from slivers: row %.5f, closed form %.5f\n", row, expected);
    EXPECT_NEAR(row / expected - 1, 0, 0.005);
}

// --- a receiver that meets the shooter's edge -------------------------------------------------
// Perpendicular rectangles with a common edge (Howell C-14), l along the edge, w and h across
// it: F(1 -> 2) from the w side to the h side.
double perpendicular_with_common_edge(double l, double w, double h) {
    const double W = w / l, H = h / l, WH = W * W + H * H;
    const double a = (1 + W * W) * (1 + H * H) / (1 + WH);
    const double b = W * W * (1 + WH) / ((1 + W * W) * WH);
    const double c = H * H * (1 + WH) / ((1 + H * H) * WH);
    return (W * std::atan(1 / W) + H * std::atan(1 / H) -
            std::sqrt(WH) * std::atan(1 / std::sqrt(WH)) +
            0.25 * (std::log(a) + W * W * std::log(b) + H * H * std::log(c))) /
           (M_PI * W);
}

// A lamp 3 mm wide and 50 cm long against a 20 cm housing wall of 5 cm polygons that meets its
// edge (the office glb's LED bars against the PC's case): the kernel peaks logarithmically
// along the common edge, where the wall's polygons touch the lamp, and the polygons are seen
// edge-on from the lamp's centre (the far ones on no pixel). Measured: -46.8 % when the
// polygons were averaged over parts by their distance to the lamp's centre and those on no
// pixel took the kernel at their centre; -2.8 % with the parts split by their distance to the
// lamp. What is left is the midpoint rule on the parts one to eight of their sizes from the
// lamp below the third level (-0.3 % when those are split too, at four times the work).
TEST(NearReceivers, StripAgainstAWallAcrossItsEdgeMatchesTheClosedForm) {
    EXPECT_NEAR(perpendicular_with_common_edge(1, 1, 1), kAdjacent, 1e-12); // the formula
    const double l = 0.5, w = 0.003, h = 0.2, side = 0.05;
    std::vector<std::vector<dvec3>> polygons{{{0, -w, 0}, {l, -w, 0}, {l, 0, 0}, {0, 0, 0}}};
    std::vector<std::string> groups{"lamp"};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 10; ++i) {
            const double x = i * side, z = j * side; // in y = 0, facing -y (the lamp's side)
            polygons.push_back(
                {{x, 0, z}, {x + side, 0, z}, {x + side, 0, z + side}, {x, 0, z + side}});
            groups.push_back("wall");
        }
    const Scene scene = make_scene(polygons, groups);
    ASSERT_NEAR(scene.polygons[1].normal.y, -1.0, 1e-12);
    // The lamp sees nothing but the wall: its row is F(lamp -> wall).
    const double expected = perpendicular_with_common_edge(l, w, h); // 0.491787
    EXPECT_NEAR(lamp_row(scene) / expected - 1, 0, 0.04);
}

// A strip 0.8 mm wide and 21 cm long, standing on its edge 0.8 mm above a floor 8 cm wide
// that runs along it (a quarter of the office glb's LED bar, 3.3 mm high, over the PC case
// it stands on). The kernel falls from 0.5 to 0.1 within 2 mm of the strip's foot, where the
// floor's parts were taken at their centres once they were six levels down (2 mm across):
// +5.6 % on the office's node, +6.5 % here. Split on while wider than the strip: -0.8 %.
// Closed form: the strip as the difference of two walls with a common edge (Howell C-14).
TEST(NearReceivers, FloorUnderANarrowStripAcrossAGapMatchesTheClosedForm) {
    const double w = 0.0008, g = 0.0008, l = 0.21, W = 0.08;
    const std::vector<dvec3> strip{{0, g, 0}, {l, g, 0}, {l, g + w, 0}, {0, g + w, 0}};
    const std::vector<dvec3> floor{{0, 0, 0}, {0, 0, W}, {l, 0, W}, {l, 0, 0}};
    const Scene scene = make_scene({strip, floor}, {"lamp", "floor"});
    ASSERT_NEAR(scene.polygons[0].normal.z, 1.0, 1e-12);
    ASSERT_NEAR(scene.polygons[1].normal.y, 1.0, 1e-12);
    const double expected = ((g + w) * perpendicular_with_common_edge(l, g + w, W) -
                             g * perpendicular_with_common_edge(l, g, W)) /
                            w;
    const double row = lamp_row(scene);
    std::printf("narrow strip over a floor: row %.5f, closed form %.5f\n", row, expected);
    EXPECT_NEAR(row / expected - 1, 0, 0.01);
}

// A lamp 3 mm wide and 50 cm long 2.5 mm in front of a wall, beside a trapezoid of it whose
// short side runs along the lamp (the office glb's LED bars and their backing, cut by the
// meeting lines into such pieces). The kernel's mean over the trapezoid: its parts are of
// unequal area, the small ones nearest the lamp where the kernel is largest. Against the
// kernel integrated over the trapezoid here (a graded 400 x 120 product rule in its bilinear
// parameters, with their Jacobian): +18.2 % when the parts were averaged with equal weights,
// -0.12 % weighted by their areas.
TEST(NearReceivers, TrapezoidBesideALampMatchesItsIntegral) {
    const double l = 0.5, w = 0.003, gap = 0.0025;
    const std::vector<dvec3> lamp{{0, 0, -gap - w}, {0, l, -gap - w}, {0, l, -gap}, {0, 0, -gap}};
    // In z = 0 facing -z (the lamp's side); the side at x = 0 is 0.3, the one at x = 0.05 0.5.
    const std::vector<dvec3> trapezoid{{0, 0.1, 0}, {0, 0.4, 0}, {0.05, 0.5, 0}, {0.05, 0, 0}};
    const Scene scene = make_scene({lamp, trapezoid}, {"lamp", "wall"});
    const Polygon& q = scene.polygons[1];
    ASSERT_NEAR(q.normal.z, -1.0, 1e-12);
    ASSERT_NEAR(scene.polygons[0].normal.x, 1.0, 1e-12);
    // F(lamp -> wall) = (1 / A_lamp) integral over the wall of F(x -> lamp) dA.
    const auto graded = [](int n, int k, double& weight) { // cosine-spaced, dense at both ends
        const double t = M_PI * (k + 0.5) / n;
        weight = 0.5 * M_PI / n * std::sin(t);
        return 0.5 * (1 - std::cos(t));
    };
    double integral = 0;
    for (int i = 0; i < 400; ++i)
        for (int j = 0; j < 120; ++j) {
            double wu, wv;
            const double u = graded(400, i, wu), v = graded(120, j, wv);
            const dvec3 du = (1 - v) * (q.v[1] - q.v[0]) + v * (q.v[2] - q.v[3]);
            const dvec3 dv = (1 - u) * (q.v[3] - q.v[0]) + u * (q.v[2] - q.v[1]);
            const dvec3 x = polygon_point(q, u, v);
            integral += point_to_polygon_ff(x, q.normal, scene.polygons[0].v.data(), 4) *
                        glm::length(glm::cross(du, dv)) * wu * wv;
        }
    const double expected = integral / scene.polygons[0].area;
    EXPECT_NEAR(lamp_row(scene) / expected - 1, 0, 0.01) << "expected " << expected;
}

// A board 20 cm wide 1 cm in front of a 1 m wall whose unshot light is all on its other half
// (a whiteboard on a wall half in its shadow, as in the office glb): the board sees the dark
// wall in front of it, and only grazing light from the lit half. Its factor is the kernel of
// the lit half, twice the wall's mean radiosity, averaged over the board (a 40 x 40 midpoint
// rule here): 0.00078; with the wall's mean it reads 0.999.
TEST(NearReceivers, BoardBeforeTheDarkHalfOfAWallSeesTheDarkness) {
    const std::vector<dvec3> wall{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const double z = 0.01, x0 = 0.65, x1 = 0.85, y0 = 0.4, y1 = 0.6;
    const std::vector<dvec3> board{{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}};
    const Scene scene = make_scene({wall, board}, {"wall", "board"});
    const Polygon &w = scene.polygons[0], &b = scene.polygons[1];
    ASSERT_NEAR(w.normal.z, 1.0, 1e-12);
    ASSERT_NEAR(b.normal.z, -1.0, 1e-12);
    Shooter sh = whole_polygon_shooter(scene, 0);
    sh.emission_levels = 1;
    std::vector<PatchGeometry> lit;
    for (std::uint32_t c : patch_children(false, 0, 0)) {
        const PatchGeometry g = patch_geometry(w, 1, c);
        sh.emission.push_back(g.centre.x < 0.5 ? 2.0f : 0.0f);
        if (g.centre.x < 0.5) lit.push_back(g);
    }
    ASSERT_EQ(lit.size(), 2u);
    double expected = 0, even = 0;
    const int n = 40;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const dvec3 x(x0 + (x1 - x0) * (i + 0.5) / n, y0 + (y1 - y0) * (j + 0.5) / n, z);
            for (const PatchGeometry& g : lit)
                expected += 2 * point_to_polygon_ff(x, b.normal, g.corners.data(), g.count);
            even += point_to_polygon_ff(x, b.normal, w.v.data(), 4);
        }
    expected /= n * n;
    even /= n * n;
    ASSERT_GT(even, 10 * expected); // the case means something
    double ff = -1;
    for (const Link& l : hybrid_links(scene, sh, 256))
        if (l.receiver.polygon == 1) ff = l.ff;
    ASSERT_GE(ff, 0) << "the board is not linked";
    EXPECT_NEAR(ff / expected - 1, 0, 0.03) << "expected " << expected << ", even " << even;
}

// The floor of a closed box shoots, its unshot light all on one quarter, under a panel 2 cm
// above that quarter (a desk's side panel whose lit part faces a PC case 34 cm away, in the
// office glb). The panel takes the lit quarter's kernel; what it takes more than the floor's
// mean would give it, the rest of the box, which the panel hides from the lit quarter, does
// not get: every part of the floor sends all its light into the box once, so the row sums to
// 1. With the rest of the box taking the mean's shares, it summed to 1.68. The bar is 0.1 % (the
// solver's row-sum bar, 1.001) above and 3 % below: the centre's visibility, the pixels'
// share of partial nodes.
TEST(NearReceivers, AnUnevenFloorUnderAPanelSendsItsLightOnce) {
    Scene scene = closed_box(dvec3(1.0), {"box", "panel"});
    const double y = 0.02;
    std::vector<dvec3> panel{{0, y, 0}, {0.5, y, 0}, {0.5, y, 0.5}, {0, y, 0.5}};
    if (glm::cross(panel[1] - panel[0], panel[2] - panel[0]).y > 0) std::swap(panel[1], panel[3]);
    add_polygon(scene, panel, 0, 1);
    finish_scene(scene, "test");
    const Polygon& floor = scene.polygons[0];
    ASSERT_NEAR(floor.normal.y, 1.0, 1e-12);
    ASSERT_NEAR(scene.polygons[6].normal.y, -1.0, 1e-12);
    Shooter sh = whole_polygon_shooter(scene, 0);
    sh.emission_levels = 1;
    int lit = 0;
    for (std::uint32_t k : patch_children(false, 0, 0)) {
        const PatchGeometry g = patch_geometry(floor, 1, k);
        const bool under = g.centre.x < 0.5 && g.centre.z < 0.5;
        sh.emission.push_back(under ? 4.0f : 0.0f);
        lit += under;
    }
    ASSERT_EQ(lit, 1);
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    std::vector<Link> links;
    gpu_provider("hybrid", scene, disc, 256)->shoot(sh, links);
    double row = 0, on_panel = 0;
    for (const Link& l : links) {
        row += link_share(scene, l, floor.area);
        if (l.receiver.polygon == 6) on_panel += link_share(scene, l, floor.area);
    }
    std::printf("uneven floor under a panel: row %.5f, on the panel %.5f\n", row, on_panel);
    EXPECT_GT(on_panel, 0.5) << "the panel takes most of the lit quarter's light";
    EXPECT_LE(row, 1.001);
    EXPECT_GE(row, 0.97);
}

// --- the shader's analytic value against Howell's closed forms -----------------------------
double b3(double a, double b, double c) { // element parallel to a x b at c, normal through a corner
    const double X = a / c, Y = b / c;
    return (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
            Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
           (2 * M_PI);
}
double b4(double L, double d, double H) { // element at origin, normal +z; L x H plate in y = d
    return (std::atan(L / d) -
            d / std::sqrt(H * H + d * d) * std::atan(L / std::sqrt(H * H + d * d))) /
           (2 * M_PI);
}

struct KernelCase {
    const char* name;
    std::vector<dvec3> shooter; // facing the receiver at the origin (normal +z)
    double expected;
};

class ShaderKernel : public ::testing::TestWithParam<KernelCase> {};

TEST_P(ShaderKernel, AnalyticValueMatchesClosedForm) {
    const KernelCase& k = GetParam();
    // Receiver: a square centred at the origin, facing +z, large enough to cover pixels; at
    // depth 0 its analytic value is taken at its centre, the origin, whatever its size.
    const double e = 0.05;
    const Scene scene = make_scene({{{-e, -e, 0}, {e, -e, 0}, {e, e, 0}, {-e, e, 0}}, k.shooter},
                                   {"receiver", "shooter"});
    ASSERT_GT(glm::dot(scene.polygons[1].normal, dvec3(0) - scene.polygons[1].centroid()), 0)
        << "test setup: the shooter must face the receiver";
    const Discretisation disc = discretise(scene, {0, 0});
    // Tolerances, relative. The table, indexed by the chord, is the most precise (measured
    // 1.9e-7 at worst): 1e-6. llvmpipe's atan reaches 2e-5 (3e-5); its acos is a polynomial
    // good to about 2e-4 (3e-4; on a GPU it is better).
    const char* names[3] = {"table", "acos", "atan"};
    const double tolerance[3] = {1e-6, 3e-4, 3e-5};
    for (int angle : {0, 1, 2}) {
        auto provider = gpu_provider("analytic", scene, disc, 256, angle);
        std::vector<Link> links;
        provider->shoot(whole_polygon_shooter(scene, 1), links);
        ASSERT_EQ(links.size(), 1u);
        const double error = links[0].ff_analytic / k.expected - 1;
        std::printf("%-14s %-5s F %.9f  Howell %.9f  relative error %+.2e\n", k.name, names[angle],
                    double(links[0].ff_analytic), k.expected, error);
        EXPECT_NEAR(error, 0, tolerance[angle])
            << names[angle] << ": " << links[0].ff_analytic << " vs " << k.expected;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Howell, ShaderKernel,
    ::testing::Values(
        KernelCase{"B3_1_1_1", {{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, b3(1, 1, 1)},
        KernelCase{"B3_2_1_1", {{0, 0, 1}, {0, 1, 1}, {2, 1, 1}, {2, 0, 1}}, b3(2, 1, 1)},
        KernelCase{"B3_3_4_2", {{0, 0, 2}, {0, 4, 2}, {3, 4, 2}, {3, 0, 2}}, b3(3, 4, 2)},
        KernelCase{
            "B3_small_far", {{0, 0, 5}, {0, 0.1, 5}, {0.1, 0.1, 5}, {0.1, 0, 5}}, b3(0.1, 0.1, 5)},
        KernelCase{"centred_square",
                   {{-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}},
                   4 * b3(0.5, 0.5, 1)},
        // B-4: a plate standing in the plane y = d, from x = 0..L and height z = 0..H.
        KernelCase{"B4_1_1_1", {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}, b4(1, 1, 1)},
        KernelCase{"B4_3_2_1", {{0, 2, 0}, {3, 2, 0}, {3, 2, 1}, {0, 2, 1}}, b4(3, 2, 1)},
        // A plate that dips below the receiver's plane: only the part above counts (clip).
        KernelCase{"B4_clipped", {{0, 1, -0.5}, {1, 1, -0.5}, {1, 1, 1}, {0, 1, 1}}, b4(1, 1, 1)}),
    [](const auto& info) { return std::string(info.param.name); });

// --- ID encoding round trip and LOD clamping ------------------------------------------------
// Renders a hemicube over a large floor and decodes every pixel: the patch it names must
// contain the point that the pixel's ray hits (computed on the CPU), at a level no deeper
// than the polygon's depth.
struct Decoded {
    std::map<int, long> levels; // level -> pixel count
    long pixels = 0, mismatches = 0;
};

Decoded decode_floor(const Scene& scene, const Discretisation& disc, int res, double bias,
                     dvec3 eye) {
    context();
    gpu::HemicubeRenderer r(scene, disc, res);
    const gpu::HemicubeLayout L = gpu::make_hemicube_layout(res);
    // Shooter: a tiny downward-facing square at `eye` (polygon 1 of the scene).
    Shooter sh = whole_polygon_shooter(scene, 1);
    r.render(sh, L, bias, false);
    std::vector<float> px;
    r.read_back(L, px);
    const Polygon& floor = scene.polygons[0];
    Decoded d;
    const dvec3 N = sh.normal;
    dvec3 T = glm::normalize(sh.geometry.corners[1] - sh.geometry.corners[0]);
    T = glm::normalize(T - glm::dot(T, N) * N);
    const dvec3 B = glm::cross(N, T);
    // The renderer's frame (hemicube.cpp): faces look along N, T, -T, B, -B; glm::lookAt's
    // screen x is dir x up and screen y is up (B for the top face, N for the sides).
    const dvec3 dirs[5] = {N, T, -T, B, -B};
    const dvec3 ups[5] = {B, N, N, N, N};
    for (int f = 0; f < 5; ++f) {
        const auto& face = L.faces[f];
        const dvec3 screen_x = glm::cross(dirs[f], ups[f]);
        for (int y = 0; y < face.h; ++y)
            for (int x = 0; x < face.w; ++x) {
                const float* p = &px[(std::size_t(face.y + y) * L.width + face.x + x) * 4];
                if (p[2] < 0.5f) continue;
                ++d.pixels;
                const auto level = std::uint32_t(p[1]), index = std::uint32_t(p[0]);
                d.levels[int(level)]++;
                const double sx = -1 + (x + 0.5) * 2.0 / res;
                const double sy = f == 0 ? -1 + (y + 0.5) * 2.0 / res : (y + 0.5) * 2.0 / res;
                const dvec3 dir = dirs[f] + sx * screen_x + sy * ups[f];
                const double t = glm::dot(floor.v[0] - sh.geometry.centre, floor.normal) /
                                 glm::dot(dir, floor.normal);
                const dvec3 hit = sh.geometry.centre + t * dir;
                double u, v;
                if (!polygon_uv(floor, hit, u, v, 1e-3)) continue;
                // Pixel centres near a patch border may round either way: allow one texel.
                const std::uint32_t expected = patch_at(floor, level, u, v);
                const std::uint32_t n = 1u << level;
                const long dx = long(expected % n) - long(index % n);
                const long dy = long(expected / n) - long(index / n);
                if (std::abs(dx) > 1 || std::abs(dy) > 1 || level > disc.depth[0]) ++d.mismatches;
            }
    }
    return d;
}

Scene floor_and_eye(dvec3 eye, bool triangle_floor) {
    const double e = 1e-3;
    std::vector<dvec3> floor =
        triangle_floor ? std::vector<dvec3>{{-4, -4, 0}, {4, -4, 0}, {-4, 4, 0}}
                       : std::vector<dvec3>{{-4, -4, 0}, {4, -4, 0}, {4, 4, 0}, {-4, 4, 0}};
    return make_scene({floor,
                       {eye + dvec3(-e, -e, 0), eye + dvec3(-e, e, 0), eye + dvec3(e, e, 0),
                        eye + dvec3(e, -e, 0)}},
                      {"floor", "eye"});
}

TEST(PatchIds, RoundTripOnQuadsAndTriangles) {
    for (bool tri : {false, true}) {
        const dvec3 eye(0.3, -0.2, 1.0);
        const Scene scene = floor_and_eye(eye, tri);
        Discretisation disc{{10, 0}};
        const Decoded d = decode_floor(scene, disc, 256, 0, eye);
        EXPECT_GT(d.pixels, 10000) << (tri ? "triangle" : "quad");
        EXPECT_LT(double(d.mismatches), 0.002 * d.pixels) << (tri ? "triangle" : "quad");
        // The oracle links where patches cover about a pixel: texels of the depth-10 base are
        // 8/1024 wide, as is a top-face pixel's footprint at height 1 (the face's plane is
        // parallel to the floor at the same distance): level 10 there. The side faces see the
        // floor far away and obliquely: coarser levels (a footprint of 4 units at most: > 3).
        EXPECT_GE(d.levels.size(), 3u) << (tri ? "triangle" : "quad");
        EXPECT_GE(d.levels.begin()->first, 3) << (tri ? "triangle" : "quad");
        EXPECT_EQ(d.levels.rbegin()->first, 10) << (tri ? "triangle" : "quad");
    }
}

TEST(PatchIds, LodIsClampedToThePolygonsDepth) {
    // The floor is close (0.05 away): GL asks for very fine levels; depth 3 caps them.
    const dvec3 eye(0, 0, 0.05);
    const Scene scene = floor_and_eye(eye, false);
    const Decoded capped = decode_floor(scene, Discretisation{{3, 0}}, 128, 0, eye);
    ASSERT_GT(capped.pixels, 0);
    EXPECT_EQ(capped.levels.rbegin()->first, 3);
    EXPECT_GT(capped.levels.at(3), capped.pixels / 2);
    EXPECT_EQ(capped.mismatches, 0);
}

TEST(PatchIds, LodBiasLinksCoarser) {
    const dvec3 eye(0.3, -0.2, 1.0);
    const Scene scene = floor_and_eye(eye, false);
    const Discretisation disc{{9, 0}};
    const auto mean_level = [&](double bias) {
        const Decoded d = decode_floor(scene, disc, 128, bias, eye);
        double sum = 0;
        for (const auto& [level, count] : d.levels) sum += double(level) * count;
        return sum / double(d.pixels);
    };
    const double l0 = mean_level(0), l1 = mean_level(1);
    EXPECT_NEAR(l0 - l1, 1.0, 0.25) << l0 << " " << l1;
}

// --- the view probe's image: polygon IDs alone -------------------------------------------
// render_polygon_ids() skips the patch-ID texture and the form factor: its B channel must be
// render()'s, pixel for pixel (fronts, backs and nothing), with R, G and A left 0. The
// Cornell box at 64 and 256 from three of its polygons, and from inside the last one's block
// looking in (the block's other faces from behind).
TEST(PatchIds, PolygonIdsAloneMatchTheFullRender) {
    context();
    const Scene scene = make_builtin("cornell");
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    gpu::HemicubeRenderer r(scene, disc, 256);
    const auto last = std::uint32_t(scene.polygons.size() - 1);
    std::vector<Shooter> shooters;
    for (std::uint32_t p : {0u, 5u, last}) shooters.push_back(whole_polygon_shooter(scene, p));
    Shooter inside = shooters.back();
    const dvec3 step = -0.01 * inside.normal;
    inside.geometry.centre += step;
    for (dvec3& c : inside.geometry.corners) c += step;
    inside.normal = -inside.normal;
    shooters.push_back(inside);
    long fronts = 0, backs = 0, empty = 0;
    for (int res : {64, 256})
        for (std::size_t k = 0; k < shooters.size(); ++k) {
            const gpu::HemicubeLayout L = gpu::make_hemicube_layout(res);
            std::vector<float> full, ids;
            r.render(shooters[k], L, 0.0, 0);
            r.read_back(L, full);
            r.render_polygon_ids(shooters[k], L);
            r.read_back(L, ids);
            ASSERT_EQ(full.size(), ids.size());
            long differ = 0, nonzero = 0;
            for (std::size_t i = 0; i < full.size(); i += 4) {
                const float b = full[i + 2];
                if (b > 0.5f)
                    ++fronts;
                else if (b < -0.5f)
                    ++backs;
                else
                    ++empty;
                differ += ids[i + 2] != b;
                nonzero += ids[i] != 0.f || ids[i + 1] != 0.f || ids[i + 3] != 0.f;
            }
            EXPECT_EQ(differ, 0) << "res " << res << " shooter " << k;
            EXPECT_EQ(nonzero, 0) << "res " << res << " shooter " << k;
        }
    // Every kind of pixel was compared.
    EXPECT_GT(fronts, 1000);
    EXPECT_GT(backs, 1000);
    EXPECT_GT(empty, 1000);
}

// --- a receiver across a narrow gap ----------------------------------------------------------
// A bookshelf's plinth, 3.8 m x 11 cm, stands 1.6 cm from the wall of a closed room 4.9 m x
// 2.9 m x 4.9 m (the office glb's; its rows reached 1.0044 without the guard). A part of it
// 47 cm x 1.4 cm, 16 cm from the plinth's end, shoots. 80 % of its light lands on the wall
// within a few centimetres, in a bump of the kernel as wide as the gap, 20 % on the floor
// in the gap, and a trace on the side wall down the gap, which meets the shooter's plane.
// The reference: the exact kernel of each polygon (point_to_polygon_ff) at 200 x 200 points
// of the part; nothing lies between. Measured before: the wall 0.8062 (its nodes' means over
// parts as large as their distance from the part, each at its centre), the side wall 0.00026
// (nodes with their centres behind the part's plane, at the shader's kernel there), the row
// 1.0017; in a room twice as large, 0.8116, 0.0014 and 1.008.
TEST(NearReceivers, APlinthAcrossANarrowGapFromAWallSendsItsLightOnce) {
    const double w = 4.9, h = 2.92;
    Scene scene;
    scene.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    scene.groups = {"room", "plinth"};
    const double x0 = 1.05, x1 = 4.83, y0 = -0.008, y1 = 0.104, z = 0.016;
    add_facing(scene, {{0, 0, 0}, {w, 0, 0}, {w, h, 0}, {0, h, 0}}, {0, 0, 1}, 0);
    add_facing(scene, {{0, 0, w}, {w, 0, w}, {w, h, w}, {0, h, w}}, {0, 0, -1}, 0);
    add_facing(scene, {{0, 0, 0}, {0, 0, w}, {0, h, w}, {0, h, 0}}, {1, 0, 0}, 0);
    add_facing(scene, {{w, 0, 0}, {w, 0, w}, {w, h, w}, {w, h, 0}}, {-1, 0, 0}, 0);
    add_facing(scene, {{0, h, 0}, {w, h, 0}, {w, h, w}, {0, h, w}}, {0, -1, 0}, 0);
    // The floor: the gap's strip and the rest.
    add_facing(scene, {{0, 0, 0}, {w, 0, 0}, {w, 0, z}, {0, 0, z}}, {0, 1, 0}, 0);
    add_facing(scene, {{0, 0, z}, {w, 0, z}, {w, 0, w}, {0, 0, w}}, {0, 1, 0}, 0);
    const auto plinth = std::uint32_t(scene.polygons.size());
    add_facing(scene, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, {0, 0, -1}, 1);
    finish_scene(scene, "test");
    const Polygon& poly = scene.polygons[plinth];
    ASSERT_NEAR(poly.normal.z, -1.0, 1e-12);
    Shooter sh; // the part of the third level whose centre is nearest (1.21, 0.0153)
    double best = 1e300;
    for (std::uint32_t i = 0; i < 64; ++i) {
        const PatchGeometry g = patch_geometry(poly, 3, i);
        const double off = std::abs(g.centre.x - 1.21) + std::abs(g.centre.y - 0.0153);
        if (off < best) {
            best = off;
            sh.address = {plinth, 3, i};
            sh.geometry = g;
        }
    }
    sh.normal = poly.normal;
    sh.unshot_power = 1;
    ASSERT_NEAR(sh.geometry.area, 0.4725 * 0.014, 1e-4);
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    std::vector<Link> links;
    gpu_provider("hybrid", scene, disc, 256)->shoot(sh, links);
    std::vector<double> taken(plinth, 0.0), exact(plinth, 0.0);
    double row = 0;
    for (const Link& l : links) {
        const double f = link_share(scene, l, sh.geometry.area);
        row += f;
        if (l.receiver.polygon < plinth) taken[l.receiver.polygon] += f;
    }
    const int n = 200;
    const PatchGeometry& g = sh.geometry;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const dvec3 x = g.corners[0] + (g.corners[1] - g.corners[0]) * ((i + 0.5) / n) +
                            (g.corners[3] - g.corners[0]) * ((j + 0.5) / n);
            for (std::uint32_t p = 0; p < plinth; ++p)
                exact[p] += point_to_polygon_ff(x, sh.normal, scene.polygons[p].v.data(),
                                                scene.polygons[p].count) /
                            (n * n);
        }
    std::printf("plinth part across a gap: row %.5f; wall %.5f (exact %.5f), gap's floor %.5f "
                "(%.5f), side wall %.5f (%.5f)\n",
                row, taken[0], exact[0], taken[5], exact[5], taken[2], exact[2]);
    ASSERT_GT(exact[0], 0.8); // the case means something
    EXPECT_NEAR(taken[0], exact[0], 0.001);
    EXPECT_NEAR(taken[5], exact[5], 0.002);
    EXPECT_NEAR(taken[2], exact[2], 0.0001);
    EXPECT_LE(row, 1.001);
    EXPECT_GE(row, 0.995);
}

// --- a shooter's parts: what its centre sees that they do not ------------------------------
// A 20 cm square on the floor of a closed 1 m box shoots under a plate 5 cm above it with a
// 4 cm hole over its centre. The centre sees the ceiling through the hole, a disc some 0.8 m
// wide, and the links take the whole square's kernel for it, though the rest of the square
// sees only the plate's underside there: the row summed to 1.129 (the ceiling 0.166). Past 1 %
// over 1, each link takes the share of the square's kernel that reaches it unblocked from its
// 64 parts (see_from_parts): 0.970 (the ceiling 0.007). The box is closed, so the exact row is
// 1: no light may be made (the solver's bar, 1.001). What is lost is the light that the parts
// send through the hole to the ceiling beyond the disc the centre sees, which has no links:
// 3 % here, for a hole that shows the centre 17 % of the sky; the bar below is 5 %.
TEST(ShooterParts, AFloorUnderAPlateWithAHoleSendsItsLightOnce) {
    const double e = 0.5; // the box: [-e, e] x [0, 1] x [-e, e]
    Scene scene = box_without_floor(e, {"box", "square", "plate"});
    const auto add_facing = [&](const std::vector<dvec3>& v, const dvec3& normal,
                                std::uint32_t group) { ::add_facing(scene, v, normal, group); };
    // The floor: the square in the middle, four pieces around it.
    const double s = 0.1;
    const auto floor_rect = [&](double x0, double z0, double x1, double z1, std::uint32_t g) {
        add_facing({{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}}, {0, 1, 0}, g);
    };
    const auto square = std::uint32_t(scene.polygons.size());
    floor_rect(-s, -s, s, s, 1);
    floor_rect(-e, -e, e, -s, 0);
    floor_rect(-e, s, e, e, 0);
    floor_rect(-e, -s, -s, s, 0);
    floor_rect(s, -s, e, s, 0);
    // The plate, 0.6 wide, facing down, a frame of four pieces around a 4 cm hole.
    const double y = 0.05, p = 0.3, h = 0.02;
    const auto plate_rect = [&](double x0, double z0, double x1, double z1) {
        add_facing({{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}}, {0, -1, 0}, 2);
    };
    plate_rect(-p, -p, p, -h);
    plate_rect(-p, h, p, p);
    plate_rect(-p, -h, -h, h);
    plate_rect(h, -h, p, h);
    finish_scene(scene, "test");
    ASSERT_NEAR(scene.polygons[square].normal.y, 1.0, 1e-12);
    const auto [row, ceiling] =
        whole_polygon_row(scene, square, [](std::uint32_t p) { return p == 0; });
    std::printf("square under a plate with a hole: row %.5f, on the ceiling %.5f\n", row, ceiling);
    EXPECT_GT(ceiling, 0) << "the centre sees the ceiling through the hole";
    EXPECT_LE(row, 1.001);
    EXPECT_GE(row, 0.95);
}

// A strip of floor 4 cm wide between two bars that stand 3.3 mm high along its sides, as
// the office glb's PC face between its two LED bars (its worst row before the guard, 1.026),
// in a closed box: the exact row is 1. From the strip's centre the bars are seen at a grazing
// 9 degrees, so its pixels and its links to the room beyond hold almost all of its light; the
// bars' sides take 0.08 of it (closed form for a strip and a wall that meet at a right angle:
// 0.04 each), mostly near them, from the parts of the strip a few millimetres away. Rays from
// a 4 x 4 grid of the strip's parts sample that at 1 and 15 mm from a bar, and found a 0.052
// share hidden where the exact share is 0.08: the row 1.027. From an 8 x 8 grid, 1.006 (0.071
// hidden). From 256 parts four levels down, where the row stays over 1.001 (see_from_parts):
// 0.9995.
TEST(ShooterParts, AStripBetweenTwoLowBarsSendsItsLightOnce) {
    const double e = 0.5; // the box: [-e, e] x [0, 1] x [-e, e]
    Scene scene = box_without_floor(e, {"box", "strip", "bars"});
    const auto add_facing = [&](const std::vector<dvec3>& v, const dvec3& normal,
                                std::uint32_t group) { ::add_facing(scene, v, normal, group); };
    const double w = 0.02, b = 0.014, h = 0.0033, l = 0.22; // half widths, bar, height, half length
    const auto floor_rect = [&](double x0, double z0, double x1, double z1, std::uint32_t g) {
        add_facing({{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}}, {0, 1, 0}, g);
    };
    const auto strip = std::uint32_t(scene.polygons.size());
    floor_rect(-w, -l, w, l, 1);
    floor_rect(-e, -e, e, -l, 0); // the floor around; none under the bars
    floor_rect(-e, l, e, e, 0);
    floor_rect(-e, -l, -w - b, l, 0);
    floor_rect(w + b, -l, e, l, 0);
    for (const double side : {-1.0, 1.0}) { // each bar: [w, w + b] on its side, closed above
        const double x0 = side * w, x1 = side * (w + b);
        add_facing({{x0, 0, -l}, {x0, 0, l}, {x0, h, l}, {x0, h, -l}}, {-side, 0, 0}, 2);
        add_facing({{x1, 0, -l}, {x1, 0, l}, {x1, h, l}, {x1, h, -l}}, {side, 0, 0}, 2);
        add_facing({{x0, h, -l}, {x1, h, -l}, {x1, h, l}, {x0, h, l}}, {0, 1, 0}, 2);
        add_facing({{x0, 0, -l}, {x1, 0, -l}, {x1, h, -l}, {x0, h, -l}}, {0, 0, -1}, 2);
        add_facing({{x0, 0, l}, {x1, 0, l}, {x1, h, l}, {x0, h, l}}, {0, 0, 1}, 2);
    }
    finish_scene(scene, "test");
    ASSERT_NEAR(scene.polygons[strip].normal.y, 1.0, 1e-12);
    const auto [row, bars] = whole_polygon_row(
        scene, strip, [&](std::uint32_t p) { return scene.polygons[p].group == 2; });
    std::printf("strip between two low bars: row %.5f, on the bars %.5f\n", row, bars);
    EXPECT_NEAR(bars, 0.08, 0.02) << "the bars' sides take about 0.04 each";
    EXPECT_LE(row, 1.001);
    EXPECT_GE(row, 0.95);
}

// --- a silhouette less than a pixel wide ----------------------------------------------------
// Polygon 2's (the panel's) kernel towards polygon 0 (the lamp, a quad), F(x -> lamp), averaged
// over 64 x 64 points of the panel: {where `hidden` (a point's ray to the lamp's centre meets
// something) is false, everywhere}.
template <class Hidden>
std::pair<double, double> kernel_over_panel(const Scene& scene, Hidden&& hidden) {
    const Polygon& panel = scene.polygons[2];
    double seen = 0, all = 0;
    const int n = 64;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const dvec3 x = polygon_point(panel, (i + 0.5) / n, (j + 0.5) / n);
            const double f = point_to_polygon_ff(x, panel.normal, scene.polygons[0].v.data(), 4);
            all += f;
            seen += hidden(x) ? 0 : f;
        }
    return {seen / (n * n), all / (n * n)};
}

// A 2 mm shooter looks past a bar 3.4 mm high, 4 cm in front of it, at a strip of a slanted
// panel 24 cm away, about half of which lies behind the bar (the office glb's LED bar, the one
// across from it, and the PC case's slanted face). On the 64^2 hemicube the part behind the
// bar is 0.7 pixel high and lies between the centres of the bar's pixel rows, so no pixel
// ray meets the panel behind the bar: the panel was taken as seen whole, at its unoccluded
// value (in the office, rows up to 1.0095). The rays near the bar's pixels' corners find it
// going on behind the bar: the panel is linked as partly hidden, by the pixels it shows. The
// reference: the kernel times visibility from the shooter's centre (the bar intersected
// exactly), averaged over 64 x 64 points of the panel. Measured: +92 % linked whole, +17 % by
// its pixels (the part seen is 0.8 pixel high: the bar is 30 %).
TEST(SubPixelSilhouettes, APanelHalfHiddenByAThinBarIsNotLinkedWhole) {
    Scene scene;
    scene.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    scene.groups = {"lamp", "bar", "panel"};
    const double s = 0.001, bx = 0.04, b0 = -0.0004, b1 = 0.003, bl = 0.2;
    add_facing(scene, {{0, -s, -s}, {0, s, -s}, {0, s, s}, {0, -s, s}}, {1, 0, 0}, 0);
    add_facing(scene, {{bx, -bl, b0}, {bx, bl, b0}, {bx, bl, b1}, {bx, -bl, b1}}, {-1, 0, 0}, 1);
    const dvec3 top(0.24, 0, 0.003), bottom(0.2553, 0, -0.00894);
    const dvec3 normal = glm::normalize(dvec3(-0.078, 0, -0.1));
    const double pw = 0.05;
    add_facing(scene,
               {top - dvec3(0, pw, 0), top + dvec3(0, pw, 0), bottom + dvec3(0, pw, 0),
                bottom - dvec3(0, pw, 0)},
               normal, 2);
    finish_scene(scene, "test");
    const Polygon& panel = scene.polygons[2];
    ASSERT_GT(glm::dot(panel.normal, -panel.centroid()), 0); // it faces the lamp
    const auto [seen, all] = kernel_over_panel(scene, [&](const dvec3& x) {
        const dvec3 at_bar = x * (bx / x.x); // where the ray from the lamp's centre passes
        return at_bar.z > b0 && at_bar.z < b1 && std::abs(at_bar.y) < bl;
    });
    ASSERT_NEAR(seen / all, 0.5, 0.1); // the case means something
    const std::vector<Link> links = hybrid_links(scene, whole_polygon_shooter(scene, 0), 64);
    const auto it = std::find_if(links.begin(), links.end(),
                                 [](const Link& l) { return l.receiver.polygon == 2; });
    ASSERT_NE(it, links.end()) << "the panel is not linked";
    const double expected = seen;
    std::printf("panel half behind a thin bar: ff %.4g, analytic %.4g, expected %.4g (%s)\n",
                double(it->ff), double(it->ff_analytic), expected,
                it->partial ? "partial" : "whole");
    EXPECT_TRUE(it->partial) << "a silhouette crosses the panel";
    EXPECT_NEAR(it->ff / expected - 1, 0, 0.3);
}

// A bar 3.3 mm proud of a panel, just beyond its near edge, seen at a grazing angle from a
// small shooter 43 cm away (the office glb's LED bar beside a PC case's side): it hides a
// strip 1.2 cm wide along the panel's near edge, where the panel is nearest the shooter. The
// panel's five samples (centre and quarters' centres) all lie beyond the strip, so it was
// linked whole at its unoccluded value, though a silhouette borders its pixels; now its
// pixels measure the share the centre sees (HemicubeProvider::pixel_seen_share). The
// reference: the kernel times visibility from the shooter's centre (the bar intersected
// exactly), averaged over 64 x 64 points of the panel. Measured at 256^2: +13.8 % linked
// whole, -2.5 % by its pixels (the bar's edge crosses the pixel rows at a slant; unoccluded
// nodes' pixels read the exact value within about 3 %: hence the 4 %).
TEST(SubPixelSilhouettes, AStripAlongAPanelsEdgeBehindABarIsNotLinked) {
    Scene scene;
    scene.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
    scene.groups = {"lamp", "bar", "panel"};
    const double s = 0.005, zp = 0.1, zb = zp - 0.0033, x0 = 0.35, x1 = 0.51, y = 0.15;
    add_facing(scene, {{0, -s, -s}, {0, s, -s}, {0, s, s}, {0, -s, s}}, {1, 0, 0}, 0);
    add_facing(scene, {{0.336, -0.2, zb}, {x0, -0.2, zb}, {x0, 0.2, zb}, {0.336, 0.2, zb}},
               {0, 0, -1}, 1);
    add_facing(scene, {{x0, -y, zp}, {x1, -y, zp}, {x1, y, zp}, {x0, y, zp}}, {0, 0, -1}, 2);
    finish_scene(scene, "test");
    const auto [seen, all] = kernel_over_panel(scene, [&](const dvec3& x) {
        const double at_bar = x.x * (zb / zp); // where the ray from the lamp's centre passes
        return at_bar > 0.336 && at_bar < x0;
    });
    ASSERT_LT(seen / all, 0.95); // the strip holds a share of the light worth the test
    const std::vector<Link> links = hybrid_links(scene, whole_polygon_shooter(scene, 0), 256);
    const auto it = std::find_if(links.begin(), links.end(),
                                 [](const Link& l) { return l.receiver.polygon == 2; });
    ASSERT_NE(it, links.end()) << "the panel is not linked";
    const double expected = seen, unoccluded = all;
    std::printf("panel with a strip behind a bar: ff %.5g, analytic %.5g, expected %.5g, "
                "unoccluded %.5g (%s)\n",
                double(it->ff), double(it->ff_analytic), expected, unoccluded,
                it->partial ? "partial" : "whole");
    EXPECT_TRUE(it->partial) << "a silhouette borders the panel";
    EXPECT_NEAR(it->ff / expected - 1, 0, 0.04);
}

// --- partial occlusion: hybrid links the seen parts of a node -----------------------------
// A square blocker, turned 30 degrees, halfway between two parallel plates 0.93 apart; one
// shot from a small ceiling patch (1/32 wide, so that the hemicube's point of view stands for
// it); receivers on the floor at depth 6 (64 x 64 nodes of about 1.1 pixels at resolution
// 256: the oracle's own scale, where pixel counting aliases). The reference per node is
// independent of the hemicube: the analytic kernel times visibility from the shooter's
// centre, averaged over 8 x 8 points of the node, with the blocker intersected exactly.
// Hybrid (analytic where a node is seen whole; where a silhouette crosses it, the parts of it
// seen, down to the leaves) must beat binary visibility (analytic) and pixel counting
// (hemicube).
TEST(Hybrid, PartialNodesLinkTheirSeenPartsAndCloserToReference) {
    const double h = 0.93, hb = 0.45, c = std::cos(M_PI / 6), sn = std::sin(M_PI / 6);
    std::vector<dvec3> blocker;
    for (const auto& [x, y] : std::vector<std::pair<double, double>>{
             {-0.2, -0.2}, {-0.2, 0.2}, {0.2, 0.2}, {0.2, -0.2}}) // faces down (-z)
        blocker.push_back(dvec3(0.5 + c * x - sn * y, 0.5 + sn * x + c * y, hb));
    const Scene scene = make_scene({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, // floor, up
                                    {{0, 0, h}, {0, 1, h}, {1, 1, h}, {1, 0, h}}, // ceiling
                                    blocker},
                                   {"floor", "ceiling", "blocker"});
    const int depth = 6, n = 1 << depth;
    const Discretisation disc{{std::uint8_t(depth), 5, 0}};
    Shooter shooter = whole_polygon_shooter(scene, 1);
    shooter.address = {1, 5, 13 * 32 + 14};
    shooter.geometry = patch_geometry(scene.polygons[1], 5, 13 * 32 + 14);
    const dvec3 eye = shooter.geometry.centre;
    // Is the segment from floor point x to the eye blocked? Intersect the blocker's plane.
    const auto blocked = [&](const dvec3& x) {
        const dvec3 q = x + (eye - x) * ((hb - x.z) / (eye.z - x.z));
        const dvec3 d = q - dvec3(0.5, 0.5, hb);
        const double u = c * d.x + sn * d.y, v = -sn * d.x + c * d.y; // undo the rotation
        return std::abs(u) < 0.2 && std::abs(v) < 0.2;
    };
    std::vector<double> reference(std::size_t(n) * n);
    const int k = 8;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double sum = 0;
            for (int b = 0; b < k; ++b)
                for (int a = 0; a < k; ++a) {
                    const dvec3 x((i + (a + 0.5) / k) / n, (j + (b + 0.5) / k) / n, 0);
                    if (!blocked(x))
                        sum += point_to_polygon_ff(x, dvec3(0, 0, 1),
                                                   shooter.geometry.corners.data(), 4);
                }
            reference[std::size_t(j) * n + i] = sum / (k * k);
        }

    std::map<std::string, double> rms;
    for (const char* mode : {"hybrid", "analytic", "hemicube"}) {
        auto p = gpu_provider(mode, scene, disc, 256);
        std::vector<Link> links;
        p->shoot(shooter, links);
        // Spread each link over the leaves under it (the oracle may link coarser).
        std::vector<double> gpu(reference.size(), 0.0);
        long partial = 0;
        for (const Link& l : links) {
            if (l.receiver.polygon != 0) continue;
            const std::uint32_t m = 1u << l.receiver.level, shift = depth - l.receiver.level;
            const std::uint32_t x0 = (l.receiver.index % m) << shift, y0 = (l.receiver.index / m)
                                                                           << shift;
            for (std::uint32_t y = y0; y < y0 + (1u << shift); ++y)
                for (std::uint32_t x = x0; x < x0 + (1u << shift); ++x) gpu[y * n + x] = l.ff;
            if (std::string(mode) != "hybrid") continue;
            EXPECT_LE(l.ff, l.ff_analytic);
            if (l.partial)
                ++partial;
            else
                EXPECT_EQ(l.ff, l.ff_analytic);
        }
        if (std::string(mode) == "hybrid") {
            EXPECT_GT(partial, 0);
        }
        double sum = 0, norm = 0;
        for (std::size_t i = 0; i < reference.size(); ++i) {
            sum += (gpu[i] - reference[i]) * (gpu[i] - reference[i]);
            norm += reference[i] * reference[i];
        }
        rms[mode] = std::sqrt(sum / norm);
    }
    std::printf("relative RMS error per floor node vs reference: hybrid %.4f analytic %.4f "
                "hemicube %.4f\n",
                rms["hybrid"], rms["analytic"], rms["hemicube"]);
    EXPECT_LT(rms["hybrid"], rms["analytic"]);
    EXPECT_LT(rms["hybrid"], rms["hemicube"]);
}

// --- cluster probes: a cluster's shares measured before its shot -------------------------
// probe_cluster() reads, on 64² hemicubes of polygon IDs, the shares the solver reads after a
// cluster's shot (its misplaced share: parallax + near + backs; and the backs alone) to refuse
// it without shooting. In the Cornell box: a point cluster of two lobes (+x and +y, half the
// power each; radius a twentieth of the box) a fiftieth of the box from a block's
// face, in the middle of the room, low over the floor and inside the block (backs all round),
// and a flat one (a rectangle of a tenth of the box) just over the floor. The probe's pixels and
// the shot's samples (every fourth pixel of its 256² hemicubes) look along directions half a probe
// pixel apart, and the probe weighs each pixel by its flux where the shot weighs links by their
// values: a few per cent (on the courtyard's 87 clusters the probe read 0.97-1.02 of the shot's
// misplaced share, 10th-90th percentiles; the office's flat clusters, next to thin emissive bars,
// up to 1.33). The bar is 10 % on each share here; a probe that read the parallax on the hemicube
// against the axis, not along it, reads the cluster low over the floor 38 % low.
TEST(ClusterProbe, ReadsTheSharesTheShotReads) {
    const Scene scene = make_builtin("cornell");
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    auto p = gpu_provider("hybrid", scene, disc, 256);
    dvec3 lo(1e300), hi(-1e300);
    for (const Polygon& q : scene.polygons)
        for (int k = 0; k < q.count; ++k) lo = glm::min(lo, q.v[k]), hi = glm::max(hi, q.v[k]);
    const dvec3 size = hi - lo;
    const double side = std::max({size.x, size.y, size.z});
    const auto point_cluster = [&](const dvec3& centre) {
        ClusterShooter c;
        c.centre = centre;
        c.axis = {0, 1, 0};
        c.radius = side / 20;
        c.normals = {{1, 0, 0}, {0, 1, 0}};
        c.weights = {0.5, 0.5};
        c.unshot_power = 1;
        return c;
    };
    std::vector<ClusterShooter> clusters;
    const dvec3 middle = lo + 0.5 * size;
    clusters.push_back(point_cluster(middle));
    clusters.push_back(point_cluster({middle.x, lo.y + 0.05 * size.y, middle.z}));
    // Beside a block: a fiftieth of the box in front of the block's side face nearest the
    // room's middle (a block's faces: the polygons not on the box's walls).
    double best = 1e300;
    dvec3 beside(0.0), face_normal(0.0);
    for (const Polygon& q : scene.polygons) {
        const dvec3 c = q.centroid();
        const bool wall = c.x - lo.x < 1e-6 * side || hi.x - c.x < 1e-6 * side ||
                          c.y - lo.y < 1e-6 * side || hi.y - c.y < 1e-6 * side ||
                          c.z - lo.z < 1e-6 * side || hi.z - c.z < 1e-6 * side;
        if (wall || std::abs(q.normal.y) > 0.5) continue; // a block's side face
        const double d = glm::length(c - middle);
        if (d < best) best = d, beside = c + 0.02 * side * q.normal, face_normal = q.normal;
    }
    ASSERT_LT(best, 1e300) << "the Cornell box has blocks";
    clusters.push_back(point_cluster(beside));
    // Inside the block, a fiftieth of the box behind that face: backs all round.
    clusters.push_back(point_cluster(beside - 0.04 * side * face_normal));
    ClusterShooter flat = point_cluster({middle.x, lo.y + 0.01 * size.y, middle.z});
    flat.normals = {{0, 1, 0}};
    flat.weights = {1.0};
    const double h = 0.05 * side;
    flat.rect.count = 4;
    flat.rect.corners = {flat.centre + dvec3(-h, 0, -h), flat.centre + dvec3(h, 0, -h),
                         flat.centre + dvec3(h, 0, h), flat.centre + dvec3(-h, 0, h)};
    flat.rect.centre = flat.centre;
    flat.rect.area = 4 * h * h;
    clusters.push_back(flat);
    double largest = 0;
    for (std::size_t k = 0; k < clusters.size(); ++k) {
        FormFactorProvider::ClusterProbe probe;
        ASSERT_TRUE(p->probe_cluster(clusters[k], probe)) << "cluster " << k;
        std::vector<Link> links;
        p->shoot_cluster(clusters[k], links);
        const double misplaced =
            p->last_parallax_fraction() + p->last_near_fraction() + p->last_backface_fraction();
        const double back = p->last_backface_fraction();
        std::printf("cluster %zu: misplaced probe %.4f shot %.4f, backs probe %.4f shot %.4f\n", k,
                    probe.misplaced, misplaced, probe.backface, back);
        EXPECT_NEAR(probe.misplaced, misplaced, 0.1 * misplaced + 1e-3) << "cluster " << k;
        EXPECT_NEAR(probe.backface, back, 0.1 * back + 1e-3) << "cluster " << k;
        largest = std::max(largest, misplaced);
    }
    EXPECT_GT(largest, 0.1) << "some cluster must misplace light for the test to mean anything";
}

// --- flat clusters: the far field divided as the pixels divide it ---------------------------
// A flat cluster shoots as a rectangle from an eye at its centre. Farther than twice the
// rectangle's reach, each polygon takes the light its pixels take, the node values keeping
// their shape (match_pixel_totals): the analytic values at node centres, each with its own
// visibility test, misjudge a tessellated round surface, whose facets seen edge-on hide each
// other's centres. A room 1 x 1 x 1, a column of 16, 48 or 96 facets (radius 0.05, height
// 0.8) 0.35 or 0.5 from a 0.1 square on the floor (its reach 0.071); the exact share is the
// ray-cast reference provider's (the square as a polygon, 16 x 16 samples on it, occlusion by
// rays). Before the pixels divided the far light the column read 1.02 / 0.98, 1.16 / 1.21 and
// 1.30 / 1.07 of it (at 0.5 / 0.35); with the pixels counted from the links, 0.92 / 0.90 at
// 48 facets (a node that GL's LOD showed together with all its children had no link to carry
// its pixels); now 0.98-1.01. The bar, 5 %, is the eye standing in for the square: a kernel
// error of order (reach / distance)^2, 2-4 % here.
TEST(FlatCluster, FarReceiversTakeTheLightTheirPixelsTake) {
    for (const int facets : {16, 48, 96})
        for (const double column_x : {0.2, 0.35}) {
            Scene scene;
            scene.materials.push_back({"grey", dvec3(0.5), dvec3(0.0)});
            scene.groups = {"room", "column", "cluster"};
            const dvec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
            const int faces[6][4] = {{1, 2, 3, 0}, {7, 6, 5, 4}, {3, 7, 4, 0},
                                     {5, 6, 2, 1}, {4, 5, 1, 0}, {2, 6, 7, 3}}; // facing in
            for (const auto& f : faces)
                add_polygon(scene, {c[f[0]], c[f[1]], c[f[2]], c[f[3]]}, 0, 0);
            const double r = 0.05, height = 0.8;
            for (int k = 0; k < facets; ++k) {
                const double a0 = 2 * M_PI * k / facets, a1 = 2 * M_PI * (k + 1) / facets;
                const dvec3 p0(column_x + r * std::cos(a0), 0, 0.5 + r * std::sin(a0));
                const dvec3 p1(column_x + r * std::cos(a1), 0, 0.5 + r * std::sin(a1));
                add_polygon(scene, {p0, p0 + dvec3(0, height, 0), p1 + dvec3(0, height, 0), p1}, 0,
                            1);
            }
            const dvec3 centre(0.7, 0.002, 0.5);
            const double h = 0.05;
            const auto square = std::uint32_t(scene.polygons.size());
            add_polygon(scene,
                        {centre + dvec3(-h, 0, -h), centre + dvec3(-h, 0, h),
                         centre + dvec3(h, 0, h), centre + dvec3(h, 0, -h)},
                        0, 2);
            finish_scene(scene, "test");
            ASSERT_GT(scene.polygons[square].normal.y, 0.9);
            const Discretisation disc = discretise(scene, HierarchyOptions{});

            // The share of the square's light on the column: the cluster's links are per watt
            // (E_j / P), the reference's F(j -> S) (times A_j / A_S).
            const auto on_column = [&](const std::vector<Link>& links, double scale) {
                double sum = 0;
                for (const Link& l : links) {
                    const Polygon& q = scene.polygons[l.receiver.polygon];
                    if (q.group == 1)
                        sum += double(l.ff) *
                               patch_geometry(q, l.receiver.level, l.receiver.index).area;
                }
                return sum * scale;
            };
            ClusterShooter cluster;
            cluster.centre = centre;
            cluster.axis = {0, 1, 0};
            cluster.radius = h * std::sqrt(2.0);
            cluster.normals = {{0, 1, 0}};
            cluster.weights = {1.0};
            cluster.unshot_power = 1;
            cluster.members = {square};
            cluster.rect = patch_geometry(scene.polygons[square], 0, 0);
            std::vector<Link> links;
            gpu_provider("hybrid", scene, disc, 256)->shoot_cluster(cluster, links);
            const double shot = on_column(links, 1.0);
            ProviderOptions o;
            o.cpu.visibility_samples = 16;
            make_provider("reference", scene, disc, o)
                ->shoot(whole_polygon_shooter(scene, square), links);
            const double exact = on_column(links, 1.0 / scene.polygons[square].area);
            std::printf(
                "column of %d facets at x = %.2f: cluster %.5f, reference %.5f, ratio %.4f\n",
                facets, column_x, shot, exact, shot / exact);
            ASSERT_GT(exact, 0.01)
                << "the column must take a fair share for the test to mean anything";
            EXPECT_NEAR(shot / exact, 1.0, 0.05) << facets << " facets at x = " << column_x;
        }
}

// A long thin flat cluster in a closed box sends all its light into the box and no more: the
// row (the links' flux per watt, the backs' share kept) sums to 1. Its near receivers take the
// rectangle's analytic values and its far ones the light its eye's pixels show; where the eye
// stands for the rectangle badly (a bar 0.86 long, 1.4 cm wide, whose ends are 5-8 cm from the
// floor and the top, as the office glb's LED bar under a desk: the eye sees the top 1.24 times
// as large as the bar does, the floor 0.8 times), the two together summed to 1.024 there, and
// 1.011 here. The far links are held to the light the pixels leave after the near ones. The
// bar is 0.1 % (the solver's row-sum bar, 1.001), below by the escaped light (none here).
TEST(FlatCluster, ALongBarInAClosedBoxSendsItsLightOnce) {
    const dvec3 size(0.615, 0.99, 1.07);
    Scene scene = closed_box(size, {"box", "bar"});
    const double x0 = 0.3166, x1 = 0.3311, y0 = 0.053, y1 = 0.91, z = 0.002;
    const auto bar = std::uint32_t(scene.polygons.size());
    add_polygon(scene, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, 0, 1);
    finish_scene(scene, "test");
    for (std::size_t p = 0; p < 6; ++p)
        ASSERT_GT(glm::dot(scene.polygons[p].normal, 0.5 * size - scene.polygons[p].centroid()), 0)
            << "the box's face " << p << " must face in";
    ASSERT_GT(scene.polygons[bar].normal.z, 0.99) << "the bar must face into the box";
    const Discretisation disc = discretise(scene, HierarchyOptions{});
    ClusterShooter cluster;
    cluster.centre = scene.polygons[bar].centroid();
    cluster.axis = {0, 0, 1};
    cluster.radius = 0.5 * glm::length(dvec3(x1 - x0, y1 - y0, 0));
    cluster.normals = {{0, 0, 1}};
    cluster.weights = {1.0};
    cluster.unshot_power = 1;
    cluster.members = {bar};
    cluster.rect = patch_geometry(scene.polygons[bar], 0, 0);
    auto provider = gpu_provider("hybrid", scene, disc, 256);
    std::vector<Link> links;
    provider->shoot_cluster(cluster, links);
    double row = 0, far = 0;
    for (const Link& l : links) {
        const PatchAddress& r = l.receiver;
        row += link_share(scene, l, 1.0); // per watt
        if (glm::length(patch_centre(scene.polygons[r.polygon], r.level, r.index) -
                        cluster.centre) > 2 * cluster.radius)
            far += link_share(scene, l, 1.0);
    }
    std::printf("bar in a closed box: row %.5f (far links %.5f), backs %.4f\n", row, far,
                provider->last_backface_fraction());
    EXPECT_GT(far, 0.2) << "the far links must carry a fair share for the test to mean anything";
    EXPECT_LE(row, 1.001);
    EXPECT_GE(row, 0.97) << "a closed box takes all the bar's light";
}

// A point cluster in a closed box sends all its light into the box and no more, its near
// receivers too. A board modelled twice (two coincident faces facing the same way, as the
// office glb's desk parts were once their faces got twins), 10-30 cm from the point: the pixels
// show one face, and the other, which no pixel shows, was linked by its kernel all the same, since
// its depth matches what is drawn there. Near the point each polygon kept its own values, and
// the board took its light twice: the office's clusters of 4-17 polygons summed to 1.009-1.037
// (a desk part 20 cm away with no pixel took 0.074 of the light). Each polygon now takes the
// light its pixels show, near or far (the point's pixels integrate its kernel exactly, most
// finely where the receiver is nearest). The bar is the solver's row-sum bar, 1.001.
TEST(PointCluster, NearABoardModelledTwiceSendsItsLightOnce) {
    for (double gap : {0.1, 0.3}) {
        Scene scene = closed_box(dvec3(1.0), {"box", "board"});
        const double x = 0.5 + gap, h = 0.1;
        for (int twice = 0; twice < 2; ++twice)
            add_facing(scene,
                       {{x, 0.5 - h, 0.5 - h},
                        {x, 0.5 + h, 0.5 - h},
                        {x, 0.5 + h, 0.5 + h},
                        {x, 0.5 - h, 0.5 + h}},
                       {-1, 0, 0}, 1);
        finish_scene(scene, "test");
        const Discretisation disc = discretise(scene, HierarchyOptions{});
        ClusterShooter cluster;
        cluster.centre = {0.5, 0.5123, 0.4876};
        cluster.axis = {1, 0, 0};
        cluster.radius = 0.2;
        cluster.normals = {{1, 0, 0}, {0, 1, 0}};
        cluster.weights = {0.75, 0.25};
        cluster.unshot_power = 1;
        auto provider = gpu_provider("hybrid", scene, disc, 256);
        std::vector<Link> links;
        provider->shoot_cluster(cluster, links);
        double row = 0, board = 0;
        for (const Link& l : links) {
            row += link_share(scene, l, 1.0); // per watt
            if (l.receiver.polygon >= 6) board += link_share(scene, l, 1.0);
        }
        std::printf("point cluster %.1f from a board modelled twice: row %.5f (the board %.5f), "
                    "backs %.4f\n",
                    gap, row, board, provider->last_backface_fraction());
        EXPECT_GT(board, 0.05) << "the board must take a fair share for the test to mean anything";
        EXPECT_LE(row, 1.001) << "at " << gap;
        EXPECT_GE(row, 0.97) << "a closed box takes all the cluster's light, at " << gap;
    }
}

// A patch 5-30 cm from a board modelled by both its faces, each two-sided (the office glb's
// desk parts), in a closed box: the row sums to 1 at most. Had each face a twin, the twin of
// the back face would lie on the front face, facing the patch; the pixels show one of the two
// and the other is linked by its kernel all the same (its depth matches what is drawn): rows
// 1.75, 1.45 and 1.11. make_two_sided pairs the two faces instead. Bar: the solver's 1.001.
TEST(TwoSidedBoard, APatchNearABoardModelledByBothFacesSendsItsLightOnce) {
    for (double gap : {0.05, 0.1, 0.3}) {
        Scene scene = closed_box(dvec3(1.0), {"box", "board", "shooter"});
        const double x = 0.5 + gap, h = 0.1;
        const std::vector<dvec3> board{{x, 0.5 - h, 0.5 - h},
                                       {x, 0.5 + h, 0.5 - h},
                                       {x, 0.5 + h, 0.5 + h},
                                       {x, 0.5 - h, 0.5 + h}};
        add_facing(scene, board, {-1, 0, 0}, 1); // 6, facing the patch
        add_facing(scene, board, {1, 0, 0}, 1);  // 7, its back
        const double s = 0.05;
        add_facing(scene,
                   {{0.5, 0.5 - s, 0.5 - s},
                    {0.5, 0.5 + s, 0.5 - s},
                    {0.5, 0.5 + s, 0.5 + s},
                    {0.5, 0.5 - s, 0.5 + s}},
                   {1, 0, 0}, 2); // 8, the patch
        make_two_sided(scene, [](std::uint32_t p) { return p == 6 || p == 7; });
        finish_scene(scene, "test");
        EXPECT_EQ(scene.polygons.size(), 9u) << "the two faces are each other's back";
        const auto [row, board_share] =
            whole_polygon_row(scene, 8, [](std::uint32_t p) { return p == 6 || p == 7; });
        std::printf("patch %.2f from a board modelled by both faces: row %.5f (the board %.5f)\n",
                    gap, row, board_share);
        EXPECT_GT(board_share, 0.05) << "the board must take a fair share for the test to mean "
                                        "anything";
        EXPECT_LE(row, 1.001) << "at " << gap;
    }
}

// --- polygons that no pixel shows ----------------------------------------------------------
// A square of side 2 `half` centred on c, facing `normal` (an axis).
std::vector<dvec3> facing_square(const dvec3& c, const dvec3& normal, double half) {
    const dvec3 a = std::abs(normal.x) > 0.5 ? dvec3(0, 1, 0) : dvec3(1, 0, 0);
    const dvec3 b = glm::cross(normal, a);
    std::vector<dvec3> v{c - half * a - half * b, c + half * a - half * b, c + half * a + half * b,
                         c - half * a + half * b};
    if (glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), normal) < 0) std::swap(v[1], v[3]);
    return v;
}

// A closed box 2 mm wide with walls 0.5 mm thick (its outer faces facing out, its inner faces
// facing in), 1 m above a 2 m floor that shoots: at 64 x 64 a pixel there is about 3 cm, so
// the box falls between pixel centres and every face of it is linked, if at all, as a polygon
// that no pixel shows, whole, where its centre is seen. The depth map shows nothing around the
// box, so it saw the inner faces' centres too, and the floor's light went inside the closed
// box (in the office glb: into a tea container on a shelf, from the LED bars). The segment to
// an inner face crosses the box's wall: only the outer faces towards the floor are linked.
TEST(MissedPolygons, TheInsideOfAClosedBoxSmallerThanAPixelGetsNothing) {
    const dvec3 c(0.1234, 1.0, -0.0567);
    const double outer = 1e-3, inner = 0.5e-3;
    std::vector<std::vector<dvec3>> polys{facing_square(dvec3(0.0), dvec3(0, 1, 0), 1.0)};
    std::vector<std::string> groups{"floor"};
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            dvec3 n(0.0);
            n[axis] = side;
            polys.push_back(facing_square(c + outer * n, n, outer));  // out
            polys.push_back(facing_square(c + inner * n, -n, inner)); // in
            groups.push_back("out");
            groups.push_back("in");
        }
    const Scene scene = make_scene(polys, groups);
    ASSERT_GT(scene.polygons[0].normal.y, 0.99);
    const std::vector<Link> links = hybrid_links(scene, whole_polygon_shooter(scene, 0), 64);
    // The outer faces that face the floor's centre: the bottom, and (the box stands off the
    // centre at x > 0, z < 0) the sides facing -x and +z.
    int outer_linked = 0;
    for (const Link& l : links) {
        const std::uint32_t p = l.receiver.polygon;
        EXPECT_EQ(scene.groups[scene.polygons[p].group], "out") << "polygon " << p;
        if (scene.groups[scene.polygons[p].group] == "out") {
            EXPECT_LT(glm::dot(scene.polygons[p].normal, c), 0) << "polygon " << p;
            EXPECT_GT(l.ff, 0.f);
            ++outer_linked;
        }
    }
    EXPECT_EQ(outer_linked, 3);
}

// --- a point cluster whose centre lies inside a closed jar ---------------------------------
// A point cluster shoots from the centre of its polygons. That of a jar and the lit board over
// it lies inside the jar (the office glb's tea container on its shelf), and the point sees the
// jar's inner faces, which face it and are drawn; merged lobe planes let its light onto them
// (here the cluster has no planes: every receiver passes share_in_front). Yet neither the
// jar's outer faces nor the board, whose light it is, see any of them (share_seen): a jar 0.2
// wide with walls 0.02 thick on a 2 m floor, a board 0.3 wide 0.1 over it facing down with
// half the light. The inner faces get nothing, and the point, all of whose light went there, is
// reported enclosed (the solver refuses it; its halves shoot). Before, the inner faces took
// all of it (in the office glb the container's inside read 1.5 % of the room's median, where
// the reference reads 0).
TEST(PointCluster, TheInsideOfAJarItsCentreIsInGetsNothing) {
    const dvec3 c(0.0123, 0.5, -0.0234);
    const double outer = 0.1, inner = 0.08;
    std::vector<std::vector<dvec3>> polys{facing_square(dvec3(0.0), dvec3(0, 1, 0), 1.0),
                                          facing_square(c + dvec3(0, 0.2, 0), {0, -1, 0}, 0.15)};
    std::vector<std::string> groups{"floor", "board"};
    ClusterShooter cluster;
    cluster.centre = c;
    cluster.radius = std::hypot(0.2, 0.15);
    cluster.unshot_power = 1;
    cluster.sources = {{1, 0.5, true}}; // the centre is behind them all (the solver's marking)
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            dvec3 n(0.0);
            n[axis] = side;
            cluster.sources.push_back({std::uint32_t(polys.size()), 0.5 / 6, true});
            polys.push_back(facing_square(c + outer * n, n, outer));  // out
            polys.push_back(facing_square(c + inner * n, -n, inner)); // in
            groups.push_back("out");
            groups.push_back("in");
            cluster.normals.push_back(n);
            cluster.weights.push_back(side < 0 && axis == 1 ? 0.5 + 0.5 / 6 : 0.5 / 6);
        }
    for (std::uint32_t p = 1; p < polys.size(); ++p) cluster.members.push_back(p);
    const Scene scene = make_scene(polys, groups);
    ASSERT_GT(scene.polygons[0].normal.y, 0.99);
    ASSERT_LT(scene.polygons[1].normal.y, -0.99);
    auto provider = gpu_provider("hybrid", scene, whole_polygons(scene), 256);
    std::vector<Link> links;
    provider->shoot_cluster(cluster, links);
    for (const Link& l : links)
        EXPECT_NE(scene.groups[scene.polygons[l.receiver.polygon].group], "in")
            << "polygon " << l.receiver.polygon << " ff " << l.ff;
    EXPECT_GT(provider->last_backface_fraction(), 0.5);
}

// The rays of share_seen aim at the source's point nearest the receiver, and at its centroid
// only if that is blocked: a panel 4 mm in front of a lit board, with a rib in the gap between
// the panel's centre and the board's centroid (in the office glb, desk panels a few millimetres
// from the lit parts they face), sees the board straight across. Aimed at the centroid alone,
// the panel got none of the light and the point's light went elsewhere.
TEST(PointCluster, APanelAcrossAGapSeesItsLight) {
    const std::vector<std::vector<dvec3>> polys{
        facing_square({0, 0.5, 0}, {0, 0, 1}, 0.2),         // the lit board
        facing_square({0.25, 0.5, 0.004}, {0, 0, -1}, 0.1), // the panel across the gap
        {{0.1, 0.3, 0.0005}, {0.1, 0.7, 0.0005}, {0.1, 0.7, 0.0035}, {0.1, 0.3, 0.0035}}};
    const Scene scene = make_scene(polys, {"board", "panel", "rib"});
    ASSERT_EQ(scene.polygons.size(), 3u);
    ClusterShooter cluster;
    cluster.centre = {0, 0.5, -0.05}; // behind the board, as a cluster's centre may lie
    cluster.radius = 0.3;
    cluster.unshot_power = 1;
    cluster.normals = {{0, 0, 1}};
    cluster.weights = {1.0};
    cluster.members = {0};
    cluster.sources = {{0, 1.0, true}}; // the centre is behind it
    auto provider = gpu_provider("hybrid", scene, whole_polygons(scene), 256);
    std::vector<Link> links;
    provider->shoot_cluster(cluster, links);
    double panel = 0;
    for (const Link& l : links)
        if (l.receiver.polygon == 1) panel += double(l.ff);
    EXPECT_GT(panel, 0.0);
    EXPECT_LT(provider->last_backface_fraction(), 0.5);
}

} // namespace
