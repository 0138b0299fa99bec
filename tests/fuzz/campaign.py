"""A stand-alone fuzz campaign against ``lieng`` (outside pytest).

    python tests/fuzz/campaign.py --cases 200 --kind diagnose --seed 1
    python tests/fuzz/campaign.py --cases 900 --kind all --seed 1 --save /tmp/lieng-repro
    python tests/fuzz/campaign.py --kind sweep --seed 1 --replay 17      # case 17 again, verbose
    python tests/fuzz/campaign.py --replay-spec /tmp/lieng-repro/03-sweep-timeout/spec.json

Case ``i`` of kind ``K`` and seed ``S`` is drawn by ``random.Random(f"{S}:{K}:{i}")``
from the generators of :mod:`fuzz.cases` (the ones the pytest suite draws
with hypothesis), so any case is reproducible.  Each case runs in a forked
child (``lieng.cli.main`` in-process there, see :mod:`fuzz.harness`), so a
hang in compiled code or a crash cannot stop the campaign: the parent kills a
child that outlives the timeout by 30 s.

Failures are grouped by (kind, failure class, message); for each group the
simplest case is shrunk (dropping mutations, user files and options while the
failure stays the same) and printed with its reproduction.  With ``--kind
all`` the ``--cases`` are shared among the kinds.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing
import os
import re
import shlex
import sys
import time
from pathlib import Path

os.environ.setdefault("MPLBACKEND", "Agg")
for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from fuzz.cases import KINDS, build, random_case, shrink_candidates, spec_json  # noqa: E402
from fuzz.harness import _norm, run_and_check  # noqa: E402

HARD_GRACE = 30.0


def _preimport():
    """Import what the runs use before forking, so that each child starts warm."""
    import importlib

    for m in ("lieng.cli", "lieng.programs.lieng1", "lieng.programs.mlien", "lieng.programs.trc", "lieng.analysis.cycles", "lieng.analysis.synth",
              "lieng.analysis.twodof", "lieng.programs.graf", "lieng.analysis.figures", "lieng.programs.listing", "lieng.io.outputs", "lieng.diagnose",
              "lieng.diagnose.report", "matplotlib.pyplot", "scipy.signal", "scipy.optimize"):
        try:
            importlib.import_module(m)
        except Exception:  # noqa: BLE001
            pass


def _child(case, timeout, conn):
    try:
        res, vs = run_and_check(case, timeout=timeout, keep_failures=False, hard_kill=HARD_GRACE / 2)
        conn.send({"how": res.how, "code": res.code if isinstance(res.code, (int, type(None))) else str(res.code),
                   "elapsed": res.elapsed, "stderr": res.stderr[-3000:], "stdout": res.stdout[:1500],
                   "violations": [(v.cls, v.msg, v.detail) for v in vs]})
    except BaseException as e:  # noqa: BLE001 - a harness failure is reported, not raised
        import traceback

        conn.send({"how": "harness-error", "code": None, "elapsed": 0.0, "stderr": traceback.format_exc(),
                   "stdout": "", "violations": [("harness-error", f"{type(e).__name__}: {e}", "")]})
    finally:
        conn.close()


def run_isolated(case, timeout: float) -> dict:
    """Run a case in a forked child; a child that hangs or dies is a finding."""
    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    p = ctx.Process(target=_child, args=(case, timeout, send))
    t0 = time.monotonic()
    p.start()
    send.close()
    out = None
    deadline = t0 + timeout + HARD_GRACE
    while time.monotonic() < deadline:
        ready = recv.poll(0.2)
        if not ready and not p.is_alive():
            ready = recv.poll(0.1)
            if not ready:
                break
        if ready:
            try:
                out = recv.recv()
            except EOFError:
                out = None
            break
    p.join(timeout=5 if out is not None else 0.1)
    if p.is_alive():
        p.kill()
        p.join()
        if out is None:
            return {"how": "hard-hang", "code": None, "elapsed": time.monotonic() - t0, "stderr": "", "stdout": "",
                    "violations": [("timeout", f"hard hang: the child was killed after {timeout + HARD_GRACE:.0f} s "
                                               f"(SIGALRM could not stop it: compiled code?)", "")]}
    if out is None:
        sig = -p.exitcode if p.exitcode and p.exitcode < 0 else None
        return {"how": "crash", "code": p.exitcode, "elapsed": time.monotonic() - t0, "stderr": "", "stdout": "",
                "violations": [("crash", f"the process died ({'signal %d' % sig if sig else 'exit %s' % p.exitcode})"
                                         f" without a result", "")]}
    return out


def group_key(kind, v):
    cls, msg = v[0], v[1]
    msg = re.sub(r"\[[^\]]*\]", "[…]", msg) if cls.startswith(("exit", "after")) else msg
    return (kind, cls, _norm(msg))


def shrink(case, key, timeout, budget=25):
    """Drop mutations, user files and options while the failure ``key`` stays."""
    best, runs = case, 0
    improved = True
    while improved and runs < budget:
        improved = False
        for spec in shrink_candidates(best.spec):
            if runs >= budget:
                break
            try:
                cand = build(spec)
            except Exception:  # noqa: BLE001
                continue
            runs += 1
            out = run_isolated(cand, timeout)
            if any(group_key(key[0], v) == key for v in out["violations"]):
                best, improved = cand, True
                break
    return best


def _save(dirpath: Path, case, out, key):
    dirpath.mkdir(parents=True, exist_ok=True)
    case.materialize(dirpath)
    (dirpath / "spec.json").write_text(spec_json(case.spec) + "\n")
    (dirpath / "argv.json").write_text(json.dumps(case.argv) + "\n")
    (dirpath / "cmd.sh").write_text("#!/bin/sh\n# run from this directory\ncd \"$(dirname \"$0\")/work\" && "
                                    "LIENG_DEBUG=1 lieng " + " ".join(shlex.quote(a) for a in case.argv) + "\n")
    os.chmod(dirpath / "cmd.sh", 0o755)
    (dirpath / "report.txt").write_text(f"{key}\n\n{case.describe()}\n\n"
                                        + "\n".join(f"[{c}] {m}\n{d}" for c, m, d in out["violations"]) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", type=int, default=100, help="number of cases (shared among kinds with --kind all)")
    ap.add_argument("--kind", default="all", choices=("all",) + KINDS)
    ap.add_argument("--seed", default="1")
    ap.add_argument("--start", type=int, default=0, help="first case index")
    ap.add_argument("--timeout", type=float, default=30.0)
    ap.add_argument("--replay", type=int, help="run only this case index, verbose")
    ap.add_argument("--replay-spec", help="run the case of a spec.json (from --save), verbose")
    ap.add_argument("--no-shrink", action="store_true")
    ap.add_argument("--save", help="write each group's minimal case here (files, cmd.sh, spec.json, report.txt)")
    ap.add_argument("--json", help="write the groups as JSON here")
    ap.add_argument("--notes", action="store_true", help="show the advisory (note:) classes too")
    a = ap.parse_args(argv)
    _preimport()

    if a.replay is not None or a.replay_spec:
        if a.replay_spec:
            case = build(json.loads(Path(a.replay_spec).read_text()))
        else:
            case = random_case(a.kind, a.seed, a.replay)
        print(case.describe())
        out = run_isolated(case, a.timeout)
        print(f"\nexit: {out['how']} {out['code']!r} in {out['elapsed']:.2f} s")
        print("stderr:", out["stderr"][-3000:])
        for c, m, d in out["violations"]:
            print(f"[{c}] {m}\n{d}")
        return 1 if any(not c.startswith("note:") for c, _, _ in out["violations"]) else 0

    kinds = KINDS if a.kind == "all" else (a.kind,)
    per = {k: a.cases // len(kinds) + (1 if j < a.cases % len(kinds) else 0) for j, k in enumerate(kinds)}
    groups: dict = {}
    stats = {k: {"n": 0, "exit0": 0, "exit2": 0, "other": 0, "fail": 0, "time": 0.0} for k in kinds}
    t_start = time.monotonic()
    for kind in kinds:
        for i in range(a.start, a.start + per[kind]):
            case = random_case(kind, a.seed, i)
            out = run_isolated(case, a.timeout)
            st = stats[kind]
            st["n"] += 1
            st["time"] += out["elapsed"]
            st["exit0" if out["code"] == 0 else "exit2" if out["code"] == 2 else "other"] += 1
            bad = False
            for v in out["violations"]:
                if v[0].startswith("note:") and not a.notes:
                    continue
                key = group_key(kind, v)
                g = groups.setdefault(key, {"count": 0, "best": None, "out": None, "index": None})
                g["count"] += 1
                bad = bad or not v[0].startswith("note:")
                if g["best"] is None or case.size() < g["best"].size():
                    g["best"], g["out"], g["index"] = case, out, i
            st["fail"] += bad
            if (i - a.start + 1) % 50 == 0:
                print(f"  {kind}: {i - a.start + 1}/{per[kind]} cases, {len(groups)} groups so far, "
                      f"{time.monotonic() - t_start:.0f} s", file=sys.stderr, flush=True)

    print(f"\n{'kind':12} {'cases':>6} {'exit0':>6} {'exit2':>6} {'other':>6} {'failed':>6} {'mean s':>7}")
    for k, st in stats.items():
        print(f"{k:12} {st['n']:6d} {st['exit0']:6d} {st['exit2']:6d} {st['other']:6d} {st['fail']:6d} "
              f"{st['time'] / max(st['n'], 1):7.2f}")
    print(f"total {time.monotonic() - t_start:.0f} s\n")
    keys = sorted(groups, key=lambda k: (k[0], k[1], -groups[k]["count"]))
    print(f"{len(keys)} failure group(s):")
    print(f"{'#':>3} {'kind':12} {'class':30} {'n':>4}  message")
    for j, k in enumerate(keys, 1):
        print(f"{j:3d} {k[0]:12} {k[1]:30} {groups[k]['count']:4d}  {k[2][:150]}")
    dump = []
    for j, k in enumerate(keys, 1):
        g = groups[k]
        case, out = g["best"], g["out"]
        if not a.no_shrink and not k[1].startswith(("note:", "timeout")):
            small = shrink(case, k, a.timeout)
            if small is not case:
                case = small
                out = run_isolated(case, a.timeout)
        print(f"\n=== {j}. {k[0]} / {k[1]} ({g['count']} case(s)): {k[2]}")
        print(f"    first seen as case {g['index']} (replay: python tests/fuzz/campaign.py --kind {k[0]} "
              f"--seed {a.seed} --replay {g['index']})")
        print("    " + case.describe().replace("\n", "\n    "))
        print(f"    -> exit {out['how']} {out['code']!r}; stderr: {out['stderr'].strip().splitlines()[-1][:300] if out['stderr'].strip() else ''}")
        for c, m, d in out["violations"]:
            if group_key(k[0], (c, m, d)) == k and d:
                dl = d.strip().splitlines()
                tail = "\n".join(dl[:2] + ["..."] + dl[-2:]) if c == "traceback" and len(dl) > 5 else "\n".join(dl[-6:])
                print("    " + tail.replace("\n", "\n    "))
                break
        if a.save:
            name = re.sub(r"[^A-Za-z0-9_.-]+", "-", f"{j:02d}-{k[0]}-{k[1]}")[:80]
            _save(Path(a.save) / name, case, out, k)
        dump.append({"kind": k[0], "class": k[1], "message": k[2], "count": g["count"], "argv": case.argv,
                     "description": case.describe(), "spec": case.spec, "violations": out["violations"]})
    if a.json:
        Path(a.json).write_text(json.dumps(dump, indent=1, default=str))
    return 1 if any(not k[1].startswith("note:") for k in keys) else 0


if __name__ == "__main__":
    sys.exit(main())
