#!/usr/bin/env bash
# Lighting design from a SCENE.json (issue 12's "done when"): an IES downlight and an isotropic
# point source over a black floor; `--grid floor:9x9 --grid-out g.csv --lux` gives, at every
# grid point, the lux of I(gamma) cos(theta) / r^2 summed over both within 1 %, computed here
# from the analytic distributions (not the table). Also: the report's luminaire schedule,
# installed lumens, U0 and Emin/Emax, the grid plan PNG, the scene JSON, save/resume of a
# scene with luminaires, and errors that name the file, the line and the key or value.
set -euo pipefail
HEMIRAD="$1"
SRC="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
room="$SRC/tests/data/lighting/room.json"

"$HEMIRAD" solve "$room" --grid floor:9x9 --grid-out g.csv --lux --report r.json \
    --grid-png plans 2> log.txt
grep -q "2 luminaires, 9422.78 lm installed" log.txt || { cat log.txt; exit 1; }
grep -q "grid floor 9x9: Emin .* lx, Eavg .* lx, Emax .* lx, U0 = Emin/Eavg" log.txt ||
    { cat log.txt; exit 1; }
python3 - <<'PY'
import csv, json, math
# D1: bilateral_0_180.ies, I = 1000 cos(g) (1 + 0.3 cos C) turned by 30 degrees, at (1.5, 2.8, 2)
# aimed down: C = 0 along +x, counterclockwise seen from above (+x -> -z). P1: 500 cd at (3, 2, 1).
def d1(x, z):
    dx, dy, dz = x - 1.5, -2.8, z - 2
    r = math.sqrt(dx * dx + dy * dy + dz * dz)
    g = math.acos(-dy / r)
    c = math.atan2(-dz, dx) - math.radians(30)
    return 1000 * math.cos(g) * (1 + 0.3 * math.cos(c)) * (2.8 / r) / r**2
def p1(x, z):
    dx, dy, dz = x - 3, -2, z - 1
    r = math.sqrt(dx * dx + dy * dy + dz * dz)
    return 500 * (2 / r) / r**2
rows = list(csv.DictReader(open("g.csv")))
assert len(rows) == 81, len(rows)
worst = 0
for row in rows:
    x, z = float(row["x"]), float(row["z"])
    want = d1(x, z) + p1(x, z)
    got = float(row["lux"])
    worst = max(worst, abs(got / want - 1))
    assert abs(got - want) <= 0.01 * want, (x, z, got, want)
print("lighting: 81 grid points within %.3f %% of I cos / r^2" % (100 * worst))

r = json.load(open("r.json"))
lum = {l["name"]: l for l in r["luminaires"]}
assert set(lum) == {"D1", "P1"}, lum
assert lum["D1"]["kind"] == "ies" and lum["D1"]["file"] == "../ies/bilateral_0_180.ies", lum["D1"]
assert abs(lum["D1"]["lumens"] / (1000 * math.pi) - 1) < 2e-3, lum["D1"]  # cos C averages out
assert abs(lum["P1"]["lumens"] - 4 * math.pi * 500) < 1e-9, lum["P1"]
assert abs(r["installed_lumens"] - lum["D1"]["lumens"] - lum["P1"]["lumens"]) < 1e-9
# Every watt accounted for: emitted = absorbed + escaped + unshot, and it is the lumens / 683.
assert abs(r["emitted_power"][1] * 683 - r["installed_lumens"]) < 1e-9 * r["installed_lumens"]
bal = r["absorbed_power"][1] + r["escaped_power"][1] + r["unshot_power"][1]
assert abs(bal - r["emitted_power"][1]) < 1e-6 * r["emitted_power"][1], bal
g = r["grids"][0]
assert abs(g["U0"] - g["lux"]["min"] / g["lux"]["avg"]) < 1e-12, g
assert abs(g["Emin/Emax"] - g["lux"]["min"] / g["lux"]["max"]) < 1e-12, g
floor = [x for x in r["groups"] if x["name"] == "floor"][0]
assert 0 < floor["lumens"] < r["installed_lumens"], floor
PY
python3 -c "
d = open('plans/floor.png', 'rb').read()
assert d[:8] == b'\x89PNG\r\n\x1a\n', d[:8]
"

# The scene JSON lists the luminaires with their lumens.
"$HEMIRAD" scene "$room" --json > s.json
python3 -c "
import json; s = json.load(open('s.json'))
assert [l['name'] for l in s['luminaires']] == ['D1', 'P1'], s['luminaires']
assert s['cameras'] == ['door'], s['cameras']
"

# Two included files: groups of the same name merge; paths are relative to the JSON file.
mkdir -p sub
cp "$SRC/tests/data/lighting/black_floor."* sub/
printf 'mtllib black_floor.mtl\nv 4 0 0\nv 8 0 0\nv 8 0 4\nv 4 0 4\ng floor\nusemtl black\nf 4 3 2 1\n' > sub/more.obj
printf '{"include": ["sub/black_floor.obj", "sub/more.obj"], "luminaires": [{"candela": 10, "position": [4, 2, 2]}]}\n' > merged.json
"$HEMIRAD" scene merged.json --json > merged_scene.json
python3 -c "
import json; s = json.load(open('merged_scene.json'))
assert [(g['name'], g['polygons'], g['area']) for g in s['groups']] == [('floor', 2, 32)], s['groups']
assert s['luminaires'][0]['name'] == 'L1' and s['warnings'] == [], s
"

# Save after the first shot (a luminaire's), resume: the same grid as an uninterrupted run.
"$HEMIRAD" solve "$room" --quiet --max-shots 1 --save-solution s.bin
"$HEMIRAD" solve "$room" --quiet --resume s.bin --grid floor:9x9 --grid-out g2.csv --lux
cmp g.csv g2.csv

# Errors name the file, the line and the key or value.
expect_error() { # file, then patterns the message must hold
    local f="$1"; shift
    if "$HEMIRAD" scene "$f" > out.txt 2> err.txt; then echo "accepted: $f"; exit 1; fi
    for p in "$@"; do
        grep -q -- "$p" err.txt || { echo "no '$p' in: $(cat err.txt)"; exit 1; }
    done
}
cp "$SRC/tests/data/lighting/black_floor."* .
cat > typo.json <<'EOF'
{"include": ["black_floor.obj"],
 "luminaires": [
   {"candela": 500,
    "positon": [1, 2, 1]}
 ]}
EOF
expect_error typo.json "typo.json:4:" "luminaires\[0\].positon" "unknown key 'positon'"
printf '{"include": ["black_floor.obj"], "lights": []}\n' > top.json
expect_error top.json "top.json:1:" "unknown key 'lights'"
printf '{"include": ["black_floor.obj"],\n "luminaires": [{"ies": "none.ies", "position": [1, 2, 1]}]}\n' > noies.json
expect_error noies.json "noies.json:2:" "none.ies"
printf 'IESNA:LM-63-2002\n[TEST] t\nTILT=INCLUDE\n1\n' > tilt.ies
printf '{"include": ["black_floor.obj"],\n "luminaires": [{"ies": "tilt.ies", "position": [1, 2, 1]}]}\n' > tilt.json
expect_error tilt.json "tilt.json:2:" "tilt.ies:4:" "TILT=INCLUDE number of tilt angles"
printf 'company\r\n1\r\n7\r\n' > bad.ldt
printf '{"include": ["black_floor.obj"],\n "luminaires": [{"ldt": "bad.ldt", "position": [1, 2, 1]}]}\n' > ldt.json
expect_error ldt.json "ldt.json:2:" "luminaires\[0\].ldt" "bad.ldt:3: Isym (symmetry indicator) '7'"
printf '{"include": ["black_floor.obj"],\n "luminaires": [{"candela": 5, "spot": {"candela": 5, "cone": 20}, "position": [1, 2, 1]}]}\n' > two.json
expect_error two.json "two.json:2:" "not several"
printf '{"include": ["black_floor.obj"],\n "luminaires": [{"spot": {"candela": 5, "cone": 20, "falof": 5}, "position": [1, 2, 1]}]}\n' > spot.json
expect_error spot.json "spot.json:2:" "unknown key 'falof'"
printf '{"include": ["black_floor.obj"],\n "luminaires": [{"candela": 5, "position": [1, 2]}]}\n' > pos.json
expect_error pos.json "pos.json:2:" "luminaires\[0\].position" "3 numbers"
printf '{"include": ["black_floor.obj"], \n "cameras": [{"eye": [0, 1, 0]}]\n' > broken.json
expect_error broken.json "broken.json" "not valid JSON"
echo ok
