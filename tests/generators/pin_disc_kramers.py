"""Independent record generator: a pin on a rotating disc held by a torsional spring arm, thermally activated
(Kramers) stick-slip with a stochastic breakaway, written without reading the diagnosis code; numpy/scipy only.

`write_record(case, seed, outdir, nuisance)` follows README.md here; `python pin_disc_kramers.py [CASE ...]` runs
the self-check (6 cases x seeds 0-7, nuisance NUISANCES[seed % 7]; about 7 s on one core, every record < 0.6 s).

The rig (rotational)
--------------------
A pin on a disc track of radius R (4-30 mm) turning at Omega(t) = V(t) / R; the pin sits at the end of an arm of
radius L (40-120 mm) pivoted on a torsional spring k_th (a strain-gauged flexure) with moment of inertia J about the
pivot and a small torsional damping c_th (zeta 1-4 %).  With theta the arm's angle and w = theta':

    J w' = -k_th theta - c_th w + L Ff,     sliding speed of the disc under the pin  v = V(t) - L w

What a lab records: the load cell's torque converted to the tangential force at the pin, F = k_th theta / L
(`--stiffness` k = k_th / L^2 in N/m at the pin), or the arm's deflection at the pin x = L theta (a capacitive
probe on the arm, calibrated to the pin) in mm or um.  fn_true = sqrt(k_th / J) / 2 pi: the arm's natural
frequency with the pin SLIDING (the contact then adds no stiffness, only the friction's slope as a damping, which
is left out, as is c_th: the damped frequency differs by < 0.1 %).  In stick the pin is held by the contact.

Friction: two contact states
----------------------------
* pinned (stick): the pin moves with the disc except for thermally activated creep, a mean hop rate
  v_cr = q V_ref exp((F - F*) / (phi_a N)) (Eyring; q = 0.4-1.5 % of the drive at F*, phi_a N = 3-6 % of the drop,
  so it acts only in the last tenth of the rise), F the spring's force at the pin.  The breakaway is a Poisson
  event with the Kramers rate of escape over a barrier that vanishes at the threshold Fs = mu_s N A(t_st):
      r(F) = r0 exp(-u (N / N0) A (1 - F / Fs)^{3/2})          (u = U0 / kT_eff at N0)
  drawn exactly: the cumulative hazard (trapezoidal per step) against a fresh Exp(1) draw per stick, located in
  the step by linear interpolation.  u and r0 are set from the drop D of a deterministic pilot so that the peak
  force is Gumbel-distributed with its mode at F* = Fs (1 - x*) (x* = 4-10 %) and a standard deviation of
  s_pk D (s_pk = 1.5-3 % drawn; the Gumbel sd is pi/sqrt(6) / |dg/dF| at F*).  The peak then depends on the
  loading rate (ln V: 1.28 s_pk D less per e-fold slower), and a normal-load oscillation moves the barrier.
* sliding: single-valued in the sliding speed (per unit load):
      mu_k(v) = mu1 + alpha ln(1 + v / v1) + Delta exp(-sqrt(v / v_w))   (+ mu_d d in `twin_branch`)
  a stretched-exponential weakening (Delta, v_w 3-12 % of the slip-speed scale) on a mild logarithmic
  strengthening (alpha 0.8-2.5 % of mu_s): falling steeply from mu_k(0+) = 2-5 % below F*/N, a minimum at about
  half the slip speed, rising past it.  A slip starts at v = v_cr (continuous arm speed) and ends when v crosses
  0 within a step (Heun's predictor or corrector; located linearly): the pin is pinned again, its arm speed set
  to the pinned one (the creep there is < 1e-6 of the drive).

Integrator (own, fixed step, no ODE library): stick steps Tn/32 (Tn/(20 ft/fn) with a shaker): the arm angle
advances with the disc's exact track distance S(t) minus the creep integrated by Heun; slip steps Tn/256: Heun
(RK2) on (theta, w, d).  The loop's states are interpolated (cubic Hermite in theta with w) onto a uniform grid of
Tn/256 for the sensor.

Sensor (own): the channel's transducer as a second-order low-pass (10-30 fn, damping 0.35-0.7, exact
first-order-hold discretisation), the amplifier's one-pole anti-alias at 0.25-0.4 of the sampling rate (never
below 8-12 fn: a coarse record is not lagged by it), white
noise 0.08-0.3 % of the drop plus 1/f amplifier noise 0.05-0.2 % (per channel), a 16-bit ADC over a round full
scale (1.3-4x the signal).  The normal load cell the same with its own draws; in displacement records the normal
channel is the loading spring's compression in mm (an affine reading, an offset on half).

Departures (case)
-----------------
* none: constant load, constant drive; only the stochastic peak scatter and the stick creep depart from the
  baseline.
* load_variation (N recorded): even seeds a disc runout / warp: N = N0 (1 + e1 sin(phi + p1) + e2 sin(2 phi + p2))
  with phi = S / R the disc's angle (about 12-45 slip cycles per revolution, the record spans 0.75-1.8 turns);
  odd seeds a pivot axis tilted so the pin rides up or down with the arm's deflection: N = N0 (1 + c (x - xm)),
  c of either sign, calibrated on the run (peak-to-peak 15-35 % of N0 targeted).
* twin_branch: a wear-debris state d (0..1) that builds with the slip distance, d' = (v / l_d)(1 - d), and is
  swept away in stick, d' = -d / tau_c (tau_c 5-15 % of the stick): mu_d d added while sliding, so the
  decelerating half of a slip, debris-laden, rubs harder than the accelerating half at equal speed.  mu_d is
  calibrated on the run (up to 4 runs) to a twin of 13-20 % of the drop (11.5-22 % accepted).
* static_ageing: the barrier and the threshold grow together with the contact's age (from its arrest),
  A = 1 + beta ln(1 + t_st / tau) (tau 0.3-1 fast stick; A = 1 elsewhere); the disc speed steps between two
  levels 4-8x apart in 5-7 blocks of 3-5 slips (block lengths from deterministic pilots of the ageing rig at
  either speed), odd seeds also stop the disc (holds of 1.5-6 fast stick times) in every other slip of the fast
  blocks; beta is calibrated on the run (up to 4 runs) to a peak growth of 9-14 % of the drop (7-16 % accepted)
  across the record's stick times, the ln V rate effect (about -1.28 s_pk D per e-fold) included.  The drive
  is recorded (sliding speed in mm/s, or the encoder's track distance in mm).
* triggering: a normal-load shaker, N = N0 (1 + a sin(2 pi ft t + p)), a 3-8 %, ft 2.5-8 fn (and <= 0.4 of the
  sampling rate).  The shaker moves the barrier by a Fs, far more than the thermal scatter, so the breakaways
  lock to its troughs and each stick lasts a whole number of its periods: ten shaker frequencies spread over the
  range are tried on short runs (15 slips) and taken in the order of their ft / f_ss's distance from an integer
  (sticks mixing n and n + 1 periods) until the full record's is >= 0.15 (up to 8 runs, else the best).
* drive_modulation: V = V0n (1 + a sin(2 pi fm t + p)), a 0.22-0.43, fm 0.12-0.4 f_ss (re-run if the record's
  fm/f_ss leaves 0.1-0.5); only --v0 V0n is given, no drive column.

Records: force (2/3: N or mN, `--stiffness`) or deflection (mm/um); time in s or ms (a third); comma, TAB or
whitespace; units in brackets; `#` comment lines on a third; the drive as a sliding-speed column (mm/s), an
encoder track distance (mm, force records only), the disc's angle (deg, cumulative, encoder counts, with --v0)
or --v0 alone; uneven (jittered 2-8 % of the interval) sampling with 1-3 short gaps (2-6 samples) on a third;
two seeds in eight of none/load/twin/drive (not coarse) long: 70-100 samples/period and the disc slowed so
40-60 cycles make 70 000-170 000 samples; `--fn` on 7 of 8 seeds (one seed per case without, never the fn_off
one: 6 of 48).  A cycle whose slip was cut by a drive step or stop (the pin caught by the slower disc and
broken away again at once) is counted as one slip in the measurements.

Measured (model internals; the self-check's 48 records, and 6 cases x seeds 0-23 x all 7 nuisances = 1008):
* none: peak force sd 1.4-2.8 % of the drop (1008-run: 1.3-3.0 %, median 2.0 %); the contact's twin exactly 0
  (single-valued law); a 1-DoF reading of the clean transducer output (F + c F'/k + m F''/k against
  V - F'/k, true m, c, k) -0.002..+0.000 of the drop (1008-run: -0.005..+0.015, p10-p90 -0.002..+0.005); creep
  at the breakaway 0.4-1.2 % of the drive speed; stick times vary only 1.08-1.17x, but within that range the
  peak rises with the stick time (a later escape is a higher peak: the regression of the peak on ln t_st across
  the 5-95 % range of stick times gives +0.025..+0.071 of the drop; 1008-run +0.024..+0.082): the stochastic
  breakaway's own "ageing-like" correlation, with no ageing in the law.
* load_variation: N peak-to-peak 0.15-0.32 of N0 (runout over 0.91-1.15 turns, 0.75-1.8 on seeds 0-23;
  deflection coupling of either sign); 1008-run 0.13-0.34.
* twin_branch: decelerating minus accelerating friction at equal speed (20-80 % of each slip's top speed,
  median over slips) 0.12-0.16 of the drop (the 1-DoF reading of the clean transducer: 0.12-0.17); 1008-run
  0.115-0.167.
* static_ageing: peak growth (mean peak of the longest quarter of sticks minus the shortest quarter, / drop)
  0.076-0.140, the regression on ln t_st 0.087-0.133, stick times spanning 5.4-9.9x; 1008-run 0.074-0.140.
* triggering: a 0.032-0.079, ft/fn 3.6-7.2, the record's ft/f_ss 0.23-0.48 from an integer (1008-run: >= 0.15
  on 162 of 168, one seed of 24 (22, every nuisance but coarse) at 0.11 after 8 runs: a = 7.5 % locks whatever
  ft); breakaway phase locking to the shaker 0.62-0.93 (mean resultant length); peaks lowered by 0.05-0.32 of
  the drop below the unforced F*.
* drive_modulation: a 0.24-0.39, fm/f_ss 0.22-0.38 (1008-run 0.12-0.38).
"""

import bisect
import json
import math
import os
import time
import zlib

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.signal import cont2discrete, lfilter, lfilter_zi

NAME = "pin_disc_kramers"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
TWOPI = 2.0 * math.pi
GUMBEL_SD = math.pi / math.sqrt(6.0)

def _rng(*keys):
    s = "|".join(str(k) for k in (NAME,) + keys)
    return np.random.default_rng([zlib.crc32(s.encode()), len(s)])


def _logu(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# ------------------------------------------------------------------------------------------------ drive, load
class _Drive:
    """The disc's sliding speed at the track V(t) (m/s) and track distance S(t) (m)."""

    def __init__(self, kind, V0, a=0.0, fm=0.0, ph=0.0, tb=None, vb=None):
        self.kind, self.V0, self.a, self.fm, self.ph = kind, float(V0), float(a), float(fm), float(ph)
        self.w = TWOPI * fm
        if kind == "sched":
            self.tb = [float(x) for x in tb]
            self.vb = [float(x) for x in vb]
            sb = [0.0]
            for i in range(1, len(self.tb)):
                sb.append(sb[-1] + self.vb[i - 1] * (self.tb[i] - self.tb[i - 1]))
            self.sb = sb
            self._tb = np.array(self.tb)
            self._vb = np.array(self.vb)
            self._sb = np.array(sb)

    def V(self, t):
        if self.kind == "const":
            return self.V0
        if self.kind == "mod":
            return self.V0 * (1.0 + self.a * math.sin(self.w * t + self.ph))
        i = bisect.bisect_right(self.tb, t) - 1
        return self.vb[max(i, 0)]

    def S(self, t):
        if self.kind == "const":
            return self.V0 * t
        if self.kind == "mod":
            return self.V0 * (t - self.a / self.w * (math.cos(self.w * t + self.ph) - math.cos(self.ph)))
        i = max(bisect.bisect_right(self.tb, t) - 1, 0)
        return self.sb[i] + self.vb[i] * (t - self.tb[i])

    def Vv(self, t):
        if self.kind == "const":
            return np.full(np.shape(t), self.V0)
        if self.kind == "mod":
            return self.V0 * (1.0 + self.a * np.sin(self.w * t + self.ph))
        i = np.clip(np.searchsorted(self._tb, t, side="right") - 1, 0, None)
        return self._vb[i]

    def Sv(self, t):
        if self.kind == "const":
            return self.V0 * t
        if self.kind == "mod":
            return self.V0 * (t - self.a / self.w * (np.cos(self.w * t + self.ph) - math.cos(self.ph)))
        i = np.clip(np.searchsorted(self._tb, t, side="right") - 1, 0, None)
        return self._sb[i] + self._vb[i] * (t - self._tb[i])


class _Load:
    """Normal load N(t, x, s): x the pin's deflection (m), s the disc's track distance (m)."""

    def __init__(self, kind, N0, **kw):
        self.kind, self.N0 = kind, float(N0)
        self.__dict__.update({k: float(v) for k, v in kw.items()})

    def N(self, t, x, s):
        k = self.kind
        if k == "const":
            return self.N0
        if k == "runout":
            ph = s / self.R
            return self.N0 * (1.0 + self.e1 * math.sin(ph + self.p1) + self.e2 * math.sin(2.0 * ph + self.p2))
        if k == "deflect":
            return self.N0 * max(0.3, 1.0 + self.c * (x - self.xm))
        return self.N0 * (1.0 + self.a * math.sin(TWOPI * self.ft * t + self.p))

    def Nv(self, t, x, s):
        k = self.kind
        if k == "const":
            return np.full(np.shape(t), self.N0)
        if k == "runout":
            ph = s / self.R
            return self.N0 * (1.0 + self.e1 * np.sin(ph + self.p1) + self.e2 * np.sin(2.0 * ph + self.p2))
        if k == "deflect":
            return self.N0 * np.maximum(0.3, 1.0 + self.c * (x - self.xm))
        return self.N0 * (1.0 + self.a * np.sin(TWOPI * self.ft * t + self.p))


# ------------------------------------------------------------------------------------------------ simulation
def _simulate(P, drv, ld, sim_key, t_cap, n_stop=0, t_min=0.0, det=False, beta=0.0, tau_a=1.0, mu_d=0.0,
              ell=1.0, tau_c=1.0, h_st=None):
    """Fixed-step two-state integration.  Stops at the escape that makes n_stop escapes (n_stop > 0), or at the
    first escape after t_min (n_stop == 0), or at t_cap.  det: escape exactly at F* (the pilot)."""
    rng = _rng("sim", *sim_key)
    E_draws = rng.exponential(size=4096)
    ie = 0
    J, kth, cth, L = P["J"], P["k_th"], P["c_th"], P["L"]
    mu_s, xs, mu1, al, v1, Dl, vw = P["mu_s"], P["x_star"], P["mu1"], P["alpha"], P["v1"], P["Delta"], P["v_w"]
    N0, u, r0, q, phia, Vref = P["N0"], P["u"], P["r0"], P["q_creep"], P["phi_a"], P["V_ref"]
    Tn = 1.0 / P["fn"]
    hs = h_st if h_st is not None else Tn / 32.0
    hl = Tn / 256.0
    Nf, Vf, Sf = ld.N, drv.V, drv.S
    exp, sqrt, log1p = math.exp, math.sqrt, math.log1p
    creep_k = q * Vref
    ageing = beta > 0.0
    twin = mu_d > 0.0
    dec_c = math.exp(-hs / tau_c) if twin else 1.0

    t = 0.0
    th = N0 * mu1 * L / kth
    d = 0.0
    mode = 0
    tarr = 0.0
    H = 0.0
    E = E_draws[ie]
    ie += 1
    s = Sf(t)
    om = Vf(t) / L
    T, TH, OM, MD, DB, FF, VR = [t], [th], [om], [0], [d], [kth * th / L], [0.0]
    esc, arr = [], []
    nslip_steps = 0

    while t < t_cap:
        if mode == 0:
            h = hs
            t1 = t + h
            s1 = Sf(t1)
            F = kth * th / L
            N = Nf(t, L * th, s)
            A = 1.0 + beta * log1p((t - tarr) / tau_a) if ageing else 1.0
            Fs = N * mu_s * A
            Fst = Fs * (1.0 - xs)
            e = (F - Fst) / (phia * N)
            vc = creep_k * exp(e if e < 50.0 else 50.0)
            thp = th + ((s1 - s) - h * vc) / L
            Fp = kth * thp / L
            N1 = Nf(t1, L * thp, s1)
            A1 = 1.0 + beta * log1p((t1 - tarr) / tau_a) if ageing else 1.0
            Fs1 = N1 * mu_s * A1
            Fst1 = Fs1 * (1.0 - xs)
            e = (Fp - Fst1) / (phia * N1)
            vc1 = creep_k * exp(e if e < 50.0 else 50.0)
            th1 = th + ((s1 - s) - 0.5 * h * (vc + vc1)) / L
            F1 = kth * th1 / L
            e = (F1 - Fst1) / (phia * N1)
            vc1 = creep_k * exp(e if e < 50.0 else 50.0)
            frac = -1.0
            if det:
                ga, gb = F - Fst, F1 - Fst1
                if gb >= 0.0:
                    frac = -ga / (gb - ga) if gb > ga else 0.0
            else:
                ga, gb = F - Fs, F1 - Fs1
                if gb >= 0.0:
                    frac = -ga / (gb - ga) if gb > ga else 0.0
                else:
                    xa = 1.0 - F / Fs if F < Fs else 0.0
                    ra = r0 * exp(-u * (N / N0) * A * xa * sqrt(xa))
                    xb = 1.0 - F1 / Fs1
                    rb = r0 * exp(-u * (N1 / N0) * A1 * xb * sqrt(xb))
                    Hn = H + 0.5 * h * (ra + rb)
                    if Hn >= E:
                        frac = (E - H) / (Hn - H)
                    else:
                        H = Hn
            om0 = (Vf(t) - vc) / L
            om1 = (Vf(t1) - vc1) / L
            if frac >= 0.0:
                frac = min(max(frac, 0.0), 1.0)
                te = t + frac * h
                th = th + frac * (th1 - th)
                om = om0 + frac * (om1 - om0)
                vce = vc + frac * (vc1 - vc)
                t = te
                s = Sf(t)
                Fe = kth * th / L
                Ne = Nf(t, L * th, s)
                esc.append((t, Fe, t - tarr, Ne, vce / max(Vf(t), 1e-30), len(T)))
                mode = 1
                nslip_steps = 0
                T.append(t); TH.append(th); OM.append(om); MD.append(1); DB.append(d); FF.append(Fe)
                VR.append(vce)
                if (n_stop > 0 and len(esc) >= n_stop) or (n_stop == 0 and t >= t_min):
                    break
                continue
            if twin:
                d *= dec_c
            t, th, om, s = t1, th1, om1, s1
            T.append(t); TH.append(th); OM.append(om); MD.append(0); DB.append(d); FF.append(F1); VR.append(vc1)
        else:
            h = hl
            t1 = t + h
            # stage a
            x = L * th
            N = Nf(t, x, s)
            v = Vf(t) - L * om
            av = v if v >= 0.0 else -v
            fk = N * (mu1 + al * log1p(av / v1) + Dl * exp(-sqrt(av / vw)) + mu_d * d)
            Ff = fk if v >= 0.0 else -fk
            dw1 = (-kth * th - cth * om + L * Ff) / J
            dd1 = av / ell * (1.0 - d) if twin else 0.0
            thp = th + h * om
            omp = om + h * dw1
            dp = d + h * dd1
            s1 = Sf(t1)
            N1 = Nf(t1, L * thp, s1)
            V1 = Vf(t1)
            vp = V1 - L * omp
            if vp <= 0.0 and v > 0.0 and nslip_steps > 0:
                # the predictor crosses v = 0: the pin stops within the step (Euler fraction) -> pinned
                nslip_steps += 1
                frac = v / (v - vp)
                t = t + frac * h
                th = th + frac * h * om
                d = d + frac * h * dd1
                s = Sf(t)
                F = kth * th / L
                N = Nf(t, L * th, s)
                e = (F - N * mu_s * (1.0 - xs)) / (phia * N)
                vc = creep_k * exp(e if e < 50.0 else 50.0)
                om = (Vf(t) - vc) / L
                arr.append((t, F, len(T)))
                mode = 0
                tarr = t
                H = 0.0
                E = E_draws[ie % 4096]
                ie += 1
                T.append(t); TH.append(th); OM.append(om); MD.append(0); DB.append(d); FF.append(F); VR.append(vc)
                continue
            avp = vp if vp >= 0.0 else -vp
            fk = N1 * (mu1 + al * log1p(avp / v1) + Dl * exp(-sqrt(avp / vw)) + mu_d * dp)
            Ffp = fk if vp >= 0.0 else -fk
            dw2 = (-kth * thp - cth * omp + L * Ffp) / J
            dd2 = avp / ell * (1.0 - dp) if twin else 0.0
            th1 = th + 0.5 * h * (om + omp)
            om1 = om + 0.5 * h * (dw1 + dw2)
            d1 = d + 0.5 * h * (dd1 + dd2)
            v1n = V1 - L * om1
            nslip_steps += 1
            F1 = kth * th1 / L
            if v1n <= 0.0 and nslip_steps > 1:
                # arrest: v crosses 0 (the creep speed there is < 1e-6 of the drive) -> pinned
                frac = v / (v - v1n) if v > v1n else 1.0
                frac = min(max(frac, 0.0), 1.0)
                t = t + frac * h
                th = th + frac * (th1 - th)
                d = d + frac * (d1 - d)
                s = Sf(t)
                F = kth * th / L
                N = Nf(t, L * th, s)
                A = 1.0  # a fresh contact
                e = (F - N * mu_s * (1.0 - xs)) / (phia * N)
                vc = creep_k * exp(e if e < 50.0 else 50.0)
                om = (Vf(t) - vc) / L
                arr.append((t, F, len(T)))
                mode = 0
                tarr = t
                H = 0.0
                E = E_draws[ie % 4096]
                ie += 1
                T.append(t); TH.append(th); OM.append(om); MD.append(0); DB.append(d); FF.append(F); VR.append(vc)
                continue
            t, th, om, d, s = t1, th1, om1, d1, s1
            # friction at the new point (for the internals)
            av = v1n if v1n >= 0.0 else -v1n
            N1 = Nf(t, L * th, s)
            fk = N1 * (mu1 + al * log1p(av / v1) + Dl * exp(-sqrt(av / vw)) + mu_d * d)
            T.append(t); TH.append(th); OM.append(om); MD.append(1); DB.append(d)
            FF.append(fk if v1n >= 0.0 else -fk); VR.append(v1n)
    return dict(T=np.array(T), TH=np.array(TH), OM=np.array(OM), MD=np.array(MD, dtype=np.int8),
                DB=np.array(DB), FF=np.array(FF), VR=np.array(VR), esc=esc, arr=arr, t_end=t)


def _cycles(run, t0, t1):
    """Complete cycles (escape + its arrest) with the escape in [t0, t1]: list of dicts."""
    esc, arr = run["esc"], run["arr"]
    out = []
    ia = 0
    for j, e in enumerate(esc):
        if e[0] < t0 or e[0] > t1:
            continue
        while ia < len(arr) and arr[ia][0] < e[0]:
            ia += 1
        if ia >= len(arr):
            break
        a = arr[ia]
        out.append(dict(te=e[0], Fp=e[1], tst=e[2], Ne=e[3], creep=e[4], ie=e[5], ta=a[0], Fa=a[1], ia=a[2],
                        drop=e[1] - a[1]))
    if len(out) < 3:
        return out
    # a slip interrupted by a drive step or stop (the pin caught by the slower disc, broken away again at once)
    # is one slip: merged with its continuation
    mt = float(np.median([c["tst"] for c in out]))
    merged = []
    for c in out:
        if merged and c["tst"] < 0.02 * mt:
            p = merged[-1]
            p.update(ta=c["ta"], Fa=c["Fa"], ia=c["ia"], drop=p["Fp"] - c["Fa"])
            continue
        merged.append(dict(c))
    # micro-slips (drop < 1/4 of the median) are not cycles: the next cycle's stick is counted from the last real
    # arrest
    md = float(np.median([c["drop"] for c in merged]))
    kept = []
    t_real = None
    for c in merged:
        if c["drop"] < 0.25 * md:
            if t_real is None:
                t_real = c["te"] - c["tst"]
            continue
        if t_real is not None:
            c["tst"] = c["te"] - t_real
            t_real = None
        kept.append(c)
    return kept


def _twin_stat(v, f):
    """Decelerating minus accelerating branch of one slip at equal speed, mean over 20-80 % of its top speed."""
    if v.size < 8:
        return float("nan")
    im = int(np.argmax(v))
    vm = v[im]
    if im < 3 or v.size - im < 3 or vm <= 0:
        return float("nan")
    grid = np.linspace(0.2, 0.8, 13) * vm
    va, fa = np.maximum.accumulate(v[: im + 1]), f[: im + 1]
    vd, fd = v[im:][::-1], f[im:][::-1]
    vd = np.maximum.accumulate(vd)
    ka = np.concatenate([[True], np.diff(va) > 0])
    kd = np.concatenate([[True], np.diff(vd) > 0])
    if ka.sum() < 3 or kd.sum() < 3:
        return float("nan")
    return float(np.mean(np.interp(grid, vd[kd], fd[kd]) - np.interp(grid, va[ka], fa[ka])))


def _measure(P, run, t0, t1, drv, ld, grid=None):
    cyc = _cycles(run, t0, t1)
    m = dict(cycles=len(cyc))
    if len(cyc) < 3:
        m.update(drop=float("nan"), f_ss=float("nan"))
        return m, cyc
    drops = np.array([c["drop"] for c in cyc])
    peaks = np.array([c["Fp"] for c in cyc])
    te = np.array([c["te"] for c in cyc])
    D = float(np.mean(drops))
    m["drop"] = D
    m["f_ss"] = float((len(te) - 1) / (te[-1] - te[0])) if len(te) > 1 else float("nan")
    m["peak_sd_over_drop"] = float(np.std(peaks) / D)
    m["drop_sd_over_drop"] = float(np.std(drops) / D)
    # peaks per unit load (the load-driven part removed)
    Ne = np.array([c["Ne"] for c in cyc])
    m["peak_per_load_sd_over_drop"] = float(np.std(peaks / Ne * P["N0"]) / D)
    m["creep_at_escape_over_V"] = float(np.mean([c["creep"] for c in cyc]))
    tst = np.array([c["tst"] for c in cyc])
    m["stick_range"] = float(tst.max() / tst.min())
    lt = np.log(tst)
    if np.ptp(lt) > 0:
        sl = float(np.polyfit(lt, peaks, 1)[0])
        lo, hi = np.percentile(lt, [5, 95])
        m["peak_growth_over_drop"] = sl * (hi - lo) / D
    else:
        m["peak_growth_over_drop"] = 0.0
    qlo, qhi = np.percentile(tst, [25, 75])
    if qhi > qlo * 1.05:
        m["peak_growth_quartiles_over_drop"] = float((peaks[tst >= qhi].mean() - peaks[tst <= qlo].mean()) / D)
    else:
        m["peak_growth_quartiles_over_drop"] = 0.0
    # twin on the contact's own friction, per slip (speed, friction from the loop)
    tw = []
    VR, FF = run["VR"], run["FF"]
    for c in cyc:
        i0, i1 = c["ie"], c["ia"]
        if i1 - i0 > 8:
            val = _twin_stat(VR[i0:i1 + 1], FF[i0:i1 + 1])
            if np.isfinite(val):
                tw.append(val / c["drop"])
    m["twin_contact_over_drop"] = float(np.median(tw)) if tw else float("nan")
    m["slip_over_Tn"] = float(np.mean([(c["ta"] - c["te"]) * P["fn"] for c in cyc]))
    if grid is not None:
        tg, Ng = grid
        m["N_pp_over_N0"] = float(np.ptp(Ng) / P["N0"])
    return m, cyc


# ------------------------------------------------------------------------------------------------ drawing
def _draw(rp, case, seed):
    P = {}
    P["N0"] = _logu(rp, 2.0, 20.0)
    P["mu_s"] = float(rp.uniform(0.3, 0.6))
    P["x_star"] = float(rp.uniform(0.04, 0.10))
    P["gap"] = float(rp.uniform(0.02, 0.05))
    P["mu1"] = P["mu_s"] * float(rp.uniform(0.62, 0.72))
    mu_k0 = P["mu_s"] * (1.0 - P["x_star"]) * (1.0 - P["gap"])
    P["Delta"] = mu_k0 - P["mu1"]
    P["alpha"] = P["mu_s"] * float(rp.uniform(0.008, 0.025))
    P["D_est"] = 2.0 * P["N0"] * (P["mu_s"] * (1.0 - P["x_star"]) - P["mu1"]) * 0.8
    P["fn"] = _logu(rp, 15.0, 90.0)
    P["zeta"] = float(rp.uniform(0.01, 0.04))
    P["L"] = float(rp.uniform(0.04, 0.12))
    P["s_pk"] = float(rp.uniform(0.015, 0.03))
    P["q_creep"] = float(rp.uniform(0.004, 0.015))
    P["kappa_a"] = float(rp.uniform(0.03, 0.06))
    P["R"] = float(rp.uniform(0.004, 0.030))
    P["dx_mm"] = _logu(rp, 0.05, 1.5)
    return P


def _finish_rig(P, rho):
    """k from the deflection drop, J and k_th from fn and L; speeds from the slip-speed scale."""
    k = P["D_est"] / (P["dx_mm"] * 1e-3)
    w = TWOPI * P["fn"]
    m = k / w ** 2
    P["k"] = k
    P["m_eq"] = m
    P["k_th"] = k * P["L"] ** 2
    P["J"] = m * P["L"] ** 2
    P["c_th"] = 2.0 * P["zeta"] * math.sqrt(P["k_th"] * P["J"])
    v_ref = 0.5 * P["D_est"] * w / k
    P["v_ref"] = v_ref
    P["rho"] = rho
    P["V0"] = v_ref / rho
    P["V_ref"] = P["V0"]


def _kramers(P, D):
    """u, r0 from the pilot's drop D: Gumbel mode at F*, sd s_pk D."""
    Fs = P["N0"] * P["mu_s"]
    xs = P["x_star"]
    sig = P["s_pk"] * D
    P["u"] = GUMBEL_SD * Fs / (1.5 * math.sqrt(xs) * sig)
    g = 1.5 * P["u"] * math.sqrt(xs) / Fs
    Fdot = P["k"] * P["V0"] * (1.0 - P["q_creep"])
    P["barrier_at_mode_kT"] = P["u"] * xs ** 1.5
    P["r0"] = Fdot * g * math.exp(P["barrier_at_mode_kT"])
    P["phi_a"] = P["kappa_a"] * D / P["N0"]


def _draw_ft(rp, fn, ft_hi, fss):
    """a shaker frequency in 2.5-ft_hi fn whose ratio to fss is >= 0.25 from an integer."""
    ft = 2.5 * fn
    for _ in range(500):
        ft = float(rp.uniform(2.5, ft_hi)) * fn
        rr = ft / fss
        if abs(rr - round(rr)) >= 0.25:
            break
    return ft


# ------------------------------------------------------------------------------------------------ sensor
def _lp2(y, h, fc, z):
    wc = TWOPI * fc
    num, den, _ = cont2discrete(([wc * wc], [1.0, 2.0 * z * wc, wc * wc]), h, method="foh")
    b = np.asarray(num).ravel()
    a = np.asarray(den).ravel()
    b = b * (a.sum() / b.sum())
    return lfilter(b, a, y, zi=lfilter_zi(b, a) * y[0])[0]


def _lp1(y, h, fc):
    wc = TWOPI * fc
    num, den, _ = cont2discrete(([wc], [1.0, wc]), h, method="foh")
    b = np.asarray(num).ravel()
    a = np.asarray(den).ravel()
    b = b * (a.sum() / b.sum())
    return lfilter(b, a, y, zi=lfilter_zi(b, a) * y[0])[0]


def _pink(rng, n):
    w = rng.standard_normal(max(n, 8))
    W = np.fft.rfft(w)
    f = np.arange(W.size, dtype=float)
    f[0] = 1.0
    W = W / np.sqrt(f)
    W[0] = 0.0
    p = np.fft.irfft(W, max(n, 8))[:n]
    return p / (p.std() + 1e-300)


def _nice_fs(v):
    e = 10.0 ** math.floor(math.log10(v))
    for mlt in (1.0, 2.0, 5.0, 10.0):
        if mlt * e >= v:
            return mlt * e
    return 10.0 * e


def _adc16(y, fs):
    step = 2.0 * fs / 65536.0
    return np.round(np.clip(y, -fs, fs - step) / step) * step, step


def _fmt_time(dt):
    d = max(0, int(math.ceil(-math.log10(dt))) + 3)
    return "%." + str(d) + "f"


# ------------------------------------------------------------------------------------------------ record
def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    tic = time.time()
    ci = CASES.index(case)
    rp = _rng("phys", case, seed)
    rl = _rng("lab", case, seed)
    rn = _rng("noise", case, seed, nuisance)
    P = _draw(rp, case, seed)
    info = {}

    # ---------------------------------------------------------------- lab choices
    coarse = nuisance == "coarse"
    long_rec = (not coarse) and (seed % 4 == (ci + 1) % 4) and case not in ("static_ageing", "triggering")
    if coarse:
        sp = float(rl.uniform(10.0, 15.0))
    elif long_rec:
        sp = float(rl.uniform(70.0, 100.0))
    else:
        sp = float(rl.uniform(20.0, 100.0))
    kind = "force" if rl.random() < 0.67 else "displacement"
    sep = str(rl.choice([",", "\t", " "]))
    t_ms = rl.random() < 0.33
    uneven = rl.random() < 0.33
    comments = rl.random() < 0.33
    funit = "mN" if rl.random() < 0.4 else "N"
    xunit = "um" if rl.random() < 0.25 else "mm"

    # ---------------------------------------------------------------- rig and speeds
    load_kind = "const"
    if case == "load_variation":
        load_kind = "runout" if seed % 2 == 0 else "deflect"
    if case == "drive_modulation":
        rho = float(rp.uniform(8.0, 14.0))
    else:
        rho = float(rp.uniform(5.0, 14.0))
    if load_kind == "runout":
        # the deflection drop sets the track distance per cycle: 12-45 cycles per revolution
        P["dx_mm"] = _logu(rp, 0.3, 1.5)
        n_rev = float(rp.uniform(12.0, 45.0))
        P["R"] = n_rev * P["dx_mm"] * 1e-3 / TWOPI
        if P["R"] < 0.004:
            P["R"] = 0.004
        P["fn"] = _logu(rp, 15.0, 45.0)
    _finish_rig(P, rho)
    Tn = 1.0 / P["fn"]
    P["v_w"] = P["v_ref"] * float(rp.uniform(0.03, 0.12))
    P["v1"] = P["v_ref"] * float(rp.uniform(0.05, 0.2))
    P["u"], P["r0"], P["phi_a"] = 1.0, 0.0, P["kappa_a"] * P["D_est"] / P["N0"]

    # ---------------------------------------------------------------- pilot (deterministic escape at F*)
    drv0 = _Drive("const", P["V0"])
    ld0 = _Load("const", P["N0"])
    pil = _simulate(P, drv0, ld0, (case, seed, "pilot"), t_cap=400 * Tn, n_stop=7, det=True)
    pc = _cycles(pil, 0.0, 1e9)[2:]
    D = float(np.mean([c["drop"] for c in pc]))
    t_stk = float(np.mean([c["te"] - cp["ta"] for cp, c in zip(pc[:-1], pc[1:])]))
    T_ss0 = float(np.mean(np.diff([c["te"] for c in pc])))
    info.update(pilot_drop=D, pilot_Tss_over_Tn=T_ss0 / Tn, pilot_stick_over_Tn=t_stk / Tn)
    if long_rec:
        # slow the disc so that 40-60 cycles make 60 000-200 000 samples
        n_long = int(rp.integers(40, 61))
        target = float(rp.uniform(70000.0, 170000.0))
        Tss_need = target / (n_long * sp * P["fn"])
        fac = max(1.0, (Tss_need - (T_ss0 - t_stk)) / t_stk)
        P["V0"] /= fac
        P["V_ref"] = P["V0"]
        P["rho"] *= fac
        drv0 = _Drive("const", P["V0"])
        pil = _simulate(P, drv0, ld0, (case, seed, "pilot2"), t_cap=400 * Tn * fac, n_stop=7, det=True)
        pc = _cycles(pil, 0.0, 1e9)[2:]
        D = float(np.mean([c["drop"] for c in pc]))
        t_stk = float(np.mean([c["te"] - cp["ta"] for cp, c in zip(pc[:-1], pc[1:])]))
        T_ss0 = float(np.mean(np.diff([c["te"] for c in pc])))
        info.update(pilot_drop=D, pilot_Tss_over_Tn=T_ss0 / Tn, pilot_stick_over_Tn=t_stk / Tn, long_slowdown=fac)
    _kramers(P, D)
    n_lead = 3

    # ---------------------------------------------------------------- the case
    drv, ld = drv0, ld0
    kw = {}
    h_st = None
    n_cyc = int(rp.integers(15, 61))
    if long_rec:
        n_cyc = n_long
    if load_kind == "runout":
        n_rev_c = TWOPI * P["R"] / (D / P["k"])  # cycles per revolution (pilot drop)
        n_cyc = int(min(60, max(n_cyc, math.ceil(0.8 * n_rev_c) + 2)))
    sched_end = None
    if case == "load_variation":
        pp = float(rp.uniform(0.15, 0.35))
        if load_kind == "runout":
            e2r = float(rp.uniform(0.0, 0.4))
            p1, p2 = rp.uniform(0, TWOPI, 2)
            ph = np.linspace(0, TWOPI, 2001)
            shape = np.sin(ph + p1) + e2r * np.sin(2 * ph + p2)
            e1 = pp / np.ptp(shape)
            ld = _Load("runout", P["N0"], e1=e1, e2=e1 * e2r, p1=p1, p2=p2, R=P["R"])
            info.update(runout_e1=e1, runout_e2=e1 * e2r, runout_pp_target=pp,
                        cycles_per_revolution=TWOPI * P["R"] / (D / P["k"]))
        else:
            sgn = 1.0 if rp.random() < 0.6 else -1.0
            xm = float(np.mean([0.5 * (c["Fp"] + c["Fa"]) for c in pc])) / P["k"]
            c0 = sgn * pp / (1.15 * D / P["k"])
            ld = _Load("deflect", P["N0"], c=c0, xm=xm)
            info.update(tilt_c_per_m=c0, pp_target=pp)
    elif case == "twin_branch":
        tw_target = float(rp.uniform(0.13, 0.20))
        slip_len = D / P["k"] + P["V0"] * 0.5 * Tn
        kw = dict(mu_d=tw_target * D / (0.45 * P["N0"]), ell=float(rp.uniform(0.3, 0.6)) * slip_len,
                  tau_c=float(rp.uniform(0.05, 0.15)) * t_stk)
        info.update(twin_target=tw_target)
    elif case == "static_ageing":
        ratio = float(rp.uniform(4.0, 8.0))
        holds = seed % 2 == 1
        V_hi, V_lo = P["V0"], P["V0"] / ratio
        nb = int(rp.integers(5, 8))  # blocks after the lead, slow first
        nbcs = [int(rp.integers(3, 6)) for _ in range(nb)]
        hold_mult = [float(rp.uniform(1.5, 6.0)) for _ in range(40)]
        tau = float(rp.uniform(0.3, 1.0)) * t_stk
        g_target = float(rp.uniform(0.09, 0.14))
        hold_list = [hold_mult[j] * t_stk for j in range(sum(nbcs[1::2]) // 2)] if holds else []
        t_long = max(ratio * t_stk, (max(hold_list) + t_stk) if hold_list else 0.0)
        dln = math.log1p(t_long / tau) - math.log1p(t_stk / tau)
        rate_eff = math.log(ratio) * P["s_pk"] * D / GUMBEL_SD
        beta = (g_target * D + rate_eff) / (P["N0"] * P["mu_s"] * (1 - P["x_star"]) * dln)
        kw = dict(beta=beta, tau_a=tau)

        def schedule(beta):
            """The drive program: blocks of slips at V_lo / V_hi (holds in the fast blocks on odd seeds), timed
            from deterministic pilots of the ageing rig at either speed (the controller steps by distance)."""
            per = {}
            for lvl, V in (("hi", V_hi), ("lo", V_lo)):
                pl = _simulate(P, _Drive("const", V), ld0, (case, seed, "pilot_" + lvl),
                               t_cap=60.0 * ratio * T_ss0 + 100 * Tn, n_stop=7, det=True, beta=beta, tau_a=tau)
                cc = _cycles(pl, 0.0, 1e9)[2:]
                per[lvl] = (float(np.mean(np.diff([c["te"] for c in cc]))),
                            float(np.mean([c["te"] - cp["ta"] for cp, c in zip(cc[:-1], cc[1:])])))
            T_hi, ts_hi = per["hi"]
            T_lo = per["lo"][0]
            tb, vb = [0.0], [V_hi]
            t = (n_lead + 0.5) * T_hi
            hl = []
            jh = 0
            for b, nbc in enumerate(nbcs):
                lo = b % 2 == 0
                tb.append(t)
                vb.append(V_lo if lo else V_hi)
                if lo:
                    t += nbc * T_lo
                    continue
                for j in range(nbc):
                    if holds and j % 2 == 1:
                        th0 = t + 0.15 * ts_hi
                        hd = hold_mult[jh] * t_stk
                        jh += 1
                        tb.extend([th0, th0 + hd])
                        vb.extend([0.0, V_hi])
                        hl.append(hd)
                        t += hd
                    t += T_hi
            return _Drive("sched", P["V0"], tb=tb, vb=vb), t, hl, T_hi, T_lo

        drv, sched_end, hold_list, T_hi, T_lo = schedule(beta)
        info.update(ageing_target=g_target, v_ratio=ratio, tau_a_over_Tn=tau / Tn,
                    cycles_planned=n_lead + sum(nbcs))
    elif case == "triggering":
        a = float(rp.uniform(0.03, 0.08))
        ft_hi = min(8.0, 0.4 * sp)
        ph = float(rp.uniform(0, TWOPI))
        # the forced slips lock to the shaker (each stick lasts a whole number of its periods): scan 10 shaker
        # frequencies on short runs (15 slips) and take them in the order of their ft/f_ss's distance from an
        # integer (the sticks then mix n and n+1 periods)
        off = float(rp.uniform(0.0, 1.0))
        cands = []
        for j in range(10):
            ft = (2.5 + (j + off) / 10.0 * (ft_hi - 2.5)) * P["fn"]
            ldj = _Load("shaker", P["N0"], a=a, ft=ft, p=ph)
            trial = _simulate(P, drv0, ldj, (case, seed), t_cap=40 * T_ss0 + 50 * Tn, n_stop=n_lead + 16,
                              h_st=min(Tn / 32.0, 1.0 / (20.0 * ft)))
            tte = [e[0] for e in trial["esc"][n_lead:]]
            if len(tte) < 5:
                continue
            rr = ft * (len(tte) - 1) / (tte[-1] - tte[0])
            cands.append((-abs(rr - round(rr)), ft))
        cands.sort()
        trig_queue = [c[1] for c in cands] or [_draw_ft(rp, P["fn"], ft_hi, 1.0 / T_ss0)]
        ft = trig_queue.pop(0)
        ld = _Load("shaker", P["N0"], a=a, ft=ft, p=ph)
        h_st = min(Tn / 32.0, 1.0 / (20.0 * ft))
        info.update(trig_a=a, ft_hz=ft, ft_over_fss_unforced=ft * T_ss0, trig_scan=[[c[1], -c[0]] for c in cands])
    elif case == "drive_modulation":
        a = float(rp.uniform(0.22, 0.43))
        r_fm = float(rp.uniform(0.12, 0.4))
        ph = float(rp.uniform(0, TWOPI))
        drv = _Drive("mod", P["V0"], a=a, fm=r_fm / T_ss0, ph=ph)
        info.update(mod_a=a, mod_fm_target=r_fm)

    def run_main(drv, ld, kw, h_st=None):
        if sched_end is not None:
            return _simulate(P, drv, ld, (case, seed), t_cap=3.0 * sched_end + 200 * Tn, n_stop=0,
                             t_min=sched_end, h_st=h_st, **kw)
        return _simulate(P, drv, ld, (case, seed), t_cap=(n_lead + n_cyc + 2) * T_ss0 * 4.0 + 50 * Tn,
                         n_stop=n_lead + n_cyc + 1, h_st=h_st, **kw)

    f0, f1 = float(rl.uniform(0.2, 0.7)), float(rl.uniform(0.3, 0.8))

    def window(run):
        esc, arr = run["esc"], run["arr"]
        a0 = arr[n_lead - 1][0]
        t0 = a0 + f0 * (esc[n_lead][0] - a0)
        a1 = arr[-1][0]
        t1 = a1 + f1 * (esc[-1][0] - a1)
        return t0, t1

    attempts = 0
    good = None
    best_trig = None
    while True:
        attempts += 1
        run = run_main(drv, ld, kw, h_st)
        ok = len(run["arr"]) >= n_lead + 8 and len(run["esc"]) >= n_lead + 8
        if not ok:
            if good is None:
                raise RuntimeError("%s %s %d: the rig stopped stick-slipping" % (NAME, case, seed))
            run, drv, ld, kw, h_st = good
            info["fallback"] = True
            break
        good = (run, drv, ld, dict(kw), h_st)
        t0, t1 = window(run)
        m, cyc = _measure(P, run, t0, t1, drv, ld)
        if case == "triggering":
            r = info["ft_hz"] / m["f_ss"]
            dist = abs(r - round(r))
            if best_trig is None or dist > best_trig[0]:
                best_trig = (dist, good, info["ft_hz"])
            if dist >= 0.15:
                break
            if attempts >= 8:
                run, drv, ld, kw, h_st = best_trig[1]
                info["ft_hz"] = best_trig[2]
                break
        elif attempts >= 4:
            break
        if case == "load_variation" and load_kind == "deflect":
            idx = (run["T"] >= t0) & (run["T"] <= t1)
            Nw = ld.Nv(run["T"][idx], P["L"] * run["TH"][idx], 0.0)
            ppm = float(np.ptp(Nw) / P["N0"])
            if 0.13 <= ppm <= 0.37:
                break
            ld = _Load("deflect", P["N0"], c=ld.c * info["pp_target"] / max(ppm, 1e-3), xm=ld.xm)
            info["tilt_c_per_m"] = ld.c
        elif case == "twin_branch":
            tw = m["twin_contact_over_drop"]
            if 0.115 <= tw <= 0.22:
                break
            kw["mu_d"] *= info["twin_target"] / max(tw, 0.02)
        elif case == "static_ageing":
            g = m["peak_growth_quartiles_over_drop"]
            if 0.07 <= g <= 0.16:
                break
            # growth = ageing part - rate part: rescale the ageing part
            rate_part = math.log(info["v_ratio"]) * P["s_pk"] * D / GUMBEL_SD / m["drop"]
            fac = (info["ageing_target"] + rate_part) / max(g + rate_part, 0.01)
            kw["beta"] *= min(2.0, max(0.5, fac))
            drv, sched_end, hold_list, T_hi, T_lo = schedule(kw["beta"])
        elif case == "triggering":
            ft = trig_queue.pop(0) if trig_queue else _draw_ft(rp, P["fn"], ft_hi, m["f_ss"])
            info["ft_hz"] = ft
            ld = _Load("shaker", P["N0"], a=info["trig_a"], ft=ft, p=ph)
            h_st = min(Tn / 32.0, 1.0 / (20.0 * ft))
        elif case == "drive_modulation":
            rr = drv.fm / m["f_ss"]
            if 0.1 <= rr <= 0.5:
                break
            drv = _Drive("mod", P["V0"], a=drv.a, fm=info["mod_fm_target"] * m["f_ss"], ph=drv.ph)
        else:
            break
    info["attempts"] = attempts
    t0, t1 = window(run)
    if case == "static_ageing":
        info.update(holds=hold_list, sched_t=list(drv.tb), sched_v_mm_s=[v * 1e3 for v in drv.vb],
                    sched_T_hi_over_Tn=T_hi / Tn, sched_T_lo_over_Tn=T_lo / Tn)

    # ---------------------------------------------------------------- fine grid, model internals
    fs = sp * P["fn"]
    dt = 1.0 / fs
    hf = Tn / 256.0
    pad = 3.0 * Tn
    T, TH, OM = run["T"], run["TH"], run["OM"]
    keep = np.concatenate([[True], np.diff(T) > 1e-9 * Tn])
    spl = CubicHermiteSpline(T[keep], TH[keep], OM[keep])
    tg = np.arange(max(T[0], t0 - pad), t1 + 2 * dt + hf, hf)
    thg = spl(tg)
    Fg = P["k_th"] * thg / P["L"]
    xg = P["L"] * thg
    Sg = drv.Sv(tg)
    Vg = drv.Vv(tg)
    Ng = ld.Nv(tg, xg, Sg)
    inw = (tg >= t0) & (tg <= t1)
    m, cyc = _measure(P, run, t0, t1, drv, ld, grid=(tg[inw], Ng[inw]))
    m["samples_per_period"] = sp
    if case == "triggering":
        r = info["ft_hz"] / m["f_ss"]
        te_ = np.array([c["te"] for c in cyc])
        Fst0 = P["N0"] * P["mu_s"] * (1.0 - P["x_star"])
        m.update(trig_a=info["trig_a"], ft_over_fn=info["ft_hz"] / P["fn"], ft_over_fss=r,
                 ft_over_fss_dist=abs(r - round(r)),
                 escape_phase_locking=float(abs(np.mean(np.exp(2j * math.pi * info["ft_hz"] * te_)))),
                 peak_lowering_over_drop=float((Fst0 - np.mean([c["Fp"] for c in cyc])) / m["drop"]))
    if case == "drive_modulation":
        m.update(mod_a=drv.a, mod_fm_over_fss=drv.fm / m["f_ss"])
    if case == "load_variation" and load_kind == "runout":
        m["revolutions"] = float((drv.S(t1) - drv.S(t0)) / (TWOPI * P["R"]))

    # ---------------------------------------------------------------- sensor
    main_is_force = kind == "force"
    sig = Fg if main_is_force else xg
    fc = float(rl.uniform(10.0, 30.0)) * P["fn"]
    zc = float(rl.uniform(0.35, 0.7))
    faa = max(float(rl.uniform(0.25, 0.4)) * fs, float(rl.uniform(8.0, 12.0)) * P["fn"])
    y = _lp1(_lp2(sig, hf, fc, zc), hf, faa)
    # the 1-DoF reading of the clean transducer output (what a perfect 1-DoF analysis would see)
    Fy = y if main_is_force else y * P["k"]
    d1 = np.gradient(Fy, hf)
    d2 = np.gradient(d1, hf)
    f_est = Fy + P["c_th"] / P["L"] ** 2 / P["k"] * d1 + P["m_eq"] / P["k"] * d2
    v_est = Vg - d1 / P["k"]
    tw1 = []
    for c in cyc:
        i0 = np.searchsorted(tg, c["te"])
        i1 = np.searchsorted(tg, c["ta"])
        if i1 - i0 > 8:
            val = _twin_stat(v_est[i0:i1 + 1], f_est[i0:i1 + 1])
            if np.isfinite(val):
                tw1.append(val / c["drop"])
    m["twin_1dof_reading_over_drop"] = float(np.median(tw1)) if tw1 else float("nan")

    # sample times
    n = int(math.floor((t1 - t0) / dt)) + 1
    ts = t0 + np.arange(n) * dt
    jit = 0.0
    gaps = []
    if uneven:
        jit = float(rl.uniform(0.02, 0.08))
        ts = ts + jit * dt * rl.uniform(-1.0, 1.0, n)
        ts[0] = t0
        ts = np.clip(ts, t0, t1)
        ng = int(rl.integers(1, 4))
        keep_s = np.ones(n, bool)
        for _ in range(ng):
            g0 = int(rl.integers(n // 10, n - n // 10))
            gl = int(rl.integers(2, 7))
            keep_s[g0:g0 + gl] = False
            gaps.append(gl)
        ts = ts[keep_s]
    main = np.interp(ts, tg, y)
    Nint = np.interp(ts, tg, Ng)

    # scales: output units
    if main_is_force:
        fmul = 1e3 if funit == "mN" else 1.0
        main = main * fmul
        mscale = m["drop"] * fmul
        munit = funit
    else:
        xmul = 1e3 if xunit == "mm" else 1e6
        main = main * xmul
        mscale = m["drop"] / P["k"] * xmul
        munit = xunit
    nz = {}
    # transducer/amplifier noise (every record)
    wn = float(rn.uniform(0.0008, 0.003)) * mscale
    pn = float(rn.uniform(0.0005, 0.002)) * mscale
    main = main + wn * rn.standard_normal(main.size) + pn * _pink(rn, main.size)
    nz.update(white_over_drop=wn / mscale, pink_over_drop=pn / mscale)
    # nuisances
    if nuisance == "hum":
        fh = float(rn.choice([50.0, 60.0]))
        amp = float(rn.uniform(0.01, 0.05)) * mscale
        phs = rn.uniform(0.0, TWOPI, 3)
        hh = np.zeros(ts.size)
        nh = 0
        for jh, ah in ((1, 1.0), (2, 0.3), (3, 0.15)):
            if jh * fh < 0.45 * fs:
                hh += ah * amp * np.sin(TWOPI * jh * fh * ts + phs[jh - 1])
                nh += 1
        main = main + hh
        nz.update(hum_hz=fh, hum_over_drop=amp / mscale, hum_harmonics=nh)
    elif nuisance == "drift":
        amp = float(rn.uniform(0.02, 0.06)) * mscale * float(rn.choice([-1.0, 1.0]))
        uu = (ts - ts[0]) / (ts[-1] - ts[0])
        shape = 0.5 * uu + 0.5 * (1.0 - np.cos(math.pi * uu)) / 2.0
        main = main + amp * shape / shape.max()
        nz.update(drift_over_drop=amp / mscale)
    # ADC
    span = float(np.max(np.abs(main)))
    full = _nice_fs(span * float(rn.uniform(1.3, 4.0)))
    if nuisance == "quantisation":
        qs = float(rn.uniform(0.002, 0.01)) * mscale
        main = np.round(main / qs) * qs
        nz.update(adc_step_over_drop=qs / mscale)
    else:
        main, step = _adc16(main, full)
        nz.update(adc16_full_scale=full, adc_step_over_drop=step / mscale)
    if nuisance == "spikes":
        frac = float(rn.uniform(0.0005, 0.005))
        ns = max(2, int(round(frac * main.size)))
        ii = np.sort(rn.choice(np.arange(3, main.size - 3, 4), ns, replace=False))
        main = main.copy()
        main[ii] += rn.choice([-1.0, 1.0], ns) * rn.uniform(0.3, 1.5, ns) * mscale
        nz.update(spike_fraction=ns / main.size)

    # normal channel
    if case == "load_variation":
        has_N = True
    elif case == "triggering":
        has_N = rl.random() < 0.5
    else:
        has_N = rl.random() < 0.33
    nrm = None
    nunit = None
    if has_N:
        Nsens = _lp1(_lp2(Ng, hf, float(rl.uniform(10.0, 30.0)) * P["fn"], float(rl.uniform(0.35, 0.7))), hf, faa)
        nrm = np.interp(ts, tg, Nsens)
        if main_is_force:
            nrm = nrm * fmul
            nunit = funit
            nsc = P["N0"] * fmul
        else:
            k_ld = _logu(rl, 2e3, 2e4)
            off = float(rl.uniform(-0.5, 0.5)) if rl.random() < 0.5 else 0.0
            nrm = nrm / k_ld * 1e3 + off
            nunit = "mm"
            nsc = P["N0"] / k_ld * 1e3
            info.update(normal_reading_k_N_per_m=k_ld, normal_reading_offset_mm=off)
        nrm = nrm + float(rn.uniform(0.0005, 0.002)) * nsc * rn.standard_normal(nrm.size) \
            + float(rn.uniform(0.0003, 0.001)) * nsc * _pink(rn, nrm.size)
        nrm, _ = _adc16(nrm, _nice_fs(float(np.max(np.abs(nrm))) * float(rn.uniform(1.3, 3.0))))

    # drive column
    if case == "static_ageing":
        drive_col = "speed" if rl.random() < 0.6 else "position"
    elif case == "drive_modulation":
        drive_col = None
    else:
        drive_col = [None, "speed", "position", "angle"][int(rl.integers(0, 4))]
    if not main_is_force and drive_col == "position":
        drive_col = "speed"  # a deflection record keeps one length column (beside its y)
    counts = int(rl.choice([3600, 4096, 10000, 16384]))
    dcol = None
    if drive_col == "speed":
        dcol = (str(rl.choice(["v0", "speed", "sliding speed"])), "mm/s", drv.Vv(ts) * 1e3)
    elif drive_col == "position":
        stp = TWOPI * P["R"] / counts
        sv = np.floor((drv.Sv(ts) - drv.S(t0)) / stp) * stp
        dcol = (str(rl.choice(["position", "distance", "sliding distance"])), "mm", sv * 1e3)
    elif drive_col == "angle":
        stp = 360.0 / counts
        av = np.floor(np.degrees((drv.Sv(ts) - drv.S(t0)) / P["R"]) / stp) * stp
        dcol = ("angle", "deg", av)

    # fn given?
    if nuisance == "fn_off":
        fn_given = P["fn"] * (1.0 + 0.05 * float(rn.choice([-1.0, 1.0])))
    elif (seed + 3 * ci) % 8 == 3:
        fn_given = None
    else:
        fn_given = P["fn"]

    # ---------------------------------------------------------------- write
    args = []
    if fn_given is not None:
        args += ["--fn", "%.6g" % fn_given]
    if drive_col in (None, "angle"):
        args += ["--v0", "%.6g" % (P["V0"] * 1e3)]
    if main_is_force:
        args += ["--stiffness", "%.6g" % P["k"]]
    ws = sep == " "
    cols = []
    if main_is_force:
        nm = str(rl.choice(["friction", "Ft", "friction force", "tangential force"]))
        cols.append((nm, munit, main))
        if has_N:
            cols.append((str(rl.choice(["normal", "Fn", "normal force", "normal load"])), nunit, nrm))
    else:
        cols.append((str(rl.choice(["x", "deflection"])), munit, main))
        if has_N:
            cols.append(("y", nunit, nrm))
    if dcol is not None:
        cols.append(dcol)
    tname = str(rl.choice(["time", "t", "Time"]))
    tunit = "ms" if t_ms else "s"
    tmul = 1e3 if t_ms else 1.0
    names = [(tname, tunit)] + [(c[0], c[1]) for c in cols]
    if ws:
        hdr = "  ".join("%s[%s]" % (nm.replace(" ", "_"), un) for nm, un in names)
    else:
        hdr = sep.join("%s [%s]" % (nm, un) for nm, un in names)
    os.makedirs(outdir, exist_ok=True)
    ext = {",": "csv", "\t": "tsv", " ": "txt"}[sep]
    fout = os.path.abspath(os.path.join(outdir, "%s_%s_%03d_%s.%s" % (NAME, case, seed, nuisance, ext)))
    tout = (ts - t0) * tmul
    data = np.column_stack([tout] + [c[2] for c in cols])
    delim = "  " if ws else sep
    with open(fout, "w") as fh_:
        if comments:
            fh_.write("# pin-on-disc tribometer export\n")
            fh_.write("# track radius %.1f mm, arm %.0f mm, sampling %.1f Hz\n" % (P["R"] * 1e3, P["L"] * 1e3, fs))
        fh_.write(hdr + "\n")
        np.savetxt(fh_, data, fmt=[_fmt_time(dt * tmul)]
                   + ["%.8g"] * len(cols), delimiter=delim)

    # ---------------------------------------------------------------- truth
    params = dict(P)
    params.update(info)
    params.update(case=case, load_kind=load_kind, samples_per_period=sp, n_samples=int(ts.size),
                  record_kind=kind, has_normal=has_N, drive_column=drive_col, separator=sep, time_unit=tunit,
                  uneven=uneven, jitter=jit, gaps=gaps, long_record=long_rec, sensor_fc_over_fn=fc / P["fn"],
                  sensor_zeta=zc, antialias_over_fs=faa / fs, duration_s=float(ts[-1] - ts[0]),
                  v0_nominal_mm_s=P["V0"] * 1e3, t_record_start=float(t0), kw={k: float(v) for k, v in kw.items()})
    params["nuisance_params"] = nz
    params["measured"] = m
    params["seconds"] = time.time() - tic
    params = json.loads(json.dumps(params, default=float))
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=fout, args=args,
                fn_true=float(P["fn"]), fn_given=None if fn_given is None else float(fn_given), params=params)


# ------------------------------------------------------------------------------------------------ self-check
def _departure(case, m, p):
    f = lambda key: m.get(key, float("nan"))
    if case == "none":
        return "twin(contact) %+.3f twin(1dof) %+.3f creep %.3f sticks x%.2f pk~tst %+.3f" % (
            f("twin_contact_over_drop"), f("twin_1dof_reading_over_drop"), f("creep_at_escape_over_V"),
            f("stick_range"), f("peak_growth_over_drop"))
    if case == "load_variation":
        return "N p-p/N0 %.3f (%s)%s" % (f("N_pp_over_N0"), p["load_kind"],
                                         " revs %.2f" % f("revolutions") if p["load_kind"] == "runout" else "")
    if case == "twin_branch":
        return "twin/drop %.3f (1dof %.3f)" % (f("twin_contact_over_drop"), f("twin_1dof_reading_over_drop"))
    if case == "static_ageing":
        return "growth/drop %.3f (regr %.3f) sticks x%.1f%s" % (f("peak_growth_quartiles_over_drop"),
                                                               f("peak_growth_over_drop"), f("stick_range"),
                                                    " holds" if p.get("holds") else "")
    if case == "triggering":
        return "a %.3f ft/fn %.2f ft/fss %.2f (dist %.2f) lock %.2f lowered %.2f" % (
            f("trig_a"), f("ft_over_fn"), f("ft_over_fss"), f("ft_over_fss_dist"), f("escape_phase_locking"),
            f("peak_lowering_over_drop"))
    return "a %.3f fm/fss %.3f" % (f("mod_a"), f("mod_fm_over_fss"))


if __name__ == "__main__":
    import sys
    import tempfile

    outdir = tempfile.mkdtemp(prefix="pin_disc_kramers_")
    t_all = time.time()
    only = sys.argv[1:] or CASES
    summary = {}
    print("%-16s %4s %-12s %-5s %4s %6s %7s %5s %6s %6s  %s" % (
        "case", "seed", "nuisance", "kind", "cyc", "sp", "samples", "fn?", "pk_sd", "sec", "departure"))
    for case in only:
        for seed in range(8):
            nu = NUISANCES[seed % 7]
            tic = time.time()
            r = write_record(case, seed, outdir, nu)
            sec = time.time() - tic
            p, m = r["params"], r["params"]["measured"]
            print("%-16s %4d %-12s %-5s %4d %6.1f %7d %5s %6.3f %6.2f  %s" % (
                case, seed, nu, p["record_kind"][:5], m["cycles"], p["samples_per_period"], p["n_samples"],
                "-" if r["fn_given"] is None else ("off" if nu == "fn_off" else "yes"),
                m.get("peak_sd_over_drop", float("nan")), sec, _departure(case, m, p)), flush=True)
            summary.setdefault(case, []).append((m, p, sec))
    print("\nall in %.1f s (%s)" % (time.time() - t_all, outdir))
    for case, rows in summary.items():
        cyc = [m_["cycles"] for m_, _, _ in rows]
        spp = [p_["samples_per_period"] for _, p_, _ in rows]
        ns = [p_["n_samples"] for _, p_, _ in rows]
        pk = [m_["peak_sd_over_drop"] for m_, _, _ in rows]
        secs = [s_ for _, _, s_ in rows]
        print("%-16s cycles %d-%d  samples/period %.1f-%.1f  samples %d-%d  peak sd/drop %.3f-%.3f  %.2f-%.2f s" % (
            case, min(cyc), max(cyc), min(spp), max(spp), min(ns), max(ns), min(pk), max(pk), min(secs), max(secs)))
