#!/usr/bin/env python3
"""Writes the textured assets of assets/ (run by tools/make_assets.sh; Python 3 standard
library only, deterministic output):

  textured_room.obj/.mtl + textured_room_floor.png, textured_room_wall.png
      a closed 4 x 2.5 x 4 m room: a checkerboard floor (map_Kd, repeated twice each way), a
      striped back wall (map_Kd with Kd as a multiplier), plain side walls and ceiling, a
      0.8 m square light 2 cm under the ceiling (exitance 1000 W/m^2).
  gltf_room.gltf + gltf_room.bin
      a 5 x 3 x 4 m room as a glTF 2.0 node tree (a root node scaled and moved, walls as a
      child mesh, a cube mesh instanced twice with rotations), a checkerboard floor texture
      held in the .bin (baseColorTexture), an emissive ceiling panel (emissiveFactor x
      KHR_materials_emissive_strength) and a perspective camera: the default view.

Usage: tools/make_texture_assets.py [ASSET_DIR]   (default: assets/ next to tools/)
"""
import json
import math
import os
import struct
import sys
import zlib


def png(width, height, rgb):
    """An 8-bit RGB PNG (rgb: rows top first, each a list of (r, g, b) in 0..255)."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rgb)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def checker(size, cells, a, b):
    step = size // cells
    return [[a if ((x // step) + (y // step)) % 2 == 0 else b for x in range(size)]
            for y in range(size)]


def stripes(size, colours):
    step = size // len(colours)
    return [[colours[min(y // step, len(colours) - 1)] for _ in range(size)] for y in range(size)]


# sRGB 8-bit colours (decoded to linear reflectance by hemirad).
CREAM, BROWN = (230, 220, 200), (120, 80, 50)
RED, GREEN, BLUE = (200, 60, 50), (70, 170, 80), (60, 90, 190)


def textured_room(out):
    floor = checker(64, 8, CREAM, BROWN)
    wall = stripes(32, [RED, GREEN, BLUE, GREEN])
    with open(os.path.join(out, "textured_room_floor.png"), "wb") as f:
        f.write(png(64, 64, floor))
    with open(os.path.join(out, "textured_room_wall.png"), "wb") as f:
        f.write(png(32, 32, wall))
    W, H, D = 4.0, 2.5, 4.0
    obj = [
        "# textured_room: a closed 4 x 2.5 x 4 m room (metres), every surface facing in",
        "# (tools/make_texture_assets.py). The floor is a checkerboard (textured_room_floor.png,",
        "# 4 x 4 squares per repeat, repeated twice each way: 0.25 m squares), the back wall",
        "# (z = 4) horizontal stripes (textured_room_wall.png) times Kd 0.9, the other walls and",
        "# the ceiling plain; a 0.8 m square light 2 cm under the ceiling, exitance 1000 W/m^2.",
        "# No camera: the default view looks across the room from a corner inside.",
        "mtllib textured_room.mtl",
    ]
    v = [(0, 0, 0), (W, 0, 0), (W, 0, D), (0, 0, D), (0, H, 0), (W, H, 0), (W, H, D), (0, H, D)]
    obj += ["v %g %g %g" % p for p in v]
    # vt: OBJ's v runs upwards in the image.
    obj += ["vt 0 0", "vt 2 0", "vt 2 2", "vt 0 2", "vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
    obj += ["usemtl floor", "g floor", "f 1/1 4/4 3/3 2/2"]
    obj += ["usemtl ceiling", "g ceiling", "f 5 6 7 8"]
    obj += ["usemtl stripes", "g back_wall", "f 4/5 8/8 7/7 3/6"]
    obj += ["usemtl wall", "g wall_x0", "f 1 5 8 4", "g wall_x1", "f 2 3 7 6", "g wall_z0",
            "f 1 2 6 5"]
    y = H - 0.02
    obj += ["v 1.6 %g 1.6" % y, "v 2.4 %g 1.6" % y, "v 2.4 %g 2.4" % y, "v 1.6 %g 2.4" % y]
    obj += ["usemtl light", "g light", "f 9 10 11 12"]
    with open(os.path.join(out, "textured_room.obj"), "w") as f:
        f.write("\n".join(obj) + "\n")
    mtl = [
        "# Materials of textured_room.obj: Kd is diffuse reflectance (a multiplier of map_Kd),",
        "# Ke emitted radiance (W sr^-1 m^-2).",
        "newmtl floor", "Kd 0.9 0.9 0.9", "map_Kd textured_room_floor.png",
        "newmtl stripes", "Kd 0.9 0.9 0.9", "map_Kd textured_room_wall.png",
        "newmtl ceiling", "Kd 0.8 0.8 0.8",
        "newmtl wall", "Kd 0.6 0.6 0.6",
        "newmtl light", "Kd 0.8 0.8 0.8", "Ke %r %r %r" % ((1000 / math.pi,) * 3),
    ]
    with open(os.path.join(out, "textured_room.mtl"), "w") as f:
        f.write("\n".join(mtl) + "\n")


class Bin:
    """The .bin buffer: views and accessors appended in order, 4-byte aligned."""

    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def view(self, payload, target=None):
        while len(self.data) % 4:
            self.data += b"\x00"
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if target:
            v["target"] = target
        self.data += payload
        self.views.append(v)
        return len(self.views) - 1

    def floats(self, rows, kind):
        n = len(rows[0])
        payload = b"".join(struct.pack("<%df" % n, *r) for r in rows)
        a = {"bufferView": self.view(payload, 34962), "componentType": 5126, "count": len(rows),
             "type": kind}
        if kind == "VEC3":
            a["min"] = [min(r[i] for r in rows) for i in range(3)]
            a["max"] = [max(r[i] for r in rows) for i in range(3)]
        self.accessors.append(a)
        return len(self.accessors) - 1

    def indices(self, idx, ctype):
        fmt = {5121: "B", 5123: "H", 5125: "I"}[ctype]
        payload = struct.pack("<%d%s" % (len(idx), fmt), *idx)
        self.accessors.append({"bufferView": self.view(payload, 34963), "componentType": ctype,
                               "count": len(idx), "type": "SCALAR"})
        return len(self.accessors) - 1


def quad_faces(quads):
    """Triangles (counter-clockwise) of quads given as 4 corner indices each."""
    out = []
    for a, b, c, d in quads:
        out += [a, b, c, a, c, d]
    return out


def gltf_room(out):
    b = Bin()
    # The room in local units of 0.5 m (the root node "room" scales by 0.5), so that node
    # transforms matter: local 10 x 6 x 8 -> 5 x 3 x 4 m.
    W, H, D = 10.0, 6.0, 8.0
    floor_pos = [(0, 0, 0), (0, 0, D), (W, 0, D), (W, 0, 0)]
    floor_uv = [(0, 0), (0, 2), (2.5, 2), (2.5, 0)]
    floor_p = b.floats(floor_pos, "VEC3")
    floor_t = b.floats(floor_uv, "VEC2")
    floor_i = b.indices(quad_faces([(0, 1, 2, 3)]), 5123)
    walls_pos = [(0, 0, 0), (W, 0, 0), (W, H, 0), (0, H, 0), (0, 0, D), (W, 0, D), (W, H, D),
                 (0, H, D)]
    walls_p = b.floats(walls_pos, "VEC3")
    walls_i = b.indices(quad_faces([(0, 1, 2, 3), (5, 4, 7, 6), (4, 0, 3, 7), (1, 5, 6, 2),
                                    (3, 2, 6, 7)]), 5123)
    # A unit cube facing out, without its bottom (it stands on the floor); one mesh, instanced
    # twice; indices as unsigned bytes.
    cube_pos = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    cube_p = b.floats(cube_pos, "VEC3")
    cube_i = b.indices(quad_faces([(0, 2, 3, 1), (4, 5, 7, 6), (2, 6, 7, 3), (0, 4, 6, 2),
                                   (1, 3, 7, 5)]), 5121)
    # The light panel: 1 x 1 m, facing down, 2 cm under the ceiling (room coordinates, m).
    light_pos = [(2.0, 2.98, 1.5), (3.0, 2.98, 1.5), (3.0, 2.98, 2.5), (2.0, 2.98, 2.5)]
    light_p = b.floats(light_pos, "VEC3")
    light_i = b.indices(quad_faces([(0, 1, 2, 3)]), 5125)
    tex = checker(64, 8, CREAM, BROWN)
    image_view = b.view(png(64, 64, tex))
    mesh = lambda name, p, i, m, t=None: {
        "name": name, "primitives": [dict({"attributes": dict({"POSITION": p},
                                                              **({"TEXCOORD_0": t} if t is not None else {})),
                                           "indices": i, "material": m, "mode": 4})]}
    gltf = {
        "asset": {"version": "2.0", "generator": "hemirad tools/make_texture_assets.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "room", "nodes": [0, 5, 6]}],
        "nodes": [
            {"name": "room", "scale": [0.5, 0.5, 0.5], "children": [1, 2, 3, 4]},
            {"name": "floor", "mesh": 0},
            {"name": "walls", "mesh": 1},
            # Cubes in room units (0.5 m): a 1 m block at (0.75, 0, 2.25) m, turned 30 degrees
            # about y; a 0.6 m block at (3.5, 0, 1.5) m, turned 45 degrees.
            {"name": "block_a", "mesh": 2, "translation": [1.5, 0, 4.5],
             "rotation": [0, math.sin(math.radians(15)), 0, math.cos(math.radians(15))],
             "scale": [2, 2, 2]},
            {"name": "block_b", "mesh": 2, "translation": [7, 0, 3],
             "rotation": [0, math.sin(math.radians(22.5)), 0, math.cos(math.radians(22.5))],
             "scale": [1.2, 1.2, 1.2]},
            {"name": "light", "mesh": 3},
            # The camera: at (2.5, 2.2, 0.2) m looking into the room (its -z towards +z, so
            # the rig is turned 180 degrees about y), tilted 25 degrees down by its own node.
            {"name": "camera_rig", "translation": [2.5, 2.2, 0.2], "rotation": [0, 1, 0, 0],
             "children": [7]},
            {"name": "camera", "camera": 0,
             "rotation": [math.sin(math.radians(-12.5)), 0, 0, math.cos(math.radians(-12.5))]},
        ],
        "cameras": [{"name": "door", "type": "perspective",
                     "perspective": {"yfov": math.radians(70), "znear": 0.05,
                                     "aspectRatio": 1.0}}],
        "meshes": [mesh("floor", floor_p, floor_i, 0, floor_t), mesh("walls", walls_p, walls_i, 1),
                   mesh("cube", cube_p, cube_i, 2), mesh("light", light_p, light_i, 3)],
        "materials": [
            {"name": "checker", "pbrMetallicRoughness": {
                "baseColorFactor": [0.9, 0.9, 0.9, 1], "baseColorTexture": {"index": 0},
                "metallicFactor": 0}},
            {"name": "plaster", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.65, 1],
                                                          "metallicFactor": 0}},
            {"name": "blue", "pbrMetallicRoughness": {"baseColorFactor": [0.15, 0.25, 0.6, 1],
                                                       "metallicFactor": 0}},
            # Ke = 1 x 1000/pi: exitance 1000 W/m^2.
            {"name": "panel", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1],
                                                        "metallicFactor": 0},
             "emissiveFactor": [1, 1, 1],
             "extensions": {"KHR_materials_emissive_strength": {
                 "emissiveStrength": 1000 / math.pi}}},
        ],
        "textures": [{"source": 0}],
        "images": [{"name": "checker", "bufferView": image_view, "mimeType": "image/png"}],
        "buffers": [{"uri": "gltf_room.bin", "byteLength": 0}],
        "bufferViews": b.views,
        "accessors": b.accessors,
    }
    gltf["buffers"][0]["byteLength"] = len(b.data)
    with open(os.path.join(out, "gltf_room.bin"), "wb") as f:
        f.write(bytes(b.data))
    with open(os.path.join(out, "gltf_room.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "assets")
    textured_room(out)
    gltf_room(out)


if __name__ == "__main__":
    main()
