"""``lieng cycles``, ``sweep``, ``map``, ``synth``, ``figures`` and ``twodof``: the modern analyses."""

from __future__ import annotations

import math
from pathlib import Path

from lieng.errors import LiengInputError

from lieng.cli.common import _map_plot


def _deck_char(args):
    from lieng.programs import read_deck

    deck = read_deck(args.deck, program=args.program)
    return deck, deck.xchl[: deck.n], deck.ychl[: deck.n]


def _cycles(args) -> int:
    from lieng.analysis.cycles import find_cycles
    from lieng.io.outputs import dumps_json

    deck, x, y = _deck_char(args)
    res = find_cycles(x, y, mode=args.mode, dtheta=deck.dtheta, lookup=args.lookup)
    if args.json:
        print(dumps_json(res.to_json(), indent=2))
    else:
        print(f"{args.deck}: mode {args.mode}; equilibrium at X = {res.equilibrium:.6g}; the origin is "
              f"{'stable' if res.origin_stable else 'unstable'}")
        if not res.cycles:
            print("no limit cycle")
        for c in res.to_json()["cycles"]:
            print(f"  {c['kind']:>11} cycle: amplitude {c['amplitude']:.6g} mm (X from {c['x_left']:.6g} to "
                  f"{c['x_right']:.6g}), period {c['period']:.6g}")
    return 0


def _sweep(args) -> int:
    from lieng.analysis.cycles import parse_range, sweep_dmu, sweep_v0
    from lieng.io.outputs import dumps_json

    deck, x, y = _deck_char(args)
    if args.dmu is not None:
        fac = parse_range(args.dmu, "--dmu")
        if min(fac) <= 0:
            raise LiengInputError(f"--dmu {args.dmu}: the factors of dmu0 must be positive (at 0 the static peak's "
                                  f"points fall onto the kinetic minimum and the characteristic has no slope there)")
        res = sweep_dmu(x, y, fac, v0=args.at_v0, mode=args.mode, dtheta=deck.dtheta, lookup=args.lookup)
        head, unit, crit = "dmu0/dmu0_deck", "", "dmu_oc (self-sustained oscillation from)"
    else:
        res = sweep_v0(x, y, parse_range(args.v0, "--v0"), mode=args.mode, dtheta=deck.dtheta, lookup=args.lookup)
        head, unit, crit = "v0 (mm/s)", " mm/s", "v_oc (S.L.C. and U.L.C. merge)"
    if args.json:
        print(dumps_json(res.to_json(), indent=2))
    else:
        print(f"{head:>14} {'origin':>9} {'S.L.C. (mm)':>12} {'U.L.C. (mm)':>12}")
        for v, o, a, b in zip(res.v0, res.origin_stable, res.stable_amplitude, res.unstable_amplitude):
            fa = "-" if a is None else f"{a:.6g}"
            fb = "-" if b is None else f"{b:.6g}"
            print(f"{v:14.4g} {'stable' if o else 'unstable':>9} {fa:>12} {fb:>12}")
        print(f"{crit}: " + ("not in the range" if res.v_oc is None else f"{res.v_oc:.6g}{unit}"))
    return 0

def _map(args) -> int:
    from lieng.analysis.cycles import parse_range
    from lieng.analysis.executor import check_workers, open_executor
    from lieng.io.outputs import check_outdir, dumps_json, staged_outdir, write_csv
    from lieng.analysis.regime_map import AXES, REGIMES, check_grid, regime_map

    check_outdir(args.outdir, args.force)
    check_workers(args.workers, args.scheduler)
    axis, opt, text = ("dmu", "--dmu", args.dmu) if args.dmu is not None else ("slope", "--slope", args.slope)
    v0s, vals = parse_range(args.v0, "--v0"), parse_range(text, opt)
    deck, x, y = _deck_char(args)
    v0s, vals = check_grid(x, y, v0s, axis, vals, "--v0", opt)
    with open_executor(args.workers, args.scheduler, tasks=len(vals)) as ex:
        res = regime_map(x, y, v0s, **{f"{axis}s": vals}, mode=args.mode, dtheta=deck.dtheta, lookup=args.lookup,
                         executor=ex)
    col = AXES[axis][0]
    with staged_outdir(args.outdir, args.force) as tmp:
        write_csv(tmp / "map.csv", ["v0 [mm/s]", col, "regime", "regime_name", "table_2_iv_row", "origin",
                                    "slc_amplitude [mm]", "ulc_amplitude [mm]", "cycles"],
                  ((v, p, code, r.key, r.row, "stable" if o else "unstable", s, u, n)
                   for v, p, code, r, o, s, u, n in res.points()))
        write_csv(tmp / "v_oc.csv", [col, "v_oc [mm/s]"],
                  ((float(a), None if math.isnan(b) else float(b)) for a, b in zip(res.values, res.v_oc)))
        plots = [] if args.no_plots else [_map_plot(res, tmp, Path(args.deck).name)]
    if args.json:
        print(dumps_json(res.summary(), indent=2))
    elif not args.quiet:
        counts = res.counts()
        print(f"map {args.deck}: regimes of Table 2.IV at {res.v0.size} x {res.values.size} points (v0 {res.v0[0]:.6g} to {res.v0[-1]:.6g} "
              f"mm/s; {col} {res.values[0]:.6g} to {res.values[-1]:.6g}), mode {res.mode}")
        for r in REGIMES:
            if counts[r.key] or r.code < 4:
                print(f"  {r.label:<40}{counts[r.key]:>8} points")
        found = [(a, b) for a, b in zip(res.values, res.v_oc) if not math.isnan(b)]
        if found:
            print(f"v_oc (S.L.C. and U.L.C. merge) at {len(found)} of {res.values.size} values: "
                  + ", ".join(f"{b:.6g} mm/s at {a:.6g}" for a, b in (found if len(found) <= 3
                                                                       else [found[0], found[-1]])))
        else:
            print("v_oc (S.L.C. and U.L.C. merge): not in the range")
        print(f"wrote {Path(args.outdir) / 'map.csv'}, v_oc.csv" + "".join(f", {p.name}" for p in plots))
    return 0


def _synth(args) -> int:
    from lieng.io.outputs import check_outfile, replace_file
    from lieng.analysis.synth import MAX_CYCLES, synthesize

    out = check_outfile(args.output, args.force)
    if args.seed is not None and not 0 <= args.seed < 2**63:
        raise LiengInputError(f"--seed {args.seed}: a seed is an integer from 0 to 2**63-1")
    if not 1 <= args.cycles <= MAX_CYCLES:
        raise LiengInputError(f"--cycles {args.cycles}: from 1 to {MAX_CYCLES} cycles")
    if args.strength is not None and not (0 <= args.strength <= 10):
        raise LiengInputError(f"--strength {args.strength}: the effect's scale must be from 0 to 10 (1 = the default)")
    rec = synthesize(args.effect, args.seed, cycles=args.cycles, strength=args.strength)
    replace_file(out, rec.write_csv)
    if not args.quiet:
        extra = ""
        v0 = "" if rec.v0_col is not None else f" --v0 {rec.v0:.6g}"
        print(f"wrote {out} ({rec.t.size} samples); analyse with: lieng diagnose {out}{v0} --fn {rec.fn:.6g}{extra} "
              f"-o DIR")
    return 0


def _figures(args) -> int:
    from lieng.analysis.figures import figures
    from lieng.io.outputs import check_outdir, staged_outdir

    check_outdir(args.outdir, args.force)
    with staged_outdir(args.outdir, args.force) as tmp:
        paths = figures(tmp, cards=args.cards, only=[n for a in args.only for n in a.split(",") if n] if args.only else None)
    if not args.quiet:
        print(f"wrote {len(paths)} figure{'' if len(paths) == 1 else 's'} to {args.outdir}/: "
              + ", ".join(p.name for p in paths))
    return 0


#: the largest preload (N) of `lieng twodof`
PRELOAD_MAX = 10_000.0


def _twodof(args) -> int:
    from lieng.io.outputs import all_finite, check_outdir, dumps_json
    from lieng.analysis.twodof import T_END_MAX, T_END_MIN, compare, parse_reading, write_outputs

    if args.outdir is not None:
        check_outdir(args.outdir, args.force)
    if args.belt is not None and args.rpm is not None:
        raise LiengInputError("--belt and --rpm: give one of them (the belt velocity, or the disc speed)")
    if args.rpm is None:
        args.rpm = 0.1
    for name in ("preload", "rpm", "t_end"):
        v = getattr(args, name)
        if not (v > 0 and v < float("inf")):
            raise LiengInputError(f"--{name.replace('_', '-')} {v}: must be a positive number")
    if not T_END_MIN <= args.t_end <= T_END_MAX:
        raise LiengInputError(f"--t-end {args.t_end:g}: from {T_END_MIN:g} to {T_END_MAX:g} s (the steady state is read "
                              f"after the first {T_END_MIN / 2:g} s)")
    if args.preload > PRELOAD_MAX:
        raise LiengInputError(f"--preload {args.preload:g}: at most {PRELOAD_MAX:g} N (the paper's rig: 80 N)")
    if not 1 <= args.members <= 64:
        raise LiengInputError(f"--members {args.members}: from 1 to 64")
    reading = parse_reading(args.reading)
    if args.belt is not None and not (0 < args.belt < 1):
        raise LiengInputError(f"--belt {args.belt}: the belt velocity must be between 0 and 1 m/s")
    if args.belt is None and not reading.belt_speed(args.rpm) < 1:
        raise LiengInputError(f"--rpm {args.rpm:g}: the belt of reading {reading.name} must be slower than 1 m/s")
    res = compare(preload=args.preload, rpm=args.rpm, t_end=args.t_end, belt=args.belt, reading=reading,
                  members=args.members)
    if not all_finite(res):
        raise LiengInputError(f"--preload {args.preload:g}, --rpm {args.rpm:g}: the simulation leaves the range of "
                              f"the model (a non-finite result); use values nearer the paper's (80 N, 0.1 rpm)")
    if args.outdir is not None:
        from lieng.io.outputs import staged_outdir

        with staged_outdir(args.outdir, args.force) as tmp:
            write_outputs(res, tmp)
    if args.json:
        print(dumps_json(res, indent=2))
    else:
        pap = res.get("paper")
        print(f"dual-pin-on-disc, reading {res['reading']['name']}, Fn = {args.preload:g} N, belt "
              f"{res['belt_m_s']:.4g} m/s, {args.t_end:g} s, {res['members']} initial states; modal frequencies "
              + ", ".join(f"{f:.3f}" for f in res["modal_hz"]) + " Hz")
        print(f"{'':24}{'peak (deg)':>20}{'fluct (deg)':>20}{'freq (Hz)':>20}")
        if pap:
            for lab, r in (("paper, experiment", pap["experiment"]), ("paper, theory", pap["theory"])):
                print(f"{lab:24}{r['peak_deg']:20.3f}{r['fluct_deg']:20.3f}{r['dominant_hz']:20.3f}")

        def cell(st):
            return f"{st['median']:.3f} [{st['min']:.2f},{st['max']:.2f}]" if st["n"] else "-"

        print(f"{'2-DoF median [range]':24}{cell(res['peak_deg']):>20}{cell(res['fluct_deg']):>20}"
              f"{cell(res['dominant_hz']):>20}")
        for lab, r in (("1-DoF, constant N", res["onedof"]), ("1-DoF, C_N(t)", res["onedof_load_corrected"])):
            print(f"{lab:24}{r['peak_deg']:20.3f}{r['fluct_deg']:20.3f}{r['dominant_hz']:20.3f}")
        print("m2 lines (Hz, median): " + ", ".join(f"{ln['median']:.2f}" if ln["n"] else "-"
                                                    for ln in res["m2_lines_hz"]["lines"])
              + ("  (paper, Fig. 12: 0.68, 4.6, 5.26, 5.92, 6.58)" if args.preload == 80 else ""))
        rg = res["regimes"]["regular"]
        print(f"time in the regular regime: median {cell(rg)}; normal force std median "
              f"{cell(res['normal_force']['std'])} N")
        print("checks: " + ", ".join(f"{k} {'yes' if v else 'no'}" for k, v in res["checks"].items()))
    return 0
