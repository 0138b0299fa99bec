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

from lieng.io.outputs import plot_settings  # noqa: E402

__all__ = ["graf", "lieng1_plots", "mlien_plots", "trc_plots", "save", "finish", "lienard_view"]


def save(fig, path, title: str = "", description: str = "") -> Path:
    """Save and close a figure in the format and resolution the command chose
    (:func:`lieng.outputs.plot_output`), with its title and caption in the
    file's metadata; returns the path written."""
    fmt, dpi = plot_settings()
    p = Path(path).with_suffix("." + fmt)
    meta = {}
    if title:
        meta["Title"] = title
    if description:
        meta["Subject" if fmt == "pdf" else "Description"] = description
    fig.savefig(p, dpi=dpi, metadata=meta)
    plt.close(fig)
    return p


def lienard_view(ax, xs, ys, pad: float = 0.08) -> None:
    """Fit a phase plane's axes to its trajectories (``xs``, ``ys``: arrays
    or sequences of arrays) with equal scales on both axes: the box takes
    the data's shape, so that a cycle is drawn round and fills the plot; a
    characteristic line reaching beyond the trajectories is cut at the
    axes."""
    def flat(v):
        return np.concatenate([np.ravel(np.asarray(a, float)) for a in (v if isinstance(v, (list, tuple)) else [v])])

    x, y = flat(xs), flat(ys)
    ok = np.isfinite(x) & np.isfinite(y)
    if not np.any(ok):
        return
    x, y = x[ok], y[ok]
    (x0, x1), (y0, y1) = (float(x.min()), float(x.max())), (float(y.min()), float(y.max()))
    span = max(x1 - x0, y1 - y0, 1e-12)
    # neither side thinner than a fifth of the other (a decay to a point stays readable)
    cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    hx, hy = max(0.5 * (x1 - x0), 0.1 * span), max(0.5 * (y1 - y0), 0.1 * span)
    hx, hy = hx + pad * span, hy + pad * span
    ax.set_xlim(cx - hx, cx + hx)
    ax.set_ylim(cy - hy, cy + hy)
    ax.set_aspect("equal", adjustable="box")


def graf(curves: Sequence[tuple], path, *, xlabel: str, ylabel: str, title: str, caption: str = "",
         labels: Sequence[str] | None = None, styles: Sequence[dict] | None = None,
         equal: bool = False, xlim: tuple | None = None, fit: Sequence[int] | None = None) -> Path:
    """Draw curves as one GRAF call did and save the plot (a PNG unless
    the command chose another format: :func:`lieng.outputs.plot_output`).

    Parameters
    ----------
    curves : sequence of (x, y)
        The curves, in GRAF's order.
    path : path-like
        Where to write the plot (its suffix follows the format).
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
        is geometric), the axes fitted to the curves (:func:`lienard_view`).
    xlim : (float, float), optional
        Abscissa limits (points outside are still drawn, off the axes).
    fit : sequence of int, optional
        With ``equal``: the curves the axes are fitted to (default all; a
        characteristic line reaching far beyond the trajectories is left
        out, and cut at the axes).
    """
    p = Path(path).with_suffix("." + plot_settings()[0])
    fig, ax = plt.subplots(figsize=(8.2, 5.6), dpi=110)
    try:
        _draw(fig, ax, curves, p, xlabel, ylabel, title, caption, labels, styles, equal, xlim, fit)
    except (ValueError, OverflowError, np.linalg.LinAlgError) as exc:
        # matplotlib's transforms fail on axis ranges near the largest doubles
        import warnings

        warnings.warn(f"{p.name} not drawn: the values are too large to plot ({type(exc).__name__})", stacklevel=2)
        if p.exists():
            p.unlink()
    finally:
        plt.close(fig)
    return p


def _draw(fig, ax, curves, p, xlabel, ylabel, title, caption, labels, styles, equal, xlim, fit) -> None:
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
        sel = [curves[i] for i in (range(len(curves)) if fit is None else fit)]
        lienard_view(ax, [c[0] for c in sel], [c[1] for c in sel])
    if xlim is not None:
        ax.set_xlim(*xlim)
    if labels is not None:
        if equal:                       # beside the fitted box, off the data
            ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
        else:
            ax.legend(fontsize=7, loc="upper right", ncol=2 if len(labels) > 4 else 1, framealpha=0.85)
    if caption:
        fig.text(0.01, 0.005, caption, fontsize=7, color="0.3", ha="left", va="bottom", wrap=True)
    fig.tight_layout(rect=(0, 0.03 if len(caption) < 150 else 0.05, 1, 1))
    save(fig, p, title, caption)


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
             styles=[{"color": "k", "lw": 1.6}] + [{"lw": 0.8}] * len(trajs), equal=True,
             fit=range(1, len(trajs) + 1)),
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
             styles=[{"color": "k", "lw": 1.6}, {"lw": 0.8}], equal=True, fit=[1]),
        graf([(t, x)], outdir / "displacement_time.png", xlabel="time T (1/omega_n units)",
             ylabel="displacement x (mm)", title="Displacement against time", caption=cap),
        graf([(t, y), (result.t, result.ymdl)], outdir / "velocity_time.png", xlabel="time T (1/omega_n units)",
             ylabel="velocity v (mm/s)", title="Velocity against time, with the driving velocity VO(t)",
             caption=cap, labels=["trajectory", "VO = YMDL of the moved characteristic"],
             styles=[{"lw": 0.9}, {"color": "0.4", "lw": 0.8, "ls": "--"}]),
    ]


def _clip(a, lim):
    """The listing's plot clips (loops 1230, 1240): |value| > lim drawn at +-lim."""
    return np.clip(np.asarray(a, float), -lim, lim)


def _robust_xlim(*arrays):
    """Limits holding the 3rd-97th percentiles, widened: the reverse
    construction's few ill-conditioned points near the abscissa would
    otherwise flatten the characteristic to a line."""
    a = np.concatenate([np.asarray(x, float).ravel() for x in arrays])
    a = a[np.isfinite(a)]
    if a.size < 5:
        return None
    lo, hi = np.percentile(a, [3, 97])
    pad = 0.4 * (hi - lo) if hi > lo else 1.0
    return (lo - pad, hi + pad)


def _beyond(lim, *arrays) -> str:
    """A caption's note of the constructed points beyond the abscissa limits
    ``lim`` (ill-conditioned where the velocity changes sign)."""
    a = np.concatenate([np.asarray(x, float).ravel() for x in arrays if x is not None])
    if lim is None or a.size == 0:
        return ""
    out = int(np.count_nonzero(~((a >= lim[0]) & (a <= lim[1]))))
    return f"; {out} of {a.size} points beyond the axes (near v = 0)" if out else ""


def trc_plots(result, outdir) -> list[Path]:
    """The GRAF plots of TRC (App. 7): the Lisitsyn ellipse x-xn, both phase
    planes, the apparent coefficient of friction against velocity, the
    trajectories and the characteristic lines in the shifted Lienard plane,
    and the non-dimensional coefficient of friction.  Curves of the normal
    mode are drawn only when the trace has one.  Points 1 and NN of the
    characteristic are not constructed by the listing and are left out."""
    r = result
    outdir = Path(outdir)
    inner = slice(1, r.nn - 1)
    cap = (f"TRC (Antoniou 1971, App. 7; ch. 3.3): {r.nn} points, OMNH = {r.omnh:g} rad/s"
           + (f", OMNV = {r.omnv:g} rad/s" if r.has_normal else "") + f"; origin ({r.origin}) EL = {r.el:.4g} mm")
    two = r.has_normal
    hn = ["horizontal (friction) mode", "normal mode"]
    paths = []
    if two:
        paths.append(graf([(r.x, r.xn)], outdir / "lisitsyn_ellipse.png", xlabel="friction displacement x (mm)",
                          ylabel="normal displacement xn (mm)", title="Lisitsyn plot: normal against "
                          "friction displacement (an ellipse when the two modes are out of phase, a line when in "
                          "phase)", caption=cap + "  (ch. 3.3.1, App. 5)"))
    paths.append(graf([(r.x[1:], r.v[1:])] + ([(r.xn[1:], r.vn[1:])] if two else []), outdir / "phase_planes.png",
                      xlabel="displacement (mm)", ylabel="velocity (mm/s)",
                      title="Experimental phase-plane trajectories", caption=cap, labels=hn[: 1 + two]))
    if two:
        paths.append(graf([(-r.v[1:], _clip(r.am[1:], 3.0))], outdir / "apparent_mu.png",
                          xlabel="-v: the body's velocity, sign reversed, as TRC plots it (mm/s)", ylabel="apparent coefficient of friction X/XN",
                          title="Apparent coefficient of friction against velocity", caption=cap + "  (Fig. 3.21)",
                          styles=[{"ls": "none", "marker": ".", "ms": 3}]))
    paths.append(graf([(r.xlnr, r.vln)] + ([(r.xnlnr, r.vnln)] if two else []), outdir / "lienard_phase_planes.png",
                      xlabel="displacement from the origin (mm)", ylabel="velocity / natural frequency (mm)",
                      title="Trajectories in the Lienard plane (smoothed by BELFIT)", caption=cap,
                      labels=hn[: 1 + two], equal=True))
    pts = [{"ls": "none", "marker": ".", "ms": 3}] * 2
    xl = _robust_xlim(r.xx[inner], r.xxn[inner] if two else r.xx[inner])
    ml = _robust_xlim(r.amt[inner], r.amtn[inner] if two else r.amt[inner])
    paths.append(graf([(_clip(r.xx[inner], 20.0), r.yy[inner])]
                      + ([(_clip(r.xxn[inner], 20.0), r.yyn[inner])] if two else []),
                      outdir / "characteristic.png", xlabel="characteristic x = -phi(v) (mm)",
                      ylabel="velocity / natural frequency (mm)",
                      title="Experimental characteristic lines (reverse Lienard construction)",
                      caption=cap + "  (ch. 3.3.3, Fig. 4.1)" + _beyond(xl, r.xx[inner], r.xxn[inner] if two else None),
                      labels=hn[: 1 + two], styles=pts, xlim=xl))
    paths.append(graf([(_clip(r.amt[inner], 3.0), r.yy[inner])]
                      + ([(_clip(r.amtn[inner], 3.0), r.yyn[inner])] if two else []),
                      outdir / "nondim_mu.png", xlabel="non-dimensional coefficient of friction (mu - mu(0))",
                      ylabel="velocity / natural frequency (mm)", title="Coefficient of friction against velocity",
                      caption=cap + _beyond(ml, r.amt[inner], r.amtn[inner] if two else None), labels=hn[: 1 + two],
                      styles=pts, xlim=ml))
    return paths


def finish(fig, ax, caption: str, path) -> Path:
    """Legend(s) (where the caller placed none: upper right), a caption line
    under the plot, save (:func:`save`) and close: the last steps of every analysis plot (diagnose, twodof).  ``ax``
    may be one axis or a sequence of axes.  Returns the path written."""
    for a in (ax if isinstance(ax, (list, tuple, np.ndarray)) else [ax]):
        if a.get_legend_handles_labels()[0] and a.get_legend() is None:
            a.legend(fontsize=8, loc="upper right", framealpha=0.85)
    fig.text(0.01, 0.005, caption, fontsize=7, color="0.3", wrap=True)
    fig.tight_layout(rect=(0, 0.03 if len(caption) < 150 else 0.05, 1, 1))
    return save(fig, path, description=caption)
