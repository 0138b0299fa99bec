"""Regenerate the golden outputs of tests/test_golden.py.

Run only when a change to a listing or a CSV is intended, and say why in the
commit::

    .venv/bin/python tests/golden/regenerate.py        # all decks
    .venv/bin/python tests/golden/regenerate.py trc_demo

For each deck of :data:`DECKS` the command ``lieng run PROGRAM DECK`` is run
and ``<name>.listing.txt.gz`` (the whole line-printer listing) and
``<name>.csv.gz`` (the header and every :data:`STRIDE`-th row of the
trajectory CSV, every row of a CSV of at most 1000) are written beside this
file.  They guard against regressions; they are not evidence of correctness
(that is tests/reference.py, the gfortran listing test and the thesis's
claims), which is why regenerating them needs a reason.
"""

from __future__ import annotations

import gzip
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
CARDS = HERE.parents[1] / "cards"

#: name -> (program, deck relative to cards/, the CSV compared)
DECKS = {
    "lieng1_demo": ("lieng1", "lieng1_demo.dat", "trajectories.csv"),
    "mlien_a9_7": ("mlien", "mlien_a9_7.dat", "trajectories.csv"),
    "mlien_a9_7_decay": ("mlien", "mlien_a9_7_decay.dat", "trajectories.csv"),
    "trc_demo": ("trc", "trc_demo.dat", "trc.csv"),
    **{p.stem: ("lieng1", f"figures/{p.name}", "trajectories.csv")
       for p in sorted((CARDS / "figures").glob("*.dat"))},
}
#: every STRIDE-th CSV row is kept (the listing keeps every tenth point itself)
STRIDE = 25


def run(name: str, outdir: Path) -> tuple[list[str], list[str]]:
    """The listing lines and the kept CSV lines of deck ``name``."""
    from lieng.cli import main

    prog, deck, csv = DECKS[name]
    code = main(["run", prog, str(CARDS / deck), "-o", str(outdir), "--no-plots", "-q"])
    if code != 0:
        raise RuntimeError(f"lieng run {prog} {deck} exited {code}")
    listing = (outdir / "listing.txt").read_text().splitlines()
    rows = (outdir / csv).read_text().splitlines()
    return listing, [rows[0]] + rows[1::STRIDE if len(rows) > 1000 else 1]


def main(names) -> None:
    for name in names or DECKS:
        with tempfile.TemporaryDirectory() as tmp:
            listing, rows = run(name, Path(tmp) / "o")
        for suffix, lines in ((".listing.txt.gz", listing), (".csv.gz", rows)):
            with gzip.open(HERE / f"{name}{suffix}", "wt", encoding="utf-8", compresslevel=9) as fh:
                fh.write("\n".join(lines) + "\n")
        print(f"{name}: {len(listing)} listing lines, {len(rows) - 1} CSV rows")


if __name__ == "__main__":
    main(sys.argv[1:])
