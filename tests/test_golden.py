"""Golden outputs: the listings and CSVs of the demo and figure decks, stored
under tests/golden/ and compared, so that a change of the code and of
tests/reference.py together cannot pass unnoticed.  An intended change is
recorded with ``python tests/golden/regenerate.py`` (see its docstring)."""

import gzip
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent / "golden"))

from regenerate import DECKS, HERE, run  # noqa: E402


def stored(name, suffix):
    with gzip.open(HERE / f"{name}{suffix}", "rt", encoding="utf-8") as fh:
        return fh.read().splitlines()


@pytest.mark.parametrize("name", list(DECKS))
def test_listing_and_csv_match_the_golden_files(name, tmp_path):
    listing, rows = run(name, tmp_path / "o")
    want = stored(name, ".listing.txt.gz")
    diff = next((k for k, (a, b) in enumerate(zip(listing, want)) if a != b), None)
    assert diff is None and len(listing) == len(want), (
        f"{name}: listing differs from tests/golden at line {diff if diff is not None else min(len(listing), len(want))}"
        f" (regenerate only for an intended change: tests/golden/regenerate.py)\n"
        f"  now:    {listing[diff] if diff is not None else len(listing)}\n"
        f"  golden: {want[diff] if diff is not None else len(want)}")
    want_rows = stored(name, ".csv.gz")
    assert rows[0] == want_rows[0] and len(rows) == len(want_rows)

    def num(lines):
        return np.array([[float(c) if c else np.nan for c in r.split(",")] for r in lines[1:]])

    np.testing.assert_allclose(num(rows), num(want_rows), rtol=1e-12, atol=1e-300, equal_nan=True,
                               err_msg=f"{name}: CSV differs from tests/golden")
