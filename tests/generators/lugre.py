"""lugre -- an independent generator of "measured" stick-slip records built on a LuGre bristle friction model.

Written for evaluating `lieng diagnose`; it shares no code and no model with the package (only numpy/scipy).

Mechanical model (SI units inside, 1 tangential DoF + bristle state)
--------------------------------------------------------------------
A slider of mass m rests on a belt moving at the drive velocity v0(t); it is held by a tangential spring k
(the dynamometer) and a small viscous damper c = 2 zeta sqrt(k m).  q is the slider's displacement in the drive
direction = the spring extension x, p = dq/dt, vr = v0(t) - p the sliding velocity (belt relative to slider).

    dq/dt = p
    m dp/dt = -k q - c p + Ff
    dz/dt = vr - sigma0 |vr| z / g(vr)                        (mean bristle deflection, LuGre)
    Ff    = N(t)/N0 * (sigma0 z + sigma1(vr) dz/dt + sigma2 vr)
    g(vr) = (Fc + (Fs(h) - Fc) exp(-|vr/vs|^delta)) * (1 + b s)        Stribeck curve, delta in [1.5, 2.5]
    sigma1(vr) = sigma1 exp(-(vr/vs)^2)                       (bristle damping only active near stick)

There is no separate stick state: "stick" is the bristles loading elastically (sigma0 = 300..1500 k, so the
presliding deflection Fs/sigma0 is < 5 % of the slip amplitude -- checked on every seed).  The system is stiff
(contact mode ~ 17..40 fn); it is integrated with scipy's LSODA (max step 1/4 natural period, rtol 1e-7).

Two extra states are integrated only where the case needs them (otherwise they stay 0):
  s  (twin branch switch)  ds/dt = (w(vr) * sigmoid((Ff - k q - c p - m dv0/dt)/Fsc) - s) / tau_s
     the sigmoid is 1 while the sliding speed decreases (dvr/dt < 0), w(vr) = 1 - exp(-(vr/v_on)^2) keeps it
     off in stick; so on the decelerating half of each slip Fc and Fs are raised by the factor (1 + b).
  h  (stick-time clock)    dh/dt = e - (1 - e) h / tau_r,  e = exp(-(vr/v_th)^2): h counts the time the
     sliding speed has been below v_th and resets in a slip.  Fs(h) = Fs0 (1 + beta ln(1 + h/tau_age)).

Cases (what is hidden; calibrated on noise-free short runs of the same system, then checked on the record)
  none              N = N0, constant v0; or (half the seeds) a recorded stepped drive, 4-6 levels spanning a
                    factor 4-8 (v0 or position column).  The usual LuGre bristle lag is present.
  load_variation    geometric coupling N = N0 (1 + cN (x - xmean)), pp of N 10-40 % of N0; normal channel recorded.
  twin_branch       b > 0: friction on the decelerating half higher by 10-25 % of the slip's force drop
                    (net, measured at equal sliding speeds between 25 % and 75 % of the slip's peak speed).
  static_ageing     beta > 0 with a stepped drive (4-6 levels, factor 4-8) and on half the seeds 1-3 holds
                    (drive 0); peak force grows 5-20 % over the record's range of stick times.
  triggering        N = N0 (1 + a sin(2 pi f_tr t + phi)), a 3-8 %, f_tr 2.5-8 fn and not near a multiple of
                    the stick-slip frequency; normal channel recorded.
  drive_modulation  v0(t) = v0n (1 + a sin(2 pi fm t + phi)), a 20-45 %, fm 0.1-0.5 f_ss; only v0n given.

Parameter ranges: fn 5-100 Hz (log-uniform), m 0.02-2 kg, N0 = m g (1..5), Fs = (0.2..0.6) N0,
Fc/Fs 0.55-0.9, vs = (0.3..3) * 2 pi fn (Fs-Fc)/k, zeta 0.005-0.03, stick 2-12 natural periods (constant
drive), 12-40 stick-slip cycles, 20-100 samples per natural period.  Parameter sets that do not give real
stick-slip (stop in every cycle, drop 15-60 % of the peak force, presliding < 5 %) are redrawn.

Records: displacement (~60 %): t, x [mm] (= F/k), optional y [mm] (normal dynamometer deflection, affine in
N), optional v0 [mm/s]; force (~40 %): t [s], F [N|mN|uN], optional N [same unit], optional position [mm|um]
or v0 [mm/s].  Separator comma, TAB, or (for unit-less displacement headers only) whitespace.
Noise: white 0.2-1 % of the force drop plus AR(1) coloured noise (correlation 0.5-5 natural periods,
0.2-0.8 % of the drop) on x/F; the normal channel gets the same relative to S_N = N0 * drop/peak; a v0 column
gets 0.2-0.5 % white noise; ~30 % of seeds carry a tiny unrelated vibration (drop/100..500, 3-12 fn) in x/F.
Nuisances: hum (50/60 Hz + 2nd/3rd harmonic, 1-5 % of the drop, in x/F, the normal channel and a v0 column;
not in an encoder position column), drift, spikes (x/F and normal channel), quantisation (all channels),
coarse (10-15 samples per period), fn_off (+-5 % on --fn).
"""
import json
import math
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp

NAME = "lugre"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
G = 9.81


# ----------------------------------------------------------------------------------------------------------
# drive schedules
# ----------------------------------------------------------------------------------------------------------
class Drive:
    """v0(t) = v_init + sum_i dv_i * H_w(t - T_i) (smooth steps of width w) optionally times a sinusoidal
    modulation (1 + a sin(2 pi f t + phi))."""

    def __init__(self, v_init, times=(), dvs=(), width=1e-3, mod_a=0.0, mod_f=0.0, mod_phi=0.0):
        self.v_init = float(v_init)
        self.T = np.asarray(times, float)
        self.dv = np.asarray(dvs, float)
        self.w = float(width)
        self.a, self.f, self.phi = float(mod_a), float(mod_f), float(mod_phi)
        self.n = len(self.T)

    def v_dv(self, t):
        v, dv = self.v_init, 0.0
        if self.n:
            arg = (t - self.T) / self.w
            arg = np.clip(arg, -40.0, 40.0)
            th = np.tanh(arg)
            v += float(np.dot(self.dv, 0.5 * (1.0 + th)))
            dv += float(np.dot(self.dv, 0.5 * (1.0 - th * th))) / self.w
        if self.a:
            om = 2 * math.pi * self.f
            sn, cs = math.sin(om * t + self.phi), math.cos(om * t + self.phi)
            dv = dv * (1 + self.a * sn) + v * self.a * om * cs
            v = v * (1 + self.a * sn)
        return v, dv

    def v_array(self, t):
        t = np.asarray(t, float)
        v = np.full_like(t, self.v_init)
        for Ti, dvi in zip(self.T, self.dv):
            v += dvi * 0.5 * (1 + np.tanh(np.clip((t - Ti) / self.w, -40, 40)))
        if self.a:
            v = v * (1 + self.a * np.sin(2 * math.pi * self.f * t + self.phi))
        return v

    def position(self, t):
        """Analytic integral of v0 from 0 (no modulation for recorded drives)."""
        t = np.asarray(t, float)
        u = self.v_init * t
        for Ti, dvi in zip(self.T, self.dv):
            a = (t - Ti) / self.w
            a0 = (0.0 - Ti) / self.w
            lc = np.logaddexp(a, -a) - math.log(2)
            lc0 = np.logaddexp(a0, -a0) - math.log(2)
            u = u + dvi * 0.5 * ((t - 0.0) + self.w * (lc - lc0))
        return u


# ----------------------------------------------------------------------------------------------------------
# the simulation
# ----------------------------------------------------------------------------------------------------------
def _simulate(P, drive, t_eval, t_start, case_on):
    """Integrate from t_start (at rest, unloaded) to t_eval[-1]; return dict of arrays on t_eval."""
    m, k, c = P["m"], P["k"], P["c"]
    s0, s1, s2 = P["sigma0"], P["sigma1"], P["sigma2"]
    Fc, Fs0, vs, dl = P["Fc"], P["Fs"], P["vs"], P["delta"]
    b = P.get("twin_b", 0.0) if case_on == "twin_branch" else 0.0
    beta = P.get("age_beta", 0.0) if case_on == "static_ageing" else 0.0
    tau_age = P.get("age_tau", 1.0)
    v_th = P.get("age_vth", 1.0)
    tau_r = P.get("age_tau_reset", 1.0)
    v_on = P.get("twin_von", 1.0)
    tau_s = P.get("twin_tau", 1.0)
    fsc = P.get("twin_fscale", 1.0)
    cN = P.get("load_c", 0.0) if case_on == "load_variation" else 0.0
    xmean = P.get("load_xmean", 0.0)
    tr_a = P.get("trig_a", 0.0) if case_on == "triggering" else 0.0
    tr_om = 2 * math.pi * P.get("trig_f", 0.0)
    tr_phi = P.get("trig_phi", 0.0)
    exp, log, sin = math.exp, math.log, math.sin

    def nratio(t, q):
        r = 1.0
        if cN:
            r += cN * (q - xmean)
        if tr_a:
            r += tr_a * sin(tr_om * t + tr_phi)
        return r

    def rhs(t, y):
        q, p, z, s, h = y
        v0, dv0 = drive.v_dv(t)
        vr = v0 - p
        avr = abs(vr)
        Fs = Fs0 * (1.0 + beta * log(1.0 + h / tau_age)) if beta else Fs0
        g = Fc + (Fs - Fc) * exp(-(avr / vs) ** dl)
        if b:
            g *= 1.0 + b * s
        zd = vr - s0 * avr * z / g
        Ff = nratio(t, q) * (s0 * z + s1 * exp(-(vr / vs) ** 2) * zd + s2 * vr)
        pd = (-k * q - c * p + Ff) / m
        if b:
            arg = (Ff - k * q - c * p - m * dv0) / fsc
            arg = max(min(arg, 50.0), -50.0)
            tgt = (1.0 - exp(-(vr / v_on) ** 2)) / (1.0 + exp(-arg))
            sd = (tgt - s) / tau_s
        else:
            sd = 0.0
        if beta:
            e = exp(-(vr / v_th) ** 2)
            hd = e - (1.0 - e) * h / tau_r
        else:
            hd = 0.0
        return [p, pd, zd, sd, hd]

    fn = P["fn"]
    max_step = 0.25 / fn
    if tr_a:
        max_step = min(max_step, 0.1 / P["trig_f"])
    scale = np.array([P["q_scale"], P["v_scale"], Fs0 / s0, 1.0, 1.0 / fn])
    y0 = [0.0, drive.v_dv(t_start)[0], 0.0, 0.0, 0.0]
    sol = solve_ivp(rhs, (t_start, t_eval[-1]), y0, method="LSODA", t_eval=t_eval, rtol=1e-7,
                    atol=1e-7 * scale, max_step=max_step)
    if not sol.success:
        raise RuntimeError("integration failed: " + sol.message)
    q, p, z, s, h = sol.y
    v0 = drive.v_array(t_eval)
    vr = v0 - p
    Fs = Fs0 * (1.0 + beta * np.log1p(h / tau_age)) if beta else Fs0
    g = Fc + (Fs - Fc) * np.exp(-(np.abs(vr) / vs) ** dl)
    if b:
        g = g * (1.0 + b * s)
    zd = vr - s0 * np.abs(vr) * z / g
    nr = np.ones_like(q)
    if cN:
        nr = nr + cN * (q - xmean)
    if tr_a:
        nr = nr + tr_a * np.sin(tr_om * t_eval + tr_phi)
    Ff = nr * (s0 * z + s1 * np.exp(-(vr / vs) ** 2) * zd + s2 * vr)
    return dict(t=t_eval, q=q, p=p, z=z, s=s, h=h, v0=v0, vr=vr, Ff=Ff, nr=nr)


def _analyse(S, fn):
    """Find slips and per-cycle quantities in a noise-free simulation."""
    t, q, vr, v0 = S["t"], S["q"], S["vr"], S["v0"]
    hi = np.percentile(vr, 99.7)
    thr = max(0.3 * hi, 1.2 * float(np.max(v0)))
    mask = vr > thr
    d = np.diff(mask.astype(int))
    starts = list(np.where(d == 1)[0] + 1)
    ends = list(np.where(d == -1)[0] + 1)
    if mask[0]:
        starts = [0] + starts
    if mask[-1]:
        ends = ends + [len(mask)]
    segs = []
    gap = 0.15 / fn
    for a, e in zip(starts, ends):
        if segs and t[a] - t[segs[-1][1] - 1] < gap:
            segs[-1][1] = e
        else:
            segs.append([a, e])
    slips = []
    for i, (a, e) in enumerate(segs):
        if a == 0 or e >= len(t):
            continue
        ip = a + int(np.argmax(vr[a:e]))
        # slip extends to where vr falls back to ~0 around the segment
        a0 = a
        while a0 > 0 and vr[a0 - 1] > 0.02 * vr[ip] and vr[a0 - 1] < vr[a0]:
            a0 -= 1
        e0 = e
        while e0 < len(t) - 1 and vr[e0] > 0.02 * vr[ip] and vr[e0] < vr[e0 - 1]:
            e0 += 1
        slips.append(dict(a=a0, e=e0, ip=ip, vpeak=float(vr[ip])))
    cyc = []
    for j in range(1, len(slips)):
        prev, cur = slips[j - 1], slips[j]
        st = slice(prev["e"], cur["a"] + 1)
        if cur["a"] <= prev["e"]:
            continue
        iq = prev["e"] + int(np.argmax(q[st]))
        nxt_end = slips[j + 1]["a"] if j + 1 < len(slips) else len(t) - 1
        sl = slice(cur["ip"], max(nxt_end, cur["ip"] + 1))
        imin = cur["ip"] + int(np.argmin(q[sl]))
        minvr = float(np.min(np.abs(vr[st])))
        cyc.append(dict(t_peak=float(t[iq]), qmax=float(q[iq]), qmin=float(q[imin]),
                        t_stick=float(t[cur["a"]] - t[prev["e"]]), h_at_slip=float(S["h"][cur["a"]]),
                        stop=minvr < 0.05 * cur["vpeak"], vpeak=cur["vpeak"], slip=cur,
                        zmax=float(np.max(np.abs(S["z"][st])))))
    return slips, cyc


def _twin_metric(S, slips, lo=0.25, hi=0.75):
    """Median over slips of (friction on decelerating half - accelerating half) at equal sliding speed."""
    out = []
    vr, F = S["vr"], S["Ff"]
    for sl in slips:
        a, e, ip = sl["a"], sl["e"], sl["ip"]
        if ip - a < 4 or e - ip < 4:
            continue
        vp = sl["vpeak"]
        grid = np.linspace(lo * vp, hi * vp, 9)
        va, Fa = vr[a:ip + 1], F[a:ip + 1]
        vd, Fd = vr[ip:e][::-1], F[ip:e][::-1]
        oa, od = np.argsort(va), np.argsort(vd)
        fa = np.interp(grid, va[oa], Fa[oa])
        fd = np.interp(grid, vd[od], Fd[od])
        out.append(float(np.mean(fd - fa)))
    return float(np.median(out)) if out else float("nan")


def _summary(S, fn):
    slips, cyc = _analyse(S, fn)
    if len(cyc) < 3:
        return None
    qmax = np.array([c["qmax"] for c in cyc])
    qmin = np.array([c["qmin"] for c in cyc])
    drop = qmax - qmin
    tp = np.array([c["t_peak"] for c in cyc])
    return dict(slips=slips, cyc=cyc, drop=float(np.median(drop)), dropfrac=drop / qmax,
                qmean=float(np.mean(S["q"])), peak=float(np.median(qmax)),
                fss=(len(tp) - 1) / (tp[-1] - tp[0]) if len(tp) > 1 else float("nan"),
                allstop=all(c["stop"] for c in cyc),
                presl=float(np.max([c["zmax"] for c in cyc]) / np.min(drop)),
                vpeak=float(np.median([c["vpeak"] for c in cyc])),
                slipdur=float(np.median([S["t"][c["slip"]["e"]] - S["t"][c["slip"]["a"]] for c in cyc])))


def _ok(sm):
    return (sm is not None and sm["allstop"] and np.all(sm["dropfrac"] > 0.15) and np.all(sm["dropfrac"] < 0.6)
            and sm["presl"] < 0.05)


# ----------------------------------------------------------------------------------------------------------
# parameter drawing
# ----------------------------------------------------------------------------------------------------------
def _logu(rng, a, b):
    return float(math.exp(rng.uniform(math.log(a), math.log(b))))


def _draw_system(rng, stick_periods, factor=1.0):
    fn = _logu(rng, 5, 100)
    m = _logu(rng, 0.02, 2.0)
    k = m * (2 * math.pi * fn) ** 2
    N0 = m * G * rng.uniform(1, 5)
    Fs = rng.uniform(0.2, 0.6) * N0
    Fc = rng.uniform(0.6, 0.9) * Fs
    vstar = 2 * math.pi * fn * (Fs - Fc) / k
    drop_est = 1.4 * (Fs - Fc)
    v0 = drop_est / (k * stick_periods / fn)
    vs = v0 / factor / _logu(rng, 0.08, 0.4)
    delta = rng.uniform(1.3, 2.2)
    sigma0 = k * _logu(rng, 300, 1500)
    zeta_c = rng.uniform(0.2, 0.7)
    sigma1 = 2 * zeta_c * math.sqrt(sigma0 * m)
    sigma2 = rng.uniform(0.0, 0.05) * (Fs - Fc) / vs
    zeta = rng.uniform(0.005, 0.03)
    c = 2 * zeta * math.sqrt(k * m)
    return dict(fn=fn, m=m, k=k, N0=N0, Fs=Fs, Fc=Fc, vs=vs, delta=delta, sigma0=sigma0, sigma1=sigma1,
                sigma2=sigma2, zeta=zeta, zeta_contact=zeta_c, c=c, v0=v0,
                q_scale=drop_est / k, v_scale=vstar + v0)


def _short_run(P, v0, ncyc=7):
    """Constant-drive calibration run of about ncyc cycles (after a warm-up)."""
    fn = P["fn"]
    T_est = (1.4 * (P["Fs"] - P["Fc"]) / (P["k"] * v0)) + 0.6 / fn
    t_end = (ncyc + 2.5) * T_est
    t = np.linspace(0.0, t_end, int(t_end * fn * 60) + 2)
    S = _simulate(P, Drive(v0), t, 0.0, "none")
    keep = t > 1.5 * T_est
    S2 = {kk: (vv[keep] if isinstance(vv, np.ndarray) else vv) for kk, vv in S.items()}
    return S2


def _stepped_drive(rng, P, sm, vmax, factor, nlev, holds):
    """Levels geometric from vmax/factor to vmax in random order; each lasts 3-6 cycles."""
    fn = P["fn"]
    levels = vmax / factor ** np.linspace(1, 0, nlev)
    rng.shuffle(levels)
    drop_F = sm["drop"] * P["k"]
    tslip = sm["slipdur"]
    t = 0.0
    times, dvs, cur = [], [], levels[0]
    plan = []
    total_cyc = 0
    hold_levels = set()
    if holds:
        hold_levels = set(rng.choice(np.arange(1, nlev), size=min(holds, nlev - 1), replace=False).tolist())
    hold_info = []
    for i, v in enumerate(levels):
        tcyc = drop_F / (P["k"] * v) + tslip
        n = int(rng.integers(3, 7))
        total_cyc += n
        dur = n * tcyc
        if i > 0:
            times.append(t)
            dvs.append(v - cur)
            cur = v
        if i in hold_levels:
            th = t + rng.uniform(0.35, 0.65) * dur
            hd = rng.uniform(3, 10) * (tcyc - tslip)
            times += [th, th + hd]
            dvs += [-v, v]
            hold_info.append(dict(start_s=th, duration_s=hd))
            dur += hd
        plan.append(dict(v0_mm_s=v * 1e3, cycles=n))
        t += dur
    return times, dvs, t, plan, hold_info, total_cyc


# ----------------------------------------------------------------------------------------------------------
# noise and writing
# ----------------------------------------------------------------------------------------------------------
def _ar1(rng, n, rho, std):
    e = rng.normal(0.0, std * math.sqrt(max(1 - rho * rho, 1e-12)), n)
    out = np.empty(n)
    acc = rng.normal(0.0, std)
    for i in range(n):  # simple loop; n < 2e5
        acc = rho * acc + e[i]
        out[i] = acc
    return out


def _ar1_fast(rng, n, rho, std):
    from scipy.signal import lfilter
    e = rng.normal(0.0, std * math.sqrt(max(1 - rho * rho, 1e-12)), n)
    zi = np.array([rho * rng.normal(0.0, std)])
    out, _ = lfilter([1.0], [1.0, -rho], e, zi=zi)
    return out


def _fmt_col(vals, sig=7):
    return [("%." + str(sig) + "g") % v for v in vals]


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    """Write one record (see the module docstring); a draw whose final record does not show enough stick-slip
    cycles is redrawn (deterministically)."""
    for attempt in range(6):
        try:
            return _write_record(case, seed, outdir, nuisance, attempt)
        except _Redraw:
            continue
    raise RuntimeError("no usable record for %s seed %d" % (case, seed))


class _Redraw(Exception):
    pass


def _write_record(case, seed, outdir, nuisance, attempt):
    if case not in CASES:
        raise ValueError("unknown case %r" % (case,))
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % (nuisance,))
    seed = int(seed)
    ci, ni = CASES.index(case), NUISANCES.index(nuisance)
    extra = [attempt] if attempt else []
    rng = np.random.default_rng([seed, 4242, ci] + extra)
    rng_fmt = np.random.default_rng([seed, 77, ci] + extra)
    rng_nz = np.random.default_rng([seed, 91, ci, ni] + extra)

    stepped = case == "static_ageing" or (case == "none" and rng.random() < 0.5)
    holds = 0
    if case == "static_ageing" and rng.random() < 0.5:
        holds = int(rng.integers(1, 4))

    # --- draw a system that really sticks and slips -------------------------------------------------------
    for attempt in range(40):
        stick_periods = _logu(rng, 1.5, 4.0) if stepped else _logu(rng, 2.0, 12.0)
        P = _draw_system(rng, stick_periods)
        Sb = _short_run(P, P["v0"])
        sm = _summary(Sb, P["fn"])
        if _ok(sm):
            break
    else:
        raise RuntimeError("no stick-slip parameter set found")
    P["draw_attempts"] = attempt + 1
    fn, k, m = P["fn"], P["k"], P["m"]
    params = {"fn_Hz": fn, "m_kg": m, "k_N_per_m": k, "N0_N": P["N0"], "Fs_N": P["Fs"], "Fc_N": P["Fc"],
              "vs_mm_s": P["vs"] * 1e3, "stribeck_exponent": P["delta"], "sigma0_N_per_m": P["sigma0"],
              "sigma0_over_k": P["sigma0"] / k, "sigma1_N_s_per_m": P["sigma1"],
              "sigma2_N_s_per_m": P["sigma2"], "zeta": P["zeta"], "zeta_contact": P["zeta_contact"],
              "c_N_s_per_m": P["c"], "draw_attempts": attempt + 1}

    # --- drive --------------------------------------------------------------------------------------------
    fss = sm["fss"]
    v0n = P["v0"]
    plan, hold_info = None, []
    if stepped:
        factor = _logu(rng, 4.0, 8.0)
        nlev = int(rng.integers(4, 7))
        times, dvs, t_rec, plan, hold_info, ncyc = _stepped_drive(rng, P, sm, v0n, factor, nlev, holds)
        # the first level starts at t = 0 after a warm-up at that level
        v_first = v0n / factor ** np.linspace(1, 0, nlev)  # unused, kept for clarity
        levels = [pl["v0_mm_s"] * 1e-3 for pl in plan]
        drive = Drive(levels[0], times, dvs, width=0.1 / fn)
        t_warm = 1.5 * (sm["drop"] / levels[0] + sm["slipdur"])
        params.update({"drive": "stepped", "drive_levels_mm_s": [pl["v0_mm_s"] for pl in plan],
                       "drive_level_cycles": [pl["cycles"] for pl in plan], "drive_factor": factor,
                       "drive_step_times_s": [float(x) for x in times], "holds": hold_info,
                       "step_width_s": 0.1 / fn})
    else:
        ncyc = int(rng.integers(12, 41))
        t_rec = ncyc / fss
        mod_a = mod_f = mod_phi = 0.0
        if case == "drive_modulation":
            mod_a = rng.uniform(0.2, 0.45)
            mod_f = rng.uniform(0.1, 0.5) * fss
            mod_phi = rng.uniform(0, 2 * math.pi)
            params.update({"drive_mod_amplitude_frac": mod_a, "drive_mod_f_Hz": mod_f,
                           "drive_mod_f_over_fss": mod_f / fss, "drive_mod_phase_rad": mod_phi})
        drive = Drive(v0n, mod_a=mod_a, mod_f=mod_f, mod_phi=mod_phi)
        t_warm = 1.5 / fss
        params.update({"drive": "modulated" if mod_a else "constant", "v0_mm_s": v0n * 1e3})
    params.update({"n_cycles_planned": int(ncyc), "stick_periods_at_ref_v0": stick_periods,
                   "fss_base_Hz": fss, "drop_base_frac": float(np.median(sm["dropfrac"])),
                   "presliding_frac_base": sm["presl"]})

    # --- sampling -----------------------------------------------------------------------------------------
    spp = rng_fmt.uniform(10, 15) if nuisance == "coarse" else _logu(rng_fmt, 20, 100)
    dt = 1.0 / (fn * spp)
    t = np.arange(0.0, t_rec, dt)
    params["samples_per_period"] = spp
    params["dt_s"] = dt
    t_sim = t  # record grid

    # --- case calibration ---------------------------------------------------------------------------------
    drop_F = sm["drop"] * k
    P["twin_von"] = 0.1 * sm["vpeak"]
    P["twin_fscale"] = 0.03 * drop_F
    P["twin_tau"] = rng.uniform(0.01, 0.025) / fn
    P["age_vth"] = 0.3 * (min(params.get("drive_levels_mm_s", [v0n * 1e3])) * 1e-3)
    P["age_tau_reset"] = 0.05 / fn

    def run(case_on):
        return _simulate(P, drive, t_sim, -t_warm, case_on)

    if case == "twin_branch":
        target = rng.uniform(0.12, 0.22)
        d0 = _twin_metric(Sb, sm["slips"])
        gmid = P["Fc"] + (P["Fs"] - P["Fc"]) * math.exp(-(0.5 * sm["vpeak"] / P["vs"]) ** P["delta"])
        P["twin_b"] = max((target * drop_F - d0) / gmid, 0.01)
        for it in range(4):
            St = _simulate(P, Drive(v0n), Sb["t"], -1.0 / fss, "twin_branch")
            smt = _summary(St, fn)
            if smt is None:
                raise _Redraw()
            dd = _twin_metric(St, smt["slips"]) / (smt["drop"] * k)
            if abs(dd - target) < 0.02:
                break
            P["twin_b"] *= (target - d0 / drop_F) / max(dd - d0 / drop_F, 1e-3)
        params.update({"twin_target_frac_of_drop": target, "twin_b": P["twin_b"],
                       "twin_tau_s": P["twin_tau"], "twin_v_on_mm_s": P["twin_von"] * 1e3,
                       "twin_base_lag_frac_of_drop": d0 / drop_F})
    if case == "load_variation":
        target = rng.uniform(0.12, 0.35)
        sign = 1.0 if rng.random() < 0.5 else -1.0
        P["load_xmean"] = sm["qmean"]
        P["load_c"] = sign * target / sm["drop"]
        params.update({"load_pp_target_frac": target, "load_sign": sign})
    if case == "triggering":
        for _ in range(100):
            ftr = rng.uniform(2.5, 8.0) * fn
            r = ftr / fss
            if abs(r - round(r)) > 0.15:
                break
        P["trig_f"], P["trig_a"], P["trig_phi"] = ftr, rng.uniform(0.03, 0.08), rng.uniform(0, 2 * math.pi)
        params.update({"trig_f_Hz": ftr, "trig_f_over_fn": ftr / fn, "trig_f_over_fss": ftr / fss,
                       "trig_amplitude_frac": P["trig_a"], "trig_phase_rad": P["trig_phi"]})
    if case == "static_ageing":
        target = rng.uniform(0.07, 0.17)
        lv = np.array(params["drive_levels_mm_s"]) * 1e-3
        tst = drop_F / (k * lv)
        hmin = float(tst.min())
        hmax = max([float(tst.max())] + [h["duration_s"] + float(tst.max()) for h in hold_info])
        P["age_tau"] = hmin * _logu(rng, 0.05, 1.0)
        L = lambda h: math.log1p(h / P["age_tau"])
        P["age_beta"] = target / (L(hmax) - L(hmin) - target * L(hmin))
        params.update({"age_target_growth": target, "age_tau_s": P["age_tau"],
                       "age_vth_mm_s": P["age_vth"] * 1e3, "age_reset_tau_s": P["age_tau_reset"]})

    S = run(case)
    smS = _summary(S, fn)
    if smS is None:
        raise _Redraw()

    if case == "load_variation":
        for it in range(2):
            pp = _load_pp(S, smS)
            if 0.1 < pp < 0.4 and abs(pp - params["load_pp_target_frac"]) < 0.05:
                break
            P["load_c"] *= params["load_pp_target_frac"] / pp
            S = run(case)
            smS = _summary(S, fn)
            if smS is None:
                raise _Redraw()
        params.update({"load_c_per_mm": P["load_c"] * 1e-3, "load_xmean_mm": P["load_xmean"] * 1e3,
                       "load_pp_measured_frac": _load_pp(S, smS)})
    if case == "static_ageing":
        for it in range(3):
            gr = _age_growth(S, smS, P["age_tau"])
            if abs(gr - params["age_target_growth"]) < 0.03:
                break
            P["age_beta"] *= params["age_target_growth"] / max(gr, 0.01)
            S = run(case)
            smS = _summary(S, fn)
            if smS is None:
                raise _Redraw()
        params.update({"age_beta": P["age_beta"], "age_growth_measured": _age_growth(S, smS, P["age_tau"])})
    if case == "twin_branch":
        params["twin_measured_frac_of_drop"] = _twin_metric(S, smS["slips"]) / (smS["drop"] * k)

    # --- measured quantities of the final record ----------------------------------------------------------
    if smS is None or len(smS["cyc"]) < 8 or not smS["allstop"] or np.min(smS["dropfrac"]) < 0.1:
        raise _Redraw()          # the final record must itself show real stick-slip (e.g. triggering can quench it)
    params.update({"n_cycles_measured": len(smS["cyc"]), "drop_frac_min": float(np.min(smS["dropfrac"])),
                   "drop_frac_max": float(np.max(smS["dropfrac"])), "drop_mm": smS["drop"] * 1e3,
                   "peak_mm": smS["peak"] * 1e3, "fss_measured_Hz": smS["fss"],
                   "stop_every_cycle": bool(smS["allstop"]), "presliding_frac": smS["presl"]})

    # --- channels (noise free) ----------------------------------------------------------------------------
    n = len(t)
    x_mm = S["q"] * 1e3
    drop_mm = smS["drop"] * 1e3
    rdrop = smS["drop"] / smS["peak"]
    Nt = P["N0"] * S["nr"]
    fmt_disp = rng_fmt.random() < 0.6
    need_normal = case in ("load_variation", "triggering")
    has_normal = need_normal or rng_fmt.random() < 0.5
    drive_col = None
    if stepped:
        drive_col = "v0" if rng_fmt.random() < 0.5 else "position"
    elif case != "drive_modulation" and rng_fmt.random() < 0.25:
        drive_col = "v0" if rng_fmt.random() < 0.5 else "position"
    if fmt_disp and drive_col == "position":
        drive_col = "v0"  # displacement records carry the drive as v0
    params["record_kind"] = "displacement" if fmt_disp else "force"
    params["normal_channel"] = bool(has_normal)
    params["drive_column"] = drive_col

    # normal channel in "N" units; converted later
    S_N = rdrop * P["N0"]
    # --- base noise ----------------------------------------------------------------------------------------
    wf = rng_nz.uniform(0.002, 0.01)
    cf = rng_nz.uniform(0.002, 0.008)
    ctau = _logu(rng_nz, 0.5, 5.0) / fn
    rho = math.exp(-dt / ctau)
    x_meas = x_mm + rng_nz.normal(0, wf * drop_mm, n) + _ar1_fast(rng_nz, n, rho, cf * drop_mm)
    N_meas = Nt + rng_nz.normal(0, wf * S_N, n) + _ar1_fast(rng_nz, n, rho, cf * S_N)
    v_true = drive.v_array(t) if drive_col == "v0" else None
    v_meas = None
    if v_true is not None:
        vm = float(np.mean(v_true))
        v_meas = v_true * 1e3 + rng_nz.normal(0, rng_nz.uniform(0.002, 0.005) * vm * 1e3, n)
    pos_meas = None
    if drive_col == "position":
        pos_meas = drive.position(t) * 1e3 + rng_nz.normal(0, 0.002 * drop_mm, n)
    params.update({"noise_white_frac_of_drop": wf, "noise_ar1_frac_of_drop": cf, "noise_ar1_tau_s": ctau})
    if rng_nz.random() < 0.3:
        va = drop_mm / rng_nz.uniform(100, 500)
        vf = rng_nz.uniform(3, 12) * fn
        x_meas += va * np.sin(2 * math.pi * vf * t + rng_nz.uniform(0, 2 * math.pi))
        params.update({"tiny_vibration_mm": va, "tiny_vibration_f_Hz": vf})

    # --- nuisance -----------------------------------------------------------------------------------------
    fn_given = fn
    if nuisance == "hum":
        fh = 50.0 if rng_nz.random() < 0.5 else 60.0
        frac = rng_nz.uniform(0.01, 0.05)
        h2, h3 = rng_nz.uniform(0.1, 0.5), rng_nz.uniform(0.05, 0.3)
        ph = rng_nz.uniform(0, 2 * math.pi, 3)
        hum = (np.sin(2 * math.pi * fh * t + ph[0]) + h2 * np.sin(4 * math.pi * fh * t + ph[1])
               + h3 * np.sin(6 * math.pi * fh * t + ph[2]))
        x_meas += frac * drop_mm * hum
        N_meas += frac * S_N * np.roll(hum, 1)
        if v_meas is not None:
            v_meas += frac * 0.5 * np.mean(v_meas) * hum
        params.update({"hum_f_Hz": fh, "hum_frac_of_drop": frac, "hum_h2": h2, "hum_h3": h3})
    elif nuisance == "drift":
        dx = rng_nz.uniform(0.005, 0.03) * drop_mm * (1 if rng_nz.random() < 0.5 else -1)
        dN = rng_nz.uniform(0.01, 0.05) * float(np.mean(Nt)) * (1 if rng_nz.random() < 0.5 else -1)
        u = t / t[-1]
        shape_x = u if rng_nz.random() < 0.5 else u ** 2
        shape_n = u if rng_nz.random() < 0.5 else np.sin(0.5 * math.pi * u)
        x_meas += dx * shape_x
        N_meas += dN * shape_n
        params.update({"drift_x_mm": dx, "drift_N_N": dN})
    elif nuisance == "spikes":
        frac = rng_nz.uniform(0.0005, 0.005)
        ns = max(1, int(round(frac * n)))
        idx = rng_nz.choice(n, ns, replace=False)
        chans = rng_nz.integers(0, 2 if has_normal else 1, ns)
        mag = rng_nz.uniform(0.05, 0.3, ns) * rng_nz.choice([-1.0, 1.0], ns)
        for i, ch, mg in zip(idx, chans, mag):
            if ch == 0:
                x_meas[i] += mg * drop_mm
            else:
                N_meas[i] += mg * S_N
        params.update({"spikes_n": int(ns), "spikes_frac": ns / n})
    elif nuisance == "fn_off":
        fn_given = fn * (1.05 if rng_nz.random() < 0.5 else 0.95)
    qstep = None
    if nuisance == "quantisation":
        qf = rng_nz.uniform(0.002, 0.01)
        x_meas = np.round(x_meas / (qf * drop_mm)) * qf * drop_mm
        N_meas = np.round(N_meas / (qf * S_N)) * qf * S_N
        if v_meas is not None:
            st = qf * float(np.mean(v_meas))
            v_meas = np.round(v_meas / st) * st
        if pos_meas is not None:
            pos_meas = np.round(pos_meas / (qf * drop_mm)) * qf * drop_mm
        params["quant_frac_of_drop"] = qf

    # --- write --------------------------------------------------------------------------------------------
    sep = [",", "\t", " "][int(rng_fmt.integers(0, 3))]
    if not fmt_disp and sep == " ":
        sep = ","
    units = sep != " " and (not fmt_disp or rng_fmt.random() < 0.6)
    tdec = max(3, int(math.ceil(-math.log10(dt))) + 2)
    cols, names = [["%.*f" % (tdec, v) for v in t]], ["t [s]" if units else "t"]
    args = []
    if fmt_disp:
        cols.append(_fmt_col(x_meas, 7))
        names.append("x [mm]" if units else "x")
        if has_normal:
            kn = _logu(rng_fmt, 1e3, 1e5)  # normal dynamometer stiffness N/m
            off = rng_fmt.uniform(-0.5, 0.5) if rng_fmt.random() < 0.4 else 0.0
            y = off + N_meas / kn * 1e3
            cols.append(_fmt_col(y, 7))
            names.append("y [mm]" if units else "y")
            params.update({"y_gain_mm_per_N": 1e3 / kn, "y_offset_mm": off})
        if drive_col == "v0":
            cols.append(_fmt_col(v_meas, 7))
            names.append("v0 [mm/s]" if units else "v0")
        args += ["--fn", "%.6g" % fn_given]
    else:
        Fmax = smS["peak"] * k
        cands = [u for u, f in (("N", 1.0), ("mN", 1e3), ("uN", 1e6)) if 0.05 <= Fmax * f <= 2e5]
        fu = cands[int(rng_fmt.integers(0, len(cands)))] if cands else "N"
        fsc = {"N": 1.0, "mN": 1e3, "uN": 1e6}[fu]
        cols.append(_fmt_col(x_meas * 1e-3 * k * fsc, 7))
        names.append("F [%s]" % fu)
        if has_normal:
            cols.append(_fmt_col(N_meas * fsc, 7))
            names.append("N [%s]" % fu)
        if drive_col == "v0":
            cols.append(_fmt_col(v_meas, 7))
            names.append("v0 [mm/s]")
        elif drive_col == "position":
            pu = "mm" if rng_fmt.random() < 0.5 else "um"
            ps = 1.0 if pu == "mm" else 1e3
            cols.append(_fmt_col(pos_meas * ps, 8))
            names.append("position [%s]" % pu)
        args += ["--stiffness", "%.6g" % k, "--fn", "%.6g" % fn_given]
        params["force_unit"] = fu
    if drive_col is None:
        args += ["--v0", "%.6g" % (v0n * 1e3)]
    params["separator"] = {",": "comma", "\t": "tab", " ": "space"}[sep]
    ext = ".csv" if sep == "," else ".txt"
    path = os.path.abspath(os.path.join(outdir, "lugre_%s_%d%s" % (case, seed, ext)))
    with open(path, "w") as fh:
        fh.write(sep.join(names) + "\n")
        for row in zip(*cols):
            fh.write(sep.join(row) + "\n")
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance, "file": path,
            "args": args, "fn_true": fn, "fn_given": fn_given, "params": _jsonable(params)}


def _load_pp(S, sm):
    pps = []
    for c1, c2 in zip(sm["cyc"][:-1], sm["cyc"][1:]):
        sel = (S["t"] >= c1["t_peak"]) & (S["t"] < c2["t_peak"])
        if np.any(sel):
            pps.append(float(np.ptp(S["nr"][sel])))
    return float(np.median(pps))


def _age_growth(S, sm, tau):
    """Fit peak = a + b ln(1 + t_stick/tau) over cycles; growth = fit(max)/fit(min) - 1."""
    ts = np.array([c["t_stick"] for c in sm["cyc"]])
    pk = np.array([c["qmax"] for c in sm["cyc"]])
    X = np.log1p(ts / tau)
    A = np.vstack([np.ones_like(X), X]).T
    coef, *_ = np.linalg.lstsq(A, pk, rcond=None)
    lo, hi = coef[0] + coef[1] * X.min(), coef[0] + coef[1] * X.max()
    return float(hi / lo - 1.0)


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
    if isinstance(o, np.ndarray):
        return _jsonable(o.tolist())
    return o


if __name__ == "__main__":
    out = sys.argv[1]
    nseeds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    for case in CASES:
        for seed in range(nseeds):
            nu = NUISANCES[seed % len(NUISANCES)]
            d = os.path.join(out, "%s_%d" % (case, seed))
            os.makedirs(d, exist_ok=True)
            truth = write_record(case, seed, d, nu)
            with open(os.path.join(d, "truth.json"), "w") as fh:
                json.dump(truth, fh, indent=1)
            print(case, seed, nu, os.path.basename(truth["file"]))
