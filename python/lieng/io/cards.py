"""Punched-card decks read and written with Fortran edit-descriptor semantics.

The 1971 programs read their data with ``READ(5,fmt)`` from 80-column cards
on a CDC 6600.  This module reproduces that input exactly:

* ``Iw``: an integer in ``w`` columns.
* ``Fw.d`` / ``Ew.d`` / ``Dw.d``: a real in ``w`` columns.  A field without a
  decimal point has an implied one ``d`` digits from the right of its
  digits (``1234`` in ``F10.2`` is 12.34); a written point overrides ``d``.
  An exponent may follow (``1.5E2``, ``1.5D2``, ``1.5+2``).
* Blanks are zeros (FORTRAN 66 / CDC ``BZ`` semantics): leading blanks are
  ignored, every other blank counts as the digit 0, and an all-blank field
  is zero.  So ``'  12 '`` in ``I5`` reads 120, exactly as on a card:
  numbers are right-justified.
* A line shorter than the format is padded with blanks (a card has 80
  columns); characters past the last field are ignored.

The same FORMAT engine writes line-printer records (``Iw``, ``Fw.d``,
``Ew.d``, ``nX``, ``nH...``, quoted strings, ``/``, repeat counts and
groups, format reversion) for :mod:`lieng.listing`.

Decks are described by a list of :class:`Card` (a FORMAT and the names of
its fields); :func:`read_deck` and :func:`write_deck` use the layouts of the
programs (``lieng1``, ``mlien``, ``trc``).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from decimal import ROUND_HALF_EVEN, Context, Decimal, DecimalException

from typing import Iterable, Sequence

import numpy as np

from lieng.errors import LiengInputError

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
# FORMAT parsing
# --------------------------------------------------------------------------


@dataclass(frozen=True)
class Edit:
    """One edit descriptor: kind is 'I', 'F', 'E', 'D', 'X', 'H', '/'."""

    kind: str
    w: int = 0
    d: int = 0
    text: str = ""


@dataclass(frozen=True)
class Group:
    """A parenthesised group with a repeat count."""

    repeat: int
    items: tuple


def parse_format(fmt: str) -> Group:
    """Parse a FORMAT specification such as ``"(I5,5F10.2)"``.

    Hollerith strings (``3HABC``) keep their blanks; outside them blanks
    are insignificant, as in Fortran.
    """
    s = fmt.strip()
    if not (s.startswith("(") and s.endswith(")")):
        raise ValueError(f"FORMAT must be parenthesised: {fmt!r}")
    pos, items = _parse_items(s, 1)
    if pos != len(s):
        raise ValueError(f"unbalanced FORMAT: {fmt!r}")
    return Group(1, tuple(items))


def _skip_blanks(s: str, pos: int) -> int:
    while pos < len(s) and s[pos] in " ,":
        pos += 1
    return pos


def _read_int(s: str, pos: int) -> tuple[int | None, int]:
    start = pos
    while pos < len(s) and s[pos].isdigit():
        pos += 1
    return (int(s[start:pos]) if pos > start else None), pos


def _parse_items(s: str, pos: int) -> tuple[int, list]:
    items: list = []
    while True:
        pos = _skip_blanks(s, pos)
        if pos >= len(s):
            raise ValueError(f"unterminated FORMAT: {s!r}")
        c = s[pos]
        if c == ")":
            return pos + 1, items
        if c == "/":
            items.append(Edit("/"))
            pos += 1
            continue
        if c == "'":
            end = pos + 1
            text = []
            while True:
                if end >= len(s):
                    raise ValueError(f"unterminated string in FORMAT: {s!r}")
                if s[end] == "'":
                    if end + 1 < len(s) and s[end + 1] == "'":
                        text.append("'")
                        end += 2
                        continue
                    break
                text.append(s[end])
                end += 1
            items.append(Edit("H", text="".join(text)))
            pos = end + 1
            continue
        rep, pos = _read_int(s, pos)
        c = s[pos].upper()
        if c == "H":
            if rep is None:
                raise ValueError(f"H without a count in FORMAT: {s!r}")
            text = s[pos + 1 : pos + 1 + rep]
            if len(text) < rep:
                raise ValueError(f"Hollerith runs past the FORMAT: {s!r}")
            items.append(Edit("H", text=text))
            pos = pos + 1 + rep
        elif c == "X":
            items.append(Edit("X", w=rep if rep is not None else 1))
            pos += 1
        elif c == "(":
            pos, sub = _parse_items(s, pos + 1)
            items.append(Group(rep if rep is not None else 1, tuple(sub)))
        elif c in "IFED":
            w, pos = _read_int(s, pos + 1)
            if w is None:
                raise ValueError(f"{c} without a width in FORMAT: {s!r}")
            d = 0
            if pos < len(s) and s[pos] == ".":
                d, pos = _read_int(s, pos + 1)
                d = d or 0
            elif c != "I":
                raise ValueError(f"{c}{w} without .d in FORMAT: {s!r}")
            ed = Edit(c, w=w, d=d)
            items.extend([ed] * (rep if rep is not None else 1))
        else:
            raise ValueError(f"unsupported edit descriptor {s[pos]!r} in FORMAT: {s!r}")


def _flatten(group: Group) -> list[Edit]:
    """Expand repeat counts: the flat sequence of one pass through a group."""
    out: list[Edit] = []
    for _ in range(group.repeat):
        for it in group.items:
            if isinstance(it, Group):
                out.extend(_flatten(it))
            else:
                out.append(it)
    return out


# --------------------------------------------------------------------------
# Input: reading fields
# --------------------------------------------------------------------------

_REAL_RE = re.compile(r"^([+-]?)(\d*)(\.(\d*))?(?:[EeDdQq]([+-]?\d+)|([+-]\d+))?$")
_INT_RE = re.compile(r"^[+-]?\d+$")


def read_field(text: str, ed: Edit) -> int | float:
    """Read one field's text with edit descriptor ``ed`` (BZ semantics).

    Raises ``ValueError`` with a short reason when the field is not a number.
    """
    body = text.lstrip(" ")
    if body == "":
        return 0 if ed.kind == "I" else 0.0
    body = body.replace(" ", "0")
    if ed.kind == "I":
        if not _INT_RE.match(body):
            raise ValueError("is not an integer")
        return int(body)
    m = _REAL_RE.match(body)
    if not m or not (m.group(2) or m.group(4)):
        raise ValueError("is not a number")
    sign, ipart, has_point, fpart, e1, e2 = m.groups()
    exp = int(e1 or e2 or 0)
    try:
        if has_point is not None:
            value = Decimal(f"{ipart or '0'}.{fpart or '0'}")
        else:
            value = Decimal(ipart).scaleb(-ed.d, context=_WIDE)
        value = value.scaleb(exp, context=_WIDE)
    except DecimalException:                # an exponent beyond any context (1E99999999)
        raise ValueError("is out of the range of a real number") from None
    f = float(value)
    if not math.isfinite(f):
        raise ValueError("is out of the range of a real number")
    return -f if sign == "-" else f


def read_record(line: str, fmt: str | Group) -> list[int | float]:
    """Read one record (card) with a FORMAT that has no ``/``.

    Returns the values of the data fields in order.  Errors are
    ``ValueError`` whose args are ``(reason, first_column, last_column,
    field_index)``.
    """
    group = parse_format(fmt) if isinstance(fmt, str) else fmt
    col = 0
    values: list[int | float] = []
    for ed in _flatten(group):
        if ed.kind == "X":
            col += ed.w
        elif ed.kind == "H":
            col += len(ed.text)
        elif ed.kind == "/":
            raise ValueError("read_record: '/' in an input FORMAT")
        else:
            field = line[col : col + ed.w].ljust(ed.w)
            try:
                values.append(read_field(field, ed))
            except ValueError as exc:
                raise ValueError(str(exc), col + 1, col + ed.w, len(values), field) from None
            col += ed.w
    return values


# --------------------------------------------------------------------------
# Output: Fortran output editing (gfortran conventions)
# --------------------------------------------------------------------------


#: enough digits for any double printed in F (at most 309 integer digits)
_WIDE = Context(prec=800)


def _stars(w: int) -> str:
    return "*" * w


def _nonfinite(v: float, w: int) -> str:
    """A value the arithmetic could not give: an infinity does not fit any
    field (asterisks, as for an overflow); an undefined value (NaN) prints
    ``UNDEF`` (lieng's convention: a listing holds no NaN token)."""
    if math.isnan(v):
        return "UNDEF"[:w].rjust(w)
    return _stars(w)


def _format_I(v: int, w: int) -> str:
    s = str(int(v))
    return s.rjust(w) if len(s) <= w else _stars(w)


def _format_F(v: float, w: int, d: int) -> str:
    if not math.isfinite(v):
        return _nonfinite(v, w)
    neg = math.copysign(1.0, v) < 0
    if abs(v) >= 10.0 ** min(w, 308):      # more integer digits than the field has columns
        return _stars(w)
    q = abs(Decimal(v)).quantize(Decimal(1).scaleb(-d), rounding=ROUND_HALF_EVEN, context=_WIDE)
    digits = f"{q:f}"
    ipart, _, fpart = digits.partition(".")
    body = f"{ipart}.{fpart}"
    sign = "-" if neg else ""
    s = sign + body
    if len(s) > w and ipart == "0":
        s = sign + "." + fpart
    return s.rjust(w) if len(s) <= w else _stars(w)


def _format_E(v: float, w: int, d: int, letter: str = "E") -> str:
    if not math.isfinite(v):
        return _nonfinite(v, w)
    neg = math.copysign(1.0, v) < 0
    a = abs(Decimal(v))
    if a == 0:
        mant, e = Decimal(0).quantize(Decimal(1).scaleb(-d)), 0
    else:
        e = a.adjusted() + 1
        mant = a.scaleb(-e, context=_WIDE).quantize(Decimal(1).scaleb(-d), rounding=ROUND_HALF_EVEN, context=_WIDE)
        if mant >= 1:
            e += 1
            mant = a.scaleb(-e, context=_WIDE).quantize(Decimal(1).scaleb(-d), rounding=ROUND_HALF_EVEN, context=_WIDE)
    frac = f"{mant:f}".partition(".")[2]
    if abs(e) <= 99:
        exp = f"{letter}{'-' if e < 0 else '+'}{abs(e):02d}"
    elif abs(e) <= 999:
        exp = f"{'-' if e < 0 else '+'}{abs(e):03d}"
    else:
        return _stars(w)
    sign = "-" if neg else ""
    s = f"{sign}0.{frac}{exp}"
    if len(s) > w:
        s = f"{sign}.{frac}{exp}"
    return s.rjust(w) if len(s) <= w else _stars(w)


def format_value(v, ed: Edit) -> str:
    """Format one value with a data edit descriptor, as a Fortran WRITE does."""
    if ed.kind == "I":
        return _format_I(v, ed.w)
    if ed.kind == "F":
        return _format_F(float(v), ed.w, ed.d)
    if ed.kind in "ED":
        return _format_E(float(v), ed.w, ed.d, ed.kind)
    raise ValueError(f"not a data edit descriptor: {ed}")


def write_record(fmt: str | Group, values: Sequence = ()) -> list[str]:
    """Records (lines) a ``WRITE(6,fmt) values`` produces.

    Follows the Fortran rules: output stops at the first data edit
    descriptor with no value left, or at the final parenthesis; if values
    remain there, a new record starts and the format reverts to its last
    top-level group (or to its beginning).  Column 1 of each record is the
    line printer's carriage-control character, kept as written.
    """
    group = parse_format(fmt) if isinstance(fmt, str) else fmt
    vals = list(values)
    records: list[str] = []
    cur: list[str] = []
    state = {"i": 0, "pending": 0}  # pending: blanks of X editing not yet materialised

    def emit(text: str) -> None:
        cur.append(" " * state["pending"] + text)
        state["pending"] = 0

    def end_record() -> None:
        records.append("".join(cur))
        cur.clear()
        state["pending"] = 0  # X at the end of a record writes nothing

    def run(items: Iterable) -> bool:
        """Process items; False when the values ran out at a data descriptor."""
        for it in items:
            if isinstance(it, Group):
                for _ in range(it.repeat):
                    if not run(it.items):
                        return False
            elif it.kind == "/":
                end_record()
            elif it.kind == "X":
                state["pending"] += it.w
            elif it.kind == "H":
                emit(it.text)
            else:
                if state["i"] >= len(vals):
                    return False
                emit(format_value(vals[state["i"]], it))
                state["i"] += 1
        return True

    if run(group.items):
        while state["i"] < len(vals):
            # format reversion: new record, restart at the last top-level group
            end_record()
            last = [k for k, it in enumerate(group.items) if isinstance(it, Group)]
            items = group.items[last[-1] :] if last else group.items
            if not any(
                (isinstance(it, Group) or it.kind in "IFED") for it in items
            ):
                raise ValueError("FORMAT has no data edit descriptor for the remaining values")
            if not run(items):
                break
    end_record()
    return records


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
