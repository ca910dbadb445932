#!/usr/bin/env bash
# --export-ply parses back (vertex count, property names, finite values, faces in range);
# --export-lightmaps writes an EXR, OBJ and MTL per surface group. (The exact texel values are
# checked in tests/export_test.cpp.)
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$HEMIRAD" solve cornell --max-shots 20 --max-depth 4 --quiet --export-ply m.ply \
    --export-lightmaps lm --report r.json
python3 - <<'PY'
import json, math, struct
data = open("m.ply", "rb").read()
end = data.index(b"end_header\n") + len(b"end_header\n")
header = data[:end].decode().splitlines()
assert header[0] == "ply" and header[1] == "format binary_little_endian 1.0", header[:2]
props, nv, nf = [], None, None
for line in header:
    w = line.split()
    if w[:2] == ["element", "vertex"]: nv = int(w[2])
    if w[:2] == ["element", "face"]: nf = int(w[2])
    if w[0] == "property" and w[1] == "float": props.append(w[2])
assert props == ["x", "y", "z", "red", "green", "blue"], props
r = json.load(open("r.json"))
assert nv > r["leaf_patches"] and nf >= r["leaf_patches"], (nv, nf, r["leaf_patches"])
verts = struct.unpack_from("<%df" % (6 * nv), data, end)
assert all(math.isfinite(v) for v in verts)
assert all(v >= 0 for i, v in enumerate(verts) if i % 6 >= 3)
assert max(verts[i] for i in range(3, 6 * nv, 6)) > 0
off = end + 24 * nv
for f in range(nf):
    n, a, b, c = struct.unpack_from("<Biii", data, off)
    assert n == 3 and 0 <= min(a, b, c) and max(a, b, c) < nv
    off += 13
assert off == len(data), (off, len(data))
PY
for g in floor ceiling light back_wall; do
    for ext in exr obj mtl; do [ -s "lm/$g.$ext" ] || { echo "missing lm/$g.$ext"; exit 1; }; done
done
grep -q '^vt ' lm/floor.obj && grep -q 'map_Kd floor.exr' lm/floor.mtl
if ls lm | grep -q '\.tmp-'; then echo "temporary files left"; exit 1; fi

# Grids in the report: x or × between the counts, lux = 683 lm/W x luminance.
"$HEMIRAD" solve cornell --max-shots 10 --max-depth 3 --quiet --grid 'floor:3×2' \
    --grid ceiling:2x2 --lux --report g.json --grid-out g.csv
python3 - <<'PY'
import json, csv
r = json.load(open("g.json"))
g = r["grids"]
assert [(x["group"], x["nx"], x["ny"], x["points"]) for x in g] == \
    [("floor", 3, 2, 6), ("ceiling", 2, 2, 4)], g
f = g[0]
assert f["E_min"] <= f["E_avg"] <= f["E_max"] and abs(f["U0"] - f["E_min"] / f["E_avg"]) < 1e-12
assert abs(f["lux"]["avg"] - 683 * f["E_avg"]) <= 1e-9 * f["lux"]["avg"]
rows = list(csv.DictReader(open("g.csv")))
assert len(rows) == 10 and rows[0]["group"] == "floor", rows[0]
PY
echo ok
