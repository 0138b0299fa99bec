"""Issue #18, part 2: where does the stable limit cycle shrink as v0 rises?

Ch. 2.4.2.1 d (seed lines 2663-2665) says: "As vo increases the stable
limiting cycle decreases in size while the unstable limiting cycle
increases", until the two coincide at v_oc.  On Fig. 2.21's own shape the
S.L.C. grows instead (docs/claims.md, row 4).  This study sweeps v0 with the
exact return map (`lieng.analysis.cycles.sweep_v0`) over a family of characteristics
of Fig. 2.21's shape (tests/conftest.py: static peak FS = 10 over a stick part
of width 0.5, a falling part to the kinetic minimum FM at sliding speed UM, a
rising part of slope C beyond it) and classifies each shape:

* ``grows to v_oc``: the S.L.C. grows with v0 and merges with the U.L.C. at v_oc
  (Fig. 2.27's topology, but the S.L.C. growing);
* ``shrinks to v_k``: the S.L.C. shrinks while the origin is still unstable
  and vanishes where it turns stable; there is no U.L.C. and no v_oc;
* ``as the thesis``: the S.L.C. shrinks somewhere while a U.L.C. exists;
* ``unresolved``: neither within the scanned v0 (up to 2.5 UM + 10).

The ratio r = C / ((FS - FM) / (UM - 0.5)) is the rising slope over the falling
one.  Run:

    python tests/studies/slc_vs_v0.py
"""

from __future__ import annotations

import sys
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from conftest import thesis_characteristic  # noqa: E402

from lieng import cycles  # noqa: E402

C = (0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0)
UM = (5.0, 20.0, 40.0)
FM = (3.0, 6.0, 9.0)


def classify(c: float, um: float, fm: float) -> tuple[str, float]:
    x, v = thesis_characteristic(v0=10.0, fs=10.0, fm=fm, eps=0.5, um=um, c=c, vmax=300)
    v0s = np.linspace(0.6, 2.5 * um + 10, 60)
    s = cycles.sweep_v0(x, v, v0s, progress=False)
    S = np.array([np.nan if a is None else a for a in s.stable_amplitude])
    U = np.array([np.nan if a is None else a for a in s.unstable_amplitude])
    o = np.array(s.origin_stable)
    dS = np.diff(S)
    r = c / ((10.0 - fm) / (um - 0.5))
    if np.any((dS < 0) & np.isfinite(U[1:]) & np.isfinite(U[:-1])):
        return "as the thesis", r
    if s.v_oc is not None:
        return "grows to v_oc", r
    if np.any((dS < 0) & ~o[1:] & ~o[:-1]) and not np.any(np.isfinite(U)):
        return "shrinks to v_k", r
    return "unresolved", r


def main() -> None:
    rows = []
    for c in C:
        for um in UM:
            for fm in FM:
                kind, r = classify(c, um, fm)
                rows.append((r, kind))
                print(f"C {c:5.2f}  UM {um:4.0f}  FM {fm:3.0f}  r = {r:7.3f}  {kind}", flush=True)
    bins = ((0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, np.inf))
    table = defaultdict(Counter)
    for r, kind in rows:
        b = next(b for b in bins if b[0] <= r < b[1])
        table[b][kind] += 1
    print(f"\n{len(rows)} shapes; by r = rising slope / falling slope:")
    for b in bins:
        print(f"  r in [{b[0]}, {b[1]}): " + ", ".join(f"{k} {n}" for k, n in sorted(table[b].items())))


if __name__ == "__main__":
    main()
