#!/usr/bin/env bash
# Writes the scene files of assets/ that come from built-in scenes, with `hemirad scene NAME
# --obj`, so that the files and the built-ins stay the same scene (tests/scene_loader_test.cpp,
# Assets.*, compares their content hashes). assets/cube_room.* is written by hand.
#
#   tools/make_assets.sh [BUILD_DIR]     (default: build)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
hemirad="${1:-$root/build}/hemirad"
for name in cornell cie53 cie56 cie57 cie58 room402 scene3138; do
  "$hemirad" scene "$name" --obj "$root/assets/$name.obj" >/dev/null
done
# The textured room (OBJ/MTL + PNG) and the glTF room (.gltf + .bin), written by a generator of
# their own (Python standard library only).
python3 "$root/tools/make_texture_assets.py" "$root/assets"
