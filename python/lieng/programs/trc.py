"""TRC (thesis App. 7): recorder readings to experimental phase-plane
trajectories and, by the reverse Lienard construction, the friction
characteristic.

The deck::

    card 1        HO, HON, VEL              (3F20.5)   reference levels (microstrain), paper speed (mm/s)
    card 2        OMNH, OMNV                (2F20.5)   natural frequencies, horizontal and normal (rad/s)
    card 3        SENSF, SENSN, AN1, AN2    (4F10.3)   sensitivities; cross-interference (fractions)
    card 4        NN                        (I5)       number of points of the trace (10..200)
    cards 5-      NT, NH, NHN  six a card   (18I4)     as loop 20 reads them: cards for J = 1, 7, ...,
                                                       up to NN+4, i.e. at least NN+4 triplets

NT is the paper distance from the previous point, NH and NHN the readings
of the horizontal (friction) and normal traces, all in hundredths of a
recorder millimetre.  :meth:`Deck.run` calibrates them and runs the reduction,
:func:`lieng.programs.trc_reduce.trc` (its steps are described there);
a CSV ``t,x[,xn]`` (s, mm, mm) of calibrated displacements enters it
directly (:func:`read_csv`).  Errors and warnings of a run name the deck
(:meth:`Deck.where`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from lieng.io.cards import Card, card_location, read_cards, write_cards
from lieng.errors import LiengInputError, located
from lieng.io.table import read_columns
from .trc_reduce import CSV_COLUMNS, NMIN, TrcResult, belfit, calibrate, lsqfit, origin_fit, trc

__all__ = ["Deck", "TrcResult", "trc", "calibrate", "belfit", "lsqfit", "read_csv", "CSV_COLUMNS",
           "NMIN", "NMAX_DECK", "origin_fit"]

#: "TRACE DESCRIPTION WITH 200 POINTS AT MAXIMUM" (the listing's comment).
NMAX_DECK = 200

HEAD: list[Card] = [
    Card("(3F20.5)", ("HO", "HON", "VEL")),
    Card("(2F20.5)", ("OMNH", "OMNV")),
    Card("(4F10.3)", ("SENSF", "SENSN", "AN1", "AN2")),
    Card("(I5)", ("NN",)),
]


def data_cards(nn: int) -> list[Card]:
    """The 18I4 cards loop 20 reads for NN points: J = 1, 7, ... <= NN+4."""
    cards = []
    for j in range(1, nn + 4 + 1, 6):
        names = []
        for k in range(j, j + 6):
            names += [f"NT({k})", f"NH({k})", f"NHN({k})"]
        cards.append(Card("(18I4)", tuple(names)))
    return cards


@dataclass
class Deck:
    """A TRC deck's values as the listing reads them."""

    ho: float
    hon: float
    vel: float
    omnh: float
    omnv: float
    sensf: float
    sensn: float
    an1: float
    an2: float
    nn: int
    nt: np.ndarray
    nh: np.ndarray
    nhn: np.ndarray
    source: str = "deck"

    program = "trc"

    @property
    def layout(self) -> list[Card]:
        return HEAD + data_cards(self.nn)

    def locate(self, name: str) -> str:
        return f"{self.source}: {card_location(self.layout, name)}"

    def where(self, field: str) -> str:
        """The deck's name for a field of :func:`trc`'s errors (the trace as a whole): its source."""
        return self.source

    @classmethod
    def from_lines(cls, lines: Sequence[str], source: str = "deck") -> "Deck":
        """Read the deck; raises LiengInputError naming card and columns."""
        head = read_cards(lines[:4] if len(lines) >= 4 else lines, HEAD, source)
        nn = head["NN"]
        loc = f"{source}: {card_location(HEAD, 'NN')}"
        if not NMIN <= nn <= NMAX_DECK:
            hint = " (blanks after the digits count as zeros: right-justify NN in columns 1-5)" if nn > NMAX_DECK else ""
            raise LiengInputError(f"{loc}: NN = {nn} is out of range: a trace needs {NMIN} <= NN <= {NMAX_DECK} "
                                  f"points{hint}")
        v = read_cards(lines, HEAD + data_cards(nn), source)
        nt = np.array([v[f"NT({k})"] for k in range(1, nn + 1)], dtype=np.int32)
        nh = np.array([v[f"NH({k})"] for k in range(1, nn + 1)], dtype=np.int32)
        nhn = np.array([v[f"NHN({k})"] for k in range(1, nn + 1)], dtype=np.int32)
        deck = cls(v["HO"], v["HON"], v["VEL"], v["OMNH"], v["OMNV"], v["SENSF"], v["SENSN"], v["AN1"],
                   v["AN2"], nn, nt, nh, nhn, source)
        deck.check()
        return deck

    def check(self) -> None:
        """The checks the listing lacked."""
        for name in ("HO", "HON", "VEL", "OMNH", "OMNV", "SENSF", "SENSN", "AN1", "AN2"):
            if not math.isfinite(getattr(self, name.lower())):
                raise LiengInputError(f"{self.locate(name)}: {name} is not a finite number")
        if self.vel == 0:
            raise LiengInputError(f"{self.locate('VEL')}: VEL = 0: the paper speed divides every time "
                                  f"T(I) = (T(I-1)*VEL + TC(I))/VEL")
        if self.vel < 0:
            raise LiengInputError(f"{self.locate('VEL')}: VEL = {self.vel:g}: the paper speed must be positive "
                                  f"(with VEL < 0 the times T(I) = T(I-1) + NT(I)/100/VEL run backwards)")
        for name in ("OMNH", "OMNV"):
            if getattr(self, name.lower()) == 0:
                raise LiengInputError(f"{self.locate(name)}: {name} = 0: the Lienard-plane velocity V/{name} "
                                      f"divides by the natural frequency")
        if self.an1 * self.an2 == 1:
            raise LiengInputError(f"{self.locate('AN1')}: AN1*AN2 = 1: the interference correction divides by "
                                  f"1 - AN1*AN2 = 0")
        for k in range(2, self.nn + 1):
            if self.nt[k - 1] == 0:
                raise LiengInputError(f"{self.locate(f'NT({k})')}: NT({k}) = 0: points {k - 1} and {k} have the "
                                      f"same time, the velocity divides by zero")
            if self.nt[k - 1] < 0:
                raise LiengInputError(f"{self.locate(f'NT({k})')}: NT({k}) = {int(self.nt[k - 1])}: the paper "
                                      f"distance from point {k - 1} must be positive (times must increase)")

    def values(self) -> dict:
        v = {"HO": self.ho, "HON": self.hon, "VEL": self.vel, "OMNH": self.omnh, "OMNV": self.omnv,
             "SENSF": self.sensf, "SENSN": self.sensn, "AN1": self.an1, "AN2": self.an2, "NN": self.nn}
        for card in data_cards(self.nn):
            for name in card.names:
                v[name] = 0
        for k in range(self.nn):
            v[f"NT({k + 1})"] = int(self.nt[k])
            v[f"NH({k + 1})"] = int(self.nh[k])
            v[f"NHN({k + 1})"] = int(self.nhn[k])
        return v

    def to_lines(self) -> list[str]:
        """The deck's cards (each reads back to the same value)."""
        return write_cards(self.values(), self.layout)

    def calibrated(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """T (s), X, XN (mm) after calibration and interference correction."""
        return calibrate(self.nt, self.nh, self.nhn, ho=self.ho, hon=self.hon, vel=self.vel, sensf=self.sensf,
                         sensn=self.sensn, an1=self.an1, an2=self.an2)

    def run(self, origin: str = "listing") -> "TrcResult":
        """Run the deck as the 1971 program did (``origin``: see :func:`trc`)."""
        t, x, xn = self.calibrated()
        with located(self.where):
            res = trc(t, x, xn, omnh=self.omnh, omnv=self.omnv, origin=origin)
        res.readings = (self.nt.copy(), self.nh.copy(), self.nhn.copy())
        return res


def read_csv(path):
    """Read a ``t,x[,xn]`` CSV (s, mm, mm; the normal channel may be named
    ``y``, as in diagnose records).  Returns (t, x, xn or None).

    Raises LiengInputError naming the row and column of any bad value.
    """
    arrs = read_columns(path, ("t", "x"), ("xn", "y"), "t,x[,xn]: s, mm, mm")
    if "xn" in arrs and "y" in arrs:
        raise LiengInputError(f"{path}: columns xn and y are both the normal channel: keep one")
    # y is the normal channel's name in diagnose and synth records: accepted here as xn
    return arrs["t"], arrs["x"], arrs.get("xn", arrs.get("y"))
