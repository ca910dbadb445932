// point_to_polygon_ff (differential area -> polygon, Lambert/Nusselt contour integral) against
// closed forms from docs/references.md §1(c1), §1(c2).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <ostream>
#include <vector>

#include "hemirad/form_factors.h"

namespace hemirad {
namespace {

constexpr double kPi = std::numbers::pi;

double ff(const dvec3& p, const dvec3& n, const std::vector<dvec3>& c) {
    return point_to_polygon_ff(p, n, c.data(), int(c.size()));
}

// Howell B-3: element parallel to an a x b rectangle at distance c, its normal through a
// corner. X = a/c, Y = b/c.
double howell_b3(double a, double b, double c) {
    const double X = a / c, Y = b / c;
    const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
    return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * kPi);
}

// Howell B-4: element at the origin, normal +z; rectangle in the plane y = d facing it,
// 0 <= x <= L, 0 <= z <= H.
double howell_b4(double H, double d, double L) {
    const double s = std::sqrt(H * H + d * d);
    return (std::atan(L / d) - d / s * std::atan(L / s)) / (2 * kPi);
}

// Element at distance h from the plane of a disk of radius r, offset a from its axis.
double disk_off_axis(double r, double h, double a) {
    const double s = h * h + a * a + r * r;
    return 0.5 * (1 - (h * h + a * a - r * r) / std::sqrt(s * s - 4 * a * a * r * r));
}

std::vector<dvec3> rect_z(double x0, double x1, double y0, double y1, double z) {
    return {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
}

// --- B-3 -------------------------------------------------------------------------------

struct B3Case {
    double a, b, c;
};
void PrintTo(const B3Case& c, std::ostream* os) {
    *os << "a=" << c.a << " b=" << c.b << " c=" << c.c;
}
class HowellB3 : public ::testing::TestWithParam<B3Case> {};

TEST_P(HowellB3, MatchesClosedForm) {
    const auto [a, b, c] = GetParam();
    const double expected = howell_b3(a, b, c);
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, rect_z(0, a, 0, b, c)), expected, 1e-12);
    // Orientation does not matter: the same rectangle listed clockwise.
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, {{0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c}}), expected,
                1e-12);
}

INSTANTIATE_TEST_SUITE_P(Catalog, HowellB3,
                         ::testing::Values(B3Case{1, 1, 1}, B3Case{2, 1, 1}, B3Case{1, 1, 0.5},
                                           B3Case{3, 4, 2}, B3Case{0.01, 0.02, 10},
                                           B3Case{100, 50, 0.1}));

TEST(HowellB3, TabulatedValues) {
    // docs/references.md §1(c1): the sterad_view_factor doc-test value and the catalog table.
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, rect_z(0, 1, 0, 1, 1)), 0.13853160599489298, 1e-14);
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, rect_z(0, 2, 0, 1, 1)), 0.167375, 5e-7);
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, rect_z(0, 3, 0, 4, 2)), 0.194980, 5e-7);
}

TEST(HowellB3, ElementUnderCentreOfSquare) {
    // 4 * B-3(0.5, 0.5, 1) = 0.239456 (docs/references.md §1(c1)).
    const double f = ff({0.5, 0.5, 0}, {0, 0, 1}, rect_z(0, 1, 0, 1, 1));
    EXPECT_NEAR(f, 4 * howell_b3(0.5, 0.5, 1), 1e-12);
    EXPECT_NEAR(f, 0.239456, 5e-7);
    // 2 x 1 rectangle at 0.5: 0.669500.
    EXPECT_NEAR(ff({1, 0.5, 0}, {0, 0, 1}, rect_z(0, 2, 0, 1, 0.5)), 0.669500, 5e-7);
}

TEST(HowellB3, GeneralPositionByFormFactorAlgebra) {
    // Element under (0.3, -0.2) of the rectangle [0,1]x[0,2] at c = 0.7: inclusion-exclusion
    // of four corner rectangles measured from the foot point.
    const double px = 0.3, py = -0.2, c = 0.7;
    const double expected = howell_b3(1 - px, 2 - py, c) + howell_b3(px, 2 - py, c) -
                            howell_b3(1 - px, -py, c) - howell_b3(px, -py, c);
    EXPECT_NEAR(ff({px, py, 0}, {0, 0, 1}, rect_z(0, 1, 0, 2, c)), expected, 1e-12);
}

// --- B-4 (perpendicular; the rectangle touches the receiver's plane) ---------------------

struct B4Case {
    double H, d, L;
};
void PrintTo(const B4Case& c, std::ostream* os) {
    *os << "H=" << c.H << " d=" << c.d << " L=" << c.L;
}
class HowellB4 : public ::testing::TestWithParam<B4Case> {};

TEST_P(HowellB4, MatchesClosedForm) {
    const auto [H, d, L] = GetParam();
    const std::vector<dvec3> rect{{0, d, 0}, {L, d, 0}, {L, d, H}, {0, d, H}};
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, rect), howell_b4(H, d, L), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Catalog, HowellB4,
                         ::testing::Values(B4Case{1, 1, 1}, B4Case{1, 2, 3}, B4Case{2, 1, 1},
                                           B4Case{0.1, 5, 0.2}, B4Case{10, 0.01, 10}));

TEST(HowellB4, TabulatedValue) {
    const std::vector<dvec3> rect{{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}};
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, rect), 0.05573419700255351, 1e-14);
}

// --- clipping -----------------------------------------------------------------------------

TEST(Clipping, StraddlingRectangleEqualsItsUpperPart) {
    // The B-4 rectangle extended below the receiver's plane (z from -0.7 to H): only the part
    // z >= 0 is seen, so the result is B-4 itself.
    const double H = 1.3, d = 0.8, L = 1.7;
    const std::vector<dvec3> straddling{{0, d, -0.7}, {L, d, -0.7}, {L, d, H}, {0, d, H}};
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, straddling), howell_b4(H, d, L), 1e-12);
}

TEST(Clipping, ClippedByHand) {
    // A tilted triangle crossing the tangent plane; the clipped part is computed independently
    // by cutting the triangle at z = 0 by hand (a quad), and the part below gives 0.
    const dvec3 p(0.1, -0.2, 0), n(0, 0, 1);
    const dvec3 a(-1, 1, -0.5), b(2, 1.5, 1.5), c(0.5, 3, 0.5);
    // Edges a-b and a-c cross z = 0 at t = 0.25 and 0.5.
    const dvec3 ab = a + 0.25 * (b - a), ac = a + 0.5 * (c - a);
    const double whole = ff(p, n, {a, b, c});
    const double upper = ff(p, n, {ab, b, c, ac});
    EXPECT_NEAR(whole, upper, 1e-13);
    EXPECT_GT(whole, 1e-3);
    EXPECT_EQ(ff(p, n, {a, ab, ac}), 0.0); // below the plane but for its edge on it
    // A quad straddling on two sides clips to a pentagon (count + 1 corners).
    const std::vector<dvec3> quad{{-1, 1, -1}, {1, 1, 1}, {1, 2, 1}, {-1, 2, 0.5}};
    const double t1 = 0.5, t2 = 1.0 / 3.0; // (-1,1,-1)->(1,1,1) and (-1,2,0.5)->(-1,1,-1)
    const dvec3 q1 = quad[0] + t1 * (quad[1] - quad[0]);
    const dvec3 q2 = quad[3] + t2 * (quad[0] - quad[3]);
    EXPECT_NEAR(ff(p, n, quad), ff(p, n, {q1, quad[1], quad[2], quad[3], q2}), 1e-13);
}

TEST(Clipping, Degenerate) {
    const dvec3 n(0, 0, 1);
    // Entirely behind the receiver.
    EXPECT_EQ(ff({0, 0, 0}, n, rect_z(-1, 1, -1, 1, -1)), 0.0);
    // Lying in the receiver's tangent plane (coplanar), p inside and outside.
    EXPECT_EQ(ff({0, 0, 0}, n, rect_z(-1, 1, -1, 1, 0)), 0.0);
    EXPECT_EQ(ff({5, 0, 0}, n, rect_z(-1, 1, -1, 1, 0)), 0.0);
    // p on the polygon's plane (edge-on), and on its edge and corner.
    const std::vector<dvec3> wall{{-1, 1, 0}, {1, 1, 0}, {1, 1, 1}, {-1, 1, 1}};
    EXPECT_EQ(ff({0, 1, 0.5}, dvec3(0, 0, 1), wall), 0.0);
    EXPECT_EQ(ff({0, 1, 0}, n, wall), 0.0);
    EXPECT_EQ(ff({-1, 1, 0}, n, wall), 0.0);
    EXPECT_EQ(ff({5, 1, 0.5}, dvec3(-1, 0, 0), wall), 0.0); // in the wall's plane
    // p at a corner of a polygon above it: the corner term vanishes, the rest is finite.
    const double f = ff({0, 0, 0}, n, {{0, 0, 0}, {1, 0, 1}, {0, 1, 1}});
    EXPECT_TRUE(std::isfinite(f));
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
}

// --- disks ------------------------------------------------------------------------------

// An N-gon with the disk's area (circumradius R_N, N/2 R_N^2 sin(2pi/N) = pi r^2), centred on
// the z axis at height h. Each sector of the polygon has exactly the area of the disk's
// sector, so the first-order error (kernel value times area difference) cancels per sector;
// what is left is bounded by |grad K| * sector diameter * |sliver area| summed over sectors:
// N * |grad K| * (2 pi r / N) * r^2 (2 pi / N)^3 / 12 = |grad K| r^3 (2 pi)^4 / (12 N^3),
// with |grad K| <= 1/(pi h^3) for K = cos^2/(pi d^2) (d >= h): 1.5e-10 for r = h = 1,
// N = 4096. The tolerance below is 1e-9 (r/h <= 3 makes it 3^3 larger at most).
std::vector<dvec3> disk(double r, double h, int N) {
    const double R = r * std::sqrt(2 * kPi / (N * std::sin(2 * kPi / N)));
    std::vector<dvec3> c(N);
    for (int k = 0; k < N; ++k)
        c[k] = {R * std::cos(2 * kPi * k / N), R * std::sin(2 * kPi * k / N), h};
    return c;
}

struct DiskCase {
    double r, h, a;
};
void PrintTo(const DiskCase& c, std::ostream* os) {
    *os << "r=" << c.r << " h=" << c.h << " a=" << c.a;
}
class Disk : public ::testing::TestWithParam<DiskCase> {};

TEST_P(Disk, MatchesClosedForm) {
    const auto [r, h, a] = GetParam();
    const double tol = 1e-9 * std::max(1.0, std::pow(r / h, 3));
    EXPECT_NEAR(ff({a, 0, 0}, {0, 0, 1}, disk(r, h, 4096)), disk_off_axis(r, h, a), tol);
}

INSTANTIATE_TEST_SUITE_P(Catalog, Disk,
                         ::testing::Values(DiskCase{1, 1, 0}, DiskCase{1, 2, 0},
                                           DiskCase{0.5, 2, 0}, DiskCase{3, 1, 0},
                                           DiskCase{1, 1, 0.5}, DiskCase{1, 2, 1.5},
                                           DiskCase{0.5, 1, 2.0}));

TEST(Disk, TabulatedValues) {
    EXPECT_NEAR(disk_off_axis(1, 1, 0.5), 0.437983, 5e-7); // the closed form itself
    EXPECT_NEAR(ff({0, 0, 0}, {0, 0, 1}, disk(1, 1, 4096)), 0.5, 1e-9);
    EXPECT_NEAR(ff({0.5, 0, 0}, {0, 0, 1}, disk(1, 1, 4096)), 0.437983, 5e-7);
}

TEST(Disk, TiltedElement) {
    // Element tilted by w about the x axis under a coaxial disk that stays entirely above its
    // tangent plane (tan w < h / r): F = cos w * r^2 / (r^2 + h^2).
    const double r = 1, h = 2;
    for (double w_deg : {0.0, 10.0, 30.0, 60.0}) {
        const double w = w_deg * kPi / 180;
        const dvec3 n(0, std::sin(w), std::cos(w));
        EXPECT_NEAR(ff({0, 0, 0}, n, disk(r, h, 4096)), std::cos(w) * r * r / (r * r + h * h), 1e-9)
            << "tilt " << w_deg;
    }
}

// --- invariances and sums -----------------------------------------------------------------

TEST(Invariance, RigidMotion) {
    // Rotate and translate a B-3 configuration: the result must not change.
    const double a = 1.2, b = 0.7, c = 0.9;
    const dvec3 axis = glm::normalize(dvec3(0.3, -0.8, 0.5));
    const double angle = 1.1;
    const auto rot = [&](const dvec3& v) { // Rodrigues
        return v * std::cos(angle) + glm::cross(axis, v) * std::sin(angle) +
               axis * glm::dot(axis, v) * (1 - std::cos(angle));
    };
    const dvec3 shift(10, -3, 7);
    std::vector<dvec3> r;
    for (const dvec3& v : rect_z(0, a, 0, b, c)) r.push_back(rot(v) + shift);
    EXPECT_NEAR(ff(shift, rot({0, 0, 1}), r), howell_b3(a, b, c), 1e-12);
}

TEST(Sum, EnclosureFromInsideIsOne) {
    // An element on the floor of a box sees the other five faces: the form factors sum to 1
    // (they tile its hemisphere). Also from an element on a wall, tilted faces included.
    const double X = 2, Y = 1.5, Z = 1;
    const std::vector<std::vector<dvec3>> faces{
        rect_z(0, X, 0, Y, Z),                        // ceiling
        {{0, 0, 0}, {X, 0, 0}, {X, 0, Z}, {0, 0, Z}}, // y = 0
        {{0, Y, 0}, {X, Y, 0}, {X, Y, Z}, {0, Y, Z}}, // y = Y
        {{0, 0, 0}, {0, Y, 0}, {0, Y, Z}, {0, 0, Z}}, // x = 0
        {{X, 0, 0}, {X, Y, 0}, {X, Y, Z}, {X, 0, Z}}, // x = X
        rect_z(0, X, 0, Y, 0)};                       // floor
    for (const dvec3& p : {dvec3(0.3, 0.2, 0), dvec3(1.9, 1.4, 0), dvec3(1, 0.75, 0)}) {
        double sum = 0;
        for (const auto& f : faces) sum += ff(p, {0, 0, 1}, f);
        EXPECT_NEAR(sum, 1.0, 1e-12);
    }
    double sum = 0;
    for (const auto& f : faces) sum += ff({X, 0.4, 0.3}, {-1, 0, 0}, f);
    EXPECT_NEAR(sum, 1.0, 1e-12);
}

TEST(Sum, SmallAngleAccuracy) {
    // A far, small square: F ~ A cos^2 / (pi d^2) for d >> size; relative error of the
    // far-field approximation is O((size/d)^2), here 1e-10 -- tests the atan2 angle near 0.
    const double s = 1e-3, d = 100;
    const double f = ff({0, 0, 0}, {0, 0, 1}, rect_z(-s / 2, s / 2, -s / 2, s / 2, d));
    EXPECT_NEAR(f / (s * s / (kPi * d * d)), 1.0, 1e-9);
}

// ClusterShooter::share_in_front: a cluster of two slabs facing away from each other (lobe +x,
// its polygons at x >= 0.5; lobe -x, at x <= -0.5), weights 1/2 each. A point beyond a slab
// takes all the light sent towards it; a point between the slabs (inside the object, or
// behind the wall a lobe's polygons cover) none; towards a point along y no lobe emits.
TEST(ClusterLobes, ShareInFrontOfTheLobesPlanes) {
    // Receivers face the centre (the origin); planes without a box pass any receiver.
    const auto facing_origin = [](const dvec3& x) { return -glm::normalize(x); };
    ClusterShooter c;
    c.normals = {{1, 0, 0}, {-1, 0, 0}};
    c.weights = {0.5, 0.5};
    c.planes = {{0, 0.5, 0.5}, {1, 0.5, 0.5}};
    EXPECT_DOUBLE_EQ(c.share_in_front({2, 0, 0}, facing_origin({2, 0, 0}), 1e-9), 1.0);
    EXPECT_DOUBLE_EQ(c.share_in_front({2, 2, 0}, facing_origin({2, 2, 0}), 1e-9), 1.0);
    EXPECT_DOUBLE_EQ(c.share_in_front({-3, 1, 0}, facing_origin({-3, 1, 0}), 1e-9), 1.0);
    EXPECT_DOUBLE_EQ(c.share_in_front({0.2, 0, 0}, facing_origin({0.2, 0, 0}), 1e-9), 0.0)
        << "between the slabs";
    EXPECT_DOUBLE_EQ(c.share_in_front({0.5, 0.1, 0}, facing_origin({0.5, 0.1, 0}), 1e-9), 0.0)
        << "in the +x lobe's plane";
    EXPECT_DOUBLE_EQ(c.share_in_front({0, 2, 0}, facing_origin({0, 2, 0}), 1e-9), 0.0)
        << "no lobe emits along y";
    // Lobes +x and +y (weights 1/2): at (1, 1) the +x lobe's plane is passed, the +y lobe's
    // (its polygons at y >= 3) not: the +x lobe's half of the intensity there.
    c.normals = {{1, 0, 0}, {0, 1, 0}};
    c.planes = {{0, 0.5, 0.5}, {1, 3.0, 0.5}};
    EXPECT_NEAR(c.share_in_front({1, 1, 0}, facing_origin({1, 1, 0}), 1e-9), 0.5, 1e-12);
    c.planes.clear();
    EXPECT_DOUBLE_EQ(c.share_in_front({0.2, 0, 0}, facing_origin({0.2, 0, 0}), 1e-9), 1.0)
        << "no planes: all";
}

// ClusterShooter planes: a cluster whose -x lobe holds a lit wall face (x = 4.9, 99 % of the
// power) and the inner face of the slab's far side (x = 5.1, 1 %), shooting from inside the
// slab (x = 5.05). Kept apart (a gap of 0.2 against 4 mm), a receiver inside the slab
// (x = 5.0) takes only the inner face's 1 %; one plane at their lowest offset (as when a lobe
// had one plane) would give it all. A receiver in the room takes all; one in the room facing
// away from both faces, none.
TEST(ClusterLobes, PlanesAWallApartKeepTheirLightApart) {
    ClusterShooter c;
    c.centre = {5.05, 1.5, 1.5};
    c.normals = {{-1, 0, 0}};
    c.weights = {1.0};
    ClusterShooter::Plane wall{0, -4.9, 0.99, {4.9, 0, 0}, {4.9, 3, 3}};
    ClusterShooter::Plane inner{0, -5.1, 0.01, {5.1, 0, 0}, {5.1, 3, 3}};
    c.add_lobe_planes(0, {wall, inner}, 0.004, 16);
    ASSERT_EQ(c.planes.size(), 2u);
    EXPECT_NEAR(c.share_in_front({5.0, 1.0, 1.5}, {0, 1, 0}, 1e-9), 0.01, 1e-12) << "in the slab";
    EXPECT_NEAR(c.share_in_front({3.0, 1.0, 1.5}, {1, 0, 0}, 1e-9), 1.0, 1e-12) << "the room";
    EXPECT_EQ(c.share_in_front({3.0, 1.0, 1.5}, {-1, 0, 0}, 1e-9), 0.0) << "facing away";
    // Within the gap they share one plane, at the lower offset, with both weights.
    ClusterShooter merged = c;
    merged.planes.clear();
    merged.add_lobe_planes(0, {wall, inner}, 0.5, 16);
    ASSERT_EQ(merged.planes.size(), 1u);
    EXPECT_DOUBLE_EQ(merged.planes[0].offset, -5.1);
    EXPECT_DOUBLE_EQ(merged.planes[0].weight, 1.0);
    EXPECT_NEAR(merged.share_in_front({5.0, 1.0, 1.5}, {0, 1, 0}, 1e-9), 1.0, 1e-12);
    // Over max_planes, the closest neighbours merge first.
    ClusterShooter three;
    three.normals = {{0, 1, 0}};
    three.weights = {1.0};
    three.add_lobe_planes(0, {{0, 0.0, 0.5}, {0, 0.75, 0.25}, {0, 0.8, 0.25}}, 0.001, 2);
    ASSERT_EQ(three.planes.size(), 2u);
    EXPECT_DOUBLE_EQ(three.planes[0].offset, 0.0);
    EXPECT_DOUBLE_EQ(three.planes[1].offset, 0.75);
    EXPECT_DOUBLE_EQ(three.planes[1].weight, 0.5);
}

} // namespace
} // namespace hemirad
