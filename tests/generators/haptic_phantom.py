"""haptic_phantom -- evaluation records from a simulated haptics / skin-tribology bench.

Independent generator for ``lieng diagnose`` (shares no code or model with the tool).

THE RIG
-------
A silicone (PDMS / Ecoflex-like) fingertip phantom (radius R 6-10 mm, effective modulus
E* 100-600 kPa) is pressed with a constant dead load N0 = 0.5-2 N on a glass plate and
dragged by a motorised linear stage through a compliant mount (leaf-spring flexure).  A
6-axis force/torque sensor (ATI Nano17 / Mini40-like) sits between the flexure and the
phantom holder, so it reads the force transmitted by the mount (the "spring force"), the
normal load (Fz) and the torques of both about its origin (lever 12-35 mm to the contact,
contact offset +-1.5 mm).  Moving mass m (phantom + holder) 8-120 g, mount stiffness
k 300-2500 N/m, natural frequency fn 17-60 Hz, stage speed 0.1-4.5 mm/s (chosen per seed
so that a stick lasts 6-30 natural periods and the record 3-35 s), 15-40 slips.

MECHANICS (SI units inside)
  u = Xs(t) - x                      (Xs stage position, x phantom position)
  F = k u + c (dXs/dt - v) + q       (force through the mount = what the sensor reads)
  dq/dt = k1 (dXs/dt - v) - q/tau    (Maxwell arm: the phantom's viscoelastic shear;
                                      spring + Maxwell arm = a standard linear solid; a
                                      flexure in series with it is again one, so it is
                                      lumped), k1 = 2-5 % of k, tau = (0.3-3)/(2 pi fn),
                                      c from a damping ratio 0.01-0.035.
  slip:  m dv/dt = F - sgn * Ff
  fn_true = |s|/2pi of the complex pole of m s^2 + c s + k + k1 tau s/(1 + tau s).

FRICTION LAW (soft-matter, my own)
  Fa(N, t) = Cadh N^(2/3) (1 + dm (1 - exp(-t/taum)))     adhesion: tau0 * Hertz/JKR area,
             area ~ N^(2/3) so mu_adh ~ N^(-1/3); mu_s0 = Fa/N0 0.6-1.4 (tau0 is stated in
             params); dm = 0.2-0.5 % is the slow occlusion/moisture growth (taum 20-80 s).
  Ff = Fa * [1 - d (1 - exp(-v/vw))] + N b ln(1 + w/vh)
             velocity-weakening adhesion (d 0.25-0.45, vw 0.5-3 mm/s) plus the viscoelastic
             hysteresis term growing with log v (b 0.02-0.05, vh 1-8 mm/s);
  dw/dt = (|v| - w)/taul     w is the sliding speed the bulk hysteresis "feels".  In every
             case except twin_branch taul = (0.008-0.015)/fn (so the law is single-valued
             up to the small lag measured below); in twin_branch taul = (0.12-0.3)/fn and b
             0.06-0.1 calibrated by short pilot runs: the lagged hysteresis makes the friction
             higher on the decelerating half of each slip than on the accelerating half.
  static level = Fa (continuous with Ff at v = 0+).
  static_ageing only: Fs = Fa (1 + beta ln(1 + t_stick/taua)) (creep of the elastomer
             asperities, contact-area growth, taua 0.05-0.3 s); the surplus is erased over a
             slip distance Dc 5-20 um: Fa -> Fa (1 + (A0 - 1) exp(-s/Dc)).

STICK HANDLING AND INTEGRATOR (my own)
  Two modes on a fixed grid h = 1/(fs M) <= min(1/(160 fn), taul/2, 1/(24 f_trigger)).
  Stick: x frozen, v = 0; the Maxwell arm advanced exactly (linear recursion through
  scipy.signal.lfilter on the whole stick in blocks of 4096 steps), F and the static level
  evaluated vectorially; release at the first step where |F| > Fs, the crossing located by
  linear interpolation of |F| - Fs inside the step, the step split there.  Slip: classical
  fixed-step RK4 on (x, v, q, w, s) with the friction direction frozen for the slip (the law
  continued C1 past v = 0 so the step is smooth); stick onset when v changes sign inside a
  step, located by bisection on the cubic Hermite interpolant of v (v and dv/dt at both
  ends), the step re-done up to that point with RK4, the rest of the step spent stuck.  A
  slip may end in a new stick at any force (back slip allowed if |F| > Fs the other way).
  Output = every M-th grid point (decimated by a further integer for `coarse`).

THE SIX CASES ON THIS RIG
  none            constant load, constant stage speed; on seeds 4 and 7 the stage steps
                  between 3 recorded levels (factor 2-4, Stage column).
  load_variation  the phantom's leaf mount rotates as it deflects and presses the phantom
                  into the plate: N = N0 + kappa (u - u_ref) (tilt ratio 0.05-0.3 times the
                  phantom's normal stiffness); Fz recorded.
  twin_branch     lagged viscoelastic hysteresis (taul, above).
  static_ageing   contact-area creep in stick; stage speed steps (factor 4.1-6.9) and/or
                  holds of 1.5-8 sticks; Stage (encoder) position recorded.
  triggering      a vibrotactile actuator (LRA 120-260 Hz, else voice coil) in the plate
                  modulates the load N = N0 (1 + A sin(2 pi f t)), A 3.5-7 %, f = 2.8-7 fn;
                  f set so that f / f_ss(unforced) is 0.35-0.66 from an integer; if the
                  vibration lubricates the contact into micro-slips (no stick-slip), the
                  pilot lowers vw, f and A (up to 8 tries).
  drive_modulation stage speed ripple v = v0n (1 + a sin(2 pi fm t + phi)), a 22-42 %,
                  fm = 0.12-0.45 of the pilot's stick-slip frequency; only --v0 v0n given;
                  no stage column.

SENSOR AND EXPORTS
  Sliding along x (Fx = friction) or y (Fy = friction, Fx = crosstalk 0-2 % + noise); Fz =
  +-(N + 0-0.8 % crosstalk of F) (negative on about half the seeds, the sensor's
  convention); torques from the lever arm; white noise 0.15-0.35 % of the drop (floor
  0.6 mN Nano17 / 1.5 mN Mini40); untared offsets on ~40 % of seeds (forces +-0.4/0.8 N,
  torques +-15 N-mm).  fs from the RDT/DAQ rates 500-7000 Hz with 20-100 samples per natural
  period.  Formats (rotating with seed and case):
   * ATI Net F/T CSV: `Status (hex),RDT Sequence,F/T Sequence,Fx,Fy,Fz,Tx,Ty,Tz,Time` either
     with units in the names (`Fx (N)`, `Tx (N-m)`, `Time (s)`) or under an ATI metadata block
     (`Force Units:,N`, `Torque Units:,N-m`, `Time Units:,s`); status 0x00000000; no stage.
   * LabVIEW TAB export `Time (s)  Fx (N) ... Tz (N-mm) [Stage (mm)]`, decimal comma on ~30 %.
   * MATLAB writetable CSV `time_s,Fx_N,Fy_N,Fz_N,Tx_Nmm,Ty_Nmm,Tz_Nmm[,stage_mm]`, %.10g.
  Stage position: encoder (0.1-1 um resolution), absolute (5-40 mm start).
USER OPTIONS ("args")
  --fn (a tap test, +-1.2 %) on ~75 % of the seeds, always with fn_off (+-5 % exactly);
  --stiffness (static push calibration of the mount, +-2 %) on ~85 %, as N/m or "x N/mm";
  --v0 (stage setting, mm/s or "um/s") whenever the stage is not logged.
  (No --names: the helper's first version gave it on every ATI export and y-sliding record,
  a workaround for the tool's reader, which refused the ATI exports and took the crosstalk
  channel Fx as the friction of a y-sliding record; removed in stop 70, which reads both.)

NUISANCES (on top of the sensor model; physics identical across nuisances)
  hum 50/60 Hz + 2nd/3rd harmonics, half peak-to-peak 1-5 % of the drop, all channels;
  drift linear + curved, 2-6 % of the drop over the record, all channels; spikes corrupted
  packets on 0.05-0.5 % of samples, 0.3-1.5 drops, all channels at once; quantisation ADC
  step 0.2-1 % of the drop; coarse integer decimation to 10-15 samples per natural period
  (no anti-alias filter); fn_off --fn given 5 % off.

MEASURED (seeds 0-7, nuisance clean; true noise-free signals; "drop" = median force drop)
  all cases: fn 17-59 Hz, 21-97 samples/period, 15-40 slips, f_ss/fn 0.024-0.17.
  none: the law's own memory (lagged hysteresis, friction on the decelerating minus the
        accelerating half at equal speed, 0.2-0.8 of the peak speed) 0.7-3.0 % of the drop
        (median 1.6 %); Maxwell-arm force not absorbed by a constant + viscous term: rms
        0.03-0.43 %, max 0.4-2.3 % of the drop; moisture drift of the peak force over the
        record 0.09-0.45 % of the drop; load constant (Fz varies only by crosstalk/noise).
  load_variation: N peak-to-peak 14-26 % of N0 (median 23 %).  (In force terms the slip's two
        halves then differ by -16..+33 % of the drop: friction = mu N with N following u.)
  twin_branch: branch gap 14.2-20.6 % of the drop (median 18.6 %).
  static_ageing: peak (static) force growth over the record's stick-time range 7.5-15.8 %
        of the peak force (median 12.7 %) = 11-32 % of the drop; longest/shortest stick
        4.8-37; modes steps/holds/both.  Law memory other than ageing: gap -0.8..1.9 %.
  triggering: load modulation A 4.2-6.5 % of N0 (N pp 8-13 %), f/fn 2.9-6.2; the stick-slip
        locks to the vibration (f/f_ss of the record is an integer, 21-121; unforced
        0.35-0.66 from an integer); seeds 2 and 7 have a micro-slip just before each slip.
  drive_modulation: depth a 26-42 %, fm/f_ss 0.18-0.40 (f_ss of the record).
  Per record, params["measured"] holds these numbers.

A record takes 0.05-0.6 s (one triggering seed ~5 s, its pilot retries), numpy/scipy only,
deterministic in (case, seed, nuisance).
"""
import bisect
import json
import math
import os
import zlib

import numpy as np
from scipy.signal import lfilter

NAME = "haptic_phantom"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering",
         "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

TWO_PI = 2.0 * math.pi


# --------------------------------------------------------------------------- rng
def _rng(case, seed, tag):
    h = zlib.crc32(("%s|%s|%d|%s" % (NAME, case, int(seed), tag)).encode())
    return np.random.default_rng([h, int(seed) & 0xFFFFFFFF, 44])


def _u(r, a, b):
    return float(r.uniform(a, b))


# ------------------------------------------------------------------ the stage drive
class Stage:
    """Motorised linear stage: piecewise constant commanded speeds (steps, holds),
    optionally with a periodic speed ripple v(t) = v_nom * a * sin(2 pi fm t + phi)
    added (lead-screw / micro-stepping ripple)."""

    def __init__(self, knots, speeds, a=0.0, fm=0.0, phi=0.0, v_nom=0.0):
        self.tk = [float(t) for t in knots]
        self.vl = [float(v) for v in speeds]
        xk = [0.0]
        for i in range(1, len(self.tk)):
            xk.append(xk[-1] + self.vl[i - 1] * (self.tk[i] - self.tk[i - 1]))
        self.xk = xk
        self.a, self.fm, self.phi, self.vn = float(a), float(fm), float(phi), float(v_nom)
        self.om = TWO_PI * self.fm
        self._tk = np.asarray(self.tk)
        self._vl = np.asarray(self.vl)
        self._xk = np.asarray(self.xk)

    def X(self, t):
        i = bisect.bisect_right(self.tk, t) - 1
        x = self.xk[i] + self.vl[i] * (t - self.tk[i])
        if self.a:
            x += self.vn * self.a / self.om * (math.cos(self.phi) - math.cos(self.om * t + self.phi))
        return x

    def V(self, t):
        i = bisect.bisect_right(self.tk, t) - 1
        v = self.vl[i]
        if self.a:
            v += self.vn * self.a * math.sin(self.om * t + self.phi)
        return v

    def Xa(self, t):
        i = np.searchsorted(self._tk, t, side="right") - 1
        x = self._xk[i] + self._vl[i] * (t - self._tk[i])
        if self.a:
            x = x + self.vn * self.a / self.om * (math.cos(self.phi) - np.cos(self.om * t + self.phi))
        return x

    def Va(self, t):
        i = np.searchsorted(self._tk, t, side="right") - 1
        v = self._vl[i].copy()
        if self.a:
            v = v + self.vn * self.a * np.sin(self.om * t + self.phi)
        return v


# ------------------------------------------------------------------ the simulation
def _simulate(P, stage, h, n_target, tail_frac, t_max, keep_slips=False, min_drop=0.0):
    """Phantom (mass m) on a glass plate, pulled by the stage through the mount.

    Chain (sensor) force F = k u + c (vs - v) + q,  u = Xs - x,
    Maxwell arm of the phantom's shear compliance  dq/dt = k1 (vs - v) - q / tau.
    Slip:  m dv/dt = F - Ff(v, N, w, s)   (Ff the soft-matter law, see _fric)
    Stick: v = 0 until |F| exceeds the static level Fs(N, t_stick).
    Fixed-step classical RK4 in slip; exact linear recursion (lfilter) in stick;
    both transitions located inside the step (cubic Hermite root of v for the
    stick onset, linear root of F - Fs for the release) and the step re-split.
    """
    k, c, m, k1, tau = P["k"], P["c"], P["m"], P["k1"], P["tau"]
    Cadh, d, vw, b, vh, taul = P["Cadh"], P["d"], P["vw"], P["b"], P["vh"], P["taul"]
    beta, taua, Dc = P["beta"], P["taua"], P["Dc"]
    N0, Atr, omtr, phtr, kap, uref = P["N0"], P["Atr"], TWO_PI * P["ftr"], P["phtr"], P["kap"], P["uref"]
    dm, taum = P["dmoist"], P["taum"]
    X, V = stage.X, stage.V
    exp, log, sin = math.exp, math.log, math.sin
    Nfloor = 0.05 * N0

    def Nf(t, u):
        n = N0 * (1.0 + Atr * sin(omtr * t + phtr)) + kap * (u - uref)
        return n if n > Nfloor else Nfloor

    def Na(t, u):
        n = N0 * (1.0 + Atr * np.sin(omtr * t + phtr)) + kap * (u - uref)
        return np.maximum(n, Nfloor)

    def fric(t, vd, N, w, s, A0):
        Fa = Cadh * N ** (2.0 / 3.0) * (1.0 + dm * (1.0 - exp(-t / taum)))
        if A0 != 1.0:
            Fa *= 1.0 + (A0 - 1.0) * exp(-s / Dc)
        wk = 1.0 - d * (1.0 - exp(-vd / vw)) if vd > 0 else 1.0 - d * vd / vw  # C1 past v = 0
        return Fa * wk + N * b * log(1.0 + (w if w > 0 else 0.0) / vh)

    def deriv(t, x, v, q, w, s, dirn, A0):
        vs = V(t)
        u = X(t) - x
        F = k * u + c * (vs - v) + q
        N = Nf(t, u)
        vd = dirn * v
        Ff = dirn * fric(t, vd, N, w, s, A0)
        return v, (F - Ff) / m, k1 * (vs - v) - q / tau, (abs(v) - w) / taul, abs(v)

    def rk4(t, y, hh, dirn, A0):
        x, v, q, w, s = y
        a1 = deriv(t, x, v, q, w, s, dirn, A0)
        h2 = 0.5 * hh
        a2 = deriv(t + h2, x + h2 * a1[0], v + h2 * a1[1], q + h2 * a1[2], w + h2 * a1[3], s + h2 * a1[4], dirn, A0)
        a3 = deriv(t + h2, x + h2 * a2[0], v + h2 * a2[1], q + h2 * a2[2], w + h2 * a2[3], s + h2 * a2[4], dirn, A0)
        a4 = deriv(t + hh, x + hh * a3[0], v + hh * a3[1], q + hh * a3[2], w + hh * a3[3], s + hh * a3[4], dirn, A0)
        h6 = hh / 6.0
        return tuple(y[j] + h6 * (a1[j] + 2.0 * a2[j] + 2.0 * a3[j] + a4[j]) for j in range(5))

    def Fs_arr(t, N, tst0):
        Fa = Cadh * N ** (2.0 / 3.0) * (1.0 + dm * (1.0 - np.exp(-t / taum)))
        if beta:
            Fa = Fa * (1.0 + beta * np.log1p(np.maximum(t - tst0, 0.0) / taua))
        return Fa

    # storage (substep grid)
    outF, outN, outV, outFf, outX = [], [], [], [], []
    # initial state: stuck, spring preloaded
    u0 = P["F0"] / k
    x = X(0.0) - u0
    q = k1 * tau * V(0.0)
    w = 0.0
    i = 0
    tst0 = -P["tpre"]  # the contact had already been at rest for tpre
    slips = []  # dicts: t_rel, F_rel, t_end, F_end, t_stick, N_rel
    n_done = 0
    i_end = None
    L = 4096
    eh = math.exp(-h / tau)
    while True:
        # ------------------------------------------------------------- stick
        t0 = i * h
        jj = np.arange(0, L + 1)
        tj = (i + jj) * h
        vmid = stage.Va(tj[:-1] + 0.5 * h)
        bq = k1 * tau * (1.0 - eh) * vmid
        qj = np.empty(L + 1)
        qj[0] = q
        qj[1:], _ = lfilter([1.0], [1.0, -eh], bq, zi=[eh * q])
        uj = stage.Xa(tj) - x
        Fj = k * uj + c * stage.Va(tj) + qj
        Nj = Na(tj, uj)
        Fsj = Fs_arr(tj, Nj, tst0)
        wj = w * np.exp(-jj * h / taul)
        g = np.abs(Fj) - Fsj
        hit = np.nonzero(g[1:] > 0.0)[0]
        jr = int(hit[0]) + 1 if hit.size else None
        if g[0] > 0.0:
            jr = 0
        if i_end is not None and (jr is None or i + jr > i_end) and i_end - i <= L:
            nkeep = max(0, i_end - i)
            outF.append(Fj[1:nkeep + 1]); outN.append(Nj[1:nkeep + 1]); outV.append(np.zeros(nkeep))
            outFf.append(Fj[1:nkeep + 1]); outX.append(np.full(nkeep, x))
            break
        if jr is None:
            outF.append(Fj[1:]); outN.append(Nj[1:]); outV.append(np.zeros(L))
            outFf.append(Fj[1:]); outX.append(np.full(L, x))
            i += L
            q, w = float(qj[-1]), float(wj[-1])
            if i * h > t_max:
                break
            continue
        if jr == 0:
            th, jlast = 0.0, 0
            tr = t0
            qr, wr = q, w
            Fr = float(Fj[0])
        else:
            outF.append(Fj[1:jr]); outN.append(Nj[1:jr]); outV.append(np.zeros(jr - 1))
            outFf.append(Fj[1:jr]); outX.append(np.full(jr - 1, x))
            g0, g1 = g[jr - 1], g[jr]
            th = float(g0 / (g0 - g1)) if g0 < 0 else 0.0
            tr = (i + jr - 1 + th) * h
            qr = float(qj[jr - 1] + th * (qj[jr] - qj[jr - 1]))
            wr = float(wj[jr - 1] * math.exp(-th * h / taul))
            Fr = float(Fj[jr - 1] + th * (Fj[jr] - Fj[jr - 1]))
            jlast = jr - 1
        dirn = 1.0 if Fr > 0 else -1.0
        tstick = tr - tst0
        A0 = 1.0 + beta * math.log1p(max(tstick, 0.0) / taua) if beta else 1.0
        Nr = Nf(tr, X(tr) - x)
        slip = {"t_rel": tr, "F_rel": Fr, "t_stick": tstick, "N_rel": Nr, "dirn": dirn}
        # ------------------------------------------------------------- slip
        y = (x, 0.0, qr, wr, 0.0)
        tcur = tr
        hh = (i + jlast + 1) * h - tr
        i = i + jlast  # grid index of the last stored point
        sv, sF = [], []
        first = True
        while True:
            if hh <= 1e-15 * h:
                yn = y
            else:
                yn = rk4(tcur, y, hh, dirn, A0)
            vd0, vd1 = dirn * y[1], dirn * yn[1]
            if vd1 <= 0.0 and not (first and hh <= 1e-15 * h):
                # stick onset inside this step: Hermite root of v
                a0 = dirn * deriv(tcur, *y, dirn, A0)[1]
                a1 = dirn * deriv(tcur + hh, *yn, dirn, A0)[1]
                if vd0 <= 0.0:
                    thc = 1.0
                else:
                    lo, hi = 0.0, 1.0
                    for _ in range(40):
                        mid = 0.5 * (lo + hi)
                        s2, s3 = mid * mid, mid * mid * mid
                        p = ((2 * s3 - 3 * s2 + 1) * vd0 + (s3 - 2 * s2 + mid) * hh * a0
                             + (-2 * s3 + 3 * s2) * vd1 + (s3 - s2) * hh * a1)
                        if p > 0:
                            lo = mid
                        else:
                            hi = mid
                    thc = hi
                yc = rk4(tcur, y, thc * hh, dirn, A0) if thc < 1.0 else yn
                tc = tcur + thc * hh
                xc, _, qc, wc, sc = yc
                Fc = k * (X(tc) - xc) + c * V(tc) + qc
                rh = hh - thc * hh
                er = math.exp(-rh / tau)
                tm = tc + 0.5 * rh
                q = qc * er + k1 * tau * (1.0 - er) * V(tm)
                w = wc * math.exp(-rh / taul)
                x = xc
                tst0 = tc
                i += 1
                tg = i * h
                u = X(tg) - x
                Fg = k * u + c * V(tg) + q
                outF.append(np.array([Fg])); outN.append(np.array([Nf(tg, u)])); outV.append(np.zeros(1))
                outFf.append(np.array([Fg])); outX.append(np.array([x]))
                slip.update({"t_end": tc, "F_end": Fc, "dist": sc})
                if keep_slips:
                    sv.append(0.0)
                    sF.append(dirn * fric(tc, 0.0, Nf(tc, X(tc) - xc), wc, sc, A0))
                    slip["v"] = np.array(sv)
                    slip["Ff"] = np.array(sF)
                slips.append(slip)
                break
            y = yn
            tcur = tcur + hh
            i += 1
            hh = h
            first = False
            xg, vg, qg, wg, sg = y
            tg = i * h
            u = X(tg) - xg
            Fg = k * u + c * (V(tg) - vg) + qg
            Ng = Nf(tg, u)
            Ffg = dirn * fric(tg, dirn * vg, Ng, wg, sg, A0)
            outF.append(np.array([Fg])); outN.append(np.array([Ng])); outV.append(np.array([vg]))
            outFf.append(np.array([Ffg])); outX.append(np.array([xg]))
            if keep_slips:
                sv.append(vg)
                sF.append(Ffg)
            if i * h > t_max:
                break
        if i * h > t_max:
            break
        if abs(slips[-1]["F_rel"] - slips[-1]["F_end"]) >= min_drop:
            n_done += 1
        if n_done >= n_target and i_end is None:
            tst = slips[-1]["t_end"] - slips[-1]["t_rel"] + np.median([s_["t_stick"] for s_ in slips[1:]] or [0.1])
            i_end = i + int(tail_frac * tst / h) + 1
    F = np.concatenate(outF)
    return {"F": F, "N": np.concatenate(outN), "v": np.concatenate(outV),
            "Ff": np.concatenate(outFf), "x": np.concatenate(outX),
            "t": h * np.arange(1, F.size + 1), "slips": slips}


# ------------------------------------------------------------------ parameters
def _fn_true(P):
    """Undamped natural frequency |s|/2pi of the tangential mode's complex pole
    (mass on the mount: spring k, dashpot c, Maxwell arm k1, tau)."""
    m, c, k, k1, tau = P["m"], P["c"], P["k"], P["k1"], P["tau"]
    r = np.roots([m * tau, m + c * tau, c + k * tau + k1 * tau, k])
    r = r[np.abs(r.imag) > 1e-9]
    return float(np.abs(r[0]) / TWO_PI)


def _base_params(r):
    P = {}
    while True:
        k = _u(r, 300.0, 2500.0)
        fn0 = _u(r, 15.0, 60.0)
        m = k / (TWO_PI * fn0) ** 2
        if 0.008 <= m <= 0.12:
            break
    P["k"], P["m"] = k, m
    zeta = _u(r, 0.01, 0.035)
    P["c"] = 2.0 * zeta * math.sqrt(k * m)
    P["k1"] = _u(r, 0.02, 0.05) * k
    P["tau"] = _u(r, 0.3, 3.0) / (TWO_PI * fn0)
    P["N0"] = _u(r, 0.5, 2.0)
    mu_s = _u(r, 0.6, 1.4)
    P["mu_s0"] = mu_s
    P["Cadh"] = mu_s * P["N0"] ** (1.0 / 3.0)       # Fs = Cadh N^(2/3)
    P["R_mm"] = _u(r, 6.0, 10.0)
    P["Estar_kPa"] = _u(r, 100.0, 600.0)
    a = (3.0 * P["N0"] * P["R_mm"] * 1e-3 / (4.0 * P["Estar_kPa"] * 1e3)) ** (1.0 / 3.0)
    P["contact_radius_mm"] = a * 1e3
    P["tau0_kPa"] = mu_s * P["N0"] / (math.pi * a * a) / 1e3
    P["d"] = _u(r, 0.25, 0.45)
    P["vw"] = _u(r, 0.5, 3.0) * 1e-3
    P["b"] = _u(r, 0.02, 0.05)
    P["vh"] = _u(r, 1.0, 8.0) * 1e-3
    P["taul"] = _u(r, 0.008, 0.015) / fn0
    P["beta"], P["taua"], P["Dc"] = 0.0, 1.0, 1e-5
    P["Atr"], P["ftr"], P["phtr"] = 0.0, 0.0, 0.0
    P["kap"], P["uref"] = 0.0, 0.0
    P["dmoist"] = _u(r, 0.002, 0.005)
    P["taum"] = _u(r, 20.0, 80.0)
    P["v0"] = _u(r, 0.4, 3.0) * 1e-3
    P["F0frac"] = _u(r, 0.35, 0.85)
    P["F0"] = P["F0frac"] * mu_s * P["N0"]
    P["tpre"] = _u(r, 0.5, 4.0)
    P["n_target"] = int(r.integers(15, 41))
    P["tail"] = _u(r, 0.2, 0.8)
    P["fn0"] = fn0
    return P


def _h_for(P, fs):
    hmax = min(1.0 / (160.0 * P["fn_true"]), 0.5 * P["taul"])
    if P.get("ftr"):
        hmax = min(hmax, 1.0 / (24.0 * P["ftr"]))
    M = max(1, int(math.ceil(1.0 / (hmax * fs))))
    return 1.0 / (fs * M), M


def _pilot(P, stage, h, n=6, keep=False, min_drop=0.0):
    s = _simulate(P, stage, h, n, 0.1, 60.0, keep_slips=keep, min_drop=min_drop)
    sl = s["slips"]
    if min_drop > 0:
        sl = [x for x in sl if abs(x["F_rel"] - x["F_end"]) >= min_drop]
    if len(sl) < 4:
        return None, s
    drops = [x["F_rel"] - x["F_end"] for x in sl[1:]]
    trel = [x["t_rel"] for x in sl]
    info = {"drop": float(np.median(drops)), "Tc": float(np.median(np.diff(trel[1:]))) if len(trel) > 2 else float(np.diff(trel)[0]),
            "Tslip": float(np.median([x["t_end"] - x["t_rel"] for x in sl[1:]])),
            "Frel": float(np.median([x["F_rel"] for x in sl[1:]])),
            "Fend": float(np.median([x["F_end"] for x in sl[1:]]))}
    return info, s


# ------------------------------------------------------------------ measurements
def _branch_gap(slips, drop_ref=None):
    """Per slip: friction on the decelerating minus the accelerating half at equal
    sliding speed (0.2-0.8 of the slip's peak speed), over the slip's force drop."""
    out = []
    for s in slips:
        if "v" not in s or s["v"].size < 8:
            continue
        v = s["dirn"] * s["v"]
        Ff = s["dirn"] * s["Ff"]
        j = int(np.argmax(v))
        vm = v[j]
        if j < 3 or v.size - j < 3 or vm <= 0:
            continue
        va, fa = np.concatenate([[0.0], v[:j + 1]]), np.concatenate([[s["F_rel"] * s["dirn"]], Ff[:j + 1]])
        vd, fd = v[j:][::-1], Ff[j:][::-1]
        grid = np.linspace(0.2, 0.8, 25) * vm
        ia = np.argsort(va)
        idd = np.argsort(vd)
        ga = np.interp(grid, va[ia], fa[ia])
        gd = np.interp(grid, vd[idd], fd[idd])
        drop = s["F_rel"] - s["F_end"] if drop_ref is None else drop_ref
        drop = abs(drop)
        if drop > 0:
            out.append(float(np.mean(gd - ga) / drop))
    return out


def _measure(sim, P, stage, case):
    md = P.get("min_drop", 0.0)
    sl = [s_ for s_ in sim["slips"] if abs(s_["F_rel"] - s_["F_end"]) >= md]
    M = {"n_micro_slips": len(sim["slips"]) - len(sl)}
    drops = np.array([abs(s["F_rel"] - s["F_end"]) for s in sl])
    M["n_slips"] = len(sl)
    M["drop_median_N"] = float(np.median(drops[1:])) if len(sl) > 1 else float(drops[0])
    trel = np.array([s["t_rel"] for s in sl])
    M["f_ss_Hz"] = float((len(trel) - 2) / (trel[-1] - trel[1])) if len(trel) > 3 else float("nan")
    M["record_s"] = float(sim["t"][-1])
    gaps = _branch_gap(sl[1:])
    if gaps:
        M["branch_gap_pct_of_drop"] = 100.0 * float(np.median(gaps))
        M["branch_gap_pct_range"] = [100.0 * float(np.min(gaps)), 100.0 * float(np.max(gaps))]
    Nt = sim["N"]
    M["N_pp_pct_of_N0"] = 100.0 * float(np.percentile(Nt, 99.5) - np.percentile(Nt, 0.5)) / P["N0"]
    pk = np.array([s["F_rel"] for s in sl[1:]])
    tr = trel[1:]
    if pk.size > 3:
        A = np.vstack([tr, np.ones_like(tr)]).T
        if case in ("none", "twin_branch", "load_variation", "triggering", "drive_modulation"):
            slope = np.linalg.lstsq(A, pk, rcond=None)[0][0]
            M["peak_trend_pct_of_drop_over_record"] = 100.0 * float(slope * (tr[-1] - tr[0]) / M["drop_median_N"])
    # Maxwell-arm memory: q not absorbed by a constant + viscous term
    ts = sim["t"]
    q = sim["F"] - P["k"] * (stage.Xa(ts) - sim["x"]) - P["c"] * (stage.Va(ts) - sim["v"])
    A = np.vstack([stage.Va(ts) - sim["v"], np.ones_like(ts)]).T
    coef = np.linalg.lstsq(A, q, rcond=None)[0]
    M["sls_memory_rms_pct_of_drop"] = 100.0 * float(np.std(q - A @ coef) / M["drop_median_N"])
    M["sls_memory_max_pct_of_drop"] = 100.0 * float(np.max(np.abs(q - A @ coef)) / M["drop_median_N"])
    tst = np.array([s["t_stick"] for s in sl[1:]])
    M["stick_time_range_s"] = [float(tst.min()), float(tst.max())] if tst.size else None
    if case == "static_ageing" and tst.size:
        fa = lambda t: 1.0 + P["beta"] * math.log1p(t / P["taua"])
        g = fa(tst.max()) / fa(tst.min()) - 1.0
        M["ageing_growth_pct_of_peak"] = 100.0 * g
        # the same in force: Fs(N0) times the ageing factors
        Fs0 = P["Cadh"] * P["N0"] ** (2.0 / 3.0)
        M["ageing_growth_pct_of_drop"] = 100.0 * Fs0 * (fa(tst.max()) - fa(tst.min())) / M["drop_median_N"]
        ish, ilg = int(np.argmin(tst)), int(np.argmax(tst))
        M["peak_force_short_long_N"] = [float(pk[ish]), float(pk[ilg])]
    if case == "triggering":
        M["trigger_amp_pct_of_N0"] = 100.0 * P["Atr"]
        M["f_trigger_over_fn"] = P["ftr"] / P["fn_true"]
        rr = P["ftr"] / M["f_ss_Hz"]
        M["f_trigger_over_f_ss"] = rr
        M["f_trigger_frac_of_f_ss_multiple"] = rr - math.floor(rr)
    if case == "drive_modulation":
        M["mod_depth_pct"] = 100.0 * stage.a
        M["fm_over_f_ss"] = stage.fm / M["f_ss_Hz"]
    return M


# ------------------------------------------------------------------ building a record
FS_LIST = (500, 1000, 1500, 2000, 2500, 3000, 4000, 5000, 7000)


def _settle_v0(P, r):
    """Choose the stage speed so that a stick lasts rho natural periods (stick-slip
    well below fn, as on the bench), the record stays below ~30 s."""
    fn = P["fn_true"]
    rho_hi = min(30.0, 30.0 * fn / P["n_target"])
    rho = _u(r, 6.0, max(6.5, rho_hi))
    P["rho_target"] = rho
    h = min(1.0 / (160.0 * fn), 0.5 * P["taul"])
    for _ in range(6):
        st = Stage([0.0], [P["v0"]])
        info, _s = _pilot(P, st, h, n=6)
        if info is None:          # steady sliding: slower stage, deeper weakening
            P["v0"] *= 0.5
            P["d"] = min(0.55, P["d"] * 1.1)
            continue
        tstk = info["Tc"] - info["Tslip"]
        want = rho / fn - info["Tslip"]
        if abs(tstk / want - 1.0) < 0.1:
            break
        P["v0"] = float(np.clip(P["v0"] * tstk / want, 0.05e-3, 10e-3))
    return info


def _choose_fs(P, r, nuisance):
    fn = P["fn_true"]
    ok = [f for f in FS_LIST if 20.0 <= f / fn <= 100.0]
    fs = float(ok[int(r.integers(len(ok)))]) if ok else float(round(fn * _u(r, 25, 80), -1))
    D = 1
    if nuisance == "coarse":
        spp = fs / fn
        cands = [dd for dd in range(2, 12) if 10.0 <= spp / dd <= 15.0]
        D = cands[0] if cands else int(round(spp / 12.5))
    return fs, D


def _build(case, seed, nuisance):
    r = _rng(case, seed, "phys")
    P = _base_params(r)
    P["fn_true"] = _fn_true(P)
    rf = _rng(case, seed, "format")
    fmt = ["ati", "labview", "matlab"][(seed + CASES.index(case)) % 3]
    if case == "static_ageing" and fmt == "ati":
        fmt = "labview" if seed % 2 else "matlab"
    stage_logged = case == "static_ageing" or (case != "drive_modulation" and fmt != "ati" and rf.random() < 0.5)
    if case == "none":
        stage_logged = fmt != "ati" and seed % 8 in (1, 4, 5, 7)
    info = _settle_v0(P, r)
    fs, D = _choose_fs(P, _rng(case, seed, "fs"), "clean")
    if nuisance == "coarse":
        _, D = _choose_fs(P, _rng(case, seed, "fs"), "coarse")
    # stick-slip pilot on the final grid
    h, Msub = _h_for(P, fs)
    st = Stage([0.0], [P["v0"]])
    info, _ = _pilot(P, st, h, n=6, keep=True)
    P["pilot"] = info
    v0 = P["v0"]
    stage = Stage([0.0], [v0])
    rc = _rng(case, seed, "case")
    if case == "none" and stage_logged and seed % 8 in (4, 7):
        # drive steps between a few recorded levels (no ageing in the law)
        fac = _u(rc, 2.0, 4.0)
        lev = [v0, v0 / fac, v0] if rc.random() < 0.5 else [v0 / fac, v0, v0 * 0.5]
        nper = P["n_target"] / 3.0
        tk = [0.0]
        for j, vv in enumerate(lev[:-1]):
            tk.append(tk[-1] + nper * info["drop"] / (P["k"] * vv) + nper * info["Tslip"])
        stage = Stage(tk, lev)
        P["drive_levels_mm_s"] = [1e3 * x for x in lev]
    elif case == "load_variation":
        p = _u(rc, 0.15, 0.32)
        sgn = 1.0 if rc.random() < 0.7 else -1.0
        P["uref"] = 0.5 * (info["Frel"] + info["Fend"]) / P["k"]
        P["kap"] = sgn * p * P["N0"] * P["k"] / info["drop"]
        P["mount_tilt_ratio"] = _u(rc, 0.05, 0.3)
        P["normal_contact_stiffness_N_per_m"] = abs(P["kap"]) / P["mount_tilt_ratio"]
        for _ in range(3):
            i2, s2 = _pilot(P, stage, h, n=6)
            if i2 is None:
                P["kap"] *= 0.7
                continue
            pp = (np.percentile(s2["N"], 99.5) - np.percentile(s2["N"], 0.5)) / P["N0"]
            if 0.12 <= pp <= 0.36:
                break
            P["kap"] *= p / pp
        P["normal_contact_stiffness_N_per_m"] = abs(P["kap"]) / P["mount_tilt_ratio"]
    elif case == "twin_branch":
        Tn = 1.0 / P["fn_true"]
        P["taul"] = _u(rc, 0.12, 0.3) * Tn
        target = _u(rc, 0.13, 0.21)
        P["b"] = _u(rc, 0.06, 0.1)
        P["twin_target"] = target
        for _ in range(5):
            i2, s2 = _pilot(P, stage, h, n=6, keep=True)
            if i2 is None:
                P["b"] *= 0.7
                continue
            g = float(np.median(_branch_gap(s2["slips"][1:])))
            if abs(g / target - 1.0) < 0.12:
                break
            P["b"] *= (target / max(g, 1e-3)) ** 0.8
        info = i2 or info
    elif case == "static_ageing":
        fac = _u(rc, 4.0, 8.0)
        mode = ["steps", "holds", "both"][seed % 3]
        v_hi = v0 * math.sqrt(fac) if v0 * math.sqrt(fac) < 8e-3 else v0
        v_lo = v_hi / fac
        P["taua"] = _u(rc, 0.05, 0.3)
        P["Dc"] = _u(rc, 5e-6, 20e-6)
        tstick = lambda vv: info["drop"] / (P["k"] * vv)
        P["n_target"] = max(P["n_target"], 20)
        nseg = max(4, int(round(P["n_target"] / (3.0 if mode == "holds" else 4.0))))
        tk, lev = [0.0], []
        holds = []
        seq = []
        if mode in ("steps", "both"):
            pat = [v_hi, v_lo, v_hi, v_lo]
            for vv in pat:
                seq.append(("run", vv, int(rc.integers(max(2, nseg - 2), nseg + 2))))
        else:
            seq = [("run", v_hi, nseg), ("run", v_hi, nseg), ("run", v_hi, nseg)]
            v_lo = v_hi
        if mode in ("holds", "both"):
            th = [_u(rc, 3.0, 8.0) * tstick(v_lo), _u(rc, 1.5, 4.0) * tstick(v_lo)]
            seq.insert(1, ("hold", 0.0, th[0]))
            seq.insert(3 if mode == "holds" else 4, ("hold", 0.0, th[1]))
            holds = th
        t = 0.0
        for kind, vv, nn in seq:
            lev.append(vv)
            if kind == "run":
                dur = nn * (tstick(vv) + info["Tslip"]) + 0.5 * tstick(vv)
            else:
                dur = nn
            t += dur
            tk.append(t)
        lev.append(v_hi)
        stage = Stage(tk, lev)
        t_short = tstick(v_hi)
        t_long = max(tstick(v_lo), max(holds) + 0.6 * tstick(v_hi) if holds else 0.0)
        G = _u(rc, 0.08, 0.15)
        P["beta"] = G / math.log((1.0 + t_long / P["taua"]) / (1.0 + t_short / P["taua"]))
        P["ageing_mode"] = mode
        P["drive_levels_mm_s"] = [1e3 * x for x in lev]
        P["drive_knots_s"] = tk
        P["n_target"] = 10 ** 6   # the schedule sets the length
        P["t_end_schedule"] = t
    elif case == "triggering":
        P["Atr"] = _u(rc, 0.035, 0.07)
        P["phtr"] = _u(rc, 0.0, TWO_PI)
        rr = _u(rc, 2.8, 7.0)
        drop0 = info["drop"]
        for _ in range(8):
            f_ss = 1.0 / info["Tc"]
            ftr = rr * P["fn_true"]
            n = ftr / f_ss
            frac = n - math.floor(n)
            if not 0.3 <= frac <= 0.7:
                ftr = (math.floor(n) + 0.5) * f_ss
            P["ftr"] = ftr
            P["f_trigger_over_f_ss_unforced"] = ftr / f_ss
            h, Msub = _h_for(P, fs)
            i2, _s2 = _pilot(P, stage, h, n=8, min_drop=0.4 * drop0)
            if i2 is not None and i2["drop"] > 0.6 * drop0:
                break
            # the vibration lubricates the contact (micro-slips, no stick-slip):
            # a steeper weakening and a lower actuator frequency for this phantom
            P["vw"] *= 0.7
            rr = max(2.6, rr * 0.85)
            P["Atr"] = max(0.032, P["Atr"] * 0.9)
            info = _pilot(P, Stage([0.0], [v0]), h, n=6)[0] or info
            drop0 = info["drop"]
        P["actuator"] = "LRA" if 120.0 <= ftr <= 260.0 else "voice coil"
        P["min_drop"] = 0.4 * drop0
    elif case == "drive_modulation":
        f_ss = 1.0 / info["Tc"]
        a = _u(rc, 0.22, 0.42)
        fm = _u(rc, 0.12, 0.45) * f_ss
        stage = Stage([0.0], [v0], a=a, fm=fm, phi=_u(rc, 0, TWO_PI), v_nom=v0)
        P["mod_a"], P["mod_fm"] = a, fm
        P["n_target"] = max(P["n_target"], int(math.ceil(2.2 * f_ss / fm)))
        P["n_target"] = min(P["n_target"], 40)
    if case == "static_ageing":
        sim = _simulate(P, stage, h, 10 ** 6, 0.0, P["t_end_schedule"] + 0.7 * info["drop"] / (P["k"] * v0 * 2), keep_slips=True)
    else:
        sim = _simulate(P, stage, h, P["n_target"], P["tail"], 90.0, keep_slips=True,
                        min_drop=P.get("min_drop", 0.0))
    P["fs"], P["M_sub"], P["h"], P["D_coarse"] = fs, Msub, h, D
    P["format"], P["stage_logged"] = fmt, bool(stage_logged)
    meas = _measure(sim, P, stage, case)
    return P, stage, sim, meas, info


# ------------------------------------------------------------------ sensor and export
def _write_table(path, header_lines, cols, fmts, sep, decimal_comma=False):
    arr = np.column_stack(cols)
    n = arr.shape[0]
    lines = list(header_lines)
    rowfmt = sep.join(fmts)
    ints = [j for j, f in enumerate(fmts) if f.endswith(("d", "X"))]
    rows = arr.tolist()
    if ints:
        for row in rows:
            for j in ints:
                row[j] = int(row[j])
    body = [rowfmt % tuple(row) for row in rows]
    txt = "\n".join(lines + body) + "\n"
    if decimal_comma:
        # a German-locale LabVIEW: decimal comma, TAB separated
        hdr = "\n".join(lines)
        txt = hdr + "\n" + "\n".join(body).replace(".", ",") + "\n"
    with open(path, "w", newline="\n") as f:
        f.write(txt)
    return n


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case %r" % (case,))
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % (nuisance,))
    seed = int(seed)
    P, stage, sim, meas, info = _build(case, seed, nuisance)
    fs, Msub, D = P["fs"], P["M_sub"], P["D_coarse"]
    step = Msub * D
    fs_out = fs / D
    # samples at t = j * step * h (sim index n <-> t = (n + 1) h)
    idx = np.arange(step - 1, sim["F"].size, step)
    t = sim["t"][idx]
    t = t - t[0]
    F = sim["F"][idx]
    Nn = sim["N"][idx]
    Xs = stage.Xa(sim["t"][idx])
    n = t.size
    drop = meas["drop_median_N"]

    # ---------------------------------------------------------------- sensor model
    rs = _rng(case, seed, "sensor")
    axis = "y" if rs.random() < 0.4 else "x"
    sz = -1.0 if rs.random() < 0.5 else 1.0
    tared = rs.random() < 0.6
    sensor = "Nano17" if P["N0"] * P["mu_s0"] < 2.0 and rs.random() < 0.6 else "Mini40"
    L_mm = _u(rs, 12.0, 35.0)      # sensor origin to contact (lever of the torques)
    ex, ey = _u(rs, -1.5, 1.5), _u(rs, -1.5, 1.5)
    eps_t, eps_z = _u(rs, -0.02, 0.02), _u(rs, -0.008, 0.008)
    sig = max(_u(rs, 0.0015, 0.0035) * drop, 0.0006 if sensor == "Nano17" else 0.0015)
    rn = _rng(case, seed, "noise")
    Ft = F + sig * rn.standard_normal(n)
    Fo = eps_t * F + sig * rn.standard_normal(n)
    Fz = sz * (Nn + eps_z * F) + 1.5 * sig * rn.standard_normal(n)
    if axis == "x":
        Fx, Fy = Ft, Fo
    else:
        Fx, Fy = Fo, Ft
    Fzp = sz * Nn
    Lm = L_mm
    Tx = (ey * Fzp + Lm * Fy) + 0.3 * Lm * sig * rn.standard_normal(n)
    Ty = (-Lm * Fx - ex * Fzp) + 0.3 * Lm * sig * rn.standard_normal(n)
    Tz = (ex * Fy - ey * Fx) + 0.05 * Lm * sig * rn.standard_normal(n)
    off = {}
    if not tared:
        off = {"Fx": _u(rs, -0.4, 0.4), "Fy": _u(rs, -0.4, 0.4), "Fz": _u(rs, -0.8, 0.8),
               "Tx": _u(rs, -15, 15), "Ty": _u(rs, -15, 15), "Tz": _u(rs, -5, 5)}
        Fx = Fx + off["Fx"]; Fy = Fy + off["Fy"]; Fz = Fz + off["Fz"]
        Tx = Tx + off["Tx"]; Ty = Ty + off["Ty"]; Tz = Tz + off["Tz"]
    chans = {"Fx": Fx, "Fy": Fy, "Fz": Fz, "Tx": Tx, "Ty": Ty, "Tz": Tz}   # N, N-mm

    # ---------------------------------------------------------------- nuisances
    rnu = _rng(case, seed, "nuis-" + nuisance)
    nz = {}
    fric_key = "F" + axis
    if nuisance == "hum":
        fmains = 50.0 if rnu.random() < 0.6 else 60.0
        amp = _u(rnu, 0.01, 0.05) * drop
        for kname in chans:
            scale = (1.0 if kname.startswith("F") else L_mm) * _u(rnu, 0.5, 1.0) if kname != fric_key else 1.0
            sgl = np.zeros(n)
            for hk, rel in ((1, 1.0), (2, _u(rnu, 0.1, 0.4)), (3, _u(rnu, 0.2, 0.5))):
                sgl += rel * np.sin(TWO_PI * hk * fmains * t + _u(rnu, 0, TWO_PI))
            sgl *= amp / (np.max(sgl) - np.min(sgl)) * 2.0  # amp = half the pp
            chans[kname] = chans[kname] + scale * sgl
        nz = {"mains_Hz": fmains, "hum_amplitude_pct_of_drop": 100.0 * amp / drop}
    elif nuisance == "drift":
        amp = _u(rnu, 0.02, 0.06) * drop * (1 if rnu.random() < 0.5 else -1)
        tt = t / t[-1]
        curv = _u(rnu, -0.5, 0.5)
        shape = tt + curv * tt * (tt - 1.0)
        for kname in chans:
            scale = 1.0 if kname == fric_key else (_u(rnu, -1, 1) * (1.0 if kname.startswith("F") else L_mm))
            chans[kname] = chans[kname] + scale * amp * shape
        nz = {"drift_pct_of_drop_over_record": 100.0 * amp / drop, "curvature": curv}
    elif nuisance == "spikes":
        frac = _u(rnu, 0.0005, 0.005)
        ns = max(3, int(round(frac * n)))
        where = np.sort(rnu.choice(np.arange(5, n - 5), size=ns, replace=False))
        for kname in chans:
            scale = 1.0 if kname.startswith("F") else L_mm
            mag = rnu.uniform(0.3, 1.5, ns) * drop * np.where(rnu.random(ns) < 0.5, -1.0, 1.0)
            chans[kname][where] = chans[kname][where] + scale * mag
        nz = {"spike_fraction": ns / n, "n_spikes": int(ns)}
    elif nuisance == "quantisation":
        qs = _u(rnu, 0.002, 0.01) * drop
        for kname in chans:
            qq = qs if kname.startswith("F") else qs * L_mm
            chans[kname] = np.round(chans[kname] / qq) * qq
        nz = {"adc_step_N": qs, "adc_step_pct_of_drop": 100.0 * qs / drop}

    # ---------------------------------------------------------------- user options
    ru = _rng(case, seed, "user")
    u_fn, u_sgn, u_err, u_k, u_kerr, u_kfmt, u_vfmt = ru.random(7)
    give_fn = (nuisance == "fn_off") or (u_fn < 0.75)
    fn_true = P["fn_true"]
    fn_given = None
    if nuisance == "fn_off":
        fn_given = fn_true * (1.0 + (0.05 if u_sgn < 0.5 else -0.05))
    elif give_fn:
        fn_given = fn_true * (1.0 + 0.012 * (2.0 * u_err - 1.0))   # a tap test on the mount
    give_k = u_k < 0.85
    k_given = P["k"] * (1.0 + 0.02 * (2.0 * u_kerr - 1.0))       # quasi-static push calibration
    args = []
    if fn_given is not None:
        args += ["--fn", "%.2f" % fn_given]
    if give_k:
        if u_kfmt < 0.5:
            args += ["--stiffness", "%.0f" % k_given]
        else:
            args += ["--stiffness", "%.3f N/mm" % (k_given / 1000.0)]
    if not P["stage_logged"]:
        v_nom = P["v0"] * 1e3
        if u_vfmt < 0.7:
            args += ["--v0", "%.3g" % v_nom]
        else:
            args += ["--v0", "%.0f um/s" % (v_nom * 1e3)]

    # ---------------------------------------------------------------- file
    os.makedirs(outdir, exist_ok=True)
    fmt = P["format"]
    base = "%s_%s_s%d_%s" % (NAME, case, seed, nuisance)
    rfmt = _rng(case, seed, "format2")
    stage_mm = (Xs * 1e3) + _u(rfmt, 5.0, 40.0)
    enc = rfmt.choice([0.0001, 0.0005, 0.001])
    stage_mm = np.round(stage_mm / enc) * enc
    fmt_detail = {}
    if fmt == "ati":
        path = os.path.join(outdir, base + ".csv")
        units_in_names = rfmt.random() < 0.5
        seq0 = int(rfmt.integers(1000, 60000))
        rdt = np.arange(1, n + 1, dtype=float)
        ftseq = seq0 + np.arange(n, dtype=float) * int(round(7000 / fs_out)) if fs_out <= 7000 else seq0 + np.arange(n)
        Tconv = 1e-3    # N-mm -> N-m
        cols = [np.zeros(n), rdt, ftseq, chans["Fx"], chans["Fy"], chans["Fz"],
                chans["Tx"] * Tconv, chans["Ty"] * Tconv, chans["Tz"] * Tconv, t]
        fmts = ["0x%08X", "%d", "%d", "%.6f", "%.6f", "%.6f", "%.7f", "%.7f", "%.7f", "%.6f"]
        if units_in_names:
            hdr = ["Status (hex),RDT Sequence,F/T Sequence,Fx (N),Fy (N),Fz (N),Tx (N-m),Ty (N-m),Tz (N-m),Time (s)"]
        else:
            hdr = ["Final Calibration Name:,FT%05d" % int(rfmt.integers(10000, 99999)),
                   "Calibration Index:,1",
                   "Counts per Force:,1000000",
                   "Counts per Torque:,1000000",
                   "Force Units:,N",
                   "Torque Units:,N-m",
                   "Time Units:,s",
                   "Status (hex),RDT Sequence,F/T Sequence,Fx,Fy,Fz,Tx,Ty,Tz,Time"]
        _write_table(path, hdr, cols, fmts, ",")
        fmt_detail = {"ati_units_in_names": bool(units_in_names)}
    elif fmt == "labview":
        path = os.path.join(outdir, base + ".txt")
        dc = rfmt.random() < 0.3
        names = ["Time (s)", "Fx (N)", "Fy (N)", "Fz (N)", "Tx (N-mm)", "Ty (N-mm)", "Tz (N-mm)"]
        cols = [t, chans["Fx"], chans["Fy"], chans["Fz"], chans["Tx"], chans["Ty"], chans["Tz"]]
        fmts = ["%.6f", "%.6f", "%.6f", "%.6f", "%.4f", "%.4f", "%.4f"]
        if P["stage_logged"]:
            names.append("Stage (mm)"); cols.append(stage_mm); fmts.append("%.4f")
        _write_table(path, ["\t".join(names)], cols, fmts, "\t", decimal_comma=dc)
        fmt_detail = {"decimal_comma": bool(dc)}
    else:
        path = os.path.join(outdir, base + ".csv")
        names = ["time_s", "Fx_N", "Fy_N", "Fz_N", "Tx_Nmm", "Ty_Nmm", "Tz_Nmm"]
        cols = [t, chans["Fx"], chans["Fy"], chans["Fz"], chans["Tx"], chans["Ty"], chans["Tz"]]
        fmts = ["%.10g"] * 7
        if P["stage_logged"]:
            names.append("stage_mm"); cols.append(stage_mm); fmts.append("%.10g")
        _write_table(path, [",".join(names)], cols, fmts, ",")
    # (the helper that wrote this generator gave --names on every ATI export and every y-sliding record, as a
    # user's workaround: the tool then refused the ATI exports and read Fx on a rig sliding along y; the
    # reader reads both since stop 70, and a user is not expected to know the workaround)
    params = {k_: v_ for k_, v_ in P.items() if k_ not in ("pilot",)}
    params.update({"slide_axis": axis, "Fz_sign": sz, "tared": bool(tared), "sensor": sensor,
                   "lever_mm": L_mm, "contact_offset_mm": [ex, ey], "crosstalk_tangential": eps_t,
                   "crosstalk_normal": eps_z, "noise_N": sig, "offsets": off, "fs_out": fs_out,
                   "samples_per_period": fs_out / fn_true, "n_rows": int(n), "nuisance_params": nz,
                   "k_given": k_given if give_k else None, "measured": meas, "format_detail": fmt_detail,
                   "stiffness_true_static_N_per_m": P["k"], "mass_kg": P["m"]})
    params = json.loads(json.dumps(params, default=_jsonable))
    return {"generator": NAME, "case": case, "seed": seed, "nuisance": nuisance,
            "file": os.path.abspath(path), "args": args, "fn_true": float(fn_true),
            "fn_given": None if fn_given is None else float(fn_given), "params": params}


def _jsonable(o):
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    return str(o)
