"""``map.png`` of ``lieng map``: the regimes of a :class:`lieng.analysis.regime_map.RegimeMap` (imported only
when plots are asked for: it imports matplotlib)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from lieng.analysis.regime_map import AXES, REGIMES
from lieng.programs.graf import save

__all__ = ["REGIME_COLOURS", "regime_map_plot"]


#: the colour of each regime of a map (:data:`lieng.regime_map.REGIMES`, by code)
REGIME_COLOURS = ("#d9d9d9", "#9ecae1", "#e6550d", "#fdd49e", "#756bb1", "#252525")


def _cell_edges(c):
    """Edges of the cells centred on the ascending values ``c``."""
    c = np.asarray(c, float)
    if c.size == 1:
        h = 0.05 * max(abs(c[0]), 1.0)
        return np.array([c[0] - h, c[0] + h])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


def regime_map_plot(res, outdir, source: str = "") -> Path:
    """``map.png``: the regime of Table 2.IV at each point of a
    :class:`lieng.regime_map.RegimeMap` as coloured cells, v_oc drawn over
    them as a curve, a legend naming each regime and its row of the table,
    and a caption saying what is shown.  Returns the path written."""
    import textwrap

    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    cmap = ListedColormap(REGIME_COLOURS)
    norm = BoundaryNorm(np.arange(-0.5, len(REGIMES) + 0.5), cmap.N)
    fig, ax = plt.subplots(figsize=(9.6, 5.6), dpi=110)
    try:
        ax.pcolormesh(_cell_edges(res.v0), _cell_edges(res.values), res.regime, cmap=cmap, norm=norm,
                      shading="flat")
        handles = [Patch(facecolor=REGIME_COLOURS[r.code], edgecolor="0.5", label=r.label)
                   for r in REGIMES if np.any(res.regime == r.code)]
        ok = np.isfinite(res.v_oc)
        if ok.any():
            (line,) = ax.plot(res.v_oc[ok], res.values[ok], color="k", lw=1.4, marker="." if ok.sum() < 40 else None,
                              ms=4, label="v_oc(" + ("dmu0" if res.axis == "dmu" else "slope") + "): metastable, "
                                          "S.L.C. = U.L.C. (row 4a)")
            handles.append(line)
        ax.set_xlabel("driving velocity v0 (mm/s)")
        ax.set_ylabel(AXES[res.axis][1])
        title = f"Regimes of Table 2.IV{': ' + source if source else ''}"
        ax.set_title(title, fontsize=11)
        ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
                  title="regime (Table 2.IV)", title_fontsize=8)
        what = "dmu0 scaled" if res.axis == "dmu" else "the rising part's slope set"
        caption = (f"Each cell: the origin's stability and the limit cycles ({res.mode} mode, {res.v0.size} x "
                   f"{res.values.size} points) of the characteristic with {what} and moved to v0 as TIMDIS moves "
                   f"it, read as Table 2.IV (ch. 2.4.2.1). Black curve: v_oc, where the S.L.C. and U.L.C. merge "
                   f"(the metastable cycle), bisected along v0 as `lieng sweep --v0` finds it; missing where the "
                   f"grid does not cross it.")
        fig.text(0.01, 0.005, "\n".join(textwrap.wrap(caption, 165)), fontsize=7, color="0.3", ha="left",
                 va="bottom")
        fig.tight_layout(rect=(0, 0.06, 1, 1))
        return save(fig, Path(outdir) / "map.png", title, caption)
    finally:
        plt.close(fig)
