"""Independent stick-slip record generator: a Hertzian sphere on a flat with Cattaneo-Mindlin partial slip.

Written without reading the diagnosis code; contact model, rig, integrator, sensor, noise and file writers are
this file's own.

Rig: a **dead-weight lever tribometer**. A weight on the lever's long arm presses a steel sphere onto a flat on a
linear stage (the drive, speed v_d(t)), N0 2-30 N. The sphere's holder hangs from the lever on a **cantilever
leaf** bending along the drive: the measuring spring (stiffness k, its own damping c = 2 zeta m omega_n, zeta
0.005-0.03); holder plus trim mass is the slider (m, fn = sqrt(k/m)/2pi, 3-146 Hz over seeds 0-23). The leaf's
deflection x is read by a strain gauge at its root (the force k x, N/mN, `--stiffness`) or by an eddy-current
probe at its tip (x in mm/um, with an affine load-ring reading y of the normal load, mm). Sliding speed w = v_d - x'.

Contact:
  * **Stick = Cattaneo-Mindlin partial slip with Masing hysteresis**, restarted at every arrest from the arrest
    state: the traction is then the sliding traction Q0 (a uniform fraction Q0/N of the pressure), so loading on
    is a Cattaneo problem with the capacity left to that side, P+ = mu_s N - Q0 or P- = mu_s N + Q0:
        Q = Q0 +- P (1 - (1 - D/ds)^(3/2)),   ds = 3 P / (2 kt),   kt = kt0 (N/N0)^(1/3)
    (kt0 = 8 G* a, the contact's compliance 1/kt0 = 2-5 % of the leaf's 1/k). Each zero of w starts a Masing
    branch of capacity 2 mu_s N from the reversal point; loops close by the extended Masing rules (a branch
    passing the previous reversal point rejoins the older branch; the first one rejoins the virgin branch where
    their stick radii agree, delta = -D1 P_now/P_prev), so the reversal stack stays short. A contact damping
    proportional to the tangent stiffness (ct (dQ/dD)/kt w, ct = 2 zeta_t sqrt((k + kt0) m), zeta_t 0.08-0.2)
    acts in stick only and vanishes at gross slip. Gross slip when the annulus reaches the centre (D = ds on the
    virgin branch, Q = mu_s N), in the direction of Q. The slider creeps towards v_d as the annulus grows before
    each breakaway, and the contact mode (4.6-7.2 fn) rings after each arrest: 0.35-2.5 % of the drop p-p in the
    leaf force (seeds 0-23).
  * **Slip = a Pade [1/2] rational law** (not a Stribeck exponential, not a power law, not a Lorentzian):
        mu_k(u) = mu_inf + (mu_1 - mu_inf) (1 + b q) / (1 + b q + q^2) + eta u,   q = u / v_c,
    b 0.2-1.5 (a shoulder and a slow 1/q tail), mu_1 = mu_k(0+) 4-12 % below mu_s, a weakening of 12-30 % of mu_s,
    v_c 0.15-0.6 of the slip-speed scale, a weak viscous strengthening; single-valued.
  * Re-sticking: when w reaches 0 in slip (the step retaken to the crossing, w set to 0), Mindlin restarts from
    the arrest state; if the force is then beyond the static limit the virgin branch breaks away at once.

Integrator: own adaptive **Runge-Kutta-Fehlberg 4(5)** (local extrapolation, scaled tolerance 1e-6 per
component, steps capped at Tn/10, 1/12 of a shaker period and 1/14 of the rider's period, drive knots never
stepped over, the end derivative reused as the next first stage); every switch (a Masing reversal, the
breakaway, the arrest) is located by a scan and bisection on the step's cubic Hermite interpolant and the step
retaken exactly to it; reversals of |w| < 1e-3 v0 are left to the branch's elastic tangent. Cubic Hermite dense
output on a grid 4x finer than the record. 0.15-3.2 s a record (median ~0.5 s).

Sensor: 2-pole Butterworth anti-alias at 0.3-0.4 fs, then sampled; every record has **band-limited pink (1/f)
noise** (rms 0.15-0.5 % of the drop, ~1/record .. 0.45 fs, rolled off outside) and a **slow temperature drift of
the gauge's gain** (warm-up exponential plus an air-conditioning cycle, 0.2-0.5 % of the reading over the
record, either sign); the normal channel has its own.

Departures (sizes tuned on short pilots, then measured on the final ground truth; seeds 0-7, [0-23]):
  * load_variation: the dead weight is a **rider on the lever's long arm, pulled along it by a cord from the
    holder over a pulley**: its arm follows the slider's deflection x through the compliant cord, x_f with its
    own mode (1.5-4 fn, zeta 0.06-0.15), N = N0 (1 + c (x_f - x_m)); rising, or falling on seeds 1 mod 4 (a
    falling one that does not settle within the record is replaced by a rising one). N p-p 10.9-23.8 % of N0
    [10.9-31.6 %]; the friction force's own twin then reads -32..+17 % of the drop [-40..+32 %]. The normal
    channel is recorded (N, or the affine load-ring reading y).
  * twin_branch: **lagged Tabor junction growth**: the real area grows by a fraction j g under the shear of
    sliding, g relaxing toward w/(w + v_g) (v_g 0.2-0.5 of the slip-speed scale) with a viscoplastic time tau_j
    0.1-0.25 Tn, back to 0 in stick; sliding friction and static level scale with the area (the static excess
    above the arrest traction is kept). Law's twin (decelerating minus accelerating at equal speed, 10-90 % of
    each slip's peak speed, median over slips): +15.2..+21.5 % of the drop [+13.4..+21.5 %]; a 1-DoF reading of
    the clean anti-aliased samples (central differences) +13.5..+21.3 %.
  * static_ageing: **creep of the Hertz contact** (a Norton-type power-law growth of the real area): mu_s(t_st) =
    mu_s0 (1 + t_st/tau_a)^p, tau_a 0.3-1 stick time, kt0 growing with its square root, erased by the next slip;
    the stage steps 4-8x between two recorded levels (even seeds) or holds 1-6.5 stick times (odd seeds). Peak of
    the leaf force (the observable maximum of each cycle) against ln(stick time), over the record's range:
    +8.5..+17.5 % of the drop over sticks 5.1-9.7x apart [same].
  * triggering: a voice-coil shaker on the lever, N = N0 (1 + A sin(2 pi f_t t)), A 3.5-6.7 % [3.3-6.9 %], f_t
    2.6-7.3 fn [2.6-7.7], the static excess drawn >= 1.4 A (so the shaker triggers slips late in the stick
    rather than breaking every arrest); f_t re-drawn (up to 7 draws) while the record's f_t/f_ss is within 0.15
    of an integer: f_t/f_ss 11.4-40.5 [11.4-59.2], 0.17-0.48 [0.16-0.48] from an integer; drop cv 0.02-0.31.
  * drive_modulation: the stage speed v_d = v0 (1 + a sin(2 pi fm t + phi)), a 0.23-0.44, fm/f_ss 0.23-0.45
    [0.13-0.45] (f_ss measured on the record); only v0 is given (`--v0`).
  * none: constant load and drive; on seeds 2 and 5 mod 8 a stage stepping 4-8x between two recorded levels.
    The law's own twin is 0 (|twin| < 0.004 % of the drop); a 1-DoF reading of the clean samples by central
    differences reads -1.8..-0.06 % at >= 40 samples per period and -3.8..-3.2 % at 30-32 (the static-kinetic
    kink smeared by the differencing), none at the coarse 12-15. Peak scatter 0.003-0.005 % of the drop (sd) with
    a constant drive (the record noise dominates), 0.4-1.6 % with the stepped one, where the peak falls
    -1.9..-0.6 % of the drop across sticks 3.9-8.7x apart (the slider's inertia at the end of the presliding:
    a faster stage reaches the breakaway with more momentum); no ageing in the law.

Records: a third MATLAB .mat (`scipy.io.savemat`, lab vectors `time`/`t`, `Ff`/`friction_force`,
`Fn`/`normal_force`, `stage_pos`/`position`, `v_drive`/`speed`, or `x`/`deflection` with `y`/`load_ring`, in s,
N, mm, mm/s; scalars `fs`, `operator`, `rig`, `date`), a third .xlsx written here with `zipfile` (one sheet,
inline-string header `Time [s]`, ... or a names row plus a units row, numeric cells), a third text (TAB with a
`key = value` instrument header and `Name [unit]`, or comma CSV `Name (unit)`; s/ms, N/mN, mm/um). Force records
(friction, normal on load/half of triggering/a third of the rest, stage-encoder position or a stage-speed column
or `--v0`, `--stiffness`) or displacement records (x = F/k, the load-ring y, a stage-speed column on stepped/hold
drives or `--v0`). 20-100 samples per natural period (coarse 10-15), 17-47 slips. `--fn` on 7 of 8 seeds (8 of
8 for triggering and for `fn_off`). Byte-deterministic in (case, seed, nuisance).
"""
from __future__ import annotations

import bisect
import io
import math
import os
import zipfile

import numpy as np
import scipy.io
import scipy.signal

NAME = "mindlin_pendulum"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

STICK, SLIP = 0, 1
_TAG = 0x4D494E44  # "MIND"


# ----------------------------------------------------------------------------------------------------------
# drives
# ----------------------------------------------------------------------------------------------------------
class PWLDrive:
    """Stage speed piecewise linear through knots (t_i, v_i), constant after the last; position exact."""

    def __init__(self, tk, vk):
        self.tk = [float(a) for a in tk]
        self.vk = [float(a) for a in vk]
        n = len(self.tk)
        self.sl = [(self.vk[i + 1] - self.vk[i]) / (self.tk[i + 1] - self.tk[i]) for i in range(n - 1)] + [0.0]
        p = [0.0]
        for i in range(n - 1):
            p.append(p[-1] + 0.5 * (self.vk[i] + self.vk[i + 1]) * (self.tk[i + 1] - self.tk[i]))
        self.pk = p
        self.breaks = self.tk[1:]
        self._i = 0

    def pv(self, t):
        tk = self.tk
        i = self._i
        if t < tk[i] or (i + 1 < len(tk) and t >= tk[i + 1]):
            i = max(0, bisect.bisect_right(tk, t) - 1)
            self._i = i
        tau = t - tk[i]
        s = self.sl[i]
        return self.pk[i] + (self.vk[i] + 0.5 * s * tau) * tau, self.vk[i] + s * tau

    def acc(self, t):
        i = max(0, bisect.bisect_right(self.tk, t) - 1)
        return self.sl[i]

    def arrays(self, t):
        t = np.asarray(t, float)
        tk = np.asarray(self.tk)
        i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 1)
        tau = t - tk[i]
        s = np.asarray(self.sl)[i]
        v = np.asarray(self.vk)[i] + s * tau
        p = np.asarray(self.pk)[i] + (np.asarray(self.vk)[i] + 0.5 * s * tau) * tau
        return p, v


class ModDrive:
    """v_d = v0 (1 + a sin(wm t + phi)) from t = 0 (the stage starts at that speed)."""

    def __init__(self, v0, a, fm, phi):
        self.v0, self.a, self.wm, self.phi = v0, a, 2 * math.pi * fm, phi
        self.breaks = []
        self.c0 = math.cos(phi)

    def pv(self, t):
        ph = self.wm * t + self.phi
        return (self.v0 * (t - self.a / self.wm * (math.cos(ph) - self.c0)),
                self.v0 * (1.0 + self.a * math.sin(ph)))

    def acc(self, t):
        return self.v0 * self.a * self.wm * math.cos(self.wm * t + self.phi)

    def arrays(self, t):
        ph = self.wm * np.asarray(t, float) + self.phi
        return (self.v0 * (t - self.a / self.wm * (np.cos(ph) - self.c0)),
                self.v0 * (1.0 + self.a * np.sin(ph)))


# ----------------------------------------------------------------------------------------------------------
# the rig's equations and the integrator
# ----------------------------------------------------------------------------------------------------------
class Rig:
    """Plain parameter holder (SI units)."""

    def __init__(self, **kw):
        self.j = 0.0
        self.tauj = 1.0
        self.vg = 1.0
        self.age_p = 0.0
        self.age_tau = 1.0
        self.load_c = 0.0
        self.load_xm = 0.0
        self.load_wf = 1.0
        self.load_zf = 0.1
        self.sh_A = 0.0
        self.sh_f = 0.0
        self.sh_phi = 0.0
        self.__dict__.update(kw)

    def mu_k(self, u):
        q = np.abs(u) / self.vc
        bq = self.bq * q
        return self.muinf + (self.mu1 - self.muinf) * (1 + bq) / (1 + bq + q * q) + self.eta * np.abs(u)


# Fehlberg 4(5) coefficients
_A21 = 0.25
_A31, _A32 = 3 / 32, 9 / 32
_A41, _A42, _A43 = 1932 / 2197, -7200 / 2197, 7296 / 2197
_A51, _A52, _A53, _A54 = 439 / 216, -8.0, 3680 / 513, -845 / 4104
_A61, _A62, _A63, _A64, _A65 = -8 / 27, 2.0, -3544 / 2565, 1859 / 4104, -11 / 40
_B1, _B3, _B4, _B5, _B6 = 16 / 135, 6656 / 12825, 28561 / 56430, -9 / 50, 2 / 55
_E1, _E3, _E4, _E5, _E6 = 1 / 360, -128 / 4275, -2197 / 75240, 1 / 50, 2 / 55


def _herm(s, h, y0, y1, d0, d1):
    s2 = s * s
    s3 = s2 * s
    return ((2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * y1
            + (s3 - s2) * h * d1)


def _dherm(s, h, y0, y1, d0, d1):
    s2 = s * s
    return ((6 * s2 - 6 * s) * y0 / h + (3 * s2 - 4 * s + 1) * d0 + (-6 * s2 + 6 * s) * y1 / h
            + (3 * s2 - 2 * s) * d1)


def simulate(P, drive, t_end, tol=1e-6):
    """Integrate the rig from rest (contact unloaded) to t_end. Returns segments, step ends and events."""
    m, k, c = P.m, P.k, P.c
    kt0, ct, N0 = P.kt0, P.ct, P.N0
    mus0, mu1, muinf, vc, bqc, eta = P.mus0, P.mu1, P.muinf, P.vc, P.bq, P.eta
    jg, tauj, vg = P.j, P.tauj, P.vg
    age_p, age_tau = P.age_p, P.age_tau
    lc, lxm, wf, zf = P.load_c, P.load_xm, P.load_wf, P.load_zf
    shA, shw, shphi = P.sh_A, 2 * math.pi * P.sh_f, P.sh_phi
    pv = drive.pv
    wn = math.sqrt(k / m)
    Tn = 2 * math.pi / wn
    xs, vs = P.xscale, P.xscale * wn
    atol = (tol * xs, tol * vs, tol, tol * xs, tol * vs)
    w_eps = 1e-3 * P.v0ref
    hmax = Tn / 10.0
    if shA > 0:
        hmax = min(hmax, 1.0 / (12.0 * P.sh_f))
    if lc != 0.0:
        hmax = min(hmax, 2 * math.pi / wf / 14.0)
    third = 1.0 / 3.0

    S = {"phase": STICK, "sref": 0.0, "Q0": 0.0, "tarr": 0.0, "dcur": 1, "dslip": 1, "ga": 0.0}
    stack = []

    def normal(t, xf):
        if lc != 0.0:
            return N0 * max(1.0 + lc * (xf - lxm), 0.02)
        if shA > 0.0:
            return N0 * (1.0 + shA * math.sin(shw * t + shphi))
        return N0

    tang = [1.0]  # tangent stiffness / kt of the last contact evaluation

    def cfun(P_, D, kt):
        if D <= 0.0:
            tang[0] = 1.0
            return kt * D
        ds = 1.5 * P_ / kt
        if D >= ds:
            tang[0] = 0.0
            return P_
        r = 1.0 - D / ds
        sr = math.sqrt(r)
        tang[0] = sr
        return P_ * (1.0 - r * sr)

    def contact(delta, N, me, kt):
        """Mindlin-Masing tangential force at contact displacement delta; (Q, margin on the virgin branch)."""
        Q0 = S["Q0"]
        d = S["dcur"]
        Pup = me * N - Q0
        Pdn = me * N + Q0
        i = len(stack)
        while i > 0:
            dr, Qr = stack[i - 1]
            if i >= 2:
                dm = stack[i - 2][0]
            else:
                Pc = Pup if d > 0 else Pdn
                Pp = Pdn if d > 0 else Pup
                dm = -dr * Pc / Pp if Pp > 0 else math.copysign(1e30, d)
            if d * (delta - dm) >= 0.0:
                i -= 2
                continue
            return Qr + d * cfun(2.0 * me * N, d * (delta - dr), kt), 1.0
        if delta >= 0.0:
            P_, D, sg = Pup, delta, 1.0
        else:
            P_, D, sg = Pdn, -delta, -1.0
        if P_ <= 1e-12 * N:
            tang[0] = 0.0
            return sg * me * N, -1.0
        ds = 1.5 * P_ / kt
        if D >= ds:
            tang[0] = 0.0
            return Q0 + sg * P_, 1.0 - D / ds
        r = 1.0 - D / ds
        sr = math.sqrt(r)
        tang[0] = sr
        return Q0 + sg * P_ * (1.0 - r * sr), r

    def commit(delta, me, N):
        d = S["dcur"]
        Q0 = S["Q0"]
        while stack:
            i = len(stack)
            dr = stack[-1][0]
            if i >= 2:
                dm = stack[-2][0]
            else:
                Pup = me * N - Q0
                Pdn = me * N + Q0
                Pc = Pup if d > 0 else Pdn
                Pp = Pdn if d > 0 else Pup
                dm = -dr * Pc / Pp if Pp > 0 else math.copysign(1e30, d)
            if d * (delta - dm) >= 0.0:
                stack.pop()
                if i >= 2:
                    stack.pop()
            else:
                break

    def stick_me_kt(t, N, g):
        if age_p > 0.0:
            mus = mus0 * (1.0 + (t - S["tarr"]) / age_tau) ** age_p
            kt = kt0 * math.sqrt(mus / mus0)
        else:
            mus = mus0
            kt = kt0
        if N != N0:
            kt *= (N / N0) ** third
        if jg > 0.0:
            # the junction growth relaxes in stick, but never below what keeps the static excess above the
            # traction left at the arrest: mu_s (1 + j (mu_1/mu_s) g_arrest) - mu_1 (1 + j g_arrest) = mu_s - mu_1
            return mus * (1.0 + jg * max(g, mu1 / mus * S["ga"])), kt
        return mus, kt

    last = [0.0, 0.0, 1.0]  # F, N, margin of the last evaluation

    def f(t, y):
        x, v, g, xf, vf = y
        xd, vd = pv(t)
        w = vd - v
        N = normal(t, xf)
        if S["phase"] == STICK:
            me, kt = stick_me_kt(t, N, g)
            Q, mg = contact(xd - x - S["sref"], N, me, kt)
            F = Q + ct * tang[0] * w
            gd = -g / tauj
        else:
            u = abs(w)
            q = u / vc
            bq = bqc * q
            mk = muinf + (mu1 - muinf) * (1.0 + bq) / (1.0 + bq + q * q) + eta * u
            F = S["dslip"] * N * mk * (1.0 + jg * g)
            gd = (u / (u + vg) - g) / tauj
            mg = 1.0
        last[0] = F
        last[1] = N
        last[2] = mg
        a = (F - k * x - c * v) / m
        if lc != 0.0:
            af = wf * wf * (x - xf) - 2.0 * zf * wf * vf
        else:
            af = 0.0
        return (v, a, gd, vf, af)

    def rk(t, y, h, k1):
        y2 = tuple(y[i] + h * _A21 * k1[i] for i in range(5))
        k2 = f(t + 0.25 * h, y2)
        y3 = tuple(y[i] + h * (_A31 * k1[i] + _A32 * k2[i]) for i in range(5))
        k3 = f(t + 0.375 * h, y3)
        y4 = tuple(y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i]) for i in range(5))
        k4 = f(t + 12 / 13 * h, y4)
        y5 = tuple(y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i]) for i in range(5))
        k5 = f(t + h, y5)
        y6 = tuple(y[i] + h * (_A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i])
                   for i in range(5))
        k6 = f(t + 0.5 * h, y6)
        yn = tuple(y[i] + h * (_B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i] + _B6 * k6[i])
                   for i in range(5))
        err = 0.0
        for i in range(5):
            e = h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i])
            sc = atol[i] + tol * abs(yn[i])
            r = abs(e) / sc
            if r > err:
                err = r
        return yn, err

    segs = []     # (t0, h, y0..., y1..., d0..., d1..., phase)
    ends = []     # (t1, phase, F, w, N)
    breakaways = []
    arrests = []

    def push_seg(t0, h, y0, y1, d0, d1, ph):
        segs.append((t0, h) + tuple(y0) + tuple(y1) + tuple(d0) + tuple(d1) + (ph,))

    breaks = sorted(b for b in drive.breaks if 0 < b < t_end) + [t_end]
    bi = 0
    t = 0.0
    y = (0.0, 0.0, 0.0, P.load_xm if lc != 0.0 else 0.0, 0.0)
    k1 = f(t, y)
    h = Tn / 200.0
    nsteps = 0
    max_steps = 4_000_000
    while t < t_end * (1 - 1e-12) and nsteps < max_steps:
        while bi < len(breaks) and breaks[bi] <= t + 1e-12 * Tn:
            bi += 1
        tb = breaks[bi] if bi < len(breaks) else t_end
        hh = min(h, hmax, tb - t)
        if tb - t - hh < 1e-9 * Tn:
            hh = tb - t
        yn, err = rk(t, y, hh, k1)
        nsteps += 1
        if err > 1.0:
            h = hh * max(0.1, 0.9 * err ** -0.2)
            continue
        t1 = t + hh
        kn = f(t1, yn)
        fac = min(4.0, 0.9 * err ** -0.2) if err > 0 else 4.0
        h_next = hh * fac
        ph = S["phase"]
        xd1, vd1 = pv(t1)
        w1 = vd1 - yn[1]
        ev = None
        if ph == STICK:
            te_r = None
            te_b = None
            d = S["dcur"]
            if d * w1 < -w_eps:
                # first zero of d*w in (t, t1] on the Hermite interpolant
                def gfun(tt):
                    s = (tt - t) / hh
                    return d * (pv(tt)[1] - _herm(s, hh, y[1], yn[1], k1[1], kn[1]))
                te_r = _first_root(gfun, t, t1, rising=False)
            if last[2] <= 0.0:
                def mfun(tt):
                    s = (tt - t) / hh
                    yy = tuple(_herm(s, hh, y[i], yn[i], k1[i], kn[i]) for i in range(5))
                    f(tt, yy)
                    return last[2]
                te_b = _first_root(mfun, t, t1, rising=False, strict=True)
                f(t1, yn)
            cand = [(te, name) for te, name in ((te_r, "rev"), (te_b, "brk")) if te is not None]
            if cand:
                te, ev = min(cand)
        else:
            if S["dslip"] * w1 <= 0.0:
                d = S["dslip"]

                def gfun(tt):
                    s = (tt - t) / hh
                    return d * (pv(tt)[1] - _herm(s, hh, y[1], yn[1], k1[1], kn[1]))
                te = _first_root(gfun, t, t1, rising=False, strict=True)
                ev = "arr"
        if ev is not None:
            he = te - t
            if he > 1e-10 * Tn:
                ye, _ = rk(t, y, he, k1)
            else:
                he = 0.0
                ye = y
            if ev == "arr":
                ye = (ye[0], pv(te)[1], ye[2], ye[3], ye[4])
            ke = f(te, ye)
            if he > 0.0:
                push_seg(t, he, y, ye, k1, ke, ph)
                ends.append((te, ph, last[0], pv(te)[1] - ye[1], last[1]))
            t, y = te, ye
            if ev == "rev":
                xd, vd = pv(t)
                N = last[1]
                me, kt = stick_me_kt(t, N, y[2])
                delta = xd - y[0] - S["sref"]
                commit(delta, me, N)
                Qr, _ = contact(delta, N, me, kt)
                stack.append((delta, Qr))
                S["dcur"] = -S["dcur"]
                k1 = f(t, y)
            elif ev == "brk":
                xd, vd = pv(t)
                delta = xd - y[0] - S["sref"]
                Fb = last[0]
                S["phase"] = SLIP
                S["dslip"] = (1 if Fb > 0 else -1) if Fb != 0.0 else (1 if delta >= 0.0 else -1)
                stack.clear()
                breakaways.append(t)
                k1 = f(t, y)
            else:  # arrest
                Ffr = last[0]
                xd, vd = pv(t)
                S["phase"] = STICK
                S["sref"] = xd - y[0]
                S["Q0"] = Ffr
                S["tarr"] = t
                S["ga"] = y[2]
                stack.clear()
                ab = (Ffr - k * y[0] - c * y[1]) / m
                wd = drive.acc(t) - ab
                S["dcur"] = 1 if wd > 0 else (-1 if wd < 0 else S["dslip"])
                arrests.append(t)
                k1 = f(t, y)
            h = max(h_next, Tn * 1e-6) if he > 0 else h
            continue
        push_seg(t, hh, y, yn, k1, kn, ph)
        ends.append((t1, ph, last[0], w1, last[1]))
        if ph == STICK:
            N = last[1]
            me, kt = stick_me_kt(t1, N, yn[2])
            commit(xd1 - yn[0] - S["sref"], me, N)
        t, y, k1 = t1, yn, kn
        h = h_next
    return {"segs": np.array(segs), "ends": np.array(ends), "brk": np.array(breakaways),
            "arr": np.array(arrests), "nsteps": nsteps}


def _first_root(fun, a, b, rising=False, strict=False, n_scan=12, n_bis=48):
    """First t in (a, b] where fun turns negative (fun(a) >= 0 assumed); None if fun(b) >= 0 and not strict."""
    ta = a
    fa = fun(a)
    tb = None
    for i in range(1, n_scan + 1):
        tt = a + (b - a) * i / n_scan
        ft = fun(tt)
        if ft < 0.0:
            tb = tt
            break
        ta, fa = tt, ft
    if tb is None:
        return b if strict else None
    lo, hi = ta, tb
    for _ in range(n_bis):
        mid = 0.5 * (lo + hi)
        if fun(mid) < 0.0:
            hi = mid
        else:
            lo = mid
        if hi - lo < 1e-13 * max(1.0, abs(hi)):
            break
    return hi


def dense(res, tg, nstate=5):
    """Cubic Hermite of the state on the grid tg; returns (Y[nstate, n], dY, phase)."""
    S = res["segs"]
    t0 = S[:, 0]
    h = S[:, 1]
    idx = np.clip(np.searchsorted(t0 + h, tg, side="left"), 0, len(t0) - 1)
    s = np.clip((tg - t0[idx]) / h[idx], 0.0, 1.0)
    hh = h[idx]
    Y = np.empty((nstate, len(tg)))
    dY = np.empty((nstate, len(tg)))
    for i in range(nstate):
        y0 = S[idx, 2 + i]
        y1 = S[idx, 7 + i]
        d0 = S[idx, 12 + i]
        d1 = S[idx, 17 + i]
        Y[i] = _herm(s, hh, y0, y1, d0, d1)
        dY[i] = _dherm(s, hh, y0, y1, d0, d1)
    return Y, dY, S[idx, 22]


# ----------------------------------------------------------------------------------------------------------
# measurements on the ground truth
# ----------------------------------------------------------------------------------------------------------
def slips_of(res, P, drive):
    """Breakaway/arrest pairs with their peak sliding speed; micro-slips (peak speed < 15 % of the typical)
    are merged into the stick around them."""
    brk, arr = res["brk"], res["arr"]
    pairs = []
    for tb in brk:
        a = arr[arr > tb]
        if len(a) == 0:
            continue
        ts = np.linspace(tb, a[0], 40)
        Y, _, _ = dense(res, ts)
        wp = float(np.max(drive.arrays(ts)[1] - Y[1]))
        pairs.append((tb, float(a[0]), wp))
    if not pairs:
        return []
    wps = np.array([p[2] for p in pairs])
    ref = np.median(wps[wps >= np.percentile(wps, 50)])
    return [p for p in pairs if p[2] > 0.15 * ref]


def cycles(res, P, t_lo, t_hi, tg, Fspring, drive=None):
    """Per significant slip inside [t_lo, t_hi]: breakaway, its arrest, the previous slip's arrest, the stick
    time, the peak of the spring force over the cycle, the trough after the breakaway, the drop."""
    sl = slips_of(res, P, drive if drive is not None else P._drive)
    out = []
    for i in range(1, len(sl) - 1):
        tb, ta1, wp = sl[i]
        ta0 = sl[i - 1][1]
        tnext = sl[i + 1][0]
        if tb < t_lo or ta0 < t_lo or tnext > t_hi:
            continue
        i0, i1 = np.searchsorted(tg, [ta0, ta1])
        i2 = np.searchsorted(tg, tnext)
        ib = np.searchsorted(tg, tb)
        if i1 - i0 < 3 or i2 - ib < 2:
            continue
        pk = Fspring[i0:i1].max()
        tr = Fspring[ib:i2].min()
        out.append({"tb": tb, "ta0": ta0, "ta1": ta1, "tst": tb - ta0, "peak": pk, "trough": tr,
                    "drop": pk - tr, "wpk": wp})
    return out


def twin_of(t, w, F, cyc, lo=0.1, hi=0.9, pad=0.0):
    vals = []
    for cy in cyc:
        i0, i1 = np.searchsorted(t, [cy["tb"] - pad, cy["ta1"] + pad])
        ww, ff = w[i0:i1], F[i0:i1]
        if len(ww) < 10:
            continue
        ip = int(np.argmax(ww))
        wp = ww[ip]
        if ip < 4 or len(ww) - ip < 4 or wp <= 0:
            continue
        grid = np.linspace(lo, hi, 33) * wp
        below = np.nonzero(ww[:ip] < lo * wp)[0]
        ia = below[-1] if len(below) else 0
        below = np.nonzero(ww[ip:] < lo * wp)[0]
        idd = ip + below[0] + 1 if len(below) else len(ww)
        wa, fa = ww[ia:ip + 1], ff[ia:ip + 1]
        wd, fd = ww[ip:idd], ff[ip:idd]
        if len(wa) < 3 or len(wd) < 3:
            continue
        ka = np.argsort(wa, kind="stable")
        kd = np.argsort(wd, kind="stable")
        Fa = np.interp(grid, wa[ka], fa[ka])
        Fd = np.interp(grid, wd[kd], fd[kd])
        vals.append(float(np.mean(Fd - Fa) / cy["drop"]))
    return vals


def ageing_growth(cyc):
    """Peak growth over the record's range of stick times: the fit peak = p0 + s ln t_st across the range."""
    tst = np.array([c["tst"] for c in cyc])
    pk = np.array([c["peak"] for c in cyc])
    dr = np.median([c["drop"] for c in cyc])
    if len(tst) < 4 or tst.max() / tst.min() < 1.3:
        return 0.0, float(tst.max() / max(tst.min(), 1e-30)) if len(tst) else 1.0
    A = np.vstack([np.ones_like(tst), np.log(tst)]).T
    coef = np.linalg.lstsq(A, pk, rcond=None)[0]
    return float(coef[1] * math.log(tst.max() / tst.min()) / dr), float(tst.max() / tst.min())


# ----------------------------------------------------------------------------------------------------------
# parameters
# ----------------------------------------------------------------------------------------------------------
def _rng(*key):
    return np.random.default_rng(np.random.SeedSequence([_TAG] + [int(a) for a in key]))


def draw(case, seed):
    ci = CASES.index(case)
    rng = _rng(ci, seed)
    u = ((seed * 0.618034 + ci * 0.2871) + rng.uniform(0, 0.12)) % 1.0
    fn = 3.0 * 50.0 ** u
    wn = 2 * math.pi * fn
    N0 = float(math.exp(rng.uniform(math.log(2.0), math.log(30.0))))
    mus0 = rng.uniform(0.22, 0.5)
    s_ex = rng.uniform(0.04, 0.12) if case != "twin_branch" else rng.uniform(0.07, 0.12)
    sh_A = 0.0
    if case == "triggering":
        # the shaker's dip in the static limit (mu_s A N) kept below the static excess, so that it triggers
        # slips near the end of a stick rather than breaking every arrest at once
        sh_A = rng.uniform(0.03, 0.07)
        s_ex = rng.uniform(max(0.05, 1.4 * sh_A), max(0.05, 1.4 * sh_A) + 0.04)
    w_d = rng.uniform(0.12, 0.30)
    mu1 = mus0 * (1 - s_ex)
    muinf = mu1 - w_d * mus0
    drop_est = (2 * s_ex + 1.1 * w_d) * mus0 * N0
    A_t = rng.uniform(0.05e-3, 0.4e-3)                 # drop / k, m
    k = drop_est / A_t
    m = k / wn ** 2
    kappa = rng.uniform(0.02, 0.05)                    # contact compliance / leaf compliance
    kt0 = k / kappa
    zeta_t = rng.uniform(0.08, 0.2)
    ct = 2 * zeta_t * math.sqrt((k + kt0) * m)
    zeta = rng.uniform(0.005, 0.03)
    c = 2 * zeta * m * wn
    Vs = wn * drop_est / (2 * k)
    vc = Vs * rng.uniform(0.15, 0.6)
    bq = rng.uniform(0.2, 1.5)
    eta = rng.uniform(0.05, 0.25) * (mu1 - muinf) / Vs
    tst_ratio = rng.uniform(3.0, 11.0)
    P = Rig(fn=fn, wn=wn, N0=N0, mus0=mus0, mu1=mu1, muinf=muinf, vc=vc, bq=bq, eta=eta, k=k, m=m,
            kt0=kt0, ct=ct, c=c, xscale=A_t, v0ref=drop_est / (k * tst_ratio * 2 * math.pi / wn))
    meta = dict(fn=fn, N0=N0, mus0=mus0, s_ex=s_ex, w_d=w_d, A_target_m=A_t, kappa=kappa, zeta_t=zeta_t,
                zeta=zeta, vc_over_Vs=vc / Vs, bq=bq, eta=eta, tst_ratio=tst_ratio, drop_est=drop_est,
                sh_A=sh_A)
    return P, meta, rng


# ----------------------------------------------------------------------------------------------------------
# runs: pilots, calibration, final
# ----------------------------------------------------------------------------------------------------------
def _const_drive(v0, Tn):
    return PWLDrive([0.0, 0.05 * Tn], [0.0, v0])


def _law_F(P, drive, tg, Y):
    vd = drive.arrays(tg)[1]
    w = vd - Y[1]
    if P.load_c != 0.0:
        N = P.N0 * np.maximum(1 + P.load_c * (Y[3] - P.load_xm), 0.02)
    elif P.sh_A > 0:
        N = P.N0 * (1 + P.sh_A * np.sin(2 * math.pi * P.sh_f * tg + P.sh_phi))
    else:
        N = np.full_like(tg, P.N0)
    return w, np.sign(w) * N * P.mu_k(w) * (1 + P.j * Y[2]), N


def _slip_grid(res, t_lo, t_hi, n=200):
    brk, arr = res["brk"], res["arr"]
    ts = []
    for tb in brk:
        if tb < t_lo or tb > t_hi:
            continue
        a = arr[arr > tb]
        if len(a) == 0:
            continue
        ts.append(np.linspace(tb, a[0], n)[1:-1])
    return np.concatenate(ts) if ts else np.zeros(0)


def _stats(P, drive, res, t_lo, t_hi, per_Tn=96):
    Tn = 2 * math.pi / P.wn
    tg = np.arange(t_lo, t_hi, Tn / per_Tn)
    Y, dY, ph = dense(res, tg)
    Fs = P.k * Y[0]
    cyc = cycles(res, P, t_lo, t_hi, tg, Fs, drive)
    return tg, Y, Fs, cyc


def _law_twin(P, drive, res, cyc, t_lo, t_hi):
    ts = _slip_grid(res, t_lo, t_hi)
    if len(ts) == 0 or not cyc:
        return []
    Y, _, _ = dense(res, ts)
    w, F, _ = _law_F(P, drive, ts, Y)
    return twin_of(ts, w, F, cyc)


def _transient_end(P, drive, v0, Tn, ncyc=2):
    """Run from rest until ncyc + 1 arrests; returns the arrests and the median stick-slip period."""
    Tst = P.xscale / v0
    t_end = (P.mus0 * P.N0 / P.k) / v0 * 1.3 + (ncyc + 2.5) * (Tst + Tn)
    res = simulate(P, drive, t_end)
    return res, t_end


def _f_ss(cyc):
    if len(cyc) < 3:
        return float("nan")
    tb = np.array([c["tb"] for c in cyc])
    dr = np.array([c["drop"] for c in cyc])
    keep = dr > 0.3 * np.median(dr)
    tb = tb[keep]
    return float((len(tb) - 1) / (tb[-1] - tb[0]))


def _calibrate(measure, p0, target, n_max=7, tol=0.05):
    """Find p > 0 with measure(p) = target, measure increasing in p. measure returns (value, drop, aux) or
    (None, None, None) when the pilot did not stick-slip (taken as too strong). Returns the best
    (p, value, drop, aux) and the number of pilots."""
    lo = hi = None
    p = p0
    best = None
    n = 0
    for _ in range(n_max):
        val, dp, aux = measure(p)
        n += 1
        if val is None or not np.isfinite(val) or val <= 0:
            hi = (p, float("inf"))
            p = math.sqrt(lo[0] * p) if lo else 0.5 * p
            continue
        err = abs(val / target - 1)
        if best is None or err < best[0]:
            best = (err, p, val, dp, aux)
        if err < tol:
            break
        if val < target:
            lo = (p, val)
        else:
            hi = (p, val)
        if lo and hi:
            if math.isinf(hi[1]):
                p = math.sqrt(lo[0] * hi[0])
            else:
                a = (math.log(target) - math.log(lo[1])) / (math.log(hi[1]) - math.log(lo[1]))
                a = min(max(a, 0.15), 0.85)
                p = math.exp(math.log(lo[0]) + a * (math.log(hi[0]) - math.log(lo[0])))
        else:
            p *= min(max(target / val, 0.4), 2.5)
    if best is None:
        return (p, float("nan"), None, None), n
    return best[1:], n


def build(case, seed, force_rising=False):
    """All the physics of one record: parameters, calibrations, the final run and its ground-truth sizes."""
    ci = CASES.index(case)
    P, meta, rng = draw(case, seed)
    Tn = 2 * math.pi / P.wn
    wn = P.wn
    drive_kind = "const"
    if case == "none" and seed % 8 in (2, 5):
        drive_kind = "steps"
    if case == "static_ageing":
        drive_kind = "steps" if seed % 2 == 0 else "holds"
    if case == "drive_modulation":
        drive_kind = "mod"
    if drive_kind == "steps":
        tst_target = rng.uniform(3.0, 4.5)
    elif drive_kind == "holds":
        tst_target = rng.uniform(2.5, 4.5)
    else:
        tst_target = meta["tst_ratio"]
    meta["drive_kind"] = drive_kind
    # mechanisms' first guesses
    Vs = wn * meta["drop_est"] / (2 * P.k)
    if case == "twin_branch":
        P.tauj = rng.uniform(0.1, 0.25) * Tn
        P.vg = rng.uniform(0.2, 0.5) * Vs
        meta["twin_target"] = rng.uniform(0.13, 0.21)
        P.j = meta["twin_target"] * meta["drop_est"] / (P.mu1 * P.N0 * 0.25)
    if case == "load_variation":
        sgn = -1.0 if (seed % 4 == 1 and not force_rising) else 1.0
        meta["load_sign"] = sgn
        meta["load_target"] = rng.uniform(0.14, 0.32) if sgn > 0 else rng.uniform(0.11, 0.18)
        P.load_wf = rng.uniform(1.5, 4.0) * wn
        P.load_zf = rng.uniform(0.06, 0.15)
        P.load_c = sgn * meta["load_target"] / P.xscale
        P.load_xm = P.mus0 * P.N0 / P.k * 0.8
    step_ratio = rng.uniform(4.0, 8.0)
    hold_f = list(rng.permutation(np.linspace(1.0, 6.5, 6)))
    if case == "static_ageing":
        P.age_tau = rng.uniform(0.3, 1.0) * tst_target * Tn
        meta["age_target"] = rng.uniform(0.08, 0.15)
        span = step_ratio if drive_kind == "steps" else 1.0 + max(hold_f)
        lr = math.log((1 + span * tst_target * Tn / P.age_tau) / (1 + tst_target * Tn / P.age_tau))
        P.age_p = meta["age_target"] * meta["drop_est"] / (P.mus0 * P.N0 * lr)
        meta["age_span_planned"] = span
    # pilot 1: the drop at a provisional speed, then the speed for the wanted stick time
    v0 = P.v0ref
    dr0 = _const_drive(v0, Tn)
    res, t_end = _transient_end(P, dr0, v0, Tn, ncyc=3)
    npil = 1
    sl = slips_of(res, P, dr0)
    if len(sl) >= 3:
        _, _, _, cyc = _stats(P, dr0, res, sl[1][1], t_end)
        if cyc:
            drop = float(np.median([c["drop"] for c in cyc]))
        else:
            drop = meta["drop_est"]
    else:
        drop = meta["drop_est"]
    v0 = drop / (P.k * tst_target * Tn)
    P.xscale = drop / P.k
    P.v0ref = v0
    # calibration pilots of the departures (a bracketing secant in log-log on short pilots)
    if case in ("twin_branch", "load_variation"):
        state = {"drop": drop, "v0": v0}

        def measure(pval):
            if case == "twin_branch":
                P.j = pval
            else:
                P.load_c = meta["load_sign"] * pval
            vv = state["v0"]
            P.v0ref = vv
            dr_ = _const_drive(vv, Tn)
            res_, te_ = _transient_end(P, dr_, vv, Tn, ncyc=3)
            sl_ = slips_of(res_, P, dr_)
            if len(sl_) < 4:
                return None, None, None
            t_lo_ = sl_[1][1]
            tg_, Y_, Fs_, cyc_ = _stats(P, dr_, res_, t_lo_, te_)
            if len(cyc_) < 2:
                return None, None, None
            dp = float(np.median([c_["drop"] for c_ in cyc_]))
            aux = None
            if case == "twin_branch":
                val = float(np.median(_law_twin(P, dr_, res_, cyc_, t_lo_, te_)))
            else:
                Nn = 1 + P.load_c * (Y_[3] - P.load_xm)
                val = float(Nn.max() - Nn.min())
                aux = float(0.5 * (Y_[3].max() + Y_[3].min()))
                P.load_xm = aux
            # keep the stick time near its target while calibrating
            state["v0"] = vv * dp / state["drop"]
            state["drop"] = dp
            return val, dp, aux

        tgt = meta["twin_target"] if case == "twin_branch" else meta["load_target"]
        p0 = P.j if case == "twin_branch" else abs(P.load_c)
        best, npc = _calibrate(measure, p0, tgt)
        npil += npc
        pbest, vbest, dbest, xmb = best
        if case == "twin_branch":
            P.j = pbest
        else:
            P.load_c = meta["load_sign"] * pbest
            P.load_xm = xmb
        drop = dbest
        v0 = drop / (P.k * tst_target * Tn)
        P.xscale = drop / P.k
        P.v0ref = v0
        meta["calib_value"] = vbest
    meta["pilots"] = npil
    meta["v0"] = v0
    meta["drop_pilot"] = drop
    Tst = drop / (P.k * v0)
    # transient at the final speed (constant), for the schedules' start
    res0, t0end = _transient_end(P, _const_drive(v0, Tn), v0, Tn, ncyc=2)
    sl0 = slips_of(res0, P, _const_drive(v0, Tn))
    arr0 = np.array([a[1] for a in sl0])
    brk0 = np.array([a[0] for a in sl0])
    Tss = float(np.median(np.diff(brk0[1:]))) if len(brk0) >= 3 else Tst + 0.6 * Tn
    Tslip = max(Tss - Tst, 0.3 * Tn)
    t_s = float(arr0[1] if len(arr0) >= 2 else t0end * 0.5) + rng.uniform(0.15, 0.7) * Tst
    meta["Tss_pilot"] = Tss
    # sampling and record length
    n_slips = int(rng.integers(18, 43))
    spp = float(rng.uniform(20.0, 100.0))
    sched = {}
    if drive_kind == "const" or drive_kind == "mod":
        dur = n_slips * Tss
        t_rec0 = t_s
        if drive_kind == "const":
            drive = _const_drive(v0, Tn)
        else:
            a_m = rng.uniform(0.2, 0.45)
            fm = rng.uniform(0.12, 0.45) / Tss
            phi = rng.uniform(0, 2 * math.pi)
            drive = ModDrive(v0, a_m, fm, phi)
            sched = {"a": a_m, "fm_hz": fm, "phi": phi}
            dur = max(dur, 3.0 / fm)
    elif drive_kind == "steps":
        r = step_ratio
        vs_ = v0 / r
        Tss_s = r * Tst + Tslip
        n_s = int(rng.integers(2, 4))
        n_f = int(rng.integers(3, 6))
        nblk = 0
        tk, vk = [0.0, 0.05 * Tn], [0.0, v0]
        t = t_s
        total = 0
        levels = []
        tramp = 0.05 * Tn
        while total < max(n_slips, 20) + 2 or nblk < 4:
            slow = nblk % 2 == 0
            v_new = vs_ if slow else v0
            tk += [t, t + tramp]
            vk += [vk[-1], v_new]
            nc = n_s if slow else n_f
            d_ = nc * (Tss_s if slow else Tss) * 1.15 + 0.3 * Tst
            levels.append([t, v_new])
            t += d_
            total += nc
            nblk += 1
        drive = PWLDrive(tk, vk)
        t_rec0 = t_s - rng.uniform(0.3, 0.8) * Tst
        dur = t - t_rec0
        sched = {"ratio": r, "levels_mm_s": [v0 * 1e3, vs_ * 1e3], "n_slow": n_s, "n_fast": n_f}
    else:  # holds
        tk, vk = [0.0, 0.05 * Tn], [0.0, v0]
        t = t_s
        total = 0
        holds = []
        tramp = 0.03 * Tn
        hf = hold_f
        while total < max(n_slips, 20) or len(holds) < 4:
            nc = int(rng.integers(2, 4))
            t += nc * Tss + rng.uniform(0.2, 0.6) * Tst
            H = hf[len(holds) % len(hf)] * Tst * rng.uniform(0.9, 1.1)
            tk += [t, t + tramp, t + tramp + H, t + 2 * tramp + H]
            vk += [v0, 0.0, 0.0, v0]
            holds.append([t, H])
            t += H + 2 * tramp
            total += nc
        t += 2 * Tss
        drive = PWLDrive(tk, vk)
        t_rec0 = t_s - rng.uniform(0.3, 0.8) * Tst
        dur = t - t_rec0
        sched = {"holds_s": holds}
    # sample rate: samples per natural period, at most ~45000 samples a record
    nmax = 45000.0
    if dur * spp * meta["fn"] > nmax:
        spp = max(20.0, nmax / (dur * meta["fn"]))
    meta["spp_clean"] = spp
    P._drive = drive
    t_rec1 = t_rec0 + dur
    t_end = t_rec1 + 0.5 * Tn
    extra = {}
    if case == "static_ageing":
        lr = math.log((1 + meta["age_span_planned"] * Tst / P.age_tau) / (1 + Tst / P.age_tau))
        P.age_p = meta["age_target"] * drop / (P.mus0 * P.N0 * lr)
    if case == "triggering":
        P.sh_A = meta["sh_A"]
        P.sh_phi = rng.uniform(0, 2 * math.pi)
    tries = []
    for attempt in range(7):
        if case == "triggering":
            P.sh_f = rng.uniform(2.5, 8.0) * meta["fn"]
        res = simulate(P, drive, t_end)
        tg, Y, Fs, cyc = _stats(P, drive, res, t_rec0, t_rec1)
        if case == "static_ageing" and attempt == 0:
            g, _ = ageing_growth(cyc)
            tgt = meta["age_target"]
            if g > 0.01 and not (0.75 * tgt < g < 1.3 * tgt):
                P.age_p *= tgt / g
                continue
            break
        if case == "triggering":
            fss = _f_ss(cyc)
            rt = P.sh_f / fss if np.isfinite(fss) and fss > 0 else float("nan")
            dist = abs(rt - round(rt)) if np.isfinite(rt) else 0.0
            tries.append((dist, P.sh_f, rt))
            if dist >= 0.15:
                break
            continue
        break
    if case == "triggering" and tries and tries[-1][0] < 0.15:
        best = max(tries)
        if best[1] != P.sh_f:
            P.sh_f = best[1]
            res = simulate(P, drive, t_end)
            tg, Y, Fs, cyc = _stats(P, drive, res, t_rec0, t_rec1)
        extra["trigger_tries"] = len(tries) + 1
    elif case == "triggering":
        extra["trigger_tries"] = len(tries)
    # at most 48 slips in the record: end it within the stick after the 48th
    if len(cyc) > 48:
        ta = cyc[47]["ta1"]
        nxt = cyc[48]["tb"]
        t_rec1 = ta + rng.uniform(0.4, 0.8) * (nxt - ta)
        tg, Y, Fs, cyc = _stats(P, drive, res, t_rec0, t_rec1)
    # ---- ground-truth sizes
    drops = np.array([c["drop"] for c in cyc])
    peaks = np.array([c["peak"] for c in cyc])
    drop_med = float(np.median(drops))
    if case == "load_variation" and meta["load_sign"] < 0 and drops.std() / drop_med > 0.04:
        # a falling load that did not settle to a steady limit cycle within the record: use a rising one
        return build(case, seed, force_rising=True)
    w, Fl, Nl = _law_F(P, drive, tg, Y)
    lawtw = _law_twin(P, drive, res, cyc, t_rec0, t_rec1)
    ms = {"n_slips": len(cyc), "drop_N": drop_med, "drop_cv": float(drops.std() / drop_med),
          "peak_sd_pct_drop": float(100 * peaks.std() / drop_med),
          "law_twin_pct_drop_median": float(100 * np.median(lawtw)) if lawtw else None,
          "law_twin_pct_drop_range": [float(100 * min(lawtw)), float(100 * max(lawtw))] if lawtw else None,
          "Tss_over_Tn": float(1.0 / (_f_ss(cyc) * Tn)),
          "f_ss_hz": _f_ss(cyc),
          "tst_over_Tn_median": float(np.median([c["tst"] for c in cyc]) / Tn),
          "steps": int(res["nsteps"])}
    ms["mean_friction_over_drop"] = float(np.mean(Fs) / drop_med)
    # slip speed and creep before the breakaway
    wpk = []
    for cy in cyc:
        i0, i1 = np.searchsorted(tg, [cy["tb"], cy["ta1"]])
        if i1 > i0:
            wpk.append(float(w[i0:i1].max()))
    vd_rec = drive.arrays(tg)[1]
    ms["v0_over_peak_slip_speed"] = float(v0 / np.median(wpk)) if wpk else None
    # ringing of the contact mode after the arrests (spring force, % of the drop), from 0.5 Tn after arrest
    rng_amp = []
    for cy in cyc:
        i0, i1 = np.searchsorted(tg, [cy["ta1"] + 0.3 * Tn, cy["ta1"] + 1.5 * Tn])
        if i1 - i0 > 8:
            seg = Fs[i0:i1]
            tt = tg[i0:i1]
            pf = np.polyfit(tt - tt[0], seg, 2)
            rng_amp.append(float(np.ptp(seg - np.polyval(pf, tt - tt[0])) / drop_med))
    ms["ringing_pp_pct_drop"] = float(100 * np.median(rng_amp)) if rng_amp else None
    if drive_kind in ("steps", "holds"):
        g, rr = ageing_growth(cyc)
        ms["peak_growth_pct_drop"] = 100 * g
        ms["stick_time_range_x"] = rr
    if case == "load_variation":
        ms["N_pp_pct_N0"] = float(100 * np.ptp(Nl) / P.N0)
        ms["F_over_N_twin_pct"] = None
    if case == "triggering":
        ms["f_t_over_f_ss"] = float(P.sh_f / _f_ss(cyc))
        ms["f_t_over_fn"] = float(P.sh_f / meta["fn"])
        rt = ms["f_t_over_f_ss"]
        ms["dist_from_integer"] = float(abs(rt - round(rt)))
        ms["shaker_pct_N0"] = float(100 * P.sh_A)
        ms.update(extra)
    if case == "drive_modulation":
        ms["fm_over_f_ss"] = float(sched["fm_hz"] / _f_ss(cyc))
        ms["a"] = float(sched["a"])
    meta["sched"] = sched
    return {"P": P, "meta": meta, "drive": drive, "res": res, "t_rec0": t_rec0, "t_rec1": t_rec1,
            "cyc": cyc, "measured": ms, "spp": spp, "v0": v0, "Tn": Tn, "drive_kind": drive_kind}


# ----------------------------------------------------------------------------------------------------------
# sensor, noise, nuisances
# ----------------------------------------------------------------------------------------------------------
def _pink(rng, n, fs, f_lo, f_hi):
    """Band-limited pink noise: white noise shaped by 1/sqrt(f) between f_lo and f_hi, unit rms."""
    if n < 8:
        return np.zeros(n)
    X = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, 1.0 / fs)
    g = np.zeros_like(f)
    band = (f >= f_lo) & (f <= f_hi)
    g[band] = 1.0 / np.sqrt(f[band])
    # gentle edges (first order) just outside the band
    lo = (f > 0) & (f < f_lo)
    g[lo] = (f[lo] / f_lo) / np.sqrt(f_lo)
    hi = f > f_hi
    g[hi] = (f_hi / f[hi]) ** 2 / np.sqrt(f_hi)
    y = np.fft.irfft(X * g, n)
    sd = y.std()
    return y / sd if sd > 0 else y


def _gain(rng, t):
    """The gauge's gain through a slow temperature drift: a warm-up exponential and an air-conditioning
    cycle, 0.2-0.5 % over the record, either sign."""
    dur = max(t[-1] - t[0], 1e-9)
    delta = rng.uniform(0.002, 0.005) * (1 if rng.random() < 0.5 else -1)
    tw = rng.uniform(0.3, 1.0) * dur
    Ph = rng.uniform(0.6, 2.0) * dur
    ph = rng.uniform(0, 2 * math.pi)
    s = t - t[0]
    warm = (1 - np.exp(-s / tw)) / (1 - math.exp(-dur / tw))
    hv = np.sin(2 * math.pi * s / Ph + ph) - math.sin(ph)
    return 1.0 + delta * (0.8 * warm + 0.2 * hv), float(delta)


def _nuisance(rng, nuis, t, sig, drop, info):
    if nuis == "hum":
        fh = 50.0 if rng.random() < 0.5 else 60.0
        A = rng.uniform(0.01, 0.05) * drop
        out = sig.copy()
        for h, rel in ((1, 1.0), (2, rng.uniform(0.1, 0.4)), (3, rng.uniform(0.05, 0.3))):
            out += A * rel * np.sin(2 * math.pi * h * fh * t + rng.uniform(0, 2 * math.pi))
        info.update(hum_hz=fh, hum_pct_drop=100 * A / drop)
        return out
    if nuis == "drift":
        A = rng.uniform(0.02, 0.06) * drop * (1 if rng.random() < 0.5 else -1)
        s = (t - t[0]) / max(t[-1] - t[0], 1e-12)
        kq = rng.uniform(-0.6, 0.6)
        info.update(drift_pct_drop=100 * A / drop)
        return sig + A * (s + kq * s * (s - 1))
    if nuis == "spikes":
        n = len(sig)
        frac = rng.uniform(0.0005, 0.005)
        k = max(2, int(round(frac * n)))
        idx = np.sort(rng.choice(np.arange(2, n - 2), size=k, replace=False))
        keep = np.concatenate([[True], np.diff(idx) > 2])
        idx = idx[keep]
        out = sig.copy()
        out[idx] += rng.uniform(0.3, 1.2, len(idx)) * drop * rng.choice([-1.0, 1.0], len(idx))
        info.update(spikes=int(len(idx)), spike_frac=float(len(idx) / n))
        return out
    if nuis == "quantisation":
        q = rng.uniform(0.002, 0.01) * drop
        info.update(adc_step_pct_drop=100 * q / drop)
        return np.round(sig / q) * q
    return sig


# ----------------------------------------------------------------------------------------------------------
# file writers
# ----------------------------------------------------------------------------------------------------------
def _col_letter(i):
    s = ""
    i += 1
    while i:
        i, r = divmod(i - 1, 26)
        s = chr(65 + r) + s
    return s


def _xml_esc(s):
    return s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _write_xlsx(path, header_rows, cols):
    """Minimal OOXML workbook: one sheet, inline-string header rows, numeric cells."""
    ncol = len(cols)
    letters = [_col_letter(i) for i in range(ncol)]
    parts = ['<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
             '<worksheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main">'
             '<sheetData>']
    r = 0
    for hr in header_rows:
        r += 1
        cells = "".join('<c r="%s%d" t="inlineStr"><is><t>%s</t></is></c>' % (letters[i], r, _xml_esc(h))
                        for i, h in enumerate(hr))
        parts.append('<row r="%d">%s</row>' % (r, cells))
    strs = [np.char.mod("%.9g", np.asarray(c, float)) for c in cols]
    n = len(cols[0])
    for k in range(n):
        r += 1
        cells = "".join('<c r="%s%d"><v>%s</v></c>' % (letters[i], r, strs[i][k]) for i in range(ncol))
        parts.append('<row r="%d">%s</row>' % (r, cells))
    parts.append("</sheetData></worksheet>")
    sheet = "".join(parts)
    ct = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
          '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
          '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
          '<Default Extension="xml" ContentType="application/xml"/>'
          '<Override PartName="/xl/workbook.xml" '
          'ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.sheet.main+xml"/>'
          '<Override PartName="/xl/worksheets/sheet1.xml" '
          'ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/>'
          '</Types>')
    rels = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
            '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
            '<Relationship Id="rId1" '
            'Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/officeDocument" '
            'Target="xl/workbook.xml"/></Relationships>')
    wb = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
          '<workbook xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" '
          'xmlns:r="http://schemas.openxmlformats.org/officeDocument/2006/relationships">'
          '<sheets><sheet name="Data" sheetId="1" r:id="rId1"/></sheets></workbook>')
    wbrels = ('<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
              '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
              '<Relationship Id="rId1" '
              'Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/worksheet" '
              'Target="worksheets/sheet1.xml"/></Relationships>')
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED) as z:
        for name, text in (("[Content_Types].xml", ct), ("_rels/.rels", rels), ("xl/workbook.xml", wb),
                           ("xl/_rels/workbook.xml.rels", wbrels), ("xl/worksheets/sheet1.xml", sheet)):
            zi = zipfile.ZipInfo(name, date_time=(2024, 1, 1, 0, 0, 0))   # fixed stamp: byte-deterministic
            zi.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(zi, text)


def _write_text(path, sep, header, cols, fmts, preamble=()):
    strs = [np.char.mod(f, np.asarray(c, float)) for c, f in zip(cols, fmts)]
    body = np.stack(strs, axis=1)
    with open(path, "w", newline="\n") as fh:
        for line in preamble:
            fh.write(line + "\n")
        fh.write(sep.join(header) + "\n")
        fh.write("\n".join(sep.join(row) for row in body))
        fh.write("\n")


_OPERATORS = ("K. Sato", "M. Weber", "A. Rossi", "J. Novak", "L. Martin", "P. Okafor", "S. Lindqvist",
              "R. Gupta")


def _json_ok(o):
    if isinstance(o, dict):
        return {str(k): _json_ok(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_json_ok(v) for v in o]
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, float) and not math.isfinite(o):
        return None
    return o


# ----------------------------------------------------------------------------------------------------------
# the interface
# ----------------------------------------------------------------------------------------------------------
def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    ci = CASES.index(case)
    B = build(case, seed)
    P, meta, drive, res = B["P"], B["meta"], B["drive"], B["res"]
    Tn, fn = B["Tn"], meta["fn"]
    ms = B["measured"]
    drop = ms["drop_N"]
    rngf = _rng(ci, seed, 7)                                   # format choices: (case, seed)
    rngn = _rng(ci, seed, 100 + NUISANCES.index(nuisance))      # noise and nuisance: (case, seed, nuisance)
    spp = B["spp"] if nuisance != "coarse" else float(rngn.uniform(10.0, 15.0))
    fs = spp * fn
    t0, t1 = B["t_rec0"], B["t_rec1"]
    n = int((t1 - t0) * fs)
    pre = 96
    tf = t0 + (np.arange(4 * n + pre) - pre) / (4.0 * fs)
    Y, dY, ph = dense(res, tf)
    _, _, Nf = _law_F(P, drive, tf, Y)
    fc = float(rngf.uniform(0.3, 0.4)) * fs
    b, a = scipy.signal.butter(2, fc / (2.0 * fs))
    zi = scipy.signal.lfilter_zi(b, a)
    xs = scipy.signal.lfilter(b, a, Y[0], zi=zi * Y[0][0])[0][pre::4][:n]
    Ns = scipy.signal.lfilter(b, a, Nf, zi=zi * Nf[0])[0][pre::4][:n]
    ts = tf[pre::4][:n]
    # the 1-DoF reading of the clean, anti-aliased gauge signal (what a perfect record shows)
    dt = 1.0 / fs
    xdot = np.gradient(xs, dt)
    xdd = np.gradient(xdot, dt)
    vds = drive.arrays(ts)[1]
    F1 = P.m * xdd + P.c * xdot + P.k * xs
    tw1 = twin_of(ts, vds - xdot, F1, B["cyc"], pad=0.05 * Tn)
    ms = dict(ms)
    ms["record_1dof_twin_pct_drop_median"] = float(100 * np.median(tw1)) if tw1 else None
    ms["samples_per_period"] = float(spp)
    # record kind and columns
    kind = "force" if (seed + ci) % 2 == 0 else "disp"
    fmt = ("mat", "xlsx", "text")[(seed + 2 * ci) % 3]
    sub = (seed // 3 + ci) % 2
    dk = B["drive_kind"]
    stepped = dk in ("steps", "holds")
    if kind == "force":
        has_N = case == "load_variation" or (case == "triggering" and seed % 2 == 0) or seed % 3 == 1
        if stepped:
            dcol = "pos" if seed % 2 == 0 else "vel"
        elif dk == "mod":
            dcol = None
        else:
            dcol = "pos" if seed % 4 in (0, 1) else None
    else:
        has_N = True
        dcol = "vel" if stepped else None
    # sensor: gain drift + band-limited pink noise on every channel, nuisance on the main one
    gain, gdelta = _gain(rngn, ts)
    f_lo = max(1.0 / (t1 - t0), fs * 1e-5)
    f_hi = 0.45 * fs
    sig_rel = float(rngn.uniform(0.0015, 0.005))
    main = P.k * xs * gain + sig_rel * drop * _pink(rngn, n, fs, f_lo, f_hi)       # N (force units)
    ninfo = {}
    main = _nuisance(rngn, nuisance, ts, main, drop, ninfo)
    gainN, _ = _gain(rngn, ts)
    Nmeas = Ns * gainN + rngn.uniform(0.001, 0.003) * P.N0 * _pink(rngn, n, fs, f_lo, f_hi)
    tt = ts - t0 + (0.0 if rngf.random() < 0.6 else float(np.round(rngf.uniform(0.5, 30.0), 3)))
    xd_s, vd_s = drive.arrays(ts)
    enc_res = float(rngf.choice([0.1e-6, 0.2e-6, 0.5e-6, 1.0e-6]))
    pos = np.round((xd_s - xd_s[0] + rngf.uniform(2e-3, 40e-3)) / enc_res) * enc_res      # m
    k_ring = float(rngf.uniform(50.0, 400.0)) * 1e3                                   # N/m
    y0 = float(rngf.uniform(0.5e-3, 3e-3))
    ymeas = y0 + Nmeas / k_ring                                                       # m
    # fn given
    fn_given = None
    omit = (case != "triggering") and nuisance != "fn_off" and (seed + 2 * ci) % 8 == 3
    if not omit:
        fn_given = fn
        if nuisance == "fn_off":
            fn_given = fn * (1.0 + 0.05 * (1 if rngn.random() < 0.5 else -1))
    args = []
    if fn_given is not None:
        args += ["--fn", "%.6g" % fn_given]
    if kind == "force":
        args += ["--stiffness", "%.6g" % P.k]
    v0_mm = B["v0"] * 1e3
    if dcol is None:
        args += ["--v0", "%.6g" % v0_mm]
    # units and columns
    os.makedirs(outdir, exist_ok=True)
    base = "%s_%s_s%d_%s" % (NAME, case, seed, nuisance)
    names_f = (("Time", "Friction force", "Normal force", "Stage position", "Stage speed"),
               ("time", "Ft", "Fn", "x_stage", "v_stage"),
               ("t", "Tangential force", "Normal load", "Encoder", "Drive speed"))[seed % 3]
    names_d = (("Time", "Deflection", "Load ring", "Stage speed"),
               ("time", "x", "y", "v0"),
               ("t", "Displacement", "Normal LVDT", "Drive velocity"))[seed % 3]
    cols = []   # (name, unit, values, fmt)
    if fmt == "mat":
        tu, fu, xu, pu = ("s", 1.0), ("N", 1.0), ("mm", 1e3), ("mm", 1e3)
    else:
        tu = ("ms", 1e3) if rngf.random() < 0.3 else ("s", 1.0)
        fu = ("mN", 1e3) if (drop < 0.5 and rngf.random() < 0.6) else ("N", 1.0)
        xu = ("um", 1e6) if rngf.random() < 0.35 else ("mm", 1e3)
        pu = ("um", 1e6) if rngf.random() < 0.35 else ("mm", 1e3)
    tdec = max(0, int(math.ceil(-math.log10(tu[1] / fs / 50.0))))
    cols.append((names_f[0] if kind == "force" else names_d[0], tu[0], tt * tu[1], "%%.%df" % tdec))
    if kind == "force":
        cols.append((names_f[1], fu[0], main * fu[1], "%.7g"))
        if has_N:
            cols.append((names_f[2], fu[0], Nmeas * fu[1], "%.6g"))
        if dcol == "pos":
            cols.append((names_f[3], pu[0], pos * pu[1], "%.7g"))
        elif dcol == "vel":
            cols.append((names_f[4], "mm/s", vd_s * 1e3, "%.6g"))
    else:
        cols.append((names_d[1], xu[0], main / P.k * xu[1], "%.7g"))
        cols.append((names_d[2], "mm", ymeas * 1e3, "%.7g"))
        if dcol == "vel":
            cols.append((names_d[3], "mm/s", vd_s * 1e3, "%.6g"))
    op = _OPERATORS[int(rngf.integers(len(_OPERATORS)))]
    date = "20%02d-%02d-%02d %02d:%02d:%02d" % (
        int(rngf.integers(19, 26)), int(rngf.integers(1, 13)), int(rngf.integers(1, 29)),
        int(rngf.integers(8, 19)), int(rngf.integers(0, 60)), int(rngf.integers(0, 60)))
    sensor = ("strain gauge full bridge at the leaf root" if kind == "force"
              else "eddy-current probe at the leaf tip")
    if fmt == "mat":
        path = os.path.join(outdir, base + ".mat")
        mnames_f = (("time", "Ff", "Fn", "stage_pos", "v_drive"),
                    ("t", "friction_force", "normal_force", "position", "speed"))[sub]
        mnames_d = (("time", "x", "y", "v_drive"), ("time", "deflection", "load_ring", "v_stage"))[sub]
        d = {}
        for i, (nm, un, val, _) in enumerate(cols):
            if kind == "force":
                key = {names_f[0]: mnames_f[0], names_f[1]: mnames_f[1], names_f[2]: mnames_f[2],
                       names_f[3]: mnames_f[3], names_f[4]: mnames_f[4]}[nm]
            else:
                key = {names_d[0]: mnames_d[0], names_d[1]: mnames_d[1], names_d[2]: mnames_d[2],
                       names_d[3]: mnames_d[3]}[nm]
            d[key] = np.asarray(val, float).reshape(-1, 1)
        d["fs"] = float(fs)
        d["operator"] = op
        d["rig"] = "dead-weight lever tribometer, ball on flat, " + sensor
        d["date"] = date
        buf = io.BytesIO()
        scipy.io.savemat(buf, d, do_compression=True, oned_as="column")
        raw = bytearray(buf.getvalue())
        # a fixed 116-byte descriptive header instead of savemat's creation time: byte-deterministic files
        txt = b"MATLAB 5.0 MAT-file, Platform: posix, written by the lever tribometer DAQ export"
        raw[:116] = txt.ljust(116, b" ")
        with open(path, "wb") as fh:
            fh.write(bytes(raw))
    elif fmt == "xlsx":
        path = os.path.join(outdir, base + ".xlsx")
        if sub == 0:
            hdr = [["%s [%s]" % (nm, un) for nm, un, _, _ in cols]]
        else:
            hdr = [[nm for nm, _, _, _ in cols], [un for _, un, _, _ in cols]]
        _write_xlsx(path, hdr, [c[2] for c in cols])
    else:
        if sub == 0:
            path = os.path.join(outdir, base + ".txt")
            pre_l = ["Instrument = dead-weight lever tribometer (ball on flat)",
                     "Sensor = " + sensor,
                     "Ball = 6.35 mm, 100Cr6",
                     "Sample rate = %.6g Hz" % fs,
                     "Operator = " + op,
                     "Date = " + date,
                     "Channels = %d" % len(cols)]
            _write_text(path, "\t", ["%s [%s]" % (nm, un) for nm, un, _, _ in cols], [c[2] for c in cols],
                        [c[3] for c in cols], pre_l)
        else:
            path = os.path.join(outdir, base + ".csv")
            _write_text(path, ",", ["%s (%s)" % (nm, un) for nm, un, _, _ in cols], [c[2] for c in cols],
                        [c[3] for c in cols])
    ms.update({"nuisance_" + k: v for k, v in ninfo.items()})
    params = {
        "rig": "dead-weight lever, sphere on flat, cantilever leaf; Cattaneo-Mindlin/Masing stick, Pade slip law",
        "fn_hz": fn, "k_N_per_m": P.k, "m_kg": P.m, "c_Ns_per_m": P.c, "kt0_N_per_m": P.kt0,
        "ct_Ns_per_m": P.ct, "N0_N": P.N0, "mu_s0": P.mus0, "mu_1": P.mu1, "mu_inf": P.muinf,
        "v_c_mm_s": P.vc * 1e3, "b_pade": P.bq, "eta_per_mm_s": P.eta * 1e-3, "v0_mm_s": v0_mm,
        "twin_j": P.j, "tau_j_s": P.tauj, "v_g_mm_s": P.vg * 1e3, "age_p": P.age_p, "age_tau_s": P.age_tau,
        "load_c_per_mm": P.load_c * 1e-3, "load_xm_mm": P.load_xm * 1e3, "rider_f_hz": P.load_wf / (2 * math.pi),
        "rider_zeta": P.load_zf, "shaker_A": P.sh_A, "shaker_f_hz": P.sh_f, "drive_kind": dk,
        "schedule": meta.get("sched", {}), "draw": {k: v for k, v in meta.items() if k != "sched"},
        "record": {"kind": kind, "format": fmt, "sub": sub, "fs_hz": fs, "samples": n,
                   "columns": [[nm, un] for nm, un, _, _ in cols], "anti_alias_hz": fc,
                   "pink_rms_pct_drop": 100 * sig_rel, "gain_drift_pct": 100 * gdelta,
                   "t_start_s": t0, "duration_s": t1 - t0},
        "measured": ms,
    }
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance,
            "file": os.path.abspath(path), "args": args, "fn_true": float(fn),
            "fn_given": None if fn_given is None else float(fn_given), "params": _json_ok(params)}
