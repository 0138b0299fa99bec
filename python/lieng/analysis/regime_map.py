"""Regime maps: Table 2.IV over a grid of driving velocity and a second
parameter (thesis ch. 2.4.2.1, Figs 2.27-2.28).

At each point (v0, p) of the grid the characteristic is first changed by p
and then moved to the driving velocity v0 as TIMDIS moves it
(:func:`lieng.cycles.move_to_v0`), and :func:`lieng.cycles.find_cycles`
finds the stability of the origin and the limit cycles.  The second
parameter is one of:

* ``dmu``: the factor on the static peak dmu0 = mu_s - mu_k0 of the
  characteristic (:func:`lieng.cycles.scale_static_peak`, as ``lieng sweep
  --dmu`` scales it; 1 = the characteristic as given, mu_k0 unchanged);
* ``slope``: the slope of the rising part beyond the kinetic minimum,
  d|X - XMDL| / d|Y - YMDL| in mm per mm/s (:func:`lieng.cycles.set_rising_slope`:
  the rising part replaced by a straight line of that slope from the
  minimum; the static peak and the falling part unchanged).

The regime of each point is read from the origin's stability and the cycles
(sorted by amplitude, innermost first) as Table 2.IV lists them:

==== ========================== =========== =====================================================
code name                       Table 2.IV  what find_cycles finds
==== ========================== =========== =====================================================
0    no motion                  rows 1-2    origin stable, no limit cycle, and the origin on the
                                            stick part (between the two static peaks:
                                            -vr < v0 < vr, :func:`lieng.cycles.stick_part`)
1    no self-sustained          row 4b      origin stable, no limit cycle, the origin beyond the
     oscillation                            stick part (v0 > v_oc, or on a rising part)
2    self-excited               row 3       origin unstable, the innermost cycle stable (the
                                            S.L.C.; vr < v0 < vk)
3    depends on the trigger     row 4       origin stable inside an unstable cycle (U.L.C.)
                                            inside a stable one (S.L.C.): vk < v0 < v_oc
4    metastable                 row 4a      a semi-stable cycle (S.L.C. and U.L.C. coincide:
                                            v0 = v_oc at this very point)
5    outside Table 2.IV         -           anything else (an unstable origin with no stable
                                            cycle in the scanned range, a stable origin with an
                                            unstable cycle and nothing outside it)
==== ========================== =========== =====================================================

Rows 1 and 2 of the table differ only in v0 = 0 or not (with a stable
origin and no cycle, the thesis says "no motion", and for 0 < |v0| < vr
"equilibrium on the triggering cycle"); row 4b has the same dynamics as
row 2 (a stable origin, no cycle: the triggering cycle only) with the origin
on the rising part.  Codes 0 and 1 are therefore told apart by where the
origin lies on the characteristic, not by the cycles.  The metastable case
is a curve, not an area: v_oc(p), where the S.L.C. and the U.L.C. merge, is
found for each p as ``lieng sweep --v0`` finds it (the first step of the
grid along v0 from both cycles to none with a stable origin,
:func:`lieng.cycles.merged`, refined by bisection to 1e-6 relative,
:func:`lieng.cycles.first_critical`), so that a row of the map and a sweep
over the same velocities give the same v_oc.

Each value of the second parameter (a row of the grid, all its velocities
and its v_oc) is one task for an executor (:mod:`lieng.executor`): the
result does not depend on where the rows ran.
"""

from __future__ import annotations

import sys
import warnings
from dataclasses import dataclass

import numpy as np

from lieng.programs.characteristic import centre_of_symmetry, check_characteristic
from .cycles import (_mode_args, _progress, find_cycles, first_critical, merged, move_to_v0, scale_static_peak,
                     set_rising_slope, stick_part)
from lieng.errors import LiengInputError
from lieng.analysis.executor import run_tasks

__all__ = ["Regime", "REGIMES", "AXES", "RegimeMap", "regime_map", "classify", "characteristic_at", "check_grid",
           "MAX_POINTS"]


@dataclass(frozen=True)
class Regime:
    """One regime of the map.

    Attributes
    ----------
    code : int
        The code in :attr:`RegimeMap.regime` and in ``map.csv``.
    key : str
        A name without spaces (``map.csv``'s ``regime_name``).
    name : str
        The name in words (the plot's legend).
    row : str
        The row of Table 2.IV.
    """

    code: int
    key: str
    name: str
    row: str

    @property
    def label(self) -> str:
        """The name with its row of Table 2.IV (``"no motion (rows 1-2)"``)."""
        if self.row == "-":
            return self.name
        return f"{self.name} (row{'s' if '-' in self.row else ''} {self.row})"


#: the regimes, by code (see the module's table)
REGIMES = (
    Regime(0, "no_motion", "no motion", "1-2"),
    Regime(1, "no_self_sustained", "no self-sustained oscillation", "4b"),
    Regime(2, "self_excited", "self-excited", "3"),
    Regime(3, "depends_on_trigger", "depends on the trigger", "4"),
    Regime(4, "metastable", "metastable", "4a"),
    Regime(5, "other", "outside Table 2.IV", "-"),
)
NO_MOTION, NO_SELF_SUSTAINED, SELF_EXCITED, DEPENDS_ON_TRIGGER, METASTABLE, OTHER = range(6)

#: the second parameter: (its CSV column, with unit; its axis label)
AXES = {
    "dmu": ("dmu0/dmu0_deck", "dmu0 / dmu0 of the deck (static peak mu_s - mu_k0)"),
    "slope": ("slope [mm/(mm/s)]", "slope of the rising part beyond mu_k0 (mm per mm/s)"),
}

#: the most points a map takes (each is a limit-cycle search of some 5 ms)
MAX_POINTS = 1_000_000


def classify(res, on_stick: bool) -> int:
    """The regime code of one point (see the module's table).

    Parameters
    ----------
    res : lieng.cycles.CyclesResult
        The origin's stability and the cycles at the point.
    on_stick : bool
        The origin lies on the stick part of the characteristic (between
        its two static peaks).

    Returns
    -------
    int
    """
    kinds = [c.kind for c in sorted(res.cycles, key=lambda c: c.amplitude)]
    if "semi-stable" in kinds:
        return METASTABLE
    if not kinds:
        if not res.origin_stable:
            return OTHER
        return NO_MOTION if on_stick else NO_SELF_SUSTAINED
    if not res.origin_stable and kinds[0] == "stable":
        return SELF_EXCITED
    if res.origin_stable and kinds[0] == "unstable" and "stable" in kinds[1:]:
        return DEPENDS_ON_TRIGGER
    return OTHER


def characteristic_at(xchl, ychl, axis: str, value: float):
    """The characteristic changed by the second parameter, before it is
    moved to v0: its static peak scaled (``axis="dmu"``) or its rising
    part's slope set (``axis="slope"``).

    Returns
    -------
    xchl, ychl : ndarray
    """
    if axis == "dmu":
        return scale_static_peak(xchl, ychl, value)
    if axis == "slope":
        return set_rising_slope(xchl, ychl, value)
    raise LiengInputError(f"axis {axis!r}: choose one of {', '.join(AXES)}")


def check_grid(xchl, ychl, v0s, axis: str, values, v0_name: str = "v0s", axis_name: str | None = None):
    """Check a map's grid before any cycle is searched for.

    Parameters
    ----------
    xchl, ychl : array_like
        The characteristic.
    v0s : array_like
        The driving velocities.
    axis : {"dmu", "slope"}
        The second parameter.
    values : array_like
        Its values.
    v0_name, axis_name : str, optional
        How the messages name the two (the command line's ``--v0``,
        ``--dmu``, ``--slope``).

    Returns
    -------
    v0s, values : ndarray
        Both sorted ascending.

    Raises
    ------
    LiengInputError
        An empty axis, a value that is not finite or appears twice, a factor
        or slope that is not positive, more than :data:`MAX_POINTS` points, a
        driving velocity the characteristic cannot be moved to, a value that
        moves the centre of symmetry's velocity (v0 is measured from it).
    """
    if axis not in AXES:
        raise LiengInputError(f"axis {axis!r}: choose one of {', '.join(AXES)}")
    axis_name = axis_name or f"{axis}s"
    x, y = check_characteristic(xchl, ychl)
    out = []
    for name, vals in ((v0_name, v0s), (axis_name, values)):
        try:
            a = np.asarray(vals, dtype=float).ravel()
        except (TypeError, ValueError):
            raise LiengInputError(f"{name}: expected numbers") from None
        if a.size < 1:
            raise LiengInputError(f"{name}: at least one value")
        if not np.all(np.isfinite(a)):
            raise LiengInputError(f"{name}: every value must be a finite number")
        if np.unique(a).size != a.size:
            raise LiengInputError(f"{name}: a value appears twice (START = STOP with N > 1?): the grid's values "
                                  f"must differ")
        out.append(np.sort(a))
    v0, val = out
    if v0.size * val.size > MAX_POINTS:
        raise LiengInputError(f"{v0_name} x {axis_name}: {v0.size} x {val.size} = {v0.size * val.size} points; a map "
                              f"takes at most {MAX_POINTS}")
    if val[0] <= 0:
        what = "factors of dmu0" if axis == "dmu" else "slopes of the rising part"
        raise LiengInputError(f"{axis_name} {val[0]:g}: the {what} must be positive")
    for v in (v0[0], v0[-1]):
        try:
            move_to_v0(x, y, v)
        except LiengInputError as exc:
            raise LiengInputError(f"{v0_name}: {exc}") from None
    ymdl = centre_of_symmetry(x, y).ymdl
    for v in val:
        try:
            xs, ys = characteristic_at(x, y, axis, float(v))
            moved = centre_of_symmetry(xs, ys).ymdl
        except LiengInputError as exc:        # set_rising_slope's messages name the slope
            raise LiengInputError(f"{axis_name}{'' if axis == 'slope' else f' {v:g}'}: {exc}") from None
        if not abs(moved - ymdl) <= 1e-9 * max(1.0, abs(ymdl)):
            raise LiengInputError(f"{axis_name} {v:g}: the characteristic's centre of symmetry moves from YMDL = "
                                  f"{ymdl:g} to {moved:g}, so v0 would not be measured from the same centre")
    return v0, val


@dataclass
class _Row:
    """One row of the map: one value of the second parameter, every v0."""

    regime: np.ndarray
    origin_stable: np.ndarray
    slc: np.ndarray
    ulc: np.ndarray
    n_cycles: np.ndarray
    v_oc: float


def _row(x, y, axis, value, v0s, mode, dtheta, lookup, ngrid) -> _Row:
    """A task: the regimes along v0 at one value of the second parameter, and v_oc."""
    xs, ys = characteristic_at(x, y, axis, value)
    stick = stick_part(xs, ys)

    def move(v):
        return move_to_v0(xs, ys, v)

    res = [find_cycles(*move(v), mode, dtheta, lookup, ngrid=ngrid) for v in v0s]
    on = [stick is not None and stick[0] < v < stick[1] for v in v0s]
    voc = first_critical(list(v0s), res, move, merged, mode, dtheta, lookup, ngrid=ngrid)

    def amp(a):
        return np.nan if a is None else float(a)

    return _Row(np.array([classify(r, s) for r, s in zip(res, on)], dtype=np.int8),
                np.array([r.origin_stable for r in res], dtype=bool),
                np.array([amp(r.stable_amplitude) for r in res]),
                np.array([amp(r.unstable_amplitude) for r in res]),
                np.array([len(r.cycles) for r in res], dtype=np.int16),
                np.nan if voc is None else float(voc))


@dataclass
class RegimeMap:
    """The regimes of Table 2.IV over a grid (:func:`regime_map`).

    Arrays over the grid have the shape ``(values.size, v0.size)``: one row
    per value of the second parameter.

    Attributes
    ----------
    v0 : ndarray
        The driving velocities (the characteristic's velocity unit, mm/s),
        ascending.
    axis : str
        The second parameter: ``"dmu"`` or ``"slope"`` (:data:`AXES`).
    values : ndarray
        Its values, ascending.
    regime : ndarray of int8
        The regime code of each point (:data:`REGIMES`).
    origin_stable : ndarray of bool
        The origin's stability.
    slc, ulc : ndarray
        The amplitude (mm, X_right - X_left) of the largest stable cycle
        (S.L.C.) and of the smallest unstable or semi-stable one (U.L.C.);
        NaN where there is none.
    n_cycles : ndarray
        The number of limit cycles found.
    v_oc : ndarray
        v_oc for each value (mm/s), where the S.L.C. and U.L.C. merge; NaN
        where the grid's velocities do not cross it.
    mode : str
        ``"exact"`` or ``"faithful"`` (:func:`lieng.cycles.find_cycles`).
    """

    v0: np.ndarray
    axis: str
    values: np.ndarray
    regime: np.ndarray
    origin_stable: np.ndarray
    slc: np.ndarray
    ulc: np.ndarray
    n_cycles: np.ndarray
    v_oc: np.ndarray
    mode: str = "exact"

    @property
    def axis_label(self) -> str:
        """The second parameter's name with its unit."""
        return AXES[self.axis][0]

    def points(self):
        """Each point, row by row: (v0, value, code, Regime, origin_stable,
        S.L.C. or None, U.L.C. or None, number of cycles)."""
        for i, val in enumerate(self.values):
            for j, v in enumerate(self.v0):
                code = int(self.regime[i, j])
                s, u = self.slc[i, j], self.ulc[i, j]
                yield (float(v), float(val), code, REGIMES[code], bool(self.origin_stable[i, j]),
                       None if np.isnan(s) else float(s), None if np.isnan(u) else float(u),
                       int(self.n_cycles[i, j]))

    def counts(self) -> dict:
        """Points per regime, ``{key: count}``, every regime listed."""
        return {r.key: int(np.count_nonzero(self.regime == r.code)) for r in REGIMES}

    def summary(self) -> dict:
        """The map in brief (JSON-ready): grid, points per regime, v_oc per value."""
        return {"axis": self.axis, "axis_label": self.axis_label, "mode": self.mode,
                "v0": {"start": float(self.v0[0]), "stop": float(self.v0[-1]), "n": int(self.v0.size)},
                "values": {"start": float(self.values[0]), "stop": float(self.values[-1]),
                           "n": int(self.values.size)},
                "regimes": [{"code": r.code, "key": r.key, "name": r.name, "table_2_iv_row": r.row}
                            for r in REGIMES],
                "counts": self.counts(),
                "v_oc": [{"value": float(a), "v_oc": None if np.isnan(b) else float(b)}
                         for a, b in zip(self.values, self.v_oc)]}


def regime_map(xchl, ychl, v0s, dmus=None, slopes=None, mode: str = "exact", dtheta=None, lookup: str = "listing",
               executor=None, progress: bool | None = None, ngrid: int = 120) -> RegimeMap:
    """The regime of Table 2.IV at every point of a grid of (v0, dmu0) or
    (v0, slope), and v_oc along the second parameter.

    Parameters
    ----------
    xchl, ychl : array_like
        The characteristic (as a deck gives it).
    v0s : array_like
        Driving velocities (mm/s).
    dmus : array_like, optional
        Factors on the static peak dmu0 (1 = as given).
    slopes : array_like, optional
        Slopes of the rising part (mm per mm/s).  Give ``dmus`` or
        ``slopes``.
    mode : {"exact", "faithful"}, optional
        :func:`lieng.cycles.find_cycles`'s mode; ``dtheta`` and ``lookup``
        for the faithful one.
    executor : concurrent.futures.Executor, optional
        Where the rows run (one task per value of the second parameter):
        :func:`lieng.executor.open_executor` gives a process pool or a Dask
        cluster's executor.  Default: in this process.
    progress : bool, optional
        A progress bar on standard error, by rows (default: only when it is
        a terminal).
    ngrid : int, optional
        find_cycles' scan (the same default as ``lieng cycles`` and
        ``lieng sweep``).

    Returns
    -------
    RegimeMap

    Raises
    ------
    LiengInputError
        A bad grid (:func:`check_grid`).
    """
    if (dmus is None) == (slopes is None):
        raise LiengInputError("regime_map: give dmus or slopes (the second parameter), not both")
    axis, vals = ("dmu", dmus) if dmus is not None else ("slope", slopes)
    x, y = check_characteristic(xchl, ychl)
    _mode_args(mode, dtheta, lookup)
    v0, val = check_grid(x, y, v0s, axis, vals)
    if progress is None:
        progress = sys.stderr.isatty()
    shape = (val.size, v0.size)
    regime = np.empty(shape, dtype=np.int8)
    stable = np.empty(shape, dtype=bool)
    slc, ulc = np.empty(shape), np.empty(shape)
    ncyc = np.empty(shape, dtype=np.int16)
    voc = np.empty(val.size)
    tasks = [(x, y, axis, float(v), v0, mode, dtheta, lookup, int(ngrid)) for v in val]
    for i, row, msgs in run_tasks(executor, _row, tasks, on_done=lambda k, n: _progress(k, n, "map", progress)):
        regime[i], stable[i], slc[i], ulc[i], ncyc[i], voc[i] = (row.regime, row.origin_stable, row.slc, row.ulc,
                                                                 row.n_cycles, row.v_oc)
        for m in msgs:
            warnings.warn(m, stacklevel=2)
    return RegimeMap(v0, axis, val, regime, stable, slc, ulc, ncyc, voc, mode)
