"""``lieng figures``: the thesis's theoretical figures regenerated from the
decks in ``cards/figures`` (written by ``cards/make_figure_decks.py``) and
``cards/mlien_a9_7.dat``.

Each PNG is captioned with the section it reproduces and what the text says
of it; the figures themselves are lost in the seed's OCR, so each shows the
claim the text makes, computed by the restored programs (LIENG-1, MLIEN) and
by :mod:`lieng.cycles` (exact mode).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lieng.programs import read_deck
from lieng.errors import LiengInputError

__all__ = ["FIGURES", "PANELS", "figures", "CARDS"]

#: the demo and figure decks installed with the package (the project's cards/)
CARDS = Path(__file__).resolve().parents[1] / "cards"


def _installed(rel: str) -> Path:
    """A deck installed with the package, found through the package's
    resources (so that an editable install finds the project's cards/)."""
    import importlib.resources

    r = importlib.resources.files("lieng") / "cards"
    for part in rel.split("/"):
        r = r / part
    return Path(str(r))

#: figure -> (deck(s) in the cards directory, caption)
FIGURES = {
    "2.22": (["figures/fig2_22.dat"], "Fig. 2.22 (ch. 2.3.1.4): trajectories from inside and outside reach the "
             "limit cycle (LIENG-1, 9 trajectories)"),
    "2.23": (["figures/fig2_23_stable.dat", "figures/fig2_23_unstable.dat"],
             "Fig. 2.23 (ch. 2.3.1.3): the slope of the characteristic at the origin decides its stability "
             "(left: rising part, stable; right: falling part, unstable)"),
    "2.26": (["figures/fig2_26.dat"], "Fig. 2.26 (ch. 2.4.2.1): v0 below the first critical velocity (on the "
             "stick part): the bodies come to rest, no oscillation"),
    "2.27": (["figures/fig2_27.dat"], "Fig. 2.27 (ch. 2.4.2.1, Table 2.IV): S.L.C. and U.L.C. amplitudes against "
             "the driving velocity; they merge at v_oc"),
    "2.28": (["figures/fig2_28.dat"], "Fig. 2.28 (ch. 2.4.2.2): amplitude against dmu0 = mu_s - mu_k0 at a fixed "
             "v0; below dmu_oc no self-sustained oscillation"),
    "2.29": (["figures/fig2_29_arc.dat", "figures/fig2_29_circle.dat"],
             "Fig. 2.29 (ch. 2.4.2.3): slopes of the two parts: zero and infinite -> a circular arc closed by a "
             "straight part (left); both infinite -> circles, a conservative system (right; LIENG-1's tangent step "
             "adds a little energy each turn, so its circles open slowly)"),
    **{f"A9-{k}": ([f"figures/figA9_{k}.dat"],
                   f"Fig. A9-{k} (App. 9): the characteristic's geometry ("
                   + ["the reference line", "a flatter falling part", "a steeper falling part",
                      "a higher static peak", "a steeper rising part", "a wider stick part"][k - 1]
                   + ") -> a trajectory and its displacement against time") for k in range(1, 7)},
    "A9-7": (["mlien_a9_7.dat"], "Fig. A9-7 (App. 9, App. 6): MLIEN, v0 = v0(t) and the triggering "
             "oscillation in the formation of the trajectories"),
}


#: deck -> the title of its panel (what it shows, not the file's name)
PANELS = {
    "figures/fig2_22.dat": "trajectories from inside and outside the limit cycle",
    "figures/fig2_23_stable.dat": "rising characteristic at the origin: stable",
    "figures/fig2_23_unstable.dat": "falling characteristic at the origin: unstable",
    "figures/fig2_26.dat": "v0 on the stick part: the bodies come to rest",
    "figures/fig2_27.dat": "limit cycles against the driving velocity",
    "figures/fig2_28.dat": "limit cycles against the friction difference",
    "figures/fig2_29_arc.dat": "slopes zero and infinite: an arc closed by a straight part",
    "figures/fig2_29_circle.dat": "both slopes infinite: circles",
    "mlien_a9_7.dat": "phase plane with the characteristic's last position",
    **{f"figures/figA9_{k}.dat": f"Fig. A9-{k}: phase plane" for k in range(1, 7)},
}


def _fig(ncols=1):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, ncols, figsize=(6.5 * ncols, 5.2), dpi=110, squeeze=False)
    return fig, axes[0]


def _save(fig, path: Path, caption: str) -> Path:
    from lieng.programs.graf import save

    fig.text(0.01, 0.01, caption, fontsize=7.5, color="0.25", wrap=True)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return save(fig, path, caption.split(" (")[0], caption)


def _phase(ax, res, title, every=5):
    from lieng.programs.graf import lienard_view

    ax.plot(res.xchl, res.ychl, "k", lw=1.5, label="characteristic line")
    for k in range(res.x.shape[0]):
        ax.plot(res.x[k, ::every], res.y[k, ::every], lw=0.7, label="trajectories" if k == 0 else None)
    ax.set_xlabel("displacement x (mm)")
    ax.set_ylabel("velocity v (mm/s)")
    ax.set_title(title, fontsize=9)
    lienard_view(ax, list(res.x), list(res.y))
    ax.legend(fontsize=7, loc="upper right", framealpha=0.85)


def _lieng1(cards, name: str, ntraj=9, npts=3000):
    from lieng.programs.lieng1 import run_deck

    return run_deck(read_deck(cards(name), program="lieng1"), ntraj=ntraj, npts=npts)


def _plot_phase_figs(cards, decks, path, caption, ntraj):
    fig, axes = _fig(len(decks))
    for ax, name in zip(axes, decks):
        res = _lieng1(cards, name, ntraj=ntraj)
        _phase(ax, res, PANELS.get(name, Path(name).name))
    return _save(fig, path, caption)


def _sweep_fig(cards, name, path, caption, kind):
    from lieng.analysis.cycles import sweep_dmu, sweep_v0

    deck = read_deck(cards(name), program="lieng1")
    x, y = deck.xchl[: deck.n], deck.ychl[: deck.n]
    if kind == "v0":
        vals = np.linspace(0.2, 30.0, 60)
        s = sweep_v0(x, y, vals, progress=False)
        xlabel, crit, unit = "driving velocity v0 (mm/s)", "v_oc", " mm/s"
    else:
        vals = np.linspace(0.1, 2.0, 40)
        s = sweep_dmu(x, y, vals, progress=False)
        xlabel, crit, unit = "dmu0 / dmu0 of the deck", "dmu_oc", " of the deck's dmu0"
    fig, (ax,) = _fig()
    sa = np.array([np.nan if a is None else a for a in s.stable_amplitude])
    ua = np.array([np.nan if a is None else a for a in s.unstable_amplitude])
    ax.plot(vals, sa, "o-", ms=3, label="S.L.C. (stable)")
    ax.plot(vals, ua, "s--", ms=3, label="U.L.C. (unstable)")
    if s.v_oc is not None:
        ax.axvline(s.v_oc, color="0.4", ls=":", label=f"{crit} = {s.v_oc:.4g}{unit}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("limit-cycle amplitude X_right - X_left (mm)")
    ax.legend(fontsize=8)
    ax.set_title(PANELS.get(name, Path(name).name), fontsize=9)
    return _save(fig, path, caption + " (amplitude: the distance between the cycle's two crossings of the "
                 "displacement axis, as the thesis measures it)")


def _a9(cards, name, path, caption):
    res = _lieng1(cards, name, ntraj=1, npts=3000)
    fig, axes = _fig(2)
    _phase(axes[0], res, PANELS.get(name, Path(name).name), every=2)
    axes[1].plot(res.t[0], res.x[0], lw=0.8)
    axes[1].set_xlabel("time T (1/omega_n units)")
    axes[1].set_ylabel("displacement x (mm)")
    axes[1].set_title("displacement against time (the same trajectory)", fontsize=9)
    return _save(fig, path, caption)


def _a9_7(cards, name, path, caption):
    from lieng.programs.mlien import run_deck

    deck = read_deck(cards(name), program="mlien")
    res = run_deck(deck)
    fig, axes = _fig(2)
    from lieng.programs.graf import lienard_view

    axes[0].plot(res.xchl_last, res.ychl_last, "k", lw=1.5, label="characteristic (last position)")
    axes[0].plot(res.x, res.y, lw=0.6, label="trajectory")
    axes[0].set_xlabel("displacement x (mm)")
    axes[0].set_ylabel("velocity v (mm/s)")
    axes[0].set_title(PANELS.get(name, name), fontsize=9)
    lienard_view(axes[0], res.x, res.y)
    axes[0].legend(fontsize=7, loc="upper right", framealpha=0.85)
    axes[1].set_title("velocity against time, with the driving velocity", fontsize=9)
    axes[1].plot(res.t, res.y, lw=0.6, label="velocity")
    axes[1].plot(res.t, res.ymdl, lw=1.0, label="driving velocity v0(t)")
    axes[1].set_xlabel("time T (1/omega_n units)")
    axes[1].set_ylabel("velocity v (mm/s)")
    axes[1].legend(fontsize=8)
    return _save(fig, path, caption)


def figures(outdir, cards=None, only=None) -> list[Path]:
    """Regenerate the theoretical figures into ``outdir``.

    Parameters
    ----------
    outdir : path-like
        An existing directory.
    cards : path-like, optional
        A directory laid out as the project's ``cards/`` (with ``figures/``);
        by default the decks installed with the package (:data:`CARDS`).
    only : iterable of str, optional
        Figure names (keys of :data:`FIGURES`); all by default.

    Returns
    -------
    list of Path
        The plots written, ``fig_<name>.png`` (or the format chosen by
        :func:`lieng.outputs.plot_output`).
    """
    outdir = Path(outdir)
    # where(deck) -> its path; the helpers below read decks through it
    where = _installed if cards is None else (lambda d, c=Path(cards): c / d)
    names = list(FIGURES) if only is None else list(only)
    for n in names:
        if n not in FIGURES:
            raise LiengInputError(f"figure {n!r}: choose from {', '.join(FIGURES)}")
        for d in FIGURES[n][0]:
            if not where(d).is_file():
                raise LiengInputError(f"{where(d)}: deck of Fig. {n} not found (--cards names a directory like "
                                      f"the project's cards/, with figures/; cards/make_figure_decks.py writes them)")
    out = []
    for n in names:
        decks, cap = FIGURES[n]
        path = outdir / f"fig_{n.replace('.', '_')}.png"
        if n in ("2.22", "2.26"):
            out.append(_plot_phase_figs(where, decks, path, cap, 9))
        elif n in ("2.23", "2.29"):
            out.append(_plot_phase_figs(where, decks, path, cap, 6))
        elif n == "2.27":
            out.append(_sweep_fig(where, decks[0], path, cap, "v0"))
        elif n == "2.28":
            out.append(_sweep_fig(where, decks[0], path, cap, "dmu"))
        elif n == "A9-7":
            out.append(_a9_7(where, decks[0], path, cap))
        else:
            out.append(_a9(where, decks[0], path, cap))
    return out
