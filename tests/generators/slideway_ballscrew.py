"""Machine-tool slideway on a ball-screw feed drive: an independent generator of stick-slip records.

Written without reading the diagnosis (only `tests/generators/README.md` and the top-level README's
description of the input files); `lieng diagnose` / `lieng synth` were never run on these records.

Rig
---
A machine-tool table (mass m) on oil-lubricated, scraped cast-iron slideways is fed by a servo motor and a
ball screw; the screw's axial compliance and a flexure in the nut housing are the spring k. The nut is the
drive (an ideal kinematic feed, x_d(t)): its position is the motor's rotary encoder times the lead (0.1 um
counts). The spring force is read by a strain-gauge load washer in the nut housing, or the spring's extension
as the nut's position less the table's linear glass scale (the axis' "following error"). fn 4-30 Hz,
k 3-80 kN/m, normal load N0 30-600 N, fn/f_ss 4-44.

Friction law (slideway oil with polar additives), per unit load, single-valued in the sliding speed u:
    mu(u) = mu_m + D * erfc(ln(u / v_s) / (sqrt(2) w)) / 2 + mu_e * asinh(u / v_e)
a log-normal (erfc of ln u) weakening of depth D = 0.15-0.35 mu_s centred at v_s (0.08-0.35 of the slip-speed
scale, width w 0.5-1.2 in ln u) on an Eyring (asinh) strengthening of the additive's boundary layer
(mu_e 0.05-0.2 D). It is C-infinity at u -> 0+ (the erfc of ln u is flat there), mu(0+) = mu_m + D; the static
level mu_s (0.12-0.22) is 5-12 % of mu_s above mu(0+). Friction = N mu. The static level has a small texture
along the table's position (the scraped ways' bearing spots: 8 random sinusoids, wavelengths 0.05-0.5 slip
lengths), sd 0.2-0.6 % of the drop (2-3.5 % on `triggering`, where it breaks the 1:n locking, below).

Stick handling: exact switching with **Henon's method** (the independent variable swapped for the guard
function, then one integration step landing exactly on it): the arrest by integrating
d(t, x, h)/dv = (1, v, h')/v' from the step's start to v = 0 (one GBS step; 4 or 16 sub-steps when v' >= 0
at the start); the breakaway by a vectorised scan of the guard g(t) = |k e(t)| - mu_s,eff N(t) over the stick
(the table exactly at rest, the drive and the auxiliary states in closed form; scan Tn/12, 1/12 of a shaker
period), the bracket cut at a drive knot and by 16 sub-points, then dt/dg = 1/g'(t) (g' analytic) integrated
from the last negative point to g = 0 (1, 4 or 16 GBS steps; the scan's point as a fallback, never needed on
seeds 0-7). At an arrest the table stays stuck if |k e| <= mu_s N, else slides on toward the spring force.
No band, no regularisation, no bisection or root finder.

Integrator: own fixed-step **Gragg-Bulirsch-Stoer** (modified midpoint, step sequence 2, 4, 6, 8,
polynomial Richardson extrapolation in h^2: order 8) at Tn/48 in the slips (1/10 of a shaker period at most),
never stepping over a drive knot; the Henon steps are GBS steps of the swapped systems. Tn/48 against Tn/192:
drop and f_ss within 3e-9 (3e-4 with the lift state), twin and ageing within 1e-5 of the drop. Dense output by
quintic Hermite interpolation (x, v, a at the step ends; the stick exactly constant).

Sensor and record: the load washer / glass scales on a grid R = 4-8 times the record rate, a linear-phase
Kaiser-window FIR (brick-wall at 0.45 fs, beta 9, delay compensated, as a DSA card's decimation filter),
decimated; noise white plus a component with a 1/sqrt(1 + (f/fc)^2) amplitude spectrum (fc 0.3-3 fn), sd
0.2-1 % of the drop; the nut encoder quantised to 0.1 um (never filtered). Exports: comma CSV with `#` lines
(`Time [s]`, `Friction force (N)`, `Normal load [N]`, `stage_pos[um]`, `Feed speed [mm/s]`), semicolon with
a decimal comma under instrument lines (`t (s)`, `F_friction [mN]`, `x [um]`, `normal_load_N`,
`v_drive [mm/s]`), TAB (`time_ms`, `feed_force_N`, `spring_extension_um`, `nut_position_mm`), whitespace
`.dat` with a unit row under blank-free names; time in s or ms, sometimes with an offset; the spring force
(N or mN, `--stiffness`) on ~60 %, the extension (mm or um) on the rest; the drive as the encoder position,
the commanded feed, or `--v0`; 20-100 samples per natural period (coarse 10-15; hum records raised to
fs >= 260 Hz where possible), 17-46 cycles, 2 500-75 000 rows; `--fn` left out on seeds 3 mod 8 (never on
`triggering` or `fn_off`). A record takes 0.1-0.8 s.

Departures (each only in its own case; measured on the ground truth, seeds 0-7, as fractions of the
median stick-slip force drop unless said; see the self-check):
* load_variation: even seeds, the nut sits off the slideway's centre line, so the screw's axial force pitches
  the table onto its front way: N = N0 + gamma (k e - F_ref), gamma of either sign (|gamma mu_s| <= 0.45);
  odd seeds, a slideway waviness along the table's position, N = N0 (1 + A sin(2 pi x / lambda + phi)),
  lambda 1.3-3 slip lengths. Measured N p-p 12.4-28.4 % of N0 (15-35 % of the drop in friction); the friction
  per unit load exactly single-valued, F itself double-valued by -0.14..+0.16 on the gamma seeds. The normal
  load (load washers under the gibs) recorded on seeds 0, 3, 4, 7 mod 8.
* twin_branch: hydrodynamic lift of the table ("floating"): a lift state h relaxes with tau_h 0.08-0.2 Tn
  toward h_eq(u) = u/(u + v_h) (v_h 0.3-1 of the peak slip speed); the boundary share falls as the table
  floats, mu = mu(u) - G (h - h_eq(u)) (zero in steady sliding): h lags below h_eq while accelerating and above
  it while decelerating, so the friction is LOWER while decelerating. G calibrated on short pilots. Measured
  (decelerating minus accelerating at equal true sliding speed, 10-90 % of each slip's peak speed, median over
  slips): -0.188..-0.123.
* static_ageing: ordering of the adsorbed additive layer at rest,
  mu_s,eff = mu_s + b ln(1 + (t_stick / tau_a)^p), p 0.5-0.9, tau_a 0.3-1 of the short stick; feed steps
  4-8x (even seeds) or slide-hold-slide holds of 3-9 stick times (odd seeds); b calibrated on a shortened run.
  Measured (true breakaway peaks regressed on ln t_stick, over the record's range): +0.138..+0.196 over
  stick times 5.7-10.8x apart. The drive recorded (encoder position or commanded feed).
* triggering: an unbalanced spindle motor on the machine shakes the normal load, N0 (1 + A sin(2 pi f_t t)),
  A 3-8 % (3.1-5.5 % on seeds 0-7), f_t 2.5-7 fn; the static excess is drawn >= 2.4 A so that the shaker's
  crest does not re-arrest a starting slip (with less, each breakaway stuttered through 2-5 micro-slips one
  shaker period apart). Without the texture every f_t tried gave an exact 1:n lock (f_t/f_ss an integer, no
  mixed window found by bisection); with it, f_t is redrawn (up to 10 runs) while the record's f_t/f_ss is
  within 0.15 of an integer. Seeds 0-7: f_t 3.7-6.7 fn, f_t/f_ss 23-48, 0.19-0.47 from an integer; the slips
  come early by 0.04-0.09 of the drop (mean peak below mu_s N0); peak sd 2.1-3.9 %; F (not F/N) double-valued
  by -0.015..+0.032 from N's swing inside the slips.
* drive_modulation: a worn ball screw's once-per-turn lead error, v_d = v0 (1 + a sin(2 pi f_m t + phi)),
  a 0.23-0.45, f_m/f_ss of the record 0.13-0.39; the file gives only the commanded (mean) feed or `--v0`.
  Law single-valued, no ageing (peaks vs stick time -0.002..+0.003 over 1.5-2.4x).

`none` (seeds 0-7): constant load, a single-valued law, no ageing, no lift state; seeds 2 mod 8 step the feed
4-8x, seeds 5 mod 8 have slide-hold-slide holds (stick times 6.8-8.3x apart on the two), the drive then
recorded.
Measured on the ground truth: twin |.| < 1e-5 of the drop, N exactly constant, peak sd 0.2-0.5 % (the
texture), peak growth with stick time -0.10..+0.12 % on the stepped/held records (-0.25..-0.07 % read on the
clean sampled record). What a 1-DoF reading may mistake: (i) the FIR decimation filter's ringing at the
breakaway and arrest kinks, the recorded clean peak 0.02-0.4 % of the drop above the true one (no phase lag:
the filter is zero-phase); (ii) a 1-DoF reading of the clean samples by central differences
(friction = k e - m x'', x = x_d - e) sees a twin of -0.6..-1.4 % at 79-99 samples per period, -3 % at 56,
-5.6 % at 33, -10 % at 26 and -23 % at 13 (coarse): the breakaway's jump in acceleration (mu_s - mu(0+)) N/m
smeared by the differencing, not in the physics (the same on ideal, unfiltered samples); (iii) the texture's
peak scatter. All are stored per record in `params` (`twin_1dof_clean_record`, `twin_1dof_ideal_samples`,
`fir_peak_overshoot_over_drop`, `peak_growth_clean_record`, `peak_sd_over_drop`).
"""

import json
import math
import os
import sys
import time
import zlib

import numpy as np
from scipy import signal
from scipy.special import erfc as _erfc_vec

NAME = "slideway_ballscrew"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

_SQ2 = math.sqrt(2.0)
_TWOPI = 2.0 * math.pi


def _rng(case, seed, extra):
    base = zlib.crc32(NAME.encode())
    return np.random.default_rng([base, CASES.index(case), int(seed), int(extra)])


# ----------------------------------------------------------------------------------------------------------
# drive
# ----------------------------------------------------------------------------------------------------------
class Drive:
    """Nut position x_d(t): piecewise-constant speed (steps, holds) or a sinusoidally modulated speed."""

    def __init__(self, v0, knots=None, mod=None):
        self.v0 = float(v0)
        self.mod = mod  # (a, fm, phi)
        if knots is None:
            knots = [(0.0, v0)]
        self.kt = np.array([k[0] for k in knots], float)
        self.kv = np.array([k[1] for k in knots], float)
        pos = [0.0]
        for i in range(1, len(self.kt)):
            pos.append(pos[-1] + self.kv[i - 1] * (self.kt[i] - self.kt[i - 1]))
        self.kx = np.array(pos)
        self.ktl = list(self.kt)

    def pos(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            a, fm, ph = self.mod
            w = _TWOPI * fm
            return self.v0 * t - self.v0 * a / w * (np.cos(w * t + ph) - math.cos(ph))
        i = np.clip(np.searchsorted(self.kt, t, side="right") - 1, 0, None)
        return self.kx[i] + self.kv[i] * (t - self.kt[i])

    def vel(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            a, fm, ph = self.mod
            return self.v0 * (1.0 + a * np.sin(_TWOPI * fm * t + ph))
        i = np.clip(np.searchsorted(self.kt, t, side="right") - 1, 0, None)
        return self.kv[i]

    def pos_s(self, t):
        if self.mod is not None:
            a, fm, ph = self.mod
            w = _TWOPI * fm
            return self.v0 * t - self.v0 * a / w * (math.cos(w * t + ph) - math.cos(ph))
        kt = self.ktl
        lo, hi = 0, len(kt)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if kt[mid] <= t:
                lo = mid
            else:
                hi = mid
        return self.kx[lo] + self.kv[lo] * (t - kt[lo])

    def vel_s(self, t):
        if self.mod is not None:
            a, fm, ph = self.mod
            return self.v0 * (1.0 + a * math.sin(_TWOPI * fm * t + ph))
        kt = self.ktl
        lo, hi = 0, len(kt)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if kt[mid] <= t:
                lo = mid
            else:
                hi = mid
        return float(self.kv[lo])

    def next_knot(self, t):
        if self.mod is not None or len(self.ktl) < 2:
            return math.inf
        i = int(np.searchsorted(self.kt, t, side="right"))
        return float(self.kt[i]) if i < len(self.kt) else math.inf


# ----------------------------------------------------------------------------------------------------------
# Gragg-Bulirsch-Stoer step (plain Python floats: the state has 1-3 components)
# ----------------------------------------------------------------------------------------------------------
_SEQ = (2, 4, 6, 8)
_H_DIV = 48.0  # slip step Tn / _H_DIV


def _gbs(f, t0, y0, H):
    n_y = len(y0)
    f0 = f(t0, y0)
    rows = []
    for j, n in enumerate(_SEQ):
        h = H / n
        za = list(y0)
        zb = [y0[i] + h * f0[i] for i in range(n_y)]
        for mm in range(1, n):
            fm = f(t0 + mm * h, zb)
            zc = [za[i] + 2.0 * h * fm[i] for i in range(n_y)]
            za, zb = zb, zc
        fe = f(t0 + H, zb)
        yn = [0.5 * (za[i] + zb[i] + h * fe[i]) for i in range(n_y)]
        row = [yn]
        for kk in range(j):
            r = (n / _SEQ[j - kk - 1]) ** 2
            prev = rows[j - 1][kk]
            cur = row[kk]
            row.append([cur[i] + (cur[i] - prev[i]) / (r - 1.0) for i in range(n_y)])
        rows.append(row)
    return rows[-1][-1]


# ----------------------------------------------------------------------------------------------------------
# the rig
# ----------------------------------------------------------------------------------------------------------
class Rig:
    def __init__(self, P):
        self.P = P
        self.k = P["k"]
        self.m = P["m"]
        self.N0 = P["N0"]
        self.mu_m = P["mu_m"]
        self.Dw = P["Dw"]
        self.vs = P["vs"]
        self.w = P["w"]
        self.mu_e = P["mu_e"]
        self.v_e = P["v_e"]
        self.mu_s = P["mu_s"]
        self.load_mode = P.get("load_mode")  # None, 'nut', 'wave'
        self.gamma = P.get("gamma", 0.0)
        self.F_ref = P.get("F_ref", 0.0)
        self.A_w = P.get("A_w", 0.0)
        self.lam = P.get("lam", 1.0)
        self.ph_w = P.get("ph_w", 0.0)
        self.A_t = P.get("A_t", 0.0)
        self.f_t = P.get("f_t", 0.0)
        self.ph_t = P.get("ph_t", 0.0)
        self.G = P.get("G", 0.0)
        self.tau_h = P.get("tau_h", 1.0)
        self.v_h = P.get("v_h", 1.0)
        self.b_age = P.get("b_age", 0.0)
        self.tau_a = P.get("tau_a", 1.0)
        self.p_age = P.get("p_age", 0.7)
        self.tex_c = np.asarray(P.get("tex_c", []), float)
        self.tex_q = np.asarray(P.get("tex_q", []), float)
        self.tex_p = np.asarray(P.get("tex_p", []), float)

    def tex(self, x):
        """Static level's texture along the table's position (the scraped ways' bearing spots)."""
        if self.tex_c.size == 0:
            return 0.0
        return float(np.sum(self.tex_c * np.sin(self.tex_q * x + self.tex_p)))

    # friction law per unit load (scalar)
    def mu(self, u):
        if u <= 0.0:
            return self.mu_m + self.Dw + self.mu_e * math.asinh(u / self.v_e)
        return (self.mu_m + 0.5 * self.Dw * math.erfc(math.log(u / self.vs) / (_SQ2 * self.w))
                + self.mu_e * math.asinh(u / self.v_e))

    def mu_vec(self, u):
        u = np.asarray(u, float)
        up = np.maximum(u, 1e-300)
        val = self.mu_m + 0.5 * self.Dw * _erfc_vec(np.log(up / self.vs) / (_SQ2 * self.w))
        val = np.where(u <= 0.0, self.mu_m + self.Dw, val)
        return val + self.mu_e * np.arcsinh(u / self.v_e)

    def heq(self, u):
        u = max(u, 0.0)
        return u / (u + self.v_h)

    def N(self, t, x, e):
        if self.load_mode == "nut":
            return self.N0 + self.gamma * (self.k * e - self.F_ref)
        if self.load_mode == "wave":
            return self.N0 * (1.0 + self.A_w * math.sin(_TWOPI * x / self.lam + self.ph_w))
        if self.A_t:
            return self.N0 * (1.0 + self.A_t * math.sin(_TWOPI * self.f_t * t + self.ph_t))
        return self.N0

    def N_vec(self, t, x, e):
        t = np.asarray(t, float)
        if self.load_mode == "nut":
            return self.N0 + self.gamma * (self.k * np.asarray(e) - self.F_ref)
        if self.load_mode == "wave":
            return self.N0 * (1.0 + self.A_w * np.sin(_TWOPI * np.asarray(x) / self.lam + self.ph_w)) + 0 * t
        if self.A_t:
            return self.N0 * (1.0 + self.A_t * np.sin(_TWOPI * self.f_t * t + self.ph_t))
        return self.N0 + 0.0 * t

    def age(self, ts):
        ts = np.maximum(np.asarray(ts, float), 0.0)
        return self.b_age * np.log1p((ts / self.tau_a) ** self.p_age)

    def dage(self, ts):
        if self.b_age == 0.0 or ts <= 0.0:
            return 0.0
        r = (ts / self.tau_a) ** self.p_age
        return self.b_age * self.p_age * r / (ts * (1.0 + r))


def simulate(rig, drive, t_end, max_slips=10 ** 9, x_init=None):
    """Run the rig to t_end. Returns nodes (t, x, v, aL, aR, h), the interval kinds and the events."""
    k, m = rig.k, rig.m
    Tn = _TWOPI * math.sqrt(m / k)
    H0 = Tn / _H_DIV
    if rig.A_t:
        H0 = min(H0, 1.0 / (rig.f_t * 10.0))
    hs0 = Tn / 12.0
    if rig.A_t:
        hs0 = min(hs0, 1.0 / (rig.f_t * 12.0))
    twin = rig.G != 0.0
    sig = [1.0]

    def acc(t, x, v, h):
        xd = drive.pos_s(t)
        e = xd - x
        N = rig.N(t, x, e)
        u = sig[0] * v
        mu = rig.mu(u)
        if twin:
            mu -= rig.G * (h - rig.heq(u))
        return (k * e - sig[0] * N * mu) / m

    def rhs(t, y):
        x, v, h = y
        a = acc(t, x, v, h)
        hd = (rig.heq(sig[0] * v) - h) / rig.tau_h
        return (v, a, hd)

    def rhs_henon(s, z):  # independent variable: v
        t, x, h = z
        a = acc(t, x, s, h)
        hd = (rig.heq(sig[0] * s) - h) / rig.tau_h
        return (1.0 / a, s / a, hd / a)

    T, X, V, AL, AR, HH, KIND, SIG = [], [], [], [], [], [], [], []
    stats = dict(henon_breakaway=0, henon_breakaway_fallback=0, henon_arrest=0, henon_arrest_substeps=0)
    brk, arr = [], []

    t = 0.0
    x = 0.0 if x_init is None else x_init
    h = 0.0
    t_arr = 0.0
    h_arr = 0.0
    T.append(t); X.append(x); V.append(0.0); AL.append(0.0); AR.append(0.0); HH.append(0.0)
    n_slips = 0
    while t < t_end:
        # ------------------------------------------------------------------ stick
        xs = x
        mus_x = rig.mu_s + rig.tex(xs)

        def g_vec(ts):
            e = drive.pos(ts) - xs
            N = rig.N_vec(ts, xs, e)
            return np.abs(k * e) - (mus_x + rig.age(ts - t_arr)) * N

        def g_s(ts):
            return float(g_vec(np.array([ts]))[0])

        def gp_s(ts, sgn):
            vd = drive.vel_s(ts)
            e = drive.pos_s(ts) - xs
            N = rig.N(ts, xs, e)
            musx = mus_x + float(rig.age(ts - t_arr))
            if rig.load_mode == "nut":
                dN = rig.gamma * k * vd
            elif rig.A_t:
                dN = rig.N0 * rig.A_t * _TWOPI * rig.f_t * math.cos(_TWOPI * rig.f_t * ts + rig.ph_t)
            else:
                dN = 0.0
            return sgn * k * vd - rig.dage(ts - t_arr) * N - musx * dN

        t_lo = t
        t_b = None
        if g_s(t) >= 0.0:
            t_b = t
        while t_b is None and t_lo < t_end:
            ts = t_lo + hs0 * np.arange(1, 257)
            gs = g_vec(ts)
            idx = np.nonzero(gs >= 0.0)[0]
            if idx.size == 0:
                t_lo = float(ts[-1])
                continue
            j = int(idx[0])
            a_ = t_lo if j == 0 else float(ts[j - 1])
            b_ = float(ts[j])
            kn = drive.next_knot(a_)
            if a_ < kn < b_:
                if g_s(kn) >= 0.0:
                    b_ = kn
                else:
                    a_ = kn
            sub = np.linspace(a_, b_, 17)
            gsub = g_vec(sub)
            jj = int(np.nonzero(gsub >= 0.0)[0][0])
            if jj == 0:
                t_b = a_
                break
            ta, tb_ = float(sub[jj - 1]), float(sub[jj])
            ga = float(gsub[jj - 1])
            e_b = drive.pos_s(tb_) - xs
            sgn = 1.0 if e_b >= 0 else -1.0
            tt = None
            for nsub in (1, 4, 16):
                try:
                    # Henon: dt/dg = 1/g'(t), from g = ga to 0, in nsub GBS steps
                    tcur = ta
                    gcur = ga
                    ok = True
                    for _ in range(nsub):
                        dg = -ga / nsub
                        gpa = gp_s(tcur, sgn)
                        if gpa <= 0:
                            ok = False
                            break
                        tcur = _gbs(lambda gg, z: (1.0 / gp_s(z[0], sgn),), gcur, [tcur], dg)[0]
                        gcur += dg
                    if ok and ta - 1e-12 * Tn <= tcur <= tb_ + 1e-9 * Tn and math.isfinite(tcur):
                        tt = tcur
                        break
                except ZeroDivisionError:
                    pass
            if tt is None:  # g' not positive over the sub-interval (shaker): take the scan's next point
                tt = tb_
                stats["henon_breakaway_fallback"] += 1
            else:
                stats["henon_breakaway"] += 1
            t_b = min(max(tt, ta), tb_)
        if t_b is None or t_b >= t_end:
            if t_end > t:
                T.append(t_end); X.append(x); V.append(0.0); AL.append(0.0); AR.append(0.0)
                HH.append(h_arr * math.exp(-(t_end - t_arr) / rig.tau_h))
                KIND.append(1); SIG.append(0.0)
            break
        e_b = drive.pos_s(t_b) - x
        sig[0] = 1.0 if e_b >= 0 else -1.0
        h = h_arr * math.exp(-(t_b - t_arr) / rig.tau_h)
        Nb = rig.N(t_b, x, e_b)
        a0 = acc(t_b, x, 0.0, h)
        if t_b > T[-1]:
            T.append(t_b); X.append(x); V.append(0.0); AL.append(0.0); AR.append(a0); HH.append(h)
            KIND.append(1); SIG.append(0.0)
        else:
            AR[-1] = a0
        brk.append(dict(t=t_b, F=k * e_b, t_stick=t_b - t_arr, N=Nb, node=len(T) - 1))
        n_slips += 1
        # ------------------------------------------------------------------ slip
        t = t_b
        v = 0.0
        arrested = False
        while t < t_end:
            H = H0
            kn = drive.next_knot(t + 1e-12 * Tn)
            if t + H > kn:
                H = kn - t
                if H < 1e-9 * Tn:
                    H = H0
            y1 = _gbs(rhs, t, (x, v, h), H)
            if sig[0] * y1[1] <= 0.0 and t > t_b:
                # arrest inside the step: Henon from a step start with v' < 0
                res = None
                for nsub in (1, 4, 16):
                    hh_ = H / nsub
                    tc, yc = t, (x, v, h)
                    for _ in range(nsub):
                        yn = _gbs(rhs, tc, yc, hh_)
                        if sig[0] * yn[1] <= 0.0:
                            break
                        tc, yc = tc + hh_, yn
                    a_c = acc(tc, yc[0], yc[1], yc[2])
                    if sig[0] * a_c >= 0.0:
                        continue
                    try:
                        z = _gbs(rhs_henon, yc[1], (tc, yc[0], yc[2]), -yc[1])
                    except ZeroDivisionError:
                        continue
                    if tc - 1e-12 <= z[0] <= tc + hh_ * 1.000001 and all(map(math.isfinite, z)):
                        if tc > t:  # keep the intermediate node
                            T.append(tc); X.append(yc[0]); V.append(yc[1]); AL.append(a_c); AR.append(a_c)
                            HH.append(yc[2]); KIND.append(0); SIG.append(sig[0])
                        res = z
                        break
                if res is None:
                    raise RuntimeError("Henon arrest failed")
                stats["henon_arrest"] += 1
                if nsub > 1:
                    stats["henon_arrest_substeps"] += 1
                t, x, h = res
                v = 0.0
                aL = acc(t, x, 0.0, h)
                T.append(t); X.append(x); V.append(0.0); AL.append(aL); AR.append(0.0); HH.append(h)
                KIND.append(0); SIG.append(sig[0])
                e_a = drive.pos_s(t) - x
                Na = rig.N(t, x, e_a)
                if abs(k * e_a) <= (rig.mu_s + rig.tex(x)) * Na:  # stays stuck
                    arr.append(dict(t=t, F=k * e_a, node=len(T) - 1))
                    t_arr = t
                    h_arr = h
                    arrested = True
                    break
                # not held: slides on in the direction of the spring force
                sig[0] = 1.0 if e_a >= 0 else -1.0
                AR[-1] = acc(t, x, 0.0, h)
                t_b = t
                continue
            t += H
            x, v, h = y1
            a1 = acc(t, x, v, h)
            T.append(t); X.append(x); V.append(v); AL.append(a1); AR.append(a1); HH.append(h)
            KIND.append(0); SIG.append(sig[0])
        if not arrested:
            break
        if n_slips >= max_slips:
            break
    nodes = dict(T=np.array(T), X=np.array(X), V=np.array(V), AL=np.array(AL), AR=np.array(AR),
                 H=np.array(HH), KIND=np.array(KIND, int), SIG=np.array(SIG), stats=stats)
    return nodes, brk, arr


def hermite(nodes, tq, deriv=False):
    """Quintic Hermite x(t) (and v(t)) through the nodes."""
    T, X, V, AL, AR = nodes["T"], nodes["X"], nodes["V"], nodes["AL"], nodes["AR"]
    tq = np.asarray(tq, float)
    i = np.clip(np.searchsorted(T, tq, side="right") - 1, 0, len(T) - 2)
    t0, t1 = T[i], T[i + 1]
    D = t1 - t0
    s = np.clip((tq - t0) / D, 0.0, 1.0)
    s2, s3 = s * s, s * s * s
    s4, s5 = s3 * s, s3 * s2
    p0, p1 = X[i], X[i + 1]
    v0, v1 = V[i] * D, V[i + 1] * D
    a0, a1 = AR[i] * D * D, AL[i + 1] * D * D
    h0 = 1 - 10 * s3 + 15 * s4 - 6 * s5
    h1 = s - 6 * s3 + 8 * s4 - 3 * s5
    h2 = 0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5
    h3 = 10 * s3 - 15 * s4 + 6 * s5
    h4 = -4 * s3 + 7 * s4 - 3 * s5
    h5 = 0.5 * s3 - s4 + 0.5 * s5
    x = h0 * p0 + h1 * v0 + h2 * a0 + h3 * p1 + h4 * v1 + h5 * a1
    stick = nodes["KIND"][i] == 1
    x = np.where(stick, p0, x)
    if not deriv:
        return x, i
    d0 = (-30 * s2 + 60 * s3 - 30 * s4)
    d1 = 1 - 18 * s2 + 32 * s3 - 15 * s4
    d2 = s - 4.5 * s2 + 6 * s3 - 2.5 * s4
    d3 = 30 * s2 - 60 * s3 + 30 * s4
    d4 = -12 * s2 + 28 * s3 - 15 * s4
    d5 = 1.5 * s2 - 4 * s3 + 2.5 * s4
    v = (d0 * p0 + d1 * v0 + d2 * a0 + d3 * p1 + d4 * v1 + d5 * a1) / D
    v = np.where(stick, 0.0, v)
    return x, v, i


def friction_truth(rig, drive, nodes, tq):
    """True friction force, sliding speed and normal load at the times tq."""
    x, v, i = hermite(nodes, tq, deriv=True)
    e = drive.pos(tq) - x
    N = rig.N_vec(tq, x, e)
    H = nodes["H"]
    T = nodes["T"]
    w = np.clip((tq - T[i]) / (T[i + 1] - T[i]), 0, 1)
    h = H[i] * (1 - w) + H[i + 1] * w
    sg = nodes["SIG"][i]
    u = sg * v
    mu = rig.mu_vec(u)
    if rig.G:
        uu = np.maximum(u, 0)
        mu = mu - rig.G * (h - uu / (uu + rig.v_h))
    F = np.where(nodes["KIND"][i] == 1, rig.k * e, sg * N * mu)
    return F, v, N, e, x


# ----------------------------------------------------------------------------------------------------------
# measurements on the ground truth
# ----------------------------------------------------------------------------------------------------------
def cycle_stats(rig, brk, arr, t0, t1):
    B = [b for b in brk if t0 <= b["t"] <= t1]
    A = [a for a in arr if t0 <= a["t"] <= t1]
    drops, peaks, sticks = [], [], []
    for b in B:
        nxt = [a for a in A if a["t"] > b["t"]]
        if not nxt:
            continue
        drops.append(b["F"] - nxt[0]["F"])
        peaks.append(b["F"])
        sticks.append(b["t_stick"])
    tb = np.array([b["t"] for b in B])
    f_ss = (tb.size - 1) / float(tb[-1] - tb[0]) if tb.size > 2 else float("nan")
    dr = np.array(drops)
    n_micro = int(np.sum(dr < 0.1 * np.median(dr))) if dr.size else 0
    return dict(n_cycles=len(B), n_micro_slips=n_micro, drop=float(np.median(drops)) if drops else float("nan"),
                peaks=np.array(peaks), sticks=np.array(sticks), drops=np.array(drops), f_ss=f_ss,
                tb=tb)


def ageing_growth(peaks, sticks, drop):
    """Peak growth over the record's range of stick times, by regression on ln(t_stick), / drop."""
    if len(peaks) < 4:
        return float("nan"), 1.0
    ratio = float(sticks.max() / sticks.min())
    if ratio < 1.5:
        return float("nan"), ratio
    L = np.log(sticks)
    sl = np.polyfit(L, peaks, 1)[0]
    return float(sl * math.log(ratio) / drop), ratio


def twin_measure(rig, drive, nodes, brk, arr, t0, t1, drop, per_load=False):
    """Decelerating minus accelerating friction at equal true sliding speed (10-90 % of each slip's peak
    speed), median over slips, / drop (per_load: F/N * N0)."""
    out = []
    for b in brk:
        if not (t0 <= b["t"] <= t1):
            continue
        nxt = [a for a in arr if a["t"] > b["t"]]
        if not nxt:
            continue
        ta = nxt[0]["t"]
        tq = np.linspace(b["t"], ta, 500)
        F, v, N, e, x = friction_truth(rig, drive, nodes, tq)
        sg = np.sign(b["F"])
        u = sg * v
        Fs = sg * F
        if per_load:
            Fs = Fs / N * rig.N0
        j = int(np.argmax(u))
        vp = u[j]
        if j < 5 or j > len(u) - 6 or vp <= 0:
            continue
        ua, Fa = u[: j + 1], Fs[: j + 1]
        ud, Fd = u[j:][::-1], Fs[j:][::-1]
        grid = np.linspace(0.1, 0.9, 33) * vp
        oa = np.argsort(ua)
        od = np.argsort(ud)
        fa = np.interp(grid, ua[oa], Fa[oa])
        fd = np.interp(grid, ud[od], Fd[od])
        out.append(float(np.mean(fd - fa)))
    if not out:
        return float("nan")
    return float(np.median(out) / drop)


# ----------------------------------------------------------------------------------------------------------
# drawing the rig
# ----------------------------------------------------------------------------------------------------------
def _draw_rig(rng, case, seed):
    fn = math.exp(rng.uniform(math.log(4.0), math.log(30.0)))
    k = math.exp(rng.uniform(math.log(3e3), math.log(8e4)))
    m = k / (_TWOPI * fn) ** 2
    N0 = math.exp(rng.uniform(math.log(30.0), math.log(600.0)))
    mu_s = rng.uniform(0.12, 0.22)
    big = case == "load_variation" and seed % 2 == 0
    dstat = rng.uniform(0.08, 0.12) * mu_s if big else rng.uniform(0.05, 0.12) * mu_s
    A_t = None
    if case == "triggering":
        # a static excess of at least 2.4 A: the shaker's crest does not re-arrest a starting slip
        # (with less, every breakaway stutters through 2-5 micro-slips one shaker period apart)
        A_t = rng.uniform(0.03, 0.08)
        dstat = rng.uniform(max(0.05, 2.4 * A_t), max(0.12, 2.4 * A_t + 0.04)) * mu_s
    Dw = rng.uniform(0.25, 0.35) * mu_s if big else rng.uniform(0.15, 0.32) * mu_s
    mu0p = mu_s - dstat
    mu_m = mu0p - Dw
    v_sc = _TWOPI * fn * N0 * (dstat + 0.6 * Dw) / k
    P = dict(fn=fn, k=k, m=m, N0=N0, mu_s=mu_s, dstat=dstat, Dw=Dw, mu_m=mu_m, v_sc=v_sc,
             vs=rng.uniform(0.08, 0.35) * v_sc, w=rng.uniform(0.5, 1.2),
             mu_e=rng.uniform(0.05, 0.2) * Dw, v_e=rng.uniform(0.5, 2.0) * v_sc)
    if A_t is not None:
        P["A_t_drawn"] = A_t
    return P


def _pilot(P, v, n_slips=7, extra=None):
    Q = dict(P)
    if extra:
        Q.update(extra)
    rig = Rig(Q)
    Tn = 1.0 / P["fn"]
    drop_est = 2 * P["N0"] * (P["dstat"] + 0.6 * P["Dw"])
    t_end = (n_slips + 1) * (drop_est / (P["k"] * v) + Tn) * 1.5
    nodes, brk, arr = simulate(rig, Drive(v), t_end, max_slips=n_slips + 1)
    t0 = brk[1]["t"] if len(brk) > 2 else 0.0
    st = cycle_stats(rig, brk, arr, t0 - 1e-9, math.inf)
    slip_d = [a["t"] - b["t"] for b, a in zip(brk, arr)]
    st["T_slip"] = float(np.median(slip_d[1:])) if len(slip_d) > 1 else 0.6 * Tn
    return rig, nodes, brk, arr, st, t0


def _set_v0(P, q):
    """Drive speed for fn/f_ss ~ q (two short pilots)."""
    Tn = 1.0 / P["fn"]
    drop_est = 2 * P["N0"] * (P["dstat"] + 0.6 * P["Dw"])
    v = drop_est / (P["k"] * max(q - 0.6, 1.0) * Tn)
    for _ in range(2):
        _, _, _, _, st, _ = _pilot(P, v, 6)
        Tss = 1.0 / st["f_ss"]
        Tst = max(Tss - st["T_slip"], 0.05 * Tss)
        v = v * Tst / max(q * Tn - st["T_slip"], 0.5 * Tn)
    return v, st


# ----------------------------------------------------------------------------------------------------------
# the record
# ----------------------------------------------------------------------------------------------------------
def _shaped_noise(rng, n, fs, fc, sd):
    """White plus a component with a 1/sqrt(1 + (f/fc)^2) amplitude spectrum, total sd."""
    white = rng.standard_normal(n)
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, 1.0 / fs)
    spec *= 1.0 / np.sqrt(1.0 + (f / fc) ** 2)
    col = np.fft.irfft(spec, n)
    col /= col.std() + 1e-300
    frac = rng.uniform(0.3, 0.8)
    z = math.sqrt(1 - frac) * white + math.sqrt(frac) * col
    return sd * z / z.std()


def _fmt_num(a, dec_comma, digits=7):
    s = [f"{v:.{digits}g}" for v in a]
    if dec_comma:
        s = [z.replace(".", ",") for z in s]
    return s


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    t_start = time.time()
    rng = _rng(case, seed, 0)          # physics
    rfmt = _rng(case, seed, 77)        # record format (same for every nuisance)
    rnu = _rng(case, seed, 1000 + NUISANCES.index(nuisance))  # sensor noise and nuisance
    P = _draw_rig(rng, case, seed)
    fn = P["fn"]
    Tn = 1.0 / fn
    k = P["k"]
    N0 = P["N0"]
    s8 = seed % 8

    # drive schedule kind
    if case == "none":
        dkind = {2: "steps", 5: "holds"}.get(s8, "const")
    elif case == "static_ageing":
        dkind = "steps" if seed % 2 == 0 else "holds"
    elif case == "drive_modulation":
        dkind = "mod"
    else:
        dkind = "const"

    if dkind == "steps":
        q = rng.uniform(3.0, 5.5)
    elif case in ("triggering", "drive_modulation"):
        q = rng.uniform(4.0, 10.0)
    else:
        q = rng.uniform(5.0, 14.0)
    v0, st0 = _set_v0(P, q)
    D0 = st0["drop"]
    Tss0 = 1.0 / st0["f_ss"]
    Tst0 = max(Tss0 - st0["T_slip"], 0.2 * Tss0)
    params = dict(P)
    params.update(q_target=q, v0_m_s=v0, pilot_drop_N=D0, pilot_Tss_s=Tss0, drive_kind=dkind)

    # the scraped ways' texture of the static level (random bearing-spot pattern along the position)
    tex_sd = rng.uniform(0.02, 0.035) if case == "triggering" else rng.uniform(0.002, 0.006)
    nt = 8
    lam_t = np.exp(rng.uniform(np.log(0.05), np.log(0.5), nt)) * D0 / k
    c_t = rng.normal(0, 1, nt)
    c_t *= tex_sd * D0 / N0 / math.sqrt(0.5 * np.sum(c_t ** 2))
    P.update(tex_c=list(c_t), tex_q=list(_TWOPI / lam_t), tex_p=list(rng.uniform(0, _TWOPI, nt)))
    params.update(texture_sd_over_drop=tex_sd)

    # --------------------------------------------------------------- case set-up
    extra = {}
    n_cyc = int(rng.integers(20, 41))
    if case == "load_variation":
        P_pp = rng.uniform(0.12, 0.26)
        if seed % 2 == 0:
            sgn = 1.0 if rng.uniform() < 0.5 else -1.0
            F_ref = float(np.mean(st0["peaks"]) - 0.5 * D0)
            gamma = sgn * P_pp * N0 / D0
            gmax = 0.45 / P["mu_s"]
            gamma = float(np.clip(gamma, -gmax, gmax))
            extra = dict(load_mode="nut", gamma=gamma, F_ref=F_ref)
            for _ in range(2):  # the drop moves with gamma
                _, _, _, _, stp, _ = _pilot(P, v0, 6, extra)
                gamma = float(np.clip(sgn * P_pp * N0 / stp["drop"], -gmax, gmax))
                extra["gamma"] = gamma
                extra["F_ref"] = float(np.mean(stp["peaks"]) - 0.5 * stp["drop"])
        else:
            lam = rng.uniform(1.3, 3.0) * D0 / k
            extra = dict(load_mode="wave", A_w=P_pp / 2, lam=lam, ph_w=rng.uniform(0, _TWOPI))
        params.update(load_target_pp=P_pp)
    elif case == "twin_branch":
        tgt = rng.uniform(0.12, 0.20)
        _, nd, bk, ar, stp, t0p = _pilot(P, v0, 4)
        F, vv, _, _, _ = friction_truth(Rig(P), Drive(v0), nd, np.linspace(bk[1]["t"], ar[1]["t"], 200))
        vpk = float(np.max(np.abs(vv)))
        extra = dict(tau_h=rng.uniform(0.08, 0.2) * Tn, v_h=rng.uniform(0.3, 1.0) * vpk)
        G = 0.3 * tgt * D0 / N0
        for _ in range(3):
            extra["G"] = G
            rg, nd, bk, ar, stp, t0p = _pilot(P, v0, 6, extra)
            tw = twin_measure(rg, Drive(v0), nd, bk, ar, t0p, math.inf, stp["drop"])
            if not np.isfinite(tw) or tw == 0:
                break
            G = G * min(max(tgt / abs(tw), 0.3), 3.0)
        extra["G"] = G
        params.update(twin_target=tgt)
    elif case == "static_ageing":
        tgt = rng.uniform(0.10, 0.18)
        extra = dict(tau_a=rng.uniform(0.3, 1.0) * Tst0, p_age=rng.uniform(0.5, 0.9), b_age=0.0)
        params.update(ageing_target=tgt)
    elif case == "triggering":
        extra = dict(A_t=P["A_t_drawn"], ph_t=rng.uniform(0, _TWOPI))
    elif case == "drive_modulation":
        a_m = rng.uniform(0.2, 0.45)
        r_m = rng.uniform(0.1, 0.4)
        fm = r_m * st0["f_ss"]
        n_cyc = max(n_cyc, int(math.ceil(3.2 / r_m)) + 2)
        n_cyc = min(n_cyc, 55)
        params.update(mod_a=a_m, mod_fm_Hz=fm, mod_fm_over_fss_pilot=r_m)

    # --------------------------------------------------------------- drive schedule
    def make_drive(n_cycles):
        if dkind == "const":
            return Drive(v0), (n_cycles + 2.6) * Tss0, {}
        if dkind == "mod":
            return (Drive(v0, mod=(params["mod_a"], params["mod_fm_Hz"], phm)), (n_cycles + 2.6) * Tss0, {})
        if dkind == "steps":
            knots = [(0.0, v0)]
            t = 0.0
            lev = 0
            cyc = 0
            info = dict(step_ratio=r_steps)
            while cyc < n_cycles + 2.6:
                nlev = int(rngd.integers(3, 6))
                if lev == 0:
                    T_ss_l = sched["Tst"] + st0["T_slip"]
                    vl = v0
                else:
                    T_ss_l = sched["Tst"] * r_steps + st0["T_slip"]
                    vl = v0 / r_steps
                if t > 0:
                    knots.append((t, vl))
                if cyc == 0:
                    nlev += 2
                t += nlev * T_ss_l + 0.5 * sched["Tst"] * (r_steps if lev else 1)
                cyc += nlev
                lev = 1 - lev
            return Drive(v0, knots=knots), t, info
        if dkind == "holds":
            knots = [(0.0, v0)]
            Tss_h = sched["Tst"] + st0["T_slip"]
            t = 2.3 * Tss_h
            cyc = 2.3
            holds = []
            while cyc < n_cycles + 2.3:
                ncyc = rngd.uniform(2.5, 5.0)
                t += ncyc * Tss_h
                cyc += ncyc
                th = rngd.uniform(3.0, 9.0) * sched["Tst"]
                knots.append((t, 0.0))
                knots.append((t + th, v0))
                holds.append(th)
                t += th
                cyc += 1
            t += 1.5 * Tss_h
            return Drive(v0, knots=knots), t, dict(holds_s=holds)
        raise ValueError(dkind)

    sched = dict(Tst=Tst0)
    r_steps = rng.uniform(4.0, 8.0)
    phm = rng.uniform(0, _TWOPI)
    rngd_seed = int(rng.integers(0, 2 ** 31))

    def run(extra_, n_cycles):
        nonlocal rngd
        rngd = np.random.default_rng(rngd_seed)
        drv, t_end, dinfo = make_drive(n_cycles)
        Q = dict(P)
        Q.update(extra_)
        rg = Rig(Q)
        nodes, brk, arr = simulate(rg, drv, t_end)
        return rg, drv, t_end, dinfo, nodes, brk, arr

    rngd = None
    if case == "triggering":
        # the breakaways lock 1:n to the shaker's troughs; the ways' texture (2-3.5 % of the drop) mixes the
        # locks; f_t redrawn (up to 10 runs) while the record's f_t/f_ss is within 0.15 of an integer
        best = None
        n_tries = 0
        for attempt in range(10):
            ft = rng.uniform(2.5, 7.0) * fn
            extra["f_t"] = ft
            rg_, drv_, te_, _, nd_, bk_, ar_ = run(extra, n_cyc)
            t0_ = ar_[1]["t"] + 0.3 * (bk_[2]["t"] - ar_[1]["t"])
            st_ = cycle_stats(rg_, bk_, ar_, max(t0_, 3.0 * Tn + 1e-9), te_ - 3.0 * Tn)  # the record's window
            rr = ft / st_["f_ss"]
            n_tries += 1
            if os.environ.get("SW_DEBUG"):
                print("  trig", ft / fn, rr, file=sys.stderr)
            dd = abs(rr - round(rr))
            if best is None or dd > best[0]:
                best = (dd, ft)
            if dd >= 0.15:
                break
        extra["f_t"] = best[1]
        params.update(trigger_search_runs=n_tries)
    if case == "static_ageing":
        # calibrate b: one shortened run with a trial b, rescale
        b_try = 0.1 * P["mu_s"]
        for _ in range(2):
            extra["b_age"] = b_try
            rg, drv, t_end, dinfo, nodes, brk, arr = run(extra, 14)
            stp = cycle_stats(rg, brk, arr, brk[2]["t"] - 1e-9, math.inf)
            gr, _ = ageing_growth(stp["peaks"], stp["sticks"], stp["drop"])
            if not np.isfinite(gr) or gr <= 0:
                break
            b_try = b_try * min(max(params["ageing_target"] / gr, 0.3), 3.0)
            sched["Tst"] = Tst0 * stp["drop"] / D0
        extra["b_age"] = b_try

    rg, drv, t_end, dinfo, nodes, brk, arr = run(extra, n_cyc)
    params.update(nodes["stats"])
    params.update({kk: (float(vv) if isinstance(vv, (float, np.floating)) else vv) for kk, vv in extra.items()})
    params.update(dinfo)

    # --------------------------------------------------------------- the record's window
    fmt_spp = int(rfmt.integers(20, 101))
    if nuisance == "coarse":
        spp = int(rnu.integers(10, 16)) if case != "triggering" else int(rnu.integers(14, 16))
    else:
        spp = fmt_spp
        if nuisance == "hum":
            spp = min(100, max(spp, int(math.ceil(260.0 / fn))))
    fs = spp * fn
    R = 8 if spp <= 40 else 4
    pad = 3.0 * Tn  # >= 30 samples: the FIR settles; the same window for every nuisance
    t_rec0 = arr[1]["t"] + 0.3 * (brk[2]["t"] - arr[1]["t"]) if len(arr) > 2 else 0.0
    t_rec0 = max(t_rec0, pad + 1e-9)
    t_rec1 = t_end - pad
    n_out = int((t_rec1 - t_rec0) * fs)
    if n_out * 1.0 > 250000:
        fs = 250000 / (t_rec1 - t_rec0)
        spp = fs / fn
        n_out = 250000
    fs_f = R * fs
    n_f = n_out * R + 2 * int(pad * fs_f) + 1
    tf = t_rec0 - int(pad * fs_f) / fs_f + np.arange(n_f) / fs_f
    xf, _ = hermite(nodes, tf)
    ef = drv.pos(tf) - xf
    Nf = rg.N_vec(tf, xf, ef)
    numtaps = 24 * R + 1
    taps = signal.firwin(numtaps, 0.9 / R, window=("kaiser", 9.0))
    off = int(pad * fs_f)
    sel = off + R * np.arange(n_out)
    e_out = np.convolve(ef, taps, mode="same")[sel]
    N_out = np.convolve(Nf, taps, mode="same")[sel]
    t_out = tf[sel]
    e_true_s = ef[sel]

    # --------------------------------------------------------------- ground-truth measurements
    stc = cycle_stats(rg, brk, arr, t_rec0, t_rec1)
    drop = stc["drop"]
    gr, sratio = ageing_growth(stc["peaks"], stc["sticks"], drop)
    tw = twin_measure(rg, drv, nodes, brk, arr, t_rec0, t_rec1, drop)
    tw_mu = twin_measure(rg, drv, nodes, brk, arr, t_rec0, t_rec1, drop, per_load=True)
    Fgrid = np.linspace(t_rec0, t_rec1, 20000)  # the normal load over the record
    _, _, Ng, _, _ = friction_truth(rg, drv, nodes, Fgrid)
    N_pp = float((Ng.max() - Ng.min()) / N0)
    meas = dict(n_cycles=stc["n_cycles"], n_micro_slips=stc["n_micro_slips"], drop_N=drop, f_ss_Hz=stc["f_ss"], fn_over_fss=fn / stc["f_ss"],
                twin_true=tw, twin_true_per_load=tw_mu, peak_growth_true=gr, stick_time_ratio=sratio,
                peak_sd_over_drop=float(np.std(stc["peaks"]) / drop), N_pp_over_N0=N_pp,
                N_pp_friction_over_drop=float(N_pp * N0 * P["mu_s"] / drop),
                samples_per_period=float(spp), fs_Hz=float(fs), n_samples=int(n_out),
                duration_s=float(t_rec1 - t_rec0))
    if case == "triggering":
        rr = rg.f_t / stc["f_ss"]
        meas.update(f_t_over_fn=rg.f_t / fn, f_t_over_fss=rr, f_t_dist_from_integer=abs(rr - round(rr)),
                    shaker_amp_over_N0=rg.A_t,
                    early_trigger_over_drop=float((P["mu_s"] * N0 - np.mean(stc["peaks"])) / drop))
    if case == "drive_modulation":
        meas.update(mod_fm_over_fss=params["mod_fm_Hz"] / stc["f_ss"])
    if case == "static_ageing" or dkind in ("steps", "holds"):
        meas.update(stick_min_s=float(stc["sticks"].min()), stick_max_s=float(stc["sticks"].max()))
    # what a 1-DoF reading of the clean sampled record sees (x from the clean samples, central differences)
    def twin_1dof(e_s):
        xr = drv.pos(t_out) - e_s
        vr = np.gradient(xr, t_out)
        ar_ = np.gradient(vr, t_out)
        F1 = k * e_s - P["m"] * ar_
        res = []
        for b in brk:
            if not (t_rec0 + 2 / fs <= b["t"] <= t_rec1 - 2 / fs):
                continue
            nxt = [a for a in arr if a["t"] > b["t"]]
            if not nxt or nxt[0]["t"] > t_rec1 - 2 / fs:
                continue
            msk = (t_out >= b["t"] - 0.5 / fs) & (t_out <= nxt[0]["t"] + 0.5 / fs)
            u, Fq = np.sign(b["F"]) * vr[msk], np.sign(b["F"]) * F1[msk]
            if u.size < 6:
                continue
            j = int(np.argmax(u))
            vp = u[j]
            if j < 2 or j > u.size - 3:
                continue
            grid = np.linspace(0.1, 0.9, 33) * vp
            oa = np.argsort(u[: j + 1])
            od = np.argsort(u[j:])
            fa = np.interp(grid, u[: j + 1][oa], Fq[: j + 1][oa])
            fd = np.interp(grid, u[j:][od], Fq[j:][od])
            res.append(float(np.mean(fd - fa)))
        return float(np.median(res) / drop) if res else float("nan")

    meas["twin_1dof_clean_record"] = twin_1dof(e_out)
    meas["twin_1dof_ideal_samples"] = twin_1dof(e_true_s)
    # the FIR filter's ringing at the breakaways (recorded clean peak minus true peak)
    pk_rec = []
    for b in brk:
        if t_rec0 + 5 / fs < b["t"] < t_rec1 - 5 / fs:
            msk = np.abs(t_out - b["t"]) < 0.3 * Tn
            pk_rec.append(float(np.max(k * e_out[msk]) - b["F"]))
    meas["fir_peak_overshoot_over_drop"] = float(np.median(pk_rec) / drop) if pk_rec else float("nan")
    if dkind in ("steps", "holds"):
        # peak growth read from the clean sampled record
        pks = []
        sts = []
        for b in brk:
            if t_rec0 + 5 / fs < b["t"] < t_rec1 - 5 / fs:
                msk = np.abs(t_out - b["t"]) < 0.3 * Tn
                pks.append(float(np.max(k * e_out[msk])))
                sts.append(b["t_stick"])
        grr, _ = ageing_growth(np.array(pks), np.array(sts), drop)
        meas["peak_growth_clean_record"] = grr
    meas["filter_error_sd_over_drop"] = float(np.std(k * (e_out - e_true_s)) / drop)

    # --------------------------------------------------------------- sensor, channels, nuisance
    chan = "force" if rfmt.uniform() < 0.6 else "ext"
    if case == "drive_modulation":
        dcol = "speed" if rfmt.uniform() < 0.4 else None
    elif dkind in ("steps", "holds"):
        dcol = "pos" if rfmt.uniform() < 0.6 else "speed"
    else:
        u_ = rfmt.uniform()
        dcol = "pos" if u_ < 0.35 else ("speed" if u_ < 0.6 else None)
    if case == "load_variation":
        ncol = s8 in (0, 3, 4, 7)
    elif case == "triggering":
        ncol = s8 % 2 == 0
    else:
        ncol = s8 in (1, 6)
    fmt = int(rfmt.integers(0, 4))
    f_unit = "mN" if rfmt.uniform() < 0.35 else "N"
    e_unit = "um" if rfmt.uniform() < 0.5 else "mm"
    p_unit = "um" if rfmt.uniform() < 0.5 else "mm"
    t_unit = "ms" if rfmt.uniform() < 0.3 else "s"
    t_offset = float(rfmt.uniform(0, 30.0)) if rfmt.uniform() < 0.3 else 0.0

    noise_frac = rnu.uniform(0.002, 0.01)
    main = k * e_out  # in N (force equivalent)
    main = main + _shaped_noise(rnu, n_out, fs, rnu.uniform(0.3, 3.0) * fn, noise_frac * drop)
    nz = dict(noise_sd_over_drop=noise_frac)
    if nuisance == "hum":
        fh = 50.0 if rnu.uniform() < 0.5 else 60.0
        amp = rnu.uniform(0.01, 0.05) * drop
        hum = np.zeros(n_out)
        rel = [1.0, rnu.uniform(0.2, 0.5), rnu.uniform(0.15, 0.4)]
        for hN, r_ in enumerate(rel, start=1):
            if hN * fh < 0.45 * fs:
                hum += r_ * np.sin(_TWOPI * hN * fh * t_out + rnu.uniform(0, _TWOPI))
        hum *= amp / (np.max(np.abs(hum)) + 1e-300)
        main = main + hum
        nz.update(hum_Hz=fh, hum_amp_over_drop=amp / drop)
    elif nuisance == "drift":
        A = rnu.uniform(0.015, 0.03) * drop
        s = (t_out - t_out[0]) / (t_out[-1] - t_out[0])
        d = rnu.uniform(0.5, 1.0) * s * (1 if rnu.uniform() < 0.5 else -1)
        d = d + rnu.uniform(-0.4, 0.4) * np.sin(math.pi * s * rnu.uniform(0.5, 2.0) + rnu.uniform(0, 6.3))
        d -= d[0]
        d *= A / (np.max(np.abs(d)) + 1e-300)
        main = main + d
        nz.update(drift_max_over_drop=A / drop)
    elif nuisance == "spikes":
        frac = rnu.uniform(0.0005, 0.005)
        nsp = max(3, int(round(frac * n_out)))
        idx = rnu.choice(n_out, nsp, replace=False)
        main = main.copy()
        main[idx] = main[idx] + rnu.choice([-1.0, 1.0], nsp) * rnu.uniform(0.05, 0.3, nsp) * drop
        nz.update(spike_fraction=nsp / n_out, n_spikes=int(nsp))
    elif nuisance == "quantisation":
        qf = rnu.uniform(0.002, 0.01)
        main = np.round(main / (qf * drop)) * (qf * drop)
        nz.update(adc_step_over_drop=qf)
    N_rec = N_out + rnu.normal(0, rnu.uniform(0.001, 0.003) * N0, n_out)

    # units
    if chan == "force":
        scale = 1e3 if f_unit == "mN" else 1.0
        main_vals = main * scale
    else:
        scale = 1e6 if e_unit == "um" else 1e3
        main_vals = main / k * scale
    tt = t_out - t_out[0] + t_offset
    t_vals = tt * (1e3 if t_unit == "ms" else 1.0)
    cols = []
    names = []
    names_time = {"s": ["Time [s]", "t (s)", "time_s", "Time (s)"], "ms": ["Time [ms]", "t (ms)", "time_ms",
                                                                          "Time (ms)"]}[t_unit]
    names.append(names_time[fmt])
    cols.append(t_vals)
    if chan == "force":
        nm = {"N": ["Friction force (N)", "F_friction [N]", "feed_force_N", "Friction force [N]"],
              "mN": ["Friction force (mN)", "F_friction [mN]", "feed_force_mN", "Friction force [mN]"]}[f_unit]
    else:
        nm = {"mm": ["Spring extension [mm]", "x [mm]", "spring_extension_mm", "Spring extension (mm)"],
              "um": ["Spring extension [um]", "x [um]", "spring_extension_um", "Spring extension (um)"]}[e_unit]
    names.append(nm[fmt])
    cols.append(main_vals)
    if ncol:
        names.append(["Normal load [N]", "normal_load_N", "Normal force (N)", "Normal load (N)"][fmt])
        cols.append(N_rec)
    if dcol == "pos":
        pos = np.round(drv.pos(t_out) * 1e7) / 1e7  # 0.1 um encoder counts
        pos = pos - pos[0] + (rfmt.uniform(0, 50e-3) if rfmt.uniform() < 0.5 else 0.0)
        ps = 1e6 if p_unit == "um" else 1e3
        names.append({"um": ["stage_pos[um]", "Stage position [um]", "nut_position_um", "Stage position (um)"],
                      "mm": ["stage_pos[mm]", "Stage position [mm]", "nut_position_mm",
                             "Stage position (mm)"]}[p_unit][fmt])
        cols.append(pos * ps)
    elif dcol == "speed":
        if dkind == "mod":
            vcol = np.full(n_out, v0)
        else:
            # the commanded feed of each sample interval
            vcol = np.asarray(drv.vel(t_out), float)
        names.append(["Feed speed [mm/s]", "v_drive [mm/s]", "feed_speed_mm_s", "Drive speed (mm/s)"][fmt])
        cols.append(vcol * 1e3)

    os.makedirs(outdir, exist_ok=True)
    ext = [".csv", ".csv", ".txt", ".dat"][fmt]
    fname = os.path.join(os.path.abspath(outdir), f"{NAME}_{case}_s{seed}_{nuisance}{ext}")
    if fmt == 0:
        sep, dec_comma = ",", False
        head = [f"# {NAME}: machine-tool slideway stick-slip test, ball-screw feed",
                f"# sample rate {fs:.6g} Hz"]
    elif fmt == 1:
        sep, dec_comma = ";", True
        head = ["Machine;VMC slideway test rig", "Operator;lab", f"Rate [Hz];{fs:.6g}".replace(".", ","), ""]
    elif fmt == 2:
        sep, dec_comma = "\t", False
        head = []
    else:
        sep, dec_comma = " ", False
        head = [f"# slideway rig, ball-screw feed; {n_out} samples"]
    t_digits = 10
    lines = list(head)
    if fmt == 3:
        # whitespace table: names without blanks, a row of units under them
        import re
        nn, uu = [], []
        for nm_ in names:
            mt = re.match(r"^(.*?)\s*[\(\[](.*)[\)\]]$", nm_)
            nn.append(mt.group(1).replace(" ", "_"))
            uu.append(mt.group(2))
        lines.append(sep.join(nn))
        lines.append(sep.join(uu))
    else:
        lines.append(sep.join(names))
    str_cols = [_fmt_num(cols[0], dec_comma, t_digits)] + [_fmt_num(c, dec_comma, 7) for c in cols[1:]]
    for row in zip(*str_cols):
        lines.append(sep.join(row))
    with open(fname, "w") as fh:
        fh.write("\n".join(lines) + "\n")

    # --------------------------------------------------------------- the args
    args = []
    fn_given = None
    omit_fn = (s8 == 3) and case != "triggering" and nuisance != "fn_off"
    if not omit_fn:
        fn_given = fn
        if nuisance == "fn_off":
            fn_given = fn * (1.05 if rnu.uniform() < 0.5 else 0.95)
        args += ["--fn", f"{fn_given:.6g}"]
    if chan == "force":
        args += ["--stiffness", f"{k:.6g}"]
    if dcol is None:
        args += ["--v0", f"{v0 * 1e3:.6g}"]
    params.update(meas)
    params.update(nz)
    params.update(channel=chan, drive_column=dcol, normal_column=bool(ncol), fmt=fmt,
                  record_spp=float(spp), elapsed_s=time.time() - t_start)
    params = _jsonable(params)
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=fname, args=args,
                fn_true=float(fn), fn_given=(float(fn_given) if fn_given is not None else None),
                params=params)


def _jsonable(d):
    out = {}
    for kk, vv in d.items():
        if isinstance(vv, (np.floating, float)):
            vv = float(vv)
            out[kk] = vv if math.isfinite(vv) else None
        elif isinstance(vv, (np.integer,)):
            out[kk] = int(vv)
        elif isinstance(vv, (list, tuple, np.ndarray)):
            out[kk] = [float(z) for z in np.asarray(vv, float).ravel()]
        else:
            out[kk] = vv
    return out


if __name__ == "__main__":
    import tempfile

    out = tempfile.mkdtemp(prefix="slideway_")
    t_all = time.time()
    rows = []
    fmt = "{:17s} {:2d} {:13s} fn={:6.2f} cyc={:3d} spp={:6.1f} fn/fss={:6.1f} {:40s} {:5.1f}s"
    for case in CASES:
        for seed in range(8):
            nu = NUISANCES[seed % 7]
            t0 = time.time()
            r = write_record(case, seed, out, nu)
            p = r["params"]
            if case == "none":
                eff = "twin %+.4f grow %s 1dof %+.3f" % (
                    p["twin_true"], "%+.4f" % p["peak_growth_true"] if p["peak_growth_true"] is not None
                    else "  -  ", p["twin_1dof_clean_record"] or 0)
            elif case == "load_variation":
                eff = "N p-p %.3f (fric %.2f drop)" % (p["N_pp_over_N0"], p["N_pp_friction_over_drop"])
            elif case == "twin_branch":
                eff = "twin %+.3f" % p["twin_true"]
            elif case == "static_ageing":
                eff = "growth %+.3f over %.1fx" % (p["peak_growth_true"], p["stick_time_ratio"])
            elif case == "triggering":
                eff = "A %.3f ft/fn %.2f ft/fss %.2f" % (p["shaker_amp_over_N0"], p["f_t_over_fn"],
                                                        p["f_t_over_fss"])
            else:
                eff = "a %.2f fm/fss %.2f" % (p["mod_a"], p["mod_fm_over_fss"])
            print(fmt.format(case, seed, nu, r["fn_true"], p["n_cycles"], p["samples_per_period"],
                             p["fn_over_fss"], eff, time.time() - t0), flush=True)
            rows.append(r)
    with open(os.path.join(out, "truth.json"), "w") as fh:
        json.dump(rows, fh, indent=1)

    def rng_of(case, key, only=None):
        v = [r["params"].get(key) for r in rows if r["case"] == case and (only is None or only(r))]
        v = [z for z in v if z is not None]
        return "%+.4f..%+.4f" % (min(v), max(v)) if v else "-"

    print("summary over seeds 0-7 (ground truth; sizes / drop unless said):")
    for case in CASES:
        print("  %-17s twin %s  twin F/N %s  peak growth %s  stick ratio %s  N p-p/N0 %s  peak sd %s"
              % (case, rng_of(case, "twin_true"), rng_of(case, "twin_true_per_load"),
                 rng_of(case, "peak_growth_true"), rng_of(case, "stick_time_ratio"),
                 rng_of(case, "N_pp_over_N0"), rng_of(case, "peak_sd_over_drop")))
    print("  none: 1-DoF reading of the clean samples (central differences) twin %s; FIR peak overshoot %s;"
          " peak growth read on the clean record (stepped/holds) %s"
          % (rng_of("none", "twin_1dof_clean_record"), rng_of("none", "fir_peak_overshoot_over_drop"),
             rng_of("none", "peak_growth_clean_record")))
    print("  triggering: A %s, f_t/fn %s, f_t/f_ss %s (distance from an integer %s), early trigger %s"
          % (rng_of("triggering", "shaker_amp_over_N0"), rng_of("triggering", "f_t_over_fn"),
             rng_of("triggering", "f_t_over_fss"), rng_of("triggering", "f_t_dist_from_integer"),
             rng_of("triggering", "early_trigger_over_drop")))
    print("  drive_modulation: a %s, fm/f_ss %s" % (rng_of("drive_modulation", "mod_a"),
                                                    rng_of("drive_modulation", "mod_fm_over_fss")))
    print("  cycles %d-%d, samples/period %.0f-%.0f, slowest record %.1f s"
          % (min(r["params"]["n_cycles"] for r in rows), max(r["params"]["n_cycles"] for r in rows),
             min(r["params"]["samples_per_period"] for r in rows),
             max(r["params"]["samples_per_period"] for r in rows),
             max(r["params"]["elapsed_s"] for r in rows)))
    print("all %d records in %s, %.1f s" % (len(rows), out, time.time() - t_all))
