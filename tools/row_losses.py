#!/usr/bin/env python3
"""Where a solve's shots lose or create light: reads a shot log ('hemirad solve --log
FILE.jsonl') and prints, for each kind of shot (luminaire, patch, cluster), its share of the
shot power, the share of all shot power that its rows under 1 lost (power x (1 - row sum))
and that its rows over 1 would create (power x (row sum - 1), before the guard rescales
them), the rows over 1.001 and the worst row; then the shooters (polygon or cluster) that
lost the most, with --worst N.

In an open scene a row under 1 is light that leaves it; in a closed one (a room with every
wall, or a model closed for the purpose by a box around it, included from a SCENE.json)
every row should sum to about 1, so what is lost there is the form factors' error.

usage: row_losses.py SHOTS.jsonl [--worst N]
"""
import json
import sys


def kind(shot):
    if "cluster" in shot:
        return "cluster"
    return "luminaire" if shot.get("luminaire", -1) >= 0 else "patch"


def lost(shot):
    """The light a row under 1 lost, in the units of shooter_power."""
    return shot["shooter_power"] * max(0.0, 1 - shot["row_sum"])


def made(shot):
    """The light a row over 1 created, in the units of shooter_power."""
    return shot["shooter_power"] * max(0.0, shot["row_sum"] - 1)


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    worst = int(argv[argv.index("--worst") + 1]) if "--worst" in argv else 0
    shots = []
    try:
        with open(argv[1]) as f:
            for n, line in enumerate(f, 1):
                if line.strip():
                    shots.append(json.loads(line))
    except OSError as e:
        print(f"row_losses: {argv[1]}: {e.strerror}", file=sys.stderr)
        return 2
    except json.JSONDecodeError as e:
        print(f"row_losses: {argv[1]}:{n}: {e}", file=sys.stderr)
        return 2
    shots = [s for s in shots if "row_sum" in s and "shooter_power" in s]
    total = sum(s["shooter_power"] for s in shots)
    if not shots or total <= 0:
        print(f"row_losses: {argv[1]}: no shot with a row sum and power", file=sys.stderr)
        return 2
    print(f"{len(shots)} shots")
    by_shooter = {}
    for k in ("luminaire", "patch", "cluster"):
        group = [s for s in shots if kind(s) == k]
        if not group:
            continue
        power = sum(s["shooter_power"] for s in group)
        lost_here = sum(lost(s) for s in group)
        made_here = sum(made(s) for s in group)
        over = sum(s["row_sum"] > 1.001 for s in group)
        rows = sorted(s["row_sum"] for s in group)
        print(f"  {k:9s} {len(group):6d} shots  power {100 * power / total:5.1f} %  "
              f"lost {100 * lost_here / total:5.2f} %  over 1 {100 * made_here / total:5.2f} %  "
              f"(of all shot power)  rows > 1.001: {over}  row p10 {rows[len(rows) // 10]:.3f} "
              f"median {rows[len(rows) // 2]:.3f} worst {rows[-1]:.3f}")
        for s in group:
            name = (f"cluster {s['cluster']}" if k == "cluster"
                    else f"polygon {s.get('shooter', {}).get('polygon', '?')}" if k == "patch"
                    else f"luminaire {s['luminaire']}")
            entry = by_shooter.setdefault(name, [0, 0.0, []])
            entry[0] += 1
            entry[1] += lost(s)
            entry[2].append(s["row_sum"])
    for name, (n, light, rows) in sorted(by_shooter.items(), key=lambda kv: -kv[1][1])[:worst]:
        print(f"  {name}: {n} shots, lost {100 * light / total:.2f} % of all shot power, rows "
              + " ".join(f"{r:.3f}" for r in rows[:8]) + (" ..." if len(rows) > 8 else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
