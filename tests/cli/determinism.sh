#!/usr/bin/env bash
# Same input, options and backend: identical bytes (PLY, lightmaps, grid CSV, solution file
# apart from its timing field) and identical reports once the timing fields are removed.
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

for run in a b; do
    "$HEMIRAD" solve cornell --max-shots 40 --quiet --report $run.json --export-ply $run.ply \
        --export-lightmaps lm_$run --grid floor:6x6 --grid-out $run.csv --lux \
        --save-solution $run.bin
done
cmp a.ply b.ply
cmp a.csv b.csv
for f in lm_a/*; do cmp "$f" "lm_b/$(basename "$f")"; done
python3 - <<'PY'
import json
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if k != "seconds"}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
a, b = (strip(json.load(open(f))) for f in ("a.json", "b.json"))
assert a == b, "reports differ"
# Solution files: identical except the f64 'seconds' counter and the checksum after it all
# (layout in include/hemirad/solution_file.h).
import struct
def seconds_offset(d):
    pos = 20
    n, = struct.unpack_from("<I", d, pos); pos += 4 + n          # scene source
    count, = struct.unpack_from("<I", d, pos); pos += 4
    for _ in range(2 * count):                                   # option names and values
        n, = struct.unpack_from("<I", d, pos); pos += 4 + n
    return pos + 8 + 48 + 24 + 16                                # shots, powers, rows, ints
A, B = open("a.bin", "rb").read(), open("b.bin", "rb").read()
assert A[:8] == b"HEMIRAD\x1a" and len(A) == len(B)
o = seconds_offset(A)
assert A[:o] + A[o + 8:-8] == B[:o] + B[o + 8:-8], "solution files differ"
PY
echo ok
