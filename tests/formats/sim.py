"""The helper's own 1-DoF spring-slider (static above kinetic friction, a little damping) for the zoo."""
import numpy as np
def simulate(m=0.5, k=2000.0, v0=1.0e-3, N=10.0, mus=0.40, muk=0.30, zeta=0.02, fs=500.0, ncyc=25, noise=0.005, seed=0):
    """1-DoF spring-slider. returns t, F_spring (N), x_ext (m), slider pos (m), drive pos (m)"""
    wn = np.sqrt(k/m); c = 2*zeta*np.sqrt(k*m)
    dt_int = 1/(fs*20)
    # approximate period to set duration
    dF = 2*(mus-muk)*N
    T = dF/(k*v0) + np.pi/wn
    tend = (ncyc+0.6)*T
    n = int(tend*fs)
    t = np.arange(n)/fs
    x = 0.0; v = 0.0; stick = True
    # start with spring partly loaded
    x = -0.5*mus*N/k  # slider behind so spring preloaded
    out = np.empty(n); pos = np.empty(n)
    tt = 0.0; j = 0
    sub = 20
    for i in range(n):
        for s in range(sub):
            F = k*(v0*tt - x)
            if stick:
                if F > mus*N:
                    stick = False
                else:
                    v = 0.0
            if not stick:
                a = (F - muk*N*np.sign(v if v != 0 else 1) - c*v)/m
                vn = v + a*dt_int
                if vn <= 0 and v > 0:
                    v = 0.0; stick = True
                else:
                    x += v*dt_int  # semi-implicit
                    v = vn
            tt += dt_int
        out[i] = k*(v0*tt - x); pos[i] = x
    rng = np.random.default_rng(seed)
    Fn = out + noise*dF*rng.standard_normal(n)
    return t, Fn, Fn/k, pos, v0*t, out

def truth_drops(t, F):
    """find slip drops in clean force: local max followed by local min"""
    d = np.diff(F)
    drops = []; i = 0; n = len(F)
    peaks = []
    while i < n-1:
        if d[i] < 0:
            j = i
            while j < n-1 and d[j] < 0: j += 1
            drops.append(F[i]-F[j]); peaks.append(t[i]); i = j
        else: i += 1
    drops = np.array(drops)
    big = drops[drops > 0.3*drops.max()]
    return float(np.median(big)), len(big)
