#!/usr/bin/env bash
# Installs what hemirad needs from Debian 12's packages (only what is missing), then
# configures and builds it in ./build (Release). Safe to run again: it does only what is left.
#
#   tools/setup.sh            install + build
#   HEMIRAD_BUILD_DIR=dir     build somewhere else
#   HEMIRAD_BUILD_TYPE=Debug  a debug build (GL debug output on)
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${HEMIRAD_BUILD_DIR:-$root/build}"
type="${HEMIRAD_BUILD_TYPE:-Release}"

packages=(
  build-essential cmake pkg-config python3
  libegl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev   # headless GL: EGL (default), OSMesa
  libglfw3-dev libglm-dev python3-glad                     # viewer window, maths, GL loader
  libimgui-dev                                             # the viewer's panels (Dear ImGui)
  libopenexr-dev libpng-dev zlib1g-dev libgtest-dev
  libtinyobjloader-dev                                     # tests: the OBJ reader's oracle
  nlohmann-json3-dev                                       # SCENE.json files
  pybind11-dev python3-dev python3-numpy                   # the Python module (python/)
  dpkg-dev                                                 # cpack -G DEB: dpkg-shlibdeps
  libstb-dev libtinygltf-dev                               # textures (PNG, JPEG), glTF 2.0
  xvfb xauth                                               # the viewer's tests run under Xvfb
  clang libclang-rt-14-dev                                 # tools/fuzz.sh: libFuzzer, sanitizers
  clang-format                                             # tools/check_format.sh (CI)
  libopenmpi-dev openmpi-bin                               # mpirun -np N: ranks (docs/scaling.md)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root (or sudo) to install: ${missing[*]}" >&2; exit 1; }
    sudo=sudo
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs="$(nproc 2>/dev/null || echo 2)"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="$type" >/dev/null
echo "setup: building in $build (log: $build/build.log)" >&2
if ! cmake --build "$build" -j"$jobs" >"$build/build.log" 2>&1; then
  grep -E -A3 "error" "$build/build.log" | head -60 >&2
  echo "setup: the build failed; see $build/build.log" >&2
  exit 1
fi
echo "setup: built hemirad in $build" >&2
