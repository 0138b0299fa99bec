"""Errors raised for bad input.

Every error the user can cause by a deck, a CSV file or an argument is a
:class:`LiengInputError`: one line that names the card and columns (or the
CSV column, or the argument).  The command line prints it as
``lieng: error: <message>`` and exits with status 2.
"""

from __future__ import annotations


class LiengInputError(ValueError):
    """Bad input, with a one-line message naming where it is."""

    def __init__(self, message: str):
        super().__init__(" ".join(str(message).split()))


class CentreUndefined(LiengInputError):
    """The centre of symmetry of a characteristic cannot be found (no
    negative-slope segment, or the equal-slope interpolation divides by zero)."""
