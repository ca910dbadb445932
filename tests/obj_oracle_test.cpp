// The OBJ reader (src/scene/obj_loader.cpp) against tinyobjloader (Debian's
// libtinyobjloader-dev, the library the design card names for OBJ): every OBJ file of the test
// corpus (tests/data, assets/) and of ../shared/scenes that both read gives the same triangles
// — the same corner positions, the same faces once triangulated, the same material on each.
//
// tinyobjloader only parses here; the rules hemirad documents for what it makes of the faces
// (README, "Scene files") are applied to its faces the same way: faces that repeat the corners
// of an earlier face on the same side are dropped, degenerate ones too; then every face is
// triangulated one way on both sides (triangles as they are, quads along the shorter
// diagonal, larger polygons as a fan from their first corner), which is the split hemirad
// itself makes of the faces it splits. Where tinyobjloader does not find a material library
// that hemirad finds (hemirad also looks for it by its base name next to the OBJ), only the
// geometry is compared.
#include <gtest/gtest.h>

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"

using namespace hemirad;
namespace fs = std::filesystem;

namespace {

using P = dvec3;

struct Triangle {
    std::array<P, 3> v; ///< rotated so that the smallest corner (x, y, z order) comes first
    std::string material;
};

bool less(const P& a, const P& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

/// tinyobjloader's own number parser can be an ulp or two off the correctly rounded double
/// (0.42000000000000004 for "0.42"): positions are snapped to a grid far finer than any
/// scene's detail before they are ordered, so that both lists sort alike.
double g_grid = 1e-9;
P snap(const P& p) {
    return glm::round(p / g_grid) * g_grid;
}

Triangle make_triangle(P a, P b, P c, const std::string& material) {
    Triangle t{{snap(a), snap(b), snap(c)}, material};
    int first = 0;
    for (int k = 1; k < 3; ++k)
        if (less(t.v[k], t.v[first])) first = k;
    std::rotate(t.v.begin(), t.v.begin() + first, t.v.end()); // keeps the orientation
    return t;
}

double area(const P& a, const P& b, const P& c) {
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

/// The canonical triangulation of a face: a triangle as it is, a quad along its shorter
/// diagonal (the first one on a tie), a larger polygon as a fan from its first corner.
void triangulate(const std::vector<P>& v, const std::string& material, std::vector<Triangle>& out) {
    if (v.size() == 4) {
        if (glm::length(v[2] - v[0]) <= glm::length(v[3] - v[1])) {
            out.push_back(make_triangle(v[0], v[1], v[2], material));
            out.push_back(make_triangle(v[0], v[2], v[3], material));
        } else {
            out.push_back(make_triangle(v[0], v[1], v[3], material));
            out.push_back(make_triangle(v[1], v[2], v[3], material));
        }
        return;
    }
    for (std::size_t i = 1; i + 1 < v.size(); ++i)
        out.push_back(make_triangle(v[0], v[i], v[i + 1], material));
}

/// Drops zero-area triangles (what hemirad drops as degenerate) and sorts.
void finish(std::vector<Triangle>& t, double scale) {
    const double eps = 1e-12 * scale * scale;
    t.erase(
        std::remove_if(t.begin(), t.end(),
                       [&](const Triangle& x) { return !(area(x.v[0], x.v[1], x.v[2]) > eps); }),
        t.end());
    std::sort(t.begin(), t.end(), [](const Triangle& a, const Triangle& b) {
        for (int k = 0; k < 3; ++k)
            if (a.v[k] != b.v[k]) return less(a.v[k], b.v[k]);
        return a.material < b.material;
    });
}

/// hemirad's triangles: its polygons, quads split as above.
std::vector<Triangle> hemirad_triangles(const Scene& scene, bool materials) {
    std::vector<Triangle> out;
    for (const Polygon& p : scene.polygons) {
        std::string m = materials ? scene.material_of(p).name : "";
        const std::string suffix = " (texture mean)"; // untextured_material()'s copy
        if (m.size() > suffix.size() &&
            m.compare(m.size() - suffix.size(), suffix.size(), suffix) == 0)
            m.resize(m.size() - suffix.size());
        triangulate(std::vector<P>(p.v.begin(), p.v.begin() + p.count), m, out);
    }
    return out;
}

/// What tinyobjloader read, with hemirad's rules for duplicate and degenerate faces applied.
std::vector<Triangle> tinyobj_triangles(const tinyobj::ObjReader& r, bool materials) {
    const tinyobj::attrib_t& a = r.GetAttrib();
    const auto& mats = r.GetMaterials();
    struct Face {
        std::vector<P> v;
        std::string material;
        bool emits = false;
    };
    std::vector<Face> faces;
    for (const tinyobj::shape_t& s : r.GetShapes()) {
        std::size_t k = 0;
        for (std::size_t f = 0; f < s.mesh.num_face_vertices.size(); ++f) {
            Face face;
            for (unsigned i = 0; i < s.mesh.num_face_vertices[f]; ++i, ++k) {
                const int vi = s.mesh.indices[k].vertex_index;
                const P p(a.vertices[3 * vi], a.vertices[3 * vi + 1], a.vertices[3 * vi + 2]);
                if (face.v.empty() || p != face.v.back()) face.v.push_back(p); // repeated corner
            }
            while (face.v.size() > 1 && face.v.front() == face.v.back()) face.v.pop_back();
            const int m = s.mesh.material_ids[f];
            face.material = !materials ? "" : m >= 0 ? mats[std::size_t(m)].name : "default";
            if (m >= 0) {
                const auto& e = mats[std::size_t(m)].emission;
                face.emits = e[0] > 0 || e[1] > 0 || e[2] > 0;
            }
            faces.push_back(face);
        }
    }
    // A face with the corners of an earlier kept face, facing the same side, is dropped, or
    // that earlier face is, where only the later one emits.
    const auto newell = [](const std::vector<P>& v) {
        P n(0.0);
        for (std::size_t i = 0; i < v.size(); ++i) n += glm::cross(v[i], v[(i + 1) % v.size()]);
        return n;
    };
    const auto corner_set = [](std::vector<P> v) {
        std::sort(v.begin(), v.end(), less);
        v.erase(std::unique(v.begin(), v.end()), v.end());
        return v;
    };
    struct Kept {
        P n;
        std::size_t face;
    };
    std::map<std::vector<std::array<double, 3>>, std::vector<Kept>> seen; // by corner set
    std::vector<char> keep(faces.size(), 0);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Face& f = faces[i];
        if (f.v.size() < 3) continue;
        std::vector<std::array<double, 3>> key;
        for (const P& p : corner_set(f.v)) key.push_back({p.x, p.y, p.z});
        const P n = newell(f.v);
        std::vector<Kept>& kept = seen[key];
        const auto same_side = std::find_if(kept.begin(), kept.end(),
                                            [&](const Kept& k) { return glm::dot(k.n, n) > 0; });
        if (same_side == kept.end()) {
            kept.push_back({n, i});
            keep[i] = 1;
        } else if (f.emits && !faces[same_side->face].emits) {
            keep[same_side->face] = 0;
            keep[i] = 1;
            *same_side = {n, i};
        }
    }
    std::vector<Triangle> out;
    for (std::size_t i = 0; i < faces.size(); ++i)
        if (keep[i]) triangulate(faces[i].v, faces[i].material, out);
    return out;
}

/// Compares the two readers on one OBJ file; returns what was compared, or why not.
std::string compare(const fs::path& obj, bool& compared) {
    compared = false;
    Scene scene;
    try {
        ObjOptions as_written; // the reader alone, polygons not cut where others stand
        as_written.split_intersections = false;
        scene = load_obj(obj.string(), as_written);
    } catch (const InputError& e) {
        return std::string("refused by hemirad (") + e.what() + "): not compared";
    }
    tinyobj::ObjReaderConfig config;
    config.triangulate = false; // faces as written; triangulated below, the same way for both
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(obj.string(), config))
        return "refused by tinyobjloader (" + reader.Error() + "): not compared";
    const bool materials = reader.Warning().find("not found") == std::string::npos &&
                           reader.Error().find("not found") == std::string::npos;
    compared = true;

    const double scale = std::max(scene.bounds().diagonal(), 1e-30);
    g_grid = 1e-9 * scale;
    std::vector<Triangle> ours = hemirad_triangles(scene, materials);
    std::vector<Triangle> theirs = tinyobj_triangles(reader, materials);
    finish(ours, scale);
    finish(theirs, scale);
    EXPECT_EQ(ours.size(), theirs.size()) << obj << ": triangles";
    if (ours.size() != theirs.size()) return "different triangle counts";
    // tinyobjloader reads numbers with its own parser: the same double, or one ulp apart.
    const double tol = 1e-12 * scale;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < ours.size(); ++i) {
        bool same = ours[i].material == theirs[i].material;
        for (int k = 0; k < 3; ++k)
            same = same && glm::length(ours[i].v[k] - theirs[i].v[k]) <= tol;
        if (!same && differ++ < 3)
            ADD_FAILURE() << obj << ": triangle " << i << ": (" << ours[i].v[0].x << ", "
                          << ours[i].v[0].y << ", " << ours[i].v[0].z << ") '" << ours[i].material
                          << "' vs (" << theirs[i].v[0].x << ", " << theirs[i].v[0].y << ", "
                          << theirs[i].v[0].z << ") '" << theirs[i].material << "'";
    }
    EXPECT_EQ(differ, 0u) << obj;
    return std::to_string(ours.size()) + " triangles" + (materials ? "" : ", geometry only");
}

std::vector<fs::path> obj_files(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file() && e.path().extension() == ".obj") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

void compare_all(const fs::path& dir, std::size_t at_least) {
    std::size_t compared = 0;
    for (const fs::path& f : obj_files(dir)) {
        bool done = false;
        std::string what = compare(f, done);
        std::replace(what.begin(), what.end(), '\n', ' ');
        std::printf("  %s: %s\n", fs::relative(f, dir).c_str(), what.c_str());
        compared += done;
    }
    EXPECT_GE(compared, at_least) << dir;
}

TEST(ObjOracle, TestCorpus) {
    compare_all(fs::path(HEMIRAD_TEST_DATA), 10);
    compare_all(fs::path(HEMIRAD_SOURCE_DIR) / "assets", 8);
}

TEST(ObjOracle, SharedScenes) {
    const fs::path shared = fs::path(HEMIRAD_SOURCE_DIR) / ".." / "shared" / "scenes";
    if (!fs::is_directory(shared))
        GTEST_SKIP() << shared << " is absent: the real-world OBJ files are not compared";
    compare_all(shared, 5);
}

} // namespace
