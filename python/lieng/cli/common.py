"""What the command line's modules share: the constants of the options and messages, and the plots (matplotlib
is imported only when plots are asked for)."""

from __future__ import annotations

import math
import re
from pathlib import Path

PROGRAMS = ("lieng1", "mlien", "trc")
#: the words of the message for a failure no check foresaw (the fuzz suite looks for them)
UNEXPECTED = "unexpected failure on this input"
#: --force of the commands that write an output directory
FORCE_HELP = ("write into an existing directory that holds other files (they are left as they are; lieng replaces "
              "only its own outputs)")
#: the programs whose decks hold a characteristic (cycles, sweep)
CHAR_PROGRAMS = ("lieng1", "mlien")


def _map_plot(res, outdir, source):
    """``lieng map``'s plot (matplotlib is imported only when plots are asked for)."""
    from lieng.analysis.map_plot import regime_map_plot

    return regime_map_plot(res, outdir, source)


def _plots(name, res, outdir, *more):
    """A program's plots (matplotlib is imported only when plots are asked for)."""
    from lieng.programs import graf

    return getattr(graf, name)(res, outdir, *more)


def _is_table(path) -> bool:
    """A delimited table with a header naming a time column (comma, TAB,
    semicolon or whitespace), rather than a card deck.  A path that is not a
    readable regular file is an error here (a FIFO is never opened)."""
    from lieng.io.inputs import head, split_lines

    p = Path(path)
    first = split_lines(head(p))[0]
    if p.suffix.lower() in (".csv", ".tsv"):
        return True
    cells = [c.strip().lower() for c in re.split(r"[,;\t]|\s+", first) if c.strip()]
    return any(c in ("t", "time") or c.startswith(("t[", "t(", "time[", "time(")) for c in cells)


def _cell(v):
    """A CSV cell: the float, or None (an empty cell) for an undefined value."""
    v = float(v)
    return v if math.isfinite(v) else None
