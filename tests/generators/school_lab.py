"""school_lab: stick-slip records from a teaching-lab friction experiment.

The rig
-------
A block (wood, felt-, rubber- or sandpaper-faced; 0.2-2 kg with its extra masses) on a plank or an
aluminium track is pulled through a steel spring, a rubber band or a force sensor's own hook spring by a
motorised cart (smart-cart encoder), a constant-speed motor winding a string on a pulley (rotary motion
sensor) or a dynamics-track cart (ultrasonic motion sensor).  The force sensor (strain gauge, +-10 N or
+-50 N, 12-16 bit, its own zeroing offset, PASCO pull-negative sign convention sometimes) sits in the
string, so it reads the string tension T.  A second force sensor under the track records the normal load
in `load_variation`.

Physics (own choices, none of the laws listed as taken by other generators)
-------------------------------------------------------------------------
* Friction law: a *student's measured table* mu_i at the lab's drag speeds 0, 0.5, 1, 2, 5, 10, 20, 50,
  100, 200, 500, 1000 mm/s (measurement scatter 0.2 % of the static-kinetic difference), interpolated by
  a C2 cubic spline in the log-speed u = ln(1 + v / 1 mm/s) (clamped slope at v = 0, natural at the top
  end, linear in v above 1 m/s).  The underlying trend the student sampled is a "shouldered" decay
  mu_s0 - D (1 - (1 + c x) exp(-x)), x = v / v_s, plus a viscous strengthening b v.  The table is redrawn
  until the interpolant falls strictly below its static level mu(0) = mu_s0 for every v > 0 and is
  monotone below its minimum (single-valued, static level at v = 0).
* Spring: the string tension T = k0 e + kq e^2 + kM d, e = cos(theta) (x_drive - x) the string extension,
  d a Maxwell (standard-linear-solid) arm d' = e' - d / tau_b: a rubber band is slightly stiffening and
  slightly hysteretic; a steel spring or a hook spring has kq = kM = 0.  The string goes slack (T = 0)
  when e's force would be negative.  The string leaves the block at an angle theta, so the normal load is
  N = m g - T sin(theta) (theta <= 0.5 deg except in `load_variation`).
* load_variation: the string rises steeply to a pulley on a stand (theta up to 40 deg, N falls as the pull
  grows) or runs down over the bench edge to the motor on the floor (theta < 0, N grows with the pull; kept
  clear of self-locking, cos - mu_s sin >= 0.55); theta is tuned to a 12-33 % p-p load; a second force
  sensor under the track records N.
* twin_branch: the block rocks on its facing.  Its pitch phi follows, with a lag tau_phi = 0.04-0.08 T_n,
  the deceleration that the pull and the sliding law impose (tau_phi phi' = -(T cos - mu(v) N)/(m a_ref) - phi)
  and its leading edge ploughs while pitched forward: mu += dp phi^2 / (phi + 0.05) for phi > 0.  Friction
  is therefore higher on the decelerating half of a slip than on the accelerating half at equal speed;
  dp is tuned to 12-22 % of the slip's force drop (mean over 0.25-0.9 of the peak speed).
* static_ageing: the static threshold grows with the stick's age t as mu_s(t) = mu_s0 + dmu t / (t + tau_a)
  (saturating junction growth), the cart steps between two speeds a factor 4.2-7.8 apart (3-4 segments)
  and may hold (0.6-1.4 slow-level stick times); tau_a ~ the geometric mean of the stick times seen, dmu
  tuned to a 6.5-17 % growth of the peak force over the record's stick times; the drive is recorded.
* triggering: a vibration motor (taped to the block or clamped to the bench) modulates the normal load,
  N += eps m g sin(2 pi f_t t + psi), eps 3.1-6 %, f_t 2.6-4.2 fn, redrawn until f_t / f_ss is 0.25-0.75
  from an integer; the rig is dragged faster (v0 ~ 0.3 of the slips' peak speed) so that the ripple does not
  lock every slip to the same vibration period.
* drive_modulation: the motor turns at constant rpm but the string winds on an off-centre pulley (or the
  motor's speed controller hunts): v_drive = v0n (1 + a sin(2 pi f_m t + phi)); only v0n is given.

Stick handling and integrator (own)
-----------------------------------
Stick is a hard constraint (v = 0, x frozen).  While stuck the release function
g(t) = T cos(theta) - mu_s(age) N is evaluated *vectorised* on a fine grid (T_n/200, the Maxwell arm by an
exact first-order recursion) and the release is located by secant interpolation of g.  A slip is
integrated by a fixed-step Ralston third-order Runge-Kutta (T_n/160, finer under triggering); re-stick is
captured where v crosses zero by a secant step fraction (the step is redone from its start with that
fraction).  A slip that fails at its first step (friction above the pull, e.g. a load peak) is undone and
the stick goes on.

Memory in `none` (measured from the truth by check.py / a 70-seed survey of `none`, all nuisances): the
friction law itself is memoryless (a pure function of v); the friction at equal speed on the decelerating
and accelerating halves of a slip differs by at most 0.53 % of the slip's force drop (median 0.1 %; all of
it from the 0-0.5 deg string angle's load variation); the rubber band's Maxwell arm carries at most 1.1 % of
the force drop (kM <= 1.2 % of k0, in 22 of 70 rigs; steel and hook springs have none), its stiffening changes
the tangent stiffness by at most 1.5 % over a stick; the normal load varies by at most 0.38 % p-p; the peak
(static) force is the same in every cycle to 1e-8.

Side effects inherent to a case (not separate departures): in `load_variation` the friction at equal speed
differs between the halves of a slip because N does (N is recorded); in `triggering` the slips start at
preferred phases of the vibration, so peaks vary by 4-10 % and the stick-slip tends to lock at 2:1 or 3:1
sub-patterns with the vibration (f_t / f_ss stays 0.2-0.5 away from an integer; the truth's
params.rig.effect.locking gives the onset-phase concentration).

Record files
------------
One run per file, as exported: PASCO Capstone CSV (`Time (s),Force (N)[,Normal Force (N)][,Position (m)
| ,Velocity (m/s)]`), Vernier Logger Pro CSV or TAB text (`Latest: Time (s)`, ...), Vernier Graphical
Analysis CSV (`Run 1: Time (s)`, ...), or a student's Excel CSV with ';' and a decimal comma (position in
mm).  The force may read pull as negative (PASCO; then the drive position/velocity is signed the same
way), may carry a zeroing offset; ultrasonic positions are noisy, 0.1 mm resolved and drop out (blank
cells).  `args`: `--v0` (mm/s, the cart's setting, within 1.5 % of the true speed) when no drive column,
`--stiffness` (the label or a quick measurement, +-3 %) in 70 % of records (never in `load_variation`, whose
steep string makes the label differ from the stiffness the record shows), `--fn` in 30 % (+-1.5 %) and
always in `fn_off` (+-4.5-4.9 %).  fn_true = sqrt(k_tan / m) / 2 pi, k_tan the band's tangent + storage
stiffness times cos(theta) (cos(theta) + mu_k sin(theta)).
"""
import bisect
import math
import os
import zlib

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.signal import lfilter

NAME = "school_lab"
G = 9.81
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
V_TABLE_MM = [0.0, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0]
V1_MM = 1.0


# ----------------------------------------------------------------------------------------------------
# friction law: student's table interpolated in log-speed
# ----------------------------------------------------------------------------------------------------
class Law:
    def __init__(self, L):
        v = np.asarray(L["v_mm"], float) / 1000.0
        self.v1 = L["v1_mm"] / 1000.0
        u = np.log1p(v / self.v1)
        mu = np.asarray(L["mu"], float)
        self.cs = CubicSpline(u, mu, bc_type=((1, L["slope0_u"]), (2, 0.0)))
        self.ub = u.tolist()
        self.n = len(u)
        self.c = self.cs.c.T.tolist()
        self.v_last = float(v[-1])
        self.mu_last = float(mu[-1])
        self.slope_v = float(self.cs(u[-1], 1)) / (self.v1 + self.v_last)
        self.mu0 = float(mu[0])

    def mu(self, v):
        if v >= self.v_last:
            return self.mu_last + self.slope_v * (v - self.v_last)
        u = math.log1p(v / self.v1)
        i = bisect.bisect_right(self.ub, u) - 1
        if i < 0:
            i = 0
        elif i > self.n - 2:
            i = self.n - 2
        c3, c2, c1, c0 = self.c[i]
        du = u - self.ub[i]
        return ((c3 * du + c2) * du + c1) * du + c0

    def mu_vec(self, v):
        v = np.abs(np.asarray(v, float))
        out = self.cs(np.log1p(np.minimum(v, self.v_last) / self.v1))
        hi = v > self.v_last
        out = np.where(hi, self.mu_last + self.slope_v * (v - self.v_last), out)
        return out


def _underlying(v, mus0, D, vs, c, b):
    x = v / vs
    return mus0 - D * (1.0 - (1.0 + c * x) * np.exp(-x)) + b * v


def _draw_law(rng, mus0, D, vs, b, v_check):
    """Student's table of mu at the lab's drag speeds (m/s inside), redrawn until well behaved
    (below its static level up to v_check, several times the slips' peak speed)."""
    v = np.asarray(V_TABLE_MM) / 1000.0
    c = float(rng.uniform(0.3, 0.7))
    v1 = V1_MM / 1000.0
    vf = np.linspace(0.0, 1.0, 4001) ** 2 * min(1.2, v_check)
    for attempt in range(60):
        scat = 0.002 * D if attempt < 40 else 0.0
        mu = _underlying(v, mus0, D, vs, c, b)
        mu[1:] += rng.normal(0.0, scat, len(v) - 1)
        # analytic slope at v = 0 in u units (dmu/du = dmu/dv * v1)
        slope0 = v1 * (-D * (1.0 - c) / vs + b)
        L = {"v_mm": list(V_TABLE_MM), "mu": [float(z) for z in mu], "slope0_u": float(slope0),
             "v1_mm": V1_MM, "shape_c": c, "v_s": float(vs), "D": float(D), "b_visc": float(b),
             "mu_s0": float(mus0)}
        law = Law(L)
        mf = law.mu_vec(vf)
        imin = int(np.argmin(mf))
        if imin < 10:
            continue
        ok = np.all(mf[1:] < mus0) and np.all(np.diff(mf[: int(imin * 0.9)]) < 0)
        if ok:
            L["v_min"] = float(vf[imin])
            L["mu_min"] = float(mf[imin])
            return L
    raise RuntimeError("no well-behaved friction table")


# ----------------------------------------------------------------------------------------------------
# drive
# ----------------------------------------------------------------------------------------------------
class Drive:
    def __init__(self, Dp):
        self.kind = Dp["kind"]
        if self.kind == "schedule":
            self.tb = [float(z) for z in Dp["t"]]
            self.vb = [float(z) for z in Dp["v"]]
            xb = [0.0]
            for i in range(1, len(self.tb)):
                xb.append(xb[-1] + self.vb[i - 1] * (self.tb[i] - self.tb[i - 1]))
            self.xb = xb
            self.tba = np.asarray(self.tb)
            self.vba = np.asarray(self.vb)
            self.xba = np.asarray(xb)
        else:
            self.v0 = Dp["v0"]
            self.a = Dp["a"]
            self.w = 2 * math.pi * Dp["fm"]
            self.ph = Dp["phase"]

    def x(self, t):
        if self.kind == "schedule":
            i = bisect.bisect_right(self.tb, t) - 1
            if i < 0:
                i = 0
            return self.xb[i] + self.vb[i] * (t - self.tb[i])
        return self.v0 * (t - self.a / self.w * (math.cos(self.w * t + self.ph) - math.cos(self.ph)))

    def v(self, t):
        if self.kind == "schedule":
            i = bisect.bisect_right(self.tb, t) - 1
            if i < 0:
                i = 0
            return self.vb[i]
        return self.v0 * (1.0 + self.a * math.sin(self.w * t + self.ph))

    def xv(self, t):
        t = np.asarray(t, float)
        if self.kind == "schedule":
            i = np.clip(np.searchsorted(self.tba, t, side="right") - 1, 0, None)
            return self.xba[i] + self.vba[i] * (t - self.tba[i])
        return self.v0 * (t - self.a / self.w * (np.cos(self.w * t + self.ph) - math.cos(self.ph)))

    def vv(self, t):
        t = np.asarray(t, float)
        if self.kind == "schedule":
            i = np.clip(np.searchsorted(self.tba, t, side="right") - 1, 0, None)
            return self.vba[i]
        return self.v0 * (1.0 + self.a * np.sin(self.w * t + self.ph))


# ----------------------------------------------------------------------------------------------------
# simulation: stick as a constraint, slips by Ralston RK3
# ----------------------------------------------------------------------------------------------------
def simulate(P, stop_after_slips=None):
    """Noise-free truth of the rig described by P (the truth's params["sim"]).

    Returns knots t, x, v, T (string tension = sensor force), N (normal load), Ff (tangential friction
    force; = T cos(theta) in stick) and a list of slips (t_on, T_on, age, t_off, T_off, i_on, i_off, vmax)."""
    law = Law(P["law"])
    drv = Drive(P["drive"])
    m = P["m"]
    Nw = m * G
    th = P["theta"]
    cth, sth = math.cos(th), math.sin(th)
    k0, kq, kM, taub = P["k0"], P["kq"], P["kM"], P["tau_b"]
    mus0 = P["law"]["mu"][0]
    dma, taua = P["age"]["dmu"], P["age"]["tau"]
    dp, tauphi, aref = P["plough"]["dp"], P["plough"]["tau"], P["plough"]["a_ref"]
    eps, wt, psi = P["trig"]["eps"], 2 * math.pi * P["trig"]["f"], P["trig"]["psi"]
    h, hs, t_end = P["h_slip"], P["h_stick"], P["t_end"]
    mu = law.mu
    xdf, vdf = drv.x, drv.v
    epsN = eps * Nw

    def rhs(t, x, v, d, phi):
        e = cth * (xdf(t) - x)
        T = k0 * e + kM * d
        if e > 0:
            T += kq * e * e
        if T < 0:
            T = 0.0
        N = Nw - T * sth
        if epsN:
            N += epsN * math.sin(wt * t + psi)
        # a slip is always forward (the string cannot push): friction opposes it even at the RK stages
        # that overshoot to v < 0 just before the re-stick, which the step's zero crossing then captures
        mf = mu(v if v >= 0 else -v)
        if dp:
            # pitch driven by the deceleration that the pull and the sliding law impose (the ploughing
            # resistance acts in the contact plane and does not feed the pitch back)
            dph = (-(T * cth - mf * N) / (m * aref) - phi) / tauphi
            if phi > 0:
                mf += dp * phi * phi / (phi + 0.05)
        else:
            dph = 0.0
        Ff = mf * N
        a = (T * cth - Ff) / m
        dd = (cth * (vdf(t) - v) - d / taub) if kM else 0.0
        return a, dd, dph, T, N, Ff

    def rk3(t, x, v, d, phi, hh, k1):
        a1, dd1, dp1 = k1[0], k1[1], k1[2]
        v2 = v + 0.5 * hh * a1
        x2, d2, p2 = x + 0.5 * hh * v, d + 0.5 * hh * dd1, phi + 0.5 * hh * dp1
        a2, dd2, dp2, _, _, _ = rhs(t + 0.5 * hh, x2, v2, d2, p2)
        v3 = v + 0.75 * hh * a2
        x3, d3, p3 = x + 0.75 * hh * v2, d + 0.75 * hh * dd2, phi + 0.75 * hh * dp2
        a3, dd3, dp3, _, _, _ = rhs(t + 0.75 * hh, x3, v3, d3, p3)
        return (x + hh * (2 * v + 3 * v2 + 4 * v3) / 9.0,
                v + hh * (2 * a1 + 3 * a2 + 4 * a3) / 9.0,
                d + hh * (2 * dd1 + 3 * dd2 + 4 * dd3) / 9.0,
                phi + hh * (2 * dp1 + 3 * dp2 + 4 * dp3) / 9.0)

    # initial state: stuck, spring pre-tensioned to half the static force
    t = 0.0
    e0 = 0.5 * mus0 * Nw / k0
    x = drv.x(0.0) - e0 / cth
    v, d, phi = 0.0, 0.0, 0.0
    t_st0 = -P.get("age0", 0.0)
    mode = "stick"
    beta = math.exp(-hs / taub)
    kt, kx, kv, kT, kN, kF = [], [], [], [], [], []   # chunks (arrays) / scalars mixed via lists of arrays
    sl_t, sl_x, sl_v, sl_T, sl_N, sl_F = [], [], [], [], [], []
    nk = 0
    slips = []

    def flush_scalars():
        nonlocal sl_t, sl_x, sl_v, sl_T, sl_N, sl_F
        if sl_t:
            kt.append(np.asarray(sl_t)); kx.append(np.asarray(sl_x)); kv.append(np.asarray(sl_v))
            kT.append(np.asarray(sl_T)); kN.append(np.asarray(sl_N)); kF.append(np.asarray(sl_F))
            sl_t, sl_x, sl_v, sl_T, sl_N, sl_F = [], [], [], [], [], []

    M = 2048
    while t < t_end:
        if mode == "stick":
            tt = t + hs * np.arange(1, M + 1)
            e = cth * (drv.xv(tt) - x)
            if kM:
                s = cth * drv.vv(tt - 0.5 * hs)
                dd_arr = lfilter([taub * (1 - beta)], [1.0, -beta], s, zi=[beta * d])[0]
            else:
                dd_arr = np.zeros(M)
            T = k0 * e + kq * np.where(e > 0, e * e, 0.0) + kM * dd_arr
            T = np.maximum(T, 0.0)
            N = Nw - T * sth
            if epsN:
                N = N + epsN * np.sin(wt * tt + psi)
            mus = mus0 + (dma * (tt - t_st0) / (tt - t_st0 + taua) if dma else 0.0)
            g = T * cth - mus * N
            pos = np.flatnonzero(g > 0)
            if pos.size == 0:
                flush_scalars()
                kt.append(tt); kx.append(np.full(M, x)); kv.append(np.zeros(M)); kT.append(T)
                kN.append(N); kF.append(T * cth)
                nk += M
                t = float(tt[-1]); d = float(dd_arr[-1])
                continue
            idx = int(pos[0])
            if idx == 0:
                t_rel, d_rel = float(tt[0]), float(dd_arr[0])
            else:
                f = g[idx - 1] / (g[idx - 1] - g[idx])
                f = min(max(f, 1e-9), 1.0)
                t_rel = float(tt[idx - 1] + f * hs)
                d_rel = float(dd_arr[idx - 1] + f * (dd_arr[idx] - dd_arr[idx - 1]))
                flush_scalars()
                kt.append(tt[:idx]); kx.append(np.full(idx, x)); kv.append(np.zeros(idx))
                kT.append(T[:idx]); kN.append(N[:idx]); kF.append(T[:idx] * cth)
                nk += idx
            t, d, v = t_rel, d_rel, 0.0
            mode = "slip"
            slips.append({"t_on": t, "age": t - t_st0, "i_on": nk, "fresh": True})
        else:
            k1 = rhs(t, x, v, d, phi)
            sl_t.append(t); sl_x.append(x); sl_v.append(v); sl_T.append(k1[3]); sl_N.append(k1[4])
            sl_F.append(k1[5])
            nk += 1
            if slips[-1].get("fresh"):
                slips[-1]["T_on"] = k1[3]
                slips[-1]["vmax"] = 0.0
                del slips[-1]["fresh"]
            xn, vn, dn, pn = rk3(t, x, v, d, phi, h, k1)
            if vn <= 0.0:
                if v == 0.0:            # failed start: the block did not move, the stick goes on
                    slips.pop()
                    mode = "stick"
                    continue
                fr = v / (v - vn)
                xz, vz, dz, pz = rk3(t, x, v, d, phi, h * fr, k1)
                t = t + h * fr
                x, v, d, phi = xz, 0.0, dz, pz
                k = rhs(t, x, 0.0, d, phi)
                sl_t.append(t); sl_x.append(x); sl_v.append(0.0); sl_T.append(k[3]); sl_N.append(k[4])
                sl_F.append(k[3] * cth)
                slips[-1].update({"t_off": t, "T_off": k[3], "i_off": nk})
                nk += 1
                mode = "stick"
                t_st0 = t
                if dp:
                    phi = 0.0  # the block settles flat on its facing while stuck
                if stop_after_slips and len(slips) >= stop_after_slips:
                    break
            else:
                t += h
                x, v, d, phi = xn, vn, dn, pn
                if vn > slips[-1]["vmax"]:
                    slips[-1]["vmax"] = vn
    flush_scalars()
    out = {"t": np.concatenate(kt), "x": np.concatenate(kx), "v": np.concatenate(kv),
           "T": np.concatenate(kT), "N": np.concatenate(kN), "Ff": np.concatenate(kF)}
    out["slips"] = [s for s in slips if "t_off" in s]
    return out


# ----------------------------------------------------------------------------------------------------
# internal measurements used for tuning the effect sizes
# ----------------------------------------------------------------------------------------------------
def _window_slips(sim, t0, t1):
    S = [s for s in sim["slips"] if s["t_on"] >= t0 and s["t_off"] <= t1]
    if not S:
        return []
    drops = np.array([s["T_on"] - s["T_off"] for s in S])
    med = np.median(drops)
    return [s for s, dr in zip(S, drops) if dr >= 0.4 * med]


def _stats(sim, t0, t1):
    S = _window_slips(sim, t0, t1)
    drops = np.array([s["T_on"] - s["T_off"] for s in S])
    ons = np.array([s["t_on"] for s in S])
    st = {"n": len(S), "drop": float(np.median(drops)) if len(S) else np.nan,
          "f_ss": float((len(S) - 1) / (ons[-1] - ons[0])) if len(S) > 2 else np.nan,
          "t_slip": float(np.median([s["t_off"] - s["t_on"] for s in S])) if S else np.nan,
          "vmax": float(np.median([s["vmax"] for s in S])) if S else np.nan,
          "peaks": [s["T_on"] for s in S], "ages": [s["age"] for s in S]}
    return st


def _twin_ratio(sim, t0, t1):
    S = _window_slips(sim, t0, t1)
    r = []
    for s in S:
        vv = sim["v"][s["i_on"]: s["i_off"] + 1]
        ff = sim["Ff"][s["i_on"]: s["i_off"] + 1]
        im = int(np.argmax(vv))
        if im < 4 or len(vv) - im < 4:
            continue
        va, fa = np.maximum.accumulate(vv[: im + 1]), ff[: im + 1]
        vd, fd = np.minimum.accumulate(vv[im:])[::-1], ff[im:][::-1]
        grid = vv[im] * np.linspace(0.3, 0.85, 12)
        r.append(np.mean(np.interp(grid, vd, fd) - np.interp(grid, va, fa)) / (s["T_on"] - s["T_off"]))
    return float(np.median(r)) if r else np.nan


def _load_pp(sim, t0, t1):
    sel = (sim["t"] >= t0) & (sim["t"] <= t1)
    N = sim["N"][sel]
    return float((N.max() - N.min()) / N.mean())


def _growth(sim, t0, t1):
    p = np.array(_stats(sim, t0, t1)["peaks"])
    return float((p.max() - p.min()) / p.min())


# ----------------------------------------------------------------------------------------------------
# design of one record
# ----------------------------------------------------------------------------------------------------
def _rng(case, seed, nuisance):
    key = zlib.crc32(f"{NAME}|{case}|{seed}|{nuisance}".encode())
    return np.random.default_rng([key, int(seed), 6969])


def _sig(x, n=2):
    if x == 0:
        return 0.0
    p = n - 1 - int(math.floor(math.log10(abs(x))))
    return round(x, p)


FS_MENU = [50, 100, 200, 500, 1000]
FS_US = [20, 25, 30, 40, 50]
MATERIALS = {  # face: (mu_s0 range, (mu_s0 - mu_min)/mu_s0 range, track)
    "wood": ((0.40, 0.55), (0.20, 0.32), "plank"),
    "felt": ((0.26, 0.36), (0.16, 0.24), "aluminium track"),
    "rubber": ((0.75, 0.95), (0.20, 0.30), "aluminium track"),
    "sandpaper": ((0.55, 0.75), (0.17, 0.28), "plank"),
}


def _design(case, seed, nuisance):
    rng = _rng(case, seed, nuisance)
    meta = {}
    # ---------------- sensors / software ----------------
    if case == "drive_modulation":
        dsens = "none"
    elif case == "static_ageing":
        dsens = str(rng.choice(["ultrasonic", "encoder", "rotary", "cart_velocity"], p=[.3, .3, .2, .2]))
    elif case == "load_variation":
        dsens = str(rng.choice(["none", "ultrasonic", "encoder", "rotary"], p=[.4, .2, .2, .2]))
    else:
        dsens = str(rng.choice(["none", "ultrasonic", "encoder", "rotary", "cart_velocity"],
                               p=[.4, .2, .2, .1, .1]))
    if nuisance == "hum" and dsens == "ultrasonic":
        dsens = "encoder"
    steps = case == "static_ageing" or (case == "none" and dsens != "none" and rng.random() < 0.4)
    # ---------------- block and material ----------------
    if case == "load_variation":
        face = str(rng.choice(["rubber", "sandpaper", "wood"]))
    else:
        face = str(rng.choice(list(MATERIALS)))
    (a0, a1), (f0, f1), track = MATERIALS[face]
    if case == "load_variation":      # a grippy pair: a large drop for the string's lift to act on
        f0, f1 = 0.28, 0.36
    mus0 = float(rng.uniform(a0, a1))
    D = float(rng.uniform(f0, f1)) * mus0
    m_block = float(rng.uniform(0.15, 0.5))
    extra = float(rng.choice([0.0, 0.2, 0.5, 1.0, 1.5]))
    m = float(min(max(m_block + extra, 0.2), 2.0))
    if case == "triggering":
        m += float(rng.uniform(0.02, 0.05))   # the vibration motor taped on (or the bench: no mass)
    meta.update(face=face, track=track, m_block=m_block, extra_mass=extra)
    # ---------------- spring and sample rate ----------------
    coarse = nuisance == "coarse"
    if coarse:
        fs = int(rng.choice([20, 25, 50, 100] if dsens != "ultrasonic" else [20, 25, 40, 50]))
        fn = fs / float(rng.uniform(10.6, 14.4))
    else:
        sp = str(rng.choice(["steel spring", "rubber band", "hook spring"], p=[.45, .35, .2]))
        kr = {"steel spring": (8, 80), "rubber band": (25, 250), "hook spring": (300, 2000)}[sp]
        k = float(np.exp(rng.uniform(np.log(kr[0]), np.log(kr[1]))))
        fn = math.sqrt(k / m) / (2 * math.pi)
        if case == "triggering" and fn < 1.5:   # a stiffer spring: the fast drag stays below ~100 mm/s
            fn = float(rng.uniform(1.5, 4.0))
        if dsens == "ultrasonic" and fn > 1.9:
            fn = float(rng.uniform(1.5 if case == "triggering" else 0.6, 1.9))
        fn = min(max(fn, 0.45), 18.0)
        fs = None
    k0 = m * (2 * math.pi * fn) ** 2
    if k0 < 90:
        spring = "steel spring" if (coarse or sp != "rubber band" or k0 < 20) else "rubber band"
    elif k0 < 300:
        spring = "rubber band" if (coarse or sp != "steel spring") else "steel spring"
    else:
        spring = "hook spring"
    if spring == "rubber band":
        alpha = float(rng.uniform(0.005, 0.012)) if case == "none" else float(rng.uniform(0.005, 0.02))
        eta = float(rng.uniform(0.005, 0.012)) if case == "none" else float(rng.uniform(0.005, 0.02))
        tau_b = float(rng.uniform(0.3, 2.0))
    else:
        alpha, eta, tau_b = 0.0, 0.0, 1.0
    meta.update(spring=spring, band_stiffening=alpha, band_maxwell_ratio=eta)
    w_n = 2 * math.pi * fn
    Tn = 1.0 / fn
    # ---------------- law ----------------
    v_sp = D * G / w_n                    # scale of the slip's peak speed
    vs = float(rng.uniform(0.25, 0.4) if case == "triggering" else rng.uniform(0.12, 0.35)) * v_sp
    b = float(rng.uniform(0.05, 0.25)) * D / v_sp
    L = _draw_law(rng, mus0, D, vs, b, 2.5 * v_sp)
    # ---------------- drive ----------------
    # drive speed / slips' peak speed; a vibration-triggered rig is run faster so that the load ripple
    # cannot hold the release for a whole vibration period (no phase locking of the stick-slip)
    r = float(rng.uniform(0.28, 0.4)) if case == "triggering" else float(rng.uniform(0.05, 0.12))
    v0 = min(r * v_sp, 0.45 * L["v_min"])
    v0_nom = _sig(v0 * 1000.0, 2) / 1000.0        # the cart's setting (m/s)
    v0 = v0_nom * (1.0 + float(rng.uniform(-0.015, 0.015)))
    theta = float(np.radians(rng.uniform(0.0, 0.5)))
    Nw = m * G
    e_mean = 0.8 * mus0 * Nw / k0
    kq = alpha * k0 / e_mean
    kM = eta * k0
    P = {"m": m, "theta": theta, "k0": k0, "kq": kq, "kM": kM, "tau_b": tau_b, "law": L,
         "age": {"dmu": 0.0, "tau": 1.0}, "plough": {"dp": 0.0, "tau": 0.05 * Tn, "a_ref": 1.0},
         "trig": {"eps": 0.0, "f": 0.0, "psi": 0.0}, "h_slip": Tn / 160.0, "h_stick": Tn / 200.0,
         "drive": {"kind": "schedule", "t": [0.0], "v": [v0]}, "t_end": 1e9, "age0": 0.0}
    # ---------------- pilot (constant drive, no effect) ----------------
    pilot = simulate(P, stop_after_slips=7)
    S = pilot["slips"][2:]
    drop_p = float(np.median([s["T_on"] - s["T_off"] for s in S]))
    tcyc_p = float((S[-1]["t_on"] - S[0]["t_on"]) / (len(S) - 1))
    tslip_p = float(np.median([s["t_off"] - s["t_on"] for s in S]))
    tstick_p = tcyc_p - tslip_p
    P["plough"]["a_ref"] = drop_p / (2 * m)
    P["age0"] = tstick_p
    meta["pilot"] = {"drop": drop_p, "t_cycle": tcyc_p, "t_slip": tslip_p}

    def tstick(v):
        return tstick_p * v0 / v

    # ---------------- schedule, window ----------------
    n_cyc = int(rng.integers(15, 30))
    # the track is 1.2-2.2 m long: a soft spring's long travel per cycle allows fewer cycles
    n_cyc = int(min(n_cyc, max(13, math.floor(1.5 / (v0 * tcyc_p)))))
    t_w = 2.6 * tcyc_p
    rec_frac = float(rng.uniform(0.2, 0.8))
    if steps:
        F = float(rng.uniform(4.2, 7.8)) if case == "static_ageing" else float(rng.uniform(2.0, 4.5))
        hi_first = bool(rng.random() < 0.5)
        nseg = int(rng.choice([3, 4]))
        v_hi = v0 if hi_first else v0 * F
        if v_hi > 0.5 * L["v_min"] or v_hi > 0.16 * v_sp:   # keep stick-slip at the fast level
            v_hi = min(0.5 * L["v_min"], 0.16 * v_sp)
        v_lo = v_hi / F
        v_hi_nom = _sig(v_hi * 1000, 2) / 1000
        v_lo_nom = _sig(v_lo * 1000, 2) / 1000
        is_hi = [(i % 2 == 0) == hi_first for i in range(nseg)]
        levels = [(v_hi_nom if hi else v_lo_nom) * (1 + float(rng.uniform(-0.01, 0.01))) for hi in is_hi]
        ncyc_seg = [int(rng.integers(6, 11)) if hi else int(rng.integers(4, 7)) for hi in is_hi]
        hold_at = [case == "static_ageing" and hi and i > 0 and rng.random() < 0.45 for i, hi in enumerate(is_hi)]
        hold_len = [float(rng.uniform(0.6, 1.4)) for _ in is_hi]

        def make_schedule(ts_hi, ts_lo):
            """Drive breakpoints from the stick times expected at the two levels."""
            tb, vb, holds = [0.0], [levels[0]], []
            t_cur = 0.0
            tw = 2.6 * ((ts_hi if is_hi[0] else ts_lo) + tslip_p)
            for i, lv in enumerate(levels):
                dur = ncyc_seg[i] * ((ts_hi if is_hi[i] else ts_lo) + tslip_p) + (tw if i == 0 else 0.0)
                if i > 0:
                    tb.append(t_cur)
                    vb.append(lv)
                if hold_at[i]:
                    H = hold_len[i] * ts_lo
                    th0 = t_cur + 0.5 * dur
                    tb += [th0, th0 + H]
                    vb += [0.0, lv]
                    dur += H
                    holds.append([th0, H])
                t_cur += dur
            return {"kind": "schedule", "t": tb, "v": vb}, t_cur, tw, holds

        ts_hi, ts_lo = tstick(v_hi_nom), tstick(v_lo_nom)
        P["drive"], t_end, t_w, hold_info = make_schedule(ts_hi, ts_lo)
        t_rec0 = t_w - rec_frac * (ts_hi if is_hi[0] else ts_lo)
        meta["drive_levels"] = {"v_hi": v_hi_nom, "v_lo": v_lo_nom, "factor": v_hi_nom / v_lo_nom,
                                "levels": levels, "holds": hold_info}
    else:
        t_end = t_w + n_cyc * tcyc_p
        t_rec0 = t_w - rec_frac * tstick_p
    P["t_end"] = float(t_end)
    meta["t_rec0"] = float(t_rec0)

    # ---------------- the case's effect ----------------
    def run():
        return simulate(P)

    eff = {}
    if case == "none":
        sim = run()
    elif case == "twin_branch":
        target = float(rng.uniform(0.13, 0.21))
        P["plough"]["dp"] = target * drop_p / (0.5 * Nw)
        P["plough"]["tau"] = float(rng.uniform(0.04, 0.08)) * Tn
        for it in range(4):
            sim = run()
            r_m = _twin_ratio(sim, t_rec0, t_end)
            if 0.115 <= r_m <= 0.23:
                break
            P["plough"]["dp"] *= min(max(target / max(r_m, 1e-3), 0.3), 3.0)
        eff = {"target_ratio": target, "measured_ratio": r_m}
    elif case == "load_variation":
        target = float(rng.uniform(0.13, 0.28))
        first = str(rng.choice(["up", "down"]))
        # the string rises to a pulley on a stand (N = m g - T sin) or runs down over the bench edge to
        # the motor on the floor (N = m g + T sin; kept well clear of self-locking, cos - mu_s sin >= 0.55)
        caps = {"up": 0.643, "down": None}
        sd_ = np.linspace(0.0, 0.9, 901)
        okd = np.cos(np.arcsin(sd_)) - mus0 * sd_ >= 0.55
        caps["down"] = float(sd_[okd][-1])
        best = None
        for direc in (first, "down" if first == "up" else "up"):
            sg = 1.0 if direc == "up" else -1.0
            s = min(target * Nw / (drop_p * (1 + target)), caps[direc])
            for it in range(6):
                P["theta"] = float(sg * math.asin(s))
                sim = run()
                pp = _load_pp(sim, t_rec0, t_end)
                if best is None or abs(math.log(pp / target)) < best[0]:
                    best = (abs(math.log(pp / target)), P["theta"], sim, pp)
                if 0.115 <= pp <= 0.33 or (s >= caps[direc] and pp >= 0.11):
                    break
                if s >= caps[direc] and pp < target:
                    break
                s = min(s * target / pp, caps[direc])
            if 0.11 <= pp <= 0.35:
                break
        _, P["theta"], sim, pp = best
        eff = {"target_pp": target, "measured_pp": pp, "theta_deg": math.degrees(P["theta"]),
               "string": "rising to a pulley on a stand" if P["theta"] > 0 else "down over the bench edge"}
    elif case == "static_ageing":
        target = float(rng.uniform(0.08, 0.15))
        ufac = float(rng.uniform(0.7, 1.4))

        def fac_of(t_min, t_max, tau):
            return t_max / (t_max + tau) - t_min / (t_min + tau)

        tau_a = ufac * math.sqrt(ts_hi * ts_lo)
        P["age"] = {"dmu": target * mus0 / fac_of(ts_hi, ts_lo, tau_a), "tau": tau_a}
        P["age0"] = ts_hi
        best = None
        for it in range(7):
            sim = run()
            S_w = _window_slips(sim, t_rec0, P["t_end"])
            gr = _growth(sim, t_rec0, P["t_end"])
            ok = 0.065 <= gr <= 0.17 and 12 <= len(S_w) <= 38
            score = abs(math.log(gr / target)) + (0 if 12 <= len(S_w) <= 38 else 1)
            if best is None or score < best[0]:
                best = (score, {k: (dict(v) if isinstance(v, dict) else v) for k, v in P.items()}, sim, t_rec0)
            if ok:
                break
            # stick times actually seen at the two levels (the aged threshold lengthens the sticks)
            vd_on = np.array([Drive(P["drive"]).v(s_["t_on"]) for s_ in S_w])
            ag = np.array([s_["age"] for s_ in S_w])
            hi_m = vd_on > 0.5 * (v_hi_nom + v_lo_nom)
            lo_m = (vd_on > 0) & ~hi_m
            if hi_m.any():
                ts_hi = float(np.median(ag[hi_m]))
            if lo_m.any():
                ts_lo = float(np.median(ag[lo_m]))
            P["drive"], t_end, t_w, hold_info = make_schedule(ts_hi, ts_lo)
            t_rec0 = t_w - rec_frac * (ts_hi if is_hi[0] else ts_lo)
            P["t_end"] = float(t_end)
            tau_a = ufac * math.sqrt(ts_hi * ts_lo)
            P["age"] = {"dmu": P["age"]["dmu"] * min(max(target / max(gr, 1e-3), 0.3), 3.0), "tau": tau_a}
            P["age0"] = ts_hi
        if not ok:
            _, P, sim, t_rec0 = best
            gr = _growth(sim, t_rec0, P["t_end"])
        meta["drive_levels"]["holds"] = [h_ for h_ in hold_info]
        t_end = P["t_end"]
        eff = {"target_growth": target, "measured_growth": gr, "tau_a": P["age"]["tau"],
               "dmu": P["age"]["dmu"]}
    elif case == "triggering":
        eps = float(rng.uniform(0.033, 0.06))
        f_ss = 1.0 / tcyc_p
        rmax = min(4.2, 0.3 * (fs if coarse else 1e9) / fn)
        # ramp of the pull per vibration period over the ripple of the static threshold
        rho = drop_p / (tstick_p * 2.6 * fn * mus0 * eps * Nw)
        if rho < 1.5:
            eps = max(0.032, eps * rho / 1.5)
        mount = str(rng.choice(["taped to the block", "clamped to the bench"]))
        P["trig"] = {"eps": eps, "f": 0.0, "psi": float(rng.uniform(0, 2 * math.pi))}
        best = None
        for it in range(10):
            for _ in range(500):
                ft = float(rng.uniform(2.6, rmax)) * fn
                if 0.3 <= (ft / f_ss) % 1.0 <= 0.7:
                    break
            P["trig"]["f"] = ft
            P["trig"]["eps"] = eps
            P["h_slip"] = min(Tn / 160.0, 1.0 / (25 * ft))
            P["h_stick"] = min(Tn / 200.0, 1.0 / (30 * ft))
            sim = run()
            S_w = _window_slips(sim, t_rec0, P["t_end"])
            ons = np.array([s_["t_on"] for s_ in S_w])
            f_ss_new = (len(ons) - 1) / (ons[-1] - ons[0])
            fr = (ft / f_ss_new) % 1.0
            sd = float(np.std(np.diff(ons) * ft))     # cycle lengths in vibration periods: 0 = locked
            score = abs(fr - 0.5) - 0.2 * min(sd, 0.5)
            if best is None or score < best[0]:
                best = (score, dict(P["trig"]), P["h_slip"], P["h_stick"], sim,
                        {"cycle_sd_periods": sd, "onset_phase_R": float(abs(np.mean(np.exp(2j * np.pi * ft * ons)))),
                         "ft_over_fss": ft / f_ss_new})
            if 0.25 <= fr <= 0.75 and sd > 0.1:
                break
            f_ss = f_ss_new
            if it >= 3:
                eps = max(0.031, 0.9 * eps)   # weaker coupling: out of the locking tongues
        _, P["trig"], P["h_slip"], P["h_stick"], sim, lock = best
        eps, ft = P["trig"]["eps"], P["trig"]["f"]
        eff = {"eps": eps, "f_t": ft, "f_t_over_fn": ft / fn, "mount": mount, "locking": lock}
    elif case == "drive_modulation":
        a = float(rng.uniform(0.22, 0.42))
        rt = float(rng.uniform(0.15, 0.38))
        f_ss = 1.0 / tcyc_p
        ph = float(rng.uniform(0, 2 * math.pi))
        P["t_end"] = float(t_w + n_cyc * tcyc_p / math.sqrt(1 - a * a))
        t_end = P["t_end"]
        for it in range(4):
            fm = rt * f_ss
            P["drive"] = {"kind": "eccentric", "v0": v0, "a": a, "fm": fm, "phase": ph}
            sim = run()
            f_ss = _stats(sim, t_rec0, t_end)["f_ss"]
            if 0.12 <= fm / f_ss <= 0.45:
                break
        R0 = v0 / (2 * math.pi * fm)
        eff = {"a": a, "fm": fm, "phase": ph, "pulley_radius_m": R0,
               "mechanism": "off-centre pulley" if 0.004 <= R0 <= 0.06 else "motor speed controller hunting"}
    # keep 10-40 cycles in the record: lengthen a window that came out short (the effect changed the
    # cycle), trim one that came out too long
    S_w = _window_slips(sim, t_rec0, P["t_end"])
    if not steps and len(S_w) < 14:
        S_a = [s_ for s_ in sim["slips"] if s_["t_on"] >= t_rec0] or sim["slips"][-3:]
        tc = (S_a[-1]["t_on"] - S_a[0]["t_on"]) / max(len(S_a) - 1, 1) if len(S_a) > 1 else 3 * tcyc_p
        P["t_end"] = float(t_rec0 + (n_cyc + 0.5) * tc)
        sim = run()
        S_w = _window_slips(sim, t_rec0, P["t_end"])
    if len(S_w) > 36:
        ncut = int(rng.integers(30, 36))
        t_cut = S_w[ncut]["t_off"] + float(rng.uniform(0.2, 0.8)) * (S_w[ncut + 1]["t_on"] - S_w[ncut]["t_off"])
        P["t_end"] = float(t_cut)
    meta["effect"] = eff
    meta["t_end"] = float(P["t_end"])
    return P, meta, sim, dict(fs=fs, fn=fn, dsens=dsens, v0_nom=v0_nom, drop_p=drop_p, coarse=coarse,
                              t_rec0=t_rec0, t_end=float(P["t_end"]), steps=steps)


# ----------------------------------------------------------------------------------------------------
# sensor chain and file
# ----------------------------------------------------------------------------------------------------
def _fmt_col(x, dec, comma=False):
    x = np.round(np.asarray(x, float), dec) + 0.0     # no "-0.000"
    s = np.char.mod("%." + str(dec) + "f", x)
    if comma:
        s = np.char.replace(s, ".", ",")
    return s


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    P, meta, sim, D = _design(case, seed, nuisance)
    rng = _rng(case + "/sensor", seed, nuisance)
    t0, t1 = D["t_rec0"], D["t_end"]
    st = _stats(sim, t0, t1)
    drop = st["drop"]
    fn = D["fn"]
    dsens = D["dsens"]
    m = P["m"]
    # natural frequency of the tangential mode (tangent + storage stiffness, string angle, load coupling)
    sel = (sim["t"] >= t0) & (sim["t"] <= t1)
    e_mean = float(np.mean(sim["T"][sel])) / P["k0"]
    k_t = P["k0"] + 2 * P["kq"] * e_mean
    w = 2 * math.pi * fn
    for _ in range(3):
        wt = w * P["tau_b"]
        k_dyn = k_t + P["kM"] * wt * wt / (1 + wt * wt)
        mu_k = float(Law(P["law"]).mu_vec(0.5 * st["vmax"]))
        k_tan = k_dyn * math.cos(P["theta"]) * (math.cos(P["theta"]) + mu_k * math.sin(P["theta"]))
        w = math.sqrt(k_tan / m)
    fn_true = w / (2 * math.pi)
    # ---------------- sample rate ----------------
    dur = t1 - t0
    if D["coarse"]:
        # 10-15 samples per natural period: the rate typed into the logger's box (whole Hz), the
        # design's rate corrected for the string angle's and the band's effect on fn
        fs = int(round(D["fs"] * fn_true / fn))
        if not 10.4 <= fs / fn_true <= 14.6:
            fs = int(round(fn_true * float(rng.uniform(10.8, 14.2))))
    else:
        if dsens == "ultrasonic":
            menu = FS_US
        elif nuisance == "hum":
            menu = [500, 1000]
        else:
            menu = FS_MENU
        ok = [f for f in menu if f >= 25 * fn_true and f * dur <= 150000]
        if case == "triggering":
            ok = [f for f in ok if f >= 4 * P["trig"]["f"]] or ok
        if not ok:
            ok = [f for f in menu if f * dur <= 150000] or [menu[0]]
            ok = [max(ok)]
        fs = int(rng.choice(ok[:3]))
    n = int(math.floor(dur * fs)) + 1
    tf = np.arange(n) / fs
    ts = t0 + tf
    T_true = np.interp(ts, sim["t"], sim["T"])
    N_true = np.interp(ts, sim["t"], sim["N"])
    drv = Drive(P["drive"])
    xd = drv.xv(ts) - drv.x(t0)
    vd = drv.vv(ts)
    # ---------------- software / format ----------------
    pasco = dsens in ("encoder", "rotary", "cart_velocity")
    if dsens == "ultrasonic":
        fmt = str(rng.choice(["loggerpro_csv", "loggerpro_txt", "ga", "student", "capstone"],
                             p=[.3, .2, .2, .15, .15]))
    elif pasco:
        fmt = str(rng.choice(["capstone", "student"], p=[.75, .25])) if dsens != "cart_velocity" else "capstone"
    else:
        fmt = str(rng.choice(["capstone", "loggerpro_csv", "loggerpro_txt", "ga", "student"],
                             p=[.3, .2, .15, .15, .2]))
    brand = "PASCO" if (fmt == "capstone" or (fmt == "student" and pasco)) else "Vernier"
    sign = -1.0 if (brand == "PASCO" and dsens != "none" and rng.random() < 0.6) else 1.0
    # ---------------- force channel ----------------
    Fmax = float(np.max(T_true))
    rngN = 10.0 if Fmax < 8.0 else 50.0
    bits = int(rng.choice([12, 16]))
    adc = 2 * rngN / 2 ** bits
    if adc > 0.001 * drop:
        bits = 16
        adc = 2 * rngN / 2 ** bits
        if adc > 0.001 * drop:
            adc = 0.0005 * drop   # oversampled/averaged: effective resolution finer than one code
    nu = {}
    zeroed = rng.random() < 0.6
    offset = 0.0 if zeroed else float(rng.choice([-1, 1]) * rng.uniform(0.02, 0.3))
    sigma = float(rng.uniform(0.002, 0.005)) * drop
    F = sign * T_true + offset + rng.normal(0.0, sigma, n)
    if nuisance == "hum":
        fh = int(rng.choice([50, 60]))
        A1 = float(rng.uniform(0.015, 0.032)) * drop
        A2 = float(rng.uniform(0.15, 0.35)) * A1
        A3 = float(rng.uniform(0.05, 0.2)) * A1
        ph = rng.uniform(0, 2 * np.pi, 3)
        F += (A1 * np.sin(2 * np.pi * fh * tf + ph[0]) + A2 * np.sin(4 * np.pi * fh * tf + ph[1])
              + A3 * np.sin(6 * np.pi * fh * tf + ph[2]))
        nu = {"f_hum": fh, "A1": A1, "A2": A2, "A3": A3, "A1_over_drop": A1 / drop}
    elif nuisance == "drift":
        Dd = float(rng.choice([-1, 1]) * rng.uniform(0.02, 0.06)) * drop
        taud = float(rng.uniform(0.3, 1.5)) * dur
        shape = (1 - np.exp(-tf / taud)) / (1 - math.exp(-dur / taud))
        F += Dd * shape
        nu = {"drift_total": Dd, "drift_over_drop": abs(Dd) / drop, "tau": taud}
    elif nuisance == "spikes":
        frac = float(rng.uniform(0.001, 0.004))
        k = max(3, int(round(frac * n)))
        idx = np.sort(rng.choice(np.arange(2, n - 2), size=k, replace=False))
        keep = np.concatenate([[True], np.diff(idx) > 2])
        idx = idx[keep]
        amp = rng.choice([-1, 1], len(idx)) * rng.uniform(0.3, 1.5, len(idx)) * drop
        F[idx] += amp
        nu = {"n_spikes": int(len(idx)), "fraction": len(idx) / n, "idx": idx.tolist()}
    if nuisance == "quantisation":
        q = float(rng.uniform(0.003, 0.008)) * drop
        nu = {"adc_step": q, "step_over_drop": q / drop}
    else:
        q = adc
    F = np.round(F / q) * q
    decF = int(max(3, math.ceil(-math.log10(min(q, 0.0005 * drop) / 2.0))))
    # ---------------- normal channel ----------------
    Ncol = None
    if case == "load_variation":
        Noff = float(rng.choice([0.0, rng.uniform(-0.2, 0.2), rng.uniform(2.0, 6.0)]))
        Ncol = N_true + Noff + rng.normal(0.0, float(rng.uniform(0.001, 0.003)) * m * G, n)
        Ncol = np.round(Ncol / adc) * adc
        meta["normal_sensor"] = {"offset": Noff}
    # ---------------- drive channel ----------------
    Dcol, Dkind = None, None
    miss = np.zeros(n, bool)
    dinfo = {}
    if dsens == "ultrasonic":
        p0 = float(rng.uniform(0.2, 0.5))
        sig_us = float(rng.uniform(0.0003, 0.001))
        pos = p0 + sign * xd + rng.normal(0.0, sig_us, n)
        Dcol = np.round(pos / 1e-4) * 1e-4
        pd = float(rng.uniform(0.001, 0.005))
        starts = np.flatnonzero(rng.random(n) < pd / 1.5)
        for s0 in starts:
            miss[s0: s0 + int(rng.integers(1, 3))] = True
        miss[0] = False
        Dkind = "position"
        dinfo.update(sensor="ultrasonic motion sensor", noise_m=sig_us, p0=p0, dropout_rate=float(miss.mean()))
    elif dsens in ("encoder", "rotary"):
        res = 1e-4 if dsens == "encoder" else 0.0145 * math.radians(0.25)
        Dcol = np.round(sign * xd / res) * res
        Dkind = "position"
        dinfo.update(sensor="smart cart encoder" if dsens == "encoder" else "rotary motion sensor on pulley",
                     resolution_m=res)
    elif dsens == "cart_velocity":
        vpos = [z for z in (P["drive"]["v"] if P["drive"]["kind"] == "schedule" else [P["drive"]["v0"]]) if z > 0]
        sv = float(rng.uniform(0.03, 0.07)) * min(vpos)   # the cart's smoothed encoder velocity
        Dcol = np.round((sign * vd + rng.normal(0.0, sv, n)) / 1e-5) * 1e-5
        Dkind = "velocity"
        dinfo.update(sensor="smart cart encoder velocity", noise_m_s=sv)
    # ---------------- write ----------------
    comma = fmt == "student"
    sep = {"capstone": ",", "loggerpro_csv": ",", "loggerpro_txt": "\t", "ga": ",", "student": ";"}[fmt]
    pre = {"capstone": "", "loggerpro_csv": "Latest: ", "loggerpro_txt": "Latest: ", "ga": "Run 1: ",
           "student": ""}[fmt]
    names = []
    cols = []
    stud_style = int(rng.integers(0, 2))
    tname = "time (s)" if (comma and stud_style == 0) else ("t (s)" if comma else "Time (s)")
    names.append(pre + tname)
    cols.append(_fmt_col(tf, 4 if (10000 % fs == 0) else 6, comma))
    names.append(pre + ("force (N)" if comma and stud_style == 0 else ("F (N)" if comma else "Force (N)")))
    cols.append(_fmt_col(F, decF, comma))
    if Ncol is not None:
        names.append(pre + ("normal force (N)" if comma else "Normal Force (N)"))
        cols.append(_fmt_col(Ncol, decF, comma))
    pos_mm = False
    if Dkind == "position":
        if comma:
            pos_mm = True
            names.append("position (mm)" if stud_style == 0 else "x (mm)")
            cols.append(_fmt_col(Dcol * 1000.0, 2, comma))
        else:
            names.append(pre + "Position (m)")
            cols.append(_fmt_col(Dcol, 5, comma))
    elif Dkind == "velocity":
        names.append(pre + "Velocity (m/s)")
        cols.append(_fmt_col(Dcol, 5, comma))
    if Dkind is not None and miss.any():
        cols[-1] = np.where(miss, "", cols[-1])
    ext = "txt" if fmt == "loggerpro_txt" else "csv"
    os.makedirs(outdir, exist_ok=True)
    path = os.path.abspath(os.path.join(outdir, f"{NAME}_{case}_s{seed}_{nuisance}.{ext}"))
    body = cols[0]
    for c in cols[1:]:
        body = np.char.add(np.char.add(body, sep), c)
    with open(path, "w", newline="\n") as fh:
        fh.write(sep.join(names) + "\n")
        fh.write("\n".join(body.tolist()))
        fh.write("\n")
    # ---------------- args ----------------
    args = []
    if Dkind is None:
        args += ["--v0", f"{D['v0_nom'] * 1000:g}"]
    k_label = None
    if rng.random() < 0.7 and case != "load_variation":   # (a steep string: its label is not the
        # tangential stiffness the record shows, so the students' sheet leaves it out)
        k_label = _sig(k_t * (1 + float(rng.uniform(-0.03, 0.03))), 3)
        args += ["--stiffness", f"{k_label:g}"]
    fn_given = None
    if nuisance == "fn_off":
        fn_given = fn_true * (1 + float(rng.choice([-1, 1]) * rng.uniform(0.045, 0.049)))
    elif rng.random() < 0.3:
        fn_given = fn_true * (1 + float(rng.uniform(-0.015, 0.015)))
    if fn_given is not None:
        fn_given = float(_sig(fn_given, 4))
        args += ["--fn", f"{fn_given:g}"]
    params = {
        "sim": P, "rig": meta, "format": fmt, "brand": brand, "columns": names, "fs": fs,
        "force_sign": sign, "force_offset": offset, "force_noise": sigma, "force_range": rngN,
        "adc_bits": bits, "adc_step": q, "force_decimals": decF, "drive_sensor": dsens,
        "drive_column": Dkind, "drive_info": dinfo, "position_in_mm": pos_mm, "v0_nominal_mm_s": D["v0_nom"] * 1000,
        "v0_true_mm_s": (P["drive"]["v0"] if P["drive"]["kind"] == "eccentric" else P["drive"]["v"][0]) * 1000,
        "stiffness_label": k_label, "k_tangent": k_t, "fn_true": fn_true, "fn_given": fn_given,
        "record_t0_sim": t0, "record_duration": dur, "drop": drop, "n_cycles": st["n"],
        "f_stickslip": st["f_ss"], "nuisance_info": nu,
    }
    params = _jsonable(params)
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": path,
            "args": args, "fn_true": float(fn_true), "fn_given": fn_given, "params": params}


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
    if isinstance(o, np.ndarray):
        return _jsonable(o.tolist())
    return o


if __name__ == "__main__":
    import json
    import sys
    import time
    c = sys.argv[1] if len(sys.argv) > 1 else "none"
    s = int(sys.argv[2]) if len(sys.argv) > 2 else 0
    nz = sys.argv[3] if len(sys.argv) > 3 else "clean"
    t_ = time.time()
    tr = write_record(c, s, "/tmp/w69gen2/out", nz)
    print(json.dumps({k: tr[k] for k in ("file", "args", "fn_true", "fn_given")}), time.time() - t_)
