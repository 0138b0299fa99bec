"""Rotary (ring / torsional) shear apparatus: stick-slip of a sheared granular layer.

Written blind: from the generator README's interface, case definitions, formats
and nuisances and `lieng diagnose --help` only.

The rig
-------
A motor turns the lower ring at a constant or stepped angular speed through a
gearbox.  The upper ring (inertia J: platen + torque arm) is held by a torque
arm against a load cell on a torsion-spring reaction (torsional stiffness k_t).
Normal load by a dead-weight hanger, a pneumatic piston or a servo.  The layer
between the rings stick-slips.  Mechanics are done at the mean radius R of the
annulus: x = R theta_upper (the arm's twist = the spring's extension),
u = R theta_drive, m = J/R^2, k = k_t/R^2, F = torque/R, viscous damping
zeta = 1-4 %.  fn_true = sqrt(k/m)/(2 pi), the undamped torsional mode.

Friction law (not Stribeck, LuGre, Dieterich-Ruina or Karnopp)
-----------------------------------------------------------------
A two-state granular rheology of the shear band:

    mu = mu_d + dmu_s (1 - phi) + b Theta          (+ h in static_ageing)

* phi in [0, 1], the band's normalised dilatancy (porosity): dense (0) is
  strong.  It relaxes towards phi_ss(v) = v/(v + v_phi) at the rate
  1/tau_phi0 + v/L_phi (dilation over a slip distance, compaction at rest).
* Theta >= 0, the granular temperature made by shearing: Theta_ss = (v/v_T)^2,
  relaxing (collisional dissipation) with the time constant tau_T; its
  collisional (Bagnold) stress adds b Theta.
* v = R (omega_lower - omega_upper) >= 0, the sliding speed at R.
Steady state mu_ss(v) = mu_d + dmu_s v_phi/(v + v_phi) + b (v/v_T)^2: a
static level, weakening, then collisional strengthening.

Stick handling: an explicit two-mode switch.  In stick the upper ring turns
with the lower one (x follows u exactly), the states relax at v = 0, and the
reaction k x + c x' + m u'' is compared with mu(v=0, states) N; slip starts when
it exceeds it.  A slipping sub-step whose end v <= 0 is cut at the zero
crossing (linear in v) and the rest of the step is done in stick.

Integrator (own): outer step dt = T_n/128 (T_n/160 for triggering); a slipping
step is done in 4 sub-steps, each a Strang splitting: a half sub-step of exact
exponential relaxation of the states at the (extrapolated) mean v, an exact
propagator (matrix exponential) of m x'' + c x' + k x = F with F = mu N frozen,
then the second half sub-step of the states at the new v.

Cases
-----
* none: tau_phi0 = 0.0004-0.0008 T_n, L_phi = 0.0005 v_est T_n,
  tau_T = 0.003-0.006 T_n, so mu is nearly single-valued; constant load;
  constant drive, or (drive recorded, half of those seeds) steps between 2-3
  levels a factor 2-6 apart.  Inherent effects, measured on the ground truth
  of seeds 0-7: double-valuedness mean(F_dec - F_acc) at equal v over
  0.2-0.8 v_max = +0.2 to +0.6 % of the slip's drop, over 0.03-0.2 v_max
  = -0.7 to -1.3 %; range of the peak forces over the record's sticks (stick
  times up to 6x apart) <= 0.3 % of the drop (inherent ageing nil: phi
  relaxes completely in every stick); drop scatter <= 0.2 %.
* load_variation (normal channel recorded), one of:
  (a) a closed pneumatic piston on the layer: N = N0 (1 + c delta), delta a
      slower dilation of the layer (delta_ss = v/(v + v_delta), dilation
      0.5-1 T_n, re-compaction 1-3 T_n), c <= 1.2, on a layer with a marked
      static peak (dmu_s >= 0.10);
  (b) the torque arm's inclined reaction strut bears on the loading yoke:
      N = N0 + s (k x - F_ref), 0 < s < 0.92/mu_s.
  c or s calibrated on pilots to a drawn p-p target.
* twin_branch: slow granular-temperature decay, tau_T = 0.12-0.3 T_n, and a
  stronger collisional stress (b calibrated on pilots): the decelerating half
  of each slip has more friction than the accelerating half at equal v.
* static_ageing: consolidation creep of the layer during stick,
  h = beta ln(1 + t_a/tau_a), t_a the time at rest, erased over a slip
  distance L_h = 0.005 drop/k (t_a *= exp(-dx/L_h)); the drive steps 4-8x
  between levels and/or holds (slide-hold-slide), always recorded; beta
  calibrated so that the ageing term's range over the record is on target.
* triggering: the dead-weight hanger's bounce, excited by a nearby machine:
  N = N0 (1 + eps A(t) sin(Phi(t))), a narrow-band vibration (frequency
  wander 0.8-2 % rms, amplitude A fluctuating 5-9 % rms, clipped to
  0.85-1.2; a pure sine phase-locks the stick-slip to f_tr/n), mean f_tr
  2.5-8 fn, retuned (<= 6 runs) until it is >= 0.25 f_ss from any multiple
  of the measured stick-slip frequency; dmu_s >= 0.075.
* drive_modulation: eccentric wear of an intermediate gear shaft: the lower
  ring turns at v0n (1 + a sin(2 pi fm t + psi)); the motor-side encoder,
  when logged (Rotation / Angle / Drive arc), gives the nominal rotation
  only, otherwise only --v0 = v0n is given.

MEASURED on the ground truth (before the sensor chain) of the 48 records of
seeds 0-7 (nuisance NUISANCES[seed % 7]):
  twin_branch       twin 12.0-19.0 % of the drop (0.2-0.8 v_max),
                    9.7-16.7 % (0.03-0.2 v_max)
  load_variation    N peak-to-peak 11.4-25.9 % of N0
  static_ageing     range of the ageing term N h over the record's slips
                    8.4-11.6 % of the mean drop; peak-force range 8.5-11.6 %;
                    side effect: at 0.03-0.2 v_max the accelerating half is
                    7.6-16.5 % of the drop higher (aged contacts are erased
                    at slip onset), 0.2-0.8 v_max: -0.2 to +0.5 %
  triggering        vibration amplitude 3.3-5.9 % of N0 (nominal eps
                    3.6-5.1 %), f_tr 3.0-7.7 fn, 0.28-0.47 f_ss from the
                    nearest multiple of f_ss; peak scatter 4-11 % of the drop
  drive_modulation  a 0.25-0.41, fm 0.13-0.43 f_ss
  all               17-36 slips per record, 25-94 samples per T_n
                    (coarse 10.5-13.9), T_ss/T_n 5.5-13 at the nominal v0
Each record's own values are in params["measured"], these ranges in
params["measured_ranges_seeds0_7"].

Record formats (chosen by seed % 3)
-----------------------------------
0: a GDS-style CSV (GDSLAB-like preamble of quoted "key:","value" rows, stage
   list; columns Stage Number, Time since start of test (s), Time since start
   of stage (s), Torque (N.m), Normal Stress (kPa), Rotation (deg), Angular
   Velocity (deg/min)); a stage per drive level; CRLF; --stiffness 'N·m/rad'.
1: a PC datalogger CSV: first column an ISO date-time stamp (ms), nominally
   fixed but jittered rate, occasional dropped rows; Shear force [N] at the
   mean radius, Normal load [kN], Drive arc [mm] at the mean radius (radius
   in the header); seeds with (seed // 6) odd: semicolon + decimal comma;
   --stiffness in N/mm, --v0 in mm/s when there is no arc column.
2: a TAB file: Time [s], Torque [N·m], Normal force [kN], Angle [deg] of the
   driven ring (no angle column on some seeds: --v0 in rpm or deg/s).
The drive column is absent on logger/TAB seeds with (seed // 3) odd (never
for static_ageing).  Sensor chain: 2nd-order Butterworth low-pass of the
amplifiers (torque 0.22-0.35 fs, normal 0.15-0.3 fs), white noise
(0.2-0.5 % of the drop on the torque, 0.1-0.3 % of N0 on the normal), a
zero offset, fixed-decimal printing.
--fn is given except on seeds = 3 mod 8 (always on fn_off: +-5 %);
--stiffness is given except on seeds = 5 mod 8.
"""

import copy
import hashlib
import math
import os

import numpy as np
from scipy import signal

NAME = "ring_shear"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering",
         "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

# measured on the ground truth of seeds 0-7 (see the module docstring)
MEASURED_RANGES = {
    "none": {"twin_frac_0.2-0.8vmax": [0.002, 0.006], "twin_frac_0.03-0.2vmax": [-0.013, -0.007],
             "peak_range_frac_of_drop": [0.0, 0.003], "drop_cv": [0.0, 0.002]},
    "twin_branch": {"twin_frac_0.2-0.8vmax": [0.120, 0.190], "twin_frac_0.03-0.2vmax": [0.097, 0.167]},
    "load_variation": {"N_pp_frac_of_N0": [0.114, 0.259]},
    "static_ageing": {"ageing_range_frac_of_drop": [0.084, 0.116], "peak_range_frac_of_drop": [0.085, 0.116],
                      "twin_frac_0.03-0.2vmax": [-0.165, -0.076]},
    "triggering": {"amplitude_frac_of_N0": [0.033, 0.059], "f_over_fn": [3.03, 7.71],
                   "dist_to_multiple_of_fss": [0.28, 0.47], "peak_range_frac_of_drop": [0.044, 0.106]},
    "drive_modulation": {"a": [0.249, 0.406], "fm_over_fss": [0.127, 0.429]},
    "all": {"n_slips": [17, 36], "samples_per_Tn": [25.0, 94.2], "samples_per_Tn_coarse": [10.5, 13.9]},
}

_TWO_PI = 2.0 * math.pi


def _rng(*parts):
    h = hashlib.sha256(("|".join(str(p) for p in (NAME,) + parts)).encode()).digest()
    return np.random.default_rng(int.from_bytes(h[:8], "little"))


# ----------------------------------------------------------------------------
# physics
# ----------------------------------------------------------------------------

def _draw_physics(case, seed):
    g = _rng("phys", case, seed)
    fmt = ("gds", "logger", "tab")[seed % 3]
    if fmt == "logger":
        fn = float(g.uniform(2.0, 5.0))
    elif fmt == "gds":
        fn = float(g.uniform(4.0, 25.0))
    else:
        fn = float(g.uniform(5.0, 40.0))
    ri = float(g.uniform(0.025, 0.060))           # inner radius (m)
    w = float(g.uniform(0.015, 0.030))            # annulus width (m)
    ro = ri + w
    R = 0.5 * (ri + ro)                           # mean radius
    area = math.pi * (ro * ro - ri * ri)
    sigma_n = float(g.uniform(60e3, 350e3))       # Pa
    N0 = sigma_n * area
    mu_d = float(g.uniform(0.45, 0.62))
    dmu_s = float(g.uniform(0.05, 0.10))
    b_frac = float(g.uniform(0.25, 0.45))
    dtheta_slip = math.radians(float(g.uniform(0.05, 0.4)))   # drive twist per slip
    # spring: extension per slip at the mean radius ~ 2 dmu_s N0 / k
    dx_est = R * dtheta_slip
    k = 2.0 * dmu_s * N0 / dx_est
    wn = _TWO_PI * fn
    m = k / wn ** 2
    zeta = float(g.uniform(0.01, 0.04))
    v_est = wn * dmu_s * N0 / k
    p = dict(
        fmt=fmt, fn=fn, R=R, ri=ri, ro=ro, area=area, sigma_n=sigma_n, N0=N0,
        mu_d=mu_d, dmu_s=dmu_s, b=b_frac * dmu_s, k=k, m=m, zeta=zeta,
        c=2.0 * zeta * math.sqrt(k * m), J=m * R * R, k_t=k * R * R,
        v_est=v_est,
        v_phi=float(g.uniform(0.04, 0.10)) * v_est,
        v_T=float(g.uniform(0.8, 1.3)) * v_est,
        tau_phi0=float(g.uniform(0.0004, 0.0008)) / fn,
        L_phi=v_est * 0.0005 / fn,
        tau_T=float(g.uniform(0.003, 0.006)) / fn,
        rho=float(g.uniform(6.0, 13.0)),      # target T_ss / T_n at v0
        n_slips=int(g.integers(18, 37)),
        # extra draws (used by some cases only; drawn always for stability)
        u1=float(g.uniform()), u2=float(g.uniform()), u3=float(g.uniform()),
        u4=float(g.uniform()), u5=float(g.uniform()), u6=float(g.uniform()),
    )
    # drive speed from the estimated stick extension (refined by the pilot)
    p["v0"] = 0.8 * dx_est / (p["rho"] / fn)
    return p


def _bounce(t, eps, ftr, psi, key, sig_f, ncorr, amp_sig):
    """Phase and relative amplitude of the hanger's bounce: a lightly damped
    mode excited by a nearby machine, i.e. a narrow-band vibration whose
    frequency wanders (Ornstein-Uhlenbeck, rms sig_f * ftr, correlation time
    ncorr cycles) and whose amplitude fluctuates (rms amp_sig)."""
    g = _rng("bounce", *key)
    dtc = 0.25 / ftr
    nc = int(t[-1] / dtc) + 3
    tc = np.arange(nc) * dtc
    a = math.exp(-dtc / (ncorr / ftr))
    a2 = math.exp(-dtc / (3.0 * ncorr / ftr))
    w1 = g.normal(size=nc)
    w2 = g.normal(size=nc)
    df = signal.lfilter([math.sqrt(1 - a * a) * sig_f * ftr], [1.0, -a], w1,
                        zi=[a * sig_f * ftr * w1[0]])[0]
    am = signal.lfilter([math.sqrt(1 - a2 * a2) * amp_sig], [1.0, -a2], w2,
                        zi=[a2 * amp_sig * w2[0]])[0]
    theta = _TWO_PI * np.cumsum(df) * dtc
    phi = _TWO_PI * ftr * t + psi + np.interp(t, tc, theta)
    amp = np.clip(1.0 + np.interp(t, tc, am), 0.85, 1.2)
    return phi, amp


def _simulate(p, t_end, vd_fun=None, mode=None, sub=128, record=True, ksub=4):
    """Integrate the rig.  vd_fun(t) -> drive speed array (m/s at R).

    Fixed outer step dt = T_n/sub; a slipping step is split into ksub
    sub-steps (the fast states and the stick transition need them).
    mode: dict with optional keys 'beta','tau_a','L_h' (ageing),
    'trig' (eps, f, psi), 'dil' (c, v_delta, tau_d, tau_c), 'link' (s, F_ref).
    Returns dict of numpy arrays on the outer grid.
    """
    from scipy.linalg import expm
    mode = mode or {}
    fn = p["fn"]
    dt = 1.0 / (fn * sub)
    n = int(math.ceil(t_end / dt)) + 1
    t = np.arange(n) * dt
    if vd_fun is None:
        vd = np.full(n, p["v0"])
    else:
        vd = np.asarray(vd_fun(t), dtype=float)
    u = np.concatenate(([0.0], np.cumsum(0.5 * (vd[1:] + vd[:-1]) * dt)))
    ad = np.gradient(vd, dt)
    N0 = p["N0"]
    trig = "trig" in mode
    if trig:
        eps = mode["trig"][0]
        PhiA, AmpA = _bounce(t, *mode["trig"])
        Next = N0 * (1.0 + eps * AmpA * np.sin(PhiA))
        PhiL = PhiA.tolist()
        AmpL = AmpA.tolist()
    else:
        Next = np.full(n, N0)
    vdl = vd.tolist()
    ul = u.tolist()
    adl = ad.tolist()
    Nl = Next.tolist()

    k = p["k"]; m = p["m"]; c = p["c"]
    mu_d = p["mu_d"]; dmu = p["dmu_s"]; b = p["b"]
    v_phi = p["v_phi"]; inv_tphi0 = 1.0 / p["tau_phi0"]; inv_Lphi = 1.0 / p["L_phi"]
    v_T = p["v_T"]; inv_tT = 1.0 / p["tau_T"]
    K = int(ksub)
    h = dt / K
    hh2 = 0.5 * h
    e_phi_stick = math.exp(-dt * inv_tphi0)
    e_T_stick = math.exp(-dt * inv_tT)
    e_T_h = math.exp(-hh2 * inv_tT)
    # exact damped-oscillator propagator over a sub-step h
    A = np.array([[0.0, 1.0], [-k / m, -c / m]])
    Phi = expm(A * h)
    P00, P01, P10, P11 = float(Phi[0, 0]), float(Phi[0, 1]), float(Phi[1, 0]), float(Phi[1, 1])

    ageing = "beta" in mode
    if ageing:
        beta = mode["beta"]; inv_ta = 1.0 / mode["tau_a"]; inv_Lh = 1.0 / mode["L_h"]
    else:
        beta = 0.0; inv_ta = 1.0; inv_Lh = 0.0
    dil = "dil" in mode
    if dil:
        c_dil, v_del, tau_d, tau_c = mode["dil"]
        e_c_stick = math.exp(-dt / tau_c)
        inv_td = 1.0 / tau_d; inv_tc = 1.0 / tau_c
    else:
        c_dil = 0.0; v_del = 1.0; inv_td = inv_tc = 0.0
    link = "link" in mode
    if link:
        s_link, F_ref = mode["link"]

    # initial state: stuck, the arm preloaded to just below the static level
    x = (mu_d + 0.4 * dmu) * N0 / k; xd = vdl[0]; v = 0.0; v_prev = 0.0
    phi = 0.0; Th = 0.0; ta = 0.0; dl = 0.0
    stick = True
    X = [0.0] * n; V = [0.0] * n; FF = [0.0] * n; NN = [0.0] * n; ST = [True] * n
    PH = [0.0] * n; TH = [0.0] * n; HH = [0.0] * n
    X[0] = x; NN[0] = Nl[0]
    exp = math.exp
    for i in range(n - 1):
        Nb = Nl[i + 1]
        if stick:
            x += ul[i + 1] - ul[i]
            xd = vdl[i + 1]
            phi *= e_phi_stick
            Th *= e_T_stick
            if ageing:
                ta += dt
            if dil:
                dl *= e_c_stick
                Nb = Nb * (1.0 + c_dil * dl)
            if link:
                Nb = Nb + s_link * (k * x - F_ref)
            hgt = beta * math.log(1.0 + ta * inv_ta) if ageing else 0.0
            mu_thr = mu_d + dmu * (1.0 - phi) + b * Th + hgt
            Freq = k * x + c * xd + m * adl[i + 1]
            if Freq > mu_thr * Nb:
                stick = False
                F = mu_thr * Nb
            else:
                F = Freq
            v = 0.0
            v_prev = 0.0
        else:
            Fimp = 0.0
            tslip = 0.0
            vd0 = vdl[i]; dvd = vdl[i + 1] - vd0
            u0 = ul[i]; du = ul[i + 1] - u0
            Na = Nl[i]; dN = Nl[i + 1] - Na
            for jj in range(K):
                a1 = (jj + 1.0) / K
                am = (jj + 0.5) / K
                # first half sub-step of the states at the mean v over it
                vv = v + 0.25 * (v - v_prev)
                if vv < 0.0:
                    vv = 0.0
                pss = vv / (vv + v_phi)
                phi = pss + (phi - pss) * exp(-hh2 * (inv_tphi0 + vv * inv_Lphi))
                tss = (vv / v_T) ** 2
                Th = tss + (Th - tss) * e_T_h
                if ageing:
                    ta *= exp(-vv * hh2 * inv_Lh)
                if dil:
                    dss = vv / (vv + v_del)
                    dl = dss + (dl - dss) * exp(-hh2 * (inv_td if dss > dl else inv_tc))
                if trig:
                    ph_ = PhiL[i] + am * (PhiL[i + 1] - PhiL[i])
                    a_ = AmpL[i] + am * (AmpL[i + 1] - AmpL[i])
                    Nm = N0 * (1.0 + eps * a_ * math.sin(ph_))
                else:
                    Nm = Na + am * dN
                if dil:
                    Nm *= (1.0 + c_dil * dl)
                if link:
                    Nm += s_link * (k * x - F_ref)
                hgt = beta * math.log(1.0 + ta * inv_ta) if ageing else 0.0
                mu = mu_d + dmu * (1.0 - phi) + b * Th + hgt
                F = mu * Nm
                xe = F / k
                y = x - xe
                x_new = xe + P00 * y + P01 * xd
                xd_new = P10 * y + P11 * xd
                v_new = vd0 + a1 * dvd - xd_new
                v_prev = v
                if v_new <= 0.0:
                    # the upper ring has caught up with the lower one: stick at
                    # the crossing, the rest of the outer step in stick
                    s = v / (v - v_new) if v > v_new else 1.0
                    x = x + s * (x_new - x)
                    ucross = u0 + ((jj + s) / K) * du
                    x += ul[i + 1] - ucross
                    xd = vdl[i + 1]
                    Fimp += F * s * h
                    tslip += s * h
                    rem = dt - (jj + s) * h
                    phi *= exp(-rem * inv_tphi0)
                    Th *= exp(-rem * inv_tT)
                    if ageing:
                        ta += rem
                    if dil:
                        dl *= exp(-rem * inv_tc)
                    v = 0.0
                    v_prev = 0.0
                    stick = True
                    break
                Fimp += F * h
                tslip += h
                vv = v_new - 0.25 * (v_new - v)
                x = x_new; xd = xd_new; v = v_new
                # second half sub-step of the states
                pss = vv / (vv + v_phi)
                phi = pss + (phi - pss) * exp(-hh2 * (inv_tphi0 + vv * inv_Lphi))
                tss = (vv / v_T) ** 2
                Th = tss + (Th - tss) * e_T_h
                if ageing:
                    ta *= exp(-vv * hh2 * inv_Lh)
                if dil:
                    dss = vv / (vv + v_del)
                    dl = dss + (dl - dss) * exp(-hh2 * (inv_td if dss > dl else inv_tc))
            F = Fimp / tslip if tslip > 0.0 else F
            if dil:
                Nb = Nb * (1.0 + c_dil * dl)
            if link:
                Nb = Nb + s_link * (k * x - F_ref)
        j = i + 1
        X[j] = x; V[j] = v; FF[j] = F; NN[j] = Nb; ST[j] = stick
        if record:
            PH[j] = phi; TH[j] = Th
            if ageing:
                HH[j] = beta * math.log(1.0 + ta * inv_ta)
    out = dict(t=t, x=np.array(X), v=np.array(V), Ff=np.array(FF), N=np.array(NN),
               stick=np.array(ST, dtype=bool), u=u, vd=vd, dt=dt, fn=fn)
    if record:
        out.update(phi=np.array(PH), Th=np.array(TH), h=np.array(HH))
    return out


def _slips(sim):
    """Slip events: list of dicts with start/end indices, peak, min, drop, stick time."""
    st = sim["stick"]
    d = np.diff(st.astype(np.int8))
    starts = np.flatnonzero(d == -1) + 1     # stick -> slip
    ends = np.flatnonzero(d == 1) + 1        # slip -> stick
    k_x = sim["x"]
    out = []
    prev_end = 0
    dt = sim["dt"]
    for s0 in starts:
        e = ends[ends > s0]
        if len(e) == 0:
            break
        e0 = int(e[0])
        if e0 - s0 < 3:
            continue
        seg = k_x[s0:e0 + 1]
        out.append(dict(i0=int(s0), i1=e0, xpk=float(k_x[s0]), xmin=float(seg.min()),
                        t_stick=float((s0 - prev_end) * dt), t0=float(s0 * dt)))
        prev_end = e0
    # merge re-slips (a slip that ends and restarts within 0.3 T_n: chatter at
    # the end of a slip) into one event
    gap = max(4, int(0.3 / (sim["fn"] * dt)))
    merged = []
    for ev in out:
        if merged and ev["i0"] - merged[-1]["i1"] < gap:
            merged[-1]["i1"] = ev["i1"]
            merged[-1]["xmin"] = min(merged[-1]["xmin"], ev["xmin"])
        else:
            merged.append(ev)
    # macro slips only: a micro-slip (chatter under a vibrating load) with a
    # drop below a quarter of the median is folded into the stick around it
    if len(merged) > 2:
        drops = np.array([e["xpk"] - e["xmin"] for e in merged])
        med = float(np.median(drops))
        keep = []
        for e, d_ in zip(merged, drops):
            if d_ >= 0.25 * med:
                if keep:
                    e["t_stick"] = float((e["i0"] - keep[-1]["i1"]) * dt)
                keep.append(e)
        merged = keep
    return merged


def _twin(sim, ev, N_ref, lo=0.2, hi=0.8):
    i0, i1 = ev["i0"], ev["i1"]
    # the friction stored at step j acted over (t_{j-1}, t_j): pair it with the mid-step v
    vv = sim["v"]
    v = 0.5 * (vv[i0:i1 + 1] + vv[i0 - 1:i1])
    mu = sim["Ff"][i0:i1 + 1] / (0.5 * (sim["N"][i0:i1 + 1] + sim["N"][i0 - 1:i1]))
    j = int(np.argmax(v))
    vmax = v[j]
    if j < 3 or len(v) - j < 3 or vmax <= 0:
        return float("nan")
    va = np.maximum.accumulate(v[:j + 1]); ma = mu[:j + 1]
    vdv = np.maximum.accumulate(v[j:][::-1]); md = mu[j:][::-1]
    grid = np.linspace(lo, hi, 13) * vmax
    fa = np.interp(grid, va, ma)
    fd = np.interp(grid, vdv, md)
    return float(np.mean(fd - fa) * N_ref)


def _measure(p, sim, evs):
    k = p["k"]
    if len(evs) < 3:
        return dict(n_slips=len(evs), mean_drop_N=float("nan"), drop_cv=float("inf"),
                    twin_frac_mean=float("nan"), f_ss_Hz=float("nan"), N_pp_frac=float("nan"),
                    ageing_range_frac=float("nan"), peak_range_frac=float("nan"), failed=True)
    drops = np.array([k * (e["xpk"] - e["xmin"]) for e in evs])
    peaks = np.array([k * e["xpk"] for e in evs])
    tst = np.array([e["t_stick"] for e in evs])
    mean_drop = float(np.mean(drops))
    tw = np.array([_twin(sim, e, p["N0"]) for e in evs]) / drops
    twl = np.array([_twin(sim, e, p["N0"], 0.03, 0.2) for e in evs]) / drops
    res = dict(n_slips=len(evs), mean_drop_N=mean_drop,
               drop_cv=float(np.std(drops) / mean_drop),
               twin_frac_mean=float(np.nanmean(tw)),
               twin_frac_min=float(np.nanmin(tw)), twin_frac_max=float(np.nanmax(tw)),
               twin_low_v_frac_mean=float(np.nanmean(twl)),
               peak_range_frac=float((peaks.max() - peaks.min()) / mean_drop),
               stick_time_min_s=float(tst.min()), stick_time_max_s=float(tst.max()))
    if len(evs) > 1:
        res["f_ss_Hz"] = float((len(evs) - 1) / (evs[-1]["t0"] - evs[0]["t0"]))
    i0 = evs[0]["i0"]; i1 = evs[-1]["i1"]
    Nw = sim["N"][i0:i1 + 1]
    res["N_pp_frac"] = float((Nw.max() - Nw.min()) / p["N0"])
    if "h" in sim:
        hs = np.array([sim["h"][max(e["i0"] - 1, 0)] for e in evs]) * p["N0"]
        res["ageing_range_frac"] = float((hs.max() - hs.min()) / mean_drop)
    return res


# ----------------------------------------------------------------------------
# drive schedules
# ----------------------------------------------------------------------------

def _smooth_steps(t, times, levels, ramp):
    """Piecewise-constant speed with smooth (raised-cosine) ramps of length ramp."""
    vd = np.full_like(t, levels[0])
    for tk, l0, l1 in zip(times, levels[:-1], levels[1:]):
        s = np.clip((t - tk) / ramp, 0.0, 1.0)
        vd += (l1 - l0) * (0.5 - 0.5 * np.cos(math.pi * s))
    return vd


def _pilot(p, mode=None, n=5):
    """Short constant-drive run (n slips after the first)."""
    T = p["rho"] / p["fn"]
    for _ in range(4):
        sim = _simulate(p, T * (n + 2.5), mode=mode, record=True, sub=96)
        evs = _slips(sim)
        if len(evs) >= n:
            break
        T *= 2.0
    return sim, evs


# ----------------------------------------------------------------------------
# record writing
# ----------------------------------------------------------------------------

def _decimals_for(step):
    """decimals so that one unit of the last digit <= step."""
    return max(0, int(math.ceil(-math.log10(step))))


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    seed = int(seed)
    p = _draw_physics(case, seed)
    gN = _rng("nuis", case, seed, nuisance)
    gF = _rng("fmt", case, seed)
    fmt = p["fmt"]
    fn = p["fn"]
    Tn = 1.0 / fn
    # drive recorded?
    if fmt == "gds":
        has_drive = True
    else:
        has_drive = ((seed // 3) % 2 == 0)
    if case == "static_ageing":
        has_drive = True
    none_steps = (case == "none" and has_drive and p["u1"] < 0.5)

    # ---------------- pilots at constant drive: calibration ----------------
    mode = {}
    if case == "triggering":
        # a layer with a marked static peak (a weaker one is turned into steady
        # vibration-assisted creep by the bouncing hanger instead of triggered slips)
        p["dmu_s"] = max(p["dmu_s"], 0.075 + 0.02 * p["u6"])
    if case == "twin_branch":
        # slow granular-temperature decay and a stronger collisional stress;
        # the twin size is ~ proportional to b: calibrate b on pilots
        target = 0.11 + 0.09 * p["u2"]
        p["tau_T"] = (0.12 + 0.18 * p["u3"]) * Tn
        p["b"] *= 3.0
        for _ in range(4):
            sim, evs = _pilot(p)
            tw = _measure(p, sim, evs[1:])["twin_frac_mean"]
            if abs(tw - target) < 0.015:
                break
            p["b"] *= min(max(target / max(tw, 0.01), 0.4), 2.5)
    elif case == "load_variation":
        if p["u3"] < 0.5:
            # closed pneumatic piston: N follows the layer's (lagging) dilation
            target = 0.12 + 0.08 * p["u2"]
            # a layer with a marked static peak (a closed piston on a weakly
            # weakening layer arrests the slips and leaves only tiny drops)
            p["dmu_s"] = max(p["dmu_s"] * 1.4, 0.10 + 0.03 * p["u1"])
            v_del = float(0.2 + 0.3 * p["u4"]) * p["v_est"]
            tau_d = (0.5 + 0.5 * p["u5"]) * Tn
            tau_c = (1.0 + 2.0 * p["u6"]) * Tn
            c_dil = 0.6
            for _ in range(5):
                mode = {"dil": (c_dil, v_del, tau_d, tau_c)}
                s_, e_ = _pilot(p, mode)
                got = _measure(p, s_, e_[1:])["N_pp_frac"]
                if abs(got - target) < 0.015:
                    break
                c_new = min(max(c_dil * min(max((target / max(got, 1e-3)) ** 1.2, 0.3), 3.0), 0.3), 1.2)
                if c_new == c_dil:
                    break
                c_dil = c_new
            mode = {"dil": (c_dil, v_del, tau_d, tau_c)}
            p["load_mode"] = dict(kind="closed pneumatic piston on the layer: N = N0 (1 + c delta)",
                                  c=c_dil, v_delta=v_del, tau_dilate_s=tau_d, tau_compact_s=tau_c)
        else:
            # inclined reaction strut of the torque arm presses on the loading yoke
            target = 0.13 + 0.22 * p["u2"]
            sim, evs = _pilot(p)
            F_ref = float(np.mean(p["k"] * sim["x"][evs[1]["i0"]:evs[-1]["i1"]]))
            mu_s = p["mu_d"] + p["dmu_s"]
            lo, hi = 0.0, 0.92 / mu_s
            s_l = 0.8
            for _ in range(7):
                mode = {"link": (s_l, F_ref)}
                s_, e_ = _pilot(p, mode)
                got = _measure(p, s_, e_[1:])["N_pp_frac"]
                if abs(got - target) < 0.015:
                    break
                if got < target:
                    lo = s_l
                else:
                    hi = s_l
                s_l = 0.5 * (lo + hi)
            mode = {"link": (s_l, F_ref)}
            p["load_mode"] = dict(kind="reaction strut on the loading yoke: N = N0 + s (k x - F_ref)",
                                  s=s_l, F_ref_N=F_ref)
    pmode = mode if case == "load_variation" else None
    sim, evs = _pilot(p, pmode)
    base = _measure(p, sim, evs[1:])
    T_ss = 1.0 / base["f_ss_Hz"]
    drop0 = base["mean_drop_N"]
    # adjust v0 so that T_ss / T_n is near rho (stick time ~ 1/v0)
    t_slip = float(np.mean([(e["i1"] - e["i0"]) * sim["dt"] for e in evs[1:]]))
    t_stick = max(T_ss - t_slip, 0.2 * T_ss)
    want_stick = max(p["rho"] * Tn - t_slip, 2.0 * Tn)
    p["v0"] *= t_stick / want_stick
    T_ss = t_slip + want_stick
    t_stick = want_stick
    f_ss = 1.0 / T_ss

    v0 = p["v0"]
    n_sl = p["n_slips"]
    ramp = float(gF.uniform(0.05, 0.25)) * T_ss
    vd_fun = None
    sched = None
    pre = 2.3 * T_ss     # pre-roll (discarded)

    if case == "load_variation":
        t_end = pre + (n_sl + 0.8) * T_ss
    elif case == "triggering":
        eps = 0.036 + 0.016 * p["u2"]
        ftr = fn * (2.6 + 5.3 * p["u3"])
        psi = _TWO_PI * p["u4"]
        sig_f = 0.008 + 0.012 * p["u5"]
        ncorr = 10.0 + 20.0 * p["u6"]
        amp_sig = 0.05 + 0.04 * p["u1"]
        p["trig"] = dict(eps=eps, f_Hz=ftr, psi=psi, freq_wander_rms=sig_f,
                         wander_corr_cycles=ncorr, amp_fluct_rms=amp_sig)
        mode = {"trig": (eps, ftr, psi, (case, seed), sig_f, ncorr, amp_sig)}
        t_end = pre + (n_sl + 0.8) * T_ss
    elif case == "drive_modulation":
        a = 0.22 + 0.21 * p["u2"]
        r = 0.12 + 0.33 * p["u3"]
        fm = r * f_ss
        psi = _TWO_PI * p["u4"]
        p["modulation"] = dict(a=a, fm_Hz=fm, psi=psi, ratio_target=r)
        vd_fun = lambda t, a=a, fm=fm, psi=psi: v0 * (1.0 + a * np.sin(_TWO_PI * fm * t + psi))
        t_end = pre + (n_sl + 0.8) * T_ss
    elif case == "static_ageing" or none_steps:
        if case == "static_ageing":
            r = 4.0 + 4.0 * p["u2"]
            kind = ("steps", "holds", "both")[int(p["u3"] * 3) % 3]
        else:
            r = 2.0 + 4.0 * p["u2"]
            kind = "steps"
        T_slow = t_slip + r * (T_ss - t_slip)
        segs = []   # (speed, duration)
        if kind == "steps":
            ns_slow = max(3, int(round(n_sl * 0.25)))
            nf = n_sl - 2 * ns_slow
            nf1 = nf // 3 + 2
            nf2 = max(nf // 3, 2)
            nf3 = max(nf - nf1 - nf2, 2)
            segs = [(v0, pre + nf1 * T_ss), (v0 / r, ns_slow * T_slow),
                    (v0, nf2 * T_ss), (v0 / r, ns_slow * T_slow), (v0, (nf3 + 0.8) * T_ss)]
            if case == "none" and p["u4"] < 0.5:    # three levels
                segs[3] = (v0 / math.sqrt(r), ns_slow * (t_slip + math.sqrt(r) * (T_ss - t_slip)))
        elif kind == "holds":
            holds = [3.0, 10.0, 30.0] if p["u4"] < 0.5 else [5.0, 20.0]
            ng = len(holds) + 1
            per = max(3, (n_sl - len(holds)) // ng)
            segs = [(v0, pre + per * T_ss)]
            for hmult in holds:
                segs.append((0.0, hmult * T_ss * (0.6 + 0.3 * p["u5"])))
                segs.append((v0, per * T_ss))
            segs[-1] = (v0, (n_sl - per * (ng - 1) - len(holds) + 0.8) * T_ss)
        else:
            ns_slow = max(3, int(round(n_sl * 0.2)))
            per = max(3, (n_sl - ns_slow - 2) // 3)
            hmult = 8.0 + 12.0 * p["u5"]
            segs = [(v0, pre + per * T_ss), (v0 / r, ns_slow * T_slow), (v0, per * T_ss),
                    (0.0, hmult * T_ss), (v0, (n_sl - ns_slow - 2 * per + 0.8) * T_ss)]
        segs[-1] = (segs[-1][0], segs[-1][1] + 4.0 * T_ss)   # margin; cut at n_slips
        times = np.cumsum([d for _, d in segs])[:-1]
        levels = [s for s, _ in segs]
        t_end = float(np.sum([d for _, d in segs]))
        sched = dict(kind=kind, ratio=(None if kind == "holds" else r), times=times, levels=levels)
        vd_fun = lambda t, times=times, levels=levels: np.maximum(
            _smooth_steps(t, times, levels, ramp), 0.0)
        if case == "static_ageing":
            target = 0.08 + 0.08 * p["u6"]
            tau_a = (0.2 + 0.6 * p["u1"]) * Tn
            L_h = 0.005 * drop0 / p["k"]
            tmin = t_stick * 0.9
            tmax = max(tmin * r, (hmult if kind == "both" else (30.0 if kind == "holds" else 1.0)) * T_ss
                       * (0.6 if kind == "holds" else 1.0))
            lnr = math.log((1 + tmax / tau_a) / (1 + tmin / tau_a))
            beta = target * drop0 / p["N0"] / lnr
            p["ageing"] = dict(tau_a_s=tau_a, L_h_m=L_h, target=target)
            mode = {"beta": beta, "tau_a": tau_a, "L_h": L_h}
    else:
        t_end = pre + (n_sl + 0.8) * T_ss

    # ---------------- main simulation ------------------------------------
    sub = 160 if case == "triggering" else 128

    def _trial():
        sim_ = _simulate(p, t_end, vd_fun=vd_fun, mode=mode, sub=sub)
        ev_ = [e for e in _slips(sim_) if e["t0"] > pre * 0.95]
        evk_ = ev_[:min(len(ev_), n_sl)]
        return sim_, ev_, evk_, _measure(p, sim_, evk_)

    attempts = []
    for attempt in range(6):
        sim, evs, evs_k, meas = _trial()
        score = 0.0
        if meas.get("failed"):
            score = 1e9
        elif case == "static_ageing":
            af = meas["ageing_range_frac"]
            score = abs(af - p["ageing"]["target"]) * 20.0   # accepted within 0.015
            if score >= 0.3:
                mode["beta"] *= p["ageing"]["target"] / max(af, 1e-3)
                score += 0.0 if 0.05 <= af <= 0.20 else 10.0
        elif case == "triggering":
            fss = meas["f_ss_Hz"]
            stick_frac = float(np.mean(sim["stick"]))
            frac = (mode["trig"][1] / fss) % 1.0
            if len(evs) < 0.7 * n_sl or stick_frac < 0.7 or meas["drop_cv"] > 0.3:
                score = 100.0 + meas["drop_cv"]
            elif not (0.25 <= frac <= 0.75):
                score = 1.0 + abs(frac - 0.5)
            else:
                score = abs(frac - 0.5) * 0.01
        elif case == "drive_modulation":
            rr = p["modulation"]["fm_Hz"] / meas["f_ss_Hz"]
            score = 0.0 if 0.11 <= rr <= 0.46 else 1.0
        attempts.append((score, sim, evs, evs_k, meas, copy.deepcopy(mode),
                         copy.deepcopy({kk: p.get(kk) for kk in ("trig", "modulation")}), vd_fun))
        if score < 0.3:
            break
        # adjust for the next attempt
        if case == "triggering":
            if score >= 100.0:
                # the vibration suppressed the macro stick-slip: weaker vibration
                # (not below 3 % of N0) and a lower frequency
                eps_ = max(mode["trig"][0] * 0.88, 0.036)
                ftr = max(mode["trig"][1] * 0.85, 2.6 * fn)
            else:
                eps_ = mode["trig"][0]
                ftr = (math.floor(mode["trig"][1] / fss) + 0.5) * fss
                if ftr / fn < 2.55:
                    ftr += fss
                if ftr / fn > 7.95:
                    ftr -= fss
            mode["trig"] = (eps_, ftr) + tuple(mode["trig"][2:])
            p["trig"]["eps"] = eps_
            p["trig"]["f_Hz"] = ftr
        elif case == "drive_modulation":
            fm = p["modulation"]["ratio_target"] * meas["f_ss_Hz"]
            a_, psi_ = p["modulation"]["a"], p["modulation"]["psi"]
            p["modulation"]["fm_Hz"] = fm
            vd_fun = lambda t, a=a_, fm=fm, psi=psi_: v0 * (1.0 + a * np.sin(_TWO_PI * fm * t + psi))
    best = min(range(len(attempts)), key=lambda j_: attempts[j_][0])
    _, sim, evs, evs_k, meas, mode, saved, vd_fun = attempts[best]
    for kk, vv in saved.items():
        if vv is not None:
            p[kk] = vv
    if meas.get("failed"):
        raise RuntimeError(f"{NAME}: no stick-slip for case={case} seed={seed}")
    # cut the record: start inside the stick before the first kept slip
    first = evs[0]
    last_keep = len(evs_k)
    prev_end_t = (first["i0"] * sim["dt"]) - first["t_stick"]
    t_start = prev_end_t + (0.3 + 0.4 * p["u5"]) * first["t_stick"]
    if last_keep < len(evs):
        nxt = evs[last_keep]
        t_stop = evs_k[-1]["i1"] * sim["dt"] + (0.3 + 0.5 * p["u6"]) * (nxt["i0"] - evs_k[-1]["i1"]) * sim["dt"]
    else:
        t_stop = sim["t"][-1]
    if case == "triggering":
        q = p["trig"]["f_Hz"] / meas["f_ss_Hz"]
        meas["trig_eps"] = p["trig"]["eps"]
        i0_, i1_ = evs_k[0]["i0"], evs_k[-1]["i1"]
        _, amp_ = _bounce(sim["t"][i0_:i1_], *mode["trig"])
        meas["trig_amp_min"] = float(p["trig"]["eps"] * amp_.min())
        meas["trig_amp_max"] = float(p["trig"]["eps"] * amp_.max())
        meas["trig_f_over_fn"] = p["trig"]["f_Hz"] / fn
        meas["trig_f_over_fss"] = q
        meas["trig_dist_to_multiple_fss"] = float(abs(q - round(q)))
    if case == "drive_modulation":
        meas["mod_a"] = p["modulation"]["a"]
        meas["mod_fm_over_fss"] = p["modulation"]["fm_Hz"] / meas["f_ss_Hz"]
    if case == "static_ageing":
        p["ageing"]["beta"] = mode["beta"]

    return _write(case, seed, outdir, nuisance, p, sim, meas, t_start, t_stop, has_drive,
                  sched, gN, gF)


# ----------------------------------------------------------------------------
# logging
# ----------------------------------------------------------------------------

def _write(case, seed, outdir, nuisance, p, sim, meas, t_start, t_stop, has_drive, sched, gN, gF):
    fmt = p["fmt"]
    fn = p["fn"]
    drop = meas["mean_drop_N"]           # force at R (N)
    R = p["R"]
    # sampling rate
    if nuisance == "coarse":
        spt = float(gN.uniform(10.5, 14.5))
    else:
        spt = float(gF.uniform(22.0, 95.0))
    fs = spt * fn
    if fmt == "logger":
        fs = min(fs, 250.0)
    # nice rate
    if fs >= 50:
        fs = float(round(fs / 5.0) * 5.0)
    elif fs >= 10:
        fs = float(round(fs))
    else:
        fs = float(round(fs * 2) / 2.0)
    spt = fs / fn
    if nuisance == "coarse":
        spt = min(max(spt, 10.0), 15.0)
    else:
        spt = min(max(spt, 20.0), 100.0)
    fs = spt * fn if abs(fs / fn - spt) > 1e-9 else fs

    # sample times
    Ts = 1.0 / fs
    nS = int((t_stop - t_start) * fs)
    ts_nom = t_start + np.arange(nS) * Ts
    keep = np.ones(nS, dtype=bool)
    if fmt == "logger":
        jit = gF.normal(0.0, 0.08 * Ts, nS)
        jit = np.clip(jit, -0.3 * Ts, 0.3 * Ts)
        ts = ts_nom + jit
        ndrop = int(gF.integers(max(2, nS // 800), max(4, nS // 150)))
        idx = gF.choice(np.arange(5, nS - 5), size=ndrop, replace=False)
        for i in idx:
            L = 1 if gF.uniform() < 0.8 else int(gF.integers(2, 5))
            keep[i:i + L] = False
    else:
        ts = ts_nom

    # sensor chain: load-cell amplifier low-pass (2nd order Butterworth) on the fine grid
    dt = sim["dt"]
    fine_fs = 1.0 / dt
    fc = float(gF.uniform(0.22, 0.35)) * fs
    sos = signal.butter(2, min(fc / (0.5 * fine_fs), 0.9), output="sos")
    F_true = p["k"] * sim["x"]
    N_true = sim["N"]
    zi = signal.sosfilt_zi(sos)
    F_f = signal.sosfilt(sos, F_true, zi=zi * F_true[0])[0]
    fcN = float(gF.uniform(0.15, 0.3)) * fs
    sosN = signal.butter(2, min(fcN / (0.5 * fine_fs), 0.9), output="sos")
    N_f = signal.sosfilt(sosN, N_true, zi=signal.sosfilt_zi(sosN) * N_true[0])[0]
    Fs = np.interp(ts, sim["t"], F_f)
    Ns = np.interp(ts, sim["t"], N_f)
    us = np.interp(ts, sim["t"], sim["u"])
    if case == "drive_modulation":
        # the motor-side encoder sees the nominal rotation only
        us = p["v0"] * ts
    # drive reading at the start of the log: the GDS rotation counts from the
    # start of the test, the TAB angle is the ring's absolute angle, the logger's
    # arc is zeroed when logging starts
    if fmt == "gds":
        us = us - us[0] + math.radians(float(gF.uniform(5.0, 120.0))) * R
    elif fmt == "tab":
        us = us - us[0] + math.radians(float(gF.uniform(0.0, 360.0))) * R
    else:
        us = us - us[0]
    vds = np.interp(ts, sim["t"], sim["vd"])
    if case == "drive_modulation":
        vds = np.full_like(ts, p["v0"])

    # noise, nuisances (force channel in N at R; normal in N)
    Fs = Fs + gF.normal(0.0, float(gF.uniform(0.002, 0.005)) * drop, nS)
    Ns = Ns + gF.normal(0.0, float(gF.uniform(0.001, 0.003)) * p["N0"], nS)
    Fs = Fs + float(gF.uniform(-0.02, 0.02)) * drop   # zero offset of the cell
    nz = dict(kind=nuisance)
    if nuisance == "hum":
        f_line = 50.0 if gN.uniform() < 0.6 else 60.0
        A = float(gN.uniform(0.01, 0.05)) * drop
        ph = gN.uniform(0, _TWO_PI, 3)
        h = (np.sin(_TWO_PI * f_line * ts + ph[0]) + 0.35 * np.sin(_TWO_PI * 2 * f_line * ts + ph[1])
             + 0.25 * np.sin(_TWO_PI * 3 * f_line * ts + ph[2]))
        h *= A / (np.max(np.abs(h)) + 1e-12)
        Fs = Fs + h
        nz.update(line_Hz=f_line, amplitude_frac_drop=A / drop)
    elif nuisance == "drift":
        A = float(gN.uniform(0.02, 0.06)) * drop * (1 if gN.uniform() < 0.5 else -1)
        s = (ts - ts[0]) / (ts[-1] - ts[0])
        Fs = Fs + A * (0.7 * s + 0.3 * s * s)
        nz.update(total_frac_drop=A / drop)
    elif nuisance == "spikes":
        frac = float(gN.uniform(0.0005, 0.005))
        ns = max(1, int(round(frac * nS)))
        idx = gN.choice(np.arange(nS), size=ns, replace=False)
        Fs[idx] += gN.choice([-1.0, 1.0], ns) * gN.uniform(0.3, 1.0, ns) * drop
        nz.update(fraction=ns / nS)
    elif nuisance == "quantisation":
        q = float(gN.uniform(0.002, 0.01)) * drop
        Fs = np.round(Fs / q) * q
        nz.update(step_frac_drop=q / drop)
    elif nuisance == "coarse":
        nz.update(samples_per_period=spt)

    Fs = Fs[keep]; Ns = Ns[keep]; us = us[keep]; ts = ts[keep]; vds = vds[keep]
    t_rel = ts - ts[0]

    os.makedirs(outdir, exist_ok=True)
    fname = f"{NAME}_{case}_s{seed}_{nuisance}"
    args = []
    # fn given?
    fn_given = None
    if nuisance == "fn_off":
        fn_given = fn * (1.0 + (0.05 if gN.uniform() < 0.5 else -0.05))
    elif seed % 8 != 3:
        fn_given = fn
    if fn_given is not None:
        args += ["--fn", f"{fn_given:.4g}"]
        fn_given = float(f"{fn_given:.4g}")     # the value the user passes
    give_k = (seed % 8 != 5)
    k_lin = p["k"]
    k_t = p["k_t"]
    v0 = p["v0"]
    meta_extra = {}

    if fmt == "gds":
        # torque (N.m), normal stress (kPa), rotation (deg), angular velocity (deg/min)
        T = Fs * R
        sig = Ns / p["area"] / 1e3
        rot = np.degrees(us / R)
        omg = np.degrees(vds / R) * 60.0
        # stages from the drive schedule
        stage = np.full(len(ts), 3, dtype=int)
        if sched is not None:
            for tk in sched["times"]:
                stage += (ts >= tk).astype(int)
            stage = stage - stage[0] + 3
        t_test = t_rel + float(gF.uniform(1800.0, 7200.0))
        st_time = np.empty_like(t_test)
        for sv in np.unique(stage):
            msk = stage == sv
            st_time[msk] = t_test[msk] - (t_test[msk][0] if sv != stage[0] else t_test[msk][0] - float(gF.uniform(5, 60)))
        dT = _decimals_for(0.0005 * drop * R)
        dS = _decimals_for(0.001 * p["N0"] / p["area"] / 1e3)
        dR = _decimals_for(max(0.0005 * meas["mean_drop_N"] / k_lin / R * 180 / math.pi, 1e-7))
        lines = []
        q = lambda s: '"' + s + '"'
        date = f"{int(gF.integers(1, 28)):02d}/{int(gF.integers(1, 13)):02d}/2025 {int(gF.integers(8, 17)):02d}:{int(gF.integers(0, 60)):02d}:{int(gF.integers(0, 60)):02d}"
        hdr = [
            ("GDSLAB Data File", "v2.5.3"),
            ("Station Name:", "RS-" + str(int(gF.integers(1, 4))) + " Ring Shear (torsional reaction)"),
            ("Station Number:", str(int(gF.integers(1, 9)))),
            ("Test Name:", f"RS{int(gF.integers(100, 999))}_{('kaolin-sand', 'glass beads 0.3mm', 'quartz gouge', 'PTFE annulus', 'halite gouge')[int(gF.integers(0, 5))]}_stickslip"),
            ("Date Test Started:", date),
            ("Test Type:", "Ring Shear - Multistage"),
            ("Specimen Type:", "Annular, remoulded"),
            ("Inner Diameter (mm):", f"{2e3 * p['ri']:.1f}"),
            ("Outer Diameter (mm):", f"{2e3 * p['ro']:.1f}"),
            ("Area (mm2):", f"{p['area'] * 1e6:.1f}"),
            ("Mean Radius (mm):", f"{R * 1e3:.2f}"),
            ("Initial Height (mm):", f"{gF.uniform(4.0, 8.0):.2f}"),
            ("Torque Reaction:", "torque arm on load cell, torsion-spring reaction"),
            ("Reaction Torsional Stiffness (N.m/rad):", f"{k_t:.5g}"),
            ("Normal Load Application:", ("dead-weight hanger, lever 10:1", "pneumatic piston", "servo actuator")[int(gF.integers(0, 3))]),
            ("Log Interval (s):", f"{1.0 / fs:.5g}"),
            ("Sample Description:", ""),
            ("Comments:", "stick-slip study"),
        ]
        for kk, vv in hdr:
            lines.append(q(kk) + "," + q(vv))
        if sched is not None:
            for j, lv in enumerate(sched["levels"]):
                lines.append(q(f"Stage {3 + j}:") + "," + q(f"Shear at {np.degrees(lv / R) * 60:.4g} deg/min" if lv > 0 else "Hold (motor stopped)"))
        else:
            lines.append(q("Stage 3:") + "," + q(f"Shear at {np.degrees(v0 / R) * 60:.4g} deg/min"))
        lines.append("")
        cols = ["Stage Number", "Time since start of test (s)", "Time since start of stage (s)",
                "Torque (N.m)", "Normal Stress (kPa)", "Rotation (deg)", "Angular Velocity (deg/min)"]
        lines.append(",".join(q(cn) for cn in cols))
        dt_dec = 4 if fs > 100 else 3
        for i in range(len(ts)):
            lines.append(f"{stage[i]},{t_test[i]:.{dt_dec}f},{st_time[i]:.{dt_dec}f},{T[i]:.{dT}f},{sig[i]:.{dS}f},{rot[i]:.{dR}f},{omg[i]:.4f}")
        path = os.path.join(outdir, fname + ".csv")
        with open(path, "w", newline="") as fh:
            fh.write("\r\n".join(lines) + "\r\n")
        if give_k:
            args += ["--stiffness", f"{k_t:.5g} N·m/rad"]
        units = dict(force="torque N.m", normal="kPa", drive="deg")
    elif fmt == "logger":
        euro = (seed // 6) % 2 == 1
        sep = ";" if euro else ","
        dF = _decimals_for(0.0005 * drop)
        dN = _decimals_for(0.0005 * p["N0"] / 1e3)
        dA = _decimals_for(max(0.0005 * drop / k_lin * 1e3, 1e-6))
        y, mo, d = 2024 + int(gF.integers(0, 2)), int(gF.integers(1, 13)), int(gF.integers(1, 29))
        hh, mi, ss = int(gF.integers(7, 19)), int(gF.integers(0, 60)), float(gF.uniform(0, 60))
        import datetime as _dtm
        t0 = _dtm.datetime(y, mo, d, hh, mi, int(ss), int((ss % 1) * 1e6))
        lines = [
            "# RSA-3 ring shear acquisition, export of logger channel group 'shear'",
            f"# operator: {('JM', 'AK', 'LB', 'PW')[int(gF.integers(0, 4))]}  specimen: {('sand-clay mix', 'glass ballotini', 'granite gouge', 'rubber annulus')[int(gF.integers(0, 4))]}",
            f"# annulus: inner radius {p['ri'] * 1e3:.1f} mm, outer radius {p['ro'] * 1e3:.1f} mm, mean radius {R * 1e3:.2f} mm",
            "# shear force = reaction torque / mean radius; drive arc = lower-ring rotation x mean radius",
            f"# nominal sample rate {fs:g} Hz",
        ]
        cols = ["Date Time", "Shear force [N]", "Normal load [kN]"]
        if has_drive:
            cols.append("Drive arc [mm]")
        lines.append(sep.join(cols))
        arc = us * 1e3
        for i in range(len(ts)):
            stamp = t0 + _dtm.timedelta(seconds=float(t_rel[i]))
            st = stamp.strftime("%Y-%m-%d %H:%M:%S.") + f"{stamp.microsecond // 1000:03d}"
            row = [st, f"{Fs[i]:.{dF}f}", f"{Ns[i] / 1e3:.{dN}f}"]
            if has_drive:
                row.append(f"{arc[i]:.{dA}f}")
            r_ = sep.join(row)
            if euro:
                r_ = r_.replace(".", ",")
                # keep the stamp's decimal point as the logger writes it (comma too)
            lines.append(r_)
        path = os.path.join(outdir, fname + ".csv")
        with open(path, "w", newline="") as fh:
            fh.write("\n".join(lines) + "\n")
        if give_k:
            args += ["--stiffness", f"{k_lin / 1e3:.5g} N/mm"]
        if not has_drive:
            args += ["--v0", f"{v0 * 1e3:.5g} mm/s"]
        units = dict(force="N at mean radius", normal="kN", drive="mm of arc at mean radius")
        meta_extra["decimal_comma"] = euro
    else:
        T = Fs * R
        ang = np.degrees(us / R)
        dT = _decimals_for(0.0005 * drop * R)
        dN = _decimals_for(0.0005 * p["N0"] / 1e3)
        dR = _decimals_for(max(0.0005 * drop / k_lin / R * 180 / math.pi, 1e-7))
        lines = [
            "# Torsional shear rig TSR-1 / DAQ export (tab separated)",
            f"# mean radius {R * 1e3:.2f} mm; annulus {2e3 * p['ri']:.1f}/{2e3 * p['ro']:.1f} mm",
            f"# sample rate {fs:g} Hz; torque from reaction arm load cell",
        ]
        cols = ["Time [s]", "Torque [N·m]", "Normal force [kN]"]
        if has_drive:
            cols.append("Angle [deg]")
        lines.append("\t".join(cols))
        tdec = 5 if fs > 200 else 4
        for i in range(len(ts)):
            row = f"{t_rel[i]:.{tdec}f}\t{T[i]:.{dT}f}\t{Ns[i] / 1e3:.{dN}f}"
            if has_drive:
                row += f"\t{ang[i]:.{dR}f}"
            lines.append(row)
        path = os.path.join(outdir, fname + ".txt")
        with open(path, "w", encoding="utf-8", newline="") as fh:
            fh.write("\n".join(lines) + "\n")
        if give_k:
            args += ["--stiffness", f"{k_t:.5g} N·m/rad"]
        if not has_drive:
            if seed % 2 == 0:
                args += ["--v0", f"{v0 / R / _TWO_PI * 60:.5g} rpm"]
            else:
                args += ["--v0", f"{math.degrees(v0 / R):.5g} deg/s"]
        units = dict(force="torque N.m", normal="kN", drive="deg")

    params = dict(
        format=fmt, units=units, drive_recorded=has_drive, fs_Hz=fs, samples_per_Tn=spt,
        fn_Hz=fn, mean_radius_m=R, inner_radius_m=p["ri"], outer_radius_m=p["ro"],
        area_m2=p["area"], N0_N=p["N0"], sigma_n_Pa=p["sigma_n"],
        k_lin_N_per_m=k_lin, k_torsional_Nm_per_rad=k_t, m_eff_kg=p["m"], J_kgm2=p["J"],
        zeta=p["zeta"], v0_m_per_s=v0, v0_deg_per_s=math.degrees(v0 / R),
        law=dict(mu_d=p["mu_d"], dmu_s=p["dmu_s"], b=p["b"], v_phi=p["v_phi"], v_T=p["v_T"],
                 tau_phi0_s=p["tau_phi0"], L_phi_m=p["L_phi"], tau_T_s=p["tau_T"]),
        sensor=dict(force_lowpass_Hz=fc, normal_lowpass_Hz=fcN),
        nuisance=nz, measured=meas, measured_ranges_seeds0_7=MEASURED_RANGES[case],
        **meta_extra,
    )
    for key in ("load_mode", "trig", "modulation", "ageing"):
        if key in p:
            params[key] = p[key]
    if sched is not None:
        params["drive_schedule"] = dict(kind=sched["kind"], ratio=sched["ratio"],
                                        change_times_s=[float(x - t_start) for x in sched["times"]],
                                        levels_m_per_s=[float(x) for x in sched["levels"]])
    params = _jsonable(params)
    return dict(generator=NAME, case=case, seed=seed, nuisance=nuisance,
                file=os.path.abspath(path), args=args, fn_true=fn, fn_given=fn_given,
                params=params)


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
        return [_jsonable(v) for v in o.tolist()]
    if isinstance(o, float) and not math.isfinite(o):
        return None
    return o
