"""Fuzzed inputs for the ``lieng`` command line.

Every case is made in two steps:

1. a *generator* ``gen_<kind>(d)`` draws a **spec**: plain data (dicts,
   lists, strings, numbers; JSON-serialisable) that says which base input
   to start from and which mutations to apply.  ``d`` is a :class:`Drawer`,
   backed either by hypothesis (``HypDrawer``, for pytest: shrinking works
   on the draws) or by ``random.Random`` (``RandomDrawer``, for the
   stand-alone campaign: case ``i`` of seed ``S`` is reproducible);
2. :func:`build` turns a spec into a :class:`Case`: the files to create
   (relative to the working directory ``WORK`` under a fresh root), the
   argv of ``lieng`` and a human description of how the inputs were made.

Specs have the lists ``mut`` (input mutations) and ``setup`` (user files
made before the run) and the dict ``opts`` (options of the command), so a
failing case can be shrunk by dropping items (see ``campaign.py``).

Kinds (``KINDS``): lieng1_deck, mlien_deck, trc_deck, trc_csv, diagnose,
synth, sweep, twodof, outpaths, map.
"""

from __future__ import annotations

import copy
import json
import math
import random
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CARDS = ROOT / "cards"
#: the working directory (cwd of the run) under the case's root
WORK = "work"

# ---------------------------------------------------------------------------
# Drawers
# ---------------------------------------------------------------------------


class Drawer:
    """What generators draw with.  The first element of a choice and the
    ``False`` of a boolean are the simple values hypothesis shrinks to."""

    def integer(self, lo: int, hi: int) -> int:  # pragma: no cover - interface
        raise NotImplementedError

    def choice(self, seq):
        seq = list(seq)
        return seq[self.integer(0, len(seq) - 1)]

    def boolean(self, p: float = 0.5) -> bool:
        return self.integer(0, 999) >= round(1000 * (1 - p))

    def uniform(self, lo: float, hi: float) -> float:
        return lo + (hi - lo) * self.integer(0, 10**6) / 10**6

    def log_uniform(self, lo: float, hi: float) -> float:
        return math.exp(self.uniform(math.log(lo), math.log(hi)))


class RandomDrawer(Drawer):
    def __init__(self, rnd: random.Random):
        self.rnd = rnd

    def integer(self, lo, hi):
        return self.rnd.randint(lo, hi)


class HypDrawer(Drawer):
    def __init__(self, draw):
        self.draw = draw

    def integer(self, lo, hi):
        from hypothesis import strategies as st

        return self.draw(st.integers(lo, hi))


# ---------------------------------------------------------------------------
# A case
# ---------------------------------------------------------------------------


@dataclass
class Entry:
    """A path to create under the working directory before the run."""

    path: str
    type: str = "file"          # file | dir | fifo | symlink
    data: bytes = b""
    target: str = ""            # symlink target

    def describe(self) -> str:
        if self.type == "file":
            return f"file {self.path!r} ({len(self.data)} bytes)"
        if self.type == "symlink":
            return f"symlink {self.path!r} -> {self.target!r}"
        return f"{self.type} {self.path!r}"


@dataclass
class Case:
    kind: str
    argv: list
    entries: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    spec: dict = field(default_factory=dict)

    def materialize(self, root) -> Path:
        """Create the entries under ``root/WORK``; returns the working directory."""
        import os

        work = Path(root) / WORK
        work.mkdir(parents=True, exist_ok=True)
        for e in self.entries:
            p = work / e.path
            if e.type != "symlink":
                p.parent.mkdir(parents=True, exist_ok=True)
            if e.type == "file":
                p.write_bytes(e.data)
            elif e.type == "dir":
                p.mkdir(parents=True, exist_ok=True)
            elif e.type == "fifo":
                os.mkfifo(p)
            elif e.type == "symlink":
                p.parent.mkdir(parents=True, exist_ok=True)
                os.symlink(e.target, p)
        return work

    def describe(self) -> str:
        import shlex

        lines = [f"kind {self.kind}", "cd to an empty directory and create:"]
        lines += [f"  {e.describe()}" for e in self.entries]
        lines += [f"  - {n}" for n in self.notes]
        lines.append("run: lieng " + " ".join(shlex.quote(a) for a in self.argv))
        return "\n".join(lines)

    def size(self) -> float:
        """A measure of how complicated the case is (for picking a minimal one)."""
        s = self.spec
        return (10 * len(s.get("mut", [])) + 5 * len(s.get("setup", [])) + len(s.get("opts", {}))
                + sum(len(e.data) for e in self.entries) / 1e5)


# ---------------------------------------------------------------------------
# Extreme values
# ---------------------------------------------------------------------------

REAL_FIELD = ["0", "-0", "1E30", "-1E30", "1.7E308", "-1.7E308", "5E-324", "1E-300", "-1E-300", "1E300",
              "1.8E308", "", "1", "-1", "9999999999", ".", "-", "+", "E5", "1E", "1+", "1.5D2", "1.5+2",
              "1.5-2", "NaN", "Inf", "-Inf", "0x1", "1,5", "abc", "\f", "\t", "\r", "\x00", "\u00e9", "1 2",
              "--1", "1.0.0", "-.5", "1E999", "1E-999", "1E+308", "0.0001", "-0.0001", "1e5", "2.2250738585072014E-308",
              "4.9E-324", "1Q5", "12345678901234567890", "   -   1"]
INT_FIELD = ["0", "-0", "-1", "1", "2", "3", "4", "5", "9", "10", "99999", "-9999", "", "1.5", "1E3", "abc", "\t",
             "+1", " 1 ", "200", "201", "199", "9999999", "-999999", "\f", "12345678"]
#: field values that read as numbers (they reach the computation)
REAL_NUMERIC = ["0", "-0", "1E30", "-1E30", "1.7E308", "5E-324", "1E-300", "-1E-300", "1E300", "1", "-1",
                "9999999999", "1.5D2", "-.5", "0.0001", "1e5", "2.2250738585072014E-308", "1E-20", "1E20", "-1E20",
                "0.01", "100", "-100", "1E10"]
INT_NUMERIC = ["0", "-1", "1", "2", "3", "4", "5", "9", "10", "99999", "-9999", "200", "201", "199", "9999999"]
FLOAT_ARG = ["0", "-0", "-1", "1e308", "1.7976931348623157e308", "-1e308", "5e-324", "1e-300", "-1e-300", "nan",
             "-nan", "inf", "-inf", "Infinity", "abc", "", " ", "1e", "0x10", "1_0", "1e-9", "1e9", "1e30", "1e-30",
             "3", "10", "0.5", "100", "1e6", "1e12"]
INT_ARG = ["0", "-1", "1", "2", "3", "16", "-2147483648", "2147483647", "4294967296", "18446744073709551616",
           "-9223372036854775809", "1000000", "1000000000", "1e3", "abc", "", "nan", " 5", "0x10", "1_000", "+7"]

# ---------------------------------------------------------------------------
# Decks
# ---------------------------------------------------------------------------

LIENG1_BASES = ["lieng1_demo.dat"] + [f"figures/{p.name}" for p in sorted((CARDS / "figures").glob("*.dat"))]
MLIEN_BASES = ["mlien_a9_7.dat", "mlien_a9_7_decay.dat"]
TRC_BASES = ["trc_demo.dat"]


def _fields(fmt: str) -> list:
    """(first column 0-based, width, kind) of the data fields of a simple FORMAT."""
    import re

    out, col = [], 0
    for rep, kind, w in re.findall(r"(\d*)([IFEDX])(\d+)(?:\.\d+)?", fmt):
        for _ in range(int(rep or 1)):
            if kind != "X":
                out.append((col, int(w), kind))
            col += int(w)
    return out


def deck_layout(program: str, ncards: int) -> list:
    """[(format, names)] of each card of a deck of ``ncards`` lines."""
    char = ([("(5F10.2)", [f"XCHL({5 * k + j + 1})" for j in range(5)]) for k in range(40)]
            + [("(5F10.2)", [f"YCHL({5 * k + j + 1})" for j in range(5)]) for k in range(40)])
    if program == "lieng1":
        return [("(I1)", ["KEY"]), ("(2F10.4)", ["XINCR", "YINCR"]),
                ("(I5,5F10.2)", ["N", "OMEGA", "AMPV0", "XINP", "YINP", "DTHETA"])] + char
    if program == "mlien":
        return ([("(I1)", ["KEY"]), ("(I5,5F10.2,I7)", ["N", "OMEGA", "AMPV0", "XINP", "YINP", "DTHETA", "M"])]
                + char + [("(4F10.2)", ["OMINTR", "OMETRI", "ATRI", "BTRI"])])
    head = [("(3F20.5)", ["HO", "HON", "VEL"]), ("(2F20.5)", ["OMNH", "OMNV"]),
            ("(4F10.3)", ["SENSF", "SENSN", "AN1", "AN2"]), ("(I5)", ["NN"])]
    return head + [("(18I4)", [f"{n}({6 * k + j // 3 + 1})" for j, n in
                                enumerate(["NT", "NH", "NHN"] * 6)]) for k in range(max(ncards - 4, 0))]


def _char_start(program):
    return {"lieng1": 3, "mlien": 2}[program]


def _fmt10(v: float) -> str:
    for s in (f"{v:.4f}", f"{v:.2f}", f"{v:.4G}", f"{v:.3E}", f"{v:.2E}", f"{v:.1E}", f"{v:.0E}"):
        if len(s) <= 10:
            return s.rjust(10)
    return f"{v:.0E}"


def _char_values(lines, program):
    s = _char_start(program)
    vals = []
    for ln in lines[s:s + 80]:
        ln = ln.ljust(50)
        vals += [_safe_float(ln[10 * j:10 * j + 10]) for j in range(5)]
    return vals[:200], vals[200:400]


def _safe_float(text: str) -> float:
    try:
        v = float(text.strip() or 0)
    except ValueError:
        return 0.0
    return v if math.isfinite(v) else 0.0


def _set_char(lines, program, xs, ys):
    s = _char_start(program)
    allv = list(xs) + list(ys)
    for k in range(80):
        lines[s + k] = "".join(_fmt10(v) for v in allv[5 * k:5 * k + 5])


def _deck_n(lines, program) -> int:
    try:
        card = lines[2] if program == "lieng1" else lines[1]
        return max(3, min(200, int(card[:5].strip() or 0)))
    except (IndexError, ValueError):
        return 50


def gen_deck_mutation(d: Drawer, program: str, nlines: int) -> dict:
    """One mutation of a card deck (plain data)."""
    kinds = ["field", "field", "field", "field", "truncate", "delete", "dup", "insert", "append", "ctrl", "long",
             "eol", "bom", "byte", "empty", "shift"]
    if program in ("lieng1", "mlien"):
        kinds += ["char", "char", "char"]
    else:
        kinds += ["readings", "readings", "readings"]
    op = d.choice(kinds)
    card = lambda: d.integer(0, max(nlines - 1, 0))  # noqa: E731
    if op == "field":
        head = {"lieng1": 3, "mlien": 2, "trc": 4}[program]
        ci = d.integer(0, head - 1) if d.boolean(0.65) or nlines <= head else d.integer(head, min(nlines - 1, head + 14))
        if program == "mlien" and d.boolean(0.1):
            ci = nlines - 1                 # the trigger card
        return {"op": "field", "card": ci, "field": d.integer(0, 17), "value": None, "pick": d.integer(0, 10**6),
                "numeric": d.boolean(0.5)}
    if op == "truncate":
        return {"op": op, "keep": d.choice([0, 1, 2, 3, 4, 5, 10, 43, nlines - 1, nlines - 2])}
    if op in ("delete", "dup"):
        return {"op": op, "card": card()}
    if op == "insert":
        return {"op": op, "at": card(), "text": d.choice(["", " ", "\f", "\t", "garbage", "1" * 80, "-" * 200,
                                                         "\f1", "0", "    1", "\x1a", "\r"])}
    if op == "append":
        return {"op": op, "count": d.choice([1, 2, 10, 1000]),
                "text": d.choice(["", "1", " " * 80, "    0.0000    0.0000", "extra card", "\f", "9" * 80])}
    if op == "ctrl":
        return {"op": op, "card": card(), "col": d.integer(0, 60),
                "char": d.choice(["\t", "\f", "\r", "\x00", "\x1a", "\x0b", "\u00e9", "\x85", "\u2028", "\x7f"])}
    if op == "long":
        return {"op": op, "card": card(), "len": d.choice([81, 200, 10000, 1000000])}
    if op == "eol":
        return {"op": op, "style": d.choice(["crlf", "cr", "nofinal", "lfcr", "ff"])}
    if op == "bom":
        return {"op": op}
    if op == "byte":
        return {"op": op, "card": card(), "col": d.integer(0, 40), "byte": d.choice([0xFF, 0x80, 0xC3, 0x00, 0xFE])}
    if op == "empty":
        return {"op": op, "what": d.choice(["empty", "blank", "newlines", "one"])}
    if op == "shift":                      # a card's fields one column to the left/right
        return {"op": op, "card": card(), "by": d.choice([-1, 1, 2, -3])}
    if op == "char":
        return {"op": op, "what": d.choice(["scale_x", "scale_y", "scale_xy", "shift_x", "dup_point", "reverse",
                                            "zero", "const_y", "n_small", "flip_y", "spike"]),
                "factor": d.choice([1e30, 1e-30, 1e300, 1e-300, 0.0, -1.0, 1e6, 1e-6, 2.0, 1e15]),
                "j": d.integer(0, 60)}
    return {"op": "readings", "what": d.choice(["zero", "const_nh", "dup_nt", "rev_nt", "neg", "max", "const_nt",
                                                "one_jump", "nn_more", "nn_less"]),
            "k": d.integer(0, 170)}


def _field_value(m, kind, name):
    vals = INT_FIELD if kind == "I" else REAL_FIELD
    if m.get("numeric"):
        vals = INT_NUMERIC if kind == "I" else REAL_NUMERIC
    special = {"N": ["0", "1", "2", "3", "4", "200", "201", "-1", "99999"],
               "NN": ["0", "1", "9", "10", "11", "180", "181", "200", "201", "-1", "99999"],
               "M": ["0", "-1", "1", "2", "9999999", "1000000"],
               "KEY": ["0", "9", "-", "a", " ", "\t"],
               "DTHETA": ["0", "-0.01", "1E-300", "5E-324", "1E30", "3.15", "6.3", "1E-9"],
               "OMEGA": ["0", "-0", "1E-300", "1E300"],
               "OMNH": ["0", "-1", "1E-300", "1E300", "NaN"], "OMNV": ["0", "-1", "1E-300", "1E300"]}
    pick = m["pick"]
    if name in special and pick % 3 == 0:
        vals = special[name]
    return m["value"] if m.get("value") is not None else vals[(pick // 3) % len(vals)]


def apply_deck_mutations(lines: list, program: str, muts: list, notes: list) -> bytes:
    """Apply the mutations to a deck's lines; returns the file's bytes."""
    lines = list(lines)
    eol, prefix, byte_muts, empty = "\n", b"", [], None
    for m in muts:
        op = m["op"]
        n = len(lines)
        idx = lambda k: min(max(k, 0), n - 1) if n else 0  # noqa: E731
        if op == "field":
            if not n:
                continue
            ci = idx(m["card"])
            lay = deck_layout(program, n)
            fmt, names = lay[ci] if ci < len(lay) else ("(5F10.2)", [f"field{j + 1}" for j in range(5)])
            flds = _fields(fmt)
            fi = m["field"] % len(flds)
            c0, w, kind = flds[fi]
            name = names[fi] if fi < len(names) else f"field {fi + 1}"
            val = _field_value(m, kind, name)
            ln = lines[ci].ljust(c0 + w)
            txt = val.rjust(w) if len(val) <= w else val
            lines[ci] = ln[:c0] + txt + ln[c0 + len(txt):]
            notes.append(f"card {ci + 1}, columns {c0 + 1}-{c0 + w} ({name}, {kind}{w}) := {val!r}")
        elif op == "truncate":
            lines = lines[:max(m["keep"], 0)]
            notes.append(f"deck truncated to its first {max(m['keep'], 0)} card(s)")
        elif op == "delete" and n:
            ci = idx(m["card"])
            del lines[ci]
            notes.append(f"card {ci + 1} deleted")
        elif op == "dup" and n:
            ci = idx(m["card"])
            lines.insert(ci, lines[ci])
            notes.append(f"card {ci + 1} duplicated")
        elif op == "insert":
            ci = idx(m["at"])
            lines.insert(ci, m["text"])
            notes.append(f"line {m['text']!r} inserted before card {ci + 1}")
        elif op == "append":
            lines += [m["text"]] * m["count"]
            notes.append(f"{m['count']} extra card(s) {m['text'][:20]!r} appended")
        elif op == "ctrl" and n:
            ci = idx(m["card"])
            ln = lines[ci].ljust(m["col"])
            lines[ci] = ln[:m["col"]] + m["char"] + ln[m["col"] + 1:]
            notes.append(f"card {ci + 1}, column {m['col'] + 1} := {m['char']!r}")
        elif op == "long" and n:
            ci = idx(m["card"])
            lines[ci] = lines[ci].ljust(80) + "7" * (m["len"] - 80)
            notes.append(f"card {ci + 1} padded with '7's to {m['len']} columns")
        elif op == "shift" and n:
            ci = idx(m["card"])
            lines[ci] = lines[ci][-m["by"]:] if m["by"] < 0 else " " * m["by"] + lines[ci]
            notes.append(f"card {ci + 1} shifted by {m['by']} column(s)")
        elif op == "eol":
            eol = {"crlf": "\r\n", "cr": "\r", "lfcr": "\n\r", "ff": "\n\f", "nofinal": "\n"}[m["style"]]
            if m["style"] == "nofinal":
                empty = empty or "nofinal"
            notes.append(f"line ends {m['style']}")
        elif op == "bom":
            prefix = b"\xef\xbb\xbf"
            notes.append("UTF-8 BOM prepended")
        elif op == "byte":
            byte_muts.append(m)
        elif op == "empty":
            empty = m["what"]
        elif op == "char" and program in ("lieng1", "mlien") and len(lines) >= _char_start(program) + 80:
            _char_mutation(lines, program, m, notes)
        elif op == "readings" and program == "trc" and len(lines) > 5:
            _readings_mutation(lines, m, notes)
    if empty in ("empty", "blank", "newlines", "one"):
        data = {"empty": b"", "blank": b"   \n  \n", "newlines": b"\n" * 90, "one": b"1\n"}[empty]
        notes.append(f"whole deck replaced by {data[:12]!r}")
        return data
    text = eol.join(lines) + ("" if empty == "nofinal" else eol)
    data = bytearray(prefix + text.encode("utf-8"))
    for m in byte_muts:
        # position of (card, col) in the encoded text
        ci = min(m["card"], max(len(lines) - 1, 0))
        pos = len(prefix) + len(eol.join(lines[:ci]).encode("utf-8")) + (len(eol) if ci else 0) + m["col"]
        pos = min(pos, len(data))
        data[pos:pos + 1] = bytes([m["byte"]])
        notes.append(f"byte {pos} := 0x{m['byte']:02X} (card {ci + 1}, column {m['col'] + 1})")
    return bytes(data)


def _char_mutation(lines, program, m, notes):
    xs, ys = _char_values(lines, program)
    n = _deck_n(lines, program)
    f, what, j = m["factor"], m["what"], min(m["j"], n - 2)
    if what == "scale_x":
        xs = [v * f for v in xs[:n]] + xs[n:]
    elif what == "scale_y":
        ys = [v * abs(f) for v in ys[:n]] + ys[n:]
    elif what == "scale_xy":
        xs = [v * f for v in xs[:n]] + xs[n:]
        ys = [v * abs(f) for v in ys[:n]] + ys[n:]
    elif what == "shift_x":
        xs = [v + f for v in xs[:n]] + xs[n:]
    elif what == "dup_point":
        xs[j + 1], ys[j + 1] = xs[j], ys[j]
    elif what == "reverse":
        xs = xs[:n][::-1] + xs[n:]
    elif what == "zero":
        xs = [0.0] * 200
        ys = [0.0] * 200
    elif what == "const_y":
        ys = [ys[0]] * n + ys[n:]
    elif what == "flip_y":
        ys = [-v for v in ys[:n]][::-1] + ys[n:]
    elif what == "spike":
        xs[j] = f if f else 1e30
    elif what == "n_small":
        ci = 2 if program == "lieng1" else 1
        k = 3 + (m["j"] % 3)
        lines[ci] = f"{k:5d}" + lines[ci][5:]
        notes.append(f"N := {k}")
    _set_char(lines, program, xs, ys)
    if what != "n_small":
        notes.append(f"characteristic: {what} (factor {f:g}, point {j + 1}), rewritten in F10 fields")


def _readings_mutation(lines, m, notes):
    """Mutate the 18I4 readings cards (NT, NH, NHN triples) of a TRC deck."""
    data = []
    for ln in lines[4:]:
        ln = ln.ljust(72)
        data.append([ln[4 * j:4 * j + 4] for j in range(18)])
    flat = [c for row in data for c in row]
    trip = [flat[3 * k:3 * k + 3] for k in range(len(flat) // 3)]
    what, k = m["what"], min(m["k"], max(len(trip) - 2, 0))
    if what == "zero":
        trip = [["   0"] * 3 for _ in trip]
    elif what == "const_nh":
        trip = [[a, "1000", c] for a, b, c in trip]
    elif what == "dup_nt" and trip:
        trip[k + 1][0] = trip[k][0]
    elif what == "rev_nt" and trip:
        trip[k][0] = "  99"
    elif what == "neg" and trip:
        trip[k][1] = "-999"
    elif what == "max" and trip:
        trip[k] = ["9999", "9999", "9999"]
    elif what == "const_nt":
        trip = [["  60", b, c] for a, b, c in trip]
    elif what == "one_jump" and trip:
        trip[k][1] = "9999"
    if what in ("nn_more", "nn_less"):
        try:
            nn = int(lines[3][:5].strip() or 0)
        except ValueError:
            nn = 180
        new = nn + 30 if what == "nn_more" else max(nn - 170 + k % 20, 0)
        lines[3] = f"{new:5d}" + lines[3][5:]
        notes.append(f"NN := {new} (the readings cards unchanged)")
        return
    flat = [c for tr in trip for c in tr]
    for r in range(len(data)):
        lines[4 + r] = "".join(flat[18 * r:18 * r + 18]).rstrip()
    notes.append(f"readings: {what} at point {k + 1}")


# --- setup (user files) and output paths ------------------------------------

#: output file names per command (a pre-existing file of such a name may be replaced on success)
OUTPUTS = {
    "run lieng1": {"listing.txt", "trajectories.csv", "phase_plane.png", "displacement_time.png",
                   "velocity_time.png"},
    "run mlien": {"listing.txt", "trajectories.csv", "characteristic_last.csv", "phase_plane.png",
                  "displacement_time.png", "velocity_time.png"},
    "run trc": {"listing.txt", "trc.csv", "lisitsyn_ellipse.png", "phase_planes.png", "apparent_mu.png",
                "lienard_phase_planes.png", "characteristic.png", "nondim_mu.png"},
    "diagnose": {"diagnosis.json", "report.md", "trace.png", "characteristic.png", "residuals.png"},
    "twodof": {"twodof.json", "angle.png", "forces.png", "spectrum.png", "regimes.png"},
    "map": {"map.csv", "v_oc.csv", "map.png"},
    "figures": None,   # any *.png
}
#: the manifest of the outputs lieng writes in an output directory
MANIFEST = ".lieng-outputs"
for _k, _v in OUTPUTS.items():
    if _v is not None:
        _v.add(MANIFEST)

OUT_DIR_VARIANTS = ["fresh", "fresh", "fresh", "existing", "existing", "nested", "empty", "dot", "file",
                    "under_file", "fifo", "symlink_loop", "symlink_dir", "dangling", "trailing_slash", "long_name",
                    "unicode", "input", "dotdot", "dash", "outname_dir"]
OUT_FILE_VARIANTS = ["fresh", "fresh", "existing_file", "nested_missing", "nested_exists", "empty", "dot", "dir",
                     "under_file", "fifo", "symlink_loop", "dangling", "trailing_slash", "long_name", "input",
                     "symlink_file"]


def gen_setup(d: Drawer, command: str) -> list:
    """User files to create in the output directory before the run."""
    items = []
    names = sorted(OUTPUTS.get(command) or {"fig.png"})
    if d.boolean(0.5):
        items.append({"t": "notes"})
    if d.boolean(0.3):
        items.append({"t": "outname_dir", "name": d.choice([n for n in names if not n.endswith(".png")] or names)})
    if d.boolean(0.3):
        items.append({"t": "old_output", "name": d.choice(names)})
    return items


def out_entries(variant: str, outdir_kind: str, input_path: str | None, notes: list) -> tuple[str, list]:
    """The -o value and the entries it needs, for an output directory
    (``outdir_kind == "dir"``) or an output file (``"file"``)."""
    e = []
    if outdir_kind == "dir":
        o = {"fresh": "out", "existing": "out", "nested": "a/b/c/out", "empty": "", "dot": ".", "file": "afile",
             "under_file": "afile/out", "fifo": "fifo", "symlink_loop": "loop", "symlink_dir": "link",
             "dangling": "dangling", "trailing_slash": "out/", "long_name": "o" * 300, "unicode": "\u00f6ut dir",
             "input": input_path or "afile", "dotdot": f"../{WORK}/out", "dash": "-", "outname_dir": "out"}[variant]
    else:
        o = {"fresh": "s.csv", "existing_file": "afile", "nested_missing": "nodir/s.csv",
             "nested_exists": "sub/s.csv", "empty": "", "dot": ".", "dir": "out", "under_file": "afile/s.csv",
             "fifo": "fifo", "symlink_loop": "loop", "dangling": "dangling", "trailing_slash": "s.csv/",
             "long_name": "s" * 300 + ".csv", "input": input_path or "afile", "symlink_file": "link"}[variant]
    if variant in ("file", "under_file", "existing_file"):
        e.append(Entry("afile", data=b"a user's file\n"))
    if variant in ("existing", "symlink_dir") or (variant == "dir"):
        e.append(Entry("out/notes.txt" if variant != "symlink_dir" else "realdir/notes.txt", data=b"keep me\n"))
    if variant == "symlink_dir":
        e.append(Entry("link", "symlink", target="realdir"))
    if variant == "nested_exists":
        e.append(Entry("sub", "dir"))
    if variant == "fifo":
        e.append(Entry("fifo", "fifo"))
    if variant == "symlink_loop":
        e.append(Entry("loop", "symlink", target="loop"))
    if variant == "dangling":
        e.append(Entry("dangling", "symlink", target="nowhere/x"))
    if variant == "symlink_file":
        e.append(Entry("target.csv", data=b"t,x\n0,0\n"))
        e.append(Entry("link", "symlink", target="target.csv"))
    if variant == "outname_dir":
        e.append(Entry("out/trajectories.csv/keep.txt", data=b"a user's file inside a directory\n"))
    if variant not in ("fresh",):
        notes.append(f"-o variant: {variant}")
    return o, e


def setup_entries(setup: list, outdir: str | None) -> list:
    if outdir is None:
        return []
    base = outdir.rstrip("/") or "."
    if base in ("", "."):
        base = "."
    e = []
    for it in setup:
        if it["t"] == "notes":
            e.append(Entry(f"{base}/notes.txt", data=b"the user's notes, not an output\n"))
        elif it["t"] == "outname_dir":
            e.append(Entry(f"{base}/{it['name']}/keep.txt", data=b"a user's file in a directory named like an output\n"))
        elif it["t"] == "old_output":
            e.append(Entry(f"{base}/{it['name']}", data=b"an older output\n"))
    return e


def _setup_ok(variant):
    """Setup files can go into the output directory for these -o variants."""
    return variant in ("fresh", "existing", "nested", "trailing_slash", "unicode", "dotdot", "dash", "outname_dir",
                       "empty", "dot")


def _dedupe(entries):
    seen, out = {}, []
    for e in entries:
        key = str(Path(e.path))
        if key in seen:
            continue
        # a file whose path is a parent of another entry would clash: keep the first
        if any(key.startswith(s + "/") or s.startswith(key + "/") for s in seen):
            continue
        seen[key] = e
        out.append(e)
    return out


# ---------------------------------------------------------------------------
# Tables (sawtooth stick-slip)
# ---------------------------------------------------------------------------


def sawtooth(n, dt, fn, v0, drop, xs, noise, seed):
    """Samples of a simple stick-slip signal: x rises at v0 while sticking,
    drops by ``drop`` in half a period of fn while slipping."""
    rnd = random.Random(seed)
    tslip = 1.0 / (2.0 * fn)
    tstick = drop / v0
    period = tslip + tstick
    t, x = [], []
    for i in range(n):
        ti = i * dt
        ph = math.fmod(ti, period)
        if ph < tstick:
            xi = xs - drop + v0 * ph
        else:
            xi = xs - drop / 2 + drop / 2 * math.cos(math.pi * (ph - tstick) / tslip)
        t.append(ti)
        x.append(xi + (rnd.gauss(0.0, noise) if noise else 0.0))
    return t, x


TABLE_MUTS = ["repeat", "dup_row", "swap_rows", "bad_cell", "bad_cell", "huge", "scale_col", "time_scale",
              "time_offset", "ragged", "long_field", "bom", "non_utf8", "header_only", "empty", "eol", "comment",
              "truncate_rows", "negate", "zero_col", "noise_only", "precision", "unit", "dup_header",
              "decimal_comma", "nul", "trailing_sep", "blank_lines", "quote", "header_case"]


#: mutations that keep the table readable (the numbers change, not the syntax): they reach the analysis
TABLE_NUMERIC = ["repeat", "scale_col", "time_scale", "time_offset", "negate", "zero_col", "noise_only", "precision",
                 "dup_row", "swap_rows", "huge", "truncate_rows"]


def gen_table_mutation(d: Drawer, numeric: bool = False) -> dict:
    op = d.choice(TABLE_NUMERIC if numeric else TABLE_MUTS)
    m = {"op": op, "row": d.integer(0, 10**6), "col": d.integer(0, 5)}
    if op == "bad_cell":
        m["value"] = d.choice(["nan", "NaN", "inf", "-inf", "Infinity", "", " ", "abc", "1e309", "-", "1,5", "0x1",
                               "1e", "--1", "1.2.3", "\u00e9", "None", "null", "1e-400"])
        m["span"] = d.choice([1, 1, 1, 10, 100000])
    elif op == "huge":
        m["value"] = d.choice(["1e308", "-1e308", "1.7976931348623157e308", "1e100", "1.0000001e100", "9.9e99",
                               "1e99", "5e-324", "1e-300", "1e50", "-1e50", "1e20"])
        m["span"] = d.choice([1, 1, 10, 100000])
    elif op in ("scale_col",):
        m["factor"] = d.choice([1e99, 1e-300, 1e50, 1e-9, 1e9, 0.0, -1.0, 1e-20, 1e20])
    elif op == "time_scale":
        m["factor"] = d.choice([1e-9, 1e9, 1e-300, 1e90, 1e-15, 1e15])
    elif op == "time_offset":
        m["offset"] = d.choice([1e9, 1e12, 1e16, -1e9, 1e99])
    elif op == "ragged":
        m["how"] = d.choice(["drop_cell", "extra_cell", "one_cell", "empty_row_cells", "all_rows_short"])
    elif op == "long_field":
        m["how"] = d.choice(["zeros", "digits", "garbage_line", "long_header"])
        m["len"] = d.choice([400, 5000, 200000])
    elif op == "non_utf8":
        m["byte"] = d.choice([0xFF, 0x80, 0xC3, 0xFE, 0xB5])
        m["where"] = d.choice(["header", "row", "unit"])
    elif op == "eol":
        m["style"] = d.choice(["crlf", "cr", "nofinal", "ff"])
    elif op == "truncate_rows":
        m["keep"] = d.choice([0, 1, 2, 9, 10, 11, 49, 50, 51, 60])
    elif op == "precision":
        m["digits"] = d.choice([1, 2, 3, 4, 17])
    elif op == "unit":
        m["unit"] = d.choice(["furlong", "", "s", "ms", "us", "min", "mm", "um", "m", "nm", "N", "mN", "kN", "mm/s",
                              "m/s", "mm/min", "\u00b5m", "MM", " mm ", "[", "s]"])
    elif op == "noise_only":
        m["level"] = d.choice([0.0, 1e-12, 1.0, 1e50])
    return m


def apply_table_mutations(header: list, units: list, cols: list, sep: str, muts: list, notes: list,
                          fmt: str = "%.9g") -> bytes:
    """Render a table (header names, units, float columns) with mutations."""
    ncol = len(header)
    n = len(cols[0]) if cols else 0
    cols = [list(c) for c in cols]
    units = list(units)
    header = list(header)
    digits = None
    for m in muts:
        op = m["op"]
        if op == "time_scale":
            cols[0] = [v * m["factor"] for v in cols[0]]
            notes.append(f"time scaled by {m['factor']:g}")
        elif op == "time_offset":
            cols[0] = [v + m["offset"] for v in cols[0]]
            notes.append(f"time offset by {m['offset']:g}")
        elif op == "scale_col" and ncol > 1:
            c = 1 + m["col"] % (ncol - 1)
            cols[c] = [v * m["factor"] for v in cols[c]]
            notes.append(f"column {header[c]} scaled by {m['factor']:g}")
        elif op == "negate" and ncol > 1:
            c = 1 + m["col"] % (ncol - 1)
            cols[c] = [-v for v in cols[c]]
            notes.append(f"column {header[c]} negated")
        elif op == "zero_col" and ncol > 1:
            c = 1 + m["col"] % (ncol - 1)
            cols[c] = [0.0] * n
            notes.append(f"column {header[c]} all zero")
        elif op == "noise_only" and ncol > 1:
            rnd = random.Random(m["row"])
            cols[1] = [rnd.gauss(0, m["level"]) if m["level"] else 0.0 for _ in range(n)]
            notes.append(f"column {header[1]} replaced by noise of sd {m['level']:g}")
        elif op == "repeat" and ncol > 1 and n:
            c = 1 + m["col"] % (ncol - 1)
            r0 = m["row"] % n
            r1 = min(n, r0 + max(n // 3, 1))
            cols[c][r0:r1] = [cols[c][r0]] * (r1 - r0)
            notes.append(f"column {header[c]} rows {r0 + 1}-{r1} repeat one value")
        elif op == "precision":
            digits = m["digits"]
            notes.append(f"numbers written with %.{digits}g")
        elif op == "unit":
            c = m["col"] % ncol
            units[c] = m["unit"]
            notes.append(f"unit of column {header[c]} := {m['unit']!r}")
        elif op == "dup_header" and ncol > 1:
            header[1] = header[0]
            notes.append(f"header names column 2 {header[0]!r} too")
        elif op == "header_case":
            header = [h.upper() for h in header]
            notes.append("header upper case")
    f = (lambda v: f"{v:.{digits}g}") if digits else (lambda v: fmt % v)
    rows = [[f(cols[c][r]) for c in range(ncol)] for r in range(n)]
    head = [h + (f" [{u}]" if u else "") for h, u in zip(header, units)]
    lines_extra = []
    eol, prefix, post = "\n", "", []
    for m in muts:
        op = m["op"]
        n = len(rows)
        r = m["row"] % n if n else 0
        if op in ("bad_cell", "huge") and n:
            c = m["col"] % ncol
            for rr in range(r, min(n, r + m["span"])):
                if c < len(rows[rr]):                 # a ragged row may be short
                    rows[rr][c] = m["value"]
            shown = repr(m["value"]) if op == "bad_cell" else m["value"]
            notes.append(f"rows {r + 1}..{min(n, r + m['span'])}, column {header[c]} := {shown}")
        elif op == "dup_row" and n:
            rows.insert(r, list(rows[r]))
            notes.append(f"row {r + 1} duplicated")
        elif op == "swap_rows" and n > 1:
            r = min(r, n - 2)
            rows[r], rows[r + 1] = rows[r + 1], rows[r]
            notes.append(f"rows {r + 1} and {r + 2} swapped")
        elif op == "ragged" and n:
            how = m["how"]
            if how == "drop_cell":
                rows[r] = rows[r][:-1]
            elif how == "extra_cell":
                rows[r] = rows[r] + ["1"]
            elif how == "one_cell":
                rows[r] = rows[r][:1]
            elif how == "empty_row_cells":
                rows[r] = [""] * ncol
            elif how == "all_rows_short":
                rows = [row[:-1] for row in rows]
            notes.append(f"ragged: {how} at row {r + 1}")
        elif op == "long_field" and n:
            how, ln = m["how"], m["len"]
            c = m["col"] % max(1, len(rows[r]))   # a ragged row may be short
            if how == "zeros" and rows[r]:
                rows[r][c] = "0." + "0" * ln + "1"
            elif how == "digits" and rows[r]:
                rows[r][c] = "1" + "0" * ln
            elif how == "garbage_line":
                lines_extra.append((r, "x" * ln))
            elif how == "long_header":
                head[-1] = head[-1] + "h" * ln
            notes.append(f"long field ({how}, {ln} characters) at row {r + 1}")
        elif op == "truncate_rows":
            rows = rows[:m["keep"]]
            notes.append(f"only the first {m['keep']} data rows kept")
        elif op == "header_only":
            rows = []
            notes.append("header only")
        elif op == "decimal_comma" and n:
            rows = [[c.replace(".", ",") for c in row] for row in rows]
            notes.append("decimal commas in the cells")
        elif op == "trailing_sep":
            rows = [row + [""] for row in rows]
            head = head + [""]
            notes.append("a trailing separator on every line")
        elif op == "quote":
            head = [f'"{h}"' for h in head]
            notes.append("header cells quoted")
        elif op == "comment":
            lines_extra.append((r, "# a comment line"))
            notes.append(f"a comment line before row {r + 1}")
        elif op == "blank_lines":
            lines_extra.append((r, ""))
            lines_extra.append((r, "   "))
            notes.append(f"blank lines before row {r + 1}")
        elif op == "eol":
            eol = {"crlf": "\r\n", "cr": "\r", "nofinal": "\n", "ff": "\n\f"}[m["style"]]
            if m["style"] == "nofinal":
                post.append("nofinal")
            notes.append(f"line ends {m['style']}")
        elif op == "bom":
            prefix = "\ufeff"
            notes.append("UTF-8 BOM")
        elif op in ("non_utf8", "nul", "empty"):
            post.append(m)
    sep_w = sep if sep != " " else "  "
    out_lines = [sep_w.join(head)] + [sep_w.join(row) for row in rows]
    for r, text in sorted(lines_extra, key=lambda a: -a[0]):
        out_lines.insert(min(r + 1, len(out_lines)), text)
    text = prefix + eol.join(out_lines) + ("" if "nofinal" in post else eol)
    data = bytearray(text.encode("utf-8"))
    for m in post:
        if m == "nofinal":
            continue
        if m["op"] == "empty":
            data = bytearray()
            notes.append("empty file")
        elif m["op"] == "nul":
            pos = min(len(data), len(out_lines[0]) + 5 + m["row"] % 200)
            data[pos:pos] = b"\x00"
            notes.append(f"NUL byte at offset {pos}")
        elif m["op"] == "non_utf8":
            where = m["where"]
            pos = {"header": 1, "row": min(len(data), len(out_lines[0]) + 3 + m["row"] % 500),
                   "unit": max(data.find(b"["), 0)}[where]
            data[pos:pos] = bytes([m["byte"]])
            notes.append(f"non-UTF-8 byte 0x{m['byte']:02X} in the {where} (offset {pos})")
    return bytes(data)


def gen_signal(d: Drawer, cycles=(10, 6, 20, 3, 40)) -> dict:
    """A sawtooth's parameters; the sampling rate puts about ``ncyc`` cycles in the n samples."""
    sig = {"n": d.choice([300, 60, 50, 120, 1000, 2000, 3000]), "fn": d.choice([10.0, 5.0, 20.0, 40.0]),
           "v0": d.choice([1.0, 0.5, 2.0, 5.0]), "drop": d.choice([0.4, 0.1, 1.0]),
           "xs": d.choice([0.5, 0.0, 3.0]), "noise": d.choice([0.002, 0.0, 0.02]),
           "ncyc": d.choice(list(cycles)), "seed": d.integer(0, 10**6)}
    return sig


def signal_rate(sig) -> float:
    if "rate" in sig:
        return sig["rate"]
    period = sig["drop"] / sig["v0"] + 1.0 / (2.0 * sig["fn"])
    return sig["n"] / (sig["ncyc"] * period)


# ---------------------------------------------------------------------------
# Generators and builders per kind
# ---------------------------------------------------------------------------


def _out_spec(d: Drawer, command: str, outpaths=False) -> dict:
    variant = d.choice(OUT_DIR_VARIANTS) if outpaths else d.choice(["fresh"] * 6 + ["existing", "outname_dir",
                                                                                   "nested"])
    setup = gen_setup(d, command) if d.boolean(0.4) or outpaths else []
    # an existing directory with other files is refused without --force
    force = d.boolean(0.6 if (setup or variant in ("existing", "outname_dir")) else 0.1)
    return {"out": variant, "setup": setup, "force": force}


def _deck_opts(d: Drawer, program: str) -> dict:
    o = {}
    if d.boolean(0.3):
        o["--lookup"] = d.choice(["bisect", "fast", "listing"])
    if program == "trc" and d.boolean(0.3):
        o["--origin"] = d.choice(["fit", "listing"])
    if d.boolean(0.85):
        o["--no-plots"] = True
    if d.boolean(0.5):
        o["-q"] = True
    return o


def gen_deck_kind(program: str):
    bases = {"lieng1": LIENG1_BASES, "mlien": MLIEN_BASES, "trc": TRC_BASES}[program]

    def gen(d: Drawer) -> dict:
        base = d.choice(bases)
        nlines = len((CARDS / base).read_text().splitlines())
        muts = [gen_deck_mutation(d, program, nlines) for _ in range(d.choice([0, 1, 1, 1, 2, 3]))]
        spec = {"kind": f"{program}_deck", "program": program, "base": base, "mut": muts,
                "opts": _deck_opts(d, program), "name": d.choice(["deck.dat", "deck.dat", "deck", "deck.csv",
                                                                   "deck.txt"])}
        if program == "lieng1" and not any(m["op"] == "field" and m.get("card") == 2 for m in muts) and d.boolean(0.5):
            spec["opts"]["--lookup"] = "fast"     # the listing look-up is ~10x slower
        if d.boolean(0.05):
            spec["run_as"] = d.choice(["lieng1", "mlien", "trc"])
        spec.update(_out_spec(d, f"run {program}"))
        return spec
    return gen


def _opts_argv(opts: dict) -> list:
    a = []
    for k, v in opts.items():
        if v is True:
            a.append(k)
        elif v is False or v is None:
            continue
        else:
            a += [k, str(v)]
    return a


def _finish(kind, spec, argv_head, opts, outdir_kind, input_path, entries, notes, command,
            out_opt="-o") -> Case:
    o, oe = out_entries(spec.get("out", "fresh"), outdir_kind, input_path, notes)
    entries = list(entries) + oe
    if outdir_kind == "dir" and _setup_ok(spec.get("out", "fresh")):
        entries += setup_entries(spec.get("setup", []), o)
    elif outdir_kind == "file" and spec.get("setup"):
        entries += setup_entries(spec.get("setup", []), ".")
    argv = list(argv_head) + _opts_argv(opts) + (["--force"] if spec.get("force") else []) \
        + ([out_opt, o] if out_opt else [])
    for it in spec.get("setup", []):
        notes.append(f"user file set up: {it}")
    return Case(kind, argv, _dedupe(entries), notes, spec)


def build_deck_case(spec) -> Case:
    program = spec["program"]
    notes = [f"deck: cards/{spec['base']} with mutations:"]
    lines = (CARDS / spec["base"]).read_text().splitlines()
    data = apply_deck_mutations(lines, program, spec["mut"], notes)
    name = spec["name"]
    run_as = spec.get("run_as", program)
    if run_as != program:
        notes.append(f"run as {run_as}")
    return _finish(spec["kind"], spec, ["run", run_as, name], spec["opts"], "dir", name,
                   [Entry(name, data=data)], notes, f"run {run_as}")


# --- trc CSV ----------------------------------------------------------------


def gen_trc_csv(d: Drawer) -> dict:
    numeric = d.boolean(0.5)     # only mutations that keep the table readable
    sig = gen_signal(d, cycles=(1.3, 1.3, 2.5, 0.5, 5))
    sig["n"] = d.choice([200, 60, 10, 11, 9, 500, 1500])
    spec = {"kind": "trc_csv", "sig": sig, "xn": d.boolean(0.4), "sep": d.choice([",", ",", "\t", ";", " "]),
            "name": d.choice(["data.csv", "data.csv", "data.txt", "data", "data.tsv"]),
            "mut": [gen_table_mutation(d, numeric) for _ in range(d.choice([0, 0, 1, 1, 2, 3]))], "opts": {}}
    o = spec["opts"]
    o["--omnh"] = d.choice(["62.8", "62.8", "125.6"]) if d.boolean(0.7) else d.choice(FLOAT_ARG)
    if spec["xn"] or d.boolean(0.2):
        o["--omnv"] = d.choice(["94.2", "94.2"]) if d.boolean(0.7) else d.choice(FLOAT_ARG)
    if d.boolean(0.05):
        del o["--omnh"]
    o.update(_deck_opts(d, "trc"))
    spec.update(_out_spec(d, "run trc"))
    return spec


def build_trc_csv(spec) -> Case:
    s = spec["sig"]
    t, x = sawtooth(s["n"], 1.0 / signal_rate(s), s["fn"], s["v0"], s["drop"], s["xs"], s["noise"], s["seed"])
    header, cols = ["t", "x"], [t, x]
    if spec["xn"]:
        xn = [0.05 * math.sin(2 * math.pi * 3 * s["fn"] * ti) + 0.3 for ti in t]
        header.append("xn")
        cols.append(xn)
    notes = [f"table: sawtooth {s}, columns {','.join(header)}, separator {spec['sep']!r}"]
    if spec["sep"] != ",":
        notes.append("(only comma-separated tables are documented for trc)")
    data = apply_table_mutations(header, [""] * len(header), cols, spec["sep"], spec["mut"], notes)
    name = spec["name"]
    return _finish("trc_csv", spec, ["run", "trc", name], spec["opts"], "dir", name, [Entry(name, data=data)],
                   notes, "run trc")


# --- diagnose tables ----------------------------------------------------------

DIAG_LAYOUTS = {
    "tx": (["t", "x"], ["", ""]),
    "txv": (["t", "x", "v0"], ["", "", ""]),
    "txyv": (["t", "x", "y", "v0"], ["", "", "", ""]),
    "txy": (["t", "x", "y"], ["", "", ""]),
    "units_disp": (["time", "displacement", "drive velocity"], ["ms", "um", "mm/s"]),
    "force": (["Time", "Friction force", "Normal load", "Stage position"], ["s", "mN", "N", "um"]),
    "force_tf": (["t", "F"], ["s", "N"]),
    "force_tfn": (["t", "F", "N"], ["s", "N", "N"]),
    "force_v": (["t", "F", "v0"], ["s", "mN", "mm/s"]),
}


def gen_diagnose(d: Drawer) -> dict:
    numeric = d.boolean(0.5)     # only mutations that keep the table readable
    sig = gen_signal(d)
    sig["n"] = d.choice([1500, 600, 3000, 1000, 2000, 50, 49, 100])
    layout = d.choice(list(DIAG_LAYOUTS))
    spec = {"kind": "diagnose", "sig": sig, "layout": layout, "sep": d.choice([",", ",", "\t", ";", " "]),
            "name": d.choice(["data.csv", "data.csv", "data.txt", "data.tsv", "data", "data.dat"]),
            "mut": [gen_table_mutation(d, numeric) for _ in range(d.choice([0, 0, 1, 1, 2, 3]))], "opts": {},
            "trc_deck": d.boolean(0.06)}
    if spec["trc_deck"]:
        spec["mut"] = [gen_deck_mutation(d, "trc", 35) for _ in range(d.choice([0, 1, 2]))]
    o = spec["opts"]
    has_drive = layout in ("txv", "txyv", "units_disp", "force", "force_v")
    if not has_drive or spec["trc_deck"] or d.boolean(0.2):
        o["--v0"] = str(sig["v0"]) if d.boolean(0.7) else d.choice(FLOAT_ARG)
    if d.boolean(0.5):
        o["--fn"] = str(sig["fn"]) if d.boolean(0.6) else d.choice(FLOAT_ARG)
    if layout.startswith("force") and d.boolean(0.6) or d.boolean(0.05):
        o["--stiffness"] = "1000" if d.boolean(0.6) else d.choice(FLOAT_ARG)
    if d.boolean(0.85):
        o["--no-plots"] = True
    if d.boolean(0.3):
        o["--json"] = True
    elif d.boolean(0.5):
        o["-q"] = True
    spec.update(_out_spec(d, "diagnose"))
    return spec


def diagnose_table(spec, notes) -> bytes:
    s = spec["sig"]
    t, x = sawtooth(s["n"], 1.0 / signal_rate(s), s["fn"], s["v0"], s["drop"], s["xs"], s["noise"], s["seed"])
    names, units = DIAG_LAYOUTS[spec["layout"]]
    cols = [t]
    k = 1000.0      # N/m
    for nm, u in zip(names[1:], units[1:]):
        low = nm.lower()
        if low in ("x", "displacement"):
            cols.append([v * (1e3 if u == "um" else 1.0) for v in x])
        elif low in ("y",):
            cols.append([1.0 + 0.001 * math.sin(7.0 * ti) for ti in t])
        elif low in ("v0", "drive velocity"):
            cols.append([s["v0"]] * len(t))
        elif low in ("friction force", "f"):
            cols.append([v * k / 1e3 * (1e3 if u == "mN" else 1.0) for v in x])
        elif low in ("normal load", "n"):
            cols.append([10.0 + 0.01 * math.sin(5.0 * ti) for ti in t])
        elif low == "stage position":
            cols.append([s["v0"] * ti * 1e3 for ti in t])
    if units[0] == "ms":
        cols[0] = [v * 1e3 for v in t]
    notes.append(f"table: sawtooth {s}, header {list(zip(names, units))}, separator {spec['sep']!r}")
    return apply_table_mutations(names, units, cols, spec["sep"], spec["mut"], notes)


def build_diagnose(spec) -> Case:
    notes = []
    name = spec["name"]
    if spec.get("trc_deck"):
        notes.append("input: cards/trc_demo.dat with mutations:")
        name = "deck.dat"
        data = apply_deck_mutations((CARDS / "trc_demo.dat").read_text().splitlines(), "trc", spec["mut"], notes)
    else:
        data = diagnose_table(spec, notes)
    return _finish("diagnose", spec, ["diagnose", name], spec["opts"], "dir", name, [Entry(name, data=data)],
                   notes, "diagnose")


# --- synth --------------------------------------------------------------------


def gen_synth(d: Drawer) -> dict:
    o = {"--effect": d.choice(["none", "load_variation", "twin_branch", "static_ageing", "triggering",
                               "drive_modulation"])}
    if d.boolean(0.7):
        o["--seed"] = str(d.integer(0, 1000)) if d.boolean(0.5) else d.choice(INT_ARG)
    if d.boolean(0.8):
        o["--cycles"] = d.choice(["4", "2", "8"]) if d.boolean(0.4) else d.choice(INT_ARG)
    else:
        o["--cycles"] = "4"
    if d.boolean(0.5):
        o["--strength"] = d.choice(FLOAT_ARG)
    if d.boolean(0.5):
        o["-q"] = True
    variant = d.choice(OUT_FILE_VARIANTS) if d.boolean(0.3) else "fresh"
    return {"kind": "synth", "opts": o, "out": variant, "setup": [{"t": "notes"}] if d.boolean(0.5) else [],
            "mut": [], "force": d.boolean(0.3)}


def build_synth(spec) -> Case:
    notes = []
    entries = [Entry("input.csv", data=b"t,x\n")] if spec["out"] == "input" else []
    return _finish("synth", spec, ["synth"], spec["opts"], "file", "input.csv", entries, notes, "synth")


# --- sweep / cycles -------------------------------------------------------------

RANGES = ["1:30:5", "0.5:20:3", "1:2:100000", "-1:2:3", "2:1:3", "a:b:c", "1:2:0", "1:2:-1", "nan:1:3", "inf:1:2",
          "1:2", "1:2:3:4", "", ":", "::", "1e308:1.7e308:3", "-1e308:1e308:3", "0:0:1", "1:2:2.5", " 1 : 2 : 3 ",
          "5e-324:1e-300:3", "1:1e30:4", "0:10:2", "-30:-1:4", "1:2:1", "1:2:100001", "0x1:2:3", "1:2:1e2",
          "1:2:3 ", "1_0:2:3", "\u0661:2:3", "1:2:200"]


def gen_sweep(d: Drawer) -> dict:
    cmd = d.choice(["sweep", "cycles", "sweep"])
    program = d.choice(["lieng1", "lieng1", "lieng1", "mlien"])
    base = d.choice(["figures/fig2_27.dat", "figures/fig2_28.dat", "lieng1_demo.dat"] + LIENG1_BASES) \
        if program == "lieng1" else d.choice(MLIEN_BASES)
    o = {}
    if d.boolean(0.1):
        o["--program"] = "mlien" if program == "lieng1" else "lieng1"
        o["mismatch"] = True
    elif program == "mlien" or d.boolean(0.3):
        o["--program"] = program
    if d.boolean(0.4):
        o["--mode"] = d.choice(["faithful", "exact"])
    if d.boolean(0.2):
        o["--lookup"] = d.choice(["bisect", "fast", "listing"])
    if d.boolean(0.4):
        o["--json"] = True
    if cmd == "sweep":
        which = d.choice(["--v0", "--dmu"])
        o[which] = d.choice(RANGES[:2]) if d.boolean(0.3) else d.choice(RANGES)
        if which == "--dmu" and d.boolean(0.4):
            o["--at-v0"] = d.choice(FLOAT_ARG)
    muts = [gen_deck_mutation(d, program, 83) for _ in range(1)] if d.boolean(0.3) else []
    return {"kind": "sweep", "cmd": cmd, "program": program, "base": base, "opts": o, "mut": muts,
            "setup": [], "out": None}


def build_sweep(spec) -> Case:
    notes = [f"deck: cards/{spec['base']}" + (" with mutations:" if spec["mut"] else "")]
    lines = (CARDS / spec["base"]).read_text().splitlines()
    data = apply_deck_mutations(lines, spec["program"], spec["mut"], notes)
    opts = {k: v for k, v in spec["opts"].items() if k != "mismatch"}
    argv = [spec["cmd"], "deck.dat"] + _opts_argv(opts)
    return Case("sweep", argv, [Entry("deck.dat", data=data)], notes, spec)


# --- map ------------------------------------------------------------------------

#: small grids that make sense for each axis (the others come from RANGES)
MAP_OK = {"--v0": ["1:30:5", "0.5:20:3", "0:10:2", "1:2:1", "-30:-1:4"], "--dmu": ["0.5:1.5:3", "0.2:2:4", "1:1:1"],
          "--slope": ["0.05:0.3:3", "0.1:0.1:1", "0.5:2:2"]}


def gen_map(d: Drawer) -> dict:
    """``lieng map``: a deck, --v0 and one of --dmu / --slope (small grids, or any range of RANGES), the
    pool size or a scheduler address that is not a cluster."""
    program = d.choice(["lieng1", "lieng1", "lieng1", "mlien"])
    base = d.choice(["figures/fig2_27.dat", "figures/fig2_28.dat"] + LIENG1_BASES) if program == "lieng1" \
        else d.choice(MLIEN_BASES)
    o = {"--v0": d.choice(MAP_OK["--v0"]) if d.boolean(0.7) else d.choice(RANGES)}
    axis = d.choice(["--dmu", "--slope", "--dmu", "--slope", "none", "both"])
    for a in (["--dmu", "--slope"] if axis == "both" else [] if axis == "none" else [axis]):
        o[a] = d.choice(MAP_OK[a]) if d.boolean(0.7) else d.choice(RANGES)
    if program == "mlien" or d.boolean(0.1):
        o["--program"] = program if d.boolean(0.9) else ("mlien" if program == "lieng1" else "lieng1")
    if d.boolean(0.3):
        o["--mode"] = d.choice(["faithful", "exact"])
    if d.boolean(0.3):
        o["--workers"] = d.choice(["1", "2", "2", "0", "-1", "1.5", "abc", "257", ""])
    elif d.boolean(0.1):
        o["--scheduler"] = d.choice(["nonsense", "tcp://", "tcp://127.0.0.1:1", "udp://x:1", ""])
    if d.boolean(0.8):
        o["--no-plots"] = True
    muts = [gen_deck_mutation(d, program, 83)] if d.boolean(0.25) else []
    spec = {"kind": "map", "program": program, "base": base, "opts": o, "mut": muts}
    spec.update(_out_spec(d, "map"))
    return spec


def build_map(spec) -> Case:
    notes = [f"deck: cards/{spec['base']}" + (" with mutations:" if spec["mut"] else "")]
    lines = (CARDS / spec["base"]).read_text().splitlines()
    data = apply_deck_mutations(lines, spec["program"], spec["mut"], notes)
    return _finish("map", spec, ["map", "deck.dat"], spec["opts"], "dir", "deck.dat",
                   [Entry("deck.dat", data=data)], notes, "map")


# --- twodof ---------------------------------------------------------------------


def gen_twodof(d: Drawer) -> dict:
    o = {"--t-end": d.choice(["40", "45", "60", "100"]) if d.boolean(0.6)
         else d.choice(["0", "-1", "5e-324", "1e-300", "1e-9", "nan", "inf", "36000.0001", "1e308", "abc", "",
                        "39.999999", "40", "1", "20"])}
    if d.boolean(0.5):
        o["--preload"] = d.choice(["80", "10", "200", "1"]) if d.boolean(0.5) else d.choice(FLOAT_ARG)
    if d.boolean(0.4):
        o["--rpm"] = d.choice(["0.1", "1", "0.01", "5"]) if d.boolean(0.5) else d.choice(FLOAT_ARG)
    if d.boolean(0.3):
        o["--belt"] = d.choice(FLOAT_ARG + ["0.00838", "0.999999", "1", "0.5", "0.0001", "0.1"])
    if d.boolean(0.3):
        o["--reading"] = d.choice(["default", "previous", "3dof", "slow-belt", "point", "nonsense", "",
                                   "rod/cos2/+sincos/m1-table/r80/sec5", "rod/full/+sin/m1-r1/r90/sec4.3/3dof",
                                   "rod+tip/sin2/-sincos/m1-r1/r90/sec5/3dof", "a/b/c/d/e/f"])
    if d.boolean(0.3):
        o["--members"] = d.choice(["1", "2", "3", "0", "-1", "65", "abc", "1.5"])
    if d.boolean(0.5):
        o["--json"] = True
    spec = {"kind": "twodof", "opts": o, "mut": [], "use_out": d.boolean(0.4)}
    spec.update(_out_spec(d, "twodof"))
    return spec


def build_twodof(spec) -> Case:
    notes = []
    if spec["use_out"]:
        return _finish("twodof", spec, ["twodof"], spec["opts"], "dir", None, [], notes, "twodof")
    return Case("twodof", ["twodof"] + _opts_argv(spec["opts"]), [], notes, spec)


# --- output paths -------------------------------------------------------------


def gen_outpaths(d: Drawer) -> dict:
    cmd = d.choice(["run lieng1", "run trc", "run mlien", "diagnose", "synth", "twodof", "figures", "run trc csv"])
    spec = {"kind": "outpaths", "cmd": cmd, "mut": [], "opts": {"--no-plots": d.boolean(0.8), "-q": d.boolean(0.5)}}
    if cmd == "synth":
        spec["out"] = d.choice(OUT_FILE_VARIANTS)
        spec["setup"] = [{"t": "notes"}] if d.boolean(0.5) else []
        spec["force"] = d.boolean(0.5)
    else:
        spec.update(_out_spec(d, cmd.replace(" csv", ""), outpaths=True))
    if d.boolean(0.15):
        spec["input"] = d.choice(["dir", "fifo", "missing", "loop", "dangling", "empty_name", "dash"])
    return spec


def build_outpaths(spec) -> Case:
    cmd, notes, entries = spec["cmd"], [], []
    o = dict(spec["opts"])
    inp = None
    if cmd.startswith("run") and cmd != "run trc csv":
        prog = cmd.split()[1]
        inp = "deck.dat"
        base = {"lieng1": "lieng1_demo.dat", "mlien": "mlien_a9_7.dat", "trc": "trc_demo.dat"}[prog]
        entries.append(Entry(inp, data=(CARDS / base).read_bytes()))
        notes.append(f"{inp}: a copy of cards/{base}")
        if prog == "lieng1":
            o["--lookup"] = "fast"
        head = ["run", prog, inp]
        command = cmd
    elif cmd == "run trc csv":
        inp = "data.csv"
        t, x = sawtooth(300, 0.45 * 1.3 / 300, 10.0, 1.0, 0.4, 0.5, 0.002, 1)
        entries.append(Entry(inp, data=("t,x\n" + "".join(f"{a:.9g},{b:.9g}\n" for a, b in zip(t, x))).encode()))
        notes.append("data.csv: sawtooth n=300 over 1.3 cycles, fn 10, v0 1, drop 0.4 (t,x)")
        head, command = ["run", "trc", inp], "run trc"
        o["--omnh"] = "62.8"
    elif cmd == "diagnose":
        inp = "data.csv"
        sub = {"sig": {"n": 1500, "fn": 10.0, "v0": 1.0, "drop": 0.4, "xs": 0.5, "noise": 0.002, "ncyc": 10,
                       "seed": 1}, "layout": "txv", "sep": ",", "mut": []}
        entries.append(Entry(inp, data=diagnose_table(sub, notes)))
        head, command = ["diagnose", inp], "diagnose"
    elif cmd == "synth":
        head, command = ["synth", "--seed", "1", "--cycles", "3"], "synth"
        o.pop("--no-plots", None)
        inp = "input.csv"
        if spec["out"] == "input":
            entries.append(Entry(inp, data=b"t,x\n"))
        c = _finish("outpaths", spec, head, o, "file", inp, entries, notes, command)
        return c
    elif cmd == "twodof":
        head, command = ["twodof", "--t-end", "40"], "twodof"
        o.pop("--no-plots", None)
        o.pop("-q", None)
    else:
        head, command = ["figures", "--cards", str(CARDS), "--only", "2.29"], "figures"
        o.pop("--no-plots", None)
    if inp and spec.get("input"):
        how = spec["input"]
        entries = [e for e in entries if e.path != inp]
        if how == "dir":
            entries.append(Entry(inp, "dir"))
        elif how == "fifo":
            entries.append(Entry(inp, "fifo"))
        elif how == "loop":
            entries.append(Entry(inp, "symlink", target=inp))
        elif how == "dangling":
            entries.append(Entry(inp, "symlink", target="nowhere/x"))
        elif how == "empty_name":
            head = [("" if a == inp else a) for a in head]
        elif how == "dash":
            head = [("-" if a == inp else a) for a in head]
        notes.append(f"input path variant: {how}")
    return _finish("outpaths", spec, head, o, "dir", inp, entries, notes, command)


# ---------------------------------------------------------------------------
# Registry
# ---------------------------------------------------------------------------

GENERATORS = {
    "lieng1_deck": gen_deck_kind("lieng1"),
    "mlien_deck": gen_deck_kind("mlien"),
    "trc_deck": gen_deck_kind("trc"),
    "trc_csv": gen_trc_csv,
    "diagnose": gen_diagnose,
    "synth": gen_synth,
    "sweep": gen_sweep,
    "twodof": gen_twodof,
    "outpaths": gen_outpaths,
    "map": gen_map,
}
BUILDERS = {
    "lieng1_deck": build_deck_case, "mlien_deck": build_deck_case, "trc_deck": build_deck_case,
    "trc_csv": build_trc_csv, "diagnose": build_diagnose, "synth": build_synth, "sweep": build_sweep,
    "twodof": build_twodof, "outpaths": build_outpaths, "map": build_map,
}
KINDS = tuple(GENERATORS)


def build(spec: dict) -> Case:
    return BUILDERS[spec["kind"]](spec)


def random_case(kind: str, seed, index: int) -> Case:
    """Case ``index`` of a campaign with ``seed`` (reproducible)."""
    d = RandomDrawer(random.Random(f"{seed}:{kind}:{index}"))
    return build(GENERATORS[kind](d))


def cases(kind: str):
    """A hypothesis strategy of :class:`Case` of one kind."""
    from hypothesis import strategies as st

    @st.composite
    def strat(draw):
        return build(GENERATORS[kind](HypDrawer(draw)))
    return strat()


def shrink_candidates(spec: dict):
    """Specs one step simpler than ``spec``: one mutation, user file or option less."""
    for key in ("mut", "setup"):
        for i in range(len(spec.get(key) or [])):
            s = copy.deepcopy(spec)
            del s[key][i]
            yield s
    for k in list(spec.get("opts", {})):
        if k in ("--omnh", "--effect", "--v0", "--dmu", "--t-end"):
            continue
        s = copy.deepcopy(spec)
        del s["opts"][k]
        yield s
    if spec.get("force"):
        s = copy.deepcopy(spec)
        s["force"] = False
        yield s
    if spec.get("out") not in (None, "fresh"):
        s = copy.deepcopy(spec)
        s["out"] = "fresh"
        yield s
    if spec.get("input"):
        s = copy.deepcopy(spec)
        del s["input"]
        yield s
    sig = spec.get("sig")
    if sig and sig["n"] > 300:
        s = copy.deepcopy(spec)
        s["sig"]["n"] = 300
        yield s


def spec_json(spec: dict) -> str:
    return json.dumps(spec, sort_keys=True)
