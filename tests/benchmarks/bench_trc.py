"""TRC on 250 points with 8 BELFIT passes: the compiled core against a NumPy
reference of the same reduction, in one run.

Not a test: it prints times and the ratio (machines are shared and noisy).
Target of the TRC issue: < 1 ms for the compiled reduction.

    .venv/bin/python tests/benchmarks/bench_trc.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

import lieng

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from reference import belfit_reference  # noqa: E402


def numpy_trc(t, x, xn, omnh, omnv):
    """The reduction with NumPy: velocities, BELFIT by numpy.polyfit over every
    5-point group (8 passes), the reverse construction vectorised."""
    v = np.r_[0.0, np.diff(x) / np.diff(t)]
    vn = np.r_[0.0, np.diff(xn) / np.diff(t)]
    vln = belfit_reference(x, v / omnh)
    vnln = vn / omnv
    out = []
    for X, V in ((x, vln), (xn, vnln)):
        a, b, c = X[:-2], X[1:-1], X[2:]
        va, vb, vc = V[:-2], V[1:-1], V[2:]
        xk = b + vb * (va - vb) / (a - b)
        xl = b + vb * (vb - vc) / (b - c)
        l1 = np.hypot(a - b, va - vb)
        l2 = np.hypot(b - c, vb - vc)
        out.append((xk * l1 + xl * l2) / (l1 + l2))
    return out


def best(fn, reps):
    ts = []
    for _ in range(reps):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return min(ts)


def main():
    n = 250
    t = np.arange(n) * 2e-4
    x = 0.05 * np.sin(2 * np.pi * 20 * t) + 0.01 * np.sin(2 * np.pi * 53 * t)
    xn = 0.3 + 0.01 * np.cos(2 * np.pi * 20 * t)
    omnh, omnv = 188.5, 282.7
    t_core = best(lambda: lieng.trc(t, x, xn, omnh=omnh, omnv=omnv), 200)
    t_np = best(lambda: numpy_trc(t, x, xn, omnh, omnv), 5)
    print(f"TRC, {n} points, 8 BELFIT passes")
    print(f"  compiled core (lieng.trc, incl. Python checks): {t_core * 1e3:8.3f} ms  (target < 1 ms)")
    print(f"  NumPy reference (polyfit per group):            {t_np * 1e3:8.3f} ms")
    print(f"  ratio NumPy / compiled:                         {t_np / t_core:8.1f}x")


if __name__ == "__main__":
    main()
