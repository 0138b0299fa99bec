"""video_block: a bench-top spring-block stick-slip experiment recorded by video tracking.

RIG. A wooden/polymer block (50-800 g, log-uniform) on a board, pulled through a soft linear coil spring
(k = m (2 pi fn)^2, fn 1.3-7.5 Hz; 3-7.5 Hz on `triggering`) by a motorised winch/cart at 1-38 mm/s; the
spring has a little internal damping (zeta 0.3-1.5 %, acting on the relative speed drive - block).
Normal load N0 = m g. The block moves forward only in every record measured (no back-slips).

FRICTION LAW (single-valued, mine): a Cauchy (Lorentzian) weakening in the log of the sliding speed on a
Coulomb floor plus a square-root (film-like) strengthening,
    mu(u) = mu_c + D / (1 + (ln(1 + u/v_s)/w)^2) + E (sqrt(1 + u/v_t) - 1),
mu_c 0.20-0.38 (0.12-0.20 on `triggering`), v_s 2-8 % of the peak slip speed, w 0.8-1.5, E such that the
strengthening at the peak slip speed is 8-20 % of D; a static level mu_s0 = mu(0+) + S, S 30-50 % of the
static-kinetic gap (gap 0.06-0.30; 0.20-0.30 on `triggering`).

STICK HANDLING: exact event-driven switching. In stick the block is at rest (x fixed, no creep); it
breaks away when |spring force| reaches the static limit mu_s N, located by Ridders' method on the
analytic spring force (the drive position is analytic). In slip it arrests when s*v crosses 0, located by
Ridders' method on re-taken integrator sub-steps from the step start; it sticks again if the spring force
is within the static limit there (else it slips on).

INTEGRATOR (own): fixed-step 4th-order Runge-Kutta-Nystrom in its general form for x'' = f(t, x, x')
(Kreyszig's stages, position stages with h^2/8), step Tn/200 in slip; a state variable (twin) by the
matching RK4 weights. The trajectory between steps/events is a cubic Hermite (x, v) for sampling.

CASES (mechanism; MEASURED on the ground truth, seeds 0-23 with nuisance s % 7; "twin" = decelerating
minus accelerating contact friction at equal true speed, mean over 10-90 % of each slip's peak speed,
median over slips, over the slip's spring-force drop; "ageing" = slope of the breakaway force on
ln(stick time) times ln(stick-time ratio), over the median drop):
- none: constant load, constant drive; on seeds 2, 5 mod 8 a drive stepping between two recorded speeds
  2-4x apart (stick times 2.1-3.7x apart). Contains: twin exactly 0 (the law has no state), ageing exactly
  0 (exact switching: the breakaway force is mu_s0 N to the root-finder's tolerance: peak sd 0.000 of the
  drop), constant N. What a 1-DoF reading could mistake: only the sensor chain (timing jitter, rolling
  shutter, 1 px quantisation, duplicated/dropped frames) and the spring's small internal damping (a term
  in the relative speed, not in the block's speed alone; with a constant drive that is a viscous term).
  17-33 slips.
- load_variation: even seeds: a magnet under the board pulls on a steel washer on the block, N = N0 (1 +
  A / (1 + ((x - x_m)/w_m)^2)) (a Lorentzian bump in the block's position); odd seeds: a roller on a leaf
  spring pressing on the block rides a wedge, N = N0 (1 + c (x - x_mid)/span), c of either sign. Measured
  N p-p 10.3-28.5 % of N0 over the record; F-level twin -0.021..+0.015 (mu-level 0); the peaks follow N
  (peak sd 4-23 % of the drop). The normal load is NOT recorded (video records carry no load channel).
- twin_branch: frictional heating dries the adsorbed water film of the contact: a dry fraction q with
  dq/dt = (|F v|/P_q)(1 - q) - q/tau_r (tau_r 0.3-0.7 of the stick time), friction x (1 + g q); the static
  limit carries the same g q term at the arrest, relaxing with q (so at a constant drive all peaks are
  equal). g calibrated on pilot runs: twin +0.122..+0.180 of the drop (target 0.115-0.185).
- static_ageing: mu_s = mu_s0 (1 + beta ln(1 + t_stick/tau_a)), tau_a 0.3-1 of the fast stick time; even
  seeds: drive stepping 4-8x between two recorded speeds; odd seeds: constant drive with holds (the winch
  paused 2-6 stick times). beta calibrated on pilot runs: ageing +0.111..+0.228 of the drop over stick
  times 4.1-10.8x apart; peak sd 4-9 % of the drop; the drive is always recorded (puller/cart column).
- triggering: a pager motor glued to the block: N = N0 (1 + eps sin(2 pi f_t t + phi)), eps 0.03-0.06,
  f_t 3.1-5.1 fn, below 0.42 of the frame rate. With exact thresholds the breakaways lock to the shaker's
  troughs (f_t/f_ss an integer) unless the load ramp per shaker period is comparable with the static
  limit's modulation, so these records use a large static-kinetic gap and a fast drive (fn/f_ss about
  1.5-2), and f_t is scanned (up to 48 pilot runs) until the record's f_t/f_ss is >= 0.17 from an integer:
  measured f_t/f_ss 5.2-8.2 (all >= 0.18 from an integer), N p-p 6.1-11.7 % of N0, peak sd 1.9-5.6 % of the
  drop, 17-34 slips in 5-19 s. F-level twin -0.012..+0.008 (mu-level 0).
- drive_modulation: the winch drum is not round: v0(t) = v0n (1 + a sin(2 pi fm t + phi)), a 0.20-0.45,
  fm set from a pilot's f_ss; measured fm/f_ss 0.12-0.38; stick times 1.5-2.3x apart. Only v0n is given
  (`--v0`); these records never carry the drive's position (block only, extension or force only).

SENSOR CHAIN (every record): VIDEO: frame rate 30/60/120/240 fps (30/60 declared as 29.97/59.94 on 40 %
of those; the true rate off by ~3e-4), per-frame timing jitter 0.05-0.8 ms (the Tracker/spreadsheet time
column is nominal; the OpenCV/phyphox time column is the container's timestamp), rolling shutter (each
marker read 0.1-0.6 frame late), sub-pixel tracking jitter 0.12-0.35 px (x0.8-1.5 on the puller), positions
rounded to whole pixels, 0-3 duplicated frames (position repeated) and 0-3 dropped frames (row missing);
pixel 0.05-0.5 mm chosen as 0.3-1 % of the slip (1.5-3 % on `quantisation`) but never smaller than the
field of view needs (both markers in a 1280/1920/3840 px frame), so long-travel records are coarser:
measured pixel 0.8-7.5 % of the slip (median 2.5 %) outside `quantisation`, 1.7-4.9 % on it (the field of
view dominates; `quantisation` is not always the coarsest); calibration-stick error 0.4 %; for the force sensor: a strain-gauge cell
in series with the spring (first-order, 15-40 fn), noise 0.3-0.8 % of the drop, ADC step 0.2-0.6 % of
the drop (1.5-3 % on `quantisation`), a winch rotary encoder (1440 counts/rev) for the drive.
Samples per natural period 11-99 (10.5-14.5 on `coarse`); 17-37 slips; records 5-552 s long (the
ageing records with slow steps or holds at low fn are minutes long); under 1.2 s a record to generate.
NUISANCES: hum = lighting flicker at 100/120 Hz, aliased by the frame rate (1.5-4.5 % of the slip,
smaller on the puller) or 50/60 Hz + 3rd harmonic pickup on the force channel; drift = camera creep
(4-12 % of the slip, on both markers) plus a zoom/scale drift 0.1-0.4 % (or a force-zero drift 3-10 % of
the drop); spikes = 0.1-0.5 % of frames mis-tracked by 15-60 % of the slip (1-2 frames) per marker (force:
0.3-1 drop outliers); quantisation = coarse pixel/ADC step; coarse = 10.5-14.5 frames (samples) per
natural period; fn_off = `--fn` 5 % off (+ or -).

FILES (what the software writes; not tailored): 
- Tracker "#multi:" export (TAB; track names line `mass A` `mass B`; `t x [y] x [y]`; units m or cm as
  calibrated, NOT in the header; E-notation or 6 significant digits), or a single-track `mass A` table.
- a Python/OpenCV tracker CSV with `#` comment lines (video, fps, resolution, `# scale: S mm/px`):
  `frame,time_s,block_x_px[,puller_x_px]` (raw image columns, the motion may run towards smaller px),
  `frame,time_s,block_x_mm,puller_x_mm`, or `frame,time_s,spring_extension_mm`; on about a third, 2-5
  rows repeated with the same time stamp (a frame decoded twice).
- phyphox-like `"Time (s)","Position (m)"` (block only).
- a spreadsheet CSV, `;` separated with a decimal comma: `t (s);block x (cm|mm);cart x (cm|mm)`.
- a force logger (Logger Pro style `"Latest: Time (s)"` or plain): `"Time (s)","Force (N)"[,"Position (m)"]`.
Positions may decrease with the motion (direction or axes flipped) on the two-marker formats.
ARGS: `--fn` (4 significant digits) except on seeds 7 mod 8 (never omitted on `triggering`/`fn_off`);
`--v0` (mm/s, "mm/s" or "cm/s") only when the file has no drive column; `--stiffness` (N/m or "N/mm")
only on force records.
"""
from __future__ import annotations

import bisect
import json
import math
import os
import zlib

import numpy as np
from scipy.interpolate import CubicHermiteSpline
from scipy.signal import lfilter

NAME = "video_block"
G = 9.81
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")


# ----------------------------------------------------------------------------------------------
# drive
# ----------------------------------------------------------------------------------------------
class Drive:
    """Piecewise-constant speed profile (steps, holds) with an optional sinusoidal wobble."""

    def __init__(self, t_starts, speeds, a=0.0, fm=0.0, phi=0.0):
        self.ts = [float(t) for t in t_starts]
        self.vs = [float(v) for v in speeds]
        ps = [0.0]
        for i in range(1, len(self.ts)):
            ps.append(ps[-1] + self.vs[i - 1] * (self.ts[i] - self.ts[i - 1]))
        self.ps = ps
        self.a, self.fm, self.phi = float(a), float(fm), float(phi)
        self.v0n = self.vs[0]

    def _i(self, t):
        return max(bisect.bisect_right(self.ts, t) - 1, 0)

    def pos(self, t):
        i = self._i(t)
        p = self.ps[i] + self.vs[i] * (t - self.ts[i])
        if self.a:
            w = 2 * math.pi * self.fm
            p += self.v0n * self.a / w * (math.cos(self.phi) - math.cos(w * t + self.phi))
        return p

    def vel(self, t):
        v = self.vs[self._i(t)]
        if self.a:
            v += self.v0n * self.a * math.sin(2 * math.pi * self.fm * t + self.phi)
        return v

    def pos_arr(self, t):
        t = np.asarray(t, float)
        i = np.clip(np.searchsorted(np.array(self.ts), t, side="right") - 1, 0, None)
        p = np.array(self.ps)[i] + np.array(self.vs)[i] * (t - np.array(self.ts)[i])
        if self.a:
            w = 2 * math.pi * self.fm
            p = p + self.v0n * self.a / w * (math.cos(self.phi) - np.cos(w * t + self.phi))
        return p

    def vel_arr(self, t):
        t = np.asarray(t, float)
        i = np.clip(np.searchsorted(np.array(self.ts), t, side="right") - 1, 0, None)
        v = np.array(self.vs)[i]
        if self.a:
            v = v + self.v0n * self.a * np.sin(2 * math.pi * self.fm * t + self.phi)
        return v


# ----------------------------------------------------------------------------------------------
# root finder (Ridders' method) and the Runge-Kutta-Nystrom step
# ----------------------------------------------------------------------------------------------
def ridders(g, a, b, ga, gb, tol, maxit=80):
    """Root of g in [a, b] (ga, gb of opposite sign or gb == 0). Returns (root, g(root))."""
    if gb == 0.0:
        return b, gb
    best, gbest = (a, ga) if abs(ga) < abs(gb) else (b, gb)
    for _ in range(maxit):
        m = 0.5 * (a + b)
        gm = g(m)
        s = math.sqrt(max(gm * gm - ga * gb, 0.0))
        if s == 0.0:
            return m, gm
        xn = m + (m - a) * (1.0 if ga > gb else -1.0) * gm / s
        gn = g(xn)
        if abs(gn) < abs(gbest):
            best, gbest = xn, gn
        if gn == 0.0:
            return xn, gn
        if (gm > 0) != (gn > 0):
            if m < xn:
                a, ga, b, gb = m, gm, xn, gn
            else:
                a, ga, b, gb = xn, gn, m, gm
        elif (ga > 0) != (gn > 0):
            b, gb = xn, gn
        else:
            a, ga = xn, gn
        if abs(b - a) < tol:
            break
    # return the bracket end on the far side (g <= 0 side for a falling function)
    return (b, gb) if gb <= 0 else (best, gbest)


class Slider:
    """1-DoF block on a board, spring (k, internal damping c) to the drive; forces in N, lengths in m."""

    def __init__(self, P, drive):
        self.P = P
        self.d = drive
        self.m, self.k, self.c = P["m"], P["k"], P["c"]
        self.N0 = P["N0"]
        self.mu_c, self.D, self.vs, self.w = P["mu_c"], P["D"], P["v_s"], P["w"]
        self.E, self.vt = P["E"], P["v_t"]
        self.mu_s0 = P["mu_s0"]
        self.beta, self.tau_a = P.get("beta", 0.0), P.get("tau_a", 1.0)
        self.g, self.Pq, self.tau_r = P.get("g_twin", 0.0), P.get("P_q", 1.0), P.get("tau_r", 1.0)
        self.load = P.get("load", None)
        self.eps, self.ft, self.phit = P.get("eps", 0.0), P.get("f_t", 0.0), P.get("phi_t", 0.0)

    # friction coefficient of the sliding speed u >= 0: a Cauchy (Lorentzian) weakening in ln(1 + u/v_s)
    # on a Coulomb floor, plus a square-root (film-like) strengthening
    def mu(self, u):
        L = math.log1p(u / self.vs) / self.w
        return self.mu_c + self.D / (1.0 + L * L) + self.E * (math.sqrt(1.0 + u / self.vt) - 1.0)

    def mu_arr(self, u):
        L = np.log1p(np.maximum(u, 0) / self.vs) / self.w
        return self.mu_c + self.D / (1.0 + L * L) + self.E * (np.sqrt(1.0 + np.maximum(u, 0) / self.vt) - 1.0)

    def load_factor(self, x):
        ld = self.load
        if ld is None:
            return 1.0
        if ld["kind"] == "magnet":
            z = (x - ld["x_m"]) / ld["w_m"]
            return (1.0 + ld["A"] / (1.0 + z * z)) / ld["norm"]
        return 1.0 + ld["c"] * (x - ld["x_mid"]) / ld["span"]

    def normal(self, t, x):
        n = self.N0 * self.load_factor(x)
        if self.eps:
            n *= 1.0 + self.eps * math.sin(2 * math.pi * self.ft * t + self.phit)
        return n

    def spring(self, t, x, v):
        return self.k * (self.d.pos(t) - x) + self.c * (self.d.vel(t) - v)

    def static_limit(self, t, x, t_arr, q_arr=0.0):
        age = max(t - t_arr, 0.0)
        mus = self.mu_s0 * (1.0 + self.beta * math.log1p(age / self.tau_a)) if self.beta else self.mu_s0
        if self.g and q_arr:
            # the dry fraction left at the arrest raises the static level by as much as the kinetic level
            # at 0+, and relaxes with it (so the block can always start to move at the breakaway)
            mus += (self.mu_c + self.D) * self.g * q_arr * math.exp(-age / self.tau_r)
        return mus * self.normal(t, x)

    def rhs(self, t, x, v, q, s):
        N = self.normal(t, x)
        u = s * v
        if u < 0.0:
            u = 0.0
        Ff = s * self.mu(u) * N * (1.0 + self.g * q)
        a = (self.spring(t, x, v) - Ff) / self.m
        qd = (abs(Ff * v) / self.Pq) * (1.0 - q) - q / self.tau_r if self.g else 0.0
        return a, qd, Ff, N

    def rkn(self, t, x, v, q, s, h):
        """Runge-Kutta-Nystrom (4th order, general form x'' = f(t, x, x')) step; q by RK4 weights."""
        k1, r1, _, _ = self.rhs(t, x, v, q, s)
        x2 = x + 0.5 * h * v + h * h / 8.0 * k1
        k2, r2, _, _ = self.rhs(t + 0.5 * h, x2, v + 0.5 * h * k1, q + 0.5 * h * r1, s)
        k3, r3, _, _ = self.rhs(t + 0.5 * h, x2, v + 0.5 * h * k2, q + 0.5 * h * r2, s)
        k4, r4, _, _ = self.rhs(t + h, x + h * v + 0.5 * h * h * k3, v + h * k3, q + h * r3, s)
        xn = x + h * v + h * h / 6.0 * (k1 + k2 + k3)
        vn = v + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        qn = q + h / 6.0 * (r1 + 2 * r2 + 2 * r3 + r4)
        return xn, vn, qn


def simulate(P, drive, n_slips, t_max):
    """Event-driven exact stick/slip switching. Stick: the block is at rest (x fixed), leaves when the
    spring force reaches the static limit (located by Ridders' method on the analytic force). Slip:
    RKN steps of Tn/h_div; the arrest (s v crosses 0) is located by Ridders' method on re-taken RKN
    sub-steps from the step start; the block sticks if the spring force is within mu_s N there."""
    S = Slider(P, drive)
    Tn = 1.0 / P["fn"]
    h = Tn / P["h_div"]
    hst = Tn / 24.0
    if S.eps:
        hst = min(hst, 1.0 / (14.0 * S.ft))
    T, X, V, Q, FF, NN = [0.0], [0.0], [0.0], [0.0], [0.0], [S.normal(0.0, 0.0)]
    brk, arr = [], []  # (t, x, F_spring, N, F_lim)
    t, x, q = 0.0, 0.0, 0.0
    t_arr = -P.get("t_age0", 5.0)
    q_arr = 0.0
    slip_rows = []  # (i0, i1) index ranges of each slip in the arrays
    while len(brk) < n_slips and t < t_max:
        # ---------------- stick ----------------
        def gst(tt):
            return abs(S.spring(tt, x, 0.0)) - S.static_limit(tt, x, t_arr, q_arr)
        ga = gst(t)
        tb = t
        found = ga >= 0.0
        while not found and tb < t_max:
            ta, tb = tb, tb + hst
            gb = gst(tb)
            if gb >= 0.0:
                tb, _ = ridders(lambda z: -gst(z), ta, tb, -ga, -gb, 1e-12 * max(1.0, tb))
                # ensure on the breakaway side
                while gst(tb) < 0.0:
                    tb += 1e-12 * max(1.0, tb)
                found = True
            ga = gb
        if not found:
            break
        if S.g:
            q = q * math.exp(-(tb - t) / S.tau_r)
        t = tb
        Fsp = S.spring(t, x, 0.0)
        s = 1.0 if Fsp > 0 else -1.0
        brk.append((t, x, Fsp, S.normal(t, x), S.static_limit(t, x, t_arr, q_arr)))
        if t - T[-1] > 1e-12:
            T.append(t); X.append(x); V.append(0.0); Q.append(q); FF.append(s * S.static_limit(t, x, t_arr, q_arr))
            NN.append(S.normal(t, x))
        i0 = len(T) - 1
        # ---------------- slip ----------------
        v = 0.0
        nstep = 0
        while True:
            xn, vn, qn = S.rkn(t, x, v, q, s, h)
            nstep += 1
            if s * vn <= 0.0:
                if nstep == 1 and v == 0.0:
                    raise RuntimeError("no acceleration at the breakaway")
                x0, v0_, q0, t0 = x, v, q, t

                def gv(tau):
                    return s * S.rkn(t0, x0, v0_, q0, s, tau)[1]
                tau, _ = ridders(gv, 0.0, h, s * v0_, s * vn, 1e-13 * max(1.0, t0) + 1e-15)
                x, v, q = S.rkn(t0, x0, v0_, q0, s, tau)[:3] if tau > 0 else (x0, v0_, q0)
                t = t0 + tau
                v = 0.0
                a, _, Ff, N = S.rhs(t, x, 0.0, q, s)
                if t - T[-1] <= 1e-12:
                    T.pop(); X.pop(); V.pop(); Q.pop(); FF.pop(); NN.pop()
                T.append(t); X.append(x); V.append(0.0); Q.append(q); FF.append(Ff); NN.append(N)
                break
            t += h
            x, v, q = xn, vn, qn
            a, _, Ff, N = S.rhs(t, x, v, q, s)
            T.append(t); X.append(x); V.append(v); Q.append(q); FF.append(Ff); NN.append(N)
            if nstep > 50 * P["h_div"]:
                raise RuntimeError("slip does not arrest")
        slip_rows.append((i0, len(T) - 1))
        Fsp = S.spring(t, x, 0.0)
        arr.append((t, x, Fsp, S.normal(t, x)))
        t_arr = t
        q_arr = q
    return dict(T=np.array(T), X=np.array(X), V=np.array(V), Q=np.array(Q), FF=np.array(FF), NN=np.array(NN),
                brk=brk, arr=arr, slips=slip_rows, S=S)


# ----------------------------------------------------------------------------------------------
# ground-truth measurements
# ----------------------------------------------------------------------------------------------
def measure(sim, P, drive, t0, t1):
    T, V, FF, NN = sim["T"], sim["V"], sim["FF"], sim["NN"]
    brk, arr = sim["brk"], sim["arr"]
    out = {}
    idx = [i for i, b in enumerate(brk) if t0 <= b[0] and i < len(arr) and arr[i][0] <= t1]
    out["n_slips"] = len(idx)
    drops = np.array([brk[i][2] - arr[i][2] for i in idx])
    peaks = np.array([brk[i][2] for i in idx])
    tb = np.array([brk[i][0] for i in idx])
    out["drop_N_median"] = float(np.median(drops)) if len(idx) else 0.0
    if len(idx) > 1:
        out["f_ss"] = float((len(idx) - 1) / (tb[-1] - tb[0]))
    else:
        out["f_ss"] = float("nan")
    # stick times (arrest -> next breakaway)
    st = np.array([brk[i][0] - arr[i - 1][0] for i in idx if i >= 1])
    pk = np.array([brk[i][2] for i in idx if i >= 1])
    okst = st > 1e-6
    out["n_zero_sticks"] = int((~okst).sum())
    st, pk = st[okst], pk[okst]
    out["stick_s_min"] = float(st.min()) if len(st) else 0.0
    out["stick_s_max"] = float(st.max()) if len(st) else 0.0
    out["stick_ratio"] = float(st.max() / st.min()) if len(st) else 0.0
    md = float(np.median(drops)) if len(drops) else 1.0
    out["peak_sd_over_drop"] = float(np.std(peaks) / md) if len(peaks) else 0.0
    # peak growth with ln(stick time): slope * ln(ratio), over the drop
    if len(st) > 3 and st.max() / st.min() > 1.3:
        A = np.vstack([np.log(st), np.ones_like(st)]).T
        sl = np.linalg.lstsq(A, pk, rcond=None)[0][0]
        out["ageing_growth_over_drop"] = float(sl * math.log(st.max() / st.min()) / md)
    else:
        out["ageing_growth_over_drop"] = 0.0
    # twin: decelerating minus accelerating friction (true contact friction vs true speed)
    for on_mu in (False, True):
        tw = []
        vmax_l = []
        for i in idx:
            i0, i1 = sim["slips"][i]
            u = np.abs(V[i0:i1 + 1])
            f = np.abs(FF[i0:i1 + 1])
            if on_mu:
                f = f / NN[i0:i1 + 1] * P["N0"]
            if len(u) < 8:
                continue
            j = int(np.argmax(u))
            vmax = u[j]
            vmax_l.append(vmax)
            ua, fa = np.maximum.accumulate(u[:j + 1]), f[:j + 1]
            ud, fd = np.maximum.accumulate(u[j:][::-1]), f[j:][::-1]
            grid = np.linspace(0.1, 0.9, 41) * vmax
            dd = np.interp(grid, ud, fd) - np.interp(grid, ua, fa)
            tw.append(float(np.mean(dd)) / (brk[i][2] - arr[i][2]))
        out["twin_mu_over_drop" if on_mu else "twin_over_drop"] = float(np.median(tw)) if tw else 0.0
    out["v_slip_max_mm_s"] = float(np.median(vmax_l) * 1e3) if vmax_l else 0.0
    sel = (T >= t0) & (T <= t1)
    n = NN[sel]
    out["load_pp_over_N0"] = float((n.max() - n.min()) / P["N0"]) if n.size else 0.0
    # spring force range over the record (all samples: stick endpoints included)
    out["slip_len_mm_median"] = float(np.median([arr[i][1] - brk[i][1] for i in idx]) * 1e3) if idx else 0.0
    return out


# ----------------------------------------------------------------------------------------------
# parameter draw
# ----------------------------------------------------------------------------------------------
def _rng(case, seed, nuisance, salt=""):
    h = zlib.crc32(f"{NAME}|{case}|{seed}|{nuisance}|{salt}".encode())
    return np.random.default_rng(h)


def _loguni(rng, a, b):
    return float(math.exp(rng.uniform(math.log(a), math.log(b))))


def draw_rig(case, seed, nuisance, rng):
    P = {}
    coarse = nuisance == "coarse"
    trig = case == "triggering"
    if coarse:
        fps = 60.0 if trig else float(rng.choice([30.0, 60.0]))
        fn = fps / rng.uniform(10.5, 14.5)
    else:
        fn = _loguni(rng, 3.0, 7.5) if trig else _loguni(rng, 1.3, 7.5)
        ok = [f for f in (30.0, 60.0, 120.0, 240.0) if 14.0 <= f / fn <= 100.0]
        fps = float(rng.choice(ok))
    P["fps_nominal"] = fps
    P["fn"] = fn
    m = _loguni(rng, 0.05, 0.8)
    P["m_block_kg"] = m
    P["m"] = m  # moving mass (block + hook)
    w0 = 2 * math.pi * fn
    P["k"] = m * w0 * w0
    P["zeta_spring"] = rng.uniform(0.003, 0.015)
    P["c"] = 2 * P["zeta_spring"] * m * w0
    P["N0"] = m * G
    # slip length target (mm) and the static-kinetic gap that gives it
    slip_mm = _loguni(rng, 2.5, 14.0)
    dmu = slip_mm * 1e-3 * w0 * w0 / (2 * G)
    dmu = min(max(dmu, 0.06), 0.30)
    if trig:
        # a large static-kinetic gap (drop comparable with the static level), so that the load ramp per
        # shaker period exceeds the shaker's modulation of the static limit and the breakaways do not all
        # lock to the shaker's troughs
        dmu = rng.uniform(0.2, 0.3)
    slip_mm = dmu * 2 * G / (w0 * w0) * 1e3
    frac_S = rng.uniform(0.3, 0.5)
    S = frac_S * dmu
    D = (dmu - S) / 0.75
    P["mu_c"] = rng.uniform(0.12, 0.2) if trig else rng.uniform(0.2, 0.38)
    P["D"] = D
    P["mu_s0"] = P["mu_c"] + D + S
    vpk = w0 * slip_mm * 1e-3 / 2.0  # m/s, rough peak slip speed
    P["v_s"] = rng.uniform(0.02, 0.08) * vpk
    P["w"] = rng.uniform(0.8, 1.5)
    P["v_t"] = vpk
    P["E"] = rng.uniform(0.08, 0.2) * D / (math.sqrt(2.0) - 1.0)
    P["h_div"] = 200
    P["slip_est_mm"] = slip_mm
    P["v_peak_est_mm_s"] = vpk * 1e3
    return P


def choose_v0(P, rng, r_lo, r_hi, cap=0.15):
    Tn = 1.0 / P["fn"]
    r = rng.uniform(r_lo, r_hi)
    Tst = max(r * Tn - 0.6 * Tn, 0.8 * Tn)
    v0 = P["slip_est_mm"] / Tst  # mm/s
    v0 = min(max(v0, 1.0), 50.0)
    v0 = min(v0, cap * P["v_peak_est_mm_s"])
    return max(v0, 0.8)


# ----------------------------------------------------------------------------------------------
# building and running one experiment
# ----------------------------------------------------------------------------------------------
def _drive_for(case, seed, P, rng, v0, stepped_factor=None, holds=False):
    Tn = 1.0 / P["fn"]
    Tst = P["slip_est_mm"] / v0
    tsw = [0.0]
    vs = [v0 * 1e-3]
    info = {"kind": "constant", "v0_mm_s": v0}
    if stepped_factor is not None:
        t = 0.0
        levels = [v0, v0 / stepped_factor]
        i = int(rng.integers(0, 2))
        tsw, vs = [], []
        while t < 5000 * Tn + 200:
            lv = levels[i % 2]
            tsw.append(t)
            vs.append(lv * 1e-3)
            nc = rng.uniform(3.0, 5.0)
            t += nc * (P["slip_est_mm"] / lv + 0.6 * Tn)
            i += 1
            if len(tsw) > 400:
                break
        info = {"kind": "stepped", "levels_mm_s": levels, "factor": stepped_factor}
    elif holds:
        t = 0.0
        tsw, vs = [], []
        hold_l = []
        while len(tsw) < 400:
            tsw.append(t)
            vs.append(v0 * 1e-3)
            nc = rng.uniform(2.5, 4.5)
            t += nc * (Tst + 0.6 * Tn)
            hd = rng.uniform(2.0, 6.0) * Tst
            tsw.append(t)
            vs.append(0.0)
            hold_l.append(hd)
            t += hd
        info = {"kind": "holds", "v0_mm_s": v0, "hold_s_range": [float(min(hold_l)), float(max(hold_l))]}
    return tsw, vs, info


def run_experiment(case, seed, nuisance):
    rng = _rng(case, seed, nuisance)
    P = draw_rig(case, seed, nuisance, rng)
    Tn = 1.0 / P["fn"]
    stepped = None
    holds = False
    if case == "static_ageing":
        if seed % 2 == 0:
            stepped = rng.uniform(4.0, 8.0)
        else:
            holds = True
        v0 = choose_v0(P, rng, 2.5, 5.0)
    elif case == "none" and seed % 8 in (2, 5):
        stepped = rng.uniform(2.0, 4.0)
        v0 = choose_v0(P, rng, 2.5, 6.0)
    elif case == "triggering":
        # a fast drive (few shaker periods per cycle), else the breakaways lock to the shaker's troughs
        v0 = choose_v0(P, rng, 1.5, 2.0, cap=0.35)
    else:
        v0 = choose_v0(P, rng, 3.0, 11.0)
    P["v0_mm_s"] = v0
    n_target = int(rng.integers(16, 35))
    if stepped or holds:
        n_target = int(rng.integers(20, 37))
    tsw, vs, dinfo = _drive_for(case, seed, P, rng, v0, stepped, holds)
    P["drive"] = dinfo
    Tst = P["slip_est_mm"] / v0
    t_max_est = (n_target + 6) * (Tst + Tn) * (8.0 if stepped or holds else 2.0) + 50 * Tn
    travel_est = v0 * 1e-3 * (n_target + 3) * (Tst + Tn)

    # departures
    if case == "load_variation":
        if seed % 2 == 0:
            # a magnet under the board (the block carries a steel washer): a Lorentzian bump in x
            pp = rng.uniform(0.13, 0.27)
            x_m = rng.uniform(0.3, 0.9) * travel_est
            w_m = rng.uniform(0.25, 0.5) * travel_est
            # p-p over x in [0, travel] for A: compute numerically
            xs = np.linspace(0, travel_est, 400)
            shape = 1.0 / (1.0 + ((xs - x_m) / w_m) ** 2)
            A = pp / max(shape.max() - shape.min(), 1e-3)
            A = min(A, 0.6)
            P["load"] = {"kind": "magnet", "x_m": x_m, "w_m": w_m, "A": A, "norm": 1.0}
            P["load_mechanism"] = "magnet under the board (pull grows as the block nears it)"
        else:
            c = rng.uniform(0.12, 0.28) * (1 if rng.random() < 0.5 else -1)
            P["load"] = {"kind": "wedge", "c": c, "x_mid": 0.5 * travel_est, "span": travel_est}
            P["load_mechanism"] = ("a roller on a leaf spring pressing on the block rides on a wedge-shaped "
                                   "guide: N = N0 (1 + c (x - x_mid)/span)")
    if case == "triggering":
        P["eps"] = rng.uniform(0.03, 0.06)
        ftmax = min(5.0, 0.42 * P["fps_nominal"] / P["fn"])
        P["f_t"] = rng.uniform(3.0, ftmax) * P["fn"]
        P["phi_t"] = rng.uniform(0, 2 * math.pi)
        P["trigger_mechanism"] = "small unbalanced motor (pager motor) glued to the block"
    if case == "twin_branch":
        P["P_q"] = rng.uniform(0.5, 1.2) * P["mu_c"] * P["N0"] * P["slip_est_mm"] * 1e-3 / (0.6 * Tn)
        P["tau_r"] = rng.uniform(0.3, 0.7) * Tst
        P["g_twin"] = 0.3
        P["twin_mechanism"] = ("frictional heating dries the adsorbed water film of the wood contact (dry "
                               "fraction q driven by the frictional power, re-adsorbed in stick)")
    if case == "static_ageing":
        P["tau_a"] = rng.uniform(0.3, 1.0) * Tst
        P["beta"] = 0.04
        P["t_age0"] = 5.0 * Tst
    if case == "drive_modulation":
        P["mod_a"] = rng.uniform(0.2, 0.45)
        P["mod_phi"] = rng.uniform(0, 2 * math.pi)
        P["mod_fm_over_fss_target"] = rng.uniform(0.12, 0.38)

    def make_drive():
        if case == "drive_modulation" and P["mod_fm"] > 0:
            return Drive([0.0], [v0 * 1e-3], P["mod_a"], P["mod_fm"], P["mod_phi"])
        return Drive(tsw, vs)

    def run(nsl):
        d = make_drive()
        sim = simulate(P, d, nsl, t_max_est * 3)
        return d, sim

    def window(sim):
        brk, arr = sim["brk"], sim["arr"]
        # record starts during the stick after the first slip, ends in the stick after slip n_target+1
        ta = arr[0][0] + rng_w.uniform(0.15, 0.6) * (brk[1][0] - arr[0][0])
        j = min(n_target + 1, len(arr) - 1)
        if j + 1 < len(brk):
            tb = arr[j][0] + rng_w.uniform(0.3, 0.8) * (brk[j + 1][0] - arr[j][0])
        else:
            tb = arr[j][0] + 0.3 * Tn
        return ta, tb

    # pilots / calibrations
    if case == "drive_modulation":
        P["mod_fm"] = 0.0
        d, sim = run(8)
        b = [x[0] for x in sim["brk"]][2:]
        fss0 = (len(b) - 1) / (b[-1] - b[0])
        P["mod_fm"] = P["mod_fm_over_fss_target"] * fss0
    if case == "twin_branch":
        d, sim = run(10)
        mm = measure(sim, P, d, sim["arr"][1][0], sim["T"][-1])
        target = rng.uniform(0.115, 0.185)
        tw = max(mm["twin_over_drop"], 1e-3)
        for _ in range(3):
            P["g_twin"] = P["g_twin"] * target / tw
            d, sim = run(10)
            mm = measure(sim, P, d, sim["arr"][1][0], sim["T"][-1])
            tw = max(mm["twin_over_drop"], 1e-3)
            if abs(tw - target) < 0.02:
                break
        P["twin_target"] = target
    if case == "static_ageing":
        d, sim = run(n_target + 3)
        mm = measure(sim, P, d, sim["arr"][1][0], sim["T"][-1])
        target = rng.uniform(0.12, 0.25)
        gr = max(mm["ageing_growth_over_drop"], 1e-3)
        for _ in range(3):
            P["beta"] = P["beta"] * target / gr
            d, sim = run(n_target + 3)
            mm = measure(sim, P, d, sim["arr"][1][0], sim["T"][-1])
            gr = max(mm["ageing_growth_over_drop"], 1e-3)
            if abs(gr - target) < 0.025:
                break
        P["ageing_target"] = target

    rng_w = _rng(case, seed, nuisance, "window")
    d, sim = run(n_target + 3)
    t0, t1 = window(sim)
    meas = measure(sim, P, d, t0, t1)
    if case == "triggering":
        # the breakaways lock to the shaker's troughs: scan f_t (within 3-7 fn and below 0.42 fps) until
        # the record's f_t / f_ss is at least 0.17 from an integer
        lo, hi = 3.0 * P["fn"], min(5.5, 0.42 * P["fps_nominal"] / P["fn"]) * P["fn"]
        best = None
        tried = 0
        fr0 = P["f_t"]
        while tried < 48:
            r = P["f_t"] / meas["f_ss"]
            dist = abs(r - round(r))
            if best is None or dist > best[0]:
                best = (dist, P["f_t"], d, sim, t0, t1, meas, P["eps"])
            if dist >= 0.17:
                break
            tried += 1
            if tried % 16 == 0:
                P["eps"] = max(0.03, 0.8 * P["eps"])
            P["f_t"] = float(lo + (hi - lo) * (((fr0 - lo) / (hi - lo) + 0.618034 * tried) % 1.0))
            rng_w = _rng(case, seed, nuisance, "window")
            d, sim = run(n_target + 3)
            t0, t1 = window(sim)
            meas = measure(sim, P, d, t0, t1)
        dist, P["f_t"], d, sim, t0, t1, meas, P["eps"] = best
        P["f_t_tries"] = tried
        meas["ft_over_fss"] = P["f_t"] / meas["f_ss"]
        meas["ft_over_fn"] = P["f_t"] / P["fn"]
    if case == "drive_modulation":
        meas["fm_over_fss"] = P["mod_fm"] / meas["f_ss"]
    return P, d, sim, t0, t1, meas


# ----------------------------------------------------------------------------------------------
# sensor chain
# ----------------------------------------------------------------------------------------------
def _nice_step(x):
    e = 10 ** math.floor(math.log10(x))
    for f in (1, 2, 2.5, 5, 10):
        if f * e >= x * 0.8:
            return f * e
    return 10 * e


def video_tracks(P, d, sim, t0, t1, rng, nuisance, meas):
    """Frames: true capture times, block and puller positions (px, image coordinates)."""
    spl = CubicHermiteSpline(sim["T"], sim["X"], sim["V"])
    fps = P["fps_nominal"]
    ntsc = fps in (30.0, 60.0) and rng.random() < 0.4
    fps_decl = fps * 1000.0 / 1001.0 if ntsc else fps
    fps_true = fps_decl * (1.0 + rng.normal(0, 3e-4))
    n = int((t1 - t0) * fps_true)
    i = np.arange(n)
    jit = rng.uniform(0.05, 0.8) * 1e-3
    t_cap = t0 + i / fps_true + rng.normal(0, jit, n)
    t_cap = np.maximum.accumulate(t_cap)
    # rolling shutter: each marker is read at its row's time
    line_t = rng.uniform(0.3, 0.9) / fps
    rs_b, rs_p = rng.uniform(0.3, 0.7) * line_t, rng.uniform(0.3, 0.7) * line_t
    slip_mm = max(meas["slip_len_mm_median"], 0.5)
    pix_frac = rng.uniform(0.015, 0.03) if nuisance == "quantisation" else rng.uniform(0.003, 0.01)
    L0 = rng.uniform(60.0, 180.0)  # mm between the two markers with the spring slack
    xb = spl(t_cap + rs_b) * 1e3  # mm
    xp = d.pos_arr(t_cap + rs_p) * 1e3 + L0
    width = float(rng.choice([1280.0, 1920.0, 3840.0]))
    span = max(xp.max(), xb.max()) - min(xp.min(), xb.min()) + 40.0  # both markers must stay in frame
    pixel = min(max(slip_mm * pix_frac, 0.05, span / (width - 60.0)), 0.5)  # mm per px
    dirn = 1.0 if rng.random() < 0.7 else -1.0
    Xc = 30.0 if dirn > 0 else width - 30.0
    Xc -= dirn * min(xp.min(), xb.min()) / pixel
    Xb = Xc + dirn * xb / pixel
    Xp = Xc + dirn * xp / pixel
    sj = rng.uniform(0.12, 0.35)
    Xb = Xb + rng.normal(0, sj, n)
    Xp = Xp + rng.normal(0, sj * rng.uniform(0.8, 1.5), n)
    info = {"fps_declared": fps_decl, "fps_true": fps_true, "timing_jitter_ms": jit * 1e3,
            "rolling_shutter_ms": [rs_b * 1e3, rs_p * 1e3], "pixel_mm": pixel, "L0_mm": L0,
            "direction": dirn, "subpixel_jitter_px": sj, "pixel_over_drop": pixel / slip_mm,
            "frame_width_px": width}
    drop_px = slip_mm / pixel
    if nuisance == "hum":
        mains = 50.0 if rng.random() < 0.5 else 60.0
        amp = rng.uniform(0.015, 0.045) * drop_px
        ph = rng.uniform(0, 2 * math.pi)
        fl = np.sin(2 * math.pi * 2 * mains * t_cap + ph)
        Xb = Xb + amp * fl
        Xp = Xp + amp * rng.uniform(0.4, 1.0) * fl
        fa = abs(2 * mains - round(2 * mains / fps_true) * fps_true)
        info.update(hum="lighting flicker", flicker_hz=2 * mains, flicker_amp_px=amp, aliased_hz=fa,
                    flicker_over_drop=amp / drop_px)
    if nuisance == "drift":
        T = t_cap[-1] - t_cap[0]
        s = (t_cap - t_cap[0]) / T
        creep = rng.uniform(0.04, 0.12) * drop_px * (1 if rng.random() < 0.5 else -1)
        prof = s * s * (3 - 2 * s) if rng.random() < 0.5 else s
        zoom = rng.uniform(0.001, 0.004) * (1 if rng.random() < 0.5 else -1)
        Xb = Xb + creep * prof
        Xp = Xp + creep * prof
        Xb = 640 + (Xb - 640) * (1 + zoom * s)
        Xp = 640 + (Xp - 640) * (1 + zoom * s)
        info.update(drift_camera_creep_px=creep, drift_scale=zoom, drift_over_drop=abs(creep) / drop_px)
    Xb = np.round(Xb)
    Xp = np.round(Xp)
    # mis-tracked frames
    n_sp = 0
    if nuisance == "spikes":
        frac = rng.uniform(0.001, 0.005)
        n_sp = max(3, int(frac * n))
        for arr_ in (Xb, Xp):
            pos = rng.choice(np.arange(5, n - 5), size=n_sp // 2 + 1, replace=False)
            for p in pos:
                jump = rng.uniform(0.15, 0.6) * drop_px * (1 if rng.random() < 0.5 else -1)
                ln = 1 if rng.random() < 0.7 else 2
                arr_[p:p + ln] += np.round(jump)
        info["spike_frames"] = int(n_sp)
    # duplicated frames (encoder repeats a frame) and dropped frames
    keep = np.ones(n, bool)
    ndup = int(rng.integers(0, 4))
    for p in rng.choice(np.arange(2, n - 2), size=ndup, replace=False):
        Xb[p] = Xb[p - 1]
        Xp[p] = Xp[p - 1]
    ndrop = int(rng.integers(0, 4))
    for p in rng.choice(np.arange(2, n - 2), size=ndrop, replace=False):
        keep[p] = False
    info.update(duplicated_frames=ndup, dropped_frames=ndrop)
    return dict(frame=i, t_nom=i / fps_decl, t_cap=t_cap, Xb=Xb, Xp=Xp, keep=keep, Xc=Xc), info


def force_channel(P, d, sim, t0, t1, rng, nuisance, meas):
    """A force sensor in series with the spring at the pulled end (logger), and a rotary encoder on the winch."""
    spl = CubicHermiteSpline(sim["T"], sim["X"], sim["V"])
    fn = P["fn"]
    if nuisance == "coarse":
        fs = round(fn * rng.uniform(10.5, 14.5), 1)
    else:
        ok = [f for f in (20.0, 25.0, 50.0, 100.0, 200.0, 250.0, 500.0) if 20 <= f / fn <= 100]
        fs = float(rng.choice(ok)) if ok else round(fn * 40)
    n = int((t1 - t0) * fs)
    t = t0 + np.arange(n) / fs
    x = spl(t)
    v = spl(t, 1)
    F = P["k"] * (d.pos_arr(t) - x) + P["c"] * (d.vel_arr(t) - v)
    drop = meas["drop_N_median"]
    # strain-gauge sensor: first-order response (bandwidth 15-40 fn), noise, ADC
    tau = 1.0 / (2 * math.pi * fn * rng.uniform(15, 40))
    a = math.exp(-1.0 / (fs * tau))
    Fy = lfilter([1 - a], [1.0, -a], F, zi=[a * F[0]])[0]
    Fy += rng.normal(0, rng.uniform(0.003, 0.008) * drop, n)
    info = {"rate_hz": fs, "sensor_tau_ms": tau * 1e3}
    if nuisance == "hum":
        mains = 50.0 if rng.random() < 0.5 else 60.0
        amp = rng.uniform(0.015, 0.045) * drop
        Fy += amp * (np.sin(2 * math.pi * mains * t + rng.uniform(0, 6.3))
                     + 0.3 * np.sin(2 * math.pi * 3 * mains * t + rng.uniform(0, 6.3)))
        info.update(hum_hz=mains, hum_over_drop=amp / drop)
    if nuisance == "drift":
        dr = rng.uniform(0.03, 0.1) * drop * (1 if rng.random() < 0.5 else -1)
        Fy += dr * (t - t0) / (t1 - t0)
        info.update(drift_over_drop=abs(dr) / drop)
    if nuisance == "spikes":
        ns = max(3, int(rng.uniform(0.001, 0.005) * n))
        pos = rng.choice(np.arange(3, n - 3), size=ns, replace=False)
        Fy[pos] += rng.uniform(0.3, 1.0, ns) * drop * np.where(rng.random(ns) < 0.5, 1, -1)
        info["spikes"] = int(ns)
    step = _nice_step(drop * (rng.uniform(0.015, 0.03) if nuisance == "quantisation" else rng.uniform(0.002, 0.006)))
    Fy = np.round(Fy / step) * step
    info["adc_step_N"] = step
    # winch encoder (rotary motion sensor): drive position quantised
    enc = 2 * math.pi * rng.uniform(0.01, 0.02) / 1440.0 * 1e3  # mm per count
    pd = np.round(d.pos_arr(t) * 1e3 / enc) * enc
    info["encoder_mm"] = enc
    return t - t0, Fy, pd, info


# ----------------------------------------------------------------------------------------------
# file writers
# ----------------------------------------------------------------------------------------------
def _fmt_e(x):
    return f"{x:.9E}".replace("E+0", "E").replace("E-0", "E-").replace("E+", "E")


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError(case)
    os.makedirs(outdir, exist_ok=True)
    P, d, sim, t0, t1, meas = run_experiment(case, seed, nuisance)
    rng = _rng(case, seed, nuisance, "sensor")
    needs_drive_col = P["drive"]["kind"] != "constant"
    no_drive_col = case == "drive_modulation"
    # format choice
    if needs_drive_col:
        fmts = ["tracker_multi", "opencv_px", "opencv_mm", "spreadsheet", "force_enc"]
    elif no_drive_col:
        fmts = ["tracker_single", "opencv_px1", "opencv_ext", "phyphox", "force_only"]
    else:
        fmts = ["tracker_multi", "tracker_single", "opencv_px", "opencv_mm", "opencv_ext", "phyphox",
                "spreadsheet", "force_enc", "force_only"]
    fmt = fmts[(seed * 7 + CASES.index(case) * 3 + int(rng.integers(0, 3))) % len(fmts)]
    base = f"{NAME}_{case}_s{seed:02d}_{nuisance}"
    args = []
    fn_true = P["fn"]
    fn_given = fn_true
    if nuisance == "fn_off":
        fn_given = fn_true * (1.05 if rng.random() < 0.5 else 0.95)
    if seed % 8 == 7 and case != "triggering" and nuisance != "fn_off":
        fn_given = None
    if fn_given is not None:
        args += ["--fn", f"{fn_given:.4g}"]
    v0 = P["v0_mm_s"]
    sens = {}
    lines = []
    has_drive = True
    if fmt.startswith("force"):
        t, F, pd, sens = force_channel(P, d, sim, t0, t1, rng, nuisance, meas)
        logger = rng.random() < 0.5
        pre = "Latest: " if logger else ""
        if fmt == "force_enc":
            path = os.path.join(outdir, base + ".csv")
            lines.append(f'"{pre}Time (s)","{pre}Force (N)","{pre}Position (m)"')
            for a, b, c in zip(t, F, pd):
                lines.append(f"{a:.4f},{b:.4f},{c * 1e-3:.6f}")
        else:
            has_drive = False
            path = os.path.join(outdir, base + ".csv")
            lines.append(f'"{pre}Time (s)","{pre}Force (N)"')
            for a, b in zip(t, F):
                lines.append(f"{a:.4f},{b:.4f}")
        kstr = f"{P['k']:.4g}" if rng.random() < 0.6 else f"{P['k'] * 1e-3:.4g} N/mm"
        args += ["--stiffness", kstr]
        sens["chain"] = "strain-gauge force sensor (first-order, noise, ADC) + winch rotary encoder"
    else:
        tr, sens = video_tracks(P, d, sim, t0, t1, rng, nuisance, meas)
        sens["chain"] = ("video: frame timing jitter, rolling shutter, sub-pixel jitter, 1 px quantisation, "
                         "duplicated/dropped frames")
        keep = tr["keep"]
        fr, tn, tc, Xb, Xp = tr["frame"][keep], tr["t_nom"][keep], tr["t_cap"][keep], tr["Xb"][keep], tr["Xp"][keep]
        tc = tc - tc[0] + tn[0] * 0  # container timestamps start near 0
        pixel = sens["pixel_mm"]
        cal = pixel * (1 + rng.normal(0, 0.004))  # calibration-stick error
        org = tr["Xc"] - rng.uniform(20, 120) * sens["direction"]
        ax = sens["direction"] if rng.random() < 0.8 else -sens["direction"]  # Tracker axes may point either way
        if fmt in ("tracker_multi", "tracker_single"):
            unit = "m" if rng.random() < 0.5 else "cm"
            sc = 1e-3 if unit == "m" else 1e-1
            xa = (Xb - org) * ax * cal * sc
            xbb = (Xp - org) * ax * cal * sc
            with_y = rng.random() < 0.5
            yb = (rng.uniform(200, 300) + rng.normal(0, 0.3, len(Xb))).round() * cal * sc
            yp = (rng.uniform(200, 300) + rng.normal(0, 0.3, len(Xb))).round() * cal * sc
            efmt = rng.random() < 0.5
            f = _fmt_e if efmt else (lambda z: f"{z:.6g}")
            path = os.path.join(outdir, base + ".txt")
            sens["units"] = unit
            if fmt == "tracker_multi":
                lines.append("#multi:")
                if with_y:
                    lines.append("\tmass A\t\tmass B\t")
                    lines.append("t\tx\ty\tx\ty")
                else:
                    lines.append("\tmass A\tmass B")
                    lines.append("t\tx\tx")
                for j in range(len(tn)):
                    row = [f(tn[j]), f(xa[j])] + ([f(yb[j])] if with_y else []) + [f(xbb[j])] + \
                          ([f(yp[j])] if with_y else [])
                    lines.append("\t".join(row))
            else:
                has_drive = False
                lines.append("mass A")
                lines.append("t\tx\ty" if with_y else "t\tx")
                for j in range(len(tn)):
                    lines.append("\t".join([f(tn[j]), f(xa[j])] + ([f(yb[j])] if with_y else [])))
        elif fmt in ("opencv_px", "opencv_px1", "opencv_mm", "opencv_ext"):
            path = os.path.join(outdir, base + ".csv")
            vid = f"IMG_{int(rng.integers(1000, 9999))}.MOV"
            lines.append(f"# track_blocks.py (OpenCV {rng.choice(['CSRT', 'KCF', 'template matching'])} tracker)")
            lines.append(f"# video: {vid}  {int(round(P['fps_nominal']))} fps  "
                         f"{rng.choice(['1280x720', '1920x1080'])}")
            lines.append(f"# scale: {cal:.4f} mm/px (from a 100 mm ruler in frame)")
            tt = np.round(tc, 4)
            # repeated container timestamps: a frame decoded twice (whole row repeated)
            rep = set()
            if rng.random() < 0.35:
                rep = set(int(p) for p in rng.choice(np.arange(3, len(tt) - 3), size=int(rng.integers(2, 6)),
                                                     replace=False))
                sens["repeated_rows"] = len(rep)
            xa = (Xb - org) * ax
            xbb = (Xp - org) * ax
            if fmt in ("opencv_px", "opencv_px1"):  # raw image columns (pixels from the left edge)
                xa, xbb = Xb, Xp
            lines[1] = lines[1].rsplit("  ", 1)[0] + f"  {int(sens['frame_width_px'])}x" + \
                {1280: "720", 1920: "1080", 3840: "2160"}[int(sens["frame_width_px"])]
            if fmt == "opencv_px":
                lines.append("frame,time_s,block_x_px,puller_x_px")
                rows = [f"{fr[j]},{tt[j]:.4f},{xa[j]:.0f},{xbb[j]:.0f}" for j in range(len(tt))]
            elif fmt == "opencv_px1":
                has_drive = False
                lines.append("frame,time_s,block_x_px")
                rows = [f"{fr[j]},{tt[j]:.4f},{xa[j]:.0f}" for j in range(len(tt))]
            elif fmt == "opencv_mm":
                lines.append("frame,time_s,block_x_mm,puller_x_mm")
                rows = [f"{fr[j]},{tt[j]:.4f},{xa[j] * cal:.3f},{xbb[j] * cal:.3f}" for j in range(len(tt))]
            else:
                has_drive = False
                # extension: marker distance minus the slack length measured on the first frames of a
                # reference clip (a small error)
                Lr = sens["L0_mm"] + rng.normal(0, 0.02) * meas["slip_len_mm_median"]
                ext = (Xp - Xb) * sens["direction"] * cal - Lr
                lines[-1] = lines[-1]  # keep the scale line
                lines.append("frame,time_s,spring_extension_mm")
                rows = [f"{fr[j]},{tt[j]:.4f},{ext[j]:.3f}" for j in range(len(tt))]
            out = []
            for j, r in enumerate(rows):
                out.append(r)
                if j in rep:
                    out.append(r)
            lines += out
        elif fmt == "phyphox":
            has_drive = False
            path = os.path.join(outdir, base + ".csv")
            lines.append('"Time (s)","Position (m)"')
            xa = (Xb - org) * ax * cal * 1e-3
            for j in range(len(tn)):
                lines.append(f"{tc[j]:.9E},{xa[j]:.9E}")
        elif fmt == "spreadsheet":
            path = os.path.join(outdir, base + ".csv")
            unit = "cm" if rng.random() < 0.5 else "mm"
            sc = 0.1 if unit == "cm" else 1.0
            lines.append(f"t (s);block x ({unit});cart x ({unit})")
            xa = (Xb - org) * ax * cal * sc
            xbb = (Xp - org) * ax * cal * sc
            for j in range(len(tn)):
                lines.append(f"{tn[j]:.4f};{xa[j]:.3f};{xbb[j]:.3f}".replace(".", ","))
        else:
            raise RuntimeError(fmt)
    if not has_drive:
        r = rng.random()
        if r < 0.5:
            args += ["--v0", f"{v0:.3g}"]
        elif r < 0.8:
            args += ["--v0", f"{v0:.3g} mm/s"]
        else:
            args += ["--v0", f"{v0 / 10:.3g} cm/s"]
    with open(path, "w", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")
    params = {k: v for k, v in P.items() if k not in ("h_div",)}
    params.update({"format": fmt, "record_t0_s": t0, "record_t1_s": t1, "measured": meas, "sensor": sens,
                   "samples_per_period": (sens.get("fps_true") or sens.get("rate_hz")) / P["fn"]})
    params = json.loads(json.dumps(params, default=float))
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance, "file": os.path.abspath(path),
            "args": args, "fn_true": float(fn_true), "fn_given": None if fn_given is None else float(fn_given),
            "params": params}
