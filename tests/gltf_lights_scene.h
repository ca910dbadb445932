// A small glTF file with KHR_lights_punctual lights over a black plane, written by the tests
// that read lights (gltf_test.cpp, luminaire_gl_test.cpp): the plane is [-a, a]^2 at y = 0
// facing up (a mesh node "floor"), and the lights' nodes (JSON text each, light k at index k)
// hang under a parent node "rig" translated by `rig`.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hemirad/error.h"

namespace hemirad::test {

struct GltfLight {
    std::string light; ///< the light object: {"type": "point", "intensity": 100}
    std::string node;  ///< the node's other members: "\"translation\": [0, 2, 0]"
};

/// Writes DIR/NAME.gltf and DIR/NAME.bin; returns the .gltf's path.
inline std::string write_gltf_lights(const std::filesystem::path& dir, const std::string& name,
                                     double a, const double rig[3],
                                     const std::vector<GltfLight>& lights) {
    std::filesystem::create_directories(dir);
    const float p[12] = {float(-a), 0, float(-a), float(a),  0, float(-a),
                         float(a),  0, float(a),  float(-a), 0, float(a)};
    // Counterclockwise seen from +y; the first edge along +z, so that a grid over the plane
    // (grid.h: u along the first edge) is aligned with the square.
    const std::uint16_t idx[6] = {0, 3, 2, 0, 2, 1};
    {
        std::ofstream bin(dir / (name + ".bin"), std::ios::binary);
        bin.write(reinterpret_cast<const char*>(p), sizeof p);
        bin.write(reinterpret_cast<const char*>(idx), sizeof idx);
    }
    std::string nodes =
        "{\"name\": \"floor\", \"mesh\": 0}, {\"name\": \"rig\", \"translation\": [" + num(rig[0]) +
        ", " + num(rig[1]) + ", " + num(rig[2]) + "], \"children\": [";
    for (std::size_t k = 0; k < lights.size(); ++k)
        nodes += (k ? ", " : "") + std::to_string(k + 2);
    nodes += "]}";
    std::string list;
    for (std::size_t k = 0; k < lights.size(); ++k) {
        nodes += ", {" + lights[k].node + (lights[k].node.empty() ? "" : ", ") +
                 "\"extensions\": {\"KHR_lights_punctual\": {\"light\": " + std::to_string(k) +
                 "}}}";
        list += (k ? ", " : "") + lights[k].light;
    }
    const std::string json =
        "{\"asset\": {\"version\": \"2.0\"}, \"extensionsUsed\": [\"KHR_lights_punctual\"],\n"
        "\"extensions\": {\"KHR_lights_punctual\": {\"lights\": [" +
        list +
        "]}},\n"
        "\"scene\": 0, \"scenes\": [{\"nodes\": [0, 1]}],\n\"nodes\": [" +
        nodes +
        "],\n"
        "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, "
        "\"material\": 0}]}],\n"
        "\"materials\": [{\"name\": \"black\", \"pbrMetallicRoughness\": {\"baseColorFactor\": "
        "[0, 0, 0, 1]}}],\n"
        "\"buffers\": [{\"uri\": \"" +
        name +
        ".bin\", \"byteLength\": 60}],\n"
        "\"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 48}, "
        "{\"buffer\": 0, \"byteOffset\": 48, \"byteLength\": 12}],\n"
        "\"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": "
        "\"VEC3\", \"min\": [" +
        num(-a) + ", 0, " + num(-a) + "], \"max\": [" + num(a) + ", 0, " + num(a) +
        "]}, {\"bufferView\": 1, \"componentType\": 5123, \"count\": 6, \"type\": "
        "\"SCALAR\"}]}\n";
    const std::filesystem::path out = dir / (name + ".gltf");
    std::ofstream(out) << json;
    return out.string();
}

} // namespace hemirad::test
