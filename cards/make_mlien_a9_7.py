"""Writes mlien_a9_7.dat (plain f-strings, independent of the lieng package).

Fig. A9-7 of the thesis (App. 9): MLIEN with a driving velocity that varies
in time and the triggering oscillation, which "can produce the observed
dying-out oscillation after the slip part of stick-slip".  The figure is
lost; this deck shows the claim.  The characteristic has the shape of
Fig. 2.21 for a belt at 10 mm/s, moved so that it passes through the origin
(MLIEN works in the transformed plane of eq. 2.18):
  x = g(10 - v) - g(10),  g(s) = sign(s) h(|s|),
  h(u) = 20u (u <= 0.5), 10 - 4(u-0.5)/19.5 (u <= 20), 6 + 0.1(u-20).
Drive: AMPV0 = 12 mm/s, OMEGA = 0.01; triggering card: OMINTR = 1.25,
OMETRI = 30000 (the listing's), ATRI = 0.02 mm, BTRI = 0.2 mm/s.
"""
import numpy as np

def h(u):
    return 20.0 * u if u <= 0.5 else (10.0 - 4.0 * (u - 0.5) / 19.5 if u <= 20.0 else 6.0 + 0.1 * (u - 20.0))

def g(s):
    return float(np.sign(s)) * h(abs(s))

v = sorted({*np.round(np.arange(60.0, -60.01, -2.0), 2), *np.round(np.linspace(10.5, 9.5, 11), 2), 30.0, -10.0},
           reverse=True)
x = [g(10.0 - vi) - g(10.0) for vi in v]
n = len(v)
xs, ys = x + [0.0] * (200 - n), list(v) + [0.0] * (200 - n)
lines = ["1", f"{n:5d}{0.01:10.2f}{12.0:10.2f}{-8.0:10.2f}{0.0:10.2f}{0.01:10.2f}{0:7d}"]
for arr in (xs, ys):
    for c in range(40):
        lines.append("".join(f"{val:10.4f}" for val in arr[5 * c:5 * c + 5]))
lines.append(f"{1.25:10.2f}{30000.0:10.2f}{0.02:10.2f}{0.2:10.2f}")
open("mlien_a9_7.dat", "w").write("\n".join(lines) + "\n")
print(n, "points")
