"""Independent stick-slip record generator: Dieterich-Ruina RATE-AND-STATE friction on an inertial spring-slider.

Written without reading the diagnosis code or the other generators (see README.md in this folder for the
contract). Only numpy and scipy.

Model
-----
Physical:  m x'' = k (u(t) - x) - c x' - N(t, x) mu(V, theta),   u' = v0(t),   V = x'.
Integrated dimensionless (time unit 1/omega_n, force unit N0, length unit N0/k, so the mass is 1 and the
spring extension s = k (u - x) / N0 is the spring force over N0):

    s'     = v0(t) - V
    V'     = s - 2 zeta V - n(t, s) mu               (integrated as ln V; V > 0 always)
    theta' = 1 - V theta / Dc                        AGEING (Dieterich) law
    mu     = a asinh( V / (2 V*) exp(Psi / a) ) + mu_twin,   Psi = mu0 + b ln(V* theta / Dc)

No separate stick state: the asinh form regularises V -> 0 and a "stick" is creep at V ~ 1e-5..1e-4 v0.
Two sensor states ride along in the ODE: a 1st-order low-pass of the spring force (cut-off 5-20 fn) and of
the normal load (15-30 fn). Integrator: scipy LSODA (stiff/non-stiff switching) with an analytic Jacobian
on y = [s, ln V, ln theta, s_f, n_f, w], rtol 1e-6; fall-back to a smaller first step, then Radau.
Drive steps and holds are applied only as a slip ends (the segment is prolonged to the end of the next slip),
so each stick is loaded at a single rate and holds start at the beginning of a stick.

Parameters (per record, log-uniform where marked *)
    fn* 2-200 Hz; zeta 0.01-0.08; a = r b with r = a/b 0.88-0.95 (0.96-0.975 for the stepped `none`,
    0.88-0.93 twin, 0.9-0.95 static_ageing); b set (preliminary-run secant) so that the drop is a target
    fraction 20-45 % of the peak (stepped none 20-25 %, twin 30-50 %, static_ageing 20-36 %) -> b ~ 0.01-0.1;
    mu0 0.25-0.6 (stepped none 0.3-0.45, static_ageing 0.4-0.65); Dc = kap (b - a) with
    kap = k / k_c = 0.0015-0.004 (k_c = N (b-a)/Dc, quasi-static critical stiffness), so Dc is 1e-5..1e-4 of
    the slip distance and the state follows its steady state within a small part of each slip;
    V* = v0n; v0n = drop / (2 R) in the units above with R* 15-60 (stepped 35-70, triggering 12-30), giving
    slip peak velocities 12-75 v0, stick velocities 1e-5..1e-4 v0 and f_ss = 0.035-0.25 fn;
    N0* 0.5-50 N, slip distance* 0.03-1 mm (sets k), m = k / omega_n^2.

Cases
    none            constant drive (even seeds) or 4-6 recorded drive levels spanning a factor 4-8 (odd seeds).
    static_ageing   1-3 holds (drive 0 for 3-40 stick times, starting as a slip ends), and in half the seeds
                    also the stepped drive; the ageing-law healing b ln(t) IS the effect. Hold length calibrated
                    (<= 4 runs) to a peak growth target of 7-15 %.
    twin_branch     mu_twin = h sig g: sig = (1 + tanh((w - ln V)/0.03))/2 with w' = (ln V - w)/0.05 (a lagged
                    ln V, so sig ~ 1 while V decreases), gate g = (1 + tanh(4 ln(V / Vg)))/2, Vg = 0.06-0.14
                    of the slip peak velocity (the thesis' branch merge at low speed). h calibrated (secant) to a
                    NET decelerating-minus-accelerating difference of 12-22 % of the drop (RSF's own lag has the
                    opposite sign and is included in the net figure).
    load_variation  geometric coupling N = N0 (1 + kappa (s - s_mean)) (spring inclined to the contact);
                    kappa > 0 (70 %, pp target 13-36 %) or < 0 (30 %, pp target 12-22 %), calibrated on the
                    measured peak-to-peak. Normal channel recorded (y [mm] affine, or normal [force unit]).
    triggering      N = N0 (1 + A sin(2 pi f_tr t + phi)), recorded amplitude 3.5-7.5 % (true amplitude
                    divided by the normal sensor's attenuation), f_tr 2.5 fn .. min(8, 0.4 * coarse samples per
                    period) fn, placed half-way between harmonics of the untriggered f_ss; up to 3 frequencies
                    are tried and the one with f_tr/f_ss farthest from an integer is kept.
    drive_modulation v0 = v0n (1 + a sin(2 pi fm t + phi)), a 0.2-0.45, fm = 0.12-0.45 f_ss (re-tuned on the
                    measured f_ss); only --v0 v0n is given, no drive column.

Records: 12-40 cycles (a record the effect pushed past 40 is cut after ~38); 20-100 samples per natural
period (coarse: 10-15), interpolated from an internal >= 80 samples/period grid of the low-passed sensor states. Displacement
records `t [s],x [mm][,y [mm]][,v0 [mm/s]]` (x = spring force / k; y = affine reading of N, written for the
load cases and 25 % of the others) or force records `time [s],friction [mN|N],normal [same],position [um|mm]`
(friction = spring force, position = drive position; drive_modulation has no position); --stiffness on ~80 %
of force records; --fn on ~70 % of seeds (always for fn_off, x1.05 or x0.95); --v0 when no drive column.
Delimiter comma, semicolon or tab. Noise: sensor low-pass (in the ODE), pink (1/f) noise 0.2-1 % of the drop
rms + white 0.1-0.5 %; the normal channel its own low-pass + pink 0.05-0.3 % + white 0.05-0.3 % of N0.
Nuisances: hum 50/60 Hz + 2nd/3rd harmonic, fundamental 1-5 % of the drop; drift 2-6 % of the drop over the
record (linear + quadratic); spikes on 0.05-0.5 % of samples, +-0.3-1.5 drops; quantisation 0.2-1 % of the
drop (normal channel 0.2-1 % of N0); coarse 10-15 samples/period; fn_off. Physics depends on (case, seed)
only; the nuisance changes sampling/noise/--fn only.

Measured (params["measured"], on the noise-free record trajectory; "equal V" compares the decelerating and
accelerating halves of each slip on 13 speeds in 0.2-0.8 of the slip's peak speed, reported as % of that
slip's spring-force drop, median over slips; a low band 0.05-0.2 is reported separately; peak growth is the
regression slope of peak spring force on ln(stick time) times the ln range, in % of the median peak and of
the median drop). Seeds 0-7 of every case, nuisance NUISANCES[seed % 7] (48 records, 64 s in all):

  intrinsic memory in `none` (the RSF lag, acc. branch higher):
      hysteresis 0.2-0.8 Vmax        -0.017 .. -0.036 % of the drop
      hysteresis 0.05-0.2 Vmax       -0.25 .. -0.54 % of the drop
      peak growth, constant drive    0.002 .. 0.015 % of the peak (0.008 .. 0.033 % of the drop)
      peak growth, stepped drive     1.0 .. 1.4 % of the peak (3.9 .. 5.7 % of the drop); the growth is the
                                     ageing law's (b - a) ln(stick time), amplified ~2-4x through the drop;
                                     a -> b lowers it only slowly and loses robust stick-slip
  drop / peak (all cases)          18.6 .. 59.2 % (per-cycle min..max); stick V / v0 (median) 1.5e-5 .. 1.3e-4
  static_ageing                    peak growth 7.4 .. 16.9 % of the peak (20 .. 68 % of the drop),
                                   stick-time ratio 5.9 .. 28.6
  twin_branch                      net dec - acc 12.7 .. 19.4 % of the drop (per slip 12.7 .. 19.4 %);
                                   0.05-0.2 Vmax band 5.3 .. 13.4 %
  load_variation                   N pp 11.3 .. 24.1 % of N0 (recorded 11.2 .. 24.0 %); the friction
                                   coefficient stays single-valued (mu hysteresis -0.07 .. -0.01 % of the drop)
                                   while the friction FORCE loops by -38 .. +26 % of the drop (load effect)
  triggering                       amplitude 3.9 .. 7.4 % of N0 (recorded 3.8 .. 7.2 %), f_tr 3.3 .. 5.0 fn,
                                   f_tr / f_ss = 14.01, 22.86, 22.36, 16.71, 29.20, 14.98, 45.64, 31.20
  drive_modulation                 a 0.20 .. 0.44, fm / f_ss 0.15 .. 0.40, stick-time CV 0.11 .. 0.25
  cycles per record 14 .. 40; generation 0.5 .. 2.3 s per record (triggering 1.2 .. 5.7 s)

Not met / caveats
  * triggering: a 3-8 % load oscillation entrains RSF stick-slip (slips start near a trigger minimum), which
    pulls f_tr / f_ss onto an integer; in 2 of the 8 verified seeds (0 and 5) the best of three tried
    frequencies still ends within 0.02 of a harmonic. The measured ratio is stored (measured.ftr_over_fss).
    Triggering records also take the longest (up to ~6 s) because the solver resolves the trigger through
    the sticks.
  * triggering frequencies stay below 0.4 x the coarse sampling rate (so the same physics can be written at
    10-15 samples/period without aliasing the trigger): in practice f_tr = 2.5 .. 4-6 fn, not up to 8 fn.
  * stepped `none`: intrinsic peak growth 1.0-1.4 % of the peak is below the 2 % target but is 4-6 % of
    the drop; constant-drive `none` has none.
  * the friction FORCE in load_variation and triggering is double-valued in V because N is; mu = F/N is not.
  * Dc is tiny in absolute terms (nm) because it is tied to k/k_c = 0.0015-0.004; the weakening happens
    within ~1e-4 of the slip distance.
"""

import json
import math
import os
import sys
import time
import warnings
import zlib

import numpy as np
from scipy.integrate import solve_ivp

NAME = "ratestate"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

TWO_PI = 2.0 * math.pi
LN2 = math.log(2.0)
_ATOL = [1e-9, 1e-6, 1e-6, 1e-9, 1e-9, 1e-6]
_MAX_RECORD_SAMPLES = 150_000
_HYST_BAND = (0.2, 0.8)          # fraction of the slip's peak velocity used for "equal V" comparisons
_HYST_LOW = (0.05, 0.2)          # the low-velocity band, reported separately (state evolution / direct effect)


def _cexp(x):
    """exp with the argument clamped (LSODA trial points may wander far out)."""
    if x < -300.0:
        x = -300.0
    elif x > 300.0:
        x = 300.0
    return math.exp(x)


# --------------------------------------------------------------------------------------------------------------
# the model (dimensionless)
#   time unit 1/omega_n, force unit N0, length unit N0/k; the mass is 1, so the spring force / N0 equals the
#   spring extension s and   s' = v0(t) - V,   V' = s - 2 zeta V - n(t, s) mu,   theta' = 1 - V theta / Dc
#   mu = a asinh( V / (2 V*) exp(Psi / a) ) + twin term,   Psi = mu0 + b ln(V* theta / Dc)
# state y = [s, ln V, ln theta, s_f (sensor low-pass of s), n_f (sensor low-pass of n), w (lagged ln V)]
# --------------------------------------------------------------------------------------------------------------
class _Model:
    def __init__(self, mu0, a, b, Dc, Vs, zeta, tauf, taun, h=0.0, lnVg=0.0, eps=0.03, tauw=0.05,
                 kapN=0.0, sref=0.0, trigA=0.0, trigW=0.0, trigP=0.0, v0n=None, modA=0.0, modW=0.0, modP=0.0):
        self.mu0, self.a, self.b, self.Dc, self.Vs = mu0, a, b, Dc, Vs
        self.c = 2.0 * zeta
        self.tauf, self.taun = tauf, taun
        self.h, self.lnVg, self.eps, self.tauw = h, lnVg, eps, tauw
        self.kapN, self.sref = kapN, sref
        self.trigA, self.trigW, self.trigP = trigA, trigW, trigP
        self.v0n, self.modA, self.modW, self.modP = v0n, modA, modW, modP
        self.v0c = v0n
        self._k1 = math.log(Vs) - math.log(Dc)       # Psi = mu0 + b (k1 + ln theta)
        self._l2Vs = math.log(2.0 * Vs)

    # ---- scalar pieces ----
    def _mu(self, lnV, lnth, w):
        """mu, dmu/dlnV, dmu/dlnth, dmu/dw"""
        a, b = self.a, self.b
        lz = lnV - self._l2Vs + (self.mu0 + b * (self._k1 + lnth)) / a
        if lz > 18.0:
            m = a * (lz + LN2)
            g = 1.0
        else:
            z = math.exp(lz)
            m = a * math.asinh(z)
            g = z / math.sqrt(1.0 + z * z)
        dV = a * g
        dth = b * g
        dw = 0.0
        if self.h:
            ts = math.tanh((w - lnV) / self.eps)
            tg = math.tanh(4.0 * (lnV - self.lnVg))
            sig = 0.5 * (1.0 + ts)
            gate = 0.5 * (1.0 + tg)
            m += self.h * sig * gate
            dsig = 0.5 * (1.0 - ts * ts) / self.eps
            dgate = 2.0 * (1.0 - tg * tg)
            dV += self.h * (-dsig * gate + sig * dgate)
            dw = self.h * dsig * gate
        return m, dV, dth, dw

    def _n(self, t, s):
        n = 1.0
        if self.kapN:
            n += self.kapN * (s - self.sref)
        if self.trigA:
            n += self.trigA * math.sin(self.trigW * t + self.trigP)
        return n

    def _v0(self, t):
        if self.modA:
            return self.v0n * (1.0 + self.modA * math.sin(self.modW * t + self.modP))
        return self.v0c

    def rhs(self, t, y):
        s, lnV, lnth, sf, nf, w = y
        V = _cexp(lnV)
        m = self._mu(lnV, lnth, w)[0]
        n = self._n(t, s)
        return [self._v0(t) - V,
                (s - n * m) / V - self.c,
                _cexp(-lnth) - V / self.Dc,
                (s - sf) / self.tauf,
                (n - nf) / self.taun,
                (lnV - w) / self.tauw]

    def jac(self, t, y):
        s, lnV, lnth, sf, nf, w = y
        V = _cexp(lnV)
        m, dV, dth, dw = self._mu(lnV, lnth, w)
        n = self._n(t, s)
        J = np.zeros((6, 6))
        J[0, 1] = -V
        J[1, 0] = (1.0 - self.kapN * m) / V
        J[1, 1] = -(s - n * m) / V - n * dV / V
        J[1, 2] = -n * dth / V
        J[1, 5] = -n * dw / V
        J[2, 1] = -V / self.Dc
        J[2, 2] = -_cexp(-lnth)
        J[3, 0] = 1.0 / self.tauf
        J[3, 3] = -1.0 / self.tauf
        J[4, 0] = self.kapN / self.taun
        J[4, 4] = -1.0 / self.taun
        J[5, 1] = 1.0 / self.tauw
        J[5, 5] = -1.0 / self.tauw
        return J

    # ---- vectorised pieces (post-processing) ----
    def mu_arr(self, lnV, lnth, w):
        a, b = self.a, self.b
        lz = lnV - self._l2Vs + (self.mu0 + b * (self._k1 + lnth)) / a
        big = lz > 0
        m = np.empty_like(lz)
        m[big] = a * (lz[big] + np.log1p(np.sqrt(1.0 + np.exp(-2.0 * lz[big]))))
        m[~big] = a * np.arcsinh(np.exp(lz[~big]))
        if self.h:
            m = m + self.h * 0.25 * (1 + np.tanh((w - lnV) / self.eps)) * (1 + np.tanh(4.0 * (lnV - self.lnVg)))
        return m

    def n_arr(self, t, s):
        n = np.ones_like(t)
        if self.kapN:
            n = n + self.kapN * (s - self.sref)
        if self.trigA:
            n = n + self.trigA * np.sin(self.trigW * t + self.trigP)
        return n


def _integrate(model, y0, segments, t_eval):
    """segments: list of [ta, tb, v0c(, align)] (v0c None: the model's own modulated drive). With align true the
    segment is prolonged until the end of the next slip (V falling below twice its drive), so that a drive step
    falls at the start of a stick; the later segments are shifted by the prolongation. Returns the state on
    t_eval (NaN beyond the actual end), the end state and the actual segments [ta, tb, v0c]."""
    out = np.full((6, len(t_eval)), np.nan)
    y = np.asarray(y0, dtype=float)
    max_step = 1.0
    if model.trigA:
        max_step = min(max_step, 0.5 / model.trigW)
    shift = 0.0
    actual = []

    def run(ta, tb, y, last, events=None):
        sel = (t_eval >= ta) & ((t_eval <= tb) if last else (t_eval < tb))
        te = t_eval[sel]
        te_full = np.append(te, tb) if (te.size == 0 or te[-1] < tb) else te
        # LSODA's own first-step guess occasionally fails on this stiff system: give it one, retry smaller,
        # and fall back to Radau
        for method, fs in (("LSODA", 1e-4), ("LSODA", 1e-8), ("Radau", None)):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                sol = solve_ivp(model.rhs, (ta, tb), y, method=method, jac=model.jac, rtol=1e-6, atol=_ATOL,
                                t_eval=te_full, max_step=max_step, events=events,
                                first_step=None if fs is None else min(fs, 0.5 * (tb - ta)))
            if sol.status >= 0 and np.isfinite(sol.y).all():
                break
            sol.status = -1
        if sol.status < 0:
            raise RuntimeError("ratestate: integration failed: " + str(sol.message))
        if sol.status == 1:                     # stopped at the event
            tstop = float(sol.t_events[0][0])
            ystop = sol.y_events[0][0].copy()
            k = int(np.sum(te < tstop))
            k = min(k, sol.y.shape[1])
            out[:, np.where(sel)[0][:k]] = sol.y[:, :k]
            return ystop, tstop
        out[:, sel] = sol.y[:, :te.size]
        return sol.y[:, -1].copy(), tb

    for j, sg in enumerate(segments):
        ta, tb, v = sg[0] + shift, sg[1] + shift, sg[2]
        align = len(sg) > 3 and sg[3] and j < len(segments) - 1 and v
        if tb <= ta:
            continue
        model.v0c = v
        last = j == len(segments) - 1
        y, tend = run(ta, tb, y, last and not align)
        if align:
            lthr = math.log(2.0 * v)

            def ev(t, yy):
                return yy[1] - lthr
            ev.terminal = True
            ev.direction = -1
            y, t_al = run(tb, tb + 4.0 * (tb - ta) + 50.0, y, False, events=[ev])
            shift += t_al - tb
            tend = t_al
        actual.append([ta, tend, v])
    return out, y, actual


# --------------------------------------------------------------------------------------------------------------
# measurement on a simulated (noise-free, fine) trajectory
# --------------------------------------------------------------------------------------------------------------
def _slips(t, V, thr, gap=math.pi):
    """index runs where V > thr (runs separated by < gap merged); incomplete runs at the ends dropped."""
    m = V > thr
    if not m.any():
        return []
    d = np.diff(m.astype(np.int8))
    st = np.where(d == 1)[0] + 1
    en = np.where(d == -1)[0] + 1
    runs = []
    for i0 in st:
        j = np.searchsorted(en, i0, side="right")
        if j >= en.size:
            break
        runs.append([int(i0), int(en[j])])
    merged = []
    for r in runs:
        if merged and t[r[0]] - t[merged[-1][1]] < gap:
            merged[-1][1] = r[1]
        else:
            merged.append(r)
    return merged


def _measure(t, s, V, Ff, v0arr, thr):
    """Cycle statistics of a trajectory in dimensionless units (t, s = spring force/N0, V, Ff = friction/N0)."""
    runs = _slips(t, V, thr)
    res = {"n_slips": 0}
    if len(runs) < 3:
        res["n_slips"] = len(runs)
        return res
    peaks, mins, drops, sticks, vmax, hyst, tstart, stickV = [], [], [], [], [], [], [], []
    hyst_lo = []
    for k in range(1, len(runs)):
        p0 = runs[k - 1][1]
        i0, i1 = runs[k]
        nxt = runs[k + 1][0] if k + 1 < len(runs) else None
        ip = p0 + int(np.argmax(s[p0:i1]))
        pk = s[ip]
        if nxt is None:
            # the minimum must be reached before the record ends: require V to fall below v0 again
            tail = np.where(V[i1:] < v0arr[i1:])[0]
            if tail.size == 0:
                continue
            hi = i1 + tail[0] + 1
        else:
            hi = nxt
        mn = float(np.min(s[i0:hi]))
        peaks.append(pk)
        mins.append(mn)
        drops.append(pk - mn)
        sticks.append(t[i0] - t[p0])
        tstart.append(t[i0])
        mid = (p0 + i0) // 2
        stickV.append(V[mid] / max(v0arr[mid], 1e-300) if v0arr[mid] > 0 else np.nan)
        # branches of the slip: from the velocity maximum walk out while V > 0.1 Vmax
        lo_i = p0
        hi_i = hi
        im = lo_i + int(np.argmax(V[lo_i:hi_i]))
        Vm = V[im]
        vmax.append(Vm)
        a0 = im
        while a0 > lo_i and V[a0 - 1] > 0.04 * Vm:
            a0 -= 1
        d1 = im
        while d1 < hi_i - 1 and V[d1 + 1] > 0.04 * Vm:
            d1 += 1
        if im - a0 >= 3 and d1 - im >= 3:
            g = np.linspace(_HYST_BAND[0], _HYST_BAND[1], 13) * Vm
            va, fa = V[a0:im + 1], Ff[a0:im + 1]
            vd, fd = V[im:d1 + 1][::-1], Ff[im:d1 + 1][::-1]
            oa, od = np.argsort(va, kind="stable"), np.argsort(vd, kind="stable")
            Fa = np.interp(g, va[oa], fa[oa])
            Fd = np.interp(g, vd[od], fd[od])
            hyst.append(float(np.mean(Fd - Fa) / (pk - mn) * 100.0))
            g = np.linspace(_HYST_LOW[0], _HYST_LOW[1], 7) * Vm
            hyst_lo.append(float(np.mean(np.interp(g, vd[od], fd[od]) - np.interp(g, va[oa], fa[oa]))
                                 / (pk - mn) * 100.0))
    peaks, drops, sticks = np.array(peaks), np.array(drops), np.array(sticks)
    res.update(n_slips=len(runs), n_cycles=len(peaks), peaks=peaks, drops=drops, sticks=sticks,
               vmax=np.array(vmax), hyst=np.array(hyst), tstart=np.array(tstart), stickV=np.array(stickV))
    if len(peaks) == 0:
        return res
    res["peak_med"] = float(np.median(peaks))
    res["drop_med"] = float(np.median(drops))
    res["drop_frac_pct"] = (float(np.min(drops / peaks) * 100), float(np.max(drops / peaks) * 100))
    res["hyst_pct"] = float(np.median(res["hyst"])) if len(hyst) else float("nan")
    res["hyst_lo_pct"] = float(np.median(hyst_lo)) if len(hyst_lo) else float("nan")
    lt = np.log(sticks)
    if len(peaks) >= 3 and lt.max() - lt.min() > 0.3:
        A = np.vstack([lt, np.ones_like(lt)]).T
        slope = np.linalg.lstsq(A, peaks, rcond=None)[0][0]
        rng = lt.max() - lt.min()
        res["growth_pct_peak"] = float(slope * rng / res["peak_med"] * 100)
        res["growth_pct_drop"] = float(slope * rng / res["drop_med"] * 100)
    else:
        res["growth_pct_peak"] = float((peaks.max() - peaks.min()) / res["peak_med"] * 100)
        res["growth_pct_drop"] = float((peaks.max() - peaks.min()) / res["drop_med"] * 100)
    res["stick_time_ratio"] = float(sticks.max() / sticks.min())
    ts = res["tstart"]
    res["T_ss"] = float(np.median(np.diff(ts))) if len(ts) >= 2 else float("nan")
    res["stickV_med"] = float(np.nanmedian(res["stickV"])) if np.isfinite(res["stickV"]).any() else float("nan")
    return res


# --------------------------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------------------------
def _crc(sv):
    return zlib.crc32(sv.encode("utf-8")) & 0xFFFFFFFF


def _pink(n, rng):
    if n < 4:
        return np.zeros(n)
    X = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n)
    f[0] = f[1]
    X = X / np.sqrt(f)
    X[0] = 0.0
    x = np.fft.irfft(X, n)
    return x / (np.std(x) + 1e-300)


def _loguniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, np.ndarray):
        return [_jsonable(v) for v in o.tolist()]
    if isinstance(o, (np.floating,)):
        o = float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.bool_,)):
        return bool(o)
    if isinstance(o, float):
        if not math.isfinite(o):
            return None
        return float(f"{o:.6g}")
    return o


def _secant(hist, target, expo):
    """next value of a positive parameter p from [(p, measured)] assuming measured ~ p**expo locally (log-log
    secant once two points exist), step limited to a factor 3"""
    p2, g2 = hist[-1]
    e = expo
    if len(hist) >= 2:
        p1, g1 = hist[-2]
        if g1 > 0 and g2 > 0 and p1 != p2:
            e = (math.log(g2) - math.log(g1)) / (math.log(p2) - math.log(p1))
            e = min(max(e, 0.3), 4.0)
    f = (max(target, 1e-9) / max(g2, 1e-9)) ** (1.0 / e)
    return p2 * min(max(f, 1.0 / 3.0), 3.0)


def _sin_amp(t, x, W):
    """least-squares amplitude of a sinusoid of angular frequency W in x(t) (mean and trend removed)."""
    A = np.vstack([np.sin(W * t), np.cos(W * t), np.ones_like(t), t - t.mean()]).T
    c = np.linalg.lstsq(A, x, rcond=None)[0]
    return float(math.hypot(c[0], c[1]))


# --------------------------------------------------------------------------------------------------------------
# the generator
# --------------------------------------------------------------------------------------------------------------
def _prelim(mu0, a, b, Dc, v0n, zeta, tauf, taun, drop_guess):
    """constant-drive run of a few cycles of the plain RSF slider; returns measurement and end state."""
    model = _Model(mu0, a, b, Dc, v0n, zeta, tauf, taun, v0n=v0n)
    s0 = mu0 - 0.3 * drop_guess
    lnth0 = math.log(Dc / v0n) + 3.0
    lnV0 = math.log(v0n) + (s0 - mu0 - b * 3.0) / a
    y0 = [s0, lnV0, lnth0, s0, 1.0, lnV0]
    T_est = drop_guess / v0n + math.pi
    T = 5.0 * T_est
    t0 = 0.0
    y = y0
    for _ in range(4):
        te = np.arange(t0, t0 + T, 0.05)
        Y, y, _ = _integrate(model, y, [(t0, t0 + T, v0n)], te)
        V = np.exp(Y[1])
        m = _measure(te, Y[0], V, Y[0], np.full_like(te, v0n), 2.0 * v0n)
        if m.get("n_cycles", 0) >= 3:
            # statistics of the last cycles only (transient from the initial condition dropped)
            k = m["n_cycles"]
            last = slice(max(1, k - 2), k)
            out = {"drop": float(np.mean(m["drops"][last])), "peak": float(np.mean(m["peaks"][last])),
                   "T_ss": float(np.median(np.diff(m["tstart"][-3:]))), "vmax": float(np.mean(m["vmax"][last])),
                   "smean": float(np.mean(Y[0][len(te) // 2:])), "stick": float(np.mean(m["sticks"][last]))}
            return out, y, t0 + T
        t0 += T
        T *= 2.0
    raise RuntimeError("ratestate: no stick-slip in the preliminary run")


def _simulate(case, seed, frac_scale=1.0):
    """Draw the physics of (case, seed), run it, calibrate the effect size. Returns a dict with the
    fine dimensionless trajectory of the record window, the drive schedule and all drawn/measured quantities."""
    rng = np.random.default_rng([_crc(NAME), _crc(case), int(seed)])
    P = {}
    P["fn"] = fn = _loguniform(rng, 2.0, 200.0)
    P["zeta"] = zeta = float(rng.uniform(0.01, 0.08))
    P["sensor_fc_over_fn"] = fc = float(rng.uniform(5.0, 20.0))
    P["normal_sensor_fc_over_fn"] = fcn = float(rng.uniform(15.0, 30.0))
    tauf, taun = 1.0 / fc, 1.0 / fcn                 # dimensionless (omega_n t): tau*omega = fn / fc
    P["kc_ratio"] = kap = float(rng.uniform(0.0015, 0.004))  # k / k_c (quasi-static critical stiffness)

    stepped = False
    holds = 0
    if case == "none":
        stepped = bool(seed % 2 == 1)
    elif case == "static_ageing":
        holds = int(rng.integers(1, 4))
        stepped = bool(rng.random() < 0.5)

    # parameters: a = r b (r < 1: velocity weakening), Dc = kap (b - a) so that k / k_c = kap; with r and kap
    # fixed the stress drop scales with b (drop / b ~ 2.8 at r = 0.95, ~4.3 at r = 0.9), so b sets the drop
    if case == "static_ageing":
        mu0 = float(rng.uniform(0.4, 0.65))
        frac = float(rng.uniform(0.2, 0.36))
        r = float(rng.uniform(0.9, 0.95))
    elif case == "none" and stepped:
        # stepped baseline: a close to b keeps the intrinsic growth of the peak with stick time small
        mu0 = float(rng.uniform(0.3, 0.45))
        frac = float(rng.uniform(0.2, 0.25))
        r = float(rng.uniform(0.96, 0.975))
    elif case == "twin_branch":
        # the decelerating-branch term shortens the slips: start from larger drops
        mu0 = float(rng.uniform(0.25, 0.6))
        frac = float(rng.uniform(0.3, 0.5))
        r = float(rng.uniform(0.88, 0.93))
    else:
        mu0 = float(rng.uniform(0.25, 0.6))
        frac = float(rng.uniform(0.2, 0.45))
        r = float(rng.uniform(0.88, 0.95))
    frac = min(frac * frac_scale, 0.5)
    drop_t = frac * mu0 / (1.0 - 0.45 * frac)
    b = drop_t / (2.8 + 30.0 * (0.95 - r))
    a = r * b
    Dc = kap * (b - a)
    if stepped:
        R = _loguniform(rng, 35.0, 70.0)
    elif case == "triggering":
        R = _loguniform(rng, 12.0, 30.0)      # short cycles: the trigger must be resolved through the sticks
    else:
        R = _loguniform(rng, 15.0, 60.0)
    v0n = drop_t / (2.0 * R)

    # ---- preliminary run: calibrate the drop fraction ----
    bh = []
    for _ in range(6):
        pre, yend, _tp = _prelim(mu0, a, b, Dc, v0n, zeta, tauf, taun, drop_t)
        f_m = pre["drop"] / pre["peak"]
        bh.append((b, f_m))
        if abs(f_m / frac - 1.0) < 0.1:
            break
        b = _secant(bh, frac, 1.0)
        a = r * b
        Dc = kap * (b - a)
    P.update(mu0=mu0, a=a, b=b, a_over_b=r, Dc_dimless=Dc, drive_ratio_R=R, drop_frac_target=frac, kc_ratio=kap)
    drop0, T0, vmax0 = pre["drop"], pre["T_ss"], pre["vmax"]
    P["prelim"] = {"drop": drop0, "peak": pre["peak"], "T_ss_over_Tn": T0 / TWO_PI, "vmax_over_v0": vmax0 / v0n}

    # ---- record length and sampling ----
    P["samples_per_period"] = spp = float(rng.uniform(20.0, 100.0))
    spp_coarse = float(rng.uniform(10.0, 15.0))      # used by the 'coarse' nuisance
    P["samples_per_period_coarse"] = spp_coarse
    n_cyc = int(rng.integers(12, 21)) if case == "triggering" else int(rng.integers(12, 41))
    if case == "drive_modulation":
        P["fm_over_fss_target"] = rmod = float(rng.uniform(0.12, 0.45))
        n_cyc = max(n_cyc, int(math.ceil(1.0 / rmod + 2)))

    def T_of(v):
        return (T0 - math.pi) * v0n / v + math.pi

    # drive schedule (dimensionless time, t = 0 at the start of the main run, record window [tr0, tr1])
    if stepped:
        n_lev = int(rng.integers(4, 7))
        P["step_factor"] = fac = float(rng.uniform(4.0, 8.0))
        u = np.linspace(-0.5, 0.5, n_lev)
        rng.shuffle(u)
        levels = [v0n * fac ** float(x) for x in u]
    else:
        levels = [v0n]
    cyc_per_level = max(2, int(round(n_cyc / len(levels))))
    # sample budget
    def total_T(cpl):
        return sum(cpl * T_of(v) for v in levels)
    while cyc_per_level * len(levels) > 12 and total_T(cyc_per_level) / TWO_PI * spp > _MAX_RECORD_SAMPLES * 0.8:
        cyc_per_level -= 1
    if not stepped:
        cyc_per_level = n_cyc
        while cyc_per_level > 12 and cyc_per_level * T_of(v0n) / TWO_PI * spp > _MAX_RECORD_SAMPLES * 0.8:
            cyc_per_level -= 1
    # warm-up before the record: the plain-RSF preliminary run ends on the limit cycle, but the twin term and
    # the load coupling change the cycle, which then settles over ~10 cycles
    warm = (12.0 if case in ("twin_branch", "load_variation") else 1.6) * T_of(levels[0])
    seg = []
    tcur = 0.0
    for j, v in enumerate(levels):
        d = (cyc_per_level + (1.2 if j == len(levels) - 1 else 0.0)) * T_of(v) * float(rng.uniform(1.0, 1.15))
        if j == 0:
            d += warm
        seg.append([tcur, tcur + d, v, stepped])
        tcur += d
    tr0 = warm - float(rng.uniform(0.2, 0.6)) * T_of(levels[0])
    P["n_cycles_target"] = cyc_per_level * len(levels)
    P["drive_levels_rel"] = [v / v0n for v in levels]

    hold_info = []
    if holds:
        P["n_holds"] = holds
        H = None
    model_kw = dict(v0n=v0n)
    calib = {}
    # case-specific setup
    if case == "twin_branch":
        P["twin_target_pct"] = tw_t = float(rng.uniform(12.0, 22.0))
        P["twin_gate_frac_vmax"] = gfr = float(rng.uniform(0.06, 0.14))
        T_ = tw_t / 100.0
        model_kw.update(h=T_ * drop0 / (0.9 + 2.5 * T_), lnVg=math.log(gfr * vmax0), eps=0.03, tauw=0.05)
    elif case == "load_variation":
        # geometric coupling N = N0 (1 + kappa (s - s_ref)) (a spring inclined to the contact plane): with
        # kappa > 0 the load grows with the spring force and the drops grow; kappa < 0 weakens the stick-slip
        sign = 1.0 if rng.random() < 0.7 else -1.0
        pp_t = float(rng.uniform(13.0, 36.0)) if sign > 0 else float(rng.uniform(12.0, 22.0))
        P["load_pp_target_pct"] = pp_t
        P["load_coupling_sign"] = sign
        model_kw.update(kapN=sign * pp_t / 100.0 / drop0 * (0.6 if sign > 0 else 1.0), sref=pre["smean"])
    elif case == "triggering":
        spp_eff_min = min(spp, spp_coarse)
        qmax = min(8.0, 0.4 * spp_eff_min)
        q = float(rng.uniform(2.5, qmax))
        qss = TWO_PI / T0
        m_ = q / qss
        m_adj = math.floor(m_) + float(rng.uniform(0.3, 0.7))
        q = m_adj * qss
        if q < 2.5:
            q += qss
        if q > qmax:
            q -= qss
        A_rec = float(rng.uniform(3.5, 7.5)) / 100.0
        att = 1.0 / math.sqrt(1.0 + (q / fcn) ** 2)
        P["trig_amp_target_pct"] = A_rec * 100
        model_kw.update(trigA=A_rec / att, trigW=q, trigP=float(rng.uniform(0, TWO_PI)))
    elif case == "drive_modulation":
        P["mod_amp"] = ma = float(rng.uniform(0.2, 0.45))
        model_kw.update(modA=ma, modW=TWO_PI * rmod / T0, modP=float(rng.uniform(0, TWO_PI)))
    elif case == "static_ageing":
        P["growth_target_pct"] = g_t = float(rng.uniform(7.0, 15.0))
        H = math.exp(g_t / 100.0 * pre["peak"] / b * 1.15)
        # hold positions: cycle indices within the record, spread out
        nrec = cyc_per_level * len(levels)
        slots = np.sort(rng.choice(np.arange(2, max(nrec - 1, 3 + holds)), size=holds, replace=False))
        hold_pos = [(int(k), float(rng.uniform(0.2, 0.9))) for k in slots]

    hist = []
    mkmodel = lambda kw: _Model(mu0, a, b, Dc, v0n, zeta, tauf, taun, **kw)

    n_att = 6 if case in ("load_variation", "twin_branch") else (3 if case == "triggering" else 4)
    best = None
    for attempt in range(n_att):
        segs = [list(sg) for sg in seg]
        if holds:
            # insert holds: split the schedule at the chosen times
            H = min(max(H, 3.0), 40.0)
            th = pre["stick"] * H
            hold_info = []
            for (kc, ph) in hold_pos:
                # time of the kc-th record cycle (estimated from the schedule at that point)
                t_h = tr0 + 0.0
                acc = 0
                for sg in segs:
                    if sg[2] == 0.0:
                        continue
                    Tl = T_of(sg[2])
                    start = max(sg[0], tr0)
                    ncl = (sg[1] - start) / Tl
                    if acc + ncl > kc:
                        t_h = start + (kc - acc + ph) * Tl
                        break
                    acc += ncl
                else:
                    t_h = segs[-1][1] - 2 * T_of(segs[-1][2] or v0n)
                hold_info.append((t_h, th))
            for (t_h, th_) in sorted(hold_info, reverse=True):
                new = []
                for sg in segs:
                    if sg[0] <= t_h < sg[1] and sg[2] != 0.0:
                        new.append([sg[0], t_h, sg[2], True])      # the hold starts as the next slip ends
                        new.append([t_h, t_h + th_, 0.0, False])
                        new.append([t_h + th_, sg[1] + th_, sg[2], sg[3]])
                    elif sg[0] > t_h:
                        new.append([sg[0] + th_, sg[1] + th_, sg[2], sg[3]])
                    else:
                        new.append(sg)
                segs = new
        t_end = segs[-1][1]
        margin = sum(1.5 * T_of(sg[2]) + 60.0 for sg in segs if sg[3] and sg[2])
        spp_fine = spp * max(1, int(math.ceil(80.0 / spp)))
        dtf = TWO_PI / spp_fine
        tf = np.arange(tr0, t_end + margin, dtf)
        try:
            model = mkmodel(model_kw)
            if case == "drive_modulation":
                segs_run = [[0.0, t_end, None]]
            else:
                segs_run = segs
            y_start = np.array(yend, dtype=float)
            # start in force balance with the case's friction (load coupling / twin term change n mu)
            for _ in range(3):
                m_, dV_, _, _ = model._mu(y_start[1], y_start[2], y_start[5])
                n_ = model._n(0.0, y_start[0])
                y_start[1] += (y_start[0] - n_ * m_) / max(n_ * dV_, 1e-12)
            y_start[5] = y_start[1]
            Y, _, segs = _integrate(model, y_start, segs_run, tf)
            keep = tf <= segs[-1][1]
            tf, Y = tf[keep], Y[:, keep]
            if not np.isfinite(Y).all():
                raise RuntimeError("ratestate: incomplete trajectory")
            V = np.exp(Y[1])
            if case == "drive_modulation":
                v0a = model.v0n * (1.0 + model.modA * np.sin(model.modW * tf + model.modP))
            else:
                v0a = np.zeros_like(tf)
                for sg in segs:
                    v0a[(tf >= sg[0]) & (tf < sg[1])] = sg[2]
                v0a[tf >= segs[-1][1]] = segs[-1][2]
            n_true = model.n_arr(tf, Y[0])
            mu = model.mu_arr(Y[1], Y[2], Y[5])
            Ff = n_true * mu
            thr = 2.0 * float(np.max(v0a))
            M = _measure(tf, Y[0], V, Ff, v0a, thr)
            if M.get("n_cycles", 0) < 3:
                raise RuntimeError("ratestate: no stick-slip in the main run")
        except RuntimeError:
            # the effect was made too strong (stick-slip lost or integration failure): halve it and retry
            if case == "load_variation" and attempt < n_att - 1:
                model_kw["kapN"] *= 0.5
                hist.clear()
                continue
            if case == "twin_branch" and attempt < n_att - 1:
                model_kw["h"] *= 0.5
                hist.clear()
                continue
            raise
        # ---- calibration of the effect size ----
        ok = True
        if case == "twin_branch":
            got = M["hyst_pct"]
            calib["twin_net_pct"] = got
            hist.append((model_kw["h"], got))
            if not (10.5 <= got <= 24.5):
                ok = False
                model_kw["h"] = _secant(hist, P["twin_target_pct"], 1.5)
        elif case == "load_variation":
            got = float(np.ptp(n_true) * 100)
            calib["load_pp_pct"] = got
            hist.append((abs(model_kw["kapN"]), got))
            if not (10.5 <= got <= 39.0):
                ok = False
                model_kw["kapN"] = math.copysign(_secant(hist, P["load_pp_target_pct"], 1.0), model_kw["kapN"])
        elif case == "triggering":
            fss = TWO_PI / M["T_ss"]
            r_ = model.trigW / fss
            calib["ftr_over_fss"] = r_
            fr = r_ - math.floor(r_)
            # the trigger often entrains the stick-slip (slips start at a trigger minimum), which pulls
            # f_tr / f_ss onto an integer; try up to three trigger frequencies and keep the best
            dist = abs(fr - 0.5)
            if best is None or dist < best[0]:
                best = (dist, dict(model=model, tf=tf, Y=Y, V=V, v0a=v0a, n_true=n_true, mu=mu, Ff=Ff, M=M,
                                   segs=segs, thr=thr))
            if not ((0.2 <= fr <= 0.8) if attempt == 0 else (0.15 <= fr <= 0.85)):
                ok = False
                q = (math.floor(r_) + 0.5 + 0.25 * attempt) * fss
                qmax = min(8.0, 0.4 * min(spp, spp_coarse))
                if q > qmax:
                    q -= fss
                if q < 2.5:
                    q += fss
                att = 1.0 / math.sqrt(1.0 + (q / fcn) ** 2)
                model_kw.update(trigW=q, trigA=P["trig_amp_target_pct"] / 100.0 / att)
        elif case == "drive_modulation":
            fss = TWO_PI / M["T_ss"]
            r_ = model.modW / fss
            calib["fm_over_fss"] = r_
            if not (0.1 <= r_ <= 0.5):
                ok = False
                model_kw["modW"] = TWO_PI / M["T_ss"] * P["fm_over_fss_target"]
        elif case == "static_ageing":
            got = M["growth_pct_peak"]
            calib["growth_pct"] = got
            if not (5.5 <= got <= 19.0):
                ok = False
                lnH = math.log(H) * P["growth_target_pct"] / max(got, 0.5)
                H = math.exp(min(max(lnH, math.log(3.0)), math.log(40.0)))
        if M["n_cycles"] < 12 and attempt < n_att - 1:
            # the effect changed the cycle period: lengthen the record
            ok = False
            seg[-1][1] += (12.8 - M["n_cycles"]) * M["T_ss"]
        if ok:
            break
    P["calibration_attempts"] = attempt + 1
    P["calibration_last_measured"] = calib
    if case == "triggering" and not ok:
        b_ = best[1]
        model, tf, Y, V, v0a, n_true, mu, Ff, M, segs, thr = (b_[k] for k in (
            "model", "tf", "Y", "V", "v0a", "n_true", "mu", "Ff", "M", "segs", "thr"))
    if M["n_cycles"] > 40:
        # the effect shortened the cycles: keep the first ~38 cycles of the record
        t_cut = M["tstart"][38] + 0.5 * (M["tstart"][38] - M["tstart"][37])
        keep = tf <= t_cut
        tf, Y, V, v0a, n_true, mu, Ff = tf[keep], Y[:, keep], V[keep], v0a[keep], n_true[keep], mu[keep], Ff[keep]
        M = _measure(tf, Y[0], V, Ff, v0a, thr)
    # friction coefficient mu = F_friction / N (differs from F / N0 only when the load varies)
    Mmu = _measure(tf, Y[0], V, mu, v0a, thr)
    M["hyst_mu_pct"] = Mmu.get("hyst_pct", float("nan"))
    M["hyst_mu_lo_pct"] = Mmu.get("hyst_lo_pct", float("nan"))
    if holds:
        P["hold_durations_over_stick"] = [H] * holds
    return dict(P=P, model=model, tf=tf, Y=Y, V=V, v0a=v0a, n_true=n_true, Ff=Ff, M=M, segs=segs,
                tr0=tr0, spp=spp, spp_coarse=spp_coarse, spp_fine=spp_fine, v0n=v0n, fcn=fcn, rng=rng,
                stepped=stepped, holds=holds)


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case " + str(case))
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance " + str(nuisance))
    t_start = time.time()
    frac_sc = 1.0
    for _ in range(4):
        S = _simulate(case, seed, frac_sc)
        lo, hi = S["M"]["drop_frac_pct"]
        if lo >= 15.5 and hi <= 60.0:
            break
        frac_sc *= (16.5 / lo) if lo < 15.5 else (58.0 / hi)
    P, M, model = S["P"], S["M"], S["model"]
    rng = np.random.default_rng([_crc(NAME), _crc(case), int(seed), _crc(nuisance), 7])
    rngf = np.random.default_rng([_crc(NAME), _crc(case), int(seed), 11])   # format choices: nuisance-independent

    fn = P["fn"]
    omega = TWO_PI * fn
    # ---- physical scales ----
    N0 = _loguniform(rngf, 0.5, 50.0)                  # N
    slip_mm = _loguniform(rngf, 0.03, 1.0)             # slip distance (spring extension drop), mm
    k = N0 * P["prelim"]["drop"] / (slip_mm * 1e-3)    # N/m
    L0 = N0 / k                                        # m
    mass = k / omega ** 2
    P.update(N0_N=N0, k_N_per_m=k, mass_kg=mass, c_Ns_per_m=2 * P["zeta"] * math.sqrt(k * mass),
             Dc_mm=P["Dc_dimless"] * L0 * 1e3, Vstar_mm_s=S["v0n"] * omega * L0 * 1e3,
             v0n_mm_s=S["v0n"] * omega * L0 * 1e3, state_law="ageing (Dieterich)")

    # ---- sampling of the record from the fine grid ----
    spp = S["spp_coarse"] if nuisance == "coarse" else S["spp"]
    tf = S["tf"]
    dtr = TWO_PI / spp
    t_rec = np.arange(tf[0], tf[-1], dtr)
    # the fine grid resolves ~80 samples per period: interpolate the (smooth, low-passed) sensor states
    sf = np.interp(t_rec, tf, S["Y"][3])
    nf = np.interp(t_rec, tf, S["Y"][4])
    v0r = np.interp(t_rec, tf, S["v0a"]) if not S["stepped"] and not S["holds"] else \
        S["v0a"][np.clip(np.searchsorted(tf, t_rec, side="right") - 1, 0, len(tf) - 1)]
    # drive position (integral of v0 on the fine grid)
    u_f = np.concatenate([[0.0], np.cumsum(0.5 * (S["v0a"][1:] + S["v0a"][:-1]) * np.diff(tf))])
    u_rec = np.interp(t_rec, tf, u_f)
    n = t_rec.size
    t_phys = (t_rec - t_rec[0]) / omega
    T_rec = t_phys[-1]
    drop = M["drop_med"]                               # dimensionless (units of N0)

    # ---- noise: sensor low-pass (in the ODE) + pink + white; normal channel its own ----
    pink_pct = float(rng.uniform(0.2, 1.0))
    white_pct = float(rng.uniform(0.1, 0.5))
    main = sf + drop * (pink_pct / 100 * _pink(n, rng) + white_pct / 100 * rng.standard_normal(n))
    npink = float(rng.uniform(0.05, 0.3))
    nwhite = float(rng.uniform(0.05, 0.3))
    normal = nf + npink / 100 * _pink(n, rng) + nwhite / 100 * rng.standard_normal(n)
    noise = {"force_lowpass_fc_over_fn": P["sensor_fc_over_fn"], "pink_pct_drop": pink_pct,
             "white_pct_drop": white_pct, "normal_lowpass_fc_over_fn": P["normal_sensor_fc_over_fn"],
             "normal_pink_pct_N0": npink, "normal_white_pct_N0": nwhite}
    if nuisance == "hum":
        f_h = 50.0 if rng.random() < 0.5 else 60.0
        amp = float(rng.uniform(1.0, 5.0))
        ph = rng.uniform(0, TWO_PI, 3)
        h2, h3 = float(rng.uniform(0.2, 0.5)), float(rng.uniform(0.1, 0.35))
        hum = (np.sin(TWO_PI * f_h * t_phys + ph[0]) + h2 * np.sin(2 * TWO_PI * f_h * t_phys + ph[1])
               + h3 * np.sin(3 * TWO_PI * f_h * t_phys + ph[2]))
        main = main + amp / 100 * drop * hum
        noise.update(hum_hz=f_h, hum_pct_drop=amp, hum_h2=h2, hum_h3=h3)
    elif nuisance == "drift":
        amp = float(rng.uniform(2.0, 6.0)) * (1 if rng.random() < 0.5 else -1)
        al = float(rng.uniform(0.0, 1.0))
        x = t_phys / T_rec
        main = main + amp / 100 * drop * (al * x + (1 - al) * x * x)
        noise.update(drift_pct_drop=amp, drift_linear_share=al)
    elif nuisance == "spikes":
        fr = float(rng.uniform(0.0005, 0.005))
        ns = max(3, int(round(fr * n)))
        idx = np.unique(rng.choice(np.arange(2, n - 2), size=ns, replace=False))
        idx = idx[np.concatenate([[True], np.diff(idx) > 2])]
        main[idx] += drop * rng.uniform(0.3, 1.5, idx.size) * rng.choice([-1.0, 1.0], idx.size)
        noise.update(spike_fraction=float(idx.size / n), spike_count=int(idx.size))
    elif nuisance == "quantisation":
        q = float(rng.uniform(0.2, 1.0))
        main = np.round(main / (q / 100 * drop)) * (q / 100 * drop)
        qn = float(rng.uniform(0.2, 1.0))
        normal = np.round(normal / (qn / 100)) * (qn / 100)
        noise.update(adc_step_pct_drop=q, normal_adc_step_pct_N0=qn)
    P["noise"] = noise

    # ---- format ----
    case_has_normal = case in ("load_variation", "triggering")
    fmt_force = rngf.random() < 0.5
    delim = str(rngf.choice([",", ",", ",", ";", "\t"]))
    args = []
    fn_given = None
    give_fn = nuisance == "fn_off" or rngf.random() < 0.7
    if give_fn:
        fn_given = fn * ((1.05 if rng.random() < 0.5 else 0.95) if nuisance == "fn_off" else 1.0)
        args += ["--fn", f"{fn_given:.6g}"]
    drive_recorded = case != "drive_modulation" and (S["stepped"] or S["holds"] or fmt_force)
    cols, names, fmts = [t_phys], ["t [s]" if not fmt_force else "time [s]"], ["%.9g"]
    if fmt_force:
        funit = "mN" if (N0 < 3.0 or rngf.random() < 0.3) else "N"
        fs_ = 1e3 if funit == "mN" else 1.0
        cols.append(main * N0 * fs_)
        names.append(f"friction [{funit}]")
        fmts.append("%.7g")
        cols.append(normal * N0 * fs_)
        names.append(f"normal [{funit}]")
        fmts.append("%.7g")
        if drive_recorded:
            punit = "um" if rngf.random() < 0.5 else "mm"
            ps = 1e6 if punit == "um" else 1e3
            off = float(rngf.uniform(0, 50)) * 1e-3          # m
            cols.append((u_rec * L0 + off) * ps)
            names.append(f"position [{punit}]")
            fmts.append("%.9g")
        if rngf.random() < 0.8:
            args += ["--stiffness", f"{k:.6g}"]
            P["stiffness_given"] = True
        else:
            P["stiffness_given"] = False
        P["format"] = "force"
        P["force_unit"] = funit
    else:
        cols.append(main * L0 * 1e3)
        names.append("x [mm]")
        fmts.append("%.7g")
        if case_has_normal or rngf.random() < 0.25:
            y0 = float(rngf.uniform(-1.0, 1.0))
            gain = float(rngf.uniform(0.2, 2.0)) / N0            # mm per N
            cols.append(y0 + gain * normal * N0)
            names.append("y [mm]")
            fmts.append("%.7g")
            P["y_affine_mm"] = {"offset_mm": y0, "gain_mm_per_N": gain}
        if drive_recorded:
            cols.append(v0r * omega * L0 * 1e3)
            names.append("v0 [mm/s]")
            fmts.append("%.7g")
        P["format"] = "displacement"
    if not drive_recorded:
        args += ["--v0", f"{S['v0n'] * omega * L0 * 1e3:.6g}"]
    P["drive_recorded"] = bool(drive_recorded)
    P["delimiter"] = {",": "comma", ";": "semicolon", "\t": "tab"}[delim]
    P["samples_per_period_record"] = spp
    P["n_samples"] = n
    P["duration_s"] = T_rec

    # ---- measured effects (noise-free trajectory of this record) ----
    meas = {"n_cycles": M["n_cycles"], "n_slips": M["n_slips"],
            "drop_frac_pct_min": M["drop_frac_pct"][0], "drop_frac_pct_max": M["drop_frac_pct"][1],
            "peak_N": M["peak_med"] * N0, "drop_N": drop * N0,
            "stick_V_over_v0_median": M["stickV_med"],
            "vmax_over_v0n": float(np.median(M["vmax"]) / S["v0n"]),
            "hysteresis_dec_minus_acc_pct_drop": M["hyst_pct"],
            "hysteresis_band_vmax": list(_HYST_BAND),
            "hysteresis_low_band_pct_drop": M["hyst_lo_pct"], "hysteresis_low_band_vmax": list(_HYST_LOW),
            "hysteresis_mu_pct_drop": M["hyst_mu_pct"], "hysteresis_mu_low_band_pct_drop": M["hyst_mu_lo_pct"],
            "peak_growth_pct_peak": M["growth_pct_peak"], "peak_growth_pct_drop": M["growth_pct_drop"],
            "stick_time_ratio": M["stick_time_ratio"]}
    meas["fss_over_fn"] = float(TWO_PI / M["T_ss"])
    if case == "twin_branch":
        meas["twin_net_pct_drop"] = M["hyst_pct"]
        meas["twin_per_slip_min"] = float(np.min(M["hyst"]))
        meas["twin_per_slip_max"] = float(np.max(M["hyst"]))
        P["twin_h"] = model.h
    if case == "load_variation":
        meas["load_pp_pct_N0"] = float(np.ptp(S["n_true"]) * 100)
        meas["load_pp_recorded_pct_N0"] = float((np.percentile(nf, 99.5) - np.percentile(nf, 0.5)) * 100)
        P["load_kappa"] = model.kapN
    if case == "triggering":
        fss = TWO_PI / M["T_ss"]
        meas["trig_amp_pct_N0"] = float(model.trigA * 100)
        meas["trig_amp_recorded_pct_N0"] = _sin_amp(t_rec, nf, model.trigW) * 100
        meas["ftr_over_fn"] = float(model.trigW)
        meas["ftr_over_fss"] = float(model.trigW / fss)
        P["f_tr_hz"] = float(model.trigW * fn)
    if case == "drive_modulation":
        fss = TWO_PI / M["T_ss"]
        meas["mod_amp"] = float(model.modA)
        meas["fm_over_fss"] = float(model.modW / fss)
        meas["fm_hz"] = float(model.modW * fn)
        st = M["sticks"]
        meas["stick_time_cv"] = float(np.std(st) / np.mean(st))
    if case == "static_ageing":
        meas["hold_count"] = S["holds"]
    P["measured"] = meas
    P["gen_seconds"] = time.time() - t_start

    # ---- write ----
    os.makedirs(outdir, exist_ok=True)
    fname = os.path.abspath(os.path.join(outdir, f"{NAME}_{case}_{int(seed):03d}_{nuisance}.csv"))
    data = np.column_stack(cols)
    np.savetxt(fname, data, fmt=fmts, delimiter=delim, header=delim.join(names), comments="")
    P["gen_seconds"] = time.time() - t_start
    return _jsonable({"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": fname,
                      "args": args, "fn_true": fn, "fn_given": fn_given, "params": P})


if __name__ == "__main__":
    if len(sys.argv) < 2:
        print("usage: python ratestate.py OUTDIR [NSEEDS]")
        sys.exit(2)
    outdir = sys.argv[1]
    nseeds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    truth = []
    for c in CASES:
        for sd in range(nseeds):
            nu = NUISANCES[sd % len(NUISANCES)]
            tr = write_record(c, sd, outdir, nu)
            truth.append(tr)
            print(c, sd, nu, f"{tr['params']['gen_seconds']:.2f}s", os.path.basename(tr["file"]), flush=True)
    with open(os.path.join(outdir, "truth.json"), "w") as fh:
        json.dump(truth, fh, indent=1)
