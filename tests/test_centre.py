"""The centre-of-symmetry search of PINPUT on symmetric and asymmetric characteristics."""

import numpy as np
import pytest

from lieng import LiengInputError, centre_of_symmetry
from lieng.errors import CentreUndefined

from conftest import rng


def symmetric_char(xc, yc, stick_pts, outer):
    """A characteristic point-symmetric about (xc, yc).

    ``stick_pts``: offsets (dx, dy) of the upper half of the stick run from
    the centre (dy > 0, dx < 0: negative slope), nearest first; ``outer``:
    offsets of the points beyond it (positive then negative slopes)."""
    upper = [(xc + dx, yc + dy) for dx, dy in list(stick_pts) + list(outer)]
    lower = [(2 * xc - px, 2 * yc - py) for px, py in upper]
    pts = upper[::-1] + [(xc, yc)] + lower
    x, y = np.array(pts).T
    return x, y


def test_symmetric_characteristic_centre_is_half_a_segment_off():
    # The listing takes the midpoint of points LLL and MMM, the first points of
    # the first and last negative segments: for a symmetric run that is the
    # true centre moved by half of the last segment of the run.
    r = rng(7)
    for _ in range(50):
        xc, yc = r.uniform(-5, 5), r.uniform(1, 20)
        k = int(r.integers(1, 6))
        dys = np.cumsum(r.uniform(0.05, 0.3, k))
        dxs = -np.cumsum(r.uniform(0.5, 3.0, k))
        stick = list(zip(dxs, dys))
        outer = [(dxs[-1] + 2.0, dys[-1] + 10.0), (dxs[-1] + 1.0, dys[-1] + 30.0)]
        x, y = symmetric_char(xc, yc, stick, outer)
        c = centre_of_symmetry(x, y)
        # the end slopes are equal up to rounding, so any branch may be taken;
        # the interpolation is continuous there and gives the same point
        nrun = c.mmm - c.lll + 1
        assert nrun == 2 * k
        half_last = np.array([x[c.mmm] - x[c.mmm - 1], y[c.mmm] - y[c.mmm - 1]]) / 2
        assert c.xmdl == pytest.approx(xc - half_last[0], abs=1e-9)
        assert c.ymdl == pytest.approx(yc - half_last[1], abs=1e-9)


def test_centre_converges_as_the_stick_part_is_refined():
    xc, yc = 1.5, 8.0
    errs = []
    for k in (2, 8, 32):
        dys = np.linspace(0.5 / k, 0.5, k)
        dxs = -np.linspace(10.0 / k, 10.0, k)
        x, y = symmetric_char(xc, yc, zip(dxs, dys), [(-6.0, 20.0), (-7.0, 40.0)])
        c = centre_of_symmetry(x, y)
        errs.append(np.hypot(c.xmdl - xc, c.ymdl - yc))
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 0.2


def reference_centre(x, y):
    """The search of statements 135-2001, re-derived with NumPy from the text:
    I = the negative slope of largest value; the run around it; the equal-slope
    interpolation on the steeper end."""
    s = np.diff(y) / np.diff(x)
    neg = np.flatnonzero(s[: len(s) - 1] < 0)  # the listing never starts at SLOPE(K)
    first = neg[0]
    cand = np.flatnonzero(s < 0)
    cand = cand[cand >= first]
    i = cand[np.argmax(s[cand])]  # first of the largest
    lll = i
    while lll - 1 >= 0 and s[lll - 1] < 0:
        lll -= 1
    mmm = i
    while mmm + 1 < len(s) and s[mmm + 1] < 0:
        mmm += 1
    if s[lll] < s[mmm]:
        f = (s[mmm] - s[lll]) / (s[lll + 1] - s[lll])
        xx, yy = x[lll] + f * (x[lll + 1] - x[lll]), y[lll] + f * (y[lll + 1] - y[lll])
        return (xx + x[mmm]) / 2, (yy + y[mmm]) / 2, -1
    if s[lll] > s[mmm]:
        f = (s[lll] - s[mmm - 1]) / (s[mmm] - s[mmm - 1])
        xx, yy = x[mmm - 1] + f * (x[mmm] - x[mmm - 1]), y[mmm - 1] + f * (y[mmm] - y[mmm - 1])
        return (xx + x[lll]) / 2, (yy + y[lll]) / 2, 1
    return (x[lll] + x[mmm]) / 2, (y[lll] + y[mmm]) / 2, 0


@pytest.mark.parametrize("seed", range(30))
def test_asymmetric_characteristics_follow_the_listing(seed):
    r = rng(300 + seed)
    # positive-slope flanks around a run of 2-6 negative slopes of varying value
    k = int(r.integers(2, 7))
    slopes = -np.sort(r.uniform(0.02, 2.0, k))  # steepest to shallowest
    if r.random() < 0.5:
        slopes = slopes[::-1]
    r.shuffle(slopes[1:-1]) if k > 2 else None
    dy = -r.uniform(0.2, 1.0, k)
    dx = dy / slopes
    flank_up = [(-r.uniform(1, 3), -r.uniform(3, 9)) for _ in range(3)]  # positive slope going down
    segs = flank_up + list(zip(dx, dy)) + flank_up
    x = np.concatenate([[0.0], np.cumsum([s[0] for s in segs])])
    y = np.concatenate([[30.0], 30.0 + np.cumsum([s[1] for s in segs])])
    c = centre_of_symmetry(x, y)
    xm, ym, br = reference_centre(x, y)
    assert c.branch == br
    assert c.xmdl == pytest.approx(xm, rel=1e-12, abs=1e-12)
    assert c.ymdl == pytest.approx(ym, rel=1e-12, abs=1e-12)


def test_no_negative_slope_is_an_error():
    y = np.linspace(10, -10, 9)
    with pytest.raises(CentreUndefined, match="not a negative slope"):
        centre_of_symmetry(0.3 * y, y)


def test_equal_slope_interpolation_division_by_zero_is_an_error():
    # run slopes -2, -2, -1: SLOPE(LLL) < SLOPE(MMM) and SLOPE(LLL+1) = SLOPE(LLL)
    segs = [(-1.0, -5.0), (1.0, -2.0), (1.0, -2.0), (2.0, -2.0), (-1.0, -5.0)]
    x = np.concatenate([[0.0], np.cumsum([s[0] for s in segs])])
    y = np.concatenate([[20.0], 20.0 + np.cumsum([s[1] for s in segs])])
    with pytest.raises(CentreUndefined, match="divides by zero"):
        centre_of_symmetry(x, y)


@pytest.mark.parametrize("x, y, msg", [
    ([0.0, 1.0, 1.0, 2.0], [3.0, 2.0, 1.0, 0.0], "infinite slope"),
    ([0.0, 1.0, 2.0, 3.0], [3.0, 2.0, 2.5, 0.0], "decrease strictly"),
    ([0.0, 1.0], [1.0, 0.0], "at least 3"),
    ([0.0, np.nan, 2.0], [1.0, 0.0, -1.0], "not a finite"),
])
def test_bad_characteristics(x, y, msg):
    with pytest.raises(LiengInputError, match=msg):
        centre_of_symmetry(x, y)
