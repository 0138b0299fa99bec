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


def _sessions():
    """Every `$ lieng ...` command of the README's console blocks with the
    lines the README shows after it."""
    out, cmd, lines, inblock = [], None, [], False
    for ln in README.splitlines():
        if ln.startswith("```console"):
            inblock = True
            continue
        if inblock and ln.startswith("```"):
            inblock = False
        if not inblock or ln.startswith("$ "):
            if cmd is not None:
                out.append((cmd, lines))
            cmd, lines = (ln[2:].split(), []) if inblock and ln.startswith("$ lieng ") else (None, [])
            continue
        if cmd is not None:
            lines.append(ln)
    return out


@pytest.mark.slow
@pytest.mark.parametrize("cmd,shown", _sessions(), ids=lambda v: " ".join(v[:3]) if isinstance(v, list) and v
                         and v[0] == "lieng" else None)
def test_every_readme_session_prints_what_the_readme_shows(cmd, shown, tmp_path, monkeypatch, capsys):
    """The README's sessions (real records, the regime map) run as shown, from
    the repository's root, and print every line the README shows (the output
    directory moved to a temporary one; "wrote ..." names it)."""
    monkeypatch.chdir(ROOT)
    args = cmd[1:]
    if "-o" in args:
        args[args.index("-o") + 1] = str(tmp_path / "out")
    assert main(args) == 0
    printed = capsys.readouterr()
    text = printed.out + printed.err
    for ln in shown:
        if ln.startswith("wrote ") or not ln.strip():
            continue
        assert ln.rstrip() in text, f"{' '.join(cmd)}: the README shows {ln!r}, the command printed:\n{text}"
