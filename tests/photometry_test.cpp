// IES LM-63 reading and type C distributions (photometry.h), against the analytic
// distributions that tests/data/ies/make_ies.py tabulated: intensities, every symmetry of the
// horizontal angles, integrated lumens against stated lumens, the multipliers, and errors that
// name the file, the line and the value.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "hemirad/error.h"
#include "hemirad/photometry.h"

using namespace hemirad;

namespace {

const std::string kDir = std::string(HEMIRAD_TEST_DATA) + "/ies/";
constexpr double kPi = std::numbers::pi;

double cosd(double deg) {
    return std::cos(deg * kPi / 180);
}

// The message of the InputError that parsing `text` as "bad.ies" throws ("" if none).
std::string parse_error(const std::string& text) {
    try {
        parse_ies(text, "bad.ies");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// A valid LM-63-2002 file with the given lines after the format line and keywords.
std::string file_with(const std::string& body) {
    return "IESNA:LM-63-2002\n[TEST] t\n[MANUFAC] m\nTILT=NONE\n" + body;
}

} // namespace

TEST(Ies, ReadsTheHeaderAndTheTable) {
    const IesFile f = read_ies(kDir + "cosine.ies");
    EXPECT_EQ(f.format, "LM-63-2002");
    EXPECT_EQ(f.keyword("MANUFAC"), "hemirad");
    EXPECT_EQ(f.keyword("LUMINAIRE"), "analytic distribution");
    EXPECT_EQ(f.lamps, 1);
    EXPECT_NEAR(f.lumens_per_lamp, 1000 * kPi, 1e-4);
    EXPECT_EQ(f.distribution.gamma.size(), 19u);
    EXPECT_EQ(f.distribution.c.size(), 1u);
    EXPECT_EQ(f.distribution.symmetry, HorizontalSymmetry::Axial);
    EXPECT_DOUBLE_EQ(f.input_watts, 50);
}

TEST(Ies, IntensityIsBilinearAndZeroOutsideTheVerticalRange) {
    const CandelaDistribution& d = read_ies(kDir + "cosine.ies").distribution;
    EXPECT_NEAR(d.intensity(0, 123), 1000, 1e-9);
    EXPECT_NEAR(d.intensity(60, 0), 500, 1e-9);                         // a tabulated angle
    EXPECT_NEAR(d.intensity(62.5, 77), 0.5 * (500 + 422.618262), 1e-9); // halfway
    EXPECT_EQ(d.intensity(90.5, 0), 0.0); // beyond the table: nothing upwards
    // Linear interpolation of cos on 5 degree steps: within 0.1 % of the analytic value where
    // there is light (0.4 % of the peak near 90 degrees).
    for (double g = 0; g < 85; g += 0.7) EXPECT_NEAR(d.intensity(g, 0), 1000 * cosd(g), 1.0) << g;
}

// The integral of the interpolated table against the lumens the file states (cosine.ies:
// I = 1000 cos(gamma) over the lower hemisphere, flux 1000 pi, stated as the lamp lumens).
TEST(Ies, IntegratedLumensMatchTheStatedLumens) {
    const IesFile f = read_ies(kDir + "cosine.ies");
    const double lm = f.distribution.lumens();
    EXPECT_NEAR(lm / f.rated_lumens(), 1.0, 2e-3) << lm << " lm vs stated " << f.rated_lumens();
    // The exact integral of the piecewise-linear interpolant: sum over 5 degree steps of
    // int (linear cos) sin dg, computed here by a fine midpoint rule.
    double fine = 0;
    const int n = 90000;
    for (int k = 0; k < n; ++k) {
        const double g = (k + 0.5) * 90.0 / n;
        fine += f.distribution.intensity(g, 0) * std::sin(g * kPi / 180) * (90.0 / n) * kPi / 180;
    }
    EXPECT_NEAR(lm, 2 * kPi * fine, 1e-6 * lm);
    // Isotropic: 4 pi I.
    EXPECT_NEAR(isotropic_distribution(100).lumens(), 400 * kPi, 1e-9);
}

// Every symmetry of the horizontal angles: the same quadrant-symmetric distribution tabulated
// over 0-90, 0-180, 90-270 and 0-360 must give the same intensity in every direction (the
// interpolants coincide) and the same flux; a bilateral one over 0-180 and 0-360 likewise.
TEST(Ies, EverySymmetryOfHorizontalAnglesGivesTheSameDistribution) {
    const IesFile full = read_ies(kDir + "quad_0_360.ies");
    EXPECT_EQ(full.distribution.symmetry, HorizontalSymmetry::None);
    const struct {
        const char* file;
        HorizontalSymmetry symmetry;
    } cases[] = {{"quad_0_90.ies", HorizontalSymmetry::Quadrant},
                 {"quad_0_180.ies", HorizontalSymmetry::Bilateral},
                 {"quad_90_270.ies", HorizontalSymmetry::Bilateral90}};
    const double lm = full.distribution.lumens();
    EXPECT_NEAR(lm, 1000 * kPi, 2e-3 * 1000 * kPi); // cos 2C integrates to 0 over the circle
    for (const auto& c : cases) {
        const IesFile f = read_ies(kDir + c.file);
        EXPECT_EQ(f.distribution.symmetry, c.symmetry) << c.file;
        EXPECT_NEAR(f.distribution.lumens(), lm, 1e-9 * lm) << c.file;
        for (double g = 0; g <= 90; g += 7.3)
            for (double C = -360; C <= 720; C += 11.7)
                ASSERT_NEAR(f.distribution.intensity(g, C), full.distribution.intensity(g, C), 1e-9)
                    << c.file << " gamma " << g << " C " << C;
    }
    // Spot values against the analytic function (15 degree steps in C: within 2 %).
    const auto quad = [](double g, double C) { return 1000 * cosd(g) * (1 + 0.5 * cosd(2 * C)); };
    for (double C : {0.0, 45.0, 90.0, 135.0, 225.0, 300.0})
        EXPECT_NEAR(full.distribution.intensity(30, C), quad(30, C), 0.02 * quad(30, 0)) << C;

    const IesFile b180 = read_ies(kDir + "bilateral_0_180.ies");
    const IesFile b360 = read_ies(kDir + "bilateral_0_360.ies");
    EXPECT_EQ(b180.distribution.symmetry, HorizontalSymmetry::Bilateral);
    EXPECT_NEAR(b180.distribution.lumens(), b360.distribution.lumens(), 1e-9 * lm);
    for (double g = 0; g <= 90; g += 7.3)
        for (double C = 0; C < 360; C += 11.7)
            ASSERT_NEAR(b180.distribution.intensity(g, C), b360.distribution.intensity(g, C), 1e-9);
    // Not quadrant-symmetric: C = 0 and C = 180 differ (1.3 vs 0.7).
    EXPECT_NEAR(b180.distribution.intensity(0.0001, 0) / b180.distribution.intensity(0.0001, 180),
                1.3 / 0.7, 1e-3);
}

TEST(Ies, MultipliersAndFormats) {
    // LM-63-1995: candela multiplier 2 x ballast factor 0.5 x ballast-lamp factor 0.8.
    const IesFile up = read_ies(kDir + "uplight.ies");
    EXPECT_EQ(up.format, "LM-63-1995");
    EXPECT_DOUBLE_EQ(up.ballast_lamp_factor, 0.8);
    EXPECT_NEAR(up.distribution.intensity(180, 0), 100 * 0.8, 1e-9);
    EXPECT_EQ(up.distribution.intensity(45, 0), 0.0); // the table starts at 90 degrees
    EXPECT_DOUBLE_EQ(up.rated_lumens(), 1000);        // 2 lamps of 500 lm
    // LM-63-1986 (no format line), CR LF line ends, absolute photometry.
    const IesFile abs = read_ies(kDir + "absolute.ies");
    EXPECT_EQ(abs.format, "LM-63-1986");
    EXPECT_EQ(abs.lumens_per_lamp, -1);
    EXPECT_EQ(abs.rated_lumens(), 0);
    EXPECT_NEAR(abs.distribution.lumens(), 400 * kPi, 1e-9);
    // In LM-63-2002 the second value of the ballast line is "future use": not applied.
    const IesFile f =
        parse_ies(file_with("1 -1 1 2 1 1 2 0 0 0\n1 0.5 10\n0 90\n0\n10 10\n"), "t.ies");
    EXPECT_NEAR(f.distribution.intensity(45, 0), 10, 1e-12);
    // Commas as delimiters, values spread over lines anyhow.
    const IesFile g =
        parse_ies(file_with("1,-1,3,2,1,1,2,0,0,0,1,1,10\n0,\n90 0 10\n10\n"), "t.ies");
    EXPECT_NEAR(g.distribution.intensity(0, 0), 30, 1e-12);
}

TEST(Ies, TiltOtherThanNoneIsRefused) {
    for (const char* tilt : {"INCLUDE", "lamp.tlt"}) {
        const std::string e = parse_error(std::string("IESNA:LM-63-2002\n[TEST] t\nTILT=") + tilt +
                                          "\n1\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10 10\n");
        EXPECT_NE(e.find("bad.ies:3:"), std::string::npos) << e;
        EXPECT_NE(e.find(tilt), std::string::npos) << e;
        EXPECT_NE(e.find("only TILT=NONE"), std::string::npos) << e;
    }
}

// Malformed files: each error names the file, the line and the offending value.
TEST(Ies, ErrorsNameFileLineAndValue) {
    const struct {
        std::string body;
        const char* where;
        const char* value;
    } cases[] = {
        // line numbers: 1 format, 2-3 keywords, 4 TILT, 5.. the data
        {"1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 9O\n0\n10 10\n", "bad.ies:7:", "'9O'"},
        {"1 -1 1 2 1 2 2 0 0 0\n1 1 10\n0 90\n0\n10 10\n", "bad.ies:5:", "type B"},
        {"1 -1 1 2 1 3 2 0 0 0\n1 1 10\n0 90\n0\n10 10\n", "bad.ies:5:", "type A"},
        {"1 -1 0 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10 10\n", "bad.ies:5:", "multiplier 0"},
        {"1 -2 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10 10\n", "bad.ies:5:", "-2"},
        {"0 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10 10\n", "bad.ies:5:", "lamps 0"},
        {"1 -1 1 2 1 1 3 0 0 0\n1 1 10\n0 90\n0\n10 10\n", "bad.ies:5:", "units type 3"},
        {"1 -1 1 2 1 1 2 0 0 0\n0 1 10\n0 90\n0\n10 10\n", "bad.ies:6:", "ballast factor 0"},
        {"1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 60 50\n0\n10 10 10\n", "bad.ies:7:", "50"},
        {"1 -1 1 2 1 1 2 0 0 0\n1 1 10\n10 90\n0\n10 10\n", "bad.ies:7:", "vertical angle 10"},
        {"1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 80\n0\n10 10\n", "bad.ies:7:", "vertical angle 80"},
        {"1 -1 1 2 2 1 2 0 0 0\n1 1 10\n0 90\n0 270\n10 10\n10 10\n",
         "bad.ies:8:", "horizontal angle 270"},
        {"1 -1 1 2 2 1 2 0 0 0\n1 1 10\n0 90\n45 90\n10 10\n10 10\n",
         "bad.ies:8:", "horizontal angle 45"},
        {"1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10 -1\n", "bad.ies:9:", "-1"},
        {"1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10\n", "bad.ies:9:", "candela value 2"},
        {"1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10 10 10\n", "bad.ies:9:", "'10' after"},
        {"1 -1 1 2.5 1 1 2 0 0 0\n1 1 10\n0 90\n0\n10 10\n", "bad.ies:5:", "'2.5'"},
    };
    for (const auto& c : cases) {
        const std::string e = parse_error(file_with(c.body));
        EXPECT_NE(e.find(c.where), std::string::npos) << "expected " << c.where << " in: " << e;
        EXPECT_NE(e.find(c.value), std::string::npos) << "expected " << c.value << " in: " << e;
    }
    EXPECT_NE(parse_error("IESNA:LM-63-2002\n[TEST] no tilt\n").find("no TILT="),
              std::string::npos);
    EXPECT_NE(parse_error("IESNA:LM-63-2019\nTILT=NONE\n").find("bad.ies:1:"), std::string::npos);
    try {
        read_ies(kDir + "missing.ies");
        FAIL() << "a missing file was read";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.ies"), std::string::npos);
    }
}

TEST(Photometry, SpotDistribution) {
    const CandelaDistribution s = spot_distribution(1000, 20, 10);
    EXPECT_DOUBLE_EQ(s.intensity(0, 0), 1000);
    EXPECT_DOUBLE_EQ(s.intensity(20, 0), 1000);
    EXPECT_NEAR(s.intensity(25, 0), 500, 1e-9);
    EXPECT_EQ(s.intensity(31, 0), 0.0);
    // Flux: 2 pi [I (1 - cos 20) + int_20^30 I (30 - g)/10 sin g dg].
    double fall = 0;
    for (int k = 0; k < 100000; ++k) {
        const double g = 20 + (k + 0.5) * 1e-4;
        fall += (30 - g) / 10 * std::sin(g * kPi / 180) * 1e-4 * kPi / 180;
    }
    EXPECT_NEAR(s.lumens(), 2 * kPi * 1000 * (1 - cosd(20) + fall), 1e-6 * s.lumens());
    // A hard edge.
    const CandelaDistribution hard = spot_distribution(1000, 30, 0);
    EXPECT_NEAR(hard.lumens(), 2 * kPi * 1000 * (1 - cosd(30)), 1e-3);
    EXPECT_THROW(spot_distribution(1000, 0, 10), InputError);
    EXPECT_THROW(spot_distribution(1000, 170, 20), InputError);
    EXPECT_THROW(spot_distribution(1000, 20, -1), InputError);
}

// A luminaire's frame: gamma from the aim, C counterclockwise seen from above, C = 0 along +x
// for a downlight, turned by `rotation`.
TEST(Photometry, LuminaireOrientation) {
    Luminaire l;
    l.distribution = read_ies(kDir + "bilateral_0_360.ies").distribution; // peak at C = 0
    l.aim = {0, -2, 0};
    l.orient();
    EXPECT_NEAR(glm::length(l.aim), 1, 1e-15);
    EXPECT_NEAR(glm::distance(l.c0, glm::dvec3(1, 0, 0)), 0, 1e-12);
    EXPECT_NEAR(glm::distance(l.c90, glm::dvec3(0, 0, -1)), 0, 1e-12); // x -> -z, from above
    const glm::dvec3 d = glm::normalize(glm::dvec3(1, -1, 0));         // gamma 45, C 0
    EXPECT_NEAR(l.intensity(d), l.distribution.intensity(45, 0), 1e-9);
    const glm::dvec3 e = glm::normalize(glm::dvec3(0, -1, -1)); // gamma 45, C 90
    EXPECT_NEAR(l.intensity(e), l.distribution.intensity(45, 90), 1e-9);
    l.rotation = 90; // C = 0 now along -z
    l.orient();
    EXPECT_NEAR(l.intensity(e), l.distribution.intensity(45, 0), 1e-9);
    l.multiplier = 2;
    EXPECT_NEAR(l.intensity(e), 2 * l.distribution.intensity(45, 0), 1e-9);
    EXPECT_NEAR(l.lumens(), 2 * l.distribution.lumens(), 1e-9);
    // Irradiance: I cos / (683 r^2) at a floor point 2 m below and 1 m aside.
    l.position = {0, 2, 0};
    const glm::dvec3 x(0, 0, -2), up(0, 1, 0);
    const glm::dvec3 w = glm::normalize(x - l.position);
    EXPECT_NEAR(l.irradiance(x, up), l.intensity(w) * (2 / std::sqrt(8.0)) / (683 * 8), 1e-12);
    EXPECT_EQ(l.irradiance(x, -up), 0.0); // behind the surface
    l.aim = {0, 0, 0};
    EXPECT_THROW(l.orient(), InputError);
}
