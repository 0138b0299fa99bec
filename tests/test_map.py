"""`lieng map` (Table 2.IV over a grid of v0 and dmu0 or the rising part's
slope) against single find_cycles / `lieng cycles` / `lieng sweep` runs, on
every executor; `lieng diagnose --batch` through the same executors."""

import dataclasses
import json
import re
import shutil
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from lieng import cycles
from lieng.programs import read_deck, write_deck
from lieng.cli import main
from lieng.analysis.executor import open_executor
from lieng.analysis.regime_map import (DEPENDS_ON_TRIGGER, METASTABLE, NO_MOTION, NO_SELF_SUSTAINED, REGIMES, SELF_EXCITED,
                              classify, regime_map)

from conftest import CARDS, ROOT, thesis_characteristic

#: the velocities of test_cycles.py's Table 2.IV test: |v0| < vr, vr < v0 < vk (two), vk < v0 < v_oc (two), v0 > v_oc
V0S = [0.2, 2.0, 10.0, 21.0, 23.0, 40.0]
DMUS = [0.6, 0.8, 1.0, 1.2]
FIG2_28 = CARDS / "figures" / "fig2_28.dat"
#: Table 2.IV's order along a rising v0 (the metastable cycle sits at v_oc, between rows 4 and 4b)
ORDER = {NO_MOTION: 0, SELF_EXCITED: 1, DEPENDS_ON_TRIGGER: 2, METASTABLE: 3, NO_SELF_SUSTAINED: 4}


def char():
    return thesis_characteristic(v0=10.0, eps=0.5, um=20.0, vmax=80)


@pytest.fixture(scope="module")
def small_map():
    x, v = char()
    return regime_map(x, v, V0S, dmus=DMUS, progress=False)


def test_each_point_is_a_single_find_cycles_run_read_as_table_2_iv(small_map):
    m = small_map
    x, v = char()
    assert m.regime.shape == (len(DMUS), len(V0S)) and list(m.v0) == V0S and list(m.values) == DMUS
    for i, f in enumerate(DMUS):
        xs, vs = cycles.scale_static_peak(x, v, f)
        lo, hi = cycles.stick_part(xs, vs)
        for j, v0 in enumerate(V0S):
            res = cycles.find_cycles(*cycles.move_to_v0(xs, vs, v0))
            assert m.origin_stable[i, j] == res.origin_stable
            assert (np.isnan(m.slc[i, j]) if res.stable_amplitude is None else m.slc[i, j] == res.stable_amplitude)
            assert (np.isnan(m.ulc[i, j]) if res.unstable_amplitude is None
                    else m.ulc[i, j] == res.unstable_amplitude)
            assert m.regime[i, j] == classify(res, lo < v0 < hi)
        # Table 2.IV along v0: no motion, self-excited, depends on the trigger, (metastable,) none
        ranks = [ORDER[c] for c in m.regime[i]]
        assert ranks == sorted(ranks), (f, m.regime[i])
        assert m.regime[i, 0] == NO_MOTION and m.regime[i, 1] == SELF_EXCITED and m.regime[i, -1] == NO_SELF_SUSTAINED
    # the deck's own dmu0: the regimes test_cycles.py reads off a sweep
    assert list(m.regime[DMUS.index(1.0)]) == [NO_MOTION, SELF_EXCITED, SELF_EXCITED, DEPENDS_ON_TRIGGER,
                                               DEPENDS_ON_TRIGGER, NO_SELF_SUSTAINED]
    # the depends-on-trigger band ends at v_oc, which rises with dmu0 (Fig. 2.28)
    assert np.all(np.diff(m.v_oc) > 0)
    for i in range(len(DMUS)):
        band = [V0S[j] for j in range(len(V0S)) if m.regime[i, j] == DEPENDS_ON_TRIGGER]
        assert band and max(band) < m.v_oc[i] < min(V0S[j] for j in range(len(V0S))
                                                    if V0S[j] > max(band))


@pytest.mark.parametrize("f", [0.8, 1.2])
def test_v_oc_is_the_sweeps(small_map, f):
    x, v = char()
    s = cycles.sweep_v0(*cycles.scale_static_peak(x, v, f), V0S, progress=False)
    assert s.v_oc is not None and small_map.v_oc[DMUS.index(f)] == s.v_oc


def arrays(m):
    return [m.v0, m.values, m.regime, m.origin_stable, m.slc, m.ulc, m.n_cycles, m.v_oc]


def test_process_pools_give_identical_arrays(small_map):
    x, v = char()
    with ProcessPoolExecutor(2) as ex:
        pooled = regime_map(x, v, V0S, dmus=DMUS, executor=ex, progress=False)
    for a, b in zip(arrays(small_map), arrays(pooled)):
        assert np.array_equal(a, b, equal_nan=True)
    with open_executor(workers=2) as ex:          # the command line's pool (forkserver)
        pooled = regime_map(x, v, V0S, dmus=DMUS, executor=ex, progress=False)
    for a, b in zip(arrays(small_map), arrays(pooled)):
        assert np.array_equal(a, b, equal_nan=True)


def test_the_slope_axis_sets_the_rising_part():
    x, y = read_deck(FIG2_28).xchl[:54], read_deck(FIG2_28).ychl[:54]
    # the deck's own rising part is the line of slope 0.1 from its kinetic minima
    xs, ys = cycles.set_rising_slope(x, y, 0.1)
    np.testing.assert_allclose(xs, x, atol=1e-12)
    xs, _ = cycles.set_rising_slope(x, y, 0.3)
    assert xs[-1] == pytest.approx(6.0 + 0.3 * 81) and xs[0] == pytest.approx(-6.0 - 0.3 * 39)
    assert np.array_equal(xs[11:32], x[11:32])         # the static peaks and falling parts stay
    # a steeper rising part damps more: v_oc falls with the slope, and from some slope on no U.L.C. is left
    m = regime_map(x, y, [2.0, 21.0, 24.0, 28.0, 35.0, 45.0], slopes=[0.05, 0.1, 0.3], progress=False)
    assert m.v_oc[0] > m.v_oc[1] and np.isnan(m.v_oc[2])
    assert not np.any(m.regime[2] == DEPENDS_ON_TRIGGER) and np.any(m.regime[0] == DEPENDS_ON_TRIGGER)
    assert cycles.stick_part(x, y) == pytest.approx((-0.45, 0.55))


def read_csv(path):
    lines = Path(path).read_text().splitlines()
    return lines[0].split(","), [ln.split(",") for ln in lines[1:]]


def test_cli_map_writes_csv_and_plot_and_agrees_with_lieng_cycles(tmp_path, capsys):
    """A grid the regime tests do not use; at sampled points the CSV agrees
    with `lieng cycles` on a deck of the characteristic scaled and moved
    there (written to the cards' precision, so to 1e-6)."""
    out = tmp_path / "m"
    assert main(["map", str(FIG2_28), "--v0", "1.05:41.05:5", "--dmu", "0.7:1.3:3", "--workers", "1", "-o",
                 str(out)]) == 0
    stdout = capsys.readouterr().out
    assert "depends on the trigger (row 4)" in stdout and "v_oc" in stdout
    head, rows = read_csv(out / "map.csv")
    assert head == ["v0 [mm/s]", "dmu0/dmu0_deck", "regime", "regime_name", "table_2_iv_row", "origin",
                    "slc_amplitude [mm]", "ulc_amplitude [mm]", "cycles"]
    assert len(rows) == 15 and {r[3] for r in rows} <= {g.key for g in REGIMES}
    vhead, vrows = read_csv(out / "v_oc.csv")
    assert vhead == ["dmu0/dmu0_deck", "v_oc [mm/s]"] and len(vrows) == 3
    assert (out / "map.png").stat().st_size > 10_000
    deck = read_deck(FIG2_28)
    x, y = deck.xchl[:deck.n], deck.ychl[:deck.n]
    for r in rows[1::3]:
        v0, f = float(r[0]), float(r[1])
        xs, ys = cycles.move_to_v0(*cycles.scale_static_peak(x, y, f), v0)
        p = tmp_path / "point.dat"
        write_deck(dataclasses.replace(deck, xchl=xs, ychl=ys), p)
        assert main(["cycles", str(p), "--json"]) == 0
        one = json.loads(capsys.readouterr().out)
        assert r[5] == ("stable" if one["origin_stable"] else "unstable")
        st = [c["amplitude"] for c in one["cycles"] if c["kind"] == "stable"]
        un = [c["amplitude"] for c in one["cycles"] if c["kind"] != "stable"]
        assert (r[6] == "") == (not st) and (r[7] == "") == (not un) and int(r[8]) == len(one["cycles"])
        if st:
            assert float(r[6]) == pytest.approx(max(st), rel=1e-6)
        if un:
            assert float(r[7]) == pytest.approx(min(un), rel=1e-6)
    # the deck as it is (v0 = its VO = 21.05, dmu0 factor 1): the deck itself
    assert main(["cycles", str(FIG2_28), "--json"]) == 0
    one = json.loads(capsys.readouterr().out)
    r = next(r for r in rows if float(r[0]) == pytest.approx(21.05) and float(r[1]) == 1.0)
    assert float(r[6]) == pytest.approx(max(c["amplitude"] for c in one["cycles"] if c["kind"] == "stable"),
                                        rel=1e-9)


BAD = [
    (["--v0", "1:2", "--dmu", "0.5:1:3"], "--v0"),
    (["--v0", "1:20:0", "--dmu", "0.5:1:3"], "--v0"),
    (["--v0", "1:20:3", "--dmu", "0.5:1:0"], "--dmu"),
    (["--v0", "1:20:3", "--dmu", "0:1:3"], "--dmu"),
    (["--v0", "1:20:3", "--slope", "-0.1:1:3"], "--slope"),
    (["--v0", "1:20:3", "--slope", "1:40:3"], "--slope"),          # a rising part as steep as the stick part
    (["--v0", "1:200:3", "--dmu", "0.5:1:3"], "--v0"),             # beyond the characteristic
    (["--v0", "5:5:3", "--dmu", "0.5:1:3"], "--v0"),
    (["--v0", "1:20:3", "--dmu", "0.5:1:3", "--slope", "0.1:0.2:2"], "--slope"),
    (["--v0", "1:20:3"], "--dmu --slope"),
    (["--v0", "1:20:1000", "--dmu", "0.5:1:1001"], "at most"),
    (["--v0", "1:20:3", "--dmu", "0.5:1:3", "--workers", "0"], "--workers"),
    (["--v0", "1:20:3", "--dmu", "0.5:1:3", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--workers"),
    (["--v0", "1:20:3", "--dmu", "0.5:1:3", "--scheduler", "tcp://127.0.0.1:1"], "--scheduler"),
    (["--v0", "1:20:3", "--dmu", "0.5:1:3", "--scheduler", "no-port"], "--scheduler"),
]


@pytest.mark.parametrize("args,needle", BAD)
def test_cli_map_bad_input_is_one_line_and_writes_nothing(tmp_path, capsys, args, needle):
    out = tmp_path / "never"
    assert main(["map", str(FIG2_28), *args, "-o", str(out)]) == 2
    cap = capsys.readouterr()
    assert cap.err.startswith("lieng: error:") and cap.err.count("\n") == 1 and needle in cap.err, cap.err
    assert cap.out == "" and not out.exists()


def test_cli_map_without_dask_is_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)          # import distributed -> ImportError
    out = tmp_path / "never"
    assert main(["map", str(FIG2_28), "--v0", "1:20:3", "--dmu", "0.5:1:3", "--scheduler", "tcp://127.0.0.1:8786",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "lieng[dask]" in err and not out.exists()


@pytest.mark.slow
def test_a_local_dask_cluster_gives_the_same_csv(tmp_path):
    distributed = pytest.importorskip("distributed")
    args = ["map", str(FIG2_28), "--v0", "0.5:40:12", "--dmu", "0.3:1.7:5", "--no-plots", "-q", "-o"]
    assert main(args + [str(tmp_path / "local"), "--workers", "2"]) == 0
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        assert main(args + [str(tmp_path / "dask"), "--scheduler", cluster.scheduler_address]) == 0
    for name in ("map.csv", "v_oc.csv"):
        assert (tmp_path / "dask" / name).read_bytes() == (tmp_path / "local" / name).read_bytes()


def batch_dir(tmp_path):
    from lieng.analysis.synth import synthesize

    d = tmp_path / "records"
    d.mkdir()
    for name, effect, seed in (("a.csv", "none", 1), ("b.csv", "drive_modulation", 2)):
        synthesize(effect, seed, cycles=8).write_csv(d / name)
    (d / "broken.txt").write_text("t,x\n0,1\n0.001,oops\n")
    (d / "notes.md").write_text("not a record\n")
    return d


def test_diagnose_batch_reports_each_record_and_goes_on_past_a_bad_one(tmp_path, capsys):
    d = batch_dir(tmp_path)
    out = tmp_path / "out"
    assert main(["diagnose", "--batch", str(d), "--v0", "1", "--no-plots", "--workers", "2", "-o", str(out)]) == 1
    cap = capsys.readouterr()
    assert cap.err.count("\n") == 1 and cap.err.startswith(f"lieng: error: {d / 'broken.txt'}: line 3")
    head, rows = read_csv(out / "batch.csv")
    assert head == ["record", "outdir", "status", "effect", "effects_named", "gain", "cycles", "error"]
    assert [r[0] for r in rows] == ["a.csv", "b.csv", "broken.txt"]
    assert [r[2] for r in rows] == ["ok", "ok", "error"] and "'oops' is not a number" in rows[2][-1]
    for r in rows[:2]:
        one = json.loads((out / r[1] / "diagnosis.json").read_text())
        assert one["effect"] == r[3] and int(r[6]) == one["cycles"]
    assert not (out / "broken").exists()
    assert sorted((out / ".lieng-outputs").read_text().split()) == ["a", "b", "batch.csv"]


@pytest.mark.slow
def test_diagnose_batch_writes_what_diagnose_writes_and_may_run_again(tmp_path):
    d = batch_dir(tmp_path)
    out = tmp_path / "out"
    assert main(["diagnose", "--batch", str(d), "--v0", "1", "--no-plots", "-q", "-o", str(out)]) == 1
    # what one `lieng diagnose` writes for the same record
    assert main(["diagnose", str(d / "a.csv"), "--v0", "1", "--no-plots", "-q", "-o", str(tmp_path / "one")]) == 0
    assert (json.loads((tmp_path / "one" / "diagnosis.json").read_text())
            == json.loads((out / "a" / "diagnosis.json").read_text()))
    # all good: status 0, and the same directory may be written again
    (d / "broken.txt").unlink()
    assert main(["diagnose", "--batch", str(d), "--v0", "1", "--no-plots", "--workers", "1", "-q", "-o",
                 str(out)]) == 0
    assert len(read_csv(out / "batch.csv")[1]) == 2


@pytest.mark.parametrize("extra,needle", [
    ([], "--batch"),                                               # neither a record nor --batch
    (["--batch", "{d}", "{d}/a.csv"], "not both"),
    (["--batch", "{d}/a.csv"], "not a directory"),
    (["--batch", "{d}", "--json"], "--json"),
    (["--batch", "{d}", "--workers", "0"], "--workers"),
    (["{d}/a.csv", "--workers", "2"], "--workers"),
])
def test_diagnose_batch_bad_input(tmp_path, capsys, extra, needle):
    d = tmp_path / "records"
    d.mkdir()
    (d / "a.csv").write_text("t,x\n0,1\n")
    out = tmp_path / "never"
    assert main(["diagnose", *[e.format(d=d) for e in extra], "--v0", "1", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("lieng: error:") and err.count("\n") == 1 and needle in err, err
    assert not out.exists()


@pytest.mark.slow
def test_readme_regime_map_numbers(tmp_path, capsys, monkeypatch):
    """The README's "Regime maps" section states what its command prints."""
    monkeypatch.chdir(ROOT)
    text = (ROOT / "README.md").read_text()
    sec = text[text.index("## Regime maps"):]
    sec = sec[:sec.index("\n## ", 4)]
    cmd = re.search(r"\$ lieng (map .*)", sec).group(1).split()
    cmd[cmd.index("-o") + 1] = str(tmp_path / "map")
    assert main(cmd) == 0
    printed = capsys.readouterr().out
    block = sec[sec.index("$ lieng map"):]
    block = block[block.index("\n") + 1:block.index("```")]
    for line in block.strip().splitlines():
        if not line.startswith("wrote"):
            assert line in printed, line
    shutil.rmtree(tmp_path / "map")
