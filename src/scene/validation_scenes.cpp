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

Scene make_cavity_room(double rho, bool split) {
    if (!(rho >= 0 && rho < 1)) throw InputError("cavity room: rho must be in [0, 1)");
    using C = CavityRoom;
    Builder b;
    const auto wall = b.material("wall", rho);
    const auto light = b.material("light", rho, 1.0);
    const double S = C::side;
    b.room(S, S, S, wall, wall, wall, nullptr, false);
    const double c = S / 2, w = S / 10, y = S - S / 1000;
    b.horizontal(c - w, c + w, c - w, c + w, y, -1, light, b.group("light"));
    b.box(C::slab_lo, C::slab_hi, wall, b.group("slab"));
    b.box(C::sunk_lo, C::sunk_hi, wall, b.group("sunk"));
    b.box(C::hollow_lo, C::hollow_hi, wall, b.group("hollow"));
    // The inner box faces inwards: its six faces, each turned about (corners reversed).
    const std::size_t first = b.scene.polygons.size();
    b.box(C::inner_lo, C::inner_hi, wall, b.group("inner"));
    for (std::size_t p = first; p < b.scene.polygons.size(); ++p) {
        Polygon& q = b.scene.polygons[p];
        std::reverse(q.v.begin() + 1, q.v.begin() + q.count);
        q.normal = -q.normal;
    }
    if (split) split_intersections(b.scene);
    return b.finish("cavity_room", dvec3(c, 0.55 * S, 0.02 * S), dvec3(c, 0.45 * S, S));
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

namespace {

// Triangles as exporters write them, for make_courtyard.
struct Mesher {
    Builder& b;
    // A triangle whose front faces along `facing`.
    void tri(const dvec3& a, dvec3 c1, dvec3 c2, const dvec3& facing, std::uint32_t m,
             std::uint32_t g) {
        if (glm::dot(glm::cross(c1 - a, c2 - a), facing) < 0) std::swap(c1, c2);
        add_polygon(b.scene, {a, c1, c2}, m, g);
    }
    // The planar quad a b c d (corners in order around it) as two triangles.
    void quad(const dvec3& a, const dvec3& c1, const dvec3& c2, const dvec3& d, const dvec3& facing,
              std::uint32_t m, std::uint32_t g) {
        tri(a, c1, c2, facing, m, g);
        tri(a, c2, d, facing, m, g);
    }
    // The parallelogram o + s u + t v (s, t in [0, 1]) in cells of about `cell`.
    void grid(const dvec3& o, const dvec3& u, const dvec3& v, const dvec3& facing, double cell,
              std::uint32_t m, std::uint32_t g) {
        const int nu = std::max(1, int(std::ceil(glm::length(u) / cell - 1e-9)));
        const int nv = std::max(1, int(std::ceil(glm::length(v) / cell - 1e-9)));
        const auto at = [&](int i, int j) {
            return o + (double(i) / nu) * u + (double(j) / nv) * v;
        };
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i)
                quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), facing, m, g);
    }
    // A vertical cylinder (outside out, no caps) about (x, z) from y0 to y1, in `segments`
    // facets around and rings of about `ring` metres.
    void cylinder(double x, double z, double r, double y0, double y1, int segments, double ring,
                  std::uint32_t m, std::uint32_t g) {
        const int rings = std::max(1, int(std::ceil((y1 - y0) / ring)));
        for (int k = 0; k < segments; ++k) {
            const double a0 = 2 * std::numbers::pi * k / segments;
            const double a1 = 2 * std::numbers::pi * (k + 1) / segments;
            const dvec3 d0(std::cos(a0), 0, std::sin(a0)), d1(std::cos(a1), 0, std::sin(a1));
            const dvec3 out = d0 + d1;
            for (int j = 0; j < rings; ++j) {
                const double ya = y0 + (y1 - y0) * j / rings, yb = y0 + (y1 - y0) * (j + 1) / rings;
                const dvec3 c(x, 0, z);
                quad(c + r * d0 + dvec3(0, ya, 0), c + r * d1 + dvec3(0, ya, 0),
                     c + r * d1 + dvec3(0, yb, 0), c + r * d0 + dvec3(0, yb, 0), out, m, g);
            }
        }
    }
    // The five visible faces of a box [lo, hi] (no bottom), two triangles each.
    void block(const dvec3& lo, const dvec3& hi, std::uint32_t m, std::uint32_t g) {
        const dvec3 e = hi - lo;
        grid(lo + dvec3(0, e.y, 0), {e.x, 0, 0}, {0, 0, e.z}, {0, 1, 0}, 1e9, m, g);
        grid(lo, {0, e.y, 0}, {0, 0, e.z}, {-1, 0, 0}, 1e9, m, g);
        grid(lo + dvec3(e.x, 0, 0), {0, e.y, 0}, {0, 0, e.z}, {1, 0, 0}, 1e9, m, g);
        grid(lo, {e.x, 0, 0}, {0, e.y, 0}, {0, 0, -1}, 1e9, m, g);
        grid(lo + dvec3(0, 0, e.z), {e.x, 0, 0}, {0, e.y, 0}, {0, 0, 1}, 1e9, m, g);
    }
    // One storey of an arcade in the plane z in [z0 - t, z0] (the front at z0 faces `front`
    // along z): arches of radius R springing at ys, centred at the bays' centres xc, the wall
    // up to y_front (front face) and y_back (back face). Spandrels: each bay's rectangle minus
    // its half disc, cut along rays from the arch's centre (the rectangle's corners among them).
    void arcade(const std::vector<double>& xc, double bay, double R, double ys, double y_front,
                double y_back, double z0, double t, double front, int steps, std::uint32_t m,
                std::uint32_t g) {
        const double pi = std::numbers::pi;
        for (double x : xc) {
            for (int side = 0; side < 2; ++side) {
                const double z = side == 0 ? z0 : z0 - front * t;
                const double top = side == 0 ? y_front : y_back;
                const dvec3 facing(0, 0, side == 0 ? front : -front);
                std::vector<double> angles;
                for (int k = 0; k <= steps; ++k) angles.push_back(pi * k / steps);
                const double corner = std::atan2(top - ys, bay / 2);
                angles.push_back(corner);
                angles.push_back(pi - corner);
                std::sort(angles.begin(), angles.end());
                const auto boundary = [&](double a) {
                    const dvec3 d(std::cos(a), std::sin(a), 0);
                    double s = 1e300;
                    if (std::abs(d.x) > 1e-12) s = std::min(s, (bay / 2) / std::abs(d.x));
                    if (d.y > 1e-12) s = std::min(s, (top - ys) / d.y);
                    return dvec3(x, ys, z) + s * d;
                };
                for (std::size_t k = 0; k + 1 < angles.size(); ++k) {
                    const double a0 = angles[k], a1 = angles[k + 1];
                    if (a1 - a0 < 1e-9) continue;
                    const dvec3 p0 = dvec3(x + R * std::cos(a0), ys + R * std::sin(a0), z);
                    const dvec3 p1 = dvec3(x + R * std::cos(a1), ys + R * std::sin(a1), z);
                    quad(p0, boundary(a0), boundary(a1), p1, facing, m, g);
                }
            }
            // The arch's underside (intrados), facing its axis.
            for (int k = 0; k < steps; ++k) {
                const double a0 = pi * k / steps, a1 = pi * (k + 1) / steps;
                const dvec3 d0(std::cos(a0), std::sin(a0), 0), d1(std::cos(a1), std::sin(a1), 0);
                const dvec3 c(x, ys, z0);
                const dvec3 back(0, 0, -front * t);
                quad(c + R * d0, c + R * d1, c + R * d1 + back, c + R * d0 + back, -(d0 + d1), m,
                     g);
            }
        }
    }
};

} // namespace

Scene make_courtyard(const CourtyardOptions& o) {
    if (!(o.rho >= 0 && o.rho < 1) || !(o.cell > 0) || o.segments < 6)
        throw InputError("courtyard: rho in [0, 1), cell > 0, segments >= 6");
    Builder b;
    Mesher mesh{b};
    const auto mat = b.material("stone", o.rho);
    const double L = 24, Dc = 10, G = 4; // courtyard x in [0, L], z in [0, Dc]; galleries G deep
    const double H1 = 5, T = 0.3, H2 = 4, Hw = 10; // storeys, slab, wall top
    const double bay = 3, t = 0.5, rc = 0.25, R = bay / 2 - rc;
    const double spring[2] = {3.2, H1 + T + 2.5}; // arches spring here, on each storey
    const double base[2] = {0, H1 + T};
    const double y_roof = H1 + T + H2;
    const double cell = o.cell;
    std::vector<double> bays;
    for (double x = bay / 2; x < L; x += bay) bays.push_back(x);
    const auto floor = b.group("courtyard_floor"), gfloor = b.group("gallery_floors");
    const auto ceil = b.group("gallery_ceilings"), walls = b.group("walls");
    const auto arc = b.group("arcades"), cols = b.group("columns");
    const auto bal = b.group("balustrades"), edge = b.group("slab_edges");
    // One floor under courtyard and galleries; the end walls close everything.
    mesh.grid({0, 0, -G}, {L, 0, 0}, {0, 0, Dc + 2 * G}, {0, 1, 0}, cell, mat, floor);
    mesh.grid({0, 0, -G}, {0, Hw, 0}, {0, 0, Dc + 2 * G}, {1, 0, 0}, cell, mat, walls);
    mesh.grid({L, 0, -G}, {0, Hw, 0}, {0, 0, Dc + 2 * G}, {-1, 0, 0}, cell, mat, walls);
    for (int side = 0; side < 2; ++side) {
        const double f = side == 0 ? 1 : -1;       // the courtyard lies towards +f along z
        const double z0 = side == 0 ? 0 : Dc;      // the arcade's front
        const double zo = side == 0 ? -G : Dc + G; // the outer wall
        const double zb = z0 - f * t;              // the arcade's back
        mesh.grid({0, 0, zo}, {L, 0, 0}, {0, y_roof, 0}, {0, 0, f}, cell, mat, walls);
        // Gallery ceilings (behind the arcade walls) and the upper gallery floor.
        mesh.grid({0, H1, zo}, {L, 0, 0}, {0, 0, zb - zo}, {0, -1, 0}, cell, mat, ceil);
        mesh.grid({0, y_roof, zo}, {L, 0, 0}, {0, 0, zb - zo}, {0, -1, 0}, cell, mat, ceil);
        mesh.grid({0, H1 + T, zo}, {L, 0, 0}, {0, 0, z0 - zo}, {0, 1, 0}, cell, mat, gfloor);
        mesh.grid({0, H1, z0}, {L, 0, 0}, {0, T, 0}, {0, 0, f}, cell, mat, edge);
        for (int storey = 0; storey < 2; ++storey) {
            const double ys = spring[storey];
            const double top_front = storey == 0 ? H1 : Hw;
            const double top_back = storey == 0 ? H1 : y_roof;
            mesh.arcade(bays, bay, R, ys, top_front, top_back, z0, t, f, o.segments, mat, arc);
            // The wall's underside between the arches (over the columns, and at the ends).
            for (std::size_t k = 0; k <= bays.size(); ++k) {
                const double xa = k == 0 ? 0 : bays[k - 1] + R;
                const double xb = k == bays.size() ? L : bays[k] - R;
                mesh.grid({xa, ys, zb}, {xb - xa, 0, 0}, {0, 0, z0 - zb}, {0, -1, 0}, cell, mat,
                          arc);
            }
            if (storey == 1) // the parapet's top, above the upper gallery's roof
                mesh.grid({0, Hw, zb}, {L, 0, 0}, {0, 0, z0 - zb}, {0, 1, 0}, cell, mat, arc);
            // Columns between the bays: shaft sunk 0.3 m into the floor, a base block and a
            // capital under the wall.
            const double zc = z0 - f * t / 2;
            for (std::size_t k = 1; k < bays.size(); ++k) {
                const double x = bays[k] - bay / 2;
                mesh.cylinder(x, zc, rc, base[storey] - 0.3, ys - 0.3, o.segments, 0.5, mat, cols);
                mesh.block({x - 0.35, base[storey] - 0.1, zc - 0.35},
                           {x + 0.35, base[storey] + 0.3, zc + 0.35}, mat, cols);
                mesh.block({x - 0.35, ys - 0.3, zc - 0.35}, {x + 0.35, ys, zc + 0.35}, mat, cols);
            }
            if (storey == 0) continue;
            // The upper storey's balustrade: balusters and a rail between the columns.
            for (std::size_t k = 0; k < bays.size(); ++k) {
                const double xa = bays[k] - bay / 2 + 0.4, xb = bays[k] + bay / 2 - 0.4;
                const double y0 = base[1], y1 = base[1] + 0.9;
                for (double x = xa + 0.12; x < xb - 0.05; x += 0.25)
                    mesh.cylinder(x, zc, 0.05, y0, y1, 8, 0.45, mat, bal);
                mesh.block({xa, y1, zc - 0.12}, {xb, y1 + 0.1, zc + 0.12}, mat, bal);
            }
        }
    }
    b.scene.luminaires.resize(3);
    const dvec3 at[3] = {{L / 2, 7, Dc / 2}, {L / 4, 3.5, -G / 2}, {3 * L / 4, 3.5, Dc + G / 2}};
    const double cd[3] = {3000, 1000, 1000};
    for (int k = 0; k < 3; ++k) {
        Luminaire& l = b.scene.luminaires[std::size_t(k)];
        l.name = "P" + std::to_string(k + 1);
        l.kind = "candela";
        l.position = at[k];
        l.distribution = isotropic_distribution(cd[k]);
        l.orient();
    }
    return b.finish("courtyard", dvec3(1.0, 1.7, -3.0), dvec3(L, 4.0, Dc / 2));
}

} // namespace hemirad::validation
