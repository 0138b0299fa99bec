"""Evaluation of ``lieng diagnose`` on records it was not built on.

Every generator in ``tests/generators/`` (written without reading the
diagnosis code: a different friction law, stick handling and noise each)
and ``lieng.analysis.synth`` writes records with one hidden case (five effects and
``none``) and one nuisance (hum, drift, spikes, quantisation, coarse
sampling, ``--fn`` off by 5 %); each is diagnosed as a user would (the
written file and the generator's command-line options, through the same
reader as ``lieng diagnose``).  Printed per generator: the confusion matrix
(true case x primary effect named), the rate of "named with gain >= 0.3" per
effect, the false-alarm rate on effect-free records, and the time per
record.

    python tests/benchmarks/bench_diagnose.py [--seeds 8] [--only lugre,synth] [--cases none,twin_branch]
                                              [--json out.json] [--fn-uncertainty 0.01]
                                              [--nuisances spikes,hum] [--highpass-known]
                                              [--without-fn]
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

HERE = Path(__file__).resolve().parent
GEN_DIR = HERE.parent / "generators"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")


class SynthGen:
    """``lieng synth`` behind the generators' interface, with the nuisances
    applied to its output here (plain NumPy)."""

    NAME = "synth"

    @staticmethod
    def write_record(case, seed, outdir, nuisance="clean"):
        import numpy as np

        from lieng.analysis.synth import synthesize

        rec = synthesize(case, seed)
        g = np.random.default_rng(1000 + seed)
        t, x, y, v0c = rec.t, rec.x.copy(), None if rec.y is None else rec.y.copy(), rec.v0_col
        D = float(np.percentile(x, 98) - np.percentile(x, 2))
        fn_given = rec.fn
        if nuisance == "hum":
            f = g.choice([50.0, 60.0])
            ph = g.uniform(0, 2 * np.pi)
            hum = lambda a: a * (np.sin(2 * np.pi * f * t + ph) + 0.3 * np.sin(4 * np.pi * f * t + 2 * ph))
            x = x + hum(g.uniform(0.01, 0.05) * D)
            if y is not None:
                y = y + hum(g.uniform(0.01, 0.05) * float(np.ptp(y) + 1e-9))
        elif nuisance == "drift":
            x = x + g.uniform(-0.03, 0.03) * D * (t / t[-1])
            if y is not None:
                y = y + g.uniform(-0.05, 0.05) * float(np.mean(np.abs(y))) * (t / t[-1]) ** 2
        elif nuisance == "spikes":
            k = g.choice(t.size, max(1, int(g.uniform(0.0005, 0.005) * t.size)), replace=False)
            x[k] += g.uniform(-0.3, 0.3, k.size) * D
        elif nuisance == "quantisation":
            q = g.uniform(0.002, 0.01) * D
            x = np.round(x / q) * q
        elif nuisance == "coarse":
            step = max(1, int(round((1.0 / (rec.fn * (t[1] - t[0]))) / g.uniform(10, 15))))
            t, x = t[::step], x[::step]
            y = None if y is None else y[::step]
            v0c = None if v0c is None else v0c[::step]
        elif nuisance == "fn_off":
            fn_given = rec.fn * (1.05 if g.uniform() < 0.5 else 0.95)
        cols = {"t": t, "x": x}
        if y is not None:
            cols["y"] = y
        if v0c is not None:
            cols["v0"] = v0c
        path = Path(outdir) / "record.csv"
        np.savetxt(path, np.column_stack(list(cols.values())), delimiter=",", header=",".join(cols), comments="",
                   fmt="%.9g")
        args = ["--fn", repr(fn_given)]
        if v0c is None:
            args += ["--v0", repr(rec.v0)]
        return {"generator": "synth", "case": case, "seed": seed, "nuisance": nuisance, "file": str(path),
                "args": args, "fn_true": rec.fn, "fn_given": fn_given}


def generators(only=None):
    gens = {"synth": SynthGen}
    for f in sorted(GEN_DIR.glob("*.py")):
        if f.name.startswith("_"):
            continue
        spec = importlib.util.spec_from_file_location(f"gen_{f.stem}", f)
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        if hasattr(mod, "write_record"):
            gens[getattr(mod, "NAME", f.stem)] = mod
    if only:
        gens = {k: v for k, v in gens.items() if k in only}
    return gens


def parse_args(args):
    """A generator's options as ``lieng diagnose`` reads them (``--v0`` and
    ``--stiffness`` a number, or a number and its unit: "2.5 N.mm/deg")."""
    from lieng.cli.parser import _quantity

    p = argparse.ArgumentParser()
    p.add_argument("--fn", type=float)
    p.add_argument("--v0", type=_quantity)
    p.add_argument("--stiffness", type=_quantity)
    return p.parse_args(args)


def run_one(truth, fn_uncertainty=None, highpass_known=False):
    """Diagnose one generator record as a user would.  ``fn_uncertainty``:
    a user who measured fn to this relative uncertainty passes it with
    --fn-uncertainty (only where the given fn is in fact that close to the
    generator's true fn; otherwise the default).  ``highpass_known``: a
    user who knows the time constant of an AC-coupled force channel (a
    charge amplifier's, the generator's ``params["tau_ca_s"]``) passes it
    with --highpass."""
    from lieng.diagnose import diagnose, read_record
    from lieng.errors import LiengInputError

    a = parse_args(truth["args"])
    t0 = time.perf_counter()
    try:
        tau = truth.get("params", {}).get("tau_ca_s") if highpass_known else None
        rec = read_record(truth["file"], v0=a.v0, stiffness=a.stiffness, highpass=tau)
        kw = {}
        if fn_uncertainty and a.fn and truth.get("fn_true") and \
                abs(a.fn / truth["fn_true"] - 1.0) <= fn_uncertainty:
            kw["fn_uncertainty"] = fn_uncertainty
        d = diagnose(rec, a.fn, **kw)
        eff, g = d.effect, d.gain
        named = [e["effect"] for e in d.effects]
        err = None
        detail = {"evidence": {k: {q: r.get(q) for q in ("statistic", "null_mean", "null_sd", "se", "z", "p",
                                                          "effect_size", "interval", "named", "withheld", "fn_band", "p_size",
                                                          "size_level")}
                               for k, r in d.evidence.items()},
                  "warnings": d.warnings, "notes": d.notes, "fn_used": d.fn, "fn_source": d.fn_source,
                  "cycles": d.n_cycles,
                  "effects": d.effects, "detected": d.detected, "goodness": d.goodness}
    except LiengInputError as e:
        eff, g, named, err, detail = "error", 0.0, [], str(e), {}
    except Exception as e:  # noqa: BLE001 - a crash is a result here
        eff, g, named, err, detail = "crash", 0.0, [], f"{type(e).__name__}: {e}", {}
    return {"effect": eff, "gain": g if math.isfinite(g) else None, "named": named, "error": err,
            "seconds": time.perf_counter() - t0, "detail": detail}


def table(results, gen):
    rows = [r for r in results if r["generator"] == gen]
    if not rows:
        return f"\n== {gen}: no record selected =="
    cols = list(CASES) + ["unexplained", "no_stick_slip", "too_few_cycles", "friction_drift", "direction_asymmetry", "creep",
                          "error", "crash"]
    used = [c for c in cols if any(r["effect"] == c for r in rows) or c in CASES]
    w = max(len(c) for c in used)
    out = [f"\n== {gen}: confusion matrix (rows: hidden case, columns: primary effect named) =="]
    out.append(" " * 18 + " ".join(f"{c[:w][:10]:>10}" for c in used))
    for case in CASES:
        cnt = Counter(r["effect"] for r in rows if r["case"] == case)
        out.append(f"{case:>18}" + " ".join(f"{cnt.get(c, 0):>10}" for c in used))
    out.append("named with gain >= 0.3:")
    for case in CASES[1:]:
        rs = [r for r in rows if r["case"] == case]
        ok = sum(1 for r in rs if r["effect"] == case and (r["gain"] or 0) >= 0.3)
        out.append(f"  {case:>18}: {ok}/{len(rs)}")
    rs = [r for r in rows if r["case"] == "none"]
    fa = sum(1 for r in rs if r["effect"] not in ("none",))
    out.append(f"  false alarms on none: {fa}/{len(rs)}")
    by_n = Counter()
    bad_n = Counter()
    for r in rows:
        by_n[r["nuisance"]] += 1
        good = (r["case"] == "none" and r["effect"] == "none") or (r["case"] == r["effect"] and (r["gain"] or 0) >= 0.3)
        bad_n[r["nuisance"]] += 0 if good else 1
    out.append("misses by nuisance: " + ", ".join(f"{k} {bad_n[k]}/{by_n[k]}" for k in by_n))
    secs = [r["seconds"] for r in rows]
    out.append(f"time per record: median {sorted(secs)[len(secs) // 2]:.2f} s, max {max(secs):.2f} s")
    return "\n".join(out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--only", default="")
    ap.add_argument("--cases", default="", help="comma-separated subset of the cases (default: all six)")
    ap.add_argument("--nuisances", default="", help="comma-separated subset of the nuisances: only the seeds that "
                    "carry them (seed s carries the nuisance s mod 7 in the order " + ", ".join(NUISANCES) + ")")
    ap.add_argument("--json")
    ap.add_argument("--fn-uncertainty", type=float, default=None,
                    help="pass it with --fn on the records whose given fn is within it of the true fn (what a "
                         "better-measured fn buys)")
    ap.add_argument("--highpass-known", action="store_true",
                    help="pass --highpass with the time constant of a record's AC-coupled force channel where its "
                         "generator states one (params tau_ca_s: a user who knows the charge amplifier's setting)")
    ap.add_argument("--without-fn", action="store_true",
                    help="only the records the generator gives no --fn for (fn estimated from the record; each "
                         "record is still written, to learn its options)")
    a = ap.parse_args(argv)
    cases = [c for c in CASES if not a.cases or c in a.cases.split(",")]
    gens = generators(set(a.only.split(",")) if a.only else None)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for gname, g in gens.items():
            for case in cases:
                for seed in range(a.seeds):
                    nu = NUISANCES[seed % len(NUISANCES)]
                    if a.nuisances and nu not in a.nuisances.split(","):
                        continue
                    d = Path(tmp) / f"{gname}_{case}_{seed}"
                    d.mkdir()
                    try:
                        truth = g.write_record(case, seed, str(d), nu)
                    except Exception as e:  # noqa: BLE001 - the generator's failure, not the diagnosis'
                        print(f"{gname:>12} {case:>17} seed {seed}: generator failed: {type(e).__name__}: {e}",
                              file=sys.stderr, flush=True)
                        continue
                    if a.without_fn and "--fn" in (truth.get("args") or []):
                        continue
                    r = run_one(truth, a.fn_uncertainty, a.highpass_known)
                    r.update(generator=gname, case=case, seed=seed, nuisance=truth.get("nuisance", nu),
                             args=truth.get("args"), fn_true=truth.get("fn_true"))
                    results.append(r)
                    mark = "ok" if (case == "none" and r["effect"] == "none") or \
                        (case == r["effect"] and (r["gain"] or 0) >= 0.3) else "MISS"
                    print(f"{gname:>12} {case:>17} seed {seed} {r['nuisance']:>12} -> {r['effect']:>17} "
                          f"gain {r['gain'] if r['gain'] is None else round(r['gain'], 2)} {mark}"
                          + (f"  [{r['error']}]" if r["error"] else ""), file=sys.stderr, flush=True)
            print(table(results, gname), flush=True)
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
