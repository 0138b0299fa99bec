"""Stage 3 of ``lieng diagnose``: the thesis's model as the baseline, and the
simulator its extensions share.

The baseline is the 1-DoF model of ch. 2.3: a dynamometer of natural
frequency fn, a **single-valued characteristic of general shape** phi(s) of
the sliding velocity s = v0 - x', a static limit FS, the small relative
velocity in stick of ch. 2.3.1.1 (the stick velocity a fraction
1 - c0 - c1 r**m of the drive, r the spring force over the static limit: the
stick branch is a steep line of finite slope, so the slider creeps more as
the force nears the limit; m sets how near the limit), constant load and drive, started from the record's own state at
the start of every stroke.  It is identified from the record:

* phi by the **reverse construction pooled over slips**: during slip the
  friction is F = x + x''/wn**2 (the centre of curvature of the trajectory
  in the Lienard plane, TRC's XX); F is binned by s (quantile bins) and the
  median of each bin is a point of the table (damping cannot be told from
  the slope of phi and is part of it);
* FS, the median peak; c0, c1 and m from the slope of x in the sticks;
* then the level of phi is moved until the simulated mean trough matches the
  record's (the smoothing of x'' biases the level, not the shape).  Below
  RESOLVED samples per natural period a slip has too few samples for x'':
  phi is then its level alone (a constant kinetic friction), the part of the
  characteristic such a record resolves.

The simulator (:func:`simulate`) runs the compiled slider core
(``fortran/modern/slider.f90``) stroke by stroke with the extensions' parameters
(:class:`Params`), each zero in the baseline.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

import numpy as np


from lieng import _core
from lieng.errors import LiengInputError
from lieng import status as st
from lieng.diagnose.signals import resonance
from lieng.diagnose.segment import Cycles, Prepared, creep_pairs, slip_seconds, stick_part, stick_ratios, travel

__all__ = ["Params", "simulate", "run_slice", "fit_baseline", "identify", "slip_friction", "calibrate_fn"]

#: quantile bins of the sliding velocity for the characteristic's table
NBINS = 10


@dataclass
class Params:
    """The slider's parameters (mm, s) and the model of the normal channel.

    The baseline sets ``fs``, ``sg``/``fg`` (the characteristic), ``creep0``
    and the locked model of y (``y_c``); every extension term is zero in it.
    """

    fs: float
    sg: np.ndarray
    fg: np.ndarray
    zeta: float = 0.0
    creep0: float = 0.0
    creep1: float = 0.0            # creep growing towards the static limit
    creep_m: float = 4.0           # as (x / limit)**creep_m
    delta: float = 0.0             # twin: decelerating minus accelerating branch (mm)
    dg: np.ndarray | None = None   # twin of general shape: the decelerating branch less fg at sg (mm)
    age_a: float = 0.0             # ageing: FS (1 + a ln(1 + ts/tau))
    age_tau: float = 0.01
    age_r: float = 0.0             # rate-dependent static friction: ... + r ln(vl / age_v), vl the loading velocity
    age_v: float = 1.0             # (mm/s)
    load_k: float = 0.0            # exogenous: load = 1 + load_k * (ylow - mean), ylow measured
    load_kx: float = 0.0           # coupled: load += load_kx * (x - load_xref)
    load_xref: float = 0.0
    load_lock: float = 0.0         # the measured channel's part locked to x (ylow per mm): taken out of
                                   # the played-back channel, its load following the model's x (load_kx)
    trig_eps: float = 0.0          # load *= 1 + eps sin(2 pi f t + ph)
    trig_f: float = 0.0
    trig_ph: float = 0.0
    drv_a: float = 0.0             # vd *= 1 + a sin(2 pi f t + ph)
    drv_f: float = 0.0
    drv_ph: float = 0.0
    drv_steady: bool = False       # on a recorded reciprocating drive made steady (Prepared.vd_steady)
    drift: float = 0.0             # friction level: load *= 1 + drift (t - drift_t0)
    drift_t0: float = 0.0
    level_a: float = 0.0           # ... * (1 + level_a sin(2 pi level_f travel + level_ph)), travel in mm
    level_f: float = 0.0
    level_ph: float = 0.0
    trig_ax: float = 0.0           # the triggering line superposed on x: ax sin(2 pi f t + phx)
    trig_phx: float = 0.0
    y_c: tuple = (0.0, 0.0, 0.0)   # y = c0 + c1 x + c2 x' (the part of y locked to the motion)
    offset: float = 0.0            # x recorded with an offset drifting in time: + sign offset (t - offset_t0)
    offset_t0: float = 0.0         # (mm/s; sign the stroke's direction, x being turned forward stroke by stroke)
    rig_f: float = 0.0             # x recorded through a resonance of the rig or its sensor (Hz; 0: none;
    rig_zeta: float = 0.0          # the replicates' only) and its damping ratio

    def copy(self, **kw) -> "Params":
        q = Params(**{f.name: getattr(self, f.name) for f in fields(self)})
        for k, v in kw.items():
            setattr(q, k, v)
        return q

    def to_json(self) -> dict:
        d = {}
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name.startswith("rig_") and not self.rig_f:
                continue
            if f.name in ("sg", "fg", "dg"):
                d[f.name] = [float(a) for a in v] if v is not None else None
            elif f.name == "y_c":
                d.update(y_c0=float(v[0]), y_cx=float(v[1]), y_cv=float(v[2]))
            else:
                d[f.name] = float(v)
        return d


def _sin(t, f, ph):
    return np.sin(2 * math.pi * f * t + ph)


def simulate(pr: Prepared, p: Params, fn: float, ylow=None, x0=None):
    """Simulate the slider on the prepared record's grid, stroke by stroke.

    Parameters
    ----------
    pr : Prepared
        The record (its time grid, drive and strokes).
    p : Params
        The model.
    fn : float
        Natural frequency (Hz).
    ylow : ndarray, optional
        The low-passed normal channel (for the exogenous load term).
    x0 : ndarray, optional
        The displacement to start each stroke from (default: the record's).

    Returns
    -------
    x, v, state : ndarray
        Displacement (mm), velocity (mm/s), 1 in stick / 0 in slip.
    """
    xs, vs, ss = [], [], []
    rest = 0.0           # how long the contact has been stuck at a stroke's start (unknown at the record's)
    for k, sl in enumerate(pr.stroke_slices()):
        start = float(pr.x[sl][0] if x0 is None else x0[k])
        if k and sl.start > 0:
            rest += float(pr.t[sl.start] - pr.t[sl.start - 1])     # (a dwell cut out between the strokes)
        x, v, state = run_slice(pr, p, fn, sl, start, ylow, t_stick=rest)
        rest = stuck_for(pr.t[sl], state, rest)
        xs.append(x)
        vs.append(v)
        ss.append(state)
    return np.concatenate(xs), np.concatenate(vs), np.concatenate(ss)


def stuck_for(t, state, rest: float = 0.0) -> float:
    """How long the slider has been stuck at the last of the samples
    ``t`` (its states ``state``, 1 in stick), having been stuck for
    ``rest`` at the first: the contact rests through a reversal and its
    dwell, and a static limit that ages keeps its clock across them."""
    if state.size == 0:
        return rest
    if state[-1] != 1:
        return 0.0
    slip = np.flatnonzero(state != 1)
    return float(t[-1] - t[slip[-1] + 1]) if slip.size else rest + float(t[-1] - t[0])


def model_drive(pr: Prepared, p: Params, sl: slice):
    """The drive velocity the model ``p`` runs on over the samples ``sl``:
    the record's (or, with ``drv_steady``, its steady course,
    :func:`.segment.steady_drive`), modulated as ``p`` says (``drv_a``)."""
    src = pr.vd_steady if p.drv_steady and pr.vd_steady is not None else pr.vd
    vdd = src[sl].astype(float).copy()
    if p.drv_a:
        vdd = vdd * (1.0 + p.drv_a * _sin(pr.t[sl], p.drv_f, p.drv_ph))
    return vdd


def run_slice(pr: Prepared, p: Params, fn: float, sl: slice, start: float, ylow=None, t_stick: float = 0.0):
    """The slider on the samples ``sl`` of the record's grid (within one
    stroke), started in stick at the displacement ``start``, stuck for
    ``t_stick`` seconds already (the ageing's clock): (x, v, state)."""
    dt = pr.dt
    if sl.stop - sl.start < 2:
        n = max(sl.stop - sl.start, 0)
        return np.full(n, float(start)), pr.vd[sl].astype(float), np.ones(n, np.int32)
    wn = 2 * math.pi * fn
    nsub = max(4, int(math.ceil(dt * wn / 0.05)))
    sg = np.ascontiguousarray(p.sg, float)
    fg = np.ascontiguousarray(p.fg, float)
    t = pr.t[sl]
    vdd = model_drive(pr, p, sl)
    load = np.ones_like(t)
    if p.load_k and ylow is not None:
        load = load + p.load_k * (ylow[sl] - np.mean(ylow) - p.load_lock * (pr.x[sl] - p.load_xref))
    if p.trig_eps:
        load = load * (1.0 + p.trig_eps * _sin(t, p.trig_f, p.trig_ph))
    if p.drift:
        load = load * (1.0 + p.drift * (t - p.drift_t0))
    if p.level_a and pr.pos is not None:
        load = load * (1.0 + p.level_a * np.sin(2 * math.pi * p.level_f * pr.pos[sl] + p.level_ph))
    load = np.maximum(load, 0.05)
    dg = np.zeros_like(sg) if p.dg is None else np.ascontiguousarray(p.dg, float)
    off = 0.0
    if p.offset:
        sgn = next((s.sign for s in pr.strokes if s.j0 <= sl.start < s.j0 + s.n), 1)
        off = sgn * p.offset * (t - p.offset_t0)
        start = float(start) - float(off[0])
    x, v, state, status = _core.core_slider(dt, nsub, vdd, load, wn, p.zeta, p.fs, sg, fg, p.delta, dg,
                                            p.age_a, max(p.age_tau, 1e-3 * dt), p.age_r, max(p.age_v, 1e-12),
                                            p.load_kx, p.load_xref, p.creep0, p.creep1, p.creep_m,
                                            float(start), max(float(t_stick), 0.0))
    if status != st.OK:
        raise LiengInputError(f"the slider simulation failed ({st.name(status)}): check --fn and the record's units")
    x = x + off
    if p.trig_ax:
        x = x + p.trig_ax * _sin(t, p.trig_f, p.trig_phx)
    if p.rig_f > 0:
        x = resonance(x, dt, p.rig_f, p.rig_zeta)
    return x, v, state


def slip_samples(c: Cycles, n: int):
    """The inner samples of every slip (peak to trough, less an eighth at
    each end), with the branch: -0.5 before the sliding speed peaks, +0.5
    after; and the slip number of each sample."""
    idx, br, sid = [], [], []
    for j, (pk, tr) in enumerate(zip(c.peak_i, c.trough_i)):
        m = tr - pk
        if m < 4:
            continue
        cut = max(1, m // 8) if m >= 8 else 0
        seg = np.arange(pk + cut, tr + 1 - cut)
        seg = seg[seg < n]
        if seg.size < 3:
            continue
        kmin = int(np.argmin(c.v[seg]))
        idx.append(seg)
        br.append(np.where(np.arange(seg.size) <= kmin, -0.5, 0.5))
        sid.append(np.full(seg.size, j))
    if not idx:
        return np.array([], int), np.array([]), np.array([], int)
    return np.concatenate(idx), np.concatenate(br), np.concatenate(sid)


def slip_friction(pr: Prepared, c: Cycles, fn: float, x=None):
    """The reverse construction in the slips: (indices, sliding velocity s,
    friction F = x + x''/wn**2, branch, slip number)."""
    x = pr.x if x is None else x
    idx, br, sid = slip_samples(c, x.size)
    wn = 2 * math.pi * fn
    F = x[idx] + c.a[idx] / wn ** 2
    s = pr.vd[idx] - c.v[idx]
    return idx, s, F, br, sid


def characteristic(s, F, nbins: int = NBINS):
    """A single-valued table phi(s) from pooled (s, F): medians in quantile
    bins of s (s > 0), increasing in s."""
    ok = s > 0
    s, F = s[ok], F[ok]
    if s.size < 2 * nbins:
        nbins = max(2, s.size // 4)
    if s.size < 4:
        return np.array([0.0]), np.array([float(np.median(F)) if F.size else 0.0])
    q = np.quantile(s, np.linspace(0, 1, nbins + 1))
    sg, fg = [], []
    for a, b in zip(q[:-1], q[1:]):
        m = (s >= a) & (s <= b)
        if np.count_nonzero(m) >= 2:
            sg.append(float(np.median(s[m])))
            fg.append(float(np.median(F[m])))
    sg, fg = np.asarray(sg), np.asarray(fg)
    keep = np.r_[True, np.diff(sg) > 1e-12 * max(1.0, float(np.max(np.abs(sg))))]
    return sg[keep], fg[keep]


#: the creep's exponents tried (r**m: 4 a rise spread over the stick; 48
#: creep gathered in the last few per cent before the static limit)
CREEP_M = (4.0, 6.0, 8.0, 12.0, 16.0, 24.0, 32.0, 48.0)


#: the part of a stick its start is read on (:func:`stick_start`): past a rebound after the arrest, before a
#: creeping top
START_PART = (0.3, 0.6)


def stick_start(pr: Prepared, c: Cycles, k: int, p: Params | None = None) -> float:
    """The record's state at the start of stick ``k`` (trough ``k`` to peak
    ``k + 1``): the stick line's level at the trough, x read against the
    drive's travel over the stick's early middle (:data:`START_PART`).  A
    rig that rings or rebounds after the arrest (a second mode, a contact
    lag) puts its trough below the level the stick then rises from; the
    1-DoF slider arrests at that level.  (Not read further into the stick:
    a stick that creeps before its slip, its top rounded, would lean the
    line and raise its level above the trough it rose from.)  The travel is that of the drive the model ``p`` runs on
    (:func:`model_drive`: a modulated drive's own, so that a model
    of the modulation reads the stick on its own drive); the record's drive
    when ``p`` is None.  The trough itself when the stick is too short for a
    line (fewer than 8 samples), when the record's drive holds or steps by
    more than a factor 2 within it (its 10th percentile there below half
    its 90th: x may relax in a hold) or when its line does not rise with
    the drive.  A model ``p`` whose stick creeps towards the limit (ch.
    2.3.1.1's c1 r**m) reads its line in its own stick law: x through
    G(x) = integral of dx / (1 - c0 - c1 (x / peak)**m) against the travel,
    the level G's inverse of the line's (a straight line when c1 is 0: the
    same level)."""
    a, b = int(c.trough_i[k]), int(c.peak_i[k + 1])
    seg = stick_part(c, k, START_PART)
    x0 = float(pr.x[a])
    if seg.size < 8:
        return x0
    lo_v, hi_v = np.percentile(pr.vd[a:b + 1], [10, 90])
    if not lo_v > 0.5 * hi_v:
        return x0     # a hold or a step within the stick: x may relax there, the line is not the state
    vd = pr.vd[a:seg[-1] + 1] if p is None else model_drive(pr, p, slice(a, int(seg[-1]) + 1))
    X = travel(vd, pr.dt)[seg - a]
    if not np.ptp(X) > 0:
        return x0
    top = float(pr.x[b])
    if p is not None and p.creep1 > 0 and top > 0:
        # the stick read in the model's own law: G(x) rises as the travel does
        lo_x = min(float(np.min(pr.x[a:b + 1])), 0.0)
        xg = np.linspace(lo_x, top, 801)
        ig = 1.0 / np.maximum(1.0 - p.creep0 - p.creep1 * np.clip(xg / top, 0.0, 1.0) ** p.creep_m, 1e-3)
        g = travel(ig, np.diff(xg))          # (the cumulative trapezoid of 1 / the stick law over x)
        slope, gl = np.polyfit(X, np.interp(pr.x[seg], xg, g), 1)
        level = float(np.interp(gl, g, xg))
    else:
        slope, level = np.polyfit(X, pr.x[seg], 1)
    # a stick line that rises with the drive, its level between the trough and the peak
    if not (slope > 0 and x0 - 0.5 * (top - x0) <= level <= top):
        return x0
    return float(level)


def stick_creep(pr: Prepared, c: Cycles) -> tuple:
    """The relative velocity in stick (ch. 2.3.1.1): (c0, c1, m) of the stick
    velocity vd (1 - c0 - c1 r**m), r = x / limit.  c0 is one minus the
    median stick slope over the drive in the stick's middle half, unless the
    slope in the last fifth of the rise is below the middle's by more than
    three times its scatter: then the stick's slope over the drive is read
    in tenths of its rise from 30 to 97 % (the median over the sticks),
    against the median of (mean r there)**m as the record's x reads it (r = x
    over the stick's final peak), and (c0, c1) is
    the least-squares line through them (weighted by their scatter) for the
    exponent m of :data:`CREEP_M` that fits best; c1 is then set so that the
    model's stick needs the drive travel the record's median stick takes per
    unit of the limit (its last 3 %, where the creep is fastest, is in no
    window)."""
    r = stick_ratios(pr, c, (0.25, 0.75))[1]
    if r.size < 3:
        return 0.0, 0.0, 4.0
    c0 = 1.0 - float(np.median(r))
    se = 1.2533 * float(np.std(r)) / math.sqrt(r.size)
    c0 = float(np.clip(c0, 0.0, 0.5)) if abs(c0) > 3 * se else 0.0
    mid, late = creep_pairs(pr, c)
    if mid.size < 4:
        return c0, 0.0, 4.0
    d = 1.0 - late / np.where(mid != 0, mid, np.nan)
    d = d[np.isfinite(d)]
    if d.size < 4:
        return c0, 0.0, 4.0
    m, e = float(np.median(d)), 1.2533 * float(np.std(d)) / math.sqrt(d.size)
    if not m > 3 * e:
        return c0, 0.0, 4.0
    edges = np.r_[np.arange(0.3, 0.91, 0.1), 0.97]
    a, w, rx = [], [], []
    for part in zip(edges[:-1], edges[1:]):
        _, ra, k = stick_ratios(pr, c, part, index=True)
        if ra.size < 3:
            continue
        a.append(float(np.median(ra)))
        w.append(ra.size / max(1.2533 ** 2 * float(np.var(ra)), 1e-12))
        rx.append([float(np.mean(np.clip(pr.x[stick_part(c, int(j), part)] / pr.x[c.peak_i[j + 1]], 0.0, 1.0)))
                   if pr.x[c.peak_i[j + 1]] > 0 else np.nan for j in k])
    if len(a) < 4:
        return c0, 0.0, 4.0
    a, sw = np.asarray(a), np.sqrt(np.asarray(w))
    best = None
    for mm in CREEP_M:
        R = np.array([float(np.nanmedian(np.asarray(q) ** mm)) if np.any(np.isfinite(q)) else np.nan for q in rx])
        ok = np.isfinite(R)
        if np.count_nonzero(ok) < 4 or np.ptp(R[ok]) < 0.05:
            continue
        A = np.column_stack([np.ones(np.count_nonzero(ok)), -R[ok]]) * sw[ok, None]
        coef, *_ = np.linalg.lstsq(A, (1.0 - a[ok]) * sw[ok], rcond=None)
        ssr = float(np.sum((A @ coef - (1.0 - a[ok]) * sw[ok]) ** 2))
        if best is None or ssr < best[0]:
            best = (ssr, float(coef[0]), -float(coef[1]), mm)
    if best is None:
        return c0, 0.0, 4.0
    _, b0, b1, mm = best
    if not b1 > 0:
        return c0, 0.0, 4.0        # (the slopes do not fall towards the limit after all: c0 alone, as read)
    c0, c1 = float(np.clip(b0, 0.0, 0.5)), float(min(b1, 0.9))
    # c1 then so that the stick lasts as long as the record's from its trough to the limit (the median stick,
    # as the drive's travel over it per unit of the limit: a stepped drive's sticks alike): the slopes are read
    # up to 97 % of the rise, and the last few per cent, where the creep is fastest, weigh most on the stick's
    # duration.  The model's stick needs the travel lim * integral from r0 to 1 of dr / (1 - c0 - c1 r**m).
    k = np.flatnonzero(c.next_ok)
    pk = pr.x[c.peak_i[k + 1]]
    ok = pk > 0
    if np.count_nonzero(ok) >= 3:
        track = travel(pr.vd, pr.dt)
        need = float(np.median(((track[c.peak_i[k + 1]] - track[c.trough_i[k]]) / np.where(ok, pk, 1.0))[ok]))
        # from where the model is started in each stick (:func:`stick_start`: the stick line's level at the
        # trough, past a rebound after the arrest), as the held-out cycles start it: from the trough itself, a
        # rig that rebounds after each arrest (bouc_wen_brake's hysteretic presliding, x rising at 1.26 the
        # drive just after it) had the model start 3 % of the rise higher than fitted, its sticks 4 % of the
        # period short of the record's in every cycle, and that bias in every error (a twin branch gaining
        # 0.16 gained 0.51 without it)
        st0 = np.array([stick_start(pr, c, int(j)) for j in k])
        r0 = float(np.clip(np.median(st0[ok] / pk[ok]), 0.0, 0.999))
        q = np.linspace(r0, 1.0, 2001)

        def stick_travel(c1_):
            return float(np.trapezoid(1.0 / (1.0 - c0 - c1_ * q ** mm), q))

        lo, hi = 0.0, min(0.98 - c0, 0.95)
        if stick_travel(lo) < need < stick_travel(hi):
            for _ in range(40):
                mid_ = 0.5 * (lo + hi)
                lo, hi = (mid_, hi) if stick_travel(mid_) < need else (lo, mid_)
            c1 = 0.5 * (lo + hi)
    return c0, c1, mm


def trough_mean(pr, c_fn, x):
    """Mean trough of a simulated trace (cycles found the record's way)."""
    from lieng.diagnose.segment import find_cycles

    cc = find_cycles(pr_like(pr, x), c_fn, speeds=False)
    if cc.n == 0:
        return None
    return float(np.mean(x[cc.trough_i]))


def pr_like(pr: Prepared, x, y=None) -> Prepared:
    """The prepared record with another displacement (and normal channel)."""
    return replace(pr, x=x, y=pr.y if y is None else y, notes=[])


#: below this many samples per natural period x'' cannot be read inside a
#: slip (it lasts half a period): the characteristic is then its level alone
RESOLVED = 20


def identify(pr: Prepared, c: Cycles, fn: float, load=None, sel=None) -> tuple:
    """The characteristic and the static limit read off the record: (sg, fg,
    fs).  phi by the reverse construction pooled over the slips (module
    docstring), FS the median peak; with ``load`` (the load factor N/N0 at
    every sample: a measured or modelled load) both are read per unit load,
    F / load, as the slider core applies them (friction = load x phi).
    ``sel``: a mask over the cycles whose slips and peaks are read."""
    idx, s, F, br, sid = slip_friction(pr, c, fn)
    pk = c.peak_i
    if sel is not None:
        keep = np.isin(sid, np.flatnonzero(sel))
        idx, s, F = idx[keep], s[keep], F[keep]
        pk = pk[sel]
    peaks = pr.x[pk]
    if load is not None:
        F = F / load[idx]
        peaks = peaks / load[pk]
    sg, fg = characteristic(s, F)
    if 1.0 / (fn * pr.dt) < RESOLVED:
        sg, fg = np.array([0.0]), np.array([float(np.median(F)) if F.size else float(np.median(pr.x))])
    return sg, fg, float(np.median(peaks))


def fit_baseline(pr: Prepared, c: Cycles, fn: float, iters: int = 6, loaded=None) -> Params:
    """The baseline (module docstring), identified on ``pr`` with its cycles ``c``.
    With ``loaded`` (:func:`under_load` of a recorded normal *force*) the
    slider's friction is the load times the characteristic, as
    :func:`calibrate_fn` reads fn under a load that varies; simulate it with
    ``loaded``'s channel."""
    load, kw, yfree = loaded if loaded is not None else (None, {}, None)
    sg, fg, fs = identify(pr, c, fn, load=load)
    c0, c1, cm = stick_creep(pr, c)
    p = _fit_level(pr, c, fn, Params(fs=fs, sg=sg, fg=np.minimum(fg, fs), creep0=c0, creep1=c1, creep_m=cm, **kw),
                   iters, yfree)
    if (c0 or c1) and _cycles_of(pr, p, fn, yfree) < min(3, c.n):
        # a creeping stick that never reaches the static limit is no stick-slip model: the thesis's
        # rigid stick (finite slope only in the sense of ch. 2.3.1.1's steep line) instead
        p = _fit_level(pr, c, fn, Params(fs=fs, sg=sg, fg=np.minimum(fg, fs), **kw), iters, yfree)
    return p


def under_load(pr: Prepared, c: Cycles, ylow) -> tuple:
    """The slider whose friction follows a recorded normal force ``ylow``
    (Amontons: the characteristic and the static limit per unit load, the
    load N / its mean): the part of N locked to x (:func:`.signals.y_on_motion`)
    as a coupling that follows the *simulated* x (``load_kx``; played back in
    time it would part from a simulated slip that runs early or late), the
    rest played back in time (``load_lock``: that part is taken out of the
    channel played back).  Returns (the record's load factor at every
    sample, the Params terms, the channel to simulate with)."""
    m = float(np.mean(ylow))
    kw = locked_load(pr, c, ylow, 1.0 / m)
    return np.maximum(ylow / m, 0.05), kw, ylow


def locked_load(pr: Prepared, c: Cycles, ylow, k: float) -> dict:
    """The Params terms of a load 1 + k (ylow - its mean) whose part locked
    to x (:func:`.signals.y_on_motion`) follows the model's own x: the
    coupling ``load_kx`` = k c1, ``load_lock`` = c1 (taken out of the channel
    played back), about the record's mean x."""
    from lieng.diagnose.signals import y_on_motion

    _, c1, _ = y_on_motion(pr.x, c.v, ylow)
    return {"load_k": k, "load_kx": k * c1, "load_xref": float(np.mean(pr.x)), "load_lock": c1}


def _cycles_of(pr, p, fn, ylow=None) -> int:
    from lieng.diagnose.segment import find_cycles

    xs, _, _ = simulate(pr, p, fn, ylow)
    return find_cycles(pr_like(pr, xs), fn, speeds=False).n


def _fit_level(pr, c, fn, p, iters, ylow=None):
    """Move the level of phi until the simulated mean trough matches the record's."""
    target = float(np.mean(pr.x[c.trough_i]))
    d0 = float(np.ptp(pr.x[c.peak_i]) + np.median(c.drops(pr.x)))
    return level_to_trough(p, lambda q: trough_mean(pr, fn, simulate(pr, q, fn, ylow)[0]), target, iters,
                           0.1 * max(d0, 1e-9))


#: the simulated trough rises about twice as fast as the characteristic's
#: level (a free half-oscillation about it: trough = 2 level - peak), the
#: first step of :func:`level_to_trough`
TROUGH_PER_LEVEL = 2.0


def level_to_trough(p: Params, trough_of, target: float, iters: int, step: float) -> Params:
    """Move the level of ``p``'s characteristic (an offset added to fg, kept
    below the static limit) until ``trough_of`` (the simulated mean trough
    of a model, None when it does not slip) matches ``target``: a secant
    search on the offset from 0, its first step at TROUGH_PER_LEVEL,
    bisection within the bracket found when a step would leave it, an
    expanding ``step`` downwards while no model slips.  ``p`` is left at
    the offset whose simulated trough came nearest the target among those
    simulated (so that the model returned is one whose trough was
    measured, not an untried midpoint) and returned."""
    fg0, fs = p.fg.copy(), p.fs
    lo = hi = None
    seen = []                                   # (offset, trough) of the models that slipped
    off, best = 0.0, (math.inf, 0.0)
    for _ in range(iters):
        tried = off
        tr = trough_of(p.copy(fg=np.minimum(fg0 + off, fs)))
        if tr is None or tr > target:          # (no slip: the kinetic level is too high)
            hi = off if hi is None else min(hi, off)
        else:
            lo = off if lo is None else max(lo, off)
        if tr is None:
            nxt = off - step
            step *= 2.0
        else:
            best = min(best, (abs(tr - target), off))
            slope = TROUGH_PER_LEVEL
            if seen:
                o0, t0 = seen[-1]
                if off != o0 and (tr - t0) / (off - o0) > 0.1 * TROUGH_PER_LEVEL:
                    slope = (tr - t0) / (off - o0)
            seen.append((off, tr))
            nxt = off + (target - tr) / slope
        if lo is not None and hi is not None and not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        off = nxt
    # (no model slipped: the lowest level tried)
    p.fg = np.minimum(fg0 + (best[1] if seen else tried), fs)
    return p


#: calibrate_fn reads at most this many samples (the record's beginning)
CALIBRATION_SAMPLES = 60_000


def calibrate_fn(pr: Prepared, f0: float, iters: int = 6, bound: float = 0.9, ylow=None,
                 again: int = 1) -> float | None:
    """The natural frequency by **indirect inference** from the slips.

    The slips' own arc frequency (:func:`.segment.estimate_fn`) is biased by
    the friction acting in them (a characteristic that changes along the
    slip bends the arcs: up to -50 % on records of several friction laws).
    The fn sought is the one whose baseline (identified on the record at
    that fn) gives, simulated and read the same way, slips as long as the
    record's: f <- f d_sim(f) / d_record, a few fixed-point steps from
    ``f0``, within a factor 1 + ``bound`` of it either way (the arcs read
    0.36-1.14 of the true fn on the independent generators' records without
    --fn; a bound of 0.4 about them left a quarter of those records 15-50 %
    low where the steps had not converged; stopped at the bound, the steps
    go on once from there).  Read on the record's first
    CALIBRATION_SAMPLES samples.  With ``ylow`` (a recorded normal force,
    low-passed) the slider's friction follows it (:func:`under_load`): a
    load that follows the motion lengthens or shortens the slips as a
    softer or stiffer spring would, and a baseline at constant load would
    put that into fn (a third off on a rate-and-state record whose load
    follows the slider).  None when the slips or the baseline cannot be
    read or simulated."""
    from lieng.diagnose.segment import find_cycles, head

    # a fixed-length part of a long record: as many slips as fix the duration, at a fixed cost
    pr = head(pr, CALIBRATION_SAMPLES)
    if ylow is not None:
        ylow = ylow[:pr.t.size]
    dur = slip_seconds(pr, find_cycles(pr, f0, retry=True))
    if dur is None:
        return None
    f, moved = f0, False
    seen = []                       # (ln f, ln of the simulated over the record's duration)
    for _ in range(iters):
        c = find_cycles(pr, f, retry=True)
        if c.n < 3:
            break
        try:
            ul = under_load(pr, c, ylow) if ylow is not None else None
            base = fit_baseline(pr, c, f, loaded=ul)
            xs, _, _ = simulate(pr, base, f, None if ul is None else ul[2])
        except (LiengInputError, np.linalg.LinAlgError, ValueError):
            break
        q = pr_like(pr, xs)
        ds = slip_seconds(q, find_cycles(q, f))
        if ds is None:
            break
        seen.append((math.log(f), math.log(ds / dur)))
        fnew = _next_fn(seen)
        fnew = float(np.clip(fnew, f0 / (1 + bound), f0 * (1 + bound)))
        step = abs(fnew / f - 1.0)
        f, moved = fnew, True
        if step < 0.003:
            break
    if moved and again and abs(math.log(f / f0)) >= 0.999 * math.log(1 + bound):
        # stopped at the bound, still moving that way: once more from there
        return calibrate_fn(pr, f, iters, bound, ylow, again - 1) or f
    return f if moved else None


def _next_fn(seen) -> float:
    """The next fn of :func:`calibrate_fn` from the (ln f, ln d_sim / d_rec)
    seen so far: f d_sim / d_rec (a duration that scales as 1 / f) until the
    ratio has been seen on both sides of 1, then the secant in logs between
    the closest pair that brackets it (a slip whose duration does not scale
    as 1 / f, under a load that follows the motion, made the plain step
    swing about the answer)."""
    lf, lr = seen[-1]
    lo = [p for p in seen if p[1] > 0]
    hi = [p for p in seen if p[1] < 0]
    if not lo or not hi:
        return math.exp(lf + lr)
    a = min(lo, key=lambda p: p[1])
    b = max(hi, key=lambda p: p[1])
    return math.exp(a[0] - a[1] * (b[0] - a[0]) / (b[1] - a[1]))
