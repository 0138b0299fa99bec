"""moreau_stage: a slider pulled by a spring from a linear-motor stage under a PID position loop, its contact
integrated by Moreau-Jean non-smooth time stepping. Written without reading the diagnosis code; the ground truth
below is measured on this file's own model.

FRICTION LAW (per unit normal load, a new shape per seed). A sum of smooth tanh (logistic) steps in the sliding
speed v itself (not ln v, no exponential):
    mu(v) = mu_b + sum_i A_i (1 + tanh((v - c_i)/w_i))/2 + eta v,    v = |sliding speed| > 0,
two weakening steps (depth Wt 0.06-0.13; the first at c 0-0.05 V, w 0.035-0.07 V; the second at 0.14-0.32 V,
w 0.05-0.12 V), a strengthening step (0.35-0.9 Wt at 0.6-1.15 V, w 0.12-0.3 V) that makes the law non-monotone
(minimum at 0.27-0.66 V), a shoulder (a plateau of 0.12-0.3 of the second step) on about half the seeds, a weak
viscous term; V = Wt N0/(m w0) is the slip-speed scale. mu_b 0.30-0.58 (mu_s 0.30-0.59, mu_min 0.20-0.50).
Static level mu_s = mu(0+) + 0.12-0.35 Wt (on triggering records raised to mu(0+) + 2.4 A mu_s, so that a slip
the shaker starts in a trough is not arrested by the next crest). Every record also has a counterface texture:
the static level varies along the track, + sd xi(x), sd 0.3-1.2 % of 2 (mu_s - mu_min), knots 0.2-0.6 slip
lengths apart, linear between (no effect on the sliding law).

STICK HANDLING: Moreau-Jean. The friction is set-valued at u = 0. Each step the coupled linear system gives the
end-of-step free slider speed u_free and the Delassus scalar w (u = u_free + w p, p the friction impulse);
|u_free| <= w h N mu_s(x, t_stick) -> stick, u = 0 exactly and p = -u_free/w; else slip in the direction of
u_free with |u| + w h N mu(|u|) = |u_free| (a 1-D complementarity / projection problem, solved by safeguarded
Newton in (0, |u_free|)). No events, no regularisation, no zero-velocity band. The step is chosen so that
h N max|mu'|/m < 0.6 with N up to 1.5 N0 (the scalar problem stays monotone).

INTEGRATOR: own fixed-step theta-method (theta 0.50-0.62) on the 5-state linear system y = [x_m, v_m, x_s, v_s,
I] (slider, stage, the PID's integral), (I - h th A)^-1 and (I + h (1-th) A) precomputed; the friction impulse
enters v_m only; the normal load, the texture, the ageing and the temperature states are taken at the start of
each step (the temperature updated exactly after it). h = Tn/320 (Tn/400 with the shaker). First order; h/4
(9 records) moves the drop by <= 0.16 %, the stick-slip rate by <= 0.11 %, the twin by <= 9e-4 of the drop, the
ageing growth by <= 1e-3 of the drop. Speed: ~6 us a step, 0.2-1.6 s a record.

RIG: a linear-motor stage (mass 5-20 m, a viscous guide) under a PID (PD on half the seeds) position loop,
bandwidth 3-6 w0, damping 0.6-0.9, with a cogging force of 1-4 % of mu_s N0 (magnet pitch 16-48 mm); the
spring's reaction loads the stage, so it lags its command and surges after every slip. A slider (0.24-4.8 kg,
fn 4.1-29.6 Hz, k 0.94-100 kN/m, N0 3-77 N, slip length 0.08-2.5 mm) on the spring, a dashpot in parallel
(zeta 0.005-0.03). Drives: constant speed; stepped (the `none` seeds 2, 5 and the even `static_ageing` seeds:
6-7 levels alternating, factor 4.2-7.8, 4-7 slips a level); holds (`static_ageing` seeds 1, 5: 6-8 runs of 3-5
slips, holds of 1.5-8 stick times); a reciprocating trapezoid (seeds 3 and 7 of every case except
drive_modulation: 4-6 strokes, ramps 5-15 % of the stroke, dwells 0.3-1.5 stick times, 0.5-5 in static_ageing);
modulated (drive_modulation: the stage's reference runs at v0 (1 + a sin(2 pi fm t + phi)), a long-wavelength lead
error of its position reference the loop does not see; the user gets only --v0).

DEPARTURES.
  load_variation: the slider's guide rail under its own position: even seeds tilted, N = N0 (1 + c (x - x_mid)),
    c of either sign; odd seeds wavy, N = N0 (1 + (pp/2) sin(2 pi x/lambda + phi)), lambda 2-6 slip lengths.
  twin_branch: a contact temperature theta heated by the frictional power and cooling with tau_h 0.22-0.42 Tn,
    d theta/dt = G |F| |u|/(N0 V) - theta/tau_h, friction x (1 + theta): the decelerating half of each slip is
    hotter; G tuned on pilot runs to a drawn target of 13-21 % of the drop; cold again before the next slip.
  static_ageing: log-in-time junction growth, mu_s = mu_s0 + b ln(1 + t_st/tau_a), t_st the time since the
    last arrest, tau_a 0.05-0.25 of the short stick, b from the expected stick-time range (one correction run).
  triggering: a normal-load shaker N = N0 (1 + A sin 2 pi f_t t), A 3.5-7.5 %, f_t 2.5-8 fn. The breakaways
    lock to its troughs (f_t/f_ss an integer over most of f_t); f_t is stepped and bisected on short runs from the
    record's own start until the slips mix two locks (record's f_t/f_ss >= 0.15 from an integer).
  drive_modulation: a 0.22-0.43, fm 0.15-0.42 of the stick-slip rate (one correction run if the record's own
    rate moves it out of 0.12-0.48).

RECORDS (a lab's DAQ export). About half (24 of 48; never drive_modulation): the stage's encoder (quantised
0.05-1 um, an absolute offset 20-250 mm) and a laser triangulation sensor on the slider: the slider's ABSOLUTE
position (offset 5-40 mm, one-pole 150-500 fn, white noise 0.1-0.4 % of the slip length), so the spring's
extension is encoder - laser + const. The others: a load cell in the spring (k e + c e', one-pole 15-40 fn,
noise 0.1-0.4 % of the drop; N or mN; `--stiffness`), with the stage encoder's position on every stepped, hold,
reciprocating and ageing record and about half of the rest, else `--v0` (mm/s; always on drive_modulation).
A normal force (N or mN, one-pole 10-30 fn) on every load_variation record, the even triggering seeds and ~25 %
of the rest. Formats by (seed + 2 case) mod 4: a LabVIEW .lvm export (a file header ending in
***End_of_Header***, on 60 % a second channel header with Y_Unit_Label / X_Dimension / Unit_X / X0 / Delta_X
and its own ***End_of_Header***; then `X_Value<TAB>name...<TAB>Comment`, units in the channel header or in the
names as `Name (unit)`, time in s); comma .csv with `name [unit]`; semicolon with a decimal comma (.csv/.txt,
`name [unit]`, `name (unit)` or `name/unit`, optionally a `Messung;date` / `Abtastrate;...;Hz` preamble); and
whitespace (.dat/.txt) with a `%` or `#` comment preamble (date, rate, sometimes the stiffness and the encoder's
resolution), the names row plain (`Name[unit]`) or commented. Time in s or ms (35 %), positions m/mm/um, forces
N/mN; channel names drawn from the rig software's vocabulary (Stage Position, Encoder, Motor Position, X Stage,
Laser Displacement, Slider Position, LDS Slider, Load Cell, Friction Force, Fx, Normal Force, Fz, Fn, ...).
20-100 samples per Tn (coarse 10-15), 18-48 slips (a run is cut after the 48th). The motion starts 0.5-2 Tn
into the record from an unloaded spring. `--fn` on 7 of 8 seeds per case (all for triggering; the seed left out
is 1, 4, 7, 2, -, 0 for the cases in order). Nuisances as the README: hum 50/60 Hz (+2nd, 3rd) of 1-5 % of the
drop on the analog channels (laser, load cell, normal); drift 2-6 % of the drop (exponential + linear);
spikes on 0.05-0.5 % of samples of the laser or load cell (0.3-1.5 drops); quantisation 0.2-1 % of the drop;
coarse 10-15 samples per Tn; fn_off the given --fn +-5 %.

GROUND TRUTH, measured on the simulated contact (seeds 0-7; nuisance NUISANCES[seed % 7]). Twin: per slip, the
mean over speeds 0.15-0.85 of the slip's peak of F(decelerating) - F(accelerating) at equal sliding speed,
divided by the slip's drop (spring force at breakaway minus at arrest), median over slips ("1-DoF" = the same
read from k e + c e' - m x'' on ideal samples at 100/Tn; "sensors" = from the record's noise-free sensor
outputs). Peak growth: least-squares slope of the breakaway force on ln(stick time) x ln(max/min stick time),
over the median drop (first slip left out). Load p-p: (max N - min N)/N0. f_ss: 1/mean interval between
breakaways (intervals > 1.5x the median, at reversals / holds / slower levels, left out); fm/f_ss with the
record's overall rate. a: least-squares fit of the stage's true speed.

  case/seed  nuisance      drive      fn Hz slips /Tn  record                 measured
  none 0     clean         const      20.23  29  47.1  lvm  laser+encoder      twin -0.0 % (1-DoF +0.2, sensors +0.2); peak sd 0.4 %; stage speed dev max 4.7 % rms 1.2 %
  none 1     hum           const       6.52  28  80.0  csv  laser+encoder      twin -0.0 % (-0.2, -0.2); sd 0.9 %; stage 6.5 % / 1.3 %
  none 2     drift         stepped     4.55  33  31.5  semi load cell+encoder  twin -0.0 % (+0.0, -0.3); sd 1.3 %; growth +0.2 % over 6.9x sticks; stage 20.5 % / 3.2 %
  none 3     spikes        recip       9.04  46  78.1  ws   laser+encoder      twin -0.0 % (+0.2, +0.2); sd 0.4 %; growth +0.4 % over 9.2x; stage 10.6 % / 2.2 %
  none 4     quantisation  const      19.47  24  28.3  lvm  load cell, --v0    twin -0.0 % (-0.1, -0.2); sd 0.4 %; stage 5.5 % / 1.3 %
  none 5     coarse        stepped    25.87  34  11.2  csv  laser+encoder      twin -0.0 % (-0.3, -0.3); sd 0.4 %; growth +0.1 % over 4.9x; stage 12.3 % / 1.6 %
  none 6     fn_off        const       4.13  21  28.8  semi laser+encoder      twin -0.0 % (+0.2, +0.2); sd 1.1 %; stage 4.3 % / 1.0 %
  none 7     clean         recip       8.18  33  45.5  ws   load cell+encoder  twin -0.0 % (+0.4, +0.4); sd 0.5 %; growth -0.1 % over 9.8x; stage 4.0 % / 0.8 %
  load 0     clean         const      10.01  39  81.8  semi laser+enc+Fn      tilted rail, N p-p 26.7 % N0 (F twin +1.9 %, F/N twin -0.0 %)
  load 1     hum           const       8.58  38  51.6  ws   load cell+Fn,--v0  wavy rail, 15.1 % (+3.7 %, -0.0 %)
  load 2     drift         const      14.38  38  65.6  lvm  laser+enc+Fn      tilted, 22.6 % (-0.6 %, -0.0 %)
  load 3     spikes        recip       8.28  36  93.1  csv  load cell+enc+Fn  wavy, 33.6 % (+3.4 %, -0.0 %)
  load 4     quantisation  const      18.85  37  30.9  semi laser+enc+Fn      tilted, 15.1 % (+0.6 %, -0.0 %)
  load 5     coarse        const      18.99  24  14.8  ws   laser+enc+Fn      wavy, 15.4 % (-2.9 %, -0.0 %)
  load 6     fn_off        const      11.64  31  24.5  lvm  load cell+Fn,--v0  tilted, 20.8 % (+1.4 %, -0.0 %)
  load 7     clean         recip      12.27  38  26.2  csv  laser+enc+Fn      wavy, 23.5 % (+2.9 %, -0.0 %)
  twin 0     clean         const      25.39  36  96.9  lvm  load cell, --v0    twin +21.4 % (1-DoF +21.2, sensors +20.2)
  twin 1     hum           const      29.57  25  55.0  csv  laser+encoder      +16.8 % (+17.4, +17.4)
  twin 2     drift         const      16.77  28  22.8  semi load cell+Fn,--v0 +14.2 % (+14.4, +14.7)
  twin 3     spikes        recip       5.59  37  82.7  ws   laser+enc+Fn      +19.7 % (+19.9, +19.9)
  twin 4     quantisation  const      29.25  25  31.0  lvm  laser+encoder      +16.2 % (+16.3, +16.3)
  twin 5     coarse        const       6.42  26  14.4  csv  load cell, --v0    +15.4 % (+15.9, +15.9)
  twin 6     fn_off        const      12.39  26  87.0  semi laser+encoder      +17.5 % (+17.7, +17.7)
  twin 7     clean         recip       9.72  48  37.7  ws   load cell+encoder  +17.9 % (+18.3, +18.3)
  ageing 0   clean         stepped     7.75  22  59.9  semi laser+enc+Fn      peak growth +15.0 % of the drop over 7.9x stick times
  ageing 1   hum           holds       5.71  27  51.4  ws   load cell+encoder  +10.9 % over 7.2x
  ageing 2   drift         stepped     6.63  25  32.3  lvm  laser+encoder      +14.0 % over 9.3x
  ageing 3   spikes        recip      15.61  39  73.7  csv  laser+enc+Fn      +16.1 % over 13.0x
  ageing 4   quantisation  stepped     5.27  31  36.6  semi load cell+encoder  +11.9 % over 7.2x
  ageing 5   coarse        holds      10.71  18  10.7  ws   laser+encoder      +11.7 % over 7.5x
  ageing 6   fn_off        stepped     4.26  23  24.6  lvm  load cell+encoder  +10.1 % over 8.4x
  ageing 7   clean         recip       9.56  32  42.0  csv  laser+encoder      +13.2 % over 10.3x
  trig 0     clean         const      27.22  22  45.7  lvm  load cell+enc+Fn  A 7.2 % N0, f_t 3.92 fn, f_t/f_ss 18.24 (F twin +5.7 %)
  trig 1     hum           const      13.58  39  35.4  csv  laser+encoder      A 4.7 %, 4.10 fn, 20.74 (+9.6 %)
  trig 2     drift         const      25.04  25  44.5  semi laser+enc+Fn      A 7.3 %, 6.09 fn, 19.33 (+5.2 %)
  trig 3     spikes        recip      10.07  46  36.0  ws   load cell+encoder  A 4.3 %, 4.51 fn, 13.78 (+5.1 %)
  trig 4     quantisation  const      25.58  33  51.0  lvm  laser+enc+Fn      A 5.9 %, 5.96 fn, 30.50 (-0.8 %)
  trig 5     coarse        const      11.30  36  11.0  csv  load cell+encoder  A 6.1 %, 2.98 fn, 17.80 (+4.5 %)
  trig 6     fn_off        const      21.52  23  76.2  semi laser+enc+Fn      A 5.2 %, 6.80 fn, 21.45 (+0.8 %)
  trig 7     clean         recip       5.82  46  24.8  ws   laser+encoder      A 5.2 %, 5.26 fn, 20.43 (+3.7 %)
  mod 0      clean         modulated   4.52  39  97.9  semi load cell+Fn,--v0 a 0.270, fm/f_ss 0.213
  mod 1      hum           modulated   8.43  32  66.9  ws   load cell, --v0    a 0.230, 0.407
  mod 2      drift         modulated  12.14  29  38.7  lvm  load cell, --v0    a 0.242, 0.452
  mod 3      spikes        modulated   6.25  37  26.6  csv  load cell+Fn,--v0 a 0.410, 0.302
  mod 4      quantisation  modulated   9.43  39  70.9  semi load cell, --v0    a 0.253, 0.296
  mod 5      coarse        modulated  21.50  27  12.6  ws   load cell, --v0    a 0.279, 0.462
  mod 6      fn_off        modulated   8.53  21  59.3  lvm  load cell, --v0    a 0.269, 0.460
  mod 7      clean         modulated  21.17  39  22.9  csv  load cell, --v0    a 0.374, 0.342

WHAT `none` CONTAINS. The law's own hysteresis: the contact's friction is exactly single-valued (F = N mu(|u|) at
the end-of-step speed; measured twin -0.03..0.00 % of the drop on every record without a twin, load or shaker); a
1-DoF reading of ideal samples sees -0.7..+0.4 % (central differences), of the noise-free sensor outputs
(laser lag, load-cell low-pass) -0.5..+0.4 %. No ageing in the law: on the stepped and reciprocating `none`
records (sticks 4.9-9.8x apart) the peak grows -0.1..+0.4 % of the drop (texture scatter); the peaks scatter by
0.4-1.3 % of the drop (sd, the counterface texture). The stage is not an ideal drive: its speed deviates from the
command by 4-21 % of v0 at most (the surge after each slip, largest at the slow level of a stepped drive;
rms 0.8-3.2 %) and its position by 0.2-1.3 % of the slip length; the records with the encoder carry it, those with
--v0 do not. The load is exactly constant. The load_variation and triggering records' F/N is single-valued
(twin -0.02..+0.00 %); their force twin (+-3 %, up to +10 % with the shaker: the breakaways sit in its troughs)
comes from N alone.
"""
import math
import os
import zlib

import numpy as np
from scipy.signal import lfilter

NAME = "moreau_stage"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
TWO_PI = 2.0 * math.pi
_STEP_REFINE = 1.0          # a convergence check multiplies the steps per period (1: the records)


def _rng(*keys):
    s = "|".join(str(k) for k in (NAME,) + tuple(keys))
    return np.random.default_rng([zlib.crc32(s.encode()), zlib.adler32(s.encode()), len(s)])


# ----------------------------------------------------------------------------------------------
# friction law: a sum of smooth tanh (logistic) steps in the sliding speed v itself
# ----------------------------------------------------------------------------------------------
class _Law:
    """mu(v) = mu_b + sum_i A_i (1 + tanh((v - c_i)/w_i))/2 + eta v, v >= 0 the sliding speed (m/s);
    static level mu_s > mu(0+). Single-valued, of general non-monotone shape."""

    def __init__(self, mu_b, pieces, eta, mu_s):
        self.mu_b = float(mu_b)
        self.pieces = [(float(a), float(c), float(w)) for a, c, w in pieces]
        self.eta = float(eta)
        self.mu_s = float(mu_s)

    def scaled(self, f):
        """The same shape with all speeds multiplied by f."""
        return _Law(self.mu_b, [(a, c * f, w * f) for a, c, w in self.pieces], self.eta / f, self.mu_s)

    def mu(self, v):
        s = self.mu_b + self.eta * v
        for a, c, w in self.pieces:
            s += 0.5 * a * (1.0 + math.tanh((v - c) / w))
        return s

    def mu_d(self, v):
        s = self.mu_b + self.eta * v
        d = self.eta
        for a, c, w in self.pieces:
            t = math.tanh((v - c) / w)
            s += 0.5 * a * (1.0 + t)
            d += 0.5 * a * (1.0 - t * t) / w
        return s, d

    def mu_vec(self, v):
        v = np.asarray(v, float)
        s = self.mu_b + self.eta * v
        for a, c, w in self.pieces:
            s = s + 0.5 * a * (1.0 + np.tanh((v - c) / w))
        return s

    def dmu_vec(self, v):
        v = np.asarray(v, float)
        d = self.eta + 0.0 * v
        for a, c, w in self.pieces:
            t = np.tanh((v - c) / w)
            d = d + 0.5 * a * (1.0 - t * t) / w
        return d


def _draw_law(rng, N0, m, w0):
    """Pieces drawn in units of the slip-speed scale V = Wt N0 / (m w0) (Wt the weakening depth), returned in SI."""
    mu_b = rng.uniform(0.30, 0.58)
    Wt = rng.uniform(0.06, 0.13)                     # weakening depth
    V = Wt * N0 / (m * w0)
    f1 = rng.uniform(0.35, 0.7)
    pieces = [(-f1 * Wt, rng.uniform(0.0, 0.05), rng.uniform(0.035, 0.07)),
              (-(1.0 - f1) * Wt, rng.uniform(0.14, 0.32), rng.uniform(0.05, 0.12))]
    G = rng.uniform(0.35, 0.9) * Wt                   # strengthening above the minimum
    pieces.append((G, rng.uniform(0.6, 1.15), rng.uniform(0.12, 0.3)))
    shoulder = bool(rng.uniform() < 0.5)
    if shoulder:                                      # a plateau (shoulder) on the weakening branch
        Hs = rng.uniform(0.12, 0.3) * (1.0 - f1) * Wt
        c4 = rng.uniform(0.06, 0.14)
        pieces.append((Hs, c4, 0.03))
        pieces.append((-Hs, c4 + rng.uniform(0.1, 0.2), 0.04))
    eta = rng.uniform(0.0, 0.04) * Wt                 # per unit V
    tmp = _Law(mu_b, pieces, eta, 1.0)
    mu0 = tmp.mu(0.0)
    gap = rng.uniform(0.12, 0.35) * Wt                # static level above mu(0+)
    si = [(a, c * V, w * V) for a, c, w in pieces]
    law = _Law(mu_b, si, eta / V, mu0 + gap)
    vv = np.linspace(0.0, 3.0 * V, 3001)
    mv = law.mu_vec(vv)
    imin = int(np.argmin(mv))
    info = {"mu_b": float(mu_b), "weakening_depth": float(Wt), "V_m_per_s": float(V),
            "pieces_in_V": [[float(x) for x in p] for p in pieces],
            "eta_per_V": float(eta), "shoulder": shoulder, "mu_0plus": float(mu0), "mu_s": float(mu0 + gap),
            "static_gap": float(gap), "mu_min": float(mv[imin]), "v_min_over_V": float(vv[imin] / V),
            "mu_at_3V": float(mv[-1]),
            "max_weakening_slope": float(-law.dmu_vec(vv).min())}
    return law, V, info


# ----------------------------------------------------------------------------------------------
# drive schedules (the stage's commanded speed on the step grid)
# ----------------------------------------------------------------------------------------------
def _speed_profile(segments, t, v_init=0.0):
    """segments: list of (t_start, v_target, ramp_time). Piecewise: linear ramp from the current speed."""
    v = np.full(t.shape, v_init)
    cur = v_init
    for i, (ts, vt, tr) in enumerate(segments):
        te = segments[i + 1][0] if i + 1 < len(segments) else np.inf
        m = (t >= ts) & (t < te)
        tt = t[m] - ts
        if tr > 0:
            v[m] = np.where(tt < tr, cur + (vt - cur) * tt / tr, vt)
        else:
            v[m] = vt
        # speed reached at the end of this segment
        if te - ts < tr:
            cur = cur + (vt - cur) * (te - ts) / tr
        else:
            cur = vt
    return v


# ----------------------------------------------------------------------------------------------
# Moreau-Jean time stepping of the coupled slider / stage / PID system
# ----------------------------------------------------------------------------------------------
def _simulate(P, law, t_end, vc, xc, mode, stop_after=None, shaker=None, slip_min=0.0):
    """Fixed-step theta-method Moreau-Jean scheme.

    State y = [x_m, v_m, x_s, v_s, I] (slider, stage, PID integral), linear between contact impulses:
      y' = A y + b(t),  the friction impulse p enters v_m only.
    Per step: (I - h th A) y1 = (I + h (1-th) A) y0 + h (th b1 + (1-th) b0) + e_vm p/m
      -> y1 = y_free + g p,  u = v_m1 = u_free + w p (w the Delassus scalar of the coupled system).
    The contact law is set-valued at u = 0: |p| <= h N mu_s (stick, u = 0 exactly) else
      p = -sign(u) h N mu(|u|) with u solved from |u| + w h N mu(|u|) = |u_free| (safeguarded Newton).
    """
    h = P["h"]
    th = P["theta"]
    m, k, c, M = P["m"], P["k"], P["c"], P["M"]
    Kp, Kd, Ki, cs = P["Kp"], P["Kd"], P["Ki"], P["cs"]
    A = np.array([[0, 1, 0, 0, 0],
                  [-k / m, -c / m, k / m, c / m, 0],
                  [0, 0, 0, 1, 0],
                  [k / M, c / M, -(Kp + k) / M, -(Kd + c + cs) / M, Ki / M],
                  [0, 0, -1, 0, 0]], float)
    I5 = np.eye(5)
    Ainv = np.linalg.inv(I5 - h * th * A)
    B1 = Ainv @ (I5 + h * (1 - th) * A)
    g = Ainv[:, 1] / m
    w = g[1]
    qcog = h * Ainv[:, 3] / M
    nst = len(vc)
    Ad = h * Ainv

    def forcing(n0, n1):
        """h Ainv (th b_{n} + (1-th) b_{n-1}) for steps n0..n1-1, as a list of rows."""
        i0 = max(n0 - 1, 0)
        bx = xc[i0:n1]
        bv = vc[i0:n1]
        bb = np.zeros((5, len(bx)))
        bb[3] = (Kp * bx + Kd * bv) / M
        bb[4] = bx
        dd = Ad @ (th * bb[:, 1:] + (1 - th) * bb[:, :-1])
        if n0 == 0:
            dd = np.concatenate([np.zeros((5, 1)), dd], axis=1)
        return dd.T.tolist()
    (b00, b01, b02, b03, b04), (b10, b11, b12, b13, b14), (b20, b21, b22, b23, b24), \
        (b30, b31, b32, b33, b34), (b40, b41, b42, b43, b44) = B1.tolist()
    g0, g1, g2, g3, g4 = g.tolist()
    q0, q1, q2, q3, q4 = qcog.tolist()
    Acog, kcog = P["cog_amp"], TWO_PI / P["cog_pitch"]
    N0 = P["N0"]
    mus0 = law.mu_s
    mud = law.mu_d
    # effects
    eff = mode
    lin = P.get("load_lin", 0.0)
    xmid = P.get("load_xmid", 0.0)
    wav_a = P.get("load_wave_amp", 0.0)
    wav_k = TWO_PI / P["load_wave_len"] if P.get("load_wave_len") else 0.0
    wav_p = P.get("load_wave_phase", 0.0)
    Gh = P.get("twin_gain", 0.0)
    tau_h = P.get("twin_tau", 1.0)
    eh = math.exp(-h / tau_h)
    Vn = P["V"]
    b_age = P.get("age_b", 0.0)
    tau_a = P.get("age_tau", 1.0)
    if shaker is not None:
        sh_a, sh_w = shaker
    else:
        sh_a, sh_w = 0.0, 0.0
    # the counterface's texture: a static level varying along the track (knots every tex_dx, linear between)
    tex = P.get("_texture")
    if tex is not None and P.get("texture_sd", 0.0) > 0.0:
        tex_x0, tex_il = P["texture_x0"], 1.0 / P["texture_dx"]
        tex = list(tex)
        tex_n = len(tex) - 1
    else:
        tex_x0, tex_il, tex_n = 0.0, 1.0, 0
    nmax = min(nst - 1, int(round(t_end / h)))
    X = [0.0] * (nmax + 1)
    U = [0.0] * (nmax + 1)
    XS = [0.0] * (nmax + 1)
    VS = [0.0] * (nmax + 1)
    FC = [0.0] * (nmax + 1)
    NN = [N0] * (nmax + 1)
    y0 = y1 = y2 = y3 = y4 = 0.0
    chi = 0.0
    age = 0.0
    a_prev = 0.0
    nslip = 0
    slipping = False
    x_start = 0.0
    n_end = nmax
    chunk = 8192
    c0 = 0
    dl = forcing(0, min(chunk, nmax + 1))
    for n in range(1, nmax + 1):
        if n - c0 >= len(dl):
            c0 = n
            dl = forcing(c0, min(c0 + chunk, nmax + 1))
        dn = dl[n - c0]
        fc = Acog * math.sin(kcog * y2)
        f0 = b00 * y0 + b01 * y1 + b02 * y2 + b03 * y3 + b04 * y4 + dn[0] + q0 * fc
        f1 = b10 * y0 + b11 * y1 + b12 * y2 + b13 * y3 + b14 * y4 + dn[1] + q1 * fc
        f2 = b20 * y0 + b21 * y1 + b22 * y2 + b23 * y3 + b24 * y4 + dn[2] + q2 * fc
        f3 = b30 * y0 + b31 * y1 + b32 * y2 + b33 * y3 + b34 * y4 + dn[3] + q3 * fc
        f4 = b40 * y0 + b41 * y1 + b42 * y2 + b43 * y3 + b44 * y4 + dn[4] + q4 * fc
        # normal load at the start of the step
        if eff == 0:
            N = N0
        else:
            N = N0
            if lin != 0.0:
                N = N * (1.0 + lin * (y0 - xmid))
            if wav_a != 0.0:
                N = N * (1.0 + wav_a * math.sin(wav_k * y0 + wav_p))
            if sh_a != 0.0:
                N = N * (1.0 + sh_a * math.sin(sh_w * n * h))
        scale = 1.0 + chi
        mus = mus0 + b_age * math.log1p(age / tau_a) if b_age else mus0
        if tex_n:
            z = (y0 - tex_x0) * tex_il
            iz = int(z)
            if 0 <= iz < tex_n:
                fz = z - iz
                mus += tex[iz] * (1.0 - fz) + tex[iz + 1] * fz
        K = w * h * N * scale
        uf = f1
        auf = abs(uf)
        if auf <= K * mus:
            p = -uf / w
            u = 0.0
            a = 0.0
        else:
            s = 1.0 if uf > 0 else -1.0
            lo, hi = 0.0, auf
            a = a_prev if 0.0 < a_prev < auf else 0.5 * auf
            for _ in range(40):
                mu, dmu = mud(a)
                gfun = a + K * mu - auf
                if gfun > 0:
                    hi = a
                else:
                    lo = a
                dg = 1.0 + K * dmu
                an = a - gfun / dg if dg > 0 else 0.5 * (lo + hi)
                if not (lo < an < hi):
                    an = 0.5 * (lo + hi)
                if abs(an - a) <= 1e-13 * auf:
                    a = an
                    break
                a = an
            mu = law.mu(a)
            p = -s * h * N * scale * mu
            u = s * a
        y0 = f0 + g0 * p
        y1 = u
        y2 = f2 + g2 * p
        y3 = f3 + g3 * p
        y4 = f4 + g4 * p
        Fc = -p / h
        if Gh:
            chi = chi * eh + (1.0 - eh) * tau_h * Gh * abs(Fc) * a / (N0 * Vn)
        if u == 0.0:
            age += h
            if slipping:
                slipping = False
                if abs(y0 - x_start) > slip_min:
                    nslip += 1
        else:
            age = 0.0
            if not slipping:
                slipping = True
                x_start = y0
                if stop_after is not None and nslip >= stop_after:
                    n_end = n - 1
                    break
        a_prev = a
        X[n] = y0
        U[n] = y1
        XS[n] = y2
        VS[n] = y3
        FC[n] = Fc
        NN[n] = N
    n_end = min(n_end, nmax)
    sl = slice(0, n_end + 1)
    out = {"t": np.arange(n_end + 1) * h, "xm": np.array(X[sl]), "vm": np.array(U[sl]),
           "xs": np.array(XS[sl]), "vs": np.array(VS[sl]), "Fc": np.array(FC[sl]), "N": np.array(NN[sl]),
           "vc": vc[:n_end + 1], "xc": xc[:n_end + 1]}
    out["Fc"][0] = out["Fc"][1]
    out["N"][0] = out["N"][1]
    out["e"] = out["xs"] - out["xm"]
    out["Fs"] = k * out["e"] + c * (out["vs"] - out["vm"])
    return out


# ----------------------------------------------------------------------------------------------
# ground-truth measurements on the simulated contact
# ----------------------------------------------------------------------------------------------
def _slips(u, n_merge):
    mv = u != 0.0
    if not mv.any():
        return []
    dm = np.diff(mv.astype(np.int8))
    st = list(np.flatnonzero(dm == 1) + 1)
    en = list(np.flatnonzero(dm == -1) + 1)
    if mv[0]:
        st = [0] + st
    if mv[-1]:
        en = en + [len(u)]
    runs = []
    for a, b in zip(st, en):
        if runs and a - runs[-1][1] < n_merge:
            runs[-1][1] = b
        else:
            runs.append([a, b])
    return runs


def _slip_table(S, P):
    h = P["h"]
    runs = _slips(S["vm"], max(2, int(0.03 * P["Tn"] / h)))
    rows = []
    for a, b in runs:
        if a < 2 or b >= len(S["vm"]) - 1:
            continue
        dist = abs(S["xm"][b] - S["xm"][a - 1])
        rows.append((a, b, dist))
    if not rows:
        return []
    dmed = np.median([r[2] for r in rows])
    out = []
    prev_end = None
    for a, b, dist in rows:
        if dist < 0.15 * dmed:
            prev_end = b
            continue
        Fk = P["k"] * S["e"]
        peak = abs(Fk[a - 1])
        drop = abs(Fk[a - 1] - Fk[b])
        tst = (a - prev_end) * h if prev_end is not None else np.nan
        out.append({"a": a, "b": b, "dist": dist, "peak": peak, "drop": drop, "t_stick": tst,
                    "t0": a * h, "N": S["N"][a - 1]})
        prev_end = b
    return out


def _fss(rows):
    """The stick-slip rate: 1 / the mean interval between breakaways, intervals longer than 1.5x the median
    (a reversal, a hold, a slower level) left out."""
    if len(rows) < 3:
        return None
    dt = np.diff([r["t0"] for r in rows])
    dt = dt[dt <= 1.5 * np.median(dt)]
    return float(1.0 / np.mean(dt))


def _twin_of(u, F, drop):
    U = np.abs(u)
    Fa = np.abs(F)
    if len(U) < 8:
        return np.nan
    im = int(np.argmax(U))
    um = U[im]
    if im < 3 or len(U) - im < 3:
        return np.nan
    ua, fa = U[:im + 1], Fa[:im + 1]
    ud, fd = U[im:][::-1], Fa[im:][::-1]
    oa, od = np.argsort(ua, kind="stable"), np.argsort(ud, kind="stable")
    grid = np.linspace(0.15, 0.85, 36) * um
    return float(np.mean(np.interp(grid, ud[od], fd[od]) - np.interp(grid, ua[oa], fa[oa])) / drop)


def _twin_1dof(xm, e, P, rows, force=None):
    """The twin a 1-DoF reading sees: friction = k e + c e' - m xm'' from samples at 100 per Tn
    (central differences), F against the slider speed, decelerating minus accelerating half."""
    h = P["h"]
    step = max(1, int(round(P["Tn"] / (100.0 * h))))
    xs_ = xm[::step]
    es_ = e[::step]
    dt = step * h
    vm = np.gradient(xs_, dt)
    am = np.gradient(vm, dt)
    if force is None:
        Fr = P["k"] * es_ + P["c"] * np.gradient(es_, dt) - P["m"] * am
    else:
        Fr = force[::step] - P["m"] * am
    tw = []
    for r in rows:
        i0, i1 = r["a"] // step, r["b"] // step + 1
        if i1 - i0 >= 8:
            tw.append(_twin_of(vm[i0:i1], Fr[i0:i1], r["drop"]))
    tw = np.array([x for x in tw if np.isfinite(x)])
    return float(np.median(tw)) if len(tw) else None


def _truth(S, P, rows, fs_rec, sched_kind):
    T = {}
    if len(rows) < 3:
        T["n_slips"] = len(rows)
        return T
    drops = np.array([r["drop"] for r in rows])
    T["n_slips"] = len(rows)
    T["drop_median_N"] = float(np.median(drops))
    T["slip_distance_median_m"] = float(np.median([r["dist"] for r in rows]))
    t0 = np.array([r["t0"] for r in rows])
    T["f_ss_hz"] = _fss(rows)
    T["f_ss_overall_hz"] = float((len(t0) - 1) / (t0[-1] - t0[0]))
    # twin at the contact (friction force vs sliding speed, decelerating minus accelerating half)
    tw = [_twin_of(S["vm"][r["a"]:r["b"]], S["Fc"][r["a"]:r["b"]], r["drop"]) for r in rows]
    tw = np.array([x for x in tw if np.isfinite(x)])
    T["twin_contact_median"] = float(np.median(tw)) if len(tw) else None
    # twin of F/N (the coefficient), for the varying-load cases
    twn = [_twin_of(S["vm"][r["a"]:r["b"]], S["Fc"][r["a"]:r["b"]] / S["N"][r["a"]:r["b"]] * P["N0"], r["drop"])
           for r in rows]
    twn = np.array([x for x in twn if np.isfinite(x)])
    T["twin_coefficient_median"] = float(np.median(twn)) if len(twn) else None
    # a 1-DoF reading of ideal (noise-free, unfiltered) samples at 100 per Tn: friction = k e + c e' - m xm''
    T["twin_1dof_median"] = _twin_1dof(S["xm"], S["e"], P, rows)
    # normal load
    N = S["N"]
    T["load_pp_over_N0"] = float((N.max() - N.min()) / P["N0"])
    # peaks vs stick time
    ts = np.array([r["t_stick"] for r in rows])
    pk = np.array([r["peak"] for r in rows])
    ok = np.isfinite(ts) & (ts > 0)
    if ok.sum() >= 4:
        tso, pko = ts[ok], pk[ok]
        T["stick_time_range"] = float(tso.max() / tso.min())
        if T["stick_time_range"] > 1.5:
            sl = np.polyfit(np.log(tso), pko, 1)[0]
            T["peak_growth_over_drop"] = float(sl * math.log(tso.max() / tso.min()) / np.median(drops))
            ilo, ihi = int(np.argmin(tso)), int(np.argmax(tso))
            T["peak_growth_minmax_over_drop"] = float((pko[ihi] - pko[ilo]) / np.median(drops))
        else:
            T["peak_growth_over_drop"] = None
        short = tso <= 1.2 * np.median(tso)
        T["peak_sd_over_drop"] = float(np.std(pko[short]) / np.median(drops)) if short.sum() > 2 else None
    # stage: following and speed ripple in the constant-speed parts
    h = P["h"]
    vc = S["vc"]
    vs = S["vs"]
    vabs = np.max(np.abs(vc)) if np.max(np.abs(vc)) > 0 else 1.0
    steady = np.zeros(len(vc), bool)
    dv = np.abs(np.diff(vc, prepend=vc[0]))
    # steady: commanded speed constant over the last Tn
    nT = int(P["Tn"] / h)
    const = dv < 1e-12 * vabs
    cs = np.convolve(const.astype(float), np.ones(nT), mode="full")[:len(vc)]
    steady = (cs >= nT - 0.5) & (np.abs(vc) > 0)
    if sched_kind == "modulated":
        steady[:] = False
    if steady.any():
        rel = (vs[steady] - vc[steady]) / np.abs(vc[steady])
        T["stage_speed_dev_max"] = float(np.max(np.abs(rel)))
        T["stage_speed_dev_rms"] = float(np.sqrt(np.mean(rel ** 2)))
        T["stage_follow_err_max_over_slipdist"] = float(
            np.max(np.abs(S["xc"][steady] - S["xs"][steady])) / T["slip_distance_median_m"])
    return T


# ----------------------------------------------------------------------------------------------
# record writing
# ----------------------------------------------------------------------------------------------
_UNIT = {"s": 1.0, "ms": 1e3, "m": 1.0, "mm": 1e3, "um": 1e6, "N": 1.0, "mN": 1e3}


def _decimals(step_in_unit):
    if step_in_unit <= 0:
        return 6
    return int(min(10, max(0, math.ceil(-math.log10(step_in_unit)))))


def _fmt_cols(cols, decimal_comma=False):
    """cols: list of (values array, decimals). Returns a list of row strings (no separator yet)."""
    strs = []
    for vals, dec in cols:
        s = np.char.mod("%%.%df" % dec, vals)
        if decimal_comma:
            s = np.char.replace(s, ".", ",")
        strs.append(s)
    return strs


def _write(path, fmt, time_s, chans, meta):
    """chans: list of dict(name, unit, values (SI), step (SI, for the number of decimals))."""
    lines = []
    tunit = "s" if fmt == "lvm" else meta["time_unit"]
    tv = time_s * _UNIT[tunit]
    dt_u = (time_s[1] - time_s[0]) * _UNIT[tunit]
    cols = [(tv, max(_decimals(dt_u / 1000.0), 3))]
    for ch in chans:
        f = _UNIT[ch["unit"]]
        cols.append((ch["values"] * f, _decimals(ch["step"] * f)))
    n = len(tv)
    if fmt == "lvm":
        strs = _fmt_cols(cols)
        sep = "\t"
        date = meta["date"].replace("-", "/")
        hdr = ["LabVIEW Measurement\t", "Writer_Version\t2", "Reader_Version\t2", "Separator\tTab",
               "Decimal_Separator\t.", "Multi_Headings\tNo", "X_Columns\tOne", "Time_Pref\tRelative",
               "Operator\t%s" % meta["operator"], "Description\t%s" % meta["description"],
               "Date\t%s" % date, "Time\t%s" % meta["clock"], "***End_of_Header***\t", "\t"]
        two = meta["lvm_two_headers"]
        if two:
            nc = len(chans)
            hdr += ["Channels\t%d\t" % nc,
                    "Samples\t" + "\t".join([str(n)] * nc) + "\t",
                    "Date\t" + "\t".join([date] * nc) + "\t",
                    "Time\t" + "\t".join([meta["clock"]] * nc) + "\t",
                    "Y_Unit_Label\t" + "\t".join(ch["unit"] for ch in chans) + "\t",
                    "X_Dimension\t" + "\t".join(["Time"] * nc) + "\t",
                    "Unit_X\t" + "\t".join(["s"] * nc) + "\t",
                    "X0\t" + "\t".join(["0.0000000000000000E+0"] * nc) + "\t",
                    "Delta_X\t" + "\t".join(["%.9g" % (time_s[1] - time_s[0])] * nc) + "\t",
                    "***End_of_Header***\t"]
            names = [ch["name"] for ch in chans]
        else:
            hdr.insert(8, "Unit_X\ts")
            names = ["%s (%s)" % (ch["name"], ch["unit"]) for ch in chans]
        lines = hdr + ["X_Value\t" + "\t".join(names) + "\tComment"]
        body = strs[0]
        for s in strs[1:]:
            body = np.char.add(np.char.add(body, sep), s)
        lines += body.tolist()
    elif fmt == "csv":
        strs = _fmt_cols(cols)
        names = ["%s [%s]" % (meta["time_name"], tunit)] + ["%s [%s]" % (ch["name"], ch["unit"]) for ch in chans]
        lines = [",".join(names)]
        body = strs[0]
        for s in strs[1:]:
            body = np.char.add(np.char.add(body, ","), s)
        lines += body.tolist()
    elif fmt == "semi":
        strs = _fmt_cols(cols, decimal_comma=True)
        br = meta["bracket"]
        names = [br % (meta["time_name"], tunit)] + [br % (ch["name"], ch["unit"]) for ch in chans]
        lines = []
        if meta["semi_preamble"]:
            lines += ["Messung;%s;%s" % (meta["date"], meta["clock"]), "Abtastrate;%s;Hz" %
                      ("%.6g" % (1.0 / (time_s[1] - time_s[0]))).replace(".", ","), ""]
        lines.append(";".join(names))
        body = strs[0]
        for s in strs[1:]:
            body = np.char.add(np.char.add(body, ";"), s)
        lines += body.tolist()
    else:  # whitespace with a comment preamble
        strs = _fmt_cols(cols)
        cc = meta["comment_char"]
        names = [(meta["time_name"], tunit)] + [(ch["name"], ch["unit"]) for ch in chans]
        lines = ["%s %s" % (cc, meta["description"]), "%s date %s %s, operator %s" % (cc, meta["date"], meta["clock"],
                                                                                      meta["operator"]),
                 "%s sample rate %.6g Hz" % (cc, 1.0 / (time_s[1] - time_s[0]))]
        for extra in meta.get("extra_lines", []):
            lines.append("%s %s" % (cc, extra))
        if meta["ws_header"] == "commented":
            lines.append("%s columns: " % cc + ", ".join("%d %s (%s)" % (i + 1, a, b) for i, (a, b) in enumerate(names)))
            lines.append("%s " % cc + "  ".join("%s[%s]" % (a.replace(" ", "_"), b) for a, b in names))
        else:
            lines.append("  ".join("%s[%s]" % (a.replace(" ", "_"), b) for a, b in names))
        widths = [max(len(s[0]), len(s[-1])) + 2 for s in strs]
        body = np.char.rjust(strs[0], widths[0])
        for s, wd in zip(strs[1:], widths[1:]):
            body = np.char.add(body, np.char.rjust(s, wd))
        lines += body.tolist()
    with open(path, "w", newline="\n") as fh:
        fh.write("\n".join(lines) + "\n")


# ----------------------------------------------------------------------------------------------
# the record
# ----------------------------------------------------------------------------------------------
def _onepole(x, fc, h):
    a = math.exp(-TWO_PI * fc * h)
    y = lfilter([1.0 - a], [1.0, -a], x - x[0]) + x[0]
    return y


def _build(case, seed):
    rng = _rng("phys", case, seed)
    P = {}
    # friction law (its speeds scale with V = (weakening depth) N0 / (m w0): drawn at V = Wt, rescaled below)
    law, V1, linfo = _draw_law(rng, 1.0, 1.0, 1.0)
    if case == "triggering":
        # the shaker's amplitude; the static level kept 2.4 A mu_s above mu(0+) so that a slip the shaker
        # starts in a trough is not arrested by the next crest (no micro-slips)
        P["shaker_amp"] = float(rng.uniform(0.035, 0.075))
        need = law.mu(0.0) + 2.4 * P["shaker_amp"] * law.mu_s
        if law.mu_s < need:
            law.mu_s = need
            linfo["mu_s"] = float(need)
            linfo["static_gap"] = float(need - linfo["mu_0plus"])
            linfo["static_gap_raised_for_shaker"] = True
    # a bench rig: fn 4-30 Hz, slider 0.1-5 kg, load 3-80 N, drawn until the slip length is 0.08-2.5 mm
    dmu = linfo["mu_s"] - linfo["mu_min"]
    for _ in range(200):
        fn = float(np.exp(rng.uniform(np.log(4.0), np.log(30.0))))
        m = float(np.exp(rng.uniform(np.log(0.1), np.log(5.0))))
        N0 = float(np.exp(rng.uniform(np.log(3.0), np.log(80.0))))
        w0 = TWO_PI * fn
        k = m * w0 * w0
        Dx_t = 2.0 * dmu * N0 / k
        if 8e-5 <= Dx_t <= 2.5e-3:
            break
    V = linfo["weakening_depth"] * N0 / (m * w0)
    law = law.scaled(V / V1)
    linfo["V_m_per_s"] = float(V)
    linfo["max_weakening_slope"] *= V1 / V
    P.update(fn=fn, m=m, k=k, N0=N0, Tn=1.0 / fn, omega=w0, slip_distance_target_m=Dx_t)
    P["zeta"] = float(rng.uniform(0.005, 0.03))
    P["c"] = 2.0 * P["zeta"] * m * w0
    # stage and its PID position loop
    r = float(rng.uniform(5.0, 20.0))
    wc = float(rng.uniform(3.0, 6.0)) * w0
    zc = float(rng.uniform(0.6, 0.9))
    M = r * m
    P.update(M=M, stage_mass_ratio=r, loop_bw_over_omega=wc / w0, loop_zeta=zc)
    P["Kp"] = M * wc * wc
    P["Kd"] = 2.0 * zc * M * wc
    P["Ki"] = P["Kp"] * wc / float(rng.uniform(6.0, 15.0)) if rng.uniform() < 0.5 else 0.0
    P["cs"] = float(rng.uniform(0.01, 0.05)) * 2.0 * M * wc
    P["cog_pitch"] = float(rng.uniform(0.016, 0.048))
    P["V"] = V
    P["cog_amp"] = float(rng.uniform(0.01, 0.04)) * law.mu_s * N0
    P["theta"] = float(rng.uniform(0.5, 0.62))
    # the step: Tn/320 (Tn/400 with the shaker), smaller if the law's steepest weakening needs it
    spt = 400 if case == "triggering" else 320
    Nmax = N0 * 1.5
    h = 1.0 / (fn * spt)
    while linfo["max_weakening_slope"] * h * Nmax / m > 0.6:
        spt += 40
        h = 1.0 / (fn * spt)
    spt = int(spt * _STEP_REFINE)
    h = 1.0 / (fn * spt)
    P["steps_per_Tn"] = spt
    P["h"] = h
    P["law"] = linfo
    # drive
    if case == "drive_modulation":
        kind = "modulated"
    elif case == "static_ageing":
        kind = "recip" if seed % 4 == 3 else ("stepped" if seed % 2 == 0 else "holds")
    elif case == "none":
        kind = "recip" if seed % 4 == 3 else ("stepped" if seed % 8 in (2, 5) else "const")
    else:
        kind = "recip" if seed % 4 == 3 else "const"
    P["drive_kind"] = kind
    return P, law, rng


def _pilot(P, law, v0, nslip, mode=0, extra=None, slip_min=0.0):
    """A short constant-speed run: drop and stick time at v0."""
    Q = dict(P)
    if extra:
        Q.update(extra)
    h = P["h"]
    t_end = P["Tn"] * (4 + nslip * 30)
    t = np.arange(int(t_end / h) + 2) * h
    vc = np.where(t < 0.2 * P["Tn"], v0 * t / (0.2 * P["Tn"]), v0)
    xc = np.concatenate([[0.0], np.cumsum(0.5 * (vc[1:] + vc[:-1]) * h)])
    S = _simulate(Q, law, t_end, vc, xc, mode, stop_after=nslip, slip_min=slip_min)
    rows = _slip_table(S, P)
    return S, rows


def _run(case, seed, nuisance):
    if case not in CASES:
        raise ValueError(case)
    if nuisance not in NUISANCES:
        raise ValueError(nuisance)
    P, law, rng = _build(case, seed)
    fn, k, m, N0, h, Tn = P["fn"], P["k"], P["m"], P["N0"], P["h"], P["Tn"]
    kind = P["drive_kind"]
    mode = 0 if case in ("none", "drive_modulation", "static_ageing", "twin_branch") else 1

    # ---- base drive speed from the wanted stick time (a pilot measures the drop)
    Dx_est = 2.2 * (law.mu_s - P["law"]["mu_min"]) * N0 / k
    n_st = float(rng.uniform(2.5, 6.0)) if case != "twin_branch" else float(rng.uniform(3.0, 6.0))
    v0 = Dx_est / (n_st * Tn)
    S0, rows0 = _pilot(P, law, v0, 4)
    if len(rows0) >= 2:
        drop0 = float(np.median([r["drop"] for r in rows0[1:]]))
    else:
        drop0 = Dx_est * k
    Dx = drop0 / k
    v0 = Dx / (n_st * Tn)
    T_st = n_st * Tn

    # ---- effects
    if case == "twin_branch":
        P["twin_tau"] = float(rng.uniform(0.22, 0.42)) * Tn
        target = float(rng.uniform(0.13, 0.21))
        Wt = P["law"]["weakening_depth"]
        mu_avg = 0.5 * (law.mu_s + P["law"]["mu_min"])
        G = 1.6 * Wt / (mu_avg ** 2 * Tn)
        hist = []
        for it in range(3):
            Sx, rx = _pilot(P, law, v0, 5, mode=0, extra={"twin_gain": G, "twin_tau": P["twin_tau"]})
            tw = [_twin_of(Sx["vm"][r["a"]:r["b"]], Sx["Fc"][r["a"]:r["b"]], r["drop"]) for r in rx[1:]]
            tw = float(np.nanmedian(tw)) if len(tw) else np.nan
            hist.append((G, tw))
            if not np.isfinite(tw) or abs(tw - target) < 0.015:
                break
            if len(hist) >= 2 and abs(hist[-1][1] - hist[-2][1]) > 1e-4:
                (Ga, ta), (Gb, tb) = hist[-2], hist[-1]
                Gn = Gb + (target - tb) * (Gb - Ga) / (tb - ta)
                G = float(np.clip(Gn, 0.3 * Gb, 3.0 * Gb))
            else:
                G = G * target / max(tw, 0.02)
        P["twin_gain"] = G
        P["twin_target"] = target
    if case == "load_variation":
        pp = float(rng.uniform(0.14, 0.34))
        P["load_kind"] = "tilted_rail" if seed % 2 == 0 else "wavy_rail"
        P["load_pp_target"] = pp

    # ---- the drive schedule
    t_pre = float(rng.uniform(0.5, 2.0)) * Tn
    ramp = 0.15 * Tn
    T_ss = T_st + 0.6 * Tn
    segs = [(0.0, 0.0, 0.0)]
    if kind in ("const", "modulated"):
        n_target = int(rng.integers(20, 41))
        t_end = t_pre + (n_target + 3) * T_ss * 1.6 + 20 * Tn
        segs.append((t_pre, v0, ramp))
        stop_after = n_target
    elif kind == "stepped":
        ratio = float(rng.uniform(4.2, 7.8))
        P["step_ratio"] = ratio
        v_hi = v0 * (ratio / 2.2) if ratio > 4.5 else v0 * 1.8
        v_hi = max(v_hi, v0)
        # the fast level keeps >= 1.6 Tn sticks
        v_hi = min(v_hi, Dx / (1.6 * Tn))
        v_lo = v_hi / ratio
        n_lev = int(rng.integers(6, 8))
        t = t_pre
        first_hi = bool(rng.uniform() < 0.5)
        for i in range(n_lev):
            hi = (i % 2 == 0) == first_hi
            v = v_hi if hi else v_lo
            nsl = int(rng.integers(5, 8)) if hi else int(rng.integers(4, 6))
            dur = nsl * (Dx / v + 0.6 * Tn)
            segs.append((t, v, ramp * 2))
            t += dur
        t_end = t
        stop_after = None
        P["v_levels"] = [v_hi, v_lo]
    elif kind == "holds":
        n_runs = int(rng.integers(6, 9))
        t = t_pre
        holds = []
        for i in range(n_runs):
            nsl = int(rng.integers(3, 6))
            segs.append((t, v0, ramp))
            t += nsl * T_ss + float(rng.uniform(0.2, 0.8)) * T_st
            if i < n_runs - 1:
                hd = float(np.exp(rng.uniform(np.log(1.5), np.log(8.0)))) * T_st
                segs.append((t, 0.0, ramp))
                holds.append(hd)
                t += hd
        t_end = t
        stop_after = None
        P["holds_s"] = holds
    else:  # recip: trapezoid strokes with dwells
        n_str = int(rng.integers(4, 7))
        n_tot = float(rng.uniform(22, 40))
        sl_per = int(np.clip(round(n_tot / n_str) - 1, 3, 8))
        acc_frac = float(rng.uniform(0.05, 0.15))
        # each reversal unloads the spring and loads it the other way (2 mu_s N0 / k of stage travel)
        t_rel = 2.0 * law.mu_s * N0 / (k * v0)
        t_const = sl_per * T_ss + t_rel
        t_acc = acc_frac * t_const
        t = t_pre
        dwells = []
        sgn = 1.0
        for i in range(n_str):
            segs.append((t, sgn * v0, t_acc))
            t += t_const + t_acc
            segs.append((t, 0.0, t_acc))
            t += t_acc
            dw = float(rng.uniform(0.5, 5.0)) * T_st if case == "static_ageing" else float(rng.uniform(0.3, 1.5)) * T_st
            dwells.append(dw)
            t += dw
            sgn = -sgn
        t_end = t
        stop_after = None
        P["stroke_accel_s"] = t_acc
        P["dwells_s"] = dwells

    if case == "static_ageing":
        if kind == "stepped":
            t_short, t_long = Dx / P["v_levels"][0], Dx / P["v_levels"][1]
        elif kind == "holds":
            t_short, t_long = T_st, T_st + max(P["holds_s"])
        else:
            t_short, t_long = T_st, 2.0 * T_st + max(P["dwells_s"])
        P["age_tau"] = float(rng.uniform(0.05, 0.25)) * t_short
        g_target = float(rng.uniform(0.07, 0.16))
        lr = math.log((1.0 + t_long / P["age_tau"]) / (1.0 + t_short / P["age_tau"]))
        P["age_b"] = g_target * drop0 / (N0 * lr)
        P["age_growth_target"] = g_target
        mode = 2

    nst = int(t_end / h) + 3
    tg = np.arange(nst) * h
    vc = _speed_profile(segs, tg)
    if kind == "modulated":
        a_m = float(rng.uniform(0.22, 0.43))
        fm_ratio = float(rng.uniform(0.15, 0.42))
        f_ss0 = 1.0 / (Dx / v0 + 0.5 * Tn)
        if len(rows0) >= 3:
            f_ss0 = (len(rows0) - 2) / (rows0[-1]["t0"] - rows0[1]["t0"])
        fm = fm_ratio * f_ss0
        ph = float(rng.uniform(0, TWO_PI))
        on = tg >= t_pre
        vc_base = vc.copy()

        def modulate(fm_):
            return vc_base * np.where(on, 1.0 + a_m * np.sin(TWO_PI * fm_ * (tg - t_pre) + ph), 1.0)
        vc = modulate(fm)
        P.update(mod_a=a_m, mod_fm_hz=fm, mod_phase=ph, mod_fm_target_ratio=fm_ratio)
        t_end = t_pre + (n_target + 3) * (1.0 / f_ss0) * 1.8 + 20 * Tn
    xc = np.concatenate([[0.0], np.cumsum(0.5 * (vc[1:] + vc[:-1]) * h)])
    P["v0"] = v0
    # the counterface's texture (every record): static level + sd * xi(x), knots 0.2-0.6 slip lengths apart
    trng = _rng("texture", case, seed)
    P["texture_sd"] = float(trng.uniform(0.003, 0.012)) * 2.0 * (law.mu_s - P["law"]["mu_min"])
    P["texture_dx"] = float(trng.uniform(0.2, 0.6)) * Dx
    marg = 3.0 * law.mu_s * N0 * 1.5 / k
    P["texture_x0"] = float(xc.min() - marg)
    ntex = int((xc.max() + marg - P["texture_x0"]) / P["texture_dx"]) + 3
    P["_texture"] = P["texture_sd"] * trng.standard_normal(ntex)

    # load geometry along the slider's position (travel known from the command)
    if case == "load_variation":
        travel_lo, travel_hi = float(xc[:int(t_end / h)].min()), float(xc[:int(t_end / h)].max())
        if kind == "const":
            travel_hi = min(travel_hi, v0 * (n_target + 1) * T_ss)
        travel = travel_hi - travel_lo
        pp = P["load_pp_target"]
        if P["load_kind"] == "tilted_rail":
            sgn = 1.0 if rng.uniform() < 0.5 else -1.0
            P["load_lin"] = sgn * pp / travel
            P["load_xmid"] = 0.5 * (travel_lo + travel_hi)
        else:
            lam = float(rng.uniform(2.0, 6.0)) * Dx
            lam = min(lam, travel / 1.2)
            P["load_wave_len"] = lam
            P["load_wave_amp"] = pp / 2.0
            P["load_wave_phase"] = float(rng.uniform(0, TWO_PI))

    # ---- the run (triggering: f_t re-drawn while the record's f_t/f_ss is near an integer)
    if case == "triggering":
        # the slips lock to the shaker's troughs (f_t/f_ss an integer over a range of f_t); f_t is bisected
        # between an n- and an (n+1)-lock on short runs (the record's own start) until the slips mix
        f_ss0 = 1.0 / (Dx / v0 + 0.5 * Tn)
        if len(rows0) >= 3:
            f_ss0 = (len(rows0) - 2) / (rows0[-1]["t0"] - rows0[1]["t0"])
        A = P["shaker_amp"]

        def ratio_of(ft, nsl):
            Sx = _simulate(P, law, t_end, vc, xc, 1, stop_after=nsl, shaker=(A, TWO_PI * ft), slip_min=0.3 * Dx)
            rx = _slip_table(Sx, P)
            f = _fss(rx[1:])
            return (ft / f if f else np.nan), Sx, rx

        def dist(r):
            return abs(r - round(r)) if np.isfinite(r) else 0.0

        lo_ft, hi_ft = 2.5 * fn, 8.0 * fn
        ft = float(rng.uniform(2.6, 7.6)) * fn
        r = ft / f_ss0
        if dist(r) < 0.2:
            ft = (math.floor(r) + 0.5) * f_ss0
            if ft > hi_ft:
                ft -= f_ss0
        tries = []
        npil = 13
        r, Sx, rx = ratio_of(ft, npil)
        tries.append([ft, r])
        if dist(r) < 0.15 and np.isfinite(r):
            # bracket: step f_t away (6 % at a time) until the lock's n changes, then bisect
            n0 = round(r)
            fa, fb, rb = ft, None, None
            for sgn in ((1.0, -1.0) if ft < 0.5 * (lo_ft + hi_ft) else (-1.0, 1.0)):
                for j in range(1, 6):
                    f2 = ft * (1.0 + sgn * 0.06 * j)
                    if not (lo_ft <= f2 <= hi_ft):
                        break
                    r2, Sx, rx = ratio_of(f2, npil)
                    tries.append([f2, r2])
                    if dist(r2) >= 0.15:
                        fb, rb = f2, r2
                        break
                    if round(r2) != n0:
                        fb, rb = f2, r2
                        break
                    fa = f2
                if fb is not None:
                    break
                fa = ft
            if fb is not None and dist(rb) < 0.15:
                ra = n0
                for it in range(9):
                    fm = 0.5 * (fa + fb)
                    rm, Sx, rx = ratio_of(fm, npil)
                    tries.append([fm, rm])
                    if dist(rm) >= 0.15:
                        break
                    if round(rm) == ra:
                        fa = fm
                    else:
                        fb = fm
            ft, r = max(tries, key=lambda q: dist(q[1]))
        cands = sorted(tries, key=lambda q: -dist(q[1]))
        cands = [ft] + [q[0] for q in cands if q[0] != ft][:2]
        best = None
        for fc_ in cands:
            S = _simulate(P, law, t_end, vc, xc, 1, stop_after=stop_after, shaker=(A, TWO_PI * fc_),
                          slip_min=0.3 * Dx)
            rows = _slip_table(S, P)
            f = _fss(rows[1:])
            rr = fc_ / f if f else np.nan
            if best is None or dist(rr) > best[0]:
                best = (dist(rr), fc_, S, rows)
            if dist(rr) >= 0.15:
                break
        _, ft, S, rows = best
        P["shaker_f_hz"] = ft
        P["shaker_tries"] = tries
    else:
        S = _simulate(P, law, t_end, vc, xc, mode, stop_after=stop_after, slip_min=0.3 * Dx)
        rows = _slip_table(S, P)
        if case == "drive_modulation":
            # one correction of fm if the record's own stick-slip rate moved it out of 0.12-0.48
            t0s = [r["t0"] for r in rows]
            f_all = (len(t0s) - 1) / (t0s[-1] - t0s[0])
            P["mod_fm_first_ratio"] = P["mod_fm_hz"] / f_all
            if not (0.12 <= P["mod_fm_hz"] / f_all <= 0.48):
                P["mod_fm_hz"] = fm_ratio * f_all
                vc = modulate(P["mod_fm_hz"])
                xc = np.concatenate([[0.0], np.cumsum(0.5 * (vc[1:] + vc[:-1]) * h)])
                S = _simulate(P, law, t_end, vc, xc, mode, stop_after=stop_after, slip_min=0.3 * Dx)
                rows = _slip_table(S, P)
        if case == "static_ageing":
            # one correction of the ageing's size from the measured growth
            Tq = _truth(S, P, rows, 50.0 * fn, kind)
            gm = Tq.get("peak_growth_over_drop")
            P["age_growth_first_run"] = gm
            if gm is not None and not (0.065 <= gm <= 0.18) and gm > 0.005:
                P["age_b"] *= P["age_growth_target"] / gm
                S = _simulate(P, law, t_end, vc, xc, mode, stop_after=stop_after, slip_min=0.3 * Dx)
                rows = _slip_table(S, P)

    # ---- at most 48 slips in a record: the run is cut in the stick after the 48th
    if len(rows) > 48:
        cut = int(rows[47]["b"] + 0.6 * (rows[48]["a"] - rows[47]["b"]))
        for key in list(S.keys()):
            S[key] = S[key][:cut + 1]
        rows = _slip_table(S, P)
    # ---- ground truth
    fs_spt = float(rng.uniform(10.0, 15.0)) if nuisance == "coarse" else float(np.exp(rng.uniform(np.log(20), np.log(100))))
    fs = fs_spt * fn
    T = _truth(S, P, rows, fs, kind)
    if case == "triggering":
        T["shaker_amp"] = P["shaker_amp"]
        T["ft_over_fn"] = P["shaker_f_hz"] / fn
        T["ft_over_fss"] = P["shaker_f_hz"] / T["f_ss_hz"]
    if case == "drive_modulation":
        # the stage's true speed fitted to v0 (1 + a sin(2 pi fm t + phi)) after the start
        on = S["t"] >= t_pre + 2 * Tn
        tt = S["t"][on]
        Xd = np.column_stack([np.ones(on.sum()), np.sin(TWO_PI * P["mod_fm_hz"] * tt),
                              np.cos(TWO_PI * P["mod_fm_hz"] * tt)])
        cf = np.linalg.lstsq(Xd, S["vs"][on], rcond=None)[0]
        T["mod_a_stage"] = float(math.hypot(cf[1], cf[2]) / cf[0])
        T["fm_over_fss"] = P["mod_fm_hz"] / T["f_ss_overall_hz"]
    if case == "static_ageing":
        T["age_b"] = P.get("age_b")
    P["truth"] = T
    P["rows"] = rows
    return P, law, S, fs, t_pre



_OPERATORS = ["jk", "M. Weber", "lab2", "operator", "A. Rossi", "tribo", "S. Chen", "student"]
_NAMES = {
    "stage": ["Stage Position", "Encoder", "Stage Encoder", "X Stage", "Motor Position", "Stage"],
    "laser": ["Laser Displacement", "Laser", "Slider Position", "LDS Slider", "Laser Sensor", "Slider Laser"],
    "force": ["Load Cell", "Friction Force", "Spring Force", "Fx", "Tangential Force", "Force"],
    "normal": ["Normal Force", "Fz", "Fn", "Normal Load", "Load Fz"],
    "time": ["Time", "time", "t", "Zeit", "Elapsed Time"],
}


def write_record(case, seed, outdir, nuisance="clean"):
    P, law, S, fs, t_pre = _run(case, seed, nuisance)
    ci = CASES.index(case)
    fn, k, N0, h, Tn = P["fn"], P["k"], P["N0"], P["h"], P["Tn"]
    kind = P["drive_kind"]
    T = P["truth"]
    rng = _rng("rec", case, seed)
    nrng = _rng("nuis", case, seed, nuisance)
    drop = T.get("drop_median_N", 1.0)
    Dx = drop / k
    # ---- what the rig records
    rec = "F" if case == "drive_modulation" else ("D" if (seed + ci) % 5 in (0, 1, 3) else "F")
    if rec == "D":
        stage_col = True
    else:
        stage_col = (case == "static_ageing") or kind in ("stepped", "holds", "recip") or \
            (case != "drive_modulation" and rng.uniform() < 0.5)
    if case == "load_variation":
        normal_col = True
    elif case == "triggering":
        normal_col = seed % 2 == 0
    else:
        normal_col = bool(rng.uniform() < 0.25)
    missing = (3 * ci + 1) % 8
    if missing == 6:
        missing = 7
    give_fn = case == "triggering" or seed != missing
    # ---- sampling grid
    t_rec_end = S["t"][-1]
    ns = int(t_rec_end * fs)
    ts = np.arange(ns) / fs
    tg = S["t"]

    def samp(x):
        return np.interp(ts, tg, x)

    chans = []
    fmt = ("lvm", "csv", "semi", "ws")[(seed + 2 * ci) % 4]
    pos_unit = ["mm", "um", "m", "mm"][int(rng.integers(0, 4))]
    f_unit = "mN" if (drop < 3.0 and rng.uniform() < 0.7) or rng.uniform() < 0.2 else "N"
    nm = {key: vals[int(rng.integers(0, len(vals)))] for key, vals in _NAMES.items()}
    sens = {}
    # analog channels (fine grid), their noise, their 'drop' scale (for the nuisances)
    analog = []
    if rec == "D":
        fc_l = float(rng.uniform(150.0, 500.0)) * fn
        off_l = float(rng.uniform(0.005, 0.04))
        xl = _onepole(S["xm"], fc_l, h)
        lz = xl + off_l
        sens.update(laser_lowpass_hz=fc_l, laser_offset_m=off_l)
        T["twin_1dof_sensors_median"] = _twin_1dof(xl, S["xs"] - xl, P, P["rows"])
        analog.append(["laser", lz, Dx, float(rng.uniform(0.001, 0.004)) * Dx])
    else:
        fc_f = float(rng.uniform(15.0, 40.0)) * fn
        ff = _onepole(S["Fs"], fc_f, h)
        fz = ff + float(rng.uniform(-0.01, 0.01)) * drop
        sens.update(loadcell_lowpass_hz=fc_f)
        T["twin_1dof_sensors_median"] = _twin_1dof(S["xs"] - ff / k, ff / k, P, P["rows"], force=ff)
        analog.append(["force", fz, drop, float(rng.uniform(0.001, 0.004)) * drop])
    if normal_col:
        fc_n = float(rng.uniform(10.0, 30.0)) * fn
        analog.append(["normal", _onepole(S["N"], fc_n, h) + float(rng.uniform(-0.003, 0.003)) * N0, drop,
                       float(rng.uniform(0.0005, 0.002)) * N0])
        sens.update(normal_lowpass_hz=fc_n)
    rec_vals = {}
    for name, x, scale, sig in analog:
        y = samp(x) + sig * nrng.standard_normal(ns)
        step = sig
        if nuisance == "hum":
            fl = 50.0 if rng.uniform() < 0.6 else 60.0
            A = float(nrng.uniform(0.01, 0.05)) * scale
            y = y + A * (np.sin(TWO_PI * fl * ts + nrng.uniform(0, TWO_PI))
                         + nrng.uniform(0.2, 0.5) * np.sin(2 * TWO_PI * fl * ts + nrng.uniform(0, TWO_PI))
                         + nrng.uniform(0.1, 0.3) * np.sin(3 * TWO_PI * fl * ts + nrng.uniform(0, TWO_PI)))
            sens.setdefault("hum", {})[name] = {"f_line": fl, "amp_over_drop": A / scale}
        if nuisance == "drift":
            D = float(nrng.uniform(0.02, 0.06)) * scale * (1 if nrng.uniform() < 0.5 else -1)
            tau = float(nrng.uniform(0.3, 1.5)) * ts[-1]
            shape = (1.0 - np.exp(-ts / tau)) / (1.0 - math.exp(-ts[-1] / tau))
            lin = ts / ts[-1]
            wmix = float(nrng.uniform(0, 1))
            y = y + D * (wmix * shape + (1 - wmix) * lin)
            sens.setdefault("drift", {})[name] = D / scale
        if nuisance == "spikes" and name != "normal":
            frac = float(nrng.uniform(0.0005, 0.005))
            nsp = max(2, int(round(frac * ns)))
            idx = nrng.choice(np.arange(5, ns - 5), nsp, replace=False)
            y[idx] += nrng.choice([-1.0, 1.0], nsp) * nrng.uniform(0.3, 1.5, nsp) * scale
            sens["spikes"] = {"channel": name, "n": int(nsp), "fraction": nsp / ns}
        if nuisance == "quantisation":
            q = float(nrng.uniform(0.002, 0.01)) * scale
            y = np.round(y / q) * q
            step = q
            sens.setdefault("quantisation", {})[name] = q / scale
        rec_vals[name] = (y, step)
    if stage_col:
        res = [5e-8, 1e-7, 5e-7, 1e-6][int(rng.integers(0, 4))]
        while res > 0.002 * Dx and res > 5e-9:
            res /= 2.0
        off_s = float(rng.uniform(0.02, 0.25))
        xs = np.round((samp(S["xs"]) + off_s) / res) * res
        rec_vals["stage"] = (xs, res)
        sens.update(encoder_resolution_m=res, encoder_offset_m=off_s)
    # ---- columns in a rig's order
    order = []
    if rec == "D":
        order = ["stage", "laser"] if rng.uniform() < 0.6 else ["laser", "stage"]
    else:
        order = ["force"] + (["stage"] if stage_col else [])
    if normal_col:
        order.insert(int(rng.integers(1, len(order) + 1)), "normal")
    for key in order:
        y, step = rec_vals[key]
        if key in ("stage", "laser"):
            unit = pos_unit
        else:
            unit = "N" if key == "normal" and f_unit == "N" else f_unit
            if key == "normal" and rng.uniform() < 0.5:
                unit = "N"
        nmk = nm[key]
        chans.append({"name": nmk, "unit": unit, "values": y, "step": step * 0.2, "role": key})
    # ---- file
    alt = zlib.crc32(("%s|%d|ext" % (case, seed)).encode()) % 2
    ext = {"lvm": ".lvm", "csv": ".csv", "semi": [".csv", ".txt"][alt], "ws": [".dat", ".txt"][alt]}[fmt]
    os.makedirs(outdir, exist_ok=True)
    path = os.path.abspath(os.path.join(outdir, "%s_%s_s%d_%s%s" % (NAME, case, seed, nuisance, ext)))
    meta = {"time_unit": "ms" if rng.uniform() < 0.35 else "s",
            "time_name": nm["time"],
            "date": "2024-%02d-%02d" % (1 + (seed * 5 + ci) % 12, 1 + (seed * 11 + 3 * ci) % 28),
            "clock": "%02d:%02d:%07.4f" % (8 + seed % 10, (7 * seed + 13 * ci) % 60, (seed * 3.7 + ci) % 60),
            "operator": _OPERATORS[int(rng.integers(0, len(_OPERATORS)))],
            "description": "stick-slip rig, slider on a spring from a linear-motor stage (PID position loop)",
            "lvm_two_headers": bool(rng.uniform() < 0.6),
            "bracket": ["%s [%s]", "%s (%s)", "%s/%s"][int(rng.integers(0, 3))],
            "semi_preamble": bool(rng.uniform() < 0.5),
            "comment_char": "%" if rng.uniform() < 0.5 else "#",
            "ws_header": "commented" if rng.uniform() < 0.5 else "plain",
            "extra_lines": []}
    if rng.uniform() < 0.5:
        meta["extra_lines"].append("spring stiffness %.1f N/m" % k)
    if stage_col:
        meta["extra_lines"].append("stage encoder resolution %.3g um" % (sens["encoder_resolution_m"] * 1e6))
    if rec == "D":
        meta["extra_lines"].append("laser triangulation sensor on the slider (absolute position)")
    _write(path, fmt, ts, chans, meta)
    # ---- what the user passes
    args = []
    fn_given = None
    if give_fn:
        fn_given = fn * (1.0 + (0.05 if nrng.uniform() < 0.5 else -0.05)) if nuisance == "fn_off" else fn
        args += ["--fn", "%.4g" % fn_given]
    if rec == "F":
        args += ["--stiffness", "%.6g" % k]
    if not stage_col:
        args += ["--v0", "%.6g" % (P["v0"] * 1e3)]
    P.pop("rows", None)
    P.pop("_texture", None)
    params = _jsonable(P)
    params["record"] = {"type": "laser+encoder" if rec == "D" else "load cell", "format": fmt,
                        "columns": [(c["name"], c["unit"], c["role"]) for c in chans],
                        "fs_hz": fs, "samples_per_Tn": fs / fn, "n_samples": ns, "sensors": _jsonable(sens),
                        "t_motion_start_s": t_pre}
    return {"generator": NAME, "case": case, "seed": int(seed), "nuisance": nuisance, "file": path,
            "args": args, "fn_true": float(fn), "fn_given": None if fn_given is None else float(fn_given),
            "params": params}


def _jsonable(x):
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, (np.floating,)):
        return float(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, np.ndarray):
        return [_jsonable(v) for v in x.tolist()]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x
