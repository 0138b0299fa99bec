"""The 2-DoF dual-pin-on-disc model of the second seed (``001_...txt``),
reconstructed (its equations (1)-(12) were images and are lost), solved by
the compiled switch-model integrator (``fortran/modern/twodof.f90``), and set
beside the thesis's 1-DoF model of the same rig.

The reconstruction, each term traced to the seed's sentences, is in
``python/lieng/twodof.md``.  In short, with x1 = r1*theta1 (Part 1 at the
tensile spring's lever), x2 the pins' tangential displacement and
rho = r2/r1:

    M = [[m1 + m2 rho^2/3, m2 rho/6], [m2 rho/6, m2/3]]        (App.: Part 2 a rigid rod,
                                                               linear velocity distribution)
    K = [[k1 + rho^2 k2, -rho k2], [-rho k2, k2 + k3 cos^2 a]]
    C = [[c1 + rho^2 c2, -rho c2], [-rho c2, c2 + c3 cos^2 a]]
    N = Fn + k3 sin a cos a x2                                 (the inclined spring k3)
    slip: Ff = muk N sign(v0 - x2'),  stick: x2' = v0 while |Ff| <= mus N.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace

import numpy as np

from lieng import _core
from lieng.errors import LiengInputError
from lieng import status as st

__all__ = ["RigParams", "matrices", "modal_frequencies", "identify_k2", "simulate", "Simulation", "metrics",
           "onedof", "compare", "Comparison", "PAPER", "rpm_to_belt", "write_outputs"]

#: The paper's Tables 3 and 4 (experiment, theory) at 0.1 rpm: peak angle of
#: Part 1 (deg), amplitude of its fluctuation (deg), dominant frequency (Hz).
#: Table 3's body swaps the fluctuation values against the text (sec. 4.3:
#: experiment 0.84, theory 0.79); the text's values are used.
PAPER = {
    80.0: {"experiment": {"peak_deg": 7.87, "fluct_deg": 0.84, "dominant_hz": 0.70},
           "theory": {"peak_deg": 8.86, "fluct_deg": 0.79, "dominant_hz": 0.68},
           "muk": 0.17},
    100.0: {"experiment": {"peak_deg": 9.82, "fluct_deg": 0.90, "dominant_hz": 0.65},
            "theory": {"peak_deg": 11.57, "fluct_deg": 0.96, "dominant_hz": 0.64},
            "muk": 0.19},
}
#: measured modal frequencies (Hz): the lever (tangential) and the pin (normal)
MEASURED_MODES = (0.61, 19.53)


def rpm_to_belt(rpm: float, radius: float = 0.08) -> float:
    """Belt velocity (m/s) of the disc at ``rpm`` and ``radius`` (m): 0.1 rpm
    at r2 = 0.08 m is 8.38e-4 m/s, the paper's simulation value."""
    return rpm * 2.0 * math.pi / 60.0 * radius


@dataclass(frozen=True)
class RigParams:
    """Table 2 of the seed (SI units)."""

    J1: float = 0.75          # kg m^2, Part 1 about the axle
    m1: float = 10.52         # kg, its equivalent mass at the lever (the paper's value; J1/r1^2 = 10.29)
    m2: float = 1.10          # kg, Parts 2 and 3 (both pins)
    k1: float = 165.5         # N/m, tensile spring
    k2: float = 10.7e3        # N/m, Part 1 - pins
    k3: float = 800.0         # N/m, inclined spring
    k4: float = 26.2e3        # N/m, ground spring (sets the preload; not a DoF here)
    alpha: float = math.pi / 3
    c1: float = 0.02
    c2: float = 0.01
    c3: float = 0.01
    r1: float = 0.27          # m, lever of the tensile spring
    r2: float = 0.08          # m, pins
    mus: float = 0.28
    muk: float = 0.17
    eta: float = 1e-10        # m/s, Leine's band
    rod: bool = True          # Part 2 as the appendix's rod (False: a point mass)

    def to_json(self) -> dict:
        return asdict(self)


def matrices(p: RigParams):
    """M, C, K (2x2) and kn, the normal force per metre of x2."""
    rho = p.r2 / p.r1
    if p.rod:
        M = np.array([[p.m1 + p.m2 * rho ** 2 / 3, p.m2 * rho / 6], [p.m2 * rho / 6, p.m2 / 3]])
    else:
        M = np.array([[p.m1, 0.0], [0.0, p.m2]])
    ca, sa = math.cos(p.alpha), math.sin(p.alpha)
    K = np.array([[p.k1 + rho ** 2 * p.k2, -rho * p.k2], [-rho * p.k2, p.k2 + p.k3 * ca * ca]])
    C = np.array([[p.c1 + rho ** 2 * p.c2, -rho * p.c2], [-rho * p.c2, p.c2 + p.c3 * ca * ca]])
    return M, C, K, p.k3 * sa * ca


def modal_frequencies(p: RigParams) -> np.ndarray:
    """Undamped natural frequencies (Hz) without contact (the pins off the disc)."""
    from scipy.linalg import eigh

    M, _, K, _ = matrices(p)
    return np.sqrt(eigh(K, M, eigvals_only=True)) / (2 * math.pi)


def identify_k2(p: RigParams, targets=MEASURED_MODES) -> tuple[float, np.ndarray]:
    """k2 re-identified from the measured 0.61 Hz and 19.53 Hz as the paper
    did: the k2 whose modal frequencies are closest to both (least squares in
    log frequency).  Returns k2 and the frequencies it gives."""
    from scipy.optimize import minimize_scalar

    tg = np.log(np.asarray(targets, float))

    def err(lk):
        return float(np.sum((np.log(modal_frequencies(replace(p, k2=math.exp(lk)))) - tg) ** 2))

    r = minimize_scalar(err, bounds=(math.log(1e2), math.log(1e6)), method="bounded",
                        options={"xatol": 1e-10})
    k2 = math.exp(r.x)
    return k2, modal_frequencies(replace(p, k2=k2))


@dataclass
class Simulation:
    """Time series of a run (SI units; angle in degrees)."""

    t: np.ndarray
    x1: np.ndarray
    x2: np.ndarray
    v1: np.ndarray
    v2: np.ndarray
    theta_deg: np.ndarray
    normal: np.ndarray
    friction: np.ndarray
    stick: np.ndarray
    nswitch: int
    params: RigParams
    preload: float
    v0: float


def simulate(params: RigParams | None = None, t_end: float = 600.0, preload: float = 80.0,
             v0: float = rpm_to_belt(0.1), dt: float = 1e-3, nsub: int = 10) -> Simulation:
    """Integrate the 2-DoF model with the switch model (compiled core).

    Parameters
    ----------
    params : RigParams, optional
        Table 2 by default.
    t_end : float
        Duration (s); the paper's tests last 600 s.
    preload : float
        Fn, the total normal preload of both pins (N).
    v0 : float
        Belt velocity (m/s).
    dt : float
        Output interval (s).
    nsub : int
        Runge-Kutta sub-steps per output interval.

    Returns
    -------
    Simulation
        Part 1 at rest and the pins stuck to the belt (x2' = v0) at t = 0.
    """
    p = params or RigParams()
    M, C, K, kn = matrices(p)
    t, x1, v1, x2, v2, fnorm, ffric, state, nswitch = _run(M, C, K, kn, p, preload, v0, t_end, dt, nsub)
    return Simulation(t, x1, x2, v1, v2, np.degrees(x1 / p.r1), fnorm, ffric, state, nswitch, p,
                      float(preload), float(v0))


def _run(M, C, K, kn, p, preload, v0, t_end, dt, nsub):
    """Check the run's numbers and call the compiled core from Part 1 at rest
    and the pins on the belt; returns t and the core's series."""
    for name, val in (("t_end", t_end), ("preload", preload), ("v0", v0), ("dt", dt)):
        if not (math.isfinite(val) and val > 0):
            raise LiengInputError(f"--{name.replace('_', '-')} {val}: must be a positive number")
    n = int(round(t_end / dt)) + 1
    if n > 20_000_000:
        raise LiengInputError(f"t_end / dt = {n}: too many samples (at most 2e7)")
    if not 1 <= nsub <= 10000:
        raise LiengInputError(f"nsub = {nsub} must be 1..10000")
    out = _core.core_twodof(n, dt, nsub, M, C, K, float(preload), kn, p.mus, p.muk, float(v0), p.eta,
                            np.array([0.0, 0.0, 0.0, float(v0)]))
    x1, v1, x2, v2, fnorm, ffric, state, nswitch, status = out
    if status != st.OK:
        raise LiengInputError(f"the integration failed ({st.name(status)}): check the parameters")
    return np.arange(n) * dt, x1, v1, x2, v2, fnorm, ffric, state.astype(bool), int(nswitch)


def onedof(params: RigParams | None = None, load_correction: bool = False, **kw) -> Simulation:
    """The same rig as the thesis's 1-DoF model: the pins rigid on Part 1
    (k2 -> infinity: x2 = rho x1), one mass, and a constant normal force;
    with ``load_correction`` the thesis's remedy (ch. 2.4.1.1): the friction
    scaled by C_N(t) = N(t)/Fn with N from the rig's law N = Fn + kn x2."""
    p = params or RigParams()
    rho = p.r2 / p.r1
    # one DoF in x2 = rho x1: the 2-DoF matrices referred to the pins (q = (1/rho, 1) . x2)
    M2, C2, K2, kn2 = matrices(p)
    q = np.array([1.0 / rho, 1.0])
    m_eq, c_eq, k_eq = float(q @ M2 @ q), float(q @ C2 @ q), float(q @ K2 @ q)
    kn = kn2 if load_correction else 0.0
    # a 2x2 system with a negligible second mass carried rigidly: solve as diagonal with a dummy DoF
    M = np.array([[1.0, 0.0], [0.0, m_eq]])
    K = np.array([[1.0, 0.0], [0.0, k_eq]])
    C = np.array([[0.0, 0.0], [0.0, c_eq]])
    preload = kw.pop("preload", 80.0)
    v0 = kw.pop("v0", rpm_to_belt(0.1))
    t, _, _, x2, v2, fnorm, ffric, state, nswitch = _run(M, C, K, kn, p, preload, v0, kw.pop("t_end", 600.0),
                                                         kw.pop("dt", 1e-3), kw.pop("nsub", 10))
    x1 = x2 / rho
    return Simulation(t, x1, x2, v2 / rho, v2, np.degrees(x1 / p.r1), fnorm, ffric, state, nswitch, p,
                      float(preload), float(v0))


#: the shortest run the metrics can read (s): the steady state is its last half, and the dominant
#: frequency is searched above 0.05 Hz, which that half must resolve
T_END_MIN = 40.0
#: the longest run the command line makes (s): an hour of rig time, 3.6e6 samples of 1 ms
T_END_MAX = 3600.0


def _dominant(sig, dt, fmin=0.05):
    s = sig - sig.mean()
    w = np.hanning(s.size)
    a = np.abs(np.fft.rfft(s * w))
    f = np.fft.rfftfreq(s.size, dt)
    ok = f >= fmin
    return float(f[ok][np.argmax(a[ok])])


def metrics(sim: Simulation, steady_from: float = 0.5) -> dict:
    """Table 3/4's quantities: the peak angle of Part 1 (its maximum over
    the run, deg), the amplitude of its steady-state fluctuation (half the
    median peak-to-peak range over windows of the dominant period, deg, on
    the last half), the dominant FFT frequency of the angle there (Hz, above
    0.05 Hz), and the normal force's mean and standard deviation there (N)."""
    t, th = sim.t, sim.theta_deg
    dt = float(t[1] - t[0])
    i0 = int(steady_from * t.size)
    ss = th[i0:]
    f = _dominant(ss, dt)
    per = max(int(round(1.0 / f / dt)), 2)
    ptp = [np.ptp(ss[j:j + per]) for j in range(0, ss.size - per + 1, per)]
    nf = sim.normal[i0:]
    return {"peak_deg": float(th.max()), "fluct_deg": 0.5 * float(np.median(ptp) if ptp else np.ptp(ss)),
            "dominant_hz": f, "normal_force": {"mean": float(nf.mean()), "std": float(nf.std())}}


class Comparison(dict):
    """:func:`compare`'s result: the JSON summary (this dict) and the three simulations it was measured on,
    which the plots of :func:`write_outputs` draw.

    Attributes
    ----------
    simulations : dict
        ``{"2-DoF": ..., "1-DoF": ..., "1-DoF C_N": ...}``: :func:`simulate`'s and :func:`onedof`'s results.
    """

    def __init__(self, summary: dict, simulations: dict):
        super().__init__(summary)
        self.simulations = simulations


def compare(preload: float = 80.0, rpm: float = 0.1, t_end: float = 600.0, params: RigParams | None = None,
            belt: float | None = None) -> Comparison:
    """``lieng twodof``'s JSON: modal frequencies, the 2-DoF metrics, the
    1-DoF (constant load) and load-corrected 1-DoF metrics, the re-identified
    k2 and the paper's Table 3/4 values.  muk is the paper's for 80 N (0.17)
    and 100 N (0.19), interpolated linearly in the preload between them.
    The belt moves at 0.1 rpm at r2 = 0.08 m (8.38e-4 m/s, sec. 4.3) unless
    ``belt`` (m/s) is given.  The result (a dict) also carries the
    simulations (:class:`Comparison`)."""
    p = params or RigParams()
    if params is None:
        muk = float(np.interp(preload, [80.0, 100.0], [PAPER[80.0]["muk"], PAPER[100.0]["muk"]]))
        p = replace(p, muk=muk)
    v0 = rpm_to_belt(rpm) if belt is None else float(belt)
    s2 = simulate(p, t_end=t_end, preload=preload, v0=v0)
    s1 = onedof(p, t_end=t_end, preload=preload, v0=v0)
    sc = onedof(p, load_correction=True, t_end=t_end, preload=preload, v0=v0)
    k2, fk2 = identify_k2(p)
    out = {"modal_hz": [float(f) for f in modal_frequencies(p)], **metrics(s2), "onedof": metrics(s1),
           "onedof_load_corrected": metrics(sc),
           "k2_identified": {"k2": k2, "modal_hz": [float(f) for f in fk2], "table2_k2": p.k2},
           "preload_n": float(preload), "rpm": float(rpm), "belt_m_s": v0, "params": p.to_json()}
    if float(preload) in PAPER:
        out["paper"] = {k: PAPER[float(preload)][k] for k in ("experiment", "theory")}
    return Comparison(out, {"2-DoF": s2, "1-DoF": s1, "1-DoF C_N": sc})


def write_outputs(res: Comparison, outdir) -> None:
    """Plots (angle, forces, spectrum: 2-DoF beside 1-DoF, the paper's values
    marked) and ``twodof.json`` into ``outdir``, from :func:`compare`'s result."""
    from lieng.io.outputs import dumps_json
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from lieng.programs.graf import finish

    out = Path(outdir)
    (out / "twodof.json").write_text(dumps_json(res, indent=2) + "\n", encoding="utf-8")
    cap = (f"lieng twodof: dual-pin-on-disc rig (seed 001), Fn = {res['preload_n']:g} N, {res['rpm']:g} rpm; "
           f"2-DoF reconstruction vs the thesis's 1-DoF model (constant load)")
    two, one = res.simulations["2-DoF"], res.simulations["1-DoF"]
    fig, ax = plt.subplots(2, 1, figsize=(10, 7), dpi=110)
    for lab, s, kw in (("2-DoF", two, {"color": "C0"}), ("1-DoF (constant N)", one, {"color": "C1"})):
        ax[0].plot(s.t, s.theta_deg, lw=0.5, label=lab, **kw)
        w = (s.t > s.t[-1] - 20)
        ax[1].plot(s.t[w], s.theta_deg[w], lw=0.8, label=lab, **kw)
    pap = res.get("paper")
    if pap:
        ax[0].axhline(pap["experiment"]["peak_deg"], color="k", ls=":", lw=0.8, label="paper: measured peak")
        ax[0].axhline(pap["theory"]["peak_deg"], color="0.5", ls="--", lw=0.8, label="paper: its theory's peak")
    ax[0].set_ylabel("angle of Part 1 (deg)")
    ax[1].set_xlabel("time (s)")
    ax[1].set_ylabel("angle of Part 1 (deg)")
    ax[1].set_title("last 20 s", fontsize=9)
    finish(fig, list(ax), cap, out / "angle.png")
    fig, ax = plt.subplots(figsize=(10, 4.8), dpi=110)
    w = (two.t > two.t[-1] - 20)
    ax.plot(two.t[w], two.normal[w], label="2-DoF normal force N")
    ax.plot(two.t[w], two.friction[w], label="2-DoF friction force")
    ax.plot(one.t[w], one.friction[w], label="1-DoF friction force", alpha=0.7)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("force on both pins (N)")
    finish(fig, ax, cap, out / "forces.png")
    fig, ax = plt.subplots(figsize=(9, 4.8), dpi=110)
    for lab, s in (("2-DoF", two), ("1-DoF", one)):
        i0 = s.t.size // 2
        th = s.theta_deg[i0:] - s.theta_deg[i0:].mean()
        f = np.fft.rfftfreq(th.size, float(s.t[1] - s.t[0]))
        a = 2 * np.abs(np.fft.rfft(th * np.hanning(th.size))) / np.hanning(th.size).sum()
        ax.semilogy(f[(f > 0) & (f < 5)], a[(f > 0) & (f < 5)] + 1e-9, lw=0.7, label=lab)
    for fm in (0.7, 0.9, 1.1):
        ax.axvline(fm, color="k", ls=":", lw=0.8)
    ax.set_xlabel("frequency (Hz) — dotted: the paper's measured 0.7, 0.9, 1.1 Hz")
    ax.set_ylabel("amplitude of the angle (deg)")
    finish(fig, ax, cap, out / "spectrum.png")
