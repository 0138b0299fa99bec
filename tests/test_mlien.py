"""MLIEN: TIMDIS geometry, the small-OMEGA limit against LIENG-1, the triggering ellipse, bad decks."""

import numpy as np
import pytest

import lieng
from lieng import _core, read_deck, write_deck
from lieng.cli import main

import reference
from conftest import CARDS, rng, thesis_characteristic

A97 = CARDS / "mlien_a9_7.dat"


def through_origin(**kw):
    x, v = thesis_characteristic(vmax=60, **kw)
    return x - reference.xb_interp(x, v, 0.0), v


def test_timdis_keeps_origin_and_puts_centre_on_the_drive():
    r = rng(11)
    for _ in range(40):
        x, v = thesis_characteristic(v0=r.uniform(3, 15), vmax=60, step=r.uniform(1.5, 4))
        x = x + r.uniform(-3, 3)  # need not pass through the origin before
        c0 = lieng.centre_of_symmetry(x, v)
        ampv0 = abs(c0.ymdl) * r.uniform(1.0, 2.0)
        omega, tl = r.uniform(0.01, 1), r.uniform(0, 20)
        xs, ys = x.copy(), v.copy()
        diff, adiff, status = _core.core_timdis(xs, ys, c0.ymdl, ampv0, omega, tl)
        assert status == 0
        # the moved line passes through the origin ...
        assert abs(reference.xb_interp(xs, ys, 0.0)) < 1e-9
        # ... is the same line translated ...
        np.testing.assert_allclose(np.diff(xs), np.diff(x), atol=1e-12)
        np.testing.assert_allclose(np.diff(ys), np.diff(v), atol=1e-12)
        # ... and its centre of symmetry sits at AMPV0*COS(OMEGA*t)
        c1 = lieng.centre_of_symmetry(xs, ys)
        assert c1.ymdl == pytest.approx(ampv0 * np.cos(omega * tl), abs=1e-9)


def test_run_centre_follows_drive_and_last_line_through_origin():
    x, v = through_origin()
    res = lieng.mlien(x, v, -8.0, 0.0, 0.01, omega=0.05, ampv0=12.0, trigger=(1.25, 30000, 0, 0))
    np.testing.assert_allclose(res.ymdl[1:], 12.0 * np.cos(0.05 * res.t[1:]), atol=1e-9)
    assert abs(reference.xb_interp(res.xchl_last, res.ychl_last, 0.0)) < 1e-9
    assert res.t[0] == pytest.approx(np.arccos(res.vo / 12.0) / 0.05)


def test_small_omega_without_triggering_approaches_lieng1():
    x, v = through_origin()
    vo = lieng.centre_of_symmetry(x, v).ymdl
    ref = lieng.lieng1(x, v, -8.0, 0.0, 0.01, ntraj=1, npts=1500)
    errs = []
    for omega in (1e-2, 1e-3, 1e-4):
        res = lieng.mlien(x, v, -8.0, 0.0, 0.01, omega=omega, ampv0=vo, trigger=(0, 0, 0, 0), npts=1500)
        errs.append(max(np.abs(res.x - ref.x[0]).max(), np.abs(res.y - ref.y[0]).max()))
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 0.05  # mm and mm/s, on a cycle of about 20


def test_triggering_ellipse_axes():
    r = rng(3)
    t = np.sort(r.uniform(0, 50, 20000))
    for omintr, ometri, a, b in [(1.25, 30000.0, 10.0, 2.0), (0.3, 777.0, 0.02, 0.5)]:
        xt, yt = _core.core_trigger(t, omintr, ometri, a, b)
        np.testing.assert_allclose((xt / a) ** 2 + (yt / b) ** 2, 1.0, atol=1e-12)
        assert np.abs(xt).max() == pytest.approx(a, rel=1e-4)
        assert np.abs(yt).max() == pytest.approx(b, rel=1e-4)
        # the listing's phase: AKTRI = OMTRIL/2.*3.1415927 is OMTRIL*pi/2 (precedence),
        # and 2*3.1415927*INT(AKTRI) is removed with the listing's inexact pi
        pl = 3.1415927
        om = ometri * t + omintr
        phase = om - np.trunc(om / 2.0 * pl) * 2.0 * pl
        np.testing.assert_allclose(xt, a * np.cos(phase), atol=1e-9 * a)
        np.testing.assert_allclose(yt, b * np.sin(phase), atol=1e-9 * b)
    xt, yt = _core.core_trigger(t, 1.25, 30000.0, 0.0, 0.0)
    assert not xt.any() and not yt.any()


def test_trigger_off_first_step_is_the_lienard_step():
    x, v = through_origin()
    res = lieng.mlien(x, v, -8.0, 0.0, 0.01, omega=0.05, ampv0=12.0, trigger=(1.25, 30000, 0, 0), npts=2)
    xn, yn, tn, *_ , status = _core.core_point(x, v, 0.01, -8.0, 0.0, res.t[0], 0)
    assert (res.x[1], res.y[1], res.t[1]) == (xn, yn, tn)


def test_a9_7_deck_reads_and_runs_with_its_trigger_card():
    d = read_deck(A97, program="mlien")
    assert d.trigger == (1.25, 30000.0, 0.02, 0.2)
    res = d.run()
    assert res.npts == 3000 and np.all(np.isfinite(res.x))
    # stick-slip: the velocity reaches the drive (stick) and falls far below it (slip)
    e = res.y - res.ymdl
    assert e.max() > -1.0 and e.min() < -10.0


def test_deck_round_trip_with_and_without_trigger_card(tmp_path):
    d = read_deck(A97, program="mlien")
    p = tmp_path / "a.dat"
    write_deck(d, p)
    assert read_deck(p, program="mlien").values() == d.values()
    d.trigger = None
    write_deck(d, p)
    assert len(p.read_text().splitlines()) == 82
    again = read_deck(p, program="mlien")
    assert again.trigger is None and again.trigger_used == lieng.mlien_module.TRIGGER_LISTING


def _bad(tmp_path, capsys, edit):
    lines = A97.read_text().splitlines()
    lines[1] = edit(lines[1].ljust(80))
    deck = tmp_path / "bad.dat"
    deck.write_text("\n".join(lines) + "\n")
    out = tmp_path / "out"
    code = main(["run", "mlien", str(deck), "-o", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and err[0].startswith("lieng: error:")
    assert not out.exists()
    return err[0]


def test_vo_above_ampv0_is_an_error(tmp_path, capsys):
    msg = _bad(tmp_path, capsys, lambda s: s[:15] + f"{5.0:10.2f}" + s[25:])
    assert "card 2, columns 16-25 (AMPV0" in msg and "ARCOS" in msg


def test_omega_zero_is_an_error(tmp_path, capsys):
    msg = _bad(tmp_path, capsys, lambda s: s[:5] + f"{0.0:10.2f}" + s[15:])
    assert "card 2, columns 6-15 (OMEGA" in msg


def test_drive_leaving_the_characteristic_is_an_error(tmp_path, capsys):
    # AMPV0 = 90 with OMEGA = 0.05: VO swings below the characteristic's range
    msg = _bad(tmp_path, capsys, lambda s: s[:5] + f"{0.05:10.2f}{90.0:10.2f}" + s[25:])
    assert "outside its range" in msg and "card 2" in msg


def test_aktri_precedence_changes_the_phase_through_the_inexact_pi():
    # OMTRIL/(2*pi) (the evident intent) against OMTRIL*pi/2 (the listing):
    # both remove whole turns of 2*3.1415927, which is not 2*pi, so the phase
    # drifts by (number of turns)*2*(3.1415927 - pi); the listing removes
    # pi^2 ~ 9.87 times as many turns, so drifts ~9.87 times as far.
    pl = 3.1415927
    t = np.array([1.0, 10.0, 50.0])
    om = 30000.0 * t + 1.25
    listing = om - np.trunc(om / 2.0 * pl) * 2.0 * pl
    intended = om - np.trunc(om / (2.0 * pl)) * 2.0 * pl
    xt, _ = _core.core_trigger(t, 1.25, 30000.0, 1.0, 1.0)
    np.testing.assert_allclose(xt, np.cos(listing), atol=1e-9)
    drift_l = np.abs(np.angle(np.exp(1j * (listing - om))))
    drift_i = np.abs(np.angle(np.exp(1j * (intended - om))))
    assert np.all(drift_l > 5 * drift_i)
    assert drift_l[-1] > 0.1  # radians at T = 50: the precedence matters


def test_a9_7_decay_deck_oscillation_dies_out_at_the_damping_of_the_stable_origin():
    """cards/mlien_a9_7_decay.dat (App. 9, Fig. A9-7; ch. 2.4.1.2): the drive
    rises past v_oc, the stable limit cycle vanishes and the oscillation dies
    out about the stable origin.  Its log decrement per turn is the analytic
    one of the rising part (slope C = 0.1 in the Lienard plane, D = C/2),
    2 pi D / sqrt(1 - D^2), less the listing's tangent step's energy gain,
    about pi*DTHETA per turn; with the deck's small triggering oscillation
    the decay is the same within its scatter."""
    import math

    from scipy.signal import find_peaks

    from lieng.programs.mlien import Deck, run_deck

    deck = Deck.from_lines((CARDS / "mlien_a9_7_decay.dat").read_text().splitlines())
    assert deck.trigger == (1.25, 30000.0, 0.02, 0.02) and deck.omega < 0
    d = 0.1 / 2
    expect = 2 * math.pi * d / math.sqrt(1 - d * d) - math.pi * deck.dtheta
    for trig, tol in (((0.0, 0.0, 0.0, 0.0), 0.02), (None, 0.1)):
        if trig is not None:
            deck.trigger = trig
        res = run_deck(deck)
        xs = np.convolve(res.x, np.ones(25) / 25, mode="same")
        pk, _ = find_peaks(xs, distance=100)
        pk = pk[(pk > 12) & (pk < xs.size - 12)]
        late = pk[res.ymdl[pk] > 35.0]                 # the drive well past v_oc: no limit cycle left
        assert late.size >= 4
        dec = np.log(xs[late][:-1] / xs[late][1:])
        assert np.mean(dec) == pytest.approx(expect, rel=tol)
        assert xs[late][-1] < 0.4 * xs[pk[0]]           # it has died out to well under the stick-slip size


def test_the_ychl_echo_is_edited_e20_2_as_mlien_lists_it(tmp_path, capsys):
    """MLIEN's `33 FORMAT(5E20.2)` (App. 6, line 5207; LIENG-1's is F20.2):
    the echo of the characteristic's velocities, edited here by hand as the
    E edit does (0.dd E+ee, right-justified in 20)."""
    def e20_2(v):
        if v == 0:
            return f"{'0.00E+00':>20}"
        e = int(np.floor(np.log10(abs(v)))) + 1
        m = round(abs(v) / 10.0 ** e, 2)
        if m >= 1.0:
            m, e = m / 10, e + 1
        return f"{'-' if v < 0 else ''}{m:.2f}E{e:+03d}".rjust(20)

    deck = CARDS / "mlien_a9_7.dat"
    assert main(["run", "mlien", str(deck), "-o", str(tmp_path / "o"), "--no-plots", "-q"]) == 0
    listing = (tmp_path / "o" / "listing.txt").read_text().splitlines()
    ychl = read_deck(deck, program="mlien").ychl
    want = "".join(e20_2(float(v)) for v in ychl[:5])
    assert want in listing, want


@pytest.mark.parametrize("ometri,lo,hi", [(30000.0, 200.0, 1e9), (3000.0, 0.0, 60.0)])
def test_ometri_30000_or_3000(ometri, lo, hi):
    """OMETRI = 30000 as printed, or 3000. (the OCR's `.` read as `0`),
    with the listing's ATRI = 10, BTRI = 2 on the A9-7 deck: the first makes
    the offsets random-walk hundreds of mm, the second stays on the figure's
    scale (RESTORATION.md M6 records both; 30000 is kept)."""
    import copy

    deck = copy.deepcopy(read_deck(CARDS / "mlien_a9_7.dat", program="mlien"))
    deck.trigger = (1.25, ometri, 10.0, 2.0)
    x = np.asarray(deck.run().x)
    assert lo <= np.max(np.abs(x)) < hi
