#!/usr/bin/env bash
# SIGINT during a long solve: the shot in progress finishes, every requested output is written
# complete (atomically: no *.tmp-* files), the exit code is 130, and the saved solution resumes.
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$HEMIRAD" solve cornell --max-shots 100000 --tolerance 1e-6 --quiet --log log.jsonl \
    --report r.json --save-solution s.bin --export-ply m.ply --grid floor:4x4 &
pid=$!
# Wait until it has shot a while (the log grows by one line per shot).
for _ in $(seq 1 600); do
    kill -0 "$pid" 2> /dev/null || break
    if [ -f log.jsonl ] && [ "$(wc -l < log.jsonl)" -ge 20 ]; then break; fi
    sleep 0.05
done
[ -f log.jsonl ] && [ "$(wc -l < log.jsonl)" -ge 20 ] ||
    { echo "solve did not run 20 shots"; kill "$pid" 2> /dev/null; exit 1; }
kill -INT "$pid"
set +e
wait "$pid"
rc=$?
set -e
[ "$rc" -eq 130 ] || { echo "exit code $rc, expected 130"; exit 1; }
python3 -c 'import json; r = json.load(open("r.json")); assert r["shots"] >= 20, r["shots"]; assert r["grids"][0]["points"] == 16'
[ -s s.bin ] && [ -s m.ply ] || { echo "missing outputs"; ls -la; exit 1; }
if ls | grep -q '\.tmp-'; then echo "temporary files left: $(ls)"; exit 1; fi

shots=$(python3 -c 'import json; print(json.load(open("r.json"))["shots"])')
"$HEMIRAD" solve cornell --resume s.bin --max-shots $((shots + 3)) --quiet --report r2.json
python3 -c "import json; r = json.load(open('r2.json')); assert r['shots'] == $shots + 3, r['shots']"
echo ok
