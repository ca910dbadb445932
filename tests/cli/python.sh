#!/usr/bin/env bash
# The Python module (python/), with Debian's python3 and numpy: it solves the Cornell box and
# its irradiance at points equals `hemirad solve --probes` for the same points and options
# (the final gather is seeded per point: deterministic; the CSV keeps 9 digits, hence 1e-7);
# group statistics, the shot log and the progress callback agree with each other and with the
# report; bad input raises a Python exception carrying hemirad's message; every option of the
# options table is a keyword of hemirad.Solver; edits re-converge incrementally.
set -euo pipefail
HEMIRAD="$1"
export PYTHONPATH="$(dirname "$HEMIRAD")/python"
PYTHON=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$HEMIRAD" scene cornell --surface-points 60 --points-out p.csv
"$HEMIRAD" solve cornell --tolerance 0.02 --quiet --probes p.csv --probe-out cli.csv \
    --report cli.json --gather-rays 256
"$PYTHON" - <<'PY'
import json, math
import numpy as np
import hemirad

rows = np.loadtxt("p.csv", delimiter=",", skiprows=1, ndmin=2)
scene = hemirad.load_scene("cornell")
assert scene.polygon_count > 0 and "floor" in scene.groups, scene

s = hemirad.Solver(scene, tolerance=0.02)
seen = []
reason = s.solve(progress=lambda shot: seen.append(shot["shot"]))
assert reason == "converged" and s.converged, reason
assert seen == list(range(1, s.shots + 1)), (seen[:5], s.shots)
log = s.shot_log
assert len(log) == s.shots and log[-1]["error_bound"] <= 0.02, log[-1]
assert {"shot", "shooter_power", "links", "time", "unshot", "error_bound"} <= set(log[0])

E = s.irradiance(rows[:, 0:3], rows[:, 3:6], gather_rays=256)
assert E.shape == (len(rows), 3) and E.dtype == np.float64
cli = np.loadtxt("cli.csv", delimiter=",", skiprows=1, usecols=(6, 7, 8), ndmin=2)
assert np.all(np.isfinite(E)) and E.max() > 0
err = np.abs(E - cli).max() / np.abs(cli).max()
assert err < 1e-7, f"Python vs CLI probes: max relative difference {err:.3g}"
# Again: the same numbers (seeded per point, whatever the threads).
assert np.array_equal(E, s.irradiance(rows[:, 0:3], rows[:, 3:6], gather_rays=256))

report = json.load(open("cli.json"))
groups = s.group_statistics()
assert set(groups) == {g["name"] for g in report["groups"]}, groups.keys()
for g in report["groups"]:
    py = groups[g["name"]]
    for key in ("E_avg", "E_min", "E_max"):
        for a, b in zip(py[key], g[key]):
            assert math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12), (g["name"], key, a, b)
assert s.report()["shots"] == report["shots"] == s.shots

# A solver that steps on while others are made and destroyed, each on its own GL context.
early = hemirad.Solver(scene, tolerance=0.02)
assert early.solve(progress=lambda shot: shot["shot"] < 2) == "stopped"

# The callback may stop the solve.
s2 = hemirad.Solver(scene, tolerance=0.02)
assert s2.solve(progress=lambda shot: shot["shot"] < 3) == "stopped" and s2.shots == 3

def raises(kind, words, f):
    try:
        f()
    except kind as e:
        assert all(w in str(e) for w in words), (str(e), words)
        return
    raise AssertionError(f"no {kind.__name__} for {words}")

raises(ValueError, ["no-such-scene"], lambda: hemirad.load_scene("no-such-scene"))
raises(hemirad.InputError, ["missing.obj"], lambda: hemirad.load_scene("missing.obj"))
raises(ValueError, ["--tolerance"], lambda: hemirad.Solver(scene, tolerance=-1))
raises(ValueError, ["(N, 3)"], lambda: s.irradiance(np.zeros((4, 2)), np.zeros((4, 2))))
raises(ValueError, ["differ"], lambda: s.irradiance(np.zeros((4, 3)), np.zeros((5, 3))))
raises(ValueError, ["not finite"],
       lambda: s.irradiance(np.full((1, 3), np.nan), np.array([[0.0, 1.0, 0.0]])))
raises(ValueError, ["--gather-rays"],
       lambda: s.irradiance(rows[:1, 0:3], rows[:1, 3:6], gather_rays=1))
raises(ValueError, ["--gather-bright", "0.5"],
       lambda: s.irradiance(rows[:1, 0:3], rows[:1, 3:6], gather_bright=0.5))
# Every solver option by its key (the options table, hemirad/solver_options.h): each one set
# alone to another value comes back, and leaves the others at their defaults.
table = hemirad.solver_option_table()
keys = [o["key"] for o in table]
assert "shooter_parallax" in keys and len(keys) == len(set(keys)) >= 28, keys
defaults = hemirad.solver_options()
assert list(defaults) == keys, (list(defaults), keys)
for o in table:
    d = o["default"]
    if isinstance(d, bool):
        v = not d
    elif isinstance(d, int):
        v = d + 3
    elif isinstance(d, float):
        v = d * 0.5 + 0.125
    else:
        v = "sr" if d == "pdm" else "pdm"
    got = hemirad.solver_options(**{o["key"]: v})
    assert got[o["key"]] == v, (o["key"], got[o["key"]], v)
    assert all(got[k] == defaults[k] for k in keys if k != o["key"]), o["key"]
s3 = hemirad.Solver(scene, shooter_parallax=1e-3, max_shots=3)
assert s3.options["shooter_parallax"] == 1e-3 and s3.solve() == "max-shots" and s3.shots == 3
assert hemirad.Solver(scene, memory_limit="4G", max_shots=1).options["memory_limit"] == 4 << 30
raises(TypeError, ["no_such_option"], lambda: hemirad.Solver(scene, no_such_option=1))
raises(TypeError, ["max_shots"], lambda: hemirad.Solver(scene, max_shots=1.5))
raises(ValueError, ["--shooter-parallax"], lambda: hemirad.Solver(scene, shooter_parallax=-1))
# Incremental re-solving: an edit leaves the converged solver unconverged; solve() goes on
# from its solution (fewer shots than the first solve) and the edit shows in the read-outs.
# `early` steps on after the temporary solvers above were made and destroyed: the same shots
# as `s`, alone, and the same read-outs (before the GL contexts were counted, a destroyed
# solver's took the display down with it and these were wrong).
del s2, s3
assert early.solve() == "converged" and early.shots == s.shots, (early.shots, s.shots)
E_early = early.irradiance(rows[:, 0:3], rows[:, 3:6], gather_rays=256)
assert np.allclose(E_early, E, rtol=1e-9, atol=0), np.abs(E_early - E).max()
del early
s = hemirad.Solver(scene, tolerance=0.02)
assert s.solve() == "converged"
first = s.shots
ceiling = s.group_statistics()["ceiling"]["E_avg"]
s.set_reflectance("floor", (0.2, 0.3, 0.4))
s.set_emission("light", 8.5)
assert not s.converged
assert s.solve() == "converged" and s.shots - first < first, (s.shots, first)
after = s.group_statistics()["ceiling"]["E_avg"]
assert after[0] < 0.7 * ceiling[0], (after, ceiling)
s.set_reflectance("floor", 0.5)
raises(ValueError, ["--reflectance floor=1.5"], lambda: s.set_reflectance("floor", 1.5))
raises(ValueError, ["no surface group 'roof'"], lambda: s.set_emission("roof", 1))
raises(ValueError, ["no luminaire named 'L9'"], lambda: s.set_luminaire_multiplier("L9", 0))
# The Cornell box has no luminaires, so no light layers: moving one is refused, naming them.
raises(ValueError, ["light layers"], lambda: s.place_luminaire("L9", (0, 1, 0), (0, -1, 0)))
print("python: ok,", s.shots, "shots, max relative difference to the CLI", err,
      ";", len(keys), "options by keyword")
PY
