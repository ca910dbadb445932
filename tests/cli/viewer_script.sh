#!/usr/bin/env bash
# hemirad-view --script under a virtual X server (issue 21): the office walk-through, 400 shots,
# downlight D2 off, 400 more, a pick and a screenshot. The pick line's illuminance (final gather
# at the picked point) is within 3 % of `hemirad solve --luminaire-multiplier D2=0 --probes` at
# the same point and normal; the screenshot has the window's size. Then bad scripts: an unknown
# command, a bad argument and an unknown luminaire name are errors naming the script file and
# line (non-zero exit, no crash); a luminaire moved and aimed; a reflectance edit and a pick in
# W/unit^2 (--units W); the
# Dear ImGui panels draw (when built with them) and --no-panels hides them.
#
# CTest runs: bash viewer_script.sh <path to hemirad> <source dir>
set -euo pipefail

hemirad="$1"
src="$2"
build="$(cd "$(dirname "$hemirad")" && pwd)"
view="$build/hemirad-view"
[ -x "$view" ] || { echo "FAIL: $view not built (needs libglfw3-dev)" >&2; exit 1; }
command -v xvfb-run >/dev/null || {
    echo "FAIL: xvfb-run not found: the viewer test needs a virtual X server" \
         "(apt-get install -y xvfb xauth, or run tools/setup.sh)" >&2
    exit 1
}
office="$src/assets/lighting/office.json"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

# The issue's case, exactly.
cat > office.txt <<'SCRIPT'
# the office, one downlight off half-way
shots 400
luminaire D2 multiplier 0
shots 400
pick 480 620
screenshot office.png
quit
SCRIPT
start=$(date +%s)
xvfb-run -a -s "-screen 0 1280x1024x24" "$view" "$office" --width 960 --height 720 \
    --script office.txt --quiet > out.txt
echo "viewer script: $(($(date +%s) - start)) s"
cat out.txt
pick="$(grep '^pick 480 620: ' out.txt)" || { echo "FAIL: no pick line" >&2; exit 1; }
grep -q '^frame-time: [0-9]* frames drawn' out.txt || { echo "FAIL: no frame-time line" >&2; exit 1; }
# pick 480 620: x y z nx ny nz GROUP E lx -> the probe point.
read -r _ _ _ x y z nx ny nz group lux unit <<<"$pick"
[ "$unit" = lx ] || { echo "FAIL: pick not in lux: $pick" >&2; exit 1; }
printf 'x,y,z,nx,ny,nz\n%s,%s,%s,%s,%s,%s\n' "$x" "$y" "$z" "$nx" "$ny" "$nz" > probe.csv
"$hemirad" solve "$office" --luminaire-multiplier D2=0 --probes probe.csv --probe-out ref.csv \
    --quiet
python3 - "$lux" "$group" <<'PY'
import csv, struct, sys
lux, group = float(sys.argv[1]), sys.argv[2]
row = next(csv.DictReader(open("ref.csv")))
ref = 683 * (0.2126 * float(row["E_r"]) + 0.7152 * float(row["E_g"]) + 0.0722 * float(row["E_b"]))
assert row["group"] == group, f"probe group {row['group']} != pick group {group}"
err = lux / ref - 1
print(f"pick {lux:.1f} lx vs hemirad solve --probes {ref:.1f} lx: {100 * err:+.2f} %")
assert abs(err) < 0.03, f"pick differs from the probe by {100 * err:.2f} % (limit 3 %)"
data = open("office.png", "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "office.png: not a PNG"
w, h = struct.unpack(">II", data[16:24])
assert (w, h) == (960, 720), f"office.png is {w}x{h}, expected 960x720"
PY

# A luminaire moved and re-aimed in the viewer (light layers: its light leaves the old place,
# and is shot from the new one): the pick agrees with a fresh solve of the moved SCENE.json
# within 3 %, as above.
cat > moved.txt <<'SCRIPT'
shots 300
luminaire D2 position 3.7 2.79 2.1
luminaire D2 aim 0.3 -1 0
shots 400
pick 480 620
SCRIPT
xvfb-run -a "$view" "$office" --width 960 --height 720 --script moved.txt --quiet > moved_out.txt
python3 - "$src/assets/lighting" <<'PY'
import json, sys
src = sys.argv[1]
j = json.load(open(src + "/office.json"))
j["include"] = [src + "/" + f for f in j["include"]]
for l in j["luminaires"]:
    if "ies" in l: l["ies"] = src + "/" + l["ies"]
    if l["name"] == "D2": l["position"], l["aim"] = [3.7, 2.79, 2.1], [0.3, -1, 0]
json.dump(j, open("moved.json", "w"))
PY
read -r _ _ _ x y z nx ny nz group lux unit <<<"$(grep '^pick 480 620: ' moved_out.txt)"
printf 'x,y,z,nx,ny,nz\n%s,%s,%s,%s,%s,%s\n' "$x" "$y" "$z" "$nx" "$ny" "$nz" > moved_probe.csv
"$hemirad" solve moved.json --probes moved_probe.csv --probe-out moved_ref.csv --quiet
python3 - "$lux" <<'PY'
import csv, sys
lux = float(sys.argv[1])
row = next(csv.DictReader(open("moved_ref.csv")))
ref = 683 * (0.2126 * float(row["E_r"]) + 0.7152 * float(row["E_g"]) + 0.0722 * float(row["E_b"]))
err = lux / ref - 1
print(f"moved D2: pick {lux:.1f} lx vs hemirad solve of the moved scene {ref:.1f} lx: {100 * err:+.2f} %")
assert abs(err) < 0.03, f"pick differs by {100 * err:.2f} % (limit 3 %)"
PY

# Reflectance edits, grey and RGB (a blank line, an indented line); a pick in W/unit^2.
printf 'shots 20\n\nreflectance floor 0.5\n  reflectance floor 0.2 0.3 0.4\nshots 10\npick 80 40\n' \
    > small.txt
xvfb-run -a "$view" "$office" --width 160 --height 120 --script small.txt --units W --quiet \
    > small_out.txt
grep -Eq '^pick 80 40: [-0-9.e]+ [-0-9.e]+ [-0-9.e]+ .* W/unit\^2$' small_out.txt ||
    { echo "FAIL: W pick: $(cat small_out.txt)" >&2; exit 1; }

# The Dear ImGui panels (when built with them): drawn in the top left (Solver, Luminaires) and
# top right (Surface groups) with the status line shown; hidden by --no-panels and --no-overlay.
help="$("$view" --help)"
if [[ "$help" == *"--no-panels"*"(key P)"* ]]; then
    printf 'shots 20\nluminaire D1 multiplier 0\nshots 5\nscreenshot panels.png\n' > panels.txt
    xvfb-run -a "$view" "$office" --width 480 --height 360 --script panels.txt --quiet >/dev/null
    sed -i 's/panels.png/plain.png/' panels.txt
    xvfb-run -a "$view" "$office" --width 480 --height 360 --script panels.txt --no-panels \
        --quiet >/dev/null
    python3 - <<'PY'
import struct, zlib
def rgb(path):
    data = open(path, "rb").read()
    w, h = struct.unpack(">II", data[16:24])
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        if kind == b"IDAT": idat += data[pos + 8:pos + 8 + n]
        pos += 12 + n
    raw, stride, rows, prev = zlib.decompress(idat), 3 * w, [], bytearray(3 * w)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b, c = prev[i], prev[i - 3] if i >= 3 else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, rows
w, h, panels = rgb("panels.png")
_, _, plain = rgb("plain.png")
assert (w, h) == (480, 360), (w, h)
def changed(x0, x1, y0, y1):
    n = sum(panels[y][3 * x:3 * x + 3] != plain[y][3 * x:3 * x + 3]
            for y in range(y0, y1) for x in range(x0, x1))
    return n / ((x1 - x0) * (y1 - y0))
left, right = changed(10, 150, 10, 60), changed(330, 470, 10, 60)
print(f"panels: {100 * left:.0f}% of the top left and {100 * right:.0f}% of the top right changed")
assert left > 0.5 and right > 0.5, "no panels drawn"
PY
else
    echo "viewer script: this hemirad-view has no panels (built without Dear ImGui)"
fi

# Bad scripts: the message names the file and line; a non-zero exit that is not a signal.
bad() { # bad SCRIPT_TEXT EXPECTED_SUBSTRING
    printf '%b' "$1" > bad.txt
    rc=0
    err="$(xvfb-run -a "$view" "$office" --width 64 --height 48 --script bad.txt --quiet 2>&1)" ||
        rc=$?
    if [ "$rc" -eq 0 ] || [ "$rc" -ge 128 ]; then
        echo "FAIL: script '$1' exited $rc: $err" >&2; exit 1
    fi
    case "$err" in
        "hemirad-view: bad.txt:"[0-9]*": "*) ;;
        *) echo "FAIL: script '$1': the message names no line of bad.txt: $err" >&2; exit 1 ;;
    esac
    case "$err" in
        *"$2"*) ;;
        *) echo "FAIL: script '$1': expected '$2' in: $err" >&2; exit 1 ;;
    esac
}
bad 'shots 1\n# ok\nfly away\n' "bad.txt:3: 'fly away': unknown command 'fly'"
bad 'shots many\n' "bad.txt:1: 'shots many': N 'many'"
bad 'shots 1\nluminaire D2 multiplier -1\n' "bad.txt:2:"
bad 'reflectance floor 0.2 0.3\n' "bad.txt:1:"
bad 'reflectance floor 1.5\n' "bad.txt:1:"
bad 'pick 10\n' "bad.txt:1:"
bad 'pick 100 10\n' "bad.txt:1: pixel 100 10 is outside the 64x48 window"
bad 'screenshot shot.jpg\n' "bad.txt:1:"
bad 'quit now\n' "bad.txt:1:"
bad 'shots 1\nluminaire D9 multiplier 0\n' "bad.txt:2:"
bad 'shots 1\nluminaire D9 multiplier 0\n' "D9"
bad 'reflectance ceiling_tiles 0.5\n' "ceiling_tiles"
rc=0
err="$("$view" "$office" --script no-such-script.txt 2>&1)" || rc=$?
[ "$rc" -ge 1 ] && [ "$rc" -lt 128 ] && [[ "$err" == *"no-such-script.txt"* ]] ||
    { echo "FAIL: missing script: exit $rc: $err" >&2; exit 1; }
echo "viewer script: ok"
