#!/usr/bin/env python3
"""Compares two probe CSVs (hemirad solve --probe-out, hemirad reference --probe-out), row by
row: relative error of the luminance-weighted irradiance E_Y = 0.2126 E_r + 0.7152 E_g +
0.0722 E_b of TEST against REF. Prints median, p95, max and the worst rows; by surface group
with --groups. Rows where REF has no value, or a value under 1 % of REF's median (points in
the dark, e.g. the ceiling above a light, where a relative error means nothing), are skipped
and counted.

usage: compare_probes.py TEST.csv REF.csv [--groups] [--worst N]
"""
import csv
import sys


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    out = []
    for r in rows:
        try:
            e = [float(r["E_r"]), float(r["E_g"]), float(r["E_b"])]
        except (KeyError, ValueError):
            out.append(None)
            continue
        out.append((0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2], r.get("group", ""), r))
    return out


def pct(v, q):
    v = sorted(v)
    if not v:
        return float("nan")
    k = (len(v) - 1) * q
    lo = int(k)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def main(argv):
    if len(argv) < 3 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    test, ref = read(argv[1]), read(argv[2])
    if len(test) != len(ref):
        print(f"compare_probes: {argv[1]} has {len(test)} rows, {argv[2]} has {len(ref)}", file=sys.stderr)
        return 2
    worst = int(argv[argv.index("--worst") + 1]) if "--worst" in argv else 0
    errs, signed, groups = [], [], {}
    floor = 0.01 * pct([r[0] for r in ref if r is not None], 0.5)
    dark = 0
    for k, (t, r) in enumerate(zip(test, ref)):
        if r is None or t is None:
            continue
        if r[0] <= floor:
            dark += 1
            continue
        e = (t[0] - r[0]) / r[0]
        errs.append((abs(e), k, t[0], r[0], r[1]))
        signed.append(e)
        groups.setdefault(r[1], []).append(e)
    a = [e[0] for e in errs]
    print(f"points {len(a)} (+{dark} dark)  median {100 * pct(a, 0.5):.2f} %  p95 {100 * pct(a, 0.95):.2f} %  "
          f"max {100 * max(a):.2f} %  mean signed {100 * sum(signed) / len(signed):+.2f} %")
    if "--groups" in argv:
        for g, v in sorted(groups.items()):
            print(f"  {g:16s} n={len(v):4d}  median signed {100 * pct(v, 0.5):+6.2f} %  "
                  f"median |e| {100 * pct([abs(x) for x in v], 0.5):5.2f} %  max |e| {100 * max(abs(x) for x in v):6.2f} %")
    for e, k, t, r, g in sorted(errs, reverse=True)[:worst]:
        row = ref[k][2]
        print(f"  row {k + 1}: {g} ({row['x']},{row['y']},{row['z']}) test {t:.6g} ref {r:.6g} {100 * (t - r) / r:+.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
