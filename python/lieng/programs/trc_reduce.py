"""TRC's reduction (thesis App. 7) of a calibrated trace: velocities, BELFIT, the reverse Lienard
construction and the origin, in the compiled core.  The decks and CSV traces that feed it are
:mod:`lieng.programs.trc`, from which these names are importable too.

From the recorder readings (:func:`calibrate`), the run (:func:`trc`):

1. calibration: X = HO/500 + NH/100*SENSF/500, XN = HON/568.2 +
   NHN/100*SENSN/568.2 (mm), the interference correction (A5-3, A5-4),
   T(I) = T(I-1) + NT(I)/100/VEL (s);
2. velocities (backward differences), VLN = V/OMNH and VNLN = VN/OMNV (the
   Lienard plane's velocity coordinate, mm), AM = X/XN;
3. BELFIT: VLN smoothed as a function of X by "group fitting" ({D, n, N} =
   {2, 5, 8}, ch. 3.3.2);
4. the reverse Lienard construction (ch. 3.3.3): at each point the normals
   of the two chords meet the abscissa at XK and XL; their mean weighted by
   the chord lengths is the characteristic XX at velocity YY = VLN (and XXN
   at YYN = VNLN for the normal mode, from the unsmoothed trace);
5. the origin: the first point where VLN goes from + to - and stays - for
   four samples; EL is where the characteristic crosses the abscissa there
   (ELN likewise, - to +, for the normal mode); every x is shifted by EL
   (ELN), and AMT = XX*OMNH**2/9810 is the characteristic as a coefficient
   of friction (relative to its value at zero velocity).

A CSV ``t,x[,xn]`` (s, mm, mm) enters at step 2: its displacements are taken
as calibrated and corrected.

:func:`trc`'s errors and warnings name the trace as a whole (their field
``"trc"``); a deck or a CSV file names it again by its source.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from lieng import _core
from lieng.errors import LiengInputError, LiengInputWarning
from lieng import status as st

__all__ = ["TrcResult", "trc", "calibrate", "belfit", "lsqfit", "origin_fit", "CSV_COLUMNS", "NMIN", "G_MM",
           "TRACE"]

#: g in mm/s**2, the 9810. of loop 540 (AMT = XX*OMNH**2/9810.; g_mm in fortran/restored/trc.f90).
G_MM = 9810.0
#: BELFIT needs 2M-1 = 9 points; the issue and the origin search want 10.
NMIN = 10

#: The columns of ``trc.csv`` (values after the EL / ELN shift: x = X - EL, xn = XN - ELN).  An empty
#: cell is a value undefined at that point (a warning names the points and the cause); the normal-mode
#: columns (xn, vn, am, xxn, yyn, amtn) are empty when the trace has no normal mode.
CSV_COLUMNS = ("i", "t", "x", "v", "xn", "vn", "am", "xx", "yy", "amt", "xxn", "yyn", "amtn")


#: the field of :func:`trc`'s errors and warnings: the trace as a whole (a deck or a CSV file names its source)
TRACE = "trc"


def _err_status(status: int, where: int, what: str) -> LiengInputError:
    """The core's status as an error about ``what`` (its field)."""
    if status == st.TRC_FEW_POINTS:
        detail = f"fewer than {NMIN} points (BELFIT fits groups of 5 points)"
    elif status == st.TRC_NO_EL:
        detail = ("no velocity sign change: VLN never goes from + to - and stays - for four samples, so the origin "
                  "EL is undefined (the listing leaves it so)")
    elif status == st.TRC_DEGENERATE_FIT:
        detail = (f"points {where}-{where + 4} have fewer than 3 distinct displacements: BELFIT's quadratic "
                  f"least-squares fit over them is singular")
    elif status == st.TRC_ZERO_DT:
        detail = f"points {where - 1} and {where} have the same time: the velocity V({where}) divides by zero"
    else:
        detail = f"the TRC core stopped ({st.name(status)}) at point {where}"
    return LiengInputError(detail, fields=(what,))


def calibrate(nt, nh, nhn, *, ho, hon, vel, sensf, sensn, an1=0.0, an2=0.0):
    """Readings to time and corrected displacements (the listing's loops 40-50).

    Parameters
    ----------
    nt, nh, nhn : array_like of int
        Paper distance from the previous point and the horizontal and normal
        trace readings, in hundredths of a recorder millimetre.
    ho, hon : float
        Reference levels of the two bridges (microstrain).
    vel : float
        Paper speed (mm/s), not zero.
    sensf, sensn : float
        Sensitivities of the friction and normal traces.
    an1, an2 : float
        Cross-interference as fractions: AN1 of the friction on the normal
        reading, AN2 of the normal on the friction reading (App. 5, A5-3/A5-4).

    Returns
    -------
    t, x, xn : ndarray
        Time (s) from T(1) = 0, and the two displacements (mm).
    """
    nt = np.ascontiguousarray(nt, dtype=np.int32)
    nh = np.ascontiguousarray(nh, dtype=np.int32)
    nhn = np.ascontiguousarray(nhn, dtype=np.int32)
    if not (nt.shape == nh.shape == nhn.shape and nt.ndim == 1 and nt.size >= 1):
        raise LiengInputError("nt, nh, nhn must be 1-D arrays of the same length")
    if vel == 0 or an1 * an2 == 1:
        raise LiengInputError("vel must not be 0 and an1*an2 must not be 1")
    return _core.core_trc_calibrate(nt, nh, nhn, ho, hon, vel, sensf, sensn, an1, an2)


@dataclass
class TrcResult:
    """What TRC computes, point by point (1-based point i = index + 1).

    Attributes
    ----------
    t : ndarray
        Time (s).
    x, xn : ndarray
        Horizontal and normal displacement (mm), before the shift.
    v, vn : ndarray
        Velocities (mm/s), backward differences; v[0] = vn[0] = 0.
    vln, vnln : ndarray
        Lienard-plane velocities V/OMNH (smoothed by BELFIT) and VN/OMNV (mm).
    am : ndarray
        Apparent coefficient of friction X/XN (am[0] = 0 as in the listing).
    xx, yy : ndarray
        The horizontal characteristic: XX (mm, shifted by EL) at velocity
        YY = VLN.  Points 1 and NN are not constructed (the listing's 0 - EL).
    amt : ndarray
        XX*OMNH**2/9810: the characteristic as a coefficient of friction
        relative to its value at zero velocity.
    xxn, yyn, amtn : ndarray
        The same for the normal mode (NaN when the trace has no normal mode).
    xlnr, xnlnr : ndarray
        X - EL and XN - ELN: the trajectories in the shifted Lienard plane.
    el, eln : float
        The origins used for the shift (ELN is NaN when the normal velocity
        has no - to + sign change).
    origin : {"listing", "fit"}
        How EL and ELN were found (see :func:`trc`).
    el_listing, eln_listing : float
        The listing's EL and ELN (equal to ``el``, ``eln`` for
        ``origin="listing"``).
    omnh, omnv : float
        Natural frequencies (rad/s).
    """

    t: np.ndarray
    x: np.ndarray
    xn: np.ndarray
    v: np.ndarray
    vn: np.ndarray
    vln: np.ndarray
    vnln: np.ndarray
    am: np.ndarray
    xx: np.ndarray
    yy: np.ndarray
    amt: np.ndarray
    xxn: np.ndarray
    yyn: np.ndarray
    amtn: np.ndarray
    xlnr: np.ndarray
    xnlnr: np.ndarray
    el: float
    eln: float
    omnh: float
    omnv: float
    has_normal: bool = True
    readings: tuple | None = None
    origin: str = "listing"
    el_listing: float = math.nan
    eln_listing: float = math.nan

    @property
    def nn(self) -> int:
        return self.t.size

    def columns(self) -> dict:
        """The ``trc.csv`` columns, in :data:`CSV_COLUMNS` order, values
        after the EL / ELN shift: ``x`` is XLNR = X - EL and ``xn`` is
        XNLNR = XN - ELN (the listing's table prints X and XN unshifted)."""
        cols = {"i": np.arange(1, self.nn + 1)}
        for name in CSV_COLUMNS[1:]:
            cols[name] = getattr(self, {"x": "xlnr", "xn": "xnlnr"}.get(name, name))
        return cols


def _trace_error(detail: str) -> LiengInputError:
    return LiengInputError(detail, fields=(TRACE,))


def _check_trace(t, x, xn):
    for name, a in (("t", t), ("x", x), ("xn", xn)):
        if a is None:
            continue
        if a.ndim != 1:
            raise _trace_error(f"{name} must be one-dimensional")
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise _trace_error(f"column {name}, point {bad[0] + 1}: {a[bad[0]]} is not a finite number")
    if x.size != t.size or (xn is not None and xn.size != t.size):
        raise _trace_error("t, x and xn must have the same length")
    if t.size < NMIN:
        raise _trace_error(f"{t.size} points: TRC needs at least {NMIN} (BELFIT fits groups of 5)")
    dt = np.diff(t)
    bad = np.flatnonzero(dt <= 0)
    if bad.size:
        k = bad[0] + 2
        what = "the same time as" if dt[bad[0]] == 0 else "an earlier time than"
        raise _trace_error(f"column t, point {k}: t = {t[k - 1]:g} is {what} point {k - 1}: times must increase")


def origin_fit(xx_raw, yy, vel, i, lo=0.1, hi=0.4, half=12):
    """A modern estimate of the origin (EL or ELN), beside the listing's.

    The listing interpolates the characteristic linearly between the two
    constructed points on either side of the velocity sign change.  Those
    are the worst-conditioned points of the reverse construction (the
    trajectory crosses the abscissa at right angles, and BELFIT fits the
    velocity as a function of a displacement that turns there), so its EL
    can be off by the size of the characteristic.  Here a straight line is
    fitted by least squares to the constructed points within ``half``
    samples of the same sign change whose velocity lies between ``lo`` and
    ``hi`` times the largest |velocity| of the trace, and evaluated at zero
    velocity.

    Parameters
    ----------
    xx_raw, yy : ndarray
        The unshifted characteristic (XX before loop 540) and its velocity.
    vel : ndarray
        The velocity whose sign change marks the origin (VLN or VNLN).
    i : int
        0-based index of the sign change, as the listing's loop 52 (EL) or
        520 (ELN) finds it in the compiled core.

    Returns
    -------
    float
        The origin, or NaN when there are fewer than two usable points on
        each side.
    """
    n = vel.size
    s = float(np.max(np.abs(vel)))
    j = np.arange(max(1, i - half), min(n - 1, i + half + 1))
    a = np.abs(yy[j])
    j = j[(a >= lo * s) & (a <= hi * s) & np.isfinite(xx_raw[j])]
    if np.count_nonzero(yy[j] > 0) < 2 or np.count_nonzero(yy[j] < 0) < 2:
        return math.nan
    coef = np.linalg.lstsq(np.c_[np.ones(j.size), yy[j]], xx_raw[j], rcond=None)[0]
    return float(coef[0])


def trc(t, x, xn=None, *, omnh, omnv=None, origin: str = "listing") -> TrcResult:
    """The TRC reduction of a calibrated trace.

    Parameters
    ----------
    t : array_like
        Time (s), strictly increasing; at least 10 points.
    x : array_like
        Horizontal (friction) displacement of the dynamometer (mm).
    xn : array_like, optional
        Normal displacement (mm).  Without it the normal-mode results are NaN.
    omnh : float
        Natural frequency of the horizontal mode (rad/s).
    omnv : float, optional
        Natural frequency of the normal mode (rad/s); required with ``xn``.
    origin : {"listing", "fit"}, optional
        "listing" (default): EL and ELN as the 1971 program finds them, by
        linear interpolation between the two constructed points either side
        of the velocity sign change.  "fit": a modern, better-conditioned
        estimate (:func:`origin_fit`); the listing's values stay in
        ``el_listing`` and ``eln_listing``.

    Returns
    -------
    TrcResult

    Raises
    ------
    LiengInputError
        Too few points, times not increasing, a non-finite value, a zero
        frequency, no + to - velocity sign change (EL undefined), or a
        smoothing group with fewer than 3 distinct displacements.  Its
        ``fields`` are ``("trc",)``: the trace as a whole.

    Warns
    -----
    LiengInputWarning
        Points where a value is undefined (left NaN), an undefined ELN.
    """
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    has_normal = xn is not None
    xn_arr = np.ascontiguousarray(xn, dtype=float) if has_normal else None
    _check_trace(t, x, xn_arr)
    if not (math.isfinite(omnh) and omnh != 0):
        raise _trace_error(f"OMNH = {omnh}: the natural frequency must be a finite non-zero number")
    if has_normal:
        if omnv is None or not (math.isfinite(omnv) and omnv != 0):
            raise _trace_error(f"OMNV = {omnv}: the normal mode needs a finite non-zero natural frequency")
    else:
        xn_arr = np.ones_like(x)
        omnv = 1.0
    if origin not in ("listing", "fit"):
        raise _trace_error(f"origin must be 'listing' or 'fit', not {origin!r}")
    with np.errstate(all="ignore"):
        (xs, v, vn, vln, vnln, am, xx, yy, xxn, yyn, xlnr, xnlnr, amt, amtn, el, eln, has_eln, iel, ieln,
         status, where, xx0, xxn0) = _core.core_trc_reduce(t, x, xn_arr, float(omnh), float(omnv))
    if status != st.OK:
        raise _err_status(int(status), int(where), TRACE)
    el_listing, eln_listing = float(el), float(eln) if has_eln else math.nan
    eln_undefined = False
    if origin == "listing" and not math.isfinite(el_listing):
        raise _trace_error(f"EL is undefined: the reverse construction at points {int(iel)}-{int(iel) + 1}, where "
                           f"the velocity changes sign, divides by zero (neighbouring points with the same "
                           f"displacement, as in a quantised trace); --origin fit estimates EL from the points "
                           f"around them")
    with np.errstate(all="ignore"):
        if origin == "fit":
            el_new = origin_fit(xx0, yy, vln, int(iel) - 1)
            if not math.isfinite(el_new):
                raise _trace_error("origin 'fit': fewer than two constructed points on each side of the velocity "
                                   "sign change with 0.1-0.4 of the largest |VLN|")
            el = el_new
            xx = xx0 - el
            xlnr = xs - el
            amt = _as_mu(xx, omnh)
            if has_normal and has_eln:
                eln_new = origin_fit(xxn0, yyn, vnln, int(ieln) - 1)
                if math.isfinite(eln_new):
                    eln = eln_new
                    xxn = xxn0 - eln
                    xnlnr = xn_arr - eln
                    amtn = _as_mu(xxn, omnv)
        if has_normal and has_eln and not math.isfinite(float(eln)):
            warnings.warn(LiengInputWarning(f"ELN is undefined: the reverse construction at points {int(ieln)}-"
                                            f"{int(ieln) + 1}, where the normal velocity changes sign, divides by "
                                            f"zero; the normal-mode characteristic is not shifted", fields=(TRACE,)),
                          stacklevel=2)
            has_eln, eln, eln_undefined = 0, math.nan, True
            xxn, xnlnr = xxn0.copy(), xn_arr.copy()
            amtn = _as_mu(xxn, omnv)
    if not has_normal:
        nan = np.full_like(x, np.nan)
        xn_out, vn, vnln, am, xxn, yyn, amtn, xnlnr = (nan.copy() for _ in range(8))
        eln = math.nan
    else:
        xn_out = xn_arr
        if not has_eln:
            if not eln_undefined:           # (an undefined ELN was said above)
                warnings.warn(LiengInputWarning("the normal velocity has no - to + sign change: ELN is undefined, "
                                                "the normal-mode characteristic is not shifted", fields=(TRACE,)),
                              stacklevel=2)
            eln = math.nan
    cols = {"x": xlnr, "v": v, "xx": xx, "yy": yy, "amt": amt}
    if has_normal:
        cols.update({"xn": xnlnr, "vn": vn, "am": am, "xxn": xxn, "yyn": yyn, "amtn": amtn})
    _flag_missing(cols)
    return TrcResult(t=t, x=xs, xn=xn_out, v=v, vn=vn, vln=vln, vnln=vnln, am=am, xx=xx, yy=yy, amt=amt,
                     xxn=xxn, yyn=yyn, amtn=amtn, xlnr=xlnr, xnlnr=xnlnr, el=float(el), eln=float(eln),
                     omnh=float(omnh), omnv=float(omnv) if has_normal else math.nan, has_normal=has_normal,
                     origin=origin, el_listing=el_listing, eln_listing=eln_listing if has_normal else math.nan)


def _as_mu(xx, om):
    """XX*OM**2/9810 (loop 540's AMT), in float64: an overflow is inf, flagged later, never an exception."""
    with np.errstate(all="ignore"):
        return xx * (np.float64(om) ** 2 / G_MM)


#: why a point's value can be undefined, per column (the messages of :func:`_flag_missing`)
_MISSING_WHY = {
    "xx": "the reverse construction divides by zero (neighbouring points with the same displacement)",
    "xxn": "the reverse construction divides by zero (neighbouring points with the same normal displacement)",
    "am": "AM = X/XN divides by zero (XN = 0)",
}


def _flag_missing(cols: dict) -> None:
    """Set every non-finite value of the per-point columns to NaN (written as
    an empty cell in trc.csv, ``UNDEF`` in the listing) and say so, once per
    column, with the first points and the cause."""
    for name, a in cols.items():
        bad = ~np.isfinite(a)
        if not bad.any():
            continue
        a[bad] = np.nan
        pts = np.flatnonzero(bad) + 1
        shown = ", ".join(str(int(k)) for k in pts[:5]) + (", ..." if pts.size > 5 else "")
        base = {"amt": "xx", "amtn": "xxn"}.get(name)
        if base in cols and np.isnan(cols[base][bad]).all():
            why = f"{base.upper()} is undefined there"
        else:
            why = _MISSING_WHY.get(name, "the arithmetic overflows")
        warnings.warn(LiengInputWarning(f"{name.upper()} is undefined at {pts.size} point(s) ({shown}): {why}; left "
                                        f"empty in trc.csv", fields=(TRACE,)), stacklevel=3)


def belfit(x, y):
    """BELFIT's group-fitting smoothing of ``y`` as a function of ``x``.

    A quadratic in ``x`` is fitted by least squares to each run of 5
    consecutive points; each point's value is the mean of its fitted values
    over the runs that hold it; 8 passes (ch. 3.3.2, {D, n, N} = {2, 5, 8}).

    Returns
    -------
    ndarray
        The smoothed ``y`` (``x`` is not changed).
    """
    x = np.ascontiguousarray(x, dtype=float)
    y = np.ascontiguousarray(y, dtype=float)
    if x.shape != y.shape or x.ndim != 1:
        raise LiengInputError("belfit: x and y must be 1-D arrays of the same length")
    if x.size < 10:
        raise LiengInputError(f"belfit: {x.size} points: BELFIT needs at least 10 (two runs of 5; at 9 the "
                              f"listing averages the last points over one run too many)")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise LiengInputError("belfit: x and y must be finite")
    ys, status, where = _core.core_belfit(x, y)
    if status != st.OK:
        raise _err_status(int(status), int(where), "belfit")
    return ys


def lsqfit(x, y, deg: int = 2):
    """LSQFIT / POLYNL / POLFIT: least-squares polynomial by orthogonal
    polynomials.  Returns the coefficients of x**0 .. x**deg."""
    x = np.ascontiguousarray(x, dtype=float)
    y = np.ascontiguousarray(y, dtype=float)
    if x.shape != y.shape or x.ndim != 1 or not 0 <= deg < x.size or len(set(x.tolist())) <= deg:
        raise LiengInputError("lsqfit: need 1-D x, y of equal length with more than deg distinct x values")
    return _core.core_lsqfit(int(deg), x, y)
