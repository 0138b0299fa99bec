"""Ice-friction stick-slip records: a runner on an ice track in a cold room (independent generator).

Rig
---
A slider (a steel or polymer runner carrying dead weights, or an ice block) of mass m = 1.5-8 kg sits on a
planed ice track in a cold room (-4..-18 degC) and is pulled by a motorised stage through a spring (a load
cell's flexure or a leaf flexure with a strain gauge), k = m (2 pi fn)^2, fn 4-25 Hz; the flexure's material
damping acts on the spring's extension (zeta 0.01-0.04). The normal load N0 = m g (1-1.5) (dead weight plus a
bellows). The lab exports the load cell's force (N or mN, `--stiffness` given), or the flexure's extension
(mm or um, x = F/k), optionally a normal-force column, the stage's position or commanded speed, and the ice
temperature (a column nothing should read).

Friction law (written for this generator: a frictional-melt film, Oksanen-Keinonen / Makkonen type)
------------------------------------------------------------------------------------------------
The melt water film's thickness h (in units of the asperity roughness) is set by the frictional heat per unit
real contact area, mu p_H v (p_H the ice's indentation hardness, so not by the load): its steady value is
h_ss(v) = (v / v_h)^p, p 0.45-0.6 (conduction-limited melting). The dry (solid-solid) fraction of the real
contact is 1 / (1 + h^n) (n 1.6-2.4); the wet fraction shears the water film, a stress eta v / h. So

    mu(v, h) = mu_p + (mu_a + mu_e (v / v_h) h^(n-1)) / (1 + h^n)

mu_p a film-independent ploughing part, mu_a the adhesive dry part (0.2-0.4 of mu(0)), mu_e the film's viscous
shear. On h = h_ss(v) this is single-valued: weakening from mu(0) = mu_p + mu_a to a minimum (0.80-0.92 mu(0))
and a mild wet strengthening beyond (the classic minimum of ice friction). The static level is
mu_s = mu(0) (1.08-1.25) (the bonded, film-free contact).

Outside `twin_branch` the film follows the speed instantly (h = h_ss(v)), so the law is single-valued.
In `twin_branch` the film has its thermal time constant: dh/dt = (h_ss(v) - h) / tau_th in slip (the film
builds with the dissipated heat), dh/dt = -h / tau_fz in stick (it freezes back, tau_fz 0.15-0.4 Tn, gone
before the next breakaway); tau_th is set by short calibration runs so that the friction is lower while
decelerating than while accelerating at equal sliding speed by 10-25 % of the force drop (the film built
during the slip persists). NB: the sign is negative (decelerating below accelerating), the melt film's own.

Ice creep at rest: in stick the asperities creep by Glen's flow law, the slider moving at
v_cr = v_c0 (F / F_s)^3 (F the needed force, F_s the current static limit), v_c0 0.3-1.2 % of the slowest drive
speed; so the stuck slider creeps before each slip and the force relaxes slightly during holds.

Sintering (only in `static_ageing`): the ice bonds' necks grow in stick (surface-diffusion sintering,
neck area ~ t^0.4): mu_s(t_st) = mu_s0 + Delta ((1 + t_st / tau_s)^q - 1), q 0.25-0.45, tau_s 0.05-0.3 of the
fast level's stick time, Delta set by a calibration run so the peak grows 10-20 % of the drop across the
record's stick times.

Stick handling (own design)
---------------------------
An exact two-mode switched system (no band, no regularisation, no bristles, no LCP): STICK integrates only the
creeping contact (x' = v_cr(F)) and the film's freezing; it leaves at the first time the needed force
k e + c (v_d - v_cr) reaches mu_s(t_st) N(t, x, e); SLIP integrates x, v (and h in `twin_branch`) and leaves
when v crosses 0 (the needed force then checked against the static limit: beyond it the slider slides on).
Both switches are located by a safeguarded Newton iteration (Newton steps with a central-difference slope,
bisection when a step leaves the bracket) on the step's cubic Hermite interpolant of the state, and the step
is then retaken from its start to the located time, so each mode ends exactly on its guard.

Integrator (own)
----------------
Fixed-step Gragg-Bulirsch-Stoer extrapolation: Gragg's modified midpoint rule with 2 and 4 substeps and one
Richardson extrapolation in h^2 (order 4, 7 evaluations a step); H = Tn/160 in slip, Tn/24 in stick (at most
1/18 of a shaker period); steps are cut at the stage's speed knots. The stored steps are put on a grid 8 times
finer than the record by cubic Hermite interpolation.

Sensor and record
-----------------
3rd-order Butterworth anti-alias (causal, cut at 0.3 fs) on the fine grid, decimation by 8; noise = white +
an AR(1) amplifier wander (correlation 0.2-2 s), 0.2-1 % of the drop in all. Nuisances on the recorded main
channel only: `hum` mains 50 or 60 Hz (+ 2nd/3rd harmonics below 0.4 fs, 1-5 % of the drop), `drift` a
load-cell offset following the cold room's temperature cycle (<= 3 % of the drop over the record), `spikes`
(0.05-0.5 % of samples, up to 0.3 of the drop), `quantisation` (ADC step 0.2-1 % of the drop), `coarse`
(10-15 samples per natural period), `fn_off` (`--fn` 5 % off). 10-100 samples per natural period otherwise
(>= 300 Hz with hum). Formats by seed: comma CSV `Time [s],Friction force [N],...`; TAB `Time (s)`,
`Friction force (mN)`; whitespace `time_s Ffric_N Fn_N stage_pos_um`; semicolon with a decimal comma;
extension records `spring extension [mm]` / `[um]`; time in s or ms; `#` metadata lines or plain `key: value`
lines above the header; optional `stage_pos[um]` / `Stage position [mm]` / `stage speed [mm/s]`,
`Normal force [N]` / `Fn_N`, `T_ice [°C]` columns. `--fn` left out on seeds 5 mod 8 (never for `triggering`
or `fn_off`).

Cases (departure present only in its own case)
----------------------------------------------
- `none`: constant N0, the instantaneous film (single-valued law), constant mu_s. Seeds 1 mod 4: the stage
  steps between two speeds 4-8x apart (recorded); seeds 3 mod 4: slide-hold-slide holds (recorded); others a
  constant drive.
- `load_variation`: even seeds an undulating track (planing marks), N = N0 (1 + a sin(2 pi x / lambda + phi))
  along the slider's position x, lambda 2.5-6 slip advances; odd seeds a load arm hinged on the carriage,
  N = N0 (1 + c (e - e_m) / D_e) along the spring's extension e (c of either sign); 12-30 % p-p, measured;
  the normal force recorded on seeds 0, 1 mod 4.
- `twin_branch`: the lagged film (above).
- `static_ageing`: sintering, stepped drive 4-8x (even seeds) or holds (odd seeds), recorded.
- `triggering`: the compressor's / a shaker's vibration of the normal load, N = N0 (1 + a sin(2 pi f_t t)),
  a 3-8 %, f_t 2.5-7 fn, redrawn (up to 12 runs) while the record's f_t / f_ss is within 0.15 of an integer;
  here alone the static level scatters 0.8-1.5 % from stick to stick (a new patch of ice at each slip), which
  keeps the breakaways from locking to the shaker.
- `drive_modulation`: the leadscrew's periodic error, v_d = v0 (1 + a sin(2 pi f_m t + phi)), a 0.20-0.45,
  f_m 0.1-0.4 f_ss, not recorded (`--v0` = v0, or a constant set-speed column).

Measured sizes (ground truth, seeds 0-7 of the self-check; `params["measured"]`)
-------------------------------------------------------------------------------
Sizes are on the true state (the spring force k e, the contact's friction mu N against the true sliding
speed), in units of the record's force drop D (median peak-to-trough of k e); D is 0.35-0.85 of the static
level. Twin = decelerating minus accelerating friction at equal sliding speed, over 10-90 % of each slip's
peak speed, median over slips. Ageing = OLS slope of the peak on ln(stick time) times the ln-range of the
stick times.

| case | its own measure | other measures |
|---|---|---|
| `none` | twin |t| <= 1e-4 D; ageing -0.3..0 % D on the stepped/hold seeds (1, 3, 5, 7: sticks 4.9-9.8x apart) | peak sd <= 0.15 % D |
| `load_variation` | N p-p 12.0-29.1 % of N0 (track 12.0-23.1, arm 17.4-29.1); mu(0) dN = 21-48 % of D | F-vs-v twin -0.22..+0.36 D (the load's; the coefficient's 0); track seeds: peak sd 10-15 % D |
| `twin_branch` | -0.220..-0.117 D (decelerating BELOW accelerating: the film persists) | slips 0.57-0.61 Tn long against 0.51-0.54 Tn in `none` |
| `static_ageing` | +0.150..+0.216 D over sticks 6.5-10.6x apart | slow-minus-fast peaks +0.14..+0.18 D (stepped seeds) |
| `triggering` | a 3.2-7.2 % of N0 (a mu_s N0 = 6-19 % of D), f_t 3.3-6.0 fn, f_t/f_ss 12.4-27.4, 0.24-0.46 from an integer; peaks lowered 3-17 % of D | patch scatter: peak sd 2.4-3.7 % D; F-vs-v twin -0.01..+0.08 D (the shaken load); on seed 7 the peak rises with the stick time by 0.16 D (stick times only 1.4x apart: an early trigger is a short stick and a low peak) |
| `drive_modulation` | a 0.23-0.41, f_m/f_ss 0.11-0.36 | stick times 1.5-2.0x apart within a record |

Over seeds 0-23 (self-check of 144 records): twin -0.220..-0.117 D; ageing +0.097..+0.238 D over sticks
5.8-10.6x apart; load p-p 12.0-29.1 %; triggering 0.155-0.46 from an integer; f_m/f_ss 0.10-0.40; 15-60 cycles.

What the `none` records contain (measured, seeds 0-7)
---------------------------------------------------
- The law is exactly single-valued (twin at the contact |t| <= 1e-4 D) with a static jump (mu_s 8-25 % above
  mu(0+)) and a weak wet strengthening branch beyond the friction minimum.
- Glen-law creep of the ice in stick: the stuck slider creeps at 0.4-1.2 % of the drive speed at the
  breakaway (less earlier in the stick, as (F/F_s)^3): the force ramp bends slightly before each slip.
- Holds (seeds 3, 7): the force relaxes by 0.4-3.8 % of D during each hold (the same creep), and the peak after
  a hold is the same static level: no ageing (-0.0 % D).
- Stepped drive (seeds 1, 5; 4-8x): the drop at the slow level is 0.98-0.99 of the fast one, the peaks differ
  -0.1..-0.3 % of D (the slider leaves the static level with the creep speed at both levels).
- Normal load exactly constant (the recorded normal column carries 0.2 % of N0 white noise); drive exact.
- A crude 1-DoF reading of the clean sampled force (reverse construction F + F''/wn^2 by central differences
  against vd - F'/k) reads -0.20..-0.003 D: -0.15..-0.20 at 10-14 samples per period, -0.003..-0.05 at
  30-97. This is the differencing of the sharp breakaway and arrest kinks (the same on the unfiltered samples;
  the anti-alias filter changes it by < 0.03 D), not a property of the law; it is stored in
  `twin_1dof_clean_samples_over_D` for every record.
- In `triggering` only, the static level scatters from stick to stick by 0.8-1.5 % (each slip lands on a new
  patch of ice): without it the breakaways lock to the shaker (f_t an exact multiple of f_ss, checked).

Runtime: 0.1-1.0 s a record (one core); the self-check's 48 records take about 11 s.
"""
from __future__ import annotations

import bisect
import math
import os
import time
import zlib

import numpy as np
from scipy import signal

NAME = "ice_sled"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

G = 9.81
STICK, SLIP = 0, 1


# ----------------------------------------------------------------------------------------------------------
# drive
# ----------------------------------------------------------------------------------------------------------
class Drive:
    """Piecewise-constant stage speed (knots) plus an optional sinusoidal lead error."""

    def __init__(self, t_knots, v_knots, a_mod=0.0, f_mod=0.0, phi_mod=0.0, v_mod_ref=0.0):
        self.tk = [float(t) for t in t_knots]
        self.vk = [float(v) for v in v_knots]
        xk = [0.0]
        for i in range(1, len(self.tk)):
            xk.append(xk[-1] + self.vk[i - 1] * (self.tk[i] - self.tk[i - 1]))
        self.xk = xk
        self.a = float(a_mod)
        self.w = 2 * math.pi * float(f_mod)
        self.phi = float(phi_mod)
        self.vr = float(v_mod_ref)

    def idx(self, t):
        return max(0, bisect.bisect_right(self.tk, t) - 1)

    def x(self, t):
        i = self.idx(t)
        xb = self.xk[i] + self.vk[i] * (t - self.tk[i])
        if self.a:
            xb -= self.a * self.vr / self.w * (math.cos(self.w * t + self.phi) - math.cos(self.phi))
        return xb

    def v(self, t):
        i = self.idx(t)
        vb = self.vk[i]
        if self.a:
            vb += self.a * self.vr * math.sin(self.w * t + self.phi)
        return vb

    def x_arr(self, t):
        t = np.asarray(t, float)
        tk = np.array(self.tk)
        i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 1)
        xb = np.array(self.xk)[i] + np.array(self.vk)[i] * (t - tk[i])
        if self.a:
            xb = xb - self.a * self.vr / self.w * (np.cos(self.w * t + self.phi) - math.cos(self.phi))
        return xb

    def v_arr(self, t):
        t = np.asarray(t, float)
        tk = np.array(self.tk)
        i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 1)
        vb = np.array(self.vk)[i]
        if self.a:
            vb = vb + self.a * self.vr * np.sin(self.w * t + self.phi)
        return vb

    def next_knot(self, t):
        i = bisect.bisect_right(self.tk, t)
        return self.tk[i] if i < len(self.tk) else math.inf


# ----------------------------------------------------------------------------------------------------------
# the switched system
# ----------------------------------------------------------------------------------------------------------
def simulate(P, drive, n_slips, t_max, tail_frac=0.5):
    """Integrate the STICK/SLIP system until n_slips arrests (plus a part of the next stick) or t_max.

    Returns dict of stored step points (t, x, v, h, dx, dv, mode) and event lists."""
    m, k, c = P["m"], P["k"], P["c"]
    mu_p, mu_a, mu_e, v_h, p_f, n_f = P["mu_p"], P["mu_a"], P["mu_e"], P["v_h"], P["p_film"], P["n_film"]
    lagged = P["film_lag"]
    tau_th, tau_fz = P.get("tau_th", 1.0), P.get("tau_fz", 1.0)
    vc0 = P["v_c0"]
    mus0, dA, tau_s, q_s = P["mu_s0"], P.get("age_delta", 0.0), P.get("age_tau", 1.0), P.get("age_q", 0.4)
    N0 = P["N0"]
    ltype = P.get("load_type", "const")
    la, llam, lphi, lc, lem, lde = (P.get("load_a", 0.0), P.get("load_lambda", 1.0), P.get("load_phi", 0.0),
                                    P.get("load_c", 0.0), P.get("load_em", 0.0), P.get("load_De", 1.0))
    ta_, tf_, tphi = P.get("trig_a", 0.0), P.get("trig_f", 0.0), P.get("trig_phi", 0.0)
    wt = 2 * math.pi * tf_
    xd_f, vd_f = drive.x, drive.v
    Tn = 1.0 / P["fn"]
    hd = P.get("h_div", 1.0)  # for convergence checks only
    H_slip = Tn / 160.0 / hd
    H_stick = Tn / 24.0 / hd
    if ta_:
        H_stick = min(H_stick, 1.0 / (18.0 * tf_))
        H_slip = min(H_slip, 1.0 / (18.0 * tf_))
    pw = p_f
    nm1 = n_f - 1.0

    if ltype == "track":
        def Nf(t, x, e):
            return N0 * (1.0 + la * math.sin(2 * math.pi * x / llam + lphi))
    elif ltype == "arm":
        def Nf(t, x, e):
            return N0 * (1.0 + lc * (e - lem) / lde)
    elif ltype == "shaker":
        def Nf(t, x, e):
            return N0 * (1.0 + ta_ * math.sin(wt * t + tphi))
    else:
        def Nf(t, x, e):
            return N0

    def hss(v):
        return (v / v_h) ** pw if v > 0.0 else 0.0

    def mu(v, h):
        if h <= 0.0:
            return mu_p + mu_a
        hn1 = h ** nm1
        return mu_p + (mu_a + mu_e * (v / v_h) * hn1) / (1.0 + hn1 * h)

    st = {"ta": 0.0, "xi": 1.0}  # time of the last arrest (start of the stick), this stick's patch factor
    sc_sd = P.get("patch_sd", 0.0)
    sc_rng = np.random.default_rng(P.get("patch_seed", 0))
    if dA:
        def mus(tst):
            return (mus0 + dA * ((1.0 + tst / tau_s) ** q_s - 1.0)) * st["xi"]
    else:
        def mus(tst):
            return mus0 * st["xi"]

    def vcr(t, x, h):
        e = xd_f(t) - x
        Fs = mus(t - st["ta"]) * Nf(t, x, e)
        r = k * e / Fs
        return vc0 * r * r * r

    def f_stick(t, y):
        x, v, h = y
        return (vcr(t, x, h), 0.0, (-h / tau_fz) if lagged else 0.0)

    def f_slip(t, y):
        x, v, h = y
        e = xd_f(t) - x
        N = Nf(t, x, e)
        he = h if lagged else hss(v)
        a = (k * e + c * (vd_f(t) - v) - mu(v, he) * N) / m
        dh = (hss(v) - h) / tau_th if lagged else 0.0
        return (v, a, dh)

    def g_break(t, y):
        x = y[0]
        e = xd_f(t) - x
        N = Nf(t, x, e)
        Fs = mus(t - st["ta"]) * N
        r = k * e / Fs
        return k * e + c * (vd_f(t) - vc0 * r * r * r) - Fs

    def gbs(f, t, y, f0, H):
        out = []
        for n in (2, 4):
            h = H / n
            z0 = y
            z1 = (y[0] + h * f0[0], y[1] + h * f0[1], y[2] + h * f0[2])
            for i in range(1, n):
                fz = f(t + i * h, z1)
                z0, z1 = z1, (z0[0] + 2 * h * fz[0], z0[1] + 2 * h * fz[1], z0[2] + 2 * h * fz[2])
            fz = f(t + H, z1)
            out.append((0.5 * (z0[0] + z1[0] + h * fz[0]), 0.5 * (z0[1] + z1[1] + h * fz[1]),
                        0.5 * (z0[2] + z1[2] + h * fz[2])))
        a, b = out
        return (b[0] + (b[0] - a[0]) / 3.0, b[1] + (b[1] - a[1]) / 3.0, b[2] + (b[2] - a[2]) / 3.0)

    def herm(s, H, y0, d0, y1, d1):
        h00 = (1 + 2 * s) * (1 - s) ** 2
        h10 = s * (1 - s) ** 2
        h01 = s * s * (3 - 2 * s)
        h11 = s * s * (s - 1)
        return tuple(h00 * a + h10 * H * b + h01 * cc + h11 * H * d for a, b, cc, d in zip(y0, d0, y1, d1))

    def locate(gfun, t0, t1, g0, g1):
        """Safeguarded Newton on g along the step's interpolant: returns the guard's time."""
        lo, hi, glo = t0, t1, g0
        t = t0 - g0 * (t1 - t0) / (g1 - g0)
        span = t1 - t0
        for _ in range(40):
            g = gfun(t)
            if (g < 0) == (glo < 0):
                lo, glo = t, g
            else:
                hi = t
            if abs(hi - lo) < 1e-11 * span or g == 0.0:
                break
            dt = 1e-6 * span
            dg = (gfun(min(t + dt, t1)) - gfun(max(t - dt, t0))) / (min(t + dt, t1) - max(t - dt, t0))
            tn = t - g / dg if dg != 0 else 0.5 * (lo + hi)
            if not (lo < tn < hi):
                tn = 0.5 * (lo + hi)
            if abs(tn - t) < 1e-12 * span:
                t = tn
                break
            t = tn
        return t

    T, X, V, Hh, DX, DV, MODE = [], [], [], [], [], [], []
    breaks, arrests = [], []  # (time, needed force / static limit info)
    t = 0.0
    y = (0.0, 0.0, 0.0)
    mode = STICK
    y = (y[0], vcr(t, y[0], y[2]), y[2])
    f0 = f_stick(t, y)

    def store(t, y, f0, md):
        T.append(t); X.append(y[0]); V.append(y[1]); Hh.append(y[2]); DX.append(f0[0]); DV.append(f0[1])
        MODE.append(md)

    store(t, y, f0, mode)
    t_stop = None
    n_steps = 0
    while t < t_max:
        if t_stop is not None and t >= t_stop:
            break
        H = H_stick if mode == STICK else H_slip
        t1 = t + H
        kn = drive.next_knot(t + 1e-12)
        if kn < t1 - 1e-12:
            t1 = kn
        H = t1 - t
        f = f_stick if mode == STICK else f_slip
        y1 = gbs(f, t, y, f0, H)
        n_steps += 1
        if mode == STICK:
            y1 = (y1[0], vcr(t1, y1[0], y1[2]), y1[2])
            f1 = f_stick(t1, y1)
            g0, g1 = g_break(t, y), g_break(t1, y1)
            if g1 >= 0.0:
                if g0 >= 0.0:
                    te = t
                else:
                    y0c, f0c, t0c = y, f0, t

                    def gh(tt):
                        yy = herm((tt - t0c) / H, H, y0c, f0c, y1, f1)
                        return g_break(tt, yy)
                    te = locate(gh, t, t1, g0, g1)
                    if te > t:
                        ye = gbs(f_stick, t, y, f0, te - t)
                        y1 = (ye[0], vcr(te, ye[0], ye[2]), ye[2])
                    else:
                        y1 = y
                    t1 = te
                    f1 = f_stick(t1, y1)
                    store(t1, y1, f1, STICK)
                x = y1[0]
                e = drive.x(t1) - x
                breaks.append((t1, k * e, t1 - st["ta"], mus(t1 - st["ta"]) * Nf(t1, x, e)))
                mode = SLIP
                f1 = f_slip(t1, y1)
                store(t1, y1, f1, SLIP)
                t, y, f0 = t1, y1, f1
                continue
            store(t1, y1, f1, STICK)
            t, y, f0 = t1, y1, f1
        else:
            f1 = f_slip(t1, y1)
            if y1[1] <= 0.0:
                y0c, f0c, t0c = y, f0, t

                def gv(tt):
                    return herm((tt - t0c) / H, H, y0c, f0c, y1, f1)[1]
                te = locate(gv, t, t1, y[1], y1[1])
                ye = gbs(f_slip, t, y, f0, te - t) if te > t else y
                y1 = (ye[0], 0.0, ye[2])
                t1 = te
                f1 = f_slip(t1, y1)
                store(t1, y1, f1, SLIP)
                x = y1[0]
                e = drive.x(t1) - x
                need = k * e + c * drive.v(t1)
                if need > mus(0.0) * Nf(t1, x, e):
                    # beyond the static limit at rest: slides on
                    y1 = (y1[0], 1e-12, y1[2])
                    t, y, f0 = t1, y1, f_slip(t1, y1)
                    continue
                arrests.append((t1, k * e))
                st["ta"] = t1
                if sc_sd:
                    st["xi"] = 1.0 + sc_sd * float(np.clip(sc_rng.normal(), -3, 3))
                mode = STICK
                y1 = (y1[0], vcr(t1, y1[0], y1[2]), y1[2])
                f1 = f_stick(t1, y1)
                store(t1, y1, f1, STICK)
                t, y, f0 = t1, y1, f1
                if len(arrests) >= n_slips and t_stop is None:
                    # the rest of this stick, part of it
                    t_stop = t1 + tail_frac * P.get("stick_est", 5 * Tn)
                continue
            store(t1, y1, f1, SLIP)
            t, y, f0 = t1, y1, f1
    res = {k_: np.array(v_) for k_, v_ in
           (("t", T), ("x", X), ("v", V), ("h", Hh), ("dx", DX), ("dv", DV), ("mode", MODE))}
    res["breaks"] = breaks
    res["arrests"] = arrests
    res["n_steps"] = n_steps
    # the contact's true friction and load at the stored points
    xd = drive.x_arr(res["t"])
    e = xd - res["x"]
    res["e"] = e
    res["F"] = k * e
    tt, xx = res["t"], res["x"]
    if ltype == "track":
        N = N0 * (1 + la * np.sin(2 * np.pi * xx / llam + lphi))
    elif ltype == "arm":
        N = N0 * (1 + lc * (e - lem) / lde)
    elif ltype == "shaker":
        N = N0 * (1 + ta_ * np.sin(wt * tt + tphi))
    else:
        N = np.full_like(tt, N0)
    res["N"] = N
    v = np.maximum(res["v"], 0.0)
    he = res["h"] if lagged else np.where(v > 0, (v / v_h) ** pw, 0.0)
    hn = np.where(he > 0, he, 0.0)
    mu_arr = mu_p + (mu_a + mu_e * (v / v_h) * hn ** nm1) / (1.0 + hn ** n_f)
    res["Ff"] = np.where(res["mode"] == SLIP, mu_arr * N, np.nan)
    return res


def hermite_grid(res, tq):
    """Cubic Hermite of the slider's position and speed on the query times."""
    T = res["t"]
    i = np.clip(np.searchsorted(T, tq, side="right") - 1, 0, len(T) - 2)
    H = T[i + 1] - T[i]
    H = np.where(H > 0, H, 1.0)
    s = np.clip((tq - T[i]) / H, 0.0, 1.0)
    h00 = (1 + 2 * s) * (1 - s) ** 2
    h10 = s * (1 - s) ** 2
    h01 = s * s * (3 - 2 * s)
    h11 = s * s * (s - 1)
    x = h00 * res["x"][i] + h10 * H * res["dx"][i] + h01 * res["x"][i + 1] + h11 * H * res["dx"][i + 1]
    return x


# ----------------------------------------------------------------------------------------------------------
# ground-truth measurements
# ----------------------------------------------------------------------------------------------------------
def cycles_truth(res):
    """Per slip: peak (max F from breakaway to arrest), trough (min F), stick time before it, max speed."""
    t, F, v = res["t"], res["F"], res["v"]
    out = []
    arr_t = [a[0] for a in res["arrests"]]
    for j, (tb, Fb, tst, Fs) in enumerate(res["breaks"]):
        # the arrest that follows
        k_ = bisect.bisect_right(arr_t, tb)
        if k_ >= len(arr_t):
            break
        ta = arr_t[k_]
        sel = (t >= tb) & (t <= ta)
        if sel.sum() < 3:
            continue
        out.append({"tb": tb, "ta": ta, "peak": float(F[sel].max()), "trough": float(F[sel].min()),
                    "tst": tst, "Fs": Fs, "vmax": float(v[sel].max())})
    return out


def twin_truth(res, cyc, per_load=False):
    """Decelerating minus accelerating contact friction at equal true sliding speed (10-90 % of each slip's
    peak speed), mean over the speed grid, median over slips (force units; per_load: the coefficient times
    the mean load, i.e. the law's own twin with the load's variation taken out)."""
    t, v, Ff = res["t"], res["v"], res["Ff"]
    if per_load:
        Ff = Ff / res["N"] * float(np.mean(res["N"]))
    vals = []
    for c_ in cyc:
        sel = np.where((t >= c_["tb"]) & (t <= c_["ta"]))[0]
        vv, ff = v[sel], Ff[sel]
        ok = np.isfinite(ff)
        vv, ff = vv[ok], ff[ok]
        if len(vv) < 10:
            continue
        im = int(np.argmax(vv))
        if im < 3 or im > len(vv) - 4:
            continue
        va, fa = vv[:im + 1], ff[:im + 1]
        vd, fd = vv[im:][::-1], ff[im:][::-1]
        grid = np.linspace(0.1, 0.9, 41) * vv[im]
        ia = np.argsort(va)
        idd = np.argsort(vd)
        fa_g = np.interp(grid, va[ia], fa[ia])
        fd_g = np.interp(grid, vd[idd], fd[idd])
        vals.append(float(np.mean(fd_g - fa_g)))
    return float(np.median(vals)) if vals else 0.0


def ageing_truth(cyc):
    """OLS of the peak on ln(stick time), times ln(max/min stick time) (force units), and the ratio."""
    ts = np.array([c_["tst"] for c_ in cyc])
    pk = np.array([c_["peak"] for c_ in cyc])
    if len(ts) < 4 or ts.max() / ts.min() < 1.3:
        return 0.0, float(ts.max() / ts.min()) if len(ts) else 1.0
    lx = np.log(ts)
    b = np.polyfit(lx, pk, 1)[0]
    return float(b * (lx.max() - lx.min())), float(ts.max() / ts.min())


# ----------------------------------------------------------------------------------------------------------
# parameters
# ----------------------------------------------------------------------------------------------------------
def draw_physics(case, seed):
    rng = np.random.default_rng([zlib.crc32(NAME.encode()), CASES.index(case), int(seed), 7])
    P = {}
    fn = float(np.exp(rng.uniform(math.log(4.0), math.log(25.0))))
    m = float(rng.uniform(1.5, 8.0))
    k = m * (2 * math.pi * fn) ** 2
    zeta = float(rng.uniform(0.01, 0.04))
    N0 = m * G * float(rng.uniform(1.0, 1.5))
    mu0 = float(rng.uniform(0.08, 0.3))
    fa = float(rng.uniform(0.2, 0.4))
    n_f = float(rng.uniform(1.6, 2.4))
    p_f = float(rng.uniform(0.45, 0.6))
    P.update(fn=fn, m=m, k=k, zeta=zeta, c=2 * zeta * math.sqrt(k * m), N0=N0, mu0=mu0,
             mu_a=fa * mu0, mu_p=(1 - fa) * mu0, n_film=n_f, p_film=p_f,
             mu_e=fa * mu0 * float(rng.uniform(0.12, 0.25)),
             mu_s0=mu0 * float(rng.uniform(1.08, 1.25)), film_lag=False)
    w = 2 * math.pi * fn
    # slip-speed scale: half the expected drop over k, times omega
    D_est = 2 * (P["mu_s0"] - 0.88 * mu0) * N0
    Vp = 0.5 * D_est / k * w
    P["v_h"] = Vp * float(rng.uniform(0.12, 0.4))
    P["D_est"] = D_est
    P["ratio_target"] = float(rng.uniform(4.0, 11.0))   # stick-slip period / Tn at the (mean/fast) speed
    P["n_cycles"] = int(rng.integers(15, 61))
    P["creep_frac"] = float(rng.uniform(0.003, 0.012))
    if case == "triggering":
        # the contact meets a new patch of ice at each slip: its static level scatters from stick to stick
        # (without it the breakaways lock to the shaker, f_t an exact multiple of f_ss)
        P["patch_sd"] = float(rng.uniform(0.008, 0.015))
        P["patch_seed"] = int(rng.integers(0, 2**31))
        P["ratio_target"] = float(rng.uniform(3.0, 8.0))
    P["_rng_state"] = rng
    return P


def _clean(d):
    out = {}
    for k_, v in d.items():
        if k_.startswith("_"):
            continue
        if isinstance(v, (np.floating, np.integer)):
            v = v.item()
        if isinstance(v, float) and not math.isfinite(v):
            v = None
        if isinstance(v, (list, tuple)):
            v = [x.item() if isinstance(x, (np.floating, np.integer)) else x for x in v]
        out[k_] = v
    return out


def period_of(res):
    tb = np.array([b[0] for b in res["breaks"]])
    if len(tb) < 3:
        return math.nan
    return float(np.median(np.diff(tb[1:])))


def build(case, seed):
    """Draw the physics for (case, seed), calibrate, simulate; returns (P, drive, res, measured)."""
    P = draw_physics(case, seed)
    rng = P["_rng_state"]
    fn, Tn, k = P["fn"], 1.0 / P["fn"], P["k"]
    # speed from the expected drop; one short pre-run rescales it to the target period
    v0 = P["D_est"] / k / (P["ratio_target"] * Tn)
    P["v_c0"] = P["creep_frac"] * v0
    P["stick_est"] = P["ratio_target"] * Tn
    pre = simulate(P, Drive([0.0], [v0]), 6, 400 * Tn)
    T_pre = period_of(pre)
    cyc = cycles_truth(pre)
    D_pre = float(np.median([c_["peak"] - c_["trough"] for c_ in cyc[1:]]))
    slip_T = float(np.median([c_["ta"] - c_["tb"] for c_ in cyc[1:]]))
    # stick time scales as 1/v0
    st_pre = T_pre - slip_T
    st_want = P["ratio_target"] * Tn - slip_T
    scale = st_pre / max(st_want, 0.8 * Tn)
    v0 = v0 * scale
    P["v0"] = v0
    P["D_pre"] = D_pre
    P["slip_T"] = slip_T
    T_ss = slip_T + st_pre / scale
    P["v_c0"] = P["creep_frac"] * v0
    P["stick_est"] = T_ss - slip_T
    ncyc = P["n_cycles"]
    drive_kind = "constant"
    if case == "none":
        drive_kind = {1: "steps", 3: "holds"}.get(seed % 4, "constant")
    elif case == "static_ageing":
        drive_kind = "steps" if seed % 2 == 0 else "holds"
    P["drive_kind"] = drive_kind
    if case == "triggering":
        ncyc = min(ncyc, 40)
    if drive_kind != "constant":
        ncyc = max(ncyc, 20)
    ncyc = min(ncyc, 57)
    P["n_cycles"] = ncyc

    # --- the drive's programme
    if drive_kind == "steps":
        r = float(rng.uniform(4.0, 8.0))
        v_fast = v0 * float(rng.uniform(1.2, 2.0))
        v_slow = v_fast / r
        st_fast = P["stick_est"] * v0 / v_fast
        st_slow = st_fast * r
        tk, vk = [0.0], []
        t_ = 0.0
        level = int(rng.integers(0, 2))
        tot = 0
        while tot < ncyc + 4:
            nb = int(rng.integers(4, 8)) if level == 0 else int(rng.integers(2, 5))
            vv = v_fast if level == 0 else v_slow
            dur = nb * ((st_fast if level == 0 else st_slow) + slip_T)
            vk.append(vv)
            t_ += dur
            tk.append(t_)
            tot += nb
            level = 1 - level
        vk.append(vk[-2])
        drive = Drive(tk, vk)
        P.update(v_fast=v_fast, v_slow=v_slow, step_ratio=r, v_mean=float(np.mean(vk)))
        P["stick_est"] = st_slow
        t_max = tk[-1] * 1.5 + 50 * Tn
    elif drive_kind == "holds":
        tk, vk = [0.0], [v0]
        t_ = 0.0
        n_h = 0
        T_cyc = P["stick_est"] + slip_T
        tot = 0
        while tot < ncyc + 4:
            nb = int(rng.integers(3, 7))
            t_ += (nb + float(rng.uniform(0.2, 0.8))) * T_cyc
            th = float(rng.uniform(3.5, 9.0)) * P["stick_est"]
            tk += [t_, t_ + th]
            vk += [0.0, v0]
            t_ += th
            tot += nb + 1
            n_h += 1
        drive = Drive(tk, vk)
        P.update(n_holds=n_h)
        t_max = t_ * 1.5 + 50 * Tn
    elif case == "drive_modulation":
        a = float(rng.uniform(0.20, 0.45))
        fm = float(rng.uniform(0.1, 0.4)) / T_ss
        ph = float(rng.uniform(0, 2 * math.pi))
        drive = Drive([0.0], [v0], a, fm, ph, v0)
        P.update(mod_a=a, mod_f=fm, mod_phi=ph, mod_f_over_fss_design=fm * T_ss)
        t_max = (ncyc + 4) * T_ss * 3 + 50 * Tn
    else:
        drive = Drive([0.0], [v0])
        t_max = (ncyc + 4) * T_ss * 3 + 50 * Tn

    # --- departures
    if case == "load_variation":
        if seed % 2 == 0:
            adv = v0 * T_ss
            P.update(load_type="track", load_a=0.5 * float(rng.uniform(0.12, 0.30)),
                     load_lambda=float(rng.uniform(2.5, 6.0)) * adv, load_phi=float(rng.uniform(0, 2 * math.pi)))
        else:
            De = D_pre / k
            em = (P["mu_s0"] * P["N0"] - 0.5 * D_pre) / k
            cc = float(rng.uniform(0.12, 0.30)) * (1 if rng.uniform() < 0.5 else -1)
            if cc > 0:
                cc = min(cc, 0.2)
            P.update(load_type="arm", load_c=cc, load_em=em, load_De=De)
    elif case == "triggering":
        P.update(load_type="shaker", trig_a=float(rng.uniform(0.03, 0.08)),
                 trig_phi=float(rng.uniform(0, 2 * math.pi)))
    elif case == "twin_branch":
        P["film_lag"] = True
        P["tau_fz"] = float(rng.uniform(0.15, 0.4)) * Tn
        P["twin_target"] = float(rng.uniform(0.12, 0.22))
    elif case == "static_ageing":
        P["age_q"] = float(rng.uniform(0.25, 0.45))
        st_min = P["stick_est"] / (P.get("step_ratio", 1.0)) if drive_kind == "steps" else P["stick_est"]
        P["age_tau"] = float(rng.uniform(0.05, 0.3)) * st_min
        P["age_target"] = float(rng.uniform(0.11, 0.19))

    # calibrations on short runs
    if case == "twin_branch":
        taus = np.array([0.02, 0.05, 0.1, 0.2]) * Tn
        tw = []
        for tau in taus:
            P["tau_th"] = float(tau)
            rr = simulate(P, Drive([0.0], [v0]), 5, 300 * Tn)
            cy = cycles_truth(rr)[1:]
            D_ = np.median([c_["peak"] - c_["trough"] for c_ in cy])
            tw.append(-twin_truth(rr, cy) / D_)
        tw = np.array(tw)
        tgt = P["twin_target"]
        # monotone interpolation in log tau
        order = np.argsort(tw)
        P["tau_th"] = float(np.exp(np.interp(tgt, tw[order], np.log(taus[order]))))
        P["twin_calib"] = {"tau_over_Tn": (taus / Tn).tolist(), "twin_over_D": tw.tolist()}
    if case == "static_ageing":
        P["age_delta"] = 0.15 * D_pre / P["N0"]
    if case == "triggering":
        f_ss0 = 1.0 / T_ss
        P["_trig_tries"] = 0

    # --- the run (re-done for calibration where needed)
    best = None
    for attempt in range(12 if case == "triggering" else 6):
        if case == "triggering":
            f_ref = f_ss0 if attempt == 0 else f_ss_rec
            for _ in range(200):
                ft = float(rng.uniform(2.5, 7.0)) * fn
                rr_ = ft / f_ref
                if abs(rr_ - round(rr_)) >= 0.25:
                    break
            P["trig_f"] = ft
        res = simulate(P, drive, ncyc + 1, t_max)
        cyc = cycles_truth(res)
        cyc_r = cyc[1:]
        D = float(np.median([c_["peak"] - c_["trough"] for c_ in cyc_r]))
        if case == "static_ageing":
            grow, ratio = ageing_truth(cyc_r)
            g = grow / D
            P.setdefault("age_calib", []).append([P["age_delta"], g])
            if 0.09 <= g <= 0.24 or attempt >= 3:
                break
            P["age_delta"] *= P["age_target"] / max(g, 0.02)
            continue
        if case == "load_variation" and P["load_type"] == "arm":
            sel = res["t"] >= cyc_r[0]["tb"] - 0.5 * T_ss
            pp = float(np.ptp(res["N"][sel]) / P["N0"])
            P.setdefault("load_calib", []).append([P["load_c"], pp])
            tgt = 0.5 * (0.12 + 0.30)
            if 0.12 <= pp <= 0.30 or attempt >= 3:
                break
            P["load_c"] *= min(0.2 / abs(P["load_c"]), tgt / pp) if P["load_c"] > 0 else tgt / pp
            continue
        if case == "triggering":
            tbs = np.array([c_["tb"] for c_ in cyc_r])
            f_ss_rec = (len(tbs) - 1) / (tbs[-1] - tbs[0])
            rr_ = P["trig_f"] / f_ss_rec
            dist = abs(rr_ - round(rr_))
            P["_trig_tries"] += 1
            P.setdefault("trig_scan", []).append([P["trig_f"] / fn, rr_])
            if best is None or dist > best[0]:
                best = (dist, P["trig_f"], res, cyc)
            if dist >= 0.15:
                break
            continue
        break
    if case == "triggering":
        P["trig_f"] = best[1]
        res, cyc = best[2], best[3]
    return P, drive, res, cyc


def measure(case, P, drive, res, cyc, t0, t1):
    """Effect sizes on the ground truth within the record window [t0, t1]."""
    cyc_r = [c_ for c_ in cyc if c_["tb"] >= t0 and c_["ta"] <= t1]
    D = float(np.median([c_["peak"] - c_["trough"] for c_ in cyc_r]))
    pk = np.array([c_["peak"] for c_ in cyc_r])
    tbs = np.array([c_["tb"] for c_ in cyc_r])
    Mx = {"cycles": len(cyc_r), "drop_N": D, "drop_over_Fs": D / (P["mu_s0"] * P["N0"])}
    Mx["twin_over_D"] = twin_truth(res, cyc_r) / D
    Mx["twin_coefficient_over_D"] = twin_truth(res, cyc_r, per_load=True) / D
    g, ratio = ageing_truth(cyc_r)
    Mx["ageing_growth_over_D"] = g / D
    Mx["stick_time_ratio"] = ratio
    Mx["peak_sd_over_D"] = float(np.std(pk) / D)
    Mx["f_ss"] = float((len(tbs) - 1) / (tbs[-1] - tbs[0]))
    Mx["T_ss_over_Tn"] = P["fn"] / Mx["f_ss"]
    sel = (res["t"] >= t0) & (res["t"] <= t1)
    Mx["load_pp_over_N0"] = float(np.ptp(res["N"][sel]) / P["N0"])
    Mx["load_pp_force_over_D"] = float(P["mu0"] * np.ptp(res["N"][sel]) / D)
    # creep at the breakaway relative to the local drive speed
    vd_b = np.array([drive.v(c_["tb"]) for c_ in cyc_r])
    Mx["creep_at_peak_over_vd"] = float(np.median(P["v_c0"] / np.maximum(vd_b, 1e-12)))
    Mx["slip_duration_over_Tn"] = float(np.median([(c_["ta"] - c_["tb"]) * P["fn"] for c_ in cyc_r]))
    if case == "triggering":
        rr = P["trig_f"] / Mx["f_ss"]
        Mx["ft_over_fn"] = P["trig_f"] / P["fn"]
        Mx["ft_over_fss"] = rr
        Mx["ft_over_fss_dist_int"] = abs(rr - round(rr))
        Mx["shaker_force_over_D"] = P["trig_a"] * P["mu_s0"] * P["N0"] / D
        Mx["peak_lowering_over_D"] = float(np.mean(P["mu_s0"] * P["N0"] - pk) / D)
    if case == "drive_modulation":
        Mx["mod_a"] = P["mod_a"]
        Mx["fm_over_fss"] = P["mod_f"] / Mx["f_ss"]
    if case == "load_variation":
        Mx["load_type"] = P["load_type"]
    # what a 1-DoF reading may mistake in a record without a departure
    if P["drive_kind"] == "steps":
        vb = np.array([drive.v(c_["tb"]) for c_ in cyc_r])
        dr = np.array([c_["peak"] - c_["trough"] for c_ in cyc_r])
        fast = vb > 0.5 * (vb.max() + vb.min())
        if fast.any() and (~fast).any():
            Mx["drop_slow_over_fast"] = float(np.median(dr[~fast]) / np.median(dr[fast]))
            Mx["peak_slow_minus_fast_over_D"] = float((np.median(pk[~fast]) - np.median(pk[fast])) / D)
    if P["drive_kind"] == "holds":
        rel = []
        for i in range(1, len(drive.tk) - 1, 2):
            th0, th1 = drive.tk[i], drive.tk[i + 1]
            if th0 < t0 or th1 > t1:
                continue
            s0 = (res["t"] >= th0) & (res["t"] <= th1) & (res["mode"] == STICK)
            if s0.sum() > 2:
                Fh = res["F"][s0]
                rel.append(float((Fh[0] - Fh[-1]) / D))
        Mx["hold_relaxation_over_D"] = rel
    return Mx


def _twin_1dof(Fr, ts, drive, P, res, t0, t1, D):
    k, wn = P["k"], 2 * math.pi * P["fn"]
    dt = ts[1] - ts[0]
    F1 = np.gradient(Fr, dt)
    F2 = np.gradient(F1, dt)
    v = drive.v_arr(ts) - F1 / k
    fr = Fr + F2 / wn ** 2
    vals = []
    arr_t = [a[0] for a in res["arrests"]]
    for tb, _, _, _ in res["breaks"]:
        j = bisect.bisect_right(arr_t, tb)
        if j >= len(arr_t) or tb < t0 or arr_t[j] > t1:
            continue
        sel = np.where((ts >= tb) & (ts <= arr_t[j]))[0]
        if len(sel) < 6:
            continue
        vv, ff = v[sel], fr[sel]
        im = int(np.argmax(vv))
        if im < 2 or im > len(vv) - 3:
            continue
        grid = np.linspace(0.1, 0.9, 41) * vv[im]
        va, fa, vd_, fd = vv[:im + 1], fr[sel][:im + 1], vv[im:], fr[sel][im:]
        ia, idd = np.argsort(va), np.argsort(vd_)
        vals.append(float(np.mean(np.interp(grid, vd_[idd], fd[idd]) - np.interp(grid, va[ia], fa[ia]))))
    return float(np.median(vals) / D) if vals else None


# ----------------------------------------------------------------------------------------------------------
# the record
# ----------------------------------------------------------------------------------------------------------
def _fmt_num(v, nd, dec_comma):
    s = f"{v:.{nd}f}"
    return s.replace(".", ",") if dec_comma else s


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError(f"unknown case {case}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance}")
    P, drive, res, cyc = build(case, seed)
    fn, Tn, k = P["fn"], 1.0 / P["fn"], P["k"]
    # format and record stream: (case, seed) only, nuisance stream separate
    frng = np.random.default_rng([zlib.crc32(NAME.encode()), CASES.index(case), int(seed), 11])
    nrng = np.random.default_rng([zlib.crc32(NAME.encode()), CASES.index(case), int(seed),
                                  NUISANCES.index(nuisance), 13])

    # record window: from part of the first full stick to part of the last
    arr = [a[0] for a in res["arrests"]]
    brk = [b[0] for b in res["breaks"]]
    t0 = arr[0] + float(frng.uniform(0.2, 0.7)) * (brk[1] - arr[0])
    t1 = min(res["t"][-1], arr[-1] + 0.4 * (res["t"][-1] - arr[-1]) + 1e-9)
    if t1 <= arr[-1]:
        t1 = res["t"][-1]
    Mx = measure(case, P, drive, res, cyc, t0, t1)
    D = Mx["drop_N"]

    spp = float(np.exp(frng.uniform(math.log(10.0), math.log(100.0))))
    if nuisance == "coarse":
        spp = float(nrng.uniform(10.0, 15.0))
    if nuisance == "hum":
        spp = min(100.0, max(spp, 300.0 / fn))
    fs = spp * fn
    ovs = 8
    dt_f = 1.0 / (fs * ovs)
    n_rec = int((t1 - t0) * fs)
    tf = t0 + np.arange(n_rec * ovs) * dt_f
    xs = hermite_grid(res, tf)
    ef = drive.x_arr(tf) - xs
    Ff = k * ef
    # normal load on the fine grid
    lt = P.get("load_type", "const")
    if lt == "track":
        Nf = P["N0"] * (1 + P["load_a"] * np.sin(2 * np.pi * xs / P["load_lambda"] + P["load_phi"]))
    elif lt == "arm":
        Nf = P["N0"] * (1 + P["load_c"] * (ef - P["load_em"]) / P["load_De"])
    elif lt == "shaker":
        Nf = P["N0"] * (1 + P["trig_a"] * np.sin(2 * np.pi * P["trig_f"] * tf + P["trig_phi"]))
    else:
        Nf = np.full_like(tf, P["N0"])
    # anti-alias: 3rd-order Butterworth at 0.3 fs, causal, started at rest on the first value
    b, a = signal.butter(3, 0.3 * fs / (0.5 * fs * ovs))
    zi = signal.lfilter_zi(b, a)
    Fr = signal.lfilter(b, a, Ff, zi=zi * Ff[0])[0][::ovs]
    Nr = signal.lfilter(b, a, Nf, zi=zi * Nf[0])[0][::ovs]
    tr = (tf[::ovs] - t0)
    n = len(tr)
    # a 1-DoF reading of the clean sampled force (reverse construction F + F''/wn^2 against vd - F'/k,
    # central differences; the slips delimited by the true events): the sensor's share of a twin
    Mx["twin_1dof_clean_samples_over_D"] = _twin_1dof(Fr, tr + t0, drive, P, res, t0, t1, D)

    # sensor noise (white + AR(1) amplifier wander), from the (case, seed, nuisance) stream
    sig = float(nrng.uniform(0.002, 0.01)) * D
    share = float(nrng.uniform(0.2, 0.5))
    tc = float(nrng.uniform(0.2, 2.0))
    phi_ar = math.exp(-1.0 / (fs * tc))
    w_ar = nrng.normal(0, 1, n) * math.sqrt(1 - phi_ar ** 2)
    ar = signal.lfilter([1.0], [1.0, -phi_ar], w_ar)
    noise = sig * (math.sqrt(1 - share ** 2) * nrng.normal(0, 1, n) + share * ar)
    Fr = Fr + noise
    Nr = Nr + 0.002 * P["N0"] * nrng.normal(0, 1, n)
    # cold-room temperature (ice): a compressor cycle
    T_ice0 = float(frng.uniform(-18.0, -4.0))
    P_comp = float(frng.uniform(300.0, 1200.0))
    ph_c = float(frng.uniform(0, 2 * math.pi))
    T_ice = T_ice0 + 0.25 * np.sin(2 * np.pi * tr / P_comp + ph_c) + 0.01 * nrng.normal(0, 1, n)
    nz = {"noise_sd_over_D": sig / D}
    if nuisance == "hum":
        fmains = 50.0 if nrng.uniform() < 0.5 else 60.0
        amp = float(nrng.uniform(0.01, 0.05)) * D
        hum = np.zeros(n)
        rel = [1.0, float(nrng.uniform(0.1, 0.4)), float(nrng.uniform(0.1, 0.5))]
        tot = sum(rl for j, rl in enumerate(rel) if (j + 1) * fmains < 0.4 * fs)
        for j, rl in enumerate(rel):
            if (j + 1) * fmains < 0.4 * fs:
                hum += rl / tot * np.sin(2 * np.pi * (j + 1) * fmains * tr + nrng.uniform(0, 2 * np.pi))
        Fr = Fr + amp * hum
        nz.update(mains_hz=fmains, hum_amp_over_D=amp / D)
    elif nuisance == "drift":
        amp = float(nrng.uniform(0.015, 0.03)) * D
        # the load cell's offset follows the room's temperature with a thermal lag
        lag = float(nrng.uniform(60.0, 300.0))
        u = np.sin(2 * np.pi * tr / P_comp + ph_c - math.atan(2 * np.pi * lag / P_comp))
        u = u - u[0]
        sgn = 1.0 if nrng.uniform() < 0.5 else -1.0
        u = u / max(np.max(np.abs(u)), 1e-9) if np.max(np.abs(u)) > 0 else u
        if np.max(np.abs(u)) < 1e-6:
            u = tr / tr[-1]
        Fr = Fr + sgn * amp * u
        nz.update(drift_over_D=amp / D)
    elif nuisance == "spikes":
        frac = float(nrng.uniform(0.0005, 0.005))
        ns = max(1, int(round(frac * n)))
        idx = nrng.choice(n, ns, replace=False)
        Fr[idx] = Fr[idx] + nrng.choice([-1, 1], ns) * nrng.uniform(0.1, 0.3, ns) * D
        nz.update(spike_fraction=ns / n)
    elif nuisance == "quantisation":
        q = float(nrng.uniform(0.002, 0.01)) * D
        Fr = np.round(Fr / q) * q
        nz.update(adc_step_over_D=q / D)

    # ---------------- the file
    kind_force = True
    want_normal = False
    if case == "load_variation":
        want_normal = (seed % 4) in (0, 1)
    elif seed % 4 == 2 and case not in ("drive_modulation",):
        want_normal = True
    if not want_normal and frng.uniform() < 0.375:
        kind_force = False
    drive_col = None
    if P["drive_kind"] != "constant":
        drive_col = ("pos", "speed")[int(frng.integers(0, 2))] if P["drive_kind"] == "steps" else "pos"
    elif case == "drive_modulation":
        drive_col = "setspeed" if frng.uniform() < 0.25 else None
    elif frng.uniform() < 0.35:
        drive_col = ("pos", "speed")[int(frng.integers(0, 2))]
    temp_col = frng.uniform() < 0.4
    style = int(frng.integers(0, 4))  # 0 comma, 1 tab, 2 whitespace, 3 semicolon+decimal comma
    time_ms = frng.uniform() < 0.2
    f_unit = "mN" if frng.uniform() < 0.4 else "N"
    x_unit = "um" if frng.uniform() < 0.4 else "mm"
    pos_unit = "um" if frng.uniform() < 0.5 else "mm"

    def hdr(name, unit):
        if style == 0:
            return f"{name} [{unit}]"
        if style == 1:
            return f"{name} ({unit})"
        if style == 2:
            return f"{name.replace(' ', '_')}_{unit.replace('/', '_')}"
        return f"{name} [{unit}]"

    cols, names, nds = [], [], []
    tt = tr * (1000.0 if time_ms else 1.0)
    names.append(hdr("Time", "ms" if time_ms else "s")); cols.append(tt); nds.append(4 if time_ms else 6)
    if kind_force:
        sc = 1000.0 if f_unit == "mN" else 1.0
        nm = {0: "Friction force", 1: "Friction force", 2: "Ffric", 3: "Friction force"}[style]
        names.append(hdr(nm, f_unit)); cols.append(Fr * sc)
        nds.append(max(2, int(math.ceil(-math.log10(D * sc * 1e-4)))))
        if want_normal:
            nmn = "Fn" if style == 2 else "Normal force"
            names.append(hdr(nmn, f_unit)); cols.append(Nr * sc)
            nds.append(max(2, int(math.ceil(-math.log10(P["N0"] * sc * 1e-5)))))
    else:
        sc = 1000.0 if x_unit == "mm" else 1e6
        names.append(hdr("spring extension", x_unit)); cols.append(Fr / k * sc)
        nds.append(max(2, int(math.ceil(-math.log10(D / k * sc * 1e-4)))))
    if drive_col == "pos":
        sc = 1000.0 if pos_unit == "mm" else 1e6
        step = 1e-7  # encoder 0.1 um
        xp = np.round(drive.x_arr(tr + t0) / step) * step * sc
        names.append(hdr("stage_pos" if style in (0, 2) else "Stage position", pos_unit)); cols.append(xp)
        nds.append(4 if pos_unit == "mm" else 1)
    elif drive_col in ("speed", "setspeed"):
        vv = drive.v_arr(tr + t0) if drive_col == "speed" else np.full(n, P["v0"])
        if drive_col == "setspeed":
            vv = np.full(n, P["v0"])
        names.append(hdr("stage speed" if drive_col == "speed" else "set speed", "mm/s")); cols.append(vv * 1000)
        nds.append(5)
    if temp_col:
        names.append("T_ice [°C]" if style != 2 else "T_ice_degC"); cols.append(T_ice); nds.append(2)
    sep = {0: ",", 1: "\t", 2: " ", 3: ";"}[style]
    dec_comma = style == 3
    ext = {0: "csv", 1: "txt", 2: "dat", 3: "csv"}[style]
    os.makedirs(outdir, exist_ok=True)
    fname = os.path.abspath(os.path.join(outdir, f"{NAME}_{case}_s{seed}_{nuisance}.{ext}"))
    meta = [f"Ice friction rig, cold room, runner on planed ice", f"ice temperature setpoint {T_ice0:.1f} C",
            f"slider mass {P['m']:.3f} kg, normal load {P['N0']:.2f} N",
            f"sampling {fs:.3f} Hz"]
    if frng.uniform() < 0.5:
        meta_lines = ["# " + s for s in meta]
    else:
        meta_lines = [s.replace(",", " -").replace(";", " ") for s in meta] if style in (0, 3) else meta
        meta_lines = ["Instrument: cold-room stick-slip rig"] + [f"Note: {s}" for s in meta_lines[1:]]
    M = np.column_stack(cols)
    with open(fname, "w", encoding="utf-8", newline="\n") as fh:
        for ln in meta_lines:
            fh.write(ln + "\n")
        fh.write(sep.join(names) + "\n")
        fmts = [f"%.{d}f" for d in nds]
        lines = []
        for row in M:
            s = sep.join(f % v for f, v in zip(fmts, row))
            lines.append(s)
        txt = "\n".join(lines) + "\n"
        if dec_comma:
            txt = txt.replace(".", ",")
        fh.write(txt)

    # ---------------- args
    args = []
    fn_given = None
    omit_fn = (seed % 8 == 5) and case != "triggering" and nuisance != "fn_off"
    if not omit_fn:
        fn_given = fn
        if nuisance == "fn_off":
            fn_given = fn * (1.05 if nrng.uniform() < 0.5 else 0.95)
        args += ["--fn", f"{fn_given:.4f}"]
    if kind_force:
        args += ["--stiffness", f"{k:.2f}"]
    if drive_col is None or drive_col == "setspeed":
        if drive_col is None:
            args += ["--v0", f"{P['v0'] * 1000:.6g}"]
    params = _clean(P)
    params["measured"] = Mx
    params["nuisance_params"] = nz
    params["record"] = {"samples_per_period": spp, "fs_hz": fs, "n_samples": n, "style": style,
                        "force_record": kind_force, "normal_column": want_normal and kind_force,
                        "drive_column": drive_col, "temperature_column": bool(temp_col),
                        "time_unit": "ms" if time_ms else "s", "n_sim_steps": res["n_steps"]}
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": fname,
            "args": args, "fn_true": fn, "fn_given": fn_given, "params": params}


if __name__ == "__main__":
    import sys
    import tempfile

    seeds = range(8)
    cases = CASES
    if len(sys.argv) > 1:
        cases = tuple(sys.argv[1].split(","))
    if len(sys.argv) > 2:
        seeds = [int(s) for s in sys.argv[2].split(",")]
    tmp = tempfile.mkdtemp(prefix="ice_sled_")
    T0 = time.time()
    print(f"{'case':17s} {'sd':>2s} {'nuisance':12s} {'fn':>6s} {'cyc':>4s} {'spp':>5s} {'Tss/Tn':>6s} "
          f"{'twin':>7s} {'ageing':>7s} {'stR':>5s} {'loadpp':>6s} {'effect':>28s} {'s':>5s}")
    for case in cases:
        for seed in seeds:
            nu = NUISANCES[seed % 7]
            t_ = time.time()
            r = write_record(case, seed, tmp, nu)
            dt_ = time.time() - t_
            Mx = r["params"]["measured"]
            eff = ""
            if case == "load_variation":
                eff = f"load pp {Mx['load_pp_over_N0']:.3f} N0 ({Mx['load_type']})"
            elif case == "twin_branch":
                eff = f"twin {Mx['twin_over_D']:+.3f} D"
            elif case == "static_ageing":
                eff = f"age {Mx['ageing_growth_over_D']:+.3f} D x{Mx['stick_time_ratio']:.1f}"
            elif case == "triggering":
                eff = f"a {r['params']['trig_a']:.3f} ft/fss {Mx['ft_over_fss']:.2f}"
            elif case == "drive_modulation":
                eff = f"a {Mx['mod_a']:.2f} fm/fss {Mx['fm_over_fss']:.2f}"
            else:
                eff = f"{r['params']['drive_kind']} stR {Mx['stick_time_ratio']:.1f}"
            print(f"{case:17s} {seed:2d} {nu:12s} {r['fn_true']:6.2f} {Mx['cycles']:4d} "
                  f"{r['params']['record']['samples_per_period']:5.1f} {Mx['T_ss_over_Tn']:6.2f} "
                  f"{Mx['twin_over_D']:+7.3f} {Mx['ageing_growth_over_D']:+7.3f} {Mx['stick_time_ratio']:5.1f} "
                  f"{Mx['load_pp_over_N0']:6.3f} {eff:>28s} {dt_:5.1f}", flush=True)
    print(f"total {time.time() - T0:.1f} s, records in {tmp}")
