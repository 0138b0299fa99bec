"""Servo-driven lever tribometer with a mixed-lubrication contact (independent generator).

Written without reading the diagnosis code.  NAME = "servo_lever".

Rig
---
A pin on a pivoted lever is pressed on a lubricated flat by a dead weight (N0 3-15 N).  The pin holder is
carried by a parallel flexure (the tangential spring k 400-8000 N/m, strain gauges on it: the force channel; or
a probe on it: the extension x = F/k); its effective mass m sets fn = sqrt(k/m)/2pi (3-80 Hz).  The flat sits
on the nut of a leadscrew driven by a DC motor under a PI **velocity** loop (reflected motor inertia M_d =
200-2000 m, closed-loop bandwidth 1-2.5 omega_n, damping 0.6-1): the friction's reaction loads the motor, so
the drive's speed dips in stick and surges after each slip (measured below); a stepping programme runs on a
finer lead (M_d and the gains x the step ratio).  The motor's encoder (quadrature counts of lead/4 CPR) gives
the drive position on some records.  The lever has a small sprag (self-energising) offset: the normal load
gets gamma F_friction, gamma 0.03-0.1 outside `load_variation`.

Friction law (not used by the other generators): **mixed lubrication**, not a function of the speed alone.
A dimensionless film thickness H (film / composite roughness) follows the sliding speed toward
H_ss = (v/v_h)^p (p 0.60-0.72, EHL-like): it builds by entrainment at the rate v/L_e (L_e 0.0006-0.0012 of the
slip's size) and thins by squeeze flow at the rate (1/tau_q) H^2/(H^2 + H_q^2) (tau_q 0.0006-0.0012 Tn;
Reynolds' h^3 law once thin).  A trapped lubricant layer Ht is replenished by sliding (toward Ht0 over L_t)
and squeezed out at rest, dHt/dt = -Ht^3/(tau_t Ht0^2).  With h = sqrt(H^2 + Ht^2) (the trapped layer fills
valleys a full film already covers), the asperity contact fraction phi = 1/(1 + h^n) (n 1.7-2.4) weights a
boundary friction mu_b = mu_bk + beta_b ln(1 + v/v_b) + Delta_w (1 - theta) against a fluid shear
mu_h0 (v/v_h)(1 - phi)/h (mu_h0 (v/v_h)^(1-p) in steady state):
    F = N [phi mu_b + (1 - phi) mu_h0 (v/v_h)/h].
The static friction is the same contact fraction at rest: F_s = N phi(h) (mu_bs + Delta_w (1 - theta)),
mu_bs 0.14-0.20 = 1.06-1.16 mu_bk.  theta is the coverage of an adsorbed additive layer, worn off by slip
distance and re-adsorbed at rest (dtheta/dt = -v theta/L_w + (1 - theta)/tau_ads); Delta_w = 0 outside
`twin_branch`.  v_h is 0.8-1.6 of the slip-speed scale, so the slips run from boundary into mixed
lubrication; the drop is 15-104 % of the peak spring force (median 52 %; past 100 % the spring swings through
zero, on load_variation records with a rising load).

Stick handling: a hybrid automaton with two modes.  STICK: the pin moves with the flat (x' = the flat's
speed; the pin's mass rides in the drive's equation); it leaves when the force the contact must carry reaches
the static limit (with the sprag: mu_s (N_lever + gamma F) - |F| crosses 0).  SLIP: it leaves when the
sliding speed reaches 0 with the needed force within the static limit, else it slides on in the direction of
that force.  No band, no regularisation.

Integrator: own **variable-step Cash-Karp 5(4)** embedded pair (error per component against scaled absolute
tolerances, rtol 1e-6), cubic Hermite dense output per step; guards located by the **Illinois (modified regula
falsi)** method on the Hermite interpolant (the stick guard is also sampled at 1/8 of a shaker period inside
long steps, so no crossing is stepped over), then the step is retaken exactly to the event; a trial step that
crosses v = 0 is re-aimed at the crossing (linear in v), and |v| < 1e-6 of the speed scale is an arrest.  The
friction in the ground truth is evaluated from the interpolated state by the law (slip) or as the force the
contact carries (stick), never by differentiating the interpolant.

Departures (measured on the simulated ground truth and returned in `params["measured"]`; figures for seeds
0-23, each with the bench's nuisance for its seed):
- `load_variation`: a bell crank moves the dead weight's hanger with the pin holder, N_lever = N0 (1 + c (x -
  xm)), plus a large sprag (gamma 0.25-0.6) through the lever's normal mode (f_N 3-6 fn, zeta 0.15-0.3).  c is
  set after a calibration run with the crank off, for a load p-p of 15-30 % (capped at mu_s N0 c <= k/2: a
  rising limit must not keep pace with the spring); a falling load (c < 0, 11-16 %) on seeds 3 mod 4 whose
  slips are large (drop >= 0.45 of the peak), as it shrinks the slips.  Measured N p-p 10.1-39.8 % of N0, the
  normal channel always recorded.  Read as F against v the record looks double-valued (-23..-5 % of the drop
  with c > 0, +5..+22 % with c < 0, 5 of 24 records); F/N against v: -1.3..-0.3 %.
- `twin_branch`: the additive layer is worn through by the slip distance within each slip (L_w 0.4-1.0 of the
  slip's size) and re-adsorbs in stick (tau_ads 0.25-0.4 of the stick); Delta_w rescaled from a calibration
  run.  Decelerating minus accelerating friction at equal true sliding speed (0.15-0.85 of the slip's peak
  speed, averaged, over each slip's drop): +11.8..+19.6 % (median 15 %).
- `static_ageing`: a thick trapped layer squeezed out slowly in stick (tau_t with 2 t_stick/tau_t 0.5-2 at the
  shortest sticks), Ht0 solved from the squeeze law for the target growth and rescaled after the run: the
  static friction grows as phi(Ht0 / sqrt(1 + 2 t/tau_t)).  The drive steps 4-8x between levels (even seeds)
  or holds 1-10 stick-slip periods (odd seeds, slide-hold-slide); the drive is recorded (encoder position or
  the controller's speed readout).  Peak growth over the record's range of stick times (6-27x; slope of the
  peak on ln t_stick times the ln range): 7.9-19.5 % of the drop (median 13 %), 2.7-11.3 % of the peak.  The
  squeezed layer at each breakaway makes the law's own twin -4.2..-1.0 % of the drop here.
- `triggering`: an unbalanced motor on the lever, N_lever = N0 (1 + a sin(2 pi f_t t)), a 3-8 %, f_t 2.5-8 fn;
  the static-kinetic gap is 1.11-1.16 and the film weakening stronger here, so the shaker triggers slips rather
  than arresting them.  The breakaways lock readily (and unpredictably in f_t) to the shaker, f_t/f_ss an
  integer; f_t is drawn afresh for up to 6 runs until f_t/f_ss is at least 0.15 from an integer with a drop at
  least 0.6 of the unforced one (a shaker that arrests the slips is weakened 0.7x).  Measured: f_t/f_ss
  9.4-38.6, all 24 at least 0.15 from an integer; load p-p 6.8-15.9 % of N0; F/N twin -1.3..-0.6 %.
- `drive_modulation`: a periodic leadscrew lead error once per screw turn, the nut's speed is
  Vm (1 + a [sin phi + r2 sin(2 phi + psi)]), a 0.20-0.45, r2 0.2-0.3 on odd seeds (0 on even), the screw's lead
  set so fm = 0.15-0.4 f_ss of a calibration run (measured fm/f_ss 0.14-0.32); the motor's loop does not see
  it; only --v0 (v0n) is given, no drive column.  The law's own twin: -1.5..-0.4 %.

`none` (24 records): constant drive, or (seeds 2 and 5 mod 8) a drive stepping 4-8x between levels with the
drive recorded.  Its inherent departures: the film's lag and the trapped layer make the law double-valued by
-1.7..-0.5 % of the drop (median -0.7 %; the same with the ideal-drive speed v0 - x' or with F/N); peak
growth with stick time on the stepped records (sticks 6-6.6x apart) -0.03..+0.19 % of the drop; normal-load
p-p 0.13-1.0 % of N0 (the sprag); the drive's speed dips 0.03-0.6 % and surges 0.08-3.9 % of v0 after a slip.

Records: force records (friction and normal in N or mN, the encoder's drive position in mm or um,
`--stiffness`), half of them from a charge amplifier (piezo: first-order high-pass, tau 60-200x the run from
the unloaded reset) or displacement records (x = F/k in mm, an affine normal reading y in mm, optional
controller speed readout v0 in mm/s from the encoder counts); headers `name [unit]` (`name[unit]` when
whitespace-separated); comma, TAB or whitespace.  Sensor: 2-pole Bessel anti-alias at 0.25-0.4 fs on a 4x
finer grid, white noise 0.2-0.6 % of the drop, 20-100 samples per natural period (coarse 10-15), 18-50
stick-slip cycles.  `--fn` on 7 of 8 seeds per case (8 of 8 for triggering); fn_off: +-5 %.  A record takes
0.2-1.3 s (triggering up to 2.3 s when its first runs lock).
"""

from __future__ import annotations

import bisect
import math
import os

import numpy as np
from scipy import signal

NAME = "servo_lever"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
_OMIT_FN = {"none": 3, "load_variation": 5, "twin_branch": 1, "static_ageing": 2, "triggering": None,
            "drive_modulation": 4}

# Cash-Karp 5(4) tableau
_C2, _C3, _C4, _C5, _C6 = 1 / 5, 3 / 10, 3 / 5, 1.0, 7 / 8
_A21 = 1 / 5
_A31, _A32 = 3 / 40, 9 / 40
_A41, _A42, _A43 = 3 / 10, -9 / 10, 6 / 5
_A51, _A52, _A53, _A54 = -11 / 54, 5 / 2, -70 / 27, 35 / 27
_A61, _A62, _A63, _A64, _A65 = 1631 / 55296, 175 / 512, 575 / 13824, 44275 / 110592, 253 / 4096
_B1, _B3, _B4, _B6 = 37 / 378, 250 / 621, 125 / 594, 512 / 1771
_E1 = _B1 - 2825 / 27648
_E3 = _B3 - 18575 / 48384
_E4 = _B4 - 13525 / 55296
_E5 = -277 / 14336
_E6 = _B6 - 1 / 4

STICK, SLIP = 0, 1
# state: x, u, Xm, Vm, I, H, Ht, th, N, Nd
NS = 10


# ----------------------------------------------------------------------------------------------------------
# the rig's equations
# ----------------------------------------------------------------------------------------------------------
def _make_model(P):
    """Right-hand sides of the two modes and their guards, as closures over scalar parameters."""
    k, m, c = P["k"], P["m"], P["c"]
    Md, Kp, Ki, bd = P["Md"], P["Kp"], P["Ki"], P["bd"]
    N0, cx, xm, gam = P["N0"], P["cx"], P["xm"], P["gamma"]
    at, wt, pht = P["a_t"], 2 * math.pi * P["f_t"], P["phi_t"]
    mode_on = P["normal_mode"]
    wN, zN = 2 * math.pi * P["f_N"], P["zeta_N"]
    mubk, mubs, betab, vb = P["mu_bk"], P["mu_bs"], P["beta_b"], P["v_b"]
    muh, vh, ph, nphi = P["mu_h0"], P["v_h"], P["p_h"], P["n_phi"]
    Le, tq, Hq2 = P["L_e"], P["tau_q"], P["H_q"] ** 2
    Lt, Ht0, tt = P["L_t"], P["Ht0"], P["tau_t"]
    Lw, tads, dw = P["L_w"], P["tau_ads"], P["Delta_w"]
    am, r2, psi, phm = P["a_m"], P["r2"], P["psi"], P["phi_m"]
    km = 2 * math.pi / P["p_m"] if am > 0 else 0.0
    vref = P["vref"]
    inv_tt_h2 = 1.0 / (tt * Ht0 * Ht0)
    log1p, sin, cos = math.log1p, math.sin, math.cos

    def nlever(t, x):
        n = 1.0 + cx * (x - xm)
        if at:
            n += at * sin(wt * t + pht)
        return N0 * n

    def screw(X):
        if am == 0.0:
            return 1.0, 0.0
        a = km * X + phm
        return (1.0 + am * (sin(a) + r2 * sin(2 * a + psi)),
                am * km * (cos(a) + 2 * r2 * cos(2 * a + psi)))

    def phi_of(hs):
        return 1.0 / (1.0 + hs ** nphi) if hs > 0 else 1.0

    def mu_slip(va, H, Ht, th):
        hs = math.sqrt(H * H + Ht * Ht)  # the trapped layer fills the valleys a full film already covers
        if hs > 0:
            q = hs ** nphi
            phi = 1.0 / (1.0 + q)
            ff = q / hs * phi  # (1 - phi)/hs
        else:
            phi, ff = 1.0, 0.0
        mub = mubk + betab * log1p(va / vb) + dw * (1.0 - th)
        return phi * mub + muh * (va / vh) * ff

    def films(va, H, Ht, th):
        if va > 0:
            hss = (va / vh) ** ph
        else:
            hss = 0.0
        if H < hss:
            dH = (hss - H) * va / Le
        else:
            h2 = H * H
            dH = -(H - hss) * h2 / (tq * (h2 + Hq2))
        dHt = va / Lt * (Ht0 - Ht) - Ht * Ht * Ht * inv_tt_h2
        dth = -va * th / Lw + (1.0 - th) / tads
        return dH, dHt, dth

    def rhs_stick(t, y):
        x, u, Xm, Vm, I, H, Ht, th, N, Nd = y
        e1, e2 = screw(Xm)
        vr = vref(t)
        upi = Kp * (vr - Vm) + Ki * I
        Vd = Vm * e1
        dVm = (upi - e1 * (m * Vm * Vm * e2 + k * x + c * Vd) - bd * Vm) / (Md + m * e1 * e1)
        ad = dVm * e1 + Vm * Vm * e2
        dH, dHt, dth = films(0.0, H, Ht, th)
        if mode_on:
            F = m * ad + k * x + c * Vd
            dNd = wN * wN * (nlever(t, x) + gam * F - N) - 2 * zN * wN * Nd
            return [Vd, ad, Vm, dVm, vr - Vm, dH, dHt, dth, Nd, dNd]
        return [Vd, ad, Vm, dVm, vr - Vm, dH, dHt, dth, 0.0, 0.0]

    def rhs_slip(t, y):
        x, u, Xm, Vm, I, H, Ht, th, N, Nd = y
        e1, e2 = screw(Xm)
        vr = vref(t)
        upi = Kp * (vr - Vm) + Ki * I
        Vd = Vm * e1
        v = Vd - u
        va = v if v >= 0 else -v
        s = 1.0 if v >= 0 else -1.0
        mu = mu_slip(va, H, Ht, th)
        if mode_on:
            Ff = s * mu * N
            dNd = wN * wN * (nlever(t, x) + gam * Ff - N) - 2 * zN * wN * Nd
        else:
            Ff = s * mu * nlever(t, x) / (1.0 - gam * s * mu)
            dNd = 0.0
        du = (Ff - k * x - c * u) / m
        dVm = (upi - e1 * Ff - bd * Vm) / Md
        dH, dHt, dth = films(va, H, Ht, th)
        return [u, du, Vm, dVm, vr - Vm, dH, dHt, dth, Nd, dNd]

    def needed(t, y):
        """Force the contact must carry to keep the pin on the flat, and the static limit on it."""
        x, u, Xm, Vm, I, H, Ht, th, N, Nd = y
        e1, e2 = screw(Xm)
        upi = Kp * (vref(t) - Vm) + Ki * I
        Vd = Vm * e1
        dVm = (upi - e1 * (m * Vm * Vm * e2 + k * x + c * Vd) - bd * Vm) / (Md + m * e1 * e1)
        F = m * (dVm * e1 + Vm * Vm * e2) + k * x + c * Vd
        mus = phi_of(math.sqrt(H * H + Ht * Ht)) * (mubs + dw * (1.0 - th))
        if mode_on:
            return F, mus * N
        return F, mus * (nlever(t, x) + gam * F)

    def g_stick(t, y):
        F, lim = needed(t, y)
        return lim - abs(F)

    def vslide(t, y):
        e1, _ = screw(y[2])
        return y[3] * e1 - y[1]

    return rhs_stick, rhs_slip, g_stick, vslide, needed


def _cash_karp(f, t, y, h, k1):
    n = len(y)
    r = range(n)
    y2 = [y[i] + h * _A21 * k1[i] for i in r]
    k2 = f(t + _C2 * h, y2)
    y3 = [y[i] + h * (_A31 * k1[i] + _A32 * k2[i]) for i in r]
    k3 = f(t + _C3 * h, y3)
    y4 = [y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i]) for i in r]
    k4 = f(t + _C4 * h, y4)
    y5 = [y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i]) for i in r]
    k5 = f(t + _C5 * h, y5)
    y6 = [y[i] + h * (_A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i]) for i in r]
    k6 = f(t + _C6 * h, y6)
    yn = [y[i] + h * (_B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B6 * k6[i]) for i in r]
    err = [h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i]) for i in r]
    return yn, err


def _hermite(t0, t1, y0, f0, y1, f1, t):
    h = t1 - t0
    s = (t - t0) / h
    s2, s3 = s * s, s * s * s
    h00 = 2 * s3 - 3 * s2 + 1
    h10 = s3 - 2 * s2 + s
    h01 = -2 * s3 + 3 * s2
    h11 = s3 - s2
    return [h00 * a + h10 * h * fa + h01 * b + h11 * h * fb for a, fa, b, fb in zip(y0, f0, y1, f1)]


def _illinois(g, a, b, ga, gb, tol):
    """Root of g on [a, b] with ga > 0 >= gb: Illinois modification of regula falsi."""
    side = 0
    for _ in range(60):
        cpt = (a * gb - b * ga) / (gb - ga)
        gc = g(cpt)
        if gc > 0:
            a, ga = cpt, gc
            if side == 1:
                gb *= 0.5
            side = 1
        else:
            b, gb = cpt, gc
            if side == -1:
                ga *= 0.5
            side = -1
        if b - a < tol:
            break
    return b


def _simulate(P, n_break, t_max):
    """Integrate the hybrid system until n_break breakaways (or t_max).  Returns the step table and events."""
    rhs_stick, rhs_slip, g_stick, vslide, needed = _make_model(P)
    Tn = 1.0 / P["fn"]
    xs = P["x_scale"]
    vs = xs * 2 * math.pi * P["fn"]
    atol = [1e-6 * xs, 1e-6 * vs, 1e-6 * xs, 1e-6 * vs, 1e-6 * xs * Tn, 1e-5, 1e-5, 1e-5,
            1e-6 * P["N0"], 1e-6 * P["N0"] * P["f_N"] * 6.3]
    rtol = 1e-6
    v_eps = 1e-6 * vs  # a sliding speed this small is an arrest
    sub = P["gsub"]  # max spacing of guard samples inside a step (normal-load vibration) or 0
    y = [0.0] * NS
    y[6], y[7], y[8] = P["Ht0"], 1.0, P["N0"]
    t = 0.0
    mode = STICK
    sdir = 1.0
    f = rhs_stick
    k1 = f(t, y)
    h = Tn / 50
    hmax = Tn / 6
    T0, T1, Y0, F0, Y1, F1, MODE = [], [], [], [], [], [], []
    breaks, arrests = [], []
    nb = 0
    gprev = g_stick(t, y)
    skip = False  # the first step after a breakaway: the sliding speed leaves 0
    nrej = 0
    while t < t_max and nb < n_break:
        if h > hmax:
            h = hmax
        yn, err = _cash_karp(f, t, y, h, k1)
        en = 0.0
        for i in range(NS):
            q = abs(err[i]) / (atol[i] + rtol * abs(yn[i]))
            if q > en:
                en = q
        if not en <= 1.0:
            nrej += 1
            if mode == SLIP and not skip:
                # a trial step across v = 0 meets the friction's sign change: aim the next trial just short of
                # the crossing (linear in v) instead of creeping up on it by rejections
                va_, vb_ = sdir * vslide(t, y), sdir * vslide(t + h, yn)
                if va_ > 0 and vb_ < 0:
                    h *= max(0.01, 0.98 * va_ / (va_ - vb_))
                    continue
            h *= max(0.2, 0.9 * en ** -0.25) if en == en else 0.2
            if nrej > 200000:
                raise RuntimeError("step size underflow")
            continue
        t1 = t + h
        k1n = f(t1, yn)
        if mode == STICK:
            def gfun(tt, _t=t, _t1=t1, _y=y, _k=k1, _yn=yn, _kn=k1n):
                return g_stick(tt, _hermite(_t, _t1, _y, _k, _yn, _kn, tt))
            g1 = g_stick(t1, yn)
        else:
            def gfun(tt, _t=t, _t1=t1, _y=y, _k=k1, _yn=yn, _kn=k1n, _s=sdir):
                return _s * vslide(tt, _hermite(_t, _t1, _y, _k, _yn, _kn, tt))
            g1 = sdir * vslide(t1, yn)
        hit = None
        if not skip:
            ta, ga = t, gprev
            if sub and mode == STICK and h > sub:
                nsub = int(math.ceil(h / sub))
                for j in range(1, nsub):
                    tj = t + h * j / nsub
                    gj = gfun(tj)
                    if ga > 0 and gj <= 0:
                        hit = (ta, tj, ga, gj)
                        break
                    ta, ga = tj, gj
            if hit is None and ga > 0 and g1 <= 0:
                hit = (ta, t1, ga, g1)
            if hit is None and mode == SLIP and g1 < v_eps and g1 < gprev:
                hit = "here"  # the sliding speed is at 0 to within v_eps: the event is this step's end
        if hit is None:
            T0.append(t); T1.append(t1); Y0.append(y); F0.append(k1); Y1.append(yn); F1.append(k1n)
            MODE.append(mode)
            t, y, k1 = t1, yn, k1n
            gprev = g1 if g1 > 0 or not skip else 1e-30
            skip = False
            h *= min(5.0, max(0.2, 0.9 * (en + 1e-12) ** -0.2))
            continue
        if hit == "here":
            T0.append(t); T1.append(t1); Y0.append(y); F0.append(k1); Y1.append(yn); F1.append(k1n)
            MODE.append(mode)
            te, ye = t1, yn
        else:
            te = _illinois(gfun, hit[0], hit[1], hit[2], hit[3], 1e-9 * Tn)
            if te - t > 1e-12 * Tn:  # retake the step exactly to the event
                ye, _ = _cash_karp(f, t, y, te - t, k1)
                ke = f(te, ye)
                T0.append(t); T1.append(te); Y0.append(y); F0.append(k1); Y1.append(ye); F1.append(ke)
                MODE.append(mode)
            else:
                ye = y
        t, y = te, list(ye)
        F, lim = needed(t, y)
        if mode == STICK:
            sdir = 1.0 if F >= 0 else -1.0
            y[1] = vslide(t, y) + y[1]  # the pin leaves at the flat's speed
            mode, f = SLIP, rhs_slip
            breaks.append(t)
            nb += 1
            skip = True
            gprev = 0.0
        elif abs(F) <= lim:
            mode, f = STICK, rhs_stick
            arrests.append(t)
            y[1] = vslide(t, y) + y[1]
            gprev = g_stick(t, y)
            if gprev <= 0:
                gprev = 1e-30
        else:  # cannot hold: slides on in the direction of the force the contact cannot carry
            sdir = 1.0 if F >= 0 else -1.0
            skip = True
            gprev = 0.0
        k1 = f(t, y)
        h = min(h, Tn / 100)
    return dict(T0=np.array(T0), T1=np.array(T1), Y0=np.array(Y0), F0=np.array(F0), Y1=np.array(Y1),
                F1=np.array(F1), MODE=np.array(MODE), breaks=np.array(breaks), arrests=np.array(arrests),
                t_end=t, n_steps=len(T0), n_rejected=nrej)


def _dense(sim, tg):
    """Cubic Hermite evaluation of the state on the grid tg (vectorised); also the mode per sample."""
    T0, T1 = sim["T0"], sim["T1"]
    idx = np.searchsorted(T1, tg, side="left")
    idx = np.clip(idx, 0, len(T1) - 1)
    t0, t1 = T0[idx], T1[idx]
    h = (t1 - t0)[:, None]
    s = ((tg - t0) / (t1 - t0))[:, None]
    s2, s3 = s * s, s * s * s
    Y = ((2 * s3 - 3 * s2 + 1) * sim["Y0"][idx] + (s3 - 2 * s2 + s) * h * sim["F0"][idx]
         + (-2 * s3 + 3 * s2) * sim["Y1"][idx] + (s3 - s2) * h * sim["F1"][idx])
    return Y, sim["MODE"][idx]


def _signals(P, sim, tg):
    """Ground-truth signals on tg: spring force, friction force, normal load, sliding and drive speeds.  The
    friction is evaluated from the interpolated state by the law itself (slip) or as the force the contact
    carries (stick), not by differentiating the interpolant."""
    Y, mode = _dense(sim, tg)
    x, u, Xm, Vm, I, H, Ht, th = (Y[:, i] for i in range(8))
    k, m, c = P["k"], P["m"], P["c"]
    am = P["a_m"]
    if am > 0:
        km = 2 * math.pi / P["p_m"]
        a = km * Xm + P["phi_m"]
        e1 = 1 + am * (np.sin(a) + P["r2"] * np.sin(2 * a + P["psi"]))
        e2 = am * km * (np.cos(a) + 2 * P["r2"] * np.cos(2 * a + P["psi"]))
    else:
        e1, e2 = np.ones_like(x), np.zeros_like(x)
    Vd = Vm * e1
    stick = mode == STICK
    u = np.where(stick, Vd, u)
    nl = 1 + P["cx"] * (x - P["xm"])
    if P["a_t"]:
        nl = nl + P["a_t"] * np.sin(2 * math.pi * P["f_t"] * tg + P["phi_t"])
    NL = P["N0"] * nl
    # stick: the force the contact carries
    vr = P["vref"].np(tg)
    upi = P["Kp"] * (vr - Vm) + P["Ki"] * I
    dVm = (upi - e1 * (m * Vm * Vm * e2 + k * x + c * Vd) - P["bd"] * Vm) / (P["Md"] + m * e1 * e1)
    F_st = m * (dVm * e1 + Vm * Vm * e2) + k * x + c * Vd
    # slip: the law
    v = Vd - u
    va = np.abs(v)
    s = np.where(v >= 0, 1.0, -1.0)
    hs = np.sqrt(H * H + Ht * Ht)
    q = hs ** P["n_phi"]
    phi = 1 / (1 + q)
    ff = np.where(hs > 0, q / np.where(hs > 0, hs, 1.0) * phi, 0.0)
    mub = P["mu_bk"] + P["beta_b"] * np.log1p(va / P["v_b"]) + P["Delta_w"] * (1 - th)
    mu = phi * mub + P["mu_h0"] * (va / P["v_h"]) * ff
    if P["normal_mode"]:
        N = Y[:, 8]
        F_sl = s * mu * N
    else:
        F_sl = s * mu * NL / (1 - P["gamma"] * s * mu)
        N = NL + P["gamma"] * np.where(stick, F_st, F_sl)
    Ff = np.where(stick, F_st, F_sl)
    return dict(x=x, u=u, Xm=Xm, Vm=Vm, Vd=Vd, v=np.where(stick, 0.0, v), Ff=Ff, N=N, stick=stick, H=H, Ht=Ht,
                th=th, mu=np.where(stick, np.nan, mu))


# ----------------------------------------------------------------------------------------------------------
# measurements on the ground truth
# ----------------------------------------------------------------------------------------------------------
def _slips(sim, t_a, t_b):
    br, ar = sim["breaks"], sim["arrests"]
    out = []
    for tb in br:
        if tb < t_a or tb > t_b:
            continue
        later = ar[ar > tb]
        if len(later) == 0 or later[0] > t_b:
            continue
        prev = ar[ar < tb]
        tprev = prev[-1] if len(prev) else None
        out.append((tb, later[0], tprev))
    return out


def _measure(P, sim, t_a, t_b):
    k = P["k"]
    sl = _slips(sim, t_a, t_b)
    tw, tw1, twm, peaks, drops, tst, dur, vpk, dist = [], [], [], [], [], [], [], [], []
    for tb, te, tp in sl:
        tg = np.linspace(tb, te, 401)
        S = _signals(P, sim, tg)
        drop = k * (S["x"][0] - S["x"][-1])
        drops.append(drop)
        peaks.append(k * S["x"][0])
        dur.append(te - tb)
        dist.append(np.trapezoid(np.abs(S["v"]), tg))
        if tp is not None:
            tst.append(tb - tp)
        else:
            tst.append(np.nan)
        for vv, store in ((S["v"], tw), (P["v0n"] - S["u"], tw1), (S["v"], twm)):
            i = int(np.argmax(vv))
            vpk_ = vv[i]
            if store is tw:
                vpk.append(vpk_)
            if i < 5 or i > 395:
                continue
            lev = np.linspace(0.15, 0.85, 15) * vpk_
            acc_v, acc_f = vv[: i + 1], S["Ff"][: i + 1]
            dec_v, dec_f = vv[i:][::-1], S["Ff"][i:][::-1]
            if store is twm:  # the friction coefficient F/N: the law's own double-valuedness
                r_ = S["Ff"] / S["N"] * np.mean(S["N"])
                acc_f, dec_f = r_[: i + 1], r_[i:][::-1]
            fa = np.interp(lev, np.maximum.accumulate(acc_v), acc_f)
            fd = np.interp(lev, np.maximum.accumulate(dec_v), dec_f)
            store.append(float(np.mean(fd - fa)) / drop)
    peaks, drops, tst = np.array(peaks), np.array(drops), np.array(tst)
    out = dict(n_slips=len(sl), drop=float(np.mean(drops)) if len(drops) else float("nan"),
               drop_over_peak=float(np.mean(drops) / np.mean(peaks)) if len(drops) else float("nan"),
               trough_over_peak=float(1 - np.mean(drops) / np.mean(peaks)) if len(drops) else float("nan"),
               twin=float(np.mean(tw)) if tw else float("nan"),
               twin_ideal_drive=float(np.mean(tw1)) if tw1 else float("nan"),
               twin_of_mu=float(np.mean(twm)) if twm else float("nan"),
               slip_duration_Tn=float(np.mean(dur) * P["fn"]) if dur else float("nan"),
               slip_distance=float(np.mean(dist)) if dist else float("nan"),
               v_peak=float(np.mean(vpk)) if vpk else float("nan"))
    ok = np.isfinite(tst)
    if ok.sum() >= 3:
        lt = np.log(tst[ok])
        rng_t = lt.max() - lt.min()
        if rng_t > 0.05:
            b = np.polyfit(lt, peaks[ok], 1)[0]
            g = b * rng_t
        else:
            g = 0.0
        out.update(stick_time_ratio=float(np.exp(rng_t)), peak_growth_of_peak=float(g / np.mean(peaks)),
                   peak_growth_of_drop=float(g / np.mean(drops)),
                   peak_sd_of_drop=float(np.std(peaks[ok]) / np.mean(drops)))
    tg = np.linspace(t_a, t_b, 20000)
    S = _signals(P, sim, tg)
    N = S["N"]
    out["load_pp"] = float((np.percentile(N, 99.5) - np.percentile(N, 0.5)) / P["N0"])
    vr = P["vref"].np(tg[::20])
    vr3 = P["vref"].np(tg[::20] - 3 / P["fn"])
    vd = S["Vd"][::20]
    steady = (vr > 0) & (np.abs(vr - vr3) <= 1e-9 * vr)
    if P["a_m"] == 0:
        rel = vd[steady] / vr[steady] - 1
        out["drive_dip"] = float(-rel.min())
        out["drive_surge"] = float(rel.max())
    out["f_ss"] = len(sl) / (t_b - t_a) if len(sl) else float("nan")
    return out


# ----------------------------------------------------------------------------------------------------------
def _vref_factory(levels, hold):
    """Velocity reference: levels [(t_start, value)] joined by cosine ramps of length `ramp`; holds [(t0, t1)]
    (the drive brought to rest and restarted by the same ramps).  Scalar, with a vectorised twin `.np`."""
    ts = np.array([a for a, _ in levels], float)
    vs = np.array([b for _, b in levels], float)
    ramp = hold["ramp"]
    holds = hold["holds"]

    tl, vl = [float(a) for a in ts], [float(b) for b in vs]
    bis, cos = bisect.bisect_right, math.cos

    def vref(t):
        i = bis(tl, t) - 1
        if i < 0:
            return 0.0
        v = vl[i]
        dt = t - tl[i]
        if dt < ramp:
            vp = vl[i - 1] if i > 0 else 0.0
            w = 0.5 - 0.5 * cos(math.pi * dt / ramp)
            v = vp + (v - vp) * w
        if not holds:
            return v
        for a, b in holds:
            if a - ramp < t < b + ramp:
                if t <= a:
                    w = 0.5 + 0.5 * math.cos(math.pi * (t - a + ramp) / ramp)
                elif t >= b:
                    w = 0.5 - 0.5 * math.cos(math.pi * (t - b) / ramp)
                else:
                    w = 0.0
                v *= w
        return v

    def vref_np(t):
        t = np.asarray(t, float)
        i = np.searchsorted(ts, t, side="right") - 1
        ic = np.clip(i, 0, len(ts) - 1)
        v = vs[ic].copy()
        vp = np.where(ic > 0, vs[np.maximum(ic - 1, 0)], 0.0)
        dt = t - ts[ic]
        w = 0.5 - 0.5 * np.cos(math.pi * np.clip(dt / ramp, 0, 1))
        v = np.where(dt < ramp, vp + (v - vp) * w, v)
        v = np.where(i < 0, 0.0, v)
        for a, b in holds:
            w = np.ones_like(t)
            w = np.where((t > a - ramp) & (t <= a), 0.5 + 0.5 * np.cos(math.pi * (t - a + ramp) / ramp), w)
            w = np.where((t > a) & (t < b), 0.0, w)
            w = np.where((t >= b) & (t < b + ramp), 0.5 - 0.5 * np.cos(math.pi * (t - b) / ramp), w)
            v = v * w
        return v

    vref.np = vref_np
    return vref


def _draw(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([20260611, ci, seed])
    fn = float(math.exp(rng.uniform(math.log(3.0), math.log(80.0))))
    wn = 2 * math.pi * fn
    k = float(math.exp(rng.uniform(math.log(400.0), math.log(8000.0))))
    m = k / wn ** 2
    zeta = rng.uniform(0.005, 0.02)
    N0 = float(rng.uniform(3.0, 15.0))
    mu_bs = float(rng.uniform(0.14, 0.20))
    mu_bk = mu_bs / rng.uniform(1.06, 1.16)
    mu_h0 = float(rng.uniform(0.015, 0.03))
    n_phi = float(rng.uniform(1.7, 2.4))
    p_h = float(rng.uniform(0.60, 0.72))
    D_est = 2 * N0 * (mu_bs - 0.5 * (mu_bk + mu_h0))
    x_scale = D_est / k
    v_sl = 0.5 * D_est * wn / k
    v_h_factor = float(rng.uniform(0.8, 1.6))
    v_h = v_h_factor * v_sl
    t_st = float(rng.uniform(3.0, 9.0)) / fn
    v0 = D_est / (k * t_st)
    P = dict(fn=fn, k=k, m=m, c=2 * zeta * math.sqrt(k * m), zeta=zeta, N0=N0, mu_bs=mu_bs, mu_bk=mu_bk,
             beta_b=float(rng.uniform(0.0015, 0.003)), v_b=0.05 * v_h, mu_h0=mu_h0, n_phi=n_phi, p_h=p_h,
             v_h=v_h, v_h_factor=v_h_factor, x_scale=x_scale, D_est=D_est, v0n=v0, t_stick_target=t_st)
    # film: fast entrainment and squeeze (its lag is what makes the law double-valued in `none`); a thin trapped
    # layer squeezed out within a fraction of a period (a thick, slow one in `static_ageing`)
    P["L_e"] = float(rng.uniform(0.0006, 0.0012)) * x_scale
    P["tau_q"] = float(rng.uniform(0.0006, 0.0012)) / fn
    P["H_q"] = float(rng.uniform(0.2, 0.35))
    P["Ht0"] = float(rng.uniform(0.03, 0.06))
    P["L_t"] = float(rng.uniform(0.01, 0.02)) * x_scale
    P["tau_t"] = float(rng.uniform(0.01, 0.03)) / fn
    P["L_w"] = float(rng.uniform(0.4, 1.0)) * x_scale
    P["tau_ads"] = float(rng.uniform(0.25, 0.4)) * t_st
    P["Delta_w"] = 0.0
    # lever
    P["gamma"] = float(rng.uniform(0.03, 0.1))
    P["cx"], P["xm"] = 0.0, 0.0
    P["normal_mode"] = False
    P["f_N"] = float(rng.uniform(3.0, 6.0)) * fn
    P["zeta_N"] = float(rng.uniform(0.15, 0.3))
    P["a_t"], P["f_t"], P["phi_t"] = 0.0, 0.0, 0.0
    # drive
    mu_d = float(math.exp(rng.uniform(math.log(200), math.log(2000))))
    wd = float(rng.uniform(1.0, 2.5)) * wn
    zd = float(rng.uniform(0.6, 1.0))
    Md = mu_d * m
    P.update(Md=Md, Kp=2 * zd * wd * Md, Ki=wd * wd * Md, bd=0.0, mu_d=mu_d, omega_d_over_wn=wd / wn, zeta_d=zd)
    P["a_m"], P["r2"], P["psi"], P["phi_m"], P["p_m"] = 0.0, 0.0, 0.0, 0.0, 1.0
    P["n_cycles"] = int(rng.integers(18, 51))
    P["spp"] = float(rng.uniform(20, 100))
    P["rng_state"] = int(rng.integers(0, 2 ** 31))
    return P, rng


def _program(P, rng, case, seed, t_cyc):
    """Drive program: constant, stepped (levels alternate every few cycles) or slide-hold-slide."""
    v0 = P["v0n"]
    Tn = 1 / P["fn"]
    ramp = 0.6 * Tn
    levels = [(0.0, v0)]
    holds = []
    kind = "constant"
    if case == "static_ageing" or (case == "none" and seed % 8 in (2, 5)):
        if case == "static_ageing" and seed % 2 == 1:
            kind = "holds"
        else:
            kind = "steps"
    P["drive_kind"] = kind
    if kind == "steps":
        rho = float(rng.uniform(4.0, 8.0))
        P["step_ratio"] = rho
        # a stepping programme runs on a finer lead (the same motor): the reflected inertia and the loop gains
        # grow by rho, so the drive's dips and surges stay a few % at the slow level too
        P["Md"] *= rho
        P["Kp"] *= rho
        P["Ki"] *= rho
        # fast segments of 3-5 cycles, slow segments of 2-3 cycles (a slow cycle lasts ~rho times longer)
        t = 3 * t_cyc
        hi = True
        levels = [(0.0, v0)]
        tt = t
        while tt < 400 * t_cyc:
            if hi:
                levels.append((tt, v0 / rho))
                tt += float(rng.integers(2, 4)) * t_cyc * rho * 0.85
            else:
                levels.append((tt, v0))
                tt += float(rng.integers(3, 6)) * t_cyc
            hi = not hi
    elif kind == "holds":
        P["step_ratio"] = 1.0
        tt = 3.3 * t_cyc
        mult = [1.5, 4, 8, 2, 6, 1, 3, 10]
        j = int(rng.integers(0, 8))
        while tt < 400 * t_cyc:
            th = mult[j % 8] * t_cyc * float(rng.uniform(0.8, 1.2))
            holds.append((tt, tt + th))
            tt += th + float(rng.integers(4, 7)) * t_cyc + 0.37 * t_cyc
            j += 1
    P["levels"] = [(float(a), float(b)) for a, b in levels]
    P["holds"] = [(float(a), float(b)) for a, b in holds]
    P["vref"] = _vref_factory(levels, dict(ramp=ramp, holds=holds))


def _run(P, n_break, t_max):
    return _simulate(P, n_break, t_max)


def _build(case, seed):
    """Draw, calibrate and run the rig for one (case, seed).  Returns P, sim, record window and measurement."""
    P, rng = _draw(case, seed)
    Tn = 1 / P["fn"]
    P["gsub"] = 0.0
    t_cyc = P["t_stick_target"] + 0.6 * Tn
    # case set-up (before the calibration run)
    if case == "static_ageing":
        P["Ht0"] = float(rng.uniform(0.35, 0.7))
        P["L_t"] = float(rng.uniform(0.015, 0.03)) * P["x_scale"]
    if case == "twin_branch":
        P["Delta_w"] = 0.45 * P["D_est"] / P["N0"] * float(rng.uniform(0.8, 1.2))
    if case == "triggering":
        # a clear static-kinetic gap and a film that weakens the slip: the shaker triggers the slips, it does not
        # arrest them (a gap smaller than the load swing turns the record into chatter)
        P["mu_bk"] = P["mu_bs"] / float(rng.uniform(1.11, 1.16))
        P["v_h"] = float(rng.uniform(0.8, 1.1)) * P["v_h"] / P["v_h_factor"]
        P["v_b"] = 0.05 * P["v_h"]
    if case == "load_variation":
        P["normal_mode"] = True
        P["gamma"] = float(rng.uniform(0.25, 0.6))
        P["cx"] = 0.0  # the bell crank is set after the calibration run (the lever's sprag and mode only)
    target_tw = float(rng.uniform(0.13, 0.21))
    target_load = float(rng.uniform(0.15, 0.3))
    target_age_drop = float(rng.uniform(0.08, 0.15))  # peak growth over the stick-time range, of the drop
    target_age = 0.55 * target_age_drop  # the same of the peak, for a drop ~0.55 of the peak
    P["targets"] = dict(twin=target_tw, load_pp=target_load, age_of_drop=target_age_drop)
    # calibration run (constant drive): slip size, stick-slip frequency
    P["vref"] = _vref_factory([(0.0, P["v0n"])], dict(ramp=2 * Tn, holds=[]))
    # (a second pass sets v0 so that the stick lasts t_stick_target)
    for attempt in range(4):
        cal = _run(P, 8, 400 * t_cyc)
        if len(cal["breaks"]) < 8:
            # no stick-slip: slow down the drive
            P["v0n"] *= 0.5
            P["vref"] = _vref_factory([(0.0, P["v0n"])], dict(ramp=2 * Tn, holds=[]))
            continue
        t_a, t_b = cal["arrests"][2], cal["breaks"][-1]
        M = _measure(P, cal, t_a, t_b)
        t_st_meas = 1 / M["f_ss"] - M["slip_duration_Tn"] * Tn
        if attempt >= 1 and abs(t_st_meas / P["t_stick_target"] - 1) < 0.25:
            break
        P["v0n"] *= float(np.clip(t_st_meas / P["t_stick_target"], 0.3, 1.6))
        P["vref"] = _vref_factory([(0.0, P["v0n"])], dict(ramp=2 * Tn, holds=[]))
    else:
        raise RuntimeError(f"{NAME}: calibration failed for {case} seed {seed}")
    t_cyc = 1 / M["f_ss"]
    P["drop_cal"] = M["drop"]
    if case == "twin_branch" and np.isfinite(M["twin"]) and M["twin"] > 0.02:
        P["Delta_w"] *= float(np.clip(target_tw / M["twin"], 0.3, 3.0))
    if case == "load_variation":
        P["xm"] = float(np.mean(_signals(P, cal, np.linspace(t_a, t_b, 2000))["x"]))
        # a falling load (c < 0: seeds 3 mod 4) raises the friction through each slip and shrinks it: only on a
        # law whose slips are large against the friction level, and with a smaller swing
        falling = seed % 4 == 3 and M["drop_over_peak"] >= 0.45
        if falling:
            target_load = float(rng.uniform(0.11, 0.16))
            P["targets"]["load_pp"] = target_load
        # a rising load must not lift the static limit as fast as the spring loads it (the stick would never end):
        # mu_s N0 c <= 0.5 k
        P["c_max"] = 0.5 * P["k"] / (P["mu_bs"] * P["N0"])
        P["cx"] = (-1.0 if falling else 1.0) * min(target_load / (M["drop"] / P["k"]), P["c_max"])
    if case == "static_ageing":
        # squeeze time from the shortest stick (the fast level) for 2 t/tau_t in 0.5-2
        t_short = t_cyc - M["slip_duration_Tn"] * Tn
        P["tau_t"] = 2 * t_short / float(rng.uniform(0.5, 2.0))
    if case == "triggering":
        P["a_t"] = float(rng.uniform(0.03, 0.08))
        P["phi_t"] = float(rng.uniform(0, 2 * math.pi))
    if case == "drive_modulation":
        P["a_m"] = float(rng.uniform(0.20, 0.45))
        P["r2"] = float(rng.uniform(0.2, 0.3)) if seed % 2 == 1 else 0.0
        P["psi"] = float(rng.uniform(0, 2 * math.pi))
        P["phi_m"] = float(rng.uniform(0, 2 * math.pi))
        P["fm_ratio"] = float(rng.uniform(0.15, 0.4))
        P["p_m"] = P["v0n"] / (P["fm_ratio"] * M["f_ss"])
    _program(P, rng, case, seed, t_cyc)
    warm = 3
    n_cyc = P["n_cycles"]
    if case == "static_ageing":
        # the trapped layer's thickness for the target growth, from the squeeze law and the expected range of
        # stick times: phi(Ht(t_long)) / phi(Ht(t_short)) - 1 = target, Ht(t) = Ht0 / sqrt(1 + 2 t / tau_t)
        t_short = t_cyc - M["slip_duration_Tn"] * Tn
        if P["drive_kind"] == "steps":
            t_long = P["step_ratio"] * t_short
        else:
            t_long, before = t_short, 0.0
            for a, b in P["holds"]:
                if (a - before) / t_cyc > warm + n_cyc:
                    break
                t_long = max(t_long, t_short + (b - a))
                before += b - a
        P["t_stick_range_expected"] = [t_short, t_long]

        def growth(h0):
            p1 = 1 / (1 + (h0 / math.sqrt(1 + 2 * t_long / P["tau_t"])) ** P["n_phi"])
            p0 = 1 / (1 + (h0 / math.sqrt(1 + 2 * t_short / P["tau_t"])) ** P["n_phi"])
            return p1 / p0 - 1

        lo, hi = 0.05, 1.5
        for _ in range(50):
            mid = 0.5 * (lo + hi)
            if growth(mid) < target_age:
                lo = mid
            else:
                hi = mid
        P["Ht0"] = 0.5 * (lo + hi)
    tries = 6 if case == "triggering" else 3 if case in ("static_ageing", "load_variation") else \
        2 if case == "twin_branch" else 1
    best = None
    for attempt in range(tries):
        if case == "triggering":
            # a triggered stick-slip locks readily to the shaker (f_t/f_ss an integer: the line at f_t is then a
            # harmonic of the stick-slip), unpredictably in f_t: draw f_t afresh until a run is not locked
            P["f_t"] = float(rng.uniform(2.5, 8.0)) * P["fn"]
            P["gsub"] = 1.0 / (P["f_t"] * 8)
        t_hold = sum(b - a for a, b in P["holds"])
        sim = _run(P, warm + n_cyc + 1, 15 * (warm + n_cyc + 1) * t_cyc * P.get("step_ratio", 1.0) + t_hold)
        br, ar = sim["breaks"], sim["arrests"]
        if len(br) < warm + n_cyc + 1:
            if case == "load_variation" and attempt < tries - 1:
                P["cx"] *= 0.5
                continue
            raise RuntimeError(f"{NAME}: no stick-slip for {case} seed {seed}")
        t_a = 0.5 * (ar[warm - 1] + br[warm])
        t_b = 0.5 * (ar[warm + n_cyc - 1] + br[warm + n_cyc])
        M = _measure(P, sim, t_a, t_b)
        if case == "triggering":
            r = P["f_t"] / M["f_ss"]
            M["ft_over_fss"] = float(r)
            M["drop_over_unforced_drop"] = float(M["drop"] / P["drop_cal"])
            chatter = M["drop"] < 0.6 * P["drop_cal"]  # the shaker arrests the slips: weaken it
            score = abs(r - round(r)) - (1.0 if chatter else 0.0)
            if best is None or score > best[0]:
                best = (score, sim, t_a, t_b, M, P["a_t"], P["f_t"])
            if score >= 0.15:
                break
            if chatter:
                P["a_t"] = max(0.03, 0.7 * P["a_t"])
            if attempt == tries - 1:  # the least locked of the runs
                _, sim, t_a, t_b, M, P["a_t"], P["f_t"] = best
                M = dict(M)
                P["gsub"] = 1.0 / (P["f_t"] * 8)
        elif case == "static_ageing":
            g = M.get("peak_growth_of_drop", 0.0)
            if 0.06 <= g <= 0.2 or attempt == tries - 1:
                break
            # growth ~ Ht0^n
            P["Ht0"] = float(np.clip(P["Ht0"] * (target_age_drop / max(g, 0.01)) ** (1 / P["n_phi"]), 0.05, 1.5))
        elif case == "twin_branch":
            if 0.1 <= M["twin"] <= 0.25 or attempt == tries - 1:
                break
            P["Delta_w"] *= float(np.clip(target_tw / max(M["twin"], 0.02), 0.3, 3.0))
        elif case == "load_variation":
            # a falling load (c < 0) raises the friction through each slip: it must not swamp the slip itself
            swamped = P["cx"] < 0 and M["twin"] > 0.6
            if (0.1 <= M["load_pp"] <= 0.4 and not swamped) or attempt == tries - 1:
                break
            if swamped:
                if M["load_pp"] <= 0.125:
                    break
                P["cx"] *= 0.6
            else:
                P["cx"] *= float(np.clip(target_load / max(M["load_pp"], 1e-3), 0.3, 3.0))
                P["cx"] = float(np.clip(P["cx"], -P["c_max"], P["c_max"]))
    if case == "drive_modulation":
        M["fm_over_fss"] = float(P["v0n"] / P["p_m"] / M["f_ss"])
    return P, sim, t_a, t_b, M


# ----------------------------------------------------------------------------------------------------------
def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    P, sim, t_a, t_b, M = _build(case, seed)
    rng = np.random.default_rng([P["rng_state"], NUISANCES.index(nuisance)])
    fmt_rng = np.random.default_rng([P["rng_state"], 7])  # record format: same for every nuisance
    fn = P["fn"]
    Tn = 1 / fn
    drop = M["drop"]
    k = P["k"]
    spp = P["spp"] if nuisance != "coarse" else float(rng.uniform(10, 15))
    dt = Tn / spp
    OS = 4
    n_out = int((t_b - t_a) / dt)
    # the fine grid starts before the record so the filters settle; the piezo is reset at t = 0 (unloaded)
    t_pre = min(t_a, 30 * Tn)
    n_pre = int(t_pre / dt)
    tg = t_a - n_pre * dt + np.arange((n_pre + n_out) * OS) * (dt / OS)
    S = _signals(P, sim, tg)
    # ---- record format
    kind = "force" if fmt_rng.random() < 0.5 else "displacement"
    sep = ["comma", "tab", "space"][int(fmt_rng.integers(0, 3))]
    piezo = kind == "force" and fmt_rng.random() < 0.5
    f_unit = "N" if fmt_rng.random() < 0.5 else "mN"
    p_unit = "mm" if fmt_rng.random() < 0.5 else "um"
    if case == "load_variation":
        has_normal = True
    else:
        has_normal = fmt_rng.random() < 0.5
    if case == "static_ageing" or P["drive_kind"] != "constant":
        has_drive = True
    elif case == "drive_modulation":
        has_drive = False
    else:
        has_drive = fmt_rng.random() < 0.4
    # ---- sensors
    fs = 1 / dt
    fc = float(fmt_rng.uniform(0.25, 0.4)) * fs
    b, a = signal.bessel(2, fc, fs=fs * OS, norm="mag")
    Fspring = k * S["x"]
    if piezo:
        # charge amplifier reset with the pin unloaded (t = 0, F = 0); a first-order high-pass of time constant
        # tau_hp >> the run: output = F - (1/tau) int_0^t F (to first order in t/tau < 1/60)
        tau_hp = float(fmt_rng.uniform(60, 200)) * tg[-1]
        Fpre = float(np.mean(Fspring[: max(1, OS * n_pre)])) * tg[0]  # the leak before the grid starts
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (Fspring[1:] + Fspring[:-1])) * (dt / OS)])
        Fsig = Fspring - (Fpre + cum) / tau_hp
    else:
        tau_hp = None
        Fsig = Fspring
    zi = signal.lfilter_zi(b, a)
    Ff_meas = signal.lfilter(b, a, Fsig, zi=zi * Fsig[0])[0]
    Nm = signal.lfilter(b, a, S["N"], zi=zi * S["N"][0])[0]
    sl = slice(n_pre * OS, None, OS)
    t_out = tg[sl] - tg[sl][0] + float(fmt_rng.uniform(0, 2)) * dt
    F_out = Ff_meas[sl].copy()
    N_out = Nm[sl].copy()
    Xm_out = S["Xm"][sl]
    n = len(t_out)
    # motor encoder: quadrature counts of lead / (4 CPR); a finer (interpolated) encoder where a count would be
    # more than the drive travels in a sample at its slowest level
    lead = float(fmt_rng.choice([1e-3, 2e-3, 5e-3]))
    cpr = float(fmt_rng.choice([500, 1000, 2500]))
    v_slow = P["v0n"] / P.get("step_ratio", 1.0)
    while lead / (4 * cpr) > v_slow * dt and cpr < 1e7:
        cpr *= 4
    res = lead / (4 * cpr)
    counts = np.floor(Xm_out / res)
    pos_out = counts * res
    # white noise
    sig_n = float(rng.uniform(0.002, 0.006)) * drop
    F_out += rng.normal(0, sig_n, n)
    N_out += rng.normal(0, sig_n * 0.5 + 0.001 * P["N0"] * 0.2, n)
    # ---- nuisances on the main channel (and normal, proportionally)
    nu = {}
    if nuisance == "hum":
        fh = 50.0 if rng.random() < 0.5 else 60.0
        amp = float(rng.uniform(0.01, 0.05)) * drop
        ph = rng.uniform(0, 2 * math.pi, 3)
        hum = amp * (np.sin(2 * math.pi * fh * t_out + ph[0]) + 0.3 * np.sin(2 * math.pi * 3 * fh * t_out + ph[1])
                     + 0.15 * np.sin(2 * math.pi * 2 * fh * t_out + ph[2]))
        F_out += hum
        N_out += 0.5 * hum
        nu = dict(f_hum=fh, amp_of_drop=amp / drop)
    elif nuisance == "drift":
        amp = float(rng.uniform(0.02, 0.06)) * drop * (1 if rng.random() < 0.5 else -1)
        s = t_out / t_out[-1]
        F_out += amp * (0.7 * s + 0.3 * np.sin(0.5 * math.pi * s) ** 2)
        nu = dict(amp_of_drop=amp / drop)
    elif nuisance == "spikes":
        frac = float(rng.uniform(0.0005, 0.005))
        ns = max(3, int(frac * n))
        ii = rng.choice(n, ns, replace=False)
        F_out[ii] += rng.choice([-1, 1], ns) * rng.uniform(0.3, 1.5, ns) * drop
        nu = dict(fraction=ns / n)
    elif nuisance == "quantisation":
        q = float(rng.uniform(0.002, 0.01)) * drop
        F_out = np.round(F_out / q) * q
        N_out = np.round(N_out / q) * q
        nu = dict(step_of_drop=q / drop)
    elif nuisance == "coarse":
        nu = dict(samples_per_period=spp)
    # ---- columns
    cols, heads = [t_out], ["time [s]"]
    args = []
    if kind == "force":
        fs_ = 1.0 if f_unit == "N" else 1e3
        cols.append(F_out * fs_)
        heads.append(f"friction [{f_unit}]")
        if has_normal:
            cols.append(N_out * fs_)
            heads.append(f"normal [{f_unit}]")
        if has_drive:
            ps = 1e3 if p_unit == "mm" else 1e6
            cols.append(pos_out * ps)
            heads.append(f"position [{p_unit}]")
        args += ["--stiffness", f"{k:.6g}"]
    else:
        cols.append(F_out / k * 1e3)
        heads.append("x [mm]")
        if has_normal:
            gy = float(fmt_rng.uniform(0.02, 0.2)) / P["N0"]  # mm per N
            y0 = float(fmt_rng.uniform(-1, 1))
            cols.append(y0 + gy * N_out)
            heads.append("y [mm]")
        if has_drive:
            # controller's speed readout: encoder counts differenced over a window
            w = max(1, int(round(0.125 * Tn / dt)))
            i = np.arange(n)
            lo, hi = np.maximum(i - w, 0), np.minimum(i + w, n - 1)
            vcol = (counts[hi] - counts[lo]) * res / ((hi - lo) * dt)
            cols.append(vcol * 1e3)
            heads.append("v0 [mm/s]")
    if not has_drive:
        args += ["--v0", f"{P['v0n'] * 1e3:.6g}"]
    fn_given = None
    if _OMIT_FN[case] is None or seed % 8 != _OMIT_FN[case]:
        fn_given = fn
        if nuisance == "fn_off":
            fn_given = fn * (1 + (0.05 if rng.random() < 0.5 else -0.05))
        args = ["--fn", f"{fn_given:.6g}"] + args
    data = np.column_stack(cols)
    os.makedirs(outdir, exist_ok=True)
    ext = ".csv" if sep == "comma" else ".txt"
    path = os.path.abspath(os.path.join(outdir, f"{NAME}_{case}_s{seed}_{nuisance}{ext}"))
    delim = {"comma": ",", "tab": "\t", "space": " "}[sep]
    fmts = ["%.7f"] + ["%.7g"] * (data.shape[1] - 1)
    header = delim.join(heads) if sep != "space" else " ".join(h.replace(" [", "[") for h in heads)
    np.savetxt(path, data, fmt=fmts, delimiter=delim, header=header, comments="")
    params = {kk: vv for kk, vv in P.items() if kk not in ("vref",) and not callable(vv)}
    params = _jsonable(params)
    params.update(record=dict(kind=kind, sep=sep, piezo=piezo, tau_hp=tau_hp, force_unit=f_unit,
                              pos_unit=p_unit, normal=has_normal, drive_column=has_drive, samples_per_period=spp,
                              anti_alias_hz=fc, noise_of_drop=sig_n / drop, encoder_res_m=res, screw_lead_m=lead, encoder_cpr=cpr, n_samples=n,
                              nuisance=nu),
                  measured=_jsonable(M))
    return dict(generator=NAME, case=case, seed=seed, nuisance=nuisance, file=path, args=args, fn_true=fn,
                fn_given=fn_given, params=params)


def _jsonable(d):
    if isinstance(d, dict):
        return {str(k): _jsonable(v) for k, v in d.items()}
    if isinstance(d, (list, tuple)):
        return [_jsonable(v) for v in d]
    if isinstance(d, (np.floating, float)):
        v = float(d)
        return v if math.isfinite(v) else None
    if isinstance(d, (np.integer, int)) and not isinstance(d, bool):
        return int(d)
    if isinstance(d, (bool, np.bool_)):
        return bool(d)
    return d
