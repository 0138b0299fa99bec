"""crank_srv: stick-slip records of a crank-driven (Scotch-yoke) reciprocating tribometer, SRV-like.

Rig: the yoke's position is sinusoidal, p = A sin(theta), theta' = 2 pi f_c (stroke 2A 1-10 mm, fn/f_c 30-60),
so the drive velocity is never constant: it reverses twice per crank turn, through zero at the stroke ends.
The pin holder (mass m) hangs on the yoke through the measuring spring k (fn 20-300 Hz); it slides on a fixed
flat. Each stroke: a long stick through the reversal (the spring unloads and reloads the other way), then
2-5 slips in the part of the stroke where the yoke is fast. 4-12 strokes, 10-60 slips.

Friction law (own): arctan weakening in log speed on a Coulomb level plus a weak viscous term,
    F = sgn(v) N [mu_k + D (1/2 - atan(ln(|v|/v_s)/w)/pi)] + eta v,
mu(0+) = mu_k + D (D 8-20 % of mu_k), the static level mu_s = mu(0+) (1 + r_s), r_s 0.10-0.30, the same in
both directions. Stick handling: exact stick; the pin stays put while the needed force k (p - x) is within
the static level, breaks away in the direction of that force, arrests when its speed would change sign
(the crossing located within the step). Integrator: own fixed-step semi-implicit (symplectic) Euler,
h = Tn/250..Tn/325, the friction taken at the step's start speed, the viscous term implicit.

Departures: load_variation = the flat under the pin is tilted (even seeds, c of either sign) or wavy (odd)
along the pin's position x; twin_branch = a transfer-film (ploughing debris) state q built by the slip
distance (dq/dx = (1 - q)/Dc), wiped in stick (tau 0.3-0.6 Tn), friction x (1 + g q), g calibrated on a
pilot; static_ageing = mu_s (1 + beta ln(1 + t_stick/tau)), the crank frequency stepping 4-8x between strokes
(even seeds) or the crank stopping 5-50 Tn at some stroke ends (odd), beta calibrated on a pilot;
triggering = a normal-load vibration a_t N0 sin(2 pi f_t t), 3.5-7 %, 2.6-7.5 fn, f_t redrawn until the
record's f_t/f_ss is >= 0.15 from an integer; drive_modulation = the crank speed itself,
theta' = 2 pi f_c (1 + a sin(2 pi fm t + phi)), a 0.22-0.43, fm/f_ss 0.15-0.45 (shows in the recorded position).

Records: SRV-style export (metadata block, then TAB table `Time [s]  Friction force [N]  Normal force [N]
Stroke position [mm]`), a comma CSV `time (ms), Ff (mN), Fn (N), x_drive (um)` or a whitespace `.dat` with a
units row; force (`--stiffness`) or the spring's extension `deflection [mm]` = F/k with an affine normal
reading (mm); the drive position column always; white noise, 20-100 samples per period. `--fn` on 7 of 8
seeds (8 of 8 for triggering).

Measured on the ground truth by _selfcheck (seeds 0-7 of each case, nuisance NUISANCES[seed % 7]; each
record's own sizes are in params["measured"]; all 48 records in 4.3 s together):
- none: the law at the contact is exactly single-valued (decelerating minus accelerating at equal speed,
  10-90 % of each slip's peak speed: |twin| < 1e-4 of the drop); a 1-DoF reading of the clean sampled force
  (x = p - F/k, central differences, F - m x'') reads -5.6..-1.3 % (-5.6..-4.8 % at 25-29 samples/period, the
  static-kinetic kink smeared by the differencing; -1.9..-1.3 % at 50-62). Peak sd 0.03-0.08 % of the drop;
  no ageing: the peak changes -0.01..+0.04 % of the drop across sticks 5.5-9.2x apart (the reversal sticks
  are the long ones). Load constant, drive an exact sinusoid. 14-32 slips, fn/f_ss 5.4-11.6.
- load_variation: N p-p 21.7-34.8 % of N0; F against v reads -0.1..+15.9 % of the drop as a twin (the load
  moves during the slip), peaks scatter 4-30 % of the drop. 12-28 slips.
- twin_branch: +13.1..+22.3 % of the drop at the contact (+10.4..+18.7 % in the 1-DoF reading).
- static_ageing: peak growth +7.7..+12.6 % of the drop over sticks 19-50x apart (the law's twin 0).
- triggering: a_t 3.9-6.8 % (N p-p 7.7-13.5 %), f_t 2.6-7.0 fn, f_t/f_ss 20.7-43.7, >= 0.15 from an
  integer; the shaker moves F against v by +0.2..+11.4 % of the drop.
- drive_modulation: fm/f_ss 0.19-0.43, a 0.22-0.43 (twin 0, no ageing).
"""
import math
import os

import numpy as np

NAME = "crank_srv"
CASES = ("none", "load_variation", "twin_branch", "static_ageing", "triggering", "drive_modulation")
NUISANCES = ("clean", "hum", "drift", "spikes", "quantisation", "coarse", "fn_off")


# ----------------------------------------------------------------------------------------------- simulation
def _simulate(P, p, h, dep):
    """Fixed-step semi-implicit Euler with exact stick. Returns fine-grid arrays and the slip list."""
    k, m, N0 = P["k"], P["m"], P["N0"]
    mu_k, D, vs, w, eta, mu_s0 = P["mu_k"], P["D"], P["vs"], P["w"], P["eta"], P["mu_s0"]
    load = dep.get("load")
    trig = dep.get("trig")
    twin = dep.get("twin")
    age = dep.get("age")
    g, Dc, tau_r = twin if twin else (0.0, 1.0, 1.0)
    beta, tau_a = age if age else (0.0, 1.0)
    dec_r = math.exp(-h / tau_r)
    pl = p.tolist()
    n = len(pl)
    X = [0.0] * n; V = [0.0] * n; FR = [0.0] * n; NN = [0.0] * n; FS = [0.0] * n
    x = P["x0"]; v = 0.0; stuck = True; t_st = 0.0; q = 0.0; s = 1.0
    slips = []; cur = None
    hm = h / m; den = 1.0 + h * eta / m
    log, atan, sin, pi = math.log, math.atan, math.sin, math.pi
    for i in range(n):
        N = N0
        if load is not None:
            if load[0] == "tilt":
                N = N0 * (1.0 + load[1] * (x - load[2]))
            else:
                N = N0 * (1.0 + load[1] * sin(load[2] * x + load[3]))
        if trig is not None:
            N *= 1.0 + trig[0] * sin(2 * pi * trig[1] * i * h)
        fsp = k * (pl[i] - x)
        if stuck:
            Fs = mu_s0 * N * (1.0 + beta * log(1.0 + t_st / tau_a))
            if abs(fsp) > Fs:
                stuck = False
                s = 1.0 if fsp > 0 else -1.0
                cur = [i, None, s, abs(fsp), t_st, fsp]
            else:
                t_st += h
                q *= dec_r
                X[i] = x; V[i] = 0.0; FR[i] = fsp; NN[i] = N; FS[i] = fsp
                continue
        av = abs(v)
        W = 1.0 if av <= 0.0 else 0.5 - atan(log(av / vs) / w) / pi
        ff = N * (mu_k + D * W) * (1.0 + g * q)
        X[i] = x; V[i] = v; FR[i] = s * ff + eta * v; NN[i] = N; FS[i] = fsp
        v1 = (v + hm * (fsp - s * ff)) / den
        if v1 * s <= 0.0:
            frac = v / (v - v1) if v != v1 else 0.0
            x += 0.5 * h * v * frac
            v = 0.0; stuck = True; t_st = (1.0 - frac) * h
            cur[1] = i + 1
            slips.append(cur); cur = None
        else:
            x += h * v1
            v = v1
            if twin:
                q += h * abs(v1) / Dc * (1.0 - q)
    A = dict(x=np.array(X), v=np.array(V), fr=np.array(FR), N=np.array(NN), fsp=np.array(FS))
    out = []
    for (i0, i1, s, peak, tst, f0) in slips:
        if i1 >= n:
            continue
        f1 = A["fsp"][i1]
        out.append(dict(i0=i0, i1=i1, s=s, peak=peak, t_stick=tst, drop=s * (f0 - f1)))
    return A, out


def _twin(v, fr, slips, drop_ref=None):
    """Median over slips of (decelerating - accelerating) friction at equal speed, 10-90 % of the peak speed."""
    vals = []
    for sl in slips:
        i0, i1, s = sl["i0"], sl["i1"], sl["s"]
        if i1 - i0 < 7:
            continue
        u = s * v[i0:i1]; f = s * fr[i0:i1]
        j = int(np.argmax(u)); um = u[j]
        if j < 4 or len(u) - j < 4 or um <= 0:
            continue
        ua, fa = u[:j + 1], f[:j + 1]
        ud, fd = u[j:][::-1], f[j:][::-1]
        oa, od = np.argsort(ua), np.argsort(ud)
        grid = np.linspace(0.1, 0.9, 17) * um
        d = np.interp(grid, ud[od], fd[od]) - np.interp(grid, ua[oa], fa[oa])
        vals.append(float(np.mean(d)) / (drop_ref or sl["drop"]))
    return float(np.median(vals)) if vals else float("nan")


def _growth(slips, drop):
    """Peak growth over the record's range of stick times (regression on ln t_stick), fraction of the drop."""
    t = np.array([s["t_stick"] for s in slips]); pk = np.array([s["peak"] for s in slips])
    ok = t > 0
    t, pk = t[ok], pk[ok]
    if len(t) < 4 or t.max() / t.min() < 1.2:
        return 0.0, float(t.max() / t.min()) if len(t) else 1.0
    lt = np.log(t)
    b = np.polyfit(lt, pk, 1)[0]
    return float(b * (lt.max() - lt.min()) / drop), float(t.max() / t.min())


# ----------------------------------------------------------------------------------------------- drives
def _drive_strokes(strokes, h, theta0=-math.pi / 2):
    """strokes: list of (f_c, hold_before_s). Constant crank speed within a stroke; holds at stroke ends."""
    parts = []; th = theta0
    for f, hold in strokes:
        nh = int(round(hold / h))
        if nh > 0:
            parts.append(np.full(nh, th))
        ns = int(round(0.5 / f / h))
        parts.append(th + math.pi * np.arange(ns) / ns)
        th += math.pi
    return np.concatenate(parts)


def _drive_mod(fc, nstrokes, h, a, fm, ph, theta0=-math.pi / 2):
    T = nstrokes / (2 * fc)
    t = np.arange(int(round(T / h))) * h
    if a == 0:
        return theta0 + 2 * math.pi * fc * t
    return theta0 + 2 * math.pi * fc * (t - a / (2 * math.pi * fm) * (np.cos(2 * math.pi * fm * t + ph) - math.cos(ph)))


# ----------------------------------------------------------------------------------------------- record
def _write(path, fmt, mode, t, F, Nn, pos, meta, units):
    fu, pu = units  # force unit 'N'/'mN', position 'mm'/'um'
    fsc = 1e3 if fu == "mN" else 1.0
    psc = 1e6 if pu == "um" else 1e3
    if fmt == 0:       # SRV export, TAB
        if mode == "force":
            head = "Time [s]\tFriction force [%s]\tNormal force [N]\tStroke position [%s]" % (fu, pu)
            cols = (t, F * fsc, Nn, pos * psc)
        else:
            head = "Time [s]\tdeflection [mm]\tNormal reading [mm]\tStroke position [%s]" % pu
            cols = (t, F, Nn, pos * psc)
        lines = ["Test: %s" % meta["test"], "Date: %s" % meta["date"], "Stroke [mm]: %.3g" % meta["stroke"],
                 "Frequency [Hz]: %.4g" % meta["fc"], "Load [N]: %.4g" % meta["load"],
                 "Duration [s]: %.4g" % t[-1], "", head]
        sep = "\t"; tsc = 1.0
    elif fmt == 1:     # comma CSV, ms / mN / um
        if mode == "force":
            head = "time (ms), Ff (mN), Fn (N), x_drive (um)"
            cols = (t * 1e3, F * 1e3, Nn, pos * 1e6)
        else:
            head = "time (ms), deflection (mm), y (mm), x_drive (um)"
            cols = (t * 1e3, F, Nn, pos * 1e6)
        lines = [head]; sep = ", "
    else:              # whitespace .dat, names row + units row
        if mode == "force":
            lines = ["time  Ff  Fn  x_drive", "s  %s  N  %s" % (fu, pu)]
            cols = (t, F * fsc, Nn, pos * psc)
        else:
            lines = ["time  deflection  y  x_drive", "s  mm  mm  %s" % pu]
            cols = (t, F, Nn, pos * psc)
        sep = "  "
    data = np.column_stack(cols)
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
        for row in data:
            fh.write(sep.join("%.9g" % val for val in row) + "\n")


# ----------------------------------------------------------------------------------------------- main entry
def write_record(case, seed, outdir, nuisance="clean"):
    assert case in CASES and nuisance in NUISANCES
    ci = CASES.index(case)
    rng = np.random.default_rng([0xC5A7, ci, seed, NUISANCES.index(nuisance)])
    rs = np.random.default_rng([0xC5A7, ci, seed])  # physics independent of the nuisance
    u = rs.uniform
    fn = float(math.exp(u(math.log(20), math.log(300))))
    wn = 2 * math.pi * fn; Tn = 1 / fn
    A = u(0.5e-3, 5e-3)
    N0 = float(u(10, 200))
    mu_k = u(0.15, 0.45); D = mu_k * u(0.08, 0.20); r_s = u(0.10, 0.30)
    mu0p = mu_k + D; mu_s0 = mu0p * (1 + r_s)
    n_s = u(2.2, 4.5)
    Fs = mu_s0 * N0; drop_est = 2 * (Fs - (mu_k + 0.4 * D) * N0)
    k = (2 * Fs - drop_est + n_s * drop_est) / (2 * A * 0.95)
    m = k / wn ** 2
    R = u(30, 60)
    fc = fn / R
    Vp = 2 * math.pi * fc * A
    P = dict(fn=fn, k=k, m=m, N0=N0, A=A, mu_k=mu_k, D=D, r_s=r_s, mu_s0=mu_s0, vs=Vp * u(1.0, 3.0),
             w=u(0.7, 1.5), fc=fc, R=R)
    P["eta"] = 0.02 * (mu_s0 - mu_k) * N0 / (8 * Vp) * u(0.5, 1.5)
    P["x0"] = -A + 0.9 * mu0p * N0 / k
    spp = int(rs.integers(20, 101)) if nuisance != "coarse" else int(rng.integers(10, 16))
    r = int(math.ceil(260 / spp)); dt = Tn / spp; h = dt / r
    nstrokes = int(rs.integers(4, 9))
    dep = {}
    meas = {}
    # ---- drive
    if case == "static_ageing" and seed % 2 == 0:
        ratio = u(4, 8); R = u(28, 40); fc = fn / R; P["fc"], P["R"] = fc, R
        pat = [1, 1, 0, 0, 1, 1] if rs.random() < 0.5 else [0, 0, 1, 1, 0, 0]
        strokes = [(fc if b else fc / ratio, 0.0) for b in pat]
        theta = _drive_strokes(strokes, h); P["step_ratio"] = ratio; nstrokes = len(pat)
    elif case == "static_ageing":
        R = u(28, 45); fc = fn / R; P["fc"], P["R"] = fc, R
        nstrokes = 6
        holds = [0.0] * nstrokes
        for j in (1, 3, 5):
            holds[j] = u(5, 50) * Tn
        strokes = [(fc, hd) for hd in holds]
        theta = _drive_strokes(strokes, h); P["holds_Tn"] = [hd / Tn for hd in holds]
    else:
        theta = _drive_mod(fc, nstrokes, h, 0.0, 1.0, 0.0)
    P["nstrokes"] = nstrokes
    p = A * np.sin(theta)
    # ---- pilot (no departure) on the same drive; more strokes while it has fewer than 12 slips
    G, sl = _simulate(P, p, h, {})
    while len(sl) < 12 and nstrokes < 12 and not case == "static_ageing":
        nstrokes += 2; P["nstrokes"] = nstrokes
        theta = _drive_mod(fc, nstrokes, h, 0.0, 1.0, 0.0); p = A * np.sin(theta)
        G, sl = _simulate(P, p, h, {})
    drop = float(np.median([s["drop"] for s in sl]))
    T = len(p) * h
    f_ss = len(sl) / T
    xmin, xmax = float(G["x"].min()), float(G["x"].max())
    if case == "load_variation":
        pp = u(0.12, 0.35); xm = 0.5 * (xmin + xmax); xh = 0.5 * (xmax - xmin)
        if seed % 2 == 0:
            c = (1 if rs.random() < 0.5 else -1) * pp / 2 / xh
            dep["load"] = ("tilt", c, xm)
        else:
            lam = (xmax - xmin) / u(1.2, 2.5)
            dep["load"] = ("wave", pp / 2, 2 * math.pi / lam, u(0, 2 * math.pi))
        P["load"] = [str(dep["load"][0])] + [float(z) for z in dep["load"][1:]]
    elif case == "twin_branch":
        L = drop / k
        tw = (0.10, L * u(0.25, 0.5), Tn * u(0.3, 0.6))
        G1, s1 = _simulate(P, p, h, {"twin": tw})
        t0 = _twin(G1["v"], G1["fr"], s1)
        target = u(0.13, 0.21)
        dep["twin"] = (tw[0] * target / max(t0, 1e-3), tw[1], tw[2])
        P["twin_g_Dc_tau"] = list(dep["twin"])
    elif case == "static_ageing":
        tau_a = Tn * u(0.5, 2.0)
        b0 = 0.03
        G1, s1 = _simulate(P, p, h, {"age": (b0, tau_a)})
        g0, _ = _growth(s1, drop)
        target = u(0.08, 0.16)
        dep["age"] = (b0 * target / max(g0, 1e-3), tau_a)
        P["age_beta_tau"] = list(dep["age"])
    elif case == "triggering":
        a_t = u(0.035, 0.07)
        for _ in range(8):
            f_t = fn * u(2.6, 7.5)
            rr = f_t / f_ss
            if abs(rr - round(rr)) >= 0.2:
                break
        dep["trig"] = (a_t, f_t)
    elif case == "drive_modulation":
        a = u(0.22, 0.43); fm = f_ss * u(0.15, 0.45); ph = u(0, 2 * math.pi)
        theta = _drive_mod(fc, nstrokes, h, a, fm, ph)
        p = A * np.sin(theta)
        P.update(mod_a=a, mod_fm=fm, mod_phase=ph)
    # ---- final run
    for attempt in range(5):
        G, sl = _simulate(P, p, h, dep)
        T = len(p) * h
        f_ss = len(sl) / T
        if case != "triggering":
            break
        rr = dep["trig"][1] / f_ss
        if abs(rr - round(rr)) >= 0.15:
            break
        dep["trig"] = (dep["trig"][0], fn * u(2.6, 7.5))
    if case == "triggering":
        P["trig_a_ft"] = list(dep["trig"])
        meas["ft_over_fn"] = dep["trig"][1] / fn
        meas["ft_over_fss"] = dep["trig"][1] / f_ss
    drops = np.array([s["drop"] for s in sl])
    drop = float(np.median(drops))
    meas.update(n_slips=len(sl), f_ss=f_ss, fn_over_fss=fn / f_ss, drop_N=drop,
                twin_law=_twin(G["v"], G["fr"], sl), load_pp=float((G["N"].max() - G["N"].min()) / N0))
    gr, trange = _growth(sl, drop)
    meas.update(peak_growth=gr, stick_range=trange,
                peak_sd=float(np.std([s["peak"] for s in sl]) / drop))
    if case == "drive_modulation":
        meas["fm_over_fss"] = P["mod_fm"] / f_ss
    # ---- sampling, sensor
    idx = np.arange(0, len(p), r)
    t = idx * h
    Fsp = G["fsp"][idx]; Nn = G["N"][idx]; pos = p[idx]
    # 1-DoF reading of the clean sampled force (central differences), a check on the integrator
    xs = pos - Fsp / k
    vs_ = np.gradient(xs, dt); acc = np.gradient(vs_, dt)
    fr1 = Fsp - m * acc
    sl_s = [dict(s, i0=int(math.ceil(s["i0"] / r)), i1=int(s["i1"] // r)) for s in sl]
    meas["twin_1dof"] = _twin(vs_, fr1, sl_s, drop)
    mode = "force" if rs.random() < 0.6 else "disp"
    fmt = int(rs.integers(0, 3))
    fu = "mN" if (fmt == 1 or rs.random() < 0.3) else "N"
    pu = "um" if (fmt == 1 or rs.random() < 0.4) else "mm"
    F = Fsp + rng.normal(0, drop * rng.uniform(0.0015, 0.004), len(t))
    Nrec = Nn + rng.normal(0, 0.002 * N0, len(t))
    pos_rec = np.round((pos + rng.normal(0, 0.1e-6, len(t))) / 0.1e-6) * 0.1e-6
    nz = {}
    if nuisance == "hum":
        fh = 50.0 if rng.random() < 0.5 else 60.0
        amp = drop * rng.uniform(0.01, 0.05); ph0 = rng.uniform(0, 2 * math.pi, 3)
        F = F + amp * (np.sin(2 * math.pi * fh * t + ph0[0]) + 0.3 * np.sin(4 * math.pi * fh * t + ph0[1])
                       + 0.15 * np.sin(6 * math.pi * fh * t + ph0[2]))
        nz = dict(hum_hz=fh, hum_amp_drop=amp / drop)
    elif nuisance == "drift":
        amp = drop * rng.uniform(0.02, 0.06) * (1 if rng.random() < 0.5 else -1)
        tt = t / t[-1]
        F = F + amp * (0.7 * tt + 0.3 * tt ** 2)
        nz = dict(drift_drop=amp / drop)
    elif nuisance == "spikes":
        fr_ = rng.uniform(0.0005, 0.005); ns = max(1, int(round(fr_ * len(t))))
        js = rng.choice(np.arange(2, len(t) - 2), ns, replace=False)
        F = F.copy(); F[js] += drop * rng.uniform(0.3, 1.0, ns) * rng.choice([-1, 1], ns)
        nz = dict(spike_fraction=ns / len(t))
    elif nuisance == "quantisation":
        qs = drop * rng.uniform(0.002, 0.01)
        F = np.round(F / qs) * qs
        nz = dict(quant_step_drop=qs / drop)
    if mode == "disp":
        y0, yb = rng.uniform(0.1, 1.0), rng.uniform(0.005, 0.02)
        chan = F / k * 1e3
        Nrec = y0 + yb * Nrec
        P["y_affine_mm"] = [y0, yb]
    else:
        chan = F
    # ---- --fn
    omit = (3 * ci + 1) % 8
    if omit == 6:
        omit = 7
    give = not (seed % 8 == omit and case != "triggering" and nuisance != "fn_off")
    fn_given = None
    if give:
        fn_given = fn * (1 + (0.05 if rng.random() < 0.5 else -0.05)) if nuisance == "fn_off" else fn
    args = []
    if fn_given is not None:
        args += ["--fn", "%.6g" % fn_given]
    if mode == "force":
        args += ["--stiffness", "%.6g" % k]
    ext = (".txt", ".csv", ".dat")[fmt]
    os.makedirs(outdir, exist_ok=True)
    path = os.path.abspath(os.path.join(outdir, "%s_%s_s%d_%s%s" % (NAME, case, seed, nuisance, ext)))
    meta = dict(test="SRV oscillating, pin-on-flat, seed %d" % seed, date="2024-0%d-1%d" % (1 + seed % 9, seed % 10),
                stroke=2 * A * 1e3, fc=fc, load=N0)
    _write(path, fmt, mode, t, chan, Nrec, pos_rec, meta, (fu, pu))
    P.update(spp=spp, substeps=r, h=h, mode=mode, fmt=fmt, force_unit=fu, pos_unit=pu, nuisance_params=nz,
             measured=meas)
    meas = {kk: (None if isinstance(vv, float) and not math.isfinite(vv) else vv) for kk, vv in meas.items()}
    P["measured"] = meas
    P = {kk: (float(vv) if isinstance(vv, (np.floating, float)) else vv) for kk, vv in P.items()}
    return dict(generator=NAME, case=case, seed=seed, nuisance=nuisance, file=path, args=args,
                fn_true=float(fn), fn_given=None if fn_given is None else float(fn_given), params=P)


def _selfcheck(outdir, seeds=range(8)):
    import json
    import time
    rows = []
    for case in CASES:
        for sd in seeds:
            t0 = time.time()
            rec = write_record(case, sd, outdir, NUISANCES[sd % 7])
            el = time.time() - t0
            fn = rec["file"]
            skip = 8 if fn.endswith(".txt") else (2 if fn.endswith(".dat") else 1)
            dat = np.loadtxt(fn, delimiter="," if fn.endswith(".csv") else None, skiprows=skip)
            assert dat.ndim == 2 and dat.shape[1] == 4 and np.all(np.isfinite(dat)), fn
            me = rec["params"]["measured"]
            json.dumps(rec, allow_nan=False)
            rows.append((case, sd, el, dat.shape[0], me, rec["params"]["spp"]))
            print(case, sd, rec["nuisance"], "%.2fs" % el, dat.shape[0], json.dumps(
                {kk: (round(vv, 4) if isinstance(vv, float) else vv) for kk, vv in me.items()}), rec["args"],
                "spp", rec["params"]["spp"], "strokes", rec["params"]["nstrokes"])
    return rows


if __name__ == "__main__":
    import sys
    import tempfile
    _selfcheck(sys.argv[1] if len(sys.argv) > 1 else tempfile.mkdtemp())
