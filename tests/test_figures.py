"""`lieng figures`: every theoretical figure the text describes, from a deck in cards/, captioned."""

from PIL import Image

from lieng.cli import main
from lieng.analysis.figures import FIGURES

from conftest import CARDS

EXPECTED = {"2.22", "2.23", "2.26", "2.27", "2.28", "2.29", *(f"A9-{k}" for k in range(1, 8))}


def test_every_figure_is_written_and_captioned(tmp_path, capsys):
    out = tmp_path / "figs"
    assert set(FIGURES) == EXPECTED
    code = main(["figures", "-o", str(out), "--cards", str(CARDS), "-q"])
    assert code == 0
    for name in EXPECTED:
        png = out / f"fig_{name.replace('.', '_')}.png"
        assert png.is_file(), png
        meta = Image.open(png).text
        assert meta["Title"] == f"Fig. {name}"
        assert "ch." in meta["Description"] or "App." in meta["Description"]
    # every deck a figure names is shipped
    for decks, _ in FIGURES.values():
        assert all((CARDS / d).is_file() for d in decks)


def test_unknown_figure_or_missing_cards_exit_2(tmp_path, capsys):
    assert main(["figures", "-o", str(tmp_path / "a"), "--cards", str(CARDS), "--only", "9.99"]) == 2
    err = capsys.readouterr().err
    assert "9.99" in err and err.count("\n") == 1 and not (tmp_path / "a").exists()
    assert main(["figures", "-o", str(tmp_path / "b"), "--cards", str(tmp_path)]) == 2
    assert "not found" in capsys.readouterr().err and not (tmp_path / "b").exists()
