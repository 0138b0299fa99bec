"""Froude pendulum: an independent generator of measured stick-slip records for `lieng diagnose`.

The rig
-------
A pendulum (mass m, centre of mass at l from the axis, moment of inertia I = m (l^2 + rho^2)) hangs in a
bearing on a shaft of radius R that a motor turns at Omega(t). The bearing's friction drags the pendulum
round; gravity pulls it back with the torque m g l sin(theta), a nonlinear "gravity spring". Sliding speed at
the bearing v = R (Omega - theta'); the 1-DoF reading of the rig is k = m g l / R^2 (N/m at the shaft
surface), M = I / R^2, v0 = R Omega, x = R theta (arc at the shaft), F = m g l sin(theta) / R. Static
deflections 7-16 degrees by design, peaks 6-19 measured (a linear-spring reading is right to ~1 %). fn_true = sqrt(m g l / I) / (2 pi), the
small-angle frequency with the bearing stuck.

Friction law: a random smooth single-valued mu(v): a monotone cubic (PCHIP) interpolant through 5-8 random
knots in ln(v/v_ref): flat at the static level mu_s below 0.003-0.03 v_ref, weakening through 2-3 random
knots to a minimum at 0.3-3 v_ref, then strengthening through 0-2 knots up to 100 v_ref; plus a small viscous
term (mu_visc = kappa v / v_ref). The bearing's normal load is the pendulum's bearing reaction
N = m |a_cm - g| (weight plus the centripetal and tangential inertia of the swinging mass; friction-circle
correction neglected), evaluated from the previous step's state; a spring-loaded cap may add a preload.

Stick handling: Moreau-Jean time stepping. Each fixed step (Tn/400-Tn/800) the impulse that would keep the
bearing stuck over the step is computed; if it is within h R N mu_static the step is a stick step, else the
step slides and the end-of-step sliding speed solves the one-dimensional implicit equation
u = A - B mu(u) (safeguarded Newton in the bracket (0, A), continued from the previous step's speed). No
events, no regularisation, no zero-velocity band.

Integrator: a theta-method (theta 0.5-0.6) on the pendulum, with gravity linearised about the step's start
(the linearised Moreau-Jean scheme); own code, a plain Python loop.

Departures
----------
- load_variation: a spring-loaded bearing cap whose preload follows the pendulum angle through a cam,
  N = Nw + P0 + P1 f(theta), f a cam lift (linear + a small quadratic) across the stick-slip's range of
  angles, rising or falling; P1 calibrated on a pilot run; the load cell channel is recorded.
- twin_branch: lubricant starvation. A film state phi (1 = full film) is depleted by the sliding distance
  (dphi/dt = -u phi / L_d) and recovers with a time constant tau_r (0.1-0.3 of the stick); the friction is
  mu(u) + D (1 - phi): the decelerating half of each slip sees the thinner film. D calibrated on a pilot.
- static_ageing: the static level grows with the contact's age (time since the last arrest) as a Langmuir /
  Michaelis-Menten saturation, mu_s0 + Da t/(t + tau_a), tau_a at the geometric mean of the record's stick
  times; drive steps 4-8x between levels (even seeds) or holds (Omega = 0) on odd seeds; drive recorded.
- triggering: a vibrator on the bearing housing modulates the whole load by 3.2-5.5 % (amplitude) at
  2.6-7.9 fn; sticks are shorter in this case (slip speed ~3 v0) so a cycle spans few vibrator periods. The
  slips lock to the vibrator; 1:n locks (f_t / f_ss an integer) are rejected: short pilots bisect over f_t
  between two neighbouring 1:n tongues for a finer lock, and the full record is re-checked (>= 0.15).
- drive_modulation: Omega(t) = Omega0 (1 + a sin(2 pi fm t + phi)), a 0.22-0.43, fm 0.13-0.42 of the
  unmodulated f_ss (from a pilot); only --v0 (nominal) is given.

Record
------
Either an optical encoder on the pendulum (x = R theta in mm or um, quantised to the encoder's counts,
interpolation noise, a slow thermal drift of the read head) with the normal load as a cap-spring deflection
y (mm, affine in N), or a MEMS inclinometer on the pendulum's hub (on the axis, so it reads gravity only: the
restoring torque m g l sin(theta) as a force at the shaft surface, N or mN, `--stiffness`; a torque cell on
the shaft would read the bearing's friction torque, which is not the 1-DoF model's spring force in a slip)
behind a one-pole low-pass at 15-40 fn and a fine ADC, with the bearing's load cell (N or mN). White noise
0.1-0.5 % of the drop and a thermal drift of 0.05-0.3 % (2-5 % with `drift`) on every record; encoder or
ADC steps 0.01-0.05 % of the drop (0.2-1 % with `quantisation`). The drive is the shaft's speed
(v0 = R Omega, mm/s) or the shaft encoder's arc R phi (mm or um). Comma with `name [unit]`, TAB with `name/unit`,
semicolon with a decimal comma and `Name (unit)`, or whitespace with a row of units, `#` comment lines on
some. --fn on 7 of 8 seeds (always with fn_off).

Measured (ground truth, seeds 0-23 of every case, each with the bench's nuisance seed mod 7; every size is
in `params["measured"]`; "drop" is the slip's drop of the restoring force, median over the record)
--------------------------------------------------------------------------------------------------------
- every record: 16-39 stick-slip cycles (18-38 on seeds 0-7), 20-95 samples per (shorter) stick-slip period,
  coarse records 10.6-14.4 samples per Tn; peak deflection 6-19 deg; the drop 35-109 % of the peak (over
  100 %: the pendulum swings past the vertical, some load_variation records); slip speed 4-16 v0;
  0.1-1.2 s a record (one process); no NaN. The Moreau-Jean scheme converges to first order:
  Tn/400 against Tn/3200 changes the drop by 0.3 %, the period by 0.5 %, the peak by < 0.01 %.
- none: the friction coefficient is exactly single-valued (decelerating minus accelerating at equal speed,
  F/N: -0.02..0.00 % of the drop). The bearing load is not constant: the swinging pendulum's inertia moves
  N by 0.5-4.3 % of N0 p-p (0.4-5.2 % of the drop in the friction force), so the friction force F = mu N is
  double-valued by +0.3..+2.8 % of the drop. A linear 1-DoF reading (x = F/k, friction = M x'' + k x, the
  pendulum's sin taken as linear) of the exact restoring force sees a twin of -0.8..+0.7 % of the drop,
  of the encoder's arc x = R theta -0.3..+0.9 %, behind a 15 fn one-pole low-pass -2.6..+0.6 %. Peak
  scatter 0-1.5 % of the drop (sd). Stepped drives / holds (seeds 2, 5 mod 8; sticks 4.0-8.8x apart): peak
  growth -0.9..+0.02 % of the drop (the shaft's restart ramp breaks a held contact slightly early); no
  ageing in the law.
- load_variation: N p-p 13.6-27.4 % of N0 (rising cams 13.4-23.4 %, falling 14.2-27.3 %, 0.5-99.5 pct).
- twin_branch: +13.6..+21.0 % of the drop in F (+11.7..+19.6 % in F/N x N0; +11.8..+19.4 % in a 1-DoF
  reading of the restoring force); the film falls to 0.22-0.64 in a slip and recovers in stick.
- static_ageing: peak growth +7.3..+15.5 % of the drop between the record's long and short sticks
  (stick times 4.2-8.2x apart; steps 4-8x in v0 on even seeds, holds on odd seeds).
- triggering: vibrator 3.3-5.4 % of N0 (amplitude; 6.7-10.8 % p-p), f_t 3.5-7.0 fn, the record's
  f_t / f_ss 6.19-14.74, 0.175-0.50 from an integer (the slips lock to the vibrator 2:(2n+1) or finer:
  1:n locks are rejected by a bisection over f_t on short pilots).
- drive_modulation: a 0.23-0.43, fm / f_ss 0.17-0.41.
"""
import bisect
import json
import math
import os
import sys
import time

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.signal import lfilter

NAME = "froude_pendulum"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
G = 9.81


# ----------------------------------------------------------------------------------------------------------
# friction law
# ----------------------------------------------------------------------------------------------------------
class _Law:
    """Random smooth single-valued mu(v): PCHIP in s = ln(v / v_ref) plus a viscous term."""

    def __init__(self, rng, mu_s, weak_frac):
        dmu = mu_s * weak_frac
        s0 = math.log(10 ** rng.uniform(-2.5, -1.5))
        sm = rng.uniform(math.log(0.3), math.log(3.0))
        stop = math.log(100.0)
        nw = int(rng.integers(2, 4))
        ns = int(rng.integers(0, 3))
        sw = np.sort(rng.uniform(s0 + 0.3, sm - 0.3, nw))
        rng.dirichlet(np.full(nw + 1, 1.5))          # a spare draw (kept: the seeds' laws depend on it)
        # weakening values: monotone from mu_s down to mu_min, random partition
        mw = mu_s - dmu * np.sort(rng.dirichlet(np.full(nw + 1, 1.5)).cumsum()[:-1])
        rise = dmu * rng.uniform(0.2, 0.6)
        ss = np.sort(rng.uniform(sm + 0.4, stop - 0.4, ns))
        ms = (mu_s - dmu) + rise * np.sort(rng.uniform(0.1, 0.8, ns))
        s = np.concatenate([[s0 - 1.5, s0], sw, [sm], ss, [stop]])
        m = np.concatenate([[mu_s, mu_s], mw, [mu_s - dmu], ms, [mu_s - dmu + rise]])
        self.p = PchipInterpolator(s, m)
        self.x = [float(v) for v in s]
        c = self.p.c
        self.c = [[float(c[j, i]) for j in range(4)] for i in range(c.shape[1])]
        self.s_lo, self.s_hi = self.x[0], self.x[-1]
        self.m_top = float(m[-1])
        self.sl_top = float(self.p(stop, 1))
        self.mu_s = float(mu_s)
        self.kappa = dmu * rng.uniform(0.001, 0.004)
        self.knots = {"ln_v_over_vref": [float(v) for v in s[1:]], "mu": [float(v) for v in m[1:]]}
        self.v_min = math.exp(sm)
        self.dmu = dmu

    def mu(self, u):
        """(mu, dmu/du) at sliding speed u (in units of v_ref), u > 0."""
        s = math.log(u)
        if s <= self.s_lo:
            val, ds = self.mu_s, 0.0
        elif s >= self.s_hi:
            val = self.m_top + self.sl_top * (s - self.s_hi)
            ds = self.sl_top
        else:
            i = bisect.bisect_right(self.x, s) - 1
            c0, c1, c2, c3 = self.c[i]
            d = s - self.x[i]
            val = ((c0 * d + c1) * d + c2) * d + c3
            ds = (3.0 * c0 * d + 2.0 * c1) * d + c2
        return val + self.kappa * u, ds / u + self.kappa

    def vec(self, u):
        u = np.asarray(u, float)
        s = np.log(np.maximum(u, 1e-300))
        out = np.where(s <= self.s_lo, self.mu_s,
                       np.where(s >= self.s_hi, self.m_top + self.sl_top * (s - self.s_hi),
                                self.p(np.clip(s, self.s_lo, self.s_hi))))
        return out + self.kappa * u


# ----------------------------------------------------------------------------------------------------------
# the Moreau-Jean / theta-method simulation
# ----------------------------------------------------------------------------------------------------------
def _simulate(P, law, omega, nmult=None, cam=None, film=None, age=None, q0=0.0):
    """Run the pendulum over len(omega) - 1 steps of P['h'].

    omega: shaft speed (rad/s) at every step boundary. nmult: multiplicative load factor per step boundary
    (the vibrator). cam: (P0, P1, qc, qw, beta): cap preload P0 + P1 f((q - qc)/qw). film: (D, L_d, tau_r)
    in SI (L_d in m). age: (Da, tau_a).
    Returns a dict of arrays on the step grid.
    """
    h, th = P["h"], P["theta"]
    m, l, I, R, c = P["m"], P["l"], P["I"], P["R"], P["c_air"]
    vref = P["vref"]
    mgl = m * G * l
    nst = len(omega) - 1
    q, w, acc = q0, float(omega[0]), 0.0
    phi, tage = 1.0, 0.0
    u_prev = 0.0
    Q = np.empty(nst + 1)
    W = np.empty(nst + 1)
    NN = np.empty(nst + 1)
    TT = np.empty(nst + 1)
    UU = np.empty(nst + 1)
    ST = np.zeros(nst + 1, dtype=bool)
    PH = np.empty(nst + 1)
    AG = np.empty(nst + 1)
    om = omega.tolist()
    nm = nmult.tolist() if nmult is not None else None
    muf = law.mu
    mu_s0 = law.mu_s
    if cam is not None:
        P0, P1, qc, qw, beta = cam
    else:
        P0 = P1 = qc = beta = 0.0
        qw = 1.0
    if film is not None:
        D, Ld, taur = film
    else:
        D, Ld, taur = 0.0, 1.0, 1.0
    if age is not None:
        Da, taua = age
    else:
        Da, taua = 0.0, 1.0
    Q[0], W[0], ST[0], UU[0], PH[0], AG[0] = q, w, True, 0.0, 1.0, 0.0
    sq, cq = math.sin(q), math.cos(q)
    NN[0] = m * G + P0
    TT[0] = mgl * sq
    a1 = (1.0 - th) * h * c
    for n in range(nst):
        Om1 = om[n + 1]
        sq = math.sin(q)
        cq = math.cos(q)
        Gq = mgl * sq
        dG = mgl * cq
        Nw = m * math.sqrt((G * cq + l * w * w) ** 2 + (G * sq + l * acc) ** 2)
        N = Nw
        if cam is not None:
            z = (q - qc) / qw
            N = Nw + P0 + P1 * (z + beta * z * z)
        if nm is not None:
            N = N * nm[n + 1]
        extra = D * (1.0 - phi)
        mus = mu_s0 + extra + (Da * tage / (tage + taua) if Da else 0.0)
        Ihat = I + th * th * h * h * dG + th * h * c
        wfree = (I * w - h * Gq - th * (1.0 - th) * h * h * dG * w - a1 * w) / Ihat
        Pneed = Ihat * (Om1 - wfree)
        lim = h * R * N * mus
        if abs(Pneed) <= lim:
            w1 = Om1
            Pimp = Pneed
            u = 0.0
            stick = True
        else:
            stick = False
            sgn = 1.0 if Pneed > 0 else -1.0
            A = R * abs(Pneed) / Ihat / vref          # speeds in units of vref
            B = h * R * R * N / Ihat / vref
            lo, hi = 0.0, A
            mu_g, _ = muf(u_prev) if u_prev > 0 else (mus, 0.0)
            u = A - B * (mu_g + extra)
            if not (lo < u < hi):
                u = 0.5 * A
            for _it in range(60):
                mv, dm = muf(u)
                g = u - A + B * (mv + extra)
                if g > 0:
                    hi = u
                else:
                    lo = u
                dg = 1.0 + B * dm
                un = u - g / dg if dg > 0 else -1.0
                if not (lo < un < hi):
                    un = 0.5 * (lo + hi)
                if abs(un - u) <= 1e-13 * A + 1e-300:
                    u = un
                    break
                u = un
            mv, _ = muf(u)
            Pimp = sgn * h * R * N * (mv + extra)
            w1 = wfree + Pimp / Ihat
        q1 = q + h * ((1.0 - th) * w + th * w1)
        acc = (w1 - w) / h
        # film and contact age after the step
        if film is not None:
            phi = (phi + h / taur) / (1.0 + h * u * vref / Ld + h / taur)
        tage = tage + h if stick else 0.0
        q, w = q1, w1
        u_prev = u
        Q[n + 1] = q
        W[n + 1] = w
        NN[n + 1] = N
        TT[n + 1] = Pimp / h
        UU[n + 1] = (R * (Om1 - w1)) if not stick else 0.0
        ST[n + 1] = stick
        PH[n + 1] = phi
        AG[n + 1] = tage
    t = np.arange(nst + 1) * h
    return {"t": t, "q": Q, "w": W, "N": NN, "T": TT, "v": UU, "stick": ST, "phi": PH, "age": AG,
            "omega": np.asarray(omega, float)}


# ----------------------------------------------------------------------------------------------------------
# ground-truth measurements
# ----------------------------------------------------------------------------------------------------------
def _cycles(sim, P, skip=1):
    """Breakaway/arrest index pairs of the real slips (drop above 20 % of the median)."""
    st = sim["stick"]
    Fs = P["k"] * P["R"] * np.sin(sim["q"])
    d = np.diff(st.astype(np.int8))
    brk = np.nonzero(d == -1)[0]          # last stick sample before slipping
    arr = np.nonzero(d == 1)[0] + 1       # first stick sample after the slip
    out = []
    for b in brk:
        j = np.searchsorted(arr, b)
        if j >= len(arr):
            break
        out.append((int(b), int(arr[j])))
    if not out:
        return [], Fs
    drops = np.array([Fs[b] - Fs[a] for b, a in out])
    md = np.median(drops)
    out = [ba for ba, dr in zip(out, drops) if dr > 0.2 * md]
    return out[skip:], Fs


def _twin(u, f, segs, drops):
    """Median over slips of mean(f_dec - f_acc) at equal u (0.2-0.8 of the slip's peak), / drop."""
    vals = []
    for (b, a), dr in zip(segs, drops):
        uu, ff = u[b:a + 1], f[b:a + 1]
        if len(uu) < 12 or dr <= 0:
            continue
        ip = int(np.argmax(uu))
        if ip < 4 or ip > len(uu) - 5:
            continue
        ua, fa = uu[:ip + 1], ff[:ip + 1]
        ud, fd = uu[ip:][::-1], ff[ip:][::-1]
        ug = np.linspace(0.2, 0.8, 25) * uu[ip]
        oa, od = np.argsort(ua, kind="stable"), np.argsort(ud, kind="stable")
        fa_g = np.interp(ug, ua[oa], fa[oa])
        fd_g = np.interp(ug, ud[od], fd[od])
        vals.append(float(np.mean(fd_g - fa_g)) / dr)
    return float(np.median(vals)) if vals else float("nan")


def _measure(sim, P, skip=1):
    segs, Fs = _cycles(sim, P, skip)
    t = sim["t"]
    res = {"n_cycles": len(segs)}
    if len(segs) < 3:
        res["ok"] = False
        return res, segs, Fs
    res["ok"] = True
    drops = np.array([Fs[b] - Fs[a] for b, a in segs])
    peaks = np.array([Fs[b] for b, a in segs])
    brk_t = np.array([t[b] for b, a in segs])
    res["drop_N"] = float(np.median(drops))
    res["f_ss"] = float((len(segs) - 1) / (brk_t[-1] - brk_t[0])) if len(segs) > 1 else float("nan")
    # stick times: from the previous arrest to each breakaway
    arr_all = [a for b, a in segs]
    st_times, pk = [], []
    for i in range(1, len(segs)):
        st_times.append(t[segs[i][0]] - t[arr_all[i - 1]])
        pk.append(peaks[i])
    res["stick_times"] = np.array(st_times)
    res["peaks"] = np.array(pk)
    res["drops"] = drops
    res["segs"] = segs
    return res, segs, Fs


def _ageing_growth(res):
    ts, pk, dr = res["stick_times"], res["peaks"], res["drops"]
    if len(ts) < 4:
        return float("nan"), float("nan")
    gm = math.exp(np.mean(np.log(ts)))
    hi, lo = ts > gm * 1.3, ts < gm / 1.3
    if hi.sum() < 1 or lo.sum() < 1:
        return 0.0, float(ts.max() / ts.min())
    return float((pk[hi].mean() - pk[lo].mean()) / np.median(dr)), float(np.median(ts[hi]) / np.median(ts[lo]))


# ----------------------------------------------------------------------------------------------------------
# the generator
# ----------------------------------------------------------------------------------------------------------
def _smooth_steps(t, times, levels, ramp):
    """Piecewise-constant levels switching at `times` with smoothstep ramps of length `ramp`."""
    y = np.full_like(t, levels[0], dtype=float)
    for tk, a, b in zip(times, levels[:-1], levels[1:]):
        z = np.clip((t - tk) / ramp, 0.0, 1.0)
        y += (b - a) * z * z * (3.0 - 2.0 * z)
    return y


def _design(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([48017, ci, int(seed)])
    m = rng.uniform(0.4, 2.5)
    l = rng.uniform(0.02, 0.07)
    rho = l * rng.uniform(0.35, 1.0)
    I = m * (l * l + rho * rho)
    mu_s = rng.uniform(0.18, 0.42)
    wf = rng.uniform(0.42, 0.55) if case == "load_variation" else rng.uniform(0.28, 0.45)
    law = _Law(rng, mu_s, wf)
    P0 = m * G * rng.uniform(0.3, 1.0) if case == "load_variation" else 0.0
    N0 = m * G + P0
    th_s = math.radians(rng.uniform(7.0, 16.0))
    R = l * math.sin(th_s) * m * G / (mu_s * N0)
    k = m * G * l / R ** 2
    wn = math.sqrt(m * G * l / I)
    fn = wn / (2 * math.pi)
    Tn = 1.0 / fn
    # drive speed from a target slip-to-drive speed ratio
    # (triggering: shorter sticks, a few shaker periods a cycle, so the slips need not lock 1:n)
    r = rng.uniform(2.2, 3.4) if case == "triggering" else rng.uniform(4.5, 10.0)
    mu_k = float(law.vec([0.5 * r])[0])
    dth = 1.6 * (mu_s - mu_k) * N0 * R / (m * G * l)
    v0 = wn * R * dth / (2 * r)
    P = dict(m=m, l=l, rho=rho, I=I, R=R, k=k, M=I / R ** 2, fn=fn, Tn=Tn, N0=N0, P0=P0, mu_s=mu_s,
             v0=v0, vref=v0, theta=rng.uniform(0.5, 0.6), h=Tn / float(rng.integers(400, 801)),
             c_air=2 * rng.uniform(0.002, 0.006) * math.sqrt(m * G * l * I), th_s=th_s, r=r)
    return rng, P, law


def _pilot(P, law, n_per, **kw):
    Om0 = P["v0"] / P["R"]
    nst = int(n_per * P["Tn"] / P["h"])
    q0 = 0.8 * P["th_s"]
    sim = _simulate(P, law, np.full(nst + 1, Om0), q0=q0, **kw)
    res, segs, Fs = _measure(sim, P, skip=1)
    return sim, res


def _build(case, seed):
    """Simulate the rig for (case, seed): returns (P, law, sim, truth-dict)."""
    rng, P, law = _design(case, seed)
    h, Tn, R = P["h"], P["Tn"], P["R"]
    Om0 = P["v0"] / R
    n_cyc = int(rng.integers(18, 37))
    q0 = 0.8 * P["th_s"]
    kw = {}
    info = {}
    # pilot at the nominal drive: stick-slip period, drop, angle range
    psim, pres = _pilot(P, law, 40)
    if not pres["ok"]:
        raise RuntimeError("no stick-slip in the pilot")
    Tss = 1.0 / pres["f_ss"]
    t_st = float(np.median(pres["stick_times"]))
    drop0 = pres["drop_N"]
    omega_fn = None
    nmult_fn = None
    mode = "constant"
    if case == "load_variation":
        segs = pres["segs"]
        qa = psim["q"][segs[0][0]:]
        qmin, qmax = float(np.percentile(qa, 1)), float(np.percentile(qa, 99))
        qc, qw = 0.5 * (qmin + qmax), 0.5 * (qmax - qmin)
        sign = 1.0 if rng.random() < 0.5 else -1.0
        target = rng.uniform(0.13, 0.22) if sign > 0 else rng.uniform(0.13, 0.30)
        beta = rng.uniform(-0.25, 0.25)
        P1 = sign * 0.5 * target * P["N0"]
        for _ in range(4):
            cam = (P["P0"], P1, qc, qw, beta)
            s2, r2 = _pilot(P, law, 40, cam=cam)
            if not r2["ok"]:
                P1 *= 0.6
                continue
            a0 = r2["segs"][0][0]
            Nv = s2["N"][a0:]
            pp = (np.percentile(Nv, 99.5) - np.percentile(Nv, 0.5)) / P["N0"]
            if abs(pp / target - 1) < 0.12:
                break
            P1 *= (target / pp) ** 0.8
        kw["cam"] = (P["P0"], P1, qc, qw, beta)
        info.update(cam_P1_N=P1, cam_qc=qc, cam_qw=qw, cam_beta=beta, cam_sign=sign, load_target=target)
        s2, r2 = _pilot(P, law, 40, cam=kw["cam"])
        Tss = 1.0 / r2["f_ss"]
    elif case == "twin_branch":
        # slip distance of a typical slip
        segs = pres["segs"]
        sd = [np.sum(np.abs(psim["v"][b:a + 1])) * h for b, a in segs]
        Ld = float(np.median(sd)) * rng.uniform(0.3, 0.8)
        taur = t_st * rng.uniform(0.1, 0.3)
        target = rng.uniform(0.13, 0.21)
        D = target * drop0 / P["N0"] * 2.0
        for _ in range(4):
            s2, r2 = _pilot(P, law, 40, film=(D, Ld, taur))
            tw = _twin(np.abs(s2["v"]), s2["T"] / R, r2["segs"], r2["drops"])
            if abs(tw / target - 1) < 0.1:
                break
            D *= (target / tw) ** 0.9
        kw["film"] = (D, Ld, taur)
        info.update(film_D=D, film_Ld_m=Ld, film_tau_r_s=taur, twin_target=target)
        Tss = 1.0 / r2["f_ss"]
    elif case == "triggering":
        pass
    elif case == "drive_modulation":
        pass
    # drive schedule
    stepped = case == "static_ageing" or (case == "none" and seed % 8 in (2, 5))
    if stepped:
        rho_t = rng.uniform(4.0, 8.0)
        t_slip = Tss - t_st
        if seed % 2 == 0:
            mode = "steps"
            ratio = rho_t
            T_hi, T_lo = Tss, t_st * ratio + t_slip
            times, levels, t = [], [Om0], 0.0
            ncount = 0
            hi = True
            while ncount < n_cyc + 2:
                nb = int(rng.integers(3, 6)) if hi else int(rng.integers(2, 4))
                t += nb * (T_hi if hi else T_lo)
                ncount += nb
                times.append(t)
                hi = not hi
                levels.append(Om0 if hi else Om0 / ratio)
            t_end = t
            times, levels = times[:-1], levels[:-1]
            info.update(drive_ratio=ratio)
        else:
            mode = "holds"
            hold = (rho_t + 0.5) * t_st
            times, levels, t = [], [Om0], 0.0
            ncount = 0
            while ncount < n_cyc + 2:
                nb = int(rng.integers(3, 5))
                t += (nb - 0.5 + rng.uniform(-0.3, 0.3)) * Tss
                times += [t, t + hold]
                levels += [0.0, Om0]
                t += hold + 0.5 * Tss
                ncount += nb
            t_end = t + 1.0 * Tss
            info.update(hold_s=hold, hold_ratio_target=rho_t)
        nst = int(t_end / h) + 1
        tg = np.arange(nst + 1) * h
        omega_fn = _smooth_steps(tg, times, levels, 0.15 * Tn)
        if case == "static_ageing":
            target = rng.uniform(0.08, 0.16)
            # contact age saturation at the geometric mean of the stick times
            ts_lo, ts_hi = t_st, t_st * rho_t
            taua = math.sqrt(ts_lo * ts_hi)
            brk = (math.sqrt(rho_t) - 1) / (math.sqrt(rho_t) + 1)
            Da = target * drop0 / (P["N0"] * brk)
            kw["age"] = (Da, taua)
            info.update(age_Da=Da, age_tau_s=taua, ageing_target=target)
    else:
        t_end = (n_cyc + 1.3) * Tss
        nst = int(t_end / h) + 1
        tg = np.arange(nst + 1) * h
        omega_fn = np.full(nst + 1, Om0)
        if case == "drive_modulation":
            a = rng.uniform(0.22, 0.43)
            fm = rng.uniform(0.13, 0.42) / Tss
            ph = rng.uniform(0, 2 * math.pi)
            omega_fn = Om0 * (1.0 + a * np.sin(2 * math.pi * fm * tg + ph))
            mode = "modulated"
            info.update(mod_a=a, mod_fm_hz=fm, mod_phase=ph)
    if case == "triggering":
        at = rng.uniform(0.032, 0.055)
        ph = rng.uniform(0, 2 * math.pi)
        best = None
        n_pil = min(n_cyc, 16)
        npil = int(n_pil * Tss / h) + 1
        cache = {}

        def pilot_ratio(c_):
            # short pilot: the record's f_t / f_ss at the shaker frequency c_ fn
            if c_ not in cache:
                ft_ = c_ * P["fn"]
                nm = 1.0 + at * np.sin(2 * math.pi * ft_ * tg[:npil + 1] + ph)
                s1 = _simulate(P, law, omega_fn[:npil + 1], nmult=nm, q0=q0, **kw)
                r1, _, _ = _measure(s1, P, skip=2)
                cache[c_] = ft_ / r1["f_ss"] if r1["ok"] else float("nan")
            return cache[c_]

        def dist_int(x):
            return abs(x - round(x)) if x == x else 0.0

        # the slips lock to the shaker 1:n over most frequencies; between two neighbouring 1:n and 1:(n+1)
        # tongues lie 2:(2n+1) (and finer) locks: bisect on the shaker frequency to find one
        attempt = 0
        for attempt in range(6):
            found = None
            c0 = rng.uniform(2.6, 6.8)
            r0 = pilot_ratio(c0)
            if dist_int(r0) >= 0.2:
                found = c0
            else:
                c1 = min(7.9, c0 * (1.0 + 1.2 / max(r0, 2.0)))
                r1_ = pilot_ratio(c1)
                if dist_int(r1_) >= 0.2:
                    found = c1
                elif r0 == r0 and r1_ == r1_ and round(r1_) != round(r0):
                    a_, b_ = c0, c1
                    for _k in range(9):
                        cm = 0.5 * (a_ + b_)
                        rm = pilot_ratio(cm)
                        if dist_int(rm) >= 0.2:
                            found = cm
                            break
                        if rm != rm:
                            break
                        if round(rm) == round(r0):
                            a_ = cm
                        else:
                            b_ = cm
            if found is None:
                continue
            ft = found * P["fn"]
            nmult_fn = 1.0 + at * np.sin(2 * math.pi * ft * tg + ph)
            sim = _simulate(P, law, omega_fn, nmult=nmult_fn, q0=q0, **kw)
            res, segs, Fs = _measure(sim, P)
            ratio = ft / res["f_ss"]
            dist = abs(ratio - round(ratio))
            if best is None or dist > best[0]:
                best = (dist, sim, res, ft)
            if dist >= 0.15:
                break
        info["shaker_pilots"] = len(cache)
        if best is None:
            raise RuntimeError("triggering: no usable shaker frequency")
        dist, sim, res, ft = best
        info.update(shaker_ft_hz=ft, shaker_amp=at, shaker_phase=ph, shaker_attempts=attempt + 1)
    else:
        sim = _simulate(P, law, omega_fn, q0=q0, **kw)
        res, segs, Fs = _measure(sim, P)
        if case == "static_ageing":
            # one correction of the ageing amplitude toward the drawn target, on the full record
            g, _ = _ageing_growth(res)
            if g > 0 and abs(g / info["ageing_target"] - 1.0) > 0.15:
                Da, taua = kw["age"]
                Da *= (info["ageing_target"] / g) ** 1.1
                kw["age"] = (Da, taua)
                info["age_Da"] = Da
                sim = _simulate(P, law, omega_fn, q0=q0, **kw)
                res, segs, Fs = _measure(sim, P)
    return P, law, sim, res, info, mode, kw


def _truth_measures(case, P, law, sim, res, info, mode):
    """The departure sizes and the rig's inherent effects, measured on the ground truth."""
    R, k, h = P["R"], P["k"], P["h"]
    meas = {}
    segs, drops = res["segs"], res["drops"]
    drop = float(np.median(drops))
    u = np.abs(sim["v"])
    Ff = sim["T"] / R
    N = sim["N"]
    a0 = segs[0][0]
    meas["n_cycles"] = len(segs) + 1
    meas["f_ss_hz"] = res["f_ss"]
    meas["drop_N"] = drop
    meas["drop_over_peak"] = float(drop / np.median(res["peaks"]))
    meas["static_deflection_deg"] = float(np.degrees(np.max(sim["q"][a0:])))
    meas["slip_speed_over_v0"] = float(np.median([u[b:a + 1].max() for b, a in segs]) / P["v0"])
    meas["twin_F"] = _twin(u, Ff, segs, drops)
    meas["twin_mu_x_N0"] = _twin(u, Ff / N * P["N0"], segs, drops)
    Nv = N[a0:]
    meas["load_pp_over_N0"] = float((Nv.max() - Nv.min()) / P["N0"])
    meas["load_pp_over_N0_p05"] = float((np.percentile(Nv, 99.5) - np.percentile(Nv, 0.5)) / P["N0"])
    mu_mean = float(np.mean(Ff[a0:] / N[a0:]))
    meas["load_pp_effect_over_drop"] = float(mu_mean * (Nv.max() - Nv.min()) / drop)
    # a linear 1-DoF reading of the exact restoring force: x = F/k, friction = M x'' + c x' + k x
    xl = R * np.sin(sim["q"])
    v0t = sim["omega"] * R
    xd = np.gradient(xl, h)
    xdd = np.gradient(xd, h)
    f1 = P["M"] * xdd + P["c_air"] / R ** 2 * xd + k * xl
    dr1 = np.array([k * (xl[b] - xl[a]) for b, a in segs])
    meas["twin_1dof_reading"] = _twin(np.abs(v0t - xd), f1, segs, dr1)
    # and of the encoder's arc x = R theta
    xe = R * sim["q"]
    xd = np.gradient(xe, h)
    xdd = np.gradient(xd, h)
    f2 = P["M"] * xdd + P["c_air"] / R ** 2 * xd + k * xe
    dr2 = np.array([k * (xe[b] - xe[a]) for b, a in segs])
    meas["twin_1dof_arc"] = _twin(np.abs(v0t - xd), f2, segs, dr2)
    # the same reading behind the slowest sensor low-pass used (one pole at 15 fn)
    a = math.exp(-2 * math.pi * 15.0 * P["fn"] * h)
    xf = lfilter([1 - a], [1, -a], xl - xl[0]) + xl[0]
    xd = np.gradient(xf, h)
    xdd = np.gradient(xd, h)
    f3 = P["M"] * xdd + P["c_air"] / R ** 2 * xd + k * xf
    dr3 = np.array([k * (xf[b] - xf[a_]) for b, a_ in segs])
    meas["twin_1dof_lowpass15"] = _twin(np.abs(v0t - xd), f3, segs, dr3)
    g, rr = _ageing_growth(res)
    meas["peak_growth_over_drop"] = g
    meas["stick_time_ratio"] = rr
    meas["peak_sd_over_drop"] = float(np.std(res["peaks"]) / drop)
    if case == "triggering":
        ratio = info["shaker_ft_hz"] / res["f_ss"]
        meas["ft_over_fss"] = float(ratio)
        meas["ft_over_fss_int_dist"] = float(abs(ratio - round(ratio)))
        meas["ft_over_fn"] = float(info["shaker_ft_hz"] / P["fn"])
        meas["shaker_pp_over_N0"] = 2 * info["shaker_amp"]
    if case == "drive_modulation":
        meas["fm_over_fss"] = float(info["mod_fm_hz"] / res["f_ss"])
        meas["mod_a"] = info["mod_a"]
    if case == "twin_branch":
        meas["film_min"] = float(np.min(sim["phi"][a0:]))
    return meas


def _fmt(v):
    return "%.7g" % v


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    t_start = time.time()
    P, law, sim, res, info, mode, kw = _build(case, seed)
    meas = _truth_measures(case, P, law, sim, res, info, mode)
    ci, ni = CASES.index(case), NUISANCES.index(nuisance)
    rng = np.random.default_rng([48017, ci, int(seed), 100 + ni])
    R, k, h, fn, Tn = P["R"], P["k"], P["h"], P["fn"], P["Tn"]
    drop = meas["drop_N"]
    t = sim["t"]
    # ---------------- choices of the record ----------------
    kind = "encoder" if rng.random() < 0.5 else "inclinometer"
    has_N = case == "load_variation" or (case != "load_variation" and rng.random() < 0.35)
    drive_col = None
    if mode in ("steps", "holds"):
        drive_col = "v0" if (kind == "encoder" or rng.random() < 0.5) else "position"
    elif case != "drive_modulation" and rng.random() < 0.25:
        drive_col = "v0" if (kind == "encoder" or rng.random() < 0.5) else "position"
    style = int(rng.integers(0, 4))
    omit_fn = (seed % 8) == ((2 + 3 * ci) % 8 if (2 + 3 * ci) % 8 != 6 else 1)
    if nuisance == "fn_off":
        omit_fn = False
    # ---------------- sampling ----------------
    segs = res["segs"]
    bt = np.array([t[b] for b, a in segs])
    f_ss = 1.0 / float(np.percentile(np.diff(bt), 20))      # the record's shorter periods
    if nuisance == "coarse":
        fs = rng.uniform(10.0, 15.0) * fn
        if fs / f_ss < 20.0:
            fs = 20.5 * f_ss
    else:
        fs = rng.uniform(30.0, 95.0) * f_ss
        if fs / f_ss > 100.0:
            fs = 99.0 * f_ss
        fs = max(fs, 16.0 * fn)
    t0 = rng.uniform(0, 0.5 / fs)
    tk = np.arange(t0, t[-1], 1.0 / fs)
    # ---------------- main channel ----------------
    noise = rng.uniform(0.001, 0.005) * drop
    drift_amp = rng.uniform(0.0005, 0.003) * drop
    if nuisance == "drift":
        drift_amp = rng.uniform(0.02, 0.05) * drop * rng.choice([-1, 1])
    tau_th = rng.uniform(0.3, 1.5) * t[-1]
    drift = drift_amp * (1 - np.exp(-tk / tau_th)) / (1 - math.exp(-t[-1] / tau_th))
    if kind == "encoder":
        unit = "mm" if rng.random() < 0.6 else "um"
        scale = 1000.0 / k if unit == "mm" else 1e6 / k   # N (force units) -> x units
        if nuisance == "quantisation":
            qstep_F = rng.uniform(0.002, 0.01) * drop
        else:
            qstep_F = rng.uniform(0.0001, 0.0005) * drop
        counts = int(round(2 * math.pi * R * k / qstep_F))
        dq = 2 * math.pi / counts
        qk = np.interp(tk, t, sim["q"])
        qk = qk + rng.normal(0, noise / (k * R), tk.size) + drift / (k * R)
        qk = np.round(qk / dq) * dq
        y_main = R * qk * (1000.0 if unit == "mm" else 1e6)
        main_name, main_unit = "x", unit
        sig_scale = scale
        info["encoder_counts_per_rev"] = counts
    else:
        unit = "N" if rng.random() < 0.5 else "mN"
        fscale = 1.0 if unit == "N" else 1000.0
        fc = rng.uniform(15.0, 40.0) * fn
        a = math.exp(-2 * math.pi * fc * h)
        Fs = k * R * np.sin(sim["q"])
        Fl = lfilter([1 - a], [1, -a], Fs - Fs[0]) + Fs[0]
        Fk = np.interp(tk, t, Fl) + rng.normal(0, noise, tk.size) + drift
        if nuisance == "quantisation":
            adc = rng.uniform(0.002, 0.01) * drop
        else:
            adc = 2 * k * R * 0.5 / 2 ** 20
        Fk = np.round(Fk / adc) * adc
        y_main = Fk * fscale
        main_name, main_unit = ("F" if rng.random() < 0.5 else "friction"), unit
        sig_scale = fscale
        info["lowpass_fc_over_fn"] = fc / fn
        info["adc_step_over_drop"] = adc / drop
    if nuisance == "hum":
        fh = 50.0 if rng.random() < 0.6 else 60.0
        A1 = rng.uniform(0.01, 0.04) * drop
        hum = A1 * np.sin(2 * math.pi * fh * tk + rng.uniform(0, 6.3)) + \
            0.3 * A1 * np.sin(2 * math.pi * 3 * fh * tk + rng.uniform(0, 6.3))
        y_main = y_main + hum * sig_scale
        info.update(hum_hz=fh, hum_amp_over_drop=A1 * 1.3 / drop)
    if nuisance == "spikes":
        frac = rng.uniform(0.0008, 0.004)
        nsp = max(2, int(round(frac * tk.size)))
        idx = np.sort(rng.choice(np.arange(2, tk.size - 2), nsp, replace=False))
        keep = np.concatenate([[True], np.diff(idx) > 2])
        idx = idx[keep]
        y_main[idx] += rng.choice([-1, 1], idx.size) * rng.uniform(0.2, 1.0, idx.size) * drop * sig_scale
        info.update(spike_fraction=idx.size / tk.size)
    cols = [("t", "s", tk), (main_name, main_unit, y_main)]
    # ---------------- normal channel ----------------
    if has_N:
        Nk = np.interp(tk, t, sim["N"])
        if kind == "encoder":
            kcap = rng.uniform(2e4, 2e5)
            y0 = rng.uniform(0.2, 1.0)
            yk = y0 + 1000.0 * Nk / kcap + rng.normal(0, 0.001 * 1000.0 * P["N0"] / kcap, tk.size)
            cols.append(("y", "mm", yk))
            info["cap_stiffness_N_per_m"] = kcap
        else:
            nunit = unit
            Nn = Nk + rng.normal(0, 0.001 * P["N0"], tk.size)
            cols.append(("N" if main_name == "F" else "normal", nunit, Nn * (1.0 if nunit == "N" else 1000.0)))
    # ---------------- drive channel ----------------
    if drive_col == "v0":
        vk = np.interp(tk, t, sim["omega"]) * R * 1000.0
        cols.append(("v0", "mm/s", np.round(vk, 6)))
    elif drive_col == "position":
        pu = "mm" if rng.random() < 0.5 else "um"
        phi_sh = np.concatenate([[0.0], np.cumsum(0.5 * (sim["omega"][1:] + sim["omega"][:-1]) * h)])
        pk = np.interp(tk, t, phi_sh) * R * (1000.0 if pu == "mm" else 1e6)
        cols.append(("position", pu, pk))
    # ---------------- args ----------------
    args = []
    fn_given = None
    if not omit_fn:
        fn_given = fn * (1.0 + (rng.choice([-1, 1]) * 0.05 if nuisance == "fn_off" else 0.0))
        args += ["--fn", "%.6g" % fn_given]
    if drive_col is None:
        args += ["--v0", "%.6g" % (P["v0"] * 1000.0)]
    if kind == "inclinometer":
        args += ["--stiffness", "%.6g" % k]
    # ---------------- write ----------------
    os.makedirs(outdir, exist_ok=True)
    fname = "%s_%s_s%d_%s.%s" % (NAME, case, seed, nuisance, "txt" if style == 3 else "csv")
    path = os.path.abspath(os.path.join(outdir, fname))
    data = np.column_stack([c[2] for c in cols])
    if not np.all(np.isfinite(data)):
        raise RuntimeError("non-finite values in the record")
    lines = []
    if style == 0:
        if rng.random() < 0.5:
            lines.append("# Froude pendulum rig, %s, seed %d" % ("encoder" if kind == "encoder" else "hub inclinometer", seed))
        names = {"t": "time"} if rng.random() < 0.5 else {}
        lines.append(",".join("%s [%s]" % (names.get(n, n), u) for n, u, _ in cols))
        lines += [",".join(_fmt(v) for v in row) for row in data]
    elif style == 1:
        lines.append("\t".join("%s/%s" % ("time" if n == "t" else n, u) for n, u, _ in cols))
        lines += ["\t".join(_fmt(v) for v in row) for row in data]
    elif style == 2:
        lines.append(";".join("%s (%s)" % ("Time" if n == "t" else n, u) for n, u, _ in cols))
        lines += [";".join(_fmt(v).replace(".", ",") for v in row) for row in data]
    else:
        lines.append("# Froude pendulum, bearing stick-slip; sampled at %.4g Hz" % fs)
        lines.append(" ".join("%s" % ("time" if n == "t" else n) for n, u, _ in cols))
        lines.append(" ".join(u for n, u, _ in cols))
        lines += [" ".join(_fmt(v) for v in row) for row in data]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    meas["samples_per_period"] = float(fs / f_ss)
    meas["samples_per_mean_period"] = float(fs / meas["f_ss_hz"])
    meas["samples_per_Tn"] = float(fs / fn)
    meas["gen_seconds"] = time.time() - t_start
    params = {k_: (float(v) if isinstance(v, (float, np.floating, int, np.integer)) else v) for k_, v in P.items()}
    params.update({k_: (float(v) if isinstance(v, (float, np.floating, np.integer)) else v) for k_, v in info.items()})
    params.update(law_knots=law.knots, law_kappa=law.kappa, law_v_min_over_vref=law.v_min, record_kind=kind,
                  normal_recorded=bool(has_N), drive_column=drive_col, drive_mode=mode, style=style,
                  fs_hz=float(fs), noise_over_drop=noise / drop, drift_over_drop=float(drift_amp / drop),
                  measured={k_: float(v) for k_, v in meas.items()})
    params = json.loads(json.dumps(params, default=float))
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": path,
            "args": args, "fn_true": float(fn), "fn_given": (float(fn_given) if fn_given is not None else None),
            "params": params}


def _summary(tr):
    m = tr["params"]["measured"]
    c = tr["case"]
    s = "%-16s s%d %-12s cyc %3d  spp %5.1f  t %.2fs  " % (c, tr["seed"], tr["nuisance"], m["n_cycles"],
                                                           m["samples_per_period"], m["gen_seconds"])
    if c == "load_variation":
        s += "load p-p %.3f N0 (%+.0f)" % (m["load_pp_over_N0_p05"], tr["params"]["cam_sign"])
    elif c == "twin_branch":
        s += "twin %.3f drop" % m["twin_F"]
    elif c == "static_ageing":
        s += "growth %.3f drop over stick x%.1f" % (m["peak_growth_over_drop"], m["stick_time_ratio"])
    elif c == "triggering":
        s += "ft/fss %.2f (dist %.2f) ft/fn %.2f" % (m["ft_over_fss"], m["ft_over_fss_int_dist"], m["ft_over_fn"])
    elif c == "drive_modulation":
        s += "a %.2f fm/fss %.2f" % (m["mod_a"], m["fm_over_fss"])
    else:
        s += "twin F %+.4f mu %+.4f 1dof %+.4f arc %+.4f lp %+.4f | N p-p %.4f N0 (%.4f drop) | growth %+.4f x%.1f" % (
            m["twin_F"], m["twin_mu_x_N0"], m["twin_1dof_reading"], m["twin_1dof_arc"], m["twin_1dof_lowpass15"],
            m["load_pp_over_N0"],
            m["load_pp_effect_over_drop"], m["peak_growth_over_drop"], m["stick_time_ratio"])
    return s


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "froude_records"
    cases = sys.argv[2].split(",") if len(sys.argv) > 2 else CASES
    for case in cases:
        for seed in range(8):
            tr = write_record(case, seed, out, NUISANCES[seed % len(NUISANCES)])
            print(_summary(tr), flush=True)
