#!/usr/bin/env bash
# Incremental re-solving on the command line (issue 21): --luminaire-multiplier and
# --reflectance, with and without --resume; --resume of a SCENE.json whose photometry differs
# (a luminaire's multiplier) is accepted and re-converges (rescaled by its light layer, or
# shot with --light-layers off), reported as incremental; one whose
# geometry differs (a luminaire moved) or another scene is refused; bad edits name the value.
set -euo pipefail
HEMIRAD="$1"
SRC="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
lighting="$SRC/tests/data/lighting"
# room.json with absolute paths, its luminaires edited by the Python snippet given.
scene() { # scene OUT.json PYTHON
    python3 - "$lighting" "$1" "$2" <<'PY'
import json, sys
src, out, edit = sys.argv[1], sys.argv[2], sys.argv[3]
j = json.load(open(src + "/room.json"))
j["include"] = [src + "/" + f for f in j["include"]]
for l in j["luminaires"]:
    if "ies" in l: l["ies"] = src + "/" + l["ies"]
lum = {l["name"]: l for l in j["luminaires"]}
exec(edit)
json.dump(j, open(out, "w"))
PY
}
scene room.json "pass"
scene dimmed.json 'lum["D1"]["multiplier"] = 0.5'
scene moved.json 'lum["P1"]["position"][0] += 0.5'
opts=(--tolerance 0.001 --grid floor:5x5 --grid-out)

"$HEMIRAD" solve room.json "${opts[@]}" base.csv --save-solution base.sol --quiet
# The edited SCENE.json resumes incrementally: the report says so and counts this run's shots.
"$HEMIRAD" solve dimmed.json --resume base.sol "${opts[@]}" inc.csv --report inc.json \
    2> inc.txt
grep -q "resumed incrementally from base.sol after [0-9]* shots: 1 luminaires" inc.txt ||
    { cat inc.txt; exit 1; }
grep -q "this run took [0-9]* shots in [0-9.]* s (resumed incrementally from [0-9]*)" inc.txt ||
    { cat inc.txt; exit 1; }
# The same edit on the command line, fresh (no --resume): the same grid.
"$HEMIRAD" solve room.json --luminaire-multiplier D1=0.5 "${opts[@]}" fresh.csv --quiet
python3 - <<'PY'
import csv, json
r = json.load(open("inc.json"))["resume"]
assert r["incremental"] and r["luminaires_changed"] == 1 and r["polygons_changed"] == 0, r
# The scene's luminaires have light layers (--light-layers auto): the dimming is a rescaling,
# and re-converging takes at most a few shots, not a solve's.
assert r["luminaires_rescaled"] == 1, r
assert r["shots_this_run"] * 20 <= r["shots_before"], r
def grid(f): return [float(row["E_Y"]) for row in csv.DictReader(open(f))]
base, inc, fresh = grid("base.csv"), grid("inc.csv"), grid("fresh.csv")
worst = max(abs(a / b - 1) for a, b in zip(inc, fresh))
assert worst < 0.01, worst
assert min(a / b for a, b in zip(base, inc)) > 1.05, "D1 halved must darken the floor"
PY
# Without light layers the dimming is shot as negative light; the grid is the same.
"$HEMIRAD" solve dimmed.json --resume base.sol --light-layers off "${opts[@]}" shot.csv \
    --report shot.json --quiet
python3 - <<'PY'
import csv, json
r = json.load(open("shot.json"))["resume"]
assert r["luminaires_rescaled"] == 0 and r["shots_this_run"] >= 1, r
def grid(f): return [float(row["E_Y"]) for row in csv.DictReader(open(f))]
worst = max(abs(a / b - 1) for a, b in zip(grid("shot.csv"), grid("fresh.csv")))
assert worst < 0.01, worst
PY
# Edits on the command line with --resume (P1 off, the floor's reflectance) re-converge too.
"$HEMIRAD" solve room.json --resume base.sol --luminaire-multiplier P1=0 \
    --reflectance floor=0.2,0.3,0.4 --reflectance floor=0.3 --quiet --report off.json
python3 -c '
import json; r = json.load(open("off.json"))
assert r["resume"]["luminaires_changed"] == 1 and r["resume"]["polygons_changed"] == 1, r["resume"]
assert r["stop_reason"] == "converged", r["stop_reason"]'

expect_fail() { # expect_fail WORD command...: fails, and the message holds WORD
    local word="$1"; shift
    if "$@" > out.txt 2> err.txt; then echo "accepted: $*"; exit 1; fi
    grep -q -- "$word" err.txt || { echo "no '$word' in: $(cat err.txt)"; exit 1; }
}
# Another geometry: a luminaire moved, or another scene.
expect_fail "another scene" "$HEMIRAD" solve moved.json --resume base.sol --quiet
expect_fail "geometry hash" "$HEMIRAD" solve moved.json --resume base.sol --quiet
expect_fail "another scene" "$HEMIRAD" solve cornell --resume base.sol --quiet
# Bad edits name the value.
expect_fail "no luminaire named 'Z'" "$HEMIRAD" solve room.json --luminaire-multiplier Z=1
expect_fail "P1=-1" "$HEMIRAD" solve room.json --luminaire-multiplier P1=-1
expect_fail "P1=nan" "$HEMIRAD" solve room.json --luminaire-multiplier P1=nan
expect_fail "'P1': expected NAME=F" "$HEMIRAD" solve room.json --luminaire-multiplier P1
expect_fail "'x'" "$HEMIRAD" solve room.json --luminaire-multiplier P1=x
expect_fail "floor=1.5" "$HEMIRAD" solve room.json --reflectance floor=1.5
expect_fail "no surface group 'roof'" "$HEMIRAD" solve room.json --reflectance roof=0.5
echo ok
