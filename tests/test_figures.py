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


def test_a_lienard_plane_is_fitted_to_its_trajectories_with_equal_scales():
    """The phase plane's axes hold the trajectories with a small margin and
    equal scales (a cycle is drawn round), whatever the characteristic's
    extent: a spiral of radius 0.2 about x = 6.2 is not drawn on -9..9."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    from lieng.programs.graf import lienard_view

    th = np.linspace(0, 12 * np.pi, 2000)
    r = 0.2 * np.exp(-0.03 * th)
    x, y = 6.2 + r * np.cos(th), r * np.sin(th)
    fig, ax = plt.subplots()
    ax.plot([-9, 9], [-60, 60], "k")          # a characteristic line far beyond the data
    lienard_view(ax, x, y)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert x0 < x.min() and x1 > x.max() and y0 < y.min() and y1 > y.max()
    assert x1 - x0 < 1.3 * np.ptp(x) and y1 - y0 < 1.3 * np.ptp(y)
    assert ax.get_aspect() == 1.0
    # a flat record (a decay to a point on the axis) keeps a readable height
    ax2 = fig.add_subplot(2, 1, 2)
    lienard_view(ax2, np.linspace(0, 10, 50), np.zeros(50))
    assert np.ptp(ax2.get_ylim()) >= 0.2 * np.ptp(ax2.get_xlim())
    plt.close(fig)
