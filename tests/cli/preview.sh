#!/usr/bin/env bash
# hemirad-preview on the Cornell box at a small size: every file is written, the PNGs have the
# sizes asked for, the CSV has one row per shot with a non-increasing unshot fraction, and bad
# options fail with "hemirad-preview: message" and a non-zero exit.
#
# CTest runs: bash preview.sh <path to hemirad> <source dir>
set -euo pipefail

hemirad="$1"
build="$(cd "$(dirname "$hemirad")" && pwd)"
preview="$build/hemirad-preview"
[ -x "$preview" ] || { echo "FAIL: $preview not built" >&2; exit 1; }
command -v python3 >/dev/null || { echo "FAIL: python3 is needed to check the PNGs" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
out="$work/frames"

"$preview" cornell --out "$out" --max-depth 3 --width 64 --height 64 --every 5 \
    --max-shots 20 --exr --quiet

# Writes nothing with --quiet.
quiet_err="$("$preview" cornell --out "$work/q" --max-depth 3 --width 32 --height 32 --every 5 \
    --max-shots 5 --quiet 2>&1)"
[ -z "$quiet_err" ] || { echo "FAIL: --quiet printed: $quiet_err" >&2; exit 1; }

python3 - "$out" <<'PY'
import csv, os, struct, sys, zlib

out = sys.argv[1]

def png_size(path):
    """Width, height and the decoded 8-bit RGB rows of a PNG written by hemirad."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert (depth, ctype) == (8, 2), f"{path}: expected 8-bit RGB"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    assert len(raw) == h * (1 + 3 * w), f"{path}: {len(raw)} bytes of image data"
    return w, h

expected = {f"frame_{s:05d}.png" for s in (0, 5, 10, 15, 20)}
expected |= {f.replace(".png", ".exr") for f in expected}
expected |= {"contact_sheet.png", "convergence.png", "convergence.csv"}
have = set(os.listdir(out))
missing = expected - have
assert not missing, f"missing outputs: {sorted(missing)}"
extra = {f for f in have - expected if not f.endswith(".exr")}
assert not extra, f"unexpected outputs: {sorted(extra)}"

for s in (0, 5, 10, 15, 20):
    size = png_size(os.path.join(out, f"frame_{s:05d}.png"))
    assert size == (64, 64), f"frame {s}: {size}, expected 64x64"
    assert os.path.getsize(os.path.join(out, f"frame_{s:05d}.exr")) > 0

# Contact sheet: 5 frames of 64x64 on min(6, 5) = 5 columns, one row, captions
# (draw.h: width = c (cw + 8) + 8, height = r (ch + 12 + 8) + 8).
size = png_size(os.path.join(out, "contact_sheet.png"))
assert size == (5 * 72 + 8, 64 + 12 + 8 + 8), f"contact sheet {size}"
size = png_size(os.path.join(out, "convergence.png"))
assert size[0] >= 256 and size[1] >= 128, f"convergence plot {size}"

rows = list(csv.DictReader(open(os.path.join(out, "convergence.csv"))))
assert [int(r["shot"]) for r in rows] == list(range(21)), "one row per shot, 0..20"
unshot = [float(r["unshot_fraction"]) for r in rows]
bound = [float(r["error_bound"]) for r in rows]
secs = [float(r["seconds"]) for r in rows]
assert unshot[0] == 1.0 or abs(unshot[0] - 1.0) < 1e-6, f"unshot fraction at shot 0: {unshot[0]}"
for a, b in zip(unshot, unshot[1:]):
    assert b <= a * (1 + 1e-9), f"unshot fraction rose: {a} -> {b}"
for a, b in zip(secs, secs[1:]):
    assert b >= a, f"seconds went back: {a} -> {b}"
assert all(b > 0 for b in bound) and bound[-1] < bound[0], "error bound must fall"
print(f"ok: {len(rows)} rows, unshot {unshot[0]:.3f} -> {unshot[-1]:.3f}")
PY

# --every-seconds alone works (frames at shot 0, then by time, and the final state).
"$preview" cornell --out "$work/t" --max-depth 2 --width 32 --height 32 --every-seconds 0.05 \
    --max-shots 10 --quiet
[ -f "$work/t/frame_00000.png" ] && [ -f "$work/t/frame_00010.png" ] \
    || { echo "FAIL: --every-seconds frames missing: $(ls "$work/t")" >&2; exit 1; }

# Errors: "hemirad-preview: message", non-zero exit, no crash.
expect_error() { # expected-substring command...
    local want="$1"; shift
    local err rc=0
    err="$("$@" 2>&1 >/dev/null)" || rc=$?
    if [ "$rc" -eq 0 ] || [ "$rc" -ge 128 ]; then
        echo "FAIL: '$*' exited $rc (expected an error)" >&2; exit 1
    fi
    case "$err" in
        "hemirad-preview: "*"$want"*) ;;
        *) echo "FAIL: '$*': unexpected message: $err" >&2; exit 1 ;;
    esac
}
expect_error "--every" "$preview" cornell --out "$work/e1" --every 0
expect_error "--every" "$preview" cornell --out "$work/e1" --every -3
expect_error "--every-seconds" "$preview" cornell --out "$work/e1" --every-seconds 0
expect_error "--every" "$preview" cornell --out "$work/e1"
expect_error "--out" "$preview" cornell --every 5
touch "$work/file"
expect_error "not a directory" "$preview" cornell --out "$work/file" --every 5
expect_error "cannot create" "$preview" cornell --out "$work/file/sub" --every 5
expect_error "camera" "$preview" cornell --out "$work/e2" --every 5 --camera 1,2,3
expect_error "no-such-scene" "$preview" no-such-scene.obj --out "$work/e3" --every 5
"$preview" --help > "$work/help.txt"  # whole: grep -q on a pipe could cut the writer off
grep -q -- "--every-seconds" "$work/help.txt" || { echo "FAIL: --help" >&2; exit 1; }
echo "preview: ok"
