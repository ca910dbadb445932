#!/usr/bin/env bash
# SCENE.json "sky" and --daylight-factor: `hemirad scene` lists the sky (text and JSON); bad
# sky inputs fail with a non-zero exit and a message naming the file, line and key;
# --daylight-factor without a sky is an error; with one, the probe and grid CSVs get a DF
# column and the report a DF block per grid (an open floor under the sky reads DF 100 %).
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

printf 'v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\ng floor\nf 1 2 3 4\n' > floor.obj
scene() { # scene FILE SKY [EXTRA]: a floor under that sky
    printf '{\n  "include": ["floor.obj"],\n  "sky": %s%s\n}\n' "$2" "${3:-}" > "$1"
}

scene ok.json '{"model": "cie-overcast", "illuminance": 10000, "ground_reflectance": 0.2}'
"$HEMIRAD" scene ok.json > out.txt
grep -q 'sky        cie-overcast, E_h 10000 lx .*zenith 4098.3.* cd/m2, ground reflectance 0.2 .*horizon blended' \
    out.txt || { echo "sky not listed: $(cat out.txt)"; exit 1; }
"$HEMIRAD" scene ok.json --json > ok_scene.json
python3 - <<'PY'
import json, math
s = json.load(open("ok_scene.json"))["sky"]
assert s["model"] == "cie-overcast" and s["illuminance"] == 10000 and s["horizon_blend"], s
# Blended with the ground near the horizon (as Radiance): renormalised, a little brighter.
assert 1 < s["zenith_luminance"] / (9 * 10000 / (7 * math.pi)) < 1.003, s
assert abs(s["ground_luminance"] - 0.2 * 10000 / math.pi) < 1e-6, s
PY
scene sharp.json '{"model": "cie-overcast", "illuminance": 10000, "horizon_blend": false}'
"$HEMIRAD" scene sharp.json --json > sharp_scene.json
python3 - <<'PY'
import json, math
s = json.load(open("sharp_scene.json"))["sky"]
assert not s["horizon_blend"] and abs(s["zenith_luminance"] - 9 * 10000 / (7 * math.pi)) < 1e-6, s
PY

fails() { # fails SKY KEY: loading a floor under SKY fails naming KEY at line 3
    scene bad.json "$1"
    if "$HEMIRAD" scene bad.json > out.txt 2> err.txt; then
        echo "accepted: $1"; exit 1
    fi
    grep -q "bad.json:3: $2" err.txt || { echo "no 'bad.json:3: $2' in: $(cat err.txt)"; exit 1; }
}
fails '{"model": "overcast", "illuminance": 1}' 'sky.model'
fails '{"model": "uniform", "illuminance": -1}' 'sky.illuminance'
fails '{"model": "uniform", "illuminance": "nan"}' 'sky.illuminance'
fails '{"model": "uniform", "illuminance": 1, "ground_reflectance": 1.5}' 'sky.ground_reflectance'
fails '{"model": "cie-clear", "illuminance": 1}' 'sky.model'
fails '{"model": "uniform", "lux": 1}' 'sky.lux'
fails '{"model": "uniform", "illuminance": 1, "horizon_blend": "yes"}' 'sky.horizon_blend'

# --daylight-factor: no sky, an error; with one, DF columns and the report's DF block.
printf '0.5,0,0.5,0,1,0\n0.5,1,0.5,0,1,0\n' > probes.csv
printf '{"include": ["floor.obj"], "luminaires": [{"position": [0.5, 1, 0.5], "candela": 100}]}\n' \
    > lamp.json
if "$HEMIRAD" solve lamp.json --daylight-factor --quiet 2> err.txt; then
    echo "--daylight-factor accepted without a sky"; exit 1
fi
grep -q 'daylight-factor needs a sky' err.txt || { echo "bad error: $(cat err.txt)"; exit 1; }
scene day.json '{"model": "cie-intermediate", "illuminance": 10000}' \
    ',
  "sun": {"altitude": 40, "azimuth": 180, "illuminance": 0}'
"$HEMIRAD" solve day.json --daylight-factor --probes probes.csv --probe-out p.csv \
    --grid floor:4x4 --grid-out g.csv --report r.json --quiet
python3 - <<'PY'
import csv, json
rows = list(csv.DictReader(open("p.csv")))
assert "DF" in rows[0], rows[0]
for r in rows:  # an open floor and a point above it: the whole sky, DF 100 %
    assert abs(float(r["DF"]) - 100) < 0.5, r
grid = list(csv.DictReader(open("g.csv")))
assert all(abs(float(r["DF"]) - 100) < 0.5 for r in grid), grid
g = json.load(open("r.json"))["grids"][0]["DF"]
for k in ("avg", "min", "median", "max"):
    assert abs(g[k] - 100) < 0.5, g
assert g["share_ge_1"] == 1 and g["share_ge_3"] == 1, g
PY
echo ok
