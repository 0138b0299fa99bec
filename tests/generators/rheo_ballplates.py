"""Independent generator of "measured" stick-slip records: a ROTATIONAL RHEOMETER'S BALL-ON-THREE-PLATES
TRIBOLOGY CELL driven through a TORSION-SPRING COUPLING (`rheo_ballplates`). Written without reading the
diagnosis (python/, fortran/, tests/test_*.py, tests/benchmarks/, the other generators' code); only numpy/scipy.

Rig
---
The rheometer's motor (position controlled, the drive) turns a torsion-spring coupling (k_theta 0.03-1.2
N m/rad); its other end carries the ball holder (inertia J, the slider) whose 1/2 inch steel ball (r_b = 6.35
mm) is pressed with the normal force F_N (4-30 N) onto three grease-lubricated plates inclined at 45 deg (the
three contacts act at r_b/sqrt 2; friction torque T_f = mu F_N r_b). The plates sit on the rheometer's
normal-force sensor. fn = sqrt(k_theta/J)/2 pi, 6-240 Hz. The 1-DoF equivalent is exact in angle: x = motor
angle - ball angle (the coupling's twist, rad or deg) is the spring's extension, the torque k_theta x the
spring force, the motor angle (or speed) the drive; `--stiffness` is given in N m/rad or N m/deg as the file's
angle unit is (or, for the tribology software's linear export, F = T/R_e, R_e = r_b/sqrt 2, distance R_e phi,
k = k_theta/R_e^2 in N/m).

Friction law (sliding, w = ball's angular sliding speed > 0)
-----------------------------------------------------------
    T_f = r_b F_N [ mu_k + Delta sech(w/w_s) + c_v Psi(w(t - tau_d)) ],
    Psi(u) = (u/w_c) (1 + (u/w_c)^a)^((n-1)/a)           (Carreau-Yasuda shear-thinning film term)
mu_k 0.07-0.13; a sech weakening Delta 0.20-0.34 mu_k over w_s 0.25-0.6 of the slip-speed scale; the grease's
base-oil film term, shear-thinning (n 0.35-0.7, a 1.5-2.5), c_v 0.08-0.2 Delta; a static level mu_s =
mu(0+) + delta_s (delta_s 0.06-0.13 mu_k) times a plate texture along the ball's angle (1 + eps chi(s), peak
scatter 0.4-1.1 % of the drop). In every case but `twin_branch` tau_d = 0: the law is single-valued in w.

Stick handling
--------------
Exact and in closed form: in stick the ball does not move, x(t) = phi(t) - s is known analytically (the motor's
piecewise-linear speed profile or its sinusoidal modulation), the static limit T_s(t) = r_b F_N(t, x, s) mu_s
(1 + ageing)(1 + texture) too; the breakaway is the first zero of k x(t) - T_s(t), found by a vectorised scan
(Tn/30, 1/12 of a shaker period) and Ridders' method. The arrest is the step length at which the sliding speed
reaches zero, found by Anderson-Bjorck regula falsi on the integrator's step length (the step retaken to it);
the slider then sticks unless the spring already exceeds the static limit (it slides on). No band, no
regularisation, no bristles.

Integrator
----------
Own fixed-step GENERALIZED-ALPHA (Chung-Hulbert 1993; rho_inf 0.7-0.9, h = Tn/300..Tn/420, 1/40 of a shaker
period) on J s'' = k (phi(t) - s) - T_f, a scalar Newton iteration on the end-of-step acceleration with the
friction's analytic derivatives; the friction's direction is held within a step. The delayed film term is a
DELAY DIFFERENTIAL EQUATION: w(t - tau_d) is read from the stored history by linear interpolation (tau_d >= 20
h). Positions between nodes by cubic Hermite (s, w). Step h/4 moves the median drop by <= 1.3e-4, the slip
frequency by <= 4e-5 and the twin by <= 1e-4 (none, twin, load seeds); triggering records' slip sequences
follow the shaker's phase, so there h/4 changes the median drop by 2 %.

Sensors and noise (the record is never the state)
-------------------------------------------------
Torque flange: 3rd-order Butterworth at 8-25 fn (<= 0.38 fs), an odd cubic nonlinearity (+-0.3 % of full
scale), Student-t white noise (3-6 degrees of freedom, 0.1-0.35 % of the drop) plus an AR(2) resonant
coloured noise (0.05-0.2 %). Twist: two sin/cos encoders (2048-8192 lines, 4096-fold interpolation), each with
an interpolation error periodic in its own angle, no low-pass (aliasing as sampled), Student-t jitter 0.08-0.25
% of the slip angle. Normal force: one pole at 15-40 fn, Gaussian 0.03-0.12 % of F_N, 1 mN resolution. Motor:
22-bit encoder angle (absolute offset) or the controller's speed readout (0.2 % noise). Plate temperature
(Peltier, slow wander) and, on the logger, an acoustic-emission RMS channel with a burst at every breakaway.
A fine grid at 4x the record's rate is filtered and decimated; 20-100 samples per natural period (coarse 10-15).

The six cases (each a physical departure; the rest as in `none`)
---------------------------------------------------------------
- none: constant load, constant motor speed, single-valued law, no ageing.
- load_variation: (even seeds) a BALL-RAMP coupling: the twist lifts the ball holder against the stiff normal
  path, F_N = N0 (1 + g (x - x_m)/dx0), g calibrated by secant on pilots to 14-26 % p-p (rising on seeds 0-23; a
  falling ramp, which stiffens the slips, is drawn only where the target is below 0.3 D/T_s); (odd seeds) a WAVY PLATE surface under the ball's track with the gap
  held, F_N = N0 (1 + g sin(2 pi (s - s0)/lambda)), lambda 3-8 slip lengths, 2g 12-28 % p-p. Its law's weakening
  is 1.35x and its static excess 1.5x deeper, so the load's swing in the static level stays within the drop.
  The normal force is recorded on 7 of 8 seeds (not seed 3 mod 8).
- twin_branch: a transport delay in the film term (tau_d 0.08-0.14 Tn: the lubricant carrying the film stress
  arrives from the inlet meniscus a fixed time later). A delayed strengthening term is lower while the slip
  accelerates and higher while it decelerates: c_v calibrated by secant on pilot runs to a twin of +12.5..+21 %.
- static_ageing: the grease's thickener network rebuilds at rest as a power law, T_s = T_s0 (1 + beta
  (t_stick/theta)^p), p 0.3-0.5, theta 1-4 Tn, broken down by each slip; even seeds: motor speed steps 4-8x (2-3
  slow blocks of 3-5 slips between fast blocks of 5-8), odd seeds: 5-8 holds (motor stopped 2-7 sticks long);
  beta calibrated on the record's own run to +9.5..+16.5 % of the drop; drive always recorded (angle or speed).
- triggering: a piezo shaker under the plate holder, F_N = N0 (1 + A sin(2 pi f_t t)), A 3-7.5 %, f_t 2.5-5 fn,
  recorded in the normal channel; the static excess is raised to >= 2.5 A mu_s (the shaker triggers
  breakaways instead of chopping slips into steps at its troughs); f_t re-chosen (half-integer multiples of the
  measured f_ss, up to 7 runs) until the record's f_t/f_ss is >= 0.2 from an integer.
- drive_modulation: the motor speed Omega0 (1 + a sin(2 pi fm t + psi)), a 0.22-0.42, fm 0.2-0.38 of the
  pilot's f_ss (re-chosen if the record's fm/f_ss leaves 0.17-0.43); no drive column, `--v0` the mean speed.

Record formats (three instrument exports, UTF-8)
------------------------------------------------
1. Rheometer raw-data export (.txt, TAB): `Project:`/`Test:`/`Result:`/`Measuring System:`/`Accessory:`/
   `Interval and data points:`/`Sampling rate:`/`Interval data:` preamble, a blank line, a names row
   (`Point No.`, `Time`, `Torque` | `Deflection Angle` | `Friction Force`, `Normal Force`, `Motor Angle` |
   `Motor Speed` | `Sliding Distance` | `Sliding Speed`, `Temperature`) and a `[unit]` row (`[s]`, `[N·m]`,
   `[deg]`/`[rad]`, `[N]`/`[mN]`, `[mm]`, `[deg/s]`, `[mm/s]`, `[°C]`; empty under `Point No.`); a decimal comma
   on about a third.
2. Digital oscilloscope CSV (.csv, CRLF): `Model,`, `Firmware Version,`, ..., `Sample Interval,`, `Record
   Length,`, `Probe Attenuation,`, `Vertical Units,`, `Label,` lines, a blank line, `TIME (s),CH1 Torque
   (N·m)[,CH2 Normal force (N)][,CH3 Motor speed (deg/s|rad/s)]`; time from a negative pre-trigger; %.6e.
3. Data-logger CSV (.csv/.dat, CRLF, quoted fields): a logger preamble (start time, sampling interval in us,
   number of samples, a channel table), a blank line, `"No.","Time[s]"|"Time[ms]","Torque[N·m]"|"Spring
   deflection[deg|rad]"[,"Normal load[N]"][,"Drive angle[..]"|"Drive speed[../s]"],"Oil temp[degC]","AE
   RMS[mV]"`: a sample counter and two channels with no role; semicolons with a decimal comma on about a third.
Quantities: torque (N m, `--stiffness` in N m/deg or N m/rad), the coupling's twist (deg or rad; no
`--stiffness`), or the tribology software's linear friction force (N/mN, `--stiffness` N/m, drive in mm or
mm/s). `--v0` (file's angle unit/s, or mm/s) whenever no drive column is written.

--fn policy: given (4 significant digits) on 7 of 8 seeds of each case, omitted on seed 5 (none), 2 (load), 7
(twin), 4 (ageing), 1 (modulation) mod 8, never for triggering or `fn_off`; `fn_off` gives fn (1 +- 0.05).
Nuisances act on the written channels only (the physics has its own RNG): hum 50/60 Hz or a harmonic (1-5 % of
each channel's spread, plus a 3rd harmonic), drift (an exponential sensor settling, 1.2-3 % of the drop),
spikes (0.05-0.5 % of samples, 5-30 % of the drop), quantisation (ADC step 0.2-1 % of the drop), coarse
(10-15 samples per Tn), fn_off.

Measured on the ground truth (true friction torque against the true sliding speed, decelerating minus
accelerating branch at equal speed over 10-90 % of each slip's peak speed, median over the slips, over that
slip's drop D; peak growth = median peak of the long sticks less that of the short ones, over the median drop),
seeds 0-23 (all 144 records ran, 41 s):
- none: twin -3.4e-5..0 (the law is exactly single-valued); a 1-DoF reading of ideal samples at 60 per Tn
  (x'' by central differences) -3.6..-1.5 % (the static-kinetic step smeared by the differencing); no ageing
  in the law: on an unrecorded probe run with a 6x stepped drive the peak changes -0.9..+1.1 % of the drop
  over 3.8-5.9x stick times; peak sd 0.4-1.1 % of the drop (texture); load and drive exactly constant.
- load_variation: N p-p 14.2-25.3 % of N0; F against w reads -0.26..+0.12 of the drop, F/N against w 0
  (|.| < 4e-5); the wavy track scatters the peaks (sd up to 0.28 of the drop).
- twin_branch: +0.125..+0.216 (1-DoF reading of ideal samples +0.10..+0.20).
- static_ageing: +0.093..+0.154 of the drop over stick times 4.5-11x apart; twin 0.
- triggering: A 3.0-7.4 % (N p-p 6.1-14.8 %), f_t 2.7-5.0 fn, the record's f_t/f_ss 11.5-32.2, 0.22-0.49 from
  an integer; F/N twin 0 (F against w reads -0.01..+0.19: the shaker's load moves the friction within a slip).
- drive_modulation: a 0.22-0.41, the record's fm/f_ss 0.21-0.39; twin 0, peak change -1.2..+1.3 %.
Records: 18-59 slips, fn/f_ss 2.9-13.5 (13-46 on stepped/hold records), 0.4-111 s, 1000-120000 rows.

Self-check (`python rheo_ballplates.py [OUTDIR]`: seeds 0-7 of every case, nuisance NUISANCES[seed % 7];
every file read back by its own loader, finite, time increasing; json.dumps(allow_nan=False); 16 s):

    (case, seed, nuisance, fn in Hz, fn/f_ss, slips, samples per Tn, export, quantity, drive column, normal
    column N0/N1 | the measured sizes, fractions of the drop D; N p-p and A fractions of N0)
    none             0 clean        fn  17.6 fn/fss  6.41 slips 38 spp  85.2 scope  torque none     N0 | twin -0.00000 (1-DoF -0.015), probe ageing -0.0065 over 4.8x, peak sd 0.0087
    none             1 hum          fn   7.1 fn/fss  5.70 slips 35 spp  40.5 rheo   torque none     N1 | twin -0.00002 (1-DoF -0.031), probe ageing +0.0038 over 4.8x, peak sd 0.0074
    none             2 drift        fn  17.5 fn/fss  5.52 slips 40 spp  57.6 scope  torque none     N0 | twin -0.00002 (1-DoF -0.031), probe ageing +0.0063 over 4.8x, peak sd 0.0082
    none             3 spikes       fn  20.7 fn/fss  3.61 slips 21 spp  54.8 logger twist  position N0 | twin -0.00001 (1-DoF -0.016), probe ageing +0.0050 over 5.7x, peak sd 0.0074
    none             4 quantisation fn   6.0 fn/fss  6.07 slips 38 spp  21.5 scope  torque speed    N0 | twin -0.00002 (1-DoF -0.028), probe ageing +0.0071 over 5.0x, peak sd 0.0087
    none             5 coarse       fn  78.5 fn/fss  6.88 slips 29 spp  13.3 rheo   torque none     N1 | twin -0.00001 (1-DoF -0.019), probe ageing +0.0108 over 4.8x, peak sd 0.0092
    none             6 fn_off       fn 166.0 fn/fss  4.02 slips 39 spp  64.4 rheo   twist  none     N1 | twin -0.00002 (1-DoF -0.030), probe ageing -0.0044 over 5.2x, peak sd 0.0083
    none             7 clean        fn 102.7 fn/fss  5.72 slips 29 spp  59.2 logger twist  none     N1 | twin -0.00003 (1-DoF -0.036), probe ageing +0.0103 over 5.0x, peak sd 0.0040
    load_variation   0 clean        fn  60.3 fn/fss 11.24 slips 30 spp  83.7 scope  torque none     N1 | N pp 0.221 (ball g +0.120), twin F -0.209, F/N -0.00001
    load_variation   1 hum          fn 234.9 fn/fss  7.43 slips 38 spp  65.3 logger twist  speed    N1 | N pp 0.178 (wavy g +0.089), twin F +0.077, F/N -0.00002
    load_variation   2 drift        fn  66.7 fn/fss 10.47 slips 26 spp  30.0 rheo   linear none     N1 | N pp 0.164 (ball g +0.117), twin F -0.151, F/N -0.00001
    load_variation   3 spikes       fn  59.3 fn/fss 10.84 slips 20 spp  67.6 scope  torque none     N0 | N pp 0.233 (wavy g +0.116), twin F +0.061, F/N -0.00001
    load_variation   4 quantisation fn 106.9 fn/fss 11.42 slips 41 spp  67.1 logger twist  position N1 | N pp 0.151 (ball g +0.073), twin F -0.207, F/N -0.00001
    load_variation   5 coarse       fn  67.3 fn/fss  3.39 slips 23 spp  13.1 rheo   torque speed    N1 | N pp 0.236 (wavy g +0.118), twin F +0.049, F/N -0.00002
    load_variation   6 fn_off       fn  19.7 fn/fss 12.48 slips 26 spp  98.4 scope  torque speed    N1 | N pp 0.176 (ball g +0.121), twin F -0.167, F/N -0.00000
    load_variation   7 clean        fn  21.7 fn/fss  8.45 slips 18 spp  49.3 scope  torque none     N1 | N pp 0.221 (wavy g +0.110), twin F -0.007, F/N +0.00000
    twin_branch      0 clean        fn 101.6 fn/fss  5.11 slips 39 spp  29.5 rheo   torque none     N1 | twin +0.1625 (1-DoF +0.135), delay 0.140 Tn
    twin_branch      1 hum          fn   7.8 fn/fss  3.92 slips 31 spp  80.1 logger torque none     N0 | twin +0.2162 (1-DoF +0.197), delay 0.088 Tn
    twin_branch      2 drift        fn  11.8 fn/fss  4.83 slips 23 spp  97.0 scope  torque speed    N0 | twin +0.1401 (1-DoF +0.100), delay 0.129 Tn
    twin_branch      3 spikes       fn  92.4 fn/fss  4.60 slips 35 spp  35.9 logger twist  position N0 | twin +0.1863 (1-DoF +0.168), delay 0.083 Tn
    twin_branch      4 quantisation fn 210.5 fn/fss  4.34 slips 19 spp  29.0 scope  torque speed    N1 | twin +0.1714 (1-DoF +0.150), delay 0.133 Tn
    twin_branch      5 coarse       fn  46.7 fn/fss  6.76 slips 28 spp  13.6 rheo   torque none     N1 | twin +0.2054 (1-DoF +0.186), delay 0.099 Tn
    twin_branch      6 fn_off       fn   6.2 fn/fss  4.30 slips 21 spp  97.3 scope  torque speed    N1 | twin +0.1424 (1-DoF +0.123), delay 0.117 Tn
    twin_branch      7 clean        fn  23.8 fn/fss  3.63 slips 38 spp  61.5 rheo   linear none     N1 | twin +0.2164 (1-DoF +0.197), delay 0.098 Tn
    static_ageing    0 clean        fn 100.7 fn/fss 40.55 slips 38 spp  28.2 logger twist  speed    N0 | growth +0.1075 over 9.9x (steps), twin -0.00001
    static_ageing    1 hum          fn  36.5 fn/fss 14.45 slips 29 spp  96.7 logger torque position N0 | growth +0.0970 over 4.5x (holds), twin +0.00000
    static_ageing    2 drift        fn   9.4 fn/fss 14.53 slips 24 spp  75.8 rheo   linear position N1 | growth +0.1167 over 8.7x (steps), twin -0.00001
    static_ageing    3 spikes       fn  17.5 fn/fss 32.98 slips 25 spp  59.1 logger torque speed    N0 | growth +0.1119 over 5.9x (holds), twin -0.00000
    static_ageing    4 quantisation fn  20.9 fn/fss 45.53 slips 24 spp  50.9 rheo   torque speed    N1 | growth +0.1428 over 11.2x (steps), twin -0.00001
    static_ageing    5 coarse       fn  15.2 fn/fss 16.36 slips 26 spp  12.1 rheo   linear position N1 | growth +0.1070 over 5.9x (holds), twin -0.00001
    static_ageing    6 fn_off       fn  99.0 fn/fss 39.12 slips 23 spp  99.2 scope  torque speed    N0 | growth +0.1430 over 8.7x (steps), twin -0.00001
    static_ageing    7 clean        fn 139.9 fn/fss 27.74 slips 25 spp  66.4 scope  torque speed    N0 | growth +0.1292 over 5.1x (holds), twin -0.00000
    triggering       0 clean        fn  21.2 fn/fss  4.71 slips 57 spp  25.6 logger twist  position N1 | A 0.051, ft/fn 4.13, ft/fss 19.48 (0.48 off), N pp 0.101
    triggering       1 hum          fn   9.7 fn/fss  3.73 slips 30 spp  88.7 logger twist  position N1 | A 0.068, ft/fn 3.11, ft/fss 11.58 (0.42 off), N pp 0.137
    triggering       2 drift        fn  13.0 fn/fss  5.97 slips 40 spp  73.5 scope  torque speed    N1 | A 0.053, ft/fn 3.79, ft/fss 22.67 (0.33 off), N pp 0.105
    triggering       3 spikes       fn  80.9 fn/fss  5.46 slips 41 spp  76.5 scope  torque none     N1 | A 0.072, ft/fn 4.70, ft/fss 25.67 (0.33 off), N pp 0.144
    triggering       4 quantisation fn  22.6 fn/fss  4.51 slips 37 spp  45.4 rheo   linear none     N1 | A 0.058, ft/fn 5.00, ft/fss 22.53 (0.47 off), N pp 0.116
    triggering       5 coarse       fn  25.8 fn/fss  4.20 slips 29 spp  12.8 rheo   torque none     N1 | A 0.036, ft/fn 4.86, ft/fss 20.40 (0.40 off), N pp 0.072
    triggering       6 fn_off       fn  83.3 fn/fss  3.02 slips 50 spp  54.8 scope  torque none     N1 | A 0.050, ft/fn 3.81, ft/fss 11.53 (0.47 off), N pp 0.100
    triggering       7 clean        fn 137.3 fn/fss  4.87 slips 53 spp  26.1 rheo   linear position N1 | A 0.059, ft/fn 2.96, ft/fss 14.40 (0.40 off), N pp 0.118
    drive_modulation 0 clean        fn 110.7 fn/fss  6.79 slips 20 spp  98.5 scope  torque none     N1 | a 0.252, fm/fss 0.207, twin -0.00002
    drive_modulation 1 hum          fn  26.4 fn/fss  5.42 slips 38 spp  39.2 rheo   torque none     N1 | a 0.248, fm/fss 0.284, twin -0.00001
    drive_modulation 2 drift        fn  11.1 fn/fss  6.68 slips 20 spp  68.3 logger torque none     N0 | a 0.339, fm/fss 0.232, twin -0.00003
    drive_modulation 3 spikes       fn  33.3 fn/fss  4.86 slips 37 spp  25.8 rheo   torque none     N1 | a 0.411, fm/fss 0.384, twin -0.00001
    drive_modulation 4 quantisation fn  41.5 fn/fss  3.73 slips 27 spp  61.2 scope  torque none     N1 | a 0.367, fm/fss 0.238, twin -0.00000
    drive_modulation 5 coarse       fn 230.9 fn/fss  6.49 slips 20 spp  10.0 rheo   twist  none     N1 | a 0.251, fm/fss 0.269, twin -0.00001
    drive_modulation 6 fn_off       fn   7.7 fn/fss  4.57 slips 27 spp  98.6 logger twist  none     N0 | a 0.262, fm/fss 0.356, twin -0.00001
    drive_modulation 7 clean        fn 108.6 fn/fss  4.26 slips 37 spp  70.8 rheo   linear none     N1 | a 0.366, fm/fss 0.276, twin -0.00001
"""
from __future__ import annotations

import bisect
import json
import math
import os
import sys
import zlib

import numpy as np
from scipy import optimize, signal
from scipy.interpolate import CubicHermiteSpline

NAME = "rheo_ballplates"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")

R_BALL = 6.35e-3            # ball radius (a 1/2 inch ball), m
R_EFF = R_BALL / math.sqrt(2.0)   # lever arm of the three contacts (plates at 45 deg), m
_CRC = zlib.crc32(NAME.encode())
_OMIT_FN = {"none": 5, "load_variation": 2, "twin_branch": 7, "static_ageing": 4,
            "triggering": None, "drive_modulation": 1}


# ----------------------------------------------------------------------------------------------
# the drive: the rheometer motor's angle phi(t), a piecewise-linear speed profile or a modulated one
# ----------------------------------------------------------------------------------------------
class _Drive:
    def __init__(self, tk=None, wk=None, mod=None):
        self.mod = mod
        if mod is None:
            self.tk = [float(v) for v in tk]
            self.wk = [float(v) for v in wk]
            ck = [0.0]
            for i in range(1, len(self.tk)):
                ck.append(ck[-1] + 0.5 * (self.wk[i] + self.wk[i - 1]) * (self.tk[i] - self.tk[i - 1]))
            self.ck = ck
            self.tka = np.array(self.tk)
            self.wka = np.array(self.wk)
            self.cka = np.array(ck)

    def phi1(self, t):
        if self.mod is not None:
            om0, a, fm, psi = self.mod
            w = 2 * math.pi * fm
            return om0 * (t - a / w * (math.cos(w * t + psi) - math.cos(psi)))
        i = bisect.bisect_right(self.tk, t) - 1
        if i < 0:
            i = 0
        tau = t - self.tk[i]
        sl = (self.wk[i + 1] - self.wk[i]) / (self.tk[i + 1] - self.tk[i]) if i < len(self.tk) - 1 else 0.0
        return self.ck[i] + self.wk[i] * tau + 0.5 * sl * tau * tau

    def phi(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            om0, a, fm, psi = self.mod
            w = 2 * math.pi * fm
            return om0 * (t - a / w * (np.cos(w * t + psi) - math.cos(psi)))
        n = len(self.tk)
        i = np.clip(np.searchsorted(self.tka, t, "right") - 1, 0, n - 1)
        tau = t - self.tka[i]
        ip = np.minimum(i + 1, n - 1)
        dt = np.where(ip > i, self.tka[ip] - self.tka[i], 1.0)
        sl = np.where(ip > i, (self.wka[ip] - self.wka[i]) / dt, 0.0)
        return self.cka[i] + self.wka[i] * tau + 0.5 * sl * tau * tau

    def om(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            om0, a, fm, psi = self.mod
            return om0 * (1 + a * np.sin(2 * math.pi * fm * t + psi))
        return np.interp(t, self.tka, self.wka)

    def domdt(self, t):
        t = np.asarray(t, float)
        if self.mod is not None:
            om0, a, fm, psi = self.mod
            w = 2 * math.pi * fm
            return om0 * a * w * np.cos(w * t + psi)
        n = len(self.tk)
        if n < 2:
            return np.zeros_like(t)
        i = np.clip(np.searchsorted(self.tka, t, "right") - 1, 0, n - 2)
        sl = (self.wka[i + 1] - self.wka[i]) / (self.tka[i + 1] - self.tka[i])
        return np.where((t >= self.tka[0]) & (t < self.tka[-1]), sl, 0.0)


# ----------------------------------------------------------------------------------------------
# the physics: generalized-alpha slips, closed-form sticks, a delay in the film term
# ----------------------------------------------------------------------------------------------
def _simulate(P, drive, t_end, max_events=10 ** 9):
    k = P["k"]; J = P["J"]; rb = R_BALL
    muk = P["muk"]; Dl = P["Dl"]; ws = P["ws"]; mus = P["mus"]
    cv = P["cv"]; wc = P["wc"]; ncy = P["ncy"]; acy = P["acy"]; taud = P["taud"]
    kind, lp = P["load"]
    N0 = P["N0"]
    beta = P.get("beta", 0.0); theta = P.get("theta", 1.0); pag = P.get("pag", 0.5)
    eps = P.get("eps", 0.0)
    tex_k = np.asarray(P.get("tex_k", [0.0])); tex_p = np.asarray(P.get("tex_p", [0.0]))
    tex_a = np.asarray(P.get("tex_a", [0.0]))
    Tn = 1.0 / P["fn"]
    rho = P["rho"]
    am = (2 * rho - 1) / (rho + 1)
    af = rho / (rho + 1)
    gam = 0.5 - am + af
    bet = 0.25 * (1 - am + af) ** 2
    h0 = Tn / P["nh"]
    if kind == "ramp":
        g, xm, dx = lp
    elif kind == "wavy":
        g, kap, s0w = lp
    elif kind == "shaker":
        A, ft, psit = lp
        wt = 2 * math.pi * ft
        h0 = min(h0, 1.0 / (40.0 * ft))

    def Nfun(t, s, x):
        if kind == "const":
            return N0, 0.0
        if kind == "ramp":
            return N0 * (1 + g * (x - xm) / dx), -N0 * g / dx
        if kind == "wavy":
            return N0 * (1 + g * math.sin(kap * (s - s0w))), N0 * g * kap * math.cos(kap * (s - s0w))
        return N0 * (1 + A * math.sin(wt * t + psit)), 0.0

    def Nvec(t, s, x):
        t = np.asarray(t, float)
        if kind == "const":
            return np.full(t.shape, N0)
        if kind == "ramp":
            return N0 * (1 + g * (x - xm) / dx)
        if kind == "wavy":
            return N0 * (1 + g * np.sin(kap * (s - s0w)))
        return N0 * (1 + A * np.sin(wt * t + psit))

    def texf(s):
        if eps == 0.0:
            return 0.0
        return float(np.sum(tex_a * np.cos(tex_k * s + tex_p)))

    pw = (ncy - 1.0) / acy

    def Psi(w):
        q = w / wc
        return q * (1 + abs(q) ** acy) ** pw

    def dPsi(w):
        aq = abs(w / wc) ** acy
        return (1 + aq) ** (pw - 1) * (1 + ncy * aq) / wc

    Ht = [-1.0, 0.0]
    Hw = [0.0, 0.0]
    cur = [0]

    def wdel(t):
        tq = t - taud
        n = len(Ht)
        if tq >= Ht[-1]:
            return Hw[-1]
        i = min(cur[0], n - 2)
        while i > 0 and Ht[i] > tq:
            i -= 1
        while i < n - 2 and Ht[i + 1] <= tq:
            i += 1
        cur[0] = i
        t0 = Ht[i]
        t1 = Ht[i + 1]
        return Hw[i] + (Hw[i + 1] - Hw[i]) * (tq - t0) / (t1 - t0)

    def fric(t, s, x, w, wd):
        N, dNs = Nfun(t, s, x)
        u = w / ws
        if abs(u) > 300:
            se = 0.0
            th = 1.0 if u > 0 else -1.0
        else:
            se = 1.0 / math.cosh(u)
            th = math.tanh(u)
        mu = muk + Dl * se
        dmu = -Dl * se * th / ws
        if cv != 0.0:
            if taud > 0:
                mu += cv * Psi(wd)
            else:
                mu += cv * Psi(w)
                dmu += cv * dPsi(w)
        return rb * N * mu, rb * N * dmu, rb * mu * dNs, N

    def gvec(tt, s, ta):
        x = drive.phi(tt) - s
        N = Nvec(tt, s, x)
        if beta > 0:
            f = 1.0 + beta * (np.maximum(tt - ta, 0.0) / theta) ** pag
        else:
            f = 1.0
        return k * x - rb * N * mus * f * (1.0 + eps * texf(s))

    def gen_alpha(t0, s0, w0, a0, G0, h):
        t1 = t0 + h
        ph1 = drive.phi1(t1)
        wd1 = wdel(t1) if taud > 0 else 0.0
        a1 = a0
        hh = h * h
        for _ in range(40):
            s1 = s0 + h * w0 + hh * ((0.5 - bet) * a0 + bet * a1)
            w1 = w0 + h * ((1 - gam) * a0 + gam * a1)
            x1 = ph1 - s1
            Tf, dTw, dTs, N1 = fric(t1, s1, x1, w1, wd1)
            R = J * ((1 - am) * a1 + am * a0) - ((1 - af) * (k * x1 - Tf) + af * G0)
            dR = J * (1 - am) + (1 - af) * ((k + dTs) * bet * hh + dTw * gam * h)
            da = -R / dR
            a1 += da
            if abs(da) <= 1e-11 * (abs(a1) + abs(a0)) + 1e-300:
                break
        s1 = s0 + h * w0 + hh * ((0.5 - bet) * a0 + bet * a1)
        w1 = w0 + h * ((1 - gam) * a0 + gam * a1)
        x1 = ph1 - s1
        Tf, dTw, dTs, N1 = fric(t1, s1, x1, w1, wd1)
        return t1, s1, w1, a1, k * x1 - Tf, Tf, N1

    t = 0.0
    s = 0.0
    ta = 0.0
    nodes_t = [0.0]; nodes_s = [0.0]; nodes_w = [0.0]
    events = []
    slips = []
    dts = Tn / 30.0
    if kind == "shaker":
        dts = min(dts, 1.0 / (12.0 * ft))
    t_scan = 0.0
    ok = True
    while t < t_end:
        # ---- stick: the slider holds still; find where the spring's torque meets the static limit
        tb = None
        if gvec(np.array([t_scan]), s, ta)[0] >= 0:
            tb = t_scan
        else:
            tcur = t_scan
            while tcur < t_end + 60 * Tn:
                tt = tcur + dts * np.arange(1, 257)
                gg = gvec(tt, s, ta)
                idx = np.nonzero(gg >= 0)[0]
                if len(idx):
                    j = idx[0]
                    lo = tt[j - 1] if j > 0 else tcur
                    hi = tt[j]
                    tb = optimize.ridder(lambda z: gvec(np.array([z]), s, ta)[0], lo, hi,
                                         xtol=1e-13 * max(1.0, hi), rtol=4e-15)
                    break
                tcur = tt[-1]
                if tcur > t_end:
                    break
        if tb is None:
            nodes_t.append(max(t_end, t + 1e-9)); nodes_s.append(s); nodes_w.append(0.0)
            break
        if tb > nodes_t[-1]:
            nodes_t.append(tb); nodes_s.append(s); nodes_w.append(0.0)
            Ht.append(tb); Hw.append(0.0)
        xb = drive.phi1(tb) - s
        age = tb - ta
        Nb = Nfun(tb, s, xb)[0]
        # ---- slip
        t = tb
        wd0 = wdel(t) if taud > 0 else 0.0
        Tf0 = fric(t, s, xb, 0.0, wd0)[0]
        a = (k * xb - Tf0) / J
        G = k * xb - Tf0
        w = 0.0
        st = [t]; ss = [s]; sw = [0.0]; sT = [Tf0]; sN = [Nb]
        t_slip0 = t
        while True:
            t1, s1, w1, a1, G1, Tf1, N1 = gen_alpha(t, s, w, a, G, h0)
            if w1 <= 0.0 and w > 0.0:
                # the arrest: the step length that brings the sliding speed to zero (Anderson-Bjorck)
                hl, fl = 0.0, w
                hr, fr = h0, w1
                tm = (t1, s1, w1, a1, G1, Tf1, N1)
                for _ in range(80):
                    hm = hr - fr * (hr - hl) / (fr - fl)
                    if not (0.0 < hm < h0):
                        hm = 0.5 * (hl + hr)
                    tm = gen_alpha(t, s, w, a, G, hm)
                    fm = tm[2]
                    if abs(fm) <= 1e-12 * abs(w) or abs(hr - hl) <= 1e-12 * h0:
                        break
                    if fm * fr < 0:
                        hl, fl = hr, fr
                        hr, fr = hm, fm
                    else:
                        m = 1.0 - fm / fr
                        fl *= m if m > 0 else 0.5
                        hr, fr = hm, fm
                t1, s1, w1, a1, G1, Tf1, N1 = tm
                st.append(t1); ss.append(s1); sw.append(0.0); sT.append(Tf1); sN.append(N1)
                Ht.append(t1); Hw.append(0.0)
                t, s, w = t1, s1, 0.0
                xa = drive.phi1(t) - s
                t_scan = t
                if gvec(np.array([t]), s, t)[0] >= 0:
                    wd0 = wdel(t) if taud > 0 else 0.0
                    Tf0 = fric(t, s, xa, 0.0, wd0)[0]
                    a = (k * xa - Tf0) / J
                    G = k * xa - Tf0
                    if a > 0:
                        continue
                    t_scan = t + taud
                break
            st.append(t1); ss.append(s1); sw.append(w1); sT.append(Tf1); sN.append(N1)
            Ht.append(t1); Hw.append(w1)
            t, s, w, a, G = t1, s1, w1, a1, G1
            if t - t_slip0 > 40 * Tn:
                ok = False
                break
        nodes_t.extend(st[1:]); nodes_s.extend(ss[1:]); nodes_w.extend(sw[1:])
        xa = drive.phi1(t) - s
        events.append(dict(tb=tb, xb=xb, Nb=Nb, age=age, ta=t, xa=xa))
        slips.append((np.array(st), np.array(sw), np.array(sT), np.array(sN)))
        ta = t
        if not ok or len(events) >= max_events:
            break
    nt = np.array(nodes_t)
    keep = np.concatenate([[True], np.diff(nt) > 0])
    return dict(t=nt[keep], s=np.array(nodes_s)[keep], w=np.array(nodes_w)[keep],
                events=events, slips=slips, ok=ok, h=h0)


def _load_vec(P, t, s, x):
    kind, lp = P["load"]
    N0 = P["N0"]
    if kind == "const":
        return np.full(np.shape(t), N0)
    if kind == "ramp":
        g, xm, dx = lp
        return N0 * (1 + g * (x - xm) / dx)
    if kind == "wavy":
        g, kap, s0w = lp
        return N0 * (1 + g * np.sin(kap * (s - s0w)))
    A, ft, psit = lp
    return N0 * (1 + A * np.sin(2 * math.pi * ft * t + psit))


# ----------------------------------------------------------------------------------------------
# ground-truth measurements
# ----------------------------------------------------------------------------------------------
def _window_events(sim, t0, t1):
    ev = sim["events"]
    return [i for i, e in enumerate(ev) if e["tb"] >= t0 and e["ta"] <= t1]


def _fss(sim, idx):
    tb = np.array([sim["events"][i]["tb"] for i in idx])
    if len(tb) < 3:
        return float("nan")
    return (len(tb) - 1) / (tb[-1] - tb[0])


def _drops(P, sim, idx):
    return np.array([P["k"] * (sim["events"][i]["xb"] - sim["events"][i]["xa"]) for i in idx])


def _twin(P, sim, idx, per_load=False):
    """decelerating minus accelerating branch of the true friction at equal true sliding speed,
    10-90 % of each slip's peak speed, over that slip's drop; median over the slips"""
    out = []
    for i in idx:
        st, sw, sT, sN = sim["slips"][i]
        e = sim["events"][i]
        D = P["k"] * (e["xb"] - e["xa"])
        if len(sw) < 8 or D <= 0:
            continue
        y = sT / sN * P["N0"] if per_load else sT
        ip = int(np.argmax(sw))
        wp = sw[ip]
        if ip < 3 or ip > len(sw) - 4:
            continue
        u = wp * np.linspace(0.1, 0.9, 33)
        wa, ya = sw[:ip + 1], y[:ip + 1]
        wd, yd = sw[ip:][::-1], y[ip:][::-1]
        oa = np.argsort(wa, kind="stable")
        od = np.argsort(wd, kind="stable")
        Ta = np.interp(u, wa[oa], ya[oa])
        Td = np.interp(u, wd[od], yd[od])
        out.append(float(np.mean(Td - Ta) / D))
    return float(np.median(out)) if out else float("nan")


def _ageing(P, sim, idx):
    """peak growth with the stick time, over the median drop: the long sticks' median peak less the
    short sticks' (split at the geometric mean of the 10th and 90th percentile stick times; thirds
    when they are within 2x); and the two groups' median stick-time ratio"""
    ev = sim["events"]
    age = np.array([ev[i]["age"] for i in idx])
    pk = np.array([P["k"] * ev[i]["xb"] / ev[i]["Nb"] * P["N0"] for i in idx])
    if len(age) < 6:
        return float("nan"), float("nan")
    D = np.median(_drops(P, sim, idx))
    p10, p90 = np.percentile(age, 10), np.percentile(age, 90)
    if p90 >= 2 * p10:
        cut = math.sqrt(p10 * p90)
        lo, hi = age <= cut, age > cut
    else:
        o = np.argsort(age)
        n3 = max(2, len(o) // 3)
        lo = np.zeros(len(age), bool); lo[o[:n3]] = True
        hi = np.zeros(len(age), bool); hi[o[-n3:]] = True
    g = (np.median(pk[hi]) - np.median(pk[lo])) / D
    return float(g), float(np.median(age[hi]) / np.median(age[lo]))


def _positions(sim, drive, tt):
    sp = CubicHermiteSpline(sim["t"], sim["s"], sim["w"], extrapolate=True)
    s = sp(tt)
    return s, drive.phi(tt) - s


def _twin_1dof(P, sim, drive, idx, fs):
    """a 1-DoF reading of ideal samples at the record's rate: F = k x - J (Omega' - x''),
    speed Omega - x' by central differences"""
    t0 = sim["events"][idx[0]]["tb"] - 0.5 / P["fn"]
    t1 = sim["events"][idx[-1]]["ta"] + 0.5 / P["fn"]
    tt = np.arange(t0, t1, 1.0 / fs)
    s, x = _positions(sim, drive, tt)
    xd = np.gradient(x, tt)
    xdd = np.gradient(xd, tt)
    w = drive.om(tt) - xd
    F = P["k"] * x - P["J"] * (drive.domdt(tt) - xdd)
    out = []
    for i in idx:
        e = sim["events"][i]
        D = P["k"] * (e["xb"] - e["xa"])
        m = (tt >= e["tb"]) & (tt <= e["ta"])
        if m.sum() < 6:
            continue
        ws_, Fs_ = w[m], F[m]
        ip = int(np.argmax(ws_))
        if ip < 2 or ip > len(ws_) - 3:
            continue
        u = ws_[ip] * np.linspace(0.1, 0.9, 33)
        wa, ya = ws_[:ip + 1], Fs_[:ip + 1]
        wd, yd = ws_[ip:][::-1], Fs_[ip:][::-1]
        oa = np.argsort(wa, kind="stable")
        od = np.argsort(wd, kind="stable")
        out.append(float(np.mean(np.interp(u, wd[od], yd[od]) - np.interp(u, wa[oa], ya[oa])) / D))
    return float(np.median(out)) if out else float("nan")


# ----------------------------------------------------------------------------------------------
# parameters
# ----------------------------------------------------------------------------------------------
def _rngs(case, seed, nuisance):
    ci = CASES.index(case)
    ni = NUISANCES.index(nuisance)
    return (np.random.default_rng([_CRC, ci, int(seed), 11]),
            np.random.default_rng([_CRC, ci, int(seed), 22]),
            np.random.default_rng([_CRC, ci, int(seed), 33, ni]))


def _base_params(rp):
    fn = math.exp(rp.uniform(math.log(6.0), math.log(240.0)))
    k = math.exp(rp.uniform(math.log(0.03), math.log(1.2)))        # N m / rad
    J = k / (2 * math.pi * fn) ** 2
    N0 = rp.uniform(4.0, 30.0)
    muk = rp.uniform(0.07, 0.13)
    Dl = rp.uniform(0.20, 0.34) * muk
    ds = rp.uniform(0.06, 0.13) * muk
    Tu = N0 * R_BALL
    Wu = 2 * math.pi * fn * Tu / k
    P = dict(fn=fn, k=k, J=J, N0=N0, muk=muk, Dl=Dl, ds=ds, mus=muk + Dl + ds,
             ws=rp.uniform(0.25, 0.6) * (Dl + ds) * Wu,
             wc=rp.uniform(0.8, 2.0) * (Dl + ds) * Wu,
             cv=rp.uniform(0.08, 0.2) * Dl,
             ncy=rp.uniform(0.35, 0.7), acy=rp.uniform(1.5, 2.5),
             taud=0.0, load=("const", (0.0,)), rho=rp.uniform(0.7, 0.9),
             nh=int(rp.integers(300, 420)), eps=0.0)
    P["R_target"] = rp.uniform(3.5, 9.0)
    ntex = 10
    P["_tex_draw"] = (rp.uniform(0.3, 4.0, ntex), rp.uniform(0, 2 * math.pi, ntex), rp.normal(size=ntex))
    P["eps_rel"] = rp.uniform(0.004, 0.011)
    return P


def _omega_guess(P, R):
    Tu = P["N0"] * R_BALL
    D = 1.6 * (P["Dl"] + P["ds"]) * Tu
    return D / P["k"] / ((R - 0.55) / P["fn"])


def _pilot(P, drive, ncyc=8):
    Tn = 1.0 / P["fn"]
    sim = _simulate(P, drive, 400 * ncyc * Tn, max_events=ncyc + 2)
    idx = list(range(2, len(sim["events"])))
    return sim, idx


def _set_texture(P, D, Ts, dx):
    lam_fac, ph, a = P["_tex_draw"]
    a = a / math.sqrt(0.5 * np.sum(a ** 2))
    P["tex_k"] = [float(v) for v in 2 * math.pi / (lam_fac * dx)]
    P["tex_p"] = [float(v) for v in ph]
    P["tex_a"] = [float(v) for v in a]
    P["eps"] = P["eps_rel"] * D / Ts


# ----------------------------------------------------------------------------------------------
# the physics of one (case, seed)
# ----------------------------------------------------------------------------------------------
def _physics(case, seed, rp):
    P = _base_params(rp)
    fn = P["fn"]
    Tn = 1.0 / fn
    if case == "load_variation":
        # a deeper weakening: the load's swing in the static level stays within the drop
        P["Dl"] *= 1.35
        P["ds"] *= 1.5
        P["mus"] = P["muk"] + P["Dl"] + P["ds"]
    if case == "triggering":
        # a static excess of at least 2.5 A mu_s: the shaker triggers the breakaways, it does not
        # chop a slip into steps at its troughs
        A = rp.uniform(0.03, 0.075)
        P["ds"] = max(P["ds"], 2.5 * A * (P["muk"] + P["Dl"]) / (1 - 2.5 * A))
        P["mus"] = P["muk"] + P["Dl"] + P["ds"]
    # pilot at a constant drive: the stick-slip's frequency, drop and twist range
    om0 = _omega_guess(P, P["R_target"])
    for _ in range(2):
        sim, idx = _pilot(P, _Drive([0.0], [om0]))
        R = fn / _fss(sim, idx)
        if abs(R - P["R_target"]) < 0.15 * P["R_target"]:
            break
        om0 *= max(0.3, min(3.0, (R - 0.55) / (P["R_target"] - 0.55)))
    sim, idx = _pilot(P, _Drive([0.0], [om0]))
    fss0 = _fss(sim, idx)
    D0 = float(np.median(_drops(P, sim, idx)))
    xb = np.median([sim["events"][i]["xb"] for i in idx])
    xa = np.median([sim["events"][i]["xa"] for i in idx])
    dx0 = xb - xa
    Ts0 = P["k"] * xb
    _set_texture(P, D0, Ts0, dx0)
    P["Omega0"] = om0
    info = dict(fss0=fss0, D0=D0, dx0=dx0, xm=0.5 * (xb + xa), Ts0=Ts0)
    ncyc = int(rp.integers(18, 41))
    drive = _Drive([0.0], [om0])
    T_rec = ncyc / fss0
    extra = {}

    if case == "load_variation":
        if seed % 2 == 0:
            # a ball-ramp coupling: the twist x lifts the ball holder against the stiff normal path
            target = rp.uniform(0.14, 0.26)
            Ds = D0 / Ts0
            falling = target < 0.3 * Ds and rp.random() < 0.5
            # Coulomb estimate: the coupling softens (rising) or stiffens (falling) the spring the static
            # limit sees, so the twist range, and with it N's p-p, changes with g
            mag = target / (1 - target / Ds) if falling else target / (1 + target / Ds)
            sign = -1.0 if falling else 1.0
            hist = []
            for _ in range(5):
                P["load"] = ("ramp", (sign * mag, info["xm"], dx0))
                simp, idxp = _pilot(P, drive, 6)
                tt = np.linspace(simp["events"][idxp[0]]["tb"], simp["events"][idxp[-1]]["ta"], 4000)
                s, x = _positions(simp, drive, tt)
                N = _load_vec(P, tt, s, x)
                pp = (N.max() - N.min()) / P["N0"]
                hist.append((mag, pp))
                if abs(pp - target) < 0.07 * target:
                    break
                if len(hist) >= 2 and hist[-1][1] != hist[-2][1]:
                    (m1, p1), (m2, p2) = hist[-2], hist[-1]
                    new = m2 + (target - p2) * (m2 - m1) / (p2 - p1)
                else:
                    new = mag * target / max(pp, 1e-3)
                mag = float(min(max(new, 0.5 * mag), 1.5 * mag, (0.5 if falling else 0.8) * Ds))
            g = sign * mag
            extra.update(load_kind="ball_ramp_twist", load_g=g, load_target_pp=target)
        else:
            # a wavy plate surface along the ball's track (the gap held, the load follows the ball's angle)
            g = rp.uniform(0.065, 0.14)
            g = min(g, max(0.06, 0.45 * D0 / Ts0))
            lam = rp.uniform(3.0, 8.0) * dx0
            P["load"] = ("wavy", (g, 2 * math.pi / lam, rp.uniform(0, lam)))
            extra.update(load_kind="wavy_track_angle", load_g=g, wave_over_slip=lam / dx0)
        simp, idxp = _pilot(P, drive, 8)
        fss0 = _fss(simp, idxp)
        T_rec = ncyc / fss0
    elif case == "twin_branch":
        P["taud"] = rp.uniform(0.08, 0.14) * Tn
        target = rp.uniform(0.125, 0.21)
        cv = P["cv"] * 3.0
        hist = []
        for _ in range(6):
            P["cv"] = cv
            simp, idxp = _pilot(P, drive, 7)
            tw = _twin(P, simp, idxp)
            hist.append((cv, tw))
            if abs(tw - target) < 0.08 * target:
                break
            if len(hist) >= 2 and hist[-1][1] != hist[-2][1]:
                (c1, t1), (c2, t2) = hist[-2], hist[-1]
                cv_new = c2 + (target - t2) * (c2 - c1) / (t2 - t1)
            else:
                cv_new = cv * target / max(tw, 0.02)
            cv = float(min(max(cv_new, 0.3 * cv), 3.0 * cv))
        extra.update(twin_target=target)
        simp, idxp = _pilot(P, drive, 6)
        fss0 = _fss(simp, idxp)
        T_rec = ncyc / fss0
    elif case == "static_ageing":
        P["pag"] = rp.uniform(0.3, 0.5)
        P["theta"] = rp.uniform(1.0, 4.0) * Tn
        target = rp.uniform(0.095, 0.165)
        tst0 = 1.0 / fss0 - 0.55 * Tn
        steps = seed % 2 == 0
        if steps:
            r = rp.uniform(4.0, 8.0)
            nblk = int(rp.integers(2, 4))
            plan = [(int(rp.integers(3, 6)), int(rp.integers(5, 9))) for _ in range(nblk)]
            tS, tL = tst0, r * tst0
            extra.update(drive_kind="steps", step_ratio=r)
        else:
            nh = int(rp.integers(5, 9))
            plan = [(int(rp.integers(2, 5)), rp.uniform(0.1, 0.7), rp.uniform(2.0, 7.0)) for _ in range(nh)]
            tS, tL = tst0, tst0 * (1.0 + float(np.median([p_[2] for p_ in plan])))
            extra.update(drive_kind="holds", n_holds=nh)

        def level(om, nev):
            sm = _simulate(P, _Drive([0.0], [om]), 1e4 / fss0, max_events=nev)
            ev = sm["events"]
            cyc = (ev[-1]["tb"] - ev[-3]["tb"]) / 2.0
            return ev, cyc, float(np.mean([e["age"] for e in ev[-2:]]))

        def schedule():
            ev, cyc_f, tst_f = level(om0, 6)
            tw = ev[3]["tb"]
            tk, wk = [0.0], [om0]
            t = tw + 3.0 * cyc_f
            if steps:
                _, cyc_s, _ = level(om0 / r, 5)
                ramp = 0.3 * Tn
                for nslow, nfast in plan:
                    tk += [t, t + ramp]
                    wk += [om0, om0 / r]
                    t += ramp + nslow * cyc_s
                    tk += [t, t + ramp]
                    wk += [om0 / r, om0]
                    t += ramp + nfast * cyc_f
            else:
                ramp = 0.1 * Tn
                for ncy_, ph_, thf in plan:
                    t += ncy_ * cyc_f + ph_ * tst_f
                    th = thf * tst_f
                    tk += [t, t + ramp, t + ramp + th, t + 2 * ramp + th]
                    wk += [om0, 0.0, 0.0, om0]
                    t += 2 * ramp + th
                t += 2.0 * cyc_f
            return _Drive(tk, wk), t - tw + 0.5 * cyc_f, 1.0 / cyc_f

        th_ = P["theta"]
        beta = target * D0 / Ts0 / ((tL / th_) ** P["pag"] - (tS / th_) ** P["pag"])
        rp_w0 = rp.uniform(0.2, 0.8)
        for _ in range(4):
            P["beta"] = beta
            drive, T_rec, fss0 = schedule()
            simp, t0p, t1p = _run(P, drive, T_rec, fss0, rp_w0)
            gr, _ = _ageing(P, simp, _window_events(simp, t0p, t1p))
            if abs(gr - target) < 0.07 * target:
                break
            beta *= target / max(gr, 0.2 * target)
        extra.update(ageing_target=target, _rp_w=rp_w0)
    elif case == "triggering":
        ftr = rp.uniform(2.5, 5.0)
        P["load"] = ("shaker", (A, ftr * fn, rp.uniform(0, 2 * math.pi)))
        extra.update(shaker_A=A)
    elif case == "drive_modulation":
        a = rp.uniform(0.22, 0.42)
        rm = rp.uniform(0.2, 0.38)
        psi = rp.uniform(0, 2 * math.pi)
        drive = _Drive(mod=(om0, a, rm * fss0, psi))
        extra.update(mod_a=a, mod_rm_plan=rm)
    info["fss0"] = fss0
    return P, drive, T_rec, info, extra, ncyc


def _run(P, drive, T_rec, fss0, rp_w):
    """the final run: a warm-up of three slips, then the record's window"""
    Tn = 1.0 / P["fn"]
    t_end = 3.2 / fss0 + T_rec + 2.0 / fss0 + 2 * Tn
    for _ in range(6):
        sim = _simulate(P, drive, t_end)
        ev = sim["events"]
        if len(ev) >= 5:
            t0 = ev[3]["tb"] - rp_w * (ev[3]["tb"] - ev[2]["ta"])
            t1 = t0 + T_rec
            if t1 + 1.0 / fss0 < sim["t"][-1] or not sim["ok"]:
                return sim, t0, t1
            t_end += t1 + 1.5 / fss0 - sim["t"][-1]
        else:
            t_end *= 2.0
    raise RuntimeError("%s: no steady stick-slip" % NAME)


# ----------------------------------------------------------------------------------------------
# measurement chain
# ----------------------------------------------------------------------------------------------
def _ar2_noise(rng, n, f0, r):
    a1 = 2 * r * math.cos(2 * math.pi * f0)
    a2 = -r * r
    e = rng.normal(size=n + 200)
    y = signal.lfilter([1.0], [1.0, -a1, -a2], e)[200:]
    return y / (np.std(y) + 1e-300)


def _student(rng, n, df):
    z = rng.standard_t(df, size=n)
    return z / math.sqrt(df / (df - 2.0))


def _measure(P, sim, drive, t0, t1, fs, rm, extra):
    """true signals on a fine grid, then each sensor: returns the record's channels (SI: N m, rad, N, rad/s)"""
    OS = 4
    dtf = 1.0 / (fs * OS)
    i0 = 40 * OS
    ns = int(round((t1 - t0) * fs))
    tf = t0 + dtf * np.arange(-i0, OS * ns)
    s, x = _positions(sim, drive, tf)
    N = _load_vec(P, tf, s, x)
    T = P["k"] * x
    fn = P["fn"]
    sel = i0 + OS * np.arange(ns)
    tout = np.arange(ns) / fs
    n = ns
    ch = {}
    D = extra["D_med"]
    # torque flange: 3rd-order Butterworth, an odd cubic nonlinearity, Student-t + AR(2) noise
    fcT = min(rm.uniform(8.0, 25.0) * fn, 0.38 * fs)
    sos = signal.butter(3, fcT, fs=fs * OS, output="sos")
    Tflt = signal.sosfilt(sos, T, zi=signal.sosfilt_zi(sos) * T[0])[0]
    TFS = 1.5 * np.max(np.abs(T))
    eta = rm.uniform(-0.003, 0.003)
    Tr = Tflt * (1 + eta * (Tflt / TFS) ** 2)
    Tr = Tr[sel] + D * (rm.uniform(0.001, 0.0035) * _student(rm, n, rm.uniform(3.0, 6.0))
                        + rm.uniform(0.0005, 0.002) * _ar2_noise(rm, n, rm.uniform(0.05, 0.3), rm.uniform(0.85, 0.97)))
    ch["torque"] = Tr
    ch["torque_true"] = T[sel]
    # twist from two sin/cos encoders: no low-pass, an interpolation error periodic in each angle,
    # the electronics' jitter, 2^-? counts
    lines = int(rm.choice([2048, 4096, 8192]))
    pitch = 2 * math.pi / lines
    q = pitch / 4096.0
    dxr = D / P["k"]
    ph_m = drive.phi(tf[sel])
    ie = 0.0015 * pitch
    enc_m = ph_m + ie * np.sin(2 * math.pi * ph_m / pitch + rm.uniform(0, 6.3))
    enc_s = s[sel] + ie * np.sin(2 * math.pi * s[sel] / pitch + rm.uniform(0, 6.3))
    tw = np.round(enc_m / q) * q - np.round(enc_s / q) * q
    tw = tw + dxr * rm.uniform(0.0008, 0.0025) * _student(rm, n, rm.uniform(3.0, 6.0))
    ch["twist"] = tw
    ch["twist_true"] = x[sel]
    # the normal-force sensor: one pole, Gaussian noise, 1 mN resolution
    fcN = min(rm.uniform(15.0, 40.0) * fn, 0.4 * fs)
    bN, aN = signal.butter(1, fcN, fs=fs * OS)
    Nf = signal.lfilter(bN, aN, N, zi=signal.lfilter_zi(bN, aN) * N[0])[0]
    Nr = Nf[sel] + P["N0"] * rm.uniform(0.0003, 0.0012) * rm.normal(size=n)
    ch["normal"] = np.round(Nr / 1e-3) * 1e-3
    ch["normal_true"] = N[sel]
    # the motor: its encoder angle and the controller's speed readout
    qm = 2 * math.pi / 2 ** 22
    ch["motor_angle"] = np.round((ph_m + rm.uniform(0.0, 2 * math.pi)) / qm) * qm
    om = drive.om(tf[sel])
    ch["motor_speed"] = om * (1 + 0.002 * rm.normal(size=n)) + P["Omega0"] * 0.001 * rm.normal(size=n)
    # plate temperature (Peltier controlled) and an acoustic-emission RMS channel
    T0 = rm.uniform(24.0, 40.0)
    ch["temperature"] = np.round(T0 + 0.05 * np.cumsum(rm.normal(size=n)) / math.sqrt(n) * 3 + 0.02 * rm.normal(size=n), 2)
    ae = np.zeros(n)
    tau_ae = rm.uniform(0.08, 0.25) / fn
    for e in sim["events"]:
        if t0 - 1.0 / fn <= e["tb"] <= t1:
            m = tout >= e["tb"] - t0
            amp = rm.lognormal(math.log(40.0), 0.3)
            ae[m] += amp * np.exp(-(tout[m] - (e["tb"] - t0)) / tau_ae)
    ae = np.abs(ae + 2.0 * rm.normal(size=n)) + 1.5
    ch["ae"] = ae
    return tout, ch, dict(fc_torque_over_fn=fcT / fn, fc_normal_over_fn=fcN / fn, torque_nonlin=eta)


def _apply_nuisance(nuisance, rn, chans, main, D_main, fs, others=()):
    info = {}
    y = chans[main]
    n = len(y)
    t = np.arange(n) / fs
    if nuisance == "hum":
        fh = float(rn.choice([50.0, 60.0])) * float(rn.choice([1, 1, 2, 3]))
        for c in (main,) + tuple(others):
            v = chans[c]
            spread = np.percentile(v, 99) - np.percentile(v, 1)
            if c != main:
                spread = max(spread, 0.003 * np.mean(np.abs(v)))
            amp = rn.uniform(0.01, 0.05) * spread
            chans[c] = v + amp * np.sin(2 * math.pi * fh * t + rn.uniform(0, 6.3)) \
                + 0.3 * amp * np.sin(2 * math.pi * 3 * fh * t + rn.uniform(0, 6.3))
        info.update(hum_hz=fh)
    elif nuisance == "drift":
        size = rn.uniform(0.012, 0.03) * D_main * rn.choice([-1.0, 1.0])
        tau = rn.uniform(0.3, 1.5) * t[-1]
        shape = (1 - np.exp(-t / tau)) / (1 - math.exp(-t[-1] / tau))
        chans[main] = y + size * shape
        info.update(drift_over_D=float(abs(size) / D_main))
    elif nuisance == "spikes":
        frac = rn.uniform(0.0005, 0.005)
        m = max(1, int(round(frac * n)))
        where = rn.choice(n, size=m, replace=False)
        y = y.copy()
        y[where] += rn.uniform(0.05, 0.3, size=m) * D_main * rn.choice([-1.0, 1.0], size=m)
        chans[main] = y
        info.update(spike_fraction=m / n)
    elif nuisance == "quantisation":
        q = rn.uniform(0.002, 0.01) * D_main
        chans[main] = np.round(y / q) * q
        info.update(adc_step_over_D=float(q / D_main))
    return info


# ----------------------------------------------------------------------------------------------
# writers: a rheometer's raw-data export, a digital oscilloscope's CSV, a data logger's CSV
# ----------------------------------------------------------------------------------------------
def _table(cols, fmts, sep, dec_comma):
    n = len(cols[0])
    parts = []
    for c, f in zip(cols, fmts):
        if f == "int":
            parts.append(np.char.mod("%d", np.asarray(c, dtype=np.int64)))
        else:
            parts.append(np.char.mod(f, np.asarray(c, float)))
    rows = parts[0]
    for p in parts[1:]:
        rows = np.char.add(np.char.add(rows, sep), p)
    body = "\n".join(rows.tolist())
    if dec_comma:
        body = body.replace(".", ",")
    return body + "\n"


def _write_rheo(path, meta, names, units, cols, fmts, dec_comma):
    sep = "\t"
    head = [
        "Project:\tTribology stick-slip %s" % meta["id"],
        "Test:\tBall-on-three-plates, grease, torsion coupling",
        "Result:\tRaw data (high-speed acquisition)",
        "Measuring System:\tBC12.7 ball on three plates (45 deg)",
        "Accessory:\tPeltier tribology cell, coupling %s" % meta["coupling"],
        "Interval and data points:\t1\t%d" % len(cols[0]),
        "Sampling rate:\t%s Hz" % (("%.6g" % meta["fs"]).replace(".", ",") if dec_comma else "%.6g" % meta["fs"]),
        "Interval data:",
        "",
    ]
    txt = "\n".join(head) + "\n" + sep.join(names) + "\n" + sep.join(units) + "\n" + _table(cols, fmts, sep, dec_comma)
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(txt)


def _write_scope(path, meta, names, cols, fmts):
    n = len(cols[0])
    head = [
        "Model,MDO3034",
        "Firmware Version,1.26",
        "Waveform Type,ANALOG",
        "Point Format,Y",
        "Horizontal Units,s",
        "Horizontal Scale,%.3e" % meta["hscale"],
        "Sample Interval,%.6e" % (1.0 / meta["fs"]),
        "Record Length,%d" % n,
        "Gating,0.0%,100.0%",
        "Probe Attenuation," + ",".join(meta["probes"]),
        "Vertical Units," + ",".join(meta["vunits"]),
        "Label," + ",".join(meta["labels"]),
        "",
    ]
    txt = "\n".join(head) + "\n" + ",".join(names) + "\n" + _table(cols, fmts, ",", False)
    with open(path, "w", encoding="utf-8", newline="\r\n") as f:
        f.write(txt)


def _write_logger(path, meta, names, cols, fmts, semicolon):
    sep = ";" if semicolon else ","
    q = lambda s: '"%s"' % s
    head = [
        sep.join([q("Data logger"), q("midi LOGGER GL-840")]),
        sep.join([q("Start time"), q(meta["start"])]),
        sep.join([q("Sampling interval"), q(meta["interval"])]),
        sep.join([q("Number of samples"), q(str(len(cols[0])))]),
        sep.join([q("CH"), q("Signal"), q("Range"), q("Filter")]),
    ]
    for i, (nm, rg) in enumerate(meta["chans"]):
        head.append(sep.join([q("CH%d" % (i + 1)), q(nm), q(rg), q("Off")]))
    head.append("")
    txt = "\n".join(head) + "\n" + sep.join(q(nm) for nm in names) + "\n" + _table(cols, fmts, sep, semicolon)
    with open(path, "w", encoding="utf-8", newline="\r\n") as f:
        f.write(txt)


# ----------------------------------------------------------------------------------------------
# the record
# ----------------------------------------------------------------------------------------------
def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case %r" % (case,))
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % (nuisance,))
    rp, rm, rn = _rngs(case, seed, nuisance)
    P, drive, T_rec, info, extra, ncyc = _physics(case, seed, rp)
    fn = P["fn"]
    Tn = 1.0 / fn
    rp_w = extra.pop("_rp_w", None) or rp.uniform(0.2, 0.8)
    fss0 = info["fss0"]
    meas = {}
    if case == "triggering":
        A, ft, psit = P["load"][1]
        tried = []
        for _ in range(7):
            P["load"] = ("shaker", (A, ft, psit))
            sim, t0, t1 = _run(P, drive, T_rec, fss0, rp_w)
            idx = _window_events(sim, t0, t1)
            fss = _fss(sim, idx)
            r = ft / fss
            d = abs(r - round(r))
            tried.append((d, ft))
            if d >= 0.2:
                break
            base = math.floor(r) + 0.5
            cand = [base * fss, (base + 1) * fss, (base - 1) * fss]
            cand = [c for c in cand if 2.5 * fn <= c <= 5.2 * fn] or [min(max(base * fss, 2.5 * fn), 5.2 * fn)]
            ft = cand[int(rp.integers(len(cand)))] * (1 + rp.uniform(-0.02, 0.02))
        else:
            d, ft = max(tried)
            P["load"] = ("shaker", (A, ft, psit))
            sim, t0, t1 = _run(P, drive, T_rec, fss0, rp_w)
            idx = _window_events(sim, t0, t1)
        meas.update(shaker_ft_over_fn=ft / fn)
    elif case == "drive_modulation":
        om0, a, fm, psi = drive.mod
        for _ in range(4):
            sim, t0, t1 = _run(P, drive, T_rec, fss0, rp_w)
            idx = _window_events(sim, t0, t1)
            r = fm / _fss(sim, idx)
            if 0.17 <= r <= 0.43:
                break
            fm *= min(max(0.3 / r, 0.5), 2.0)
            drive = _Drive(mod=(om0, a, fm, psi))
        meas.update(mod_fm_hz=fm)
    else:
        sim, t0, t1 = _run(P, drive, T_rec, fss0, rp_w)
        idx = _window_events(sim, t0, t1)
    if not sim["ok"] or len(idx) < 8:
        raise RuntimeError("%s %s seed %d: no steady stick-slip (%d slips)" % (NAME, case, seed, len(idx)))

    # ---------------- ground truth
    drops = _drops(P, sim, idx)
    D = float(np.median(drops))
    fss = _fss(sim, idx)
    extra["D_med"] = D
    meas.update(n_slips=len(idx), fn_over_fss=fn / fss, drop_torque_Nm=D,
                drop_over_peak=D / float(np.median([P["k"] * sim["events"][i]["xb"] for i in idx])))
    meas["twin_over_D"] = _twin(P, sim, idx)
    if P["load"][0] != "const":
        meas["twin_per_load_over_D"] = _twin(P, sim, idx, per_load=True)
    gr, ratio = _ageing(P, sim, idx)
    meas["peak_growth_over_D"] = gr
    meas["stick_ratio"] = ratio
    pk = np.array([P["k"] * sim["events"][i]["xb"] for i in idx])
    meas["peak_sd_over_D"] = float(np.std(pk) / D)
    tt = np.linspace(t0, t1, 20000)
    sgrid, xgrid = _positions(sim, drive, tt)
    Ng = _load_vec(P, tt, sgrid, xgrid)
    meas["N_pp_over_N0"] = float((Ng.max() - Ng.min()) / P["N0"])
    if case == "triggering":
        r = P["load"][1][1] / fss
        meas.update(ft_over_fss=r, ft_dist_integer=abs(r - round(r)))
    if case == "drive_modulation":
        meas.update(fm_over_fss=meas["mod_fm_hz"] / fss)
    if case in ("none", "twin_branch"):
        meas["twin_1dof_ideal_over_D"] = _twin_1dof(P, sim, drive, idx, fs=60 * fn)
    if case == "none":
        # the law's own ageing, probed on an unrecorded run with a 6x stepped drive
        om0 = P["Omega0"]
        tst0 = 1.0 / fss0 - 0.55 * Tn
        t = 3.0 / fss0
        tk, wk = [0.0], [om0]
        for _ in range(2):
            tk += [t, t + 0.3 * Tn]; wk += [om0, om0 / 6]
            t += 0.3 * Tn + 3 * (6 * tst0 + 0.55 * Tn)
            tk += [t, t + 0.3 * Tn]; wk += [om0 / 6, om0]
            t += 0.3 * Tn + 4 / fss0
        probe = _simulate(P, _Drive(tk, wk), t)
        pidx = list(range(3, len(probe["events"])))
        g2, r2 = _ageing(P, probe, pidx)
        meas.update(law_ageing_probe_over_D=g2, law_ageing_probe_stick_ratio=r2)

    # ---------------- the record's form (measurement RNG only)
    fmt = str(rm.choice(["rheo", "scope", "logger"], p=[0.4, 0.3, 0.3]))
    spp_n = rm.uniform(20.0, 100.0)
    spp_c = rm.uniform(10.0, 15.0)
    spp = spp_c if nuisance == "coarse" else spp_n
    if nuisance != "coarse":
        spp = max(20.0, min(spp, 120000.0 / (T_rec * fn)))
    fs = spp * fn
    if fmt == "rheo":
        qty = str(rm.choice(["torque", "twist", "linear"], p=[0.45, 0.3, 0.25]))
    elif fmt == "scope":
        qty = "torque"
    else:
        qty = str(rm.choice(["torque", "twist"], p=[0.6, 0.4]))
    if case == "static_ageing":
        drv = str(rm.choice(["position", "speed"], p=[0.6, 0.4]))
    elif case == "drive_modulation":
        drv = "none"
        rm.random()
    else:
        drv = str(rm.choice(["position", "speed", "none"], p=[0.3, 0.2, 0.5]))
    if fmt == "scope" and drv == "position":
        drv = "speed"
    if case == "load_variation":
        has_N = (seed % 8) != 3
        rm.random()
    elif case == "triggering":
        has_N = True
        rm.random()
    else:
        has_N = fmt == "rheo" or bool(rm.random() < 0.4)
    deg = bool(rm.random() < 0.55)
    dec_comma = bool(rm.random() < 0.35)
    tout, ch, sens = _measure(P, sim, drive, t0, t1, fs, rm, extra)
    n = len(tout)

    # ---------------- units and channels
    aconv = 180.0 / math.pi if deg else 1.0
    aunit = "deg" if deg else "rad"
    chans = {}
    if qty == "torque":
        chans["main"] = ch["torque"]
        D_main = D
        main_unit = "N·m"
        stiff = P["k"] / aconv
        stiff_unit = "N·m/" + aunit
    elif qty == "twist":
        chans["main"] = ch["twist"] * aconv
        D_main = D / P["k"] * aconv
        main_unit = aunit
        stiff = None
        stiff_unit = None
    else:
        mm = bool(rm.random() < 0.7)
        chans["main"] = ch["torque"] / R_EFF * (1.0 if mm else 1000.0)
        D_main = D / R_EFF * (1.0 if mm else 1000.0)
        main_unit = "N" if mm else "mN"
        stiff = P["k"] / R_EFF ** 2
        stiff_unit = "N/m"
    if has_N:
        chans["normal"] = ch["normal"]
    if drv == "position":
        if qty == "linear":
            chans["drive"] = ch["motor_angle"] * R_EFF * 1000.0
        else:
            chans["drive"] = ch["motor_angle"] * aconv
    elif drv == "speed":
        if qty == "linear":
            chans["drive"] = ch["motor_speed"] * R_EFF * 1000.0
        else:
            chans["drive"] = ch["motor_speed"] * aconv
    nz = _apply_nuisance(nuisance, rn, chans, "main", D_main, fs, others=("normal",) if has_N else ())

    # ---------------- the file
    os.makedirs(outdir, exist_ok=True)
    stem = "%s_%s_s%d_%s" % (NAME, case, seed, nuisance)
    v0 = P["Omega0"] * (R_EFF * 1000.0 if qty == "linear" else aconv)
    v0_unit = "mm/s" if qty == "linear" else aunit + "/s"
    if fmt == "rheo":
        names = ["Point No.", "Time"]
        units = ["", "[s]"]
        cols = [np.arange(1, n + 1), tout]
        fmts = ["int", "%.7f"]
        if qty == "torque":
            names.append("Torque"); units.append("[N·m]")
        elif qty == "twist":
            names.append("Deflection Angle"); units.append("[%s]" % aunit)
        else:
            names.append("Friction Force"); units.append("[%s]" % main_unit)
        cols.append(chans["main"]); fmts.append("%.7g")
        if has_N:
            names.append("Normal Force"); units.append("[N]"); cols.append(chans["normal"]); fmts.append("%.4f")
        if drv == "position":
            names.append("Sliding Distance" if qty == "linear" else "Motor Angle")
            units.append("[mm]" if qty == "linear" else "[%s]" % aunit)
            cols.append(chans["drive"]); fmts.append("%.8g")
        elif drv == "speed":
            names.append("Sliding Speed" if qty == "linear" else "Motor Speed")
            units.append("[mm/s]" if qty == "linear" else "[%s/s]" % aunit)
            cols.append(chans["drive"]); fmts.append("%.6g")
        names.append("Temperature"); units.append("[°C]"); cols.append(ch["temperature"]); fmts.append("%.2f")
        path = os.path.join(outdir, stem + ".txt")
        meta = dict(id="%s-%d" % (case[:4].upper(), seed), fs=fs,
                    coupling="%.4g N·m/rad" % P["k"])
        _write_rheo(path, meta, names, units, cols, fmts, dec_comma)
        style = "rheometer raw-data export, TAB, names row + [unit] row" + (", decimal comma" if dec_comma else "")
    elif fmt == "scope":
        pre = rm.uniform(0.05, 0.2) * (tout[-1] + tout[1])
        tsc = tout - pre
        names = ["TIME (s)", "CH1 Torque (N·m)"]
        cols = [tsc, chans["main"]]
        fmts = ["%.6e", "%.6e"]
        probes = ["1.0E-2"]
        vunits = ["N·m"]
        labels = ["TORQUE"]
        if has_N:
            names.append("CH2 Normal force (N)"); cols.append(chans["normal"]); fmts.append("%.5e")
            probes.append("10"); vunits.append("N"); labels.append("FN")
        if drv == "speed":
            names.append("CH3 Motor speed (%s/s)" % aunit); cols.append(chans["drive"]); fmts.append("%.5e")
            probes.append("1"); vunits.append(aunit + "/s"); labels.append("TACHO")
        path = os.path.join(outdir, stem + ".csv")
        meta = dict(fs=fs, hscale=(tout[-1] + tout[1]) / 10.0, probes=probes, vunits=vunits, labels=labels)
        _write_scope(path, meta, names, cols, fmts)
        style = "oscilloscope CSV, header block, pre-trigger time"
    else:
        semi = dec_comma
        tms = bool(rm.random() < 0.4)
        names = ["No.", "Time[ms]" if tms else "Time[s]"]
        cols = [np.arange(1, n + 1), tout * (1000.0 if tms else 1.0)]
        fmts = ["int", "%.4f" if tms else "%.7f"]
        chl = []
        if qty == "torque":
            names.append("Torque[N·m]"); chl.append(("Torque flange", "0.2 N·m"))
        else:
            names.append("Spring deflection[%s]" % aunit); chl.append(("Coupling encoders", "digital"))
        cols.append(chans["main"]); fmts.append("%.7g")
        if has_N:
            names.append("Normal load[N]"); chl.append(("Load cell", "50 N"))
            cols.append(chans["normal"]); fmts.append("%.4f")
        if drv == "position":
            names.append("Drive angle[%s]" % aunit); chl.append(("Motor encoder", "digital"))
            cols.append(chans["drive"]); fmts.append("%.8g")
        elif drv == "speed":
            names.append("Drive speed[%s/s]" % aunit); chl.append(("Motor speed", "10 V"))
            cols.append(chans["drive"]); fmts.append("%.6g")
        names.append("Oil temp[degC]"); chl.append(("Pt100", "100 degC"))
        cols.append(ch["temperature"]); fmts.append("%.2f")
        names.append("AE RMS[mV]"); chl.append(("AE sensor", "1 V"))
        cols.append(ch["ae"]); fmts.append("%.1f")
        path = os.path.join(outdir, stem + (".csv" if semi or rm.random() < 0.6 else ".dat"))
        dtus = 1e6 / fs
        meta = dict(start="2024/%02d/%02d %02d:%02d:%02d" % (1 + seed % 12, 1 + (7 * seed) % 28, 9 + seed % 8,
                                                         (13 * seed) % 60, (29 * seed) % 60),
                    interval=("%.4g" % dtus).replace(".", ",") + "us" if semi else "%.4gus" % dtus, chans=chl)
        _write_logger(path, meta, names, cols, fmts, semi)
        style = "data-logger CSV, quoted names, sample counter, temperature and AE channels" + \
            (", semicolon + decimal comma" if semi else "")

    # ---------------- arguments a user would pass
    args = []
    omit = _OMIT_FN[case] is not None and seed % 8 == _OMIT_FN[case] and nuisance != "fn_off"
    if nuisance == "fn_off":
        fn_given = fn * (1.0 + float(rn.choice([-0.05, 0.05])))
    elif omit:
        fn_given = None
    else:
        fn_given = float("%.4g" % fn)
    if fn_given is not None:
        args += ["--fn", "%.4g" % fn_given]
        fn_given = float("%.4g" % fn_given)
    if stiff is not None:
        args += ["--stiffness", "%.5g" % stiff]
    if drv == "none":
        args += ["--v0", "%.5g" % v0]
    params = dict(
        rig="rotational rheometer, ball-on-three-plates tribology cell, torsion-spring coupling",
        record_format=style, quantity=qty, angle_unit=aunit, drive_column=drv, normal_column=has_N,
        samples_per_period=fs / fn, fs_hz=fs, n_rows=n, record_s=float(tout[-1]),
        k_Nm_per_rad=P["k"], J_kgm2=P["J"], N0_N=P["N0"], r_ball_m=R_BALL, r_eff_m=R_EFF,
        mu_k=P["muk"], mu_weak=P["Dl"], mu_static_excess=P["ds"], mu_s=P["mus"],
        w_s_rad_s=P["ws"], film_cv=P["cv"], film_wc_rad_s=P["wc"], carreau_n=P["ncy"], carreau_a=P["acy"],
        film_delay_s=P["taud"], film_delay_over_Tn=P["taud"] * fn, texture_eps=P["eps"],
        genalpha_rho_inf=P["rho"], step_over_Tn=sim["h"] * fn,
        Omega0_rad_s=P["Omega0"], v0_file_units=v0, v0_unit=v0_unit,
        load=P["load"][0], load_params=[float(v) for v in P["load"][1]],
        ageing_beta=P.get("beta", 0.0), ageing_theta_s=P.get("theta", 0.0), ageing_p=P.get("pag", 0.0),
        stiffness_arg=stiff, stiffness_unit=stiff_unit,
    )
    if drive.mod is not None:
        params.update(mod=[float(v) for v in drive.mod])
    params.update({k_: (float(v) if isinstance(v, (float, np.floating)) else v) for k_, v in extra.items()})
    params.update({k_: float(v) for k_, v in sens.items()})
    params.update({k_: (float(v) if isinstance(v, (float, np.floating, int, np.integer)) else v) for k_, v in meas.items()})
    params.update(nz)
    params = _jsonable(params)
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=os.path.abspath(path),
                args=args, fn_true=float(fn), fn_given=fn_given, params=params)


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.floating, float)):
        v = float(o)
        return v if math.isfinite(v) else None
    if isinstance(o, (np.bool_,)):
        return bool(o)
    return o


# ----------------------------------------------------------------------------------------------
# self-check
# ----------------------------------------------------------------------------------------------
def _read_back(path):
    """our own loader: the table under the header; returns (names, array)"""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    sep = "\t" if path.endswith(".txt") else (";" if ";" in lines[-1] else ",")
    dec_comma = sep != "," and "," in lines[-1]
    i = len(lines) - 1
    while i > 0:
        cells = lines[i].split(sep)
        try:
            [float(c.replace(",", ".") if dec_comma else c) for c in cells]
        except ValueError:
            break
        i -= 1
    data = np.array([[float(c.replace(",", ".") if dec_comma else c) for c in ln.split(sep)]
                     for ln in lines[i + 1:] if ln.strip()])
    hdr = i
    if lines[hdr].split(sep)[1].strip() == "[s]":
        hdr -= 1
    return [c.strip('"') for c in lines[hdr].split(sep)], data


def _selfcheck(outdir):
    rows = []
    for case in CASES:
        for seed in range(8):
            nz = NUISANCES[seed % 7]
            r = write_record(case, seed, outdir, nz)
            json.dumps(r, allow_nan=False)
            names, data = _read_back(r["file"])
            assert data.ndim == 2 and data.shape[1] == len(names) and np.all(np.isfinite(data)), r["file"]
            it = [i for i, nm in enumerate(names) if nm.lower().startswith("time")][0]
            assert np.all(np.diff(data[:, it]) > 0), r["file"]
            p = r["params"]
            rows.append((case, seed, nz, p))
            sizes = dict(
                none="twin %+.5f (1-DoF %+.3f), probe ageing %+.4f over %.1fx, peak sd %.4f"
                % (p["twin_over_D"], p["twin_1dof_ideal_over_D"], p["law_ageing_probe_over_D"],
                   p["law_ageing_probe_stick_ratio"], p["peak_sd_over_D"]) if case == "none" else "",
                load_variation="N pp %.3f (%s g %+.3f), twin F %+.3f, F/N %+.5f"
                % (p["N_pp_over_N0"], p["load_kind"].split("_")[0], p["load_g"], p["twin_over_D"],
                   p["twin_per_load_over_D"]) if case == "load_variation" else "",
                twin_branch="twin %+.4f (1-DoF %+.3f), delay %.3f Tn" % (
                    p["twin_over_D"], p["twin_1dof_ideal_over_D"], p["film_delay_over_Tn"]) if case == "twin_branch" else "",
                static_ageing="growth %+.4f over %.1fx (%s), twin %+.5f" % (
                    p["peak_growth_over_D"], p["stick_ratio"], p["drive_kind"], p["twin_over_D"])
                if case == "static_ageing" else "",
                triggering="A %.3f, ft/fn %.2f, ft/fss %.2f (%.2f off), N pp %.3f" % (
                    p["shaker_A"], p["shaker_ft_over_fn"], p["ft_over_fss"], p["ft_dist_integer"], p["N_pp_over_N0"])
                if case == "triggering" else "",
                drive_modulation="a %.3f, fm/fss %.3f, twin %+.5f" % (p["mod_a"], p["fm_over_fss"], p["twin_over_D"])
                if case == "drive_modulation" else "",
            )[case]
            style = {"rheometer": "rheo", "oscilloscope": "scope", "data-logger": "logger"}[p["record_format"].split()[0]]
            print("%-16s %d %-12s fn %5.1f fn/fss %5.2f slips %2d spp %5.1f %-6s %-6s %-8s N%d | %s | %s"
                  % (case, seed, nz, r["fn_true"], p["fn_over_fss"], p["n_slips"], p["samples_per_period"],
                     style, p["quantity"], p["drive_column"], p["normal_column"], sizes, " ".join(r["args"])))
            sys.stdout.flush()
    return rows


if __name__ == "__main__":
    import tempfile
    import time
    out = sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp(prefix=NAME + "_")
    t0 = time.time()
    _selfcheck(out)
    print("records in", out, "%.1f s" % (time.time() - t0))
