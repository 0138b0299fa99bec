"""Time and memory of ``lieng diagnose`` against record length.

Records of 25 000 to 750 000 samples (375 s at 2 kHz), made by repeating a
``lieng synth`` record end to end (its time continued), and the real
paper-on-paper record of 751 281 samples when ../shared/data is beside the
repository; each diagnosed by the command line in a fresh process, which
reports its wall time and peak resident memory.  Target (issue): 750 000
samples in < 60 s and < 1 GB, time linear in length.

    python tests/benchmarks/bench_diagnose_scale.py
"""

import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
V42 = ROOT.parent / "shared" / "data" / "colas2019" / "k168Nm_v42.mat"


def run(args):
    code = ("import resource, sys, time; from lieng.cli import main; t0 = time.perf_counter(); "
            "rc = main(sys.argv[1:]); el = time.perf_counter() - t0; "
            "print(f'{rc} {el:.2f} {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f}')")
    out = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True)
    rc, el, mb = out.stdout.strip().split()[-3:]
    return int(rc), float(el), float(mb)


def main():
    from lieng.analysis.synth import synthesize

    base = synthesize("none", 3, cycles=20)
    dt = float(base.t[1] - base.t[0])
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in (25_000, 100_000, 250_000, 750_000):
            reps = int(np.ceil(n / base.t.size))
            x = np.tile(base.x, reps)[:n]
            t = np.arange(n) * dt
            p = Path(tmp) / f"r{n}.csv"
            np.savetxt(p, np.column_stack([t, x]), delimiter=",", header="t,x", comments="", fmt="%.9g")
            rc, el, mb = run(["diagnose", str(p), "--v0", repr(base.v0), "--fn", repr(base.fn), "-o",
                              str(Path(tmp) / f"o{n}"), "-q", "--no-plots"])
            rows.append((f"synth repeated, {n} samples", rc, el, mb, el / n * 1e6))
        if V42.exists():
            import scipy.io

            m = scipy.io.loadmat(V42)
            p = Path(tmp) / "v42.csv"
            F = m["Fnorm"].ravel() * 0.0307 * 9.81
            np.savetxt(p, np.column_stack([m["t"].ravel(), F]), delimiter=",", header="t [s],F [N]", comments="",
                       fmt="%.7g")
            rc, el, mb = run(["diagnose", str(p), "--stiffness", "168", "--v0", "0.042", "--fn", "11.77", "-o",
                              str(Path(tmp) / "o42"), "-q"])
            rows.append((f"colas2019 v42 (real), {F.size} samples, with plots", rc, el, mb, el / F.size * 1e6))
    print(f"{'record':>52} {'exit':>4} {'wall s':>8} {'peak MB':>8} {'us/sample':>9}")
    for r in rows:
        print(f"{r[0]:>52} {r[1]:>4} {r[2]:>8.2f} {r[3]:>8.0f} {r[4]:>9.1f}")


if __name__ == "__main__":
    main()
