#!/usr/bin/env python3
"""Writes the small IES LM-63 files of hemirad's photometry tests (run from this folder).

Each file tabulates an analytic distribution, so that tests know the exact intensity and flux:
  cosine.ies        axial (C = 0 only), I = 1000 cos(gamma) over 0..90 (a Lambertian downlight):
                    flux 1000 pi = 3141.59 lm, stated as the lamp lumens
  quad_*.ies        I = 1000 cos(gamma) (1 + 0.5 cos 2C), symmetric in each quadrant, tabulated
                    over C in 0-90, 0-180, 90-270 and 0-360 (the same interpolant every time)
  bilateral_*.ies   I = 1000 cos(gamma) (1 + 0.3 cos C), symmetric about the 0-180 plane,
                    tabulated over 0-180 and 0-360
  uplight.ies       vertical angles 90..180 (LM-63-1995, ballast-lamp factor 0.8, multiplier 2,
                    ballast factor 0.5: candela scaled by 0.8)
  absolute.ies      absolute photometry (-1 lumens), LM-63-1986 (no format line), isotropic
                    100 cd over 0..180
"""
import math

def fmt(values, per_line=10):
    out = []
    for i in range(0, len(values), per_line):
        out.append(" ".join(f"{v:g}" if isinstance(v, int) or float(v).is_integer() else f"{v:.6f}"
                            for v in values[i:i + per_line]))
    return "\n".join(out)

def write(name, header, lamps, lumens, mult, gammas, cs, fn, ballast="1.0 1.0 50", extra=""):
    rows = []
    for c in cs:
        rows.append(fmt([round(fn(g, c), 6) for g in gammas]))
    text = "\n".join(
        header + ["TILT=NONE",
                  f"{lamps} {lumens} {mult} {len(gammas)} {len(cs)} 1 2 0 0 0",
                  ballast,
                  fmt(gammas), fmt(cs)] + rows) + "\n" + extra
    open(name, "w", newline="\r\n" if name == "absolute.ies" else "\n").write(text)

lm2002 = ["IESNA:LM-63-2002", "[TEST] hemirad test file", "[TESTLAB] none",
          "[ISSUEDATE] 2026-12-01", "[MANUFAC] hemirad", "[LUMINAIRE] analytic distribution"]
g90 = list(range(0, 91, 5))
g180 = list(range(0, 181, 5))
cos = lambda g: math.cos(math.radians(g))

write("cosine.ies", lm2002, 1, f"{1000 * math.pi:.4f}", 1, g90, [0], lambda g, c: 1000 * cos(g))

quad = lambda g, c: 1000 * cos(g) * (1 + 0.5 * math.cos(math.radians(2 * c)))
for name, cs in [("quad_0_90.ies", range(0, 91, 15)), ("quad_0_180.ies", range(0, 181, 15)),
                 ("quad_90_270.ies", range(90, 271, 15)), ("quad_0_360.ies", range(0, 361, 15))]:
    write(name, lm2002, 1, -1, 1, g90, list(cs), quad)

bil = lambda g, c: 1000 * cos(g) * (1 + 0.3 * math.cos(math.radians(c)))
for name, cs in [("bilateral_0_180.ies", range(0, 181, 15)), ("bilateral_0_360.ies", range(0, 361, 15))]:
    write(name, lm2002, 1, -1, 1, g90, list(cs), bil)

write("uplight.ies", ["IESNA:LM-63-1995", "[TEST] uplight", "[MANUFAC] hemirad"], 2, 500, 2,
      list(range(90, 181, 10)), [0], lambda g, c: 100 * max(0.0, -cos(g)), ballast="0.5 0.8 40")

write("absolute.ies", ["hemirad test: LM-63-1986 has no format line, free text instead"], 1, -1, 1,
      [0, 90, 180], [0], lambda g, c: 100.0)
