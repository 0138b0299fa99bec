"""``lieng diagnose``: what the thesis's 1-DoF model gets wrong on a measured
stick-slip record, which effect causes it, and how much an extended model gains.

The path (each step documented in ``report.md``):

1. **Cycles.**  The record (t, x[, y][, v0]) is smoothed (Savitzky-Golay) and
   cut into stick-slip cycles: slip where the velocity falls well below zero;
   the peak (x where slip starts), the trough (lowest x of the slip), the
   period and the rise time (trough to next peak) of each cycle.
2. **Baseline.**  The thesis's model: a 1-DoF slider (natural frequency
   ``fn``), a single-valued characteristic (static limit FS, kinetic level
   FK), constant load and drive.  FS is the median peak; FK is adjusted until
   the simulated trough matches.  Simulated with the compiled slider core
   (``fortran/slider.f90``).
3. **Evidence** for each effect, a statistic with a threshold (an effect
   is named when its score is >= 1, else ``none``; see below for the
   score and for several):

   * ``twin_branch``: the step of the friction between the accelerating and
     decelerating halves of the slips (the width of the loop of the
     experimental characteristic, ch. 4.1), fitted to x itself: in each
     slip x is an arc of the free oscillation about the friction level, and
     the level steps by dF where the sliding velocity peaks (linear least
     squares, no derivatives, so it holds at coarse sampling; fitting the
     frequency too was tried: it absorbs half the step); dF over the
     stick-slip amplitude, threshold 0.05, counted only when positive (the
     decelerating branch above the accelerating one, as the thesis found;
     a load that follows x gives a negative step).
   * ``load_variation``: the reverse construction gives the friction during
     slip, F = x + x''/wn**2 (the centre of curvature of the trajectory in
     the Lienard plane, TRC's XX); F is fitted by a quadratic in the
     relative velocity, a branch step and a term in the low-passed normal
     displacement y; the y term's contribution (coefficient x std of y in
     slip) over the amplitude, threshold 0.02.
   * ``static_ageing``: the peak against the log of the drive velocity during
     the stick (which sets the stick time); the change of the peak over the
     drive range, over the amplitude, threshold 0.05.  Needs a varying drive
     (a ``v0`` column); with a constant drive every stick lasts the same and
     ageing cannot be told from a higher FS.
   * ``triggering``: the strongest spectral line of y (or x) above 2 fn that
     is not a harmonic of the stick-slip; its amplitude over the stick-slip
     amplitude of x, threshold 0.02 (App. 2's ever-present triggering is
     100-500 times smaller than the stick-slip).
   * ``drive_modulation``: the stick velocity (a line fitted to x in each
     stick) relative to the given drive; its coefficient of variation over
     the sticks, threshold 0.08.

   Each statistic is computed on the record and on the baseline's simulation
   of it (with the baseline's model of y: the part of y locked to x); the
   score is their difference over the threshold, so that what the method
   itself makes of a clean 1-DoF record (smoothing, trimming) is not
   evidence.  The slip-shape statistics (twin, load) are read last: the
   other effects change the shape of a slip too and leave traces there, the
   converse is not true.  Within a group the largest score wins.
4. **Extension** with the named effect, fitted on the first 70 % of the
   record.
5. **Gain** on the last 30 %: the error is the RMS of normalised differences
   of cycle features and effect statistics between the record and the
   simulation (mean and spread of peak, trough, period, rise; the named
   effect's statistic), each displacement over the amplitude, each time
   over the mean period, the statistic over its threshold.  Plain time-domain
   RMS is not used: stick-slip phase drifts.  gain = 1 - e_extended /
   e_baseline.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import _core
from .errors import LiengInputError
from .table import read_columns

__all__ = ["EFFECTS", "THRESHOLDS", "Record", "Diagnosis", "read_record", "record_from_trc_deck", "cycles",
           "diagnose", "simulate"]

EFFECTS = ("load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
THRESHOLDS = {"twin_branch": 0.05, "load_variation": 0.02, "static_ageing": 0.05, "triggering": 0.02,
              "drive_modulation": 0.08}
#: the statistics read from the shape of the slips (see diagnose)
SLIP_SHAPE = ("twin_branch", "load_variation")
ZETA = 0.02
TRAIN = 0.7
METRIC = ("RMS of normalised differences, record vs simulation, on the last 30 % of the record: mean and std "
          "of peak, trough (/ amplitude), period, rise time (/ mean period), and the named effect's statistic "
          "(/ its threshold)")


@dataclass
class Record:
    """A measured record: time (s), x (mm), optional y (mm) and v0 (mm/s)."""

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray | None = None
    v0: np.ndarray | None = None
    source: str = "record"
    #: the constant drive (mm/s) when there is no v0 column (else its mean)
    v0_nominal: float = math.nan


def _fail(msg):
    raise LiengInputError(msg)


def read_record(path, v0: float | None = None) -> Record:
    """Read a CSV ``t,x[,y][,v0]`` (s, mm, mm, mm/s).

    The drive is the ``v0`` column or, without it, the constant ``v0``.
    Raises :class:`LiengInputError` naming the line and column of bad input.
    """
    a = read_columns(path, ("t", "x"), ("y", "v0"), "t,x[,y][,v0]: s, mm, mm, mm/s")
    t = a["t"]
    if t.size < 50:
        _fail(f"{path}: {t.size} samples: too short for stick-slip analysis")
    d = np.diff(t)
    bad = np.flatnonzero(d <= 0)
    if bad.size:
        k = bad[0] + 3
        what = "repeats" if d[bad[0]] == 0 else "goes back"
        _fail(f"{path}: line {k}, column t: time {what} ({t[bad[0] + 1]:g} after {t[bad[0]]:g}): t must increase")
    if np.max(d) > 1.5 * np.min(d) + 1e-12:
        _fail(f"{path}: column t: the samples must be evenly spaced (steps from {np.min(d):g} to {np.max(d):g} s)")
    vcol = a.get("v0")
    if vcol is None:
        if v0 is None:
            _fail(f"{path}: no column v0 and no --v0: the drive velocity is needed")
        if not (math.isfinite(v0) and v0 > 0):
            _fail(f"--v0 {v0}: the drive velocity must be a positive number (mm/s)")
        vcol_arr = None
    else:
        if np.any(vcol < 0):
            k = int(np.flatnonzero(vcol < 0)[0]) + 2
            _fail(f"{path}: line {k}, column v0: the drive velocity must not be negative (0 is a hold)")
        if not np.mean(vcol) > 0:
            _fail(f"{path}: column v0: the drive never moves (all zero): no stick-slip")
        vcol_arr = vcol
    return Record(t=t, x=a["x"], y=a.get("y"), v0=vcol_arr, source=str(path),
                  v0_nominal=float(v0) if vcol_arr is None else float(np.mean(vcol_arr)))


def record_from_trc_deck(path, v0: float | None) -> tuple[Record, float]:
    """A thesis-style TRC deck (App. 7) as a record: the calibrated readings
    T, X, XN (s, mm, mm; XN becomes y) resampled linearly onto an even grid
    at the median reading interval.  Returns the record and the natural
    frequency the deck gives (OMNH, rad/s, in Hz)."""
    from .cards import read_deck

    deck = read_deck(path, program="trc")
    t, x, xn = deck.calibrated()
    if np.any(np.diff(t) <= 0):
        _fail(f"{path}: the readings' times do not increase (NT): cannot be resampled")
    if v0 is None:
        _fail(f"{path}: a TRC deck does not give the drive velocity: --v0 is needed")
    if not (math.isfinite(v0) and v0 > 0):
        _fail(f"--v0 {v0}: the drive velocity must be a positive number (mm/s)")
    dt = float(np.median(np.diff(t)))
    tu = np.arange(t[0], t[-1] + 0.5 * dt, dt)
    tu = tu[tu <= t[-1]]
    y = np.interp(tu, t, xn) if np.any(xn != 0) else None
    rec = Record(t=tu, x=np.interp(tu, t, x), y=y, source=str(path), v0_nominal=float(v0))
    if rec.t.size < 50:
        _fail(f"{path}: {rec.t.size} samples after resampling: too short for stick-slip analysis")
    return rec, abs(deck.omnh) / (2 * math.pi)


# ------------------------------------------------------------------ signal

def _window(dt, fn) -> int:
    """The Savitzky-Golay window (samples): a quarter of the natural period."""
    return max(int(round(0.25 / fn / dt)) | 1, 7)


def _smooth(x, dt, fn, deriv=0):
    from scipy.signal import savgol_filter

    return savgol_filter(x, _window(dt, fn), 3, deriv=deriv, delta=dt)


@dataclass
class Cycles:
    """Stick-slip cycles of a trace (indices into the samples)."""

    peak_i: np.ndarray
    trough_i: np.ndarray
    slip: list
    v: np.ndarray
    a: np.ndarray
    peak: np.ndarray
    trough: np.ndarray
    period: np.ndarray
    rise: np.ndarray
    #: samples of the smoothing window that gave v and a
    win: int = 7

    @property
    def amplitude(self) -> float:
        return float(np.median(self.peak[: self.trough.size] - self.trough))


def cycles(t, x, fn, vd, min_cycles: int = 3) -> Cycles:
    """Cut a trace into stick-slip cycles (see the module docstring); fewer
    than ``min_cycles`` complete cycles is an error."""
    dt = float(t[1] - t[0])
    v = _smooth(x, dt, fn, 1)
    a = _smooth(x, dt, fn, 2)
    vmin = float(np.percentile(v, 0.5))
    thr = min(-0.5 * float(np.median(vd)), 0.25 * vmin)
    if not vmin < 0 or not np.any(v < thr):
        raise LiengInputError("no stick-slip: the velocity never falls well below zero (no slip)")
    m = v < thr
    edges = np.flatnonzero(np.diff(m.astype(int)))
    starts = [i + 1 for i in edges if not m[i]]
    ends = [i + 1 for i in edges if m[i]]
    if m[0]:
        ends = ends[1:] if ends and (not starts or ends[0] < starts[0]) else ends
    slips = []
    for s in starts:
        e = next((e for e in ends if e > s), None)
        if e is None:
            break
        slips.append((s, e))
    peak_i, trough_i, slip = [], [], []
    for k, (s, e) in enumerate(slips):
        lo = slips[k - 1][1] if k else 0
        if s - lo < 3:
            continue
        p = lo + int(np.argmax(x[lo:s + 1]))
        nxt = slips[k + 1][0] if k + 1 < len(slips) else len(x)
        q = s + int(np.argmin(x[s:min(nxt, e + (e - s) + 3)]))
        peak_i.append(p)
        trough_i.append(q)
        slip.append((p, q))
    peak_i = np.array(peak_i, int)
    trough_i = np.array(trough_i, int)
    if peak_i.size < min_cycles + 1:
        raise LiengInputError(f"fewer than {min_cycles} stick-slip cycles in the record ({max(peak_i.size - 1, 0)} found)")
    peak = x[peak_i]
    trough = x[trough_i]
    period = np.diff(t[peak_i])
    rise = t[peak_i[1:]] - t[trough_i[:-1]]
    return Cycles(peak_i, trough_i, slip, v, a, peak, trough, period, rise, _window(dt, fn))


# ------------------------------------------------------------------ evidence

def _slip_samples(c: Cycles, t, vd):
    """Samples inside slips (trimmed), with the branch: -0.5 before the
    relative speed peaks, +0.5 after."""
    idx, br = [], []
    for p, q in c.slip:
        n = q - p
        if n < 6:
            continue
        cut = max(1, n // 8)
        lo, hi = p + cut, q - cut
        if hi - lo < 4:
            continue
        seg = np.arange(lo, hi)
        vr = vd[seg] - c.v[seg]
        kmax = int(np.argmax(vr))
        idx.append(seg)
        br.append(np.where(np.arange(seg.size) <= kmax, -0.5, 0.5))
    if not idx:
        return np.array([], int), np.array([])
    return np.concatenate(idx), np.concatenate(br)


def _slip_design(c: Cycles, t, x, vd, fn):
    """The reverse construction during slip: the sample indices, the friction
    F = x + x''/wn**2 there (the trajectory's centre of curvature in the
    Lienard plane, TRC's XX), and the baseline regressors of F: 1, the
    relative velocity and its square (scaled), the branch step (-0.5/+0.5)
    and the slider velocity (scaled; it carries the damping)."""
    F = x + c.a / (2 * math.pi * fn) ** 2
    idx, br = _slip_samples(c, t, vd)
    vr = vd[idx] - c.v[idx]
    cols = [np.ones(idx.size), vr / vr.std(), (vr / vr.std()) ** 2, br, c.v[idx] / c.v[idx].std()]
    return idx, F[idx], cols


def _branch_step(c: Cycles, t, x, vd, fn) -> float:
    """The step of the friction between the accelerating and decelerating
    halves of the slips, fitted to x itself (no derivatives): in each slip
    x = F1 + A cos(wn t) + B sin(wn t) + dF (1 - cos(wn (t - t*))) H(t - t*),
    t* the peak of the sliding velocity, F1, A, B per slip, dF common, least
    squares (linear).  dF > 0: the decelerating branch lies above the
    accelerating one (the twin mechanism, ch. 4.1); a friction that follows a
    load rising with x gives dF < 0."""
    slips = []
    for p, q in c.slip:
        seg = np.arange(p + 1, q)
        if seg.size >= 6:
            ks = seg[int(np.argmax(vd[seg] - c.v[seg]))]
            slips.append((seg, t[seg] - t[p], t[ks] - t[p]))
    if not slips:
        return 0.0
    n = sum(sg.size for sg, _, _ in slips)
    rhs = np.concatenate([x[sg] for sg, _, _ in slips])

    def fit(wn):
        A = np.zeros((n, 3 * len(slips) + 1))
        r0 = 0
        for j, (sg, tt, ts) in enumerate(slips):
            rows = slice(r0, r0 + sg.size)
            A[rows, 3 * j] = 1.0
            A[rows, 3 * j + 1] = np.cos(wn * tt)
            A[rows, 3 * j + 2] = np.sin(wn * tt)
            A[rows, -1] = np.where(tt > ts, 1.0 - np.cos(wn * (tt - ts)), 0.0)
            r0 += sg.size
        coef = np.linalg.lstsq(A, rhs, rcond=None)[0]
        return float(np.sum((A @ coef - rhs) ** 2)), float(coef[-1])

    return fit(2 * math.pi * fn)[1]


def _stick_segments(c: Cycles):
    """The inner part of each stick (trough to next peak, less its first
    quarter and last eighth), as index arrays of at least 5 samples."""
    for k in range(min(c.trough_i.size, c.peak_i.size - 1)):
        lo, hi = c.trough_i[k], c.peak_i[k + 1]
        n = hi - lo
        seg = np.arange(lo + n // 4, hi - n // 8)
        if seg.size >= 5:
            yield seg


def _stick_drive(c: Cycles, vd):
    """Mean drive velocity over each stick (trough k to peak k+1)."""
    return np.array([np.mean(vd[c.trough_i[k]:c.peak_i[k + 1] + 1]) for k in range(c.trough_i.size - 1)])


def _lowpass(y, dt, fcut):
    f = np.fft.rfftfreq(y.size, dt)
    Y = np.fft.rfft(y - y.mean())
    Y[f > fcut] = 0
    return np.fft.irfft(Y, y.size) + y.mean()


def _spectral_line(sig, dt, fmin, f0=None):
    """The strongest line above fmin, and, with f0, not on a harmonic of f0
    (within one frequency bin): (frequency, amplitude, phase) from a Hann-windowed
    FFT of ``sig``."""
    s = sig - np.mean(sig)
    n = s.size
    w = np.hanning(n)
    S = np.fft.rfft(s * w)
    f = np.fft.rfftfreq(n, dt)
    amp = 2 * np.abs(S) / w.sum()
    ok = (f > fmin) & (f < 0.4 / dt)
    if f0 is not None:
        ok &= ~(np.abs(f / f0 - np.round(f / f0)) * f0 < 1.0 / (n * dt))
    if not np.any(ok):
        return 0.0, 0.0, 0.0
    k = int(np.flatnonzero(ok)[np.argmax(amp[ok])])
    return float(f[k]), float(amp[k]), float(np.angle(S[k]))


def statistics(t, x, y, vd, fn, min_cycles: int = 3) -> tuple[dict, dict]:
    """The five effect statistics (see the module docstring), and the
    cycles, amplitude, triggering line and low-passed y they came from."""
    dt = float(t[1] - t[0])
    c = cycles(t, x, fn, vd, min_cycles)
    amp = c.amplitude
    st = {}
    # triggering line: the strongest line above 2 fn in the part of y not
    # locked to the stick-slip (y less its regression on the smoothed motion),
    # or, without y, in x away from the stick-slip's harmonics
    f0 = 1.0 / float(np.mean(c.period))
    if y is not None:
        A, coef = _y_on_motion(t, x, y, fn, c)
        f_tr, a_tr, _ = _spectral_line(y - A @ coef, dt, 2.0 * fn)
    else:
        f_tr, a_tr, _ = _spectral_line(x, dt, 2.0 * fn, f0)
    st["triggering"] = a_tr / amp
    # reverse construction during slip, with the triggering line's load
    # modulation as regressors so that it cannot pass for a load variation
    idx, F, cols = _slip_design(c, t, x, vd, fn)
    cols += [_sin(t[idx], f_tr, 0.0), np.cos(2 * math.pi * f_tr * t[idx])]
    ylow, ycol = None, None
    if y is not None:
        ylow = _lowpass(y, dt, 1.5 * fn)
        yl = ylow[idx] - ylow[idx].mean()
        if yl.std() > 1e-9 * (1.0 + abs(float(ylow.mean()))):
            ycol = len(cols)
            cols.append(yl / yl.std())
    A = np.column_stack(cols)
    coef = np.linalg.lstsq(A, F, rcond=None)[0]
    st["twin_branch"] = _branch_step(c, t, x, vd, fn) / amp
    st["load_variation"] = abs(float(coef[ycol])) / amp if ycol is not None else 0.0
    # ageing: peak against log drive during the stick
    vst = _stick_drive(c, vd)
    pk = c.peak[1:1 + vst.size]
    if vst.size >= 3 and np.ptp(np.log(vst)) > 0.2:
        slope = np.polyfit(np.log(vst), pk, 1)[0]
        st["static_ageing"] = float(-slope * np.ptp(np.log(vst))) / amp
    else:
        st["static_ageing"] = 0.0
    # stick velocity
    ratios = np.array([np.polyfit(t[seg], x[seg], 1)[0] / np.mean(vd[seg]) for seg in _stick_segments(c)])
    st["drive_modulation"] = float(np.std(ratios) / abs(np.mean(ratios))) if ratios.size >= 3 else 0.0
    aux = {"cycles": c, "amp": amp, "f_tr": f_tr, "ylow": ylow}
    return st, aux


# ------------------------------------------------------------------ model

@dataclass
class Params:
    """The slider's parameters (mm, s), and the model of the recorded normal
    channel y (the part locked to the motion, plus the triggering line)."""

    fs: float
    fk: float
    zeta: float = ZETA
    ds: float = 0.0
    vs: float = 1.0
    delta: float = 0.0
    age_a: float = 0.0
    age_tau: float = 0.01
    load_k: float = 0.0            # exogenous: load = 1 + load_k * (ylow - mean), ylow measured
    load_kx: float = 0.0           # coupled: load += load_kx * (x - load_xref), x simulated
    load_xref: float = 0.0
    trig_eps: float = 0.0          # load *= 1 + eps sin(2 pi f t + ph)
    trig_f: float = 0.0
    trig_ph: float = 0.0
    trig_ax: float = 0.0           # superposed on x: ax sin(2 pi f t + phx) (MLIEN's XTRI)
    trig_phx: float = 0.0
    trig_ay: float = 0.0           # superposed on y: ay sin(2 pi f t + phy)
    trig_phy: float = 0.0
    drv_a: float = 0.0             # vd *= 1 + a sin(2 pi f t + ph)
    drv_f: float = 0.0
    drv_ph: float = 0.0
    y_c: tuple = (0.0, 0.0, 0.0)   # y = c0 + c1 x + c2 x'  (the locked part of the normal channel)

    def to_json(self) -> dict:
        d = {k: float(v) for k, v in self.__dict__.items() if k != "y_c"}
        d.update(y_c0=float(self.y_c[0]), y_cx=float(self.y_c[1]), y_cv=float(self.y_c[2]))
        return d

    def copy(self, **kw) -> "Params":
        q = Params(**self.__dict__)
        for k, v in kw.items():
            setattr(q, k, v)
        return q


def _sin(t, f, ph):
    return np.sin(2 * math.pi * f * t + ph)


def simulate(p: Params, t, vd, fn, ylow=None, x0=0.0, with_y=False):
    """Simulate the slider on the record's time grid with the compiled core.

    Returns x, v, state (1 stick, 0 slip) and, with ``with_y``, the modelled
    normal channel y (after x, v)."""
    t = np.asarray(t, float)
    dt = float(t[1] - t[0])
    vdd = np.asarray(vd, float).copy()
    if p.drv_a:
        vdd = vdd * (1.0 + p.drv_a * _sin(t, p.drv_f, p.drv_ph))
    load = np.ones_like(t)
    if p.load_k and ylow is not None:
        load = load + p.load_k * (ylow - np.mean(ylow))
    if p.trig_eps:
        load = load * (1.0 + p.trig_eps * _sin(t, p.trig_f, p.trig_ph))
    if np.any(load <= 0):
        load = np.maximum(load, 0.05)
    wn = 2 * math.pi * fn
    nsub = max(4, int(math.ceil(dt * wn / 0.05)))
    x, v, state, status = _core.core_slider(dt, nsub, vdd, load, wn, p.zeta, p.fs, p.fk, p.ds, p.vs, p.delta,
                                            p.age_a, p.age_tau, p.load_kx, p.load_xref, x0)
    if status != 0:
        raise LiengInputError(f"the slider simulation failed (status {status}): check --fn and the record's units")
    if p.trig_ax:
        x = x + p.trig_ax * _sin(t, p.trig_f, p.trig_phx)
    if not with_y:
        return x, v, state
    y = p.y_c[0] + p.y_c[1] * x + p.y_c[2] * v
    if p.trig_ay:
        y = y + p.trig_ay * _sin(t, p.trig_f, p.trig_phy)
    return x, v, state, y


# ------------------------------------------------------------------ errors

def _features(t, x, y, vd, fn, sel):
    """Cycle features and statistics on the samples sel (a slice)."""
    tt, xx = t[sel], x[sel]
    yy = None if y is None else y[sel]
    st, aux = statistics(tt, xx, yy, vd[sel], fn, min_cycles=1)
    c = aux["cycles"]
    f = {"peak_mean": np.mean(c.peak), "peak_std": np.std(c.peak), "trough_mean": np.mean(c.trough),
         "trough_std": np.std(c.trough), "period_mean": np.mean(c.period), "period_std": np.std(c.period),
         "rise_mean": np.mean(c.rise), "rise_std": np.std(c.rise)}
    return {k: float(v) for k, v in f.items()}, st, aux


def _line_fit(sig, t, f):
    """Amplitude and phase of sig at frequency f (least squares on a sine and
    cosine, with a mean and a trend), as a sin(2 pi f t + ph)."""
    A = np.column_stack([np.ones(t.size), t - t.mean(), _sin(t, f, 0.0), np.cos(2 * math.pi * f * t)])
    c = np.linalg.lstsq(A, sig, rcond=None)[0]
    return float(math.hypot(c[2], c[3])), float(math.atan2(c[3], c[2]))


def feature_error(meas, sim, amp, period, effect=None) -> float:
    """The documented error (module docstring) between the features of the
    record, ``meas``, and of a simulation, ``sim``, with the statistic of the
    named ``effect`` (the other statistics are not used: on a short held-out
    part they are noisy and would drown the features)."""
    fm, sm = meas
    fs_, ss = sim
    d = []
    for k, v in fm.items():
        scale = period if k.startswith(("period", "rise")) else amp
        d.append((v - fs_[k]) / scale)
    if effect in EFFECTS:
        d.append((sm[effect] - ss[effect]) / THRESHOLDS[effect])
    return float(np.sqrt(np.mean(np.square(d))))


# ------------------------------------------------------------------ fitting

def _fit_fk(p: Params, t, vd, fn, target_trough, ylow=None, it=6):
    """Adjust FK so that the simulated mean trough matches."""
    lo, hi = p.fk - 0.5 * (p.fs - p.fk), p.fk + 0.45 * (p.fs - p.fk)
    for _ in range(it):
        x, _, _ = simulate(p, t, vd, fn, ylow)
        try:
            c = cycles(t, x, fn, vd, min_cycles=1)
            tr = float(np.mean(c.trough))
        except LiengInputError:
            tr = p.fs
        if tr > target_trough:
            hi = p.fk
        else:
            lo = p.fk
        p.fk = 0.5 * (lo + hi)
    return p


class _Judge:
    """The record's features on a slice, and the error of a simulation there."""

    def __init__(self, t, x, y, vd, fn, ylow, sel, effect):
        self.t, self.y, self.vd, self.fn, self.ylow, self.sel, self.effect = t, y, vd, fn, ylow, sel, effect
        self.meas = _features(t, x, y, vd, fn, sel)
        self.amp = self.meas[2]["cycles"].amplitude
        self.period = self.meas[0]["period_mean"]

    def sim(self, p: Params):
        """The simulated record (x, y or None)."""
        xs, _, _, ys = simulate(p, self.t, self.vd, self.fn, self.ylow, with_y=True)
        return xs, (ys if self.y is not None else None)

    def error(self, p: Params) -> tuple[float, np.ndarray]:
        xs, ys = self.sim(p)
        try:
            sim = _features(self.t, xs, ys, self.vd, self.fn, self.sel)
        except LiengInputError:
            return float("inf"), xs
        return feature_error(self.meas[:2], sim[:2], self.amp, self.period, self.effect), xs


def _y_on_motion(t, x, y, fn, c: Cycles):
    """The regression of y on the smoothed motion, y ~ c0 + c1 x + c2 x':
    the design matrix and the coefficients."""
    A = np.column_stack([np.ones_like(x), _smooth(x, float(t[1] - t[0]), fn), c.v])
    return A, np.linalg.lstsq(A, y, rcond=None)[0]


def _y_locked(t, x, y, fn, c: Cycles):
    """Coefficients of the part of y locked to the motion: y ~ c0 + c1 x + c2 x'
    (a constant when the motion explains less than a third of y's variance:
    a channel of noise and lines must not be modelled as following x)."""
    A, coef = _y_on_motion(t, x, y, fn, c)
    r2 = 1.0 - float(np.var(y - A @ coef)) / max(float(np.var(y)), 1e-300)
    if r2 < 1.0 / 3.0:
        return (float(np.mean(y)), 0.0, 0.0)
    return tuple(float(v) for v in coef)


@dataclass
class Diagnosis:
    effect: str
    scores: dict
    statistics: dict
    baseline: Params
    extended: Params
    baseline_error: float
    extended_error: float
    gain: float
    features: dict = field(default_factory=dict)
    reason: str = ""
    warnings: list = field(default_factory=list)
    baseline_statistics: dict = field(default_factory=dict)

    def to_json(self) -> dict:
        fitted = {"baseline": self.baseline.to_json(), "extended": self.extended.to_json()}
        return {"effect": self.effect, "scores": {k: round(v, 6) for k, v in self.scores.items()},
                "baseline_error": self.baseline_error, "extended_error": self.extended_error, "gain": self.gain,
                "metric": METRIC, "fitted": fitted, "statistics": self.statistics,
                "baseline_statistics": self.baseline_statistics, "thresholds": THRESHOLDS,
                "features": self.features, "reason": self.reason, "warnings": self.warnings}


def _candidates(effect, base: Params, st, aux, t, x, y, vd, fn, ylow, tr, ctr: Cycles):
    """Extended models for ``effect``, fitted on the training samples ``tr``
    (whose cycles are ``ctr``): the estimate the evidence gives and a few
    variants of it (the training error picks one)."""
    target = float(np.mean(ctr.trough))
    amp = aux["amp"]
    out = []

    def fk(p, **kw):
        return _fit_fk(p, t[tr], vd[tr], fn, target, **kw)

    if effect == "twin_branch":
        d0 = st["twin_branch"] * amp
        for s in (0.6, 1.0, 1.5):
            out.append(fk(base.copy(delta=s * d0)))
    elif effect == "load_variation":
        yl = ylow[tr]
        idx, F, cols = _slip_design(ctr, t[tr], x[tr], vd[tr], fn)
        A = np.column_stack(cols + [yl[idx] - np.mean(yl)])
        kf = float(np.linalg.lstsq(A, F, rcond=None)[0][5]) / max(base.fk, 1e-12)   # load per mm of y
        for s in (0.7, 1.0, 1.4):
            k = s * kf
            # exogenous: the recorded normal channel drives the load
            ld = 1.0 + k * (yl[ctr.peak_i] - np.mean(yl))
            out.append(fk(base.copy(load_k=k, fs=float(np.median(ctr.peak / ld))), ylow=yl))
            # coupled: the load follows the simulated displacement through y's locked part
            kx, xref = k * base.y_c[1], float(np.mean(x[tr]))
            ld = 1.0 + kx * (ctr.peak - xref)
            if np.all(ld > 0.05):
                out.append(fk(base.copy(load_kx=kx, load_xref=xref, fs=float(np.median(ctr.peak / ld)))))
    elif effect == "static_ageing":
        vst = _stick_drive(ctr, vd[tr])
        pk = ctr.peak[1:1 + vst.size]
        ts = (pk - np.mean(ctr.trough)) / vst            # stick time: rise distance over drive
        b, a0 = np.polyfit(np.log(ts), pk, 1)            # peak = FS (1 + A ln(1 + ts/tau)) ~ FS + FS A ln(ts/tau)
        for ftau in (0.01, 0.1, 0.5):
            tau = ftau * float(np.min(ts))
            fs = max(a0 + b * math.log(tau), 0.2 * base.fs)
            for s in (0.8, 1.0, 1.25):
                out.append(fk(base.copy(age_tau=tau, fs=fs, age_a=s * b / fs)))
    elif effect == "triggering":
        f_tr = aux["f_tr"]
        tt = t[tr]
        idx, F, cols = _slip_design(ctr, tt, x[tr], vd[tr], fn)
        A = np.column_stack(cols + [_sin(tt[idx], f_tr, 0.0), np.cos(2 * math.pi * f_tr * tt[idx])])
        coef = np.linalg.lstsq(A, F, rcond=None)[0]
        eps = float(math.hypot(coef[5], coef[6])) / max(base.fk, 1e-12)
        ph = float(math.atan2(coef[6], coef[5]))
        dt = float(t[1] - t[0])
        ax_, phx = _line_fit(x[tr] - _lowpass(x[tr], dt, 2 * fn), tt, f_tr)
        kw = dict(trig_f=f_tr, trig_ax=ax_, trig_phx=phx)
        if y is not None:
            ay, phy = _line_fit(y[tr] - _lowpass(y[tr], dt, 2 * fn), tt, f_tr)
            kw.update(trig_ay=ay, trig_phy=phy)
        for s in (0.0, 0.5, 1.0):
            out.append(fk(base.copy(trig_eps=s * eps, trig_ph=ph, **kw)))
    elif effect == "drive_modulation":
        # the stick velocity is the drive: fit v/vd = c0 (1 + a sin(2 pi f t + ph)) to the smoothed velocity
        # inside the sticks, f on a grid from well below the stick-slip frequency to half the natural one
        tt = t[tr]
        idx = np.concatenate(list(_stick_segments(ctr)))
        ts, rat = tt[idx], ctr.v[idx] / vd[tr][idx]
        f_ss = 1.0 / np.mean(ctr.period)
        span = float(tt[-1] - tt[0])
        nf = int(min(4000, max(400, 4 * span * 0.5 * fn)))
        best_fit = None
        for f in np.geomspace(0.05 * f_ss, 0.5 * fn, nf):
            A = np.column_stack([np.ones(ts.size), _sin(ts, f, 0.0), np.cos(2 * math.pi * f * ts)])
            coef = np.linalg.lstsq(A, rat, rcond=None)[0]
            r = float(np.sum((A @ coef - rat) ** 2))
            if best_fit is None or r < best_fit[0]:
                best_fit = (r, f, coef)
        _, f, coef = best_fit
        for s in (0.8, 1.0, 1.2):
            out.append(fk(base.copy(drv_f=float(f), drv_a=s * float(math.hypot(coef[1], coef[2]) / coef[0]),
                                    drv_ph=float(math.atan2(coef[2], coef[1])))))
    return out


def diagnose(rec: Record, fn: float, fnv: float | None = None, keep=None) -> Diagnosis:
    """Diagnose a record (see the module docstring).

    Parameters
    ----------
    rec : Record
        From :func:`read_record`.
    fn : float
        Natural frequency of the tangential mode (Hz).
    fnv : float, optional
        Natural frequency of the normal mode (Hz); informative only.
    keep : dict, optional
        Filled with intermediate arrays for the plots.

    Returns
    -------
    Diagnosis
    """
    if not (math.isfinite(fn) and fn > 0):
        raise LiengInputError(f"--fn {fn}: the natural frequency must be a positive number (Hz)")
    t, x, y = rec.t, rec.x, rec.y
    dt = float(t[1] - t[0])
    if fn * dt > 0.2:
        raise LiengInputError(f"--fn {fn} Hz: the record has only {1 / (fn * dt):.1f} samples per natural period; "
                              f"at least 5 are needed")
    t = t - t[0]
    vd = rec.v0 if rec.v0 is not None else np.full_like(t, rec.v0_nominal)
    st, aux = statistics(t, x, y, vd, fn)
    c = aux["cycles"]
    ylow = aux["ylow"]

    # the baseline, fitted on the training part: the first 70 % of the
    # record, less if that would leave fewer than three cycles to test on
    # (two in a record of fewer than seven)
    ntr = int(TRAIN * t.size)
    if np.count_nonzero(c.peak_i > ntr) < 4:
        ntr = int(c.peak_i[-4 if c.peak_i.size >= 8 else -3]) - 1
    tr = slice(0, ntr)
    ctr = cycles(t[tr], x[tr], fn, vd[tr], min_cycles=1)
    fs = float(np.median(ctr.peak))
    base = Params(fs=fs, fk=0.5 * (float(np.median(ctr.trough)) + fs))
    if y is not None:
        base.y_c = _y_locked(t[tr], x[tr], y[tr], fn, ctr)
    base = _fit_fk(base, t[tr], vd[tr], fn, float(np.mean(ctr.trough)))

    # the evidence: what the record shows and the baseline does not
    xb, _, _, yb = simulate(base, t, vd, fn, with_y=True)
    warnings = []
    try:
        st_base, aux_b = statistics(t, xb, yb if y is not None else None, vd, fn)
        # the slip lasts about half a natural period: a mismatch says --fn is off
        slip_rec = float(np.median(t[c.trough_i] - t[c.peak_i[:c.trough_i.size]]))
        cb = aux_b["cycles"]
        slip_sim = float(np.median(t[cb.trough_i] - t[cb.peak_i[:cb.trough_i.size]]))
        if abs(slip_rec / slip_sim - 1.0) > 0.1:
            warnings.append(f"the slips last {slip_rec:.4g} s in the record but {slip_sim:.4g} s in the baseline "
                            f"with --fn {fn:g} Hz: check --fn (the slip-shape evidence needs it to a few per cent)")
    except LiengInputError:
        st_base = {k: 0.0 for k in EFFECTS}
    if 1.0 / (fn * dt) < 20:
        warnings.append(f"{1.0 / (fn * dt):.1f} samples per natural period: the load evidence needs about "
                        f"20 to resolve the slips")
    scores = {k: abs(st[k] - st_base[k]) / THRESHOLDS[k] for k in EFFECTS}
    # the twin loop has a direction (the decelerating branch above): only a positive step counts
    scores["twin_branch"] = max(st["twin_branch"] - st_base["twin_branch"], 0.0) / THRESHOLDS["twin_branch"]
    if y is None:
        scores["load_variation"] = 0.0
    best = max(scores, key=scores.get)
    firing = [k for k in EFFECTS if scores[k] >= 1.0]
    # the slip-shape statistics (twin, load) are read last: the other effects
    # change the shape of a slip too and leave traces in them, not conversely
    group = [k for k in firing if k not in SLIP_SHAPE] or firing
    if len(group) > 1:
        effect = max(group, key=scores.get)
        reason = (f"{', '.join(f'{k} (score {scores[k]:.2f})' for k in group)} all >= 1; {effect} has the "
                  f"largest score")
    elif group:
        effect = group[0]
        reason = f"{effect}: score {scores[effect]:.2f} >= 1"
    else:
        effect = "none"
        reason = (f"every score below 1 (largest: {best}, {scores[best]:.2f}): the baseline explains the record "
                  f"within its noise")
    if firing and effect != "none" and set(firing) - set(group):
        reason += f" (read before {', '.join(sorted(set(firing) - set(group)))}: slip-shape evidence comes last)"

    # the extension: candidates fitted on the training part, the best on it kept
    train = _Judge(t, x, y, vd, fn, ylow, tr, effect)
    ext = base
    if effect != "none":
        cands = _candidates(effect, base, st, aux, t, x, y, vd, fn, ylow, tr, ctr)
        errs = [train.error(p)[0] for p in cands]
        if errs and np.isfinite(min(errs)):
            ext = cands[int(np.argmin(errs))]

    # the gain on the last 30 %
    test = _Judge(t, x, y, vd, fn, ylow, slice(ntr, t.size), effect)
    e0, x_base = test.error(base)
    e1, x_ext = (e0, x_base) if effect == "none" else test.error(ext)
    gain = 0.0 if effect == "none" or not math.isfinite(e0) or e0 == 0 else 1.0 - e1 / e0
    if keep is not None:
        keep.update(t=t, x=x, y=y, vd=vd, x_base=x_base, x_ext=x_ext, cycles=c, fn=fn, ntr=ntr)
    feats = {"record": test.meas[0]}
    return Diagnosis(effect=effect, scores=scores, statistics={k: float(v) for k, v in st.items()}, baseline=base,
                     extended=ext, baseline_error=float(e0), extended_error=float(e1), gain=float(gain),
                     features=feats, reason=reason, baseline_statistics={k: float(v) for k, v in st_base.items()},
                     warnings=warnings)


# ------------------------------------------------------------------ outputs

def _amp_spectrum(sig, dt):
    s = sig - sig.mean()
    w = np.hanning(s.size)
    f = np.fft.rfftfreq(s.size, dt)
    return f[1:], (2 * np.abs(np.fft.rfft(s * w)) / w.sum())[1:] + 1e-12


def write_outputs(d: Diagnosis, keep: dict, outdir, source: str) -> None:
    """Write diagnosis.json, report.md and the plots into ``outdir``
    (a staged directory: see :func:`lieng.outputs.staged_outdir`)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .graf import finish

    out = Path(outdir)
    (out / "diagnosis.json").write_text(json.dumps(d.to_json(), indent=2) + "\n", encoding="utf-8")
    t, x = keep["t"], keep["x"]
    xb, xe = keep["x_base"], keep["x_ext"]
    fn = keep["fn"]
    cap = f"lieng diagnose {source}: effect {d.effect}, gain {d.gain:.2f} on the last 30 % (metric: feature RMS)"
    curves = [("record", x, {"color": "k", "lw": 0.8}), ("baseline (thesis 1-DoF)", xb, {"color": "C0", "lw": 0.8})]
    if d.effect != "none" and xe is not None:
        curves.append((f"extended ({d.effect})", xe, {"color": "C3", "lw": 0.8}))
    fig, ax = plt.subplots(figsize=(9, 4.8), dpi=110)
    for lab, arr, kw in curves:
        if arr is not None:
            ax.plot(t, arr, label=lab, **kw)
    ax.axvline(t[keep["ntr"]], color="0.5", ls="--", lw=0.8)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("tangential displacement x (mm)")
    ax.set_title("Measured trace against the simulations (dashed: start of the held-out 30 %)")
    finish(fig, ax, cap, out / "trace.png")
    dt = float(t[1] - t[0])
    fig, ax = plt.subplots(figsize=(8, 5.6), dpi=110)
    for lab, arr, kw in curves:
        if arr is not None:
            ax.plot(arr, _smooth(arr, dt, fn, 1) / (2 * math.pi * fn), label=lab, **kw)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("velocity / natural frequency (mm)")
    ax.set_title("Phase plane (Lienard plane)")
    finish(fig, ax, cap, out / "phase_plane.png")
    fig, ax = plt.subplots(figsize=(8, 5.6), dpi=110)
    for lab, arr, kw in curves:
        if arr is None:
            continue
        try:
            c = cycles(t, arr, fn, keep["vd"])
        except LiengInputError:
            continue
        idx, F, _ = _slip_design(c, t, arr, keep["vd"], fn)
        ax.plot(keep["vd"][idx] - c.v[idx], F, ".", ms=2, label=lab, color=kw["color"])
    ax.set_xlabel("sliding velocity v0 - x' (mm/s)")
    ax.set_ylabel("friction / stiffness F = x + x''/wn^2 (mm)")
    ax.set_title("Characteristic during slip (reverse construction): a loop means two branches")
    finish(fig, ax, cap, out / "characteristic.png")
    fig, ax = plt.subplots(figsize=(8, 5.6), dpi=110)
    for lab, arr, kw in curves:
        if arr is None:
            continue
        ax.semilogy(*_amp_spectrum(arr, dt), label=lab, **kw)
    if keep.get("y") is not None:
        ax.semilogy(*_amp_spectrum(keep["y"], dt), label="record, y", color="C2", lw=0.6)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("amplitude (mm)")
    ax.set_title("Spectrum")
    finish(fig, ax, cap, out / "spectrum.png")
    lines = [f"# lieng diagnose: {source}", "",
             f"**Effect: `{d.effect}`** ({d.reason}).", "",
             *[f"> warning: {w}" for w in d.warnings], *([""] if d.warnings else []),
             f"* baseline error e0 = {d.baseline_error:.4g}, extended error e1 = {d.extended_error:.4g}, "
             f"gain = 1 - e1/e0 = {d.gain:.3f}",
             f"* metric: {METRIC}", "",
             "## Evidence (score = statistic / threshold; >= 1 names the effect)", "",
             "| effect | statistic | threshold | score |", "|---|---|---|---|"]
    for k in EFFECTS:
        lines.append(f"| {k} | {d.statistics[k]:.4g} | {THRESHOLDS[k]} | {d.scores[k]:.3f} |")
    lines += ["", "## Fitted parameters (mm, s)", "", "| parameter | baseline | extended |", "|---|---|---|"]
    b, e = d.baseline.to_json(), d.extended.to_json()
    for k in b:
        lines.append(f"| {k} | {b[k]:.5g} | {e[k]:.5g} |")
    lines += ["", "## Record features (last 30 %)", ""]
    for k, v in d.features["record"].items():
        lines.append(f"* {k}: {v:.5g}")
    lines += ["", "Plots: trace.png, phase_plane.png, characteristic.png, spectrum.png.", ""]
    (out / "report.md").write_text("\n".join(lines), encoding="utf-8")
