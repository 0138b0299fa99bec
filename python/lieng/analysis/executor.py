"""Where the independent tasks of a command run: in this process, on a local
process pool, or on a Dask distributed cluster.

``lieng map`` (one row of the grid per task) and ``lieng diagnose --batch``
(one record per task) submit their tasks through :func:`open_executor` and
collect them with :func:`run_tasks`.  Every executor has the
:class:`concurrent.futures.Executor` interface:

* ``workers == 1`` (and no scheduler): :class:`InProcess`, the tasks run one
  after the other in this process;
* ``workers > 1``: a :class:`concurrent.futures.ProcessPoolExecutor` whose
  processes are started by the ``forkserver`` method (never ``fork``: a
  process that already runs threads, a Dask client or a plotting backend,
  is not forked);
* ``scheduler="tcp://HOST:PORT"``: ``distributed.Client(address).get_executor()``
  (``pip install lieng[dask]``; dask is imported only then).  The cluster's
  workers must have lieng installed and, for ``diagnose --batch``, see the
  records at the same path.

The tasks are pure functions of their arguments, so a result does not depend
on the executor that computed it.
"""

from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import Executor, Future, ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from typing import Callable, Iterator, Sequence

import numpy as np

from lieng.errors import LiengInputError, describe, run_reporting

__all__ = ["InProcess", "open_executor", "run_tasks", "check_workers", "default_workers", "MAX_WORKERS",
           "CONNECT_TIMEOUT"]

#: the most local worker processes
MAX_WORKERS = 256
#: seconds to wait for a Dask scheduler to answer
CONNECT_TIMEOUT = 10.0


class InProcess(Executor):
    """An executor that runs each task at once, in this process."""

    def submit(self, fn, /, *args, **kwargs) -> Future:
        f = Future()
        try:
            f.set_result(fn(*args, **kwargs))
        except BaseException as exc:        # handed to the caller through the future
            if isinstance(exc, KeyboardInterrupt):
                raise
            f.set_exception(exc)
        return f


def default_workers() -> int:
    """The processors this process may run on (the local pool's default size)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:                  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def check_workers(workers, scheduler=None, option: str = "--workers") -> None:
    """Refuse a pool size that is not a whole number from 1 to :data:`MAX_WORKERS`,
    or one given together with a scheduler (whose cluster has its own workers)."""
    if workers is None:
        return
    if scheduler is not None:
        raise LiengInputError(f"{option} {workers} and --scheduler: give one of them (the cluster's workers run the "
                              f"tasks with --scheduler)")
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or not 1 <= workers <= MAX_WORKERS:
        raise LiengInputError(f"{option} {workers}: the number of worker processes must be from 1 to {MAX_WORKERS}")


@contextmanager
def open_executor(workers: int | None = None, scheduler: str | None = None, tasks: int | None = None):
    """An executor for ``tasks`` independent tasks, shut down on exit.

    Parameters
    ----------
    workers : int, optional
        Local worker processes (default: :func:`default_workers`); 1 runs the
        tasks in this process.
    scheduler : str, optional
        The address of a Dask scheduler (``tcp://HOST:PORT``); then the
        cluster's workers run the tasks.
    tasks : int, optional
        The number of tasks: no more processes are started than there are
        tasks.

    Yields
    ------
    concurrent.futures.Executor

    Raises
    ------
    LiengInputError
        A bad ``workers``; dask not installed; a scheduler that cannot be
        reached within :data:`CONNECT_TIMEOUT` seconds (each one line that
        names ``--workers`` or ``--scheduler``).
    """
    check_workers(workers, scheduler)
    if scheduler is not None:
        with _dask_executor(scheduler) as ex:
            yield ex
        return
    n = default_workers() if workers is None else int(workers)
    if tasks is not None:
        n = max(1, min(n, int(tasks)))
    if n == 1:
        yield InProcess()
        return
    ctx = multiprocessing.get_context("forkserver" if "forkserver" in multiprocessing.get_all_start_methods()
                                      else "spawn")
    ex = ProcessPoolExecutor(max_workers=n, mp_context=ctx)
    try:
        yield ex
    except BaseException:
        ex.shutdown(wait=False, cancel_futures=True)
        raise
    else:
        ex.shutdown(wait=True)


@contextmanager
def _dask_executor(address: str):
    if not isinstance(address, str) or not address.strip():
        raise LiengInputError(f"--scheduler {address!r}: expected the address of a Dask scheduler, e.g. "
                              f"tcp://127.0.0.1:8786")
    try:
        import logging

        import distributed
    except ImportError:
        raise LiengInputError("--scheduler: needs Dask's distributed scheduler, which is not installed: "
                              "pip install 'lieng[dask]'") from None
    _probe(address)
    quiet = [logging.getLogger(n) for n in ("distributed", "distributed.client", "distributed.core",
                                            "distributed.comm", "tornado")]
    levels = [q.level for q in quiet]
    for q in quiet:                         # an unreachable scheduler is one line of ours, not a log
        q.setLevel(logging.CRITICAL)
    try:
        try:
            client = distributed.Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False)
        except (OSError, TimeoutError, ValueError, TypeError) as exc:
            why = " ".join(str(exc).split())[:160] or type(exc).__name__
            _discard_client(exc, distributed.Client)
            raise LiengInputError(f"--scheduler {address}: cannot reach a Dask scheduler there within "
                                  f"{CONNECT_TIMEOUT:g} s ({why})") from None
    finally:
        for q, lv in zip(quiet, levels):
            q.setLevel(lv)
    try:
        yield client.get_executor()
    finally:
        client.close()


def _probe(address: str) -> None:
    """Refuse an address Dask cannot parse, and a TCP scheduler that does not
    accept a connection, before a client is made (a client that fails to
    connect leaves a traceback behind when it is collected)."""
    import socket

    from distributed.comm import parse_address, parse_host_port

    try:
        scheme, loc = parse_address(address)
        if scheme not in ("tcp", "tls", "ws", "wss"):
            return                          # inproc://, ucx://: left to the client
        host, port = parse_host_port(loc)
    except (ValueError, TypeError) as exc:
        raise LiengInputError(f"--scheduler {address}: not the address of a Dask scheduler "
                              f"({' '.join(str(exc).split())}); e.g. tcp://127.0.0.1:8786") from None
    try:
        socket.create_connection((host, int(port)), timeout=CONNECT_TIMEOUT).close()
    except (OSError, ValueError, OverflowError) as exc:
        why = getattr(exc, "strerror", None) or " ".join(str(exc).split()) or type(exc).__name__
        raise LiengInputError(f"--scheduler {address}: cannot reach a Dask scheduler there ({why})") from None


def _discard_client(exc, cls) -> None:
    """Stop the half-made client a failed ``Client(address)`` leaves in its
    traceback: collected later, it would wait 20 s to close a connection it
    never had and print a traceback of its own."""
    tb = exc.__traceback__
    while tb is not None:
        obj = tb.tb_frame.f_locals.get("self")
        if isinstance(obj, cls):
            try:
                obj.status = "closed"
                obj._loop_runner.stop()
            except Exception:               # pragma: no cover - best effort on dask's internals
                pass
            return
        tb = tb.tb_next


def _call(fn, args):
    """Run ``fn(*args)`` as the command line runs its work (a worker process's standard error is not the
    user's): returns (result, warning messages), :func:`lieng.errors.run_reporting`."""
    return run_reporting(fn, *args)


def _call_caught(fn, args):
    """:func:`_call`, with an exception returned as (None, messages, error
    message) instead of raised (one bad task must not stop a batch)."""
    try:
        value, msgs = _call(fn, args)
    except LiengInputError as exc:
        return None, [], str(exc)
    except MemoryError:
        return None, [], "not enough memory for this input"
    except Exception as exc:                # reported per task; the batch goes on
        return None, [], describe(exc)
    return value, msgs, None


def run_tasks(executor: Executor | None, fn: Callable, args: Sequence[tuple], *, catch: bool = False,
              on_done: Callable[[int, int], None] | None = None) -> Iterator[tuple]:
    """Submit ``fn(*a)`` for each ``a`` in ``args`` and yield the results as
    they complete.

    Parameters
    ----------
    executor : concurrent.futures.Executor or None
        Where the tasks run (None: in this process).
    fn : callable
        A function importable by name (it is pickled for other processes).
    args : sequence of tuple
        The arguments of each task.
    catch : bool, optional
        Hand a task's exception back as its error message instead of raising
        it (also a worker that died: ``BrokenProcessPool``).
    on_done : callable, optional
        ``on_done(k, n)`` after the k-th of n tasks completes (a progress bar).

    Yields
    ------
    (int, object, list of str) or, with ``catch``, (int, object, list of str, str or None)
        The task's index in ``args``, its result, the messages of the
        warnings it raised and, with ``catch``, its error message (the
        result is then None).
    """
    n = len(args)
    call = _call_caught if catch else _call
    if executor is None or isinstance(executor, InProcess):
        done = ((k, InProcess().submit(call, fn, a)) for k, a in enumerate(args))    # one at a time
    else:
        futures = {executor.submit(call, fn, a): k for k, a in enumerate(args)}
        done = ((futures[f], f) for f in as_completed(futures))
    for i, (k, f) in enumerate(done, start=1):
        if catch:
            try:
                value, msgs, err = f.result()
            except Exception as exc:        # the worker itself failed
                value, msgs, err = None, [], describe(exc)
            item = (k, value, msgs, err)
        else:
            value, msgs = f.result()
            item = (k, value, msgs)
        if on_done is not None:
            on_done(i, n)
        yield item
