#!/usr/bin/env bash
# Builds hemirad with AddressSanitizer + UndefinedBehaviorSanitizer (-DHEMIRAD_SANITIZE=
# address,undefined) in its own folder and runs the tests under them; the first report stops
# the test that made it (halt_on_error) and fails the run.
#
#   tools/sanitize.sh            the CI subset (below)
#   tools/sanitize.sh --all      the whole suite (about 3x the normal suite's time)
#   HEMIRAD_SANITIZE_BUILD_DIR=dir   build somewhere else (default build-sanitize)
#
# The CI subset exercises every parser (OBJ/MTL loader and its corpus, probe CSV, grid and
# camera options, the option parser, solution files and their fuzz regressions), the solver,
# the GPU provider (hemicube, hybrid, parallax), the outputs (images, EXR/PNG, reports, PLY,
# lightmaps, atomic files) and the command line; it leaves out the slow accuracy, CIE 171,
# closed-scene and paper 000 cube tests and the viewer, which run the same code paths longer.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${HEMIRAD_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
all=0
[ "${1:-}" = "--all" ] && all=1

# MPI off: Open MPI's own allocations at MPI_Init/MPI_Finalize would be reported as leaks,
# and the sanitized tests run single-process anyway (the MPI layer is a world of one then).
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DHEMIRAD_SANITIZE=address,undefined -DHEMIRAD_BUILD_VIEWER=OFF -DHEMIRAD_MPI=OFF >/dev/null
echo "sanitize: building in $build (log: $build/build.log)" >&2
if ! cmake --build "$build" -j"${HEMIRAD_JOBS:-2}" >"$build/build.log" 2>&1; then
  grep -E -A3 "error" "$build/build.log" | head -40 >&2
  echo "sanitize: the build failed; see $build/build.log" >&2
  exit 1
fi

# Leaks inside Mesa and LLVM (the GL driver's own allocations, freed at exit or never) are
# not ours: tools/lsan.supp names them. The driver (swrast_dri.so) is unloaded before
# LeakSanitizer looks, so its leaks would come from "<unknown module>" that no suppression can
# name: it is preloaded, which keeps it mapped (verify_asan_link_order=0 lets it come before
# the ASan runtime). (fast_unwind_on_malloc=0 would also see the whole stack, but deadlocked
# llvmpipe's threads here.)
dri="$(find /usr/lib -name swrast_dri.so -path '*/dri/*' 2>/dev/null | head -1)"
[ -n "$dri" ] && export LD_PRELOAD="$dri${LD_PRELOAD:+:$LD_PRELOAD}"
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:verify_asan_link_order=0:strict_string_checks=1:check_initialization_order=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$root/tools/lsan.supp:print_suppressions=0:${LSAN_OPTIONS:-}"

subset=()
if [ "$all" -eq 0 ]; then
  # Left out: accuracy_gl_test, cie171_gl_test, closed_scenes_gl_test and the Paper000Cube
  # form-factor sweeps of hemicube_gl_test (minutes-long solves of code the rest runs too),
  # cli.viewer (Xvfb), cli.preview and cli.determinism (repeat solves).
  subset=(-E '^(accuracy_gl_test|cie171_gl_test|closed_scenes_gl_test)\.|Paper000Cube|^cli\.(viewer|preview|determinism)$')
fi
start=$(date +%s)
ctest --test-dir "$build" -j"${HEMIRAD_JOBS:-2}" --output-on-failure --timeout 900 "${subset[@]}"
echo "sanitize: passed in $(( $(date +%s) - start )) s" >&2
