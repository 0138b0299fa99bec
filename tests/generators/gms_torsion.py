"""gms_torsion: DOCSTRING PLACEHOLDER (filled in after measurement)."""

import math
import os
import zlib
from bisect import bisect_right

import numpy as np
from scipy import signal
from scipy.interpolate import CubicHermiteSpline

NAME = "gms_torsion"
_DBG = []
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
    h_quiet = Tn / (160.0 if eps > 0 else 80.0)
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
    xm_ = x
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
        for _ in range(14):
            v1 = vd1 - u1
            vm = 0.5 * (v0s + v1)
            x1 = x + hh * (u + u1)
            q1 = q * E2 + k2 * (x1 - x) * G2
            dx = x1 - xm
            lam1 = 1.0 + L1 * dx + L2 * dx * dx + (eps * math.sin(wt * td + pt) if eps else 0.0)
            dlam1 = (L1 + 2.0 * L2 * dx) * hh
            lamm = 0.5 * (lam_now + lam1)
            avm = vm if vm >= 0.0 else -vm
            sg = 1.0 if vm >= 0.0 else -1.0
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
        for i in range(n):
            if stk[i]:
                ag = alp[i] * gage[i]
                e1 = abs(Fn[i]) - ag * s1
                if e1 > 0.0:
                    e0 = abs(F[i]) - ag * s0
                    if e1 <= e0:  # at or past the limit but moving inward: no switch
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
        for i in range(n):
            if stk[i]:
                ag = alp[i] * gage[i]
                e1 = abs(F[i]) - ag * sl
                if e1 >= -1e-12 * ag * sl and e1 > abs(Fold[i]) - ag * s_old:
                    stk[i] = False
                    switched = True
        if v1 > thr_slip:
            in_slip = True
        Ffe = force_now(v1) if switched else Ff
        if _DBG and _DBG[0] <= t / Tn <= _DBG[1]:
            print(f"t={t/Tn:.5f} h={hstep/Tn:.2e} v={v1/vref:+.4f} th={th:.3f} stk={''.join('S' if b else '-' for b in stk)} F={[round(f/Fs,3) for f in F]} lim={round(sl/Fs,3)} Ff={Ffe/Fs:.3f}")
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
    vs = r.uniform(0.15, 0.5) * Vst
    delta = r.uniform(1.3, 2.0)
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
