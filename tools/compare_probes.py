#!/usr/bin/env python3
"""Compares two probe CSVs (hemirad solve --probe-out, hemirad reference --probe-out), row by
row: relative error of the luminance-weighted irradiance E_Y = 0.2126 E_r + 0.7152 E_g +
0.0722 E_b of TEST against REF. Prints median, p95, max and the worst rows; by surface group
with --groups; by REF's brightness with --bins (REF over its lit median, in six bins: where
a bias sits, e.g. the indirect light at dim points). Rows where REF has no value, or a value
under 1 % of its lit median (the median of REF's nonzero values: points in the dark, e.g.
the ceiling above a light, where a relative error means nothing), are skipped and counted;
with --bins, those dark rows where TEST reads light (over that floor and over REF plus 3 of
REF's standard errors, the sem_ columns of 'hemirad reference') are counted as leaking.

usage: compare_probes.py TEST.csv REF.csv [--groups] [--bins] [--worst N]
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
        out.append((luminance(e), r.get("group", ""), r))
    return out


def luminance(e):
    return 0.2126 * e[0] + 0.7152 * e[1] + 0.0722 * e[2]


def sem(row):
    """REF's standard error of E_Y (0 without the sem_ columns)."""
    try:
        return luminance([float(row["sem_r"]), float(row["sem_g"]), float(row["sem_b"])])
    except (KeyError, ValueError):
        return 0.0


BINS = ((0.01, 0.1), (0.1, 0.3), (0.3, 0.7), (0.7, 1.5), (1.5, 4.0), (4.0, float("inf")))


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
    median = pct([r[0] for r in ref if r is not None and r[0] > 0], 0.5)
    floor = 0.01 * median
    dark = leaking = 0
    bins = [[] for _ in BINS]
    for k, (t, r) in enumerate(zip(test, ref)):
        if r is None or t is None:
            continue
        if r[0] <= floor:
            dark += 1
            leaking += t[0] > floor and t[0] > r[0] + 3 * sem(r[2])
            continue
        e = (t[0] - r[0]) / r[0]
        errs.append((abs(e), k, t[0], r[0], r[1]))
        signed.append(e)
        groups.setdefault(r[1], []).append(e)
        for b, (lo, hi) in enumerate(BINS):
            if lo * median <= r[0] < hi * median:
                bins[b].append((e, sem(r[2]) / r[0]))
    a = [e[0] for e in errs]
    print(f"points {len(a)} (+{dark} dark)  median {100 * pct(a, 0.5):.2f} %  p95 {100 * pct(a, 0.95):.2f} %  "
          f"max {100 * max(a):.2f} %  mean signed {100 * sum(signed) / len(signed):+.2f} %")
    if "--groups" in argv:
        for g, v in sorted(groups.items()):
            print(f"  {g:16s} n={len(v):4d}  median signed {100 * pct(v, 0.5):+6.2f} %  "
                  f"median |e| {100 * pct([abs(x) for x in v], 0.5):5.2f} %  max |e| {100 * max(abs(x) for x in v):6.2f} %")
    if "--bins" in argv:
        print(f"  by REF / REF's lit median ({median:.6g}); {leaking} of the {dark} dark points leak")
        for (lo, hi), v in zip(BINS, bins):
            if v:
                e = [x[0] for x in v]
                print(f"  {lo:4g} - {hi:<4g} n={len(v):4d}  median |e| {100 * pct([abs(x) for x in e], 0.5):5.2f} %  "
                      f"median signed {100 * pct(e, 0.5):+6.2f} %  REF's median sem {100 * pct([x[1] for x in v], 0.5):5.2f} %")
    for e, k, t, r, g in sorted(errs, reverse=True)[:worst]:
        row = ref[k][2]
        print(f"  row {k + 1}: {g} ({row['x']},{row['y']},{row['z']}) test {t:.6g} ref {r:.6g} {100 * (t - r) / r:+.1f} %")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
