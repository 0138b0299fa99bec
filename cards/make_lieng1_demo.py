"""Writes lieng1_demo.dat (plain f-strings, independent of the lieng package).

A characteristic of the shape of the thesis's Fig. 2.21, in the plane of
LIENG-1 (x: displacement, mm; v: slider velocity, mm/s), for a belt at
v0 = 10 mm/s:  x = g(v0 - v), g odd, g(s) = sign(s) h(|s|) with
  h(u) = FS*u/EPS                          for u <= EPS (stick part),
  h(u) = FS - (FS-FM)*(u-EPS)/(UM-EPS)    for EPS <= u <= UM (falling),
  h(u) = FM + C*(u-UM)                     for u >= UM (rising).
"""
import numpy as np

V0, FS, FM, EPS, UM, C = 10.0, 10.0, 6.0, 0.5, 20.0, 0.1


def h(u):
    if u <= EPS:
        return FS * u / EPS
    if u <= UM:
        return FS - (FS - FM) * (u - EPS) / (UM - EPS)
    return FM + C * (u - UM)


v = sorted({*np.round(np.arange(40.0, -40.01, -2.0), 2), *np.round(np.linspace(V0 + EPS, V0 - EPS, 11), 2),
            V0 + UM, V0 - UM},
           reverse=True)
x = [np.copysign(h(abs(V0 - vi)), V0 - vi) if vi != V0 else 0.0 for vi in v]
n = len(v)
xs = list(x) + [0.0] * (200 - n)
ys = list(v) + [0.0] * (200 - n)
lines = ["1", f"{0.0:10.4f}{-3.0:10.4f}",
         f"{n:5d}{0.0:10.2f}{20.0:10.2f}{8.0:10.2f}{1.0:10.2f}{0.01:10.2f}"]
for arr in (xs, ys):
    for c in range(40):
        lines.append("".join(f"{val:10.4f}" for val in arr[5 * c:5 * c + 5]))
open("lieng1_demo.dat", "w").write("\n".join(lines) + "\n")
print(n, "points")
