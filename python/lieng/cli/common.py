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
    """A delimited table rather than a card deck: a .csv or .tsv file, or a
    first line with a comma, semicolon or TAB, or with words (a header, a
    comment, an instrument's metadata): a deck's cards hold numbers in fixed
    columns separated by blanks.  A path that is not a readable regular file
    is an error here (a FIFO is never opened)."""
    from lieng.io.inputs import head, split_lines

    p = Path(path)
    first = split_lines(head(p))[0]
    if p.suffix.lower() in (".csv", ".tsv") or re.search(r"[,;\t]", first):
        return True
    words = re.sub(r"[-+]?(\d+\.?\d*|\.\d+)([eEdD][-+]?\d+)?", " ", first)
    return bool(re.search(r"[A-Za-z#]", words))


def _cell(v):
    """A CSV cell: the float, or None (an empty cell) for an undefined value."""
    v = float(v)
    return v if math.isfinite(v) else None
