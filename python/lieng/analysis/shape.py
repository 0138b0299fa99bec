"""The characteristic's shape changed for a sweep or a map (thesis ch. 2.4.2, Figs 2.27-2.28, Table 2.IV):
moved to a driving velocity as TIMDIS moves it, its static peak scaled, the slope of its rising part set,
and the driving velocities that put the origin on its stick part.  Each works on a characteristic alone;
the limit cycles of the result are :mod:`lieng.analysis.cycles` (whose names these stay, too).
"""

from __future__ import annotations

import math

import numpy as np

from lieng import _core
from lieng.programs.characteristic import centre_of_symmetry, check_characteristic
from lieng.errors import LiengInputError
from lieng import status as st

__all__ = ["move_to_v0", "scale_static_peak", "set_rising_slope", "stick_part"]


def move_to_v0(xchl, ychl, v0: float):
    """The characteristic moved to the driving velocity ``v0`` exactly as
    TIMDIS moves it: by (-ADIFF, -DIFF), DIFF = VO - v0 with VO = YMDL its
    centre, so that its centre sits at ``v0`` and the line passes through
    the origin."""
    x, y = check_characteristic(xchl, ychl)
    vo = centre_of_symmetry(x, y).ymdl
    xs, ys = x.copy(), y.copy()
    diff, adiff, status = _core.core_timdis(xs, ys, vo, float(v0), 0.0, 0.0)
    if status != st.OK:
        raise LiengInputError(f"v0 = {v0:g}: the characteristic has no point at velocity VO - v0 = {vo - v0:g} "
                              f"(its range is {y[-1]:g} to {y[0]:g}), so TIMDIS cannot move it there")
    return xs, ys


def _kinetic_sides(x, y):
    """The static peak and the kinetic minimum on each side of the centre of
    symmetry of a checked characteristic.

    Returns
    -------
    centre : Centre
    sides : list of (ndarray, int, int)
        Per side that has a static peak: the side's indices from the centre
        outwards, the position ``p`` (in that order) of the static peak, the
        first local maximum of |X - XMDL|, and the position ``m`` of the
        kinetic minimum after it, the lowest |X - XMDL| before it rises
        again (the side's last point when it never rises).
    """
    c = centre_of_symmetry(x, y)
    dx = np.abs(x - c.xmdl)
    sides = []
    for side in (np.flatnonzero(y < c.ymdl), np.flatnonzero(y > c.ymdl)[::-1]):
        if side.size < 2:
            continue
        a = dx[side]                              # from the centre outwards
        fall = np.flatnonzero(np.diff(a) < 0)
        if fall.size == 0:
            continue                              # no static peak on this side
        p = int(fall[0])                          # the static peak: the first local maximum
        rise = np.flatnonzero(np.diff(a[p:]) > 0)
        m = p + (int(rise[0]) if rise.size else a.size - 1 - p)   # the kinetic minimum after it
        sides.append((side, p, m))
    return c, sides


def scale_static_peak(xchl, ychl, factor: float):
    """The characteristic with its static peak scaled (Fig. 2.28).

    On each side of the centre of symmetry, from the centre out to the
    minimum of the kinetic part (mu_k0, the lowest |X - XMDL| beyond the
    static peak), the excess of |X - XMDL| over that minimum is multiplied
    by ``factor``; the line beyond the minimum (the rising part) is left as
    it is.  So dmu0 = mu_s - mu_k0 scales by ``factor`` and mu_k0 stays."""
    x, y = check_characteristic(xchl, ychl)
    c, sides = _kinetic_sides(x, y)
    dx = x - c.xmdl
    xs = x.copy()
    for side, p, m in sides:
        kin = abs(dx[side[m]])
        inner = side[:m]
        over = inner[np.abs(dx[inner]) > kin]
        xs[over] = c.xmdl + np.sign(dx[over]) * (kin + factor * (np.abs(dx[over]) - kin))
    return xs, y


def set_rising_slope(xchl, ychl, slope: float):
    """The characteristic with the slope of its rising part set to ``slope``.

    On each side of the centre of symmetry, beyond the kinetic minimum
    (mu_k0, the lowest |X - XMDL| after the static peak: see
    :func:`scale_static_peak`), the rising part is replaced by the straight
    line |X - XMDL| = |X_m - XMDL| + slope * |Y - Y_m| from the minimum
    (X_m, Y_m), at the characteristic's own velocities.  ``slope`` is
    d|X - XMDL| / d|Y - YMDL| in the characteristic's units (mm per mm/s):
    the damping of the rising part (Fig. 2.21's c).  The static peak, the
    falling part and the centre's velocity YMDL stay as they are; a side
    without a rising part (its minimum is its last point) is unchanged.

    Raises
    ------
    LiengInputError
        ``slope`` not a positive finite number, no side with a rising part,
        or a slope so steep that the centre-of-symmetry search would find
        another centre (so that v0 would no longer be measured from YMDL).
    """
    x, y = check_characteristic(xchl, ychl)
    if not (math.isfinite(slope) and slope > 0):
        raise LiengInputError(f"the rising part's slope must be a positive number (mm per mm/s), not {slope:g}")
    c, sides = _kinetic_sides(x, y)
    dx = x - c.xmdl
    xs = x.copy()
    rising = 0
    for side, p, m in sides:
        beyond = side[m + 1:]
        rising += beyond.size
        kin = abs(dx[side[m]])
        xs[beyond] = c.xmdl + np.sign(dx[beyond]) * (kin + slope * np.abs(y[beyond] - y[side[m]]))
    if rising == 0:
        raise LiengInputError("the characteristic has no rising part beyond a kinetic minimum: its slope cannot be "
                              "set")
    moved = centre_of_symmetry(xs, y)
    if not abs(moved.ymdl - c.ymdl) <= 1e-9 * max(1.0, abs(c.ymdl)):
        raise LiengInputError(f"a rising part of slope {slope:g} moves the centre of symmetry from YMDL = "
                              f"{c.ymdl:g} to {moved.ymdl:g} (the centre search takes it for the stick part)")
    return xs, y


def stick_part(xchl, ychl):
    """The driving velocities for which the origin lies on the stick part.

    The stick part runs between the two static peaks (:func:`scale_static_peak`);
    moved to v0 (:func:`move_to_v0`: the centre of symmetry to velocity
    v0), the characteristic has the origin on it when YMDL - y_upper < v0 <
    YMDL - y_lower, with y_upper, y_lower the peaks' velocities: Table
    2.IV's -vr < v0 < vr.  The interval does not change when the
    characteristic is moved.

    Returns
    -------
    (float, float) or None
        The interval's ends, or None when a side has no static peak.
    """
    x, y = check_characteristic(xchl, ychl)
    c, sides = _kinetic_sides(x, y)
    if len(sides) < 2:
        return None
    (lo, plo, _), (hi, phi, _) = sides
    return float(c.ymdl - y[hi[phi]]), float(c.ymdl - y[lo[plo]])
