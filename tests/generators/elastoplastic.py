"""Elastoplastic-junction stick-slip records (an independent generator for ``lieng diagnose``).

Written without reading the diagnosis (nor the other generators): its own friction law, stick
handling, integrator, sensor and noise.

Rig.  A slider of mass m held by a dynamometer spring k (anchored; the record is its extension x or
force k x) rests on a counterface (belt or stage) moving at vb(t); sliding velocity vr = vb - dx/dt.

Friction law.  An elastoplastic junction (Dupont, Hayward, Armstrong & Altpeter 2002): a junction
deflection z with F = sigma0 z + sigma1 (1 - alpha) dz/dt (the damping acts on the elastic part)
and dz/dt = vr (1 - alpha(z, vr) z / z_ss(vr)),
alpha = 0 below the breakaway deflection z_ba = rho z_ss (rho 0.7-0.9) and whenever z unloads,
a half-sine ramp to 1 between z_ba and z_ss: the stick is purely elastic (genuine stiction, no
creep drift); sigma0 = 400-900 k.  Steady state sigma0 z_ss = mu_ss(|vr|) N with a power-law
(algebraic) weakening and a weak linear strengthening,
    mu_ss(v) = mu_k + (mu_s - mu_k) / (1 + (v/vs)^q) + cv v,   q 0.7-1.5.
No Stribeck exponential, Gaussian or Lorentzian.

Effects.
- twin_branch: a flash-temperature state theta, d theta/dt = (|F vr| / P_ref - theta) / tau_th
  (tau_th 0.06-0.15 natural periods), adds lam (mu_s - mu_k) theta to mu_ss: the junction heats in the
  slip and is stronger on the decelerating half (the heat is still there) than on the accelerating
  half at the same speed; it cools in the stick.  lam is calibrated until the split, measured on the
  simulated friction inside the slips, is 10-25 % of the slip's force drop (params["twin_split"]).
- load_variation: an eccentric (tilted) counterface seen through a compliant normal support: the
  load follows the slider position through a second-order mode (3-6 fn, damping ratio 0.3-0.7),
  N = N0 (1 + eps u), u'' = wu^2 ((x - xm)/A - u) - 2 zu wu u';  p-p 10-40 % of N0, recorded.
  Either sign; a load that grows with the extension raises the static limit as the spring loads,
  so there eps is kept below 0.3 drop/peak (else the stick never ends) or the sign is turned.
- static_ageing: a contact age a (grows as the time in stick, wiped out over a slip distance L_r of
  the plastic slip); mu_s(a) = mu_s0 + beta (1 - exp(-(a/tau_a)^0.5)) (stretched exponential, not
  logarithmic).  Stepped drive (two levels a factor 4.5-7.5 apart, 4-7 cycles per step) or a
  reciprocating stage with dwells of varied length (0.2-5.2 stick times) and stroke speeds the same
  factor apart; the drive is recorded.  Growth measured as the peak force's
  regression on ln(stick time) over the 10-90 % range of stick times, as a fraction of the drop.
- triggering: N = N0 (1 + a sin(2 pi ft t + phi)), a 3-8 %, ft 2.5-8 fn, half-way between two
  harmonics of the unforced stick-slip frequency (below); the normal channel on half the records.
- drive_modulation: vb = v0n (1 + a sin(2 pi fm t + phi)), a 0.2-0.45, fm 0.1-0.5 f_ss; only --v0.

Integrator.  Own fixed step (about 200 steps per natural period, commensurate with the sampling):
symplectic Euler for the slider (x advanced with the new velocity), the junction, the temperature
and the age linearly implicit (the junction's stiff relaxation z_ss/|vr| and the slider-on-junction
mode at sqrt(sigma0/m) are resolved without a stiff solver); the friction's speed law is explicit,
at the sliding speed extrapolated to the end of the step (no one-step lag: with it the scheme alone
made a -5 % branch split at this step).

Sensor.  A 2nd-order Bessel low-pass at 5-10 fn (normal channel 8-15 fn), then an integrating
(moving-average) ADC over each sample interval; noise white plus 1/f (pink) coloured noise.

Records.  Displacement `t [s], x [mm][, y [mm]][, v0 [mm/s]]` (y an affine reading of N) or force
`time [s], friction [N|mN|uN][, normal [...]][, position [mm|um] | v0 [mm/s]]` with --stiffness
(columns sometimes permuted); comma, semicolon, TAB or whitespace (then `name[unit]`).  Seeds 3 and 7
(mod 4 == 3) are on a reciprocating stage with dwells (except drive_modulation).  20-100 samples per
natural period (`coarse`: 10-15), 15-60 stick-slip cycles.  --fn is omitted on about one record in six
(never with `fn_off`).

Inherent memory of the law, measured on `none` (seeds 0-7, the bench's nuisances; the simulated
friction, the same statistics as the effects'):
- branch split (decelerating - accelerating friction at equal speed, 20-80 % of each slip's peak
  speed, median over the slips, per drop): -0.3 to -1.2 % of the drop (-1.0 to -2.1 % over 5-95 % of
  the peak speed): the junction's relaxation length F/sigma0 lags the weakening a little, the
  opposite sign of a twin branch.  (On the twin records: +13.8 to +20.5 %.)
- peak growth with stick time (regression on ln t_stick over its 10-90 % range, per drop): 0 on
  constant drives; -0.9 % and -3.3 % on the two stepped-drive `none` records (seeds 1 and 5, a factor
  2-4): a faster loading breaks a little higher in the partial-plastic zone, the opposite sign of
  ageing.  (On the ageing records: +9 to +16.5 % of the drop, +7 to +11 % of the peak.)
- stick: no drift below z_ba; creep (vr > 5 % of the drive) over the last 10-25 % of each rise's
  duration (the partial-plastic zone), a rounded top over the last 2-5 % of the drop below the peak.
Triggering: ft is set half-way between two harmonics of the rig's own stick-slip frequency measured
on the same record without the forcing (params trig_ft_over_fss_unforced = n + 0.5); with the forcing
on, the slips tend to lock onto its troughs (the stick lasting a whole number of forcing periods),
which is the effect itself (trig_ft_over_fss_forced).
"""

from __future__ import annotations

import math
import os

import numpy as np
from scipy import signal

NAME = "elastoplastic"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

_STEPS_PER_PERIOD = 200


# --------------------------------------------------------------------------------------------
# the integrator
# --------------------------------------------------------------------------------------------

def _integrate(p, h, vb, Nt):
    """Fixed-step semi-implicit integration.  vb, Nt: lists (len n+1) of the belt velocity and the
    imposed normal load (Nt ignored when p['eps'] != 0: the load then follows the slider)."""
    m, k, c = p["m"], p["k"], p["c"]
    sig0, sig1 = p["sig0"], p["sig1"]
    muk, mus0, beta = p["muk"], p["mus0"], p["beta"]
    inv_tau_a = 1.0 / p["tau_a"]
    q, inv_vs, cv, rho = p["q"], 1.0 / p["vs"], p["cv"], p["rho"]
    lamd = p["lam"] * (p["mus0"] - p["muk"])
    tau_th, inv_Pref = p["tau_th"], 1.0 / p["Pref"]
    inv_Lr = 1.0 / p["Lr"]
    eps, N0 = p["eps"], p["N0"]
    lv = eps != 0.0
    wu2, c2u, xm, invA = p["wu"] ** 2, 2 * p["zu"] * p["wu"], p["xm"], 1.0 / p["A"]
    n = len(vb) - 1
    inv_sig0 = 1.0 / sig0
    mh = m / h
    diag0 = mh + c
    dth = 1.0 + h / tau_th
    hth = h * inv_Pref / tau_th
    sin, sqrt, exp = math.sin, math.sqrt, math.exp
    pi = math.pi

    x = p["x0"]
    v = 0.0
    z = k * x * inv_sig0
    th = 0.0
    age = 0.0
    u = (x - xm) * invA
    ud = 0.0
    xs = [0.0] * (n + 1)
    vrs = [0.0] * (n + 1)
    Fs = [0.0] * (n + 1)
    Ns = [0.0] * (n + 1)
    xs[0] = x
    vrs[0] = vb[0]
    Fs[0] = k * x
    Ns[0] = N0 * (1 + eps * u) if lv else Nt[0]
    vr_prev = vb[0] - v
    for i in range(n):
        vbn = vb[i + 1]
        if lv:
            ud += h * (wu2 * ((x - xm) * invA - u) - c2u * ud)
            u += h * ud
            Nn = N0 * (1.0 + eps * u)
        else:
            Nn = Nt[i + 1]
        vr0 = vbn - v
        # the speed law at the sliding speed extrapolated to the end of the step (no one-step lag)
        vr = 2.0 * vr0 - vr_prev
        if (vr > 0.0) != (vr0 > 0.0):
            vr = vr0
        s = vr if vr >= 0.0 else -vr
        if beta != 0.0:
            mus = mus0 + beta * (1.0 - exp(-sqrt(age * inv_tau_a)))
        else:
            mus = mus0
        w = (s * inv_vs) ** q if s > 0.0 else 0.0
        mu = muk + (mus - muk) / (1.0 + w) + cv * s + lamd * th
        zmax = mu * Nn * inv_sig0
        if (vr > 0.0 and z > 0.0) or (vr < 0.0 and z < 0.0):
            az = z if z > 0.0 else -z
            zba = rho * zmax
            if az <= zba:
                al = 0.0
            elif az >= zmax:
                al = 1.0
            else:
                al = 0.5 * sin(pi * (az - 0.5 * (zmax + zba)) / (zmax - zba)) + 0.5
        else:
            al = 0.0
        # junction damping acts on the elastic part of the deflection rate only
        s1h = sig1 * (1.0 - al) / h
        S = sig0 + s1h
        d = 1.0 / (1.0 + h * s * al / zmax)
        Az = (z + h * vbn) * d
        Bz = h * d
        vn = (mh * v - k * x + S * Az - s1h * z) / (diag0 + S * Bz)
        zn = Az - Bz * vn
        F = sig0 * zn + s1h * (zn - z)
        x = x + h * vn
        vrn = vbn - vn
        vp = vrn - (zn - z) / h
        z = zn
        v = vn
        vr_prev = vr0
        if lamd != 0.0:
            P = F * vrn
            th = (th + hth * (P if P > 0.0 else -P)) / dth
        if beta != 0.0:
            age = (age + h) / (1.0 + h * (vp if vp > 0.0 else -vp) * inv_Lr)
        i1 = i + 1
        xs[i1] = x
        vrs[i1] = vrn
        Fs[i1] = F
        Ns[i1] = Nn
    return np.array(xs), np.array(vrs), np.array(Fs), np.array(Ns)


# --------------------------------------------------------------------------------------------
# analysis of the simulated (true) signals
# --------------------------------------------------------------------------------------------

def _slips(vr, nT):
    """Slip intervals (i0, ip, i1) from the true sliding velocity; nT = steps per natural period."""
    s = np.abs(vr)
    ref = float(np.percentile(s, 99.5))
    if ref <= 0:
        return []
    mask = s > 0.05 * ref
    d = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    starts = list(np.flatnonzero(d == 1))
    ends = list(np.flatnonzero(d == -1))
    runs = []
    for a, b in zip(starts, ends):
        if runs and a - runs[-1][1] < 0.05 * nT:
            runs[-1][1] = b
        else:
            runs.append([a, b])
    out = []
    for a, b in runs:
        if b - a < 0.08 * nT:
            continue
        ip = a + int(np.argmax(s[a:b]))
        if s[ip] < 0.3 * ref:
            continue
        out.append((a, ip, b - 1))
    return out


def _twin_split(sl, vr, F, x, k):
    """Per slip: mean (decelerating - accelerating) friction at equal speed (20-80 % of the peak
    speed), over the slip's spring-force drop."""
    vals = []
    for a, ip, b in sl:
        dr = 1.0 if vr[ip] > 0 else -1.0
        sp = np.abs(vr)
        vmax = sp[ip]
        grid = np.linspace(0.2, 0.8, 25) * vmax
        sa, fa = sp[a:ip + 1], dr * F[a:ip + 1]
        sd, fd = sp[ip:b + 1][::-1], dr * F[ip:b + 1][::-1]
        if sa.size < 4 or sd.size < 4:
            continue
        sa = np.maximum.accumulate(sa)
        sd = np.maximum.accumulate(sd)
        drop = dr * k * (x[a] - x[b])
        if drop <= 0:
            continue
        vals.append(float(np.mean(np.interp(grid, sd, fd) - np.interp(grid, sa, fa)) / drop))
    return vals


def _cycle_stats(sl, t, vr, x, k):
    """Per slip (after the first): stick time before it, peak spring force, drop, slip duration."""
    rows = []
    for j in range(1, len(sl)):
        a, ip, b = sl[j]
        pb = sl[j - 1][2]
        dr = 1.0 if vr[ip] > 0 else -1.0
        peak = float(np.max(dr * k * x[pb:b + 1]))
        rows.append({"stick": float(t[a] - t[pb]), "peak": peak, "drop": float(dr * k * (x[a] - x[b])),
                     "slip": float(t[b] - t[a]), "t0": float(t[a]), "dir": dr})
    return rows


def _growth(rows):
    """Peak force growth over the 10-90 % range of stick times (regression on ln t), per drop."""
    if len(rows) < 4:
        return 0.0
    st = np.array([r["stick"] for r in rows])
    pk = np.array([r["peak"] for r in rows])
    D = float(np.median([r["drop"] for r in rows]))
    lt = np.log(np.maximum(st, 1e-9))
    lo, hi = np.percentile(lt, [10, 90])
    if hi - lo < 1e-3:
        return 0.0
    slope = np.polyfit(lt, pk, 1)[0]
    return float(slope * (hi - lo) / D)


# --------------------------------------------------------------------------------------------
# drive programmes
# --------------------------------------------------------------------------------------------

def _stepped_plan(levels, seg_durs, ramp):
    tb, vv = [0.0], [levels[0]]
    tcur = 0.0
    for j, (lv, du) in enumerate(zip(levels, seg_durs)):
        if j > 0:
            tb.append(tcur + ramp)
            vv.append(lv)
        tcur += du
        tb.append(tcur)
        vv.append(lv)
    return np.array(tb), np.array(vv), tcur


def _recip_plan(speeds, dwells, stroke, ramp):
    """Trapezoidal strokes of length `stroke` (alternating sign), each followed by a dwell."""
    tb, vv = [0.0], [0.0]
    tcur = 0.0
    sgn = 1.0
    for V, dw in zip(speeds, dwells):
        T = stroke / V + ramp  # travel = V (T - ramp)
        tb += [tcur + ramp, tcur + T, tcur + T + ramp]
        vv += [sgn * V, sgn * V, 0.0]
        tcur += T + ramp
        tcur += dw
        tb.append(tcur)
        vv.append(0.0)
        sgn = -sgn
    return np.array(tb), np.array(vv), tcur


# --------------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------------

def _draw(case, seed):
    g = np.random.default_rng([0xE1A5, CASES.index(case), seed])
    fn = float(np.exp(g.uniform(np.log(4.0), np.log(25.0))))
    w = 2 * np.pi * fn
    k = float(np.exp(g.uniform(np.log(300.0), np.log(8000.0))))
    m = k / w ** 2
    N0 = float(g.uniform(2.0, 25.0))
    mus0 = float(g.uniform(0.3, 0.65))
    muk = mus0 * float(g.uniform(0.62, 0.8))
    dmu = mus0 - muk
    zeta = float(g.uniform(0.004, 0.025))
    R = float(g.uniform(400.0, 900.0))
    sig0 = R * k
    zb = float(g.uniform(0.4, 1.0))
    sig1 = 2 * zb * math.sqrt(sig0 * m)
    X = dmu * N0 / k
    Vslip = X * w
    p = dict(fn=fn, k=k, m=m, c=2 * zeta * m * w, zeta=zeta, N0=N0, mus0=mus0, muk=muk, sig0=sig0, R=R,
             zeta_junction=zb, sig1=sig1, rho=float(g.uniform(0.7, 0.9)), q=float(g.uniform(0.7, 1.5)),
             vs=float(g.uniform(0.06, 0.2)) * Vslip, cv=float(g.uniform(0.02, 0.06)) * dmu / Vslip,
             beta=0.0, tau_a=1.0, lam=0.0, tau_th=float(g.uniform(0.06, 0.15)) / fn,
             Pref=N0 * muk * Vslip, Lr=0.01 * X, eps=0.0, wu=float(g.uniform(3.0, 6.0)) * w,
             zu=float(g.uniform(0.3, 0.7)), xm=0.0, A=1.0,
             r_stick=float(g.uniform(1.5, 6.0)), n_cyc=int(g.integers(15, 61)),
             x0=0.5 * muk * N0 / k, Vslip=Vslip)
    recip = (seed % 4 == 3) and case != "drive_modulation"
    p["recip"] = bool(recip)
    # per-case draws (always drawn, so the stream does not depend on branches)
    p["twin_target"] = float(g.uniform(0.13, 0.21))
    p["load_target"] = float(g.uniform(0.14, 0.34))
    p["load_sign"] = float(g.choice([-1.0, 1.0]))
    p["age_target"] = float(g.uniform(0.09, 0.16))
    p["age_factor"] = float(g.uniform(4.5, 7.5))
    p["tau_a_u"] = float(np.exp(g.uniform(-0.5, 0.5)))
    p["trig_amp"] = float(g.uniform(0.03, 0.08))
    p["trig_ratio"] = float(g.uniform(2.8, 7.5))
    p["trig_phase"] = float(g.uniform(0, 2 * np.pi))
    p["mod_amp"] = float(g.uniform(0.2, 0.45))
    p["mod_ratio"] = float(g.uniform(0.14, 0.4))
    p["mod_phase"] = float(g.uniform(0, 2 * np.pi))
    p["none_stepped"] = bool(case == "none" and seed % 2 == 1 and not recip)
    p["none_factor"] = float(g.uniform(2.0, 4.0))
    p["seg_cycles"] = [int(s) for s in g.integers(4, 8, size=40)]
    p["per_stroke"] = int(g.integers(3, 7))
    p["dwell_u"] = [float(s) for s in g.uniform(0.0, 1.0, size=80)]
    p["ramp_frac"] = float(g.uniform(0.1, 0.3))
    # sensor / record
    p["fc_main"] = float(g.uniform(5.0, 10.0)) * fn
    p["fc_norm"] = float(g.uniform(8.0, 15.0)) * fn
    p["sp"] = float(g.uniform(20.0, 100.0))
    p["sp_coarse"] = float(g.uniform(10.0, 15.0))
    p["white"] = float(g.uniform(0.001, 0.004))
    p["pink"] = float(g.uniform(0.0005, 0.002))
    p["nwhite"] = float(g.uniform(0.001, 0.004))
    p["kind"] = "displacement" if g.uniform() < 0.5 else "force"
    p["sep"] = str(g.choice([",", ";", "\t", " "]))
    p["funit"] = str(g.choice(["N", "mN", "uN"]))
    p["nunit"] = str(g.choice(["N", "mN"]))
    p["punit"] = str(g.choice(["mm", "um"]))
    p["pos_offset_mm"] = float(g.uniform(-120.0, 120.0))
    p["y_gain"] = float(g.uniform(0.02, 0.2))
    p["y_off"] = float(g.uniform(-1.0, 1.0))
    p["permute"] = bool(g.uniform() < 0.3)
    p["drive_col_u"] = float(g.uniform())
    p["normal_u"] = float(g.uniform())
    p["omit_fn_u"] = float(g.uniform())
    p["names_u"] = int(g.integers(0, 3))
    p["start_u"] = float(g.uniform(0.1, 0.8))
    p["t0_offset"] = float(g.choice([0.0, g.uniform(1.0, 50.0)]))
    return p


# --------------------------------------------------------------------------------------------
# one simulation with a given drive
# --------------------------------------------------------------------------------------------

def _build_drive(case, p):
    """Returns (fun(t) -> vb, T_total, description)."""
    Tn = 1.0 / p["fn"]
    v0 = p["v0"]
    Tss = p["stick_est"] + p["slip_est"]
    warm = p["load_est"] + 2.0 * Tss
    if p["recip"]:
        f = p["age_factor"] if case == "static_ageing" else 1.0
        nst = int(math.ceil(p["n_cyc"] / p["per_stroke"])) + 2
        speeds, dwells = [], []
        for j in range(nst):
            V = v0 if (j // 2) % 2 == 0 else v0 / f  # pairs of strokes at each speed
            speeds.append(V)
            if case == "static_ageing":
                dw = (0.2 + 5.0 * p["dwell_u"][j]) * p["stick_est"]
            else:
                dw = (1.0 + 1.5 * p["dwell_u"][j]) * p["stick_est"]
            dwells.append(dw)
        stroke = 2.0 * p["peak_est_x"] + (p["per_stroke"] - 0.5) * p["drop_est_x"]
        ramp = max(0.2 * Tn, 0.02 * stroke / v0)
        tb, vv, T = _recip_plan(speeds, dwells, stroke, ramp)
        return (lambda t: np.interp(t, tb, vv)), T, {"stroke_mm": stroke * 1e3, "ramp_s": ramp,
                                                      "speeds_mm_s": [s * 1e3 for s in speeds],
                                                      "dwells_s": dwells}
    if case == "static_ageing" or p["none_stepped"]:
        f = p["age_factor"] if case == "static_ageing" else p["none_factor"]
        levels, durs = [], []
        ncyc = 0
        j = 0
        while ncyc < p["n_cyc"] + 2:
            lvl = v0 if j % 2 == 0 else v0 / f
            nseg = p["seg_cycles"][j % len(p["seg_cycles"])]
            tss = p["stick_est"] * (v0 / lvl) + p["slip_est"]
            du = nseg * tss + (warm if j == 0 else 0.0)
            levels.append(lvl)
            durs.append(du)
            ncyc += nseg
            j += 1
        tb, vv, T = _stepped_plan(levels, durs, 0.1 * Tn)
        return (lambda t: np.interp(t, tb, vv)), T, {"levels_mm_s": [l * 1e3 for l in levels],
                                                      "segment_s": durs}
    T = warm + (p["n_cyc"] + 0.5) * Tss
    if case == "drive_modulation":
        a, fm, ph = p["mod_amp"], p["fm"], p["mod_phase"]
        return (lambda t: v0 * (1.0 + a * np.sin(2 * np.pi * fm * t + ph))), T, {}
    return (lambda t: np.full_like(t, v0)), T, {}


def _run(case, p, sp, T_override=None, const_drive=False):
    fn = p["fn"]
    M = int(math.ceil(_STEPS_PER_PERIOD / sp))
    fs = sp * fn
    h = 1.0 / (fs * M)
    if const_drive:
        T = T_override
        vbf = lambda t: np.full_like(t, p["v0"])  # noqa: E731
        dinfo = {}
    else:
        vbf, T, dinfo = _build_drive(case, p)
    n = int(math.ceil(T / (h * M))) * M
    t = np.arange(n + 1) * h
    vb = vbf(t)
    if case == "triggering" and not const_drive:
        Nt = p["N0"] * (1.0 + p["trig_amp"] * np.sin(2 * np.pi * p["ft"] * t + p["trig_phase"]))
    else:
        Nt = np.full(n + 1, p["N0"])
    x, vr, F, N = _integrate(p, h, vb.tolist(), Nt.tolist())
    return dict(t=t, vb=vb, x=x, vr=vr, F=F, N=N, h=h, M=M, fs=fs, nT=int(round(1.0 / (fn * h))), drive=dinfo)


def _measure(case, p, r, i_start=0):
    sl = _slips(r["vr"], r["nT"])
    sl_rec = [s for s in sl if s[0] >= i_start]
    rows = _cycle_stats(sl_rec, r["t"], r["vr"], r["x"], p["k"])
    tw = _twin_split(sl_rec, r["vr"], r["F"], r["x"], p["k"])
    out = {"n_slips": len(sl_rec),
           "twin_split": float(np.median(tw)) if tw else float("nan"),
           "growth": _growth(rows),
           "drop_N": float(np.median([q["drop"] for q in rows])) if rows else float("nan"),
           "peak_N": float(np.median([q["peak"] for q in rows])) if rows else float("nan"),
           "stick_s": float(np.median([q["stick"] for q in rows])) if rows else float("nan"),
           "slip_s": float(np.median([q["slip"] for q in rows])) if rows else float("nan")}
    if len(sl_rec) >= 3:
        ts = r["t"][[s[0] for s in sl_rec]]
        out["f_ss"] = float(1.0 / np.median(np.diff(ts)))  # the median cycle (dwells left out)
    else:
        out["f_ss"] = float("nan")
    Nr = r["N"][i_start:]
    out["N_pp"] = float((np.percentile(Nr, 99.5) - np.percentile(Nr, 0.5)) / p["N0"])
    return out, sl


def _prerun(case, p, sp):
    """Short constant-drive runs: set v0 for the drawn stick ratio; learn the drop, peak, slip."""
    Tn = 1.0 / p["fn"]
    k = p["k"]
    D_guess = 1.5 * (p["mus0"] - p["muk"]) * p["N0"]
    p["v0"] = D_guess / (k * p["r_stick"] * Tn)
    meas = None
    for _ in range(3):
        load = (p["mus0"] * p["N0"] - k * p["x0"]) / (k * p["v0"])
        T = load + 6.0 * (p["r_stick"] + 0.7) * Tn
        r = _run(case, p, sp, T_override=T, const_drive=True)
        meas, sl = _measure(case, p, r)
        if not np.isfinite(meas["stick_s"]) or meas["n_slips"] < 3:
            p["v0"] *= 0.6
            continue
        ratio = meas["stick_s"] / (p["r_stick"] * Tn)
        p["v0"] *= ratio
        if abs(ratio - 1.0) < 0.15:
            break
    p["stick_est"] = p["r_stick"] * Tn
    p["slip_est"] = meas["slip_s"]
    p["drop_est_x"] = meas["drop_N"] / k
    p["peak_est_x"] = meas["peak_N"] / k
    p["load_est"] = (p["mus0"] * p["N0"] - k * p["x0"]) / (k * p["v0"])
    p["f_ss_est"] = 1.0 / (p["stick_est"] + p["slip_est"])
    return meas


# --------------------------------------------------------------------------------------------
# the public entry point
# --------------------------------------------------------------------------------------------

def _pink(g, n, rms):
    if n < 4 or rms <= 0:
        return np.zeros(n)
    w = g.standard_normal(n)
    W = np.fft.rfft(w)
    f = np.arange(W.size, dtype=float)
    f[0] = 1.0
    W = W / np.sqrt(f)
    W[0] = 0.0
    y = np.fft.irfft(W, n)
    return y * (rms / (np.std(y) + 1e-300))


def _sensor(sig, h, M, fc, i_first):
    b, a = signal.bessel(2, fc, btype="low", fs=1.0 / h, norm="mag")
    zi = signal.lfilter_zi(b, a) * sig[0]
    y, _ = signal.lfilter(b, a, sig, zi=zi)
    cs = np.concatenate([[0.0], np.cumsum(y)])
    idx = np.arange(max(1, i_first // M + (1 if i_first % M else 0)), (len(sig) - 1) // M + 1) * M
    return idx, (cs[idx + 1] - cs[idx + 1 - M]) / M


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    p = _draw(case, seed)
    gn = np.random.default_rng([0xE1A5, CASES.index(case), seed, 1 + NUISANCES.index(nuisance)])
    sp = p["sp_coarse"] if nuisance == "coarse" else p["sp"]
    fn = p["fn"]
    k = p["k"]

    # effect guesses before the pre-run
    if case == "twin_branch":
        p["lam"] = 4.0 * p["twin_target"]
    pre = _prerun(case, p, sp)
    if case == "twin_branch":
        # calibrate lam on short runs at the final v0
        for _ in range(3):
            T = p["load_est"] + 6.0 * (p["stick_est"] + p["slip_est"])
            r = _run(case, p, sp, T_override=T, const_drive=True)
            mm, _ = _measure(case, p, r)
            if np.isfinite(mm["twin_split"]) and mm["twin_split"] > 0.01:
                ratio = p["twin_target"] / mm["twin_split"]
                p["lam"] *= min(max(ratio, 0.4), 2.5)
                if abs(ratio - 1) < 0.1:
                    break
            else:
                p["lam"] *= 2.0
    if case == "load_variation":
        if p["recip"]:
            p["xm"], p["A"] = 0.0, p["peak_est_x"]
        else:
            p["xm"], p["A"] = p["peak_est_x"] - 0.5 * p["drop_est_x"], 0.5 * p["drop_est_x"]
        p["eps"] = p["load_sign"] * 0.5 * p["load_target"]
        if p["load_sign"] > 0 and not p["recip"]:
            # a load growing with the extension raises the static limit as the spring loads; keep its
            # slope (mu_s dN/dx = 2 eps F_s k / D) below 0.6 k, else the stick never ends
            p["eps_max"] = 0.3 * pre["drop_N"] / pre["peak_N"]
            if p["eps_max"] < 0.065:
                p["load_sign"] = -1.0
                p["eps"] = -0.5 * p["load_target"]
            else:
                p["eps"] = min(p["eps"], p["eps_max"])
    if case == "static_ageing":
        f = p["age_factor"]
        t_lo = p["stick_est"]
        t_hi = p["stick_est"] * f if not p["recip"] else p["stick_est"] * 4.0
        p["tau_a"] = math.sqrt(t_lo * t_hi) * p["tau_a_u"]
        # at least ~6.5 % of the peak as well as 9-16 % of the drop (both readings of "5-20 %")
        p["age_target"] = min(0.17, max(p["age_target"], 0.065 * pre["peak_N"] / pre["drop_N"]))
        dphi = math.exp(-math.sqrt(t_lo / p["tau_a"])) - math.exp(-math.sqrt(t_hi / p["tau_a"]))
        # 1.5: the drop grows with the peak and the 10-90 % range of stick times is narrower
        p["beta"] = 1.5 * p["age_target"] * pre["drop_N"] / (p["N0"] * dphi)
    if case == "drive_modulation":
        p["fm"] = p["mod_ratio"] * p["f_ss_est"]
        p["n_cyc"] = max(p["n_cyc"], int(math.ceil(3.2 / p["mod_ratio"])))

    # long records (slow strokes, long holds) are sampled more sparsely: at most ~60k samples
    if nuisance != "coarse":
        T_est = _build_drive(case, p)[1]
        sp = min(sp, max(20.0, 60000.0 / (T_est * fn)))

    if case == "triggering":
        # the forcing is placed half-way between two harmonics of the rig's own (unforced) stick-slip
        # frequency, measured on the same record without the forcing.  With the forcing on, the slips
        # lock onto its troughs (the stick then lasts a whole number of forcing periods): that is the
        # effect itself, reported as trig_ft_over_fss_forced.
        amp = p["trig_amp"]
        p["trig_amp"] = 0.0
        p["ft"] = p["trig_ratio"] * fn
        r0 = _run(case, p, sp)
        p["trig_amp"] = amp
        sl0 = _slips(r0["vr"], r0["nT"])
        f0 = 1.0 / float(np.median(np.diff(r0["t"][[q_[0] for q_ in sl0[2:]]])))
        mlt = math.floor(p["trig_ratio"] * fn / f0)
        ft = (mlt + 0.5) * f0
        while ft > 8.0 * fn:
            ft -= f0
        while ft < 2.5 * fn:
            ft += f0
        p["ft"] = ft
        p["f_ss_unforced"] = f0

    # full runs, re-calibrated when the measured effect leaves its band
    ok = False
    for attempt in range(6):
        r = _run(case, p, sp)
        sl_all = _slips(r["vr"], r["nT"])
        if len(sl_all) < 4:
            if case == "load_variation" and p["eps"] > 0:
                p["load_sign"], p["eps"] = -1.0, -0.5 * p["load_target"]
                continue
            raise RuntimeError("no stick-slip in the simulation")
        a1 = sl_all[1][2]
        nxt = sl_all[2][0] if len(sl_all) > 2 else a1
        i_start = int(a1 + p["start_u"] * (nxt - a1))
        meas, _ = _measure(case, p, r, i_start)
        ok = True
        if meas["n_slips"] < 16:
            p["n_cyc"] = int(math.ceil(p["n_cyc"] * 17.0 / max(meas["n_slips"], 4))) + 1
            ok = False
        if case == "twin_branch":
            tw = meas["twin_split"]
            if not (0.105 <= tw <= 0.24):
                p["lam"] *= min(max(p["twin_target"] / max(tw, 0.01), 0.4), 2.5)
                ok = False
        elif case == "load_variation":
            pp = meas["N_pp"]
            if not (0.11 <= pp <= 0.38) or meas["n_slips"] < 16:
                p["eps"] *= p["load_target"] / max(pp, 0.02)
                if p["eps"] > p.get("eps_max", 1.0) or (p["eps"] > 0 and meas["n_slips"] < 16):
                    p["load_sign"] = -1.0
                    p["eps"] = -0.5 * p["load_target"]
                ok = False
        elif case == "static_ageing":
            gr = meas["growth"]
            grp = gr * meas["drop_N"] / meas["peak_N"]
            if not (0.06 <= gr <= 0.19) or (grp < 0.052 and gr < 0.17):
                p["beta"] *= p["age_target"] / max(gr, 0.01)
                ok = False
        elif case == "drive_modulation":
            rr = p["fm"] / meas["f_ss"]
            if not (0.1 <= rr <= 0.5):
                p["fm"] = p["mod_ratio"] * meas["f_ss"]
                ok = False
        if ok:
            break

    # ---------------- sensor, sampling, nuisances ----------------
    h, M = r["h"], r["M"]
    idx, xs = _sensor(r["x"], h, M, p["fc_main"], i_start)
    _, Ns = _sensor(r["N"], h, M, p["fc_norm"], i_start)
    t = r["t"][idx] - r["t"][idx[0]] + p["t0_offset"]
    vb = r["vb"][idx]
    pos = np.cumsum(r["vb"]) * h
    pos = pos[idx] - pos[idx[0]]
    n = t.size
    D_x = meas["drop_N"] / k  # drop in metres of extension
    xs = xs + D_x * (p["white"] * gn.standard_normal(n)) + _pink(gn, n, p["pink"] * D_x)
    Ns = Ns + p["N0"] * p["nwhite"] * gn.standard_normal(n) + _pink(gn, n, 0.3 * p["nwhite"] * p["N0"])

    # columns
    disp = p["kind"] == "displacement"
    drive_varies = p["recip"] or case == "static_ageing" or p["none_stepped"]
    if case == "drive_modulation":
        drive_col = None
    elif drive_varies:
        drive_col = "v0" if p["drive_col_u"] < 0.5 else "position"
    else:
        drive_col = None if p["drive_col_u"] < 0.6 else ("v0" if p["drive_col_u"] < 0.8 else "position")
    if disp and drive_col == "position":
        drive_col = "v0"
    if case == "load_variation":
        has_n = True
    elif case == "triggering":
        has_n = p["normal_u"] < 0.5
    else:
        has_n = p["normal_u"] < 0.3

    nuis = {}
    if disp:
        main = xs * 1e3
        munit = "mm"
        D_out = D_x * 1e3
    else:
        fac = {"N": 1.0, "mN": 1e3, "uN": 1e6}[p["funit"]]
        main = xs * k * fac
        munit = p["funit"]
        D_out = D_x * k * fac
    if has_n:
        if disp:
            ncol = p["y_gain"] * Ns + p["y_off"]
            nunit = "mm"
        else:
            nfac = {"N": 1.0, "mN": 1e3}[p["nunit"]]
            ncol = Ns * nfac
            nunit = p["nunit"]
    else:
        ncol, nunit = None, None

    fn_given = fn
    if nuisance == "hum":
        fh = float(gn.choice([50.0, 60.0]))
        ah = float(gn.uniform(0.01, 0.05)) * D_out
        ph = gn.uniform(0, 2 * np.pi, 3)
        hum = np.sin(2 * np.pi * fh * t + ph[0]) + 0.35 * np.sin(4 * np.pi * fh * t + ph[1]) \
            + 0.15 * np.sin(6 * np.pi * fh * t + ph[2])
        main = main + ah * hum
        if ncol is not None:
            ncol = ncol + float(gn.uniform(0.002, 0.01)) * float(np.mean(np.abs(ncol))) * hum
        nuis = {"hum_hz": fh, "hum_amp_frac_drop": ah / D_out}
    elif nuisance == "drift":
        dd = float(gn.uniform(0.02, 0.05)) * float(gn.choice([-1.0, 1.0]))
        tau = float(gn.uniform(0.3, 1.5))
        sh = (1 - np.exp(-(t - t[0]) / (tau * (t[-1] - t[0])))) / (1 - np.exp(-1.0 / tau))
        main = main + dd * D_out * sh
        nuis = {"drift_frac_drop": dd, "drift_tau_frac": tau}
    elif nuisance == "spikes":
        frac = float(gn.uniform(0.0005, 0.005))
        ns = max(2, int(round(frac * n)))
        cand = gn.choice(np.arange(2, n - 2), size=ns, replace=False)
        cand = np.sort(cand)
        keep = [cand[0]]
        for c_ in cand[1:]:
            if c_ - keep[-1] > 3:
                keep.append(c_)
        keep = np.array(keep)
        mag = gn.uniform(0.2, 0.6, keep.size) * gn.choice([-1.0, 1.0], keep.size) * D_out
        main = main.copy()
        main[keep] += mag
        nuis = {"spike_frac": keep.size / n, "n_spikes": int(keep.size)}
    elif nuisance == "quantisation":
        qs = float(gn.uniform(0.002, 0.01)) * D_out
        main = np.round(main / qs) * qs
        nuis = {"adc_step": qs, "adc_step_frac_drop": qs / D_out}
    elif nuisance == "fn_off":
        fn_given = fn * (1.05 if gn.uniform() < 0.5 else 0.95)
        nuis = {"fn_factor": fn_given / fn}
    if nuisance != "fn_off" and p["omit_fn_u"] < 0.17:
        fn_given = None

    # assemble and write
    cols, names, fmts = [t], ["time", "x" if disp else "friction"], ["%.8g"]
    cols.append(main)
    fmts.append("%.7g")
    units = ["s", munit]
    if ncol is not None:
        cols.append(ncol)
        names.append("y" if disp else "normal")
        units.append(nunit)
        fmts.append("%.7g")
    if drive_col == "v0":
        cols.append(vb * 1e3)
        names.append("v0")
        units.append("mm/s")
        fmts.append("%.7g")
    elif drive_col == "position":
        pfac = 1.0 if p["punit"] == "mm" else 1e3
        cols.append((pos * 1e3 + p["pos_offset_mm"]) * pfac)
        names.append("position")
        units.append(p["punit"])
        fmts.append("%.9g")
    if disp:
        names[0] = "t"
    else:
        nm = p["names_u"]
        if nm == 1:
            names = [s.capitalize() if s != "v0" else s for s in names]
        elif nm == 2:
            names = [{"time": "t", "friction": "F", "normal": "N"}.get(s, s) for s in names]
    order = list(range(len(cols)))
    if not disp and p["permute"] and len(cols) > 2:
        order = [0] + order[1:][::-1]
    sep = p["sep"]
    if sep == " ":
        header = " ".join(f"{names[j]}[{units[j]}]" for j in order)
    else:
        header = sep.join(f"{names[j]} [{units[j]}]" for j in order)
    data = np.column_stack([cols[j] for j in order])
    ext = ".csv" if sep in (",", ";") else ".txt"
    os.makedirs(outdir, exist_ok=True)
    path = os.path.abspath(os.path.join(outdir, f"{NAME}_{case}_{seed}_{nuisance}{ext}"))
    np.savetxt(path, data, delimiter=sep, header=header, comments="", fmt=[fmts[j] for j in order])

    args = []
    if fn_given is not None:
        args += ["--fn", repr(float(fn_given))]
    if drive_col is None:
        args += ["--v0", repr(float(p["v0"] * 1e3))]
    if not disp:
        args += ["--stiffness", repr(float(k))]

    params = {kk: vv for kk, vv in p.items() if kk not in ("seg_cycles", "dwell_u")}
    params.update({
        "case": case, "v0_mm_s": p["v0"] * 1e3, "samples_per_period": sp, "steps_per_sample": M,
        "step_s": h, "record_columns": [f"{names[j]} [{units[j]}]" for j in order], "separator": sep,
        "drive_column": drive_col, "normal_column": ncol is not None, "drive": r["drive"],
        "nuisance_detail": nuis, "drop_out_units": D_out, "drop_x_mm": D_x * 1e3,
        "measured": meas, "twin_split": meas["twin_split"], "peak_growth": meas["growth"],
        "peak_growth_per_peak": meas["growth"] * meas["drop_N"] / meas["peak_N"],
        "load_pp": meas["N_pp"], "calibration_runs": attempt + 1, "calibrated": ok,
        "f_ss": meas["f_ss"], "n_samples": int(n),
    })
    if case == "triggering":
        params["trig_ft_over_fn"] = p["ft"] / fn
        params["trig_ft_over_fss_unforced"] = p["ft"] / p["f_ss_unforced"]
        params["trig_ft_over_fss_forced"] = p["ft"] / meas["f_ss"]
    if case == "drive_modulation":
        params["mod_fm_over_fss"] = p["fm"] / meas["f_ss"]
    params = _jsonable(params)
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance, "file": path,
            "args": args, "fn_true": float(fn), "fn_given": None if fn_given is None else float(fn_given),
            "params": params}


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating, float)):
        f = float(o)
        return f if math.isfinite(f) else None
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.bool_):
        return bool(o)
    return o
