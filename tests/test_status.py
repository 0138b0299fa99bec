"""One table of status codes: fortran/status.f90 and python/lieng/status.py agree, every code is unique, and
no Fortran module declares a status code of its own (issue #16)."""

import re

from conftest import ROOT

from lieng import status


def test_the_python_table_is_the_fortran_table():
    text = (ROOT / "fortran" / "status.f90").read_text()
    fortran = {int(v): k for k, v in re.findall(r"integer, parameter, public :: st_(\w+) = (\d+)", text)}
    assert fortran == status.CODES
    assert len(set(fortran)) == len(fortran) and fortran[0] == "ok"
    for code, nm in fortran.items():
        assert getattr(status, nm.upper()) == code and status.name(code) == nm
    assert status.name(99) == "unknown status 99"


def test_no_other_module_declares_status_codes():
    for f in (ROOT / "fortran").rglob("*.f90"):
        if f.name == "status.f90":
            continue
        text = f.read_text()
        assert not re.search(r"integer, parameter[^:]*:: *(st|trc)_\w+ *= *\d", text), f.name
        for m in re.finditer(r"status(?:\(\w+\))? = (\d+)", text):
            raise AssertionError(f"{f.name}: a bare status {m.group(1)} (use status_codes)")
