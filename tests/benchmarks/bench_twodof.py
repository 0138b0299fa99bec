"""600 s of the 2-DoF rig (the paper's test length) with the compiled
switch-model integrator, against scipy's solve_ivp running the same hybrid
model (slip with an event at v0 - x2' = 0, stick with an event at
|Ff| = mus N) in one run.

Not a test: prints times and the ratio.  Targets: 600 s of rig time in under
1 s of compute (issue 2-DoF); an ensemble of 8 x 600 s in under 5 s (issue
15: the exact propagation between switches).  solve_ivp runs 20 s and is
scaled.

    .venv/bin/python tests/benchmarks/bench_twodof.py
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import solve_ivp

from lieng import twodof as T


def ivp_run(p, t_end, preload, v0, tol=1e-9):
    """The hybrid model with solve_ivp (RK45, events); returns the number of
    switches."""
    M, C, K, kn = T.matrices(p, T.PREVIOUS_READING)
    Minv = np.linalg.inv(M)

    def normal(x2):
        return max(preload + kn * x2, 0.0)

    def slip_rhs(d):
        def f(t, s):
            x, v = s[[0, 2]], s[[1, 3]]
            ff = d * p.muk * normal(s[2])
            a = Minv @ (-(C @ v) - K @ x + np.array([0.0, ff]))
            return [s[1], a[0], s[3], a[1]]
        return f

    def hold(s):
        x, v = np.array([s[0], s[2]]), np.array([s[1], v0])
        a1 = -(C[0] @ v + K[0] @ x) / M[0, 0]
        return a1, M[1, 0] * a1 + C[1] @ v + K[1] @ x

    def stick_rhs(t, s):
        return [s[1], hold(s)[0], v0, 0.0]

    t, s, stick, d, n = 0.0, np.array([0.0, 0.0, 0.0, v0]), True, 0.0, 0
    while t < t_end:
        if stick:
            ev = lambda t, s: p.mus * normal(s[2]) - abs(hold(s)[1])  # noqa: E731
            ev.terminal, ev.direction = True, -1
            r = solve_ivp(stick_rhs, (t, t_end), s, rtol=tol, atol=1e-12, events=ev)
        else:
            ev = lambda t, s, d=d: d * (v0 - s[3])  # noqa: E731
            ev.terminal, ev.direction = True, -1
            r = solve_ivp(slip_rhs(d), (t, t_end), s, rtol=tol, atol=1e-12, events=ev)
        t, s = r.t[-1], r.y[:, -1].copy()
        if r.status != 1:
            break
        n += 1
        if stick:
            stick, d = False, float(np.sign(hold(s)[1]))
        else:
            s[3] = v0
            ff = hold(s)[1]
            if abs(ff) <= p.mus * normal(s[2]):
                stick = True
            else:
                d = float(np.sign(ff))
    return n


def main():
    p = T.RigParams()
    rd = T.PREVIOUS_READING                     # the slow belt: the solve_ivp comparison stays affordable
    v0 = rd.belt_speed()
    T.simulate(p, t_end=1.0, reading=rd)        # imports, first call
    t0 = time.perf_counter()
    sim = T.simulate(p, t_end=600.0, preload=80.0, v0=v0, reading=rd)
    t_exact = time.perf_counter() - t0
    t0 = time.perf_counter()
    T.simulate(p, t_end=600.0, preload=80.0, v0=v0, reading=rd, method="rk4")
    t_rk4 = time.perf_counter() - t0
    t0 = time.perf_counter()
    n_ivp = ivp_run(p, 20.0, 80.0, v0)
    t_ivp = (time.perf_counter() - t0) * 600.0 / 20.0
    n_core = int(np.count_nonzero(np.diff(sim.stick[: int(20.0 / 1e-3) + 1].astype(int))))
    print(f"600 s of rig time at 80 N, belt {v0:.4g} m/s (2-DoF, switch model, reading {rd.name})")
    print(f"  exact (expm) : {t_exact:8.3f} s   (target < 1 s; {sim.nswitch} stick/slip switches)")
    print(f"  Runge-Kutta  : {t_rk4:8.3f} s")
    print(f"  solve_ivp    : {t_ivp:8.3f} s   (20 s measured, scaled)")
    print(f"  ratio        : {t_ivp / t_exact:8.1f}x")
    print(f"  switches in the first 20 s: core {n_core}, solve_ivp {n_ivp}")
    for rd in (T.DEFAULT_READING, T.PREVIOUS_READING):
        t0 = time.perf_counter()
        for x0 in T.initial_states(8, rd.belt_speed()):
            T.simulate(p, t_end=600.0, preload=80.0, x0=x0, reading=rd)
        t_sims = time.perf_counter() - t0
        t0 = time.perf_counter()
        T.ensemble(p, rd, preload=80.0, t_end=600.0, members=8)
        t_ens = time.perf_counter() - t0
        print(f"ensemble 8 x 600 s, reading {rd.name}: simulations {t_sims:.2f} s, with every metric "
              f"{t_ens:.2f} s (target < 5 s)")


if __name__ == "__main__":
    main()
