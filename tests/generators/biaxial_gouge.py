"""Biaxial double-direct-shear gouge experiment: rate-and-state (slip law) stick-slip records.

Written without reading the diagnosis (``python/lieng/diagnose/``, ``lieng.analysis.synth``, the Fortran
slider, ``tests/test_diagnose*.py``) or the other generators' code.

**The rig.**  A rock-mechanics biaxial apparatus: a central forcing block sheared between two layers of
granular gouge, a horizontal ram servo-holding the normal stress sigma_n (5-25 MPa), a vertical ram driven
at a constant load-point velocity (a lab's round set point, 35-2200 um/s) through the machine's finite
stiffness per area k (3-12 MPa/mm).  The forcing block (with the ram's moving parts) has a mass per area
m = k / (2 pi fn)^2, fn 6-80 Hz: the 1-DoF natural frequency with the contact stuck, returned as
``fn_true``.  All in um, s, MPa; the shear stress on the layers is the machine's k (x_lp - delta).

**Friction (rate and state, slip law).**  tau = (sigma_n - p) mu,
mu = mu0 + a ln(1 + v/V0) + a_c ln(v/V0) + b1 psi1 [+ b2 ln(1 + theta2/theta_c)],
psi1' = -(v/Dc) (psi1 + ln(v/V0)) (the **slip / Ruina law**: the state heals only by slip, not with time),
with the Linker-Dieterich normal-stress term (psi1 shifts by -(alpha/b1) ln(sigma_e/sigma_e0) where the
normal stress moves, alpha 0.1-0.25 / 0.25-0.4 in load_variation / triggering, 0 elsewhere).  The direct
effect a (0.003-0.008) is cut off below V0 = 3-10x the fastest drive (Okubo-type cut-off); the small creep
coefficient a_c = 0.08-0.15 a keeps ln v finite at any stress; b1 - a = 0.004-0.008 (0.010-0.014 with the
shaker, so that its 3-4 % of sigma_n stays a trigger and does not turn the stick-slip into vibrating
sliding); k = k_crit/8..k_crit/25, k_crit = (b1 - a) sigma_e / Dc (Dc 0.18-2.7 um).  Stress drops
0.06-0.31 sigma_e, top slip speeds 20-160x the drive.

**Stick handling.**  No true stick.  The slip rate is a state in log form, u = ln(v/V0) (no back-slip, no
band, no regularisation at v = 0).  Above 1e-2 of the drive the block is fully inertial.  Once the speed
falls below 3e-3 of the drive after a slip, the block is taken as **quasi-static creep**: its inertia
(relaxation time m v/(sigma a_c) < 1e-4 s there) is dropped and ln v is algebraic, solved each evaluation
from k s = sigma_e mu(v) by Newton and projected after each step (creep speeds fall to 1e-15..1e-159 of
the drive in mid-stick); it returns to the inertial equations when the creep passes 1e-2 of the drive.

**Integrator.**  Own variable-step **modified Rosenbrock ode23s** (Shampine & Reichelt 1997, an L-stable
2(3) pair, one LU of I - h d J per step, analytic Jacobian and df/dt for the shaker / modulated drive),
step control on scaled absolute errors (ln v's error weighted by v/(v + v_lp): absolute below the drive),
ln v changing at most ~2.5 a step, steps <= 1/(16 f_t) with the shaker except deep in stick; its own
continuous extension onto a grid 4x the record's rate.  Drive steps and holds are breakpoints scheduled by
the slip count.  Convergence (tolerance / 8, which halves the error-controlled steps; 1.6-1.7x as many
steps): period and drop change by 0.06-0.45 % (none 0, 1; load 0; twin 2; ageing 1; modulation 0), the
twin by <= 0.002 of the drop, the peak growth by <= 0.0005, sigma_n's p-p by 0.0013 of sigma0; triggering 7
(tolerance / 8 and the shaker step halved): period 0.15 %, drop 0.2 %, its (forcing-phase dependent) twin
reading -0.002 -> +0.03.

**Cases** (measured on the record's own simulated truth, seeds 0-7, clean; ``params["measured"]``):

- ``none``: constant sigma_n and drive; seeds 1, 3, 5, 7 step the drive through 3-5 levels spanning 4-6x
  (the LP column records it), 4-8 cycles a level.
- ``load_variation``: the normal stress follows the motion: a wedge-coupled frame makes sigma_n follow the
  shear load (gain cw, set on pilot runs), plus the layers' dilatancy against the horizontal ram (10-30 %
  of that, through psi1), corrected by the servo over 3-10 stick-slip periods.  sigma_n p-p per cycle
  12.7-29.3 % of sigma0, recorded.  tau against v then reads a twin of -0.53..-0.38 of the drop, tau/sigma_n
  -0.003..-0.001 (it is the load).
- ``twin_branch``: **dilatancy hardening**: porosity phi' = (v/L_d)(phi0 + eps ln(1 + v/v_lp) - phi) -
  (phi - phi0)/t_c (dilates over L_d = 0.3-0.7 of a slip's displacement, compacts in stick over 0.2-0.5 of a
  period), pore pressure p' = -phi'/beta - (p - p_inf)/t_f (drained over 1-3 periods; p_inf 10-30 % of
  sigma_n): p falls during the slip, sigma_e rises, the decelerating half runs at a higher friction.  eps set
  on pilot runs.  Twin (decelerating minus accelerating friction at equal speed, 0.25-0.85 of the slip's top
  speed, over the drop): +0.154..+0.212 (a 1-DoF reading of the clean transducer +0.156..+0.212).  sigma_n
  (total, the ram's reading) constant; p is not recorded.
- ``static_ageing``: a second state with the Kato-Tullis composite evolution, theta2' = exp(-v/v_c) -
  (v theta2/D2) ln(v theta2/D2) (heals with time in stick, reset by slip), adding b2 ln(1 + theta2/theta_c)
  (theta_c 0.3-1 stick time: no part in the sliding friction).  Even seeds: drive steps 4-8x (2-3 levels
  alternating), odd seeds: slide-hold-slide, 3-5 holds of 3-30 stick times (load point stopped).  b2 set
  from the pilot and corrected once against a run with b2 = 0.  Peak growth across the stick times over the
  drop (least-squares line of the peak on ln stick time, across the range): +0.097..+0.278 in the record,
  of which beyond the law's own (the b2 = 0 run): +0.086..+0.180 (stick times 7.5-30x apart; the law's own
  growth is 0.000 on the hold records and +0.13..+0.19 on the stepped ones, see ``none``).
- ``triggering``: the horizontal ram vibrates, sigma_n (1 + A sin(2 pi f_t t)), A 3-4 % (p-p 6.0-7.9 %),
  f_t 4.5-6.5 fn; f_t re-drawn (up to 4 times) while the record's f_t/f_ss is within 0.15 of an integer:
  f_t/f_ss 30-58, 0.21-0.48 from an integer.  Slips start at the troughs; the shaker moving sigma_n within
  each slip makes tau against v read a twin of 0.00..+0.40 (tau/sigma_n -0.06..-0.01).
- ``drive_modulation``: v_lp (1 + a sin(2 pi fm t + phi)), a 0.23-0.42, fm/f_ss 0.15-0.41 (measured on the
  record); no LP column, only ``--v0`` (the nominal set point, mm/s).

**What ``none`` shows** (seeds 0-7): the law's own twin -0.009..-0.003 of the drop (state lag; 1-DoF reading
of the clean transducer -0.009..-0.001); constant-drive records are exact limit cycles (peak scatter < 1e-5
of the drop before noise); sigma_n exactly constant.  On the stepped-drive seeds the peak **grows with the
stick time by +0.12..+0.14 of the drop** (sticks 5.9-7.9x apart): the slip law heals during the slower
pre-slip creep of a slower drive (the classic rate dependence of stick-slip strength: (b - a) ln v at the
creep speeds), an ageing-like memory inherent in rate and state that a single-valued mu(v) does not have.
Expect these four records to be read as ageing; the constant-drive ones carry no such signal.

**Records** (style by seed + case): a lab export with the shear stress, the normal stress (always in
load_variation / triggering, 3 of 4 others), the load point's LVDT (um or mm; not in drive_modulation):
``Rec_Num,Time (s),LP_Disp (um),Shear_Stress (MPa),Normal_Stress (MPa)`` with 4 metadata lines (comma);
TAB ``time [ms]  lp_disp [mm]  shear stress [kPa]  normal stress [kPa]`` under two ``#`` lines; whitespace
``Record Time_s LP_Disp_um Shear_Stress_MPa Normal_Stress_MPa`` under metadata lines; comma
``Time,LP_Disp,Shear_Stress,Normal_Stress`` with a units row ``s,mm,MPa,MPa``.  Lab clock offsets on the
time, an LVDT offset on the position.  Sensors: 2-pole Butterworth conditioners (min(8-30 fn, 0.25-0.4 fs);
the normal channel >= 2 f_t with the shaker), one-pole LVDT, white + 1/f noise (0.05-0.3 % + 0.05-0.3 % of
the drop on the shear, 0.03-0.15 % of sigma_n on the normal), 16/18/24-bit ADC over a 10-100 MPa range,
LVDT counts of 0.01-0.1 um.  20-100 samples per natural period (coarse 10-15; hum records >= 320 Hz),
21-37 cycles, 4 000-126 000 samples.  ``--fn`` on 7 of 8 seeds (seed mod 8 = 3, 4, 5, 7, 1, 2 for the six
cases has none); no ``--stiffness`` (a stress record: the reader takes k per area from the sticks).
Nuisances as the interface asks (hum 50/60 Hz + harmonics on both stress channels 1-5 % of the drop; drift
2-6 % of the drop; spikes 0.05-0.5 % of the samples; ADC step 0.2-1 % of the drop; coarse; fn_off +-5 %).
0.4-2.1 s a record.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from scipy import signal
from scipy.linalg import lu_factor, lu_solve

NAME = "biaxial_gouge"
CASES = ["none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation"]
NUISANCES = ["clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off"]

# the seed (mod 8) of each case on which no --fn is given (never the fn_off seed 6)
_NO_FN = {"none": 3, "load_variation": 4, "twin_branch": 5, "static_ageing": 7, "triggering": 1,
          "drive_modulation": 2}

# state vector: spring (machine) extension s [um], u = ln(v/V0), psi1 = ln(V0 theta1/Dc),
# psi2 = ln(V0 theta2/D2) (ageing state), porosity phi, pore pressure p [MPa], servo normal stress [MPa]
NS = 7
_D = 1.0 / (2.0 + math.sqrt(2.0))
_E32 = 6.0 + math.sqrt(2.0)


# ----------------------------------------------------------------------------------------------
# the rig's equations
# ----------------------------------------------------------------------------------------------
def _make_rhs(P):
    """f(t, y), its Jacobian J = df/dy and T = df/dt for the block on the machine's spring.
    Units: um, s, MPa (stress = force per area), mass per area in MPa s^2/um."""
    k, m, V0 = P["k"], P["m"], P["V0"]
    a, ac, b1, b2, mu0 = P["a"], P["ac"], P["b1"], P["b2"], P["mu0"]
    Dc, alpha = P["Dc"], P["alpha"]
    sig0 = P["sig0"]
    D2, vc, psic = P["D2"], P["vc"], P["psic"]
    eps, Ld, vd, phi0, tc, beta, tf, pinf = (P["eps"], P["Ld"], P["vd"], P["phi0"], P["tc"], P["beta"],
                                             P["tf"], P["pinf"])
    cw, cd, Ts = P["cw"], P["cd"], P["Ts"]
    At, wt, pht = P["At"] * sig0, P["wt"], P["pht"]
    am, wm, phm = P["am"], P["wm"], P["phm"]
    dil, age, load, trig, mod = eps > 0.0, b2 > 0.0, cw != 0.0, At > 0.0, am > 0.0
    exp, log1p = math.exp, math.log1p
    la, se0 = alpha / b1, sig0 - pinf

    def rhs(t, y, lvl, want_j=True, qs=False):
        s, u, p1, p2, phi, pp, ss = y
        if trig:
            st, ct = math.sin(wt * t + pht), math.cos(wt * t + pht)
            sn = ss + At * st
        else:
            sn = ss
        se = sn - pp
        if se <= 0.0:
            return None, None, None
        # Linker-Dieterich: the state shifts by -(alpha/b1) ln(se/se0) with the effective normal stress;
        # p1 carries the part that evolves with slip (the slip law)
        ps1 = p1 - la * math.log(se / se0) if la > 0.0 else p1
        if age:
            z2 = p2 - psic
            if z2 > 0.0:
                e2 = math.exp(-z2)
                sp2, sg2 = z2 + log1p(e2), 1.0 / (1.0 + e2)
            else:
                e2 = math.exp(z2)
                sp2, sg2 = log1p(e2), e2 / (1.0 + e2)
        else:
            sp2 = sg2 = 0.0
        if qs:
            # quasi-static creep: the slip rate from the stress, k s = se mu(u) (Newton from the right)
            rest = mu0 + b1 * ps1 + b2 * sp2
            u = (k * s / se - rest) / ac
            for _ in range(30):
                if u > 30.0:
                    return None, None, None
                e = exp(u) if u < 0.0 else 1.0
                spu = log1p(e) if u < 0.0 else u + log1p(exp(-u))
                G = rest + a * spu + ac * u - k * s / se
                du = G / (a * (e / (1.0 + e) if u < 0.0 else 1.0 / (1.0 + exp(-u))) + ac)
                u -= du
                if abs(du) < 1e-11:
                    break
            y[1] = u
        elif not (-700.0 < u < 40.0):
            return None, None, None
        v = V0 * exp(max(u, -740.0))
        if u > 0.0:
            e = exp(-u)
            sp = u + log1p(e)
            sg = 1.0 / (1.0 + e)
        else:
            e = exp(u)
            sp = log1p(e)
            sg = e / (1.0 + e)
        mu = mu0 + a * sp + ac * u + b1 * ps1 + b2 * sp2
        g = a * sg + ac
        vl = lvl * (1.0 + am * math.sin(wm * t + phm)) if mod else lvl
        if dil:
            A = v / Ld
            lg = log1p(v / vd)
            dphi = A * (phi0 + eps * lg - phi) - (phi - phi0) / tc
            dpp = -dphi / beta - (pp - pinf) / tf
        else:
            dphi = dpp = 0.0
        dps = -(v / Dc) * (u + ps1)
        # normal servo: the wedge-coupled frame (sigma_n follows the shear load), the layers' dilatancy
        # (psi1 falls as the gouge dilates) against the horizontal ram, the servo's slow correction
        dss = cw * k * (vl - v) - cd * dps - (ss - sig0) / Ts if load else 0.0
        dsn = dss + (At * wt * ct if trig else 0.0)
        mv = m * v
        f = np.empty(NS)
        f[0] = vl - v
        f[2] = dps
        if age:
            h2 = (V0 / D2) * exp(-p2 - v / vc)
            f[3] = h2 - (v / D2) * (u + p2)
        else:
            f[3] = 0.0
        f[4] = dphi
        f[5] = dpp
        f[6] = dss
        if qs:
            f1 = (k * f[0] - (dsn - dpp) * (mu - alpha) - se * (b1 * f[2] + b2 * sg2 * f[3])) / (se * g)
        else:
            f1 = (k * s - se * mu) / mv
        f[1] = f1
        if not want_j:
            return f, None, None
        J = np.zeros((NS, NS))
        J[0, 1] = -v
        if not qs:
            J[1, 0] = k / mv
            J[1, 1] = -se * g / mv - f1
            J[1, 2] = -se * b1 / mv
            J[1, 3] = -se * b2 * sg2 / mv
            J[1, 5] = (mu - alpha) / mv
            J[1, 6] = -(mu - alpha) / mv
        J[2, 1] = -(v / Dc) * (u + ps1 + 1.0)
        J[2, 2] = -v / Dc
        J[2, 6] = (v / Dc) * la / se
        J[2, 5] = -J[2, 6]
        if age:
            J[3, 3] = -h2 - v / D2
            J[3, 1] = -h2 * v / vc - (v / D2) * (u + p2 + 1.0)
        if dil:
            dd_phi = -A - 1.0 / tc
            dd_u = A * (phi0 + eps * lg - phi) + A * eps * (v / vd) / (1.0 + v / vd)
            J[4, 4] = dd_phi
            J[4, 1] = dd_u
            J[5, 4] = -dd_phi / beta
            J[5, 1] = -dd_u / beta
            J[5, 5] = -1.0 / tf
        if load:
            J[6, 1] = -cw * k * v + cd * (v / Dc) * (u + ps1 + 1.0)
            J[6, 2] = cd * v / Dc
            J[6, 6] = -1.0 / Ts - cd * J[2, 6]
        T = np.zeros(NS)
        if mod:
            T[0] = lvl * am * wm * math.cos(wm * t + phm)
        if trig:
            T[1] = 0.0 if qs else -(mu - alpha) * At * wt * ct / mv
            T[2] = (v / Dc) * la / se * At * wt * ct
        if qs:
            # u is algebraic in stick: no row or column for it (the step projects it afterwards)
            J[1, :] = 0.0
            J[:, 1] = 0.0
            T[1] = 0.0
        return f, J, T

    return rhs


def _u_quasistatic(t, Y, P):
    s, u, p1, p2, phi, pp, ss = Y.T
    sn = ss + (P["At"] * P["sig0"] * np.sin(P["wt"] * t + P["pht"]) if P["At"] > 0 else 0.0)
    se = sn - pp
    ps1 = p1 - P["alpha"] / P["b1"] * np.log(se / (P["sig0"] - P["pinf"]))
    rest = P["mu0"] + P["b1"] * ps1 + (P["b2"] * np.logaddexp(0.0, p2 - P["psic"]) if P["b2"] > 0 else 0.0)
    x = P["k"] * s / se
    u = (x - rest) / P["ac"]
    for _ in range(40):
        e = np.exp(np.minimum(u, 0.0))
        G = rest + P["a"] * np.logaddexp(0.0, u) + P["ac"] * u - x
        sg = np.where(u < 0, e / (1.0 + e), 1.0 / (1.0 + np.exp(-np.maximum(u, 0.0))))
        du = G / (P["a"] * sg + P["ac"])
        u = u - du
        if np.max(np.abs(du)) < 1e-10:
            break
    return u


def _friction(t, Y, P):
    """The law's friction (MPa), the slip rate (um/s) and the normal stress on arrays of states."""
    s, u, p1, p2, phi, pp, ss = Y.T
    v = P["V0"] * np.exp(u)
    sn = ss + (P["At"] * P["sig0"] * np.sin(P["wt"] * t + P["pht"]) if P["At"] > 0 else 0.0)
    ps1 = p1 - P["alpha"] / P["b1"] * np.log((sn - pp) / (P["sig0"] - P["pinf"]))
    mu = (P["mu0"] + P["a"] * np.logaddexp(0.0, u) + P["ac"] * u + P["b1"] * ps1
          + P["b2"] * np.logaddexp(0.0, p2 - P["psic"]))
    return (sn - pp) * mu, v, sn


# ----------------------------------------------------------------------------------------------
# the integrator: Shampine-Reichelt modified Rosenbrock (ode23s) with its own step control
# ----------------------------------------------------------------------------------------------
class _Drive:
    """Load-point velocity schedule, advanced at the end of each slip (events by slip count)."""

    def __init__(self, level0, kind="const", steps=None, holds=None, tail=0.5):
        self.level0 = level0
        self.kind = kind
        self.steps = steps or {}     # slip number -> (delay in ref sticks, new level)
        self.holds = holds or {}     # slip number -> (delay in ref sticks, hold in ref sticks)
        self.tail = tail
        self.ref_stick = None
        self.level = level0

    def after_slip(self, n, t, stick, n_warm):
        if n == n_warm:
            self.ref_stick = stick
        ev = []
        rs = self.ref_stick or stick
        if n in self.steps:
            d, lv = self.steps[n]
            ev.append((t + d * rs, lv))
            self.level = lv
        if n in self.holds:
            d, hd = self.holds[n]
            ev.append((t + d * rs, 0.0))
            ev.append((t + (d + hd) * rs, self.level))
        return ev


def _simulate(P, drive, n_warm, n_rec, dt_grid, tol=1.0, hmax=None, t_lim=None):
    """Integrate until n_warm + n_rec slips have ended (+ a tail of stick).  Returns the fine grid,
    the states on it (dense output), slip onsets and ends, the drive's segments and step counts."""
    rhs = _make_rhs(P)
    sc = P["scale"] * tol
    y = np.array(P["y0"], float)
    t = 0.0
    lvl = drive.level0
    lvl_ref = drive.level0
    f0, J, T = rhs(t, y, lvl)
    h = 1e-3 / P["fn"]
    hbase = 2.0 / P["fn"]
    # with the shaker the steps resolve its period, except deep in stick where even its troughs leave
    # the creep below 1e-6 of the drive (u's swing with the forcing: u_amp)
    u_amp = (P["mu0"] - P["alpha"] + 0.1) * P["At"] * P["sig0"] / ((P["sig0"] - P["pinf"]) * P["ac"]) + 2.0
    I = np.eye(NS)
    gt, gy, gq = [], [], []
    last_grid = -1
    in_slip = False
    onsets, ends = [], []
    events = []
    segs = [(0.0, lvl)]            # (time, level) from then on
    t_stop = t_lim or 1e12
    nacc = nrej = 0
    hu = np.inf
    qs = False
    exp = math.exp
    while t < t_stop - 1e-12:
        tb = min(events[0][0] if events else t_stop, t_stop)
        if hmax is not None and (not qs or y[1] + u_amp > math.log(1e-6 * lvl_ref / P["V0"])):
            hcap = hmax
        else:
            hcap = hbase
        hh = min(h, hcap, tb - t, hu)
        if tb - t - hh < 1e-3 * hh:
            hh = tb - t
        W = I - (hh * _D) * J
        lu = lu_factor(W, check_finite=False)
        k1 = lu_solve(lu, f0 + (hh * _D) * T, check_finite=False)
        F1, _, _ = rhs(t + 0.5 * hh, y + (0.5 * hh) * k1, lvl, False, qs)
        if F1 is None:
            h = 0.25 * hh
            nrej += 1
            continue
        k2 = lu_solve(lu, F1 - k1, check_finite=False) + k1
        ynew = y + hh * k2
        if not qs and (abs(ynew[1] - y[1]) > 4.0 or not math.isfinite(ynew[1])):
            h = 0.3 * hh
            nrej += 1
            continue
        F2, J2, T2 = rhs(t + hh, ynew, lvl, True, qs)
        if F2 is None:
            h = 0.25 * hh
            nrej += 1
            continue
        k3 = lu_solve(lu, F2 - _E32 * (k2 - F1) - 2.0 * (k1 - f0) + (hh * _D) * T, check_finite=False)
        err = np.abs((hh / 6.0) * (k1 - 2.0 * k2 + k3)) / sc
        # the slip rate is controlled in absolute terms below the drive's speed (creep in stick)
        if qs:
            err[1] = 0.0          # algebraic in stick: projected, not integrated
        else:
            err[1] /= 1.0 + lvl_ref / (P["V0"] * exp(min(y[1], ynew[1])))
        en = float(err.max())
        if en > 1.0 or not math.isfinite(en):
            h = hh * max(0.2, 0.8 * en ** (-1.0 / 3.0)) if math.isfinite(en) else 0.2 * hh
            nrej += 1
            continue
        nacc += 1
        tn = t + hh
        # dense output (the method's own continuous extension) onto the fine grid
        g1 = int(math.floor(tn / dt_grid + 1e-9))
        if g1 > last_grid:
            idx = np.arange(last_grid + 1, g1 + 1)
            ts = idx * dt_grid
            th = (ts - t) / hh
            c1 = (th * (1.0 - th) / (1.0 - 2.0 * _D))[:, None]
            c2 = (th * (th - 2.0 * _D) / (1.0 - 2.0 * _D))[:, None]
            gt.append(ts)
            gy.append(y[None, :] + hh * (c1 * k1[None, :] + c2 * k2[None, :]))
            gq.append(np.full(ts.size, qs))
            last_grid = g1
        # ln v changes by at most ~2.5 a step (predicted from the last step's change)
        hu = np.inf if qs else 2.5 * hh / max(abs(ynew[1] - y[1]), 1e-12)
        t, y, f0, J, T = tn, ynew, F2, J2, T2
        fac = 5.0 if en < 1e-9 else min(5.0, 0.8 * en ** (-1.0 / 3.0))
        h = max(h, hh * fac) if hh < h else hh * fac
        changed = False
        while events and events[0][0] <= t + 1e-12:
            _, lvl = events.pop(0)
            if lvl > 0:
                lvl_ref = lvl
            segs.append((t, lvl))
            changed = True
        v = P["V0"] * exp(max(y[1], -740.0))
        if not qs and not in_slip and v < 3e-3 * lvl_ref and f0[1] < 0.0:
            qs, changed = True, True           # into stick: quasi-static creep
        elif qs and v > 1e-2 * lvl_ref:
            qs, changed, hu = False, True, np.inf
        if changed:
            f0, J, T = rhs(t, y, lvl, True, qs)
            if f0 is None:
                raise RuntimeError("stick projection failed")
        v = P["V0"] * exp(max(y[1], -740.0))
        if not in_slip and v > 4.0 * lvl_ref:
            in_slip = True
            onsets.append(t)
        elif in_slip and v < lvl_ref:
            in_slip = False
            ends.append(t)
            n = len(ends)
            stick = onsets[-1] - ends[-2] if n >= 2 else onsets[-1]
            events.extend(drive.after_slip(n, t, stick, n_warm))
            events.sort()
            if n == n_warm + n_rec:
                t_stop = t + drive.tail * (drive.ref_stick or stick)
        if nacc + nrej > 400000:
            raise RuntimeError("integration did not finish")
    T, Y, Q = np.concatenate(gt), np.concatenate(gy), np.concatenate(gq)
    if Q.any():
        # in stick the slip rate is algebraic: solve k s = se mu(u) on the grid rather than interpolate
        Y[Q, 1] = _u_quasistatic(T[Q], Y[Q], P)
    return (T, Y, np.array(onsets), np.array(ends), segs, nacc, nrej)


def _lp_position(t, segs, P):
    """The load point's position (um) on times t from the drive's piecewise-constant levels
    (with the modulation integrated exactly)."""
    x = np.zeros_like(t)
    x0 = 0.0
    for i, (ts, lv) in enumerate(segs):
        te = segs[i + 1][0] if i + 1 < len(segs) else np.inf
        sel = (t >= ts) & (t < te)
        if P["am"] > 0:
            F = lambda tt: lv * (tt - P["am"] / P["wm"] * np.cos(P["wm"] * tt + P["phm"]))
            x[sel] = x0 + F(t[sel]) - F(ts)
            if np.isfinite(te):
                x0 = x0 + F(te) - F(ts)
        else:
            x[sel] = x0 + lv * (t[sel] - ts)
            if np.isfinite(te):
                x0 = x0 + lv * (te - ts)
    return x


# ----------------------------------------------------------------------------------------------
# measurements on the simulated record
# ----------------------------------------------------------------------------------------------
def _slips(on, en, t0, t1):
    """Indices i >= 1 of the slips that start and end inside [t0, t1]."""
    return [i for i in range(1, min(len(on), len(en))) if on[i] >= t0 and en[i] <= t1]


def _cycle_table(t, tau, on, en, idx, t1):
    rows = []
    for i in idx:
        w0 = (t >= en[i - 1]) & (t <= en[i])
        nxt = on[i + 1] if i + 1 < len(on) else t1
        w1 = (t >= on[i]) & (t <= nxt)
        if not w0.any() or not w1.any():
            continue
        pk = float(tau[w0].max())
        mn = float(tau[w1].min())
        rows.append((on[i] - en[i - 1], pk, mn, pk - mn))
    return np.array(rows)


def _twin(t, F, v, on, en, idx, drops, lo=0.25, hi=0.85):
    """Decelerating minus accelerating friction at equal speed (lo..hi of the slip's top speed),
    over the slip's stress drop, per slip."""
    out = []
    for i, dr in zip(idx, drops):
        sel = np.where((t >= on[i] - 0.2 * (en[i] - on[i])) & (t <= en[i]))[0]
        if sel.size < 8:
            continue
        vv, ff = v[sel], F[sel]
        j = int(np.argmax(vv))
        vm = vv[j]
        if j < 3 or j > sel.size - 4:
            continue
        va, fa = vv[:j + 1], ff[:j + 1]
        vd, fd = vv[j:][::-1], ff[j:][::-1]
        # keep the monotone envelope of each branch
        ka = np.maximum.accumulate(va) <= va + 1e-12
        kd = np.maximum.accumulate(vd) <= vd + 1e-12
        va, fa, vd, fd = va[ka], fa[ka], vd[kd], fd[kd]
        g = np.linspace(lo, hi, 31) * vm
        g = g[(g > max(va[0], vd[0])) & (g < vm)]
        if g.size < 5:
            continue
        out.append(float(np.mean(np.interp(g, vd, fd) - np.interp(g, va, fa)) / dr))
    return np.array(out)


def _growth(cyc):
    """Peak growth across the record's stick times over the median drop (least-squares line of the
    peak against ln stick time, evaluated across the range) and the stick-time ratio."""
    st, pk, dr = cyc[:, 0], cyc[:, 1], cyc[:, 3]
    r = float(st.max() / st.min())
    if r < 1.3:
        return 0.0, r
    sl = np.polyfit(np.log(st), pk, 1)[0]
    return float(sl * math.log(r) / np.median(dr)), r


def _dist_int(x):
    return abs(x - round(x))


# ----------------------------------------------------------------------------------------------
# the experiment: parameters, drive schedules, the case's departure
# ----------------------------------------------------------------------------------------------
def _lu(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def _base(rng, case):
    sig0 = float(rng.uniform(5.0, 25.0))                       # applied normal stress, MPa
    pinf = float(rng.uniform(0.1, 0.3) * sig0) if case == "twin_branch" else 0.0   # pore pressure
    se = sig0 - pinf
    a = float(rng.uniform(0.003, 0.008))
    bma = float(rng.uniform(0.004, 0.008)) if case != "triggering" else float(rng.uniform(0.010, 0.014))
    rc = float(rng.uniform(8.0, 25.0))                         # k_crit / k
    k = float(rng.uniform(3.0, 12.0)) * 1e-3                   # machine stiffness per area, MPa/um
    fn = _lu(rng, 6.0, 80.0)
    P = dict(sig0=sig0, pinf=pinf, se=se, a=a, b1=a + bma, bma=bma, ac=float(rng.uniform(0.08, 0.15)) * a,
             mu0=float(rng.uniform(0.55, 0.68)), rc=rc, k=k, fn=fn, m=k / (2.0 * math.pi * fn) ** 2,
             Dc=bma * se / (k * rc), c1=float(rng.uniform(3.0, 10.0)),
             alpha=(float(rng.uniform(0.1, 0.25)) if case == "load_variation" else
                    float(rng.uniform(0.25, 0.4)) if case == "triggering" else 0.0),
             b2=0.0, D2=1.0, vc=1.0, psic=0.0, thc=1.0, eps=0.0, Ld=1.0, vd=1.0, phi0=0.2, tc=1.0, beta=1.0, tf=1.0,
             cw=0.0, cd=0.0, Ts=1.0, At=0.0, wt=0.0, pht=0.0, am=0.0, wm=0.0, phm=0.0)
    return P


def _prepare(P, v_init, v_top, drop_est):
    """Reference speed, error scales and the initial state (steady sliding at v_init, nudged)."""
    P["V0"] = P["c1"] * v_top
    if P["b2"] > 0:
        P["psic"] = math.log(P["V0"] * P["thc"] / P["D2"])
    P["drop_est"] = drop_est
    D = drop_est
    P["scale"] = np.array([1e-4 * D / P["k"], 2e-3, 2e-3, 2e-3, 1e-3 * max(P["eps"], 1e-9), 1e-4 * D, 1e-4 * D])
    u0 = math.log(v_init / P["V0"])
    p2 = -u0 if P["b2"] > 0 else 0.0
    mu = (P["mu0"] + P["a"] * math.log1p(math.exp(u0)) + P["ac"] * u0 - P["b1"] * u0
          + P["b2"] * math.log1p(math.exp(p2 - P["psic"])))
    P["y0"] = [1.003 * P["se"] * mu / P["k"], u0, -u0, p2, P["phi0"] + P["eps"] * math.log1p(v_init / P["vd"]),
               P["pinf"], P["sig0"]]


def _run(P, drive, n_warm, n_rec, dt_grid, **kw):
    _prepare(P, drive.level0, max([drive.level0] + [lv for _, lv in drive.steps.values()]), P["drop_est"])
    return _simulate(P, drive, n_warm, n_rec, dt_grid, **kw)


def _pilot_stats(P, drive, n_rec=3, n_warm=2):
    T, Y, on, en, segs, na, nr = _run(P, drive, n_warm, n_rec, 1.0 / (P["fn"] * 16.0))
    tau = P["k"] * Y[:, 0]
    idx = _slips(on, en, en[n_warm - 1] - 1e-9, T[-1])
    cyc = _cycle_table(T, tau, on, en, idx, T[-1])
    F, v, sn = _friction(T, Y, P)
    tw = _twin(T, F, v, on, en, idx, cyc[:, 3])
    period = float(np.mean(np.diff(on[n_warm - 1:]))) if len(on) > n_warm else float(T[-1])
    sn_pp = [float(np.ptp(sn[(T >= en[i - 1]) & (T <= en[i])])) / P["sig0"] for i in idx]
    return dict(period=period, drop=float(np.median(cyc[:, 3])), slip=float(np.median(cyc[:, 3])) / P["k"],
                sn_pp=float(np.median(sn_pp)),
                vmax=float(v.max()), twin=float(np.median(tw)) if tw.size else 0.0, stick=float(np.median(cyc[:, 0])))


def _design(case, seed, rng, P):
    """The drive schedule (relative levels), the record's length and the case's departure, before
    the speed is set by a pilot run."""
    d = dict(n_warm=3, n_rec=int(rng.integers(22, 35)), kind="const", rel=[1.0], seq=[], holds=[])
    if case == "triggering":
        d["Np"] = float(rng.uniform(10.0, 16.0))
        d["n_rec"] = int(rng.integers(21, 29))
    elif case == "none" and seed % 2 == 1 or case == "static_ageing" and seed % 2 == 0:
        R = float(rng.uniform(4.0, 6.0)) if case == "none" else float(rng.uniform(4.0, 8.0))
        nl = int(rng.integers(3, 6)) if case == "none" else int(rng.integers(2, 4))
        rel = list(R ** (-np.linspace(0.0, 1.0, nl)))
        order = list(rng.permutation(nl))
        if case == "static_ageing":            # slow and fast alternate: 4-6 segments
            seq = []
            while len(seq) < int(rng.integers(4, 7)):
                seq += [order[len(seq) % nl]]
            order = seq
        d.update(kind="steps", rel=rel, seq=[float(rel[i]) for i in order], R=R, Np=float(rng.uniform(8.0, 13.0)))
    elif case == "static_ageing":
        nh = int(rng.integers(3, 6))
        hs = np.exp(rng.uniform(math.log(3.0), math.log(30.0), nh))
        i1 = int(rng.integers(nh))
        i2 = (i1 + 1 + int(rng.integers(nh - 1))) % nh
        hs[i1] = float(rng.uniform(20.0, 30.0))       # the longest near the top, the shortest near 3
        hs[i2] = float(rng.uniform(3.0, 5.0))
        d.update(kind="holds", holds=[float(h) for h in hs], Np=float(rng.uniform(12.0, 25.0)))
    else:
        d["Np"] = float(rng.uniform(12.0, 32.0))
    return d


def _make_drive(d, v_base, rng_sched):
    if d["kind"] == "steps":
        seq = [v_base * r for r in d["seq"]]
        nseg = len(seq)
        nper = max(4, d["n_rec"] // nseg)
        steps = {}
        for j in range(1, nseg):
            steps[d["n_warm"] + j * nper] = (float(rng_sched.uniform(0.1, 0.6)), seq[j])
        return _Drive(seq[0], "steps", steps=steps)
    if d["kind"] == "holds":
        nh = len(d["holds"])
        gap = max(3, d["n_rec"] // (nh + 1))
        holds = {}
        for j, hd in enumerate(d["holds"]):
            holds[d["n_warm"] + 2 + j * gap] = (float(rng_sched.uniform(0.05, 0.3)), hd)
        return _Drive(v_base, "holds", holds=holds)
    return _Drive(v_base)


def _simulate_case(case, seed, P, d, rng, spp_fn):
    """Pilot, calibration of the departure, main run.  Returns the run and the record's measurements."""
    n_warm, n_rec = d["n_warm"], d["n_rec"]
    top = max(d["rel"]) if d["kind"] == "steps" else 1.0
    # --- pilot at a guessed speed: set the speed so that the reference level's stick-slip period is
    # Np natural periods
    drop_g = 20.0 * P["bma"] * P["se"]
    v_g = drop_g / (P["k"] * d["Np"] / P["fn"])
    P["drop_est"] = drop_g
    P["vd"] = v_g
    pl = _pilot_stats(dict(P), _Drive(v_g), n_rec=2)
    v_base = v_g * pl["period"] / (d["Np"] / P["fn"])
    v_base = float(float("%.2g" % v_base))             # a lab's round set point, um/s
    if d["kind"] == "steps":
        v_base = v_base / top
    P["drop_est"] = pl["drop"]
    P["vd"] = v_base
    Tss = pl["period"] * v_g / v_base
    meas = {}
    if case == "load_variation":
        # the normal stress follows the shear load (wedge-coupled frame, gain cw) and the gouge's
        # dilatancy (cd per unit of psi1, a fraction of it), corrected by the servo over Ts (several
        # cycles); cw set on pilot runs so that sigma_n swings q sigma0 peak to peak in each cycle
        q = float(rng.uniform(0.13, 0.30))
        fd = float(rng.uniform(0.1, 0.3))
        P["Ts"] = float(rng.uniform(3.0, 10.0)) * Tss
        drv = _Drive(v_base)
        x = q * P["mu0"] / (pl["drop"] / P["se"] + q * P["mu0"])      # mu0 cw, with the drop grown
        for it in range(4):
            P["cw"] = x / P["mu0"]
            P["cd"] = fd * P["cw"] * pl["drop"] / 4.0
            st = _pilot_stats(dict(P), drv, n_rec=3, n_warm=3)
            if abs(st["sn_pp"] - q) < 0.08 * q or it == 3:
                break
            x = min(0.75, x * min(max(q / max(st["sn_pp"], 1e-3), 0.5), 2.0) ** 0.7)
        v_base = float("%.2g" % (v_base * st["period"] / Tss))
        P["vd"] = v_base
        meas["frame_coupling_cw"] = P["cw"]
        meas["dilatancy_coupling_mpa_per_ln"] = P["cd"]
        meas["servo_time_s"] = P["Ts"]
        meas["normal_pp_target"] = q
    elif case == "twin_branch":
        target = float(rng.uniform(0.12, 0.20))
        P["beta"] = float(rng.uniform(0.5, 2.0)) * 1e-3           # storage compressibility, 1/MPa
        P["Ld"] = float(rng.uniform(0.3, 0.7)) * pl["slip"]
        P["tc"] = float(rng.uniform(0.2, 0.5)) * Tss
        P["tf"] = float(rng.uniform(1.0, 3.0)) * Tss
        tw0 = pl["twin"]
        lnv = math.log1p(0.5 * pl["vmax"] / v_g)
        sd = (target - tw0) * pl["drop"] / (0.5 * P["mu0"] * max(lnv, 1.0))    # dilatancy stress, MPa per unit ln
        drv = _Drive(v_base)
        for it in range(3):
            P["eps"] = sd * P["beta"]
            st = _pilot_stats(dict(P), drv, n_rec=4, n_warm=3)
            if abs(st["twin"] - target) < 0.015 or it == 2:
                break
            sd = max(sd * (target - tw0) / max(st["twin"] - tw0, 0.02), 0.05 * sd)
        v_base = float("%.2g" % (v_base * st["period"] / Tss))
        P["vd"] = v_base
        meas["dilatancy_mpa_per_ln"] = sd
        meas["twin_intrinsic_pilot"] = tw0
    elif case == "static_ageing":
        # a second state healing with the time in stick (Kato-Tullis composite evolution) that adds
        # b2 ln(1 + theta2/theta_c) to the strength: ln(1 + t/theta_c) growth with the stick time,
        # reset by each slip, no part in the sliding friction
        g = float(rng.uniform(0.09, 0.17))
        ct = float(rng.uniform(0.3, 1.0))
        t_ref = pl["stick"] * v_g / v_base
        rst = d["R"] if d["kind"] == "steps" else max(d["holds"]) + 1.0
        P["thc"] = ct * t_ref
        P["D2"] = float(rng.uniform(1.0, 3.0)) * P["Dc"]
        P["vc"] = float(rng.uniform(0.1, 0.3)) * v_base * (min(d["rel"]) if d["kind"] == "steps" else 1.0)
        P["b2"] = g * pl["drop"] / (P["se"] * (math.log1p(rst / ct) - math.log1p(1.0 / ct)))
        meas["ageing_target"] = g
        meas["theta_c_over_stick"] = ct
    elif case == "drive_modulation":
        P["am"] = float(rng.uniform(0.22, 0.43))
        P["wm"] = 2.0 * math.pi * float(rng.uniform(0.15, 0.42)) / Tss
        P["phm"] = float(rng.uniform(0.0, 2.0 * math.pi))
    elif case == "triggering":
        P["At"] = float(rng.uniform(0.03, 0.04))
        P["pht"] = float(rng.uniform(0.0, 2.0 * math.pi))
    rs = np.random.default_rng([18, CASES.index(case), seed, 99])
    fs = spp_fn(Tss, d)
    dt = 1.0 / (fs * 4.0)
    hmax = None
    tries = []
    for attempt in range(5 if case == "triggering" else 1):
        if case == "triggering":
            if attempt == 0:
                ft = float(rng.uniform(2.5, min(8.0, 0.3 * fs / P["fn"])))
            else:
                # redraw f_t so that the record's f_t/f_ss falls between integers
                fss = tries[-1][1]
                lo, hi = 2.5 * P["fn"] / fss, min(8.0, 0.3 * fs / P["fn"]) * P["fn"] / fss
                cands = [n + 0.5 for n in range(int(lo), int(hi) + 1) if lo <= n + 0.5 <= hi]
                r = float(rng.choice(cands)) + float(rng.uniform(-0.2, 0.2)) if cands else float(rng.uniform(lo, hi))
                ft = r * fss / P["fn"]
            P["wt"] = 2.0 * math.pi * ft * P["fn"]
            hmax = 1.0 / (16.0 * ft * P["fn"])
        drive = _make_drive(d, v_base, np.random.default_rng([18, CASES.index(case), seed, 7]))
        run = _run(P, drive, n_warm, n_rec, dt, hmax=hmax)
        T, Y, on, en, segs, na, nr = run
        t0 = en[n_warm - 1] + float(rs.uniform(0.2, 0.6)) * (drive.ref_stick or Tss)
        idx = _slips(on, en, t0, T[-1])
        fss = (len(idx) - 1) / (on[idx[-1]] - on[idx[0]])
        if case != "triggering":
            break
        ratio = P["wt"] / (2.0 * math.pi) / fss
        tries.append((run, fss, ratio, dict(P), t0, drive))
        if _dist_int(ratio) >= 0.15:
            break
    if case == "static_ageing":
        # the ageing's size beyond the law's own (the same schedule with b2 = 0), one correction of b2
        def growth_of(rr, PP):
            TT, YY, oo, ee = rr[0], rr[1], rr[2], rr[3]
            t00 = ee[n_warm - 1] + 0.3 * Tss
            ii = _slips(oo, ee, t00, TT[-1])
            return _growth(_cycle_table(TT, PP["k"] * YY[:, 0], oo, ee, ii, TT[-1]))
        P0 = dict(P)
        P0["b2"] = 0.0
        g0, _ = growth_of(_run(P0, _make_drive(d, v_base, np.random.default_rng([18, CASES.index(case), seed, 7])),
                               n_warm, n_rec, 1.0 / (16.0 * P["fn"])), P0)
        g1, rst = growth_of(run, P)
        if not 0.075 <= g1 - g0 <= 0.195:
            P["b2"] *= min(max(meas["ageing_target"] / max(g1 - g0, 0.01), 0.3), 4.0)
            drive = _make_drive(d, v_base, np.random.default_rng([18, CASES.index(case), seed, 7]))
            run = _run(P, drive, n_warm, n_rec, dt, hmax=hmax)
            T, Y, on, en, segs, na, nr = run
            idx = _slips(on, en, t0, T[-1])
            fss = (len(idx) - 1) / (on[idx[-1]] - on[idx[0]])
            g1, rst = growth_of(run, P)
            meas["b2_corrected"] = True
        meas.update(b2=P["b2"], peak_growth_without_ageing=g0, peak_growth_beyond_law=g1 - g0)
    if case == "triggering":
        best = max(tries, key=lambda z: _dist_int(z[2]))
        run, fss, ratio, P2, t0, drive = best
        P.update(P2)
        T, Y, on, en, segs, na, nr = run
        idx = _slips(on, en, t0, T[-1])
        meas.update(f_t_hz=P["wt"] / (2 * math.pi), f_t_over_fn=P["wt"] / (2 * math.pi) / P["fn"],
                    f_t_over_f_ss=ratio, f_t_ratio_dist_from_integer=_dist_int(ratio), f_t_tries=len(tries))
    return dict(T=T, Y=Y, on=on, en=en, segs=segs, steps=na, rejected=nr, t0=t0, idx=idx, fs=fs, dt=dt,
                v_base=v_base, Tss=Tss, fss=fss, drive=drive, meas=meas, pilot=pl)


# ----------------------------------------------------------------------------------------------
# sensors and the file
# ----------------------------------------------------------------------------------------------
def _lowpass(x, fc, fs_f, order=2):
    sos = signal.butter(order, min(fc, 0.45 * fs_f), fs=fs_f, output="sos")
    zi = signal.sosfilt_zi(sos) * x[0]
    return signal.sosfilt(sos, x, zi=zi)[0]


def _pink(n, rn):
    w = np.fft.rfft(rn.standard_normal(n))
    f = np.arange(w.size, dtype=float)
    f[0] = 1.0
    w = w / np.sqrt(f)
    w[0] = 0.0
    p = np.fft.irfft(w, n)
    return p / (p.std() + 1e-300)


def _adc(x, step):
    return np.round(x / step) * step


_STYLES = [
    # separator, time (unit, scale from s), position (name, unit, scale from um), shear, normal, index, header kind
    dict(sep=",", t=("Time (s)", 1.0), x=("LP_Disp (um)", 1.0), tau=("Shear_Stress (MPa)", 1.0),
         sn=("Normal_Stress (MPa)", 1.0), index="Rec_Num", head="meta"),
    dict(sep="\t", t=("time [ms]", 1e3), x=("lp_disp [mm]", 1e-3), tau=("shear stress [kPa]", 1e3),
         sn=("normal stress [kPa]", 1e3), index=None, head="hash"),
    dict(sep="  ", t=("Time_s", 1.0), x=("LP_Disp_um", 1.0), tau=("Shear_Stress_MPa", 1.0),
         sn=("Normal_Stress_MPa", 1.0), index="Record", head="meta"),
    dict(sep=",", t=("Time", 1.0, "s"), x=("LP_Disp", 1e-3, "mm"), tau=("Shear_Stress", 1.0, "MPa"),
         sn=("Normal_Stress", 1.0, "MPa"), index=None, head="units"),
]


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    ci = CASES.index(case)
    rng = np.random.default_rng([18, ci, seed])                 # the physics
    rn = np.random.default_rng([18, ci, seed, 1000 + NUISANCES.index(nuisance)])    # sensors and nuisance
    P = _base(rng, case)
    d = _design(case, seed, rng, P)
    spp_draw = float(rng.uniform(20.0, 100.0))
    spp_coarse = float(rng.uniform(10.0, 15.0))

    def spp_fn(Tss, dd):
        # the record's expected length in stick-slip periods: cycles, slower levels, holds
        if dd["kind"] == "steps":
            mult = float(np.mean([1.0 / r for r in dd["seq"]])) * max(dd["rel"])
        else:
            mult = 1.0
        n_per = (dd["n_rec"] * mult + sum(dd["holds"]) + 1.0) * (1.5 if case == "static_ageing" else 1.0)
        dur = n_per * Tss
        if nuisance == "coarse":
            spp = spp_coarse
        else:
            spp = min(spp_draw, max(20.0, 80000.0 / (dur * P["fn"])))
            if nuisance == "hum":
                spp = min(max(spp, 320.0 / P["fn"]), 100.0)
        return spp * P["fn"]

    r = _simulate_case(case, seed, P, d, rng, spp_fn)
    T, Y, on, en, segs = r["T"], r["Y"], r["on"], r["en"], r["segs"]
    t0, idx, fs, dt = r["t0"], r["idx"], r["fs"], r["dt"]
    sel = T >= t0
    T, Y = T[sel], Y[sel]
    fn = P["fn"]
    tau = P["k"] * Y[:, 0]
    F, v, sn = _friction(T, Y, P)
    xlp = _lp_position(T, segs, P)
    cyc = _cycle_table(T, tau, on, en, idx, T[-1])
    drop = float(np.median(cyc[:, 3]))
    tw_law = _twin(T, F, v, on, en, idx, cyc[:, 3])
    tw_mu = _twin(T, F / sn * P["sig0"], v, on, en, idx, cyc[:, 3])
    growth, st_ratio = _growth(cyc)
    # normal stress: per cycle and over the record
    sn_pp = [float(np.ptp(sn[(T >= en[i - 1]) & (T <= en[i])])) / P["sig0"] for i in idx]

    # --- sensors on the fine grid (4x the record's rate)
    fs_f = 1.0 / dt
    fc_tau = min(float(rn.uniform(8.0, 30.0)) * fn, float(rn.uniform(0.25, 0.4)) * fs)
    fc_sn = min(float(rn.uniform(8.0, 30.0)) * fn, float(rn.uniform(0.25, 0.4)) * fs)
    if P["At"] > 0:
        fc_sn = max(fc_sn, min(2.0 * P["wt"] / (2 * math.pi), 0.45 * fs))
    fc_x = float(rn.uniform(0.1, 0.3)) * fs
    tau_f = _lowpass(tau, fc_tau, fs_f)
    sn_f = _lowpass(sn, fc_sn, fs_f)
    x_f = _lowpass(xlp, fc_x, fs_f, order=1)
    # a 1-DoF reading of the clean transducer signal (friction = tau + tau''/omega^2 - m x_lp'')
    w2 = (2.0 * math.pi * fn) ** 2
    vlp = np.gradient(xlp, T)
    d1 = np.gradient(tau_f, T)
    v1 = vlp - d1 / P["k"]
    F1 = tau_f + np.gradient(d1, T) / w2 - P["m"] * np.gradient(vlp, T)
    tw_rec = _twin(T, F1, v1, on, en, idx, cyc[:, 3])
    ds = 4
    tr, tau_r, sn_r, x_r = T[::ds], tau_f[::ds], sn_f[::ds], x_f[::ds]
    n = tr.size
    tt = tr - tr[0]
    # white + 1/f noise, the ADC
    tau_r = tau_r + drop * (float(rn.uniform(0.0005, 0.003)) * rn.standard_normal(n)
                            + float(rn.uniform(0.0005, 0.003)) * _pink(n, rn))
    sn_r = sn_r + P["sig0"] * (float(rn.uniform(0.0003, 0.0015)) * rn.standard_normal(n)
                               + float(rn.uniform(0.0003, 0.0015)) * _pink(n, rn))
    x_r = x_r + float(rn.uniform(0.01, 0.05)) * rn.standard_normal(n)
    fs_tau = float(rn.choice([10.0, 20.0, 50.0]))
    while fs_tau < 1.3 * tau.max():
        fs_tau *= 2.0
    fs_sn = float(rn.choice([20.0, 50.0, 100.0]))
    while fs_sn < 1.3 * sn.max():
        fs_sn *= 2.0
    bits = int(rn.choice([16, 18, 24]))
    q_tau, q_sn = 2.0 * fs_tau / 2 ** bits, 2.0 * fs_sn / 2 ** bits
    nz = {}
    if nuisance == "hum":
        fm_ = float(rn.choice([50.0, 60.0]))
        ph = rn.uniform(0.0, 2 * math.pi, 3)
        hum = lambda A: A * (np.sin(2 * math.pi * fm_ * tr + ph[0]) + 0.3 * np.sin(4 * math.pi * fm_ * tr + ph[1])
                             + 0.15 * np.sin(6 * math.pi * fm_ * tr + ph[2]))
        A1, A2 = float(rn.uniform(0.01, 0.05)) * drop, float(rn.uniform(0.01, 0.05)) * drop
        tau_r, sn_r = tau_r + hum(A1), sn_r + hum(A2)
        nz.update(hum_hz=fm_, hum_over_drop=A1 / drop)
    elif nuisance == "drift":
        dd = float(rn.uniform(0.02, 0.06)) * drop * float(rn.choice([-1.0, 1.0]))
        pw = float(rn.uniform(0.7, 1.5))
        tau_r = tau_r + dd * (tt / tt[-1]) ** pw
        sn_r = sn_r + float(rn.uniform(-0.008, 0.008)) * P["sig0"] * (tt / tt[-1])
        nz.update(drift_over_drop=dd / drop)
    elif nuisance == "quantisation":
        q = float(rn.uniform(0.002, 0.01)) * drop
        q_tau = q_sn = q
        nz.update(adc_step_over_drop=q / drop)
    tau_r, sn_r = _adc(tau_r, q_tau), _adc(sn_r, q_sn)
    x_r = _adc(x_r, float(rn.choice([0.01, 0.05, 0.1])))
    if nuisance == "spikes":
        ns_ = max(2, int(float(rn.uniform(0.0005, 0.005)) * n))
        k_ = rn.choice(np.arange(5, n - 5), ns_, replace=False)
        tau_r[k_] += drop * rn.uniform(0.1, 0.5, ns_) * rn.choice([-1.0, 1.0], ns_)
        k2 = rn.choice(np.arange(5, n - 5), max(1, ns_ // 4), replace=False)
        sn_r[k2] += P["sig0"] * rn.uniform(0.01, 0.05, k2.size) * rn.choice([-1.0, 1.0], k2.size)
        nz.update(spikes=int(ns_))
    fn_given = fn
    if nuisance == "fn_off":
        fn_given = fn * (1.05 if rn.uniform() < 0.5 else 0.95)
    fn_given = float(f"{fn_given:.5g}")
    give_fn = seed % 8 != _NO_FN[case]

    # --- the file
    style = _STYLES[(seed + ci) % 4]
    rec_pos = case != "drive_modulation"
    rec_sn = case in ("load_variation", "triggering") or rn.uniform() < 0.75
    t_off = float(np.round(rn.uniform(50.0, 3000.0), 1)) if style["index"] else 0.0
    x_off = float(rn.uniform(3000.0, 12000.0))
    cols, names, units, fmts = [], [], [], []
    if style["index"]:
        cols.append(np.arange(1, n + 1))
        names.append(style["index"])
        units.append("#")
        fmts.append("%d")
    tsc = style["t"][1]
    cols.append((tt + t_off) * tsc)
    names.append(style["t"][0])
    units.append(style["t"][2] if len(style["t"]) > 2 else "")
    fmts.append("%.3f" if tsc > 1 else "%.6f")
    if rec_pos:
        cols.append((x_r + x_off) * style["x"][1])
        names.append(style["x"][0])
        units.append(style["x"][2] if len(style["x"]) > 2 else "")
        fmts.append("%.4f" if style["x"][1] == 1.0 else "%.7f")
    cols.append(tau_r * style["tau"][1])
    names.append(style["tau"][0])
    units.append(style["tau"][2] if len(style["tau"]) > 2 else "")
    fmts.append("%.5f" if style["tau"][1] == 1.0 else "%.3f")
    if rec_sn:
        cols.append(sn_r * style["sn"][1])
        names.append(style["sn"][0])
        units.append(style["sn"][2] if len(style["sn"]) > 2 else "")
        fmts.append("%.5f" if style["sn"][1] == 1.0 else "%.3f")
    sep = style["sep"]
    lines = []
    run_id = f"p{4000 + 37 * seed + 211 * ci}"
    if style["head"] == "meta":
        lines += [f"Experiment{sep if sep != '  ' else ' '}{run_id}",
                  f"Apparatus{sep if sep != '  ' else ' '}biaxial DDS with 2 x 3 mm gouge layers",
                  f"Sample rate (Hz){sep if sep != '  ' else ' '}{fs:.1f}",
                  f"Normal stress (MPa){sep if sep != '  ' else ' '}{P['sig0']:.1f}"]
    elif style["head"] == "hash":
        lines += [f"# {run_id}: double-direct shear, granular gouge, servo-controlled normal stress",
                  f"# sigma_n = {P['sig0']:.2f} MPa, logging at {fs:.1f} Hz"]
    lines.append(sep.join(names))
    if style["head"] == "units":
        lines.append(sep.join(units))
    out = Path(outdir) / f"{NAME}_{case}_{seed}_{nuisance}.{'txt' if sep != ',' else 'csv'}"
    with open(out, "w") as fh:
        fh.write("\n".join(lines) + "\n")
        np.savetxt(fh, np.column_stack(cols), fmt=fmts, delimiter=sep)

    args = []
    if give_fn:
        args += ["--fn", f"{fn_given:.5g}"]
    if not rec_pos:
        args += ["--v0", f"{r['v_base'] * 1e-3:.6g}"]
    m_ = dict(r["meas"])
    m_.update(
        n_cycles=len(idx), samples=int(n), samples_per_period=fs / fn, fs_hz=fs, duration_s=float(tt[-1]),
        drop_mpa=drop, drop_over_sigma=drop / P["se"], period_s=float(np.median(np.diff(on[idx]))),
        natural_periods_per_cycle=float(np.median(np.diff(on[idx]))) * fn,
        f_ss_hz=r["fss"], peak_sd_over_drop=float(np.std(cyc[:, 1]) / drop),
        twin_law=float(np.median(tw_law)) if tw_law.size else None,
        twin_law_range=[float(tw_law.min()), float(tw_law.max())] if tw_law.size else None,
        twin_law_of_tau_over_sigma_n=float(np.median(tw_mu)) if tw_mu.size else None,
        twin_1dof_clean=float(np.median(tw_rec)) if tw_rec.size else None,
        peak_growth_over_drop=growth, stick_time_ratio=st_ratio,
        normal_pp_cycle_over_sigma=float(np.median(sn_pp)), normal_pp_over_sigma=float(np.ptp(sn)) / P["sig0"],
        creep_min_over_v=float(np.min(v) / r["v_base"]),
        slip_speed_max_over_v=float(np.max(v) / r["v_base"]),
        integrator_steps=int(r["steps"]), integrator_rejected=int(r["rejected"]),
        sensor_fc_shear_over_fn=fc_tau / fn, adc_bits=bits, style=(seed + ci) % 4,
        normal_recorded=bool(rec_sn), position_recorded=bool(rec_pos))
    if case == "drive_modulation":
        m_.update(mod_amplitude=P["am"], f_m_over_f_ss=P["wm"] / (2 * math.pi) / r["fss"])
    if d["kind"] == "steps":
        m_.update(drive_levels_um_s=[r["v_base"] * x for x in d["rel"]], drive_ratio=d["R"])
    if d["kind"] == "holds":
        m_.update(holds_in_sticks=d["holds"])
    m_.update(nz)
    params = {kk: (float(vv) if isinstance(vv, (int, float, np.floating)) and not isinstance(vv, bool) else vv)
              for kk, vv in P.items() if kk not in ("scale", "y0")}
    params.update(v_lp_um_s=r["v_base"], measured=m_)
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance, "file": str(out.resolve()),
            "args": args, "fn_true": fn, "fn_given": fn_given if give_fn else None, "params": params}
