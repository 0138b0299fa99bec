"""oil_column: a lubricated pad pushed through a closed oil column (written without reading the diagnosis).

Rig
    A steel pad (the slider with its piston and carriage, m 0.2-4 kg) slides on a lubricated flat under a
    normal load N (dead weight, or a load cylinder / piezo stack in the departures).  It is pushed through a
    closed **oil column**: a metering (syringe) pump's plunger (the drive, glass-scale encoder, 10 nm) displaces
    oil into a cylinder whose piston carries the pad; the column's compressibility (line plus a small
    accumulator, linear over the swing) is the spring, k = m (2 pi fn)^2, fn 15-240 Hz.  The rod side is held
    at a constant back-pressure so the column never cavitates (the force read is the differential one, and
    may dip a little below zero at an arrest).  The friction force is read from the column's pressure
    transducer (F = p A), or the spring's extension as plunger minus piston (an LVDT on the piston).

Friction law (single-valued in the sliding speed w, no film state)
    Mixed lubrication with Greenwood-Williamson load sharing, instantaneous: a film parameter
    Lambda(w) = ((1 + w/v_h)^p - 1)/p (p 0.55-0.75: linear at creep speeds, a power law w^p at speed, so the
    weakening has a finite slope at rest), the asperities' share of the load for Gaussian asperity heights
    phi = F_3/2(Lambda) / F_3/2(0), with F_n(t) = Gamma(n+1) exp(-t^2/4) D_{-n-1}(t) / sqrt(2 pi) (the
    parabolic-cylinder function, tabulated once at 0.002 sigma), and the film's own shear:
        F = N mu_b [c + (1 - c) phi(Lambda(w))] + N0 mu_f (w/v_h) / (1 + Lambda(w)),
    mu_b 0.10-0.16, c (the rim that stays in boundary contact) 0.5-0.7, mu_f 0.6-2 % of mu_b (load-
    independent film shear); static level mu_s0 = mu_b (1 + 0.04..0.10); v_h set so that a slip's peak speed
    is 2-5 v_h, the drive so that a stick lasts 3-8 Tn.  The junction population is re-formed at every arrest:
    the static level scatters per stick by a relative sd of 0.2-0.6 % (peak sd 0.3-0.7 % of the drop D).

Stick handling: **closed form, no time stepping in stick**
    At rest the spring force k (x_d(t) - x_s) is known analytically (the drive program is piecewise linear,
    re-planned at the arrests for steps and holds, plus an analytic modulation); the breakaway is found by a
    vectorised scan (Tn/6, 1/16 of a shaker period) and Brent on |F| = N(t) mu_s(t_stick) (+ the twin's
    memory at rest).  A slip ends where w crosses 0: the step is retaken to the crossing (Brent on the step
    length, each trial an exact Gauss-Legendre step from the step's start), then the static test |F| <= N mu_s.

Integrator
    Own 2-stage **Gauss-Legendre** implicit Runge-Kutta (order 4, symplectic) at h = Tn/160 (<= 1/24 of a
    shaker period), its stage equations solved by a simplified Newton on the two stage speeds (2x2, the law's
    analytic slope and the spring); the twin's memory is a delay in the slip distance, read from the stored
    history by linear interpolation in the slider position.  Tn/80 vs Tn/640: slip time and period agree to
    1e-6 relative, the forces to 1e-5.  Cubic Hermite dense output onto a grid q >= 4 times the record rate.

Sensors and noise (own kind)
    Force: the pressure transducer's quadratic nonlinearity (0.2-0.6 % of full scale) and its port (Helmholtz)
    resonance at 12-30 fn, damping 0.30-0.55; extension: the LVDT demodulator's two real poles at 8-20 fn;
    normal: a load cell, one pole at 30-80 fn; point-sampled from the fine grid.  Noise: **Laplace
    (double-exponential) white** noise 0.1-0.4 % of D plus **random-telegraph (burst) noise** 0.05-0.15 % of D
    (6-20 switches a record) on the main channel, Laplace 0.03-0.1 % of N0 on the normal channel; a tare
    residual of +-0.3 % of the mean.  All drawn apart from the nuisance; the physics has its own RNG.

Cases (the departures; each calibrated on the run, sizes measured on the ground truth of the record's window)
    none: the law above, constant N, constant drive.  The law's twin is 0 (decelerating minus accelerating at
        equal speed, 10-90 % of each slip's peak speed: <= 3e-4 of D, the interpolation); a 1-DoF reading of
        the clean sampled force (x = F/k, central differences) sees -0.4..-12.6 % of D at 20-99 samples per
        period (the static-kinetic kink at the breakaway smeared by the differencing; -0.4..-6.1 % at >= 40),
        -23..-30 % at 10-15.  No ageing: an unwritten probe run on a 6x stepped drive (sticks 5.9-6.2x apart)
        gives breakaway growth 0 and peak growth -1.2..+0.5 % of D (inertial overshoot).
    load_variation: the load cylinder is teed to the drive column through a ratio piston, N = N_dead + r F:
        a loading piston (r > 0), or a relieving one (r < 0, seeds 3 mod 4); 15-30 % of N0 peak-to-peak;
        the normal force recorded on all seeds but 6 mod 8.  F/N stays single-valued (-0.4..+0.4 % of D);
        F against w reads -15..-6 % of D (rising) or +8..+42 % (falling).
    twin_branch: the flat is a tin babbitt, rate-hardening: each element of the track is sheared as it enters
        the contact at the sliding speed of that moment and keeps that hardening while it crosses the contact
        (length L 0.25-0.45 of a slip's distance), F += N (1/L) int_{s-L}^{s} b ln(1 + w(s')/v_g) ds'
        (v_g 0.3-0.8 of the slip speed): a **boxcar memory, a pure delay in the slip distance** (not an
        exponential lag), frozen at rest and part of the static level.  Twin +12.7..+21.8 % of D.
    static_ageing: indentation creep of the soft flat under the junctions (Norton exponent n 3-6):
        mu_s(t) = mu_s0 (1 + beta ((1 + t/tau)^(1/n) - 1)), tau 0.03-0.2 of the fast stick; the pump steps
        4-8x between four parts (even seeds) or holds of 2-9 stick times every 3-4 slips (odd); the drive is
        recorded (plunger position, or the commanded speed).  Peak growth +9.9..+16.2 % of D across sticks
        5.2-10x apart (breakaway +10.0..+16.3 %).
    triggering: a piezo stack under the load frame, N = N0 (1 + A sin(2 pi f_t t + phi)), A 3.6-7.8 %,
        f_t 3.1-7.8 fn, recorded.  The breakaways lock to its troughs (the stick-slip period an integer number
        of shaker periods, a devil's staircase in f_t): f_t is bisected towards the half-integer between two
        plateaus, where the per-stick scatter mixes n and n + 1 shaker periods (up to four starts, A re-drawn
        on the last two), so that f_t/f_ss is 0.18-0.50 from an integer (f_t/f_ss 19-54).
    drive_modulation: the plunger is driven through a cam, v0 (1 + a sin(2 pi f_m t + phi)), a 0.20-0.44,
        f_m/f_ss 0.18-0.41; no drive column, `--v0` the mean speed (mm/s).

Record formats (format by (seed + case index) mod 3)
    A  `.csv`, a HYDROLOG-8-like logger: five `Key: value` lines and a blank line, then
       `Time [ms];Friction force [N];Normal force [N];x_drive [um]` (or `v_drive [mm/s]`), semicolons,
       decimal commas, CRLF (force record, `--stiffness`).
    B  `.txt`, the LVDT/encoder logger: two `#` lines, TAB, `t [s]`, `extension [um]` (plunger - piston),
       `Fn [N]`, `x_drive [um]` or `v_drive [mm/s]` (displacement record).
    C  `.dat`, whitespace, a names row and a units row: `time Ff Fn x_drive` / `s mN N mm` (force record).
    The normal force is written on all triggering records, on 7 of 8 load records and on about a quarter of
    the others; a drive column on every ageing record, never on drive_modulation, on about half the rest
    (else `--v0`).  20-99 samples per natural period (coarse 10-15), 16-40 slips, 0.45-43 s, 0.7k-53k rows.
    `--fn` is passed on 7 of 8 seeds per case (left out on seeds 3, 5, 1, 7, 2 mod 8 of none, load, twin,
    ageing, drive_modulation; never on triggering or with fn_off); `--stiffness` (N/m) on force records.

Self-check (`python oil_column.py [OUTDIR]`: seeds 0-7 of every case, nuisance NUISANCES[seed % 7], ~10 s):
    case              seeds 0-7 (measured on the ground truth)
    none              twin +0.0002..+0.0003 of D; 1-DoF reading -0.5..-4.9 % (-30 % coarse); probe ageing
                      -1.2..+0.5 %; peak sd 0.27-0.71 %
    load_variation    N p-p 18.2-30.3 % of N0 (6 rising, 2 falling); F/N twin -0.1..+0.4 %
    twin_branch       twin +14.4..+21.8 % of D
    static_ageing     peak growth +11.6..+15.5 % of D over sticks 5.8-8.9x apart (4 steps, 4 holds)
    triggering        A 4.9-7.8 %, f_t/fn 3.1-7.1, f_t/f_ss 22.6-53.3, 0.20-0.50 from an integer
    drive_modulation  a 0.25-0.44, f_m/f_ss 0.18-0.41
    (per record: see `_selfcheck`'s printout; ranges over seeds 0-23 are given in the cases above.)
"""

import bisect
import json
import math
import os
import sys

import numpy as np
from scipy import signal, special
from scipy.optimize import brentq

NAME = "oil_column"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

# --------------------------------------------------------------------------------------------
# Greenwood-Williamson load sharing: Gaussian asperity heights, the asperities' share of the load
# at a film separation Lambda (in sigma) is F_3/2(Lambda) / F_3/2(0), with
# F_n(t) = Gamma(n+1) exp(-t^2/4) D_{-n-1}(t) / sqrt(2 pi) (parabolic cylinder function), and
# dF_n/dt = -n F_{n-1}.  Tabulated once (linear interpolation, step 0.002 sigma).
# --------------------------------------------------------------------------------------------


def _gw_F(n, t):
    return special.gamma(n + 1.0) / math.sqrt(2.0 * math.pi) * np.exp(-t * t / 4.0) * special.pbdv(-n - 1.0, t)[0]


_DL = 0.002
_LGRID = np.arange(0.0, 8.0 + _DL / 2, _DL)
_F32_0 = float(_gw_F(1.5, 0.0))
_PHI = (_gw_F(1.5, _LGRID) / _F32_0).tolist()
_DPHI = (-1.5 * _gw_F(0.5, _LGRID) / _F32_0).tolist()
_NT = len(_PHI)
_INV_DL = 1.0 / _DL

# Gauss-Legendre 2-stage (order 4) tableau
_S3 = math.sqrt(3.0)
_C1, _C2 = 0.5 - _S3 / 6.0, 0.5 + _S3 / 6.0
_A11, _A12, _A21, _A22 = 0.25, 0.25 - _S3 / 6.0, 0.25 + _S3 / 6.0, 0.25


def _phi(lam):
    z = lam * _INV_DL
    i = int(z)
    if i >= _NT - 1:
        return 0.0, 0.0
    fr = z - i
    p0 = _PHI[i]
    d0 = _DPHI[i]
    return p0 + fr * (_PHI[i + 1] - p0), d0 + fr * (_DPHI[i + 1] - d0)


# --------------------------------------------------------------------------------------------
# the drive: a metering (syringe) pump's plunger, piecewise-constant speed, extended at run time
# (steps and holds are scheduled at the arrests), plus an optional slow modulation.
# --------------------------------------------------------------------------------------------


class Drive:
    def __init__(self, v0, t0=0.0, amod=0.0, fm=0.0, phm=0.0):
        self.kt = [t0]
        self.kx = [0.0]
        self.kv = [v0]
        self.v0n = v0
        self.amod = amod
        self.wm = 2.0 * math.pi * fm
        self.phm = phm
        self.cmod = v0 * amod / self.wm if amod > 0 else 0.0

    def _mod(self, t):
        if self.amod <= 0:
            return 0.0
        return -self.cmod * (math.cos(self.wm * t + self.phm) - math.cos(self.phm))

    def x(self, t):
        i = bisect.bisect_right(self.kt, t) - 1
        if i < 0:
            i = 0
        return self.kx[i] + self.kv[i] * (t - self.kt[i]) + self._mod(t)

    def xv(self, t):
        t = np.asarray(t, float)
        kt = np.asarray(self.kt)
        i = np.clip(np.searchsorted(kt, t, side="right") - 1, 0, None)
        out = np.asarray(self.kx)[i] + np.asarray(self.kv)[i] * (t - kt[i])
        if self.amod > 0:
            out = out - self.cmod * (np.cos(self.wm * t + self.phm) - math.cos(self.phm))
        return out

    def vv(self, t):
        t = np.asarray(t, float)
        kt = np.asarray(self.kt)
        i = np.clip(np.searchsorted(kt, t, side="right") - 1, 0, None)
        out = np.asarray(self.kv)[i].astype(float)
        if self.amod > 0:
            out = out + self.v0n * self.amod * np.sin(self.wm * t + self.phm)
        return out

    def set_speed(self, t, v):
        # position continuous (without the modulation term, which is added on top)
        i = bisect.bisect_right(self.kt, t) - 1
        x = self.kx[i] + self.kv[i] * (t - self.kt[i])
        # drop knots after t (re-planning)
        del self.kt[i + 1:], self.kx[i + 1:], self.kv[i + 1:]
        self.kt.append(t)
        self.kx.append(x)
        self.kv.append(v)


# --------------------------------------------------------------------------------------------
# the rig
# --------------------------------------------------------------------------------------------


class Rig:
    """A slider (pad) on a lubricated flat, pushed through a closed oil column (the spring)."""

    def __init__(self, P):
        self.P = P
        self.m = P["m"]
        self.k = P["k"]
        self.wn = math.sqrt(self.k / self.m)
        self.Tn = 2.0 * math.pi / self.wn
        self.N0 = P["N0"]
        self.mub = P["mu_b"]
        self.cr = P["c_rim"]
        self.mus0 = P["mu_s0"]
        self.p = P["p_film"]
        self.inv_p = 1.0 / self.p
        self.inv_vh = 1.0 / P["v_h"]
        self.Ff0 = P["N0"] * P["mu_f"]      # film shear scale (load-independent), N
        # twin: boxcar memory over the sliding distance L of a rate-hardening term b ln(1 + w/v_g)
        self.bmem = P.get("b_mem", 0.0)
        self.Lmem = P.get("L_mem", 1.0)
        self.inv_vg = 1.0 / P.get("v_g", 1.0)
        # ageing (indentation creep of the soft flat): mu_s(t) = mu_s0 (1 + beta ((1 + t/tau)^q - 1))
        self.beta = P.get("beta_age", 0.0)
        self.tau = P.get("tau_age", 1.0)
        self.qage = P.get("q_age", 0.25)
        # load: 'const', 'tee' (N = N_dead + r Fsp) or 'shaker'
        self.load = P.get("load", "const")
        self.r = P.get("r_tee", 0.0)
        self.Ndead = P.get("N_dead", self.N0)
        self.At = P.get("A_t", 0.0)
        self.wt = 2.0 * math.pi * P.get("f_t", 1.0)
        self.pht = P.get("ph_t", 0.0)
        # per-stick scatter of the static level (the junction population re-formed at each arrest)
        self.sig_s = P.get("scatter", 0.0)
        self.xi = np.random.default_rng(P.get("xi_seed", 0)).standard_normal(4096).tolist()

    # normal load
    def N(self, t, fsp):
        if self.load == "tee":
            return self.Ndead + self.r * fsp
        if self.load == "shaker":
            return self.N0 * (1.0 + self.At * math.sin(self.wt * t + self.pht))
        return self.N0

    def Nv(self, t, fsp):
        if self.load == "tee":
            return self.Ndead + self.r * np.asarray(fsp)
        if self.load == "shaker":
            return self.N0 * (1.0 + self.At * np.sin(self.wt * np.asarray(t) + self.pht))
        return np.full(np.shape(t), self.N0)

    # the single-valued part of the law (w >= 0): returns F and dF/dw
    def law(self, w, N):
        u = w * self.inv_vh
        up = (1.0 + u) ** self.p
        lam = (up - 1.0) * self.inv_p
        dlam = up / (1.0 + u)
        ph, dph = _phi(lam)
        den = 1.0 + lam
        fl = u / den
        dfl = (den - u * dlam) / (den * den)
        mb = N * self.mub
        F = mb * (self.cr + (1.0 - self.cr) * ph) + self.Ff0 * fl
        dF = (mb * (1.0 - self.cr) * dph * dlam + self.Ff0 * dfl) * self.inv_vh
        return F, dF

    def mus(self, ts):
        if self.beta <= 0:
            return self.mus0
        return self.mus0 * (1.0 + self.beta * ((1.0 + ts / self.tau) ** self.qage - 1.0))

    def mus_vec(self, ts):
        if self.beta <= 0:
            return np.full(np.shape(ts), self.mus0)
        return self.mus0 * (1.0 + self.beta * ((1.0 + np.asarray(ts) / self.tau) ** self.qage - 1.0))

    # ------------------------------------------------------------------ simulation
    def simulate(self, drive, n_slips, schedule=None, h_frac=1.0 / 160.0, t_max=None):
        """Event-driven: closed-form stick, Gauss-Legendre slips.  Returns knots and slip records."""
        k, m = self.k, self.m
        h0 = self.Tn * h_frac
        if self.load == "shaker":
            h0 = min(h0, 2.0 * math.pi / self.wt / 24.0)
        vsc = self.P["v_peak_est"]
        tolv = 1e-12 * vsc
        # memory history: slider position -> cumulative integral of the hardening term
        hx = [-1e30, drive.x(0.0) - self.P["F_init"] / k]
        hM = [0.0, 0.0]
        Lm = self.Lmem
        bm = self.bmem
        use_mem = bm > 0

        def Mat(xq):
            j = bisect.bisect_right(hx, xq) - 1
            if j >= len(hx) - 1:
                return hM[-1]
            x0 = hx[j]
            return hM[j] + (hM[j + 1] - hM[j]) * (xq - x0) / (hx[j + 1] - x0)

        def gmem(w):
            return bm * math.log1p(w * self.inv_vg) if w > 0 else 0.0

        dxv = drive.x

        def acc(t, x, v, M, dirn):
            fsp = k * (dxv(t) - x)
            N = self.N(t, fsp)
            w = dirn * v
            if w < 0.0:
                w = 0.0
            F, dF = self.law(w, N)
            if use_mem:
                F += N * (M - Mat(x - Lm)) / Lm
            return (fsp - dirn * F) / m, -dF / m

        T, X, V, Aa, FR, NN = [], [], [], [], [], []
        slips = []
        t = 0.0
        x = drive.x(0.0) - self.P["F_init"] / k
        M = 0.0
        t_arr = 0.0
        nsl = 0
        status = "ok"
        while nsl < n_slips:
            # ---------------- stick: x fixed, the force known in closed form; breakaway by scan + Brent
            mrest = (M - Mat(x - Lm)) / Lm if use_mem else 0.0
            xs = x
            ta = t_arr
            fac = 1.0 + self.sig_s * self.xi[nsl % 4096]

            def G(tt):
                fsp = k * (drive.xv(tt) - xs)
                N = self.Nv(tt, fsp)
                return np.abs(fsp) - N * (fac * self.mus_vec(np.asarray(tt) - ta) + mrest)

            dts = self.Tn / 6.0
            if self.load == "shaker":
                dts = min(dts, 2.0 * math.pi / self.wt / 16.0)
            tb = None
            tcur = t
            g_prev = float(G(np.array([tcur]))[0])
            if g_prev >= 0:
                tb = tcur
            while tb is None:
                tt = tcur + dts * np.arange(1, 513)
                g = G(tt)
                idx = np.nonzero(g >= 0)[0]
                if idx.size:
                    j = idx[0]
                    lo = tcur if j == 0 else tt[j - 1]
                    tb = brentq(lambda s: float(G(np.array([s]))[0]), lo, tt[j], xtol=1e-13 * self.Tn, rtol=1e-14)
                    break
                tcur = tt[-1]
                if t_max is not None and tcur > t_max or tcur - t > 5e4 * self.Tn:
                    status = "stuck"
                    break
            if tb is None:
                T.append(tcur)
                X.append(xs)
                V.append(0.0)
                Aa.append(0.0)
                FR.append(np.nan)
                NN.append(np.nan)
                break
            fspb = k * (drive.x(tb) - xs)
            Nb = self.N(tb, fspb)
            dirn = 1.0 if fspb > 0 else -1.0
            # knots of the stick (start and end)
            for tt_ in (t, tb):
                fsp_ = k * (drive.x(tt_) - xs)
                T.append(tt_)
                X.append(xs)
                V.append(0.0)
                Aa.append(0.0)
                FR.append(np.nan)
                NN.append(self.N(tt_, fsp_))
            rec = dict(t_arr_prev=ta, t_brk=tb, F_brk=fspb, N_brk=Nb, mus_brk=fac * self.mus(tb - ta) + mrest,
                       k0=len(T) - 1)
            # ---------------- slip: Gauss-Legendre 2-stage, simplified Newton on the stage speeds
            t = tb
            v = 0.0
            a, D = acc(t, x, v, M, dirn)
            nsteps = 0
            arrested = False
            while not arrested:
                h = h0
                xn, vn, Mn = self._gl2(acc, t, x, v, M, a, h, dirn, tolv, Mat, gmem, use_mem)
                if dirn * vn < 0.0:
                    # the slip arrests inside the step: the step is retaken to the crossing (Brent on
                    # the step length, each trial an exact GL2 step from the step's start)
                    def fv(hh):
                        return dirn * self._gl2(acc, t, x, v, M, a, hh, dirn, tolv, Mat, gmem, use_mem)[1]
                    if dirn * v <= 0.0:
                        h = 1e-9 * h0
                    else:
                        h = brentq(fv, 0.0, h0, xtol=1e-10 * h0, rtol=1e-14)
                    xn, vn, Mn = self._gl2(acc, t, x, v, M, a, h, dirn, tolv, Mat, gmem, use_mem)
                    arrested = True
                t += h
                x, v, M = xn, vn, Mn
                nsteps += 1
                if use_mem and x > hx[-1]:
                    hx.append(x)
                    hM.append(M)
                if arrested:
                    v = 0.0
                a, D = acc(t, x, v, M, dirn)
                fsp = k * (drive.x(t) - x)
                N = self.N(t, fsp)
                w = max(dirn * v, 0.0)
                Flaw = self.law(w, N)[0] + (N * (M - Mat(x - Lm)) / Lm if use_mem else 0.0)
                T.append(t)
                X.append(x)
                V.append(v)
                Aa.append(a if not arrested else (fsp - dirn * Flaw) / m)
                FR.append(Flaw)
                NN.append(N)
                if nsteps > 40.0 / h_frac:
                    status = "steady"
                    break
            if status != "ok":
                break
            nsl += 1
            rec["t_arr"] = t
            rec["k1"] = len(T) - 1
            # stick check at the arrest (the static limit); else keep sliding the other way/on
            fsp = k * (drive.x(t) - x)
            N = self.N(t, fsp)
            mrest = (M - Mat(x - Lm)) / Lm if use_mem else 0.0
            if abs(fsp) > N * (self.mus(0.0) + mrest):
                status = "no_stick"
                slips.append(rec)
                break
            t_arr = t
            slips.append(rec)
            if schedule is not None:
                schedule(nsl, t_arr, slips, drive)
            if t_max is not None and t > t_max:
                break
        knots = dict(T=np.array(T), X=np.array(X), V=np.array(V), A=np.array(Aa), FR=np.array(FR),
                     N=np.array(NN))
        return knots, slips, status

    def _gl2(self, acc, t, x, v, M, a0, h, dirn, tolv, Mat, gmem, use_mem):
        kap = self.k / self.m
        h2k = h * h * kap
        t1 = t + _C1 * h
        t2 = t + _C2 * h
        V1 = v + _C1 * h * a0
        V2 = v + _C2 * h * a0
        G1 = G2 = 0.0
        for _ in range(30):
            X1 = x + h * (_A11 * V1 + _A12 * V2)
            X2 = x + h * (_A21 * V1 + _A22 * V2)
            if use_mem:
                G1 = abs(V1) * gmem(abs(V1))
                G2 = abs(V2) * gmem(abs(V2))
                M1 = M + h * (_A11 * G1 + _A12 * G2)
                M2 = M + h * (_A21 * G1 + _A22 * G2)
            else:
                M1 = M2 = M
            A1, D1 = acc(t1, X1, V1, M1, dirn)
            A2, D2 = acc(t2, X2, V2, M2, dirn)
            R1 = V1 - v - h * (_A11 * A1 + _A12 * A2)
            R2 = V2 - v - h * (_A21 * A1 + _A22 * A2)
            if abs(R1) + abs(R2) < tolv:
                break
            j11 = 1.0 - h * _A11 * D1 + h2k * (_A11 * _A11 + _A12 * _A21)
            j12 = -h * _A12 * D2 + h2k * (_A11 * _A12 + _A12 * _A22)
            j21 = -h * _A21 * D1 + h2k * (_A21 * _A11 + _A22 * _A21)
            j22 = 1.0 - h * _A22 * D2 + h2k * (_A21 * _A12 + _A22 * _A22)
            det = j11 * j22 - j12 * j21
            V1 -= (R1 * j22 - R2 * j12) / det
            V2 -= (j11 * R2 - j21 * R1) / det
        xn = x + 0.5 * h * (V1 + V2)
        vn = v + 0.5 * h * (A1 + A2)
        Mn = M + 0.5 * h * (G1 + G2)
        return xn, vn, Mn


# --------------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------------


def _base_params(rng):
    fn = math.exp(rng.uniform(math.log(15.0), math.log(250.0)))
    m = math.exp(rng.uniform(math.log(0.2), math.log(4.0)))
    wn = 2.0 * math.pi * fn
    k = m * wn * wn
    N0 = rng.uniform(40.0, 500.0)
    mu_b = rng.uniform(0.10, 0.16)
    c_rim = rng.uniform(0.50, 0.70)
    ds = rng.uniform(0.04, 0.10)
    mu_s0 = mu_b * (1.0 + ds)
    p = rng.uniform(0.55, 0.75)
    mu_f = mu_b * rng.uniform(0.006, 0.02)
    dF = (mu_s0 - mu_b * (c_rim + 0.1)) * N0          # static minus a typical kinetic level
    v_peak = dF / (m * wn)
    U = rng.uniform(2.0, 5.0)
    v_h = v_peak / U
    t_st = rng.uniform(3.0, 8.0) / fn                 # target stick time
    v0 = 2.0 * dF / (k * t_st)
    return dict(fn=fn, m=m, k=k, N0=N0, mu_b=mu_b, c_rim=c_rim, static_excess=ds, mu_s0=mu_s0,
                p_film=p, mu_f=mu_f, v_h=v_h, v_peak_est=v_peak, U_slip=U, v0=v0,
                t_stick_target=t_st, D_est=2.0 * dF, F_init=0.97 * mu_s0 * N0,
                scatter=rng.uniform(0.002, 0.006), xi_seed=int(rng.integers(1 << 30)))


# --------------------------------------------------------------------------------------------
# ground-truth measurements
# --------------------------------------------------------------------------------------------


def _spring(rig, drive, kn):
    return rig.k * (drive.xv(kn["T"]) - kn["X"])


def _twin_one(v, F):
    """decelerating minus accelerating branch at equal speed, 10-90 % of the slip's peak speed."""
    if v.size < 8:
        return np.nan
    im = int(np.argmax(v))
    vm = v[im]
    if im < 3 or v.size - im < 3 or vm <= 0:
        return np.nan
    va, Fa = v[:im + 1], F[:im + 1]
    vd, Fd = v[im:][::-1], F[im:][::-1]
    va = np.maximum.accumulate(va)
    vd = np.maximum.accumulate(vd)
    g = vm * np.linspace(0.1, 0.9, 33)
    return float(np.mean(np.interp(g, vd, Fd) - np.interp(g, va, Fa)))


def _measure(rig, drive, kn, slips, t0, t1):
    Fsp = _spring(rig, drive, kn)
    rows = []
    for s in slips:
        if s["t_brk"] < t0 or s.get("t_arr", np.inf) > t1:
            continue
        a, b = s["k0"], s["k1"]
        seg = Fsp[a:b + 1]
        v = kn["V"][a + 1:b + 1]
        Fr = kn["FR"][a + 1:b + 1]
        Nn = kn["N"][a + 1:b + 1]
        rows.append(dict(t_brk=s["t_brk"], t_arr=s["t_arr"], t_st=s["t_brk"] - s["t_arr_prev"],
                         F_brk=s["F_brk"], F_peak=float(seg.max()), F_min=float(seg.min()),
                         vmax=float(v.max()), dist=float(kn["X"][b] - kn["X"][a]),
                         tw=_twin_one(v, Fr), twn=_twin_one(v, Fr / Nn), N_brk=s["N_brk"],
                         mus_brk=s["mus_brk"]))
    if len(rows) < 3:
        return None
    D = float(np.median([r["F_peak"] - r["F_min"] for r in rows]))
    tb = np.array([r["t_brk"] for r in rows])
    tw = np.array([r["tw"] for r in rows])
    twn = np.array([r["twn"] for r in rows])
    Nbar = float(np.median([r["N_brk"] for r in rows]))
    out = dict(n_slips=len(rows), D=D, D_over_N=D / Nbar,
               f_ss=float((len(tb) - 1) / (tb[-1] - tb[0])),
               twin=float(np.nanmedian(tw) / D),
               twin_mu=float(np.nanmedian(twn) * Nbar / D),
               slip_dist=float(np.median([r["dist"] for r in rows])),
               v_slip=float(np.median([r["vmax"] for r in rows])),
               peak_sd=float(np.std([r["F_peak"] for r in rows]) / D))
    ts = np.array([r["t_st"] for r in rows])
    Fp = np.array([r["F_peak"] for r in rows])
    Fb = np.array([r["F_brk"] for r in rows])
    out["t_stick_median"] = float(np.median(ts))
    out["stick_ratio"] = float(ts.max() / ts.min())
    if ts.max() / ts.min() > 1.5:
        lt = np.log(ts)
        span = lt.max() - lt.min()
        out["ageing_peak"] = float(np.polyfit(lt, Fp, 1)[0] * span / D)
        out["ageing_brk"] = float(np.polyfit(lt, Fb, 1)[0] * span / D)
    else:                                   # every stick as long: the growth cannot be read
        out["ageing_peak"] = None
        out["ageing_brk"] = None
    out["rows"] = rows
    return out


def _window(slips, n_warm, rng):
    """record from inside the stick after the warm-up to inside the last stick."""
    a = slips[n_warm - 1]
    b = slips[n_warm]
    t0 = a["t_arr"] + rng.uniform(0.15, 0.8) * (b["t_brk"] - a["t_arr"])
    c = slips[-2]
    d = slips[-1]
    t1 = c["t_arr"] + rng.uniform(0.2, 0.85) * (d["t_brk"] - c["t_arr"])
    return t0, t1


# --------------------------------------------------------------------------------------------
# the six cases
# --------------------------------------------------------------------------------------------

N_WARM = 3


def _run(P, drive_fn, n_slips, schedule_fn=None):
    rig = Rig(P)
    drive = drive_fn()
    sched = schedule_fn() if schedule_fn is not None else None
    kn, slips, status = rig.simulate(drive, n_slips, schedule=sched)
    if status != "ok" or len(slips) < n_slips:
        raise RuntimeError("simulation ended early: %s after %d slips" % (status, len(slips)))
    return rig, drive, kn, slips


def _pilot(P, n=8):
    rig, drive, kn, slips = _run(P, lambda: Drive(P["v0"]), n)
    return _measure(rig, drive, kn, slips, slips[2]["t_brk"] - 1e-12, slips[-1]["t_arr"] + 1e-12)


def _stepped_schedule(levels, counts, frac=0.35):
    """change the drive speed once the given number of slips is done, during the next stick."""
    bounds = np.cumsum(counts)

    def make():
        def sched(nsl, t_arr, slips, drive):
            j = int(np.searchsorted(bounds, nsl, side="right"))
            if nsl in bounds and j < len(levels):
                last = slips[-1]["t_brk"] - slips[-1]["t_arr_prev"]
                drive.set_speed(t_arr + frac * last, levels[j])
        return sched
    return make


def _hold_schedule(v0, every, holds, t_st0):
    def make():
        state = {"i": 0}

        def sched(nsl, t_arr, slips, drive):
            if nsl >= N_WARM and (nsl - N_WARM) % every == every - 1 and state["i"] < len(holds):
                th = t_arr + 0.3 * t_st0
                drive.set_speed(th, 0.0)
                drive.set_speed(th + holds[state["i"]] * t_st0, v0)
                state["i"] += 1
        return sched
    return make


def _physics(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([20240611, ci, seed])
    P = _base_params(rng)
    P["case"] = case
    n_cyc = int(rng.integers(16, 41))
    info = {}
    drive_fn = lambda: Drive(P["v0"])
    sched = None
    n_slips = N_WARM + n_cyc + 1

    if case == "none":
        pass

    elif case == "load_variation":
        rising = (seed % 4) != 3
        target = rng.uniform(0.14, 0.32)
        P["load"] = "tee"
        pil = _pilot(P)
        D0 = pil["D"]
        sgn = 1.0 if rising else -1.0
        r = sgn * target * P["N0"] / D0
        if rising:
            r = min(r, 0.75 / P["mu_s0"])
        Fm = P["mu_s0"] * P["N0"] - 0.5 * D0
        for it in range(4):
            P["r_tee"] = r
            P["N_dead"] = P["N0"] - r * Fm
            P["F_init"] = 0.97 * P["mu_s0"] * P["N_dead"] / (1.0 - r * P["mu_s0"])
            rig, drive, kn, slips = _run(P, drive_fn, 10)
            Fsp = _spring(rig, drive, kn)
            j0 = slips[2]["k0"]
            Nn = P["N_dead"] + r * Fsp[j0:]
            pp = (Nn.max() - Nn.min()) / np.mean(Nn)
            Fm = float(0.5 * (Fsp[j0:].max() + Fsp[j0:].min()))
            if abs(pp / target - 1.0) < 0.03:
                break
            r *= target / pp
            if rising:
                r = min(r, 0.75 / P["mu_s0"])
        P["N_dead"] = P["N0"] - r * Fm
        info.update(load_sign=int(sgn), pp_target=target)

    elif case == "twin_branch":
        pil = _pilot(P)
        P["L_mem"] = rng.uniform(0.25, 0.45) * pil["slip_dist"]
        P["v_g"] = rng.uniform(0.3, 0.8) * pil["v_slip"]
        target = rng.uniform(0.12, 0.22)
        b = target * pil["D"] / P["N0"] / 0.5
        for it in range(4):
            P["b_mem"] = b
            m = _pilot(P, 10)
            if abs(m["twin"] / target - 1.0) < 0.04:
                break
            b *= target / max(m["twin"], 1e-3)
        info.update(twin_target=target, L_mem_over_slip=P["L_mem"] / pil["slip_dist"],
                    v_g_over_slip_speed=P["v_g"] / pil["v_slip"])

    elif case == "static_ageing":
        pil = _pilot(P)
        t_st0 = pil["t_stick_median"]
        P["q_age"] = 1.0 / rng.uniform(3.0, 6.0)
        P["tau_age"] = rng.uniform(0.03, 0.2) * t_st0
        target = rng.uniform(0.10, 0.17)
        if seed % 2 == 0:
            ratio = rng.uniform(4.0, 8.0)
            v_hi = P["v0"] * rng.uniform(1.1, 1.8)
            v_lo = v_hi / ratio
            na, nb = int(rng.integers(7, 10)), int(rng.integers(4, 7))
            counts = [N_WARM + na, nb, na, nb]
            levels = [v_hi, v_lo, v_hi, v_lo]
            n_slips = sum(counts) + 1
            drive_fn = lambda: Drive(v_hi)
            sched = _stepped_schedule(levels, counts)
            t_ratio = ratio * P["v0"] / v_hi
            info.update(drive_program="steps", step_ratio=ratio, v_hi=v_hi, v_lo=v_lo, parts=counts)
        else:
            every = int(rng.integers(3, 5))
            nh = int(rng.integers(6, 9))
            holds = list(rng.uniform(2.0, 9.0, nh))
            n_slips = N_WARM + every * nh + 2
            sched = _hold_schedule(P["v0"], every, holds, t_st0)
            t_ratio = 1.0 + max(holds)
            info.update(drive_program="holds", hold_every=every, holds_in_sticks=[float(h) for h in holds])
        q, tau = P["q_age"], P["tau_age"]
        span = (1 + t_ratio * t_st0 / tau) ** q - (1 + t_st0 / tau) ** q
        beta = target * pil["D"] / (P["mu_s0"] * P["N0"] * span)
        for it in range(4):
            P["beta_age"] = beta
            rig, drive, kn, slips = _run(P, drive_fn, n_slips, sched)
            mm = _measure(rig, drive, kn, slips, slips[N_WARM]["t_brk"] - 1e-12, slips[-1]["t_arr"] + 1e-12)
            g = mm["ageing_peak"]
            if abs(g / target - 1.0) < 0.05:
                break
            beta *= target / max(g, 1e-3)
        info.update(ageing_target=target)

    elif case == "triggering":
        P["load"] = "shaker"
        P["A_t"] = rng.uniform(0.03, 0.08)
        P["ph_t"] = rng.uniform(0, 2 * math.pi)
        P["f_t"], P["A_t"], ntry = _trigger_search(P, rng, n_slips)
        info.update(ft_tries=ntry)

    elif case == "drive_modulation":
        pil = _pilot(P)
        a = rng.uniform(0.2, 0.45)
        target = rng.uniform(0.18, 0.42)
        ph = rng.uniform(0, 2 * math.pi)
        fm = target * pil["f_ss"]
        n_slips = N_WARM + max(n_cyc, int(math.ceil(3.0 / target)) + 2) + 1
        for it in range(4):
            drive_fn = (lambda fm_=fm: Drive(P["v0"], amod=a, fm=fm_, phm=ph))
            rig, drive, kn, slips = _run(P, drive_fn, n_slips)
            f_ss = (len(slips) - N_WARM - 1) / (slips[-1]["t_brk"] - slips[N_WARM]["t_brk"])
            rr = fm / f_ss
            if 0.16 <= rr <= 0.44:
                break
            fm *= target / rr
        P.update(a_mod=a, f_m=fm, ph_m=ph)
        drive_fn = (lambda: Drive(P["v0"], amod=a, fm=P["f_m"], phm=ph))
        info.update(fm_target=target)

    rig, drive, kn, slips = _run(P, drive_fn, n_slips, sched)
    return P, info, rig, drive, kn, slips, rng


def _ratio_ft(P, n_slips):
    rig, drive, kn, slips = _run(P, lambda: Drive(P["v0"]), n_slips)
    tb = np.array([s["t_brk"] for s in slips[N_WARM:-1]])
    return P["f_t"] * (tb[-1] - tb[0]) / (len(tb) - 1)


def _trigger_search(P, rng, n_slips):
    """The breakaways lock to the shaker's troughs (the stick-slip period an integer number of shaker
    periods).  R(f_t) = f_t / f_ss is a staircase, non-decreasing in f_t: from a random f_t, the
    half-integer next to its R is bracketed and bisected for, until R is 0.17 or more from an integer
    (where the static scatter mixes n and n + 1 shaker periods, or a fractional plateau); up to four
    starts, the shaker's amplitude re-drawn on the last two."""
    fn = P["fn"]
    lo_f, hi_f = 2.5 * fn, 8.0 * fn
    Q = dict(P)
    cnt = [0]
    best = [(-1.0, None, None)]

    def R(f):
        Q["f_t"] = f
        cnt[0] += 1
        r = _ratio_ft(Q, n_slips)
        d = abs(r - round(r))
        if d > best[0][0]:
            best[0] = (d, f, Q["A_t"])
        return r, d >= 0.17

    for attempt in range(4):
        if attempt >= 2:
            Q["A_t"] = rng.uniform(0.03, 0.08)
        f0 = rng.uniform(2.7, 7.7) * fn
        r0, ok = R(f0)
        if ok:
            return f0, Q["A_t"], cnt[0]
        n0 = round(r0)
        target = n0 + 0.5 if f0 * (n0 + 0.5) / n0 <= hi_f else n0 - 0.5
        sgn = 1.0 if target > r0 else -1.0
        fa, ra = f0, r0
        f1 = min(max(f0 * target / r0 * (1.0 + 0.3 * sgn / target), lo_f), hi_f)
        r1, ok = R(f1)
        if ok:
            return f1, Q["A_t"], cnt[0]
        for _ in range(4):
            if (r1 - target) * (ra - target) < 0:
                break
            fa, ra = f1, r1
            f1 = min(max(f1 * (1.0 + 0.5 * sgn / target), lo_f), hi_f)
            r1, ok = R(f1)
            if ok:
                return f1, Q["A_t"], cnt[0]
        fb = f1
        for _ in range(12):
            fm = 0.5 * (fa + fb)
            rm, ok = R(fm)
            if ok:
                return fm, Q["A_t"], cnt[0]
            if (rm - target) * (ra - target) > 0:
                fa, ra = fm, rm
            else:
                fb = fm
    return best[0][1], best[0][2], cnt[0]


def _law_ageing_probe(P):
    """the law's own peak growth with the stick time (no ageing in it): a stepped drive, not written."""
    Q = dict(P)
    levels = [P["v0"] * 1.5, P["v0"] * 1.5 / 6.0, P["v0"] * 1.5, P["v0"] * 1.5 / 6.0]
    counts = [N_WARM + 5, 4, 5, 4]
    rig, drive, kn, slips = _run(Q, lambda: Drive(levels[0]), sum(counts) + 1, _stepped_schedule(levels, counts))
    m = _measure(rig, drive, kn, slips, slips[N_WARM]["t_brk"] - 1e-12, slips[-1]["t_arr"] + 1e-12)
    return dict(probe_stick_ratio=m["stick_ratio"], probe_ageing_peak=m["ageing_peak"],
                probe_ageing_brk=m["ageing_brk"], probe_twin=m["twin"])


# --------------------------------------------------------------------------------------------
# the record: fine grid, sensors, sampling, noise, nuisances, file
# --------------------------------------------------------------------------------------------


def _hermite_x(kn, tf):
    T, X, V = kn["T"], kn["X"], kn["V"]
    i = np.clip(np.searchsorted(T, tf, side="right") - 1, 0, len(T) - 2)
    h = T[i + 1] - T[i]
    h = np.where(h > 0, h, 1.0)
    u = np.clip((tf - T[i]) / h, 0.0, 1.0)
    u2, u3 = u * u, u * u * u
    return ((2 * u3 - 3 * u2 + 1) * X[i] + (u3 - 2 * u2 + u) * h * V[i]
            + (-2 * u3 + 3 * u2) * X[i + 1] + (u3 - u2) * h * V[i + 1])


def _filt(b, a, y):
    zi = signal.lfilter_zi(b, a) * y[0]
    return signal.lfilter(b, a, y, zi=zi)[0]


def _second_order(fr, zeta, rate):
    w = 2 * math.pi * fr
    wd = 2 * rate * math.tan(w / (2 * rate))          # prewarped
    return signal.bilinear([wd * wd], [1.0, 2 * zeta * wd, wd * wd], fs=rate)


def _two_real_poles(fc, rate):
    w = 2 * rate * math.tan(2 * math.pi * fc / (2 * rate))
    return signal.bilinear([w * w], [1.0, 2 * w, w * w], fs=rate)


def _one_pole(fc, rate):
    w = 2 * rate * math.tan(2 * math.pi * fc / (2 * rate))
    return signal.bilinear([w], [1.0, w], fs=rate)


def _rtn(rng, n, amp, nsw):
    """random telegraph (burst) noise: a two-level offset switching at random instants."""
    out = np.zeros(n)
    if nsw <= 0:
        return out
    cuts = np.sort(rng.choice(np.arange(1, n), size=min(nsw, n - 1), replace=False))
    lev = amp * (rng.random(len(cuts) + 1) < 0.5)
    start = 0
    for j, c in enumerate(list(cuts) + [n]):
        out[start:c] = lev[j]
        start = c
    return out - lev.mean()


def _fmt_cols(cols, decs):
    parts = [np.char.mod("%." + str(d) + "f", c) for c, d in zip(cols, decs)]
    return parts


def _decimals(res):
    return int(max(0, math.ceil(-math.log10(res))))


def _slip_spans(rig, kn, slips, t0, t1):
    return [(s["t_brk"], s["t_arr"]) for s in slips if s["t_brk"] >= t0 and s.get("t_arr", np.inf) <= t1]


def _twin_1dof(Frec, xd, m, k, fs, spans, t0, D):
    """the twin a linear 1-DoF reading of the clean sampled force sees: x = F/k, v = x_d' - x',
    friction = F - m (x_d'' - x''), central differences at the record's rate; median over the slips."""
    ext = Frec / k
    xs = xd - ext
    v = np.gradient(xs, 1.0 / fs)
    acc = np.gradient(v, 1.0 / fs)
    fr = Frec - m * acc
    t = t0 + np.arange(Frec.size) / fs
    Tn = 2 * math.pi * math.sqrt(m / k)
    vals = []
    for tb, ta in spans:
        sel = (t >= tb - 0.05 * Tn) & (t <= ta + 0.1 * Tn)
        if sel.sum() >= 8:
            vals.append(_twin_one(v[sel], fr[sel]))
    vals = [x for x in vals if np.isfinite(x)]
    return float(np.median(vals) / D) if vals else None


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    ci = CASES.index(case)
    P, info, rig, drive, kn, slips, rng = _physics(case, seed)
    t0, t1 = _window(slips, N_WARM, rng)
    meas = _measure(rig, drive, kn, slips, t0, t1)
    fn = P["fn"]
    k = P["k"]
    D = meas["D"]

    # ---- the recording set-up (drawn apart from the nuisance)
    rr = np.random.default_rng([20240612, ci, seed])
    fmt = "ABC"[(seed + ci) % 3]
    spp_nom = rr.uniform(20.0, 100.0)
    spp_coarse = rr.uniform(10.0, 15.0)
    eps_nl = rr.uniform(0.002, 0.006)
    f_port = rr.uniform(12.0, 30.0) * fn
    z_port = rr.uniform(0.30, 0.55)
    f_lvdt = rr.uniform(8.0, 20.0) * fn
    f_ncell = rr.uniform(30.0, 80.0) * fn
    s_lap = rr.uniform(0.001, 0.004)
    a_rtn = rr.uniform(0.0005, 0.0015)
    n_rtn = int(rr.integers(6, 21))
    s_lapN = rr.uniform(0.0003, 0.001)
    u_norm = rr.random()
    u_drive = rr.random()
    u_dkind = rr.random()
    x_off = rr.uniform(2.0, 40.0) * 1e-3           # encoder's absolute position at the start, m
    tare = rr.uniform(-0.003, 0.003)                # residual zero of the extension/force, of the mean
    nz_seed = int(rr.integers(1 << 30))
    fn_sign = 1.0 if rr.random() < 0.5 else -1.0

    if case == "load_variation":
        has_normal = (seed % 8) != 6
    elif case == "triggering":
        has_normal = True
    else:
        has_normal = u_norm < 0.25
    if case == "drive_modulation":
        drive_col = None
    elif case == "static_ageing":
        drive_col = "pos" if u_dkind < 0.6 else "vel"
    else:
        drive_col = None if u_drive < 0.5 else ("pos" if u_dkind < 0.7 else "vel")
    kind = "disp" if fmt == "B" else "force"

    spp = spp_coarse if nuisance == "coarse" else spp_nom
    fs = spp * fn
    q = max(4, int(math.ceil(6.0 * max(f_port, f_lvdt, f_ncell) / fs)))
    rate = q * fs
    n_rec = int(math.floor((t1 - t0) * fs)) + 1
    tf = t0 + np.arange(n_rec * q) / rate
    xs = _hermite_x(kn, tf)
    xd = drive.xv(tf)
    Fsp = k * (xd - xs)
    Ntrue = rig.Nv(tf, Fsp)

    nrng = np.random.default_rng(nz_seed)
    if kind == "force":
        F_fs = 1.5 * float(Fsp.max())
        y = Fsp + eps_nl * Fsp * Fsp / F_fs
        b, a = _second_order(min(f_port, 0.4 * rate), z_port, rate)
        y = _filt(b, a, y)[::q]
        y = y + tare * float(np.mean(Fsp))
        scale = D
    else:
        b, a = _two_real_poles(min(f_lvdt, 0.4 * rate), rate)
        xl = _filt(b, a, xs - xs[0]) + xs[0]
        y = (xd - xl)[::q]
        y = y + tare * float(np.mean(xd - xs))
        scale = D / k
    n = y.size
    tw1 = _twin_1dof(y if kind == "force" else y * k, xd[::q], P["m"], k, fs, _slip_spans(rig, kn, slips, t0, t1), t0, D)
    y = y + nrng.laplace(0.0, s_lap * scale / math.sqrt(2.0), n) + _rtn(nrng, n, a_rtn * scale, n_rtn)
    t = np.arange(n) / fs
    if has_normal:
        b, a = _one_pole(min(f_ncell, 0.4 * rate), rate)
        yN = _filt(b, a, Ntrue)[::q]
        yN = yN + nrng.laplace(0.0, s_lapN * P["N0"] / math.sqrt(2.0), n)
    xdr = xd[::q] - xd[0] + x_off
    vdr = drive.vv(tf[::q])

    # ---- nuisances (on what is written; the physics is the same for every nuisance)
    urng = np.random.default_rng([20240613, ci, seed, NUISANCES.index(nuisance)])
    nz = {}
    if nuisance == "hum":
        mains = 50.0 if urng.random() < 0.5 else 60.0
        harm = int(urng.choice([1, 1, 2, 3]))
        fh = mains * harm
        if fh > 0.45 * fs:
            fh = mains
        chans = [y] + ([yN] if has_normal else [])
        amps = []
        for c in chans:
            spread = np.percentile(c, 99.5) - np.percentile(c, 0.5)
            amp = urng.uniform(0.01, 0.05) * spread
            c += amp * np.sin(2 * math.pi * fh * t + urng.uniform(0, 2 * math.pi))
            amps.append(float(amp / spread))
        nz.update(hum_hz=fh, hum_rel_spread=amps)
    elif nuisance == "drift":
        tot = urng.uniform(0.012, 0.03) * scale
        s_ = t / t[-1]
        shape = urng.uniform(0.3, 1.0) * s_ + urng.uniform(-0.5, 0.5) * np.sin(math.pi * s_) \
            + urng.uniform(-0.3, 0.3) * s_ * s_
        shape = shape - shape[0]
        shape *= tot / max(np.ptp(shape), 1e-12)
        y += shape
        nz.update(drift_rel_D=float(np.ptp(shape) / scale))
    elif nuisance == "spikes":
        frac = urng.uniform(0.0005, 0.005)
        ns = max(3, int(round(frac * n)))
        idx = np.sort(urng.choice(np.arange(2, n - 2), size=ns, replace=False))
        amp = urng.uniform(0.08, 0.3, ns) * scale * np.where(urng.random(ns) < 0.5, -1.0, 1.0)
        y[idx] += amp
        nz.update(spike_fraction=float(ns / n), spike_max_rel_D=float(np.max(np.abs(amp)) / scale))
    elif nuisance == "quantisation":
        step = urng.uniform(0.002, 0.01) * scale
        y = np.round(y / step) * step
        nz.update(adc_step_rel_D=float(step / scale))
    fn_given = fn
    if nuisance == "fn_off":
        fn_given = fn * (1.0 + 0.05 * fn_sign)
    omit = {"none": 3, "load_variation": 5, "twin_branch": 1, "static_ageing": 7, "drive_modulation": 2}
    if case in omit and seed % 8 == omit[case] and nuisance != "fn_off":
        fn_given = None

    # ---- columns and file
    os.makedirs(outdir, exist_ok=True)
    base = "%s_%s_s%d_%s" % (NAME, case, seed, nuisance)
    Nunit = "N"
    cols, names, decs = [], [], []
    if fmt == "A":
        path = os.path.join(outdir, base + ".csv")
        cols.append(t * 1e3); names.append("Time [ms]"); decs.append(_decimals(1e3 / fs / 1000))
        cols.append(y); names.append("Friction force [N]"); decs.append(_decimals(2e-5 * D))
        if has_normal:
            cols.append(yN); names.append("Normal force [N]"); decs.append(_decimals(2e-5 * P["N0"]))
        if drive_col == "pos":
            cols.append(np.round(xdr * 1e8) / 100.0); names.append("x_drive [um]"); decs.append(2)
        elif drive_col == "vel":
            cols.append(vdr * 1e3); names.append("v_drive [mm/s]"); decs.append(_decimals(1e-6 * P["v0"] * 1e3))
    elif fmt == "B":
        path = os.path.join(outdir, base + ".txt")
        cols.append(t); names.append("t [s]"); decs.append(_decimals(1.0 / fs / 1000))
        cols.append(y * 1e6); names.append("extension [um]"); decs.append(_decimals(2e-5 * D / k * 1e6))
        if has_normal:
            cols.append(yN); names.append("Fn [N]"); decs.append(_decimals(2e-5 * P["N0"]))
        if drive_col == "pos":
            cols.append(np.round(xdr * 1e8) / 100.0); names.append("x_drive [um]"); decs.append(2)
        elif drive_col == "vel":
            cols.append(vdr * 1e3); names.append("v_drive [mm/s]"); decs.append(_decimals(1e-6 * P["v0"] * 1e3))
    else:
        path = os.path.join(outdir, base + ".dat")
        cols.append(t); names.append(("time", "s")); decs.append(_decimals(1.0 / fs / 1000))
        cols.append(y * 1e3); names.append(("Ff", "mN")); decs.append(_decimals(2e-5 * D * 1e3))
        if has_normal:
            cols.append(yN); names.append(("Fn", "N")); decs.append(_decimals(2e-5 * P["N0"]))
        if drive_col == "pos":
            cols.append(np.round(xdr * 1e8) / 1e5); names.append(("x_drive", "mm")); decs.append(5)
        elif drive_col == "vel":
            cols.append(vdr * 1e3); names.append(("v_drive", "mm/s")); decs.append(_decimals(1e-6 * P["v0"] * 1e3))
    for c in cols:
        if not np.all(np.isfinite(c)):
            raise RuntimeError("non-finite record")
    strs = _fmt_cols(cols, decs)
    if fmt == "A":
        lines = ["HYDROLOG-8 data export, firmware 2.31",
                 "Rig: oil-column slider bench OC-2 (lubricated pad on a flat)",
                 "Channels: %d" % len(cols),
                 "Sample rate: %s Hz" % ("%.3f" % fs).replace(".", ","),
                 "Operator: lab 3", ""]
        lines.append(";".join(names))
        body = strs[0]
        for s_ in strs[1:]:
            body = np.char.add(np.char.add(body, ";"), s_)
        body = np.char.replace(body, ".", ",")
        lines.extend(body.tolist())
        text = "\r\n".join(lines) + "\r\n"
    elif fmt == "B":
        lines = ["# oil-column bench, LVDT on the piston, glass-scale encoder on the pump plunger",
                 "# extension = plunger - piston (tared unloaded); fs = %.3f Hz" % fs]
        lines.append("\t".join(names))
        body = strs[0]
        for s_ in strs[1:]:
            body = np.char.add(np.char.add(body, "\t"), s_)
        lines.extend(body.tolist())
        text = "\n".join(lines) + "\n"
    else:
        w = [max(12, len(nm[0]) + 2) for nm in names]
        lines = ["".join(nm[0].ljust(wi) for nm, wi in zip(names, w)).rstrip(),
                 "".join(nm[1].ljust(wi) for nm, wi in zip(names, w)).rstrip()]
        body = np.char.ljust(strs[0], w[0])
        for s_, wi in zip(strs[1:], w[1:]):
            body = np.char.add(body, np.char.ljust(s_, wi))
        lines.extend(np.char.rstrip(body).tolist())
        text = "\n".join(lines) + "\n"
    with open(path, "w", newline="") as fh:
        fh.write(text)

    args = []
    if fn_given is not None:
        args += ["--fn", "%.4g" % fn_given]
    if kind == "force":
        args += ["--stiffness", "%.6g" % k]
    if drive_col is None:
        v_mean = P["v0"]
        args += ["--v0", "%.6g" % (v_mean * 1e3)]

    # ---- measured effect sizes (ground truth, the record's window)
    rows = meas.pop("rows")
    Nw = Ntrue
    eff = dict(meas)
    eff["twin_1dof_clean_record"] = tw1
    eff["load_pp"] = float((Nw.max() - Nw.min()) / np.mean(Nw))
    eff["fn_over_fss"] = float(fn / meas["f_ss"])
    eff["samples_per_period"] = float(spp)
    eff["record_s"] = float(t[-1])
    eff["n_samples"] = int(n)
    if case == "triggering":
        R = P["f_t"] / meas["f_ss"]
        eff.update(ft_over_fn=P["f_t"] / fn, ft_over_fss=R, ft_int_distance=abs(R - round(R)), A_t=P["A_t"])
    if case == "drive_modulation":
        eff.update(a_mod=P["a_mod"], fm_over_fss=P["f_m"] / meas["f_ss"])
    if case == "none":
        eff.update(_law_ageing_probe(P))
    params = {kk: vv for kk, vv in P.items() if kk not in ("case",)}
    params.update(info)
    params["effects"] = eff
    params["record"] = dict(format=fmt, kind=kind, has_normal=bool(has_normal), drive_column=drive_col,
                            fs_hz=fs, port_resonance_fn=f_port / fn, port_zeta=z_port,
                            lvdt_fc_fn=f_lvdt / fn, normal_cell_fc_fn=f_ncell / fn,
                            nonlinearity=eps_nl, laplace_rel_D=s_lap, rtn_rel_D=a_rtn, rtn_switches=n_rtn,
                            tare_rel=tare, nuisance=nz)
    params = json.loads(json.dumps(params, default=_jsonable))
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=os.path.abspath(path),
                args=args, fn_true=float(fn), fn_given=None if fn_given is None else float(fn_given),
                params=params)


def _jsonable(o):
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(type(o))


# --------------------------------------------------------------------------------------------
# own loader (a check that what was written reads back) and the self-check
# --------------------------------------------------------------------------------------------


def _load(path):
    """read a record back: returns (names, array).  Handles the three formats written here."""
    with open(path) as fh:
        lines = fh.read().splitlines()
    if path.endswith(".csv"):
        i = next(j for j, l in enumerate(lines) if l.startswith("Time ["))
        names = lines[i].split(";")
        data = np.array([[float(c.replace(",", ".")) for c in l.split(";")] for l in lines[i + 1:] if l])
    elif path.endswith(".txt"):
        i = next(j for j, l in enumerate(lines) if not l.startswith("#"))
        names = lines[i].split("\t")
        data = np.array([[float(c) for c in l.split("\t")] for l in lines[i + 1:] if l])
    else:
        names = ["%s [%s]" % (a, b) for a, b in zip(lines[0].split(), lines[1].split())]
        data = np.array([[float(c) for c in l.split()] for l in lines[2:] if l])
    if data.ndim != 2 or data.shape[1] != len(names) or not np.all(np.isfinite(data)):
        raise ValueError("bad record %s" % path)
    if not np.all(np.diff(data[:, 0]) > 0):
        raise ValueError("time not increasing in %s" % path)
    return names, data


def _summary(rec):
    e = rec["params"]["effects"]
    c = rec["case"]
    ag = "   n/a" if e["ageing_peak"] is None else "%+.3f" % e["ageing_peak"]
    s = "D/N %.3f twin %+.3f (1-DoF %s) ageing %s" % (e["D_over_N"], e["twin"], "n/a" if e["twin_1dof_clean_record"] is None else "%+.3f" % e["twin_1dof_clean_record"], ag)
    if c == "none":
        s += " | probe: stick x%.1f peak %+.4f twin %+.5f; peak sd %.4f" % (
            e["probe_stick_ratio"], e["probe_ageing_peak"], e["probe_twin"], e["peak_sd"])
    elif c == "load_variation":
        s += " | load pp %.3f (sign %+d) F/N twin %+.4f" % (e["load_pp"], rec["params"]["load_sign"], e["twin_mu"])
    elif c == "twin_branch":
        s += " | stick x%.2f" % e["stick_ratio"]
    elif c == "static_ageing":
        s += " | %s stick x%.1f (brk %+.3f)" % (rec["params"]["drive_program"], e["stick_ratio"], e["ageing_brk"])
    elif c == "triggering":
        s += " | A %.3f ft/fn %.2f ft/fss %.3f (int dist %.3f) load pp %.3f" % (
            e["A_t"], e["ft_over_fn"], e["ft_over_fss"], e["ft_int_distance"], e["load_pp"])
    elif c == "drive_modulation":
        s += " | a %.3f fm/fss %.3f" % (e["a_mod"], e["fm_over_fss"])
    return s


def _selfcheck(outdir):
    import time
    t_start = time.time()
    out = []
    print("%-16s %4s %-13s %6s %5s %6s %6s  %s" % ("case", "seed", "nuisance", "fn", "fn/fss", "cycles", "spp", "measured"))
    for case in CASES:
        for seed in range(8):
            nui = NUISANCES[seed % 7]
            rec = write_record(case, seed, outdir, nui)
            json.dumps(rec, allow_nan=False)
            names, data = _load(rec["file"])
            e = rec["params"]["effects"]
            print("%-16s %4d %-13s %6.1f %5.1f %6d %6.1f  %s" % (
                case, seed, nui, rec["fn_true"], e["fn_over_fss"], e["n_slips"], e["samples_per_period"],
                _summary(rec)), flush=True)
            out.append(rec)
    print("%d records in %.1f s" % (len(out), time.time() - t_start))
    return out


if __name__ == "__main__":
    import tempfile
    _selfcheck(sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix="oil_column_"))
