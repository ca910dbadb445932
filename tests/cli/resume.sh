#!/usr/bin/env bash
# --resume: M shots + save + resume to N gives the same PLY bytes as N shots at once (also for a
# scene lit by the sky and the sun, whose light is delivered before the first shot); another
# scene, a changed option or a damaged file is refused with a message naming it.
set -euo pipefail
HEMIRAD="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$HEMIRAD" solve cornell --max-depth 4 --max-shots 30 --quiet --export-ply full.ply
"$HEMIRAD" solve cornell --max-depth 4 --max-shots 12 --quiet --save-solution s.bin
# Saved options are kept when not given (--max-depth 4 comes from the file).
"$HEMIRAD" solve cornell --resume s.bin --max-shots 30 --quiet --export-ply resumed.ply
cmp full.ply resumed.ply
# Daylight: the resumed run keeps the sky's and the sun's delivered power in its error bound
# (it once dropped it and stopped at once, "converged" with the light unshot).
cat > day.json << EOF
{"include": ["$2/tests/data/sun/window_room.obj"],
 "sun": {"direction": [0.3, 0.7, 0.65], "illuminance": 80000},
 "sky": {"model": "cie-overcast", "illuminance": 10000}}
EOF
"$HEMIRAD" solve day.json --max-depth 3 --max-shots 60 --quiet --export-ply day_full.ply
"$HEMIRAD" solve day.json --max-depth 3 --max-shots 20 --quiet --save-solution day.bin
"$HEMIRAD" solve day.json --resume day.bin --max-shots 60 --quiet --export-ply day_resumed.ply
cmp day_full.ply day_resumed.ply
# Resuming at the saved shot count runs no shot and still writes its outputs.
"$HEMIRAD" solve cornell --resume s.bin --max-shots 12 --quiet --report r12.json
python3 -c 'import json; assert json.load(open("r12.json"))["shots"] == 12'

expect_fail() { # expect_fail WORD command...: fails, and the message holds WORD
    local word="$1"; shift
    if "$@" > out.txt 2> err.txt; then echo "accepted: $*"; exit 1; fi
    grep -q -- "$word" err.txt || { echo "no '$word' in: $(cat err.txt)"; exit 1; }
}
expect_fail "max-depth" "$HEMIRAD" solve cornell --resume s.bin --max-depth 3 --quiet
expect_fail "s.bin" "$HEMIRAD" solve cube --resume s.bin --quiet
expect_fail "another scene" "$HEMIRAD" solve cube --resume s.bin --quiet
head -c 2000 s.bin > t.bin
expect_fail "t.bin" "$HEMIRAD" solve cornell --resume t.bin --quiet
printf 'not a solution' > junk.bin
expect_fail "junk.bin" "$HEMIRAD" solve cornell --resume junk.bin --quiet
echo ok
