"""Errors raised for bad input.

Every error the user can cause by a deck, a CSV file or an argument is a
:class:`LiengInputError`: one line that names the card and columns (or the
CSV column, or the argument).  The command line prints it as
``lieng: error: <message>`` and exits with status 2.

The Python API knows no cards: its errors (and its warnings about the input,
:class:`LiengInputWarning`) name the argument they are about in ``fields``
(``"dtheta"``, ``"xchl[6]"``, ``"xinp, yinp"``).  The layer that read the
input names those fields where they stand in it: a deck runs the API under
:func:`located` with its card-and-columns names, a CSV trace with the file's.

:func:`run_reporting` runs a command's work under the message contract both the
command line and its worker processes keep: numerical warnings silent, the
program's own warnings collected as one line each.
"""

from __future__ import annotations

import sys
import warnings
from contextlib import contextmanager
from typing import Callable

__all__ = ["LiengInputError", "LiengInputWarning", "CentreUndefined", "located", "run_reporting", "describe"]


class _Fields:
    """A one-line message about ``fields`` of the input: ``'<field>: <detail>'``, or ``'<first>..<last>:
    <detail>'`` for two (a range), or the detail alone when it names no field."""

    def __init__(self, message: str, *, fields=()):
        self.fields = tuple(fields)
        self.detail = " ".join(str(message).split())
        super().__init__(_named(self.fields, self.detail))

    def located(self, where: Callable[[str], str]):
        """The same error (or warning) with each field named by ``where(field)``, e.g. by the card and
        columns of a deck; one that names no field comes back as it is."""
        if not self.fields:
            return self
        new = type(self)(self.detail, fields=self.fields)
        new.args = (_named([where(f) for f in self.fields], self.detail),)
        return new


def _named(names, detail: str) -> str:
    return f"{'..'.join(names)}: {detail}" if names else detail


class LiengInputError(_Fields, ValueError):
    """Bad input, with a one-line message naming where it is.

    Parameters
    ----------
    message : str
        What is wrong (after the fields' names, when ``fields`` are given).
    fields : tuple of str, optional
        What the message is about, as the Python API names it: an argument (``"dtheta"``), a group of them
        (``"xinp, yinp"``), a point of one (``"xchl[6]"``), or the input of a call as a whole (``"trc"``);
        two fields are a range (``first..last``).

    Attributes
    ----------
    fields : tuple of str
    detail : str
        The message after the fields' names.
    """


class LiengInputWarning(_Fields, UserWarning):
    """A warning about the input (a value the run cannot use, or uses with a loss), with ``fields`` as
    :class:`LiengInputError`'s."""


class CentreUndefined(LiengInputError):
    """The centre of symmetry of a characteristic cannot be found (no
    negative-slope segment, or the equal-slope interpolation divides by zero)."""


@contextmanager
def located(where: Callable[[str], str]):
    """Run a block of API calls on input read from a deck or a file: every :class:`LiengInputError` and
    :class:`LiengInputWarning` it raises is given again with its fields named by ``where(field)`` (the card
    and columns, the file); other warnings are given again as they were."""
    caught: list = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            yield
    except LiengInputError as exc:
        raise exc.located(where).with_traceback(exc.__traceback__) from None
    finally:
        for w in caught:
            _warn_again(w, w.message.located(where) if isinstance(w.message, LiengInputWarning) else w.message)


def _warn_again(w, message) -> None:
    """Give a recorded warning again as ``warnings.warn`` first gave it: from the same place, module and
    registry, so that the filters and the once-per-place rule apply to it as they would have."""
    module = next((m for m in list(sys.modules.values()) if getattr(m, "__file__", None) == w.filename), None)
    env = vars(module) if module is not None else None
    warnings.warn_explicit(message, w.category, w.filename, w.lineno, source=w.source,
                           module=env.get("__name__") if env else None,
                           registry=env.setdefault("__warningregistry__", {}) if env else None, module_globals=env)


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
