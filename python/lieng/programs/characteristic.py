"""The characteristic line: checks and centre of symmetry (PINPUT / CHALIN).

Shared by LIENG-1 and MLIEN.  The checks run before any compiled routine is
called, so no input can make the Fortran read out of range; each error
names the bad point as the API takes it (``fields``: ``"xchl[6]"``), and a
deck names it again by card and columns (:meth:`DeckBase.where`).
"""

from __future__ import annotations

import re
import warnings
from dataclasses import dataclass, fields

import numpy as np

from lieng import _core
from lieng.io.cards import Card, card_location, read_cards, write_cards
from lieng.errors import CentreUndefined, LiengInputError, LiengInputWarning, located
from lieng import status as st

__all__ = ["Centre", "check_characteristic", "centre_of_symmetry", "NMAX_DECK", "CHAR_CARDS", "DeckBase"]

#: DIMENSION XCHL(200), YCHL(200) of the listings.
NMAX_DECK = 200


def _point(kind: str, j: int) -> str:
    """The field of point ``j`` (1-based) of array ``kind`` ("XCHL") as the API takes it: ``xchl[j-1]``."""
    return f"{kind.lower()}[{j - 1}]"


@dataclass(frozen=True)
class Centre:
    """Result of the centre-of-symmetry search of PINPUT / CHALIN.

    Attributes
    ----------
    slope : ndarray
        SLOPE(1..N-1) = dv/dx of each segment.
    isel : int
        I, the segment with the largest negative slope (1-based).
    lll, mmm : int
        First and last segment of the run of negative slopes around I.
    branch : int
        -1, 0, +1 as SLOPE(LLL) is .LT., .EQ., .GT. SLOPE(MMM)
        (FORMATs 1007, 1006, 1008).
    xmdl, ymdl : float
        XMDL, YMDL: the centre of symmetry; YMDL is the mean driving
        velocity VO.
    """

    slope: np.ndarray
    isel: int
    lll: int
    mmm: int
    branch: int
    xmdl: float
    ymdl: float


#: the largest magnitude of a characteristic's value (mm)
MAX_ABS = 1e12


def check_characteristic(xchl, ychl) -> tuple[np.ndarray, np.ndarray]:
    """Check a characteristic line before it reaches the compiled core.

    Raises :class:`LiengInputError` for fewer than 3 points, arrays of
    different length, a value that is not finite, two neighbouring points
    with equal XCHL (infinite slope: the listing's "control statement does
    not exist") and a YCHL that does not decrease strictly (the look-up in
    POINT scans YCHL(1..N) from the highest velocity down).
    """
    x = np.ascontiguousarray(xchl, dtype=np.float64).ravel()
    y = np.ascontiguousarray(ychl, dtype=np.float64).ravel()
    if x.size != y.size:
        raise LiengInputError(f"xchl has {x.size} points but ychl has {y.size}")
    if x.size < 3:
        raise LiengInputError(f"the characteristic needs at least 3 points, got {x.size}")
    for kind, arr in (("XCHL", x), ("YCHL", y)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise LiengInputError(f"{arr[bad[0]]} is not a finite number", fields=(_point(kind, int(bad[0]) + 1),))
        big = np.flatnonzero(np.abs(arr) > MAX_ABS)
        if big.size:
            raise LiengInputError(f"{kind}({int(big[0]) + 1}) = {arr[big[0]]:g} is out of range: a "
                                  f"characteristic's values (mm) are at most {MAX_ABS:g} in magnitude, so that "
                                  f"its slopes and trajectories stay finite", fields=(_point(kind, int(big[0]) + 1),))
    eq = np.flatnonzero(np.diff(x) == 0.0)
    if eq.size:
        j = int(eq[0]) + 1
        raise LiengInputError(
            f"XCHL({j + 1}) = XCHL({j}) = {x[j - 1]:g}: infinite slope between points {j} and {j + 1}; "
            f"Lienard's construction does not apply (the listing: 'control statement does not exist')",
            fields=(_point("XCHL", j + 1),))
    up = np.flatnonzero(np.diff(y) >= 0.0)
    if up.size:
        j = int(up[0]) + 1
        raise LiengInputError(f"YCHL({j + 1}) = {y[j]:g} is not below YCHL({j}) = {y[j - 1]:g}: YCHL must "
                              f"decrease strictly from point 1 to point N", fields=(_point("YCHL", j + 1),))
    return x, y


def centre_of_symmetry(xchl, ychl, *, undefined: str = "raise") -> Centre:
    """Slopes and centre of symmetry of a characteristic, as PINPUT finds them.

    Parameters
    ----------
    xchl, ychl : array_like
        The characteristic line, YCHL strictly decreasing.
    undefined : {"raise", "warn"}, optional
        What to do when the equal-slope interpolation divides by zero: raise
        :class:`CentreUndefined`, or warn and return the centre as NaN (with
        the slopes and the run LLL..MMM as found).  A characteristic with no
        negative slope always raises.

    Returns
    -------
    Centre

    Raises
    ------
    CentreUndefined
        No negative-slope segment (the listing prints "THERE IS NOT A
        NEGATIVE SLOPE POINT" and goes on with undefined values), or an
        equal-slope interpolation that divides by zero.
    """
    x, y = check_characteristic(xchl, ychl)
    slope, isel, lll, mmm, branch, xmdl, ymdl, status, where = _core.core_centre(x, y)
    n = x.size
    if status == st.NO_NEGATIVE_SLOPE:
        raise CentreUndefined(f"there is not a negative slope point among segments 1..{n - 2} (FORMAT 1175): "
                              f"the centre of symmetry cannot be found", fields=(_point("YCHL", 1), _point("YCHL", n)))
    if status == st.CENTRE_UNDEFINED:
        msg = (f"segments {where} and {where + 1} of the negative-slope run have equal slopes, so the equal-slope "
               f"interpolation of PINPUT (statement 210/220) divides by zero: the centre of symmetry is undefined")
        run = (_point("XCHL", where), _point("XCHL", where + 2))
        if undefined != "warn":
            raise CentreUndefined(msg, fields=run)
        warnings.warn(LiengInputWarning(f"{msg}; XMDL and YMDL are NaN", fields=run), stacklevel=2)
        return Centre(np.asarray(slope[: n - 1]).copy(), int(isel), int(lll), int(mmm), int(branch),
                      float("nan"), float("nan"))
    if status != st.OK:  # pragma: no cover - ruled out by check_characteristic
        raise LiengInputError(f"characteristic rejected by the core ({st.name(status)} at {where})")
    return Centre(np.asarray(slope[: n - 1]).copy(), int(isel), int(lll), int(mmm), int(branch),
                  float(xmdl), float(ymdl))


#: The 40 XCHL and 40 YCHL cards (5F10.2) both programs read whatever N is.
CHAR_CARDS: list[Card] = (
    [Card("(5F10.2)", tuple(f"XCHL({5 * c + i + 1})" for i in range(5))) for c in range(40)]
    + [Card("(5F10.2)", tuple(f"YCHL({5 * c + i + 1})" for i in range(5))) for c in range(40)]
)


def char_from_values(v: dict) -> tuple[np.ndarray, np.ndarray]:
    """XCHL(1..200), YCHL(1..200) from a deck's ``{name: value}``."""
    xchl = np.array([v[f"XCHL({j})"] for j in range(1, NMAX_DECK + 1)], dtype=float)
    ychl = np.array([v[f"YCHL({j})"] for j in range(1, NMAX_DECK + 1)], dtype=float)
    return xchl, ychl


_POINT = re.compile(r"^(\w+)\[(\d+)\]$")


def card_field(field: str) -> str:
    """The card's name of a field the API names: ``"xchl[6]"`` -> ``"XCHL(7)"``, ``"dtheta"`` -> ``"DTHETA"``."""
    m = _POINT.match(field)
    return f"{m[1].upper()}({int(m[2]) + 1})" if m else field.upper()


class DeckBase:
    """What the LIENG-1 and MLIEN decks share: the characteristic cards,
    card-and-column locations, writing, and PINPUT's missing checks.

    Subclasses are dataclasses with ``n``, ``dtheta``, ``xchl``, ``ychl``,
    ``source``, a class attribute ``layout`` and a ``check()``; their other
    scalar fields are the layout's fields of the same names.
    """

    layout: list = []

    @classmethod
    def from_lines(cls, lines, source: str = "deck"):
        """Read the deck's cards; raises LiengInputError naming card and columns.  Each scalar field is the
        card field of its name in capitals (``key`` <- KEY); ``extra(values)`` adds the others."""
        v = read_cards(lines, cls.layout, source)
        xchl, ychl = char_from_values(v)
        kw = {f.name: v[f.name.upper()] for f in fields(cls) if f.name.upper() in v}
        deck = cls(**kw, **cls.extra(v), xchl=xchl, ychl=ychl, source=source)
        deck.check()
        return deck

    @classmethod
    def extra(cls, values: dict) -> dict:
        """Fields read from the cards other than the scalars of the same name (none by default)."""
        return {}

    def scalars(self) -> dict:
        """``{card field: value}`` of the scalar fields (those with a field of the layout's name)."""
        names = {n for card in self.layout for n in card.names}
        return {f.name.upper(): getattr(self, f.name) for f in fields(self) if f.name.upper() in names}

    def values(self) -> dict:
        """``{field name: value}`` in the names of the layout."""
        v = dict(self.scalars())
        xchl = np.zeros(NMAX_DECK)
        ychl = np.zeros(NMAX_DECK)
        xchl[: len(self.xchl)] = self.xchl[:NMAX_DECK]
        ychl[: len(self.ychl)] = self.ychl[:NMAX_DECK]
        for j in range(NMAX_DECK):
            v[f"XCHL({j + 1})"] = float(xchl[j])
            v[f"YCHL({j + 1})"] = float(ychl[j])
        return v

    def to_lines(self) -> list[str]:
        """The deck's cards (each reads back to the same value)."""
        return write_cards(self.values(), self.layout)

    def locate(self, name: str) -> str:
        """'<source>: card C, columns A-B (NAME, Fw.d)'."""
        return f"{self.source}: {card_location(self.layout, name)}"

    def where(self, field: str) -> str:
        """Where a field the API names (the ``fields`` of its errors) stands on the cards: ``"xchl[6]"`` ->
        '<source>: card 4, columns 11-20 (XCHL(7), F10.2)'; a group of one card's fields (``"xinp, yinp"``)
        by the columns from its first field to its last.  The deck layer runs the API under
        ``located(deck.where)``."""
        names = [card_field(f) for f in field.split(", ")]
        return f"{self.source}: {card_location(self.layout, names[0], names[-1] if len(names) > 1 else None)}"

    def check_characteristic_fields(self) -> None:
        """KEY a digit, N in 3..200, DTHETA > 0, and the characteristic's own checks."""
        if not 0 <= self.key <= 9:
            raise LiengInputError(f"{self.locate('KEY')}: KEY = {self.key} must be a digit 0-9")
        if not 3 <= self.n <= NMAX_DECK:
            hint = ""
            if self.n > NMAX_DECK:
                hint = " (blanks after the digits count as zeros: right-justify N in columns 1-5)"
            raise LiengInputError(
                f"{self.locate('N')}: N = {self.n} is out of range: the characteristic needs "
                f"3 <= N <= {NMAX_DECK} points (DIMENSION XCHL(200)){hint}"
            )
        if not (self.dtheta > 0 and np.isfinite(self.dtheta)):
            raise LiengInputError(f"{self.locate('DTHETA')}: DTHETA = {self.dtheta:g} must be positive")
        with located(self.where):
            check_characteristic(self.xchl[: self.n], self.ychl[: self.n])
