"""A 200-velocity sweep (Fig. 2.27): the compiled exact return map against a
tuned scipy solve_ivp on the same equation, in one run.

Not a test: it prints times, ratios and the accuracy each side reaches
(machines are shared and noisy).  Target (issue #19): >= 300x the tuned
reference at equal accuracy.

The reference: one LSODA call per revolution (the left crossing an event,
the right crossing a terminal event), the characteristic by np.interp, at
two tolerances; it runs the same search (the same grid of starting points,
the same root finder) on a subset of the velocities, and its time is scaled
to 200.  Accuracy: the cycles' X_right against DOP853 at rtol = atol = 1e-13
with max_step 0.01 (the "truth", on the same subset).

    .venv/bin/python tests/benchmarks/bench_sweep.py
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from lieng import cycles


def characteristic(v0=10.0, fs=10.0, fm=6.0, eps=0.5, um=20.0, c=0.1, vmax=80.0):
    """Fig. 2.21's shape (plain NumPy)."""
    v = np.unique(np.concatenate([np.arange(-vmax, vmax + 1e-9, 2.0), np.linspace(v0 - eps, v0 + eps, 11),
                                  [v0 - um, v0 + um]]))[::-1]
    u = np.abs(v0 - v)
    h = np.where(u <= eps, fs * u / eps, np.where(u <= um, fs - (fs - fm) * (u - eps) / (um - eps), fm + c * (u - um)))
    return np.sign(v0 - v) * h, v


def ivp_return(x, v, x0, tol=1e-10, method="LSODA", max_step=np.inf):
    """One revolution from (x0, 0) in one solve_ivp call: P(x0) (NaN when it
    does not come back)."""
    xr, vr = x[::-1], v[::-1]

    def rhs(t, s):
        return [s[1], -(s[0] - np.interp(s[1], vr, xr))]

    def up(t, s):
        return s[1]
    up.direction = 1

    def down(t, s):
        return s[1]
    down.direction, down.terminal = -1, True
    r = solve_ivp(rhs, (0, 400), [x0, -1e-300], method=method, rtol=tol, atol=tol, events=[up, down],
                  max_step=max_step)
    return r.y_events[1][0][0] if r.t_events[1].size and r.t_events[0].size else np.nan


def ivp_cycles(x, v, ngrid=120, **kw):
    """find_cycles' search (sign changes of P - X0 on the same grid, brentq)
    with solve_ivp: the amplitudes' right-hand crossings."""
    xs = float(np.interp(0.0, v[::-1], x[::-1]))
    rmax = 2.0 * (np.abs(x - xs).max() + np.abs(v).max())
    r = np.geomspace(rmax * 1e-5, rmax, ngrid)
    d = np.array([ivp_return(x, v, xs + q, **kw) - (xs + q) for q in r])
    d = np.where(np.isnan(d), -r, d)
    out = []
    for k in range(ngrid - 1):
        if np.sign(d[k]) != np.sign(d[k + 1]):
            out.append(xs + brentq(lambda q: ivp_return(x, v, xs + q, **kw) - (xs + q), r[k], r[k + 1], xtol=1e-12))
    return out


def truth(x, v, xr):
    """A cycle's X_right refined with DOP853 at 1e-13 (brentq from the given one)."""
    xs = float(np.interp(0.0, v[::-1], x[::-1]))
    f = lambda q: ivp_return(x, v, xs + q, tol=1e-13, method="DOP853", max_step=0.01) - (xs + q)
    q = xr - xs
    return xs + brentq(f, q * (1 - 1e-4), q * (1 + 1e-4), xtol=1e-13)


def main():
    x, v = characteristic()
    v0s = np.linspace(0.5, 30.0, 200)
    best = np.inf
    for _ in range(3):
        t0 = time.perf_counter()
        cycles.sweep_v0(x, v, v0s, progress=False, find_voc=False)
        best = min(best, time.perf_counter() - t0)
    sub = v0s[::40]
    mine = {v0: sorted(c.x_right for c in cycles.find_cycles(*cycles.move_to_v0(x, v, v0)).cycles) for v0 in sub}
    true = {v0: [truth(*cycles.move_to_v0(x, v, v0), xr) for xr in mine[v0]] for v0 in sub}

    def err(found):
        worst = 0.0
        for v0 in sub:
            if len(found[v0]) != len(true[v0]):
                return f"{len(found[v0])} cycles at v0 = {v0:.3g} where there are {len(true[v0])}"
            for a, b in zip(sorted(found[v0]), true[v0]):
                worst = max(worst, abs(a - b) / abs(b))
        return f"{worst:.1e}"

    print(f"sweep of {len(v0s)} driving velocities (exact mode, 120-point scan and brentq each)")
    print(f"  {'implementation':<44} {'time (s)':>9} {'ratio':>8}  largest relative error of X_right")
    print(f"  {'compiled core (lieng.analysis.cycles.sweep_v0)':<44} {best:9.3f} {1.0:7.1f}x  {err(mine)}")
    for tol in (1e-7, 1e-10, 1e-12):
        t0 = time.perf_counter()
        ref = {v0: ivp_cycles(*cycles.move_to_v0(x, v, v0), tol=tol) for v0 in sub}
        t_ref = (time.perf_counter() - t0) * len(v0s) / len(sub)
        name = f"solve_ivp LSODA rtol=atol={tol:g}, 1 call/rev"
        print(f"  {name:<44} {t_ref:9.1f} {t_ref / best:7.1f}x  {err(ref)}")
    print("  (solve_ivp measured on 5 velocities and scaled to 200; errors against DOP853 at 1e-13 on those 5)")


if __name__ == "__main__":
    main()
