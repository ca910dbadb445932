#!/usr/bin/env bash
# SCENE.json "sun": `hemirad scene` lists it (text and JSON); bad sun inputs fail with a
# non-zero exit and a message naming the file, line and key; a sun below the horizon warns.
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

printf 'v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nf 1 2 3 4\n' > floor.obj
scene() { # scene FILE SUN: a floor under that sun
    printf '{\n  "include": ["floor.obj"],\n  "sun": %s\n}\n' "$2" > "$1"
}

scene ok.json '{"altitude": 30, "azimuth": 90, "illuminance": 80000}'
"$HEMIRAD" scene ok.json > out.txt
grep -q 'sun .*towards (0.8660, 0.5000, 0.0000), altitude 30.00 deg, azimuth 90.00 deg.*E_n 80000 lx' \
    out.txt || { echo "sun not listed: $(cat out.txt)"; exit 1; }
"$HEMIRAD" scene ok.json --json > ok_scene.json
python3 - <<'PY'
import json
s = json.load(open("ok_scene.json"))["sun"]
assert abs(s["altitude"] - 30) < 1e-9 and abs(s["azimuth"] - 90) < 1e-9, s
assert abs(s["direction"][0] - 0.75 ** 0.5) < 1e-9 and s["illuminance"] == 80000, s
PY

fails() { # fails SUN KEY: loading a floor under SUN fails naming KEY at line 3
    scene bad.json "$1"
    if "$HEMIRAD" scene bad.json > out.txt 2> err.txt; then
        echo "accepted: $1"; exit 1
    fi
    grep -q "bad.json:3: $2" err.txt || { echo "no 'bad.json:3: $2' in: $(cat err.txt)"; exit 1; }
}
fails '{"direction": [0, 0, 0], "illuminance": 1}' 'sun.direction'
fails '{"altitude": 95, "azimuth": 0, "illuminance": 1}' 'sun.altitude'
fails '{"direction": [0, 1, 0], "illuminance": -5}' 'sun.illuminance'
fails '{"direction": [0, 1, 0], "altitude": 30, "illuminance": 1}' 'sun: '
fails '{"direction": [0, 1, 0], "lux": 1}' 'sun.lux'

scene below.json '{"direction": [0, -1, 1], "illuminance": 1000}'
"$HEMIRAD" scene below.json > out.txt 2>&1
grep -q 'below the horizon' out.txt || { echo "no warning: $(cat out.txt)"; exit 1; }
echo ok
