"""gms_torsion: an independent record generator for `lieng diagnose` (written without reading the package).

README table row, in words (every number measured on the noise-free ground truth, seeds 0-7 of each case,
the nuisance of seed s being ["clean","hum","drift","spikes","quantisation","coarse","fn_off"][s % 7]):

Rig. A **torsion-arm tribometer**: a pin at the end of an arm of radius R = 25-70 mm on a torsion bar
(k_theta; linearised at the pin k = k_theta / R^2 = 300-4000 N/m, m = J / R^2) rests on a rotating table
whose surface speed at the pin is the drive. The load cell reads the bar's torque, reported as the force at
the pin. The bar is **viscoelastic (a standard linear solid)**: a Maxwell arm of 1-3 % of k relaxing with
tau2 = 0.2-2 Tn (bar force k x + q, q' = k2 x' - q / tau2), plus 0.3-1.2 % structural damping.
fn_true = |s| / 2 pi of the complex root of m s^2 + c s + k + k2 tau2 s / (1 + tau2 s) = 0 (the pin
sliding): 6.1-50 Hz.

Friction law. **Generalized Maxwell-Slip** (Al-Bender, Lampaert & Swevers 2005) with 4-8 parallel elements
(weights alpha_i ~ Gamma(2), normalised; break displacements spread log-uniformly over 0.7-1.3 decades;
total presliding stiffness 20-50 k; stuck elements carry a micro-damping of 0.15-0.35 of the presliding
mode's critical). Stuck: F_i' = k_i v (v the sliding speed, table minus pin). Slipping:
F_i' = sign(v) C alpha_i (1 - F_i / (alpha_i s(v))), the lag s(v)/C being 0.04-0.1 % of Tn at Fs.
s(v) = lambda (Fc + (Fs - Fc) exp(-(|v|/vs)^delta)), delta 1.0-1.25, vs 0.08-0.25 of the slip speed scale
(Fs - Fc)/sqrt(k m), mu_s/mu_c 1.18-1.45, lambda = N/N0; plus a viscous sigma2 v (3-10 % of Fs - Fc at that
speed scale). Its `none`: the law's hysteresis (decelerating minus accelerating true friction at equal
sliding speed, 0.15-0.85 of each slip's peak speed, over the drop) is **-0.56..-0.28 %** of the drop (the
slip lag makes the accelerating branch the higher); a 1-DoF reading of the clean bar force
(F + m x'' + c x' against v0 - x') sees +0.8..+1.7 % (the SLS arm); constant-drive peaks identical; on the
two stepped-drive seeds (3, 6: levels 1, 1.4-1.8, 0.55-0.75 of v0, recorded) the peak against ln(stick
time) reads -6.0 % and -1.6 % of the drop over 2.4x / 1.8x stick times (the breakaway's inertial overshoot
grows with the drive speed; the law has no ageing outside `static_ageing`).

Stick handling. None beyond the law: each GMS element switches stick -> slip when its force reaches
alpha_i s(v) on the side it is being pushed to, slip -> stick when v crosses zero (an element pushed past
its limit on the other side by a shrinking load yields back to it); the pin's speed is a continuous state.
In stick the pin creeps at **2.0-5.1 %** of the drive (median over the stick) and rings in presliding after
each arrest.

Integrator. Own, fixed step Tn/320 (Tn/40 once a stick is quiet, Tn/20 during drive holds, Tn/160 with the
shaker): the trapezoidal rule for the arm (x, x'), the exact exponential update of the SLS arm, per-element
closed forms over the step (stuck: k_i times the integral of v; slipping: exact relaxation toward
sign(v) alpha_i s(v) at the step's mid speed, the slip direction frozen over the step), Newton on the
end-of-step arm speed with an analytic derivative. Switches are events: v crossing zero and an element
reaching its limit are located by linear interpolation within the step and the step is retaken to the
event. The film (twin) and the junction ages (ageing) are advanced explicitly after each step. No solve_ivp.

Departures (realised in the physics; measured sizes):
- load_variation: a **dished disc face** under the swinging pin; the pin's height on its arc sets the load
  of a stiff loading flexure, N = N0 (1 + c1 xi + c2 xi^2), xi = (x - Fc/k) / ((Fs - Fc)/k), |c2| <= 0.4
  |c1|; rising on 6 seeds (kept below the wedge lock), falling on seeds 1 and 5. **N p-p 12.0-32.3 % of
  N0**, recorded; F/N against v stays single-valued (-1.9..+0.2 % of the drop).
- twin_branch: a **tribo-oxide film** phi, delaminated by the frictional power (phi' = -phi |F v| / W,
  1/e after 0.5-1.25 slips' energy) and regrown by parabolic (Wagner) oxidation, d(phi^2)/dt = kappa (full
  regrowth in 0.3-0.7 of a stick); the bare fraction raises every element's level, s -> s (1 + gamma
  (1 - phi)), gamma tuned per seed. **+13.0..+19.8 %** of the drop (a 1-DoF reading +14.6..+21.3 %).
- static_ageing: **per-junction ageing**: each element's limit alpha_i (1 + beta ln(1 + a_i / tau_a)),
  tau_a 0.05-0.3 Tn, its age a_i growing while it is stuck and lost over 0.02-0.06 of the largest break
  displacement of slip (so elements that creep out early lose theirs); beta tuned per seed (0.03-0.11).
  Drive steps 4.5-7.5x (even seeds) or holds of 1.5-12 stick times (odd seeds), the drive recorded.
  **Peak growth +9.4..+11.8 %** of the drop over 5.7-10x stick times (regression on ln stick time;
  beyond the same record's beta = 0 trend +10.0..+12.8 %, that trend -1.3..0 %); the ageing's own twin
  -2.2..-0.3 %.
- triggering: a voice-coil shaker on the loading arm, N = N0 (1 + eps sin(2 pi f_t t + psi)),
  **eps 3.1-5.1 % (p-p 6.1-10.3 %) of N0, f_t 2.6-5.5 fn**; the drive is set for 2.5-6 shaker periods per
  stick and f_t redrawn (up to 8 runs) until the record's f_t/f_ss is >= 0.2 from an integer:
  **f_t/f_ss 4.50-7.67, 0.23-0.50 from an integer** (the breakaways lock to the shaker's troughs,
  alternating n and n+1 shaker periods per cycle). Normal channel recorded.
- drive_modulation: v0(t) = v0n (1 + a sin(2 pi fm t + phi)), **a 0.23-0.42, fm/f_ss 0.16-0.38** (fm set
  from a 5-cycle pilot, checked on the record); only v0n given (--v0), no drive column.

Records. Force (the bar force at the pin in N or mN, `--stiffness` k; a normal column in N/mN; a drive
position column in mm/um from a 1 um / 0.1 um encoder, or the table speed v0 in mm/s) on half the seeds,
displacement (x = F/k in mm, y = y0 + b N in mm from the loading flexure's gauge, v0 in mm/s) on the
others; comma, semicolon, TAB or whitespace (`name [unit]`, `name[unit]` when whitespace-separated), a
round sampling rate. Sensor: a second-order transducer (10-30 fn, zeta 0.05-0.3) and a one-pole
anti-alias (0.15-0.3 fs; 0.33-0.42 fs on triggering records), AR(1) noise (rho 0.3-0.9) of 0.2-0.8 % of the
drop on the force, 0.1-0.4 % of N0 on the load. 20-100 samples per period (10-15 `coarse`), 18-38
cycles after 3 warm-up slips. `--fn` on 7 of 8 seeds per case (8 of 8 for triggering), 5 % off for
`fn_off`; `--v0` when there is no drive column. Nuisances: hum 50/60 Hz with 2nd/3rd harmonics of 1-5 % of
the drop; drift 2-6 % of the drop (linear + quadratic); isolated spikes on 0.05-0.5 % of samples
(0.3-1.2 drops); quantisation steps 0.2-1 % of the drop.

Time: 0.13-1.5 s per record (0.9-2.2 s including the interpreter and imports).
The physics depends on (case, seed) only (for triggering also on whether the record is `coarse`); the
sensor noise and the nuisance on (case, seed, nuisance).
"""

import math
import os
import zlib
from bisect import bisect_right

import numpy as np
from scipy import signal
from scipy.interpolate import CubicHermiteSpline

NAME = "gms_torsion"
CASES = ["none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation"]
NUISANCES = ["clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off"]


# ----------------------------------------------------------------------------------------------
# random streams
# ----------------------------------------------------------------------------------------------
def _rng(*keys):
    s = "|".join(str(k) for k in keys)
    return np.random.default_rng([zlib.crc32(s.encode()), len(s), 20240611])


def _lu(r, a, b):
    """log-uniform draw"""
    return float(math.exp(r.uniform(math.log(a), math.log(b))))


# ----------------------------------------------------------------------------------------------
# drive: piecewise-linear table speed at the pin radius (motor ramps), or a modulated speed
# ----------------------------------------------------------------------------------------------
class _Drive:
    def __init__(self, v0, mod=None):
        self.tb = [0.0]
        self.vb = [v0]
        self.mod = mod  # (a, wm, phi)
        self.v0 = v0

    def vd(self, t):
        if self.mod is not None:
            a, wm, ph = self.mod
            return self.v0 * (1.0 + a * math.sin(wm * t + ph))
        tb = self.tb
        if t >= tb[-1]:
            return self.vb[-1]
        i = bisect_right(tb, t) - 1
        t0 = tb[i]
        return self.vb[i] + (self.vb[i + 1] - self.vb[i]) * (t - t0) / (tb[i + 1] - t0)

    def ramp_to(self, t0, v_new, tr):
        """from time t0 (>= last breakpoint) ramp linearly to v_new in tr"""
        v_old = self.vd(t0)
        if t0 > self.tb[-1]:
            self.tb.append(t0)
            self.vb.append(v_old)
        self.tb.append(t0 + tr)
        self.vb.append(v_new)

    def hold(self, t0, dur, tr):
        v_old = self.vd(t0)
        self.ramp_to(t0, 0.0, tr)
        self.tb.append(t0 + tr + dur)
        self.vb.append(0.0)
        self.tb.append(t0 + 2 * tr + dur)
        self.vb.append(v_old)

    def vd_arr(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            a, wm, ph = self.mod
            return self.v0 * (1.0 + a * np.sin(wm * t + ph))
        return np.interp(t, self.tb + [max(self.tb[-1], t.max()) + 1.0], self.vb + [self.vb[-1]])

    def X_arr(self, t):
        """drive position (exact integral of the speed)"""
        t = np.asarray(t, float)
        if self.mod is not None:
            a, wm, ph = self.mod
            return self.v0 * (t - a / wm * (np.cos(wm * t + ph) - math.cos(ph)))
        tb = np.array(self.tb + [max(self.tb[-1], t.max()) + 1.0])
        vb = np.array(self.vb + [self.vb[-1]])
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (vb[1:] + vb[:-1]) * np.diff(tb))])
        i = np.clip(np.searchsorted(tb, t, side="right") - 1, 0, len(tb) - 2)
        dt = t - tb[i]
        slope = (vb[i + 1] - vb[i]) / (tb[i + 1] - tb[i])
        return cum[i] + vb[i] * dt + 0.5 * slope * dt * dt


# ----------------------------------------------------------------------------------------------
# physics: torsion arm (linearised at the pin radius), SLS torsion bar, GMS contact
# ----------------------------------------------------------------------------------------------
def _simulate(P, drive, n_slips, ctl=None, t_max=None):
    """Own integrator: trapezoidal rule for the arm (x, u), exact exponential update of the SLS arm q,
    per-element closed forms for the GMS elements over a step (stuck: F += k_i * integral of v;
    slipping: exact relaxation toward sign(v) alpha_i s(v) for the step's mid speed), Newton on the
    end-of-step arm speed. Element switches are events: v crossing zero (slip -> stick) and an
    element reaching its limit (stick -> slip) are located by linear interpolation of the step and
    the step is retaken to the event. Film (twin) and contact ages (ageing) are advanced explicitly
    after each accepted step."""
    m, k, c = P["m"], P["k"], P["c"]
    k2, tau2 = P["k2"], P["tau2"]
    n = P["n_el"]
    kel = list(P["k_el"])
    alp = list(P["alpha"])
    dd = list(P["d_el"])
    Fs, Fc, vs, dl, sig2, Cg = P["Fs"], P["Fc"], P["vs"], P["delta"], P["sig2"], P["C"]
    dF = Fs - Fc
    Tn = P["Tn"]
    Vst = P["Vstar"]
    vref = P["v0"]
    # load
    L1, L2, xm = P.get("L1", 0.0), P.get("L2", 0.0), P.get("xm", 0.0)
    eps, wt, pt = P.get("eps_t", 0.0), P.get("w_t", 0.0), P.get("psi_t", 0.0)
    # twin film
    gam = P.get("gamma_tw", 0.0)
    Wf = P.get("W_film", 1.0)
    kap = P.get("kappa_film", 1.0)
    # ageing
    beta = P.get("beta_age", 0.0)
    tau_a = P.get("tau_age", 1.0)
    Da = P.get("D_age", 1.0)

    h_fine = Tn / 320.0
    h_quiet = Tn / (160.0 if eps > 0 else 40.0)
    h_hold = Tn / 20.0
    hmin = h_fine * 1e-3
    utol = 1e-11 * Vst
    thr_slip = 0.25 * Vst

    def sfun(a):
        return Fc + dF * math.exp(-((a / vs) ** dl))

    def lamf(t, x):
        dx = x - xm
        return 1.0 + L1 * dx + L2 * dx * dx + (eps * math.sin(wt * t + pt) if eps else 0.0)

    # initial state: pin moving with the table, spring loaded to the kinetic level, elements stuck
    t = 0.0
    vd0 = drive.vd(0.0)
    u = vd0 * (1.0 - 0.03)
    x = (0.5 * (Fs + Fc)) / k
    q = 0.0
    F = [a * k * x for a in alp]
    stk = [True] * n
    phi = 1.0
    ages = [20.0 * Tn] * n
    gage = [1.0 + beta * math.log(1.0 + a / tau_a) for a in ages]
    lam_now = lamf(t, x)
    gtw = 1.0 + gam * (1.0 - phi)

    def force_now(v):
        Ff = sig2 * v
        for i in range(n):
            Ff += F[i] + (dd[i] * v if stk[i] else 0.0)
        return Ff

    Ff0 = force_now(vd0 - u)
    G0 = Ff0 - k * x - q - c * u

    T_, X_, U_, Q_, FF_, LA_, VD_, PH_ = [t], [x], [u], [q], [Ff0], [lam_now], [vd0], [phi]
    arrests = []  # log index of each arrest (end of a slip)
    in_slip = False
    t_active = 0.0
    nsl = 0
    t_stop = None
    Fn = [0.0] * n
    nev = 0

    def attempt(h):
        td = t + h
        vd1 = drive.vd(td)
        v0s = vd0 - u
        E2 = math.exp(-h / tau2)
        G2 = (1.0 - E2) * tau2 / h
        u1 = u + h * G0 / m
        hh = 0.5 * h
        sg = 1.0 if v0s >= 0.0 else -1.0  # slip direction is fixed over a step (a reversal is an event)
        for _ in range(14):
            v1 = vd1 - u1
            vm = 0.5 * (v0s + v1)
            x1 = x + hh * (u + u1)
            q1 = q * E2 + k2 * (x1 - x) * G2
            dx = x1 - xm
            lam1 = 1.0 + L1 * dx + L2 * dx * dx + (eps * math.sin(wt * td + pt) if eps else 0.0)
            dlam1 = (L1 + 2.0 * L2 * dx) * hh
            lamm = 0.5 * (lam_now + lam1)
            avm = sg * vm
            if avm < 0.0:
                avm = 0.0
            r = avm / vs
            ex = math.exp(-(r ** dl))
            sv = Fc + dF * ex
            dsv = (dF * ex * dl * (r ** (dl - 1.0)) / vs) * 0.5 * sg  # d s / d u1
            smf = sv * lamm * gtw
            E = math.exp(-h * Cg / smf)
            Ff = sig2 * v1
            dFf = -sig2
            for i in range(n):
                if stk[i]:
                    Fi = F[i] + kel[i] * h * vm
                    Ff += Fi + dd[i] * v1
                    dFf -= kel[i] * hh + dd[i]
                else:
                    ag = alp[i] * gage[i]
                    T = sg * ag * smf
                    Fi = T + (F[i] - T) * E
                    Ff += Fi
                    dFf += (1.0 - E) * sg * ag * gtw * (dsv * lamm + sv * 0.5 * dlam1)
                Fn[i] = Fi
            G1 = Ff - k * x1 - q1 - c * u1
            dG1 = dFf - k * hh - k2 * G2 * hh - c
            R = m * (u1 - u) - hh * (G0 + G1)
            du = R / (m - hh * dG1)
            u1 -= du
            if abs(du) < utol:
                break
        # events
        th = 2.0
        anyslip = not all(stk)
        if anyslip and v0s * v1 < 0.0:
            th = v0s / (v0s - v1)
        s0 = sfun(abs(v0s)) * lam_now * gtw
        s1 = sfun(abs(v1)) * lam1 * gtw
        sg1 = 1.0 if v1 >= 0.0 else -1.0
        for i in range(n):
            if stk[i]:
                # a stuck element breaks when its force reaches the limit on the side it is pushed to
                ag = alp[i] * gage[i]
                e1 = sg1 * Fn[i] - ag * s1
                if e1 > 0.0:
                    e0 = sg1 * F[i] - ag * s0
                    if e1 <= e0:
                        continue
                    thi = 0.0 if e0 >= 0.0 else e0 / (e0 - e1)
                    if thi < th:
                        th = thi
        return th, u1, x1, q1, Ff, lam1, vd1, v1, td

    while True:
        v_now = vd0 - u
        if abs(v_now) > 0.08 * vref or (not all(stk) and abs(v_now) > 0.02 * vref):
            t_active = t
        quiet = (t - t_active) > Tn / 3.0
        if quiet:
            h = h_hold if (eps == 0.0 and vd0 == 0.0 and drive.vd(t + h_hold) == 0.0) else h_quiet
        else:
            h = h_fine
        res = attempt(h)
        if res[0] < 1.0:
            nev += 1
            h2 = max(res[0] * h, hmin)
            if h2 < h:
                res = attempt(h2)
        th, u1, x1, q1, Ff, lam1, vd1, v1, td = res
        v0s = vd0 - u
        # accept
        Fold = F[:]
        s_old = sfun(abs(v0s)) * lam_now * gtw
        F[:] = Fn
        # explicit film / age updates over the step
        vm = 0.5 * (v0s + v1)
        hstep = td - t
        if gam:
            P_ = abs((Ff - sig2 * v1) * vm)
            phi *= math.exp(-P_ * hstep / Wf)
            phi = min(1.0, math.sqrt(phi * phi + kap * hstep))
            gtw = 1.0 + gam * (1.0 - phi)
        if beta:
            dec = math.exp(-abs(vm) * hstep / Da)
            for i in range(n):
                if stk[i]:
                    ages[i] += hstep
                else:
                    ages[i] *= dec
                gage[i] = 1.0 + beta * math.log(1.0 + ages[i] / tau_a)
        t, x, u, q = td, x1, u1, q1
        vd0 = vd1
        lam_now = lam1
        switched = False
        # slip -> stick when v crosses zero
        if not all(stk) and (v0s * v1 <= 0.0 or abs(v1) < 1e-9 * Vst):
            for i in range(n):
                stk[i] = True
            switched = True
            if in_slip:
                in_slip = False
                nsl += 1
                arrests.append(len(T_))
                if ctl is not None:
                    ctl(nsl, t, drive)
                if nsl >= n_slips and t_stop is None:
                    per = (t - T_[arrests[0]]) / max(1, len(arrests) - 1) if len(arrests) > 1 else 2 * Tn
                    t_stop = t + 0.45 * per
        # stick -> slip when an element reaches its limit
        sl = sfun(abs(v1)) * lam1 * gtw
        sg1 = 1.0 if v1 >= 0.0 else -1.0
        for i in range(n):
            if stk[i]:
                ag = alp[i] * gage[i]
                lim = ag * sl
                e1 = sg1 * F[i] - lim
                if e1 >= -1e-12 * lim and e1 > sg1 * Fold[i] - ag * s_old:
                    stk[i] = False
                    switched = True
                elif -sg1 * F[i] > lim:
                    # over the limit on the side opposite the motion (a shrinking limit): the junction
                    # yields back to its limit and stays stuck
                    F[i] = -sg1 * lim
                    switched = True
        if v1 > thr_slip:
            in_slip = True
        Ffe = force_now(v1) if switched else Ff
        G0 = Ffe - k * x - q - c * u
        T_.append(t)
        X_.append(x)
        U_.append(u)
        Q_.append(q)
        FF_.append(Ffe)
        LA_.append(lam1)
        VD_.append(vd1)
        PH_.append(phi)
        if t_stop is not None and t >= t_stop:
            break
        if t_max is not None and t >= t_max:
            break
    gt = dict(t=np.array(T_), x=np.array(X_), u=np.array(U_), q=np.array(Q_), Ff=np.array(FF_),
              lam=np.array(LA_), vd=np.array(VD_), phi=np.array(PH_), arrests=np.array(arrests, int),
              n_events=nev)
    gt["v"] = gt["vd"] - gt["u"]
    gt["Fsp"] = k * gt["x"] + gt["q"]
    return gt


def _draw_physics(case, seed):
    r = _rng(NAME, "phys", case, seed)
    fn0 = _lu(r, 6.0, 50.0)
    w0 = 2 * math.pi * fn0
    k = _lu(r, 300.0, 4000.0)  # N/m at the pin radius (k_theta / R^2)
    R = r.uniform(0.025, 0.070)  # m, arm radius
    m = k / w0 ** 2
    Tn = 1.0 / fn0
    N0 = _lu(r, 1.0, 15.0)
    mu_c = r.uniform(0.15, 0.45)
    mu_s = mu_c * r.uniform(1.18, 1.45)
    Fs, Fc = mu_s * N0, mu_c * N0
    Vst = (Fs - Fc) / math.sqrt(k * m)
    vs = r.uniform(0.08, 0.25) * Vst
    delta = r.uniform(1.0, 1.25)
    sig2 = r.uniform(0.03, 0.10) * (Fs - Fc) / Vst
    zeta = r.uniform(0.003, 0.012)
    c = 2 * zeta * math.sqrt(k * m)
    k2 = r.uniform(0.01, 0.03) * k
    tau2 = r.uniform(0.2, 2.0) * Tn
    n_el = int(r.integers(4, 9))
    alpha = r.gamma(2.0, 1.0, n_el)
    alpha = alpha / alpha.sum()
    spread = r.uniform(0.7, 1.3)
    zrel = 10 ** (np.sort(r.uniform(0, 1, n_el)) * spread)
    Kp = r.uniform(20.0, 50.0) * k
    # k_i = alpha_i Fs / z_i, z_i = z0 zrel_i ; sum k_i = Kp
    z0 = float(np.sum(alpha * Fs / zrel)) / Kp
    zstar = z0 * zrel
    k_el = alpha * Fs / zstar
    zeta_p = r.uniform(0.15, 0.35)
    Dtot = 2 * zeta_p * math.sqrt((k + Kp) * m)
    d_el = Dtot * k_el / k_el.sum()
    tau_lag = r.uniform(0.0004, 0.001) * Tn
    C = Fs / tau_lag
    n_st = r.uniform(0.8, 3.0)
    drop_est = 1.6 * (Fs - Fc)
    v0 = drop_est / k / (n_st * Tn)
    P = dict(fn0=fn0, k=k, R=R, k_theta=k * R * R, m=m, J=m * R * R, Tn=Tn, N0=N0, mu_c=mu_c, mu_s=mu_s,
             Fs=Fs, Fc=Fc, Vstar=Vst, vs=vs, delta=delta, sig2=sig2, zeta=zeta, c=c, k2=k2, tau2=tau2,
             n_el=n_el, alpha=alpha.tolist(), zstar=zstar.tolist(), k_el=k_el.tolist(), Kp_over_k=Kp / k,
             zeta_p=zeta_p, d_el=d_el.tolist(), tau_lag=tau_lag, C=C, n_stick_target=n_st, v0=v0,
             drop_est=drop_est)
    return P, r


# ----------------------------------------------------------------------------------------------
# measurements on the noise-free ground truth
# ----------------------------------------------------------------------------------------------
def _branch_twin(t, v, F, i0, i1, lo=0.15, hi=0.85, ng=29):
    """decelerating minus accelerating F at equal v over [lo, hi] of the peak speed in window [i0, i1)"""
    vw = v[i0:i1]
    if len(vw) < 8:
        return None, None
    ip = int(np.argmax(vw))
    vp = float(vw[ip])
    if vp <= 0:
        return None, None
    # accelerating branch: from the last sample below 0.1 vp before the peak
    below = np.nonzero(vw[:ip] < 0.1 * vp)[0]
    ia = int(below[-1]) if len(below) else 0
    vg = np.linspace(lo, hi, ng) * vp
    va, Fa = vw[ia:ip + 1], F[i0 + ia:i0 + ip + 1]
    vdd, Fd = vw[ip:][::-1], F[i0 + ip:i1][::-1]  # from the end backwards
    belowd = np.nonzero(vdd < 0.1 * vp)[0]
    if len(belowd):
        j = int(belowd[0])
        vdd, Fd = vdd[j:], Fd[j:]

    def first_cross(vb, Fb):
        cm = np.maximum.accumulate(vb)
        j = np.searchsorted(cm, vg, side="left")
        j = np.clip(j, 1, len(vb) - 1)
        v0_, v1_ = vb[j - 1], vb[j]
        w = np.where(v1_ != v0_, (vg - v0_) / np.where(v1_ != v0_, v1_ - v0_, 1.0), 0.0)
        w = np.clip(w, 0.0, 1.0)
        return Fb[j - 1] + w * (Fb[j] - Fb[j - 1])

    if len(va) < 3 or len(vdd) < 3:
        return None, vp
    return float(np.mean(first_cross(vdd, Fd) - first_cross(va, Fa))), vp


def _cycles(gt, P, t_lo=None):
    """per slip: peak (breakaway) of the spring force, trough, drop, stick time, peak speed, twin"""
    t, Fsp, v, Ff = gt["t"], gt["Fsp"], gt["v"], gt["Ff"]
    ar = gt["arrests"]
    out = []
    for j in range(1, len(ar)):
        a0, a1 = ar[j - 1], ar[j]
        ip = a0 + int(np.argmax(Fsp[a0:a1]))
        it = ip + int(np.argmin(Fsp[ip:a1 + 1]))
        drop = float(Fsp[ip] - Fsp[it])
        tw, vp = _branch_twin(t, v, Ff, a0 + 1, a1 + 1)
        out.append(dict(t_arrest_prev=float(t[a0]), t_peak=float(t[ip]), t_arrest=float(t[a1]),
                        peak=float(Fsp[ip]), trough=float(Fsp[it]), drop=drop, t_stick=float(t[ip] - t[a0]),
                        vp=vp, twin=(tw / drop if tw is not None and drop > 0 else None),
                        vd_stick=float(np.mean(gt["vd"][a0:ip + 1])),
                        creep=float(np.median(v[a0 + (ip - a0) // 3: ip - (ip - a0) // 4 + 1] /
                                              np.maximum(gt["vd"][a0 + (ip - a0) // 3: ip - (ip - a0) // 4 + 1],
                                                         1e-30)))))
    if t_lo is not None:
        out = [cy for cy in out if cy["t_arrest_prev"] >= t_lo]
    return out


def _fn_true(P):
    """undamped natural frequency of the pin on the viscoelastic (SLS) torsion bar, pin sliding"""
    m, c, k, k2, tau2 = P["m"], P["c"], P["k"], P["k2"], P["tau2"]
    roots = np.roots([m * tau2, m + c * tau2, c + (k + k2) * tau2, k])
    cpx = [z for z in roots if abs(z.imag) > 1e-9]
    return float(abs(cpx[0]) / (2 * math.pi))


def _twin_1dof(gt, P, cy):
    """the twin statistic a 1-DoF reading of the clean spring force sees (F + m x'' + c x', v0 - x')"""
    Tn = P["Tn"]
    dt = Tn / 400.0
    tg = np.arange(gt["t"][0], gt["t"][-1], dt)
    dF = P["k"] * gt["u"] + P["k2"] * gt["u"] - gt["q"] / P["tau2"]
    sp = CubicHermiteSpline(gt["t"], gt["Fsp"], dF)
    Fg = sp(tg)
    d1 = sp(tg, 1)
    d2 = np.gradient(d1, dt)
    k = P["k"]
    vdg = np.interp(tg, gt["t"], gt["vd"])
    v1 = vdg - d1 / k
    F1 = Fg + P["m"] * d2 / k + P["c"] * d1 / k
    vals = []
    for c_ in cy:
        i0 = np.searchsorted(tg, c_["t_arrest_prev"])
        i1 = np.searchsorted(tg, c_["t_arrest"] + 0.05 * Tn)
        tw, _ = _branch_twin(tg, v1, F1, i0, i1)
        if tw is not None:
            vals.append(tw / c_["drop"])
    return float(np.mean(vals)) if vals else None


def _peak_growth(cy):
    """peak growth over the record's range of stick times (regression on ln t_stick), over the drop"""
    ts = np.array([c["t_stick"] for c in cy])
    pk = np.array([c["peak"] for c in cy])
    dr = np.mean([c["drop"] for c in cy])
    L = np.log(ts)
    if L.max() - L.min() < 1e-6:
        return 0.0, 1.0
    A = np.vstack([L, np.ones_like(L)]).T
    sl = np.linalg.lstsq(A, pk, rcond=None)[0][0]
    return float(sl * (L.max() - L.min()) / dr), float(ts.max() / ts.min())


def _fss(cy):
    if len(cy) < 2:
        return None
    return float((len(cy) - 1) / (cy[-1]["t_arrest"] - cy[0]["t_arrest"]))


# ----------------------------------------------------------------------------------------------
# cases
# ----------------------------------------------------------------------------------------------
N_WARM = 3


def _run(P, sched, n_cyc):
    Tn = P["Tn"]
    v0 = P["v0"]
    typ = sched["type"]
    if typ == "mod":
        drive = _Drive(v0, mod=(sched["a"], 2 * math.pi * sched["fm"], sched["phi"]))
    else:
        drive = _Drive(v0)
    ctl = None
    if typ == "steps":
        bounds = {}
        nsl, j = N_WARM - 1, 0
        while nsl < N_WARM + n_cyc + 2:
            cnt = sched["counts"][j % len(sched["counts"])]
            nsl += cnt
            j += 1
            bounds[nsl] = v0 * sched["levels"][j % len(sched["levels"])]

        def ctl(n, t, drv):
            if n in bounds:
                drv.ramp_to(max(t + 0.02 * Tn, drv.tb[-1]), bounds[n], 0.1 * Tn)
    elif typ == "holds":
        holds = dict(zip(sched["at"], sched["durs"]))

        def ctl(n, t, drv):
            if n in holds:
                drv.hold(max(t + sched["delay"], drv.tb[-1]), holds[n], 0.1 * Tn)
    gt = _simulate(P, drive, N_WARM + n_cyc, ctl=ctl, t_max=4000 * Tn)
    gt["drive"] = drive
    return gt


def _window(gt, P, frac):
    ar = gt["arrests"]
    t = gt["t"]
    if len(ar) <= N_WARM + 2:
        return t[0], t[-1]
    per = (t[ar[-1]] - t[ar[N_WARM - 1]]) / (len(ar) - N_WARM)
    t0 = t[ar[N_WARM - 1]] + frac * per
    return float(t0), float(t[-1])


def _stats(gt, P, t0):
    cy = _cycles(gt, P, t_lo=t0)
    tw = [c["twin"] for c in cy if c["twin"] is not None]
    return cy, (float(np.mean(tw)) if tw else None)


def _setup_and_run(case, seed, coarse):
    P, r = _draw_physics(case, seed)
    Tn = P["Tn"]
    sched = {"type": "const"}
    frac = float(r.uniform(0.05, 0.7))
    tst_est = 2 * (P["Fs"] - P["Fc"]) / P["k"] / P["v0"]
    calib = []
    meas = {}
    if case == "none":
        n_cyc = int(r.integers(20, 41))
        if seed % 8 in (3, 6):
            f1, f2 = r.uniform(1.4, 1.8), r.uniform(0.55, 0.75)
            sched = {"type": "steps", "levels": [1.0, f1, f2], "counts": [int(x) for x in r.integers(4, 7, 3)]}
        gt = _run(P, sched, n_cyc)
    elif case == "load_variation":
        # a dished (spherical) disc face under the swinging pin: the pin's height on its arc, hence the
        # load of its stiff loading flexure, is linear + quadratic in the arm angle (the spring extension)
        n_cyc = int(r.integers(18, 37))
        rising = seed % 4 != 1
        Fr = P["Fs"] / (P["Fs"] - P["Fc"])
        pp_t = float(r.uniform(0.13, 0.34) if rising else r.uniform(0.12, 0.22))
        sgn = 1.0 if rising else -1.0
        c2rel = float(r.uniform(-0.4, 0.4))
        halfx = (P["Fs"] - P["Fc"]) / P["k"]
        P["xm"] = P["Fc"] / P["k"]
        cmax = 0.55 / Fr if rising else 0.4  # a rising load past ~1/Fr locks the stick (a wedge)
        lo, hi = 0.0, cmax
        a = min(pp_t / 2, 0.7 * cmax)
        best = None
        for it in range(8):
            c1 = sgn * a
            P["L1"] = c1 / halfx
            P["L2"] = c2rel * c1 / halfx ** 2
            gt = _run(P, sched, n_cyc)
            t0, t1 = _window(gt, P, frac)
            w = gt["t"] >= t0
            pp = float(gt["lam"][w].max() - gt["lam"][w].min())
            nsl = len(_cycles(gt, P, t_lo=t0))
            calib.append(dict(c1=c1, c2=c2rel * c1, pp=pp, slips=nsl))
            if nsl < 12:
                hi = a
                a = 0.5 * (lo + hi)
                continue
            if best is None or abs(pp / pp_t - 1) < abs(best[1] / pp_t - 1):
                best = (gt, pp, c1)
            if abs(pp / pp_t - 1) < 0.06:
                break
            if pp < pp_t:
                lo = a
            else:
                hi = a
            a_new = a * (pp_t / max(pp, 1e-4)) ** 0.7
            a = a_new if lo < a_new < hi else 0.5 * (lo + hi)
        gt, pp, c1 = best
        P["L1"] = c1 / halfx
        P["L2"] = c2rel * c1 / halfx ** 2
        P["c1"], P["c2"], P["pp_target"] = c1, c2rel * c1, pp_t
    elif case == "twin_branch":
        n_cyc = int(r.integers(18, 37))
        tw_t = float(r.uniform(0.12, 0.22))
        E_est = P["Fc"] * 2 * (P["Fs"] - P["Fc"]) / P["k"]
        P["W_film"] = E_est / float(r.uniform(0.8, 2.0))
        P["kappa_film"] = 1.0 / (float(r.uniform(0.3, 0.7)) * tst_est)
        gam = tw_t * 2 * (P["Fs"] - P["Fc"]) / (0.4 * P["Fc"])
        best = None
        for it in range(6):
            P["gamma_tw"] = gam
            gt = _run(P, sched, n_cyc)
            t0, _ = _window(gt, P, frac)
            cy, tw = _stats(gt, P, t0)
            calib.append(dict(gamma=gam, twin=tw, slips=len(cy)))
            if tw is not None and len(cy) >= 12 and (best is None or abs(tw / tw_t - 1) < abs(best[1] / tw_t - 1)):
                best = (gt, tw, gam)
            if tw is not None and abs(tw / tw_t - 1) < 0.08:
                break
            gam *= (tw_t / tw) if (tw is not None and tw > 0.01) else 2.0
        gt, tw, gam = best
        P["gamma_tw"] = gam
        P["twin_target"] = tw_t
    elif case == "static_ageing":
        g_t = float(r.uniform(0.08, 0.16))
        P["tau_age"] = float(r.uniform(0.05, 0.3)) * Tn
        P["D_age"] = float(r.uniform(0.02, 0.06)) * max(P["zstar"])
        if seed % 2 == 0:
            n_cyc = int(r.integers(20, 31))
            ratio = float(r.uniform(4.5, 7.5))
            P["v0"] *= float(r.uniform(0.6, 1.0))
            sched = {"type": "steps", "levels": [1.0, 1.0 / ratio],
                     "counts": [int(r.integers(4, 7)), int(r.integers(2, 4))], "ratio": ratio}
        else:
            n_cyc = int(r.integers(18, 29))
            tst_est = 2 * (P["Fs"] - P["Fc"]) / P["k"] / P["v0"]
            at, durs = [], []
            nn = N_WARM + int(r.integers(1, 3))
            while nn < N_WARM + n_cyc:
                at.append(nn)
                durs.append(_lu(r, 1.5, 12.0) * tst_est)
                nn += int(r.integers(2, 4))
            sched = {"type": "holds", "at": at, "durs": durs, "delay": float(r.uniform(0.15, 0.5)) * tst_est}
        # calibrated on the growth beyond the law's own (beta = 0) peak-vs-stick-time trend, the total
        # (what the record shows) kept at >= 0.06 of the drop
        # (the calibration runs are short, 12 cycles; the record's run is checked and corrected once)
        xs, gs = [], []
        beta = 0.0
        best = None
        n_cal = min(n_cyc, 12)
        for it in range(7):
            P["beta_age"] = beta
            gt = _run(P, sched, n_cal)
            t0, _ = _window(gt, P, frac)
            cy = _cycles(gt, P, t_lo=t0)
            g, rr = _peak_growth(cy)
            calib.append(dict(beta=beta, growth=g, stick_ratio=rr))
            if len(xs) == 0:
                g0 = g
                meas["law_peak_growth_beta0"] = g0
                g_t = float(min(max(g0 + g_t, 0.06), 0.19))  # total target: excess g_t over the law, total >= 0.06
                xs.append(beta)
                gs.append(g)
                beta = 0.03
                continue
            xs.append(beta)
            gs.append(g)
            if best is None or abs(g / g_t - 1) < abs(best[1] / g_t - 1):
                best = (gt, g, beta)
            if abs(g / g_t - 1) < 0.07:
                break
            else:
                sl = (gs[-1] - gs[-2]) / (xs[-1] - xs[-2]) if xs[-1] != xs[-2] else 0.0
                beta = (xs[-1] + (g_t - gs[-1]) / sl) if sl > 1e-6 else xs[-1] * 2
                beta = float(min(max(beta, 0.3 * xs[-1]), 3 * xs[-1], 0.12))
        gt, g, beta = best
        for it in range(3):
            P["beta_age"] = beta
            gt = _run(P, sched, n_cyc)
            t0, _ = _window(gt, P, frac)
            g, rr = _peak_growth(_cycles(gt, P, t_lo=t0))
            calib.append(dict(beta=beta, growth=g, stick_ratio=rr, full=True))
            if abs(g / g_t - 1) < 0.15 or it == 2:
                break
            sl = (g - meas["law_peak_growth_beta0"]) / beta
            beta = float(min(max(beta + (g_t - g) / sl, 0.5 * beta), 2 * beta, 0.12)) if sl > 1e-6 else beta
        P["beta_age"] = beta
        P["growth_target"] = g_t
    elif case == "triggering":
        # a voice-coil shaker on the loading arm. The breakaways lock to the shaker's troughs when a
        # stick lasts many shaker periods, so the drive is set for 2.5-6 shaker periods per stick and
        # f_t is redrawn (up to 8 runs) while the record's f_t / f_ss is within 0.15 of an integer.
        n_cyc = int(r.integers(18, 37))
        P["eps_t"] = float(r.uniform(0.03, 0.06))
        P["psi_t"] = float(r.uniform(0, 2 * math.pi))
        hi = 4.4 if coarse else 6.5
        fn_t = _fn_true(P)
        v_nom = P["v0"]
        best = None
        for it in range(8):
            ft = float(r.uniform(2.6, hi)) * fn_t
            nper = float(r.uniform(2.5, 6.0))
            P["v0"] = 2 * (P["Fs"] - P["Fc"]) / P["k"] / (nper / ft)
            P["w_t"] = 2 * math.pi * ft
            gt = _run(P, sched, n_cyc)
            t0, _ = _window(gt, P, frac)
            cy = _cycles(gt, P, t_lo=t0)
            fss = _fss(cy)
            ratio = ft / fss
            dist = abs(ratio - round(ratio))
            calib.append(dict(ft=ft, v0=P["v0"], fss=fss, ratio=ratio, dist=dist, slips=len(cy)))
            if len(cy) >= 12 and (best is None or dist > best[1]):
                best = (gt, dist, ft, P["v0"])
            if dist >= 0.2 and len(cy) >= 12:
                break
        gt, dist, ft, v0b = best
        P["v0"] = v0b
        P["v0_nominal_draw"] = v_nom
        P["w_t"] = 2 * math.pi * ft
        P["f_t"] = ft
    elif case == "drive_modulation":
        n_cyc = int(r.integers(24, 41))
        gt0 = _run(P, sched, 5)
        cy0 = _cycles(gt0, P)
        fss0 = _fss(cy0[N_WARM - 1:]) or _fss(cy0)
        a = float(r.uniform(0.22, 0.43))
        rt = float(r.uniform(0.14, 0.42))
        sched = {"type": "mod", "a": a, "fm": rt * fss0, "phi": float(r.uniform(0, 2 * math.pi))}
        for it in range(3):
            gt = _run(P, sched, n_cyc)
            t0, _ = _window(gt, P, frac)
            fss = _fss(_cycles(gt, P, t_lo=t0))
            calib.append(dict(fm=sched["fm"], fss=fss, ratio=sched["fm"] / fss))
            if 0.11 <= sched["fm"] / fss <= 0.46:
                break
            sched["fm"] = rt * fss
    else:
        raise ValueError(case)
    return P, r, sched, gt, frac, calib, meas


# ----------------------------------------------------------------------------------------------
# sensor, nuisances, file
# ----------------------------------------------------------------------------------------------
_OMIT_FN = {"none": 2, "load_variation": 5, "twin_branch": 0, "static_ageing": 3, "triggering": None,
            "drive_modulation": 1}


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.ndarray):
        return [_jsonable(v) for v in o.tolist()]
    if isinstance(o, float) and not math.isfinite(o):
        return None
    return o


def _sensor(gt, P, fn, fs, t_rec, rs, triggering):
    """force at the torsion bar through a 2nd-order transducer and a one-pole anti-alias filter,
    evaluated on a fine grid and sampled at the record's times; the normal load through the
    anti-alias filter only"""
    Tn = 1.0 / fn
    dt_rec = 1.0 / fs
    M = max(1, int(math.ceil(dt_rec / (Tn / 400.0))))
    dtf = dt_rec / M
    pad = 2.0 * Tn
    npad = int(math.ceil(pad / dtf))
    tf = t_rec[0] - npad * dtf + dtf * np.arange(npad + (len(t_rec) - 1) * M + 1)
    tf = np.clip(tf, gt["t"][0], gt["t"][-1])
    dF = (P["k"] + P["k2"]) * gt["u"] - gt["q"] / P["tau2"]
    Ff = CubicHermiteSpline(gt["t"], gt["Fsp"], dF)(tf)
    Nf = P["N0"] * np.interp(tf, gt["t"], gt["lam"])
    f_tr = float(rs.uniform(10.0, 30.0)) * fn
    z_tr = float(rs.uniform(0.05, 0.3))
    w = 2 * math.pi * f_tr
    bz, az, _ = signal.cont2discrete(([w * w], [1.0, 2 * z_tr * w, w * w]), dtf, method="zoh")
    bz = np.atleast_1d(np.squeeze(bz))
    zi = signal.lfilter_zi(bz, az) * Ff[0]
    Ft, _ = signal.lfilter(bz, az, Ff, zi=zi)
    f_aa = float(rs.uniform(0.33, 0.42) if triggering else rs.uniform(0.15, 0.3)) * fs
    a1 = math.exp(-2 * math.pi * f_aa * dtf)
    b_aa, a_aa = [1.0 - a1], [1.0, -a1]
    Fa, _ = signal.lfilter(b_aa, a_aa, Ft, zi=[a1 * Ft[0]])
    Na, _ = signal.lfilter(b_aa, a_aa, Nf, zi=[a1 * Nf[0]])
    idx = npad + M * np.arange(len(t_rec))
    return Fa[idx], Na[idx], dict(f_transducer_over_fn=f_tr / fn, zeta_transducer=z_tr,
                                  f_antialias_over_fs=f_aa / fs, fine_steps_per_sample=M)


def _ar1(rs, n, rho, sd):
    e = rs.normal(0.0, 1.0, n)
    x = signal.lfilter([1.0], [1.0, -rho], e) * math.sqrt(1 - rho * rho)
    return sd * x


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    seed = int(seed)
    ci = CASES.index(case)
    coarse = nuisance == "coarse"
    P, r, sched, gt, frac, calib, meas = _setup_and_run(case, seed, coarse)
    rf = _rng(NAME, "format", case, seed)  # record format: the same for every nuisance
    rs = _rng(NAME, "sensor", case, seed, nuisance)
    rn = _rng(NAME, "nuisance", case, seed, nuisance)
    fn = _fn_true(P)
    Tn_true = 1.0 / fn

    # ---- measurements on the noise-free truth ----
    t0, t1 = _window(gt, P, frac)
    cy = _cycles(gt, P, t_lo=t0)
    drops = np.array([c["drop"] for c in cy])
    drop = float(np.median(drops))
    tw = [c["twin"] for c in cy if c["twin"] is not None]
    meas.update(dict(
        cycles=len(cy), f_ss=_fss(cy), f_ss_over_fn=_fss(cy) / fn,
        drop_N=drop, drop_over_Fs=drop / P["Fs"],
        twin_law=float(np.mean(tw)) if tw else None,
        twin_law_range=[float(min(tw)), float(max(tw))] if tw else None,
        twin_1dof_reading=_twin_1dof(gt, P, cy),
        creep_in_stick_over_drive=float(np.median([c["creep"] for c in cy])),
        slip_peak_speed_over_v0=float(np.mean([c["vp"] for c in cy]) / P["v0"]),
        stick_time_over_Tn=[float(min(c["t_stick"] for c in cy) / Tn_true),
                            float(max(c["t_stick"] for c in cy) / Tn_true)],
        peak_sd_over_drop=float(np.std([c["peak"] for c in cy]) / drop),
    ))
    g, rr = _peak_growth(cy)
    meas["peak_growth_over_drop"] = g
    meas["stick_time_ratio"] = rr
    w = gt["t"] >= t0
    meas["load_pp_over_N0"] = float(gt["lam"][w].max() - gt["lam"][w].min())
    if case == "load_variation":
        # the law per unit load (friction / load against speed)
        gtl = dict(gt)
        gtl["Ff"] = gt["Ff"] / gt["lam"]
        twl = [c["twin"] for c in _cycles(gtl, P, t_lo=t0) if c["twin"] is not None]
        meas["twin_per_unit_load"] = float(np.mean(twl)) if twl else None
    if case == "static_ageing":
        meas["ageing_growth_beyond_law"] = g - meas.get("law_peak_growth_beta0", 0.0)
    if case == "triggering":
        ft = P["f_t"]
        meas["ft_over_fn"] = ft / fn
        meas["ft_over_fss"] = ft / meas["f_ss"]
        meas["ft_over_fss_dist_to_integer"] = abs(meas["ft_over_fss"] - round(meas["ft_over_fss"]))
        meas["load_amplitude_over_N0"] = P["eps_t"]
    if case == "drive_modulation":
        meas["fm_over_fss"] = sched["fm"] / meas["f_ss"]
        meas["a"] = sched["a"]
        meas["fm_over_fn"] = sched["fm"] / fn

    # ---- sampling ----
    if coarse:
        spp = float(rs.uniform(10.0, 15.0))
    else:
        lo = 20.0
        if case == "triggering":
            lo = max(20.0, 4.5 * P["f_t"] / fn)
        spp = _lu(rs, lo, max(100.0, lo * 1.2))
    lo_, hi_ = (10.0, 15.0) if coarse else (20.0, 100.0)
    q_ = 1.0 if spp * fn > 50 else 0.1  # a round sampling rate (1 Hz, or 0.1 Hz below 50 Hz)
    fs = round(spp * fn / q_) * q_
    while fs / fn < lo_:
        fs += q_
    while fs / fn > hi_ and fs - q_ >= lo_ * fn:
        fs -= q_
    fs = float(round(fs, 1))
    spp = fs / fn
    n = int((t1 - t0) * fs)
    t_rec = t0 + np.arange(n) / fs
    Fm, Nm, sens = _sensor(gt, P, fn, fs, t_rec, rs, case == "triggering")
    # noise: AR(1) coloured on the force, white-ish on the normal load
    Fm = Fm + _ar1(rs, n, float(rs.uniform(0.3, 0.9)), drop * float(rs.uniform(0.002, 0.008)))
    Nm = Nm + _ar1(rs, n, float(rs.uniform(0.0, 0.5)), P["N0"] * float(rs.uniform(0.001, 0.004)))
    tr = t_rec - t_rec[0]
    nz = {}
    if nuisance == "hum":
        fh = 50.0 if rn.uniform() < 0.5 else 60.0
        A = drop * float(rn.uniform(0.01, 0.05))
        a2, a3 = float(rn.uniform(0.1, 0.5)), float(rn.uniform(0.1, 0.4))
        ph = rn.uniform(0, 2 * math.pi, 3)
        Fm = Fm + A * (np.sin(2 * math.pi * fh * tr + ph[0]) + a2 * np.sin(4 * math.pi * fh * tr + ph[1])
                       + a3 * np.sin(6 * math.pi * fh * tr + ph[2]))
        Nm = Nm + 0.3 * A * np.sin(2 * math.pi * fh * tr + ph[0] + 0.5)
        nz = dict(f_hum=fh, amp_over_drop=A / drop, h2=a2, h3=a3)
    elif nuisance == "drift":
        D = drop * float(rn.uniform(0.02, 0.06)) * (1 if rn.uniform() < 0.5 else -1)
        al = float(rn.uniform(0.3, 1.0))
        tau = tr / tr[-1]
        Fm = Fm + D * (al * tau + (1 - al) * tau * tau)
        nz = dict(drift_over_drop=D / drop, linear_fraction=al)
    elif nuisance == "spikes":
        pfr = float(rn.uniform(0.0005, 0.005))
        k_ = max(3, int(round(pfr * n)))
        cand = rn.choice(np.arange(2, n - 2, 3), size=min(k_, (n - 4) // 3), replace=False)
        amp = drop * rn.uniform(0.3, 1.2, len(cand)) * rn.choice([-1.0, 1.0], len(cand))
        Fm[cand] += amp
        nz = dict(fraction=len(cand) / n, n_spikes=len(cand))
    elif nuisance == "quantisation":
        qs = drop * float(rn.uniform(0.002, 0.01))
        Fm = np.round(Fm / qs) * qs
        nz = dict(step_over_drop=qs / drop)

    # ---- channels and format ----
    kind = "force" if (seed + ci) % 2 == 0 else "displacement"
    has_N = case in ("load_variation", "triggering") or (case == "none" and seed % 8 == 1) or \
        (case == "twin_branch" and seed % 8 == 4)
    has_drive = case == "static_ageing" or sched["type"] == "steps"
    sep_name = ["comma", "semicolon", "tab", "whitespace"][int(rf.integers(0, 4))]
    sep = {"comma": ",", "semicolon": ";", "tab": "\t", "whitespace": "  "}[sep_name]
    sp = "" if sep_name == "whitespace" else " "
    cols, names, fmts = [tr], ["time%s[s]" % sp], ["%.9g"]
    drive_t = gt["drive"]
    if kind == "force":
        fu = "mN" if (drop < 0.3 or rf.uniform() < 0.4) else "N"
        fsc = 1000.0 if fu == "mN" else 1.0
        cols.append(Fm * fsc)
        names.append("%s%s[%s]" % (["friction", "force", "F"][int(rf.integers(0, 3))], sp, fu))
        fmts.append("%.6g")
        if has_N:
            nu = fu if rf.uniform() < 0.7 else ("N" if fu == "mN" else "mN")
            cols.append(Nm * (1000.0 if nu == "mN" else 1.0))
            names.append("%s%s[%s]" % (["normal", "N", "load"][int(rf.integers(0, 3))], sp, nu))
            fmts.append("%.6g")
        if has_drive:
            if rf.uniform() < 0.6:
                pu = "um" if rf.uniform() < 0.5 else "mm"
                Xd = drive_t.X_arr(t_rec)
                Xd = Xd - Xd[0] + float(rf.uniform(0, 0.02))
                res_ = 1e-7 if pu == "um" else 1e-6  # encoder: 0.1 um or 1 um
                Xq = np.round(Xd / res_) * res_
                cols.append(Xq * (1e6 if pu == "um" else 1e3))
                names.append("position%s[%s]" % (sp, pu))
                fmts.append("%.9g")
            else:
                cols.append(drive_t.vd_arr(t_rec) * 1e3)
                names.append("v0%s[mm/s]" % sp)
                fmts.append("%.6g")
    else:
        cols.append(Fm / P["k"] * 1e3)
        names.append("x%s[mm]" % sp)
        fmts.append("%.6g")
        if has_N:
            b = float(rf.uniform(0.02, 0.3))  # mm per N: the loading flexure's deflection gauge
            y0 = float(rf.uniform(0.1, 2.0))
            cols.append(y0 + b * Nm)
            names.append("y%s[mm]" % sp)
            fmts.append("%.6g")
        if has_drive:
            cols.append(drive_t.vd_arr(t_rec) * 1e3)
            names.append("v0%s[mm/s]" % sp)
            fmts.append("%.6g")
    os.makedirs(outdir, exist_ok=True)
    ext = "csv" if sep_name in ("comma", "semicolon") else "txt"
    path = os.path.abspath(os.path.join(outdir, "%s_%s_s%d_%s.%s" % (NAME, case, seed, nuisance, ext)))
    data = np.column_stack(cols)
    np.savetxt(path, data, fmt=fmts, delimiter=sep, header=sep.join(names), comments="")

    # ---- options a user would pass ----
    args = []
    omit = _OMIT_FN[case]
    pass_fn = not (omit is not None and seed % 8 == omit and nuisance != "fn_off")
    fn_given = None
    if pass_fn:
        if nuisance == "fn_off":
            fn_given = fn * (1.05 if rn.uniform() < 0.5 else 0.95)
        else:
            fn_given = fn
        fn_given = float("%.4g" % fn_given)
        args += ["--fn", "%.4g" % fn_given]
    if not has_drive:
        v0n = P["v0"]
        args += ["--v0", "%.4g" % (v0n * 1e3)]
    if kind == "force":
        args += ["--stiffness", "%.5g" % P["k"]]

    meas["samples_per_period"] = spp
    meas["n_samples"] = n
    params = dict(P)
    params.pop("d_el", None)
    params.update(dict(case_schedule=sched, record_kind=kind, separator=sep_name, columns=names, fs=fs,
                       sensor=sens, nuisance_params=nz, calibration=calib, measured=meas,
                       window=[t0, t1], fn_static=P["fn0"], C_attraction=P["C"]))
    return dict(generator=NAME, case=case, seed=seed, nuisance=nuisance, file=path, args=args,
                fn_true=fn, fn_given=fn_given, params=_jsonable(params))
