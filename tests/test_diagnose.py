"""`lieng diagnose` on records with a hidden effect (generator: lieng.analysis.synth,
an implementation that shares no code with the diagnosis), and bad input."""

import json
import math

import numpy as np
import pytest

from lieng.cli import main
from lieng.errors import LiengInputError
from lieng.diagnose import CANDIDATES, diagnose, record_from_arrays
from lieng.analysis.synth import synthesize


def run(rec):
    v0 = rec.v0_col if rec.v0_col is not None else rec.v0
    return diagnose(record_from_arrays(rec.t, rec.x, v0, rec.y), rec.fn)


#: named with gain >= 0.3 in at least this many of six records (measured
#: rates: tests/benchmarks/bench_diagnose.py).  Triggering: 2 of these six
#: since stop 67, when the held-out metric stopped comparing the normal
#: channel, whose line is the effect's own statistic (5-6 of 6 before, the
#: gain earned mostly by reproducing that line; the load modulation moves
#: the sticks and peaks of these records by little more than their noise)
EFFECTS = {"twin_branch": 5, "triggering": 2, "drive_modulation": 5, "static_ageing": 3, "load_variation": 2}


@pytest.mark.slow
@pytest.mark.parametrize("effect", sorted(EFFECTS))
def test_hidden_effect_is_named_with_gain(effect):
    """Six records with random parameters: the effect named with gain >= 0.3."""
    good = 0
    for seed in range(6):
        d = run(synthesize(effect, seed))
        good += d.effect == effect and d.gain >= 0.3
    assert good >= EFFECTS[effect]


@pytest.mark.slow
@pytest.mark.parametrize("seeds", [range(0, 5), range(5, 10)])
def test_no_false_alarm_on_effect_free_data(seeds):
    """Effect-free records, half of them under a stepped drive with a v0
    column: always `none`, every score below 1."""
    for seed in seeds:
        d = run(synthesize("none", seed))
        assert d.effect == "none", (seed, d.reason)
        assert not any(r["named"] for r in d.evidence.values())
        assert d.gain == 0.0


def test_generator_shares_no_code_with_the_diagnosis():
    import ast
    import inspect

    import lieng.analysis.synth

    tree = ast.parse(inspect.getsource(lieng.analysis.synth))
    mods = {a.name.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    mods |= {n.module.split(".")[0] if n.module else "." for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert mods <= {"__future__", "math", "dataclasses", "numpy"}, mods


def test_gain_is_measured_on_held_out_cycles():
    """The extended model is fitted on the first 70 %: its fitted drive
    modulation reproduces the generator's frequency, and the error it is
    judged by comes from the rest of the record."""
    rec = synthesize("drive_modulation", 2)
    d = run(rec)
    assert d.extended.drv_f == pytest.approx(rec.truth["f"], rel=0.1)
    assert d.extended.drv_a == pytest.approx(rec.truth["a"], rel=0.35)
    assert d.extended_error < d.baseline_error


def test_gain_is_judged_at_both_ends_of_the_record_and_a_short_ones_middle(monkeypatch):
    """Held-out parts: the record's last 30 % (models fitted on its first
    70 %) and its first 30 % (models fitted on its last 70 %), each with at
    least three cycles, and on a short record its middle in two parts, each
    with the rest of the record training: the held-out parts tile the record,
    every cycle's peak lies in exactly one of them and in none of its own
    training parts; a long record holds out its two ends only.  The same
    model on every side gains exactly 0."""
    import lieng.diagnose.extend as ext_mod
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.extend import folds, gain_folds, window
    from lieng.diagnose.segment import find_cycles, prepare

    rec = synthesize("static_ageing", 0)
    r = record_from_arrays(rec.t, rec.x, rec.v0_col if rec.v0_col is not None else rec.v0, rec.y)
    pr = prepare(r)
    c = find_cycles(pr, rec.fn)
    parts = folds(pr, c)
    t0, t1 = float(pr.t[0]), float(pr.t[-1]) + pr.dt
    assert len(parts) == 4
    (a0, a1, h0, h1), (b0, b1, g0, g1) = parts[:2]
    assert (a0, h1, b1, g0) == (t0, t1, t1, t0) and a1 == h0 and b0 == g1 and g1 < h0
    tests = sorted((p[2], p[3]) for p in parts)
    assert tests[0][0] == t0 and tests[-1][1] == t1 and all(u[1] == v[0] for u, v in zip(tests, tests[1:]))
    ts = pr.t[c.peak_i]
    held = np.array([window(ts, p[2:]) for p in parts])
    assert np.all(held.sum(axis=0) == 1) and held.sum(axis=1).min() >= 3
    for p, h in zip(parts, held):
        assert not np.any(window(ts, p) & h) and np.all(window(ts, p) | h)
    base = fit_baseline(pr, c, rec.fn)
    g = gain_folds(pr, c, rec.fn, [(p[2], p[3], base, base) for p in parts])
    assert g["parts"] == 4 and g["gain"] == 0.0 and g["e0"] > 0
    monkeypatch.setattr(ext_mod, "MIDDLE_SAMPLES", pr.x.size - 1)
    assert [p[2:] for p in folds(pr, c)] == [(h0, h1), (g0, g1)]


def test_a_training_part_around_a_held_out_one_judges_the_cycles_within_its_pieces():
    """A Judge on [lo, hi) less a held-out [a, b) judges the cycles of
    [lo, a) and of [b, hi), none that spans the held-out part, and its
    error is theirs pooled."""
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.extend import Judge
    from lieng.diagnose.segment import find_cycles, prepare

    rec = synthesize("none", 0)
    pr = prepare(record_from_arrays(rec.t, rec.x, rec.v0_col if rec.v0_col is not None else rec.v0, rec.y))
    c = find_cycles(pr, rec.fn)
    base = fit_baseline(pr, c, rec.fn)
    t0, t1 = float(pr.t[0]), float(pr.t[-1]) + pr.dt
    a, b = t0 + 0.4 * (t1 - t0), t0 + 0.6 * (t1 - t0)
    J = Judge(pr, c, rec.fn, t0, t1, gap=(a, b))
    J1, J2 = Judge(pr, c, rec.fn, t0, a), Judge(pr, c, rec.fn, b, t1)
    assert J.rec.shape[0] == J1.rec.shape[0] + J2.rec.shape[0] >= 6
    assert not np.any(J.mask & (pr.t >= a) & (pr.t < b)) and np.all(J.mask == (J1.mask | J2.mask))
    d, d1, d2 = J.vector(base)[0], J1.vector(base)[0], J2.vector(base)[0]
    assert np.allclose(d, np.r_[d1, d2])


def test_cli_writes_json_report_and_plots(tmp_path, capsys):
    rec = synthesize("drive_modulation", 0)
    p = tmp_path / "d.csv"
    rec.write_csv(p)
    code = main(["diagnose", str(p), "--v0", repr(rec.v0), "--fn", repr(rec.fn), "-o", str(tmp_path / "o"), "-q"])
    assert code == 0
    d = json.loads((tmp_path / "o" / "diagnosis.json").read_text())
    assert set(d) >= {"effect", "evidence", "effects", "baseline_error", "extended_error", "gain", "metric", "fitted"}
    assert d["effect"] == "drive_modulation" and d["gain"] >= 0.3
    assert d["gain"] == pytest.approx(1 - d["extended_error"] / d["baseline_error"])
    for f in ("report.md", "trace.png", "characteristic.png", "residuals.png"):
        assert (tmp_path / "o" / f).exists()


def _bad(tmp_path, capsys, text, *extra):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    out = tmp_path / "never"
    code = main(["diagnose", str(p), "--fn", "10", "-o", str(out), *extra])
    err = capsys.readouterr().err
    assert code == 2 and err.startswith("lieng: error:") and err.count("\n") == 1
    assert not out.exists()
    return err


def test_bad_input(tmp_path, capsys):
    assert "displacement (x)" in _bad(tmp_path, capsys, "t,y\n" + "0,1\n" * 60, "--v0", "1")
    rows = "".join(f"{0.001 * i},{np.sin(i)}\n" for i in range(100))
    # a word where a number belongs is named (a NaN or empty cell is a missed sample: tests/test_table.py)
    assert "line 7, column x: 'n/c'" in _bad(tmp_path, capsys, "t,x\n" + rows.replace("0.005,", "0.005,n/c", 1)
                                            .replace(f"{np.sin(5)}", "", 1), "--v0", "1")
    assert "t must increase" in _bad(tmp_path, capsys, "t,x\n" + rows.replace("0.005,", "0.003,", 1), "--v0", "1")
    dup = "t,x\n" + "".join(f"{0.001 * min(i, 50)},{np.sin(i)}\n" for i in range(100))
    assert "column t" in _bad(tmp_path, capsys, dup, "--v0", "1")
    assert "--v0" in _bad(tmp_path, capsys, "t,x\n" + rows)
    for tau in ("-2", "0", "nan"):
        assert f"--highpass {tau}" in _bad(tmp_path, capsys, "t,x\n" + rows, "--v0", "1", "--highpass", tau)
    assert "5 sampling intervals" in _bad(tmp_path, capsys, "t,x\n" + rows, "--v0", "1", "--highpass", "0.002")

def test_records_without_stick_slip_are_reported_not_refused(tmp_path):
    """Steady sliding, or a record of two cycles: exit 0, effect
    no_stick_slip (too_few_cycles for the two: stick-slip, too short to
    diagnose), the reason names the cycles found."""
    flat = tmp_path / "flat.csv"
    flat.write_text("t,x\n" + "".join(f"{0.001 * i},{0.001 * i}\n" for i in range(500)))
    short = synthesize("none", 0, cycles=2)
    p = tmp_path / "short.csv"
    short.write_csv(p)
    for f, args in ((flat, ["--v0", "1"]), (p, ["--v0", repr(short.v0)])):
        out = tmp_path / (f.stem + "_o")
        assert main(["diagnose", str(f), *args, "--fn", "10", "-o", str(out), "-q"]) == 0
        d = json.loads((out / "diagnosis.json").read_text())
        assert d["effect"] == ("no_stick_slip" if f is flat else "too_few_cycles") and "cycles" in d["reason"]
        assert d["drop_mm"] is None                 # no drop to read: null, not 0
    out = tmp_path / "flat_nofn"
    assert main(["diagnose", str(flat), "--v0", "1", "-o", str(out), "-q"]) == 0
    assert json.loads((out / "diagnosis.json").read_text())["natural_frequency_hz"]["used"] is None


def test_slips_are_found_where_the_level_wanders_by_more_than_they_drop():
    """A sawtooth (sticks rising at the drive, slips falling in half a
    natural period) whose level climbs by six drops and falls once by eight
    (a load along the track, one large slip among small ones: the level's
    span is many times a slip's drop): every slip is found, the large one
    among them, and no other (geometry, not a model)."""
    from lieng.diagnose.segment import find_cycles, prepare

    fn, v0, drop, dt = 50.0, 1.0, 0.02, 1e-4
    stick, slip = drop / v0, 0.5 / fn
    t, x, level, n = [], [], 0.0, 0
    t0 = 0.0
    drops = [drop] * 24
    drops[8] = 8 * drop                    # one large slip
    for k, d in enumerate(drops):
        climb = 6 * drop / len(drops) if k != 8 else 0.0      # the level climbs between slips
        ts = np.arange(0.0, stick + climb / v0, dt)
        t.append(t0 + ts)
        x.append(level + v0 * ts)
        top = level + v0 * ts[-1]
        tf = np.arange(dt, slip, dt)
        t.append(t0 + ts[-1] + tf)
        x.append(top - d * 0.5 * (1 - np.cos(np.pi * tf / slip)))
        t0 = t[-1][-1] + dt
        level = top - d
        n += 1
    ts = np.arange(0.0, 0.5 * stick, dt)       # and a last stick after the last slip
    t, x = np.concatenate(t + [t0 + ts]), np.concatenate(x + [level + v0 * ts])
    rec = record_from_arrays(t, x, v0)
    c = find_cycles(prepare(rec), fn, retry=True)
    assert c.n == n
    # at the first threshold alone (a simulated trace's reading) the level's span hides the small slips
    assert find_cycles(prepare(rec), fn).n < 4


def test_a_thesis_style_trc_deck_is_accepted(tmp_path, capsys):
    """A TRC readings deck (App. 7) of an effect-free record: diagnose reads
    it (OMNH gives fn, XN becomes y), resamples the readings and finds no
    effect."""
    import math
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from reference import trc_readings_deck

    rec = synthesize("none", 0, cycles=12)
    m = 3                                       # 20 readings per natural period, 200 readings
    t, x = rec.t[-200 * m::m] - rec.t[-200 * m], rec.x[-200 * m::m]    # past the start-up
    dt = float(t[1] - t[0])
    lines, _ = trc_readings_deck(t, x, np.zeros_like(x), omnh=2 * math.pi * rec.fn, omnv=1.0,
                                 vel=1.0 / (100 * dt), sensf=10.0)
    deck = tmp_path / "rec.dat"
    deck.write_text("\n".join(lines) + "\n")
    code = main(["diagnose", str(deck), "--v0", repr(rec.v0), "-o", str(tmp_path / "o"), "-q"])
    assert code == 0, capsys.readouterr().err
    d = json.loads((tmp_path / "o" / "diagnosis.json").read_text())
    assert d["effect"] == "none"
    # without --v0 a deck is refused (it has no drive velocity)
    assert main(["diagnose", str(deck), "-o", str(tmp_path / "p")]) == 2
    assert "--v0" in capsys.readouterr().err and not (tmp_path / "p").exists()


def _force_record(path, rec, load):
    """A synth record written as a lab writes a force record: TAB separated,
    friction in mN through a 200 N/m spring, normal force in N, the stage
    position in um (plain NumPy)."""
    vd = rec.v0_col if rec.v0_col is not None else np.full(rec.t.size, rec.v0)
    pos = np.r_[0, np.cumsum(0.5 * (vd[1:] + vd[:-1]) * np.diff(rec.t))]
    N = 2.0 * load + 0.003 * np.random.default_rng(7).standard_normal(rec.t.size)
    with open(path, "w") as fh:
        fh.write("Time [s]\tFriction [mN]\tNormal [N]\tPosition [um]\n")
        for row in zip(rec.t, 200.0 * rec.x, N, pos * 1000):
            fh.write("\t".join(f"{v:.7g}" for v in row) + "\n")


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1])
def test_force_records_with_a_normal_force(tmp_path, seed):
    """Force records (TAB, mN, N, um, the drive from the position column):
    a normal force that follows the motion is a load variation (named, with
    gain); a constant one is not."""
    lv = synthesize("load_variation", seed)
    p = tmp_path / "lv.txt"
    _force_record(p, lv, 1 + lv.truth["ky"] * (lv.y - 1.0))
    assert main(["diagnose", str(p), "--stiffness", "200", "--fn", repr(lv.fn), "-o", str(tmp_path / "a"), "-q",
                 "--no-plots"]) == 0
    d = json.loads((tmp_path / "a" / "diagnosis.json").read_text())
    assert d["effect"] == "load_variation" and d["gain"] >= 0.3
    nn = synthesize("none", seed)
    p = tmp_path / "nn.txt"
    _force_record(p, nn, np.ones(nn.t.size))
    assert main(["diagnose", str(p), "--stiffness", "200", "--fn", repr(nn.fn), "-o", str(tmp_path / "b"), "-q",
                 "--no-plots"]) == 0
    assert json.loads((tmp_path / "b" / "diagnosis.json").read_text())["effect"] == "none"


@pytest.mark.slow
def test_a_twin_branch_is_not_explained_away_by_a_load_that_does_not_drive_the_friction(tmp_path):
    """A twin-branch record whose normal force follows the motion (a contact
    that tilts) while the friction does not follow it: both are named (the
    normal force does vary), and the twin branch stays first: the load's
    extension does not account for the slips (issue #13: a twin and a load
    both named are each tested against the other's extension)."""
    tw = synthesize("twin_branch", 0)
    p = tmp_path / "tw.txt"
    _force_record(p, tw, 1 + 0.3 * (tw.x - tw.x.mean()) / np.ptp(tw.x))
    assert main(["diagnose", str(p), "--stiffness", "200", "--fn", repr(tw.fn), "-o", str(tmp_path / "o"), "-q",
                 "--no-plots"]) == 0
    d = json.loads((tmp_path / "o" / "diagnosis.json").read_text())
    assert d["effect"] == "twin_branch" and d["evidence"]["twin_branch"]["named"], d["reason"]


def _write(path, cols, sep=","):
    names = list(cols)
    with open(path, "w") as fh:
        fh.write(sep.join(names) + "\n")
        for row in zip(*(cols[n] for n in names)):
            fh.write(sep.join(f"{v:.9g}" for v in row) + "\n")


@pytest.mark.slow
def test_records_as_labs_record_them(tmp_path):
    """Whitespace separated with units in the header, a 50 Hz hum, spikes,
    uneven sampling with gaps, no --fn: read, each repair said, fn read from
    the slips within 10 %, and nothing named on an effect-free record."""
    from lieng.diagnose import read_record

    rec = synthesize("none", 2)
    g = np.random.default_rng(0)
    D = float(np.ptp(rec.x))
    x = rec.x + 0.03 * D * np.sin(2 * np.pi * 50.0 * rec.t)
    k = g.choice(x.size, 20, replace=False)
    x[k] += 0.2 * D * g.choice([-1, 1], k.size)
    keep = np.ones(x.size, bool)
    keep[g.choice(x.size, x.size // 20, replace=False)] = False      # dropped samples: gaps
    p = tmp_path / "lab.dat"
    cols = {"t [s]": rec.t[keep], "x [um]": 1000 * x[keep]}
    if rec.v0_col is not None:
        cols["v0 [mm/s]"] = rec.v0_col[keep]
    _write(p, cols, sep="   ")
    r = read_record(p, v0=rec.v0)
    notes = " ".join(r.notes)
    assert "resampled" in notes and "spikes" in notes and "50.00 Hz" in notes
    d = diagnose(r)
    assert d.fn == pytest.approx(rec.fn, rel=0.1) and d.fn_source.startswith("estimated")
    assert d.effect == "none", d.reason


@pytest.mark.slow
def test_a_reversing_drive_is_cut_into_strokes(tmp_path):
    """A reciprocating drive (the v0 column changes sign, dwells at the
    ends): every stroke turned forward and analysed; an effect-free stick-slip
    in both directions names nothing."""
    rec = synthesize("none", 0, cycles=30)
    n = rec.t.size
    sign = np.where((np.arange(n) // (n // 4)) % 2 == 0, 1.0, -1.0)
    # build x stroke by stroke: each quarter of the forward record, mirrored in the backward strokes
    x = rec.x * sign
    vd = rec.v0 * sign
    dwell = (np.arange(n) % (n // 4)) < 5
    vd[dwell] = 0.0
    p = tmp_path / "recip.csv"
    _write(p, {"t": rec.t, "x": x, "v0": vd})
    assert main(["diagnose", str(p), "--fn", repr(rec.fn), "-o", str(tmp_path / "o"), "-q", "--no-plots"]) == 0
    d = json.loads((tmp_path / "o" / "diagnosis.json").read_text())
    assert any("strokes" in s for s in d["notes"])
    assert d["effect"] == "none", d["reason"]


def _reciprocating_coulomb(fs_of_pos, fn=20.0, v0=2.0, stroke=8.0, nstrokes=8, fk=0.4, rate=2000.0, seed=0):
    """A reciprocating Coulomb slider written out analytically (plain NumPy,
    no lieng code): sticks at the drive velocity until |x| reaches the static
    limit at the drive's position, slips half a natural period about the
    kinetic level; strokes of ``stroke`` mm with short dwells."""
    g = np.random.default_rng(seed)
    dt, wn = 1.0 / rate, 2 * np.pi * fn
    t, x, v = [], [], []
    tt, xx, pos = 0.0, 0.0, 0.0
    for k in range(nstrokes):
        d = 1.0 if k % 2 == 0 else -1.0
        for _ in range(40):                               # dwell
            t.append(tt), x.append(xx), v.append(0.0)
            tt += dt
        travel = 0.0
        slip_t, xp = None, 0.0
        while travel < stroke:
            if slip_t is None:
                xx += d * v0 * dt
                if d * xx >= fs_of_pos(pos):
                    slip_t, xp = 0.0, xx
            else:
                slip_t += dt
                xx = d * fk + (xp - d * fk) * np.cos(wn * slip_t)
                if wn * slip_t >= np.pi:
                    slip_t = None
            pos += d * v0 * dt
            travel += v0 * dt
            t.append(tt), x.append(xx), v.append(d * v0)
            tt += dt
    x = np.asarray(x) + 0.002 * g.standard_normal(len(x))
    return np.asarray(t), x, np.asarray(v)


@pytest.mark.slow
@pytest.mark.parametrize("amp,named", [(0.25, True), (0.0, False)])
def test_friction_along_the_track(tmp_path, amp, named):
    """Static friction that depends on the position along a reciprocating
    track (the same profile in both directions) is named position_dependence;
    a uniform track is not."""
    t, x, v = _reciprocating_coulomb(lambda p: 1.0 + amp * np.sin(2 * np.pi * p / 8.0))
    p = tmp_path / "track.csv"
    _write(p, {"t": t, "x": x, "v0": v})
    assert main(["diagnose", str(p), "--fn", "20", "-o", str(tmp_path / "o"), "-q", "--no-plots"]) == 0
    d = json.loads((tmp_path / "o" / "diagnosis.json").read_text())
    assert d["evidence"]["position_dependence"]["named"] is named, d["evidence"]["position_dependence"]


@pytest.mark.slow
@pytest.mark.parametrize("c,named", [(0.3, True), (-0.3, True), (0.0, False)])
def test_a_normal_force_that_follows_the_force_as_written_on_a_reciprocating_rig(tmp_path, c, named):
    """A reciprocating force record whose normal force follows the friction
    force as the rig wrote it (signed: it changes sign with the direction, so
    no single line in the turned force fits it) is a load variation, and one
    that falls as the friction rises is one too (found on an independent
    generator's records: 'the friction runs against N' had hidden them);
    a constant normal force names nothing."""
    t, x, v = _reciprocating_coulomb(lambda p: 1.0)
    N = 2.0 * (1.0 + c * x) + 0.002 * np.random.default_rng(3).standard_normal(t.size)
    pos = np.r_[0, np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))]
    p = tmp_path / "recip_force.csv"
    _write(p, {"time [s]": t, "friction [mN]": 200.0 * x, "normal [N]": N, "position [mm]": pos})
    assert main(["diagnose", str(p), "--fn", "20", "--stiffness", "200", "-o", str(tmp_path / "o"), "-q",
                 "--no-plots"]) == 0
    d = json.loads((tmp_path / "o" / "diagnosis.json").read_text())
    assert d["evidence"]["load_variation"]["named"] is named, d["evidence"]["load_variation"]
    if named:
        lock = 2.0 * (1.0 + c * x)                       # the normal force without its noise,
        way = np.sign(v)                                 # less its mean in each direction
        lock = np.concatenate([lock[way == s] - np.mean(lock[way == s]) for s in (1, -1)])
        pp = (np.percentile(lock, 97.5) - np.percentile(lock, 2.5)) / np.mean(N[way != 0])
        assert d["evidence"]["load_variation"]["statistic"] == pytest.approx(pp, rel=0.15)


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_orientation_when_noise_swamps_the_rise(sign):
    """Noise that hides the stick's slow rise sample to sample (a third of
    the moving samples rise) does not turn a record over: the slips, the fast
    moves, tell which way x rises (found on an effect-free bristle record
    with mains hum that was read upside down)."""
    from lieng.diagnose.segment import SLOPE_SHARE, prepare, smooth

    rec = synthesize("none", 0)
    v0 = rec.v0_col if rec.v0_col is not None else rec.v0
    x = rec.x + 0.05 * np.ptp(rec.x) * np.random.default_rng(0).standard_normal(rec.x.size)
    dt = float(rec.t[1] - rec.t[0])
    assert np.mean(np.gradient(smooth(x, dt, 1.0, 0, win=9)) > 0) < SLOPE_SHARE   # the slope alone cannot tell
    assert prepare(record_from_arrays(rec.t, sign * x, v0, rec.y)).flipped == (sign < 0)


def test_an_effect_beyond_its_own_model_is_reported_not_named():
    """A twin branch of more than half the drop (ch. 4.1's loops are 10-30 %)
    is significant but not named: the slips depart for another reason."""
    from lieng.diagnose.decide import decide
    from lieng.diagnose.evidence import CANDIDATES, UPPER

    rng = np.random.default_rng(1)
    st = dict.fromkeys(CANDIDATES, 0.0)
    se = dict.fromkeys(CANDIDATES, 0.01)
    null = {k: rng.normal(0.0, 0.01, 39) for k in CANDIDATES}
    st["twin_branch"] = 2 * UPPER["twin_branch"]
    r = decide(st, se, null)["twin_branch"]
    assert r["significant"] and not r["named"] and "beyond_model" in r
    st["twin_branch"] = 0.2
    assert decide(st, se, null)["twin_branch"]["named"]


def test_a_twin_branch_below_is_read_two_sided_and_named_only_where_nothing_else_accounts_for_it():
    """The twin branch is tested both ways: a decelerating branch 0.2 D below
    the accelerating one (a friction that lags the speed, Hess & Soom's
    hysteresis) is significant with half the p it would have one-sided
    (Bonferroni over the two sides); it stands where no other candidate is
    named and no recorded load can account for it, and not where a
    triggering is named or the normal channel's load reaches its size."""
    from lieng.diagnose.decide import below_accounted, calibrate, decide
    from lieng.diagnose.evidence import CANDIDATES

    rng = np.random.default_rng(1)
    st = dict.fromkeys(CANDIDATES, 0.0)
    se = dict.fromkeys(CANDIDATES, 0.01)
    null = {k: rng.normal(0.0, 0.01, 39) for k in CANDIDATES}
    st["twin_branch"] = -0.2
    rows = decide(st, se, null)
    tw = rows["twin_branch"]
    assert tw["named"] and tw["effect_size"] < -0.15 and tw["interval"][1] < 0
    st["twin_branch"] = -0.03               # z about -3: one-sided p about 1e-3, two-sided twice that
    below = calibrate(0.03, 0.01, -null["twin_branch"], True)[5]
    assert decide(st, se, null)["twin_branch"]["p"] == pytest.approx(2 * below, rel=1e-9) and below < 0.01
    assert calibrate(-0.03, 0.01, null["twin_branch"], True)[5] > 0.5   # the side above alone never passes
    assert below_accounted(rows, normal_recorded=False)[0] is None
    rows["triggering"]["named"] = True
    assert "triggering is named" in below_accounted(rows, False)[0]
    rows["triggering"]["named"] = False
    lv = rows["load_variation"]
    lv.update(applicable=True, interval=[-0.01, 0.05])
    assert below_accounted(rows, True) == (None, 0.05)
    lv["interval"] = [0.1, 0.3]             # a load whose effect reaches the twin's size
    assert "could account for it" in below_accounted(rows, True)[0]
    lv.update(applicable=False, interval=None)
    assert "not read" in below_accounted(rows, True)[0]


def test_each_side_of_a_two_way_candidate_keeps_its_own_fn_band():
    """A twin read at fn (1 -+ u) as 0.10 and 0.40 about 0.14: an fn error
    can move it 0.04 towards the null below it (the band of the side above)
    and 0.26 away; the side above is tested with the 0.04, as one-sided, its
    p doubled; a symmetric band (0.26) would hide it.  Mirrored, the side
    below is tested alike."""
    from lieng.diagnose.decide import calibrate, calibrate_two_way

    v = np.random.default_rng(3).normal(0.0, 0.005, 39)
    one = calibrate(0.14, 0.01, v, True, readings=(0.10, 0.40))
    two = calibrate_two_way("twin_branch", 0.14, 0.01, v, readings=(0.10, 0.40))
    assert one[6] == pytest.approx(0.04) and two[6] == pytest.approx(0.04)
    assert two[5] == pytest.approx(min(1.0, 2 * one[5])) and two[5] < 1e-9 and two[4] > 0
    assert calibrate(0.14, 0.01, v, False, readings=(0.10, 0.40))[6] == pytest.approx(0.26)
    below = calibrate_two_way("twin_branch", -0.14, 0.01, -v, readings=(-0.10, -0.40))
    assert below[2] == pytest.approx(-two[2]) and below[5] == pytest.approx(two[5]) and below[4] < 0


def test_the_fn_band_is_read_on_the_record_itself():
    """A statistic that follows fn is tested at the least favourable fn
    within the stated uncertainty.  How far it moves is read on the record
    (its statistic at fn (1 -+ u)), not assumed from the replicates' 1-DoF
    slider: a record that moves less than they do keeps its evidence, one
    that moves more (a second mode of the rig) is held to it."""
    from lieng.diagnose.decide import calibrate

    rng = np.random.default_rng(3)
    e = rng.uniform(-0.05, 0.05, 39)
    v = 1.6 * e + rng.normal(0.0, 0.005, 39)          # the replicates: 0.08 per 5 % of fn
    S = 0.12
    *_, p_rep, band_rep = calibrate(S, 0.005, v, True, e, 0.05)
    assert band_rep == pytest.approx(0.08, abs=0.01)
    *_, p_flat, band_flat = calibrate(S, 0.005, v, True, e, 0.05, readings=(0.15, 0.09))
    assert band_flat == pytest.approx(0.03) and p_flat < p_rep
    *_, p_steep, band_steep = calibrate(S, 0.005, v, True, e, 0.05, readings=(0.24, 0.0))
    assert band_steep == pytest.approx(0.12) and p_steep > 0.4
    # two-sided: the larger move either way
    *_, band2 = calibrate(-S, 0.005, v, False, e, 0.05, readings=(-0.10, -0.17))
    assert band2 == pytest.approx(0.05)


def test_a_size_with_its_own_test_is_joined_to_the_line_by_the_intersection_union_test():
    """Triggering is named when both hold: there is a line, and it is in the
    friction (its own test).  The candidate's p is the larger of the two
    (Berger 1982), tested at the level Holm gives it: with four other effects
    significant before it, a size test at p = 0.01 passes (level 0.05 / 4),
    which a fixed Bonferroni level 0.05 / 8 refused; at 0.03 it does not."""
    from lieng.diagnose.decide import decide
    from lieng.diagnose.evidence import CANDIDATES

    rng = np.random.default_rng(2)
    st = dict.fromkeys(CANDIDATES, 0.0)
    se = dict.fromkeys(CANDIDATES, 0.01)
    null = {k: rng.normal(0.0, 0.01, 39) for k in CANDIDATES}
    for k in ("load_variation", "twin_branch", "static_ageing", "drive_modulation"):
        st[k] = 0.5
    st["triggering"] = 0.5
    for p_size, named in ((0.01, True), (0.03, False)):
        r = decide(st, se, null, sizes={"triggering": (0.05, 0.01, p_size)})["triggering"]
        assert r["p"] == pytest.approx(max(p_size, r["p_line"]))
        assert r["holm_level"] == pytest.approx(0.05 / 4)
        assert r["line_significant"] and r["named"] is named and r["size_shown"] is named


@pytest.mark.parametrize("left_twin,left_load,first", [(0.08, 0.10, "load_variation"),
                                                       (0.02, 0.10, "load_variation"),
                                                       (0.08, -0.01, "twin_branch"),
                                                       (0.03, 0.003, "twin_branch")])
def test_of_rivals_that_neither_survive_the_one_that_accounts_for_the_other_goes_first(monkeypatch, left_twin,
                                                                                      left_load, first):
    """A twin branch and a load both named, each failing its re-test against
    the other's extension: when the other's extension leaves one below its
    margin (0.05) and not the other, that one is not named; otherwise both
    stay named, and the first is the one the other's extension leaves the
    larger share of (a share of the other sign counts as none)."""
    import importlib

    dm = importlib.import_module("lieng.diagnose.decide")

    rows = {"twin_branch": {"effect_size": 0.25, "holm_level": 0.0125, "se": 0.01},
            "load_variation": {"effect_size": 0.30, "holm_level": 0.01, "se": 0.01}}
    left = {"twin_branch": left_twin, "load_variation": left_load}

    def fake(pr, k, other, *a):
        rows[k]["given_rival"] = {"rival": other, "null_mean": 0.0, "null_sd": 0.01, "effect_size": left[k],
                                  "p": 0.5, "replicates": 19}
        return 0.5, abs(left[k])

    monkeypatch.setattr(dm, "_given_rival", fake)
    base = object()
    fitted = {k: (object(), None, 0.5, True) for k in dm.RIVALS}
    named, notes = list(dm.RIVALS), []
    got = dm.rivals(None, base, fitted, 10.0, 0.05, {"twin_branch": 0.25, "load_variation": 0.3}, rows, named, [],
                    notes, False, True, None, 19, 10.0)
    if (abs(left_twin) < 0.05) != (abs(left_load) < 0.05):
        assert got is None and named == [first], (got, named)
        assert any(n.startswith(next(k for k in dm.RIVALS if k != first) + " is not named") for n in notes)
    else:
        assert got == first and sorted(named) == sorted(dm.RIVALS)
        assert any(n.startswith(first + " goes first") for n in notes)


def test_replicates_skip_the_permutations_not_the_statistics():
    """The baseline's replicates are read without the within-record
    permutation tests (their p-values are not used): every statistic is the
    same either way."""
    from lieng.diagnose.evidence import statistics
    from lieng.diagnose.segment import find_cycles, prepare

    rec = synthesize("drive_modulation", 1)
    v0 = rec.v0_col if rec.v0_col is not None else rec.v0
    pr = prepare(record_from_arrays(rec.t, rec.x, v0, rec.y))
    c = find_cycles(pr, rec.fn)
    full, _, aux = statistics(pr, c, rec.fn)
    quick, _, aux0 = statistics(pr, c, rec.fn, nperm=0)
    assert full == quick
    assert aux["p_own"]["drive_modulation"] < 0.05 and aux0["p_own"]["drive_modulation"] == 1.0


@pytest.mark.parametrize("extra,needle", [(["--fn", "@fn", "--fn-uncertainty", "0"], "--fn-uncertainty 0.0"),
                                          (["--fn-uncertainty", "0.01"], "give --fn")])
def test_fn_uncertainty_is_checked(tmp_path, capsys, extra, needle):
    """--fn-uncertainty outside 0.1-50 %, or without the --fn it qualifies:
    one line naming it, exit 2, no output directory."""
    rec = synthesize("none", 0)
    p = tmp_path / "r.csv"
    _write(p, {"t": rec.t, "x": rec.x})
    extra = [repr(rec.fn) if a == "@fn" else a for a in extra]
    assert main(["diagnose", str(p), "--v0", repr(rec.v0), "-o", str(tmp_path / "o"), "-q", *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert needle in err and len(err.splitlines()) == 1 and not (tmp_path / "o").exists()


def test_a_table_without_a_header_is_asked_for_one(tmp_path, capsys):
    """Columns of numbers with no header (``numpy.savetxt``'s default) are
    not a TRC deck: one line saying how many columns there are and how to
    name them, exit 2, no output directory (before: the deck reader's
    message about card 1's columns 1-20)."""
    rec = synthesize("none", 0)
    p = tmp_path / "r.txt"
    np.savetxt(p, np.column_stack([rec.t, rec.x]))
    assert main(["diagnose", str(p), "--v0", repr(rec.v0), "-o", str(tmp_path / "o"), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert "2 columns of numbers and no header" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "o").exists()


@pytest.mark.slow
def test_the_twin_calibration_follows_the_stated_fn_uncertainty():
    """The replicates draw fn within the stated uncertainty and the twin
    statistic follows it (the slips' shape and fn trade off: ch. 4.1's
    reverse construction): it is tested at the least favourable fn, so the
    band an fn error can make shrinks with the uncertainty (1 % against the
    default 5 %), while the noise about the line at the nominal fn stays."""
    rec = synthesize("none", 1)
    r = record_from_arrays(rec.t, rec.x, rec.v0_col if rec.v0_col is not None else rec.v0, rec.y)
    rows = [diagnose(r, rec.fn, fn_uncertainty=u).evidence["twin_branch"] for u in (0.01, 0.05)]
    band = [row["fn_band"] for row in rows]
    assert band[1] > 0 and band[0] < 0.35 * band[1], band
    assert rows[0]["null_sd"] < 2 * rows[1]["null_sd"] and rows[1]["null_sd"] < 2 * rows[0]["null_sd"]


def test_an_fn_error_at_the_edge_of_its_uncertainty_is_no_twin():
    """An effect-free record analysed with an fn off by exactly the stated
    5 %: the twin statistic moves by what that error makes, and the test at
    the least favourable fn does not name it (averaged over fn errors, the
    edge would count as 1.7 standard deviations before any noise)."""
    from lieng.diagnose.decide import calibrate

    g = np.random.default_rng(3)
    e = g.uniform(-0.05, 0.05, 39)
    v = -0.04 + 1.6 * e + 0.005 * g.standard_normal(39)      # a slope of 1.6 D per unit fn error
    S = -0.04 + 1.6 * 0.05                                    # the record: fn off by +5 %, no twin
    m0, s0, d, den, z, p, band = calibrate(S, 0.004, v, True, e, 0.05)
    assert band == pytest.approx(0.08, rel=0.1) and p > 0.05
    assert calibrate(S + 0.06, 0.004, v, True, e, 0.05)[5] < 1e-4      # a twin beyond the band
    # the average over fn errors (the uniform draw) would have been far less cautious at the edge
    assert d / np.std(v, ddof=1) > 1.5


def test_an_alternative_null_is_compared_with_the_null_at_the_same_fn():
    """Two nulls whose statistic follows fn alike (a slope of -1.3 D per unit
    fn error, the replicates' fn drawn within +-5 %) and part by 0.0105 D at
    the nominal fn, 3.5 times their noise about the line (0.003 D): read at
    the nominal fn, the alternative's shift is found (within three of its
    standard errors); read as raw means and spreads, the fn draws' spread
    (0.04 D) hides it.  With no shift, the 2-standard-error test finds one
    in few of 400 draws (measured: 2.75 %, one-sided towards the effect)."""
    from lieng.diagnose.decide import alt_shift, at_nominal_fn, fn_sensitivity

    def draw(g, n, shift):
        e = 1.0 / (1.0 - g.uniform(-0.05, 0.05, n)) - 1.0      # fb = fn / (1 - w), as the replicates draw it
        return -0.012 + shift - 1.3 * e + 0.003 * g.standard_normal(n), e

    g = np.random.default_rng(7)
    v, e = draw(g, 39, 0.0)
    alt, ea = draw(g, 16, 0.0105)
    m0, s0, _ = fn_sensitivity(v, e, 0.05)
    assert alt_shift(m0, s0, v.size, alt, True) == 0.0
    assert alt_shift(m0, s0, v.size, at_nominal_fn(alt, ea, 0.05), True) == pytest.approx(0.0105, abs=3 * 0.003 / 4)
    found = 0
    for seed in range(400):
        g = np.random.default_rng(100 + seed)
        v, e = draw(g, 39, 0.0)
        alt, ea = draw(g, 16, 0.0)
        m0, s0, _ = fn_sensitivity(v, e, 0.05)
        found += alt_shift(m0, s0, v.size, at_nominal_fn(alt, ea, 0.05), True) > 0
    assert found <= 20, found                                  # binomial(400, 0.025): P(>= 21) < 0.01


def test_spikes_come_out_before_a_jittered_record_is_resampled():
    """Jittered sampling (no sample on the even grid) and isolated spikes:
    each spike is replaced on the samples as read; interpolated first, it
    would straddle two grid points and stay (found on an independent
    generator's force records, where the leftover spikes became cycles)."""
    from lieng.diagnose import read_record

    g = np.random.default_rng(5)
    n = 4000
    t = np.cumsum(g.uniform(0.5e-3, 1.5e-3, n))
    clean = 0.5 * (1 - np.cos(2 * np.pi * 3.0 * t)) + 0.001 * g.standard_normal(n)
    x = clean.copy()
    k = g.choice(np.arange(10, n - 10), 12, replace=False)
    x[k] += g.choice([-1, 1], k.size) * 0.3
    rec = record_from_arrays(t, x, 1.0)
    assert any("spikes" in s and "before resampling" in s for s in rec.notes), rec.notes
    assert np.max(np.abs(rec.x - np.interp(rec.t, t, clean))) < 0.02


def test_spikes_of_two_and_three_samples_come_out_and_slips_stay():
    """A spike a sensor's filter spreads over two or three samples (found
    on an independent generator's force record: a pair of samples at twice
    the drop above a peak stayed, became that cycle's peak and cost the
    extension's gain) is replaced by the line between its neighbours like
    an isolated one; a slip (a drop of the whole drop within one sample,
    the samples on either side not agreeing) and a stick-slip sawtooth stay
    exactly as they are."""
    from lieng.diagnose.read import despike

    g = np.random.default_rng(3)
    t = np.arange(6000) * 1e-3
    saw = 1.0 * ((3.0 * t) % 1.0)                          # rises, then drops in one sample: slips
    clean = saw + 0.002 * g.standard_normal(t.size)
    x = clean.copy()
    starts = [500, 1500, 2500, 3500, 4500]
    for i, (j, L) in enumerate(zip(starts, (1, 2, 3, 2, 3))):
        x[j:j + L] += (-1) ** i * g.uniform(0.5, 2.0, L)
    y, n = despike(x)
    assert n == 11
    assert np.max(np.abs(y - clean)) < 0.02
    y0, n0 = despike(clean)
    assert n0 == 0 and np.array_equal(y0, clean)
    # a narrow trough entered and left as steeply as it is deep (a slip's overshoot with a second mode
    # ringing, sampled from an independent two-mass generator's force record, mN) is physics, not a spike
    trough = np.array([4726.9, 4382.5, 4110.2, 3893.7, 3736.3, 3660.8, 3703.5, 3831.4, 3952.8, 4015.1, 4011.8])
    rec = np.r_[np.linspace(3500.0, 4726.9, 60), trough, np.linspace(4011.8, 4600.0, 60)]
    rec = rec + 12.0 * g.standard_normal(rec.size)
    y1, n1 = despike(rec)
    assert n1 == 0 and np.array_equal(y1, rec)
    # a spike in the first or the last sample (one neighbour only) comes out too (found by a black-box
    # fuzz of the CLI: a spike of 1e6 N in the first sample turned a real record's diagnosis to unexplained)
    xe = clean.copy()
    xe[0] += 1e6
    xe[-1] -= 3.0
    ye, ne = despike(xe)
    assert ne == 2 and np.max(np.abs(ye - clean)) < 0.02


def test_spikes_on_a_reading_quantised_coarser_than_its_noise_come_out():
    """A slow sawtooth (a twentieth of a step a sample) read on a grid of
    1 % of its drop, its noise a third of that (most samples repeat their
    neighbour's value: the second
    differences' median is 0, and the noise level with it, which turned the
    search off: three spikes of twice the drop stayed and made the record
    `unexplained`, found by a black-box audit): the three come out, and the
    quantised sawtooth alone loses no sample."""
    from lieng.diagnose.read import despike

    g = np.random.default_rng(5)
    t = np.arange(6000) * 1e-3
    q = 0.01
    clean = np.round((((0.5 * t) % 1.0) + 0.003 * g.standard_normal(t.size)) / q) * q
    x = clean.copy()
    for j in (700, 2700, 4500):
        x[j] += 2.0
    y, n = despike(x)
    assert n == 3 and np.max(np.abs(y - clean)) < 3 * q
    y0, n0 = despike(clean)
    assert n0 == 0 and np.array_equal(y0, clean)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_coarse_records_peaks_and_troughs_are_not_spikes(seed):
    """Sampled at 10-12 samples per natural period (the coarse nuisance), a
    breakaway's peak and a slip's trough stand out from the line joining
    their neighbours as a spike does, but one of those neighbours is a step
    of the drop: none is replaced (before: 6-18 peaks and troughs cut on
    these records, on an independent generator's 20 of 32 slips), while a
    spike in a stick still comes out."""
    from lieng.diagnose.read import despike

    rec = synthesize("none", seed)
    for spp in (10, 12):
        step = max(1, int(round(1.0 / (rec.fn * (rec.t[1] - rec.t[0])) / spp)))
        x = rec.x[::step].copy()
        assert despike(x)[1] == 0
        i = int(np.argmin(np.abs(np.diff(x)))) + 1           # a sample in a stick
        x[i] += 0.3 * float(np.ptp(x))
        y, n = despike(x)
        assert n == 1 and y[i] == pytest.approx(0.5 * (x[i - 1] + x[i + 1]))


def test_a_second_mode_ringing_after_each_arrest_is_read():
    """A rig's second mode rings after each arrest (the 1-DoF slider is then
    in stick): a decaying oscillation at 6 fn added after every trough of an
    effect-free record, 0.05 D decaying as exp(-2 fn t), is read as its RMS
    over the two natural periods after the trough, 0.05 D / 4 = 0.0125 D
    (the mean square of the decay over 2/fn is 1/16 of 0.05**2 D**2); the
    record itself as none of it."""
    from lieng.diagnose.goodness import arrest_ringing
    from lieng.diagnose.segment import find_cycles, prepare

    rec = synthesize("none", 3)
    r = record_from_arrays(rec.t, rec.x, rec.v0_col if rec.v0_col is not None else rec.v0, rec.y)
    pr = prepare(r)
    c = find_cycles(pr, rec.fn)
    D = c.amplitude(pr.x)
    assert abs(arrest_ringing(pr, c, rec.fn, D)) < 0.005
    x = pr.x.copy()
    for i in c.trough_i:
        tt = pr.t[i:] - pr.t[i]
        x[i:] += 0.05 * D * np.exp(-tt * rec.fn * 2.0) * np.sin(2 * np.pi * 6 * rec.fn * tt)
    pr.x = x
    assert arrest_ringing(pr, c, rec.fn, D) == pytest.approx(0.0125, rel=0.2)


def test_a_line_beside_the_mains_frequency_is_the_records_own():
    """Mains hum is a line at 50 or 60 Hz (within the grid's 0.4 %); the
    shoulder of a stick-slip harmonic at 49.1 Hz (4 x 12.28 Hz) is not hum,
    and a 50 Hz line added to the same record is found at 50 Hz."""
    import numpy as np

    from lieng.diagnose.read import _hum_lines

    dt = 1.0 / 4800.0
    t = np.arange(0.0, 2.8, dt)
    f0 = 12.28
    saw = 2 * ((t * f0) % 1.0) - 1.0           # a stick-slip's sawtooth: every harmonic of f0
    assert _hum_lines(saw, dt) == []
    hum = 0.04 * np.sin(2 * np.pi * 50.0 * t + 0.3)        # 2 % of the drop
    lines = _hum_lines(saw + hum, dt)
    assert len(lines) == 1 and abs(lines[0][2][0] - 50.0) < 0.05 and abs(lines[0][2][1] - 0.04) < 0.012


def test_a_columns_unit_decides_between_the_roles_its_name_allows(tmp_path):
    """A name's words can point two ways; the unit says which: "Load point
    displacement (um)" is the drive's position (rock mechanics), not a
    normal load; "Normal load (N)" stays the normal force; a unit of none of
    the dimensions still names the column."""
    from lieng.diagnose import read_record
    from lieng.diagnose.read import _role
    from lieng.errors import LiengInputError

    assert _role("Load point displacement", "um") == "position"
    assert _role("Normal load", "N") == "N"
    assert _role("Friction", "mN") == "F"
    assert _role("Position", "mm") == "position"
    t = np.arange(0.0, 20.0, 0.005)
    saw = (t * 2.0) % 1.0                               # a sawtooth of the friction, 2 Hz
    p = tmp_path / "lp.csv"
    _write(p, {"Time (s)": t, "Load point displacement (um)": 1000.0 * t, "Friction force (N)": 1.0 + 0.2 * saw})
    rec = read_record(p, stiffness=1000.0)
    assert rec.drive_recorded and abs(float(np.median(rec.vd)) - 1.0) < 1e-3      # mm/s from um over s
    assert rec.y is None
    p2 = tmp_path / "bad.csv"
    _write(p2, {"Time (s)": t, "Friction (mm)": saw, "Position (mm)": t})
    with pytest.raises(LiengInputError, match="Friction"):
        read_record(p2, stiffness=1000.0)



def test_a_tribometers_deflection_and_sliding_distance_columns_are_read(tmp_path):
    """A pin-on-disc export names the spring's (the arm's) extension
    "deflection" and the drive's travel "distance" (the sliding distance
    along the track): read as x and as the drive's position (both had been
    refused: "no displacement ... column", "no drive column")."""
    from lieng.diagnose import read_record
    from lieng.diagnose.read import _role

    assert _role("deflection", "mm") == "x"
    assert _role("distance", "mm") == "position"
    assert _role("sliding distance", "m") == "position"
    assert _role("sliding_speed", "mm/s") == "v0"
    t = np.arange(0.0, 20.0, 0.005)
    saw = (t * 2.0) % 1.0
    p = tmp_path / "pod.csv"
    _write(p, {"time [ms]": 1000.0 * t, "Ft [N]": 1.0 + 0.2 * saw, "distance [mm]": 0.5 * t})
    rec = read_record(p, stiffness=1000.0)
    assert rec.drive_recorded and abs(float(np.median(rec.vd)) - 0.5) < 1e-3
    p2 = tmp_path / "defl.csv"
    _write(p2, {"Time [s]": t, "deflection [um]": 100.0 * saw})
    rec = read_record(p2, v0=0.2)
    assert abs(float(np.ptp(rec.x)) - 0.099) < 1e-4                # um read as mm (the samples reach 99 um)


def test_a_brake_rigs_torque_arm_and_clamp_force_columns_are_read(tmp_path):
    """A brake or pin-on-disc rig names its friction channel by where it is
    measured ("torque_arm_force [N]", "F_arm/mN") and its normal one by what
    presses ("clamp_force [N]", "Fnorm/mN": a force unit makes Fnorm the
    normal force, while Colas's unitless Fnorm, F over the weight, stays a
    coefficient); the drive's "disc_track [mm]" is its travel (all four had
    been refused: "no displacement ... column", "Fnorm: unit 'N': a friction
    coefficient has none", by `bouc_wen_brake`'s records)."""
    from lieng.diagnose import read_record
    from lieng.diagnose.read import _role

    assert _role("torque_arm_force", "N") == "F"
    assert _role("clamp_force", "N") == "N"
    assert _role("F_arm", "mN") == "F"
    assert _role("Fnorm", "mN") == "N" and _role("Fnorm", "") == "mu"
    assert _role("disc_track", "mm") == "position"
    t = np.arange(0.0, 20.0, 0.005)
    saw = (t * 2.0) % 1.0
    p = tmp_path / "brake.csv"
    _write(p, {"t [s]": t, "torque_arm_force [N]": 1.0 + 0.2 * saw, "clamp_force [N]": np.full_like(t, 4.0),
               "disc_track [mm]": 0.5 * t})
    rec = read_record(p, stiffness=1000.0)
    assert rec.drive_recorded and abs(float(np.median(rec.vd)) - 0.5) < 1e-3
    assert rec.y_is_force and abs(float(np.median(rec.y)) - 4.0) < 1e-9
    assert abs(float(np.ptp(rec.x)) - 0.198) < 1e-9                # (1.0 + 0.2 saw) N / 1000 N/m: mm, saw <= 0.99


def test_a_friction_coefficient_column_is_the_force_over_the_load(tmp_path):
    """Tribometers often record the friction coefficient: "COF" with a
    normal force column is the force mu N (x = mu N / k); "mu" alone is a
    force in units of the load, whose scale the sticks give (so --stiffness
    has nothing to act on and is refused, naming the column); "Ff (N)" is
    the friction force."""
    from lieng.diagnose import read_record
    from lieng.diagnose.read import _role
    from lieng.errors import LiengInputError

    assert _role("Friction coefficient", "") == "mu"
    assert _role("COF", "-") == "mu"
    assert _role("Ff", "N") == "F"
    t = np.arange(0.0, 20.0, 0.005)
    mu = 0.3 + 0.05 * ((t * 2.37) % 1.0)
    N = np.full_like(t, 4.0)
    p = tmp_path / "cof.csv"
    _write(p, {"Time (s)": t, "COF": mu, "Normal force (N)": N})
    rec = read_record(p, v0=1.0, stiffness=2000.0)
    assert np.allclose(rec.x, mu * 4.0 / 2000.0 * 1e3) and rec.y_is_force
    assert any("friction coefficient" in n for n in rec.notes)
    p2 = tmp_path / "mu.csv"
    _write(p2, {"t [s]": t, "mu": mu})
    rec2 = read_record(p2, v0=1.0)
    assert rec2.stiffness_unknown and np.allclose(rec2.x, 1e3 * mu)       # mu N0 over k = 1 N/m, in mm
    with pytest.raises(LiengInputError, match="column mu is a friction coefficient"):
        read_record(p2, v0=1.0, stiffness=2000.0)


def test_a_shear_stress_record_stands_for_the_force(tmp_path):
    """A biaxial (rock mechanics) record: "Shear stress (MPa)" is the
    friction per area, "Normal stress (MPa)" the load, "Load point
    displacement (um)" the drive; x is the stress over a stiffness per area
    read from the sticks (Pa/m), so --stiffness (N/m) is refused, naming the
    column."""
    from lieng.diagnose import read_record
    from lieng.diagnose.read import _column_role, _role
    from lieng.errors import LiengInputError

    assert _role("Shear stress", "MPa") == "F" and _role("Normal stress", "MPa") == "N"
    # the symbols and bare names a rock-mechanics export uses (an audit's "tau [kPa]" was refused)
    assert [_column_role(n, u)[0] for n, u in (("tau", "kPa"), ("stress", "MPa"), ("tau_kPa", ""), ("sigma", "MPa"),
                                                ("sigma_n", "kPa"))] == ["F", "F", "F", "N", "N"]
    t = np.arange(0.0, 20.0, 0.005)
    tau = 3.0 + 0.5 * ((t * 2.37) % 1.0)
    p = tmp_path / "biax.csv"
    _write(p, {"Time (s)": t, "Load point displacement (um)": 10.0 * t, "Shear stress (MPa)": tau,
               "Normal stress (MPa)": np.full_like(t, 10.0)})
    rec = read_record(p)
    assert rec.stiffness_unknown and rec.stiffness_unit == "Pa/m" and rec.y_is_force
    assert np.allclose(rec.x, tau * 1e6 * 1e3) and np.allclose(rec.y, 1e7)
    assert abs(float(np.median(rec.vd)) - 0.01) < 1e-6                    # 10 um/s
    with pytest.raises(LiengInputError, match="column Shear stress is a stress"):
        read_record(p, stiffness=1e6)

def test_a_slip_ends_at_its_arrest_not_in_the_hold_after_it():
    """A stick-slip trace whose drive stops after one slip (a hold of 20
    stick times, noisy flat x): that slip's trough is its arrest, the slip
    samples of the reverse construction stay in the slips, and the stick
    through the hold counts from the arrest (geometry of the trace, plain
    NumPy)."""
    from lieng.diagnose.baseline import slip_samples
    from lieng.diagnose.segment import find_cycles, prepare

    fn, dt, v0 = 10.0, 0.002, 1.0
    wn = 2 * math.pi * fn
    g = np.random.default_rng(3)
    t_list, x_list, v_list = [], [], []
    t, x = 0.0, 0.0
    hold_after = 5
    for k in range(12):
        n_st = int(0.5 / dt)                                  # stick: x rises from -0.25 to 0.25 at v0
        for i in range(n_st):
            t_list.append(t); x_list.append(-0.25 + v0 * i * dt); v_list.append(v0); t += dt
        n_sl = int(0.5 / fn / dt)                             # slip: half a natural period, 0.25 -> -0.25
        for i in range(n_sl):
            t_list.append(t); x_list.append(0.25 * math.cos(wn * i * dt)); v_list.append(v0); t += dt
        if k == hold_after:                                   # hold: the drive stops, x stays
            for i in range(int(10.0 / dt)):
                t_list.append(t); x_list.append(-0.25); v_list.append(0.0); t += dt
    x = np.array(x_list) + 0.002 * g.standard_normal(len(x_list))
    from lieng.diagnose import record_from_arrays

    pr = prepare(record_from_arrays(np.array(t_list), x, np.array(v_list)))
    c = find_cycles(pr, fn)
    hold_t0 = (hold_after + 1) * (0.5 + 0.5 / fn)            # when the hold starts
    k = int(np.argmin(np.abs(pr.t[c.peak_i] - (hold_t0 - 0.5 / fn))))
    assert abs(pr.t[c.trough_i[k]] - hold_t0) < 0.1 / fn      # the arrest, not somewhere in the 10 s hold
    idx, _, _ = slip_samples(c, pr.x.size)
    assert not np.any((pr.t[idx] > hold_t0 + 0.5 / fn) & (pr.t[idx] < hold_t0 + 10.0))


def test_the_stick_through_a_reversal_counts_from_the_last_arrest():
    """A reciprocating trace (stick-slip forward, a 1 s dwell, stick-slip
    backward): the stick that ends in the backward stroke's first peak lasts
    from the forward stroke's last arrest through the dwell (the contact
    rests while the spring unloads and loads the other way), so a static
    friction that ages over the dwell is seen (geometry of the trace)."""
    from lieng.diagnose import record_from_arrays
    from lieng.diagnose.evidence import stick_times
    from lieng.diagnose.segment import find_cycles, prepare

    fn, dt, v0 = 10.0, 0.002, 1.0
    wn = 2 * math.pi * fn
    T, X, V = [], [], []
    t = 0.0

    def add(xs, v):
        nonlocal t
        for xv in xs:
            T.append(t); X.append(xv); V.append(v); t += dt

    # the friction swings between 0.8 (peak) and 0.3 (trough) in the drive's direction
    for direction in (1, -1):
        for k in range(6):
            lo = -0.3 if (direction == -1 and k == 0) else 0.3   # backward: from the forward stroke's last arrest
            n_st = int(round((0.8 - lo) / v0 / dt))
            add([direction * (lo + v0 * i * dt) for i in range(n_st)], direction * v0)
            add([direction * (0.55 + 0.25 * math.cos(wn * i * dt)) for i in range(int(0.5 / fn / dt))],
                direction * v0)
        if direction == 1:
            add([0.3] * int(1.0 / dt), 0.0)                      # the dwell at the reversal
    x = np.array(X) + 0.001 * np.random.default_rng(0).standard_normal(len(X))
    pr = prepare(record_from_arrays(np.array(T), x, np.array(V)))
    c = find_cycles(pr, fn)
    k, ts, pk = stick_times(pr, c)
    across = np.flatnonzero(c.stroke[k + 1] != c.stroke[k])
    assert across.size == 1
    j = k[across[0]]
    assert abs(ts[across[0]] - (pr.t[c.peak_i[j + 1]] - pr.t[c.trough_i[j]])) < 1e-12
    assert ts[across[0]] > 1.0 + np.median(np.delete(ts, across))     # the dwell and the longer reload


def _core_peaks(vd, dt, fs=1.0, age_r=0.0, age_v=1.0):
    """The slider core with a constant kinetic friction of half the static
    limit, no ageing: the displacement at each slip onset."""
    from lieng import _core
    n = vd.size
    x, v, state, status = _core.core_slider(dt, 8, vd, np.ones(n), 2 * math.pi * 5.0, 0.0, fs,
                                            np.array([0.0, 100.0]), np.array([0.5, 0.5]), 0.0, np.zeros(2), 0.0, 1.0,
                                            age_r, age_v, 0.0, 0.0, 0.0, 0.0, 4.0, 0.0, 0.0)
    assert status == 0
    onset = np.flatnonzero((state[:-1] == 1) & (state[1:] == 0))
    return onset, x[onset]


def test_a_drive_that_wobbles_does_not_kick_the_slips():
    """A Coulomb slip (kinetic level FK 20 drops above zero, undamped) from
    the static limit FS arrests at 2 FK - FS whatever the drive does within
    the slip's few milliseconds (geometry: a half turn about FK).  A
    measured drive's velocity wobbles from sample to sample; the core once
    read a wobble that made the relative speed s slightly negative right
    after the release as sliding the other way, and the friction then pushed
    with the spring for a sub-step, a kick that grows with the friction's
    level (not the drop): with 0.5 % noise on the drive, about half the
    slips came out with their trough 0.6 drops low (found on an independent
    generator's slide-hold-slide record, whose baseline's held-out troughs
    were bimodal).  The sub-step is the one :func:`.baseline.run_slice`
    gives (wn h = 0.05)."""
    from lieng import _core

    dt, v0, wn, FS, FK = 1e-3, 1.0, 200.0, 10.5, 10.0
    rng = np.random.default_rng(3)
    for wobble in (0.0, 0.005, 0.02):
        vd = v0 * (1.0 + wobble * rng.standard_normal(30000))
        x, v, state, status = _core.core_slider(dt, 4, vd, np.ones(vd.size), wn, 0.0, FS, np.array([0.0, 100.0]),
                                                np.array([FK, FK]), 0.0, np.zeros(2), 0.0, 1.0, 0.0, 1.0, 0.0, 0.0,
                                                0.0, 0.0, 4.0, 2 * FK - FS, 0.0)
        assert status == 0
        onset = np.flatnonzero((state[:-1] == 1) & (state[1:] == 0))
        arrest = np.flatnonzero((state[:-1] == 0) & (state[1:] == 1)) + 1
        assert onset.size >= 20 and arrest.size >= 20
        # less what the drive's travel through the half turn changes (v0 / wn = 0.005 of the drop) and a
        # sub-step's travel at the slip's speed (wn h (FS - FK) = 0.025)
        assert np.all(np.abs(x[arrest] - (2 * FK - FS)) < 0.03), (wobble, np.round(x[arrest][:10] - 9.5, 3))


def test_the_static_limit_follows_the_loading_velocity_as_stated():
    # slider.f90: stick until x > FS (1 + r ln(max(vl, vr) / vr)), vl the fastest drive of the stick so
    # far. Geometry of the law itself: a drive stepping 0.5 -> 1 -> 4 mm/s gives peaks FS, FS and
    # FS (1 + r ln 4); a hold between two sticks at 4 mm/s keeps the faster limit (no slip in the hold)
    dt, r = 1e-3, 0.1
    vd = np.concatenate([np.full(20000, 0.5), np.full(20000, 1.0), np.full(20000, 4.0), np.zeros(5000),
                         np.full(5000, 4.0)])
    onset, pk = _core_peaks(vd, dt, age_r=r, age_v=1.0)
    t = onset * dt
    tol = 4.0 * dt * 4.0                       # a sample's travel at the fastest drive
    for lo, hi, want in ((2.0, 20.0, 1.0), (22.0, 40.0, 1.0), (42.0, 60.0, 1.0 + r * math.log(4.0))):
        got = pk[(t > lo) & (t < hi)]
        assert got.size >= 2 and np.all(np.abs(got - want) < tol), (lo, hi, got, want)
    assert not np.any((t > 60.0 + dt) & (t < 65.0))           # no slip while the drive holds
    # without the term the core is unchanged: every peak at FS
    _, pk0 = _core_peaks(vd, dt)
    assert np.all(np.abs(pk0[1:] - 1.0) < tol)


def test_a_stretch_between_two_slips_that_is_no_line_is_no_stick_for_the_drive():
    """A sawtooth at v0 with, after every fourth slip, 3 s in which the slider
    oscillates about a level instead of sticking (a stepped drive that puts it
    in another regime): the drive evidence reads only the sticks in which x
    is a line (stick velocity = the drive), so a regime change is not a drive
    modulation (geometry of the trace)."""
    from lieng.diagnose import record_from_arrays
    from lieng.diagnose.evidence import _stick_series
    from lieng.diagnose.segment import find_cycles, prepare, stick_ratios

    fn, dt, v0 = 10.0, 0.002, 1.0
    wn = 2 * math.pi * fn
    g = np.random.default_rng(5)
    X = []
    for k in range(16):
        if k % 4 == 3:                                        # no stick: an oscillation of 0.04 about 0.1
            s = np.arange(int(3.0 / dt)) * dt
            X.append(np.linspace(-0.25, 0.1, int(0.35 / dt)))
            X.append(0.1 + 0.04 * np.sin(2 * math.pi * 2.0 * s))
            X.append(np.linspace(0.1, 0.25, int(0.15 / dt)))
        else:
            X.append(-0.25 + v0 * np.arange(int(0.5 / dt)) * dt)
        X.append(0.25 * np.cos(wn * np.arange(int(0.5 / fn / dt)) * dt))
    x = np.concatenate(X) + 0.002 * g.standard_normal(sum(a.size for a in X))
    t = np.arange(x.size) * dt
    pr = prepare(record_from_arrays(t, x, np.full(x.size, v0)))
    c = find_cycles(pr, fn)
    _, r_all = stick_ratios(pr, c)
    _, r = _stick_series(pr, c)
    assert np.any(np.abs(r_all) < 0.3)                      # the oscillating stretches, read as sticks
    assert r.size >= 9 and np.all(np.abs(r - 1.0) < 0.05)   # only the sticks: at the drive


def test_a_long_smoothing_window_is_convolved_by_fft_to_scipys_numbers():
    """A finely sampled record (a quarter natural period of hundreds of
    samples: a black-box fuzz's 14 kHz record took 78 s, most of it in
    direct convolutions) is smoothed by FFT: the same numbers as scipy's
    savgol_filter (mode "interp", edges included) to rounding."""
    from scipy.signal import savgol_filter

    from lieng.diagnose.segment import FFT_WINDOW, smooth

    g = np.random.default_rng(1)
    x = np.cumsum(g.standard_normal(50001)) * 1e-3 + np.sin(np.arange(50001) * 0.001)
    dt, fn = 7e-5, 10.0
    w = int(round(0.25 / fn / dt)) | 1
    assert w > FFT_WINDOW
    for d in (0, 1, 2):
        ref = savgol_filter(x, w, 3, deriv=d, delta=dt)
        assert np.max(np.abs(smooth(x, dt, fn, deriv=d) - ref)) < 1e-12 * np.max(np.abs(ref))


def test_an_effect_is_named_only_when_its_extension_predicts_the_held_out_cycles():
    """Detection and confirmation: a significant effect is named only when
    the lower end of its extension's held-out gain interval (90 %) is above
    0; otherwise it is reported as detected, with why (diagnosis.json,
    report.md), and the answer is not that effect."""
    from lieng.diagnose import Diagnosis
    from lieng.diagnose.extend import unconfirmed
    from lieng.diagnose.report import write_outputs

    g = dict(parts=2, e0=0.04, e1=0.03, gain=0.25, interval=[0.05, 0.4])
    assert unconfirmed(g, True) is None
    g = dict(g, interval=[-0.1, 0.4])
    why = unconfirmed(g, True)
    assert why and "-0.10" in why and "held-out" in why
    assert unconfirmed(g, True, direct=True) is None        # a measured normal force
    assert unconfirmed(g, False) is None              # no extension to test
    assert unconfirmed(dict(g, parts=0), True) is None      # nothing held out
    same = dict(parts=2, e0=0.04, e1=0.04, gain=0.0, interval=[0.0, 0.0])
    assert "training" in unconfirmed(same, True)

    det = {"effect": "friction_drift", "effect_size": 0.3, "interval_95": [0.1, 0.5], "p": 0.004, "z": 2.6,
           "gain": -0.2, "gain_interval_90": [-0.3, -0.1], "held_out_error_baseline": 0.05,
           "held_out_error_extended": 0.06, "why_not_named": why}
    d = Diagnosis(effect="none", reason="no effect named", detected=[det])
    import tempfile
    from pathlib import Path
    with tempfile.TemporaryDirectory() as tmp:
        write_outputs(d, tmp, "rec.csv", plots=False)
        js = json.loads((Path(tmp) / "diagnosis.json").read_text())
        md = (Path(tmp) / "report.md").read_text()
    assert js["effects"] == [] and js["detected"][0]["effect"] == "friction_drift"
    assert "## Detected, not named" in md and "| friction_drift |" in md


def _sawtooth_sticks(vs_of, fn=10.0, dt=0.001, n=12):
    """A sawtooth whose stick lines rise from -0.25 to 0.25 on the drive
    ``vs_of(k, m)`` (stick k, m samples) and whose slips are half-cosines;
    returns (t, x, drive)."""
    wn = 2 * math.pi * fn
    t_list, x_list, v_list = [], [], []
    t = 0.0
    for k in range(n):
        v0 = 1.0 if k % 2 else 2.0
        vs = vs_of(k, v0, int(0.5 / v0 / dt))
        line = -0.25 + np.r_[0.0, np.cumsum(vs[:-1] * dt)]
        m = int(np.searchsorted(line, 0.25))
        for i in range(m):
            t_list.append(t); x_list.append(line[i]); v_list.append(vs[i]); t += dt
        for i in range(int(0.5 / fn / dt)):
            t_list.append(t); x_list.append(0.25 * math.cos(wn * i * dt)); v_list.append(v0); t += dt
    return np.array(t_list), np.array(x_list), np.array(v_list)


def _noisy_cycles(t, x, vd, fn, g):
    """A plain-NumPy trace with noise of 0.001 added, prepared: (the record,
    its cycles, the drop D, the sticks between two slips, at least 8)."""
    from lieng.diagnose.segment import find_cycles, prepare

    pr = prepare(record_from_arrays(t, x + 0.001 * g.standard_normal(x.size), vd))
    c = find_cycles(pr, fn)
    ks = np.flatnonzero(c.next_ok)
    assert ks.size >= 8
    return pr, c, c.amplitude(pr.x), ks


def test_each_prediction_starts_from_the_stick_line_not_a_rebound_below_it():
    """A sawtooth whose arrests rebound (a second mode: after every trough
    x rings back up, 0.1 D below the stick line at the trough and decaying
    as exp(-3 fn t)): the state each prediction starts from is the stick
    line's level at the trough, read against the drive's travel also where
    the drive steps up within the stick; the trough itself on the plain
    sawtooth and where the drive holds within the stick (x may relax in a
    hold).  A drive modulated in truth but recorded constant: the line is
    read on the drive of the model that carries the modulation (geometry of
    the trace, plain NumPy)."""
    from lieng.diagnose.baseline import Params, stick_start
    from lieng.diagnose.segment import find_cycles, prepare

    fn = 10.0
    g = np.random.default_rng(5)

    def drive(k, v0, n):
        vs = np.full(2 * n, v0)
        if k == 5:                                           # a step up within the stick
            vs[:n // 3] = 0.7 * v0
        if k == 7:                                           # a hold within the stick
            vs[n // 2:n // 2 + n // 4] = 0.0
        return vs

    t, x0, vd = _sawtooth_sticks(drive, fn)
    pr0, c, D, ks = _noisy_cycles(t, x0, vd, fn, g)
    for k in ks:
        assert stick_start(pr0, c, int(k)) == pytest.approx(pr0.x[c.trough_i[k]], abs=0.02 * D)
    x = x0.copy()
    for i in c.trough_i:                                     # the rebound: below the line, ringing back up
        tt = pr0.t[i:] - pr0.t[i]
        x[i:] -= 0.1 * D * np.exp(-3 * fn * tt) * np.cos(2 * np.pi * 4 * fn * tt)
    pr0.x = x
    held = 0
    for k in ks:
        a, b = c.trough_i[k], c.peak_i[k + 1]
        assert pr0.x[a] < -0.25 - 0.08 * D
        if np.min(vd[a:b + 1]) == 0.0:                       # the hold: the trough
            held += 1
            assert stick_start(pr0, c, int(k)) == pr0.x[a]
        else:
            assert stick_start(pr0, c, int(k)) == pytest.approx(-0.25, abs=0.01 * D)
    assert held == 1
    # the drive modulated by 40 % at 0.37 Hz, recorded as its mean
    p = Params(fs=1.0, sg=np.zeros(2), fg=np.zeros(2), drv_a=0.4, drv_f=0.37, drv_ph=0.3)
    # the sticks rise on the modulated drive at their own clock
    t_list, x_list, v_list, tnow = [], [], [], 0.0
    for k in range(12):
        v0 = 1.0 if k % 2 else 2.0
        line = [-0.25]
        while line[-1] < 0.25:
            t_list.append(tnow); x_list.append(line[-1]); v_list.append(v0)
            line.append(line[-1] + v0 * (1 + 0.4 * math.sin(2 * math.pi * 0.37 * tnow + 0.3)) * 0.001)
            tnow += 0.001
        for i in range(50):
            t_list.append(tnow); x_list.append(0.25 * math.cos(2 * math.pi * fn * i * 0.001)); v_list.append(v0)
            tnow += 0.001
    prm = prepare(record_from_arrays(np.array(t_list), np.array(x_list), np.array(v_list)))
    cm = find_cycles(prm, fn)
    xm = prm.x.copy()
    for i in cm.trough_i:
        tt = prm.t[i:] - prm.t[i]
        xm[i:] -= 0.1 * D * np.exp(-3 * fn * tt) * np.cos(2 * np.pi * 4 * fn * tt)
    prm.x = xm
    km = np.flatnonzero(cm.next_ok)
    assert km.size >= 8
    for k in km:
        assert stick_start(prm, cm, int(k), p) == pytest.approx(-0.25, abs=0.01 * D)
    # on the recorded (constant) drive the line leans: the start is off
    assert max(abs(stick_start(prm, cm, int(k)) + 0.25) for k in km) > 0.02 * D



def test_the_stick_creep_is_fitted_from_where_each_prediction_starts():
    """A slider that creeps before each slip (its stick rising at
    1 - 0.6 r**6 of the drive, r its share of the rise) and rebounds after
    each arrest (x 0.08 of the drop below the stick line at the trough,
    decaying as exp(-3 fn t); a cosine slip of half a natural period between
    a friction level of 1.5 and a limit of 2.5): the baseline's creep law is
    fitted so that its stick, started where every held-out prediction starts
    it (the stick line's level at the trough), lasts as long as the record's
    (within 1 % of the period).  Fitted from the trough itself, the model
    started 0.08 higher than fitted and its sticks ran 6 % of the period
    short in every cycle (bouc_wen_brake: 4 %, the bias in every error)
    (geometry of the trace, plain NumPy)."""
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.extend import Judge

    fn, v0, dt = 10.0, 1.0, 0.001
    lo, hi, a = 1.5, 2.5, 0.08
    xs = []
    for _ in range(30):
        x, tt, stick = lo, 0.0, []
        while x < hi:
            x += v0 * dt * (1.0 - 0.6 * ((x - lo) / (hi - lo)) ** 6)
            tt += dt
            stick.append(x - a * np.exp(-3 * fn * tt))
        slip = 0.5 * (hi + lo) + 0.5 * (hi - lo) * np.cos(2 * np.pi * fn * np.arange(1, int(0.5 / fn / dt)) * dt)
        xs += [np.array(stick), slip]
    x = np.concatenate(xs)
    t = dt * np.arange(x.size)
    pr, c, D, ks = _noisy_cycles(t, x, np.full(x.size, v0), fn, np.random.default_rng(7))
    base = fit_baseline(pr, c, fn)
    assert base.creep1 > 0
    dc = Judge(pr, c, fn, float(t[0]), float(t[-1])).vector(base)[0]
    assert abs(float(np.median(dc[:, 0]))) < 0.01


def test_a_stick_that_creeps_before_its_slip_starts_from_its_trough(monkeypatch):
    """A sawtooth whose sticks rise at the drive velocity from the trough
    and creep for their last third (x at 0.2 of the drive velocity from
    0.9 of the rise on, a rounded top): the state each prediction starts
    from is the trough, where the 1-DoF slider arrested, read on the
    stick's early part (:data:`.baseline.START_PART`); the line through the
    whole middle of the stick, the knee included, would start it 5 % of
    the drop higher (geometry of the trace, plain NumPy)."""
    import lieng.diagnose.baseline as ext_mod

    fn, v0, dt = 10.0, 1.0, 0.001
    g = np.random.default_rng(3)
    xs = []
    for k in range(12):
        rise = np.r_[np.arange(-0.25, 0.2, v0 * dt), np.arange(0.2, 0.25, 0.2 * v0 * dt)]
        xs += [rise, 0.25 * np.cos(2 * np.pi * fn * np.arange(int(0.5 / fn / dt)) * dt)]
    x = np.concatenate(xs)
    pr, c, D, ks = _noisy_cycles(dt * np.arange(x.size), x, v0, fn, g)
    for k in ks:
        assert ext_mod.stick_start(pr, c, int(k)) == pytest.approx(pr.x[c.trough_i[k]], abs=0.01 * D)
    monkeypatch.setattr(ext_mod, "START_PART", (0.25, 0.875))
    assert min(ext_mod.stick_start(pr, c, int(k)) - pr.x[c.trough_i[k]] for k in ks) > 0.03 * D


def test_the_records_own_scatter_is_read_from_successive_cycles_and_left_out_of_the_explainable_gain():
    """A sawtooth (plain NumPy) whose peaks scatter at random (1.5 % of the
    drop, white) on a slow trend (+20 % of the drop over the record): the
    scatter each prediction faces in the peaks (:meth:`.extend.Judge.scatter`,
    half the mean square difference of successive cycles) reads the white
    part within a factor 1.6, not the trend; the gain of the explainable
    part is 0 for the same model on both sides, of the sign of the whole
    gain otherwise, and larger than it when the scatter is a share of the
    error."""
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.extend import Judge, gain_folds
    from lieng.diagnose.segment import find_cycles, prepare

    fn, v0, dt, n = 10.0, 1.0, 0.001, 40
    g = np.random.default_rng(11)
    jitter = 0.015 * 0.5 * g.standard_normal(n)
    xs = []
    for k in range(n):
        top = 0.25 + 0.1 * k / n + jitter[k]
        xs += [np.arange(-0.25, top, v0 * dt), -0.25 + (top + 0.25) * 0.5 * (1 + np.cos(
            np.pi * np.arange(int(0.5 / fn / dt)) * dt * 2 * fn))]
    x = np.concatenate(xs)
    t = dt * np.arange(x.size)
    pr = prepare(record_from_arrays(t, x + 0.0005 * g.standard_normal(x.size), v0))
    c = find_cycles(pr, fn)
    D = c.amplitude(pr.x)
    J = Judge(pr, c, fn, float(pr.t[0]), float(pr.t[-1]) + dt)
    white = float(np.var(jitter)) / D ** 2
    peaks = J.rec[:, 1]
    assert np.var(peaks) > 3 * white                       # the trend dominates the plain variance
    assert white / 1.6 < J.scatter()[1] < 1.6 * white
    base = fit_baseline(pr, c, fn)
    h = float(pr.t[int(0.6 * pr.t.size)])
    same = gain_folds(pr, c, fn, [(h, float(pr.t[-1]) + dt, base, base)])
    assert same["gain"] == 0.0 and same["gain_explainable"] == 0.0 and same["scatter_share"] > 0
    other = base.copy(fs=base.fs * 1.02)
    for a, b in ((base, other), (other, base)):
        r = gain_folds(pr, c, fn, [(h, float(pr.t[-1]) + dt, a, b)])
        assert np.sign(r["gain_explainable"]) == np.sign(r["gain"]) != 0
        assert abs(r["gain_explainable"]) >= abs(r["gain"]) and math.isfinite(r["gain_explainable"])


def _ac_coupled_sawtooth(tau, fn=10.0, v0=2.0, level=5.0, cycles=30, dt=0.001, seed=4):
    """A Coulomb slider's spring force (plain NumPy: sticks rising at v0 from
    level - 0.25 to level + 0.25 mm, slips as half a cosine at fn, as x in mm
    and as F in N with a stiffness of 1000 N/m) recorded through a
    first-order high-pass of time constant ``tau`` (an AC-coupled sensor,
    discretised as the RC filter y[n] = a (y[n-1] + x[n] - x[n-1]),
    a = tau / (tau + dt), its output starting at the force's own value):
    (t, recorded, true)."""
    g = np.random.default_rng(seed)
    xs = []
    for _ in range(cycles):
        xs += [np.arange(level - 0.25, level + 0.25, v0 * dt),
               level + 0.25 * np.cos(2 * np.pi * fn * np.arange(int(0.5 / fn / dt)) * dt)]
    x = np.concatenate(xs) + 0.0005 * g.standard_normal(sum(map(len, xs)))
    a = tau / (tau + dt)
    y = np.empty_like(x)
    y[0] = x[0]
    for i in range(1, x.size):
        y[i] = a * (y[i - 1] + x[i] - x[i - 1])
    return dt * np.arange(x.size), y, x


def test_an_ac_coupled_force_is_recovered_and_its_decay_not_read_as_drift(tmp_path):
    """A force recorded AC-coupled (a charge amplifier's high-pass, tau 40 s
    on a 9.5 s record: the level sinks by 1.1 mm, 2.2 drops) is read back
    with ``--highpass`` within 0.4 % of the drop (RMS; the filter inverted is
    an RC discretisation, the inverse a trapezoid integral); diagnosed as
    recorded, the sensor's decay is a friction level that drifts; with
    ``--highpass`` the Coulomb slider it is (effect none, no drift)."""
    from lieng.diagnose import read_record

    t, y, x = _ac_coupled_sawtooth(40.0)
    assert x[-1] - y[-1] > 2.0 * 0.5
    p = tmp_path / "ac.csv"
    p.write_text("time [s],friction [N]\n" + "".join(f"{a:.4f},{b:.6f}\n" for a, b in zip(t, y)))
    rec = read_record(p, v0=2.0, stiffness=1000.0, highpass=40.0)
    assert rec.highpass == 40.0 and any("high-pass" in n for n in rec.notes)
    assert float(np.sqrt(np.mean((rec.x - x) ** 2))) < 0.004 * 0.5
    raw = diagnose(read_record(p, v0=2.0, stiffness=1000.0), 10.0)
    assert "friction_drift" in [e["effect"] for e in raw.effects + raw.detected]
    out = tmp_path / "o"
    assert main(["diagnose", str(p), "--v0", "2", "--stiffness", "1000", "--fn", "10", "--highpass", "40",
                 "-o", str(out), "-q", "--no-plots"]) == 0
    d = json.loads((out / "diagnosis.json").read_text())
    assert d["effect"] == "none" and not d["detected"]
    assert any("high-pass" in n for n in d["notes"])


def _forced_coulomb(eps, sensor=0.0, fn=10.0, r=3.7, v0=2.0, fs=1.0, fk=0.6, seconds=12.0, seed=0, load_of=None,
                    load_x=0.0, mode=None, rig=None):
    """A Coulomb slider whose load is modulated, N (1 + eps sin(2 pi f t)), f = r fn (the
    static and the kinetic force both), stepped by semi-implicit Euler at 40 kHz (plain NumPy,
    no lieng code), sampled at 2 kHz; ``sensor``: a line at f added to the recorded x (a
    vibration of the sensor, not of the load); ``load_of(t)``: the load instead; ``load_x``:
    the load also follows the slider, times 1 + load_x (x - 0.8); ``mode`` (zeta, gamma):
    the friction drives a normal mode at f (a lever's, damping ratio zeta) that adds q to
    the load, q'' + 2 zeta w q' + w**2 q = w**2 gamma (F - fk), F the friction force (the
    spring's in stick, fk N in slip).  With ``load_x`` or ``mode`` the load at the samples
    is returned too.  ``rig`` (f_s, zeta): x recorded through a sensor with its own resonance
    at f_s Hz, y'' = ws**2 (x - y) - 2 zeta ws y', integrated alongside at the same step."""
    g = np.random.default_rng(seed)
    wn, w, h = 2 * math.pi * fn, 2 * math.pi * r * fn, 1.0 / 40000
    n = int(seconds / h)
    x, xd, stick, q, qd = 0.3, v0, True, 0.0, 0.0
    y, yd, ws = x, 0.0, 2 * math.pi * rig[0] if rig else 0.0
    out, loads = np.empty(n // 20), np.empty(n // 20)
    for i in range(n):
        t = i * h
        load = 1.0 + eps * math.sin(w * t) if load_of is None else load_of(t)
        load *= 1.0 + load_x * (x - 0.8)
        if mode is not None:
            load += q
            F = x if stick else fk * load
            qd += h * (-2 * mode[0] * w * qd - w * w * (q - mode[1] * (F - fk)))
            q += h * qd
        if stick:
            x += v0 * h
            if x >= fs * load:
                stick = False
        else:
            xd += h * wn * wn * (fk * load - x)
            x += h * xd
            if xd >= v0:
                stick, xd = True, v0
        if rig:
            yd += h * (ws * ws * (x - y) - 2 * rig[1] * ws * yd)
            y += h * yd
        if i % 20 == 0:
            out[i // 20], loads[i // 20] = (y if rig else x), load
    tt = np.arange(out.size) * 20 * h
    xs = out + sensor * np.sin(w * tt) + 0.002 * g.standard_normal(out.size)
    return (tt, xs, r * fn) if not load_x and mode is None else (tt, xs, r * fn, loads)


@pytest.mark.parametrize("eps", [0.03, 0.06])
def test_the_triggering_size_is_the_load_modulation(eps):
    """Without a normal force, the triggering size is the load modulation
    the line in x implies: recovered within a quarter (the analytic truth of
    an independently stepped slider, not a number the code produced)."""
    from lieng.diagnose.evidence import trig_modulation
    from lieng.diagnose.segment import find_cycles, prepare
    t, x, f = _forced_coulomb(eps)
    pr = prepare(record_from_arrays(t, x, 2.0))
    c = find_cycles(pr, 10.0)
    size, se, p = trig_modulation(pr, c, 10.0, f, c.amplitude(pr.x))
    assert abs(size - eps) < 0.25 * eps + 2 * se
    assert p < 0.005                       # and it is in the friction: the sticks do not carry it


@pytest.mark.parametrize("wander", [0.0, 0.03])
def test_a_normal_forces_modulation_is_read_whole_when_its_frequency_wanders(wander):
    """A recorded normal force modulated by 5 % by a shaker whose frequency
    wanders by +-3 % (an unbalanced motor under load): the size is read as
    the band about the line, the noise beside it taken out, so it is the
    analytic 5 % (within a tenth) whether the frequency wanders or not; one
    sinusoid fitted at the line's frequency reads well under half of the
    wandering one (`drill_string`'s exciter read 0.008-0.025 against
    0.036-0.065)."""
    from types import SimpleNamespace

    from lieng.diagnose.evidence import force_modulation
    from lieng.diagnose.signals import line_fit

    g = np.random.default_rng(3)
    dt, f0 = 5e-4, 40.0
    t = np.arange(40000) * dt
    phase = 2 * np.pi * f0 * (t + wander / (2 * np.pi * 0.13) * (1 - np.cos(2 * np.pi * 0.13 * t)))
    N = 100.0 * (1 + 0.05 * np.sin(phase)) + 0.5 * g.standard_normal(t.size)
    size, se = force_modulation(SimpleNamespace(dt=dt, t=t), N - N.mean(), f0, float(N.mean()))
    assert abs(size - 0.05) < 0.005 and se < 0.005
    if wander:
        assert line_fit(N - N.mean(), t, f0)[0] / N.mean() < 0.5 * 0.05


def test_a_line_the_sticks_show_too_is_no_load_modulation():
    """A line added to x (a sensor's vibration: in the sticks as in the
    slips) at the size of a 6 % modulation's response: the size's own test
    (Hotelling's, slips' line less the sticks') holds its level over 60
    such records, lines from 3.7 to 5.2 fn (measured: 2.5 % below 0.05 and
    1.5 % below 0.01 over 200)."""
    from lieng.diagnose.evidence import trig_modulation
    from lieng.diagnose.segment import find_cycles, prepare
    ps = []
    for seed in range(60):
        t, x, f = _forced_coulomb(0.0, sensor=0.004, seed=seed, r=3.7 + 0.37 * (seed % 5))
        pr = prepare(record_from_arrays(t, x, 2.0))
        c = find_cycles(pr, 10.0)
        ps.append(trig_modulation(pr, c, 10.0, f, c.amplitude(pr.x))[2])
    ps = np.array(ps)
    # binomial(60, 0.05): P(>= 8) = 0.01; binomial(60, 0.01): P(>= 3) = 0.02
    assert np.count_nonzero(ps < 0.05) <= 7 and np.count_nonzero(ps < 0.01) <= 2, np.sort(ps)[:8]


def test_the_load_modulation_read_in_the_slips_has_the_loads_phase():
    """The modulation x's line implies in the slips, which the triggering
    extension starts from, with its phase: on a Coulomb slider whose load is
    N (1 + 0.06 sin(2 pi f t)) (plain NumPy, f 3.7 and 4.6 fn, where the
    friction's line in x is of the opposite sign: x = F / (1 - (f/fn)**2)),
    the size reads 0.06 within 10 % and the phase 0 within 0.2 rad (measured:
    0.059-0.064, -0.04..+0.09 rad)."""
    from lieng.diagnose.evidence import trig_modulation
    from lieng.diagnose.segment import find_cycles, prepare
    for seed, r in ((0, 3.7), (1, 4.6)):
        t, x, f = _forced_coulomb(0.06, seed=seed, r=r)
        pr = prepare(record_from_arrays(t, x, 2.0))
        c = find_cycles(pr, 10.0)
        eps, _, p, ph = trig_modulation(pr, c, 10.0, f, c.amplitude(pr.x), phase=True)
        assert eps == pytest.approx(0.06, rel=0.1) and p < 1e-6
        assert abs(math.remainder(ph, 2 * math.pi)) < 0.2


def _weakening_slider(fn=10.0, v0=2.0, fs=1.0, f0=0.95, fk=0.5, vs=3.0, cv=0.01, seconds=10.0, seed=0):
    """A slider whose friction falls exponentially with the sliding speed s
    and has a viscous part, fk + (f0 - fk) exp(-s / vs) + cv s, below a
    static limit fs, stepped by semi-implicit Euler at 40 kHz (plain NumPy,
    no lieng code), sampled at 2 kHz with noise of 0.2 % of fs."""
    g = np.random.default_rng(seed)
    wn, h = 2 * math.pi * fn, 1.0 / 40000
    n = int(seconds / h)
    x, xd, stick = 0.3, v0, True
    out = np.empty(n // 20)
    for i in range(n):
        if stick:
            x += v0 * h
            if x >= fs:
                stick = False
        else:
            s = v0 - xd
            xd += h * wn * wn * (fk + (f0 - fk) * math.exp(-max(s, 0.0) / vs) + cv * s - x)
            x += h * xd
            if xd >= v0:
                stick, xd = True, v0
        if i % 20 == 0:
            out[i // 20] = x
    return np.arange(out.size) * 20 * h, out + 0.002 * fs * g.standard_normal(out.size)


@pytest.mark.parametrize("start", [0.55, 1.6])
def test_fn_from_the_slips_duration_is_reached_from_a_far_start(start):
    """Indirect inference of fn (calibrate_fn) from a first guess far from
    it (the slips' arcs read 0.36-1.14 of the true fn on the independent
    generators' records without --fn): the fixed-point steps reach the
    independent slider's fn within 3 %, not the end of a bound about the
    guess (a bound of 0.4 stopped at 0.77 and 1.14 fn here)."""
    from lieng.diagnose.baseline import calibrate_fn
    from lieng.diagnose.segment import prepare
    t, x = _weakening_slider()
    pr = prepare(record_from_arrays(t, x, 2.0))
    assert calibrate_fn(pr, start * 10.0) == pytest.approx(10.0, rel=0.03)


@pytest.mark.slow
def test_an_offset_force_reads_as_the_same_record():
    """A force sensor's zero offset (here 100 drops) is no physics: the same
    independently stepped Coulomb slider read with and without it gives the
    same answer, on a full set of replicates, and its kinetic level moved by
    the offset (the slider core once kicked each slip off with the whole
    spring force, so a slip from a large x ran away and no replicate
    stick-slipped: `none` on 0 replicates, found by a black-box audit)."""
    t, x, _ = _forced_coulomb(0.0)
    off = 100 * 0.4
    d0, d1 = (diagnose(record_from_arrays(t, x + o, 2.0), 10.0) for o in (0.0, off))
    assert d0.effect == d1.effect == "none"
    assert d0.n_replicates == d1.n_replicates >= 30
    assert abs(np.median(d1.baseline.fg) - off - np.median(d0.baseline.fg)) < 0.02
    assert abs(d1.baseline.fs - off - d0.baseline.fs) < 0.02


def test_a_long_gap_is_cut_not_interpolated():
    """A pause in the logging (one stray sample 20 s before the run, a
    600 s pause in its middle) is not bridged by a straight line, which
    would be read as a stick or a slip: the longest part without a gap of
    more than GAP_CUT intervals is analysed, and the note says so (found by
    a black-box audit: a stray early sample hid all 26 cycles of a record)."""
    from lieng.diagnose.read import GAP_CUT

    t = np.arange(4000) * 1e-3
    x = 0.5 * (1 - np.cos(2 * np.pi * 3.0 * t))
    rec = record_from_arrays(np.r_[-20.0, t], np.r_[0.0, x], 1.0)
    assert rec.t[0] == 0.0 and rec.t.size == t.size
    assert any("gap" in s and "not interpolated" in s for s in rec.notes), rec.notes
    t2 = np.r_[t, t[-1] + 600 + t[:1000]]
    rec = record_from_arrays(t2, np.r_[x, x[:1000]], 1.0)
    assert rec.t[-1] == t[-1] and rec.t.size == t.size
    # a gap within GAP_CUT intervals is bridged, as before
    keep = np.r_[np.arange(100), np.arange(100 + GAP_CUT - 2, t.size)]
    rec = record_from_arrays(t[keep], x[keep], 1.0)
    assert rec.t.size == t.size and any("resampled" in s for s in rec.notes)


def test_a_quantised_position_column_gives_a_smooth_drive(tmp_path):
    """An encoder's position column (steps of 0.1 mm at 2 mm/s, sampled at
    2 kHz: 49 samples in 50 repeat the last count) gives the drive
    velocity the stage had, not a train of pulses (which `diagnose` once
    read as a drive modulation, found by a black-box audit)."""
    from lieng.diagnose import read_record

    t, x, _ = _forced_coulomb(0.0)
    pos = np.floor(2.0 * t / 0.1) * 0.1
    p = tmp_path / "enc.csv"
    p.write_text("t [s],x [mm],position [mm]\n" + "".join(f"{a:.6f},{b:.6f},{c:.1f}\n" for a, b, c in zip(t, x, pos)))
    rec = read_record(p)
    mid = slice(rec.t.size // 20, -rec.t.size // 20)
    assert np.max(np.abs(rec.vd[mid] / 2.0 - 1.0)) < 0.1
    assert any("steps of 0.1 mm" in s for s in rec.notes), rec.notes


def test_a_noisy_position_column_gives_a_one_way_drive(tmp_path):
    """A rock-mechanics LVDT on the load point (white noise 20 nm at 1 um/s,
    sampled at 1 kHz: its noise 20 times its travel per sample) gives one
    forward stroke at the drive velocity, not hundreds of strokes cut where
    a 0.02 s derivative of the noise changes sign (found by a black-box
    audit: 536 "strokes" and a stiffness off by 2.8 times)."""
    from lieng.diagnose import read_record
    from lieng.diagnose.segment import prepare

    t, x, _ = _forced_coulomb(0.0)
    pos = 0.001 * t + 2e-5 * np.random.default_rng(3).standard_normal(t.size)
    p = tmp_path / "lvdt.csv"
    p.write_text("t [s],x [mm],position [mm]\n" + "".join(f"{a:.6f},{b:.6f},{c:.3e}\n" for a, b, c in zip(t, x, pos)))
    rec = read_record(p)
    mid = slice(rec.t.size // 20, -rec.t.size // 20)
    assert abs(np.median(rec.vd[mid]) / 0.001 - 1.0) < 0.1
    assert np.all(rec.vd[mid] > 0)
    assert len(prepare(rec).strokes) == 1
    assert any("noise" in s and "derivative over" in s for s in rec.notes), rec.notes


def test_steady_sliding_keeps_the_sign_of_its_level():
    """Steady sliding (no sticks, no slips): x holds a positive level while
    the drive moves forward, so it is written with the drive and not turned
    (the sign had been left to the noise's; found by the audit)."""
    from lieng.diagnose.segment import prepare

    t = np.arange(20000) * 5e-4
    for seed in range(4):
        x = 0.8 + 0.007 * np.random.default_rng(seed).standard_normal(t.size)
        for sign in (1.0, -1.0):
            pr = prepare(record_from_arrays(t, sign * x, sign * 1.0))
            assert not pr.flipped and np.median(pr.x) > 0.7
        assert prepare(record_from_arrays(t, -x, 1.0)).flipped


@pytest.mark.slow
def test_a_sawtooth_whose_fn_the_arcs_cannot_fix_is_diagnosed():
    """A drifting sawtooth sampled at 200 Hz whose drops are a sample or
    two: the arcs fix fn so loosely (its standard error over a third of it)
    that the replicates' fn, drawn within three of them, went negative and
    the slider failed (a helper session's fuzzing of `lieng diagnose`);
    the uncertainty is now held at 50 %.  The arcs' reading sits at the
    edge of what the record's sampling can carry: with numpy 2.4.6 and
    scipy 1.17.1 (stop 63's machine) they read 69.7 +- 31.8 Hz, 2.9 samples
    a period, and the record asks for --fn instead, in one line (exit 2 at
    the command line); either way, no crash and no non-finite number."""
    from lieng.errors import LiengInputError

    g = np.random.default_rng(7)
    t = np.arange(6133) / 200.0
    F = np.minimum(0.1 * t, 0.3088)
    F = F + 0.2 * 0.3088 * ((t * 2.7) % 1 - 0.5) + 0.001 * g.standard_normal(t.size)
    try:
        d = diagnose(record_from_arrays(t, F, 0.01))
    except LiengInputError as e:
        assert "give --fn" in str(e) and "\n" not in str(e)
        return
    assert d.effect in CANDIDATES + ("none", "unexplained", "no_stick_slip", "too_few_cycles") and math.isfinite(d.gain)
    json.dumps(d.to_json(), allow_nan=False)


def test_a_noisy_fast_sampled_record_keeps_its_cycles():
    """An independently stepped Coulomb slider sampled at 2 kHz under white
    noise of a quarter of its drop: every cycle the clean record has is
    found (the cycle finder's thresholds read the per-sample noise, eight
    times which exceeded the drop: 'no stick-slip'; found by the audit), and
    a clean record is read exactly as before (its thresholds unchanged)."""
    from lieng.diagnose.segment import find_cycles, prepare

    t, x, _ = _forced_coulomb(0.0)
    clean = find_cycles(prepare(record_from_arrays(t, x, 2.0)), 10.0)
    noisy = x + 0.2 * np.random.default_rng(4).standard_normal(x.size)
    for fn in (10.0, None):
        c = find_cycles(prepare(record_from_arrays(t, noisy, 2.0)), fn)
        assert c.n >= clean.n - 1, (fn, c.n, clean.n)
        assert np.median(np.diff(t[c.peak_i])) == pytest.approx(np.median(np.diff(t[clean.peak_i])), rel=0.05)


@pytest.mark.slow
def test_a_wildly_wrong_fn_is_never_none():
    """--fn twenty times too low (a Coulomb slider of 10 Hz read at 0.5 Hz):
    the slips are questioned in a warning, and the answer is not `none`
    (which says the baseline explains the record): with no calibration the
    audit's 47x-off --fn had been `none` on 4 replicates."""
    t, x, _ = _forced_coulomb(0.0)
    d = diagnose(record_from_arrays(t, x, 2.0), 0.5)
    assert d.effect != "none", d.reason
    assert any("check --fn" in w for w in d.warnings), d.warnings


def test_a_sliding_force_record_reads_its_stiffness_from_the_reversal_ramps(tmp_path):
    """A reciprocating force record that never stick-slips, without
    --stiffness: an elastic-perfectly-plastic contact (20 N/mm up to +-3 N,
    plain NumPy) on a sinusoidal stage, whose presliding ramps fall where the
    stage is slow.  The stiffness is read from those ramps (within 2 %; the
    steepest fifth of the fast part once read 8 % low, and on a 0.01 mm
    stroke a noise slope), so the report's own ramp slope is 1."""
    from lieng.diagnose import read_record

    t = np.arange(0, 40, 0.001)
    pos = 0.5 * np.sin(2 * np.pi * 0.25 * t)
    F = np.empty_like(pos)
    f = -3.0
    for i in range(pos.size):
        f = min(max(f + 20.0 * (pos[i] - pos[i - 1]), -3.0), 3.0) if i else f
        F[i] = f
    F += 0.003 * np.random.default_rng(0).standard_normal(F.size)
    p = tmp_path / "ep.csv"
    p.write_text("t [s],F [N],position [mm]\n" + "".join(f"{a:.4f},{b:.6f},{c:.7f}\n" for a, b, c in zip(t, F, pos)))
    rec = read_record(p)
    d = diagnose(rec)
    assert d.effect == "no_stick_slip"
    assert rec.stiffness == pytest.approx(2.0e4, rel=0.02)
    assert np.nanmedian(d.to_json()["sliding"]["ramp_slope"]) == pytest.approx(1.0, abs=0.02)


@pytest.mark.slow
def test_sticks_rising_faster_than_the_drive_are_questioned():
    """A stuck slider loads the spring at the drive velocity, no faster: the
    independently stepped Coulomb slider (drive 2 mm/s) read with --v0 0.5
    rises at 4 times the drive in its sticks, which the report says (a wrong
    --v0, stiffness or unit); read as it was driven, it says nothing."""
    t, x, _ = _forced_coulomb(0.0)
    right, wrong = (diagnose(record_from_arrays(t, x, v0), 10.0, replicates=9, budget=5.0) for v0 in (2.0, 0.5))
    said = lambda d: [w for w in d.warnings if "times the drive velocity" in w]
    assert not said(right)
    assert said(wrong) and "4 times" in said(wrong)[0], wrong.warnings


def _tilted_track(tilt, n_drift=0.0, f_drift=0.0, fn=12.0, v0=1.5, seconds=14.0, seed=3, mod=(0.0, 0.0)):
    """A Coulomb slider (static 1.0, kinetic 0.6, over the stiffness, mm) on a
    track whose normal load follows the slider's position along it,
    N = 1 + tilt (u - u_mid) / travel (a tilted track: the static and kinetic
    friction both follow N), stepped by semi-implicit Euler at 20 kHz (plain
    NumPy, no lieng code) and sampled at 1 kHz; returns (t, x, N recorded as a
    force) with a sensor drift of the normal channel ``n_drift`` (relative,
    linear in time, which the friction does not follow) and of x ``f_drift``
    (mm); ``mod`` = (a, f): the load also modulated in time, a sin(2 pi f t)
    (an exogenous load: a servo's own course)."""
    g = np.random.default_rng(seed)
    wn, h = 2 * math.pi * fn, 1.0 / 20000
    n = int(seconds / h)
    travel = v0 * seconds
    x, xd, stick = 0.4, v0, True
    xs, ns = np.empty(n // 20), np.empty(n // 20)
    for i in range(n):
        u = v0 * i * h - x
        load = 1.0 + tilt * (u / travel - 0.5) + mod[0] * math.sin(2 * math.pi * mod[1] * i * h)
        if stick:
            x += v0 * h
            if x >= 1.0 * load:
                stick = False
        else:
            xd += h * wn * wn * (0.6 * load - x)
            x += h * xd
            if xd >= v0:
                stick, xd = True, v0
        if i % 20 == 0:
            xs[i // 20], ns[i // 20] = x, load
    t = np.arange(xs.size) * 20 * h
    x_rec = xs + f_drift * t / t[-1] + 0.002 * g.standard_normal(t.size)
    n_rec = 5.0 * (ns + n_drift * t / t[-1]) + 0.002 * g.standard_normal(t.size)
    return t, x_rec, n_rec


@pytest.mark.slow
@pytest.mark.parametrize("tilt,n_drift,named", [(0.3, 0.0, "load_variation"), (0.0, 0.08, "none")])
def test_a_load_that_follows_the_track_is_named_and_a_drifting_sensor_is_not(tilt, n_drift, named):
    """A normal force that changes along the track (a tilted track) carries
    the friction level with it: the drift of the friction is the load's,
    named as a load variation (not as a drift of the friction).  A normal
    channel that drifts by 8 % while the friction does not follow it (a
    sensor's drift) names nothing."""
    t, x, N = _tilted_track(tilt, n_drift, f_drift=0.01)
    d = diagnose(record_from_arrays(t, x, 1.5, N, y_is_force=True), 12.0)
    assert d.effect == named
    if named != "none":
        assert d.gain >= 0.3 and d.evidence["friction_drift"]["named"] is False
        assert "accounted_for" in d.evidence["friction_drift"]


def _lab_rows(n=400, rate=1000.0):
    """A plain sawtooth force record (N) at ``rate`` Hz and a normal force."""
    t = np.arange(n) / rate
    F = 1.0 + 0.4 * ((t * 5.0) % 1.0)
    return t, F, 5.0 + 0.0 * t


@pytest.mark.parametrize("kind", ["savetxt", "repeated_header", "footer", "cp1252", "utf16", "gf", "minus",
                                  "quoted_decimal_comma", "restart", "excel_sep", "labview", "french",
                                  "excel_serial"])
def test_exports_as_lab_software_writes_them(tmp_path, kind):
    """Table exports a black-box audit found refused (stop 40): read, and
    what was done said in a note.  The numbers read are the file's own."""
    from lieng.diagnose import read_record

    t, F, N = _lab_rows()
    rows = [f"{a:.6f},{b:.6f},{c:.3f}" for a, b, c in zip(t, F, N)]
    head = "t [s],F [N],N [N]"
    enc, scale, note = "utf-8", 1.0, None
    if kind == "savetxt":
        text, note = "# " + head + "\n" + "\n".join(rows), "comment line"
    elif kind == "repeated_header":
        text, note = "\n".join([head] + rows[:200] + [head] + rows[200:]), "repeats"
    elif kind == "footer":
        text, note = "\n".join([head] + rows + ["Mean friction: 1.2 N", "End of test"]), "after the last row"
    elif kind == "cp1252":
        text, enc, note = "\n".join(["Zeit [s];Reibkraft [N];Normalkraft [N]"] +
                                    [r.replace(",", ";") for r in rows]), "cp1252", "windows-1252"
        text = "Prüfstand: Stift-Scheibe\n" + text
    elif kind == "utf16":
        text, enc, note = "\n".join([head] + rows), "utf-16", "utf-16"
    elif kind == "gf":
        text, scale = "\n".join(["t [s],F [gf],N [gf]"] + rows), 9.80665e-3
    elif kind == "minus":
        rows = [f"{a:.6f},\u2212{b:.6f},{c:.3f}" for a, b, c in zip(t, F, N)]
        text, scale = "\n".join([head] + rows), -1.0
    elif kind == "quoted_decimal_comma":
        rows = ['"' + '","'.join(f"{v:.6f}".replace(".", ",") for v in r) + '"' for r in zip(t, F, N)]
        text = "\n".join(['"t [s]","F [N]","N [N]"'] + rows)
    elif kind == "excel_sep":              # Excel's separator hint above the header (stop 42's audit)
        text = "\n".join(["sep=;", "t [s];F [N];N [N]"] + [r.replace(",", ";") for r in rows])
    elif kind == "labview":                # a LabVIEW .lvm's time column
        text = "\n".join(["X_Value\tFriction force\tNormal force"] + [r.replace(",", "\t") for r in rows])
    elif kind == "french":                 # French column names, accents and all, in Latin-1
        text, enc = "\n".join(["Temps (s);Force tangentielle (N);Force normale (N)"] +
                               [r.replace(",", ";") for r in rows]), "latin-1"
    elif kind == "excel_serial":           # a spreadsheet's serial dates (days) in a Date column
        rows = [f"{45363.5 + a / 86400:.12f},{b:.6f},{c:.3f}" for a, b, c in zip(t, F, N)]
        text, note = "\n".join(["Date,F [N],N [N]"] + rows), "serial dates"
    else:                                  # a second run appended: the clock starts again; the longer is read
        text, note = "\n".join([head] + rows[:150] + rows), "starts again"
    p = tmp_path / "export.csv"
    p.write_bytes(text.encode(enc))
    r = read_record(p, v0=1.0, stiffness=1000.0)
    assert r.t.size == t.size
    # x = F / stiffness in mm (the sign turned back when the force is written negative)
    assert np.allclose(np.abs(r.x), np.abs(scale) * F, rtol=1e-5)
    if note:
        assert note in " ".join(r.notes)


def test_a_flat_record_has_no_cycle_and_a_force_that_changes_sign_is_questioned():
    """A force exactly constant shows no stick-slip cycle (it had one, from
    rounding); a force-only record read with a constant --v0 whose force
    changes sign for long stretches (a reciprocating rig) is read as one:
    its strokes from the force's side, and said."""
    t = np.arange(4000) / 1000.0
    d = diagnose(record_from_arrays(t, np.full(t.size, 3.0), 5.0), 10.0)
    assert d.effect == "no_stick_slip" and d.n_cycles == 0
    x = np.sign(np.sin(2 * np.pi * 0.5 * t)) * (1.0 + 0.4 * ((t * 5.0) % 1.0))
    d = diagnose(record_from_arrays(t, x, 5.0), 10.0)
    assert any("taken to reverse" in n and "4 strokes" in n for n in d.notes)


def test_a_reciprocating_slider_that_never_slides_has_no_sliding_level():
    """A reciprocating drive whose stroke (2 mm of x behind the spring)
    stays under the static limit (4 mm): x follows the drive through every
    stroke, a rigid stick, and no stroke reaches a level.  Nothing is read
    as steady sliding: no direction asymmetry (the median of each stroke's
    second half differs between the directions by where the stroke starts,
    and was named at +4 of the level, p = 0, found by a black-box audit),
    and the reason says the slider does not slide.  The same drive over a
    slider that slides at 0.5 mm after a ramp reads its level as before."""
    dt, v0, half = 1e-3, 2.0, 1.0                    # s, mm/s, s per stroke
    t = np.arange(int(24 * half / dt)) * dt
    ph = (t / half) % 2.0
    pos = np.where(ph < 1.0, ph, 2.0 - ph) * v0 * half - 1.0          # a triangle, -1 .. +1 mm
    vd = np.where(ph < 1.0, v0, -v0)
    noise = 0.002 * np.random.default_rng(0).standard_normal(t.size)
    d = diagnose(record_from_arrays(t, pos + noise, vd), 20.0)
    assert d.effect == "no_stick_slip" and not d.effects
    assert "does not slide" in d.reason and "steady sliding" not in d.reason
    assert not any(r.get("named") for r in d.evidence.values())
    # each stroke: a rigid ramp from the reversal, then sliding at 0.5 mm
    slides = np.where(ph < 1.0, np.minimum(v0 * ph * half, 0.5), -np.minimum(v0 * (ph - 1.0) * half, 0.5))
    d = diagnose(record_from_arrays(t, slides + noise, vd), 20.0)
    assert d.effect == "no_stick_slip" and "steady sliding over" in d.reason
    assert abs(np.mean(d.sliding["levels_mm"]) - 0.5) < 0.01


def _reciprocating_dwells(v0=4.0, fn=25.0, stroke_s=1.2, dwell_s=0.3, strokes=6, dt=2e-4, every=5):
    """A pin on a spring (static friction 1.0, kinetic 0.7, in units of
    k mm) on a stage that runs +v0 and -v0 in turn with dwells at rest
    between, by its own semi-implicit Euler with exact sticking (the pin
    moves with the stage while the spring force is within the static
    level): (t, spring extension x in mm, stage velocity), sampled every
    ``every`` steps, and the times the stage sets off the other way."""
    w2 = (2 * np.pi * fn) ** 2
    plan = []
    tt = 0.0
    for k in range(strokes):
        plan.append((tt, tt + stroke_s, (-1) ** k * v0))
        tt += stroke_s + dwell_s
    n = int(tt / dt)
    ts = np.arange(n) * dt
    vs = np.zeros(n)
    for a, b, v in plan:
        vs[(ts >= a) & (ts < b)] = v
    x = np.zeros(n)
    p, u, stuck = 0.0, 0.0, True    # the pin's displacement (the spring's extension), its velocity, stuck?
    for i in range(n):
        vd = vs[i]
        if stuck:
            u = vd
            if abs(p) >= 1.0:
                stuck = False
        if not stuck:
            rel = u - vd
            fr = -0.7 * (np.sign(rel) if rel != 0 else -np.sign(p))
            u_new = u + dt * w2 * (-p + fr)
            if rel != 0 and (u_new - vd) * rel <= 0 and abs(p) < 1.0:
                stuck, u_new = True, vd
            u = u_new
        p += dt * u
        x[i] = p
    return ts[::every], x[::every], vs[::every], np.array([a for a, _, _ in plan[1:]])


def test_a_reciprocating_record_given_only_its_speed_is_cut_into_strokes_by_its_force():
    """A reciprocating rig's force record read with --v0 alone (no stage
    position): the force changes side with the drive, so the strokes are
    read from it; each starts within a few samples of the stage's turn (the
    spring starts over to the other side there), and the slips are the same
    as with the stage's velocity recorded (a real record:
    ``test_diagnose_real.test_the_tribometer_without_its_stage_position``)."""
    from lieng.diagnose.segment import drive_from_force, strokes

    t, x, vs, turns = _reciprocating_dwells()
    x = x + 0.003 * np.random.default_rng(3).standard_normal(x.size)
    vd = drive_from_force(x, 4.0)
    st = strokes(vd)
    assert [s.sign for s in st] == [1, -1, 1, -1, 1, -1]
    starts = np.array([t[s.i0] for s in st[1:]])
    assert np.all(np.abs(starts - turns) < 0.01)          # 10 ms: 0.04 mm of the stage's travel at 4 mm/s
    d_inf = diagnose(record_from_arrays(t, x, 4.0), 25.0)
    d_rec = diagnose(record_from_arrays(t, x, vs), 25.0)
    assert any("taken to reverse" in n for n in d_inf.notes)
    assert abs(d_inf.n_cycles - d_rec.n_cycles) <= 2 and d_inf.n_cycles >= 25
    assert d_inf.effect == d_rec.effect == "none"
    # a speed readout without its sign (the dwells at 0): the sign from the force's side
    d_abs = diagnose(record_from_arrays(t, x, np.abs(vs)), 25.0)
    assert any("without its sign" in n and "6 strokes" in n for n in d_abs.notes)
    assert abs(d_abs.n_cycles - d_rec.n_cycles) <= 2 and d_abs.effect == "none"
    # a one-way stick-slip trace about zero (an AC-coupled sensor) crosses zero in every cycle, down in the
    # slips and up in the sticks: no drive that turns
    t, x, vs, _ = _reciprocating_dwells(strokes=1, stroke_s=6.0)
    ac = x - np.convolve(x, np.ones(1200) / 1200, mode="same")
    keep = slice(600, -600)
    assert min(np.mean(ac[keep] > 0.1), np.mean(ac[keep] < -0.1)) > 0.2
    assert drive_from_force(ac[keep], 4.0) is None




@pytest.mark.slow
def test_a_load_modulated_in_time_is_named_and_not_read_as_ageing():
    """A normal force modulated +-20 % at a sixth of the stick-slip rate (an
    exogenous load, not locked to the motion) changes the peaks and the stick
    times together: named as a load variation, and the peaks read per unit
    load show no ageing (the slider has none).  A black-box audit found it
    named on 10 s and lost on 20 s of the same run, with ageing at p = 0."""
    t, x, N = _tilted_track(0.0, mod=(0.2, 0.5), seconds=24.0)
    d = diagnose(record_from_arrays(t, x, 1.5, N, y_is_force=True), 12.0)
    assert d.effect == "load_variation" and d.gain >= 0.3
    assert not d.evidence["static_ageing"]["significant"]


def test_a_clipped_sensor_is_warned_of_and_a_quantised_one_is_not():
    """A force sensor at its limit flattens the peaks where the force would
    go on rising (read as a lower static friction): warned of.  The same
    record read through a coarse ADC (its top level holds about as long as
    the levels under it) is not."""
    from lieng.analysis.synth import synthesize

    r = synthesize("none", 1)
    top = float(np.percentile(r.x, 95))
    d = diagnose(record_from_arrays(r.t, np.minimum(r.x, top), r.v0), r.fn)
    assert any("sits at its largest value" in w for w in d.warnings)
    q = 0.005 * float(np.ptp(r.x))
    d = diagnose(record_from_arrays(r.t, np.round(r.x / q) * q, r.v0), r.fn)
    assert not any("limit" in w for w in d.warnings)


def test_a_stick_slip_whose_period_wanders_has_no_line_at_its_harmonics():
    """A sawtooth whose period wanders by 3 % (an independent NumPy stick-slip,
    no line in it) spreads its h-th harmonic over h times that: without the
    wander the strongest "line" is a smeared harmonic (an unseen multi-contact
    generator's effect-free records were named `triggering` so, 2 of 8); with
    it the line found is off every harmonic, and a real line between them is
    still found."""
    from lieng.diagnose.signals import spectral_line

    rng = np.random.default_rng(3)
    dt, per = 0.005, 1.0 + 0.03 * rng.standard_normal(80)
    edges = np.r_[0.0, np.cumsum(per)]
    t = np.arange(0.0, edges[-1], dt)
    k = np.searchsorted(edges, t, side="right") - 1
    x = (t - edges[k]) / per[k] - 0.5 + 0.002 * rng.standard_normal(t.size)
    f0, jit = 1.0 / per.mean(), per.std() / per.mean()
    off = lambda f: abs(f / f0 - round(f / f0))
    assert off(spectral_line(x, dt, 5.0, f0, by="snr")[0]) < 0.1            # the smeared 6th harmonic
    assert off(spectral_line(x, dt, 5.0, f0, by="snr", jitter=jit)[0]) > 0.2
    f = spectral_line(x + 0.05 * np.sin(2 * np.pi * 10.47 * t), dt, 5.0, f0, by="snr", jitter=jit)[0]
    assert f == pytest.approx(10.47, abs=0.02)


def test_a_stepped_drives_own_stick_slip_at_each_level_is_no_line():
    """A stick-slip under a drive that steps between two levels (an
    independent NumPy sawtooth: 1.0 s cycles at the slow level, 0.3 s at the
    fast one, each slip a 0.05 s half-cosine, no line in it) puts each
    level's harmonics where the record's mean period has none: the strongest
    "line" off the mean period's harmonics is one of them (`school_lab`'s
    effect-free records were named `triggering` so, 2 of 8).  Each level's
    own period is read from the cycles loaded at it (:func:`.evidence.level_combs`)
    and its harmonics are passed over too: the line found is off every
    level's harmonics, and a real line between them is still found."""
    from lieng.diagnose.evidence import level_combs
    from lieng.diagnose.segment import find_cycles, prepare
    from lieng.diagnose.signals import spectral_line

    rng = np.random.default_rng(5)
    dt, slip = 0.005, 0.05
    per = np.r_[np.full(30, 1.0), np.full(100, 0.3)] * (1.0 + 0.002 * rng.standard_normal(130))
    edges = np.r_[0.0, np.cumsum(per)]
    t = np.arange(0.0, edges[-1], dt)
    k = np.searchsorted(edges, t, side="right") - 1
    tau, rise = t - edges[k], per[k] - slip
    x = np.where(tau < rise, tau / rise, 0.5 + 0.5 * np.cos(np.pi * (tau - rise) / slip)) \
        + 0.002 * rng.standard_normal(t.size)
    pr = prepare(record_from_arrays(t, x, 1.0 / rise))
    c = find_cycles(pr, 10.0)
    combs = level_combs(pr, c)
    assert sorted(round(f, 2) for f, _, _ in combs) == [1.0, pytest.approx(3.33, abs=0.02)]
    f0 = 1.0 / float(np.mean(c.periods(pr.t)))
    off = lambda f, fc: abs(f / fc - round(f / fc))
    f = spectral_line(x, dt, 5.0, f0, by="snr")[0]
    assert min(off(f, 1.0), off(f, 1.0 / 0.3)) < 0.05                       # a harmonic of one level
    f = spectral_line(x, dt, 5.0, f0, by="snr", combs=combs)[0]
    assert min(off(f, 1.0), off(f, 1.0 / 0.3)) > 0.05
    f = spectral_line(x + 0.05 * np.sin(2 * np.pi * 11.47 * t), dt, 5.0, f0, by="snr", combs=combs)[0]
    assert f == pytest.approx(11.47, abs=0.02)


def test_a_weak_line_among_a_stick_slips_harmonics_is_refined_where_it_is():
    """The line's frequency refined on the record's own times keeps the weak
    line the spectrum found: a sawtooth (an independent NumPy stick-slip at
    1.2254 Hz, slow rise, fast fall) with a line of 0.2 % of its drop at
    10.418 Hz, between its 8th and 9th harmonics (as an unseen pendulum
    generator's vibrator, where an unweighted fit moved it by 4 bins, and
    the size read there fell from 0.047 to 0.005).  The phase the refined
    frequency accumulates over the record stays under 0.06 of a cycle (0.25
    unweighted; the noise allows about 0.015); and a
    line on a record whose dwells were cut (times with gaps; the spectrum,
    read on the samples, puts it 3 bins off) is still found."""
    from lieng.diagnose.signals import lowpass, refine_line

    rng = np.random.default_rng(3)
    dt, fss, ft = 0.01, 1.2254, 10.418
    t = np.arange(0.0, 17.5, dt)
    ph = (t * fss) % 1.0
    saw = np.where(ph < 0.85, ph / 0.85, (1.0 - ph) / 0.15)
    x = saw + 0.002 * np.sin(2 * np.pi * ft * t) + 0.002 * rng.standard_normal(t.size)
    hp = x - lowpass(x, dt, 4.0)
    T = t[-1] - t[0]
    assert abs(refine_line(hp, t, ft + 0.3 / T) - ft) * T < 0.06
    # four stretches of 20 s with 2 s cut between them
    tc = np.concatenate([np.arange(0.0, 20.0, 0.005) + 22.0 * j for j in range(4)])
    y = np.sin(2 * np.pi * 10.7659 * tc) + 0.05 * rng.standard_normal(tc.size)
    assert abs(refine_line(y, tc, 10.7659 - 3.0 / (tc[-1] - tc[0])) - 10.7659) * (tc[-1] - tc[0]) < 0.02


def test_a_rebound_after_each_arrest_weighs_on_no_model():
    """The metric's slip waveform is the slip's, from its peak to its arrest:
    a rig's second mode that rebounds after every arrest (0.1 D at 6 fn,
    decaying as exp(-2 fn t), added to a Coulomb slider written in plain
    NumPy) is the rig's, which no model of the slider has, and leaves a
    model's held-out error as it was (it would add about 0.03 to it, on
    every model alike, at the window's instants past the arrest)."""
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.extend import Judge
    from lieng.diagnose.segment import find_cycles, prepare

    t, x, _ = _forced_coulomb(0.0)
    fn = 10.0
    pr = prepare(record_from_arrays(t, x, 2.0))
    c = find_cycles(pr, fn)
    base = fit_baseline(pr, c, fn)
    lo, hi = float(pr.t[0]), float(pr.t[-1]) + 1.0
    e0 = Judge(pr, c, fn, lo, hi).error(base)
    D = c.amplitude(pr.x)
    xr = pr.x.copy()
    for i in c.trough_i:
        tt = pr.t[i:] - pr.t[i]
        xr[i:] += 0.1 * D * np.exp(-tt * fn * 2.0) * np.sin(2 * np.pi * 6 * fn * tt)
    pr.x = xr
    e1 = Judge(pr, c, fn, lo, hi).error(base)
    assert math.isfinite(e0) and e0 < 0.05
    assert abs(e1 - e0) < 0.005


def test_an_ageing_limit_keeps_its_clock_across_a_reversal():
    """The slider core starts stuck for ``t0`` seconds already: its static
    limit is then FS (1 + a ln(1 + t0/tau)) from the first step (the stated
    law), so a contact that rested through a reversal and its dwell is not
    released by a spring loaded past FS alone; ``simulate`` and the judged
    predictions from a stroke's start pass the rest since the last arrest
    (``stuck_for``)."""
    from lieng import _core
    from lieng.diagnose.baseline import stuck_for

    n, dt, fs, a, tau = 200, 0.001, 1.0, 0.1, 0.01
    vd = np.full(n, 5.0)

    def first_slip(x0, t0):
        x, v, state, status = _core.core_slider(dt, 8, vd, np.ones(n), 2 * math.pi * 5.0, 0.0, fs,
                                                np.array([0.0, 100.0]), np.array([0.5, 0.5]), 0.0, np.zeros(2),
                                                a, tau, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 4.0, x0, t0)
        assert status == 0
        slip = np.flatnonzero(state == 0)
        return slip[0] if slip.size else None

    assert first_slip(1.2, 0.0) == 1                       # above FS with a fresh contact: at once
    lim = fs * (1 + a * math.log(1 + 10.0 / tau))          # 1.69 after 10 s of rest
    k = first_slip(1.2, 10.0)
    # stuck until x = 1.2 + 5 t reaches the limit, which grows with t0 + t
    t_hit = next(i * dt for i in range(1, n) if 1.2 + 5.0 * i * dt > fs * (1 + a * math.log(1 + (10.0 + i * dt) / tau)))
    assert lim > 1.2 and k is not None and abs(k * dt - t_hit) <= 2 * dt
    t = np.arange(6.0)
    assert stuck_for(t, np.array([1, 1, 1, 1, 1, 1]), 2.0) == 7.0
    assert stuck_for(t, np.array([1, 0, 0, 1, 1, 1]), 2.0) == 2.0
    assert stuck_for(t, np.array([1, 1, 1, 1, 1, 0]), 2.0) == 0.0


def test_a_fold_that_cannot_form_the_extension_holds_nothing_out_for_it(monkeypatch):
    """The gain is judged on the folds whose training part formed the
    extension: a fold with too few sticks to read an ageing law on (no
    candidate at all) is left out, not counted as an extension that gains
    nothing; a fold that formed one no better than the baseline stays in."""
    import lieng.diagnose as dg

    rec = synthesize("static_ageing", 1)
    real = dg._extend
    calls = []

    def first_fold_only(k, base, train, pr, c, fn, st, aux, win, trough):
        res = real(k, base, train, pr, c, fn, st, aux, win, trough)
        calls.append(win)
        # (the first fold trains up to where its held-out part begins)
        return res if win[1] == win[2] else (base, res[2], res[2], [])

    d_all = run(rec)
    e_all = {e["effect"]: e for e in d_all.effects + d_all.detected}["static_ageing"]
    monkeypatch.setattr(dg, "_extend", first_fold_only)
    d_first = run(rec)
    e_first = {e["effect"]: e for e in d_first.effects + d_first.detected}["static_ageing"]
    assert len(calls) >= 2 and sum(w[1] == w[2] for w in calls) == 1
    # the first fold alone: its own held-out errors, not diluted by a fold where the extension is the baseline
    assert e_first["gain"] > 0.3 and e_first["held_out_error_baseline"] != e_all["held_out_error_baseline"]


def test_a_slow_drive_level_beside_a_fast_one_is_a_stroke_and_a_dwell_is_not():
    """A stretch of drive below 5 % of the fast level is a dwell only when it
    stands still: a slow level that moves one way throughout (0.5 mm/s
    beside 20 mm/s, with the scatter of a differentiated position) is part
    of the stroke, a still stage (zero with that scatter) is not."""
    from lieng.diagnose.segment import strokes

    g = np.random.default_rng(0)
    vd = np.r_[np.full(3000, 0.5), np.full(3000, 20.0)] + 0.05 * g.standard_normal(6000)
    st = strokes(vd)
    assert [(s.i0, s.i1, s.sign) for s in st] == [(0, 6000, 1)]
    vd = np.r_[np.full(3000, 20.0), np.zeros(1000), np.full(3000, -20.0)] + 0.05 * g.standard_normal(7000)
    st = strokes(vd)
    assert [(s.sign, s.n) for s in st] == [(1, 3000), (-1, 3000)]


def test_a_record_that_stops_stick_slipping_is_analysed_where_it_stick_slips():
    """A Coulomb slider (plain NumPy) that stick-slips for 12 s and then
    slides steadily for 12 s (a lubricant came in): the steady part, with
    no cycle to predict, is left out and said; the stick-slip part is the
    effect-free slider it is.  A record that stick-slips throughout is not
    cut."""
    from lieng.diagnose.segment import find_cycles, prepare, stick_slip_span

    t, x, _ = _forced_coulomb(0.0)
    g = np.random.default_rng(1)
    steady = 0.5 + 0.002 * g.standard_normal(t.size)
    tt = np.r_[t, t[-1] + t[1] + t]
    d = diagnose(record_from_arrays(tt, np.r_[x, steady], 2.0), 10.0)
    assert d.effect == "none"
    said = [n for n in d.notes if n.startswith("no stick-slip in ")]
    assert len(said) == 1 and "drive 2 mm/s" in said[0]
    pr = prepare(record_from_arrays(t, x, 2.0))
    assert stick_slip_span(pr, find_cycles(pr, 10.0)) is None
    # a part where x oscillates but the cycle finder reads no cycle (a slow level's small swings) is no
    # steady sliding: not cut
    wavy = 0.5 + 0.2 * np.sin(2 * np.pi * 1.3 * t)
    pr = prepare(record_from_arrays(tt, np.r_[x, wavy], 2.0))
    assert stick_slip_span(pr, find_cycles(pr, 10.0)) is None


def test_a_stepped_drive_whose_one_level_slides_steadily_is_analysed_on_its_stick_slip():
    """A Coulomb slider (plain NumPy) that stick-slips for 6 s, slides
    steadily for 8 s (a drive level at which the rig is on its other
    attractor), stick-slips for 12 s, slides steadily for 8 s and
    stick-slips for 4 s: the record is analysed on its longest stick-slip
    part, from its first arrest, and the steady stretches and the cycles
    left out are said (a baseline started in stick stick-slips through a
    steady stretch: two generators' effect-free stepped-drive records were
    `unexplained` for it).  Two runs of cycles without a steady stretch
    between them are not cut."""
    from lieng.diagnose.segment import find_cycles, prepare, stick_slip_span

    t, x, _ = _forced_coulomb(0.0, seconds=12.0)
    g = np.random.default_rng(2)
    dt = t[1] - t[0]
    steady = lambda sec: 0.5 + 0.002 * g.standard_normal(int(sec / dt))
    xs = np.r_[x[:int(6 / dt)], steady(8), x, steady(8), x[:int(4 / dt)]]
    tt = np.arange(xs.size) * dt
    pr = prepare(record_from_arrays(tt, xs, 2.0))
    c = find_cycles(pr, 10.0)
    span = stick_slip_span(pr, c)
    assert span is not None
    a, b, said = span
    assert 14.0 <= tt[a] < 14.6 and 25.8 < tt[b - 1] <= 26.1
    assert a in set(c.trough_i.tolist())
    assert said.count(" s (x at ") == 2 and "cycles outside its longest stick-slip part left out" in said
    # the same runs back to back (no steady stretch): one run, nothing cut
    pr = prepare(record_from_arrays(np.arange(2 * t.size) * dt, np.r_[x, x], 2.0))
    assert stick_slip_span(pr, find_cycles(pr, 10.0)) is None


def test_a_mains_frequency_that_is_a_harmonic_of_the_record_is_its_own():
    """A stick-slip at 8.6 Hz has its 7th harmonic at 60.2 Hz, within the
    mains grid's tolerance, and a reciprocating rig's 10 Hz square wave its
    5th at 50 Hz: lines with their series beside them, no stronger than a
    sawtooth's harmonic, which are the record's own (a black-box audit's
    clean records had them 'removed' as hum).  Hum of 3 % of the drop added
    at 60 Hz to a stick-slip at 11.3 Hz (no harmonic near) is still found."""
    from lieng.diagnose.read import _hum_lines

    dt = 1.0 / 2000.0
    t = np.arange(0.0, 20.0, dt)
    saw = 2 * ((t * 60.2 / 7) % 1.0) - 1.0
    assert _hum_lines(saw, dt) == []
    square = np.sign(np.sin(2 * np.pi * 10.0 * t))
    assert _hum_lines(square, dt) == []
    slow = 2 * ((t * 2.0) % 1.0) - 1.0          # a 2 Hz stick-slip: its 25th-90th harmonics at 50-180 Hz
    assert _hum_lines(slow, dt) == []
    saw = 2 * ((t * 11.3) % 1.0) - 1.0
    lines = _hum_lines(saw + 0.06 * np.sin(2 * np.pi * 60.0 * t + 0.3), dt)
    assert len(lines) == 1 and abs(lines[0][2][0] - 60.0) < 0.05


def test_a_stick_slip_at_a_mains_frequency_is_kept_and_the_hum_beside_it_fitted_clean():
    """A short record (0.45 s: a bin of 2.2 Hz) stick-slipping at 50.7 Hz,
    within half a bin of 50 Hz, with 60 Hz hum of 3 % of the drop: the
    50.7 Hz line is the stick-slip's fundamental (most of the record's
    variance, and the amplitude a sawtooth rising at the drive's speed has at
    that frequency, vd / (pi f)), so it is kept; the hum, 4.4 bins from it, is
    removed at 60 Hz with its amplitude (an unweighted fit took 60.41 Hz,
    pulled by the fundamental's leakage, and left a beat in every stick)."""
    from lieng.diagnose import record_from_arrays
    from lieng.diagnose.read import _hum_lines

    dt = 1.0 / 10200.0
    t = np.arange(0.0, 0.4536, dt)
    f0, vd = 50.72, 0.18                       # mm/s
    drop = vd / f0                              # a sawtooth rising at vd all period long
    saw = drop * ((t * f0) % 1.0)
    hum = 0.03 * drop * np.sin(2 * np.pi * 60.0 * t + 1.1)
    assert _hum_lines(saw - saw.mean(), dt, vd) == []
    rec = record_from_arrays(t, saw + hum, v0=vd)
    removed = [n for n in rec.notes if "mains hum" in n]
    assert len(removed) == 1 and abs(float(removed[0].split()[3]) - 60.0) < 0.1, rec.notes
    resid = rec.x - saw
    resid -= resid.mean()
    assert 2 * abs(np.mean(resid * np.exp(-2j * np.pi * 60.0 * t))) < 0.1 * 0.03 * drop


def test_hum_on_times_written_to_few_digits_is_removed_on_the_records_own_clock():
    """A record whose times are written to five decimals (a true interval of
    0.0017268 s written as 0.00172 and 0.00173 s alternately, as a logger's
    text export rounds them), 50 Hz hum of 2 % of the drop on a sawtooth of
    11.7 s: the grid is the record's mean interval, so the hum is found at
    50.00 Hz and what is left of it is under a tenth.  On the first
    interval's grid (0.00173 s, 0.18 % long) it was found at 49.91 Hz and
    subtracted on the written times, where it is at 50.00 Hz: 0.43 cycles
    apart over the record, it left more hum than there was (the twin
    branch's statistic read through x'' at six times fn)."""
    from lieng.diagnose import record_from_arrays

    dt = 0.0017268499
    t = np.round(np.arange(6804) * dt, 5)
    saw = 2.0 * ((np.arange(6804) * dt * 2.3) % 1.0)
    hum = 0.04 * np.sin(2 * np.pi * 50.0 * np.arange(6804) * dt + 0.7)
    assert set(np.round(np.diff(t), 6)) == {0.00172, 0.00173}
    rec = record_from_arrays(t, saw + hum, v0=2.0 * 2.3)       # (the sawtooth's rise: 2.0 a period at 2.3 Hz)
    removed = [n for n in rec.notes if "mains hum" in n]
    assert len(removed) == 1 and abs(float(removed[0].split()[3]) - 50.0) < 0.01, rec.notes
    assert rec.dt == pytest.approx(dt, rel=1e-5)
    resid = rec.x - saw
    resid -= resid.mean()
    tt = np.arange(6804) * dt
    assert 2 * abs(np.mean(resid * np.exp(-2j * np.pi * 50.0 * tt))) < 0.1 * 0.04


def test_a_line_near_the_other_mains_family_is_the_records_own():
    """A grid runs at 50 Hz or at 60 Hz, never both: on a record with 60 Hz
    hum (and its third harmonic), a mode of the rig ringing in the normal
    channel at 100.2 Hz sits within the tolerance of a 50 Hz harmonic but
    is the record's own; it is kept, and said."""
    from lieng.diagnose import record_from_arrays

    dt = 1.0 / 2000.0
    t = np.arange(0.0, 20.0, dt)
    saw = 2 * ((t * 11.3) % 1.0) - 1.0
    hum = 0.06 * np.sin(2 * np.pi * 60.0 * t + 0.3) + 0.03 * np.sin(2 * np.pi * 180.0 * t)
    mode = 0.02 * np.sin(2 * np.pi * 100.2 * t)
    y = 1.0 + 0.1 * saw + 0.5 * hum + mode
    rec = record_from_arrays(t, saw + hum, v0=1.0, y=y)
    assert np.max(np.abs(rec.x - saw)) < 0.01
    resid = rec.y - 1.0 - 0.1 * saw
    amp = 2 * abs(np.mean(resid * np.exp(-2j * np.pi * 100.2 * t)))
    assert abs(amp - 0.02) < 0.003
    assert 2 * abs(np.mean(resid * np.exp(-2j * np.pi * 60.0 * t))) < 0.003
    assert any("read as the record's own" in n and "100.2" in n for n in rec.notes)


def test_a_line_at_a_mains_frequency_is_read_unless_the_records_hum_was_there():
    """A line at a mains frequency is not always hum (a shaker, a motor run
    off the grid): the triggering line is read there unless the record's
    hum was removed there (``exclude``)."""
    from lieng.diagnose.signals import spectral_line

    dt = 1.0 / 2000.0
    t = np.arange(0.0, 4.0, dt)
    g = np.random.default_rng(3)
    x = 0.01 * np.sin(2 * np.pi * 100.1 * t) + 0.004 * np.sin(2 * np.pi * 163.0 * t) + 1e-3 * g.standard_normal(t.size)
    assert spectral_line(x, dt, 60.0)[0] == pytest.approx(100.1, abs=0.3)
    assert spectral_line(x, dt, 60.0, exclude=(100.0,))[0] == pytest.approx(163.0, abs=0.3)


def test_mains_families_tied_go_to_the_one_whose_line_sits_on_its_harmonic():
    """One line of each family, neither a fundamental (60 Hz hum seen only
    at 180.00 Hz in x, a shaker at 99.83 Hz in the normal channel, within
    the tolerance of 50 Hz's second harmonic): the grid holds its
    frequency, so the record's hum is the family whose line sits on its
    exact harmonic; the 99.83 Hz line is kept, and said."""
    dt = 1.0 / 2000.0
    t = np.arange(0.0, 20.0, dt)
    saw = 2 * ((t * 11.3) % 1.0) - 1.0
    shaker = 0.02 * np.sin(2 * np.pi * 99.83 * t)
    rec = record_from_arrays(t, saw + 0.03 * np.sin(2 * np.pi * 180.0 * t + 0.4), v0=1.0,
                             y=1.0 + 0.1 * saw + shaker)
    assert np.max(np.abs(rec.x - saw)) < 0.01
    resid = rec.y - 1.0 - 0.1 * saw
    assert abs(2 * abs(np.mean(resid * np.exp(-2j * np.pi * 99.83 * t))) - 0.02) < 0.003
    assert any("read as the record's own" in n and "99.83" in n for n in rec.notes)
    assert rec.hum_hz == pytest.approx((180.0,), abs=0.05)


def test_the_strokes_own_pattern_of_sticks_is_no_drive_modulation():
    """On a reciprocating record the sticks repeat their pattern in every
    stroke (the first after a reversal reloads the spring from the other
    side): the drive test reads the stick series less its mean at each place
    in the stroke, so the pattern, periodic at the stroke's frequency, is
    gone and a modulation of the drive across the strokes is kept."""
    from types import SimpleNamespace

    from lieng.diagnose.evidence import _less_stroke_pattern

    nst, per = 12, 10
    stroke = np.repeat(np.arange(nst), per)
    k = np.arange(stroke.size)
    c = SimpleNamespace(stroke=stroke)
    pattern = np.tile(np.linspace(0.2, 0.0, per), nst)            # each stroke's own course
    drive = 0.05 * np.sin(2 * np.pi * np.arange(stroke.size) / 37.0)   # across the strokes
    r = 1.0 + pattern + drive
    out = _less_stroke_pattern(r, k, c)
    place = k % per
    means = [float(np.mean(out[place == q])) for q in range(per)]
    assert np.ptp(means) < 0.02                                    # the pattern is gone (0.2 before)
    assert np.corrcoef(out, drive)[0, 1] > 0.95                    # the drive's modulation is kept
    few = SimpleNamespace(stroke=np.repeat(np.arange(3), per))     # three strokes: left as it is
    assert np.array_equal(_less_stroke_pattern(r[:30], k[:30], few), r[:30])


def test_the_slips_smoothing_is_scipys_savgol_filter():
    """The reverse construction's cubic Savitzky-Golay (value, x', x'' at
    once, kernels computed once per window) is scipy's
    ``savgol_filter(mode="interp")``, edges included, to rounding."""
    from scipy.signal import savgol_filter

    from lieng.diagnose.segment import savgol3

    g = np.random.default_rng(5)
    for w, n in ((7, 7), (9, 40), (21, 100), (65, 300)):
        x = np.cumsum(g.standard_normal(n))
        for d, y in enumerate(savgol3(x, w, 1e-3)):
            ref = savgol_filter(x, w, 3, deriv=d, delta=1e-3, mode="interp")
            assert np.allclose(y, ref, rtol=1e-9, atol=1e-9 * np.max(np.abs(ref)))


def test_a_pin_on_disc_angle_column_asks_for_the_sliding_speed(tmp_path):
    """A pin-on-disc's angle column (degrees) is not a linear drive and the
    record has no track radius: without --v0 the command asks for the
    sliding speed naming the column; with it, it says the angle is not read
    (it had been passed over without a word: found by the black-box audit)."""
    from lieng.diagnose import read_record
    from lieng.errors import LiengInputError

    t, x, _ = _forced_coulomb(0.0)
    p = tmp_path / "pod.csv"
    p.write_text("Time [s],x [mm],Angle [deg]\n" + "".join(f"{a:.6f},{b:.6f},{2.865 * a:.5f}\n" for a, b in zip(t, x)))
    with pytest.raises(LiengInputError, match="column Angle is an angle.*--v0"):
        read_record(p)
    rec = read_record(p, v0=2.0)
    assert any("Angle" in s and "not read" in s for s in rec.notes), rec.notes


def test_a_slider_and_a_stage_position_give_the_spring_extension(tmp_path):
    """A laser on the slider and an encoder on the stage, and no force
    column: the spring's extension is the stage's position less the
    slider's, the drive the stage's (the record had been refused for want
    of an x or F column: black-box audit)."""
    from lieng.diagnose import read_record

    t, x, _ = _forced_coulomb(0.0)
    stage = 2.0 * t
    p = tmp_path / "laser.csv"
    p.write_text("Time [s],Slider position [um],Stage position [mm]\n"
                 + "".join(f"{a:.6f},{1e3 * (c - b):.4f},{c:.7f}\n" for a, b, c in zip(t, x, stage)))
    rec = read_record(p)
    assert np.allclose(rec.x, x, atol=2e-6)
    mid = slice(rec.t.size // 20, -rec.t.size // 20)
    assert abs(np.median(rec.vd[mid]) / 2.0 - 1.0) < 0.01
    assert any("Slider position" in s and "extension" in s for s in rec.notes), rec.notes


def test_a_cam_load_raises_the_peaks_without_ageing():
    """A Coulomb slider (0.5 / 0.4; plain NumPy, semi-implicit Euler at 40 kHz) on a
    cam: the normal force follows the drive's position, N = 1 + 0.2 sin(2 pi
    travel / 8 mm), recorded.  The peaks and the sticks grow and shrink with
    it together, which is no ageing: read per unit of the load not locked to
    the stick-slip within its cycles, the peaks do not grow with the stick
    time (the audit's cam-load control had its slow load counted as locked
    to the motion, since x's peaks follow it, and `static_ageing` detected
    at +0.61 of the drop)."""
    from lieng.diagnose.evidence import statistics
    from lieng.diagnose.segment import find_cycles, prepare

    cam = lambda t: 1.0 + 0.2 * np.sin(2 * np.pi * 2.0 * t / 8.0)
    t, x, _ = _forced_coulomb(0.0, fs=0.5, fk=0.4, seconds=24.0, seed=4, load_of=cam)
    n = 10.0 * cam(t) + 0.01 * np.random.default_rng(4).standard_normal(t.size)
    rec = record_from_arrays(t, x, 2.0, y=n, y_is_force=True)
    pr = prepare(rec)
    c = find_cycles(pr, 10.0)
    st, se, _ = statistics(pr, c, 10.0, y=pr.y, y_is_force=True)
    assert abs(st["static_ageing"]) < 0.05 + 2 * se["static_ageing"], (st["static_ageing"], se["static_ageing"])


@pytest.mark.parametrize("load_x", [0.5, -0.5])
def test_without_fn_a_load_that_follows_the_slider_is_not_put_into_fn(load_x):
    """A Coulomb slider (plain NumPy) whose normal force follows its own
    displacement, N = 1 + load_x (x - 0.8), recorded, no --fn: its slips
    swing at fn sqrt(1 - 0.6 load_x) (8.4 or 11.4 Hz for fn 10), and a
    baseline at constant load read fn there (the old reading: 8.38 and
    11.44 Hz, and no gain for the load, whose extension then counted its
    effect twice).  Read with the slider's friction following the recorded
    force, fn is the true one within 5 % (10.03 and 10.04 Hz), and the load is named
    with a gain."""
    t, x, _, n = _forced_coulomb(0.0, seconds=12.0, load_x=load_x)
    rec = record_from_arrays(t, x, 2.0, y=10.0 * n + 0.01 * np.random.default_rng(1).standard_normal(t.size),
                             y_is_force=True)
    d = diagnose(rec)
    assert d.fn_source.startswith("estimated")
    assert abs(d.fn / 10.0 - 1.0) < 0.05, d.fn
    assert d.effect == "load_variation" and d.gain >= 0.3, (d.effect, d.gain)


def test_the_report_says_why_a_candidates_evidence_is_withheld(tmp_path):
    """Without --fn the twin evidence is withheld (its reading cannot be told
    from an fn error): the report's evidence table says so and why, not "not
    applicable" (a NumPy Coulomb slider)."""
    from lieng.diagnose.report import write_outputs

    t, x, _ = _forced_coulomb(0.0)
    d = diagnose(record_from_arrays(t, x, 2.0))
    assert "withheld" in d.evidence["twin_branch"]
    write_outputs(d, tmp_path, "slider", plots=False)
    row = next(line for line in (tmp_path / "report.md").read_text().splitlines() if line.startswith("| twin_branch"))
    assert "withheld: without --fn" in row, row


def _eyring_creep(fn=10.0, v0=2.0, fs=1.0, fk=0.6, a=0.7, w=0.03, seconds=12.0, seed=0, step=None):
    """A Coulomb slider that creeps in stick as a thermally activated
    contact does: the slider's creep velocity a v0 exp(-(1 - x / fs) / w), so
    the creep gathers in the last few per cent of the rise (an exponential
    law, not the baseline's power of x); slip at x = fs; semi-implicit Euler
    at 40 kHz (plain NumPy, no lieng code), sampled at 2 kHz.  ``step``
    (period, factor): the drive steps between v0 and factor v0 every period
    seconds (then the drive is returned too)."""
    g = np.random.default_rng(seed)
    wn, h = 2 * math.pi * fn, 1.0 / 40000
    n = int(seconds / h)
    x, xd, stick = 0.3, v0, True
    out, drive = np.empty(n // 20), np.empty(n // 20)
    for i in range(n):
        vd = v0 if step is None or int(i * h / step[0]) % 2 == 0 else v0 * step[1]
        if stick:
            x += h * vd * (1.0 - a * math.exp(-(1.0 - x / fs) / w))
            if x >= fs:
                stick = False
        else:
            xd += h * wn * wn * (fk - x)
            x += h * xd
            if xd >= vd:
                stick, xd = True, vd
        if i % 20 == 0:
            out[i // 20], drive[i // 20] = x, vd
    tt, xs = np.arange(out.size) * 20 * h, out + 0.002 * g.standard_normal(out.size)
    return (tt, xs) if step is None else (tt, xs, drive)


def test_a_creep_gathered_near_the_static_limit_is_read_with_its_shape():
    """A stick whose creep gathers in the last few per cent of the rise
    (an Eyring-type slider, exponential in the force) after slips that drop
    x to 0.6 of the limit: the baseline's stick law (ch. 2.3.1.1's
    1 - c0 - c1 r**m, m read from the record) lasts as long as the record's
    sticks, and the baseline's one-cycle-ahead stick times are right to 1.5 %
    of the period.  (r**4, scaled as if the slips dropped x near zero,
    spread the creep over the whole rise: sticks 31 % too long, stick times
    26 % of the period long.)"""
    from lieng.diagnose.baseline import fit_baseline, pr_like, simulate
    from lieng.diagnose.extend import Judge
    from lieng.diagnose.segment import find_cycles, prepare
    t, x = _eyring_creep(fk=0.8, a=0.85, w=0.02)
    pr = prepare(record_from_arrays(t, x, 2.0))
    c = find_cycles(pr, 10.0)
    p = fit_baseline(pr, c, 10.0)
    assert p.creep1 > 0 and p.creep_m > 4

    def stick(xx):
        cc = find_cycles(pr_like(pr, xx), 10.0, speeds=False)
        k = np.flatnonzero(cc.next_ok)
        return float(np.median(pr.t[cc.peak_i[k + 1]] - pr.t[cc.trough_i[k]]))

    xs = simulate(pr, p, 10.0)[0]
    assert abs(stick(xs) / stick(pr.x) - 1.0) < 0.03
    J = Judge(pr, c, 10.0, 0.0, float(pr.t[-1]))
    dc = J.vector(p)[0]
    assert abs(float(np.mean(dc[:, 0]))) < 0.015


def test_a_creeping_stick_through_holds_lasts_the_records_travel():
    """The creep's c1 is set so that a stick needs the drive travel the
    record's sticks take (per unit of the limit): under a drive that holds
    for 1.5 s every 1.5 s (the Eyring slider above) the baseline's sticks
    take the record's travel within 2 % (measured 0.6 %).  (Matched on the
    median stick *time* at the mean drive, the holds inside some sticks
    counted as travel: 2.9 % off.)"""
    from lieng.diagnose.baseline import fit_baseline, pr_like, simulate
    from lieng.diagnose.segment import find_cycles, prepare, travel
    t, x, vd = _eyring_creep(v0=1.0, fk=0.8, a=0.85, w=0.02, seconds=24.0, step=(1.5, 0.0))
    pr = prepare(record_from_arrays(t, x, vd))
    c = find_cycles(pr, 10.0)
    p = fit_baseline(pr, c, 10.0)
    assert p.creep1 > 0
    track = travel(pr.vd, pr.dt)

    def need(xx):
        cc = find_cycles(pr_like(pr, xx), 10.0, speeds=False)
        k = np.flatnonzero(cc.next_ok)
        return float(np.median((track[cc.peak_i[k + 1]] - track[cc.trough_i[k]]) / xx[cc.peak_i[k + 1]]))

    assert abs(need(simulate(pr, p, 10.0)[0]) / need(pr.x) - 1.0) < 0.02


def _coulomb_baseline(fn=10.0):
    """The unmodulated Coulomb slider of :func:`_forced_coulomb` (plain
    NumPy), prepared: (record, cycles, fitted baseline, drop, fn)."""
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.segment import find_cycles, prepare
    t, x, _ = _forced_coulomb(0.0, fn=fn)
    pr = prepare(record_from_arrays(t, x, 2.0))
    c = find_cycles(pr, fn)
    return pr, c, fit_baseline(pr, c, fn), c.amplitude(pr.x), fn


def test_refining_an_extension_returns_its_own_error_and_never_loses_the_candidate(monkeypatch):
    """``extend.refine`` scales the extension's term on the training error,
    levelling each scaled model again, and keeps the candidate when no
    factor beats it: the error it returns is the returned model's, and
    never above the candidate's own, however the levelling lands.  (It
    compared the factors with the candidate levelled once more, and that
    levelling's bisection can end elsewhere: on `lugre` load 7 a coupled
    load whose training error was 0.0136 came back with 0.0188, the
    baseline's, and was dropped.)  Here every levelling lands 0.05 D high."""
    import lieng.diagnose.extend as ext_mod
    pr, c, base, D, fn = _coulomb_baseline()
    monkeypatch.setattr(ext_mod, "_fit_level", lambda pr_, q, *a, **k: q.copy(fg=q.fg + 0.05 * D))
    cand = base.copy(delta=0.01 * D)
    J = ext_mod.Judge(pr, c, fn, float(pr.t[0]), float(pr.t[-1]) + 1.0)
    p, e = ext_mod.refine("twin_branch", cand, base, J, pr, fn, np.ones(pr.t.size, bool), 0.0)
    assert e == pytest.approx(J.error(p), rel=1e-12)
    assert e <= J.error(cand)


def test_the_level_fit_lands_on_the_records_trough_and_stays_there():
    """The characteristic's level is moved until the simulated mean trough
    is the record's (a Coulomb slider, plain NumPy): from 10 % of the drop
    off either way it lands within 0.05 % of the drop in five simulations,
    and levelled again it does not move (0.05 %).  (The bisection it
    replaces ended at the midpoint of its last bracket, a level it had not
    simulated: 0.3-0.5 % of the drop off, and 0.4 % away when levelled
    again: a candidate came back with another model's error.)"""
    from lieng.diagnose.baseline import pr_like, simulate
    from lieng.diagnose.extend import _fit_level
    from lieng.diagnose.segment import find_cycles
    pr, c, base, D, fn = _coulomb_baseline()
    target = float(np.mean(pr.x[c.trough_i]))
    every = np.ones(pr.t.size, bool)

    def trough(q):
        xs = simulate(pr, q, fn)[0]
        cc = find_cycles(pr_like(pr, xs), fn, speeds=False)
        return float(np.mean(xs[cc.trough_i]))

    for shift in (0.1, -0.1, 0.03):
        q = _fit_level(pr, base.copy(fg=base.fg + shift * D), fn, target, every)
        assert abs(trough(q) - target) < 5e-4 * D, shift
        again = _fit_level(pr, q.copy(), fn, target, every)
        assert abs(float(np.mean(again.fg - q.fg))) < 5e-4 * D, shift


@pytest.mark.parametrize("load_x", [0.4, -0.4])
def test_a_load_locked_to_the_motion_follows_the_models_own_motion(load_x):
    """A recorded normal force with a part locked to the slider's x and a
    slow course of its own, N = (1 + 0.08 sin(2 pi 0.23 t)) (1 + load_x
    (x - 0.8)) (a Coulomb slider, plain NumPy): the load extension whose
    locked part follows the model's own x and whose rest is played back in
    time predicts the cycles one ahead within 1 % (0.3-0.7 %); played back
    in time, the locked part arrests or prolongs a model's slip that runs
    early or late (1.1-10.5 %), and a coupling to x alone misses the slow
    course (5-7 %)."""
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.extend import Judge, candidates
    from lieng.diagnose.segment import find_cycles, prepare
    from lieng.diagnose.signals import lowpass, y_on_motion
    fn = 10.0
    t, x, _, n = _forced_coulomb(0.0, seconds=16.0, load_x=load_x,
                                 load_of=lambda s: 1.0 + 0.08 * math.sin(2 * math.pi * 0.23 * s))
    y = 10.0 * n + 0.01 * np.random.default_rng(1).standard_normal(t.size)
    pr = prepare(record_from_arrays(t, x, 2.0, y=y, y_is_force=True))
    c = find_cycles(pr, fn)
    base = fit_baseline(pr, c, fn)
    base.y_c = y_on_motion(pr.x, c.v, pr.y)
    ylow = lowpass(pr.y, pr.dt, 4 * fn)
    whole = (float(pr.t[0]), float(pr.t[-1]) + 1.0)
    J = Judge(pr, c, fn, *whole, ylow)
    cands = candidates("load_variation", base, pr, c, fn, {"load_variation": 0.2, "load_variation_raw": 0.2},
                       {"D": c.amplitude(pr.x), "ylow": ylow, "y_is_force": True}, whole)
    locked = min(J.error(p) for p in cands if p.load_lock and p.load_k)
    played = min(J.error(p) for p in cands if not p.load_lock and not p.load_kx)
    coupled = min(J.error(p) for p in cands if p.load_kx and not p.load_k)
    assert locked < 0.01 and locked < 0.5 * min(played, coupled), (locked, played, coupled)


@pytest.mark.parametrize("load_x", [-0.6, -0.7, -0.8])
def test_a_load_that_accounts_for_the_twin_reading_names_no_twin(load_x):
    """A Coulomb slider (plain NumPy) whose load falls as the spring
    stretches, N = 1 + load_x (x - 0.8), recorded with an affine normal
    reading: the friction falls through each slip's first half and rises
    through its second with the load, so the reverse construction reads a
    twin branch (0.24-0.37 of the drop).  The load's fitted extension
    reproduces that reading (it leaves 0.001-0.012 of the drop) and the
    twin's leaves 0.08-0.14 of the load's, above its margin: only the load
    is named.  (Both were named before, the twin second, neither
    significant beyond the other at the fn band.  At load_x = -0.5 the
    twin's extension leaves 0.050 of the load's, at the margin itself: not
    a case to test.)"""
    t, x, _, N = _forced_coulomb(0.0, load_x=load_x)
    N = N + 0.002 * np.random.default_rng(1).standard_normal(N.size)
    d = diagnose(record_from_arrays(t, x, 2.0, y=3.0 + 0.5 * N), 10.0)
    assert d.effect == "load_variation" and d.gain >= 0.5, (d.effect, d.gain)
    assert not d.evidence["twin_branch"]["named"], d.evidence["twin_branch"]


@pytest.mark.slow
def test_without_fn_a_load_along_the_record_is_read_and_a_crosstalk_is_not():
    """Without --fn (fn from the slips, +- 15 %) the load read from a normal
    reading is tested at the least favourable fn within that: a Coulomb
    slider (plain NumPy) whose load follows a course of its own in time,
    N = 1 + 0.15 sin(2 pi 0.23 t), read as y = 3 + 0.5 N, is named a load
    variation (an fn error moves its reading by 0.001 of the drop: the
    course does not follow x''); a normal reading that picks up x (crosstalk,
    y = 3 + 0.3 x, the load constant) is not (an fn error moves its reading
    by 0.36 of the drop).  Before, both were withheld without --fn."""
    t, x, _ = _forced_coulomb(0.0, seconds=16.0, load_of=lambda s: 1.0 + 0.15 * math.sin(2 * math.pi * 0.23 * s))
    N = 1.0 + 0.15 * np.sin(2 * math.pi * 0.23 * t)
    y = 3.0 + 0.5 * N + 0.002 * np.random.default_rng(1).standard_normal(t.size)
    d = diagnose(record_from_arrays(t, x, 2.0, y=y))
    assert d.effect == "load_variation" and d.gain >= 0.5, (d.effect, d.gain, d.evidence["load_variation"])
    assert "twin_branch" in d.evidence and d.evidence["twin_branch"].get("withheld")
    t, x, _ = _forced_coulomb(0.0, seconds=16.0)
    y = 3.0 + 0.3 * x + 0.002 * np.random.default_rng(2).standard_normal(x.size)
    d = diagnose(record_from_arrays(t, x, 2.0, y=y))
    assert not d.evidence["load_variation"]["named"] and d.effect == "none", (d.effect, d.evidence["load_variation"])


def test_slips_faster_than_the_given_fn_withhold_the_twin():
    """A load that falls as the spring stretches (N = 1 - (x - 0.8), a plain
    NumPy Coulomb slider) stiffens the slider in slip: its slips last as
    long as a baseline's at 1.27 fn.  A reverse construction at too low an
    fn parts the branches as a twin branch does, so the twin evidence is
    withheld, saying why, as it is for slips whose arcs swing faster; the
    load is named.  (Before, the twin was named too, size 0.37.)"""
    t, x, _, N = _forced_coulomb(0.0, load_x=-1.0)
    N = N + 0.002 * np.random.default_rng(1).standard_normal(N.size)
    d = diagnose(record_from_arrays(t, x, 2.0, y=3.0 + 0.5 * N), 10.0)
    assert d.effect == "load_variation"
    assert "above fn" in (d.evidence["twin_branch"].get("withheld") or ""), d.evidence["twin_branch"]


@pytest.mark.parametrize("r", [2.3, 3.7, 5.1])
def test_a_normal_mode_the_slips_ring_is_not_a_triggering(r):
    """A lever's normal mode that each slip rings and that dies away in the
    stick (a NumPy Coulomb slider whose friction drives it, damping ratio
    0.1, N peak-to-peak 12-15 %: :func:`_forced_coulomb`'s ``mode``) puts lines in
    the normal channel that the motion drives, not a forcing of the load:
    recorded as a normal reading, no triggering is named.  (Read as a line
    wherever it was strongest, it was named at all three mode frequencies,
    with held-out gains 0.03-0.13: a forcing from outside shows in the
    sticks as in the slips, and this one does not.)"""
    t, x, _, N = _forced_coulomb(0.0, r=r, mode=(0.1, 0.1))
    N = N + 0.002 * np.random.default_rng(1).standard_normal(N.size)
    d = diagnose(record_from_arrays(t, x, 2.0, y=3.0 + 0.5 * N), 10.0)
    assert not d.evidence["triggering"]["named"], d.evidence["triggering"]
    assert d.effect != "triggering"


def test_an_encoder_that_counts_back_in_a_hold_is_no_reversal():
    """A one-way drive with holds, its position recorded by an encoder
    (0.5 um counts) that counts one back and forth while the servo holds:
    one stroke, not a reciprocating record whose "backward strokes" are a
    count long (a lever tribometer's ageing record was cut into 8 strokes,
    and its peak growth of 0.17 of the drop read as 0.02).  A drive that
    reverses by 3 mm is still cut at each reversal."""
    from lieng.diagnose.read import _drive_from_position
    from lieng.diagnose.segment import strokes

    dt = 0.002
    t = np.arange(0.0, 36.0, dt)
    hold = (t % 6.0) > 4.0
    pos = np.cumsum(np.where(hold, 0.0, 0.25 * dt))                      # mm, 0.25 mm/s between holds
    q = 0.0005
    counts = np.round(pos / q)
    rng = np.random.default_rng(3)
    for h0 in np.flatnonzero(np.diff(hold.astype(int)) == 1):            # a count back, twice in each hold
        for a in h0 + rng.integers(50, 900, 2):
            counts[a:a + rng.integers(4, 12)] -= 1
    st = strokes(_drive_from_position(counts * q, dt, []))
    assert len(st) == 1 and st[0].sign == 1, [(s.i0, s.i1, s.sign) for s in st]
    back = 3.0 - np.abs(3.0 - (np.arange(0.0, 48.0, dt) * 0.5) % 6.0)     # 0..3 mm and back, 4 times
    st = strokes(_drive_from_position(np.round(back / q) * q, dt, []))
    assert [s.sign for s in st] == [1, -1] * 4, [(s.i0, s.i1, s.sign) for s in st]


def test_the_resonance_a_record_is_taken_through_is_the_second_order_ramp_response():
    """``signals.resonance`` on a ramp that starts at a sample (exact for its
    input linear between samples) against the closed form of
    w**2 / (s**2 + 2 zeta w s + w**2)'s response to t from rest:
    t - 2 zeta / w + exp(-zeta w t) (2 zeta / w cos(wd t) + (2 zeta**2 - 1) / wd sin(wd t))."""
    from lieng.diagnose.signals import resonance

    dt, f, z = 1e-3, 40.0, 0.05
    t = np.arange(3000) * dt
    x = np.maximum(t - 0.1, 0.0)
    w = 2 * math.pi * f
    wd = w * math.sqrt(1 - z * z)
    tau = np.maximum(t - 0.1, 0.0)
    exact = tau - 2 * z / w + np.exp(-z * w * tau) * (2 * z / w * np.cos(wd * tau)
                                                      + (2 * z * z - 1) / wd * np.sin(wd * tau))
    y = resonance(x + 3.0, dt, f, z) - 3.0
    assert np.max(np.abs(y - exact)) < 1e-9


def test_a_sensor_that_rings_after_each_arrest_is_modelled_not_read_as_a_twin_branch():
    """A Coulomb slider recorded through a sensor whose own resonance is at
    4 fn (damping ratio 0.05): each arrest and each onset ring it, and x''
    (the reverse construction's) sees that ringing 16 times over, which a
    1-DoF baseline's replicates do not have (its twin statistic was 0.44 of
    the drop, p = 0, named with gain 0.23 before the resonance was
    modelled).  The resonance is read off the sticks within 2 % in frequency
    and 20 % in damping, the baseline's replicates are recorded through it,
    and the Coulomb slider is what is reported; the same slider without the
    sensor shows no resonance."""
    from lieng.diagnose.goodness import rig_mode
    from lieng.diagnose.segment import find_cycles, prepare

    t, x, _ = _forced_coulomb(0.0, rig=(40.0, 0.05))
    rec = record_from_arrays(t, x, 2.0)
    pr = prepare(rec)
    m = rig_mode(pr, find_cycles(pr, 10.0), 10.0)
    assert m is not None and abs(m["f"] / 40.0 - 1) < 0.02 and abs(m["zeta"] / 0.05 - 1) < 0.2
    d = diagnose(rec, 10.0)
    assert d.effect == "none", (d.effect, d.gain)
    assert any("rings after each arrest at 40" in n for n in d.notes)
    t, x, _ = _forced_coulomb(0.0)
    pr = prepare(record_from_arrays(t, x, 2.0))
    assert rig_mode(pr, find_cycles(pr, 10.0), 10.0) is None


def test_a_sliders_position_named_x_is_read_as_the_drives_travel_less_it(tmp_path):
    """A laser on the slider written as ``x`` (the slider's position, which
    moves one way by the drive's travel less the spring's extension) is not
    the spring's extension the diagnosis reads: read as it was (before this
    check), the Coulomb slider of :func:`_ac_coupled_sawtooth` gave
    'no_stick_slip' with a friction level of -11 mm.  Now the extension is
    the drive's travel less it, equal to the true extension less its first
    sample to the rounding of the file, and said in a note; the spring's
    extension written as ``x`` is read as it is, also one whose level climbs
    with the drive nearly as fast as a slider would move."""
    from lieng.diagnose import read_record

    v0 = 2.0
    t, _, ext = _ac_coupled_sawtooth(1e9, v0=v0)
    slider = v0 * t - ext + 3.0                       # the slider's position (mm), from an arbitrary origin
    p = tmp_path / "slider.csv"
    p.write_text("t [s],x [mm]\n" + "".join(f"{a:.4f},{b:.7f}\n" for a, b in zip(t, slider)))
    rec = read_record(p, v0=v0)
    assert any("slider's position" in n for n in rec.notes)
    assert float(np.max(np.abs(rec.x - (ext - ext[0])))) < 1e-5
    d = diagnose(rec, 10.0)
    assert d.effect == "none" and d.n_cycles >= 25
    q = tmp_path / "extension.csv"
    q.write_text("t [s],x [mm]\n" + "".join(f"{a:.4f},{b:.7f}\n" for a, b in zip(t, ext)))
    rec = read_record(q, v0=v0)
    assert not any("slider's position" in n for n in rec.notes)
    assert float(np.max(np.abs(rec.x - ext))) < 1e-6
    # an extension whose level climbs with the drive (0.75 of its travel over five cycles: a slope and a
    # spread a slider's position could have) rises with the drive in every stick: it is left as it is
    t5, _, e5 = _ac_coupled_sawtooth(1e9, v0=v0, cycles=5)
    climb = e5 + 0.75 * v0 * t5
    q5 = tmp_path / "climbing.csv"
    q5.write_text("t [s],x [mm]\n" + "".join(f"{a:.4f},{b:.7f}\n" for a, b in zip(t5, climb)))
    rec = read_record(q5, v0=v0)
    assert not any("slider's position" in n for n in rec.notes)


def test_a_reading_quantised_coarser_than_its_noise_is_calibrated_through_its_quantiser():
    """The weakening slider of :func:`_weakening_slider` (noise 0.2 % of fs)
    read by an encoder of 0.02 mm (2.8 % of its drop): its stick ramps step
    through the counts at v0 / q and its slips through them at their own
    speeds, lines the baseline's replicates with white noise alone never
    show.  Before, the replicates were not quantised and a line at such a
    tone was named 'triggering' (p 2e-5, a 'load modulation' of 14); now
    the step is found (:func:`.read.quantum`, to 1e-9 of 0.02), the
    replicates are read through it, and the answer is 'none'.  The same
    slider unquantised has no step."""
    from lieng.diagnose.read import quantum

    t, x = _weakening_slider()
    q = 0.02
    xq = q * np.round(x / q)
    assert quantum(xq) == pytest.approx(q, rel=1e-9)
    assert quantum(x) == 0.0
    d = diagnose(record_from_arrays(t, xq, 2.0), 10.0)
    assert d.effect == "none" and not d.effects


def test_a_lasers_slider_position_beside_a_reciprocating_stages_encoder_is_read_as_the_extension(tmp_path):
    """A reciprocating rig that writes its stage encoder and a laser on the
    slider (``Stage Encoder [mm]``, ``Laser Sensor [mm]``: the slider's
    position, back and forth with the stage): the extension is the stage's
    travel less the laser's reading, equal to the true extension of
    :func:`_reciprocating_coulomb` less its first sample to the file's
    rounding and a constant (set midway between the two directions' levels,
    as the positions' origins do not give it; direction_asymmetry then not
    read), and the record reads as that slider's: stick-slip in every
    stroke, effect none.  Before, 'Laser Sensor' and 'Encoder' named no
    column and the record was refused; a laser that moves one way only was
    the only slider position read."""
    from lieng.diagnose import read_record

    t, ext, v = _reciprocating_coulomb(lambda p: 1.0)
    pos = np.concatenate([[0.0], np.cumsum(v[1:] * np.diff(t))])
    laser = pos - ext + 7.0
    p = tmp_path / "rig.csv"
    p.write_text("time [s],Stage Encoder [mm],Laser Sensor [mm]\n"
                 + "".join(f"{a:.4f},{b:.6f},{c:.6f}\n" for a, b, c in zip(t, pos, laser)))
    rec = read_record(p)
    assert any("follows the drive's travel" in n for n in rec.notes)
    off = rec.x - ext
    assert float(np.ptp(off)) < 2e-5
    # the zero, which the positions do not give, midway between the directions' levels: this slider's
    # friction is the same either way, so that is its own zero, within 2 % of its drop (1.2 mm; the sticks'
    # medians in the two directions are not quite mirror images: measured 0.011 mm)
    assert rec.zero_unknown and abs(float(np.mean(off))) < 0.024
    d = diagnose(rec, 20.0)
    assert d.effect == "none" and d.n_cycles >= 20, d.reason
    assert not d.evidence["direction_asymmetry"]["applicable"]


def test_a_level_that_drifts_is_carried_by_the_baseline_the_gains_are_judged_against():
    """A sawtooth (sticks at the drive velocity from a friction level of
    1.5 to a limit of 2.5, cosine slips of half a natural period) read
    through a sensor whose offset drifts by 0.1 of the drop over the record:
    the baseline carries the trend in time of the level on the first 70 %
    (its slope within 10 % of the drift's 0.1 D / T), so that on the
    held-out 30 % its peaks and troughs are within 0.01 of the drop where
    the plain baseline's are 0.04-0.07 off (the drift between the training
    part's middle and the held-out cycles); without the drift the baseline
    is left as it is (geometry of the trace, plain NumPy)."""
    from lieng.diagnose.baseline import fit_baseline
    from lieng.diagnose.extend import Judge, level_trend, subset, window

    fn, v0, dt = 10.0, 1.0, 0.001
    lo, hi = 1.5, 2.5
    rise = np.arange(1, int((hi - lo) / v0 / dt) + 1) * v0 * dt + lo
    slip = 0.5 * (hi + lo) + 0.5 * (hi - lo) * np.cos(2 * np.pi * fn * np.arange(1, int(0.5 / fn / dt)) * dt)
    x0 = np.tile(np.r_[rise, slip], 30)
    t = dt * np.arange(x0.size)
    T = float(t[-1])
    for drift in (0.1, 0.0):
        pr, c, D, _ = _noisy_cycles(t, x0 + drift * (hi - lo) * t / T, np.full(x0.size, v0), fn,
                                    np.random.default_rng(3))
        tsplit = float(t[0] + 0.7 * T)
        train = (float(t[0]), tsplit)
        base = fit_baseline(pr, subset(c, window(pr.t[c.peak_i], train)), fn)
        tr = level_trend(base, pr, c, train)
        if drift == 0.0:
            assert tr is base
            continue
        assert tr.offset == pytest.approx(0.1 * (hi - lo) / T, rel=0.1)
        J = Judge(pr, c, fn, tsplit, float(t[-1]) + dt)
        plain, trended = (np.abs(J.vector(p)[0][:, 1:]) for p in (base, tr))
        assert np.median(plain) > 0.04
        assert np.median(trended) < 0.01


def _crank_record(a: float, fm: float = 1.3, fc: float = 1.0, seconds: float = 8.0, dt: float = 1e-3):
    """A Scotch-yoke drive, p = A sin(theta), its crank speed theta' =
    2 pi fc (1 + a sin(2 pi fm t)) (integrated in closed form), and a slider
    that sticks to it (x = the drive's travel within each stroke: the
    steady-drive reading needs only the drive)."""
    from lieng.diagnose.read import Record

    t = np.arange(0.0, seconds, dt)
    w, wm = 2 * math.pi * fc, 2 * math.pi * fm
    theta = w * t + (w * a / wm) * (1.0 - np.cos(wm * t)) if a else w * t
    v = 5.0 * np.cos(theta) * w * (1.0 + a * np.sin(wm * t))       # dp/dt, A = 5 mm
    x = np.abs(np.sin(theta)) * 0.01
    return Record(t=t, x=x, vd=v, drive_recorded=True, source="crank")


def test_a_recorded_crank_drive_is_made_steady_and_its_speed_modulation_read_against_it():
    """Geometry: a crank at steady speed repeats its speed along the track
    stroke after stroke, so its steady course (each direction's median
    stroke at each place) is its recorded speed, and the ratio of the two is
    1; a crank whose speed is modulated by a = 25 % reads ratios that the
    permutation scan finds modulated: at fm, with an amplitude of about
    half of a, where the modulation is faster than the strokes (the median
    of the strokes run at a like speed takes up part of it), and still well
    beyond the 5 % margin where it is slower (the strokes' own speeds then
    carry it, and the strokes at a like speed read against each other show
    it aliased: the frequency is not claimed there)."""
    from types import SimpleNamespace

    from lieng.diagnose.segment import drive_ratios, prepare
    from lieng.diagnose.signals import drive_scan

    cyc = SimpleNamespace(periods=lambda t: np.full(10, 0.05))       # a stick-slip period of 50 ms
    pr = prepare(_crank_record(0.0))
    assert pr.vd_steady is not None and len(pr.strokes) >= 12
    fast = pr.vd_steady > 0.3 * pr.vd_steady.max()
    assert np.max(np.abs(np.abs(pr.vd[fast]) / pr.vd_steady[fast] - 1.0)) < 0.03
    t, r = drive_ratios(pr, cyc)
    assert t.size > 100 and np.std(r) < 0.01
    for fm in (3.3, 1.3, 0.45):            # (the strokes: 2 a second)
        pr = prepare(_crank_record(0.25, fm))
        t, r = drive_ratios(pr, cyc)
        _, f, amp, p = drive_scan(t, r, 2.0 / (t[-1] - t[0]), 10.0, nperm=199)
        assert amp > 0.05 and p <= 0.01, (fm, f, amp, p)
        if fm > 2.0:
            assert f == pytest.approx(fm, abs=0.15) and 0.1 < amp < 0.25, (f, amp)


def _coulomb_thresholds(n_cyc=40, sd=0.2, holds=None, beta=0.0, seed=4, v0=1.0, fn=10.0, fk=1.0, fs0=1.5,
                        rate=500.0, noise=0.002):
    """An independent piecewise-analytic stick-slip (NumPy only, written for
    this test): Coulomb slips, each an exact undamped half-oscillation about
    the kinetic level ``fk`` until the slider stops again, and rigid sticks
    loaded at ``v0``; each stick's static limit drawn at random, ``fs0 + sd
    (fs0 - fk) N(0, 1)``, plus ``beta ln(stick time / 1 s)`` (an ageing
    limit); holds {slip index: seconds} stop the drive as that stick starts.
    Returns (t, x, drive velocity, each stick's duration, each peak)."""
    g = np.random.default_rng(seed)
    w = 2 * np.pi * fn
    holds = holds or {}
    seg_t, seg_x, hold_iv, ts, pk = [], [], [], [], []
    t, x = 0.0, fk - 0.5 * (fs0 - fk)
    for n in range(n_cyc):
        h = holds.get(n, 0.0)
        if h:
            seg_t.append(np.array([t, t + h]))
            seg_x.append(np.array([x, x]))
            hold_iv.append((t, t + h))
            t += h
        lim0 = fs0 + sd * (fs0 - fk) * g.standard_normal()
        s = max((lim0 - x) / v0, 1e-3)
        for _ in range(60):                     # the limit reached at x + v0 s = lim0 + beta ln(h + s)
            s = max((lim0 + beta * np.log(h + s) - x) / v0, 1e-3)
        ts.append(h + s)
        seg_t.append(np.array([t, t + s]))
        seg_x.append(np.array([x, x + v0 * s]))
        t, x = t + s, x + v0 * s
        pk.append(x)
        a = x - fk                              # the slip: x = fk + a cos(w tau) + (v0 / w) sin(w tau) until x' = v0
        th = 2 * np.pi - 2 * np.arctan(w * a / v0)
        tau = np.linspace(0.0, th / w, 40)
        seg_t.append(t + tau)
        seg_x.append(fk + a * np.cos(w * tau) + (v0 / w) * np.sin(w * tau))
        t, x = t + th / w, float(seg_x[-1][-1])
    tt, i = np.unique(np.concatenate(seg_t), return_index=True)
    xx = np.concatenate(seg_x)[i]
    grid = np.arange(0.0, tt[-1], 1.0 / rate)
    v = np.full(grid.size, v0)
    for a, b in hold_iv:
        v[(grid >= a) & (grid < b)] = 0.0
    return grid, np.interp(grid, tt, xx) + noise * g.standard_normal(grid.size), v, np.array(ts), np.array(pk)


def test_peaks_that_scatter_set_their_own_sticks_and_are_not_read_as_ageing():
    """A static limit drawn at random each stick (no ageing) makes a higher
    peak a longer stick: the peaks against their own sticks' durations read
    as ageing (0.24 of the drop at p = 3e-5 on this record; the
    paper-on-paper record's first 30 s, with 2 % mains hum or 1 % quantising,
    was named so).  Each peak is read against the stick the drive gives it
    from the arrest before it to the typical peak, which the peak does not
    set (checked against a rigid stick's (median peak - arrest) / v0), and
    nothing is read.
    The same slider with holds and an ageing limit (beta ln t) is still
    named, its growth over the record's range of stick times within 20 % of
    beta ln(31 s / 1 s) over the drop."""
    from lieng.diagnose.evidence import expected_sticks, stick_times
    from lieng.diagnose.segment import find_cycles, prepare

    t, x, v, ts, pk = _coulomb_thresholds()
    rec = record_from_arrays(t, x, v)
    pr = prepare(rec)
    c = find_cycles(pr, 10.0)
    k, _, _ = stick_times(pr, c)
    want = (np.median(pr.x[c.peak_i]) - pr.x[c.trough_i[k]]) / 1.0       # rigid sticks at 1 mm/s
    assert np.max(np.abs(expected_sticks(pr, c, k) - want)) < 0.01
    d = diagnose(rec, 10.0)
    assert not d.evidence["static_ageing"]["significant"], d.evidence["static_ageing"]
    assert "static_ageing" not in {e["effect"] for e in d.effects}

    beta, holds = 0.05, {5: 2.0, 12: 8.0, 20: 30.0, 27: 4.0, 33: 15.0}
    t, x, v, ts, pk = _coulomb_thresholds(sd=0.03, holds=holds, beta=beta)
    d = diagnose(record_from_arrays(t, x, v), 10.0)
    assert d.effect == "static_ageing" and d.gain >= 0.3
    drop = 2.0 * (np.median(pk) - 1.0)                  # an undamped Coulomb slip falls twice its excess over fk
    assert d.evidence["static_ageing"]["statistic"] == pytest.approx(beta * np.ptp(np.log(ts)) / drop, rel=0.2)


def test_noise_that_swamps_the_slopes_does_not_turn_the_force():
    """A sawtooth (stick ramps at the drive velocity, slips of half a period) under
    white noise of 40 % of its drop: the slopes' sign and the increments'
    tails say nothing, and the decision had fallen to a coin (the median
    slope's sign), turning a record written the right way round (found by
    the blind edge-case test); the level's sign decides there, both ways."""
    from lieng.diagnose.segment import _turned

    dt, v0, drop = 1e-3, 1.0, 0.3                       # s, mm/s, mm
    ramp = 0.2 + v0 * dt * np.arange(300)               # a stick from 0.2 to 0.5 mm
    slip = 0.35 + 0.15 * np.cos(np.linspace(0, np.pi, 30))  # a slip over 30 samples (half a period)
    saw = np.tile(np.r_[ramp, slip], 60)
    t = np.arange(saw.size) * dt
    for seed in range(6):
        x = saw + 0.4 * drop * np.random.default_rng(seed).standard_normal(t.size)
        vd = np.full(t.size, v0)
        assert not _turned([x], vd, dt) and _turned([-x], vd, dt), seed


def test_slips_under_white_noise_of_forty_percent_of_the_drop_are_found():
    """The blind edge-case test's heavy noise (stop 68): a sawtooth (stick
    ramps at the drive velocity, slips of half a natural period) under white
    noise of 40 % of its drop, sampled 60 times a natural period.  A
    quarter-period window let 8 times its noise through above the drop, and
    the noise had widened the swing it was read against: 17 of 60 slips with
    fn given, and the record was `no_stick_slip` without it.  The window now
    grows with the swing read through it, to a natural period (without fn, a
    quarter of the stroke's strongest period): every slip is found, with
    and without fn, and the drop within 15 % of the truth."""
    from lieng.diagnose.segment import find_cycles, prepare

    dt, v0, drop = 1e-3, 1.0, 0.3                       # s, mm/s, mm
    ramp = 0.2 + v0 * dt * np.arange(300)               # a stick from 0.2 to 0.5 mm
    slip = 0.35 + 0.15 * np.cos(np.linspace(0, np.pi, 30))  # a slip over 30 samples (half a period)
    saw = np.tile(np.r_[ramp, slip], 60)
    t = np.arange(saw.size) * dt
    fn = 1.0 / (60 * dt)
    for seed in range(3):
        x = saw + 0.4 * drop * np.random.default_rng(seed).standard_normal(t.size)
        pr = prepare(record_from_arrays(t, x, v0))
        for f in (fn, None):
            c = find_cycles(pr, f, retry=True)
            assert abs(c.n - 59) <= 1, (seed, f, c.n)
            assert c.amplitude(pr.x) == pytest.approx(drop, rel=0.15), (seed, f)


def test_slips_found_only_through_a_window_as_long_as_they_last_do_not_fix_fn():
    """A Coulomb slider's stick-slip (exact: a stick at the drive velocity,
    each slip half a free period about the kinetic level, fn = 10 Hz) with
    and without white noise of 40 % of its drop.  Clean, fn is read from the
    slips' duration to within the stated 15 %.  Under the noise its slips are
    found only through a window nearly as long as they last, and their
    duration read from their extremes outward had read 2.2 times fn (the
    blind edge-case test's records: 30-50 % off, with 15 % stated); read
    both ways it is open by +- 45 % (:func:`.segment.slip_durations`): the
    record is refused in one line asking for --fn (by either rule: the
    window as long as the slips, or the falls open beyond the widest
    uncertainty), and with --fn it is read (every slip, nothing named)."""
    fn, dt, v0 = 10.0, 1e-3, 2.0                 # Hz, s, mm/s
    fs, fk = 1.0, 0.8                            # static and kinetic levels (mm of spring extension)
    arc = fk + (fs - fk) * np.cos(2 * np.pi * fn * dt * np.arange(int(round(0.5 / fn / dt)) + 1))
    ramp = arc[-1] + v0 * dt * np.arange(1, int((fs - arc[-1]) / (v0 * dt)) + 1)
    x = np.tile(np.r_[ramp, arc[1:]], 30)
    t = np.arange(x.size) * dt
    d = diagnose(record_from_arrays(t, x, v0), None)
    assert d.fn == pytest.approx(fn, rel=0.15) and d.fn_uncertainty == 0.15
    noisy = record_from_arrays(t, x + 0.4 * 2 * (fs - fk) * np.random.default_rng(0).standard_normal(t.size), v0)
    with pytest.raises(LiengInputError, match=r"white noise of \d+ % of the drop: .* cannot fix the natural "
                                              r"frequency: give --fn \(Hz\)"):
        diagnose(noisy, None)
    d = diagnose(noisy, fn)
    assert d.effect == "none" and d.n_cycles >= 28


def test_a_friction_that_reads_below_zero_under_a_one_way_drive_is_an_offset():
    """An analytic Coulomb slider (``_coulomb_thresholds``, fn = 10 Hz, no
    effect) whose force sensor was not tared: its friction reads 3 drops
    below zero throughout, under a drive in either direction.  No friction
    that pushes the slider on is the 1-DoF model's: the baseline was read
    flat below zero and its replicates' peaks scattered 8 times the
    record's, `unexplained` (`haptic_phantom`'s six-axis cell, -0.37 N of
    offset under +0.2 N of friction, was a false alarm so).  The level is
    read higher, its lowest trough one drop above zero, and said: `none`, as
    the record without the offset."""
    t, x, v, _, _ = _coulomb_thresholds(n_cyc=30, sd=0.05, seed=2, noise=0.002, rate=1000.0)
    assert diagnose(record_from_arrays(t, x, v), 10.0).effect == "none"
    for sign in (1.0, -1.0):
        d = diagnose(record_from_arrays(t, sign * (x - 3.0), sign * v), 10.0)
        assert d.effect == "none", (sign, d.reason)
        assert any(n.startswith("the friction reads below zero while the drive runs one way") for n in d.notes)


def test_the_natural_frequency_read_from_noisy_slips_states_what_the_noise_leaves_open():
    """An analytic Coulomb slider (fn = 10 Hz, exact half-period slips,
    ``_coulomb_thresholds``) under white noise of 5 and 10 % of its drop,
    no --fn.  The slips' falls read from their extremes outward had
    lengthened them by 20-63 % (fn 8-38 % low, with 15 % stated).  Each
    level's crossing is now read nearest the fall's middle and farthest from
    it, the duration is the middle of the two, and the stated uncertainty
    adds their half-difference: the true fn lies within it.  A fall that
    does not turn back reads as before, its two readings the same: the
    clean slider's spread is 0 and its uncertainty 15 %."""
    from lieng.diagnose.segment import find_cycles, first_below, prepare, slip_durations, FALL_FRACTION

    t, x, v, _, _ = _coulomb_thresholds(n_cyc=30, sd=0.05, seed=2, noise=0.0, rate=1000.0)
    pr = prepare(record_from_arrays(t, x, v))
    c = find_cycles(pr, None, retry=True)
    d, half = slip_durations(pr, c, spread=True)
    assert np.all(half == 0.0)
    for j, (a, b) in enumerate(zip(c.peak_i, c.trough_i)):     # the reading from the extremes, as before
        seg, tt = pr.x[a:b + 1], pr.t[a:b + 1]
        drop = seg[0] - seg[-1]
        want = (first_below(tt, seg, seg[-1] + 0.1 * drop) - first_below(tt, seg, seg[0] - 0.1 * drop)) / FALL_FRACTION
        assert d[j] == pytest.approx(want, rel=1e-12)
    assert diagnose(record_from_arrays(t, x, v), None).fn_uncertainty == 0.15
    for noise, seed in ((0.05, 2), (0.1, 3)):
        t, x, v, _, _ = _coulomb_thresholds(n_cyc=30, sd=0.05, seed=seed, noise=noise, rate=1000.0)
        dg = diagnose(record_from_arrays(t, x, v), None)
        assert dg.fn_source == "estimated from the slips' duration"
        assert dg.fn_uncertainty > 0.15 and abs(dg.fn / 10.0 - 1.0) <= dg.fn_uncertainty, (noise, dg.fn)
        assert any("the noise leaves their falls open" in n for n in dg.notes)
