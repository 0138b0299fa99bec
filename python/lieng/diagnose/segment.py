"""Stage 2 of ``lieng diagnose``: strokes, stick-slip cycles and the natural
frequency.

* **Strokes.**  A drive that reverses (a reciprocating rig) is cut where its
  sign changes; the dwells between strokes of opposite direction are left
  out (holds between strokes of one direction are kept: they are part of
  the stick).  Each stroke is turned to the forward direction (x and the
  drive times its sign), so that every stroke is a forward stick-slip trace.
  A record that gives only the drive's speed while its force changes side
  (a reciprocating rig without its stage's position) has its strokes read
  from the force (:func:`drive_from_force`).
* **Orientation.**  Labs write the friction force with either sign; x is
  turned so that it rises at the drive velocity while the slider sticks.
* **Cycles.**  Alternating extrema of the lightly smoothed x with a
  hysteresis of a quarter of the typical swing (no natural frequency
  needed): a drop is a slip when it is faster than the rise before it.  A
  slip ends at its arrest (:func:`arrest`: the first local minimum most of
  the way down), not at the lowest wiggle of a hold that follows it.  A
  record whose level wanders by more than its slips drop (a load along the
  track, one large slip among many small ones) shows fewer than four slips
  at that hysteresis; its own reading halves it until it shows them.
* **Natural frequency.**  From x inside the slips: between the peak and
  the trough the slider swings a half natural period about the friction
  level (exactly, for any level, also one that steps where the sliding
  speed peaks), so each slip is fitted by arcs of one frequency; the
  frequency that fits all slips best, with a jackknife over slips for its
  uncertainty.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple
from dataclasses import dataclass, field

import numpy as np

from lieng.errors import LiengInputError
from lieng.diagnose.read import Record, cumulative_trapezoid, noise_level, quantum

__all__ = ["Stroke", "Prepared", "Cycles", "prepare", "find_cycles", "estimate_fn", "smooth"]


@dataclass
class Stroke:
    """A part of the record with one drive direction: samples [i0, i1) of the
    original record, the direction (+1/-1), and where it starts in the
    prepared (concatenated) arrays."""

    i0: int
    i1: int
    sign: int
    j0: int = 0

    @property
    def n(self) -> int:
        return self.i1 - self.i0


@dataclass
class Cycles:
    """Stick-slip cycles of a prepared record (indices into its arrays).

    ``peak_i[k]`` is the peak before slip k, ``trough_i[k]`` its trough;
    cycle k runs from peak k to peak k+1 within one stroke (``next_ok[k]``)."""

    peak_i: np.ndarray
    trough_i: np.ndarray
    stroke: np.ndarray
    next_ok: np.ndarray
    v: np.ndarray
    a: np.ndarray
    win: int
    #: the widest window (samples) a noisy stroke's slips were found through (:func:`_light`), 0 where no
    #: stroke was noisy enough to widen the light one
    light: int = 0

    @property
    def n(self) -> int:
        return int(self.peak_i.size)

    def drops(self, x) -> np.ndarray:
        return x[self.peak_i] - x[self.trough_i]

    def amplitude(self, x) -> float:
        return float(np.median(self.drops(x))) if self.n else 0.0

    def levels(self, x) -> np.ndarray:
        """Each cycle's level: the mean of its peak and trough in ``x``."""
        return 0.5 * (x[self.peak_i] + x[self.trough_i])

    def periods(self, t) -> np.ndarray:
        k = np.flatnonzero(self.next_ok)
        return t[self.peak_i[k + 1]] - t[self.peak_i[k]]

    def rises(self, t) -> np.ndarray:
        k = np.flatnonzero(self.next_ok)
        return t[self.peak_i[k + 1]] - t[self.trough_i[k]]


@dataclass
class Prepared:
    """The record turned forward stroke by stroke, and concatenated."""

    t: np.ndarray
    x: np.ndarray
    vd: np.ndarray
    y: np.ndarray | None
    strokes: list
    dt: float
    flipped: bool
    notes: list = field(default_factory=list)
    #: the drive's position along the track (mm, the record's own direction)
    pos: np.ndarray | None = None
    #: the step x is quantised to (mm; :func:`.read.quantum`), 0 when it is not
    quantum: float = 0.0
    #: a recorded reciprocating drive made steady (:func:`steady_drive`), or None
    vd_steady: np.ndarray | None = None
    #: the samples of the strokes whose steady course is read from strokes like them (:func:`steady_drive`)
    steady_read: np.ndarray | None = None
    #: the mains hum lines removed from the record (Hz; :func:`.read.condition`): a line read there is the hum's
    hum_hz: tuple = ()

    def stroke_slices(self):
        return [slice(s.j0, s.j0 + s.n) for s in self.strokes]


def crop(p: Prepared, a: int, b: int) -> Prepared:
    """The prepared record's samples [a, b) (the strokes cut there)."""
    a, b = max(int(a), 0), min(int(b), p.t.size)
    if a == 0 and b == p.t.size:
        return p
    strokes = []
    for s in p.strokes:
        lo, hi = max(a, s.j0), min(b, s.j0 + s.n)
        if hi > lo:
            i0 = s.i0 + (lo - s.j0)
            strokes.append(Stroke(i0=i0, i1=i0 + (hi - lo), sign=s.sign, j0=lo - a))
    return Prepared(t=p.t[a:b], x=p.x[a:b], vd=p.vd[a:b], y=None if p.y is None else p.y[a:b], strokes=strokes,
                    dt=p.dt, flipped=p.flipped, notes=[], pos=None if p.pos is None else p.pos[a:b],
                    quantum=p.quantum, vd_steady=None if p.vd_steady is None else p.vd_steady[a:b],
                    steady_read=None if p.steady_read is None else p.steady_read[a:b], hum_hz=p.hum_hz)


def head(p: Prepared, nmax: int) -> Prepared:
    """The prepared record's first ``nmax`` samples (whole strokes, the last
    one cut): a part long enough for a global estimate at a fixed cost."""
    return p if p.t.size <= nmax else crop(p, 0, nmax)


#: a record that slides steadily before or after its stick-slip, over more than
#: this share of it, is analysed where it stick-slips
STEADY_SHARE = 0.2
#: ... and over at least this many of its stick-slip periods
STEADY_PERIODS = 10
#: ... with x within this share of the drop about its level (its standard deviation)
STEADY_SPREAD = 0.1
#: the fewest cycles of a run of stick-slip between steady stretches
STEADY_RUN = 3


def stick_slip_span(p: Prepared, c: Cycles):
    """Where the record stick-slips when it also slides steadily (the drive
    changed to a level where it does not stick-slip, a lubricant came in):
    (a, b, what was left out, in words) with a margin of two periods, or
    None when the cycles span it.  The record's runs of cycles are those no
    further apart than STEADY_PERIODS periods; the stretches before, between
    and after them that are steady (the drive moves, above a twentieth of
    its fast level, and x holds its level within STEADY_SPREAD of the drop)
    and span STEADY_PERIODS periods at least are the record's steady
    sliding.  When they span STEADY_SHARE of the record, the record is
    analysed on its longest run of cycles: a baseline started in stick
    stick-slips through a steady stretch (a stepped drive whose one level
    slides steadily: the record on the other of two attractors), which no
    model of the cycles can be judged on.  The cycles of the other runs are
    then left out too, and said."""
    if c.n < 4:
        return None
    per = c.periods(p.t)
    P = float(np.median(per)) if per.size else float(np.median(p.t[c.trough_i] - p.t[c.peak_i])) * 4
    m = int(round(2 * P / p.dt))
    # the runs of cycles no further apart than STEADY_PERIODS periods of moving drive (the samples: dwells are
    # cut out of the prepared record); a lone drop outside them (a start-up) is no stick-slip
    cut = np.flatnonzero(np.diff(c.peak_i) * p.dt > STEADY_PERIODS * P)
    runs = np.split(np.arange(c.n), cut + 1)
    run = max(runs, key=len)
    # (a drop or two on their own within a steady stretch is no run: the stretch is judged with them in it)
    runs = [r for r in runs if r.size >= STEADY_RUN] or [run]
    a, b = max(int(c.peak_i[run[0]]) - m, 0), min(int(c.trough_i[run[-1]]) + m + 1, p.t.size)
    n = p.t.size
    D = c.amplitude(p.x)
    vmove = 0.05 * float(np.percentile(np.abs(p.vd), 90))
    # the stretches without cycles: before the first run, between runs (less two periods each side), after
    # the last
    gaps = [(0, max(int(c.peak_i[runs[0][0]]) - m, 0))]
    gaps += [(int(c.trough_i[r0[-1]]) + m + 1, int(c.peak_i[r1[0]]) - m) for r0, r1 in zip(runs[:-1], runs[1:])]
    gaps.append((min(int(c.trough_i[runs[-1][-1]]) + m + 1, n), n))
    # steady: the drive moves and x holds its level (within STEADY_SPREAD of the drop: no stick-slip the
    # cycle finder missed, no hold)
    # (a stretch between two runs is over STEADY_PERIODS periods from drop to drop: less its margins, 4 fewer)
    parts = [(i, j) for i, j in gaps if j - i > 1
             and (j - i) * p.dt >= (STEADY_PERIODS - (4 if 0 < i and j < n else 0)) * P
             and np.median(np.abs(p.vd[i:j])) > vmove and np.std(p.x[i:j]) < STEADY_SPREAD * D]
    if not parts or sum(j - i for i, j in parts) < STEADY_SHARE * n:
        return None
    inner = len(runs) > 1 and any(0 < i and j < n for i, j in parts)
    if inner:
        # from the run's first arrest (the slider stuck: the baseline's own start) to a quarter period past
        # its last: no stretch of the steady sliding at its ends, where the baseline started in stick
        # stick-slips
        a, b = int(c.trough_i[run[0]]), min(int(c.trough_i[run[-1]]) + int(round(0.25 * P / p.dt)) + 1, n)
    else:
        # steady only before or after the stick-slip: the run is the record's stick-slip, kept whole
        a = a if any(i == 0 for i, _ in parts) else 0
        b = b if any(j == n for _, j in parts) else n
    said = "; ".join(f"{p.t[i]:.4g} to {p.t[j - 1]:.4g} s (x at {np.median(p.x[i:j]):.4g} +- "
                     f"{np.std(p.x[i:j]):.2g} mm, drive {np.median(np.abs(p.vd[i:j])):.4g} mm/s)"
                     for i, j in parts if j <= a or i >= b)
    others = int(np.count_nonzero((c.peak_i < a) | (c.peak_i >= b)))
    if inner and others:
        said += f"; {others} cycle{'s' if others > 1 else ''} outside its longest stick-slip part left out"
    return a, b, said


def smooth(x, dt, fn, deriv=0, win=None):
    """Savitzky-Golay (cubic) over a quarter natural period (or ``win``
    samples), derivative ``deriv``; short traces are returned unfiltered."""
    from scipy.signal import savgol_filter

    w = win if win is not None else max(int(round(0.25 / fn / dt)) | 1, 7)
    w = int(w) | 1
    if w >= x.size:
        w = (x.size - 2) | 1
    if w < 5:
        return np.gradient(x, dt) if deriv == 1 else (x if deriv == 0 else np.gradient(np.gradient(x, dt), dt))
    if w > FFT_WINDOW:
        return _savgol_fft(x, w, 3, deriv, dt)
    return savgol_filter(x, w, 3 if w > 5 else 2, deriv=deriv, delta=dt)


#: windows longer than this (samples) are convolved by FFT (finely sampled
#: records: a quarter period of a 12 Hz slider at 14 kHz is 300 samples)
FFT_WINDOW = 64


def _savgol_fft(x, w: int, order: int, deriv: int, dt: float):
    """scipy's ``savgol_filter(mode="interp")`` at a cost that does not grow
    with the window: the interior by overlap-add FFT convolution, the first
    and last w // 2 samples from the polynomial fitted to the first and last
    w samples."""
    from scipy.signal import oaconvolve, savgol_coeffs

    y = oaconvolve(x, savgol_coeffs(w, order, deriv=deriv, delta=dt, use="conv"), mode="same")
    h = w // 2
    tt = np.arange(w, dtype=float)
    for sl, out in ((slice(0, w), slice(0, h)), (slice(x.size - w, x.size), slice(x.size - h, x.size))):
        co = np.polyder(np.polyfit(tt, x[sl], order), deriv)
        ev = tt[:h] if out.start == 0 else tt[w - h:]
        y[out] = np.polyval(co, ev) / dt ** deriv
    return y


@functools.lru_cache(maxsize=64)
def savgol3_kernels(w: int, dt: float):
    """The cubic Savitzky-Golay kernels of window ``w`` (value, first and
    second derivative): the interior's (for np.correlate) and, for the first
    and last w // 2 samples, the rows that evaluate the cubic fitted to the
    first and last w samples there (scipy's ``mode="interp"``)."""
    from scipy.signal import savgol_coeffs

    h = w // 2
    mid = [savgol_coeffs(w, 3, deriv=d, delta=dt, use="dot") for d in range(3)]
    head = [np.array([savgol_coeffs(w, 3, deriv=d, delta=dt, pos=j, use="dot") for j in range(h)]) for d in range(3)]
    tail = [np.array([savgol_coeffs(w, 3, deriv=d, delta=dt, pos=j, use="dot") for j in range(w - h, w)])
            for d in range(3)]
    return mid, head, tail


def savgol3(x, w: int, dt: float):
    """``scipy.signal.savgol_filter(x, w, 3, deriv=d, delta=dt,
    mode="interp")`` for d = 0, 1, 2 at once (the same arithmetic with the
    kernels computed once per window: a slip's reverse construction,
    thousands of times per record).  ``x`` has at least ``w`` samples."""
    mid, head, tail = savgol3_kernels(int(w), float(dt))
    h = w // 2
    out = []
    for d in range(3):
        y = np.empty(x.size)
        y[h:x.size - h] = np.correlate(x, mid[d], mode="valid")
        y[:h] = head[d] @ x[:w]
        y[x.size - h:] = tail[d] @ x[x.size - w:]
        out.append(y)
    return out


def _runs(mask):
    """Start and end (exclusive) of the True runs of a boolean array."""
    d = np.diff(np.r_[0, mask.astype(np.int8), 0])
    return np.flatnonzero(d == 1), np.flatnonzero(d == -1)


def _sign_runs(sgn):
    """Start and end (exclusive) of the runs of one nonzero sign (a drive
    that turns from one sample to the next, with no sample at rest between,
    ends a run there)."""
    s0, s1 = _runs(sgn != 0)
    starts, ends = [], []
    for i0, i1 in zip(s0, s1):
        cut = i0 + 1 + np.flatnonzero(np.diff(sgn[i0:i1]))
        starts.extend([i0, *cut])
        ends.extend([*cut, i1])
    return np.array(starts, int), np.array(ends, int)


def strokes(vd, min_samples: int = 20) -> list:
    """Strokes of one drive direction (see the module docstring)."""
    a = np.abs(vd)
    moving = a > 0.05 * float(np.percentile(a[a > 0], 90)) if np.any(a > 0) else a > 0
    sgn = np.where(moving, np.sign(vd), 0).astype(int)
    # a stretch below that is a dwell only when it stands still: one that moves one way throughout, clear of
    # its own scatter (a slow drive level beside a fast one, 0.5 and 20 mm/s), is a stroke of its own
    for i0, i1 in zip(*_runs(sgn == 0)):
        v = np.asarray(vd[i0:i1], float)
        if v.size < min_samples:
            continue
        d = float(np.sign(np.median(v)))
        if d and np.mean(np.sign(v) == d) >= 0.95 and abs(float(np.mean(v))) > 3.0 * float(np.std(v)):
            sgn[i0:i1] = int(d)
    # a run that travels less than STROKE_SHORTEST of the longest run's travel is a dwell's jitter (an
    # encoder's count back and forth while a servo holds, a drive settling after a stop), not a stroke: a
    # reversal brings the drive back by a travel of the strokes' order
    s0, s1 = _sign_runs(sgn)
    travel = np.array([abs(float(np.sum(vd[i0:i1]))) for i0, i1 in zip(s0, s1)])
    if travel.size:
        for i0, i1, d in zip(s0, s1, travel):
            if d < STROKE_SHORTEST * float(travel.max()):
                sgn[i0:i1] = 0
        s0, s1 = _sign_runs(sgn)
    out = []
    for i0, i1 in zip(s0, s1):
        d = int(np.sign(np.sum(sgn[i0:i1])))
        if out and out[-1].sign == d:
            out[-1].i1 = int(i1)          # a hold between two runs of one direction: part of the stick
        else:
            out.append(Stroke(int(i0), int(i1), d))
    return [s for s in out if s.n >= min_samples]


#: a run of the drive shorter than this share of the longest run's travel is no stroke (:func:`strokes`)
STROKE_SHORTEST = 0.02

#: a force that changes sign: at least this share of the record on each side,
#: beyond REVERSING_LEVEL of its largest size (:func:`drive_from_force`)
REVERSING_SHARE = 0.2
REVERSING_LEVEL = 0.2
#: the crossings up and down of a drive that turns take alike: one way this many times longer is
#: a one-way stick-slip trace about zero (slips down, sticks up)
CROSSING_RATIO = 3.0


def force_sides(x) -> tuple[float, float]:
    """The shares of the record whose force is below -REVERSING_LEVEL and
    above +REVERSING_LEVEL of its largest size: (below, above)."""
    x = np.asarray(x, float)
    big = float(np.max(np.abs(x))) if x.size else 0.0
    if not big > 0:
        return 0.0, 0.0
    return float(np.mean(x < -REVERSING_LEVEL * big)), float(np.mean(x > REVERSING_LEVEL * big))


def drive_from_force(x, v0: float, min_samples: int = 20):
    """The drive's direction read from the friction force, for a record
    that gives only the drive's speed (``--v0``) while its force changes
    sign over long stretches (a reciprocating rig without its stage's
    position): the signed drive velocity (mm/s) at each sample, or None
    when the force does not reverse.

    The friction holds the spring on the side the drive pulls it to, so the
    force's side (with a hysteresis of half each side's median level about
    their mid-point) is the stroke's direction.  A stroke begins where the
    spring starts over to the other side: from where the force leaves the
    old side's threshold, back while it still moved over at a quarter of
    its speed across the thresholds or more, then back by what the window
    there straddles of the corner (the stage turned there; a dwell's force
    stands still or relaxes slowly before it).  A dwell is not told from a
    stroke's steady sliding by the force alone, so it stays in the stroke
    before it, read as moving.  Sides held for fewer than ``min_samples``
    samples are the slips' overshoot, not strokes; a force whose crossings
    one way take CROSSING_RATIO times longer than the other way's is a
    one-way stick-slip about zero (an AC-coupled sensor: slips cross down,
    sticks up), not a drive that turns: None."""
    x = np.asarray(x, float)
    n = x.size
    big = float(np.max(np.abs(x))) if n else 0.0
    if not (n >= 4 * min_samples and big > 0 and v0 > 0):
        return None
    if min(force_sides(x)) <= REVERSING_SHARE:
        return None
    pos, neg = x > REVERSING_LEVEL * big, x < -REVERSING_LEVEL * big
    lp, ln = float(np.median(x[pos])), float(np.median(x[neg]))
    mid, h = 0.5 * (lp + ln), 0.25 * (lp - ln)
    # the side by hysteresis: +1 above mid + h, -1 below mid - h, else the last side
    side = np.zeros(n, int)
    side[x > mid + h] = 1
    side[x < mid - h] = -1
    idx = np.flatnonzero(side)
    state = side[idx[np.maximum(np.searchsorted(idx, np.arange(n), side="right") - 1, 0)]]
    state[:idx[0]] = side[idx[0]]
    # sides held briefly (a slip's overshoot) belong to the side around them
    for _ in range(3):
        b = np.flatnonzero(np.diff(state)) + 1
        starts, ends = np.r_[0, b], np.r_[b, n]
        short = [(i0, i1) for i0, i1 in zip(starts, ends) if i1 - i0 < min_samples and i0 > 0]
        if not short:
            break
        for i0, i1 in short:
            state[i0:i1] = state[i0 - 1]
    changes = np.flatnonzero(np.diff(state)) + 1
    if changes.size == 0:
        return None
    k = max(3, int(min_samples) // 4)
    xs = np.convolve(x, np.ones(k) / k, mode="same")
    # the crossings: from the last sample beyond the old side's threshold to the first beyond the new one's
    cross = []
    prev = 0
    for c in changes:
        old = int(state[c - 1])
        beyond = np.flatnonzero(old * (xs[prev:c] - mid) >= h)
        cross.append((c, prev + (int(beyond[-1]) if beyond.size else 0), old))
        prev = c
    # a drive that turns loads the spring over to the other side at its speed both ways; a one-way
    # stick-slip trace about zero (an AC-coupled sensor) crosses down in its slips, fast, and up in its sticks
    ups = [c - c0 for c, c0, old in cross if old < 0]
    downs = [c - c0 for c, c0, old in cross if old > 0]
    if ups and downs and max(np.median(ups), np.median(downs)) > CROSSING_RATIO * min(np.median(ups),
                                                                                       np.median(downs)):
        return None
    vd = v0 * state.astype(float)
    prev = 0
    for c, c0, old in cross:
        rate = 2.0 * h / max(c - c0, 1)                  # the force's speed across (per sample)
        # walking back from there while the force still moved over at a quarter of that speed or more (the
        # stage turned where it began; a dwell's force stands still or relaxes slowly before it)
        w = max(k, (c - c0) // 4, 1)
        r = c0
        while r - w >= prev and old * (xs[r - w] - xs[r]) >= 0.25 * rate * w:
            r -= 1
        if r - w >= prev:
            # the window there straddles the corner: the ramp, at its rate, began its fall ago
            r -= int(round(max(old * float(xs[r - w] - xs[r]), 0.0) / rate))
        vd[r:c] = v0 * -old
        prev = c
    return vd


#: the slips' side of the increments' distribution must be this many times
#: longer than the other for the tails to decide the orientation
TAIL_RATIO = 2.0
#: the sign of x' / vd decides the orientation when at least this share of
#: the moving samples agree on it
SLOPE_SHARE = 0.65
#: the slopes say nothing of the orientation when their share of either sign is within this of a half ...
NO_SLOPE = 0.05
#: ... and the level then decides where its median stands this many interquartile ranges from zero
LEVEL_SPREAD = 0.5


def _turned(xs, vd, dt) -> bool:
    """Whether x is written opposite to the drive (its strokes already
    turned forward).  In the sticks (or in steady sliding after a reversal)
    x moves with the drive: when most moving samples (SLOPE_SHARE) agree on
    the sign of x' / vd, that sign decides.  When noise swamps the slow rise
    sample to sample, the slips decide: they are the fast moves, so the long
    tail of the increments of x (the 0.1 % and 99.9 % quantiles, one at least
    TAIL_RATIO times the other) is opposite to the rise."""
    v = np.concatenate([np.gradient(smooth(xx, dt, 1.0, 0, win=9), dt) for xx in xs])
    mv = np.abs(vd) > 0
    q = v[mv] / vd[mv]
    share = float(np.mean(q > 0)) if q.size else 0.5
    if max(share, 1.0 - share) < SLOPE_SHARE:
        # (each stroke's first tenth left out: the spring unloading and loading again through a reversal
        # rises fast in the new direction, a step that is no slip)
        d = np.concatenate([np.diff(smooth(xx, dt, 1.0, 0, win=9))[max(3, xx.size // 10):] for xx in xs
                            if xx.size > 10] or [np.zeros(0)])
        if d.size >= 100:
            lo, hi = -float(np.quantile(d, 0.001)), float(np.quantile(d, 0.999))
            if lo > TAIL_RATIO * hi > 0:
                return False
            if hi > TAIL_RATIO * lo > 0:
                return True
        # no sticks and no slips to read (steady sliding): the level the spring holds while the drive
        # moves has the drive's sign, where it stands clear of its spread
        lev = np.concatenate(xs)[mv]
        if lev.size >= 20:
            m, iqr = float(np.median(lev)), float(np.subtract(*np.percentile(lev, [75, 25])))
            if abs(m) > 2.0 * iqr:
                return m < 0
            # noise that swamps the rise and the slips alike (white noise of a third of the drop or more):
            # the slopes' sign is a coin's there, the level's sign still the friction's where it stands above
            # half its spread (a force written the other way round leaves it below zero)
            if abs(share - 0.5) < NO_SLOPE and abs(m) > LEVEL_SPREAD * iqr:
                return m < 0
    return bool(np.median(q) < 0) if q.size else False


def prepare(rec: Record) -> Prepared:
    """Strokes turned forward and concatenated; x oriented so that it rises
    with the drive in the sticks."""
    st = strokes(rec.vd)
    if not st:
        raise LiengInputError(f"{rec.source}: the drive never moves long enough to analyse (no stroke of 20 samples)")
    dt = rec.dt
    xs, vs, ys, ts = [], [], [], []
    j = 0
    for s in st:
        s.j0 = j
        j += s.n
        sl = slice(s.i0, s.i1)
        xs.append(s.sign * rec.x[sl])
        vs.append(s.sign * rec.vd[sl])
        ts.append(rec.t[sl])
        if rec.y is not None:
            ys.append(rec.y[sl])
    x = np.concatenate(xs)
    vd = np.concatenate(vs)
    # (a drive read from the force's side has the force's sign: nothing to turn)
    flipped = False if rec.drive_from_force else _turned(xs, vd, dt)
    notes = []
    if flipped:
        x = -x
        notes.append("the force is written opposite to the drive in this record: its sign was turned")
    if len(st) > 1 or st[0].sign < 0:
        nb = sum(1 for s in st if s.sign < 0)
        notes.append(f"{len(st)} strokes ({len(st) - nb} forward, {nb} backward), each turned forward")
    track = travel(rec.vd, dt)
    pos = np.concatenate([track[s.i0:s.i1] for s in st])
    pr = Prepared(t=np.concatenate(ts), x=x, vd=vd, y=None if rec.y is None else np.concatenate(ys),
                  strokes=st, dt=dt, flipped=flipped, notes=notes, pos=pos, quantum=quantum(rec.x),
                  hum_hz=tuple(rec.hum_hz))
    if rec.drive_recorded:
        steady = steady_drive(pr)
        if steady is not None:
            pr.vd_steady, pr.steady_read = steady
    return pr


#: a recorded reciprocating drive is made steady (:func:`steady_drive`) from at
#: least this many strokes in each direction
STEADY_STROKES = 2
#: ... over this many bins of the track
STEADY_BINS = 64
#: strokes run at speeds within this factor of each other are alike (:func:`steady_drive`): a programme's
#: steps are larger; a modulation of the speed moves a stroke's by less
STEADY_LIKE = 1.25


def steady_drive(pr: Prepared):
    """A recorded reciprocating drive made steady: at each sample, the
    median over the strokes of its direction run at a like speed (each
    stroke's own speed, its mean where it runs at least DRIVE_RATIO_FLOOR of
    its fastest, within STEADY_LIKE of each other's) of their speed at that
    position on the track (each stroke's mean in STEADY_BINS bins of the
    track, linear between the bins' middles).  A crank, a cam or a
    trapezoidal programme repeats its speed along the track stroke after
    stroke, at each of the speeds it steps between; a drive whose speed
    wanders (a motor's speed modulated) does not, and the recorded drive
    over this is its modulation (:func:`drive_ratios`).  A stroke with
    fewer than STEADY_STROKES like it gets the median of its direction's
    strokes' shapes (each over its own speed) times its own speed, and is
    not read for a modulation.  Returns (the steady speed, the mask of the
    samples read), or None where a direction has fewer than STEADY_STROKES
    strokes."""
    if pr.pos is None or len(pr.strokes) < 2 * STEADY_STROKES:
        return None
    lo, hi = float(np.min(pr.pos)), float(np.max(pr.pos))
    if not hi > lo:
        return None
    edges = np.linspace(lo, hi, STEADY_BINS + 1)
    mid = 0.5 * (edges[1:] + edges[:-1])
    b = np.clip(np.digitize(pr.pos, edges) - 1, 0, STEADY_BINS - 1)
    speed = np.abs(pr.vd)
    scale = np.ones(pr.t.size)
    for s in pr.strokes:
        sp = speed[s.j0:s.j0 + s.n]
        fast = sp >= DRIVE_RATIO_FLOOR * float(np.max(sp))
        m = float(np.mean(sp[fast])) if np.any(fast) else 0.0
        if not m > 0:
            return None
        scale[s.j0:s.j0 + s.n] = m
    out = np.zeros(pr.t.size)
    read = np.zeros(pr.t.size, bool)

    def course(group, own: bool):
        """The median of ``group``'s strokes' speeds along the track (with ``own``, each over its own
        speed, and the median laid on each times its own), laid on each of them."""
        u = speed / scale if own else speed
        M = np.full((len(group), STEADY_BINS), np.nan)
        for i, s in enumerate(group):
            sl = slice(s.j0, s.j0 + s.n)
            cnt = np.bincount(b[sl], minlength=STEADY_BINS)
            tot = np.bincount(b[sl], weights=u[sl], minlength=STEADY_BINS)
            M[i, cnt > 0] = tot[cnt > 0] / cnt[cnt > 0]
        seen = np.sum(np.isfinite(M), axis=0) > 0
        if np.count_nonzero(seen) < 2:
            return False
        pat = np.nanmedian(M[:, seen], axis=0)
        for s in group:
            sl = slice(s.j0, s.j0 + s.n)
            out[sl] = np.interp(pr.pos[sl], mid[seen], pat) * (scale[sl] if own else 1.0)
        return True

    for sign in (1, -1):
        ss = sorted((s for s in pr.strokes if s.sign == sign), key=lambda s: scale[s.j0])
        if not ss:
            continue
        if len(ss) < STEADY_STROKES or not course(ss, True):
            return None
        # the strokes run at a like speed, read against each other
        groups, cur = [], [ss[0]]
        for s in ss[1:]:
            if scale[s.j0] <= STEADY_LIKE * scale[cur[0].j0]:
                cur.append(s)
            else:
                groups.append(cur)
                cur = [s]
        groups.append(cur)
        for g in groups:
            if len(g) >= STEADY_STROKES and course(g, False):
                for s in g:
                    read[s.j0:s.j0 + s.n] = True
    return out, read


#: a stroke's own speed, and the drive's ratio to its steady course, are read
#: where the stroke runs at least this share of its fastest (not in the ramps
#: and reversals: a programme's ramp may keep its acceleration, not its shape,
#: when the speed steps)
DRIVE_RATIO_FLOOR = 0.7


def drive_ratios(pr: Prepared, c: Cycles):
    """A recorded reciprocating drive over its steady course
    (:func:`steady_drive`), averaged over runs of a quarter of the mean
    stick-slip period (within each stroke, where its steady speed is at
    least DRIVE_RATIO_FLOOR of the stroke's fastest): (times, ratios),
    empty without a steady drive."""
    st = pr.vd_steady
    per = c.periods(pr.t)
    if st is None or per.size < 2 or not np.max(st) > 0:
        return np.zeros(0), np.zeros(0)
    run = max(5, int(round(float(np.mean(per)) / 4.0 / pr.dt)))
    tt, rr = [], []
    for s in pr.strokes:
        idx = np.arange(s.j0, s.j0 + s.n)
        if pr.steady_read is not None and not np.all(pr.steady_read[idx]):
            continue
        idx = idx[st[idx] >= DRIVE_RATIO_FLOOR * float(np.max(st[idx]))]
        for k in range(0, idx.size - run + 1, run):
            q = idx[k:k + run]
            tt.append(float(np.mean(pr.t[q])))
            rr.append(float(np.mean(np.abs(pr.vd[q]) / st[q])))
    return np.asarray(tt), np.asarray(rr)


def _zigzag_fast(x, h):
    """Alternating extrema of x with hysteresis h: (indices, kinds) with kind
    +1 for a maximum, -1 for a minimum; the walk runs over the candidate
    extrema only (where the slope changes sign), so long records stay fast."""
    d = np.diff(x)
    sgn = np.sign(d)
    # indices where the slope changes sign (plateaus resolved to the left)
    nz = np.flatnonzero(sgn != 0)
    if nz.size < 2:
        return np.array([], int), np.array([], int)
    s = sgn[nz]
    ch = np.flatnonzero(np.diff(s) != 0)
    cand = nz[ch + 1]
    cand = np.r_[0, cand, x.size - 1]
    return _zigzag_on(x, cand, h)


def _zigzag_on(x, cand, h):
    vals = x[cand]
    idx, kind = [], []
    imax = imin = 0
    trend = 0
    for k in range(1, cand.size):
        xi = vals[k]
        if trend >= 0:
            if xi > vals[imax]:
                imax = k
            elif vals[imax] - xi > h:
                idx.append(cand[imax])
                kind.append(1)
                trend, imin = -1, k
                continue
        if trend <= 0:
            if xi < vals[imin]:
                imin = k
            elif xi - vals[imin] > h:
                idx.append(cand[imin])
                kind.append(-1)
                trend, imax = 1, k
    return np.asarray(idx, int), np.asarray(kind, int)


#: the slip has ended (arrested) at the first local minimum of x after the peak
#: that lies this fraction of the way down from the peak to the lowest x
ARREST_DEPTH = 0.8
#: local minima tried before the lowest point is taken (a hold in which x keeps relaxing)
ARREST_TRIES = 64


def arrest(xl, pi_: int, ti_: int, tol: float) -> int:
    """Where the slip from the peak ``pi_`` ends: the first local minimum of
    the lightly smoothed ``xl`` after it, at least ARREST_DEPTH of the way
    down to the lowest point ``ti_``, that x does not fall below by more
    than ``tol`` (the noise) within half the time since the peak.  In a
    plain slip that is the lowest point; before a hold (a stop of the drive)
    it is the arrest, not the lowest wiggle of the noise somewhere in the
    hold, so that the slip's samples stay in the slip and the stick through
    the hold counts from its start."""
    if ti_ - pi_ < 3:
        return ti_
    seg = xl[pi_:ti_ + 1]
    # the local minima deep enough before the last sample (which, the lowest, ends the slip when none does);
    # at most ARREST_TRIES are tried (each looks at most the fall's length ahead): linear time
    deep_up = (seg[:-1] <= seg[0] - ARREST_DEPTH * (seg[0] - seg[-1])) & (seg[1:] >= seg[:-1])
    for j in np.flatnonzero(deep_up)[:ARREST_TRIES]:
        if seg[j] <= float(np.min(seg[j:j + max(3, j // 2) + 1])) + tol:
            return pi_ + int(j)
    return ti_


def _sg_gain(w: int) -> float:
    """How much of white noise :func:`smooth` (its value, window ``w``) lets through: the kernel's norm."""
    from scipy.signal import savgol_coeffs

    return float(np.linalg.norm(savgol_coeffs(w, 3 if w > 5 else 2)))


#: the widest window (in natural periods) a noisy stroke is smoothed over to find its slips: a slip lasts
#: about half a period, and a cubic fit over a period keeps most of its drop (stop 68's edge-case test: white
#: noise of 30-50 % of the drop hid the slips of a quarter-period window; stop 69)
NOISY_WINDOW = 1.0


def _swing(v) -> float:
    """A trace's swing: its 98th less its 2nd percentile (a spike or a
    reversal's overshoot does not set it)."""
    return float(np.subtract(*np.percentile(v, [98, 2])))


def _light(x, dt, fn, win: int, noise: float):
    """A stroke's trace lightly smoothed for finding its extrema (``win``
    samples), and the noise the cycle finder's thresholds are read against.
    Where 8 times the per-sample noise exceeds half the swing (a noisy
    sensor sampled fast, whose slips the thresholds would not see), the
    window is doubled, at most to :data:`NOISY_WINDOW` natural periods
    (without fn, a sixteenth of the stroke and a quarter of its strongest
    period), until 8 times the noise it lets through is within half the
    swing read through it (the noise widens the swing read sample by
    sample: white noise of 40 % of the drop reads a swing of twice the
    drop); where no window up to that does, the one whose swing stands
    highest above the noise it lets through (past the slips' own time scale
    a wider window smooths the swing away faster than the noise).  The
    thresholds then read that window's noise; returned with the window."""
    xl = smooth(x, dt, 1.0, 0, win=win)
    span = _swing(xl)
    if not 8 * noise > 0.5 * span:
        return xl, noise, win
    if fn is not None:
        wmax = max(int(NOISY_WINDOW / fn / dt) | 1, 7)
    else:
        # without fn, a sixteenth of the stroke and a quarter of its strongest period (of four to a
        # thousand in the stroke: the stick-slip's, whose slip a window as long as the cycle smooths away)
        wmax = max(win, (x.size // 16) | 1)
        f = np.abs(np.fft.rfft(x - np.linspace(x[0], x[-1], x.size)))
        if f.size > 8:
            k = 4 + int(np.argmax(f[4:min(f.size, 1001)]))
            wmax = max(win, min(wmax, (x.size // (4 * k)) | 1))
    w, xw = win, xl
    best = (span / _sg_gain(w), w, xw)
    while 8 * noise * _sg_gain(w) > 0.5 * span:
        if 2 * w + 1 > wmax:
            _, w, xw = best
            break
        w = 2 * w + 1
        xw = smooth(x, dt, 1.0, 0, win=w)
        span = _swing(xw)
        best = max(best, (span / _sg_gain(w), w, xw), key=lambda b: b[0])
    return xw, noise * _sg_gain(w), w


_RAMP = True


#: a record with fewer slips than this at the first swing threshold (a quarter of each stroke's span) is
#: read again at half the threshold, and so on (:func:`find_cycles` with ``retry``): too few to read as
#: stick-slip anyway (:func:`lieng.diagnose.diagnose` reads four at least)
RETRY_SLIPS = 4
#: the smallest share of a stroke's span the swing threshold is lowered to (its other floors, 8 times the
#: noise and a twentieth of the stroke's whole span, hold throughout)
SHARE_FLOOR = 0.25 / 16


def _stroke_slips(xl, noise: float, share: float) -> list:
    """The slips of one stroke's lightly smoothed trace ``xl``: (peak,
    trough, whether the slip before it is in the same run of cycles), the
    indices within the stroke; found as the alternating extrema with a
    hysteresis of ``share`` of the stroke's span (at least 8 times the
    noise), then again at 0.3 of their median swing, each fall that is
    faster than the rise before it."""
    out = []
    # the swing's scale, less a reversal's reload at the stroke's start (x climbing from the other side to
    # its level: a ramp as tall as two static limits, which no slip is)
    head_end = int(np.argmax(xl >= np.median(xl))) if _RAMP else 0
    body = xl[head_end:] if 2 * (xl.size - head_end) >= xl.size else xl
    span = _swing(body)
    if not span > 1e-9 * float(np.max(np.abs(xl))):
        return out                      # a flat stroke (within rounding): no cycle in it
    # (and at least a twentieth of the whole stroke's, reload included: a steady stroke's wiggles are no
    # stick-slip)
    h0 = max(share * span, 8 * noise, 0.05 * _swing(xl))
    ix, kd = _zigzag_fast(xl, h0)
    if ix.size >= 4:
        sw = np.abs(np.diff(xl[ix]))
        h = max(0.3 * float(np.median(sw)), 8 * noise)
        ix, kd = _zigzag_fast(xl, h)
    follows = False
    # (the local minima before each sample, counted once: a slip with none before its lowest point ends
    # there, which :func:`arrest` would find at a cost per slip)
    nmin = np.r_[0, np.cumsum(xl[1:] >= xl[:-1])]
    ixl, kdl = ix.tolist(), kd.tolist()
    for m in range(ix.size - 1):
        if kdl[m] != 1 or kdl[m + 1] != -1:
            continue
        pi_, ti_ = ixl[m], ixl[m + 1]
        if nmin[ti_] > nmin[pi_]:
            ti_ = arrest(xl, pi_, ti_, 3 * noise)
        fall = ti_ - pi_
        rise = pi_ - ixl[m - 1] if m >= 1 else None
        if rise is not None and not fall < rise:
            follows = False
            continue            # not a slip: as slow as the rise before it
        if fall < 1:
            continue
        out.append((pi_, ti_, follows))
        follows = True
    return out


def find_cycles(p: Prepared, fn: float | None, speeds: bool = True, retry: bool = False) -> Cycles:
    """The stick-slip cycles of every stroke (see the module docstring);
    with ``speeds=False`` the peaks and troughs alone (``v`` and ``a`` are
    left empty: a simulated trace's troughs, read many times over);
    ``retry``: a record's own reading, whose level may wander by more than
    its slips: with fewer than :data:`RETRY_SLIPS` slips found, the swing
    threshold is halved until it shows them (a simulated trace is read at
    the first threshold alone: a baseline that settles into steady sliding
    rings down, and its ringing is no slip)."""
    dt = p.dt
    noise = noise_level(p.x)
    base_win = 5 if fn is None or 0.25 / fn / dt < 9 else max(5, int(0.08 / fn / dt) | 1)
    light, noises, wide = [], [], 0
    for sl in p.stroke_slices():
        xl, nl, w = _light(p.x[sl], dt, fn, base_win, noise)
        light.append(xl)
        noises.append(nl)
        if w > base_win:
            wide = max(wide, w)
    peaks, troughs, strk, nxt = [], [], [], []
    vs, acc = [], []
    win = None
    for s in p.strokes:
        sl = slice(s.j0, s.j0 + s.n)
        xr = p.x[sl]
        if fn is not None:
            win = max(int(round(0.25 / fn / dt)) | 1, 7)
        if speeds and fn is not None:
            vs.append(smooth(xr, dt, fn, 1))
            acc.append(smooth(xr, dt, fn, 2))
        elif speeds:
            vs.append(smooth(xr, dt, 1.0, 1, win=7))
            acc.append(smooth(xr, dt, 1.0, 2, win=7))
    # the first swing threshold is a quarter of each stroke's span; a record whose level wanders by more than
    # its slips (a load along the track, one large slip among many small ones) swings fewer times at it than it
    # slips, and the threshold is halved until the record shows enough slips to be read (at most to the floor
    # that the noise and a twentieth of the stroke's span set, as before)
    share = 0.25
    while True:
        found = [_stroke_slips(xl, noise, share) for xl, noise in zip(light, noises)]
        if not retry or sum(len(f) for f in found) >= RETRY_SLIPS or share <= SHARE_FLOOR:
            break
        share *= 0.5
    for k, (s, f) in enumerate(zip(p.strokes, found)):
        for pi_, ti_, follows in f:
            if follows:                # (the slip before it is in this stroke: appended just before)
                nxt[-1] = True
            peaks.append(s.j0 + pi_)
            troughs.append(s.j0 + ti_)
            strk.append(k)
            nxt.append(False)
    c = Cycles(peak_i=np.asarray(peaks, int), trough_i=np.asarray(troughs, int), stroke=np.asarray(strk, int),
               next_ok=np.asarray(nxt, bool), v=np.concatenate(vs) if speeds else np.empty(0),
               a=np.concatenate(acc) if speeds else np.empty(0),
               win=win if win is not None else 7, light=wide)
    return c


def _arc_rss(slips, w, with_step=True):
    """Pooled RSS of arcs of frequency w fitted to each slip (x = c + A cos +
    B sin [+ step after the sliding-speed peak]), slip by slip (linear)."""
    rss = 0.0
    for tt, xx, ts in slips:
        cols = [np.ones(tt.size), np.cos(w * tt), np.sin(w * tt)]
        if with_step:
            cols.append(np.where(tt > ts, 1.0 - np.cos(w * (tt - ts)), 0.0))
        A = np.column_stack(cols)
        coef, res, rank, _ = np.linalg.lstsq(A, xx, rcond=None)
        r = xx - A @ coef
        rss += float(r @ r)
    return rss


def slip_arcs(p: Prepared, c: Cycles, extend: int = 1):
    """The slips as (time from the peak, x, time of the sliding-speed peak),
    from one sample before the peak to one after the trough."""
    out = []
    for pi_, ti_ in zip(c.peak_i, c.trough_i):
        lo, hi = pi_, ti_ + 1
        if hi - lo < 4:
            lo, hi = max(pi_ - extend, 0), min(ti_ + 1 + extend, p.x.size)
        if hi - lo < 4:
            continue
        seg = np.arange(lo, hi)
        k = seg[int(np.argmin(c.v[seg]))] if seg.size > 2 else seg[seg.size // 2]
        out.append((p.t[seg] - p.t[pi_], p.x[seg], p.t[k] - p.t[pi_]))
    return out


#: a free half-oscillation x = c + A cos(wt) falls from 10 % to 90 % of its
#: drop in this fraction of its peak-to-trough time (2 acos(0.8) / pi)
FALL_FRACTION = 2.0 * math.acos(0.8) / math.pi


def first_below(t, x, level: float) -> float | None:
    """The first moment ``x`` falls below ``level``, linear between samples;
    None when it never does or starts below it."""
    below = np.flatnonzero(x < level)
    if below.size == 0 or below[0] == 0:
        return None
    j = int(below[0])
    a, b = float(x[j - 1]) - level, float(x[j]) - level
    return float(t[j - 1] + (t[j] - t[j - 1]) * a / (a - b))


def slip_durations(p: Prepared, c: Cycles, spread: bool = False):
    """Each slip's duration (s) read from its fall: the time x takes from
    10 % to 90 % of the way from its peak to its trough, over
    :data:`FALL_FRACTION` (so that a free half-oscillation gives its
    peak-to-trough time).  Read on the fall, not between the extremes: a
    flat or rounded top (creep before slip, noise) puts the peak anywhere on
    it.  Noise on a fall's flat top or bottom crosses a level near it
    anywhere there: each level's crossing is read both nearest the fall's
    middle (the last sample at or above 10 % before it, the first below
    90 % after it) and farthest from it (the first below 10 %, the last at
    or above 90 %), and the duration is the middle of the two readings
    (identical on a fall that does not turn back); with ``spread``, also
    each slip's half-difference of the two (s).  On an analytic Coulomb
    slider under white noise of 5 % of the drop the farthest reading alone
    (the code before) lengthened the slips by 20-51 %, the nearest shortened
    them by up to 13 %, and the truth lay between the two at every noise
    level up to 20 % of the drop."""
    out, half = np.empty(c.n), np.zeros(c.n)
    x, t = p.x, p.t
    for j, (a, b) in enumerate(zip(c.peak_i, c.trough_i)):
        seg = x[a:b + 1]
        drop = float(seg[0] - seg[-1]) if seg.size else 0.0
        if seg.size < 3 or not drop > 0:
            out[j] = np.nan
            continue
        tt = t[a:b + 1]
        hi, lo = float(seg[0]) - 0.1 * drop, float(seg[-1]) + 0.1 * drop
        m = int(np.argmax(seg < float(seg[0]) - 0.5 * drop))        # the fall's middle
        i = int(np.flatnonzero(seg[:m] >= hi)[-1])
        k = m + int(np.argmax(seg[m:] < lo))
        e = int(np.flatnonzero(seg >= lo)[-1])
        near = (_down(tt, seg, i, hi), _down(tt, seg, k - 1, lo))
        far = (first_below(tt, seg, hi), _down(tt, seg, e, lo))
        out[j] = 0.5 * ((near[1] + far[1]) - (near[0] + far[0])) / FALL_FRACTION
        half[j] = 0.5 * ((far[1] - far[0]) - (near[1] - near[0])) / FALL_FRACTION
    return (out, half) if spread else out


def _down(t, x, i: int, level: float) -> float:
    """The moment ``x`` crosses ``level`` downward between samples ``i`` and
    ``i + 1`` (x[i] >= level > x[i + 1]), linear between them."""
    return float(t[i] + (t[i + 1] - t[i]) * (x[i] - level) / (x[i] - x[i + 1]))


def slip_seconds(p: Prepared, c: Cycles, spread: bool = False):
    """The slips' median duration (s, :func:`slip_durations`); None below
    three.  With ``spread``: (that, the median over the slips of the
    half-difference of their two readings over their duration: how far
    noise leaves the duration open), or (None, 0.0)."""
    d, h = slip_durations(p, c, spread=True)
    ok = np.isfinite(d) & (d > 0)
    if np.count_nonzero(ok) < 3:
        return (None, 0.0) if spread else None
    dur = float(np.median(d[ok]))
    return (dur, float(np.median(h[ok] / d[ok]))) if spread else dur


def estimate_fn(p: Prepared, c: Cycles, fn_guess: float | None = None):
    """The natural frequency from the slips (module docstring): (fn, its
    standard error, the number of slips used), or (None, None, 0) when the
    slips cannot fix it."""
    dur = slip_seconds(p, c)
    if dur is None:
        return None, None, 0
    f0 = fn_guess if fn_guess else 0.5 / dur
    slips = slip_arcs(p, c)
    if len(slips) < 3:
        return None, None, 0
    if len(slips) > 400:                       # plenty: an even subset keeps it linear in time
        slips = [slips[i] for i in np.linspace(0, len(slips) - 1, 400).astype(int)]
    grid = f0 * np.geomspace(0.6, 1.6, 61)

    def best(sl):
        r = np.array([_arc_rss(sl, 2 * math.pi * f) for f in grid])
        k = int(np.argmin(r))
        if 0 < k < grid.size - 1:
            # parabolic refinement in log f
            y0, y1, y2 = r[k - 1], r[k], r[k + 1]
            den = y0 - 2 * y1 + y2
            off = 0.5 * (y0 - y2) / den if den > 0 else 0.0
            return float(grid[k] * (grid[1] / grid[0]) ** off), True
        return float(grid[k]), False

    f, interior = best(slips)
    if not interior:
        return None, None, len(slips)
    # jackknife over groups of slips for the uncertainty
    g = min(10, len(slips))
    parts = np.array_split(np.arange(len(slips)), g)
    est = []
    for idx in parts:
        keep = set(idx.tolist())
        est.append(best([s for i, s in enumerate(slips) if i not in keep])[0])
    est = np.asarray(est)
    se = float(math.sqrt((g - 1) / g * np.sum((est - est.mean()) ** 2)))
    return f, se, len(slips)


#: a stick's rise over its scatter about a line, at least (a line, not an oscillation)
STICK_LINE = 5.0


def travel(vd, dt):
    """The drive's travel (mm) at each sample from its velocity ``vd``
    (mm/s), by the trapezoid rule over the steps ``dt`` (s: one step, or the
    n - 1 steps); 0 at the first sample."""
    return cumulative_trapezoid(vd, dt)


class Ramp(NamedTuple):
    """A stroke's presliding ramp (:func:`reversal_ramp`)."""
    #: the sliding level (the median x over the stroke's second half)
    level: float
    #: x at the stroke's start (the median of its first three samples)
    x0: float
    #: the drive's travel (mm) until x has first gone 90 % of the way from x0 to the level (nan when it never does)
    travel: float
    #: that sample within the stroke (None when it never does)
    k90: int | None
    #: the drive's travel from the stroke's start at each of its samples (mm)
    tr: np.ndarray

    @property
    def slope(self) -> float:
        """The ramp's slope, x per mm of the drive's travel to its 90 % point
        (1 for a rigid stick behind the given spring; nan without a ramp)."""
        return 0.9 * (self.level - self.x0) / self.travel if self.travel > 0 else math.nan


def reversal_ramp(p: Prepared, s) -> Ramp:
    """A stroke's presliding ramp in steady sliding (:class:`Ramp`): its
    sliding level, x at its start, the drive's travel until x has first
    gone 90 % of the way from the start to the level, that sample, and the
    travel along the stroke."""
    sl = slice(s.j0, s.j0 + s.n)
    x = p.x[sl]
    P, x0 = float(np.median(x[x.size // 2:])), float(np.median(x[:3]))
    tr = travel(p.vd[sl], np.diff(p.t[sl]))
    k90 = np.flatnonzero((x - x0) >= 0.9 * (P - x0)) if P > x0 else np.array([], int)
    return Ramp(P, x0, float(tr[k90[0]]), int(k90[0]), tr) if k90.size else Ramp(P, x0, math.nan, None, tr)


#: the part of a stick (trough to next peak) its line is read on: past the
#: arrest's transient, before the creep that precedes the slip
STICK_PART = (0.25, 0.875)


def stick_part(c: Cycles, k: int, part=STICK_PART):
    """The samples of the fraction ``part`` of stick ``k`` (trough ``k`` to
    peak ``k + 1``)."""
    lo, hi = int(c.trough_i[k]), int(c.peak_i[k + 1])
    m = hi - lo
    return np.arange(lo + int(m * part[0]), lo + int(m * part[1]))


def stick_ratios(pr: Prepared, c: Cycles, part=STICK_PART, lines_only: bool = False, index: bool = False):
    """Per stick (trough to next peak, the fraction ``part`` of it): the time
    of its middle and the slope of x there over the mean drive (and, with
    ``index``, the stick's cycle, so that two parts of one stick can be
    paired).  With ``lines_only``, only where x is a line there (its rise
    over the part at least STICK_LINE times the scatter about the line): a
    stretch between two slips in which the slider oscillates or slides (a
    drive step into another regime) is no stick."""
    tt, rr, kk = [], [], []
    for k in np.flatnonzero(c.next_ok):
        seg = stick_part(c, k, part)
        if seg.size < 5:
            continue
        vd = float(np.mean(pr.vd[seg]))
        if vd <= 0:
            continue
        # the least-squares line in closed form (np.polyfit's lstsq costs ten times more, once per stick)
        ts, xs = pr.t[seg], pr.x[seg]
        tm = float(np.mean(ts))
        dtm = ts - tm
        slope = float(dtm @ (xs - np.mean(xs))) / float(dtm @ dtm)
        if lines_only:
            scatter = float(np.std(xs - np.mean(xs) - slope * dtm))
            if not abs(slope) * float(ts[-1] - ts[0]) >= STICK_LINE * scatter:
                continue
        tt.append(tm)
        rr.append(slope / vd)
        kk.append(int(k))
    return (np.asarray(tt), np.asarray(rr), np.asarray(kk, int)) if index else (np.asarray(tt), np.asarray(rr))


def creep_pairs(pr: Prepared, c: Cycles):
    """The stick slope over the drive in the middle of each stick (30-60 %
    of its rise) and in its last part (80-97 %), paired stick by stick (a
    stick too short for one of the parts is left out of both)."""
    _, mid, km = stick_ratios(pr, c, (0.3, 0.6), index=True)
    _, late, kl = stick_ratios(pr, c, (0.8, 0.97), index=True)
    _, im, il = np.intersect1d(km, kl, return_indices=True)
    return mid[im], late[il]
