"""Errors raised for bad input.

Every error the user can cause by a deck, a CSV file or an argument is a
:class:`LiengInputError`: one line that names the card and columns (or the
CSV column, or the argument).  The command line prints it as
``lieng: error: <message>`` and exits with status 2.

:func:`run_reporting` runs a command's work under the message contract both the
command line and its worker processes keep: numerical warnings silent, the
program's own warnings collected as one line each.
"""

from __future__ import annotations

import warnings


class LiengInputError(ValueError):
    """Bad input, with a one-line message naming where it is."""

    def __init__(self, message: str):
        super().__init__(" ".join(str(message).split()))


class CentreUndefined(LiengInputError):
    """The centre of symmetry of a characteristic cannot be found (no
    negative-slope segment, or the equal-slope interpolation divides by zero)."""


def describe(exc: BaseException) -> str:
    """An unforeseen failure in one line: its type and the first 200 characters of its message."""
    return f"{type(exc).__name__}: {' '.join(str(exc).split())[:200]}"


def run_reporting(fn, *args):
    """``fn(*args)`` with numerical warnings silent (every output is checked for finiteness where it is
    written) and the program's own warnings (``UserWarning``) collected.

    Returns
    -------
    value, messages
        What ``fn`` returned, and each warning's message on one line, in the order raised.
    """
    import numpy as np

    with warnings.catch_warnings(record=True) as caught, np.errstate(all="ignore"):
        warnings.simplefilter("always")
        for cat in (RuntimeWarning, DeprecationWarning, PendingDeprecationWarning):
            warnings.simplefilter("ignore", cat)
        value = fn(*args)
    return value, [" ".join(str(w.message).split()) for w in caught if issubclass(w.category, UserWarning)]
