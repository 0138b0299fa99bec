"""Micro-/nano-tribometer stick-slip records (an independent generator for `lieng diagnose`).

Rig
---
A spherical probe (steel, sapphire, ruby, Si3N4, glass ball 0.5-3 mm, or a polymer microsphere) on a
flat (OTS monolayer on Si, PMMA/PDMS/PTFE film, hydrogel, DLC), held by a double-leaf-spring cantilever
whose lateral stiffness k (20-2000 N/m) is the spring. The instrument head is fixed; the flat rides on a
stage (the drive) moving at 0.5-200 um/s. Moving mass m = k / (2 pi fn)^2 with fn 50-2000 Hz; light
air damping (zeta 0.005-0.03). Normal loads 50 uN - 50 mN (open loop: no normal-force feedback).
Stages: a closed-loop piezo read back by its capacitive sensor (the position is recorded), an open-loop
piezo (residual hysteresis after the controller's linearisation: x_s = u - d 2 eh (u - u^2/L) on each
stroke, eh 0.01-0.025, so the real speed varies by +-2..5 % along a stroke; the recorded position is the
command u), or a stepper/leadscrew (microstep ripple x_s = u + A sin(2 pi u / p), A 1-3 % of a microstep;
the recorded position is the commanded microstep count). Drive ramps (constant acceleration) last
0.15-0.6 natural periods. About 5/12 of the records are reciprocating (odd seeds except
`drive_modulation`): strokes of 3-6 stick-slip cycles after the reversal's static ramp, with a dwell at
each end.

Friction law (single-valued in the sliding speed w >= 0, per unit load)
--------------------------------------------------------------------
    mu(w) = mu_k + D (1 + (w/v_st)^2)^(-(1-n)/2) + a_T [ln(1 + w/v_T)]^(2/3)
a Carreau shear-thinning term of a confined boundary film (the weakening; n 0.15-0.45, D 0.35-0.8 mu_k,
mu_k 0.08-0.35) on a thermally activated Prandtl-Tomlinson (Sang-Dube-Grant ln^(2/3)) strengthening
term (a_T 0.02-0.06 D, v_T 0.02-0.1 v_st); static level mu_s = (1 + s_st) mu(0+), s_st 0.04-0.12
(raised to 2.3 eps + 0.02..0.05 on `triggering` so that the shaker triggers slips rather than re-arresting
them). Friction F = sgn(w) N mu(|w|), w = stage speed - probe speed.

Stick handling: exact, event-driven switching. In stick the probe rides with the stage and the state is
explicit (x = x_a + x_s(t) - x_s(t_a)); the breakaway |m a_s + k x + c v_s| = mu_s N is located by a
vectorised scan on a grid (Tn/40, Tn/24 of a shaker period with `triggering`) and Ridders' method. A slip
ends where w crosses 0: the crossing is reached exactly with **Henon's trick** (the sliding speed becomes
the independent variable for two RK4 sub-steps from the last node to w = 0); the probe sticks if the
needed force is within the static limit, else it slides on in the direction of that force.
Integrator: own fixed-step 4th-order **Runge-Kutta-Nystrom** (x'' = f(t, x, x')) at Tn/160 (Tn/(24 ft/fn)
with the shaker), with any friction state carried by the matching RK4 stages; the sampled trajectory is
the exact stick solution plus a cubic Hermite interpolant of the slip nodes on a fine grid (>= 160 points
per natural period), through the sensor chain, then decimated. Everything is solved in units m = k = N0
= 1, omega_n = 1 and scaled to physical units afterwards (fn, k, v0 drawn jointly so that N0, v0 and the
stroke length stay in the ranges above). Pilot runs (a few cycles) set the drive so that the stick-slip
period is 5-35 natural periods and calibrate each effect's size.

Cases (measured on the ground truth, seeds 0-23 with nuisance = NUISANCES[seed % 7])
---------------------------------------------------------------------------------
The twin statistic is the true contact friction per unit load (F/N x N0) on the decelerating half of each
slip minus the accelerating half at equal true sliding speed, averaged over 10-90 % of the slip's peak
speed, over that slip's force drop, median over the slips. Ageing: the slope of the breakaway force against
ln(stick time), times the record's ln range of stick times, over the median drop.
- `none`: constant load and drive (stepped 4-8x on seeds 2, 6 mod 8; reciprocating on odd seeds), the law
  above, no memory. Measured: twin -0.03..+0.02 % of the drop (the law is single-valued; the residue is
  the integrator's); peak change with stick time 0.000..+0.002 of the drop across sticks up to 10.9x apart
  (reversal and slow-level sticks: no ageing in the law); drop cv <= 0.005 at a constant speed, 0.009-0.21
  on the stepped seeds (the drop depends on the speed: faster slips arrest lower). What a 1-DoF
  reading could mistake: on open-loop-piezo seeds (6/24) the real stage speed varies +-2..5 % along each
  stroke while the command is what is recorded; stepper seeds carry a microstep speed ripple (6-19 % of
  v0 at ~10x the stick-slip frequency, a position ripple of 0.1-0.6 % of a slip's travel) and the recorded
  position is quantised to microsteps; each drive ramp takes 0.15-0.6 Tn; the sensor's low-pass (below)
  delays the force, which a 1-DoF reading of the samples may read as a small twin (not measured here).
- `load_variation`: the normal load follows the probe's position on the flat, s = x_stage - x_probe: a
  tilted flat N = N0 (1 + c1 (s - s_m)/h) (seeds 0, 1 mod 4, c1 of either sign) or a wavy/curved flat
  N = N0 (1 + A sin(2 pi s / lambda + phi)) (lambda 0.6-1.25 track), amplitude rescaled once after a first
  run. Measured p-p 12.8-29.2 % of N0 (median 19.9 %); the normal channel is always recorded.
  (F against v then reads -4..+38 % of the drop as a twin, F/N against v +-0.04 %.)
- `twin_branch`: a friction state z built during the slip and relaxed in stick, calibrated by pilots:
  even seeds a **shear-melting confined film** (solid fraction theta: d theta/dt = -theta |w|/l +
  (1 - theta)/tau, l 0.6-1.2 slip distances, tau 0.4-0.7 Tn; friction + D_f theta N, static + D_f N):
  measured twin -17.9..-12.0 % of the drop (lower while decelerating); odd seeds a **viscoelastic pile-up
  (ploughing bow wave)** of the polymer flat (dq/dt = (|w|/l)(1 - q) - q/tau; friction + D_p q N):
  +10.3..+15.1 % (higher while decelerating).
- `static_ageing`: mu_s (1 + b ln(1 + t_stick/tau_a)), tau_a 0.05-0.3 of the plain stick time, b set by
  pilots; even seeds a stage programme by distance stepping the speed 4-8x (fast 4-5 cycles, slow 3),
  odd seeds reciprocating with dwells of 0.2-10 stick times at the reversals. Measured peak growth
  +10.2..+22.9 % of the drop (median 14.5 %) across stick times 5.5-14.2x apart; position always
  recorded.
- `triggering`: a shaker on the load, N = N0 (1 + eps sin(2 pi ft t + phi)), eps 3.3-7.8 %, ft 3.0-7.0 fn,
  ft re-drawn (up to 5 times) while ft / f_ss of the record is within 0.16 of an integer: measured ft/f_ss
  14.2-111.5, its distance to the nearest integer 0.17-0.50; `--fn` always given.
- `drive_modulation`: a leadscrew's periodic error, v = v0n (1 + a sin(2 pi fm t + phi)), a 0.20-0.43,
  measured fm/f_ss 0.14-0.38 (>= 2.6 modulation periods a record); never reciprocating, no position
  column (`--v0` carries the nominal speed).
Over all records: 16-35 slips a record (each an exact arrest, w = 0), f_ss/fn 0.012-0.21, 2 000-94 000
samples, 10-100 samples per natural period.

Sensor chain and nuisances
--------------------------
Lateral: the cantilever's deflection by a capacitive sensor (1st-order, 8-25 fn, or lock-in demodulated,
2nd-order 6-14 fn) or a fibre-optic sensor; white noise 0.3-1.2 % of the drop before a 4th-order
Bessel or Butterworth anti-alias filter (0.30-0.42 fs, causal, on the fine grid), 1/f noise 0.2-0.8 % of
the drop after sampling, a 16-bit ADC over +-2.5x the largest reading. Normal: its own 1st-order sensor
(8-20 fn), noise 0.1-0.5 % of N0, the same anti-alias filter, 16 bits. Position: the capacitive read-back
(0.3-1.5 nm noise, 2nd-order 3-8 fn) or the controller's command. Nuisances: `hum` 50/60 Hz (1-5 % of the
drop) plus its 2nd or 3rd harmonic (20-50 %) on both analog channels; `drift` a thermal drift of 4-15 %
of the drop (linear + exponential) on the lateral channel, +-3 % of N0 on the normal; `spikes` 0.05-0.5 %
of the samples +-(0.5-3) drops (30 % of them also on the normal); `quantisation` an ADC step of 0.2-1 %
of the drop (0.4 % of N0 on the normal); `coarse` 10-15 samples per natural period; `fn_off` `--fn` 5 %
off (either way).

Files (what the instrument software exports)
--------------------------------------------
Five styles, by seed and case: an NTR-like TAB export with `Key: value` metadata and `Time [s]`,
`Fx [uN]`/`Fx [mN]` (`µN` on some), `Dx [nm]`, `Fz [..]`, `Position X [um]`, `Mu`; a UMT-like CSV with
`key,value` metadata and `Time (s)`, `Lateral Force (mN)`, `Normal Force (mN)`, `COF`, `Position (um)`
(on some records `COF` and `Normal Force` only, no lateral force column); a home-built LabVIEW export,
semicolon and decimal comma, `#` metadata, `Time [ms]`, `Dx [nm]`, `Dz [nm]` (the normal deflection)
or `Fz`, `Stage X [um]`; a TAB export with a row of names and a row of units; a CSV with `#` metadata and
`name [unit]`. Metadata give the instrument, probe, sample, `Acquisition rate: 20 kHz`, `Normal load`,
`Speed`, `Stiffness (lateral)`, `Stiffness (normal)`, the mode and the stage. Lateral channel: force
(then `--stiffness "K N/m"`) or the cantilever's deflection (nm/um, no `--stiffness`); normal channel on
about half of the records (all of `load_variation`); the stage position on reciprocating, stepped and
ageing records and on half of the others (never on `drive_modulation`), else `--v0 "V um/s"`. `--fn` is
left out on seeds 3 mod 8 (3, 11, 19) except `triggering` and `fn_off` records. The record starts in the
stick after the first slip.
"""
import math
import os
import zlib

import numpy as np
from scipy import signal
from scipy.interpolate import CubicHermiteSpline

NAME = "micro_tribometer"
_CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
_NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
_TWO_PI = 2.0 * math.pi
_H_SLIP = _TWO_PI / 160.0          # slip step (dimensionless time, omega_n = 1)
_MAX_SAMPLES = 290_000


def _rng(*parts):
    key = "|".join(str(p) for p in parts).encode()
    return np.random.default_rng([zlib.crc32(key), zlib.adler32(key), 8191])


# --------------------------------------------------------------------------------------------
# friction law (dimensionless: normal load N0 = 1, stiffness k = 1, mass m = 1)
# --------------------------------------------------------------------------------------------
class _Law:
    """mu(w) = mu_k + D (1 + (w/v_st)^2)^(-(1-n)/2) + a_T [ln(1 + w/v_T)]^(2/3)

    a Carreau shear-thinning boundary-film term (the weakening) on a thermally activated
    (Sang-Dube-Grant, ln^(2/3)) strengthening term; static level (1 + s_st) mu(0+)."""

    def __init__(self, mu_k, D, n, v_st, a_T, v_T, s_st):
        self.mu_k, self.D, self.n, self.v_st = mu_k, D, n, v_st
        self.a_T, self.v_T, self.s_st = a_T, v_T, s_st
        self.mu0 = mu_k + D
        self.ex = -(1.0 - n) / 2.0

    def mu(self, w):
        w = abs(w)
        return (self.mu_k + self.D * (1.0 + (w / self.v_st) ** 2) ** self.ex
                + self.a_T * math.log1p(w / self.v_T) ** (2.0 / 3.0))

    def mu_vec(self, w):
        w = np.abs(w)
        return (self.mu_k + self.D * (1.0 + (w / self.v_st) ** 2) ** self.ex
                + self.a_T * np.log1p(w / self.v_T) ** (2.0 / 3.0))


# --------------------------------------------------------------------------------------------
# stage (drive) program
# --------------------------------------------------------------------------------------------
class _Stage:
    """commanded motion u(t) piecewise constant-acceleration; real stage x_s(u, t):
    'cl'  closed-loop piezo (x_s = u, read back by its capacitive sensor),
    'ol'  open-loop piezo, residual hysteresis x_s = u - d 2 eh (u - u^2/L) on a stroke [0, L],
    'st'  stepper, microstep ripple x_s = u + A sin(2 pi u / p),
    plus an optional slow speed modulation (a leadscrew's periodic error)."""

    def __init__(self, moves, t_ramp, v_start, kind, eh=0.0, L=1.0, A_ms=0.0, p_ms=1.0,
                 mod=None):
        T, X, V, A = [], [], [], []
        t, x, v = 0.0, 0.0, v_start
        for vt, dur in moves:
            if vt != v:
                a = (vt - v) / t_ramp
                T.append(t); X.append(x); V.append(v); A.append(a)
                x += v * t_ramp + 0.5 * a * t_ramp * t_ramp
                t += t_ramp
                v = vt
            T.append(t); X.append(x); V.append(v); A.append(0.0)
            x += v * dur
            t += dur
        self.T, self.X, self.V, self.A = (np.array(T), np.array(X), np.array(V), np.array(A))
        self.t_prog_end = t
        self.kind, self.eh, self.L, self.A_ms, self.p_ms, self.mod = kind, eh, L, A_ms, p_ms, mod

    def command(self, t):
        i = np.clip(np.searchsorted(self.T, t, side="right") - 1, 0, len(self.T) - 1)
        dt = t - self.T[i]
        u = self.X[i] + self.V[i] * dt + 0.5 * self.A[i] * dt * dt
        ud = self.V[i] + self.A[i] * dt
        udd = self.A[i] + 0.0 * dt
        return u, ud, udd

    def __call__(self, t):
        t = np.asarray(t, dtype=float)
        u, ud, udd = self.command(t)
        if self.kind == "ol":
            d = np.where(ud < 0.0, -1.0, 1.0)
            e2 = 2.0 * self.eh
            g1 = 1.0 - d * e2 * (1.0 - 2.0 * u / self.L)
            xs = u - d * e2 * (u - u * u / self.L)
            vs = ud * g1
            acs = udd * g1 + ud * ud * d * 2.0 * e2 / self.L
        elif self.kind == "st":
            q = _TWO_PI / self.p_ms
            s, c = np.sin(q * u), np.cos(q * u)
            xs = u + self.A_ms * s
            vs = ud * (1.0 + self.A_ms * q * c)
            acs = udd * (1.0 + self.A_ms * q * c) - ud * ud * self.A_ms * q * q * s
        else:
            xs, vs, acs = u.copy(), ud.copy(), udd.copy()
        if self.mod is not None:
            a, v0n, wm, ph = self.mod
            xs = xs + (a * v0n / wm) * (math.cos(ph) - np.cos(wm * t + ph))
            vs = vs + a * v0n * np.sin(wm * t + ph)
            acs = acs + a * v0n * wm * np.cos(wm * t + ph)
        return xs, vs, acs, u

    def at(self, t):
        xs, vs, acs, _ = self(np.array([t]))
        return float(xs[0]), float(vs[0]), float(acs[0])


# --------------------------------------------------------------------------------------------
# model (dimensionless)
# --------------------------------------------------------------------------------------------
class _Model:
    def __init__(self, law, zeta, stage):
        self.law, self.zeta, self.stage = law, zeta, stage
        self.twin = 0          # 0 none, 1 shear-melting film (theta), 2 viscoelastic pile-up (q)
        self.tw_D, self.tw_l, self.tw_tau = 0.0, 1.0, 1.0
        self.age_b, self.age_tau = 0.0, 1.0
        self.load = None       # ("tilt", c1, s_m, hw) | ("wave", A, lam, ph)
        self.trig = None       # (eps, w_t, ph)
        self.dt_stick = _TWO_PI / 40.0

    # --- normal load -----------------------------------------------------------------------
    def N(self, t, s):
        n = 1.0
        if self.load is not None:
            if self.load[0] == "tilt":
                _, c1, s_m, hw = self.load
                n = 1.0 + c1 * (s - s_m) / hw
            else:
                _, A, lam, ph = self.load
                n = 1.0 + A * np.sin(_TWO_PI * s / lam + ph)
        if self.trig is not None:
            eps, wt, ph = self.trig
            n = n * (1.0 + eps * np.sin(wt * t + ph))
        return n

    def z_rest(self):
        return 1.0 if self.twin == 1 else 0.0

    def z_stick(self, z_a, dt):
        if self.twin == 1:
            return 1.0 - (1.0 - z_a) * np.exp(-dt / self.tw_tau)
        if self.twin == 2:
            return z_a * np.exp(-dt / self.tw_tau)
        return 0.0 * dt + z_a

    def mu_static(self, z, age):
        base = (self.law.mu0 + (self.tw_D * z if self.twin == 1 else 0.0)) * (1.0 + self.law.s_st)
        if self.age_b > 0.0:
            base = base * (1.0 + self.age_b * np.log1p(age / self.age_tau))
        return base

    # --- slip right-hand side ----------------------------------------------------------------
    def rhs(self, t, x, v, z, xs, vs, sgn):
        w = vs - v
        aw = abs(w)
        N = self.N(t, xs - x)
        mu = self.law.mu(aw)
        if self.twin == 1:
            mu += self.tw_D * z
            zd = -z * aw / self.tw_l + (1.0 - z) / self.tw_tau
        elif self.twin == 2:
            mu += self.tw_D * z
            zd = (aw / self.tw_l) * (1.0 - z) - z / self.tw_tau
        else:
            zd = 0.0
        F = sgn * N * mu
        acc = -x - 2.0 * self.zeta * v + F
        return acc, zd, F, N


def _ridders(f, a, b, fa, fb, tol):
    for _ in range(60):
        m = 0.5 * (a + b)
        fm = f(m)
        s = math.sqrt(max(fm * fm - fa * fb, 0.0))
        if s == 0.0:
            return m
        xn = m + (m - a) * (math.copysign(1.0, fa - fb) * fm / s)
        fn = f(xn)
        if math.copysign(fm, fn) != fm:
            a, fa, b, fb = m, fm, xn, fn
        elif math.copysign(fa, fn) != fa:
            b, fb = xn, fn
        else:
            a, fa = xn, fn
        if abs(b - a) < tol or fn == 0.0:
            return xn
    return 0.5 * (a + b)


def _simulate(M, n_target, t_max, tail=0.5):
    """event-driven: stick (explicit, scan + Ridders), slip (RKN4 + Henon's step to w = 0)."""
    st = M.stage
    phases = []
    breaks, arrests = [], []
    t_a, x_a, z_a = 0.0, 0.0, M.z_rest()
    last_cycle = None
    n_slip = 0
    while True:
        xs_a = st.at(t_a)[0]
        s_pos = xs_a - x_a

        def g_vec(tt):
            xs, vs, acs, _ = st(tt)
            x = x_a + xs - xs_a
            Fn = acs + x + 2.0 * M.zeta * vs
            Fs = M.N(tt, s_pos) * M.mu_static(M.z_stick(z_a, tt - t_a), tt - t_a)
            return np.abs(Fn) - Fs

        t_lim = t_max
        if n_slip >= n_target:
            t_lim = min(t_max, t_a + tail * (last_cycle if last_cycle else 50.0))
        t_b = None
        t0 = t_a
        g0 = float(g_vec(np.array([t_a]))[0])
        if g0 >= 0.0:
            t_b = t_a
        while t_b is None and t0 < t_lim:
            tt = t0 + M.dt_stick * np.arange(1, 2049)
            g = g_vec(tt)
            idx = np.nonzero(g >= 0.0)[0]
            if len(idx):
                i = idx[0]
                lo = tt[i - 1] if i > 0 else t0
                glo = g[i - 1] if i > 0 else float(g_vec(np.array([t0]))[0])
                if tt[i] > t_lim:
                    break
                t_b = _ridders(lambda q: float(g_vec(np.array([q]))[0]), lo, tt[i], glo, g[i], 1e-9)
            t0 = tt[-1]
        if t_b is None or (n_slip >= n_target):
            t_end = t_lim if t_b is None else t_b
            phases.append(("stick", t_a, t_end, x_a, xs_a, z_a))
            break
        phases.append(("stick", t_a, t_b, x_a, xs_a, z_a))
        xs_b, vs_b, as_b = st.at(t_b)
        x_b = x_a + xs_b - xs_a
        z_b = float(M.z_stick(z_a, t_b - t_a))
        Fn_b = as_b + x_b + 2.0 * M.zeta * vs_b
        breaks.append((t_b, x_b, Fn_b, float(M.N(t_b, s_pos)), t_b - t_a))
        # ---- slip (possibly several, if an arrest cannot hold) ----
        t, x, v, z = t_b, x_b, vs_b, z_b
        sgn = 1.0 if Fn_b > 0 else -1.0
        while True:
            res = _slip(M, t, x, v, z, sgn, t_max)
            phases.append(("slip",) + res[:7])
            t, x, v, z = res[7]
            xs, vs, acs = st.at(t)
            v = vs
            Fn = acs + x + 2.0 * M.zeta * vs
            Fs = M.N(t, xs - x) * M.mu_static(z, 0.0)
            if abs(Fn) <= Fs or t >= t_max:
                break
            sgn = 1.0 if Fn > 0 else -1.0
        arrests.append((t, x))
        n_slip += 1
        if len(arrests) >= 2:
            last_cycle = arrests[-1][0] - arrests[-2][0]
        t_a, x_a, z_a = t, x, z
        if t >= t_max:
            phases.append(("stick", t_a, t_a, x_a, st.at(t_a)[0], z_a))
            break
    return phases, breaks, arrests


class _NoStick(RuntimeError):
    pass


def _slip(M, t, x, v, z, sgn, t_max):
    st = M.stage
    t_in = t
    h = _H_SLIP
    if M.trig is not None:
        h = min(h, _TWO_PI / M.trig[1] / 24.0)
    T, Xn, Vn, Zn, Fn, Nn, Wn = [], [], [], [], [], [], []
    K = 256
    while True:
        tg = t + 0.5 * h * np.arange(2 * K + 1)
        XS, VS, _, _ = st(tg)
        XS, VS = XS.tolist(), VS.tolist()
        for k in range(K):
            i = 2 * k
            k1, q1, F, N = M.rhs(t, x, v, z, XS[i], VS[i], sgn)
            T.append(t); Xn.append(x); Vn.append(v); Zn.append(z); Fn.append(F); Nn.append(N)
            Wn.append(VS[i] - v)
            xm = x + 0.5 * h * v + h * h / 8.0 * k1
            k2, q2, _, _ = M.rhs(t + 0.5 * h, xm, v + 0.5 * h * k1, z + 0.5 * h * q1, XS[i + 1], VS[i + 1], sgn)
            k3, q3, _, _ = M.rhs(t + 0.5 * h, xm, v + 0.5 * h * k2, z + 0.5 * h * q2, XS[i + 1], VS[i + 1], sgn)
            k4, q4, _, _ = M.rhs(t + h, x + h * v + 0.5 * h * h * k3, v + h * k3, z + h * q3, XS[i + 2], VS[i + 2], sgn)
            x1 = x + h * v + h * h / 6.0 * (k1 + k2 + k3)
            v1 = v + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            z1 = z + h / 6.0 * (q1 + 2.0 * q2 + 2.0 * q3 + q4)
            w1 = VS[i + 2] - v1
            if sgn * w1 <= 0.0 or t + h >= t_max:
                te, xe, ve, ze = _henon(M, t, x, v, z, sgn)
                if not (t < te <= t + 1.5 * h):     # fallback: linear location
                    w0 = VS[i] - v
                    fr = w0 / (w0 - w1) if w0 != w1 else 1.0
                    te, xe, ve, ze = t + fr * h, x + fr * (x1 - x), v + fr * (v1 - v), z + fr * (z1 - z)
                _, _, F, N = M.rhs(te, xe, ve, ze, st.at(te)[0], st.at(te)[1], sgn)
                T.append(te); Xn.append(xe); Vn.append(ve); Zn.append(ze); Fn.append(F); Nn.append(N)
                Wn.append(0.0)
                return (np.array(T), np.array(Xn), np.array(Vn), np.array(Zn), np.array(Fn),
                        np.array(Nn), sgn, (te, xe, ve, ze))
            t, x, v, z = t + h, x1, v1, z1
        if t - t_in > 60.0 * _TWO_PI:
            raise _NoStick("no arrest within 60 natural periods")


def _henon(M, t, x, v, z, sgn):
    """Henon's trick: integrate (t, x, v, z) with the sliding speed w as the independent
    variable from its value at the last node to exactly 0 (two RK4 steps)."""
    st = M.stage

    def d(y):
        tt, xx, vv, zz = y
        xs, vs, acs = st.at(tt)
        acc, zd, _, _ = M.rhs(tt, xx, vv, zz, xs, vs, sgn)
        wd = acs - acc
        if abs(wd) < 1e-14:
            wd = math.copysign(1e-14, wd if wd != 0 else -sgn)
        return np.array([1.0, vv, acc, zd]) / wd

    y = np.array([t, x, v, z])
    w0 = st.at(t)[1] - v
    dw = -w0 / 2.0
    for _ in range(2):
        k1 = d(y)
        k2 = d(y + 0.5 * dw * k1)
        k3 = d(y + 0.5 * dw * k2)
        k4 = d(y + dw * k3)
        y = y + dw / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    return float(y[0]), float(y[1]), float(y[2]), float(y[3])


# --------------------------------------------------------------------------------------------
# ground-truth measurements
# --------------------------------------------------------------------------------------------
def _measure(M, phases, breaks, arrests, t0, t1):
    st = M.stage
    groups, cur, ai = [], [], 0
    for p in phases:
        if p[0] != "slip":
            continue
        cur.append(p)
        if ai < len(arrests) and abs(p[1][-1] - arrests[ai][0]) < 1e-12:
            groups.append(cur)
            cur, ai = [], ai + 1
    drops, peaks, sticks, twins, twins_F, wmax = [], [], [], [], [], []
    for gi, grp in enumerate(groups):
        if gi >= len(breaks) or gi >= len(arrests):
            break
        tb, xb, Fnb, Nb, tst = breaks[gi]
        ta, xa = arrests[gi]
        if tb < t0 or ta > t1:
            continue
        sgn = grp[0][7]
        drop = sgn * (xb - xa)
        drops.append(drop)
        peaks.append(abs(xb))
        sticks.append(tst)
        T = np.concatenate([p[1] for p in grp])
        V = np.concatenate([p[3] for p in grp])
        F = np.concatenate([p[5] for p in grp])
        N = np.concatenate([p[6] for p in grp])
        _, VS, _, _ = st(T)
        w = sgn * (VS - V)
        ip = int(np.argmax(w))
        wm = w[ip]
        wmax.append(wm)
        if ip < 3 or len(w) - ip < 4 or drop <= 0:
            continue
        lev = np.linspace(0.1, 0.9, 33) * wm
        res = []
        for Fx in (sgn * F / N, sgn * F):
            wa, fa = w[:ip + 1], Fx[:ip + 1]
            wd, fd = w[ip:][::-1], Fx[ip:][::-1]
            oa, od = np.argsort(wa, kind="stable"), np.argsort(wd, kind="stable")
            res.append(np.mean(np.interp(lev, wd[od], fd[od]) - np.interp(lev, wa[oa], fa[oa])))
        twins.append(res[0] / drop)      # friction coefficient (x N0 = 1) over the drop
        twins_F.append(res[1] / drop)
    drops, peaks, sticks = np.array(drops), np.array(peaks), np.array(sticks)
    out = {"n_slips": int(len(drops)), "drop": float(np.median(drops)) if len(drops) else float("nan"),
           "drop_cv": float(np.std(drops) / np.mean(drops)) if len(drops) > 1 else 0.0,
           "twin": float(np.median(twins)) if twins else 0.0,
           "twin_F": float(np.median(twins_F)) if twins_F else 0.0,
           "w_peak": float(np.median(wmax)) if wmax else 0.0}
    if len(sticks) > 2:
        ls = np.log(sticks)
        rng = ls.max() - ls.min()
        out["stick_ratio"] = float(math.exp(rng))
        if rng > 0.2:
            slope = np.polyfit(ls, peaks, 1)[0]
            out["ageing"] = float(slope * rng / np.median(drops))
        else:
            out["ageing"] = 0.0
        out["peak_sd"] = float(np.std(peaks) / np.median(drops))
    out["stick_min"] = float(sticks.min()) if len(sticks) else float("nan")
    out["stick_med"] = float(np.median(sticks)) if len(sticks) else float("nan")
    # sample coordinate range and load
    return out


# --------------------------------------------------------------------------------------------
# case / seed set-up
# --------------------------------------------------------------------------------------------
def _draw_law(r):
    mu_k = r.uniform(0.08, 0.35)
    D = mu_k * r.uniform(0.35, 0.8)
    n = r.uniform(0.15, 0.45)
    s_st = r.uniform(0.04, 0.12)
    v_st = (D + s_st * (mu_k + D)) * r.uniform(0.08, 0.25)
    a_T = D * r.uniform(0.02, 0.06)
    v_T = v_st * r.uniform(0.02, 0.1)
    return _Law(mu_k, D, n, v_st, a_T, v_T, s_st)


def _plan(case, seed, attempt=0):
    r = _rng(NAME, "phys", case, seed, attempt)
    law = _draw_law(r)
    zeta = float(r.uniform(0.005, 0.03))
    recip = (seed % 2 == 1) and case != "drive_modulation"
    stepped = (case == "static_ageing" and seed % 2 == 0) or (case == "none" and seed % 8 in (2, 6))
    if case == "triggering":
        eps = float(r.uniform(0.03, 0.08))
        law.s_st = max(law.s_st, 2.3 * eps + float(r.uniform(0.02, 0.05)))
        law.eps_trig = eps
    if stepped:
        r_ratio = float(r.uniform(5.0, 9.0))
    elif recip:
        r_ratio = float(r.uniform(5.0, 14.0))
    else:
        r_ratio = float(r.uniform(8.0, 30.0))
    return r, law, zeta, recip, stepped, r_ratio


def _pilot(law, zeta, v, n=6, twin=None, age=None):
    st = _Stage([(v, 1e9)], 1.0, v, "cl")
    M = _Model(law, zeta, st)
    if age is not None:
        M.age_b, M.age_tau = age
    if twin is not None:
        M.twin, M.tw_D, M.tw_l, M.tw_tau = twin
    ph, br, ar = _simulate(M, n, 1e7, tail=0.0)
    t0 = ar[0][0] if ar else 0.0
    meas = _measure(M, ph, br, ar, t0, ar[-1][0] + 1)
    T_cyc = (ar[-1][0] - ar[1][0]) / (len(ar) - 2) if len(ar) > 3 else float("nan")
    T_slip = float(np.median([ar[i][0] - br[i][0] for i in range(1, len(ar))]))
    return meas, T_cyc, T_slip


def _run(case, seed, nuisance, write=True, outdir=None):
    for attempt in range(6):
        try:
            return _run1(case, seed, attempt)
        except _NoStick:
            continue
    raise RuntimeError("no stick-slip for %s seed %d" % (case, seed))


def _run1(case, seed, attempt):
    r, law, zeta, recip, stepped, r_ratio = _plan(case, seed, attempt)
    # ---- pilot: set the drive so that T_ss ~ r_ratio Tn ----
    v_guess = (2.0 * (law.mu0 * (1 + law.s_st) - law.mu_k - 0.4 * law.D)) / (_TWO_PI * r_ratio)
    meas, T_cyc, T_slip = _pilot(law, zeta, v_guess)
    drop0 = meas["drop"]
    v_d = drop0 / max(_TWO_PI * r_ratio - T_slip, 0.3 * _TWO_PI * r_ratio)
    T_st = drop0 / v_d                   # stick time at v_d (dimensionless)
    T_ss = T_st + T_slip
    params = {"law": {"form": "mu_k + D (1+(w/v_st)^2)^(-(1-n)/2) + a_T ln(1+w/v_T)^(2/3)",
                      "mu_k": law.mu_k, "D": law.D, "n": law.n, "s_static": law.s_st,
                      "v_st_over_v0": law.v_st / v_d, "a_T": law.a_T, "v_T_over_v0": law.v_T / v_d},
              "zeta": zeta, "reciprocating": bool(recip), "stepped": bool(stepped),
              "Tss_over_Tn_nominal": T_ss / _TWO_PI}
    twin = None
    if case == "twin_branch":
        kind = 1 if seed % 2 == 0 else 2
        target = float(r.uniform(0.11, 0.19)) * (-1 if kind == 1 else 1)
        l = float(r.uniform(0.6, 1.2)) * drop0 if kind == 1 else float(r.uniform(0.3, 0.7)) * drop0
        tau = float(r.uniform(0.4, 0.7)) * _TWO_PI
        tau = min(tau, 0.08 * T_st)
        Dg = 0.6 * law.D
        best = None
        for _ in range(6):
            mt, _, _ = _pilot(law, zeta, v_d, n=6, twin=(kind, Dg, l, tau))
            tw = mt["twin"]
            if best is None or abs(tw - target) < abs(best[1] - target):
                best = (Dg, tw)
            if abs(tw - target) < 0.01:
                break
            if abs(tw) < 1e-4:
                Dg *= 3.0
                continue
            Dg = float(np.clip(Dg * (target / tw) ** 1.3, 0.05 * law.D, 4.0 * law.D))
        Dg = best[0]
        twin = (kind, Dg, l, tau)
        mt, T_cyc, T_slip = _pilot(law, zeta, v_d, n=6, twin=twin)
        v_d = v_d * (T_cyc - T_slip) / (_TWO_PI * r_ratio - T_slip)
        drop0 = mt["drop"]
        T_st = drop0 / v_d
        T_ss = T_st + T_slip
        params["twin"] = {"mechanism": "shear-melting confined film" if kind == 1 else
                          "viscoelastic pile-up (ploughing bow wave)",
                          "D": Dg, "l_over_drop": l / drop0, "tau_over_Tn": tau / _TWO_PI,
                          "target": target}
    age_pre = None
    if case == "static_ageing":
        target = float(r.uniform(0.13, 0.25))
        tau_rel = float(r.uniform(0.05, 0.3))
        ratio_pre = float(r.uniform(4.0, 8.0))
        long_rel = ratio_pre if stepped else (6.0 + 2.0 * law.mu0 / drop0)
        b = target * drop0 / (law.mu0 * (1 + law.s_st) * math.log((1 + long_rel / tau_rel) / (1 + 1.0 / tau_rel)))
        ma, T_cyc, T_slip = _pilot(law, zeta, v_d, n=6, age=(b, tau_rel * T_st))
        v_d = v_d * (T_cyc - T_slip) / (_TWO_PI * r_ratio - T_slip)
        drop0 = ma["drop"]
        T_st = drop0 / v_d
        T_ss = T_st + T_slip
        age_pre = (b, tau_rel * T_st, target, ratio_pre)
    # ---- stage programme ----
    tr = float(r.uniform(0.15, 0.6)) * _TWO_PI       # ramp time
    n_cyc = int(r.integers(18, 36))
    mod = None
    holds = []
    if recip:
        n_ps = int(r.integers(3, 7))
        rev = 2.0 * law.mu0 * (1 + law.s_st) - 0.9 * drop0   # reversal travel (dimensionless, k = 1)
        L = rev + n_ps * drop0
        n_str = max(4, int(math.ceil(n_cyc / n_ps)))
        moves = []
        dw_list = []
        for i in range(n_str + 5):
            if case == "static_ageing":
                dw = float(r.choice([0.2, 1.0, 3.0, 8.0]) * r.uniform(0.8, 1.25)) * T_st
            else:
                dw = float(r.uniform(0.15, 0.5)) * T_st
            dw_list.append(dw)
            sg = 1.0 if i % 2 == 0 else -1.0
            moves.append((sg * v_d, L / v_d - tr))
            moves.append((0.0, dw))
        kind_st = "cl" if r.random() < 0.5 else "ol"
        if L * 1.0 > 0 and case == "drive_modulation":
            kind_st = "st"
        st_kw = dict(eh=float(r.uniform(0.01, 0.025)), L=L) if kind_st == "ol" else {}
        stage = _Stage(moves, tr, 0.0, kind_st, **st_kw)
        n_target = n_cyc + 1
        params["stroke_cycles"] = n_ps
        params["dwells_over_Tstick"] = [d / T_st for d in dw_list]
    elif stepped:
        ratio = float(r.uniform(4.0, 8.0)) if age_pre is None else age_pre[3]
        v_lo = v_d / ratio
        levels = []
        fast_first = r.random() < 0.5
        ncs = []
        grow = 1.2 if case == "static_ageing" else 1.0
        for i in range(10):
            fast = (i % 2 == 0) == fast_first
            nc = int(r.integers(4, 6)) if fast else 3
            vv = v_d if fast else v_lo
            dist = nc * drop0 * (1.0 if fast else grow)        # a stage programme by distance
            if i == 0:
                dist += law.mu0 * (1 + law.s_st)                # the first loading from rest
            levels.append((vv, dist / vv))
            ncs.append(nc)
        n_target = min(max(sum(ncs[:5]) + 1, 17), 38)
        stage = _Stage(levels, tr, levels[0][0], "st" if r.random() < 0.6 else "cl",
                       A_ms=float(r.uniform(0.01, 0.03)) * drop0 * 0.2, p_ms=drop0 * 0.2)
        params["speed_ratio"] = ratio
    else:
        kind_st = "st" if (r.random() < 0.6 or case == "drive_modulation") else "cl"
        n_target = n_cyc + 1
        if case == "drive_modulation":
            a = float(r.uniform(0.2, 0.45))
            fm_rel = float(r.uniform(0.1, 0.4))
            n_target = min(40, max(n_target, int(math.ceil(2.6 / fm_rel)) + 1))
            wm = fm_rel * _TWO_PI / T_ss
            mod = (a, v_d, wm, float(r.uniform(0, _TWO_PI)))
            params["modulation"] = {"a": a, "fm_over_fss_nominal": fm_rel}
        stage = _Stage([(v_d, 1e9)], tr, v_d, kind_st,
                       A_ms=float(r.uniform(0.01, 0.03)) * drop0 * 0.1, p_ms=drop0 * 0.1, mod=mod)
    params["stage_kind"] = {"cl": "closed-loop piezo", "ol": "open-loop piezo",
                            "st": "stepper/leadscrew"}[stage.kind]
    M = _Model(law, zeta, stage)
    if twin is not None:
        M.twin, M.tw_D, M.tw_l, M.tw_tau = twin
    # ---- departures ----
    if case == "load_variation":
        pp = float(r.uniform(0.12, 0.30))
        if recip:
            span = stage.L if hasattr(stage, "L") and stage.kind == "ol" else None
            span = law.mu0 * 2.2 + 5 * drop0 if span is None else span
            span = float(np.max(stage.X) - np.min(stage.X)) or span
            lo = float(np.min(stage.X))
        else:
            span = v_d * n_target * T_ss
            lo = 0.0
        if seed % 4 in (0, 1):
            c1 = pp / 2.0 * (1 if r.random() < 0.5 else -1)
            M.load = ("tilt", c1, lo + span / 2.0, span / 2.0)
            params["load"] = {"shape": "tilted flat", "c1": c1, "target_pp": pp}
        else:
            lam = span / float(r.uniform(0.8, 1.6))
            M.load = ("wave", pp / 2.0, lam, float(r.uniform(0, _TWO_PI)))
            params["load"] = {"shape": "wavy/curved flat", "amp": pp / 2.0, "lambda_over_track": lam / span,
                              "target_pp": pp}
    if case == "triggering":
        eps = law.eps_trig
        ft_rel = float(r.uniform(3.0, 7.0))
        M.trig = (eps, ft_rel, float(r.uniform(0, _TWO_PI)))
        M.dt_stick = min(M.dt_stick, _TWO_PI / ft_rel / 24.0)
    if case == "static_ageing":
        M.age_b, M.age_tau = age_pre[0], age_pre[1]
        params["ageing_target"] = age_pre[2]
        params["age_tau_over_Tstick"] = age_pre[1] / T_st
    if recip:
        t_max = min(stage.t_prog_end, (n_target + 3) * T_ss * 25.0)
    elif stepped:
        t_max = (n_target + 3) * T_ss * params["speed_ratio"] * 3.0
    else:
        t_max = (n_target + 3) * T_ss * 3.0
    R_stub = {}
    for attempt in range(6):
        phases, breaks, arrests = _simulate(M, n_target, t_max)
        t_start = arrests[0][0] + 0.4 * (breaks[1][0] - arrests[0][0]) if len(breaks) > 1 else 0.0
        t_end = phases[-1][2]
        meas = _measure(M, phases, breaks, arrests, t_start, t_end)
        f_ss_rel = meas["n_slips"] / (t_end - t_start) * _TWO_PI     # f_ss / fn
        if case == "static_ageing" and attempt < 2 and meas["n_slips"] >= 10 and meas.get("ageing", 0) > 0.01:
            tgt = params["ageing_target"]
            if abs(meas["ageing"] - tgt) > 0.015:
                M.age_b *= float(np.clip(tgt / meas["ageing"], 0.5, 2.0))
                continue
        if case == "load_variation" and attempt < 2:
            pp = _truth(dict(R_stub, M=M, phases=phases, breaks=breaks, arrests=arrests, t_start=t_start,
                             t_end=t_end, meas=meas, f_ss_rel=f_ss_rel), case).get("load_pp_over_N0", 0.0)
            tgt = params["load"]["target_pp"]
            if pp > 0.01 and abs(pp - tgt) > 0.015:
                f = float(np.clip(tgt / pp, 0.5, 2.0))
                M.load = (M.load[0], M.load[1] * f) + tuple(M.load[2:])
                continue
        if case == "triggering":
            q = M.trig[1] / f_ss_rel
            if abs(q - round(q)) < 0.16 and attempt < 5:
                r2 = _rng(NAME, "trig", seed, attempt)
                M.trig = (M.trig[0], float(r2.uniform(3.0, 7.0)), M.trig[2])
                M.dt_stick = min(_TWO_PI / 40.0, _TWO_PI / M.trig[1] / 24.0)
                continue
        break
    params["age_b"] = M.age_b
    if M.load is not None:
        params["load"]["final"] = list(M.load[1:])
    return dict(r=r, law=law, M=M, phases=phases, breaks=breaks, arrests=arrests, t_start=t_start,
                t_end=t_end, meas=meas, f_ss_rel=f_ss_rel, params=params, v_d=v_d, drop0=drop0,
                recip=recip, stepped=stepped, T_ss=T_ss, T_st=T_st)


# --------------------------------------------------------------------------------------------
# physical scaling, sensor chain and export
# --------------------------------------------------------------------------------------------
_NICE_FS = (500.0, 1000.0, 2000.0, 2500.0, 5000.0, 10000.0, 12500.0, 20000.0, 25000.0,
            40000.0, 50000.0, 100000.0)


def _scale(R, case, seed):
    r = _rng(NAME, "scale", case, seed)
    v_d = R["v_d"]
    L_d = R["M"].stage.L if R["recip"] else None
    if R["recip"]:
        L_d = float(np.max(R["M"].stage.X) - np.min(R["M"].stage.X))
    for relax in range(4):
        n = 4000
        fn = np.exp(r.uniform(math.log(50.0), math.log(2000.0), n))
        k = np.exp(r.uniform(math.log(20.0), math.log(2000.0), n))
        v0 = np.exp(r.uniform(math.log(0.5e-6), math.log(200e-6), n))
        Lu = v0 / (v_d * _TWO_PI * fn)
        N0 = k * Lu
        ok = (N0 >= 50e-6) & (N0 <= 50e-3)
        if L_d is not None:
            stroke = L_d * Lu
            ok &= (stroke >= 10e-6 / (1 + relax)) & (stroke <= 500e-6 * (1 + relax))
        idx = np.nonzero(ok)[0]
        if len(idx):
            i = idx[0]
            return float(fn[i]), float(k[i]), float(v0[i]), float(Lu[i]), float(N0[i])
    i = 0
    return float(fn[i]), float(k[i]), float(v0[i]), float(Lu[i]), float(N0[i])


def _one_over_f(r, n, rms):
    if n < 4 or rms <= 0:
        return np.zeros(n)
    w = r.standard_normal(n)
    W = np.fft.rfft(w)
    f = np.arange(len(W), dtype=float)
    f[0] = 1.0
    W = W / np.sqrt(f)
    W[0] = 0.0
    y = np.fft.irfft(W, n)
    return y / (np.std(y) + 1e-30) * rms


def _fmt_num(v, sig=4):
    return ("%." + str(sig) + "g") % v


def _render(R, case, seed, nuisance, outdir):
    M, law = R["M"], R["law"]
    st = M.stage
    rf = _rng(NAME, "fmt", case, seed)
    rn = _rng(NAME, "noise", case, seed, nuisance)
    fn, k, v0, Lu, N0 = _scale(R, case, seed)
    wn = _TWO_PI * fn
    drop_F = R["meas"]["drop"] * N0                  # force drop (N)
    t0d, t1d = R["t_start"], R["t_end"]
    dur = (t1d - t0d) / wn
    # ---- sampling rate ----
    if nuisance == "coarse":
        spp_lo, spp_hi = 10.0, 15.0
    else:
        spp_lo, spp_hi = 20.0, 100.0
    cands = [f for f in _NICE_FS if spp_lo <= f / fn <= spp_hi and f * dur <= _MAX_SAMPLES]
    if cands:
        fs = float(cands[int(rf.integers(0, len(cands)))])
    else:
        spp = float(rf.uniform(spp_lo, spp_hi))
        fs = float(round(spp * fn, -1 if spp * fn < 5000 else -2))
        if fs * dur > _MAX_SAMPLES:
            fs = max(spp_lo * fn, _MAX_SAMPLES / dur)
            fs = float(math.ceil(fs / 10.0) * 10.0)
            if fs * dur > _MAX_SAMPLES:          # shorten the record (keeps >= 15 slips)
                dur = _MAX_SAMPLES / fs
                t1d = t0d + dur * wn
    n = int(dur * fs)
    ov = int(max(2, min(math.ceil(160.0 / (fs / fn)), 1.5e6 / max(n, 1))))
    fsf = fs * ov
    nf = n * ov
    n_warm = 4 * ov * 64
    tf = t0d / wn + (np.arange(-n_warm, nf) / fsf)
    td = tf * wn
    # ---- ground-truth trajectory on the fine grid ----
    xd = np.empty_like(td)
    starts = np.array([p[1] if p[0] == "stick" else p[1][0] for p in R["phases"]])
    ends = np.array([p[2] if p[0] == "stick" else p[1][-1] for p in R["phases"]])
    xs_f, vs_f, as_f, u_f = st(td)
    for j, p in enumerate(R["phases"]):
        lo = np.searchsorted(td, starts[j], side="left")
        hi = np.searchsorted(td, ends[j], side="right")
        if hi <= lo:
            continue
        if p[0] == "stick":
            xd[lo:hi] = p[3] + xs_f[lo:hi] - p[4]
        else:
            T, X, V = p[1], p[2], p[3]
            keep = np.concatenate([[True], np.diff(T) > 1e-12])
            if keep.sum() >= 2:
                xd[lo:hi] = CubicHermiteSpline(T[keep], X[keep], V[keep])(td[lo:hi])
            else:
                xd[lo:hi] = X[0]
    before = td < starts[0]
    xd[before] = 0.0
    after = td > ends[-1]
    if after.any():
        xd[after] = xd[~after][-1]
    Nd = np.asarray(M.N(td, xs_f - xd)) * np.ones_like(td)
    F_true = xd * N0                     # lateral force k x (N)
    N_true = Nd * N0
    pos_true = xs_f * Lu
    pos_cmd = u_f * Lu
    # ---- sensor chain, lateral ----
    sens = "capacitive" if rf.random() < 0.6 else "fibre-optic"
    lockin = sens == "capacitive" and rf.random() < 0.5
    if lockin:
        fc1 = float(rf.uniform(6.0, 14.0)) * fn
        sos1 = signal.butter(2, min(fc1, 0.45 * fsf), fs=fsf, output="sos")
    else:
        fc1 = float(rf.uniform(8.0, 25.0)) * fn
        sos1 = signal.butter(1, min(fc1, 0.45 * fsf), fs=fsf, output="sos")
    aa_kind = "bessel" if rf.random() < 0.5 else "butter"
    fc_aa = float(rf.uniform(0.3, 0.42)) * fs
    if aa_kind == "bessel":
        sos_aa = signal.bessel(4, fc_aa, fs=fsf, output="sos", norm="mag")
    else:
        sos_aa = signal.butter(4, fc_aa, fs=fsf, output="sos")

    def chain(sig, sos_list):
        y = sig
        for so in sos_list:
            zi = signal.sosfilt_zi(so) * y[0]
            y, _ = signal.sosfilt(so, y, zi=zi)
        return y

    white_rel = float(rn.uniform(0.003, 0.012))
    pink_rel = float(rn.uniform(0.002, 0.008))
    lat = F_true + rn.standard_normal(len(tf)) * white_rel * drop_F * math.sqrt(ov / 2.0)
    nuis = {}
    hum_f = None
    if nuisance == "hum":
        hum_f = 50.0 if rn.random() < 0.5 else 60.0
        ha = float(rn.uniform(0.01, 0.05)) * drop_F
        h2 = float(rn.uniform(0.2, 0.5))
        hk = int(rn.choice([2, 3]))
        ph1, ph2 = rn.uniform(0, _TWO_PI, 2)
        lat = lat + ha * (np.sin(_TWO_PI * hum_f * tf + ph1) + h2 * np.sin(_TWO_PI * hk * hum_f * tf + ph2))
        nuis.update({"hum_hz": hum_f, "hum_amp_over_drop": ha / drop_F, "harmonic": hk, "harm_rel": h2})
    if nuisance == "drift":
        dr = float(rn.uniform(0.04, 0.15)) * drop_F * (1 if rn.random() < 0.5 else -1)
        tau_dr = float(rn.uniform(0.3, 2.0)) * dur
        tt = tf - tf[0]
        lat = lat + dr * (0.5 * tt / dur + 0.5 * (1 - np.exp(-tt / tau_dr)) / (1 - math.exp(-dur / tau_dr)))
        nuis.update({"drift_over_drop": dr / drop_F, "drift_tau_s": tau_dr})
    lat = chain(lat, [sos1, sos_aa])[n_warm::ov][:n]
    lat = lat + _one_over_f(rn, n, pink_rel * drop_F)
    # ---- normal channel ----
    nsens_white = float(rn.uniform(0.001, 0.005)) * N0
    nor = N_true + rn.standard_normal(len(tf)) * nsens_white * math.sqrt(ov / 2.0)
    if hum_f is not None:
        nor = nor + 0.5 * nuis["hum_amp_over_drop"] * drop_F * np.sin(_TWO_PI * hum_f * tf + 0.7)
    if nuisance == "drift":
        nor = nor + float(rn.uniform(-0.03, 0.03)) * N0 * (tf - tf[0]) / dur
    sos_n = signal.butter(1, min(float(rf.uniform(8.0, 20.0)) * fn, 0.45 * fsf), fs=fsf, output="sos")
    nor = chain(nor, [sos_n, sos_aa])[n_warm::ov][:n]
    nor = nor + _one_over_f(rn, n, 0.002 * N0)
    # ---- stage position ----
    if st.kind == "cl":
        pn = float(rn.uniform(0.3e-9, 1.5e-9))
        pos = pos_true + rn.standard_normal(len(tf)) * pn * math.sqrt(ov / 2.0)
        sos_p = signal.butter(2, min(float(rf.uniform(3.0, 8.0)) * fn, 0.45 * fsf), fs=fsf, output="sos")
        pos = chain(pos, [sos_p])[n_warm::ov][:n]
    elif st.kind == "st":
        pstep = st.p_ms * Lu
        pos = (np.round(pos_cmd / pstep) * pstep)[n_warm::ov][:n]
    else:
        pos = pos_cmd[n_warm::ov][:n]
    t_s = tf[n_warm::ov][:n] - tf[n_warm]
    # ---- ADC ----
    full = 2.5 * max(np.max(np.abs(lat)), 1e-30)
    q = 2 * full / 65536.0
    if nuisance == "quantisation":
        q = float(rn.uniform(0.002, 0.01)) * drop_F
        nuis["adc_step_over_drop"] = q / drop_F
    lat = np.round(lat / q) * q
    qn = 2 * 2.0 * N0 / 65536.0 if nuisance != "quantisation" else 0.004 * N0
    nor = np.round(nor / qn) * qn
    if nuisance == "spikes":
        frac = float(rn.uniform(0.0005, 0.005))
        m = int(max(3, frac * n))
        idx = rn.choice(n, m, replace=False)
        amp = rn.uniform(0.5, 3.0, m) * drop_F * np.where(rn.random(m) < 0.5, -1, 1)
        lat[idx] += amp
        idn = idx[rn.random(m) < 0.3]
        nor[idn] += rn.uniform(0.1, 0.4, len(idn)) * N0 * np.where(rn.random(len(idn)) < 0.5, -1, 1)
        nuis.update({"spike_fraction": m / n})
    # ---- what to export ----
    style = int((seed * 2 + _CASES.index(case) * 3 + seed // 5) % 5)
    lat_kind = "F" if rf.random() < (0.75 if style in (0, 1, 4) else 0.25) else "D"
    rec_normal = case == "load_variation" or rf.random() < 0.45
    mu_only = style == 1 and rec_normal and lat_kind == "F" and rf.random() < 0.4
    if R["recip"] or R["stepped"] or case == "static_ageing":
        rec_pos = True
    elif case == "drive_modulation":
        rec_pos = False
    else:
        rec_pos = rf.random() < 0.5
    add_mu = rec_normal and lat_kind == "F" and not mu_only and rf.random() < 0.4
    f_unit = "uN" if N0 < 2e-3 else "mN"
    f_mul = 1e6 if f_unit == "uN" else 1e3
    d_unit = "nm" if drop_F / k < 2e-6 else "um"
    d_mul = 1e9 if d_unit == "nm" else 1e6
    time_ms = style == 2 or (style == 3 and rf.random() < 0.5)
    kn = k * float(rf.uniform(0.5, 3.0))          # normal stiffness of the cantilever
    # columns
    cols = []
    tcol = t_s * (1e3 if time_ms else 1.0)
    tu = "ms" if time_ms else "s"
    Fz_meas = nor
    lat_force = lat
    mu_meas = lat_force / np.where(np.abs(Fz_meas) > 1e-3 * N0, Fz_meas, 1e-3 * N0)
    us = "\u00b5" if (style == 0 and seed % 3 == 0) else "u"
    if style == 0:
        names = {"t": "Time [%s]" % tu, "F": "Fx [%sN]" % (us if f_unit == "uN" else "m"),
                 "D": "Dx [%s]" % (d_unit.replace("u", us)), "N": "Fz [%sN]" % (us if f_unit == "uN" else "m"),
                 "Dz": None, "P": "Position X [%sm]" % us, "Mu": "Mu"}
    elif style == 1:
        names = {"t": "Time (%s)" % tu, "F": "Lateral Force (%s)" % f_unit, "D": "Lateral Deflection (%s)" % d_unit,
                 "N": "Normal Force (%s)" % f_unit, "P": "Position (um)", "Mu": "COF"}
    elif style == 2:
        names = {"t": "Time [%s]" % tu, "F": "Fx [%s]" % f_unit, "D": "Dx [%s]" % d_unit,
                 "N": "Fz [%s]" % f_unit, "Dz": "Dz [%s]" % d_unit, "P": "Stage X [um]", "Mu": "Mu"}
    elif style == 3:
        names = {"t": ("Time", tu), "F": ("Lateral force", f_unit), "D": ("Lateral deflection", d_unit),
                 "N": ("Normal force", f_unit), "P": ("Stage position", "um"), "Mu": ("Friction coefficient", "1")}
    else:
        names = {"t": "Time [%s]" % tu, "F": "Fx [%s]" % f_unit, "D": "Dx [%s]" % d_unit,
                 "N": "Fz [%s]" % f_unit, "P": "Position X [um]", "Mu": "Mu"}
    cols.append((names["t"], tcol, "%.6f" if not time_ms else "%.4f"))
    if mu_only:
        cols.append((names["Mu"], mu_meas, "%.5f"))
    elif lat_kind == "F":
        cols.append((names["F"], lat_force * f_mul, "%.6g"))
    else:
        cols.append((names["D"], lat / k * d_mul, "%.6g"))
    normal_as = None
    if rec_normal:
        if style == 2 and rf.random() < 0.5:
            cols.append((names["Dz"], nor / kn * d_mul, "%.6g"))
            normal_as = "deflection"
        else:
            cols.append((names["N"], Fz_meas * f_mul, "%.6g"))
            normal_as = "force"
    if rec_pos:
        p0 = float(rf.uniform(-200, 200)) * 1e-6 if rf.random() < 0.5 else 0.0
        cols.append((names["P"], (pos - (pos[0] if not R["recip"] else 0.0) + p0) * 1e6, "%.5f"))
    if add_mu:
        cols.append((names["Mu"], mu_meas, "%.5f"))
    # ---- metadata ----
    probe = rf.choice(["Steel ball 100Cr6, d = 1.5 mm", "Sapphire ball, d = 1 mm", "Si3N4 ball, d = 2 mm",
                       "Borosilicate glass sphere, d = 0.5 mm", "Ruby ball, d = 3 mm",
                       "PS microsphere on cantilever, d = 0.8 mm"])
    sample = rf.choice(["OTS monolayer on Si(100)", "PMMA film, 2 um, spin-coated", "PDMS film",
                        "Polyacrylamide hydrogel", "PTFE film", "Epoxy coating", "DLC on Si"])
    inst = ["Anton Paar NTR3 Nanotribometer", "Bruker UMT TriboLab, micro-load head", "Home-built piezo micro-tribometer",
            "Fibre-optic micro-tribometer (lab-built)", "CSM Nano Tribometer"][style]
    sp_txt = _fmt_num(v0 * 1e6, 4) + " um/s"
    load_txt = (_fmt_num(N0 * 1e6, 4) + " uN") if N0 < 2e-3 else (_fmt_num(N0 * 1e3, 4) + " mN")
    fs_txt = (_fmt_num(fs / 1e3, 4) + " kHz") if fs >= 1000 else (_fmt_num(fs, 4) + " Hz")
    meta = [("Instrument", inst), ("Probe", str(probe)), ("Sample", str(sample)),
            ("Acquisition rate", fs_txt), ("Normal load", load_txt), ("Speed", sp_txt),
            ("Stiffness (lateral)", _fmt_num(k, 4) + " N/m"), ("Stiffness (normal)", _fmt_num(kn, 4) + " N/m"),
            ("Mode", "reciprocating" if R["recip"] else "linear"),
            ("Stage", {"cl": "piezo, closed loop (capacitive)", "ol": "piezo, open loop",
                       "st": "stepper motor, microstepping"}[st.kind]),
            ("Lateral sensor", sens + (" (lock-in demodulated)" if lockin else "")),
            ("Temperature", _fmt_num(float(rf.uniform(20.5, 24.5)), 3) + " C"),
            ("Humidity", _fmt_num(float(rf.uniform(25, 55)), 2) + " %RH")]
    if R["recip"]:
        meta.append(("Track length", _fmt_num(float(np.max(pos) - np.min(pos)) * 1e6, 4) + " um"))
    os.makedirs(outdir, exist_ok=True)
    ext = {0: ".txt", 1: ".csv", 2: ".txt", 3: ".txt", 4: ".csv"}[style]
    fname = os.path.join(outdir, "%s_%s_s%02d_%s%s" % (NAME, case, seed, nuisance, ext))
    data = np.column_stack([c[1] for c in cols])
    fmts = [c[2] for c in cols]
    lines = []
    if style == 0:
        lines += ["%s: %s" % kv for kv in meta] + ["", "\t".join(c[0] for c in cols)]
        sep, dec = "\t", "."
    elif style == 1:
        lines += ["%s,%s" % (a, '"%s"' % b if "," in b else b) for a, b in meta] + ["", ",".join(c[0] for c in cols)]
        sep, dec = ",", "."
    elif style == 2:
        lines += ["# %s: %s" % (a, b.replace(".", ",")) for a, b in meta] + [";".join(c[0] for c in cols)]
        sep, dec = ";", ","
    elif style == 3:
        lines += ["%s:\t%s" % kv for kv in meta[:8]] + ["\t".join(c[0][0] for c in cols),
                                                          "\t".join(c[0][1] for c in cols)]
        sep, dec = "\t", "."
    else:
        lines += ["# %s: %s" % kv for kv in meta] + [",".join(c[0] for c in cols)]
        sep, dec = ",", "."
    fmt = sep.join(fmts)
    body = "\n".join(fmt % tuple(row) for row in data)
    if dec == ",":
        body = body.replace(".", ",")
    with open(fname, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n" + body + "\n")
    # ---- arguments a user would pass ----
    given = None
    args = []
    omit_fn = (seed % 8 == 3) and case != "triggering" and nuisance != "fn_off"
    fn_given = None
    if not omit_fn:
        fn_given = fn * ((1.05 if rn.random() < 0.5 else 0.95) if nuisance == "fn_off" else 1.0)
        args += ["--fn", _fmt_num(fn_given, 5)]
    if not rec_pos:
        args += ["--v0", sp_txt]
    if lat_kind == "F" or mu_only:
        args += ["--stiffness", _fmt_num(k, 4) + " N/m"]
    export = {"style": style, "file_format": ["NTR-like TAB", "UMT-like CSV", "LabVIEW semicolon/decimal comma",
                                              "TAB with a unit row", "CSV with # comments"][style],
              "columns": [c[0] if isinstance(c[0], str) else "%s [%s]" % c[0] for c in cols],
              "lateral": "mu" if mu_only else ("force" if lat_kind == "F" else "deflection"),
              "normal": normal_as, "position": bool(rec_pos),
              "fs_hz": fs, "samples": n, "samples_per_period": fs / fn,
              "sensor": sens, "lockin": lockin, "sensor_fc_over_fn": fc1 / fn, "aa": aa_kind,
              "aa_fc_over_fs": fc_aa / fs, "white_over_drop": white_rel, "pink_over_drop": pink_rel}
    phys = {"fn_hz": fn, "k_N_per_m": k, "m_kg": k / wn ** 2, "N0_N": N0, "v0_m_per_s": v0,
            "drop_N": drop_F, "duration_s": n / fs, "normal_stiffness_N_per_m": kn}
    return fname, args, fn, fn_given, export, phys, nuis


def _truth(R, case):
    M, meas = R["M"], R["meas"]
    out = {k: v for k, v in meas.items()}
    out["f_ss_over_fn"] = R["f_ss_rel"]
    Ns = [b[3] for b in R["breaks"] if R["t_start"] <= b[0] <= R["t_end"]]
    for p in R["phases"]:
        if p[0] == "slip" and R["t_start"] <= p[1][0] <= R["t_end"]:
            Ns.extend(p[6].tolist())
    if Ns:
        out["load_pp_over_N0"] = float(max(Ns) - min(Ns))
    if M.trig is not None:
        out["trig_eps"] = M.trig[0]
        out["ft_over_fn"] = M.trig[1]
        out["ft_over_fss"] = M.trig[1] / R["f_ss_rel"]
        out["load_pp_over_N0"] = 2.0 * M.trig[0]
    if M.stage.mod is not None:
        out["mod_a"] = M.stage.mod[0]
        out["fm_over_fss"] = M.stage.mod[2] / R["f_ss_rel"]
    return out


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in _CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in _NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    R = _run(case, seed, nuisance)
    fname, args, fn, fn_given, export, phys, nuis = _render(R, case, seed, nuisance, outdir)
    params = dict(R["params"])
    params["truth"] = _truth(R, case)
    params["physical"] = phys
    params["export"] = export
    params["nuisance"] = nuis
    params["v0_given"] = "--v0" in args
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance,
            "file": os.path.abspath(fname), "args": args, "fn_true": float(fn),
            "fn_given": None if fn_given is None else float(fn_given), "params": _jsonable(params)}


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.bool_):
        return bool(o)
    if isinstance(o, float) and not math.isfinite(o):
        return None
    return o
