"""The 2-DoF dual-pin-on-disc model of the second seed (``001_...txt``),
reconstructed (its equations (1)-(12) were images and are lost), solved by
the compiled switch-model integrator (``fortran/twodof.f90``), and set
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
           "onedof", "compare", "PAPER", "rpm_to_belt", "write_outputs"]

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


def matrices(p: RigParams, reading=None):
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
             v0: float = rpm_to_belt(0.1), dt: float = 1e-3, nsub: int | None = None, method: str = "exact",
             x0: tuple | None = None, reading: "Reading | None" = None) -> Simulation:
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
    nsub : int, optional
        Sub-steps per output interval: for ``exact``, the event sampling
        (default: enough that the spectral radius of each regime's matrix
        times the sub-step is below 1/2); for ``rk4`` the Runge-Kutta
        sub-steps (default 10).
    method : {"exact", "rk4"}
        ``exact``: each regime is linear, propagated by its matrix exponential
        between switches (events located on the exponential series);
        ``rk4``: the classical Runge-Kutta core (kept as a cross-check).
    x0 : (x1, v1, x2, v2), optional
        The initial state (default Part 1 at rest, the pins on the belt).
    reading : Reading, optional
        Which reading of the paper's lost equations builds M, C, K and the
        normal force (default: :data:`DEFAULT_READING`).

    Returns
    -------
    Simulation
    """
    p = params or RigParams()
    M, C, K, kn = matrices(p, reading)
    s0 = np.array([0.0, 0.0, 0.0, float(v0)]) if x0 is None else np.asarray(x0, float)
    if method == "rk4":
        t, x1, v1, x2, v2, fnorm, ffric, state, nswitch = _run(M, C, K, kn, p, preload, v0, t_end, dt,
                                                             10 if nsub is None else nsub, s0)
    elif method == "exact":
        t, x1, v1, x2, v2, fnorm, ffric, state, nswitch = _run_exact(M, C, K, kn, p, preload, v0, t_end, dt,
                                                                   nsub, s0)
    else:
        raise LiengInputError(f"method {method!r}: 'exact' or 'rk4'")
    return Simulation(t, x1, x2, v1, v2, np.degrees(x1 / p.r1), fnorm, ffric, state, nswitch, p,
                      float(preload), float(v0))


def _check_run(preload, v0, t_end, dt):
    for name, val in (("t_end", t_end), ("preload", preload), ("v0", v0), ("dt", dt)):
        if not (math.isfinite(val) and val > 0):
            raise LiengInputError(f"--{name.replace('_', '-')} {val}: must be a positive number")
    n = int(round(t_end / dt)) + 1
    if n > 20_000_000:
        raise LiengInputError(f"t_end / dt = {n}: too many samples (at most 2e7)")
    return n


def _run(M, C, K, kn, p, preload, v0, t_end, dt, nsub, s0):
    """Check the run's numbers and call the Runge-Kutta core; returns t and
    the core's series."""
    n = _check_run(preload, v0, t_end, dt)
    if not 1 <= nsub <= 10000:
        raise LiengInputError(f"nsub = {nsub} must be 1..10000")
    out = _core.core_twodof(n, dt, nsub, M, C, K, float(preload), kn, p.mus, p.muk, float(v0), p.eta, s0)
    x1, v1, x2, v2, fnorm, ffric, state, nswitch, status = out
    if status != st.OK:
        raise LiengInputError(f"the integration failed ({st.name(status)}): check the parameters")
    return np.arange(n) * dt, x1, v1, x2, v2, fnorm, ffric, state.astype(bool), int(nswitch)


#: order of the exponential series for part-steps and event polynomials (the sub-step keeps the
#: spectral radius times the step below 1/2: the truncation is below 1e-25)
KORD = 20


def regime_matrices(M, C, K, kn, preload, mus, muk, v0, isl=1):
    """The three linear regimes of the switch model for M q'' + C q' + K q =
    e_isl Ff, N = Fn + kn q_isl, in the augmented state z = (q, q', 1):
    A[0] stick (q_isl' = v0 held; the other DoFs free), A[1] slip with the
    friction forward (Ff = +muk N), A[2] slip backward.  Returns A, the
    holding-force row (Ff = hold . z in stick), the normal-force row and the
    event rows: stick mus N - Ff and mus N + Ff, slip +(v0 - q_isl'),
    slip -(q_isl' - v0)."""
    M, C, K = (np.asarray(X, float) for X in (M, C, K))
    nd = M.shape[0]
    nz = 2 * nd + 1
    kn_vec = np.atleast_1d(np.asarray(kn, float))
    nq = np.zeros(nd)
    if kn_vec.size == 1:
        nq[isl] = kn_vec[0]
    else:
        nq[:] = kn_vec
    nrow = np.concatenate([nq, np.zeros(nd), [float(preload)]])
    A = np.zeros((3, nz, nz))
    Minv = np.linalg.inv(M)
    e = np.zeros(nd)
    e[isl] = 1.0
    for r, d in ((1, 1.0), (2, -1.0)):
        Keff = K - d * muk * np.outer(e, nq)
        f = d * muk * preload * e
        A[r, :nd, nd:2 * nd] = np.eye(nd)
        A[r, nd:2 * nd, :nd] = -Minv @ Keff
        A[r, nd:2 * nd, nd:2 * nd] = -Minv @ C
        A[r, nd:2 * nd, -1] = Minv @ f
    # stick: the free DoFs obey their rows with q_isl'' = 0; the holding force closes the pins' row
    fr = [i for i in range(nd) if i != isl]
    A[0, :nd, nd:2 * nd] = np.eye(nd)
    hold = np.zeros(nz)
    if fr:
        Mff = M[np.ix_(fr, fr)]
        rows = -np.linalg.solve(Mff, np.hstack([K[fr], C[fr]]))        # q_f'' = rows . (q, q')
        for j, i in enumerate(fr):
            A[0, nd + i, :2 * nd] = rows[j]
        acc = np.zeros((nd, 2 * nd))
        acc[fr] = rows
        hold[:2 * nd] = M[isl] @ acc + np.concatenate([K[isl], C[isl]])
    else:
        hold[:2 * nd] = np.concatenate([K[isl], C[isl]])
    ev = np.zeros((3, 2, nz))
    ev[0, 0] = mus * nrow - hold
    ev[0, 1] = mus * nrow + hold
    ev[1, 0, nd + isl], ev[1, 0, -1] = -1.0, v0
    ev[2, 0, nd + isl], ev[2, 0, -1] = 1.0, -v0
    return A, hold, nrow, ev


def _run_exact(M, C, K, kn, p, preload, v0, t_end, dt, nsub, s0, isl=1):
    """The exact propagation: expm of each regime's matrix over the sub-step,
    the event polynomials, and the compiled stepping; returns t and the series
    as ``_run`` does (the forces evaluated from the state)."""
    from scipy.linalg import expm

    n = _check_run(preload, v0, t_end, dt)
    A, hold, nrow, ev = regime_matrices(M, C, K, kn, preload, p.mus, p.muk, v0, isl)
    nz = A.shape[1]
    rad = max(float(np.max(np.abs(np.linalg.eigvals(a)))) for a in A)
    if nsub is None:
        nsub = max(1, int(math.ceil(rad * dt / 0.5)))
    if not 1 <= nsub <= 10000:
        raise LiengInputError(f"nsub = {nsub} must be 1..10000")
    h = dt / nsub
    phi = np.stack([expm(a * h) for a in A])
    coef = np.zeros((KORD + 1, nz, 2, 3))
    for r in range(3):
        for e_ in range(2 if r == 0 else 1):
            row = ev[r, e_].copy()
            for k in range(KORD + 1):
                coef[k, :, e_, r] = row
                row = row @ A[r] / (k + 1)
    nd = (nz - 1) // 2
    z0 = np.zeros(nz)
    z0[-1] = 1.0
    # s0 = (x1, v1, x2, v2) for two DoFs; (q, q') for more
    if nd == 2:
        z0[[0, 2, 1, 3]] = s0
    else:
        z0[:2 * nd] = s0
    out = _core.core_twodof_exact(n, nsub, h, np.asfortranarray(A.transpose(1, 2, 0)),
                                  np.asfortranarray(phi.transpose(1, 2, 0)), np.asfortranarray(coef),
                                  np.array([2, 1, 1], np.int32), nd + isl + 1, float(v0), p.eta, p.mus, hold,
                                  nrow, z0)
    z, state, nswitch, status = out
    if status != st.OK:
        raise LiengInputError(f"the integration failed ({st.name(status)}): check the parameters")
    stick = state == 1
    fnorm = np.maximum(nrow @ z, 0.0)
    ffric = np.where(stick, hold @ z, np.where(state == 2, 1.0, -1.0) * p.muk * fnorm)
    t = np.arange(n) * dt
    if nd == 2:
        return t, z[0], z[2], z[1], z[3], fnorm, ffric, stick, int(nswitch)
    return t, z, fnorm, ffric, stick, int(nswitch)


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
    t, _, _, x2, v2, fnorm, ffric, state, nswitch = _run_exact(M, C, K, kn, p, preload, v0,
                                                               kw.pop("t_end", 600.0), kw.pop("dt", 1e-3),
                                                               kw.pop("nsub", None), np.array([0.0, 0.0, 0.0, v0]))
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


def compare(preload: float = 80.0, rpm: float = 0.1, t_end: float = 600.0, params: RigParams | None = None,
            keep: dict | None = None, belt: float | None = None) -> dict:
    """``lieng twodof``'s JSON: modal frequencies, the 2-DoF metrics, the
    1-DoF (constant load) and load-corrected 1-DoF metrics, the re-identified
    k2 and the paper's Table 3/4 values.  muk is the paper's for 80 N (0.17)
    and 100 N (0.19), interpolated linearly in the preload between them.
    The belt moves at 0.1 rpm at r2 = 0.08 m (8.38e-4 m/s, sec. 4.3) unless
    ``belt`` (m/s) is given."""
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
    if keep is not None:
        keep.update({"2-DoF": s2, "1-DoF": s1, "1-DoF C_N": sc})
    return out


def write_outputs(res: dict, sims: dict, outdir) -> None:
    """Plots (angle, forces, spectrum: 2-DoF beside 1-DoF, the paper's values
    marked) and ``twodof.json`` into ``outdir``."""
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
    two, one = sims["2-DoF"], sims["1-DoF"]
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
