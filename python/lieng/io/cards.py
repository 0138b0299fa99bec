"""Punched-card decks: a layout of named fields on cards, read and written with the FORMAT engine
(:mod:`lieng.io.fortran_format`, whose names are importable from here too).

Decks are described by a list of :class:`Card` (a FORMAT and the names of
its fields); :func:`read_cards` reads a deck's lines with a layout, naming
the card and columns of a bad field, and :func:`write_cards` writes cards
that read back to the same values (:func:`deck_field`).  The programs'
layouts and ``read_deck`` / ``write_deck`` are in :mod:`lieng.programs`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from lieng.errors import LiengInputError
from lieng.io.fortran_format import Edit, _flatten, format_value, parse_format, read_field, read_record, write_record

#: a deck is at most a few hundred cards of 80 columns
MAX_DECK_BYTES = 1024**2

__all__ = [
    "Card",
    "parse_format",
    "read_field",
    "read_record",
    "write_record",
    "format_value",
    "deck_field",
    "read_cards",
    "write_cards",
    "card_location",
]


# --------------------------------------------------------------------------
# Writing decks: fields that read back to the same value
# --------------------------------------------------------------------------


def deck_field(value, ed: Edit) -> str:
    """Text of one card field for ``value``, as close as ``w`` columns allow.

    The Fortran output form (``Fw.d``) is used when it reads back exactly;
    otherwise the shortest decimal that does, always with a decimal point
    (which overrides the implied one), in fixed or exponent form.  A value
    that no ``w`` columns can hold exactly (1/3 in 10 columns) is written
    with as many digits as fit: a deck that was read from cards always
    reads back to the same values.
    """
    if ed.kind == "I":
        s = str(int(value))
        if len(s) > ed.w:
            raise ValueError(f"{value} does not fit in I{ed.w}")
        return s.rjust(ed.w)
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{value} is not finite")
    if v == 0.0:
        v = 0.0  # a card has no negative zero
    s = format_value(v, ed)
    if "*" not in s and read_field(s, ed) == v:
        return s
    best = None
    for unique, prec in [(True, None)] + [(False, p) for p in range(16, -1, -1)]:
        for c in (
            np.format_float_positional(v, unique=unique, precision=prec, trim="."),
            np.format_float_scientific(v, unique=unique, precision=prec, trim=".", exp_digits=1).upper(),
        ):
            if len(c) <= ed.w:
                err = abs(read_field(c.rjust(ed.w), ed) - v)
                if best is None or err < best[0]:
                    best = (err, c)
        if best is not None and (best[0] == 0 or not unique):
            return best[1].rjust(ed.w)
    raise ValueError(f"{value!r} does not fit in {ed.kind}{ed.w}.{ed.d}")


# --------------------------------------------------------------------------
# Decks
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Card:
    """One card of a deck layout: its FORMAT and the names of its fields."""

    fmt: str
    names: tuple[str, ...]
    optional: bool = False

    def edits(self) -> list[Edit]:
        return [e for e in _flatten(parse_format(self.fmt)) if e.kind in "IFED"]


def card_location(layout: Sequence[Card], name: str, last: str | None = None) -> str:
    """'card C, columns A-B (NAME, Fw.d)' for a field name of a layout; with ``last``, a later field of the
    same card, 'card C, columns A-B (NAME, ..., LAST)' for the fields from one to the other."""
    first = _field_position(layout, name)
    if first is None:
        return name
    cno, c1, c2, ed = first
    if last is None:
        return f"card {cno}, columns {c1}-{c2} ({name}, {_desc(ed)})"
    names = layout[cno - 1].names
    span = names[names.index(name): names.index(last) + 1]
    return f"card {cno}, columns {c1}-{_field_position(layout, last)[2]} ({', '.join(span)})"


def _field_position(layout: Sequence[Card], name: str):
    """(card number, first column, last column, edit descriptor) of a field name of a layout, or None."""
    for cno, card in enumerate(layout, start=1):
        col = 0
        k = 0
        for ed in _flatten(parse_format(card.fmt)):
            if ed.kind in "XH":
                col += ed.w if ed.kind == "X" else len(ed.text)
                continue
            if ed.kind == "/":
                continue
            if k < len(card.names) and card.names[k] == name:
                return cno, col + 1, col + ed.w, ed
            k += 1
            col += ed.w
    return None


def _desc(ed: Edit) -> str:
    return f"I{ed.w}" if ed.kind == "I" else f"{ed.kind}{ed.w}.{ed.d}"


def read_cards(lines: Sequence[str], layout: Sequence[Card], source: str = "deck") -> dict:
    """Read a deck's lines with a layout; returns ``{name: value}``.

    Optional cards are read when present.  A missing card, or a field that
    is not a number, raises :class:`LiengInputError` naming the card and
    columns.
    """
    values: dict = {}
    cards = [ln.rstrip("\r\n") for ln in lines]
    # a final empty line left by an editor is not a card
    while cards and cards[-1].strip() == "" and len(cards) > sum(1 for c in layout if not c.optional):
        cards.pop()
    for cno, card in enumerate(layout, start=1):
        if cno > len(cards):
            if card.optional:
                break
            first = card.names[0] if card.names else ""
            raise LiengInputError(
                f"{source}: card {cno} ({', '.join(card.names[:1])}{'...' if len(card.names) > 1 else ''}, "
                f"{card.fmt}) is missing: the deck ends after {len(cards)} card(s)"
                if first
                else f"{source}: card {cno} is missing"
            )
        line = cards[cno - 1]
        if "\t" in line:
            col = line.index("\t") + 1
            raise LiengInputError(f"{source}: card {cno}, column {col}: a TAB character (cards have blanks, not tabs)")
        try:
            vals = read_record(line, card.fmt)
        except ValueError as exc:
            reason, c1, c2, k, field = exc.args
            name = card.names[k] if k < len(card.names) else f"field {k + 1}"
            ed = card.edits()[k]
            raise LiengInputError(
                f"{source}: card {cno}, columns {c1}-{c2} ({name}, {_desc(ed)}): {field.strip()!r} {reason}"
            ) from None
        for name, v in zip(card.names, vals):
            values[name] = v
    return values


def write_cards(values: dict, layout: Sequence[Card]) -> list[str]:
    """Lines of a deck for ``{name: value}`` with a layout (optional cards
    are written when all their names are present)."""
    lines = []
    for cno, card in enumerate(layout, start=1):
        if card.optional and not all(n in values for n in card.names):
            continue
        fields = []
        for name, ed in zip(card.names, card.edits()):
            try:
                fields.append(deck_field(values[name], ed))
            except ValueError as exc:
                raise LiengInputError(f"card {cno} ({name}): {exc}") from None
        lines.append("".join(fields).rstrip())
    return lines
