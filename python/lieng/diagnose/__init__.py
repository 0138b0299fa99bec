"""``lieng diagnose``: what the thesis's 1-DoF model gets wrong on a measured
stick-slip record, which effect causes it, and how much an extended model
gains.

One module per stage: :mod:`.read` (records as labs record them),
:mod:`.segment` (strokes, cycles, natural frequency), :mod:`.baseline` (the
thesis's model identified from the record), :mod:`.evidence` (one effect
size per candidate), :mod:`.decide` (calibration against the fitted
baseline's own replicates, Holm), :mod:`.extend` (nested extensions, held-out
gain), :mod:`.report` (diagnosis.json, report.md, plots).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from lieng.errors import LiengInputError
from lieng.io.outputs import finite_json as _finite
from lieng.diagnose.baseline import (CALIBRATION_SAMPLES, Params, calibrate_fn, fit_baseline, pr_like,
                                     simulate, slip_friction)
from lieng.diagnose.decide import (ALPHA, REPLICATE_BUDGET, RIVALS, below_accounted, decide, fn_needed, misfit,
                                   null_replicates, rivals)
from lieng.diagnose.evidence import (CANDIDATES, MARGIN, ONE_SIDED, SLIDING, fn_readings, sliding_statistics,
                                     statistics)
from lieng.diagnose.goodness import RIG, mean_above_zero, onset_ringing, rig_mode
from lieng.diagnose.signals import lowpass, y_on_motion
from lieng.diagnose.extend import (METRIC, Judge, candidates, folds, gain_folds, level_trend, refine, subset,
                                   unconfirmed, window)
from lieng.diagnose.read import Record, check_fn, noise_level, read_record, record_from_arrays, record_from_trc_deck
from lieng.diagnose.segment import (REVERSING_SHARE, Prepared, crop, drive_from_force, estimate_fn, find_cycles,
                                    force_sides, head, prepare, reversal_ramp, slip_seconds, stick_ratios,
                                    stick_slip_span)

__all__ = ["CANDIDATES", "Diagnosis", "Record", "read_record", "record_from_arrays", "record_from_trc_deck",
           "diagnose", "FN_UNCERTAINTY"]

#: the relative uncertainty a user-given --fn is taken to have
FN_UNCERTAINTY = 0.05
#: the relative uncertainty of fn fixed by the slips' duration (:func:`.baseline.calibrate_fn`;
#: measured on the 62 records the six independent generators write without --fn: 0.68-1.21 of
#: the true fn, 53 within 15 %, 49 within 10 %, 37 within 5 %; twin branches, which shorten the
#: slips, read high)
FN_UNCERTAINTY_DURATION = 0.15
#: the widest relative uncertainty fn is read with from the slips (the replicates' fn is drawn within it and
#: stays > 0); where the noise leaves the slips' falls open beyond it, the record is refused, asking for --fn
FN_UNCERTAINTY_MAX = 0.5
#: a --fn further than this from the slips' estimate is questioned
FN_CHECK = 0.20
#: slips whose own frequency (their arcs', or the fn at which the baseline's last as long) is this far off
#: the given fn are not arcs of a free oscillation at it (the twin-branch evidence is withheld when faster)
SLIPS_OFF = 0.25
#: fewer baseline replicates than this calibrate nothing (:func:`.decide.decide` reads a candidate on
#: five or more): the answer is then `unexplained`, never `none`
MIN_REPLICATES = 5
#: the sticks' rise over the drive beyond which the record is questioned: a
#: stuck slider loads the spring at the drive velocity (ratio 1; a compliant
#: contact or creep makes it less), so a quarter faster is a wrong --v0,
#: --stiffness or unit, not friction
STICK_FASTEST = 1.25
#: and below which: a slider that loads its spring at under a fifth of the drive velocity through the middle of
#: its sticks would creep most of the drive away (a creeping contact loses a part of it: the lowest of the 1031
#: cached benchmark records, a reciprocating stage's, reads 0.35), so --v0 or --stiffness is too large (stated a
#: priori, a factor of five)
STICK_SLOWEST = 0.2
#: a slip lasts about half a natural period (longer where the friction falls with speed): slips shorter
#: than this many natural periods of a given --fn say that --fn is wrong
SLIP_SHORTEST = 0.2
#: the twin-branch evidence's side above is read only when the record's slips
#: last no longer than the baseline's replicates', beyond this fraction
#: (shorter slips are what a decelerating branch above the accelerating one
#: makes: the effect itself; longer, what one below makes, which is read)
SLIP_MATCH = 0.10
#: the effects whose extension moves the friction level along the record: their gains are judged against
#: the plain baseline, the others' against the one read through the level's trend (:func:`.extend.level_trend`)
LEVEL_EFFECTS = ("friction_drift", "load_variation")
#: a normal force drives the extensions' load low-passed at this many fn (the evidence reads it at 1.5 fn)
EXT_LOWPASS = 4.0


@dataclass
class Diagnosis:
    """The result of :func:`diagnose`.

    Attributes
    ----------
    effect : str
        The primary effect named, ``"none"``, ``"unexplained"``,
        ``"no_stick_slip"`` (no cycle found: steady sliding) or
        ``"too_few_cycles"`` (one to three: stick-slip too short to
        diagnose).
    effects : list of dict
        Every effect named: name, effect size and interval, p, gain and its
        interval.
    detected : list of dict
        Effects significant and above their margin whose extension does not
        predict the held-out cycles better than the baseline: the same keys
        and ``why_not_named``.  Not named.
    evidence : dict
        Per candidate: statistic, null mean and spread, z, p, significant,
        named, margin.
    gain : float
        1 - e_extended / e_baseline on the held-out cycles (primary effect).
    """

    effect: str
    reason: str
    effects: list = field(default_factory=list)
    detected: list = field(default_factory=list)
    evidence: dict = field(default_factory=dict)
    goodness: dict = field(default_factory=dict)
    sliding: dict = field(default_factory=dict)
    fn: float = 0.0
    fn_source: str = ""
    fn_uncertainty: float = 0.0
    fn_data: float | None = None
    fn_data_se: float | None = None
    baseline: Params | None = None
    extended: Params | None = None
    baseline_error: float = 0.0
    extended_error: float = 0.0
    gain: float = 0.0
    gain_interval: list = field(default_factory=lambda: [0.0, 0.0])
    n_cycles: int = 0
    n_replicates: int = 0
    drop: float = 0.0
    notes: list = field(default_factory=list)
    warnings: list = field(default_factory=list)
    plot: dict = field(default_factory=dict, repr=False)
    #: the unit of x and of every length here (mm; mrad for a rotary record, its twist; the JSON's keys that
    #: end in _mm hold it)
    length_unit: str = "mm"

    def to_json(self) -> dict:
        d = {"effect": self.effect, "reason": self.reason, "gain": self.gain, "gain_interval_90": self.gain_interval,
             "baseline_error": self.baseline_error, "extended_error": self.extended_error, "metric": METRIC,
             "effects": self.effects, "detected": self.detected, "evidence": self.evidence, "goodness_of_fit": self.goodness,
             "sliding": self.sliding,
             "calibration": {"method": "parametric bootstrap of the fitted baseline (fn drawn within its "
                                       "uncertainty, noise at the record's level); Holm over the candidates",
                             "family_wise_alpha": ALPHA, "replicates": self.n_replicates},
             # (null where nothing fixed them: no stick-slip, no natural frequency or drop to read)
             "natural_frequency_hz": {"used": self.fn if self.fn > 0 else None, "source": self.fn_source,
                                      "relative_uncertainty": self.fn_uncertainty, "from_slips": self.fn_data,
                                      "from_slips_se": self.fn_data_se},
             "cycles": self.n_cycles, "drop_mm": self.drop if self.drop > 0 else None,
             "fitted": {"baseline": self.baseline.to_json() if self.baseline else None,
                        "extended": self.extended.to_json() if self.extended else None},
             "units": {"x": self.length_unit, "t": "s", "velocity": f"{self.length_unit}/s", "frequency": "Hz",
                       "effect_size": "per evidence row: over the drop D, or relative"},
             "notes": self.notes, "warnings": self.warnings}
        return _finite(d)


def _stiffness_from_sticks(pr):
    """The stiffness (N/m) from a force record read with 1 N/m (x holds the
    force in N times 1000, so its rise over the drive while the slider sticks
    is the stiffness): the median stick slope over the drive, or in steady
    sliding the presliding ramp after each reversal (its rise to 90 % of the
    sliding level over the travel meanwhile, the median over two strokes or
    more that resolve it); None when neither can be read."""
    c = find_cycles(pr, None, retry=True)
    if c.n >= 4:
        r = stick_ratios(pr, c)[1]
        if r.size >= 3 and np.median(r) > 0:
            return float(np.median(r))
    # steady sliding: the presliding ramp after each reversal, its rise to 90 % of the sliding level over
    # the drive's travel meanwhile (the ramp the report reads, so that it reads a slope of 1 there); a ramp
    # within one sample's travel is not resolved
    slopes = []
    for s in pr.strokes:
        if s.n < 20:
            continue
        ramp = reversal_ramp(pr, s)
        step = float(np.median(np.abs(pr.vd[s.j0:s.j0 + s.n]))) * pr.dt
        if ramp.level > ramp.x0 and ramp.travel > step:
            slopes.append(ramp.slope)
    return float(np.median(slopes)) if len(slopes) >= 2 else None


def _train_trough(pr, c, sel) -> float:
    """The mean trough of the training cycles ``sel`` (all when none)."""
    return float(np.mean(pr.x[c.trough_i[sel]])) if np.any(sel) else float(np.mean(pr.x[c.trough_i]))


def _extend(k, base, train, pr, c, fn, st, aux, win, trough):
    """Effect ``k``'s nested extension of ``base`` fitted on the training
    part ``win`` (its Judge ``train``): the best candidate on the training
    error, refined; the baseline itself when none is better (its term at
    zero).  Returns (ext, its training error, the baseline's, the candidates)."""
    cands = candidates(k, base, pr, c, fn, st, aux, win)
    e_train0 = train.error(base)
    ext, e_tr = base, e_train0
    if cands:
        errs = [train.error(p) for p in cands]
        if np.isfinite(min(errs)):
            ext = cands[int(np.argmin(errs))]
            mask = window(pr.t, win)
            ext, e_tr = refine(k, ext, base, train, pr, fn, mask, trough, ylow=aux.get("ylow"))
            if not e_tr < e_train0:   # nested: the extension's own term at zero is the baseline itself
                ext, e_tr = base, e_train0
    return ext, e_tr, e_train0, cands


def _in_units(d: Diagnosis, rec: Record) -> Diagnosis:
    """``d`` with the record's length unit (mm, or a rotary record's mrad)."""
    d.length_unit = rec.length_unit
    return d


def _no_stick_slip(pr, c_n: int, notes, warnings, fn=None, src="", fd=None, fse=None) -> Diagnosis:
    """A record without stick-slip: what steady sliding shows, stroke by
    stroke (direction asymmetry and drift tested within the record: block
    jackknife, Holm)."""
    st, se, aux = sliding_statistics(pr)
    p_own = {"position_dependence": aux["p_position"]} if "p_position" in aux else {}
    app = [k for k in SLIDING if k != "position_dependence" or p_own]
    rows = decide(st, se, {k: np.zeros(10) for k in CANDIDATES}, applicable=app, p_own=p_own)
    if "position_note" in aux:
        rows["position_dependence"]["withheld"] = aux["position_note"]
    named = [k for k in SLIDING if rows[k]["named"]]
    effects = [_finite({"effect": k, "effect_size": rows[k]["effect_size"], "interval_95": rows[k].get("interval"),
                        "p": rows[k]["p"], "z": rows[k]["z"], "gain": 0.0, "gain_interval_90": [0.0, 0.0],
                        "held_out_error_baseline": None, "held_out_error_extended": None,
                        "extension": "none (no stick-slip to simulate)"}) for k in named]
    reason = (f"{c_n} stick-slip cycles found: the record does not show stick-slip (no drop faster than the rise "
              f"before it)" if c_n == 0 else
              f"only {c_n} stick-slip cycle{'s' if c_n > 1 else ''} found (a drop faster than the rise before it, "
              f"from a peak to a trough within one stroke): too few to diagnose (4 or more are needed: a longer "
              f"record)")
    if aux.get("stuck"):
        reason += (f"; the slider does not slide: in {aux['stuck']} of {aux['levels'].size} strokes x still rises "
                   f"over the stroke's last quarter at {np.nanmedian(aux['late_slope']):.2g} of its ramp's slope "
                   f"(per mm of drive travel), so the spring is still loading when the drive reverses (the static "
                   f"limit is not reached within a stroke: a longer stroke, or check --stiffness); no sliding level "
                   f"to read")
    elif aux["levels"].size >= 4:
        tr = aux["travel"][np.isfinite(aux["travel"])]
        rs = aux["ramp_slope"][np.isfinite(aux["ramp_slope"])]
        reason += (f"; steady sliding over {aux['levels'].size} strokes at a level of {aux['level']:.4g} mm "
                   f"(friction over stiffness)")
        if tr.size:
            reason += (f"; after each reversal x reaches 90 % of that level after {np.median(tr):.3g} mm of drive "
                       f"travel " + (f"(ramp slope {np.median(rs):.3g} mm of x per mm of travel: 1 would be a rigid "
                                     f"stick behind the given spring)" if rs.size else
                                     "(within a sample of the reversal: the ramp is not resolved)"))
        if named:
            reason += "; " + "; ".join(f"{k}: {rows[k]['effect_size']:+.3g} of the level, p = {rows[k]['p']:.2g}"
                                       for k in named)
    sliding = {"levels_mm": aux["levels"].tolist(), "stroke_sign": aux["sign"].tolist(),
               "presliding_travel_mm": aux["travel"].tolist(), "ramp_slope": aux["ramp_slope"].tolist(),
               "late_slope_over_ramp": aux["late_slope"].tolist(), "stuck": bool(aux.get("stuck"))}
    # one to three cycles are stick-slip too few to diagnose, not its absence: a label of their own
    return Diagnosis(effect="no_stick_slip" if c_n == 0 else "too_few_cycles", reason=reason, effects=effects,
                     evidence=_finite(rows),
                     sliding=_finite(sliding),
                     fn=fn or 0.0, fn_source=src, fn_data=fd, fn_data_se=fse, notes=notes, warnings=warnings,
                     n_cycles=c_n)


def _plot_data(pr, c, fn, g0, tsplit) -> dict:
    """What the report's plots draw, computed here (the report only draws):
    the record's slips by the reverse construction (sliding velocity,
    friction, branch) and the baseline trace's peaks and troughs."""
    _, s, F, br, _ = slip_friction(pr, c, fn)
    xb = g0["x_base"]
    cb = find_cycles(pr_like(pr, xb), fn) if xb is not None else None
    return {"pr": pr, "c": c, "x_base": xb, "x_ext": g0["x_ext"], "tsplit": tsplit, "fn": fn,
            "slips": (s, F, br), "base_extrema": None if cb is None else (cb.peak_i, cb.trough_i)}


def _load_of(rec: Record, pr, f: float):
    """The recorded normal force low-passed at EXT_LOWPASS f, for the slider
    whose friction follows it (:func:`.baseline.calibrate_fn`); None without
    a normal force, or with one that comes near zero or changes sign (no
    load to divide by)."""
    if not rec.y_is_force or pr.y is None:
        return None
    yl = lowpass(pr.y, pr.dt, EXT_LOWPASS * f)
    m = float(np.mean(yl))
    return yl if m != 0 and np.all(yl / m > 0.05) else None


#: a resonance is modelled as the sensor's when the slips' onsets ring in phase with what it makes of the
#: baseline's slips (:func:`_rig`), at this level
RIG_PHASE_ALPHA = 0.05


def _rig(pr: Prepared, c, fn: float, base: Params, notes: list, warnings: list):
    """A resonance of the rig or its sensor that rings after the arrests
    (:func:`.goodness.rig_mode`): (f, zeta, modelled) or None; modelled, the
    baseline's replicates are recorded through it (unit gain at 0 Hz: a
    sensor's own).

    A sensor's resonance rings at every slip's onset too, in the phase its
    response to the slip gives: the record's onset ringing (per slip,
    :func:`.goodness.onset_ringing`) projected on the mean of the baseline's
    recorded through it must be positive (one-sided t over the slips at
    RIG_PHASE_ALPHA).  A second mode of the rig need not ring so (a
    two-mass rig's onsets ring in the opposite phase): it is then said, and
    the replicates stay the 1-DoF slider's."""
    mode = rig_mode(pr, c, fn)
    if mode is None:
        return None
    f, z = mode["f"], mode["zeta"]
    why = None
    try:
        xs = simulate(pr, base.copy(rig_f=f, rig_zeta=z), fn)[0]
        cs = find_cycles(pr_like(pr, xs), fn)
    except LiengInputError:
        cs = None
    if cs is not None and c.n >= 3 and cs.n >= 3:
        w = int(min(np.median(c.trough_i - c.peak_i), np.median(cs.trough_i - cs.peak_i), round(2.5 / (f * pr.dt))))
        rec_on = onset_ringing(pr.x, c, pr.dt, f, z, w) if w >= 8 and w * pr.dt * f >= 1.0 else np.zeros((0, 2))
        mod_on = onset_ringing(xs, cs, pr.dt, f, z, w) if rec_on.shape[0] else np.zeros((0, 2))
        m = mod_on.mean(axis=0) if mod_on.shape[0] >= 3 else np.zeros(2)
        if rec_on.shape[0] >= 5 and np.hypot(*m) > 0:
            p = mean_above_zero(rec_on @ (m / np.hypot(*m)))
            if p > RIG_PHASE_ALPHA:
                why = (f"the slips' onsets do not ring in the phase a sensor's resonance gives them (p = {p:.2g}): a "
                       f"second mode of the rig, not modelled")
        else:
            why = "the slips are too short to tell a sensor's resonance from a second mode of the rig: not modelled"
    else:
        why = "the baseline recorded through it does not stick-slip: not modelled"
    head = (f"x rings after each arrest at {f:.4g} Hz (damping ratio {z:.2g}, p = {mode['p']:.2g} in each half of "
            f"the sticks)")
    if why is not None:
        warnings.append(head + ": " + why + "; it bends the slips' x'', so read the twin-branch evidence with care")
        return f, z, False
    notes.append(head + ": a resonance of the rig or its sensor (the slips' onsets ring as it makes the baseline's "
                 "ring), which the baseline's replicates are recorded through")
    return f, z, True


def diagnose(rec: Record, fn: float | None = None, *, fn_uncertainty: float = FN_UNCERTAINTY,
             replicates: int = 39, budget: float = REPLICATE_BUDGET, progress=None) -> Diagnosis:
    """Diagnose a record (see the package docstring and the stage modules).

    Parameters
    ----------
    rec : Record
        From :func:`read_record` (or :func:`record_from_arrays`).
    fn : float, optional
        Natural frequency of the tangential mode (Hz).  Estimated from the
        slips when not given; when given, taken to be within
        ``fn_uncertainty`` and checked against the slips.
    fn_uncertainty : float, optional
        The relative uncertainty of a given ``fn`` (default
        :data:`FN_UNCERTAINTY`, 5 %).  The slip-shape evidence (twin branch,
        a load read from a normal reading) is calibrated over it: an fn
        measured to 1 % (ringing of the slider, a hammer test) lets smaller
        effects through.  Between 0.1 % and 50 %.
    replicates : int, optional
        Baseline replicates for the calibration (fewer when ``budget``
        seconds run out).
    progress : callable, optional
        Called as progress(done, total) during the calibration.

    Returns
    -------
    Diagnosis
    """
    if fn is not None and not (math.isfinite(fn) and fn > 0):
        raise LiengInputError(f"--fn {fn}: the natural frequency must be a positive number (Hz)")
    if not (math.isfinite(fn_uncertainty) and 0.001 <= fn_uncertainty <= FN_UNCERTAINTY_MAX):
        raise LiengInputError(f"--fn-uncertainty {fn_uncertainty}: a relative uncertainty between 0.001 and "
                              f"{FN_UNCERTAINTY_MAX:g}")
    if fn is None and fn_uncertainty != FN_UNCERTAINTY:
        raise LiengInputError(f"--fn-uncertainty {fn_uncertainty}: it is the uncertainty of a given --fn; give --fn")
    # a speed without a sign: only --v0 (a reciprocating rig without its stage's position), or a speed readout
    # that is never negative (a drive that turns, its dwells at 0); the direction then from the force's side
    speed = None
    if not rec.drive_recorded and rec.vd.size and np.all(rec.vd == rec.vd[0]):
        speed = np.abs(rec.vd)
    elif rec.drive_recorded and rec.vd.size and np.all(rec.vd >= 0) and np.any(rec.vd > 0):
        speed = rec.vd
    side = drive_from_force(rec.x, 1.0) if speed is not None else None
    if side is not None:
        rec = dataclasses.replace(rec, vd=speed * side, notes=list(rec.notes), warnings=list(rec.warnings),
                                  drive_from_force=True)
    pr = prepare(rec)
    notes = list(rec.notes) + list(pr.notes)
    warnings = list(rec.warnings)
    if rec.drive_from_force and not rec.drive_recorded:
        notes.append(f"the force changes side over the record and no drive was recorded: the drive is taken to "
                     f"reverse where it does ({len(pr.strokes)} strokes at --v0 {float(speed[0]):g} mm/s: a "
                     f"reciprocating rig), each stroke starting where the spring starts over to the other side (a "
                     f"dwell before it is read as moving); give the stage's position to set the strokes and the "
                     f"dwells")
    elif rec.drive_from_force:
        notes.append(f"the drive column is never negative while the force changes side: a speed readout without "
                     f"its sign, read with the force's side as the direction ({len(pr.strokes)} strokes); give a "
                     f"signed velocity or the stage's position to set them")
    if not rec.drive_recorded and len(pr.strokes) == 1 and not rec.drive_from_force:
        neg, pos = force_sides(rec.x)
        if min(neg, pos) > REVERSING_SHARE:
            warnings.append(f"the force changes sign over long stretches ({100 * neg:.0f} % of the record below zero, "
                            f"{100 * pos:.0f} % above): a drive that reverses? With a constant drive (--v0) only the "
                            f"strokes in its direction are read as stick-slip: give the drive's position, or a signed "
                            f"v0 column")
    if rec.stiffness_unknown:
        k = _stiffness_from_sticks(pr)
        if k is None:
            raise LiengInputError(f"{rec.source}: a force record without --stiffness, and no sticks or reversal "
                                  f"ramps to read it from: give --stiffness (N/m)")
        pr.x = pr.x / k
        pr.quantum = pr.quantum / k
        rec.x = rec.x / k
        rec.stiffness = k
        notes.append(f"tangential stiffness estimated from the sticks: {rec.stiffness:.4g} {rec.stiffness_unit} (the force rises at "
                     f"stiffness x drive velocity while the slider sticks); give --stiffness to set it")
    if fn is not None:
        check_fn(rec, fn, f"--fn {fn:g} Hz", "--fn (Hz)")
        ph = head(pr, CALIBRATION_SAMPLES)     # (a fixed cost on a long record)
        dur = slip_seconds(ph, find_cycles(ph, None, retry=True))
        if dur is not None and dur * fn < SLIP_SHORTEST:
            warnings.append(f"the slips last {dur:.3g} s, {dur * fn:.2g} of a natural period at --fn {fn:g} Hz: a "
                            f"slip lasts about half a period (fn about {0.5 / dur:.3g} Hz): check --fn (Hz)")
    c0 = find_cycles(pr, fn, retry=True)
    span = stick_slip_span(pr, c0)
    if span is not None:
        # the baseline is fitted where the record stick-slips: a steady stretch before or after it (the drive
        # changed, a lubricant came in) has no cycle to predict, and its replicates would stick-slip there
        pr = crop(pr, span[0], span[1])
        c0 = find_cycles(pr, fn, retry=True)
        notes.append(f"no stick-slip in {span[2]}: the record is analysed from {pr.t[0]:.4g} to {pr.t[-1]:.4g} s, "
                     f"where it stick-slips")
    if len(pr.strokes) == 1 and c0.n >= 3 and float(np.median(pr.x[c0.peak_i])) <= 0:
        # a friction that reads below zero through its stick-slip while the drive runs one way: a sensor's offset
        # not tared (`haptic_phantom`'s six-axis cell, -0.37 N under a friction of +0.2 N), as no friction that
        # pushes the slider on is the 1-DoF model's: its baseline was read flat below zero, and its replicates'
        # peaks scattered 25 times the record's.  The level is read from the lowest trough, one drop above zero
        # (a constant added to the friction is another single-valued characteristic: the stick-slip is the same)
        shift = c0.amplitude(pr.x) - float(np.percentile(pr.x[c0.trough_i], 2))
        pr.x = pr.x + shift
        rec.x = rec.x + shift * pr.strokes[0].sign
        notes.append(f"the friction reads below zero while the drive runs one way (its peaks at "
                     f"{float(np.median(pr.x[c0.peak_i])) - shift:.4g} mm): a sensor's offset not tared? Read "
                     f"{shift:.4g} mm higher, its lowest trough one drop above zero")
    fd, fse, nsl = estimate_fn(pr, c0, fn) if c0.n >= 3 else (None, None, 0)
    if fd is not None and not (fd * pr.dt < 0.2):
        fd = None
    nofn = None
    if fn is None:
        if c0.n < 4 and fd is None:
            return _in_units(_no_stick_slip(pr, c0.n, notes, warnings), rec)
        if fd is not None:
            c1 = find_cycles(pr, fd, retry=True)
            fd2, fse2, _ = estimate_fn(pr, c1, fd) if c1.n >= 3 else (None, None, 0)
            if fd2 is not None:
                fd, fse = fd2, fse2
        dur, u_read = slip_seconds(pr, c0, spread=True)
        if dur is not None and c0.light * pr.dt >= dur:
            # the slips were found only through a window as long as they last (:func:`.segment._light`, on a
            # noisy record): their duration, and their arcs, are the window's as much as theirs (the blind
            # edge-case test's records under noise of 30-50 % of the drop read fn 30-50 % off, a Coulomb
            # slider's 120 % off)
            amp = c0.amplitude(pr.x)
            share = f"white noise of {100 * noise_level(pr.x) / amp:.0f} % of the drop" if amp > 0 else "white noise"
            raise LiengInputError(f"{rec.source}: {share}: the slips are found only through a window of "
                                  f"{c0.light * pr.dt:.3g} s, as long as they last ({dur:.3g} s), and cannot fix "
                                  f"the natural frequency: give --fn (Hz)")
        if dur is not None and FN_UNCERTAINTY_DURATION + u_read > FN_UNCERTAINTY_MAX:
            # the noise leaves the slips' falls open by more than the widest uncertainty fn is read with
            # (:func:`.segment.slip_durations`: the two readings of each crossing, nearest and farthest from the
            # fall's middle, half a duration apart or more): an fn "known to +- 50 %" is none
            amp = c0.amplitude(pr.x)
            share = f"white noise of {100 * noise_level(pr.x) / amp:.0f} % of the drop" if amp > 0 else "white noise"
            raise LiengInputError(f"{rec.source}: {share}: read through it, the slips' falls last {dur:.3g} s "
                                  f"+- {100 * u_read:.0f} % and cannot fix the natural frequency: give --fn (Hz)")
        f0 = fd if fd is not None else (0.5 / dur if dur is not None else None)
        fcal = None
        # a slip lasts half a natural period or longer (friction falling with speed lengthens it): when
        # the baseline at the first guess does not stick-slip, start higher
        loaded = False
        for m in ((1.0, 1.3, 1.7) if f0 is not None else ()):
            yl = _load_of(rec, pr, m * f0)
            fcal, loaded = calibrate_fn(pr, m * f0, ylow=yl), yl is not None
            if fcal is not None:
                break
        if fcal is not None and fcal * pr.dt < 0.2:
            # the law's shape (FN_UNCERTAINTY_DURATION) and how far the record's noise leaves the slips' falls
            # open (:func:`.segment.slip_durations`: 0 on a clean record; at most FN_UNCERTAINTY_MAX, above)
            u_fn = FN_UNCERTAINTY_DURATION + u_read
            fn_used, src = fcal, "estimated from the slips' duration"
            who = ("baseline's slips, their friction following the recorded normal force," if loaded else
                   "baseline's slips")
            notes.append(f"fn estimated from the slips: {fcal:.4g} Hz is the natural frequency at which the "
                         f"{who} last as long as the record's (+- {100 * u_fn:.0f} %"
                         + (f", of which {100 * u_read:.0f} % the noise leaves their falls open" if u_read >= 0.005
                            else "")
                         + (f"; their arcs alone say {fd:.4g} Hz" if fd is not None else "") + ")")
        elif fd is not None:
            fn_used, src = fd, "estimated from the slips' arcs"
            # (at most FN_UNCERTAINTY_MAX, the widest --fn-uncertainty)
            u_fn = min(max(FN_UNCERTAINTY_DURATION, 3 * (fse or 0.0) / fd), FN_UNCERTAINTY_MAX)
        else:
            raise LiengInputError(f"{rec.source}: the natural frequency cannot be fixed from the slips "
                                  f"({nsl} usable): give --fn (Hz)")
        nofn = (f"without --fn the natural frequency is known to +- {100 * u_fn:.0f} % only, and an error in it "
                f"bends the reverse construction (its two branches part like a twin branch, the friction follows x "
                f"like a load): give --fn")
    else:
        fn_used, src, u_fn = float(fn), "given (--fn)", fn_uncertainty
        f0 = fd if fd is not None else fn
        fcal = calibrate_fn(pr, f0, ylow=_load_of(rec, pr, f0))
        if fcal is not None and abs(fcal / fn - 1.0) > FN_CHECK:
            warnings.append(f"the slips say fn = {fcal:.4g} Hz (the baseline's slips last as long as the record's "
                            f"there), {100 * (fcal / fn - 1):+.0f} % from --fn {fn:g}: check --fn (the slip-shape "
                            f"evidence assumes it within {100 * u_fn:g} %)")
    # the slip-shape evidence (twin, load) reads the slips as arcs of a free
    # oscillation at fn: withheld when they are not (heavily damped or
    # rate-dependent slips, or an fn far off)
    withheld = {}
    # without --fn the twin branch is withheld: an error of fn within what the slips fix (15 %) parts the
    # branches by more than ch. 4.1's loops.  A load read from a normal reading is tested at the least
    # favourable fn within it (its reading at both edges, :func:`.evidence.fn_readings`): an fn error
    # imitates a load only as far as the reading follows x'' in the slips, which a load along the track or
    # a course in time does not (a recorded normal force is read directly, not through the slips' shape)
    if nofn:
        withheld = {"twin_branch": nofn}
        read_at_edges = rec.y is not None and not rec.y_is_force
        warnings.append(nofn + " (the twin-branch evidence is withheld" +
                        ("; the load read from the normal channel is tested at the least favourable fn within it"
                         if read_at_edges else "") + ")")
    # (slips that fit no single arc frequency, with fn given, are read as they are: the evidence
    # assumes no arc shape, and the replicates carry what the shape does to it)
    if not withheld and nsl >= 3 and fd is not None and abs(fd / fn_used - 1.0) > SLIPS_OFF:
        # Slips that swing faster than fn say that fn is given too low, and the reverse construction at too
        # low an fn parts its branches exactly like a twin branch (F = x + x''/wn**2 overweights x''): the
        # twin evidence is withheld.  Slips that swing slower are what a twin branch itself does (friction
        # that grows through the slip) or what too high an fn looks like, and too high an fn parts the
        # branches the other way (the one-sided test cannot be faked by it): read, and said.
        # (the load is still read: a load that follows the motion changes the stiffness the slips swing on,
        # so slips off fn are what it does; its evidence is the friction's relation with the measured channel)
        why = f"the slips swing at {fd:.4g} Hz, not near fn = {fn_used:.4g} Hz"
        if fd > fn_used:
            withheld = {"twin_branch": why}
            warnings.append(why + ": the twin-branch evidence is withheld (check --fn; a load that follows the "
                                  "motion also moves the slips' frequency)")
        else:
            warnings.append(why + " (check --fn): slower, as a friction that grows through each slip (a twin "
                                  "branch above), one that lags the speed (below) or a load that follows the motion "
                                  "makes them; the twin-branch evidence is read by the reverse construction at fn")
    if not withheld and fn is not None and fcal is not None and fcal / fn_used - 1.0 > SLIPS_OFF:
        # the same reading by the slips' duration rather than their arcs' frequency: the baseline's slips at
        # the given fn outlast the record's as a baseline at a higher fn would not (a load that stiffens the
        # slider as it moves, or fn given too low).  A twin branch shortens them too, but by less: a step of
        # 30 % of the drop where the speed peaks (ch. 4.1's largest loops) cuts the slip's second arc, about a
        # higher centre, to make the whole 14 % shorter, as the baseline's would be at 1.17 fn
        why = (f"the slips last as long as the baseline's at fn = {fcal:.4g} Hz, {100 * (fcal / fn_used - 1):.0f} % "
               f"above fn = {fn_used:.4g} Hz")
        withheld = {"twin_branch": why}
        warnings.append(why + ": the twin-branch evidence is withheld (check --fn; a load that follows the motion "
                              "also shortens the slips)")
    # and the other way: slips that outlast the baseline's at the given fn as the baseline's would only at an fn
    # a fifth lower (the given one a quarter above it: SLIPS_OFF) say that fn is given too high, which parts the
    # branches the other way, like a twin below: its side below is then not named (a branch below lengthens the
    # slips too, but by less: the bench's 13 twins below last as long as the baseline's within 20 %)
    below_off = None
    if fn is not None and fcal is not None and fcal / fn_used < 1.0 / (1.0 + SLIPS_OFF):
        below_off = (f"the slips last as long as the baseline's at fn = {fcal:.4g} Hz, "
                     f"{100 * (1 - fcal / fn_used):.0f} % below fn = {fn_used:.4g} Hz (too high an fn parts the "
                     f"branches like a twin below)")
    if 1.0 / (fn_used * pr.dt) < 15:
        warnings.append(f"{1.0 / (fn_used * pr.dt):.1f} samples per natural period: the slip-shape evidence is "
                        f"weak below about 20")
    c = find_cycles(pr, fn_used, retry=True)
    if c.n < 4:
        return _in_units(_no_stick_slip(pr, c.n, notes, warnings, fn_used, src, fd, fse), rec)
    ratio = max((stick_ratios(pr, cc)[1] for cc in (c0, c)), key=np.size)
    if ratio.size >= 2 and np.median(ratio) > STICK_FASTEST:
        warnings.append(f"x rises at {np.median(ratio):.3g} times the drive velocity in the sticks (median over "
                        f"{ratio.size}): a stuck slider loads the spring at the drive velocity, no faster; check "
                        f"--v0, --stiffness and the record's units (the baseline is fitted as given)")
    elif ratio.size >= 2 and 0 < np.median(ratio) < STICK_SLOWEST:
        warnings.append(f"x rises at {np.median(ratio):.3g} times the drive velocity in the sticks (median over "
                        f"{ratio.size}): a stuck slider loads the spring at the drive velocity, and a creeping one "
                        f"not five times slower; check --v0, --stiffness and the record's units (the baseline is "
                        f"fitted as given)")
    base_all = fit_baseline(pr, c, fn_used)
    mode = _rig(pr, c, fn_used, base_all, notes, warnings)
    rig = mode[:2] if mode is not None and mode[2] else None
    if pr.y is not None:
        base_all.y_c = y_on_motion(pr.x, c.v, pr.y)
    # the slips are arcs of a free oscillation near fn when their own frequency was found within 25 % of it
    arcs = fd is not None and abs(fd / fn_used - 1.0) <= 0.25
    # a recorded drive that reverses: its modulation is read on the drive itself (:func:`.segment.steady_drive`)
    drive_read = pr.vd_steady is not None
    if drive_read:
        notes.append("the drive is recorded and reverses: a modulation of its speed is read on the drive itself, "
                     "against its steady course (at each place on the track, the median speed of the strokes of "
                     "that direction run at a like speed), not on the sticks, which follow whatever it does")
    st, se, aux = statistics(pr, c, fn_used, y_is_force=rec.y_is_force, arcs=arcs)
    # the evidence is calibrated by replicates recorded through the rig's resonance where one rings; it may be
    # a second mode of the rig, which shapes the slips otherwise than a sensor does: the baseline without it is
    # the alternative null, and a statistic the two nulls part on is tested against the least favourable
    # (:func:`.decide.calibrate`).  (The predictions that judge the gain stay the 1-DoF slider's: recorded
    # through the resonance they lost the gains of a two-mass rig's twin branches, 0.5 to 0.2-0.35.)
    base_null = base_all if rig is None else base_all.copy(rig_f=rig[0], rig_zeta=rig[1])
    null, nrep = null_replicates(pr, base_null, fn_used, u_fn, B=replicates, budget=budget, progress=progress,
                                 y_is_force=rec.y_is_force, arcs=arcs)
    null_alt = null_replicates(pr, base_all, fn_used, u_fn, B=max(replicates * 2 // 5, 5), budget=0.4 * budget,
                               seed=1, y_is_force=rec.y_is_force, arcs=arcs)[0] if rig is not None else None
    # the twin-branch evidence is calibrated by replicates whose slips are like the record's: where the
    # record's slips outlast the baseline's (by over SLIP_MATCH of it and 3.5 of its spread) its side above is
    # withheld: longer slips are what a decelerating branch below the accelerating one makes (the slip runs on
    # over a lower friction), the effect itself, and the side below is read (named only where nothing else
    # accounts for it, :func:`.decide.below_accounted`)
    dur, dn = aux["gof"]["slip_duration"], null.get("slip_duration", np.array([]))
    dn = dn[np.isfinite(dn)]
    longer = None
    if dn.size >= 5 and not withheld:
        m0, s0 = float(np.mean(dn)), float(np.std(dn, ddof=1))
        if dur - m0 > max(SLIP_MATCH * m0, 3.5 * s0):
            longer = (f"the baseline does not reproduce the slips (they last {dur:.3g} half natural periods, its "
                      f"replicates' {m0:.3g} +- {s0:.2g})")
            warnings.append(longer + ": a twin branch above is not read (it shortens the slips); below, as a friction "
                                     "that lags the speed lengthens them, it is (a load that follows the motion, "
                                     "itself a candidate, also changes the slips' duration)")
    # a second mode that rings after each arrest bends the slips' x'' too: said, not acted on (withholding
    # the twin there cost as many twin branches as it saved false alarms on a two-mass generator)
    ring = [m for m in misfit(aux["gof"], null, RIG) if m[1] > m[2]]
    if ring and mode is None:
        warnings.append(f"x rings after each arrest ({ring[0][1]:.3g} D against {ring[0][2]:.3g} in the baseline's "
                        f"replicates, whose slider is still in stick): a second mode of the rig, which the 1-DoF "
                        f"baseline does not have; it also bends the slips' shape, so read the twin-branch evidence "
                        f"with care")
    # the band an error of fn within u_fn makes, read on the record itself (the replicates' 1-DoF slider need
    # not follow fn as the record does)
    if rec.zero_unknown:
        withheld = {**withheld, "direction_asymmetry": "the extension's zero is not in the record (two positions "
                                                       "whose origins it does not give, on a drive both ways)"}
    rd = fn_readings(pr, c, fn_used, u_fn, aux["D"], aux.get("ylow"), rec.y_is_force, arcs, skip=withheld)
    rows = decide(st, se, null, p_own=aux.get("p_own"), withheld=withheld, u_fn=u_fn, sizes=aux.get("sizes"),
                  fn_readings=rd, null_alt=null_alt)
    # the extensions' load: a normal *force* drives the friction at every frequency the slider follows, so
    # it is low-passed at 4 fn there (the evidence's 1.5 fn keeps a triggering line out of the load's
    # reading, which the extension need not); a normal reading keeps the evidence's channel
    aux_ext = {**aux, "ylow": lowpass(pr.y, pr.dt, EXT_LOWPASS * fn_used) if rec.y_is_force else aux.get("ylow")}
    warnings.extend(r["beyond_model"] for r in rows.values() if "beyond_model" in r)
    tr = rows["triggering"]
    if tr.get("line_significant") and tr.get("size_shown") is False:
        p_in = f", p = {tr['p_size']:.2g}" if "p_size" in tr else ""
        warnings.append(f"a line at {aux['f_tr']:.4g} Hz is significant, but the slips carry no load modulation "
                        f"distinguishable from 0 there ({tr['effect_size']:.3g}, 95 % interval {tr['interval'][0]:.2g} "
                        f"to {tr['interval'][1]:.2g}{p_in}): a vibration the stuck slider shows too (the sensor, "
                        f"the frame), or slips sampled too coarsely to measure it; not named")
    for k in CANDIDATES:
        r = rows[k]
        size = r["effect_size"] if k in ONE_SIDED else abs(r["effect_size"])
        un = fn_needed(r, u_fn, nrep) if size >= MARGIN[k] else None
        if un is not None:
            r["fn_uncertainty_needed"] = un
            warnings.append(f"{k} reads {r['effect_size']:+.3g} (over the drop), but an error of fn within the stated "
                            f"+- {100 * u_fn:.3g} % can make up to {r['fn_band']:.3g}: not named; with fn known to "
                            f"+- {100 * un:.2g} % (--fn-uncertainty {un:.2g}) the same reading would be significant")
    # a twin branch read below 0 (the decelerating branch below the accelerating one: a friction that lags the
    # speed, frictional memory, a film's thermal lag) is what a load that rises with x, a triggering or a
    # modulated drive also make of the slips (stop 59's bench read it on 28 load, 15 triggering and 8 drive
    # records, 3 effect-free): named only where nothing else accounts for it (:func:`.decide.below_accounted`).
    # (Stop 58 named it beside the others: that cost 23 load records named right, now twin, for 7 twins found.)
    tw = rows["twin_branch"]
    if longer is not None and tw["named"] and tw["effect_size"] > 0:
        tw["named"] = False
        tw["not_named"] = longer + ": a branch above shortens the slips, these outlast the baseline's"
    if tw["named"] and tw["effect_size"] < 0:
        size = abs(tw["effect_size"])
        why, load_hi = below_accounted(rows, pr.y is not None)
        why = below_off or why
        tw["below"] = {"p": float(tw["p"]), "effect_size": float(tw["effect_size"])}
        head_ = (f"the slips read a decelerating branch {size:.3g} D below the accelerating one (p = {tw['p']:.2g}, "
                 f"beyond what an error of fn within +- {100 * u_fn:.3g} % makes): a friction that lags the speed "
                 f"(frictional memory, a lubricant film's or a melt film's thermal lag)")
        if why is not None:
            tw["named"] = False
            tw["not_named"] = why
            warnings.append(head_ + f", or a load that rises with x; not named: {why}")
        elif pr.y is None:
            notes.append(head_ + "; a load that rises with x bends the slips alike, and the record has no normal "
                                 "channel to tell the two apart")
        else:
            notes.append(head_ + f"; the load the recorded normal channel carries accounts for at most "
                                 f"{max(load_hi, 0.0):.2g} of the drop (its 95 % interval's upper end)")
    for k in CANDIDATES:
        r = rows[k]
        size = r["effect_size"] if k in ONE_SIDED else abs(r["effect_size"])
        if r.get("alt_band", 0.0) > 0 and size >= MARGIN[k] and not r["significant"]:
            warnings.append(f"{k}: its statistic departs by {r['statistic'] - r['null_mean']:+.3g} from the "
                            f"baseline's replicates recorded through the resonance at {rig[0]:.4g} Hz, by "
                            f"{r['statistic'] - r['alt_null_mean']:+.3g} from those without it (a second mode of the "
                            f"rig shapes the slips otherwise than a sensor does): not named")
    dpl, fd_row = aux.get("drift_per_load"), rows["friction_drift"]
    if dpl is not None and rows["load_variation"]["named"] and fd_row["named"] and \
            not (dpl[1] is not None and dpl[1] <= fd_row["holm_level"] and dpl[0] >= MARGIN["friction_drift"]):
        # the friction level drifts with a recorded load that it follows: the load is the cause
        fd_row["named"] = False
        fd_row["accounted_for"] = (f"by the recorded normal channel: the level less its relation with the channel "
                                   f"changes by {dpl[0]:.3g} of the drop"
                                   + (f" (p = {dpl[1]:.2g})" if dpl[1] is not None else ""))
        notes.append("friction_drift is not named: the friction level drifts with the recorded normal channel, "
                     "which it follows (load_variation); " + fd_row["accounted_for"])
    named = [k for k in CANDIDATES if rows[k]["named"]]
    named.sort(key=lambda k: -abs(rows[k]["effect_size"]) / MARGIN[k])

    # fit on the training part, judge on the rest: the record's end (models fitted on its first 70 %) and,
    # where it has enough cycles, its beginning (models fitted on its last 70 %) and, on a short record, its
    # middle (models fitted on the rest)
    parts = folds(pr, c)
    tsplit = parts[0][1]
    fold_models = []
    for lo, hi, a, b_ in parts:
        # (the training part: [lo, hi) less the held-out [a, b_), which lies beside it or within it)
        sel = window(pr.t[c.peak_i], (lo, hi, a, b_))
        cf = subset(c, sel)
        b = fit_baseline(pr, cf, fn_used) if cf.n >= 3 else base_all
        b.y_c = base_all.y_c
        fold_models.append((b, Judge(pr, c, fn_used, lo, hi, aux_ext["ylow"], gap=(a, b_)), (lo, hi, a, b_),
                            _train_trough(pr, c, sel)))
    base = fold_models[0][0]
    effects = []
    fitted = {}
    trended = {}
    for k in named:
        # the extension starts from the effect's size over the baseline's replicates (the statistic less
        # what the baseline itself gives), not from the raw statistic
        stk = {**st, k: rows[k]["effect_size"], k + "_raw": st[k]}
        fits, first, formed = [], None, []
        for j, ((b, train, win, trough), part) in enumerate(zip(fold_models, parts)):
            # judged against the baseline with the training part's drift in its level, when it has one (a
            # sensor's drift is no effect's); not a drift of the friction nor a load's course along the record
            # (a tilted track, a cam), which move the level as a drift does: their own extensions carry it
            if k not in LEVEL_EFFECTS:
                if j not in trended:
                    trended[j] = level_trend(b, pr, c, win)
                b = trended[j]
            if k == "drive_modulation" and drive_read:
                # a recorded drive whose speed wanders: the baseline already runs on it; the comparison is
                # the same model on the drive made steady (the strokes' median speed along the track)
                # (the training errors only for the first fold's, the one reported: each simulates its part)
                steady = b.copy(drv_steady=True)
                fits.append((part[2], part[3], steady, b))
                formed.append(True)
                first = first or (b, train.error(b), train.error(steady), [b], steady)
                continue
            res = _extend(k, b, train, pr, c, fn_used, stk, aux_ext, win, trough)
            fits.append((part[2], part[3], b, res[0]))
            formed.append(bool(res[3]))
            first = first or (*res, b)
        # a fold whose training part cannot form the extension at all (too few sticks to read an ageing
        # law on) holds nothing out for it: the gain is judged on the folds that formed one (an extension
        # formed but no better than the baseline on its training part stays in, as the baseline itself)
        if any(formed) and not all(formed):
            fits = [f for f, ok in zip(fits, formed) if ok]
        # the first fold's extension is the one reported (fitted on the record's first 70 %)
        ext, e_tr, e_train0, cands, b0 = first
        g = gain_folds(pr, c, fn_used, fits, aux_ext["ylow"])
        # how much the extension explains of the training part: ranks the named effects
        imp = 1.0 - e_tr / e_train0 if e_train0 > 0 and math.isfinite(e_train0) else 0.0
        r = rows[k]
        recorded_drive = k == "drive_modulation" and drive_read
        ext = base if ext is b0 or recorded_drive else ext
        fitted[k] = (ext, g, imp, bool(cands))
        effects.append(_finite({"effect": k, "effect_size": r["effect_size"], "interval_95": r.get("interval"),
                                "p": r["p"], "z": r["z"], "gain": g["gain"], "gain_interval_90": g["interval"],
                                "held_out_error_baseline": g["e0"], "held_out_error_extended": g["e1"],
                                "gain_explainable": g["gain_explainable"],
                                "gain_explainable_interval_90": g["interval_explainable"],
                                "held_out_scatter_share": g["scatter_share"],
                                "training_improvement": imp,
                                "baseline_offset_trend_per_s": b0.offset,
                                "extension": "the recorded drive, against the same model on the drive made "
                                "steady (each direction's median stroke speed along the track)" if recorded_drive
                                else "fitted" if ext is not base else
                                ("none better than the baseline on the training part" if cands else
                                 "none available")}))
    first = rivals(pr, base, fitted, fn_used, u_fn, st, rows, named, effects, notes, rec.y_is_force, arcs,
                   aux_ext["ylow"], replicates, budget)
    # named = detected and confirmed by prediction: an extension that does not predict the held-out cycles
    # better than the baseline leaves the effect detected, not named (a load read from a normal force is
    # its own evidence)
    detected = []
    for e in list(effects):
        k = e["effect"]
        why = unconfirmed(fitted[k][1], fitted[k][3], direct=(k == "load_variation" and rec.y_is_force)
                          or (k == "drive_modulation" and drive_read))
        if why is None:
            continue
        rows[k]["named"] = False
        rows[k]["not_confirmed"] = why
        named.remove(k)
        effects.remove(e)
        detected.append({**e, "why_not_named": why})
    # the primary effect: the one whose extension explains most of the training part (of a twin branch and a
    # load that neither survive the other, the one that accounts for the other better)
    named.sort(key=lambda k: -fitted[k][2])
    if "load_variation" in named and "twin_branch" in named:
        if first is not None:
            i, j = sorted(named.index(k) for k in RIVALS)
            named[i], named[j] = first, next(k for k in RIVALS if k != first)
        notes.append("load_variation and twin_branch are both named: a load that follows the motion bends the "
                     "slips as a twin branch does (the friction rises or falls through each slip with the load), "
                     "so one may stand for the other; the first is "
                     + ("the one that accounts for the other better" if first is not None else
                        "the one whose extension explains more of the training part"))
    effects.sort(key=lambda e: named.index(e["effect"]))
    if ("friction_drift" in named or any(e["effect"] == "friction_drift" for e in detected)) and rec.highpass is None:
        # a sensor that drifts moves the whole record as a drifting friction level does
        force = rec.stiffness is not None or rec.stiffness_unknown
        warnings.append("the friction level drifts in this record; a sensor that drifts moves it alike (a bridge's "
                        "offset with temperature" + (", an AC-coupled force cell's output sinking towards zero: a "
                        "piezoelectric cell's charge amplifier is a high-pass, which --highpass TAU undoes" if force
                        else "") + "): check the sensor before reading it as the friction's")
    primary_ext, primary_gain = (fitted[named[0]][0], fitted[named[0]][1]) if named else (base, None)
    g0 = primary_gain or gain_folds(pr, c, fn_used, [(p[2], p[3], m[0], m[0]) for p, m in zip(parts, fold_models)],
                                    aux_ext["ylow"])
    det = "; ".join(f"{e['effect']} is significant (size {e['effect_size']:+.3g}, margin {MARGIN[e['effect']]}, "
                    f"p = {e['p']:.2g}) but {e['why_not_named']}" for e in detected)
    if named:
        effect = named[0]
        reason = "; ".join(f"{k}: size {rows[k]['effect_size']:+.3g} (margin {MARGIN[k]}), p = {rows[k]['p']:.2g}"
                           for k in named) + f" (Holm, family-wise {ALPHA})"
    elif nrep < MIN_REPLICATES:
        # nothing could be calibrated: "none" would say the baseline explains the record
        effect = "unexplained"
        reason = (f"the fitted baseline does not stick-slip like the record: only {nrep} of its replicates (up to "
                  f"{replicates} are run) showed three cycles or more, so no evidence could be calibrated (check "
                  f"--fn, --stiffness and the record's units)")
    elif misfit(aux["gof"], null):
        effect = "unexplained"
        reason = ("the baseline misses beyond its noise and no candidate accounts for it: " +
                  "; ".join(f"{k} {v:.3g} in the record against {m:.3g} in the baseline's replicates"
                            for k, v, m in misfit(aux["gof"], null)))
        if detected:
            reason += "; " + det
    elif detected:
        effect = "none"
        reason = "no effect named: " + det
    else:
        effect = "none"
        best = min((k for k in CANDIDATES if rows[k]["applicable"]), key=lambda k: rows[k]["p"], default=None)
        reason = ("no candidate both significant and above its relevance margin: the baseline explains the record "
                  "within its noise" + (f" (smallest p: {best}, {rows[best]['p']:.2g})" if best else ""))
    if named and not g0.get("parts"):
        warnings.append(f"the gain is not measured: {c.n} cycles leave none to hold out (gain 0 in the outputs); "
                        f"{named[0]} is named on its calibrated evidence alone")
    if nrep < 10:
        warnings.append(f"only {nrep} baseline replicates could be analysed: the calibration is coarse")
    creep = {"creep_before_slip": {"record": st["creep"], "record_se": se["creep"],
                                   "meaning": "1 - stick velocity in the last fifth of the rise / in its middle",
                                   "baseline_c0": base.creep0, "baseline_c1": base.creep1,
                                   "baseline_m": base.creep_m}}
    gof = {k: {"record": aux["gof"][k],
                                   "replicates_mean": float(np.mean(null[k])) if null[k].size else None,
                                   "replicates_sd": float(np.std(null[k])) if null[k].size > 1 else None}
                               for k in aux["gof"]}
    gof.update(creep)
    if named and detected:
        notes.append("not named: " + det)
    return _in_units(Diagnosis(effect=effect, reason=reason, effects=effects, detected=detected,
                               evidence=_finite(rows),
                     goodness=_finite(gof),
                     fn=fn_used, fn_source=src, fn_uncertainty=u_fn,
                     fn_data=fd, fn_data_se=fse, baseline=base, extended=primary_ext,
                     baseline_error=g0["e0"], extended_error=g0["e1"], gain=g0["gain"] if named else 0.0,
                     gain_interval=g0["interval"] if named else [0.0, 0.0], n_cycles=c.n, n_replicates=nrep,
                     drop=aux["D"], notes=notes, warnings=warnings,
                     plot=_plot_data(pr, c, fn_used, g0, tsplit)), rec)
