// Scene model: polygon validation, derived quantities, content hash.
#include "hemirad/scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <sstream>

#include "core/geometry.h"
#include "hemirad/error.h"

namespace hemirad {

dvec3 Material::exitance() const {
    return std::numbers::pi * Ke;
}

dvec3 Polygon::centroid() const {
    dvec3 c(0.0);
    for (int i = 0; i < count; ++i) c += v[i];
    return c / double(count);
}

namespace {

/// Keeps Scene::texcoords parallel to the polygons once any polygon has coordinates: the
/// polygon just added gets `uv` (or zeros).
void push_texcoords(Scene& s, const TexCoords* uv) {
    if (!uv && s.texcoords.empty()) return;
    s.texcoords.resize(s.polygons.size() - 1, TexCoords{});
    s.texcoords.push_back(uv ? *uv : TexCoords{});
}

/// Corner texture coordinates for corners i, j, k (, l) of `uv`, or null without.
struct CornerUV {
    const std::vector<glm::dvec2>* uv;
    bool have() const { return uv != nullptr; }
    TexCoords pick(std::initializer_list<std::size_t> idx) const {
        TexCoords t{};
        int n = 0;
        for (std::size_t i : idx) t[std::size_t(n++)] = glm::vec2((*uv)[i]);
        return t;
    }
};

bool add_triangle(Scene& s, const std::vector<dvec3>& v, std::size_t i, std::size_t j,
                  std::size_t k, std::uint32_t material, std::uint32_t group, CornerUV uv) {
    const dvec3 &a = v[i], &b = v[j], &c = v[k];
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
    const TexCoords t = uv.have() ? uv.pick({i, j, k}) : TexCoords{};
    push_texcoords(s, uv.have() ? &t : nullptr);
    return true;
}

} // namespace

AddResult add_polygon(Scene& s, const std::vector<dvec3>& corners, std::uint32_t material,
                      std::uint32_t group, double planarity_tolerance,
                      const std::vector<glm::dvec2>* corner_uv) {
    AddResult r;
    HEMIRAD_CHECK(!corner_uv || corner_uv->size() == corners.size());
    for (const dvec3& c : corners)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(c[k])) {
                std::ostringstream m;
                m << "non-finite vertex coordinate (" << c.x << ", " << c.y << ", " << c.z << ")";
                throw InputError(m.str());
            }
    // Drop repeated consecutive corners (their texture coordinates with them).
    std::vector<dvec3> v;
    std::vector<glm::dvec2> uvs;
    for (std::size_t i = 0; i < corners.size(); ++i)
        if (v.empty() || glm::length(corners[i] - v.back()) > 0) {
            v.push_back(corners[i]);
            if (corner_uv) uvs.push_back((*corner_uv)[i]);
        }
    while (v.size() > 1 && glm::length(v.front() - v.back()) == 0) {
        v.pop_back();
        if (corner_uv) uvs.pop_back();
    }
    const CornerUV uv{corner_uv ? &uvs : nullptr};
    if (v.size() < 3) {
        r.degenerate = true;
        return r;
    }
    if (v.size() == 3) {
        r.added = add_triangle(s, v, 0, 1, 2, material, group, uv) ? 1 : 0;
        r.degenerate = r.added == 0;
        return r;
    }
    if (v.size() > 4) {
        // Larger polygons: fan triangulation (convex polygons are expected).
        r.split = true;
        for (std::size_t i = 1; i + 1 < v.size(); ++i)
            r.added += add_triangle(s, v, 0, i, i + 1, material, group, uv) ? 1 : 0;
        r.degenerate = r.added == 0;
        return r;
    }
    const dvec3 nn = newell_normal(v);
    const double len = glm::length(nn);
    double scale = 0;
    for (int i = 0; i < 4; ++i) scale = std::max(scale, glm::length(v[(i + 1) % 4] - v[i]));
    if (!(len > 1e-12 * scale * scale)) {
        r.degenerate = true;
        return r;
    }
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
            r.added += add_triangle(s, v, 0, 1, 2, material, group, uv);
            r.added += add_triangle(s, v, 0, 2, 3, material, group, uv);
        } else {
            r.added += add_triangle(s, v, 0, 1, 3, material, group, uv);
            r.added += add_triangle(s, v, 1, 2, 3, material, group, uv);
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
    const TexCoords t = uv.have() ? uv.pick({0, 1, 2, 3}) : TexCoords{};
    push_texcoords(s, uv.have() ? &t : nullptr);
    r.added = 1;
    return r;
}

std::uint32_t untextured_material(Scene& scene, std::uint32_t material,
                                  std::map<std::uint32_t, std::uint32_t>& cache) {
    const auto [it, fresh] = cache.try_emplace(material, 0);
    if (fresh) {
        Material copy = scene.materials[material];
        copy.rho *= scene.textures[std::size_t(copy.texture)].mean();
        copy.texture = -1;
        copy.name += " (texture mean)";
        it->second = std::uint32_t(scene.materials.size());
        scene.materials.push_back(copy);
    }
    return it->second;
}

void finish_scene(Scene& s, const std::string& origin) {
    if (s.polygons.empty())
        throw InputError(origin, 0, "the scene has no polygons (nothing to solve)");
    const dvec3 power = s.emitted_power();
    const bool sunlit = (s.sun && s.sun->normal_irradiance() > 0) ||
                        (s.sky && (s.sky->illuminance > 0 || s.sky->ground_luminance() > 0));
    if (!(power.x > 0 || power.y > 0 || power.z > 0) && !sunlit)
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

const Texture* Scene::texture_of(std::uint32_t polygon) const {
    const int t = materials[polygons[polygon].material].texture;
    return t >= 0 && !texcoords.empty() ? &textures[std::size_t(t)] : nullptr;
}

double Scene::max_reflectance() const {
    double m = 0;
    for (std::uint32_t i = 0; i < polygons.size(); ++i) {
        dvec3 r = materials[polygons[i].material].rho;
        if (const Texture* t = texture_of(i)) r *= dvec3(t->max);
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

std::size_t Scene::quad_count() const {
    return polygons.size() - triangle_count();
}

int Scene::find_group(const std::string& name) const {
    for (std::size_t i = 0; i < groups.size(); ++i)
        if (groups[i] == name) return int(i);
    return -1;
}

namespace {

/// FNV-1a 64 over the bytes given (Scene::content_hash(), Scene::geometry_hash()).
struct Fnv1a {
    std::uint64_t h = 1469598103934665603ull;
    void operator()(const void* data, std::size_t size) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) h = (h ^ b[i]) * 1099511628211ull;
    }
};

void mix_textures(Fnv1a& mix, const Scene& s) {
    mix(s.texcoords.data(), s.texcoords.size() * sizeof(TexCoords));
    for (const Texture& t : s.textures) {
        const Texture::Level& l = t.levels[0];
        mix(&l.width, sizeof l.width);
        mix(&l.height, sizeof l.height);
        mix(l.texels.data(), l.texels.size() * sizeof(glm::vec3));
    }
}

/// The sun's direction and normal illuminance (none: nothing, so a scene without a sun hashes
/// as it always did).
void mix_sun(Fnv1a& mix, const std::optional<Sun>& sun) {
    if (!sun) return;
    mix(&sun->direction, sizeof(dvec3));
    const double e = sun->normal_irradiance();
    mix(&e, sizeof e);
}

/// The sky's model, illuminance, ground and sun position (none: nothing, so a scene without a
/// sky hashes as it always did).
void mix_sky(Fnv1a& mix, const std::optional<Sky>& sky) {
    if (!sky) return;
    const auto model = int(sky->model);
    mix(&model, sizeof model);
    for (const double* v : {&sky->illuminance, &sky->ground_reflectance, &sky->sun_horizontal})
        mix(v, sizeof(double));
    mix(&sky->up, sizeof(dvec3));
    const char blend = sky->horizon_blend ? 1 : 0;
    mix(&blend, 1);
    if (sky_needs_sun(sky->model)) mix(&sky->sun, sizeof(dvec3));
}

/// The panes' corners and transmittance (none: nothing, so a scene without glazing hashes as it
/// always did). Both belong to the geometry: incremental re-solving does not edit them.
void mix_glazing(Fnv1a& mix, const std::vector<GlazingPane>& glazing) {
    for (const GlazingPane& g : glazing) {
        mix(&g.polygon.count, sizeof g.polygon.count);
        for (int i = 0; i < g.polygon.count; ++i) mix(&g.polygon.v[i], sizeof(dvec3));
        mix(&g.transmittance.normal, sizeof(double));
        const char angular = g.transmittance.angular ? 1 : 0;
        mix(&angular, 1);
    }
}

/// A luminaire's placement and distribution; its multiplier when `multiplier`.
void mix_luminaire(Fnv1a& mix, const Luminaire& l, bool multiplier) {
    for (const dvec3* v : {&l.position, &l.aim, &l.c0}) mix(v, sizeof(dvec3));
    if (multiplier) mix(&l.multiplier, sizeof l.multiplier);
    const CandelaDistribution& d = l.distribution;
    mix(d.gamma.data(), d.gamma.size() * sizeof(double));
    mix(d.c.data(), d.c.size() * sizeof(double));
    mix(d.candela.data(), d.candela.size() * sizeof(double));
    mix(&d.symmetry, sizeof d.symmetry);
}

} // namespace

std::uint64_t Scene::content_hash() const {
    Fnv1a mix;
    for (const Polygon& p : polygons) {
        mix(&p.count, sizeof p.count);
        for (int i = 0; i < p.count; ++i) mix(&p.v[i], sizeof(dvec3));
        mix(&p.material, sizeof p.material);
        mix(&p.group, sizeof p.group);
        if (p.twin != kNoTwin) mix(&p.twin, sizeof p.twin); // one-sided scenes: as before
    }
    for (const Material& m : materials) {
        mix(&m.rho, sizeof m.rho);
        mix(&m.Ke, sizeof m.Ke);
    }
    // Textures change the solution (none: the hash of an untextured scene is what it was).
    if (!textures.empty() && !texcoords.empty()) {
        for (const Material& m : materials) mix(&m.texture, sizeof m.texture);
        mix_textures(mix, *this);
    }
    // Luminaires change the solution: their placement and distribution count (none: the hash
    // of a scene without luminaires is what it always was).
    for (const Luminaire& l : luminaires) mix_luminaire(mix, l, true);
    mix_sun(mix, sun);
    mix_sky(mix, sky);
    mix_glazing(mix, glazing);
    return mix.h;
}

std::uint64_t Scene::geometry_hash() const {
    Fnv1a mix;
    const bool textured = !textures.empty() && !texcoords.empty();
    for (const Polygon& p : polygons) {
        mix(&p.count, sizeof p.count);
        for (int i = 0; i < p.count; ++i) mix(&p.v[i], sizeof(dvec3));
        mix(&p.group, sizeof p.group);
        mix(&p.twin, sizeof p.twin);
        if (textured) mix(&material_of(p).texture, sizeof(int));
    }
    if (textured) mix_textures(mix, *this);
    for (const Luminaire& l : luminaires) {
        mix(l.name.data(), l.name.size() + 1);
        mix_luminaire(mix, l, false);
    }
    // The sun: incremental re-solving does not edit it, so a solution of another sun is of
    // another scene.
    mix_sun(mix, sun);
    mix_sky(mix, sky);
    mix_glazing(mix, glazing);
    return mix.h;
}

namespace {

/// A polygon's corners as a set, each on a grid of `quantum`, sorted: the same key for two
/// polygons with the same corners in any order and either winding.
std::vector<std::int64_t> corner_key(const Polygon& p, double quantum) {
    std::vector<std::array<std::int64_t, 3>> corners(std::size_t(p.count));
    for (int k = 0; k < p.count; ++k)
        for (int a = 0; a < 3; ++a)
            corners[std::size_t(k)][std::size_t(a)] = std::llround(p.v[k][a] / quantum);
    std::sort(corners.begin(), corners.end());
    std::vector<std::int64_t> key;
    for (const auto& c : corners) key.insert(key.end(), c.begin(), c.end());
    return key;
}

/// The grid corner_key() puts a scene's corners on: a billionth of its largest coordinate
/// (exported float corners that are the same are the same here).
double corner_quantum(const Scene& scene) {
    double extent = 0;
    for (const Polygon& q : scene.polygons)
        for (int k = 0; k < q.count; ++k)
            extent = std::max({extent, std::abs(q.v[k].x), std::abs(q.v[k].y), std::abs(q.v[k].z)});
    return std::max(extent, 1e-300) * 1e-9;
}

} // namespace

std::size_t drop_coincident_polygons(Scene& scene, std::uint32_t* first_group) {
    const double quantum = corner_quantum(scene);
    std::map<std::vector<std::int64_t>, std::vector<std::uint32_t>> by_corners;
    std::vector<char> dropped(scene.polygons.size(), 0);
    std::size_t count = 0;
    // Of two, the one that emits stays (a lamp's face laid on a ceiling's), else the first.
    const auto emits = [&](std::uint32_t p) {
        return scene.material_of(scene.polygons[p]).emits();
    };
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        std::vector<std::uint32_t>& same = by_corners[corner_key(scene.polygons[p], quantum)];
        const auto kept = std::find_if(same.begin(), same.end(), [&](std::uint32_t q) {
            return glm::dot(scene.polygons[q].normal, scene.polygons[p].normal) > 0;
        });
        if (kept == same.end()) {
            same.push_back(p);
            continue;
        }
        std::uint32_t drop = p;
        if (emits(p) && !emits(*kept)) std::swap(drop, *kept); // p stays in its place
        if (count == 0 && first_group) *first_group = scene.polygons[drop].group;
        dropped[drop] = 1;
        ++count;
    }
    if (count == 0) return 0;
    std::size_t kept = 0;
    for (std::size_t p = 0; p < scene.polygons.size(); ++p) {
        if (dropped[p]) continue;
        scene.polygons[kept] = scene.polygons[p];
        if (!scene.texcoords.empty()) scene.texcoords[kept] = scene.texcoords[p];
        ++kept;
    }
    scene.polygons.resize(kept);
    if (!scene.texcoords.empty()) scene.texcoords.resize(kept);
    return count;
}

std::size_t make_two_sided(Scene& scene, const std::function<bool(std::uint32_t)>& pick,
                           std::size_t* paired) {
    const auto n = std::uint32_t(scene.polygons.size());
    std::size_t added = 0, backs_found = 0;
    // The polygons without a twin by their corners, made at the first picked polygon: a picked
    // polygon whose back is in the model already (a board modelled by both its faces, each
    // two-sided) is paired with it, where a twin would lie on that face, and the light that
    // reaches one would be taken twice (the office glb's desk parts: 16 such twins; a patch 5 cm
    // from such a board summed to 1.75 in hemicube_gl_test's TwoSidedBoard).
    std::map<std::vector<std::int64_t>, std::vector<std::uint32_t>> by_corners;
    double quantum = 0;
    for (std::uint32_t p = 0; p < n; ++p) {
        if (scene.polygons[p].twin != kNoTwin || !pick(p)) continue;
        if (quantum == 0) {
            quantum = corner_quantum(scene);
            for (std::uint32_t q = 0; q < n; ++q)
                if (scene.polygons[q].twin == kNoTwin)
                    by_corners[corner_key(scene.polygons[q], quantum)].push_back(q);
        }
        std::uint32_t back = kNoTwin;
        for (std::uint32_t q : by_corners[corner_key(scene.polygons[p], quantum)])
            if (q != p && scene.polygons[q].twin == kNoTwin &&
                glm::dot(scene.polygons[q].normal, scene.polygons[p].normal) < -0.999)
                back = q;
        if (back != kNoTwin) {
            scene.polygons[p].twin = back;
            scene.polygons[back].twin = p;
            ++backs_found;
            continue;
        }
        Polygon t = scene.polygons[p];
        // Corners reversed about the first: (v0, v3, v2, v1) or (v0, v2, v1).
        std::reverse(t.v.begin() + 1, t.v.begin() + t.count);
        t.normal = -t.normal;
        t.twin = p;
        scene.polygons[p].twin = std::uint32_t(scene.polygons.size());
        scene.polygons.push_back(t);
        if (!scene.texcoords.empty()) {
            TexCoords uv = scene.texcoords[p];
            std::reverse(uv.begin() + 1, uv.begin() + t.count);
            scene.texcoords.push_back(uv);
        }
        ++added;
    }
    if (paired) *paired = backs_found;
    return added;
}

} // namespace hemirad
