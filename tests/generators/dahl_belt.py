"""Independent record generator: Dahl presliding friction with a velocity-weakening level, belt-driven rig.

Written without reading the diagnosis code; numpy/scipy only.  `write_record(case, seed, outdir, nuisance)`
(see README.md here for the contract; `tests/benchmarks/bench_diagnose.py` loads it).

The rig
-------
A motor runs at v0(t) (motor position u, u' = v0).  It pulls the end s of the measuring spring k through a
belt of finite stiffness kb = 15-30 k, light damping (2-8 % of critical) and a small carriage mass mb =
0.05-0.2 m.  The slider (mass m) rubs on a fixed track:

    mb s'' = kb (u - s) + cb (u' - s') - k (s - x)
    m  x'' = k (s - x) - Ff,          Ff = z + c x' + D_tw w
    z'     = sigma x' (1 - z sign(x') / Fc(x', N))            (Dahl presliding state, F = z)
    Fc(v, N) = N mu_k + (Fs(Nj, theta) - N mu_k) / (1 + |v| / vs),   Fs = Nj mu_s (+ ageing)
    tau_j Nj' = N - Nj                                       (junction load, tau_j = 0.4-1 Tn)

The static part follows the normal load through the junction's lag tau_j (the real contact area needs time
to grow); without it the 2.5-8 fn normal vibration of `triggering` entrains the stick-slip (breakaway locked
to a trough of N).

There is no stick switch: stick is the Dahl state's elastic presliding (sigma = 500-1500 k).  The recorded
force is the measuring spring's k (s - x).  In stick the spring end moves at v0 kb / (kb + k), i.e. 3-6 % below
the motor speed (the rig's belt nuisance, present in every case).

Measured (seeds 0-7 of `none`): rest-phase creep (median slider speed over the middle 80 % of each stick /
drive speed) 0.9-1.8 % (0.35-2.7 % over all cases; the creep grows only near breakaway).  The Dahl state's own
lag makes the friction slightly double-valued, in the other sense than the `twin_branch` effect: decelerating
minus accelerating friction at equal sliding speed (25-85 % of the peak slip speed) is -0.1 % to -0.6 % of the
slip's force drop (params["measured"]["twin_over_drop"] of each record).  `twin_branch` records measure
+13 % to +19 %; `static_ageing` peak growth (slowest vs fastest level) 10-19 %.

Cases
-----
* none: constant drive.  load_variation: N = N0 (1 + c (x - xm)) (a tilted track) or N = N0 (1 + a/2 sin(2 pi
  x / lambda + phi)) (a cam, 1.5-4 cam periods over the record's travel), peak-to-peak 12-35 % of N0; force records
  (a normal force column) on even seeds, displacement records (an affine normal reading y [mm]) on odd seeds.
* twin_branch: a state w, dw/dt = (1 - w)/tau_w while the slider decelerates in a slip (|v| > 1.5 v0),
  -w/tau_w while it accelerates, -w/(10 tau_w) near rest; tau_w = 1-3 % of Tn; D_tw set (one correction from a
  pilot) so that the measured double-valuedness is 10-25 % of the drop.
* static_ageing: Fs = N (mu_s + b ln(1 + theta / tau_a)), theta = time in stick (reset within ~2 % of Tn in a
  slip); the motor steps between 3-5 levels spanning a factor 4-8; the drive is recorded (v0 or position).
* triggering: N = N0 (1 + a sin(2 pi f_tr t + phi)), a = 3-8 %, f_tr = 2.5-8 fn away from multiples of the
  stick-slip frequency (checked on the final record); the normal channel is recorded.
* drive_modulation: v0(t) = v0n (1 + a sin(2 pi fm t + phi)), a = 20-45 %, fm = 0.1-0.5 fss; only --v0 v0n.

Integrator: scipy odeint (LSODA, rtol 1e-6), sampled on a fine grid, the record is every nsub-th sample
(20-100 samples per natural period, 10-15 for `coarse`).
"""
import bisect
import json
import math
import os
import time
import zlib

import numpy as np
from scipy.integrate import odeint

NAME = "dahl_belt"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
TWOPI = 2.0 * math.pi
RTOL = 1e-5


def _rng(*keys):
    s = "|".join(str(k) for k in (NAME,) + keys)
    return np.random.default_rng([zlib.crc32(s.encode()), len(s)])


def _logu(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# ------------------------------------------------------------------------------------------------ drive
class Drive:
    def __init__(self, kind, v0, times=None, levels=None, ramp=0.0, a=0.0, fm=0.0, phi=0.0):
        self.kind, self.v0 = kind, v0
        self.times, self.levels, self.ramp = times, levels, ramp
        self.a, self.fm, self.phi = a, fm, phi

    def v(self, t):
        if self.kind == "const":
            return self.v0
        if self.kind == "mod":
            return self.v0 * (1.0 + self.a * math.sin(TWOPI * self.fm * t + self.phi))
        i = bisect.bisect_right(self.times, t) - 1
        if i < 0:
            return self.levels[0]
        if i > 0 and t - self.times[i] < self.ramp:
            r = (t - self.times[i]) / self.ramp
            return self.levels[i - 1] + r * (self.levels[i] - self.levels[i - 1])
        return self.levels[i]

    def va(self, ts):
        return np.array([self.v(float(t)) for t in ts])


# ------------------------------------------------------------------------------------------------ simulation
def _simulate(P, drive, t_end, dt_fine, twin=False, ageing=False, load=None):
    m, k, kb, mb, cb, c = P["m"], P["k"], P["kb"], P["mb"], P["cb"], P["c"]
    sig, vs, mus, muk, N0 = P["sigma"], P["vs"], P["mu_s"], P["mu_k"], P["N0"]
    Dtw, tw = P.get("D_tw", 0.0), P.get("tau_w", 1.0)
    b_age, tau_a, tau_r, v_age = P.get("b_age", 0.0), P.get("tau_a", 1.0), P.get("tau_r", 1.0), P.get("v_age", 1.0)
    v_lo = 1.5 * P["v_ref"]
    tau_j = P["tau_j"]
    ld = load or {"kind": "const"}
    lk = ld["kind"]
    dv = drive.v

    def Nof(t, x):
        if lk == "const":
            return N0
        if lk == "tilt":
            return N0 * (1.0 + ld["c"] * (x - ld["xm"]))
        if lk == "cam":
            return N0 * (1.0 + 0.5 * ld["a"] * math.sin(TWOPI * x / ld["lam"] + ld["phi"]))
        return N0 * (1.0 + ld["a"] * math.sin(TWOPI * ld["f"] * t + ld["phi"]))

    def rhs(t, y):
        u, s, sd, x, v, z, w, th, Nj = y
        v0 = dv(t)
        N = Nof(t, x)
        Fs = Nj * mus
        if ageing:
            Fs += Nj * b_age * math.log(1.0 + max(th, 0.0) / tau_a)
        Fk = N * muk
        av = abs(v)
        Fc = Fk + (Fs - Fk) / (1.0 + av / vs)
        Fspr = k * (s - x)
        Ff = z + c * v + Dtw * w
        a = (Fspr - Ff) / m
        sdd = (kb * (u - s) + cb * (v0 - sd) - Fspr) / mb
        dz = sig * (v - av * z / Fc)
        dw = 0.0
        if twin:
            if av > v_lo:
                dw = (1.0 - w) / tw if a * v < 0.0 else -w / tw
            else:
                dw = -w / (10.0 * tw)
        dth = 0.0
        if ageing:
            g = 1.0 / (1.0 + (v / v_age) ** 2)
            dth = g - (1.0 - g) * th / tau_r
        return [v0, sd, sdd, v, a, dz, dw, dth, (N - Nj) / tau_j]

    F0 = P["N0"] * muk
    v00 = dv(0.0)
    y0 = [F0 / k + F0 / kb, F0 / k, v00, 0.0, 0.0, F0, 0.0, 0.0, Nof(0.0, 0.0)]
    n = int(t_end / dt_fine) + 1
    te = np.arange(n) * dt_fine
    atol = [1e-9 * P["xs"], 1e-9 * P["xs"], 1e-7 * P["vsc"], 1e-9 * P["xs"], 1e-7 * P["vsc"], 1e-7 * P["Fsc"],
            1e-6, 1e-6 * P["Tn"], 1e-7 * N0]
    Y, infod = odeint(rhs, y0, te, rtol=RTOL, atol=atol, hmax=P["Tn"] / 8.0, mxstep=200000, tfirst=True,
                      full_output=True)
    if infod["message"] != "Integration successful.":
        return None
    u, s, sd, x, v, z, w, th, Nj = Y.T
    t = te
    N = np.array([Nof(tt, xx) for tt, xx in zip(t, x)]) if lk != "const" else np.full(t.size, N0)
    return dict(t=t, u=u, s=s, x=x, v=v, z=z, w=w, th=th, F=P["k"] * (s - x), Ff=z + c * v + Dtw * w, N=N,
                vd=drive.va(t) if drive.kind != "const" else np.full(t.size, drive.v0))


def _cycles(S, Tn):
    """Slip events from the true slider velocity: list of (i_start, i_peak_v, i_end) plus peak/trough forces."""
    v, F, vd = S["v"], S["F"], S["vd"]
    thr = 1.5 * np.abs(vd) + 1e-15
    on = v > np.maximum(thr, 0.05 * np.max(v))
    idx = np.flatnonzero(np.diff(on.astype(int)) == 1) + 1
    ends = np.flatnonzero(np.diff(on.astype(int)) == -1) + 1
    ev = []
    for i0 in idx:
        j = ends[ends > i0]
        if j.size == 0:
            break
        i1 = int(j[0])
        ip = i0 + int(np.argmax(v[i0:i1]))
        # force peak just before, trough just after
        dt = S["t"][1] - S["t"][0]
        w = max(2, int(0.3 * Tn / dt))
        a = max(0, i0 - w)
        b = min(F.size, i1 + w)
        Fp = float(np.max(F[a:i1]))
        Ft = float(np.min(F[i0:b]))
        ev.append((int(i0), int(ip), int(i1), Fp, Ft))
    return ev


def _measure(S, P, ev, skip_t=0.0):
    t, v, vd, Ff = S["t"], S["v"], S["vd"], S["Ff"]
    ev = [e for e in ev if t[e[0]] >= skip_t]
    out = {"n_slips": len(ev)}
    if len(ev) < 3:
        return out
    tp = np.array([t[e[0]] for e in ev])
    out["Tss"] = float(np.median(np.diff(tp)))
    drops = np.array([e[3] - e[4] for e in ev])
    out["drop"] = float(np.median(drops))
    # rest-phase creep: slider speed between slips (middle 80 % of each stick) over the drive speed
    cr = []
    for e0, e1 in zip(ev[:-1], ev[1:]):
        a, b = e0[2], e1[0]
        L = b - a
        if L < 5:
            continue
        sl = slice(a + L // 10, b - L // 10)
        cr.append(np.median(v[sl] / np.maximum(np.abs(vd[sl]), 1e-15)))
    out["creep_over_v0"] = float(np.median(cr)) if cr else float("nan")
    out["stick_fraction_min_speed"] = float(np.min(np.abs(v[ev[0][2]:ev[-1][0]]))
                                            / max(np.min(np.abs(vd)), 1e-15))
    # double-valuedness: decelerating minus accelerating friction at equal speed, over the drop
    tw = []
    for (i0, ip, i1, Fp, Ft) in ev:
        vp = v[ip]
        if ip - i0 < 4 or i1 - ip < 4:
            continue
        vg = np.linspace(0.25, 0.85, 13) * vp
        va, fa = v[i0:ip + 1], Ff[i0:ip + 1]
        vdc, fdc = v[ip:i1 + 1][::-1], Ff[ip:i1 + 1][::-1]
        oa, od = np.argsort(va), np.argsort(vdc)
        Fa = np.interp(vg, va[oa], fa[oa])
        Fd = np.interp(vg, vdc[od], fdc[od])
        tw.append(float(np.mean(Fd - Fa) / max(Fp - Ft, 1e-30)))
    out["twin_over_drop"] = float(np.median(tw)) if tw else float("nan")
    out["vpeak_over_v0"] = float(np.median([v[e[1]] for e in ev]) / max(float(np.median(np.abs(vd))), 1e-15))
    return out


# ------------------------------------------------------------------------------------------------ physics draw
def _draw(rng, case):
    P = {}
    P["fn"] = _logu(rng, 6.0, 25.0) if case != "static_ageing" else _logu(rng, 12.0, 30.0)
    P["Tn"] = 1.0 / P["fn"]
    wn = TWOPI * P["fn"]
    P["N0"] = _logu(rng, 0.5, 20.0)
    P["mu_s"] = float(rng.uniform(0.3, 0.7))
    P["mu_k"] = P["mu_s"] * float(rng.uniform(0.5, 0.72))
    dF = (P["mu_s"] - P["mu_k"]) * P["N0"]
    A = _logu(rng, 0.05e-3, 0.8e-3)            # slip length scale, m
    P["k"] = 2.0 * dF / A
    P["m"] = P["k"] / wn ** 2
    P["vs"] = float(rng.uniform(0.08, 0.3)) * wn * A / 2.0
    P["sigma"] = float(rng.uniform(500.0, 1500.0)) * P["k"]
    P["tau_j"] = float(rng.uniform(0.4, 1.0)) * P["Tn"]
    P["zeta"] = float(rng.uniform(0.005, 0.025))
    P["c"] = 2.0 * P["zeta"] * P["m"] * wn
    P["kb_over_k"] = float(rng.uniform(15.0, 30.0))
    P["kb"] = P["kb_over_k"] * P["k"]
    P["mb"] = float(rng.uniform(0.05, 0.2)) * P["m"]
    P["zeta_b"] = float(rng.uniform(0.02, 0.08))
    P["cb"] = 2.0 * P["zeta_b"] * math.sqrt((P["kb"] + P["k"]) * P["mb"])
    keff = P["k"] * P["kb"] / (P["k"] + P["kb"])
    P["Tstick"] = float(rng.uniform(1.5, 4.5)) * P["Tn"] if case != "static_ageing" else \
        float(rng.uniform(1.2, 2.0)) * P["Tn"]
    P["v0"] = 2.0 * dF / (keff * P["Tstick"])
    P["xs"], P["vsc"], P["Fsc"] = A, wn * A, P["mu_s"] * P["N0"]
    P["v_ref"] = P["v0"]
    # lowest mode of the coupled rig (slider + belt carriage), for information
    M = np.diag([P["m"], P["mb"]])
    K = np.array([[P["k"], -P["k"]], [-P["k"], P["k"] + P["kb"]]])
    ev = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    P["fn_coupled_sliding"] = float(math.sqrt(ev[0]) / TWOPI)
    P["f_belt_mode"] = float(math.sqrt(ev[1]) / TWOPI)
    return P


def _pilot(P, drive, ncyc=7, Tss=None, **kw):
    if Tss is None:
        Tss = P["Tstick"] * P["v0"] / drive.v0 + 0.6 * P["Tn"]
    S = _simulate(P, drive, ncyc * Tss, P["Tn"] / 60.0, **kw)
    if S is None:
        return None, None
    ev = _cycles(S, P["Tn"])
    M = _measure(S, P, ev, skip_t=1.2 * Tss)
    ok = (M.get("n_slips", 0) >= 3 and M.get("creep_over_v0", 1.0) < 0.05 and M.get("vpeak_over_v0", 0) > 3.0
          and M.get("drop", 0.0) > 0.6 * (P["mu_s"] - P["mu_k"]) * P["N0"])
    M["ok"] = bool(ok)
    return M, S


def _fmt_time(dt):
    d = max(0, int(math.ceil(-math.log10(dt))) + 2)
    return "%." + str(d) + "f"


# ------------------------------------------------------------------------------------------------ main entry
def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    tic = time.time()
    rng = _rng(case, seed)
    rn = _rng(case, seed, nuisance)
    fr = _rng(case, seed, "format")
    info = {}
    twin = case == "twin_branch"
    ageing = case == "static_ageing"

    for attempt in range(20):
        P = _draw(rng, case)
        Tn = P["Tn"]
        if ageing:
            factor = float(rng.uniform(4.0, 8.0))
            nl = int(rng.integers(3, 6))
            lev = list(P["v0"] / factor ** (np.arange(nl) / (nl - 1.0)))
            order = list(rng.permutation(nl))
            while any(abs(order[i] - order[i + 1]) == 0 for i in range(nl - 1)):
                order = list(rng.permutation(nl))
            lev = [float(lev[i]) for i in order]
            ncl = int(rng.integers(5, 9))
            Tsts = [P["Tstick"] * P["v0"] / L + 0.6 * Tn for L in lev]
            tot = sum(ncl * T for T in Tsts) + 1.5 * Tsts[0]
            if tot > 19.0 or ncl * nl < 19:
                continue
            P["v_age"] = 0.3 * min(lev)
            P["tau_a"] = float(rng.uniform(0.1, 0.4)) * P["Tstick"]
            P["tau_r"] = 0.02 * Tn
            g = float(rng.uniform(0.09, 0.15))
            Tf, Tsl = P["Tstick"], P["Tstick"] * factor
            P["b_age"] = 1.1 * g * P["mu_s"] / (math.log(1 + Tsl / P["tau_a"]) - math.log(1 + Tf / P["tau_a"]))
            P["age_growth_design"] = g
            P["v_ref"] = P["v0"]
            M1, _ = _pilot(P, Drive("const", max(lev)), ncyc=5, ageing=True)
            if M1 is None or not M1["ok"]:
                continue
            pil = M1
            break
        P_try = dict(P)
        M, _ = _pilot(P_try, Drive("const", P["v0"]))
        if M is None or not M["ok"]:
            continue
        Tss = M["Tss"]
        if not (2.0 / 38.0 < Tss < 20.0 / 16.0):
            continue
        if case == "drive_modulation":
            a_m = float(rng.uniform(0.2, 0.45))
            P["v_ref"] = P["v0"] * (1 - a_m)
            M2, _ = _pilot(P, Drive("const", P["v0"] * (1 - a_m)), ncyc=5)
            M3, _ = _pilot(P, Drive("const", P["v0"] * (1 + a_m)), ncyc=6)
            if M2 is None or M3 is None or not (M2["ok"] and M3["ok"]):
                continue
            info["a_mod"] = a_m
        pil = M
        break
    else:
        raise RuntimeError("no stick-slip regime found")

    Tn = P["Tn"]
    # ------------------------------------------------------------------ drive, load, record length
    load = None
    if ageing:
        times, levels = [0.0], [lev[0]]
        tcur = 1.5 * Tsts[0] + ncl * Tsts[0]
        for i in range(1, nl):
            times.append(tcur)
            levels.append(lev[i])
            tcur += ncl * Tsts[i]
        drive = Drive("steps", max(lev), times=times, levels=levels, ramp=0.05 * Tn)
        t_rec0 = 1.0 * Tsts[0]
        t_end = tcur
        info.update(drive="steps", levels_m_s=levels, step_times_s=times, factor=factor, cycles_per_level=ncl)
    else:
        Tss = pil["Tss"]
        ncyc = float(rng.uniform(18.0, 36.0))
        dur = min(max(ncyc * Tss, 2.0), 19.5)
        t_rec0 = 1.5 * Tss
        t_end = t_rec0 + dur
        if case == "drive_modulation":
            fm = float(rng.uniform(0.12, 0.45)) / Tss
            phi = float(rng.uniform(0, TWOPI))
            drive = Drive("mod", P["v0"], a=info["a_mod"], fm=fm, phi=phi)
            info.update(drive="modulated", v0n=P["v0"], fm_hz=fm, fm_over_fss=fm * Tss, phi=phi)
        else:
            drive = Drive("const", P["v0"])
            info.update(drive="constant")
        if case == "load_variation":
            travel = P["v0"] * dur
            ptp = float(rng.uniform(0.12, 0.35))
            if rng.random() < 0.5:
                xm = P["v0"] * (t_rec0 + 0.5 * dur)
                load = {"kind": "tilt", "c": ptp / travel, "xm": xm}
            else:
                load = {"kind": "cam", "a": ptp, "lam": travel / float(rng.uniform(1.5, 4.0)),
                        "phi": float(rng.uniform(0, TWOPI))}
            info.update(load=load, load_ptp_design=ptp)
        if case == "triggering":
            a_t = float(rng.uniform(0.03, 0.08))
            fss = 1.0 / Tss
            for _ in range(200):
                ftr = float(rng.uniform(2.5, 8.0)) * P["fn"]
                r = ftr / fss
                if 0.25 < r - math.floor(r) < 0.75:
                    break
            load = {"kind": "trig", "a": a_t, "f": ftr, "phi": float(rng.uniform(0, TWOPI))}
            info.update(load=load, ftr_over_fn=ftr / P["fn"], ftr_over_fss_pilot=ftr * Tss)
    if twin:
        frac = float(rng.uniform(0.13, 0.22))
        P["tau_w"] = float(rng.uniform(0.01, 0.03)) * Tn
        P["D_tw"] = frac * pil["drop"] * 1.3
        P["v_ref"] = P["v0"]
        for it in range(3):
            Mt, _ = _pilot(P, drive, ncyc=6, twin=True)
            if Mt is None or not np.isfinite(Mt.get("twin_over_drop", np.nan)) or Mt["twin_over_drop"] <= 0:
                break
            err = frac / Mt["twin_over_drop"]
            if abs(err - 1.0) < 0.12:
                break
            P["D_tw"] *= min(max(err, 0.5), 2.0)
        info["twin_target"] = frac

    # ------------------------------------------------------------------ sampling and final run
    sp = float(rng.uniform(20.0, 100.0)) if nuisance != "coarse" else float(rn.uniform(10.0, 15.0))
    dt = Tn / sp
    nsub = max(1, int(math.ceil(150.0 / sp)))
    S = _simulate(P, drive, t_end, dt / nsub, twin=twin, ageing=ageing, load=load)
    if S is None:
        raise RuntimeError("integration failed")
    ev = _cycles(S, Tn)
    meas = _measure(S, P, ev, skip_t=t_rec0)
    sel = slice(int(round(t_rec0 / (dt / nsub))), None, nsub)
    ts = S["t"][sel] - S["t"][sel][0]
    F = S["F"][sel].copy()
    Nn = S["N"][sel].copy()
    vdr = S["vd"][sel].copy()
    pos = S["u"][sel].copy()
    meas["N_ptp_over_N0"] = float(np.ptp(S["N"][sel]) / P["N0"])
    if case == "triggering":
        meas["ftr_over_fss"] = float(load["f"] * meas.get("Tss", np.nan))
    if ageing:
        # peak force per level, against stick time
        tp = S["t"]
        pk = []
        for j in range(len(levels)):
            t_a = times[j] + 1.5 * Tsts[j] if j == 0 else times[j] + 1.2 * Tsts[j]
            t_b = times[j + 1] if j + 1 < len(levels) else t_end
            pks = [e[3] for e in ev if t_a <= tp[e[0]] < t_b]
            if pks:
                pk.append((levels[j], float(np.median(pks))))
        if pk:
            pk.sort()
            meas["peak_by_level"] = pk
            meas["peak_growth_over_peak"] = float((pk[0][1] - pk[-1][1]) / pk[-1][1])
    drop = meas.get("drop", pil["drop"])

    # ------------------------------------------------------------------ sensor noise and nuisances
    nz = {}
    nsd = float(rn.uniform(0.001, 0.003)) * drop
    F = F + rn.normal(0.0, nsd, F.size)
    Nn = Nn + rn.normal(0.0, 0.002 * P["N0"] * 0.05, Nn.size)
    nz["white_over_drop"] = nsd / drop
    if nuisance == "hum":
        fh = float(rn.choice([50.0, 60.0]))
        amp = float(rn.uniform(0.01, 0.05)) * drop
        h = amp * np.sin(TWOPI * fh * ts + rn.uniform(0, TWOPI))
        h += 0.3 * amp * np.sin(TWOPI * 3 * fh * ts + rn.uniform(0, TWOPI))
        F = F + h
        nz.update(hum_hz=fh, hum_over_drop=amp / drop)
    elif nuisance == "drift":
        amp = float(rn.uniform(0.02, 0.06)) * drop * float(rn.choice([-1.0, 1.0]))
        T = ts[-1]
        F = F + amp * (0.7 * ts / T + 0.3 * (ts / T) ** 2)
        nz.update(drift_over_drop=amp / drop)
    elif nuisance == "spikes":
        fr_s = float(rn.uniform(0.0005, 0.005))
        ns = max(2, int(round(fr_s * F.size)))
        ii = rn.choice(F.size, ns, replace=False)
        F[ii] += rn.choice([-1.0, 1.0], ns) * rn.uniform(0.3, 1.5, ns) * drop
        nz.update(spike_fraction=ns / F.size)
    elif nuisance == "quantisation":
        q = float(rn.uniform(0.002, 0.01)) * drop
        F = np.round(F / q) * q
        nz.update(adc_step_over_drop=q / drop)
    fn_given = None
    if nuisance == "fn_off":
        fn_given = P["fn"] * float(rn.choice([0.95, 1.05]))
    elif fr.random() < 7.0 / 8.0:
        fn_given = P["fn"]

    # ------------------------------------------------------------------ record file
    if case == "load_variation":
        disp = seed % 2 == 1
    else:
        disp = bool(fr.random() < 0.4)
    has_N = case in ("load_variation", "triggering") or bool(fr.random() < 0.3)
    drive_col = None
    if ageing:
        drive_col = "v0" if disp else str(fr.choice(["v0", "pos"]))
    elif case != "drive_modulation" and fr.random() < 0.25:
        drive_col = "v0" if disp else str(fr.choice(["v0", "pos"]))
    args = []
    if fn_given is not None:
        args += ["--fn", "%.6g" % fn_given]
    if drive_col is None:
        args += ["--v0", "%.6g" % (P["v0"] * 1e3)]
    cols = []
    if disp:
        cols.append(("x [mm]", F / P["k"] * 1e3))
        if has_N:
            gy = float(fr.uniform(0.3, 3.0)) / P["N0"]
            y0 = float(fr.uniform(-2.0, 2.0))
            cols.append(("y [mm]", y0 + gy * Nn))
            info["normal_reading"] = {"offset_mm": y0, "mm_per_N": gy}
        if drive_col == "v0":
            cols.append(("v0 [mm/s]", vdr * 1e3))
        tname = str(fr.choice(["t [s]", "time [s]"]))
        sep = str(fr.choice([",", "\t"]))
        kind = "displacement"
    else:
        scale = {"N": 1.0, "mN": 1e3}
        fu = "mN" if P["mu_s"] * P["N0"] < 2.0 else str(fr.choice(["N", "mN"]))
        cols.append(("%s [%s]" % (str(fr.choice(["friction", "Friction", "F"])), fu), F * scale[fu]))
        if has_N:
            cols.append(("%s [%s]" % (str(fr.choice(["normal", "Normal", "N"])), fu), Nn * scale[fu]))
        if drive_col == "pos":
            pu, ps = ("mm", 1e3) if fr.random() < 0.7 else ("um", 1e6)
            cols.append(("position [%s]" % pu, pos * ps))
        elif drive_col == "v0":
            cols.append(("v0 [mm/s]", vdr * 1e3))
        tname = str(fr.choice(["time [s]", "t [s]", "Time [s]"]))
        sep = str(fr.choice([",", "\t"]))
        kind = "force"
        args += ["--stiffness", "%.6g" % P["k"]]
    os.makedirs(outdir, exist_ok=True)
    fout = os.path.abspath(os.path.join(outdir, "%s_%s_%03d_%s.%s" % (
        NAME, case, seed, nuisance, "csv" if sep == "," else "tsv")))
    names = [tname] + [cn for cn, _ in cols]
    Mx = np.column_stack([ts] + [cv for _, cv in cols])
    with open(fout, "w") as fh:
        fh.write(sep.join(names) + "\n")
        np.savetxt(fh, Mx, fmt=[_fmt_time(dt)] + ["%.7g"] * len(cols), delimiter=sep)

    params = {kk: vv for kk, vv in P.items()}
    params.update(info)
    params.update(dict(samples_per_period=sp, n_sub=nsub, n_samples=int(ts.size), record_kind=kind,
                       has_normal=has_N, drive_column=drive_col, separator=sep, t_record_start=t_rec0,
                       duration_s=float(ts[-1])))
    params["pilot"] = pil
    params["nuisance_params"] = nz
    params["measured"] = meas
    params["seconds"] = time.time() - tic
    params = json.loads(json.dumps(params, default=float))
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=fout, args=args,
                fn_true=float(P["fn"]), fn_given=(float(fn_given) if fn_given is not None else None),
                params=params)
