"""A linear characteristic x = c*v: LIENG-1 against the exact damped / growing oscillator.

With x = -phi(v) = c*v the construction integrates X'' - c X' + X = 0
(dX/dT = Y, dY/dT = -(X - c Y)).  Starting on the abscissa at (X0, 0), the
exact return to the positive abscissa after one revolution is
X0 * exp(c*pi/w), w = sqrt(1 - c^2/4).  The tangent step of POINT is first
order in DTHETA, so the error of the return must shrink linearly.
"""

import warnings

import numpy as np
import pytest

import lieng


def linear_char(c, vmax=100.0, n=41):
    v = np.linspace(vmax, -vmax, n)
    return c * v, v


def first_return(x, y):
    """X at the first crossing of the positive abscissa from above, after the
    trajectory has left it (linear interpolation between points)."""
    for i in range(10, len(y) - 1):
        if y[i] > 0 >= y[i + 1] and x[i] > 0:
            f = y[i] / (y[i] - y[i + 1])
            return x[i] + f * (x[i + 1] - x[i])
    raise AssertionError("no return to the abscissa")


def exact_return(x0, c):
    return x0 * np.exp(c * np.pi / np.sqrt(1 - c * c / 4))


@pytest.mark.parametrize("c", [-0.3, -0.1, 0.1, 0.25])
def test_return_map_converges_linearly(c):
    x0 = 10.0
    xchl, ychl = linear_char(c)
    errs = []
    dths = [0.02, 0.01, 0.005]
    for dth in dths:
        npts = int(2.5 * np.pi / dth)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # c > 0: no negative slope, no centre
            res = lieng.lieng1(xchl, ychl, x0, 0.0, dth, ntraj=1, npts=npts)
        errs.append(first_return(res.x[0], res.y[0]) - exact_return(x0, c))
    errs = np.abs(errs)
    # the tangent step lengthens the radius by sqrt(1 + DTHETA^2) a step:
    # about exp(pi*DTHETA) - 1 relative in one revolution, times the return
    bound = 2.0 * (np.exp(np.pi * dths[-1]) - 1.0) * exact_return(x0, c)
    assert errs[-1] < bound, (errs, bound)
    # first order: halving DTHETA halves the error
    for e1, e2 in zip(errs, errs[1:]):
        assert 1.7 < e1 / e2 < 2.3, errs


def test_growing_oscillator_grows_and_damped_decays():
    for c, grows in ((0.2, True), (-0.2, False)):
        xchl, ychl = linear_char(c)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = lieng.lieng1(xchl, ychl, 5.0, 0.0, 0.005, ntraj=1, npts=3000)
        r = np.hypot(res.x[0], res.y[0])
        assert (r[-1] > r[0]) == grows


def test_growing_characteristic_has_no_centre_in_api():
    xchl, ychl = linear_char(0.2)
    with pytest.warns(UserWarning, match="negative slope"):
        res = lieng.lieng1(xchl, ychl, 5.0, 0.0, 0.01, ntraj=1, npts=10)
    assert np.isnan(res.xmdl) and np.isnan(res.ymdl)


def test_damped_centre_is_the_origin_region():
    # x = c v with c < 0: all slopes equal and negative: the whole line is the run
    xchl, ychl = linear_char(-0.5, n=21)
    res = lieng.lieng1(xchl, ychl, 5.0, 0.0, 0.01, ntraj=1, npts=10)
    assert res.centre.lll == 1 and res.centre.mmm == 20
    # the listing's midpoint of points LLL and MMM (not MMM+1): half a segment above the origin
    assert res.ymdl == pytest.approx((ychl[0] + ychl[19]) / 2)
