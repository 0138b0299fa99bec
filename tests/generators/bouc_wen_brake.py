"""Bouc-Wen brake rig: an independent generator of "measured" stick-slip records.

Rig.  A brake / pin-on-disc torque rig read as an equivalent linear slider at the pad radius R (60-150 mm): the
pad (equivalent mass m = J / R^2) sits on a torque arm held by a torsional spring (k = k_theta / R^2, 2-60 kN/m),
fn = sqrt(k/m)/2pi drawn log-uniform in 3-40 Hz; x is the arm's deflection at the pad (the spring's extension),
the disc's track speed vd(t), the sliding speed s = vd - x'.  The disc is driven by a motor through a gearbox with
a small backlash; the drive is one-directional, so the gear stays loaded by the friction and the play is taken up
once, when the motor starts (before the record): the disc then follows the motor exactly, and the motor's
incremental encoder reads the disc plus that constant play.

Friction.  No stick switch, no Karnopp band, no regularised sign: a **Bouc-Wen hysteretic presliding state** z,
    dz/dt = s (1 - |z|^n (beta + gamma sign(s z))) / delta,   A = 1, beta + gamma = 1, n 1.5-3, beta 0.55-0.8,
    delta = mu_s N0 / k_p, presliding stiffness k_p = 40-120 k (150-250 k on `triggering`),
multiplied by a stretched-exponential Stribeck level, plus a viscous term and the interface's presliding damping:
    F = N(t) mu(|s|) z g + c_v s + c_p s (1 - |z|^n (beta + gamma sign(s z))),
    mu(s) = mu_k + (mu_s' - mu_k) exp(-(s/v_s)^q),  mu_s/mu_k 1.18-1.4, q 1.5-2.5, v_s 2-5 v0,
c_v 1-3.5 % and c_p 15-40 % of the critical damping of the slider resp. of the presliding mode (c_p acts only
while z is below saturation).  Stick is the hysteretic state's own elastic presliding: the pad creeps at 1-6 %
of the drive in stick, and z saturates (z = 1) in every slip, so in the slip the friction is exactly N mu(s) +
c_v s, single-valued.  g = 1 and mu_s' = mu_s unless a departure says otherwise.
Departures (each alone):
  load_variation   the floating caliper rides on a cam along the arm's deflection, N = N0 (1 + c sin(2 pi (x -
                   x_c)/lambda)), lambda 2.5-5 arm travels, the travel on the cam's rising flank; c from a pilot
                   run so that N moves 14-31 % p-p (re-scaled if the record's p-p leaves 12-35 %).  The normal
                   force is recorded on every record of this case.
  twin_branch      a wear-debris (third-body) state D: dD/dt = |s| (|s|/(|s| + v_d)) (1 - D)/L_d - D/tau_c (made
                   by fast sliding, v_d 0.15-0.3 of the nominal slip speed pi fn dx, over L_d 0.3-0.7 nominal slips;
                   swept out / compacted in stick, tau_c 0.15-0.35 stick times),
                   g = 1 + kappa D: the friction while decelerating is higher than while accelerating at equal
                   speed; kappa scaled on a pilot run towards a twin of 13-21 % of the drop.
  static_ageing    a contact-age state th, dth/dt = 1 - th |s|/L_a (L_a 1-3 delta: Dieterich's ageing law),
                   mu_s' = mu_s + b_a ln(1 + th/tau_a), tau_a 0.05-0.2 Tn, b_a set for a peak growth of 11-17 %
                   of the drop; the drive steps 4.2-7.8x between levels (hi, lo, hi, lo on even seeds; hi, lo, hi,
                   hold, hi, hold, hi on odd seeds, holds of 2-6 and 3-10 fast stick times); the drive is recorded;
                   v_s 4.5-6 v0 here, so that the law's own loading-rate effect on the peak stays small.
  triggering       a normal-load shaker N = N0 (1 + a sin(2 pi f_t t)), a 3-4.5 % (lowered towards 3 % on
                   retries), f_t 2.5 fn .. min(8 fn, 0.45 f_presliding), re-drawn (up to 8 runs) while the
                   record's f_t/f_ss is within 0.15 of an integer (the breakaways lock to the shaker's troughs
                   readily); a sharper Stribeck curve here (v_s 0.9-1.3 v0, q 2.6-3.5, mu_s/mu_k 1.3-1.45) so
                   that the shaker triggers slips rather than quenching the stick-slip.
  drive_modulation the motor speed v0 (1 + a sin(2 pi fm t + p)), a 0.2-0.45, fm 0.13-0.42 of the pilot's f_ss;
                   no drive column on this case, only --v0 (the nominal speed).
Integrator: own fixed-step **ROS2** (Verwer et al. 1999: the two-stage L-stable Rosenbrock-W method, gamma =
1 + 1/sqrt 2) on (x, x', z, D, th), an analytic 3x3 Jacobian for (x, x', z) solved by Cramer's rule, diagonal for
D and th; output step Tn/260 (at most 1/(30 f_t)), sub-stepped wherever |J_vv| h or 0.15 |J_zz| h exceeds 0.5
(the fast slips: the weakening's unstable rate and the Bouc-Wen rate); |z| <= 1 (invariant of the exact flow)
enforced by projection.  Each record starts 0.2-0.8 stick-slip periods after the first slip (the rig run in).
Measurement chain: the arm's strain-gauge torque sensor read as the force at the pad (k x) through a bridge
amplifier (first-order low-pass at 8-30 fn; the clamp-force load cell through one at 0.7 of that), sampled by a
clock with Gaussian jitter (0.5-3 % of the interval; the samples are stamped with their nominal times) that drops
0.05-0.3 % of the samples (single rows missing), white (0.2-0.6 % of the drop) + 1/f (0.1-0.4 %) noise, a 24-bit
ADC; the motor encoder's counts (0.5-3 um of track) as a position column, or the controller's speed readout
(counts over ~40 counts' time, at least 8 samples, at most a quarter period) as a v0 column, or neither (--v0).
Records: force (N or mN, `--stiffness`; clamp force N/mN; position mm/um or v0 mm/s) or displacement (x = F/k mm,
an affine proximity reading y of the clamp spring in mm, v0 mm/s); comma with `name [unit]`, TAB with
`name/unit`, whitespace with `name_unit`, or semicolon with a decimal comma and `Name (unit)` (time in s or ms);
a `#` comment line first.  20-100 samples per natural period (10-15 on `coarse`).  `--fn` on 7 of 8 seeds (left
out on one seed per case, never on `triggering` or `fn_off`).  0.3-3.3 s a record.

Ground truth (params["measured"]), measured on the noise-free simulated contact signals over the recorded span:
twin = decelerating minus accelerating contact friction at equal sliding speed (15-85 % of each slip's peak
speed, median over the grid, then over slips), over the slip's spring-force drop (twin_mu: the same with the
friction coefficient F/N); ageing_growth = b ln(t_max/t_min)/median drop from a fit peak = a + b ln t_stick;
load_pp = p-p of N over its mean; cycles; f_ss/fn.  MEASURED below is the check script's summary for seeds 0-7
(seed s with nuisance s mod 7), [min, max] over the 8 records.  Notes:
  * `none` holds, beyond a strict 1-DoF slider, the Bouc-Wen presliding hysteresis: the pad creeps at 2.0-4.9 %
    of v0 in the middle of each stick (stick_creep_rel), over a presliding scale delta of 1.9-3.6 % of the slip
    (presliding_delta_over_slip), and the contact's presliding mode (at sqrt(k_p/k) fn, 6-11 fn) rings briefly
    after each arrest, damped by c_p; its slip friction is single-valued (twin -0.00..+0.01 % of the drop); the
    sensor's low-pass (13-28 fn on these seeds) and clock jitter; a 1-DoF reading of the noise-free low-passed
    arm force (friction = m x'' + c x' + k x) reads a twin of +0.08..+0.12 %.  Constant drive, constant load, no
    ageing (peak growth 0: every cycle alike), f_ss/fn 0.11-0.18.
  * `static_ageing`: the growth is 8.7-11.8 % of the drop over stick times 5.5-7.5x apart; the same runs without
    the ageing law grow 0.1-3.5 % (the Bouc-Wen/Stribeck loading-rate effect on the breakaway).
  * `twin_branch`: +15.1..+20.9 % of the drop (0.00 % with kappa = 0); a 1-DoF reading of the sensor +15.0..+20.4 %.
  * `load_variation`: the force's twin is -52..-23 % of the drop (the load rises along the stick's ramp), the
    friction coefficient's +0.1..+0.3 %.
  * `triggering`: f_t/f_ss 25.8-42.8, 3.0-3.4 % of N0 (load p-p 6.0-6.8 %); one record of eight (seed 4) stays
    locked at f_t/f_ss = 29.000 after 8 runs, one (seed 3) is locked at 41.500 (two periods of 83 shaker cycles);
    the shaker adds a twin of -4.4..+2.9 % of the drop to the force (F/N: +-0.03 %).
"""
import json
import math
import os
import time as _time

import numpy as np

NAME = "bouc_wen_brake"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

# the check script's summary (/tmp/check_bwb.py): [min, max] over seeds 0-7 of each case
MEASURED = {
    "none": {"twin": [-0.0000, 0.0001], "twin_1dof_sensor": [0.0008, 0.0012], "ageing_growth": [0.0, 0.0],
             "load_pp": [0.0, 0.0], "cycles": [20, 40], "fss_over_fn": [0.108, 0.184],
             "stick_creep_rel": [0.020, 0.049], "presliding_delta_over_slip": [0.019, 0.036], "time_s": [0.39, 1.06]},
    "load_variation": {"twin": [-0.520, -0.234], "twin_mu": [0.0009, 0.0033], "ageing_growth": [0.0, 0.0],
                       "load_pp": [0.199, 0.345], "cycles": [17, 24], "fss_over_fn": [0.067, 0.134],
                       "time_s": [0.66, 1.82]},
    "twin_branch": {"twin": [0.151, 0.209], "twin_kappa0": [0.0, 0.0001], "twin_1dof_sensor": [0.150, 0.204],
                    "ageing_growth": [0.0, 0.0], "load_pp": [0.0, 0.0], "cycles": [25, 50],
                    "fss_over_fn": [0.134, 0.246], "time_s": [0.32, 0.76]},
    "static_ageing": {"twin": [-0.004, 0.0], "ageing_growth": [0.087, 0.118], "ageing_growth_lawfree": [0.001, 0.035],
                      "stick_time_ratio": [5.48, 7.53], "load_pp": [0.0, 0.0], "cycles": [18, 23],
                      "fss_over_fn": [0.042, 0.062], "time_s": [0.75, 1.12]},
    "triggering": {"twin": [-0.044, 0.029], "twin_mu": [-0.0003, 0.0002], "ageing_growth": [0.0, 0.0],
                   "load_pp": [0.060, 0.068], "ft_over_fss": [25.8, 42.8], "ft_over_fn": [3.79, 6.35],
                   "cycles": [27, 45], "fss_over_fn": [0.121, 0.181], "time_s": [1.22, 3.33]},
    "drive_modulation": {"twin": [0.0, 0.0021], "twin_1dof_sensor": [-0.0007, 0.0027],
                         "ageing_growth": [-0.007, 0.042], "stick_time_ratio": [1.51, 2.17], "load_pp": [0.0, 0.0],
                         "fm_over_fss": [0.135, 0.332], "cycles": [25, 39], "fss_over_fn": [0.107, 0.185],
                         "time_s": [0.30, 1.78]},
}

_SQ2 = math.sqrt(2.0)
_GAM = 1.0 + 1.0 / _SQ2


# ----------------------------------------------------------------------------------------------------------
# parameters
# ----------------------------------------------------------------------------------------------------------
def _draw(case, seed):
    ci = CASES.index(case)
    rng = np.random.default_rng([7731, ci, seed])
    p = {}
    p["fn"] = float(np.exp(rng.uniform(np.log(3.0), np.log(40.0))))
    p["k"] = float(np.exp(rng.uniform(np.log(2.0e3), np.log(6.0e4))))           # N/m
    p["m"] = p["k"] / (2 * math.pi * p["fn"]) ** 2
    p["R"] = float(rng.uniform(0.06, 0.15))                                     # m, pad radius
    p["mu_k"] = float(rng.uniform(0.28, 0.5))
    p["mu_s"] = p["mu_k"] * float(rng.uniform(1.18, 1.4) if case != "triggering" else rng.uniform(1.3, 1.45))
    p["x_static"] = float(np.exp(rng.uniform(np.log(0.4e-3), np.log(4e-3))))    # m, arm deflection at mu_s N0
    p["N0"] = p["k"] * p["x_static"] / p["mu_s"]                                # N
    p["q"] = float(rng.uniform(1.5, 2.5))                                       # Stribeck exponent
    p["n_bw"] = float(rng.uniform(1.5, 3.0))
    p["beta_bw"] = float(rng.uniform(0.55, 0.8))
    p["gamma_bw"] = 1.0 - p["beta_bw"]
    p["kp_over_k"] = float(rng.uniform(40.0, 120.0))
    if case == "triggering":
        # a stiffer, better damped contact: its presliding mode stays well above the shaker
        p["kp_over_k"] = float(rng.uniform(150.0, 250.0))
    p["delta"] = p["mu_s"] * p["N0"] / (p["kp_over_k"] * p["k"])               # m
    wn = 2 * math.pi * p["fn"]
    p["zeta_arm"] = float(rng.uniform(0.005, 0.02))
    p["c_arm"] = 2 * p["zeta_arm"] * p["m"] * wn
    p["zeta_visc"] = float(rng.uniform(0.01, 0.035))
    p["c_visc"] = 2 * p["zeta_visc"] * p["m"] * wn
    p["zeta_pre"] = float(rng.uniform(0.15, 0.4) if case != "triggering" else rng.uniform(0.3, 0.5))
    p["c_pre"] = 2 * p["zeta_pre"] * math.sqrt(p["kp_over_k"] * p["k"] * p["m"])
    dx = 2 * (p["mu_s"] - p["mu_k"]) * p["N0"] / p["k"]                        # nominal slip (m)
    p["dx_nom"] = dx
    v_slip = wn * dx / 2
    r = float(rng.uniform(5.0, 10.0))                                           # T_ss / Tn wanted
    p["v0"] = dx / ((r - 0.6) / p["fn"])
    p["vs"] = float(rng.uniform(2.0, 5.0)) * p["v0"]
    if case == "static_ageing":
        # a Stribeck scale well above the fastest drive: the law's own loading-rate effect on the peak stays small
        p["vs"] = float(rng.uniform(4.5, 6.0)) * p["v0"]
    if case == "triggering":
        # the friction at the drive speed well below the static level: the shaker triggers slips, not quench them
        p["vs"] = float(rng.uniform(0.9, 1.3)) * p["v0"]
        p["q"] = float(rng.uniform(2.6, 3.5))
    p["Tss_est"] = r / p["fn"]
    p["n_cycles_target"] = int(rng.integers(20, 42))
    p["backlash"] = float(rng.uniform(0.05, 0.4)) * 1e-3 * p["R"] / 0.1 * 0.1   # m of track (small)
    # departures (switched off by default)
    p.update(kappa=0.0, L_d=1.0, v_d=1.0, tau_c=1.0, b_a=0.0, L_a=1.0, tau_a=1.0, cam_c=0.0, cam_lambda=1.0,
             cam_x0=0.0, trig_a=0.0, trig_f=0.0, mod_a=0.0, mod_f=0.0, mod_p=0.0)
    p["drive"] = "constant"
    # measurement chain
    p["lp_over_fn"] = float(rng.uniform(8.0, 30.0))
    p["jitter_rel"] = float(rng.uniform(0.005, 0.03))
    p["drop_rate"] = float(rng.uniform(0.0005, 0.003))
    p["white_rel"] = float(rng.uniform(0.002, 0.006))
    p["pink_rel"] = float(rng.uniform(0.001, 0.004))
    p["enc_um"] = float(rng.uniform(0.5, 3.0))
    p["spp"] = float(rng.uniform(20.0, 100.0))
    return p, rng


# ----------------------------------------------------------------------------------------------------------
# drive and load inputs
# ----------------------------------------------------------------------------------------------------------
def _drive_profile(p, T):
    """Piecewise-linear motor speed (breakpoints) for stepped / held drives; None otherwise."""
    if p["drive"] != "stepped":
        return None
    ts, vs = [0.0], [p["v0_levels"][0]]
    t = 0.0
    ramp = 0.3 / p["fn"]
    for lev, dur in zip(p["v0_levels"], p["level_durations"]):
        if t > 0:
            ts.append(t + ramp)
            vs.append(lev)
        t += dur
        ts.append(t)
        vs.append(lev)
    return np.array(ts), np.array(vs)


def _make_vd(p):
    v0 = p["v0"]
    bl = _drive_profile(p, None)
    if bl is not None:
        tb, vb = bl
        tbl = tb.tolist()
        vbl = vb.tolist()

        def vd(t, tbl=tbl, vbl=vbl):
            if t <= tbl[0]:
                return vbl[0]
            if t >= tbl[-1]:
                return vbl[-1]
            lo, hi = 0, len(tbl) - 1
            while hi - lo > 1:
                mid = (lo + hi) // 2
                if tbl[mid] <= t:
                    lo = mid
                else:
                    hi = mid
            a = (t - tbl[lo]) / (tbl[hi] - tbl[lo]) if tbl[hi] > tbl[lo] else 1.0
            return vbl[lo] + a * (vbl[hi] - vbl[lo])
        return vd
    if p["mod_a"] > 0:
        a, w, ph = p["mod_a"], 2 * math.pi * p["mod_f"], p["mod_p"]
        return lambda t: v0 * (1.0 + a * math.sin(w * t + ph))
    return lambda t: v0


# ----------------------------------------------------------------------------------------------------------
# integrator: ROS2 (Verwer et al. 1999), fixed step
# ----------------------------------------------------------------------------------------------------------
def _simulate(p, T, x0=None, steps_per_tn=260):
    fn = p["fn"]
    h = 1.0 / (fn * steps_per_tn)
    if p["trig_f"] > 0:
        h = min(h, 1.0 / (30.0 * p["trig_f"]))
    nstep = int(math.ceil(T / h))
    m, k, c_arm, c_v, c_p = p["m"], p["k"], p["c_arm"], p["c_visc"], p["c_pre"]
    N0, mu_k, mu_s, vs, q = p["N0"], p["mu_k"], p["mu_s"], p["vs"], p["q"]
    nbw, bet, gam, dlt = p["n_bw"], p["beta_bw"], p["gamma_bw"], p["delta"]
    kap, Ld, tauc, vdeb = p["kappa"], p["L_d"], p["tau_c"], p["v_d"]
    ba, La, taua = p["b_a"], p["L_a"], p["tau_a"]
    cc, clam, cx0 = p["cam_c"], p["cam_lambda"], p["cam_x0"]
    ta, tw = p["trig_a"], 2 * math.pi * p["trig_f"]
    vd_f = _make_vd(p)
    inv_m = 1.0 / m
    inv_d = 1.0 / dlt
    ckw = 2 * math.pi / clam
    exp, sin, cos, log = math.exp, math.sin, math.cos, math.log

    def load(x, t):
        N = N0
        dN = 0.0
        if cc != 0.0:
            ph = ckw * (x - cx0)
            N = N0 * (1.0 + cc * sin(ph))
            dN = N0 * cc * ckw * cos(ph)
        if ta != 0.0:
            N = N * (1.0 + ta * sin(tw * t))
            dN = dN * (1.0 + ta * sin(tw * t))
        return N, dN

    def mu_fun(sa, th):
        mus = mu_s
        if ba != 0.0:
            mus = mu_s + ba * log(1.0 + (th if th > 0 else 0.0) / taua)
        if sa <= 0.0:
            return mus, 0.0
        r = sa / vs
        rq = r ** q
        e = exp(-rq)
        mu = mu_k + (mus - mu_k) * e
        dmu = -(mus - mu_k) * e * q * rq / sa
        return mu, dmu

    def rhs(t, x, v, z, D, th, want_jac):
        vd = vd_f(t)
        s = vd - v
        sa = s if s >= 0 else -s
        ss = 1.0 if s >= 0 else -1.0
        N, dN = load(x, t)
        mu, dmu = mu_fun(sa, th)
        g = 1.0 + kap * D
        za = z if z >= 0 else -z
        sz = 1.0 if s * z >= 0 else -1.0
        bg = bet + gam * sz
        zan = za ** nbw
        fz = 1.0 - zan * bg
        dz = s * fz * inv_d
        Ff = N * mu * z * g + c_v * s + c_p * s * fz
        ax = (Ff - k * x - c_arm * v) * inv_m
        gd = sa / (sa + vdeb)            # debris is produced by fast sliding (wear ~ frictional power)
        dD = sa * gd * (1.0 - D) / Ld - D / tauc if kap != 0.0 else 0.0
        dth = 1.0 - th * sa / La if ba != 0.0 else 0.0
        if not want_jac:
            return v, ax, dz, dD, dth, Ff, N, s
        jxx = (-k + dN * mu * z * g) * inv_m
        jzv = -fz * inv_d
        jzz = -s * nbw * (za ** (nbw - 1.0)) * (1.0 if z >= 0 else -1.0) * bg * inv_d
        jvv = (-c_arm - N * g * z * dmu * ss - c_v - c_p * fz) * inv_m
        jvz = (N * mu * g + c_p * dlt * jzz) * inv_m
        jD = -(sa * gd / Ld + 1.0 / tauc) if kap != 0.0 else 0.0
        jth = -sa / La if ba != 0.0 else 0.0
        return v, ax, dz, dD, dth, Ff, N, s, jxx, jvv, jvz, jzv, jzz, jD, jth

    # output arrays (every step)
    X = np.empty(nstep + 1)
    V = np.empty(nstep + 1)
    Z = np.empty(nstep + 1)
    FF = np.empty(nstep + 1)
    NN = np.empty(nstep + 1)
    SS = np.empty(nstep + 1)
    DD = np.empty(nstep + 1)
    TH = np.empty(nstep + 1)
    XD = np.empty(nstep + 1)
    x = 0.0 if x0 is None else x0
    v = 0.0
    z = 0.0
    D = 0.0
    th = 0.0
    xd = 0.0
    t = 0.0
    nsub_total = 0
    r = rhs(t, x, v, z, D, th, True)
    for i in range(nstep + 1):
        X[i] = x; V[i] = v; Z[i] = z; FF[i] = r[5]; NN[i] = r[6]; SS[i] = r[7]; DD[i] = D; TH[i] = th; XD[i] = xd
        if i == nstep:
            break
        t_end = (i + 1) * h
        while True:
            f1, f2, f3, f4, f5, Ff, N, s, jxx, jvv, jvz, jzv, jzz, jD, jth = r
            # sub-step where the slip is fast: the weakening's unstable rate and the Bouc-Wen rate resolved
            rate = max(abs(jvv), 0.15 * abs(jzz), 1e-30)
            hs = t_end - t
            if hs * rate > 0.5:
                hs = 0.5 / rate
                nsub_total += 1
            gh = _GAM * hs
            # M = I - gh J ;  J = [[0,1,0],[jxx,jvv,jvz],[0,jzv,jzz]]
            a11, a12, a13 = 1.0, -gh, 0.0
            a21, a22, a23 = -gh * jxx, 1.0 - gh * jvv, -gh * jvz
            a31, a32, a33 = 0.0, -gh * jzv, 1.0 - gh * jzz
            c11 = a22 * a33 - a23 * a32
            c12 = a13 * a32 - a12 * a33
            c13 = a12 * a23 - a13 * a22
            c21 = a23 * a31 - a21 * a33
            c22 = a11 * a33 - a13 * a31
            c23 = a13 * a21 - a11 * a23
            c31 = a21 * a32 - a22 * a31
            c32 = a12 * a31 - a11 * a32
            c33 = a11 * a22 - a12 * a21
            idet = 1.0 / (a11 * c11 + a12 * c21 + a13 * c31)
            k1 = (c11 * f1 + c12 * f2 + c13 * f3) * idet
            k2 = (c21 * f1 + c22 * f2 + c23 * f3) * idet
            k3 = (c31 * f1 + c32 * f2 + c33 * f3) * idet
            dD1 = 1.0 / (1.0 - gh * jD)
            dT1 = 1.0 / (1.0 - gh * jth)
            k4 = f4 * dD1
            k5 = f5 * dT1
            g1, g2, g3, g4, g5 = rhs(t + hs, x + hs * k1, v + hs * k2, z + hs * k3, D + hs * k4, th + hs * k5, False)[:5]
            g1 -= 2 * k1; g2 -= 2 * k2; g3 -= 2 * k3; g4 -= 2 * k4; g5 -= 2 * k5
            l1 = (c11 * g1 + c12 * g2 + c13 * g3) * idet
            l2 = (c21 * g1 + c22 * g2 + c23 * g3) * idet
            l3 = (c31 * g1 + c32 * g2 + c33 * g3) * idet
            l4 = g4 * dD1
            l5 = g5 * dT1
            x += hs * (1.5 * k1 + 0.5 * l1)
            v += hs * (1.5 * k2 + 0.5 * l2)
            z += hs * (1.5 * k3 + 0.5 * l3)
            # |z| <= 1 is invariant for the exact flow (A = beta + gamma = 1): project the step back onto it
            if z > 1.0:
                z = 1.0
            elif z < -1.0:
                z = -1.0
            D += hs * (1.5 * k4 + 0.5 * l4)
            th += hs * (1.5 * k5 + 0.5 * l5)
            if th < 0:
                th = 0.0
            # disc position (trapezoid of the speed)
            xd += 0.5 * hs * (vd_f(t) + vd_f(t + hs))
            t += hs
            r = rhs(t, x, v, z, D, th, True)
            if t >= t_end - 1e-9 * h:
                t = t_end
                break
    tt = np.arange(nstep + 1) * h
    return {"t": tt, "x": X, "v": V, "z": Z, "Ff": FF, "N": NN, "s": SS, "D": DD, "th": TH, "xd": XD, "h": h,
            "substeps": nsub_total}


# ----------------------------------------------------------------------------------------------------------
# ground-truth measurement on the noise-free contact signals
# ----------------------------------------------------------------------------------------------------------
def _slips(sim, t_from=0.0):
    """Slips of the noise-free run: events where the sliding speed exceeds 35 % of its typical peak, each
    widened from the spring force's peak before it to its minimum after it."""
    s = sim["s"]
    t = sim["t"]
    F = sim["x"]
    sel = t >= t_from
    if not np.any(sel):
        return [], 0.0
    smax = np.percentile(s[sel], 99.5)
    thr = 0.35 * smax
    on = s > thr
    d = np.diff(on.astype(np.int8))
    starts = np.nonzero(d == 1)[0] + 1
    ends = np.nonzero(d == -1)[0] + 1
    ev = []
    for a in starts:
        e = ends[ends > a]
        if len(e) == 0:
            break
        ev.append((a, e[0]))
    out = []
    for j, (a, b) in enumerate(ev):
        lo = ev[j - 1][1] if j > 0 else max(0, a - (b - a) * 20)
        hi = ev[j + 1][0] if j + 1 < len(ev) else None
        if hi is None:
            continue
        i_pk = a + int(np.argmax(s[a:b]))
        sa = lo + int(np.argmax(F[lo:i_pk + 1]))
        # arrest: the spring force's minimum before the next event, looked for within 3 slip durations
        hi2 = min(hi, b + 3 * (b - sa) + 2)
        sb = i_pk + int(np.argmin(F[i_pk:hi2]))
        if j == 0 or t[sa] < t_from:
            continue
        out.append((sa, sb, i_pk))
    return out, thr


def _measure(sim, p, t_from=0.0):
    t, s, Ff, x, N = sim["t"], sim["s"], sim["Ff"], sim["x"], sim["N"]
    k = p["k"]
    F = k * x
    slips, thr = _slips(sim, t_from)
    res = {}
    if len(slips) < 3:
        return {"cycles": len(slips), "ok": False}
    twins, twins_mu, drops, peaks, tst, smaxs = [], [], [], [], [], []
    prev_end = None
    for (a0, b0, i_pk) in slips:
        a = a0
        b = b0
        sm = s[i_pk]
        smaxs.append(sm)
        acc_s, acc_f, acc_m = s[a0:i_pk + 1], Ff[a0:i_pk + 1], Ff[a0:i_pk + 1] / N[a0:i_pk + 1]
        dec_s, dec_f, dec_m = s[i_pk:b0 + 1][::-1], Ff[i_pk:b0 + 1][::-1], (Ff / N)[i_pk:b0 + 1][::-1]
        drop = F[a0:i_pk + 1].max() - F[i_pk:b0 + 1].min()
        grid = np.linspace(0.15, 0.85, 29) * sm
        # keep the monotone envelopes
        ia = np.maximum.accumulate(acc_s)
        idd = np.maximum.accumulate(dec_s)
        fa = np.interp(grid, ia, acc_f)
        fd = np.interp(grid, idd, dec_f)
        ma = np.interp(grid, ia, acc_m)
        md = np.interp(grid, idd, dec_m)
        twins.append(float(np.median(fd - fa) / drop))
        twins_mu.append(float(np.median(md - ma) / (drop / np.mean(N[a0:b0 + 1]))))
        drops.append(drop)
        # stick before this slip
        if prev_end is not None:
            peaks.append(F[prev_end:i_pk + 1].max())
            tst.append(t[a] - t[prev_end])
        prev_end = b
    drops = np.array(drops)
    md = float(np.median(drops))
    if not md > 0 or not np.all(np.isfinite(twins)):
        return {"cycles": len(slips), "ok": False}
    res["cycles"] = len(slips)
    res["twin_median"] = float(np.median(twins))
    res["twin_mu_median"] = float(np.median(twins_mu))
    res["drop_median_N"] = md
    res["drop_cv"] = float(np.std(drops) / md)
    dur = t[slips[-1][0]] - t[slips[0][0]]
    res["f_ss"] = float((len(slips) - 1) / dur)
    res["fss_over_fn"] = res["f_ss"] / p["fn"]
    peaks = np.array(peaks)
    tst = np.array(tst)
    res["stick_time_ratio"] = float(tst.max() / tst.min())
    if tst.max() / tst.min() > 1.3:
        A = np.vstack([np.ones_like(tst), np.log(tst)]).T
        coef = np.linalg.lstsq(A, peaks, rcond=None)[0]
        res["ageing_growth"] = float(coef[1] * np.log(tst.max() / tst.min()) / md)
    else:
        res["ageing_growth"] = 0.0
    res["peak_sd_rel"] = float(np.std(peaks) / md)
    sel = t >= t_from
    Nm = N[sel]
    res["load_pp"] = float((Nm.max() - Nm.min()) / Nm.mean())
    # stick creep (presliding) as a fraction of the drive speed, in the middle half of the sticks
    creep = []
    ends = [b for (_, b, _) in slips]
    starts = [a for (a, _, _) in slips]
    for e, a in zip(ends[:-1], starts[1:]):
        L = a - e
        mid = slice(e + L // 4, e + 3 * L // 4)
        vdm = np.mean(np.abs(np.diff(sim["xd"][mid]))) / sim["h"] if L > 8 else np.nan
        if vdm > 0:
            creep.append(np.mean(s[mid]) / vdm)
    res["stick_creep_rel"] = float(np.nanmedian(creep)) if creep else float("nan")
    res["presliding_delta_over_slip"] = float(p["delta"] / (md / p["k"]))
    res["ok"] = True
    return res


# ----------------------------------------------------------------------------------------------------------
# case set-up (pilot runs for calibration)
# ----------------------------------------------------------------------------------------------------------
def _frac_dist(r):
    return abs(r - round(r))


def _setup_case(case, p, rng):
    """Returns the simulated run, its measurement and the recorded time window start."""
    fn = p["fn"]
    pilot_T = 8.0 * p["Tss_est"]
    if case == "static_ageing":
        ratio = float(rng.uniform(4.2, 7.8))
        p["step_ratio"] = ratio
    for _ in range(6):
        # the pilot (no departure) must stick-slip regularly: else the Stribeck scale is raised
        pil = _simulate(p, pilot_T, steps_per_tn=200)
        sl, _ = _slips(pil)
        mp = {"ok": False}
        if len(sl) >= 3:
            t_first = pil["t"][sl[0][1]]
            Tss = float(np.median(np.diff(pil["t"][[a for a, _, _ in sl]])))
            if len(sl) >= 4:
                mp = _measure(pil, p, t_from=t_first)
        if mp.get("ok") and Tss * fn > 2.5 and mp["drop_cv"] < 0.1:
            break
        if len(sl) < 4 and (len(sl) < 3 or Tss * fn > 2.5):
            pilot_T *= 1.6                       # sticks longer than guessed: a longer pilot
            continue
        p["vs"] *= 1.3
        p["vs_raised"] = p.get("vs_raised", 0) + 1
    else:
        t_first, Tss = p["Tss_est"], p["Tss_est"]
    p["Tss_pilot"] = Tss
    ncyc = p["n_cycles_target"]
    t0 = t_first + float(rng.uniform(0.2, 0.8)) * Tss        # record starts here (rig run in)
    T = t0 + ncyc * Tss
    if case == "load_variation":
        xs = pil["x"][pil["t"] > t_first]
        xmin, xmax = float(xs.min()), float(xs.max())
        amp = xmax - xmin
        p["cam_lambda"] = float(rng.uniform(2.5, 5.0)) * amp
        # the arm's travel sits on the cam's rising flank
        rising = True   # a falling cam (N dropping as the arm loads) broke the stick-slip up: not used
        phc = (0.0 if rising else math.pi) + float(rng.uniform(-0.3, 0.3))
        p["cam_rising"] = rising
        xm = 0.5 * (xmin + xmax)
        p["cam_x0"] = xm - phc * p["cam_lambda"] / (2 * math.pi)
        target = float(rng.uniform(0.14, 0.31))
        xx = np.linspace(xmin, xmax, 400)
        sh = np.sin(2 * math.pi * (xx - p["cam_x0"]) / p["cam_lambda"])
        p["cam_c"] = target / max(0.2, sh.max() - sh.min())
        p["load_pp_target"] = target
    elif case == "twin_branch":
        p["L_d"] = float(rng.uniform(0.3, 0.7)) * p["dx_nom"]
        p["v_d"] = float(rng.uniform(0.15, 0.3)) * math.pi * fn * p["dx_nom"]
        p["tau_c"] = float(rng.uniform(0.15, 0.35)) * (Tss - 0.5 / fn)
        target = float(rng.uniform(0.13, 0.21))
        p["twin_target"] = target
        kap = 0.3
        for it in range(2):
            p["kappa"] = kap
            pk = _simulate(p, pilot_T, steps_per_tn=200)
            slk, _ = _slips(pk)
            mk = _measure(pk, p, t_from=pk["t"][slk[0][1]]) if len(slk) >= 4 else {"ok": False}
            tw0 = mp.get("twin_median", 0.0) if mp.get("ok") else 0.0
            if not mk.get("ok") or mk["twin_median"] - tw0 <= 0.01:
                kap *= 2
                continue
            kap = kap * target / (mk["twin_median"] - tw0)
            kap = min(kap, 3.0)
        p["kappa"] = kap
    elif case == "static_ageing":
        ratio = p["step_ratio"]
        v_hi = p["v0"] * 1.3
        v_lo = v_hi / ratio
        p["L_a"] = float(rng.uniform(1.0, 3.0)) * p["delta"]
        p["tau_a"] = float(rng.uniform(0.05, 0.2)) / fn
        Tst_hi = (Tss - 0.5 / fn) / 1.3
        Tst_lo = Tst_hi * ratio
        target = float(rng.uniform(0.11, 0.17))
        p["ageing_target"] = target
        drop = mp["drop_median_N"] if mp.get("ok") else 2 * (p["mu_s"] - p["mu_k"]) * p["N0"]
        lg = math.log((1 + Tst_lo / p["tau_a"]) / (1 + Tst_hi / p["tau_a"]))
        p["b_a"] = target * drop / (p["N0"] * lg)
        # levels: hi, lo, hi, lo (even seeds) / hi, lo, hi with holds (odd seeds)
        n_hi = int(rng.integers(9, 12))
        n_lo = int(rng.integers(5, 8))
        T_hi = n_hi * Tst_hi * 1.0 + n_hi * 0.5 / fn
        T_lo = n_lo * (Tst_lo + 0.5 / fn)
        if p["seed"] % 2 == 0:
            levels = [v_hi, v_lo, v_hi, v_lo]
            durs = [t0 + T_hi, T_lo, T_hi, T_lo]
        else:
            th_ = float(rng.uniform(2.0, 6.0)) * Tst_hi
            levels = [v_hi, v_lo, v_hi, 0.0, v_hi, 0.0, v_hi]
            durs = [t0 + T_hi, T_lo, 0.7 * T_hi, th_, 0.7 * T_hi, 1.6 * th_, 0.7 * T_hi]
        p["drive"] = "stepped"
        p["v0_levels"] = levels
        p["level_durations"] = durs
        T = float(sum(durs))
    elif case == "triggering":
        p["trig_a"] = float(rng.uniform(0.03, 0.045))
        fss = 1.0 / Tss
        for _ in range(200):
            ft = float(rng.uniform(2.5, min(8.0, 0.45 * math.sqrt(p["kp_over_k"])))) * fn
            if 0.25 <= ft / fss - math.floor(ft / fss) <= 0.75:
                break
        p["trig_f"] = ft
    elif case == "drive_modulation":
        p["mod_a"] = float(rng.uniform(0.2, 0.45))
        p["mod_p"] = float(rng.uniform(0, 2 * math.pi))
        p["mod_ratio_target"] = float(rng.uniform(0.13, 0.42))
        p["mod_f"] = p["mod_ratio_target"] / Tss
    p["t_record0"] = t0
    p["_rng"] = rng
    ncyc_target = ncyc
    p["attempts"] = []
    best = None
    short = False
    for attempt in range(8 if case == "triggering" else 5):
        T_run = min(T, t0 + 12 * Tss) if short else T
        p["T_sim"] = T_run
        sim = _simulate(p, T_run)
        meas = _measure(sim, p, t_from=t0)
        note = _accept(case, p, meas, fn)
        note["short_run"] = short
        p["attempts"].append(note)
        if short:
            # on a short run only the frequency ratio and the stick-slip's survival count
            note["problems"] = [q for q in note["problems"] if not q.startswith("cycles")]
            if not note["problems"] or attempt >= 8:
                short = False
                continue
        cyc = meas.get("cycles", 0)
        if meas.get("ok"):
            score = len(note["problems"])
            if best is None or score < best[0]:
                best = (score, sim, meas)
        if not note["problems"]:
            break
        # adjustments for the next attempt
        if case != "static_ageing" and meas.get("ok") and not (16 <= cyc <= 58):
            T = t0 + (T - t0) * ncyc_target / max(cyc, 1)
        if "kappa" in note:
            p["kappa"] = note["kappa"]
        if "cam_c" in note:
            p["cam_c"] = note["cam_c"]
        if "trig_f" in note:
            p["trig_f"] = note["trig_f"]
        if "trig_a" in note:
            p["trig_a"] = note["trig_a"]
        if "mod_f" in note:
            p["mod_f"] = note["mod_f"]
        if "b_a" in note:
            p["b_a"] = note["b_a"]
    if best is not None:
        _, sim, meas = best
    p.pop("_rng", None)
    return sim, meas


def _accept(case, p, meas, fn):
    """Checks a run against the case's ranges; proposes corrections."""
    note = {"problems": []}
    if not meas.get("ok"):
        note["problems"].append("no stick-slip")
        if case == "triggering":
            note["trig_a"] = max(0.03, 0.8 * p["trig_a"])
            note["trig_f"] = float(p["_rng"].uniform(2.5, min(8.0, 0.45 * math.sqrt(p["kp_over_k"])))) * fn
        return note
    cyc = meas["cycles"]
    if not 15 <= cyc <= 60:
        note["problems"].append(f"cycles {cyc}")
    if meas["drop_cv"] > (0.15 if case != "static_ageing" else 0.3):
        note["problems"].append(f"irregular slips (drop cv {meas['drop_cv']:.2f})")
    if case == "none" or case in ("triggering", "drive_modulation"):
        pass
    if case == "load_variation":
        pp = meas["load_pp"]
        target = p["load_pp_target"]
        if not 0.12 <= pp <= 0.35:
            note["problems"].append(f"load p-p {pp:.3f}")
            note["cam_c"] = p["cam_c"] * target / max(pp, 1e-3)
        if meas["drop_cv"] > 0.15 or meas["fss_over_fn"] > 1.5 / max(1.0, 1.0) * (1.0 / (p["Tss_pilot"] * fn)):
            note["problems"].append("stick-slip changed by the cam")
            note["cam_c"] = p["cam_c"] * 0.85
    if case == "twin_branch":
        tw = meas["twin_median"]
        if not 0.11 <= tw <= 0.24:
            note["problems"].append(f"twin {tw:.3f}")
            if 0 < tw < 0.6:
                note["kappa"] = p["kappa"] * (p["twin_target"] / tw) ** 0.8
            else:
                note["kappa"] = p["kappa"] * 0.6
    if case == "static_ageing":
        g = meas["ageing_growth"]
        if not 0.085 <= g <= 0.19:
            note["problems"].append(f"ageing growth {g:.3f}")
            if g > 0.01:
                note["b_a"] = p["b_a"] * p["ageing_target"] / g
            else:
                note["b_a"] = p["b_a"] * 2
    if case == "triggering":
        r = p["trig_f"] / meas["f_ss"]
        meas["ft_over_fss"] = r
        meas["ft_over_fn"] = p["trig_f"] / fn
        lost = meas["fss_over_fn"] > 0.6 or meas["cycles"] > 60 or meas["drop_cv"] > 0.15
        if _frac_dist(r) < 0.15 or lost:
            note["problems"].append(f"f_t/f_ss {r:.2f} near an integer" if not lost else "stick-slip lost under the shaker")
            fss = meas["f_ss"] if not lost else 1.0 / p["Tss_pilot"]
            hi = min(8.0, 0.45 * math.sqrt(p["kp_over_k"])) * fn
            rr = p["_rng"]
            for _ in range(200):
                ft = float(rr.uniform(2.5 * fn, hi))
                if 0.25 <= ft / fss - math.floor(ft / fss) <= 0.75:
                    break
            note["trig_f"] = ft
            # a weaker shaker locks the breakaways less readily (narrower tongues), and quenches less
            note["trig_a"] = max(0.03, (0.8 if lost else 0.9) * p["trig_a"])
    if case == "drive_modulation":
        r = p["mod_f"] / meas["f_ss"]
        meas["fm_over_fss"] = r
        if not 0.1 <= r <= 0.5:
            note["problems"].append(f"fm/f_ss {r:.2f}")
            note["mod_f"] = p["mod_ratio_target"] * meas["f_ss"]
    return note


# ----------------------------------------------------------------------------------------------------------
# measurement chain and writing
# ----------------------------------------------------------------------------------------------------------
def _lowpass(u, h, fc):
    """First-order low-pass (the bridge amplifier), exact for an input linear between the fine-grid points."""
    from scipy.signal import lfilter, lfilter_zi
    a = math.exp(-2 * math.pi * fc * h)
    b = 1.0 - (1.0 - a) / (2 * math.pi * fc * h)
    num, den = [1.0 - b, b - a], [1.0, -a]
    y, _ = lfilter(num, den, u, zi=lfilter_zi(num, den) * u[0])
    return y


def _pink(rng, n, rms):
    if n < 4 or rms <= 0:
        return np.zeros(n)
    f = np.fft.rfftfreq(n)
    spec = (rng.standard_normal(len(f)) + 1j * rng.standard_normal(len(f)))
    spec[1:] /= np.sqrt(f[1:])
    spec[0] = 0
    y = np.fft.irfft(spec, n)
    return y * rms / (np.std(y) + 1e-300)


def _fmt(v, dec=6, comma=False):
    s = f"{v:.{dec}f}"
    return s.replace(".", ",") if comma else s


def _sig_dec(step):
    return max(0, int(math.ceil(-math.log10(step))) + 1) if step > 0 else 6


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    t_start = _time.time()
    p, rng = _draw(case, seed)
    p["seed"] = int(seed)
    sim, meas = _setup_case(case, p, rng)
    fn = p["fn"]
    k = p["k"]
    nrng = np.random.default_rng([991, CASES.index(case), seed, NUISANCES.index(nuisance)])

    # --- signals at the rig (fine grid) ---
    h = sim["h"]
    t_f = sim["t"]
    F_arm = k * sim["x"]                               # the spring's (torque arm's) force at the pad radius
    N_true = sim["N"]
    fc = p["lp_over_fn"] * fn
    F_s = _lowpass(F_arm, h, fc)
    N_s = _lowpass(N_true, h, fc * 0.7)
    x_motor = sim["xd"] + p["backlash"]                # the encoder on the motor: the disc + the taken-up play
    # --- sampling ---
    spp = p["spp"] if nuisance != "coarse" else float(nrng.uniform(10.0, 15.0))
    fs = spp * fn
    t0 = p["t_record0"]
    n = int((t_f[-1] - t0) * fs) - 2
    i_nom = np.arange(n)
    t_true = t0 + i_nom / fs + nrng.standard_normal(n) * p["jitter_rel"] / fs
    t_true = np.clip(t_true, t_f[0], t_f[-1])
    Fm = np.interp(t_true, t_f, F_s)
    Nm = np.interp(t_true, t_f, N_s)
    Xm = np.interp(t_true, t_f, x_motor)
    drop = meas.get("drop_median_N", 2 * (p["mu_s"] - p["mu_k"]) * p["N0"])
    Fm = Fm + nrng.standard_normal(n) * p["white_rel"] * drop + _pink(nrng, n, p["pink_rel"] * drop)
    Nm = Nm + nrng.standard_normal(n) * 0.002 * p["N0"] + _pink(nrng, n, 0.001 * p["N0"])
    tn = i_nom / fs
    nz = {}
    if nuisance == "hum":
        fh = float(nrng.choice([50.0, 60.0]))
        ah = float(nrng.uniform(0.01, 0.05)) * drop
        ph1, ph2 = nrng.uniform(0, 2 * math.pi, 2)
        Fm = Fm + ah * np.sin(2 * math.pi * fh * t_true + ph1) + 0.3 * ah * np.sin(2 * math.pi * 3 * fh * t_true + ph2)
        nz = {"hum_hz": fh, "hum_rel_drop": ah / drop}
    elif nuisance == "drift":
        ad = float(nrng.uniform(0.02, 0.05)) * drop * float(nrng.choice([-1.0, 1.0]))
        u = tn / tn[-1]
        shape = 0.7 * u + 0.3 * np.sin(math.pi * u)
        Fm = Fm + ad * shape / np.abs(shape).max()          # a slow sensor drift, ad at its largest
        nz = {"drift_rel_drop": ad / drop}
    elif nuisance == "spikes":
        frac = float(nrng.uniform(0.0005, 0.005))
        nsp = max(2, int(frac * n))
        idx = nrng.choice(np.arange(5, n - 5), nsp, replace=False)
        amp = nrng.uniform(0.15, 0.40, nsp) * drop * nrng.choice([-1.0, 1.0], nsp)
        Fm[idx] += amp
        nz = {"spike_fraction": nsp / n, "spike_rel_drop_range": [float(np.abs(amp).min() / drop), float(np.abs(amp).max() / drop)]}
    # ADC: 24 bit over a range 1.3x the channel's span (quantisation nuisance: coarse step)
    fsr = 1.3 * (np.abs(Fm).max() + 1e-12) * 2
    qF = fsr / 2 ** 24
    if nuisance == "quantisation":
        qF = float(nrng.uniform(0.002, 0.01)) * drop
        nz = {"quant_rel_drop": qF / drop}
    Fm = np.round(Fm / qF) * qF
    qN = 1.3 * 2 * Nm.max() / 2 ** 24
    Nm = np.round(Nm / qN) * qN
    qx = p["enc_um"] * 1e-6
    Xm = np.floor(Xm / qx) * qx
    # dropped samples (single rows)
    keep = np.ones(n, bool)
    nd = int(p["drop_rate"] * n)
    if nd:
        keep[nrng.choice(np.arange(3, n - 3), nd, replace=False)] = False
    # --- record layout ---
    fmt_id = (seed + CASES.index(case)) % 4
    want_N = case == "load_variation" or (case == "triggering" and seed % 4 != 3) or (case not in ("load_variation", "triggering") and seed % 3 == 0)
    # drive column: position (encoder), v0 column, or --v0
    if case == "drive_modulation":
        drive = "none"
    elif case == "static_ageing":
        drive = "position" if seed % 2 == 0 else "v0col"
    else:
        drive = ("position", "none", "v0col", "none")[(seed + 2 * CASES.index(case)) % 4]
    displacement = fmt_id == 2
    force_unit = "mN" if (seed % 2 == 1 and not displacement) else "N"
    fscale = 1e3 if force_unit == "mN" else 1.0
    time_ms = fmt_id == 3 and seed % 2 == 0
    pos_unit = "um" if (seed // 2) % 2 == 1 else "mm"
    posscale = 1e6 if pos_unit == "um" else 1e3
    # the controller's speed readout (mm/s): encoder counts over a window of ~40 counts at the nominal speed
    # (at least 8 samples, at most a quarter of the stick-slip period), centred
    def speed_readout():
        v_nom = max(p["v0"], max(p.get("v0_levels", [p["v0"]])))
        win = min(max(8.0 / fs, 40.0 * qx / v_nom), 0.25 * p["Tss_pilot"])
        lag = max(2, int(round(win * fs)))
        ve = np.empty(n)
        ve[lag:] = (Xm[lag:] - Xm[:-lag]) / (lag / fs)
        ve[:lag] = ve[lag]
        ve = np.roll(ve, -(lag // 2))
        ve[-(lag // 2) - 1:] = ve[-(lag // 2) - 2]
        p["speed_readout_window_s"] = lag / fs
        return ve * 1e3

    v_enc = speed_readout() if drive == "v0col" else None
    cols, names = [], []
    tcol = tn * (1e3 if time_ms else 1.0)
    if displacement:
        names = ["t [s]", "x [mm]"]
        cols = [tn, Fm / k * 1e3]
        if want_N:
            # proximity probe on the clamp spring (k_n), offset: y = y0 + N/k_n
            kn = float(p["N0"] / float(nrng.uniform(0.4, 1.2)) * 1e3)   # N/m
            y0 = float(nrng.uniform(0.5, 2.0))
            names.append("y [mm]")
            cols.append(y0 + Nm / kn * 1e3)
            p["y_map"] = {"y0_mm": y0, "k_n_N_per_m": kn}
        if drive == "v0col":
            names.append("v0 [mm/s]")
            cols.append(v_enc)
        elif drive == "position":
            drive = "v0col"
            names.append("v0 [mm/s]")
            cols.append(speed_readout())
    else:
        tname = {0: "t [s]", 1: "time/s", 3: "Time (ms)" if time_ms else "Time (s)"}[fmt_id]
        names = [tname, f"torque_arm_force [{force_unit}]" if fmt_id != 1 else f"F_arm/{force_unit}"]
        if fmt_id == 3:
            names[1] = f"friction ({force_unit})"
        cols = [tcol, Fm * fscale]
        if want_N:
            names.append({0: f"clamp_force [{force_unit}]", 1: f"Fnorm/{force_unit}", 3: f"normal ({force_unit})"}[fmt_id])
            cols.append(Nm * fscale)
        if drive == "position":
            names.append({0: f"disc_track [{pos_unit}]", 1: f"position/{pos_unit}", 3: f"Position ({pos_unit})"}[fmt_id])
            cols.append(Xm * posscale)
        elif drive == "v0col":
            names.append({0: "v0 [mm/s]", 1: "v0/(mm/s)", 3: "v0 (mm/s)"}[fmt_id])
            if fmt_id == 1:
                names[-1] = "speed_mm_s"
            cols.append(v_enc)
    delim = {0: ",", 1: "\t", 2: " ", 3: ";"}[fmt_id]
    dcomma = fmt_id == 3
    if fmt_id == 2:
        names = [nm.replace(" [", "_").replace("]", "").replace("/", "_") for nm in names]
    # decimals
    decs = []
    for nm, c in zip(names, cols):
        if c is tcol or c is tn:
            decs.append(7 if not time_ms else 4)
        else:
            span = float(np.ptp(c)) + 1e-12
            decs.append(max(0, _sig_dec(span * 1e-6)))
    rows = np.nonzero(keep)[0]
    lines = []
    lines.append(f"# {NAME} brake rig export, seed {seed}; record {len(rows)} rows")
    lines.append(delim.join(names))
    arrs = [np.asarray(c)[rows] for c in cols]
    for j in range(len(rows)):
        lines.append(delim.join(_fmt(a[j], d, dcomma) for a, d in zip(arrs, decs)))
    os.makedirs(outdir, exist_ok=True)
    ext = ".csv" if delim in ",;" else ".txt"
    path = os.path.join(os.path.abspath(outdir), f"{NAME}_{case}_s{seed}_{nuisance}{ext}")
    with open(path, "w") as fh_:
        fh_.write("\n".join(lines) + "\n")
    # --- args ---
    args = []
    if not displacement:
        args += ["--stiffness", f"{k:.6g}"]
    omit_fn_seed = {"none": 3, "load_variation": 4, "twin_branch": 1, "static_ageing": 2,
                    "triggering": None, "drive_modulation": 5}[case]
    fn_given = None
    if nuisance == "fn_off":
        fn_given = fn * (1.0 + 0.05 * float(nrng.choice([-1.0, 1.0])))
    elif seed % 8 != omit_fn_seed:
        fn_given = fn
    if fn_given is not None:
        args += ["--fn", f"{fn_given:.5g}"]
    if drive == "none":
        v0n = p["v0"]
        args += ["--v0", f"{v0n * 1e3:.5g}"]
    params = {k_: (v_ if not isinstance(v_, (np.floating, np.integer)) else float(v_)) for k_, v_ in p.items()}
    params.update(record={"format": ["comma", "tab", "whitespace", "semicolon_decimal_comma"][fmt_id],
                          "displacement": displacement, "normal_column": bool(want_N), "drive": drive,
                          "samples_per_period": spp, "rows": int(len(rows)), "force_unit": force_unit},
                  nuisance_params=nz, measured=meas, gen_time_s=round(_time.time() - t_start, 3))
    params = json.loads(json.dumps(params, default=float))
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": path, "args": args,
            "fn_true": fn, "fn_given": fn_given, "params": params}
