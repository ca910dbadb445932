// Validation scenes (CIE 171:2006 cases) and benchmark rooms (paper 002 §5), built in code.
#include "hemirad/validation_scenes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hemirad/error.h"

namespace hemirad::validation {

namespace {

struct Builder {
    Scene scene;

    std::uint32_t material(const std::string& name, double rho, double exitance = 0) {
        // Emitted radiance Ke = exitance / pi (scene.h: exitance = pi*Ke).
        scene.materials.push_back(Material{name, dvec3(rho), dvec3(exitance / std::numbers::pi)});
        return std::uint32_t(scene.materials.size() - 1);
    }
    std::uint32_t group(const std::string& name) {
        const int g = scene.find_group(name);
        if (g >= 0) return std::uint32_t(g);
        scene.groups.push_back(name);
        return std::uint32_t(scene.groups.size() - 1);
    }
    // A quad whose front faces along `facing` (corner order flipped if needed).
    void quad(std::vector<dvec3> c, const dvec3& facing, std::uint32_t m, std::uint32_t g) {
        const dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
        if (glm::dot(n, facing) < 0) std::reverse(c.begin(), c.end());
        add_polygon(scene, c, m, g);
    }
    // Horizontal rectangle at height y facing up (+1) or down (-1).
    void horizontal(double x0, double x1, double z0, double z1, double y, int up, std::uint32_t m,
                    std::uint32_t g) {
        quad({{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}}, dvec3(0, up, 0), m, g);
    }
    // Closed box [lo, hi], six quads facing outwards.
    void box(const dvec3& lo, const dvec3& hi, std::uint32_t m, std::uint32_t g) {
        horizontal(lo.x, hi.x, lo.z, hi.z, hi.y, +1, m, g);
        horizontal(lo.x, hi.x, lo.z, hi.z, lo.y, -1, m, g);
        quad({{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {lo.x, lo.y, hi.z}},
             dvec3(-1, 0, 0), m, g);
        quad({{hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}},
             dvec3(1, 0, 0), m, g);
        quad({{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}},
             dvec3(0, 0, -1), m, g);
        quad({{lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}},
             dvec3(0, 0, 1), m, g);
    }
    // The inside of a room [0,W] x [0,H] x [0,D]: floor, four walls, and the ceiling, the
    // latter as a frame around `hole` (or whole when hole is null). Materials per surface.
    void room(double W, double H, double D, std::uint32_t floor_m, std::uint32_t wall_m,
              std::uint32_t ceiling_m, const HorizontalRect* hole, bool walls_one_group) {
        horizontal(0, W, 0, D, 0, +1, floor_m, group("floor"));
        const auto gw = [&](const char* name) { return group(walls_one_group ? "walls" : name); };
        quad({{0, 0, 0}, {0, H, 0}, {0, H, D}, {0, 0, D}}, dvec3(1, 0, 0), wall_m, gw("wall_x0"));
        quad({{W, 0, 0}, {W, H, 0}, {W, H, D}, {W, 0, D}}, dvec3(-1, 0, 0), wall_m, gw("wall_x1"));
        quad({{0, 0, 0}, {W, 0, 0}, {W, H, 0}, {0, H, 0}}, dvec3(0, 0, 1), wall_m, gw("wall_z0"));
        quad({{0, 0, D}, {W, 0, D}, {W, H, D}, {0, H, D}}, dvec3(0, 0, -1), wall_m, gw("wall_z1"));
        const auto gc = group("ceiling");
        if (!hole) {
            horizontal(0, W, 0, D, H, -1, ceiling_m, gc);
            return;
        }
        // Frame: two full-width strips (z < z0, z > z1) and two side pieces (x < x0, x > x1).
        horizontal(0, W, 0, hole->z0, H, -1, ceiling_m, gc);
        horizontal(0, W, hole->z1, D, H, -1, ceiling_m, gc);
        horizontal(0, hole->x0, hole->z0, hole->z1, H, -1, ceiling_m, gc);
        horizontal(hole->x1, W, hole->z0, hole->z1, H, -1, ceiling_m, gc);
    }
    Scene finish(const std::string& name, const dvec3& eye, const dvec3& target) {
        Camera cam;
        cam.eye = eye;
        cam.target = target;
        cam.fov_y_deg = 60;
        scene.cameras.push_back(cam);
        scene.source = "validation:" + name;
        finish_scene(scene, scene.source);
        return std::move(scene);
    }
};

constexpr double W = CieRoom::width, H = CieRoom::height, D = CieRoom::depth;

} // namespace

Scene make_cie53_area_source(double exitance) {
    if (!(exitance > 0)) throw InputError("cie53: exitance must be > 0");
    Builder b;
    const auto black = b.material("black", 0.0);
    const auto source = b.material("source", 0.0, exitance);
    b.room(W, H, D, black, black, black, &kCie53Source, false);
    const HorizontalRect& s = kCie53Source;
    b.horizontal(s.x0, s.x1, s.z0, s.z1, s.y, -1, source, b.group("source"));
    return b.finish("cie53", dvec3(2, 1.5, -3), dvec3(2, 1.5, 2));
}

Scene make_cie_room(double rho, const std::vector<Luminaire>& luminaires) {
    if (!(rho >= 0 && rho < 1)) throw InputError("cie room: rho must be in [0, 1)");
    Builder b;
    const auto m = b.material(rho > 0 ? "grey" : "black", rho);
    b.room(W, H, D, m, m, m, nullptr, false);
    b.scene.luminaires = luminaires;
    for (Luminaire& l : b.scene.luminaires) l.orient();
    return b.finish("cie_room", dvec3(2, 1.5, -3), dvec3(2, 1.5, 2));
}

Scene make_cie56_lit_floor(double floor_exitance, bool obstruction) {
    if (!(floor_exitance > 0)) throw InputError("cie56: floor exitance must be > 0");
    Builder b;
    const auto black = b.material("black", 0.0);
    // The floor's own reflectance does not matter (nothing comes back): all else is black.
    const auto floor = b.material("lit_floor", kCie56FloorReflectance, floor_exitance);
    b.room(W, H, D, floor, black, black, nullptr, false);
    if (obstruction) {
        const HorizontalRect& p = kCie57Plate;
        b.horizontal(p.x0, p.x1, p.z0, p.z1, p.y, +1, black, b.group("plate"));
    }
    return b.finish(obstruction ? "cie57" : "cie56", dvec3(2, 1.5, -3), dvec3(2, 1.5, 2));
}

Scene make_cie58_cube(double rho, double side, double exitance) {
    if (!(rho >= 0 && rho < 1)) throw InputError("cie58: rho must be in [0, 1)");
    if (!(side > 1)) throw InputError("cie58: side must exceed the 1 m source");
    Builder b;
    const auto wall = b.material("wall", rho);
    const auto source = b.material("source", rho, exitance);
    const double c = side / 2;
    const HorizontalRect hole{c - 0.5, c + 0.5, c - 0.5, c + 0.5, side};
    b.room(side, side, side, wall, wall, wall, &hole, true);
    b.horizontal(hole.x0, hole.x1, hole.z0, hole.z1, side, -1, source, b.group("source"));
    return b.finish("cie58", dvec3(c, c, 0.2), dvec3(c, c, side));
}

Scene make_light_room(double rho, double side, double exitance) {
    if (!(rho >= 0 && rho < 1)) throw InputError("light room: rho must be in [0, 1)");
    if (!(side > 0) || !(exitance > 0))
        throw InputError("light room: side and exitance must be positive");
    Builder b;
    const auto wall = b.material("wall", rho);
    const auto light = b.material("light", rho, exitance);
    b.room(side, side, side, wall, wall, wall, nullptr, false);
    const double c = side / 2, w = side / 10, y = side - side / 1000;
    b.horizontal(c - w, c + w, c - w, c + w, y, -1, light, b.group("light"));
    return b.finish("room", dvec3(c, 0.55 * side, 0.02 * side), dvec3(c, 0.45 * side, side));
}

int bench_room_polygons(const BenchRoomOptions& o) {
    return 6 + o.lights + 174 * o.sets + 6 * o.cabinets;
}

Scene make_bench_room(const BenchRoomOptions& o) {
    if (o.sets < 0 || o.lights < 1 || o.cabinets < 0 || !(o.rho >= 0 && o.rho < 1))
        throw InputError("bench room: sets >= 0, lights >= 1, cabinets >= 0, rho in [0, 1)");
    Builder b;
    const auto floor_m = b.material("floor", 0.3);
    const auto wall_m = b.material("wall", o.rho);
    const auto wood = b.material("furniture", 0.5 * o.rho + 0.2);
    const auto light_m = b.material("light", 0.8, 1000.0);
    // Sets on a grid of 4 m x 4 m cells, a 1.5 m margin to the walls for the cabinets.
    const int cols = std::max(1, int(std::ceil(std::sqrt(double(std::max(o.sets, 1))))));
    const int rows = std::max(1, (std::max(o.sets, 1) + cols - 1) / cols);
    const double RW = std::max(8.0, 4.0 * cols + 3.0), RD = std::max(6.0, 4.0 * rows + 3.0);
    const double RH = 3.0;
    b.room(RW, RH, RD, floor_m, wall_m, wall_m, nullptr, true);
    // Lights: a grid under the ceiling (1 cm below it), facing down.
    const auto gl = b.group("lights");
    const int lcols = std::max(1, int(std::ceil(std::sqrt(o.lights * RW / RD))));
    const int lrows = (o.lights + lcols - 1) / lcols;
    for (int i = 0; i < o.lights; ++i) {
        const double cx = RW * (i % lcols + 0.5) / lcols, cz = RD * (i / lcols + 0.5) / lrows;
        b.horizontal(cx - 0.6, cx + 0.6, cz - 0.3, cz + 0.3, RH - 0.01, -1, light_m, gl);
    }
    // Furniture stands 2 mm above the floor so that no face lies in the floor's plane.
    const double e = 0.002;
    const auto gt = b.group("tables"), gc = b.group("chairs");
    for (int s = 0; s < o.sets; ++s) {
        const double cx = 1.5 + 4.0 * (s % cols) + 2.0, cz = 1.5 + 4.0 * (s / cols) + 2.0;
        // Table 1.6 x 0.9 m, top 0.72..0.76 m, legs 5 cm square.
        b.box({cx - 0.8, 0.72, cz - 0.45}, {cx + 0.8, 0.76, cz + 0.45}, wood, gt);
        for (int l = 0; l < 4; ++l) {
            const double lx = cx + (l & 1 ? 0.7 : -0.75), lz = cz + (l & 2 ? 0.35 : -0.4);
            b.box({lx, e, lz}, {lx + 0.05, 0.72, lz + 0.05}, wood, gt);
        }
        // Four chairs, two on each long side, facing the table.
        for (int c = 0; c < 4; ++c) {
            const double x = cx + (c & 1 ? 0.2 : -0.6);
            const int side = c & 2 ? 1 : -1;
            const double z = cz + side * 0.85 - 0.2; // seat 0.4 x 0.4, centre 0.85 from table axis
            b.box({x, 0.42, z}, {x + 0.4, 0.45, z + 0.4}, wood, gc);
            const double bz = side > 0 ? z + 0.37 : z;
            b.box({x, 0.45, bz}, {x + 0.4, 0.9, bz + 0.03}, wood, gc);
            for (int l = 0; l < 4; ++l) {
                const double lx = x + (l & 1 ? 0.36 : 0.0), lz = z + (l & 2 ? 0.36 : 0.0);
                b.box({lx, e, lz}, {lx + 0.04, 0.42, lz + 0.04}, wood, gc);
            }
        }
    }
    // Cabinets 1.0 x 0.4 x 1.8 m, evenly along the perimeter, 5 cm off the walls.
    const auto gk = b.group("cabinets");
    const double perimeter = 2 * (RW + RD);
    for (int k = 0; k < o.cabinets; ++k) {
        double t = perimeter * (k + 0.5) / o.cabinets;
        dvec3 lo, hi;
        if (t < RW - 1.2) { // along z = 0
            const double x = std::clamp(t, 0.1, RW - 1.1);
            lo = {x, e, 0.05}, hi = {x + 1.0, 1.8, 0.45};
        } else if ((t -= RW) < RD - 1.2) { // along x = RW
            const double z = std::clamp(t, 0.1, RD - 1.1);
            lo = {RW - 0.45, e, z}, hi = {RW - 0.05, 1.8, z + 1.0};
        } else if ((t -= RD) < RW - 1.2) { // along z = RD
            const double x = std::clamp(RW - 1.0 - t, 0.1, RW - 1.1);
            lo = {x, e, RD - 0.45}, hi = {x + 1.0, 1.8, RD - 0.05};
        } else { // along x = 0
            t -= RW;
            const double z = std::clamp(RD - 1.0 - t, 0.1, RD - 1.1);
            lo = {0.05, e, z}, hi = {0.45, 1.8, z + 1.0};
        }
        b.box(lo, hi, wood, gk);
    }
    Scene s = b.finish("bench_room", dvec3(0.3, 2.2, 0.3), dvec3(RW / 2, 0.6, RD / 2));
    HEMIRAD_CHECK(int(s.polygons.size()) == bench_room_polygons(o));
    return s;
}

Scene make_furnished_floor(long triangles) {
    if (triangles < 1000 || triangles > 100000000)
        throw InputError("furnished floor: triangles must be in [1000, 1e8], not " +
                         std::to_string(triangles));
    // Two triangles per quad: 2 * (6 + sets/4 + 174 sets + 6 sets/8) ~ triangles.
    const int sets = std::max(1, int(std::lround((triangles / 2.0 - 6.0) / 175.0)));
    const BenchRoomOptions o{sets, std::max(6, sets / 4), std::max(7, sets / 8), 0.6};
    const Scene quads = make_bench_room(o);
    Scene s;
    s.source = "validation:furnished_floor";
    s.materials = quads.materials;
    s.groups = quads.groups;
    s.cameras = quads.cameras;
    s.polygons.reserve(2 * quads.polygons.size());
    for (const Polygon& p : quads.polygons) {
        if (p.is_triangle()) {
            add_polygon(s, {p.v[0], p.v[1], p.v[2]}, p.material, p.group);
            continue;
        }
        add_polygon(s, {p.v[0], p.v[1], p.v[2]}, p.material, p.group);
        add_polygon(s, {p.v[0], p.v[2], p.v[3]}, p.material, p.group);
    }
    finish_scene(s, s.source);
    return s;
}

} // namespace hemirad::validation
