"""A 100 x 100 regime map (10^4 points) of Fig. 2.28's deck: v0 from 0.5 to
40 mm/s against dmu0 from 0.2 to 2 times the deck's, with v_oc bisected on
every row, on a local pool of 2 worker processes and serially in this
process.  Target of issue #19: under 2 minutes on 2 workers.

Not a test: it prints wall times and points per second (machines are shared
and noisy), and whether the two runs gave identical arrays.

    .venv/bin/python tests/benchmarks/bench_map.py [--n 100] [--workers 2] [--no-serial]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from lieng.programs import read_deck
from lieng.analysis.executor import open_executor
from lieng.analysis.regime_map import regime_map

DECK = Path(__file__).resolve().parents[2] / "cards" / "figures" / "fig2_28.dat"


def run(x, y, v0s, dmus, workers):
    t0 = time.perf_counter()
    if workers is None:
        m = regime_map(x, y, v0s, dmus=dmus, progress=False)
    else:
        with open_executor(workers=workers, tasks=len(dmus)) as ex:
            m = regime_map(x, y, v0s, dmus=dmus, executor=ex, progress=False)
    return m, time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=100, help="points along each axis (default 100: 10^4 points)")
    ap.add_argument("--workers", type=int, default=2, help="local worker processes (default 2)")
    ap.add_argument("--no-serial", action="store_true", help="skip the serial run")
    a = ap.parse_args()
    deck = read_deck(DECK)
    x, y = deck.xchl[:deck.n], deck.ychl[:deck.n]
    v0s, dmus = np.linspace(0.5, 40.0, a.n), np.linspace(0.2, 2.0, a.n)
    npts = v0s.size * dmus.size
    m, t_par = run(x, y, v0s, dmus, a.workers)
    print(f"regime map of {DECK.name}: {a.n} x {a.n} = {npts} points (exact mode, v_oc on every row)")
    print(f"  {a.workers} workers: {t_par:7.1f} s wall, {npts / t_par:6.0f} points/s   (target < 120 s)")
    if not a.no_serial:
        s, t_ser = run(x, y, v0s, dmus, None)
        same = all(np.array_equal(getattr(m, k), getattr(s, k), equal_nan=True)
                   for k in ("regime", "origin_stable", "slc", "ulc", "n_cycles", "v_oc"))
        print(f"  serial   : {t_ser:7.1f} s wall, {npts / t_ser:6.0f} points/s   (speed-up {t_ser / t_par:.2f}x; "
              f"identical arrays: {same})")
    print("  points per regime: " + ", ".join(f"{k} {v}" for k, v in m.counts().items()))
    print(f"  v_oc found on {int(np.isfinite(m.v_oc).sum())} of {dmus.size} rows")


if __name__ == "__main__":
    main()
