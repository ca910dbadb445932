#!/usr/bin/env bash
# Every bad input (issue 13, part 5): each parser is fed the nasty cases and must end with exit
# status 2, one line on stderr ("hemirad: ...") naming the file (and line and value) or the
# option (and value), no output file left behind, no crash and no hang (each case has 60 s).
#   OBJ/MTL: a face of a million corners, a 100 MB line, an index of 2^31 and of -2^63, 1e999
#            coordinates and colours, NUL bytes, a directory, /dev/zero;
#   probe CSV, solution file (--resume), --camera, --grid, numeric options, --memory-limit and
#   the memory guard itself.
set -euo pipefail
HEMIRAD="$1"
ROOT="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir in out
failures=0

# expect_bad NAME "SUBSTRING|SUBSTRING..." -- ARGS...: every SUBSTRING must be in the message.
expect_bad() {
  local name="$1" want="$2"
  shift 3
  local rc=0
  timeout 60 "$HEMIRAD" "$@" >out.txt 2>err.txt || rc=$?
  local lines msg
  lines=$(wc -l <err.txt)
  msg=$(head -c 600 err.txt)
  local ok=1
  [ "$rc" -eq 2 ] || { echo "FAIL $name: exit $rc, expected 2: $msg"; ok=0; }
  [ "$lines" -eq 1 ] || { echo "FAIL $name: $lines lines on stderr, expected 1: $msg"; ok=0; }
  [[ "$msg" == "hemirad: "* ]] || { echo "FAIL $name: message does not start 'hemirad: ': $msg"; ok=0; }
  local IFS='|'
  for w in $want; do
    [[ "$msg" == *"$w"* ]] || { echo "FAIL $name: message lacks '$w': $msg"; ok=0; }
  done
  if [ -n "$(ls -A out)" ]; then
    echo "FAIL $name: output left behind: $(ls -A out)"
    ok=0
    rm -rf out/* out/.[!.]* 2>/dev/null || true
  fi
  if [ "$ok" -eq 1 ]; then echo "ok   $name: $msg"; else failures=$((failures + 1)); fi
}
OUTS=(-o out/view.png --report out/report.json --log out/shots.jsonl)
solve() { echo solve "$@" "${OUTS[@]}" --max-shots 3 --quiet; }

# --- OBJ / MTL -------------------------------------------------------------------------------
python3 - <<'PY'
with open("in/big_face.obj", "w") as f:
    f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf" + " 1 2 3" * 333334 + "\n")
PY
{ printf 'v '; head -c 104857600 /dev/zero | tr '\0' '1'; printf ' 0 0\n'; } >in/long_line.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2147483648\n' >in/index_2_31.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n' >in/index_neg.obj
printf 'v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n' >in/huge_coord.obj
printf 'v 0 0 0\nv 1\0 0 0\nv 0 1 0\nf 1 2 3\n' >in/nul.obj
mkdir in/folder.obj
printf 'mtllib bad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n' >in/bad_mtl.obj
printf 'newmtl m\nKd 0.5 1e999 0.5\n' >in/bad.mtl
printf 'mtllib nul.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n' >in/nul_mtl.obj
printf 'newmtl m\nKd 0.5 0.5\0 0.5\n' >in/nul.mtl

expect_bad obj-million-corner-face "big_face.obj:4|1000002 corners" -- $(solve in/big_face.obj)
expect_bad obj-100MB-line "long_line.obj:1|longer than 16 MiB" -- $(solve in/long_line.obj)
expect_bad obj-index-2^31 "index_2_31.obj:4|2147483648" -- $(solve in/index_2_31.obj)
expect_bad obj-index--2^63 "index_neg.obj:4|-9223372036854775808" -- $(solve in/index_neg.obj)
expect_bad obj-1e999 "huge_coord.obj:2|1e999" -- $(solve in/huge_coord.obj)
expect_bad obj-nul "nul.obj:2|NUL byte" -- $(solve in/nul.obj)
expect_bad obj-directory "folder.obj|directory" -- $(solve in/folder.obj)
expect_bad obj-dev-zero "/dev/zero" -- $(solve /dev/zero)
expect_bad mtl-1e999 "bad.mtl:2|1e999" -- $(solve in/bad_mtl.obj)
expect_bad mtl-nul "nul.mtl:2|NUL byte" -- $(solve in/nul_mtl.obj)
expect_bad scene-obj-1e999 "huge_coord.obj:2|1e999" -- scene in/huge_coord.obj

# --- probe CSV -------------------------------------------------------------------------------
P=(--probe-out out/probes.csv)
printf '1e999,0,0,0,1,0\n' >in/huge.csv
printf 'x,y,z,nx,ny,nz\n0,0,0,0,1\0,0\n' >in/nul.csv
python3 -c "open('in/long.csv','w').write('0,'*100000 + '0\n')"
: >in/empty.csv
mkdir in/folder.csv
printf '0,0,0,0,1,0\n0,0,0,1e308,1e308,1e308\n' >in/overflow_normal.csv
expect_bad probes-1e999 "huge.csv:1|1e999" -- $(solve cornell) --probes in/huge.csv "${P[@]}"
expect_bad probes-nul "nul.csv:2|NUL byte" -- $(solve cornell) --probes in/nul.csv "${P[@]}"
expect_bad probes-long-line "long.csv:1|longer than" -- $(solve cornell) --probes in/long.csv "${P[@]}"
expect_bad probes-empty "empty.csv|no probe points" -- $(solve cornell) --probes in/empty.csv "${P[@]}"
expect_bad probes-directory "folder.csv|directory" -- $(solve cornell) --probes in/folder.csv "${P[@]}"
expect_bad probes-normal-overflow "overflow_normal.csv:2|normal" -- $(solve cornell) --probes in/overflow_normal.csv "${P[@]}"
expect_bad reference-probes-1e999 "huge.csv:1|1e999" -- reference cornell --probes in/huge.csv --probe-out out/ref.csv --quiet

# --- solution files (--resume) ---------------------------------------------------------------
mkdir in/folder.hrs
printf 'HEMIRAD\032\001\000\000\000garbage' >in/truncated.hrs
head -c 100 /dev/urandom >in/random.hrs
expect_bad resume-directory "folder.hrs|directory" -- $(solve cornell) --resume in/folder.hrs
expect_bad resume-truncated "truncated.hrs" -- $(solve cornell) --resume in/truncated.hrs
expect_bad resume-random "random.hrs|not a hemirad solution file" -- $(solve cornell) --resume in/random.hrs
expect_bad resume-dev-zero "/dev/zero|not a regular file" -- $(solve cornell) --resume /dev/zero

# --- option strings --------------------------------------------------------------------------
expect_bad camera-1e999 "camera|1e999" -- $(solve cornell) --camera 1e999,0,0,0,0,1,0,1,0,40
expect_bad camera-name "--camera 'nosuch'" -- $(solve cornell) --camera nosuch
expect_bad grid-count "--grid|99999999999" -- $(solve cornell) --grid floor:99999999999x2
expect_bad grid-group "--grid|nosuch" -- $(solve cornell) --grid nosuch:4x4
expect_bad max-depth-2^31 "--max-depth|2147483648" -- $(solve cornell) --max-depth 2147483648
expect_bad patch-size-1e999 "--patch-size|1e999" -- $(solve cornell) --patch-size 1e999
expect_bad tolerance-nan "--tolerance|nan" -- $(solve cornell) --tolerance nan
expect_bad memory-limit-unit "--memory-limit|12Q" -- $(solve cornell) --memory-limit 12Q
expect_bad resolution "--max-resolution|99999" -- $(solve cornell) --max-resolution 99999

# --- the memory guard ------------------------------------------------------------------------
expect_bad memory-guard "needs about|available|--max-depth|--patch-size|--memory-limit" -- \
  $(solve scene3138) --patch-size 1e-6 --max-depth 11
expect_bad memory-limit "needs about|4.0 MiB is available (--memory-limit)|--max-depth" -- \
  $(solve cornell) --memory-limit 4M

# A good solve under --memory-limit still runs.
"$HEMIRAD" solve cornell --quiet --max-shots 2 --memory-limit 1G --report out/ok.json
[ -s out/ok.json ] || { echo "FAIL: a solve under --memory-limit 1G wrote no report"; failures=$((failures + 1)); }

if [ "$failures" -ne 0 ]; then
  echo "$failures case(s) failed"
  exit 1
fi
echo "every bad input refused"
