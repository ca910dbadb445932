#!/usr/bin/env bash
# Textured and glTF scenes from the command line: the textured OBJ room, the glTF room and a
# .glb solve and write images and lightmaps; `hemirad scene` lists a glTF file's cameras; a bad
# glTF file is exit status 2 naming the file and the element; a missing texture is a warning.
set -euo pipefail
HEMIRAD="$1"
ROOT="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$HEMIRAD" solve "$ROOT/assets/textured_room.obj" --quiet --max-shots 30 --width 64 --height 64 \
    --max-depth 4 -o room.png --export-lightmaps lm
test -s room.png && test -s lm/floor.exr && test -s lm/back_wall.exr

"$HEMIRAD" solve "$ROOT/assets/gltf_room.gltf" --max-shots 20 --width 64 --height 64 \
    --max-depth 3 -o gltf.png 2> err.txt
grep -q "camera door" err.txt || { echo "the glTF camera is not the default view: $(cat err.txt)"; exit 1; }
"$HEMIRAD" solve "$ROOT/tests/data/gltf/nodes.glb" --quiet --max-shots 5 --width 32 --height 32 \
    --max-depth 1 -o glb.png
"$HEMIRAD" scene "$ROOT/assets/gltf_room.gltf" --json > scene.json
python3 - <<'PY'
import json
s = json.load(open("scene.json"))
# 34 faces; the floor cut along the two blocks' footprints (they stand on it): 44 polygons
assert s["polygons"] == 44, s["polygons"]
PY

# Errors: file and element named, exit status 2.
set +e
"$HEMIRAD" solve "$ROOT/tests/data/gltf/bad_accessor.gltf" --quiet 2> bad.txt
rc=$?
set -e
[ "$rc" = 2 ] || { echo "bad glTF: exit status $rc, not 2"; exit 1; }
grep -q "bad_accessor.gltf: accessor 0" bad.txt || { echo "message: $(cat bad.txt)"; exit 1; }

# A missing texture: a warning naming the MTL line; the solve goes on.
printf 'newmtl a\nKd 0.5 0.5 0.5\nmap_Kd gone.png\nnewmtl l\nKe 1 1 1\n' > t.mtl
printf 'mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl l\nf 1 3 4\n' > t.obj
"$HEMIRAD" solve t.obj --max-shots 3 --width 32 --height 32 -o t.png 2> warn.txt
grep -q "t.mtl:3: texture not read" warn.txt || { echo "no warning: $(cat warn.txt)"; exit 1; }
echo "textures: ok"
