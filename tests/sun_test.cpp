// The sun's conventions (sun.h) and its SCENE.json syntax: directions from altitude and
// azimuth in the default and in other frames, the solar position at hand-checkable instants,
// and the errors that bad "sun" inputs give (naming the file and the key).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"
#include "hemirad/sun.h"
#include "scene_json_files.h"

using namespace hemirad;

namespace {

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// A folder with a 1 m floor (floor.obj) and SCENE.json with `sun` as its "sun" (and `extra`
// top-level keys); returns the SCENE.json path.
std::string write_scene(const std::string& name, const std::string& sun,
                        const std::string& extra = "") {
    return scene_json_files::write_files(
        "hemirad_sun_test_" + name, {{"floor.obj", scene_json_files::kFloorObj},
                                     {"scene.json", "{\n  \"include\": [\"floor.obj\"],\n" + extra +
                                                        "  \"sun\": " + sun + "\n}\n"}});
}

using scene_json_files::load_error;

} // namespace

// Default frame: up +y, north -z, so east = north x up = +x. Altitude 0 azimuth 90 is east;
// altitude 30 azimuth 90 is (cos 30, sin 30, 0); azimuth 180 is south, +z.
TEST(SunConventions, DefaultFrame) {
    const SkyFrame f;
    expect_near(f.east(), {1, 0, 0}, 1e-15);
    expect_near(f.direction(0, 90), {1, 0, 0}, 1e-15);
    expect_near(f.direction(30, 90), {std::sqrt(3.0) / 2, 0.5, 0}, 1e-15);
    expect_near(f.direction(0, 0), {0, 0, -1}, 1e-15);
    expect_near(f.direction(45, 180), {0, std::sqrt(0.5), std::sqrt(0.5)}, 1e-15);
    expect_near(f.direction(0, 270), {-1, 0, 0}, 1e-15);
    double alt = 0, az = 0;
    f.angles(glm::normalize(glm::dvec3(1, 1, 1)), alt, az);
    EXPECT_NEAR(alt, std::asin(1 / std::sqrt(3.0)) * 180 / M_PI, 1e-12);
    EXPECT_NEAR(az, 135, 1e-12); // between east (+x) and south (+z)
}

// A z-up frame with north +y: east = y x z = +x, as on a map.
TEST(SunConventions, OtherFrame) {
    SkyFrame f;
    f.up = {0, 0, 1};
    f.north = {0, 1, 0};
    expect_near(f.east(), {1, 0, 0}, 1e-15);
    expect_near(f.direction(30, 90), {std::sqrt(3.0) / 2, 0, 0.5}, 1e-15);
    expect_near(f.direction(90, 0), {0, 0, 1}, 1e-15);
}

// Solar position against hand-made values: the 2027 March equinox is at 20:25 UTC on the 20th
// and the June solstice at 14:11 UTC on the 21st (published ephemerides); the declination
// moves 0.3946 degrees a day at an equinox, and is the obliquity, 23.436 degrees, at the
// solstice. So the day's highest sun stands at 90 - |latitude - declination|: lat 45 N on
// March 20 (noon 12:07 UTC, declination -0.138): 44.862 due south; 30 S, 151 E, UTC+10
// (noon 02:03 UTC, declination -0.302): 60.302 due north; 50 N on June 21: 63.436. Found by a
// 1-minute scan (near noon the altitude changes by < 0.001 degrees in a minute). 0.05 degrees:
// the algorithm is good to ~0.01, the hand values to ~0.01.
TEST(SolarPosition, NoonAltitudeAndAzimuth) {
    const auto highest = [](double lat, double lon, int y, int m, int d, double offset) {
        SolarPosition best{-100, 0};
        for (int minute = 0; minute < 24 * 60; ++minute) {
            const SolarPosition p = solar_position(lat, lon, y, m, d, minute / 60.0, offset);
            if (p.altitude_deg > best.altitude_deg) best = p;
        }
        return best;
    };
    SolarPosition p = highest(45, 0, 2027, 3, 20, 0);
    EXPECT_NEAR(p.altitude_deg, 44.862, 0.05);
    EXPECT_NEAR(p.azimuth_deg, 180, 1.0);
    p = highest(-30, 151, 2027, 3, 20, 10);
    EXPECT_NEAR(p.altitude_deg, 60.302, 0.05);
    EXPECT_TRUE(p.azimuth_deg < 1 || p.azimuth_deg > 359) << p.azimuth_deg;
    p = highest(50, 10, 2027, 6, 21, 2);
    EXPECT_NEAR(p.altitude_deg, 63.436, 0.05);
    // Solar noon at longitude 15 E in UTC+1 is at ~12:00 + equation of time (March: +7 min).
    const SolarPosition at_noon = solar_position(45, 15, 2027, 3, 20, 12 + 7.5 / 60, 1);
    EXPECT_NEAR(at_noon.azimuth_deg, 180, 0.5);
    // Equinox sunrise, on the equator at 06:00 local mean time (+7 min): due east.
    const SolarPosition rise = solar_position(0, 0, 2027, 3, 20, 6 + 7.5 / 60, 0);
    EXPECT_NEAR(rise.altitude_deg, 0, 0.5);
    EXPECT_NEAR(rise.azimuth_deg, 90, 0.5);
    EXPECT_THROW(solar_position(0, 0, 2027, 2, 29, 12, 0), InputError); // not a leap year
    EXPECT_THROW(solar_position(0, 0, 2027, 13, 1, 12, 0), InputError);
    EXPECT_THROW(solar_position(0, 0, 2147483647, 1, 1, 12, 0), InputError); // no overflow
    EXPECT_NO_THROW(solar_position(0, 0, 2028, 2, 29, 12, 0));
}

TEST(SunSceneJson, DirectionAndAngles) {
    Scene s = load_scene_json(
        write_scene("direction", "{\"direction\": [1, 1, 0], \"illuminance\": 80000}"));
    ASSERT_TRUE(s.sun.has_value());
    expect_near(s.sun->direction, glm::normalize(glm::dvec3(1, 1, 0)), 1e-15);
    EXPECT_NEAR(s.sun->altitude_deg, 45, 1e-12);
    EXPECT_NEAR(s.sun->azimuth_deg, 90, 1e-12);
    EXPECT_NEAR(s.sun->normal_irradiance(), 80000 / 683.0, 1e-9);
    s = load_scene_json(
        write_scene("angles", "{\"altitude\": 30, \"azimuth\": 90, \"illuminance\": 1000}"));
    expect_near(s.sun->direction, {std::sqrt(3.0) / 2, 0.5, 0}, 1e-15);
    // Another frame: z up, north +x; azimuth 90 is then east = x cross z = -y.
    s = load_scene_json(write_scene("frame",
                                    "{\"altitude\": 0.5, \"azimuth\": 90, \"illuminance\": 1000}",
                                    "  \"up\": [0, 0, 2], \"north\": [1, 0, 0],\n"));
    EXPECT_NEAR(s.sun->direction.y, -std::cos(0.5 * M_PI / 180), 1e-12);
    s = load_scene_json(write_scene(
        "place", "{\"latitude\": 45, \"longitude\": 15, \"date\": \"2027-03-20\", \"time\": "
                 "\"12:07:30\", \"utc_offset\": 1, \"illuminance\": 90000}"));
    EXPECT_NEAR(s.sun->altitude_deg, 45, 0.5);
    EXPECT_NEAR(s.sun->azimuth_deg, 180, 0.5);
    EXPECT_NEAR(s.sun->direction.z, std::cos(45 * M_PI / 180), 0.01); // south is +z
}

// Below the horizon: a warning, and the sun delivers nothing (normal_irradiance() is 0).
TEST(SunSceneJson, BelowTheHorizonWarnsAndIsDark) {
    const Scene s =
        load_scene_json(write_scene("below", "{\"direction\": [0, -1, 1], \"illuminance\": 5}"));
    ASSERT_TRUE(s.sun.has_value());
    EXPECT_EQ(s.sun->normal_irradiance(), 0.0);
    EXPECT_EQ(s.sun->irradiance({0, -1, 0}), 0.0);
    bool warned = false;
    for (const std::string& w : s.warnings) warned |= w.find("below the horizon") != w.npos;
    EXPECT_TRUE(warned);
}

// Each bad input names the file and the key.
TEST(SunSceneJson, BadInputsNameTheKey) {
    const struct {
        const char* name;
        const char* sun;
        const char* extra;
        const char* expect; // in the message
    } cases[] = {
        {"zero", "{\"direction\": [0, 0, 0], \"illuminance\": 1}", "", "sun.direction"},
        {"alt", "{\"altitude\": 91, \"azimuth\": 0, \"illuminance\": 1}", "", "sun.altitude"},
        {"neg", "{\"altitude\": 30, \"azimuth\": 0, \"illuminance\": -1}", "", "sun.illuminance"},
        {"nonnum", "{\"altitude\": 30, \"azimuth\": 0, \"illuminance\": \"bright\"}", "",
         "sun.illuminance"},
        {"both", "{\"direction\": [0, 1, 0], \"altitude\": 30, \"illuminance\": 1}", "",
         "not several"},
        {"none", "{\"illuminance\": 1}", "", "not none"},
        {"noE", "{\"direction\": [0, 1, 0]}", "", "'illuminance'"},
        {"onlyalt", "{\"altitude\": 30, \"illuminance\": 1}", "", "'azimuth'"},
        {"unknown", "{\"direction\": [0, 1, 0], \"lux\": 1}", "", "sun.lux"},
        {"date",
         "{\"latitude\": 0, \"longitude\": 0, \"date\": \"2027-02-30\", \"time\": "
         "\"12:00\", \"illuminance\": 1}",
         "", "sun.date"},
        {"time",
         "{\"latitude\": 0, \"longitude\": 0, \"date\": \"2027-02-03\", \"time\": "
         "\"25:00\", \"illuminance\": 1}",
         "", "sun.time"},
        {"lat",
         "{\"latitude\": 100, \"longitude\": 0, \"date\": \"2027-02-03\", \"time\": "
         "\"12:00\", \"illuminance\": 1}",
         "", "sun.latitude"},
        {"up", "{\"direction\": [0, 1, 0], \"illuminance\": 1}", "  \"up\": [0, 0, 0],\n", "up"},
        {"north", "{\"direction\": [0, 1, 0], \"illuminance\": 1}", "  \"north\": [0, 3, 0],\n",
         "north"},
    };
    for (const auto& c : cases) {
        const std::string path = write_scene(std::string("bad_") + c.name, c.sun, c.extra);
        const std::string m = load_error(path);
        EXPECT_NE(m.find(path), std::string::npos) << c.name << ": " << m;
        EXPECT_NE(m.find(c.expect), std::string::npos) << c.name << ": " << m;
    }
}
