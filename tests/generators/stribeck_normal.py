"""Independent record generator: reciprocating rig, regularised Stribeck friction, coupled normal mode.

Written without reading the diagnosis code; numpy/scipy only.  `write_record(case, seed, outdir, nuisance)`
(see README.md here for the contract); `python stribeck_normal.py OUTDIR [NSEEDS]` writes NSEEDS seeds of every
case (nuisance = NUISANCES[seed % 7]) and OUTDIR/truth.json.

The rig (two degrees of freedom)
--------------------------------
Slider (mass m) held by a spring k through the force sensor, rubbing on a stage moving at s'(t) = vd(t);
relative sliding velocity v = x' - vd.  A normal contact mode z (stiffness kz, mass mz, fz = 3-10 fn, damping
ratio 2-10 %) is forced by the friction force through a contact angle / lever gamma (|gamma| = 0.004-0.010):

    m x'' + c x' + k x = -F(v, N, Ns)                        (recorded force: k x, through the sensor)
    mz z'' + cz z' + kz z = -gamma F
    N  = N0 g(t) + kz z + c_geo N0 (x - x_ref)               (g = 1 + a sin(2 pi f_tr t + phi) if triggering)
    tau_s Ns' = N - Ns                                       (junction load, tau_s = 0.6-1.2 Tn)

Friction: a regularised Stribeck law with a viscous term, no stick/slip switching (stick is the stiff region
of the tanh, eps = 0.004 x the slowest drive speed: the creep stays ~1 % of the drive speed until breakaway):

    F = [ N mu_c + (Ns mu_s - N mu_c) exp(-(v/vs)^2) + N d_tw w ] tanh(v/eps) + sigma_v v

i.e. N [mu_c + (mu_s - mu_c) exp(-(v/vs)^2)] tanh(v/eps) + sigma_v v when N is steady; the static excess
follows the normal load with the junction lag tau_s (without it a 3-8 % normal vibration entrains the
stick-slip, the slip starting in a trough of N, and f_tr sits exactly on a multiple of the stick-slip
frequency).  Ranges: fn 2-200 Hz log-uniform; N0 0.003-30 N; mu_s 0.2-0.6; mu_c = (0.55-0.8) mu_s;
k = (mu_s - mu_c) N0 / A_d with A_d 3-200 um; damping ratio 0.5-3 %; vs = (0.06-0.25) wn A_d (0.1-0.25 for
static_ageing); sigma_v wn A_d = (2-6 %) (mu_s - mu_c) N0; drive speed for 2.5-10 natural periods of stick and
v0 <= 0.8 vs (steady sliding unstable).  A short pilot run at the nominal and at the slowest drive speed must
show full stick-slip (drop > the (mu_s-mu_c) N0 scale, slip speed > 3 drive speeds) or the draw is repeated.

Integrator (own, fixed step Tn/64 .. Tn/96, Tn/6 inside long dwells): trapezoidal rule for spring and damper,
backward Euler for the friction force, whose scalar equation in the end-of-step sliding velocity is solved by
bracketed Newton (monotone for these steps); exact zero-order-hold discretisation of the normal mode; backward
Euler for the linear relaxations of Ns, w and theta.  The recorded force is interpolated with cubic Hermite
splines (x, x') onto a 4x oversampled acquisition grid.

Drives: on about half the seeds of none / load_variation / twin_branch / triggering / static_ageing a
reciprocating stage (trapezoidal position wave, 4-12 strokes of equal length, each long enough for 4-8
stick-slip cycles, dwells 0.2-1 s, short acceleration ramps), recorded as a stage position column; otherwise a
one-direction drive at constant speed (--v0, or a v0 / position column); some `none` seeds step between 2-4
recorded speed levels (factor 2-3).

Cases
-----
none            : as above.  The weak lever gives N pp < 2 % of N0 (checked; gamma is scaled down otherwise).
load_variation  : geometric coupling c_geo (contact angle) calibrated to N pp 14-34 % of N0 (re-run once if the
                  measured pp leaves 11-38 %); one-direction records start after the first slip (c_geo is set up
                  around the steady operating point); normal channel always recorded.
twin_branch     : w = smoothed indicator (sliding and |v| decreasing): tau_w w' = ind - w, tau_w = Tn/40,
                  ind = (1 - exp(-(v/v_on)^2)) (1 + tanh(-sign(v) v'/a_sc))/2; d_tw calibrated on short runs to
                  12-22 % of the slip's force drop (measured: friction on the decelerating half minus the
                  accelerating half at equal speed, 25-85 % of the slip's peak speed, over the drop).
static_ageing   : mu_s -> mu_s (1 + beta ln(1 + theta/tau_age)), stick clock theta' = S - theta (1 - S)/tau_r,
                  S = exp(-(v/v_stick)^2) (grows in stick, resets within Tn/30 in slip); 4-6 speed levels over a
                  factor 4-8, either strokes of a reciprocating stage (the first stick of a stroke also includes
                  the dwell) or one-direction steps (1/3 with a hold); beta calibrated on the record to a peak
                  growth of 8-16 % (fit of peak force on ln(1 + t_stick/tau_age) over the record's slips).
triggering      : N0 (1 + a sin(2 pi f_tr t + phi)), a 3-8 %; f_tr drawn in 2.5-8 fn (capped so f_tr/f_ss <= 30),
                  moved to a half-integer multiple of the stick-slip frequency, checked on short runs and on the
                  record (re-run up to twice); normal channel always recorded.
drive_modulation: one direction, v0n (1 + a sin(2 pi fm t + phi)), a 20-45 %, fm = 0.15-0.4 f_ss (checked on the
                  record), 3-5+ modulation periods; only --v0 = v0n, no drive column.

Records
-------
Force records (time first, other columns permuted; friction/normal in N, mN or uN; position in mm or um; v0 in
mm/s; TAB, whitespace, semicolon or comma) with --stiffness on ~3/4 of them; ~30 % of the one-direction records
without a position column are displacement records `t [s],x [mm][,y [mm]][,v0 [mm/s]]` (x = F/k, y affine in
N).  --fn on ~60 % of the seeds (always, x0.95 or x1.05, with fn_off).  20-100 samples per natural period (10-15
with `coarse`; lowered towards 20 only to keep a file under ~150k rows); on ~30 % of the seeds jittered sample
times (sd 2-12 % of dt) and on ~30 % a few dropped samples (gaps of 2-3 intervals).  Sensor: either a resonance
(6-20 fn, at most 0.3 x the sampling rate, damping 0.08-0.3) or a 2nd-order low-pass at 0.15-0.35 x the sampling
rate; normal channel: 1st-order low-pass.  White noise 0.2-1 % of the drop (normal: 0.1-0.4 % of N0).
Nuisances: hum 50/60 Hz + 2 harmonics, 1-5 % of the drop (also, smaller, on the normal channel); drift 2-6 % of
the drop over the record (linear + bow); spikes on 0.05-0.5 % of the samples (0.3-1.5 drops); quantisation
step 0.2-1 % of the drop (normal 0.1-0.4 % of N0); coarse; fn_off.

Measured (noise-free simulated signals of the produced record; params["measured"]), seeds 0-7 of every case
with nuisance NUISANCES[seed % 7]; in brackets the range over seeds 0-23:
  all cases     : 15-73 slips per record [15-78]; stick 82-97 % of the driven time; slip peak speed 10-34 drive
                  speeds [9-54]; stick-slip period 3.1-18 Tn [3.1-22]; >= 4 cycles in every stroke (4-10).
  none          : N pp 0.28-0.66 % of N0 [0.19-1.03 %]; memory: twin measure -0.03..+0.13 % of the drop
                  [-0.03..+0.14 %], peak growth over the stick-time range -0.05..+0.04 % [-1.5..+0.1 %, the
                  larger ones on speed-step seeds: rate dependence of the breakaway].
  load_variation: N pp 15.6-29.2 % of N mean [15.6-33.6 %]; the twin measure on the force is -17..+36 % of the
                  drop (the load differs between the two halves of a slip) but -1.5..+1.1 % [-1.5..+1.6 %] on F/N
                  (the junction lag tau_s is the only memory).
  twin_branch   : 12.2-20.5 % of the drop [12.0-20.5 %]; per slip spread < 0.3 %.
  static_ageing : peak growth 7.3-13.7 % [7.3-17.9 %]; mu_s(theta) growth by the law 7.0-13.9 % [7.0-24.5 %].
  triggering    : amplitude 3.6-7.5 % of N [3.2-7.5 %]; f_tr 2.6-5.4 fn [2.5-5.4]; f_tr/f_ss 14.5-29.6;
                  distance of f_tr/f_ss to the nearest integer 0.28-0.50 [0.21-0.50].
  drive_modulation: a 27-44 % [22-45 %]; fm/f_ss 0.16-0.40; 4.3-7.3 modulation periods.
Time per record (incl. pilots, re-runs and writing): 0.07-0.9 s for seeds 0-7 and at most 1.2 s over 144 records
on a quiet machine; 0.2-2.4 s and at most 3.2 s on the shared 2-core machine at load ~3.

Not met / caveats: f_tr reaches only 2.5-5.4 fn in practice (the cap f_tr/f_ss <= 30, needed for "off a
multiple" to mean anything, binds since f_ss = fn/3..fn/10); the static part of friction follows the normal
load with a lag tau_s (needed against entrainment), a small memory effect in load_variation; `none` uses speed
steps on few seeds (3 of 24).  _LAST holds the last run's grid, states and slip events, for inspection.
"""

import json
import math
import os
import sys
import time
import zlib

import numpy as np
from scipy import signal
from scipy.interpolate import CubicHermiteSpline
from scipy.linalg import expm

NAME = "stribeck_normal"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

TWOPI = 2.0 * math.pi
_LAST = {}  # the last simulation (grid, states, slip events), for inspection


def _rng(*keys):
    s = "|".join(str(k) for k in (NAME,) + keys)
    return np.random.default_rng([zlib.crc32(s.encode()), len(s)])


def _logu(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# ----------------------------------------------------------------------------------------------------------------
# the rig: integrator
# ----------------------------------------------------------------------------------------------------------------

def _simulate(P, H, VD, NM=None, twin=False, ageing=False):
    """Fixed-step semi-implicit integration of the two-degree-of-freedom rig.

    H: list of step lengths; VD: stage velocity at the len(H)+1 grid points; NM: factor on N0 (triggering).
    Tangential: trapezoidal rule for spring and damper, backward Euler for the friction force, whose
    scalar equation in the relative velocity at the end of the step is solved by bracketed Newton (it is
    strictly monotone for the step sizes used).  Normal mode: exact zero-order-hold discretisation of the
    linear oscillator forced by -gamma * friction.  Extra state (twin indicator w or stick clock theta):
    backward Euler of a linear relaxation.
    """
    k = float(P["k"]); m = float(P["m"]); c = float(P["c"]); N0 = float(P["N0"])
    mus0 = float(P["mu_s"]); muc = float(P["mu_c"]); vs = float(P["vs"]); sv = float(P["sigma_v"])
    eps = float(P["eps"]); gam = float(P["gamma"]); kz = float(P["kz"]); mz = float(P["mz"])
    wz = TWOPI * float(P["fz"]); zz = float(P["zeta_z"])
    cgeo = float(P.get("c_geo", 0.0)); xref = float(P.get("x_ref", 0.0))
    dtw = float(P.get("d_twin", 0.0)); tauw = float(P.get("tau_w", 1.0)); von = float(P.get("v_on", 1.0))
    asc = float(P.get("a_sc", 1.0))
    bage = float(P.get("beta_age", 0.0)); taua = float(P.get("tau_age", 1.0))
    taur = float(P.get("tau_reset", 1.0)); vst = float(P.get("v_stick", 1.0))
    taus = float(P["tau_s"])
    n = len(H) + 1
    A = np.array([[0.0, 1.0, 0.0], [-wz * wz, -2.0 * zz * wz, 1.0 / mz], [0.0, 0.0, 0.0]])
    cache = {}
    X = [0.0] * n; U = [0.0] * n; R = [0.0] * n; F = [0.0] * n; NN = [0.0] * n; Q = [0.0] * n
    V = VD
    x = 0.0; u = float(V[0]); r = 0.0; z = 0.0; zd = 0.0; w = 0.0; th = 0.0
    N = N0 * (NM[0] if NM is not None else 1.0) + cgeo * N0 * (x - xref)
    Ns = N
    X[0] = x; U[0] = u; NN[0] = N
    atanh = math.atanh; exp = math.exp; tanh = math.tanh; log1p = math.log1p
    mus = mus0
    Nmin = 0.05 * N0
    for i in range(n - 1):
        h = H[i]
        cf = cache.get(h)
        if cf is None:
            E = expm(A * h)
            cf = tuple(float(v) for v in (1.0 + h * h * k / (4.0 * m) + h * c / (2.0 * m), h / m,
                                          E[0, 0], E[0, 1], E[0, 2], E[1, 0], E[1, 1], E[1, 2]))
            cache[h] = cf
        a, bet, p11, p12, g1, p21, p22, g2 = cf
        vd1 = V[i + 1]
        B = (2.0 - a) * u - bet * k * x - a * vd1
        ap = a + bet * sv
        if ageing:
            mus = mus0 * (1.0 + bage * log1p(th / taua))
        Cc = bet * N * (muc + dtw * w)
        Cs = bet * (Ns * mus - N * muc)
        Fcap = Cc + Cs
        lo = (B - Fcap) / ap
        hi = (B + Fcap) / ap
        if abs(r) < 50.0 * eps and abs(B) < 0.9999999 * Fcap:
            rr = eps * atanh(B / Fcap)
        else:
            rr = r
            if not lo < rr < hi:
                rr = 0.5 * (lo + hi)
        for _ in range(80):
            q = rr / vs
            e = Cs * exp(-q * q)
            tt = tanh(rr / eps)
            M = Cc + e
            g = ap * rr + M * tt - B
            if g > 0.0:
                hi = rr
            else:
                lo = rr
            dg = ap - 2.0 * q / vs * e * tt + M * (1.0 - tt * tt) / eps
            rn = rr - g / dg
            if not lo < rn < hi:
                rn = 0.5 * (lo + hi)
            if abs(rn - rr) <= 1e-4 * eps + 1e-8 * abs(rr):
                rr = rn
                break
            rr = rn
        q = rr / vs
        Ff = (N * (muc + dtw * w) + (Ns * mus - N * muc) * exp(-q * q)) * tanh(rr / eps) + sv * rr
        u1 = rr + vd1
        x += h * (u + u1) * 0.5
        if twin:
            acc = (rr - r) / h
            s_ = 1.0 if rr > 0.0 else -1.0
            qq = rr / von
            ind = (1.0 - exp(-qq * qq)) * 0.5 * (1.0 + tanh(-s_ * acc / asc))
            w = (w + h * ind / tauw) / (1.0 + h / tauw)
        if ageing:
            qq = rr / vst
            S = exp(-qq * qq)
            th = (th + h * S) / (1.0 + h * (1.0 - S) / taur)
        u = u1
        r = rr
        f = -gam * Ff
        z, zd = p11 * z + p12 * zd + g1 * f, p21 * z + p22 * zd + g2 * f
        N = N0 * (NM[i + 1] if NM is not None else 1.0) + kz * z + cgeo * N0 * (x - xref)
        if N < Nmin:
            N = Nmin
        Ns = (Ns + h * N / taus) / (1.0 + h / taus)
        X[i + 1] = x; U[i + 1] = u; R[i + 1] = r; F[i + 1] = Ff; NN[i + 1] = N
        Q[i + 1] = w if twin else th
    return dict(x=np.array(X), u=np.array(U), vr=np.array(R), Ff=np.array(F), N=np.array(NN), q=np.array(Q))


# ----------------------------------------------------------------------------------------------------------------
# the stage (drive)
# ----------------------------------------------------------------------------------------------------------------

class _Drive:
    """Stage velocity: piecewise linear through knots, or a sinusoidally modulated constant velocity."""

    def __init__(self, kt, kv, quiet=None, mod=None):
        self.kt = np.asarray(kt, float)
        self.kv = np.asarray(kv, float)
        self.quiet = list(quiet) if quiet is not None else [False] * (len(kt) - 1)
        dt = np.diff(self.kt)
        self.ks = np.concatenate([[0.0], np.cumsum(0.5 * (self.kv[1:] + self.kv[:-1]) * dt)])
        self.mod = mod  # (v0n, a, fm, phi)

    @property
    def T(self):
        return float(self.kt[-1])

    def v(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            v0, a, fm, ph = self.mod
            return v0 * (1.0 + a * np.sin(TWOPI * fm * t + ph))
        return np.interp(t, self.kt, self.kv)

    def s(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            v0, a, fm, ph = self.mod
            return v0 * t - v0 * a / (TWOPI * fm) * (np.cos(TWOPI * fm * t + ph) - math.cos(ph))
        j = np.clip(np.searchsorted(self.kt, t, side="right") - 1, 0, len(self.kt) - 2)
        d = t - self.kt[j]
        sl = (self.kv[j + 1] - self.kv[j]) / np.maximum(self.kt[j + 1] - self.kt[j], 1e-300)
        return self.ks[j] + self.kv[j] * d + 0.5 * sl * d * d

    def grid(self, h, hq, Tn):
        """Simulation grid: step ~h, ~hq inside quiet (dwell) intervals away from their ends."""
        ts = []
        hs = []
        for j in range(len(self.kt) - 1):
            a, b = self.kt[j], self.kt[j + 1]
            if b <= a:
                continue
            parts = [(a, b, h)]
            if self.quiet[j] and hq > h and (b - a) > 10.0 * Tn:
                parts = [(a, a + 6.0 * Tn, h), (a + 6.0 * Tn, b - 1.5 * Tn, hq), (b - 1.5 * Tn, b, h)]
            for pa, pb, ph in parts:
                nn = max(1, int(math.ceil((pb - pa) / ph - 1e-9)))
                hh = (pb - pa) / nn
                ts.append(pa + hh * np.arange(nn))
                hs.extend([hh] * nn)
        t = np.concatenate(ts + [np.array([self.kt[-1]])])
        return t, hs


# ----------------------------------------------------------------------------------------------------------------
# analysis of a simulated record (noise free)
# ----------------------------------------------------------------------------------------------------------------

def _events(t, vr, Fs, vd, Tn):
    """Slip events: |v_rel| above half the largest drive speed, and faster than 1.5x the local drive speed."""
    vmax = float(np.max(np.abs(vd)))
    sl = np.abs(vr) > 0.5 * vmax
    d = np.diff(sl.astype(np.int8))
    starts = list(np.nonzero(d == 1)[0] + 1)
    ends = list(np.nonzero(d == -1)[0] + 1)
    if sl[0]:
        starts = [0] + starts
    if sl[-1]:
        ends = ends + [len(sl)]
    segs = []
    for a, b in zip(starts, ends):
        if segs and t[a] - t[segs[-1][1] - 1] < 0.1 * Tn:
            segs[-1][1] = b
        else:
            segs.append([a, b])
    out = []
    prev_end = 0
    for a, b in segs:
        if a == 0 or b >= len(sl) or t[b - 1] + 0.3 * Tn > t[-1]:
            continue  # cut by the ends of the run
        ip = a + int(np.argmax(np.abs(vr[a:b])))
        vpk = abs(vr[ip])
        vloc = max(abs(vd[a]), abs(vd[ip]))
        sd = -1.0 if vr[ip] > 0 else 1.0
        w0 = int(np.searchsorted(t, t[a] - 0.3 * Tn))
        w1 = int(np.searchsorted(t, t[b - 1] + 0.3 * Tn))
        Fpk = float(np.max(sd * Fs[w0:ip + 1]))
        Fmn = float(np.min(sd * Fs[ip:w1 + 1]))
        if vpk > 1.5 * vloc:
            out.append(dict(i0=a, i1=b, ip=ip, t0=float(t[a]), t1=float(t[b - 1]), vpk=float(vpk),
                            vratio=float(vpk / max(vloc, 1e-300)), dir=sd, Fpk=Fpk, Fmin=Fmn, drop=Fpk - Fmn,
                            tstick=float(t[a] - t[prev_end])))
            prev_end = b - 1
    return out


def _twin_measure(ev, vr, Ff, N=None):
    """(F_dec - F_acc) at equal speed (25-85 % of the slip's peak speed), over the slip's force drop.
    With N: the same on the friction coefficient Ff/N (times the slip's mean N)."""
    res = []
    n = len(vr)
    if N is not None:
        Ff = Ff / N * np.mean(N)
    for e in ev:
        ip = e["ip"]
        vpk = e["vpk"]
        a = ip
        while a > 0 and abs(vr[a - 1]) > 0.1 * vpk and vr[a - 1] * vr[ip] > 0:
            a -= 1
        b = ip
        while b < n - 1 and abs(vr[b + 1]) > 0.1 * vpk and vr[b + 1] * vr[ip] > 0:
            b += 1
        if ip - a < 4 or b - ip < 4:
            continue
        sa = np.abs(vr[a:ip + 1]); fa = np.abs(Ff[a:ip + 1])
        sb = np.abs(vr[ip:b + 1])[::-1]; fb = np.abs(Ff[ip:b + 1])[::-1]
        oa = np.argsort(sa, kind="stable"); ob = np.argsort(sb, kind="stable")
        grid = np.linspace(0.25, 0.85, 25) * vpk
        Fa = np.interp(grid, sa[oa], fa[oa]); Fb = np.interp(grid, sb[ob], fb[ob])
        if e["drop"] > 0:
            res.append(float(np.mean(Fb - Fa) / e["drop"]))
    return res


def _peak_growth(ev, tau):
    """Peak force growth over the record's stick-time range: linear fit of Fpk on ln(1 + t_stick/tau)."""
    ts = np.array([e["tstick"] for e in ev]); fp = np.array([e["Fpk"] for e in ev])
    ok = ts > 0
    ts = ts[ok]; fp = fp[ok]
    if len(ts) < 3 or np.ptp(ts) <= 0:
        return float("nan"), float("nan"), float("nan")
    L = np.log1p(ts / tau)
    A = np.vstack([np.ones_like(L), L]).T
    cf, *_ = np.linalg.lstsq(A, fp, rcond=None)
    fmin = cf[0] + cf[1] * L.min(); fmax = cf[0] + cf[1] * L.max()
    return float(fmax / fmin - 1.0), float(ts.min()), float(ts.max())


def _ss_frequency(ev, drive, Tn):
    """Stick-slip frequency: 1 / mean interval between successive slips of the same stroke."""
    if len(ev) < 3:
        return float("nan")
    t0 = np.array([e["t0"] for e in ev])
    d = np.diff(t0)
    sgn = np.array([e["dir"] for e in ev])
    same = sgn[1:] == sgn[:-1]
    d = d[same]
    if len(d) == 0:
        return float("nan")
    return float(1.0 / np.mean(d))


# ----------------------------------------------------------------------------------------------------------------
# model parameters and drive design
# ----------------------------------------------------------------------------------------------------------------

def _draw_physics(rng, case):
    fn = _logu(rng, 2.0, 200.0)
    Tn = 1.0 / fn
    wn = TWOPI * fn
    N0 = _logu(rng, 0.003, 30.0)
    mu_s = float(rng.uniform(0.2, 0.6))
    mu_c = mu_s * float(rng.uniform(0.55, 0.8))
    Ad = _logu(rng, 3e-6, 2e-4)  # (Fs - Fc)/k, m
    k = (mu_s - mu_c) * N0 / Ad
    m = k / wn ** 2
    zeta = float(rng.uniform(0.005, 0.03))
    c = 2.0 * zeta * math.sqrt(k * m)
    Vslip = wn * Ad
    rho = float(rng.uniform(0.1, 0.25) if case == "static_ageing" else rng.uniform(0.06, 0.25))
    vs = rho * Vslip
    rv = float(rng.uniform(0.02, 0.06))
    sigma_v = rv * (mu_s - mu_c) * N0 / Vslip
    fz = fn * float(rng.uniform(3.0, 10.0))
    zeta_z = float(rng.uniform(0.02, 0.10))
    delta_z = _logu(rng, 0.5e-6, 5e-6)
    kz = N0 / delta_z
    mz = kz / (TWOPI * fz) ** 2
    gamma = float(rng.uniform(0.004, 0.010)) * float(rng.choice([-1.0, 1.0]))
    tau_s = float(rng.uniform(0.6, 1.2)) * Tn
    return dict(tau_s=tau_s, fn=fn, Tn=Tn, N0=N0, mu_s=mu_s, mu_c=mu_c, A_d=Ad, k=k, m=m, zeta=zeta, c=c, Vslip=Vslip,
                rho=rho, vs=vs, r_visc=rv, sigma_v=sigma_v, fz=fz, zeta_z=zeta_z, kz=kz, mz=mz, gamma=gamma)


def _v_for_stick(P, Tst):
    """Drive speed that gives roughly Tst natural periods of stick (stick travel ~ 2 A_d)."""
    return 2.0 * P["A_d"] / (Tst * P["Tn"])


def _tst_low(P):
    # keep v0 <= 0.8 vs at the fastest drive speed, so that steady sliding is unstable
    return max(2.5, 1.0 / (0.8 * math.pi * P["rho"]))


def _pilot(P, v0, n_sub=64, twin=False):
    """Short constant-speed run: drop, peak, stick-slip period, slip speed."""
    Tn = P["Tn"]
    T = P["mu_s"] * P["N0"] / (P["k"] * v0) + 7.0 * (2.0 * P["A_d"] / v0 + 0.6 * Tn)
    dr = _Drive([0.0, 0.5 * Tn, T], [v0, v0, v0])
    t, H = dr.grid(Tn / n_sub, Tn / n_sub, Tn)
    vd = dr.v(t)
    o = _simulate(P, H, vd.tolist(), twin=twin)
    ev = _events(t, o["vr"], P["k"] * o["x"], vd, Tn)[1:]
    if len(ev) < 4:
        return None
    drop = float(np.median([e["drop"] for e in ev]))
    res = dict(drop=drop, Fpk=float(np.median([e["Fpk"] for e in ev])),
               Fmin=float(np.median([e["Fmin"] for e in ev])),
               Tss=float(np.median(np.diff([e["t0"] for e in ev]))),
               tslip=float(np.median([e["t1"] - e["t0"] for e in ev])),
               vpk=float(np.median([e["vpk"] for e in ev])),
               vratio=float(np.median([e["vratio"] for e in ev])), n=len(ev))
    if twin:
        tw = _twin_measure(ev, o["vr"], o["Ff"])
        res["twin"] = float(np.median(tw)) if tw else float("nan")
    res["real"] = bool(drop > 0.5 * 2.0 * (P["mu_s"] - P["mu_c"]) * P["N0"] and res["vratio"] > 3.0)
    return res


def _trig_pilot(P, v0, a, f, phi, n_sub):
    """Short constant-speed run with the normal-load vibration: (stick-slip frequency, distance of f/fss to the
    nearest integer)."""
    Tn = P["Tn"]
    T = P["mu_s"] * P["N0"] / (P["k"] * v0) + 14.0 * (2.0 * P["A_d"] / v0 + 0.6 * Tn)
    dr = _Drive([0.0, 0.5 * Tn, T], [v0, v0, v0])
    t, H = dr.grid(Tn / n_sub, Tn / n_sub, Tn)
    vd = dr.v(t)
    NM = (1.0 + a * np.sin(TWOPI * f * t + phi)).tolist()
    o = _simulate(P, H, vd.tolist(), NM=NM)
    ev = _events(t, o["vr"], P["k"] * o["x"], vd, Tn)[2:]
    if len(ev) < 6:
        return None
    fss = (len(ev) - 1) / (ev[-1]["t0"] - ev[0]["t0"])
    r = f / fss
    return fss, abs(r - round(r))


def _ramp(rng, Tn):
    return float(rng.uniform(0.3, 1.0)) * Tn


def _recip_drive(rng, P, pil, speeds, dwell, n_cps):
    """Trapezoidal position wave: strokes of equal length L at the given speeds, dwells at the ends."""
    Tn = P["Tn"]; k = P["k"]
    v_ref = speeds[0]
    travel_cycle = pil["drop"] / k + v_ref * pil["tslip"]
    Fm = 0.5 * (pil["Fpk"] + pil["Fmin"])
    L = (Fm + pil["Fpk"]) / k + (n_cps + 0.5) * travel_cycle
    tr = _ramp(rng, Tn)
    kt = [0.0, 0.5 * Tn]
    kv = [0.0, 0.0]
    quiet = [False]
    strokes = []
    sgn = 1.0
    for V in speeds:
        trr = min(tr, 0.1 * L / V)
        Tc = L / V - trr
        t0 = kt[-1]
        kt += [t0 + trr, t0 + trr + Tc, t0 + 2 * trr + Tc, t0 + 2 * trr + Tc + dwell]
        kv += [sgn * V, sgn * V, 0.0, 0.0]
        quiet += [False, False, False, True]
        strokes.append((t0, t0 + 2 * trr + Tc + dwell, sgn, V))
        sgn = -sgn
    return _Drive(kt, kv, quiet), strokes, L


def _levels_drive(rng, P, levels, durations, hold=None):
    """One-direction drive stepping between speed levels (with short acceleration ramps); optional hold."""
    Tn = P["Tn"]
    tr = _ramp(rng, Tn)
    kt = [0.0]
    kv = [levels[0]]
    quiet = []
    for j, (v, d) in enumerate(zip(levels, durations)):
        if j > 0:
            kt.append(kt[-1] + tr); kv.append(v); quiet.append(False)
        kt.append(kt[-1] + d); kv.append(v); quiet.append(False)
        if hold is not None and hold[0] == j:
            kt.append(kt[-1] + tr); kv.append(0.0); quiet.append(False)
            kt.append(kt[-1] + hold[1]); kv.append(0.0); quiet.append(True)
            kt.append(kt[-1] + tr); kv.append(v); quiet.append(False)
            kt.append(kt[-1] + 3.0 * Tn); kv.append(v); quiet.append(False)
    return _Drive(kt, kv, quiet)


# ----------------------------------------------------------------------------------------------------------------
# record acquisition: sensor dynamics, sampling, noise, nuisances, file
# ----------------------------------------------------------------------------------------------------------------

def _sample_times(rng, t0, t1, dt, jitter, drops):
    n = int(math.floor((t1 - t0) / dt))
    ts = t0 + dt * np.arange(n + 1)
    if jitter > 0:
        ts = ts + np.clip(rng.normal(0.0, jitter * dt, ts.size), -0.4 * dt, 0.4 * dt)
        ts[0] = t0
        ts = np.clip(ts, t0, t1)
    if drops > 0:
        keep = np.ones(ts.size, bool)
        for i in rng.integers(5, ts.size - 5, drops):
            keep[i:i + int(rng.integers(1, 3))] = False
        ts = ts[keep]
    return ts


def _fmt_time(dt):
    return "%." + str(max(4, int(math.ceil(-math.log10(dt))) + 3)) + "f"


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    tic = time.time()
    rng = _rng(case, seed)
    rn = _rng(case, seed, nuisance)

    # ---------------------------------------------------------------- physics, checked by a pilot run
    for attempt in range(12):
        P = _draw_physics(rng, case)
        Tn = P["Tn"]
        tlo = _tst_low(P)
        if case == "static_ageing":
            factor = float(rng.uniform(4.0, 8.0))
            Tst = float(rng.uniform(tlo, max(tlo + 0.5, 4.0)))
        elif case == "drive_modulation":
            Tst = float(rng.uniform(1.5 * tlo, max(1.5 * tlo + 1.0, 10.0)))
        else:
            Tst = float(rng.uniform(tlo, max(tlo + 1.0, 10.0)))
        v0 = _v_for_stick(P, Tst)
        v_slowest = v0 / factor if case == "static_ageing" else v0 * (0.55 if case == "drive_modulation" else 1.0)
        if case == "none":
            v_slowest = v0 / 3.0
        P["eps"] = 0.004 * v_slowest
        pil = _pilot(P, v0)
        if pil is None or not pil["real"]:
            continue
        if case in ("none", "static_ageing", "drive_modulation"):
            # the slowest drive speed must give real stick-slip too (not the small near-harmonic cycle that a
            # flat Stribeck curve gives at very low speeds)
            pslow = _pilot(P, v_slowest)
            if pslow is None or not pslow["real"]:
                continue
        break
    else:
        raise RuntimeError("no stick-slip regime found")
    P["v0"] = v0
    P["Tst_design"] = Tst

    # ---------------------------------------------------------------- drive
    recip = False
    if case in ("none", "load_variation", "twin_branch", "triggering", "static_ageing"):
        recip = bool(rng.random() < 0.5)
    steps = False
    if case == "none" and not recip:
        steps = bool(rng.random() < 0.35)
    if case == "static_ageing" and not recip:
        steps = True
    dwell = float(rng.uniform(0.2, 1.0))
    info = {}
    levels = None
    hold = None
    if recip:
        if case == "static_ageing":
            nl = int(rng.integers(4, 7))
            levels = list(v0 / factor ** (np.arange(nl) / (nl - 1.0)))
            rng.shuffle(levels)
            speeds = [float(v) for v in levels]
            n_cps = float(rng.uniform(4.0, 6.0))
        else:
            ns = int(rng.integers(4, 13))
            n_cps = float(rng.uniform(4.0, 8.0))
            ns = max(min(ns, int(60.0 / n_cps)), int(math.ceil(14.0 / n_cps)))
            speeds = [v0] * ns
        # keep the file and the run short on fast rigs: shorten dwells within 0.2-1 s if needed
        budget_T = 1500.0 * Tn
        stroke_T = sum((n_cps + 2.0) * (2.0 * P["A_d"] / v + 0.6 * Tn) for v in speeds)
        if len(speeds) * dwell + stroke_T > budget_T:
            dwell = max(0.2, (budget_T - stroke_T) / len(speeds))
        pil_ref = pil
        drive, strokes, L = _recip_drive(rng, P, pil_ref, speeds, dwell, n_cps)
        info.update(drive="reciprocating", n_strokes=len(speeds), stroke_length_m=L, dwell_s=dwell,
                    stroke_speeds_m_s=speeds)
    elif case == "drive_modulation":
        a_m = float(rng.uniform(0.2, 0.45))
        ratio = float(rng.uniform(0.15, 0.4))
        fss0 = 1.0 / pil["Tss"]
        fm = ratio * fss0
        phi = float(rng.uniform(0.0, TWOPI))
        n_mod = float(rng.uniform(3.0, 5.0))
        T = max(n_mod / fm, 16.0 / fss0) + P["mu_s"] * P["N0"] / (P["k"] * v0)
        drive = _Drive([0.0, T], [v0, v0], mod=(v0, a_m, fm, phi))
        info.update(drive="modulated", v0n=v0, a_mod=a_m, fm=fm, phi=phi)
    elif steps:
        if case == "static_ageing":
            nl = int(rng.integers(4, 7))
            levels = list(v0 / factor ** (np.arange(nl) / (nl - 1.0)))
            rng.shuffle(levels)
            ncyc = [float(rng.uniform(4.0, 6.0)) for _ in levels]
            if rng.random() < 0.35:
                hold = (int(rng.integers(0, nl - 1)), 0.0)
        else:
            nl = int(rng.integers(2, 5))
            fac = float(rng.uniform(2.0, 3.0))
            levels = list(v0 / fac ** (np.arange(nl) / max(nl - 1.0, 1.0)))
            rng.shuffle(levels)
            ncyc = [float(rng.uniform(4.0, 8.0)) for _ in levels]
        ncyc = [nc * max(1.0, 18.0 / sum(ncyc)) for nc in ncyc]  # >= 18 cycles in all
        tsl = pil["tslip"]
        Tss_v = [tsl + (pil["Tss"] - tsl) * v0 / v for v in levels]
        durs = [nc * T_ for nc, T_ in zip(ncyc, Tss_v)]
        durs[0] += pil["Fpk"] / (P["k"] * levels[0])
        if hold is not None:
            hold = (hold[0], float(rng.uniform(1.5, 3.0)) * max(Tss_v))
        levels = [float(v) for v in levels]
        drive = _levels_drive(rng, P, levels, durs, hold)
        info.update(drive="steps", levels_m_s=levels, hold_s=(hold[1] if hold else 0.0))
    else:
        ncy = float(rng.uniform(16.0, 36.0))
        T = ncy * pil["Tss"] + P["mu_s"] * P["N0"] / (P["k"] * v0)
        drive = _Drive([0.0, 0.5 * Tn, T], [v0, v0, v0])
        info.update(drive="constant", v0=v0)

    # ---------------------------------------------------------------- case parameters
    P["c_geo"] = 0.0
    P["x_ref"] = 0.0
    twin = case == "twin_branch"
    ageing = case == "static_ageing"
    if twin:
        P["tau_w"] = Tn / 40.0
        P["v_on"] = 0.1 * pil["vpk"]
        P["a_sc"] = 0.02 * pil["vpk"] * TWOPI / Tn
        target_tw = float(rng.uniform(0.12, 0.22))
        P["d_twin"] = target_tw * pil["drop"] / P["N0"] / 0.8
        for _ in range(2):  # calibrate on short pilots
            pt = _pilot(P, v0, twin=True)
            if pt is None or not np.isfinite(pt.get("twin", np.nan)) or pt["twin"] <= 0:
                break
            P["d_twin"] *= target_tw / pt["twin"]
            if abs(pt["twin"] / target_tw - 1.0) < 0.08:
                break
        info["twin_target"] = target_tw
    if ageing:
        P["tau_reset"] = Tn / 30.0
        P["v_stick"] = 0.3 * min(levels)
        tmin = pil["Tss"] - pil["tslip"]
        tmax = tmin * factor + (dwell if recip else (hold[1] if hold else 0.0))
        P["tau_age"] = float(rng.uniform(0.2, 1.0)) * tmin
        target_g = float(rng.uniform(0.08, 0.16))
        span = math.log1p(tmax / P["tau_age"]) - math.log1p(tmin / P["tau_age"])
        P["beta_age"] = target_g / max(span, 0.3)
        info["growth_target"] = target_g
        info["speed_factor"] = factor
    if case == "load_variation":
        target_pp = float(rng.uniform(0.14, 0.34))
        if recip:
            xr = 2.0 * pil["Fpk"] / P["k"]
            P["x_ref"] = 0.0
        else:
            xr = pil["drop"] / P["k"]
            P["x_ref"] = 0.5 * (pil["Fpk"] + pil["Fmin"]) / P["k"]
        P["c_geo"] = float(rng.choice([-1.0, 1.0])) * target_pp / xr
        info["load_pp_target"] = target_pp

    # ---------------------------------------------------------------- sampling (needed for the grid)
    coarse = nuisance == "coarse"
    sp = float(rng.uniform(20.0, 100.0))
    if coarse:
        sp = float(rn.uniform(10.0, 15.0))
    fs_rec = sp / Tn
    if not coarse:
        n_est = drive.T * fs_rec
        if n_est > 150000:
            sp = max(20.0, sp * 150000 / n_est)
            fs_rec = sp / Tn
    trig = case == "triggering"
    n_sub = max(64.0, 0.6 * sp, 6.0 * P["fz"] / P["fn"])
    if trig:
        # f_tr is put near a half-integer multiple of the stick-slip frequency (checked on short runs, the
        # slip timing moves a little with the vibration), as near as possible to a drawn 2.5-8 fn.
        a_tr = float(rng.uniform(0.03, 0.08))
        phi_tr = float(rng.uniform(0.0, TWOPI))
        fss0 = 1.0 / pil["Tss"]
        # (f_tr / f_ss kept below ~30 where the drawn range allows: far up, "off a multiple" loses meaning)
        f_want = float(rng.uniform(2.5, min(8.0, max(2.5, 30.0 * fss0 / P["fn"])))) * P["fn"]
        cands = [fss0 * (j + 0.5) for j in range(1, 400) if 2.5 * P["fn"] <= fss0 * (j + 0.5) <= 8.0 * P["fn"]]
        cands.sort(key=lambda f_: abs(f_ - f_want))
        best = None
        for f_ in cands[:8]:
            ns_ = max(n_sub, 12.0 * f_ / P["fn"])
            r_ = _trig_pilot(P, v0, a_tr, f_, phi_tr, ns_)
            if r_ is None:
                continue
            if best is None or r_[1] > best[1]:
                best = (f_, r_[1])
            if r_[1] >= 0.25:
                break
        f_tr = best[0] if best is not None else cands[0]
        info.update(a_trig=a_tr, phi_trig=phi_tr)
        n_sub = max(n_sub, 12.0 * f_tr / P["fn"])
    h = Tn / n_sub
    hq = min(Tn / 6.0, 0.25 / f_tr) if trig else Tn / 6.0

    # ---------------------------------------------------------------- run, measure, recalibrate
    # one-direction records start at rest with an unloaded spring; some are cut to start after the first slip
    # (always with load_variation, whose geometric coupling is set up around the steady operating point)
    trim = (not recip) and case != "drive_modulation" and not steps and (
        case == "load_variation" or bool(rng.random() < 0.3))
    trim_frac = float(rng.uniform(0.2, 0.8))
    meas = {}
    for it in range(4):
        t, H = drive.grid(h, hq, Tn)
        vd = drive.v(t)
        NM = None
        if trig:
            NM = (1.0 + a_tr * np.sin(TWOPI * f_tr * t + phi_tr)).tolist()
        o = _simulate(P, H, vd.tolist(), NM=NM, twin=twin, ageing=ageing)
        Fs = P["k"] * o["x"]
        ev = _events(t, o["vr"], Fs, vd, Tn)
        again = False
        if recip:
            cps = []
            for (ta, tb, sg, V) in strokes:
                cps.append(sum(1 for e in ev if ta <= e["t0"] < tb))
            meas["cycles_per_stroke_min"] = int(min(cps))
            if min(cps) < 4 and it < 3:
                drive, strokes, L = _recip_drive(_rng(case, seed, "stroke", it), P, pil, speeds, dwell,
                                                 n_cps * 4.6 / max(min(cps), 1) + 0.5)
                info["stroke_length_m"] = L
                again = True
        if case == "none" and not again:
            Nn = o["N"]
            pp = float(np.ptp(Nn) / np.mean(Nn))
            if pp > 0.018 and it < 3:
                P["gamma"] *= 0.014 / pp
                again = True
        if case == "load_variation" and not again:
            Nn = o["N"][t >= (ev[0]["t1"] + trim_frac * pil["Tss"] if trim else 0.0)]
            pp = float(np.ptp(Nn) / np.mean(Nn))
            if not 0.11 <= pp <= 0.38 and it < 3:
                P["c_geo"] *= info["load_pp_target"] / pp
                again = True
        if twin and not again:
            tw = _twin_measure(ev, o["vr"], o["Ff"])
            tm = float(np.median(tw)) if tw else float("nan")
            if (not np.isfinite(tm) or not 0.105 <= tm <= 0.24) and it < 3 and np.isfinite(tm) and tm > 0:
                P["d_twin"] *= info["twin_target"] / tm
                again = True
        if ageing and not again:
            g, _, _ = _peak_growth(ev, P["tau_age"])
            if (not 0.055 <= g <= 0.19) and it < 3:
                P["beta_age"] *= max(0.2, min(5.0, info["growth_target"] / max(g, 0.01)))
                again = True
        if trig and not again:
            fss = _ss_frequency(ev, drive, Tn)
            ratio = f_tr / fss
            dist = abs(ratio - round(ratio))
            info.setdefault("trig_history", []).append([f_tr, fss, dist])
            if dist < 0.2 and it < 2:
                f_new = fss * (math.floor(ratio) + 0.5)
                if not 2.5 * P["fn"] <= f_new <= 8.0 * P["fn"]:
                    f_new = fss * (math.floor(ratio) + (1.5 if f_new < 2.5 * P["fn"] else -0.5))
                f_tr = f_new
                n_sub = max(n_sub, 12.0 * f_tr / P["fn"])
                h = Tn / n_sub
                hq = min(Tn / 6.0, 0.25 / f_tr)
                again = True
        if case == "drive_modulation" and not again:
            fss = len(ev) / max(ev[-1]["t0"] - ev[0]["t0"], 1e-300) if len(ev) > 2 else float("nan")
            r_ = info["fm"] / fss
            if not 0.12 <= r_ <= 0.45 and it < 3:
                fm_new = info["fm"] * (0.27 / r_)
                v0n, a_m, _, phi = drive.mod
                T = max(n_mod / fm_new, 16.0 * fss ** -1) + P["mu_s"] * P["N0"] / (P["k"] * v0)
                drive = _Drive([0.0, T], [v0n, v0n], mod=(v0n, a_m, fm_new, phi))
                info["fm"] = fm_new
                again = True
        if not again:
            break
    n_runs = it + 1
    _LAST.clear()
    _LAST.update(t=t, sim=o, events=ev, P=P)

    # ---------------------------------------------------------------- measurements on the produced record
    Tend = float(t[-1])
    t_rec0 = 0.0
    if trim:
        t_rec0 = float(ev[0]["t1"] + trim_frac * pil["Tss"])
    evr = [e for e in ev if e["t0"] >= t_rec0]
    drops = np.array([e["drop"] for e in evr])
    drop = float(np.median(drops))
    meas["n_slips"] = len(evr)
    meas["drop_median"] = drop
    meas["drop_min_over_median"] = float(drops.min() / drop)
    meas["slip_speed_over_drive"] = float(np.median([e["vratio"] for e in evr]))
    moving = np.abs(vd) > 0.0
    stick = np.abs(o["vr"]) < 0.05 * np.abs(vd)
    meas["stick_fraction"] = float(np.mean(stick[moving]))
    tw = _twin_measure(evr, o["vr"], o["Ff"])
    meas["twin_ratio_median"] = float(np.median(tw)) if tw else float("nan")
    meas["twin_ratio_min"] = float(np.min(tw)) if tw else float("nan")
    meas["twin_ratio_max"] = float(np.max(tw)) if tw else float("nan")
    twm = _twin_measure(evr, o["vr"], o["Ff"], o["N"])
    meas["twin_ratio_mu_median"] = float(np.median(twm)) if twm else float("nan")
    tau_g = P.get("tau_age", max(1e-3 * Tn, np.median([e["tstick"] for e in evr]) * 0.5))
    g, tsmin, tsmax = _peak_growth(evr, tau_g)
    meas["peak_growth"] = g
    meas["stick_time_min_s"] = tsmin
    meas["stick_time_max_s"] = tsmax
    rec = (t >= t_rec0)
    Nr = o["N"][rec]
    meas["N_pp_over_mean"] = float(np.ptp(Nr) / np.mean(Nr))
    meas["N_mean_over_N0"] = float(np.mean(Nr) / P["N0"])
    fss = _ss_frequency(evr, drive, Tn)
    meas["f_stickslip"] = fss
    meas["stickslip_period_over_Tn"] = float(1.0 / (fss * Tn))
    if ageing:
        th_b = np.array([o["q"][max(e["i0"] - 1, 0)] for e in evr])
        mus_b = P["mu_s"] * (1.0 + P["beta_age"] * np.log1p(th_b / P["tau_age"]))
        meas["mu_s_law_growth"] = float(mus_b.max() / mus_b.min() - 1.0)
    if trig:
        # fit N = c0 + c1 t + A sin + B cos at f_tr on the recorded window
        tt = t[rec]
        Mx = np.vstack([np.ones_like(tt), tt - tt.mean(), np.sin(TWOPI * f_tr * tt), np.cos(TWOPI * f_tr * tt)]).T
        cf, *_ = np.linalg.lstsq(Mx, Nr, rcond=None)
        meas["trig_amp_over_Nmean"] = float(math.hypot(cf[2], cf[3]) / np.mean(Nr))
        meas["trig_f_over_fn"] = float(f_tr / P["fn"])
        meas["trig_f_over_fss"] = float(f_tr / fss)
        meas["trig_dist_to_multiple"] = float(abs(f_tr / fss - round(f_tr / fss)))
        info["f_trig"] = f_tr
    if case == "drive_modulation":
        fss_m = (len(evr) - 1) / max(evr[-1]["t0"] - evr[0]["t0"], 1e-300)
        meas["f_stickslip"] = float(fss_m)
        meas["fm_over_fss"] = float(info["fm"] / fss_m)
        meas["a_mod"] = info["a_mod"]
        meas["n_mod_periods"] = float((Tend - t_rec0) * info["fm"])
    if recip:
        meas["cycles_total"] = len(evr)

    # ---------------------------------------------------------------- acquisition
    fmt_rng = _rng(case, seed, "format")
    jitter = float(fmt_rng.uniform(0.02, 0.12)) if fmt_rng.random() < 0.3 else 0.0
    ndrop = int(fmt_rng.integers(3, 13)) if fmt_rng.random() < 0.3 else 0
    dt = Tn / sp
    ts = _sample_times(rn, t_rec0, Tend, dt, jitter, ndrop)
    # oversampled acquisition grid for the analogue sensor dynamics
    dto = dt / 4.0
    to = t_rec0 + dto * np.arange(int((Tend - t_rec0) / dto) + 1)
    Fsp = CubicHermiteSpline(t, Fs, P["k"] * o["u"])
    Fo = Fsp(to)
    nm_t = (lambda tq: 1.0 + a_tr * np.sin(TWOPI * f_tr * tq + phi_tr)) if trig else (lambda tq: np.ones_like(tq))
    No = P["N0"] * nm_t(to) + np.interp(to, t, o["N"] - P["N0"] * nm_t(t))
    fso = 1.0 / dto
    sensor = "resonance" if fmt_rng.random() < 0.5 else "lowpass"
    if sensor == "resonance":
        fr = min(float(fmt_rng.uniform(6.0, 20.0)) * P["fn"], 0.3 * fs_rec)
        zr = float(fmt_rng.uniform(0.08, 0.3))
        wr = TWOPI * fr
        b, a = signal.bilinear([wr * wr], [1.0, 2.0 * zr * wr, wr * wr], fs=fso)
        info.update(sensor="resonance", sensor_f_hz=fr, sensor_zeta=zr)
    else:
        fc = float(fmt_rng.uniform(0.15, 0.35)) * fs_rec
        b, a = signal.butter(2, fc, fs=fso)
        info.update(sensor="lowpass2", sensor_f_hz=fc)
    Fo = signal.lfilter(b, a, Fo, zi=signal.lfilter_zi(b, a) * Fo[0])[0]
    fcn = float(fmt_rng.uniform(0.1, 0.3)) * fs_rec
    bn, an = signal.butter(1, fcn, fs=fso)
    No = signal.lfilter(bn, an, No, zi=signal.lfilter_zi(bn, an) * No[0])[0]
    Fm = np.interp(ts, to, Fo)
    Nm = np.interp(ts, to, No)
    sF = float(rn.uniform(0.002, 0.01)) * drop
    sN = float(rn.uniform(0.001, 0.004)) * P["N0"]
    Fm = Fm + rn.normal(0.0, sF, ts.size)
    Nm = Nm + rn.normal(0.0, sN, ts.size)
    nz = dict(noise_F_over_drop=sF / drop, noise_N_over_N0=sN / P["N0"])
    if nuisance == "hum":
        fh = float(rn.choice([50.0, 60.0]))
        amp = float(rn.uniform(0.01, 0.05)) * drop
        hum = np.zeros_like(ts)
        for hn, fr_ in ((1, 1.0), (2, float(rn.uniform(0.1, 0.4))), (3, float(rn.uniform(0.1, 0.5)))):
            hum += fr_ * np.sin(TWOPI * hn * fh * ts + rn.uniform(0, TWOPI))
        hum *= amp / max(np.max(np.abs(hum)), 1e-300)
        Fm = Fm + hum
        Nm = Nm + hum * (float(rn.uniform(0.2, 1.0)) * sN / sF)
        nz.update(hum_hz=fh, hum_amp_over_drop=amp / drop)
    elif nuisance == "drift":
        amp = float(rn.uniform(0.02, 0.06)) * drop * float(rn.choice([-1.0, 1.0]))
        u_ = (ts - ts[0]) / (ts[-1] - ts[0])
        cur = float(rn.uniform(-0.5, 0.5))
        Fm = Fm + amp * (u_ + cur * u_ * (u_ - 1.0))
        nz.update(drift_over_drop=amp / drop)
    elif nuisance == "spikes":
        frac = float(rn.uniform(0.0005, 0.005))
        nsp = max(2, int(round(frac * ts.size)))
        idx = rn.choice(np.arange(3, ts.size - 3), nsp, replace=False)
        Fm[idx] += rn.uniform(0.3, 1.5, nsp) * drop * rn.choice([-1.0, 1.0], nsp)
        nz.update(spike_fraction=nsp / ts.size)
    elif nuisance == "quantisation":
        q = float(rn.uniform(0.002, 0.01)) * drop
        qn = float(rn.uniform(0.001, 0.004)) * P["N0"]
        Fm = np.round(Fm / q) * q
        Nm = np.round(Nm / qn) * qn
        nz.update(adc_step_over_drop=q / drop)

    # ---------------------------------------------------------------- record file
    has_N = case in ("load_variation", "triggering") or bool(fmt_rng.random() < 0.5)
    drive_col = None
    if recip:
        drive_col = "pos"
    elif steps:
        drive_col = "pos" if fmt_rng.random() < 0.5 else "v0"
    elif case in ("none", "load_variation", "twin_branch", "triggering") and fmt_rng.random() < 0.25:
        drive_col = "v0" if fmt_rng.random() < 0.5 else "pos"
    disp = (not recip) and drive_col != "pos" and bool(fmt_rng.random() < 0.3)
    args = []
    fn_given = None
    if nuisance == "fn_off":
        fn_given = P["fn"] * float(rn.choice([0.95, 1.05]))
    elif fmt_rng.random() < 0.6:
        fn_given = P["fn"]
    if fn_given is not None:
        args += ["--fn", "%.6g" % fn_given]
    if drive_col is None:
        v_user = info.get("v0n", v0)
        args += ["--v0", "%.6g" % (v_user * 1e3)]
    cols = []
    if disp:
        xs = Fm / P["k"] * 1e3
        cols.append(("x [mm]", xs))
        if has_N:
            gy = float(fmt_rng.uniform(0.2, 2.0)) / P["N0"]
            y0 = float(fmt_rng.uniform(-1.0, 1.0))
            cols.append(("y [mm]", y0 + gy * Nm))
        if drive_col == "v0":
            cols.append(("v0 [mm/s]", drive.v(ts) * 1e3))
        tname = fmt_rng.choice(["t [s]", "time [s]"])
        sep = str(fmt_rng.choice([",", ",", "\t", " "]))
        fmt_kind = "displacement"
    else:
        scale = {"N": 1.0, "mN": 1e3, "uN": 1e6}
        ok = [u for u in scale if 0.05 <= P["mu_s"] * P["N0"] * scale[u] <= 2e5]
        fu = str(fmt_rng.choice(ok))
        fname = str(fmt_rng.choice(["Friction", "friction", "Friction force", "Tangential force"]))
        cols.append(("%s [%s]" % (fname, fu), Fm * scale[fu]))
        if has_N:
            nname = str(fmt_rng.choice(["Normal", "normal", "Normal load", "Normal force"]))
            cols.append(("%s [%s]" % (nname, fu), Nm * scale[fu]))
        if drive_col == "pos":
            pu, ps = (("mm", 1e3) if fmt_rng.random() < 0.6 else ("um", 1e6))
            pname = str(fmt_rng.choice(["Position", "position", "Stage position"]))
            s_off = float(fmt_rng.uniform(0.0, 10.0)) * 1e-3 if fmt_rng.random() < 0.5 else 0.0
            cols.append(("%s [%s]" % (pname, pu), (s_off + drive.s(ts)) * ps))
        elif drive_col == "v0":
            cols.append((str(fmt_rng.choice(["v0 [mm/s]", "V0 [mm/s]", "drive v0 [mm/s]"])), drive.v(ts) * 1e3))
        order = fmt_rng.permutation(len(cols))
        cols = [cols[i] for i in order]
        tname = str(fmt_rng.choice(["Time [s]", "time [s]", "t [s]"]))
        sep = str(fmt_rng.choice(["\t", "\t", " ", ";", ","]))
        fmt_kind = "force"
        if fmt_rng.random() < 0.75:
            args += ["--stiffness", "%.6g" % P["k"]]
    tf = _fmt_time(dt)
    names = [tname] + [cn for cn, _ in cols]
    data = [ts] + [cv for _, cv in cols]
    os.makedirs(outdir, exist_ok=True)
    fname_out = os.path.abspath(os.path.join(outdir, "%s_%s_%03d_%s.%s" % (
        NAME, case, seed, nuisance, "csv" if sep in (",", ";") else ("tsv" if sep == "\t" else "txt"))))
    with open(fname_out, "w") as fh:
        if sep == " ":
            fh.write("  ".join(names) + "\n")
            M = np.column_stack(data)
            np.savetxt(fh, M, fmt=[tf] + ["%14.7g"] * len(cols), delimiter="  ")
        else:
            fh.write(sep.join(names) + "\n")
            M = np.column_stack(data)
            np.savetxt(fh, M, fmt=[tf] + ["%.7g"] * len(cols), delimiter=sep)

    params = {kk: (float(vv) if isinstance(vv, (float, np.floating, int)) else vv) for kk, vv in P.items()}
    params.update(info)
    params.update(dict(samples_per_period=sp, n_sub=n_sub, jitter_over_dt=jitter, dropped_gaps=ndrop,
                       n_samples=int(ts.size), record_kind=fmt_kind, has_normal=has_N, drive_column=drive_col,
                       separator=sep, t_record_start=t_rec0, n_runs=n_runs))
    params["nuisance_params"] = nz
    params["measured"] = meas
    params["seconds"] = time.time() - tic
    params = json.loads(json.dumps(params, default=float))
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=fname_out, args=args,
                fn_true=float(P["fn"]), fn_given=(float(fn_given) if fn_given is not None else None),
                params=params)


def _main(argv):
    if len(argv) < 2:
        print("usage: python stribeck_normal.py OUTDIR [NSEEDS]")
        return 2
    outdir = argv[1]
    nseeds = int(argv[2]) if len(argv) > 2 else 8
    truth = []
    for case in CASES:
        for seed in range(nseeds):
            nuis = NUISANCES[seed % len(NUISANCES)]
            tr = write_record(case, seed, outdir, nuis)
            truth.append(tr)
            print("%-17s %3d %-13s %5.2fs %s" % (case, seed, nuis, tr["params"]["seconds"],
                                                  os.path.basename(tr["file"])), flush=True)
    with open(os.path.join(outdir, "truth.json"), "w") as fh:
        json.dump(truth, fh, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(_main(sys.argv))
