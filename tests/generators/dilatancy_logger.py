"""Dilatant interlayer on a spring-slider rig, written by a stand-alone data logger or a Python DAQ script.

Independent generator of "measured" stick-slip records for `lieng diagnose` (written without reading the
diagnosis code). A slider of mass m under a normal load N is dragged through a spring k by a stage at v0;
fn = sqrt(k/m)/2pi is 5-500 Hz; 14-34 stick-slip cycles a record.

Friction law (slip, v > 0): F = N [mu_k + Dm (1 - tanh(sqrt(v/vs))) + cv v] + N gam phi: a Coulomb level with a
**tanh-of-square-root weakening** (infinitely steep at v = 0+, Dm 0.06-0.14, vs 0.4-1.2 of the pilot's peak slip
speed) and a weak viscous term, plus (twin_branch only) a **Segall-Rice dilatancy state** phi of a granular
interlayer: dphi/dt = (v/L)(v/(v + v_p) - phi) in slip (L 0.25-0.5 of the slip distance), compacting
exponentially in stick (tau_c 0.25-0.4 Tn); the dilated layer raises the decelerating branch. A Coulomb static
limit N mu_s with mu_s = mu_s0 + beta t_st/(t_st + tau_a) (hyperbolic, Michaelis-Menten-like contact growth;
beta = 0 outside static_ageing); mu_s0 3-8 % of N above mu(0+), scattered per stick (sd 0.4-0.8 % of
mu_s0 - mu_k: peak sd 0.2-0.8 % of the drop). A structural dashpot to ground (zeta 0.01-0.03).

Stick handling: a **Leine-type switch model with exponential capture**: when the sliding speed falls below
eta = 0.05 v0 the slider is captured, its speed decaying as eta exp(-t/tau) (tau = Tn/100, solved in closed form),
the friction being whatever holds it; it breaks away when the spring force reaches the static limit (checked on a
coarse grid, Tn/10 or 1/16 of a shaker period, then bisection on the closed-form stick).
Integrator: own fixed-step **Kutta third-order Runge-Kutta** at Tn/200 in slip; nodes interpolated by a cubic
Hermite spline (positions and speeds) onto a grid 4-8x the record's rate, a **4-pole critically damped sensor
low-pass** (four identical one-poles, fc 6-12 fn, bilinear) and decimation; white noise 0.2-0.6 % of the drop,
the normal channel with 0.15 % of N0.

Departures (each case alone): load_variation = a load servo fed back from the spring's tension (misconfigured
force-control loop), N = N0 + g (k e - F_mid), g of either sign tuned to 14-30 % p-p of N0, the normal channel
recorded on 7 of 8 seeds; twin_branch = dilatancy (gam tuned to +12..+22 % of the drop, measured at the contact on
the true speed, decelerating minus accelerating at 20-80 % of each slip's peak speed); static_ageing = beta tuned
to 10-17 % of the drop between the longest and the shortest third of the sticks, with drive steps 4-8x (even
seeds) or holds of 1-7 cycles (odd seeds), the drive recorded; triggering = N0 (1 + A sin 2 pi f_t t), A 3-8 %,
f_t 2.5-8 fn redrawn until the record's f_t/f_ss is >= 0.15 from an integer, recorded in the normal channel;
drive_modulation = v0 (1 + a sin(2 pi fm t + ph)), a 0.2-0.45, fm 0.15-0.45 of the record's f_ss, not recorded
(`--v0` the mean). `none`: constant load and drive (seeds 3 mod 4: the drive steps 3-5x, recorded); the law is
exactly single-valued (twin 0 at the contact) and the static limit has no ageing (peak growth 0 within 1e-6).

Files (two export styles, neither in the README's list):
* **Bench data-logger CSV** (Graphtec-midi-LOGGER-like, even seeds): quoted `"key","value"` metadata lines, a
  blank line, header `No.,Time,<channels>` and a units row, time as **date-time stamps** `2024-03-01
  10:22:01.250` at 1, 2 or 5 ms sampling (fs 1000/500/200 Hz, fn = fs / samples-per-period). Force records:
  `Friction force` (N or mN), `Normal load` (N), `Stage position` (mm); displacement records: `Spring extension`
  (mm), `Normal deflection` (mm, affine), `Drive speed` (mm/s).
* **NumPy .npz** from a Python acquisition script (odd seeds): force records `time_s`, `friction_mN` or
  `friction_N`, `normal_N`, `stage_position_um`; displacement records `t`, `x`, `y`, `v0` (s, mm, mm, mm/s).
`--fn` on 7 of 8 seeds (omitted on seeds 5 mod 8 except triggering / fn_off), `--stiffness` (N/m) on force
records, `--v0` (mm/s) when no drive column.
"""

import bisect
import datetime
import json
import math
import os
import sys

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.signal import bilinear, lfilter, lfilter_zi

NAME = "dilatancy_logger"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
_CASE_ID = {c: i for i, c in enumerate(CASES)}
_NUI_ID = {c: i for i, c in enumerate(NUISANCES)}


# ----------------------------------------------------------------------------------------------- drive
class _Drive:
    """x_d(t), v_d(t): constant, piecewise-constant (knots) or sinusoidally modulated."""

    def __init__(self, v0, knots=None, mod=None):
        self.v0 = v0
        self.knots = knots  # list of (t_start, v)
        self.mod = mod  # (a, fm, ph)
        if knots:
            self.T = [k[0] for k in knots]
            self.V = [k[1] for k in knots]
            P = [0.0]
            for i in range(1, len(knots)):
                P.append(P[-1] + self.V[i - 1] * (self.T[i] - self.T[i - 1]))
            self.P = P

    def x(self, t):
        if self.knots:
            i = max(bisect.bisect_right(self.T, t) - 1, 0)
            return self.P[i] + self.V[i] * (t - self.T[i])
        if self.mod:
            a, fm, ph = self.mod
            w = 2 * math.pi * fm
            return self.v0 * (t - a / w * (math.cos(w * t + ph) - math.cos(ph)))
        return self.v0 * t

    def xv(self, t):
        t = np.asarray(t, float)
        if self.knots:
            i = np.clip(np.searchsorted(self.T, t, side="right") - 1, 0, None)
            T, V, P = np.array(self.T), np.array(self.V), np.array(self.P)
            return P[i] + V[i] * (t - T[i]), V[i]
        if self.mod:
            a, fm, ph = self.mod
            w = 2 * math.pi * fm
            return (self.v0 * (t - a / w * (np.cos(w * t + ph) - math.cos(ph))),
                    self.v0 * (1 + a * np.sin(w * t + ph)))
        return self.v0 * t, np.full_like(t, self.v0)


# ----------------------------------------------------------------------------------------- simulation
def _simulate(P, drive, t_end, load=None, trig=None, beta=0.0, gam=0.0):
    srng = np.random.default_rng(P["scatter_seed"])
    scat = P["scatter"]
    """Returns node arrays and the list of slips. P: dict of the rig."""
    m, k, c = P["m"], P["k"], P["c"]
    N0, muk, Dm, vs, cv, mus0 = P["N0"], P["muk"], P["Dm"], P["vs"], P["cv"], P["mus0"]
    Tn = 1.0 / P["fn"]
    tau, eta = Tn / 100.0, 0.05 * P["v0"]
    tau_a, L, vp, tauc = P["tau_a"], P["L"], P["vp"], P["tauc"]
    h = Tn / 200.0
    hs = Tn / 10.0
    if trig:
        hs = min(hs, 1.0 / trig[1] / 16.0)
    if drive.mod:
        hs = min(hs, 1.0 / drive.mod[1] / 60.0)
    sqrt, tanh, sin = math.sqrt, math.tanh, math.sin
    xd_f = drive.x

    if load:
        g, Fref = load

        def Nf(t, e):
            return max(N0 + g * (k * e - Fref), 0.1 * N0)
    elif trig:
        A, ft = trig
        wt = 2 * math.pi * ft

        def Nf(t, e):
            return N0 * (1.0 + A * sin(wt * t))
    else:
        def Nf(t, e):
            return N0

    def rhs(t, x, v, ph):
        e = xd_f(t) - x
        N = Nf(t, e)
        vv = v if v > 0.0 else 0.0
        Ff = N * (muk + Dm * (1.0 - tanh(sqrt(vv / vs))) + cv * vv + gam * ph)
        return v, (k * e - c * v - Ff) / m, (vv / L) * (vv / (vv + vp) - ph), Ff, N

    TN, XN, VN, PH, FF, NN = [], [], [], [], [], []
    slips = []  # dicts: t_break, F_break, t_stick, t_arrest, i0, i1 (node indices of the slip)
    t, x, v, ph = 0.0, 0.0, 0.0, 0.0
    t_cap, x_cap, v_cap, ph_cap = 0.0, 0.0, 0.0, 0.0
    mode = "stick"
    while t < t_end:
        if mode == "stick":
            xi = scat * srng.standard_normal()

            def stick_state(tt):
                s = tt - t_cap
                ex = math.exp(-s / tau)
                return x_cap + v_cap * tau * (1.0 - ex), v_cap * ex, ph_cap * math.exp(-s / tauc)

            def gfun(tt):
                xx = stick_state(tt)[0]
                e = xd_f(tt) - xx
                st = tt - t_cap
                return k * e - Nf(tt, e) * (mus0 * (1.0 + xi) + beta * st / (st + tau_a))

            tt = t
            broke = False
            while tt < t_end:
                t1 = tt + hs
                g1 = gfun(t1)
                xx, vv, pp = stick_state(t1)
                if g1 >= 0.0:
                    lo, hi = tt, t1
                    for _ in range(40):
                        mid = 0.5 * (lo + hi)
                        if gfun(mid) >= 0.0:
                            hi = mid
                        else:
                            lo = mid
                    t1 = hi
                    xx, vv, pp = stick_state(t1)
                    broke = True
                e = xd_f(t1) - xx
                N = Nf(t1, e)
                TN.append(t1); XN.append(xx); VN.append(vv); PH.append(pp); FF.append(k * e); NN.append(N)
                tt = t1
                if broke:
                    break
            t, x, v, ph = tt, xx, vv, pp
            if not broke:
                break
            st = t - t_cap
            slips.append(dict(t_break=t, F_break=k * (xd_f(t) - x), t_stick=st, i0=len(TN) - 1))
            mode = "slip"
        else:
            d1 = rhs(t, x, v, ph)
            if not TN or TN[-1] < t:
                TN.append(t); XN.append(x); VN.append(v); PH.append(ph); FF.append(d1[3]); NN.append(d1[4])
            else:
                FF[-1] = d1[3]
            while True:
                d1 = rhs(t, x, v, ph)
                h2 = 0.5 * h
                d2 = rhs(t + h2, x + h2 * d1[0], v + h2 * d1[1], ph + h2 * d1[2])
                d3 = rhs(t + h, x - h * d1[0] + 2 * h * d2[0], v - h * d1[1] + 2 * h * d2[1],
                         ph - h * d1[2] + 2 * h * d2[2])
                xn = x + h / 6.0 * (d1[0] + 4 * d2[0] + d3[0])
                vn = v + h / 6.0 * (d1[1] + 4 * d2[1] + d3[1])
                pn = ph + h / 6.0 * (d1[2] + 4 * d2[2] + d3[2])
                moving_up = vn > v
                if vn <= eta and not (moving_up or v < eta):
                    s = (v - eta) / (v - vn)
                    ta = t + s * h
                    x = x + s * (xn - x)
                    ph = ph + s * (pn - ph)
                    v = eta
                    t = ta
                    dd = rhs(t, x, v, ph)
                    TN.append(t); XN.append(x); VN.append(v); PH.append(ph); FF.append(dd[3]); NN.append(dd[4])
                    break
                t, x, v, ph = t + h, xn, vn, pn
                dd = rhs(t, x, v, ph)
                TN.append(t); XN.append(x); VN.append(v); PH.append(ph); FF.append(dd[3]); NN.append(dd[4])
                if t >= t_end:
                    break
            slips[-1]["t_arrest"] = t
            slips[-1]["i1"] = len(TN) - 1
            t_cap, x_cap, v_cap, ph_cap = t, x, v, ph
            mode = "stick"
    A = {n: np.array(a) for n, a in zip(("t", "x", "v", "phi", "Ff", "N"), (TN, XN, VN, PH, FF, NN))}
    return A, [s for s in slips if "t_arrest" in s]


# -------------------------------------------------------------------------------------- measurements
def _measure(A, slips, drive, k, t0, t1, N0):
    """Ground-truth sizes over the record window [t0, t1]."""
    S = [s for s in slips if t0 <= s["t_break"] and s["t_arrest"] <= t1]
    t = A["t"]
    xd = drive.xv(t)[0]
    Fs = k * (xd - A["x"])
    drops, twins = [], []
    for s in S:
        i0, i1 = s["i0"], s["i1"]
        Fmin = Fs[i0:i1 + 1].min()
        drops.append(s["F_break"] - Fmin)
    D = float(np.mean(drops)) if drops else float("nan")
    for s in S:
        i0, i1 = s["i0"], s["i1"]
        v = A["v"][i0:i1 + 1]
        mu = A["Ff"][i0:i1 + 1] / A["N"][i0:i1 + 1] * N0
        j = int(np.argmax(v))
        if j < 4 or len(v) - j < 4:
            continue
        va, fa = v[:j + 1], mu[:j + 1]
        vd, fd = v[j:][::-1], mu[j:][::-1]
        if np.any(np.diff(va) <= 0) or np.any(np.diff(vd) <= 0):
            oka = np.r_[True, np.diff(np.maximum.accumulate(va)) > 0]
            okd = np.r_[True, np.diff(np.maximum.accumulate(vd)) > 0]
            va, fa, vd, fd = va[oka], fa[oka], vd[okd], fd[okd]
        q = np.linspace(0.2, 0.8, 25) * v[j]
        twins.append(np.mean(np.interp(q, vd, fd) - np.interp(q, va, fa)) / D)
    st = np.array([s["t_stick"] for s in S])
    pk = np.array([s["F_break"] for s in S])
    tb = np.array([s["t_break"] for s in S])
    fss = (len(tb) - 1) / (tb[-1] - tb[0]) if len(tb) > 2 else float("nan")
    age = 0.0
    if len(st) >= 6:
        o = np.argsort(st)
        n3 = max(len(st) // 3, 2)
        age = float((pk[o[-n3:]].mean() - pk[o[:n3]].mean()) / D)
    return dict(n_slips=len(S), drop_N=D, f_ss=float(fss), twin=float(np.median(twins)) if twins else 0.0,
                ageing=age, stick_ratio=float(st.max() / st.min()) if len(st) else 1.0,
                peak_sd=float(pk.std() / D) if len(pk) else 0.0)


# ---------------------------------------------------------------------------------------------- writer
def _four_pole(y, fc, fs):
    b1, a1 = bilinear([1.0], [1.0 / (2 * math.pi * fc), 1.0], fs)
    out = y
    for _ in range(4):
        out = lfilter(b1, a1, out, zi=lfilter_zi(b1, a1) * out[0])[0]
    return out


def _fmt(v, nd):
    return f"{v:.{nd}f}"


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES or nuisance not in NUISANCES:
        raise ValueError(f"unknown case/nuisance {case}/{nuisance}")
    rng = np.random.default_rng([20250611, _CASE_ID[case], int(seed)])
    nrng = np.random.default_rng([20250612, _CASE_ID[case], int(seed), _NUI_ID[nuisance]])
    style = "logger" if seed % 2 == 0 else "npz"
    force_rec = (seed % 8) in (0, 1, 3, 4, 6) or case == "static_ageing" and seed % 2 == 0
    coarse = nuisance == "coarse"
    # ---- rig: physics independent of the nuisance (spp is a recording choice, fn is not redrawn)
    if style == "logger":
        fs = float(rng.choice([1000.0, 500.0, 200.0]))
        spp_phys = float(rng.uniform(20, 100))
        fn = fs / spp_phys
        if fn < 5.0:
            fn = float(rng.uniform(5.0, 8.0))
    else:
        fn = float(math.exp(rng.uniform(math.log(20), math.log(500))))
        spp_phys = float(rng.uniform(20, 100))
        fs = fn * spp_phys
    if coarse:
        spp = float(nrng.uniform(10, 15))
        if style == "logger":
            fs = max(f for f in (1000.0, 500.0, 200.0, 100.0, 50.0) if f / fn <= 15.0) if fn * 10 <= 1000 else 1000.0
            spp = fs / fn
        else:
            fs = fn * spp
    else:
        spp = fs / fn
    w = 2 * math.pi * fn
    m = float(rng.uniform(0.05, 1.5))
    k = m * w * w
    N0 = float(rng.uniform(5, 60))
    muk = float(rng.uniform(0.2, 0.4))
    Dm = float(rng.uniform(0.06, 0.14))
    mus0 = muk + Dm + float(rng.uniform(0.03, 0.08))
    zeta = float(rng.uniform(0.01, 0.03))
    dF = N0 * (mus0 - muk)
    vslip = dF / (m * w)
    r_st = float(rng.uniform(3.0, 8.0))
    v0 = 2 * dF / (k * r_st / fn)
    P = dict(m=m, k=k, c=2 * zeta * m * w, N0=N0, muk=muk, Dm=Dm, mus0=mus0, fn=fn, v0=v0,
             vs=float(rng.uniform(0.4, 1.2)) * vslip, cv=float(rng.uniform(0.0, 0.02)) / vslip,
             scatter=float(rng.uniform(0.004, 0.008)) * (mus0 - muk) / mus0,
             scatter_seed=int(rng.integers(2**31)), tau_a=1.0, L=1.0, vp=0.3 * vslip, tauc=float(rng.uniform(0.25, 0.4)) / fn)
    # pilot
    A0, s0 = _simulate(P, _Drive(v0), 12.0 * r_st / fn)
    ts = np.array([s["t_break"] for s in s0])
    Tss = float(np.median(np.diff(ts[2:]))) if len(ts) > 4 else 8.0 / fn
    slip_d = float(np.median([A0["x"][s["i1"]] - A0["x"][s["i0"]] for s in s0]))
    vpk = float(np.median([A0["v"][s["i0"]:s["i1"] + 1].max() for s in s0]))
    P["L"] = float(rng.uniform(0.25, 0.5)) * slip_d
    P["vp"] = float(rng.uniform(0.2, 0.5)) * vpk
    P["tau_a"] = float(rng.uniform(0.5, 1.5)) * (Tss - 0.5 / fn)
    ncyc = int(rng.integers(14, 35))
    warm = 2.5 * Tss
    drive = _Drive(v0)
    t_end = warm + ncyc * Tss
    load = trig = None
    beta = gam = 0.0
    extra = {}
    drive_rec = case == "static_ageing" or (case == "none" and seed % 4 == 3) or \
        (case not in ("drive_modulation",) and force_rec and seed % 2 == 1)
    stepped = case == "static_ageing" or (case == "none" and seed % 4 == 3)
    if stepped:
        holds = case == "static_ageing" and seed % 2 == 1
        ratio = float(rng.uniform(4, 8)) if case == "static_ageing" else float(rng.uniform(3, 5))
        knots = [(0.0, v0)]
        t = warm
        nc = 0
        while nc < ncyc:
            if holds:
                t += int(rng.integers(2, 4)) * Tss
                knots.append((t, 0.0))
                t += float(rng.uniform(1.0, 7.0)) * Tss
                knots.append((t, v0))
                nc += 3
            else:
                nfast, nslow = int(rng.integers(3, 5)), int(rng.integers(2, 4))
                t += nfast * Tss
                knots.append((t, v0 / ratio))
                t += nslow * ratio * Tss * 0.95
                knots.append((t, v0))
                nc += nfast + nslow
        t_end = t + 2.5 * Tss
        drive = _Drive(v0, knots=knots)
        extra.update(drive_kind="holds" if holds else "steps", step_ratio=ratio)
    if case == "drive_modulation":
        a = float(rng.uniform(0.2, 0.45))
        r = float(rng.uniform(0.17, 0.42))
        ph = float(rng.uniform(0, 2 * math.pi))
        fss = 1.0 / Tss
        for _ in range(5):
            fm = r * fss
            drive = _Drive(v0, mod=(a, fm, ph))
            A, S = _simulate(P, drive, t_end)
            M = _measure(A, S, drive, k, warm, t_end, N0)
            if 0.15 <= fm / M["f_ss"] <= 0.45:
                break
            fss = M["f_ss"]
        extra.update(mod_a=a, mod_fm_hz=fm, mod_phase=ph, fm_over_fss=fm / M["f_ss"])
    elif case == "triggering":
        best = None
        for it in range(40):
            Aamp = float(rng.uniform(0.03, 0.08)) if it < 20 else float(rng.uniform(0.03, 0.045))
            ft = float(rng.uniform(2.5, 8.0)) * fn
            trig = (Aamp, ft)
            A, S = _simulate(P, drive, t_end, trig=trig)
            M = _measure(A, S, drive, k, warm, t_end, N0)
            q = ft / M["f_ss"]
            dq = abs(q - round(q))
            if best is None or dq > best[0]:
                best = (dq, Aamp, ft, A, S, M, q)
            if dq >= 0.15 and 10 <= M["n_slips"] <= 60:
                break
        dq, Aamp, ft, A, S, M, q = best
        trig = (Aamp, ft)
        extra.update(trig_runs=it + 1)
        extra.update(trig_amp=Aamp, f_t_hz=ft, ft_over_fn=ft / fn, ft_over_fss=q)
    elif case == "load_variation":
        target = float(rng.uniform(0.15, 0.30))
        sign = 1.0 if rng.random() < 0.5 else -1.0
        Fref = N0 * (mus0 + muk) / 2
        g = sign * target * N0 / (1.5 * dF)
        for _ in range(12):
            A, S = _simulate(P, drive, t_end, load=(g, Fref))
            M = _measure(A, S, drive, k, warm, t_end, N0)
            sel = (A["t"] >= warm)
            pp = float(np.ptp(A["N"][sel]) / N0)
            if abs(pp - target) <= 0.04:
                break
            g *= float(np.clip(target / max(pp, 1e-3), 0.5, 2.0)) ** 0.7
        load = (g, Fref)
        extra.update(load_gain=g, load_pp=pp)
    elif case == "twin_branch":
        target = float(rng.uniform(0.12, 0.22))
        gam = 0.3 * (mus0 - muk)
        for _ in range(5):
            A, S = _simulate(P, drive, t_end, gam=gam)
            M = _measure(A, S, drive, k, warm, t_end, N0)
            if abs(M["twin"] - target) <= 0.03:
                break
            gam *= float(np.clip(target / max(M["twin"], 1e-3), 0.3, 4.0))
        extra.update(dilatancy_gam=gam)
    elif case == "static_ageing":
        target = float(rng.uniform(0.10, 0.17))
        P["tau_a"] = float(rng.uniform(0.5, 1.5)) * (ratio if not holds else 4.0) * Tss
        beta = 0.5 * (mus0 - muk)
        for _ in range(6):
            A, S = _simulate(P, drive, t_end, beta=beta)
            M = _measure(A, S, drive, k, warm, t_end, N0)
            if abs(M["ageing"] - target) <= 0.03:
                break
            beta *= float(np.clip(target / max(M["ageing"], 1e-3), 0.3, 4.0))
        extra.update(ageing_beta=beta)
    else:
        A, S = _simulate(P, drive, t_end)
        M = _measure(A, S, drive, k, warm, t_end, N0)
    D = M["drop_N"]
    # ---- sensor on a fine grid, decimated
    os_ = 8 if coarse else 4
    nrec = int((t_end - warm) * fs)
    tf = warm + np.arange(nrec * os_) / (fs * os_)
    tn, ix = np.unique(A["t"], return_index=True)
    sp = CubicHermiteSpline(tn, A["x"][ix], A["v"][ix])
    xs = sp(tf)
    xd, vd = drive.xv(tf)
    e = xd - xs
    if load:
        Nt = np.maximum(N0 + load[0] * (k * e - load[1]), 0.1 * N0)
    elif trig:
        Nt = N0 * (1 + trig[0] * np.sin(2 * math.pi * trig[1] * tf))
    else:
        Nt = np.full_like(tf, N0)
    fc = float(rng.uniform(6, 12)) * fn
    Fsens = _four_pole(k * e, min(fc, 0.3 * fs * os_), fs * os_)[::os_]
    Nsens = _four_pole(Nt, min(fc, 0.3 * fs * os_), fs * os_)[::os_]
    tr = np.arange(nrec) / fs
    xd_r, vd_r = xd[::os_], vd[::os_]
    Fsens = Fsens + nrng.normal(0, float(rng.uniform(0.002, 0.006)) * D, nrec)
    Nsens = Nsens + nrng.normal(0, 0.0015 * N0, nrec)
    nui = {}
    if nuisance == "hum":
        fh = float(nrng.choice([50.0, 60.0]))
        amp = float(nrng.uniform(0.01, 0.05)) * D
        Fsens = Fsens + amp * np.sin(2 * math.pi * fh * tr + nrng.uniform(0, 6.28)) \
            + 0.2 * amp * np.sin(6 * math.pi * fh * tr + nrng.uniform(0, 6.28))
        nui.update(hum_hz=fh, hum_amp_over_drop=amp / D)
    elif nuisance == "drift":
        amp = float(nrng.uniform(0.01, 0.03)) * D
        Fsens = Fsens + amp * (np.sin(math.pi * tr / tr[-1] * nrng.uniform(0.3, 1.0)) if seed % 2 else tr / tr[-1])
        nui.update(drift_over_drop=amp / D)
    elif nuisance == "spikes":
        frac = float(nrng.uniform(0.0005, 0.005))
        idx = nrng.choice(nrec, max(int(frac * nrec), 2), replace=False)
        Fsens[idx] += nrng.choice([-1, 1], len(idx)) * nrng.uniform(0.1, 0.3, len(idx)) * D
        nui.update(spike_fraction=len(idx) / nrec)
    elif nuisance == "quantisation":
        q = float(nrng.uniform(0.002, 0.01)) * D
        Fsens = np.round(Fsens / q) * q
        nui.update(quant_over_drop=q / D)
    # ---- channels
    normal_rec = (case == "load_variation" and seed % 8 != 6) or case == "triggering" or \
        (case not in ("load_variation",) and seed % 3 == 0)
    args = []
    fn_given = None
    if not (seed % 8 == 5 and case != "triggering" and nuisance != "fn_off"):
        fn_given = fn * (1 + (0.05 if nrng.random() < 0.5 else -0.05)) if nuisance == "fn_off" else fn
        args += ["--fn", f"{fn_given:.4g}"]
    if force_rec:
        args += ["--stiffness", f"{k:.6g}"]
    if not drive_rec:
        args += ["--v0", f"{v0 * 1e3:.5g}"]
    cols = []  # (name, unit, values, decimals)
    fu = "mN" if (seed // 2) % 2 == 0 and N0 < 30 else "N"
    fsc = 1e3 if fu == "mN" else 1.0
    nd_F = max(int(-math.floor(math.log10(D * fsc * 1e-4))), 0)
    if force_rec:
        cols.append(("Friction force", fu, Fsens * fsc, nd_F))
        if normal_rec:
            cols.append(("Normal load", "N", Nsens, 4))
        if drive_rec:
            cnt = 1e-7  # 0.1 um encoder
            pos = np.round(xd_r / cnt) * cnt
            cols.append(("Stage position", "mm", pos * 1e3, 4))
    else:
        xmm = Fsens / k * 1e3
        cols.append(("Spring extension", "mm", xmm, max(int(-math.floor(math.log10(D / k * 1e3 * 1e-4))), 0)))
        if normal_rec:
            b = float(rng.uniform(0.005, 0.03))
            y = 0.3 + b * Nsens
            cols.append(("Normal deflection", "mm", y, max(int(-math.floor(math.log10(b * N0 * 1e-5))), 0)))
        if drive_rec:
            cols.append(("Drive speed", "mm/s", vd_r * 1e3, 5))
    os.makedirs(outdir, exist_ok=True)
    base = f"{NAME}_{case}_{seed}_{nuisance}"
    if style == "logger":
        path = os.path.abspath(os.path.join(outdir, base + ".csv"))
        start = datetime.datetime(2024, 3, 1 + seed % 27, 8 + seed % 9, int(rng.integers(0, 60)),
                                  int(rng.integers(0, 60)))
        stamps = [(start + datetime.timedelta(milliseconds=int(round(i * 1000.0 / fs)))).strftime(
            "%Y-%m-%d %H:%M:%S.%f")[:-3] for i in range(nrec)]
        with open(path, "w", newline="") as f:
            f.write('"Model","GL840"\n"Title","stick-slip rig %d"\n' % (seed + 1))
            f.write('"Sampling interval","%dms"\n"Trigger","Start"\n\n' % int(round(1000 / fs)))
            f.write("No.,Time," + ",".join(c[0] for c in cols) + "\n")
            f.write(",," + ",".join(c[1] for c in cols) + "\n")
            fmtcols = [[_fmt(v, c[3]) for v in c[2]] for c in cols]
            for i in range(nrec):
                f.write(f"{i + 1},{stamps[i]}," + ",".join(fc_[i] for fc_ in fmtcols) + "\n")
    else:
        path = os.path.abspath(os.path.join(outdir, base + ".npz"))
        arrs = {}
        if force_rec:
            arrs["time_s"] = tr
            arrs[f"friction_{fu}"] = cols[0][2]
            for c in cols[1:]:
                if c[0] == "Normal load":
                    arrs["normal_N"] = c[2]
                else:
                    arrs["stage_position_um"] = c[2] * 1e3
        else:
            arrs["t"] = tr
            arrs["x"] = cols[0][2]
            for c in cols[1:]:
                arrs["y" if c[0] == "Normal deflection" else "v0"] = c[2]
        np.savez(path, **arrs)
    params = dict(style=style, force_record=bool(force_rec), normal_recorded=bool(normal_rec),
                  drive_recorded=bool(drive_rec), fs_hz=fs, samples_per_period=spp, m_kg=m, k_N_m=k,
                  N0_N=N0, mu_k=muk, weakening_Dm=Dm, mu_s0=mus0, zeta=zeta, v0_mm_s=v0 * 1e3,
                  vs_mm_s=P["vs"] * 1e3, cv=P["cv"], sensor_fc_over_fn=fc / fn, dilatancy_L_mm=P["L"] * 1e3,
                  tau_a_s=P["tau_a"], duration_s=float(tr[-1]), n_samples=int(nrec),
                  measured=dict(M, drop_over_N0=D / N0), **extra, **nui)
    params = json.loads(json.dumps(params, default=float))
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=path, args=args,
                fn_true=fn, fn_given=fn_given, params=params)


# ------------------------------------------------------------------------------------------ self-check
def _load(path):
    if path.endswith(".npz"):
        z = np.load(path)
        return {kk: z[kk] for kk in z.files}
    with open(path) as f:
        lines = f.read().splitlines()
    i = next(j for j, l in enumerate(lines) if l.startswith("No.,Time"))
    names = lines[i].split(",")
    rows = [l.split(",") for l in lines[i + 2:]]
    out = {n: np.array([float(r[j]) for r in rows]) for j, n in enumerate(names) if n != "Time"}
    t0 = datetime.datetime.strptime(rows[0][1], "%Y-%m-%d %H:%M:%S.%f")
    out["Time"] = np.array([(datetime.datetime.strptime(r[1], "%Y-%m-%d %H:%M:%S.%f") - t0).total_seconds()
                            for r in rows])
    return out


def _sizes(r):
    M = r["params"]["measured"]
    c, p = r["case"], r["params"]
    s = dict(slips=M["n_slips"], fss_over_fn=M["f_ss"] / r["fn_true"], twin=M["twin"], ageing=M["ageing"])
    if c == "load_variation":
        s["size"] = p["load_pp"]
    elif c == "twin_branch":
        s["size"] = M["twin"]
    elif c == "static_ageing":
        s["size"] = M["ageing"]
    elif c == "triggering":
        s["size"] = p["ft_over_fss"]
    elif c == "drive_modulation":
        s["size"] = p["fm_over_fss"]
    else:
        s["size"] = max(abs(M["twin"]), abs(M["ageing"]))
    return s


def _check(r):
    c, p, M = r["case"], r["params"], r["params"]["measured"]
    json.dumps(r, allow_nan=False)
    d = _load(r["file"])
    lens = {len(v) for v in d.values()}
    assert len(lens) == 1 and all(np.all(np.isfinite(v)) for v in d.values()), r["file"]
    assert 5 <= r["fn_true"] <= 500
    assert 10 <= M["n_slips"] <= 60, M["n_slips"]
    if c == "none":
        assert abs(M["twin"]) < 0.01 and abs(M["ageing"]) < 0.015
    if c == "load_variation":
        assert 0.12 <= p["load_pp"] <= 0.35, p["load_pp"]
    if c == "twin_branch":
        assert 0.10 <= M["twin"] <= 0.25, M["twin"]
    if c == "static_ageing":
        assert 0.08 <= M["ageing"] <= 0.20, M["ageing"]
    if c == "triggering":
        q = p["ft_over_fss"]
        assert abs(q - round(q)) >= 0.15 and 2.5 <= p["ft_over_fn"] <= 8 and 0.03 <= p["trig_amp"] <= 0.08
    if c == "drive_modulation":
        assert 0.15 <= p["fm_over_fss"] <= 0.45 and 0.2 <= p["mod_a"] <= 0.45
    if r["nuisance"] == "coarse":
        assert 10 <= p["samples_per_period"] <= 15.5, p["samples_per_period"]
    else:
        assert 19.5 <= p["samples_per_period"] <= 101


def _selfcheck(outdir):
    rows = []
    for case in CASES:
        for seed in range(8):
            nui = NUISANCES[seed % 7]
            r = write_record(case, seed, outdir, nui)
            _check(r)
            rows.append((case, seed, nui, _sizes(r), r))
    return rows


if __name__ == "__main__":
    import tempfile
    import time
    t0 = time.time()
    out = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix=NAME + "_")
    rows = _selfcheck(out)
    print(f"{'case':17s} seed nuisance      style  fn_Hz  slips fss/fn  twin    ageing  size")
    for case, seed, nui, s, r in rows:
        print(f"{case:17s} {seed:4d} {nui:13s} {r['params']['style']:6s} {r['fn_true']:6.1f} {s['slips']:5d} "
              f"{s['fss_over_fn']:.3f}  {s['twin']:+.3f}  {s['ageing']:+.3f}  {s['size']:.3f}")
    print(f"{len(rows)} records OK in {time.time() - t0:.1f} s -> {out}")
