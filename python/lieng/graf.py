"""matplotlib in place of the CALCOMP ``GRAF`` / ``ENPLOT`` calls.

``GRAF(X, Y, NUM, NCURVE, ..., XLABEL, ..., YLABEL, ...)`` drew NCURVE
curves whose points lie one after the other in X and Y, NUM(i) points for
the i-th.  :func:`graf` takes the same: a list of curves, each (x, y), and
writes a PNG.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["graf", "lieng1_plots", "mlien_plots"]


def graf(curves: Sequence[tuple], path, *, xlabel: str, ylabel: str, title: str, caption: str = "",
         labels: Sequence[str] | None = None, styles: Sequence[dict] | None = None,
         equal: bool = False) -> Path:
    """Draw curves as one GRAF call did and save a PNG.

    Parameters
    ----------
    curves : sequence of (x, y)
        The curves, in GRAF's order.
    path : path-like
        Where to write the PNG.
    xlabel, ylabel, title : str
        Axis labels (with units) and title.
    caption : str, optional
        A line under the plot naming the thesis figure or section.
    labels : sequence of str, optional
        Legend entries.
    styles : sequence of dict, optional
        matplotlib keyword arguments per curve.
    equal : bool, optional
        Equal scales on both axes (the Lienard plane, where the construction
        is geometric).
    """
    fig, ax = plt.subplots(figsize=(8.2, 5.6), dpi=110)
    for i, (x, y) in enumerate(curves):
        kw = dict(styles[i]) if styles is not None and i < len(styles) else {"lw": 0.9}
        if labels is not None and i < len(labels) and labels[i]:
            kw["label"] = labels[i]
        ax.plot(np.asarray(x), np.asarray(y), **kw)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=11)
    ax.grid(True, lw=0.3, alpha=0.6)
    ax.axhline(0.0, color="0.5", lw=0.5)
    if equal:
        ax.set_aspect("equal", adjustable="datalim")
    if labels is not None:
        ax.legend(fontsize=7, loc="best", ncol=2)
    if caption:
        fig.text(0.01, 0.005, caption, fontsize=7, color="0.3", ha="left", va="bottom")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    p = Path(path)
    fig.savefig(p)
    plt.close(fig)
    return p


def lieng1_plots(result, outdir) -> list[Path]:
    """The three GRAF plots of LIENG-1: phase plane with the characteristic,
    displacement-time and velocity-time, every 10th point of each trajectory
    (as the listing passes X(10), X(20), ... to GRAF)."""
    outdir = Path(outdir)
    sel = slice(9, None, 10)
    trajs = [(result.x[k, sel], result.y[k, sel], result.t[k, sel]) for k in range(result.ntraj)]
    labels = [f"traj {k + 1}: start ({result.starts[k, 0]:g}, {result.starts[k, 1]:g})" for k in range(result.ntraj)]
    cap = "LIENG-1 (Antoniou 1971, App. 4): Lienard's construction, DTHETA = %g" % result.dtheta
    paths = [
        graf([(result.xchl, result.ychl)] + [(x, y) for x, y, _ in trajs], outdir / "phase_plane.png",
             xlabel="displacement x (mm)", ylabel="velocity v (mm/s)",
             title="Phase portrait in the Lienard plane with the characteristic line",
             caption=cap, labels=["characteristic line"] + labels,
             styles=[{"color": "k", "lw": 1.6}] + [{"lw": 0.8}] * len(trajs), equal=True),
        graf([(t, x) for x, _, t in trajs], outdir / "displacement_time.png",
             xlabel="time T (1/omega_n units)", ylabel="displacement x (mm)",
             title="Displacement against time", caption=cap, labels=labels),
        graf([(t, y) for _, y, t in trajs], outdir / "velocity_time.png",
             xlabel="time T (1/omega_n units)", ylabel="velocity v (mm/s)",
             title="Velocity against time", caption=cap, labels=labels),
    ]
    return paths


def mlien_plots(result, outdir) -> list[Path]:
    """The three GRAF plots of MLIEN: the phase plane with the last position
    of the characteristic, x-t and v-t, every 5th point (X(5), X(10), ...)."""
    outdir = Path(outdir)
    sel = slice(4, None, 5)
    x, y, t = result.x[sel], result.y[sel], result.t[sel]
    a = result.trigger
    cap = (f"MLIEN (Antoniou 1971, App. 6): v0 = {result.ampv0:g} cos({result.omega:g} t), DTHETA = "
           f"{result.dtheta:g}, triggering OMINTR={a[0]:g} OMETRI={a[1]:g} ATRI={a[2]:g} BTRI={a[3]:g}")
    return [
        graf([(result.xchl_last, result.ychl_last), (x, y)], outdir / "phase_plane.png",
             xlabel="displacement x (mm)", ylabel="velocity v (mm/s)",
             title="Phase plane with the last position of the characteristic", caption=cap,
             labels=["characteristic (last position)", "trajectory"],
             styles=[{"color": "k", "lw": 1.6}, {"lw": 0.8}], equal=True),
        graf([(t, x)], outdir / "displacement_time.png", xlabel="time T (1/omega_n units)",
             ylabel="displacement x (mm)", title="Displacement against time", caption=cap),
        graf([(t, y), (result.t, result.ymdl)], outdir / "velocity_time.png", xlabel="time T (1/omega_n units)",
             ylabel="velocity v (mm/s)", title="Velocity against time, with the driving velocity VO(t)",
             caption=cap, labels=["trajectory", "VO = YMDL of the moved characteristic"],
             styles=[{"lw": 0.9}, {"color": "0.4", "lw": 0.8, "ls": "--"}]),
    ]
