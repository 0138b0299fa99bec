"""Reciprocating linear tribometer (pin on a flat on a trapezoidal stage): an independent record generator.

Rig.  A pin (mass m: pin + holder + the arm's effective mass) on a compliant arm of stiffness k (fn = sqrt(k/m)/2pi,
18-50 Hz, k 1.5-12 kN/m, damping 1-4 % of critical) rests with a normal load N0 (2-15 N) on a flat carried by a
linear stage.  The stage runs back and forth with a **trapezoidal velocity profile**: a linear acceleration ramp at
each stroke end lasting 5-20 % of the stroke time, constant speed V in between, a **dwell** (stage at rest, 0.1-0.6 s;
0.1-1 s alternately in the ageing "holds" seeds) at each end; 4-12 strokes a record.  The stroke length is set so
that each stroke has the reload after the reversal (the pin stuck, the arm force going from +F to -Fs) followed by
3-13 stick-slip cycles at speed V; stick-slip also continues through the ramps, so both directions carry 16-43 slips.

Friction law (polymer-like, single-valued and symmetric in the sliding direction, w = |sliding speed| > 0):
    mu(w) = mu_m + D exp(-w / v_w) + beta ((1 + w / v_p)^q - 1)
an exponential weakening (D 25-50 % of mu_m, v_w 0.15-0.3 of the slip-speed scale omega_n N0 D / k) onto a
power-law strengthening (q 0.3-0.6, beta 15-40 % of D, v_p 0.4-1 of that scale); static level
mu_s = mu_m + D + jump (jump 2-8 % of D); a Hertzian pressure dependence, friction force = N0 (N/N0)^(1 + gam) mu
with gam drawn in -0.36..-0.22 (Hertz: -1/3).

Stick handling: a **Moreau/Kikuuwe implicit set-valued friction update**: in every step the friction is the
projection onto the set-valued law at the END-of-step relative velocity: if the force needed to bring the
relative velocity to zero is within the static level the pin sticks exactly (relative velocity 0, no band, no
regularisation); otherwise the end-of-step sliding speed solves the scalar monotone equation
(m/h) w + N mu(w) = (m/h) |relative free velocity| (safeguarded Newton; the step keeps (m/h) > N max|mu'|).

Integrator: own fixed-step **Stormer-Verlet (midpoint drift-kick-drift)** with the implicit friction above and the
damping by the trapezoidal rule, h = Tn/300 (>= 40 steps a shaker period).  Halving the step changes the stick-slip
period by <= 0.25 %, the drop by <= 0.2 %, the peak force by <= 0.06 % and the twin size of `twin_branch` by 0.6 %
(first order, as expected of a time-stepping scheme across switches).

Departures (sizes measured per stroke / per slip on the fine simulation, seeds 0-23):
- `load_variation`: the load follows the contact point's position on the flat (s - x): a wavy flat
  N = N0 (1 + a sin(2 pi (s - x)/lambda + phi)) with 1.3-3 waves per stroke (even seeds) or a tilted flat
  N = N0 (1 + c ((s - x)/L - 1/2)), c of either sign (odd seeds); normal channel recorded (N/mN, or an affine
  reading y in mm in displacement records).  Measured p-p per stroke 12.4-31.2 % of N0.
- `twin_branch`: **tribo-electric adhesion**: the polymer pin charges by sliding, dq/dt = (w/L_q)(1 - q) - q/tau_l
  (L_q 0.4-0.8 of the slip-length scale, leakage tau_l 0.08-0.2 of the stick time, so it discharges in stick); the
  electrostatic attraction adds N_q q^2 to the load the friction sees (not the recorded load).  Friction is higher
  on the decelerating half of each slip: measured +12.0..+21.2 % of the drop (a 1-DoF reading of the ADC output
  +12.6..+20.9 %), N_q tuned per seed.
- `static_ageing`: Hill-type contact-age law mu_s(t) = mu_s0 + b (t/tau)^n / (1 + (t/tau)^n), n 0.6-1.0, tau at the
  geometric middle of the record's short and long stick times; even seeds: stage speed steps 4.2-7.8x between pairs
  of strokes; odd seeds: dwells alternating 0.1-0.25 s and 0.6-1 s act as holds.  The drive is always recorded
  (position or v0 column).  Peak growth (median of the 10 % longest sticks minus median of the shorter half) measured
  +8.9..+14.8 % of the drop over 10-51x stick times.
- `triggering`: a normal-load shaker N = N0 (1 + eps sin(2 pi f_t t)), eps 3.5-7 %, f_t 3.1-7.5 fn, redrawn until
  the record's f_t/f_ss (f_ss: the mean slip rate in the constant-speed parts) is >= 0.2 from an integer (the
  breakaways lock to the shaker readily): measured f_t/f_ss 7.2-18.6, distance 0.21-0.50.  Normal channel on even
  seeds.
- `drive_modulation`: the stage speed (ramps included) times 1 + a sin(2 pi fm t + phi), a 0.22-0.43, fm/f_ss
  measured 0.18-0.45; never a position column, only --v0 with the nominal speed.
- `none`: see below.

`none` (measured, seeds 0-23): the law is single-valued, so the twin at the contact is 0 (|twin| < 1e-4 of the
drop); a 1-DoF reading of the clean ADC output (the integrate-and-dump average, differentiated on the fine grid)
reads +0.26..+0.85 % of the drop.  No ageing in the law: stick times within a record differ 5.9-39x (ramps,
reversals; stepped stage on seeds 2 and 5, 4.2-7.8x speed steps, recorded) and the peak grows -0.13..+0.39 % of
the drop across them.  Load exactly constant (the normal channel, when given, only carries 0.1 % noise).
Direction asymmetry of the peaks < 0.11 % of the drop.  Peak scatter within the constant-speed parts < 0.2 %.

Sensor and record: an integrate-and-dump ADC (each sample the mean over the preceding interval) + white noise
0.2-0.5 % of the drop; 26-90 samples per stick-slip period (coarse: 12-15 fn, at least 21 per period; stepped
stages: counted at the fast speed, the slow strokes have 4-8x more); 16-43 slips per direction; 0.1-2 s a record.
Force records (friction N/mN with --stiffness; normal N/mN; stage encoder position mm/um at 0.1/0.5 um resolution)
or arm-deflection records (x = F/k in mm/um; affine normal reading y in mm; stage speed v0 mm/s) on about 4 of 10;
position/v0 on 6 of 8 seeds (all for static_ageing, none for drive_modulation), else --v0 with the nominal speed;
--fn on 7 of 8 seeds (5 % off under fn_off).  Delimiters and headers: `name [unit]` with comma or semicolon,
`name/unit` with semicolon and decimal comma, `Name (unit)` with TAB and a `#` comment, `name[unit]` whitespace.
"""
from __future__ import annotations

import math
import os
import sys
import time as _time

import numpy as np

NAME = "recip_trapezoid"

CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

# seed without --fn, per case (never seed 6, which carries fn_off)
_NO_FN = {"none": 1, "load_variation": 3, "twin_branch": 4, "static_ageing": 0, "triggering": 2,
          "drive_modulation": 5}
# seeds whose record has no stage position (only --v0 with the nominal speed)
_NO_POS = {"none": (3, 7), "load_variation": (0, 5), "twin_branch": (2, 7), "static_ageing": (),
           "triggering": (1, 4), "drive_modulation": tuple(range(8))}
_NONE_STEPPED = (2, 5)   # `none` seeds with a stage stepping between two recorded speeds


# ----------------------------------------------------------------------------------------------
# friction law (per unit load at the reference load N0): a polymer-like curve
#   mu(w) = mu_m + D exp(-w / v_w) + beta ((1 + w / v_p)^q - 1)           (w = |sliding speed| > 0)
# static level mu_s = mu_m + D + jump (+ the Hill ageing term in `static_ageing`);
# load dependence (Hertzian pressure): friction force = N0 (N_eff / N0)^(1 + gam) mu, gam ~ -1/3.
# ----------------------------------------------------------------------------------------------

def _mu(w, P):
    return (P["mum"] + P["D"] * math.exp(-w / P["vw"])
            + P["beta"] * ((1.0 + w / P["vp"]) ** P["q"] - 1.0))


def _stage_profile(P, h):
    """Fine-grid stage speed (signed, m/s) and position; stroke bookkeeping."""
    segs = []                      # (t0, t1, kind, stroke index)
    t = 0.0
    tw0 = P["t_start"]
    segs.append((0.0, tw0, "dwell", -1))
    t = tw0
    for i, (d, V) in enumerate(zip(P["dirs"], P["speeds"])):
        tr, tc = P["t_ramp"][i], P["t_const"][i]
        segs.append((t, t + tr, "up", i)); t += tr
        segs.append((t, t + tc, "const", i)); t += tc
        segs.append((t, t + tr, "down", i)); t += tr
        segs.append((t, t + P["dwells"][i], "dwell", i)); t += P["dwells"][i]
    T = t
    n = int(math.ceil(T / h))
    tt = np.arange(n + 1) * h
    vs = np.zeros(n + 1)
    kind = np.zeros(n + 1, dtype=np.int8)        # 0 dwell, 1 ramp, 2 const
    stroke = np.full(n + 1, -1, dtype=np.int16)
    for (a, b, kd, i) in segs:
        sel = (tt >= a) & (tt < b)
        if kd == "dwell":
            continue
        d, V = P["dirs"][i], P["speeds"][i]
        tr = P["t_ramp"][i]
        if kd == "up":
            vs[sel] = d * V * (tt[sel] - a) / tr
            kind[sel] = 1
        elif kd == "const":
            vs[sel] = d * V
            kind[sel] = 2
        else:
            vs[sel] = d * V * (b - tt[sel]) / tr
            kind[sel] = 1
        stroke[sel] = i
    if P.get("mod_a", 0.0) > 0.0:
        vs *= 1.0 + P["mod_a"] * np.sin(2 * np.pi * P["mod_f"] * tt + P["mod_phi"])
    s = np.concatenate(([0.0], np.cumsum(0.5 * (vs[1:] + vs[:-1]) * h)))
    return tt, vs, s, kind, stroke


def _simulate(P, h):
    """Moreau-type midpoint (Stormer-Verlet) time stepping with the set-valued friction solved implicitly.

    Each step: half drift of the position, an implicit velocity update in which the friction is the
    projection onto the set-valued law at the END-of-step relative velocity (Kikuuwe/Moreau: stick if the
    force needed to bring the relative velocity to zero is within the static level, otherwise a scalar
    monotone equation for the sliding speed, solved by safeguarded Newton), then the second half drift.
    Damping is treated by the trapezoidal rule."""
    tt, vs, s, kind, stroke = _stage_profile(P, h)
    n = len(tt) - 1
    m, k, c = P["m"], P["k"], P["c"]
    A = 1.0 + h * c / (2.0 * m)
    B = 2.0 - A
    Mp = m * A / h
    hk_m = h * k / m
    mum, D, vw, beta, vp, q = P["mum"], P["D"], P["vw"], P["beta"], P["vp"], P["q"]
    mus0 = mum + D + P["jump"]
    N0, g1 = P["N0"], 1.0 + P["gam"]
    # normal load
    load_mode = P.get("load_mode", "const")
    if load_mode == "shaker":
        Nt = (N0 * (1.0 + P["trig_eps"] * np.sin(2 * np.pi * P["trig_f"] * tt + P["trig_phi"]))).tolist()
    sl = s.tolist()
    vsl = vs.tolist()
    lw_amp = P.get("load_amp", 0.0); lw_lam = P.get("load_lambda", 1.0); lw_phi = P.get("load_phi", 0.0)
    lt_c = P.get("load_tilt", 0.0); L_tr = P.get("track", 1.0)
    # ageing (Hill): mu_s = mus0 + b (t/tau)^n / (1 + (t/tau)^n)
    ag_b = P.get("age_b", 0.0); ag_tau = P.get("age_tau", 1.0); ag_n = P.get("age_n", 1.0)
    # tribocharge (twin): N_eff = N + Nq qc^2 ; dqc/dt = (w/Lq)(1 - qc) - qc/tau_l
    Nq = P.get("charge_N", 0.0); Lq = P.get("charge_L", 1.0); tl = P.get("charge_tau", 1.0)
    exp = math.exp
    xs = [0.0] * (n + 1); ws = [0.0] * (n + 1); fs_ = [0.0] * (n + 1); Ns = [N0] * (n + 1)
    stk = [1] * (n + 1)
    x = 0.0; v = 0.0; age = 0.0; qc = 0.0; w = 0.0
    S = N0
    for i in range(n):
        vsn = vsl[i + 1]
        if load_mode == "const":
            Nn = N0
        elif load_mode == "shaker":
            Nn = Nt[i + 1]
        elif load_mode == "wavy":
            Nn = N0 * (1.0 + lw_amp * math.sin(2 * math.pi * (sl[i + 1] - x) / lw_lam + lw_phi))
        else:  # tilt along the track: the contact point on the flat is at s - x from the flat's origin
            Nn = N0 * (1.0 + lt_c * ((sl[i + 1] - x) / L_tr - 0.5))
        if Nq > 0.0:
            Ne = Nn + Nq * qc * qc
            S = N0 * (Ne / N0) ** g1
        elif load_mode != "const":
            S = N0 * (Nn / N0) ** g1
        xm = x + 0.5 * h * v
        vfree = (v * B - hk_m * xm) / A
        rel = vfree - vsn
        need = Mp * abs(rel)
        if ag_b > 0.0:
            r = (age / ag_tau) ** ag_n if age > 0.0 else 0.0
            Fs = S * (mus0 + ag_b * r / (1.0 + r))
        else:
            Fs = S * mus0
        if need <= Fs:
            f = -Mp * rel
            vn = vsn
            age += h
            w = 0.0
            stk[i + 1] = 1
        else:
            sg = 1.0 if rel > 0.0 else -1.0
            lo = 0.0
            hi = (need - S * mum) / Mp
            wk = w if 0.0 < w < hi else 0.5 * hi
            for _ in range(40):
                e = exp(-wk / vw)
                pw = (1.0 + wk / vp) ** q
                g = Mp * wk + S * (mum + D * e + beta * (pw - 1.0)) - need
                if g > 0.0:
                    hi = wk
                else:
                    lo = wk
                dg = Mp + S * (-D / vw * e + beta * q / vp * pw / (1.0 + wk / vp))
                wn = wk - g / dg
                if not (lo < wn < hi):
                    wn = 0.5 * (lo + hi)
                if abs(wn - wk) <= 1e-13 * (1.0 + abs(wk)) + 1e-15:
                    wk = wn
                    break
                wk = wn
            w = wk
            f = -sg * S * (mum + D * exp(-w / vw) + beta * ((1.0 + w / vp) ** q - 1.0))
            vn = vsn + sg * w
            age = 0.0
            stk[i + 1] = 0
        x = xm + 0.5 * h * vn
        v = vn
        if Nq > 0.0:
            a_ = w / Lq + 1.0 / tl
            tg = (w / Lq) / a_
            qc = tg + (qc - tg) * exp(-a_ * h)
        xs[i + 1] = x; ws[i + 1] = vn - vsn; fs_[i + 1] = f; Ns[i + 1] = Nn
    return dict(t=tt, vs=vs, s=s, kind=kind, stroke=stroke, x=np.array(xs), vr=np.array(ws),
                f=np.array(fs_), N=np.array(Ns), stick=np.array(stk, dtype=bool), h=h)


# ----------------------------------------------------------------------------------------------
# ground-truth measurements on the fine simulation
# ----------------------------------------------------------------------------------------------

def _slips(sim, P):
    st = sim["stick"]; t = sim["t"]; F = P["k"] * sim["x"]; vs = sim["vs"]
    d = np.diff(st.astype(np.int8))
    starts = np.flatnonzero(d == -1) + 1     # first sliding sample
    ends = np.flatnonzero(d == 1) + 1        # first stuck sample after
    out = []
    for a in starts:
        j = np.searchsorted(ends, a)
        if j >= len(ends):
            break
        b = ends[j]
        out.append((a - 1, b))
    out2 = []
    prev_end = 0
    for a, b in out:
        drop = abs(F[a] - F[b])
        di = np.sign(vs[a]) if vs[a] != 0 else -np.sign(np.mean(sim["vr"][a + 1:b]))
        out2.append(dict(a=a, b=b, peak=abs(F[a]), drop=drop, dir=int(di), tstick=t[a] - t[prev_end],
                         kind=int(sim["kind"][a]), stroke=int(sim["stroke"][a]), t0=t[a]))
        prev_end = b
    if not out2:
        return []
    md = np.median([o["drop"] for o in out2])
    return [o for o in out2 if o["drop"] > 0.25 * md]


def _measure(sim, P):
    sl = _slips(sim, P)
    res = {}
    drops = np.array([o["drop"] for o in sl])
    res["n_pos"] = int(sum(1 for o in sl if o["dir"] > 0))
    res["n_neg"] = int(sum(1 for o in sl if o["dir"] < 0))
    res["drop"] = float(np.median(drops)) if len(drops) else float("nan")
    # stick-slip frequency in the constant-speed parts
    # (mean slip rate over the constant-speed part of each stroke; for a stepped stage, the fast strokes)
    Vmax = max(P["speeds"])
    cnt, span, cnt_lo, span_lo = 0, 0.0, 0, 0.0
    for i, Vi in enumerate(P["speeds"]):
        tt = [o["t0"] for o in sl if o["kind"] == 2 and o["stroke"] == i]
        if len(tt) >= 2:
            if Vi >= 0.99 * Vmax:
                cnt += len(tt) - 1; span += tt[-1] - tt[0]
            else:
                cnt_lo += len(tt) - 1; span_lo += tt[-1] - tt[0]
    res["f_ss"] = cnt / span if span > 0 else float("nan")
    res["T_ss"] = 1.0 / res["f_ss"]
    if span_lo > 0:
        res["T_ss_slow"] = span_lo / cnt_lo
    # twin: friction magnitude on the decelerating minus the accelerating half at equal sliding speed
    tw = []
    fmag = np.abs(sim["f"]); w = np.abs(sim["vr"])
    for o in sl:
        a, b = o["a"] + 1, o["b"]
        if b - a < 12:
            continue
        ww = w[a:b]; ff = fmag[a:b]
        j = int(np.argmax(ww)); wmax = ww[j]
        if j < 4 or (b - a - j) < 4:
            continue
        grid = np.linspace(0.2, 0.8, 13) * wmax
        fa = np.interp(grid, ww[:j + 1], ff[:j + 1])            # rising speed
        fd = np.interp(grid, ww[j:][::-1], ff[j:][::-1])        # falling speed
        tw.append(np.mean(fd - fa) / o["drop"])
    res["twin"] = float(np.median(tw)) if tw else float("nan")
    # peak against stick time
    ts = np.array([o["tstick"] for o in sl[1:]]); pk = np.array([o["peak"] for o in sl[1:]])
    if len(ts) > 8:
        lo, hi = np.quantile(ts, [0.5, 0.9])
        res["age_growth"] = float((np.median(pk[ts >= hi]) - np.median(pk[ts <= lo])) / res["drop"])
        res["tstick_ratio"] = float(np.median(ts[ts >= hi]) / np.median(ts[ts <= lo]))
        sel = np.array([o["kind"] == 2 for o in sl[1:]])
        res["peak_scatter"] = float(np.std(pk[sel]) / res["drop"]) if sel.sum() > 3 else float("nan")
    # direction asymmetry of the peaks and drops in the constant part
    pp = [o["peak"] for o in sl if o["kind"] == 2 and o["dir"] > 0]
    pn = [o["peak"] for o in sl if o["kind"] == 2 and o["dir"] < 0]
    if pp and pn:
        res["dir_asym"] = float((np.median(pp) - np.median(pn)) / res["drop"])
    # load: peak-to-peak per stroke (moving part) / N0
    N = sim["N"]; strk = sim["stroke"]; kind = sim["kind"]
    lpp = []
    for i in range(len(P["dirs"])):
        sel = (strk == i) & (kind > 0)
        if sel.sum() > 10:
            lpp.append((N[sel].max() - N[sel].min()) / P["N0"])
    res["load_pp"] = float(np.median(lpp)) if lpp else 0.0
    res["slips"] = sl
    return res


# ----------------------------------------------------------------------------------------------
# drawing the rig
# ----------------------------------------------------------------------------------------------

def _draw(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([48017, ci, seed])
    P = {"case": case, "seed": seed}
    fn = rng.uniform(18.0, 50.0)
    k = math.exp(rng.uniform(math.log(1500.0), math.log(12000.0)))
    om = 2 * math.pi * fn
    m = k / om ** 2
    zeta = rng.uniform(0.01, 0.04)
    P.update(fn=fn, k=k, m=m, c=2 * zeta * m * om, zeta=zeta)
    N0 = rng.uniform(2.0, 15.0)
    gam = rng.uniform(-0.36, -0.22)
    mum = rng.uniform(0.18, 0.32)
    D = mum * rng.uniform(0.25, 0.5)
    X = N0 * D / k
    P.update(N0=N0, gam=gam, mum=mum, D=D, jump=D * rng.uniform(0.02, 0.08),
             vw=rng.uniform(0.15, 0.3) * om * X, vp=rng.uniform(0.4, 1.0) * om * X,
             q=rng.uniform(0.3, 0.6), beta=D * rng.uniform(0.15, 0.4), X=X)
    r = rng.uniform(0.08, 0.18)
    Tn = 1.0 / fn
    stepped = (case == "static_ageing" and seed % 2 == 0) or (case == "none" and seed in _NONE_STEPPED)
    holds = case == "static_ageing" and seed % 2 == 1
    if stepped:
        ns = 8
        ratio = rng.uniform(4.2, 7.8)
        r_hi = rng.uniform(0.15, 0.22)
        V_hi = r_hi * om * X
        V_lo = V_hi / ratio
        pat = [V_hi, V_hi, V_lo, V_lo, V_hi, V_hi, V_lo, V_lo]
        if rng.uniform() < 0.5:
            pat = pat[2:] + pat[:2]
        speeds = pat
        ncs = [rng.integers(9, 12) if V == V_hi else rng.integers(3, 5) for V in speeds]
        P["step_ratio"] = ratio
        V = V_hi
    else:
        ns = int(rng.choice([8, 10, 12] if holds else [4, 6, 8, 10, 12]))
        V = r * om * X
        speeds = [V] * ns
        nc0 = int(math.ceil((52.0 if holds else 44.0) / ns))
        ncs = [nc0 + int(rng.integers(0, 3))] * ns
    frac_r = rng.uniform(0.05, 0.2)
    dirs = [1 if i % 2 == 0 else -1 for i in range(ns)]
    t_ramp, t_const = [], []
    Fs_est = N0 * (mum + D + P["jump"])
    for Vi, nc in zip(speeds, ncs):
        # travel: the reload from +Fs to -Fs after each reversal, then nc stick-slip cycles
        L = (2.0 * Fs_est + nc * 1.6 * N0 * D) / k
        Tst = L / (Vi * (1.0 - frac_r))
        t_ramp.append(frac_r * Tst); t_const.append(Tst * (1.0 - 2.0 * frac_r))
    if holds:
        dw = [math.exp(rng.uniform(math.log(0.1), math.log(0.25))) if i % 2 == 0 else
              math.exp(rng.uniform(math.log(0.6), math.log(1.0))) for i in range(ns)]
    else:
        dw0 = rng.uniform(0.1, 0.6)
        dw = [dw0 * rng.uniform(0.9, 1.1) for _ in range(ns)]
    # the stroke lengths alternate in sign so that the stage returns: equalise the travel of each pair
    P.update(dirs=dirs, speeds=speeds, t_ramp=t_ramp, t_const=t_const, dwells=dw, frac_ramp=frac_r,
             t_start=0.05, V=V, Vn=V, r=r, stepped=stepped, holds=holds, ncs=[int(x) for x in ncs])
    P["track"] = max(Vi * (tc + tr) for Vi, tc, tr in zip(speeds, t_const, t_ramp))
    # departures
    if case == "load_variation":
        pp = rng.uniform(0.15, 0.34)
        if seed % 2 == 0:
            P["load_mode"] = "wavy"
            P["load_amp"] = pp / 2
            P["load_lambda"] = P["track"] / rng.uniform(1.3, 3.0)
            P["load_phi"] = rng.uniform(0, 2 * np.pi)
        else:
            P["load_mode"] = "tilt"
            P["load_tilt"] = pp * rng.choice([-1.0, 1.0])
        P["load_target"] = pp
    elif case == "triggering":
        P["load_mode"] = "shaker"
        P["trig_eps"] = rng.uniform(0.035, 0.07)
        P["trig_f"] = rng.uniform(2.7, 7.5) * fn
        P["trig_phi"] = rng.uniform(0, 2 * np.pi)
    elif case == "twin_branch":
        Tst = Tn / (math.pi * r) * 0.75
        P["charge_L"] = rng.uniform(0.4, 0.8) * X
        P["charge_tau"] = rng.uniform(0.08, 0.2) * Tst
        P["charge_N"] = 0.5 * N0
        P["twin_target"] = rng.uniform(0.13, 0.2)
    elif case == "static_ageing":
        P["age_n"] = rng.uniform(0.6, 1.0)
        P["age_b"] = 0.1 * D
        P["age_target"] = rng.uniform(0.08, 0.15)
    elif case == "drive_modulation":
        P["mod_a"] = rng.uniform(0.22, 0.43)
        P["mod_phi"] = rng.uniform(0, 2 * np.pi)
        P["mod_frac"] = rng.uniform(0.15, 0.42)
        Tss = Tn * (1.0 / (math.pi * r) * 0.75 + 0.6)
        P["mod_f"] = P["mod_frac"] / Tss
    return P, rng


def _h_of(P):
    Tn = 1.0 / P["fn"]
    h = Tn / 300.0
    if P.get("load_mode") == "shaker":
        h = min(h, 1.0 / (P["trig_f"] * 30.0))
    return h


def _run_case(case, seed, h_scale=1.0):
    """Draw, simulate and tune the departure's size; returns (P, sim, meas)."""
    P, rng = _draw(case, seed)
    h = _h_of(P) * h_scale
    sim = _simulate(P, h)
    me = _measure(sim, P)
    if case == "twin_branch":
        for _ in range(3):
            tw = me["twin"]
            if 0.12 <= tw <= 0.23:
                break
            P["charge_N"] *= P["twin_target"] / max(tw, 0.02)
            sim = _simulate(P, h); me = _measure(sim, P)
    elif case == "static_ageing":
        # tau in the middle (log scale) of the record's short and long stick times, b scaled to the target
        P["age_b"] = 0.4 * P["D"]
        for it in range(5):
            ts = np.array([o["tstick"] for o in me["slips"][1:]])
            lo, hi = np.quantile(ts, [0.5, 0.9])
            P["age_tau"] = float(np.sqrt(np.median(ts[ts <= lo]) * np.median(ts[ts >= hi])))
            sim = _simulate(P, h); me = _measure(sim, P)
            g = me["age_growth"]
            if 0.07 <= g <= 0.17:
                break
            P["age_b"] = float(min(1.2 * P["D"], P["age_b"] * min(3.0, max(0.33, P["age_target"] / max(g, 0.01)))))
    elif case == "triggering":
        best = None
        for _ in range(24):
            ratio = P["trig_f"] / me["f_ss"]
            dist = abs(ratio - round(ratio))
            if best is None or dist > best[0]:
                best = (dist, P["trig_f"], sim, me)
            if dist >= 0.2:
                break
            P["trig_f"] = rng.uniform(2.7, 7.5) * P["fn"]
            h = _h_of(P) * h_scale
            sim = _simulate(P, h); me = _measure(sim, P)
        _, P["trig_f"], sim, me = best
    elif case == "drive_modulation":
        for _ in range(3):
            fr = P["mod_f"] / me["f_ss"]
            if 0.12 <= fr <= 0.45:
                break
            P["mod_f"] *= P["mod_frac"] / fr
            sim = _simulate(P, h); me = _measure(sim, P)
    return P, sim, me


# ----------------------------------------------------------------------------------------------
# sensor, nuisances, file
# ----------------------------------------------------------------------------------------------

def _sample(sim, P, fs):
    """Integrate-and-dump ADC: each sample is the mean of the signal over the preceding interval."""
    t = sim["t"]
    T = t[-1]
    ts = np.arange(1, int(T * fs)) / fs
    def boxcar(y):
        C = np.concatenate(([0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(t))))
        return (np.interp(ts, t, C) - np.interp(ts - 1.0 / fs, t, C)) * fs
    return ts, boxcar, boxcar(P["k"] * sim["x"])


def _reading_twin(P, sim, me, fs):
    """Twin statistic of a 1-DoF reading of the ADC's clean output (no noise): the integrate-and-dump average
    over 1/fs evaluated on the fine grid (so that differentiation error does not enter), f = m x'' + c x' + k x
    against the sliding speed x' - v_stage (the stage speed on the ADC's mean time)."""
    t = sim["t"]
    y = P["k"] * sim["x"]
    C = np.concatenate(([0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(t))))
    F = (C - np.interp(t - 1.0 / fs, t, C)) * fs
    x = F / P["k"]
    xd = np.gradient(x, t); xdd = np.gradient(xd, t)
    vs = np.interp(t - 0.5 / fs, t, sim["vs"])
    f = np.abs(P["m"] * xdd + P["c"] * xd + P["k"] * x)
    w = np.abs(xd - vs)
    sh = int(round(0.5 / fs / sim["h"]))
    out = []
    for o in me["slips"]:
        i0, i1 = o["a"] + sh, o["b"] + sh
        ww, ff = w[i0:i1], f[i0:i1]
        j = int(np.argmax(ww)); wmax = ww[j]
        if j < 4 or len(ww) - j < 4:
            continue
        grid = np.linspace(0.3, 0.8, 11) * wmax
        o1 = np.argsort(ww[:j + 1]); o2 = np.argsort(ww[j:])
        fa = np.interp(grid, ww[:j + 1][o1], ff[:j + 1][o1])
        fd = np.interp(grid, ww[j:][o2], ff[j:][o2])
        out.append(np.mean(fd - fa) / o["drop"])
    return float(np.median(out)) if out else float("nan")


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    P, sim, me = _run_case(case, seed)
    ci = CASES.index(case)
    rng = np.random.default_rng([48018, ci, seed, NUISANCES.index(nuisance)])
    fn = P["fn"]
    Tss = me["T_ss"]
    if nuisance == "coarse":
        fs = max(rng.uniform(12.0, 15.0) * fn, 21.0 / Tss)
    elif case == "static_ageing" or P["stepped"]:
        fs = max(rng.uniform(25.0, 40.0) / Tss, rng.uniform(15.0, 18.0) * fn)
    else:
        fs = max(rng.uniform(30.0, 90.0) / Tss, rng.uniform(15.0, 20.0) * fn)
    ts, boxcar, F = _sample(sim, P, fs)
    drop = me["drop"]
    F = F + rng.normal(0.0, rng.uniform(0.002, 0.005) * drop, len(ts))
    nuis = {}
    if nuisance == "hum":
        fl = float(rng.choice([50.0, 60.0]))
        amp = rng.uniform(0.01, 0.05) * drop
        ph = rng.uniform(0, 2 * np.pi, 3)
        F = F + amp * (np.sin(2 * np.pi * fl * ts + ph[0]) + 0.3 * np.sin(4 * np.pi * fl * ts + ph[1])
                       + 0.15 * np.sin(6 * np.pi * fl * ts + ph[2]))
        nuis = dict(mains_hz=fl, hum_amp_drop=amp / drop)
    elif nuisance == "drift":
        dd = rng.uniform(0.02, 0.06) * drop * rng.choice([-1, 1])
        u = ts / ts[-1]
        F = F + dd * (0.7 * u + 0.3 * u ** 2)
        nuis = dict(drift_drop=dd / drop)
    elif nuisance == "spikes":
        frac = rng.uniform(0.0005, 0.005)
        nsp = max(2, int(frac * len(ts)))
        idx = rng.choice(len(ts), nsp, replace=False)
        F[idx] += rng.choice([-1, 1], nsp) * rng.uniform(0.5, 2.0, nsp) * drop
        nuis = dict(spike_frac=nsp / len(ts))
    elif nuisance == "quantisation":
        qs = rng.uniform(0.002, 0.01) * drop
        F = np.round(F / qs) * qs
        nuis = dict(adc_step_drop=qs / drop)
    fn_given = fn
    if nuisance == "fn_off":
        fn_given = fn * (1.0 + 0.05 * rng.choice([-1.0, 1.0]))
    if seed == _NO_FN[case]:
        fn_given = None
    # record layout
    with_pos = seed not in _NO_POS[case]
    force_rec = rng.uniform() < 0.62
    with_N = case in ("load_variation",) or (case == "triggering" and seed % 2 == 0) or \
        (case == "none" and seed in (0, 4))
    Nrec = boxcar(sim["N"]) + rng.normal(0.0, 0.001 * P["N0"], len(ts))
    cols = [ts]
    style = int(rng.integers(0, 5))
    fu = rng.choice(["N", "mN"]) if force_rec else rng.choice(["mm", "um"])
    fsc = {"N": 1.0, "mN": 1e3, "mm": 1e3 / P["k"], "um": 1e6 / P["k"]}[fu]
    head = [("time", "s")]
    cols.append(F * fsc); head.append(("friction" if force_rec else "x", fu))
    args = []
    if with_N:
        if force_rec:
            nu = rng.choice(["N", "mN"]); cols.append(Nrec * (1.0 if nu == "N" else 1e3)); head.append(("normal", nu))
        else:
            g = rng.uniform(0.01, 0.05)   # mm per N of a normal-load flexure
            cols.append(0.2 + g * Nrec); head.append(("y", "mm"))
    if with_pos:
        if force_rec:
            pu = rng.choice(["mm", "um"])
            res_m = 1e-7 if rng.uniform() < 0.5 else 5e-7
            pos = np.round(np.interp(ts, sim["t"], sim["s"]) / res_m) * res_m
            cols.append(pos * (1e3 if pu == "mm" else 1e6)); head.append(("position", pu))
        else:
            vsr = np.interp(ts, sim["t"], sim["vs"]) * 1e3
            cols.append(np.round(vsr, 4)); head.append(("v0", "mm/s"))
    else:
        args += ["--v0", "%.6g" % (P["Vn"] * 1e3)]
    if force_rec:
        args += ["--stiffness", "%.6g" % P["k"]]
    if fn_given is not None:
        args = ["--fn", "%.6g" % fn_given] + args
    # formatting: comma / semicolon with decimal comma / TAB / whitespace; header styles
    delim, deccomma = [(",", False), (";", True), ("\t", False), (" ", False), (";", False)][style]
    if style == 0:
        hdr = ",".join("%s [%s]" % (a, u) for a, u in head)
    elif style == 1:
        hdr = ";".join("%s/%s" % (a, u) for a, u in head)
    elif style == 2:
        hdr = "\t".join("%s (%s)" % (a.capitalize(), u) for a, u in head)
    elif style == 3:
        hdr = " ".join("%s[%s]" % (a, u) for a, u in head)
    else:
        hdr = ";".join("%s [%s]" % (a, u) for a, u in head)
    lines = []
    if style in (2, 3):
        lines.append("# reciprocating tribometer export, pin on flat, %s record" % ("load cell" if force_rec else "arm deflection"))
    lines.append(hdr)
    M = np.column_stack(cols)
    fmts = ["%.7f"] + ["%.7g"] * (M.shape[1] - 1)
    body = []
    for row in M:
        s = delim.join(f % v for f, v in zip(fmts, row))
        body.append(s)
    txt = "\n".join(body)
    if deccomma:
        txt = txt.replace(".", ",")
    lines.append(txt)
    ext = [".csv", ".csv", ".txt", ".dat", ".csv"][style]
    os.makedirs(outdir, exist_ok=True)
    path = os.path.abspath(os.path.join(outdir, "%s_%s_s%d_%s%s" % (NAME, case, seed, nuisance, ext)))
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    meas = {k_: v for k_, v in me.items() if k_ != "slips"}
    meas["samples_per_period"] = float(fs * Tss)
    meas["n_samples"] = int(len(ts))
    meas["reading_twin"] = _reading_twin(P, sim, me, fs)
    if case == "triggering":
        meas["ft_over_fn"] = P["trig_f"] / fn
        meas["ft_over_fss"] = P["trig_f"] / me["f_ss"]
        meas["ft_int_dist"] = abs(meas["ft_over_fss"] - round(meas["ft_over_fss"]))
    if case == "drive_modulation":
        meas["fm_over_fss"] = P["mod_f"] / me["f_ss"]
    params = {k_: (v.item() if isinstance(v, np.generic) else v) for k_, v in P.items()}
    params["speeds"] = [float(v) for v in P["speeds"]]
    params.update(fs=float(fs), nuisance_params={k_: float(v) for k_, v in nuis.items()},
                  measured=meas, force_record=bool(force_rec), unit=str(fu), with_position=bool(with_pos),
                  with_normal=bool(with_N))
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": path,
            "args": args, "fn_true": float(fn), "fn_given": None if fn_given is None else float(fn_given),
            "params": params}


def _summary(info):
    me = info["params"]["measured"]
    c = info["case"]
    pr = info["params"]
    if c == "none":
        size = "twin %+.4f (reading %+.4f) peak-vs-stick %+.4f (%.1fx) asym %+.4f" % (
            me["twin"], me["reading_twin"], me.get("age_growth", float("nan")), me.get("tstick_ratio", float("nan")), me.get("dir_asym", float("nan")))
    elif c == "load_variation":
        size = "load p-p %.3f of N0 (%s)" % (me["load_pp"], pr["load_mode"])
    elif c == "twin_branch":
        size = "twin %+.3f of drop (1-DoF reading of the ADC %+.3f)" % (me["twin"], me["reading_twin"])
    elif c == "static_ageing":
        size = "peak growth %+.3f of drop over %.1fx stick times" % (me["age_growth"], me["tstick_ratio"])
    elif c == "triggering":
        size = "eps %.3f ft/fn %.2f ft/fss %.2f (dist %.2f)" % (pr["trig_eps"], me["ft_over_fn"], me["ft_over_fss"],
                                                             me["ft_int_dist"])
    else:
        size = "a %.3f fm/fss %.3f" % (pr["mod_a"], me["fm_over_fss"])
    return "%-16s s%d %-12s cycles +%d/-%d  spp %.1f  %s" % (c, info["seed"], info["nuisance"], me["n_pos"],
                                                             me["n_neg"], me["samples_per_period"], size)


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "recip_trapezoid_out"
    for case in CASES:
        for seed in range(8):
            t0 = _time.time()
            info = write_record(case, seed, out, NUISANCES[seed % 7])
            print(_summary(info), " (%.1fs)" % (_time.time() - t0), flush=True)
