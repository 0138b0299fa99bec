"""Sheet-metal strip-drawing friction tester (deep-drawing tribology): an independent test-data generator.

Rig.  A lubricated steel or aluminium strip (DC04, DC06, DX54D+Z, HC220BD+Z, AA5182-O, AA6016-T4) is clamped
between two flat dies (two friction faces) by a hydraulic clamp (N0 = 2-40 kN) and drawn by a servo puller at
0.01-2 mm/s.  The load cell sits in the strip line: the compliance of the strip's free length, load cell and
puller frame is the spring (k = 2e6-6e7 N/m), the strip plus gripper the moving mass (1.5-150 kg, fn = 30-220 Hz,
damping ratio 0.01-0.04 to ground).  The exported force is the spring force k (x_puller - x_strip), the exported
position the puller's (the drive end), so a user passes --stiffness (with its unit).

Friction law (not Stribeck / LuGre / rate-and-state / Karnopp): a pressure- and temperature-dependent
boundary-film law,
    F_b(N)  = 2 mu_bl(T_die) A p_r (1 - exp(-p/p_r)),  p = N/A        real-contact saturation (Wanheim-Bay like),
                                                                     mu_bl falls with the die temperature
    Theta   = 1 / (1 + th1 (N/N0) (sqrt(|v| + v_eps) - sqrt(v_eps)))  flash-temperature softening, dT ~ p sqrt(v)
    film    = 1 - lam_h h - lam_q q
    kinetic F_k = F_b Theta film + c_v |v|   static level F_s = F_b (1 + s_b) film   (s_b = 6-14 %)
with two lubricant states: h, the boundary film squeezed out while stuck (Reynolds squeeze film,
1/h^2 = 1/h_0^2 + t/t_sq) and rebuilt by sliding over a sub-micron length (h = 1 - (1 - h_0) exp(-s/L_f));
q, the lubricant trapped in the strip's surface pockets (micro-plasto-hydrodynamic lubrication), re-pressurised
while stuck (dq/dt = (1 - q)/tau_fill, tau_fill ~ T_n) and emptied by sliding (- q |v| / L_esc), so friction
rises along a slip.  Stick handling is exact and event driven: a stick ends at the root (brentq, bracketed on a
fine scan) of |k e(t)| = F_s(N(t), h(t), q(t)) with h, q, N and the drive evaluated in closed form; a slip is a
smooth mode of fixed direction integrated by a hand-written classical RK4 at T_n/400; its end is the zero of the
step's cubic-Hermite velocity, reached by an exact re-step, and the mass sticks if |k e| <= F_s there.
The truth is the Hermite interpolant of the nodes on an 8x oversampled grid, filtered by the strain-gauge
amplifier (Bessel or Butterworth, order 2 or 4, a standard cut-off <= 0.42 fs), noise 0.2-0.6 % of the drop,
24-bit ADC (quantisation nuisance: 12/14/16-bit on a 10-50 kN cell, step 0.2-1 % of the drop); the clamp load
cell (kN), puller encoder (0.1-0.5 um) or the controller's speed signal (mm/s, 1st-order lag, 0.3-1.5 % noise).
Sampling: a standard DAQ rate giving 20-100 samples per natural period (10-15 for `coarse`); 16-40 slips after
three run-in slips; time axis re-zeroed or the test clock.

Formats (chosen by (seed + case index) % 3): a German test-machine export (`Key;Value` preamble with Prüfer,
Datum, Probe ..., `Zeit;Standardkraft;Normalkraft;Traversenweg` plus a `s;kN;kN;mm` units row or `Zeit [s]` style
headers, decimal commas, CRLF, cp1252 or UTF-8; Standardkraft in N or kN); an English CSV
(`Time (s),Pull force (N),Clamp force (kN),Crosshead (mm)`, optional 2-field preamble); a TAB DAQ file with `#`
comments and `time [s]  pull force [N]  clamp force [kN]  puller position [mm] | puller speed [mm/s]`.
The clamp channel is always present for load_variation, on about half of the triggering records and a third of
the others; the drive is the puller position, its speed, or only --v0 (required for static_ageing and stepped
`none` drives, never for drive_modulation).  --fn is passed (true fn within +-1 %) except on seeds 3 mod 8 that
are not fn_off; fn_off passes fn x (1 +- 0.05).

Cases (effect sizes measured on the simulated ground truth, not on the files; seeds 0-7 = the 48 records,
[seeds 0-23] in brackets; also stored per record in params["effects"]):
- none: constant load, constant drive (seeds 1 mod 4: the drive steps between 2-3 recorded levels, ratio
  1.5-2.5).  Inherent memory of the law, measured: double-valuedness (decelerating minus accelerating friction at
  equal speed, 0.3-0.8 of the slip's peak speed) 0.24-1.0 % of the force drop [0.20-1.03 %] (pockets: lam_q
  1-3 %, L_esc 8-20 slip lengths); static ageing (film squeeze, t_sq = 1000-4000 stick times) peak growth over
  the record's stick-time range 0-0.008 % of the drop [0-0.03 %], < 0.04 % per decade of stick time [< 0.08 %].
  The film rebuild length L_f is 0.4-1.2 % of a slip.  Drop 19-29 % of the peak force.
- load_variation: the pull tilts the floating die carriage into the compliant clamp frame (self-energising):
  N = N0 (1 + c (e - e_mean)), e = F/k, gain dF_s/de / k = 0.40-0.67; clamp channel recorded.  N peak-to-peak
  20.1-29.6 % of mean N [13.9-32.2 %].
- twin_branch: strong pocket lubrication (lam_q 5-12 %, L_esc 0.7-1.4 slip lengths): friction higher on the
  decelerating half; measured 13.0-20.4 % of the drop [13.0-22.3 %].
- static_ageing: strong film squeeze-out during sticks (t_sq 0.3-1.5 x the geometric-mean stick time, lam_h
  4-18 %); the puller steps between two speeds (ratio 4.4-7.9 [4.0-7.9]) and/or holds (2-10 stick times); drive
  recorded.  Peak-force growth over the record's stick-time range 11.9-15.0 % of the mean drop [8.1-15.0 %]
  (13-17 % per decade [9-19 %]); inherent double-valuedness < 0.06 %.
- triggering: the clamp pump's pressure ripple N = N0 (1 + a sin(2 pi f_T t)), a 4.1-7.2 % [3.7-7.4 %] of N0,
  f_T 3.3-6.1 fn [3.3-7.9 fn]; f_T / f_ss 0.21-0.43 [0.21-0.50] from the nearest integer.  The ripple tends to
  entrain the slips (onsets at its troughs, f_T = n f_ss): the pump speed (and after 8 / 16 tries its amplitude
  and the set draw speed) is redrawn until a record is not entrained.  Static excess s_b 15-22 % here so the
  stick-slip survives the ripple (drop 18-30 % of the peak).
- drive_modulation: the servo-hydraulic puller hunts, v = v0n (1 + a sin(2 pi fm t + phi)), a 22-41 %
  [22-42 %], fm 0.17-0.40 [0.14-0.40] of the measured stick-slip frequency; only v0n is given (--v0).

Nuisances (on the force channel): hum 50/60 Hz + 2nd/3rd harmonics, fundamental 1.2-3.5 % of the drop (total
<= 5 %); drift 2-6 % of the drop (linear + warm-up exponential); spikes on 0.05-0.5 % of samples, 0.5-3 drops;
quantisation (see above); coarse 10-15 samples per period; fn_off.

Cost: the 48 records take about 30 s in one process.
"""

import bisect
import datetime
import math
import os
import zlib

import numpy as np
from scipy import signal
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq

NAME = "strip_draw"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

_STD_RATES = (200, 250, 300, 400, 500, 600, 800, 1000, 1200, 1250, 1500, 2000, 2400, 2500, 3000, 4000,
              4800, 5000, 6000, 8000, 9600, 10000, 12000, 12800, 16000, 19200, 20000)
_STD_FILTERS = (10, 20, 50, 100, 200, 300, 500, 1000, 2000, 3000, 5000)
_MAX_SAMPLES = 200_000

# effect sizes measured on the ground truth of the 48 benchmark records (seeds 0-7) [and of seeds 0-23]
MEASURED_RANGES = {
    "none": {"twin_frac_of_drop": [0.0024, 0.0102], "twin_frac_of_drop_seeds0_23": [0.0020, 0.0103],
             "ageing_growth_frac_of_drop": [0.0, 0.00008], "ageing_growth_frac_of_drop_seeds0_23": [0.0, 0.00028],
             "ageing_per_decade_frac_of_drop_max": 0.0008, "N_pp_frac": [0.0, 0.0]},
    "load_variation": {"N_pp_frac_of_N": [0.201, 0.296], "N_pp_frac_of_N_seeds0_23": [0.139, 0.322]},
    "twin_branch": {"twin_frac_of_drop": [0.130, 0.204], "twin_frac_of_drop_seeds0_23": [0.130, 0.223]},
    "static_ageing": {"ageing_growth_frac_of_drop": [0.119, 0.150],
                      "ageing_growth_frac_of_drop_seeds0_23": [0.081, 0.150], "speed_ratio": [4.0, 7.9],
                      "twin_frac_of_drop_abs_max": 0.0006},
    "triggering": {"amp_frac_of_N0": [0.041, 0.072], "amp_frac_of_N0_seeds0_23": [0.037, 0.074],
                   "f_over_fn": [3.3, 6.1], "f_over_fn_seeds0_23": [3.25, 7.95],
                   "f_over_fss_distance_from_integer": [0.21, 0.43],
                   "f_over_fss_distance_from_integer_seeds0_23": [0.21, 0.50]},
    "drive_modulation": {"a": [0.221, 0.408], "a_seeds0_23": [0.221, 0.424], "fm_over_fss": [0.17, 0.40],
                         "fm_over_fss_seeds0_23": [0.14, 0.40]},
}
_N_PRE = 3                      # slips run before the exported section (run-in)


# ----------------------------------------------------------------------------------------------- helpers
def _rng(*parts):
    key = "|".join(str(p) for p in parts).encode()
    return np.random.default_rng([zlib.crc32(key), zlib.adler32(key), 2025])


def _lu(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def _u(rng, lo, hi):
    return float(rng.uniform(lo, hi))


def _sig(x, n=3):
    if x == 0:
        return 0.0
    return float(f"{x:.{n}g}")


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, np.ndarray):
        return [_jsonable(v) for v in o.tolist()]
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.bool_,)):
        return bool(o)
    return o


# ----------------------------------------------------------------------------------------------- drives
class _PWDrive:
    """Puller velocity piecewise linear between breakpoints (servo ramps); position integrated exactly."""

    def __init__(self, tb, vb):
        self.tb = np.asarray(tb, float)
        self.vb = np.asarray(vb, float)
        dt = np.diff(self.tb)
        self.sl = np.append(np.diff(self.vb) / dt, 0.0)
        xb = [0.0]
        for i in range(len(dt)):
            xb.append(xb[-1] + 0.5 * (self.vb[i] + self.vb[i + 1]) * dt[i])
        self.xb = np.array(xb)
        self._tl = self.tb.tolist()
        self._vl = self.vb.tolist()
        self._sl = self.sl.tolist()
        self._xl = self.xb.tolist()

    def x(self, t):
        t = np.asarray(t, float)
        i = np.clip(np.searchsorted(self.tb, t, "right") - 1, 0, len(self.tb) - 1)
        d = t - self.tb[i]
        return self.xb[i] + self.vb[i] * d + 0.5 * self.sl[i] * d * d

    def v(self, t):
        t = np.asarray(t, float)
        i = np.clip(np.searchsorted(self.tb, t, "right") - 1, 0, len(self.tb) - 1)
        return self.vb[i] + self.sl[i] * (t - self.tb[i])

    def xs(self, t):
        i = bisect.bisect_right(self._tl, t) - 1
        if i < 0:
            i = 0
        d = t - self._tl[i]
        return self._xl[i] + self._vl[i] * d + 0.5 * self._sl[i] * d * d


class _ModDrive:
    """Servo-hydraulic puller hunting: v = v0n (1 + a sin(2 pi fm t + phi))."""

    def __init__(self, v0n, a, fm, phi):
        self.v0n, self.a, self.w, self.phi = v0n, a, 2 * math.pi * fm, phi
        self.c0 = math.cos(phi)

    def x(self, t):
        t = np.asarray(t, float)
        return self.v0n * (t - self.a / self.w * (np.cos(self.w * t + self.phi) - self.c0))

    def v(self, t):
        t = np.asarray(t, float)
        return self.v0n * (1 + self.a * np.sin(self.w * t + self.phi))

    def xs(self, t):
        return self.v0n * (t - self.a / self.w * (math.cos(self.w * t + self.phi) - self.c0))


# ----------------------------------------------------------------------------------------------- friction law
class _Law:
    """Pressure/temperature-dependent boundary-film law with a squeezed film h and lubricant pockets q.

    F_b(N)  = n_f mu_bl(T_die) A p_r (1 - exp(-p/p_r)),  p = N/A       (real-contact saturation, Wanheim-Bay like)
    Theta   = 1 / (1 + th1 (N/N0) (sqrt(|v| + v_eps) - sqrt(v_eps)))  (flash-temperature softening ~ p sqrt(v))
    film    = 1 - lam_h h - lam_q q
    kinetic F_k = F_b Theta film + c_v |v|;  static level F_s = F_b (1 + s_b) film
    h: squeezed out in stick 1/h^2 = 1/h_0^2 + t/t_sq, rebuilt by sliding h = 1 - (1 - h_0) exp(-s/L_f)
    q: pockets re-pressurised dq/dt = (1-q)/tau_fill, emptied by sliding  - q |v| / L_esc
    """

    def __init__(self, P):
        self.P = P
        self.k = P["k"]
        self.m = P["m"]
        self.c = P["c"]
        self.N0 = P["N0"]
        self.A = P["A"]
        self.pr = P["p_r"]
        self.Kb = P["n_faces"] * P["mu_bl"] * P["A"] * P["p_r"]
        self.th1 = P["th1"]
        self.veps = P["v_eps"]
        self.sqveps = math.sqrt(P["v_eps"])
        self.sb = P["s_b"]
        self.cv = P["c_v"]
        self.lh = P["lam_h"]
        self.lq = P["lam_q"]
        self.tsq = P["t_sq"]
        self.Lf = P["L_f"]
        self.Lesc = P["L_esc"]
        self.tau = P["tau_fill"]
        self.load = P["load"]           # "const", "geom", "ripple"
        self.cN = P.get("c_N", 0.0)
        self.eref = P.get("e_ref", 0.0)
        self.aT = P.get("a_T", 0.0)
        self.wT = 2 * math.pi * P.get("f_T", 0.0)
        self.phT = P.get("ph_T", 0.0)

    # vectorised pieces -----------------------------------------------------------------------------------
    def N_vec(self, t, e):
        if self.load == "geom":
            return np.maximum(self.N0 * (1 + self.cN * (e - self.eref)), 0.1 * self.N0)
        if self.load == "ripple":
            return self.N0 * (1 + self.aT * np.sin(self.wT * t + self.phT))
        return np.full(np.shape(t), self.N0, float)

    def Fb_vec(self, N):
        return self.Kb * (1 - np.exp(-N / (self.A * self.pr)))

    def Fs_vec(self, N, h, q):
        return self.Fb_vec(N) * (1 + self.sb) * (1 - self.lh * h - self.lq * q)

    def Ff_vec(self, v, N, h, q):
        av = np.abs(v)
        th = 1.0 / (1 + self.th1 * (N / self.N0) * (np.sqrt(av + self.veps) - self.sqveps))
        return np.sign(v) * (self.Fb_vec(N) * th * (1 - self.lh * h - self.lq * q) + self.cv * av)


# ----------------------------------------------------------------------------------------------- simulation
def _simulate(law, drive, t_end, max_slips, fn, fT=0.0):
    """Event-driven stick/slip: exact (root-found) stick ends, classical RK4 at T_n/400 during slips,
    arrests located on the step's cubic Hermite velocity and re-stepped exactly onto v = 0."""
    k, m, c = law.k, law.m, law.c
    im = 1.0 / m
    N0, Ap, pr, Kb = law.N0, law.A, law.pr, law.Kb
    th1, veps, sqveps, sb, cv = law.th1, law.veps, law.sqveps, law.sb, law.cv
    lh, lq, tsq, Lf, iLesc, itau = law.lh, law.lq, law.tsq, law.Lf, 1.0 / law.Lesc, 1.0 / law.tau
    lk = {"const": 0, "geom": 1, "ripple": 2}[law.load]
    cN, eref, aT, wT, phT = law.cN, law.eref, law.aT, law.wT, law.phT
    xdf = drive.xs
    Tn = 1.0 / fn
    dt = Tn / 400.0
    dts = Tn / 16.0
    if fT > 0:
        dts = min(dts, 1.0 / (14.0 * fT))
    exp, sqrt, sin = math.exp, math.sqrt, math.sin

    def Nsc(t, e):
        if lk == 0:
            return N0
        if lk == 1:
            return max(N0 * (1 + cN * (e - eref)), 0.1 * N0)
        return N0 * (1 + aT * sin(wT * t + phT))

    def acc(t, x, v, s, q, h0, d):
        e = xdf(t) - x
        N = Nsc(t, e)
        Fb = Kb * (1 - exp(-N / (Ap * pr)))
        # the slip mode's direction d fixes the friction's sign for every stage (smooth RHS within the mode;
        # the mode ends at the located zero of v)
        av = d * v
        if av < 0.0:
            av = 0.0
        th = 1.0 / (1 + th1 * (N / N0) * (sqrt(av + veps) - sqveps))
        h = 1 - (1 - h0) * exp(-s / Lf)
        Fk = Fb * th * (1 - lh * h - lq * q) + cv * av
        return (k * e - c * v - d * Fk) * im, av, (1 - q) * itau - q * av * iLesc

    def rk4(t, x, v, s, q, h0, d, hstep):
        a1, s1, q1 = acc(t, x, v, s, q, h0, d)
        hh = 0.5 * hstep
        x2, v2, ss2, q2_ = x + hh * v, v + hh * a1, s + hh * s1, q + hh * q1
        a2, s2, q2 = acc(t + hh, x2, v2, ss2, q2_, h0, d)
        x3, v3, ss3, q3_ = x + hh * v2, v + hh * a2, s + hh * s2, q + hh * q2
        a3, s3, q3 = acc(t + hh, x3, v3, ss3, q3_, h0, d)
        x4, v4, ss4, q4_ = x + hstep * v3, v + hstep * a3, s + hstep * s3, q + hstep * q3
        a4, s4, q4 = acc(t + hstep, x4, v4, ss4, q4_, h0, d)
        return (x + hstep / 6 * (v + 2 * v2 + 2 * v3 + v4),
                v + hstep / 6 * (a1 + 2 * a2 + 2 * a3 + a4),
                s + hstep / 6 * (s1 + 2 * s2 + 2 * s3 + s4),
                q + hstep / 6 * (q1 + 2 * q2 + 2 * q3 + q4), a1)

    def stick_g(tt, t0, x, h0, q0):
        e = drive.x(tt) - x
        N = law.N_vec(tt, e)
        h = (1.0 / (h0 * h0) + (tt - t0) / tsq) ** -0.5
        q = 1 - (1 - q0) * np.exp(-(tt - t0) * itau)
        Fs = law.Fs_vec(N, h, q)
        return k * e - Fs, -k * e - Fs

    def stick_end(t0, x, h0, q0):
        ta = t0
        n = 256
        while ta < t_end:
            tt = ta + dts * np.arange(1, n + 1)
            g1, g2 = stick_g(tt, t0, x, h0, q0)
            hit = np.nonzero((g1 >= 0) | (g2 >= 0))[0]
            if hit.size:
                i = int(hit[0])
                lo = ta if i == 0 else float(tt[i - 1])
                hi = float(tt[i])
                d = 1.0 if g1[i] >= 0 else -1.0
                j = 0 if d > 0 else 1

                def f(tq):
                    return float(stick_g(np.array([tq]), t0, x, h0, q0)[j][0])
                if f(lo) >= 0:
                    return lo, d
                return brentq(f, lo, hi, xtol=1e-13 * max(1.0, hi), rtol=1e-12), d
            ta = float(tt[-1])
            n = min(n * 2, 8192)
        return None, 0.0

    T, X, V, H, Q = [0.0], [0.0], [0.0], [1.0], [1.0]
    slips = []
    t, x, h, q = 0.0, 0.0, 1.0, 1.0
    t_st = 0.0
    done = False
    while not done:
        tb, d = stick_end(t_st, x, h, q)
        if tb is None:
            hb = (1.0 / (h * h) + (t_end - t_st) / tsq) ** -0.5
            qb = 1 - (1 - q) * math.exp(-(t_end - t_st) * itau)
            T.append(t_end); X.append(x); V.append(0.0); H.append(hb); Q.append(qb)
            break
        hb = (1.0 / (h * h) + (tb - t_st) / tsq) ** -0.5
        qb = 1 - (1 - q) * math.exp(-(tb - t_st) * itau)
        if tb > T[-1]:
            T.append(tb); X.append(x); V.append(0.0); H.append(hb); Q.append(qb)
        if len(slips) >= max_slips:
            break
        slip = {"t_on": tb, "F_on": k * (xdf(tb) - x), "stick": tb - t_st, "i0": len(T) - 1,
                "N_on": Nsc(tb, xdf(tb) - x), "h_on": hb, "q_on": qb}
        t, v, s, q, h0 = tb, 0.0, 0.0, qb, hb
        nstep = 0
        while True:
            xn, vn, sn, qn, an = rk4(t, x, v, s, q, h0, d, dt)
            nstep += 1
            if d * vn <= 0.0 and nstep > 0:
                # arrest (or reversal) inside this step: cubic Hermite on v, then an exact re-step
                a1 = acc(t + dt, xn, vn, sn, qn, h0, d)[0]
                v0_, a0_ = v, an

                def vh(tau, v0_=v0_, a0_=a0_, vn=vn, a1=a1):
                    u = tau / dt
                    h00 = 2 * u ** 3 - 3 * u ** 2 + 1
                    h10 = u ** 3 - 2 * u ** 2 + u
                    h01 = -2 * u ** 3 + 3 * u ** 2
                    h11 = u ** 3 - u ** 2
                    return h00 * v0_ + h10 * dt * a0_ + h01 * vn + h11 * dt * a1
                if d * v0_ <= 0.0:
                    tau = dt * 1e-6
                else:
                    try:
                        tau = brentq(vh, 0.0, dt, xtol=dt * 1e-10)
                    except ValueError:
                        tau = dt
                tau = max(tau, dt * 1e-6)
                xs_, vs_, ss_, qs_, _ = rk4(t, x, v, s, q, h0, d, tau)
                t, x, v, s, q = t + tau, xs_, 0.0, ss_, qs_
                hnow = 1 - (1 - h0) * math.exp(-s / Lf)
                T.append(t); X.append(x); V.append(0.0); H.append(hnow); Q.append(q)
                e = xdf(t) - x
                N = Nsc(t, e)
                Fb = Kb * (1 - math.exp(-N / (Ap * pr)))
                Fs = Fb * (1 + sb) * (1 - lh * hnow - lq * q)
                Fapp = k * e
                if abs(Fapp) <= Fs:
                    h = hnow
                    break
                d = 1.0 if Fapp > 0 else -1.0
                continue
            t, x, v, s, q = t + dt, xn, vn, sn, qn
            T.append(t); X.append(x); V.append(v); H.append(1 - (1 - h0) * math.exp(-s / Lf)); Q.append(q)
            if t > t_end or nstep > 200000:
                done = True
                break
        if done:                          # slip cut by the end of the run: kept incomplete
            slips.append(slip)
            break
        slip["t_off"] = t
        slip["i1"] = len(T) - 1
        slip["s"] = s
        slips.append(slip)
        t_st = t
    T = np.array(T); X = np.array(X); V = np.array(V); H = np.array(H); Q = np.array(Q)
    return {"t": T, "x": X, "v": V, "h": H, "q": Q, "slips": slips}


def _slip_stats(res, law, drive, t0=-np.inf, t1=np.inf, twin=False):
    """Per-slip ground truth: peak force, drop, stick time, and (optionally) the twin-branch measure."""
    t, x, v = res["t"], res["x"], res["v"]
    k = law.k
    out = []
    for sl in res["slips"]:
        if "t_off" not in sl or sl["t_on"] < t0 or sl["t_off"] > t1:
            continue
        i0, i1 = sl["i0"], sl["i1"]
        tt = t[i0:i1 + 1]
        e = drive.x(tt) - x[i0:i1 + 1]
        F = k * e
        rec = {"t_on": sl["t_on"], "t_off": sl["t_off"], "peak": sl["F_on"], "drop": sl["F_on"] - float(F.min()),
               "stick": sl["stick"], "D": float(x[i1] - x[i0]), "vmax": float(np.max(v[i0:i1 + 1]))}
        if twin:
            vv = v[i0:i1 + 1]
            N = law.N_vec(tt, e)
            Ff = law.Ff_vec(vv, N, res["h"][i0:i1 + 1], res["q"][i0:i1 + 1])
            ip = int(np.argmax(vv))
            vp = vv[ip]
            lev = np.linspace(0.3, 0.8, 11) * vp
            va, fa = vv[:ip + 1], Ff[:ip + 1]
            vd, fd = vv[ip:][::-1], Ff[ip:][::-1]
            va = np.maximum.accumulate(va)
            vd = np.maximum.accumulate(vd)
            fa_l = np.interp(lev, va, fa)
            fd_l = np.interp(lev, vd, fd)
            rec["twin"] = float(np.mean(fd_l - fa_l) / rec["drop"])
        out.append(rec)
    return out


def _ageing_growth(st):
    """Peak-force growth over the record's range of stick times / mean drop (line in ln t_stick)."""
    ts = np.array([s["stick"] for s in st])
    pk = np.array([s["peak"] for s in st])
    dr = np.mean([s["drop"] for s in st])
    lt = np.log(ts)
    if np.ptp(lt) < 1e-9:
        return 0.0, 0.0
    b = np.polyfit(lt, pk, 1)[0]
    return float(b * np.ptp(lt) / dr), float(b * math.log(10) / dr)


# ----------------------------------------------------------------------------------------------- physics draw
_MATERIALS = (("DC04", "steel", (0.7, 0.8, 1.0, 1.2), (260e6, 360e6)),
              ("DC06", "steel", (0.7, 0.8, 1.0), (230e6, 320e6)),
              ("DX54D+Z", "steel", (0.75, 0.8, 1.0), (250e6, 350e6)),
              ("HC220BD+Z", "steel", (0.8, 1.0, 1.2), (330e6, 430e6)),
              ("AA5182-O", "aluminium", (1.0, 1.15, 1.5), (160e6, 230e6)),
              ("AA6016-T4", "aluminium", (1.0, 1.2), (170e6, 240e6)))
_LUBES = ("Anticorit PL 3802-39S", "Multidraw PL 61", "Renoform MCO 3028", "Drylube E1", "Prelube KTL N 16")


def _draw_physics(rng, case):
    mat = _MATERIALS[int(rng.integers(len(_MATERIALS)))]
    thick = float(mat[2][int(rng.integers(len(mat[2])))])
    for _ in range(500):
        k = _lu(rng, 2e6, 6e7)
        fn = _lu(rng, 30.0, 220.0) if case != "triggering" else _lu(rng, 30.0, 120.0)
        m = k / (2 * math.pi * fn) ** 2
        N0 = _lu(rng, 2e3, 40e3)
        slip_proxy = 0.1 * N0 / k                      # ~ slip distance: keep it 4-250 um
        if 1.5 <= m <= 150 and 4e-6 <= slip_proxy <= 2.5e-4:
            break
    width = float(rng.choice([20e-3, 25e-3, 30e-3, 40e-3, 50e-3]))
    length = float(rng.choice([20e-3, 30e-3, 40e-3, 50e-3]))
    A = width * length
    P = {"material": mat[0], "metal": mat[1], "thickness_mm": thick, "lubricant": _LUBES[int(rng.integers(len(_LUBES)))],
         "coat_g_m2": round(_u(rng, 0.6, 2.2), 1), "die_width_m": width, "die_length_m": length,
         "k": k, "fn": fn, "m": m, "zeta": _u(rng, 0.01, 0.04), "N0": N0, "A": A, "n_faces": 2,
         "p_r": _u(rng, *mat[3]), "mu_bl20": _u(rng, 0.10, 0.16), "T_die": _u(rng, 20.0, 45.0),
         "kappa_T": _u(rng, 0.002, 0.005),
         "s_b": _u(rng, 0.06, 0.14) if case != "triggering" else _u(rng, 0.15, 0.22), "w_flash": _u(rng, 0.02, 0.06),
         "T_soft": _u(rng, 80.0, 200.0), "visc_frac": _u(rng, 0.005, 0.02)}
    P["c"] = 2 * P["zeta"] * math.sqrt(k * m)
    P["mu_bl"] = P["mu_bl20"] * (1 - P["kappa_T"] * (P["T_die"] - 20.0))
    Fb0 = P["n_faces"] * P["mu_bl"] * A * P["p_r"] * (1 - math.exp(-N0 / (A * P["p_r"])))
    P["Fb0"] = Fb0
    w = 2 * math.pi * fn
    v_c = w * P["s_b"] * Fb0 / k                       # expected slip speed scale
    P["v_c"] = v_c
    P["v_eps"] = 1e-3 * v_c
    P["th1"] = (1 / (1 - P["w_flash"]) - 1) / (math.sqrt(v_c + P["v_eps"]) - math.sqrt(P["v_eps"]))
    P["dT_flash_1mm_s"] = P["T_soft"] * P["th1"] * (math.sqrt(1e-3 + P["v_eps"]) - math.sqrt(P["v_eps"]))
    P["c_v"] = P["visc_frac"] * Fb0 / v_c
    D_est = 2 * (P["s_b"] + P["w_flash"]) * Fb0 / k
    # inherent film / pocket memory (baseline level; cases override)
    P["lam_h"] = _u(rng, 0.05, 0.15)
    P["lam_q"] = _u(rng, 0.01, 0.03)
    P["L_f"] = D_est * _u(rng, 0.004, 0.012)
    P["L_esc"] = D_est * _u(rng, 8.0, 20.0)
    P["tau_fill"] = _u(rng, 0.6, 1.2) / fn
    P["t_sq"] = 1e9                                    # set once stick times are known
    P["load"] = "const"
    return P


# ----------------------------------------------------------------------------------------------- one case
def _const_drive(v0):
    return _PWDrive([0.0, 1.0], [v0, v0])


def _steps_drive(levels, t_ramp):
    """levels: list of (v, duration); ramps of t_ramp between them."""
    tb, vb = [0.0], [levels[0][0]]
    t = 0.0
    for i, (v, dur) in enumerate(levels):
        t += dur
        if i + 1 < len(levels):
            tb += [t, t + t_ramp]
            vb += [v, levels[i + 1][0]]
            t += t_ramp
    tb.append(t + 1.0)
    vb.append(levels[-1][0])
    return _PWDrive(tb, vb)


def _window(res, n_pre, n_max=40):
    """Exported section: from mid-stick after the run-in slips to mid-stick after the last complete slip."""
    sl = [s for s in res["slips"] if "t_off" in s]
    t0 = 0.5 * (sl[n_pre - 1]["t_off"] + sl[n_pre]["t_on"])
    sl = sl[:n_pre + n_max]
    last = sl[-1]
    later = [s["t_on"] for s in res["slips"] if s["t_on"] > last["t_off"]]
    nxt = later[0] if later else float(res["t"][-1])
    t1 = 0.5 * (last["t_off"] + nxt)
    return t0, t1


def _build(case, seed):
    rng = _rng(NAME, "phys", case, seed)
    P = _draw_physics(rng, case)
    fn = P["fn"]
    Tn = 1 / fn
    # ---- baseline calibration run: force drop and slip distance at a provisional drive speed
    law = _Law(P)
    D_est = 2 * (P["s_b"] + P["w_flash"]) * P["Fb0"] / P["k"]
    v_prov = D_est / (15 * Tn)
    res = _simulate(law, _const_drive(v_prov), 1e3, 7, fn)
    st = _slip_stats(res, law, _const_drive(v_prov), twin=True)[3:]
    drop0 = float(np.mean([s["drop"] for s in st]))
    D0 = drop0 / P["k"]
    P["drop_baseline_N"] = drop0
    P["twin_inherent_baseline"] = float(np.mean([s["twin"] for s in st]))
    # re-scale the length constants to the real slip distance
    P["L_f"] *= D0 / D_est
    P["L_esc"] *= D0 / D_est
    meta = {}
    n_target = int(rng.integers(16, 39))

    def pick_v0(R):
        v0 = D0 / (R * Tn)
        return _sig(min(max(v0, 1.0e-5), 1e-2), 2)

    drive_rec = None          # which drive channels may be recorded ("any", "required", "forbidden")
    fT = 0.0
    if case in ("none", "load_variation", "twin_branch", "triggering"):
        stepped = case == "none" and seed % 4 == 1
        R = _lu(rng, 8, 35)
        v0 = pick_v0(R)
        T_ss = D0 / v0
        if stepped:
            ratio = _u(rng, 1.5, 2.5)
            nlev = int(rng.integers(2, 4))
            facs = [1.0, 1.0 / ratio, math.sqrt(1.0 / ratio)][:nlev]
            levels = []
            n_blk = max(4, n_target // (nlev + 1))
            levels.append((v0, (_N_PRE + n_blk + 0.5) * T_ss))
            i = 1
            tot = n_blk
            while tot < n_target:
                f = facs[i % nlev]
                vv = _sig(v0 * f, 2)
                levels.append((vv, n_blk * D0 / vv))
                tot += n_blk
                i += 1
            drive = _steps_drive(levels, _u(rng, 0.01, 0.04))
            meta["drive_levels_mm_s"] = [lv[0] * 1e3 for lv in levels]
            t_end = sum(lv[1] for lv in levels) + 0.5 * T_ss
            max_slips = 10 ** 6
            drive_rec = "required"
        else:
            drive = _const_drive(v0)
            t_end = 1e6
            max_slips = _N_PRE + n_target
            drive_rec = "any"
        P["t_sq"] = _u(rng, 1000, 4000) * T_ss
        meta["v0_mm_s"] = v0 * 1e3
    elif case == "static_ageing":
        variant = ("steps", "holds", "steps+holds")[seed % 3]
        meta["ageing_variant"] = variant
        P["lam_q"] = 0.0
        if variant == "holds":
            R = _lu(rng, 8, 20)
        else:
            R = _lu(rng, 5, 9)
        v_hi = pick_v0(R)
        T_hi = D0 / v_hi
        ratio = _u(rng, 4.0, 8.0)
        v_lo = _sig(max(v_hi / ratio, 1.0e-5), 2)      # slowest puller setting 0.01 mm/s
        if v_hi / v_lo < 4.0:
            v_hi = _sig(4.2 * v_lo, 2)
            T_hi = D0 / v_hi
        levels = [(v_hi, (_N_PRE + 1.5) * T_hi)]
        tot = 0
        if variant == "steps":
            nb = int(rng.integers(4, 7))
            order = [v_lo, v_hi] * 4
            for vv in order:
                if tot >= n_target:
                    break
                levels.append((vv, nb * D0 / vv))
                tot += nb
        elif variant == "holds":
            while tot < n_target:
                nb = int(rng.integers(3, 6))
                levels.append((v_hi, (nb + _u(rng, 0.1, 0.9)) * T_hi))
                if tot + nb < n_target:
                    levels.append((0.0, _u(rng, 2.0, 10.0) * T_hi))
                tot += nb
        else:
            nb = int(rng.integers(3, 6))
            seq = [v_lo, "hold", v_hi, v_lo, "hold", v_hi, "hold", v_lo]
            for item in seq:
                if tot >= n_target:
                    break
                if item == "hold":
                    levels.append((v_hi, (2 + _u(rng, 0.1, 0.9)) * T_hi))
                    levels.append((0.0, _u(rng, 2.0, 8.0) * T_hi))
                    tot += 2
                else:
                    levels.append((item, nb * D0 / item))
                    tot += nb
        levels.append((v_hi, 5.5 * T_hi))
        t_ramp = _u(rng, 0.01, 0.04)
        drive = _steps_drive(levels, t_ramp)
        t_end = sum(lv[1] for lv in levels) + t_ramp * len(levels)
        max_slips = 10 ** 6
        drive_rec = "required"
        meta.update({"v_hi_mm_s": v_hi * 1e3, "v_lo_mm_s": v_lo * 1e3, "speed_ratio": v_hi / v_lo,
                     "drive_levels_mm_s": [lv[0] * 1e3 for lv in levels],
                     "drive_durations_s": [lv[1] for lv in levels]})
        v0 = v_hi
    else:  # drive_modulation
        R = _lu(rng, 8, 25)
        v0 = pick_v0(R)
        T_ss = D0 / v0
        a_mod = _u(rng, 0.22, 0.43)
        fm_ratio = _u(rng, 0.13, 0.42)
        n_target = int(min(40, max(n_target, math.ceil(3.2 / fm_ratio))))
        phi = _u(rng, 0, 2 * math.pi)
        drive = _ModDrive(v0, a_mod, fm_ratio / T_ss, phi)
        t_end = 1e6
        max_slips = _N_PRE + n_target
        drive_rec = "forbidden"
        P["t_sq"] = _u(rng, 1000, 4000) * T_ss
        meta.update({"v0_mm_s": v0 * 1e3, "mod_a": a_mod, "mod_fm_Hz": fm_ratio / T_ss, "mod_phi": phi,
                     "mod_fm_ratio_drawn": fm_ratio})

    # ---- case-specific physics and calibration on ground truth
    def run():
        lw = _Law(P)
        r = _simulate(lw, drive, t_end, max_slips, fn, fT)
        return lw, r

    eff = {}
    if case == "load_variation":
        target = _u(rng, 0.13, 0.33)
        P["load"] = "geom"
        Fs0 = P["Fb0"] * (1 + P["s_b"]) * (1 - P["lam_h"] - P["lam_q"])
        r = drop0 / Fs0
        # gain G = dF_s/de / k: positive = self-energising (pull tilts the floating die carriage into the clamp)
        if rng.random() < 0.7 or target > 0.55 * r:
            G = target / (target + r)
        else:
            G = -target / (r - target)
        G = float(min(max(G, -1.5), 0.85))
        P["e_ref"] = (Fs0 - 0.5 * drop0) / P["k"]
        hist = []
        for _ in range(6):
            P["c_N"] = G * P["k"] / Fs0
            law, res = run()
            t0, t1 = _window(res, _N_PRE)
            tt = np.linspace(t0, t1, 20000)
            xs = CubicHermiteSpline(res["t"], res["x"], res["v"])(tt)
            e = drive.x(tt) - xs
            N = law.N_vec(tt, e)
            pp = float((N.max() - N.min()) / N.mean())
            P["e_ref"] = float(np.mean(e))
            hist.append((G, pp))
            if abs(pp / target - 1) < 0.06:
                break
            if len(hist) >= 2 and hist[-1][1] != hist[-2][1]:
                (g1, p1), (g2, p2) = hist[-2], hist[-1]
                Gn = g2 + (target - p2) * (g2 - g1) / (p2 - p1)
            else:
                Gn = G * target / max(pp, 1e-3)
            if G > 0:
                Gn = min(max(Gn, 0.05), 0.85)
            else:
                Gn = max(min(Gn, -0.05), -1.5)
            G = float(Gn)
        eff["load_pp_target"] = target
        eff["load_gain_G"] = G
        eff["load_coupling_dNdF"] = P["c_N"] * P["N0"] / P["k"]
    elif case == "twin_branch":
        target = _u(rng, 0.12, 0.22)
        P["L_esc"] = D0 * _u(rng, 0.7, 1.4)
        P["lam_q"] = 1.5 * target * drop0 / P["Fb0"]
        P["tau_fill"] = _u(rng, 0.6, 1.0) / fn
        hist = []
        for _ in range(5):
            law, res = run()
            t0, t1 = _window(res, _N_PRE)
            st = _slip_stats(res, law, drive, t0, t1, twin=True)
            tw = float(np.mean([s["twin"] for s in st]))
            hist.append((P["lam_q"], tw))
            if abs(tw / target - 1) < 0.06:
                break
            if len(hist) >= 2 and hist[-1][1] != hist[-2][1]:
                (l1, w1), (l2, w2) = hist[-2], hist[-1]
                lq = l2 + (target - w2) * (l2 - l1) / (w2 - w1)
            else:
                lq = P["lam_q"] * target / max(tw, 1e-3)
            P["lam_q"] = float(min(max(lq, 0.2 * P["lam_q"]), min(3 * P["lam_q"], 0.45)))
        eff["twin_target"] = target
    elif case == "static_ageing":
        target = _u(rng, 0.08, 0.16)
        P["lam_h"] = 0.1
        law, res = run()
        t0, t1 = _window(res, _N_PRE)
        st = _slip_stats(res, law, drive, t0, t1)
        ts = np.array([s["stick"] for s in st])
        tmin, tmax = float(ts.min()), float(ts.max())
        P["t_sq"] = math.sqrt(tmin * tmax) * _u(rng, 0.3, 1.5)
        dh = (1 + tmin / P["t_sq"]) ** -0.5 - (1 + tmax / P["t_sq"]) ** -0.5
        dr = float(np.mean([s["drop"] for s in st]))
        P["lam_h"] = min(0.5, target * dr / (P["Fb0"] * (1 + P["s_b"]) * dh))
        for _ in range(4):
            law, res = run()
            t0, t1 = _window(res, _N_PRE)
            st = _slip_stats(res, law, drive, t0, t1)
            g, _ = _ageing_growth(st)
            if abs(g / target - 1) < 0.07:
                break
            P["lam_h"] = float(min(0.55, P["lam_h"] * target / max(g, 1e-3)))
        for _ in range(3):                              # at least 16 slips: lengthen the last fast block
            n_in = len(_slip_stats(res, law, drive, *_window(res, _N_PRE)))
            if n_in >= 16:
                break
            dr = float(np.mean([s["drop"] for s in st]))
            levels[-1] = (v_hi, levels[-1][1] + (17 - n_in) * 1.15 * dr / P["k"] / v_hi)
            drive = _steps_drive(levels, t_ramp)
            t_end = sum(lv[1] for lv in levels) + t_ramp * len(levels)
            meta["drive_durations_s"] = [lv[1] for lv in levels]
            law, res = run()
        eff["ageing_target"] = target
    elif case == "triggering":
        P["load"] = "ripple"
        P["a_T"] = _u(rng, 0.035, 0.075)
        P["ph_T"] = _u(rng, 0, 2 * math.pi)
        meta["r_T_drawn"] = _u(rng, 0.0, 1.0)     # position in the allowed r range, resolved with the sampling
    else:
        law, res = None, None
    return P, drive, t_end, max_slips, drive_rec, meta, eff, rng, D0, drop0, n_target


# ----------------------------------------------------------------------------------------------- record
def _pick_fs(fn, lo, hi, rng):
    cands = [f for f in _STD_RATES if lo <= f / fn <= hi]
    if not cands:
        return float(round(fn * 0.5 * (lo + hi)))
    return float(cands[int(rng.integers(len(cands)))])


def _fmt(arr, dec):
    return [f"{v:.{dec}f}" for v in arr]


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    seed = int(seed)
    (P, drive, t_end, max_slips, drive_rec, meta, eff, rng, D0, drop0, n_target) = _build(case, seed)
    fn = P["fn"]
    Tn = 1 / fn
    rs = _rng(NAME, "sensor", case, seed)            # sensor / format draws (independent of the nuisance)
    rn = _rng(NAME, "nuisance", case, seed, nuisance)

    # ---- sampling rate (needs the record length: estimate from the drive)
    fT = 0.0
    if case == "triggering":
        T_ss = D0 / (meta["v0_mm_s"] * 1e-3)
        T_rec = (n_target + 1) * T_ss
    elif case == "static_ageing" or "drive_levels_mm_s" in meta:
        T_rec = t_end
    else:
        T_rec = (n_target + 1) * D0 / (meta["v0_mm_s"] * 1e-3)
    if nuisance == "coarse":
        lo, hi = 10.0, 15.0
    else:
        hi = min(100.0, max(24.0, _MAX_SAMPLES / (T_rec * fn)))
        lo = 20.0
        spp_t = _lu(rs, lo, hi)
        lo, hi = max(20.0, spp_t / 1.2), min(100.0, spp_t * 1.2)
    fs = _pick_fs(fn, lo, hi, rs)
    spp = fs / fn

    if case == "triggering":
        r_hi = min(8.0, 0.3 * spp)
        r = 2.5 + meta["r_T_drawn"] * (r_hi - 2.5)
        P["f_T"] = r * fn
        fT = P["f_T"]

    law = _Law(P)
    res = _simulate(law, drive, t_end, max_slips, fn, fT)
    if case == "triggering":
        # keep the pump ripple off integer multiples of the stick-slip frequency: the ripple tends to
        # entrain the slips (onsets locked to its troughs, f_T = n f_ss); redraw the pump speed until the
        # record is not entrained (ratio at least 0.2 from an integer), keeping the least entrained one
        rr = _rng(NAME, "pump", case, seed)
        v0_set = meta["v0_mm_s"]
        best = None

        def entrainment(r_):
            t0_, t1_ = _window(r_, _N_PRE)
            st_ = _slip_stats(r_, law, drive, t0_, t1_)
            fss_ = (len(st_) - 1) / (st_[-1]["t_on"] - st_[0]["t_on"])
            ratio_ = P["f_T"] / fss_
            return abs(ratio_ - round(ratio_))
        for it in range(64):
            if it:
                P["f_T"] = _u(rr, 2.5, max(2.6, min(8.0, 0.3 * spp))) * fn
                P["ph_T"] = _u(rr, 0, 2 * math.pi)
                if it >= 8:
                    P["a_T"] = _u(rr, 0.032, 0.078)
                if it >= 16:                            # the operator's speed setting, +-20 %
                    meta["v0_mm_s"] = _sig(v0_set * _u(rr, 0.8, 1.25), 2)
                    drive = _const_drive(meta["v0_mm_s"] * 1e-3)
                fT = P["f_T"]
                law = _Law(P)
                # a short trial run first (entrainment shows within a dozen slips), the full run if promising
                res = _simulate(law, drive, t_end, min(max_slips, _N_PRE + 12), fn, fT)
                if entrainment(res) < 0.22:
                    continue
                res = _simulate(law, drive, t_end, max_slips, fn, fT)
            frac = entrainment(res)
            if best is None or frac > best[0]:
                best = (frac, P["f_T"], P["ph_T"], P["a_T"], law, res, drive, meta["v0_mm_s"])
            if frac >= 0.2:
                break
        _, P["f_T"], P["ph_T"], P["a_T"], law, res, drive, meta["v0_mm_s"] = best
        fT = P["f_T"]
        eff["pump_redraws"] = it

    t0, t1 = _window(res, _N_PRE)
    st = _slip_stats(res, law, drive, t0, t1, twin=True)
    drops = np.array([s["drop"] for s in st])
    drop = float(np.median(drops))
    fss = (len(st) - 1) / (st[-1]["t_on"] - st[0]["t_on"])
    tw = np.array([s["twin"] for s in st])
    growth, per_decade = _ageing_growth(st)
    eff.update({"n_slips": len(st), "drop_N_median": drop, "drop_frac_of_peak": float(np.median(drops / np.array([s["peak"] for s in st]))),
                "f_ss_Hz": fss, "fss_over_fn": fss / fn,
                "twin_frac_of_drop_mean": float(tw.mean()), "twin_frac_min": float(tw.min()), "twin_frac_max": float(tw.max()),
                "ageing_growth_frac_of_drop": growth, "ageing_per_decade_frac_of_drop": per_decade,
                "stick_time_range_s": [float(min(s["stick"] for s in st)), float(max(s["stick"] for s in st))],
                "slip_distance_um_median": float(np.median([s["D"] for s in st]) * 1e6),
                "slip_vmax_mm_s_median": float(np.median([s["vmax"] for s in st]) * 1e3)})
    if case == "triggering":
        eff["trig_amp_frac_of_N0"] = P["a_T"]
        eff["trig_f_over_fn"] = P["f_T"] / fn
        eff["trig_f_over_fss"] = P["f_T"] / fss
        eff["trig_frac_from_integer"] = float(abs(P["f_T"] / fss - round(P["f_T"] / fss)))
        eff["pump_pistons"] = 9 if seed % 2 else 7
        eff["pump_rpm"] = 60 * P["f_T"] / eff["pump_pistons"]
    if case == "drive_modulation":
        eff["mod_a"] = meta["mod_a"]
        eff["mod_fm_over_fss"] = meta["mod_fm_Hz"] / fss

    # ---- dense truth, sensor chain, sampling
    M = 8
    n = int(math.floor((t1 - t0) * fs))
    fsd = fs * M
    t_d = t0 + rs.uniform(0, 1) / fs + np.arange(n * M) / fsd
    spl = CubicHermiteSpline(res["t"], res["x"], res["v"])
    x_d = spl(t_d)
    xdrv = drive.x(t_d)
    e_d = xdrv - x_d
    F_true = P["k"] * e_d
    N_true = law.N_vec(t_d, e_d)
    eff["N_pp_frac_truth"] = float(np.ptp(N_true) / np.mean(N_true))
    if case == "load_variation":
        eff["load_pp_frac_of_N"] = eff["N_pp_frac_truth"]

    fc_lim = 0.42 * fs
    fcs = [f for f in _STD_FILTERS if f <= fc_lim]
    fc = float(fcs[-1]) if fcs else 0.4 * fs
    if fc < 2.0 * fn:
        fc = 0.4 * fs
    ftype = ("bessel", "butter")[int(rs.integers(2))]
    order = int(rs.choice([2, 4]))
    if ftype == "bessel":
        sos = signal.bessel(order, fc, fs=fsd, output="sos", norm="mag")
    else:
        sos = signal.butter(order, fc, fs=fsd, output="sos")

    def lowpass(y):
        zi = signal.sosfilt_zi(sos) * y[0]
        return signal.sosfilt(sos, y, zi=zi)[0]

    sig_F = _u(rs, 0.002, 0.006) * drop
    wn = rs.standard_normal(n * M)
    wn_f = lowpass(wn)[::M]
    wn_f *= sig_F / np.std(wn_f)
    F_s = lowpass(F_true)[::M] + wn_f
    ts = t_d[::M]
    trel = ts - ts[0]
    nuis = {}
    if nuisance == "hum":
        fmains = 50.0 if rn.random() < 0.7 else 60.0
        A1 = _u(rn, 0.012, 0.035) * drop
        A3 = _u(rn, 0.1, 0.4) * A1
        A2 = _u(rn, 0.0, 0.15) * A1
        hum = (A1 * np.sin(2 * np.pi * fmains * trel + _u(rn, 0, 6.3)) +
               A2 * np.sin(2 * np.pi * 2 * fmains * trel + _u(rn, 0, 6.3)) +
               A3 * np.sin(2 * np.pi * 3 * fmains * trel + _u(rn, 0, 6.3)))
        F_s = F_s + hum
        nuis = {"mains_Hz": fmains, "amp_fundamental_frac": A1 / drop, "amp_total_frac": (A1 + A2 + A3) / drop}
    elif nuisance == "drift":
        tot = _u(rn, 0.02, 0.06) * drop * (1 if rn.random() < 0.5 else -1)
        mix = _u(rn, 0.0, 1.0)
        tau = _u(rn, 0.2, 0.6) * trel[-1]
        shape = mix * trel / trel[-1] + (1 - mix) * (1 - np.exp(-trel / tau)) / (1 - math.exp(-trel[-1] / tau))
        F_s = F_s + tot * shape
        nuis = {"drift_total_frac_of_drop": tot / drop, "linear_mix": mix}
    elif nuisance == "spikes":
        frac = _u(rn, 0.0005, 0.005)
        ns = max(2, int(round(frac * n)))
        idx = np.sort(rn.choice(np.arange(2, n - 2), size=ns, replace=False))
        amp = rn.uniform(0.5, 3.0, ns) * drop * np.where(rn.random(ns) < 0.5, -1, 1)
        F_s = F_s.copy()
        F_s[idx] += amp
        nuis = {"spike_fraction": ns / n, "n_spikes": int(ns)}

    # ADC: 24-bit normally (resolution << drop); quantisation nuisance: a coarse ADC/load-cell range
    if nuisance == "quantisation":
        q_tgt = _u(rn, 0.003, 0.009) * drop
        best = None
        for bits in (12, 14, 16):
            for rng_kN in (5, 10, 20, 25, 50, 100, 200):
                step = 2 * rng_kN * 1e3 / 2 ** bits
                if rng_kN * 1e3 < 1.3 * max(F_s.max(), -F_s.min()):
                    continue
                if 0.002 * drop <= step <= 0.01 * drop:
                    if best is None or abs(math.log(step / q_tgt)) < abs(math.log(best[2] / q_tgt)):
                        best = (bits, rng_kN, step)
        if best is None:
            best = (16, None, q_tgt)
        qstep = best[2]
        nuis = {"adc_bits": best[0], "cell_range_kN": best[1], "adc_step_frac_of_drop": qstep / drop}
    else:
        cell = next(c for c in (5, 10, 20, 25, 50, 100, 200) if c * 1e3 > 1.3 * F_s.max())
        qstep = 2 * cell * 1e3 / 2 ** 24
    F_s = np.round(F_s / qstep) * qstep

    # ---- channels, format, args
    fmt = ("de", "en", "tab")[(seed + CASES.index(case)) % 3]
    if case == "load_variation":
        has_N = True
    elif case == "triggering":
        has_N = rs.random() < 0.5
    else:
        has_N = rs.random() < 0.35
    if drive_rec == "forbidden":
        dchan = None
    elif drive_rec == "required":
        dchan = "pos" if rs.random() < 0.7 else "speed"
    else:
        u = rs.random()
        dchan = "pos" if u < 0.45 else ("speed" if u < 0.65 else None)

    cols = {"t": ts}
    sig_N = _u(rs, 0.001, 0.003) * P["N0"]
    if has_N:
        fcN = min(fc, float(rs.choice([100, 200, 500, 1000])))
        sosN = signal.bessel(2, min(fcN, 0.45 * fs), fs=fsd, output="sos", norm="mag")
        Nf = signal.sosfilt(sosN, N_true, zi=signal.sosfilt_zi(sosN) * N_true[0])[0][::M]
        Nf = Nf + sig_N * rs.standard_normal(n)
        Nq = 2 * 100e3 / 2 ** 20
        cols["N"] = np.round(Nf / Nq) * Nq
    x_off = _u(rs, 4.0, 40.0) * 1e-3
    if dchan == "pos":
        res_enc = float(rs.choice([0.1e-6, 0.2e-6, 0.5e-6]))
        cols["pos"] = np.round((x_off + xdrv[::M]) / res_enc) * res_enc
    elif dchan == "speed":
        vd = drive.v(t_d)
        tau_v = _u(rs, 0.003, 0.012)
        b, a = signal.butter(1, 1 / (2 * math.pi * tau_v), fs=fsd)
        vf = signal.lfilter(b, a, vd, zi=signal.lfilter_zi(b, a) * vd[0])[0][::M]
        vmean = float(np.mean(vd))
        cols["v"] = vf + _u(rs, 0.003, 0.015) * vmean * rs.standard_normal(n)

    # time axis as exported: from 0 (section re-zeroed) or the test clock
    t_off = 0.0 if rs.random() < 0.6 else round(float(t0), 1)
    cols["t"] = trel + t_off

    k_given = _sig(P["k"], 3)
    kstyle = int(rs.integers(3))
    if kstyle == 0:
        kval = f"{k_given:.3g} N/m"
    elif kstyle == 1:
        kval = f"{k_given / 1e3:.4g} N/mm"
    else:
        kval = f"{k_given:.4e} N/m".replace("e+0", "e")
    args = ["--stiffness", kval]
    give_fn = not (seed % 8 == 3 and nuisance != "fn_off")
    fn_given = None
    if give_fn:
        if nuisance == "fn_off":
            fn_given = fn * (1.05 if rn.random() < 0.5 else 0.95)
        else:
            fn_given = fn * (1 + _u(rs, -0.01, 0.01))
        fn_given = _sig(fn_given, 4)
        args += ["--fn", f"{fn_given:g}"]
    if dchan is None:
        v0n = meta["v0_mm_s"]
        vstyle = int(rs.integers(3))
        if vstyle == 0:
            args += ["--v0", f"{v0n:g}"]
        elif vstyle == 1:
            args += ["--v0", f"{v0n * 1e3:g} um/s"]
        else:
            args += ["--v0", f"{v0n:g} mm/s"]

    # ---- write
    os.makedirs(outdir, exist_ok=True)
    ext = {"de": ".txt" if seed % 2 else ".csv", "en": ".csv", "tab": ".dat" if seed % 2 else ".txt"}[fmt]
    fname = f"{NAME}_{case}_s{seed}_{nuisance}{ext}"
    path = os.path.abspath(os.path.join(outdir, fname))
    date = datetime.date(2024, 1, 8) + datetime.timedelta(days=int(rs.integers(0, 520)))
    hh, mm_, ss = int(rs.integers(7, 18)), int(rs.integers(0, 60)), int(rs.integers(0, 60))
    tdec = max(4, int(math.ceil(math.log10(fs))) + 2)
    force_kN = fmt == "de" and rs.random() < 0.5
    fu = 1e-3 if force_kN else 1.0
    fdec = int(max(0, math.ceil(-math.log10(max(3e-4 * drop * fu, 1e-9)))))
    if nuisance == "quantisation":
        fdec = int(max(fdec, math.ceil(-math.log10(qstep * fu)) + 2))
    speed_txt = (" / ".join(f"{v:g}" for v in meta["drive_levels_mm_s"]) if "drive_levels_mm_s" in meta
                 else f"{meta['v0_mm_s']:g}")
    mat_txt = f"{P['material']} {P['thickness_mm']:g} mm"
    lines = []
    enc = "utf-8"
    if fmt == "de":
        enc = "cp1252" if seed % 4 in (1, 2) else "utf-8"

        def de(s):
            return s.replace(".", ",")
        style_units_row = rs.random() < 0.6
        lines += [f"Prüfer;{('M. Keller', 'S. Wagner', 'A. Yilmaz', 'J. Hoffmann')[int(rs.integers(4))]}",
                  f"Datum;{date.strftime('%d.%m.%Y')}",
                  f"Uhrzeit;{hh:02d}:{mm_:02d}:{ss:02d}",
                  "Prüfvorschrift;Streifenziehversuch Flachbacken",
                  f"Probe;{de(mat_txt)}",
                  f"Schmierstoff;{P['lubricant']} {de(str(P['coat_g_m2']))} g/m²",
                  "Klemmkraft Sollwert;" + de(f"{P['N0'] / 1e3:.1f}") + " kN",
                  f"Ziehgeschwindigkeit;{de(speed_txt)} mm/s",
                  f"Messrate;{fs:g} Hz",
                  ""]
        names = ["Zeit", "Standardkraft"]
        units = ["s", "kN" if force_kN else "N"]
        if has_N:
            names.append("Normalkraft"); units.append("kN")
        if dchan == "pos":
            names.append("Traversenweg"); units.append("mm")
        elif dchan == "speed":
            names.append("Traversengeschwindigkeit"); units.append("mm/s")
        if style_units_row:
            lines += [";".join(names), ";".join(units)]
        else:
            lines.append(";".join(f"{a} [{b}]" for a, b in zip(names, units)))
        sep, comma = ";", True
    elif fmt == "en":
        if rs.random() < 0.6:
            lines += [f"Test,Strip draw friction test {('SD-40', 'SDT-2', 'FT-20')[int(rs.integers(3))]}",
                      f"Specimen,{mat_txt}",
                      f"Lubricant,{P['lubricant']} {P['coat_g_m2']} g/m2",
                      f"Date,{date.isoformat()} {hh:02d}:{mm_:02d}",
                      f"Clamp force setpoint (kN),{P['N0'] / 1e3:.1f}",
                      f"Draw speed (mm/s),{speed_txt}",
                      f"Sample rate (Hz),{fs:g}",
                      ""]
        names = ["Time (s)", "Pull force (N)"]
        if has_N:
            names.append("Clamp force (kN)")
        if dchan == "pos":
            names.append("Crosshead (mm)")
        elif dchan == "speed":
            names.append("Crosshead speed (mm/s)")
        lines.append(",".join(names))
        sep, comma = ",", False
    else:
        lines += [f"# strip-drawing rig SZ-{int(rs.integers(1, 5))}, DAQ {('NI 9237 24 bit', 'QuantumX MX840B', 'DT9838')[int(rs.integers(3))]},"
                  f" bridge filter {ftype} {order}. order {fc:g} Hz",
                  f"# specimen {mat_txt}, lubricant {P['lubricant']} {P['coat_g_m2']} g/m2, {date.isoformat()}",
                  f"# clamp setpoint {P['N0'] / 1e3:.1f} kN, draw speed {speed_txt} mm/s, rate {fs:g} Hz"]
        names = ["time [s]", "pull force [N]"]
        if has_N:
            names.append("clamp force [kN]")
        if dchan == "pos":
            names.append("puller position [mm]")
        elif dchan == "speed":
            names.append("puller speed [mm/s]")
        lines.append("\t".join(names))
        sep, comma = "\t", False

    colstr = [_fmt(cols["t"], tdec), _fmt(F_s * fu, fdec)]
    if has_N:
        colstr.append(_fmt(cols["N"] * 1e-3, 4))
    if dchan == "pos":
        colstr.append(_fmt(cols["pos"] * 1e3, 5))
    elif dchan == "speed":
        colstr.append(_fmt(cols["v"] * 1e3, 5))
    body = [sep.join(r) for r in zip(*colstr)]
    text = "\n".join(lines + body) + "\n"
    if comma:
        head = "\n".join(lines)
        text = head + "\n" + "\n".join(body).replace(".", ",") + "\n"
    with open(path, "w", encoding=enc, newline="\r\n" if fmt == "de" else "\n") as fh:
        fh.write(text)

    params = dict(P)
    params.update(meta)
    params.update({"effects": eff, "nuisance_params": nuis, "fs_Hz": fs, "samples_per_period": spp,
                   "n_samples": int(n), "format": fmt, "encoding": enc, "force_unit": "kN" if force_kN else "N",
                   "has_clamp_channel": bool(has_N), "drive_channel": dchan, "amp_filter": [ftype, order, fc],
                   "force_noise_rms_frac_of_drop": sig_F / drop, "adc_step_N": qstep,
                   "record_t0_sim_s": float(t0), "record_t1_sim_s": float(t1), "time_offset_s": t_off,
                   "k_given": k_given, "measured_ranges_generator": MEASURED_RANGES[case]})
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance, "file": path, "args": args,
            "fn_true": float(fn), "fn_given": None if fn_given is None else float(fn_given),
            "params": _jsonable(params)}
