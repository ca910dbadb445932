#!/usr/bin/env bash
# MPI (docs/scaling.md): `mpirun -np 1` is the single process bit for bit; 2 ranks converge,
# conserve energy exactly, hold the same solution on both ranks, agree with 1 rank within
# the two error bounds, stop together on SIGINT to one rank, save/resume across rank counts,
# end every rank on an error; `hemirad batch` splits scenes across ranks with the same results.
# Skipped (exit 77) when mpirun is missing or hemirad was built without MPI.
set -euo pipefail
HEMIRAD="$1"
command -v mpirun >/dev/null || { echo "SKIP: mpirun not found (Debian: openmpi-bin)"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
# A coarse fixed hemicube (64): quick, and the checks do not depend on its accuracy.
opts=(room --tolerance 0.02 --resolution 64)

# 2 ranks (first, to find out whether this hemirad has MPI at all).
"${mpi[@]}" -np 2 "$HEMIRAD" solve "${opts[@]}" --report two.json --log two.jsonl 2> two.err
if grep -q "built without MPI" two.err; then echo "SKIP: hemirad was built without MPI"; exit 77; fi
grep -q "the 2 ranks hold the bit-identical solution" two.err || { cat two.err; exit 1; }
"$HEMIRAD" solve "${opts[@]}" --report alone.json --quiet
"${mpi[@]}" -np 1 "$HEMIRAD" solve "${opts[@]}" --report np1.json --quiet

python3 - <<'PY'
import json
alone, np1, two = (json.load(open(f)) for f in ("alone.json", "np1.json", "two.json"))
strip = lambda r: {k: v for k, v in r.items() if k != "seconds"}
assert strip(alone) == strip(np1), "mpirun -np 1 differs from the single process"
assert alone["ranks"] == 1 and "parallel" not in alone
assert two["ranks"] == 2 and two["converged"], two
p = two["parallel"]
assert p["rounds"] >= two["shots"] / 2 and p["bytes_per_round"] > 0, p
# Energy conserved: emitted = absorbed + escaped + unshot, per channel, to the precision of
# the hierarchy's float nodes (the single process is off by 4e-8 here, 2 ranks by 2e-8).
for r in (alone, two):
    for c in range(3):
        e = r["emitted_power"][c]
        s = r["absorbed_power"][c] + r["escaped_power"][c] + r["unshot_power"][c]
        assert abs(s - e) <= 1e-6 * e, (c, s, e)
# Each solution is within its bound of the converged one: the irradiance power still to
# arrive is at most bound * emitted (paper 001), so |dE_avg| * area <= (b1 + b2) * emitted.
b = alone["error_bound"] + two["error_bound"]
for g1, g2 in zip(alone["groups"], two["groups"]):
    for c in range(3):
        d = abs(g1["E_avg"][c] - g2["E_avg"][c]) * g1["area"]
        assert d <= b * alone["emitted_power"][c], (g1["name"], c, d, b)
# The log: every shot once, numbered in order, with its round and rank.
log = [json.loads(l) for l in open("two.jsonl")]
assert [r["shot"] for r in log] == list(range(1, two["shots"] + 1))
assert {r["rank"] for r in log} == {0, 1} and log[-1]["round"] == p["rounds"]
PY

# Save with 2 ranks, resume with 1 (and the other way): the shot counts carry on.
"${mpi[@]}" -np 2 "$HEMIRAD" solve room --resolution 64 --max-shots 20 --quiet --save-solution s2.bin
"$HEMIRAD" solve room --resume s2.bin --max-shots 30 --quiet --report r1.json
"$HEMIRAD" solve room --resolution 64 --max-shots 20 --quiet --save-solution s1.bin
"${mpi[@]}" -np 2 "$HEMIRAD" solve room --resume s1.bin --max-shots 30 --quiet --report r2.json
python3 -c 'import json; assert [json.load(open(f))["shots"] for f in ("r1.json", "r2.json")] == [30, 30]'

# SIGINT to one rank: both stop at the same round, rank 0 writes the report, exit 130.
"${mpi[@]}" -np 2 "$HEMIRAD" solve room --tolerance 1e-6 --quiet --report int.json \
    --log int.jsonl > int.out 2>&1 &
launcher=$!
for _ in $(seq 100); do [ -s int.jsonl ] && break; sleep 0.2; done
ranks=$(pgrep -P "$launcher" || true)
[ "$(echo "$ranks" | wc -w)" -eq 2 ] || { echo "ranks of mpirun $launcher: '$ranks'"; exit 1; }
kill -INT "$(echo "$ranks" | tail -1)"
status=0
wait "$launcher" || status=$?
[ "$status" -eq 130 ] || { echo "exit $status after SIGINT"; cat int.out; exit 1; }
python3 -c 'import json; r = json.load(open("int.json")); assert r["ranks"] == 2 and not r["converged"]'

# An error ends every rank (no hang), with the message naming the file.
if "${mpi[@]}" -np 2 "$HEMIRAD" solve missing.obj > err.out 2>&1; then echo "accepted"; exit 1; fi
grep -q "missing.obj" err.out || { cat err.out; exit 1; }

# batch: a folder per scene, a summary; a missing scene fails alone (exit 1); 2 ranks split
# the scenes and give the same numbers.
for n in 1 2; do
    status=0
    "${mpi[@]}" -np $n "$HEMIRAD" batch room cube missing.obj cube --out b$n --tolerance 0.05 --resolution 64 \
        --quiet 2> b$n.err || status=$?
    [ "$status" -eq 1 ] || { echo "batch on $n ranks: exit $status"; cat b$n.err; exit 1; }
    grep -q "missing.obj" b$n.err || { cat b$n.err; exit 1; }
done
python3 - <<'PY'
import json
for n in (1, 2):
    s = json.load(open(f"b{n}/summary.json"))
    assert s["ranks"] == n and s["failed"] == 1, s
    assert [x["folder"] for x in s["scenes"]] == ["room", "cube", "missing", "cube-2"], s
    assert [x["rank"] for x in s["scenes"]] == ([0, 0, 0, 0] if n == 1 else [0, 1, 0, 1])
    assert s["scenes"][2]["status"] == "error" and "missing.obj" in s["scenes"][2]["error"]
for folder in ("room", "cube", "cube-2"):
    a, b = (json.load(open(f"b{n}/{folder}/report.json")) for n in (1, 2))
    assert a["converged"] and a["groups"] == b["groups"] and a["shots"] == b["shots"], folder
PY
# (grep reads the whole help: with pipefail, grep -q quitting early would SIGPIPE the writer)
grep -q -- "--out" <<<"$("$HEMIRAD" batch --help)"
echo ok
