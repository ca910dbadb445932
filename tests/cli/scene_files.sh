#!/usr/bin/env bash
# Scene files from the command line: a built-in scene written with `hemirad scene NAME --obj`
# reads back the same (uncut: by default the floor is cut under the blocks that stand on it); an asset solves and its default PNG is not black; --max-reflectance and
# --two-sided are accepted, bad values refused with exit status 2; a warning names file:line.
set -euo pipefail
HEMIRAD="$1"
ROOT="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$HEMIRAD" scene cornell --obj box.obj 2> err.txt > /dev/null
grep -q "wrote box.obj and box.mtl" err.txt || { echo "no 'wrote' line: $(cat err.txt)"; exit 1; }
"$HEMIRAD" scene cornell --json > a.json
"$HEMIRAD" scene box.obj --split-intersections off --json > b.json
python3 - <<'PY'
import json
a, b = json.load(open("a.json")), json.load(open("b.json"))
for k in ("polygons", "triangles", "quads", "total_area", "emitted_power"):
    assert a[k] == b[k], (k, a[k], b[k])
assert [g["name"] for g in a["groups"]] == [g["name"] for g in b["groups"]]
assert b["warnings"] == [], b["warnings"]
PY

# An asset without a camera: the default view shows the lit room.
"$HEMIRAD" solve "$ROOT/assets/cube_room.obj" --quiet --max-shots 40 --width 64 --height 64 \
    -o room.png --two-sided --max-reflectance 0.95
python3 - <<'PY'
import struct, zlib
# Decode the 8-bit RGB PNG (filters 0-4) and check that most pixels are lit.
data = open("room.png", "rb").read()
pos, idat, width, height = 8, b"", 0, 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos : pos + 8])
    body = data[pos + 8 : pos + 8 + n]
    if kind == b"IHDR":
        width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        assert (depth, colour) == (8, 2), (depth, colour)
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
raw, bpp, stride = zlib.decompress(idat), 3, width * 3
rows, prev = [], bytearray(stride)
for y in range(height):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b, c = prev[i], prev[i - bpp] if i >= bpp else 0
        p = a + b - c
        pred = [0, a, b, (a + b) // 2,
                a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c)
                else b if abs(p - b) <= abs(p - c) else c][f]
        line[i] = (line[i] + pred) & 255
    rows.append(line)
    prev = line
lit = sum(1 for r in rows for x in range(width) if max(r[3 * x : 3 * x + 3]) > 20)
assert lit > 0.6 * width * height, (lit, width * height)  # all dark when black
PY

# Kd 1 warned with the MTL's file:line; the option's bad value refused.
printf 'mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl white\nf 1 2 3\n' > kd.obj
printf 'newmtl white\nKd 1 1 1\nKe 1 1 1\n' > m.mtl
"$HEMIRAD" scene kd.obj 2> err.txt > /dev/null
grep -q "m.mtl:2: Kd 1 1 1 of material 'white' is 1 or more" err.txt || {
    echo "no Kd warning: $(cat err.txt)"; exit 1; }
status=0
"$HEMIRAD" scene kd.obj --max-reflectance 1 2> err.txt > /dev/null || status=$?
[ "$status" = 2 ] || { echo "--max-reflectance 1: status $status"; exit 1; }
grep -q -- "--max-reflectance 1 must be in (0, 1)" err.txt || { echo "$(cat err.txt)"; exit 1; }
echo ok
