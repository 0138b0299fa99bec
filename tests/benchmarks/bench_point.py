"""Lienard steps per second: the compiled POINT core against a C loop of the same step and against NumPy,
in one run.

Not a test: it prints rates, ratios and the accuracy each side reaches (machines are shared and noisy).
Targets (issue #19): mode=fast >= 100 million steps/s on one core; the LIENG-1 issue's >= 20 M/s for the
listing's arithmetic.

The references:
* a C loop of the same step, compiled here with ``gcc -O2`` (``cc`` if gcc is missing) and called
  through ctypes once per run of steps: the listing's step (linear scan, ATAN/SIN/COS) and the fast step
  (band hunt, XB = A + B*Y, X + DTHETA*Y, Y - DTHETA*XK);
* NumPy, vectorised over 20000 trajectories at once (the fastest way to take this step in NumPy: one
  step of every trajectory per array operation).

    .venv/bin/python tests/benchmarks/bench_point.py
"""

from __future__ import annotations

import ctypes
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from lieng import _core

C_SOURCE = r"""
#include <math.h>
/* The listing's step: first JJ with Y >= YCHL(JJ) by a linear scan, THETA = ATAN(Y/XK). */
int listing(int n, const double *xc, const double *yc, double dth, long nsteps, double *px, double *py,
            double *pt) {
    double x = *px, y = *py, t = *pt;
    for (long l = 0; l < nsteps; l++) {
        double xb = xc[n - 1];
        for (int j = 0; j < n; j++) {
            double c = y - yc[j];
            if (c < 0.0) continue;
            if (c == 0.0) xb = xc[j];
            else if (j == 0) xb = xc[0];
            else xb = ((xc[j] - xc[j - 1]) * (yc[j - 1] - y) / (yc[j - 1] - yc[j])) + xc[j - 1];
            break;
        }
        double xk = x - xb, r = sqrt(y * y + xk * xk);
        if (xk == 0.0 && y == 0.0) return 1;
        double ds = dth * r, th = atan(y / xk);
        double dx = fabs(ds * sin(th)), dy = fabs(ds * cos(th)), den = 2.0 * y - dy;
        if (den == 0.0) return 2;
        t += fabs(2.0 * dx / den);
        if (xk >= 0.0 && y >= 0.0) { x += dx; y -= dy; }
        else if (xk >= 0.0) { x -= dx; y -= dy; }
        else if (y < 0.0) { x -= dx; y += dy; }
        else { x += dx; y += dy; }
    }
    *px = x; *py = y; *pt = t;
    return 0;
}
/* The fast step: the band followed from the previous step, XB = A + B*Y. */
int fast(int n, const double *xc, const double *yc, double dth, long nsteps, double *px, double *py,
         double *pt, double *a, double *b, double *lo, double *hi) {
    double x = *px, y = *py, t = *pt;
    a[0] = xc[0]; b[0] = 0.0; lo[0] = yc[0]; hi[0] = 1.79e308;
    a[n] = xc[n - 1]; b[n] = 0.0; lo[n] = -1.79e308; hi[n] = yc[n - 1];
    for (int k = 1; k < n; k++) {
        double s = (xc[k] - xc[k - 1]) / (yc[k - 1] - yc[k]);
        b[k] = -s; a[k] = xc[k - 1] + s * yc[k - 1]; lo[k] = yc[k]; hi[k] = yc[k - 1];
    }
    int k = n / 2;
    for (long l = 0; l < nsteps; l++) {
        while (k < n && y < lo[k]) k++;
        while (k > 0 && y >= hi[k]) k--;
        double xb = a[k] + b[k] * y, xk = x - xb;
        double dx = dth * fabs(y), dy = dth * fabs(xk), den = 2.0 * y - dy;
        if ((xk == 0.0 && y == 0.0) || den == 0.0) return 1;
        t += fabs(2.0 * dx / den);
        x += dth * y;
        y -= dth * xk;
    }
    *px = x; *py = y; *pt = t;
    return 0;
}
"""


def c_library():
    """The C reference compiled with -O2 -ffp-contract=off (the Fortran core's flags), or None."""
    cc = shutil.which("gcc") or shutil.which("cc")
    if cc is None:
        return None, "no C compiler"
    d = Path(tempfile.mkdtemp(prefix="lieng_bench_"))
    (d / "point.c").write_text(C_SOURCE)
    subprocess.run([cc, "-O2", "-ffp-contract=off", "-fPIC", "-shared", "-o", str(d / "point.so"),
                    str(d / "point.c"), "-lm"], check=True)
    lib = ctypes.CDLL(str(d / "point.so"))
    dp = ctypes.POINTER(ctypes.c_double)
    lib.listing.argtypes = [ctypes.c_int, dp, dp, ctypes.c_double, ctypes.c_long, dp, dp, dp]
    lib.fast.argtypes = [ctypes.c_int, dp, dp, ctypes.c_double, ctypes.c_long, dp, dp, dp, dp, dp, dp, dp]
    return lib, f"{Path(cc).name} -O2"


def characteristic(n):
    """A thesis-shaped characteristic with n points (v0 = 10 mm/s)."""
    v = np.linspace(40.0, -40.0, n)
    s = 10.0 - v
    u = np.abs(s)
    h = np.where(u <= 0.5, 20.0 * u, np.where(u <= 20.0, 10.0 - 4.0 * (u - 0.5) / 19.5, 6.0 + 0.1 * (u - 20.0)))
    return np.sign(s) * h, v


def numpy_steps(xchl, ychl, dtheta, x, y, nsteps):
    """The fast step, vectorised over many trajectories with NumPy."""
    xr, yr = xchl[::-1], ychl[::-1]
    t = np.zeros_like(x)
    for _ in range(nsteps):
        xb = np.interp(y, yr, xr, left=xchl[-1], right=xchl[0])
        xk = x - xb
        dx = dtheta * np.abs(y)
        dy = dtheta * np.abs(xk)
        t += np.abs(2.0 * dx / (2.0 * y - dy))
        x, y = x + dtheta * y, y - dtheta * xk
    return x, y, t


def best_of(fn, repeat=5):
    """The least wall time of ``repeat`` calls (the others were disturbed)."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main():
    lib, cname = c_library()
    nsteps = 4_000_000
    print("Lienard construction (POINT) steps per second, best of 5, one core; from (8, 1), 4e6 steps")
    print(f"{'N':>4} {'implementation':>40} {'Msteps/s':>9} {'vs C':>6} {'end point vs the listing':>25}")
    for n in (51, 200):
        xchl, ychl = characteristic(n)
        ends = {}

        def fortran(mode):
            x, y, t = np.array(8.0), np.array(1.0), np.array(0.0)
            status, _ = _core.core_advance(xchl, ychl, 0.01, nsteps, mode, x, y, t)
            assert status == 0
            ends[("F", mode)] = (float(x), float(y))

        def c_loop(kind):
            x, y, t = ctypes.c_double(8.0), ctypes.c_double(1.0), ctypes.c_double(0.0)
            xc = np.ascontiguousarray(xchl)
            yc = np.ascontiguousarray(ychl)
            dp = ctypes.POINTER(ctypes.c_double)
            args = [n, xc.ctypes.data_as(dp), yc.ctypes.data_as(dp), 0.01, nsteps, ctypes.byref(x), ctypes.byref(y),
                    ctypes.byref(t)]
            if kind == "fast":
                work = [np.zeros(n + 1) for _ in range(4)]
                args += [w.ctypes.data_as(dp) for w in work]
            assert getattr(lib, kind)(*args) == 0
            ends[("C", kind)] = (x.value, y.value)

        rates = {}
        for mode, kind, name in ((0, "listing", "listing (1971: scan, ATAN/SIN/COS)"),
                                 (1, None, "bisect (bit-identical to listing)"), (2, "fast", "fast")):
            rates[("F", mode)] = nsteps / best_of(lambda: fortran(mode))
            if lib is not None and kind is not None:
                rates[("C", kind)] = nsteps / best_of(lambda: c_loop(kind))
        m, k = 20000, 100
        x0 = np.random.default_rng(0).uniform(-5, 15, m)
        y0 = np.random.default_rng(1).uniform(-10, 20, m)
        rate_np = m * k / best_of(lambda: numpy_steps(xchl, ychl, 0.01, x0.copy(), y0.copy(), k), 3)
        ref = np.array(ends[("F", 0)])
        scale = 40.0

        def err(key):
            return f"{np.abs(np.array(ends[key]) - ref).max() / scale:.1e} (rel. to 40 mm)"

        rows = [("Fortran mode=listing", ("F", 0), ("C", "listing")),
                (f"C loop, listing step ({cname})", ("C", "listing"), ("C", "listing")),
                ("Fortran mode=bisect", ("F", 1), ("C", "listing")),
                ("Fortran mode=fast", ("F", 2), ("C", "fast")),
                (f"C loop, fast step ({cname})", ("C", "fast"), ("C", "fast"))]
        for name, key, cref in rows:
            if key not in rates:
                continue
            ratio = f"{rates[key] / rates[cref]:5.2f}x" if cref in rates else "   -  "
            print(f"{n:>4} {name:>40} {rates[key] / 1e6:9.1f} {ratio} {err(key):>25}")
        print(f"{n:>4} {'NumPy fast step, 20000 trajectories':>40} {rate_np / 1e6:9.1f}"
              f" {rate_np / rates[('C', 'fast')] if ('C', 'fast') in rates else float('nan'):5.2f}x"
              f" {'(same step, vectorised)':>25}")
        print(f"{'':>4} Fortran fast / NumPy: {rates[('F', 2)] / rate_np:.1f}x")
    print("targets: mode=fast >= 100 Msteps/s; the listing's arithmetic >= 20 Msteps/s.  'end point' is the")
    print("distance after 4e6 steps from the Fortran listing mode's end point: the fast step differs by")
    print("rounding only (DX = DTHETA*|Y| in place of DS*SIN(ATAN(Y/XK)), XB = A + B*Y).")


if __name__ == "__main__":
    main()
