"""The line-printer listings, record by record, from the restored FORMATs.

Each FORMAT below is the listing's statement as restored (readings in
fortran/RESTORATION.md).  Records are written as a Fortran WRITE makes them:
column 1 is the carriage-control character (``1`` new page, blank single
space, ``0`` double space), kept as a character as a modern compiler writes
it; trailing blanks are dropped, as a printer does not print them.
"""

from __future__ import annotations

import math

import numpy as np

from .cards import write_record

__all__ = ["FORMATS_LIENG1", "lieng1_listing"]


def _h(text: str, width: int) -> str:
    """A Hollerith constant of a given count, blank-padded."""
    return f"{width}H{text.ljust(width)}"


FORMATS_LIENG1 = {
    41: (
        "(1H1,42HLIENARD'S GRAPHICAL CONSTRACTION WITH DATA,//"
        "44H THE CHARACTERISTIC LINE IS DETERMINED WITH ,I5,8H POINTS ,/"
        "24H THE CYCLIC FREQUENCY IS,F10.5,11HRAD PER SEC,/"
        "51H THE AMPLITUDE OF THE DRIVING VELOCITY VARIATION IS,F10.5,10HMM PER SEC,/"
        "45H THE COORDINATES OF THE INITIAL POINT ARE X= ,F10.2,5X,2HY=,F10.2,5H MM  ,/"
        "25H THE ANGLE INCREMENT IS  ,F10.2,4HRADS,/"
        "35H THE INITIAL POINT COORD.INCREM.IS ,2E10.4/)"
    ),
    30: "(5F10.2)",
    33: "(5F20.2)",
    1000: "(I7,2X,2(F20.4,2X)/55X,3(F20.8,2X))",
    1001: "(I7,2X,F20.4,2X,F20.4)",
    1005: "(///I20,F20.8)",
    1006: "(/////32H FROM SLOPE(LLL).EQ.SLOPE(MMM)  ,F20.8,F20.8)",
    1007: "(/////32H FROM SLOPE(LLL).LT.SLOPE(MMM)  ,F20.8,F20.8)",
    1008: "(/////32H FROM SLOPE(LLL).GT.SLOPE(MMM)  ,F20.8,F20.8)",
    4011: "(" + _h(" THE KEY VALUE WAS KEY=0 THE INPUT DATA ARE STORED BUT NOT DISPLAYED", 90) + ")",
    4012: "(" + _h(" THE KEY VALUE WAS KEY=1 *** THE INPUT DATA ARE STORED AND DISPLAYED", 90) + ")",
    1009: "(2F50.8)",
    100: "(3F10.3)",
    80: "(6(F6.1,2F5.1,I5))",
}


def _w(records: list[str], fmt_no: int, *values) -> None:
    records.extend(write_record(FORMATS_LIENG1[fmt_no], values))


def lieng1_listing(deck, result) -> list[str]:
    """The LIENG-1 line-printer output for a deck and its result.

    Parameters
    ----------
    deck : lieng.lieng1.Deck
    result : lieng.lieng1.Lieng1Result

    Returns
    -------
    list of str
        The printed lines, in the order the program writes them.
    """
    from .lieng1 import phi_of

    out: list[str] = []
    key = deck.key
    # PINPUT
    _w(out, 41, deck.n, deck.omega, deck.ampv0, deck.xinp, deck.yinp, deck.dtheta, deck.xincr, deck.yincr)
    if key != 0:
        for j in range(0, 200, 5):
            _w(out, 30, *deck.xchl[j : j + 5])
        for j in range(0, 200, 5):
            _w(out, 33, *deck.ychl[j : j + 5])
        n = deck.n
        xc, yc = deck.xchl, deck.ychl
        slope = result.centre.slope
        for j in range(n - 1):
            _w(out, 1000, j + 1, xc[j], yc[j], xc[j] - xc[j + 1], yc[j] - yc[j + 1], slope[j])
        _w(out, 1001, n, xc[n - 1], yc[n - 1])
        c = result.centre
        _w(out, 1005, c.isel, slope[c.isel - 1])
        _w(out, {0: 1006, -1: 1007, 1: 1008}[c.branch], c.xmdl, c.ymdl)
        _w(out, 4012)
    else:
        _w(out, 4011)
    # main program
    vo = result.ymdl
    _w(out, 1009, vo, phi_of(vo, deck.ampv0))
    npts = result.npts
    for k in range(result.ntraj):
        x, y, t = result.x[k], result.y[k], result.t[k]
        _w(out, 100, x[0], y[0], t[0])
        for l0 in range(0, npts, 60):
            vals: list = []
            for i in range(l0, min(l0 + 60, npts), 10):
                vals += [x[i], y[i], t[i], i + 1]
            _w(out, 80, *vals)
    return [ln.rstrip() for ln in out]
