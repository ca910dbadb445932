#!/usr/bin/env bash
# hemirad-view under a virtual X server: a scripted screenshot of the Cornell box after 10 shots
# has the window's size, is not blank, and matches the headless render of the same solution
# (`hemirad solve --max-shots 10 -o`, same camera and size). Then: the status overlay draws,
# the last shooter's outline and the hemicube inset (--highlight, --inset) draw,
# a scene that fails to load is an error (no window, no crash), and --frames exits cleanly.
#
# CTest runs: bash viewer.sh <path to hemirad> <source dir>
set -euo pipefail

hemirad="$1"
build="$(cd "$(dirname "$hemirad")" && pwd)"
view="$build/hemirad-view"
[ -x "$view" ] || { echo "FAIL: $view not built (needs libglfw3-dev)" >&2; exit 1; }
[ -x "$hemirad" ] || {
    echo "FAIL: $hemirad not built (the reference render needs it)" >&2
    exit 1
}
command -v xvfb-run >/dev/null || {
    echo "FAIL: xvfb-run not found: the viewer test needs a virtual X server" \
         "(apt-get install -y xvfb xauth, or run tools/setup.sh)" >&2
    exit 1
}
command -v python3 >/dev/null || { echo "FAIL: python3 is needed to check the PNGs" >&2; exit 1; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

# Scripted screenshot: no ambient term and no overlay, as `hemirad solve -o` renders.
# Both with the estimate of the light not yet shot (the viewer's key B on, its default).
xvfb-run -a "$view" cornell --screenshot shot.png --after-shots 10 --width 128 --height 96 \
    --no-overlay --quiet
"$hemirad" solve cornell --max-shots 10 -o ref.png --width 128 --height 96 --quiet \
    --discontinuities off # the viewer draws the leaves only
# The same frame with the status line (bottom) and the help panel (top left).
xvfb-run -a "$view" cornell --screenshot overlay.png --after-shots 10 --width 320 --height 240 \
    --no-ambient --show-help --no-panels --quiet
xvfb-run -a "$view" cornell --screenshot plain.png --after-shots 10 --width 320 --height 240 \
    --no-ambient --no-overlay --quiet
# After one shot (the shooter: a quarter-by-quarter patch of the light, in view; without the
# parallax refinement, which would shoot a patch a quarter that size) with and without the
# shooter's outline and the hemicube inset (top right).
xvfb-run -a "$view" cornell --screenshot one.png --after-shots 1 --width 320 --height 240 \
    --no-ambient --no-overlay --quiet --shooter-parallax 0
xvfb-run -a "$view" cornell --screenshot marked.png --after-shots 1 --width 320 --height 240 \
    --no-ambient --no-overlay --highlight --inset --quiet --shooter-parallax 0
# False colour with its legend.
xvfb-run -a "$view" cornell --screenshot false.png --after-shots 10 --width 320 --height 240 \
    --false-colour --no-overlay --quiet

python3 - <<'PY'
import struct, zlib

def read_png(path):
    """(width, height, rows of RGB bytes) of an 8-bit RGB PNG, filters undone."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path}: not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert (depth, ctype) == (8, 2), f"{path}: expected 8-bit RGB"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, bpp, stride = zlib.decompress(idat), 3, 3 * w
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
            else: assert f == 0, f"{path}: filter {f}"
        rows.append(bytes(line))
        prev = line
    return w, h, rows

def stats(rows):
    v = [x for r in rows for x in r]
    mean = sum(v) / len(v)
    return mean, (sum((x - mean) ** 2 for x in v) / len(v)) ** 0.5

w, h, shot = read_png("shot.png")
assert (w, h) == (128, 96), f"screenshot is {w}x{h}, expected 128x96"
mean, sd = stats(shot)
assert 10 < mean < 245 and sd > 10, f"screenshot looks blank: mean {mean:.1f}, sd {sd:.1f}"
rw, rh, ref = read_png("ref.png")
assert (rw, rh) == (w, h), f"reference is {rw}x{rh}"
# Same solution (10 shots, same provider), same camera, same exposure (95th percentile of the
# same full-size float render), same Reinhard + sRGB formula; the viewer tone-maps in the
# shader in float, `solve -o` on the CPU in double, so a value may round to the neighbouring
# 8-bit level (measured here: identical). Allow a mean of 1 level and 0.2% of values off by more
# than 8; a wrong camera, aspect, exposure, row order or depth precision (the light z-fighting
# with the ceiling: 0.3% of values off by 255) fails.
diff = [abs(a - b) for ra, rb in zip(shot, ref) for a, b in zip(ra, rb)]
mad = sum(diff) / len(diff)
big = sum(d > 8 for d in diff) / len(diff)
print(f"screenshot mean {mean:.1f} sd {sd:.1f}; vs hemirad solve -o: mean |diff| {mad:.3f}, "
      f"{100 * big:.2f}% of values off by more than 8")
assert mad < 1.0, f"screenshot differs from the headless render: mean |diff| {mad:.2f} >= 1"
assert big < 0.002, f"{100 * big:.2f}% of values differ by more than 8 levels"

# The overlay: the status line (bottom 14 rows) and help panel differ from the plain view;
# the middle of the image does not.
_, _, over = read_png("overlay.png")
_, _, plain = read_png("plain.png")
changed = lambda ys: sum(over[y] != plain[y] for y in ys)
assert changed(range(240 - 14, 240)) >= 10, "no status line at the bottom"
assert changed(range(0, 20)) >= 10, "no help panel at the top"
mid = [r[3 * 200:3 * 300] for r in over[130:200]], [r[3 * 200:3 * 300] for r in plain[130:200]]
assert mid[0] == mid[1], "the overlay changed the middle of the image"

# The inset: the top right corner (two 4:3 panels, at most 45% of the width) differs in most
# pixels (measured: 77%; black where the box's open front is, over the black ceiling, is
# unchanged); the outline: elsewhere, some pixels turn magenta (the highlight colour).
_, _, one = read_png("one.png")
_, _, marked = read_png("marked.png")
px = lambda rows, x0, x1, y0, y1: [(r[i], r[i + 1], r[i + 2]) for r in rows[y0:y1]
                                   for i in range(3 * x0, 3 * x1, 3)]
a, b = px(one, 200, 310, 10, 50), px(marked, 200, 310, 10, 50)
inset = sum(p != q for p, q in zip(a, b)) / len(a)
assert inset > 0.5, f"hemicube inset: only {100 * inset:.0f}% of its region changed"
a, b = px(one, 0, 160, 0, 240), px(marked, 0, 160, 0, 240)
magenta = sum(p != q and q[0] > 180 and q[1] < 120 and q[2] > 160 for p, q in zip(a, b))
assert magenta >= 20, f"shooter outline: {magenta} magenta pixels changed"
print(f"inset: {100 * inset:.0f}% of its region changed; outline: {magenta} magenta pixels")

# False colour: the surfaces in viridis colours (not grey: the legend's panel and the
# background are), many distinct colours, and a legend in the top right corner.
_, _, fc = read_png("false.png")
px = [(r[i], r[i + 1], r[i + 2]) for r in fc[60:200] for i in range(3 * 80, 3 * 220, 3)]
coloured = sum(not (r == g == b) for r, g, b in px) / len(px)
assert coloured > 0.9, f"false colour: only {100 * coloured:.0f}% of the centre is coloured"
assert len(set(px)) > 20, f"false colour: {len(set(px))} distinct colours"
legend = [(r[i], r[i + 1], r[i + 2]) for r in fc[10:150] for i in range(3 * 230, 3 * 316, 3)]
assert sum(c == (245, 245, 245) for c in legend) > 500, "false colour: no legend panel"
print("viewer images: ok")
PY

# A scene that fails to load: message, non-zero exit, no crash, no window needed.
rc=0
err="$(xvfb-run -a "$view" no-such-scene.obj --frames 1 2>&1)" || rc=$?
if [ "$rc" -eq 0 ] || [ "$rc" -ge 128 ]; then
    echo "FAIL: a missing scene exited $rc" >&2; exit 1
fi
case "$err" in
    *"hemirad-view: "*"no-such-scene"*) ;;
    *) echo "FAIL: unexpected message for a missing scene: $err" >&2; exit 1 ;;
esac
# --frames K without a screenshot: K frames, exit 0.
xvfb-run -a "$view" cube --frames 3 --width 64 --height 64 --quiet
# No display at all: a clear error, not a crash.
rc=0
err="$(env -u DISPLAY -u WAYLAND_DISPLAY "$view" cornell --frames 1 2>&1)" || rc=$?
if [ "$rc" -eq 0 ] || [ "$rc" -ge 128 ]; then
    echo "FAIL: no display: exited $rc" >&2; exit 1
fi
case "$err" in
    *"hemirad-view: "*"GLFW"*) ;;
    *) echo "FAIL: unexpected message without a display: $err" >&2; exit 1 ;;
esac
echo "viewer: ok"
