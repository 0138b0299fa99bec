"""Stage 6 of ``lieng diagnose``: the extended models and their gain.

The record is split in time: the baseline and every extension are fitted on
the first 70 % (less when that would leave fewer than three cycles to test
on), and judged on the rest; and, where each side keeps enough cycles, fitted
again on the last 70 % and judged on the first 30 % (:func:`folds`: a record
whose conditions change along it, a stepped drive or holds, is judged where
they differ, not only where they end); on a record of up to 250 000 samples
the middle left between those two is held out too, in two parts each judged
with the models fitted on the rest of the record, so that every cycle is
held out once.  For each named effect a few candidates of the
nested extension (the baseline plus that one term) are fitted on the
training part from the evidence's estimate and the best on the training
error kept.  Ageing's candidates include, when the sticks were loaded at
different drive velocities (a stepped drive), a static limit that also
follows the loading velocity (rate-dependent static friction, the direct
effect of a rate-and-state law): FS (1 + a ln(1 + ts/tau) + r ln(vl/vr)),
fitted on the training sticks as the core applies it; on a stepped drive the
stick time alone cannot carry the peaks across the steps.

**Metric** (does not contain any effect's own statistic): on the held-out
cycles, one cycle ahead from the record's own state (from each trough, the
model started in stick at the record's displacement on the record's drive
and clock), the RMS of the normalised differences between the record and
the model of

* each cycle's stick, measured in the drive's travel (from the trough to
  the next slip's halfway crossing, over the mean travel of a period: the
  spring loads with the travel, and a hold adds time, not load; with a
  constant drive this is the stick time over the mean period), peak and
  trough (over D):
  what the model predicts *when* and *how high* (a modulated drive, ageing
  under holds or a stepped drive, a load or a drift show here);
* the mean slip waveform: x at 9 instants over 0.6 natural periods centred
  on the moment each slip's x crosses halfway from its peak to its trough,
  less that halfway level, over D, against the record's (aligned on the
  fall, so that a flat or creeping top does not decide where it starts);
  only the instants within the record's slips (from the median peak to the
  median arrest, relative to that crossing): what x does after the arrest,
  a second mode's rebound or a sensor's ringing, is the rig's, which no
  model of the slider has.

The normal channel is not compared (stop 67): a triggering extension's line
in it is the effect's own statistic, so a load modulation earns its gain by
what it does to the slider alone.

The baseline an effect's gain is judged against, and that its extension
extends, is read through the training part's linear trend in level when
that trend is beyond two standard errors (:func:`level_trend`: a sensor's
offset that drifts shifts every held-out peak, trough and stick time, an
error none of the other terms removes); ``friction_drift``'s and
``load_variation``'s is the plain baseline (the trend is the one's own
extension, and a load's course along the record, a tilted track or a cam,
moves the level as a drift does: the trend would stand for it).

gain = 1 - e_extended / e_baseline (:func:`gain_folds`), with a 90 % interval from resampling the
held-out cycles; always finite.  A fold whose training part cannot form the
extension at all (too few sticks to read an ageing law on) holds nothing
out for it and is left out; one that formed an extension no better than
the baseline on its training part stays in, with the baseline as its
extension.
"""

from __future__ import annotations

import math

import numpy as np

from lieng.errors import LiengInputError
from lieng.diagnose.baseline import (Params, characteristic, identify, level_to_trough, locked_load,
                                     pr_like, run_slice, simulate, slip_friction, stick_start)
from lieng.diagnose.evidence import _stick_series, stick_loading, stick_times, trig_modulation
from lieng.diagnose.signals import drive_scan, level_fit, line_fit, lowpass, refine_line
from lieng.diagnose.segment import Cycles, Prepared, find_cycles, first_below, travel

__all__ = ["TRAIN", "METRIC", "split", "folds", "window", "Judge", "candidates", "gain_folds", "unconfirmed",
           "level_trend"]

TRAIN = 0.7
METRIC = ("RMS of normalised differences on the held-out cycles (the record's last 30 % with models fitted on its "
          "first 70 %, and its first 30 % with models fitted on its last 70 %; on a record of up to 250 000 samples "
          "also its middle, in two parts each with models fitted on the rest; a fold whose training part cannot form "
          "the extension is left out), one cycle ahead from the record's own state (from "
          "each trough): stick in the drive's travel to the next slip's halfway crossing (/ mean travel of a period; with a constant drive, the stick time / mean period), peak and trough (/ drop D); "
          "mean slip waveform at 9 instants over 0.6 natural periods centred on each slip's halfway crossing, those "
          "within the record's slips (from peak to arrest) (/ D); "
          "the baseline (and so its extension) read through the training part's linear trend "
          "in level when beyond 2 standard errors, except for friction_drift and load_variation")


def subset(c: Cycles, sel) -> Cycles:
    """The cycles whose mask ``sel`` is true (a cycle keeps its successor
    only when that is kept too)."""
    k = np.flatnonzero(sel)
    nxt = c.next_ok[k].copy()
    if k.size:
        nxt &= np.r_[np.diff(k) == 1, False]
    return Cycles(peak_i=c.peak_i[k], trough_i=c.trough_i[k], stroke=c.stroke[k], next_ok=nxt, v=c.v, a=c.a,
                  win=c.win, light=c.light)



def split(pr: Prepared, c: Cycles) -> float:
    """The time that ends the training part."""
    ts = pr.t[c.peak_i]
    tsplit = float(pr.t[0] + TRAIN * (pr.t[-1] - pr.t[0]))
    if np.count_nonzero(ts > tsplit) < 4 and ts.size >= 6:
        tsplit = float(ts[-4 if ts.size >= 8 else -3]) - 0.5 * pr.dt
    return tsplit


def folds(pr: Prepared, c: Cycles) -> list:
    """The held-out parts the gain is measured on, each with the training
    part its models are fitted on: (train_lo, train_hi, test_lo, test_hi)
    in seconds, the training part being [train_lo, train_hi) less the
    held-out part (:func:`window`).  The record's end (the first 70 % trains,
    as :func:`split`) and, when each side keeps at least three cycles, its
    beginning (the last 70 % trains): a record whose conditions change along
    it (a stepped drive, holds) is judged where they differ, not only where
    they end.  On a record of at most :data:`MIDDLE_SAMPLES` samples the
    middle left between them is held out too, in two parts of at least
    :data:`MIDDLE_CYCLES` cycles each (or one), each with the rest of the
    record training: every cycle is then held out once, with 80 % of a
    short record still training (a short record's gain rests on few
    cycles; a long one's ends hold out enough)."""
    t0, t1 = float(pr.t[0]), float(pr.t[-1]) + pr.dt
    ts = pr.t[c.peak_i]
    fwd = split(pr, c)
    out = [(t0, fwd, fwd, t1)]
    back = float(pr.t[0] + (1.0 - TRAIN) * (pr.t[-1] - pr.t[0]))
    if np.count_nonzero(ts < back) < 4 and ts.size >= 6:
        back = float(ts[3 if ts.size >= 8 else 2]) + 0.5 * pr.dt
    if np.count_nonzero(ts < back) >= 4 and np.count_nonzero(ts >= back) >= 3:
        out.append((back, t1, t0, back))
        mid = ts[(ts >= back) & (ts < fwd)]
        if pr.x.size <= MIDDLE_SAMPLES and mid.size >= MIDDLE_CYCLES:
            if mid.size >= 2 * MIDDLE_CYCLES:
                # (between the two peaks that halve the middle's cycles)
                h = mid.size // 2
                cut = 0.5 * float(mid[h - 1] + mid[h])
                out += [(t0, t1, back, cut), (t0, t1, cut, fwd)]
            else:
                out.append((t0, t1, back, fwd))
    return out


#: the middle of a record of at most this many samples is held out too (:func:`folds`)
MIDDLE_SAMPLES = 250_000
#: the fewest cycles a middle held-out part holds
MIDDLE_CYCLES = 4


def window(t, win) -> np.ndarray:
    """Which of the times ``t`` lie in the window ``win``: (lo, hi), or
    (lo, hi, a, b) for [lo, hi) less [a, b) (a training part around a
    held-out one)."""
    t = np.asarray(t)
    m = (t >= win[0]) & (t < win[1])
    if len(win) > 2:
        m &= ~((t >= win[2]) & (t < win[3]))
    return m


#: instants of the mean slip waveform the Judge compares
NWAVE = 9


def _half_crossing(t, x, i0: int, i1: int):
    """The moment the slip from ``i0`` (its peak) to ``i1`` (past its trough)
    crosses halfway between the two, and that level: (t_half, x_half) or
    None.  (A slip is timed on its fall, not at its peak: a flat or creeping
    top would place the peak anywhere on it.)"""
    if i1 - i0 < 2 or i1 > x.size:
        return None
    seg = x[i0:i1]
    half = 0.5 * (float(seg[0]) + float(np.min(seg)))
    th = first_below(t[i0:i1], seg, half)
    return None if th is None else (th, half)


def _slip(t, x, i0: int, i1: int, tau):
    """When the slip from ``i0`` to ``i1`` happens (its halfway crossing, or
    its peak's time when it has none) and the slip seen from that crossing,
    x(t_half + tau) - x_half (None when it has none or the window leaves the
    samples)."""
    h = _half_crossing(t, x, i0, i1)
    if h is None:
        return float(t[i0]), None
    tt = h[0] + tau
    if tt[0] < t[0] or tt[-1] > t[-1]:
        return h[0], None
    return h[0], np.interp(tt, t, x) - h[1]


def _msq(a) -> float:
    a = np.asarray(a, float)
    a = a[np.isfinite(a)]
    return float(np.mean(a * a)) if a.size else 0.0


class Judge:
    """The record on a part of it, and the error of a model there.

    The model is judged **one cycle ahead** from the record's own state
    (ch. 2.3: the baseline started from the record's state): from each
    record trough (the slider just stuck, at the level of the stick line
    there, :func:`stick_start`) the model runs on the record's drive and clock to its next slip, and its
    predicted stick (the drive's travel to the next slip's halfway crossing,
    over the mean travel of a period: a hold adds time, not load), peak and
    trough (over D) are compared with the record's, plus
    the mean slip waveform around the halfway crossing of each predicted
    slip (over D) against the record's; e = sqrt(mean of the per-cycle
    squares + mean of the waveform's squares), x alone (a triggering's line
    in the normal channel is its own statistic).  A trajectory that parts from the record's (rounding,
    chaos, a noisy rig) costs one cycle, not the rest of the record.  A
    reciprocating record whose sticks are mostly at the reversals (fewer
    slips followed by another in their stroke than strokes) is also judged on
    each stroke's first slip, the model started from the record's x at the
    stroke's start and run through the reversal (that stick's travel over
    the mean of the record's own)."""

    #: at most this many cycles are judged (an even subset; linear time)
    MAX_CYCLES = 200

    def __init__(self, pr: Prepared, c: Cycles, fn: float, lo: float, hi: float, ylow=None, gap=None):
        self.pr, self.fn, self.lo, self.hi, self.ylow = pr, fn, lo, hi, ylow
        # [lo, hi) less the held-out part ``gap`` (a, b) when the training part lies around it: a cycle is
        # judged when it lies within one piece
        win = (lo, hi) if gap is None else (lo, hi, *gap)
        self.c = c
        self.D = c.amplitude(pr.x)
        per = c.periods(pr.t)
        self.P = float(np.mean(per)) if per.size else 1.0 / fn
        k = k_all = np.flatnonzero(c.next_ok)
        # a reciprocating record whose sticks are mostly at the reversals (fewer slips followed by another
        # in the same stroke than strokes) is also judged on each stroke's first slip, predicted from the
        # stroke's start (the model started from the record's state there, as :func:`.baseline.simulate`
        # starts it) through the reversal and its dwell, where ageing shows on such a rig
        self.from_stroke = len(pr.strokes) > 1 and k.size < np.unique(c.stroke).size
        # a cycle belongs to the part its predicted slip (the next peak) lies in, wherever the stick before
        # it started: a stick through a hold can last several periods, and a boundary in time falls within
        # it in proportion (a part that began within it would never judge the slip after the hold, where
        # ageing shows); the prediction starts from the record's own state at the trough, which is no target
        tk = pr.t[c.peak_i[k + 1]]
        inside = (tk >= lo) & (tk < hi)
        if gap is not None:
            inside &= (tk < gap[0]) | (tk >= gap[1])
        k = k[inside]
        if k.size > self.MAX_CYCLES:
            k = k[np.linspace(0, k.size - 1, self.MAX_CYCLES).astype(int)]
        ends = np.array([sl.stop for sl in pr.stroke_slices()])
        # (each row: the sample it starts from, the cycle whose slip it predicts, where it starts)
        i0, tgt = c.trough_i[k], k + 1
        # each within-stroke prediction starts from the stick line's level at the trough (:func:`stick_start`)
        # (on the record's drive; a model with a modulated drive reads it on its own drive)
        self.start = [stick_start(pr, c, int(j)) for j in k]
        self._start_cache = {}
        first = np.array([], int)
        if self.from_stroke:
            first = np.array([int(np.flatnonzero(c.stroke == s)[0]) for s in np.unique(c.stroke)], int)
            j0 = np.array([pr.strokes[int(c.stroke[j])].j0 for j in first], int)
            keep = (pr.t[j0] >= lo) & (pr.t[c.trough_i[first]] < hi) & (c.peak_i[first] > j0)
            if gap is not None:
                keep &= (pr.t[c.trough_i[first]] < gap[0]) | (pr.t[j0] >= gap[1])
            first, j0 = first[keep][:self.MAX_CYCLES], j0[keep][:self.MAX_CYCLES]
            i0, tgt = np.r_[i0, j0].astype(int), np.r_[tgt, first].astype(int)
            self.start += [float(pr.x[a]) for a in j0]
        # how long the contact has rested at each prediction's start (the ageing's clock): 0 at a trough,
        # just arrested; at a stroke's start, since the record's last arrest before it (through the reversal
        # and its dwell, as :func:`.evidence.stick_times` counts that stick)
        self.rest = np.zeros(i0.size)
        last = np.searchsorted(c.trough_i, i0[k.size:]) - 1          # (the troughs are in time order)
        self.rest[k.size:] = np.where(last >= 0, pr.t[i0[k.size:]] - pr.t[c.trough_i[np.maximum(last, 0)]], 0.0)
        self._k = k
        t, x = pr.t, pr.x
        # the stick is measured in the drive's travel, not in time: the spring loads with the travel, and a
        # hold adds time, not load (a slip that comes just as the drive stops, or just after the hold, is a
        # small difference of travel, where in time it was the whole hold); with a constant drive the two are
        # the same over their scales
        self.trav = travel(np.abs(pr.vd), np.diff(t))
        pt = np.diff(self.trav[np.c_[c.peak_i[k_all], c.peak_i[k_all + 1]]], axis=1).ravel() if k_all.size else np.zeros(0)
        self.PT = float(np.mean(pt)) if pt.size and np.mean(pt) > 0 else 0.0
        if not self.PT > 0:
            self.trav, self.PT = t - t[0], self.P          # (no drive to measure in: the clock)
        # each prediction runs over twice the record's travel to its target's arrest (and at least twice its
        # samples): through a hold, until the drive has moved as far again
        span = c.trough_i[tgt] - i0
        need = self.trav[i0] + 2.0 * (self.trav[c.trough_i[tgt]] - self.trav[i0])
        far = np.searchsorted(self.trav, need) + 8
        self.slices = [slice(int(a), int(min(max(a + 2 * m + 8, f), ends[c.stroke[j]])))
                       for a, m, f, j in zip(i0, span, far, tgt)]
        self.tau = np.linspace(-0.3 / fn, 0.3 / fn, NWAVE)
        slips = [_slip(t, x, int(c.peak_i[j]), int(c.trough_i[j]) + 1, self.tau) for j in tgt]
        tslip = (np.interp([ts for ts, _ in slips], t, self.trav) - self.trav[i0]) if slips else np.zeros(0)
        # the stick's travel over its scale: the mean travel of a period within a stroke; from a stroke's start,
        # the mean of the record's travels to a stroke's first slip
        self.scale = np.full(tslip.size, self.PT)
        if first.size:
            s0 = float(np.mean(tslip[k.size:]))
            self.scale[k.size:] = s0 if s0 > 0 else self.PT
        self.rec = np.column_stack([tslip / self.scale, x[c.peak_i[tgt]] / self.D, x[c.trough_i[tgt]] / self.D]) \
            if tslip.size else np.zeros((0, 3))
        waves = [w for _, w in slips if w is not None]
        self.wave = np.mean(waves, axis=0) / self.D if waves else np.full(NWAVE, np.nan)
        # the waveform is the slip's, from its peak to its arrest (the median over the record's slips): what x
        # does after the arrest (a second mode's rebound, a sensor's ringing) is the rig's, not the friction's,
        # and no model of the slider has it; it would weigh on every model alike and dilute every gain
        edges = [(t[int(c.peak_i[j])] - ts, t[int(c.trough_i[j])] - ts) for j, (ts, w) in zip(tgt, slips)
                 if w is not None]
        if edges:
            a, b = np.median(np.asarray(edges), axis=0)
            self.wave[(self.tau < a) | (self.tau > b)] = np.nan
        self.mask = window(pr.t, win)

    def _starts(self, p: Params) -> list:
        """The within-stroke starts read on ``p``'s own drive and stick law
        (:func:`stick_start`), cached by those parameters."""
        key = (p.drv_a, p.drv_f, p.drv_ph, p.creep0, p.creep1, p.creep_m)
        if key not in self._start_cache:
            self._start_cache[key] = [stick_start(self.pr, self.c, int(j), p) for j in self._k] + \
                self.start[self._k.size:]
        return self._start_cache[key]

    def vector(self, p: Params):
        """(per-cycle differences (n, 3), waveform differences) or None.  The
        normal channel is not compared: a triggering extension's line in it
        is the effect's own statistic (a load modulation earns its gain by
        what it does to the slider, not by reproducing the line that
        detected it)."""
        pr = self.pr
        if self.rec.shape[0] < 2:
            return None
        t = pr.t
        pred = np.empty_like(self.rec)
        waves = []
        starts = self.start if not (p.drv_a or p.creep1) else self._starts(p)
        for row, sl in enumerate(self.slices):
            xs, _, state = run_slice(pr, p, self.fn, sl, starts[row], self.ylow, t_stick=self.rest[row])
            slip = np.flatnonzero(state == 0)
            tr = self.trav[sl]
            if slip.size == 0:
                pred[row] = ((tr[-1] - tr[0]) / self.scale[row], xs[-1] / self.D, xs[-1] / self.D)
                continue
            back = slip[0] + np.flatnonzero(state[slip[0]:] == 1)
            end = int(back[0]) if back.size else xs.size - 1
            ip = int(np.argmax(xs[:end + 1]))
            it = ip + int(np.argmin(xs[ip:end + 1]))
            ts, w = _slip(t[sl], xs, ip, it + 1, self.tau)
            pred[row] = ((float(np.interp(ts, t[sl], tr)) - tr[0]) / self.scale[row], xs[ip] / self.D, xs[it] / self.D)
            if w is not None:
                waves.append(w)
        dc = self.rec - pred
        dw = self.wave - (np.mean(waves, axis=0) / self.D if waves else np.full(NWAVE, np.nan))
        return dc, dw

    @staticmethod
    def combine(dc, dw, rows=None) -> float:
        """The error from the parts (``rows``: the cycles used, repeats allowed)."""
        d = dc if rows is None else dc[rows]
        return float(math.sqrt(_msq(d) + _msq(dw)))

    def scatter(self) -> np.ndarray:
        """The record's own cycle-to-cycle scatter in each per-cycle quantity
        (stick time, peak, trough, as compared): half the mean square
        difference between successive cycles within a stroke (von Neumann's
        estimate: a trend or a slow modulation drops out of it, white scatter
        does not); inf for a quantity with fewer than three such pairs."""
        k, r = self._k, self.rec[:self._k.size]
        nxt = np.flatnonzero(np.diff(k) == 1)
        out = np.full(3, np.inf)
        if nxt.size >= 3:
            d = r[nxt + 1] - r[nxt]
            ok = np.all(np.isfinite(d), axis=1)
            if np.count_nonzero(ok) >= 3:
                out = 0.5 * np.mean(d[ok] ** 2, axis=0)
        return out

    def error(self, p: Params) -> float:
        """The error of ``p`` (inf when it cannot be judged)."""
        v = self.vector(p)
        if v is None:
            return math.inf
        e = self.combine(*v)
        return e if math.isfinite(e) else math.inf


def _fit_level(pr, p: Params, fn, target, tr_mask, ylow=None, it=5):
    """Move the characteristic's level so that the simulated mean trough on
    the training part matches ``target`` (:func:`.baseline.level_to_trough`)."""
    D = float(np.ptp(p.fg)) + 0.2 * abs(p.fs - float(np.mean(p.fg))) + 1e-9

    def trough_of(q):
        xs, _, _ = simulate(pr, q, fn, ylow)
        try:
            cc = find_cycles(pr_like(pr, xs), fn, speeds=False)
        except LiengInputError:
            return None
        m = tr_mask[cc.trough_i] if cc.n else np.array([], bool)
        return float(np.mean(xs[cc.trough_i][m])) if np.any(m) else None

    return level_to_trough(p, trough_of, target, it, 0.25 * D)


#: a trend in the training part's friction level is carried by the baseline its gains are judged against
#: when its slope is beyond this many standard errors (:func:`level_trend`)
TREND_Z = 2.0


def level_trend(base: Params, pr: Prepared, c: Cycles, train: tuple) -> Params:
    """The baseline ``base`` read through an offset of x that drifts
    linearly in time (``offset``), fitted to the friction level of the
    training part ``train`` (:func:`window`): the mean of peak and trough,
    cycle by cycle, against time (turned with each stroke's direction, as x
    is; a level for each direction), when the slope lies beyond TREND_Z
    standard errors (the cycles' scatter about the line); ``base`` itself
    otherwise.  The offset is zero at the training cycles' mean time, so
    the baseline's level there is kept.

    A level that drifts over the record (a sensor's offset with temperature,
    a friction that runs in) shifts every held-out cycle's peak and trough
    alike, and the stick times with them, for the baseline and any extension
    of it: an error none of the other effects' terms removes, which would
    dilute each one's gain.  Their gains are judged against this baseline
    (``friction_drift``'s and ``load_variation``'s against the plain one:
    the trend is the one's own extension and stands for the other's slow
    course).  Only the gains: the calibrated evidence is the plain
    baseline's."""
    sel = window(pr.t[c.peak_i], train)
    if np.count_nonzero(sel) < 6:
        return base
    tt = pr.t[c.peak_i[sel]]
    lv = c.levels(pr.x)[sel]
    sign = np.array([pr.strokes[int(k)].sign for k in c.stroke[sel]], float)
    t0 = float(np.mean(tt))
    cols = [np.ones(tt.size)] + ([sign] if np.unique(sign).size > 1 else []) + [sign * (tt - t0)]
    X = np.column_stack(cols)
    if lv.size <= X.shape[1] + 2 or np.linalg.matrix_rank(X) < X.shape[1]:
        return base
    co, *_ = np.linalg.lstsq(X, lv, rcond=None)
    r = lv - X @ co
    cov = np.linalg.inv(X.T @ X) * float(np.sum(r * r)) / (lv.size - X.shape[1])
    b, se = float(co[-1]), math.sqrt(max(float(cov[-1, -1]), 0.0))
    if not abs(b) > TREND_Z * se:
        return base
    return base.copy(offset=b, offset_t0=t0)


def _per_load(base: Params, pr: Prepared, c: Cycles, fn: float, load, sel, **kw) -> list:
    """The baseline with a load term ``kw``: its static limit read per unit
    load, with the baseline's characteristic and with the characteristic
    identified again per unit load (:func:`.baseline.identify` on the
    training cycles ``sel``; the baseline's carries the load's mean course
    along the slips, the other the noise of F / load): two candidates."""
    sg, fg, fs = identify(pr, c, fn, load=load, sel=sel)
    return [base.copy(fs=fs, **kw), base.copy(sg=sg, fg=np.minimum(fg, fs), fs=fs, **kw)]


def _branches(base: Params, pr: Prepared, c: Cycles, fn: float, sel) -> Params | None:
    """The baseline with its characteristic read on each branch apart (the
    accelerating half of the slips as ``fg``, the decelerating one less it as
    ``dg``, on the baseline's grid), from the slips of the cycles ``sel``;
    None when a branch has too few samples."""
    idx, s, F, br, sid = slip_friction(pr, c, fn)
    keep = np.isin(sid, np.flatnonzero(sel))
    acc, dec = keep & (br < 0), keep & (br > 0)
    if np.count_nonzero(acc) < 8 or np.count_nonzero(dec) < 8 or base.sg.size < 2:
        return None
    sa, fa = characteristic(s[acc], F[acc])
    sd, fd = characteristic(s[dec], F[dec])
    if sa.size < 2 or sd.size < 2:
        return None
    fa_g, fd_g = np.interp(base.sg, sa, fa), np.interp(base.sg, sd, fd)
    return base.copy(fg=np.minimum(fa_g, base.fs), dg=fd_g - fa_g, delta=0.0)


#: the faded twin candidate reaches its full step at this share of the characteristic table's fastest speed
#: (stated a priori, not tuned: one value, tried once)
TWIN_FADE = 0.25


def candidates(effect: str, base: Params, pr: Prepared, c: Cycles, fn: float, st: dict, aux: dict,
               train: tuple) -> list:
    """Extended models for ``effect`` (the baseline plus one term), from the
    evidence on the training part ``train`` ((lo, hi) seconds, or (lo, hi,
    a, b) for [lo, hi) less [a, b): :func:`window`)."""
    tr_mask = window(pr.t, train)
    ctr_sel = window(pr.t[c.peak_i], train)
    target = float(np.mean(pr.x[c.trough_i[ctr_sel]])) if np.any(ctr_sel) else float(np.mean(pr.x[c.trough_i]))
    D = aux["D"]
    Fbar = max(float(np.median(base.fg)), 1e-12)
    ylow = aux.get("ylow")
    out = []

    def lvl(p, **kw):
        return _fit_level(pr, p, fn, target, tr_mask, **kw)

    if effect == "twin_branch":
        for s in (0.6, 1.0, 1.5):
            out.append(lvl(base.copy(delta=s * st["twin_branch"] * D)))
            # the step all on the decelerating branch: the slip starts on the baseline's characteristic
            out.append(lvl(base.copy(dg=np.full(base.sg.size, s * st["twin_branch"] * D))))
        # the step split about the baseline's characteristic (the accelerating branch below it by half,
        # the decelerating one above by half: the baseline's is read on both halves of the slips alike) and
        # faded in from the release over TWIN_FADE of the table's speeds: at the release the slip starts on
        # the baseline's own characteristic, whose value there the sticks' rounded tops fixed (a step at
        # the release moved every predicted slip early, by up to 2 % of the period on `lugre`'s twins, where its
        # branches meet at low speed); levelled, and as it comes
        top = float(np.max(base.sg)) if base.sg.size else 0.0
        if top > 0:
            ramp = np.clip(base.sg / (TWIN_FADE * top), 0.0, 1.0)
            for s in (0.6, 1.0, 1.5):
                d = s * st["twin_branch"] * D
                q = base.copy(fg=np.minimum(base.fg - 0.5 * d * ramp, base.fs), dg=d * ramp)
                out.append(lvl(q))
                if s == 1.0:
                    out.append(q)
        # two branches of general shape (ch. 4.1's loops), each read by the reverse construction on the
        # training slips; their difference also scaled to the effect size (the reading less the baseline's
        # own)
        tw = _branches(base, pr, c, fn, ctr_sel)
        if tw is not None:
            out.append(lvl(tw))
            m = float(np.mean(tw.dg))
            if m * st["twin_branch"] > 0:
                out.append(lvl(tw.copy(dg=tw.dg * (st["twin_branch"] * D / m))))
    elif effect == "load_variation" and ylow is not None:
        idx, s, F, br, sid = slip_friction(pr, c, fn)
        m = tr_mask[idx]
        if np.count_nonzero(m) > 10:
            ss = s[m] / max(float(np.std(s[m])), 1e-12)
            yl = ylow[idx][m]
            A = np.column_stack([np.ones(ss.size), ss, ss ** 2, ss ** 3, br[m], yl - np.mean(ylow)])
            kf = float(np.linalg.lstsq(A, F[m], rcond=None)[0][5]) / Fbar
            # the regression carries the baseline's own bias (its replicates' mean): scaled to the effect size
            raw, size = st.get("load_variation_raw"), st.get("load_variation")
            if raw and size and raw * size > 0:
                kf *= float(np.clip(size / raw, 0.2, 5.0))
            elif raw and size:
                kf = math.copysign(abs(kf), kf * size / raw)
            if aux.get("y_is_force"):
                kf = 1.0 / abs(float(np.mean(ylow)))      # Amontons: the load factor is N / mean N
            for sc in (0.7, 1.0, 1.4):
                k = sc * kf
                # the characteristic and the static limit read again per unit load (F / load): the
                # baseline's carry the load's mean course along the slips
                ld = 1.0 + k * (ylow - np.mean(ylow))
                if np.all(ld[c.peak_i[ctr_sel]] > 0.05):
                    out += [lvl(q, ylow=ylow) for q in _per_load(base, pr, c, fn, np.maximum(ld, 0.05), ctr_sel,
                                                                 load_k=k)]
                    # the same load with its part locked to x following the model's own x (played back in
                    # time, a load locked to the record's slips would arrest a model's slip that runs early)
                    lk = locked_load(pr, c, ylow, k)
                    if lk["load_lock"]:
                        out += [lvl(q, ylow=ylow) for q in _per_load(base, pr, c, fn, np.maximum(ld, 0.05),
                                                                     ctr_sel, **lk)]
                if base.y_c[1]:
                    kx, xref = k * base.y_c[1], float(np.mean(pr.x))
                    ld = 1.0 + kx * (pr.x - xref)
                    if np.all(ld[c.peak_i[ctr_sel]] > 0.05):
                        out += [lvl(q) for q in _per_load(base, pr, c, fn, np.maximum(ld, 0.05), ctr_sel,
                                                          load_kx=kx, load_xref=xref)]
    elif effect == "static_ageing":
        k, ts, pk = stick_times(pr, c)
        # the peak's growth from all sticks and from those between two slips alone (a hold in which x
        # relaxes gives the stick through it a lower peak than its duration alone would)
        # (a stick is the training part's when the peak it ends in is, as the judged cycles are)
        sels = [ctr_sel[k + 1]]
        if not np.array_equal(sels[0], sels[0] & c.next_ok[k]):
            sels.append(sels[0] & c.next_ok[k])
        vl = stick_loading(pr, c, k)
        for sel in sels:
            if np.count_nonzero(sel) < 4 or np.ptp(np.log(ts[sel])) <= 0:
                continue
            b, a0 = np.polyfit(np.log(ts[sel]), pk[sel], 1)
            for ftau in (0.01, 0.1, 0.5):
                tau = ftau * float(np.min(ts[sel]))
                fs = max(a0 + b * math.log(tau), 0.2 * base.fs)
                for sc in (0.8, 1.0, 1.25):
                    out.append(lvl(base.copy(age_tau=tau, fs=fs, age_a=sc * b / fs)))
            # a stepped drive: the peak also follows the loading velocity (rate-dependent static friction,
            # the direct effect of a rate-and-state law), which the stick time alone cannot carry across steps
            lv = np.log(np.maximum(vl[sel], 1e-300))
            if np.count_nonzero(sel) >= 6 and np.all(vl[sel] > 0) and np.ptp(lv) > 0.3:
                vref = float(np.exp(np.min(lv)))    # the slowest loading: the term adds nothing there
                for ftau in (0.1, 0.5, 2.0):
                    # the core's own law, fitted as it applies it: FS (1 + a ln(1 + ts/tau) + r ln(vl/vref))
                    tau = ftau * float(np.min(ts[sel]))
                    X = np.column_stack([np.ones(lv.size), np.log1p(ts[sel] / tau), lv - math.log(vref)])
                    if np.linalg.cond(X - np.r_[0.0, X[:, 1:].mean(0)]) > 1e3:
                        continue
                    fs, b, r = np.linalg.lstsq(X, pk[sel], rcond=None)[0]
                    if b > 0 and r > 0 and fs > target:     # a limit below the troughs would not arrest
                        for sc in (0.8, 1.0, 1.25):
                            out.append(lvl(base.copy(age_tau=tau, fs=fs, age_a=sc * b / fs, age_r=sc * r / fs,
                                                     age_v=vref)))
    elif effect == "triggering":
        f_tr = aux["f_tr"]
        if f_tr > 0:
            tt = pr.t[tr_mask]
            # refine the frequency on the training part (sub-bin), on y or x above 2 fn
            sig = (pr.y if pr.y is not None else pr.x)[tr_mask]
            hp = sig - lowpass(sig, pr.dt, 2 * fn)
            f_tr = refine_line(hp, tt, f_tr)
            idx, s, F, br, sid = slip_friction(pr, c, fn)
            m = tr_mask[idx]
            ti = pr.t[idx][m]
            ss = s[m] / max(float(np.std(s[m])), 1e-12)
            A = np.column_stack([np.ones(ti.size), ss, ss ** 2, br[m], np.sin(2 * math.pi * f_tr * ti),
                                 np.cos(2 * math.pi * f_tr * ti)])
            co = np.linalg.lstsq(A, F[m], rcond=None)[0]
            eps = float(math.hypot(co[4], co[5])) / Fbar
            ph = float(math.atan2(co[5], co[4]))
            ax_, phx = line_fit(pr.x[tr_mask] - lowpass(pr.x[tr_mask], pr.dt, 2 * fn), tt, f_tr)
            kw = dict(trig_f=f_tr, trig_ax=ax_, trig_phx=phx)
            for sc in (0.0, 0.5, 1.0):
                out.append(lvl(base.copy(trig_eps=sc * eps, trig_ph=ph, **kw)))
            if not aux.get("y_is_force"):
                # the modulation x's line implies in the training slips (less the sticks'), read on x itself
                # (:func:`.evidence.trig_modulation`, the evidence's size): the reverse construction above is
                # smoothed over a quarter natural period, which attenuates a line several times fn
                e2, _, _, ph2 = trig_modulation(pr, subset(c, ctr_sel), fn, f_tr, D, phase=True)
                if 0.0 < e2 < 1.0:
                    # the phase at which the load sets the slips off, fitted on the training cycles: the line
                    # in the slips gives the friction's phase there, but when a slip starts also depends on
                    # what the record does not show (a sensor's lag, how the static limit follows the load)
                    # (on the baseline's level: a modulation about 1 moves the mean trough little, and the
                    # best is levelled again as it is refined, its size scaled; levelling each candidate
                    # simulates the whole record several times)
                    for j in range(1, 8):
                        out.append(base.copy(trig_eps=e2, trig_ph=ph2 + j * math.pi / 4, **kw))
                    out.append(lvl(base.copy(trig_eps=e2, trig_ph=ph2, **kw)))
    elif effect == "drive_modulation":
        ts, r = _stick_series(pr, subset(c, ctr_sel))
        per = c.periods(pr.t)
        if r.size >= 5 and per.size >= 2:
            f_ss = 1.0 / float(np.median(per))
            span = float(ts[-1] - ts[0])
            # the frequency from the training sticks; with fewer than 8 of them, the evidence's (whole record)
            f = aux.get("f_drive") or 0.0
            if r.size >= 8:
                _, f, _, _ = drive_scan(ts, r, max(2.0 / span, 0.02 * f_ss), 0.5 * f_ss, nperm=0)
            if not f > 0:
                return out

            def fit(fq):
                B = np.column_stack([np.ones(ts.size), np.sin(2 * math.pi * fq * ts), np.cos(2 * math.pi * fq * ts)])
                co = np.linalg.lstsq(B, r, rcond=None)[0]
                return float(np.sum((B @ co - r) ** 2)), co

            # the scan's grid is about a bin wide: refine (a phase that slips over the held-out part costs it all)
            f = float(min(f + np.linspace(-1.0, 1.0, 41) / max(span, 1e-12), key=lambda fq: fit(fq)[0]))
            co = fit(f)[1]
            for sc in (0.8, 1.0, 1.2):
                out.append(lvl(base.copy(drv_f=float(f), drv_a=sc * float(math.hypot(co[1], co[2]) / co[0]),
                                         drv_ph=float(math.atan2(co[2], co[1])))))
    elif effect == "friction_drift":
        lvl_c = c.levels(pr.x)
        tt = pr.t[c.peak_i]
        pos = pr.pos[c.peak_i] if pr.pos is not None else tt
        if ctr_sel.sum() >= 6:
            _, co, f = level_fit(tt[ctr_sel], pos[ctr_sel], lvl_c[ctr_sel], aux.get("f_level") or None)
            mean = max(abs(float(co[0])), 1e-12)
            t0 = float(np.mean(tt[ctr_sel]))
            amp, ph = float(math.hypot(co[2], co[3])), float(math.atan2(co[3], co[2]))
            for sc in (0.7, 1.0, 1.3):
                out.append(lvl(base.copy(drift=sc * float(co[1]) / mean, drift_t0=t0, level_a=sc * amp / mean,
                                         level_f=f, level_ph=ph)))
    elif effect == "creep":
        for sc in (1.0, 2.0, 4.0):
            out.append(lvl(base.copy(creep1=float(np.clip(sc * st["creep"], 0.0, 0.9)))))
    return out


def gain_folds(pr: Prepared, c: Cycles, fn: float, fits: list, ylow=None, nboot: int = 200, seed: int = 1) -> dict:
    """Errors of the baseline and the extension on held-out parts, each
    judged with the models fitted without it: ``fits`` lists (test_lo,
    test_hi, base, ext).  e**2 is the cycle-weighted mean over the parts of
    each part's squared error (:meth:`Judge.combine`); gain = 1 - e_ext /
    e_base with a 90 % interval from resampling the held-out cycles within
    each part.  Beside it, ``gain_explainable``: the same on the part of
    the squares a model can remove, each less the record's own
    cycle-to-cycle scatter in the per-cycle quantities
    (:meth:`Judge.scatter`, capped at either model's own error variance
    there, so that it is never more than either leaves), with its interval
    and ``scatter_share``, that scatter's share of e_base**2: on a record
    whose sticks scatter at random (a random breakaway) the whole-error gain
    of an extension that removes what it can is small, and the two together
    say so.  Both have the sign of e_base - e_ext, resample by resample
    (the named test, :func:`unconfirmed`, reads the first).  The traces
    (``x_base``, ``x_ext``) are the first fit's."""
    parts = []
    for lo, hi, base, ext in fits:
        J = Judge(pr, c, fn, lo, hi, ylow)
        vb = J.vector(base)
        ve = J.vector(ext) if ext is not base else vb
        if vb is not None and ve is not None:
            parts.append((J, vb, ve, ext is not base))
    base, ext = fits[0][2], fits[0][3]
    if not parts:
        return dict(e0=0.0, e1=0.0, gain=0.0, interval=[0.0, 0.0], x_base=None, x_ext=None, parts=0,
                    gain_explainable=0.0, interval_explainable=[0.0, 0.0], scatter_share=0.0)
    n = np.array([vb[0].shape[0] for _, vb, _, _ in parts], float)
    w = n / n.sum()

    vn = [J.scatter() for J, _, _, _ in parts]

    def errors(picks=None):
        """(e_base, e_ext, the gain of the explainable error, the scatter's share of e_base**2)."""
        e0 = e1 = f = 0.0
        for j, (J, vb, ve, _) in enumerate(parts):
            rows = None if picks is None else picks[j]
            e0 += w[j] * J.combine(*vb, rows=rows) ** 2
            e1 += w[j] * J.combine(*ve, rows=rows) ** 2
            # the part of the per-cycle squares no model can remove: the record's own scatter, at most
            # either model's own error variance in each quantity (the squares stay above it)
            db, de = (v[0] if rows is None else v[0][rows] for v in (vb, ve))
            with np.errstate(invalid="ignore"):
                fl = np.minimum(vn[j], np.minimum(np.nanvar(db, axis=0), np.nanvar(de, axis=0)))
            f += w[j] * float(np.mean(np.where(np.isfinite(fl), fl, 0.0)))
        a, b = max(e0 - f, 0.0), max(e1 - f, 0.0)
        return (math.sqrt(e0), math.sqrt(e1), 1.0 - math.sqrt(b / a) if a > 0 else 0.0,
                f / e0 if e0 > 0 else 0.0)

    e0, e1, gx, share = errors()
    try:
        x_base = simulate(pr, base, fn, ylow)[0]
        x_ext = simulate(pr, ext, fn, ylow)[0] if ext is not base else x_base
    except LiengInputError:
        x_base = x_ext = None
    g = 1.0 - e1 / e0 if e0 > 0 else 0.0
    # interval: resample the held-out cycles (each with its one-cycle-ahead prediction), part by part
    rng = np.random.default_rng(seed)
    gs, gxs = [], []
    if np.all(n >= 3) and any(p[3] for p in parts):
        for _ in range(nboot):
            a, b, gxb, _ = errors([rng.integers(0, int(m), int(m)) for m in n])
            if a > 0:
                gs.append(1.0 - b / a)
                gxs.append(gxb)
    iv = [float(np.percentile(gs, 5)), float(np.percentile(gs, 95))] if len(gs) >= 20 else [g, g]
    ivx = [float(np.percentile(gxs, 5)), float(np.percentile(gxs, 95))] if len(gxs) >= 20 else [gx, gx]
    g = float(np.clip(g, -1e6, 1.0))
    clip = lambda v: float(np.clip(v, -1e6, 1.0))
    return dict(e0=e0, e1=e1, gain=g, interval=[clip(v) for v in iv], x_base=x_base,
                x_ext=x_ext, parts=len(parts), gain_explainable=clip(gx), interval_explainable=[clip(v) for v in ivx],
                scatter_share=float(share))


def unconfirmed(g: dict, has_candidates: bool, direct: bool = False) -> str | None:
    """Why a significant effect is not confirmed by prediction, or None.

    An effect whose evidence is read through the model (the slips' shape,
    the peaks, the sticks) is **named** only when its nested extension also
    predicts the held-out cycles better than the baseline: the lower end of
    the gain's 90 % interval (``g`` from :func:`gain_folds`) above 0 (a
    one-sided 5 % test that the extension does not help).  The test adds to
    the calibrated detection (:func:`.decide.decide`) and can only lower its
    false-alarm rate.  Not applied (None) when the effect is measured
    directly (``direct``: a normal force that varies with the motion is its
    own evidence, however little the extension gains on a baseline whose
    characteristic already carries it), when no extension exists for it
    (``has_candidates`` false) or when no held-out part could be judged."""
    if direct or not has_candidates or not g.get("parts"):
        return None
    lo, hi = g["interval"]
    if lo > 0.0:
        return None
    if g["e1"] == g["e0"]:
        return "no extension beats the baseline on the training part"
    return (f"its extension does not predict the held-out cycles better than the baseline (gain {g['gain']:+.2f}, "
            f"90 % interval {lo:+.2f} to {hi:+.2f})")


#: the parameter each extension scales (refined on the training error)
SCALED = {"twin_branch": ("delta", "dg"), "load_variation": ("load_k", "load_kx"), "static_ageing": ("age_a", "age_r"),
          "triggering": ("trig_eps",), "drive_modulation": ("drv_a",), "friction_drift": ("drift", "level_a"),
          "creep": ("creep1",)}


#: records longer than this (samples) refine their extension with fewer golden-section steps, in proportion
#: (at least REFINE_MIN_STEPS): each step simulates the whole record several times, and the search's last
#: steps move the factor by less than the scatter of a long record's gain (the scale limit: 750 000 samples
#: in under a minute)
REFINE_FULL = 250_000
REFINE_MIN_STEPS = 4


def refine(effect: str, best: Params, base: Params, judge: "Judge", pr, fn, target_mask, target,
           ylow=None, it: int = 8) -> tuple:
    """Scale the extension's own parameter(s) of ``best`` by a factor in
    [0, 2] chosen by golden-section search on the training error (the level
    refitted each time; ``it`` steps, fewer on a record longer than
    REFINE_FULL samples).  Returns (params, training error)."""
    if pr.x.size > REFINE_FULL:
        it = max(REFINE_MIN_STEPS, min(it, int(it * REFINE_FULL / pr.x.size)))
    names = [n for n in SCALED.get(effect, ()) if getattr(best, n) is not None and np.any(getattr(best, n))]
    if not names:
        return best, judge.error(best)

    made = {}

    def make(f):
        if f not in made:          # (each simulates the whole record several times: once per factor)
            q = best.copy(**{n: f * getattr(best, n) for n in names})
            made[f] = _fit_level(pr, q, fn, target, target_mask, ylow=ylow if q.load_k else None)
        return made[f]

    def cost(f):
        e = judge.error(make(f))
        return e if math.isfinite(e) else 1e300

    g = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = 0.2, 2.0
    c1, c2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = cost(c1), cost(c2)
    for _ in range(it):
        if f1 < f2:
            b, c2, f2 = c2, c1, f1
            c1 = b - g * (b - a)
            f1 = cost(c1)
        else:
            a, c1, f1 = c1, c2, f2
            c2 = a + g * (b - a)
            f2 = cost(c2)
    f = c1 if f1 < f2 else c2
    e1 = min(f1, f2)
    # against the candidate as it came (levelled already): levelled again at factor 1 it may come out
    # elsewhere (the level's search ends at the best level it simulated, which need not be the one the
    # candidate came with), and the candidate itself must not be lost
    e_best = judge.error(best)
    e_best = e_best if math.isfinite(e_best) else 1e300
    return (make(f), e1) if e1 < e_best else (best, e_best)
