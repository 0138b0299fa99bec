"""The ``lieng`` command line.

``lieng run lieng1 DECK -o OUTDIR`` runs a card deck as the 1971 program did
and writes the line-printer listing, the trajectories as CSV and the plots.
Bad input prints one line, ``lieng: error: ...``, and exits with status 2,
leaving OUTDIR untouched.
"""

from lieng.cli.common import UNEXPECTED
from lieng.cli.parser import build_parser, main

__all__ = ["main", "build_parser", "UNEXPECTED"]
