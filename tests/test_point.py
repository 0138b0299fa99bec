"""POINT: the Lienard construction step, against geometry and an independent implementation."""

import numpy as np
import pytest

import lieng
from lieng import _core

import reference
from conftest import rng, thesis_characteristic


def random_characteristic(r, n):
    y = np.sort(r.uniform(-30, 30, n))[::-1]
    x = np.cumsum(r.uniform(-2, 2, n))
    x[np.abs(np.diff(np.concatenate([[np.inf], x]))) < 1e-6] += 0.01
    return x, y


def test_lookup_matches_np_interp_and_clamps():
    r = rng(1)
    for _ in range(20):
        x, y = random_characteristic(r, int(r.integers(3, 200)))
        ys = np.concatenate([r.uniform(y[-1] - 5, y[0] + 5, 500), y])  # incl. exact points and outside
        for mode in (0, 1):
            xb = _core.core_xb(x, y, ys, mode)
            np.testing.assert_allclose(xb, reference.xb_interp(x, y, ys), rtol=1e-12, atol=1e-12)
        above = ys > y[0]
        below = ys < y[-1]
        assert np.all(_core.core_xb(x, y, ys, 0)[above] == x[0])
        assert np.all(_core.core_xb(x, y, ys, 0)[below] == x[-1])


def test_bisect_lookup_identical_to_listing_scan():
    r = rng(2)
    x, y = random_characteristic(r, 200)
    ys = r.uniform(-40, 40, 20000)
    assert np.array_equal(_core.core_xb(x, y, ys, 0), _core.core_xb(x, y, ys, 1))


def test_step_geometry_perpendicular_length_direction():
    r = rng(3)
    x, y = random_characteristic(r, 50)
    for _ in range(2000):
        px, py = r.uniform(-40, 40), r.uniform(-40, 40)
        dth = r.uniform(1e-4, 0.2)
        xn, yn, tn, R, xb, xk, ds, dx, dy, dt, status = _core.core_point(x, y, dth, px, py, 0.0, 0)
        assert status == 0
        sx, sy = px - xb, py           # S -> P
        step = np.array([xn - px, yn - py])
        assert np.hypot(*step) == pytest.approx(dth * np.hypot(sx, sy), rel=1e-12)
        # perpendicular to SP
        assert abs(step @ np.array([sx, sy])) <= 1e-12 * np.hypot(*step) * np.hypot(sx, sy) + 1e-300
        # clockwise about S: moves right above the abscissa, left below
        assert np.sign(step[0]) == (1 if py > 0 else -1) or step[0] == 0
        assert sx * step[1] - sy * step[0] <= 0  # cross(SP, step) <= 0: clockwise
        # the DT formula of the listing
        assert dt == pytest.approx(abs(2 * dx / (2 * py - dy)), rel=1e-14)


def test_singular_point_is_reported_not_crashed():
    x = np.array([-1.0, 0.0, 1.0])
    y = np.array([1.0, 0.0, -1.0])
    *_, status = _core.core_point(x, y, 0.01, 0.0, 0.0, 0.0, 0)
    assert status == 4


@pytest.mark.parametrize("seed", range(4))
def test_lieng1_trajectories_match_independent_numpy(seed):
    r = rng(100 + seed)
    v0 = r.uniform(2, 20)
    x, y = thesis_characteristic(v0=v0, fs=r.uniform(5, 15), fm=r.uniform(1, 4), eps=r.uniform(0.2, 1),
                                 um=r.uniform(10, 30), c=r.uniform(0.02, 0.3), vmax=80, step=r.uniform(1, 4))
    dth = r.uniform(0.003, 0.03)
    x0, y0 = r.uniform(-5, 15), r.uniform(-10, 20)
    res = lieng.lieng1(x, y, x0, y0, dth, xincr=1.5, yincr=-2.0, ntraj=3, npts=3000)
    starts = np.array([[x0 - k * 1.5, y0 + k * 2.0] for k in range(3)])
    X, Y, _ = reference.point_steps(x, y, dth, starts[:, 0], starts[:, 1], 2999)
    scale = max(np.abs(X).max(), np.abs(Y).max())
    np.testing.assert_allclose(res.x, X.T, rtol=1e-9, atol=1e-9 * scale)
    np.testing.assert_allclose(res.y, Y.T, rtol=1e-9, atol=1e-9 * scale)


def test_time_correction_matches_literal_loop():
    x, y = thesis_characteristic()
    res = lieng.lieng1(x, y, 8.0, 1.0, 0.02, ntraj=1, npts=3000)
    _, Y, T = reference.point_steps(x, y, 0.02, [8.0], [1.0], 2999)
    t_ref = reference.time_correction(Y[:, 0], T[:, 0])
    np.testing.assert_allclose(res.t[0], t_ref, rtol=1e-9, atol=1e-9 * abs(t_ref).max())
    # the correction only acts near the abscissa: it changed something, and
    # left every increment that starts more than the band away untouched
    raw = np.diff(T[:, 0])
    cor = np.diff(res.t[0])
    assert np.any(raw != cor)
    far = np.abs(Y[:-1, 0]) >= 0.2
    far[:5] = True
    changed = ~np.isclose(raw, cor, rtol=1e-9, atol=1e-12)
    # an increment changes only at J, where |Y(J-1)| < 0.2, and becomes the
    # mean of the four before it; later increments keep their values
    assert not np.any(changed & far)
    for j in np.flatnonzero(changed):
        assert cor[j] == pytest.approx(np.mean(cor[j - 4:j]), rel=1e-9)
    assert np.all(cor > 0)  # time runs forward


def test_lookup_modes_give_identical_portraits():
    x, y = thesis_characteristic()
    a = lieng.lieng1(x, y, 8.0, 1.0, 0.01, yincr=-3.0, lookup="listing")
    b = lieng.lieng1(x, y, 8.0, 1.0, 0.01, yincr=-3.0, lookup="bisect")
    assert np.array_equal(a.x, b.x) and np.array_equal(a.y, b.y) and np.array_equal(a.t, b.t)


def test_fast_mode_agrees_with_listing_arithmetic():
    x, y = thesis_characteristic()
    a = lieng.lieng1(x, y, 8.0, 1.0, 0.01, yincr=-3.0, lookup="listing")
    b = lieng.lieng1(x, y, 8.0, 1.0, 0.01, yincr=-3.0, lookup="fast")
    scale = np.abs(a.x).max()
    np.testing.assert_allclose(b.x, a.x, rtol=1e-10, atol=1e-10 * scale)
    np.testing.assert_allclose(b.y, a.y, rtol=1e-10, atol=1e-10 * scale)
    # the O(NPTS) time correction of the fast mode gives the listing's corrected times to rounding
    assert np.count_nonzero(np.diff(a.t, axis=1) != np.diff(lieng.lieng1(x, y, 8.0, 1.0, 0.01, yincr=-3.0,
                            lookup="listing").t, axis=1)) == 0
    np.testing.assert_allclose(b.t, a.t, rtol=1e-10, atol=1e-12)


def test_the_fast_loop_takes_the_steps_of_the_fast_mode():
    """point_advance's mode_fast loop (a band hunt and XB = A + B*Y, for speed) ends where LIENG-1's
    mode_fast trajectory (point_step, the listing's interpolation) ends, and where the listing's trig
    arithmetic ends, to rounding; status and step of a failure as point_step reports them."""
    from lieng import _core

    x, y = thesis_characteristic()
    for x0, y0 in ((8.0, 1.0), (-3.0, 25.0), (40.0, -30.0)):
        ref = lieng.lieng1(x, y, x0, y0, 0.01, ntraj=1, npts=3000, lookup="fast")
        trig = lieng.lieng1(x, y, x0, y0, 0.01, ntraj=1, npts=3000, lookup="bisect")
        xs, ys, ts = np.array(x0), np.array(y0), np.array(0.0)
        status, where = _core.core_advance(x, y, 0.01, 2999, 2, xs, ys, ts)
        assert status == 0 and where == 0
        scale = np.abs(ref.x[0]).max()
        for got, a, b in ((xs, ref.x[0][-1], trig.x[0][-1]), (ys, ref.y[0][-1], trig.y[0][-1])):
            assert float(got) == pytest.approx(a, abs=1e-12 * scale)
            assert float(got) == pytest.approx(b, abs=1e-10 * scale)
        tb = np.array(0.0)
        assert _core.core_advance(x, y, 0.01, 2999, 1, np.array(x0), np.array(y0), tb)[0] == 0
        assert float(ts) == pytest.approx(float(tb), rel=1e-9)         # T before the time correction
    # the singular point: at the equilibrium on the first step
    xe = lieng.analysis.cycles.equilibrium(x, y)
    status, where = _core.core_advance(x, y, 0.01, 10, 2, np.array(xe), np.array(0.0), np.array(0.0))
    s1, w1 = _core.core_advance(x, y, 0.01, 10, 1, np.array(xe), np.array(0.0), np.array(0.0))
    assert (status, where) == (s1, w1) and status != 0 and where == 1
