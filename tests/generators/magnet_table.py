"""magnet_table: a magnetically preloaded linear tribometer with a tabulated friction law.

Written by a helper session that had not read the diagnosis code (`python/`, `fortran/`, the tests, the
other generators): only `tests/generators/README.md` and the `lieng diagnose` section of the top README.

Rig
---
A slider of mass m on a flat counterface, held down by an **electromagnet** under it (the normal load N is
the magnet's pull, N = N0 at the nominal air gap), dragged by a carriage at v0 through a flexure
dynamometer of stiffness k (fn = sqrt(k/m)/2pi, 6-300 Hz; k 0.8-20 kN/m; N0 3-25 N). The dynamometer's
extension e = x_d - x (x_d the carriage, x the slider) is what the record's main channel reads (force k e or
the extension itself). A small viscous term (zeta 0.5-3 %).

Friction law
------------
**Interpolated from a "measured" table**: 15 steady-sliding points (speeds 1e-4..4.5 of the slip-speed
scale, each with 0.2 % measurement scatter) of a weakening-then-strengthening curve, fitted by a least-squares
**polynomial in the cube root of the speed**, s = (v / v_top)^(1/3), on the powers 1, s^3 .. s^8 (no s, s^2
terms, so the slope at rest is finite and weakening), continued linearly above v_top. A new table per seed;
the fit departs from the curve behind the table by up to 0.02-0.56 of the weakening depth (the fit *is* the
law). mu(0+) is the fit at s = 0; the static level mu_s sits 4-12 % of the weakening depth above it. The law
is exactly single-valued in `none`. F = mu(v) N sgn + c_d v (+ the eddy drag in the twin).

Stick handling and integrator
-----------------------------
**Event-driven hybrid**: in stick the slider is at rest and everything is in closed form (the carriage's
travel, the magnet's pull, the decaying eddy current); the breakaway is where the needed force
|k e - c_e q| first reaches mu_s(t_stick) N(t), found by a vectorised scan (Tn/120, or 1/40 of a shaker
period) and Brent's method. Each slip is integrated by scipy's `solve_ivp` **DOP853** (rtol 1e-8) with a
terminal event at v = 0 and its dense output, the friction held opposite to the slip's direction until that
event (a Filippov chatter at v = 0 otherwise stalls the explicit solver); at the arrest the stick test is made
again (a slip may restart). No band, no regularisation. A pilot run (40 Tn, constant drive) measures the law's
drop and slip time, from which the drive and the record length are set. The truth is evaluated on a grid 4x the record's rate.

Sensor and noise
----------------
The dynamometer (and the normal channel) through a **2nd-order Chebyshev type-I low-pass (0.5 dB ripple)
at 0.35 of the record's rate**, run causally on the 4x grid and decimated; white noise (0.15-0.5 % of the
drop) plus a **gain (multiplicative) noise** of 0.05-0.15 % of the signal; the carriage's encoder quantised
to 0.1 um counts. 20-100 samples per natural period (10-15 for `coarse`).

Cases
-----
- `none`: constant drive (stepped 4-8x on seeds 2, 5 mod 8, the drive recorded), constant load.
- `load_variation`: the magnet sits on the dynamometer's moving arm, so the air gap closes as the flexure
  extends: **N = N0 / (1 - c (e - e_ref))^2** (inverse-square pull, rising with the extension), c set on a
  pilot run to 15-30 % p-p; the magnet's force recorded on 7 of 8 seeds.
- `twin_branch`: a copper-backed counterface under the magnet: an **eddy-current drag** c_e q whose induced
  current q lags the speed with the coil's L/R time, tau_e dq/dt = v - q (tau_e 0.12-0.3 Tn); the drag is
  higher decelerating than accelerating at equal speed. c_e set on a pilot run to +12..+21 % of the drop.
- `static_ageing`: mu_s = mu_s0 + b asinh(t_stick / tau_a) (tau_a 0.05-0.3 Tn), carriage steps 4-8x (even
  seeds) or holds (odd), b set on a pilot run to 10-16 % of the drop over the stick-time range; drive recorded.
- `triggering`: a ripple on the magnet's coil current: N = N0 (1 + A sin(2 pi f_t t)), A 3.5-7.5 %, f_t
  2.8-7 fn; normal recorded. Its breakaways lock 1:n to the ripple's troughs (a 1:25 tongue spans 4 % of f_t),
  so this case's counterface also has a ground **texture**: the static level varies along the track (4 sines,
  wavelengths 0.37-1.3 slip lengths, sd 2.5-4 % of the drop), and a locked breakaway skips a trough more or
  less from stick to stick; f_t is then moved (x1.13 while a run chatters; bisected between the n- and
  (n+1)-locks on full-length pilots) until the record's f_t / f_ss is >= 0.17 from an integer. Mid-slip
  arrests (a ripple crest stopping the slider) make some short slips: counted apart (`n_small`).
- `drive_modulation`: the carriage's speed v0 (1 + a sin(2 pi fm t + phi)), a 0.2-0.45, fm 0.2-0.4 of the
  stick-slip frequency of an unmodulated pilot; no drive column, `--v0` the mean.

Formats (style = (seed + case index) % 3)
-----------------------------------------
0. the tribometer software's export: metadata lines (`Instrument:`, `Operator:`, ...) above a semicolon header
   `Time [ms];Friction force [mN];Normal preload [mN];Carriage position [um]`, decimal comma;
1. TAB, `Time (s)	Tangential force (N)	Normal force (N)	Drive speed (mm/s)`;
2. whitespace `.dat`, a unit row under the names: `time flexure_deflection normal_load_gauge drive_speed`
   / `s mm mm mm/s` (a displacement record; the gauge an affine reading of the load).
Optional columns are left out where the case and seed say (see `write_record`).
`--stiffness` (N/m) on force records; `--v0` (mm/s) when no drive column; `--fn` on 7 of 8 seeds (omitted
on seed 5 mod 8 except for triggering and `fn_off`), 5 % off for `fn_off`.

Measured (ground truth, seeds 0-7 per case, `python magnet_table.py OUTDIR`, 34 s for the 48 records)
---------------------------------------------------------------------------------------------------------
Effect sizes are read on the simulated truth, not on the written samples. D = median peak-to-trough of the
spring force k e over the slips. Twin = the resisting force (mu N + c_d v + c_e q) decelerating minus
accelerating at equal sliding speed, mean over 10-90 % of each slip's peak speed, median over slips, / D.
Ageing = the slope of the peak force on ln(stick time) times ln(max/min stick time), / D.
- `none`: twin +0.0000 (|twin| < 5e-5) on all 8; no ageing in the law: on the stepped seeds 2 and 5 (sticks
  6.9x and 5.7x apart) the peaks change -0.0000 D; peak sd 0; load and drive constant.
- `load_variation`: N p-p 18.5-27.3 % of N0; the friction *force* then reads double-valued by -0.19..-0.23 D
  (F/N is single-valued); normal recorded on 7 of 8.
- `twin_branch`: +0.135..+0.203 of the drop (eddy tau_e 0.12-0.3 Tn).
- `static_ageing`: +0.104..+0.153 of the drop over stick times 5.1-10x apart (steps on even seeds, holds on odd).
- `triggering`: A 3.9-7.2 %, f_t 4.2-7.0 fn, record f_t/f_ss 20.60-51.36 (>= 0.22 from an integer); the
  texture and mid-slip arrests scatter the peaks (sd ~3 % of D) and read a twin of about +0.06 D from N(t).
- `drive_modulation`: a 0.24-0.39, fm/f_ss 0.24-0.38 (measured on the record's slips).
Records 1 850-31 500 samples, 15-50 slips, 10.2-96 samples per natural period.
"""

import json
import math
import os
import sys
from bisect import bisect_right

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.signal import cheby1, lfilter

NAME = "magnet_table"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
TWO_PI = 2.0 * math.pi


# ----------------------------------------------------------------------------------------- the law
class _Law:
    """Least-squares polynomial in s = (v/v_top)^(1/3) (no s, s^2 terms) fitted to a noisy table."""

    def __init__(self, rng, mu_k, dW, Vp):
        self.v_w = rng.uniform(0.08, 0.2) * Vp
        self.p_w = rng.uniform(0.85, 1.0)
        self.s_v = rng.uniform(0.03, 0.08) * dW
        self.mu_k, self.dW, self.Vp = mu_k, dW, Vp
        self.v_top = 4.5 * Vp
        v_tab = Vp * np.geomspace(1e-4, 4.5, 15)
        mu_tab = self._true(v_tab) * (1.0 + 0.002 * rng.standard_normal(v_tab.size))
        s = np.cbrt(v_tab / self.v_top)
        # least squares on 1, s^3 .. s^8 (no s, s^2 terms: a finite slope at rest)
        pw = [0, 3, 4, 5, 6, 7, 8]
        B = s[:, None] ** np.array(pw)[None, :]
        cf = np.linalg.lstsq(B, mu_tab, rcond=None)[0]
        c = np.zeros(9)
        c[pw] = cf
        self.c = [float(a) for a in c]
        self.slope0 = self.c[3] / self.v_top
        self.mu0 = self.c[0]
        dc = np.polynomial.polynomial.polyder(self.c)
        self.mu_top = float(np.polynomial.polynomial.polyval(1.0, self.c))
        self.slope_top = float(np.polynomial.polynomial.polyval(1.0, dc)) / (3.0 * self.v_top)
        self.table = (v_tab.tolist(), mu_tab.tolist())

    def _true(self, v):
        return self.mu_k + self.dW / (1.0 + (v / self.v_w) ** self.p_w) + self.s_v * np.log1p(v / self.Vp)

    def mu(self, v):  # scalar, v >= 0
        if v >= self.v_top:
            return self.mu_top + self.slope_top * (v - self.v_top)
        s = (v / self.v_top) ** (1.0 / 3.0)
        c = self.c
        r = c[-1]
        for a in c[-2::-1]:
            r = r * s + a
        return r

    def mu_vec(self, v):
        v = np.asarray(v, float)
        s = np.cbrt(np.minimum(v, self.v_top) / self.v_top)
        out = np.polynomial.polynomial.polyval(s, self.c)
        return np.where(v >= self.v_top, self.mu_top + self.slope_top * (v - self.v_top), out)


# ----------------------------------------------------------------------------------------- the drive
class _Drive:
    """Piecewise-constant carriage speed (steps, holds) or a sinusoidally modulated one."""

    def __init__(self, segs=None, v0=None, a=0.0, fm=0.0, phi=0.0):
        self.mod = segs is None
        if self.mod:
            self.v0, self.a, self.wm, self.phi = v0, a, TWO_PI * fm, phi
        else:
            self.tk = [0.0]
            self.vk = []
            self.xk = [0.0]
            for dur, vel in segs:
                self.vk.append(vel)
                self.xk.append(self.xk[-1] + dur * vel)
                self.tk.append(self.tk[-1] + dur)
            self.T = self.tk[-1]
            self.tk_a = np.array(self.tk)
            self.vk_a = np.array(self.vk + [self.vk[-1]])
            self.xk_a = np.array(self.xk)

    def x(self, t):  # scalar
        if self.mod:
            return self.v0 * (t - self.a / self.wm * (math.cos(self.wm * t + self.phi) - math.cos(self.phi)))
        i = min(max(bisect_right(self.tk, t) - 1, 0), len(self.vk) - 1)
        return self.xk[i] + self.vk[i] * (t - self.tk[i])

    def xv(self, t):
        t = np.asarray(t, float)
        if self.mod:
            return self.v0 * (t - self.a / self.wm * (np.cos(self.wm * t + self.phi) - math.cos(self.phi)))
        i = np.clip(np.searchsorted(self.tk_a, t, side="right") - 1, 0, len(self.vk) - 1)
        return self.xk_a[i] + self.vk_a[i] * (t - self.tk_a[i])

    def vv(self, t):
        t = np.asarray(t, float)
        if self.mod:
            return self.v0 * (1.0 + self.a * np.sin(self.wm * t + self.phi))
        i = np.clip(np.searchsorted(self.tk_a, t, side="right") - 1, 0, len(self.vk) - 1)
        return self.vk_a[i]


# ----------------------------------------------------------------------------------------- the rig
class _Rig:
    def __init__(self, P, law, drive):
        self.P, self.law, self.drive = P, law, drive
        self.k, self.m = P["k"], P["m"]
        self.cd = P["c_d"]
        self.ce = P.get("c_e", 0.0)
        self.tau_e = P.get("tau_e", 1.0)
        self.N0 = P["N0"]
        self.cl = P.get("c_load", 0.0)
        self.e_ref = P.get("e_ref", 0.0)
        self.A = P.get("A_t", 0.0)
        self.wt = TWO_PI * P.get("f_t", 0.0)
        self.b_a = P.get("b_age", 0.0)
        self.tau_a = P.get("tau_age", 1.0)
        self.mu_s0 = P["mu_s0"]
        self.age_off = P.get("age_off", 0.0)
        self.tex = P.get("texture")  # (amplitudes in mu, wavenumbers 1/m, phases): triggering only
        self.mu_floor = P["mu0"] + 0.3 * P["gap"]

    def N(self, t, e):
        n = self.N0
        if self.cl:
            n = n / (1.0 - self.cl * (e - self.e_ref)) ** 2
        if self.A:
            n = n * (1.0 + self.A * np.sin(self.wt * t))
        return n

    def Nsc(self, t, e):
        n = self.N0
        if self.cl:
            n = n / (1.0 - self.cl * (e - self.e_ref)) ** 2
        if self.A:
            n = n * (1.0 + self.A * math.sin(self.wt * t))
        return n

    def mu_s(self, ts):
        if self.b_a:
            return np.maximum(self.mu_s0 + self.b_a * (np.arcsinh(ts / self.tau_a) - self.age_off),
                              self.mu_floor)
        return self.mu_s0

    def run(self, T_end, e0):
        P, k, m, law, drv = self.P, self.k, self.m, self.law, self.drive
        Tn = 1.0 / P["fn"]
        Vp = P["Vp"]
        h = Tn / 120.0
        if self.A:
            h = min(h, 1.0 / (40.0 * P["f_t"]))
        max_step = Tn / 12.0
        if self.A:
            max_step = min(max_step, 1.0 / (10.0 * P["f_t"]))
        twin = self.ce > 0
        t, x, q = 0.0, drv.x(0.0) - e0, 0.0
        t_arr = -P["T_st0"]  # a notional earlier arrest
        segs, slips = [], []
        self.aborted = False
        n_calls = 0
        while t < T_end:
            n_calls += 1
            if n_calls > 3000:  # a chattering run (a pilot's bad shaker frequency): give it up
                self.aborted = True
                segs.append(("stick", t, T_end, x, q))
                break
            # ---- stick: closed form, find the breakaway
            xs, qs, t0 = x, q, t
            dmu_x = 0.0
            if self.tex is not None:
                dmu_x = float(np.sum(self.tex[0] * np.sin(self.tex[1] * xs + self.tex[2])))
            tb = None
            tt_prev = None
            tstart = t
            while tstart < T_end and tb is None:
                tt = tstart + h * np.arange(0, 600)
                tt = tt[tt <= T_end] if tt[-1] > T_end else tt
                if tt.size == 0:
                    break
                e = drv.xv(tt) - xs
                qq = qs * np.exp(-(tt - t0) / self.tau_e) if twin else 0.0
                g = np.abs(k * e - self.ce * qq) - np.maximum(self.mu_s(tt - t_arr) + dmu_x, self.mu_floor) * self.N(tt, e)
                idx = np.nonzero(g >= 0.0)[0]
                if idx.size:
                    i = idx[0]
                    if i == 0 and tt_prev is None:
                        tb = tt[0]
                    else:
                        ta_ = tt[i - 1] if i > 0 else tt_prev

                        def gs(s):
                            ee = drv.x(s) - xs
                            qv = qs * math.exp(-(s - t0) / self.tau_e) if twin else 0.0
                            return abs(k * ee - self.ce * qv) - max(float(self.mu_s(s - t_arr)) + dmu_x, self.mu_floor) * self.Nsc(s, ee)

                        tb = brentq(gs, ta_, tt[i], xtol=1e-12 * max(1.0, tt[i]), rtol=1e-12)
                else:
                    tt_prev = tt[-1]
                    tstart = tt[-1] + h
            if tb is None:
                segs.append(("stick", t0, T_end, xs, qs))
                break
            segs.append(("stick", t0, tb, xs, qs))
            qb = qs * math.exp(-(tb - t0) / self.tau_e) if twin else 0.0
            eb = drv.x(tb) - xs
            fnet = k * eb - self.ce * qb
            sgn = 1.0 if fnet >= 0 else -1.0
            slip = dict(tb=tb, Fpk=k * eb, stick=tb - t_arr, Nb=self.Nsc(tb, eb))
            # ---- slip: DOP853 with a terminal event at v = 0
            y0 = [xs, sgn * 1e-7 * Vp, qb]
            tau_e, ce, cd, Nsc = self.tau_e, self.ce, self.cd, self.Nsc
            mu = law.mu
            dx = drv.x

            def rhs(tq, y):
                xx, v, qv = y
                ee = dx(tq) - xx
                # friction opposes the slip's direction until the arrest event (no sign flip inside a
                # slip: the crossing of v = 0 is then clean and found by the event)
                sv = sgn * v
                f = k * ee - cd * v - ce * qv - sgn * mu(sv if sv > 0.0 else 0.0) * Nsc(tq, ee)
                return [v, f / m, (v - qv) / tau_e if twin else 0.0]

            def ev(tq, y):
                return y[1]

            ev.terminal = True
            ev.direction = -sgn
            t_cur, y_cur = tb, y0
            while True:
                t_hi = min(t_cur + 30.0 * Tn, T_end)
                sol = solve_ivp(rhs, (t_cur, t_hi), y_cur, method="DOP853", rtol=1e-8,
                                atol=[1e-10 * Vp * Tn, 1e-10 * Vp, 1e-10 * Vp], events=ev,
                                dense_output=True, max_step=max_step)
                segs.append(("slip", t_cur, sol.t[-1], sol.sol))
                if sol.status == 1 or sol.t[-1] >= T_end:
                    break
                t_cur, y_cur = sol.t[-1], sol.y[:, -1]
            if sol.status != 1:
                break
            ta = float(sol.t_events[0][0])
            ya = sol.y_events[0][0]
            segs[-1] = ("slip", segs[-1][1], ta, sol.sol)
            t, x, q = ta, float(ya[0]), float(ya[2]) if twin else 0.0
            ea = drv.x(ta) - x
            slip.update(ta=ta, Ftr=k * ea, sgn=sgn)
            slips.append(slip)
            t_arr = ta
        return segs, slips

    # truth on a grid
    def truth(self, segs, tg):
        x = np.empty_like(tg)
        v = np.zeros_like(tg)
        q = np.zeros_like(tg)
        starts = np.array([s[1] for s in segs])
        ends = np.array([s[2] for s in segs])
        i0 = np.searchsorted(tg, starts, side="left")
        i1 = np.searchsorted(tg, ends, side="left")
        i1[-1] = tg.size
        for s, a, b in zip(segs, i0, i1):
            if b <= a:
                continue
            if s[0] == "stick":
                x[a:b] = s[3]
                if self.ce > 0:
                    q[a:b] = s[4] * np.exp(-(tg[a:b] - s[1]) / self.tau_e)
            else:
                y = s[3](np.clip(tg[a:b], s[1], s[2]))
                x[a:b], v[a:b], q[a:b] = y[0], y[1], y[2]
        e = self.drive.xv(tg) - x
        return x, v, q, e, self.N(tg, e) * np.ones_like(tg)


# ----------------------------------------------------------------------------------------- measures
def _measure(rig, segs, slips):
    """Effect sizes on the ground truth: drop, twin (decelerating - accelerating, 10-90 % of peak speed)."""
    pk = np.array([s["Fpk"] for s in slips])
    tr = np.array([s["Ftr"] for s in slips])
    D = float(np.median(pk - tr)) if len(slips) else float("nan")
    twins = []
    slipsegs = [s for s in segs if s[0] == "slip"]
    # merge consecutive slip pieces per slip by time
    for sl in slips[1:]:
        pieces = [s for s in slipsegs if s[1] >= sl["tb"] - 1e-15 and s[2] <= sl["ta"] + 1e-15]
        if not pieces:
            continue
        tt = np.linspace(sl["tb"], sl["ta"], 800)
        y = np.empty((3, tt.size))
        for p in pieces:
            mk = (tt >= p[1]) & (tt <= p[2])
            y[:, mk] = p[3](tt[mk])
        x, v, q = y
        e = rig.drive.xv(tt) - x
        R = rig.cd * v + rig.ce * q + np.sign(v) * rig.law.mu_vec(np.abs(v)) * (rig.N(tt, e) * np.ones_like(tt))
        R = R * sl["sgn"]
        va = np.abs(v)
        j = int(np.argmax(va))
        if j < 5 or j > tt.size - 6:
            continue
        u = np.linspace(0.1, 0.9, 17) * va[j]
        acc = np.interp(u, np.maximum.accumulate(va[: j + 1]), R[: j + 1])
        vd, Rd = va[j:][::-1], R[j:][::-1]
        dec = np.interp(u, np.maximum.accumulate(vd), Rd)
        twins.append(float(np.mean(dec - acc)))
    twin = float(np.median(twins)) / D if twins else float("nan")
    st = np.array([s["stick"] for s in slips[1:]])
    pk1 = pk[1:]
    keep = (st > 0) & ((pk - tr)[1:] > 0.3 * D)
    st, pk1 = st[keep], pk1[keep]
    if st.size >= 4 and st.max() / st.min() > 1.3:
        b = np.polyfit(np.log(st), pk1, 1)[0]
        age = float(b * math.log(st.max() / st.min()) / D)
    else:
        age = 0.0
    big = (pk - tr) > 0.3 * D
    tb = np.array([s["tb"] for s in slips])[big]
    f_ss = (tb.size - 1) / (tb[-1] - tb[0]) if tb.size > 2 else float("nan")
    return dict(D=D, twin=twin, age=age, st_ratio=float(st.max() / st.min()) if st.size else 1.0,
                f_ss=float(f_ss), n_slips=int(big.sum()), n_small=int((~big).sum()), peak_sd=float(np.std(pk1) / D) if pk1.size > 2 else 0.0)


def _load_pp(rig, segs, T, fn):
    tg = np.arange(0.0, T, 1.0 / (200.0 * fn))
    _, _, _, _, N = rig.truth(segs, tg)
    n = N[tg.size // 20:]
    return float((n.max() - n.min()) / rig.N0)


# ----------------------------------------------------------------------------------------- build a case
def _physics(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([seed, ci, 20240611])
    fn = math.exp(rng.uniform(math.log(6.0), math.log(300.0)))
    Tn = 1.0 / fn
    w = TWO_PI * fn
    k = math.exp(rng.uniform(math.log(800.0), math.log(20000.0)))
    m = k / w ** 2
    N0 = rng.uniform(3.0, 25.0)
    mu_k = rng.uniform(0.2, 0.4)
    dW = rng.uniform(0.25, 0.45) * mu_k
    gap = rng.uniform(0.04, 0.12) * dW
    D_est = 2.0 * (gap + 0.7 * dW) * N0
    Vp = w * D_est / (2.0 * k)
    law = _Law(rng, mu_k, dW, Vp)
    zeta = rng.uniform(0.005, 0.03)
    P = dict(fn=fn, k=k, m=m, N0=N0, mu_k=mu_k, dW=dW, mu0=law.mu0, mu_s0=law.mu0 + gap, gap=gap,
             c_d=2 * zeta * m * w, zeta=zeta, Vp=Vp, D_est=D_est)
    # a pilot at a constant drive: the actual drop and slip time of this law (the drive is set from them)
    v_try = (D_est / k) / (5.0 * Tn)
    P["T_st0"] = 5.0 * Tn
    pr = _Rig(P, law, _Drive([(40.0 * Tn, v_try)]))
    _, psl = pr.run(40.0 * Tn, 0.85 * mu_k * N0 / k)
    psl = psl[1:]
    D_act = float(np.median([s_["Fpk"] - s_["Ftr"] for s_ in psl]))
    t_slip = float(np.median([s_["ta"] - s_["tb"] for s_ in psl]))
    P["D_pilot"], P["t_slip_over_Tn"] = D_act, t_slip * fn
    e_drop = D_act / k
    spp = float(rng.uniform(20.0, 100.0))
    spp_coarse = float(rng.uniform(10.0, 15.0))
    stepped = case == "static_ageing" or (case == "none" and seed % 8 in (2, 5))
    info = dict(stepped=stepped, holds=False)
    if stepped:
        ratio = rng.uniform(4.0, 8.0)
        if case == "static_ageing" and seed % 2 == 1:
            T_st = rng.uniform(2.5, 4.0) * Tn
            v0 = e_drop / T_st
            hold = 1.3 * (ratio - 1.0) * T_st
            segsd = []
            nblk = int(rng.integers(4, 6))
            for b in range(nblk):
                ncy = int(rng.integers(4, 6))
                segsd.append((ncy * (T_st + t_slip) + (0.5 * Tn if b == 0 else 0.0), v0))
                segsd.append((hold, 0.0))
            segsd.append((4 * (T_st + t_slip), v0))
            info.update(holds=True, hold_s=hold)
            v_mean = v0
        else:
            T_slow = max(rng.uniform(9.0, 15.0), 2.0 * ratio) * Tn
            vs = e_drop / T_slow
            vf = vs * ratio
            T_fast = T_slow / ratio
            segsd = []
            nlev = int(rng.choice([4, 5]))
            first_slow = bool(rng.integers(0, 2))
            for L in range(nlev):
                slow = (L % 2 == 0) == first_slow
                if slow:
                    segsd.append((int(rng.integers(3, 5)) * (T_slow + t_slip), vs))
                else:
                    segsd.append((int(rng.integers(5, 8)) * (T_fast + t_slip), vf))
            v_mean = vs
        info["ratio"] = float(ratio)
        drive = _Drive(segsd)
        T = drive.T
        P["T_st0"] = 3 * Tn
    else:
        T_st = rng.uniform(3.0, 10.0) * Tn
        v0 = e_drop / T_st
        ncyc = int(rng.integers(14, 40))
        T = ncyc * (T_st + t_slip) + T_st
        drive = _Drive([(T, v0)])
        v_mean = v0
        P["T_st0"] = T_st
    P["v0"] = v_mean
    P["T"] = T
    e0 = 0.85 * mu_k * N0 / k
    P["e0"] = e0
    return rng, P, law, drive, spp, spp_coarse, info


def _simulate(case, seed):
    rng, P, law, drive, spp, spp_coarse, info = _physics(case, seed)
    fn, Tn, T = P["fn"], 1.0 / P["fn"], P["T"]
    extra = {}
    if case == "twin_branch":
        P["tau_e"] = rng.uniform(0.12, 0.3) * Tn
        target = rng.uniform(0.13, 0.20)
        P["c_e"] = 0.06 / (P["tau_e"] * TWO_PI * fn) * 2 * P["m"] * TWO_PI * fn
        for _ in range(2):
            rig = _Rig(P, law, drive)
            segs, slips = rig.run(min(T, 12 * (T / 30)), P["e0"])
            tw = _measure(rig, segs, slips)["twin"]
            if not np.isfinite(tw) or tw <= 0:
                break
            P["c_e"] *= min(max(target / tw, 0.3), 3.0)
        extra["twin_target"] = target
    if case == "load_variation":
        target = rng.uniform(0.16, 0.28)
        P["e_ref"] = P["mu_k"] * P["N0"] / P["k"]
        e_drop = P["D_est"] / P["k"]
        P["c_load"] = target / (2.0 * e_drop)
        for _ in range(2):
            rig = _Rig(P, law, drive)
            segs, slips = rig.run(T * 0.4, P["e0"])
            pp = _load_pp(rig, segs, T * 0.4, fn)
            P["c_load"] *= min(max(target / pp, 0.4), 2.5) ** 0.8
        extra["load_target"] = target
    if case == "static_ageing":
        P["tau_age"] = rng.uniform(0.05, 0.3) * Tn
        target = rng.uniform(0.10, 0.16)
        rig = _Rig(P, law, drive)
        segs, slips = rig.run(T, P["e0"])
        mm = _measure(rig, segs, slips)
        st = np.array([s["stick"] for s in slips[1:]])
        lo, hi = np.percentile(st, 5), np.percentile(st, 95)
        dmu = (math.asinh(hi / P["tau_age"]) - math.asinh(lo / P["tau_age"])) * P["N0"]
        P["age_off"] = math.asinh(lo / P["tau_age"])  # mu_s(t_shortest stick) = mu_s0
        P["b_age"] = target * mm["D"] / dmu
        for _ in range(2):
            rig = _Rig(P, law, drive)
            segs, slips = rig.run(T, P["e0"])
            ag = _measure(rig, segs, slips)["age"]
            if ag > 0:
                P["b_age"] *= min(max(target / ag, 0.5), 2.0)
        extra["age_target"] = target
    if case == "drive_modulation":
        rig = _Rig(P, law, drive)
        segs, slips = rig.run(min(T, 10 * T / 25), P["e0"])
        f_ss0 = _measure(rig, segs, slips)["f_ss"]
        a = rng.uniform(0.22, 0.42)
        r = rng.uniform(0.2, 0.38)
        fm = r * f_ss0
        phi = rng.uniform(0, TWO_PI)
        drive = _Drive(v0=P["v0"], a=a, fm=fm, phi=phi)
        P.update(a_mod=a, fm=fm, phi_mod=phi, f_ss0=f_ss0)
        # at least 3 modulation periods, 10-60 cycles
        T = max(T, 3.2 / fm)
        T = min(T, 58.0 / f_ss0)
        P["T"] = T
    if case == "triggering":
        P["A_t"] = rng.uniform(0.035, 0.075)
        # a ground counterface's texture: the static level varies along the track (sd 2.5-4 % of the drop),
        # so a breakaway locked to the shaker's troughs skips one trough more or less from stick to stick
        ed = P["D_pilot"] / P["k"]
        amp = rng.uniform(0.025, 0.04) * P["D_pilot"] / P["N0"] * math.sqrt(2.0 / 4.0)
        P["texture"] = (np.full(4, amp), TWO_PI / (ed * rng.uniform(0.37, 1.3, 4)), rng.uniform(0, TWO_PI, 4))
        extra["texture_sd_over_Dpilot"] = amp * math.sqrt(2.0) * P["N0"] / P["D_pilot"]
        r0 = rng.uniform(2.8, 7.0)
        T_p = T  # the pilots are the record itself: the final run reproduces the chosen one

        def ratio_at(ft):
            P["f_t"] = ft
            rig_ = _Rig(P, law, drive)
            sg_, sl_ = rig_.run(T_p, P["e0"])
            if rig_.aborted or len(sl_) < 6:
                return float("nan")
            return ft / _measure(rig_, sg_, sl_)["f_ss"]

        ft = r0 * fn
        R = ratio_at(ft)
        attempt = 1
        while not np.isfinite(R) and attempt < 4:
            ft *= 1.13
            R = ratio_at(ft)
            attempt += 1
        if np.isfinite(R) and abs(R - round(R)) < 0.17:
            # the breakaways lock 1:n to the shaker: bisect f_t between the n-lock and the (n+1)-lock
            n_ = round(R)
            lo, hi = ft, ft * (n_ + 1.0) / n_
            best = (abs(R - round(R)), ft, R)
            for _ in range(7):
                mid = 0.5 * (lo + hi)
                Rm = ratio_at(mid)
                attempt += 1
                if not np.isfinite(Rm):
                    lo = mid
                    continue
                if abs(Rm - round(Rm)) > best[0]:
                    best = (abs(Rm - round(Rm)), mid, Rm)
                if abs(Rm - round(Rm)) >= 0.2:
                    break
                if Rm < n_ + 0.5:
                    lo = mid
                else:
                    hi = mid
            ft = best[1]
        P["f_t"] = ft
        extra["trigger_attempts"] = attempt
    rig = _Rig(P, law, drive)
    segs, slips = rig.run(T, P["e0"])
    mm = _measure(rig, segs, slips)
    if mm["n_slips"] < 12 and not info["stepped"] and case != "drive_modulation":
        T *= 15.0 / max(mm["n_slips"], 3)
        P["T"] = T
        drive = _Drive([(T, P["v0"])])
        rig = _Rig(P, law, drive)
        segs, slips = rig.run(T, P["e0"])
        mm = _measure(rig, segs, slips)
    mm["load_pp"] = _load_pp(rig, segs, T, fn)
    if case == "triggering":
        mm["ft_over_fss"] = P["f_t"] / mm["f_ss"]
        mm["ft_over_fn"] = P["f_t"] / fn
    if case == "drive_modulation":
        mm["fm_over_fss"] = P["fm"] / mm["f_ss"]
    # the law's own twin and ageing (what a record without the departure would have), for reference
    mm["law_twin"] = 0.0 if case != "twin_branch" else mm["twin"]
    return rng, P, law, drive, rig, segs, slips, mm, spp, spp_coarse, info, extra


# ----------------------------------------------------------------------------------------- writing
def _fmt(a, nd):
    return np.char.mod("%." + str(nd) + "g", a)


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES or nuisance not in NUISANCES:
        raise ValueError((case, nuisance))
    ci, ni = CASES.index(case), NUISANCES.index(nuisance)
    rng, P, law, drive, rig, segs, slips, mm, spp, spp_c, info, extra = _simulate(case, seed)
    fn, T, k = P["fn"], P["T"], P["k"]
    # instrument choices, drawn from their own stream (not the nuisance)
    irng = np.random.default_rng([seed, ci, 777])
    style = (seed + ci) % 3
    if case == "load_variation":
        has_N = seed % 8 != 6
    elif case == "triggering":
        has_N = True
    else:
        has_N = seed % 4 == 1
    if case == "drive_modulation":
        has_drive = False
    elif info["stepped"]:
        has_drive = True
    else:
        has_drive = seed % 2 == 0
    sp = spp_c if nuisance == "coarse" else spp
    fs = sp * fn
    fine = 4
    tg = np.arange(0.0, T, 1.0 / (fs * fine))
    x, v, q, e, N = rig.truth(segs, tg)
    b, a = cheby1(2, 0.5, 0.35 * fs, fs=fs * fine)
    F = k * e
    Ff = lfilter(b, a, F - F[0]) + F[0]
    Nf = lfilter(b, a, N - N[0]) + N[0]
    sl = slice(0, None, fine)
    t = tg[sl]
    Fm, Nm, xd, vd = Ff[sl], Nf[sl], drive.xv(t), drive.vv(t)
    D = mm["D"]
    n = t.size
    sig_w = irng.uniform(0.0015, 0.005) * D
    g_n = irng.uniform(0.0005, 0.0015)
    Fm = Fm * (1.0 + g_n * irng.standard_normal(n)) + sig_w * irng.standard_normal(n)
    Nm = Nm * (1.0 + 0.5 * g_n * irng.standard_normal(n)) + 0.002 * P["N0"] * irng.standard_normal(n)
    enc = np.round(xd / 1e-7) * 1e-7  # 0.1 um counts (m)
    # nuisances, on the main channel (in N here)
    nrng = np.random.default_rng([seed, ci, ni, 4242])
    nz = {}
    if nuisance == "hum":
        f0 = float(nrng.choice([50.0, 60.0]))
        amp = nrng.uniform(0.01, 0.05) * D
        hn = int(nrng.choice([2, 3]))
        ph = nrng.uniform(0, TWO_PI, 2)
        Fm = Fm + amp * (np.sin(TWO_PI * f0 * t + ph[0]) + 0.35 * np.sin(TWO_PI * hn * f0 * t + ph[1]))
        nz = dict(hum_hz=f0, hum_amp_over_D=amp / D, harmonic=hn)
    elif nuisance == "drift":
        amp = nrng.uniform(0.01, 0.03) * D
        tau = t / t[-1]
        shape = (1.0 - np.exp(-2.5 * tau)) / (1.0 - math.exp(-2.5))
        Fm = Fm + float(nrng.choice([-1, 1])) * amp * shape
        nz = dict(drift_over_D=amp / D)
    elif nuisance == "spikes":
        frac = nrng.uniform(0.0005, 0.005)
        ns = max(2, int(frac * n))
        idx = nrng.choice(n, ns, replace=False)
        Fm = Fm.copy()
        Fm[idx] += nrng.uniform(-0.3, 0.3, ns) * D
        nz = dict(spike_fraction=ns / n)
    elif nuisance == "quantisation":
        step = nrng.uniform(0.002, 0.01) * D
        Fm = np.round(Fm / step) * step
        nz = dict(step_over_D=step / D)
    fn_given = fn
    if nuisance == "fn_off":
        fn_given = fn * (1.0 + float(nrng.choice([-0.05, 0.05])))
    elif seed % 8 == 5 and case != "triggering":
        fn_given = None
    args = []
    if fn_given is not None:
        args += ["--fn", "%.6g" % fn_given]
    # ---- write
    os.makedirs(outdir, exist_ok=True)
    base = "%s_%s_s%d_%s" % (NAME, case, seed, nuisance)
    cols, names, seps = [], [], None
    if style == 0:
        path = os.path.join(os.path.abspath(outdir), base + ".csv")
        cols.append(_fmt(t * 1e3, 10))
        names.append("Time [ms]")
        cols.append(_fmt(Fm * 1e3, 7))
        names.append("Friction force [mN]")
        if has_N:
            cols.append(_fmt(Nm * 1e3, 7))
            names.append("Normal preload [mN]")
        if has_drive:
            cols.append(_fmt(enc * 1e6, 9))
            names.append("Carriage position [um]")
        args += ["--stiffness", "%.6g" % k]
        lines = ["Instrument: MPT-2 magnetic preload tribometer",
                 "Operator: lab 3",
                 "Sample rate: %.6g Hz" % fs,
                 "Channels: %d" % len(names),
                 ";".join(names)]
        body = [";".join(r) for r in zip(*cols)]
        text = "\n".join(lines + body).replace(".", ",") if False else None
        # decimal comma on the numbers only (and the sample-rate line)
        lines[2] = lines[2].replace(".", ",")
        body = [r.replace(".", ",") for r in body]
        text = "\n".join(lines + body) + "\n"
    elif style == 1:
        path = os.path.join(os.path.abspath(outdir), base + ".txt")
        cols.append(_fmt(t, 10))
        names.append("Time (s)")
        cols.append(_fmt(Fm, 7))
        names.append("Tangential force (N)")
        if has_N:
            cols.append(_fmt(Nm, 7))
            names.append("Normal force (N)")
        if has_drive:
            cols.append(_fmt(vd * 1e3, 7))
            names.append("Drive speed (mm/s)")
        args += ["--stiffness", "%.6g" % k]
        text = "\t".join(names) + "\n" + "\n".join("\t".join(r) for r in zip(*cols)) + "\n"
    else:
        path = os.path.join(os.path.abspath(outdir), base + ".dat")
        cols.append(_fmt(t, 10))
        names.append("time")
        units = ["s"]
        cols.append(_fmt(Fm / k * 1e3, 7))
        names.append("flexure_deflection")
        units.append("mm")
        if has_N:
            s_y = irng.uniform(0.002, 0.01)  # mm per N of the load gauge
            y0 = irng.uniform(-0.2, 0.2)
            cols.append(_fmt(y0 + s_y * Nm, 7))
            names.append("normal_load_gauge")
            units.append("mm")
        if has_drive:
            cols.append(_fmt(vd * 1e3, 7))
            names.append("drive_speed")
            units.append("mm/s")
        w_ = [max(len(a_), len(b_), 12) for a_, b_ in zip(names, units)]
        hdr = "  ".join(a_.ljust(c_) for a_, c_ in zip(names, w_))
        unr = "  ".join(a_.ljust(c_) for a_, c_ in zip(units, w_))
        text = hdr.rstrip() + "\n" + unr.rstrip() + "\n" + "\n".join("  ".join(r) for r in zip(*cols)) + "\n"
    if not has_drive:
        args += ["--v0", "%.6g" % (P["v0"] * 1e3)]
    with open(path, "w") as fh:
        fh.write(text)
    params = dict(style=style, columns=names, samples=int(n), samples_per_period=sp, fs_hz=fs,
                  fn=fn, k_N_per_m=k, m_kg=P["m"], N0_N=P["N0"], zeta=P["zeta"], mu_k=P["mu_k"],
                  weakening_dW=P["dW"], mu0_fit=P["mu0"], mu_s0=P["mu_s0"], static_gap=P["gap"],
                  law_table_v_m_s=law.table[0], law_table_mu=law.table[1], law_poly_in_s=law.c,
                  law_v_top_m_s=law.v_top, v0_mm_s=P["v0"] * 1e3, T_s=T, has_normal=has_N,
                  has_drive=has_drive, stepped_drive=info["stepped"], holds=info["holds"],
                  drive_ratio=info.get("ratio"), sensor="cheby1 n=2 0.5 dB at 0.35 fs",
                  noise_white_over_D=sig_w / D, gain_noise=g_n, nuisance_params=nz,
                  drop_N=D, twin_over_D=mm["twin"], ageing_over_D=mm["age"], stick_ratio=mm["st_ratio"],
                  load_pp_over_N0=mm["load_pp"], f_ss_hz=mm["f_ss"], fn_over_fss=fn / mm["f_ss"],
                  cycles=mm["n_slips"], peak_sd_over_D=mm["peak_sd"])
    if "texture" in P:
        params["texture_wavelength_m"] = (TWO_PI / P["texture"][1]).tolist()
    for key in ("c_e", "tau_e", "c_load", "e_ref", "b_age", "tau_age", "A_t", "f_t", "a_mod", "fm",
                "phi_mod", "f_ss0"):
        if key in P:
            params[key] = P[key]
    for key in ("ft_over_fss", "ft_over_fn", "fm_over_fss"):
        if key in mm:
            params[key] = mm[key]
    if "tau_e" in P:
        params["tau_e_over_Tn"] = P["tau_e"] * fn
        params["zeta_eddy"] = P["c_e"] / (2 * P["m"] * TWO_PI * fn)
    params.update(extra)
    params = _clean(json.loads(json.dumps(params, default=float)))
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=path, args=args,
                fn_true=float(fn), fn_given=None if fn_given is None else float(fn_given), params=params)


def _clean(o):
    if isinstance(o, dict):
        return {k_: _clean(v_) for k_, v_ in o.items()}
    if isinstance(o, list):
        return [_clean(v_) for v_ in o]
    if isinstance(o, float) and not math.isfinite(o):
        return None
    return o


# ----------------------------------------------------------------------------------------- self-check
def _load(path):
    with open(path) as fh:
        lines = fh.read().splitlines()
    if path.endswith(".csv"):
        i = next(j for j, L in enumerate(lines) if L.startswith("Time"))
        rows = [L.replace(",", ".").split(";") for L in lines[i + 1:]]
        names = lines[i].split(";")
    elif path.endswith(".txt"):
        names = lines[0].split("\t")
        rows = [L.split("\t") for L in lines[1:]]
    else:
        names = lines[0].split()
        rows = [L.split() for L in lines[2:]]
    arr = np.array(rows, float)
    return names, arr


def _selfcheck(outdir):
    import time
    rows = []
    ok = True
    for case in CASES:
        for seed in range(8):
            nu = NUISANCES[seed % 7]
            t0 = time.time()
            r = write_record(case, seed, outdir, nu)
            dt = time.time() - t0
            json.dumps(r, allow_nan=False)
            names, arr = _load(r["file"])
            fin = bool(np.all(np.isfinite(arr))) and arr.shape[1] == len(names) and arr.shape[0] > 500
            tmono = bool(np.all(np.diff(arr[:, 0]) > 0))
            p = r["params"]
            if case == "none":
                size = "twin %+.4f age %+.4f" % (p["twin_over_D"], p["ageing_over_D"])
                good = abs(p["twin_over_D"]) < 0.01 and abs(p["ageing_over_D"]) < 0.03
            elif case == "load_variation":
                size = "load p-p %.3f" % p["load_pp_over_N0"]
                good = 0.12 <= p["load_pp_over_N0"] <= 0.35
            elif case == "twin_branch":
                size = "twin %+.3f" % p["twin_over_D"]
                good = 0.10 <= p["twin_over_D"] <= 0.25
            elif case == "static_ageing":
                size = "age %+.3f over %.1fx" % (p["ageing_over_D"], p["stick_ratio"])
                good = 0.08 <= p["ageing_over_D"] <= 0.20 and p["stick_ratio"] >= 3.5
            elif case == "triggering":
                rr = p["ft_over_fss"]
                size = "A %.3f ft/fn %.2f ft/fss %.2f" % (p["A_t"], p["ft_over_fn"], rr)
                good = abs(rr - round(rr)) >= 0.15
            else:
                size = "a %.2f fm/fss %.2f" % (p["a_mod"], p["fm_over_fss"])
                good = 0.15 <= p["fm_over_fss"] <= 0.45
            good = good and fin and tmono and 10 <= p["cycles"] <= 60
            ok &= good
            rows.append((case, seed, nu, os.path.basename(r["file"])[-4:], p["fn"], p["samples_per_period"],
                         p["cycles"], p["samples"], size, "ok" if good else "CHECK", dt, " ".join(r["args"])))
            print("%-16s %d %-12s %s fn %7.2f spp %5.1f cyc %2d n %6d | %-34s %-5s %4.1fs | %s" % rows[-1],
                  flush=True)
    return ok, rows


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "/tmp/magnet_table_out"
    ok, _ = _selfcheck(out)
    print("ALL OK" if ok else "SOME CHECKS FAILED")
