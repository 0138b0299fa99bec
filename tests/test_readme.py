"""The numbers the README states about faithful vs exact cycles are the ones
the commands it shows print (README, "Faithful vs exact")."""

import re

import pytest

from lieng.cli import main

from conftest import CARDS, ROOT

README = (ROOT / "README.md").read_text()


def last_line(args, capsys):
    assert main([str(a) for a in args]) == 0
    return capsys.readouterr().out.strip().splitlines()


def value(line):
    return float(re.findall(r"[-+]?\d+\.\d+(?:e[-+]?\d+)?", line)[-1])


@pytest.mark.parametrize("what,args,pattern", [
    ("v_oc", ["sweep", CARDS / "figures" / "fig2_27.dat", "--v0", "1:30:30"],
     r"v_oc (?P<faithful>[\d.]+) instead of (?P<exact>[\d.]+) mm/s"),
    ("dmu_oc", ["sweep", CARDS / "figures" / "fig2_28.dat", "--dmu", "0.05:1.5:30"],
     r"dmu_oc (?P<faithful>[\d.]+) instead of (?P<exact>[\d.]+)"),
])
def test_faithful_vs_exact_critical_values(what, args, pattern, capsys):
    m = re.search(pattern, " ".join(README.split()))
    assert m, f"README no longer states {what}"
    for mode in ("exact", "faithful"):
        got = value(last_line(args + ["--mode", mode], capsys)[-1])
        stated = float(m.group(mode))
        digits = len(m.group(mode).split(".")[1])
        assert round(got, digits) == stated, (what, mode, got, stated)


def test_faithful_vs_exact_slc_amplitude(capsys):
    m = re.search(r"S\.L\.C\. amplitude (?P<faithful>[\d.]+) instead of (?P<exact>[\d.]+) mm", " ".join(README.split()))
    assert m
    for mode in ("exact", "faithful"):
        out = last_line(["cycles", CARDS / "figures" / "fig2_27.dat", "--mode", mode], capsys)
        amp = float(re.search(r"stable cycle: amplitude ([\d.]+)", "\n".join(out)).group(1))
        assert round(amp, 2) == float(m.group(mode)), (mode, amp)
