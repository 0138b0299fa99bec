"""Property-based fuzzing of the ``lieng`` command line (see tests/fuzz/).

Each test draws cases of one input kind (mutated card decks, tables,
argument values, output paths), runs ``lieng.cli.main`` in-process on each
and checks the contract of :mod:`fuzz.harness`: no traceback, exit 0 or 2,
one ``lieng: error:`` line on exit 2, no NaN/inf in the outputs, nothing
changed on failure, the user's files kept on success, no hang.

The default run is short (about 2 minutes in all, derandomized: the same
cases every time).  ``LIENG_FUZZ=long`` draws 20 times as many and shrinks a
failure to a minimal case; ``LIENG_FUZZ_TIMEOUT`` sets the per-case timeout
(s, default 30).  For a larger campaign outside pytest, with the failures
grouped: ``python tests/fuzz/campaign.py --help``.
"""

import os

import pytest

pytestmark = pytest.mark.slow

hypothesis = pytest.importorskip("hypothesis")

from hypothesis import HealthCheck, Phase, given, settings  # noqa: E402

from fuzz.cases import cases  # noqa: E402
from fuzz.harness import assert_contract, run_and_check  # noqa: E402

os.environ.setdefault("MPLBACKEND", "Agg")

LONG = os.environ.get("LIENG_FUZZ", "").lower() == "long"
SCALE = 20 if LONG else 1
TIMEOUT = float(os.environ.get("LIENG_FUZZ_TIMEOUT", "30"))


def fuzz_settings(n):
    """max_examples n (x20 with LIENG_FUZZ=long); the short run does not
    shrink, so that a failing run stays quick (the failure is reported as
    drawn; tests/fuzz/campaign.py shrinks outside pytest)."""
    phases = [Phase.explicit, Phase.reuse, Phase.generate] + ([Phase.shrink] if LONG else [])
    return settings(max_examples=n * SCALE, deadline=None, derandomize=True, database=None, phases=phases,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                           HealthCheck.filter_too_much, HealthCheck.large_base_example],
                    print_blob=False)


def check_case(case):
    res, violations = run_and_check(case, timeout=TIMEOUT)
    assert_contract(res, case.describe() + f"\n(files kept in {res.root})", violations)


@fuzz_settings(40)
@given(case=cases("lieng1_deck"))
def test_fuzz_lieng1_decks(case):
    check_case(case)


@fuzz_settings(40)
@given(case=cases("mlien_deck"))
def test_fuzz_mlien_decks(case):
    check_case(case)


@fuzz_settings(40)
@given(case=cases("trc_deck"))
def test_fuzz_trc_decks(case):
    check_case(case)


@fuzz_settings(40)
@given(case=cases("trc_csv"))
def test_fuzz_trc_csv(case):
    check_case(case)


@fuzz_settings(25)
@given(case=cases("diagnose"))
def test_fuzz_diagnose_tables(case):
    check_case(case)


@fuzz_settings(30)
@given(case=cases("synth"))
def test_fuzz_synth_args(case):
    check_case(case)


@fuzz_settings(40)
@given(case=cases("sweep"))
def test_fuzz_sweep_cycles_args(case):
    check_case(case)


@fuzz_settings(30)
@given(case=cases("twodof"))
def test_fuzz_twodof_args(case):
    check_case(case)


@fuzz_settings(40)
@given(case=cases("outpaths"))
def test_fuzz_output_paths(case):
    check_case(case)


@fuzz_settings(30)
@given(case=cases("map"))
def test_fuzz_map_args(case):
    check_case(case)
