"""lieng: S. S. Antoniou's 1971 Lienard-plane programs, restored and continued.

The 1971 programs (thesis, Imperial College London):

* :func:`lieng1` -- LIENG-1 (App. 4), phase portraits by Lienard's construction.
* :func:`mlien` -- MLIEN / LIENG-2 (App. 6), driving velocity v0(t) and triggering.
* :func:`trc` -- TRC (App. 7), recorder readings to trajectories and the characteristic.

Card decks: :func:`read_deck`, :func:`write_deck`.  Bad input raises
:class:`LiengInputError` with a one-line message naming the card and columns.
"""

import os as _os

# One BLAS thread: the analyses are many small solves, and a machine's other
# cores belong to the process pool or to other jobs (set the variables before
# importing lieng to choose otherwise).
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    _os.environ.setdefault(_var, "1")

from lieng.programs import read_deck, write_deck  # noqa: E402
from lieng.programs.characteristic import centre_of_symmetry
from lieng.errors import LiengInputError
from lieng.programs.lieng1 import Lieng1Result, lieng1
from lieng.programs import mlien as mlien_module
from lieng.programs.mlien import MlienResult, mlien
from lieng.programs.trc import TrcResult, trc

__version__ = "0.1.0"

#: the analyses and support modules, imported on first use: ``lieng.cycles.find_cycles(...)``
_SUBMODULES = {"cycles": "lieng.analysis.cycles", "regime_map": "lieng.analysis.regime_map",
               "twodof": "lieng.analysis.twodof", "figures": "lieng.analysis.figures", "synth": "lieng.analysis.synth",
               "executor": "lieng.analysis.executor", "diagnose": "lieng.diagnose", "outputs": "lieng.io.outputs",
               "inputs": "lieng.io.inputs", "table": "lieng.io.table", "cards": "lieng.io.cards", "status": "lieng.status"}


def __getattr__(name):
    if name in _SUBMODULES:
        import importlib

        return importlib.import_module(_SUBMODULES[name])
    raise AttributeError(f"module 'lieng' has no attribute {name!r}")

__all__ = [
    "LiengInputError",
    "Lieng1Result",
    "MlienResult",
    "TrcResult",
    "centre_of_symmetry",
    "lieng1",
    "mlien",
    "read_deck",
    "trc",
    "write_deck",
]
