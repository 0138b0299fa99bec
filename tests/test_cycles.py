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
