"""Write k168Nm_v{1100,4300}.csv from the original MATLAB files (not shipped:
k168Nm_v42.mat is 2.6 MB; the tests read it from ../shared/data when there).

The originals hold t (s, 2 kHz) and Fnorm = F / (m g), the spring force over
the slider's weight, with m = 30.7 g; the CSVs hold the spring force itself,
F = Fnorm m g (N), for `lieng diagnose ... --stiffness 168`.

    python data/colas2019/convert.py /path/to/colas2019
"""

import sys
from pathlib import Path

import numpy as np
import scipy.io

M, G = 0.0307, 9.81
src = Path(sys.argv[1] if len(sys.argv) > 1 else "../shared/data/colas2019")
for v in (1100, 4300):
    m = scipy.io.loadmat(src / f"k168Nm_v{v}.mat")
    t, fn = m["t"].ravel(), m["Fnorm"].ravel()
    out = Path(__file__).with_name(f"k168Nm_v{v}.csv")
    with open(out, "w") as fh:
        fh.write("t [s],F [N]\n")
        for a, b in zip(t, fn * M * G):
            fh.write(f"{a:.4f},{b:.7g}\n")
    print(f"wrote {out} ({t.size} rows)")
