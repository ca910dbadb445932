#!/usr/bin/env python3
"""Time-to-accuracy plot of hemirad-bench's accuracy experiments, as SVG (no dependencies).

usage: bench/plot_accuracy.py BENCH.json OUT.svg [EXPERIMENT]   (default: cornell_accuracy)

x: seconds (solve + points), log scale; y: relative error of E_Y against the path-traced
reference, median (filled) and 95th percentile (open), per setting, labelled.
"""
import json
import math
import sys


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    name = argv[3] if len(argv) > 3 else "cornell_accuracy"
    doc = json.load(open(argv[1]))
    exp = next((e for e in doc["experiments"] if e.get("name") == name), None)
    if exp is None or "settings" not in exp:
        print(f"plot_accuracy: no accuracy experiment '{name}' in {argv[1]}", file=sys.stderr)
        return 2
    rows = exp["settings"]
    W, H, L, R, T, B = 720, 420, 70, 230, 30, 50
    xs = [max(r["seconds"], 1e-3) for r in rows]
    x0, x1 = math.log10(min(xs) / 1.5), math.log10(max(xs) * 1.5)
    y1 = max(r["p95"] for r in rows) * 1.1
    px = lambda s: L + (math.log10(s) - x0) / (x1 - x0) * (W - L - R)
    py = lambda e: H - B - e / y1 * (H - T - B)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="11">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{L}" y="18" font-size="13">{name}: error at points vs seconds (this machine)</text>',
           f'<line x1="{L}" y1="{H - B}" x2="{W - R}" y2="{H - B}" stroke="black"/>',
           f'<line x1="{L}" y1="{T}" x2="{L}" y2="{H - B}" stroke="black"/>']
    for k in range(0, 7):
        e = y1 * k / 6
        out.append(f'<text x="{L - 6}" y="{py(e) + 4:.1f}" text-anchor="end">{100 * e:.0f} %</text>')
        out.append(f'<line x1="{L}" y1="{py(e):.1f}" x2="{W - R}" y2="{py(e):.1f}" stroke="#ddd"/>')
    for s in (0.3, 0.5, 1, 2, 3, 5, 10, 20, 30):
        if x0 <= math.log10(s) <= x1:
            out.append(f'<text x="{px(s):.1f}" y="{H - B + 16}" text-anchor="middle">{s:g} s</text>')
    for r, s in zip(rows, xs):
        x = px(s)
        out.append(f'<circle cx="{x:.1f}" cy="{py(r["median"]):.1f}" r="4" fill="#1f77b4"/>')
        out.append(f'<circle cx="{x:.1f}" cy="{py(r["p95"]):.1f}" r="4" fill="none" stroke="#d62728"/>')
        out.append(f'<line x1="{x:.1f}" y1="{py(r["median"]):.1f}" x2="{x:.1f}" y2="{py(r["p95"]):.1f}" stroke="#aaa"/>')
        out.append(f'<text x="{x + 6:.1f}" y="{py(r["p95"]) - 4:.1f}" font-size="9">{r["setting"]}</text>')
    out.append(f'<circle cx="{W - R + 20}" cy="{T + 10}" r="4" fill="#1f77b4"/><text x="{W - R + 30}" y="{T + 14}">median</text>')
    out.append(f'<circle cx="{W - R + 20}" cy="{T + 28}" r="4" fill="none" stroke="#d62728"/><text x="{W - R + 30}" y="{T + 32}">95th percentile</text>')
    out.append("</svg>")
    open(argv[2], "w").write("\n".join(out) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
