"""The FORMAT engine: Fortran edit descriptors read and written as the 1971 programs' ``READ`` and ``WRITE``.

Input (``READ(5,fmt)`` from 80-column cards on a CDC 6600), reproduced exactly:

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

Output: line-printer records (``Iw``, ``Fw.d``, ``Ew.d``, ``nX``, ``nH...``,
quoted strings, ``/``, repeat counts and groups, format reversion) with
gfortran's conventions, for :mod:`lieng.programs.listing`.

Decks of named fields on these records are :mod:`lieng.io.cards`.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from decimal import ROUND_HALF_EVEN, Context, Decimal, DecimalException
from typing import Iterable, Sequence

__all__ = ["Edit", "Group", "parse_format", "read_field", "read_record", "format_value", "write_record"]

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
