"""Card decks: Fortran input semantics, output editing against gfortran, round trips."""

import subprocess

import numpy as np
import pytest

from lieng import LiengInputError, read_deck, write_deck
from lieng.io.cards import Card, _flatten, parse_format, read_cards, read_record, write_record
from lieng.programs.lieng1 import Deck

from conftest import CARDS


@pytest.mark.parametrize(
    "text, fmt, expected",
    [
        ("      1234", "(F10.2)", 12.34),        # implied decimal point
        ("    12.345", "(F10.2)", 12.345),       # a written point overrides d
        ("        12", "(F10.4)", 0.0012),
        ("          ", "(F10.2)", 0.0),          # blank field reads zero
        ("  12 ", "(I5)", 120),                  # blanks are zeros (BZ, as on cards)
        ("   12", "(I5)", 12),
        ("  -12", "(I5)", -12),
        ("- 1 2", "(I5)", -102),
        ("     1.5E2", "(F10.2)", 150.0),
        ("     1.5+2", "(F10.2)", 150.0),        # exponent without a letter
        ("    -1.5D-1", "(F11.2)", -0.15),
        ("      15E1", "(F10.2)", 1.5),          # implied decimal then exponent
        ("     -.5  ", "(F10.2)", -0.5),         # trailing blanks after a point are zeros
        ("    1 .5  ", "(F10.2)", 10.5),         # an embedded blank is a zero
        ("1", "(I1)", 1),
        ("    1.5E  ", "(F10.2)", 1.5),         # exponent digits blank: E00
    ],
)
def test_field_semantics(text, fmt, expected):
    assert read_record(text, fmt) == [expected]


def test_short_line_is_padded_with_blanks():
    vals = read_record("   43      1.00", "(I5,5F10.2)")
    assert vals == [43, 1.0, 0.0, 0.0, 0.0, 0.0]


def test_implied_decimal_exact_value():
    # 0.1 + 0.2 style rounding must not creep in: the value is the decimal read
    assert read_record("       123", "(F10.2)")[0] == 1.23
    assert read_record("  33333333", "(F10.8)")[0] == 0.33333333


@pytest.mark.parametrize("text", ["    1.2.3 ", "     abc  ", "    --1   ", "         -"])
def test_non_numeric_field_raises(text):
    with pytest.raises(ValueError):
        read_record(text, "(F10.2)")


def test_read_cards_names_card_and_columns():
    layout = [Card("(I5,2F10.2)", ("N", "A", "B"))]
    with pytest.raises(LiengInputError, match=r"card 1, columns 16-25 \(B, F10.2\)"):
        read_cards(["    3      1.00      x.00"], layout, "d")


def test_missing_card_named():
    layout = [Card("(I1)", ("KEY",)), Card("(2F10.4)", ("XINCR", "YINCR"))]
    with pytest.raises(LiengInputError, match=r"card 2 .*missing"):
        read_cards(["1"], layout, "d")


def test_format_parser_hollerith_keeps_blanks():
    g = parse_format("(1H1,5H A  B,2X,I3)")
    texts = [it.text for it in g.items if it.kind == "H"]
    assert texts == ["1", " A  B"]
    assert write_record("(1H1,5H A  B,2X,I3)", [7]) == ["1 A  B    7"]


def test_format_reversion_and_slash():
    # (2I3) with 5 values: three records; a trailing / ends one more
    assert write_record("(2I3)", [1, 2, 3, 4, 5]) == ["  1  2", "  3  4", "  5"]
    assert write_record("(I3/)", [1]) == ["  1", ""]
    assert write_record("(///I2)", [5]) == ["", "", "", " 5"]


# --------------------------------------------------------------------------
# Output editing against gfortran's runtime (an independent implementation)
# --------------------------------------------------------------------------

FORMATS = ["(F10.2)", "(F6.1)", "(F5.1)", "(F20.8)", "(F10.5)", "(F3.0)", "(E10.4)", "(E12.5)",
           "(I5)", "(I7)", "(3F10.3)", "(2F50.8)", "(6(F6.1,2F5.1,I5))", "(I7,2X,2(F20.4,2X)/55X,3(F20.8,2X))"]


def _fortran_literal(v):
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    return format(float(v), ".17e").replace("e", "d")


def test_output_editing_matches_gfortran(gfortran, tmp_path):
    r = np.random.default_rng(1971)
    cases = []
    for fmt in FORMATS:
        edits = [e for e in _flatten(parse_format(fmt)) if e.kind in "IFED"]
        for _ in range(40):
            vals = []
            for e in edits:
                if e.kind == "I":
                    vals.append(int(r.integers(-99999, 99999) // 10 ** r.integers(0, 5)))
                else:
                    mag = 10.0 ** r.uniform(-6, 6)
                    v = float(r.choice([-1, 1]) * mag)
                    if r.random() < 0.15:  # exact ties and short decimals
                        v = float(r.choice([0.125, -0.375, 2.5, 0.05, 0.0, 999.95, 1e-9, 12345.678]))
                    vals.append(v)
            cases.append((fmt, vals))
    src = ["program p", "implicit none"]
    for fmt, vals in cases:
        lits = ", ".join(_fortran_literal(v) for v in vals)
        src.append(f"write(*,'{fmt}') {lits}")
    src.append("end program p")
    f90 = tmp_path / "w.f90"
    f90.write_text("\n".join(src) + "\n")
    exe = tmp_path / "w"
    subprocess.run([gfortran, "-ffree-line-length-none", str(f90), "-o", str(exe)], check=True)
    got = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout.split("\n")
    mine = []
    for fmt, vals in cases:
        mine.extend(write_record(fmt, vals))
    assert got[: len(mine)] == mine


# --------------------------------------------------------------------------
# Decks
# --------------------------------------------------------------------------


def test_demo_deck_reads(tmp_path):
    deck = read_deck(CARDS / "lieng1_demo.dat", program="lieng1")
    assert deck.key == 1
    assert 3 <= deck.n <= 200
    assert np.all(np.diff(deck.ychl[: deck.n]) < 0)


def test_deck_round_trip_exact(tmp_path):
    deck = read_deck(CARDS / "lieng1_demo.dat", program="lieng1")
    p = tmp_path / "copy.dat"
    write_deck(deck, p)
    again = read_deck(p, program="lieng1")
    for name, v in deck.values().items():
        assert again.values()[name] == v, name


def test_deck_round_trip_random_values(tmp_path):
    r = np.random.default_rng(5)
    n = 120
    y = np.sort(r.uniform(-50, 50, n))[::-1]
    y = np.round(y, 4)
    y = np.unique(y)[::-1]
    n = y.size
    x = np.round(np.cumsum(r.uniform(0.01, 1, n)) - 30.0, 3)  # increasing: no equal neighbours
    deck = Deck(key=0, xincr=r.uniform(-1, 1), yincr=0.0001234, n=n, omega=1.0 / 3.0, ampv0=12.5,
                xinp=float(x[0]), yinp=1e-7, dtheta=0.005,
                xchl=np.concatenate([x, np.zeros(200 - n)]), ychl=np.concatenate([y, np.zeros(200 - n)]))
    p = tmp_path / "r.dat"
    write_deck(deck, p)
    lines = p.read_text().splitlines()
    assert len(lines) == 83 and all(len(ln) <= 80 for ln in lines)
    once = read_deck(p, program="lieng1")
    # values that fit in the fields come back exactly; 1/3 and a random float as close as 10 columns allow
    assert once.xchl[:n].tolist() == x.tolist()
    assert once.ychl[:n].tolist() == y.tolist()
    assert once.yincr == 0.0001234 and once.yinp == 1e-7 and once.dtheta == 0.005
    assert abs(once.omega - 1 / 3) < 1e-8 and abs(once.xincr - deck.xincr) < 1e-8
    p2 = tmp_path / "r2.dat"
    write_deck(once, p2)
    assert read_deck(p2, program="lieng1").values() == once.values()
