#!/usr/bin/env bash
# Two-sided surfaces and cut intersections from the command line: --two-sided-surfaces doubles
# the polygons `hemirad scene` counts (and says so: "two-sided N polygons", --json
# two_sided_polygons); SCENE.json "two_sided" makes only the groups named two-sided, and an
# unknown group name is an error naming the file, the line and the name; two crossing quads are
# cut into four with a warning, and left whole with --split-intersections off; `hemirad solve`
# takes --two-sided-surfaces.
set -euo pipefail
HEMIRAD="$1"
ROOT="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# Two quads crossing in a plus shape: "a" in the plane y = 0, "b" in the plane z = 0, each
# through the middle of the other. A lamp above them so that nothing warns of a black scene.
printf 'newmtl white\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n' > m.mtl
cat > plus.obj <<'OBJ'
mtllib m.mtl
usemtl white
v -1 0 -1
v -1 0 1
v 1 0 1
v 1 0 -1
v -0.8 -1 0
v 0.8 -1 0
v 0.8 1 0
v -0.8 1 0
v -0.5 2 -0.5
v 0.5 2 -0.5
v 0.5 2 0.5
v -0.5 2 0.5
g a
f 1 2 3 4
g b
f 5 6 7 8
g lamp
usemtl lamp
f 9 10 11 12
OBJ

count() { # polygons, two_sided_polygons of `hemirad scene ARGS --json`
    "$HEMIRAD" scene "$@" --json 2> /dev/null |
        python3 -c 'import json, sys; s = json.load(sys.stdin); print(s["polygons"], s["two_sided_polygons"])'
}

# Cut by default (a and b into two pieces each, the lamp whole), with a warning; whole when off.
[ "$(count plus.obj)" = "5 0" ] || { echo "cut: $(count plus.obj), expected 5 0"; exit 1; }
"$HEMIRAD" scene plus.obj > out.txt 2> err.txt
grep -q "cut 2 polygon(s)" err.txt || { echo "no warning about the cut: $(cat err.txt)"; exit 1; }
grep -q "^polygons   5 " out.txt || { echo "not 5 polygons: $(cat out.txt)"; exit 1; }
off=$(count plus.obj --split-intersections off)
[ "$off" = "3 0" ] || { echo "--split-intersections off: $off, expected 3 0"; exit 1; }
"$HEMIRAD" scene plus.obj --split-intersections off > /dev/null 2> err.txt
if grep -q "cut " err.txt; then echo "cut with --split-intersections off: $(cat err.txt)"; exit 1; fi

# --two-sided-surfaces: every polygon (after the cut) gets a twin; the text output says so.
both=$(count plus.obj --two-sided-surfaces)
[ "$both" = "10 10" ] || { echo "--two-sided-surfaces: $both, expected 10 10"; exit 1; }
whole=$(count plus.obj --two-sided-surfaces --split-intersections off)
[ "$whole" = "6 6" ] || { echo "two-sided, not cut: $whole, expected 6 6"; exit 1; }
"$HEMIRAD" scene plus.obj --two-sided-surfaces > out.txt 2> /dev/null
grep -q "^two-sided  10 polygons" out.txt || { echo "no two-sided line: $(cat out.txt)"; exit 1; }
"$HEMIRAD" scene plus.obj > out.txt 2> /dev/null
if grep -q "two-sided" out.txt; then echo "two-sided line without twins"; exit 1; fi

# SCENE.json "two_sided": group b only (its two pieces).
printf '{"include": ["plus.obj"], "two_sided": ["b"]}\n' > b.json
[ "$(count b.json)" = "7 4" ] || { echo "two_sided [b]: $(count b.json), expected 7 4"; exit 1; }
# An unknown group: an error (exit 2) naming the file, the line and the name.
printf '{"include": ["plus.obj"],\n "two_sided": ["b", "Glas"]}\n' > bad.json
status=0
"$HEMIRAD" scene bad.json > /dev/null 2> err.txt || status=$?
[ "$status" = 2 ] || { echo "unknown group: exit status $status, expected 2"; exit 1; }
grep -q "bad.json:2:" err.txt || { echo "no file:line in: $(cat err.txt)"; exit 1; }
grep -q "'Glas'" err.txt || { echo "the unknown name not named in: $(cat err.txt)"; exit 1; }

# The solver takes the option too.
"$HEMIRAD" solve plus.obj --two-sided-surfaces --quiet --max-shots 3 --width 16 --height 16 \
    -o plus.png
[ -s plus.png ] || { echo "no image"; exit 1; }
echo ok
