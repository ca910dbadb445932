// Built-in scenes, available by name without files: cornell, cube, furnace, sphere, room, and the
// validation and benchmark rooms of validation_scenes.h (cie53, cie56, cie57, cie58, room402,
// scene3138).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"
#include "hemirad/validation_scenes.h"

namespace hemirad {

namespace {

struct Builder {
    Scene scene;

    std::uint32_t material(const std::string& name, dvec3 rho, dvec3 Ke = dvec3(0.0)) {
        scene.materials.push_back(Material{name, rho, Ke});
        return std::uint32_t(scene.materials.size() - 1);
    }
    std::uint32_t group(const std::string& name) {
        scene.groups.push_back(name);
        return std::uint32_t(scene.groups.size() - 1);
    }
    // Adds a polygon whose front faces the point `toward` (corner order flipped if needed).
    void add_facing(std::vector<dvec3> corners, const dvec3& toward, std::uint32_t m,
                    std::uint32_t g) {
        dvec3 c(0.0), n(0.0);
        for (const dvec3& p : corners) c += p;
        c /= double(corners.size());
        for (std::size_t i = 0; i < corners.size(); ++i)
            n += glm::cross(corners[i] - c, corners[(i + 1) % corners.size()] - c);
        if (glm::dot(n, toward - c) < 0) std::reverse(corners.begin(), corners.end());
        add_polygon(scene, corners, m, g);
    }
    // A rectangle origin + s*a + t*b (s,t in [0,1]) split into n x n quads, front toward `in`.
    void add_grid(const dvec3& origin, const dvec3& a, const dvec3& b, int n, const dvec3& in,
                  std::uint32_t m, std::uint32_t g) {
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double s0 = double(i) / n, s1 = double(i + 1) / n;
                const double t0 = double(j) / n, t1 = double(j + 1) / n;
                const dvec3 p00 = origin + s0 * a + t0 * b, p10 = origin + s1 * a + t0 * b;
                const dvec3 p11 = origin + s1 * a + t1 * b, p01 = origin + s0 * a + t1 * b;
                const dvec3 c = 0.25 * (p00 + p10 + p11 + p01);
                add_facing({p00, p10, p11, p01}, c + in, m, g);
            }
    }
};

double reflectance(const BuiltinOptions& o, double fallback) {
    if (o.rho < 0) return fallback;
    if (!(o.rho < 1)) throw InputError("--rho " + num(o.rho) + " must be in [0, 1)");
    return o.rho;
}

void check_subdiv(const BuiltinOptions& o) {
    if (o.subdiv < 1 || o.subdiv > 1000)
        throw InputError("--subdiv " + std::to_string(o.subdiv) + " must be in 1..1000");
}

// The original Cornell box (docs/references.md §4), in mm. The light quad lies in the ceiling
// plane in the data; it is lowered by 0.8 mm so that it is a separate surface below it. The
// non-planar left wall is split into two triangles by add_polygon (with a warning).
Scene cornell(const BuiltinOptions& o) {
    Builder b;
    // Reflectances: band means of the measured Cornell spectra (docs/references.md §4).
    const double r = o.rho;
    const dvec3 white = r >= 0 ? dvec3(reflectance(o, 0)) : dvec3(0.734, 0.736, 0.698);
    const dvec3 red = r >= 0 ? dvec3(r) : dvec3(0.576, 0.083, 0.056);
    const dvec3 green = r >= 0 ? dvec3(r) : dvec3(0.133, 0.351, 0.114);
    const auto mw = b.material("white", white);
    const auto mr = b.material("red", red);
    const auto mg = b.material("green", green);
    // Radiance of the light [W sr^-1 mm^-2, relative]: a warm white, common in renderers.
    const auto ml = b.material("light", dvec3(0.78), dvec3(17, 12, 4));
    const dvec3 inside(278, 274.4, 279.6);
    const auto quad = [&](const char* group, std::uint32_t m, std::vector<dvec3> v) {
        b.add_facing(std::move(v), inside, m, b.group(group));
    };
    quad("floor", mw, {{552.8, 0, 0}, {0, 0, 0}, {0, 0, 559.2}, {549.6, 0, 559.2}});
    quad("ceiling", mw, {{556, 548.8, 0}, {556, 548.8, 559.2}, {0, 548.8, 559.2}, {0, 548.8, 0}});
    quad("back_wall", mw,
         {{549.6, 0, 559.2}, {0, 0, 559.2}, {0, 548.8, 559.2}, {556, 548.8, 559.2}});
    quad("right_wall", mg, {{0, 0, 559.2}, {0, 0, 0}, {0, 548.8, 0}, {0, 548.8, 559.2}});
    quad("left_wall", mr, {{552.8, 0, 0}, {549.6, 0, 559.2}, {556, 548.8, 559.2}, {556, 548.8, 0}});
    const double ly = 548.0;
    b.add_facing({{343, ly, 227}, {343, ly, 332}, {213, ly, 332}, {213, ly, 227}},
                 dvec3(278, 0, 280), ml, b.group("light"));
    const auto block = [&](const char* name, double h, std::vector<dvec3> top) {
        const auto g = b.group(name);
        dvec3 centre(0.0);
        for (const dvec3& p : top) centre += p;
        centre = centre / 4.0 - dvec3(0, h / 2, 0);
        b.add_facing(top, centre + dvec3(0, 2 * h, 0), mw, g);
        for (int i = 0; i < 4; ++i) {
            const dvec3 t0 = top[i], t1 = top[(i + 1) % 4];
            const dvec3 b0(t0.x, 0, t0.z), b1(t1.x, 0, t1.z);
            const dvec3 mid = 0.25 * (t0 + t1 + b0 + b1);
            b.add_facing({b0, b1, t1, t0}, mid + (mid - centre), mw, g);
        }
    };
    block("short_block", 165, {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}});
    block("tall_block", 330, {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}});
    for (std::size_t i = 0; i < b.scene.polygons.size(); ++i)
        if (b.scene.polygons[i].is_triangle())
            b.scene.warnings.push_back("group '" + b.scene.groups[b.scene.polygons[i].group] +
                                       "': a non-planar quad (3.2 mm off its plane) was split "
                                       "into 2 triangles");
    // Deduplicate the warning (two triangles, one quad).
    if (b.scene.warnings.size() > 1) b.scene.warnings.resize(1);
    Camera cam;
    cam.eye = dvec3(278, 273, -800);
    cam.target = dvec3(278, 273, 0);
    cam.up = dvec3(0, 1, 0);
    cam.fov_y_deg =
        2 * std::atan(0.0125 / 0.035) * 180 / std::numbers::pi; // 25 mm film, 35 mm lens
    b.scene.cameras.push_back(cam);
    return b.scene;
}

// Unit cube [0,1]^3, six inward faces named x-, x+, y-, y+, z-, z+, each subdiv x subdiv
// quads. `emit_all`: every face emits exitance 1 (the furnace); else only y+ does.
Scene box(const BuiltinOptions& o, bool emit_all) {
    check_subdiv(o);
    Builder b;
    const double rho = reflectance(o, 0.5);
    const dvec3 Ke(1.0 / std::numbers::pi); // exitance pi*Ke = 1 [W unit^-2]
    const auto wall = b.material("wall", dvec3(rho), emit_all ? Ke : dvec3(0.0));
    const auto light = b.material("light", dvec3(rho), Ke);
    const int n = o.subdiv;
    const dvec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1), O(0.0);
    b.add_grid(O, Y, Z, n, X, wall, b.group("x-"));
    b.add_grid(X, Y, Z, n, -X, wall, b.group("x+"));
    b.add_grid(O, X, Z, n, Y, wall, b.group("y-"));
    b.add_grid(Y, X, Z, n, -Y, emit_all ? wall : light, b.group("y+"));
    b.add_grid(O, X, Y, n, Z, wall, b.group("z-"));
    b.add_grid(Z, X, Y, n, -Z, wall, b.group("z+"));
    Camera cam;
    cam.eye = dvec3(0.5, 0.5, -1.2);
    cam.target = dvec3(0.5, 0.5, 0.5);
    cam.fov_y_deg = 50;
    b.scene.cameras.push_back(cam);
    return b.scene;
}

// Unit sphere seen from inside: `rings` latitude bands, 2*rings longitude segments; the
// bands within 30 degrees of the north pole emit exitance 1.
Scene sphere(const BuiltinOptions& o) {
    if (o.sphere_rings < 4 || o.sphere_rings > 512)
        throw InputError("sphere rings " + std::to_string(o.sphere_rings) + " must be in 4..512");
    Builder b;
    const double rho = reflectance(o, 0.5);
    const auto wall = b.material("wall", dvec3(rho));
    const auto cap = b.material("cap", dvec3(rho), dvec3(1.0 / std::numbers::pi));
    const auto gw = b.group("wall");
    const auto gc = b.group("cap");
    const int rings = o.sphere_rings, segs = 2 * rings;
    const auto point = [&](int i, int j) {
        const double th = std::numbers::pi * i / rings, ph = 2 * std::numbers::pi * j / segs;
        return dvec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
    };
    const int cap_rings = std::max(1, int(std::lround(rings / 6.0))); // 30 degrees of 180
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segs; ++j) {
            std::vector<dvec3> c;
            c.push_back(point(i, j));
            c.push_back(point(i + 1, j));
            c.push_back(point(i + 1, j + 1));
            c.push_back(point(i, j + 1));
            // Poles: collapse repeated corners to a triangle.
            std::vector<dvec3> v;
            for (const dvec3& p : c)
                if (v.empty() || glm::length(p - v.back()) > 1e-12) v.push_back(p);
            if (v.size() > 3 && glm::length(v.front() - v.back()) < 1e-12) v.pop_back();
            const bool emits = i < cap_rings;
            b.add_facing(v, dvec3(0.0), emits ? cap : wall, emits ? gc : gw);
        }
    Camera cam;
    cam.eye = dvec3(0, 0, -0.9);
    cam.target = dvec3(0, 0, 1);
    cam.fov_y_deg = 90;
    b.scene.cameras.push_back(cam);
    return b.scene;
}

} // namespace

const char* builtin_names() {
    return "cornell, cube, furnace, sphere, room, cie53, cie56, cie57, cie58, room402, scene3138, "
           "courtyard";
}

bool is_builtin(const std::string& name) {
    for (const char* n : {"cornell", "cube", "furnace", "sphere", "room", "cie53", "cie56", "cie57",
                          "cie58", "room402", "scene3138", "courtyard"})
        if (name == n) return true;
    return false;
}

Scene make_builtin(const std::string& name, const BuiltinOptions& o) {
    namespace v = validation;
    // The validation and benchmark rooms, as the tests and hemirad-bench build them.
    const double floor_exitance = v::kCie56FloorReflectance * v::kCie56FloorIlluminance;
    Scene room;
    if (name == "cie53")
        room = v::make_cie53_area_source();
    else if (name == "cie56")
        room = v::make_cie56_lit_floor(floor_exitance, false);
    else if (name == "cie57")
        room = v::make_cie56_lit_floor(floor_exitance, true);
    else if (name == "cie58")
        room = v::make_cie58_cube(reflectance(o, 0.5));
    else if (name == "room402")
        room = v::make_bench_room({2, 6, 7, 0.6});
    else if (name == "scene3138")
        room = v::make_bench_room({17, 6, 28, 0.6});
    else if (name == "room")
        room = v::make_light_room(reflectance(o, 0.5));
    else if (name == "courtyard")
        room = v::make_courtyard({reflectance(o, 0.5)});
    if (!room.polygons.empty()) {
        room.source = "builtin:" + name;
        return room;
    }
    Scene s;
    if (name == "cornell")
        s = cornell(o);
    else if (name == "cube")
        s = box(o, false);
    else if (name == "furnace")
        s = box(o, true);
    else if (name == "sphere")
        s = sphere(o);
    else
        throw InputError("unknown built-in scene '" + name + "' (built-in: " + builtin_names() +
                         ")");
    s.source = "builtin:" + name;
    finish_scene(s, s.source);
    return s;
}

} // namespace hemirad
