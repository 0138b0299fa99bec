"""Stage 7 of ``lieng diagnose``: diagnosis.json (strict JSON), report.md
and the plots a tribologist reads: the trace with the slips marked, the
characteristic mu(v) from the reverse construction with both branches, the
cycle-by-cycle residuals of the baseline, and the evidence table."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from lieng.io.outputs import dumps_json, plot_name
from lieng.diagnose.decide import NOT_APPLICABLE
from lieng.diagnose.evidence import CANDIDATES
from lieng.diagnose.extend import METRIC

__all__ = ["write_outputs", "summary_lines", "PLOTS"]

PLOTS = ("trace.png", "characteristic.png", "residuals.png")


def _f(v, spec: str) -> str:
    """``v`` formatted with ``spec``, or ``n/a`` when it is missing or not finite."""
    try:
        v = float(v)
    except (TypeError, ValueError):
        return "n/a"
    return format(v, spec) if math.isfinite(v) else "n/a"


#: the answers that name no effect (no gain or extended trace to show)
NO_EFFECT = ("none", "no_stick_slip", "too_few_cycles", "unexplained")
#: the answers with no cycles to describe
NO_CYCLES = ("no_stick_slip", "too_few_cycles")


def _lu(d) -> str:
    """The unit of x (mm; a rotary record's twist in mrad)."""
    return getattr(d, "length_unit", "mm")


def summary_lines(d, source: str) -> list:
    """The terminal summary (also the head of report.md)."""
    gi = d.gain_interval or (None, None)
    out = [f"{source}: effect {d.effect}" + (f"; gain {_f(d.gain, '.2f')} (90 % interval {_f(gi[0], '.2f')} to "
                                              f"{_f(gi[1], '.2f')})" if d.effect not in NO_EFFECT
                                              else "")]
    out.append(f"  {d.reason}")
    if d.effect not in NO_CYCLES:
        out.append(f"  natural frequency {_f(d.fn, '.4g')} Hz ({d.fn_source}); {d.n_cycles} cycles; drop D = "
                   f"{_f(d.drop, '.4g')} {_lu(d)}")
    for w in d.warnings:
        out.append(f"  warning: {w}")
    for n in d.notes:
        out.append(f"  note: {n}")
    return out


def _effect_row(e: dict) -> str:
    """One effect's row of the gains table."""
    iv = e.get("interval_95") or [None, None]
    gi = e.get("gain_interval_90") or [None, None]
    return (f"| {e['effect']} | {_f(e['effect_size'], '+.4g')} | {_f(iv[0], '+.3g')} to {_f(iv[1], '+.3g')} | "
            f"{_f(e['p'], '.2g')} | {_f(e.get('held_out_error_baseline'), '.3g')} | "
            f"{_f(e.get('held_out_error_extended'), '.3g')} | {_f(e['gain'], '.3f')} | {_f(gi[0], '.2f')} to "
            f"{_f(gi[1], '.2f')} | {_f(e.get('held_out_scatter_share'), '.2f')} | "
            f"{_f(e.get('gain_explainable'), '.3f')} |")


def write_outputs(d, outdir, source: str, plots: bool = True) -> list:
    """Write diagnosis.json, report.md and (with ``plots``) the PNGs into
    ``outdir`` (a staged directory).  Returns the file names written."""
    out = Path(outdir)
    js = dumps_json(d.to_json(), indent=2)
    (out / "diagnosis.json").write_text(js + "\n", encoding="utf-8")
    written = ["diagnosis.json", "report.md"]
    lines = [f"# lieng diagnose: {source}", "", *[f"    {s}" for s in summary_lines(d, source)], ""]
    if d.evidence:
        lines += ["## Evidence", "",
                  "Each statistic against its distribution under the fitted baseline (parametric bootstrap, "
                  f"{d.n_replicates} replicates; fn drawn within its uncertainty); p one-sided for effects with a "
                  "direction (the twin branch both ways: each side one-sided, the better side's p doubled); Holm "
                  "over the candidates at family-wise 0.05; named = significant, at least the relevance margin and "
                  "confirmed by prediction (its extension's held-out gain above 0 at 90 %); "
                  "detected = the first two without the third.", "",
                  "| candidate | statistic | null mean | null sd | record se | effect size | z | p | margin | named |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for k in CANDIDATES:
            r = d.evidence.get(k)
            if not r or not r.get("applicable"):
                # a candidate whose evidence is withheld says why (no --fn, slips the baseline cannot calibrate)
                why = (r or {}).get("withheld")
                cell = f"withheld: {why}" if why and why != NOT_APPLICABLE else \
                    "not applicable to this record"
                lines.append(f"| {k} | {cell} | | | | | | | | |")
                continue
            lines.append(f"| {k} | {_f(r['statistic'], '.4g')} | {_f(r['null_mean'], '.4g')} | "
                         f"{_f(r['null_sd'], '.3g')} | {_f(r['se'] or 0, '.3g')} | {_f(r['effect_size'], '+.4g')} | "
                         f"{_f(r['z'], '.2f')} | {_f(r['p'], '.2g')} | {r['margin']} | "
                         f"{'**yes**' if r['named'] else ('detected' if r.get('not_confirmed') else 'no')} |")
        lines.append("")
    if d.goodness:
        lines += ["## Goodness of fit of the baseline", "",
                  "Features the baseline must reproduce whatever the effect (slip duration in half natural periods, "
                  "spread of the peaks over D, spread of the periods over their mean), record against the "
                  "baseline's replicates; a departure beyond the replicates with no candidate named is "
                  "`unexplained`.", "", "| feature | record | replicates mean | replicates sd |", "|---|---|---|---|"]
        for k, g in d.goodness.items():
            if "replicates_mean" not in g:
                continue
            f = [("-" if g[a] is None else f"{g[a]:.4g}") for a in ("record", "replicates_mean", "replicates_sd")]
            lines.append(f"| {k} | {f[0]} | {f[1]} | {f[2]} |")
        lines.append("")
    cr = d.goodness.get("creep_before_slip") if d.goodness else None
    if cr and cr.get("record") is not None:
        lines += [f"Creep before slip (part of the baseline's stick, ch. 2.3.1.1): the stick velocity in the last "
                  f"fifth of each rise is {100 * cr['record']:.1f} % below its middle (+- "
                  f"{100 * (cr['record_se'] or 0):.1f} %).", ""]
    if d.sliding and d.sliding.get("levels_mm"):
        lv = [v for v in d.sliding["levels_mm"] if v is not None]
        tr = [v for v in d.sliding["presliding_travel_mm"] if v is not None]
        lines += ["## Steady sliding, stroke by stroke", "",
                  f"* {len(lv)} strokes; sliding level (x over the second half of each stroke): median "
                  f"{np.median(lv):.4g} {_lu(d)}, spread {np.std(lv):.3g} {_lu(d)}",
                  f"* drive travel until x is 90 % of the way to that level after a reversal: median "
                  f"{np.median(tr):.4g} {_lu(d)}" if tr else "* no presliding ramp measured", ""]
    sections = (("Named effects and gains", d.effects,
                 [f"Metric: {METRIC}.", "",
                  "The held-out errors are in the metric's units (fractions of the drop D and of the mean period): "
                  "a baseline that already predicts the held-out cycles within the record's own scatter leaves "
                  "an extension nothing to gain, however real the effect (a load that follows the motion the same "
                  "way in every cycle is carried by the characteristic the baseline reads from the record). "
                  "Scatter: the share of the baseline's squared held-out error that is the record's own "
                  "cycle-to-cycle scatter (half the mean square difference of successive cycles' stick times, "
                  "peaks and troughs, at most either model's error variance), which no model removes; gain of "
                  "the rest: the gain on the squares less it."]),
                ("Detected, not named", d.detected,
                 ["Significant and above their margin, but their extension does not predict the held-out cycles "
                  "better than the baseline (the gain's 90 % interval not above 0): the record departs from the "
                  "baseline there, and this model of the effect does not account for it."]))
    for title, rows, intro in sections:
        if not rows:
            continue
        lines += [f"## {title}", "", *intro, "",
                  "| effect | size | 95 % interval | p | held-out error: baseline | extended | gain | 90 % interval "
                  "| scatter | gain of the rest |",
                  "|---|---|---|---|---|---|---|---|---|---|", *map(_effect_row, rows), ""]
    if d.baseline is not None:
        b = d.baseline
        lines += ["## Baseline (the thesis's 1-DoF model, fitted on the training part)", "",
                  f"* static limit FS = {b.fs:.5g} {_lu(d)}; relative velocity in stick (ch. 2.3.1.1) c0 = {b.creep0:.3g} "
                  f"of the drive, growing by c1 = {b.creep1:.3g} as (x / FS)^{b.creep_m:g} towards the static limit "
                  f"(creep before slip)",
                  f"* characteristic phi(s) (sliding velocity {_lu(d)}/s: friction/stiffness {_lu(d)}): " +
                  ", ".join(f"{s:.3g}: {f:.4g}" for s, f in zip(b.sg, b.fg)), ""]
    if plots and d.plot and d.plot.get("pr") is not None:
        _plots(d, out, source)
        names = [plot_name(n) for n in PLOTS]
        written += names
        lines += ["Plots: " + ", ".join(names) + ".", ""]
    (out / "report.md").write_text("\n".join(lines), encoding="utf-8")
    return written


def _plots(d, out: Path, source: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from lieng.programs.graf import finish

    pr, c = d.plot["pr"], d.plot["c"]
    cap = f"lieng diagnose {Path(source).name}: effect {d.effect}"
    t, x = pr.t, pr.x
    fig, ax = plt.subplots(figsize=(10, 4.8), dpi=120)
    ax.plot(t, x, color="k", lw=0.7, label="record")
    if d.plot.get("x_base") is not None:
        # (the primary effect's gain is judged against the baseline read through the level's trend, when the
        # training part's level drifts: the trace shows that baseline, and says so)
        trend = d.effects[0].get("baseline_offset_trend_per_s", 0.0) if d.effects and d.effect not in NO_EFFECT \
            else 0.0
        ax.plot(t, d.plot["x_base"], color="C0", lw=0.7, label="baseline (thesis 1-DoF)" + (
            f", its level drifting {trend:+.3g} {_lu(d)}/s as the training part's" if trend else ""))
    if d.effect not in NO_EFFECT and d.plot.get("x_ext") is not None:
        ax.plot(t, d.plot["x_ext"], color="C3", lw=0.7, label=f"extended ({d.effect})")
    ax.plot(t[c.peak_i], x[c.peak_i], "v", color="C1", ms=4, label="slip starts (peaks)")
    ax.axvline(d.plot["tsplit"], color="0.5", ls="--", lw=0.8)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel(f"spring extension x = friction / stiffness ({_lu(d)})")
    ax.set_title("Trace: record and models (dashed: start of the held-out part)")
    finish(fig, ax, cap, out / "trace.png")

    fig, ax = plt.subplots(figsize=(8, 5.6), dpi=120)
    s, F, br = d.plot["slips"]
    ax.plot(s[br < 0], F[br < 0], ".", ms=2, color="C0", label="accelerating half of the slips")
    ax.plot(s[br > 0], F[br > 0], ".", ms=2, color="C3", label="decelerating half of the slips")
    if d.baseline is not None:
        ax.plot(d.baseline.sg, d.baseline.fg, "-", color="k", lw=1.5, label="baseline characteristic phi(s)")
    ax.set_xlabel(f"sliding velocity s = v0 - x' ({_lu(d)}/s)")
    ax.set_ylabel(f"friction / stiffness F = x + x''/wn^2 ({_lu(d)})")
    ax.set_title("Characteristic during slip (reverse construction), both branches")
    finish(fig, ax, cap, out / "characteristic.png")

    fig, ax = plt.subplots(figsize=(9, 4.8), dpi=120)
    ax.plot(t[c.peak_i], x[c.peak_i], "o", ms=3, color="C1", label="record: peak")
    ax.plot(t[c.trough_i], x[c.trough_i], "o", ms=3, color="C2", label="record: trough")
    xb = d.plot.get("x_base")
    if xb is not None and d.plot.get("base_extrema") is not None:
        pk, tr = d.plot["base_extrema"]
        ax.plot(t[pk], xb[pk], "x", ms=4, color="C1", label="baseline: peak")
        ax.plot(t[tr], xb[tr], "x", ms=4, color="C2", label="baseline: trough")
    ax.axvline(d.plot["tsplit"], color="0.5", ls="--", lw=0.8)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel(f"x ({_lu(d)})")
    ax.set_title("Cycle by cycle: peaks and troughs, record (o) against the baseline (x)")
    finish(fig, ax, cap, out / "residuals.png")
