"""The ``lieng`` command line.

``lieng run lieng1 DECK -o OUTDIR`` runs a card deck as the 1971 program did
and writes the line-printer listing, the trajectories as CSV and the plots.
Bad input prints one line, ``lieng: error: ...``, and exits with status 2,
leaving OUTDIR untouched.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import sys
import warnings
from pathlib import Path

from lieng.errors import LiengInputError
from lieng.io.outputs import PLOT_DEFAULT, PLOT_FORMATS, plot_output

__all__ = ["main"]

PROGRAMS = ("lieng1", "mlien", "trc")
#: the words of the message for a failure no check foresaw (the fuzz suite looks for them)
UNEXPECTED = "unexpected failure on this input"
#: --force of the commands that write an output directory
FORCE_HELP = ("write into an existing directory that holds other files (they are left as they are; lieng replaces "
              "only its own outputs)")
#: the programs whose decks hold a characteristic (cycles, sweep)
CHAR_PROGRAMS = ("lieng1", "mlien")


def _reject_inapplicable(args) -> None:
    """One line for an option given to a program it does not apply to."""
    prog = args.program
    if prog != "trc":
        for opt, val in (("--omnh", args.omnh), ("--omnv", args.omnv), ("--fn", args.fn), ("--fnv", args.fnv)):
            if val is not None:
                raise LiengInputError(f"{opt}: applies to run trc only (a {prog} deck has no natural frequency)")
        if args.origin != "listing":
            raise LiengInputError(f"--origin {args.origin}: applies to run trc only")
    elif args.lookup != "listing":
        raise LiengInputError(f"--lookup {args.lookup}: applies to run lieng1 and run mlien only (TRC has no "
                              f"POINT step)")


def _map_plot(res, outdir, source):
    """``lieng map``'s plot (matplotlib is imported only when plots are asked for)."""
    from lieng.analysis.map_plot import regime_map_plot

    return regime_map_plot(res, outdir, source)


def _plots(name, res, outdir, *more):
    """A program's plots (matplotlib is imported only when plots are asked for)."""
    from lieng.programs import graf

    return getattr(graf, name)(res, outdir, *more)


def _run_program(args, program: str, tables, plots: str, summary) -> int:
    """``lieng run lieng1|mlien``: check the output directory, read and run the deck, write the listing, the
    CSV ``tables(res)`` ((name, header, rows) each) and the plots together, print ``summary(deck, res)``."""
    import importlib

    from lieng.io.outputs import check_outdir, staged_outdir, write_csv, write_lines
    from lieng.programs import listing, read_deck

    check_outdir(args.outdir, args.force)
    deck = read_deck(args.deck, program=program)
    res = importlib.import_module(f"lieng.programs.{program}").run_deck(deck, lookup=args.lookup)
    lines = getattr(listing, f"{program}_listing")(deck, res)
    tabs = list(tables(res))
    with staged_outdir(args.outdir, args.force) as tmp:
        write_lines(tmp / "listing.txt", lines)
        for name, header, rows in tabs:
            write_csv(tmp / name, header, rows)
        written = [] if args.no_plots else _plots(plots, res, tmp)
    if not args.quiet:
        print(summary(deck, res))
        print(f"wrote {Path(args.outdir) / 'listing.txt'}" + "".join(f", {name}" for name, _, _ in tabs)
              + "".join(f", {p.name}" for p in written))
    return 0


def _run_lieng1(args) -> int:
    def tables(res):
        rows = ((k + 1, i + 1, float(res.x[k, i]), float(res.y[k, i]), float(res.t[k, i]))
                for k in range(res.ntraj) for i in range(res.npts))
        return [("trajectories.csv", ["traj", "i", "x", "y", "t"], rows)]

    return _run_program(args, "lieng1", tables, "lieng1_plots",
                        lambda deck, res: f"lieng1: {res.ntraj} trajectories x {res.npts} points; centre of "
                                          f"symmetry XMDL = {res.xmdl:.6g}, YMDL = VO = {res.ymdl:.6g}")


def _run_mlien(args) -> int:
    def tables(res):
        return [("trajectories.csv", ["traj", "i", "x", "y", "t"],
                 ((1, i + 1, float(res.x[i]), float(res.y[i]), float(res.t[i])) for i in range(res.npts))),
                ("characteristic_last.csv", ["x", "y"],
                 ((float(a), float(b)) for a, b in zip(res.xchl_last, res.ychl_last)))]

    def summary(deck, res):
        trig = "card 83" if deck.trigger is not None else "listing values"
        return (f"mlien: {res.npts} points from T = {res.t[0]:.6g} to {res.t[-1]:.6g}; VO(0) = {res.vo:.6g}, "
                f"PHI = {res.phi:.6g}; triggering {res.trigger} ({trig})")

    return _run_program(args, "mlien", tables, "mlien_plots", summary)


def _is_table(path) -> bool:
    """A delimited table with a header naming a time column (comma, TAB,
    semicolon or whitespace), rather than a card deck.  A path that is not a
    readable regular file is an error here (a FIFO is never opened)."""
    from lieng.io.inputs import head, split_lines

    p = Path(path)
    first = split_lines(head(p))[0]
    if p.suffix.lower() in (".csv", ".tsv"):
        return True
    cells = [c.strip().lower() for c in re.split(r"[,;\t]|\s+", first) if c.strip()]
    return any(c in ("t", "time") or c.startswith(("t[", "t(", "time[", "time(")) for c in cells)


def _run_trc(args) -> int:
    from lieng.programs import read_deck
    from lieng.programs.listing import trc_listing
    from lieng.io.outputs import check_outdir, staged_outdir, write_csv, write_lines
    from lieng.programs.trc import CSV_COLUMNS, read_csv, trc

    check_outdir(args.outdir, args.force)
    # one convention with diagnose: --fn / --fnv in Hz, the listing's --omnh / --omnv in rad/s
    for hz, rad in (("fn", "omnh"), ("fnv", "omnv")):
        if getattr(args, hz) is not None:
            if getattr(args, rad) is not None:
                raise LiengInputError(f"--{hz} and --{rad}: give one of them (--{hz} in Hz, --{rad} in rad/s)")
            if not (math.isfinite(getattr(args, hz)) and getattr(args, hz) > 0):
                raise LiengInputError(f"--{hz} {getattr(args, hz)}: a natural frequency is a positive number (Hz)")
            setattr(args, rad, 2 * math.pi * getattr(args, hz))
    if _is_table(args.deck):
        if args.omnh is None:
            raise LiengInputError(f"{args.deck}: a CSV trace needs --fn (natural frequency of the "
                                  f"horizontal mode, Hz) or --omnh (rad/s)")
        t, x, xn = read_csv(args.deck)
        if xn is not None and args.omnv is None:
            raise LiengInputError(f"{args.deck}: the normal channel (column xn or y) needs --fnv (natural "
                                  f"frequency of the normal mode, Hz) or --omnv (rad/s)")
        res = trc(t, x, xn, omnh=args.omnh, omnv=args.omnv, origin=args.origin, _where=str(args.deck))
    else:
        if args.omnh is not None or args.omnv is not None:
            raise LiengInputError("--fn/--fnv/--omnh/--omnv are for CSV input: a TRC deck gives them on card 2")
        deck = read_deck(args.deck, program="trc")
        res = deck.run(origin=args.origin)
    listing = trc_listing(res)
    cols = res.columns()
    with staged_outdir(args.outdir, args.force) as tmp:
        write_lines(tmp / "listing.txt", listing)
        write_csv(tmp / "trc.csv", list(CSV_COLUMNS),
                  ([int(cols["i"][k])] + [_cell(cols[c][k]) for c in CSV_COLUMNS[1:]] for k in range(res.nn)))
        if not args.no_plots:
            _plots("trc_plots", res, tmp)
    if not args.quiet:
        eln = "" if not res.has_normal else f", ELN = {res.eln:.6g} mm"
        print(f"trc: {res.nn} points over {res.t[-1] - res.t[0]:.6g} s; origin ({res.origin}) EL = {res.el:.6g} mm"
              f"{eln}")
        print(f"wrote {Path(args.outdir) / 'listing.txt'}, trc.csv" + ("" if args.no_plots else " and the plots"))
    return 0


def _cell(v):
    """A CSV cell: the float, or None (an empty cell) for an undefined value."""
    v = float(v)
    return v if math.isfinite(v) else None


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


def _diagnose_record(data, fn=None, v0=None, stiffness=None, fn_uncertainty=None, progress=None):
    """Read one record (a table, or a TRC deck whose OMNH gives fn) and
    diagnose it: what ``lieng diagnose RECORD`` computes (also a task of
    ``diagnose --batch``).  Returns the :class:`lieng.diagnose.Diagnosis`."""
    from lieng.diagnose import diagnose, read_record, record_from_trc_deck

    if _is_table(data):
        rec = read_record(data, v0=v0, stiffness=stiffness)
    else:                                   # a thesis-style TRC deck: OMNH gives fn
        rec, fn_deck = record_from_trc_deck(data, v0)
        fn = fn_deck if fn is None else fn
    extra = {} if fn_uncertainty is None else {"fn_uncertainty": fn_uncertainty}
    return diagnose(rec, fn, progress=progress, **extra)


def _write_diagnosis(d, outdir, force: bool, source: str, plots: bool) -> list:
    """diagnosis.json, report.md and the plots of one record, written into
    ``outdir`` all at once; returns the names written."""
    from lieng.diagnose.report import write_outputs
    from lieng.io.outputs import staged_outdir

    with staged_outdir(outdir, force) as tmp:
        names = write_outputs(d, tmp, source, plots=plots)
    return names


def _diagnose(args) -> int:
    from lieng.diagnose.report import summary_lines
    from lieng.io.outputs import check_outdir, dumps_json

    if args.batch is not None:
        return _diagnose_batch(args)
    if args.data is None:
        raise LiengInputError("diagnose: give a RECORD to diagnose, or --batch DIR")
    for opt, val in (("--workers", args.workers), ("--scheduler", args.scheduler)):
        if val is not None:
            raise LiengInputError(f"{opt}: applies with --batch DIR only (one record is diagnosed in this process)")
    check_outdir(args.outdir, args.force)
    progress = None
    if sys.stderr.isatty() and not args.quiet:
        def progress(k, n):
            print(f"\rcalibrating against the baseline: replicate {k}/{n}", end="" if k < n else "\n",
                  file=sys.stderr, flush=True)
    d = _diagnose_record(args.data, args.fn, args.v0, args.stiffness, args.fn_uncertainty, progress)
    names = _write_diagnosis(d, args.outdir, args.force, str(args.data), not args.no_plots)
    if args.json:
        print(dumps_json(d.to_json(), indent=2))
    elif not args.quiet:
        print("\n".join(summary_lines(d, str(args.data))))
        print(f"wrote {Path(args.outdir) / names[0]}, " + ", ".join(names[1:]))
    return 0


#: the records ``diagnose --batch DIR`` reads: the files of DIR with these suffixes
BATCH_SUFFIXES = (".csv", ".txt", ".dat")
#: the columns of ``diagnose --batch``'s batch.csv
BATCH_COLUMNS = ("record", "outdir", "status", "effect", "effects_named", "gain", "cycles", "error")


def _batch_records(folder) -> list:
    """The records of ``--batch DIR``: its entries named *.csv, *.txt, *.dat
    (not hidden, not directories), sorted; refused when there are none or two
    would write the same OUTDIR/<stem>/."""
    p = Path(folder)
    try:
        entries = sorted(os.listdir(p))
    except NotADirectoryError:
        raise LiengInputError(f"--batch {folder}: not a directory") from None
    except FileNotFoundError:
        raise LiengInputError(f"--batch {folder}: no such directory") from None
    except OSError as exc:
        raise LiengInputError(f"--batch {folder}: cannot be read ({exc.strerror})") from None
    recs = [p / e for e in entries if not e.startswith(".") and Path(e).suffix.lower() in BATCH_SUFFIXES
            and not (p / e).is_dir()]
    if not recs:
        raise LiengInputError(f"--batch {folder}: no record in it (files named *.csv, *.txt or *.dat)")
    seen = {}
    for r in recs:
        if r.stem in seen:
            raise LiengInputError(f"--batch {folder}: {seen[r.stem].name} and {r.name} would both be written to "
                                  f"OUTDIR/{r.stem}/: rename one")
        seen[r.stem] = r
    return recs


def _diagnose_batch(args) -> int:
    """``diagnose --batch DIR``: every record through the executor, each
    written to OUTDIR/<stem>/ as one ``lieng diagnose`` writes it, and
    OUTDIR/batch.csv; status 1 when a record failed."""
    from lieng.analysis.cycles import _progress
    from lieng.diagnose.report import summary_lines
    from lieng.analysis.executor import check_workers, open_executor, run_tasks
    from lieng.io.outputs import check_outdir, staged_outdir, write_csv

    if args.data is not None:
        raise LiengInputError(f"--batch {args.batch} and {args.data}: give one record or --batch DIR, not both")
    if args.json:
        raise LiengInputError("--json: not with --batch (each record's diagnosis.json is in OUTDIR/<record>/)")
    check_workers(args.workers, args.scheduler)
    check_outdir(args.outdir, args.force)
    recs = _batch_records(args.batch)
    show = sys.stderr.isatty() and not args.quiet
    tasks = [(str(r), args.fn, args.v0, args.stiffness, args.fn_uncertainty) for r in recs]
    rows, lines, errors = [None] * len(recs), [None] * len(recs), []
    with staged_outdir(args.outdir, args.force, keep=[r.stem for r in recs]) as tmp:
        with open_executor(args.workers, args.scheduler, tasks=len(recs)) as ex:
            for k, d, msgs, err in run_tasks(ex, _diagnose_record, tasks, catch=True,
                                             on_done=lambda i, n: _progress(i, n, "diagnose --batch", show)):
                for m in msgs:                  # printed after a batch that succeeds, as for one record
                    warnings.warn(f"{recs[k]}: {m}", stacklevel=2)
                if err is None:
                    try:
                        _write_diagnosis(d, Path(args.outdir) / recs[k].stem, args.force, str(recs[k]),
                                         not args.no_plots)
                    except (LiengInputError, OSError, ValueError) as exc:
                        err = f"writing its outputs: {' '.join(str(exc).split())}"
                if err is None:
                    rows[k] = (recs[k].name, recs[k].stem, "ok", d.effect,
                               ";".join(e["effect"] for e in d.effects), float(d.gain), int(d.n_cycles), None)
                    lines[k] = summary_lines(d, str(recs[k]))[0]
                else:
                    err = err if err.startswith(str(recs[k])) else f"{recs[k]}: {err}"
                    rows[k] = (recs[k].name, None, "error", None, None, None, None, err)
                    lines[k] = f"{recs[k]}: error"
                    errors.append((k, err))
        write_csv(tmp / "batch.csv", BATCH_COLUMNS, rows)
    for _, err in sorted(errors):
        print(f"lieng: error: {err}", file=sys.stderr)
    if not args.quiet:
        print("\n".join(lines))
        print(f"wrote {Path(args.outdir) / 'batch.csv'} and {len(recs) - len(errors)} record director"
              f"{'y' if len(recs) - len(errors) == 1 else 'ies'} ({Path(args.outdir)}/<record>/)"
              + (f"; {len(errors)} of {len(recs)} records failed" if errors else ""))
    return 1 if errors else 0


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
        paths = figures(tmp, cards=args.cards, only=args.only)
    if not args.quiet:
        print(f"wrote {len(paths)} figure{'' if len(paths) == 1 else 's'} to {args.outdir}/: "
              + ", ".join(p.name for p in paths))
    return 0


#: the largest preload (N) of `lieng twodof`
PRELOAD_MAX = 10_000.0


def _twodof(args) -> int:
    from lieng.io.outputs import all_finite, check_outdir, dumps_json
    from lieng.analysis.twodof import T_END_MAX, T_END_MIN, compare, write_outputs

    if args.outdir is not None:
        check_outdir(args.outdir, args.force)
    if args.belt is not None and args.rpm is not None:
        raise LiengInputError("--belt and --rpm: give one of them (the belt velocity, or the disc speed at r2 = "
                              "0.08 m)")
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
    keep: dict = {}
    if args.belt is not None and not (0 < args.belt < 1):
        raise LiengInputError(f"--belt {args.belt}: the belt velocity must be between 0 and 1 m/s")
    if args.belt is None and not 2 * math.pi * 0.08 * args.rpm / 60 < 1:
        raise LiengInputError(f"--rpm {args.rpm:g}: the belt at r2 = 0.08 m must be slower than 1 m/s "
                              f"(rpm < {60 / (2 * math.pi * 0.08):.4g})")
    res = compare(preload=args.preload, rpm=args.rpm, t_end=args.t_end, keep=keep, belt=args.belt)
    if not all_finite(res):
        raise LiengInputError(f"--preload {args.preload:g}, --rpm {args.rpm:g}: the simulation leaves the range of "
                              f"the model (a non-finite result); use values nearer the paper's (80 N, 0.1 rpm)")
    if args.outdir is not None:
        from lieng.io.outputs import staged_outdir

        with staged_outdir(args.outdir, args.force) as tmp:
            write_outputs(res, keep, tmp)
    if args.json:
        print(dumps_json(res, indent=2))
    else:
        pap = res.get("paper")
        print(f"dual-pin-on-disc, Fn = {args.preload:g} N, belt {res['belt_m_s']:.4g} m/s, {args.t_end:g} s; modal "
              f"frequencies "
              + ", ".join(f"{f:.3f}" for f in res["modal_hz"]) + " Hz")
        print(f"{'':24}{'peak (deg)':>12}{'fluct (deg)':>12}{'freq (Hz)':>11}{'N mean':>9}{'N std':>8}")
        rows = []
        if pap:
            rows += [("paper, experiment", pap["experiment"]), ("paper, theory", pap["theory"])]
        rows += [("2-DoF (this model)", res), ("1-DoF, constant N", res["onedof"]),
                 ("1-DoF, C_N(t)", res["onedof_load_corrected"])]
        for lab, r in rows:
            nf = r.get("normal_force", {})
            nm = f"{nf['mean']:9.2f}{nf['std']:8.3f}" if nf else ""
            print(f"{lab:24}{r['peak_deg']:12.3f}{r['fluct_deg']:12.3f}{r['dominant_hz']:11.3f}{nm}")
    return 0


class _Parser(argparse.ArgumentParser):
    """argparse with a one-line usage error (``lieng: error: ...``, status 2)."""

    def error(self, message):
        sub = self.prog.split()[1:]
        where = f"{' '.join(sub)}: " if sub else ""
        hint = f"lieng {' '.join(sub)} --help" if sub else "lieng --help"
        self.exit(2, f"lieng: error: {where}{' '.join(message.split())} (see {hint})\n")


#: a value that starts with a minus sign: a negative number, a range
#: (``-1:2:3``) or ``-inf``
_NEGATIVE_VALUE = re.compile(r"^-(\d|\.\d|inf|nan)", re.IGNORECASE)


def _join_negative_values(parser: argparse.ArgumentParser, argv: list[str]) -> list[str]:
    """``--v0 -1:2:3`` as ``--v0=-1:2:3``: argparse takes a value that starts
    with a minus sign for an option unless it is a plain number."""
    takes_value = set()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sp in action.choices.values():
                takes_value |= {o for a in sp._actions if a.option_strings and a.nargs is None
                                and not isinstance(a, (argparse._StoreTrueAction, argparse._HelpAction))
                                for o in a.option_strings}
    out, k = [], 0
    while k < len(argv):
        a = argv[k]
        if a in takes_value and a.startswith("--") and k + 1 < len(argv) and _NEGATIVE_VALUE.match(argv[k + 1]):
            out.append(f"{a}={argv[k + 1]}")
            k += 2
            continue
        out.append(a)
        k += 1
    return out


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog="lieng",
        description="Antoniou's 1971 Lienard-plane stick-slip programs, restored.",
    )
    from lieng import __version__

    p.add_argument("--version", action="version", version=f"lieng {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    r = sub.add_parser("run", help="run a 1971 card deck (listing, CSV, plots)",
                       description="Run a card deck through a restored 1971 program.")
    r.add_argument("program", choices=PROGRAMS, help="which program's deck")
    r.add_argument("deck", help="the card deck (one card per line); for trc also a CSV t,x[,xn] (s, mm, mm)")
    r.add_argument("-o", "--outdir", required=True, help="output directory")
    r.add_argument("--lookup", choices=("listing", "bisect", "fast"), default="listing",
                   help="POINT step: the 1971 arithmetic (listing, default), bisection look-up with "
                        "bit-identical results (bisect), or no trig calls (fast, last bits differ)")
    r.add_argument("--no-plots", action="store_true", help="skip the plots")
    _plot_options(r)
    r.add_argument("--omnh", type=float, help="trc, CSV input: natural frequency of the horizontal mode (rad/s)")
    r.add_argument("--omnv", type=float, help="trc, CSV input with xn: natural frequency of the normal mode (rad/s)")
    r.add_argument("--fn", type=float, metavar="HZ", help="trc, CSV input: natural frequency of the horizontal mode "
                   "(Hz, as in diagnose; instead of --omnh)")
    r.add_argument("--fnv", type=float, metavar="HZ", help="trc, CSV input with xn: natural frequency of the normal "
                   "mode (Hz; instead of --omnv)")
    r.add_argument("--origin", choices=("listing", "fit"), default="listing",
                   help="trc: EL/ELN as the listing finds them (default) or by a better-conditioned line fit")
    r.add_argument("--force", action="store_true", help=FORCE_HELP)
    r.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    def deck_args(q):
        q.add_argument("deck", help="a LIENG-1 (or, with --program mlien, MLIEN) card deck")
        q.add_argument("--program", choices=CHAR_PROGRAMS, default="lieng1", help="the deck's layout (default lieng1)")
        q.add_argument("--mode", choices=("exact", "faithful"), default="exact",
                       help="exact flow (default) or the listing's POINT step with the deck's DTHETA")
        q.add_argument("--lookup", choices=("listing", "bisect", "fast"), default="listing",
                       help="POINT step of the faithful mode")
        q.add_argument("--json", action="store_true", help="print JSON")

    c = sub.add_parser("cycles", help="stability of the origin and the limit cycles of a deck's characteristic",
                       description="Limit cycles from the return map on the abscissa, classified by "
                                   "Poincare's criterion (thesis App. 3).")
    deck_args(c)
    w = sub.add_parser("sweep", help="limit cycles against the driving velocity (Fig. 2.27) or dmu0 (Fig. 2.28)",
                       description="The deck's characteristic moved to each driving velocity as TIMDIS moves "
                                   "it (--v0), or its static peak dmu0 = mu_s - mu_k0 scaled (--dmu), and its "
                                   "cycles found again; v_oc is where the S.L.C. and U.L.C. merge, dmu_oc the "
                                   "smallest dmu0 with a self-sustained oscillation.")
    deck_args(w)
    sw = w.add_mutually_exclusive_group(required=True)
    sw.add_argument("--v0", metavar="START:STOP:N", help="driving velocities (mm/s)")
    sw.add_argument("--dmu", metavar="START:STOP:N", help="factors of the deck's dmu0 (1 = the deck)")
    w.add_argument("--at-v0", type=float, metavar="V", help="with --dmu: the driving velocity (default: the deck's)")
    mp = sub.add_parser("map", help="the regime of Table 2.IV over a grid of (v0, dmu0) or (v0, slope), with "
                        "v_oc traced", description="The deck's characteristic with its static peak dmu0 scaled "
                        "(--dmu, as lieng sweep --dmu) or its rising part's slope set (--slope), moved to each "
                        "driving velocity as TIMDIS moves it; at each point the regime of Table 2.IV (no motion, "
                        "no self-sustained oscillation, self-excited, depends on the trigger, metastable) from "
                        "the limit cycles, and along each row v_oc, where the S.L.C. and U.L.C. merge. Writes "
                        "map.csv, v_oc.csv and map.png.")
    deck_args(mp)
    mp.add_argument("--v0", metavar="START:STOP:N", required=True, help="driving velocities (mm/s)")
    ma = mp.add_mutually_exclusive_group(required=True)
    ma.add_argument("--dmu", metavar="START:STOP:N", help="factors on the characteristic's static peak dmu0 = "
                    "mu_s - mu_k0 (1 = the deck)")
    ma.add_argument("--slope", metavar="START:STOP:N", help="slopes of the rising part beyond the kinetic minimum, "
                    "d|X - XMDL|/d|Y - YMDL| (mm per mm/s; positive)")
    _executor_options(mp, "")
    mp.add_argument("-o", "--outdir", required=True, help="output directory")
    mp.add_argument("--force", action="store_true", help=FORCE_HELP)
    mp.add_argument("--no-plots", action="store_true", help="write map.csv and v_oc.csv only")
    _plot_options(mp)
    mp.add_argument("-q", "--quiet", action="store_true", help="print nothing (errors still go to stderr)")
    dg = sub.add_parser("diagnose", help="what the 1-DoF model gets wrong on a measured record, and why",
                        description="Fit the thesis's 1-DoF model (a single-valued characteristic of general "
                                    "shape, constant load and drive) to a measured stick-slip record, test each "
                                    "candidate effect against the fitted baseline's own replicates (family-wise "
                                    "false-alarm rate 5 percent), fit the extension of each effect named and "
                                    "measure its gain on held-out cycles (the record's last 30 percent with "
                                    "models fitted on its first 70, and its first 30 with models fitted on "
                                    "its last 70).")
    dg.add_argument("data", nargs="?", help="a table t,x[,y][,v0] (s, mm, mm, mm/s) or t,F[,N][,position|v0] with units in "
                    "the header ('F [mN]', 'time/s', 'Time (s)', or a row of units; comma, semicolon, TAB or whitespace, a "
                    "decimal comma, '#' comments; rows with a missing value left out), or a TRC deck")
    dg.add_argument("--v0", type=float, metavar="MM_S",
                    help="drive velocity (mm/s) when the record has no v0/position column")
    dg.add_argument("--fn", type=float, metavar="HZ", help="natural frequency of the tangential mode (Hz); "
                    "estimated from the slips when not given (a TRC deck gives it: OMNH)")
    dg.add_argument("--fn-uncertainty", type=float, metavar="REL",
                    help="relative uncertainty of --fn (default 0.05); the slip-shape evidence is tested at the "
                         "least favourable fn within it: an fn measured to 0.01 lets smaller twin branches through")
    dg.add_argument("--stiffness", type=float, metavar="N_M", help="tangential stiffness (N/m) of a force "
                    "record; estimated from the sticks when not given")
    dg.add_argument("--batch", metavar="DIR", help="diagnose every record in DIR (*.csv, *.txt, *.dat; the options "
                    "above apply to each) into OUTDIR/<record>/, with a summary in OUTDIR/batch.csv; status 1 when "
                    "a record failed (the others are still written)")
    _executor_options(dg, "with --batch: ")
    dg.add_argument("-o", "--outdir", required=True, help="output directory")
    dg.add_argument("--force", action="store_true", help=FORCE_HELP)
    dg.add_argument("--json", action="store_true", help="print diagnosis.json")
    dg.add_argument("--no-plots", action="store_true", help="write diagnosis.json and report.md only")
    _plot_options(dg)
    dg.add_argument("-q", "--quiet", action="store_true", help="print nothing (errors still go to stderr)")
    sy = sub.add_parser("synth", help="synthetic measured data with an effect hidden in it",
                        description="Write a synthetic stick-slip record (t,x[,y][,v0]) with realistic noise "
                                    "and one effect hidden in it (an implementation independent of diagnose).")
    sy.add_argument("--effect", default="none",
                    choices=("none", "load_variation", "twin_branch", "static_ageing", "triggering",
                             "drive_modulation"))
    sy.add_argument("--seed", type=int, default=None, help="random seed")
    sy.add_argument("--cycles", type=int, default=16, help="approximate number of cycles (default 16)")
    sy.add_argument("--strength", type=float, default=None, help="scale of the effect (default 1)")
    sy.add_argument("-o", "--output", required=True, help="the CSV to write")
    sy.add_argument("--force", action="store_true", help="replace the file if it exists (a regular file only)")
    sy.add_argument("-q", "--quiet", action="store_true")
    td = sub.add_parser("twodof", help="the 2-DoF dual-pin-on-disc model (seed 001) against the 1-DoF model",
                        description="Simulate the reconstructed 2-DoF dual-pin-on-disc rig (Leine's switch "
                                    "model) and the thesis's 1-DoF model of the same rig; print the paper's "
                                    "Table 3/4 quantities beside the paper's values.")
    td.add_argument("--preload", type=float, default=80.0, help="total normal preload of both pins (N)")
    td.add_argument("--rpm", type=float, default=None, help="disc speed (rpm; belt at r2 = 0.08 m; default 0.1)")
    td.add_argument("--t-end", type=float, default=600.0, help="simulated time (s, default 600 as the tests)")
    td.add_argument("--belt", type=float, help="belt velocity (m/s) instead of the disc at --rpm and r2 = 0.08 m "
                    "(e.g. 0.00838, sec. 5's value)")
    td.add_argument("-o", "--outdir", help="write twodof.json and plots here")
    td.add_argument("--force", action="store_true", help=FORCE_HELP)
    td.add_argument("--json", action="store_true", help="print JSON")
    _plot_options(td)
    fg = sub.add_parser("figures", help="regenerate the thesis's theoretical figures (2.22-2.29, A9-1..A9-7)",
                        description="Regenerate the theoretical figures the thesis describes, each from a deck "
                                    "in cards/ (cards/figures/, cards/mlien_a9_7.dat), each PNG captioned with "
                                    "the section it reproduces.")
    fg.add_argument("-o", "--outdir", required=True, help="output directory")
    fg.add_argument("--force", action="store_true", help=FORCE_HELP)
    fg.add_argument("--cards", default=None, help="a directory laid out as the project's cards/ (default: the "
                    "decks installed with lieng)")
    fg.add_argument("--only", nargs="+", metavar="FIG", help="only these figures (e.g. 2.27 A9-7)")
    fg.add_argument("-q", "--quiet", action="store_true")
    _plot_options(fg)
    return p


def main(argv=None) -> int:
    """Run the command line; returns the exit status (0, or 2 for bad input)."""
    import warnings

    import numpy as np

    parser = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    try:
        args = parser.parse_args(_join_negative_values(parser, [str(a) for a in argv]))
    except SystemExit as exc:               # --help (0) or a usage error (2, one line already printed)
        return int(exc.code or 0) if isinstance(exc.code, (int, type(None))) else 2
    # numerical warnings are not messages for the user: every output is
    # checked for finiteness where it is written, and bad input gets one line.
    # The program's own warnings are printed, one line each, after a run that
    # succeeds (an error is the only line of a failed run).
    with warnings.catch_warnings(record=True) as caught, np.errstate(all="ignore"):
        warnings.simplefilter("always")
        warnings.simplefilter("ignore", RuntimeWarning)
        warnings.simplefilter("ignore", DeprecationWarning)
        warnings.simplefilter("ignore", PendingDeprecationWarning)
        code = _dispatch(parser, args)
    if code == 0:
        seen = set()
        for w in caught:
            msg = " ".join(str(w.message).split())
            if issubclass(w.category, UserWarning) and msg not in seen:
                seen.add(msg)
                print(f"lieng: warning: {msg}", file=sys.stderr)
    return code


def _executor_options(p, when: str) -> None:
    """--workers and --scheduler of a command whose tasks run on an executor (lieng.executor)."""
    p.add_argument("--workers", type=int, metavar="N", help=f"{when}local worker processes (default: one per "
                   f"processor; 1 runs in this process)")
    p.add_argument("--scheduler", metavar="ADDRESS", help=f"{when}run the tasks on a Dask cluster, e.g. "
                   f"tcp://127.0.0.1:8786 (pip install 'lieng[dask]')")


def _plot_options(p) -> None:
    """--format and --dpi of a command that writes plots."""
    p.add_argument("--format", choices=PLOT_FORMATS, default=None,
                   help=f"the plots' file format (default {PLOT_DEFAULT['format']})")
    p.add_argument("--dpi", type=float, default=None,
                   help=f"the plots' resolution (dots per inch, default {PLOT_DEFAULT['dpi']:g})")


def _dispatch(parser, args) -> int:
    try:
        if hasattr(args, "dpi"):
            plot_output(args.format, args.dpi)
        if args.command == "run":
            _reject_inapplicable(args)
            return {"lieng1": _run_lieng1, "mlien": _run_mlien, "trc": _run_trc}[args.program](args)
        handlers = {"cycles": _cycles, "sweep": _sweep, "map": _map, "diagnose": _diagnose, "synth": _synth,
                    "figures": _figures, "twodof": _twodof}
        if args.command not in handlers:
            parser.error(f"unknown command {args.command}")  # pragma: no cover
        return handlers[args.command](args)
    except LiengInputError as exc:
        print(f"lieng: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # pragma: no cover
        print("lieng: interrupted", file=sys.stderr)
        return 130
    except MemoryError:
        print(f"lieng: error: {args.command}: not enough memory for this input", file=sys.stderr)
        return 2
    except Exception as exc:
        # the last line of defence: a failure the checks above did not foresee
        # still gets one line (LIENG_DEBUG=1 shows the traceback); the fuzz
        # suite fails on this message, so each one is fixed at its cause
        if os.environ.get("LIENG_DEBUG"):
            raise
        msg = " ".join(str(exc).split())[:200]
        print(f"lieng: error: {args.command}: {UNEXPECTED} ({type(exc).__name__}: {msg}); please report it "
              f"(LIENG_DEBUG=1 shows the traceback)", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
