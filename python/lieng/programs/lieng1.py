"""LIENG-1 (thesis App. 4): phase portraits by Lienard's construction.

The deck (PINPUT)::

    card 1        KEY                                   (I1)
    card 2        XINCR, YINCR                          (2F10.4)
    card 3        N, OMEGA, AMPV0, XINP, YINP, DTHETA   (I5,5F10.2)
    cards 4-43    XCHL(1..200), five a card             (5F10.2)
    cards 44-83   YCHL(1..200), five a card             (5F10.2)

All 40 + 40 characteristic cards are read whatever N is (the DO loops of
PINPUT run to 196); points past N are ignored.

The program computes 9 trajectories of 3000 points; the k-th starts at
(XINP - (k-1)*XINCR, YINP - (k-1)*YINCR) as the listing steps it with
``XINP=XINP-XINCR``.  OMEGA and AMPV0 only enter the printed
``PHI = ARCOS(YMDL/AMPV0)``; LIENG-1's construction does not use them.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from lieng import _core
from lieng.io.cards import Card
from .characteristic import CHAR_CARDS, NMAX_DECK, Centre, DeckBase, centre_of_symmetry, check_characteristic
from lieng.errors import CentreUndefined, LiengInputError, LiengInputWarning, located
from lieng import status as st

__all__ = ["LAYOUT", "Deck", "Lieng1Result", "lieng1", "run_deck", "LOOKUP_MODES", "lookup_code"]

#: Modes of the POINT step: "listing" (the 1971 linear scan and ATAN/SIN/COS),
#: "bisect" (bisection look-up, bit-identical results), "fast" (bisection and
#: DX = DTHETA*|Y|, DY = DTHETA*|XK|: exact-arithmetic equal, last bits differ).
LOOKUP_MODES = {"listing": 0, "bisect": 1, "fast": 2}

LAYOUT: list[Card] = [
    Card("(I1)", ("KEY",)),
    Card("(2F10.4)", ("XINCR", "YINCR")),
    Card("(I5,5F10.2)", ("N", "OMEGA", "AMPV0", "XINP", "YINP", "DTHETA")),
] + CHAR_CARDS


@dataclass
class Deck(DeckBase):
    """The values of a LIENG-1 deck, as PINPUT reads them."""

    key: int = 1
    xincr: float = 0.0
    yincr: float = 0.0
    n: int = 3
    omega: float = 0.0
    ampv0: float = 0.0
    xinp: float = 0.0
    yinp: float = 0.0
    dtheta: float = 0.01
    xchl: np.ndarray = field(default_factory=lambda: np.zeros(NMAX_DECK))
    ychl: np.ndarray = field(default_factory=lambda: np.zeros(NMAX_DECK))
    source: str = "deck"

    program = "lieng1"
    layout = LAYOUT

    def check(self) -> None:
        """The checks PINPUT lacked: KEY a digit, N in 3..200, the characteristic, DTHETA."""
        self.check_characteristic_fields()

    def run(self, lookup: str = "listing") -> "Lieng1Result":
        """Run the deck as the 1971 program did: 9 trajectories of 3000 points."""
        return run_deck(self, lookup=lookup)


@dataclass
class Lieng1Result:
    """A LIENG-1 phase portrait.

    Attributes
    ----------
    x, y, t : ndarray, shape (ntraj, npts)
        Displacement, velocity and time of every point of every trajectory
        (``t`` after the near-abscissa time correction).
    xmdl, ymdl : float
        Centre of symmetry of the characteristic; ``ymdl`` is VO, the mean
        driving velocity.
    centre : Centre
        Slopes and the details of the centre search.
    xchl, ychl : ndarray
        The characteristic (N points).
    starts : ndarray, shape (ntraj, 2)
        Initial point of each trajectory.
    dtheta : float
        Angle increment used.
    """

    x: np.ndarray
    y: np.ndarray
    t: np.ndarray
    xmdl: float
    ymdl: float
    centre: Centre
    xchl: np.ndarray
    ychl: np.ndarray
    starts: np.ndarray
    dtheta: float

    @property
    def ntraj(self) -> int:
        return self.x.shape[0]

    @property
    def npts(self) -> int:
        return self.x.shape[1]


#: the field of the initial point (the errors of a trajectory name it: it is what the user chose)
START = "xinp, yinp"


def _status_error(status: int, where: int, itraj: int, x0: float, y0: float) -> LiengInputError:
    if status == st.SINGULAR_POINT:
        return LiengInputError(
            f"trajectory {itraj} reaches the singular point at step {where} (P = S: X = XB, Y = 0; it starts at "
            f"X = {x0:g}, Y = {y0:g}): Lienard's construction has no direction there", fields=(START,))
    if status == st.DT_UNDEFINED:
        return LiengInputError(f"trajectory {itraj}, step {where}: 2*Y - DY = 0 in DT = |2*DX/(2*Y-DY)|, the time "
                               f"increment is undefined", fields=(START,))
    return LiengInputError(f"the core stopped ({st.name(status)}) (trajectory {itraj}, step {where})",
                           fields=(START,))


def lieng1(xchl, ychl, xinp, yinp, dtheta, xincr=0.0, yincr=0.0, ntraj=9, npts=3000, *,
           lookup: str = "listing") -> Lieng1Result:
    """Phase portrait of the LIENG-1 program (thesis App. 4).

    Parameters
    ----------
    xchl, ychl : array_like, shape (N,)
        The characteristic line x = -phi(v): displacements XCHL (mm) and
        velocities YCHL (mm/s), YCHL strictly decreasing, N >= 3.
    xinp, yinp : float
        Initial point of the first trajectory (mm, mm/s).
    dtheta : float
        DTHETA, the angle increment of the construction (rad), > 0.
    xincr, yincr : float, optional
        Subtracted from the initial point after each trajectory.
    ntraj : int, optional
        Number of trajectories (9 in the listing).
    npts : int, optional
        Points per trajectory (3000 in the listing), >= 1.
    lookup : {"listing", "bisect", "fast"}, optional
        The POINT step: "listing" (default) is the 1971 arithmetic;
        "bisect" finds the segment by bisection (bit-identical, faster for
        large N); "fast" adds DX = DTHETA*|Y|, DY = DTHETA*|XK| in place of
        DS*|SIN(ATAN(Y/XK))|, DS*|COS(...)| (equal in exact arithmetic),
        and corrects the times in O(npts) (the excesses summed, not
        subtracted from every later time in turn: equal to rounding).

    Returns
    -------
    Lieng1Result
        ``x, y, t`` of shape (ntraj, npts), ``xmdl, ymdl`` and the centre.

    Raises
    ------
    LiengInputError
        Bad characteristic, non-positive DTHETA, a trajectory that meets the
        singular point, or sizes out of range.

    Warns
    -----
    UserWarning
        When the characteristic has no centre of symmetry (no negative
        slope, e.g. x = c*v with c > 0): ``xmdl`` and ``ymdl`` are NaN, the
        trajectories are computed all the same.  A deck with such a
        characteristic is an error (:func:`run_deck`).

    Errors and warnings about an argument name it in their ``fields``
    (:class:`lieng.errors.LiengInputError`).
    """
    x, y = check_characteristic(xchl, ychl)
    try:
        # LIENG-1's construction does not use the centre: an undefined
        # equal-slope interpolation only makes XMDL, YMDL NaN
        centre = centre_of_symmetry(x, y, undefined="warn")
    except CentreUndefined as exc:
        warnings.warn(LiengInputWarning(f"{exc.detail}; xmdl and ymdl are undefined (NaN; UNDEF in the listing; "
                                        f"LIENG-1's construction does not use them)", fields=exc.fields), stacklevel=2)
        slope = np.diff(y) / np.diff(x)
        centre = Centre(slope, 0, 0, 0, 0, float("nan"), float("nan"))
    try:
        ntraj = int(ntraj)
        npts = int(npts)
    except (TypeError, ValueError):
        raise LiengInputError("ntraj and npts must be integers") from None
    if ntraj < 1 or npts < 1:
        raise LiengInputError(f"ntraj = {ntraj} and npts = {npts} must both be >= 1")
    if ntraj * npts > 50_000_000:
        raise LiengInputError(f"ntraj*npts = {ntraj * npts} points is more than this API allocates (5e7)")
    vals = {"xinp": xinp, "yinp": yinp, "dtheta": dtheta, "xincr": xincr, "yincr": yincr}
    for k, v in vals.items():
        if not math.isfinite(float(v)):
            raise LiengInputError(f"{k} = {v} is not a finite number")
    if not float(dtheta) > 0:
        raise LiengInputError(f"dtheta = {dtheta} must be positive")
    X, Y, T, status, where, itraj = _core.core_lieng1(
        x, y, float(dtheta), float(xinp), float(yinp), float(xincr), float(yincr), ntraj, npts,
        lookup_code(lookup))
    starts = np.empty((ntraj, 2))
    xs, ys = float(xinp), float(yinp)
    for k in range(ntraj):
        starts[k] = xs, ys
        xs -= float(xincr)
        ys -= float(yincr)
    if status != st.OK:
        raise _status_error(int(status), int(where), int(itraj), *starts[int(itraj) - 1])
    return Lieng1Result(np.ascontiguousarray(X.T), np.ascontiguousarray(Y.T), np.ascontiguousarray(T.T),
                        centre.xmdl, centre.ymdl, centre, x, y, starts, float(dtheta))


#: trajectories larger than this many times the size of the characteristic are reported
GROWTH_WARN = 1e6


def check_growth(x, y, t, xchl, ychl, dtheta: float, start=()) -> None:
    """Refuse trajectories that overflow and warn on ones that grow without
    bound; both mean an arc step DTHETA too large for the POINT step.

    Raises
    ------
    LiengInputError
        A non-finite x, y or t (its field: ``dtheta``).

    Warns
    -----
    UserWarning
        |x| or |y| beyond :data:`GROWTH_WARN` times the characteristic's size.
    """
    x, y, t = (np.atleast_2d(np.asarray(a, float)) for a in (x, y, t))
    bad = ~(np.isfinite(x) & np.isfinite(y) & np.isfinite(t))
    if bad.any():
        k, i = (int(v) for v in np.argwhere(bad)[0])
        traj = f"trajectory {k + 1}, " if x.shape[0] > 1 else ""
        raise LiengInputError(f"DTHETA = {dtheta:g}: at {traj}point {i + 1} the arithmetic overflows (x, y or t is "
                              f"no longer a finite number): the arc step DTHETA (radians) is far too large for the "
                              f"POINT step", fields=("dtheta",))
    size = max(float(np.ptp(xchl)), float(np.ptp(ychl)), *(abs(float(v)) for v in start), 1e-300)
    big = max(float(np.max(np.abs(x))), float(np.max(np.abs(y))))
    if big > GROWTH_WARN * size:
        warnings.warn(LiengInputWarning(f"DTHETA = {dtheta:g}: the trajectories grow to |x|, |y| = {big:.3g}, "
                                        f"{big / size:.2g} times the size of the characteristic: the POINT step is "
                                        f"accurate only for small DTHETA (listing fields too narrow for a value "
                                        f"print asterisks)", fields=("dtheta",)), stacklevel=3)


def lookup_code(lookup: str) -> int:
    """The core's integer for a POINT mode name."""
    if lookup not in LOOKUP_MODES:
        raise LiengInputError(f"lookup = {lookup!r}: choose one of {', '.join(LOOKUP_MODES)}")
    return LOOKUP_MODES[lookup]


def phi_of(ymdl: float, ampv0: float) -> float:
    """PHI = ARCOS(VO/AMPV0) of the main program, NaN where ARCOS is undefined."""
    if ampv0 == 0 or abs(ymdl / ampv0) > 1:
        return float("nan")
    return math.acos(ymdl / ampv0)


def run_deck(deck: Deck, lookup: str = "listing", ntraj: int = 9, npts: int = 3000) -> Lieng1Result:
    """Run a LIENG-1 deck: 9 trajectories of 3000 points, as the listing does.

    Errors and warnings name the deck's cards and columns (:meth:`Deck.where`).  A characteristic with no
    negative slope, hence no centre of symmetry, is an error here (the 1971 program printed FORMAT 1175 and
    went on with undefined values), where :func:`lieng1` warns and computes the trajectories all the same.
    """
    deck.check()
    n = deck.n
    with located(deck.where):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")             # lieng1 says it below: an equal-slope centre is NaN
            centre_of_symmetry(deck.xchl[:n], deck.ychl[:n], undefined="warn")
        res = lieng1(deck.xchl[:n], deck.ychl[:n], deck.xinp, deck.yinp, deck.dtheta, deck.xincr, deck.yincr,
                     ntraj=ntraj, npts=npts, lookup=lookup)
        check_growth(res.x, res.y, res.t, res.xchl, res.ychl, deck.dtheta, (deck.xinp, deck.yinp))
    if math.isnan(phi_of(res.ymdl, deck.ampv0)):
        warnings.warn(
            f"{deck.source}: PHI = ARCOS(VO/AMPV0) is undefined for VO = {res.ymdl:g}, AMPV0 = {deck.ampv0:g} "
            f"(the 1971 run would have stopped here); LIENG-1 does not use PHI, so it is listed as UNDEF",
            stacklevel=2,
        )
    return res
