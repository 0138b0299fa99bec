"""The independent record generators (``tests/generators/``, each written
without reading the diagnosis code) run through ``diagnose`` as a user
would: every case of every generator is read and diagnosed without an error
or a crash, and its ``diagnosis.json`` is strict JSON (no NaN or Infinity).
How often the right effect is named is measured, not asserted, by
``tests/benchmarks/bench_diagnose.py`` (confusion matrices per generator:
README)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent / "benchmarks"))
import bench_diagnose as B  # noqa: E402

GENS = B.generators()
KNOWN = set(B.CASES) | {"unexplained", "no_stick_slip", "friction_drift", "direction_asymmetry",
                        "position_dependence"}


@pytest.mark.slow
@pytest.mark.parametrize("gen", sorted(k for k in GENS if k != "synth"))
@pytest.mark.parametrize("case", B.CASES)
def test_every_case_of_every_generator_is_diagnosed(tmp_path, gen, case):
    from lieng.diagnose import diagnose, read_record

    truth = GENS[gen].write_record(case, 1, str(tmp_path), B.NUISANCES[1])
    a = B.parse_args(truth["args"])
    rec = read_record(truth["file"], v0=a.v0, stiffness=a.stiffness)
    d = diagnose(rec, a.fn, replicates=19, budget=10.0)
    assert d.effect in KNOWN
    json.dumps(d.to_json(), allow_nan=False)
