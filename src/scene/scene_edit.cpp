// Edits of a scene's photometry (scene_edit.h): luminaire multipliers, group reflectance and
// emission. Geometry is never touched.
#include "hemirad/scene_edit.h"

#include <cmath>
#include <map>

#include "core/parse.h"
#include "hemirad/error.h"

namespace hemirad {

namespace {

std::string rgb_text(const dvec3& v) {
    return v.x == v.y && v.y == v.z ? num(v.x) : num(v.x) + "," + num(v.y) + "," + num(v.z);
}

/// The index of the group named `group`; InputError naming `what` and the known groups if none.
std::uint32_t group_index(const Scene& scene, const std::string& group, const char* what) {
    const int g = scene.find_group(group);
    if (g >= 0) return std::uint32_t(g);
    std::string known;
    for (std::size_t i = 0; i < scene.groups.size() && i < 12; ++i)
        known += (i ? ", " : "") + scene.groups[i];
    if (scene.groups.size() > 12) known += ", ...";
    throw InputError(std::string(what) + " " + group + ": the scene has no surface group '" +
                     group + "' (groups: " + known + ")");
}

/// Applies `edit` to the materials of group `g`'s polygons: in place where a material is used
/// by this group alone, else on a copy "MATERIAL [GROUP]" that the group's polygons then use.
template <class Edit> void edit_group_materials(Scene& scene, std::uint32_t g, Edit edit) {
    std::vector<std::uint8_t> inside(scene.materials.size(), 0), outside(inside);
    for (const Polygon& p : scene.polygons) (p.group == g ? inside : outside)[p.material] = 1;
    std::map<std::uint32_t, std::uint32_t> copies;
    for (std::uint32_t m = 0; m < inside.size(); ++m) {
        if (!inside[m]) continue;
        if (!outside[m]) {
            edit(scene.materials[m]);
            continue;
        }
        Material copy = scene.materials[m];
        copy.name += " [" + scene.groups[g] + "]";
        edit(copy);
        copies[m] = std::uint32_t(scene.materials.size());
        scene.materials.push_back(copy);
    }
    for (Polygon& p : scene.polygons)
        if (p.group == g && copies.count(p.material)) p.material = copies[p.material];
}

} // namespace

namespace {

/// The index of the luminaire named `name`, or an InputError that starts with `what` and lists
/// the scene's luminaires.
std::size_t luminaire_index(const Scene& scene, const std::string& name, const std::string& what) {
    for (std::size_t k = 0; k < scene.luminaires.size(); ++k)
        if (scene.luminaires[k].name == name) return k;
    std::string known;
    for (const Luminaire& l : scene.luminaires) known += (known.empty() ? "" : ", ") + l.name;
    throw InputError(
        what + ": the scene has no luminaire named '" + name + "'" +
        (known.empty() ? std::string(" (it has none)") : " (luminaires: " + known + ")"));
}

} // namespace

std::size_t set_luminaire_multiplier(Scene& scene, const std::string& name, double multiplier) {
    const std::string what = "--luminaire-multiplier " + name + "=" + num(multiplier);
    const std::size_t k = luminaire_index(scene, name, what);
    if (!(multiplier >= 0) || !std::isfinite(multiplier))
        throw InputError(what + ": the multiplier must be finite and >= 0 (0 = off)");
    Luminaire& l = scene.luminaires[k];
    if (l.multiplier > 0) l.rated_lumens *= multiplier / l.multiplier;
    l.multiplier = multiplier;
    return k;
}

std::size_t set_luminaire_placement(Scene& scene, const std::string& name, const dvec3& position,
                                    const dvec3& aim) {
    const auto xyz = [](const dvec3& v) { return num(v.x) + "," + num(v.y) + "," + num(v.z); };
    const std::string what =
        "luminaire " + name + " at (" + xyz(position) + ") aimed (" + xyz(aim) + ")";
    const std::size_t k = luminaire_index(scene, name, what);
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(position[c])) throw InputError(what + ": the position must be finite");
    Luminaire moved = scene.luminaires[k];
    moved.position = position;
    moved.aim = aim;
    try {
        moved.orient();
    } catch (const InputError& e) {
        throw InputError(what + ": " + e.what());
    }
    scene.luminaires[k] = moved;
    return k;
}

void set_group_reflectance(Scene& scene, const std::string& group, const dvec3& rho) {
    const std::string what = "--reflectance " + group + "=" + rgb_text(rho);
    for (int c = 0; c < 3; ++c)
        if (!(rho[c] >= 0 && rho[c] < 1))
            throw InputError(what + ": each reflectance must be in [0, 1)");
    const std::uint32_t g = group_index(scene, group, "--reflectance");
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
        if (scene.polygons[p].group == g && scene.texture_of(p))
            throw InputError(what + ": the group is textured (its reflectance varies over each "
                                    "polygon); only untextured groups can be edited");
    edit_group_materials(scene, g, [&](Material& m) { m.rho = rho; });
}

void set_group_emission(Scene& scene, const std::string& group, const dvec3& Ke) {
    for (int c = 0; c < 3; ++c)
        if (!(Ke[c] >= 0) || !std::isfinite(Ke[c]))
            throw InputError("emission " + group + "=" + rgb_text(Ke) +
                             ": each channel must be finite and >= 0");
    const std::uint32_t g = group_index(scene, group, "emission");
    edit_group_materials(scene, g, [&](Material& m) { m.Ke = Ke; });
}

Photometry photometry(const Scene& scene) {
    Photometry ph;
    ph.rho.reserve(scene.polygons.size());
    ph.exitance.reserve(scene.polygons.size());
    for (const Polygon& p : scene.polygons) {
        const Material& m = scene.material_of(p);
        ph.rho.push_back(m.rho);
        ph.exitance.push_back(m.exitance());
    }
    for (const Luminaire& l : scene.luminaires) ph.luminaires.push_back(dvec3(l.power()));
    return ph;
}

std::pair<std::string, dvec3> parse_scene_edit(const std::string& flag, const std::string& text,
                                               int channels) {
    const std::size_t eq = text.rfind('=');
    const std::string form = channels == 3 ? "GROUP=R or GROUP=R,G,B" : "NAME=F";
    if (eq == std::string::npos || eq == 0)
        throw InputError(flag + " '" + text + "': expected " + form);
    const std::string name = text.substr(0, eq), values = text.substr(eq + 1);
    std::vector<double> v;
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = values.find(',', start);
        const std::string part = values.substr(start, comma - start);
        const std::optional<double> x = parse_double(part);
        if (!x || part.empty())
            throw InputError(flag + " '" + text + "': '" + part + "' is not a number (expected " +
                             form + ")");
        v.push_back(*x);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (v.size() == 1) return {name, dvec3(v[0])};
    if (channels == 3 && v.size() == 3) return {name, dvec3(v[0], v[1], v[2])};
    throw InputError(flag + " '" + text + "': expected " + form);
}

} // namespace hemirad
