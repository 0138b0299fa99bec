"""``lieng diagnose``: one record, or every record of a folder (``--batch``)."""

from __future__ import annotations

import os
import sys
import warnings
from pathlib import Path

from lieng.errors import LiengInputError

from lieng.cli.common import _is_table


def _diagnose_record(data, fn=None, v0=None, stiffness=None, fn_uncertainty=None, progress=None, rate=None,
                     highpass=None, names=None, normal_load=None, run=None):
    """Read one record (a table, or a TRC deck whose OMNH gives fn) and
    diagnose it: what ``lieng diagnose RECORD`` computes (also a task of
    ``diagnose --batch``).  Returns the :class:`lieng.diagnose.Diagnosis`."""
    from lieng.diagnose import diagnose, read_record, record_from_trc_deck
    from lieng.diagnose.read import check_fn
    from lieng.io.table import headerless_columns

    if names is not None or _is_table(data):
        rec = read_record(data, v0=v0, stiffness=stiffness, rate=rate, highpass=highpass, names=names,
                          normal_load=normal_load, run=run)
    else:                                   # a thesis-style TRC deck: OMNH gives fn
        for opt, val in (("--highpass", highpass), ("--normal-load", normal_load), ("--run", run)):
            if val is not None:
                raise LiengInputError(f"{opt}: applies to a table, not to a TRC deck ({data})")
        try:
            rec, fn_deck = record_from_trc_deck(data, v0)
        except LiengInputError:
            ncol = headerless_columns(data)
            if ncol:
                # not a deck: rows of as many numbers, without a header to say what they are
                raise LiengInputError(
                    f"{data}: {ncol} column{'s' if ncol > 1 else ''} of numbers and no header naming "
                    f"{'them' if ncol > 1 else 'it'}: add a first line such as 't [s] F [N] position [mm]' (or "
                    f"'t [s] x [mm]'), in the columns' order, or give them with --names") from None
            raise
        if fn is None and fn_deck is not None:
            check_fn(rec, fn_deck, f"{data}: card OMNH ({fn_deck:g} Hz, the deck's natural frequency)",
                     "OMNH (rad/s) or give --fn")
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
    d = _diagnose_record(args.data, args.fn, args.v0, args.stiffness, args.fn_uncertainty, progress, args.rate,
                         args.highpass, args.names, args.normal_load, args.run)
    names = _write_diagnosis(d, args.outdir, args.force, str(args.data), not args.no_plots)
    if args.json:
        print(dumps_json(d.to_json(), indent=2))
    elif not args.quiet:
        print("\n".join(summary_lines(d, str(args.data))))
        print(f"wrote {Path(args.outdir) / names[0]}, " + ", ".join(names[1:]))
    return 0


#: the records ``diagnose --batch DIR`` reads: the files of DIR with these suffixes
BATCH_SUFFIXES = (".csv", ".txt", ".dat", ".lvm", ".xlsx", ".xlsm", ".mat", ".npz")
#: the columns of ``diagnose --batch``'s batch.csv
BATCH_COLUMNS = ("record", "outdir", "status", "effect", "effects_named", "gain", "cycles", "error")


def _batch_records(folder) -> list:
    """The records of ``--batch DIR``: its entries named *.csv, *.txt, *.dat, *.lvm,
    *.xlsx, *.xlsm, *.mat, *.npz (not hidden, not directories), sorted; refused when there are none or two
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
        raise LiengInputError(f"--batch {folder}: no record in it (files named *.csv, *.txt, *.dat, *.lvm, *.xlsx, *.mat or *.npz)")
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
    tasks = [(str(r), args.fn, args.v0, args.stiffness, args.fn_uncertainty, None, args.rate, args.highpass,
              args.names, args.normal_load, args.run)
             for r in recs]
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
