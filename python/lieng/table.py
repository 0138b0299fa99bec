"""Reading numeric tables (the modern inputs of TRC and diagnose).

One place for the header check and the cell-by-cell parse, so that every
bad value is reported the same way: one line naming the file, the line and
the column.  Comma, TAB and whitespace separated tables are read alike; a
header cell may carry its unit in brackets (``Time [s]``, ``F (mN)``).
"""

from __future__ import annotations

import math
import re
from typing import Sequence

import numpy as np

from .errors import LiengInputError
from .inputs import read_text, split_lines

__all__ = ["read_columns", "read_table", "Table"]

#: the longest line read (characters): a longer one is not a table row
MAX_LINE = 100_000
#: the most data rows a table may have (42 minutes at 2 kHz)
MAX_ROWS = 5_000_000
#: the largest magnitude a measured value may have (squares and sums of it
#: must stay finite in double precision)
MAX_ABS = 1e100


class Table:
    """A numeric table: header names (as written), their units (``""`` when
    none is written) and one float column per name."""

    def __init__(self, path, names, units, columns, lines):
        self.path = str(path)
        self.names = names
        self.units = units
        self.columns = columns
        #: the file line of each row (1-based), for messages
        self.lines = lines

    def __len__(self):
        return len(self.lines)


_UNIT = re.compile(r"^\s*(.*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*$")


def _split_header(line: str, first_row: str | None = None):
    """The separator and the header cells.  A whitespace-separated header may
    have names of several words ("Tangential force [mN]"): the cells are then
    the runs between two or more blanks, or each name with its unit, when
    that gives as many cells as the first data row."""
    if "," in line:
        return ",", [c.strip() for c in line.split(",")]
    if "\t" in line:
        return "\t", [c.strip() for c in line.split("\t")]
    if ";" in line:
        return ";", [c.strip() for c in line.split(";")]
    want = len(first_row.split()) if first_row and first_row.strip() else None
    wide = [c for c in re.split(r"\s{2,}", line.strip()) if c]
    if want is not None and len(wide) == want:
        return None, wide
    cells = []
    for tok in line.split():
        if cells and tok[:1] in "[(" and not cells[-1].endswith(("]", ")")):
            cells[-1] += " " + tok            # "t [s]": the unit belongs to the name before it
        else:
            cells.append(tok)
    if want is not None and len(cells) != want:
        united, cur = [], []
        for tok in line.split():
            cur.append(tok)
            if tok.endswith(("]", ")")):
                united.append(" ".join(cur))
                cur = []
        if cur:
            united.append(" ".join(cur))
        if len(united) == want:
            return None, united
    return None, cells


def read_table(path, expect: str) -> Table:
    """Read a delimited numeric table with a header row.

    Parameters
    ----------
    path : str or path-like
        The file: comma, semicolon, TAB or whitespace separated (the header
        row decides); blank lines are skipped.
    expect : str
        What the header should look like, for the messages.

    Returns
    -------
    Table

    Raises
    ------
    LiengInputError
        An unreadable file, a row with too few cells, a non-numeric or
        non-finite cell (naming its line and column).
    """
    text = read_text(path, what="table")
    rows = split_lines(text)
    if len(rows) > MAX_ROWS + 1 and sum(1 for r in rows if r.strip()) > MAX_ROWS + 1:
        raise LiengInputError(f"{path}: more than {MAX_ROWS} rows: split the record (lieng reads at most "
                              f"{MAX_ROWS} rows)")
    k0 = next((k for k, r in enumerate(rows) if r.strip()), None)
    if k0 is None:
        raise LiengInputError(f"{path}: empty file: expected a header {expect}")
    first = next((r for r in rows[k0 + 1:] if r.strip()), None)
    sep, head = _split_header(rows[k0], first)
    names, units = [], []
    for h in head:
        m = _UNIT.match(h)
        names.append(m.group(1) if m else h)
        units.append(m.group(2) if m else "")
    ncol = len(names)
    data, lines = [], []
    for r in range(k0 + 1, len(rows)):
        row = rows[r]
        if not row.strip():
            continue
        if len(row) > MAX_LINE:
            raise LiengInputError(f"{path}: line {r + 1}: longer than {MAX_LINE} characters: not a table row")
        cells = row.split(sep) if sep else row.split()
        if len(cells) < ncol:
            raise LiengInputError(f"{path}: line {r + 1}: {len(cells)} cells where the header has {ncol}")
        vals = []
        for c in range(ncol):
            cell = cells[c].strip()
            try:
                val = float(cell)
            except ValueError:
                raise LiengInputError(f"{path}: line {r + 1}, column {names[c]}: {cell[:40]!r} is not a "
                                      f"number") from None
            if not math.isfinite(val):
                raise LiengInputError(f"{path}: line {r + 1}, column {names[c]}: {cell} is not a finite number")
            if abs(val) > MAX_ABS:
                raise LiengInputError(f"{path}: line {r + 1}, column {names[c]}: {cell} is out of range for a "
                                      f"measurement (|value| > {MAX_ABS:g})")
            vals.append(val)
        data.append(vals)
        lines.append(r + 1)
    arr = np.asarray(data, float).reshape(len(data), ncol)
    return Table(path, names, units, {n: arr[:, j] for j, n in enumerate(names)}, lines)


def read_columns(path, required: Sequence[str], optional: Sequence[str], expect: str) -> dict:
    """Read the named columns of a table with a header row (see :func:`read_table`).

    Parameters
    ----------
    path : str or path-like
        The file.
    required, optional : sequence of str
        Column names that must be, and that may be, in the header.
    expect : str
        What the header should look like, for the messages (e.g.
        ``"t,x[,xn]: s, mm, mm"``).

    Returns
    -------
    dict
        name -> float ndarray for every column present.
    """
    tab = read_table(path, expect)
    for need in required:
        if need not in tab.names:
            raise LiengInputError(f"{path}: no column {need!r} in the header (expected {expect})")
    return {n: tab.columns[n] for n in (*required, *optional) if n in tab.names}
