"""Synthetic "measured" stick-slip records with a physical effect hidden in them.

This generator is deliberately a separate implementation from the diagnosis
path (:mod:`lieng.diagnose` simulates with the compiled core in
``fortran/modern/slider.f90``): it integrates its own equations with a classical
Runge-Kutta scheme in Python, uses its own friction laws (a Stribeck curve,
Dieterich's logarithmic ageing) and shares no function with the diagnosis.

The rig (mm, s): a dynamometer of natural frequency ``fn`` holds a slider
on a belt at ``v0``::

    x'' + 2 zeta wn x' + wn^2 x = wn^2 F(t) ,   wn = 2 pi fn

F is the friction force divided by the dynamometer stiffness (mm).  While
the slider sticks, x' equals the belt velocity; it slips when x exceeds the
static limit N(t)/N0 * FS, and sticks again when its velocity comes back to
the belt's.  In slip F = N(t)/N0 * mu(v_belt - x').

Effects (``effect=``):

``none``
    the model above, constant load and drive.
``load_variation``
    the normal displacement y follows the tangential motion through the
    rig's coupling (seed 001) and the friction follows N = N0 (1 + k_y (y - y0)).
``twin_branch``
    accelerating and decelerating slip follow two mu(v) branches.
``static_ageing``
    the static limit grows with the stick time, FS (1 + a log10(1 + ts/tau)),
    under a drive that steps between velocities (App. 1's idle-time
    experiments) and is recorded in a ``v0`` column.
``triggering``
    a normal oscillation at a frequency that is not a harmonic of the
    stick-slip modulates the load by a few per cent (2.2.2, App. 2).
``drive_modulation``
    the belt velocity varies periodically although a constant v0 is given.

Every record carries realistic noise: quantisation, sensor noise of about
0.5 % of the stick-slip amplitude, and a triggering oscillation 100-500 times
smaller than the stick-slip (App. 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["EFFECTS", "SynthRecord", "synthesize"]

EFFECTS = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")


@dataclass
class SynthRecord:
    """A synthetic record: columns and the hidden truth."""

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray | None
    v0_col: np.ndarray | None
    v0: float
    fn: float
    fnv: float | None
    effect: str
    truth: dict = field(default_factory=dict)

    def columns(self) -> dict:
        cols = {"t": self.t, "x": self.x}
        if self.y is not None:
            cols["y"] = self.y
        if self.v0_col is not None:
            cols["v0"] = self.v0_col
        return cols

    def write_csv(self, path) -> None:
        cols = self.columns()
        names = list(cols)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(",".join(names) + "\n")
            for row in zip(*(cols[n] for n in names)):
                fh.write(",".join(f"{v:.9g}" for v in row) + "\n")


def _stribeck(s, fk, ds, vs):
    return math.copysign(fk + ds * math.exp(-abs(s) / vs), s) if s != 0 else 0.0


#: the most cycles a record may have (the slowest effect, static ageing, takes about 30 s for 500)
MAX_CYCLES = 500


def synthesize(effect: str = "none", seed: int | None = None, *, cycles: int = 16, noise: bool = True,
               strength: float | None = None) -> SynthRecord:
    """Generate a record with ``effect`` hidden in it.

    Parameters
    ----------
    effect : str
        One of :data:`EFFECTS`.
    seed : int, optional
        Random seed: rig, friction and effect parameters are drawn at random.
    cycles : int, optional
        Approximate number of stick-slip cycles in the record.
    noise : bool, optional
        Add quantisation, sensor noise and the small triggering oscillation.
    strength : float, optional
        Scale of the effect (1 = the default random range's middle).

    Returns
    -------
    SynthRecord
    """
    if effect not in EFFECTS:
        raise ValueError(f"unknown effect {effect!r}: choose one of {', '.join(EFFECTS)}")
    if not 1 <= int(cycles) <= MAX_CYCLES:
        raise ValueError(f"cycles = {cycles}: from 1 to {MAX_CYCLES}")
    g = np.random.default_rng(seed)
    fn = float(g.uniform(6.0, 15.0))
    wn = 2 * math.pi * fn
    zeta = float(g.uniform(0.01, 0.04))
    fs = float(g.uniform(0.3, 0.8))                    # static limit, mm
    fk = fs * float(g.uniform(0.45, 0.7))              # kinetic level, mm
    ds = fs * float(g.uniform(0.0, 0.1))               # Stribeck excess
    v0 = float(g.uniform(1.0, 3.0))                    # mm/s
    vs = v0 * float(g.uniform(2.0, 8.0))               # Stribeck velocity
    k = 1.0 if strength is None else float(strength)
    truth: dict = {"fn": fn, "zeta": zeta, "fs": fs, "fk": fk, "v0": v0}

    period_est = (fs - (2 * fk - fs)) / v0 + 1.0 / fn
    t_end = cycles * period_est + 0.5 / fn
    fsamp = 60.0 * fn
    nsub = 8
    h = 1.0 / fsamp / nsub
    n = int(t_end * fsamp)

    # effect parameters
    ky = a_age = tau_age = dtw = a_drv = f_drv = eps_tr = f_tr = 0.0
    cy, y0, a_ny = 0.0, 1.0, 0.0
    steps = None
    if effect == "load_variation":
        cy = float(g.uniform(0.3, 0.6))                # y follows x through the coupling
        # per mm of y; ky cy fs (the load's rise over the static limit) from 0.15 to 0.4
        ky = k * float(g.uniform(0.15, 0.4)) / (cy * fs)
        truth.update(ky=ky, cy=cy)
        # the static limit is reached at fs / (1 - ky cy fs): longer sticks
        period_est *= 1.0 / max(1.0 - ky * cy * fs, 0.2)
        t_end = cycles * period_est + 0.5 / fn
        n = int(t_end * fsamp)
    elif effect == "twin_branch":
        dtw = k * fs * float(g.uniform(0.12, 0.22))    # decelerating branch above the accelerating one
        truth.update(delta=dtw)
    elif effect == "static_ageing":
        a_age = k * float(g.uniform(0.10, 0.20))
        tau_age = float(g.uniform(0.005, 0.02))
        truth.update(a=a_age, tau=tau_age)
    if effect == "static_ageing" or (effect == "none" and g.uniform() < 0.5):
        # a drive stepping between velocities, recorded in a v0 column (for
        # `none`: the same test programme without ageing)
        levels = v0 * np.array([0.35, 0.6, 1.0, 1.6])
        nseg = 6
        steps = (np.linspace(0.0, t_end, nseg + 1)[:-1], g.permutation(np.resize(levels, nseg)))
        period_est = (fs - (2 * fk - fs)) / levels.min() + 1.0 / fn
    if effect == "triggering":
        eps_tr = k * float(g.uniform(0.04, 0.08))
        f_tr = fn * float(g.uniform(3.3, 5.7))
        a_ny = 2 * (fs - fk) * float(g.uniform(0.04, 0.1))   # the normal oscillation (mm)
        truth.update(eps=eps_tr, f_tr=f_tr, a_normal=a_ny)
    elif effect == "drive_modulation":
        a_drv = k * float(g.uniform(0.25, 0.45))
        f_drv = (1.0 / period_est) * float(g.uniform(0.23, 0.41))
        truth.update(a=a_drv, f=f_drv)
    if steps is not None:
        t_end = cycles * 1.6 * period_est
        n = int(t_end * fsamp)
        steps = (np.linspace(0.0, t_end, len(steps[0]) + 1)[:-1], steps[1])
    ph_tr, ph_drv = g.uniform(0, 2 * math.pi, 2)

    def drive(t):
        if steps is not None:
            i = int(np.searchsorted(steps[0], t, side="right")) - 1
            return float(steps[1][max(i, 0)])
        return v0 * (1.0 + a_drv * math.sin(2 * math.pi * f_drv * t + ph_drv))

    def normal_disp(xx, t):
        return y0 + cy * xx + (a_ny * math.sin(2 * math.pi * f_tr * t + ph_tr) if eps_tr else 0.0)

    def load(xx, t):
        ld = 1.0 + ky * (normal_disp(xx, t) - y0) if ky else 1.0
        if eps_tr:
            ld *= 1.0 + eps_tr * math.sin(2 * math.pi * f_tr * t + ph_tr)
        return ld

    def accel(t, xx, vv, branch):
        s = drive(t) - vv
        f = load(xx, t) * (_stribeck(s, fk, ds, vs) + (0.5 * dtw * branch if s > 0 else 0.0))
        return wn * wn * (f - xx) - 2 * zeta * wn * vv

    ts_out = np.arange(n) / fsamp
    xs = np.empty(n)
    x, v, t = 0.0, drive(0.0), 0.0
    stick, t_stick0, branch, prev_s = True, 0.0, -1.0, 0.0
    j = 0
    xs[0] = x
    for j in range(1, n):
        for _ in range(nsub):
            if stick:
                x += h * 0.5 * (drive(t) + drive(t + h))
                t += h
                age = 1.0 + a_age * math.log10(1.0 + (t - t_stick0) / tau_age) if a_age else 1.0
                lim = load(x, t) * fs * age
                if x > lim:
                    stick, branch, prev_s = False, -1.0, 0.0
                    v = drive(t)
                continue
            k1x, k1v = v, accel(t, x, v, branch)
            if drive(t) - v > 0.0 and v + h * k1v >= drive(t + h) and abs(x) <= load(x, t) * fs:
                stick, t_stick0 = True, t                     # the slider catches up with the belt in this step
                x += h * 0.5 * (v + drive(t + h))
                t += h
                v = drive(t)
                continue
            k2x, k2v = v + 0.5 * h * k1v, accel(t + 0.5 * h, x + 0.5 * h * k1x, v + 0.5 * h * k1v, branch)
            k3x, k3v = v + 0.5 * h * k2v, accel(t + 0.5 * h, x + 0.5 * h * k2x, v + 0.5 * h * k2v, branch)
            k4x, k4v = v + h * k3v, accel(t + h, x + h * k3x, v + h * k3v, branch)
            x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
            v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            t += h
            s = drive(t) - v
            if s < prev_s and branch < 0:
                branch = 1.0                                  # the relative speed has peaked: decelerating
            prev_s = s
            if s <= 0.0 and abs(x) <= load(x, t) * fs:
                stick, t_stick0, v = True, t, drive(t)
        xs[j] = x
    y = np.array([normal_disp(xx, tt) for xx, tt in zip(xs, ts_out)]) if (ky or eps_tr) else None
    if y is None and g.uniform() < 0.5:
        y = y0 + float(g.uniform(0.2, 0.5)) * xs             # a recorded normal channel the friction ignores
    amp = float(np.ptp(xs[len(xs) // 4:]))
    if noise:
        tr_amp = amp / float(g.uniform(100.0, 500.0))
        f_small = fn * float(g.uniform(6.3, 9.7))
        ph = g.uniform(0, 2 * math.pi)
        xs = xs + tr_amp * 0.3 * np.sin(2 * math.pi * f_small * ts_out + ph) + 0.005 * amp * g.standard_normal(n)
        q = amp / 4000.0
        xs = np.round(xs / q) * q
        if y is not None:
            yamp = max(float(np.ptp(y)), 1e-3)
            y = y + tr_amp * np.sin(2 * math.pi * f_small * ts_out + ph) + 0.005 * yamp * g.standard_normal(n)
            y = np.round(y / (yamp / 4000.0)) * (yamp / 4000.0)
    v0_col = None
    if steps is not None:
        v0_col = np.array([drive(tt) for tt in ts_out])
    truth["amplitude"] = amp
    return SynthRecord(t=ts_out, x=xs, y=y, v0_col=v0_col, v0=v0, fn=fn, fnv=(3.0 * fn if y is not None else None),
                       effect=effect, truth=truth)
