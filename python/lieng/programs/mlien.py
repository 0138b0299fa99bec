"""MLIEN / LIENG-2 (thesis App. 6): a driving velocity that varies in time,
a moving characteristic, and the triggering oscillation.

The deck (PINPUT of MLIEN)::

    card 1        KEY                                       (I1)
    card 2        N, OMEGA, AMPV0, XINP, YINP, DTHETA, M    (I5,5F10.2,I7)
    cards 3-42    XCHL(1..200), five a card                 (5F10.2)
    cards 43-82   YCHL(1..200), five a card                 (5F10.2)
    card 83       OMINTR, OMETRI, ATRI, BTRI (optional)     (4F10.2)

The listing hard-codes the triggering oscillation (OMINTR = 1.25 rad,
OMETRI = 30000 rad per time unit, ATRI = 10 mm, BTRI = 2 mm/s); card 83, when
present, replaces those values.  ATRI = BTRI = 0 switches the triggering off.
M, "the expected maximum slope times 1000", is read and printed but used
by no statement of the listing.

The run: CHALIN finds the centre of symmetry, VO = YMDL and
PHI = ARCOS(VO/AMPV0); T(1) = PHI/OMEGA; then, for each of 3000 points,
POINT (Lienard's step plus the triggering offset), TIMDIS (the
characteristic moved so that its centre velocity is AMPV0*COS(OMEGA*T) and
the line passes through the origin) and CHALIN again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lieng import _core
from lieng.io.cards import Card
from .characteristic import CHAR_CARDS, NMAX_DECK, Centre, DeckBase, centre_of_symmetry, check_characteristic
from lieng.errors import LiengInputError, located
from lieng import status as st
from lieng.programs.lieng1 import check_growth, lookup_code

__all__ = ["LAYOUT", "TRIGGER_LISTING", "Deck", "MlienResult", "mlien", "run_deck", "trial_run_points"]

#: OMINTR, OMETRI, ATRI, BTRI as the listing sets them in POINT.
TRIGGER_LISTING = (1.25, 30000.0, 10.0, 2.0)

TRIGGER_CARD = Card("(4F10.2)", ("OMINTR", "OMETRI", "ATRI", "BTRI"), optional=True)

LAYOUT: list[Card] = [
    Card("(I1)", ("KEY",)),
    Card("(I5,5F10.2,I7)", ("N", "OMEGA", "AMPV0", "XINP", "YINP", "DTHETA", "M")),
] + CHAR_CARDS + [TRIGGER_CARD]


@dataclass
class Deck(DeckBase):
    """The values of an MLIEN deck, as its PINPUT reads them (plus the
    optional triggering card; ``trigger`` is None when it is absent)."""

    key: int = 1
    n: int = 3
    omega: float = 1.0
    ampv0: float = 1.0
    xinp: float = 0.0
    yinp: float = 0.0
    dtheta: float = 0.01
    m: int = 0
    xchl: np.ndarray = field(default_factory=lambda: np.zeros(NMAX_DECK))
    ychl: np.ndarray = field(default_factory=lambda: np.zeros(NMAX_DECK))
    trigger: tuple | None = None
    source: str = "deck"

    program = "mlien"
    layout = LAYOUT

    @classmethod
    def extra(cls, values: dict) -> dict:
        """The optional triggering card (83): ``trigger`` is None when it is absent."""
        return {"trigger": tuple(values[k] for k in TRIGGER_CARD.names) if "OMINTR" in values else None}

    def scalars(self) -> dict:
        v = super().scalars()
        if self.trigger is not None:
            v.update(zip(TRIGGER_CARD.names, self.trigger))
        return v

    def check(self) -> None:
        """The checks PINPUT and CHALIN lacked."""
        self.check_characteristic_fields()
        if self.omega == 0:
            raise LiengInputError(f"{self.locate('OMEGA')}: OMEGA = 0: T(1) = PHI/OMEGA is undefined "
                                  f"(a constant drive is LIENG-1's case)")

    def where(self, field: str) -> str:
        """As :meth:`DeckBase.where`; ``trigger`` is card 83."""
        if field == "trigger":
            return f"{self.source}: card 83 (OMINTR, OMETRI, ATRI, BTRI)"
        return super().where(field)

    @property
    def trigger_used(self) -> tuple:
        """The triggering parameters in force: the card's, else the listing's."""
        return TRIGGER_LISTING if self.trigger is None else tuple(self.trigger)

    def run(self, lookup: str = "listing", npts: int = 3000) -> "MlienResult":
        """Run the deck as the 1971 program did (3000 points)."""
        return run_deck(self, lookup=lookup, npts=npts)


@dataclass
class MlienResult:
    """An MLIEN trajectory.

    Attributes
    ----------
    x, y, t : ndarray, shape (npts,)
        The trajectory: displacement (mm), velocity (mm/s), time.
    r : ndarray, shape (npts,)
        R = |SP| of the step from each point (0 for the last point).
    xmdl, ymdl : ndarray, shape (npts,)
        Centre of symmetry of the characteristic in force at each point;
        ``ymdl`` is the driving velocity VO = AMPV0*COS(OMEGA*T) after TIMDIS.
    xchl, ychl : ndarray
        The characteristic as given.
    xchl_last, ychl_last : ndarray
        Its last position (moved for T(npts)).
    centre : Centre
        The first CHALIN's centre search.
    vo, phi : float
        VO and PHI of the first CHALIN; T(1) = PHI/OMEGA.
    omega, ampv0, dtheta : float
    trigger : tuple
        OMINTR, OMETRI, ATRI, BTRI used.
    """

    x: np.ndarray
    y: np.ndarray
    t: np.ndarray
    r: np.ndarray
    xmdl: np.ndarray
    ymdl: np.ndarray
    xchl: np.ndarray
    ychl: np.ndarray
    xchl_last: np.ndarray
    ychl_last: np.ndarray
    centre: Centre
    vo: float
    phi: float
    omega: float
    ampv0: float
    dtheta: float
    trigger: tuple

    @property
    def npts(self) -> int:
        return self.x.size


def trial_run_points(npts: int) -> list[int]:
    """L (1-based) of the trial-run prints: NL(L+1) - NL(L) /= 0 with
    NL(L) = (10+L)/10, so L = 1, 9, 19, ..., up to NPTS-1."""
    return [1] + list(range(9, npts, 10))


def mlien(xchl, ychl, xinp, yinp, dtheta, omega, ampv0, trigger=None, npts=3000, *,
          lookup: str = "listing") -> MlienResult:
    """The MLIEN program (thesis App. 6): Lienard's construction with the
    driving velocity AMPV0*COS(OMEGA*t) and the triggering oscillation.

    Parameters
    ----------
    xchl, ychl : array_like, shape (N,)
        The characteristic line as given (mm, mm/s), YCHL strictly
        decreasing, with a negative-slope part whose centre of symmetry
        gives the initial driving velocity VO = YMDL.
    xinp, yinp : float
        Initial point (mm, mm/s).
    dtheta : float
        DTHETA, angle increment (rad), > 0.
    omega : float
        OMEGA, cyclic frequency of the driving-velocity variation (rad per
        time unit), not 0.
    ampv0 : float
        AMPV0, its amplitude (mm/s); |VO| <= |AMPV0| so that
        PHI = ARCOS(VO/AMPV0) exists.
    trigger : (omintr, ometri, atri, btri) or None, optional
        The triggering oscillation; None takes the listing's values
        (1.25, 30000, 10, 2).  ``atri = btri = 0`` switches it off.
    npts : int, optional
        Points of the trajectory (3000 in the listing).
    lookup : {"listing", "bisect", "fast"}, optional
        The POINT step, as in :func:`lieng.lieng1`.

    Returns
    -------
    MlienResult

    Raises
    ------
    LiengInputError
        Bad characteristic, OMEGA = 0, |VO| > AMPV0 (ARCOS out of its domain),
        a driving velocity that leaves the velocity range of the moved
        characteristic (the listing then uses an undefined value), a point
        on the singular point.  Each names the argument in its ``fields``
        (:class:`lieng.errors.LiengInputError`).
    """
    x, y = check_characteristic(xchl, ychl)
    centre = centre_of_symmetry(x, y)
    trig = TRIGGER_LISTING if trigger is None else tuple(float(v) for v in trigger)
    if len(trig) != 4 or not all(math.isfinite(v) for v in trig):
        raise LiengInputError("(omintr, ometri, atri, btri) must be four finite numbers", fields=("trigger",))
    for k, v in (("omega", omega), ("ampv0", ampv0), ("xinp", xinp), ("yinp", yinp), ("dtheta", dtheta)):
        if not math.isfinite(float(v)):
            raise LiengInputError(f"{v} is not a finite number", fields=(k,))
    if not float(dtheta) > 0:
        raise LiengInputError(f"DTHETA = {dtheta} must be positive", fields=("dtheta",))
    if float(omega) == 0:
        raise LiengInputError("OMEGA = 0: T(1) = PHI/OMEGA is undefined", fields=("omega",))
    npts = int(npts)
    if not 1 <= npts <= 10_000_000:
        raise LiengInputError(f"npts = {npts} must be between 1 and 1e7")
    vo = centre.ymdl
    if float(ampv0) == 0 or abs(vo / float(ampv0)) > 1:
        raise LiengInputError(f"PHI = ARCOS(VO/AMPV0) is undefined: the centre of symmetry gives VO = YMDL = "
                              f"{vo:.6g} but AMPV0 = {float(ampv0):g}; |AMPV0| must be at least |VO|",
                              fields=("ampv0",))
    X, Y, T, R, XM, YM, XL, YL, status, where = _core.core_mlien(
        x, y, float(dtheta), float(omega), float(ampv0), float(xinp), float(yinp), npts,
        np.array(trig, dtype=float), lookup_code(lookup))
    status, where = int(status), int(where)
    if status == st.TIMDIS_RANGE:
        tw = float(T[where - 1])
        with np.errstate(all="ignore"):
            phase = np.float64(omega) * np.float64(tw)
            drive = float(ampv0) * float(np.cos(phase))
        if not math.isfinite(tw):
            raise LiengInputError(f"DTHETA = {float(dtheta):g}: at point {where} the time T is no longer a finite "
                                  f"number: the arc step DTHETA (radians) is far too large for the POINT step",
                                  fields=("dtheta",))
        if not math.isfinite(float(phase)):
            raise LiengInputError(f"OMEGA = {float(omega):g}: at point {where} the phase OMEGA*T overflows",
                                  fields=("omega",))
        raise LiengInputError(
            f"at point {where} (T = {tw:.6g}) the driving velocity AMPV0*COS(OMEGA*T) = {drive:.6g} needs the "
            f"characteristic at a velocity outside its range (TIMDIS would use an undefined ADIFF); extend YCHL or "
            f"reduce AMPV0", fields=("omega", "ampv0"))
    if status == st.SINGULAR_POINT:
        raise LiengInputError(f"point {where} is the singular point (P = S): Lienard's construction has no "
                              f"direction there", fields=("xinp, yinp",))
    if status == st.DT_UNDEFINED:
        raise LiengInputError(f"point {where}: 2*Y - DY = 0, the time increment is undefined",
                              fields=("xinp, yinp",))
    if status == st.CENTRE_UNDEFINED:
        raise LiengInputError(f"at point {where} the moved characteristic's centre of symmetry is undefined "
                              f"(equal-slope interpolation divides by zero)")
    if status != st.OK:
        raise LiengInputError(f"the MLIEN core stopped ({st.name(status)}) at point {where}")
    check_growth(X, Y, T, x, y, float(dtheta), (float(xinp), float(yinp)))
    return MlienResult(X, Y, T, R, XM, YM, x, y, XL, YL, centre, vo, math.acos(vo / float(ampv0)),
                       float(omega), float(ampv0), float(dtheta), trig)


def run_deck(deck: Deck, lookup: str = "listing", npts: int = 3000) -> MlienResult:
    """Run an MLIEN deck: one trajectory of 3000 points, as the listing does; errors and warnings name the
    deck's cards and columns (:meth:`Deck.where`)."""
    deck.check()
    n = deck.n
    with located(deck.where):
        return mlien(deck.xchl[:n], deck.ychl[:n], deck.xinp, deck.yinp, deck.dtheta, deck.omega, deck.ampv0,
                     trigger=deck.trigger, npts=npts, lookup=lookup)
