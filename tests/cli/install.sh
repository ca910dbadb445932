#!/usr/bin/env bash
# The installed package, used from outside: `cmake --install` into a temporary prefix, then
# examples/ configured with find_package(hemirad) against that prefix only (its compile lines
# must not name the source or build tree), built, run, and their output compared with the
# installed CLI's for the same scene and options: per-group irradiance (report) and the
# lightmap files (byte for byte: the solve is deterministic). Also pkg-config and --version.
set -euo pipefail
HEMIRAD="$1"
SRC="$2"
BUILD="$(cd "$(dirname "$HEMIRAD")" && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
P="$work/prefix"

cmake --install "$BUILD" --prefix "$P" >install.log
for f in bin/hemirad include/hemirad/hemirad.h include/hemirad/version.h \
         lib/cmake/hemirad/hemiradConfig.cmake lib/cmake/hemirad/hemiradConfigVersion.cmake \
         lib/cmake/hemirad/hemiradTargets.cmake lib/pkgconfig/hemirad.pc; do
    [ -e "$P/$f" ] || { echo "install: $f not installed"; exit 1; }
done
ls "$P"/lib/libhemirad.so.* >/dev/null
# No command-line plumbing and no private headers in the public API.
for f in args.h cli_options.h matrix_solver.h; do
    [ ! -e "$P/include/hemirad/$f" ] || { echo "install: private header $f installed"; exit 1; }
done
if grep -rhE '#include "(cli|gl|core|solver|output|render|ff|gpu)/' "$P/include/hemirad"; then
    echo "install: a public header includes a private one"; exit 1
fi

# One version: project(VERSION) in CMakeLists.txt, --version, the CMake and pkg-config files.
version=$(sed -nE 's/^project\(hemirad VERSION ([0-9.]+).*/\1/p' "$SRC/CMakeLists.txt")
[ "$("$P/bin/hemirad" --version)" = "hemirad $version" ] || { "$P/bin/hemirad" --version; exit 1; }
[ "$(PKG_CONFIG_PATH="$P/lib/pkgconfig" pkg-config --modversion hemirad)" = "$version" ]
# The installed tool runs on the installed library.
lib=$(ldd "$P/bin/hemirad" | sed -nE 's/.*libhemirad\.so[^ ]* => ([^ ]+).*/\1/p')
[ "$(dirname "$(realpath "$lib")")" = "$(realpath "$P/lib")" ] || { ldd "$P/bin/hemirad"; exit 1; }

# pkg-config alone is enough to build against it.
cat >pc.cpp <<'CPP'
#include <cstdio>
#include <hemirad/scene_io.h>
#include <hemirad/version.h>
int main() { std::printf("%s %zu\n", HEMIRAD_VERSION, hemirad::make_builtin("cube").polygons.size()); }
CPP
g++ -std=c++20 pc.cpp -o pc $(PKG_CONFIG_PATH="$P/lib/pkgconfig" pkg-config --cflags --libs hemirad) \
    -Wl,-rpath,"$P/lib"
[ "$(./pc)" = "$version 6" ] || { ./pc; exit 1; }

# examples/ against the installed package.
cmake -S "$SRC/examples" -B ex -DCMAKE_PREFIX_PATH="$P" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
      -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON >configure.log
grep -q "hemirad_DIR:PATH=$P/lib/cmake/hemirad" ex/CMakeCache.txt || {
    grep hemirad_DIR ex/CMakeCache.txt; exit 1; }
if grep -E -- "-I($SRC|$BUILD)" ex/compile_commands.json; then
    echo "install: the examples were compiled against the source or build tree"; exit 1
fi
cmake --build ex -j2 >build.log || { cat build.log; exit 1; }

# solve_groups: per-group E_avg as the CLI's report has it.
ex/solve_groups/solve_groups cie53 0.1 >groups.txt
"$P/bin/hemirad" solve cie53 --tolerance 0.1 --quiet --report r.json
python3 - <<'PY'
import json
report = {g["name"]: g["E_avg"] for g in json.load(open("r.json"))["groups"]}
rows = [l.split() for l in open("groups.txt") if not l.startswith("#")]
assert {r[0] for r in rows} == set(report), (rows, report.keys())
for name, *E in rows:
    for a, b in zip(map(float, E), report[name]):
        assert abs(a - b) <= 1e-8 * max(abs(b), 1e-30), (name, a, b)
assert any(float(x) > 0 for r in rows for x in r[1:])
PY

# bake_lightmaps: the same files as `hemirad solve --export-lightmaps`.
ex/bake_lightmaps/bake_lightmaps "$SRC/assets/cie53.obj" lm 0.1 >files.txt
"$P/bin/hemirad" solve "$SRC/assets/cie53.obj" --tolerance 0.1 --quiet --export-lightmaps lm_cli
[ "$(wc -l <files.txt)" -ge 3 ] || { cat files.txt; exit 1; }
[ "$(ls lm | wc -l)" = "$(ls lm_cli | wc -l)" ]
for f in lm_cli/*; do cmp "$f" "lm/$(basename "$f")"; done
echo "install: ok ($version, $(ls lm | wc -l) lightmap files)"
