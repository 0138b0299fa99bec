"""`lieng run lieng1`: outputs, the listing against gfortran, and every bad-deck case."""

import csv
import subprocess
import sys

import numpy as np
import pytest

import lieng.programs.listing as listing_mod
from lieng import read_deck
from lieng.cli import main

from conftest import CARDS

DEMO = CARDS / "lieng1_demo.dat"


def demo_lines():
    return DEMO.read_text().splitlines()


def put(line, c1, c2, text):
    """Replace columns c1..c2 (1-based) of a card with right-justified text."""
    line = line.ljust(80)
    w = c2 - c1 + 1
    return line[: c1 - 1] + text.rjust(w)[:w] + line[c2:]


def xchl_card(j):
    return 3 + (j - 1) // 5, 10 * ((j - 1) % 5) + 1   # 0-based line index, first column


def ychl_card(j):
    return 43 + (j - 1) // 5, 10 * ((j - 1) % 5) + 1


def run_cli(args, capsys):
    code = main(args)
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def test_demo_run_writes_everything(tmp_path, capsys):
    out = tmp_path / "o"
    code, _, err = run_cli(["run", "lieng1", str(DEMO), "-o", str(out)], capsys)
    assert code == 0, err
    names = {p.name for p in out.iterdir()}
    assert {"listing.txt", "trajectories.csv", "phase_plane.png", "displacement_time.png",
            "velocity_time.png"} <= names
    for png in out.glob("*.png"):
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    with open(out / "trajectories.csv") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["traj", "i", "x", "y", "t"]
    assert len(rows) == 1 + 9 * 3000
    assert rows[1][:2] == ["1", "1"] and rows[-1][:2] == ["9", "3000"]
    deck = read_deck(DEMO)
    assert float(rows[1][2]) == deck.xinp and float(rows[1][3]) == deck.yinp
    # the 9 starting points step by -XINCR, -YINCR
    starts = [(float(r[2]), float(r[3])) for r in rows[1:] if r[1] == "1"]
    for k, (x0, y0) in enumerate(starts):
        assert x0 == pytest.approx(deck.xinp - k * deck.xincr)
        assert y0 == pytest.approx(deck.yinp - k * deck.yincr)


def test_listing_table_prints_every_tenth_point(tmp_path, capsys):
    out = tmp_path / "o"
    assert run_cli(["run", "lieng1", str(DEMO), "-o", str(out), "--no-plots"], capsys)[0] == 0
    lines = (out / "listing.txt").read_text().splitlines()
    data = np.loadtxt(out / "trajectories.csv", delimiter=",", skiprows=1)
    traj1 = data[data[:, 0] == 1]
    # first table row of trajectory 1 follows the FORMAT 100 line of its start point
    i = next(k for k, ln in enumerate(lines) if ln.startswith("     8.000     1.000     0.000"))
    row = lines[i + 1]
    fields = [row[j: j + 21] for j in range(0, 126, 21)]
    for f, idx in zip(fields, [1, 11, 21, 31, 41, 51]):
        x, y, t, n = float(f[0:6]), float(f[6:11]), float(f[11:16]), int(f[16:21])
        assert n == idx
        assert x == pytest.approx(traj1[idx - 1, 2], abs=0.051)
        assert y == pytest.approx(traj1[idx - 1, 3], abs=0.051)


def test_listing_matches_gfortran_writing_the_same_formats(tmp_path, gfortran, monkeypatch):
    calls = []
    real_w = listing_mod._w

    def spy(records, fmt_no, *values, formats=listing_mod.FORMATS_LIENG1):
        calls.append((formats[fmt_no], values))
        real_w(records, fmt_no, *values, formats=formats)

    monkeypatch.setattr(listing_mod, "_w", spy)
    deck = read_deck(DEMO)
    res = deck.run()
    mine = listing_mod.lieng1_listing(deck, res)
    src = ["program p", "implicit none", "real(8) :: nan", "nan = 0d0", "nan = nan/nan"]
    for fmt, values in calls:
        lits = []
        for v in values:
            if isinstance(v, (int, np.integer)):
                lits.append(str(int(v)))
            elif np.isnan(v):
                lits.append("nan")
            else:
                lits.append(format(float(v), ".17e").replace("e", "d"))
        src.append(f'write(*,"{fmt}") ' + ", ".join(lits))
    src.append("end program p")
    f90 = tmp_path / "l.f90"
    f90.write_text("\n".join(src) + "\n")
    subprocess.run([gfortran, "-ffree-line-length-none", "-fno-range-check", str(f90), "-o", str(tmp_path / "l")],
                   check=True)
    got = subprocess.run([str(tmp_path / "l")], check=True, capture_output=True, text=True).stdout
    got = [ln.rstrip() for ln in got.split("\n")]
    assert got[: len(mine)] == mine
    assert mine[0].startswith("1LIENARD'S GRAPHICAL CONSTRACTION WITH DATA")


# --------------------------------------------------------------------------
# Bad decks: exit 2, one line naming card and columns, nothing written
# --------------------------------------------------------------------------


def bad_decks():
    L = demo_lines()
    n = int(L[2][:5])
    cases = {}
    d = list(L); d[2] = put(d[2], 1, 5, "201"); cases["N > 200"] = (d, "card 3, columns 1-5")
    d = list(L); d[2] = put(d[2], 1, 5, "2"); cases["N < 3"] = (d, "card 3, columns 1-5")
    d = list(L); d[2] = put(d[2], 1, 5, "1"); d[2] = d[2][:2] + "x" + d[2][3:]
    cases["non-numeric N"] = (d, "card 3, columns 1-5")
    d = list(L); li, c = xchl_card(7); d[li] = put(d[li], c, c + 9, "1.2.3")
    cases["non-numeric XCHL"] = (d, f"card {li + 1}, columns {c}-{c + 9}")
    # equal neighbouring XCHL: XCHL(5) = XCHL(4)
    d = list(L); li4, c4 = xchl_card(4); li5, c5 = xchl_card(5)
    d[li5] = put(d[li5], c5, c5 + 9, d[li4].ljust(80)[c4 - 1: c4 + 9].strip())
    cases["equal XCHL"] = (d, f"card {li5 + 1}, columns {c5}-{c5 + 9}")
    # YCHL not decreasing: YCHL(9) above YCHL(8)
    d = list(L); li, c = ychl_card(9); d[li] = put(d[li], c, c + 9, "999.0")
    cases["YCHL not decreasing"] = (d, f"card {li + 1}, columns {c}-{c + 9}")
    # no negative slope: XCHL = YCHL/2 (slope 2 everywhere)
    d = list(L)
    ys = [float(read_deck(DEMO).ychl[j]) for j in range(n)]
    for j in range(1, n + 1):
        li, c = xchl_card(j)
        d[li] = put(d[li], c, c + 9, f"{ys[j - 1] / 2:.4f}")
    cases["no negative slope"] = (d, "card 44, columns 1-10")
    cases["missing card"] = (L[:60], "card 61")
    cases["empty deck"] = ([], "card 1")
    d = list(L); d[2] = put(d[2], 46, 55, "0.0"); cases["DTHETA = 0"] = (d, "card 3, columns 46-55")
    return cases


@pytest.mark.parametrize("name", list(bad_decks()))
def test_bad_deck_exits_2_with_one_line(name, tmp_path, capsys):
    lines, where = bad_decks()[name]
    deck = tmp_path / "bad.dat"
    deck.write_text("\n".join(lines) + ("\n" if lines else ""))
    out = tmp_path / "out"
    code, stdout, err = run_cli(["run", "lieng1", str(deck), "-o", str(out)], capsys)
    assert code == 2
    err_lines = err.strip().splitlines()
    assert len(err_lines) == 1, err
    assert err_lines[0].startswith("lieng: error: ")
    assert where in err_lines[0], err_lines[0]
    assert "Traceback" not in err
    assert not out.exists()
    assert not any(p.name.startswith(".out") for p in tmp_path.iterdir())


def test_failed_run_leaves_existing_outdir_untouched(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "listing.txt").write_text("old\n")
    lines, _ = bad_decks()["equal XCHL"]
    deck = tmp_path / "bad.dat"
    deck.write_text("\n".join(lines) + "\n")
    assert run_cli(["run", "lieng1", str(deck), "-o", str(out)], capsys)[0] == 2
    assert [p.name for p in out.iterdir()] == ["listing.txt"]
    assert (out / "listing.txt").read_text() == "old\n"


def test_console_script_exit_status_and_no_traceback(tmp_path):
    deck = tmp_path / "bad.dat"
    deck.write_text("1\n")
    p = subprocess.run([sys.executable, "-m", "lieng.cli", "run", "lieng1", str(deck), "-o", str(tmp_path / "o")],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert p.stderr.count("\n") == 1 and "Traceback" not in p.stderr
    h = subprocess.run([sys.executable, "-m", "lieng.cli", "--help"], capture_output=True, text=True)
    assert h.returncode == 0 and "run" in h.stdout


def test_undefined_centre_interpolation_warns_and_completes(tmp_path, capsys):
    # run slopes -2, -2, -1: SLOPE(LLL) < SLOPE(MMM) and SLOPE(LLL+1) = SLOPE(LLL): BB = 0
    x = [0.0, -1.0, 0.0, 1.0, 3.0, 2.0]
    y = [20.0, 15.0, 13.0, 11.0, 9.0, 4.0]
    xs = x + [0.0] * 194
    ys = y + [0.0] * 194
    lines = ["1", f"{0.5:10.4f}{0.0:10.4f}", f"{6:5d}{0.0:10.2f}{0.0:10.2f}{2.0:10.2f}{1.0:10.2f}{0.01:10.2f}"]
    for arr in (xs, ys):
        lines += ["".join(f"{v:10.2f}" for v in arr[i:i + 5]) for i in range(0, 200, 5)]
    deck = tmp_path / "bb0.dat"
    deck.write_text("\n".join(lines) + "\n")
    out = tmp_path / "o"
    code, _, err = run_cli(["run", "lieng1", str(deck), "-o", str(out), "--no-plots"], capsys)
    assert code == 0
    assert "warning" in err and "divides by zero" in err
    listing = (out / "listing.txt").read_text()
    assert "FROM SLOPE(LLL).LT.SLOPE(MMM)" in listing and "UNDEF" in listing and "NaN" not in listing
    data = np.loadtxt(out / "trajectories.csv", delimiter=",", skiprows=1)
    assert np.all(np.isfinite(data))


def _png_width(path):
    """A PNG's width in pixels, from its IHDR chunk (plain bytes)."""
    return int.from_bytes(path.read_bytes()[16:20], "big")


def test_plots_in_the_format_and_resolution_asked_for(tmp_path, capsys):
    """--format svg|pdf writes every plot in that format (and names them so on
    the terminal); --dpi scales a PNG's pixels; the next run is PNG at 110
    dpi again; a resolution out of range is one line."""
    code, out, err = run_cli(["run", "lieng1", str(DEMO), "-o", str(tmp_path / "svg"), "--format", "svg"], capsys)
    assert code == 0, err
    svgs = sorted(p.name for p in (tmp_path / "svg").glob("*.svg"))
    assert svgs == ["displacement_time.svg", "phase_plane.svg", "velocity_time.svg"]
    assert not list((tmp_path / "svg").glob("*.png")) and all(n in out for n in svgs)
    assert (tmp_path / "svg" / svgs[0]).read_text()[:200].lstrip().startswith("<?xml")
    code, out, err = run_cli(["figures", "-o", str(tmp_path / "pdf"), "--only", "2.27", "--format", "pdf", "-q"],
                             capsys)
    assert code == 0, err
    assert (tmp_path / "pdf" / "fig_2_27.pdf").read_bytes()[:5] == b"%PDF-"
    for d, extra in (("a", []), ("b", ["--dpi", "220"])):
        assert run_cli(["run", "lieng1", str(DEMO), "-o", str(tmp_path / d), *extra], capsys)[0] == 0
    wa, wb = _png_width(tmp_path / "a" / "phase_plane.png"), _png_width(tmp_path / "b" / "phase_plane.png")
    assert wb == pytest.approx(2 * wa, rel=0.02)
    code, _, err = run_cli(["run", "lieng1", str(DEMO), "-o", str(tmp_path / "c"), "--dpi", "0"], capsys)
    assert code == 2 and "--dpi 0" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "c").exists()


def test_no_plots_imports_no_matplotlib(tmp_path):
    """--no-plots does not pay for matplotlib's import (issue #19)."""
    code = ("import sys; from lieng.cli import main; "
            f"assert main(['run', 'lieng1', {str(DEMO)!r}, '-o', {str(tmp_path / 'o')!r}, '--no-plots', '-q']) == 0; "
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
