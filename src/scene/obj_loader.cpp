// OBJ/MTL loading through tinyobjloader, with a validating pre-scan of our own so that every
// error names the file, the line and the value (tinyobjloader reports few line numbers and
// silently reads garbage as 0).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <tiny_obj_loader.h>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"

namespace hemirad {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> read_lines(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, 0, std::string("cannot open file: ") + std::strerror(errno));
    std::vector<std::string> lines;
    std::string line;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(line);
    }
    return lines;
}

std::vector<std::string> split_ws(const std::string& s) {
    std::istringstream in(s);
    std::vector<std::string> out;
    std::string w;
    while (in >> w) out.push_back(w);
    return out;
}

// Parses a whole token as a double; false if it is not a number at all. Accepts nan/inf
// (std::strtod does), which the caller rejects with a message of its own.
bool parse_double(const std::string& s, double& out) {
    const char* b = s.c_str();
    char* e = nullptr;
    out = std::strtod(b, &e);
    return e != b && *e == '\0';
}

// Where each material's Kd/Ke were set, for messages about values out of range.
struct MtlInfo {
    std::string file;
    std::map<std::string, int> kd_line, ke_line;
};

void scan_mtl(const std::string& path, MtlInfo& info) {
    const std::vector<std::string> lines = read_lines(path);
    std::string current;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const int line = int(i) + 1;
        const std::vector<std::string> w = split_ws(lines[i]);
        if (w.empty() || w[0][0] == '#') continue;
        if (w[0] == "newmtl") {
            current = w.size() > 1 ? w[1] : "";
            continue;
        }
        if (w[0] == "Kd" || w[0] == "Ke") {
            if (w.size() < 2)
                throw InputError(path, line, w[0] + " needs 1 or 3 values");
            for (std::size_t k = 1; k < w.size() && k < 4; ++k) {
                double x;
                if (!parse_double(w[k], x))
                    throw InputError(path, line, "cannot parse " + w[0] + " value '" + w[k] + "'");
                if (!std::isfinite(x))
                    throw InputError(path, line, w[0] + " value " + w[k] + " is not finite");
                if (w[0] == "Kd" && (x < 0 || x >= 1))
                    throw InputError(path, line,
                                     "diffuse reflectance Kd " + w[k] + " of material '" +
                                         current + "' is outside [0, 1) (a surface can't reflect "
                                                   "more than it receives)");
                if (w[0] == "Ke" && x < 0)
                    throw InputError(path, line, "emission Ke " + w[k] + " of material '" +
                                                     current + "' is negative");
            }
            (w[0] == "Kd" ? info.kd_line : info.ke_line)[current] = line;
        }
    }
    info.file = path;
}

// Checks every line tinyobjloader would read loosely: vertex coordinates and face indices.
void scan_obj(const std::string& path, const std::vector<std::string>& lines,
              std::vector<std::string>& mtl_files) {
    long vertices = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const int line = int(i) + 1;
        const std::vector<std::string> w = split_ws(lines[i]);
        if (w.empty() || w[0][0] == '#') continue;
        const std::string& key = w[0];
        if (key == "v") {
            if (w.size() < 4)
                throw InputError(path, line, "vertex needs 3 coordinates: '" + lines[i] + "'");
            for (int k = 1; k <= 3; ++k) {
                double x;
                if (!parse_double(w[k], x))
                    throw InputError(path, line, "cannot parse vertex coordinate '" + w[k] + "'");
                if (!std::isfinite(x))
                    throw InputError(path, line,
                                     "vertex coordinate " + w[k] + " is not a finite number");
            }
            ++vertices;
        } else if (key == "f") {
            if (w.size() < 4)
                throw InputError(path, line,
                                 "face needs at least 3 vertices: '" + lines[i] + "'");
            for (std::size_t k = 1; k < w.size(); ++k) {
                const std::string idx = w[k].substr(0, w[k].find('/'));
                char* e = nullptr;
                const long v = std::strtol(idx.c_str(), &e, 10);
                if (idx.empty() || *e != '\0' || v == 0)
                    throw InputError(path, line, "cannot parse face vertex index '" + w[k] + "'");
                const long resolved = v > 0 ? v : vertices + 1 + v;
                if (resolved < 1 || resolved > vertices)
                    throw InputError(path, line,
                                     "face vertex index " + idx + " refers to no vertex (" +
                                         std::to_string(vertices) + " defined so far)");
            }
        } else if (key == "mtllib") {
            for (std::size_t k = 1; k < w.size(); ++k) mtl_files.push_back(w[k]);
        } else if (key == "vt" || key == "vn" || key == "g" || key == "o" || key == "usemtl" ||
                   key == "s" || key == "l" || key == "p" || key == "vp") {
            // Understood (texture coordinates, normals, lines and points are ignored).
        } else {
            throw InputError(path, line, "unknown OBJ statement '" + key + "'");
        }
    }
}

} // namespace

Scene load_obj(const std::string& path) {
    if (!fs::exists(path)) throw InputError(path, 0, "no such file");
    if (fs::is_directory(path)) throw InputError(path, 0, "is a directory, not an OBJ file");
    const std::vector<std::string> lines = read_lines(path);
    std::vector<std::string> mtl_names;
    scan_obj(path, lines, mtl_names);
    const fs::path dir = fs::path(path).parent_path();
    MtlInfo mtl;
    for (const std::string& name : mtl_names) {
        const fs::path p = dir / name;
        if (!fs::exists(p))
            throw InputError(path, 0, "material library '" + name + "' not found (looked for " +
                                          p.string() + ")");
        scan_mtl(p.string(), mtl);
    }

    tinyobj::ObjReaderConfig config;
    config.triangulate = false;
    config.vertex_color = false;
    config.mtl_search_path = dir.string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string err = reader.Error();
        while (!err.empty() && err.back() == '\n') err.pop_back();
        throw InputError(path, 0, "cannot parse: " + err);
    }

    Scene scene;
    scene.source = path;
    // Materials: ours follow tinyobjloader's order; a last "default" one for faces without.
    for (const tinyobj::material_t& m : reader.GetMaterials()) {
        Material mat;
        mat.name = m.name;
        mat.rho = dvec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
        mat.Ke = dvec3(m.emission[0], m.emission[1], m.emission[2]);
        scene.materials.push_back(mat);
    }
    const std::uint32_t default_material = std::uint32_t(scene.materials.size());
    bool used_default = false;
    scene.materials.push_back(Material{"default", dvec3(0.5), dvec3(0.0)});

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    std::map<std::string, std::uint32_t> group_index;
    const auto group_of = [&](const std::string& name) {
        auto it = group_index.find(name);
        if (it != group_index.end()) return it->second;
        const auto g = std::uint32_t(scene.groups.size());
        scene.groups.push_back(name);
        group_index[name] = g;
        return g;
    };
    std::size_t degenerate = 0;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
            const int nv = shape.mesh.num_face_vertices[f];
            std::vector<dvec3> corners;
            for (int k = 0; k < nv; ++k) {
                const int vi = shape.mesh.indices[offset + k].vertex_index;
                corners.emplace_back(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1],
                                     attrib.vertices[3 * vi + 2]);
            }
            offset += nv;
            const int mid = shape.mesh.material_ids.empty() ? -1 : shape.mesh.material_ids[f];
            const std::uint32_t material = mid >= 0 ? std::uint32_t(mid) : default_material;
            used_default |= mid < 0;
            const std::string gname = !shape.name.empty() ? shape.name
                                      : mid >= 0         ? scene.materials[mid].name
                                                         : "default";
            const AddResult r = add_polygon(scene, corners, material, group_of(gname));
            degenerate += r.degenerate;
            if (r.split && nv == 4)
                scene.warnings.push_back("face " + std::to_string(f + 1) + " of group '" + gname +
                                         "' is a non-planar or concave quad: split into 2 "
                                         "triangles");
            else if (r.split)
                scene.warnings.push_back("face " + std::to_string(f + 1) + " of group '" + gname +
                                         "' has " + std::to_string(nv) +
                                         " corners: fan-triangulated");
        }
    }
    if (degenerate > 0)
        scene.warnings.push_back("dropped " + std::to_string(degenerate) +
                                 " degenerate polygon(s) (zero area or repeated vertices)");
    if (used_default)
        scene.warnings.push_back("faces without a material use 'default' (rho 0.5, no emission)");
    finish_scene(scene, path);
    return scene;
}

Scene load_scene(const std::string& name_or_path, const BuiltinOptions& builtin) {
    if (is_builtin(name_or_path)) return make_builtin(name_or_path, builtin);
    if (!fs::exists(name_or_path))
        throw InputError(name_or_path, 0,
                         std::string("no such file, and not a built-in scene (") +
                             builtin_names() + ")");
    return load_obj(name_or_path);
}

} // namespace hemirad
