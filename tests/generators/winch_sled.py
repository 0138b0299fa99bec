"""Winch-sled stick-slip records: a polymer sled pulled over a steel flat through a measuring spring.

An independent generator for evaluating `lieng diagnose` (written without reading the diagnosis code).

Rig. A polymer (UHMWPE / PA66) sled of mass m (0.4-2.5 kg) on a ground steel flat, pulled by a
winch: the winch's rope runs onto a drum and pulls a light carriage, and the calibrated measuring
spring k (fn = sqrt(k/m)/2 pi = 6-18 Hz) links the carriage to the sled. Normal load N0 = 1-1.8 x the
sled's weight (a pneumatic loader). Viscous damping 0.5-2 % of critical (the guide's oil film). The
spring never unloads (the rope stays taut: the smallest extension in seeds 0-23 is 0.01 mm, after a
long hold; 0.17 mm in seeds 0-7).

Friction law (single-valued in the sliding speed w): a thermally softening polymer. The polymer's
shear part softens exponentially with the flash temperature, mu_th = mu_p exp(-gamma dT), and the
flash temperature is driven by all the frictional heat, gamma dT = (mu_c + mu_th) A(w) with
A(w) = (w/v_T) / (1 + sqrt(w/v_P)) (Archard/Jaeger: linear in w at a low Peclet number, as sqrt(w) at
a high one; multi-asperity contact, so independent of the load). The self-consistent closure is a
Lambert W:  mu(w) = mu_c + W(A mu_p exp(-A mu_c)) / A,  mu_c 0.10-0.20, mu_p 0.10-0.22,
v_T 0.12-0.4 and v_P 0.3-2 x the slip-speed scale, a static level mu_s0 = (mu_c + mu_p)(1 + 6..14 %) at
w = 0; plus the viscous term. The flash temperature is taken as instantaneous (no state).

Stick handling: Filippov's convex method with Utkin's equivalent control. On the switching surface
w = 0 the sliding mode is the stick: the sled stays put and the friction is the equivalent control,
the spring force; it is admissible while |k e| <= mu_s(t_stick) N (the static level is the set-valued
extension of the law at 0). The breakaway (the equivalent control leaving the set) is found by a
vectorised scan of the exact stick trajectory (the drive is analytic) and the ITP method (Oliveira &
Takahashi 2020); the arrest (w crossing 0) by ITP on the step's cubic Hermite interpolant, the step
then retaken exactly to it and w set to 0. No band, no regularisation, no creep in stick.

Integrator: my own variable-step Bogacki-Shampine 3(2) (FSAL, scaled absolute tolerance 1e-7 of the
drop and of the slip-speed scale, step <= Tn/40, <= 1/12 of a shaker period), cubic Hermite dense
output. Tolerance 1e-7 vs 1e-9: drop and stick-slip rate agree to 1e-6 (triggering: 0.4 % on the
median drop, the breakaways being sensitive to the shaker's phase).

Departures (sizes measured on the ground truth, seeds 0-23; [seeds 0-7] in brackets):
- load_variation: a roller on the rope's carriage bears on a ramp on the sled's top through a load
  spring, so the load follows the spring's extension: N = N0 (1 + c (e - e_m)); rising ramp, or a
  falling one (c < 0) on seeds 3 mod 8; c tuned on pilot runs (bracket + ITP). Load p-p 11.3-30.4 %
  of N0 [11.3-26.1 %]; the normal channel is always recorded. F against v then reads -30..+71 % of the
  drop (F/N against v: 0).
- twin_branch: tribo-electric adhesion (cf. Burgo et al., Sci. Rep. 3, 2384, 2013): the polymer
  charges with the rubbing distance, dq/dt = |w|/L_q (1 - q) - q/tau_q (L_q 0.4-0.7 of the slip
  length, tau_q 0.4-0.8 Tn: the charge leaks to the steel within the stick), and the attraction adds
  N_e q^2 to the contact load (N_e 0.09-0.31 N0, secant-tuned on pilot runs). Friction is higher on
  the decelerating half: +13.1..+19.4 % [+13.1..+18.4 %] of the drop. The load cell under the
  flat does not see the attraction (it is internal to sled and flat).
- static_ageing: thermally activated junction growth with a log-uniform spectrum of times between
  tau1 (0.3-1 x the short stick) and tau2 (3-15 x the long one):
  mu_s = mu_s0 + dmu (1 - (E1(t/tau2) - E1(t/tau1)) / ln(tau2/tau1)), linear at short times,
  logarithmic between the cut-offs, saturating beyond. Winch speed steps 4-8x (even seeds) or holds of
  4-14 sticks (odd seeds); the drive is recorded. Peak growth (mean peak of the long sticks minus the
  short ones) +7.7..+14.9 % [+7.7..+14.2 %] of the drop over stick times 5.9-12.5 x apart
  (median stick of the long group over the short one).
- triggering: a directional vibrator (two counter-rotating unbalances) on the sled, a vertical force
  only: N = N0 (1 + eps sin(2 pi f_t t + phi)), eps 3.7-7.5 %, f_t 2.7-7.5 fn, redrawn until the
  record's f_t/f_ss is >= 0.15 from an integer (10.4-45.5, >= 0.21 from an integer).
- drive_modulation: the winch's speed loop hunts: v0(t) = v0n (1 + a sin(2 pi fm t + phi)), a
  0.23-0.43, fm/f_ss 0.14-0.41 (measured on the record); only v0n is given (`--v0`).

`none` (measured on the ground truth, seeds 0-23 [0-7]): the law has no memory, so the friction
against the true sliding speed is single-valued: twin (decelerating minus accelerating at equal
speed, 10-90 % of each slip's peak speed, median over slips, over the slip's force drop) |twin| <
2e-6. A 1-DoF reading of the noise-free recorded samples (x = F/k or the extension, the sled at
x_d - x, central first and second differences, friction = k x - m x'') sees -1.1..+0.2 %
[-0.5..-0.2 %] of the drop at 40-100 samples per period, -2.9..-2.3 % [-2.3 %] at 20-40 (the
static-kinetic kink smeared by the differencing and the load cell's lag), -9.8..-7.8 % [-7.8 %] on
the coarse records (10-15). No ageing in the law: on the stepped-drive records (seeds 2, 5 mod 8;
winch speed 3-6x apart, sticks 3.1-4.8 x apart) the peak changes -0.31..-0.09 % [-0.18, -0.15 %] of
the drop with the stick time (the slightly larger overshoot past the breakaway at the faster speed).
Peak scatter (sd) <= 0.18 % of the drop. Normal load exactly constant (0.1 % of N0 white noise on
the normal channel when recorded); drive exactly constant or stepped.

Sensor chain. Force records: the spring's strain-gauge load cell, second order (15-40 fn, damping
0.55-0.75), in N, mN or uN with `--stiffness`; a normal load cell under the flat (same kind); the
drum encoder's position (2^17 counts per turn, mm/um) or the winch's tacho speed (first-order lag
0.1-0.3 Tn, mm/s). Displacement records: an LVDT across the spring (first order, 12-30 fn) in mm, a
normal-load proving-ring gauge y = y0 + g N in mm, the tacho speed. Every analog channel goes through
a cascade of zero-phase half-band FIR decimators (by 2 each, from a grid of >= 20 points per cell
period) to the record rate; white noise 0.1-0.3 % of the drop after it, plus the winch gearbox's
tooth-mesh whine picked up by the cell (0.05-0.15 % of the drop, its frequency follows the drum
speed, silent in holds). 20-100 samples per natural period (coarse: 10-15), 17-38 slips a record.

Formats (style = (seed + case index) mod 6): 0 comma CSV with a UTF-8 BOM, CRLF and plain metadata
lines before the header (force, N); 1 semicolon, names row then a `[unit]` row, a trailing `;` (mN,
um); 2 TAB, time in ms, scientific notation (displacement); 3 whitespace, `#` metadata, `name[unit]`
(mN, mm); 4 comma CSV, CRLF, metadata lines, time in ms, a trailing comma (displacement); 5 TAB with
a BOM, CRLF, names and `[unit]` rows, scientific notation (uN, um). `--fn` is left out on one seed in
8 per case (none 3, load 4, twin 5, ageing 1, modulation 7; never for triggering or `fn_off`).

Nuisances: hum 50/60 Hz (+3rd, 5th below 0.4 fs) 1.6-4.5 % of the drop, injected before the
anti-alias filter; drift (a power-law-in-time zero drift plus a bow) 2.5-6 % of the drop over
the record; spikes on 0.08-0.4 % of the samples (0.3-1.2 drops, isolated); quantisation an ADC step of
0.2-1 % (measured 0.26-0.99 %); coarse 10-15 samples per period; fn_off `--fn` exactly 5 % off.
"""

import math
import os
import zlib
from bisect import bisect_right

import numpy as np
from scipy import signal, special

NAME = "winch_sled"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

_G = 9.81
_TWO_PI = 2.0 * math.pi


# ----------------------------------------------------------------------------------------------
# Friction law: thermally softening polymer, self-consistent flash temperature (Lambert W)
# ----------------------------------------------------------------------------------------------
def _lambertw(z):
    """Principal branch of Lambert's W for z >= 0 (Halley's iteration)."""
    if z <= 1e-300:
        return 0.0
    if z < 3.0:
        w = math.log1p(z) * (1.0 - 0.15 * math.log1p(z))
    else:
        lz = math.log(z)
        w = lz - math.log(lz)
    for _ in range(30):
        ew = math.exp(w)
        f = w * ew - z
        wn = w - f / (ew * (w + 1.0) - (w + 2.0) * f / (2.0 * w + 2.0))
        if abs(wn - w) <= 1e-15 * (1.0 + abs(wn)):
            return wn
        w = wn
    return w


def _lambertw_arr(z):
    z = np.asarray(z, dtype=float)
    w = np.where(z < 3.0, np.log1p(z) * (1.0 - 0.15 * np.log1p(z)),
                 np.log(np.maximum(z, 3.0)) - np.log(np.log(np.maximum(z, 3.0))))
    for _ in range(12):
        ew = np.exp(w)
        f = w * ew - z
        w = w - f / (ew * (w + 1.0) - (w + 2.0) * f / (2.0 * w + 2.0))
    return np.where(z <= 1e-300, 0.0, w)


class _Law:
    """mu(w) = mu_c + mu_th(w) for a sliding speed w >= 0.

    The polymer's shear component softens exponentially with the flash temperature, mu_th = mu_p
    exp(-gamma dT), and the flash temperature is driven by all the heat, dT proportional to
    (mu_c + mu_th) w / (1 + sqrt(w / v_P)) (Archard/Jaeger: linear in the speed at a low Peclet
    number, as sqrt(w) at a high one). With A(w) = (w / v_T) / (1 + sqrt(w / v_P)) this closes as
    mu_th = W(A mu_p exp(-A mu_c)) / A. Multi-asperity contact: the flash temperature does not depend
    on the load. Static level mu_s0 = (mu_c + mu_p)(1 + delta_s) at w = 0.
    """

    def __init__(self, mu_c, mu_p, v_T, v_P, delta_s):
        self.mu_c, self.mu_p, self.v_T, self.v_P = mu_c, mu_p, v_T, v_P
        self.mu0 = mu_c + mu_p
        self.mu_s0 = self.mu0 * (1.0 + delta_s)

    def mu(self, w):
        if w <= 0.0:
            return self.mu0
        a = (w / self.v_T) / (1.0 + math.sqrt(w / self.v_P))
        if a < 1e-10:
            return self.mu_c + self.mu_p * math.exp(-a * self.mu0)
        return self.mu_c + _lambertw(a * self.mu_p * math.exp(-a * self.mu_c)) / a

    def mu_arr(self, w):
        w = np.maximum(np.asarray(w, dtype=float), 0.0)
        a = (w / self.v_T) / (1.0 + np.sqrt(w / self.v_P))
        a_safe = np.maximum(a, 1e-10)
        th = _lambertw_arr(a_safe * self.mu_p * np.exp(-a_safe * self.mu_c)) / a_safe
        th = np.where(a < 1e-10, self.mu_p * np.exp(-a * self.mu0), th)
        return self.mu_c + th


def _heal(t, tau1, tau2):
    """Healed fraction after a contact time t for activated processes whose times are spread
    log-uniformly over [tau1, tau2]: 1 - (E1(t/tau2) - E1(t/tau1)) / ln(tau2/tau1). Linear for
    t << tau1, logarithmic in t between the cut-offs, saturating past tau2."""
    t = np.maximum(np.asarray(t, dtype=float), 0.0)
    tt = np.maximum(t, 1e-300)
    h = 1.0 - (special.exp1(tt / tau2) - special.exp1(tt / tau1)) / math.log(tau2 / tau1)
    return np.where(t <= 0.0, 0.0, h)


# ----------------------------------------------------------------------------------------------
# Winch drive: piecewise-linear speed programme (steps with ramps, holds) or a slow modulation
# ----------------------------------------------------------------------------------------------
class _Drive:
    def __init__(self, tk, vk, mod=None):
        self.tk = [float(t) for t in tk]
        self.vk = [float(v) for v in vk]
        pk = [0.0]
        for j in range(len(self.tk) - 1):
            pk.append(pk[-1] + 0.5 * (self.vk[j] + self.vk[j + 1]) * (self.tk[j + 1] - self.tk[j]))
        self.pk = pk
        self.mod = mod  # (v0n, a, wm, phi)
        self._tk, self._vk, self._pk = np.array(self.tk), np.array(self.vk), np.array(pk)

    def pos(self, t):
        if self.mod is not None:
            v0n, a, wm, ph = self.mod
            return v0n * (t + a / wm * (math.cos(ph) - math.cos(wm * t + ph)))
        j = bisect_right(self.tk, t) - 1
        if j < 0:
            return self.vk[0] * (t - self.tk[0])
        if j >= len(self.tk) - 1:
            return self.pk[-1] + self.vk[-1] * (t - self.tk[-1])
        tau = t - self.tk[j]
        dv = (self.vk[j + 1] - self.vk[j]) / (self.tk[j + 1] - self.tk[j])
        return self.pk[j] + self.vk[j] * tau + 0.5 * dv * tau * tau

    def pos_arr(self, t):
        t = np.asarray(t, dtype=float)
        if self.mod is not None:
            v0n, a, wm, ph = self.mod
            return v0n * (t + a / wm * (np.cos(ph) - np.cos(wm * t + ph)))
        tk, vk, pk = self._tk, self._vk, self._pk
        if len(tk) == 1:
            return vk[0] * (t - tk[0])
        j = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, len(tk) - 2)
        tau = t - tk[j]
        dv = (vk[j + 1] - vk[j]) / (tk[j + 1] - tk[j])
        inside = t < tk[-1]
        p_in = pk[j] + vk[j] * tau + 0.5 * dv * tau * tau
        p_out = pk[-1] + vk[-1] * (t - tk[-1])
        return np.where(inside, p_in, p_out)

    def vel_arr(self, t):
        t = np.asarray(t, dtype=float)
        if self.mod is not None:
            v0n, a, wm, ph = self.mod
            return v0n * (1.0 + a * np.sin(wm * t + ph))
        return np.interp(t, self._tk, self._vk)


# ----------------------------------------------------------------------------------------------
# Root finding: the ITP method (Oliveira & Takahashi 2020)
# ----------------------------------------------------------------------------------------------
def _itp(f, a, b, fa, fb, eps):
    """Root of f in [a, b] with f(a) f(b) < 0. Returns (lo, hi) bracketing the root, hi on fb's side."""
    sg = 1.0 if fa < 0.0 else -1.0
    ya, yb = sg * fa, sg * fb
    n_max = max(0, math.ceil(math.log2(max((b - a) / (2.0 * eps), 1.0)))) + 1
    k1 = 0.2 / (b - a)
    j = 0
    while b - a > 2.0 * eps and j < 200:
        xh = 0.5 * (a + b)
        r = eps * 2.0 ** (n_max - j) - 0.5 * (b - a)
        delta = k1 * (b - a) ** 2
        xf = (yb * a - ya * b) / (yb - ya)
        s = 1.0 if xh - xf >= 0.0 else -1.0
        xt = xf + s * delta if delta <= abs(xh - xf) else xh
        x = xt if abs(xt - xh) <= r else xh - s * r
        y = sg * f(x)
        if y > 0.0:
            b, yb = x, y
        elif y < 0.0:
            a, ya = x, y
        else:
            return x, x
        j += 1
    return a, b


# ----------------------------------------------------------------------------------------------
# The rig: sled (mass m) on the flat, measuring spring k to the winch rope's carriage
# ----------------------------------------------------------------------------------------------
class _Rig:
    def __init__(self, m, k, c, N0, law, drive, *, age_dmu=0.0, age_t1=1.0, age_t2=10.0, load_c=0.0,
                 load_em=0.0,
                 trig_eps=0.0, trig_f=0.0, trig_phi=0.0, Ne=0.0, Lq=1.0, tauq=1.0):
        self.m, self.k, self.c, self.N0, self.law, self.drive = m, k, c, N0, law, drive
        self.age_dmu, self.age_t1, self.age_t2 = age_dmu, age_t1, age_t2
        self.load_c, self.load_em = load_c, load_em
        self.trig_eps, self.trig_w, self.trig_phi = trig_eps, _TWO_PI * trig_f, trig_phi
        self.Ne, self.Lq, self.tauq = Ne, Lq, tauq
        self.wn = math.sqrt(k / m)
        self.Tn = _TWO_PI / self.wn
        self.h_scan = self.Tn / 16.0
        self.h_max = self.Tn / 40.0
        if trig_eps > 0.0:
            Tt = 1.0 / trig_f
            self.h_scan = min(self.h_scan, Tt / 12.0)
            self.h_max = min(self.h_max, Tt / 12.0)

    # normal load from outside the contact (what a normal load cell under the flat reads)
    def n_ext(self, t, e):
        n = self.N0
        if self.load_c != 0.0:
            n = n * (1.0 + self.load_c * (e - self.load_em))
        if self.trig_eps != 0.0:
            n = n * (1.0 + self.trig_eps * math.sin(self.trig_w * t + self.trig_phi))
        return n

    def n_ext_arr(self, t, e):
        n = np.full(np.shape(t), self.N0, dtype=float)
        if self.load_c != 0.0:
            n = n * (1.0 + self.load_c * (e - self.load_em))
        if self.trig_eps != 0.0:
            n = n * (1.0 + self.trig_eps * np.sin(self.trig_w * t + self.trig_phi))
        return n

    def mu_s(self, age):
        """Static level after a stick of `age` seconds (activated junction growth)."""
        if self.age_dmu == 0.0:
            return self.law.mu_s0 + 0.0 * age
        return self.law.mu_s0 + self.age_dmu * _heal(age, self.age_t1, self.age_t2)

    # ------------------------------------------------------------------------------------------
    def _rhs(self, t, xs0, s, u, v, q):
        e = self.drive.pos(t) - xs0 - u
        neff = self.n_ext(t, e) + self.Ne * q * q
        w = s * v
        fr = s * self.law.mu(w if w > 0.0 else 0.0) * neff + self.c * v
        a = (self.k * e - fr) / self.m
        if self.Ne != 0.0:
            dq = abs(v) / self.Lq * (1.0 - q) - q / self.tauq
        else:
            dq = 0.0
        return v, a, dq

    def _g_arr(self, ts, xs, t_arr, q_arr):
        e = self.drive.pos_arr(ts) - xs
        q = q_arr * np.exp(-(ts - t_arr) / self.tauq)
        fs = self.mu_s(ts - t_arr) * (self.n_ext_arr(ts, e) + self.Ne * q * q)
        return np.abs(self.k * e) - fs

    def _find_break(self, t0, xs, t_arr, q_arr, t_end):
        def g(t):
            return float(self._g_arr(np.array([t]), xs, t_arr, q_arr)[0])

        ta = t0
        while ta < t_end:
            ts = ta + self.h_scan * np.arange(1, 513)
            ts = ts[ts < t_end]
            if ts.size == 0:
                ts = np.array([t_end])
            gs = self._g_arr(ts, xs, t_arr, q_arr)
            pos = np.nonzero(gs > 0.0)[0]
            if pos.size:
                i = pos[0]
                lo = ts[i - 1] if i > 0 else ta
                glo = g(lo)
                if glo > 0.0:  # already above at lo (only at a restart from an arrest that fails)
                    return lo
                _, hi = _itp(g, lo, ts[i], glo, gs[i], 1e-11 * self.Tn)
                return hi
            ta = ts[-1]
            if ta >= t_end:
                break
        return None

    def _bs23(self, t, xs0, s, y, f, h):
        """One Bogacki-Shampine 3(2) step. y, f: tuples (u, v, q)."""
        u, v, q = y
        k2 = self._rhs(t + 0.5 * h, xs0, s, u + 0.5 * h * f[0], v + 0.5 * h * f[1], q + 0.5 * h * f[2])
        k3 = self._rhs(t + 0.75 * h, xs0, s, u + 0.75 * h * k2[0], v + 0.75 * h * k2[1],
                       q + 0.75 * h * k2[2])
        y1 = (u + h * (2.0 / 9.0 * f[0] + 1.0 / 3.0 * k2[0] + 4.0 / 9.0 * k3[0]),
              v + h * (2.0 / 9.0 * f[1] + 1.0 / 3.0 * k2[1] + 4.0 / 9.0 * k3[1]),
              q + h * (2.0 / 9.0 * f[2] + 1.0 / 3.0 * k2[2] + 4.0 / 9.0 * k3[2]))
        k4 = self._rhs(t + h, xs0, s, *y1)
        err = tuple(h * (-5.0 / 72.0 * f[i] + 1.0 / 12.0 * k2[i] + 1.0 / 9.0 * k3[i] - 0.125 * k4[i])
                    for i in range(3))
        return y1, k4, err

    def _slip(self, t, xs0, q0, s, t_end, segs, sc):
        y = (0.0, 0.0, q0)
        f = self._rhs(t, xs0, s, *y)
        h = self.Tn / 3000.0
        nstep = 0
        while True:
            h = min(h, self.h_max, t_end - t)
            y1, f1, err = self._bs23(t, xs0, s, y, f, h)
            en = max(abs(err[0]) / sc[0], abs(err[1]) / sc[1], abs(err[2]) / sc[2])
            if en > 1.0:
                h *= max(0.2, 0.9 * en ** (-1.0 / 3.0))
                continue
            nstep += 1
            if s * y[1] > 0.0 and s * y1[1] <= 0.0:
                v0_, a0_, v1_, a1_ = y[1], f[1], y1[1], f1[1]

                def vh(th, v0_=v0_, a0_=a0_, v1_=v1_, a1_=a1_, h=h):
                    h00 = (1 + 2 * th) * (1 - th) ** 2
                    h10 = th * (1 - th) ** 2
                    h01 = th * th * (3 - 2 * th)
                    h11 = th * th * (th - 1)
                    return s * (h00 * v0_ + h10 * h * a0_ + h01 * v1_ + h11 * h * a1_)

                lo, hi = _itp(vh, 0.0, 1.0, s * v0_, s * v1_, 1e-10)
                th = 0.5 * (lo + hi)
                hs = th * h
                ys, _, _ = self._bs23(t, xs0, s, y, f, hs)
                ys = (ys[0], 0.0, ys[2])
                fs_ = self._rhs(t + hs, xs0, s, *ys)
                segs.append((t, t + hs, xs0 + y[0], xs0 + ys[0], y[1], 0.0, f[1], fs_[1], y[2], ys[2],
                             f[2], fs_[2], s))
                return t + hs, xs0 + ys[0], ys[2], True, nstep
            segs.append((t, t + h, xs0 + y[0], xs0 + y1[0], y[1], y1[1], f[1], f1[1], y[2], y1[2],
                         f[2], f1[2], s))
            t, y, f = t + h, y1, f1
            if t >= t_end - 1e-12:
                return t, xs0 + y[0], y[2], False, nstep
            h *= min(4.0, 0.9 * en ** (-1.0 / 3.0)) if en > 0.0 else 4.0

    def run(self, t_end, e0, age0=0.0, max_slips=None, tol=1e-7, scale=None):
        """Simulate from a stuck sled with extension e0. Returns (segments array, slips list)."""
        de, vs = scale
        sc = (tol * de, tol * vs, tol)
        segs = []
        slips = []
        t = 0.0
        xs = self.drive.pos(0.0) - e0
        t_arr, q_arr = -age0, 0.0
        nsteps = 0
        while t < t_end:
            tb = self._find_break(t, xs, t_arr, q_arr, t_end)
            if tb is None:
                segs.append((t, t_end, xs, xs, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0))
                break
            if tb > t:
                segs.append((t, tb, xs, xs, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0))
            q = q_arr * math.exp(-(tb - t_arr) / self.tauq)
            e = self.drive.pos(tb) - xs
            s = 1 if e > 0 else -1
            slip = {"tb": tb, "s": s, "t_prev": t_arr, "Fb": self.k * e}
            while True:
                t, xs, q, arrested, n = self._slip(tb, xs, q, s, t_end, segs, sc)
                nsteps += n
                if not arrested:
                    break
                e = self.drive.pos(t) - xs
                if abs(self.k * e) <= self.law.mu_s0 * (self.n_ext(t, e) + self.Ne * q * q):
                    break
                tb, s = t, (1 if e > 0 else -1)  # slides on (never seen in practice)
                slip["resumed"] = True
            if not arrested:
                break
            slip["ta"] = t
            slips.append(slip)
            t_arr, q_arr = t, q
            if max_slips is not None and len(slips) >= max_slips:
                break
        arr = np.array(segs, dtype=float)
        return arr, slips, nsteps


def _dense(segs, t):
    """Sled position, speed, charge state at times t from the step data (cubic Hermite)."""
    t = np.asarray(t, dtype=float)
    i = np.clip(np.searchsorted(segs[:, 0], t, side="right") - 1, 0, len(segs) - 1)
    S = segs[i]
    h = S[:, 1] - S[:, 0]
    hs = np.where(h > 0, h, 1.0)
    th = np.clip((t - S[:, 0]) / hs, 0.0, 1.0)
    h00 = (1 + 2 * th) * (1 - th) ** 2
    h10 = th * (1 - th) ** 2
    h01 = th * th * (3 - 2 * th)
    h11 = th * th * (th - 1)
    x = h00 * S[:, 2] + h10 * h * S[:, 4] + h01 * S[:, 3] + h11 * h * S[:, 5]
    v = h00 * S[:, 4] + h10 * h * S[:, 6] + h01 * S[:, 5] + h11 * h * S[:, 7]
    q = h00 * S[:, 8] + h10 * h * S[:, 10] + h01 * S[:, 9] + h11 * h * S[:, 11]
    return x, v, q, S[:, 12]


# ----------------------------------------------------------------------------------------------
# Ground-truth measurements on the simulated motion
# ----------------------------------------------------------------------------------------------
def _slip_table(rig, segs, slips, t0, t1, npts=801):
    rows = []
    for sl in slips:
        if sl["tb"] < t0 or sl["ta"] > t1:
            continue
        tt = np.linspace(sl["tb"], sl["ta"], npts)
        xs, v, q, _ = _dense(segs, tt)
        e = rig.drive.pos_arr(tt) - xs
        F = rig.k * e
        neff = rig.n_ext_arr(tt, e) + rig.Ne * q * q
        s = sl["s"]
        w = s * v
        fr = s * rig.law.mu_arr(w) * neff + rig.c * v
        peak, fmin = F.max(), F.min()
        drop = peak - fmin
        ip = int(np.argmax(w))
        wp = w[ip]
        lev = wp * np.linspace(0.1, 0.9, 33)
        wa, fa = w[:ip + 1], fr[:ip + 1]
        wd, fd = w[ip:][::-1], fr[ip:][::-1]
        oa, od = np.argsort(wa, kind="stable"), np.argsort(wd, kind="stable")
        twin = float(np.mean(np.interp(lev, wd[od], s * fd[od]) - np.interp(lev, wa[oa], s * fa[oa])))
        mu_ = (fr - rig.c * v) / rig.n_ext_arr(tt, e)  # F/N with the recordable (external) load
        ma, md = mu_[:ip + 1], mu_[ip:][::-1]
        twin_mu = float(np.mean(np.interp(lev, wd[od], s * md[od]) - np.interp(lev, wa[oa], s * ma[oa])))
        rows.append({"tb": sl["tb"], "ta": sl["ta"], "stick": sl["tb"] - sl["t_prev"], "peak": float(peak),
                     "fmin": float(fmin), "drop": float(drop), "twin": twin / drop,
                     "twin_mu": twin_mu * rig.N0 / drop, "wpeak": float(wp),
                     "resumed": bool(sl.get("resumed", False))})
    return rows


def _measure(rig, segs, slips, t0, t1, case, extra):
    rows = _slip_table(rig, segs, slips, t0, t1)
    n = len(rows)
    out = {"n_slips": n}
    if n < 3:
        return out, rows
    drops = np.array([r["drop"] for r in rows])
    peaks = np.array([r["peak"] for r in rows])
    sticks = np.array([r["stick"] for r in rows])
    tbs = np.array([r["tb"] for r in rows])
    f_ss = (n - 1) / (tbs[-1] - tbs[0])
    drop = float(np.median(drops))
    out.update({"f_ss_hz": float(f_ss), "fn_over_fss": float(rig.wn / _TWO_PI / f_ss), "drop_N": drop,
                "twin_frac": float(np.median([r["twin"] for r in rows])),
                "twin_mu_frac": float(np.median([r["twin_mu"] for r in rows])),
                "peak_sd_frac": float(np.std(peaks) / drop),
                "slip_speed_over_v0": float(np.median([r["wpeak"] for r in rows]) / extra["v0_ref"]),
                "resumed_slips": int(sum(r["resumed"] for r in rows))})
    # ageing: peaks of the long sticks minus peaks of the short ones, over the drop
    lo, hi = sticks.min(), sticks.max()
    out["stick_ratio"] = float(hi / lo)
    if hi / lo > 1.5:
        cut = math.sqrt(lo * hi)
        longp, shortp = peaks[sticks > cut], peaks[sticks <= cut]
        out["peak_growth_frac"] = float((longp.mean() - shortp.mean()) / drop)
        out["stick_ratio_groups"] = float(np.median(sticks[sticks > cut])
                                          / np.median(sticks[sticks <= cut]))
        out["peak_vs_ln_stick_slope_frac"] = float(np.polyfit(np.log(sticks), peaks, 1)[0] / drop)
    tt = np.linspace(t0, t1, 20001)
    xs = _dense(segs, tt)[0]
    e = rig.drive.pos_arr(tt) - xs
    N = rig.n_ext_arr(tt, e)
    out["load_pp_frac"] = float((N.max() - N.min()) / rig.N0)
    out["min_extension_mm"] = float(e.min() * 1e3)
    if rig.trig_eps:
        ft = rig.trig_w / _TWO_PI
        r = ft / f_ss
        out.update({"trig_ft_over_fn": float(ft / (rig.wn / _TWO_PI)), "trig_ft_over_fss": float(r),
                    "trig_int_dist": float(abs(r - round(r)))})
    if rig.drive.mod is not None:
        out["mod_fm_over_fss"] = float(rig.drive.mod[2] / _TWO_PI / f_ss)
        out["mod_a"] = float(rig.drive.mod[1])
    return out, rows


# ----------------------------------------------------------------------------------------------
# Parameter drawing and case set-up
# ----------------------------------------------------------------------------------------------
def _rng(case, seed, nuisance, salt=""):
    key = zlib.crc32(f"{NAME}|{case}|{seed}|{nuisance}|{salt}".encode())
    return np.random.default_rng([key, int(seed) & 0xFFFFFFFF, 271828])


def _u(rng, a, b):
    return float(rng.uniform(a, b))


_KEEP = None

_FN_OMIT = {"none": 3, "load_variation": 4, "twin_branch": 5, "static_ageing": 1, "drive_modulation": 7}


def _build(case, seed, nuisance):
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    rng = _rng(case, seed, nuisance)
    P = {}
    m = _u(rng, 0.4, 2.5)
    fn = _u(rng, 6.0, 18.0)
    k = m * (_TWO_PI * fn) ** 2
    N0 = m * _G * _u(rng, 1.0, 1.8)
    mu_c, mu_p = _u(rng, 0.10, 0.20), _u(rng, 0.10, 0.22)
    delta_s = _u(rng, 0.06, 0.14)
    zeta = _u(rng, 0.005, 0.02)
    wn = _TWO_PI * fn
    Tn = 1.0 / fn
    c = 2.0 * zeta * m * wn
    half = ((mu_c + mu_p) * (1 + delta_s) - mu_c - 0.5 * mu_p) * N0
    v_sl = half / k * wn
    v_T = _u(rng, 0.12, 0.4) * v_sl
    v_P = _u(rng, 0.3, 2.0) * v_sl
    law = _Law(mu_c, mu_p, v_T, v_P, delta_s)
    P.update(mass_kg=m, fn_hz=fn, k_N_per_m=k, N0_N=N0, mu_c=mu_c, mu_p=mu_p, delta_s=delta_s,
             mu_s0=law.mu_s0, zeta=zeta, c_N_s_per_m=c, v_T_m_s=v_T, v_P_m_s=v_P)
    scale = (2 * half / k, v_sl)

    # pilot runs: constant drive, four slips; the load coupling and the charge are tuned on them
    v_pilot = 2 * half / k / (6 * Tn)
    e_s = law.mu_s0 * N0 / k

    def pilot(rkw):
        r = _Rig(m, k, c, N0, law, _Drive([0.0], [v_pilot]), **rkw)
        sg, sl, _ = r.run(80 * Tn, 0.6 * e_s, max_slips=4, scale=scale)
        rw = _slip_table(r, sg, sl, 0.0, 1e9)
        tt = np.linspace(sl[-2]["ta"], sl[-1]["ta"], 4001)
        xs_, _, _, _ = _dense(sg, tt)
        e_ = r.drive.pos_arr(tt) - xs_
        nn_ = r.n_ext_arr(tt, e_)
        return rw[-1], (nn_.max() - nn_.min()) / N0, 0.5 * (e_.max() + e_.min())

    dep = {}
    tries = []
    target = None
    row, _, emid = pilot(dep)
    if case == "twin_branch":
        target = _u(rng, 0.13, 0.21)
        dep = dict(Lq=_u(rng, 0.3, 0.6) * row["drop"] / k, tauq=_u(rng, 0.4, 0.8) * Tn, Ne=0.0)
        x0, f0 = 0.0, 0.0
        x1 = target * row["drop"] / (law.mu0 * 0.6)
        for _ in range(6):
            dep["Ne"] = x1
            row, _, emid = pilot(dep)
            f1 = row["twin"]
            tries.append((x1 / N0, f1))
            if abs(f1 - target) < 0.004:
                break
            x2 = x1 + (target - f1) * (x1 - x0) / (f1 - f0) if f1 != f0 else 1.5 * x1
            x0, f0, x1 = x1, f1, min(max(x2, 0.3 * x1), 3.0 * x1)
        P["twin_tuning"] = tries
    elif case == "load_variation":
        neg = seed % 8 == 3
        target = _u(rng, 0.11, 0.15) if neg else _u(rng, 0.13, 0.32)
        sgn = -1.0 if neg else 1.0
        c1 = target / (row["drop"] / k)
        cache = {}

        def pp_minus(cc):
            if cc not in cache:
                cache[cc] = pilot(dict(load_c=sgn * cc, load_em=emid))
                tries.append((sgn * cc, cache[cc][1]))
            return cache[cc][1] - target

        lo, hi = None, None
        cc = c1
        for _ in range(12):  # bracket the coupling (p-p grows with it, faster than linearly)
            f_ = pp_minus(cc)
            if f_ > 0:
                hi = cc
                if lo is not None:
                    break
                cc *= 0.5
            else:
                lo = cc
                if hi is not None:
                    break
                cc *= 1.6
        if lo is not None and hi is not None:
            a_, b_ = _itp(pp_minus, lo, hi, pp_minus(lo), pp_minus(hi), 0.002 * c1)
            best = min((a_, b_), key=lambda z: abs(pp_minus(z)))
        else:
            best = min(cache, key=lambda z: abs(cache[z][1] - target))
        dep = dict(load_c=sgn * best, load_em=emid)
        row = cache[best][0]
        P["load_tuning"] = tries
    drop = row["drop"]
    t_sl = row["ta"] - row["tb"]
    de = drop / k
    P.update(pilot_drop_N=drop, pilot_slip_time_over_Tn=t_sl / Tn)

    stepped = (case == "none" and seed % 8 in (2, 5)) or (case == "static_ageing" and seed % 2 == 0)
    holds = case == "static_ageing" and seed % 2 == 1
    t_ramp = _u(rng, 0.3, 0.8) * Tn
    mod = None
    # the drive programme, drawn in units of natural periods per cycle (R)
    if stepped:
        if case == "none":
            R_fast, ratio = _u(rng, 5.0, 7.0), _u(rng, 3.0, 6.0)
        else:
            R_fast, ratio = _u(rng, 3.5, 6.0), _u(rng, 4.0, 8.0)
        nblk = int(rng.integers(4, 6))
        start_hi = bool(rng.integers(0, 2))
        blocks = []
        for b_ in range(nblk):
            hi = (b_ % 2 == 0) == start_hi
            ncy = int(rng.integers(5, 9)) if hi else int(rng.integers(3, 5))
            blocks.append((hi, ncy + (2 if b_ == 0 else 0)))
        R = R_fast
    elif holds:
        R = _u(rng, 4.0, 9.0)
        nh = int(rng.integers(3, 5))
        hold_cycles = [int(rng.integers(4, 7)) + (2 if b_ == 0 else 0) for b_ in range(nh + 1)]
        hold_mult = [_u(rng, 4.0, 14.0) for _ in range(nh)]
    else:
        R = _u(rng, 4.0, 12.0) if case != "drive_modulation" else _u(rng, 5.0, 10.0)
        ncyc = int(rng.integers(18, 35)) if case != "drive_modulation" else int(rng.integers(24, 37))

    def plan(drop_, t_sl_, slow_factor=1.0):
        """Drive for the programme, from a pilot's drop and slip duration."""
        de_ = drop_ / k
        v_ = de_ / (R * Tn - t_sl_)
        tc = lambda v, f=1.0: f * de_ / v + t_sl_  # noqa: E731
        info = {}
        if stepped:
            v_lo = v_ / ratio
            tk, vk, t = [0.0], [v_ if blocks[0][0] else v_lo], 0.0
            lev = []
            for j, (hi, ncy) in enumerate(blocks):
                v = v_ if hi else v_lo
                lev.append((v * 1e3, ncy))
                if j > 0:
                    tk.append(t + t_ramp)
                    vk.append(v)
                t += ncy * tc(v, 1.0 if hi else slow_factor)
                tk.append(t)
                vk.append(v)
            info.update(drive="stepped", v_hi_mm_s=v_ * 1e3, v_lo_mm_s=v_lo * 1e3, step_ratio=ratio,
                        R_fast=R_fast, blocks_mm_s_cycles=lev, ramp_s=t_ramp)
            t_short, t_long = de_ / v_, slow_factor * de_ / v_lo
            return _Drive(tk, vk), t, v_, info, (t_short, t_long)
        if holds:
            tk, vk, t = [0.0], [v_], 0.0
            hl = []
            for j, ncy in enumerate(hold_cycles):
                t += ncy * tc(v_)
                tk.append(t)
                vk.append(v_)
                if j < len(hold_mult):
                    th = hold_mult[j] * de_ / v_
                    hl.append(th)
                    tk += [t + t_ramp, t + t_ramp + th, t + 2 * t_ramp + th]
                    vk += [0.0, 0.0, v_]
                    t += 2 * t_ramp + th
            info.update(drive="holds", v0_mm_s=v_ * 1e3, R=R, holds_s=hl, ramp_s=t_ramp)
            t_short = de_ / v_
            return _Drive(tk, vk), t, v_, info, (t_short, t_short + float(np.median(hl)))
        info.update(drive="constant", v0_mm_s=v_ * 1e3, R=R)
        return _Drive([0.0], [v_]), (ncyc + 2.0) * tc(v_), v_, info, (de_ / v_, de_ / v_)

    drive, t_end, v0_ref, dinfo, (t_short, t_long) = plan(drop, t_sl)
    if case == "drive_modulation":
        a = _u(rng, 0.22, 0.43)
        fm = _u(rng, 0.13, 0.42) / (de / v0_ref + t_sl) * math.sqrt(1 - a * a)
        phi = _u(rng, 0.0, _TWO_PI)
        mod = (v0_ref, a, _TWO_PI * fm, phi)
        drive = _Drive([0.0], [v0_ref], mod=mod)
        t_end = t_end / math.sqrt(1 - a * a)
        dinfo.update(drive="modulated", mod_a=a, mod_fm_hz=fm, mod_phi=phi)
    rig_kw = dict(dep)
    if case == "static_ageing":
        # thermally activated junction growth, a log-uniform spectrum of times tau1..tau2
        target = _u(rng, 0.08, 0.16)
        tau1 = _u(rng, 0.3, 1.0) * t_short
        tau2 = _u(rng, 3.0, 15.0) * t_long
        hfun = lambda t: _heal(np.array([t]), tau1, tau2)[0]  # noqa: E731
        dmu = target * drop / (N0 * (hfun(t_long) - hfun(t_short)))
        rig_kw = dict(age_dmu=dmu, age_t1=tau1, age_t2=tau2)
        # re-plan the drive with the aged drop at the short stick
        r2 = _Rig(m, k, c, N0, law, _Drive([0.0], [v0_ref]), **rig_kw)
        sg2, sl2, _ = r2.run(200 * Tn, 0.6 * e_s, age0=t_short, max_slips=4, scale=scale)
        rw2 = _slip_table(r2, sg2, sl2, 0.0, 1e9)[-1]
        drop, t_sl = rw2["drop"], rw2["ta"] - rw2["tb"]
        de = drop / k
        drive, t_end, v0_ref, dinfo, (t_short, t_long) = plan(drop, t_sl, 1.0 + target)
    elif case == "triggering":
        rig_kw = dict(trig_eps=_u(rng, 0.035, 0.075), trig_f=_u(rng, 2.7, 7.5) * fn,
                      trig_phi=_u(rng, 0.0, _TWO_PI))
    P.update(dinfo)

    e0 = _u(rng, 0.4, 0.8) * e_s
    age0 = 2 * de / v0_ref
    t_sim = t_end + 12 * Tn

    def simulate(rkw, tend, max_slips=None):
        rig = _Rig(m, k, c, N0, law, drive, **rkw)
        sg, sl, ns = rig.run(tend, e0, age0=age0, max_slips=max_slips, scale=scale)
        return rig, sg, sl, ns

    rig, segs, slips, nsteps = simulate(rig_kw, t_sim)
    # locate the record window: start inside the stick after the first arrest
    frac0 = _u(rng, 0.15, 0.85)
    n_max_slips = int(rng.integers(30, 39))

    def window(sl):
        t0 = sl[0]["ta"] + frac0 * (sl[1]["tb"] - sl[0]["ta"])
        inside = [x for x in sl if x["tb"] >= t0 and x["ta"] <= t_end]
        if len(inside) > n_max_slips:  # a record of at most n_max_slips slips
            a_, b_ = inside[n_max_slips - 1], inside[n_max_slips]
            return t0, a_["ta"] + frac0 * (b_["tb"] - a_["ta"])
        return t0, t_end

    t0, t1 = window(slips)
    meas, rows = _measure(rig, segs, slips, t0, t1, case, {"v0_ref": v0_ref})
    if case == "static_ageing":
        for _ in range(3):
            got = meas.get("peak_growth_frac", 0.0)
            if abs(got - target) < 0.015:
                break
            rig_kw["age_dmu"] *= min(3.0, max(0.3, target / max(got, 1e-3)))
            rig, segs, slips, nsteps = simulate(rig_kw, t_sim)
            t0, t1 = window(slips)
            meas, rows = _measure(rig, segs, slips, t0, t1, case, {"v0_ref": v0_ref})
    elif case == "triggering":
        for _ in range(6):
            if meas["trig_int_dist"] >= 0.15:
                break
            rig_kw["trig_f"] = _u(rng, 2.7, 7.5) * fn
            rig, segs, slips, nsteps = simulate(rig_kw, t_sim)
            t0, t1 = window(slips)
            meas, rows = _measure(rig, segs, slips, t0, t1, case, {"v0_ref": v0_ref})
    if target is not None:
        P["target_size"] = target
    P.update({k_: (float(v_) if isinstance(v_, (float, np.floating)) else v_) for k_, v_ in rig_kw.items()})
    if "Ne" in rig_kw:
        P["Ne_over_N0"] = rig_kw["Ne"] / N0
    P.update(e0_m=e0, t_window_s=[t0, t1], integrator_steps=nsteps)
    return {"rng": rng, "P": P, "rig": rig, "segs": segs, "slips": slips, "t0": t0, "t1": t1,
            "meas": meas, "rows": rows, "fn": fn, "Tn": Tn, "k": k, "m": m, "N0": N0,
            "v0_ref": v0_ref, "stepped": stepped, "holds": holds, "mod": mod}


# ----------------------------------------------------------------------------------------------
# Sensor chain: second-order load cell / first-order LVDT, half-band FIR decimation cascade
# ----------------------------------------------------------------------------------------------
def _second_order(x, dt, fc, zeta):
    wc = _TWO_PI * fc
    b, a = signal.bilinear([wc * wc], [1.0, 2 * zeta * wc, wc * wc], fs=1.0 / dt)
    zi = signal.lfilter_zi(b, a) * x[0]
    return signal.lfilter(b, a, x, zi=zi)[0]


def _first_order(x, dt, fc):
    wc = _TWO_PI * fc
    b, a = signal.bilinear([wc], [1.0, wc], fs=1.0 / dt)
    zi = signal.lfilter_zi(b, a) * x[0]
    return signal.lfilter(b, a, x, zi=zi)[0]


_HALFBAND = signal.firwin(39, 0.5, window=("kaiser", 7.5))


def _decimate(x, nstages):
    """Cascade of zero-phase half-band FIR decimators (by 2 each)."""
    h = _HALFBAND
    p = len(h) // 2
    for _ in range(nstages):
        xp = np.concatenate([np.full(p, x[0]), x, np.full(p, x[-1])])
        y = signal.oaconvolve(xp, h, mode="valid")
        x = y[::2]
    return x


def _styles():
    return {
        0: dict(kind="force", delim=",", bom=True, crlf=True, meta="plain", units_row=False,
                time_unit="s", funit="N", posunit="mm", sci=False, trailing=False),
        1: dict(kind="force", delim=";", bom=False, crlf=False, meta=None, units_row=True,
                time_unit="s", funit="mN", posunit="um", sci=False, trailing=True),
        2: dict(kind="disp", delim="\t", bom=False, crlf=False, meta=None, units_row=False,
                time_unit="ms", sci=True, trailing=False),
        3: dict(kind="force", delim=" ", bom=False, crlf=False, meta="hash", units_row=False,
                time_unit="s", funit="mN", posunit="mm", sci=False, trailing=False),
        4: dict(kind="disp", delim=",", bom=False, crlf=True, meta="plain", units_row=False,
                time_unit="ms", sci=False, trailing=True),
        5: dict(kind="force", delim="\t", bom=True, crlf=True, meta=None, units_row=True,
                time_unit="s", funit="uN", posunit="um", sci=True, trailing=False),
    }


_FSCALE = {"N": 1.0, "mN": 1e3, "uN": 1e6}
_PSCALE = {"mm": 1e3, "um": 1e6}


def _fmt_col(vals, sci, resolution):
    if sci:
        return np.char.mod("%.6e", vals)
    dec = int(min(9, max(0, math.ceil(-math.log10(max(resolution, 1e-12))))))
    return np.char.mod(f"%.{dec}f", vals)


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    B = _build(case, seed, nuisance)
    rng, P, rig, segs = B["rng"], B["P"], B["rig"], B["segs"]
    fn, Tn, k, N0 = B["fn"], B["Tn"], B["k"], B["N0"]
    t0, t1 = B["t0"], B["t1"]
    meas = B["meas"]
    drop = meas["drop_N"]
    ci = CASES.index(case)
    style_id = (seed + ci) % 6
    st = _styles()[style_id]
    kind = st["kind"]

    # ---- sampling
    if nuisance == "coarse":
        spp = _u(rng, 10.0, 15.0)
    else:
        spp = _u(rng, 20.0, 100.0)
    f_hum = 50.0 if rng.random() < 0.5 else 60.0
    if nuisance == "hum":
        spp = max(spp, 3.3 * f_hum / fn)
    fs = spp * fn
    f_cell = _u(rng, 15.0, 40.0) * fn
    z_cell = _u(rng, 0.55, 0.75)
    f_lvdt = _u(rng, 12.0, 30.0) * fn
    need = max(8.0, 20.0 * f_cell / fs)
    nst = int(math.ceil(math.log2(need)))
    D = 2 ** nst
    dtf = 1.0 / (fs * D)
    pad = 24 * D * dtf + 8.0 / (z_cell * _TWO_PI * min(f_cell, f_lvdt))
    idx0 = int(math.ceil(pad / dtf / D)) * D
    n_rec = int(math.floor((t1 - t0) * fs))
    tf = t0 + dtf * (np.arange(idx0 + n_rec * D + idx0) - idx0)
    xs = _dense(segs, tf)[0]
    xd = rig.drive.pos_arr(tf)
    e = xd - xs
    F = k * e
    Next = rig.n_ext_arr(tf, e)
    # ---- channel choice
    has_normal = True if case == "load_variation" else bool(rng.random() < 0.4)
    if case in ("static_ageing",) or (case == "none" and B["stepped"]):
        has_drive = True
    elif case == "drive_modulation":
        has_drive = False
    else:
        has_drive = bool(rng.random() < 0.3)
    drive_kind = None
    if has_drive:
        drive_kind = "v0" if (kind == "disp" or rng.random() < 0.4) else "position"

    # ---- analog chain (fine grid), hum before the anti-alias filter
    if kind == "force":
        main = _second_order(F, dtf, f_cell, z_cell)
        main_unit_scale = 1.0
    else:
        main = _first_order(e, dtf, f_lvdt)
        main_unit_scale = 1.0 / k  # N -> m of extension
    nn = None
    g_N = None
    if has_normal:
        if kind == "force":
            nn = _second_order(Next, dtf, _u(rng, 15.0, 40.0) * fn, _u(rng, 0.55, 0.75))
        else:
            g_N = _u(rng, 0.02, 0.08) * 1e-3  # m per N (proving-ring dial)
            y0 = _u(rng, 0.5, 3.0) * 1e-3
            nn = _first_order(y0 + g_N * Next, dtf, _u(rng, 12.0, 30.0) * fn)
            P["normal_gauge_y0_mm"], P["normal_gauge_mm_per_N"] = y0 * 1e3, g_N * 1e3
    nz = {}
    main_nohum = main
    if nuisance == "hum":
        amp = _u(rng, 0.015, 0.045) * drop
        ph = rng.uniform(0, _TWO_PI, 3)
        hum = amp * np.sin(_TWO_PI * f_hum * tf + ph[0])
        for hnum, rel, p_ in ((3, _u(rng, 0.15, 0.4), ph[1]), (5, _u(rng, 0.05, 0.2), ph[2])):
            if hnum * f_hum < 0.4 * fs:
                hum = hum + rel * amp * np.sin(_TWO_PI * hnum * f_hum * tf + p_)
        main = main + hum * main_unit_scale
        if nn is not None:
            nn = nn + _u(rng, 0.3, 1.0) * hum * (1.0 if kind == "force" else (g_N or 0.0))
        nz.update(hum_hz=f_hum, hum_amp_frac=amp / drop)
    # gear-mesh whine of the winch gearbox picked up by the cell (follows the drum speed)
    vdf = rig.drive.vel_arr(tf)
    r_drum = _u(rng, 0.015, 0.04)
    ratio_g, teeth = float(rng.choice([50.0, 80.0, 100.0])), int(rng.integers(14, 25))
    mesh_phase = _TWO_PI * teeth * ratio_g * np.cumsum(vdf) * dtf / (_TWO_PI * r_drum)
    whine = _u(rng, 0.0005, 0.0015) * drop * np.sin(mesh_phase + rng.uniform(0, _TWO_PI))
    main = main + whine * main_unit_scale
    P.update(drum_radius_m=r_drum, gear_ratio=ratio_g, pinion_teeth=teeth)

    # ---- ADC: half-band decimation cascade, zero phase (fine index idx0 + j D is record sample j)
    sel = slice(idx0 // D, idx0 // D + n_rec)
    main_r = _decimate(main, nst)[sel]
    t_rec = tf[idx0::D][:n_rec]
    if nn is not None:
        nn_r = _decimate(nn, nst)[sel]
    n_rec = min(n_rec, len(main_r), len(t_rec))
    main_r, t_rec = main_r[:n_rec], t_rec[:n_rec]
    if nn is not None:
        nn_r = nn_r[:n_rec]
    if isinstance(_KEEP, dict):  # inspection hook for the author's checks (not used otherwise)
        _KEEP.update(t_rec=t_rec.copy(), clean_main=_decimate(main_nohum, nst)[sel][:n_rec], kind=kind,
                     build=B)

    # ---- noise after the ADC front end
    wn_frac = _u(rng, 0.001, 0.003)
    main_r = main_r + wn_frac * drop * main_unit_scale * rng.standard_normal(n_rec)
    P["white_noise_frac"] = wn_frac
    if nn is not None:
        nscale = (1.0 if kind == "force" else g_N)
        nn_r = nn_r + 0.001 * N0 * nscale * rng.standard_normal(n_rec)
    trec_rel = t_rec - t0
    Trec = trec_rel[-1]
    if nuisance == "drift":
        tot = _u(rng, 0.025, 0.06) * drop * (1 if rng.random() < 0.5 else -1)
        p_ = _u(rng, 0.7, 1.6)
        wob = _u(rng, 0.0, 0.3)
        shape = (trec_rel / Trec) ** p_ + wob * np.sin(np.pi * trec_rel / Trec)
        main_r = main_r + tot * shape * main_unit_scale
        nz.update(drift_frac=tot / drop, drift_shape_p=p_)
    if nuisance == "spikes":
        fr_ = _u(rng, 0.0008, 0.004)
        nsp = max(3, int(round(fr_ * n_rec)))
        cand = rng.choice(np.arange(2, n_rec - 2, 3), size=nsp, replace=False)
        amps = rng.uniform(0.3, 1.2, nsp) * drop * rng.choice([-1.0, 1.0], nsp)
        main_r[cand] += amps * main_unit_scale
        nz.update(spike_frac=nsp / n_rec, n_spikes=int(nsp))
    if nuisance == "quantisation":
        qstep = _u(rng, 0.002, 0.01) * drop
        main_r = np.round(main_r / (qstep * main_unit_scale)) * (qstep * main_unit_scale)
        if nn is not None:
            nstep = qstep * (1.0 if kind == "force" else g_N)
            nn_r = np.round(nn_r / nstep) * nstep
        nz.update(adc_step_frac=qstep / drop)
    fn_given = fn
    if nuisance == "fn_off":
        fn_given = fn * (1.05 if rng.random() < 0.5 else 0.95)
    fn_given = float(f"{fn_given:.5g}")  # as written on the command line
    if nuisance == "fn_off":
        nz.update(fn_error=fn_given / fn - 1)
    give_fn = not (case in _FN_OMIT and seed % 8 == _FN_OMIT[case] and nuisance != "fn_off")

    # ---- drive channel
    drv = None
    if has_drive:
        if drive_kind == "position":
            counts = 2 ** 17
            per = _TWO_PI * r_drum / counts
            drv = np.floor(rig.drive.pos_arr(t_rec) / per) * per  # m
            P["encoder_counts_per_rev"] = counts
        else:
            tau_tach = _u(rng, 0.1, 0.3) * Tn
            vv = _first_order(vdf, dtf, 1.0 / (_TWO_PI * tau_tach))
            drv = vv[idx0::D][:n_rec] + 0.002 * B["v0_ref"] * rng.standard_normal(n_rec)
            P["tacho_tau_s"] = tau_tach

    # ---- write the file
    os.makedirs(outdir, exist_ok=True)
    ext = {",": "csv", ";": "csv", "\t": "txt", " ": "dat"}[st["delim"]]
    fname = f"{NAME}_{case}_s{seed}_{nuisance}.{ext}"
    path = os.path.abspath(os.path.join(outdir, fname))
    tu = st["time_unit"]
    tcol = trec_rel * (1e3 if tu == "ms" else 1.0)
    tres = (1e3 if tu == "ms" else 1.0) / fs / 1000.0
    cols = [("time", tu, tcol, tres)]
    if kind == "force":
        fu = st["funit"]
        cols.append(("friction", fu, main_r * _FSCALE[fu], drop * _FSCALE[fu] * 1e-5))
        if nn is not None:
            cols.append(("normal", fu, nn_r * _FSCALE[fu], N0 * _FSCALE[fu] * 1e-6))
        if drv is not None:
            if drive_kind == "position":
                pu = st["posunit"]
                cols.append(("winch position", pu, drv * _PSCALE[pu], per * _PSCALE[pu] / 10))
            else:
                cols.append(("winch speed", "mm/s", drv * 1e3, B["v0_ref"] * 1e3 * 1e-5))
    else:
        cols.append(("spring extension", "mm", main_r * 1e3, drop / k * 1e3 * 1e-5))
        if nn is not None:
            cols.append(("normal load gauge", "mm", nn_r * 1e3, 1e-6))
        if drv is not None:
            cols.append(("winch speed", "mm/s", drv * 1e3, B["v0_ref"] * 1e3 * 1e-5))
    d = st["delim"]
    nl = "\r\n" if st["crlf"] else "\n"
    lines = []
    meta = [f"Winch sled rig WS-{2 + seed % 3} / data logger export",
            f"Specimen: {'PA66' if seed % 2 else 'UHMWPE'} sled on ground steel flat",
            f"Sample rate: {fs:.6g} Hz",
            f"Channels: {len(cols) - 1}"]
    if st["meta"] == "plain":
        lines += meta + [""]
    elif st["meta"] == "hash":
        lines += ["# " + s for s in meta]
    names = [c_[0] for c_ in cols]
    units = [c_[1] for c_ in cols]
    if d == " ":
        names = [n_.replace(" ", "_") for n_ in names]
    if st["units_row"]:
        lines.append(d.join(n_.capitalize() for n_ in names) + (d if st["trailing"] else ""))
        lines.append(d.join(f"[{u_}]" for u_ in units) + (d if st["trailing"] else ""))
    else:
        sep = "" if d == " " else " "
        lines.append(d.join(f"{n_}{sep}[{u_}]" for n_, u_ in zip(names, units))
                     + (d if st["trailing"] else ""))
    body = [_fmt_col(c_[2], st["sci"], c_[3]) for c_ in cols]
    if d == " ":
        w_ = [max(len(x_) for x_ in b_[:50]) + 2 for b_ in body]
        body = [np.char.rjust(b_, w) for b_, w in zip(body, w_)]
        rows_txt = [" ".join(r_) for r_ in zip(*body)]
    else:
        rows_txt = [d.join(r_) for r_ in zip(*body)]
    if st["trailing"]:
        rows_txt = [r_ + d for r_ in rows_txt]
    text = nl.join(lines + rows_txt) + nl
    with open(path, "w", encoding="utf-8-sig" if st["bom"] else "utf-8", newline="") as fh:
        fh.write(text)

    args = []
    if give_fn:
        args += ["--fn", f"{fn_given:.5g}"]
    if drv is None:
        args += ["--v0", f"{B['v0_ref'] * 1e3:.5g}"]
    if kind == "force":
        args += ["--stiffness", f"{k:.5g}"]
    P.update(style=style_id, record=kind, has_normal=has_normal, drive_column=drive_kind,
             samples_per_period=spp, fs_hz=fs, cell_fc_over_fn=f_cell / fn, cell_zeta=z_cell,
             lvdt_fc_over_fn=f_lvdt / fn, decimation=D, rows=int(n_rec), nuisance_sizes=nz,
             measured=meas)
    P = _jsonable(P)
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": path,
            "args": args, "fn_true": float(fn), "fn_given": float(fn_given) if give_fn else None,
            "params": P}


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
