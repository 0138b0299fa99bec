"""How well the baseline reproduces a record, apart from any effect: goodness-of-fit features compared with the
baseline's own replicates (:func:`.decide.misfit`), and the rig's ringing after each arrest."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from lieng.diagnose.segment import Cycles, Prepared, slip_seconds

__all__ = ["GOF", "GOF_MARGIN", "RIG", "arrest_ringing", "goodness", "mean_above_zero", "onset_ringing", "rig_mode"]


#: goodness-of-fit features of the baseline (not effects): the slip's duration
#: in half natural periods, the spread of the peaks over D, the spread of the
#: periods over their mean; a record that departs from the baseline's
#: replicates in one of them by more than GOF_MARGIN, with no candidate named,
#: is ``unexplained``
GOF = ("slip_duration", "peak_spread", "period_spread")
GOF_MARGIN = {"slip_duration": 0.25, "peak_spread": 0.10, "period_spread": 0.10, "arrest_ringing": 0.01}
#: features of the rig read like GOF but not a miss of the friction model: what rings after each arrest
#: (a second mode of the rig, :func:`arrest_ringing`), warned about where it departs from the replicates
RIG = ("arrest_ringing",)


@lru_cache(maxsize=4096)
def _quadratic_basis(n: int) -> np.ndarray:
    """An orthonormal basis of the quadratics on n equally spaced samples: x
    less its projection on it is x less its least-squares quadratic (the
    same residual as np.polyfit's, at a tenth of the cost per stick)."""
    tt = np.linspace(-1.0, 1.0, n)
    q, _ = np.linalg.qr(np.column_stack([np.ones(n), tt, tt * tt]))
    return q


def arrest_ringing(pr: Prepared, c: Cycles, fn: float, D: float) -> float:
    """What rings after each arrest (a second mode of the rig: the 1-DoF
    baseline's slider is still in stick): in each stick, the RMS of x about
    a quadratic over the first two natural periods after the trough (at
    most the stick's first half) less that over the stick's second half
    (its last tenth left out), over D; the median over the sticks (0 when
    fewer than three sticks are long enough)."""
    n2 = int(round(2.0 / (fn * pr.dt)))
    out = []
    for k in np.flatnonzero(c.next_ok):
        a, b = int(c.trough_i[k]), int(c.peak_i[k + 1])
        m = b - a
        if m < 24:
            continue
        w1 = min(n2, m // 2)
        late = (a + m // 2, a + int(0.9 * m))
        if w1 < 8 or late[1] - late[0] < 8:
            continue
        r = []
        for i0, i1 in ((a, a + w1), late):
            seg = pr.x[i0:i1]
            q = _quadratic_basis(seg.size)
            r.append(float(np.std(seg - q @ (q.T @ seg))))
        out.append(r[0] - r[1])
    return float(np.median(out)) / D if len(out) >= 3 else 0.0


#: a resonance of the rig or its sensor is modelled when the ringing after the arrests is shown in each half
#: of the sticks at this level, by the shape read on the other half (:func:`rig_mode`)
RIG_ALPHA = 1e-3
#: a resonance rings: its damping ratio at most this (Q >= 3.3, stated a priori); a heavier transient after
#: the arrest is the slider's own (creep, a compliant contact), not a mode to record x through
RIG_ZETA = 0.15
#: and it is above the slider's own frequency: at least this many fn (below, it is the slider's business)
RIG_FMIN = 2.0


def arrest_waves(x, c: Cycles, fn: float, dt: float, w: int | None = None):
    """x in the first samples of each stick (from the trough; ``w`` samples,
    by default two natural periods or half the median stick, whichever is
    less), each less its least-squares quadratic: ((sticks, w) array, w), or
    None when fewer than six sticks are twice that long."""
    ks = np.flatnonzero(c.next_ok)
    if w is None:
        ms = c.peak_i[ks + 1] - c.trough_i[ks] if ks.size else np.array([], int)
        if ms.size < 6:
            return None
        w = min(int(round(2.0 / (fn * dt))), int(np.median(ms)) // 2)
    if w < 10:
        return None
    q = _quadratic_basis(w)
    rows = []
    for k in ks:
        a, b = int(c.trough_i[k]), int(c.peak_i[k + 1])
        if b - a >= 2 * w:
            seg = x[a:a + w]
            rows.append(seg - q @ (q.T @ seg))
    return (np.asarray(rows), w) if len(rows) >= 6 else None


def _damped(w: int, dt: float, f: float, zeta: float, q=None) -> np.ndarray:
    """The two columns of a damped oscillation at ``f`` (Hz; its undamped
    frequency) of damping ratio ``zeta`` on ``w`` samples, less their
    projection on the orthonormal columns ``q`` (by default the quadratics)."""
    tau = np.arange(w) * dt
    om = 2 * math.pi * f
    wd = om * math.sqrt(max(1.0 - zeta * zeta, 1e-6))
    e = np.exp(-zeta * om * tau)
    m = np.column_stack([e * np.cos(wd * tau), e * np.sin(wd * tau)])
    q = _quadratic_basis(w) if q is None else q
    return m - q @ (q.T @ m)


def mean_above_zero(v) -> float:
    """The one-sided p-value of Student's t that the mean of ``v`` is above 0
    (1 when its spread is 0)."""
    from scipy.special import stdtr

    v = np.asarray(v, float)
    sd = float(np.std(v, ddof=1)) if v.size > 1 else 0.0
    return float(stdtr(v.size - 1, -float(np.mean(v)) / (sd / math.sqrt(v.size)))) if sd > 0 else 1.0


def _fit_mode(mean, dt: float, fn: float):
    """The damped oscillation that fits ``mean`` best (a grid in frequency,
    2 fn to 0.45 of the sampling rate, and damping, then least squares):
    (f, zeta, its fitted waveform)."""
    from scipy.optimize import least_squares

    w = mean.size
    lo, hi = RIG_FMIN * fn, 0.45 / dt
    if not hi > lo:
        return None
    best = None
    for f in np.geomspace(lo, hi, 60):
        for z in (0.02, 0.05, 0.1, 0.2, 0.4):
            B = _damped(w, dt, f, z)
            co, *_ = np.linalg.lstsq(B, mean, rcond=None)
            r = float(np.sum((mean - B @ co) ** 2))
            if best is None or r < best[0]:
                best = (r, f, z, co)
    _, f0, z0, co0 = best
    res = least_squares(lambda p: _damped(w, dt, p[0], p[1]) @ p[2:] - mean, [f0, z0, *co0],
                        bounds=([lo, 1e-3, -np.inf, -np.inf], [hi, 0.9, np.inf, np.inf]), x_scale="jac")
    f, z = float(res.x[0]), float(res.x[1])
    return f, z, _damped(w, dt, f, z) @ res.x[2:]


def rig_mode(pr: Prepared, c: Cycles, fn: float) -> dict | None:
    """A resonance of the rig or its sensor, read off the ringing after the
    arrests (the 1-DoF slider is still in stick; a sensor's mode rings after
    every arrest with the same phase): the damped oscillation that fits the
    sticks' mean early waveform (:func:`arrest_waves`), shown by cross-fitting
    (its shape read on one half of the sticks, alternate ones, and each
    other stick's projection on it t-tested against 0, one-sided, on the
    other half: a valid test whatever the grid tried), both halves at
    RIG_ALPHA; a resonance (damping ratio at most RIG_ZETA, frequency off
    the grid's ends) that dies away (to half at least within the window).
    Returns {f, zeta, p, w, wave (the mean waveform)} or None."""
    aw = arrest_waves(pr.x, c, fn, pr.dt)
    if aw is None:
        return None
    W, w = aw
    ps = []
    for fit_on, test_on in ((W[0::2], W[1::2]), (W[1::2], W[0::2])):
        m = _fit_mode(fit_on.mean(axis=0), pr.dt, fn)
        if m is None:
            return None
        nrm = float(np.linalg.norm(m[2]))
        if not nrm > 0:
            return None
        ps.append(mean_above_zero(test_on @ (m[2] / nrm)))
    if max(ps) > RIG_ALPHA:
        return None
    wave = W.mean(axis=0)
    f, z, _ = _fit_mode(wave, pr.dt, fn)
    # (a ringing dies away after the arrest, to half at least over the window: a steady line, the mains' or
    # a machine's, is no response to the arrests)
    if not (math.log(2.0) / (2 * math.pi * f * w * pr.dt) <= z <= RIG_ZETA) or \
            not (1.01 * RIG_FMIN * fn < f < 0.99 * 0.45 / pr.dt):
        return None
    return {"f": f, "zeta": z, "p": max(ps), "w": w, "wave": wave}


def onset_ringing(x, c: Cycles, dt: float, f: float, zeta: float, w: int) -> np.ndarray:
    """What rings at the resonance (``f``, ``zeta``) as each slip starts: on
    the first ``w`` samples from each peak (slips at least that long), x
    less its least-squares cubic, the least-squares amplitudes of the damped
    oscillation's two columns: (slips, 2)."""
    tt = np.linspace(-1.0, 1.0, w)
    q, _ = np.linalg.qr(np.column_stack([np.ones(w), tt, tt * tt, tt ** 3]))
    b = _damped(w, dt, f, zeta, q)
    rows = []
    for k in range(c.n):
        p0 = int(c.peak_i[k])
        if int(c.trough_i[k]) - p0 >= w:
            seg = x[p0:p0 + w]
            rows.append(np.linalg.lstsq(b, seg - q @ (q.T @ seg), rcond=None)[0])
    return np.asarray(rows).reshape(-1, 2)


def goodness(pr: Prepared, c: Cycles, fn: float, D: float) -> dict:
    """The goodness-of-fit features (see :data:`GOF`)."""
    dur = slip_seconds(pr, c)
    per = c.periods(pr.t)
    return {"slip_duration": float(dur * 2.0 * fn) if dur else 0.0,
            "peak_spread": float(np.std(pr.x[c.peak_i]) / D) if c.n > 1 else 0.0,
            "period_spread": float(np.std(per) / np.mean(per)) if per.size > 1 else 0.0,
            "arrest_ringing": arrest_ringing(pr, c, fn, D)}
