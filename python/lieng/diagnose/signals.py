"""Signal primitives of the diagnosis, free of any model: a zero-phase low-pass, the grouped jackknife, a
spectral line's size, the part of a channel locked to the motion, the strokes' directions, a permutation
scan for a drive line, a piecewise level fit, an analysis of variance along the track.  Used by :mod:`.evidence` (the statistics) and :mod:`.extend`
(the extensions)."""

from __future__ import annotations

import math

import numpy as np

from lieng.diagnose.segment import Prepared

__all__ = ["lowpass", "resonance", "spectral_line", "y_on_motion", "directions", "y_locked", "drive_scan", "level_fit",
           "position_anova"]


def lowpass(y, dt, fcut):
    """Zero the spectrum above fcut (FFT), keeping the mean."""
    f = np.fft.rfftfreq(y.size, dt)
    Y = np.fft.rfft(y - y.mean())
    Y[f > fcut] = 0
    return np.fft.irfft(Y, y.size) + y.mean()


def bandpass(y, dt, flo, fhi):
    """Keep the spectrum within [flo, fhi] (FFT, zero phase), zero mean."""
    f = np.fft.rfftfreq(y.size, dt)
    Y = np.fft.rfft(y - y.mean())
    Y[(f < flo) | (f > fhi)] = 0
    return np.fft.irfft(Y, y.size)


#: a line read as a band (:func:`line_band`): the band's half-width, relative to the line's frequency (a
#: shaker's or a motor's frequency wanders by a few per cent under load; the band holds +-4 %), and the
#: noise beside it read over two bands as wide, one either side beyond a gap as wide
LINE_BAND = 0.04


def line_band(sig, dt, f: float, width: float = LINE_BAND):
    """A line at ``f`` read as the band f (1 +- width) of ``sig``, at least
    3 frequency bins either way: (the band's series, zero phase; the noise
    beside it, the mean of the squares of the bands f (1 - 4 width .. 1 - 2
    width) and f (1 + 2 width .. 1 + 4 width), each as wide as the band,
    sample by sample (zeros when the lower one reaches 0 Hz)).  A line whose
    frequency wanders (a shaker's, an unbalanced motor's under load)
    spreads its power over several bins, which one sinusoid fitted at f
    reads only in part."""
    n = sig.size
    w = max(width * f, 3.0 / (n * dt))
    band = bandpass(sig, dt, f - w, f + w)
    side = (bandpass(sig, dt, f - 4 * w, f - 2 * w) ** 2 + bandpass(sig, dt, f + 2 * w, f + 4 * w) ** 2) / 2 \
        if f - 4 * w > 0 else np.zeros(n)
    return band, side


def resonance(x, dt: float, f: float, zeta: float):
    """``x`` recorded through a second-order resonance at ``f`` Hz of damping
    ratio ``zeta`` (unit gain at 0 Hz: wn**2 / (s**2 + 2 zeta wn s + wn**2)),
    discretised exactly for an input linear between samples (first-order
    hold), started at rest at ``x[0]``."""
    from scipy import signal

    x = np.asarray(x, float)
    if x.size < 2 or not (f > 0 and dt > 0):
        return x.copy()
    w = 2 * math.pi * f
    b, a, _ = signal.cont2discrete(([w * w], [1.0, 2.0 * zeta * w, w * w]), dt, method="foh")
    b = np.ravel(b)
    return signal.lfilter(b, a, x, zi=signal.lfilter_zi(b, a) * x[0])[0]


def _jackknife(values_fn, n_units, groups=10):
    """Jackknife standard error of values_fn(mask of units kept), leaving out
    contiguous blocks of units (slips or cycles in time order), so that a
    scatter correlated from cycle to cycle (a real rig's wander) widens it."""
    g = min(groups, n_units)
    if g < 3:
        return math.inf
    parts = np.array_split(np.arange(n_units), g)
    est = []
    for part in parts:
        keep = np.ones(n_units, bool)
        keep[part] = False
        est.append(values_fn(keep))
    est = np.asarray(est, float)
    est = est[np.isfinite(est)]
    if est.size < 3:
        return math.inf
    return float(math.sqrt((g - 1) / g * np.sum((est - est.mean()) ** 2)))


def spectral_line(sig, dt, fmin, f0=None, by: str = "amplitude", jitter: float = 0.0, exclude=(), combs=()):
    """The strongest line above fmin and, with f0, off the harmonics of f0
    (by more than two bins, and by more than ``jitter`` times the harmonic's
    frequency, at most a fifth of f0: a stick-slip whose period wanders by a
    relative ``jitter`` spreads its h-th harmonic over h times that), and,
    with f0, off the harmonics of each further (frequency, jitter, least
    width in Hz) of ``combs`` alike (a drive that steps between levels: each
    level's own stick-slip, whose lines are as wide as the inverse of the
    time spent at that level), and
    off the frequencies ``exclude`` (by more than three bins: the record's
    mains hum, removed from it, and lines already passed over):
    (frequency, amplitude, local signal-to-noise of the line), from a
    Hann-windowed FFT.  ``by="snr"``: the line that stands
    highest above its neighbourhood (the mean amplitude 4 to 30 bins either
    side) rather than the largest, so that a response that falls with
    frequency (a slider's, as 1 / (f / fn)**2) does not prefer the low end."""
    s = sig - np.mean(sig)
    n = s.size
    w = np.hanning(n)
    S = np.fft.rfft(s * w)
    f = np.fft.rfftfreq(n, dt)
    amp = 2 * np.abs(S) / w.sum()
    ok = (f > fmin) & (f < 0.49 / dt)
    for fx in exclude:
        ok &= np.abs(f - fx) > 3.0 / (n * dt)
    if f0 is not None and f0 > 0:
        for fc, jc, wc in ((f0, jitter, 0.0), *combs):
            h = np.round(f / fc)
            ok &= np.abs(f / fc - h) * fc > np.maximum(max(2.0 / (n * dt), wc), np.minimum(jc * h * fc, 0.2 * fc))
    if not np.any(ok):
        return 0.0, 0.0, 0.0
    if by == "snr":
        cs = np.r_[0.0, np.cumsum(amp)]
        i = np.arange(amp.size)
        lo, hi = np.maximum(i - 30, 0), np.minimum(i + 31, amp.size)
        ilo, ihi = np.maximum(i - 3, lo), np.minimum(i + 4, hi)
        cnt = (ilo - lo) + (hi - ihi)
        level = ((cs[ilo] - cs[lo]) + (cs[hi] - cs[ihi])) / np.maximum(cnt, 1)
        score = np.where(level > 0, amp / np.where(level > 0, level, 1.0), 0.0)
    else:
        score = amp
    k = int(np.flatnonzero(ok)[np.argmax(score[ok])])
    lo, hi = max(k - 30, 1), min(k + 31, amp.size)
    side = np.r_[amp[lo:max(k - 3, lo)], amp[min(k + 4, hi):hi]]
    snr = float(amp[k] / np.median(side)) if side.size and np.median(side) > 0 else 0.0
    return float(f[k]), float(amp[k]), snr


def line_fit(sig, t, f):
    """Least squares sig ~ a + b t + A sin(2 pi f t + phase): (A, phase)."""
    A = np.column_stack([np.ones(t.size), t - t.mean(), np.sin(2 * math.pi * f * t), np.cos(2 * math.pi * f * t)])
    c = np.linalg.lstsq(A, sig, rcond=None)[0]
    return float(math.hypot(c[2], c[3])), float(math.atan2(c[3], c[2]))


def refine_line(sig, t, f):
    """The frequency near ``f`` at which the least-squares line in ``sig``
    (on its own times ``t``: a record whose holds were cut keeps its phase)
    is largest: a quarter of a bin (1 / the span of t) over +-4 bins, then a
    fortieth over +-1/4.  The fit is weighted by a Hann window over the span
    (as the spectrum the line was found in): unweighted, the leakage of the
    stick-slip's own strong harmonics, whose sidelobes fall only as 1 / the
    distance, can outweigh a weak line and move it by several bins."""
    T = max(float(t[-1] - t[0]), 1e-12)
    wt = np.sin(math.pi * (t - t[0]) / T) ** 2
    tc = t - t.mean()
    # the weighted normal equations of a + b t + sin + cos (line_fit's, with weights), their parts that do not
    # depend on the frequency computed once, the rest as sums of products (a third of the cost on a long
    # record)
    wtc, wy = wt * tc, wt * sig
    G = np.array([[wt.sum(), wtc.sum()], [wtc.sum(), float((wtc * tc).sum())]])
    r0 = np.array([wy.sum(), float((wy * tc).sum())])

    def amp(g):
        arg = (2 * math.pi * g) * t
        sn, cs = np.sin(arg), np.cos(arg)
        ws, wc = wt * sn, wt * cs
        M = np.empty((4, 4))
        M[:2, :2] = G
        M[0, 2], M[0, 3] = ws.sum(), wc.sum()
        M[1, 2], M[1, 3] = float((ws * tc).sum()), float((wc * tc).sum())
        M[2, 2], M[2, 3], M[3, 3] = float((ws * sn).sum()), float((ws * cs).sum()), float((wc * cs).sum())
        M[2:, :2] = M[:2, 2:].T
        M[3, 2] = M[2, 3]
        rhs = np.r_[r0, float((ws * sig).sum()), float((wc * sig).sum())]
        try:
            co = np.linalg.solve(M, rhs)
        except np.linalg.LinAlgError:
            return 0.0
        return float(math.hypot(co[2], co[3]))

    for half, num in ((4.0, 33), (0.25, 21)):
        grid = f + np.linspace(-half, half, num) / T
        f = float(max(grid, key=amp))
    return f


def y_on_motion(x, v, y):
    """The part of y locked to the motion: least squares y ~ c0 + c1 x + c2 x'
    (kept only when it explains more than a third of y's variance)."""
    A = np.column_stack([np.ones(x.size), x, v])
    coef = np.linalg.lstsq(A, y, rcond=None)[0]
    r2 = 1.0 - float(np.var(y - A @ coef)) / max(float(np.var(y)), 1e-300)
    if r2 < 1.0 / 3.0:
        return (float(np.mean(y)), 0.0, 0.0)
    return tuple(float(a) for a in coef)


def directions(pr: Prepared) -> np.ndarray:
    """The drive's direction (+1, -1) of every sample of the turned record."""
    return np.concatenate([np.full(s.n, s.sign) for s in pr.strokes])


def y_locked(x, v, y, sign):
    """The part of y locked to the motion, sample by sample, and y's mean,
    in each drive direction apart (:func:`y_on_motion` there: x is turned
    forward stroke by stroke, and a load that follows the force as the rig
    wrote it changes sign with the direction): (locked part, its direction's
    mean)."""
    fit, mean = np.empty(y.size), np.empty(y.size)
    for d in (1, -1):
        m = sign == d
        if np.any(m):
            c0, c1, c2 = y_on_motion(x[m], v[m], y[m])
            fit[m] = c0 + c1 * x[m] + c2 * v[m]
            mean[m] = np.mean(y[m])
    return fit, mean


def drive_scan(t, r, fmin, fmax, nperm=199, seed=0):
    """A periodic modulation of the stick velocity: the largest fraction of
    the series' variance a sinusoid explains over a frequency grid, its
    frequency and relative amplitude, and the permutation p-value of that
    maximum (the sticks' order shuffled: under a constant drive the stick
    velocities are exchangeable)."""
    n = r.size
    if n < 8 or not np.std(r) > 0 or not fmax > fmin > 0:
        return 0.0, 0.0, 0.0, 1.0
    span = float(t[-1] - t[0])
    nf = int(np.clip(4 * span * fmax, 50, 600))
    freqs = np.geomspace(fmin, fmax, nf)
    rng = np.random.default_rng(seed)
    R = np.column_stack([r] + [rng.permutation(r) for _ in range(nperm)])
    R = R - R.mean(axis=0)
    tot = np.sum(R * R, axis=0)
    best = np.zeros(R.shape[1])
    arg = 0
    for j, f in enumerate(freqs):
        B = np.column_stack([np.ones(n), np.sin(2 * math.pi * f * t), np.cos(2 * math.pi * f * t)])
        Q, _ = np.linalg.qr(B)
        P = Q[:, 1:].T @ R
        frac = np.sum(P * P, axis=0) / tot
        if frac[0] > best[0]:
            arg = j
        best = np.maximum(best, frac)
    f = float(freqs[arg])
    B = np.column_stack([np.ones(n), np.sin(2 * math.pi * f * t), np.cos(2 * math.pi * f * t)])
    co = np.linalg.lstsq(B, r, rcond=None)[0]
    amp = float(math.hypot(co[1], co[2]) / abs(co[0])) if co[0] else 0.0
    p = float((1 + np.count_nonzero(best[1:] >= best[0])) / (nperm + 1))
    return float(best[0]), f, amp, p


def level_fit(tt, pos, lvl, f=None):
    """The friction level per cycle as a linear trend in time plus a sinusoid
    in the drive's travel: (range of the fitted curve, coefficients
    [mean, slope, sin, cos], frequency per mm of travel).  Without ``f`` the
    frequency is scanned from one period over the record to one over four
    cycles (the one explaining most)."""
    tt0 = tt - tt.mean()
    span = float(np.ptp(pos))
    if span <= 0 or lvl.size < 8:
        X = np.column_stack([np.ones(tt.size), tt0])
        co = np.linalg.lstsq(X, lvl, rcond=None)[0]
        return float(np.ptp(X @ co)), np.r_[co, 0.0, 0.0], 0.0
    if f is None:
        freqs = np.linspace(1.0 / span, lvl.size / (4.0 * span), min(200, max(10, lvl.size)))
        best = None
        for fr in freqs:
            X = np.column_stack([np.ones(tt.size), tt0, np.sin(2 * math.pi * fr * pos), np.cos(2 * math.pi * fr * pos)])
            co, res, _, _ = np.linalg.lstsq(X, lvl, rcond=None)
            r = float(np.sum((lvl - X @ co) ** 2))
            if best is None or r < best[0]:
                best = (r, fr)
        f = best[1]
    X = np.column_stack([np.ones(tt.size), tt0, np.sin(2 * math.pi * f * pos), np.cos(2 * math.pi * f * pos)])
    co = np.linalg.lstsq(X, lvl, rcond=None)[0]
    return float(np.ptp(X @ co)), co, float(f)


def position_anova(pos, val, group, nbins: int = 6):
    """Values against position along the track, less each group's (stroke's)
    mean: (range of the position-bin means, p of the one-way F test)."""
    from scipy.stats import f as fdist

    ok = np.isfinite(pos) & np.isfinite(val)
    pos, val, group = pos[ok], val[ok], group[ok]
    if np.unique(group).size < 2 or val.size < 3 * nbins:
        return 0.0, 1.0
    r = val.copy()
    for gval in np.unique(group):
        m = group == gval
        r[m] -= np.mean(r[m])
    edges = np.quantile(pos, np.linspace(0, 1, nbins + 1))
    b = np.clip(np.searchsorted(edges, pos, side="right") - 1, 0, nbins - 1)
    means, ss_b, ss_w, k = [], 0.0, 0.0, 0
    for j in range(nbins):
        m = b == j
        if np.count_nonzero(m) < 2:
            continue
        mu = float(np.mean(r[m]))
        means.append(mu)
        ss_b += np.count_nonzero(m) * mu ** 2
        ss_w += float(np.sum((r[m] - mu) ** 2))
        k += 1
    n = r.size
    df_b, df_w = k - 1, n - k - (np.unique(group).size - 1)
    if k < 3 or df_w < 2 or not ss_w > 0:
        return 0.0, 1.0
    F = (ss_b / df_b) / (ss_w / df_w)
    return float(np.ptp(means)), float(fdist.sf(F, df_b, df_w))


def _binned_anova(pos, val, group, nbins: int = 6):
    """Position dependence from one mean per stroke and position bin."""
    edges = np.quantile(pos, np.linspace(0, 1, nbins + 1))
    b = np.clip(np.searchsorted(edges, pos, side="right") - 1, 0, nbins - 1)
    P, V, G = [], [], []
    for gval in np.unique(group):
        for j in range(nbins):
            m = (group == gval) & (b == j)
            if np.count_nonzero(m):
                P.append(0.5 * (edges[j] + edges[j + 1]))
                V.append(float(np.mean(val[m])))
                G.append(gval)
    return position_anova(np.asarray(P), np.asarray(V), np.asarray(G), nbins)
