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

from lieng.errors import LiengInputError
from lieng.io.inputs import head, read_bytes, read_table_text, split_lines

__all__ = ["read_columns", "read_table", "headerless_columns", "Table"]

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
        #: the file line of each row (1-based, an integer array), for messages
        self.lines = np.asarray(lines, dtype=np.int64)
        #: rows dropped for a missing value (``read_table(..., missing="drop")``)
        self.dropped = 0
        #: lines of text before the header that are not part of the table
        #: (an instrument's metadata: "Operator: ...", "Date: ...")
        self.preamble = 0
        #: columns of date-times (``2024-03-01 10:22:01.250``), read as
        #: seconds from the first row's: name -> that first date-time
        self.dates = {}
        #: what was read beyond a plain table, for the caller's notes: the
        #: text encoding when not UTF-8, the header taken from a comment line,
        #: header rows repeated between the rows (a second run appended), and
        #: lines of text after the last row (a summary)
        self.encoding = "utf-8"
        self.comment_header = False
        self.repeated = 0
        self.footer = 0
        #: segments of a LabVIEW measurement file written with a channel header each, read as one table
        self.segments = 1
        #: variables of an array file (.mat, .npz) not read as columns
        self.passed_over = []
        #: the line of a row of comments under the units (Origin's third header row), passed over
        self.comments_row = None
        #: columns logged on fewer rows, filled linearly between their values:
        #: name -> (rows with a value, rows)
        self.filled = {}
        #: the sampling rate a line above the header states ("Sample rate: 2 kHz", "Delta_X 0.001"), for a
        #: table without a time column: (Hz, its file line, the line's words) or None (:func:`stated_rate`)
        self.stated_rate = None
        #: the image scale a video tracker's metadata states ("# scale: 0.23 mm/px"), for columns in pixels:
        #: (mm per pixel, its file line, the line's words) or None (:func:`stated_scale`)
        self.stated_scale = None

    def __len__(self):
        return len(self.lines)

    def notes(self) -> list[str]:
        """What reading the file passed over or took as it found it, in words."""
        out = []
        if self.preamble:
            out.append(f"{self.preamble} line{'s' if self.preamble != 1 else ''} of text above the header passed "
                       f"over (not part of the table: the instrument's metadata)")
        if self.dropped:
            out.append(f"{self.dropped} rows with a missing value (empty, NaN) left out: the record is resampled "
                       f"across them")
        if self.encoding == "xlsx":
            out.append("read from the workbook's first worksheet")
        elif self.encoding != "utf-8":
            out.append(f"the file is not UTF-8: read as {self.encoding} text")
        if self.comment_header:
            out.append("the header is the comment line above the numbers (as numpy.savetxt writes it)"
                       if self.comment_header is True else
                       "the header and its units are the two comment lines above the numbers")
        if self.comments_row:
            out.append(f"line {self.comments_row}, a row of comments under the units (as Origin writes it), "
                       f"passed over")
        if self.repeated:
            out.append(f"the header row repeats {self.repeated} time{'s' if self.repeated > 1 else ''} between the "
                       f"rows (runs appended to one file, or a header per page): passed over")
        if self.passed_over:
            out.append(f"variables {', '.join(self.passed_over)[:200]} passed over (not vectors of the record's "
                       f"length)")
        for name, (k, n) in self.filled.items():
            out.append(f"column {name} has a value on {k} of {n} rows (logged less often): read linearly between "
                       f"its values")
        if self.segments > 1:
            out.append(f"a LabVIEW measurement file of {self.segments} segments, each under its own channel header: "
                       f"read as one table")
        if self.footer:
            out.append(f"{self.footer} line{'s' if self.footer > 1 else ''} of text after the last row passed over "
                       f"(a summary, not part of the table)")
        return out


_UNIT = re.compile(r"^\s*(.*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*$")
#: ``time/s``, ``force / mN``, ``v0/(mm/s)``: the quantity over its unit (ISO 80000)
_SLASH = re.compile(r"^\s*([^/]*?[A-Za-z][^/]*?)\s*/\s*\(?\s*([^()]+?)\s*\)?\s*$")
#: lines before the header or between rows that are comments, not data
_COMMENT = ("#", "%", "//")


def _unquote(cell: str) -> str:
    c = cell.strip()
    if len(c) >= 2 and c[0] == c[-1] and c[0] in "\"'":
        c = c[1:-1].strip()
    return c


#: the second word of a "date/time" header cell in the languages a lab writes it ("Date/Time",
#: "Datum/Zeit", "Date/Heure", "Fecha/Hora"): one name, not a name and its unit
_TIME_WORDS = ("time", "zeit", "uhrzeit", "heure", "hora", "ora", "tempo")


#: a data-acquisition channel's physical name after its device's ("Dev1/ai0", "cDAQ1Mod1/ai3", "Slot2/ch1"):
#: one name, not a name over its unit
_DAQ_CHANNEL = re.compile(r"^\s*(?:ai|ao|ch|chan|di|do|ctr|port|line|input|in)\s*\d+\s*$", re.IGNORECASE)


def _name_unit(cell: str) -> tuple:
    """A header cell's name and unit: ``Time [s]``, ``F (mN)``, ``time/s``
    (``Date/Time``, ``Datum/Zeit`` are one name)."""
    m = _UNIT.match(cell)
    if m:
        return m.group(1), m.group(2)
    m = _SLASH.match(cell)
    # (not a unit: words after the slash, an ATI sensor's 'F/T Sequence')
    if m and m.group(2).strip().lower() not in _TIME_WORDS and not _DAQ_CHANNEL.match(m.group(2)) and \
            not (" " in m.group(2).strip() and m.group(2).strip().lower() not in _UNITS):
        return m.group(1), m.group(2)
    return cell, ""


#: a logger's date-time stamp: ISO 8601 date, a blank or T, the time of day to any fraction of a second
_DATETIME = re.compile(r"^\s*(\d{4}([-/])\d{2}\2\d{2})[ T](\d{2}:\d{2}:\d{2}(?:[.,]\d+)?)\s*$")
#: a day-first date as Europe writes it (05/03/2024, 05.03.2024; month-first when the second number
#: exceeds 12), then the time of day; with AM or PM after it, an American month-first date
#: (3/5/2024 12:59:50.000 PM; day-first when the first number exceeds 12)
_DMY = re.compile(r"^\s*(\d{1,2})([./])(\d{1,2})\2(\d{4})[ T](\d{1,2}:\d{2}:\d{2}(?:[.,]\d+)?)"
                  r"(?:\s*([AaPp])\.?[Mm]\.?)?\s*$")
#: the time of day alone (a logger's clock: 14:02:03.125; 2:02:03.125 PM)
_CLOCK = re.compile(r"^\s*(\d{1,2}):(\d{2}):(\d{2}(?:[.,]\d+)?)(?:\s*([AaPp])\.?[Mm]\.?)?\s*$")


def _hour(h: int, ampm) -> int | None:
    """The hour of a 12-hour clock's reading (``ampm`` "a" or "p", any case) on a 24-hour one; None
    when it is no hour of it (as is 13 PM)."""
    if not ampm:
        return h
    if not 1 <= h <= 12:
        return None
    return h % 12 + (12 if ampm.lower() == "p" else 0)


_DAY_NS = 86_400 * 10 ** 9


def _datetime_ns(cell: str):
    """A date-time cell as integer nanoseconds, or None when it is not one:
    an ISO 8601 date-time, a day-first date and time (dd/mm/yyyy or
    dd.mm.yyyy; with AM or PM, an American m/d/yyyy and a 12-hour clock),
    or the time of day alone (nanoseconds from midnight; :func:`read_table`
    adds a day where the clock passes midnight)."""
    m = _DATETIME.match(cell)
    if m:
        # (year first: ISO 8601's dashes, or a Japanese logger's slashes, 2026/12/07)
        day, clock = m.group(1).replace("/", "-"), m.group(3)
    elif (m := _DMY.match(cell)):
        a, b = int(m.group(1)), int(m.group(3))
        if m.group(6):
            mo, d = (b, a) if a > 12 >= b else (a, b)
        else:
            d, mo = (b, a) if b > 12 >= a else (a, b)
        hh, rest = m.group(5).split(":", 1)
        h = _hour(int(hh), m.group(6))
        if h is None:
            return None
        day, clock = f"{m.group(4)}-{mo:02d}-{d:02d}", f"{h:02d}:{rest}"
    elif (m := _CLOCK.match(cell)):
        h, mi = _hour(int(m.group(1)), m.group(4)), int(m.group(2))
        sec = float(m.group(3).replace(",", "."))
        if h is None or h > 23 or mi > 59 or not sec < 61.0:
            return None
        return (h * 3600 + mi * 60) * 10 ** 9 + int(round(sec * 1e9))
    else:
        return None
    try:
        return int(np.datetime64(f"{day}T{clock.replace(',', '.')}", "ns").astype(np.int64))
    except ValueError:
        return None


#: a number written with its digits grouped by thousands and a decimal mark of the other kind, the only
#: unambiguous grouping ("12,345.6" in an English spreadsheet's quoted cell, "12.345,6" in a German one); a
#: grouping without a decimal mark ("12,345") is read as before: a decimal comma
_GROUPED_POINT = re.compile(r"^[-+]?\d{1,3}(?:,\d{3})+\.\d*(?:[eE][-+]?\d+)?$")
_GROUPED_COMMA = re.compile(r"^[-+]?\d{1,3}(?:\.\d{3})+,\d*(?:[eE][-+]?\d+)?$")


def _number(cell: str, decimal_comma: bool) -> float:
    c = cell.strip().replace("\u2212", "-")     # a typeset minus sign (U+2212)
    if "_" in c:                          # Python reads "0_2" as 2.0: no instrument writes it
        raise ValueError(cell)
    if decimal_comma:
        if _GROUPED_POINT.match(c):
            c = c.replace(",", "")
        elif _GROUPED_COMMA.match(c):
            c = c.replace(".", "")
        c = c.replace(",", ".")
    return float(c)


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


#: the cells a logger writes for a sample it missed (read as missing with ``missing="drop"``)
MISSING = ("", "nan", "-nan", "na", "n/a", "null", "none", "-", "--")
#: with ``missing="drop"``, at most this fraction of the rows may miss a value
MAX_MISSING = 0.10


def _is_comment(row: str) -> bool:
    return row.lstrip().startswith(_COMMENT)


def _split_counted(row: str):
    """The row split by each separator in turn (comma, TAB, semicolon,
    whitespace), trailing empty cells dropped: (cells, how many of its
    non-empty cells are numbers, how many are non-empty) for each."""
    for sep in (",", "\t", ";", None):
        cells = [_unquote(c) for c in (row.split(sep) if sep else row.split())]
        while len(cells) > 1 and not cells[-1]:
            cells.pop()
        filled = [c for c in cells if c]
        nums = 0
        for c in filled:
            try:
                _number(c, sep != ",")
                nums += 1
            except ValueError:
                pass
        yield cells, nums, len(filled)


def _numeric_cells(row: str) -> int:
    """The number of cells of a row that is all numbers (two at least) under
    some separator, else 0."""
    return next((len(cells) for cells, nums, _ in _split_counted(row) if len(cells) >= 2 and nums == len(cells)), 0)


def _numeric_row(row: str) -> bool:
    """A row that is all numbers: two or more under some separator, or one alone."""
    return bool(_numeric_cells(row)) or bool(_ONE_NUMBER.fullmatch(row.strip()))


def _data_separator(row: str, n: int):
    """The separator that splits a row of numbers into ``n`` of them (a comma only when the others do
    not: a decimal comma), ``None`` for blanks; ``False`` when none does."""
    for sep in ("\t", ";", ",", None):
        cells = [_unquote(c) for c in (row.split(sep) if sep else row.split())]
        while len(cells) > 1 and not cells[-1]:
            cells.pop()
        try:
            [_number(c, sep != ",") for c in cells]
        except ValueError:
            continue
        if len(cells) == n:
            return sep
    return False


def headerless_columns(path) -> int:
    """The number of columns when the file's first lines (its first 64 kB,
    twenty rows at least) are all rows of as many numbers, one or more (a
    table written without a header: ``numpy.savetxt``'s default), else 0."""
    counts = [_numeric_cells(r) or int(bool(_ONE_NUMBER.fullmatch(r.strip())))
              for r in split_lines(head(path, 65536))[:-1] if r.strip()]
    return counts[0] if len(counts) >= 20 and counts[0] >= 1 and all(n == counts[0] for n in counts) else 0


def _data_cells(row: str) -> tuple:
    """A data row that may carry a column of words (a status, a comment,
    blank on most rows): (its cells, its numbers) under the separator that
    splits it into the most numbers, two at least, making up at least half
    of its non-empty cells (on a tie, one whose cells are all numbers, else
    the first); (0, 0) for a row of text.  (The most, not the first:
    ``0,0000;4,507;10,329``, semicolons and decimal commas, splits at its
    commas into two numbers of four cells, at its semicolons into three of
    three; ``0,000;601,09`` at its commas into two of three, at its
    semicolons into two of two.)"""
    best, score = (0, 0), (0, False)
    for cells, nums, filled in _split_counted(row):
        if nums >= 2 and 2 * nums >= filled and (nums, nums == filled) > score:
            best, score = (len(cells), nums), (nums, nums == filled)
    return best


#: a row that is one number alone (a decimal point or a decimal comma)
_ONE_NUMBER = re.compile(r"[-+]?(?:\d+(?:[.,]\d*)?|[.,]\d+)(?:[eE][-+]?\d+)?")
#: the content lines searched for the header under an instrument's preamble
PREAMBLE_SCAN = 200


#: the line that ends each header block of a LabVIEW measurement file (.lvm)
LVM_END = "***End_of_Header***"


def _lvm_header(rows):
    """A LabVIEW measurement file's (.lvm) headers: (the row index of the
    ``***End_of_Header***`` line that ends its first channel header (or its
    file header, when it writes no channel header), that channel header's
    fields: key -> the cells after it, the row indices of the later
    segments' channel headers and their column-name rows, the number of
    segments) or None when ``rows`` are not such a file.  The column header
    row follows that line;
    ``Y_Unit_Label`` gives the channels' units, ``X_Dimension`` what the
    X_Value column is.  A file written a segment at a time (a header per
    segment, LabVIEW's default in a loop) repeats the channel header before
    each segment's rows."""
    if not rows or not rows[0].strip().lower().startswith("labview measurement"):
        return None
    ends = [k for k, r in enumerate(rows) if r.strip() == LVM_END]
    if not ends:
        return None
    first = ends[1] if len(ends) > 1 else ends[0]
    fields = {}
    for r in rows[ends[0] + 1:first] if len(ends) > 1 else []:
        cells = [c.strip() for c in r.split("\t")]
        if cells and cells[0]:
            fields[cells[0]] = [c for c in cells[1:] if c]
    later = []
    for e in ends[2:]:
        # the block: back from its end over the lines that do not start with a number (its keys)
        lo = e
        while lo - 1 > first and not _starts_with_number(rows[lo - 1]):
            lo -= 1
        names = next((k for k in range(e + 1, min(e + 4, len(rows))) if rows[k].strip()), None)
        later.extend(range(lo, e + 1))
        if names is not None and rows[names].split("\t")[0].strip() == "X_Value":
            later.append(names)
    return first, fields, later, 1 + len(ends[2:])


def _starts_with_number(row: str) -> bool:
    """Whether a row's first TAB-separated cell is a number (a data row of a
    LabVIEW file, not a header line's key)."""
    cell = row.strip().split("\t")[0].strip() if row.strip() else ""
    try:
        _number(cell, True)
        return True
    except ValueError:
        return False


def _lvm_names(names, units, fields):
    """The column names and units of a LabVIEW measurement file: each
    ``X_Value`` column is the time (s) when its ``X_Dimension`` is Time
    (the second and later ones, one per channel with ``X_Columns Multi``,
    marked as X_Value again and not read), the channels' units from
    ``Y_Unit_Label`` where the header gives none."""
    xdim = fields.get("X_Dimension", [])
    yunits = list(fields.get("Y_Unit_Label", []))
    out_n, out_u, seen_x = [], [], False
    for n, u in zip(names, units):
        if n == "X_Value":
            if not seen_x and (not xdim or xdim[0].lower() == "time"):
                n, u = "time", u or "s"
            seen_x = True
        elif n != "Comment" and yunits:
            u = u or yunits.pop(0)
        out_n.append(n)
        out_u.append(u)
    return out_n, out_u


def _row_cells(row: str) -> list:
    """A header-like row's cells, split as it is written (a whitespace table's has no comma, semicolon or
    TAB), unquoted (empty ones kept)."""
    sep = r"[,;\t]" if re.search(r"[,;\t]", row) else r"\s+"
    return [_unquote(c) for c in re.split(sep, row.strip())]


#: the units a row of units alone is written in (lower case; a unit may be in brackets): a row of other words
#: ("Label,TORQUE" in an oscilloscope's metadata) is not one
_UNITS = frozenset(
    "s sec ms msec us µs μs min h hr n mn kn un µn μn nn dan gf kgf kp lbf g kg mm um µm μm nm m cm in inch mil "
    "pa kpa mpa gpa bar mbar psi mm/s um/s µm/s μm/s m/s mm/min m/min in/s mm/sec n·m nm n*m n.m mn·m mnm n·mm nmm "
    "deg ° degree rad mrad rpm 1/min rev/min hz khz v mv a ma % °c c k - 1 n/m n/mm".split())


def _unit_cell(cell: str) -> bool:
    """Whether a cell is a unit (in brackets or bare) of :data:`_UNITS`, or empty."""
    c = cell.strip().strip("[]()").strip().replace("\u03bc", "\u00b5").lower()
    return not c or c in _UNITS


def _has_number(cells) -> bool:
    """Whether any of ``cells`` is a number (a decimal comma read too)."""
    for c in cells:
        try:
            _number(c, True)
            return True
        except ValueError:
            pass
    return False


def _units_row(row: str, width: int) -> bool:
    """Whether ``row`` is a row of units alone for a table ``width`` columns wide: as many cells (or one
    fewer, a trailing separator's), each a unit (:func:`_unit_cell`), none a number, most filled."""
    cells = _row_cells(row)
    while len(cells) > 1 and not cells[-1]:
        cells.pop()
    if not (width - 1 <= len(cells) <= width) or _numeric_cells(row):
        return False
    if sum(bool(c) for c in cells) < max(1, width - 2) or not all(_unit_cell(c) for c in cells):
        return False
    return not _has_number(c.strip("[]() ") for c in cells)


def _text_row(row: str, width: int) -> bool:
    """Whether ``row`` is a row of words for a table ``width`` columns wide (no cell a number, at most as many
    cells): a header's names or a comments row under them."""
    cells = _row_cells(row)
    return len(cells) <= width and not _has_number(cells)


def _header_after_preamble(rows, content) -> int:
    """The index into ``content`` of the header row: the last text row
    before the first two rows of as many numbers (the row above a row
    of units alone), so that an instrument's metadata lines above it
    ("Operator: ...", "Date: ...") are passed over; 0 when the data start
    directly under the first row or cannot be found."""
    # (a row's numbers decide where the data start: a column of words, blank on most rows, leaves them)
    data = [_data_cells(rows[k]) for k in content[:PREAMBLE_SCAN]]
    nums = [d[1] for d in data]
    i = next((i for i in range(1, len(nums)) if nums[i] >= 2 and (i + 1 == len(nums) or nums[i + 1] == nums[i])),
             None)
    if i is None:
        # one column of numbers (a single channel, no time column: its rate among the metadata above): the
        # text row above the first five rows that are one number each, when there is metadata above it
        one = [_ONE_NUMBER.fullmatch(rows[k].strip()) is not None for k in content[:PREAMBLE_SCAN]]
        i = next((i for i in range(2, len(one)) if all(one[i:i + 5]) and not one[i - 1]), None)
        return 0 if i is None or _has_number(_row_cells(rows[content[i - 1]])) else i - 1
    if i < 2:
        return 0
    width = [max(d[0], d[1]) for d in data]
    if i + 1 < len(width):
        width[i] = max(width[i], width[i + 1])
    h = i - 1
    if h >= 2 and _units_row(rows[content[h - 1]], width[i]) and not _units_row(rows[content[h]], width[i]) \
            and _text_row(rows[content[h]], width[i]) and _text_row(rows[content[h - 2]], width[i]):
        # Origin's three header rows: the long names, the units and the comments ("", "run 3", "stage
        # encoder"): the header is the first (read_table reads the units under it and passes the comments)
        return h - 2
    above = rows[content[h]]
    cells = [c for c in re.split(r"[,;\t]|\s+", above.strip()) if c]
    if h >= 1 and all(len(_unquote(c)) <= 12 for c in cells) and len(cells) <= width[i] and \
            any(_unit_cell(_unquote(c)) for c in cells if _unquote(c).strip()):
        # a row of units alone under the header ("s,N,N"; one of them a unit at least: a video tracker's "t  x"
        # under its track's name is the header): the header is the row above it
        prev = rows[content[h - 1]]
        # (split as the row is written: a whitespace table's header has no comma, semicolon or TAB)
        seps = r"[,;\t]" if re.search(r"[,;\t]", prev) else r"\s+"
        if len([c for c in re.split(seps, prev.strip()) if c.strip()]) == width[i] and not _numeric_cells(prev):
            h -= 1
    # a header has no number in it (a data row with a word in it is a bad row, named as such); its cells split
    # as the row is written (catman's "Time  1 - default sample rate" is one TAB-separated cell, not a number)
    return 0 if _has_number(_row_cells(rows[content[h]])) else h


#: a line that states the sampling rate: its name, then a number and a unit of frequency (the unit may
#: stand in brackets after the name instead: "Sampling frequency (Hz);500")
_FREQ_UNITS = r"hz|khz|mhz|s/s|ks/s|sps|ksps|samples?/s(?:ec)?"
_TIME_UNITS = r"s|sec|ms|us|µs|ns"
_NUMBER = r"([-+]?\d+(?:[.,]\d*)?(?:[eE][-+]?\d+)?)"
_RATE_LINE = re.compile(r"(?:sampl\w*|scan|acquisition|acq|daq)[\s_.-]*(?:rate|frequency|freq)\b\s*"
                        rf"(?:[\[(]\s*({_FREQ_UNITS})\s*[\])])?\W*?{_NUMBER}\s*\(?\s*({_FREQ_UNITS})?\b",
                        re.IGNORECASE)
#: ... or the interval between samples, a number and a unit of time
_STEP_LINE = re.compile(r"(?:sampl\w*[\s_.-]*(?:interval|period|time|step)|delta[\s_.-]?[tx]|time[\s_.-]*"
                        rf"(?:step|increment|interval|base)|dt)\b\s*(?:[\[(]\s*({_TIME_UNITS})\s*[\])])?\W*?"
                        rf"{_NUMBER}\s*\(?\s*({_TIME_UNITS})?\b", re.IGNORECASE)
_RATE_UNIT = {"": 1.0, "hz": 1.0, "khz": 1e3, "mhz": 1e6, "s/s": 1.0, "ks/s": 1e3, "sps": 1.0, "ksps": 1e3}
_STEP_UNIT = {"": 1.0, "s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "ns": 1e-9}


def stated_rate(lines) -> tuple | None:
    """The sampling rate that an instrument's metadata lines state: the
    first line naming a sampling rate or frequency ("Sample rate: 2 kHz",
    "Sampling frequency (Hz);500", "# fs_rate = 1000 S/s") or the interval
    between samples ("Sampling interval: 0.5 ms", "Delta_X  0.001",
    "dt = 1e-3 s") with a positive number, in Hz.  ``lines``: (file line,
    text) pairs.  Returns (rate, file line, the line's text), the rate None
    where the number can be read two ways ("2,000": a thousands separator or
    a decimal comma; not guessed), or None when no line states one."""
    for k, text in lines:
        for pat, units, inv in ((_RATE_LINE, _RATE_UNIT, False), (_STEP_LINE, _STEP_UNIT, True)):
            m = pat.search(text)
            if not m:
                continue
            unit = (m.group(1) or m.group(3) or "").lower()
            unit = {"sec": "s", "samples/s": "s/s", "sample/s": "s/s", "samples/sec": "s/s",
                    "sample/sec": "s/s"}.get(unit, unit)
            if unit not in units:
                continue
            if re.fullmatch(r"[-+]?\d{1,3}(?:,\d{3})+", m.group(2)):
                return None, k, text.strip()[:80]
            try:
                v = float(m.group(2).replace(",", ".")) * units[unit]
            except ValueError:
                continue
            if v > 0 and math.isfinite(v):
                return (1.0 / v if inv else v), k, text.strip()[:80]
    return None


#: a line that states a video's image scale: a length per pixel, or pixels per length
_SCALE_LINE = re.compile(rf"{_NUMBER}\s*(mm|um|µm|cm|m)\s*(?:/|per)\s*(?:px|pix|pixels?)\b|"
                         rf"{_NUMBER}\s*(?:px|pix|pixels?)\s*(?:/|per)\s*(mm|um|µm|cm|m)\b", re.IGNORECASE)
_SCALE_MM = {"mm": 1.0, "um": 1e-3, "µm": 1e-3, "cm": 10.0, "m": 1e3}


def stated_scale(lines) -> tuple | None:
    """The image scale a video tracker's metadata lines state ("# scale:
    0.2304 mm/px", "Calibration: 4.3 pixels per mm"): (mm per pixel, file
    line, the line's text) or None."""
    for k, text in lines:
        m = _SCALE_LINE.search(text)
        if not m:
            continue
        try:
            if m.group(1) is not None:
                v = float(m.group(1).replace(",", ".")) * _SCALE_MM[m.group(2).lower()]
            else:
                v = _SCALE_MM[m.group(4).lower()] / float(m.group(3).replace(",", "."))
        except (ValueError, ZeroDivisionError, KeyError):
            continue
        if v > 0 and math.isfinite(v):
            return v, k, text.strip()[:80]
    return None


def _track_names(rows, k0: int, names: list, sep) -> list | None:
    """A header whose names repeat (a video tracker's multi-track table:
    ``t  x  y  x  y`` under a row naming the tracks, ``   mass A     mass B``,
    Tracker's "#multi:" export) with each track's name before its columns'
    ("mass A x", "mass A y", "mass B x", ...): a name in the row above
    stands over its column and those after it up to the next; None when the
    row above names no track over a repeated name."""
    ka = next((k for k in range(k0 - 1, -1, -1) if rows[k].strip() and not _is_comment(rows[k])), None)
    if not sep or ka is None or _numeric_cells(rows[ka]):
        return None                       # (a whitespace row keeps no place for an empty cell)
    cells = [_unquote(c).strip() for c in rows[ka].split(sep)]
    over, cur = [], ""
    for j in range(len(names)):
        cur = cells[j] if j < len(cells) and cells[j] else cur
        over.append(cur)
    out = [f"{o} {n}" if o and n else n for o, n in zip(over, names)]
    return out if len(set(out)) == len(out) else None


#: a header cell tagged with the run it belongs to: a logger's export of several runs side by side (PASCO
#: Capstone's "Time (s) Run #1", Vernier Logger Pro's and Graphical Analysis' "Run 1: Time (s)", "Latest: ...")
_RUN_PREFIX = re.compile(r"^\s*(run\s*#?\s*\d+|latest)\s*:\s*(.+)$", re.IGNORECASE)
_RUN_SUFFIX = re.compile(r"^(.+?)\s+(run\s*#?\s*\d+)\s*$", re.IGNORECASE)


def _run_label(text: str) -> str:
    """'Run #1', 'run 1', 'RUN1', '1' -> 'run 1'; 'Latest' -> 'latest'."""
    t = text.strip().lower()
    m = re.fullmatch(r"(?:run\s*#?\s*)?(\d+)", t)
    return f"run {int(m.group(1))}" if m else t


def _run_columns(head, least: int = 2):
    """The header's cells by run, {label: [(column, the cell less its tag)]}, when every named cell carries a
    run's tag and there are ``least`` runs or more; None otherwise (one run's tags are left as they were
    read)."""
    runs, named = {}, 0
    for j, h in enumerate(head):
        if not h.strip():
            continue
        named += 1
        m = _RUN_PREFIX.match(h)
        if m:
            runs.setdefault(_run_label(m.group(1)), []).append((j, m.group(2).strip()))
            continue
        m = _RUN_SUFFIX.match(h)
        if not m:
            return None
        runs.setdefault(_run_label(m.group(2)), []).append((j, m.group(1).strip()))
    return runs if len(runs) >= least and sum(len(v) for v in runs.values()) == named else None


def _pick_cells(row: str, sep, cols) -> str:
    """A data row cut to the columns ``cols`` (blank when they are all empty: a shorter run has ended)."""
    cells = _cells(row, sep)
    picked = [cells[j] if j < len(cells) else "" for j in cols]
    # (a cell the csv reader unquoted is quoted again where it holds the separator: "12,345.6")
    picked = ['"' + c.replace('"', '""') + '"' if sep in c or '"' in c else c for c in picked]
    return sep.join(picked) if any(_unquote(c).strip() for c in picked) else ""


def read_table(path, expect: str, missing: str = "error", unused=None, sparse=None, names=None,
               run=None) -> Table:
    """Read a delimited numeric table with a header row.

    Parameters
    ----------
    path : str or path-like
        The file: comma, semicolon, TAB or whitespace separated (the header
        row decides); blank lines and comment lines (``#``, ``%``, ``//``)
        are skipped, also before the header, and so are lines of text
        above the header (an instrument's metadata) when the numeric rows
        start further down (:attr:`Table.preamble` counts them).  A header cell may be
        quoted and carry its unit as ``name [unit]``, ``name (unit)`` or
        ``name/unit``; a row of units alone under the header is read as
        the units.  With a semicolon, TAB or whitespace separator a decimal
        comma is read (``0,125``).
    expect : str
        What the header should look like, for the messages.
    missing : {"error", "drop"}
        A row with a missing value (an empty cell, ``NaN``, ``NA``, ...):
        an error naming it, or dropped (the rows kept are counted in
        :attr:`Table.dropped`; more than :data:`MAX_MISSING` of the rows
        is an error all the same).
    unused : callable, optional
        ``unused(name, unit)`` true for a column the caller does not read (a
        temperature, a comment): its cells are not parsed (NaN in the table)
        and neither a word nor a gap in it refuses or drops a row.
    sparse : callable, optional
        ``sparse(name, unit)`` true for a column that may be logged on fewer
        rows than the others (a stage's position every tenth row): with
        ``missing="drop"`` a gap in it does not drop the row; it is filled
        linearly between the column's values (:attr:`Table.filled` counts
        them).
    names : sequence of str, optional
        The columns' header cells in order (``["t [s]", "F [N]"]``), given
        by the user: they replace the file's header (a data-acquisition
        program's ``Dev1/ai0``), or head a file that has none (its first
        row is then data); a MATLAB or NumPy file's one matrix is read
        column by column under them.
    run : str or int, optional
        The run to read from a logger's export of several runs side by
        side, each column's name tagged with its run (``"Time (s) Run #2"``,
        ``"Run 2: Time (s)"``, ``"Latest: Force (N)"``): ``2``, ``"Run #2"``
        or ``"latest"``.  Such a file is refused without it, naming its runs.

    Returns
    -------
    Table

    Raises
    ------
    LiengInputError
        An unreadable file, a row with too few cells, a non-numeric or
        non-finite cell (naming its line and column).
    """
    given = None if names is None else [_name_unit(_unquote(str(h))) for h in names]
    if given is not None and (not given or not all(nm.strip() for nm, _ in given)):
        raise LiengInputError(f"--names: {', '.join(map(str, names))!r}: a name for each column, comma-separated "
                              f"('t [s],F [N],N [N]')")
    if str(path).lower().endswith(ARRAY_FILES):
        if run is not None:
            raise LiengInputError(f"--run {run}: applies to a table's columns tagged with their runs, not to "
                                  f"{path}")
        return _read_arrays(path, expect, given)
    if str(path).lower().endswith(WORKBOOKS):
        text, encoding = _workbook_text(path), "xlsx"
    else:
        text, encoding = read_table_text(path)
    if text.startswith("\ufeff"):
        text = text[1:]
    rows = split_lines(text)
    del text                              # (the rows hold it now: a long record's text is not kept twice)
    if rows and re.fullmatch(r"\s*\"?sep=.\"?\s*", rows[0], re.IGNORECASE):
        rows[0] = ""                      # Excel's separator hint ("sep=;"): the header follows
    if len(rows) > MAX_ROWS + 1 and sum(1 for r in rows if r.strip()) > MAX_ROWS + 1:
        raise LiengInputError(f"{path}: more than {MAX_ROWS} rows: split the record (lieng reads at most "
                              f"{MAX_ROWS} rows)")
    content = []
    for k, r in enumerate(rows):
        if r.strip() and not _is_comment(r):
            content.append(k)
            if len(content) > PREAMBLE_SCAN:
                break
    if not content:
        raise LiengInputError(f"{path}: empty file: expected a header {expect}")
    lvm = _lvm_header(rows)
    if lvm is not None:
        for k in lvm[2]:
            rows[k] = ""                  # a later segment's channel header and column names
    skipped = _header_after_preamble(rows, content) if lvm is None else \
        next((i for i, k in enumerate(content) if k > lvm[0]), 0)
    k0 = content[skipped]
    k1 = next((k for k in range(k0 + 1, len(rows)) if rows[k].strip() and not _is_comment(rows[k])), None)
    first = None if k1 is None else rows[k1]
    header_row = rows[k0]
    from_comment, units_c = False, None
    if skipped == 0 and _numeric_cells(rows[k0]):
        # no header above the numbers: the comment line just above them, when it names as many columns
        # (numpy.savetxt writes its header as "# t [s],F [N]")
        above = next((rows[k] for k in range(k0 - 1, -1, -1) if rows[k].strip()), None)
        if above is not None and _is_comment(above):
            cand = above.lstrip().lstrip("#%/").strip()
            _, cells_c = _split_header(cand, rows[k0])
            if len([c for c in cells_c if c]) == _numeric_cells(rows[k0]) and not _numeric_cells(cand):
                header_row, from_comment = cand, True
                first, k1, k0 = rows[k0], k0, k0 - 1
                # a comment line of units alone ("#  [s]  [N]"): the names are the comment line above it
                ka = next((k for k in range(k0 - 1, -1, -1) if rows[k].strip()), None)
                names_c = rows[ka].lstrip().lstrip("#%/").strip() if ka is not None and _is_comment(rows[ka]) \
                    else None
                if names_c and _units_row(cand, len(cells_c)) and _text_row(names_c, len(cells_c)) and \
                        len([c for c in _split_header(names_c, first)[1] if c]) == len(cells_c):
                    header_row, from_comment = names_c, "units"
                    units_c = [c.strip("[]() ") for c in cells_c]
    headless = not from_comment and _numeric_row(header_row)
    if headless and given is None:
        ncol = max(_numeric_cells(header_row), 1)
        raise LiengInputError(
            f"{path}: {ncol} column{'s' if ncol > 1 else ''} of numbers and no header naming "
            f"{'them' if ncol > 1 else 'it'}: add a first line such as 't [s],F [N],position [mm]' (or 't [s],x [mm]'), "
            f"in the columns' order, or give them with --names")
    if headless:
        # the user's names head a file without a header: its first row is data
        sep = _data_separator(header_row, len(given))
        if sep is False:
            raise LiengInputError(f"{path}: line {k0 + 1}: not {len(given)} numbers, as --names has names "
                                  f"({', '.join(nm for nm, _ in given)})")
        head, first, k1, k0 = [f"{nm} [{un}]" if un else nm for nm, un in given], None, k0 - 1, k0 - 1
    else:
        sep, head = _split_header(header_row, first)
    head = [_unquote(h) for h in head]
    while len(head) > 1 and not head[-1]:
        head.pop()                        # a separator at the end of every line
    byrun = _run_columns(head, 1) if given is None else None
    several = byrun is not None and len(byrun) > 1 and bool(sep)     # (runs side by side need a separator)
    want = None if run is None else _run_label(str(run))
    if run is None and several:
        num = next((lb.split()[1] for lb in byrun if lb.startswith("run ")), "latest")
        raise LiengInputError(f"{path}: header: {len(byrun)} runs side by side ({', '.join(byrun)}): choose one "
                              f"with --run (e.g. --run {num})")
    if run is not None and byrun is None:
        raise LiengInputError(f"--run {run}: {path}'s header holds no such run (its columns are not tagged "
                              f"'Run #{run}', 'Run {run}:')")
    if run is not None and want not in byrun:
        raise LiengInputError(f"--run {run}: not among the runs of {path} ({', '.join(byrun)})")
    if run is not None and several:
        cols = [j for j, _ in byrun[want]]
        head = [h for _, h in byrun[want]]
        # the chosen run's cells alone, from the row after the header on (a shorter run's rows end blank)
        rows = rows[:k0 + 1] + [_pick_cells(r, sep, cols) if r.strip() and not _is_comment(r) else r
                                for r in rows[k0 + 1:]]
        k1 = next((k for k in range(k0 + 1, len(rows)) if rows[k].strip() and not _is_comment(rows[k])), None)
        first = None if k1 is None else rows[k1]
    names, units = [], []
    for h in head:
        nm, un = _name_unit(h)
        names.append(nm)
        units.append(un)
    if units_c is not None and not any(units) and len(units_c) == len(names):
        units = units_c
    if lvm is not None:
        names, units = _lvm_names(names, units, lvm[1])
    tracks = _track_names(rows, k0, names, sep) if len(set(names)) < len(names) and given is None else None
    if tracks is not None:
        names = tracks
    if given is not None:
        if len(given) != len(names):
            raise LiengInputError(f"--names: {len(given)} names for the {len(names)} columns of {path}'s header "
                                  f"({', '.join(names)[:200]})")
        names, units = [nm for nm, _ in given], [un for _, un in given]
    ncol = len(names)
    comma = sep != ","
    start = k0 + 1
    comments_row = None
    if first is not None:
        # a row of units alone under the header ("s,N,N"): no cell of it is a number
        cells = [_unquote(c) for c in (first.split(sep) if sep else first.split())][:ncol]
        # (a column without a unit may leave its cell empty: a rheometer's "Point No." under "[s]", "[N·m]")
        unitlike = len(cells) == ncol and all(len(c) <= 12 for c in cells) and \
            sum(bool(c.strip()) for c in cells) >= max(1, ncol - 2)
        # (a unit is no number: a data row whose first cell is a word, an ATI sensor's status '0x00000000', is
        # no row of units; one number is allowed, a unitless column's '1')
        nums = sum(1 for c in cells if c.strip() and _is_number_cell(c, comma))
        if unitlike and nums <= 1 and nums < sum(bool(c.strip()) for c in cells):
            # (a header's parenthesis that is no unit, Bluehill's "Tensile strain (Extension)", is part of
            # the name when a row of units follows)
            odd = [j for j, u in enumerate(units) if u and not _unit_cell(u)]
            if not any(units) or given is not None or odd:
                if odd and given is None:
                    names = [f"{nm} ({u})" if j in odd else nm for j, (nm, u) in enumerate(zip(names, units))]
                    units = [""] * len(units)
                units = units if any(units) else [c.strip("[]() ") for c in cells]
                start = k1 + 1
                # Origin's comments row under the units (its first cell often empty): no number in it
                k2 = next((k for k in range(start, len(rows)) if rows[k].strip() and not _is_comment(rows[k])),
                          None)
                if k2 is not None and not _data_cells(rows[k2])[1] and _text_row(rows[k2], ncol):
                    start, comments_row = k2 + 1, k2 + 1
    # a first data row of more values than the header has names: a name left out of the header, and every
    # column after it would be read under its neighbour's name
    k_first = next((k for k in range(start, len(rows)) if rows[k].strip() and not _is_comment(rows[k])), None)
    if k_first is not None and sep is not None:
        vals = [c for c in _cells(rows[k_first], sep) if _unquote(c)]
        if len(vals) > ncol and all(_is_number_cell(c, comma or (sep == "," and "," in c)) for c in vals):
            raise LiengInputError(f"{path}: line {k_first + 1}: {len(vals)} values where the header names {ncol} "
                                  f"columns ({', '.join(names)[:160]}): a column's name is missing from the header "
                                  f"(give them all with --names)")
    skip = [bool(unused and unused(n, u)) for n, u in zip(names, units)]
    thin = [bool(missing == "drop" and sparse and not skip[j] and sparse(n, u))
            for j, (n, u) in enumerate(zip(names, units))]
    fast = _plain_block(rows, start, sep, ncol, skip, comma, missing)
    if fast is not None:
        arr, lines = fast
        dropped = repeated = footer = 0
        dates = {}
    else:
        data, lines = [], []
        dropped = repeated = footer = 0
        head_key = None if headless else header_row.strip()
        dates = {}                            # column -> its first date-time (ns): the others are seconds from it
        days, last_ns = {}, {}                # a time of day alone: days passed (ns), the last stamp
        for r in range(start, len(rows)):
            row = rows[r]
            if not row.strip() or _is_comment(row):
                continue
            if len(row) > MAX_LINE:
                raise LiengInputError(f"{path}: line {r + 1}: longer than {MAX_LINE} characters: not a table row")
            if data and row.strip() == head_key:
                repeated += 1                 # the header again: a second run appended to the file
                continue
            cells = _cells(row, sep)
            if len(cells) < ncol and not (missing == "drop" and sep):
                raise LiengInputError(f"{path}: line {r + 1}: {len(cells)} cells where the header has {ncol}")
            vals = []
            for c in range(ncol):
                if skip[c]:
                    vals.append(math.nan)
                    continue
                cell = _unquote(cells[c]) if c < len(cells) else ""
                if missing == "drop" and cell.lower() in MISSING:
                    if thin[c]:
                        vals.append(math.nan)     # filled below
                        continue
                    vals = None
                    break
                try:
                    if c in dates:
                        raise ValueError(cell)
                    # (a quoted cell of a comma-separated row may hold a decimal comma: "0,5")
                    val = _number(cell, comma or (sep == "," and "," in cell))
                except ValueError:
                    ns = _datetime_ns(cell) if c in dates or not data else None
                    if ns is None and len(data) >= MIN_FOOTER_ROWS and _footer_from(rows, r):
                        vals = "footer"
                        break
                    if ns is None:
                        raise LiengInputError(f"{path}: line {r + 1}, column {names[c]}: {cell[:40]!r} is not a "
                                              f"number" + (" (nor a date-time like its first row's)" if c in dates
                                                           else "")) from None
                    if ns < _DAY_NS and c in dates:
                        # the time of day alone: a fall of more than half a day is the clock passing midnight
                        while ns + days.get(c, 0) < last_ns[c] - _DAY_NS // 2:
                            days[c] = days.get(c, 0) + _DAY_NS
                        ns += days.get(c, 0)
                    last_ns[c] = ns
                    val = (ns - dates.setdefault(c, ns)) * 1e-9
                if not math.isfinite(val):
                    if thin[c] and math.isnan(val):
                        vals.append(val)
                        continue
                    if missing == "drop" and math.isnan(val):
                        vals = None
                        break
                    raise LiengInputError(f"{path}: line {r + 1}, column {names[c]}: {cell} is not a finite number")
                if abs(val) > MAX_ABS:
                    raise LiengInputError(f"{path}: line {r + 1}, column {names[c]}: {cell} is out of range for a "
                                          f"measurement (|value| > {MAX_ABS:g})")
                vals.append(val)
            if vals == "footer":
                footer = sum(1 for q in rows[r:] if q.strip() and not _is_comment(q))
                break
            if vals is None:
                dropped += 1
                continue
            data.append(vals)
            lines.append(r + 1)
        if dropped and dropped > MAX_MISSING * (dropped + len(data)):
            raise LiengInputError(f"{path}: {dropped} of {dropped + len(data)} rows miss a value (more than "
                                  f"{100 * MAX_MISSING:g} %): not a record to resample")
        arr = np.asarray(data, float).reshape(len(data), ncol)
    tab = Table(path, names, units, {n: arr[:, j] for j, n in enumerate(names)}, lines)
    tab.dropped = dropped
    tab.preamble = skipped
    tab.comments_row = comments_row
    # (the lines above the header: the instrument's metadata and comment lines)
    above = [(k + 1, rows[k]) for k in range(0, k0) if rows[k].strip()]
    tab.stated_rate = stated_rate(above)
    tab.stated_scale = stated_scale(above)
    if lvm is not None:
        tab.segments = lvm[3]
    for c in np.flatnonzero(thin):
        have = np.isfinite(arr[:, c])
        if have.all():
            continue
        if np.count_nonzero(have) < 2:
            raise LiengInputError(f"{path}: column {names[c]}: a value on {np.count_nonzero(have)} of {arr.shape[0]} "
                                  f"rows: too few to read it between them")
        k = np.arange(arr.shape[0], dtype=float)
        arr[:, c] = np.interp(k, k[have], arr[have, c])
        tab.filled[names[c]] = (int(np.count_nonzero(have)), arr.shape[0])
    tab.dates = {}
    for c, ns in dates.items():
        if ns < _DAY_NS:                  # the time of day alone
            tab.dates[names[c]] = "the time of day " + str(np.datetime64(ns, "ns"))[11:]
        else:
            tab.dates[names[c]] = str(np.datetime64(ns, "ns"))
    tab.encoding, tab.comment_header, tab.repeated, tab.footer = encoding, from_comment, repeated, footer
    return tab


#: files of named arrays read as tables: MATLAB (v4 to v7) and NumPy archives
ARRAY_FILES = (".mat", ".npz")
#: spreadsheet workbooks read as tables (Office Open XML: the first worksheet)
WORKBOOKS = (".xlsx", ".xlsm")


def _workbook_text(path) -> str:
    """The first worksheet of an Office Open XML workbook (``.xlsx``, as a
    tribometer's software or a spreadsheet saves it) as TAB-separated text,
    one row a line, for :func:`read_table` to read as it reads a text
    export: numbers as stored (full precision; a date-time stays Excel's
    serial day, which the record's reader knows by the column's name),
    shared and inline strings as text, empty cells empty.  Standard
    library only (zip + XML)."""
    import io
    import posixpath
    import zipfile
    import xml.etree.ElementTree as ET

    ns = {"m": "http://schemas.openxmlformats.org/spreadsheetml/2006/main",
          "r": "http://schemas.openxmlformats.org/officeDocument/2006/relationships",
          "p": "http://schemas.openxmlformats.org/package/2006/relationships"}
    raw = read_bytes(path, "record")
    try:
        with zipfile.ZipFile(io.BytesIO(raw)) as z:
            names = set(z.namelist())
            wb = ET.fromstring(z.read("xl/workbook.xml"))
            sheet = wb.find("m:sheets/m:sheet", ns)
            target = "xl/worksheets/sheet1.xml"
            if sheet is not None and "xl/_rels/workbook.xml.rels" in names:
                rid = sheet.get(f"{{{ns['r']}}}id")
                rels = ET.fromstring(z.read("xl/_rels/workbook.xml.rels"))
                for rel in rels.findall("p:Relationship", ns):
                    if rel.get("Id") == rid:
                        tg = rel.get("Target", "")
                        target = tg.lstrip("/") if tg.startswith("/") else posixpath.normpath("xl/" + tg)
            shared = []
            if "xl/sharedStrings.xml" in names:
                for si in ET.fromstring(z.read("xl/sharedStrings.xml")).findall("m:si", ns):
                    shared.append("".join(t.text or "" for t in si.iter(f"{{{ns['m']}}}t")))
            root = ET.fromstring(z.read(target))
    except (zipfile.BadZipFile, KeyError, ET.ParseError, OSError) as exc:
        raise LiengInputError(f"{path}: not a readable .xlsx workbook ({str(exc)[:80]}): save the sheet as CSV") \
            from None

    def col(ref: str) -> int:
        n = 0
        for ch in ref:
            if not ch.isalpha():
                break
            n = 26 * n + ord(ch.upper()) - 64
        return n - 1

    lines = []
    for row in root.iter(f"{{{ns['m']}}}row"):
        cells = {}
        for k, c in enumerate(row.findall("m:c", ns)):
            j = col(c.get("r", "")) if c.get("r") else k
            kind, v = c.get("t", "n"), c.find("m:v", ns)
            if kind == "s" and v is not None:
                text = shared[int(v.text)] if v.text and int(v.text) < len(shared) else ""
            elif kind == "inlineStr":
                text = "".join(t.text or "" for t in c.iter(f"{{{ns['m']}}}t"))
            else:
                text = v.text if v is not None and v.text is not None else ""
            cells[j] = text.replace("\t", " ").replace("\n", " ").strip()
        if cells:
            lines.append("\t".join(cells.get(j, "") for j in range(max(cells) + 1)))
    if not lines:
        raise LiengInputError(f"{path}: the workbook's first sheet is empty")
    return "\n".join(lines) + "\n"


def _read_arrays(path, expect: str, given=None) -> Table:
    """A MATLAB ``.mat`` file (v4 to v7) or a NumPy ``.npz`` archive as a
    table: each numeric vector (1-D, n x 1 or 1 x n) of the most common
    length is a column named by its variable (no units: give them by the
    names' conventions or the options); variables of other lengths and
    shapes are passed over and said.  ``given``: the user's (name, unit)
    of each column of the file's one numeric matrix (n x k or k x n, k
    the names' number), read column by column."""
    import io
    import zipfile

    raw = read_bytes(path, "record")
    npz = str(path).lower().endswith(".npz")
    try:
        if npz:
            with np.load(io.BytesIO(raw), allow_pickle=False) as z:
                arrays = {k: z[k] for k in z.files}
        else:
            if raw[:128].find(b"MATLAB 7.3") >= 0 or raw[:8] == b"\x89HDF\r\n\x1a\n":
                raise LiengInputError(f"{path}: a MATLAB v7.3 (HDF5) file: save it with save(..., '-v7') or "
                                      f"export a CSV ({expect})")
            import scipy.io

            arrays = {k: v for k, v in scipy.io.loadmat(io.BytesIO(raw), squeeze_me=False).items()
                      if not k.startswith("__")}
    except LiengInputError:
        raise
    except (ValueError, OSError, zipfile.BadZipFile, TypeError, NotImplementedError, KeyError) as exc:
        raise LiengInputError(f"{path}: not a readable {'NumPy archive' if npz else 'MATLAB file'} "
                              f"({str(exc)[:80]})") from None
    if given is not None:
        k = len(given)
        mats = [(name, a) for name, a in ((nm, np.asarray(v)) for nm, v in arrays.items())
                if a.dtype.kind in "iuf" and a.ndim == 2 and k in a.shape and max(a.shape) > k]
        if len(mats) != 1:
            raise LiengInputError(f"{path}: --names: {len(mats)} numeric matrices of {k} columns (or rows) in the file "
                                  f"(variables: {', '.join(sorted(arrays))[:120]}): --names reads one")
        name, m = mats[0]
        m = m if m.shape[1] == k else m.T
        other = sorted(a for a in arrays if a != name)
        arrays = {f"{name}[:, {j + 1}]": m[:, j] for j in range(k)}
    else:
        other = []
    vec = {}
    for k, v in arrays.items():
        a = np.asarray(v)
        if a.dtype.kind in "iuf" and a.ndim <= 2 and a.size >= 2 and (a.ndim == 1 or min(a.shape) == 1):
            vec[k] = a.astype(float).ravel()
        else:
            other.append(k)
    if not vec:
        raise LiengInputError(f"{path}: no numeric vector in it (variables: {', '.join(sorted(arrays))[:120]}); "
                              f"expected vectors named as the columns {expect}, or one matrix whose columns "
                              f"--names names")
    lengths = [v.size for v in vec.values()]
    n = max(set(lengths), key=lambda m: (lengths.count(m), m))
    names = [k for k, v in vec.items() if v.size == n]
    other += [k for k in vec if vec[k].size != n]
    # a NaN is a missing value, as in a text table: its sample is left out and said (the record is resampled
    # across it); an infinity or an absurd magnitude is no measurement
    missing = np.zeros(n, bool)
    for k in names:
        missing |= np.isnan(vec[k])
        bad = np.flatnonzero(np.isinf(vec[k]) | (np.abs(np.nan_to_num(vec[k])) > MAX_ABS))
        if bad.size:
            raise LiengInputError(f"{path}: variable {k}, element {bad[0] + 1}: {vec[k][bad[0]]} is not a finite "
                                  f"measurement")
    if n > MAX_ROWS:
        raise LiengInputError(f"{path}: more than {MAX_ROWS} samples: split the record")
    keep = ~missing
    units = [""] * len(names)
    if given is not None:
        cols = {nm: vec[k] for (nm, _), k in zip(given, names)}
        names, units = [nm for nm, _ in given], [un for _, un in given]
        vec = cols
    tab = Table(path, names, units, {k: vec[k][keep] for k in names}, np.arange(1, n + 1)[keep])
    tab.passed_over = sorted(other)
    tab.dropped = int(np.count_nonzero(missing))
    return tab


def _plain_block(rows, start: int, sep, ncol: int, skip, comma: bool, missing: str):
    """The data rows parsed at once by NumPy's reader, when they are plain:
    every row has a finite number in each read column and nothing the
    row-by-row reader treats apart (quotes, comments, a repeated header,
    date-times, a footer, a missing value, a typeset minus, an
    out-of-range value).  ``None`` otherwise: the row-by-row reader then
    reads them (and names the line of anything wrong)."""
    block = rows[start:]
    if len(block) < 1000 or (any(skip) and not (missing == "drop" and sep)):
        return None                       # (a short row is refused unless it may miss a value)
    # (the line numbers as an array, the rows handed to NumPy's reader as they are: a joined copy of a
    # 2.4 M-row file in a StringIO took 400 MB more than the rows themselves)
    full = np.fromiter((bool(q.strip()) for q in block), bool, len(block))
    lines = np.flatnonzero(full) + (start + 1)
    if not lines.size:
        return None
    if any(any(ch in q for ch in ('"', "#", "%", "//", "_", "\u2212")) for q in block) \
            or max(map(len, block)) > MAX_LINE:
        return None
    cols = [j for j in range(ncol) if not skip[j]]
    if not cols:
        return None
    import warnings

    src = [q for q, f in zip(block, full) if f] if not np.all(full) else block
    if comma:
        src = (q.replace(",", ".") for q in src)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            got = np.loadtxt(src, delimiter=sep, usecols=cols, ndmin=2, dtype=float, comments=None)
    except (ValueError, UserWarning, IndexError):
        return None
    if got.shape[0] != len(lines) or not np.all(np.isfinite(got)) or np.any(np.abs(got) > MAX_ABS):
        return None
    arr = np.full((len(lines), ncol), math.nan)
    arr[:, cols] = got
    return arr, lines


#: a summary after the last row is passed over only below this many rows of data
MIN_FOOTER_ROWS = 50


def _footer_from(rows, r: int) -> bool:
    """Whether the rows from ``r`` on hold no row of numbers (a summary
    written after the data: "Mean force: 2.1 N", "End of test")."""
    return not any(_numeric_cells(q) for q in rows[r:] if q.strip() and not _is_comment(q))


def _is_number_cell(cell: str, decimal_comma: bool) -> bool:
    try:
        _number(_unquote(cell), decimal_comma)
        return True
    except ValueError:
        return False


def _cells(row: str, sep):
    """A data row's cells: split at the separator, outside double quotes."""
    if sep and '"' in row:
        import csv
        return next(csv.reader([row], delimiter=sep))
    return row.split(sep) if sep else row.split()


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
