#!/usr/bin/env bash
# hemirad reference: the CSV has the columns of `solve --probe-out` plus sem_r,sem_g,sem_b
# (on-surface rows name their polygon and group, a free-space row "none"), values are finite
# and positive, the output does not depend on --threads, and bad input exits 2 naming it.
# (The estimator itself is checked against closed forms in tests/reference_test.cpp.)
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

cat > in.csv <<'CSV'
x,y,z,nx,ny,nz
278,0,280,0,1,0
0,274,280,1,0,0
278,274,280,0,1,0
CSV
"$HEMIRAD" reference cornell --probes in.csv --probe-out a.csv --samples 64 --threads 1 --quiet
"$HEMIRAD" reference cornell --probes in.csv --probe-out b.csv --samples 64 --threads 2 \
    2> log.txt
cmp a.csv b.csv
grep -q "median relative standard error" log.txt || { cat log.txt; exit 1; }
python3 - <<'PY'
import csv, math
rows = list(csv.reader(open("a.csv")))
assert rows[0] == ["x", "y", "z", "nx", "ny", "nz", "E_r", "E_g", "E_b", "polygon", "group",
                   "sem_r", "sem_g", "sem_b"], rows[0]
assert len(rows) == 4, len(rows)
for r in rows[1:]:
    assert len(r) == 14, r
    E, sem = [float(v) for v in r[6:9]], [float(v) for v in r[11:14]]
    assert all(math.isfinite(v) and v > 0 for v in E + sem), r
    assert all(s < e for s, e in zip(sem, E)), r
assert rows[1][9:11] == ["0", "floor"], rows[1]
assert rows[2][10] == "right_wall", rows[2]
assert rows[3][9:11] == ["", "none"], rows[3]
PY

expect_error() { # expected text, then the arguments
    local text="$1"
    shift
    if "$HEMIRAD" "$@" 2> err.txt; then echo "expected a failure: $*"; exit 1; else rc=$?; fi
    [ "$rc" -eq 2 ] || { echo "exit $rc, expected 2: $*"; cat err.txt; exit 1; }
    grep -qF -- "$text" err.txt || { echo "no '$text' in:"; cat err.txt; exit 1; }
}
expect_error "--samples 0" reference cornell --probes in.csv --probe-out c.csv --samples 0
expect_error "--samples -5" reference cornell --probes in.csv --probe-out c.csv --samples -5
expect_error "--probe-out" reference cornell --probes in.csv
expect_error "--probes" reference cornell --probe-out c.csv
[ ! -e c.csv ] || { echo "c.csv written despite an error"; exit 1; }
echo ok
