"""docs/api.md is the API as it is: regenerated from the docstrings, it is unchanged (issue #16).  After a change
of the public API: .venv/bin/python docs/make_api.py."""

import importlib.util

from conftest import ROOT


def test_the_api_page_is_up_to_date():
    spec = importlib.util.spec_from_file_location("make_api", ROOT / "docs" / "make_api.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert (ROOT / "docs" / "api.md").read_text() == mod.render(), \
        "docs/api.md is out of date: run .venv/bin/python docs/make_api.py"
