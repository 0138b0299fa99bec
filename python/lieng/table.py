"""Reading numeric CSV tables (the modern inputs of TRC and diagnose).

One place for the header check and the cell-by-cell parse, so that every
bad value is reported the same way: one line naming the file, the line and
the column.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Sequence

import numpy as np

from .errors import LiengInputError

__all__ = ["read_columns"]


def read_columns(path, required: Sequence[str], optional: Sequence[str], expect: str) -> dict:
    """Read the named columns of a CSV with a header row.

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    required, optional : sequence of str
        Column names that must be, and that may be, in the header.
    expect : str
        What the header should look like, for the messages (e.g.
        ``"t,x[,xn]: s, mm, mm"``).

    Returns
    -------
    dict
        name -> float ndarray for every column present; blank lines are
        skipped.

    Raises
    ------
    LiengInputError
        A missing file or column, a non-numeric or non-finite cell (naming
        its line and column).
    """
    p = Path(path)
    try:
        with open(p, newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
    except FileNotFoundError:
        raise LiengInputError(f"{path}: no such file") from None
    except (IsADirectoryError, UnicodeDecodeError):
        raise LiengInputError(f"{path}: not a CSV text file") from None
    if not rows:
        raise LiengInputError(f"{path}: empty file: expected a header {expect}")
    head = [h.strip() for h in rows[0]]
    for need in required:
        if need not in head:
            raise LiengInputError(f"{path}: no column {need!r} in the header (expected {expect})")
    cols = {n: head.index(n) for n in (*required, *optional) if n in head}
    data = {n: [] for n in cols}
    for r, row in enumerate(rows[1:], start=2):
        if not row or all(not c.strip() for c in row):
            continue
        for n, c in cols.items():
            cell = row[c].strip() if c < len(row) else ""
            try:
                val = float(cell)
            except ValueError:
                raise LiengInputError(f"{path}: line {r}, column {n}: {cell!r} is not a number") from None
            if not math.isfinite(val):
                raise LiengInputError(f"{path}: line {r}, column {n}: {cell} is not a finite number")
            data[n].append(val)
    return {n: np.asarray(v, float) for n, v in data.items()}
