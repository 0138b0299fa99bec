"""The ``lieng`` command line.

``lieng run lieng1 DECK -o OUTDIR`` runs a card deck as the 1971 program did
and writes the line-printer listing, the trajectories as CSV and the plots.
Bad input prints one line, ``lieng: error: ...``, and exits with status 2,
leaving OUTDIR untouched.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

from .errors import LiengInputError

__all__ = ["main"]

PROGRAMS = ("lieng1", "mlien")


def _run_lieng1(args) -> int:
    from .cards import read_deck
    from .graf import lieng1_plots
    from .lieng1 import run_deck
    from .listing import lieng1_listing
    from .outputs import staged_outdir, write_csv, write_lines

    deck = read_deck(args.deck, program="lieng1")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = run_deck(deck, lookup=args.lookup)
    for w in caught:
        print(f"lieng: warning: {w.message}", file=sys.stderr)
    listing = lieng1_listing(deck, res)
    with staged_outdir(args.outdir) as tmp:
        write_lines(tmp / "listing.txt", listing)
        rows = (
            (k + 1, i + 1, float(res.x[k, i]), float(res.y[k, i]), float(res.t[k, i]))
            for k in range(res.ntraj)
            for i in range(res.npts)
        )
        write_csv(tmp / "trajectories.csv", ["traj", "i", "x", "y", "t"], rows)
        if not args.no_plots:
            lieng1_plots(res, tmp)
    if not args.quiet:
        print(f"lieng1: {res.ntraj} trajectories x {res.npts} points; centre of symmetry "
              f"XMDL = {res.xmdl:.6g}, YMDL = VO = {res.ymdl:.6g}")
        print(f"wrote {Path(args.outdir) / 'listing.txt'}, trajectories.csv"
              + ("" if args.no_plots else ", phase_plane.png, displacement_time.png, velocity_time.png"))
    return 0


def _run_mlien(args) -> int:
    from .cards import read_deck
    from .graf import mlien_plots
    from .listing import mlien_listing
    from .mlien import run_deck
    from .outputs import staged_outdir, write_csv, write_lines

    deck = read_deck(args.deck, program="mlien")
    res = run_deck(deck, lookup=args.lookup)
    listing = mlien_listing(deck, res)
    with staged_outdir(args.outdir) as tmp:
        write_lines(tmp / "listing.txt", listing)
        write_csv(tmp / "trajectories.csv", ["traj", "i", "x", "y", "t"],
                  ((1, i + 1, float(res.x[i]), float(res.y[i]), float(res.t[i])) for i in range(res.npts)))
        write_csv(tmp / "characteristic_last.csv", ["x", "y"],
                  ((float(a), float(b)) for a, b in zip(res.xchl_last, res.ychl_last)))
        if not args.no_plots:
            mlien_plots(res, tmp)
    if not args.quiet:
        trig = "card 83" if deck.trigger is not None else "listing values"
        print(f"mlien: {res.npts} points from T = {res.t[0]:.6g} to {res.t[-1]:.6g}; VO(0) = {res.vo:.6g}, "
              f"PHI = {res.phi:.6g}; triggering {res.trigger} ({trig})")
        print(f"wrote {Path(args.outdir) / 'listing.txt'}, trajectories.csv, characteristic_last.csv"
              + ("" if args.no_plots else ", phase_plane.png, displacement_time.png, velocity_time.png"))
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="lieng",
        description="Antoniou's 1971 Lienard-plane stick-slip programs, restored.",
    )
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    r = sub.add_parser("run", help="run a 1971 card deck (listing, CSV, plots)",
                       description="Run a card deck through a restored 1971 program.")
    r.add_argument("program", choices=PROGRAMS, help="which program's deck")
    r.add_argument("deck", help="the card deck (one card per line)")
    r.add_argument("-o", "--outdir", required=True, help="output directory")
    r.add_argument("--lookup", choices=("listing", "bisect", "fast"), default="listing",
                   help="POINT step: the 1971 arithmetic (listing, default), bisection look-up with "
                        "bit-identical results (bisect), or no trig calls (fast, last bits differ)")
    r.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    r.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    return p


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "run":
            return {"lieng1": _run_lieng1, "mlien": _run_mlien}[args.program](args)
        parser.error(f"unknown command {args.command}")  # pragma: no cover
    except LiengInputError as exc:
        print(f"lieng: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # pragma: no cover
        print("lieng: interrupted", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
