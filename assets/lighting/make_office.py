#!/usr/bin/env python3
"""Writes the lighting-design example of the README (run from this folder): office.obj/.mtl,
a 6 m x 4 m x 2.8 m office (metres, y up) with a desk top, and downlight.ies, an example downlight
(I = 1000 cos^2(gamma) cd below the horizontal: 2094 lm from 2500 lamp lumens). office.json,
written by hand, places six downlights and a wall spot in it."""
import math

W, D, H = 6.0, 4.0, 2.8

def quad(out, corners):
    out.append("f " + " ".join(str(c) for c in corners))

obj = ["# hemirad lighting example: a 6 m x 4 m x 2.8 m office with a desk (metres, y up).",
       "# Written by make_office.py; lit by office.json.", "mtllib office.mtl"]
verts = []
def v(x, y, z):
    verts.append((x, y, z))
    return len(verts)
faces = []
def rect(group, material, a, b, c, d):
    faces.append((group, material, [v(*a), v(*b), v(*c), v(*d)]))
# Room, every face seen from inside (counter-clockwise from the front).
# The floor's first edge runs along +x: a grid floor:NXxNY has NX points along x (grid.h).
rect("floor", "carpet", (0, 0, D), (W, 0, D), (W, 0, 0), (0, 0, 0))
rect("ceiling", "ceiling", (0, H, 0), (W, H, 0), (W, H, D), (0, H, D))
rect("wall_x0", "wall", (0, 0, 0), (0, H, 0), (0, H, D), (0, 0, D))
rect("wall_x1", "wall", (W, 0, 0), (W, 0, D), (W, H, D), (W, H, 0))
rect("wall_z0", "wall", (0, 0, 0), (W, 0, 0), (W, H, 0), (0, H, 0))
rect("wall_z1", "wall", (0, 0, D), (0, H, D), (W, H, D), (W, 0, D))
# A desk: a 1.6 m x 0.8 m top, 30 mm thick, at 0.75 m (its legs left out), faces outwards.
x0, x1, z0, z1, y0, y1 = 2.2, 3.8, 1.6, 2.4, 0.72, 0.75
rect("desk", "desk", (x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))  # top, up
rect("desk", "desk", (x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # bottom, down
rect("desk", "desk", (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))  # -z
rect("desk", "desk", (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))  # +z
rect("desk", "desk", (x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # -x
rect("desk", "desk", (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))  # +x
for p in verts:
    obj.append("v %g %g %g" % p)
for group, material, idx in faces:
    obj += ["g " + group, "usemtl " + material]
    quad(obj, idx)
open("office.obj", "w").write("\n".join(obj) + "\n")
open("office.mtl", "w").write("\n".join([
    "# reflectances: carpet 0.2, walls 0.5, ceiling 0.8, desk 0.4",
    "newmtl carpet", "Kd 0.2 0.2 0.2", "newmtl wall", "Kd 0.5 0.5 0.5",
    "newmtl ceiling", "Kd 0.8 0.8 0.8", "newmtl desk", "Kd 0.4 0.4 0.4"]) + "\n")

gammas = [2.5 * k for k in range(37)]  # 0 .. 90
cd = [round(1000 * math.cos(math.radians(g)) ** 2, 3) for g in gammas]
def lines(vals, n=10):
    return [" ".join("%g" % x for x in vals[i:i + n]) for i in range(0, len(vals), n)]
ies = ["IESNA:LM-63-2002", "[TEST] hemirad example (analytic: 1000 cos^2 gamma)",
       "[TESTLAB] none", "[ISSUEDATE] 2026-12-01", "[MANUFAC] hemirad example",
       "[LUMCAT] DL-2000", "[LUMINAIRE] recessed downlight, opal diffuser", "[LAMP] LED module 2500 lm",
       "TILT=NONE", "1 2500 1 %d 1 1 2 0.15 0.15 0" % len(gammas), "1.0 1.0 22"] + \
      lines(gammas) + ["0"] + lines(cd)
open("downlight.ies", "w").write("\n".join(ies) + "\n")
