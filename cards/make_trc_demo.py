"""Writes trc_demo.dat: a TRC readings deck of a simulated stick-slip trace
(plain NumPy and f-strings, independent of the lieng package).

The dynamometer's horizontal mode in the Lienard plane (tau = OMNH*t, x in
mm, ' = d/dtau):  x'' + x = f(v0 - x'), with the friction displacement
    f(s) = sign(s) * (FK + (FS - FK) * exp(-|s|/SC)) + C*s  (slip),
and stick (x' = v0) while |x| <= FS.  The known characteristic is
XCHL(v) = f(v0 - v); TRC should give back f(v0 - v) - f(v0) (shifted by EL).
The normal mode follows the friction mode through the rig's coupling,
xn = XN0 + BETA*x, so the Lisitsyn "ellipse" is a line and AM = x/xn.
The readings carry 1 % / 2 % cross-interference (AN1, AN2), inverted here.
"""
import numpy as np

OMNH, OMNV = 2 * np.pi * 30.0, 2 * np.pi * 45.0    # rad/s
V0 = 5.0 / OMNH                                      # 5 mm/s drive, in the Lienard plane (mm)
FS, FK, SC, C = 0.060, 0.035, 0.010, 0.05            # mm
XN0, BETA = 0.30, 0.5                                # mm
HO, HON, VEL = -4.0, 164.0, 2000.0                   # microstrain, microstrain, mm/s paper speed
SENSF, SENSN, AN1, AN2 = 1.0, 1.0, 0.01, 0.02
NT_STEP, NN = 60, 180                                 # 0.6 mm of paper between points


def f(s):
    return np.sign(s) * (FK + (FS - FK) * np.exp(-abs(s) / SC)) + C * s


def simulate(tau_end, h=1e-4):
    x, v, tau, out = 0.0, V0, 0.0, [(0.0, 0.0)]
    stick = True
    while tau < tau_end:
        if stick:
            x += V0 * h
            if x > FS:
                stick = False
                v = V0 - 1e-9
        else:
            def acc(xx, vv):
                return -xx + f(V0 - vv)
            k1x, k1v = v, acc(x, v)
            k2x, k2v = v + h / 2 * k1v, acc(x + h / 2 * k1x, v + h / 2 * k1v)
            k3x, k3v = v + h / 2 * k2v, acc(x + h / 2 * k2x, v + h / 2 * k2v)
            k4x, k4v = v + h * k3v, acc(x + h * k3x, v + h * k3v)
            x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
            v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            if v >= V0:
                stick, v = True, V0
        tau += h
        out.append((tau, x))
    return np.array(out)


if __name__ == "__main__":
    dt = NT_STEP / 100.0 / VEL
    t = np.arange(NN) * dt + 0.25                     # start after the first slip
    sim = simulate(OMNH * t[-1] + 0.01)
    x = np.interp(OMNH * t, sim[:, 0], sim[:, 1])
    xn = XN0 + BETA * x
    xr, xnr = x + AN2 * xn, xn + AN1 * x              # what the bridges read
    nh = np.rint((xr - HO / 500.0) * 500.0 / SENSF * 100.0).astype(int)
    nhn = np.rint((xnr - HON / 568.2) * 568.2 / SENSN * 100.0).astype(int)
    nt = np.full(NN, NT_STEP)
    nt[0] = 0
    assert nh.min() > -1000 and nh.max() < 10000 and nhn.min() > -1000 and nhn.max() < 10000, (nh, nhn)
    trip = list(zip(nt, nh, nhn)) + [(0, 0, 0)] * 4
    trip += [(0, 0, 0)] * (-len(trip) % 6)
    lines = [f"{HO:20.5f}{HON:20.5f}{VEL:20.5f}", f"{OMNH:20.5f}{OMNV:20.5f}",
             f"{SENSF:10.3f}{SENSN:10.3f}{AN1:10.3f}{AN2:10.3f}", f"{NN:5d}"]
    for c in range(0, len(trip), 6):
        lines.append("".join(f"{a:4d}{b:4d}{d:4d}" for a, b, d in trip[c:c + 6]))
    open("trc_demo.dat", "w").write("\n".join(lines) + "\n")
    print(NN, "points;", "x from", x.min(), "to", x.max(), "mm")
