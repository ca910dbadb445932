// Scene model: polygon validation, derived quantities, content hash.
#include "hemirad/scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>

#include "hemirad/error.h"

namespace hemirad {

dvec3 Material::exitance() const { return std::numbers::pi * Ke; }

dvec3 Polygon::centroid() const {
    dvec3 c(0.0);
    for (int i = 0; i < count; ++i) c += v[i];
    return c / double(count);
}

namespace {

// Newell's method: robust normal (unnormalised, length = 2 * area) of a planar polygon.
dvec3 newell(const std::vector<dvec3>& c) {
    dvec3 n(0.0);
    for (std::size_t i = 0; i < c.size(); ++i) {
        const dvec3& a = c[i];
        const dvec3& b = c[(i + 1) % c.size()];
        n += dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return n;
}

bool add_triangle(Scene& s, const dvec3& a, const dvec3& b, const dvec3& c, std::uint32_t material,
                  std::uint32_t group) {
    const dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    const double scale = std::max({glm::length(b - a), glm::length(c - a), glm::length(c - b)});
    if (!(len > 1e-12 * scale * scale) || scale == 0) return false;
    Polygon p;
    p.v = {a, b, c, dvec3(0.0)};
    p.count = 3;
    p.normal = n / len;
    p.area = 0.5 * len;
    p.material = material;
    p.group = group;
    s.polygons.push_back(p);
    return true;
}

} // namespace

AddResult add_polygon(Scene& s, const std::vector<dvec3>& corners, std::uint32_t material,
                      std::uint32_t group, double planarity_tolerance) {
    AddResult r;
    for (const dvec3& c : corners)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(c[k])) {
                std::ostringstream m;
                m << "non-finite vertex coordinate (" << c.x << ", " << c.y << ", " << c.z << ")";
                throw InputError(m.str());
            }
    // Drop repeated consecutive corners.
    std::vector<dvec3> v;
    for (const dvec3& c : corners)
        if (v.empty() || glm::length(c - v.back()) > 0) v.push_back(c);
    while (v.size() > 1 && glm::length(v.front() - v.back()) == 0) v.pop_back();
    if (v.size() < 3) { r.degenerate = true; return r; }
    if (v.size() == 3) {
        r.added = add_triangle(s, v[0], v[1], v[2], material, group) ? 1 : 0;
        r.degenerate = r.added == 0;
        return r;
    }
    if (v.size() > 4) {
        // Larger polygons: fan triangulation (convex polygons are expected).
        r.split = true;
        for (std::size_t i = 1; i + 1 < v.size(); ++i)
            r.added += add_triangle(s, v[0], v[i], v[i + 1], material, group) ? 1 : 0;
        r.degenerate = r.added == 0;
        return r;
    }
    const dvec3 nn = newell(v);
    const double len = glm::length(nn);
    double scale = 0;
    for (int i = 0; i < 4; ++i) scale = std::max(scale, glm::length(v[(i + 1) % 4] - v[i]));
    if (!(len > 1e-12 * scale * scale)) { r.degenerate = true; return r; }
    const dvec3 n = nn / len;
    // Planar: every corner within tolerance (relative to size) of the mean plane.
    const dvec3 centre = (v[0] + v[1] + v[2] + v[3]) / 4.0;
    bool planar = true;
    for (const dvec3& c : v)
        if (std::abs(glm::dot(c - centre, n)) > planarity_tolerance * scale) planar = false;
    // Convex: every corner turns the same way as the normal.
    bool convex = true;
    for (int i = 0; i < 4; ++i) {
        const dvec3 e0 = v[(i + 1) % 4] - v[i], e1 = v[(i + 2) % 4] - v[(i + 1) % 4];
        if (glm::dot(glm::cross(e0, e1), n) <= 0) convex = false;
    }
    if (!planar || !convex) {
        r.split = true;
        // Split along the shorter diagonal, the better-shaped pair of triangles.
        if (glm::length(v[2] - v[0]) <= glm::length(v[3] - v[1])) {
            r.added += add_triangle(s, v[0], v[1], v[2], material, group);
            r.added += add_triangle(s, v[0], v[2], v[3], material, group);
        } else {
            r.added += add_triangle(s, v[0], v[1], v[3], material, group);
            r.added += add_triangle(s, v[1], v[2], v[3], material, group);
        }
        r.degenerate = r.added == 0;
        return r;
    }
    Polygon p;
    for (int i = 0; i < 4; ++i) p.v[i] = v[i];
    p.count = 4;
    p.normal = n;
    p.area = 0.5 * len;
    p.material = material;
    p.group = group;
    s.polygons.push_back(p);
    r.added = 1;
    return r;
}

void finish_scene(Scene& s, const std::string& origin) {
    if (s.polygons.empty())
        throw InputError(origin, 0, "the scene has no polygons (nothing to solve)");
    const dvec3 power = s.emitted_power();
    if (!(power.x > 0 || power.y > 0 || power.z > 0))
        s.warnings.push_back(s.luminaires.empty()
                                 ? std::string(kNoEmitterWarning) +
                                       " (every Ke is 0): the solution will be black"
                                 : std::string(kNoEmitterWarning) +
                                       ", nor does a luminaire: the solution will be black");
    // No camera is made up here: default_camera() (render.h) frames a scene without one.
}

dvec3 Scene::emitted_power() const {
    return surface_power() + luminaire_power();
}

dvec3 Scene::surface_power() const {
    dvec3 p(0.0);
    for (const Polygon& q : polygons) p += materials[q.material].exitance() * q.area;
    return p;
}

dvec3 Scene::luminaire_power() const {
    double w = 0;
    for (const Luminaire& l : luminaires) w += l.power();
    return dvec3(w);
}

double Scene::total_area() const {
    double a = 0;
    for (const Polygon& q : polygons) a += q.area;
    return a;
}

double Scene::max_reflectance() const {
    double m = 0;
    for (const Polygon& q : polygons) {
        const dvec3& r = materials[q.material].rho;
        m = std::max({m, r.x, r.y, r.z});
    }
    return m;
}

Bounds Scene::bounds() const {
    Bounds b;
    for (const Polygon& q : polygons)
        for (int i = 0; i < q.count; ++i) b.extend(q.v[i]);
    return b;
}

std::size_t Scene::triangle_count() const {
    std::size_t n = 0;
    for (const Polygon& q : polygons) n += q.is_triangle();
    return n;
}

std::size_t Scene::quad_count() const { return polygons.size() - triangle_count(); }

int Scene::find_group(const std::string& name) const {
    for (std::size_t i = 0; i < groups.size(); ++i)
        if (groups[i] == name) return int(i);
    return -1;
}

std::uint64_t Scene::content_hash() const {
    std::uint64_t h = 1469598103934665603ull;
    const auto mix = [&h](const void* data, std::size_t size) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    for (const Polygon& p : polygons) {
        mix(&p.count, sizeof p.count);
        for (int i = 0; i < p.count; ++i) mix(&p.v[i], sizeof(dvec3));
        mix(&p.material, sizeof p.material);
        mix(&p.group, sizeof p.group);
    }
    for (const Material& m : materials) {
        mix(&m.rho, sizeof m.rho);
        mix(&m.Ke, sizeof m.Ke);
    }
    // Luminaires change the solution: their placement and distribution count (none: the hash
    // of a scene without luminaires is what it always was).
    for (const Luminaire& l : luminaires) {
        for (const dvec3* v : {&l.position, &l.aim, &l.c0}) mix(v, sizeof(dvec3));
        mix(&l.multiplier, sizeof l.multiplier);
        const CandelaDistribution& d = l.distribution;
        mix(d.gamma.data(), d.gamma.size() * sizeof(double));
        mix(d.c.data(), d.c.size() * sizeof(double));
        mix(d.candela.data(), d.candela.size() * sizeof(double));
        mix(&d.symmetry, sizeof d.symmetry);
    }
    return h;
}

} // namespace hemirad
