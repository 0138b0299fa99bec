"""Output files and directories the commands own, written all at once.

Rules (every command with ``-o``):

* The output directory is checked *before* any computation
  (:func:`check_outdir`): an empty path, a path at or under an existing
  file, or an unwritable location is refused at once.
* A command owns only the files it writes.  Their names are kept in
  ``OUTDIR/.lieng-outputs`` (:data:`MANIFEST`).  An existing directory that
  holds anything else (a user's notes, a directory named like an output) is
  refused unless ``--force``; with ``--force`` the command writes beside
  those entries and never deletes, replaces or enters them (an entry with
  the name of an output that lieng did not write stops the run).
* Every file of a run is written into a fresh temporary directory; only when
  all are written are they moved into place (:func:`staged_outdir`), and the
  outputs of an earlier run that this run does not write again (a plot of a
  run with plots, now ``--no-plots``) are removed, since they are the
  command's own.  A failure leaves the target as it was.
* A single output file (``synth -o FILE``, :func:`check_outfile`) is
  replaced only with ``--force`` and only if it is a regular file.

Numbers written to CSV must be finite (:func:`write_csv` refuses NaN and
infinities; a missing value is written as an empty cell, ``None``) and JSON
is strict (:func:`dumps_json`).
"""

from __future__ import annotations

import csv
import json
import math
import os
import shutil
import stat
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Iterable, Sequence

from lieng.errors import LiengInputError

__all__ = ["MANIFEST", "check_outdir", "check_outfile", "staged_outdir", "write_csv", "write_lines",
           "dumps_json", "finite_json", "all_finite", "replace_file",
           "PLOT_FORMATS", "PLOT_DEFAULT", "plot_output", "plot_settings", "plot_name"]

#: the list of files a command wrote into its output directory
MANIFEST = ".lieng-outputs"


def _existing_ancestor(p: Path, option: str, given) -> Path:
    """The nearest existing ancestor of ``p``; it must be a writable directory."""
    a = p
    while True:
        a = a.parent
        try:
            st = a.stat()
        except FileNotFoundError:
            if a == a.parent:               # pragma: no cover - the root exists
                break
            continue
        except OSError as exc:
            raise LiengInputError(f"{option} {given}: {a} cannot be used ({exc.strerror})") from None
        _writable_dir(a, st, f"{option} {given}: {a} is a file, not a directory",
                      f"{option} {given}: cannot create it: {a} is not writable")
        return a
    raise LiengInputError(f"{option} {given}: no existing directory above it")  # pragma: no cover


def _writable_dir(path: Path, st, not_dir: str, not_writable: str) -> None:
    """Raise ``not_dir`` unless ``st`` (of ``path``) is a directory, and
    ``not_writable`` unless the directory can be written and entered."""
    if not stat.S_ISDIR(st.st_mode):
        raise LiengInputError(not_dir)
    if not os.access(path, os.W_OK | os.X_OK):
        raise LiengInputError(not_writable)
    try:
        # the permission bits do not tell all (root on a read-only or virtual file system): the staging
        # directory the outputs are written into will be made here, so make one now and take it away
        os.rmdir(tempfile.mkdtemp(prefix=".lieng-probe.", dir=path))
    except OSError as exc:
        raise LiengInputError(f"{not_writable} ({exc.strerror or exc})") from None


def _owned(target: Path) -> set[str]:
    try:
        text = (target / MANIFEST).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return set()
    return {ln for ln in text.splitlines() if ln and "/" not in ln and ln not in (".", "..")}


def check_outdir(outdir, force: bool = False, option: str = "-o") -> Path:
    """Check, before any computation, that the command may write ``outdir``.

    Parameters
    ----------
    outdir : str or path-like
        The output directory (created when missing, with its parents).
    force : bool
        Write into a directory that holds entries the command did not write
        (they are left as they are).
    option : str
        The option's name, for the message.

    Returns
    -------
    Path
        ``outdir`` as a path.

    Raises
    ------
    LiengInputError
        An empty path; a path at or under a file; an unwritable location; an
        existing directory with foreign entries and no ``force``.
    """
    given = "''" if str(outdir) == "" else outdir
    if str(outdir) == "" or "\0" in str(outdir):
        raise LiengInputError(f"{option} {given}: not a directory name")
    target = Path(outdir)
    try:
        st = target.stat()
    except FileNotFoundError:
        if os.path.islink(target):
            raise LiengInputError(f"{option} {given}: a symbolic link to nothing ({os.readlink(target)})") from None
        _existing_ancestor(target.absolute(), option, given)
        return target
    except NotADirectoryError:
        _existing_ancestor(target.absolute(), option, given)
        return target                       # pragma: no cover - the ancestor check raised
    except OSError as exc:
        raise LiengInputError(f"{option} {given}: cannot be used ({exc.strerror})") from None
    _writable_dir(target, st, f"{option} {given}: exists and is not a directory",
                  f"{option} {given}: the directory is not writable")
    man = target / MANIFEST
    if os.path.lexists(man) and (man.is_symlink() or not man.is_file()):
        raise LiengInputError(f"{option} {given}: {man} is not lieng's list of outputs (not a regular file): "
                              f"choose a new directory")
    foreign = sorted(set(os.listdir(target)) - _owned(target) - {MANIFEST})
    if foreign and not force:
        shown = ", ".join(foreign[:3]) + (", ..." if len(foreign) > 3 else "")
        raise LiengInputError(f"{option} {given}: the directory holds {len(foreign)} entr"
                              f"{'y' if len(foreign) == 1 else 'ies'} lieng did not write ({shown}): choose a "
                              f"new directory, or give --force to write beside them")
    return target


def check_outfile(path, force: bool = False, option: str = "-o") -> Path:
    """Check, before any computation, that a single output file may be written.

    The file is replaced only with ``force`` and only when it is a regular
    file (never a directory, a FIFO, a device, a socket or a symbolic link).
    """
    given = "''" if str(path) == "" else path
    if str(path) == "" or "\0" in str(path) or str(path).endswith(os.sep) or Path(path).name in ("", ".", ".."):
        raise LiengInputError(f"{option} {given}: not a file name")
    p = Path(path)
    if os.path.islink(p):
        raise LiengInputError(f"{option} {given}: is a symbolic link: name the file itself (lieng does not write "
                              f"through links)")
    try:
        st = p.stat()
    except FileNotFoundError:
        if os.path.islink(p):
            raise LiengInputError(f"{option} {given}: a symbolic link to nothing ({os.readlink(p)})") from None
        parent = p.absolute().parent
        if not parent.is_dir():
            raise LiengInputError(f"{option} {given}: the directory {p.parent} does not exist")
        if not os.access(parent, os.W_OK | os.X_OK):
            raise LiengInputError(f"{option} {given}: the directory {p.parent} is not writable")
        return p
    except NotADirectoryError:
        _existing_ancestor(p.absolute(), option, given)
        return p                            # pragma: no cover
    except OSError as exc:
        raise LiengInputError(f"{option} {given}: cannot be used ({exc.strerror})") from None
    if stat.S_ISDIR(st.st_mode):
        raise LiengInputError(f"{option} {given}: is a directory, not a file")
    if not stat.S_ISREG(st.st_mode):
        raise LiengInputError(f"{option} {given}: is not a regular file (lieng writes only regular files)")
    if not force:
        raise LiengInputError(f"{option} {given}: the file exists: give --force to replace it")
    if not os.access(p.parent if str(p.parent) else Path("."), os.W_OK | os.X_OK):
        raise LiengInputError(f"{option} {given}: its directory is not writable")
    return p


def replace_file(path, write) -> None:
    """Write ``path`` through ``write(tmp_path)`` into a temporary file beside
    it, then move it into place (never a half-written file)."""
    p = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", dir=p.parent if str(p.parent) else ".")
    os.close(fd)
    try:
        write(Path(tmp))
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)       # as open() would have made it (mkstemp makes 0600)
        os.replace(tmp, p)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


@contextmanager
def staged_outdir(outdir, force: bool = False, keep: Sequence[str] = ()):
    """Yield a temporary directory; on success move its files into ``outdir``.

    ``outdir`` is checked again (:func:`check_outdir`); an entry of the
    target that has an output's name but is a directory or was not written
    by lieng stops the move before anything is moved.

    ``keep`` names subdirectories of ``outdir`` that the command writes
    itself, each through its own :func:`staged_outdir` (``diagnose --batch``:
    one per record).  Each must be new or a directory that holds only
    lieng's outputs (checked here, before any computation); those written
    are listed among the outputs, so that a later run may write them again.
    """
    target = check_outdir(outdir, force=force)
    for name in keep:
        sub = target / name
        if os.path.lexists(sub):
            if sub.is_symlink() or not sub.is_dir():
                raise LiengInputError(f"-o {outdir}: {sub} is in the way of an output directory and lieng does not "
                                      f"replace it: move it away or choose another directory")
            try:
                check_outdir(sub, force=False)
            except LiengInputError:
                raise LiengInputError(f"-o {outdir}: {sub} holds files lieng did not write, and lieng writes this "
                                      f"output directory only when it is new or its own: move it away or choose "
                                      f"another directory") from None
    base = target if target.is_dir() else _existing_ancestor(target.absolute(), "-o", outdir)
    try:
        tmp = Path(tempfile.mkdtemp(prefix=".lieng-staging.", dir=base))
    except OSError as e:
        raise LiengInputError(f"-o {outdir}: cannot write in {base} ({e.strerror or e})") from None
    try:
        yield tmp
        names = sorted(f.name for f in tmp.iterdir())
        owned = _owned(target) if target.is_dir() else set()
        for name in names:
            dest = target / name
            if dest.is_dir() and not dest.is_symlink():
                raise LiengInputError(f"-o {outdir}: {dest} is a directory: lieng does not replace it")
            if os.path.lexists(dest) and name not in owned:
                raise LiengInputError(f"-o {outdir}: {dest} was not written by lieng, and lieng replaces only its "
                                      f"own outputs: move it away or choose another directory")
        created = not target.exists()
        target.mkdir(parents=True, exist_ok=True)
        try:
            for name in names:
                os.replace(tmp / name, target / name)
            for name in sorted(owned - set(names) - set(keep)):
                old = target / name
                if old.is_symlink() or old.is_file():
                    old.unlink()
            kept = {n for n in keep if (target / n).is_dir() and not (target / n).is_symlink()}
            (target / MANIFEST).write_text("".join(f"{n}\n" for n in sorted(set(names) | kept)), encoding="utf-8")
        except BaseException:
            if created:
                shutil.rmtree(target, ignore_errors=True)
            raise
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def write_lines(path, lines: Iterable[str]) -> None:
    """Write text lines with a final newline."""
    Path(path).write_text("".join(f"{ln}\n" for ln in lines), encoding="utf-8")


def write_csv(path, header: Sequence[str], rows: Iterable[Sequence]) -> None:
    """Write a CSV with a header row; floats with 17 significant digits.

    ``None`` is written as an empty cell (a missing value); a NaN or an
    infinity is refused (``ValueError``): the caller decides what a value it
    cannot compute is, and says so.
    """
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(header)
        for k, row in enumerate(rows):
            cells = []
            for v in row:
                if v is None:
                    cells.append("")
                elif isinstance(v, float):
                    if not math.isfinite(v):
                        raise ValueError(f"{Path(path).name}: row {k + 1}: non-finite value {v}")
                    cells.append(f"{v:.17g}")
                else:
                    cells.append(v)
            w.writerow(cells)


def finite_json(obj):
    """``obj`` with every non-finite float replaced by ``None`` (JSON null)."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: finite_json(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [finite_json(v) for v in obj]
    try:
        import numpy as np
    except ImportError:  # pragma: no cover
        return obj
    if isinstance(obj, np.ndarray):
        return finite_json(obj.tolist())
    if isinstance(obj, np.floating):
        return finite_json(float(obj))
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    return obj


def all_finite(obj) -> bool:
    """No NaN or infinity anywhere in a nested result (dicts, lists, numbers)."""
    if isinstance(obj, dict):
        return all(all_finite(v) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return all(all_finite(v) for v in obj)
    if isinstance(obj, float):
        return math.isfinite(obj)
    return True


def dumps_json(obj, **kw) -> str:
    """Strict JSON (no NaN/Infinity): non-finite numbers become null."""
    return json.dumps(finite_json(obj), allow_nan=False, **kw)


# ------------------------------------------------------------------ plots' format

#: the file formats plots are written in
PLOT_FORMATS = ("png", "svg", "pdf")
#: the plots' format and resolution (dots per inch) when a command sets none
PLOT_DEFAULT = {"format": "png", "dpi": 110.0}
#: the format and resolution of the plots written next
_PLOT = dict(PLOT_DEFAULT)


def plot_output(fmt: str | None = None, dpi: float | None = None) -> None:
    """Set the format (png, svg or pdf; default png) and resolution (dpi,
    30-1200; default 110) of every plot written after (the commands'
    --format and --dpi)."""
    fmt = PLOT_DEFAULT["format"] if fmt is None else fmt
    if fmt not in PLOT_FORMATS:
        raise LiengInputError(f"--format {fmt}: choose from {', '.join(PLOT_FORMATS)}")
    if dpi is not None and not (math.isfinite(dpi) and 30 <= dpi <= 1200):
        raise LiengInputError(f"--dpi {dpi:g}: a resolution between 30 and 1200 dots per inch")
    _PLOT.update(format=fmt, dpi=PLOT_DEFAULT["dpi"] if dpi is None else float(dpi))


def plot_settings() -> tuple:
    """(format, dpi) of the plots written next."""
    return _PLOT["format"], _PLOT["dpi"]


def plot_name(name) -> str:
    """A plot's file name in the current format (``trace.png`` -> ``trace.svg``)."""
    return Path(name).with_suffix("." + _PLOT["format"]).name
