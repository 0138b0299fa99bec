"""Capstan (rope-on-drum) stick-slip rig with a pneumatic tail tensioner.

Rig
---
A braided polyester rope is wrapped over a steel drum by a wrap angle theta (135-225 deg).  The drum is
driven by a geared motor at a surface speed v0 (the drive "belt").  The rope's tight end runs to a carriage
of mass m on a linear guide (viscous guide damping c), which is held by a coil spring k through an S-beam
load cell ("spring tension", F = k x with x the spring extension).  The rope's slack end is held by a
pneumatic constant-tension cylinder (a pressure regulator keeps the tail tension T0) through a second load
cell ("tail tension", the rig's normal-load channel).  The drum drags the rope towards the tail, stretching
the spring until the capstan (Euler-Eytelwein) limit is reached:

    m x'' + c x' + k x = T_s,    T_s = T_w exp(sign(s) theta mu(|s|, ...)),    s = v0(t) - x'   (sliding speed)

so the recorded force is N * g(v) with N = T_w and g = exp(theta mu) >= 1: the thesis's 1-DoF model with a
(very non-linear) single-valued characteristic whose static level is exp(theta mu_s).

Friction law (rope coefficient, own form, s in mm/s)
    mu(s) = mu_k + (mu_s - mu_k) / (1 + (s / v_c)**p) + eta s            (rational weakening, p 1.3-2)
  + twin_branch:   + beta_tw (1 - exp(-d / L_tw))    d = distance slid since breakaway (fibre bedding /
                   transfer film build-up within a slip; reset in stick) -> higher on the decelerating half.
  + static_ageing: + beta_a ln(1 + t_stick / tau_a) exp(-d / L_a)  (junction growth in stick, erased within
                   a memory distance L_a of 0.05-0.15 mm after breakaway).

Stick handling: exact switching (Filippov).  Stick phases are closed form (x = x_s + D(t) - D(t_s), with D
the drum surface position); the breakaway time is bracketed on a vectorised grid (finer than the trigger
period) and refined with Brent's method on m D'' + k x + c D' = T_w exp(theta mu_static(t_stick)).
Slip: fixed-step classical RK4 (step T_n/300) on (x, x', d); the re-stick instant (s crossing zero) is located
by secant iteration on the RK4 step length; stick is entered only if the required tension lies inside the
capstan cone [T_w e^-theta mu_s, T_w e^theta mu_s], else the slip continues (back-slip allowed).
Dense output: the stick phases closed form, slips by cubic Hermite between RK4 nodes, on a grid >= 2 kHz.

Sensor chain: both load cells through a strain-gauge amplifier (2-pole Butterworth, 300-500 Hz bandwidth,
no further anti-alias filter), white amplifier noise (0.15-0.35 % of the force drop on F) plus a slow
first-order (2 Hz) noise component (0.1 %), 16-bit ADC on a +-100 N range (0.003 N), point-sampled at
400/500/1000 Hz; drum encoder 16384 counts/rev on a 50 mm drum (0.0096 mm) for the position channel.

Record: export of the rig's logger ("CapstanLab 2.3"): '#' metadata lines, then a semicolon-delimited table
with a decimal comma:
    Time [s];Spring tension [N];Tail tension [N][;Drum position [mm]]
The drum position column is logged only in `static_ageing` (the programmed speed steps); other cases give
--v0 (mm/s).  Every record gives --stiffness (N/m, the spring's calibration) and --fn (tap test, Hz).

Process noise (all cases): floor/frame vibration acting on the carriage, band 5-60 Hz, RMS 0.2-0.5 % of the
nominal drop (it jitters breakaway, so cycles are not exactly periodic).

Cases (effect sizes measured on this generator's ground truth, seeds 0-7, `params["measured"]`;
"drop" = the slip's spring-force drop k (x_break - x_restick), median over slips; a cycle is a slip whose drop
exceeds a quarter of T0 (e^theta mu_s - e^theta mu_k): smaller ones are counted as micro-slips)
- none: constant T0 (regulated pneumatic tail), constant v0, the stateless law.  Memory: none by construction
  (exact switching, single-valued law); measured double-valuedness of the friction tension on the slips
  (decelerating minus accelerating half at equal s, 0.2-0.8 of the slip's peak speed): |.| <= 2.5e-5 of
  the drop; load pp 0 (exact); no ageing term; peak-force scatter between cycles 0.6-1.7 % of the drop
  (floor vibration only); 0-2 vibration micro-slips per record.  24-39 cycles.
- load_variation: the regulated tail is replaced by an elastic tail cord that slackens as the rope is drawn
  towards it: T_w = T0 (1 - c_lv (x - x_m)) (mu_k/mu_s 0.60-0.70 keeps the drop clear); tail-tension
  peak-to-peak 11.5-24 % of T0 (calibrated to a 12-26 % target), recorded in the normal column.
- twin_branch: distance-hardening term; measured decelerating-minus-accelerating friction tension at equal
  sliding speed (0.2-0.8 of the slip's peak speed) 16-23 % of the slip's force drop (calibrated to 12-22 %
  without vibration; the floor vibration adds a little).
- static_ageing: drum speed cycles through lo, hi, mid levels (hi/lo 4.5-7.5) every 4-6 cycles (0.15 s
  raised-cosine ramps, drum position column recorded); stick times 0.13-1.1 s up to 1.1-10 s; peak spring
  tension grows 9.6-15.8 % of the peak at the shortest stick times (15-35 % of the drop) from the shortest to
  the longest stick times.  The ageing excess is erased within L_a, which makes the accelerating half slightly
  higher: twin measure -0.6 to -5.7 % of the drop.
- triggering: an electrodynamic shaker in the tail line: T_w = T0 (1 + A sin(2 pi f_tr t + psi)), A 3.6-6.9 %,
  f_tr 3.9-6.5 fn.  The shaker entrains the cycle (breakaway pinned to a capacity trough; 6-122 micro-slips
  in stick), so f_tr/f_ss tends to an integer: candidates are tried until the record's f_tr/f_ss is far from
  an integer; measured f_tr/f_ss 18-93 with a distance to the nearest integer 0.19-0.38 (two seeds < 0.25).
- drive_modulation: motor speed v0(t) = v0n (1 + a sin(2 pi fm t + phi)), a 0.26-0.39, fm 0.16-0.37 of
  the record's stick-slip frequency; only v0n is given (--v0).

Nuisances: clean; hum (50 or 60 Hz + 2nd/3rd harmonics, peak 1-5 % of the drop, on both force channels);
drift (bridge warm-up, 1-exp(-t/tau) plus linear, 2-5 % of the drop over the record, on F; a quarter of it on
N); spikes (single-sample outliers, 0.05-0.5 % of samples, 15-60 % of the drop, on F); quantisation (ADC step
0.2-1 % of the drop on both force channels); coarse (10-15 samples per natural period, same amplifier);
fn_off (--fn given off by exactly +-5 %).

Known limits of `none`: no inherent memory or ageing (stateless law, twin measure <= 2.5e-5 of the drop, no
stick-time dependence); the load is exactly constant (pneumatic regulator idealised, only sensor noise in the
tail channel); the floor vibration gives 0.6-1.7 % peak-force scatter and rare micro-slips (0-2 per record);
the first stick starts from rest at a preset extension, so the first cycle is a transient.  The effective
characteristic is exp(theta mu(s)): F/N never falls below 1 (the tail tension is part of the recorded force).
"""
import json
import math
import os

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq
from scipy.signal import butter, lfilter, lfilter_zi

NAME = "capstan_rope_drum"
CASES = ["none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation"]
NUISANCES = ["clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off"]


# --------------------------------------------------------------------------------------------- drive
class Drive:
    """Drum surface position D(t) [m], speed V(t), acceleration A(t): raised-cosine steps + modulation."""

    def __init__(self, v_init, mod_a=0.0, mod_f=0.0, mod_phi=0.0):
        self.v_init = v_init
        self.steps = []  # (t_j, dv_j, R_j)
        self.a, self.f, self.phi = mod_a, mod_f, mod_phi

    def add_step(self, t_j, dv, R):
        self.steps.append((t_j, dv, R))

    def D(self, t):
        t = np.asarray(t, float)
        out = self.v_init * t
        if self.a:
            w = 2 * np.pi * self.f
            out = out - self.v_init * self.a / w * (np.cos(w * t + self.phi) - np.cos(self.phi))
        for tj, dv, R in self.steps:
            tau = t - tj
            g = np.where(tau <= 0, 0.0,
                         np.where(tau >= R, tau - R / 2, tau / 2 - R * np.sin(np.pi * np.clip(tau, 0, R) / R) / (2 * np.pi)))
            out = out + dv * g
        return out

    def V(self, t):
        t = np.asarray(t, float)
        out = self.v_init * np.ones_like(t)
        if self.a:
            out = out * (1 + self.a * np.sin(2 * np.pi * self.f * t + self.phi))
        for tj, dv, R in self.steps:
            tau = np.clip(t - tj, 0, R)
            out = out + dv * 0.5 * (1 - np.cos(np.pi * tau / R))
        return out

    def A(self, t):
        t = np.asarray(t, float)
        out = np.zeros_like(t)
        if self.a:
            w = 2 * np.pi * self.f
            out = out + self.v_init * self.a * w * np.cos(w * t + self.phi)
        for tj, dv, R in self.steps:
            tau = t - tj
            inside = (tau > 0) & (tau < R)
            out = out + np.where(inside, dv * np.pi / (2 * R) * np.sin(np.pi * np.clip(tau, 0, R) / R), 0.0)
        return out

    # scalar fast paths for the RK4 loop
    def Vs(self, t):
        v = self.v_init
        if self.a:
            v *= 1 + self.a * math.sin(2 * math.pi * self.f * t + self.phi)
        for tj, dv, R in self.steps:
            tau = t - tj
            if tau >= R:
                v += dv
            elif tau > 0:
                v += dv * 0.5 * (1 - math.cos(math.pi * tau / R))
        return v


# --------------------------------------------------------------------------------------------- model
class Rig:
    def __init__(self, P, drive):
        self.P = P
        self.drive = drive
        self.m, self.k, self.c = P["m"], P["k"], P["c"]
        self.theta = P["theta"]
        self.T0 = P["T0"]
        self.c_lv, self.x_m = P.get("c_lv", 0.0), P.get("x_m", 0.0)
        self.A_tr, self.f_tr, self.psi = P.get("A_tr", 0.0), P.get("f_tr", 0.0), P.get("psi", 0.0)
        self.mu_s, self.mu_k, self.v_c, self.p, self.eta = P["mu_s"], P["mu_k"], P["v_c"], P["p"], P["eta"]
        self.beta_tw, self.L_tw = P.get("beta_tw", 0.0), P.get("L_tw", 1.0)
        self.beta_a, self.tau_a, self.L_a = P.get("beta_a", 0.0), P.get("tau_a", 1.0), P.get("L_a", 1.0)
        # floor/frame vibration acting on the carriage (process noise), 1 kHz table, linear interpolation
        self.vib = P.get("_vib")
        self.vib_dt = 1e-3

    def Fv(self, t):
        if self.vib is None:
            return 0.0 * np.asarray(t)
        u = np.clip(np.asarray(t, float) / self.vib_dt, 0, self.vib.size - 1.000001)
        i = u.astype(np.int64)
        f = u - i
        return self.vib[i] * (1 - f) + self.vib[i + 1] * f

    def Fvs(self, t):
        if self.vib is None:
            return 0.0
        u = t / self.vib_dt
        i = int(u)
        if i >= self.vib.size - 1:
            return float(self.vib[-1])
        f = u - i
        return float(self.vib[i] * (1 - f) + self.vib[i + 1] * f)

    # tail tension (normal load)
    def Tw(self, t, x):
        T = self.T0 * (1 - self.c_lv * (x - self.x_m))
        if self.A_tr:
            T = T * (1 + self.A_tr * np.sin(2 * np.pi * self.f_tr * t + self.psi))
        return T

    def Tws(self, t, x):
        T = self.T0 * (1 - self.c_lv * (x - self.x_m))
        if self.A_tr:
            T *= 1 + self.A_tr * math.sin(2 * math.pi * self.f_tr * t + self.psi)
        return T

    def mu_ss(self, s_mm):
        """single-valued steady law, s in mm/s (>= 0)"""
        return self.mu_k + (self.mu_s - self.mu_k) / (1 + (s_mm / self.v_c) ** self.p) + self.eta * s_mm

    def mu(self, s_abs, d, age_ex):
        s_mm = s_abs * 1e3
        mu = self.mu_k + (self.mu_s - self.mu_k) / (1 + (s_mm / self.v_c) ** self.p) + self.eta * s_mm
        if self.beta_tw:
            mu += self.beta_tw * (1 - math.exp(-d / self.L_tw))
        if age_ex:
            mu += age_ex * math.exp(-d / self.L_a)
        return mu

    def age(self, t_st):
        return self.beta_a * math.log1p(t_st / self.tau_a) if self.beta_a else 0.0

    def rhs(self, t, x, v, d, age_ex, sg):
        """slip dynamics on the friction branch sg (frozen over an RK4 step: smooth continuation past
        the re-stick event, which is then located on the continued branch)"""
        s = self.drive.Vs(t) - v
        Ts = self.Tws(t, x) * math.exp(sg * self.theta * self.mu(abs(s), d, age_ex))
        return (Ts - self.k * x - self.c * v + self.Fvs(t)) / self.m, s, Ts

    def rk4(self, t, x, v, d, h, age_ex, sg):
        a1, s1, _ = self.rhs(t, x, v, d, age_ex, sg)
        x2, v2, d2 = x + 0.5 * h * v, v + 0.5 * h * a1, d + 0.5 * h * sg * s1
        a2, s2, _ = self.rhs(t + 0.5 * h, x2, v2, d2, age_ex, sg)
        x3, v3, d3 = x + 0.5 * h * v2, v + 0.5 * h * a2, d + 0.5 * h * sg * s2
        a3, s3, _ = self.rhs(t + 0.5 * h, x3, v3, d3, age_ex, sg)
        x4, v4, d4 = x + h * v3, v + h * a3, d + h * sg * s3
        a4, s4, _ = self.rhs(t + h, x4, v4, d4, age_ex, sg)
        xn = x + h / 6 * (v + 2 * v2 + 2 * v3 + v4)
        vn = v + h / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
        dn = d + h / 6 * sg * (s1 + 2 * s2 + 2 * s3 + s4)
        return xn, vn, dn

    # ---- stick
    def stick_g(self, t, t_s, x_s, sign=+1):
        dr = self.drive
        x = x_s + dr.D(t) - dr.D(t_s)
        req = self.m * dr.A(t) + self.k * x + self.c * dr.V(t) - self.Fv(t)
        tst = np.maximum(np.asarray(t) - t_s, 0.0)
        age = self.beta_a * np.log1p(tst / self.tau_a) if self.beta_a else 0.0
        cap = self.Tw(t, x) * np.exp(sign * self.theta * (self.mu_s + age))
        return (req - cap) * sign

    def find_breakaway(self, t_s, x_s, t_max):
        T_n = 2 * np.pi / math.sqrt(self.k / self.m)
        h = T_n / 12
        if self.A_tr:
            h = min(h, 1 / (16 * self.f_tr))
        if self.drive.a:
            h = min(h, 1 / (50 * self.drive.f))
        t0 = t_s
        while t0 < t_max:
            tt = t0 + h * np.arange(1, 2049)
            for sign in (+1, -1):
                g = self.stick_g(tt, t_s, x_s, sign)
                idx = np.nonzero(g > 0)[0]
                if idx.size:
                    i = idx[0]
                    a = tt[i - 1] if i > 0 else t0
                    b = tt[i]
                    if self.stick_g(a, t_s, x_s, sign) > 0:
                        return a, sign
                    tb = brentq(lambda q: float(self.stick_g(q, t_s, x_s, sign)), a, b, xtol=1e-10)
                    # take a point just past the root where g > 0
                    for eps in (1e-9, 1e-8, 1e-7, 1e-6):
                        if self.stick_g(tb + eps, t_s, x_s, sign) > 0:
                            return tb + eps, sign
                    return b, sign
            t0 = tt[-1]
        return None, 0

    # ---- full run
    def run(self, n_slips, x0, level_cb=None, t_hard=600.0):
        """Simulate until n_slips slips have ended; returns phases and slip node data."""
        T_n = 2 * np.pi / math.sqrt(self.k / self.m)
        h = T_n / 300
        phases = []  # ("stick", t0, t1, x0) or ("slip", t_arr, x_arr, v_arr, a_arr)
        slips = []   # dict per slip
        t, x = 0.0, x0
        n = 0
        last_stick_dur = None
        last_cycle = None
        self.n_micro = 0
        # a slip counts as a stick-slip cycle when its force drop exceeds a quarter of the nominal
        # static-kinetic capstan difference (the triggering shaker also causes micro-slips in stick)
        major = 0.25 * self.T0 * (math.exp(self.theta * self.mu_s) - math.exp(self.theta * self.mu_k))
        while True:
            t_s, x_s = t, x
            t_lim = t_hard
            if n >= n_slips:
                t_lim = slips[-1]["t_e"] + 0.5 * (last_cycle or last_stick_dur or 1.0)
                if t_s >= t_lim:
                    phases.append(("stick", t_s, t_s + 1e-9, x_s))
                    break
            tb, sign = self.find_breakaway(t_s, x_s, t_lim)
            if tb is None or tb >= t_lim:
                phases.append(("stick", t_s, t_lim, x_s))
                break
            last_stick_dur = tb - t_s
            age_ex = self.age(tb - t_s)
            phases.append(("stick", t_s, tb, x_s))
            x_b = x_s + float(self.drive.D(tb) - self.drive.D(t_s))
            t, x, v, d = tb, x_b, float(self.drive.V(tb)), 0.0
            T = [t]; X = [x]; Vv = [v]; Aa = []; S = []; TS = []; Dd = [d]; NW = []
            sg = float(sign)
            a0, s0, ts0 = self.rhs(t, x, v, d, age_ex, sg)
            Aa.append(a0); S.append(s0); TS.append(ts0); NW.append(self.Tws(t, x))
            moved = False
            while True:
                xn, vn, dn = self.rk4(t, x, v, d, h, age_ex, sg)
                an, sn, tsn = self.rhs(t + h, xn, vn, dn, age_ex, sg)
                if sg * sn <= 0:
                    if moved:
                        # re-stick event on the continued branch: secant/regula falsi on the step length
                        lo, hi_ = 0.0, h
                        slo, shi = sg * (self.drive.Vs(t) - v), sg * sn
                        tau = h * slo / (slo - shi)
                        for _ in range(40):
                            xq, vq, dq = self.rk4(t, x, v, d, tau, age_ex, sg)
                            sq = sg * (self.drive.Vs(t + tau) - vq)
                            if abs(sq) < 1e-12 or hi_ - lo < 1e-13:
                                break
                            if sq > 0:
                                lo, slo = tau, sq
                            else:
                                hi_, shi = tau, sq
                            tau = lo + (hi_ - lo) * slo / (slo - shi)
                            tau = min(max(tau, lo + 1e-3 * (hi_ - lo)), hi_ - 1e-3 * (hi_ - lo))
                        xq, vq, dq = self.rk4(t, x, v, d, tau, age_ex, sg)
                        tq = t + tau
                    else:
                        xq, vq, dq, tq = xn, vn, dn, t + h
                    vd = self.drive.Vs(tq)
                    req = self.m * float(self.drive.A(tq)) + self.k * xq + self.c * vd - self.Fvs(tq)
                    Tq = self.Tws(tq, xq)
                    cap_hi = Tq * math.exp(self.theta * self.mu_s)
                    cap_lo = Tq * math.exp(-self.theta * self.mu_s)
                    aq, _, tsq = self.rhs(tq, xq, vd, dq, age_ex, sg)
                    T.append(tq); X.append(xq); Vv.append(vd); Aa.append(aq); S.append(0.0); TS.append(tsq)
                    Dd.append(dq); NW.append(Tq)
                    if cap_lo <= req <= cap_hi:
                        t, x = tq, xq
                        break
                    # no stick possible: continue (back-slip if the spring pulls below the cone)
                    t, x, v, d = tq, xq, vd, dq
                    sg = 1.0 if req > cap_hi else -1.0
                    moved = False
                    continue
                if abs(sn) > 1e-6:
                    moved = True
                t, x, v, d = t + h, xn, vn, dn
                T.append(t); X.append(x); Vv.append(v); Aa.append(an); S.append(sn); TS.append(tsn); Dd.append(d)
                NW.append(self.Tws(t, x))
                if t > t_hard:
                    raise RuntimeError("slip did not end")
            T = np.array(T); X = np.array(X); Vv = np.array(Vv); Aa = np.array(Aa)
            phases.append(("slip", T, X, Vv, Aa))
            rec = dict(t_b=tb, t_e=t, x_b=x_b, x_e=x, t_stick=last_stick_dur, s=np.array(S),
                       Ts=np.array(TS), d=np.array(Dd), Nw=np.array(NW), v_drive_b=float(self.drive.V(tb)))
            if self.k * (x_b - x) >= major:
                slips.append(rec)
                n += 1
                if len(slips) >= 2:
                    last_cycle = slips[-1]["t_e"] - slips[-2]["t_e"]
                if level_cb is not None:
                    level_cb(self, n, t)
            else:
                self.n_micro += 1
        return phases, slips

    def dense(self, phases, tgrid):
        x = np.empty_like(tgrid)
        v = np.empty_like(tgrid)
        starts = np.array([ph[1] if ph[0] == "stick" else ph[1][0] for ph in phases])
        idx = np.searchsorted(starts, tgrid, side="right") - 1
        idx = np.clip(idx, 0, len(phases) - 1)
        for j, ph in enumerate(phases):
            sel = idx == j
            if not sel.any():
                continue
            tt = tgrid[sel]
            if ph[0] == "stick":
                _, t0, t1, x0 = ph
                x[sel] = x0 + self.drive.D(tt) - self.drive.D(t0)
                v[sel] = self.drive.V(tt)
            else:
                _, T, X, V, A = ph
                keep = np.concatenate([[True], np.diff(T) > 1e-12])
                sp = CubicHermiteSpline(T[keep], X[keep], V[keep])
                tc = np.clip(tt, T[0], T[-1])
                x[sel] = sp(tc)
                v[sel] = sp(tc, 1)
        return x, v


# --------------------------------------------------------------------------------------------- measures
def twin_share(rig, slips):
    """median over slips of mean(decelerating - accelerating friction tension at equal s) / drop"""
    out = []
    for sl in slips[1:]:
        s, Ts = sl["s"], sl["Ts"] / sl["Nw"] * rig.T0  # friction tension at the nominal load
        if s.size < 20:
            continue
        ipk = int(np.argmax(s))
        spk = s[ipk]
        if ipk < 5 or s.size - ipk < 5 or spk <= 0:
            continue
        lev = np.linspace(0.2, 0.8, 25) * spk
        sa, fa = s[:ipk + 1], Ts[:ipk + 1]
        sd, fd = s[ipk:][::-1], Ts[ipk:][::-1]
        oa, od = np.argsort(sa), np.argsort(sd)
        Fa = np.interp(lev, sa[oa], fa[oa])
        Fd = np.interp(lev, sd[od], fd[od])
        drop = rig.k * (sl["x_b"] - sl["x_e"])
        out.append(np.mean(Fd - Fa) / drop)
    return float(np.median(out)) if out else float("nan")


def drops(rig, slips):
    return np.array([rig.k * (sl["x_b"] - sl["x_e"]) for sl in slips])


# --------------------------------------------------------------------------------------------- build
def _draw(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([68, seed, ci])
    P = {}
    P["m"] = float(rng.uniform(0.25, 0.6))
    P["k"] = float(rng.uniform(1500.0, 4000.0))
    P["zeta"] = float(rng.uniform(0.01, 0.04))
    P["c"] = 2 * P["zeta"] * math.sqrt(P["k"] * P["m"])
    P["theta"] = float(np.deg2rad(rng.uniform(135.0, 225.0)))
    P["T0"] = float(rng.uniform(6.0, 14.0))
    P["mu_s"] = float(rng.uniform(0.26, 0.34))
    P["mu_k"] = P["mu_s"] * float(rng.uniform(0.70, 0.82))
    P["v_c"] = float(rng.uniform(3.0, 12.0))
    P["p"] = float(rng.uniform(1.1, 1.8))
    P["eta"] = float(rng.uniform(0.0, 2e-4))
    P["v0"] = float(rng.uniform(2.0, 6.0)) * 1e-3
    P["n_slips"] = int(rng.integers(24, 40))
    P["fs"] = float(rng.choice([400.0, 500.0, 1000.0]))
    P["amp_bw"] = float(rng.uniform(300.0, 500.0))
    P["noise_rel"] = float(rng.uniform(0.0015, 0.0035))
    P["temp_C"] = float(rng.uniform(19.5, 24.5))
    P["rh"] = float(rng.uniform(35, 60))
    # floor vibration on the carriage: band 5-60 Hz, RMS 0.2-0.5 % of the nominal drop
    d_nom = 1.5 * P["T0"] * (math.exp(P["theta"] * P["mu_s"]) - math.exp(P["theta"] * P["mu_k"]))
    P["vib_rms_N"] = float(rng.uniform(0.002, 0.005)) * d_nom
    rv = np.random.default_rng([68, seed, ci, 5])
    bb, ab = butter(2, [5.0, 60.0], btype="bandpass", fs=1000.0)
    w = lfilter(bb, ab, rv.standard_normal(600_000))
    P["_vib"] = w * (P["vib_rms_N"] / np.std(w))
    return P, rng


def _x_restick_est(P):
    """rough spring extension at re-stick and at breakaway (constant load)"""
    Fs = P["T0"] * math.exp(P["theta"] * P["mu_s"])
    Fk = P["T0"] * math.exp(P["theta"] * P["mu_k"])
    xe = max(2 * Fk - Fs, 0.5 * Fk) / P["k"]
    return xe, Fs / P["k"]


def simulate_case(case, seed):
    P, rng = _draw(case, seed)
    fn = math.sqrt(P["k"] / P["m"]) / (2 * math.pi)
    P["fn"] = fn
    xe, xb = _x_restick_est(P)
    meas = {}

    def plain_run(P_, drive, cb=None, n=None):
        rig = Rig(P_, drive)
        ph, sl = rig.run(n or P_["n_slips"], _x_restick_est(P_)[0], level_cb=cb)
        return rig, ph, sl

    if case == "none":
        rig, ph, sl = plain_run(P, Drive(P["v0"]))
    elif case == "load_variation":
        # the slackening tail cord lowers the capacity as the spring stretches and shrinks the drop:
        # a rope/drum pair with a larger static-kinetic difference keeps the slips clear
        P["mu_k"] = P["mu_s"] * float(rng.uniform(0.60, 0.70))
        xe, xb = _x_restick_est(P)
        x0 = xe
        target = float(rng.uniform(0.12, 0.26))
        P["x_m"] = 0.5 * (xe + xb)
        P["c_lv"] = target / (xb - xe)
        for _ in range(3):
            rig, ph, sl = plain_run(P, Drive(P["v0"]))
            xs = np.concatenate([p[2] for p in ph if p[0] == "slip"][1:])
            Nw = P["T0"] * (1 - P["c_lv"] * (xs - P["x_m"]))
            pp = (Nw.max() - Nw.min()) / P["T0"]
            if abs(pp / target - 1) < 0.05:
                break
            P["c_lv"] *= target / pp
            P["x_m"] = 0.5 * (xs.max() + xs.min())
        meas["load_pp_share_of_T0"] = float(pp)
        P["load_target"] = target
    elif case == "twin_branch":
        target = float(rng.uniform(0.12, 0.22))
        P["L_tw"] = float(rng.uniform(0.3, 0.6)) * (xb - xe)
        P["beta_tw"] = 0.3 * (P["mu_s"] - P["mu_k"])
        for _ in range(4):
            rig, ph, sl = plain_run(P, Drive(P["v0"]))
            sh = twin_share(rig, sl)
            if abs(sh / target - 1) < 0.08:
                break
            P["beta_tw"] *= target / sh
        meas["twin_share_of_drop"] = sh
        P["twin_target"] = target
    elif case == "static_ageing":
        target = float(rng.uniform(0.07, 0.15))
        r = float(rng.uniform(4.5, 7.5))
        v_lo = float(rng.uniform(1.2, 2.5)) * 1e-3
        levels = [v_lo, v_lo * r, v_lo * math.sqrt(r)]
        nb = int(rng.integers(4, 7))
        P.update(v_levels=levels, block_slips=nb, ramp=0.15, v0=v_lo)
        P["tau_a"] = float(rng.uniform(0.05, 0.2))
        P["L_a"] = float(rng.uniform(0.05, 0.15)) * 1e-3
        P["n_slips"] = int(rng.integers(30, 46))
        t_lo = (xb - xe) / levels[0]
        t_hi = (xb - xe) / levels[1]
        span = math.log1p(t_lo / P["tau_a"]) - math.log1p(t_hi / P["tau_a"])
        P["beta_a"] = math.log1p(target) / (P["theta"] * span)

        def cb(rig, n, t):
            if n % nb == 0:
                i = (n // nb) % 3
                cur = rig.drive.Vs(t + 1.0)
                rig.drive.add_step(t + 0.05, levels[i] - cur, 0.15)

        for _ in range(3):
            rig, ph, sl = plain_run(P, Drive(levels[0]), cb)
            pk = np.array([rig.k * s["x_b"] for s in sl[1:]])
            ts = np.array([s["t_stick"] for s in sl[1:]])
            # peak force at the shortest vs longest stick-time groups (quartiles)
            o = np.argsort(ts)
            q = max(2, len(o) // 6)
            F_short, F_long = np.median(pk[o[:q]]), np.median(pk[o[-q:]])
            g = F_long / F_short - 1
            if abs(g / target - 1) < 0.1:
                break
            P["beta_a"] *= math.log1p(target) / math.log1p(max(g, 1e-3))
        dr = np.median(drops(rig, sl)[1:])
        meas.update(peak_growth_share_of_peak=float(g), peak_growth_share_of_drop=float((F_long - F_short) / dr),
                    stick_time_range_s=[float(ts.min()), float(ts.max())])
        P["growth_target"] = target
    elif case == "triggering":
        P["A_tr"] = 0.0
        rig0, ph0, sl0 = plain_run(P, Drive(P["v0"]), n=8)
        fss = (len(sl0) - 1) / (sl0[-1]["t_b"] - sl0[0]["t_b"])
        A = float(rng.uniform(0.035, 0.07))
        P["psi"] = float(rng.uniform(0, 2 * np.pi))
        P["A_tr"] = A
        # The shaker entrains the cycle (breakaway pinned to a capacity trough), so the triggered cycle
        # tends to last an integer number of shaker periods.  Candidates (f_tr/f_ss0 a half-integer for
        # the untriggered f_ss0) are tried until the triggered record's f_tr/f_ss is 0.25-0.75 away from
        # an integer (cycle-to-cycle hopping between N and N+1 periods, helped by the floor vibration).
        best = None
        for r in rng.uniform(3.0, 7.0, 7):
            qq = r * fn / fss
            f_tr = (math.floor(qq) + 0.5) * fss
            P["f_tr"] = f_tr
            rig, ph, sl = plain_run(P, Drive(P["v0"]))
            fss_t = (len(sl) - 3) / (sl[-1]["t_b"] - sl[2]["t_b"])
            q = f_tr / fss_t
            fr = q - math.floor(q)
            score = abs(fr - 0.5)
            if best is None or score < best[0]:
                best = (score, f_tr, q, fr, fss_t, (rig, ph, sl))
            if score <= 0.25:
                break
        score, f_tr, q, fr, fss_t, (rig, ph, sl) = best
        P["f_tr"] = f_tr
        meas.update(trigger_amp_share_of_T0=A, trigger_f_over_fn=f_tr / fn, trigger_f_over_fss=q,
                    trigger_frac_from_multiple=float(min(fr, 1 - fr)), trigger_f_over_fss_untriggered=f_tr / fss)
    elif case == "drive_modulation":
        rig0, ph0, sl0 = plain_run(P, Drive(P["v0"]), n=8)
        fss = (len(sl0) - 1) / (sl0[-1]["t_b"] - sl0[0]["t_b"])
        a = float(rng.uniform(0.25, 0.40))
        rfm = float(rng.uniform(0.15, 0.40))
        phi = float(rng.uniform(0, 2 * np.pi))
        P.update(mod_a=a, mod_fm=rfm * fss, mod_phi=phi)
        rig, ph, sl = plain_run(P, Drive(P["v0"], a, rfm * fss, phi))
        fss2 = (len(sl) - 2) / (sl[-1]["t_b"] - sl[1]["t_b"])
        meas.update(mod_a=a, fm_over_fss=P["mod_fm"] / fss2)
    else:
        raise ValueError(case)

    dr = drops(rig, sl)
    meas["drop_N_median"] = float(np.median(dr[1:]))
    meas["n_slips"] = len(sl)
    meas["n_micro_slips"] = int(rig.n_micro)
    meas["twin_share_of_drop"] = meas.get("twin_share_of_drop", twin_share(rig, sl))
    meas["f_ss_Hz"] = float((len(sl) - 2) / (sl[-1]["t_b"] - sl[1]["t_b"]))
    pk = np.array([rig.k * s["x_b"] for s in sl[1:]])
    meas["peak_spread_share_of_drop"] = float((pk.max() - pk.min()) / meas["drop_N_median"])
    return P, rig, ph, sl, meas


def _fmt(a, nd):
    return np.char.replace(np.char.mod(f"%.{nd}f", a), ".", ",")


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    P, rig, ph, sl, meas = simulate_case(case, seed)
    rn = np.random.default_rng([68, seed, CASES.index(case), NUISANCES.index(nuisance), 99])
    fn = P["fn"]
    drop = meas["drop_N_median"]
    fs = P["fs"]
    nu = {}
    if nuisance == "coarse":
        spp = float(rn.uniform(10, 15))
        fs = spp * fn
        nu["samples_per_period"] = spp
    q = int(math.ceil(2000.0 / fs))
    fs_f = fs * q
    t_end = ph[-1][2]
    n_rec = int(math.floor(t_end * fs)) + 1
    tf = np.arange(n_rec * q) / fs_f
    tf = tf[tf <= t_end]
    x, v = rig.dense(ph, tf)
    F = rig.k * x
    Nw = rig.Tw(tf, x)
    Dp = rig.drive.D(tf) * 1e3  # mm
    # amplifier
    b, a = butter(2, min(P["amp_bw"], 0.45 * fs_f), fs=fs_f)
    F = lfilter(b, a, F, zi=lfilter_zi(b, a) * F[0])[0]
    Nw = lfilter(b, a, Nw, zi=lfilter_zi(b, a) * Nw[0])[0]
    # slow noise component (2 Hz first order), generated on the fine grid
    al = math.exp(-2 * np.pi * 2.0 / fs_f)
    wslow = lfilter([1 - al], [1, -al], rn.standard_normal(tf.size))
    wslow *= 0.001 * drop / (np.std(wslow) + 1e-12)
    F = F + wslow
    # point sampling
    F, Nw, Dp, t = F[::q], Nw[::q], Dp[::q], tf[::q]
    F = F + P["noise_rel"] * drop * rn.standard_normal(t.size)
    Nw = Nw + 0.5 * P["noise_rel"] * drop * rn.standard_normal(t.size)
    if nuisance == "hum":
        f_m = float(rn.choice([50.0, 60.0]))
        pk = float(rn.uniform(0.01, 0.05)) * drop
        ph1, ph2, ph3 = rn.uniform(0, 2 * np.pi, 3)
        h = (np.sin(2 * np.pi * f_m * t + ph1) + 0.35 * np.sin(4 * np.pi * f_m * t + ph2)
             + 0.2 * np.sin(6 * np.pi * f_m * t + ph3))
        h *= pk / np.max(np.abs(h))
        F = F + h
        Nw = Nw + 0.5 * h
        nu.update(mains_Hz=f_m, hum_peak_share_of_drop=pk / drop)
    elif nuisance == "drift":
        tot = float(rn.uniform(0.02, 0.05)) * drop * float(rn.choice([-1, 1]))
        tau = float(rn.uniform(0.2, 0.5)) * t[-1]
        shape = 0.6 * (1 - np.exp(-t / tau)) / (1 - math.exp(-t[-1] / tau)) + 0.4 * t / t[-1]
        F = F + tot * shape
        Nw = Nw + 0.25 * tot * shape
        nu["drift_share_of_drop"] = tot / drop
    elif nuisance == "spikes":
        frac = float(rn.uniform(0.0005, 0.005))
        ns = max(3, int(round(frac * t.size)))
        idx = rn.choice(np.arange(2, t.size - 2), ns, replace=False)
        F[idx] += rn.choice([-1, 1], ns) * rn.uniform(0.15, 0.6, ns) * drop
        nu.update(spike_fraction=ns / t.size, n_spikes=int(ns))
    # ADC
    step = 200.0 / 65536
    if nuisance == "quantisation":
        step = float(rn.uniform(0.002, 0.01)) * drop
        nu["adc_step_share_of_drop"] = step / drop
        nu["adc_step_N"] = step
    F = np.round(F / step) * step
    Nw = np.round(Nw / step) * step
    enc = math.pi * 50.0 / 16384
    Dp = np.round(Dp / enc) * enc

    fn_given = float(f"{fn:.4g}")
    if nuisance == "fn_off":
        sgn = float(rn.choice([-1, 1]))
        fn_given = fn * (1 + 0.05 * sgn)
        nu["fn_factor"] = 1 + 0.05 * sgn
    fn_given = round(fn_given, 3)
    args = ["--fn", f"{fn_given:g}", "--stiffness", f"{P['k']:.1f}"]
    with_pos = case == "static_ageing"
    if not with_pos:
        args += ["--v0", f"{P['v0'] * 1e3:.3f}"]

    os.makedirs(outdir, exist_ok=True)
    fname = os.path.abspath(os.path.join(outdir, f"{NAME}_{case}_s{seed}_{nuisance}.csv"))
    lines = [
        "# CapstanLab 2.3 - data export",
        "# Rig: capstan friction tester CF-2 (rope on drum, "
        + {"load_variation": "elastic tail cord", "triggering": "pneumatic tail tensioner + tail-line shaker"}.get(
            case, "pneumatic tail tensioner") + ")",
        f"# Specimen: braided polyester rope 4 mm on steel drum D=50 mm, wrap angle {np.rad2deg(P['theta']):.1f} deg".replace(".", ","),
        f"# Sample rate [Hz]: {fs:.3f}".replace(".", ","),
        f"# Ambient temperature [degC]: {P['temp_C']:.1f}; relative humidity [%]: {P['rh']:.0f}".replace(".", ","),
        f"# Spring rate [N/mm]: {P['k'] / 1e3:.4f}".replace(".", ","),
        "# Channels: AI0 spring-side load cell, AI1 tail load cell" + (", ENC0 drum" if with_pos else ""),
        "# Decimal separator: comma",
    ]
    head = "Time [s];Spring tension [N];Tail tension [N]" + (";Drum position [mm]" if with_pos else "")
    cols = [_fmt(t, 5), _fmt(F, 4), _fmt(Nw, 4)] + ([_fmt(Dp, 4)] if with_pos else [])
    body = cols[0]
    for c in cols[1:]:
        body = np.char.add(np.char.add(body, ";"), c)
    with open(fname, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n" + head + "\n")
        fh.write("\n".join(body.tolist()) + "\n")

    P = {k_: v_ for k_, v_ in P.items() if not k_.startswith("_")}
    params = {k_: (v_ if not isinstance(v_, (np.floating, np.integer)) else v_.item()) for k_, v_ in P.items()}
    params["fs_record"] = fs
    params["nuisance_params"] = nu
    params["measured"] = meas
    params["units"] = "SI internally (m, m/s, N, kg); v_c, eta per mm/s"
    params = json.loads(json.dumps(params, default=float))
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance, "file": fname,
            "args": args, "fn_true": fn, "fn_given": fn_given, "params": params}


if __name__ == "__main__":
    import sys
    import time
    c = sys.argv[1] if len(sys.argv) > 1 else "none"
    s = int(sys.argv[2]) if len(sys.argv) > 2 else 0
    nz = sys.argv[3] if len(sys.argv) > 3 else "clean"
    t0 = time.time()
    r = write_record(c, s, "/tmp/w68gen/out", nz)
    print(json.dumps(r["params"]["measured"]), r["args"], f"{time.time() - t0:.2f}s")
