"""Lienard steps per second: the compiled POINT core against NumPy, in one run.

Not a test: it prints rates and ratios (machines are shared and noisy).
Target of the LIENG-1 issue: >= 20 million steps/s on one core.

    .venv/bin/python tests/benchmarks/bench_point.py
"""

from __future__ import annotations

import time

import numpy as np

from lieng import _core


def characteristic(n):
    """A thesis-shaped characteristic with n points (v0 = 10 mm/s)."""
    v = np.linspace(40.0, -40.0, n)
    s = 10.0 - v
    u = np.abs(s)
    h = np.where(u <= 0.5, 20.0 * u, np.where(u <= 20.0, 10.0 - 4.0 * (u - 0.5) / 19.5, 6.0 + 0.1 * (u - 20.0)))
    return np.sign(s) * h, v


def numpy_steps(xchl, ychl, dtheta, x, y, nsteps):
    """The same POINT step, vectorised over many trajectories with NumPy."""
    xr, yr = xchl[::-1], ychl[::-1]
    t = np.zeros_like(x)
    for _ in range(nsteps):
        xb = np.interp(y, yr, xr, left=xchl[-1], right=xchl[0])
        xk = x - xb
        r = np.sqrt(y * y + xk * xk)
        theta = np.arctan(y / xk)
        ds = dtheta * r
        dx = np.abs(ds * np.sin(theta))
        dy = np.abs(ds * np.cos(theta))
        t += np.abs(2.0 * dx / (2.0 * y - dy))
        x = x + np.where(y >= 0, dx, -dx)
        y = y + np.where(xk >= 0, -dy, dy)
    return x, y, t


def best_of(fn, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main():
    print("Lienard construction (POINT) steps per second, best of 3, one core")
    print(f"{'characteristic':>16} {'implementation':>34} {'Msteps/s':>10} {'vs NumPy':>9}")
    for n in (51, 200):
        xchl, ychl = characteristic(n)
        nsteps = 4_000_000

        def compiled(mode):
            x, y, t = np.array(8.0), np.array(1.0), np.array(0.0)
            status, _ = _core.core_advance(xchl, ychl, 0.01, nsteps, mode, x, y, t)
            assert status == 0

        m, k = 20000, 100
        x0 = np.random.default_rng(0).uniform(-5, 15, m)
        y0 = np.random.default_rng(1).uniform(-10, 20, m)
        t_np = best_of(lambda: numpy_steps(xchl, ychl, 0.01, x0.copy(), y0.copy(), k))
        rate_np = m * k / t_np
        rows = [("NumPy, 20000 trajectories at once", rate_np)]
        for mode, name in ((0, "Fortran mode=listing (1971)"), (1, "Fortran mode=bisect (bit-identical)"),
                           (2, "Fortran mode=fast (no trig calls)")):
            rows.append((name, nsteps / best_of(lambda: compiled(mode))))
        for name, rate in rows:
            print(f"{'N = ' + str(n):>16} {name:>34} {rate / 1e6:10.1f} {rate / rate_np:8.1f}x")
    print("target: >= 20 Msteps/s for the compiled core. mode=listing keeps the listing's ATAN/SIN/COS and its")
    print("linear scan; mode=fast is the same step in exact arithmetic (agrees to ~1e-15 relative a step).")


if __name__ == "__main__":
    main()
