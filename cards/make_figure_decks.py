"""Writes the decks of `lieng figures` into cards/figures/ (plain f-strings,
independent of the lieng package).

LIENG-1 decks (card 1 KEY; card 2 XINCR, YINCR (2F10.4); card 3 N, OMEGA,
AMPV0, XINP, YINP, DTHETA (I5,5F10.2), OMEGA = 0 and AMPV0 = 80 (LIENG-1 uses neither); 40 cards XCHL and 40 cards YCHL
(5F10.4)).  The characteristics have the shape of the thesis's Fig. 2.21 in
LIENG-1's plane (x mm, v mm/s), x = g(v0 - v), g odd:
  h(u) = FS*u/EPS (stick part), FS - (FS-FM)(u-EPS)/(UM-EPS) (falling),
  FM + C(u-UM) (rising),
or, for Fig. 2.29, the two-slope lines of ch. 2.4.2.3.  Run from cards/:
    python make_figure_decks.py
"""
import os

import numpy as np


def h(u, fs, fm, eps, um, c):
    if u <= eps:
        return fs * u / eps
    if u <= um:
        return fs - (fs - fm) * (u - eps) / (um - eps)
    return fm + c * (u - um)


def thesis_line(v0=10.0, fs=10.0, fm=6.0, eps=0.5, um=20.0, c=0.1, vmax=80.0):
    v = sorted({*np.round(np.arange(vmax, -vmax - 0.01, -4.0), 3), *np.round(np.linspace(v0 + eps, v0 - eps, 11), 3),
                round(v0 + um, 3), round(v0 - um, 3)}, reverse=True)
    x = [float(np.copysign(h(abs(v0 - vi), fs, fm, eps, um, c), v0 - vi)) if vi != v0 else 0.0 for vi in v]
    return x, v


def two_slope_line(v0, fs, fk, dy, stick=True):
    """Kinetic parts vertical (x = +-fk), the stick part from (-fs, v0 + dy)
    to (fs, v0 - dy) (zero slope as dy -> 0) or none (both parts vertical)."""
    e = 1e-4
    if stick:
        return [-fk - e, -fk, -fs, fs, fk, fk + e], [v0 + 60, v0 + 2 * dy, v0 + dy, v0 - dy, v0 - 2 * dy, v0 - 60]
    return [-fk - e, -fk, fk, fk + e], [v0 + 60, v0 + dy, v0 - dy, v0 - 60]


def write(name, x, v, xinp, yinp, xincr=0.0, yincr=0.0, dtheta=0.01):
    n = len(v)
    assert 3 <= n <= 200
    xs, ys = list(x) + [0.0] * (200 - n), list(v) + [0.0] * (200 - n)
    lines = ["1", f"{xincr:10.4f}{yincr:10.4f}",
             f"{n:5d}{0.0:10.2f}{80.0:10.2f}{xinp:10.2f}{yinp:10.2f}{dtheta:10.2f}"]
    for arr in (xs, ys):
        for k in range(40):
            lines.append("".join(f"{val:10.4f}" for val in arr[5 * k:5 * k + 5]))
    with open(os.path.join("figures", name), "w") as fh:
        fh.write("\n".join(lines) + "\n")


os.makedirs("figures", exist_ok=True)
# 2.22: trajectories from inside and outside onto the limit cycle (v0 = 10, on the falling part)
write("fig2_22.dat", *thesis_line(), xinp=6.5, yinp=0.0, xincr=3.0)
# 2.23: the slope at the origin decides: v0 = 25 on the rising part (stable), v0 = 10 on the falling part
write("fig2_23_stable.dat", *thesis_line(v0=25.0), xinp=7.2, yinp=0.0, xincr=0.3)
write("fig2_23_unstable.dat", *thesis_line(v0=10.0), xinp=6.2, yinp=0.0, xincr=0.05)
# 2.26: v0 below the first critical velocity (on the stick part, |v0| < vr = EPS)
write("fig2_26.dat", *thesis_line(v0=0.3), xinp=10.5, yinp=0.0, xincr=4.0)
# 2.27 / 2.28: the line swept in driving velocity and in dmu0
write("fig2_27.dat", *thesis_line(), xinp=10.0, yinp=0.0)
write("fig2_28.dat", *thesis_line(v0=21.0), xinp=10.0, yinp=0.0)
# 2.29: two-slope lines: stick part of zero slope + vertical kinetic parts; both parts vertical
write("fig2_29_arc.dat", *two_slope_line(5.0, 8.0, 3.0, 0.005), xinp=9.0, yinp=0.0, xincr=-1.0)
write("fig2_29_circle.dat", *two_slope_line(5.0, 8.0, 3.0, 0.005, stick=False), xinp=4.4, yinp=0.0, xincr=-0.5)
# A9-1..A9-6: one geometric feature of the line changed at a time
variants = [dict(), dict(um=40.0), dict(um=8.0), dict(fs=14.0), dict(c=0.5), dict(eps=2.0)]
for k, kw in enumerate(variants, 1):
    write(f"figA9_{k}.dat", *thesis_line(**kw), xinp=kw.get("fs", 10.0) - 4.0, yinp=0.0, xincr=0.0)
print("wrote", len(os.listdir("figures")), "decks into cards/figures/")
