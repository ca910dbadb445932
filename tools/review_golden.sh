#!/usr/bin/env bash
# Reviews (and with --promote, replaces) the golden image of tests/render_gl_test.cpp.
#
#   tools/review_golden.sh [--promote] [BUILD_DIR]     (BUILD_DIR default: build)
#
# 1. Renders the Cornell box with the golden settings through `hemirad solve` into
#    BUILD_DIR/golden-review/cornell_96.exr (32-bit float) and a tone-mapped .png beside it.
# 2. Runs the golden test against that file (HEMIRAD_GOLDEN_ACTUAL) and prints the metric and
#    whether it is within the test's tolerance.
# 3. --promote: copies the new image over tests/golden/cornell_96.exr (and its .png preview).
#    Look at the .png first: red wall on the left (x = 556), green on the right (x = 0), light
#    in the ceiling, two white blocks with soft shadows and colour bleeding.
set -euo pipefail

promote=0
build=build
for arg in "$@"; do
    case "$arg" in
    --promote) promote=1 ;;
    -h | --help) sed -n '2,13p' "$0"; exit 0 ;;
    *) build="$arg" ;;
    esac
done
root=$(cd "$(dirname "$0")/.." && pwd)
case "$build" in /*) ;; *) build="$root/$build" ;; esac
hemirad="$build/hemirad"
test_bin="$build/tests/render_gl_test"
for f in "$hemirad" "$test_bin"; do
    [[ -x "$f" ]] || { echo "review_golden: $f not built (cmake --build $build)" >&2; exit 1; }
done

out="$build/golden-review"
mkdir -p "$out"
# The same settings as render_cornell_96() in tests/render_gl_test.cpp (which renders the
# leaves only: no per-pixel pass at discontinuities).
"$hemirad" solve cornell --ff hybrid --max-depth 4 --tolerance 0.02 --discontinuities off \
    --width 96 --height 96 --exr-float -o "$out/cornell_96.exr" -o "$out/cornell_96.png"
echo "review_golden: new image: $out/cornell_96.exr (preview $out/cornell_96.png)"

status=0
(cd "$out" && HEMIRAD_GOLDEN_ACTUAL="$out/cornell_96.exr" \
    "$test_bin" --gtest_filter='RenderGLTest.CornellGolden' --gtest_brief=1) || status=$?
if [[ $status -eq 0 ]]; then
    echo "review_golden: within tolerance of tests/golden/cornell_96.exr"
else
    echo "review_golden: differs from (or there is no) tests/golden/cornell_96.exr;" \
         "actual and diff images are in $out"
fi

if [[ $promote -eq 1 ]]; then
    mkdir -p "$root/tests/golden"
    cp "$out/cornell_96.exr" "$root/tests/golden/cornell_96.exr"
    cp "$out/cornell_96.png" "$root/tests/golden/cornell_96.png"
    echo "review_golden: promoted to tests/golden/cornell_96.exr (and .png preview)"
    exit 0
fi
exit $status
