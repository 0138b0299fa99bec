"""Writes docs/api.md, the API page: every public name of lieng's modules (their ``__all__``), with its
signature and the first paragraph of its docstring.  ``tests/test_api_doc.py`` fails when the page is out
of date; regenerate it with

    .venv/bin/python docs/make_api.py
"""

from __future__ import annotations

import importlib
import inspect
import sys
from pathlib import Path

#: (module, what it is), in the order of the layers: the 1971 programs, then the modern analyses, diagnose,
#: and the I/O and support modules
MODULES = [
    ("lieng", "The 1971 programs and their decks (`import lieng`)"),
    ("lieng.programs", "The restored programs' layer: decks of any program"),
    ("lieng.analysis.cycles", "Limit cycles, return maps, sweeps of v0 and dmu0 (ch. 2.3.1.4-2.4.2)"),
    ("lieng.analysis.regime_map", "Table 2.IV over a grid (`lieng map`)"),
    ("lieng.analysis.twodof", "The 2-DoF dual-pin-on-disc rig (seed 001)"),
    ("lieng.diagnose", "What the 1-DoF model gets wrong on a measured record (`lieng diagnose`)"),
    ("lieng.analysis.synth", "Synthetic records with an effect hidden in them (`lieng synth`)"),
    ("lieng.analysis.figures", "The thesis's theoretical figures (`lieng figures`)"),
    ("lieng.io.table", "Tables as labs write them (CSV/TAB/whitespace, units in the header)"),
    ("lieng.analysis.executor", "Where independent tasks run: in process, a process pool, a Dask cluster"),
    ("lieng.errors", "Bad input: the one error type, its fields, and how a deck or a file names them (`located`)"),
    ("lieng.status", "The status codes of the compiled core (one table with fortran/status.f90)"),
]


def first_paragraph(doc: str | None) -> str:
    """The docstring's first paragraph, on one line."""
    if not doc:
        return "(no docstring)"
    para = inspect.cleandoc(doc).split("\n\n")[0]
    return " ".join(line.strip() for line in para.splitlines())


def signature(obj) -> str:
    """The public signature: private parameters (``_name``) left out, a function default shown by its name,
    annotations left out (the docstrings give the types)."""
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return ""
    params = []
    for p in sig.parameters.values():
        if p.name.startswith("_"):
            continue
        d = p.default
        if d is not inspect.Parameter.empty and callable(d) and hasattr(d, "__name__"):
            d = _Named(d.__name__)
        params.append(p.replace(annotation=inspect.Parameter.empty, default=d))
    return str(sig.replace(parameters=params, return_annotation=inspect.Signature.empty))


class _Named:
    def __init__(self, name):
        self.name = name

    def __repr__(self):
        return self.name


def entry(mod, name: str) -> str:
    obj = getattr(mod, name)
    if inspect.isclass(obj):
        return f"- **class `{name}{signature(obj)}`**: {first_paragraph(obj.__doc__)}"
    if callable(obj):
        return f"- **`{name}{signature(obj)}`**: {first_paragraph(obj.__doc__)}"
    if isinstance(obj, (int, float, str)):
        return f"- `{name} = {obj!r}`"
    return f"- `{name}`: {type(obj).__name__}"


def render() -> str:
    out = ["# API reference", "",
           "Generated from the docstrings by `docs/make_api.py` (do not edit by hand). Each entry is a public name",
           "(the module's `__all__`) with its signature and the first paragraph of its docstring; `help(name)` in",
           "Python gives the whole numpy-style docstring.", ""]
    for modname, what in MODULES:
        mod = importlib.import_module(modname)
        out += [f"## `{modname}`", "", what + ".", ""]
        names = list(getattr(mod, "__all__", []))
        out += [entry(mod, n) for n in names] + [""]
    return "\n".join(out)


def main() -> None:
    path = Path(__file__).with_name("api.md")
    path.write_text(render())
    print(f"wrote {path}")


if __name__ == "__main__":
    sys.exit(main())
