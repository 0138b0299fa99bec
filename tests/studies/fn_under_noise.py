"""How well the slips fix fn without --fn, under white noise.

An analytic Coulomb slider (``tests/test_diagnose.py::_coulomb_thresholds``:
rigid sticks at the drive velocity, each slip an exact half free period about
the kinetic level, fn = 10 Hz, 1000 samples a second, 30 slips, drop 1) with
white noise of 0.2-20 % of its drop, three draws each, diagnosed without
--fn: the fn read, its error, the stated relative uncertainty, and whether
the truth lies within it (or the record is refused, asking for --fn).  Run:

    python tests/studies/fn_under_noise.py
"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def main():
    from test_diagnose import _coulomb_thresholds

    from lieng.diagnose import diagnose, record_from_arrays
    from lieng.errors import LiengInputError

    print(f"{'noise / drop':>12} {'draw':>4} {'fn (Hz)':>8} {'error':>7} {'stated':>7}  within")
    for noise in (0.002, 0.02, 0.05, 0.1, 0.2):
        for seed in (1, 2, 3):
            t, x, v, _, _ = _coulomb_thresholds(n_cyc=30, sd=0.05, seed=seed, noise=noise, rate=1000.0)
            try:
                d = diagnose(record_from_arrays(t, x, v), None)
            except LiengInputError as e:
                print(f"{noise:>12.3f} {seed:>4}  refused: {str(e).split(': ', 1)[1]}")
                continue
            err = d.fn / 10.0 - 1.0
            print(f"{noise:>12.3f} {seed:>4} {d.fn:>8.3f} {100 * err:>+6.1f}% {100 * d.fn_uncertainty:>6.1f}%  "
                  f"{'yes' if abs(err) <= d.fn_uncertainty else 'NO'}")


if __name__ == "__main__":
    main()
