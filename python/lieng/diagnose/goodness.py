"""How well the baseline reproduces a record, apart from any effect: goodness-of-fit features compared with the
baseline's own replicates (:func:`.decide.misfit`), and the rig's ringing after each arrest."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from lieng.diagnose.segment import Cycles, Prepared, slip_seconds

__all__ = ["GOF", "GOF_MARGIN", "RIG", "arrest_ringing", "goodness"]


#: goodness-of-fit features of the baseline (not effects): the slip's duration
#: in half natural periods, the spread of the peaks over D, the spread of the
#: periods over their mean; a record that departs from the baseline's
#: replicates in one of them by more than GOF_MARGIN, with no candidate named,
#: is ``unexplained``
GOF = ("slip_duration", "peak_spread", "period_spread")
GOF_MARGIN = {"slip_duration": 0.25, "peak_spread": 0.10, "period_spread": 0.10, "arrest_ringing": 0.01}
#: features of the rig read like GOF but not a miss of the friction model: what rings after each arrest
#: (a second mode of the rig, :func:`arrest_ringing`), warned about where it departs from the replicates
RIG = ("arrest_ringing",)


@lru_cache(maxsize=4096)
def _quadratic_basis(n: int) -> np.ndarray:
    """An orthonormal basis of the quadratics on n equally spaced samples: x
    less its projection on it is x less its least-squares quadratic (the
    same residual as np.polyfit's, at a tenth of the cost per stick)."""
    tt = np.linspace(-1.0, 1.0, n)
    q, _ = np.linalg.qr(np.column_stack([np.ones(n), tt, tt * tt]))
    return q


def arrest_ringing(pr: Prepared, c: Cycles, fn: float, D: float) -> float:
    """What rings after each arrest (a second mode of the rig: the 1-DoF
    baseline's slider is still in stick): in each stick, the RMS of x about
    a quadratic over the first two natural periods after the trough (at
    most the stick's first half) less that over the stick's second half
    (its last tenth left out), over D; the median over the sticks (0 when
    fewer than three sticks are long enough)."""
    n2 = int(round(2.0 / (fn * pr.dt)))
    out = []
    for k in np.flatnonzero(c.next_ok):
        a, b = int(c.trough_i[k]), int(c.peak_i[k + 1])
        m = b - a
        if m < 24:
            continue
        w1 = min(n2, m // 2)
        late = (a + m // 2, a + int(0.9 * m))
        if w1 < 8 or late[1] - late[0] < 8:
            continue
        r = []
        for i0, i1 in ((a, a + w1), late):
            seg = pr.x[i0:i1]
            q = _quadratic_basis(seg.size)
            r.append(float(np.std(seg - q @ (q.T @ seg))))
        out.append(r[0] - r[1])
    return float(np.median(out)) / D if len(out) >= 3 else 0.0


def goodness(pr: Prepared, c: Cycles, fn: float, D: float) -> dict:
    """The goodness-of-fit features (see :data:`GOF`)."""
    dur = slip_seconds(pr, c)
    per = c.periods(pr.t)
    return {"slip_duration": float(dur * 2.0 * fn) if dur else 0.0,
            "peak_spread": float(np.std(pr.x[c.peak_i]) / D) if c.n > 1 else 0.0,
            "period_spread": float(np.std(per) / np.mean(per)) if per.size > 1 else 0.0,
            "arrest_ringing": arrest_ringing(pr, c, fn, D)}
