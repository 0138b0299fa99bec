"""The line-printer listings, record by record, from the restored FORMATs.

Each FORMAT below is the listing's statement as restored (readings in
fortran/RESTORATION.md).  Records are written as a Fortran WRITE makes them:
column 1 is the carriage-control character (``1`` new page, blank single
space, ``0`` double space), kept as a character as a modern compiler writes
it; trailing blanks are dropped, as a printer does not print them.
"""

from __future__ import annotations

from lieng.io.cards import write_record

__all__ = ["FORMATS_LIENG1", "FORMATS_MLIEN", "FORMATS_TRC", "lieng1_listing", "mlien_listing", "trc_listing"]


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


#: MLIEN (App. 6): its PINPUT header (under IF(KEY.EQ.0) GO TO 410, with M
#: and DTHETA in E10.2), CHALIN's 1005 with E20.8, and the trial-run print.
FORMATS_MLIEN = dict(FORMATS_LIENG1)
FORMATS_MLIEN.update({
    41: (
        "(1H1,42HLIENARD'S GRAPHICAL CONSTRACTION WITH DATA,//"
        "44H THE CHARACTERISTIC LINE IS DETERMINED WITH ,I5,8H POINTS ,/"
        "24H THE CYCLIC FREQUENCY IS,F10.5,11HRAD PER SEC,/"
        "51H THE AMPLITUDE OF THE DRIVING VELOCITY VARIATION IS,F10.5,10HMM PER SEC,/"
        "45H THE COORDINATES OF THE INITIAL POINT ARE X= ,F10.2,5X,2HY=,F10.2,5H MM  ,/"
        "25H THE ANGLE INCREMENT IS  ,E10.2,4HRADS,/"
        "35H THE SLOPE COMPARISON FACTOR IS M= ,I7//////////)"
    ),
    1005: "(///I20,E20.8)",
    1010: "(6F10.3,I8)",
    33: "(5E20.2)",            # MLIEN's YCHL echo (line 5207: `33 FORMA-F(5E20.2)`); LIENG-1's is F20.2
})


def _w(records: list[str], fmt_no: int, *values, formats=FORMATS_LIENG1) -> None:
    records.extend(write_record(formats[fmt_no], values))


def _char_echo(out: list[str], deck, centre, formats) -> None:
    """PINPUT's echo of the characteristic cards and the slope table and
    centre search (KEY /= 0)."""
    for j in range(0, 200, 5):
        _w(out, 30, *deck.xchl[j : j + 5], formats=formats)
    for j in range(0, 200, 5):
        _w(out, 33, *deck.ychl[j : j + 5], formats=formats)
    n = deck.n
    xc, yc = deck.xchl, deck.ychl
    slope = centre.slope
    for j in range(n - 1):
        _w(out, 1000, j + 1, xc[j], yc[j], xc[j] - xc[j + 1], yc[j] - yc[j + 1], slope[j], formats=formats)
    _w(out, 1001, n, xc[n - 1], yc[n - 1], formats=formats)
    if centre.isel > 0:
        _w(out, 1005, centre.isel, slope[centre.isel - 1], formats=formats)
        _w(out, {0: 1006, -1: 1007, 1: 1008}[centre.branch], centre.xmdl, centre.ymdl, formats=formats)


def lieng1_listing(deck, result) -> list[str]:
    """The LIENG-1 line-printer output for a deck and its result.

    Parameters
    ----------
    deck : lieng.programs.lieng1.Deck
    result : lieng.programs.lieng1.Lieng1Result

    Returns
    -------
    list of str
        The printed lines, in the order the program writes them.
    """
    from lieng.programs.lieng1 import phi_of

    out: list[str] = []
    key = deck.key
    # PINPUT
    _w(out, 41, deck.n, deck.omega, deck.ampv0, deck.xinp, deck.yinp, deck.dtheta, deck.xincr, deck.yincr)
    if key != 0:
        _char_echo(out, deck, result.centre, FORMATS_LIENG1)
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


def mlien_listing(deck, result) -> list[str]:
    """The MLIEN line-printer output for a deck and its result.

    PINPUT's header and echo (KEY /= 0), the first CHALIN's slope table and
    centre (KEY /= 0; the listing repeats them at every one of the 3000
    CHALIN calls, which the port does not, see RESTORATION.md), then the
    trial-run lines R, X, Y, T, XMDL, YMDL, L (FORMAT 1010) at
    L = 1, 9, 19, ..., 2999.
    """
    from lieng.programs.mlien import trial_run_points

    out: list[str] = []
    if deck.key != 0:
        _w(out, 41, deck.n, deck.omega, deck.ampv0, deck.xinp, deck.yinp, deck.dtheta, deck.m,
           formats=FORMATS_MLIEN)
        _char_echo(out, deck, result.centre, FORMATS_MLIEN)
    for ll in trial_run_points(result.npts):
        i = ll - 1
        _w(out, 1010, result.r[i], result.x[i], result.y[i], result.t[i], result.xmdl[i], result.ymdl[i], ll,
           formats=FORMATS_MLIEN)
    return [ln.rstrip() for ln in out]


def _row(cells: list[tuple[str, int]], width: int = 90) -> str:
    """A 90H line of the TRC table head: each label right-aligned to end at
    the column where its field of FORMAT 80 ends; '*' at columns 11 and 82."""
    line = [" "] * width
    line[10] = "*"
    line[81] = "*"
    for text, end in cells:
        line[end - len(text) : end] = list(text)
    return "".join(line)


def _text(text: str, width: int = 90) -> str:
    line = list(f"{'':10}*  {text}".ljust(width))
    line[81] = "*"
    return "".join(line)


_STARS = " " * 10 + "*" * 72
#: Column ends of FORMAT 80's fields: I6 then seven F8 (11H takes columns 1-11).
_ENDS = [17, 25, 33, 41, 49, 57, 65, 73]

#: TRC (App. 7).  The texts of the 90H head lines are the listing's; their
#: spacing is lost in the OCR and is laid out on FORMAT 80's columns
#: (RESTORATION.md R25).
FORMATS_TRC = {
    # `70 FORMAT(1H1,90H****/90H STICK-SLIP CYCLE ANALYSIS/90H****/90H DATA/90H)`: the page eject is an
    # item of its own before the first 90H record; the fifth 90H record's text is lost (blank here)
    70: "(1H1," + "/".join([_h(_STARS, 90), _h(_text("STICK-SLIP CYCLE ANALYSIS"), 90),
                            _h(_STARS, 90), _h(_text("DATA"), 90), _h("", 90)]) + ")",
    110: "(" + "/".join(_h(_text(t), 90) for t in (
        "SURFACES            STEEL ST 37.11 ON STEEL ST 37.11",
        "SURFACE ROUGHNESS   20 MICROIN CLA FOR BOTH SPECIMENS",
        "SURFACE HARDNESS    40-45 RC FOR BOTH SPECIMENS",
        "GEOMETRY            1/2 IN BALL ON FLAT DISC",
        "LUBRICANT           NONE")) + ")",
    120: "(" + "/".join([
        _h(_text("AMBIENT TEMPERATURE 21 DEG CENT."), 90),
        _h(_text("RELATIVE HUMIDITY   57 PER CENT"), 90),
        _h(_STARS, 90),
        _h(_row(list(zip(["N", "T", "X", "V", "XN", "VN", "AM", "AMT"], _ENDS))), 90),
        _h(_row(list(zip(["SEC", "MM", "MM/SEC", "MM", "MM/SEC"], _ENDS[1:6]))), 90),
    ]) + ")",
    111: "(" + _h(_STARS, 90) + ")",
    80: "(11H          *,I6,2F8.4,F8.3,F8.4,F8.3,2F8.4,9H        *)",
    # `100 FORMAT(90H.../90H****/)`: a 90H record whose text is lost (blank here), then the stars
    100: "(" + _h("", 90) + "/" + _h(_STARS, 90) + "/)",
    635: "(9F12.5)",
}


def trc_listing(result) -> list[str]:
    """The TRC line-printer output: the head (FORMATs 70, 110, 120, 111),
    the table N, T, X, V, XN, VN, AM, AMT (FORMAT 80), FORMAT 100, and the
    table XX, YY, XLNR, XNLNR, VLN, VNLN, YYN, XXN, AMTN (FORMAT 635)."""
    out: list[str] = []
    for no in (70, 110, 120, 111):
        _w(out, no, formats=FORMATS_TRC)
    r = result
    for i in range(r.nn):
        _w(out, 80, i + 1, r.t[i], r.x[i], r.v[i], r.xn[i], r.vn[i], r.am[i], r.amt[i], formats=FORMATS_TRC)
    _w(out, 100, formats=FORMATS_TRC)
    for i in range(r.nn):
        _w(out, 635, r.xx[i], r.yy[i], r.xlnr[i], r.xnlnr[i], r.vln[i], r.vnln[i], r.yyn[i], r.xxn[i], r.amtn[i],
           formats=FORMATS_TRC)
    return [ln.rstrip() for ln in out]
