// Glazing (glazing.h): the pane's transmittance against the relation Radiance's reference
// manual gives for its `glass` material, its angular fall-off, and the SCENE.json "glazing"
// syntax: the groups' polygons become panes, bad inputs name the file and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hemirad/error.h"
#include "hemirad/glazing.h"
#include "hemirad/scene_io.h"
#include "scene_json_files.h"

using namespace hemirad;

namespace {

// A folder with a room of two groups, "floor" (1 quad) and "glass" (2 triangles), and
// SCENE.json with `glazing` as its "glazing"; returns the SCENE.json path.
std::string write_scene(const std::string& name, const std::string& glazing) {
    return scene_json_files::write_files(
        "hemirad_glazing_test_" + name,
        {{"room.obj", "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nv 0 1 1\nv 1 1 1\n"
                      "g floor\nf 1 2 3 4\ng glass\nf 2 3 6\nf 2 6 5\n"},
         {"scene.json", "{\n  \"include\": [\"room.obj\"],\n  \"glazing\": " + glazing + "\n}\n"}});
}

using scene_json_files::load_error;

} // namespace

// Radiance's reference manual (glass): "the transmissivity tn is related to the
// transmittance Tn by tn = (sqrt(.8402528435 + .0072522239 Tn^2) - .9166530661) /
// .0036261119 / Tn" for n = 1.52. The pane solves that relation its own way (bisection on the
// Fresnel model), so the two must agree.
TEST(Glazing, TransmissivityAsRadianceDocumentsIt) {
    for (const double Tn : {0.1, 0.5, 0.7, 0.88, 0.9}) {
        const double tn =
            (std::sqrt(.8402528435 + .0072522239 * Tn * Tn) - .9166530661) / .0036261119 / Tn;
        const PaneTransmittance p = make_pane_transmittance(Tn);
        EXPECT_TRUE(p.angular);
        // The manual's constants have 10 digits; the difference under the root loses up to 5
        // of them at small Tn: 1e-5 relative.
        EXPECT_NEAR(p.transmissivity, tn, 1e-5 * tn) << Tn;
        EXPECT_NEAR(p.at(1.0), Tn, 1e-12) << Tn;
    }
}

// Clear glass at normal incidence: each surface reflects r = ((n - 1) / (n + 1))^2, the pane
// with its interreflections (1 - r) / (1 + r) = 0.918 for n = 1.52.
TEST(Glazing, ClearGlassLimit) {
    const double r = std::pow((kGlassIndex - 1) / (kGlassIndex + 1), 2);
    EXPECT_NEAR(clear_glass_transmittance(), (1 - r) / (1 + r), 1e-12);
    EXPECT_NEAR(clear_glass_transmittance(), 0.9183, 1e-4);
    // Above it no glass is clear enough: the value applies at every angle.
    const PaneTransmittance open = make_pane_transmittance(1.0);
    EXPECT_FALSE(open.angular);
    EXPECT_EQ(open.at(0.1), 1.0);
}

// The fall-off: flat to about 40 degrees, then down to 0 at grazing incidence; the same at
// either side (|cos|); none when not angular.
TEST(Glazing, AngularFallOff) {
    const PaneTransmittance p = make_pane_transmittance(0.8);
    double last = p.at(1.0);
    for (int deg = 5; deg <= 90; deg += 5) {
        const double t = p.at(std::cos(deg * M_PI / 180));
        EXPECT_LE(t, last + 1e-12) << deg;
        last = t;
    }
    EXPECT_NEAR(p.at(std::cos(30 * M_PI / 180)), 0.8, 0.02);
    EXPECT_LT(p.at(std::cos(75 * M_PI / 180)), 0.6);
    EXPECT_EQ(p.at(0.0), 0.0);
    EXPECT_EQ(p.at(-0.5), p.at(0.5));
    const PaneTransmittance flat = make_pane_transmittance(0.8, false);
    EXPECT_EQ(flat.at(0.2), 0.8);
}

// The glazing groups' polygons leave the surfaces: here the two glass triangles become panes.
TEST(GlazingSceneJson, GroupsBecomePanes) {
    const Scene s = load_scene_json(write_scene("ok", "{\"glass\": 0.7}"));
    ASSERT_EQ(s.polygons.size(), 1u);
    EXPECT_EQ(s.groups[s.polygons[0].group], "floor");
    ASSERT_EQ(s.glazing.size(), 2u);
    for (const GlazingPane& g : s.glazing) {
        EXPECT_EQ(s.groups[g.polygon.group], "glass");
        EXPECT_NEAR(g.transmittance.at(1.0), 0.7, 1e-12);
        EXPECT_TRUE(g.transmittance.angular);
    }
    const Scene flat = load_scene_json(
        write_scene("flat", "{\"glass\": {\"transmittance\": 0.6, \"angular\": false}}"));
    ASSERT_EQ(flat.glazing.size(), 2u);
    EXPECT_FALSE(flat.glazing[0].transmittance.angular);
    EXPECT_EQ(flat.glazing[0].transmittance.at(0.3), 0.6);
    // A panel clearer than glass: loads, with a warning.
    const Scene open = load_scene_json(write_scene("open", "{\"glass\": 0.95}"));
    bool warned = false;
    for (const std::string& w : open.warnings) warned |= w.find("glazing 'glass'") == 0;
    EXPECT_TRUE(warned);
    // The panes are in the scene's hashes.
    EXPECT_NE(s.content_hash(), flat.content_hash());
    EXPECT_NE(s.geometry_hash(), flat.geometry_hash());
}

// Each bad input names the file and the key.
TEST(GlazingSceneJson, BadInputsNameTheKey) {
    const struct {
        const char* name;
        const char* glazing;
        const char* expect; // in the message
    } cases[] = {
        {"list", "[\"glass\"]", "glazing: expected an object"},
        {"group", "{\"glas\": 0.7}", "no surface group 'glas'"},
        {"range", "{\"glass\": 1.5}", "glazing.glass: the transmittance must be in [0, 1]"},
        {"neg", "{\"glass\": -0.1}", "glazing.glass"},
        {"text", "{\"glass\": \"clear\"}", "glazing.glass"},
        {"key", "{\"glass\": {\"tau\": 0.7}}", "glazing.glass.tau"},
        {"none", "{\"glass\": {\"angular\": true}}", "'transmittance'"},
        {"bool", "{\"glass\": {\"transmittance\": 0.7, \"angular\": 1}}", "glazing.glass.angular"},
        {"all", "{\"glass\": 0.7, \"floor\": 0.5}", "no polygons"},
    };
    for (const auto& c : cases) {
        const std::string path = write_scene(c.name, c.glazing);
        const std::string m = load_error(path);
        EXPECT_NE(m.find(path), std::string::npos) << c.name << ": " << m;
        EXPECT_NE(m.find(c.expect), std::string::npos) << c.name << ": " << m;
    }
}
