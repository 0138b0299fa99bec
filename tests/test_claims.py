"""What the thesis says its programs show, sentence by sentence (docs/claims.md
lists each claim with its line in the seed, this test and the verdict).  Each
test states what the model gives, so it fails if the model changes, whether the
claim holds or not."""

import numpy as np
import pytest

from lieng import cycles, read_deck

from conftest import CARDS, thesis_characteristic

SEED = "000_7c260326492ada3e.txt"


def _fig_2_21():
    return thesis_characteristic(v0=10.0, eps=0.5, um=20.0, vmax=80)


def test_slc_grows_with_v0_where_the_thesis_says_it_shrinks():
    """Ch. 2.4.2.1 d (seed lines 2663-2665): "As vo increases the stable
    limiting cycle decreases in size while the unstable limiting cycle
    increases."  Contradicted for the S.L.C. on Fig. 2.21's shape: it grows
    with v0 from the first critical velocity to v_oc (and the U.L.C. grows,
    as said)."""
    x, v = _fig_2_21()
    v0 = [2.0, 6.0, 10.0, 14.0, 18.0, 21.0, 22.0, 23.0]
    s = cycles.sweep_v0(x, v, v0, progress=False)
    S = np.array(s.stable_amplitude, float)
    assert np.all(np.diff(S) > 0), S                        # the S.L.C. grows: the claim does not hold
    U = [a for a in s.unstable_amplitude if a is not None]
    assert len(U) >= 2 and np.all(np.diff(U) > 0)           # the U.L.C. grows: holds


def test_mu_levels_shifted_with_dmu0_fixed_move_the_cycle_not_its_size():
    """Ch. 2.4.2.2 (seed lines 2721-2724): "variation of mu_s or mu_k
    separately under dmu0 constant produces a change of the limiting cycle
    position but leaves unaffected its size."  Holds: the characteristic
    shifted along x by c keeps the S.L.C.'s amplitude and period, and the
    equilibrium (the characteristic at v0) moves by c."""
    x, v = _fig_2_21()
    for c in (-2.0, 3.0):
        a = cycles.find_cycles(*cycles.move_to_v0(x, v, 6.0)).cycles[0]
        b = cycles.find_cycles(*cycles.move_to_v0(x + c, v, 6.0)).cycles[0]
        assert b.amplitude == pytest.approx(a.amplitude, rel=1e-12)
        assert b.period == pytest.approx(a.period, rel=1e-12)
        eq = lambda xx: float(np.interp(6.0, v[::-1], xx[::-1]))
        assert eq(x + c) - eq(x) == pytest.approx(c)


def test_fig_2_26_deck_shows_a_stable_node_not_a_focus():
    """Ch. 2.4.2.1 a (seed lines 2607-2616), Fig. 2.26: "The origin is a
    stable focal point ... disturbances of the slider equilibrium produce
    damped oscillations."  Stable: holds.  A focus: not on the shipped deck,
    whose trajectories cross the drive velocity at most twice in 3000 points
    (a node: they fall onto the stick part of the characteristic)."""
    r = read_deck(CARDS / "figures" / "fig2_26.dat", program="lieng1").run()
    y = np.asarray(r.y) - r.ymdl
    crossings = [int(np.count_nonzero(np.diff(np.sign(yy[np.abs(yy) > 1e-9])) != 0)) for yy in y]
    assert max(crossings) <= 2, crossings


def test_a_rising_part_steeper_than_the_falling_one_makes_the_slc_shrink_to_v_k():
    """Issue #18, part 2 (tests/studies/slc_vs_v0.py): with the rising part
    beyond the kinetic minimum steeper than the falling one (here 2.4 times),
    the S.L.C. shrinks as v0 rises while the origin is still unstable and
    vanishes where it turns stable, with no U.L.C. and no v_oc: a shrinking
    S.L.C., but not the thesis's picture of one meeting a growing U.L.C."""
    x, v = thesis_characteristic(v0=10.0, fs=10.0, fm=6.0, eps=0.5, um=20.0, c=0.5, vmax=300)
    v0 = np.linspace(16.0, 20.0, 5)                     # (it grows up to v0 = 15, then shrinks)
    s = cycles.sweep_v0(x, v, v0, progress=False)
    S = np.array(s.stable_amplitude, float)
    assert not any(s.origin_stable) and np.all(np.diff(S) < 0), S
    assert all(a is None for a in s.unstable_amplitude)
    after = cycles.sweep_v0(x, v, [22.0, 30.0], progress=False)
    assert all(after.origin_stable) and after.stable_amplitude == [None, None] and after.v_oc is None
