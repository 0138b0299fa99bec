"""The parser, the dispatch to each command and the one-line error contract."""

from __future__ import annotations

import argparse
import os
import re
import sys

from lieng.errors import LiengInputError, describe, run_reporting
from lieng.io.outputs import PLOT_DEFAULT, PLOT_FORMATS, plot_output

from lieng.cli.common import CHAR_PROGRAMS, FORCE_HELP, PROGRAMS, UNEXPECTED


from lieng.cli.analyses import _cycles, _figures, _map, _sweep, _synth, _twodof
from lieng.cli.diagnose import _diagnose
from lieng.cli.programs import _reject_inapplicable, _run_lieng1, _run_mlien, _run_trc


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


def _quantity(text: str):
    """An option's number, or (number, unit) when a unit follows it
    ("2.5 N/mm", "6deg/s"): argparse's one-line error otherwise."""
    try:
        return float(text)
    except ValueError:
        pass
    m = re.match(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d\s].*?)\s*$", text)
    if not m:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number, nor a number and its unit")
    return float(m.group(1)), m.group(2)


def _names(text: str) -> list:
    """``--names``: the columns' header cells, comma-separated ("t [s],F [N]"); argparse's one-line error for
    an empty one."""
    cells = [c.strip() for c in text.split(",")]
    if not cells or not all(cells):
        raise argparse.ArgumentTypeError(f"{text!r}: a name for each column, comma-separated ('t [s],F [N],N [N]')")
    return cells


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
                                    "models fitted on its first 70, its first 30 with models fitted on its "
                                    "last 70 and, on a record of up to 250 000 samples, its middle with "
                                    "models fitted on the rest).")
    dg.add_argument("data", nargs="?", help="a table t,x[,y][,v0] (s, mm, mm, mm/s) or t,F[,N][,position|v0] with units in "
                    "the header (F may be a friction coefficient mu or COF: times N when recorded; N an apply pressure, "
                    "'Apply pressure [kPa]'; a six-axis sensor's Fx, Fy, Fz: the friction on the tangential axis "
                    "that swings more; 'F [mN]', "
                    "'time/s', 'Time (s)', or a row of units; comma, semicolon, TAB or whitespace, a decimal comma, "
                    "'#' comments; rows with a missing value left out), a LabVIEW .lvm file, a spreadsheet .xlsx (its first "
                    "sheet, read as such a table), a MATLAB .mat (v4-v7) or NumPy .npz file of vectors named so, or a TRC deck")
    dg.add_argument("--v0", type=_quantity, metavar="MM_S",
                    help="drive velocity (mm/s) when the record has no v0/position column (a rotary record's: "
                         "its angle unit per second, rad/s when it has no angle column); or with its unit, "
                         "'0.5 um/s', '6 deg/s', '2 rpm'")
    dg.add_argument("--fn", type=float, metavar="HZ", help="natural frequency of the tangential mode (Hz); "
                    "estimated from the slips when not given (a TRC deck gives it: OMNH)")
    dg.add_argument("--fn-uncertainty", type=float, metavar="REL",
                    help="relative uncertainty of --fn (default 0.05: within 5 %% of the true fn); the slip-shape "
                         "evidence is tested at the least favourable fn within it: an fn measured to 0.01 lets "
                         "smaller twin branches through")
    dg.add_argument("--rate", type=float, metavar="HZ", help="sampling rate (Hz) of a record without a time "
                    "column (its rows are then evenly spaced samples)")
    dg.add_argument("--names", type=_names, metavar="NAMES",
                    help="the columns' names with their units, comma-separated in the file's order, e.g. "
                         "'t [s],F [N],N [N]': they replace the file's header (a data-acquisition program's "
                         "'Dev1/ai0', 'CH1') or head a file that has none; a .mat or .npz file's one matrix is "
                         "read column by column under them")
    dg.add_argument("--run", metavar="N", help="the run to read from a logger's export of several runs side by "
                    "side (PASCO Capstone's 'Time (s) Run #2', Vernier's 'Run 2: Time (s)'): 2, or 'latest'")
    dg.add_argument("--stiffness", type=_quantity, metavar="N_M", help="tangential stiffness (N/m) of a force "
                    "record (a torque record's: N·m per its angle unit, per rad when it has no angle column), or "
                    "with its unit, '2.5 N/mm', '0.05 N·m/rad'; estimated from the sticks when not given")
    dg.add_argument("--normal-load", type=_quantity, metavar="N",
                    help="the constant normal load (N, or with its unit, '30.1 gf') of a record whose friction is a "
                         "coefficient (mu, COF) without a normal-force column: the friction force is mu times it")
    dg.add_argument("--highpass", type=float, metavar="TAU_S", help="the friction channel was recorded AC-coupled "
                    "(a piezoelectric force cell's charge amplifier): the time constant (s) of its high-pass, "
                    "undone before the diagnosis (a steady force otherwise sinks towards zero, read as a drifting "
                    "friction)")
    dg.add_argument("--batch", metavar="DIR", help="diagnose every record in DIR (*.csv, *.txt, *.dat, *.lvm, *.xlsx, *.mat, *.npz; the options "
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
    td.add_argument("--rpm", type=float, default=None, help="disc speed (rpm; the belt at the reading's friction "
                    "radius, x10 in sec. 5's reading; default 0.1)")
    td.add_argument("--t-end", type=float, default=600.0, help="simulated time (s, default 600 as the tests)")
    td.add_argument("--belt", type=float, help="belt velocity (m/s) instead of the disc at --rpm and r2 = 0.08 m "
                    "(e.g. 0.00838, sec. 5's value)")
    td.add_argument("--reading", default="default",
                    help="which reading of the paper's lost equations (default: the best of the search in "
                         "twodof.md; named: default, previous, rod, point, cos2, no-normal, minus-normal, m1-table, "
                         "r80, slow-belt, 3dof; or KINETIC/K3PROJ/NORMAL/m1-REF/rRADIUS/BELT[/3dof])")
    td.add_argument("--members", type=int, default=8,
                    help="initial states of the ensemble (1-64, default 8): every metric as median and range")
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
    fg.add_argument("--only", nargs="+", action="extend", metavar="FIG",
                    help="only these figures (e.g. 2.27 A9-7, or 2.27,A9-7)")
    fg.add_argument("-q", "--quiet", action="store_true")
    _plot_options(fg)
    return p


def main(argv=None) -> int:
    """Run the command line; returns the exit status (0, or 2 for bad input)."""
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
    code, messages = run_reporting(_dispatch, parser, args)
    if code == 0:
        for msg in dict.fromkeys(messages):
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
        print(f"lieng: error: {args.command}: {UNEXPECTED} ({describe(exc)}); please report it "
              f"(LIENG_DEBUG=1 shows the traceback)", file=sys.stderr)
        return 2

