"""Writing an output directory all at once.

Every file of a run is written into a fresh temporary directory beside the
target; only when all are written are they moved into place.  A failure
leaves the target as it was: no half-written output directory.
"""

from __future__ import annotations

import csv
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Iterable, Sequence

__all__ = ["staged_outdir", "write_csv", "write_lines"]


@contextmanager
def staged_outdir(outdir):
    """Yield a temporary directory; on success move its files into ``outdir``."""
    target = Path(outdir)
    parent = target.resolve().parent
    parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.", dir=parent))
    try:
        yield tmp
        created = not target.exists()
        target.mkdir(parents=True, exist_ok=True)
        try:
            for f in sorted(tmp.iterdir()):
                dest = target / f.name
                if dest.is_dir() and not dest.is_symlink():
                    shutil.rmtree(dest)
                f.replace(dest)
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
    """Write a CSV with a header row; floats with 17 significant digits."""
    with open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(header)
        for row in rows:
            w.writerow([f"{v:.17g}" if isinstance(v, float) else v for v in row])
