"""Stage 5 of ``lieng diagnose``: calibrated decisions.

Each candidate's statistic S (:mod:`.evidence`) is compared with its
distribution under the fitted baseline, obtained by a **parametric
bootstrap**: B records simulated from the baseline on the record's own time
grid and drive, with white noise at the record's own noise level (x and the
normal channel; the normal channel modelled as its part locked to the
motion), and with the natural frequency drawn within its stated
uncertainty u (a given fn within u of the true one: fn / (1 - w), w uniform
within +-u); a normal force is constant in them (the baseline's constant
load), a normal reading keeps its part locked to the motion (crosstalk) (a ``--fn`` off by a few per cent is a nuisance, not an effect);
each replicate is analysed exactly like the record, with the nominal fn.

For candidate k: z = (S - m0) / sqrt(max(s0, se)**2 + s0**2 / B), with m0, s0
the replicates' mean and spread and se the record's own standard error
(its cycle-to-cycle scatter: a real rig is noisier than any simulation);
p from the normal distribution (one-sided for effects with a direction; the
twin branch both ways, each side one-sided with its own fn band and the
better side's p doubled: :func:`calibrate_two_way`).
A statistic that follows the natural frequency (its replicates' values
regressed on their drawn fn error: a slope beyond twice its standard error)
is tested at the least favourable fn within the stated uncertainty u: z =
(S - m0 - band) / sqrt(max(s0, se)**2 + s0**2 / B), m0 and s0 from the line
at the nominal fn (:func:`calibrate`), band the largest shift an fn error
within u makes: read on the record itself where its statistic can be read
again at fn / (1 +- u) (the twin branch, a load read from a normal reading:
the rig need not follow fn as the replicates' 1-DoF slider does), otherwise
u (|slope| + its standard error); so that the false-alarm rate holds for
every fn within u, the edges too (a user's fn off by exactly u), not only on
average over them.
The family-wise false-alarm rate over the candidates is held at ALPHA by
Holm's step-down procedure (a load that follows the motion and a twin
branch both named: each is tested again against replicates of the other's
fitted extension, at the level Holm gave it; see :func:`rivals`).
An effect is **named** when it is significant and its size S - m0 (for
triggering without a normal force: the load modulation the line implies,
which must also pass its own test, Hotelling's on the slips' line less
the sticks': an intersection-union test, the larger of the two p-values
entering Holm's ordering; see :func:`decide`) is at
least the relevance margin stated in
:data:`.evidence.MARGIN` (and at most the bound its own model allows,
:data:`.evidence.UPPER`), and its nested extension then predicts the held-out
cycles better than the baseline (:func:`.extend.unconfirmed`: the gain's
90 % interval above 0); one that passes the first two tests and not the third
is reported as detected, not named.
"""

from __future__ import annotations

import math
import time

import numpy as np

from lieng.errors import LiengInputError
from lieng.diagnose.baseline import Params, pr_like, simulate
from lieng.diagnose.evidence import CANDIDATES, MARGIN, ONE_SIDED, UPPER, statistics
from lieng.diagnose.goodness import GOF, GOF_MARGIN, RIG
from lieng.diagnose.read import noise_level
from lieng.diagnose.segment import Prepared, find_cycles

__all__ = ["ALPHA", "FN_RATIO", "alt_shift", "at_nominal_fn", "fn_needed", "null_replicates", "calibrate",
           "calibrate_side", "calibrate_two_way", "TWO_WAY", "below_accounted", "fn_sensitivity", "decide", "misfit",
           "RIVALS", "rivals"]

#: family-wise false-alarm rate
ALPHA = 0.05

#: the 95 % interval of a size read apart from the statistic (``sizes`` in
#: :func:`decide`): the 97.5 % quantile of Student's t with 9 degrees of
#: freedom (a normal force's size has a jackknife over ten blocks; x's, a
#: sandwich over its n slips and sticks with more, so there it is wider
#: than it needs to be)
SIZE_T = 2.262


def _norm_sf(z):
    return 0.5 * math.erfc(z / math.sqrt(2.0))


def _norm_ppf(p):
    """The standard normal quantile (bisection on erfc; p in (0, 1))."""
    p = min(max(p, 1e-300), 1 - 1e-16)
    lo, hi = -40.0, 40.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if 1.0 - _norm_sf(mid) < p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


#: seconds the baseline's replicates may take (at least 8 are run): a long record's replicates are cut
#: short so that the whole diagnosis stays within the scale limit (750 000 samples in under a minute;
#: about 20 replicates there); a record of ordinary length runs all of them in a few seconds
REPLICATE_BUDGET = 18.0


def null_replicates(pr: Prepared, base: Params, fn: float, u_fn: float, B: int = 39, budget: float = REPLICATE_BUDGET,
                    seed: int = 0, progress=None, y_is_force: bool = False, arcs: bool = True, ylow=None):
    """The candidates' statistics on B baseline replicates (module docstring).

    ``base`` may be an extension of the baseline: with ``ylow`` (the
    record's low-passed normal channel) its load follows the measured
    channel, and the replicates' normal channel is the record's own.

    Returns a dict name -> array of the replicates' values, and the number
    of replicates analysed."""
    rng = np.random.default_rng(seed)
    sx = noise_level(pr.x)
    y = pr.y
    sy = noise_level(y) if y is not None else 0.0
    vals = {k: [] for k in (*CANDIDATES, *GOF, *RIG, FN_RATIO)}
    t0 = time.perf_counter()
    done = 0
    for b in range(B):
        # a given fn within u_fn of the true one: the true fn within fn / (1 + u) .. fn / (1 - u)
        fb = fn / (1.0 - u_fn * rng.uniform(-1.0, 1.0))
        e = fb / fn - 1.0
        xs, vs, _ = simulate(pr, base, fb, ylow)
        xb = xs + sx * rng.standard_normal(xs.size)
        if pr.quantum > 0:
            # read through the record's quantiser (its grid's offset drawn): the steps' tones and the noise a
            # reading holds below its step are the record's too
            xb = pr.quantum * np.round(xb / pr.quantum + rng.uniform(-0.5, 0.5))
        yb = None
        if y is not None and ylow is not None:
            yb = y                       # the measured load drives the model: the channel is the record's
        elif y is not None:
            # a reading of the normal channel: its part locked to the motion is kept (crosstalk is not a
            # load effect); a normal force: constant under the baseline's constant load
            lock = 0.0 if y_is_force else base.y_c[1] * xs + base.y_c[2] * vs
            yb = base.y_c[0] + lock + sy * rng.standard_normal(xs.size)
        q = pr_like(pr, xb, yb)
        try:
            c = find_cycles(q, fn)
            if c.n < 3:
                continue
            st, _, aux = statistics(q, c, fn, y=yb, y_is_force=y_is_force, arcs=arcs, nperm=0, size=False)
        except (LiengInputError, np.linalg.LinAlgError, ValueError):
            continue
        st.update(aux["gof"])
        st[FN_RATIO] = e
        for k in vals:
            vals[k].append(st[k])
        done += 1
        if progress:
            progress(b + 1, B)
        el = time.perf_counter() - t0
        if b >= 8 and el * (b + 2) / (b + 1) > budget:
            break
    return {k: np.asarray(v, float) for k, v in vals.items()}, done


#: the key of the replicates' drawn natural frequency error (fb / fn - 1)
FN_RATIO = "_fn_ratio"


def noise_sd(s0: float, se: float, n: int) -> float:
    """The standard deviation a statistic's departure is judged by: the
    larger of the replicates' spread s0 and the record's own standard error
    se, with the uncertainty of the replicates' mean over n of them."""
    return math.sqrt(max(s0, se) ** 2 + s0 ** 2 / max(n, 1))


def _fn_slope(v, e, u: float):
    """The slope of the replicates' values ``v`` on their drawn fn errors
    ``e`` and its standard error (None when they cannot be regressed)."""
    if e is None or u <= 0 or v.size < 8 or not np.ptp(e) > 0:
        return None
    A = np.column_stack([np.ones(e.size), e - e.mean()])
    co, *_ = np.linalg.lstsq(A, v, rcond=None)
    r = v - A @ co
    s = float(np.sqrt(np.sum(r * r) / (v.size - 2)))
    return float(co[1]), s / float(np.sqrt(np.sum((e - e.mean()) ** 2))), float(co[0] - co[1] * e.mean()), s


def at_nominal_fn(v, e, u: float):
    """The replicates' values ``v`` moved to the nominal fn along their
    regression on the drawn fn errors ``e`` where its slope is significant
    (beyond twice its standard error; as :func:`fn_sensitivity` reads the
    null): an alternative null is compared with the null at the same fn, its
    spread the noise about that line, not the fn draws'."""
    fit = _fn_slope(np.asarray(v, float), e, u)
    if fit is None or not abs(fit[0]) > 2.0 * fit[1]:
        return v
    return np.asarray(v, float) - fit[0] * np.asarray(e, float)


def fn_sensitivity(v, e, u: float):
    """How a statistic follows the natural frequency: the replicates' values
    ``v`` regressed on their drawn fn error ``e`` (fb / fn - 1, fb =
    fn / (1 - w), w uniform within +-u).  Returns (m0, s0, band) when the
    slope is significant (beyond twice its standard error): the null mean at
    the nominal fn, the spread about the line (the noise alone) and the
    largest shift an fn error within u makes (the true fn as far as
    fn / (1 - u), an error of u / (1 - u)), u / (1 - u) |slope|; None
    otherwise."""
    fit = _fn_slope(v, e, u)
    if fit is None:
        return None
    b, se_b, m0, s = fit
    if not abs(b) > 2.0 * se_b:
        return None
    return m0, s, u / (1.0 - u) * (abs(b) + se_b)


def alt_shift(m0: float, s0: float, n: int, alt, one_sided: bool) -> float:
    """How far an alternative null (its replicates' values ``alt``) lies from
    the null mean ``m0`` (spread ``s0`` over ``n`` replicates), towards the
    effect for a one-sided statistic: 0 unless beyond twice the standard
    error of the difference of their means (:func:`calibrate`)."""
    alt = np.asarray(alt, float)[np.isfinite(alt)] if alt is not None else np.array([])
    if alt.size < 5 or n < 5:
        return 0.0
    shift = float(np.mean(alt)) - m0
    if not abs(shift) > 2.0 * math.sqrt(s0 ** 2 / n + float(np.var(alt, ddof=1)) / alt.size):
        return 0.0
    return max(shift, 0.0) if one_sided else abs(shift)


def calibrate(S: float, se: float, v, one_sided: bool, e=None, u: float = 0.0, readings=None, alt=None) -> tuple:
    """A statistic S with standard error se against the finite replicates'
    values v (module docstring): (m0, s0, S - m0, its standard deviation, z,
    p, band).

    With the replicates' drawn fn errors ``e`` (within +-``u``), a statistic
    that follows fn (:func:`fn_sensitivity`) is tested at the least
    favourable fn within the stated uncertainty: its departure from the null
    line at the nominal fn less the largest shift an fn error makes, against
    the noise about that line (valid for any true fn within u, not only on
    average over them); the standard deviation returned then spans the band
    too (d +- 1.96 of it is d +- (band + 1.96 sd)).

    ``readings``, the record's own statistic read at fn / (1 + u) and
    fn / (1 - u), give the band from the record itself: how far its reading
    moves when fn is anywhere within u (towards the null: the favourable
    side for the effect is never credited).  The replicates, a 1-DoF
    slider, need not follow fn as the record does (a second mode of the
    rig, a bristle lag).

    ``alt``, the statistic on replicates of an alternative null (the
    baseline without the resonance the record is read as recorded through:
    a second mode of the rig need not shape the slips as a sensor's
    resonance does), widens the band by the two nulls' difference where it
    is significant (beyond twice its standard error), towards the least
    favourable of them.  (:func:`decide` passes it at the nominal fn,
    :func:`at_nominal_fn`: both nulls follow fn alike, and the spread of
    their fn draws would hide a difference between them.)"""
    fit = fn_sensitivity(v, e, u)
    if fit is None:
        m0, s0, band = float(np.mean(v)), float(np.std(v, ddof=1)), 0.0
    else:
        m0, s0, band = fit
    if readings is not None and all(math.isfinite(r) for r in readings):
        band = max(S - min(readings), 0.0) if one_sided else max(abs(r - S) for r in readings)
    band += alt_shift(m0, s0, v.size, alt, one_sided)
    den = noise_sd(s0, se, v.size)
    d = S - m0
    excess = (d - band if one_sided else math.copysign(max(abs(d) - band, 0.0), d))
    z = excess / den if den > 0 else (math.copysign(50.0, excess) if excess else 0.0)
    z = float(np.clip(z, -50.0, 50.0))
    p = _norm_sf(z) if one_sided else min(1.0, 2.0 * _norm_sf(abs(z)))
    # the interval d +- 1.96 sd widened by the band on each side (the true fn anywhere within u)
    return m0, s0, d, den + band / 1.96, z, float(p), band


#: the reason ``decide`` gives a candidate that does not apply to the record (the report shows it as such,
#: and any other reason as evidence withheld)
NOT_APPLICABLE = "does not apply to this record"


def _finite_null(null: dict, k: str) -> tuple:
    """Candidate ``k``'s finite replicate values and their drawn fn errors
    (None where the replicates carry none)."""
    v, e = null.get(k, np.array([])), null.get(FN_RATIO)
    fin = np.isfinite(v)
    return v[fin], (e[fin] if e is not None and e.size == fin.size else None)


def calibrate_side(k: str, side, S: float, se: float, v, e=None, u: float = 0.0, readings=None, alt=None) -> tuple:
    """:func:`calibrate` for candidate ``k``: one-sided for an effect with a
    direction (ONE_SIDED), two-sided otherwise, or one-sided on the given
    ``side`` (+1, or -1: the statistic, its null, readings and alternative
    null mirrored, and the results mirrored back): (m0, s0, d, its sd, z,
    p, band, the alternative null's part of the band)."""
    g = side or 1
    one = k in ONE_SIDED or bool(side)
    mirror = (lambda a: None if a is None else -np.asarray(a, float)) if g < 0 else (lambda a: a)
    m0, s0, d, den, z, p, band = calibrate(g * S, se, mirror(v), one, e, u,
                                           None if readings is None else tuple(mirror(readings)), mirror(alt))
    rb = alt_shift(m0, s0, np.size(v), mirror(alt), one)
    return g * m0, s0, g * d, den, z, p, band, rb


#: candidates read both ways: each side is tested one-sided, with its own band (an fn error credited on
#: neither side), and the better side's p doubled (Bonferroni over the two sides)
TWO_WAY = ("twin_branch",)


def calibrate_two_way(k: str, S: float, se: float, v, e=None, u: float = 0.0, readings=None, alt=None) -> tuple:
    """:func:`calibrate_side` for candidate ``k``; for one of
    :data:`TWO_WAY`, both sides one-sided, each with its own band (how far
    an fn error within u moves the reading towards that side's null), the
    side with the smaller p kept and its p doubled: the same tuple, z
    signed as the departure."""
    if k not in TWO_WAY:
        return calibrate_side(k, None, S, se, v, e, u, readings, alt)
    up = calibrate_side(k, 1, S, se, v, e, u, readings, alt)
    dn = calibrate_side(k, -1, S, se, v, e, u, readings, alt)
    g = 1 if up[5] <= dn[5] else -1
    m0, s0, d, den, z, p, band, rb = up if g > 0 else dn
    return m0, s0, d, den, g * z, min(1.0, 2.0 * p), band, rb


def below_accounted(rows: dict, normal_recorded: bool) -> tuple:
    """Whether a twin branch named below 0 (the decelerating branch below
    the accelerating one) is accounted for otherwise: (the reason, or None
    when it stands; the upper end of the load's 95 % interval, or None).

    A load that rises with x, a triggering and a modulated drive bend the
    slips alike, so it stands only where no other candidate is named and,
    with a normal channel (``normal_recorded``), where the load that
    channel records cannot account for it: the load's effect size, read
    over the drop as the twin's is, has its 95 % interval below the twin's
    size.  Without a normal channel a load that rises with x is not
    excluded (the caller says so)."""
    size = abs(rows["twin_branch"]["effect_size"])
    others = [k for k in CANDIDATES if k != "twin_branch" and rows[k]["named"]]
    lv = rows["load_variation"]
    load_hi = float(lv["interval"][1]) if lv.get("applicable") and lv.get("interval") else None
    if others:
        one = len(others) == 1
        return (f"{', '.join(others)} {'is' if one else 'are'} named and bend{'s' if one else ''} the slips "
                f"alike"), load_hi
    if normal_recorded and (load_hi is None or load_hi >= size):
        return ("the recorded normal channel's load could account for it ("
                + (f"its effect up to {load_hi:.3g} of the drop" if load_hi is not None else
                   "its evidence is not read")
                + ")"), load_hi
    return None, load_hi


def decide(st: dict, se: dict, null: dict, alpha: float = ALPHA, applicable=None, p_own=None,
           withheld=None, u_fn: float = 0.0, sizes=None, fn_readings=None, null_alt=None) -> dict:
    """The evidence table: for every candidate the statistic, the null mean
    and spread, z, p, Holm's decision and whether it is named.

    ``p_own`` gives p-values calibrated within the record (a permutation
    test) for some candidates: their effect size is the statistic itself.
    ``withheld`` maps candidates to the reason their evidence is not read.
    ``fn_readings`` maps candidates to the record's own statistic read at
    fn / (1 +- u_fn), ``null_alt`` to their values on an alternative null's
    replicates (:func:`calibrate`).
    ``sizes`` maps candidates to an effect size read on a physical scale
    apart from the statistic the test reads, with its standard error
    (triggering: the load modulation the line implies), and optionally the
    p-value of the size's own test: that size and its interval (+- SIZE_T
    standard errors) are reported, and the effect is named only when the
    size reaches the margin and its own test passes too (the line's test
    says there is a line; the size's, that it is in the friction): the
    intersection-union test, whose p-value is the larger of the two (``p``;
    the line's own is ``p_line``), valid at the level Holm's procedure gives
    it without any further correction (Berger 1982); without a p-value the
    size's 95 % interval must lie above 0 (``size_shown`` says whether the
    size passed)."""
    rows = {}
    p_own = p_own or {}
    withheld = withheld or {}
    for k in CANDIDATES:
        if applicable is not None and k not in applicable:
            withheld.setdefault(k, NOT_APPLICABLE)
        if k in withheld:
            rows[k] = dict(statistic=float(st[k]), null_mean=0.0, null_sd=0.0, se=None, z=0.0, p=1.0,
                           effect_size=0.0, applicable=False, withheld=withheld[k])
            continue
        if k in p_own and math.isfinite(st[k]):
            p = float(p_own[k])
            z = float(np.clip(-_norm_ppf(p), -50.0, 50.0))
            rows[k] = dict(statistic=float(st[k]), null_mean=0.0, null_sd=0.0, se=None, z=z, p=p,
                           effect_size=float(st[k]), applicable=True, calibration="permutation within the record")
            continue
        v, e = _finite_null(null, k)
        S = float(st[k])
        ok = (applicable is None or k in applicable) and v.size >= 5 and math.isfinite(S) and math.isfinite(se[k])
        if not ok:
            rows[k] = dict(statistic=S, null_mean=0.0, null_sd=0.0, se=float(se[k]) if math.isfinite(se[k]) else None,
                           z=0.0, p=1.0, effect_size=0.0, applicable=False)
            continue
        err = float(se[k]) if math.isfinite(se[k]) else 0.0
        rd = (fn_readings or {}).get(k)
        alt = None
        if null_alt and k in null_alt:
            # (at the nominal fn, as the null is read)
            va, ea = _finite_null(null_alt, k)
            alt = at_nominal_fn(va, ea, u_fn) if va.size else None
        m0, s0, d, den, z, p, band, rb = calibrate_two_way(k, S, err, v, e, u_fn, rd, alt)
        rows[k] = dict(statistic=S, null_mean=m0, null_sd=s0, se=err, z=z, p=float(p), effect_size=d, applicable=True,
                       interval=[d - 1.96 * den, d + 1.96 * den], fn_band=band - rb)
        if alt is not None:
            rows[k].update(alt_null_mean=float(np.mean(alt[np.isfinite(alt)])) if np.any(np.isfinite(alt)) else None,
                           alt_band=rb)
        if rd is not None:
            rows[k]["fn_readings"] = [float(r) for r in rd]
        if sizes and k in sizes:
            size, size_se, *p_in = sizes[k]
            size_se = float(size_se) if math.isfinite(size_se) else abs(float(size)) + 1.0
            rows[k].update(statistic_departure=d, effect_size=float(size),
                           interval=[float(size) - SIZE_T * size_se, float(size) + SIZE_T * size_se])
            if p_in:
                # two hypotheses both to be rejected (there is a line; it is in the friction): the
                # intersection-union test, whose p is the larger of the two, enters Holm's ordering
                rows[k].update(p_size=float(p_in[0]), p_line=float(p), p=max(float(p), float(p_in[0])))
    # Holm's step-down over the applicable candidates
    app = sorted((r["p"], k) for k, r in rows.items() if r["applicable"])
    m = len(app)
    stop = False
    for i, (p, k) in enumerate(app):
        sig = (not stop) and p <= alpha / (m - i)
        if not sig:
            stop = True
        rows[k]["significant"] = bool(sig)
        rows[k]["holm_level"] = alpha / (m - i)
    for k, r in rows.items():
        r.setdefault("significant", False)
        size = r["effect_size"] if k in ONE_SIDED else abs(r["effect_size"])
        r["margin"] = MARGIN[k]
        r["named"] = bool(r["significant"] and size >= MARGIN[k])
        if "p_size" in r:
            # the size has its own test (triggering in x: is the line in the friction, not the sensor?),
            # joined to the line's by the intersection-union test: both at the level Holm gave the candidate
            r["size_level"] = r.get("holm_level", alpha / max(m, 1))
            r["size_shown"] = r["p_size"] <= r["size_level"]
            r["line_significant"] = r["p_line"] <= r["size_level"]
        elif "statistic_departure" in r:
            r["size_shown"] = r["interval"][0] > 0
            r["line_significant"] = r["significant"]
        if not r.get("size_shown", True):
            r["named"] = False
        if r["named"] and k in UPPER and size > UPPER[k]:
            r["named"] = False
            r["beyond_model"] = (f"{k}: a size of {size:.3g} is beyond the {UPPER[k]} its model allows: the record "
                                 f"departs from the baseline there for another reason (check --fn)")
    return rows


def fn_needed(row: dict, u_fn: float, n: int) -> float | None:
    """For a candidate that is not significant only because an fn error
    within ``u_fn`` could make its reading (its ``fn_band``): the relative
    uncertainty of fn at which the same reading would pass its Holm level,
    or None."""
    band, size = row.get("fn_band", 0.0), row.get("effect_size", 0.0)
    if not (row.get("applicable") and band > 0 and u_fn > 0) or row.get("significant"):
        return None
    den = noise_sd(row.get("null_sd") or 0.0, row.get("se") or 0.0, n)
    zreq = -_norm_ppf(row.get("holm_level", ALPHA))
    room = abs(size) - row.get("alt_band", 0.0) - zreq * den
    if not room > 0:
        return None
    u = u_fn * min(room / band, 1.0)
    return u if u < u_fn else None


def misfit(gof: dict, null: dict, features=GOF) -> list:
    """The goodness-of-fit features in which the record departs from the
    baseline's replicates beyond their spread (|z| > 3.5, about 0.05 over
    the three at once) and by more than GOF_MARGIN: [(name, record value,
    replicates' mean)]."""
    out = []
    for k in features:
        v = null.get(k, np.array([]))
        v = v[np.isfinite(v)]
        if v.size < 5:
            continue
        m0, s0 = float(np.mean(v)), float(np.std(v, ddof=1))
        d = gof[k] - m0
        rel = abs(d) / max(abs(m0), 1e-12) if k == "slip_duration" else abs(d)
        if abs(d) > 3.5 * max(s0, 1e-12) and rel > GOF_MARGIN[k]:
            out.append((k, float(gof[k]), m0))
    return out


#: pairs of candidates that can stand for each other (a load that follows the
#: motion bends the slips as a twin branch does)
RIVALS = ("twin_branch", "load_variation")


def _given_rival(pr, k, other, other_ext, fn, u_fn, st, row, y_is_force, arcs, ylow, replicates, budget):
    """Candidate ``k``'s statistic calibrated again by replicates of the
    fitted extension ``other_ext`` of its rival (a load extension's load
    follows the measured channel): (p, effect size), one-sided for effects
    with a direction; None when too few replicates."""
    null2, n2 = null_replicates(pr, other_ext, fn, u_fn, B=max(replicates // 2, 10), budget=0.5 * budget,
                                seed=1, y_is_force=y_is_force, arcs=arcs,
                                ylow=ylow if other_ext.load_k else None)
    v, e = _finite_null(null2, k)
    if v.size < 5:
        return None
    m0, s0, d, _, _, p, _, _ = calibrate_two_way(k, float(st[k]), row["se"] or 0.0, v, e, u_fn,
                                                 row.get("fn_readings"))
    row["given_rival"] = {"rival": other, "null_mean": m0, "null_sd": s0, "effect_size": d, "p": p,
                          "replicates": n2}
    return p, (d if k in ONE_SIDED else abs(d))


def rivals(pr, base, fitted, fn, u_fn, st, rows, named, effects, notes, y_is_force, arcs, ylow, replicates,
            budget):
    """When a twin branch and a load variation are both named, each is tested
    again against replicates of the other's fitted extension (at the level
    Holm's procedure gave it, by its margin), and one that the other's
    extension accounts for is not named.  A normal *force* is independent
    evidence of the load (its own variation), which no twin branch makes:
    then only the twin is tested.  When neither survives the other and
    one's extension leaves the other below its margin while the other's does
    not, the one left below its margin is not named (an effect of that size
    is not named).  Otherwise, when neither survives the other, both
    stay named (the record cannot tell them apart at its levels), and the
    one whose statistic the other's extension leaves the larger share of
    (its departure from those replicates over its departure from the
    baseline's, 0 when it has the other sign) is returned: it accounts for
    its rival better than its rival accounts for it, and goes first.
    Otherwise None."""
    if not all(k in named and fitted[k][0] is not base for k in RIVALS):
        return None
    tests = [("twin_branch", "load_variation")] + ([] if y_is_force else [("load_variation", "twin_branch")])
    keep, left = {}, {}
    for k, other in tests:
        r = _given_rival(pr, k, other, fitted[other][0], fn, u_fn, st, rows[k], y_is_force, arcs, ylow, replicates, budget)
        keep[k] = r is None or (r[0] <= rows[k]["holm_level"] and r[1] >= MARGIN[k])
        left[k] = math.inf if r is None else r[1]
    small = [k for k in left if left[k] < MARGIN[k]]
    if not any(keep.values()) and len(keep) == 2 and len(small) == 1:
        # neither is significant beyond the other, but one's extension leaves the other's effect below its
        # margin (the size below which no effect is named) and the other's does not: the one left below its
        # margin adds nothing its rival does not explain, and is not named (as an effect of that size is not)
        keep[next(k for k in keep if k not in small)] = True
    if not any(keep.values()) and len(keep) == 2:
        share = {}
        for k in keep:
            es, left = rows[k]["effect_size"], rows[k]["given_rival"]["effect_size"]
            share[k] = max(math.copysign(1.0, es) * left, 0.0) / max(abs(es), 1e-12)
            rows[k]["given_rival"]["share_left"] = share[k]
        first = max(share, key=share.get)
        notes.append(f"{first} goes first: the other's extension leaves {100 * share[first]:.0f} % of its "
                     f"statistic, its own leaves {100 * min(share.values()):.0f} % of the other's")
        return first
    for k, ok in keep.items():
        if ok:
            continue
        g = rows[k]["given_rival"]
        other = g["rival"]
        rows[k]["named"] = False
        named.remove(k)
        effects[:] = [e for e in effects if e["effect"] != k]
        notes.append(f"{k} is not named: replicates of the fitted {other} extension give a {k} statistic like "
                     f"the record's ({st[k]:.3g} against {g['null_mean']:.3g} +- {g['null_sd']:.2g} in "
                     f"{g['replicates']} replicates, p = {g['p']:.2g}"
                     + (f"; {left[k]:.3g} of the drop left, below its margin {MARGIN[k]})" if left[k] < MARGIN[k]
                        else ")"))
