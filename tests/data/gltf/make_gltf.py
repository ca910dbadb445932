#!/usr/bin/env python3
"""Writes the glTF test files of this folder (tests/gltf_test.cpp; seeds of tests/fuzz/
corpus/gltf). Deterministic; Python 3 standard library only. Run from anywhere:
    python3 tests/data/gltf/make_gltf.py
"""
import base64
import copy
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def pad4(b, fill=b"\x00"):
    return b + fill * ((4 - len(b) % 4) % 4)


def write_gltf(name, doc, buffer):
    """`name`.gltf with the buffer as a data URI (self-contained)."""
    d = copy.deepcopy(doc)
    if buffer is not None:
        d["buffers"] = [{"byteLength": len(buffer),
                         "uri": "data:application/octet-stream;base64," +
                                base64.b64encode(buffer).decode()}]
    with open(os.path.join(HERE, name + ".gltf"), "w") as f:
        json.dump(d, f, indent=1)
        f.write("\n")


def write_glb(name, doc, buffer):
    d = copy.deepcopy(doc)
    d["buffers"] = [{"byteLength": len(buffer)}]
    j = pad4(json.dumps(d).encode(), b" ")
    b = pad4(buffer)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + struct.pack("<II", len(b), 0x004E4942) + b
    with open(os.path.join(HERE, name + ".glb"), "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


# --- nodes: one triangle, three primitives (indices as u8, u16, u32), nested transforms -----
# Triangle (0,0,0), (1,0,0), (0,1,0) in the mesh's space.
positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
i8 = struct.pack("<3B", 0, 1, 2) + b"\x00"
i16 = struct.pack("<3H", 0, 1, 2) + b"\x00\x00"
i32 = struct.pack("<3I", 0, 1, 2)
buf = positions + i8 + i16 + i32
views = [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
         {"buffer": 0, "byteOffset": 36, "byteLength": 3},
         {"buffer": 0, "byteOffset": 40, "byteLength": 6},
         {"buffer": 0, "byteOffset": 48, "byteLength": 12}]
accessors = [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0]},
             {"bufferView": 1, "componentType": 5121, "count": 3, "type": "SCALAR"},
             {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"},
             {"bufferView": 3, "componentType": 5125, "count": 3, "type": "SCALAR"}]
s = math.sqrt(0.5)
nodes_doc = {
    "asset": {"version": "2.0"},
    "scene": 0,
    "scenes": [{"nodes": [0, 4]}],
    "nodes": [
        # root: translate (1, 2, 3)
        {"name": "root", "translation": [1, 2, 3], "children": [1]},
        # child: rotate 90 degrees about z, scale 2 (T R S: scale first)
        {"name": "turned", "rotation": [0, 0, s, s], "scale": [2, 2, 2], "children": [2]},
        # grandchild: a matrix translating by (0, 0, 1) (column-major)
        {"name": "leaf", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1], "mesh": 0,
         "children": [3]},
        {"name": "eye", "camera": 0},
        # a second root: the mesh untransformed, and a camera at (0, 0, 5) looking down -z
        {"name": "plain", "mesh": 0, "children": [5]},
        {"name": "cam", "camera": 1, "translation": [0, 0, 5]},
    ],
    "cameras": [{"name": "first", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}},
                {"name": "second", "type": "perspective",
                 "perspective": {"yfov": 1.0, "znear": 0.1}}],
    "meshes": [{"name": "tri", "primitives": [
        {"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
        {"attributes": {"POSITION": 0}, "indices": 2, "material": 0},
        {"attributes": {"POSITION": 0}, "indices": 3, "material": 1}]}],
    "materials": [
        {"name": "grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1]}},
        {"name": "glow", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.2, 0.2, 1]},
         "emissiveFactor": [0.5, 1, 0],
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}],
    "extensionsUsed": ["KHR_materials_emissive_strength"],
    "bufferViews": views,
    "accessors": accessors,
}
write_gltf("nodes", nodes_doc, buf)
write_glb("nodes", nodes_doc, buf)


def variant(name, change):
    d = copy.deepcopy(nodes_doc)
    change(d)
    write_gltf(name, d, buf)


# --- bad files ----------------------------------------------------------------------------
variant("bad_accessor", lambda d: d["accessors"][0].update(count=300))
# an index outside the 3 vertices: u8 index 7
buf_bad = positions + struct.pack("<3B", 0, 1, 7) + b"\x00" + i16 + i32
write_gltf("bad_index", nodes_doc, buf_bad)
variant("cycle", lambda d: d["nodes"][2].update(children=[0]))
variant("bad_mesh", lambda d: d["nodes"][4].update(mesh=9))
variant("lines", lambda d: d["meshes"][0]["primitives"][0].update(mode=1))
variant("lights", lambda d: d.update(extensionsUsed=["KHR_materials_emissive_strength",
                                                      "KHR_lights_punctual"]))
with open(os.path.join(HERE, "not_json.gltf"), "w") as f:
    f.write("{ this is not json\n")
d = copy.deepcopy(nodes_doc)
d["buffers"] = [{"byteLength": len(buf), "uri": "missing.bin"}]
with open(os.path.join(HERE, "missing_bin.gltf"), "w") as f:
    json.dump(d, f, indent=1)

# --- a textured quad whose image file is missing (a warning; baseColorFactor alone) ---------
quad = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0) + struct.pack("<8f", 0, 0, 1, 0, 1, 1, 0, 1) \
    + struct.pack("<6H", 0, 1, 2, 0, 2, 3)
tex_doc = {
    "asset": {"version": "2.0"},
    "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                "material": 0}]}],
    "materials": [{"name": "photo", "pbrMetallicRoughness": {
        "baseColorFactor": [0.5, 0.5, 0.5, 1], "baseColorTexture": {"index": 0}},
        "emissiveFactor": [1, 1, 1]}],
    "textures": [{"source": 0}],
    "images": [{"uri": "no_such_image.png"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
}
write_gltf("missing_image", tex_doc, quad)
