"""Opening the user's input files: one place for every way a path can fail.

Every input (a card deck, a CSV or other table) is read whole through
:func:`read_text`, which refuses what is not a regular file *before* opening
it (a FIFO would block forever, a device never end), follows symlinks but
names a loop, limits the size, and turns every failure into one
:class:`~lieng.errors.LiengInputError` line naming the file.
"""

from __future__ import annotations

import errno
import os
import re
import stat
from pathlib import Path

from lieng.errors import LiengInputError

__all__ = ["read_text", "read_table_text", "read_bytes", "head", "split_lines", "MAX_BYTES"]

#: the largest input read (bytes): 2 GiB (a 20-million-row table)
MAX_BYTES = 2 * 1024**3


def read_text(path, *, encoding: str = "utf-8", what: str = "file", max_bytes: int = MAX_BYTES) -> str:
    """The text of an input file.

    Parameters
    ----------
    path : str or path-like
        The file.
    encoding : str
        ``"utf-8"`` (a UTF-8 byte-order mark is dropped) or ``"ascii"``.
    what : str
        What the file should be, for the messages ("deck", "table").
    max_bytes : int
        Larger files are refused.

    Raises
    ------
    LiengInputError
        Missing, a directory, not a regular file, a symlink loop, not
        readable, too large, or not valid text in ``encoding``.
    """
    raw = _read_raw(path, what, max_bytes)
    if encoding == "utf-8" and raw.startswith(b"\xef\xbb\xbf"):
        raw = raw[3:]
    try:
        return raw.decode(encoding)
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        kind = "ASCII (a card deck is plain text)" if encoding == "ascii" else f"valid {encoding.upper()} text"
        raise LiengInputError(f"{path}: line {line}, byte {exc.start + 1}: not {kind}") from None


#: a line ends at LF, CRLF or CR only: a form feed, a vertical tab or a TAB is a character of its line
#: (str.splitlines would split a card at a form feed)
_EOL = re.compile(r"\r\n|\r|\n")


def split_lines(text: str) -> list[str]:
    """The lines of ``text``, ending at LF, CRLF or CR only (a final line
    end does not make an empty last line)."""
    lines = _EOL.split(text)
    if len(lines) > 1 and lines[-1] == "":
        lines.pop()
    return lines


def head(path, nbytes: int = 4096, *, what: str = "file") -> str:
    """The first ``nbytes`` of an input file as text (undecodable bytes
    replaced), after the same checks as :func:`read_text`."""
    p = _check(path, what, MAX_BYTES)
    try:
        with open(p, "rb") as fh:
            raw = fh.read(nbytes)
    except OSError as exc:
        raise LiengInputError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    return raw.removeprefix(b"\xef\xbb\xbf").decode("utf-8", errors="replace")


def read_table_text(path, *, max_bytes: int = MAX_BYTES) -> tuple[str, str]:
    """The text of a table as instruments export it, and its encoding:
    UTF-8 (a byte-order mark is dropped); else UTF-16 with its byte-order
    mark; else Shift-JIS (cp932: a Japanese instrument's export, "時間",
    "試験力") where the whole file decodes so and its first 4 kB hold kanji
    or kana written in two bytes; else Windows-1252 (a Latin-1 export:
    "Kraft [N]", "µm").  A file with NUL bytes and none of these is refused
    (a binary file)."""
    raw = _read_raw(path, "table", max_bytes)
    try:
        return raw.decode("utf-8").removeprefix("\ufeff"), "utf-8"
    except UnicodeDecodeError:
        pass
    if raw[:2] in (b"\xff\xfe", b"\xfe\xff"):
        try:
            return raw.decode("utf-16"), "utf-16"
        except UnicodeDecodeError:
            pass
    if b"\x00" in raw:
        raise LiengInputError(f"{path}: not valid UTF-8 text (a binary file?)")
    try:
        text = raw.decode("cp932")
        # (a Latin-1 file seldom decodes as Shift-JIS throughout; where it does, its accented letters become
        # half-width kana, one byte each, never the two-byte kanji, kana or full-width forms a Japanese
        # header is written in)
        if re.search(r"[\u3040-\u30ff\u4e00-\u9fff\uff01-\uff5e]", text[:4096]):
            return text, "shift_jis"
    except UnicodeDecodeError:
        pass
    return raw.decode("cp1252", errors="replace"), "windows-1252"


def read_bytes(path, what: str = "file", max_bytes: int = MAX_BYTES) -> bytes:
    """The bytes of a regular file no larger than ``max_bytes`` (a binary
    format: MATLAB, NumPy), refused as :func:`read_text` refuses."""
    return _read_raw(path, what, max_bytes)


def _read_raw(path, what: str, max_bytes: int) -> bytes:
    """The bytes of a regular file no larger than ``max_bytes``."""
    p = _check(path, what, max_bytes)
    try:
        with open(p, "rb") as fh:
            raw = fh.read(max_bytes + 1)
    except OSError as exc:
        raise LiengInputError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    if len(raw) > max_bytes:
        raise LiengInputError(f"{path}: larger than the {max_bytes} bytes a {what} may have")
    return raw


def _check(path, what: str, max_bytes: int) -> Path:
    """``path`` if it is a regular file no larger than ``max_bytes``."""
    if str(path) == "" or "\0" in str(path):
        raise LiengInputError(f"{path!r}: not a file name")
    p = Path(path)
    try:
        st = os.stat(p)
    except FileNotFoundError:
        raise LiengInputError(f"{path}: no such {what}") from None
    except OSError as exc:
        why = "a symlink loop" if exc.errno == errno.ELOOP else (exc.strerror or str(exc))
        raise LiengInputError(f"{path}: cannot be read ({why})") from None
    if stat.S_ISDIR(st.st_mode):
        raise LiengInputError(f"{path}: is a directory, not a {what}")
    if not stat.S_ISREG(st.st_mode):
        raise LiengInputError(f"{path}: not a regular file (a FIFO, device or socket cannot be a {what})")
    if st.st_size > max_bytes:
        raise LiengInputError(f"{path}: {st.st_size} bytes: larger than the {max_bytes} bytes a {what} may have")
    return p
