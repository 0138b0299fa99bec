"""``lieng run``: the restored programs on their decks (and TRC on a table)."""

from __future__ import annotations

import math
from pathlib import Path

from lieng.errors import LiengInputError, located

from lieng.cli.common import _cell, _is_table, _plots


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

def _run_program(args, program: str, tables, plots: str, summary, run=None, listing=None) -> int:
    """``lieng run PROGRAM``: check the output directory, read and run the input (``run(args)`` gives (deck,
    result); by default the program's deck and run_deck), write the listing (``listing(deck, result)``; by
    default the program's), the CSV ``tables(res)`` ((name, header, rows) each) and the plots together, print
    ``summary(deck, res)``."""
    import importlib

    from lieng.io.outputs import check_outdir, staged_outdir, write_csv, write_lines
    from lieng.programs import listing as listings, read_deck

    check_outdir(args.outdir, args.force)
    if run is None:
        deck = read_deck(args.deck, program=program)
        res = importlib.import_module(f"lieng.programs.{program}").run_deck(deck, lookup=args.lookup)
    else:
        deck, res = run(args)
    lines = (listing or getattr(listings, f"{program}_listing"))(deck, res)
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


def _trc_input(args):
    """The TRC run of a deck, or of a CSV trace with the natural frequencies from the options: (deck or None,
    result)."""
    from lieng.programs import read_deck
    from lieng.programs.trc import read_csv, trc

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
        with located(lambda field: str(args.deck)):     # the trace's errors and warnings name the file
            return None, trc(t, x, xn, omnh=args.omnh, omnv=args.omnv, origin=args.origin)
    if args.omnh is not None or args.omnv is not None:
        raise LiengInputError("--fn/--fnv/--omnh/--omnv are for CSV input: a TRC deck gives them on card 2")
    deck = read_deck(args.deck, program="trc")
    return deck, deck.run(origin=args.origin)


def _run_trc(args) -> int:
    from lieng.programs.listing import trc_listing
    from lieng.programs.trc import CSV_COLUMNS

    def tables(res):
        cols = res.columns()
        return [("trc.csv", list(CSV_COLUMNS),
                 ([int(cols["i"][k])] + [_cell(cols[c][k]) for c in CSV_COLUMNS[1:]] for k in range(res.nn)))]

    def summary(deck, res):
        eln = "" if not res.has_normal else f", ELN = {res.eln:.6g} mm"
        return (f"trc: {res.nn} points over {res.t[-1] - res.t[0]:.6g} s; origin ({res.origin}) "
                f"EL = {res.el:.6g} mm{eln}")

    return _run_program(args, "trc", tables, "trc_plots", summary, run=_trc_input,
                        listing=lambda deck, res: trc_listing(res))
