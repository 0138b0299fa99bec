"""vda_squeak -- records from an automotive squeak & rattle stick-slip bench (VDA 230-206 style).

Bench (Ziegler SSP-04-like): the lower plate (material B) is moved by a linear drive at 1-4 mm/s; the
upper sample (material A, 10-40 N by dead weight or by a pneumatic bellows) sits in a sledge that is held
through a calibrated measuring spring k to a strain-gauge force sensor.  The spring extension x (the
sledge's displacement, x = F/k) obeys the thesis's belt model

    m x'' = -k x - c x' + s mu N_eff,      s = sign(v_rel),  v_rel = v_b(t) - x'

Drive programmes: one-way constant speed, speed steps (e.g. 1 <-> 4 mm/s as VDA), slide-hold-slide, or
reciprocating strokes with dwells (signed drive, recorded).  fn_true = sqrt(k/m)/(2 pi).

Friction law (own choice for a polymer pair): two-state adhesive-junction kinetics (Schallamach /
Chernyak-Leonov type).  A fraction phi of the interface is bridged by adhesive junctions that form at rest
with time constant tau_f (0.03-0.15 ms, WLF-shifted with the chamber temperature) and are torn after a
slip distance d_b = v_s tau_f:

    dphi/dt = (1 - phi)/tau_f - phi |v_rel|/d_b        steady state phi = 1/(1 + |v|/v_s), v_s 0.5-3 mm/s
    mu      = mu_d + dmu phi + eta |v_rel|              eta: viscous loss-modulus term (WLF-shifted)

so that the steady law is mu_ss(v) = mu_d + dmu/(1 + |v|/v_s) + eta |v| (static level mu_d + dmu).
Case extensions (all absent in `none`):
  twin_branch    : a viscoelastic ploughing "bow wave" p of the soft skin, built up over the slip distance
                   s_p and relaxing at rest with tau_r:  dp/dt = |v|(1-p)/s_p - p/tau_r,  mu += dmu_p p.
                   It is larger late in a slip, so the friction is higher on the decelerating half than on
                   the accelerating half at equal speed; dmu_p is tuned to 12-22 % of the slip's drop.
  static_ageing  : log-time creep of the junction area at rest, g = beta ln(1 + t_stick/tau_a), wiped out
                   over d_a = 2-5 um of slip; the drive steps (factor 4-8), holds (slide-hold-slide) or
                   reverses with long dwells; beta tuned to a peak growth of 7-16 % over the stick times.
  load_variation : the sliding guide is inclined against the spring axis and the sample is pressed by a
                   compliant bellows: N = N0 + K_N (x - x_m), tuned to 13-33 % peak-to-peak (the sign of
                   K_N random), normal channel recorded; the record starts in steady stick-slip.
  triggering     : shaker / valve pulsation: N = N0 (1 + e sin(2 pi f_t t)), e 3.5-7.5 %, f_t 2.7-7.5 fn
                   (<= 4.8 fn in `coarse`), placed half-way between harmonics of the record's own
                   stick-slip rate (re-checked after the run) and > 6 Hz from 50/60 Hz lines.  The junction
                   area creeps: aged junctions carry a load N_A that follows N with tau_A (about 3 e times
                   the loading time, >= 50 ms), N_eff = phi N_A + (1 - phi) N, so the static threshold is
                   smooth and the stick-slip does not lock to a subharmonic of f_t (with a rigid threshold
                   it does: f_t/f_ss becomes an integer); while sliding the friction follows N.
                   (load_variation uses the same creep with tau_A 5-30 ms.)
  drive_modulation: spindle ripple v_b = v0n (1 + a sin(2 pi f_m t + ph)), a 22-42 %, f_m 0.15-0.4 f_ss;
                   no drive column, only --v0 v0n.

Stick handling: event driven with a needed-force test.  In stick the sledge moves with the plate exactly
(x = x_s + X_b(t) - X_b(t_s); phi, p, g analytic, N_A by an exact first-order recursion); the slip starts at
the first root (grid search at 1/(40 f_max), then Brent) of |m a_b + c v_b + k x| - mu_static(t) N_eff(t);
a slip ends where v_rel crosses zero (located by re-taking the step) and sticks if the needed force is
below the static level, otherwise it slips on the other way (drive reversals).
Integrator: own fixed-step 4th-order Runge-Kutta-Nystrom for x'' = f(t, x, x') (step T_n/200, and
<= 1/(25 f_t)); the stiff internal states (phi, p, g, N_A) are advanced in every stage by the exact solution
of z' = -b (z - z_ss) with z_ss moving linearly over the (sub)step and b frozen at the Simpson-mean speed,
so the fast junction kinetics are stable and carry only their physical lag.  Dense output: cubic Hermite.

Sensor chain: strain-gauge bridge on the measuring spring -> carrier-frequency amplifier modelled as a
2nd-order Bessel low-pass (f_c 15-40 fn, at most 0.3 of the acquisition rate), white noise 0.03-0.1 % of the
force drop, 24-bit ADC (export to 0.1 mN); normal load cell likewise; drive position from a linear encoder
(1 um or 0.1 um steps) or the drive's speed set-point.  Export at 1, 2, 2.5, 5 or 10 kHz (>= 60 samples per
natural period); `coarse` = every D-th sample of an 80-samples-per-period acquisition (no anti-alias filter).

Memory inherent in the law in `none` (measured by check.py/mem.py on `none` seeds 0-39 from the simulated
truth): the junction lag makes the friction on the decelerating half of a slip differ from that on the
accelerating half at equal speed (0.1-0.9 of the slip's peak speed) by at most 0.34 % of the slip's force
drop (median 0.04 %; 0.9 % over 0.02-0.98 of the peak speed); the largest instantaneous |mu - mu_ss(v)| N
at speeds above 5 % of the peak is 3.2 % of the drop (median 0.5 %), only in the last instants before
re-stick; the static level does not depend on the stick time (spread < 1e-13; phi saturates within a few
tau_f, every stick lasts > 5 ms).
"""
import io
import math
import os
import zlib
from bisect import bisect_right

import numpy as np
from scipy import signal
from scipy.interpolate import CubicHermiteSpline
from scipy.optimize import brentq

NAME = "vda_squeak"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
# measured (none, seeds 0-39): largest |decelerating - accelerating| friction at equal speed / drop, largest
# instantaneous |mu - mu_ss(v)| N / drop, spread of the static level over the stick times
MEMORY_TWIN = 0.0034
MEMORY_LAG = 0.032
MEMORY_AGE = 0.0

G = 9.81

# material pairs: (German, English, mu_d range, dmu range, v_s range [mm/s], eta ref [1/(mm/s)], WLF C1, C2)
_MATERIALS = [
    ("PP-T20 genarbt K31 / PP-T20 genarbt K31", "PP-T20 grained K31 / PP-T20 grained K31",
     (0.27, 0.35), (0.08, 0.14), (0.6, 2.0), (3e-4, 9e-4), 5.0, 110.0),
    ("ABS / PC-ABS", "ABS / PC/ABS", (0.30, 0.38), (0.09, 0.16), (0.5, 2.0), (2e-4, 7e-4), 4.0, 120.0),
    ("TPO-Slush-Haut / PP-EPDM-T20", "TPO slush skin / PP-EPDM-T20", (0.45, 0.58), (0.12, 0.22),
     (0.8, 3.0), (6e-4, 1.5e-3), 8.0, 100.0),
    ("PU-Kunstleder / ABS genarbt", "PU artificial leather / ABS grained", (0.50, 0.62), (0.12, 0.22),
     (0.8, 3.0), (6e-4, 1.5e-3), 8.0, 100.0),
    ("PC-ABS lackiert (Softlack) / PC-ABS lackiert", "PC/ABS soft-touch lacquer / PC/ABS lacquer",
     (0.38, 0.50), (0.10, 0.20), (0.6, 2.5), (4e-4, 1.2e-3), 6.0, 110.0),
    ("Beflockung PA / PP-T20", "PA flock / PP-T20", (0.30, 0.38), (0.07, 0.12), (1.0, 3.0),
     (3e-4, 8e-4), 5.0, 110.0),
    ("PMMA (Klavierlack) / ABS", "PMMA (piano black) / ABS", (0.38, 0.48), (0.09, 0.17), (0.5, 2.0),
     (2e-4, 6e-4), 4.0, 120.0),
    ("PVC-Folie / PP-T20 genarbt", "PVC foil / PP-T20 grained", (0.42, 0.55), (0.10, 0.20), (0.8, 2.5),
     (5e-4, 1.3e-3), 7.0, 100.0),
]
_OPERATORS = ["M. Keller", "S. Hoffmann", "J. Wagner", "A. Becker", "T. Schulz", "L. Fischer",
              "K. Weber", "R. Braun", "D. Novak", "P. Lindner"]


def _rng(*parts):
    key = "|".join(str(p) for p in (NAME,) + parts)
    return np.random.default_rng([zlib.crc32(key.encode()), 69069])


# ----------------------------------------------------------------------------------------------- drive
class _Drive:
    """Piecewise-linear drive velocity (knots) plus an optional sinusoidal ripple; SI units."""

    def __init__(self, T, V, mod=None):
        T = list(map(float, T))
        V = list(map(float, V))
        T.append(T[-1] + 1e6)
        V.append(V[-1])
        self.T = np.array(T)
        self.V = np.array(V)
        self.Tl = T
        self.Vl = V
        dT = np.diff(self.T)
        with np.errstate(divide="ignore", invalid="ignore"):
            self.A = np.where(dT > 0, np.diff(self.V) / np.where(dT > 0, dT, 1.0), 0.0)
        self.Al = list(self.A)
        self.X = np.concatenate([[0.0], np.cumsum(0.5 * (self.V[:-1] + self.V[1:]) * dT)])
        self.mod = mod  # (v0n, a, omega, phase)

    def _idx(self, t):
        return np.clip(np.searchsorted(self.T, t, side="right") - 1, 0, len(self.T) - 2)

    def v(self, t):
        t = np.asarray(t, float)
        i = self._idx(t)
        out = self.V[i] + self.A[i] * (t - self.T[i])
        if self.mod is not None:
            v0, a, w, ph = self.mod
            out = out + v0 * a * np.sin(w * t + ph)
        return out

    def x(self, t):
        t = np.asarray(t, float)
        i = self._idx(t)
        d = t - self.T[i]
        out = self.X[i] + self.V[i] * d + 0.5 * self.A[i] * d * d
        if self.mod is not None:
            v0, a, w, ph = self.mod
            out = out + v0 * a * (math.cos(ph) - np.cos(w * t + ph)) / w
        return out

    def a(self, t):
        t = np.asarray(t, float)
        i = self._idx(t)
        out = self.A[i] + 0.0 * t
        if self.mod is not None:
            v0, a, w, ph = self.mod
            out = out + v0 * a * w * np.cos(w * t + ph)
        return out

    def vs(self, t):
        """scalar velocity (hot path)"""
        i = bisect_right(self.Tl, t) - 1
        if i < 0:
            i = 0
        out = self.Vl[i] + self.Al[i] * (t - self.Tl[i])
        if self.mod is not None:
            v0, a, w, ph = self.mod
            out += v0 * a * math.sin(w * t + ph)
        return out


# ----------------------------------------------------------------------------------------------- model
class _Sim:
    """Event-driven spring-slider with exponential-RKN4 slips and analytic sticks (SI units)."""

    def __init__(self, P, drive):
        self.P = P
        self.dr = drive
        self.m, self.k, self.c = P["m"], P["k"], P["c"]
        self.N0 = P["N0"]
        self.eps = P.get("trig_eps", 0.0)
        self.wt = 2 * math.pi * P.get("trig_f", 0.0)
        self.pst = P.get("trig_phase", 0.0)
        self.KN = P.get("KN", 0.0)
        self.xm = P.get("xm", 0.0)
        self.mud, self.dmu = P["mu_d"], P["dmu"]
        self.tf, self.db, self.eta = P["tau_f"], P["d_b"], P["eta"]
        self.dp, self.sp, self.tr = P.get("dmu_p", 0.0), P.get("s_p", 1e-3), P.get("tau_r", 1.0)
        self.beta, self.ta, self.da = P.get("beta", 0.0), P.get("tau_a", 0.05), P.get("d_a", 3e-6)
        # junction-area creep: the load the aged junctions carry follows N with time constant tau_A
        self.tA = P.get("tau_A", 0.0) if (self.eps or self.KN) else 0.0
        fn = math.sqrt(self.k / self.m) / (2 * math.pi)
        fmax = max(fn, P.get("trig_f", 0.0))
        self.h = min(1.0 / (200 * fn), 1.0 / (25 * fmax))
        self.dts = 1.0 / (40 * fmax)

    # normal load
    def Nv(self, t, x):
        out = self.N0 + self.KN * (x - self.xm)
        if self.eps:
            out = out + self.N0 * self.eps * np.sin(self.wt * t + self.pst)
        return out

    # states during a stick that began at ts with (phi0, p0, age0)
    def _stick_states(self, t, ts, phi0, p0, age0):
        d = t - ts
        phi = 1.0 - (1.0 - phi0) * np.exp(-d / self.tf)
        p = p0 * np.exp(-d / self.tr) if self.dp else 0.0 * d
        g = self.beta * np.log1p((age0 + d) / self.ta) if self.beta else 0.0 * d
        return phi, p, g

    def _chunk(self, tt, ts, xs, xb0, phi0, p0, age0, t_prev, NA_prev, N_prev):
        """needed force, static threshold, N and N_A on a uniform grid tt (first point one step after t_prev)"""
        x = xs + self.dr.x(tt) - xb0
        need = self.m * self.dr.a(tt) + self.c * self.dr.v(tt) + self.k * x
        N = self.Nv(tt, x)
        if self.tA:
            a = math.exp(-(tt[1] - tt[0]) / self.tA) if len(tt) > 1 else math.exp(-(tt[0] - t_prev) / self.tA)
            b = [(1 - a) / 2, (1 - a) / 2]
            zi = [b[1] * N_prev + a * NA_prev]
            NA = signal.lfilter(b, [1.0, -a], N, zi=zi)[0]
        else:
            NA = N
        phi, p, g = self._stick_states(tt, ts, phi0, p0, age0)
        thr = (self.mud + self.dmu * phi + self.dp * p + g) * (phi * NA + (1 - phi) * N)
        return np.abs(need) - thr, need, N, NA

    def _find_slip(self, ts, xs, phi0, p0, age0, NA0, t_end):
        xb0 = float(self.dr.x(ts))
        t0 = ts
        NAp = NA0
        Np = float(self.Nv(ts, xs))
        n = 4096
        while t0 < t_end:
            tt = t0 + self.dts * np.arange(1, n + 1)
            D, _, N, NA = self._chunk(tt, ts, xs, xb0, phi0, p0, age0, t0, NAp, Np)
            idx = np.flatnonzero(D > 0)
            if idx.size:
                i = idx[0]
                lo = tt[i - 1] if i > 0 else t0
                hi = tt[i]
                NAlo = NA[i - 1] if i > 0 else NAp
                NAhi = NA[i]

                def f(t):
                    w = (t - lo) / (hi - lo)
                    x = xs + float(self.dr.x(t)) - xb0
                    need = self.m * float(self.dr.a(t)) + self.c * float(self.dr.v(t)) + self.k * x
                    Nn = float(self.Nv(t, x))
                    na = NAlo + w * (NAhi - NAlo) if self.tA else Nn
                    phi, p, g = self._stick_states(t, ts, phi0, p0, age0)
                    return abs(need) - (self.mud + self.dmu * phi + self.dp * p + g) * (phi * na + (1 - phi) * Nn)

                if f(lo) > 0:
                    r = lo
                else:
                    r = brentq(f, lo, hi, xtol=1e-12, rtol=1e-12)
                # step just past the root so the slip starts with a strictly positive excess
                r2 = r + 1e-9
                while f(r2) <= 0 and r2 < hi:
                    r2 += (hi - r2) * 0.01 + 1e-9
                r2 = min(r2, hi)
                w = (r2 - lo) / (hi - lo)
                na = NAlo + w * (NAhi - NAlo) if self.tA else None
                return r2, na
            t0 = tt[-1]
            NAp, Np = NA[-1], N[-1]
        return None, None

    def run(self, t_end, max_slips=None):
        dr = self.dr
        m, k, c = self.m, self.k, self.c
        mud, dmu, eta, dp = self.mud, self.dmu, self.eta, self.dp
        tf, db, sp, tr = self.tf, self.db, self.sp, self.tr
        beta, ta, da = self.beta, self.ta, self.da
        N0, KN, xm, eps, wt, pst = self.N0, self.KN, self.xm, self.eps, self.wt, self.pst
        tA = self.tA
        itA = 1.0 / tA if tA else 0.0
        ex = math.exp
        sin = math.sin
        itf = 1.0 / tf
        itr = 1.0 / tr
        vb = dr.vs

        def Nfun(t, x):
            N = N0 + KN * (x - xm)
            if eps:
                N += N0 * eps * sin(wt * t + pst)
            return N

        def zupd(z, wa, wb, wm, Na, Nb, tau):
            """states over tau: exact solution of z' = -b (z - z_ss(t)) for a target z_ss moving
            linearly from its value at speed wa to that at wb, b frozen at the mean speed wm"""
            phi, p, g, na = z
            b = itf + wm / db
            sa = itf / (itf + wa / db)
            sb = itf / (itf + wb / db)
            sig = (sb - sa) / tau
            e = ex(-b * tau)
            phi = sb - sig / b + (phi - sa + sig / b) * e
            if dp:
                b2 = wm / sp + itr
                qa = (wa / sp) / (wa / sp + itr)
                qb = (wb / sp) / (wb / sp + itr)
                sig = (qb - qa) / tau
                p = qb - sig / b2 + (p - qa + sig / b2) * ex(-b2 * tau)
            if g:
                g = g * ex(-wm * tau / da)
            if tA:
                sig = (Nb - Na) / tau
                na = Nb - sig * tA + (na - Na + sig * tA) * ex(-itA * tau)
            return (phi, p, g, na)

        def acc(t, x, xd, z, w, s):
            phi, p, g, na = z
            N = Nfun(t, x)
            if tA:
                N = phi * na + (1.0 - phi) * N
            mu = mud + dmu * phi + eta * w + dp * p + g
            return (-k * x - c * xd + s * mu * N) / m

        segs = []
        slips = []
        t = 0.0
        x = 0.0
        phi, p, age = 1.0, 0.0, 0.0
        na = N0 + KN * (0.0 - xm)
        h0 = self.h
        while t < t_end:
            ts = t
            tsl, na_sl = self._find_slip(ts, x, phi, p, age, na, t_end)
            te = t_end if tsl is None else tsl
            segs.append(("stick", ts, te, x, float(dr.x(ts)), phi, p, age))
            if tsl is None:
                break
            # states at slip onset
            xs = x + float(dr.x(tsl)) - float(dr.x(ts))
            phi, p, g = self._stick_states(tsl, ts, phi, p, age)
            z = (float(phi), float(p), float(g), na_sl if tA else 0.0)
            need = m * float(dr.a(tsl)) + c * float(dr.v(tsl)) + k * xs
            s = 1.0 if need > 0 else -1.0
            Nn = float(self.Nv(tsl, xs))
            Neff = z[0] * z[3] + (1 - z[0]) * Nn if tA else Nn
            Fthr = (mud + dmu * z[0] + dp * z[1] + z[2]) * Neff
            stick_time = tsl - ts
            t, x, xd = tsl, xs, float(dr.v(tsl))
            T_ = [t]; X_ = [x]; XD_ = [xd]; Z_ = [z]
            nstep = 0
            ended = False
            while True:
                h = h0
                retake = 0
                w1 = abs(vb(t) - xd)
                N1 = Nfun(t, x)
                a1 = acc(t, x, xd, z, w1, s)
                while True:
                    t2 = t + 0.5 * h
                    x2 = x + 0.5 * h * xd + h * h / 8.0 * a1
                    xd2 = xd + 0.5 * h * a1
                    vb2 = vb(t2)
                    w2 = abs(vb2 - xd2)
                    N2 = Nfun(t2, x2)
                    z2 = zupd(z, w1, w2, 0.5 * (w1 + w2), N1, N2, 0.5 * h)
                    a2 = acc(t2, x2, xd2, z2, w2, s)
                    xd3 = xd + 0.5 * h * a2
                    w3 = abs(vb2 - xd3)
                    z3 = zupd(z, w1, w3, 0.5 * (w1 + w3), N1, N2, 0.5 * h)
                    a3 = acc(t2, x2, xd3, z3, w3, s)
                    t4 = t + h
                    x4 = x + h * xd + 0.5 * h * h * a3
                    xd4 = xd + h * a3
                    vb4 = vb(t4)
                    w4 = abs(vb4 - xd4)
                    N4 = Nfun(t4, x4)
                    z4 = zupd(z, w1, w4, (w1 + 2 * w2 + 2 * w3 + w4) / 6.0, N1, N4, h)
                    a4 = acc(t4, x4, xd4, z4, w4, s)
                    xn = x + h * xd + h * h / 6.0 * (a1 + a2 + a3)
                    xdn = xd + h / 6.0 * (a1 + 2 * a2 + 2 * a3 + a4)
                    vrn = vb4 - xdn
                    if nstep >= 3 and s * vrn <= 0.0 and retake < 4:
                        vr0 = vb(t) - xd
                        den = s * vr0 - s * vrn
                        frac = (s * vr0) / den if den > 0 else 1.0
                        hn = max(h * frac * (1.0 - 1e-9), 1e-12)
                        if hn < h:
                            h = hn
                            retake += 1
                            continue
                    break
                w5 = abs(vrn)
                N5 = Nfun(t4, xn)
                z = zupd(z, w1, w5, (w1 + 2 * w2 + 2 * w3 + w5) / 6.0, N1, N5, h)
                t, x, xd = t4, xn, xdn
                nstep += 1
                T_.append(t); X_.append(x); XD_.append(xd); Z_.append(z)
                vr = vb(t) - xd
                if t >= t_end:
                    break
                if nstep >= 3 and (s * vr <= 1e-9 * max(abs(vb(t)), 1e-6) or retake >= 4):
                    ended = True
                    break
            Z = np.array(Z_)
            slips.append(dict(t=np.array(T_), x=np.array(X_), xd=np.array(XD_), phi=Z[:, 0],
                              p=Z[:, 1], g=Z[:, 2], NA=Z[:, 3], s=s, stick_time=stick_time,
                              t0=tsl, F0=k * xs, Fthr=Fthr, complete=ended))
            segs.append(("slip", len(slips) - 1))
            if not ended:
                break
            phi, p, g, na = z
            age = ta * (math.exp(g / beta) - 1.0) if beta and g > 0 else 0.0
            slips[-1]["t1"] = t
            slips[-1]["F1"] = k * x
            if max_slips is not None and len(slips) >= max_slips:
                break
        return _Result(self, segs, slips, t_end)


class _Result:
    def __init__(self, sim, segs, slips, t_end):
        self.sim = sim
        self.segs = segs
        self.slips = slips
        self.t_end = t_end
        for sl in slips:
            w = np.abs(np.array([sim.dr.vs(t) for t in sl["t"]]) - sl["xd"])
            N = sim.Nv(sl["t"], sl["x"])
            if sim.tA:
                N = sl["phi"] * sl["NA"] + (1 - sl["phi"]) * N
            mu = sim.mud + sim.dmu * sl["phi"] + sim.eta * w + sim.dp * sl["p"] + sl["g"]
            sl["w"] = w
            sl["N"] = N
            sl["Ff"] = mu * N  # magnitude, acting along s
            sl["mu_ss"] = sim.mud + sim.dmu / (1.0 + w * sim.tf / sim.db) + sim.eta * w

    def complete_slips(self, t0=-1.0, t1=1e99, frac=0.3):
        """complete major slips (force drop >= frac of the largest): precursor micro-slips are left out"""
        sl = [s for s in self.slips if s["complete"] and s["t0"] >= t0 and s["t1"] <= t1]
        if not sl:
            return sl
        dmax = max(abs(s["F0"] - s["F1"]) for s in sl)
        return [s for s in sl if abs(s["F0"] - s["F1"]) >= frac * dmax]

    def eval(self, t):
        """spring extension x at times t (sorted)"""
        t = np.asarray(t, float)
        x = np.empty_like(t)
        sim = self.sim
        for sg in self.segs:
            if sg[0] == "stick":
                _, ts, te, xs, xb0, _, _, _ = sg
                i0, i1 = np.searchsorted(t, [ts, te])
                if i1 > i0:
                    x[i0:i1] = xs + sim.dr.x(t[i0:i1]) - xb0
            else:
                sl = self.slips[sg[1]]
                ts, te = sl["t"][0], sl["t"][-1]
                i0, i1 = np.searchsorted(t, [ts, te])
                if i1 > i0:
                    if len(sl["t"]) > 1:
                        x[i0:i1] = CubicHermiteSpline(sl["t"], sl["x"], sl["xd"])(t[i0:i1])
                    else:
                        x[i0:i1] = sl["x"][0]
        last = self.segs[-1]
        if last[0] == "slip":
            sl = self.slips[last[1]]
            i0 = np.searchsorted(t, sl["t"][-1])
            x[i0:] = sl["x"][-1]
        return x


# ----------------------------------------------------------------------------------------------- metrics
def twin_ratio(sl, lo=0.1, hi=0.9, use_mu=False):
    """(friction on decelerating half - accelerating half) at equal speed, mean over lo..hi of the
    peak speed, over the slip's spring-force drop (use_mu: of the friction coefficient times mean N)."""
    w, f = sl["w"], sl["Ff"]
    if use_mu:
        f = f / sl["N"] * np.mean(sl["N"])
    if len(w) < 12:
        return np.nan
    i = int(np.argmax(w))
    wm = w[i]
    if i < 4 or len(w) - i < 4:
        return np.nan
    wa, fa = w[: i + 1], f[: i + 1]
    wd, fd = w[i:][::-1], f[i:][::-1]
    oa = np.argsort(wa, kind="stable")
    od = np.argsort(wd, kind="stable")
    u = np.linspace(lo, hi, 41) * wm
    da = np.interp(u, wa[oa], fa[oa])
    dd = np.interp(u, wd[od], fd[od])
    drop = abs(sl["F0"] - sl["F1"])
    return float(np.mean(dd - da) / drop)


def memory_ratio(sl):
    """largest |mu - mu_ss(v)| N over the drop during the slip (junction lag), speeds > 5 % of peak."""
    w = sl["w"]
    sel = w > 0.05 * w.max()
    mu = sl["Ff"] / sl["N"]
    return float(np.max(np.abs(mu[sel] - sl["mu_ss"][sel]) * sl["N"][sel]) / abs(sl["F0"] - sl["F1"]))


def ageing_growth(slips, tau_a):
    """peak-force growth over the record's range of stick times (fit A + B ln(1 + t/tau_a))."""
    ts = np.array([s["stick_time"] for s in slips])
    Fp = np.array([s["Fthr"] for s in slips])  # static friction at onset (= the peak spring force but
    # for the drive's inertial and damping share and jumps of its acceleration, on the drive's ramps)
    X = np.log1p(ts / tau_a)
    if np.ptp(X) <= 0:
        return 0.0, ts, Fp
    B, A = np.polyfit(X, Fp, 1)
    lo = A + B * X.min()
    hi = A + B * X.max()
    return float((hi - lo) / lo), ts, Fp


def slip_frequency(slips):
    """mean rate of the major slips"""
    t0 = np.array([s["t0"] for s in slips])
    if len(t0) < 3:
        return np.nan
    return float((len(t0) - 1) / (t0[-1] - t0[0]))


# ----------------------------------------------------------------------------------------------- build
def _draw_physics(case, seed):
    r = _rng("phys", case, seed)
    mi = int(r.integers(len(_MATERIALS)))
    mat = _MATERIALS[mi]
    mount = "pneumatic" if r.random() < 0.5 else "dead weight"
    N0 = float(r.choice([10.0, 10.0, 40.0, 40.0, 20.0, 25.0, 30.0]))
    v0 = float(r.choice([1.0, 4.0, 1.0, 4.0, 2.0, 3.0]))  # mm/s
    temp = float(r.choice([23.0, 23.0, 23.0, 23.0, 40.0, 60.0]))
    C1, C2 = mat[6], mat[7]
    log_aT = -C1 * (temp - 23.0) / (C2 + temp - 23.0)
    aT = 10.0 ** log_aT
    mu_d = r.uniform(*mat[2])
    dmu = r.uniform(*mat[3])
    vs = r.uniform(*mat[4]) * 1e-3  # m/s at the test temperature
    tau_f_ref = r.uniform(0.06e-3, 0.15e-3)  # junction formation time at 23 degC
    tau_f = float(np.clip(tau_f_ref * aT, 0.03e-3, 0.15e-3))
    d_b = vs * tau_f
    eta_ref = r.uniform(*mat[5])
    eta = eta_ref * max(aT, 0.2) * 1e3  # per m/s
    # bench: natural frequency and stick time drawn, spring rate and effective moving mass follow
    dF = 2.0 * dmu * N0 * 0.8
    fn = r.uniform(8.0, 40.0)
    t_stick = float(np.clip(r.uniform(2.5, 12.0) / fn, 0.05, 1.0))
    k = float(np.clip(dF / (v0 * 1e-3 * t_stick), 2000.0, 150000.0))
    m_min = 0.25 + (N0 / G if mount == "dead weight" else 0.1)
    m = float(np.clip(k / (2 * math.pi * fn) ** 2, m_min, 6.0))
    k = max(k, m * (2 * math.pi * r.uniform(7.0, 10.0)) ** 2)
    fn = math.sqrt(k / m) / (2 * math.pi)
    zeta = r.uniform(0.01, 0.05)
    c = 2 * zeta * math.sqrt(k * m)
    u = r.random()
    n_cycles = int(r.integers(15, 41)) if u < 0.7 else (int(r.integers(10, 15)) if u < 0.85
                                                        else int(r.integers(41, 61)))
    return dict(material_index=mi, material_de=mat[0], material_en=mat[1], mount=mount, N0=N0,
                v0_mm_s=v0, temperature_C=temp, aT=aT, mu_d=mu_d, dmu=dmu, v_s=vs, tau_f=tau_f,
                d_b=d_b, eta=eta, k=k, m=m, c=c, zeta=zeta, fn=fn, n_cycles=n_cycles,
                t_stick_design=t_stick)


def _const_drive(v, t_pre, ramp, mod=None):
    if mod is not None:
        return _Drive([0.0], [v], mod)
    return _Drive([0.0, t_pre, t_pre + ramp], [0.0, 0.0, v])


def _calib(P, v, n=6, extra=None):
    """short run at constant speed v (m/s): slip period and drop from the last complete slips."""
    Q = dict(P)
    if extra:
        Q.update(extra)
    dr = _const_drive(v, 0.0, 0.0) if not Q.get("_mod") else _Drive([0.0], [v], Q["_mod"])
    res = _Sim(Q, dr).run(t_end=1e4, max_slips=n)
    sl = res.complete_slips()
    t0 = np.array([s["t0"] for s in sl])
    T = float(np.mean(np.diff(t0[1:]))) if len(t0) > 3 else float(np.diff(t0)[-1])
    drop = float(np.median([abs(s["F0"] - s["F1"]) for s in sl[1:]]))
    res.Fpeak = float(np.median([abs(s["F0"]) for s in sl[1:]]))
    return T, drop, res


def _profile(kind, r, P, vlist, Tss, n_cycles, ramp_acc, t_pre, tload):
    """knots (T, V) of a drive programme in m/s; returns knots and description"""
    Tk, Vk = [0.0], [0.0]
    t = t_pre
    Tk.append(t); Vk.append(0.0)
    desc = []

    def go(vt, dur):
        nonlocal t
        dv = abs(vt - Vk[-1])
        tr = dv / ramp_acc
        t += tr
        Tk.append(t); Vk.append(vt)
        t += dur
        Tk.append(t); Vk.append(vt)

    if kind == "const":
        go(vlist[0], n_cycles * Tss[0] + tload[0])
        desc.append(("const", vlist[0]))
    elif kind == "steps":
        nseg = int(r.integers(3, 6))
        per = max(4, n_cycles // nseg)
        for i in range(nseg):
            j = i % len(vlist)
            go(vlist[j], per * Tss[j] + (tload[j] if i == 0 else 0.0))
            desc.append(("level", vlist[j], per))
    elif kind == "shs":
        nh = int(r.integers(2, 4))
        per = max(4, n_cycles // (nh + 1))
        holds = []
        go(vlist[0], per * Tss[0] + tload[0])
        for i in range(nh):
            H = float(r.uniform(3.0, 10.0) * Tss[0] * (1 + 1.5 * i))
            holds.append(H)
            go(0.0, H)
            go(vlist[0], per * Tss[0])
        desc.append(("holds", holds))
    elif kind == "recip":
        ns = int(r.integers(2, 5))
        per = max(5, n_cycles // ns)
        dw = []
        sgn = 1.0
        for i in range(ns):
            go(sgn * vlist[0], per * Tss[0] + (1.0 if i == 0 else 2.0) * tload[0])
            D = float(r.uniform(0.3, 1.5)) if P.get("_dwell_scale") is None else \
                float(P["_dwell_scale"] * r.uniform(0.6, 1.6) * (1 + (i % 3)))
            dw.append(D)
            go(0.0, D)
            sgn = -sgn
        desc.append(("recip", ns, dw))
    t_end = t + 0.3 * Tss[0]
    Tk.append(t_end + 1.0); Vk.append(Vk[-1])
    return Tk, Vk, t_end, desc


def _pick_ft(ratio, rmax, fn, fss):
    """trigger frequency near ratio*fn, half-way between stick-slip harmonics, away from mains lines"""
    ratio = min(ratio, rmax)
    n_lo = max(1, int(2.55 * fn / fss) - 1)
    n_hi = int(rmax * fn / fss) + 1
    cands = [(n_ + 0.5) * fss for n_ in range(n_lo, n_hi + 1)]
    cands = [f for f in cands if 2.55 * fn <= f <= rmax * fn]
    good = [f for f in cands if all(abs(f - j * mf) > 6.0 for mf in (50.0, 60.0) for j in range(1, 8))]
    good = good or cands or [ratio * fn]
    return float(min(good, key=lambda f: abs(f - ratio * fn)))


def _build(case, seed, nuisance="clean"):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    P = _draw_physics(case, seed)
    r = _rng("case", case, seed)
    fn = P["fn"]
    v0 = P["v0_mm_s"] * 1e-3
    base = dict(m=P["m"], k=P["k"], c=P["c"], N0=P["N0"], mu_d=P["mu_d"], dmu=P["dmu"],
                tau_f=P["tau_f"], d_b=P["d_b"], eta=P["eta"])
    T0, drop0, _ = _calib(base, v0)
    P["Tss_calib"] = T0
    P["drop_calib"] = drop0
    ramp_acc = float(r.uniform(0.1, 0.4))  # m/s^2
    t_pre = float(r.choice([0.0, r.uniform(0.05, 0.4)]))
    kind = "const"
    vlist = [v0]
    meas = {}
    mod = None
    if case == "none":
        u = r.random()
        kind = "const" if u < 0.6 else ("steps" if u < 0.8 else "recip")
        if kind == "steps":
            vlist = [v0, v0 * float(r.choice([0.25, 0.5, 2.0, 4.0]))]
    elif case == "twin_branch":
        kind = "const" if r.random() < 0.75 else "recip"
        target = float(r.uniform(0.12, 0.22))
        slip_len = drop0 / P["k"]
        base["s_p"] = float(r.uniform(0.3, 0.8) * slip_len)
        base["tau_r"] = float(r.uniform(0.15, 0.3) * T0)
        base["dmu_p"] = 0.05
        for _ in range(4):
            _, _, res = _calib(base, v0, n=6)
            tr_ = np.nanmedian([twin_ratio(s) for s in res.complete_slips()[1:]])
            if tr_ <= 0.01:
                base["dmu_p"] *= 3.0
                continue
            base["dmu_p"] *= target / tr_
            if abs(tr_ / target - 1) < 0.05:
                break
        P["twin_target"] = target
    elif case == "load_variation":
        base["tau_A"] = float(r.uniform(0.005, 0.03))
        target = float(r.uniform(0.13, 0.33))
        sgn = 1.0 if r.random() < 0.5 else -1.0
        mus = P["mu_d"] + P["dmu"]

        def _pp(res):
            xs = np.concatenate([s_["x"] for s_ in res.complete_slips()[1:]])
            Nx = res.sim.Nv(0.0, xs)
            return (Nx.max() - Nx.min()) / P["N0"], xs

        for sg_try in (sgn, -sgn):
            base.pop("KN", None)
            base.pop("xm", None)
            _, _, res = _calib(base, v0, n=6)
            pp, xs = _pp(res)
            base["KN"] = sg_try * target * P["N0"] / np.ptp(xs)
            for _ in range(6):
                base["KN"] = float(np.sign(base["KN"]) * min(abs(base["KN"]), 0.55 * P["k"] / mus))
                base["xm"] = float(0.5 * (xs.max() + xs.min()))
                _, _, res = _calib(base, v0, n=6)
                pp, xs = _pp(res)
                if abs(pp / target - 1) < 0.04:
                    break
                base["KN"] *= target / pp
            if 0.11 <= pp <= 0.38:
                break
        P["load_sign_used"] = float(np.sign(base["KN"]))
        P["load_target"] = target
    elif case == "static_ageing":
        u = r.random()
        kind = "steps" if u < 0.4 else ("shs" if u < 0.7 else "recip")
        fac = float(r.choice([4.0, 4.0, 5.0, 6.0, 8.0]))
        if kind == "steps":
            vlist = [v0, v0 * fac] if v0 * fac <= 4.5e-3 else [v0, v0 / fac]
        else:
            P["_dwell_scale"] = float(r.uniform(3.0, 8.0) * T0)
        base["tau_a"] = float(r.uniform(0.01, 0.08))
        base["d_a"] = float(r.uniform(2e-6, 5e-6))
        base["beta"] = 0.0
        P["ageing_target"] = float(r.uniform(0.07, 0.16))
    elif case == "triggering":
        base["trig_eps"] = float(r.uniform(0.035, 0.075))
        base["trig_phase"] = float(r.uniform(0, 2 * math.pi))
        P["trig_ratio_draw"] = float(r.uniform(2.7, 7.5))
    elif case == "drive_modulation":
        P["mod_a"] = float(r.uniform(0.22, 0.42))
        P["mod_ratio_draw"] = float(r.uniform(0.15, 0.4))
        P["mod_phase"] = float(r.uniform(0, 2 * math.pi))

    # nuisance-independent randomness for the acquisition
    ra = _rng("acq", case, seed)
    rn = _rng("nuis", case, seed, nuisance)
    coarse = nuisance == "coarse"
    if case == "triggering":
        rmax = 7.5 if not coarse else 4.8
        t_load = _calib(base, v0)[2].Fpeak / (P["k"] * v0)
        base["tau_A"] = float(np.clip(r.uniform(2.5, 4.0) * base["trig_eps"] * t_load, 0.05, 1.5))
        base["trig_f"] = _pick_ft(P["trig_ratio_draw"], rmax, fn, 1.0 / T0)
        Tn, _, _ = _calib(base, v0, n=8)
        base["trig_f"] = _pick_ft(P["trig_ratio_draw"], rmax, fn, 1.0 / Tn)
    if case == "drive_modulation":
        fm = P["mod_ratio_draw"] / T0
        mod = (v0, P["mod_a"], 2 * math.pi * fm, P["mod_phase"])
        P["mod_f"] = fm

    # drive programme (stick-slip periods and peak force from short runs with the effect switched on)
    if case == "static_ageing":
        base["beta"] = float(P["ageing_target"] * (P["mu_d"] + P["dmu"]) / 3.0)
    Tss, Fpk = [], []
    for v in vlist:
        Tv, _, rv = _calib(base, v)
        Tss.append(Tv)
        Fpk.append(rv.Fpeak)
    P["Tss_levels"] = Tss
    n_cyc = P["n_cycles"] + (2 if case == "load_variation" else 0)
    dwell_scale = P.pop("_dwell_scale", None) if (case == "static_ageing" and kind == "recip") else None
    P.pop("_dwell_scale", None)
    stretch = 1.0
    for attempt in range(3):
        rp = _rng("profile", case, seed)
        if case == "drive_modulation":
            t_end = n_cyc * T0 * stretch + Fpk[0] / (P["k"] * v0) + 0.2 * T0
            drive = _Drive([0.0], [v0], mod)
            desc = [("modulated", v0)]
        else:
            Pd = {"_dwell_scale": dwell_scale} if dwell_scale else {}
            Tk, Vk, t_end, desc = _profile(kind, rp, Pd, vlist, [T * stretch for T in Tss], n_cyc, ramp_acc,
                                           t_pre, [F / (P["k"] * v) for F, v in zip(Fpk, vlist)])
            drive = _Drive(Tk, Vk)
        sim = _Sim(base, drive)
        res = sim.run(t_end)
        if case == "triggering":
            # the record's own stick-slip rate: keep f_t half-way between its harmonics
            for it in range(5):
                fss_m = slip_frequency(res.complete_slips())
                rho = base["trig_f"] / fss_m
                if 0.25 <= rho - math.floor(rho) <= 0.75:
                    break
                base["trig_f"] = _pick_ft(base["trig_f"] / fn, rmax, fn, fss_m)
                sim = _Sim(base, drive)
                res = sim.run(t_end)
            P["trig_attempts"] = it + 1
        if case == "static_ageing":
            # tune beta on the full programme
            tgt = P["ageing_target"]
            if attempt == 0:
                Gr, ts_, Fp = ageing_growth(res.complete_slips(), base["tau_a"])
                X = np.log1p(ts_ / base["tau_a"])
                base["beta"] = float(tgt * (P["mu_d"] + P["dmu"]) / max(np.ptp(X), 0.3))
            for it in range(5):
                sim = _Sim(base, drive)
                res = sim.run(t_end)
                Gr, _, _ = ageing_growth(res.complete_slips(), base["tau_a"])
                if abs(Gr / tgt - 1) < 0.06:
                    break
                base["beta"] *= tgt / max(Gr, 1e-3)
        nmaj = len(res.complete_slips())
        if nmaj >= 0.85 * n_cyc:
            break
        stretch *= min(3.0, 1.05 * n_cyc / max(nmaj - 1, 1))
    P["plan_stretch"] = stretch
    # export window
    t_exp0 = 0.0
    if case == "load_variation":
        sl = res.complete_slips()
        t_exp0 = float(sl[1]["t1"] + r.uniform(0.1, 0.6) * (sl[2]["t0"] - sl[1]["t1"]))
    # ------------------------------------------------------------------ acquisition
    P["drive_kind"] = kind
    fmt = _choose_format(case, seed, ra, P, kind, nuisance)
    dur = t_end - t_exp0
    if coarse:
        spp = float(rn.uniform(10.0, 15.0)) if case != "triggering" else float(rn.uniform(13.0, 15.0))
        fs = spp * fn
        D = int(math.ceil(80.0 * fn / fs))
        fs_fine = fs * D
    else:
        rates = [1000.0, 2000.0, 2500.0, 5000.0, 10000.0]
        ok = [f for f in rates if f >= 60 * fn and f * dur <= 250000]
        if not ok:
            ok = [min([f for f in rates if f >= 60 * fn] or [10000.0])]
        fs = float(ra.choice(ok[:3]))
        D = 1
        fs_fine = fs
    n_fine = int(math.floor(dur * fs_fine)) + 1
    tf_ = t_exp0 + np.arange(n_fine) / fs_fine
    xx = res.eval(tf_)
    F_true = P["k"] * xx
    N_true = sim.Nv(tf_, xx) + 0.0 * tf_
    pos_true = drive.x(tf_)
    vel_true = drive.v(tf_)
    fc = float(min(ra.uniform(15.0, 40.0) * fn, 0.3 * fs_fine))
    sos = signal.bessel(2, fc, fs=fs_fine, output="sos", norm="phase")
    zi = signal.sosfilt_zi(sos)
    Fm = signal.sosfilt(sos, F_true, zi=zi * F_true[0])[0]
    Nm = signal.sosfilt(sos, N_true, zi=zi * N_true[0])[0]
    cs = [s for s in res.complete_slips(t_exp0) if s["t0"] >= t_exp0]
    drop = float(np.median([abs(s["F0"] - s["F1"]) for s in cs])) if cs else drop0
    noise = float(ra.uniform(3e-4, 1e-3)) * drop
    Fm = Fm + ra.normal(0, noise, n_fine)
    Nm = Nm + ra.normal(0, float(ra.uniform(2e-4, 6e-4)) * P["N0"], n_fine)
    if D > 1:
        sel = slice(0, None, D)
        tf_, Fm, Nm, pos_true, vel_true = tf_[sel], Fm[sel], Nm[sel], pos_true[sel], vel_true[sel]
        F_true, N_true = F_true[sel], N_true[sel]
    t_out = tf_ - t_exp0
    nuis = {"name": nuisance}
    if nuisance == "hum":
        fh = float(rn.choice([50.0, 60.0]))
        A = float(rn.uniform(0.01, 0.05)) * drop
        ph = rn.uniform(0, 2 * np.pi, 3)
        h2, h3 = float(rn.uniform(0.1, 0.35)), float(rn.uniform(0.05, 0.25))
        hum = A * (np.sin(2 * np.pi * fh * t_out + ph[0]) + h2 * np.sin(4 * np.pi * fh * t_out + ph[1])
                   + h3 * np.sin(6 * np.pi * fh * t_out + ph[2])) / (1 + h2 + h3)
        Fm = Fm + hum
        Nm = Nm + 0.5 * hum
        nuis.update(f_hum=fh, amp_total_over_drop=A / drop, h2=h2, h3=h3)
    elif nuisance == "drift":
        tot = float(rn.uniform(0.02, 0.06)) * drop * (1 if rn.random() < 0.5 else -1)
        curv = float(rn.uniform(-0.5, 0.5))
        u = t_out / t_out[-1]
        dr_ = tot * (u + curv * (u * u - u))
        Fm = Fm + dr_
        nuis.update(drift_total_over_drop=tot / drop, curvature=curv)
    elif nuisance == "spikes":
        fr = float(rn.uniform(0.0007, 0.0045))
        ns = max(3, int(round(fr * len(Fm))))
        idx = np.sort(rn.choice(np.arange(2, len(Fm) - 2, 4), ns, replace=False))
        amp = rn.uniform(0.5, 3.0, ns) * drop * rn.choice([-1.0, 1.0], ns)
        Fm = Fm.copy()
        Fm[idx] += amp
        nuis.update(fraction=ns / len(Fm), n=int(ns), amp_over_drop_range=[0.5, 3.0])
    elif nuisance == "quantisation":
        q = float(rn.uniform(0.002, 0.01)) * drop
        Fm = np.round(Fm / q) * q
        nuis.update(step_N=q, step_over_drop=q / drop)
    elif nuisance == "coarse":
        nuis.update(samples_per_period=fs / fn, fs=fs)
    # args
    fn_given = None
    if nuisance == "fn_off":
        sg = 1.0 if rn.random() < 0.5 else -1.0
        fn_given = round(fn * (1 + 0.05 * sg), 2)
        nuis.update(fn_factor=1 + 0.05 * sg)
    elif ra.random() < 0.7:
        fn_given = round(fn * (1 + ra.uniform(-0.01, 0.01)), 1)
    args = []
    if fn_given is not None:
        args += ["--fn", f"{fn_given:g}"]
    if not fmt["drive_col"]:
        vtxt = f"{P['v0_mm_s']:g}"
        args += ["--v0", vtxt if ra.random() < 0.6 else vtxt + " mm/s"]
    k_nom = float(f"{P['k']:.3g}")
    if ra.random() < 0.7:
        args += ["--stiffness", f"{k_nom:g}"]
    else:
        args += ["--stiffness", f"{k_nom / 1000:g} N/mm"]
    # channels and write
    chans = dict(t=t_out, F=Fm, N=Nm, pos=pos_true, vel=vel_true)
    path_rel = _write(fmt, chans, P, case, seed, nuisance, ra, fs)
    params = dict(P)
    params.update(base=base, drive_kind=kind, drive_levels_mm_s=[v * 1e3 for v in vlist],
                  drive_desc=_jsonable(desc), t_end=t_end, t_export_start=t_exp0, fs=fs,
                  fs_fine=fs_fine, amp_fc=fc, noise_F=noise, drop=drop, format=fmt,
                  k_given=k_nom, nuisance=nuis, ramp_acc=ramp_acc, t_pre=t_pre)
    truth = dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=path_rel,
                 args=args, fn_true=float(fn), fn_given=fn_given, params=_jsonable(params))
    data = dict(res=res, sim=sim, drive=drive, t=t_out, F=Fm, N=Nm, F_true=F_true, N_true=N_true,
                pos=pos_true, vel=vel_true, t_exp0=t_exp0, fs=fs, drop=drop)
    return truth, data


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
        return _jsonable(o.tolist())
    return o


# ----------------------------------------------------------------------------------------------- formats
def _choose_format(case, seed, ra, P, kind, nuisance):
    style = ["de_csv", "en_csv", "de_txt_units", "en_txt_paren", "milli_csv", "de_dat"][int(ra.integers(6))]
    # drive column
    if case == "drive_modulation":
        drive_col = None
    elif kind != "const" or case == "static_ageing":
        drive_col = "pos" if (kind == "recip" or ra.random() < 0.6) else "vel"
    else:
        drive_col = None if ra.random() < 0.5 else ("pos" if ra.random() < 0.7 else "vel")
    if case == "load_variation":
        n_col = True
    elif case == "triggering":
        n_col = ra.random() < 0.5
    else:
        n_col = P["mount"] == "pneumatic" or ra.random() < 0.3
    cof = bool(n_col and case not in ("load_variation", "triggering") and style in ("en_csv", "de_csv")
               and ra.random() < 0.2)
    return dict(style=style, drive_col=drive_col, normal_col=bool(n_col), cof=cof)


def _write(fmt, ch, P, case, seed, nuisance, ra, fs):
    st = fmt["style"]
    de = st.startswith("de")
    milli = st == "milli_csv"
    year = int(ra.integers(2019, 2025))
    date = f"{year}-{int(ra.integers(1, 13)):02d}-{int(ra.integers(1, 29)):02d}"
    clock = f"{int(ra.integers(7, 18)):02d}:{int(ra.integers(0, 60)):02d}:{int(ra.integers(0, 60)):02d}"
    op = _OPERATORS[int(ra.integers(len(_OPERATORS)))]
    sample_id = f"SR-{year % 100:02d}-{int(ra.integers(100, 999))}"
    kind = P.get("drive_kind")
    mode_de = {"recip": "reversierend mit Verweilzeit", "steps": "einseitig, Geschwindigkeitsstufen",
               "shs": "einseitig mit Haltezeiten"}.get(kind, "einseitig")
    mode_en = {"recip": "reciprocating with dwells", "steps": "one-way, speed steps",
               "shs": "one-way with holds"}.get(kind, "one-way")
    if de:
        meta = [
            "Stick-Slip-Prüfstand SSP-04 -- Messdatenexport",
            "Prüfnorm: VDA 230-206 Teil 1",
            f"Probe: {sample_id}",
            f"Werkstoffpaarung: {P['material_de']}",
            f"Normalkraft (Soll): {P['N0']:g} N ({'Gewicht' if P['mount'] == 'dead weight' else 'pneumatisch'})",
            f"Prüfgeschwindigkeit (Soll): {P['v0_mm_s']:g} mm/s".replace(".", ","),
            f"Bewegungsart: {mode_de}",
            f"Federrate Messfeder: {P['k'] / 1000:.3g} N/mm".replace(".", ","),
            f"Prüfklima: {P['temperature_C']:g} °C / 50 % r.F.",
            f"Abtastrate: {fs:.6g} Hz".replace(".", ","),
            f"Prüfer: {op}",
            f"Datum: {date} {clock}",
        ]
    else:
        meta = [
            "Stick-slip test bench SSP-04 -- data export",
            "Test standard: VDA 230-206 part 1",
            f"Specimen: {sample_id}",
            f"Material pair: {P['material_en']}",
            f"Normal load (set): {P['N0']:g} N ({P['mount']})",
            f"Test speed (set): {P['v0_mm_s']:g} mm/s",
            f"Motion: {mode_en}",
            f"Measuring spring rate: {P['k'] / 1000:.3g} N/mm",
            f"Climate: {P['temperature_C']:g} degC / 50 % RH",
            f"Sample rate: {fs:.6g} Hz",
            f"Operator: {op}",
            f"Date: {date} {clock}",
        ]
    # columns
    cols = []
    tdec = max(4, int(math.ceil(math.log10(fs))) + 2) if abs(fs - round(fs)) < 1e-9 else 7
    cols.append((("Zeit", "s") if de else ("Time", "s"), ch["t"], f"%.{tdec}f"))
    fscale = 1e3 if milli else 1.0
    if fmt["cof"]:
        cof = ch["F"] / ch["N"]
        cols.append((("Reibwert COF", "-") if de else ("COF", "-"), cof, "%.5f"))
    else:
        fname = "Reibkraft" if de else ("friction" if milli else "Friction force")
        cols.append(((fname, "mN" if milli else "N"), ch["F"] * fscale, "%.2f" if milli else "%.4f"))
    if fmt["normal_col"]:
        nname = "Normalkraft" if de else ("normal" if milli else "Normal force")
        cols.append(((nname, "mN" if milli else "N"), ch["N"] * fscale, "%.1f" if milli else "%.4f"))
    enc = 1e-6 if ra.random() < 0.6 else 1e-7
    if fmt["drive_col"] == "pos":
        off = float(ra.choice([0.0, ra.uniform(5.0, 60.0)])) * 1e-3
        pos = np.round((ch["pos"] + off) / enc) * enc
        pname = "Weg" if de else ("position" if milli else "Position")
        if milli:
            cols.append(((pname, "um"), pos * 1e6, "%.1f"))
        else:
            cols.append(((pname, "mm"), pos * 1e3, "%.4f"))
    elif fmt["drive_col"] == "vel":
        vname = "Geschwindigkeit" if de else ("v0" if milli else "Drive speed")
        cols.append(((vname, "mm/s"), np.round(ch["vel"] * 1e3, 4), "%.4f"))
    if st == "de_csv":
        sep, dec, ext, hdr = ";", ",", ".csv", "bracket"
    elif st == "en_csv":
        sep, dec, ext, hdr = ",", ".", ".csv", "bracket"
    elif st == "de_txt_units":
        sep, dec, ext, hdr = "\t", ",", ".txt", "units_row"
    elif st == "en_txt_paren":
        sep, dec, ext, hdr = "\t", ".", ".txt", "paren"
    elif st == "milli_csv":
        sep, dec, ext, hdr = ",", ".", ".csv", "bracket"
    else:
        sep, dec, ext, hdr = " ", ".", ".dat", "bracket_ws"
    buf = io.StringIO()
    for line in meta:
        buf.write("# " + line + "\n")
    if hdr == "bracket":
        buf.write(sep.join(f"{n} [{u}]" for (n, u), _, _ in cols) + "\n")
    elif hdr == "paren":
        buf.write(sep.join(f"{n} ({u})" for (n, u), _, _ in cols) + "\n")
    elif hdr == "units_row":
        buf.write(sep.join(n for (n, u), _, _ in cols) + "\n")
        buf.write(sep.join(u for (n, u), _, _ in cols) + "\n")
    else:  # whitespace: names without blanks
        buf.write("  ".join(f"{n.replace(' ', '_')}[{u}]" for (n, u), _, _ in cols) + "\n")
    M = np.column_stack([c[1] for c in cols])
    body = io.StringIO()
    np.savetxt(body, M, fmt=[c[2] for c in cols], delimiter=sep if sep != " " else "  ")
    txt = body.getvalue()
    if dec == ",":
        txt = txt.replace(".", ",")
    buf.write(txt)
    fname = f"{NAME}_{case}_s{seed}_{nuisance}{ext}"
    return fname, buf.getvalue()


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    truth, _ = _build(case, seed, nuisance)
    fname, text = truth["file"]
    os.makedirs(outdir, exist_ok=True)
    path = os.path.abspath(os.path.join(outdir, fname))
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(text)
    truth["file"] = path
    return truth


def build(case, seed, nuisance="clean", outdir=None):
    """truth dict and the simulated truth (for the self-check); writes the file when outdir is given."""
    truth, data = _build(case, seed, nuisance)
    fname, text = truth["file"]
    if outdir is not None:
        os.makedirs(outdir, exist_ok=True)
        path = os.path.abspath(os.path.join(outdir, fname))
        with open(path, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        truth["file"] = path
    else:
        truth["file"] = fname
    return truth, data
