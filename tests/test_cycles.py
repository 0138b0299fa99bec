"""Limit cycles: the exact return map against independent integration, Table 2.IV's regimes, faithful vs exact."""

import json
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from lieng import cycles
from lieng.cli import main

from conftest import CARDS, rng, thesis_characteristic


def independent_revolution(x, v, x0):
    """One revolution from (x0, 0) with scipy's DOP853 and np.interp for the
    characteristic (no lieng code): returns x_left, x_right, period."""
    xr, vr = x[::-1], v[::-1]

    def rhs(t, s):
        return [s[1], -(s[0] - np.interp(s[1], vr, xr))]

    def up(t, s):
        return s[1]
    up.direction = 1
    up.terminal = True

    def down(t, s):
        return s[1]
    down.direction = -1
    down.terminal = True
    # first leg: down from the abscissa, back up across it on the left
    a = solve_ivp(rhs, (0, 200), [x0, -1e-300], method="DOP853", rtol=1e-11, atol=1e-11, events=[up],
                  max_step=0.01)
    t_up = a.t_events[0][0]
    x_left = a.y_events[0][0][0]
    b = solve_ivp(rhs, (t_up, t_up + 200), [x_left, 1e-300], method="DOP853", rtol=1e-11, atol=1e-11,
                  events=[down], max_step=0.01)
    return x_left, b.y_events[0][0][0], b.t_events[0][0]


@pytest.mark.parametrize("seed", range(3))
def test_exact_cycles_agree_with_independent_integration(seed):
    r = rng(500 + seed)
    x, v = thesis_characteristic(v0=r.uniform(3, 15), fs=r.uniform(6, 12), fm=r.uniform(2, 5), eps=r.uniform(0.3, 1),
                                 um=r.uniform(15, 30), c=r.uniform(0.05, 0.3), vmax=100, step=r.uniform(2, 5))
    res = cycles.find_cycles(x, v)
    assert res.cycles, "a stick-slip characteristic with v0 in the falling part has a stable cycle"
    for c in res.cycles:
        xl, xr, per = independent_revolution(x, v, c.x_right)
        assert xr == pytest.approx(c.x_right, rel=1e-6, abs=1e-6)   # a fixed point of the return map
        assert c.x_left == pytest.approx(xl, rel=1e-6, abs=1e-6)
        assert c.amplitude == pytest.approx(xr - xl, rel=1e-6)
        assert c.period == pytest.approx(per, rel=1e-5)


def test_return_map_of_linear_oscillator_is_exact():
    for c in (-0.4, -0.05, 0.1, 0.3):
        v = np.linspace(100, -100, 41)
        xl, xr, per = cycles.return_map(c * v, v, [3.0, 10.0])
        w = np.sqrt(1 - c * c / 4)
        np.testing.assert_allclose(xr, np.array([3.0, 10.0]) * np.exp(c * np.pi / w), rtol=1e-12)
        np.testing.assert_allclose(per, 2 * np.pi / w, rtol=1e-12)


def test_overdamped_origin_is_stable_with_no_cycle():
    v = np.linspace(50, -50, 21)
    res = cycles.find_cycles(-3.0 * v, v)  # x = -3 v: damping ratio 1.5, a stable node
    assert res.origin_stable and res.cycles == []


def test_table_2_iv_regimes_along_the_driving_velocity():
    """Table 2.IV: vr < v0 < vk: unstable origin, one stable cycle; vk < v0 < v_oc:
    stable origin with an unstable cycle inside the stable one; v0 > v_oc: none;
    -vr < v0 < vr: stable origin, no cycle."""
    eps, um = 0.5, 20.0
    x, v = thesis_characteristic(v0=10.0, eps=eps, um=um, vmax=80)
    s = cycles.sweep_v0(x, v, [0.0, 0.2, 2.0, 10.0, 18.0, 21.0, 23.0, 40.0], progress=False)
    o, S, U = s.origin_stable, s.stable_amplitude, s.unstable_amplitude
    # |v0| < vr: on the stick part
    assert o[0] and o[1] and S[0] is None and S[1] is None
    # vr < v0 < vk
    for k in (2, 3, 4):
        assert not o[k] and S[k] is not None and U[k] is None
    # vk < v0 < v_oc
    for k in (5, 6):
        assert o[k] and S[k] is not None and U[k] is not None and U[k] < S[k]
    # v0 > v_oc
    assert o[7] and S[7] is None and U[7] is None
    assert s.v_oc is not None and 23.0 < s.v_oc < 40.0
    # the U.L.C. grows with v0 until it meets the S.L.C.
    assert U[6] > U[5]


def test_faithful_mode_adds_energy_linearly_in_dtheta():
    x, v = thesis_characteristic(vmax=80)
    exact = cycles.find_cycles(x, v).stable_amplitude
    ex = []
    for d in (0.02, 0.01, 0.005):
        ex.append(cycles.find_cycles(x, v, mode="faithful", dtheta=d).stable_amplitude - exact)
    assert all(e > 0 for e in ex)  # the tangent step lengthens |SP|: the cycle moves out
    assert 1.6 < ex[0] / ex[1] < 2.4 and 1.6 < ex[1] / ex[2] < 2.4


def test_cycles_cli_json(capsys):
    assert main(["cycles", str(CARDS / "lieng1_demo.dat"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert isinstance(out["origin_stable"], bool)
    amps = [c["amplitude"] for c in out["cycles"]]
    assert amps == sorted(amps) and len(amps) >= 1
    assert {"amplitude", "stable", "period", "x_right"} <= set(out["cycles"][0])


def test_sweep_cli_json_nulls_and_no_progress_in_a_pipe():
    p = subprocess.run([sys.executable, "-m", "lieng.cli", "sweep", str(CARDS / "lieng1_demo.dat"), "--v0",
                        "5:35:4", "--json"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert p.stderr == ""  # no progress bar when standard error is not a terminal
    out = json.loads(p.stdout)
    assert out["v0"] == [5.0, 15.0, 25.0, 35.0]
    assert len(out["stable_amplitude"]) == 4 and out["stable_amplitude"][-1] is None
    assert out["unstable_amplitude"][0] is None


def test_sweep_bad_range_exits_2(capsys):
    assert main(["sweep", str(CARDS / "lieng1_demo.dat"), "--v0", "1:2"]) == 2
    assert "START:STOP:N" in capsys.readouterr().err


def _two_slope_characteristic(k, a, v0, stick_dy, stick_vertical=False):
    """A piecewise-linear characteristic of the MLIEN plane (through the
    origin, centre at (-k, v0)): the kinetic parts vertical (x = 0 below v0,
    x = -2k above: infinite slope), the stick part from (-k - a, v0 + dy) to
    (-k + a, v0 - dy) (zero slope as dy -> 0), or, with ``stick_vertical``,
    no stick part at all (both parts of infinite slope)."""
    e, d = 1e-9, stick_dy
    if stick_vertical:
        return np.array([-2 * k - e, -2 * k, 0.0, e]), np.array([v0 + 50, v0 + d, v0 - d, v0 - 50])
    return (np.array([-2 * k - e, -2 * k, -k - a, -k + a, 0.0, e]),
            np.array([v0 + 50, v0 + 2 * d, v0 + d, v0 - d, v0 - 2 * d, v0 - 50]))


def test_zero_and_infinite_slopes_give_an_arc_closed_by_a_straight_part():
    """Ch. 2.4.2.3: first part of zero slope, second infinite -> the cycle is a
    circular arc (slip about the kinetic line's point on the abscissa) closed
    by a straight part (stick at v0): it leaves the stick at the static peak
    X = a - k, so its amplitude is 2 sqrt((a - k)^2 + v0^2), and every
    trajectory whose arc meets the stick part is on it after one turn."""
    k, a, v0 = 3.0, 8.0, 5.0
    x, y = _two_slope_characteristic(k, a, v0, 1e-3)
    r = np.hypot(a - k, v0)
    res = cycles.find_cycles(x, y)
    stable = [c for c in res.cycles if c.stable]
    assert len(stable) == 1 and stable[0].amplitude == pytest.approx(2 * r, rel=2e-3)
    # from any start whose first arc lands on the stick part: P(X0) = r
    x0 = np.array([1.1 * v0, 1.5 * v0, np.hypot(a + k, v0) * 0.99])
    _, xr, _ = cycles.return_map(x, y, x0)
    np.testing.assert_allclose(xr, r, rtol=2e-3)
    # the error is the stick part's finite slope: it shrinks with it, down to
    # stick parts of slope ~1e6 (a 1e-5 mm/s rise: F10.4 decks allow 1e-4)
    _, xr2, _ = cycles.return_map(*_two_slope_characteristic(k, a, v0, 1e-2), x0[:1])
    assert abs(xr2[0] - r) > 3 * abs(xr[0] - r)
    _, xr3, _ = cycles.return_map(*_two_slope_characteristic(k, a, v0, 1e-5), x0)
    np.testing.assert_allclose(xr3, r, rtol=2e-5)


def test_both_slopes_infinite_give_circles():
    """Ch. 2.4.2.3: both parts of infinite slope -> the cycle becomes a circle
    (a conservative system): every orbit inside the drive velocity closes on
    itself, a circle about the origin of period 2 pi."""
    x, y = _two_slope_characteristic(3.0, 0.0, 5.0, 1e-3, stick_vertical=True)
    x0 = np.array([0.5, 2.0, 4.5])
    xl, xr, per = cycles.return_map(x, y, x0)
    np.testing.assert_allclose(xr, x0, rtol=1e-6)
    np.testing.assert_allclose(xl, -x0, rtol=1e-6)
    np.testing.assert_allclose(per, 2 * np.pi, rtol=1e-9)


def test_below_the_critical_dmu_no_self_sustained_oscillation():
    """Fig. 2.28: at a driving velocity with a stable origin (vk < v0 < v_oc),
    the S.L.C. grows with dmu0 = mu_s - mu_k0, and below a critical dmu_oc
    there is no self-sustained oscillation."""
    x, v = thesis_characteristic(v0=10.0, eps=0.5, um=20.0, vmax=80)
    f = [0.1, 0.3, 0.45, 0.7, 1.0, 1.4, 2.0]
    s = cycles.sweep_dmu(x, v, f, v0=21.0, progress=False)
    assert s.v_oc is not None and 0.45 < s.v_oc < 0.7
    S = s.stable_amplitude
    assert all(a is None for fac, a in zip(f, S) if fac < s.v_oc)
    above = [a for fac, a in zip(f, S) if fac > s.v_oc]
    assert all(a is not None for a in above) and all(np.diff(above) > 0)
    # scaling keeps mu_k0 and the rising part: the line beyond the kinetic minimum is unchanged
    xs, _ = cycles.scale_static_peak(x, v, 0.5)
    far = np.abs(10.0 - v) >= 20.0
    np.testing.assert_array_equal(xs[far], x[far])
    near = (np.abs(10.0 - v) > 0.5) & ~far
    assert np.all(np.abs(xs[near]) < np.abs(x[near]) + 1e-12)


def test_sweep_dmu_cli_json(capsys):
    code = main(["sweep", str(CARDS / "lieng1_demo.dat"), "--dmu", "0.5:1.5:3", "--json"])
    assert code == 0
    d = json.loads(capsys.readouterr().out)
    assert d["dmu"] == [0.5, 1.0, 1.5] and len(d["stable_amplitude"]) == 3 and "dmu_oc" in d


def test_at_v_oc_the_two_cycles_merge_into_one_semi_stable_cycle():
    """Table 2.IV: v0 = v_oc: one limit cycle, stable from outside and
    unstable from inside; just below it the S.L.C. and U.L.C. have nearly
    the same amplitude, just above there is none; v_oc does not depend on
    the scan grid (cycles closer than the grid spacing are still found)."""
    x, v = thesis_characteristic(v0=10.0, eps=0.5, um=20.0, vmax=80)
    s = cycles.sweep_v0(x, v, [23.0, 40.0], progress=False)
    fine = cycles.sweep_v0(x, v, [23.0, 40.0], progress=False, ngrid=600)
    assert s.v_oc == pytest.approx(fine.v_oc, rel=1e-4)
    below = cycles.find_cycles(*cycles.move_to_v0(x, v, s.v_oc * (1 - 1e-5)))
    assert below.stable_amplitude == pytest.approx(below.unstable_amplitude, rel=1e-3)
    assert below.unstable_amplitude <= below.stable_amplitude
    above = cycles.find_cycles(*cycles.move_to_v0(x, v, s.v_oc * (1 + 1e-3)))
    assert above.cycles == [] and above.origin_stable


def test_stick_phase_has_a_small_but_finite_relative_velocity():
    """Ch. 2.3.1.1: with a stick part of finite slope, 'stick' is sliding at
    a small relative velocity: on the limit cycle the velocity stays within
    the stick part's width EPS of v0 but not at v0."""
    from lieng import lieng1

    eps = 0.5
    x, v = thesis_characteristic(v0=10.0, eps=eps, um=20.0, vmax=80)
    c = cycles.find_cycles(x, v).cycles[-1]
    res = lieng1(x, v, xinp=c.x_right, yinp=0.0, dtheta=0.005, ntraj=1, npts=3000)
    rel = np.abs(res.y[0] - 10.0)
    stick = rel < eps
    assert stick.mean() > 0.05                       # there is a stick phase
    assert 0.0 < np.median(rel[stick]) < eps         # finite but small relative velocity
    assert np.all(rel[stick] > 0.0)
