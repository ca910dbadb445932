#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz/fuzz_*.cpp; clang, ASan + UBSan) in their own folder
# and runs each for SECONDS (default 30), one after the other, one job each. New inputs found go
# to the build folder's corpus (the committed seeds in tests/fuzz/corpus/ are not changed);
# a crash is written to BUILD/artifacts/NAME/ and fails the run (exit 1).
#
#   tools/fuzz.sh [SECONDS]            every target
#   HEMIRAD_FUZZ_TARGETS="obj probes"  only these
#   HEMIRAD_FUZZ_BUILD_DIR=dir         build somewhere else (default build-fuzz)
#
# A crash becomes a regression test: copy the artifact to tests/fuzz/regressions/NAME/ (the
# ctest fuzz.NAME replays it in every build), then fix it.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${HEMIRAD_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${1:-30}"
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "fuzz: SECONDS must be a whole number, not '$seconds'" >&2; exit 2; }
command -v clang++ >/dev/null || { echo "fuzz: needs clang (tools/setup.sh installs it)" >&2; exit 1; }

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DHEMIRAD_FUZZ=ON -DHEMIRAD_SANITIZE=address,undefined \
  -DHEMIRAD_BUILD_TESTS=OFF -DHEMIRAD_BUILD_VIEWER=OFF -DHEMIRAD_MPI=OFF >/dev/null
# (MPI off: the fuzz targets parse files in one process; Open MPI's leaks would be reported.)
echo "fuzz: building in $build (log: $build/build.log)" >&2
if ! cmake --build "$build" --target hemirad_fuzz_targets -j"${HEMIRAD_JOBS:-2}" \
      >"$build/build.log" 2>&1; then
  grep -E -A3 "error" "$build/build.log" | head -40 >&2
  echo "fuzz: the build failed; see $build/build.log" >&2
  exit 1
fi

targets="${HEMIRAD_FUZZ_TARGETS:-}"
if [ -z "$targets" ]; then
  for f in "$root"/tests/fuzz/fuzz_*.cpp; do n="$(basename "$f" .cpp)"; targets+="${n#fuzz_} "; done
fi

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:allocator_may_return_null=0:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}"
failed=()
for t in $targets; do
  exe="$build/tests/fuzz/fuzz_$t"
  [ -x "$exe" ] || { echo "fuzz: no target fuzz_$t" >&2; failed+=("$t"); continue; }
  work="$build/corpus/$t"
  art="$build/artifacts/$t"
  mkdir -p "$work" "$art"
  log="$build/fuzz_$t.log"
  start=$(date +%s)
  rc=0
  # -timeout: one input over 10 s is a hang; -rss_limit_mb: a parser that does not bound its
  # memory is a finding; inputs up to 64 KiB.
  "$exe" "$work" "$root/tests/fuzz/corpus/$t" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$art/" -print_final_stats=1 \
    >"$log" 2>&1 || rc=$?
  runs="$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -Eo '[0-9]+$' || echo '?')"
  echo "fuzz: $t: $runs executions in $(( $(date +%s) - start )) s, exit $rc (log: $log)" >&2
  if [ "$rc" -ne 0 ]; then
    grep -E "ERROR|runtime error|==ERROR|Test unit written|SUMMARY" "$log" | head -8 >&2
    failed+=("$t")
  fi
done
if ((${#failed[@]})); then
  echo "fuzz: FAILED: ${failed[*]} (artifacts under $build/artifacts/)" >&2
  exit 1
fi
echo "fuzz: every target ran ${seconds} s without a finding" >&2
