"""Independent NumPy renderings of the 1971 statements, for the tests.

Written from the listing (thesis App. 4) with NumPy only: nothing here
imports lieng.  The look-up of the characteristic uses np.interp, not the
listing's scan, so the two implementations share no algorithm beyond the
geometry they both implement.
"""

from __future__ import annotations

import numpy as np


def xb_interp(xchl, ychl, y):
    """XB of POINT 305-342 by np.interp: linear between points, clamped to
    XCHL(1) above YCHL(1) and to XCHL(N) below YCHL(N) (YCHL decreasing)."""
    xchl = np.asarray(xchl, float)
    ychl = np.asarray(ychl, float)
    return np.interp(y, ychl[::-1], xchl[::-1], left=xchl[-1], right=xchl[0])


def point_steps(xchl, ychl, dtheta, x0, y0, nsteps):
    """Vectorised POINT: advance arrays of points x0, y0 by nsteps steps.

    Returns arrays of shape (nsteps + 1, len(x0)) for x, y and t.
    """
    x = np.array(x0, float, ndmin=1)
    y = np.array(y0, float, ndmin=1)
    t = np.zeros_like(x)
    X, Y, T = [x.copy()], [y.copy()], [t.copy()]
    for _ in range(nsteps):
        xb = xb_interp(xchl, ychl, y)
        xk = x - xb
        r = np.sqrt(y**2 + xk**2)
        with np.errstate(divide="ignore"):
            theta = np.arctan(y / xk)
        ds = dtheta * r
        dx = np.abs(ds * np.sin(theta))
        dy = np.abs(ds * np.cos(theta))
        dt = np.abs((2.0 * dx) / (2.0 * y - dy))
        sx = np.where(y >= 0.0, 1.0, -1.0)          # 360/390 move right, 370/380 left
        sy = np.where(xk >= 0.0, -1.0, 1.0)          # 360/370 move down, 380/390 up
        x = x + sx * dx
        y = y + sy * dy
        t = t + dt
        X.append(x.copy()); Y.append(y.copy()); T.append(t.copy())
    return np.array(X), np.array(Y), np.array(T)


def time_correction(y, t, factor=1.1, band=0.2):
    """DO 140 J=6,NPTS of LIENG-1 with plain Python loops: the J-th increment
    becomes A and the later times move back by D (the restored K = J+1)."""
    t = [float(v) for v in t]
    n = len(t)
    for j in range(5, n):  # 0-based J-1
        a = ((t[j - 4] - t[j - 5]) + (t[j - 3] - t[j - 4]) + (t[j - 2] - t[j - 3]) + (t[j - 1] - t[j - 2])) / 4.0
        xco = t[j] - t[j - 1]
        if abs(y[j - 1]) < band and xco > factor * a:
            d = xco - a
            t[j] = t[j - 1] + a
            for k in range(j + 1, n):
                t[k] -= d
    return np.array(t)


def trc_readings_deck(t, x, xn, *, omnh, omnv, ho=0.0, hon=0.0, vel=1000.0, sensf=1.0, sensn=1.0,
                      an1=0.0, an2=0.0):
    """A TRC readings deck (list of card strings) from a trace sampled on a
    uniform time grid, with plain f-strings (nothing from lieng).

    The readings invert the listing's calibration: the bridges read
    X + AN2*XN and XN + AN1*X; NH = (reading - HO/500)*500/SENSF*100 and
    NHN = (reading - HON/568.2)*568.2/SENSN*100, rounded; NT is the paper
    distance from the previous point in hundredths of a mm.  Returns the
    lines and the readings actually written (nt, nh, nhn).
    """
    t = np.asarray(t, float)
    dt = np.diff(t)
    nt_step = dt[0] * vel * 100.0
    assert np.allclose(dt, dt[0]) and abs(nt_step - round(nt_step)) < 1e-6, "uniform grid, integer paper steps"
    x = np.asarray(x, float)
    xn = np.asarray(xn, float)
    xr, xnr = x + an2 * xn, xn + an1 * x
    nh = np.rint((xr - ho / 500.0) * 500.0 / sensf * 100.0).astype(int)
    nhn = np.rint((xnr - hon / 568.2) * 568.2 / sensn * 100.0).astype(int)
    nt = np.full(t.size, int(round(nt_step)))
    nt[0] = 0
    for a in (nt, nh, nhn):
        assert a.min() > -1000 and a.max() < 10000, "readings must fit I4"
    trip = list(zip(nt, nh, nhn)) + [(0, 0, 0)] * 4
    trip += [(0, 0, 0)] * (-len(trip) % 6)
    lines = [f"{ho:20.5f}{hon:20.5f}{vel:20.5f}", f"{omnh:20.5f}{omnv:20.5f}",
             f"{sensf:10.3f}{sensn:10.3f}{an1:10.3f}{an2:10.3f}", f"{t.size:5d}"]
    for c in range(0, len(trip), 6):
        lines.append("".join(f"{a:4d}{b:4d}{d:4d}" for a, b, d in trip[c:c + 6]))
    return lines, (nt, nh, nhn)


def belfit_reference(x, y, deg=2, n=5, passes=8):
    """Ch. 3.3.2's group fitting with numpy.polyfit: a degree-``deg``
    polynomial fitted to every run of ``n`` consecutive points; each point
    replaced by the mean of its fitted values; ``passes`` times."""
    x = np.asarray(x, float)
    y = np.asarray(y, float).copy()
    m = x.size
    for _ in range(passes):
        acc = np.zeros(m)
        cnt = np.zeros(m)
        for s in range(m - n + 1):
            xs = x[s:s + n]
            c = np.polyfit(xs - xs.mean(), y[s:s + n], deg)
            acc[s:s + n] += np.polyval(c, xs - xs.mean())
            cnt[s:s + n] += 1
        y = acc / cnt
    return y
