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


# --- The triggering oscillation (issue #18, part 3; tests/studies/triggering.py prints the tables that
# docs/claims.md quotes).  Two representations: a harmonic forcing F cos(r T) of the Lienard-plane equation
# (the study's own solve_ivp integrator), and the listing's displacement of the state (MLIEN's POINT).

def _stable_origin_case():
    from studies.triggering import fig_2_21_at, slope_at_origin

    X, Y = fig_2_21_at(22.0)
    fc = cycles.find_cycles(X, Y)
    assert fc.origin_stable and [c.kind for c in fc.cycles] == ["unstable", "stable"]
    return X, Y, fc.cycles[0].amplitude / 2, fc.cycles[1].amplitude / 2, -slope_at_origin(X, Y) / 2


def test_near_a_stable_origin_a_trigger_settles_on_the_triggering_cycle():
    """Ch. 2.4.1.2 (seed lines 2584-2588): "In case of a stable origin a trajectory approaching it stabilizes
    itself on the triggering cycle instead of the origin 0 ... equilibrium is replaced by quasi-sinusoidal
    vibration."  Holds for both representations.  As a forcing the cycle is the linear forced ellipse (X
    semi-axis F / sqrt((1 - r^2)^2 + (2 D r)^2), Y semi-axis r times it); as the listing's displacement of
    the state with OMETRI = 1 its size is proportional to ATRI."""
    from studies.triggering import forced, linear_response, mlien_held, settled

    X, Y, ulc, slc, D = _stable_origin_case()
    assert D == pytest.approx(0.05, rel=1e-9)
    assert settled(forced(X, Y, 0.0, 1.0, 0.5), 320, 400)[0] < 1e-6            # no trigger: the origin
    for r in (0.5, 2.0):
        ax, ay = settled(forced(X, Y, 0.1, r), 320, 400)
        assert ax == pytest.approx(linear_response(0.1, r, D), rel=1e-3)
        assert ay / ax == pytest.approx(r, rel=1e-3)
    amp = {}
    for a in (0.0, 0.002, 0.02):
        x = np.asarray(mlien_held(0.5, (1.25, 1.0, a, a)).x)
        amp[a] = np.ptp(x[-x.size // 5:]) / 2
    assert amp[0.0] < 1e-6
    assert 0 < amp[0.02] < ulc / 5 and amp[0.02] / amp[0.002] == pytest.approx(10.0, rel=0.1)


def test_between_v_k_and_v_oc_self_sustained_oscillation_depends_on_the_trigger():
    """Ch. 2.4.2.1 d (seed lines 2668-2673), Table 2.IV row 4: for vk < v0 < v_oc "the existence or not of
    frictional oscillations of the self-sustained type depends on the characteristics of the triggering
    oscillation. In the case where the triggering oscillation is not enough ... the system stabilizes itself
    on the triggering cycle."  Holds, with a sharp threshold.  As a forcing at resonance (r = 1) it is
    F* = 0.213 mm, whose forced ellipse (2.13 mm) lies well inside the U.L.C. (7.15 mm): the forcing pumps
    energy across the unstable cycle.  At r = 0.25 the ellipse must reach the U.L.C. (7.06 at F* = 6.62).
    As the listing's displacement of the state (OMETRI = 30000): ATRI = BTRI = 0.02 stays on the triggering
    cycle, 0.2 reaches the S.L.C. from every trigger phase."""
    from studies.triggering import forced, linear_response, mlien_held, settled

    X, Y, ulc, slc, D = _stable_origin_case()
    below = settled(forced(X, Y, 0.200, 1.0), 320, 400)[0]
    above = settled(forced(X, Y, 0.216, 1.0), 320, 400)[0]
    assert below == pytest.approx(linear_response(0.200, 1.0, D), rel=0.03) and below < ulc / 3
    assert above > 0.9 * slc
    assert settled(forced(X, Y, 6.60, 0.25), 320, 400)[0] < ulc
    assert settled(forced(X, Y, 6.65, 0.25), 320, 400)[0] > 0.9 * slc
    for p in np.linspace(0, 2 * np.pi, 6, endpoint=False):
        small = np.asarray(mlien_held(0.5, (p, 30000.0, 0.02, 0.02)).x)
        large = np.asarray(mlien_held(0.5, (p, 30000.0, 0.2, 0.2)).x)
        assert np.ptp(small[-small.size // 5:]) / 2 < ulc / 3
        assert np.ptp(large[-large.size // 5:]) / 2 > 0.9 * slc


def test_a_high_frequency_trigger_excites_with_a_small_displacement_but_not_the_least_force():
    """Ch. 2.4.1.2 (seed lines 2574-2577): "Even assuming the amplitude A to be very small, A.w could be
    enough (for w high) to excite an oscillation."  Partly: as a forcing at r = 4 the triggering cycle at
    the threshold has a displacement semi-axis of 1.24 mm (a sixth of the U.L.C.'s 7.15) and a velocity
    semi-axis of 4.96 mm/s: it is the velocity excursion past the kinetic minimum (2 mm/s away) that feeds
    the growth (at F = 15 the cycle is already 2.4 times the linear ellipse).  But the force needed rises as
    r^2 above resonance (F* = 18.6 at r = 4 against 0.213 at r = 1), so a high frequency is not the easiest
    way to excite."""
    from studies.triggering import forced, linear_response, settled

    X, Y, ulc, slc, D = _stable_origin_case()
    assert settled(forced(X, Y, 10.0, 4.0), 320, 400)[0] == pytest.approx(linear_response(10.0, 4.0, D), rel=0.1)
    assert settled(forced(X, Y, 15.0, 4.0), 320, 400)[0] > 2 * linear_response(15.0, 4.0, D)
    assert settled(forced(X, Y, 20.0, 4.0), 320, 400)[0] > 0.9 * slc
    assert linear_response(18.6, 4.0, D) < ulc / 5 < 4 * linear_response(18.6, 4.0, D)


def test_an_unstable_origin_is_left_only_with_a_trigger():
    """Ch. 2.4.1.2 (seed lines 2538-2542) and 2.4.2.1 b (2617-2619): the triggering oscillation "can remove
    the representative point of an unstable equilibrium and trigger thus a frictional oscillation, which
    otherwise could only be obtained after infinite time".  Holds: with a forcing F the S.L.C. is reached
    after a time that grows as ln(1 / F) / sigma, sigma = half the slope at the origin (22.6 per decade of F
    against ln 10 / sigma = 22.45).  Without a trigger, from the computed equilibrium (1.7e-16 mm off the
    exact one) the point leaves only through rounding, after T = 390, as the same law gives for a trigger
    of about 1e-17 mm: in exact arithmetic never."""
    from studies.triggering import fig_2_21_at, forced, slope_at_origin, time_to_reach

    X, Y = fig_2_21_at(10.0)
    fc = cycles.find_cycles(X, Y)
    assert not fc.origin_stable
    half = fc.cycles[0].amplitude / 4
    sigma = slope_at_origin(X, Y) / 2
    t3, t7 = (time_to_reach(forced(X, Y, F, 1.0, tmax=400.0), half, 400.0) for F in (1e-3, 1e-7))
    assert (t7 - t3) / 4 == pytest.approx(np.log(10) / sigma, rel=0.03)
    t0 = time_to_reach(forced(X, Y, 0.0, 1.0, x0=cycles.equilibrium(X, Y), tmax=600.0), half, 600.0)
    assert t0 > t7 + 8 * np.log(10) / sigma                  # later than any trigger above 1e-15 mm


def test_the_dying_out_oscillation_after_slip_comes_from_the_trigger():
    """App. 9 (seed lines 5534-5538): Fig. A9-7 "shows how the triggering oscillation can produce the
    observed dying-out oscillation after the slip part of stick-slip".  Shown, as a distribution over the
    trigger's phase: MLIEN as listed, stick-slip on the S.L.C. with the drive rising slowly to 32 mm/s,
    below the faithful step's v_oc (32.1), where the U.L.C. is close to the S.L.C.  Without a trigger the
    stick-slip never dies out (0 of 24 phases); with ATRI = BTRI = 0.02 neither; with 0.1 (OMETRI 30000)
    the trigger carries the state inside the U.L.C. in 16 of 24 phases and the oscillation dies out onto the
    triggering cycle.  The shipped A9-7 deck (v0 from 10.05 down to 7.6 mm/s) has an unstable origin
    throughout, so no trigger card can make it show this (docs/claims.md)."""
    from studies.triggering import mlien_rising

    ph = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    died = {a: sum(mlien_rising((p, 30000.0, a, a)) < 10.0 for p in ph) for a in (0.0, 0.02, 0.1)}
    assert died[0.0] == 0 and died[0.02] == 0
    assert 10 <= died[0.1] <= 22, died


def test_a9_1_to_a9_6_each_geometric_feature_changes_the_cycle():
    """App. 9 (seed lines 5532-5534): "fig. A9-1 to A9-6 show how the geometry of the characteristic line
    affects the trajectories and consequently the stick-slip traces".  Holds on the shipped decks (one
    feature changed at a time from A9-1): each changes the S.L.C. by 2.9 % or more; a higher static peak
    enlarges it (25.53 -> 32.27 mm), a flatter or steeper falling part, a steeper rising part and a wider
    stick part shrink it; the steeper falling part (A9-3) also puts the drive beyond the kinetic minimum:
    a stable origin inside a U.L.C. of 7.11 mm."""
    res = {}
    for k in range(1, 7):
        d = read_deck(CARDS / "figures" / f"figA9_{k}.dat", program="lieng1")
        fc = cycles.find_cycles(np.asarray(d.xchl[:d.n]), np.asarray(d.ychl[:d.n]))
        res[k] = (fc.origin_stable, [round(c.amplitude, 2) for c in fc.cycles])
    assert res == {1: (False, [25.53]), 2: (False, [22.32]), 3: (True, [7.11, 22.94]), 4: (False, [32.27]),
                   5: (False, [24.78]), 6: (False, [22.91])}


def test_fig_2_23_the_slope_at_the_origin_decides_its_stability():
    """Ch. 2.3.1.4 a (seed lines 2404-2413), Fig. 2.23: "for negative slopes dv/dx the singular point 0 is
    stable ... while for positive slopes it is unstable"; 2.3.1.4 (2468-2476): "Only if the origin is stable,
    there is an unstable limiting cycle around it".  Holds on the shipped decks: the stable deck's slope
    dX/dY at the origin is -0.1 (the same sign as dv/dx) and LIENG-1's nine trajectories all come closer to
    it (to 0.26 of their start), with a U.L.C. (36.67 mm) inside the S.L.C.; the unstable deck's is +0.205,
    its trajectories all move out to the S.L.C. (25.53 mm) and there is no U.L.C."""
    from studies.triggering import slope_at_origin

    out = {}
    for name in ("fig2_23_stable", "fig2_23_unstable"):
        d = read_deck(CARDS / "figures" / f"{name}.dat", program="lieng1")
        x, y = np.asarray(d.xchl[:d.n]), np.asarray(d.ychl[:d.n])
        fc = cycles.find_cycles(x, y)
        r = d.run()
        rad = np.hypot(np.asarray(r.x) - cycles.equilibrium(x, y), np.asarray(r.y))
        out[name] = (fc.origin_stable, round(slope_at_origin(x, y), 3), [c.kind for c in fc.cycles],
                     bool(np.all(rad[:, -1] < 0.3 * rad[:, 0])), bool(np.all(rad[:, -1] > 5 * rad[:, 0])))
    assert out == {"fig2_23_stable": (True, -0.1, ["unstable", "stable"], True, False),
                   "fig2_23_unstable": (False, 0.205, ["stable"], False, True)}
