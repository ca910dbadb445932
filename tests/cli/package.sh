#!/usr/bin/env bash
# The Debian package: `cpack -G DEB` (into a temporary folder) writes hemirad_VERSION_amd64.deb
# with the version of project(VERSION) and dependencies from dpkg-shlibdeps; it holds the
# tools, the library, the public headers (and no private ones), the CMake and pkg-config
# files and the Python module; its hemirad, unpacked anywhere, runs on its own library.
# (Installing it with apt-get needs root and changes the system: README, "As a library".)
set -euo pipefail
HEMIRAD="$1"
SRC="$2"
BUILD="$(cd "$(dirname "$HEMIRAD")" && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

version=$(sed -nE 's/^project\(hemirad VERSION ([0-9.]+).*/\1/p' "$SRC/CMakeLists.txt")
cpack -G DEB --config "$BUILD/CPackConfig.cmake" -B "$work" >cpack.log 2>&1 || {
    cat cpack.log; exit 1; }
deb="hemirad_${version}_amd64.deb"
[ -f "$deb" ] || { ls; cat cpack.log; exit 1; }

[ "$(dpkg-deb -f "$deb" Package)" = hemirad ]
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ]
[ "$(dpkg-deb -f "$deb" Architecture)" = amd64 ]
depends=$(dpkg-deb -f "$deb" Depends)
for d in libc6 libstdc++6 libosmesa6 libopenexr libpng16-16 libegl1; do
    grep -q "$d" <<<"$depends" || { echo "package: Depends lacks $d: $depends"; exit 1; }
done

dpkg-deb --contents "$deb" | awk '{print $6}' >contents.txt
for f in ./usr/bin/hemirad ./usr/lib/libhemirad.so.0.1 ./usr/include/hemirad/hemirad.h \
         ./usr/include/hemirad/version.h ./usr/lib/cmake/hemirad/hemiradConfig.cmake \
         ./usr/lib/pkgconfig/hemirad.pc; do
    grep -qx -- "$f" contents.txt || { echo "package: $f missing"; cat contents.txt; exit 1; }
done
if [ -d "$BUILD/python" ]; then
    grep -q '^\./usr/lib/python3/dist-packages/hemirad\..*\.so$' contents.txt ||
        { echo "package: no Python module"; exit 1; }
fi
if grep -E 'hemirad/(args|cli_options|matrix_solver)\.h$' contents.txt; then
    echo "package: private headers packaged"; exit 1
fi

dpkg-deb -x "$deb" root
[ "$(root/usr/bin/hemirad --version)" = "hemirad $version" ]
root/usr/bin/hemirad solve cornell --max-shots 10 --quiet --report r.json
python3 -c 'import json; r = json.load(open("r.json")); assert r["shots"] == 10, r["shots"]'
echo "package: ok ($deb, $(wc -l <contents.txt) entries)"
