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
