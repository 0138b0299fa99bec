"""Limit cycles and driving-velocity sweeps (thesis ch. 2.3.1.4, 2.4.2, App. 3).

In 1971 the limit cycles came from many LIENG runs read by eye.  Here the
return map on the abscissa does it: from (X0, 0), right of the equilibrium,
one revolution brings the trajectory back to (P(X0), 0).  A limit cycle is a
fixed point of P, and Poincare's criterion (App. 3, A3-11 to A3-15) is the
sign of D(X0) = P(X0) - X0 on either side of it:

* D > 0 inside and D < 0 outside: stable (trajectories approach it);
* D < 0 inside and D > 0 outside: unstable;
* the same sign on both sides: semi-stable (stable from one side only).

The origin (the equilibrium on the abscissa) is stable when D < 0 near it.
The amplitude is the thesis's: the distance between two successive
intersections with the abscissa, X_right - X_left.

Two modes:

* ``exact``: the closed-form solution of X'' + phi(X') + X = 0 on each
  linear piece of the characteristic, crossings located to machine
  precision (Fortran, ``cycles.f90``);
* ``faithful``: the listing's POINT step with the deck's DTHETA.  The step
  is explicit along the tangent, so each step lengthens |SP| by the factor
  sqrt(1 + DTHETA^2): about pi*DTHETA relative a revolution, which shifts the
  cycles outwards.

The sweeps move the characteristic with :mod:`lieng.analysis.shape` (its
names are importable from here too).
"""

from __future__ import annotations

import math
import sys
from dataclasses import asdict, dataclass, field

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from lieng import _core
from lieng.programs.characteristic import check_characteristic
from lieng.errors import LiengInputError
from lieng import status as st
from lieng.programs.lieng1 import lookup_code
from lieng.analysis.shape import move_to_v0, scale_static_peak, set_rising_slope, stick_part

__all__ = ["Cycle", "CyclesResult", "return_map", "find_cycles", "move_to_v0", "scale_static_peak",
           "set_rising_slope", "stick_part", "sweep_v0", "sweep_dmu", "SweepResult", "first_critical", "merged"]

MODES = ("exact", "faithful")


@dataclass
class Cycle:
    """One limit cycle.

    Attributes
    ----------
    amplitude : float
        X_right - X_left, the distance between its two intersections with
        the abscissa (mm).
    stable : bool
        True for a stable cycle (S.L.C.), False for unstable (U.L.C.) and
        semi-stable ones.
    kind : str
        "stable", "unstable" or "semi-stable".
    period : float
        Time of one revolution (units of 1/omega_n).
    x_right, x_left : float
        Its intersections with the abscissa.
    """

    amplitude: float
    stable: bool
    kind: str
    period: float
    x_right: float
    x_left: float


@dataclass
class CyclesResult:
    """The origin's stability and the limit cycles of a characteristic."""

    origin_stable: bool
    equilibrium: float
    cycles: list = field(default_factory=list)
    mode: str = "exact"
    dtheta: float | None = None

    def to_json(self) -> dict:
        """``{"origin_stable": bool, "cycles": [{"amplitude", "stable", "period", "x_right", ...}]}``."""
        return {
            "origin_stable": bool(self.origin_stable),
            "equilibrium_x": self.equilibrium,
            "mode": self.mode,
            "cycles": [asdict(c) for c in sorted(self.cycles, key=lambda c: c.amplitude)],
        }

    @property
    def stable_amplitude(self):
        """Amplitude of the largest stable cycle (the S.L.C.), or None."""
        a = [c.amplitude for c in self.cycles if c.kind == "stable"]
        return max(a) if a else None

    @property
    def unstable_amplitude(self):
        """Amplitude of the smallest unstable or semi-stable cycle (the U.L.C.), or None."""
        a = [c.amplitude for c in self.cycles if c.kind != "stable"]
        return min(a) if a else None


def _mode_args(mode: str, dtheta, lookup: str):
    if mode not in MODES:
        raise LiengInputError(f"mode = {mode!r}: choose one of {', '.join(MODES)}")
    if mode == "exact":
        return 3, 0.0
    if dtheta is None or not float(dtheta) > 0:
        raise LiengInputError("the faithful mode needs the deck's DTHETA > 0")
    return lookup_code(lookup), float(dtheta)


def return_map(xchl, ychl, x0, mode: str = "exact", dtheta=None, lookup: str = "listing", tmax: float = 200.0):
    """The return map on the abscissa.

    Parameters
    ----------
    xchl, ychl : array_like
        The characteristic (YCHL strictly decreasing).
    x0 : array_like
        Starting abscissae, right of the equilibrium.
    mode : {"exact", "faithful"}
    dtheta : float, optional
        DTHETA for the faithful mode.
    tmax : float, optional
        Time limit of each half revolution (a trajectory that does not come
        back within it has settled on the equilibrium).

    Returns
    -------
    xleft, xright, period : ndarray
        The two crossings and the time of the revolution; where the
        trajectory did not come back, ``xright`` is the equilibrium and
        ``period`` NaN.
    """
    x, y = check_characteristic(xchl, ychl)
    code, dth = _mode_args(mode, dtheta, lookup)
    return _return_map(x, y, equilibrium(x, y), x0, code, dth, tmax)


def _return_map(x, y, xs, x0, code: int, dth: float, tmax: float = 200.0):
    """:func:`return_map` on a checked characteristic (``x, y`` float arrays, equilibrium ``xs``) with the
    mode's core code and DTHETA: the search for cycles calls it many times and checks once."""
    x0 = np.atleast_1d(np.asarray(x0, dtype=float))
    maxsteps = int(min(tmax / dth, 5e7)) if dth > 0 else 1
    xl, xr, per, stat = _core.core_return_map(x, y, code, dth, x0, float(tmax), maxsteps)
    bad = stat != st.OK                           # st.NO_RETURN: settled on the equilibrium
    xr = np.where(bad, xs, xr)
    per = np.where(bad, np.nan, per)
    return xl, xr, per


def equilibrium(xchl, ychl) -> float:
    """X of the equilibrium: the characteristic at Y = 0."""
    return float(_core.core_xb(np.asarray(xchl, float), np.asarray(ychl, float), np.zeros(1), 0)[0])


def find_cycles(xchl, ychl, mode: str = "exact", dtheta=None, lookup: str = "listing", ngrid: int = 120,
                rmax: float | None = None) -> CyclesResult:
    """Stability of the origin and every limit cycle of a characteristic.

    Parameters
    ----------
    xchl, ychl : array_like
        The characteristic.
    mode : {"exact", "faithful"}
        The exact flow, or the listing's POINT step with ``dtheta``.
    dtheta : float, optional
        DTHETA of the faithful mode.
    ngrid : int, optional
        Starting points of the scan for sign changes of D = P - X0
        (geometric in the distance from the equilibrium).
    rmax : float, optional
        Largest distance from the equilibrium scanned (default: twice the
        extent of the characteristic in X plus its extent in Y).

    Returns
    -------
    CyclesResult
    """
    x, y = check_characteristic(xchl, ychl)
    code, dth = _mode_args(mode, dtheta, lookup)
    xs = equilibrium(x, y)
    if rmax is None:
        rmax = 2.0 * (np.abs(x - xs).max() + np.abs(y).max())
    r = np.geomspace(rmax * 1e-5, rmax, ngrid)

    def D(rr):
        xl, xr, _ = _return_map(x, y, xs, xs + np.atleast_1d(rr), code, dth)
        return xr - (xs + np.atleast_1d(rr))

    d = D(r)
    scale = rmax
    cycles = []
    for k in range(len(r) - 1):
        if d[k] == 0 or np.sign(d[k]) != np.sign(d[k + 1]):
            rc = brentq(lambda q: D(q)[0], r[k], r[k + 1], xtol=1e-12 * scale, rtol=1e-15, maxiter=200)
            kind = "stable" if d[k] > 0 else "unstable"
            cycles.append(_cycle(x, y, xs, xs + rc, kind, code, dth))
    # D comes near zero without changing sign on the grid: a semi-stable
    # cycle (D touches zero), or two cycles closer than the grid spacing
    # (D crosses zero twice between grid points: a stable and an unstable
    # cycle about to merge, as near v_oc)
    ad = np.abs(d) / r
    for k in range(1, len(r) - 1):
        if np.sign(d[k - 1]) == np.sign(d[k]) == np.sign(d[k + 1]) and ad[k] < ad[k - 1] and ad[k] < ad[k + 1] \
                and ad[k] < 0.05:
            sgn = np.sign(d[k])
            res = minimize_scalar(lambda q: sgn * D(q)[0] / q, bounds=(r[k - 1], r[k + 1]), method="bounded",
                                  options={"xatol": 1e-10 * scale})
            dm = D(res.x)[0]
            if abs(dm) < 1e-7 * res.x:
                cycles.append(_cycle(x, y, xs, xs + res.x, "semi-stable", code, dth))
            elif sgn * dm < 0:
                for lo, hi in ((r[k - 1], res.x), (res.x, r[k + 1])):
                    rc = brentq(lambda q: D(q)[0], lo, hi, xtol=1e-12 * scale, rtol=1e-15, maxiter=200)
                    inside = D(0.5 * (lo + rc) if lo < rc else lo)[0]
                    cycles.append(_cycle(x, y, xs, xs + rc, "stable" if inside > 0 else "unstable", code, dth))
    origin_stable = bool(d[0] < 0)
    return CyclesResult(origin_stable, xs, sorted(cycles, key=lambda c: c.amplitude), mode,
                        None if mode == "exact" else float(dtheta))


def _cycle(x, y, xs, xr, kind, code, dth) -> Cycle:
    xl, xr2, per = _return_map(x, y, xs, [xr], code, dth)
    return Cycle(float(xr - xl[0]), kind == "stable", kind, float(per[0]), float(xr), float(xl[0]))


@dataclass
class SweepResult:
    """Cycles against a parameter: the driving velocity (Fig. 2.27) or the
    static peak's scale dmu0 / dmu0_deck (Fig. 2.28)."""

    v0: list
    origin_stable: list
    stable_amplitude: list
    unstable_amplitude: list
    v_oc: float | None
    mode: str
    #: "v0" or "dmu": what ``v0`` holds (the values swept)
    param: str = "v0"

    def to_json(self) -> dict:
        if self.param == "dmu":
            return {"dmu": self.v0, "origin_stable": self.origin_stable, "stable_amplitude": self.stable_amplitude,
                    "unstable_amplitude": self.unstable_amplitude, "dmu_oc": self.v_oc, "mode": self.mode}
        return {"v0": self.v0, "origin_stable": self.origin_stable, "stable_amplitude": self.stable_amplitude,
                "unstable_amplitude": self.unstable_amplitude, "v_oc": self.v_oc, "mode": self.mode}


def _progress(i: int, n: int, label: str, enabled: bool) -> None:
    if not enabled:
        return
    w = 30
    done = int(w * i / n)
    sys.stderr.write(f"\r{label} [{'#' * done}{'.' * (w - done)}] {i}/{n}")
    if i == n:
        sys.stderr.write("\n")
    sys.stderr.flush()


def _sweep(values, move, label, critical, mode, dtheta, lookup, progress, find_critical, param, **kw):
    """Cycles of ``move(value)`` for each value, and the critical value where
    ``critical(result_k, result_k+1)`` says the regime changes (bisection)."""
    if progress is None:
        progress = sys.stderr.isatty()
    values = [float(v) for v in values]
    res = []
    for i, val in enumerate(values):
        res.append(find_cycles(*move(val), mode, dtheta, lookup, **kw))
        _progress(i + 1, len(values), label, progress)
    crit = first_critical(values, res, move, critical, mode, dtheta, lookup, **kw) if find_critical else None
    return SweepResult(values, [r.origin_stable for r in res], [r.stable_amplitude for r in res],
                       [r.unstable_amplitude for r in res], crit, mode, param)


def first_critical(values, results, move, critical, mode: str = "exact", dtheta=None, lookup: str = "listing",
                   **kw):
    """The first critical value of a sweep, refined by bisection.

    Parameters
    ----------
    values : sequence of float
        The values swept, in order.
    results : sequence of CyclesResult
        :func:`find_cycles` of ``move(value)`` for each value.
    move : callable
        value -> (xchl, ychl), the characteristic at that value.
    critical : callable
        ``critical(results[k], results[k + 1])``: the regime changes between
        the two (e.g. :func:`merged`).
    mode, dtheta, lookup, **kw
        As for :func:`find_cycles`.

    Returns
    -------
    float or None
        Where the S.L.C. appears or disappears between the first such pair,
        bisected to 1e-6 relative (at most 40 halvings); None when no pair is
        critical.
    """
    for k in range(len(values) - 1):
        if critical(results[k], results[k + 1]):
            lo, hi = values[k], values[k + 1]
            has_lo = results[k].stable_amplitude is not None
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                if (find_cycles(*move(mid), mode, dtheta, lookup, **kw).stable_amplitude is not None) == has_lo:
                    lo = mid
                else:
                    hi = mid
                if abs(hi - lo) < 1e-6 * max(1.0, abs(hi)):
                    break
            return 0.5 * (lo + hi)
    return None


def merged(a: CyclesResult, b: CyclesResult) -> bool:
    """v_oc lies between ``a`` and ``b`` (``a`` at the lower v0): ``a`` has an
    S.L.C. and a U.L.C., ``b`` no S.L.C. and a stable origin."""
    return (a.stable_amplitude is not None and a.unstable_amplitude is not None
            and b.stable_amplitude is None and b.origin_stable)


def sweep_v0(xchl, ychl, v0s, mode: str = "exact", dtheta=None, lookup: str = "listing",
             progress: bool | None = None, find_voc: bool = True, **kw) -> SweepResult:
    """The cycles for each driving velocity in ``v0s`` (the characteristic
    moved as TIMDIS moves it), and v_oc, where the S.L.C. and U.L.C. merge
    (the first step from both cycles to none, refined by bisection).

    ``progress``: a progress bar on standard error; by default only when it
    is a terminal.
    """
    return _sweep(v0s, lambda v: move_to_v0(xchl, ychl, v), "sweep v0", merged, mode, dtheta, lookup, progress,
                  find_voc, "v0", **kw)


def sweep_dmu(xchl, ychl, factors, v0: float | None = None, mode: str = "exact", dtheta=None,
              lookup: str = "listing", progress: bool | None = None, find_dmu_oc: bool = True,
              **kw) -> SweepResult:
    """The cycles with the static peak scaled (Fig. 2.28): dmu0 = mu_s - mu_k0
    multiplied by each factor (:func:`scale_static_peak`), at the deck's
    driving velocity or moved to ``v0``, and dmu_oc, the smallest factor with
    a self-sustained oscillation (a stable cycle) when the sweep crosses it.
    """
    def move(f):
        xs, ys = scale_static_peak(xchl, ychl, f)
        return (xs, ys) if v0 is None else move_to_v0(xs, ys, v0)

    def onset(a, b):
        return a.stable_amplitude is None and b.stable_amplitude is not None

    return _sweep(factors, move, "sweep dmu", onset, mode, dtheta, lookup, progress, find_dmu_oc, "dmu", **kw)


#: the most values a sweep takes (each is a limit-cycle search of about 0.05 s)
MAX_SWEEP = 2000


def parse_range(text: str, name: str = "--v0"):
    """'START:STOP:N' -> N values from START to STOP (N at most :data:`MAX_SWEEP`)."""
    try:
        a, b, n = text.split(":")
        a, b, n = float(a), float(b), int(n)
    except ValueError:
        raise LiengInputError(f"{name} {text!r}: expected START:STOP:N, e.g. 1:30:50") from None
    if n < 1 or n > MAX_SWEEP or not (math.isfinite(a) and math.isfinite(b)) or max(abs(a), abs(b)) > 1e100:
        raise LiengInputError(f"{name} {text!r}: N must be from 1 to {MAX_SWEEP} and START, STOP finite "
                              f"numbers (|value| <= 1e100)")
    return list(np.linspace(a, b, n))
