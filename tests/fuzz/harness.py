"""Run ``lieng.cli.main(argv)`` in-process on a fuzzed case and check the contract.

The contract of the command line (README, ``lieng/cli.py``):

(i)   no exception escapes ``main`` (a traceback is a failure; a
      ``SystemExit`` from argparse is allowed only with code 2);
(ii)  the exit status is 0 or 2;
(iii) on exit 2, stderr is exactly one line starting with ``lieng: error:``;
(iv)  on exit 0, no output file written (CSV, JSON, listing.txt, report.md)
      holds a ``nan``/``inf`` number, JSON parses strictly (no NaN,
      Infinity, nor a number that overflows to inf), and JSON printed on
      stdout (``--json``) likewise;
(v)   on exit 2 nothing is changed: no file that existed before was
      modified or deleted, and nothing new is left (no half-written output
      directory, no staging directory);
(vi)  on exit 0, files that existed before and are not outputs of the
      command are unchanged (in the output directory and elsewhere: the
      input files too), and no stray file is left outside the outputs;
(vii) no hang: a run longer than the timeout is a failure.

``run_case`` snapshots every path under the case's root before and after
(path -> (type, size, mtime_ns, sha256)); ``check`` returns the
violations, each with a class and a message; ``assert_contract`` raises
with a readable report.  Classes starting with ``note:`` are advisory (not
part of the contract): e.g. ``nan`` in the human-readable stdout.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import math
import os
import re
import signal
import stat
import sys
import time
import traceback
import warnings
from dataclasses import dataclass, field
from pathlib import Path

from .cases import MANIFEST, OUTPUTS, WORK

#: outputs that must exist after a successful run (non-PNG)
#: the words of the CLI's message for a failure no check foresaw
from lieng.cli import UNEXPECTED  # noqa: E402  (the last-resort message: a failure no check foresaw)

REQUIRED = {
    "run lieng1": {"listing.txt", "trajectories.csv"},
    "run mlien": {"listing.txt", "trajectories.csv", "characteristic_last.csv"},
    "run trc": {"listing.txt", "trc.csv"},
    "diagnose": {"diagnosis.json", "report.md"},
    "twodof": {"twodof.json"},
    "figures": set(),
}


class CaseTimeout(BaseException):
    """Raised by SIGALRM in the run (a BaseException: ``except Exception`` in
    the code under test does not swallow it)."""


@dataclass
class Result:
    argv: list
    root: str
    cwd: str
    how: str = "return"            # return | systemexit | exception | timeout
    code: object = None
    exc_type: str = ""
    exc_msg: str = ""
    exc_where: str = ""
    tb: str = ""
    stdout: str = ""
    stderr: str = ""
    elapsed: float = 0.0
    before: dict = field(default_factory=dict)
    after: dict = field(default_factory=dict)
    contents: dict = field(default_factory=dict)   # rel path -> text of written output files (for the checks)
    out_real: str | None = None    # the -o path resolved before the run
    realmap: dict = field(default_factory=dict)    # rel path -> resolved path (parents resolved after the run)


@dataclass
class Violation:
    cls: str
    msg: str
    detail: str = ""

    @property
    def contract(self) -> bool:
        return not self.cls.startswith("note:")

    def __str__(self):
        return f"[{self.cls}] {self.msg}" + (f"\n{self.detail}" if self.detail else "")


# ---------------------------------------------------------------------------
# Snapshots
# ---------------------------------------------------------------------------


def _digest(path: str) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def snapshot(root) -> dict:
    """rel path -> (type, size, mtime_ns, sha256 or link target); never
    follows symlinks and never opens anything but regular files."""
    root = str(root)
    out = {}
    for dirpath, dirnames, filenames in os.walk(root, followlinks=False):
        for name in dirnames + filenames:
            p = os.path.join(dirpath, name)
            rel = os.path.relpath(p, root)
            try:
                st = os.lstat(p)
            except OSError:
                continue
            m = st.st_mode
            if stat.S_ISLNK(m):
                out[rel] = ("symlink", 0, 0, os.readlink(p))
            elif stat.S_ISDIR(m):
                out[rel] = ("dir", 0, 0, "")
            elif stat.S_ISREG(m):
                try:
                    out[rel] = ("file", st.st_size, st.st_mtime_ns, _digest(p))
                except OSError as e:
                    out[rel] = ("file", st.st_size, st.st_mtime_ns, f"unreadable: {e}")
            elif stat.S_ISFIFO(m):
                out[rel] = ("fifo", 0, 0, "")
            else:
                out[rel] = ("other", 0, 0, "")
    return out


# ---------------------------------------------------------------------------
# Running
# ---------------------------------------------------------------------------


def _vmsize() -> int:
    try:
        with open("/proc/self/status") as fh:
            for ln in fh:
                if ln.startswith("VmSize:"):
                    return int(ln.split()[1]) * 1024
    except OSError:
        pass
    return 0


def _lieng_frame(tb) -> str:
    frames = traceback.extract_tb(tb)
    inner = [f for f in frames if "/lieng/" in f.filename.replace("\\", "/") and "/tests/" not in f.filename]
    f = (inner or frames or [None])[-1]
    if f is None:
        return "?"
    fn = f.filename.replace("\\", "/")
    fn = fn.split("/lieng/", 1)[1] if "/lieng/" in fn else os.path.basename(fn)
    return f"{fn}:{f.lineno} in {f.name}"


def run_case(argv, tmp_path, timeout: float = 60, cwd=None, mem_limit: int | None = 3 << 30,
             hard_kill: float | None = 120, debug: bool = True) -> Result:
    """Run ``lieng.cli.main(argv)`` in this process.

    Parameters
    ----------
    argv : list of str
        The arguments (without the program name).
    tmp_path : path
        The case's root: every path under it is snapshotted before and after.
    timeout : float
        Seconds before SIGALRM stops the run (a failure of the contract).
    cwd : path, optional
        Working directory of the run (default ``tmp_path/work`` when it
        exists, else ``tmp_path``); restored afterwards.
    mem_limit : int, optional
        Extra address space (bytes) the run may take beyond what the process
        has (RLIMIT_AS, restored afterwards): a runaway allocation becomes a
        MemoryError instead of the OOM killer.
    hard_kill : float, optional
        Seconds after the timeout at which faulthandler dumps the stacks and
        kills the process, for a hang SIGALRM cannot interrupt (in compiled
        code).  None: no hard watchdog.
    debug : bool
        Run with ``LIENG_DEBUG=1`` (the CLI then re-raises a failure it did
        not foresee instead of printing its "unexpected failure" line).
    """
    import faulthandler

    from lieng.cli import main

    root = Path(tmp_path)
    if cwd is None:
        cwd = root / WORK if (root / WORK).is_dir() else root
    res = Result(list(argv), str(root), str(cwd))
    res.before = snapshot(root)
    o = out_arg(argv)
    if o is not None:
        res.out_real = os.path.realpath(os.path.join(str(cwd), o))
    out, err = io.StringIO(), io.StringIO()
    old_cwd = os.getcwd()
    old_handler = signal.getsignal(signal.SIGALRM)
    rl = None
    try:
        import resource

        if mem_limit:
            rl = resource.getrlimit(resource.RLIMIT_AS)
            want = _vmsize() + mem_limit
            if rl[1] == resource.RLIM_INFINITY or want < rl[1]:
                resource.setrlimit(resource.RLIMIT_AS, (want, rl[1]))
            else:
                rl = None
    except (ImportError, ValueError, OSError):
        rl = None

    def on_alarm(signum, frame):
        raise CaseTimeout(f"no result after {timeout} s")

    def show(message, category, filename, lineno, file=None, line=None):
        sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))

    old_debug = os.environ.get("LIENG_DEBUG")
    t0 = time.monotonic()
    try:
        # LIENG_DEBUG=1: the CLI's last line of defence re-raises, so an
        # unforeseen failure shows as the traceback it is
        if debug:
            os.environ["LIENG_DEBUG"] = "1"
        os.chdir(cwd)
        signal.signal(signal.SIGALRM, on_alarm)
        if hard_kill:
            faulthandler.dump_traceback_later(timeout + hard_kill, exit=True)
        signal.setitimer(signal.ITIMER_REAL, timeout)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
            # as a fresh process would: default filters, shown on (captured) stderr
            warnings.resetwarnings()
            warnings.simplefilter("default")
            warnings.showwarning = show
            try:
                res.code = main(list(argv))
                res.how = "return"
            except SystemExit as e:
                res.how, res.code = "systemexit", e.code
            except CaseTimeout:
                res.how = "timeout"
            except BaseException as e:            # noqa: BLE001 - any escape is a finding
                res.how = "exception"
                res.exc_type = type(e).__name__
                res.exc_msg = str(e)
                res.exc_where = _lieng_frame(e.__traceback__)
                res.tb = traceback.format_exc()
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        if hard_kill:
            faulthandler.cancel_dump_traceback_later()
        signal.signal(signal.SIGALRM, old_handler)
        os.chdir(old_cwd)
        if old_debug is None:
            os.environ.pop("LIENG_DEBUG", None)
        else:
            os.environ["LIENG_DEBUG"] = old_debug
        if rl is not None:
            import resource

            resource.setrlimit(resource.RLIMIT_AS, rl)
        if "matplotlib.pyplot" in sys.modules:
            sys.modules["matplotlib.pyplot"].close("all")
    res.elapsed = time.monotonic() - t0
    res.stdout, res.stderr = out.getvalue(), err.getvalue()
    res.after = snapshot(root)
    # resolved while the tree exists (check() must not look at the file system: the root may be gone)
    res.realmap = {p: os.path.join(os.path.realpath(os.path.join(str(root), os.path.dirname(p))), os.path.basename(p))
                   for p in set(res.before) | set(res.after)}
    # keep the text of written files for the checks (so results can be checked in another process)
    for rel, v in res.after.items():
        if v[0] == "file" and res.before.get(rel) != v and _checked_kind(rel, argv):
            try:
                res.contents[rel] = (root / rel).read_bytes().decode("utf-8", errors="replace")
            except OSError:
                pass
    return res


# ---------------------------------------------------------------------------
# The contract
# ---------------------------------------------------------------------------

_NAN = re.compile(r"(?<![A-Za-z0-9_])[+-]?(nan|inf|infinity)(?![A-Za-z0-9_])", re.IGNORECASE)


def command_of(argv) -> str:
    if not argv:
        return ""
    if argv[0] == "run" and len(argv) > 1:
        return f"run {argv[1]}"
    return argv[0]


def out_arg(argv):
    o = None
    for i, a in enumerate(argv):
        if a in ("-o", "--outdir", "--output") and i + 1 < len(argv):
            o = argv[i + 1]
        elif a.startswith(("--outdir=", "--output=")):
            o = a.split("=", 1)[1]
    return o


def _checked_kind(rel, argv) -> str | None:
    low = rel.lower()
    if command_of(argv) == "synth" and out_arg(argv) is not None:
        return "csv"
    for ext in ("csv", "json", "txt", "md"):
        if low.endswith("." + ext):
            return ext
    return None


def _strict_json(text: str) -> str | None:
    """None when ``text`` is strict JSON with finite numbers, else the reason."""
    def bad_const(c):
        raise ValueError(f"non-finite constant {c}")

    def num(s):
        v = float(s)
        if not math.isfinite(v):
            raise ValueError(f"number {s} overflows to {v}")
        return v
    try:
        json.loads(text, parse_constant=bad_const, parse_float=num)
    except ValueError as e:
        return str(e).splitlines()[0][:200]
    return None


def _csv_nonfinite(text: str) -> str | None:
    import csv

    for r, row in enumerate(csv.reader(io.StringIO(text)), start=1):
        for c, cell in enumerate(row, start=1):
            try:
                v = float(cell)
            except ValueError:
                continue
            if not math.isfinite(v):
                return f"line {r}, cell {c}: {cell!r}"
    return None


def _norm(s: str, root: str = "") -> str:
    if root:
        s = s.replace(os.path.realpath(root), "<tmp>").replace(root, "<tmp>")
    s = re.sub(r"/tmp/[^\s:'\"]+", "<path>", s)
    s = re.sub(r"'[^']{0,80}'", "'…'", s)
    s = re.sub(r"\"[^\"]{0,80}\"", "\"…\"", s)
    s = re.sub(r"[-+]?\b\d+(\.\d+)?([eE][-+]?\d+)?\b", "N", s)
    s = re.sub(r"\s+", " ", s).strip()
    return s[:140]


def check(res: Result) -> list[Violation]:
    """The violations of the contract by one run (see the module docstring)."""
    v: list[Violation] = []
    argv = res.argv
    cmd = command_of(argv)
    root = res.root
    if res.how == "timeout":
        return [Violation("timeout", f"no result after the timeout ({res.elapsed:.1f} s)")]
    if res.how == "exception":
        v.append(Violation("traceback", f"{res.exc_type} at {re.sub(r':[0-9]+ in', ' in', res.exc_where)}: "
                                        f"{_norm(res.exc_msg.splitlines()[0] if res.exc_msg else '', root)}",
                           f"raised at lieng/{res.exc_where}\n" + res.tb[-3000:]))
        code = None
    else:
        code = res.code
        if res.how == "systemexit" and code != 2:
            v.append(Violation("bad-exit", f"SystemExit({code!r})"))
        elif res.how == "return" and code not in (0, 2):
            v.append(Violation("bad-exit", f"main returned {code!r}"))
    # (iii)
    if code == 2 and UNEXPECTED in res.stderr:
        v.append(Violation("unexpected-failure", _norm(res.stderr.strip().splitlines()[-1], root), res.stderr[-2000:]))
    elif code == 2 and "not enough memory" in res.stderr:
        v.append(Violation("note:memory-error", _norm(res.stderr.strip().splitlines()[-1], root)))
    if code == 2:
        lines = res.stderr.splitlines()
        if len(lines) != 1 or not lines[0].startswith("lieng: error:"):
            kind = "argparse usage" if res.stderr.startswith("usage:") else f"{len(lines)} line(s)"
            first = next((ln for ln in lines if "error" in ln), lines[0] if lines else "")
            v.append(Violation("stderr-not-one-error-line", f"{kind}: {_norm(first, root)}", res.stderr[-2000:]))
    # file system
    before, after = res.before, res.after
    changed = [p for p in before if p in after and before[p] != after[p] and before[p][0] != "dir"]
    deleted = [p for p in before if p not in after]
    new = [p for p in after if p not in before]
    if code == 2 or res.how in ("exception",):
        fs = []
        if changed:
            fs.append(("exit2-modified-existing", f"{cmd}: modified {sorted(changed)[:3]}"))
        del_files = [p for p in deleted if before[p][0] != "dir"] or deleted
        if del_files:
            fs.append(("exit2-deleted-existing", f"{cmd}: deleted {sorted(del_files)[:3]}"))
        if new:
            fs.append(("exit2-left-new-paths", f"{cmd}: left {sorted(new)[:3]}"))
        if code == 2:
            v += [Violation(c, m) for c, m in fs]
        elif fs and v:
            # after a traceback: said with it (its consequence), not as a failure of its own
            v[0].detail = "after it: " + "; ".join(m for _, m in fs) + "\n" + v[0].detail
    if code == 0 and res.how in ("return", "systemexit"):
        o = out_arg(argv)
        outs: set = set()
        outdir = None
        if o is not None:
            target = res.out_real
            if cmd == "synth":
                outs = {target}
                outdir = os.path.dirname(target)
            else:
                outdir = target
                names = OUTPUTS.get(cmd)
                if names is None:       # figures: any PNG
                    outs = {os.path.join(outdir, os.path.basename(p)) for p in after
                            if p.endswith(".png")} | {os.path.join(outdir, MANIFEST)}
                else:
                    outs = {os.path.join(outdir, n) for n in names}
        real = res.realmap
        bad_changed = [p for p in changed if real[p] not in outs]
        bad_deleted = [p for p in deleted if before[p][0] != "dir" and real[p] not in outs]
        if bad_changed:
            v.append(Violation("exit0-user-file-modified", f"{cmd}: modified {sorted(bad_changed)[:3]}"))
        if bad_deleted:
            v.append(Violation("exit0-user-file-deleted", f"{cmd}: deleted {sorted(bad_deleted)[:3]}"))
        if outdir is not None:
            stray, unlisted = [], []
            for p in new:
                rp = real[p]
                if rp in outs:
                    continue
                if after[p][0] == "dir" and (outdir == rp or outdir.startswith(rp + "/")):
                    continue            # the output directory or its parents, created
                if os.path.dirname(rp) == outdir and after[p][0] == "file" and cmd != "synth":
                    unlisted.append(p)
                else:
                    stray.append(p)
            if stray:
                v.append(Violation("exit0-stray-paths", f"{cmd}: left {sorted(stray)[:3]}"))
            if unlisted:
                v.append(Violation("note:unlisted-output", f"{cmd}: wrote {sorted(unlisted)[:5]}"))
            if cmd == "synth":
                rel = [p for p in after if real[p] == next(iter(outs)) and after[p][0] == "file"]
                if not rel:
                    v.append(Violation("exit0-missing-outputs", f"synth: no regular file at -o {o!r}"))
            elif cmd in REQUIRED:
                missing = [n for n in REQUIRED[cmd]
                           if not any(real[p] == os.path.join(outdir, n) and after[p][0] == "file" for p in after)]
                if missing:
                    v.append(Violation("exit0-missing-outputs", f"{cmd}: -o {o!r}: {missing} not written"))
        elif new and cmd in ("cycles", "sweep", "twodof"):
            v.append(Violation("exit0-stray-paths", f"{cmd} (no -o): left {sorted(new)[:3]}"))
        # (iv) the written files
        for rel, text in sorted(res.contents.items()):
            kind = _checked_kind(rel, argv)
            if kind == "json":
                why = _strict_json(text)
                if why:
                    v.append(Violation("nonfinite-in-output", f"{cmd}: {os.path.basename(rel)}: not strict JSON: "
                                                              f"{_norm(why)}"))
            elif kind == "csv":
                why = _csv_nonfinite(text)
                if why:
                    v.append(Violation("nonfinite-in-output", f"{cmd}: {os.path.basename(rel)} holds non-finite "
                                                              f"numbers", why))
            elif kind in ("txt", "md"):
                m = _NAN.search(text)
                if m:
                    ln = text[:m.start()].count("\n") + 1
                    line = text.splitlines()[ln - 1] if text.splitlines() else ""
                    v.append(Violation("nonfinite-in-output", f"{cmd}: {os.path.basename(rel)} holds the token "
                                                              f"{m.group(0).strip()}", f"line {ln}: {line[:200]}"))
        if "--json" in argv:
            why = _strict_json(res.stdout)
            if why:
                v.append(Violation("nonfinite-in-output", f"{cmd}: stdout (--json) not strict JSON: {_norm(why)}",
                                   res.stdout[:500]))
        else:
            m = _NAN.search(res.stdout)
            if m:
                ln = res.stdout[:m.start()].count("\n") + 1
                v.append(Violation("note:nan-in-stdout", f"{cmd}: stdout shows {m.group(0).strip()}",
                                   res.stdout.splitlines()[ln - 1][:200]))
    return v


def report(res: Result, violations, description: str = "") -> str:
    lines = [description] if description else []
    lines.append(f"exit: {res.how} {res.code!r} in {res.elapsed:.2f} s")
    lines += [f"stderr: {ln}" for ln in res.stderr.splitlines()[:6]]
    lines += [str(x) for x in violations]
    return "\n".join(lines)


def assert_contract(res: Result, description: str = "", violations=None) -> None:
    vs = [x for x in (check(res) if violations is None else violations) if x.contract]
    if vs:
        raise AssertionError("lieng broke its contract:\n" + report(res, vs, description))


def run_and_check(case, timeout: float = 60, keep_failures: bool = True, **kw):
    """Materialize ``case`` in a fresh temporary root, run it, check it.

    Returns (result, violations); the root is removed unless a contract
    violation was found and ``keep_failures``.
    """
    import shutil
    import tempfile

    root = Path(tempfile.mkdtemp(prefix="lieng-fuzz-"))
    try:
        case.materialize(root)
        res = run_case(case.argv, root, timeout=timeout, **kw)
        vs = check(res)
    except BaseException:
        shutil.rmtree(root, ignore_errors=True)
        raise
    if keep_failures and any(x.contract for x in vs):
        res.root = str(root)
    else:
        _rmtree(root)
    return res, vs


def _rmtree(root):
    import shutil

    shutil.rmtree(root, ignore_errors=True)
