#!/usr/bin/env bash
# hemirad scene --json: the Cornell box's light emits power; a malformed OBJ fails with a
# message naming the file and line.
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$HEMIRAD" scene cornell --json > scene.json
python3 - <<'PY'
import json, math
s = json.load(open("scene.json"))
assert s["polygons"] > 0, s
total = s["emitted_power"]
assert len(total) == 3 and all(math.isfinite(x) and x > 0 for x in total), total
light = [g for g in s["groups"] if g["name"] == "light"]
assert len(light) == 1, [g["name"] for g in s["groups"]]
assert all(abs(a - b) <= 1e-9 * b for a, b in zip(light[0]["emitted_power"], total)), light
for g in s["groups"]:
    if g["name"] != "light":
        assert g["emitted_power"] == [0, 0, 0], g
PY

printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 zz 0\nf 1 2 3\n' > bad.obj
if "$HEMIRAD" scene bad.obj --json > out.txt 2> err.txt; then
    echo "malformed OBJ accepted"; exit 1
fi
grep -q 'bad.obj:4:' err.txt || { echo "no file:line in: $(cat err.txt)"; exit 1; }
grep -q "zz" err.txt || { echo "no value in: $(cat err.txt)"; exit 1; }
echo ok
