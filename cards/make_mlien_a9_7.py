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


def write(name, x, v, omega, ampv0, xinp, dtheta, trig):
    """Card 1 KEY; card 2 (I5,5F10.2,I7); 40 + 40 cards (5F10.4); the trigger card (4F10.2)."""
    n = len(v)
    xs, ys = list(x) + [0.0] * (200 - n), list(v) + [0.0] * (200 - n)
    lines = ["1", f"{n:5d}{omega:10.2f}{ampv0:10.2f}{xinp:10.2f}{0.0:10.2f}{dtheta:10.2f}{0:7d}"]
    for arr in (xs, ys):
        for c in range(40):
            lines.append("".join(f"{val:10.4f}" for val in arr[5 * c:5 * c + 5]))
    lines.append("".join(f"{val:10.2f}" for val in trig))
    open(name, "w").write("\n".join(lines) + "\n")
    print(name, n, "points")


write("mlien_a9_7.dat", x, v, 0.01, 12.0, -8.0, 0.01, (1.25, 30000.0, 0.02, 0.2))

# --- mlien_a9_7_decay.dat: the dying-out oscillation.
# Ch. 2.4.1.2: "In case of a stable origin a trajectory approaching it
# stabilizes itself on the triggering cycle instead of the origin", and App. 9:
# A9-7 "shows how the triggering oscillation can produce the observed dying-out
# oscillation after the slip part of stick-slip".  Fig. 2.21's line centred at
# 22 mm/s (FS 10, FM 6, EPS 0.5, UM 20, rising slope C = 0.1: damping ratio
# D = C/2 = 0.05 about a stable origin, inside the thesis's measured range
# 0.0089-0.059); OMEGA = -0.02 so that the drive RISES from VO = 22 (stick-slip
# on the stable limit cycle) past v_oc (the cycle vanishes) to AMPV0 = 40: the
# oscillation then dies out, by exp(-2 pi D / sqrt(1 - D^2)) per turn, less
# the faithful step's gain of about pi*DTHETA per turn.  Start on the S.L.C.
# (X = 24.6); DTHETA 0.02; triggering card OMINTR 1.25, OMETRI 30000,
# ATRI = BTRI = 0.02.
VC, FS2, FM2, EPS2, UM2, C2 = 22.0, 10.0, 6.0, 0.5, 20.0, 0.1


def h2(u):
    if u <= EPS2:
        return FS2 * u / EPS2
    if u <= UM2:
        return FS2 - (FS2 - FM2) * (u - EPS2) / (UM2 - EPS2)
    return FM2 + C2 * (u - UM2)


v2 = sorted({*np.round(np.arange(100.0, -60.01, -4.0), 2), *np.round(np.linspace(VC + EPS2, VC - EPS2, 11), 2),
             VC + UM2, VC - UM2}, reverse=True)
x2 = [float(np.sign(VC - vi)) * h2(abs(VC - vi)) - h2(VC) for vi in v2]
write("mlien_a9_7_decay.dat", x2, v2, -0.02, 40.0, 24.6, 0.02, (1.25, 30000.0, 0.02, 0.02))
