"""Independent stick-slip record generator: an elastomer (rubber) sled on glass.

Written without reading the diagnosis code (only tests/generators/README.md). numpy only.

RIG. A sled of mass m (0.15-0.8 kg) on a rubber pad, pulled over a glass plate by a soft spring k through a load
cell in the pull line (the line has a small dashpot, 1-3 % of critical); the drive pulls the spring's far end at
v0(t). fn = sqrt(k/m)/2pi (3-12 Hz). The sled also PITCHES on its pad (second, lightly damped DoF, 3-7 fn,
zeta 0.02-0.05): the moment of the pull line above the pad and of the friction at the pad
(r_pull F_line + r_contact F_fric) transfers load dN from back to front; the pads' real contact grows
sublinearly with their load (exponent 0.75-0.88), so the effective load is N (((1+d)^p + (1-d)^p)/2),
d = 2 dN/N, and a weak pitch-heave coupling (1-3 %) puts eps dN on the total load. The pitch rings after each slip
(front/back transfer 4-20 % of N0 p-p) but moves the total normal load only 0.09-0.5 % of N0 p-p and the
effective load 0.08-0.9 % (measured, all non-load cases, seeds 0-7).

LAW. Grosch-type bell in log speed on a hysteresis step: mu = mu_k v^2/(v^2 + vs^2) + mu_a (1 + beta a) B,
B = exp(-(ln(ve/vp)/w)^2), w going smoothly (tanh in ln v) from w1 (1.0-1.4) below the peak to w2 (0.75-0.85 of
ln(v_slip/vp)) above it; ve = v a_T is the WLF-reduced speed, log10 a_T = -C1 T/(C2 + T) (C1 8-9.5,
C2 90-110 K), mu -> 0 as v -> 0 (odd in v). The peak sits at vp = 0.25-0.8 % of the slowest drive, so the
stick is a slow creep up the rising (adhesive) branch and stick-slip comes from the falling branch.
Contact temperature T = Tf + Tb: a flash part dTf/dt = (Gf F v - Tf)/tau_f and a slower surface layer
dTb/dt = (Gb F v - Tb)/tau_b that cools during the stick with its own time constant (2-6 Tn). Heating shifts
the curve to higher speed along ln v (memory). The contact age a (0..1) creeps in at rest,
da/dt = (1 - a)/tau_a - |v| a / D_a (saturating viscoelastic creep of the rubber into the glass' roughness,
erased over D_a = 5 % of the slip), and only matters where beta > 0.

STICK HANDLING. None: the sliding speed is a continuous state, carried as s = asinh(v/vr) (vr = 1e-3 vp) so the
creep branch is a smooth log-like relaxation; the sled creeps up the rising branch in stick. Measured stick creep
(sled over drive displacement from arrest, v < 0.05 v0, to the peak force): mean 0.25-3.3 % of v0 (max 3.8 %)
outside triggering, 2.5-4.3 % (max 5.3 %) in triggering (faster drive, short sticks).

INTEGRATOR. Own variable-step, variable-coefficient BDF2 (backward-Euler start) with a simplified Newton
(finite-difference Jacobian reused over steps, refreshed on slow convergence or every 12 steps), local error from
the corrector minus a quadratic extrapolation predictor (2/11 factor), step ratio 0.2-3. Accepted steps are
interpolated onto a fine uniform grid (>= 320 points per natural period) for the ground truth and the sensor.

DEPARTURES (sizes MEASURED on the noise-free truth, seeds 0-7, in params["measured"]):
 - none: constant drive (stepped 2-3x between recorded levels on seeds 2, 5 mod 8). Own memory (thermal):
   twin (decelerating minus accelerating friction at equal true speed, 0.15-0.85 of each slip's peak speed,
   over the drop) +0.32..+0.71 %; on the stepped records peak vs ln(stick time) -2.1..-1.1 % of the drop over
   2.0-2.4x stick times (inertial overshoot, no ageing in the law).
 - load_variation: even seeds a pull line at an angle, N = N0 - F_line sin(theta) (the load follows the spring
   force, F against v then reads +17..+37 % twin, F/N against v +0.7..+1.4 %); odd seeds a wavy glass plate,
   N = N0 (1 + c sin(2 pi x_sled/lambda + phi)), 1.6-3.5 waves per record. Total load p-p 12.1-35.0 % of N0.
   Normal channel recorded.
 - twin_branch: a strong, lagging flash temperature (tau_f 6-10 % Tn against 0.3-0.8 % in the other cases, heating gain
   3.1-6.9 against 0.5-1.0 (units of 1/(mu_a N0 v_scale/2)), contact up to 8-15 K against 1-6 K): the decelerating half runs hotter, the reduced speed is lower, so the friction on the falling
   branch is higher: +11.9..+18.8 % of the drop (F/N: +11.5..+18.8 %).
 - static_ageing: beta > 0 with tau_a ~ the geometric mean stick time; even seeds drive steps 4.2-7.8x, odd
   seeds holds (drive stopped 1-9 stick-slip periods); peak force growth over the record's range of stick times
   (least-squares line in ln t_stick) +7.2..+10.3 % of the drop over 5.6-11x stick times. Drive recorded
   (position or v0 column).
 - triggering: the normal load shaken, N = N0 (1 + A sin(2 pi f_t t)), A 3.3-4.5 % of N0 (p-p 6.8-9.2 %),
   f_t 2.5-4.3 fn away from the pitch mode, f_t/f_ss 3.4-6.3 (0.24-0.50 from an integer; the slips lock readily,
   f_t is re-aimed between locking tongues and the best of up to 7 runs kept). Normal channel recorded.
 - drive_modulation: v0(t) = v0n (1 + a sin(2 pi fm t + phi)), a 0.25-0.39, fm/f_ss 0.15-0.44; only v0n given.

RECORDS. Force records (seed + case index even): `time [s],friction [N|mN][,normal [N|mN]][,position [mm|um] or
v0 [mm/s]]` with --stiffness; displacement records: `time [s],x [mm][,y [mm]][,v0 [mm/s]]` (x = F/k, y an affine
reading of the total normal load). Separator comma, semicolon, TAB or whitespace (whitespace: `t[s] F[N]`), a `#`
comment line on about a third. 20-100 samples per natural period (10-15 for `coarse`), 16-39 complete stick-slip
cycles in the record. Sensor: load cell with a one-pole low-pass at 5-20 fn, white noise 0.2-0.6 % and 1/f noise
0.1-0.3 % of the drop; normal channel its own one-pole and 0.1-0.3 % of N0 noise. Nuisances as in the README
(hum 50/60 Hz + 2 harmonics 1-5 % of the drop, drift 2-6 %, spikes 0.05-0.5 % of samples at 0.2-1 drop,
ADC step 0.2-1 %, coarse, fn_off +-5 %). --fn given on 7 of 8 seeds per case (all for triggering), --v0 when no
drive column. 0.4-2.3 s a record (one core).
"""
import math
import os
import bisect

import numpy as np

NAME = "rubber_sled"

CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
LN10 = math.log(10.0)


# ----------------------------------------------------------------------------------------------
# drive
# ----------------------------------------------------------------------------------------------
class Drive:
    """Piecewise-constant drive speed with cosine ramps, optional slow sinusoidal modulation."""

    def __init__(self, levels, t_breaks, t_ramp, mod_a=0.0, mod_f=0.0, mod_phi=0.0):
        self.levels = list(levels)          # level i holds from t_breaks[i] (after a ramp)
        self.tb = list(t_breaks)            # t_breaks[0] = 0
        self.tr = float(t_ramp)
        self.a = float(mod_a)
        self.wm = 2.0 * math.pi * float(mod_f)
        self.phi = float(mod_phi)

    def __call__(self, t):
        i = bisect.bisect_right(self.tb, t) - 1
        if i < 0:
            i = 0
        lv = self.levels[i]
        if i > 0:
            dt = t - self.tb[i]
            if dt < self.tr:
                l0 = self.levels[i - 1]
                lv = l0 + (lv - l0) * 0.5 * (1.0 - math.cos(math.pi * dt / self.tr))
        if self.a != 0.0:
            lv *= 1.0 + self.a * math.sin(self.wm * t + self.phi)
        return lv


# ----------------------------------------------------------------------------------------------
# the rig: sled on a pull spring, rubber pad on glass, pitch mode, contact temperature, contact age
# ----------------------------------------------------------------------------------------------
class Rig:
    """states y = [e, s, Tf, Tb, dN, dNd, a]
    e   spring extension (m), drive position minus sled position
    s   asinh(v / vr): the sliding speed on a log-like scale (v = vr sinh s)
    Tf  flash temperature excess of the contact (K)
    Tb  bulk (pad surface layer) temperature excess (K)
    dN  front-minus-half load transfer by the pitch of the sled (N); dNd its rate
    a   contact age state (0 fresh .. 1 fully crept-in rubber contact)
    """

    def __init__(self, P, drive):
        self.P = P
        self.drive = drive
        self.m = P["m"]; self.k = P["k"]; self.c = P["c_line"]
        self.vr = P["vr"]; self.vp = P["vp"]; self.vs = P["vs"]
        self.w1 = P["w1"]; self.w2 = P["w2"]
        self.muk = P["mu_k"]; self.mua = P["mu_a"]; self.beta = P["beta_age"]
        self.C1 = P["wlf_C1"]; self.C2 = P["wlf_C2"]
        self.Gf = P["G_flash"]; self.tf = P["tau_flash"]; self.Gb = P["G_bulk"]; self.tb = P["tau_bulk"]
        self.wp = 2 * math.pi * P["f_pitch"]; self.zp = P["zeta_pitch"]
        self.r1 = P["r_pull"]; self.r2 = P["r_contact"]; self.eh = P["eps_heave"]; self.pp = P["pad_exp"]
        self.taur = P["tau_age"]; self.Dc = P["D_age"]
        self.N0 = P["N0"]
        self.load_mode = P.get("load_mode", "const")
        self.sin_th = P.get("sin_theta", 0.0)
        self.wav_c = P.get("wave_c", 0.0); self.wav_k = P.get("wave_k", 0.0); self.wav_phi = P.get("wave_phi", 0.0)
        self.v0c = P.get("v0_const", 0.0)
        self.tr_A = P.get("trig_A", 0.0); self.tr_w = 2 * math.pi * P.get("trig_f", 0.0)

    def mu(self, v_abs, T, a):
        """steady friction coefficient of the rubber on glass at sliding speed v_abs and contact temperature T"""
        if v_abs <= 0.0:
            return 0.0
        lnaT = -LN10 * self.C1 * T / (self.C2 + T)
        ve = v_abs * math.exp(lnaT)
        x = math.log(ve / self.vp)
        w = self.w1 + (self.w2 - self.w1) * 0.5 * (1.0 + math.tanh(x))
        B = math.exp(-(x / w) ** 2)
        S = ve * ve / (ve * ve + self.vs * self.vs)
        return self.muk * S + self.mua * (1.0 + self.beta * a) * B

    def normal(self, t, e, Fs, dN):
        if self.load_mode == "angle":
            nb = self.N0 - Fs * self.sin_th
        elif self.load_mode == "wave":
            x = self.v0c * t - e
            nb = self.N0 * (1.0 + self.wav_c * math.sin(self.wav_k * x + self.wav_phi))
        elif self.load_mode == "shaker":
            nb = self.N0 * (1.0 + self.tr_A * math.sin(self.tr_w * t))
        else:
            nb = self.N0
        Nt = nb + self.eh * dN
        d = 2.0 * dN / Nt
        if d > 0.95:
            d = 0.95
        elif d < -0.95:
            d = -0.95
        Ne = Nt * 0.5 * ((1.0 + d) ** self.pp + (1.0 - d) ** self.pp)
        return Nt, Ne

    def aux(self, t, y):
        e, s, Tf, Tb, dN, dNd, a = y
        v = self.vr * math.sinh(s)
        v0 = self.drive(t)
        Fs = self.k * e + self.c * (v0 - v)
        Nt, Ne = self.normal(t, e, Fs, dN)
        T = Tf + Tb
        mu = self.mu(abs(v), T, a)
        Ff = Ne * mu if v >= 0 else -Ne * mu
        return v, v0, Fs, Nt, Ne, Ff, T

    def f(self, t, y):
        e, s, Tf, Tb, dN, dNd, a = y
        v, v0, Fs, Nt, Ne, Ff, T = self.aux(t, y)
        acc = (Fs - Ff) / self.m
        ds = acc / math.sqrt(self.vr * self.vr + v * v)
        P = Ff * v
        av = abs(v)
        return np.array([
            v0 - v,
            ds,
            (self.Gf * P - Tf) / self.tf,
            (self.Gb * P - Tb) / self.tb,
            dNd,
            self.wp * self.wp * (self.r1 * Fs + self.r2 * Ff - dN) - 2.0 * self.zp * self.wp * dNd,
            (1.0 - a) / self.taur - av / self.Dc * a,
        ])


# ----------------------------------------------------------------------------------------------
# own integrator: variable-step, variable-coefficient BDF2 with simplified Newton
# ----------------------------------------------------------------------------------------------
def _jac(f, t, y, f0, scale):
    n = len(y)
    J = np.empty((n, n))
    for j in range(n):
        d = 1e-7 * max(abs(y[j]), scale[j])
        yp = y.copy(); yp[j] += d
        J[:, j] = (f(t, yp) - f0) / d
    return J


def bdf2(f, y0, t_end, h0, hmax, atol, rtol=2e-4, max_steps=400000):
    n = len(y0)
    scale = np.asarray(atol) * 1e3
    atol = np.asarray(atol)
    I = np.eye(n)
    T = [0.0]; Y = [np.array(y0, float)]
    t = 0.0; y = np.array(y0, float)
    # first step: backward Euler with a tiny step
    h = h0
    f0 = f(t, y)
    J = _jac(f, t, y, f0, scale)
    yn = y + h * f0
    for _ in range(8):
        G = yn - y - h * f(t + h, yn)
        yn = yn - np.linalg.solve(I - h * J, G)
    t += h; y = yn
    T.append(t); Y.append(y.copy())
    hprev = h
    Jage = 0
    nsteps = 0
    while t < t_end and nsteps < max_steps:
        nsteps += 1
        h = min(h, hmax, t_end - t) if t_end - t > 1e-12 else h
        om = h / hprev
        a1 = (1 + om) ** 2 / (1 + 2 * om)
        a2 = om * om / (1 + 2 * om)
        g = h * (1 + om) / (1 + 2 * om)
        ym1 = Y[-2]
        psi = a1 * y - a2 * ym1
        # predictor: quadratic extrapolation through t_{n-1}, t_n and the slope at t_n
        # (Lagrange through three last points)
        tm1 = T[-2]
        tn1 = t + h
        if len(Y) >= 3:
            tm2 = T[-3]; ym2 = Y[-3]
            L0 = (tn1 - tm1) * (tn1 - t) / ((tm2 - tm1) * (tm2 - t))
            L1 = (tn1 - tm2) * (tn1 - t) / ((tm1 - tm2) * (tm1 - t))
            L2 = (tn1 - tm2) * (tn1 - tm1) / ((t - tm2) * (t - tm1))
            yp = L0 * ym2 + L1 * ym1 + L2 * y
        else:
            yp = y + om * (y - ym1)
        yn = yp.copy()
        M = I - g * J
        ok = False
        for attempt in range(2):
            yn = yp.copy()
            conv = False
            dnorm_prev = None
            for it in range(6):
                G = yn - g * f(tn1, yn) - psi
                dy = np.linalg.solve(M, -G)
                yn = yn + dy
                dn = np.max(np.abs(dy) / (atol + rtol * np.abs(yn)))
                if dn < 0.3:
                    conv = True
                    break
                if dnorm_prev is not None and dn > 0.8 * dnorm_prev:
                    break
                dnorm_prev = dn
            if conv:
                ok = True
                break
            if attempt == 0 and Jage > 0:
                J = _jac(f, t, y, f(t, y), scale)
                Jage = 0
                M = I - g * J
            else:
                break
        if not ok:
            h *= 0.3
            J = _jac(f, t, y, f(t, y), scale); Jage = 0
            if h < 1e-14:
                raise RuntimeError("bdf2: step too small")
            continue
        Jage += 1
        err = np.max(np.abs(yn - yp) / (atol + rtol * np.abs(yn))) * (2.0 / 11.0)
        if err > 1.0:
            h *= max(0.2, 0.9 * err ** (-1.0 / 3.0))
            continue
        hprev = h
        t = tn1; y = yn
        T.append(t); Y.append(y)
        fac = 0.9 * err ** (-1.0 / 3.0) if err > 1e-10 else 3.0
        h *= min(3.0, max(0.5, fac))
        if Jage > 12:
            J = _jac(f, t, y, f(t, y), scale); Jage = 0
    return np.array(T), np.array(Y)


# ----------------------------------------------------------------------------------------------
# ground-truth evaluation on a fine uniform grid
# ----------------------------------------------------------------------------------------------
def dense(rig, T, Y, dt):
    """linear interpolation of the accepted steps onto a uniform grid, then the derived signals"""
    tg = np.arange(0.0, T[-1], dt)
    Yg = np.empty((len(tg), Y.shape[1]))
    for j in range(Y.shape[1]):
        Yg[:, j] = np.interp(tg, T, Y[:, j])
    n = len(tg)
    out = {k: np.empty(n) for k in ("v", "v0", "Fs", "Nt", "Ne", "Ff", "T")}
    for i in range(n):
        r = rig.aux(tg[i], Yg[i])
        for k, val in zip(("v", "v0", "Fs", "Nt", "Ne", "Ff", "T"), r):
            out[k][i] = val
    out["t"] = tg
    out["e"] = Yg[:, 0]
    out["dN"] = Yg[:, 4]
    out["a"] = Yg[:, 6]
    return out


def slips(tr, skip_first=True):
    """slip segments from the true sliding speed; peak force, drop, stick time, creep for each"""
    t, v, v0, Fs = tr["t"], tr["v"], tr["v0"], tr["Fs"]
    vmax = np.max(v)
    vth = 0.1 * vmax
    above = v > vth
    idx = np.flatnonzero(np.diff(above.astype(int)))
    starts = [i + 1 for i in idx if not above[i]]
    ends = [i + 1 for i in idx if above[i]]
    segs = []
    for s0 in starts:
        e_ = [e for e in ends if e > s0]
        if not e_:
            break
        segs.append((s0, e_[0]))
    res = []
    for j in range(1, len(segs)):
        s_prev, e_prev = segs[j - 1]
        s0, e0 = segs[j]
        nxt = segs[j + 1][0] if j + 1 < len(segs) else None
        if nxt is None:
            break
        # window of the stick before this slip: from the end of the previous slip to this slip's peak speed
        ipk_v = s0 + int(np.argmax(v[s0:e0]))
        ipk = e_prev + int(np.argmax(Fs[e_prev:ipk_v + 1]))
        imin = e0 + int(np.argmin(Fs[e0:nxt]))
        # arrest: first time after the previous slip that v < 0.05 v0
        vloc = np.maximum(v0, 1e-30)
        ar = np.flatnonzero(v[e_prev:ipk] < 0.05 * vloc[e_prev:ipk])
        if len(ar) == 0:
            creep = np.nan; iar = e_prev
        else:
            iar = e_prev + ar[0]
            dx_sled = np.trapezoid(v[iar:ipk + 1], t[iar:ipk + 1])
            dx_drive = np.trapezoid(v0[iar:ipk + 1], t[iar:ipk + 1])
            creep = dx_sled / dx_drive if dx_drive > 0 else np.nan
        res.append(dict(i_start=s0, i_end=e0, i_peakF=ipk, i_min=imin, i_arrest=iar,
                        t_start=t[s0], Fpk=Fs[ipk], Fmin=Fs[imin], drop=Fs[ipk] - Fs[imin],
                        t_stick=t[s0] - t[e_prev], vpk=v[ipk_v], creep=creep, i_prev_end=e_prev))
    return res


def twin_measure(tr, S):
    """decelerating minus accelerating friction at equal true sliding speed (0.15..0.85 of the slip's peak)
    averaged over the speed window, divided by the slip's force drop"""
    t, v, Ff = tr["t"], tr["v"], tr["Ff"]
    vals = []
    for s in S:
        i0 = s["i_peakF"]; i1 = s["i_min"]
        seg_v = v[i0:i1 + 1]
        ipk = int(np.argmax(seg_v))
        vpk = seg_v[ipk]
        va, fa = seg_v[:ipk + 1], Ff[i0:i0 + ipk + 1]
        vd, fd = seg_v[ipk:][::-1], Ff[i0 + ipk:i1 + 1][::-1]
        grid = np.linspace(0.15, 0.85, 41) * vpk
        # keep the monotone parts
        ma = np.maximum.accumulate(va); md = np.maximum.accumulate(vd)
        ka = np.concatenate(([True], np.diff(ma) > 0)); kd = np.concatenate(([True], np.diff(md) > 0))
        Fa = np.interp(grid, ma[ka], fa[ka]); Fd = np.interp(grid, md[kd], fd[kd])
        vals.append(np.mean(Fd - Fa) / s["drop"])
    return np.array(vals)


def ageing_measure(S):
    """peak force against stick time: a least-squares line in ln(t_stick), its rise between the shortest and the
    longest stick divided by the mean drop"""
    if len(S) < 4:
        return float("nan"), float("nan")
    ts = np.array([s["t_stick"] for s in S]); fp = np.array([s["Fpk"] for s in S])
    dr = np.mean([s["drop"] for s in S])
    lt = np.log(ts)
    if np.ptp(lt) < 1e-6:
        return 0.0, 1.0
    A = np.vstack([lt, np.ones_like(lt)]).T
    coef = np.linalg.lstsq(A, fp, rcond=None)[0]
    return float(coef[0] * np.ptp(lt) / dr), float(ts.max() / ts.min())


# ----------------------------------------------------------------------------------------------
# simulation driver
# ----------------------------------------------------------------------------------------------
def _atol(P):
    return [1e-5 * P["N0"] / P["k"], 2e-3, 1e-2, 1e-2, 1e-4 * P["N0"],
            1e-4 * P["N0"] * 2 * math.pi * P["f_pitch"], 1e-4]


def _simulate(P, drive, t_end):
    rig = Rig(P, drive)
    fn = P["fn"]
    y0 = [0.3 * P["mu_k"] * P["N0"] / P["k"], math.asinh(0.1 * P["vp"] / P["vr"]), 0.0, 0.0, 0.0, 0.0, 1.0]
    hmax = 0.05 / fn
    if P.get("trig_f", 0.0) > 0:
        hmax = min(hmax, 0.05 / P["trig_f"])
    T, Y = bdf2(rig.f, y0, t_end, 1e-6 / fn, hmax, _atol(P))
    return rig, T, Y


def _quick(P, T, Y):
    """slip starts and force drops straight from the accepted steps (pre-runs)"""
    v = P["vr"] * np.sinh(Y[:, 1]); F = P["k"] * Y[:, 0]
    vth = 0.1 * v.max()
    up = np.flatnonzero((v[1:] > vth) & (v[:-1] <= vth)) + 1
    ts = T[up]
    drops = []
    for j in range(len(up) - 1):
        seg = F[up[j]:up[j + 1]]
        drops.append(F[up[j]] - seg.min())
    return ts, np.array(drops), v.max()


def _u(rng, a, b):
    return float(rng.uniform(a, b))


def _draw(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([20261127, ci, int(seed)])
    P = {}
    fn = _u(rng, 3.0, 12.0); m = _u(rng, 0.15, 0.8)
    w = 2 * math.pi * fn; k = m * w * w
    N0 = _u(rng, 3.0, 25.0)
    P.update(fn=fn, m=m, k=k, N0=N0, c_line=2 * _u(rng, 0.01, 0.03) * math.sqrt(k * m))
    P.update(mu_k=_u(rng, 0.6, 0.8), mu_a=_u(rng, 0.4, 0.6), w1=_u(rng, 1.0, 1.4))
    vsc = P["mu_a"] * N0 / (m * w)
    P["v_scale"] = vsc
    P.update(wlf_C1=_u(rng, 8.0, 9.5), wlf_C2=_u(rng, 90.0, 110.0))
    Gref = 1.0 / (P["mu_a"] * N0 * 0.5 * vsc)
    P.update(tau_flash=_u(rng, 0.003, 0.008) / fn, G_flash=_u(rng, 0.5, 1.0) * Gref,
             tau_bulk=_u(rng, 2.0, 6.0) / fn, G_bulk=_u(rng, 0.5, 1.0) * Gref)
    P.update(f_pitch=_u(rng, 3.0, 7.0) * fn, zeta_pitch=_u(rng, 0.02, 0.05), r_pull=_u(rng, 0.04, 0.08),
             r_contact=_u(rng, 0.04, 0.08), eps_heave=_u(rng, 0.01, 0.03), pad_exp=_u(rng, 0.75, 0.88))
    P.update(beta_age=0.0, tau_age=1.0 / fn, D_age=0.05 * P["mu_a"] * N0 / k)
    # drive
    q = _u(rng, 0.09, 0.16)
    if case == "triggering":
        q = _u(rng, 0.24, 0.34)
    v0 = q * vsc
    P["v0_nominal"] = v0
    levels = [v0]; fac = 1.0
    P["drive_kind"] = "constant"
    if case == "static_ageing":
        if seed % 2 == 0:
            P["drive_kind"] = "steps"; fac = _u(rng, 4.2, 7.8)
        else:
            P["drive_kind"] = "holds"
    elif case == "none" and seed % 8 in (2, 5):
        P["drive_kind"] = "steps"; fac = _u(rng, 2.0, 3.0)
    P["step_factor"] = fac
    vmin = v0 / fac
    P["vp"] = vmin * (_u(rng, 0.0025, 0.004) if case == "triggering" else _u(rng, 0.004, 0.008))
    xs = math.log(0.5 * vsc / P["vp"])
    P["w2"] = xs * _u(rng, 0.75, 0.85)
    P["vs"] = P["vp"] * _u(rng, 0.2, 0.4)
    P["vr"] = 1e-3 * P["vp"]
    P["n_cycles_target"] = int(rng.integers(18, 41))
    if case == "static_ageing":
        P["n_cycles_target"] = int(rng.integers(22, 36))
    if case == "twin_branch":
        P["tau_flash"] = _u(rng, 0.06, 0.1) / fn
        P["G_flash"] = _u(rng, 3.0, 4.5) * Gref
        P["twin_target"] = _u(rng, 0.12, 0.21)
    if case == "load_variation":
        P["load_mode"] = "angle" if seed % 2 == 0 else "wave"
        P["Npp_target"] = _u(rng, 0.13, 0.35)
    if case == "triggering":
        P["load_mode"] = "shaker"
        P["trig_A"] = _u(rng, 0.031, 0.045)
    if case == "drive_modulation":
        P["mod_a"] = _u(rng, 0.22, 0.43)
        P["mod_ratio_target"] = _u(rng, 0.13, 0.45)
        P["mod_phi"] = _u(rng, 0.0, 2 * math.pi)
    if case == "static_ageing":
        P["age_target"] = _u(rng, 0.08, 0.16)
    return P, rng


def _pre(P, v0):
    """short constant-drive run: stick-slip period and drop"""
    d = Drive([v0], [0.0], 0.02 / P["fn"])
    Tss_guess = 2.5 / P["fn"]
    rig, T, Y = _simulate(P, d, 5 * Tss_guess)
    ts, drops, vmax = _quick(P, T, Y)
    if len(ts) >= 3:
        Tss = float(np.mean(np.diff(ts[1:])))
    elif len(ts) == 2:
        Tss = float(ts[1] - ts[0])
    else:
        Tss = Tss_guess
    drop = float(np.mean(drops[1:])) if len(drops) > 1 else (float(drops[0]) if len(drops) else 0.5 * P["N0"])
    return Tss, drop


def _build_drive(P, rng, Tss, drop, case):
    """drive and run length"""
    fn = P["fn"]; v0 = P["v0_nominal"]
    tr = 0.05 / fn
    kind = P["drive_kind"]
    ncyc = P["n_cycles_target"]
    if kind == "constant":
        t_rec = ncyc * Tss
        t_cut = 1.2 * Tss + _u(rng, 0.0, 1.0) * Tss
        t_end = t_cut + t_rec
        if case == "drive_modulation":
            fm = P["mod_ratio_target"] / Tss
            P["mod_f"] = fm
            d = Drive([v0], [0.0], tr, P["mod_a"], fm, P["mod_phi"])
        else:
            d = Drive([v0], [0.0], tr)
        return d, t_cut, t_end
    if kind == "steps":
        fac = P["step_factor"]
        lo = v0 / fac
        t_st_hi = max(Tss - 0.5 / fn, 0.3 / fn)
        Tss_lo = 1.1 * t_st_hi * fac + 0.5 / fn
        levels = []; tb = []
        t = 0.0; n = 0; hi = True
        # a warm-up at the first level
        t_cut = 1.2 * Tss + _u(rng, 0.0, 0.5) * Tss
        first = True
        while n < ncyc:
            nc = int(rng.integers(3, 6)) if hi else int(rng.integers(2, 4))
            dur = nc * (Tss if hi else Tss_lo)
            if first:
                dur += t_cut
                first = False
            levels.append(v0 if hi else lo); tb.append(t)
            t += dur; n += nc; hi = not hi
        if levels[-1] == v0 and len(levels) > 2:
            pass
        P["drive_levels"] = levels; P["drive_breaks"] = tb
        return Drive(levels, tb, tr), t_cut, t
    # holds
    levels = []; tb = []
    t_cut = 1.2 * Tss + _u(rng, 0.0, 0.5) * Tss
    t = 0.0; n = 0; first = True
    while n < ncyc:
        nc = int(rng.integers(2, 5))
        dur = nc * Tss + (t_cut if first else 0.0)
        first = False
        levels.append(v0); tb.append(t); t += dur; n += nc
        hold = _u(rng, 1.0, 9.0) * Tss
        levels.append(0.0); tb.append(t); t += hold
    levels.append(v0); tb.append(t); t += 3 * Tss
    P["drive_levels"] = levels; P["drive_breaks"] = tb
    return Drive(levels, tb, tr), t_cut, t


def _run_and_measure(P, drive, t_cut, t_end, dt):
    rig, T, Y = _simulate(P, drive, t_end)
    tr = dense(rig, T, Y, dt)
    i0 = int(round(t_cut / dt))
    tw = {kk: vv[i0:] for kk, vv in tr.items()}
    S = slips(tw)
    M = {"n_steps": int(len(T))}
    if len(S) >= 2:
        tws = twin_measure(tw, S)
        M["twin_frac_mean"] = float(np.mean(tws)); M["twin_frac_sd"] = float(np.std(tws))
        M["twin_frac_min"] = float(np.min(tws)); M["twin_frac_max"] = float(np.max(tws))
        M["n_slips"] = len(S)
        twm = twin_measure(dict(tw, Ff=tw["Ff"] / tw["Ne"] * P["N0"]), S)
        M["twin_frac_of_mu_mean"] = float(np.mean(twm))
        M["drop_mean"] = float(np.mean([s["drop"] for s in S]))
        M["drop_over_N0"] = M["drop_mean"] / P["N0"]
        M["peak_force_sd_over_drop"] = float(np.std([s["Fpk"] for s in S]) / M["drop_mean"])
        cr = np.array([s["creep"] for s in S])
        M["stick_creep_mean_frac_v0"] = float(np.nanmean(cr)); M["stick_creep_max_frac_v0"] = float(np.nanmax(cr))
        st = np.array([s["t_start"] for s in S])
        M["f_ss"] = float(1.0 / np.mean(np.diff(st)))
        M["slip_peak_speed_over_v0"] = float(np.mean([s["vpk"] for s in S]) / P["v0_nominal"])
        g, r = ageing_measure(S)
        M["peak_growth_over_drop"] = g; M["stick_time_ratio"] = r
    else:
        M["n_slips"] = len(S)
    M["N_total_pp_over_N0"] = float(np.ptp(tw["Nt"]) / P["N0"])
    M["N_eff_pp_over_N0"] = float(np.ptp(tw["Ne"]) / P["N0"])
    M["pitch_transfer_pp_over_N0"] = float(np.ptp(tw["dN"]) / P["N0"])
    M["T_contact_max_K"] = float(np.max(tw["T"]))
    return tw, S, M


def _lowpass(x, dt, fc):
    al = math.exp(-2 * math.pi * fc * dt)
    y = np.empty_like(x)
    acc = x[0]
    b = 1.0 - al
    for i in range(len(x)):
        acc += b * (x[i] - acc)
        y[i] = acc
    return y


def _pink(rng, n):
    w = rng.standard_normal(n)
    W = np.fft.rfft(w)
    f = np.arange(len(W), dtype=float)
    f[0] = 1.0
    W = W / np.sqrt(f)
    W[0] = 0.0
    p = np.fft.irfft(W, n)
    sd = np.std(p)
    return p / sd if sd > 0 else p


def _frac_int(x):
    return abs(x - round(x))


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    ci = CASES.index(case); ni = NUISANCES.index(nuisance)
    P, rng = _draw(case, seed)
    fn = P["fn"]; N0 = P["N0"]; k = P["k"]
    rng_rec = np.random.default_rng([777, ci, int(seed), ni])
    spp = _u(rng_rec, 10.0, 15.0) if nuisance == "coarse" else _u(rng_rec, 20.0, 100.0)
    dt_rec = 1.0 / (spp * fn)
    Mf = max(1, int(math.ceil(320.0 / spp)))
    dt = dt_rec / Mf

    if case == "load_variation" and P["load_mode"] == "angle":
        # first guess of the pull angle from the drop of a flat-line pre-run
        Tss0, drop0 = _pre(P, P["v0_nominal"])
        P["sin_theta"] = min(0.6, P["Npp_target"] / max(drop0 / N0, 0.05))
    Tss, drop = _pre(P, P["v0_nominal"])
    P["pre_Tss"] = Tss; P["pre_drop"] = drop
    if case == "static_ageing":
        fac = P["step_factor"] if P["drive_kind"] == "steps" else 4.0
        t_hi = max(Tss - 0.5 / fn, 0.3 / fn)
        tau = t_hi * math.sqrt(fac)
        P["tau_age"] = tau
        da = math.exp(-t_hi / tau) - math.exp(-fac * t_hi / tau)
        P["beta_age"] = P["age_target"] * drop / (P["mu_a"] * N0 * max(da, 0.2))
    if case == "triggering":
        for _ in range(200):
            ft = _u(rng, 2.5, 4.5) * fn
            if abs(ft / P["f_pitch"] - 1.0) > 0.15 and _frac_int(ft * Tss) > 0.3:
                break
        P["trig_f"] = ft
    drive, t_cut, t_end = _build_drive(P, rng, Tss, drop, case)
    if case == "load_variation" and P["load_mode"] == "wave":
        P["v0_const"] = P["v0_nominal"]
        lam = P["v0_nominal"] * (t_end - t_cut) / _u(rng, 1.6, 3.5)
        P["wave_k"] = 2 * math.pi / lam; P["wave_c"] = 0.5 * P["Npp_target"]
        P["wave_phi"] = _u(rng, 0, 2 * math.pi)

    runs = 0
    best = None
    while True:
        runs += 1
        tw, S, M = _run_and_measure(P, drive, t_cut, t_end, dt)
        if case == "triggering":
            dist = _frac_int(P["trig_f"] * M.get("f_ss", 0.0) ** -1) if M.get("f_ss") else 0.0
            if best is None or dist > best[0]:
                best = (dist, tw, S, M, P["trig_f"], P["trig_A"])
        if runs >= (7 if case == "triggering" else 4):
            if case == "triggering":
                tw, S, M, P["trig_f"], P["trig_A"] = best[1:]
            break
        if case == "twin_branch":
            tm = M.get("twin_frac_mean", 0.0)
            if 0.11 <= tm <= 0.23:
                break
            P["G_flash"] *= min(2.0, max(0.5, P["twin_target"] / max(tm, 0.02)))
        elif case == "load_variation":
            npp = M["N_total_pp_over_N0"]
            if 0.11 <= npp <= 0.38:
                break
            if P["load_mode"] == "angle":
                P["sin_theta"] *= P["Npp_target"] / npp
            else:
                P["wave_c"] *= P["Npp_target"] / npp
        elif case == "static_ageing":
            gm = M.get("peak_growth_over_drop", 0.0)
            if 0.06 <= gm <= 0.18:
                break
            P["beta_age"] *= min(3.0, max(0.3, P["age_target"] / max(gm, 0.01)))
        elif case == "triggering":
            fss = M.get("f_ss", 1.0 / Tss)
            if _frac_int(P["trig_f"] / fss) >= 0.17:
                break
            # the slips lock to the shaker: aim between two locking tongues (a half-integer ratio)
            for _ in range(200):
                top = 3.8 if runs < 3 else 3.0
                nn = int(rng.integers(int(2.5 * fn / fss), int(top * fn / fss) + 1))
                ft = (nn + 0.5 + _u(rng, -0.12, 0.12)) * fss
                if 2.5 * fn <= ft <= 5.0 * fn and abs(ft / P["f_pitch"] - 1.0) > 0.15:
                    break
            P["trig_f"] = ft
            if runs >= 3:
                P["trig_A"] = max(0.0305, 0.9 * P["trig_A"])
        elif case == "drive_modulation":
            r = P["mod_f"] / M.get("f_ss", 1.0 / Tss)
            if 0.11 <= r <= 0.49:
                break
            P["mod_f"] *= P["mod_ratio_target"] / r
            drive = Drive([P["v0_nominal"]], [0.0], 0.05 / fn, P["mod_a"], P["mod_f"], P["mod_phi"])
        else:
            break
    M["runs"] = runs
    if case == "triggering":
        M["trig_f_over_fn"] = P["trig_f"] / fn
        M["trig_f_over_f_ss"] = P["trig_f"] / M["f_ss"]
        M["trig_f_over_f_ss_dist_int"] = _frac_int(M["trig_f_over_f_ss"])
        M["trig_amp_over_N0"] = P["trig_A"]
        M["trig_f_over_f_pitch"] = P["trig_f"] / P["f_pitch"]
    if case == "drive_modulation":
        M["mod_a"] = P["mod_a"]; M["mod_fm_over_f_ss"] = P["mod_f"] / M["f_ss"]
    M["samples_per_period"] = spp
    M["Tss_over_Tn"] = fn / M["f_ss"] if "f_ss" in M else None

    # ---------------- the sensor ----------------
    fc = _u(rng_rec, 5.0, 20.0) * fn
    fcN = _u(rng_rec, 5.0, 20.0) * fn
    Fline = _lowpass(tw["Fs"], dt, fc)[::Mf]
    Nread = _lowpass(tw["Nt"], dt, fcN)[::Mf]
    tt = tw["t"][::Mf] - tw["t"][0]
    v0col = tw["v0"][::Mf]
    xd = np.concatenate(([0.0], np.cumsum(0.5 * (tw["v0"][1:] + tw["v0"][:-1]) * dt)))[::Mf]
    n = len(tt)
    drop = M.get("drop_mean", 0.5 * N0)
    sw = _u(rng_rec, 0.002, 0.006) * drop; sp = _u(rng_rec, 0.001, 0.003) * drop
    F = Fline + sw * rng_rec.standard_normal(n) + sp * _pink(rng_rec, n)
    Nm = Nread + _u(rng_rec, 0.001, 0.003) * N0 * rng_rec.standard_normal(n)
    nz = {"white_sd_over_drop": sw / drop, "pink_sd_over_drop": sp / drop, "sensor_fc_over_fn": fc / fn}
    if nuisance == "hum":
        fh = 50.0 if rng_rec.random() < 0.5 else 60.0
        A = _u(rng_rec, 0.01, 0.05) * drop
        ph = rng_rec.uniform(0, 2 * np.pi, 3)
        F = F + A * (np.sin(2 * np.pi * fh * tt + ph[0]) + 0.3 * np.sin(4 * np.pi * fh * tt + ph[1])
                     + 0.15 * np.sin(6 * np.pi * fh * tt + ph[2]))
        nz.update(hum_hz=fh, hum_amp_over_drop=A / drop)
    elif nuisance == "drift":
        D = _u(rng_rec, 0.02, 0.06) * drop * (1 if rng_rec.random() < 0.5 else -1)
        u = tt / tt[-1]
        cq = _u(rng_rec, -0.5, 0.5)
        F = F + D * (u + cq * u * (u - 1.0))
        nz.update(drift_over_drop=D / drop)
    elif nuisance == "spikes":
        fr = _u(rng_rec, 0.0005, 0.005)
        ns = max(2, int(round(fr * n)))
        ii = rng_rec.choice(np.arange(5, n - 5), ns, replace=False)
        F = F.copy()
        F[ii] += rng_rec.choice([-1.0, 1.0], ns) * rng_rec.uniform(0.2, 1.0, ns) * drop
        nz.update(spike_fraction=ns / n)
    elif nuisance == "quantisation":
        q = _u(rng_rec, 0.002, 0.01) * drop
        F = np.round(F / q) * q
        Nm = np.round(Nm / q) * q
        nz.update(quant_step_over_drop=q / drop)

    # ---------------- the record ----------------
    force = (seed + ci) % 2 == 0
    has_N = case in ("load_variation", "triggering") or (case in ("none", "twin_branch") and seed % 4 == 1)
    drive_col = P["drive_kind"] != "constant"
    drive_as_pos = drive_col and ((seed // 2) % 2 == 0)
    sep = [",", ";", "\t", " "][(seed + 2 * ci) % 4]
    cols = []; names = []
    tname = "t[s]" if sep == " " else "time [s]"
    cols.append(tt); names.append(tname)
    if force:
        fu, fs = ("mN", 1e3) if rng_rec.random() < 0.4 else ("N", 1.0)
        cols.append(F * fs); names.append(("F[%s]" if sep == " " else "friction [%s]") % fu)
        if has_N:
            cols.append(Nm * fs); names.append(("N[%s]" if sep == " " else "normal [%s]") % fu)
        if drive_col:
            if drive_as_pos:
                pu, ps = ("um", 1e6) if rng_rec.random() < 0.4 else ("mm", 1e3)
                cols.append((xd + _u(rng_rec, 0.0, 0.05)) * ps)
                names.append(("pos[%s]" if sep == " " else "position [%s]") % pu)
            else:
                cols.append(v0col * 1e3); names.append("v0[mm/s]" if sep == " " else "v0 [mm/s]")
    else:
        cols.append(F / k * 1e3); names.append("x[mm]" if sep == " " else "x [mm]")
        if has_N:
            b = _u(rng_rec, 0.5, 2.0) / N0
            cols.append(_u(rng_rec, -1.0, 1.0) + b * Nm); names.append("y[mm]" if sep == " " else "y [mm]")
            nz["y_mm_per_N"] = b
        if drive_col:
            cols.append(v0col * 1e3); names.append("v0[mm/s]" if sep == " " else "v0 [mm/s]")
    os.makedirs(outdir, exist_ok=True)
    fname = os.path.abspath(os.path.join(outdir, "%s_%s_s%d_%s.%s" % (NAME, case, seed, nuisance,
                                                                       "txt" if sep in ("\t", " ") else "csv")))
    data = np.column_stack(cols)
    with open(fname, "w") as fh_:
        if rng_rec.random() < 0.35:
            fh_.write("# rubber sled on float glass, pull-line load cell, run %d\n" % (1000 + seed))
        fh_.write(sep.join(names) + "\n")
        for row in data:
            fh_.write(sep.join("%.7g" % x for x in row) + "\n")

    args = []
    omit = {"none": 1, "load_variation": 3, "twin_branch": 5, "static_ageing": 7,
            "drive_modulation": 0}.get(case, None)
    fn_given = None
    if omit is None or seed % 8 != omit:
        fn_given = fn
        if nuisance == "fn_off":
            fn_given = fn * (1.05 if rng_rec.random() < 0.5 else 0.95)
        args += ["--fn", "%.6g" % fn_given]
    if not drive_col:
        args += ["--v0", "%.6g" % (P["v0_nominal"] * 1e3)]
    if force:
        args += ["--stiffness", "%.6g" % k]
    P["noise"] = nz
    P["measured"] = M
    P["record"] = {"force": force, "normal_column": has_N, "drive_column": drive_col,
                   "drive_as_position": drive_as_pos, "separator": sep, "columns": names, "n_samples": n}
    params = _jsonable(P)
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": fname,
            "args": args, "fn_true": fn, "fn_given": fn_given, "params": params}


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating, float)):
        x = float(o)
        return x if math.isfinite(x) else None
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.bool_,)):
        return bool(o)
    return o
