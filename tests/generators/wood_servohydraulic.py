"""wood_servohydraulic: wood-on-wood friction press on a servo-hydraulic test rig.

Rig
---
An upper beech specimen (carriage mass m, on a linear guide with a little viscous damping c) is pressed onto a
lower spruce board by a force-controlled hydraulic normal cylinder (normal load N0, measured by a load cell under
the lower board).  The carriage is pulled by the piston of a servo-hydraulic actuator through a steel pull rod
with a strain-gauge load cell (tangential stiffness k, fn = sqrt(k/m)/2pi).  The piston follows its velocity
command through the servo loop's first-order lag (tau_servo 4-12 ms); its LVDT travel is recorded.

Friction law (own): saturating-logarithmic weakening with a viscous rise,
    mu(v) = mu_s - D * l/(l + kappa) + eta*v,   l = ln(1 + v/v1),
single-valued in the sliding speed, static level mu(0) = mu_s.

Stick handling: exact stick (x frozen, v = 0) checked vectorised on the fine time grid against
|F_spring| <= mu_s(age) * N(t); breakaway located by linear interpolation of the margin inside the grid
interval; stop located by a secant search on the step length for v = 0; at a stop the block sticks if the
spring force is within the static level, otherwise it slips on in the other direction.

Integrator: 2-stage Gauss-Legendre (implicit, order 4, symplectic) solved by simplified Newton with the
analytic 4x4 Jacobian, on a 10 kHz+ grid; partial first/last steps at the events.

Sensor chain / record: strain-gauge pull-rod cell and the normal load cell through a 4th-order Bessel
anti-alias filter (0.35 fs) in the logger, LVDT of the piston on the same DAQ; white noise per channel.
File: the lab's home-made LabVIEW logger (German university timber lab) -> '.csv' with '#' comment lines,
semicolon delimiter, decimal comma:
    Zeit [s];Reibkraft [N];Normalkraft [N];Kolbenweg [mm]
(no 'Kolbenweg' column when the LVDT was not connected: then `--v0` is passed).  `--stiffness` (N/m,
calibrated) and `--fn` (Hz, ring-down) are always passed.

Cases (effect sizes measured on the noise-free ground truth, seeds 0-7 of write_record, see EFFECTS below
and each record's truth["params"]["measured"]):
  none             constant drive (or 3 recorded levels, factor 1.5-2.5), constant N0, memoryless law.
  load_variation   wedge-lever linkage of the pull rod: N = N0 + lam * F_spring; N peak-to-peak / N0 ~ 0.10-0.35
                   (target 0.14-0.32) measured 0.171-0.314 (median per-cycle N pp/N0).
  twin_branch      fibre-recovery memory: extra friction dmu*tanh((vmax - v)/(0.08 vmax)) on the decelerating
                   half of each slip; branch gap at equal speed (0.2-0.8 vmax) / slip force drop measured 0.145-0.248.
  static_ageing    mu_s(t_stick) = mu_s0 + beta ln(1 + t_stick/tau_a); the drive steps hi/lo/hi/lo/hi by a
                   factor 4-8; growth of the peak force over the range of stick times measured 0.086-0.170 (log fit of peak
                   force vs stick time over stick times ~1.2-24 s, a factor 7-10).
  triggering       servo-valve dither coupling into the normal cylinder: N = N0 (1 + a sin(2 pi f_t t)),
                   a 3-8 %, f_t 2.5-5 fn, frac(f_t/f_ss) in [0.3, 0.7], away from 50 Hz harmonics; measured a 0.033-0.078, f_t/fn 2.84-4.83,
                   frac(f_t/f_ss unperturbed) 0.30-0.66; the breakaway phase-locks to the dither, so in the
                   triggered record f_t is often an integer multiple of the measured f_ss (frac 0.00-0.77).
  drive_modulation v0(t) = v0n (1 + a sin(2 pi fm t + phi)), a 0.20-0.45, fm 0.1-0.5 f_ss (measured f_ss of the
                   modulated record), no position column, only --v0 v0n; measured a 0.29-0.45, fm/f_ss 0.17-0.39.

Known limits of `none`: the law is algebraic in v, so inherent memory = 0 and ageing = 0 exactly (branch gap
measured on truth |gap| < 3e-6 of the drop); N is exactly constant in truth (recorded with 0.15 % noise); the only dynamics
outside the 1-DoF model are the servo lag of the piston (tau 4-12 ms, seen in the recorded Kolbenweg at the
drive steps) and the common delay of the anti-alias filter (same on every channel).  Spread of the peak
spring force (std/drop) in `none`: < 3e-15 (constant drive: exact limit cycle).

Nuisances: hum (50 Hz + 150 Hz + 250 Hz, 1-5 % of the drop, force channel, 1/3 of it on the normal channel),
drift (bridge drift of the pull-rod cell, 2-6 % of the drop over the record, exponential + linear), spikes
(0.05-0.5 % of samples, +-(0.3-1.5) drop on the force channel), quantisation (ADC step 0.2-1 % of the drop on both
force channels), coarse (fs = 10-15 fn), fn_off (--fn given 5 % high or low).
"""
import hashlib
import json
import math
import os

import numpy as np
from scipy import signal

NAME = "wood_servohydraulic"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

# measured over seeds 0-7 (filled in from the check run; see the docstring)
EFFECTS = {"load_variation_N_pp": (0.171, 0.314), "twin_gap_over_drop": (0.145, 0.248),
           "static_ageing_peak_growth": (0.086, 0.170), "triggering_amp": (0.033, 0.078),
           "triggering_f_over_fn": (2.84, 4.83), "drive_modulation_amp": (0.29, 0.45),
           "drive_modulation_fm_over_fss": (0.17, 0.39), "none_twin_gap_abs_max": 3e-6}

_SQ3 = np.sqrt(3.0)
_GA = np.array([[0.25, 0.25 - _SQ3 / 6.0], [0.25 + _SQ3 / 6.0, 0.25]])
_GC = np.array([0.5 - _SQ3 / 6.0, 0.5 + _SQ3 / 6.0])


def _rng(case, seed, nuisance, tag):
    h = hashlib.sha256(f"{NAME}|{case}|{seed}|{nuisance}|{tag}".encode()).digest()
    return np.random.default_rng(int.from_bytes(h[:8], "little"))


class _Law:
    def __init__(self, mu_s, D, v1, kappa, eta):
        self.mu_s, self.D, self.v1, self.kappa, self.eta = mu_s, D, v1, kappa, eta

    def mu(self, v):
        l = math.log1p(v / self.v1)
        return self.mu_s - self.D * l / (l + self.kappa) + self.eta * v

    def dmu(self, v):
        l = math.log1p(v / self.v1)
        return -self.D * self.kappa / (l + self.kappa) ** 2 / (self.v1 + v) + self.eta


def _simulate(p, law, t_end, dt, vcmd_fun, ext):
    """Fine-grid simulation. ext: dict with lam (load coupling), trig (a, f, phi), beta/tau_a/age0 (ageing),
    dmu (twin). vcmd_fun(t_array) -> commanded velocity (m/s). Returns dict of fine-grid arrays + events."""
    m, k, c, N0 = p["m"], p["k"], p["c"], p["N0"]
    n = int(round(t_end / dt)) + 1
    t = np.arange(n) * dt
    # servo piston: first-order velocity lag, exact per grid step for a piecewise-constant command
    vc = vcmd_fun(t)
    al = np.exp(-dt / p["tau_servo"])
    va = signal.lfilter([1 - al], [1, -al], vc, zi=[al * 0.0])[0]
    u = np.concatenate(([0.0], np.cumsum(0.5 * (va[1:] + va[:-1]) * dt)))
    lam = ext.get("lam", 0.0)
    ta, tf, tphi = ext.get("trig", (0.0, 0.0, 0.0))
    Nb = N0 * (1.0 + ta * np.sin(2 * np.pi * tf * t + tphi))
    beta, tau_a, age0 = ext.get("beta", 0.0), ext.get("tau_a", 1.0), ext.get("age0", 0.0)
    dmu_tw = ext.get("dmu", 0.0)
    w_tw = 0.08

    def u_at(tt):
        s = tt / dt
        i = min(int(s), n - 2)
        f = s - i
        return u[i] + f * (u[i + 1] - u[i])

    def nb_at(tt):
        return N0 * (1.0 + ta * math.sin(2 * math.pi * tf * tt + tphi)) if ta else N0

    def rhs(tt, x, v, sg, vmax):
        Fs = k * (u_at(tt) - x)
        N = nb_at(tt) + lam * Fs
        vs = max(sg * v, 0.0)
        mu = law.mu(vs)
        if dmu_tw and vmax > 0:
            mu += dmu_tw * math.tanh(max(vmax - vs, 0.0) / (w_tw * vmax))
        return (Fs - c * v - sg * mu * N) / m, mu, N

    a11, a12, a21, a22 = _GA[0, 0], _GA[0, 1], _GA[1, 0], _GA[1, 1]
    c1, c2 = _GC

    def gl_core(t0, x0, v0, h, sg, vmax):
        Fs = k * (u_at(t0) - x0)
        N = nb_at(t0) + lam * Fs
        vs = max(sg * v0, 0.0)
        mu = law.mu(vs)
        j21, j22 = (-k + sg * mu * lam * k) / m, (-c - N * law.dmu(vs)) / m
        J = np.array([[0.0, 1.0], [j21, j22]])
        Minv = np.linalg.inv(np.eye(4) - h * np.kron(_GA, J))
        z1x = z1v = z2x = z2v = 0.0
        for _ in range(12):
            f1x = v0 + z1v
            f1v = rhs(t0 + c1 * h, x0 + z1x, f1x, sg, vmax)[0]
            f2x = v0 + z2v
            f2v = rhs(t0 + c2 * h, x0 + z2x, f2x, sg, vmax)[0]
            G = (z1x - h * (a11 * f1x + a12 * f2x), z1v - h * (a11 * f1v + a12 * f2v),
                 z2x - h * (a21 * f1x + a22 * f2x), z2v - h * (a21 * f1v + a22 * f2v))
            d = Minv @ G
            z1x -= d[0]
            z1v -= d[1]
            z2x -= d[2]
            z2v -= d[3]
            if not (abs(z1v) < 10.0 and abs(z2v) < 10.0):
                return None
            if abs(d[0]) < 1e-14 and abs(d[2]) < 1e-14 and abs(d[1]) < 1e-11 and abs(d[3]) < 1e-11:
                break
        else:
            return None
        f1x = v0 + z1v
        f1v = rhs(t0 + c1 * h, x0 + z1x, f1x, sg, vmax)[0]
        f2x = v0 + z2v
        f2v = rhs(t0 + c2 * h, x0 + z2x, f2x, sg, vmax)[0]
        return x0 + 0.5 * h * (f1x + f2x), v0 + 0.5 * h * (f1v + f2v)

    def gl_step(t0, x0, v0, h, sg, vmax, depth=0):
        r_ = gl_core(t0, x0, v0, h, sg, vmax)
        if r_ is not None or depth > 8:
            return r_ if r_ is not None else (x0, v0)
        xm, vm = gl_step(t0, x0, v0, 0.5 * h, sg, vmax, depth + 1)
        return gl_step(t0 + 0.5 * h, xm, vm, 0.5 * h, sg, max(vmax, sg * vm), depth + 1)

    X = np.zeros(n)
    V = np.zeros(n)
    FR = np.zeros(n)      # friction force on the block (truth)
    NN = np.zeros(n)      # contact normal load (truth)
    MODE = np.zeros(n, dtype=np.int8)
    slips = []            # (t_start, t_end, F_start, F_end, stick_age_at_start)
    x = 0.0
    i = 0
    t_stop = -age0
    chunk = 4000
    X[0] = 0.0
    while i < n - 1:
        # ---- stick from grid index i with x frozen ----
        found = None
        while i < n - 1:
            j1 = min(i + chunk, n - 1)
            sl = slice(i, j1 + 1)
            Fs = k * (u[sl] - x)
            N = Nb[sl] + lam * Fs
            mus = law.mu_s + beta * np.log1p(np.maximum(t[sl] - t_stop, 0.0) / tau_a)
            g = np.abs(Fs) - mus * N
            X[sl], V[sl], FR[sl], NN[sl] = x, 0.0, Fs, N
            idx = np.nonzero(g[1:] > 0)[0]
            if idx.size:
                j = i + 1 + idx[0]
                gj0, gj1 = g[j - i - 1], g[j - i]
                th = gj0 / (gj0 - gj1) if gj0 < 0 else 0.0
                tb = t[j - 1] + th * dt
                found = (j, tb, np.sign(Fs[j - i]), float(k * (u_at(tb) - x)), tb - t_stop)
                break
            i = j1
        if found is None:
            break
        j, tb, sg, Fb, age = found
        # ---- slip from tb ----
        tc, v, vmax = tb, 0.0, 0.0
        i = j - 1
        stuck = False
        while i < n - 1 and not stuck:
            h = t[i + 1] - tc
            if h <= 1e-12:
                i += 1
                continue
            xn, vn = gl_step(tc, x, v, h, sg, vmax)
            if sg * vn <= 0.0 and sg * v > 0.0:
                # secant search on the step length for v = 0
                hl, hh, vl, vh = 0.0, h, sg * v, sg * vn
                xe, ve, he = x, v, 0.0
                for _ in range(30):
                    ht = hl + (hh - hl) * vl / (vl - vh) if vl != vh else 0.5 * (hl + hh)
                    ht = min(max(ht, hl + 1e-3 * (hh - hl)), hh - 1e-3 * (hh - hl))
                    xe, ve = gl_step(tc, x, v, ht, sg, vmax)
                    he = ht
                    if abs(ve) < 1e-10:
                        break
                    if sg * ve > 0:
                        hl, vl = ht, sg * ve
                    else:
                        hh, vh = ht, sg * ve
                te = tc + he
                Fe = k * (u_at(te) - xe)
                Ne = nb_at(te) + lam * Fe
                x = xe
                if abs(Fe) <= law.mu_s * Ne:
                    slips.append((tb, te, Fb, Fe, age, vmax * sg))
                    t_stop = te
                    stuck = True
                    X[i + 1], V[i + 1] = x, 0.0
                    Fs1 = k * (u[i + 1] - x)
                    FR[i + 1], NN[i + 1] = Fs1, Nb[i + 1] + lam * Fs1
                    i += 1
                else:   # slips on backwards
                    sg = -sg
                    tc, v, vmax = te, 0.0, 0.0
                continue
            x, v, tc = xn, vn, t[i + 1]
            vmax = max(vmax, sg * v)
            a, mu, N = rhs(tc, x, v, sg, vmax)
            X[i + 1], V[i + 1], FR[i + 1], NN[i + 1], MODE[i + 1] = x, v, sg * mu * N, N, 1
            i += 1
        if not stuck:
            break
    return dict(t=t, u=u, va=va, x=X, v=V, fr=FR, N=NN, mode=MODE, slips=slips, F=k * (u - X))


def _draw(case, seed):
    r = _rng(case, seed, "", "params")
    fn = r.uniform(16.0, 32.0)
    m = r.uniform(1.2, 3.0)
    k = m * (2 * np.pi * fn) ** 2
    zeta = r.uniform(0.01, 0.04)
    p = dict(fn=fn, m=m, k=k, zeta=zeta, c=2 * zeta * np.sqrt(k * m), N0=r.uniform(250.0, 700.0),
             tau_servo=r.uniform(0.004, 0.012))
    lawp = dict(mu_s=r.uniform(0.42, 0.60), D=r.uniform(0.11, 0.20), v1=r.uniform(0.0008, 0.004),
                kappa=r.uniform(0.6, 1.5), eta=r.uniform(0.03, 0.15))
    p["law"] = lawp
    p["t_stick_target"] = r.uniform(1.2, 2.6)
    p["v0"] = 0.2 * p["N0"] / (k * p["t_stick_target"])
    p["n_cycles"] = int(r.integers(24, 40))
    p["r"] = r
    return p


def _const(v):
    return lambda t: np.full_like(t, v)


def _steps(levels, durs):
    edges = np.cumsum(durs)

    def f(t):
        idx = np.searchsorted(edges, t, side="right")
        idx = np.minimum(idx, len(levels) - 1)
        return np.asarray(levels)[idx]
    return f


def _period(sim, skip=1):
    s = sim["slips"]
    if len(s) < skip + 2:
        return None
    ts = np.array([q[0] for q in s[skip:]])
    return float(np.mean(np.diff(ts)))


def _twin_gap(sim, k):
    """Mean friction gap (decel - accel) at equal speed 0.2-0.8 vmax over slips / slip force drop."""
    t, v, fr, mode = sim["t"], sim["v"], sim["fr"], sim["mode"]
    out = []
    for (tb, te, Fb, Fe, age, vm) in sim["slips"][1:]:
        sel = (t > tb) & (t < te) & (mode == 1)
        if sel.sum() < 12:
            continue
        vv, ff = np.abs(v[sel]), np.abs(fr[sel])
        ip = int(np.argmax(vv))
        va, fa = vv[:ip + 1], ff[:ip + 1]
        vd, fd = vv[ip:][::-1], ff[ip:][::-1]
        if len(va) < 4 or len(vd) < 4:
            continue
        vm_ = vv[ip]
        q = np.linspace(0.2, 0.8, 13) * vm_
        ga = np.interp(q, va, fa)
        gd = np.interp(q, vd, fd)
        out.append(np.mean(gd - ga) / abs(Fb - Fe))
    return float(np.mean(out)) if out else float("nan")


def _build(case, seed):
    p = _draw(case, seed)
    r = p.pop("r")
    law = _Law(**p["law"])
    fn = p["fn"]
    dt = 1e-4
    v0 = p["v0"]
    ext = {}
    meas = {}
    pos_col = True
    # pilot at constant v0, no effect: period and drop
    pilot = _simulate(p, law, 7.0 * 0.3 * p["N0"] / (p["k"] * v0) + 0.5, dt, _const(v0), {})
    T = _period(pilot) or 1.0
    drops = [abs(s[2] - s[3]) for s in pilot["slips"][1:]]
    drop = float(np.mean(drops)) if drops else 0.3 * p["N0"]
    # set the drive so that the stick-slip period is the drawn one (stick time scales as 1/v0)
    v0 = v0 * T / p["t_stick_target"]
    p["v0"] = v0
    T = p["t_stick_target"]
    f_ss = 1.0 / T
    p["pilot"] = dict(period=T, drop=drop)
    nc = p["n_cycles"]
    vfun = _const(v0)
    t_end = (nc + 0.6) * T
    if case == "none":
        if r.uniform() < 0.4:
            fac = r.uniform(1.5, 2.5)
            levels = [v0, v0 / fac, v0]
            n_b = [nc // 3, max(nc // 4, 4), nc // 3]
            durs = [n_b[0] * T, n_b[1] * T * fac, n_b[2] * T]
            vfun = _steps(levels, durs)
            t_end = sum(durs) + 0.5 * T
            p["drive_levels_mm_s"] = [l * 1e3 for l in levels]
            p["drive_durations_s"] = durs
        else:
            pos_col = r.uniform() < 0.6
    elif case == "load_variation":
        target = r.uniform(0.14, 0.32)
        lam_ = target * p["N0"] / drop
        for _ in range(4):   # the coupling feeds back on the drop: rescale on short pilots
            tp = 5.0 * T
            for _ in range(3):
                pil = _simulate(p, law, tp, dt, _const(v0), {"lam": lam_})
                if len(pil["slips"]) >= 4:
                    break
                tp *= 2.0
            s2 = pil["slips"]
            if len(s2) < 4:
                lam_ *= 0.6
                continue
            ppm = np.median([np.ptp(pil["N"][(pil["t"] >= a_[0]) & (pil["t"] < b_[0])])
                             for a_, b_ in zip(s2[1:-1], s2[2:])]) / p["N0"]
            T = _period(pil) or T
            if abs(ppm / target - 1.0) < 0.08:
                break
            lam_ *= (target / ppm) ** 0.8
        ext["lam"] = lam_
        t_end = (nc + 0.6) * T
        p["lam"] = ext["lam"]
        p["target_N_pp"] = target
        pos_col = r.uniform() < 0.6
    elif case == "twin_branch":
        target = r.uniform(0.12, 0.22)
        ext["dmu"] = target * drop / p["N0"]
        p["dmu_twin"] = ext["dmu"]
        p["target_gap"] = target
        pos_col = r.uniform() < 0.6
    elif case == "static_ageing":
        fac = r.uniform(4.0, 8.0)
        tau_a = r.uniform(0.05, 0.3)
        t_short, t_long = 0.6 * T, 0.6 * T * fac
        target = r.uniform(0.08, 0.16)
        beta = target * law.mu_s / (np.log1p(t_long / tau_a) - np.log1p(t_short / tau_a))
        ext.update(beta=beta, tau_a=tau_a, age0=r.uniform(10.0, 40.0))
        for _ in range(2):   # ageing lengthens the sticks: re-aim the hi-level period on a pilot with ageing
            pil = _simulate(p, law, 14.0 * T, dt, _const(v0), dict(ext, age0=0.0))
            Tp = _period(pil)
            if Tp is None:
                break
            v0 = v0 * Tp / p["t_stick_target"]
        p["v0"] = v0
        nhi, nlo = max(nc // 4, 5), max(nc // 7, 3)
        levels = [v0, v0 / fac, v0, v0 / fac, v0]
        durs = [nhi * T, nlo * T * fac, nhi * T, nlo * T * fac, nhi * T]
        vfun = _steps(levels, durs)
        t_end = sum(durs)
        p.update(beta=beta, tau_a=tau_a, age0=ext["age0"], drive_factor=fac,
                 drive_levels_mm_s=[l * 1e3 for l in levels], drive_durations_s=durs, target_growth=target)
    elif case == "triggering":
        a = r.uniform(0.03, 0.08)
        ratio = r.uniform(2.5, 5.0)
        ft = ratio * fn
        for _ in range(200):
            fr_ = (ft / f_ss) % 1.0
            if 0.3 <= fr_ <= 0.7 and min(abs(ft - 50.0 * j) for j in range(1, 12)) > 3.0 and \
                    2.5 * fn <= ft <= 5.0 * fn:
                break
            ft += 0.13 * f_ss
            if ft > 5.0 * fn:
                ft = 2.5 * fn + r.uniform(0, 0.5) * fn
        ext["trig"] = (a, ft, r.uniform(0, 2 * np.pi))
        p.update(trig_amp=a, trig_freq=ft, trig_phase=ext["trig"][2], trig_over_fss0_frac=(ft / f_ss) % 1.0)
        pil = _simulate(p, law, 10.0 * T, dt, _const(v0), ext)
        s0 = pil["slips"]
        dm = max([abs(q[2] - q[3]) for q in s0] or [0.0])
        ts = [q[0] for q in s0[1:] if abs(q[2] - q[3]) > 0.25 * dm]
        if len(ts) >= 3:
            t_end = (nc + 0.6) * float(np.mean(np.diff(ts)))
        pos_col = r.uniform() < 0.6
    elif case == "drive_modulation":
        a = r.uniform(0.2, 0.45)
        fm = r.uniform(0.15, 0.4) * f_ss
        phi = r.uniform(0, 2 * np.pi)
        vfun = lambda t: v0 * (1.0 + a * np.sin(2 * np.pi * fm * t + phi))
        p.update(mod_amp=a, mod_freq=fm, mod_phase=phi)
        # a few modulation periods at least
        t_end = max(t_end, 2.2 / fm)
        pos_col = False
    sim = _simulate(p, law, t_end, dt, vfun, ext)
    # ---- measurements on truth ----
    sl0 = sim["slips"]
    dmax = max([abs(q[2] - q[3]) for q in sl0] or [0.0])
    sl = [q for q in sl0 if abs(q[2] - q[3]) > 0.25 * dmax]   # major slips (micro-slips left out)
    sim["slips"] = sl
    meas["n_microslips"] = len(sl0) - len(sl)
    ns = len(sl)
    meas["n_slips"] = ns
    per = _period(sim)
    meas["f_ss"] = 1.0 / per if per else None
    drops = np.array([abs(s[2] - s[3]) for s in sl[1:]]) if ns > 1 else np.array([drop])
    meas["drop_mean_N"] = float(np.mean(drops))
    pk = np.array([s[2] for s in sl[1:]])
    meas["peak_spread_over_drop"] = float(np.std(pk) / np.mean(drops)) if len(pk) > 1 else None
    meas["twin_gap_over_drop"] = _twin_gap(sim, p["k"])
    if case == "load_variation":
        i0 = int(0.1 * len(sim["t"]))
        meas["N_pp_over_N0"] = float(np.ptp(sim["N"][i0:]) / p["N0"])
        cyc = []
        for a_, b_ in zip(sl[1:-1], sl[2:]):
            s_ = (sim["t"] >= a_[0]) & (sim["t"] < b_[0])
            cyc.append(np.ptp(sim["N"][s_]) / p["N0"])
        meas["N_pp_cycle_median"] = float(np.median(cyc)) if cyc else None
    if case == "static_ageing":
        ages = np.array([s[4] for s in sl[1:]])
        pkf = np.array([s[2] for s in sl[1:]])
        lo = pkf[ages < np.median(ages)]
        hi = pkf[ages >= np.median(ages)]
        # growth over the range of stick times: fit F = A + B ln(age), evaluated at min/max age
        B, A = np.polyfit(np.log(ages), pkf, 1)
        meas["peak_growth"] = float(B * (np.log(ages.max()) - np.log(ages.min())) /
                                    (A + B * np.log(ages.min())))
        meas["stick_time_range_s"] = [float(ages.min()), float(ages.max())]
        meas["peak_growth_means"] = float(hi.mean() / lo.mean() - 1.0)
    if case == "triggering":
        meas["trig_amp"] = p["trig_amp"]
        meas["trig_over_fn"] = p["trig_freq"] / fn
        meas["trig_over_fss0_frac"] = p["trig_over_fss0_frac"]
        meas["trig_over_fss_frac"] = float((p["trig_freq"] / meas["f_ss"]) % 1.0)
    if case == "drive_modulation":
        meas["mod_amp"] = p["mod_amp"]
        meas["fm_over_fss"] = p["mod_freq"] / meas["f_ss"]
    p["measured"] = meas
    p["pos_col"] = pos_col
    return p, sim


def _fmt(a, nd):
    s = np.char.mod(f"%.{nd}f", a)
    return np.char.replace(s, ".", ",")


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    p, sim = _build(case, seed)
    rn = _rng(case, seed, nuisance, "chain")
    fn = p["fn"]
    if nuisance == "coarse":
        fs = fn * rn.uniform(10.0, 15.0)
    else:
        fs = 1000.0
    dt = 1e-4
    M = int(np.ceil((1.0 / dt) / fs))
    # resample the fine truth onto a grid of fs*M by linear interpolation, then anti-alias and decimate
    t_f = np.arange(0.0, sim["t"][-1], 1.0 / (fs * M))
    F_f = np.interp(t_f, sim["t"], sim["F"])
    N_f = np.interp(t_f, sim["t"], sim["N"])
    u_f = np.interp(t_f, sim["t"], sim["u"])
    b, a = signal.bessel(4, 0.35 * fs, btype="low", fs=fs * M)
    zi = signal.lfilter_zi(b, a)
    chans = []
    for y in (F_f, N_f, u_f):
        chans.append(signal.lfilter(b, a, y, zi=zi * y[0])[0][::M])
    t = t_f[::M]
    F, N, u = chans
    drop = p["measured"]["drop_mean_N"]
    F = F + rn.normal(0, 0.003 * drop, t.size)
    N = N + rn.normal(0, 0.0015 * p["N0"], t.size)
    u = u + rn.normal(0, 0.3e-6, t.size)
    nz = {}
    if nuisance == "hum":
        amp = rn.uniform(0.01, 0.05) * drop
        ph = rn.uniform(0, 2 * np.pi, 3)
        h = amp * (np.sin(2 * np.pi * 50 * t + ph[0]) + 0.3 * np.sin(2 * np.pi * 150 * t + ph[1]) +
                   0.12 * np.sin(2 * np.pi * 250 * t + ph[2]))
        F = F + h
        N = N + h / 3.0
        nz["hum_amp_N"] = amp
    elif nuisance == "drift":
        tot = rn.uniform(0.02, 0.06) * drop * rn.choice([-1, 1])
        T = t[-1]
        d = tot * (0.6 * (1 - np.exp(-t / (0.3 * T))) / (1 - np.exp(-1 / 0.3)) + 0.4 * t / T)
        F = F + d
        nz["drift_total_N"] = tot
    elif nuisance == "spikes":
        frac = rn.uniform(0.0005, 0.005)
        nsp = max(3, int(frac * t.size))
        idx = rn.choice(t.size, nsp, replace=False)
        F[idx] += rn.choice([-1, 1], nsp) * rn.uniform(0.3, 1.5, nsp) * drop
        nz["spike_fraction"] = nsp / t.size
    elif nuisance == "quantisation":
        q = rn.uniform(0.002, 0.01) * drop
        F = np.round(F / q) * q
        N = np.round(N / q) * q
        nz["adc_step_N"] = q
    elif nuisance == "coarse":
        nz["samples_per_period"] = fs / fn
    fn_given = fn
    if nuisance == "fn_off":
        sgn = rn.choice([-1.0, 1.0])
        fn_given = fn * (1 + 0.05 * sgn)
        nz["fn_factor"] = 1 + 0.05 * sgn
    # ---- write the logger's file ----
    os.makedirs(outdir, exist_ok=True)
    code = hashlib.sha1(f"{case}|{seed}|{nuisance}".encode()).hexdigest()[:8]
    fname = os.path.abspath(os.path.join(outdir, f"RP2_Versuch_{code}.csv"))
    day = 1 + (seed * 7 + CASES.index(case) * 3) % 27
    hdr = [
        "# Reibpruefstand RP-2 (servohydraulisch) - Messprogramm ReibLog 3.2",
        f"# Datum: {day:02d}.03.2021",
        "# Probe oben: Buche, Querholz, gehobelt; Probe unten: Fichte, Laengsholz; Holzfeuchte ca. 11 %",
        f"# Abtastrate: {fs:.1f} Hz; Tiefpass: Bessel 4. Ordnung, {0.35 * fs:.1f} Hz",
        "# Kanaele: Reibkraft = Kraftaufnehmer Zugstange (DMS), Normalkraft = Kraftaufnehmer unter Probentisch",
    ]
    if p["pos_col"]:
        hdr.append("Zeit [s];Reibkraft [N];Normalkraft [N];Kolbenweg [mm]")
        cols = [_fmt(t, 4), _fmt(F, 3), _fmt(N, 2), _fmt(u * 1e3, 4)]
    else:
        hdr.insert(-1, "# Wegaufnehmer Kolben nicht angeschlossen")
        hdr.append("Zeit [s];Reibkraft [N];Normalkraft [N]")
        cols = [_fmt(t, 4), _fmt(F, 3), _fmt(N, 2)]
    body = cols[0]
    for cc in cols[1:]:
        body = np.char.add(np.char.add(body, ";"), cc)
    with open(fname, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("\n".join(hdr) + "\n")
        fh.write("\n".join(body.tolist()) + "\n")
    args = ["--stiffness", f"{p['k']:.1f}", "--fn", f"{fn_given:.3f}"]
    if not p["pos_col"]:
        args += ["--v0", f"{p['v0'] * 1e3:.4f}"]
    params = {kk: vv for kk, vv in p.items()}
    params["nuisance_params"] = nz
    params["fs"] = fs
    params = json.loads(json.dumps(params, default=float))
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance, "file": fname, "args": args,
            "fn_true": float(fn), "fn_given": float(fn_given), "params": params}


if __name__ == "__main__":
    import sys
    import time
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    for cs in CASES:
        for sd in range(8):
            t0 = time.time()
            tr = write_record(cs, sd, out, NUISANCES[sd % 7])
            print(cs, sd, tr["nuisance"], f"{time.time() - t0:.1f}s", json.dumps(tr["params"]["measured"]))
