"""Issue #18, part 3: the triggering oscillation, as a forcing and as the listing's displacement of the state.

The thesis says (ch. 2.4.1.2, seed lines 2538-2588; 2.4.2.1 b and d, lines 2617-2619 and 2668-2676;
Table 2.IV; App. 9, lines 5534-5538):

* the triggering oscillation "can remove the representative point of an unstable equilibrium and trigger
  thus a frictional oscillation, which otherwise could only be obtained after infinite time";
* "in case of a stable origin a trajectory approaching it stabilizes itself on the triggering cycle ...
  equilibrium is replaced by quasi-sinusoidal vibration";
* for vk < v0 < v_oc "the existence or not of frictional oscillations of the self-sustained type depends on
  the characteristics of the triggering oscillation";
* "even assuming the amplitude A to be very small, A.w could be enough (for w high) to excite an oscillation";
* Fig. A9-7 "shows how the triggering oscillation can produce the observed dying-out oscillation after the
  slip part of stick-slip".

Two representations of the trigger are studied:

* **forcing**: the Lienard-plane equation of `lieng cycles` (dX/dT = Y, dY/dT = -(X - C(Y)), T in 1/omega_n,
  C the characteristic read as POINT reads it) with a harmonic force F cos(r T) added to dY/dT (F in the
  units of X, r = trigger frequency / natural frequency).  Integrated here with `solve_ivp` (DOP853), an
  integrator that shares nothing with the Fortran exact flow; with F = 0 it gives `find_cycles`' S.L.C.;
* **displacement of the state**: MLIEN's POINT as listed (App. 6; RESTORATION.md M6, M7): after every step
  the state is moved by (ATRI cos phi, BTRI sin phi), phi = OMETRI T + OMINTR.  The offsets accumulate.
  With OMETRI = 30000 (the listing's) the phase advances by hundreds of radians per step and the offsets
  act as a noise; with OMETRI near 1 they are a forcing at about the natural frequency.  Runs with the
  listing's phase are a distribution over OMINTR (the trigger's initial phase), not one trajectory.

The shape is Fig. 2.21's (tests/conftest.py; the drive at v0 = 22 mm/s lies on the rising part, 2 mm/s
beyond the kinetic minimum: a stable origin inside an unstable cycle inside the stable one; v0 = 10: an
unstable origin) and the characteristic of cards/mlien_a9_7_decay.dat for MLIEN.  Run:

    python tests/studies/triggering.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from conftest import CARDS, thesis_characteristic  # noqa: E402

from lieng import cycles  # noqa: E402
from lieng.programs.mlien import Deck, run_deck  # noqa: E402


def fig_2_21_at(v0: float):
    """Fig. 2.21's characteristic moved to the driving velocity v0 (mm, mm/s)."""
    x, v = thesis_characteristic(v0=10.0, eps=0.5, um=20.0, vmax=80)
    return cycles.move_to_v0(x, v, v0)


def forced(X, Y, F: float, r: float, x0: float = 0.0, y0: float = 0.0, tmax: float = 400.0, phase: float = 0.0):
    """The Lienard-plane trajectory under a harmonic force F cos(r T + phase).

    Parameters
    ----------
    X, Y : ndarray
        The characteristic (X in mm, Y in mm/s, Y decreasing), through the origin.
    F : float
        Force amplitude in the units of X (force / stiffness, mm).
    r : float
        Trigger frequency over the natural frequency.
    x0, y0 : float
        Start.
    tmax : float
        Duration in units of 1/omega_n.

    Returns
    -------
    scipy OdeSolution
        ``sol(t)`` gives (X, Y) at times t.
    """
    ya, xa = Y[::-1], X[::-1]

    def rhs(t, s):
        return [s[1], -(s[0] - np.interp(s[1], ya, xa)) + F * np.cos(r * t + phase)]

    return solve_ivp(rhs, (0.0, tmax), [x0, y0], method="DOP853", rtol=1e-9, atol=1e-11, max_step=0.1,
                     dense_output=True).sol


def settled(sol, t0: float, t1: float, n: int = 4000):
    """Half the peak-to-peak of X and of Y over [t0, t1]: the semi-axes of the cycle the motion settled on."""
    z = sol(np.linspace(t0, t1, n))
    return float(np.ptp(z[0]) / 2), float(np.ptp(z[1]) / 2)


def linear_response(F: float, r: float, damping: float) -> float:
    """Semi-axis in X of the forced ellipse of u'' + 2 D u' + u = F cos(r t)."""
    return F / np.sqrt((1 - r * r) ** 2 + (2 * damping * r) ** 2)


def slope_at_origin(X, Y) -> float:
    """dX/dY of the characteristic at Y = 0 (its local slope)."""
    ya, xa = Y[::-1], X[::-1]
    return float((np.interp(1e-3, ya, xa) - np.interp(-1e-3, ya, xa)) / 2e-3)


def threshold(X, Y, r: float, slc_half: float, lo: float = 1e-3, hi: float = 30.0, iters: int = 14):
    """The least force F, from rest at the origin, that ends on the S.L.C. (bisection in log F)."""
    for _ in range(iters):
        m = np.sqrt(lo * hi)
        if settled(forced(X, Y, m, r), 320.0, 400.0)[0] > 0.7 * slc_half:
            hi = m
        else:
            lo = m
    return lo, hi


def time_to_reach(sol, level: float, tmax: float, dt: float = 0.01) -> float:
    """First time |(X, Y)| exceeds ``level``."""
    t = np.arange(0.0, tmax, dt)
    z = sol(t)
    k = np.flatnonzero(np.hypot(z[0], z[1]) > level)
    return float(t[k[0]]) if k.size else float("inf")


def decay_deck() -> Deck:
    """cards/mlien_a9_7_decay.dat: Fig. 2.21's line centred at 22 mm/s, D = 0.05 about a stable origin."""
    return Deck.from_lines((CARDS / "mlien_a9_7_decay.dat").read_text().splitlines())


def mlien_held(x0: float, trigger, npts: int = 30000):
    """MLIEN with the drive held at the deck's centre (VO = YMDL = 22.05 mm/s: OMEGA = 1e-9, AMPV0 = VO):
    a stable origin, U.L.C. 14.3 mm and S.L.C. 45.2 mm peak to peak (exact flow)."""
    d = decay_deck()
    d.omega, d.ampv0, d.xinp, d.trigger = 1e-9, 22.05, x0, tuple(trigger)
    return run_deck(d, npts=npts)


def mlien_rising(trigger, ampv0: float = 32.0, npts: int = 40000):
    """MLIEN from stick-slip on the S.L.C. (X = 24.6 at VO = 22.05) with the drive rising slowly
    (OMEGA = -0.002) to AMPV0 = 32 mm/s, below the faithful step's v_oc (32.1 at DTHETA = 0.02: the
    listing's step adds energy), and falling again.  Returns the semi-amplitude of X over the 40 time units
    after the drive's peak."""
    d = decay_deck()
    d.omega, d.ampv0, d.trigger = -0.002, ampv0, tuple(trigger)
    res = run_deck(d, npts=npts)
    x, vo = np.asarray(res.x), np.asarray(res.ymdl)
    k = int(np.argmax(vo))
    return float(np.ptp(x[k:k + 2000]) / 2)


def main() -> None:
    X, Y = fig_2_21_at(22.0)
    fc = cycles.find_cycles(X, Y)
    ulc, slc = (c.amplitude / 2 for c in fc.cycles)
    D = -slope_at_origin(X, Y) / 2
    print(f"Fig. 2.21 at v0 = 22 mm/s: origin stable {fc.origin_stable}, damping D = {D:.3f}; U.L.C. semi-amplitude "
          f"{ulc:.3f} mm, S.L.C. {slc:.3f} mm (exact flow)")
    print(f"  the forced integrator with F = 0 from the S.L.C.: {settled(forced(X, Y, 0.0, 1.0, fc.cycles[1].x_right), 300, 400)[0]:.3f} mm")
    print("\nA. forcing, below threshold: the triggering cycle (semi-axes) against the linear forced ellipse")
    print("   r     F      X semi-axis   linear    Y/X")
    for r in (0.5, 1.0, 2.0):
        for F in (0.01, 0.1):
            ax, ay = settled(forced(X, Y, F, r), 320, 400)
            print(f"  {r:4.2f} {F:6.3f}  {ax:10.5f}  {linear_response(F, r, D):9.5f}  {ay / ax:5.3f}")
    print("\nB. forcing: threshold F* from rest at the origin to the S.L.C.; the forced ellipse there")
    print("   r     F*            ellipse X     ellipse Y (= r X)   U.L.C. X")
    for r in (0.25, 0.5, 1.0, 2.0, 4.0):
        lo, hi = threshold(X, Y, r, slc)
        a = linear_response(lo, r, D)
        print(f"  {r:4.2f} {lo:7.4f}..{hi:7.4f}  {a:8.3f}    {a * r:8.3f}          {ulc:6.3f}")
    Xu, Yu = fig_2_21_at(10.0)
    sigma = slope_at_origin(Xu, Yu) / 2
    slu = cycles.find_cycles(Xu, Yu).cycles[0].amplitude / 2
    print(f"\nC. unstable origin (v0 = 10): growth rate sigma = {sigma:.4f}; S.L.C. semi-amplitude {slu:.3f} mm")
    print("   F        time to |(X, Y)| > S.L.C./2   (without a trigger the origin stays: X = Y = 0 for all T)")
    ts = []
    for F in (1e-3, 1e-5, 1e-7):
        ts.append(time_to_reach(forced(Xu, Yu, F, 1.0, tmax=1500.0), slu / 2, 1500.0))
        print(f"  {F:7.0e}  {ts[-1]:8.2f}")
    print(f"  per decade of F: {(ts[2] - ts[0]) / 4:.3f} (ln 10 / sigma = {np.log(10) / sigma:.3f})")
    print("\nD. displacement of the state (MLIEN, drive held at 22.05 mm/s), from X = 0.5 near the stable origin:")
    print("   OMETRI  ATRI=BTRI  X semi-amplitude over the last fifth (12 phases OMINTR: min / median / max)")
    ph = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    for om, a in ((30000.0, 0.0), (1.0, 0.002), (1.0, 0.02), (30000.0, 0.02), (30000.0, 0.2)):
        amp = []
        for p in ph:
            res = mlien_held(0.5, (p, om, a, a))
            xx = np.asarray(res.x)
            amp.append(np.ptp(xx[-len(xx) // 5:]) / 2)
        print(f"  {om:7g}  {a:6.3f}    {np.min(amp):7.3f} / {np.median(amp):7.3f} / {np.max(amp):7.3f}")
    print("\nE. MLIEN, stick-slip with the drive rising to AMPV0 below v_oc: does it die out? (24 phases OMINTR)")
    print("   AMPV0  OMETRI  ATRI=BTRI  died out (X semi-amplitude < 10 mm after the drive's peak)")
    ph = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    for ampv0 in (31.5, 32.0):
        for om, a in ((30000.0, 0.0), (30000.0, 0.02), (30000.0, 0.05), (30000.0, 0.1), (1.0, 0.1)):
            amp = np.array([mlien_rising((p, om, a, a), ampv0) for p in ph])
            print(f"  {ampv0:5.1f} {om:7g}  {a:6.3f}     {int(np.sum(amp < 10))}/{ph.size}   "
                  f"(median {np.median(amp):.1f} mm)")


if __name__ == "__main__":
    main()
