"""wet_clutch_lvfa -- evaluation records from a simulated low-velocity friction apparatus (LVFA).

The rig (an SAE J2490-style LVFA)
---------------------------------
A paper wet-clutch friction ring (annulus r_in 15-19 mm, width 7-10 mm, uniform-pressure effective
radius r_eff = 2/3 (ro^3 - ri^3)/(ro^2 - ri^2)) is pressed against a steel plate flooded with ATF.  The
apply force N0 = p_c A (contact pressure p_c 0.8-1.6 MPa) comes from a pneumatic piston (bore 40, 50 or
63 mm), so the logged apply pressure is N/A_piston (about 300-1400 kPa).  A motor turns at the drive
angle theta_d(t) and drives the plate (rotating inertia J 0.004-0.02 kg m^2) through a torsion bar with
an in-line torque cell (series stiffness k_theta = J (2 pi fn)^2, fn 6-15 Hz; shaft material damping
zeta 0.01-0.04).  The torque cell measures the shaft torque T_k = k_theta (theta_d - theta_p) +
c (Omega - omega): the "spring force" of the spring-slider, in N m.  The specimen holder is fixed; the
friction torque acts on the plate:  J omega' = T_k - T_f.

Friction law (own form: boundary + Couette shear of the ATF film, temperature through Vogel)
  T_f = sign(omega) [ mu_b(v, Theta_i) N r_eff + eta(Theta_i) |omega| pi (ro^4 - ri^4) / (2 h_eff) ]
  mu_b = mu_k (1 + kappa (Theta_i - Theta_set)) + dmu / (1 + v / v_b)^q  (+ g_f Theta_f, twin case)
  v = |omega| r_eff;  mu_k 0.085-0.125, dmu 0.022-0.045 (degraded friction modifier; 0.042-0.055 in the
  triggering case), q 0.8-1.5, v_b = V*/(4..10) with V* = dmu N0 r_eff^2/sqrt(k J) the speed scale of a
  slip (so the slips are full stick-slip, not small limit cycles), kappa +-6e-4 /K;
  eta = A exp(B/(Theta + 95 K)) (Vogel) fitted to an ATF of 30-38 cSt at 40 C and 6.5-8 cSt at 100 C
  (density 850), h_eff (an effective shear-film thickness, some 10-100 nm) set so that the Couette
  share of mu is 0.004-0.015 at 60 mm/s at the bath set point (40, 80, 100 or 120 C).
  The law is single-valued in v (positive Couette slope at speed, negative boundary slope at low speed)
  with mu(0+) = mu_k + dmu = the static level.
Heat: the interface temperature Theta_i follows C dTheta_i/dt = |T_f omega| - G (Theta_i - Theta_atf(t)),
  C 30-80 J/K, G 1-3 W/K, the bath controlled at its set point with a slow +-0.05-0.25 K controller
  swing (period 60-180 s).  The logged "ATF temp" is a thermocouple (0.1 K, updated at 10 Hz).

Stick handling (event driven, needed-torque test) and integrator (own fixed-step RK4)
  Slip: classical 4th-order Runge-Kutta with a fixed step dt = 1/(fs m) <= 1/(110 fn) on
  (theta_p, omega, Theta_f), the slip direction frozen over a step.  A change of sign of omega inside a
  step is located by 30 bisections of the step length (RK4 restarted from the step start); at that
  instant the shaft torque is compared with the static capacity T_s = mu_s N r_eff: |T_k| <= T_s ->
  stick, else the slip goes on (reverses).  Stick: omega = 0 exactly, plate held, the stick torque
  equals the needed torque T_k; each step the margin |T_k| - T_s is evaluated at both ends and the
  breakaway instant found by linear interpolation; the step is finished in slip.  No regularisation, so
  no creep in stick.  Theta_i and the regulator state advance by explicit Euler (they are slow).
  The run starts stuck at 0.75 T_s; the first 2 slips are discarded (the recording starts with the run
  going); a slip is a breakaway ... arrest with a torque drop > 0.3 of the pilot drop (a breakaway
  fragmented by a load ripple counts once).  The drive speed is set from two short effect-free pilot runs
  so that fn/f_ss is 5-11 (4-7 on the fast level of the stepped drives).

The six cases on this rig
  none: the law above, constant apply pressure, constant motor speed or (40 % of the seeds) a drive that
    steps between two recorded levels (factor 2-4).  The law's own memory is the interface temperature
    only.  MEASURED (seeds 0-7): interface temperature swing over a record 0.017-0.18 K; the resulting
    change of the friction torque at v_b 0.6e-5 - 1.5e-4 of the slip's torque drop; decelerating minus
    accelerating friction at equal speed (the twin measure below) 0.8e-5 - 1.6e-4 of the drop.
  load_variation: the plate carrier sits on a helical (lead) coupling, so the torsion bar's twist moves
    the carrier axially against the pneumatic chamber's air spring: N = N0 + k_n (tw - tw_m), tw the
    twist, tw_m its running mean held by the pressure regulator (time constant 6-20 s).  k_n signed (70 %
    positive; |k_n| mu_s r_eff/k_theta <= 0.8), calibrated by short runs to an aimed p-p of 14-35 % of N0.
    The normal channel (apply pressure kPa = chamber pressure, or a load cell under the holder in N) is
    recorded.  MEASURED: N p-p (0.5-99.5 percentiles) 13.4-32.9 % of N0 (max-min 14.3-35.4 %);
    self-energising factor -0.8 .. +0.53.
  twin_branch: friction-modifier desorption by the asperity flash temperature: Theta_f' = (R_f |T_f
    omega| - Theta_f)/tau_f (R_f 3-8 K/W, tau_f 0.25-0.6 natural periods) and mu_b += g_f Theta_f.  The
    flash temperature lags the frictional power, so at equal speed the contact is hotter and the friction
    higher on the decelerating half of a slip; g_f calibrated to an aimed 12-22 % of the drop.  MEASURED
    (median over slips of mean(T_f,dec - T_f,acc) at 0.25-0.85 of the slip's peak speed, / the slip's
    drop of the shaft torque): 0.146-0.214.
  static_ageing: boundary-film adsorption while stuck: mu_s = mu_k + dmu + beta ln(1 + t_stick/tau_a)
    (tau_a 0.03-0.15 s; reset at each slip).  The motor alternates 4-6 fast-level slips with 2-3 slow-level
    slips (speed factor 4-8) or, on half of the seeds, with a hold (motor stopped 2-6 s); the drive is
    recorded (Speed [rpm] of the motor encoder, or Motor angle [deg] of a 14-bit encoder).  beta calibrated
    to an aimed peak growth of 7-16 %.  MEASURED (mean peak of the sticks in the top decile of stick time
    vs those in the lowest quartile): +7.3..+14.0 % of the peak torque (+13.8..+20.5 % of the mean drop),
    over stick times from 0.66-1.44 s up to 4.5-10.2 s.
  triggering: apply-pressure ripple from the pneumatic regulator/compressor: N = N0 (1 + eps sin(2 pi f_t t
    + phi)), eps 3.2-6.5 % (MEASURED 3.8-6.1 %), f_t = 2.6-7.8 fn (MEASURED 3.27-7.24 fn), moved so that
    f_t / f_ss,unforced has a fractional part 0.26-0.75 (f_ss,unforced from an effect-free pilot,
    f_t/f_ss,unforced 17.5-65).  The ripple triggers the slips early at its troughs, so in the forced
    record the stick-slip locks to whole numbers of ripple periods (f_t/f_ss 15-59, integers or
    half-integers) and f_ss rises by some 10-20 %.  The pressure channel shows the ripple.
  drive_modulation: motor speed ripple Omega = Omega_n (1 + a sin(2 pi fm t + phi)), a 0.22-0.42, fm =
    0.12-0.45 of the unforced f_ss; no drive channel, only the nominal speed as --v0 (rpm).  MEASURED:
    a 0.24-0.41, fm/f_ss (forced record) 0.136-0.435.

Sensors and exports
  Torque cell: 2nd-order Butterworth low-pass at 12-30 fn on the shaft torque (at the simulation rate),
  then sampled at a DAQ rate from {100 ... 2400 Hz} with 22-90 samples per natural period (at least 7 per
  trigger period in the triggering case; 10-15 with the "coarse" nuisance), white noise 0.2-0.6 % and
  1/f noise 0.1-0.4 % (rms, of the drop), ADC 16 or 24 bit over +-5/10/20 N m.  Normal channel: apply
  pressure [kPa] (0.4 kPa noise, 0.1 kPa steps) or normal force [N] (1.5 N noise, 0.05 N steps).  ATF temp
  [°C] always.  Drive channel only for stepped drives.  Records hold 19-36 slips (2 discarded before).
  Formats (drawn per seed): HBM catman-style ASCII (4 metadata lines, TAB, a channel-name row and a unit
  row, N·m), a plain bench CSV ("Time [s],Torque [N·m],...,ATF temp [°C]"), a TAB export with
  "Time [ms]" and "Torque [Nm]", a DEWESoft-style semicolon export with decimal comma, 3 metadata lines,
  name and unit rows.
  Arguments: --stiffness "<k> N·m/rad" (the bench's torsion-bar calibration, 0-2 % off the true k), --v0
  "<rpm> rpm" when no drive channel is logged, --fn on about 75 % of the seeds (always with fn_off).
Nuisances: hum 50/60 Hz + 2nd and 3rd harmonics, 1-5 % of the drop; drift 2-6 % of the drop over the
  record (0.7 s + 0.3 s^2); spikes on 0.05-0.5 % of the samples (0.4-1.5 drop); quantisation: ADC step
  0.2-1 % of the drop; coarse: 10-15 samples per natural period; fn_off: --fn off by 4-5 % (either sign).
Readability check (lieng diagnose, all 48 clean records and 7 with nuisances): every file read (status 0);
  the column 'Apply pressure [kPa]' (23 of the 48 clean records) is left unread ('no role from its name'),
  'Normal force [N]', 'Speed [rpm]' and 'Motor angle [deg]' are read.  The files are kept as a bench writes them.
Cost: 0.1-0.9 s of CPU a record (pure Python stepper + numpy).
All randomness from numpy.random.default_rng([43, case index, seed]) (+ nuisance index for sensor noise).
"""
import math
import os

import numpy as np
from scipy import signal

NAME = "wet_clutch_lvfa"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
RPM = 2.0 * math.pi / 60.0          # rad/s per rpm
NICE_RATES = (100, 120, 150, 200, 250, 300, 400, 500, 600, 750, 800, 1000, 1200, 1500, 2000, 2400)


# ----------------------------------------------------------------------------------------------
# parameters
# ----------------------------------------------------------------------------------------------
def _draw(case, seed, nuisance):
    cidx = CASES.index(case)
    rng = np.random.default_rng([43, cidx, int(seed)])
    u = rng.uniform
    P = {}
    # --- specimen (annular paper ring) and apply piston
    ri = u(0.0150, 0.0190)
    ro = ri + u(0.0070, 0.0100)
    P["r_in_m"], P["r_out_m"] = ri, ro
    P["area_m2"] = math.pi * (ro ** 2 - ri ** 2)
    P["r_eff_m"] = 2.0 / 3.0 * (ro ** 3 - ri ** 3) / (ro ** 2 - ri ** 2)
    P["contact_pressure_MPa"] = u(0.8, 1.6)
    P["N0_N"] = P["contact_pressure_MPa"] * 1e6 * P["area_m2"]
    P["piston_d_m"] = float(rng.choice([0.040, 0.050, 0.063]))
    P["piston_area_m2"] = math.pi * P["piston_d_m"] ** 2 / 4.0
    # --- rotating plate + torsion bar
    P["J_kgm2"] = u(0.004, 0.020)
    P["fn_Hz"] = u(6.0, 15.0)
    P["k_Nm_rad"] = P["J_kgm2"] * (2 * math.pi * P["fn_Hz"]) ** 2
    P["zeta_shaft"] = u(0.01, 0.04)
    P["c_shaft_Nms_rad"] = 2 * P["zeta_shaft"] * math.sqrt(P["k_Nm_rad"] * P["J_kgm2"])
    # --- friction law (boundary + Couette shear of the ATF)
    P["mu_k"] = u(0.085, 0.125)
    P["dmu"] = u(0.022, 0.045)            # degraded friction modifier: mu(0) - mu_k
    if case == "triggering":              # a badly degraded (strongly shuddering) fluid
        P["mu_k"], P["dmu"] = u(0.075, 0.095), u(0.042, 0.055)
    P["q"] = u(0.8, 1.5)
    # speed scale of a slip, V* = dmu N0 r_eff^2 / sqrt(k J): the boundary decay speed is a fraction
    # of it so that the slips are full stick-slip (not small limit cycles)
    vstar = P["dmu"] * P["N0_N"] * P["r_eff_m"] ** 2 / math.sqrt(P["k_Nm_rad"] * P["J_kgm2"])
    P["v_b_m_s"] = vstar / u(4.0, 10.0)
    P["kappa_per_K"] = u(-6e-4, 6e-4)     # relative temperature coefficient of the boundary term
    nu40, nu100, rho = u(30, 38), u(6.5, 8.0), 850.0
    Cv = 95.0
    B = math.log(nu40 / nu100) / (1 / (40 + Cv) - 1 / (100 + Cv))
    A = nu100 * 1e-6 * rho / math.exp(B / (100 + Cv))
    P["vogel"] = {"A_Pas": A, "B_K": B, "C_K": Cv, "nu40_cSt": nu40, "nu100_cSt": nu100}
    P["T_atf_set_C"] = float(rng.choice([40.0, 80.0, 100.0, 120.0]))
    eta_set = A * math.exp(B / (P["T_atf_set_C"] + Cv))
    mu_h_ref = u(0.004, 0.015)            # Couette share of mu at 60 mm/s at the set temperature
    v_ref = 0.06
    P["h_eff_m"] = eta_set * v_ref * P["area_m2"] / (mu_h_ref * P["N0_N"])
    P["mu_h_at_60mm_s"] = mu_h_ref
    # --- heat: interface lumped capacity, ATF bath controller
    P["C_th_J_K"] = u(30.0, 80.0)
    P["G_th_W_K"] = u(1.0, 3.0)
    P["atf_ctrl_amp_K"] = u(0.05, 0.25)
    P["atf_ctrl_period_s"] = u(60.0, 180.0)
    P["atf_ctrl_phase"] = u(0, 2 * math.pi)
    # --- drive
    P["R_fn_fss"] = u(5.0, 11.0) if case != "static_ageing" else u(4.0, 7.0)
    P["n_slips_target"] = int(rng.integers(18, 36))
    # --- effects
    P["ageing_beta"] = 0.0
    P["ageing_tau_s"] = u(0.03, 0.15)
    P["flash_gain"] = 0.0
    P["flash_tau_s"] = u(0.25, 0.6) / P["fn_Hz"]
    P["flash_R_K_W"] = u(3.0, 8.0)
    P["load_kn_N_rad"] = 0.0
    P["load_reg_tau_s"] = u(6.0, 20.0)
    P["trig_eps"] = 0.0
    P["trig_ratio_fn"] = u(2.6, 7.8)
    P["trig_phase"] = u(0, 2 * math.pi)
    P["mod_a"] = 0.0
    P["mod_ratio_fss"] = u(0.12, 0.45)
    P["mod_phase"] = u(0, 2 * math.pi)
    # stepped drive: ageing always, none sometimes
    P["drive_steps"] = case == "static_ageing" or (case == "none" and u() < 0.4)
    P["step_factor"] = u(4.0, 8.0) if case == "static_ageing" else u(2.0, 4.0)
    P["holds"] = bool(case == "static_ageing" and u() < 0.5)
    P["hold_s"] = u(2.0, 6.0)
    if case == "load_variation":
        P["load_pp_target"] = u(0.14, 0.35)
        P["load_sign"] = 1.0 if u() < 0.7 else -1.0
    if case == "twin_branch":
        P["twin_target"] = u(0.12, 0.22)
    if case == "static_ageing":
        P["ageing_target"] = u(0.07, 0.16)
    if case == "triggering":
        P["trig_eps"] = u(0.032, 0.065)
    if case == "drive_modulation":
        P["mod_a"] = u(0.22, 0.42)
    # --- sensors / export
    P["spp"] = u(10.0, 15.0) if nuisance == "coarse" else u(22.0, 90.0)
    if case == "triggering" and nuisance != "coarse":
        P["spp"] = max(P["spp"], min(95.0, 7.0 * P["trig_ratio_fn"]))
    P["cell_fc_fn"] = u(12.0, 30.0)
    P["white_rel"] = u(0.002, 0.006)
    P["pink_rel"] = u(0.001, 0.004)
    P["adc_range_Nm"] = float(rng.choice([5.0, 10.0, 20.0]))
    P["adc_bits"] = int(rng.choice([16, 24]))
    P["format"] = str(rng.choice(["catman", "bench_csv", "tab_ms", "dewesoft"]))
    P["normal_channel"] = str(rng.choice(["pressure_kPa", "force_N"]))
    P["drive_channel"] = str(rng.choice(["speed_rpm", "angle_deg"]))
    P["give_fn"] = bool(u() < 0.75) or nuisance == "fn_off"
    P["k_user_err"] = u(-0.02, 0.02)
    P["hum_f"] = float(rng.choice([50.0, 60.0]))
    P["hum_rel"] = u(0.01, 0.05)
    P["drift_rel"] = u(0.02, 0.06) * (1 if u() < 0.5 else -1)
    P["spike_frac"] = u(0.0005, 0.005)
    P["quant_rel"] = u(0.002, 0.01)
    P["fn_off_rel"] = u(0.04, 0.05) * (1 if u() < 0.5 else -1)
    P["noise_seed"] = int(rng.integers(0, 2 ** 31 - 1))
    return P


# ----------------------------------------------------------------------------------------------
# drive profiles
# ----------------------------------------------------------------------------------------------
class _Drive:
    """Motor angle theta_d(t) and speed Omega(t): constant, stepped/held, or sinusoidally modulated."""

    def __init__(self, omega_n, segments=None, a=0.0, fm=0.0, phi=0.0):
        self.omega_n, self.a, self.fm, self.phi = omega_n, a, fm, phi
        self.seg = None
        if segments:
            ts, th, om = [], [], []
            t0, th0 = 0.0, 0.0
            for dur, w in segments:
                ts.append(t0); th.append(th0); om.append(w)
                t0 += dur; th0 += w * dur
            self.seg = (ts, th, om)
            self.t_end_profile = t0

    def __call__(self, t):
        if self.seg is not None:
            ts, th, om = self.seg
            i = len(ts) - 1
            while ts[i] > t:
                i -= 1
            return th[i] + om[i] * (t - ts[i]), om[i]
        if self.a:
            w = 2 * math.pi * self.fm
            th = self.omega_n * (t - self.a / w * (math.cos(w * t + self.phi) - math.cos(self.phi)))
            return th, self.omega_n * (1 + self.a * math.sin(w * t + self.phi))
        return self.omega_n * t, self.omega_n


# ----------------------------------------------------------------------------------------------
# the rig
# ----------------------------------------------------------------------------------------------
def _simulate(P, drive, t_end, dt, n_stop=None, theta_tw0=None, drop_min=0.0):
    """Event-driven stick/slip simulation of the LVFA plate on its torsion bar.

    Slip: classical RK4 with fixed step dt on (theta_p, omega, Theta_flash); a change of sign of
    omega inside a step is located by bisection on the step length (RK4 restarted from the step
    start) and the step is finished in the new mode.  Stick: omega = 0 exactly, the plate held,
    the needed torque (shaft torque) compared each step with the static capacity
    mu_s N r_eff; the breakaway instant inside the step is found by linear interpolation of the
    margin and the step finished in slip.
    """
    k, c, J = P["k_Nm_rad"], P["c_shaft_Nms_rad"], P["J_kgm2"]
    re, N0 = P["r_eff_m"], P["N0_N"]
    mu_k, dmu, vb, q, kap = P["mu_k"], P["dmu"], P["v_b_m_s"], P["q"], P["kappa_per_K"]
    A, B, Cv = P["vogel"]["A_Pas"], P["vogel"]["B_K"], P["vogel"]["C_K"]
    ri, ro = P["r_in_m"], P["r_out_m"]
    polar = math.pi * (ro ** 4 - ri ** 4) / 2.0 / P["h_eff_m"]     # Couette torque = eta*omega*polar
    Tset = P["T_atf_set_C"]
    beta, tau_a = P["ageing_beta"], P["ageing_tau_s"]
    gf, tauf, Rf = P["flash_gain"], P["flash_tau_s"], P["flash_R_K_W"]
    kn, tau_reg = P["load_kn_N_rad"], P["load_reg_tau_s"]
    eps_t = P["trig_eps"]
    wt = 2 * math.pi * P["trig_ratio_fn"] * P["fn_Hz"]
    ph_t = P["trig_phase"]
    Cth, Gth = P["C_th_J_K"], P["G_th_W_K"]
    amp_c, w_c, ph_c = P["atf_ctrl_amp_K"], 2 * math.pi / P["atf_ctrl_period_s"], P["atf_ctrl_phase"]
    exp, sin = math.exp, math.sin

    def normal(t, tw, twm):
        n = N0
        if kn:
            n += kn * (tw - twm)
        if eps_t:
            n *= 1.0 + eps_t * sin(wt * t + ph_t)
        return n

    def mu_bound(v, Ti, Tf):
        return mu_k * (1.0 + kap * (Ti - Tset)) + dmu / (1.0 + v / vb) ** q + gf * Tf

    def deriv(t, th, om, Tf, Ti, twm, s):
        # s: the slip direction, held over a step (a sign change ends the step, see below)
        thd, omd = drive(t)
        tw = thd - th
        Tk = k * tw + c * (omd - om)
        n = normal(t, tw, twm)
        v = abs(om) * re
        eta = A * exp(B / (Ti + Cv))
        Tfr = s * (mu_bound(v, Ti, Tf) * n * re + eta * abs(om) * polar)
        dTf = (Rf * abs(Tfr * om) - Tf) / tauf if gf else 0.0
        return om, (Tk - Tfr) / J, dTf, Tk, Tfr, n

    def rk4(t, h, th, om, Tf, Ti, twm):
        s = 1.0 if om > 0 else -1.0
        a1 = deriv(t, th, om, Tf, Ti, twm, s)
        a2 = deriv(t + h / 2, th + h / 2 * a1[0], om + h / 2 * a1[1], Tf + h / 2 * a1[2], Ti, twm, s)
        a3 = deriv(t + h / 2, th + h / 2 * a2[0], om + h / 2 * a2[1], Tf + h / 2 * a2[2], Ti, twm, s)
        a4 = deriv(t + h, th + h * a3[0], om + h * a3[1], Tf + h * a3[2], Ti, twm, s)
        return (th + h / 6 * (a1[0] + 2 * a2[0] + 2 * a3[0] + a4[0]),
                om + h / 6 * (a1[1] + 2 * a2[1] + 2 * a3[1] + a4[1]),
                Tf + h / 6 * (a1[2] + 2 * a2[2] + 2 * a3[2] + a4[2]))

    def capacity(t, th, Tf, Ti, twm, tst):
        thd, omd = drive(t)
        tw = thd - th
        Tk = k * tw + c * omd
        n = normal(t, tw, twm)
        mus = mu_k * (1.0 + kap * (Ti - Tset)) + dmu + gf * Tf
        if beta:
            mus += beta * math.log1p(tst / tau_a)
        return Tk, mus * n * re, n

    # initial state: stuck, shaft twisted to a given fraction of the breakaway torque
    if theta_tw0 is None:
        theta_tw0 = 0.75 * (mu_k + dmu) * N0 * re / k
    th = drive(0.0)[0] - theta_tw0
    om, Tf, Ti = 0.0, 0.0, Tset
    twm = theta_tw0
    stuck, t_st0 = True, 0.0
    n_steps = int(round(t_end / dt))
    out = np.empty((n_steps + 1, 8))
    events = []     # (kind, t, Tk)  kind 1: breakaway, 0: stop
    nslip = 0       # completed slips whose torque drop exceeds drop_min
    tb_max = -1e300
    t = 0.0
    for i in range(n_steps + 1):
        t = i * dt
        thd, omd = drive(t)
        if stuck:
            Tk, Ts, n = capacity(t, th, Tf, Ti, twm, t - t_st0)
            Tfr = Tk            # needed torque transmitted by the stuck contact
        else:
            _, _, _, Tk, Tfr, n = deriv(t, th, om, Tf, Ti, twm, 1.0 if om > 0 else -1.0)
        out[i] = (t, th, om, Tk, Tfr, n, Ti, Tf)
        if n_stop is not None and nslip >= n_stop:
            out = out[:i + 1]
            break
        if i == n_steps:
            break
        # slow states: interface temperature (explicit Euler), regulator mean of the twist
        Tatf = Tset + amp_c * sin(w_c * t + ph_c)
        Ti += dt * (abs(Tfr * om) - Gth * (Ti - Tatf)) / Cth
        if kn:
            twm += dt * ((thd - th) - twm) / tau_reg
        h_left, tt = dt, t
        guard = 0
        while h_left > 1e-15 and guard < 6:
            guard += 1
            if stuck:
                Tk0, Ts0, _ = capacity(tt, th, Tf, Ti, twm, tt - t_st0)
                Tf1 = Tf * exp(-h_left / tauf) if gf else 0.0
                Tk1, Ts1, _ = capacity(tt + h_left, th, Tf1, Ti, twm, tt + h_left - t_st0)
                m0, m1 = abs(Tk0) - Ts0, abs(Tk1) - Ts1
                if m1 <= 0.0:
                    Tf = Tf1
                    break
                f = 0.0 if m0 >= 0 else m0 / (m0 - m1)
                hb = f * h_left
                Tf = Tf * exp(-hb / tauf) if gf else 0.0
                tt += hb
                h_left -= hb
                stuck = False
                Tb_ = Tk1 if f == 0 else Tk0 + f * (Tk1 - Tk0)
                tb_max = max(tb_max, abs(Tb_))
                events.append((1, tt, Tb_))
                om = 1e-9 if Tk1 > 0 else -1e-9
                continue
            th1, om1, Tf1 = rk4(tt, h_left, th, om, Tf, Ti, twm)
            if om1 * om > 0:
                th, om, Tf = th1, om1, Tf1
                break
            # sign change of omega within the step: bisection on the sub-step length
            lo, hi = 0.0, h_left
            for _ in range(30):
                mid = 0.5 * (lo + hi)
                _, omm, _ = rk4(tt, mid, th, om, Tf, Ti, twm)
                if omm * om > 0:
                    lo = mid
                else:
                    hi = mid
            th, _, Tf = rk4(tt, hi, th, om, Tf, Ti, twm)
            tt += hi
            h_left -= hi
            Tk, Ts, _ = capacity(tt, th, Tf, Ti, twm, 0.0)
            if abs(Tk) <= Ts:
                stuck, om, t_st0 = True, 0.0, tt
                events.append((0, tt, Tk))
                if tb_max - abs(Tk) > drop_min:
                    nslip += 1
                    tb_max = -1e300
            else:
                om = 1e-9 if Tk > 0 else -1e-9
    return out, events


def _slips(events, drop_min=0.0):
    """Slips as (t_break, T_break, t_stop, T_stop): a stop whose drop from the highest breakaway
    torque since the previous slip exceeds drop_min ends a slip that began at the first breakaway
    after the previous slip (a breakaway fragmented by a load ripple counts once)."""
    res = []
    first, tmax = None, -1e300
    for kind, t, Tk in events:
        if kind == 1:
            if first is None:
                first = t
            tmax = max(tmax, Tk)
        elif first is not None and tmax - Tk > drop_min:
            res.append((first, tmax, t, Tk))
            first, tmax = None, -1e300
    return res


def _twin_measure(out, slips, P):
    """Median over slips of mean(T_f,decel - T_f,accel) at equal speed (0.25-0.85 of the peak),
    as a fraction of the slip's drop of the shaft torque."""
    t = out[:, 0]
    vals = []
    for tb, Tb, ts, Ts in slips:
        i0, i1 = np.searchsorted(t, tb), np.searchsorted(t, ts)
        if i1 - i0 < 8:
            continue
        om, Tf = out[i0:i1, 2], out[i0:i1, 4]
        ip = int(np.argmax(om))
        if ip < 3 or ip > len(om) - 4:
            continue
        g = np.linspace(0.25, 0.85, 13) * om[ip]
        a_om, a_T = om[:ip + 1], Tf[:ip + 1]
        d_om, d_T = om[ip:][::-1], Tf[ip:][::-1]
        ia, idd = np.argsort(a_om), np.argsort(d_om)
        fa = np.interp(g, a_om[ia], a_T[ia])
        fd = np.interp(g, d_om[idd], d_T[idd])
        drop = Tb - Ts
        if drop > 0:
            vals.append(float(np.mean(fd - fa) / drop))
    return float(np.median(vals)) if vals else float("nan")


def _fss(slips):
    tb = [s[0] for s in slips]
    if len(tb) < 3:
        return float("nan")
    return (len(tb) - 1) / (tb[-1] - tb[0])


# ----------------------------------------------------------------------------------------------
def _run(case, P, nuisance):
    fn = P["fn_Hz"]
    k, re, N0 = P["k_Nm_rad"], P["r_eff_m"], P["N0_N"]
    pre = 2  # slips discarded at the start of the record (the run is already going)
    n_need = P["n_slips_target"] + pre + 1
    t_max = 400.0
    fs_target = P["spp"] * fn
    cand = [r for r in NICE_RATES if (10 if nuisance == "coarse" else 20) * fn <= r <= (15 if nuisance == "coarse" else 100) * fn]
    fs = float(min(cand, key=lambda r: abs(r - fs_target))) if cand else round(fs_target, 1)
    m = max(1, int(math.ceil(110.0 * fn / fs)))
    dt = 1.0 / (fs * m)
    P["fs_Hz"], P["sub_steps"], P["dt_sim_s"] = fs, m, dt
    # drive speed from the aimed cycle: drop estimate from the law
    t_cycle = P["R_fn_fss"] / fn
    # pilot runs of the effect-free rig at a constant drive: the slip's torque drop and duration,
    # then the drive speed that gives the aimed stick-slip period
    Q = dict(P)
    Q.update(ageing_beta=0.0, flash_gain=0.0, load_kn_N_rad=0.0, trig_eps=0.0, mod_a=0.0)
    omega_try = 2.0 * P["dmu"] * N0 * re / k / t_cycle
    for _ in range(2):
        o, e = _simulate(Q, _Drive(omega_try), t_max, dt, n_stop=7)
        sl = _slips(e)[2:]
        drop_est = float(np.mean([s_[1] - s_[3] for s_ in sl]))
        t_slip = float(np.mean([s_[2] - s_[0] for s_ in sl]))
        t_stick = max(t_cycle - t_slip, 0.5 / fn)
        omega_try = drop_est / k / t_stick
    omega_n = omega_try
    o, e = _simulate(Q, _Drive(omega_n), t_max, dt, n_stop=8)
    P["fss_unforced_Hz"] = _fss(_slips(e)[2:])
    P["drop_pilot_Nm"] = drop_est
    dmin = 0.3 * drop_est
    P["omega_n_rad_s"] = omega_n
    P["v0_rpm"] = omega_n / RPM

    def make_drive(fss=None):
        if P["drive_steps"]:
            fac = P["step_factor"]
            t_fast = t_cycle
            t_slow = t_cycle * fac
            segs = []
            n_tot = 0
            k_i = 0
            while n_tot < P["n_slips_target"] + 8:
                nf = 4 + (k_i % 3)
                segs.append((nf * t_fast, omega_n)); n_tot += nf
                if P["holds"] and k_i % 2 == 1:
                    segs.append((P["hold_s"], 0.0))
                    segs.append((2 * t_fast, omega_n)); n_tot += 2
                else:
                    ns = 2 + (k_i % 2)
                    segs.append((ns * t_slow, omega_n / fac)); n_tot += ns
                k_i += 1
            segs.append((1e6, omega_n))
            return _Drive(omega_n, segs)
        if P["mod_a"]:
            return _Drive(omega_n, a=P["mod_a"], fm=P["mod_ratio_fss"] * fss, phi=P["mod_phase"])
        return _Drive(omega_n)


    def full(drive):
        out, ev = _simulate(P, drive, t_max, dt, n_stop=n_need, drop_min=dmin)
        return out, ev

    # ---- calibrations (short runs, effect scaled linearly towards its aimed size)
    if case in ("drive_modulation",):
        drive = make_drive(P["fss_unforced_Hz"])
    else:
        drive = make_drive()
    if case == "twin_branch":
        # flash temperature scale: P ~ T * omega_peak
        P["flash_gain"] = 1e-3
        for _ in range(2):
            o, e = _simulate(P, drive, t_max, dt, n_stop=7, drop_min=dmin)
            tw = _twin_measure(o, _slips(e, dmin)[1:], P)
            P["flash_gain"] *= P["twin_target"] / max(tw, 1e-3)
    if case == "load_variation":
        dth = drop_est / k
        P["load_kn_N_rad"] = P["load_sign"] * P["load_pp_target"] * N0 / dth * 0.6
        mus = P["mu_k"] + P["dmu"]
        lim = 0.8 * k / (mus * re)          # keep the self-energising factor below 0.8
        for _ in range(4):
            P["load_kn_N_rad"] = float(np.clip(P["load_kn_N_rad"], -lim, lim))
            o, e = _simulate(P, drive, t_max, dt, n_stop=8, drop_min=dmin)
            i0 = np.searchsorted(o[:, 0], _slips(e, dmin)[1][0])
            nn = o[i0:, 5]
            pp = (np.percentile(nn, 99.5) - np.percentile(nn, 0.5)) / N0
            if abs(pp / P["load_pp_target"] - 1) < 0.08:
                break
            P["load_kn_N_rad"] *= (P["load_pp_target"] / max(pp, 1e-3)) ** 0.7
        P["load_kn_N_rad"] = float(np.clip(P["load_kn_N_rad"], -lim, lim))
    if case == "static_ageing":
        fac = P["step_factor"]
        t1 = 0.8 * t_stick
        t2 = t1 * fac
        if P["holds"]:
            t2 = max(t2, P["hold_s"] + t1)
        mus = P["mu_k"] + P["dmu"]
        P["ageing_beta"] = P["ageing_target"] * mus / (math.log1p(t2 / P["ageing_tau_s"]) - math.log1p(t1 / P["ageing_tau_s"]))
    if case == "triggering":
        # f_t away from the multiples of the unforced stick-slip frequency
        fss = P["fss_unforced_Hz"]
        r = P["trig_ratio_fn"] * fn / fss
        frac = r - math.floor(r)
        if not 0.25 <= frac <= 0.75:
            P["trig_ratio_fn"] = (math.floor(r) + 0.5) * fss / fn
            if P["trig_ratio_fn"] > 8.0:
                P["trig_ratio_fn"] -= fss / fn
            if P["trig_ratio_fn"] < 2.5:
                P["trig_ratio_fn"] += fss / fn
    out, ev = full(drive)
    slips = _slips(ev, dmin)
    if case == "static_ageing":
        g = _ageing_measure(out, slips, P)
        P["ageing_beta"] *= P["ageing_target"] / max(g["growth_rel_peak"], 1e-3)
        out, ev = full(drive)
        slips = _slips(ev, dmin)
    return out, ev, slips, drive, pre


def _ageing_measure(out, slips, P):
    """Peak torques against the preceding stick time."""
    ts, pk = [], []
    for j in range(1, len(slips)):
        ts.append(slips[j][0] - slips[j - 1][2])
        pk.append(slips[j][1])
    ts, pk = np.array(ts), np.array(pk)
    if len(ts) < 4:
        return {"growth_rel_peak": float("nan")}
    lo = ts <= np.percentile(ts, 25)
    hi = ts >= np.percentile(ts, 90)
    p_lo, p_hi = np.mean(pk[lo]), np.mean(pk[hi])
    drops = np.array([s[1] - s[3] for s in slips])
    return {"growth_rel_peak": float((p_hi - p_lo) / p_lo), "growth_rel_drop": float((p_hi - p_lo) / np.mean(drops)),
            "t_stick_min_s": float(ts.min()), "t_stick_max_s": float(ts.max())}


# ----------------------------------------------------------------------------------------------
# sensors and export
# ----------------------------------------------------------------------------------------------
def _pink(rng, n):
    w = rng.standard_normal(n)
    f = np.fft.rfftfreq(n)
    F = np.fft.rfft(w)
    f[0] = f[1] if n > 1 else 1.0
    F /= np.sqrt(f)
    F[0] = 0.0
    x = np.fft.irfft(F, n)
    return x / (np.std(x) + 1e-30)


def _fmt_num(x, nd, comma=False):
    s = f"{x:.{nd}f}"
    return s.replace(".", ",") if comma else s


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError(f"unknown case {case!r}")
    if nuisance not in NUISANCES:
        raise ValueError(f"unknown nuisance {nuisance!r}")
    P = _draw(case, seed, nuisance)
    out, ev, slips, drive, pre = _run(case, P, nuisance)
    m = P["sub_steps"]
    fn, k, N0, re = P["fn_Hz"], P["k_Nm_rad"], P["N0_N"], P["r_eff_m"]
    # record window: from a little before the (pre+1)-th breakaway to after the last stop
    t_all = out[:, 0]
    t_a = slips[pre][0] - 0.5 * (slips[pre][0] - slips[pre - 1][2])
    t_b = min(t_all[-1], slips[-1][2] + 0.5 * (slips[-1][2] - slips[-2][0]) if len(slips) > 1 else t_all[-1])
    rng = np.random.default_rng(P["noise_seed"] + NUISANCES.index(nuisance))
    # torque cell: 2nd-order low-pass (Butterworth) on the shaft torque at the simulation rate
    fs_sim = 1.0 / P["dt_sim_s"]
    fc = min(P["cell_fc_fn"] * fn, 0.4 * fs_sim)
    b, a = signal.butter(2, fc / (fs_sim / 2))
    Tk = out[:, 3]
    zi = signal.lfilter_zi(b, a) * Tk[0]
    Tcell, _ = signal.lfilter(b, a, Tk, zi=zi)
    idx = np.arange(0, len(out), m)
    idx = idx[(t_all[idx] >= t_a) & (t_all[idx] <= t_b)]
    t = t_all[idx] - t_all[idx[0]]
    T = Tcell[idx].copy()
    n_s = len(t)
    rec_slips = [s for s in slips if t_a <= s[0] <= t_b]
    drops = np.array([s[1] - s[3] for s in rec_slips])
    drop = float(np.mean(drops))
    # sensor noise
    T += P["white_rel"] * drop * rng.standard_normal(n_s) + P["pink_rel"] * drop * _pink(rng, n_s)
    if nuisance == "hum":
        f0 = P["hum_f"]
        ph = rng.uniform(0, 2 * np.pi, 3)
        T += P["hum_rel"] * drop * (np.sin(2 * np.pi * f0 * t + ph[0]) + 0.35 * np.sin(4 * np.pi * f0 * t + ph[1])
                                    + 0.2 * np.sin(6 * np.pi * f0 * t + ph[2]))
    if nuisance == "drift":
        s = t / t[-1]
        T += P["drift_rel"] * drop * (0.7 * s + 0.3 * s ** 2)
    if nuisance == "spikes":
        ns = max(2, int(round(P["spike_frac"] * n_s)))
        where = rng.choice(n_s, ns, replace=False)
        T[where] += rng.choice([-1, 1], ns) * rng.uniform(0.4, 1.5, ns) * drop
        P["spike_idx"] = sorted(int(w) for w in where)
    q_step = 2 * P["adc_range_Nm"] / 2 ** P["adc_bits"]
    if nuisance == "quantisation":
        q_step = P["quant_rel"] * drop
    T = np.round(T / q_step) * q_step
    P["torque_lsb_Nm"] = q_step
    # normal channel
    N = out[idx, 5]
    if P["normal_channel"] == "pressure_kPa":
        Nrec = N / P["piston_area_m2"] / 1e3
        Nrec = Nrec + 0.4 * rng.standard_normal(n_s)
        Nrec = np.round(Nrec / 0.1) * 0.1
        n_name, n_unit, n_nd = "Apply pressure", "kPa", 1
    else:
        Nrec = N + 1.5 * rng.standard_normal(n_s)
        Nrec = np.round(Nrec / 0.05) * 0.05
        n_name, n_unit, n_nd = "Normal force", "N", 2
    # ATF temperature: thermocouple at the sump/inlet (0.1 K, updated at 10 Hz)
    Tatf = P["T_atf_set_C"] + P["atf_ctrl_amp_K"] * np.sin(2 * np.pi / P["atf_ctrl_period_s"] * t_all[idx] + P["atf_ctrl_phase"])
    Tatf = Tatf + 0.3 * (out[idx, 6] - P["T_atf_set_C"]) + 0.05 * rng.standard_normal(n_s)
    hold = np.floor(t * 10.0) / 10.0
    Tatf = np.interp(hold, t, Tatf)
    Tatf = np.round(Tatf, 1)
    # drive channel (only where the bench logs it: stepped drives)
    has_drive = bool(P["drive_steps"])
    if has_drive:
        if P["drive_channel"] == "speed_rpm":
            Dv = np.array([drive(tt)[1] for tt in t_all[idx]]) / RPM
            Dv = np.round(Dv + 0.002 * rng.standard_normal(n_s), 3)
            d_name, d_unit, d_nd = "Speed", "rpm", 3
        else:
            Dv = np.array([drive(tt)[0] for tt in t_all[idx]]) * 180 / math.pi
            Dv = np.round(Dv / (360.0 / 2 ** 14)) * (360.0 / 2 ** 14)   # 14-bit encoder
            d_name, d_unit, d_nd = "Motor angle", "deg", 4
    # ---- export
    fmt = P["format"]
    os.makedirs(outdir, exist_ok=True)
    base = f"{NAME}_{case}_s{seed}_{nuisance}"
    cols = [("Time", "s", t, 6)]
    if fmt == "tab_ms":
        cols = [("Time", "ms", t * 1e3, 3)]
    cols.append(("Torque", {"catman": "N·m", "bench_csv": "N·m", "tab_ms": "Nm", "dewesoft": "Nm"}[fmt], T, 5))
    if has_drive:
        cols.append((d_name, d_unit, Dv, d_nd))
    cols.append((n_name, n_unit, Nrec, n_nd))
    cols.append(("ATF temp" if fmt != "catman" else "ATF temperature", "°C", Tatf, 1))
    rows_data = np.column_stack([c[2] for c in cols])
    nds = [c[3] for c in cols]
    if fmt == "catman":
        path = os.path.join(outdir, base + ".txt")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("catman AP ASCII export\n")
            fh.write(f"File\tLVFA_J2490_{seed:03d}_{case[:4].upper()}.BIN\n")
            fh.write("Comment\tLVFA shudder screen, paper friction material / ATF\n")
            fh.write(f"Sample rate\t{P['fs_Hz']:g} Hz\n")
            fh.write("\t".join(c[0] for c in cols) + "\n")
            fh.write("\t".join(c[1] for c in cols) + "\n")
            for r in rows_data:
                fh.write("\t".join(_fmt_num(x, nd) for x, nd in zip(r, nds)) + "\n")
    elif fmt == "bench_csv":
        path = os.path.join(outdir, base + ".csv")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(",".join(f"{c[0]} [{c[1]}]" for c in cols) + "\n")
            for r in rows_data:
                fh.write(",".join(_fmt_num(x, nd) for x, nd in zip(r, nds)) + "\n")
    elif fmt == "tab_ms":
        path = os.path.join(outdir, base + ".txt")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("\t".join(f"{c[0]} [{c[1]}]" for c in cols) + "\n")
            for r in rows_data:
                fh.write("\t".join(_fmt_num(x, nd) for x, nd in zip(r, nds)) + "\n")
    else:  # dewesoft-like, semicolon + decimal comma
        path = os.path.join(outdir, base + ".csv")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write("Dewesoft data export;" + ";" * (len(cols) - 2) + "\n")
            fh.write(f"Setup file: LVFA_shudder_{seed:02d}.dxs;" + ";" * (len(cols) - 2) + "\n")
            fh.write(f"Sample rate: {P['fs_Hz']:g};" + ";" * (len(cols) - 2) + "\n")
            fh.write(";".join(c[0] for c in cols) + "\n")
            fh.write(";".join(c[1] for c in cols) + "\n")
            for r in rows_data:
                fh.write(";".join(_fmt_num(x, nd, comma=True) for x, nd in zip(r, nds)) + "\n")
    # ---- truth
    k_user = k * (1 + P["k_user_err"])
    args = ["--stiffness", f"{k_user:.4g} N·m/rad"]
    if not has_drive:
        args += ["--v0", f"{P['v0_rpm']:.4g} rpm"]
    fn_given = None
    if P["give_fn"]:
        fn_given = fn * (1 + P["fn_off_rel"]) if nuisance == "fn_off" else fn
        args = ["--fn", f"{fn_given:.4g}"] + args
        fn_given = float(f"{fn_given:.4g}")
    # measured effect sizes on the recorded window
    seg = (out[:, 0] >= t_a) & (out[:, 0] <= t_b)
    o = out[seg]
    fss = _fss(rec_slips)
    meas = {"n_slips": len(rec_slips), "f_ss_Hz": fss, "fn_over_fss": fn / fss, "drop_Nm": drop,
            "drop_over_peak": float(drop / np.mean([s[1] for s in rec_slips])),
            "samples_per_period": P["fs_Hz"] / fn, "duration_s": float(t[-1]),
            "twin_frac_drop": _twin_measure(o, rec_slips, P)}
    mu_ref = lambda Ti: P["mu_k"] * (1 + P["kappa_per_K"] * (Ti - P["T_atf_set_C"])) * N0 * re + \
        P["vogel"]["A_Pas"] * np.exp(P["vogel"]["B_K"] / (Ti + P["vogel"]["C_K"])) * P["v_b_m_s"] / re * \
        math.pi * (P["r_out_m"] ** 4 - P["r_in_m"] ** 4) / 2 / P["h_eff_m"]
    Ti = o[:, 6]
    meas["temp_rise_K"] = float(Ti.max() - Ti.min())
    meas["thermal_mu_change_frac_drop"] = float(abs(mu_ref(Ti.max()) - mu_ref(Ti.min())) / drop)
    n_rec = o[:, 5]
    meas["N_pp_frac"] = float((n_rec.max() - n_rec.min()) / N0)
    if case == "load_variation":
        meas["N_pp_frac_p99"] = float((np.percentile(n_rec, 99.5) - np.percentile(n_rec, 0.5)) / N0)
        meas["self_energising"] = float(P["load_kn_N_rad"] * (P["mu_k"] + P["dmu"]) * re / k)
    if case == "static_ageing":
        meas.update(_ageing_measure(o, rec_slips, P))
    if case == "triggering":
        ft = P["trig_ratio_fn"] * fn
        meas.update({"f_t_Hz": ft, "f_t_over_fn": P["trig_ratio_fn"], "f_t_over_fss": ft / fss,
                     "f_t_over_fss_unforced": ft / P["fss_unforced_Hz"], "trig_amp_frac_N0": P["trig_eps"]})
    if case == "drive_modulation":
        fm = P["mod_ratio_fss"] * P["fss_unforced_Hz"]
        meas.update({"a": P["mod_a"], "fm_Hz": fm, "fm_over_fss": fm / fss,
                     "fm_over_fss_unforced": P["mod_ratio_fss"]})
    P["measured"] = meas
    P["recorded_channels"] = [f"{c[0]} [{c[1]}]" for c in cols]

    def _js(x):
        if isinstance(x, dict):
            return {kk: _js(vv) for kk, vv in x.items()}
        if isinstance(x, (list, tuple)):
            return [_js(vv) for vv in x]
        if isinstance(x, (np.floating, float)):
            return float(x)
        if isinstance(x, (np.integer,)):
            return int(x)
        if isinstance(x, np.bool_):
            return bool(x)
        return x
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance,
            "file": os.path.abspath(path), "args": args, "fn_true": float(fn), "fn_given": fn_given,
            "params": _js(P)}
