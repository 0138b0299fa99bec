"""Issue #14's reproductions, one per class: each a clean one-line error
(exit 2) or a finite result (exit 0), never a traceback, a hang, a NaN in an
output or a user's file changed."""

import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest

from lieng.cli import UNEXPECTED, main

from conftest import CARDS

LIENG1 = CARDS / "lieng1_demo.dat"
MLIEN = CARDS / "mlien_a9_7.dat"
TRC = CARDS / "trc_demo.dat"
NONFINITE = re.compile(r"(?i)(?<![a-z])(nan|-?inf(inity)?)(?![a-z])")


def put(lines, card, c1, c2, text):
    """Columns c1..c2 (1-based) of card ``card`` (1-based) replaced, right-justified."""
    out = list(lines)
    line = out[card - 1].ljust(80)
    w = c2 - c1 + 1
    out[card - 1] = line[: c1 - 1] + text.rjust(w)[:w] + line[c2:]
    return out


def deck(tmp_path, src, card, c1, c2, text, name="d.dat"):
    p = tmp_path / name
    p.write_text("\n".join(put(src.read_text().splitlines(), card, c1, c2, text)) + "\n")
    return p


def run(args, capsys):
    code = main([str(a) for a in args])
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def one_line_error(code, err, *needles):
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1 and lines[0].startswith("lieng: error: "), err
    assert UNEXPECTED not in err, err
    for n in needles:
        assert n in lines[0], lines[0]


def finite_outputs(outdir, stdout=""):
    for f in outdir.iterdir():
        if f.suffix in (".csv", ".txt", ".md", ".json"):
            text = f.read_text()
            assert not NONFINITE.search(text), f"{f.name}: {NONFINITE.search(text).group(0)}"
            if f.suffix == ".json":
                json.loads(text, parse_constant=lambda c: pytest.fail(f"{f.name}: {c}"))
    assert not NONFINITE.search(stdout)


def trace_csv(path, x, sep=","):
    t = np.arange(x.size) * 1e-3
    path.write_text(f"t{sep}x\n" + "".join(f"{a:.17g}{sep}{b:.17g}\n" for a, b in zip(t, x)))
    return path


# ---------------------------------------------------------------- 1. silent NaN/inf


@pytest.mark.parametrize("origin", ["listing", "fit"])
def test_trc_csv_with_a_repeated_value_flags_the_undefined_points(origin, tmp_path, capsys):
    # a growing oscillation whose x repeats at two neighbouring samples near two crests
    k = np.arange(300)
    x = np.sin(2 * np.pi * k / 60) * (1 + k / 600)
    x[15], x[137] = x[14], x[136]
    out = tmp_path / "o"
    code, stdout, err = run(["run", "trc", trace_csv(tmp_path / "q.csv", x), "--omnh", "100", "--origin", origin,
                             "-o", out, "--no-plots"], capsys)
    assert code == 0, err
    finite_outputs(out, stdout)
    assert "XX is undefined at 4 point(s) (15, 16, 137, 138)" in err and "left empty" in err
    rows = [r.split(",") for r in (out / "trc.csv").read_text().splitlines()]
    xx = rows[0].index("xx")
    assert [r[xx] for r in rows[15:17]] == ["", ""] and all(r[xx] for r in rows[1:15])


def test_trc_deck_an1_zero_is_finite(tmp_path, capsys):
    out = tmp_path / "o"
    code, stdout, err = run(["run", "trc", deck(tmp_path, TRC, 3, 21, 30, "0.000"), "-o", out, "--no-plots"],
                            capsys)
    assert code == 0, err
    finite_outputs(out, stdout)


def test_lieng1_overflowing_dtheta_names_its_card(tmp_path, capsys):
    out = tmp_path / "o"
    code, _, err = run(["run", "lieng1", deck(tmp_path, LIENG1, 3, 46, 55, "1.0E18"), "-o", out], capsys)
    one_line_error(code, err, "card 3, columns 46-55", "DTHETA")
    assert not out.exists()


# ---------------------------------------------------------------- 2. listing overflow


@pytest.mark.parametrize("prog,src,card,c1,c2,val", [
    ("lieng1", LIENG1, 3, 46, 55, "0.50"),       # trajectories grow past F20.8
    ("lieng1", LIENG1, 42, 41, 50, "1.0E30"),    # XCHL(200), an unused slot, in F10.2
    ("trc", TRC, 1, 1, 20, "1.0E8"),             # HO
], ids=["dtheta-0.5", "xchl200-1e30", "trc-ho-1e8"])
def test_listing_prints_asterisks_for_values_too_wide(prog, src, card, c1, c2, val, tmp_path, capsys):
    out = tmp_path / "o"
    code, stdout, err = run(["run", prog, deck(tmp_path, src, card, c1, c2, val), "-o", out, "--no-plots"], capsys)
    assert code == 0, err
    assert "Traceback" not in err
    finite_outputs(out, stdout)


def test_format_f_overflow_is_asterisks_like_gfortran():
    from lieng.io.cards import format_value, parse_format

    ed = parse_format("(F20.8)").items[0]
    assert format_value(1e20, ed) == "*" * 20
    assert format_value(1.7e308, ed) == "*" * 20
    assert format_value(float("inf"), ed) == "*" * 20
    assert format_value(float("nan"), ed) == "UNDEF".rjust(20)
    assert format_value(-123.456, ed) == "-123.45600000".rjust(20)


# ---------------------------------------------------------------- 3. strict JSON


def test_json_outputs_are_strict(tmp_path, capsys):
    code, stdout, err = run(["cycles", CARDS / "figures" / "fig2_27.dat", "--json"], capsys)
    assert code == 0, err
    json.loads(stdout, parse_constant=lambda c: pytest.fail(c))


# ---------------------------------------------------------------- 4. other tracebacks


@pytest.mark.parametrize("args,needle", [
    (["run", "mlien", ("mlien", 2, 6, 15, "1.7E308"), "-o", "o"], "OMEGA"),
    (["run", "mlien", ("mlien", 2, 46, 55, "593.74"), "-o", "o"], "DTHETA"),
    (["run", "trc", ("trc", 1, 41, 60, "-2000.0"), "-o", "o"], "card 1, columns 41-60 (VEL"),
    (["synth", "--seed", "-1", "-o", "s.csv"], "--seed"),
    (["synth", "--cycles", "0", "-o", "s.csv"], "--cycles"),
    (["synth", "--cycles", "-5", "-o", "s.csv"], "--cycles"),
    (["synth", "--cycles", "100000000", "-o", "s.csv"], "--cycles"),
    (["synth", "-o", ""], "-o"),
    (["synth", "-o", "."], "-o"),
    (["twodof", "--t-end", "0.001"], "--t-end"),
    (["sweep", str(CARDS / "figures" / "fig2_27.dat"), "--v0", "1:2:100000"], "--v0"),
    (["run", "lieng1", str(LIENG1), "-o", ""], "-o"),
    (["sweep", str(CARDS / "figures" / "fig2_28.dat"), "--dmu", "0:1.5:5"], "--dmu 0:1.5:5"),
], ids=["mlien-omega", "mlien-dtheta", "trc-vel", "seed", "cycles0", "cycles-5", "cycles-huge", "o-empty",
        "o-dot", "t-end", "sweep-n", "run-o-empty", "sweep-dmu-zero"])
def test_bad_values_are_one_line(args, needle, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    srcs = {"mlien": MLIEN, "trc": TRC}
    args = [deck(tmp_path, srcs[a[0]], *a[1:]) if isinstance(a, tuple) else a for a in args]
    code, _, err = run(args, capsys)
    one_line_error(code, err, needle)


def test_synth_fewest_cycles_works(tmp_path, capsys):
    code, _, err = run(["synth", "--cycles", "1", "--seed", "2", "-o", tmp_path / "s.csv", "-q"], capsys)
    assert code == 0, err


def test_paths_that_cannot_be_outputs(tmp_path, capsys):
    f = tmp_path / "afile"
    f.write_text("mine")
    for target in (f, f / "sub"):
        code, _, err = run(["run", "lieng1", LIENG1, "-o", target, "--no-plots"], capsys)
        one_line_error(code, err, "-o")
    d = tmp_path / "adir"
    d.mkdir()
    code, _, err = run(["synth", "-o", d], capsys)
    one_line_error(code, err, "directory")
    assert f.read_text() == "mine"


def test_inputs_that_are_not_files(tmp_path, capsys):
    a, b = tmp_path / "loopa", tmp_path / "loopb"
    os.symlink(b, a)
    os.symlink(a, b)
    for args in (["run", "lieng1", a, "-o", tmp_path / "o"], ["diagnose", a, "-o", tmp_path / "o"],
                 ["run", "trc", tmp_path, "-o", tmp_path / "o"], ["cycles", tmp_path / "missing.dat"]):
        code, _, err = run(args, capsys)
        one_line_error(code, err)
    assert not (tmp_path / "o").exists()


def test_long_fields_are_refused_by_line(tmp_path, capsys):
    p = tmp_path / "long.csv"
    p.write_text("t,x\n" + "1" * 200_000 + ",2\n")
    code, _, err = run(["diagnose", p, "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, "line 2")


# ---------------------------------------------------------------- 5. hangs


@pytest.mark.parametrize("cmd", [["run", "lieng1"], ["run", "trc"], ["diagnose"], ["cycles"]])
def test_a_fifo_is_refused_not_read(cmd, tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    args = [sys.executable, "-m", "lieng.cli", *cmd, str(fifo)]
    if cmd[0] != "cycles":
        args += ["-o", str(tmp_path / "o")]
    p = subprocess.run(args, capture_output=True, text=True, timeout=60)
    assert p.returncode == 2 and p.stderr.count("\n") == 1 and "regular file" in p.stderr, p.stderr


# ---------------------------------------------------------------- 6. user files


def test_a_directory_named_like_an_output_is_never_deleted(tmp_path, capsys):
    out = tmp_path / "o"
    (out / "trajectories.csv").mkdir(parents=True)
    (out / "trajectories.csv" / "mine.txt").write_text("keep")
    code, _, err = run(["run", "lieng1", LIENG1, "-o", out, "--no-plots"], capsys)
    one_line_error(code, err, "--force")
    code, _, err = run(["run", "lieng1", LIENG1, "-o", out, "--no-plots", "--force"], capsys)
    one_line_error(code, err, "is a directory")
    assert (out / "trajectories.csv" / "mine.txt").read_text() == "keep"
    assert sorted(p.name for p in out.iterdir()) == ["trajectories.csv"]


def test_force_writes_beside_user_files_and_a_rerun_removes_stale_outputs(tmp_path, capsys):
    out = tmp_path / "o"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    code, _, err = run(["run", "lieng1", LIENG1, "-o", out], capsys)
    one_line_error(code, err, "notes.txt")
    assert sorted(p.name for p in out.iterdir()) == ["notes.txt"]
    assert run(["run", "lieng1", LIENG1, "-o", out, "--force"], capsys)[0] == 0
    assert (out / "phase_plane.png").exists()
    assert run(["run", "lieng1", LIENG1, "-o", out, "--no-plots", "--force"], capsys)[0] == 0
    assert not list(out.glob("*.png"))       # the first run's plots were lieng's: removed
    assert (out / "notes.txt").read_text() == "mine"
    # a directory of lieng's own outputs needs no --force
    assert run(["run", "lieng1", LIENG1, "-o", tmp_path / "p", "--no-plots"], capsys)[0] == 0
    assert run(["run", "lieng1", LIENG1, "-o", tmp_path / "p", "--no-plots"], capsys)[0] == 0


def test_synth_never_replaces_a_file_without_force_nor_a_special_file(tmp_path, capsys):
    f = tmp_path / "s.csv"
    f.write_text("mine")
    code, _, err = run(["synth", "-o", f], capsys)
    one_line_error(code, err, "--force")
    assert f.read_text() == "mine"
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    code, _, err = run(["synth", "-o", fifo, "--force"], capsys)
    one_line_error(code, err, "regular file")
    assert fifo.is_fifo()
    assert run(["synth", "-o", f, "--force", "--seed", "1", "-q"], capsys)[0] == 0
    assert f.read_text().startswith("t,")


# ---------------------------------------------------------------- 7. messages


@pytest.mark.parametrize("args,needle", [
    (["run", "lieng1"], "required"),
    (["sweep", str(CARDS / "figures" / "fig2_27.dat"), "--v0"], "--v0"),
    (["nonsense"], "invalid choice"),
    (["diagnose", "x.csv", "-o", "o", "--fn", "abc"], "--fn"),
])
def test_usage_errors_are_one_line(args, needle, capsys):
    code, _, err = run(args, capsys)
    one_line_error(code, err, needle)


def test_a_negative_range_start_needs_no_equals_sign(capsys):
    code, stdout, err = run(["sweep", CARDS / "figures" / "fig2_27.dat", "--v0", "-2:2:3"], capsys)
    assert code == 0, err
    assert len(stdout.strip().splitlines()) == 5


def test_a_form_feed_is_a_character_of_its_card(tmp_path, capsys):
    lines = LIENG1.read_text().splitlines()
    lines[3] = lines[3][:20] + "\f" + lines[3][21:]
    p = tmp_path / "ff.dat"
    p.write_text("\n".join(lines) + "\n")
    code, _, err = run(["run", "lieng1", p, "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, "card 4, columns 21-30")


def test_a_tab_separated_trace_is_read_as_a_table(tmp_path, capsys):
    t = np.arange(300) * 1e-3
    x = np.sin(2 * np.pi * t * 7) + 0.3 * np.sin(2 * np.pi * t * 19)
    p = tmp_path / "tab.txt"
    p.write_text("t\tx\n" + "".join(f"{a:.17g}\t{b:.17g}\n" for a, b in zip(t, x)))
    code, stdout, err = run(["run", "trc", p, "--omnh", "100", "-o", tmp_path / "o", "--no-plots"], capsys)
    assert code == 0, err
    finite_outputs(tmp_path / "o", stdout)


def test_warnings_are_not_printed_before_an_error(tmp_path, capsys):
    # a deck that warns (PHI undefined: AMPV0 = 0) and then fails (DTHETA overflow)
    p = deck(tmp_path, LIENG1, 3, 16, 25, "0.00", name="a.dat")
    p.write_text("\n".join(put(p.read_text().splitlines(), 3, 46, 55, "1.0E18")) + "\n")
    code, _, err = run(["run", "lieng1", p, "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, "DTHETA")


@pytest.mark.parametrize("args,needle", [
    (["run", "lieng1", str(LIENG1), "-o", "o", "--omnh", "5"], "--omnh"),
    (["run", "mlien", str(MLIEN), "-o", "o", "--origin", "fit"], "--origin"),
    (["run", "trc", str(TRC), "-o", "o", "--lookup", "fast"], "--lookup"),
    (["twodof", "--belt", "0.008", "--rpm", "0.1"], "--belt and --rpm"),
])
def test_options_that_do_not_apply_are_refused(args, needle, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run(args, capsys)
    one_line_error(code, err, needle)
    assert not (tmp_path / "o").exists()


def test_version(capsys):
    assert run(["--version"], capsys)[:2] == (0, f"lieng {__import__('lieng').__version__}\n")


def test_force_never_replaces_a_foreign_file_with_an_outputs_name(tmp_path, capsys):
    out = tmp_path / "o"
    out.mkdir()
    (out / "listing.txt").write_text("my own listing\n")
    code, _, err = run(["run", "lieng1", LIENG1, "-o", out, "--no-plots", "--force"], capsys)
    one_line_error(code, err, "not written by lieng")
    assert (out / "listing.txt").read_text() == "my own listing\n"
    assert sorted(p.name for p in out.iterdir()) == ["listing.txt"]


def test_synth_does_not_write_through_a_symlink(tmp_path, capsys):
    target = tmp_path / "target.csv"
    target.write_text("mine\n")
    (tmp_path / "link").symlink_to(target)
    code, _, err = run(["synth", "--force", "-o", tmp_path / "link"], capsys)
    one_line_error(code, err, "symbolic link")
    assert target.read_text() == "mine\n" and (tmp_path / "link").is_symlink()


def test_trc_reads_y_as_the_normal_channel_and_refuses_both(tmp_path, capsys):
    t = np.arange(300) * 1e-3
    x = np.sin(2 * np.pi * t * 7) + 0.3 * np.sin(2 * np.pi * t * 19)
    y = 1.0 + 0.1 * np.cos(2 * np.pi * t * 11)
    for head, cols, ok in (("t,x,y", (t, x, y), True), ("t,x,xn,y", (t, x, y, y), False)):
        p = tmp_path / f"{len(cols)}.csv"
        p.write_text(head + "\n" + "".join(",".join(f"{c[k]:.17g}" for c in cols) + "\n" for k in range(t.size)))
        code, _, err = run(["run", "trc", p, "--omnh", "100", "--omnv", "150", "-o", tmp_path / f"o{len(cols)}",
                            "--no-plots"], capsys)
        if ok:
            assert code == 0, err
            assert (tmp_path / "o3" / "trc.csv").read_text().splitlines()[1].split(",")[4] != ""
        else:
            one_line_error(code, err, "xn and y")


def test_a_field_whose_exponent_is_beyond_range_names_its_columns(tmp_path, capsys):
    # found by the fuzz campaign: a TRC deck read as an MLIEN deck puts '1E300' where F10.2 reads '1E3000000'
    p = deck(tmp_path, MLIEN, 2, 16, 25, "1E99999999")
    code, _, err = run(["run", "mlien", p, "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, "card 2, columns 16-25", "out of the range")


def test_a_time_column_in_the_wrong_unit_is_named(tmp_path, capsys):
    # found by the fuzz campaign: times scaled by 1e-300 divided by zero in the smoothing
    t = np.arange(2000) * 1e-303
    x = np.mod(np.arange(2000), 100) * 0.01
    p = tmp_path / "r.csv"
    p.write_text("t,x\n" + "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(t, x)))
    code, _, err = run(["diagnose", p, "--v0", "1", "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, "column t", "unit")


def test_a_decks_natural_frequency_that_does_not_fit_the_record_names_the_card(tmp_path, capsys):
    """Found by a black-box fuzz of the CLI: a TRC deck's OMNH that the
    readings cannot be analysed with was blamed on "--fn", which the user
    never gave; the card is named, and --fn overrides it."""
    deck = CARDS / "trc_demo.dat"
    rc = main(["diagnose", str(deck), "--v0", "1", "-o", str(tmp_path / "o"), "-q"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "card OMNH" in err[0] and "--fn 30" not in err[0]
    assert not (tmp_path / "o").exists()


def test_a_cell_with_an_underscore_is_no_number(tmp_path, capsys):
    """Python reads "0_2" as 2.0; a table cell like that is named as bad."""
    p = tmp_path / "u.csv"
    rows = [f"{i * 0.001:.3f},{(i % 50) * 0.01:.2f}" for i in range(300)]
    rows[20] = "0.020,0_2"
    p.write_text("t [s],x [mm]\n" + "\n".join(rows) + "\n")
    rc = main(["diagnose", str(p), "--v0", "1", "-o", str(tmp_path / "o"), "-q"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "line 22, column x: '0_2' is not a number" in err[0]


def test_a_txt_or_dat_table_without_a_time_column_is_no_deck(tmp_path, capsys):
    """A .dat or .txt table whose header names no time column (read with
    --rate) is a table, not a TRC deck: a deck's cards hold numbers only."""
    t = np.arange(4000) * 5e-4
    F = 0.5 * (1 - np.cos(2 * np.pi * 3.0 * t)) * 1e-3
    for name, sep in (("f.dat", " "), ("f.txt", ","), ("g.txt", "\t")):
        p = tmp_path / name
        p.write_text(f"Friction [N]{sep}Position [mm]\n" + "".join(f"{a:.9g}{sep}{b:.9g}\n" for a, b in zip(F, t)))
        code, _, err = run(["diagnose", p, "--rate", "2000", "--stiffness", "1000", "-o", tmp_path / name[0],
                            "--no-plots", "-q"], capsys)
        assert "card" not in err, err


def test_an_output_directory_that_cannot_be_made_is_one_line(tmp_path, capsys):
    code, _, err = run(["run", "lieng1", LIENG1, "-o", "/proc/lieng_no_such_dir", "--no-plots"], capsys)
    one_line_error(code, err, "-o /proc/lieng_no_such_dir")


def test_two_columns_of_one_name_are_refused(tmp_path, capsys):
    """Two columns named alike (`F [N]` twice): which one is the friction?
    Refused by name, not the second silently read (found by the audit)."""
    p = tmp_path / "dup.csv"
    p.write_text("t [s],F [N],F [N]\n" + "".join(f"{i * 1e-3},{0.001 * i},{0.002 * i}\n" for i in range(200)))
    code, _, err = run(["diagnose", p, "--stiffness", "1000", "--v0", "1", "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, "columns 2 and 3")
    assert not (tmp_path / "o").exists()


def test_coarse_reciprocating_sliding_prints_no_nan(tmp_path, capsys):
    """Steady sliding on a reciprocating stage sampled so coarsely that each
    reversal lies within one sample: the presliding ramp is not resolved,
    which the report says in words (it printed 'ramp slope nan'), and the
    level keeps its sign (the reversal's fast rise in the new direction was
    taken for the slips' tail; found by the black-box audit)."""
    g = np.random.default_rng(2)
    t = np.arange(2715) / 50.0
    ph = t % 1.0
    pos = np.where(ph < 0.5, 10.0 * ph, 5.0 - 10.0 * (ph - 0.5))   # 10 mm/s, 25 samples a stroke
    F = np.empty(t.size)                                         # a stiff contact: 2 N a sample, clipped at 1.22
    f = 0.0
    for j in range(t.size):
        f = min(max(f + 10.0 * (pos[j] - pos[j - 1] if j else 0.0), -1.22), 1.22)
        F[j] = f
    F = F + 0.002 * 1.22 * g.standard_normal(t.size)
    p = tmp_path / "recip.csv"
    p.write_text("Time [s],Friction [N],Position [mm]\n"
                 + "".join(f"{a:.2f},{b:.6f},{c:.4f}\n" for a, b, c in zip(t, F, pos)))
    code, stdout, err = run(["diagnose", p, "--stiffness", "1000", "-o", tmp_path / "o", "--no-plots"], capsys)
    assert code == 0, err
    finite_outputs(tmp_path / "o", stdout)
    assert "nan" not in stdout.lower() and "nan" not in (tmp_path / "o" / "report.md").read_text().lower()
    assert "at a level of 1.22 mm" in stdout and "its sign was turned" not in stdout


def test_a_record_written_last_sample_first_is_refused_saying_so(tmp_path, capsys):
    """A record whose time column runs backwards (written last sample first)
    is refused with one line that says the rows must be in time order (it
    was read as 10 000 runs appended to one file, each one sample long:
    "1 samples in the longest run"); runs appended to one file, the clock
    starting again, are still read (the longest)."""
    t = np.arange(2000) / 1000.0
    x = (t * 2.0) % 1.0
    p = tmp_path / "backwards.csv"
    p.write_text("time [s],x [mm]\n" + "".join(f"{a:.4f},{b:.5f}\n" for a, b in zip(t[::-1], x[::-1])))
    code, _, err = run(["diagnose", p, "--v0", "2", "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, "time order")
    assert not (tmp_path / "o").exists()
    from lieng.diagnose import read_record
    q = tmp_path / "appended.csv"
    q.write_text("time [s],x [mm]\n" + "".join(f"{a:.4f},{b:.5f}\n" for a, b in zip(np.r_[t[:300], t], np.r_[x[:300], x])))
    assert read_record(q, v0=2.0).t.size == t.size


@pytest.mark.parametrize("opts, needles", [
    (["--stiffness", "2.5 N/mm", "--v0", "3 rpm"], ("--v0 3 rpm", "linear drive")),
    (["--stiffness", "2.5 lb", "--v0", "1"], ("--stiffness 2.5 lb", "linear stiffness")),
    (["--stiffness", "abc", "--v0", "1"], ("--stiffness", "not a number")),
])
def test_an_options_unit_of_the_wrong_kind_is_refused_naming_it(tmp_path, capsys, opts, needles):
    """--stiffness and --v0 may carry their unit ('2.5 N/mm', '6 deg/s');
    one of the wrong kind for the record (an angular speed for a linear
    drive), or not a unit at all, is one line naming the option, exit 2,
    and nothing written."""
    p = tmp_path / "lin.csv"
    t = np.arange(400) * 1e-3
    p.write_text("t [s],F [N]\n" + "".join(f"{a},{0.5 + 0.1 * np.sin(40 * a)}\n" for a in t))
    code, out, err = run(["diagnose", p, *opts, "-o", tmp_path / "o"], capsys)
    one_line_error(code, err, *needles)
    assert not (tmp_path / "o").exists()
