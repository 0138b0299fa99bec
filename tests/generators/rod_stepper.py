"""Independent record generator: a distributed (elastic-rod) slider on a stepper-driven stage, piecewise-linear
friction with a minimum, exact event-driven stick, matrix-exponential propagation.

Written without reading the diagnosis code; numpy/scipy only.  `write_record(case, seed, outdir, nuisance)` (see
README.md here for the contract; `tests/benchmarks/bench_diagnose.py` loads it).  `python rod_stepper.py` runs
the self-check (6 cases x seeds 0-7, nuisance NUISANCES[seed % 7]; ~16 s on one core).

The rig
-------
A stage driven by a stepper motor and a leadscrew moves at vs(t) under a contact (mass M) held by an elastic rod
clamped to the frame.  The rod (mass m_rod = 0.15-0.6 M) is a chain of n = 4-8 lumped masses joined by n springs
n k (series stiffness k) with Kelvin-Voigt material damping (stiffness-proportional: the first free-end mode has
zeta1 = 0.4-1.5 %, a higher mode j zeta1 w_j / w_1); element masses are lumped half to each end, the contact node
carries M + m_rod / (2n).  The recorded signal is NOT at the contact:

* force records: the strain gauge at the clamp, F = n k x_1 (the first element's elastic tension), `--stiffness k`;
* displacement records: a capacitive probe at node j (j = n/2 .. n-1 of n, never the contact) reading x_j n / j,
  i.e. calibrated statically so that it reads the spring extension F/k of a static load.

fn_true is the lowest natural frequency of the undamped chain with the contact SLIDING, i.e. a free end (scipy
eigh of the n x n stiffness and lumped-mass matrices, clamp fixed, contact node free, the friction's slope and
the damping left out): the mode the stick-slip swings on.  The next free mode is at 4.6-8.3 fn; in stick the
contact is held and the rod's own clamped-clamped modes (first one 4.4-8.2 fn) ring after each arrest and
each breakaway.

Friction (the contact on the stage, sliding speed w = x_c' - vs, N the normal load):
    |F_f| = N mu(|w|),  mu = mu0 - s1 |w|  for |w| < vm,   mu_min + s2 (|w| - vm) above   (a minimum at vm)
    static level mu_s (0.35-0.65), mu0 = mu(0+) 12-25 % below it (22-32 % in `static_ageing`): a jump.
The weakening slope s1 is a negative damping of 3-10 % of critical, the strengthening one s2 5-25 %; vm = 0.5-1.2
of the slip-speed scale (mu_s - mu0) N0 / sqrt(k Meff), so the slips cross the minimum.

Stick is exact: in stick the contact moves with the stage (its equation of motion is replaced by x_c'' = vs');
the needed force F_req = M_c vs' + T_n (T_n: the last element's tension) is watched; slip starts when
|F_req| > mu_s N.  A slip ends when w crosses 0: the contact sticks if |F_req| <= mu_s N, else slips the other
way.  Every other switch (|w| crossing vm; the twin's acceleration sign; the drive's ramps) is an event too.

Integrator: between events the state z = (rod and contact positions and speeds, stage position, stage base speed
and acceleration, the stepper ripple's and the drive modulation's oscillator pairs, 1) obeys z' = A_mode z (+ B r),
linear and time-invariant for each friction segment; it is propagated EXACTLY with the matrix exponential of an
augmented block matrix (own scaling-and-squaring [6/6] Pade; cached for the full step h = Tn / 170-200).  Events
are located by Brent's method on the exact sub-step propagation and the step resumes from the event.  The only
non-linear terms, the varying normal load during slip in `load_variation` and `triggering`, enter as a remainder
force r = -(N - N0) sign(w) mu(|w|) by the exponential trapezoidal rule (phi1/phi2 from the same block
exponential, one predictor).  Nothing else is approximated.

The drive: stage speed vs = vb + q + m.  vb steps between levels with short linear ramps (0.08 Tn), each started at
a zero of the ripple; q = r_rip vb sin(2 pi f_step t) is the stepper's velocity ripple in EVERY record, r_rip = 2-5 %,
f_step = vb / lambda (lambda = one full step of the leadscrew) = 8-16 fn at the fastest level (kept 8 % away from
the rod's modes; >= ~10 fss at any level); m is the drive modulation (`drive_modulation` only; its ripple runs at
the step rate of v0n).

Sensor: every analog channel (gauge or probe, normal load) goes through a delta-sigma ADC's sinc^3 (CIC)
decimation filter (three moving averages over the decimation factor, 2-17 internal steps), then amplifier noise,
white (0.08-0.25 % of the drop) plus a random-walk offset (Brownian, 1/f^2; 0.1-0.4 % of the drop end to end), drawn
per channel, and a 24-bit quantiser over +-1.6x full scale.

Cases
-----
* none: constant drive (6 of 8 seeds) or a drive that steps between 3 recorded levels spanning 2.5-5x (seeds 3, 7).
* load_variation: a Hertzian wedge.  The normal load comes from a preloaded ball running on a guide rail slightly
  inclined to the sliding direction (a roller guide: its tangential reaction is neglected), so its compression
  follows the contact's position (= the spring's extension): N = N0 (1 + c (x_c - x_m))^1.5, c > 0 (a rising
  wedge, capped at 0.6 k / (1.5 mu_s N0) so that the stick cannot self-lock), c from short pilots for a
  peak-to-peak of 15-33 % of N0.  A falling wedge (c < 0) was tried and dropped: it shrinks the drop to ~0.2 of
  the peak before N swings by 10 %.  The normal channel is recorded (load cell, or the ball's deflection y [mm]).
* twin_branch: the friction depends on the sign of the contact's sliding acceleration: while |w| decreases (the
  decelerating half) it is higher by D = N0 d_tw; switching is an event on sign(w w'), self-consistent (the jump
  deepens the deceleration: no chatter); d_tw from a pilot (+ up to two corrections) for 11-17 % of the slip's drop.
* static_ageing: contact-area growth, a POWER LAW in the time in stick: mu_s = mu_s0 + b (t_st / Tn)^p, p = 0.25-0.5
  (no logarithm); the stage steps between 3-5 levels spanning 4-8x (odd seeds: also 2 holds at rest of 3-8 stick
  times); b from a pilot for a peak growth of 11-17 % of the drop (and >= 5.5 % of the peak) over the record's
  range of stick times; the drive is recorded (v0 or the stage's position).
* triggering: a shaker on the normal load, N = N0 (1 + a sin(2 pi f_t t + phi)), a = 3.5-7.5 %, f_t = 2.8-7.5 fn with
  f_t / fss (pilot) 0.3-0.7 from an integer; the normal channel is recorded.  The breakaway tends to lock to the
  forcing (it falls on a falling flank of N), which can pull f_t / fss to an integer: the record's own ratio is
  checked and f_t re-drawn (4.5-7.5 fn, up to 7 more runs) while it is within 0.15 of an integer (if all
  lock, the least locked run is kept).
* drive_modulation: vb(t) = v0n (1 + a sin(2 pi fm t + phi)), a = 22-42 %, fm = 0.12-0.45 fss (pilot); `--v0 v0n`.

Records: force (N or mN, `--stiffness k`) or displacement (mm); units in brackets; comma, TAB or whitespace
(then `name[unit]`); `--fn` on 7 of 8 seeds per case (8 of 8 for drive_modulation) -- the true fn, or 5 % off
for `fn_off`; `--v0` or a drive column (v0 [mm/s], or the stage's encoder position [mm]/[um] in force records);
20-100 samples per natural period (10-15 for `coarse`), 15-40 stick-slip cycles (a record is cut at 38).

Measured (self-check, seeds 0-7, from the model's internals; params["measured"] of every record)
----------------------------------------------------------------------------------------------
Effect-free records (`none`): the contact's friction is exactly single-valued (decelerating minus accelerating at
equal speed, 25-85 % of the slip's peak: |.| < 0.0002 of the drop).  The record is not at the contact: a 1-DoF
reading of the perfect gauge signal (x = F/k low-passed at 2.2-3.2 fn below the second mode, f = k x + k x''/wn^2,
w = x' - vs) sees -0.022 .. +0.044 of the drop of double-valuedness (twin_gauge_1dof_over_drop).  The rod's modes
ring in stick by 1.8-4.0 % of the drop (max |F - k x_c| over a stick, median over cycles).  The stepper ripple
(velocity 2-5 % of v0) needs a force M_c r_rip v0 w_step of 0.8-2.1 % of the drop from the stage in stick; the
breakaway locks to it: peak scatter 0.00-0.7 % of the drop.  Stepped `none` drives (seeds 3, 7): peak growth
between the longest and the shortest sticks -0.8 % and -1.6 % of the drop (no ageing in the law).
Departures: load N p-p 0.20-0.34 N0; twin 0.117-0.157 of the drop at the contact (0.10-0.24 in the 1-DoF gauge
view); ageing growth 0.10-0.16 of the drop, 0.058-0.112 of the peak, over stick-time ranges of 5-20x; triggering
a = 0.043-0.069, f_t = 4.7-7.3 fn, f_t / fss = 10.4-26.5 (0.17-0.49 from an integer; on seeds 8-63, 4 of 56
needed all 8 runs and 2 stayed locked, 0.04 and 0.14 from an integer); drive modulation
a = 0.33-0.42, fm = 0.14-0.36 fss of the record.  0.15-0.75 s a record (up to 1.5 s when a triggering record
needs all 8 runs).
"""
import heapq
import json
import math
import os
import time
import zlib

import numpy as np
from scipy.linalg import eigh
from scipy.optimize import brentq
from scipy.signal import butter, filtfilt

NAME = "rod_stepper"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")
TWOPI = 2.0 * math.pi


def _rng(*keys):
    s = "|".join(str(k) for k in (NAME,) + keys)
    return np.random.default_rng([zlib.crc32(s.encode()), len(s)])


def _logu(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# ------------------------------------------------------------------------------------------------ the rig
_PADE6 = (1.0, 0.5, 5.0 / 44.0, 1.0 / 66.0, 1.0 / 792.0, 1.0 / 15840.0, 1.0 / 665280.0)


def _expm(A):
    """Matrix exponential: scaling and squaring with the diagonal [6/6] Pade approximant (||A/2^s||_1 <= 1/2,
    truncation ~1e-17).  Own code: scipy's expm is pathologically slow with a multi-threaded BLAS on small
    matrices (8 ms for 26 x 26)."""
    nrm = float(np.abs(A).sum(axis=0).max())
    s = int(math.ceil(math.log2(nrm / 0.5))) if nrm > 0.5 else 0
    X = A / (2.0 ** s)
    eye = np.eye(A.shape[0])
    X2 = X @ X
    X4 = X2 @ X2
    c = _PADE6
    U = X @ (c[1] * eye + c[3] * X2 + c[5] * X4)
    V = c[0] * eye + c[2] * X2 + c[4] * X4 + c[6] * (X4 @ X2)
    E = np.linalg.solve(V - U, V + U)
    for _ in range(s):
        E = E @ E
    return E


def _decode(mode):
    m = mode - 1
    return (1.0 if m >= 4 else -1.0), (m >> 1) & 1, m & 1


def _encode(sg, r, tw):
    return 1 + (4 if sg > 0 else 0) + 2 * r + tw


class _Rig:
    """Chain of n lumped masses (the rod) clamped before node 0, contact at node n-1; augmented linear state."""

    def __init__(self, P):
        self.P = P
        n = self.n = int(P["n_nodes"])
        self.ke = n * P["k"]
        m = np.full(n, P["m_rod"] / n)
        m[-1] = P["M"] + P["m_rod"] / (2 * n)
        self.m = m
        self.Mc = float(m[-1])
        K = np.zeros((n, n))
        for e in range(n):                      # element e joins node e-1 (the clamp if e == 0) and node e
            K[e, e] += 1.0
            if e > 0:
                K[e - 1, e - 1] += 1.0
                K[e - 1, e] -= 1.0
                K[e, e - 1] -= 1.0
        self.K1 = K
        w2 = eigh(self.ke * K, np.diag(m), eigvals_only=True)
        self.om_free = np.sqrt(w2)
        self.omega1 = float(self.om_free[0])
        w2c = eigh(self.ke * K[:-1, :-1], np.diag(m[:-1]), eigvals_only=True)
        self.om_stuck = np.sqrt(w2c)
        self.ce = 2.0 * P["zeta1"] / self.omega1 * self.ke
        self.iX = np.arange(n)
        self.iV = n + np.arange(n)
        self.ivc = 2 * n - 1
        self.ixc = n - 1
        (self.iS, self.iVB, self.iAB, self.iQ1, self.iQ2, self.iM1, self.iM2,
         self.iONE) = range(2 * n, 2 * n + 8)
        self.nz = 2 * n + 8
        self.B = np.zeros(self.nz)
        self.B[self.ivc] = 1.0 / self.Mc
        self._cache = {}

    def seg(self, r):
        P = self.P
        if r == 0:
            return P["mu0"], -P["s1"]
        mu_min = P["mu0"] - P["s1"] * P["vm"]
        return mu_min - P["s2"] * P["vm"], P["s2"]

    def A(self, mode, om_s, om_m):
        A = np.zeros((self.nz, self.nz))
        A[self.iX, self.iV] = 1.0
        Minv = 1.0 / self.m
        A[np.ix_(self.iV, self.iX)] = -(Minv[:, None] * self.ke * self.K1)
        A[np.ix_(self.iV, self.iV)] = -(Minv[:, None] * self.ce * self.K1)
        A[self.iS, [self.iVB, self.iQ1, self.iM1]] = 1.0
        A[self.iVB, self.iAB] = 1.0
        A[self.iQ1, self.iQ2] = om_s
        A[self.iQ2, self.iQ1] = -om_s
        A[self.iM1, self.iM2] = om_m
        A[self.iM2, self.iM1] = -om_m
        c = self.ivc
        if mode == 0:                            # stick: the contact follows the stage
            A[c, :] = 0.0
            A[c, self.iAB] = 1.0
            A[c, self.iQ2] = om_s
            A[c, self.iM2] = om_m
        else:
            sg, r, tw = _decode(mode)
            c0, c1 = self.seg(r)
            N0 = self.P["N0"]
            g = N0 * c1 / self.Mc
            A[c, c] -= g
            A[c, [self.iVB, self.iQ1, self.iM1]] += g
            A[c, self.iONE] += -sg * N0 * (c0 + self.P["d_tw"] * tw) / self.Mc
        return A

    def blocks(self, mode, lvl, tau, om_s, om_m, cache):
        key = (mode, om_s, om_m, tau)
        if cache and key in self._cache:
            return self._cache[key]
        nz = self.nz
        A = self.A(mode, om_s, om_m)
        Big = np.zeros((nz + 2, nz + 2))
        Big[:nz, :nz] = A * tau
        Big[:nz, nz] = self.B * tau
        Big[nz, nz + 1] = 1.0
        Ex = _expm(Big)
        p1 = Ex[:nz, nz].copy()                  # tau phi1(A tau) B
        p2 = Ex[:nz, nz + 1].copy()              # tau phi2(A tau) B
        out = (Ex[:nz, :nz].copy(), p1 - p2, p2, p1, A[self.ivc].copy())
        if cache:
            self._cache[key] = out
        return out


# ------------------------------------------------------------------------------------------------ simulation
class _Sim:
    """Event-driven exact simulation on a uniform grid of step h.

    drive: dict(levels=[v (m/s)], om_s=[rad/s per level], r_rip, changes=[(t_nominal, level)], t_ramp,
                a_mod, om_m, phi_m, v0n)
    load: dict(kind='const'|'wedge'|'vib', ...)
    """

    def __init__(self, R, drive, load, ageing, twin):
        self.R, self.dr, self.ld, self.ag, self.twin = R, drive, load, ageing, twin
        self.has_rem = load["kind"] != "const"
        self.om_m = drive.get("om_m", 0.0)

    # --- helpers on the state
    def vs(self, z):
        R = self.R
        return z[R.iVB] + z[R.iQ1] + z[R.iM1]

    def as_(self, z):
        R = self.R
        return z[R.iAB] + self.om_s * z[R.iQ2] + self.om_m * z[R.iM2]

    def N(self, t, z):
        ld = self.ld
        if ld["kind"] == "const":
            return ld["N0"]
        if ld["kind"] == "vib":
            return ld["N0"] * (1.0 + ld["a"] * math.sin(ld["om"] * t + ld["phi"]))
        b = 1.0 + ld["c"] * (z[self.R.ixc] - ld["xm"])
        return ld["N0"] * max(b, 0.05) ** 1.5

    def Tn_(self, z):
        R = self.R
        n = R.n
        return R.ke * (z[n - 1] - z[n - 2]) + R.ce * (z[2 * n - 1] - z[2 * n - 2])

    def Freq(self, z):
        return self.R.Mc * self.as_(z) + self.Tn_(z)

    def mus(self, t):
        P = self.R.P
        if self.ag is None:
            return P["mu_s"]
        tst = max(t - self.t_arr, 0.0)
        return P["mu_s"] + self.ag["b"] * (tst / self.ag["Tref"]) ** self.ag["p"]

    def rem(self, t, z, mode):
        if not self.has_rem or mode == 0:
            return 0.0
        sg, r, tw = _decode(mode)
        c0, c1 = self.R.seg(r)
        w = z[self.R.ivc] - self.vs(z)
        return -(self.N(t, z) - self.ld["N0"]) * (sg * (c0 + self.R.P["d_tw"] * tw) + c1 * w)

    def advance(self, z, t, mode, dt, full):
        if full:
            dt = self.h
        E, q0, q1, p1, _ = self.R.blocks(mode, self.lvl, dt, self.om_s, self.om_m, full)
        zl = E @ z
        if self.has_rem and mode != 0:
            r0 = self.rem(t, z, mode)
            r1 = self.rem(t + dt, zl + p1 * r0, mode)
            return zl + q0 * r0 + q1 * r1
        return zl

    def events(self, t, z, mode):
        """Event function values (event fires when > 0)."""
        R = self.R
        if mode == 0:
            return (abs(self.Freq(z)) - self.mus(t) * self.N(t, z),)
        sg, r, tw = _decode(mode)
        w = z[R.ivc] - self.vs(z)
        vm = R.P["vm"]
        g = [-sg * w, (sg * w - vm) if r == 0 else (vm - sg * w)]
        if self.twin:
            arow = R.blocks(mode, self.lvl, self.h, self.om_s, self.om_m, True)[4]
            acc = float(arow @ z) + self.rem(t, z, mode) / R.Mc
            wd = acc - self.as_(z)
            g.append(-sg * wd if tw == 0 else sg * wd)
        return tuple(g)

    # --- drive actions
    def _ramp_start(self, t, z, lvl_new):
        R, dr = self.R, self.dr
        v_old = dr["levels"][self.lvl]
        v_new = dr["levels"][lvl_new]
        z = z.copy()
        z[R.iAB] = (v_new - v_old) / dr["t_ramp"]
        amp = dr["r_rip"] * v_new
        sgn = 1.0 if z[R.iQ2] >= 0 else -1.0
        z[R.iQ1] = 0.0
        z[R.iQ2] = sgn * amp
        self.lvl = lvl_new
        self.om_s = dr["om_s"][lvl_new]
        heapq.heappush(self.sched, (t + dr["t_ramp"], 1, lvl_new))
        return z

    def _ramp_end(self, z, lvl):
        z = z.copy()
        z[self.R.iAB] = 0.0
        z[self.R.iVB] = self.dr["levels"][lvl]
        return z

    def _next_ripple_zero(self, t, z):
        R = self.R
        q1, q2 = z[R.iQ1], z[R.iQ2]
        if abs(q1) + abs(q2) == 0.0:
            return t
        th = math.atan2(q1, q2) % math.pi
        return t + (math.pi - th) / self.om_s if th > 1e-9 else t

    def run(self, t_end, h, lvl0=0):
        R, dr = self.R, self.dr
        self.h = h
        nst = int(math.ceil(t_end / h))
        nz = R.nz
        self.lvl = lvl0
        self.om_s = dr["om_s"][lvl0]
        v = dr["levels"][lvl0]
        z = np.zeros(nz)
        z[R.iVB] = v
        z[R.iQ2] = dr["r_rip"] * v
        am = dr.get("a_mod", 0.0) * dr.get("v0n", v)
        z[R.iM1] = am * math.sin(dr.get("phi_m", 0.0))
        z[R.iM2] = am * math.cos(dr.get("phi_m", 0.0))
        z[R.iONE] = 1.0
        vs0 = self.vs(z)
        z[R.iV] = vs0 * (np.arange(R.n) + 1.0) / R.n
        mode = 0
        self.t_arr = 0.0
        # schedule: (time, kind, level) kind 0 = nominal level change (arm), 1 = ramp end, 2 = ramp start
        self.sched = [(float(tc), 0, int(lv)) for tc, lv in dr.get("changes", [])]
        heapq.heapify(self.sched)
        Z = np.empty((nst + 1, nz))
        MODE = np.empty(nst + 1, dtype=np.int8)
        Z[0] = z
        MODE[0] = mode
        slips, arrests = [], []
        t = 0.0
        n_ev_total = 0
        for i in range(nst):
            t_target = (i + 1) * h
            guard = 0
            while True:
                dt = t_target - t
                full = abs(dt - h) <= 1e-9 * h
                if dt <= 1e-12 * h:
                    t = t_target
                    break
                z1 = self.advance(z, t, mode, dt, full)
                # earliest scheduled action
                best_tau, best_kind = None, None
                if self.sched and self.sched[0][0] <= t_target:
                    best_tau, best_kind = max(self.sched[0][0] - t, 0.0), ("sched",)
                g1 = self.events(t_target, z1, mode)
                for j, gv in enumerate(g1):
                    if gv > 0.0:
                        lim = dt if best_tau is None else best_tau
                        tau = self._locate(z, t, mode, j, dt)
                        if tau is not None and tau <= lim:
                            best_tau, best_kind = tau, ("ev", j)
                if best_tau is None:
                    z, t = z1, t_target
                    break
                guard += 1
                n_ev_total += 1
                if guard > 400:
                    raise RuntimeError("event storm at t=%g" % t)
                if best_tau > 0.0:
                    z = self.advance(z, t, mode, best_tau, False)
                    t = t + best_tau
                if best_kind[0] == "sched":
                    ts_, kind, lv = heapq.heappop(self.sched)
                    if kind == 0:
                        tz = self._next_ripple_zero(t, z)
                        if tz - t <= 1e-9 * h:
                            z = self._ramp_start(t, z, lv)
                        else:
                            heapq.heappush(self.sched, (tz, 2, lv))
                    elif kind == 2:
                        z = self._ramp_start(t, z, lv)
                    else:
                        z = self._ramp_end(z, lv)
                    continue
                j = best_kind[1]
                if mode == 0:                                   # breakaway
                    sg = -1.0 if self.Freq(z) > 0 else 1.0
                    mode = _encode(sg, 0, 0)
                    slips.append(t)
                    continue
                sg, r, tw = _decode(mode)
                if j == 0:                                      # w crossed 0: arrest or reversal
                    z = z.copy()
                    z[R.ivc] = self.vs(z)
                    F = self.Freq(z)
                    self.t_arr = t
                    if abs(F) <= self.mus(t) * self.N(t, z):
                        mode = 0
                        arrests.append(t)
                    else:
                        mode = _encode(-1.0 if F > 0 else 1.0, 0, 0)
                elif j == 1:
                    mode = _encode(sg, 1 - r, tw)
                else:
                    mode = _encode(sg, r, 1 - tw)
            Z[i + 1] = z
            MODE[i + 1] = mode
        self.n_events = n_ev_total
        return dict(t=np.arange(nst + 1) * h, Z=Z, mode=MODE, slips=np.array(slips), arrests=np.array(arrests))

    def _locate(self, z, t, mode, j, dt):
        def g(tau):
            if tau <= 0.0:
                zz = z
            else:
                zz = self.advance(z, t, mode, tau, False)
            return self.events(t + tau, zz, mode)[j]
        lo = 0.0
        glo = g(lo)
        if glo >= 0.0:
            lo = 1e-7 * dt
            glo = g(lo)
            if glo >= 0.0:
                return lo
        try:
            return brentq(g, lo, dt, xtol=1e-10 * self.h, rtol=1e-12, maxiter=60)
        except ValueError:
            return None


# ------------------------------------------------------------------------------------------------ draws
def _draw(rng, case):
    P = {}
    P["n_nodes"] = int(rng.integers(4, 9))
    P["M"] = _logu(rng, 0.03, 0.3)
    P["m_rod"] = P["M"] * float(rng.uniform(0.15, 0.6))
    P["zeta1"] = float(rng.uniform(0.004, 0.015))
    fn_target = _logu(rng, 6.0, 30.0)
    P.update(k=1.0, N0=1.0, mu_s=0.5, mu0=0.4, s1=0.0, s2=0.0, vm=1.0, d_tw=0.0)
    om1_unit = _Rig(P).omega1
    P["k"] = (TWOPI * fn_target / om1_unit) ** 2
    P["N0"] = float(rng.uniform(2.0, 15.0))
    P["mu_s"] = float(rng.uniform(0.35, 0.65))
    jump = float(rng.uniform(0.22, 0.32)) if case == "static_ageing" else float(rng.uniform(0.12, 0.25))
    P["mu0"] = P["mu_s"] * (1.0 - jump)
    om1 = TWOPI * fn_target
    Z = P["k"] / om1                                    # sqrt(k Meff) of the first mode
    Vs = (P["mu_s"] - P["mu0"]) * P["N0"] / Z
    P["V_scale"] = Vs
    P["vm"] = float(rng.uniform(0.5, 1.2)) * Vs
    P["zeta_weak"] = float(rng.uniform(0.03, 0.10))
    P["zeta_strong"] = float(rng.uniform(0.05, 0.25))
    P["s1"] = 2.0 * P["zeta_weak"] * Z / P["N0"]
    P["s2"] = 2.0 * P["zeta_strong"] * Z / P["N0"]
    P["v0_over_V"] = float(rng.uniform(0.05, 0.13))
    P["r_rip"] = float(rng.uniform(0.02, 0.05))
    R = _Rig(P)
    bad = np.concatenate([R.om_stuck, R.om_free[1:]]) / R.omega1
    for _ in range(50):
        fs = float(rng.uniform(8.0, 16.0))
        if np.all(np.abs(bad / fs - 1.0) > 0.08):
            break
    P["fstep_over_fn"] = fs                              # at the fastest (reference) drive speed
    P["fn"] = R.omega1 / TWOPI
    P["rod_modes_free_over_fn"] = [float(x) for x in R.om_free[1:4] / R.omega1]
    P["rod_modes_stuck_over_fn"] = [float(x) for x in R.om_stuck[:3] / R.omega1]
    return P


def _drive(P, levels, vref, changes=(), a_mod=0.0, fm=0.0, phi_m=0.0, v0n=None):
    """levels: list of speeds (m/s); the ripple's frequency is f_step = v / lambda, lambda from vref."""
    om1 = TWOPI * P["fn"]
    lam = vref / (P["fstep_over_fn"] * P["fn"])          # one full step of the leadscrew (m)
    oms = []
    for v in levels:
        oms.append(TWOPI * v / lam if v > 0 else TWOPI * vref / lam)
    return dict(levels=[float(v) for v in levels], om_s=oms, r_rip=P["r_rip"], changes=list(changes),
                t_ramp=0.08 * TWOPI / om1, a_mod=float(a_mod), om_m=TWOPI * fm, phi_m=float(phi_m),
                v0n=float(v0n if v0n is not None else levels[0]), lambda_step=lam)


# ------------------------------------------------------------------------------------------------ analysis
def _derived(S, out):
    """Vectorised signals on the internal grid."""
    R = S.R
    Z, t = out["Z"], out["t"]
    n = R.n
    ke, ce = R.ke, R.ce
    vs = Z[:, R.iVB] + Z[:, R.iQ1] + Z[:, R.iM1]
    w = Z[:, R.ivc] - vs
    Fg = ke * Z[:, 0]
    ld = S.ld
    if ld["kind"] == "const":
        N = np.full(t.size, ld["N0"])
    elif ld["kind"] == "vib":
        N = ld["N0"] * (1.0 + ld["a"] * np.sin(ld["om"] * t + ld["phi"]))
    else:
        N = ld["N0"] * np.maximum(1.0 + ld["c"] * (Z[:, R.ixc] - ld["xm"]), 0.05) ** 1.5
    # contact friction (slip: the law; stick: the needed force)
    mode = out["mode"].astype(int)
    ff = np.zeros(t.size)
    Tn_ = ke * (Z[:, n - 1] - Z[:, n - 2]) + ce * (Z[:, 2 * n - 1] - Z[:, 2 * n - 2])
    for md in np.unique(mode):
        ii = mode == md
        if md == 0:
            ff[ii] = np.nan
            continue
        sg, r, tw = _decode(md)
        c0, c1 = R.seg(r)
        ff[ii] = -sg * N[ii] * (c0 + c1 * np.abs(w[ii]) + R.P["d_tw"] * tw)
    # node-0 acceleration (never the contact: n >= 4) for the 1-DoF view of the gauge signal
    a0 = (-ke * (2 * Z[:, 0] - Z[:, 1]) - ce * (2 * Z[:, n] - Z[:, n + 1])) / R.m[0]
    return dict(t=t, vs=vs, w=w, Fg=Fg, N=N, ff=ff, xc=Z[:, R.ixc], a0=a0, v1=Z[:, n], x1=Z[:, 0],
                s=Z[:, R.iS], vb=Z[:, R.iVB], Tn_=Tn_)


def _twin_stat(speed, fric, i0, i1):
    """decelerating minus accelerating |friction| at equal |speed| (25-85 % of the slip's peak), or None."""
    sp = np.abs(speed[i0:i1 + 1])
    fr = np.abs(fric[i0:i1 + 1])
    if sp.size < 8:
        return None
    ip = int(np.argmax(sp))
    pk = sp[ip]
    edges = np.linspace(0.25, 0.85, 7) * pk
    d = []
    for a, b in zip(edges[:-1], edges[1:]):
        ua = (sp[:ip] >= a) & (sp[:ip] < b)
        ud = (sp[ip:] >= a) & (sp[ip:] < b)
        if ua.any() and ud.any():
            d.append(fr[ip:][ud].mean() - fr[:ip][ua].mean())
    return float(np.mean(d)) if d else None


def _measure(S, out, D, t0, t1):
    """Cycle statistics inside the record window [t0, t1], from the model's internals."""
    R, P = S.R, S.R.P
    t = D["t"]
    Tn = 1.0 / P["fn"]
    h = t[1] - t[0]
    sl, ar = out["slips"], out["arrests"]
    sl_in = sl[(sl >= t0) & (sl <= t1)]
    res = dict(cycles=int(sl_in.size))
    if sl_in.size < 3:
        return res
    Fg = D["Fg"]
    cyc = []
    for i, ts in enumerate(sl_in):
        nxt = sl[sl > ts]
        te = nxt[0] if nxt.size else t1
        prev_ar = ar[ar < ts]
        if not prev_ar.size:
            continue
        arr = ar[(ar > ts) & (ar < te)]
        if not arr.size:
            continue
        i_s = int(round(ts / h))
        ia, ib = max(0, i_s - int(0.3 * Tn / h)), min(t.size - 1, i_s + int(0.3 * Tn / h))
        pk = float(Fg[ia:ib + 1].max())
        i_a = int(round(arr[0] / h))
        tr = float(Fg[i_s:min(t.size - 1, i_a + int(0.3 * Tn / h)) + 1].min())
        cyc.append(dict(ts=float(ts), ta=float(arr[0]), stick=float(ts - prev_ar[-1]), peak=pk,
                        drop=pk - tr, i_s=i_s, i_a=i_a))
    if len(cyc) < 3:
        return res
    pk = np.array([c["peak"] for c in cyc])
    dr = np.array([c["drop"] for c in cyc])
    st = np.array([c["stick"] for c in cyc])
    drop = float(np.median(dr))
    res.update(drop=drop, peak=float(np.median(pk)), drop_over_peak=float(drop / np.median(pk)),
               peak_scatter_over_drop=float(np.std(pk) / drop),
               stick_min_Tn=float(st.min() / Tn), stick_max_Tn=float(st.max() / Tn),
               slip_Tn=float(np.median([c["ta"] - c["ts"] for c in cyc]) / Tn))
    fss = (sl_in.size - 1) / (sl_in[-1] - sl_in[0])
    res["fss_over_fn"] = float(fss / P["fn"])
    # peak growth between the longest and the shortest sticks of the record (model-free)
    if st.max() > 1.5 * st.min():
        lo = pk[st <= 1.25 * st.min()]
        hi = pk[st >= 0.8 * st.max()]
        res["peak_growth_over_drop"] = float((np.median(hi) - np.median(lo)) / drop)
        res["peak_growth_over_peak"] = float((np.median(hi) - np.median(lo)) / np.median(pk))
        res["stick_range"] = float(st.max() / st.min())
    # double-valuedness: the contact's own friction, and what a 1-DoF reading of the gauge sees
    k, om1 = P["k"], TWOPI * P["fn"]
    # the gauge's extension x = F/k, zero-phase low-passed below the rod's second mode (an analyst's filter),
    # then f = k x + (k / om1^2) x'' and w = x' - vs: the friction a 1-DoF reading of a perfect record sees
    f2 = min(R.om_free[1], R.om_stuck[0]) / TWOPI
    fc = max(0.5 * f2, 1.8 * P["fn"])
    bb, aa = butter(4, fc * 2.0 * h)
    x = filtfilt(bb, aa, D["Fg"] / k)
    xd = np.gradient(x, h)
    f_app = k * x + (k / om1 ** 2) * np.gradient(xd, h)
    w_app = xd - D["vs"]
    res["lowpass_over_fn"] = float(fc / P["fn"])
    tw_i, tw_a = [], []
    for c in cyc:
        a = _twin_stat(D["w"], D["ff"], c["i_s"] + 1, c["i_a"] - 1)
        b = _twin_stat(w_app, f_app, c["i_s"] + 1, c["i_a"] - 1)
        if a is not None:
            tw_i.append(a / c["drop"])
        if b is not None:
            tw_a.append(b / c["drop"])
    if tw_i:
        res["twin_contact_over_drop"] = float(np.median(tw_i))
    if tw_a:
        res["twin_gauge_1dof_over_drop"] = float(np.median(tw_a))
    # ringing of the rod's own modes in stick: gauge force less its quasi-static value k x_c
    ring = []
    for c0, c1 in zip(cyc[:-1], cyc[1:]):
        ia, ib = c0["i_a"], c1["i_s"]
        if ib > ia + 3:
            ring.append(np.max(np.abs(Fg[ia:ib] - k * D["xc"][ia:ib])) / c0["drop"])
    if ring:
        res["stick_ringing_over_drop"] = float(np.median(ring))
    vb = np.abs(D["vb"][(t >= t0) & (t <= t1)])
    res["ripple_inertia_over_drop"] = float(R.Mc * P["r_rip"] * vb.max() * max(S.dr["om_s"]) / drop)
    win = (t >= t0) & (t <= t1)
    res["N_pp_over_N0"] = float((D["N"][win].max() - D["N"][win].min()) / P["N0"])
    res["_cyc"] = cyc
    return res


def _run(P, drive, load, ageing, twin, t_end, h):
    R = _Rig(P)
    S = _Sim(R, drive, load, ageing, twin)
    out = S.run(t_end, h)
    return S, out, _derived(S, out)


def _pilot(P, v, vref, h, twin=False, ncyc=7, load=None, ageing=None):
    Tn = 1.0 / P["fn"]
    k, N0 = P["k"], P["N0"]
    t_first = P["mu_s"] * N0 / (k * v)
    T_est = 2.0 * (P["mu_s"] - P["mu0"]) * N0 / (k * v) + 0.6 * Tn
    load = load or dict(kind="const", N0=N0)
    for stretch in (1.3, 3.0):
        S, out, D = _run(P, _drive(P, [v], vref), load, ageing, twin,
                         t_first * stretch + (ncyc + 2.5) * stretch * T_est, h)
        sl = out["slips"]
        t0 = sl[1] + 0.5 * Tn if sl.size > 2 else 0.0
        m = _measure(S, out, D, t0, out["t"][-1])
        if m.get("cycles", 0) >= 3 and "drop" in m:
            break
    else:
        raise RuntimeError("pilot: no regular stick-slip (%d slips)" % sl.size)
    win = D["t"] >= t0
    xc = D["xc"][win]
    m.update(Tss=1.0 / (m["fss_over_fn"] * P["fn"]), t_first=float(sl[0]), xc_lo=float(xc.min()),
             xc_hi=float(xc.max()), xc_mean=float(xc.mean()))
    m.pop("_cyc", None)
    return m


def _probe_lo(P):
    """lowest probe node (0-based): node n/2 of n (1-based)."""
    return max(1, int(P["n_nodes"]) // 2 - 1)


def _fmt_time(dt):
    d = max(0, int(math.ceil(-math.log10(dt))) + 3)
    return "%." + str(d) + "f"


def _cic3(y, L):
    """delta-sigma ADC decimation filter: three cascaded moving averages of length L (causal)."""
    if L <= 1:
        return y.copy()
    ker = np.ones(L) / L
    k3 = np.convolve(np.convolve(ker, ker), ker)
    yp = np.concatenate([np.full(k3.size - 1, y[0]), y])
    return np.convolve(yp, k3, mode="valid")


def _sensor(y, rng, scale, L, idx):
    """CIC decimation, amplifier noise (white + random-walk offset), 24-bit quantiser."""
    yd = _cic3(y, L)[idx]
    nw = float(rng.uniform(0.0008, 0.0025)) * scale
    rw_end = float(rng.uniform(0.001, 0.004)) * scale
    walk = np.cumsum(rng.normal(0.0, 1.0, yd.size))
    walk *= rw_end / max(np.sqrt(yd.size), 1.0)
    yd = yd + rng.normal(0.0, nw, yd.size) + walk
    fs = 1.6 * max(np.max(np.abs(yd)), 1e-30)
    q = 2.0 * fs / 2 ** 24
    yd = np.round(yd / q) * q
    return yd, dict(white_over_scale=nw / scale, walk_end_rms_over_scale=rw_end / scale, adc24_lsb=q)


def _stepped(P, rng, pil, levels, order, v_top, n_target, holds, lvl_hold=None, stretch=1.0):
    """Level changes (t, level) for a stage that steps between levels (and holds)."""
    Tn = 1.0 / P["fn"]
    Tslip = pil["slip_Tn"] * Tn + 0.15 * Tn
    st_top = max(pil["Tss"] - Tslip, 0.3 * Tn)

    def T_of(v):
        return Tslip + st_top * v_top / v

    visits = list(order) + [order[0]]
    ncv = max(5, int(round(stretch * n_target / len(visits))))
    v_first = levels[visits[0]]
    t = P["mu_s"] * P["N0"] / (P["k"] * v_first) + 2.0 * T_of(v_first)
    t_rec0 = t - 0.5 * st_top * v_top / v_first
    changes, hold_info = [], []
    hold_visits = set()
    if holds:
        hold_visits = set(int(x) for x in rng.choice(np.arange(1, len(visits)), size=holds, replace=False))
    for iv, lv in enumerate(visits):
        if iv > 0:
            changes.append((t, lv))
        dur = ncv * T_of(levels[lv])
        if iv in hold_visits:
            st_lv = st_top * v_top / levels[lv]
            th = float(rng.uniform(3.0, 8.0)) * st_lv
            th = min(th, 25.0 * Tn)
            tm = t + 0.5 * dur
            changes.append((tm, lvl_hold))
            changes.append((tm + th, lv))
            hold_info.append(dict(t=tm, hold=th, level=int(lv)))
            dur += th
        t += dur
    return changes, t_rec0, t, dict(visits=[int(v) for v in visits], cycles_per_visit=ncv, holds=hold_info,
                                    stick_top=st_top, Tslip=Tslip)


def write_record(case, seed, outdir, nuisance="clean"):
    if case not in CASES:
        raise ValueError("unknown case %r" % (case,))
    if nuisance not in NUISANCES:
        raise ValueError("unknown nuisance %r" % (nuisance,))
    tic = time.time()
    rng = _rng(case, seed)
    rn = _rng(case, seed, nuisance)
    fr = _rng(case, seed, "format")
    P = _draw(rng, case)
    fn, k, N0, Vs = P["fn"], P["k"], P["N0"], P["V_scale"]
    Tn = 1.0 / fn
    info = {}
    # ---------------------------------------------------------------- sampling
    if nuisance == "coarse":
        sp = float(rn.uniform(10.0, 15.0))
    else:
        sp = float(rn.uniform(20.0, 100.0))
        if nuisance == "hum":
            sp = min(max(sp, 150.0 / fn), 100.0)
    nsub = max(2, int(math.ceil(170.0 / sp)))
    dt_out = Tn / sp
    h = dt_out / nsub
    hp = Tn / 160.0
    n_target = int(rng.integers(18, 35))
    if case == "static_ageing" or (case == "none" and seed % 4 == 3):
        n_target = int(rng.integers(24, 35))
    v0 = P["v0_over_V"] * Vs
    load = dict(kind="const", N0=N0)
    ageing, twin = None, False
    stepped = case == "static_ageing" or (case == "none" and seed % 4 == 3)
    changes, t_rec0 = [], None
    # ---------------------------------------------------------------- case set-up (pilots)
    if stepped:
        span = float(rng.uniform(4.0, 8.0)) if case == "static_ageing" else float(rng.uniform(2.5, 5.0))
        nlv = int(rng.integers(3, 6)) if case == "static_ageing" else 3
        v_top = float(rng.uniform(0.10, 0.15)) * Vs
        levels = list(v_top * span ** (-np.linspace(1.0, 0.0, nlv)))
        order = [int(i) for i in rng.permutation(nlv)]
        holds = 2 if (case == "static_ageing" and seed % 2 == 1) else 0
        levels_all = levels + ([0.0] if holds else [])
        pil = _pilot(P, v_top, v_top, hp)
        stretch = 1.0
        changes, t_rec0, t_end, sch = _stepped(P, _rng(case, seed, "schedule"), pil, levels, order, v_top,
                                               n_target, holds, lvl_hold=nlv if holds else None)
        drive = _drive(P, levels_all, v_top, changes)
        info.update(levels_mm_s=[v * 1e3 for v in levels], span=span, schedule=sch)
        v_nom = float(np.exp(np.mean(np.log(levels))))
        if case == "static_ageing":
            p = float(rng.uniform(0.25, 0.5))
            g_tgt = float(rng.uniform(0.11, 0.17))            # of the drop; and >= 5.5 % of the peak
            g_tgt = min(max(g_tgt, 0.055 / pil["drop_over_peak"]), 0.185)
            st_top = sch["stick_top"]
            t_min = st_top
            t_max = st_top * span
            for hd in sch["holds"]:
                t_max = max(t_max, hd["hold"] + 0.5 * st_top * v_top / levels[hd["level"]])
            b = g_tgt * pil["drop"] / (N0 * ((t_max / Tn) ** p - (t_min / Tn) ** p))
            ageing = dict(b=float(b), p=p, Tref=Tn)
            info.update(ageing_target_over_drop=g_tgt, ageing_p=p)
    else:
        pil = _pilot(P, v0, v0, hp)
        drive = _drive(P, [v0], v0)
        v_nom = v0
        t_end = pil["t_first"] + (n_target + 2.3) * pil["Tss"]
        if case == "load_variation":
            # a rising wedge (N grows with the extension).  A falling one (c < 0) lowers the breakaway and raises
            # the arrest: tried, it shrinks the drop to ~0.2 of the peak before N swings by 10 %, so it is not used
            sgn = 1.0
            pp = float(rng.uniform(0.15, 0.33))
            c_cap = 0.6 * k / (1.5 * P["mu_s"] * N0)          # the rising wedge must not self-lock the stick
            pl = pil
            c = None
            failed = False
            for it in range(8):                                # short pilots: c for the target peak-to-peak
                if c is None:
                    c = pp / (1.5 * (pil["xc_hi"] - pil["xc_lo"]))
                elif failed:
                    c *= 0.6
                else:
                    c *= (pp / max(pl["N_pp_over_N0"], 1e-3)) ** 0.8
                c = min(c, c_cap)
                load = dict(kind="wedge", N0=N0, c=float(c), xm=pl["xc_mean"])
                try:
                    pl_new = _pilot(P, v0, v0, hp, ncyc=5, load=load)
                except RuntimeError:
                    failed = True
                    continue
                failed, pl = False, pl_new
                if abs(pl["N_pp_over_N0"] / pp - 1.0) < 0.12:
                    break
            t_end = pl["t_first"] + (n_target + 2.3) * pl["Tss"]
            info.update(load_target_pp=pp, load_sign=sgn,
                        load_pilot=dict(N_pp_over_N0=pl["N_pp_over_N0"], Tss=pl["Tss"]))
        elif case == "twin_branch":
            tau_t = float(rng.uniform(0.11, 0.17))
            P["d_tw"] = tau_t * pil["drop"] / N0
            p2 = _pilot(P, v0, v0, hp, twin=True, ncyc=5)
            P["d_tw"] *= tau_t / max(p2.get("twin_contact_over_drop", tau_t), 0.02)
            twin = True
            info.update(twin_target_over_drop=tau_t)
        elif case == "triggering":
            a = float(rng.uniform(0.035, 0.075))
            fss0 = 1.0 / pil["Tss"]
            info.update(trigger_a=a)
        elif case == "drive_modulation":
            a = float(rng.uniform(0.22, 0.42))
            fm = float(rng.uniform(0.12, 0.45)) / pil["Tss"]
            phi = float(rng.uniform(0.0, TWOPI))
            drive = _drive(P, [v0], v0, a_mod=a, fm=fm, phi_m=phi, v0n=v0)
            info.update(mod_a=a, mod_fm_hz=fm, mod_fm_over_fss_pilot=fm * pil["Tss"], mod_phi=phi)
    info["pilot"] = {kk: vv for kk, vv in pil.items() if not kk.startswith("_")}
    # ---------------------------------------------------------------- final run(s)
    tries = 0
    best = None
    while True:
        tries += 1
        if case == "triggering":
            # first try anywhere in 2.8-7.5 fn; after a lock, higher (4.5-7.5 fn: a forcing period is then a
            # smaller part of the cycle and the slips alternate between neighbouring counts more easily)
            fss_e = fss0 if tries == 1 else 0.5 * (fss0 + meas["fss_over_fn"] * fn)
            lo = (2.8 if tries == 1 else 4.5) * fn / fss_e
            hi = 7.5 * fn / fss_e
            mlo, mhi = int(math.ceil(lo)), int(math.floor(hi - 1.0))
            mm = int(rng.integers(mlo, max(mlo, mhi) + 1))
            ft = (mm + float(rng.uniform(0.3, 0.7))) * fss_e
            load = dict(kind="vib", N0=N0, a=a, om=TWOPI * ft, phi=float(rng.uniform(0.0, TWOPI)))
        S, out, D = _run(P, drive, load, ageing, twin, t_end, h)
        sl, ar = out["slips"], out["arrests"]
        if t_rec0 is None:
            t_a1 = ar[ar > sl[1]][0]
            t_s2 = sl[sl > t_a1][0]
            t_rec0 = float(t_a1 + float(rng.uniform(0.1, 0.9)) * (t_s2 - t_a1))
        t_rec1 = float(out["t"][-1])
        sw = sl[(sl >= t_rec0) & (sl <= t_rec1)]
        if sw.size > 38:                                   # keep 15-40 cycles: end the record earlier
            t_rec1 = float(sw[37] + float(rng.uniform(0.2, 0.8)) * (sw[38] - sw[37]))
        meas = _measure(S, out, D, t_rec0, t_rec1)
        redo = False
        if stepped and meas["cycles"] < 16 and tries < 4:
            stretch *= 19.0 / max(meas["cycles"], 5)
            changes, t_rec0, t_end, sch = _stepped(P, _rng(case, seed, "schedule"), pil, levels, order, v_top,
                                                   n_target, holds, lvl_hold=nlv if holds else None,
                                                   stretch=stretch)
            drive = _drive(P, levels_all, v_top, changes)
            info.update(schedule=sch)
            redo = True
        elif case == "load_variation" and not 0.12 <= meas["N_pp_over_N0"] <= 0.36 and tries < 3:
            load["c"] *= (info["load_target_pp"] / meas["N_pp_over_N0"]) ** 0.8
            redo = True
        elif case == "twin_branch" and tries < 3:
            tw = meas.get("twin_contact_over_drop", 0.0)
            tg = meas.get("twin_gauge_1dof_over_drop", tw)
            if not 0.10 <= tw <= 0.21:
                P["d_tw"] *= info["twin_target_over_drop"] / max(tw, 0.02)
                redo = True
            elif tg > 0.245:
                P["d_tw"] *= 0.22 / tg
                redo = True
        elif case == "static_ageing" and tries < 3:
            g = meas.get("peak_growth_over_drop", 0.0)
            if not (0.09 <= g <= 0.19 and meas.get("peak_growth_over_peak", 0.0) >= 0.05):
                ageing["b"] *= info["ageing_target_over_drop"] / max(g, 0.01)
                redo = True
        elif case == "triggering":
            q = ft / (meas["fss_over_fn"] * fn)
            frac = abs(q - round(q))
            if best is None or frac > best[0]:
                best = (frac, S, out, D, meas, ft, dict(load), t_rec0, t_rec1)
            if frac < 0.15:
                if tries < 8:
                    redo = True
                else:                                      # every draw locked: keep the least locked run
                    frac, S, out, D, meas, ft, load, t_rec0, t_rec1 = best
        if not redo:
            break
        t_rec0 = None if not stepped else t_rec0
    if case == "triggering":
        q = ft / (meas["fss_over_fn"] * fn)
        meas.update(ft_hz=ft, ft_over_fn=ft / fn, ft_over_fss=q, ft_over_fss_frac=abs(q - round(q)))
        info.update(trigger_ft_hz=ft)
    if case == "drive_modulation":
        meas.update(mod_a=info["mod_a"], mod_fm_over_fss=info["mod_fm_hz"] / (meas["fss_over_fn"] * fn))
    if ageing is not None:
        info.update(ageing_b=ageing["b"])
    meas["runs"] = tries
    cyc = meas.pop("_cyc", [])
    # ---------------------------------------------------------------- the record
    i0 = int(math.ceil(t_rec0 / h))
    i1 = min(int(math.floor(t_rec1 / h)), D["t"].size - 1)
    idx = np.arange(i0, i1 + 1, nsub)
    ts = D["t"][idx] - D["t"][idx[0]]
    drop = meas.get("drop", pil["drop"])
    disp = bool(fr.random() < 0.4)
    has_N = case in ("load_variation", "triggering") or bool(fr.random() < 0.3)
    drive_col = None
    if stepped:
        drive_col = "v0" if disp else str(fr.choice(["v0", "pos"]))
    elif case != "drive_modulation" and fr.random() < 0.25:
        drive_col = "v0" if disp else str(fr.choice(["v0", "pos"]))
    nz = {}
    if disp:
        j = int(fr.integers(_probe_lo(P), P["n_nodes"] - 1))          # probe node (0-based), never the contact
        Zp = out["Z"][:, j] * P["n_nodes"] / (j + 1)
        main, scale = _sensor(Zp * 1e3, rn, drop / k * 1e3, nsub, idx)
        info.update(probe_node=j + 1, probe_of_nodes=P["n_nodes"])
        mscale = drop / k * 1e3
    else:
        fu = "mN" if P["mu_s"] * N0 < 2.0 or fr.random() < 0.3 else "N"
        fmul = 1e3 if fu == "mN" else 1.0
        main, scale = _sensor(D["Fg"] * fmul, rn, drop * fmul, nsub, idx)
        mscale = drop * fmul
    nz["main"] = scale
    if has_N:
        if disp:
            gy = float(fr.uniform(0.02, 0.3))                   # mm per N: the normal spring's deflection
            y0 = float(fr.uniform(-1.0, 1.0))
            nrm, sN = _sensor(y0 + gy * D["N"], rn, gy * 0.1 * N0, nsub, idx)
            info["normal_reading"] = dict(offset_mm=y0, mm_per_N=gy)
        else:
            nrm, sN = _sensor(D["N"] * fmul, rn, 0.1 * N0 * fmul, nsub, idx)
        nz["normal"] = sN
    # ---------------------------------------------------------------- nuisances (main channel)
    fs = 1.0 / dt_out
    if nuisance == "hum":
        fh = float(rn.choice([50.0, 60.0]))
        amp = float(rn.uniform(0.01, 0.05)) * mscale
        ph = rn.uniform(0.0, TWOPI, 3)
        hh = np.zeros(ts.size)
        nh = 0
        for jh, ah in ((1, 1.0), (2, 0.3), (3, 0.15)):
            if jh * fh < 0.45 * fs:
                hh += ah * amp * np.sin(TWOPI * jh * fh * ts + ph[jh - 1])
                nh += 1
        main = main + hh
        nz.update(hum_hz=fh, hum_over_drop=amp / mscale, hum_harmonics=nh)
    elif nuisance == "drift":
        amp = float(rn.uniform(0.02, 0.06)) * mscale * float(rn.choice([-1.0, 1.0]))
        u = ts / ts[-1]
        shape = 0.6 * u + 0.4 * np.sin(0.5 * math.pi * u) ** 2
        main = main + amp * shape / shape.max()
        nz.update(drift_over_drop=amp / mscale)
    elif nuisance == "spikes":
        frac = float(rn.uniform(0.0005, 0.005))
        ns = max(2, int(round(frac * main.size)))
        ii = np.sort(rn.choice(np.arange(2, main.size - 2, 3), ns, replace=False))
        main = main.copy()
        main[ii] += rn.choice([-1.0, 1.0], ns) * rn.uniform(0.3, 1.5, ns) * mscale
        nz.update(spike_fraction=ns / main.size)
    elif nuisance == "quantisation":
        q = float(rn.uniform(0.002, 0.01)) * mscale
        main = np.round(main / q) * q
        if has_N:
            qn = q * (0.1 * N0 * (gy if disp else fmul)) / mscale
            nrm = np.round(nrm / qn) * qn
        nz.update(adc_step_over_drop=q / mscale)
    ci = CASES.index(case)
    if nuisance == "fn_off":
        fn_given = fn * (1.0 + 0.05 * float(rn.choice([-1.0, 1.0])))
    elif (seed + 3 * ci) % 8 == 5:
        fn_given = None
    else:
        fn_given = fn
    # ---------------------------------------------------------------- write
    args = []
    if fn_given is not None:
        args += ["--fn", "%.6g" % fn_given]
    if drive_col is None:
        args += ["--v0", "%.6g" % (v_nom * 1e3)]
    sep = str(fr.choice([",", "\t", " "]))
    cols = []
    if disp:
        cols.append(("x", "mm", main))
        if has_N:
            cols.append(("y", "mm", nrm))
        tname = str(fr.choice(["t", "time"]))
        kind = "displacement"
    else:
        cols.append((str(fr.choice(["friction", "F", "force"])), fu, main))
        if has_N:
            cols.append((str(fr.choice(["normal", "N"])), fu, nrm))
        tname = str(fr.choice(["time", "t", "Time"]))
        kind = "force"
        args += ["--stiffness", "%.6g" % k]
    if drive_col == "v0":
        cols.append(("v0", "mm/s", D["vb"][idx] * 1e3))
    elif drive_col == "pos":
        pu, ps = ("mm", 1e3) if fr.random() < 0.6 else ("um", 1e6)
        sp_ = D["s"][idx] - D["s"][idx[0]]
        cols.append(("position", pu, sp_ * ps))
    if sep == " ":
        names = ["%s[s]" % tname] + ["%s[%s]" % (nm, un) for nm, un, _ in cols]
    else:
        names = ["%s [s]" % tname] + ["%s [%s]" % (nm, un) for nm, un, _ in cols]
    os.makedirs(outdir, exist_ok=True)
    ext = {",": "csv", "\t": "tsv", " ": "txt"}[sep]
    fout = os.path.abspath(os.path.join(outdir, "%s_%s_%03d_%s.%s" % (NAME, case, seed, nuisance, ext)))
    data = np.column_stack([ts] + [c for _, _, c in cols])
    delim = "  " if sep == " " else sep
    with open(fout, "w") as fh_:
        fh_.write(delim.join(names) + "\n")
        np.savetxt(fh_, data, fmt=[_fmt_time(dt_out)] + ["%.8g"] * len(cols), delimiter=delim)
    # ---------------------------------------------------------------- truth
    params = dict(P)
    params.update(info)
    params.update(samples_per_period=sp, n_sub=nsub, h_over_Tn=h / Tn, n_samples=int(ts.size),
                  record_kind=kind, has_normal=has_N, drive_column=drive_col, separator=sep,
                  t_record_start=t_rec0, duration_s=float(ts[-1]), v0_nominal_mm_s=v_nom * 1e3,
                  n_events=S.n_events, f_step_hz=[o / TWOPI for o in drive["om_s"]],
                  ripple_over_v=P["r_rip"])
    params["nuisance_params"] = nz
    params["measured"] = meas
    params["seconds"] = time.time() - tic
    params = json.loads(json.dumps(params, default=float))
    return dict(generator=NAME, case=case, seed=int(seed), nuisance=nuisance, file=fout, args=args,
                fn_true=float(fn), fn_given=None if fn_given is None else float(fn_given), params=params)


# ------------------------------------------------------------------------------------------------ self-check
def _departure(case, m):
    f = lambda key: m.get(key, float("nan"))
    if case == "none":
        return "twin(1dof) %+.3f  ring %.3f  growth %+.3f" % (f("twin_gauge_1dof_over_drop"),
                                                             f("stick_ringing_over_drop"),
                                                             m.get("peak_growth_over_drop", 0.0))
    if case == "load_variation":
        return "N p-p/N0 %.3f" % f("N_pp_over_N0")
    if case == "twin_branch":
        return "twin/drop %.3f (1dof %.3f)" % (f("twin_contact_over_drop"), f("twin_gauge_1dof_over_drop"))
    if case == "static_ageing":
        return "growth/drop %.3f /peak %.3f  sticks x%.1f" % (f("peak_growth_over_drop"),
                                                             f("peak_growth_over_peak"), f("stick_range"))
    if case == "triggering":
        return "a %.3f  ft/fn %.2f  ft/fss %.2f" % (0.5 * f("N_pp_over_N0"), f("ft_over_fn"), f("ft_over_fss"))
    return "a %.3f  fm/fss %.3f" % (f("mod_a"), f("mod_fm_over_fss"))


if __name__ == "__main__":
    import tempfile

    outdir = tempfile.mkdtemp(prefix="rod_stepper_")
    t_all = time.time()
    print("%-17s %4s %-12s %-5s %6s %6s %5s %6s  %s" % ("case", "seed", "nuisance", "kind", "cyc", "sp",
                                                         "fn?", "sec", "departure (model internals)"))
    summary = {}
    for case in CASES:
        for seed in range(8):
            nu = NUISANCES[seed % 7]
            tic = time.time()
            r = write_record(case, seed, outdir, nu)
            sec = time.time() - tic
            p, m = r["params"], r["params"]["measured"]
            print("%-17s %4d %-12s %-5s %6d %6.1f %5s %6.2f  %s" % (
                case, seed, nu, p["record_kind"][:5], m["cycles"], p["samples_per_period"],
                "-" if r["fn_given"] is None else ("off" if nu == "fn_off" else "yes"), sec, _departure(case, m)))
            summary.setdefault(case, []).append((m, sec))
    print("\nall 48 records in %.1f s (%s)" % (time.time() - t_all, outdir))
    for case, rows in summary.items():
        secs = [s_ for _, s_ in rows]
        cyc = [m_["cycles"] for m_, _ in rows]
        print("%-17s cycles %d-%d, %.2f-%.2f s" % (case, min(cyc), max(cyc), min(secs), max(secs)))

