import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))

ROOT = Path(__file__).resolve().parents[1]
CARDS = ROOT / "cards"


def thesis_characteristic(v0=10.0, fs=10.0, fm=6.0, eps=0.5, um=20.0, c=0.1, vmax=40.0, nfine=11, step=2.0):
    """A characteristic of the shape of Fig. 2.21 (plain NumPy): x = g(v0 - v)."""

    def h(u):
        return np.where(u <= eps, fs * u / eps,
                        np.where(u <= um, fs - (fs - fm) * (u - eps) / (um - eps), fm + c * (u - um)))

    v = np.unique(np.concatenate([np.arange(-vmax, vmax + 1e-9, step), np.linspace(v0 - eps, v0 + eps, nfine),
                                  [v0 - um, v0 + um]]))[::-1]
    s = v0 - v
    x = np.sign(s) * h(np.abs(s))
    return x, v


@pytest.fixture
def thesis_char():
    return thesis_characteristic()


@pytest.fixture(scope="session")
def gfortran():
    exe = shutil.which("gfortran")
    if exe is None:
        pytest.skip("gfortran is not installed")
    return exe


def rng(seed):
    return np.random.default_rng(seed)
