"""Pneumatic-cylinder seal-friction rig: a lubricated elastomer lip seal, stepped by linear complementarity.

Independent record generator for `lieng diagnose` (see README.md beside this file). Only numpy/scipy.

The rig
-------
A moving-barrel seal tester. The cylinder barrel rides on a pneumatic-hydraulic feed unit (a pneumatic
cylinder checked by an oil cylinder through a flow-control valve) and moves at the drive speed v0. The piston,
with its lubricated elastomer lip seal (mass m: piston, rod and the flexure's moving mass), is held by a
stiff linear flexure of stiffness k to the frame; a piezoresistive (semiconductor strain-gauge) force cell
at the flexure's root reads the flexure force F = k x. The seal is a through-rod piston whose two chambers
are joined, so the cavity pressure energises the lip (radial load N = squeeze + pressure share) but puts no
net axial force on the piston. So m x'' + c x' + k x = F_f(w), w = v0 - x' (the barrel's speed over the lip):
the 1-DoF spring-slider, fn = sqrt(k/m)/2pi, 8-400 Hz across seeds (k 1e4-6e6 N/m, m 0.05-4 kg, N0
30-300 N, slip amplitudes 10 um - 3.6 mm, v0 0.26-22 mm/s, stick-slip period 3.6-13 Tn, 13-39 slips a
record).

Friction law (soft-EHL mixed lubrication of the lip, single-valued in steady state)
-------------------------------------------------------------------------------
A film parameter Lambda = (w/v_L)^p (inverse-hydrodynamic / soft-EHL film growth, p 0.50-0.68); the lip's
load is shared between asperity contact, alpha = 1/(1 + Lambda^q) (pq 1.15-2.2), and the film, which shears
with a Couette coefficient that grows as w/h ~ w^(1-p):

    F_k(w) = N [ mu_b alpha(w) + (1 - alpha(w)) mu_h (w/v_L)^(1-p) ],     mu(0+) = mu_b (0.30-0.60),

a minimum 0.62-0.82 mu_b (mu_h solved for it), then film strengthening; the static (breakaway) level is
mu_s0 = mu_b (1 + 0.05..0.15) (the molecular layer is expelled where the lip rests; in `triggering` at least
1 + 2.6 eps, or the shaken lip slips at every trough). v_L puts the minimum at
0.3-0.9 of the slip-speed scale wn (F_s - F_min)/k, so the slips run through the weakening branch into it.

Stick handling and integrator
-----------------------------
Stewart-Trinkle / Anitescu-Potra velocity-level linear complementarity time-stepping: per step the friction
impulse is P = h (beta1 - beta2) with a polyhedral (two-direction) cone and the slack lambda = |w(n+1)|:
0 <= beta1 _|_ lambda - w(n+1) >= 0, 0 <= beta2 _|_ lambda + w(n+1) >= 0, 0 <= lambda _|_ R(lambda) - beta1
- beta2 >= 0, with the cone radius R = F_s on a stuck contact and otherwise the kinetic law linearised about
the step's mid-speed (R = a0 + a1 lambda, F_k evaluated at (|w_n| + lambda)/2, one predictor and one
corrector pass), so the 3x3 LCP stays linear; it is solved exactly by enumerating its complementary bases.
The smooth forces (spring, damper) are integrated by the implicit midpoint rule; the film, lip and pilot
states by their exact exponential updates over the step. Step h = Tn/300 for every record.

Sensors
-------
Force: piezoresistive bridge cell -> conditioning amplifier (1st-order, 40-90 fn) -> sigma-delta ADC (sinc^3
decimation by R = 3-12 on the simulation grid: S = 300/R = 25-100 samples per natural period) -> 24-bit code;
white noise 0.05-0.15 % of the drop; a thermal zero drift of the bridge (<= 0.3 % of the drop in `clean`).
Piston / barrel position: LVDTs (demodulator lag, a carrier-ripple residual aliased into the band). Radial
load: the cavity pressure, piezoresistive transducer on a short pneumatic line (1st-order lag 1-2.5 % Tn),
turned into N by the seal's calibration (squeeze + effective area x pressure); in the displacement records it
is an eddy-current probe's lip squeeze (an affine reading of N, mm).

Files
-----
Five lab styles, by seed: a comma CSV force record `time [s],friction force [N](,radial load [N])(,barrel
position [mm])`; a LabVIEW-style TAB export with a `#` header block, `Time [ms]`, force in mN, v0 in mm/s;
a semicolon displacement record `t [s];x [mm](;squeeze [mm])(;v0 [mm/s])`; a whitespace displacement record
`t[ms] x[mm] (y[mm]) (v0[mm/s])`; a comma force record in N with the barrel position in um. `--stiffness`
(N/m) with force records, `--v0` when no drive column, `--fn` except on one seed in 8 (seed % 8 == 5, never
for triggering or fn_off).

Effect-free `none` (measured on the ground truth, seeds 0-23, clean)
--------------------------------------------------------------------
The law has no state: the friction at the contact is exactly single-valued in the sliding speed (decelerating
minus accelerating at equal true speed, 10-90 % of each slip's peak speed, median over slips: |twin| < 1e-4
of the slip's force drop). No ageing term: on the stepped-drive seeds (seed % 4 == 1, steps 3-6x between 2
or 3 recorded levels) the peak grows +0.03..+0.12 % of the drop across sticks 4.4-6.1x apart. The sensors: a
central-difference 1-DoF reading of the noise-free recorded force reads -0.35..-2.3 % of the drop more than
the same reading of point samples at the same rate (amplifier lag + sinc^3 smoothing of the breakaway kink;
the point-sampled reading itself is -1..-12 %, growing as 1/S^2: the differencing, not the data). The
force's trough is >= 0.15 of its peak in `none` (>= 0.06 load_variation, >= 0.04 static_ageing): the
flexure is never pushed through zero.

Departures (sizes measured on the ground truth, seeds 0-23, clean; the same physics for every nuisance)
---------------------------------------------------------------------------------------------------
- load_variation: the lip's energising cavity is plumbed to the feed cylinder's working chamber, whose
  pressure carries the friction load (meter-in: N rises with it, meter-out: N falls, by seed), through a
  pilot line (lag 1-2.5 % Tn): N = N0 + G (F_f,lagged - F_ref). N p-p 12.0-31.7 % of N0, recorded (force
  records: radial load in N/mN; displacement records: the lip squeeze in mm). F/N stays single-valued; F
  against w reads -3.2..+3.0 % of the drop from N's lag.
- twin_branch: lip roll-over (viscoelastic): a state phi grows with the sliding distance, dphi/dt = |w|/l_r
  (1 - phi) - phi/tau_rec (l_r 0.3-0.7 of the slip length, recovery tau_rec 6-12 % of the stick, so it is gone
  at breakaway), and raises the boundary term, mu_b (1 + gamma phi): friction higher on the decelerating half,
  twin +12.0..+21.8 % of the drop (gamma tuned on pilots).
- static_ageing: the film is squeezed out under the resting lip (Reynolds squeeze, y = (h0/h)^2 = 1 +
  2 t/tau_sq) and restored by entrainment over l_e (2-5 % of the slip length); the breakaway level is
  mu_s0 + D_a (1 - y^-1/2), tau_sq 1.5-4x the fast level's stick. The feed steps 4.3-7.5x between 2 or 3
  levels in blocks of 3-5 slips, recorded (v0 column or barrel position). Peak growth +7.3..+15.1 % of the
  drop from the fastest level's sticks to the slowest's (4.8-9.3x longer); no twin (|twin| < 2e-4).
- triggering: a pneumatic ball vibrator on the barrel shakes the lip's radial load, N = N0 (1 + eps sin
  theta(t)), eps 3.7-7.5 % (amplitude; N p-p 7.4-14.9 %), mean f_t 3.0-7.3 fn, recorded in the normal channel.
  The breakaways lock 1:n to its troughs (plateaus ~0.1 fn wide); the vibrator's frequency wanders with its
  supply pressure (+-0.6..3.5 %), and its mean is bisected onto the edge between an n- and an (n+1)-lock so
  the slips mix both: the record's f_t/f_ss (14.7-69.5) is 0.23-0.50 from an integer.
- drive_modulation: the feed unit's supply pressure oscillates, v0(t) = v0n (1 + a sin(2 pi fm t + phi)),
  a 0.23-0.42, fm/f_ss 0.13-0.39 (f_ss measured on the record); no drive column, only --v0 v0n.

Nuisances: hum 50/60 Hz fundamental 1-3.5 % of the drop (+ 3rd 0.3x, 5th 0.12x); drift a thermal zero drift
of the bridge/LVDT 2-6 % of the drop over the record (exponential approach); spikes solenoid-valve switching
transients on 0.05-0.5 % of the samples, 0.3-1.5 drops, isolated; quantisation a 0.2-1 % of the drop ADC step
(the normal channel quantised too); coarse R = 20-30 (10-15 samples per period); fn_off --fn +-5 %.
About 0.1-1.5 s a record on one core.
"""
from __future__ import annotations

import math
import os

import numpy as np
from scipy.signal import lfilter

NAME = "pneumatic_seal"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")


# ----------------------------------------------------------------------------------------------------------
# friction law
# ----------------------------------------------------------------------------------------------------------
def _mu_curve(w, mub, muh, vL, pq, p1):
    w = np.maximum(np.abs(np.asarray(w, float)), 1e-300)
    r = w / vL
    a = 1.0 / (1.0 + r ** pq)
    return mub * a + (1.0 - a) * muh * r ** p1


def _solve_muh(mub, pq, p1, ratio):
    """film coefficient mu_h such that the minimum of mu(w)/mu_b is `ratio`"""
    w = np.logspace(-2, 2.5, 900)
    lo, hi = 1e-3, 5.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        mmin = _mu_curve(w, 1.0, mid, 1.0, pq, p1).min()
        if mmin < ratio:
            lo = mid
        else:
            hi = mid
    muh = 0.5 * (lo + hi)
    c = _mu_curve(w, 1.0, muh, 1.0, pq, p1)
    return muh * mub, float(w[c.argmin()])


# ----------------------------------------------------------------------------------------------------------
# simulation: LCP time-stepping on the implicit midpoint rule
# ----------------------------------------------------------------------------------------------------------
def _simulate(P, h, vd, x0, Next=None):
    """P: dict of physics; vd: drive speed at the n+1 nodes; Next: normal load at the n step midpoints or None.

    Returns arrays: x, u (nodes), Ff, wm, N, stuck, phi (per step)."""
    m, k, c = P["m"], P["k"], P["c"]
    N0 = P["N0"]
    mub, muh, vL, pq, p1 = P["mub"], P["muh"], P["vL"], P["pq"], P["p1"]
    mus0 = P["mus0"]
    gam, lr, trec = P.get("gam", 0.0), P.get("lr", 1.0), P.get("trec", 1.0)
    Da, tsq, le = P.get("Da", 0.0), P.get("tsq", 1.0), P.get("le", 1.0)
    G, tauL, Fref = P.get("G", 0.0), P.get("tauL", 1.0), P.get("Fref", 0.0)
    n = len(vd) - 1
    M = m + h * h * k / 4.0 + h * c / 2.0
    Am = m - h * h * k / 4.0 - h * c / 2.0
    hk = h * k
    hM = h / M
    eL = math.exp(-h / tauL)
    vd = vd.tolist() if hasattr(vd, "tolist") else list(vd)
    Nx = Next.tolist() if Next is not None else None
    wtiny = 1e-9 * vL
    xs = [0.0] * (n + 1)
    us = [0.0] * (n + 1)
    Ffs = [0.0] * n
    wms = [0.0] * n
    Ns = [0.0] * n
    sts = [False] * n
    phis = [0.0] * n
    x = x0
    u = vd[0]
    w = 0.0
    stuck = True
    phi = 0.0
    y = 1.0
    Fl = Fref
    xs[0] = x
    us[0] = u
    wprev = 0.0

    def kin(wa, Nn, mbe):
        if wa <= wtiny:
            return Nn * mbe, 0.0
        r = wa / vL
        z = r ** pq
        a = 1.0 / (1.0 + z)
        f = muh * r ** p1
        F = mbe * a + (1.0 - a) * f
        da = -pq * z / (wa * (1.0 + z) ** 2)
        return Nn * F, Nn * ((mbe - f) * da + (1.0 - a) * p1 * f / wa)

    def slide(sig, wf, w0a, wpred, Nn, mbe):
        # predictor
        F0, d0 = kin(wpred, Nn, mbe)
        a0 = F0 + d0 * (0.5 * w0a - wpred)
        a1 = 0.5 * d0
        lam = (sig * wf - hM * a0) / (1.0 + hM * a1)
        if lam <= 0.0:
            return lam, a0 + a1 * max(lam, 0.0)
        # corrector about the new mid-speed
        wmid = 0.5 * (w0a + lam)
        F0, d0 = kin(wmid, Nn, mbe)
        a0 = F0 + d0 * (0.5 * w0a - wmid)
        a1 = 0.5 * d0
        lam = (sig * wf - hM * a0) / (1.0 + hM * a1)
        return lam, a0 + a1 * max(lam, 0.0)

    for i in range(n):
        vd1 = vd[i + 1]
        if Nx is not None:
            Nn = Nx[i]
        elif G != 0.0:
            Nn = N0 + G * (Fl - Fref)
            if Nn < 0.05 * N0:
                Nn = 0.05 * N0
        else:
            Nn = N0
        mbe = mub * (1.0 + gam * phi)
        uf = (u * Am - hk * x) / M
        wf = vd1 - uf
        Preq = M * wf / h  # friction force that makes w(n+1) = 0
        if stuck:
            Fs = Nn * (mus0 + Da * (1.0 - y ** -0.5))
            if abs(Preq) <= Fs:
                Ff = Preq
                w1 = 0.0
                st = True
            else:
                sig = 1.0 if Preq > 0 else -1.0
                lam, R = slide(sig, wf, 0.0, 0.0, Nn, mbe)
                if lam <= 0.0:  # cannot happen with Fs > F_k(0+); guard
                    lam = 0.0
                Ff = sig * R
                w1 = sig * lam
                st = False
        else:
            sig = 1.0 if w > 0 else -1.0
            w0a = abs(w)
            wpred = w0a + 0.5 * (w0a - abs(wprev))
            if wpred < 0.0:
                wpred = 0.5 * w0a
            lam, R = slide(sig, wf, w0a, wpred, Nn, mbe)
            if lam > 0.0:
                Ff = sig * R
                w1 = sig * lam
                st = False
            else:
                Fs = Nn * (mus0 + Da * (1.0 - y ** -0.5))
                if abs(Preq) <= max(Fs, R):
                    Ff = Preq
                    w1 = 0.0
                    st = True
                else:  # reversal
                    sig = -sig
                    lam, R = slide(sig, wf, 0.0, 0.0, Nn, mbe)
                    lam = max(lam, 0.0)
                    Ff = sig * R
                    w1 = sig * lam
                    st = False
        u1 = vd1 - w1
        x1 = x + 0.5 * h * (u + u1)
        wmid = 0.5 * (w + w1)
        aw = abs(wmid)
        # lip roll-over state (twin): grows with sliding distance, recovers viscoelastically
        if gam != 0.0:
            rate = aw / lr + 1.0 / trec
            pinf = (aw / lr) / rate
            phi = pinf + (phi - pinf) * math.exp(-rate * h)
        # film squeeze state (ageing): y = (h0/h)^2 grows linearly at rest, restored by entrainment
        if Da != 0.0:
            if aw > wtiny:
                b = aw / le
                yinf = 1.0 + 2.0 / (tsq * b)
                y = yinf + (y - yinf) * math.exp(-b * h)
            else:
                y = y + 2.0 * h / tsq
        if G != 0.0:
            Fl = Ff + (Fl - Ff) * eL
        Ffs[i] = Ff
        wms[i] = wmid
        Ns[i] = Nn
        sts[i] = st
        phis[i] = phi
        wprev = w
        x, u, w, stuck = x1, u1, w1, st
        xs[i + 1] = x
        us[i + 1] = u
    return dict(x=np.array(xs), u=np.array(us), Ff=np.array(Ffs), wm=np.array(wms), N=np.array(Ns),
                st=np.array(sts, bool), phi=np.array(phis))


# ----------------------------------------------------------------------------------------------------------
# ground-truth analysis
# ----------------------------------------------------------------------------------------------------------
def _slips(res, h, k, i_from=0, i_to=None):
    """list of slips (i0, i1, stick_before_s, peak, trough) from the stuck flags; tiny slips dropped."""
    st = res["st"]
    if i_to is None:
        i_to = len(st)
    s = st[i_from:i_to].astype(np.int8)
    d = np.diff(s)
    starts = np.nonzero(d == -1)[0] + 1 + i_from  # first slipping step
    ends = np.nonzero(d == 1)[0] + 1 + i_from  # first stuck step after a slip
    out = []
    last_end = None
    F = k * res["x"]
    for i0 in starts:
        e = ends[ends > i0]
        if len(e) == 0:
            break
        i1 = int(e[0])
        pk = F[i0]
        tr = F[i0:i1 + 1].min()
        stick = (i0 - last_end) * h if last_end is not None else np.nan
        out.append([int(i0), i1, stick, pk, tr])
        last_end = i1
    if not out:
        return []
    drops = np.array([o[3] - o[4] for o in out])
    med = np.median(drops)
    keep = []
    last_end = None
    for o, dr in zip(out, drops):
        if dr < 0.25 * med:
            continue  # micro-slip: merge into the stick
        if last_end is not None:
            o[2] = (o[0] - last_end) * h
        else:
            o[2] = np.nan
        o.append(last_end if last_end is not None else -1)  # first step of the stick before the slip
        keep.append(o)
        last_end = o[1]
    return keep


def _twin(res, slips, use_ratio=False):
    """decelerating minus accelerating friction at equal true sliding speed, 10-90 % of each slip's peak
    speed, as a fraction of the slip's force drop; median over slips."""
    vals = []
    Ff, wm, N = res["Ff"], res["wm"], res["N"]
    for i0, i1, _, pk, tr, _s in slips:
        w = wm[i0:i1]
        f = Ff[i0:i1]
        if use_ratio:
            f = f / N[i0:i1] * np.mean(N[i0:i1])
        if len(w) < 8:
            continue
        ip = int(np.argmax(w))
        wp = w[ip]
        if wp <= 0 or ip < 3 or len(w) - ip < 3:
            continue
        wa, fa = w[:ip + 1], f[:ip + 1]
        wd, fd = w[ip:][::-1], f[ip:][::-1]
        lv = np.linspace(0.1, 0.9, 17) * wp
        oa = np.argsort(wa)
        od = np.argsort(wd)
        Fa = np.interp(lv, wa[oa], fa[oa])
        Fd = np.interp(lv, wd[od], fd[od])
        vals.append(np.mean(Fd - Fa) / (pk - tr))
    return float(np.median(vals)) if vals else float("nan")


def _ageing(slips, level=None):
    """peak-force growth from the shorter to the longer sticks, fraction of the median drop. With `level`
    (the drive setpoint at each simulation step) the sticks that lie within one drive level are grouped by
    level and the slowest level's median peak is compared with the fastest's; otherwise the sticks are split
    at the geometric mean of their range. Returns (growth, ratio of the groups' median stick times)."""
    sl = [s for s in slips if np.isfinite(s[2])]
    if len(sl) < 4:
        return float("nan"), float("nan")
    dr = np.median([s[3] - s[4] for s in slips])
    t = np.array([s[2] for s in sl])
    pk = np.array([s[3] for s in sl])
    if level is not None:
        lv = np.array([level[s[0] - 1] for s in sl])
        ok = np.array([level[s[0] - 1] == level[max(s[5], 0)] for s in sl])
        u = np.unique(lv[ok])
        if len(u) >= 2:
            lo, hi = u.min(), u.max()
            gl, gh = ok & (lv == lo), ok & (lv == hi)
            if gl.sum() >= 1 and gh.sum() >= 1:
                return (float((np.median(pk[gl]) - np.median(pk[gh])) / dr),
                        float(np.median(t[gl]) / np.median(t[gh])))
    if t.max() / t.min() < 1.8:
        return 0.0, float(t.max() / t.min())
    tm = math.sqrt(t.max() * t.min())
    lo, hi = pk[t < tm], pk[t >= tm]
    if len(lo) == 0 or len(hi) == 0:
        return float("nan"), float(t.max() / t.min())
    return float((np.median(hi) - np.median(lo)) / dr), float(np.median(t[t >= tm]) / np.median(t[t < tm]))


# ----------------------------------------------------------------------------------------------------------
# design of one rig
# ----------------------------------------------------------------------------------------------------------
def _rng(*keys):
    return np.random.default_rng([30_517] + [int(q) for q in keys])


def _design(case, seed):
    ci = CASES.index(case)
    rng = _rng(1, ci, seed)
    frac = (seed * 0.6180339887 + rng.uniform(0.0, 0.15)) % 1.0
    fn = 8.0 * 50.0 ** frac
    wn = 2 * math.pi * fn
    N0 = math.exp(rng.uniform(math.log(30), math.log(300)))
    mub = rng.uniform(0.30, 0.60)
    ds = rng.uniform(0.05, 0.15)
    eps = rng.uniform(0.035, 0.075)
    if case == "triggering":
        # a shaken lip slips at every trough once eps exceeds about half the static excess: keep stick-slip
        ds = max(ds, 2.6 * eps)
    p = rng.uniform(0.50, 0.68)
    pq = rng.uniform(1.15, 2.2)
    ratio = rng.uniform(0.62, 0.82)
    muh, wmin_rel = _solve_muh(mub, pq, 1 - p, ratio)
    mus0 = mub * (1 + ds)
    dF = N0 * (mus0 - ratio * mub)  # static minus minimum kinetic
    A = math.exp(rng.uniform(math.log(8e-6), math.log(8e-4)))
    k = dF / A
    m = k / wn ** 2
    m_c = min(max(m, 0.05), 4.0)
    if m_c != m:
        m = m_c
        k = m * wn ** 2
        A = dF / k
    zeta = rng.uniform(0.004, 0.02)
    c = 2 * zeta * math.sqrt(k * m)
    Vs = wn * A
    vL = rng.uniform(0.3, 0.9) * Vs / wmin_rel
    ncyc = int(rng.integers(14, 37))
    if case == "triggering":
        ncyc = min(ncyc, 32)  # the shaker shortens the sticks
    rss = rng.uniform(4.0, min(14.0, 330.0 / ncyc))
    P = dict(fn=fn, m=m, k=k, c=c, zeta=zeta, N0=N0, mub=mub, mus0=mus0, ds=ds, muh=muh, vL=vL, pq=pq,
             p=p, p1=1 - p, ratio=ratio, A_slip=A, ncyc=ncyc, rss=rss)
    P["stepped"] = bool(case == "static_ageing" or (case == "none" and seed % 4 == 1))
    if P["stepped"]:
        P["vratio"] = rng.uniform(4.2, 7.5) if case == "static_ageing" else rng.uniform(3.0, 6.0)
        P["rss"] = rng.uniform(3.5, 5.5)  # at the fast level
        P["ncyc"] = int(rng.integers(14, 21))
    # departure draws (always drawn so that the stream is the same)
    P["twin_target"] = rng.uniform(0.12, 0.22)
    P["lr_rel"] = rng.uniform(0.3, 0.7)
    P["trec_rel"] = rng.uniform(0.06, 0.12)
    P["age_target"] = rng.uniform(0.08, 0.17)
    P["tsq_rel"] = rng.uniform(1.5, 4.0)
    P["le_rel"] = rng.uniform(0.02, 0.05)
    P["load_sign"] = 1.0 if rng.uniform() < 0.5 else -1.0
    P["load_target"] = rng.uniform(0.15, 0.33) if P["load_sign"] > 0 else rng.uniform(0.12, 0.22)
    P["tauL_rel"] = rng.uniform(0.01, 0.025)
    P["trig_eps"] = eps
    P["trig_ratio"] = rng.uniform(2.8, 7.5)
    P["trig_phase"] = rng.uniform(0, 2 * math.pi)
    P["trig_wander_rel"] = rng.uniform(0.006, 0.012)
    P["trig_wander_cycles"] = rng.uniform(3.0, 7.0)
    P["mod_a"] = rng.uniform(0.22, 0.43)
    P["mod_fm_rel"] = rng.uniform(0.13, 0.42)
    P["mod_phase"] = rng.uniform(0, 2 * math.pi)
    P["settle_frac"] = rng.uniform(0.0, 1.0)
    return P


# ----------------------------------------------------------------------------------------------------------
# drives, pilots and tuning (all on the fixed pilot grid h = Tn/300, so the physics does not depend on the
# nuisance)
# ----------------------------------------------------------------------------------------------------------
def _drive(P, kind, t):
    """drive speed at times t"""
    if kind == "const":
        return np.full_like(t, P["v0"])
    if kind == "mod":
        return P["v0"] * (1.0 + P["mod_a"] * np.sin(2 * math.pi * P["mod_fm"] * t + P["mod_phase"]))
    # stepped: piecewise constant levels from the schedule (t_switch, level), with a 0.05 Tn ramp
    ts = np.array([s[0] for s in P["schedule"]])
    lv = np.array([s[1] for s in P["schedule"]])
    idx = np.searchsorted(ts, t, side="right") - 1
    v = lv[np.clip(idx, 0, len(lv) - 1)]
    tr = 0.05 / P["fn"]
    for j in range(1, len(ts)):
        sel = (t >= ts[j]) & (t < ts[j] + tr)
        if np.any(sel):
            s = (t[sel] - ts[j]) / tr
            v[sel] = lv[j - 1] + (lv[j] - lv[j - 1]) * (0.5 - 0.5 * np.cos(math.pi * s))
    return v


def _trig_phase(P, t):
    """phase of the ball vibrator: mean frequency trig_f, wandering by trig_wander (relative)"""
    f = P["trig_f"]
    dw = P.get("trig_wander", 0.0)
    if dw == 0.0:
        return 2 * math.pi * f * t + P["trig_phase"]
    Tw = P["trig_wander_T"]
    # f(t) = f (1 + dw (sin(2 pi t/Tw) + 0.4 sin(2 pi t/(0.37 Tw) + 1)) / 1.4), integrated
    w1 = 2 * math.pi / Tw
    w2 = 2 * math.pi / (0.37 * Tw)
    integ = t + dw / 1.4 * ((1 - np.cos(w1 * t)) / w1 + 0.4 * (np.cos(1.0) - np.cos(w2 * t + 1.0)) / w2)
    return 2 * math.pi * f * integ + P["trig_phase"]


def _setpoint(P, kind, t):
    if kind != "stepped":
        return _drive(P, kind, t)
    ts = np.array([s[0] for s in P["schedule"]])
    lv = np.array([s[1] for s in P["schedule"]])
    idx = np.searchsorted(ts, t, side="right") - 1
    return lv[np.clip(idx, 0, len(lv) - 1)]


def _run(P, kind, h, T, case):
    n = int(math.ceil(T / h))
    t = np.arange(n + 1) * h
    vd = _drive(P, kind, t)
    Next = None
    if case == "triggering":
        tm = t[:-1] + 0.5 * h
        Next = P["N0"] * (1.0 + P["trig_eps"] * np.sin(_trig_phase(P, tm)))
    x0 = P["x_start"]
    res = _simulate(P, h, vd, x0, Next)
    res["t"] = t
    res["vd"] = vd
    if kind == "stepped":
        res["setpoint"] = _setpoint(P, kind, t)
    return res


def _stats(P, res, h, i_from=0):
    sl = _slips(res, h, P["k"], i_from)
    if len(sl) < 3:
        return None
    drops = np.array([s[3] - s[4] for s in sl])
    sticks = np.array([s[2] for s in sl[1:]])
    t0 = np.array([s[0] for s in sl]) * h
    fss = (len(sl) - 1) / (t0[-1] - t0[0])
    return dict(slips=sl, drop=float(np.median(drops)), stick=float(np.median(sticks)), fss=float(fss),
                n=len(sl))


def _tune(case, seed):
    """pilots: drive speed for the wanted stick time, then the departure's size; returns the physics P"""
    P = _design(case, seed)
    fn = P["fn"]
    Tn = 1.0 / fn
    h = Tn / 300.0
    N0 = P["N0"]
    drop_est = 1.8 * N0 * (P["mus0"] - P["ratio"] * P["mub"])
    P["x_start"] = (N0 * P["mus0"] - drop_est) / P["k"]
    tgt_stick = (P["rss"] - 0.7) * Tn
    P["v0"] = drop_est / (P["k"] * tgt_stick)
    Tp = 9 * P["rss"] * Tn
    st = None
    for _ in range(2):  # effect-free pilot: drive speed
        res = _run(P, "const", h, Tp, "none")
        st = _stats(P, res, h)
        P["v0"] *= st["stick"] / tgt_stick
    res = _run(P, "const", h, Tp, "none")
    st = _stats(P, res, h)
    P["drop0"] = st["drop"]
    P["fss0"] = st["fss"]
    P["stick0"] = st["stick"]
    P["Fmean0"] = float(np.mean(res["Ff"]))
    P["x_start"] = (N0 * P["mus0"] - st["drop"]) / P["k"]
    slip_len = st["drop"] / P["k"]
    P["T_ss0"] = 1.0 / st["fss"]
    if case == "twin_branch":
        P["lr"] = P["lr_rel"] * slip_len
        P["trec"] = P["trec_rel"] * st["stick"]
        P["gam"] = P["twin_target"] * st["drop"] / (0.5 * N0 * P["mub"])
        for _ in range(3):
            res = _run(P, "const", h, Tp, case)
            s2 = _stats(P, res, h)
            tw = _twin(res, s2["slips"][1:])
            P["gam"] *= P["twin_target"] / max(tw, 1e-3)
            P["v0"] *= s2["stick"] / tgt_stick
    elif case == "load_variation":
        P["Fref"] = P["Fmean0"]
        P["tauL"] = P["tauL_rel"] * Tn
        P["G"] = P["load_sign"] * P["load_target"] * N0 / st["drop"]
        for _ in range(4):
            res = _run(P, "const", h, Tp, case)
            s2 = _stats(P, res, h)
            i0 = s2["slips"][1][0]
            Nr = res["N"][i0:]
            pp = (Nr.max() - Nr.min()) / N0
            g = P["G"] * (P["load_target"] / pp) ** 0.8
            if g > 0:
                g = min(g, 0.6 / P["mus0"])
            P["G"] = g
            P["Fref"] = float(np.mean(res["Ff"][i0:]))
            P["v0"] *= s2["stick"] / tgt_stick
    elif case == "static_ageing":
        t1 = st["stick"]
        r = P["vratio"]
        P["tsq"] = P["tsq_rel"] * t1
        P["le"] = P["le_rel"] * slip_len
        gf = lambda tt: 1.0 - (1.0 + 2.0 * tt / P["tsq"]) ** -0.5
        P["Da"] = P["age_target"] * st["drop"] / (N0 * (gf(r * t1) - gf(t1)))
        v_hi = P["v0"]
        for _ in range(3):  # constant-drive pilots at the two extreme levels
            pk = []
            for v in (v_hi, v_hi / r):
                P["v0"] = v
                Tq = 6.5 * (P["stick0"] * v_hi / v + P["T_ss0"] - P["stick0"]) * 1.3
                res = _run(P, "const", h, Tq, case)
                s2 = _stats(P, res, h)
                pk.append((np.median([q[3] for q in s2["slips"][1:]]), s2["drop"], s2["stick"]))
            P["v0"] = v_hi
            growth = (pk[1][0] - pk[0][0]) / pk[0][1]
            P["stick_levels"] = [pk[0][2], pk[1][2]]
            if 0.075 <= growth <= 0.18:
                break
            P["Da"] *= P["age_target"] / max(growth, 0.01)
    elif case == "triggering":
        P["trig_f"] = P["trig_ratio"] * fn
    elif case == "drive_modulation":
        P["mod_fm"] = P["mod_fm_rel"] * st["fss"]
    if case in ("twin_branch", "load_variation"):
        res = _run(P, "const", h, Tp, case)
        s2 = _stats(P, res, h)
        P["T_ss0"] = 1.0 / s2["fss"]
    # schedule for stepped drives (times from the record's start of simulation)
    if P["stepped"]:
        r = P["vratio"]
        v_hi = P["v0"]
        levels = [v_hi, v_hi / r] if seed % 2 == 0 else [v_hi, v_hi / r, v_hi / math.sqrt(r)]
        rng = _rng(2, CASES.index(case), seed)
        order = list(levels)
        if rng.uniform() < 0.5:
            order = order[::-1]
        Tsl = P["T_ss0"] - P["stick0"]
        if "stick_levels" in P:  # aged sticks: interpolate the pilot's stick times in ln v
            sa, sb = P["stick_levels"]
            stick_of = lambda v: math.exp(math.log(sa) + (math.log(sb) - math.log(sa))
                                          * math.log(v_hi / v) / math.log(r))
        else:
            stick_of = lambda v: P["stick0"] * v_hi / v
        sched = []
        j = 0
        ncyc = 0
        settle = (1.5 + P["settle_frac"]) * P["T_ss0"]
        sched.append((0.0, order[0]))
        t = settle - 0.3 * stick_of(order[0])
        while ncyc < P["ncyc"]:
            lv = order[j % len(order)]
            nb = int(rng.integers(3, 6))
            Tlv = stick_of(lv) + Tsl
            if j > 0:
                sched.append((t, lv))
            t += nb * Tlv
            ncyc += nb
            j += 1
        P["schedule"] = [(float(a), float(b)) for a, b in sched]
        P["t_settle"] = settle
        P["T_rec"] = t - settle + 0.3 * P["T_ss0"]
        P["drive_kind"] = "stepped"
    else:
        P["t_settle"] = (1.5 + P["settle_frac"]) * P["T_ss0"]
        P["T_rec"] = (P["ncyc"] + 0.3) * P["T_ss0"]
        P["drive_kind"] = "mod" if case == "drive_modulation" else "const"
    if case == "triggering":
        # The breakaways lock 1:n to the shaker's troughs over nearly every f_t (plateaus ~0.1 fn wide, sharp
        # edges). The pneumatic ball vibrator's frequency wanders with its supply pressure; its mean is put on
        # the edge between an n- and an (n+1)-lock (bisection on short pilots), so that the wander mixes both
        # locks and f_t is not near a multiple of the record's stick-slip frequency.
        Tq = 10.5 * P["T_ss0"]
        P["trig_wander"] = 0.0

        def nlock(f):
            P["trig_f"] = f
            res = _run(P, "const", h, Tq, case)
            s2 = _stats(P, res, h, int(2.5 * P["T_ss0"] / h))
            return f / s2["fss"]

        f0 = P["trig_ratio"] * fn
        q0 = nlock(f0)
        n0 = round(q0)
        fa, qa = f0, q0
        step = (1.0 + 1.0 / max(n0, 1)) if f0 < 5.0 * fn else 1.0 / (1.0 + 1.0 / max(n0, 1))
        fb = f0 * step
        qb = nlock(fb)
        for _ in range(3):
            if round(qb) != round(qa):
                break
            fb = fb * step
            qb = nlock(fb)
        for _ in range(10):
            fm = 0.5 * (fa + fb)
            qm = nlock(fm)
            if round(qm) == round(qa):
                fa, qa = fm, qm
            else:
                fb, qb = fm, qm
        P["trig_f"] = 0.5 * (fa + fb)
        P["trig_wander"] = P["trig_wander_rel"]
        P["trig_wander_T"] = P["trig_wander_cycles"] * P["T_ss0"]
        n_lo = round(qa)
        i_from = int(P["t_settle"] / h)
        for _ in range(8):  # on the record itself: widen / re-centre the wander until both locks mix
            res = _run(P, "const", h, P["t_settle"] + P["T_rec"], case)
            s2 = _stats(P, res, h, i_from)
            q = P["trig_f"] / s2["fss"]
            P["fss_trig"] = s2["fss"]
            if 0.22 <= q - math.floor(q) <= 0.78:
                break
            up = 1.0 if round(q) <= n_lo else -1.0
            P["trig_f"] *= 1.0 + up * 0.35 * P["trig_wander"]
            P["trig_wander"] = min(1.4 * P["trig_wander"], 0.035)
    return P


# ----------------------------------------------------------------------------------------------------------
# sensors
# ----------------------------------------------------------------------------------------------------------
def _lag(sig, h, tau):
    a = math.exp(-h / tau)
    y, _ = lfilter([1 - a], [1, -a], sig, zi=[a * sig[0]])
    return y


def _sinc3(sig, R, idx):
    """sigma-delta decimation filter: three cascaded R-sample averages (causal), read at fine indices idx"""
    cs = sig
    for _ in range(3):
        c = np.cumsum(np.concatenate(([0.0], cs)))
        out = np.empty_like(cs)
        out[R - 1:] = (c[R:] - c[:-R]) / R
        out[:R - 1] = cs[:R - 1]
        cs = out
    return cs[idx]


def _measure(P, res, h, i_from, i_to, case):
    """ground-truth effect sizes in the record window"""
    k = P["k"]
    sl = _slips(res, h, k, i_from, i_to)
    drops = np.array([s[3] - s[4] for s in sl])
    out = dict(n_slips=len(sl), drop_N=float(np.median(drops)))
    t0 = np.array([s[0] for s in sl]) * h
    out["f_ss"] = float((len(sl) - 1) / (t0[-1] - t0[0])) if len(sl) > 1 else float("nan")
    out["twin"] = _twin(res, sl)
    out["twin_FoverN"] = _twin(res, sl, use_ratio=True)
    ag, tr = _ageing(sl, res.get("setpoint"))
    out["ageing"] = ag
    out["stick_ratio"] = tr
    Nw = res["N"][i_from:i_to]
    out["N_pp_rel"] = float((Nw.max() - Nw.min()) / P["N0"])
    Fs_ = k * res["x"][i_from:i_to]
    out["static_over_mu0"] = float(P["mus0"] / P["mub"])
    out["F_range_N"] = [float(Fs_.min()), float(Fs_.max())]
    return out


# ----------------------------------------------------------------------------------------------------------
# the record
# ----------------------------------------------------------------------------------------------------------
_FORMATS = ("csv_force", "lvm_tab", "semicolon_disp", "white_disp", "csv_force_um")


def _fmt_num(a, spec):
    return [spec % v for v in a]


def write_record(case: str, seed: int, outdir: str, nuisance: str = "clean") -> dict:
    if case not in CASES:
        raise ValueError("unknown case %r" % case)
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % nuisance)
    ci = CASES.index(case)
    P = _tune(case, seed)
    rs = _rng(3, ci, seed, NUISANCES.index(nuisance))
    rf = _rng(4, ci, seed)  # format and channel choices: the same for every nuisance
    fn = P["fn"]
    Tn = 1.0 / fn
    # output sampling: S = 300/R samples per natural period, sinc^3 decimation by R on the simulation grid,
    # which is h = Tn/300 for every nuisance (the same physics): R = 3..12 (S = 100..25), or R = 20..30
    # (S = 15..10) for `coarse`
    R = int(rf.integers(3, 13))
    if nuisance == "coarse":
        R = int(rs.integers(20, 31))
    S = 300.0 / R
    h = 1.0 / (300.0 * fn)
    T_tot = P["t_settle"] + P["T_rec"]
    res = _run(P, P["drive_kind"], h, T_tot, case)
    t = res["t"]
    i_from = int(round(P["t_settle"] / h))
    i_from = max(i_from, 3 * R)
    i_from = i_from - (i_from % R)
    n_out = int((len(t) - 1 - i_from) // R)
    idx = i_from + R * np.arange(n_out)
    i_to = idx[-1]
    truth = _measure(P, res, h, i_from, i_to, case)
    drop = truth["drop_N"]
    k = P["k"]
    N0 = P["N0"]
    # drive position (barrel) on the fine grid
    vd = res["vd"]
    xd = np.concatenate(([0.0], np.cumsum(0.5 * h * (vd[1:] + vd[:-1]))))
    # normal load at the nodes (per-step values are step midpoints)
    Nst = res["N"]
    Nnode = np.concatenate(([Nst[0]], 0.5 * (Nst[1:] + Nst[:-1]), [Nst[-1]]))
    t_out = t[idx] - t[idx[0]]
    T_rec = t_out[-1]
    fmt = _FORMATS[(3 * seed + ci) % 5]
    force_rec = fmt in ("csv_force", "lvm_tab", "csv_force_um")
    want_N = case in ("load_variation", "triggering") or rf.uniform() < 0.35
    if case == "drive_modulation":
        drive_col = False
    elif P["stepped"]:
        drive_col = True
    else:
        drive_col = rf.uniform() < 0.55
    sens = dict(S_per_Tn=float(S), R=R, h=float(h), fs_Hz=float(S * fn))
    # ---- main channel: force cell (F = k x) or piston LVDT (x) ----
    if force_rec:
        fc = rf.uniform(40.0, 90.0) * fn
        main = _lag(k * res["x"], h, 1.0 / (2 * math.pi * fc))
        main = _sinc3(main, R, idx)
        scale_drop = drop
        sens["force_amp_fc_Hz"] = float(fc)
    else:
        fc = rf.uniform(30.0, 60.0) * fn
        main = _lag(res["x"], h, 1.0 / (2 * math.pi * fc))
        main = _sinc3(main, R, idx)
        scale_drop = drop / k
        sens["lvdt_demod_fc_Hz"] = float(fc)
        # carrier ripple residual (2 x carrier, aliased by the output rate)
        fcar = rf.uniform(2.5e3, 10e3)
        fr = 2 * fcar
        amp = rf.uniform(0.0005, 0.0015) * scale_drop
        main = main + amp * np.sin(2 * math.pi * fr * t[idx] + rf.uniform(0, 6.28))
        sens["lvdt_carrier_Hz"] = float(fcar)
    main = main + rs.normal(0.0, rf.uniform(0.0005, 0.0015) * scale_drop, n_out)
    # thermal zero drift: tiny in clean, 2-6 % of the drop over the record with nuisance `drift`
    tau_th = rf.uniform(0.3, 1.5) * T_rec
    shape = (1 - np.exp(-t_out / tau_th)) / (1 - math.exp(-T_rec / tau_th))
    dz = rf.uniform(-0.003, 0.003)
    if nuisance == "drift":
        dz = rs.uniform(0.02, 0.06) * (1 if rs.uniform() < 0.5 else -1)
    main = main + dz * scale_drop * shape
    sens["zero_drift_rel_drop"] = float(dz)
    # ---- normal channel ----
    Ncol = None
    if want_N:
        if case == "triggering":
            tl = rf.uniform(0.004, 0.008) * Tn  # piezoresistive load ring under the seal housing
        else:
            tl = rf.uniform(0.01, 0.025) * Tn  # cavity-pressure transducer on a short pneumatic line
        Nm = _sinc3(_lag(Nnode, h, tl), R, idx)
        Nm = Nm + rs.normal(0.0, rf.uniform(0.0005, 0.0015) * N0, n_out)
        Nm = Nm + rf.uniform(-0.002, 0.002) * N0 * shape
        sens["normal_lag_s"] = float(tl)
        if force_rec:
            Ncol = Nm
        else:
            kr = rf.uniform(200.0, 2000.0)  # lip radial stiffness, N/mm: eddy-current probe reads the squeeze
            s0 = rf.uniform(0.15, 0.5)
            Ncol = s0 + Nm / kr
            sens["squeeze_probe_N_per_mm"] = float(kr)
    # ---- drive channel ----
    Dcol = None
    dkind = None
    if drive_col:
        if fmt in ("lvm_tab", "semicolon_disp", "white_disp"):
            dkind = "v0"
            Dcol = _setpoint(P, P["drive_kind"], t[idx])
        else:
            dkind = "position"
            pos = _sinc3(xd, R, idx)
            pos = pos - pos[0] + rf.uniform(5e-3, 40e-3)  # m
            pos = pos + rs.normal(0.0, 0.005 * P["v0"] * Tn, n_out)
            Dcol = pos
    # ---- nuisances ----
    if nuisance == "hum":
        fmains = 50.0 if rs.uniform() < 0.5 else 60.0
        a1 = rs.uniform(0.01, 0.035) * scale_drop
        hum = a1 * np.sin(2 * math.pi * fmains * t_out + rs.uniform(0, 6.28))
        hum += 0.3 * a1 * np.sin(2 * math.pi * 3 * fmains * t_out + rs.uniform(0, 6.28))
        hum += 0.12 * a1 * np.sin(2 * math.pi * 5 * fmains * t_out + rs.uniform(0, 6.28))
        main = main + hum
        if Ncol is not None:
            Ncol = Ncol + (a1 / scale_drop) * 0.01 * N0 * np.sin(2 * math.pi * fmains * t_out)
        sens["hum"] = dict(f=fmains, amp_rel_drop=float(a1 / scale_drop))
    if nuisance == "spikes":
        frac = rs.uniform(0.0005, 0.005)
        nsp = max(2, int(round(frac * n_out)))
        pos_ = np.sort(rs.choice(np.arange(2, n_out - 2), size=nsp, replace=False))
        keep = [pos_[0]]
        for p_ in pos_[1:]:
            if p_ - keep[-1] > 2:
                keep.append(p_)
        pos_ = np.array(keep)
        amps = rs.uniform(0.3, 1.5, len(pos_)) * np.where(rs.uniform(size=len(pos_)) < 0.5, -1, 1)
        main[pos_] += amps * scale_drop
        sens["spikes"] = dict(n=int(len(pos_)), frac=float(len(pos_) / n_out))
    if nuisance == "quantisation":
        q = rs.uniform(0.002, 0.01) * scale_drop
        main = np.round(main / q) * q
        if Ncol is not None:
            qn = rs.uniform(0.002, 0.01) * (np.ptp(Ncol) if case != "none" else 0.01 * np.mean(Ncol))
            qn = max(qn, 1e-12)
            Ncol = np.round(Ncol / qn) * qn
        sens["quant_step_rel_drop"] = float(q / scale_drop)
    else:
        # 24-bit converter on a +-2 x max range
        q = 4.0 * np.max(np.abs(main)) / 2 ** 24
        main = np.round(main / q) * q
    # fn given?
    fn_given = fn
    if nuisance == "fn_off":
        fn_given = fn * (1.05 if rs.uniform() < 0.5 else 0.95)
    elif seed % 8 == 5 and case != "triggering":
        fn_given = None
    # ---- write ----
    os.makedirs(outdir, exist_ok=True)
    base = "%s_%s_s%d_%s" % (NAME, case, seed, nuisance)
    args = []
    if fn_given is not None:
        args += ["--fn", "%.5g" % fn_given]
    if Dcol is None:
        args += ["--v0", "%.6g" % (P["v0"] * 1e3)]
    if force_rec:
        args += ["--stiffness", "%.6g" % k]
    cols = []
    heads = []
    if fmt == "csv_force":
        path = os.path.join(outdir, base + ".csv")
        heads.append("time [s]"); cols.append(_fmt_num(t_out, "%.9g"))
        heads.append("friction force [N]"); cols.append(_fmt_num(main, "%.7g"))
        if Ncol is not None:
            heads.append("radial load [N]"); cols.append(_fmt_num(Ncol, "%.7g"))
        if Dcol is not None:
            heads.append("barrel position [mm]"); cols.append(_fmt_num(Dcol * 1e3, "%.8g"))
        sep, pre = ",", []
    elif fmt == "csv_force_um":
        path = os.path.join(outdir, base + ".csv")
        heads.append("t [s]"); cols.append(_fmt_num(t_out, "%.9g"))
        heads.append("F [N]"); cols.append(_fmt_num(main, "%.7g"))
        if Ncol is not None:
            heads.append("N [N]"); cols.append(_fmt_num(Ncol, "%.7g"))
        if Dcol is not None:
            heads.append("position [um]"); cols.append(_fmt_num(Dcol * 1e6, "%.9g"))
        sep, pre = ",", []
    elif fmt == "lvm_tab":
        path = os.path.join(outdir, base + ".txt")
        heads.append("Time [ms]"); cols.append(_fmt_num(t_out * 1e3, "%.9g"))
        heads.append("Force [mN]"); cols.append(_fmt_num(main * 1e3, "%.7g"))
        if Ncol is not None:
            heads.append("Radial load [mN]"); cols.append(_fmt_num(Ncol * 1e3, "%.7g"))
        if Dcol is not None:
            heads.append("v0 [mm/s]"); cols.append(_fmt_num(Dcol * 1e3, "%.7g"))
        sep = "\t"
        pre = ["# LabVIEW Measurement", "# Writer_Version\t2", "# Reader_Version\t2", "# Separator\tTab",
               "# Multi_Headings\tNo", "# X_Columns\tOne",
               "# Operator\tpneumatics lab, seal test bench 2",
               "# Rig\tmoving-barrel seal tester, through-rod piston, lubricated NBR lip seal",
               "# Flexure stiffness [N/m]\t%.6g" % k,
               "# Sample rate [Hz]\t%.6g" % (S * fn),
               "# ***End_of_Header***"]
    elif fmt == "semicolon_disp":
        path = os.path.join(outdir, base + ".csv")
        heads.append("t [s]"); cols.append(_fmt_num(t_out, "%.9g"))
        heads.append("x [mm]"); cols.append(_fmt_num(main * 1e3, "%.7g"))
        if Ncol is not None:
            heads.append("squeeze [mm]"); cols.append(_fmt_num(Ncol, "%.7g"))
        if Dcol is not None:
            heads.append("v0 [mm/s]"); cols.append(_fmt_num(Dcol * 1e3, "%.7g"))
        sep, pre = ";", []
    else:  # white_disp
        path = os.path.join(outdir, base + ".txt")
        heads.append("t[ms]"); cols.append(_fmt_num(t_out * 1e3, "%.9g"))
        heads.append("x[mm]"); cols.append(_fmt_num(main * 1e3, "%.7g"))
        if Ncol is not None:
            heads.append("y[mm]"); cols.append(_fmt_num(Ncol, "%.7g"))
        if Dcol is not None:
            heads.append("v0[mm/s]"); cols.append(_fmt_num(Dcol * 1e3, "%.7g"))
        sep, pre = "  ", []
    lines = pre + [sep.join(heads)] + [sep.join(r) for r in zip(*cols)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    params = {kk: vv for kk, vv in P.items() if kk != "schedule"}
    if P["stepped"]:
        params["schedule_s_mps"] = [[a - P["t_settle"], b] for a, b in P["schedule"]]
    params.update(format=fmt, record="force" if force_rec else "displacement", drive_column=dkind,
                  normal_column=Ncol is not None, sensors=sens, truth=truth, T_rec_s=float(T_rec),
                  n_samples=int(n_out), v0_mm_s=float(P["v0"] * 1e3))
    if case == "triggering":
        params["trig_over_fn"] = float(P["trig_f"] / fn)
        params["trig_over_fss"] = float(P["trig_f"] / truth["f_ss"])
    if case == "drive_modulation":
        params["fm_over_fss"] = float(P["mod_fm"] / truth["f_ss"])
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=os.path.abspath(path),
                args=args, fn_true=float(fn), fn_given=None if fn_given is None else float(fn_given),
                params=_jsonable(params))


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating, float)):
        return float(o)
    if isinstance(o, (np.integer, int)) and not isinstance(o, bool):
        return int(o)
    if isinstance(o, (np.bool_, bool)):
        return bool(o)
    return o


# ----------------------------------------------------------------------------------------------------------
# self-check
# ----------------------------------------------------------------------------------------------------------
def _read(path):
    """parse a record with numpy only: '#' lines skipped, one header line, any of the four separators"""
    with open(path) as f:
        lines = [ln for ln in f if not ln.startswith("#") and ln.strip()]
    head = lines[0]
    sep = "," if "," in head else (";" if ";" in head else ("\t" if "\t" in head else None))
    data = np.loadtxt(lines[1:], delimiter=sep)
    names = head.strip().split(sep) if sep else head.split()
    return names, data


def _twin_1dof(t, F, k, m, c, v0):
    """a 1-DoF reading of a record: friction F + c x' + m x'' against w = v0 - x' (x = F/k), twin as in
    _twin (decelerating minus accelerating, 10-90 % of each slip's peak speed, fraction of the drop)"""
    x = F / k
    xd = np.gradient(x, t)
    xdd = np.gradient(xd, t)
    fr = F + c * xd + m * xdd
    w = v0 - xd
    thr = 0.05 * np.percentile(w, 99.5)
    sl = w > thr
    d = np.diff(sl.astype(np.int8))
    st = np.nonzero(d == 1)[0] + 1
    en = np.nonzero(d == -1)[0] + 1
    vals = []
    for a in st:
        e = en[en > a]
        if len(e) == 0:
            break
        b = e[0]
        if b - a < 6:
            continue
        ww, ff = w[a:b], fr[a:b]
        ip = int(np.argmax(ww))
        if ip < 2 or b - a - ip < 3:
            continue
        drop = F[max(a - 2, 0)] - F[a:min(b + 3, len(F))].min()
        lv = np.linspace(0.1, 0.9, 17) * ww[ip]
        wa, fa = ww[:ip + 1], ff[:ip + 1]
        wd, fd = ww[ip:], ff[ip:]
        oa, od = np.argsort(wa), np.argsort(wd)
        vals.append(np.mean(np.interp(lv, wd[od], fd[od]) - np.interp(lv, wa[oa], fa[oa])) / drop)
    return float(np.median(vals)) if vals else float("nan")


def _selfcheck(outdir="/tmp/gen30/selfcheck", seeds=range(8), nuisances=("clean",), verbose=True):
    import json
    import time
    rows = []
    ok = True
    for case in CASES:
        for seed in seeds:
            for nu in nuisances:
                t0 = time.time()
                r = write_record(case, seed, outdir, nu)
                el = time.time() - t0
                p = r["params"]
                tr = p["truth"]
                names, d = _read(r["file"])
                msg = []
                if not np.all(np.isfinite(d)) or d.shape[0] < 500:
                    msg.append("parse")
                if not (12 <= tr["n_slips"] <= 40):
                    msg.append("cycles %d" % tr["n_slips"])
                if not (7.5 <= r["fn_true"] <= 410):
                    msg.append("fn")
                S = p["sensors"]["S_per_Tn"]
                if nu == "coarse" and not (10 <= S <= 15) or nu != "coarse" and not (20 <= S <= 100):
                    msg.append("S %.1f" % S)
                if case == "none":
                    if abs(tr["twin"]) > 0.03 or (np.isfinite(tr["ageing"]) and abs(tr["ageing"]) > 0.03):
                        msg.append("inherent")
                if case == "load_variation" and not (0.10 <= tr["N_pp_rel"] <= 0.40):
                    msg.append("load %.3f" % tr["N_pp_rel"])
                if case == "twin_branch" and not (0.10 <= tr["twin"] <= 0.25):
                    msg.append("twin %.3f" % tr["twin"])
                if case == "static_ageing" and not (0.05 <= tr["ageing"] <= 0.20 and tr["stick_ratio"] >= 3.5):
                    msg.append("ageing %.3f" % tr["ageing"])
                if case == "triggering":
                    q = p["trig_over_fss"]
                    if not (2.5 <= p["trig_over_fn"] <= 8.0 and 0.15 <= q - math.floor(q) <= 0.85
                            and 0.03 <= p["trig_eps"] <= 0.08):
                        msg.append("trig %.2f %.2f" % (p["trig_over_fn"], q))
                if case == "drive_modulation" and not (0.1 <= p["fm_over_fss"] <= 0.5 and 0.2 <= p["mod_a"] <= 0.45):
                    msg.append("mod")
                if case in ("drive_modulation",) and p["drive_column"] is not None:
                    msg.append("drive recorded")
                if case == "static_ageing" and p["drive_column"] is None:
                    msg.append("drive not recorded")
                if r["fn_given"] is None and (case == "triggering" or nu == "fn_off"):
                    msg.append("fn missing")
                tw1 = float("nan")
                if case == "none" and nu == "clean" and p["drive_column"] != "position":
                    col = d[:, 1] * (1e-3 if names[1].lower().startswith("force [mn]") else 1.0)
                    tt = d[:, 0] * (1e-3 if "[ms]" in names[0] else 1.0)
                    if p["record"] == "displacement":
                        col = col * 1e-3 * p["k"]
                    v0 = p["v0"]
                    if p["drive_column"] == "v0":
                        v0 = d[:, -1] * 1e-3
                    tw1 = _twin_1dof(tt, col, p["k"], p["m"], p["c"], v0)
                if el > 5.0:
                    msg.append("slow %.1fs" % el)
                ok = ok and not msg
                rows.append(dict(case=case, seed=seed, nuisance=nu, time=el, truth=tr, twin_1dof=tw1, msg=msg,
                                 extra={kk: p.get(kk) for kk in ("trig_over_fn", "trig_over_fss", "trig_eps",
                                                                 "fm_over_fss", "mod_a")}))
                if verbose:
                    print("%-16s %d %-12s %5.2fs slips %2d drop %.4g twin %+.4f (1dof %+.4f) age %+.4f (x%.1f) "
                          "Npp %.3f %s %s" % (case, seed, nu, el, tr["n_slips"], tr["drop_N"], tr["twin"], tw1,
                                              tr["ageing"], tr["stick_ratio"], tr["N_pp_rel"],
                                              json.dumps({kk: round(vv, 3) for kk, vv in rows[-1]["extra"].items()
                                                          if vv is not None}), " ".join(msg)))
    return ok, rows


if __name__ == "__main__":
    import sys
    nus = tuple(sys.argv[1].split(",")) if len(sys.argv) > 1 else ("clean",)
    good, _ = _selfcheck(nuisances=nus)
    print("SELFCHECK", "OK" if good else "FAILED")
