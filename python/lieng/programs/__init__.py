"""The 1971 programs: LIENG-1 (App. 4), MLIEN / LIENG-2 (App. 6), TRC (App. 7), their decks and listings, the
characteristic's centre of symmetry (PINPUT) and the GRAF plots.

Below them: the I/O layer (:mod:`lieng.io`); above them: the modern analyses (:mod:`lieng.analysis`),
:mod:`lieng.diagnose` and the command line.
"""

from __future__ import annotations

from pathlib import Path

from lieng.errors import LiengInputError
from lieng.io.cards import MAX_DECK_BYTES
from lieng.io.inputs import read_text, split_lines

__all__ = ["PROGRAM_MODULES", "read_deck", "write_deck"]


#: Programs with a deck layout, and the module that holds each one's ``Deck``.
PROGRAM_MODULES = {"lieng1": "lieng.programs.lieng1", "mlien": "lieng.programs.mlien", "trc": "lieng.programs.trc"}


def _deck_class(program: str):
    import importlib

    if program not in PROGRAM_MODULES:
        raise LiengInputError(f"unknown program {program!r}: choose one of {', '.join(sorted(PROGRAM_MODULES))}")
    return importlib.import_module(PROGRAM_MODULES[program]).Deck


def read_deck(path, program: str = "lieng1"):
    """Read a card deck of one of the programs.

    Parameters
    ----------
    path : str or path-like
        The deck, one card per line.
    program : {"lieng1", "mlien", "trc"}
        Whose deck layout to use.

    Returns
    -------
    deck
        The program's deck object (e.g. :class:`lieng.programs.lieng1.Deck`)
        with the values as the 1971 program would have read them.
    """
    deck_class = _deck_class(program)
    text = read_text(path, encoding="ascii", what="deck", max_bytes=MAX_DECK_BYTES)
    # a form feed or a TAB inside a card is a character of that card, reported with its columns
    return deck_class.from_lines(split_lines(text) if text else [], source=str(path))


def write_deck(deck, path) -> None:
    """Write a deck object (from :func:`read_deck` or built by hand) to ``path``."""
    Path(path).write_text("\n".join(deck.to_lines()) + "\n", encoding="ascii")
