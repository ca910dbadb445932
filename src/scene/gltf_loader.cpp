// glTF 2.0 scenes (.gltf with its buffers and images, or .glb), read with TinyGLTF (Debian's
// libtinygltf, a shared library: scene_io.h, load_gltf).
//
// What is read: the node tree of the default scene (or of scene 0; without scenes, every root
// node), each node's matrix or translation * rotation * scale composed down the tree; meshes'
// triangle primitives (POSITION, TEXCOORD_0, indices of any component type); materials'
// baseColorFactor (reflectance, linear) and baseColorTexture (its TEXCOORD_0 only), emissiveFactor
// times KHR_materials_emissive_strength (emitted radiance); perspective cameras; point and spot
// lights of KHR_lights_punctual (luminaires). Every bound is
// checked here (TinyGLTF checks few): an accessor that reaches outside its buffer view, a view
// outside its buffer, an index outside the vertices is an InputError naming the file and the
// element ("accessor 3"), never a crash.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "hemirad/error.h"
#include "hemirad/scene_io.h"

namespace hemirad {

namespace {

namespace fs = std::filesystem;

/// Most node levels followed (glTF's tree is acyclic; a file that is not is refused before).
constexpr int kMaxNodeDepth = 1024;
/// Most node instances visited: a node may be the child of several (not allowed by glTF, but
/// TinyGLTF does not check), which could multiply the tree exponentially.
constexpr long kMaxNodeVisits = 1000000;
/// Most triangles read (instancing can multiply a small file's triangles).
constexpr std::size_t kMaxTriangles = std::size_t(1) << 26;
/// Most elements of an accessor without a buffer view (all zeros: nothing bounds it).
constexpr std::size_t kMaxZeroElements = std::size_t(1) << 24;

/// Images decoded by TinyGLTF's image callback, by image index; failures as warnings.
struct ImageSink {
    std::string file;
    std::map<int, Texture> decoded;
    std::vector<std::string> warnings;
};

bool decode_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                  const unsigned char* bytes, int size, void* user) {
    auto* sink = static_cast<ImageSink*>(user);
    const std::string name = sink->file + ": image " + std::to_string(index) +
                             (image && !image->uri.empty() ? " ('" + image->uri + "')" : "");
    try {
        sink->decoded.emplace(index, decode_texture(name, bytes, std::size_t(std::max(size, 0))));
    } catch (const InputError& e) {
        sink->warnings.push_back(std::string(e.what()) +
                                 ": not read, its materials use baseColorFactor alone");
    }
    return true; // a texture that cannot be read is a warning, not a failed load
}

class GltfReader {
  public:
    GltfReader(const std::string& path, const tinygltf::Model& model, const ObjOptions& options)
        : path_(path), m_(model), options_(options) {}

    /// Reads accessor `index` as `count` x `components` doubles (normalised integers to [0, 1]
    /// or [-1, 1], as glTF defines). `what` names its use in messages.
    std::vector<double> accessor(int index, int components, const std::string& what) const {
        const std::string name = "accessor " + std::to_string(index);
        if (index < 0 || std::size_t(index) >= m_.accessors.size())
            throw error(what + " refers to " + name + ", which does not exist (" +
                        std::to_string(m_.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = m_.accessors[std::size_t(index)];
        const int have = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
        const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
        if (have != components || size <= 0)
            throw error(name + " (" + what + "): type " + std::to_string(a.type) +
                        " with component type " + std::to_string(a.componentType) + " is not " +
                        std::to_string(components) + " numbers per element");
        if (a.sparse.isSparse) throw error(name + ": sparse accessors are not supported");
        const std::size_t count = a.count;
        if (count > (std::size_t(1) << 31))
            throw error(name + ": count " + std::to_string(count) + " is too large");
        if (a.bufferView < 0) { // no view: all zeros (glTF 3.6.2.3)
            if (count > kMaxZeroElements)
                throw error(name + ": " + std::to_string(count) +
                            " elements without a buffer view (at most " +
                            std::to_string(kMaxZeroElements) + ")");
            return std::vector<double>(count * std::size_t(components), 0.0);
        }
        if (std::size_t(a.bufferView) >= m_.bufferViews.size())
            throw error(name + " refers to buffer view " + std::to_string(a.bufferView) +
                        ", which does not exist");
        const tinygltf::BufferView& v = m_.bufferViews[std::size_t(a.bufferView)];
        const std::string vname = "buffer view " + std::to_string(a.bufferView);
        if (v.buffer < 0 || std::size_t(v.buffer) >= m_.buffers.size())
            throw error(vname + " refers to buffer " + std::to_string(v.buffer) +
                        ", which does not exist");
        const std::vector<unsigned char>& data = m_.buffers[std::size_t(v.buffer)].data;
        if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
            throw error(vname + " (bytes " + std::to_string(v.byteOffset) + " + " +
                        std::to_string(v.byteLength) + ") reaches outside buffer " +
                        std::to_string(v.buffer) + " (" + std::to_string(data.size()) + " bytes)");
        const std::size_t element = std::size_t(size) * std::size_t(components);
        const std::size_t stride = v.byteStride ? v.byteStride : element;
        if (stride < element)
            throw error(vname + ": byte stride " + std::to_string(stride) +
                        " is smaller than an element of " + name);
        if (count > 0 && (a.byteOffset > v.byteLength ||
                          (count - 1) * stride + element > v.byteLength - a.byteOffset))
            throw error(name + " (" + std::to_string(count) + " elements from byte " +
                        std::to_string(a.byteOffset) + ") reaches outside " + vname + " (" +
                        std::to_string(v.byteLength) + " bytes)");
        std::vector<double> out(count * std::size_t(components), 0.0);
        const unsigned char* base = data.data() + v.byteOffset + a.byteOffset;
        for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < components; ++c) {
                const unsigned char* p = base + i * stride + std::size_t(c) * std::size_t(size);
                out[i * std::size_t(components) + std::size_t(c)] =
                    component(p, a.componentType, a.normalized, name);
            }
        return out;
    }

    Scene read() {
        Scene scene;
        scene.source = path_;
        // Extensions: KHR_materials_emissive_strength is read; the others are named once.
        std::string unread;
        const auto known = [](const std::string& e) {
            return e == "KHR_materials_emissive_strength" || e == "KHR_lights_punctual";
        };
        for (const std::string& e : m_.extensionsUsed)
            if (!known(e)) unread += (unread.empty() ? "" : ", ") + e;
        if (!unread.empty()) warnings_.push_back(path_ + ": extensions not read: " + unread);
        for (const std::string& e : m_.extensionsRequired)
            if (!known(e))
                warnings_.push_back(path_ + ": the file requires extension " + e +
                                    ", which is not read: the scene may not be what it shows");
        const std::vector<int> roots = root_nodes();
        std::vector<int> stack;
        for (int r : roots) visit(scene, r, glm::dmat4(1.0), stack);
        for (const std::string& w : warnings_) scene.warnings.push_back(w);
        // doubleSided materials (glTF 3.9.6): both sides of their triangles are surfaces
        // (Material::two_sided, made so by finish_surfaces).
        if (options_.finish_surfaces) finish_surfaces(scene, options_);
        finish_scene(scene, path_);
        return scene;
    }

    ImageSink images;

  private:
    InputError error(const std::string& message) const { return InputError(path_, 0, message); }
    void warn_once(const std::string& kind, const std::string& text) {
        if (warned_.insert(kind).second) warnings_.push_back(path_ + ": " + text);
    }

    static double component(const unsigned char* p, int type, bool normalized,
                            const std::string& name) {
        const auto get = [p](auto v) {
            std::memcpy(&v, p, sizeof v);
            return v;
        };
        switch (type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return double(get(float()));
        case TINYGLTF_COMPONENT_TYPE_DOUBLE:
            return get(double());
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const double x = get(std::uint8_t());
            return normalized ? x / 255.0 : x;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const double x = get(std::int8_t());
            return normalized ? std::max(x / 127.0, -1.0) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const double x = get(std::uint16_t());
            return normalized ? x / 65535.0 : x;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const double x = get(std::int16_t());
            return normalized ? std::max(x / 32767.0, -1.0) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return double(get(std::uint32_t()));
        case TINYGLTF_COMPONENT_TYPE_INT:
            return double(get(std::int32_t()));
        }
        throw InputError(name + ": unknown component type " + std::to_string(type));
    }

    std::vector<int> root_nodes() const {
        const int n = int(m_.nodes.size());
        if (!m_.scenes.empty()) {
            int s = m_.defaultScene;
            if (s < 0 || std::size_t(s) >= m_.scenes.size()) s = 0;
            return m_.scenes[std::size_t(s)].nodes;
        }
        std::vector<std::uint8_t> child(std::size_t(n), 0);
        for (const tinygltf::Node& node : m_.nodes)
            for (int c : node.children)
                if (c >= 0 && c < n) child[std::size_t(c)] = 1;
        std::vector<int> roots;
        for (int i = 0; i < n; ++i)
            if (!child[std::size_t(i)]) roots.push_back(i);
        return roots;
    }

    /// The node's local transform: its matrix (column-major), or T * R * S.
    glm::dmat4 local(int index, const tinygltf::Node& node) const {
        const std::string name = "node " + std::to_string(index);
        const auto finite = [&](const std::vector<double>& v, const char* what) {
            for (double x : v)
                if (!std::isfinite(x)) throw error(name + ": " + what + " is not finite");
        };
        finite(node.matrix, "matrix");
        finite(node.translation, "translation");
        finite(node.rotation, "rotation");
        finite(node.scale, "scale");
        if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
        if (!node.matrix.empty()) throw error(name + ": matrix needs 16 numbers");
        glm::dmat4 t(1.0), r(1.0), s(1.0);
        if (node.translation.size() == 3)
            t = glm::translate(glm::dmat4(1.0), glm::make_vec3(node.translation.data()));
        else if (!node.translation.empty())
            throw error(name + ": translation needs 3 numbers");
        if (node.rotation.size() == 4) {
            // glTF quaternions are (x, y, z, w); glm's constructor takes (w, x, y, z).
            glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            if (!(glm::length(q) > 0)) throw error(name + ": rotation is a zero quaternion");
            r = glm::mat4_cast(glm::normalize(q));
        } else if (!node.rotation.empty()) {
            throw error(name + ": rotation needs 4 numbers (a quaternion x, y, z, w)");
        }
        if (node.scale.size() == 3)
            s = glm::scale(glm::dmat4(1.0), glm::make_vec3(node.scale.data()));
        else if (!node.scale.empty())
            throw error(name + ": scale needs 3 numbers");
        return t * r * s;
    }

    void visit(Scene& scene, int index, const glm::dmat4& parent, std::vector<int>& stack) {
        if (index < 0 || std::size_t(index) >= m_.nodes.size())
            throw error("node " + std::to_string(index) + " does not exist (" +
                        std::to_string(m_.nodes.size()) + " nodes)");
        if (std::find(stack.begin(), stack.end(), index) != stack.end())
            throw error("node " + std::to_string(index) +
                        " is its own ancestor (the node hierarchy must be a tree)");
        if (int(stack.size()) >= kMaxNodeDepth)
            throw error("node " + std::to_string(index) + ": the node tree is deeper than " +
                        std::to_string(kMaxNodeDepth) + " levels");
        if (++visits_ > kMaxNodeVisits)
            throw error("the node tree has more than " + std::to_string(kMaxNodeVisits) +
                        " node instances (nodes that are children of several parents)");
        const tinygltf::Node& node = m_.nodes[std::size_t(index)];
        const glm::dmat4 world = parent * local(index, node);
        if (node.mesh >= 0) add_mesh(scene, index, node, world);
        if (node.camera >= 0) add_camera(scene, index, node, world);
        const auto light = node.extensions.find("KHR_lights_punctual");
        if (light != node.extensions.end()) add_light(scene, index, node, light->second, world);
        if (node.skin >= 0)
            warn_once("skin", "node " + std::to_string(index) +
                                  ": skins are ignored (the bind pose is used)");
        stack.push_back(index);
        for (int c : node.children) visit(scene, c, world, stack);
        stack.pop_back();
    }

    /// A directional light becomes the scene's sun (sun.h): its light travels down the node's
    /// -z, so the sun lies along +z; `lux` its normal illuminance. One sun: a second
    /// directional light is warned and skipped.
    void add_sun(Scene& scene, const std::string& nname, const std::string& what, double lux,
                 const glm::dmat4& world) {
        const dvec3 towards = dvec3(world * glm::dvec4(0, 0, 1, 0));
        const double length = glm::length(towards);
        if (!std::isfinite(length) || !(length > 0))
            throw error(nname + ": the transform of " + what + " has no direction (+z is 0)");
        if (scene.sun) {
            warn_once("second sun", what + ": a second directional light is ignored (one sun)");
            return;
        }
        Sun sun;
        sun.direction = towards / length;
        sun.illuminance = lux;
        SkyFrame().angles(sun.direction, sun.altitude_deg, sun.azimuth_deg);
        if (!(sun.altitude_deg > 0))
            warn_once("sun below", what + ": the directional light shines upwards (the sun "
                                          "below the horizon): it lights nothing");
        scene.sun = sun;
    }

    /// KHR_lights_punctual: a point or spot light at the node becomes a luminaire (photometry.h)
    /// of the light's intensity [cd] times the luminance of its colour (luminaires are white);
    /// a spot points down the node's -z with gltf_spot_distribution(). A directional light
    /// becomes the sun (add_sun), its intensity [lux] times the colour's luminance. `range` is
    /// ignored (physical inverse-square falloff).
    void add_light(Scene& scene, int index, const tinygltf::Node& node, const tinygltf::Value& ext,
                   const glm::dmat4& world) {
        const std::string nname = "node " + std::to_string(index);
        if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsInt())
            throw error(nname + ": KHR_lights_punctual needs an integer 'light'");
        const int k = ext.Get("light").GetNumberAsInt();
        if (k < 0 || std::size_t(k) >= m_.lights.size())
            throw error(nname + " refers to light " + std::to_string(k) +
                        ", which does not exist (" + std::to_string(m_.lights.size()) + " lights)");
        const tinygltf::Light& g = m_.lights[std::size_t(k)];
        Luminaire l;
        l.name = !g.name.empty()      ? g.name
                 : !node.name.empty() ? node.name
                                      : "light" + std::to_string(k);
        const std::string what = "light " + std::to_string(k) + " ('" + l.name + "')";
        const bool directional = g.type == "directional";
        if (!directional && g.type != "point" && g.type != "spot")
            throw error(what + ": unknown type '" + g.type + "' (point, spot or directional)");
        dvec3 colour(1.0);
        if (g.color.size() == 3)
            colour = dvec3(g.color[0], g.color[1], g.color[2]);
        else if (!g.color.empty())
            throw error(what + ": color needs 3 numbers");
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(colour[c]) || colour[c] < 0)
                throw error(what + ": color " + num(colour[c]) + " must be a number >= 0");
        if (!std::isfinite(g.intensity) || g.intensity < 0)
            throw error(what + ": intensity " + num(g.intensity) + " must be >= 0 (" +
                        (directional ? "lux" : "candela") + ")");
        // Luminance weights of linear sRGB (Rec. 709), as --lux uses.
        const double y = 0.2126 * colour.x + 0.7152 * colour.y + 0.0722 * colour.z;
        if (colour.x != colour.y || colour.y != colour.z)
            warn_once("colour " + std::to_string(k),
                      what + ": color (" + num(colour.x) + ", " + num(colour.y) + ", " +
                          num(colour.z) +
                          ") is not modelled (luminaires are white): its "
                          "luminance " +
                          num(y) + " scales the intensity");
        if (directional) return add_sun(scene, nname, what, g.intensity * y, world);
        const double candela = g.intensity * y;
        l.position = dvec3(world * glm::dvec4(0, 0, 0, 1));
        l.aim = dvec3(world * glm::dvec4(0, 0, -1, 0)); // a spot shines down its local -z
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(l.position[c]) || !std::isfinite(l.aim[c]))
                throw error(nname + ": the transform of " + what + " is not finite");
        if (g.type == "point") {
            l.kind = "point";
            l.distribution = isotropic_distribution(candela);
            l.aim = dvec3(0, -1, 0);
        } else {
            l.kind = "spot";
            const double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
            if (!(inner >= 0 && inner < outer && outer <= std::numbers::pi / 2))
                throw error(what + ": innerConeAngle " + num(inner) + " and outerConeAngle " +
                            num(outer) + " must satisfy 0 <= inner < outer <= pi/2 (radians)");
            const double deg = 180 / std::numbers::pi;
            l.distribution = gltf_spot_distribution(candela, inner * deg, outer * deg);
        }
        try {
            l.orient();
        } catch (const InputError&) {
            throw error(nname + ": the transform of " + what + " has no direction (-z is 0)");
        }
        scene.luminaires.push_back(std::move(l));
    }

    void add_camera(Scene& scene, int index, const tinygltf::Node& node, const glm::dmat4& world) {
        const std::string name = "camera " + std::to_string(node.camera);
        if (std::size_t(node.camera) >= m_.cameras.size())
            throw error("node " + std::to_string(index) + " refers to " + name +
                        ", which does not exist");
        const tinygltf::Camera& c = m_.cameras[std::size_t(node.camera)];
        if (c.type != "perspective") {
            warn_once("camera " + c.type,
                      name + ": " + c.type + " cameras are not supported: skipped");
            return;
        }
        const double yfov = c.perspective.yfov;
        if (!(yfov > 0 && yfov < std::numbers::pi))
            throw error(name + ": yfov " + num(yfov) + " must be in (0, pi) radians");
        // A glTF camera looks down its local -z, with +y up.
        const dvec3 eye(world * glm::dvec4(0, 0, 0, 1));
        const dvec3 forward(world * glm::dvec4(0, 0, -1, 0));
        const dvec3 up(world * glm::dvec4(0, 1, 0, 0));
        if (!(glm::length(forward) > 0) || !(glm::length(glm::cross(forward, up)) > 0))
            throw error(name + " (node " + std::to_string(index) +
                        "): its transform leaves no view direction");
        Camera cam;
        cam.name = !c.name.empty() ? c.name : !node.name.empty() ? node.name : name;
        cam.eye = eye;
        cam.target = eye + glm::normalize(forward);
        cam.up = glm::normalize(up);
        cam.fov_y_deg = glm::degrees(yfov);
        scene.cameras.push_back(cam);
    }

    /// Our material for glTF material `index` (-1: none), made at first use.
    std::uint32_t material(Scene& scene, int index) {
        const auto it = materials_.find(index);
        if (it != materials_.end()) return it->second;
        Material mat;
        if (index < 0) {
            mat = Material{"default", dvec3(0.5), dvec3(0.0)};
            warn_once("no material", "primitives without a material use 'default' (rho 0.5, "
                                     "no emission)");
        } else {
            if (std::size_t(index) >= m_.materials.size())
                throw error("material " + std::to_string(index) + " does not exist (" +
                            std::to_string(m_.materials.size()) + " materials)");
            const tinygltf::Material& g = m_.materials[std::size_t(index)];
            const std::string name = "material " + std::to_string(index);
            mat.name = !g.name.empty() ? g.name : name;
            const std::vector<double>& f = g.pbrMetallicRoughness.baseColorFactor;
            dvec3 rho(1.0);
            if (f.size() >= 3) rho = dvec3(f[0], f[1], f[2]);
            const std::vector<double>& e = g.emissiveFactor;
            dvec3 Ke(0.0);
            if (e.size() >= 3) Ke = dvec3(e[0], e[1], e[2]);
            double strength = 1.0;
            // Glass (KHR_materials_transmission) is drawn opaque: a material does not say
            // whether its surfaces are panes; SCENE.json "glazing" does (glazing.h).
            if (const auto t = g.extensions.find("KHR_materials_transmission");
                t != g.extensions.end() && t->second.Has("transmissionFactor") &&
                t->second.Get("transmissionFactor").IsNumber() &&
                t->second.Get("transmissionFactor").GetNumberAsDouble() > 0) {
                char factor[32];
                std::snprintf(factor, sizeof factor, "%.3g",
                              t->second.Get("transmissionFactor").GetNumberAsDouble());
                warnings_.push_back(path_ + ": material '" + mat.name +
                                    "' transmits (KHR_materials_transmission " + factor +
                                    "): its surfaces are opaque here; to let light through "
                                    "them, name their groups in a SCENE.json \"glazing\"");
            }
            const auto ext = g.extensions.find("KHR_materials_emissive_strength");
            if (ext != g.extensions.end() && ext->second.Has("emissiveStrength")) {
                const tinygltf::Value& v = ext->second.Get("emissiveStrength");
                if (!v.IsNumber())
                    throw error(name + ": KHR_materials_emissive_strength.emissiveStrength "
                                       "is not a number");
                strength = v.GetNumberAsDouble();
            }
            for (int k = 0; k < 3; ++k) {
                if (!std::isfinite(rho[k]) || rho[k] < 0)
                    throw error(name + " ('" + mat.name + "'): baseColorFactor " + num(rho[k]) +
                                " must be a number in [0, 1]");
                if (!std::isfinite(Ke[k]) || Ke[k] < 0)
                    throw error(name + " ('" + mat.name + "'): emissiveFactor " + num(Ke[k]) +
                                " must be a number >= 0");
            }
            if (!std::isfinite(strength) || strength < 0)
                throw error(name + " ('" + mat.name + "'): emissiveStrength " + num(strength) +
                            " must be a number >= 0");
            mat.Ke = Ke * strength;
            const int tex = g.pbrMetallicRoughness.baseColorTexture.index;
            if (tex >= 0) {
                mat.texture = texture(scene, tex, name);
                if (g.pbrMetallicRoughness.baseColorTexture.texCoord != 0 && mat.texture >= 0) {
                    warn_once("texcoord " + name,
                              name + " ('" + mat.name + "'): baseColorTexture uses TEXCOORD_" +
                                  std::to_string(g.pbrMetallicRoughness.baseColorTexture.texCoord) +
                                  ": only TEXCOORD_0 is read, so it uses baseColorFactor times "
                                  "the texture's mean");
                    rho *= scene.textures[std::size_t(mat.texture)].mean();
                    mat.texture = -1;
                }
            }
            bool clamped = false;
            for (int k = 0; k < 3; ++k)
                if (rho[k] >= 1) rho[k] = options_.max_reflectance, clamped = true;
            // A factor of 1 is glTF's default (white, or the texture as it is): clamped quietly
            // when a texture multiplies it, with a warning otherwise.
            if (clamped && mat.texture < 0)
                warn_once("clamp " + name, name + " ('" + mat.name +
                                               "'): baseColorFactor of 1 or more (a "
                                               "surface can't reflect all the light it receives): "
                                               "reflectance " +
                                               num(options_.max_reflectance) +
                                               " used there (--max-reflectance)");
            if (g.emissiveTexture.index >= 0)
                warn_once("emissive texture " + name, name + " ('" + mat.name +
                                                          "'): emissiveTexture is not read "
                                                          "(emissiveFactor alone)");
            if (g.alphaMode == "BLEND" || (g.pbrMetallicRoughness.baseColorFactor.size() == 4 &&
                                           g.pbrMetallicRoughness.baseColorFactor[3] < 1))
                warn_once("alpha", name + " ('" + mat.name +
                                       "'): transparency is not "
                                       "modelled: every surface is opaque");
            mat.rho = rho;
            mat.two_sided = g.doubleSided;
        }
        const std::uint32_t id = std::uint32_t(scene.materials.size());
        scene.materials.push_back(mat);
        materials_.emplace(index, id);
        return id;
    }

    /// Our texture for glTF texture `index`, or -1 (its image could not be read: warned).
    int texture(Scene& scene, int index, const std::string& material) {
        if (std::size_t(index) >= m_.textures.size())
            throw error(material + ": baseColorTexture refers to texture " + std::to_string(index) +
                        ", which does not exist");
        const int source = m_.textures[std::size_t(index)].source;
        const auto known = texture_of_image_.find(source);
        if (known != texture_of_image_.end()) return known->second;
        int id = -1;
        const auto it = images.decoded.find(source);
        if (it != images.decoded.end()) {
            id = int(scene.textures.size());
            scene.textures.push_back(it->second);
        } else {
            warn_once("image " + std::to_string(source),
                      "texture " + std::to_string(index) + " (image " + std::to_string(source) +
                          ") could not be read: its materials use baseColorFactor alone");
        }
        texture_of_image_.emplace(source, id);
        return id;
    }

    void add_mesh(Scene& scene, int node_index, const tinygltf::Node& node,
                  const glm::dmat4& world) {
        const std::string mname = "mesh " + std::to_string(node.mesh);
        if (std::size_t(node.mesh) >= m_.meshes.size())
            throw error("node " + std::to_string(node_index) + " refers to " + mname +
                        ", which does not exist (" + std::to_string(m_.meshes.size()) + " meshes)");
        const tinygltf::Mesh& mesh = m_.meshes[std::size_t(node.mesh)];
        // A mirroring transform turns counter-clockwise into clockwise (glTF 3.7.4).
        const bool mirrored = glm::determinant(glm::dmat3(world)) < 0;
        for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            const tinygltf::Primitive& prim = mesh.primitives[pi];
            const std::string pname = mname + " primitive " + std::to_string(pi);
            if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
                warn_once("mode " + std::to_string(prim.mode),
                          pname + ": mode " + std::to_string(prim.mode) +
                              " (points, lines, strips or fans) is not read: only triangles "
                              "(mode 4); skipped");
                continue;
            }
            if (!prim.targets.empty())
                warn_once("morph", pname + ": morph targets are ignored (the base mesh is used)");
            const auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) throw error(pname + " has no POSITION");
            const std::vector<double> p = accessor(pos->second, 3, pname + " POSITION");
            const std::size_t nv = p.size() / 3;
            std::uint32_t mat = material(scene, prim.material);
            bool textured = scene.materials[mat].texture >= 0;
            std::vector<double> st;
            if (textured) {
                const auto tc = prim.attributes.find("TEXCOORD_0");
                if (tc != prim.attributes.end()) {
                    st = accessor(tc->second, 2, pname + " TEXCOORD_0");
                    if (st.size() / 2 != nv)
                        throw error(pname + ": TEXCOORD_0 has " + std::to_string(st.size() / 2) +
                                    " elements, POSITION " + std::to_string(nv));
                } else {
                    warn_once("no texcoord " + pname,
                              pname + " has a textured material but no TEXCOORD_0: it uses "
                                      "baseColorFactor times the texture's mean");
                    mat = untextured_material(scene, mat, variants_);
                    textured = false;
                }
            }
            std::vector<double> idx;
            if (prim.indices >= 0) {
                idx = accessor(prim.indices, 1, pname + " indices");
                const int type = m_.accessors[std::size_t(prim.indices)].componentType;
                if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                    type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                    type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                    warn_once("index type", pname + ": indices of component type " +
                                                std::to_string(type) +
                                                " (glTF allows unsigned integers only): read "
                                                "as numbers");
            } else {
                idx.resize(nv);
                for (std::size_t i = 0; i < nv; ++i) idx[i] = double(i);
            }
            if (idx.size() % 3)
                warn_once("index count " + pname,
                          pname + ": " + std::to_string(idx.size()) +
                              " indices are not a multiple of 3: the last ones are ignored");
            const std::string group = !node.name.empty() ? node.name
                                      : !scene.materials[mat].name.empty()
                                          ? scene.materials[mat].name
                                          : "node " + std::to_string(node_index);
            const std::uint32_t g = group_of(scene, group);
            std::vector<dvec3> corners(3);
            std::vector<glm::dvec2> uv(3);
            long degenerate = 0;
            if (idx.size() / 3 > kMaxTriangles - std::min(kMaxTriangles, triangles_))
                throw error(pname + ": more than " + std::to_string(kMaxTriangles) +
                            " triangles in the scene");
            triangles_ += idx.size() / 3;
            for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
                for (int k = 0; k < 3; ++k) {
                    const double i = idx[t + std::size_t(mirrored ? 2 - k : k)];
                    if (!(i >= 0 && i < double(nv)) || i != std::floor(i))
                        throw error(pname + ": index " + num(i) + " (accessor " +
                                    std::to_string(prim.indices) + ", element " +
                                    std::to_string(t + std::size_t(k)) + ") is outside its " +
                                    std::to_string(nv) + " vertices");
                    const std::size_t v = std::size_t(i);
                    const dvec3 q(world * glm::dvec4(p[3 * v], p[3 * v + 1], p[3 * v + 2], 1.0));
                    for (int c = 0; c < 3; ++c)
                        if (!std::isfinite(q[c]))
                            throw error(pname + ": vertex " + std::to_string(v) +
                                        " is not finite (accessor " + std::to_string(pos->second) +
                                        ")");
                    corners[std::size_t(k)] = q;
                    if (!st.empty()) uv[std::size_t(k)] = glm::dvec2(st[2 * v], st[2 * v + 1]);
                }
                const AddResult r =
                    add_polygon(scene, corners, mat, g, 1e-6, textured ? &uv : nullptr);
                degenerate += r.degenerate;
            }
            if (degenerate)
                warnings_.push_back(path_ + ": " + pname + ": dropped " +
                                    std::to_string(degenerate) +
                                    " degenerate triangle(s) (zero area or repeated vertices)");
        }
    }

    std::uint32_t group_of(Scene& scene, const std::string& name) {
        const auto [it, fresh] = groups_.try_emplace(name, std::uint32_t(scene.groups.size()));
        if (fresh) scene.groups.push_back(name);
        return it->second;
    }

    std::string path_;
    const tinygltf::Model& m_;
    ObjOptions options_;
    std::map<int, std::uint32_t> materials_;
    std::map<int, int> texture_of_image_;
    std::map<std::uint32_t, std::uint32_t> variants_;
    std::map<std::string, std::uint32_t> groups_;
    std::set<std::string> warned_;
    long visits_ = 0;
    std::size_t triangles_ = 0;
    std::vector<std::string> warnings_;
};

std::string lower_extension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e;
}

} // namespace

bool is_gltf(const std::string& path) {
    const std::string e = lower_extension(path);
    return e == ".gltf" || e == ".glb";
}

Scene load_gltf(const std::string& path, const ObjOptions& options) {
    if (!(options.max_reflectance > 0 && options.max_reflectance < 1))
        throw InputError("--max-reflectance " + num(options.max_reflectance) +
                         " must be in (0, 1)");
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path, 0, "no such file");
    if (fs::is_directory(path, ec)) throw InputError(path, 0, "is a directory, not a glTF file");
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    // Decode images ourselves (texture.h: sRGB to linear, our mipmap, our limits); TinyGLTF
    // still finds their bytes (data URIs, buffer views, files beside the glTF).
    static_assert(sizeof(int) >= 4);
    GltfReader reader(path, model, options);
    reader.images.file = path;
    loader.SetImageLoader(decode_image, &reader.images);
    const bool binary = lower_extension(path) == ".glb";
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                    : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    } catch (const std::exception& e) {
        throw InputError(path, 0, std::string("cannot read the glTF file (") + e.what() + ")");
    }
    const auto trim = [](std::string s) {
        while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
        for (char& c : s)
            if (c == '\n') c = ';';
        return s;
    };
    if (!ok || !err.empty())
        throw InputError(
            path, 0, "cannot read the glTF file: " + (err.empty() ? "unknown error" : trim(err)));
    Scene scene = reader.read();
    for (const std::string& w : reader.images.warnings) scene.warnings.push_back(w);
    if (!warn.empty()) scene.warnings.push_back(path + ": " + trim(warn));
    return scene;
}

} // namespace hemirad
