"""Independent "measured" stick-slip records from a laboratory torsional DRILL-STRING rig.

Written from physics and from how a rig's DAQ exports data, without reading the diagnosis code.

Rig
---
A top drive (DC motor under a speed controller) turns a slender steel shaft (torsional stiffness k_th 0.4-285
N.m/rad, sized per seed so that a slip overshoots the drive speed 3-6 fold); at its lower end a disc, the "bit"
(inertia J = k_th/(2 pi fn)^2, 3e-4..0.5 kg m^2, fn 1.5-11.3 Hz), rubs on a rock specimen pressed against it
with an axial force, the weight on bit (WOB, W0 0.3-8 kN, effective radius r_eff 20-50 mm; breakaway torques
4-150 N.m). One torsional degree of freedom (the bit angle phi_b), the shaft's material damping zeta 0.5-2 %
(c = 2 zeta sqrt(k J)), the drive angle phi_td(t) imposed (the exact integral of the commanded speed; speed steps
ramp over 0.6 Tn). Top-drive speed 6-110 rpm (0 in holds). The record's twist is phi_td - phi_b.

Friction law (bit-rock torque)
------------------------------
A stretched-exponential Stribeck torque with a static step, single-valued in the bit's speed w:
    T(w) = W r_eff [mu_c + (mu_0 - mu_c) exp(-|w/w_s|^delta)] sgn(w) + b w,
delta 0.5-2 (per seed), mu_c 20-40 % below the static mu_s (0.35-0.6), w_s 0.3-0.8 of the typical slip speed,
b a weak viscous (mud) term (2-6 % of the weakening at the peak slip speed). The static level W r_eff mu_s lies
x_static = 3-8 % above the curve's limit at 0+ (mu_0 = mu_s/(1 + x_static)): a step down at the breakaway
(at least 1.6 eps on `triggering` records, so the shaker triggers slips rather than ratchets the bit).

Stick handling: Leine's switch model (Leine, van Campen, de Kraker 1998)
----------------------------------------------------------------------
A band |w| <= eta = 1e-4 x the drive speed: inside it, if the applied torque T_ext = k (phi_td - phi_b) +
c (Omega - w) is within the static limit the friction equals T_ext (stick: zero acceleration, the bit keeps its
band speed, < 5e-6 of the drive: no visible creep), otherwise the friction is the static limit with the sign of
T_ext (transition); outside it the slip law. Stick phases are propagated in closed form (phi_b linear, everything
else explicit in t) and the breakaway time is found by a vectorised scan (Tn/40, 1/16 of a shaker period) and
the Illinois method on |T_ext(t)| - T_s(t). In slip, a step that would carry w into/through the band is
retaken to w = 0 (Illinois on the step length with the slip law held in the step's direction), then the band
logic decides stick or transition. Slips that never leave a small speed (< 2 % of the drive) do not reset the
contact's age.

Integrator
----------
Own fixed-step classical 4-stage Runge-Kutta-Nystrom (y'' = f(t, y, y'), h = Tn/220..Tn/300) for the bit, the
same stages (RK4) for the debris state; cubic Hermite dense output (angle with the speed, speed with the
acceleration, exact in stick) onto a grid of >= 640 points per natural period for the sensor chain.

Cases (measured on the ground truth inside the record window, seeds 0-23)
-----------------------------------------------------------------------
"drop" = the slip's drop of the applied torque (breakaway minus arrest); twin = decelerating minus
accelerating friction at equal bit speed, 10-90 % of each slip's peak speed, median over slips, / drop.
- none: constant WOB; constant top-drive speed, or (seeds 2, 5 mod 8: 6 of 24) stepped between two recorded
  levels 4-8x apart (5-6 slips fast, 2-4 slow). The law has no memory: twin at the contact |twin| <= 1e-4;
  constant static level, so the breakaway torque is the same after every stick: peak sd 0; on the stepped
  seeds (sticks 4.6-6.9x apart) the recorded (elastic, k x twist) breakaway torque grows +0.09..+0.33 % of the
  drop with the stick time (the shaft damping's c Omega share of the breakaway torque is smaller at the slow
  level). What a 1-DoF reading can mistake: the static step x_static (3-8 % of mu_s, a kink at every
  breakaway): a 1-DoF reading of the ideal sampled twist (central differences, F = k x + J x'') sees a twin of
  -10.4..-6.7 % of the drop at 25 samples per period, -4.0..-1.9 % at 50, -0.9..-0.25 % at 100 (-3.0..-1.1 %
  at 50 behind a 12 fn transducer). The shaft damping is not in the transducer (it measures k x twist).
- load_variation: WOB p-p 13.7-28.3 % of W0. Even seeds (and odd ones whose bit turns too little): an
  axial-torsional (helical) coupling, the bit holder screws into the specimen's disc springs as the shaft
  twists, W = W0 (1 + c (theta - theta_m)), rising with the twist (falling on seeds 6 mod 8, c < 0): 17-28 %
  p-p. Odd seeds: a tilted (once per turn) or warped (twice) specimen under the bit, W = W0 (1 + A sin(n phi_b
  + psi)), 13.7-27.6 % p-p. The friction coefficient stays single-valued (friction/W twin -0.3..+0.3 %), but the
  torque against the speed reads -0.24..+1.8 of the drop "twin" (the falling coupling: +0.48..+1.8), and on the
  specimen seeds the peaks change with the bit's angle (a peak-vs-stick-time slope of -0.23..+0.24 over
  sticks up to 2.2x apart).
- twin_branch: rock cuttings (debris) accumulate under the bit with the slipped angle and are flushed in
  stick: q' = |w|/phi_d (1 - q) - q/tau_f (phi_d 0.3-0.8 of a slip's angle, tau_f 0.3-1 Tn); the kinetic
  friction x (1 + g q), g calibrated on pilots: twin +12.2..+17.1 % of the drop (higher while decelerating).
- static_ageing: T_s = W r_eff (mu_s + beta ln(1 + t_stick/tau_a)), beta calibrated on pilots; even seeds: the
  top drive steps 4-8x between two recorded levels; odd seeds: holds at zero speed (1.5-9 nominal stick times)
  every 3-6 slips. Peak growth +12.3..+20.7 % of the drop over sticks 5.9-9.7x apart (regression of the peak on
  ln t_stick, times ln(max/min)).
- triggering: an unbalanced-mass exciter on the specimen holder, W = W0 (1 + eps sin(phase)), eps 3.5-7.5 %
  (WOB p-p 7.0-15.0 %), f_t 3.7-6.7 fn; its motor's speed wanders slowly by +-1.6-3.5 %. In this rig the
  breakaways lock 1:n to the shaker's troughs over nearly the whole band with sharp steps between locks; f_t is
  bisected on full-length runs to a step so that the record mixes n and n+1 shaker periods: f_t/f_ss 6.2-13.6,
  0.20-0.49 from an integer. Side effects: stick times vary 1.14-1.45x with the shaker phase (a
  peak-vs-stick-time slope up to +0.19 of the drop), torque-vs-speed twin -0.8..+10.9 % (friction/W: 0).
- drive_modulation: the top drive's speed controller hunts, Omega = Omega_n (1 + a sin(2 pi fm t + phi)),
  a 0.23-0.41, fm/f_ss 0.16-0.36 (f_ss of the record); no drive column, only Omega_n (`--v0`). Drive 9-99 rpm.
All records: 19-37 slips in the window, every slip ends in a stick (the bit's speed back to 0; the slowest slip
peaks at >= 2.9 x the drive speed), f_ss/fn 0.10-1.3.

Sensor chain and noise (every record)
-------------------------------------
- torque (strain-gauge flange on the shaft, k x twist): a second-order transducer at 12-40 fn (zeta 0.2-0.7),
  on 60 % of records a 2-4 pole Butterworth anti-alias filter at 0.25-0.4 fs (else none: mains hum aliases),
  a zeroing offset, white (0.2-0.6 % of the drop) + AR(1) coloured (0.2-0.5 %, 0.3-3 Tn) noise, 16-bit ADC.
- twist: either two incremental encoders (4096-20000 counts/rev; the difference of two quantised angles) with
  a little coloured coupling jitter, or (always on hum/drift records) an analog resolver-to-digital converter
  output (a critically damped tracking loop at 8-25 fn) through the same ADC chain as the torque.
- top drive: a DC tachometer (lag 3-15 ms, 0.5-1.5 % commutator ripple at 12 x the shaft speed, noise) in rpm,
  rad/s or deg/s, or the top encoder's angle in deg, rev or rad; bit speed (rpm) from bit encoder counts per
  sample; WOB from a load cell (first order at 20-60 fn, white + AR noise, in N or kN).
Nuisances: hum 50/60 Hz at 1-5 % of the drop + its 2nd or 3rd harmonic (20-50 %), also on the tacho/WOB;
drift = a warm-up offset 3-10 % of the drop (exponential, tau 0.3-2 records) on the friction channel, a small
linear one on WOB; spikes 0.05-0.4 % of samples (>= 3), 0.5-3 drops, either sign; quantisation = an ADC step
(or an encoder count) of 0.3-1 % of the drop; coarse 10-15 samples per natural period (else 20-100, "nice"
DAQ rates where possible); fn_off = `--fn` 5 % off the truth (either sign).

Files (varied per seed)
-----------------------
Comma CSV with `Key,Value` metadata and `Time [s],Torque_bit [N.m],...`; CRLF CSV with quoted metadata, a
`"Sample"` index column and `"Twist (deg)"`-style names; semicolon CSV with a decimal comma (time often in ms);
a LabVIEW .lvm (two headers, `X_Value` time column in s, a trailing empty `Comment` column); TAB .txt with
`Key:<TAB>value` metadata and `Name (unit)`; whitespace .dat with `#` metadata, a names row and a `[unit]` row.
Torque in N.m, Nm or N.mm; twist in deg, rad or rev; time in s or ms (30 % start at a DAQ clock offset); the
friction channel is the shaft torque or the twist, never both; columns permuted on 30 %; WOB on about half
(always on `load_variation`); a drive column (speed or angle) on most non-modulated records (always on stepped
or held ones), never on `drive_modulation`; a bit-speed column on a quarter of those with a drive column.

Arguments: `--fn` (4 significant digits) except on seeds 5 mod 8 (never on `triggering` or `fn_off`);
`--v0` = the nominal top-drive speed in the file's angle unit per second when there is no drive column;
`--stiffness` = k_th in the file's torque unit per the file's angle unit, with that unit written after it
(`"12.5 N.mm/deg"`: `lieng diagnose --help` reads a bare number as N·m per the angle unit), on torque
records only. The angle unit
of a torque record is that of its top-drive angle column, rad for a rad/s drive column, deg for deg/s, and rad
when there is no drive column (then `--v0` is in rad/s too). Torque records never carry an rpm drive column.
"""
from __future__ import annotations

import bisect
import math
import os
import zlib

import numpy as np
from scipy import signal

NAME = "drill_string"

CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
TWO_PI = 2.0 * math.pi
RPM = TWO_PI / 60.0


def _rng(*parts) -> np.random.Generator:
    key = "|".join(str(p) for p in parts)
    return np.random.default_rng(zlib.crc32(key.encode()) + 7919 * len(key))


# --------------------------------------------------------------------------------------------
# top drive: speed-controlled motor; the angle is the exact integral of the commanded speed
# --------------------------------------------------------------------------------------------
class Drive:
    """Piecewise-linear speed (knots appended while the run goes on) or a hunting controller."""

    def __init__(self, om0: float, mod: tuple | None = None):
        self.mod = mod  # (a, fm, phase)
        self.om0 = om0
        self.tk = [0.0]
        self.ok = [om0]
        self.pk = [0.0]

    def add_knot(self, t: float, om: float) -> None:
        t0, o0, p0 = self.tk[-1], self.ok[-1], self.pk[-1]
        if t < t0:
            t = t0
        self.pk.append(p0 + 0.5 * (o0 + om) * (t - t0))
        self.tk.append(t)
        self.ok.append(om)

    def hold_level(self, t: float) -> None:
        """pin the current (constant) level at time t so a ramp can start there"""
        self.add_knot(t, self.ok[-1])

    # scalar versions (hot loop)
    def om(self, t: float) -> float:
        if self.mod is not None:
            a, fm, ph = self.mod
            return self.om0 * (1.0 + a * math.sin(TWO_PI * fm * t + ph))
        i = bisect.bisect_right(self.tk, t) - 1
        if i >= len(self.tk) - 1:
            return self.ok[-1]
        t0, t1 = self.tk[i], self.tk[i + 1]
        s = (t - t0) / (t1 - t0) if t1 > t0 else 1.0
        return self.ok[i] + s * (self.ok[i + 1] - self.ok[i])

    def phi(self, t: float) -> float:
        if self.mod is not None:
            a, fm, ph = self.mod
            w = TWO_PI * fm
            return self.om0 * (t - a / w * (math.cos(w * t + ph) - math.cos(ph)))
        i = bisect.bisect_right(self.tk, t) - 1
        dt = t - self.tk[i]
        if i >= len(self.tk) - 1:
            return self.pk[-1] + self.ok[-1] * dt
        t0, t1 = self.tk[i], self.tk[i + 1]
        sl = (self.ok[i + 1] - self.ok[i]) / (t1 - t0) if t1 > t0 else 0.0
        return self.pk[i] + self.ok[i] * dt + 0.5 * sl * dt * dt

    # vector versions
    def om_v(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, float)
        if self.mod is not None:
            a, fm, ph = self.mod
            return self.om0 * (1.0 + a * np.sin(TWO_PI * fm * t + ph))
        tk, ok = np.array(self.tk), np.array(self.ok)
        return np.interp(t, tk, ok)

    def phi_v(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, float)
        if self.mod is not None:
            a, fm, ph = self.mod
            w = TWO_PI * fm
            return self.om0 * (t - a / w * (np.cos(w * t + ph) - math.cos(ph)))
        tk, ok, pk = np.array(self.tk), np.array(self.ok), np.array(self.pk)
        i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 1)
        dt = t - tk[i]
        nxt = np.minimum(i + 1, len(tk) - 1)
        span = tk[nxt] - tk[i]
        sl = np.where((nxt > i) & (span > 0), (ok[nxt] - ok[i]) / np.where(span > 0, span, 1.0), 0.0)
        return pk[i] + ok[i] * dt + 0.5 * sl * dt * dt


# --------------------------------------------------------------------------------------------
# the rig: bit disc J on a shaft k_th from the top drive; Leine's switch model at the bit
# --------------------------------------------------------------------------------------------
class Rig:
    def __init__(self, P: dict, drive: Drive):
        self.P = P
        self.drive = drive
        self.k = P["k_th"]
        self.J = P["J"]
        self.c = P["c_shaft"]
        self.r = P["r_eff"]
        self.mus = P["mu_s"]
        self.muc = P["mu_c"]
        self.dmu = P["mu_0"] - P["mu_c"]
        self.ws = P["w_s"]
        self.dl = P["delta"]
        self.b = P["b_bit"]
        self.eta = P["eta"]
        self.W0 = P["W0"]
        self.load = P.get("load")  # None | ("twist", c, th_m) | ("angle", A, n, psi) | ("shaker", eps, ft, ph)
        self.twin = P.get("twin")  # None | (g, phi_d, tau_f)
        self.age = P.get("age")  # None | (beta, tau_a)

    # ---- normal load (WOB) ----
    def wob(self, t, ph, th):
        L = self.load
        if L is None:
            return self.W0
        if L[0] == "twist":
            return self.W0 * (1.0 + L[1] * (th - L[2]))
        if L[0] == "angle":
            return self.W0 * (1.0 + L[1] * math.sin(L[2] * ph + L[3]))
        return self.W0 * (1.0 + L[1] * math.sin(self._shaker_phase(t, L)))

    @staticmethod
    def _shaker_phase(t, L):
        # unbalanced-mass exciter on an open-loop motor: its speed wanders slowly by +-delta
        _, _, ft, ph, dl, fw, phw = L
        if dl == 0.0:
            return TWO_PI * ft * t + ph
        return TWO_PI * ft * (t - dl / (TWO_PI * fw) * (np.cos(TWO_PI * fw * t + phw) - math.cos(phw))) + ph

    def wob_v(self, t, ph, th):
        L = self.load
        t = np.asarray(t, float)
        if L is None:
            return np.full_like(t, self.W0)
        if L[0] == "twist":
            return self.W0 * (1.0 + L[1] * (th - L[2]))
        if L[0] == "angle":
            return self.W0 * (1.0 + L[1] * np.sin(L[2] * ph + L[3]))
        return self.W0 * (1.0 + L[1] * np.sin(self._shaker_phase(t, L)))

    def mus_aged(self, tst):
        if self.age is None:
            return self.mus
        beta, tau = self.age
        return self.mus + beta * math.log1p(max(tst, 0.0) / tau)

    def mus_aged_v(self, tst):
        if self.age is None:
            return np.full_like(np.asarray(tst, float), self.mus)
        beta, tau = self.age
        return self.mus + beta * np.log1p(np.maximum(tst, 0.0) / tau)

    # ---- right-hand side with Leine's switch model ----
    def rhs(self, t, ph, w, q, mus_eff, sgn=0.0):
        """sgn = 0: Leine's switch model (band |w| <= eta: stick or transition); sgn = +-1: a step
        that started in slip keeps the slip law in that direction over its stages (the zero crossing
        is then located on a smooth function of the step length and the step retaken to it)."""
        d = self.drive
        th = d.phi(t) - ph
        text = self.k * th + self.c * (d.om(t) - w)
        W = self.wob(t, ph, th)
        if sgn == 0.0 and abs(w) <= self.eta:
            ts = W * self.r * mus_eff
            if abs(text) <= ts:
                tf = text  # stick: the friction holds the bit (zero acceleration)
            else:
                tf = math.copysign(ts, text)  # transition: the static limit
            qd = -q / self.twin[2] if self.twin else 0.0
        else:
            aw = abs(w)
            mu = self.muc + self.dmu * math.exp(-((aw / self.ws) ** self.dl))
            if self.twin:
                g, phd, tauf = self.twin
                mu *= 1.0 + g * q
                qd = aw / phd * (1.0 - q) - q / tauf
            else:
                qd = 0.0
            tf = math.copysign(W * self.r * mu, sgn if sgn != 0.0 else w) + self.b * w
        return (text - tf) / self.J, qd, tf, text, W

    def rkn(self, t, ph, w, q, h, mus_eff, sgn=0.0):
        """classical 4-stage Runge-Kutta-Nystrom step for ph'' = f(t, ph, ph'), RK4 for q"""
        k1, l1, *_ = self.rhs(t, ph, w, q, mus_eff, sgn)
        h2 = 0.5 * h
        p2 = ph + h2 * w + h * h / 8.0 * k1
        k2, l2, *_ = self.rhs(t + h2, p2, w + h2 * k1, q + h2 * l1, mus_eff, sgn)
        k3, l3, *_ = self.rhs(t + h2, p2, w + h2 * k2, q + h2 * l2, mus_eff, sgn)
        k4, l4, *_ = self.rhs(t + h, ph + h * w + 0.5 * h * h * k3, w + h * k3, q + h * l3, mus_eff, sgn)
        ph_n = ph + h * w + h * h / 6.0 * (k1 + k2 + k3)
        w_n = w + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        q_n = q + h / 6.0 * (l1 + 2 * l2 + 2 * l3 + l4)
        return ph_n, w_n, q_n

    # ---- stick phase in closed form; breakaway by a scan + Illinois ----
    def stick_margin_v(self, tt, t0, ph0, w0, tst0):
        d = self.drive
        ph = ph0 + w0 * (tt - t0)
        th = d.phi_v(tt) - ph
        text = self.k * th + self.c * (d.om_v(tt) - w0)
        W = self.wob_v(tt, ph, th)
        ts = W * self.r * self.mus_aged_v(tst0 + tt - t0)
        return np.abs(text) - ts

    def stick_margin(self, t, t0, ph0, w0, tst0):
        d = self.drive
        ph = ph0 + w0 * (t - t0)
        th = d.phi(t) - ph
        text = self.k * th + self.c * (d.om(t) - w0)
        W = self.wob(t, ph, th)
        return abs(text) - W * self.r * self.mus_aged(tst0 + t - t0)

    def breakaway(self, t0, ph0, w0, tst0, dt_scan, t_max):
        ta = t0
        ga = self.stick_margin(ta, t0, ph0, w0, tst0)
        while ta < t_max:
            tt = ta + dt_scan * np.arange(1, 513)
            g = self.stick_margin_v(tt, t0, ph0, w0, tst0)
            idx = np.nonzero(g > 0)[0]
            if idx.size:
                j = idx[0]
                lo = tt[j - 1] if j > 0 else ta
                hi = tt[j]
                glo = self.stick_margin(lo, t0, ph0, w0, tst0)
                ghi = self.stick_margin(hi, t0, ph0, w0, tst0)
                side = 0
                for _ in range(80):  # Illinois (modified regula falsi)
                    m = hi - ghi * (hi - lo) / (ghi - glo) if ghi != glo else 0.5 * (lo + hi)
                    if not (lo < m < hi):
                        m = 0.5 * (lo + hi)
                    gm = self.stick_margin(m, t0, ph0, w0, tst0)
                    if gm > 0:
                        hi, ghi = m, gm
                        if side == 1:
                            glo *= 0.5
                        side = 1
                    else:
                        lo, glo = m, gm
                        if side == -1:
                            ghi *= 0.5
                        side = -1
                    if hi - lo < 1e-12 * max(1.0, hi):
                        break
                return hi
            ta = tt[-1]
            ga = g[-1]
        return None


def simulate(P: dict, drive: Drive, n_slips: int, on_arrest=None, t_limit_tn: float = 4000.0):
    """Run until n_slips slips have ended. Returns intervals for dense output and the events."""
    rig = Rig(P, drive)
    Tn = 1.0 / P["fn"]
    h = Tn / P["steps_per_tn"]
    dt_scan = Tn / 40.0
    if P.get("load") and P["load"][0] == "shaker":
        dt_scan = min(dt_scan, 1.0 / (16.0 * P["load"][2] * (1.0 + P["load"][4])))
    eta = P["eta"]
    t_max = t_limit_tn * Tn
    # intervals: ta, tb, pa, pb, wa, wb, aa, ab
    iv = []
    slipnodes = []  # per slip: list of (t, w, tf, text, W, q)
    events = []  # dicts: t_break, t_arrest, peak (text), trough, tst, wmax
    t, ph, w, q = 0.0, 0.0, 0.0, 0.0
    tst0 = 0.0  # stick age carried over trivial slips
    n_done = 0
    while n_done < n_slips:
        # ---------------- stick -----------------
        tb = rig.breakaway(t, ph, w, tst0, dt_scan, t_max)
        if tb is None:
            raise RuntimeError("no breakaway")
        phb = ph + w * (tb - t)
        iv.append((t, tb, ph, phb, w, w, 0.0, 0.0))
        tst = tst0 + tb - t
        if rig.twin:
            q = q * math.exp(-(tb - t) / rig.twin[2])
        t, ph = tb, phb
        mus_eff = rig.mus_aged(tst)
        _, _, tf0, text0, W0 = rig.rhs(t, ph, w, q, mus_eff)
        ev = {"t_break": t, "peak": text0, "tst": tst, "W_break": W0, "peak_el": rig.k * (rig.drive.phi(t) - ph)}
        nodes = [(t, w, tf0, text0, W0, q)]
        wmax = 0.0
        # ---------------- slip -----------------
        while True:
            sgn = 0.0 if abs(w) <= eta else math.copysign(1.0, w)
            a0 = rig.rhs(t, ph, w, q, mus_eff, sgn)[0]
            ph1, w1, q1 = rig.rkn(t, ph, w, q, h, mus_eff, sgn)
            hh = h
            if sgn != 0.0 and w1 * sgn <= eta:
                # the speed reaches the band within this step: retake the step to w = 0 (Illinois on
                # the step length s, the slip law held in the step's direction)
                lo, hi, wlo, whi = 0.0, h, w, w1
                side = 0
                s = h
                for _ in range(100):
                    s = hi - whi * (hi - lo) / (whi - wlo) if whi != wlo else 0.5 * (lo + hi)
                    if not (lo < s < hi):
                        s = 0.5 * (lo + hi)
                    ph1, w1, q1 = rig.rkn(t, ph, w, q, s, mus_eff, sgn)
                    if abs(w1) <= 0.05 * eta:
                        break
                    if w1 * sgn > 0:
                        lo, wlo = s, w1
                        if side == -1:
                            whi *= 0.5
                        side = -1
                    else:
                        hi, whi = s, w1
                        if side == 1:
                            wlo *= 0.5
                        side = 1
                hh = s
                a0 = rig.rhs(t, ph, w, q, mus_eff, sgn)[0]
                ab = rig.rhs(t + hh, ph1, w1, q1, mus_eff, sgn)[0]
            else:
                ab = None
            a1, _, tf1, text1, W1 = rig.rhs(t + hh, ph1, w1, q1, mus_eff)
            iv.append((t, t + hh, ph, ph1, w, w1, a0, a1 if ab is None else ab))
            t, ph, w, q = t + hh, ph1, w1, q1
            wmax = max(wmax, abs(w))
            nodes.append((t, w, tf1, text1, W1, q))
            if abs(w) <= eta and a1 == 0.0:
                break  # arrested: Leine stick
            if t > t_max:
                raise RuntimeError("slip never ended")
        if wmax < 0.02 * P["om_ref"]:
            tst0 = tst  # a stutter inside the band: the contact keeps its age
            continue
        tst0 = 0.0
        ev.update({"t_arrest": t, "trough": text1, "wmax": wmax})
        events.append(ev)
        slipnodes.append(np.array(nodes))
        n_done += 1
        if on_arrest is not None:
            on_arrest(n_done, t)
    return np.array(iv), events, slipnodes


def dense(iv: np.ndarray, tgrid: np.ndarray):
    """cubic Hermite of the bit angle (derivative w) and of the speed (derivative acceleration)"""
    ta, tb = iv[:, 0], iv[:, 1]
    i = np.clip(np.searchsorted(ta, tgrid, side="right") - 1, 0, len(ta) - 1)
    a, b = ta[i], tb[i]
    hh = np.where(b > a, b - a, 1.0)
    s = np.clip((tgrid - a) / hh, 0.0, 1.0)
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    pa, pb, wa, wb, aa, ab = (iv[i, j] for j in range(2, 8))
    ph = h00 * pa + h10 * hh * wa + h01 * pb + h11 * hh * wb
    w = h00 * wa + h10 * hh * aa + h01 * wb + h11 * hh * ab
    return ph, w


# --------------------------------------------------------------------------------------------
# ground-truth measures
# --------------------------------------------------------------------------------------------
def twin_of(slipnodes, events, eta, use_ratio=False):
    vals = []
    for nd, ev in zip(slipnodes, events):
        w, tf, W = nd[:, 1], nd[:, 2], nd[:, 4]
        y = tf / W if use_ratio else tf
        drop = ev["peak"] - ev["trough"]
        if use_ratio:
            drop = ev["peak"] / ev["W_break"] - ev["trough"] / nd[-1, 4]
        m = np.abs(w) > 2 * eta
        if m.sum() < 8 or drop <= 0:
            continue
        j = int(np.argmax(w))
        acc = slice(0, j + 1)
        dec = slice(j, len(w))
        wa, ya = w[acc][m[acc]], y[acc][m[acc]]
        wd, yd = w[dec][m[dec]], y[dec][m[dec]]
        if len(wa) < 3 or len(wd) < 3:
            continue
        lv = np.linspace(0.1, 0.9, 17) * w[j]
        oa, od = np.argsort(wa), np.argsort(wd)
        fa = np.interp(lv, wa[oa], ya[oa])
        fd = np.interp(lv, wd[od], yd[od])
        vals.append(np.mean(fd - fa) / drop)
    return float(np.median(vals)) if vals else float("nan")


def ageing_of(events, skip=1, key="peak"):
    ev = events[skip:]
    tst = np.array([e["tst"] for e in ev])
    pk = np.array([e[key] for e in ev])
    drop = np.median([e["peak"] - e["trough"] for e in ev])
    ratio = tst.max() / tst.min()
    if ratio < 1.3:
        return 0.0, float(ratio), float(np.std(pk) / drop)
    A = np.vstack([np.ones_like(tst), np.log(tst)]).T
    coef = np.linalg.lstsq(A, pk, rcond=None)[0]
    return float(coef[1] * math.log(ratio) / drop), float(ratio), float(np.std(pk - A @ coef) / drop)


# --------------------------------------------------------------------------------------------
# parameters
# --------------------------------------------------------------------------------------------
def _draw_params(case: str, seed: int) -> dict:
    rg = _rng("drill_string-phys", case, seed)
    P: dict = {}
    fn = float(math.exp(rg.uniform(math.log(1.5), math.log(12.0))))
    W0 = 1000.0 * float(math.exp(rg.uniform(math.log(0.3), math.log(8.0))))  # WOB, N
    wn = TWO_PI * fn
    stepped = case == "static_ageing" or (case == "none" and seed % 8 in (2, 5))
    holds = stepped and case == "static_ageing" and seed % 2 == 1
    if stepped and not holds:
        om_hi_rpm = float(rg.uniform(45.0, 110.0))
        ratio = float(rg.uniform(4.0, 8.0))
        om_n_rpm = om_hi_rpm
    else:
        om_n_rpm = float(rg.uniform(12.0, 80.0 if case == "drive_modulation" else 100.0))
        ratio = 1.0
    om_ref = om_n_rpm * RPM
    r_eff = float(rg.uniform(0.02, 0.05))
    mu_s = float(rg.uniform(0.35, 0.6))
    dgap = float(rg.uniform(0.2, 0.4))
    mu_c = mu_s * (1.0 - dgap)
    x_static = float(rg.uniform(0.03, 0.08))
    eps_t = float(rg.uniform(0.035, 0.075))
    if case == "triggering":
        x_static = max(x_static, 1.6 * eps_t)
    mu_0 = mu_s / (1.0 + x_static)  # the Stribeck curve's limit at 0+ (Leine's static level above it)
    R = float(rg.uniform(3.0, 6.0))
    # the shaft is sized so that the slip overshoots the drive speed R-fold: k = W0 r dmu wn / (R Omega)
    k = W0 * wn * r_eff * (mu_s - mu_c) / (R * om_ref)
    J = k / wn**2
    u = float(rg.uniform(0.3, 0.8))
    w_s = u * om_ref * (1.0 + R) / 2.0
    delta = float(rg.uniform(0.5, 2.0))
    dT = W0 * r_eff * (mu_s - mu_c)
    b_bit = float(rg.uniform(0.02, 0.06)) * dT / (om_ref * (1.0 + R))
    zeta = float(rg.uniform(0.005, 0.02))
    P.update(
        fn=fn, k_th=k, J=J, om_n=om_ref, om_ref=om_ref, om_n_rpm=om_n_rpm, step_ratio=ratio,
        stepped=bool(stepped and not holds), holds=bool(holds), r_eff=r_eff, mu_s=mu_s, mu_c=mu_c,
        R_overshoot=R, mu_0=mu_0, x_static=x_static, W0=W0, w_s=w_s, delta=delta, b_bit=b_bit, zeta_shaft=zeta,
        c_shaft=2.0 * zeta * math.sqrt(k * J), eta=1e-4 * om_ref, steps_per_tn=int(rg.integers(220, 300)),
        n_cycles=int(rg.integers(18, 37)),
    )
    P["th_slip_est"] = 2.0 * R * om_ref / wn
    # departures' raw draws
    P["target_load_pp"] = float(rg.uniform(0.12, 0.28))
    P["load_kind"] = "twist" if seed % 2 == 0 else "angle"
    P["load_sign"] = -1.0 if seed % 8 == 6 else 1.0
    P["target_twin"] = float(rg.uniform(0.12, 0.18))
    P["phi_d"] = float(rg.uniform(0.3, 0.8)) * P["th_slip_est"]
    P["tau_f"] = float(rg.uniform(0.3, 1.0)) / fn
    P["target_age"] = float(rg.uniform(0.12, 0.22))
    P["eps_t"] = eps_t
    P["ft_over_fn"] = float(rg.uniform(3.2, 6.8))
    P["ph_t"] = float(rg.uniform(0, TWO_PI))
    P["a_mod"] = float(rg.uniform(0.22, 0.43))
    P["fm_frac"] = float(rg.uniform(0.15, 0.35))
    P["ph_m"] = float(rg.uniform(0, TWO_PI))
    P["n_wave"] = int(rg.integers(1, 3))
    P["psi"] = float(rg.uniform(0, TWO_PI))
    P["hold_mult"] = [float(x) for x in rg.uniform(1.5, 9.0, size=8)]
    P["seg_slips"] = [int(x) for x in rg.integers(3, 7, size=10)]
    return P


def _make_drive(P: dict) -> tuple[Drive, callable]:
    """drive and the operator's actions at each arrest (speed steps or holds)"""
    om = P["om_ref"]
    Tn = 1.0 / P["fn"]
    if P.get("mod"):
        return Drive(om, P["mod"]), None
    d = Drive(om)
    ramp = 0.6 * Tn
    if P["stepped"]:
        lo = om / P["step_ratio"]
        state = {"seg": 0, "cnt": 0, "level": om}
        segs = P["seg_slips"]

        def act(n, t):
            state["cnt"] += 1
            need = segs[state["seg"] % len(segs)]
            if state["level"] < om:
                need = max(2, need - 2)  # fewer of the long slow cycles
            if n >= 2 and state["cnt"] >= need:
                state["cnt"] = 0
                state["seg"] += 1
                new = lo if state["level"] == om else om
                t0 = t + 0.25 * Tn
                d.hold_level(t0)
                d.add_knot(t0 + ramp, new)
                state["level"] = new

        return d, act
    if P["holds"]:
        state = {"k": 0, "cnt": 0}
        t_st = P.get("tst_nominal", 2.0 * Tn)

        def act(n, t):
            state["cnt"] += 1
            if n >= 2 and state["cnt"] >= P["seg_slips"][state["k"] % 10]:
                state["cnt"] = 0
                hold = P["hold_mult"][state["k"] % 8] * t_st
                state["k"] += 1
                t0 = t + 0.2 * t_st
                d.hold_level(t0)
                d.add_knot(t0 + ramp, 0.0)
                d.add_knot(t0 + ramp + hold, 0.0)
                d.add_knot(t0 + 2 * ramp + hold, om)

        return d, act
    return d, None


def _run(P: dict, n_slips: int):
    d, act = _make_drive(P)
    iv, ev, sn = simulate(P, d, n_slips, act)
    return d, iv, ev, sn


def _fss(ev, skip):
    tb = np.array([e["t_break"] for e in ev[skip:]])
    return (len(tb) - 1) / (tb[-1] - tb[0])


def _build(case: str, seed: int):
    P = _draw_params(case, seed)
    Tn = 1.0 / P["fn"]
    n_pre = 2
    n_tot = P["n_cycles"] + n_pre + 1
    pilot_n = 10
    info: dict = {}
    # pilot of the baseline rig: stick time and drop
    d, iv, ev, sn = _run(P, pilot_n)
    f_ss0 = _fss(ev, 2)
    P["tst_nominal"] = float(np.median([e["tst"] for e in ev[2:]]))
    th_pp = (max(e["peak"] for e in ev[2:]) - min(e["trough"] for e in ev[2:])) / P["k_th"]
    th_m = 0.5 * (max(e["peak"] for e in ev[2:]) + min(e["trough"] for e in ev[2:])) / P["k_th"]
    if case == "load_variation":
        tgt = P["target_load_pp"]
        if P["load_kind"] == "angle":
            rot = P["n_cycles"] * P["om_ref"] / f_ss0
            if rot * P["n_wave"] < 1.6 * TWO_PI:
                P["load_kind"] = "twist"
        if P["load_kind"] == "angle":
            P["load"] = ("angle", tgt / 2.0, float(P["n_wave"]), P["psi"])
        else:
            c = P["load_sign"] * tgt / th_pp
            for _ in range(3):
                P["load"] = ("twist", c, th_m)
                d, iv, ev, sn = _run(P, pilot_n)
                ths = [e["peak"] / P["k_th"] for e in ev[2:]] + [e["trough"] / P["k_th"] for e in ev[2:]]
                pp = abs(c) * (max(ths) - min(ths))
                c *= tgt / pp
                th_m = 0.5 * (max(ths) + min(ths))
            P["load"] = ("twist", c, th_m)
    elif case == "twin_branch":
        g = 0.3
        for _ in range(3):
            P["twin"] = (g, P["phi_d"], P["tau_f"])
            d, iv, ev, sn = _run(P, pilot_n)
            tw = twin_of(sn[2:], ev[2:], P["eta"])
            g = g * P["target_twin"] / max(tw, 1e-3)
        P["twin"] = (g, P["phi_d"], P["tau_f"])
    elif case == "static_ageing":
        tau_a = 0.15 * P["tst_nominal"] if not P["holds"] else 0.3 * P["tst_nominal"]
        beta = 0.02 * P["mu_s"]
        for _ in range(3):
            P["age"] = (beta, tau_a)
            d, iv, ev, sn = _run(P, 16 if P["stepped"] else 14)
            gr, _, _ = ageing_of(ev, 2)
            beta *= P["target_age"] / max(gr, 1e-3)
        P["age"] = (beta, tau_a)
    elif case == "triggering":
        # the breakaways lock to the shaker's troughs (1:n) over nearly all the band, with sharp steps
        # between the n- and (n+1)-locks. The exciter's speed wanders slowly (+-delta), so a mean f_t
        # near a step makes the record mix n and (n+1) shaker periods; that step is found by bisection
        # on full-length runs.
        fn_ = P["fn"]
        rgt = _rng("drill_string-shaker", seed)
        dl = float(rgt.uniform(0.015, 0.035))
        fw = float(rgt.uniform(1.0, 2.5)) * f_ss0 / n_tot
        phw = float(rgt.uniform(0, TWO_PI))
        memo = {}

        def ratio(ft):
            P["load"] = ("shaker", P["eps_t"], ft, P["ph_t"], dl, fw, phw)
            res = _run(P, n_tot)
            r = ft / _fss(res[2], n_pre)
            memo[ft] = (r, res)
            return r

        def dist(r):
            return abs(r - round(r))

        fa = P["ft_over_fn"] * fn_
        ra = ratio(fa)
        best = fa
        if dist(ra) < 0.2:
            na = round(ra)
            fb = fa * (na + 1) / na
            if fb > 7.0 * fn_:
                fb = fa * (na - 1) / na
            rb = ratio(fb)
            if dist(rb) > dist(ra):
                best = fb
            for _ in range(14):
                if dist(memo[best][0]) >= 0.2:
                    break
                fm_ = 0.5 * (fa + fb)
                rm = ratio(fm_)
                if dist(rm) > dist(memo[best][0]):
                    best = fm_
                if dist(rm) >= 0.2:
                    break
                if abs(rm - ra) < abs(rm - rb):
                    fa, ra = fm_, rm
                else:
                    fb, rb = fm_, rm
        P["load"] = ("shaker", P["eps_t"], best, P["ph_t"], dl, fw, phw)
        P["shaker_wander"] = dl
        P["_trig_res"] = memo[best][1]
    elif case == "drive_modulation":
        P["mod"] = (P["a_mod"], P["fm_frac"] * f_ss0, P["ph_m"])
    if case == "triggering":
        d, iv, ev, sn = P.pop("_trig_res")
    else:
        d, iv, ev, sn = _run(P, n_tot)
    return P, d, iv, ev, sn, info


# --------------------------------------------------------------------------------------------
# ground truth summary
# --------------------------------------------------------------------------------------------
def _truth(P, d, iv, ev, sn, n_pre, t0, t1):
    rig = Rig(P, d)
    evr = [e for e in ev if e["t_break"] >= t0 and e["t_arrest"] <= t1]
    snr = [s for s, e in zip(sn, ev) if e["t_break"] >= t0 and e["t_arrest"] <= t1]
    drops = np.array([e["peak"] - e["trough"] for e in evr])
    out = {
        "n_slips_in_record": len(evr),
        "drop_torque_Nm_median": float(np.median(drops)),
        "peak_torque_Nm_median": float(np.median([e["peak"] for e in evr])),
        "f_ss_Hz": float(_fss(evr, 0)),
        "fss_over_fn": float(_fss(evr, 0) / P["fn"]),
        "wmax_over_om_min": float(min(e["wmax"] for e in evr) / P["om_ref"]),
        "twin_true_over_drop": twin_of(snr, evr, P["eta"]),
        "twin_true_mu_over_drop": twin_of(snr, evr, P["eta"], use_ratio=True),
    }
    ag, ratio, sd = ageing_of(evr, 0)
    out.update(ageing_growth_over_drop=ag, stick_time_ratio=ratio, peak_resid_sd_over_drop=sd)
    out["ageing_growth_shaft_torque_over_drop"] = ageing_of(evr, 0, "peak_el")[0]
    tt = np.linspace(t0, t1, 20000)
    ph, _ = dense(iv, tt)
    th = d.phi_v(tt) - ph
    W = rig.wob_v(tt, ph, th)
    out["wob_pp_over_W0"] = float((W.max() - W.min()) / P["W0"])
    om = d.om_v(tt)
    out["drive_rpm_min"] = float(om.min() / RPM)
    out["drive_rpm_max"] = float(om.max() / RPM)
    if P.get("load") and P["load"][0] == "shaker":
        r = P["load"][2] / out["f_ss_Hz"]
        out["ft_over_fss"] = float(r)
        out["ft_over_fss_dist_int"] = float(abs(r - round(r)))
        out["ft_over_fn"] = float(P["load"][2] / P["fn"])
    if P.get("mod"):
        out["fm_over_fss"] = float(P["mod"][1] / out["f_ss_Hz"])
    return out


# --------------------------------------------------------------------------------------------
# sensor chain
# --------------------------------------------------------------------------------------------
def _second_order(x, fs, f0, zeta):
    w0 = TWO_PI * f0
    b, a = signal.bilinear([w0 * w0], [1.0, 2 * zeta * w0, w0 * w0], fs=fs)
    zi = signal.lfilter_zi(b, a) * x[0]
    return signal.lfilter(b, a, x, zi=zi)[0]


def _first_order(x, fs, fc):
    b, a = signal.bilinear([1.0], [1.0 / (TWO_PI * fc), 1.0], fs=fs)
    zi = signal.lfilter_zi(b, a) * x[0]
    return signal.lfilter(b, a, x, zi=zi)[0]


def _butter(x, fs, fc, order):
    sos = signal.butter(order, fc, fs=fs, output="sos")
    zi = signal.sosfilt_zi(sos) * x[0]
    return signal.sosfilt(sos, x, zi=zi)[0]


def _ar1(rg, n, rho, sd):
    e = rg.normal(0.0, sd * math.sqrt(1 - rho * rho), n)
    x0 = rg.normal(0.0, sd)
    y = signal.lfilter([1.0], [1.0, -rho], e, zi=[rho * x0])[0]
    return y


ANG = {"rad": 1.0, "deg": 180.0 / math.pi, "rev": 1.0 / TWO_PI}
TORQ = {"N.m": 1.0, "Nm": 1.0, "N.mm": 1000.0}
NICE_FS = [10, 12, 15, 16, 20, 24, 25, 30, 32, 40, 48, 50, 60, 64, 80, 100, 120, 125, 128, 150, 160, 200, 240, 250,
           256, 300, 320, 400, 480, 500, 512, 600, 640, 800, 1000, 1024, 1200, 1250, 1280, 1500, 1600]


def _choose_fs(rg, fn, lo, hi):
    spp = rg.uniform(lo, hi)
    cands = [f for f in NICE_FS if lo <= f / fn <= hi]
    if cands and rg.uniform() < 0.8:
        return float(min(cands, key=lambda f: abs(f / fn - spp)))
    return float(round(spp * fn, 1))


def _dc(v):
    try:
        float(v)
        return str(v).replace(".", ",")
    except ValueError:
        return str(v)


def _write(path, style, cols, meta, time_unit, fs):
    """cols: list of (name, unit, values, fmt)"""
    n = len(cols[0][2])
    lines = []
    nl = "\n"
    dec_comma = False
    if style == "csv_meta":
        lines += [f"{k},{v}" for k, v in meta]
        lines.append("")
        lines.append(",".join(f"{nm} [{u}]" for nm, u, *_ in cols))
        sep = ","
    elif style == "csv_idx":
        nl = "\r\n"
        lines.append(f'"{meta[0][1]}"')
        lines += [f'"{k}: {v}"' for k, v in meta[1:]]
        lines.append(",".join(['"Sample"'] + [f'"{nm} ({u})"' for nm, u, *_ in cols]))
        sep = ","
    elif style == "semicolon":
        dec_comma = True
        lines += [f"{k};{_dc(v)}" for k, v in meta]
        lines.append(";".join(f"{nm} [{u}]" for nm, u, *_ in cols))
        sep = ";"
    elif style == "lvm":
        hdr = [
            "LabVIEW Measurement\t", "Writer_Version\t2", "Reader_Version\t2", "Separator\tTab",
            "Decimal_Separator\t.", "Multi_Headings\tNo", "X_Columns\tOne", "Time_Pref\tRelative",
            f"Operator\t{dict(meta).get('Operator', 'rig')}", f"Date\t{dict(meta)['Date'].split(' ')[0].replace('-', '/')}",
            f"Time\t{dict(meta)['Date'].split(' ')[1]}.000", "***End_of_Header***", "\t",
        ]
        m = len(cols) - 1
        hdr += [
            f"Channels\t{m}" + "\t" * m,
            "Samples\t" + "\t".join([str(n)] * m),
            "Date\t" + "\t".join([dict(meta)["Date"].split(" ")[0].replace("-", "/")] * m),
            "Time\t" + "\t".join([dict(meta)["Date"].split(" ")[1] + ".000"] * m),
            "X_Dimension\t" + "\t".join(["Time"] * m),
            "X0\t" + "\t".join(["0.0000000000000000E+0"] * m),
            "Delta_X\t" + "\t".join([f"{1.0 / fs:.6f}"] * m),
            "***End_of_Header***",
        ]
        lines += hdr
        lines.append("X_Value\t" + "\t".join(f"{nm} [{u}]" for nm, u, *_ in cols[1:]) + "\tComment")
        sep = "\t"
    elif style == "tab":
        lines += [f"{k}:\t{v}" for k, v in meta]
        lines.append("")
        lines.append("\t".join(f"{nm} ({u})" for nm, u, *_ in cols))
        sep = "\t"
    else:  # whitespace .dat with a names row and a units row
        lines += [f"# {k}: {v}" for k, v in meta]
        w = [max(14, len(nm) + 2, len(u) + 4) for nm, u, *_ in cols]
        lines.append("".join(f"{nm:>{wi}}" for (nm, *_), wi in zip(cols, w)))
        lines.append("".join(f"{'[' + u + ']':>{wi}}" for (nm, u, *_), wi in zip(cols, w)))
        sep = None
    body = []
    strs = [[fmt % v for v in vals] for _, _, vals, fmt in cols]
    for i in range(n):
        row = [s[i] for s in strs]
        if style == "csv_idx":
            row = [str(i)] + row
        if sep is None:
            body.append("".join(f"{x:>{wi}}" for x, wi in zip(row, w)))
        else:
            r = sep.join(row)
            if dec_comma:
                r = r.replace(".", ",")
            body.append(r)
    with open(path, "w", newline="") as f:
        f.write(nl.join(lines + body) + nl)


def _meta(rg, fs, seed, case_code):
    labs = [("TU/e drill-string setup", "Eindhoven"), ("Drill-string torsional test rig", "Nantes"),
            ("DSR-2 torsional bench", "lab 3.14"), ("Stick-slip drill rig", "Dynamics lab")]
    lab = labs[int(rg.integers(len(labs)))]
    day = int(rg.integers(1, 28))
    mon = int(rg.integers(1, 13))
    hh, mm, ss = int(rg.integers(8, 19)), int(rg.integers(60)), int(rg.integers(60))
    ops = ["J. de Vries", "M. Leclerc", "A. Kumar", "S. Otten", "rig"]
    return [
        ("Rig", lab[0]),
        ("Site", lab[1]),
        ("Date", f"2023-{mon:02d}-{day:02d} {hh:02d}:{mm:02d}:{ss:02d}"),
        ("Operator", ops[int(rg.integers(len(ops)))]),
        ("Run", f"R{seed:03d}-{case_code}"),
        ("Sample rate [Hz]", f"{fs:g}"),
    ]


def _nice_range(x):
    for r in (0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500, 1e3, 2e3, 5e3, 1e4, 2e4, 5e4, 1e5, 2e5, 5e5, 1e6):
        if r >= x:
            return r
    return x


def _adc(x, step):
    return np.round(x / step) * step


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.bool_):
        return bool(o)
    return o


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    os.makedirs(outdir, exist_ok=True)
    P, d, iv, ev, sn, _ = _build(case, seed)
    rig = Rig(P, d)
    rg = _rng("drill_string-sensors", case, seed, nuisance)
    fn = P["fn"]
    Tn = 1.0 / fn
    k = P["k_th"]
    n_pre = 2
    # ---------------- record window ----------------
    a_prev = ev[n_pre - 1]["t_arrest"]
    t0 = a_prev + rg.uniform(0.15, 0.75) * (ev[n_pre]["t_break"] - a_prev)
    min_tst = min(e["tst"] for e in ev[n_pre:])
    t1 = ev[-1]["t_arrest"] + rg.uniform(0.2, 0.5) * min_tst
    truth = _truth(P, d, iv, ev, sn, n_pre, t0, t1)
    # ---------------- sampling ----------------
    if nuisance == "coarse":
        fs = _choose_fs(rg, fn, 10.0, 15.0)
    else:
        fs = _choose_fs(rg, fn, 20.0, 100.0)
    spp = fs / fn
    M = max(4, int(math.ceil(640.0 / spp)))
    fsf = fs * M
    n_s = int(math.floor((t1 - t0) * fs)) + 1
    J0 = int(math.ceil(min(t0, 3.0 * Tn + 0.05) * fsf))
    jj = np.arange(-J0, (n_s - 1) * M + 1)
    tf = t0 + jj / fsf
    isamp = J0 + M * np.arange(n_s)
    ts = tf[isamp]
    ph_b, w_b = dense(iv, tf)
    phi_td = d.phi_v(tf)
    om_td = d.om_v(tf)
    th = phi_td - ph_b
    W = rig.wob_v(tf, ph_b, th)
    drop_T = truth["drop_torque_Nm_median"]

    # ---------------- channel plan ----------------
    frict = "torque" if rg.uniform() < 0.5 else "twist"
    twist_analog = frict == "twist" and (nuisance in ("hum", "drift") or rg.uniform() < 0.25)
    if case == "drive_modulation":
        drive_kind = None
    elif P["stepped"] or P["holds"]:
        drive_kind = "speed" if rg.uniform() < 0.55 else "angle"
    else:
        u = rg.uniform()
        drive_kind = None if u < 0.35 else ("speed" if u < 0.75 else "angle")
    has_wob = case == "load_variation" or rg.uniform() < (0.5 if case == "triggering" else 0.4)
    has_bit = drive_kind is not None and rg.uniform() < 0.25
    has_aa = rg.uniform() < 0.6
    style = ["csv_meta", "csv_idx", "semicolon", "lvm", "tab", "dat"][int(rg.integers(6))]
    tunit = "ms" if (style in ("csv_idx", "semicolon") and rg.uniform() < 0.7) or (style == "tab" and rg.uniform() < 0.3) else "s"
    if style == "lvm":
        tunit = "s"
    if frict == "torque":
        f_unit = ["N.m", "Nm", "N.mm"][int(rg.integers(3))]
    else:
        f_unit = ["deg", "rad", "rev"][int(rg.integers(3))]
    if drive_kind == "speed":
        d_unit = (["rpm", "rad/s", "deg/s"] if frict == "twist" else ["rad/s", "deg/s"])[int(rg.integers(3 if frict == "twist" else 2))]
    elif drive_kind == "angle":
        d_unit = ["deg", "rev", "rad"][int(rg.integers(3))]
    else:
        d_unit = None
    if frict == "twist":
        ang_unit = f_unit
    elif drive_kind == "angle":
        ang_unit = d_unit
    elif drive_kind == "speed":
        ang_unit = "rad" if d_unit == "rad/s" else "deg"
    else:
        ang_unit = "rad"
    wob_unit = "kN" if rg.uniform() < 0.5 else "N"

    # ---------------- friction channel ----------------
    sens: dict = {"fs_Hz": fs, "samples_per_Tn": spp, "anti_alias": bool(has_aa)}
    enc_counts = int(4 * [1024, 2048, 2500, 4096, 5000][int(rg.integers(5))])
    if nuisance == "quantisation" and frict == "twist" and not twist_analog:
        step_th = rg.uniform(0.003, 0.01) * drop_T / k
        enc_counts = int(max(64, round(TWO_PI / step_th)))
    q_enc = TWO_PI / enc_counts
    sens["encoder_counts_per_rev"] = enc_counts
    if frict == "torque" or twist_analog:
        if frict == "torque":
            fr = min(rg.uniform(12.0, 40.0) * fn, 0.15 * fsf)
            zr = rg.uniform(0.2, 0.7)
            x = _second_order(k * th, fsf, fr, zr) * TORQ[f_unit]
            sens.update(torque_transducer_f_Hz=fr, torque_transducer_zeta=zr)
            scale = TORQ[f_unit]
        else:
            fr = min(rg.uniform(8.0, 25.0) * fn, 0.15 * fsf)
            zr = rg.uniform(0.7, 1.0)
            x = _second_order(th, fsf, fr, zr) * ANG[f_unit]
            sens.update(rd_converter_f_Hz=fr, rd_converter_zeta=zr)
            scale = ANG[f_unit] / k
        if has_aa:
            fc = rg.uniform(0.25, 0.4) * fs
            x = _butter(x, fsf, fc, int(rg.integers(2, 5)))
            sens["anti_alias_fc_Hz"] = fc
        xs = x[isamp]
        drop_ch = drop_T * scale
        xs = xs + rg.uniform(-0.005, 0.005) * drop_ch  # zeroing offset
        wn_sd = rg.uniform(0.002, 0.006) * drop_ch
        cn_sd = rg.uniform(0.002, 0.005) * drop_ch
        rho = math.exp(-1.0 / (fs * rg.uniform(0.3, 3.0) * Tn))
        xs = xs + rg.normal(0.0, wn_sd, n_s) + _ar1(rg, n_s, rho, cn_sd)
        analog = True
    else:
        n_td = np.floor(phi_td[isamp] / q_enc)
        n_b = np.floor(ph_b[isamp] / q_enc)
        xs = (n_td - n_b) * q_enc
        # torsional jitter of the encoder couplings (coloured, small)
        drop_ch = drop_T / k * ANG[f_unit]
        xs = xs * ANG[f_unit]
        rho = math.exp(-1.0 / (fs * 0.05 * Tn))
        xs = xs + _ar1(rg, n_s, rho, rg.uniform(0.001, 0.003) * drop_ch)
        analog = False
    sens["friction_channel"] = frict + ("_analog_RD" if twist_analog else ("_encoders" if frict == "twist" else "_strain_gauge"))
    # ---------------- nuisances on the friction channel ----------------
    nz: dict = {}
    if nuisance == "hum":
        fh = 50.0 if rg.uniform() < 0.6 else 60.0
        A = rg.uniform(0.01, 0.05) * drop_ch
        hn = int(rg.integers(2, 4))
        Ah = rg.uniform(0.2, 0.5) * A
        ph1, ph2 = rg.uniform(0, TWO_PI, 2)
        hum = A * np.sin(TWO_PI * fh * ts + ph1) + Ah * np.sin(TWO_PI * hn * fh * ts + ph2)
        xs = xs + hum
        nz.update(hum_Hz=fh, hum_amp_over_drop=A / drop_ch, hum_harmonic=hn, hum_harm_amp_over_drop=Ah / drop_ch)
    if nuisance == "drift":
        D = rg.uniform(0.03, 0.1) * drop_ch * (1 if rg.uniform() < 0.5 else -1)
        T = ts[-1] - ts[0]
        tau = rg.uniform(0.3, 2.0) * T
        xs = xs + D * (1 - np.exp(-(ts - ts[0]) / tau)) / (1 - math.exp(-T / tau))
        nz.update(drift_over_drop=D / drop_ch, drift_tau_over_record=tau / T)
    if nuisance == "spikes":
        ns = max(3, int(round(rg.uniform(0.0005, 0.004) * n_s)))
        idx = rg.choice(np.arange(2, n_s - 2), size=ns, replace=False)
        amp = rg.uniform(0.5, 3.0, ns) * np.where(rg.uniform(size=ns) < 0.5, -1, 1) * drop_ch
        xs = xs.copy()
        xs[idx] += amp
        nz.update(n_spikes=int(ns), spike_fraction=ns / n_s)
    if analog:
        if nuisance == "quantisation":
            step = rg.uniform(0.003, 0.01) * drop_ch
        else:
            step = 2 * _nice_range(1.3 * np.max(np.abs(xs))) / 65536.0
        xs = _adc(xs, step)
        nz["adc_step_over_drop"] = step / drop_ch
    else:
        nz["encoder_step_over_drop"] = q_enc * ANG[f_unit] / drop_ch
    # ---------------- other channels ----------------
    cols = []
    ws = style == "dat"

    def nm(options):
        s = options[int(rg.integers(len(options)))]
        return s.replace(" ", "_") if ws else s

    if frict == "torque":
        cols.append((nm(["Torque_bit", "Bit torque", "TOB", "Torque"]), f_unit, xs, "%.7g"))
    else:
        cols.append((nm(["Twist", "Twist angle", "Delta_phi", "Shaft twist"]), f_unit, xs, "%.7g"))
    others = []
    if drive_kind == "speed":
        tau = rg.uniform(0.003, 0.015)
        y = _first_order(om_td, fsf, 1.0 / (TWO_PI * tau))
        y = y * (1.0 + rg.uniform(0.005, 0.015) * np.sin(12.0 * phi_td + rg.uniform(0, TWO_PI)))
        ys = y[isamp] + rg.normal(0, 0.003 * P["om_ref"], n_s)
        if nuisance == "hum":
            ys = ys + 0.01 * P["om_ref"] * np.sin(TWO_PI * nz["hum_Hz"] * ts + rg.uniform(0, TWO_PI))
        conv = {"rpm": 1.0 / RPM, "rad/s": 1.0, "deg/s": 180.0 / math.pi}[d_unit]
        ys = ys * conv
        ys = _adc(ys, 2 * _nice_range(1.3 * np.max(np.abs(ys))) / 65536.0)
        others.append((nm(["TopDrive speed", "Top drive speed", "Motor speed", "TD_speed"]), d_unit, ys, "%.6g"))
        sens["tacho_tau_s"] = tau
    elif drive_kind == "angle":
        ys = np.floor(phi_td[isamp] / q_enc) * q_enc * ANG[d_unit]
        others.append((nm(["TopDrive angle", "Top drive angle", "Motor angle", "phi_TD"]), d_unit, ys, "%.8g"))
    if has_bit:
        nb = np.floor(ph_b[isamp] / q_enc)
        bs = np.diff(nb, prepend=nb[0] - (nb[1] - nb[0])) * q_enc * fs / RPM
        others.append((nm(["Bit speed", "Bit_speed", "Lower disc speed"]), "rpm", bs, "%.6g"))
    if has_wob:
        fcw = min(rg.uniform(20.0, 60.0) * fn, 0.2 * fsf)
        y = _first_order(W, fsf, fcw)[isamp]
        y = y + rg.normal(0, rg.uniform(0.002, 0.004) * P["W0"], n_s) + _ar1(rg, n_s, 0.98, 0.002 * P["W0"])
        if nuisance == "hum":
            y = y + rg.uniform(0.003, 0.01) * P["W0"] * np.sin(TWO_PI * nz["hum_Hz"] * ts + rg.uniform(0, TWO_PI))
        if nuisance == "drift":
            y = y + rg.uniform(-0.01, 0.01) * P["W0"] * (ts - ts[0]) / (ts[-1] - ts[0])
        y = y / (1000.0 if wob_unit == "kN" else 1.0)
        y = _adc(y, 2 * _nice_range(1.3 * np.max(np.abs(y))) / 65536.0)
        others.append((nm(["WOB", "Weight on bit", "Axial load"]), wob_unit, y, "%.6g"))
    if rg.uniform() < 0.3:
        allc = cols + others
        order = rg.permutation(len(allc))
        allc = [allc[i] for i in order]
    else:
        allc = cols + others
    toff = 0.0 if (style == "lvm" or rg.uniform() < 0.7) else float(round(rg.uniform(1.0, 600.0), 3))
    tt = (ts - ts[0]) + toff
    tt = np.round(tt * fs) / fs if toff == 0.0 else tt
    tcol = ("Time", tunit, tt * (1000.0 if tunit == "ms" else 1.0), "%.3f" if tunit == "ms" else "%.6f")
    allc = [tcol] + allc
    code = "%04x" % (zlib.crc32(f"{case}{seed}{nuisance}".encode()) & 0xFFFF)
    meta = _meta(rg, fs, seed, code)
    ext = {"csv_meta": ".csv", "csv_idx": ".csv", "semicolon": ".csv", "lvm": ".lvm", "tab": ".txt", "dat": ".dat"}[style]
    path = os.path.abspath(os.path.join(outdir, f"drill_string_{case}_s{seed:02d}_{nuisance}{ext}"))
    _write(path, style, allc, meta, tunit, fs)
    # ---------------- CLI args ----------------
    args: list[str] = []
    fn_given = None
    if not (seed % 8 == 5 and case != "triggering" and nuisance != "fn_off"):
        f = fn * (1.0 + (0.05 if rg.uniform() < 0.5 else -0.05)) if nuisance == "fn_off" else fn
        fn_given = float(f"{f:.4g}")
        args += ["--fn", f"{fn_given:.4g}"]
    if drive_kind is None:
        args += ["--v0", f"{P['om_n'] * ANG[ang_unit]:.5g}"]
    if frict == "torque":
        # (with its unit, as `lieng diagnose --help` has it: a bare number is N·m per the angle unit)
        args += ["--stiffness", f"{k * TORQ[f_unit] / ANG[ang_unit]:.5g} {f_unit}/{ang_unit}"]
    params = {k_: v for k_, v in P.items() if k_ not in ("hold_mult", "seg_slips")}
    params.update(
        truth=truth, sensors=sens, nuisance_detail=nz, style=style, time_unit=tunit, friction_unit=f_unit,
        drive_column=drive_kind, drive_unit=d_unit, angle_unit_for_args=ang_unit, wob_column=bool(has_wob),
        wob_unit=wob_unit if has_wob else None, bit_speed_column=bool(has_bit), n_samples=int(n_s),
        record_t0_s=float(t0), record_t1_s=float(t1),
        columns=[c[0] + " [" + c[1] + "]" for c in allc],
    )
    return {
        "generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": path, "args": args,
        "fn_true": float(fn), "fn_given": fn_given, "params": _jsonable(params),
    }
