"""TRC on 250 points with 8 BELFIT passes: the compiled core against NumPy references of the same
reduction, in one run.

Not a test: it prints times, ratios and the agreement of the smoothed velocities (machines are shared and
noisy).  Target of the TRC issue: < 1 ms for the compiled reduction.  Two NumPy references:
* vectorised (the strongest): every 5-point window's least-squares projection from one batched QR of the
  windows' Vandermonde matrices, applied to all windows at once in each of the 8 passes;
* a polyfit per window in a Python loop (tests/reference.py, the readable reference the tests use).

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


def belfit_vectorised(x, y, deg=2, n=5, passes=8):
    """Ch. 3.3.2's group fitting, vectorised: each window's fitted values are its projection Q Q^T y onto
    the polynomials of degree ``deg`` (Q from a batched QR of the centred Vandermonde matrices, once); each
    point becomes the mean of the fitted values of the windows that hold it."""
    x = np.asarray(x, float)
    y = np.asarray(y, float).copy()
    w = np.lib.stride_tricks.sliding_window_view(x, n)
    u = w - w.mean(axis=1, keepdims=True)
    q, _ = np.linalg.qr(u[:, :, None] ** np.arange(deg + 1))          # (windows, n, deg + 1)
    cnt = np.zeros(x.size)
    for i in range(n):
        cnt[i:i + len(w)] += 1
    for _ in range(passes):
        yw = np.lib.stride_tricks.sliding_window_view(y, n)
        fit = np.einsum("wij,wkj,wk->wi", q, q, yw)
        acc = np.zeros(x.size)
        for i in range(n):
            acc[i:i + len(w)] += fit[:, i]
        y = acc / cnt
    return y


def numpy_trc(t, x, xn, omnh, omnv, belfit=belfit_vectorised):
    """The reduction with NumPy: velocities, BELFIT (8 passes), the reverse construction vectorised."""
    v = np.r_[0.0, np.diff(x) / np.diff(t)]
    vn = np.r_[0.0, np.diff(xn) / np.diff(t)]
    vln = belfit(x, v / omnh)
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
    return vln, out


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
    t_vec = best(lambda: numpy_trc(t, x, xn, omnh, omnv), 50)
    t_loop = best(lambda: numpy_trc(t, x, xn, omnh, omnv, belfit_reference), 5)
    vln = lieng.trc(t, x, xn, omnh=omnh, omnv=omnv).vln
    scale = np.abs(vln).max()
    d_vec = np.abs(numpy_trc(t, x, xn, omnh, omnv)[0] - vln).max() / scale
    d_loop = np.abs(numpy_trc(t, x, xn, omnh, omnv, belfit_reference)[0] - vln).max() / scale
    print(f"TRC, {n} points, 8 BELFIT passes (best of repeated runs)")
    print(f"  compiled core (lieng.programs.trc, incl. Python checks): {t_core * 1e3:8.3f} ms  (target < 1 ms)")
    print(f"  NumPy, vectorised BELFIT (batched QR):          {t_vec * 1e3:8.3f} ms  {t_vec / t_core:6.1f}x the core;"
          f" smoothed velocity within {d_vec:.1e} of the core's (relative to its largest)")
    print(f"  NumPy, polyfit per window in a Python loop:     {t_loop * 1e3:8.3f} ms  {t_loop / t_core:6.1f}x the core;"
          f" within {d_loop:.1e}")


if __name__ == "__main__":
    main()
