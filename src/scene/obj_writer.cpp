// A scene as OBJ/MTL files (`hemirad scene NAME --obj FILE.obj`): how the files in assets/
// are made from the built-in scenes, so that the two stay the same scene.
#include <array>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <unordered_map>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"
#include "output/atomic_file.h"

namespace hemirad {

namespace {

/// A point's bits (so that -0 and +0 stay distinct vertices: the file keeps every bit).
using PointBits = std::array<std::uint64_t, 3>;
PointBits bits_of(const dvec3& p) {
    PointBits b;
    for (int i = 0; i < 3; ++i) std::memcpy(&b[std::size_t(i)], &p[i], sizeof(double));
    return b;
}
struct PointHash {
    std::size_t operator()(const PointBits& b) const {
        std::uint64_t h = 1469598103934665603ull;
        for (std::uint64_t x : b) h = (h ^ x) * 1099511628211ull;
        return std::size_t(h);
    }
};

/// The shortest decimal that reads back as `x` (std::to_chars): 130, 0.1, 1e-07.
std::string decimal(double x) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    return std::string(buf, r.ptr);
}

std::string triple(const dvec3& v) {
    return decimal(v.x) + " " + decimal(v.y) + " " + decimal(v.z);
}

} // namespace

ObjText scene_obj_text(const Scene& scene, const std::string& mtl_name) {
    ObjText out;
    // Names as OBJ can carry them: no line breaks; unique among materials.
    const auto clean = [](std::string s) {
        for (char& c : s)
            if (c == '\n' || c == '\r' || c == '#') c = '_';
        return s.empty() ? std::string("unnamed") : s;
    };
    std::vector<std::string> material_names;
    std::set<std::string> taken;
    for (const Material& m : scene.materials) {
        std::string n = clean(m.name);
        for (int k = 2; !taken.insert(n).second; ++k) n = clean(m.name) + "_" + std::to_string(k);
        material_names.push_back(n);
    }

    out.mtl = "# Materials of " + scene.source +
              " (written by hemirad).\n"
              "# Kd: diffuse reflectance rho; Ke: emitted radiance [W sr^-1 unit^-2], exitance "
              "pi Ke.\n";
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        out.mtl += "newmtl " + material_names[i] + "\nKd " + triple(m.rho) + "\n";
        if (m.Ke != dvec3(0.0)) out.mtl += "Ke " + triple(m.Ke) + "\n";
    }

    std::string& obj = out.obj;
    obj = "# " + scene.source + " (written by hemirad): " + std::to_string(scene.polygons.size()) +
          " polygons, lengths in scene units.\n";
    for (const Camera& c : scene.cameras)
        obj += "# camera '" + c.name + "' (for --camera): " + decimal(c.eye.x) + "," +
               decimal(c.eye.y) + "," + decimal(c.eye.z) + "," + decimal(c.target.x) + "," +
               decimal(c.target.y) + "," + decimal(c.target.z) + "," + decimal(c.up.x) + "," +
               decimal(c.up.y) + "," + decimal(c.up.z) + "," + decimal(c.fov_y_deg) + "\n";
    obj += "mtllib " + mtl_name + "\n";
    // Vertices, each distinct corner once, in order of first use.
    std::unordered_map<PointBits, std::size_t, PointHash> index;
    std::vector<std::array<std::size_t, 4>> corners(scene.polygons.size());
    for (std::size_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& q = scene.polygons[p];
        for (int k = 0; k < q.count; ++k) {
            const auto [it, fresh] = index.try_emplace(bits_of(q.v[k]), index.size() + 1);
            if (fresh) obj += "v " + triple(q.v[k]) + "\n";
            corners[p][k] = it->second;
        }
    }
    // Faces, with `g` and `usemtl` where they change (in polygon order, so that reading the
    // file back numbers groups and polygons as here).
    std::uint32_t group = ~0u, material = ~0u;
    for (std::size_t p = 0; p < scene.polygons.size(); ++p) {
        const Polygon& q = scene.polygons[p];
        if (q.group != group) {
            group = q.group;
            obj += "g " + clean(scene.groups[group]) + "\n";
        }
        if (q.material != material) {
            material = q.material;
            obj += "usemtl " + material_names[material] + "\n";
        }
        obj += "f";
        for (int k = 0; k < q.count; ++k) (obj += ' ') += std::to_string(corners[p][k]);
        obj += "\n";
    }
    return out;
}

std::string write_obj(const Scene& scene, const std::string& obj_path) {
    namespace fs = std::filesystem;
    if (fs::path(obj_path).extension() != ".obj")
        throw InputError("--obj " + obj_path + ": expected a file name ending in .obj");
    const std::string mtl_path = fs::path(obj_path).replace_extension(".mtl").string();
    const ObjText text = scene_obj_text(scene, fs::path(mtl_path).filename().string());
    AtomicFile mtl(mtl_path), obj(obj_path);
    mtl.write(text.mtl);
    obj.write(text.obj);
    mtl.commit();
    obj.commit();
    return mtl_path;
}

} // namespace hemirad
