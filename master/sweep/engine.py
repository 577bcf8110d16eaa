"""Running a list of cases on Dask (or one after another in this process) into a sweep's folder.

:func:`run_cases` sends each :class:`~rotorcosim.master.sweep.case.Case` to a worker of a Dask cluster (a local
one, one single-threaded worker process per core, or a running one given by its scheduler's address), writes
each case's files into ``OUT/<case>`` as it comes back (whole or absent: folder.py) and keeps ``OUT/sweep.json``
current; at the end it writes ``OUT/sweep.csv`` (one row per case: its parameters and its numeric results).

What it does under faults (each leaves every finished case's folder complete and readable, and the folder
unlocked):

* a case that fails (a bad value, a divergence, a crashed FMU): its summary's ``error``, the others go on;
* the worker running a case dies (killed, out of memory, a crash in native code): the case is run once more
  (:data:`~rotorcosim.master.sweep.retry.RETRIES`, by :func:`~rotorcosim.master.sweep.retry.run_retried`), then
  reported failed by name ("its worker died ..."), the others go on; a case run again is reported (sweep.json
  ``retries``: the workers that died under it, the one that ran it again, its result; and the progress
  callback's ``result["retry"]``);
* the scheduler goes away: the sweep ends with :class:`SchedulerLost` naming it and how many cases are kept;
* Ctrl-C or SIGTERM: the sweep stops (on Dask at once; ``serial`` once the case running, which takes the
  signal over, has stopped or ended), the cases still running marked ``interrupted`` in sweep.json, the others
  ``pending``, and :class:`SweepInterrupted` (a KeyboardInterrupt) says what was kept;
* a full disk: the sweep ends with :class:`~rotorcosim.master.sweep.folder.DiskFullError` naming the folder.

``resume=True`` reruns only the cases that sweep.json does not list as complete (a case is deterministic: the
results equal an uninterrupted sweep's, bit for bit).

::

    from rotorcosim.master.sweep import Case, run_cases
    cases = [Case(f"F_{f:g}", "toy_thermomechanical", level=f, duration=0.05) for f in (50.0, 100.0)]
    done = run_cases(cases, "out", workers=2)          # or scheduler="tcp://10.0.0.5:8786", or serial=True
    done.summaries["F_50"]["final_outputs"]            # each case's summary.json, as in OUT/F_50/
"""
from __future__ import annotations

import csv
import json
import logging
import os
import signal
import threading
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Sequence

from rotorcosim.master import case as case_
from rotorcosim.master.schedule import budget
from rotorcosim.master.sweep.case import Case, failed_summary, run_case
from rotorcosim.master.sweep.folder import SweepFolder, named_os_error
from rotorcosim.master.sweep.retry import ALLOWED_FAILURES, Outcome, run_retried

#: how long the client waits for a scheduler given by ``scheduler=`` before saying it cannot reach it [s]
CONNECT_TIMEOUT_S = 20.0


class SweepError(RuntimeError):
    """A sweep that could not go on (the message says why and what was kept)."""


class SchedulerLost(SweepError):
    """The Dask scheduler went away during the sweep."""


class WorkerDied(SweepError):
    """A case whose worker died on every attempt."""


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C or SIGTERM stopped the sweep; ``str()`` says what was kept (the command line's one line)."""


@dataclass
class SweepRun:
    """What :func:`run_cases` returns: ``summaries`` (case -> its summary, in the cases' order), ``hosts`` (case
    -> the machine that ran it; None for a case kept from before a resume or never run), ``status`` (case ->
    one of folder.CASE_STATES), ``executed_on`` (where: "serial", "local cluster, N workers", "ADDRESS, N
    workers"), ``wall_time_s`` and ``state`` (the contents of sweep.json)."""
    summaries: dict[str, dict]
    hosts: dict[str, Any]
    status: dict[str, str]
    executed_on: str
    wall_time_s: float
    state: dict = field(default_factory=dict)

    @property
    def errors(self) -> dict[str, str]:
        """case -> its error, for the cases that failed."""
        return {n: s["error"] for n, s in self.summaries.items() if s.get("error")}


def run_cases(cases: Sequence[Case], out, *, scheduler: str | None = None, workers: int | None = None,
              serial: bool = False, client=None, progress: Callable | None = None, overwrite: bool = False,
              resume: bool = False, info: dict | None = None, finish: Callable | None = None, extra_files=(),
              connect_timeout: float = CONNECT_TIMEOUT_S, force: bool = False,
              say: Callable[[str], None] | None = None) -> SweepRun:
    """Run ``cases`` into the folder ``out`` and return their summaries (:class:`SweepRun`).

    Where: ``serial`` in this process, one after another; else on ``client`` (a ``dask.distributed.Client`` the
    caller owns), or a client of the scheduler at ``scheduler`` (e.g. ``"tcp://10.0.0.5:8786"``), or a local
    cluster of ``workers`` processes (default: the cores, at most one per case). ``progress(done, total, case,
    result)`` is called as each case ends (``result["summary"]``, ``["host"]``). ``overwrite`` replaces a
    previous sweep's results in ``out``, ``resume`` continues it (only the cases not complete run). ``info``:
    more entries of sweep.json (a command's options); ``finish(out, summaries)``, called once every case is
    complete or failed, returns more entries of it (a case's tables). ``extra_files``: name patterns of the files
    ``finish`` writes, which ``overwrite`` may clear.

    Every case is checked (:meth:`Case.check`) before any runs, and the sweep's wall time estimated from their
    prices (as ``rotorcosim run`` prices a run), given to ``say`` (a function of one line) and kept in sweep.json
    (``estimate``); beyond 24 h the sweep is refused unless ``force``. See the module's docstring for faults."""
    cases = list(cases)
    if not cases:
        raise ValueError("run_cases: no case to run")
    names = [c.name for c in cases]
    if len(set(names)) != len(names):
        raise ValueError(f"run_cases: two cases are named {next(n for n in names if names.count(n) > 1)!r}")
    check_where(scheduler, workers, serial)
    # fail early: a bad scenario, an unknown component, a duration or schedule no run takes, a sweep too long
    prices = [c.check(force) for c in cases]
    est = _estimate(prices, scheduler, workers, serial, client, connect_timeout, force)
    definitions = {c.name: c.definition() for c in cases}
    # sweep.csv's column of the level: the key its case's summaries report it under (master/case.py)
    leveled = [c for c in cases if c.level is not None]
    column = case_.scenario_level(leveled[0].scenario_of())[0].summary_key if leveled else case_.GENERIC.summary_key
    with SweepFolder(out, overwrite=overwrite, resume=resume, extra_files=extra_files) as folder:
        if say is not None:   # once the folder is taken (a refusal of it is the only line), before the first case
            say(budget.many_line(est, "sweep"))
        sweep = _Sweep(cases, folder, definitions, {**(info or {}), "estimate": est}, progress)
        sweep.level_column = column
        return sweep.run(scheduler, workers, serial, client, connect_timeout, finish)


def check_where(scheduler: str | None, workers, serial: bool) -> None:
    """Where a sweep's or a study's runs go, checked before anything is written: a local cluster of a whole
    number of workers >= 1, and ``serial`` (this process, no Dask) without a scheduler or a number of workers
    (they were ignored)."""
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"--workers must be at least 1, got {workers!r}")
    if serial and scheduler:
        raise ValueError("--serial runs in this process, without Dask: give it or --scheduler, not both")
    if serial and workers is not None:   # the local cluster's size: a serial run has none, and ignored it
        raise ValueError(f"--serial runs in this process, one run after another: give it or --workers "
                         f"({workers}), not both")


def _estimate(prices: list[dict], scheduler, workers, serial, client, connect_timeout, force) -> dict:
    """The sweep's wall time from its cases' estimates, as many at a time as it will run (budget.check_many)."""
    if serial:
        at_once = 1
    elif client is not None or scheduler:
        own = client is None
        if own:   # an unreachable scheduler is named here, before the folder is touched
            client, cluster, _ = dask_client(scheduler, None, connect_timeout, 1)
        try:
            at_once = sum(w.get("nthreads", 1) for w in client.scheduler_info().get("workers", {}).values())
        finally:
            if own:
                close_client(client, cluster)
    else:
        at_once = min(workers or os.cpu_count() or 1, len(prices))
    run_s = max(p["wall_s"] for p in prices)   # whole waves of the dearest case: an upper bound of a mixed sweep
    return budget.check_many(run_s, len(prices), at_once, "sweep", "fewer levels or --set values, a shorter "
                             "--duration, or more workers (--workers, --scheduler)", force,
                             any(p.get("upper_bound") for p in prices))


class _Sweep:
    """The state of one sweep while it runs: who is done, sweep.json."""

    def __init__(self, cases, folder: SweepFolder, definitions, info, progress):
        self.cases, self.folder, self.definitions, self.info, self.progress = cases, folder, definitions, info, progress
        self.level_column = case_.GENERIC.summary_key
        self.summaries: dict[str, dict] = folder.complete_cases(definitions)
        self.status = {c.name: "complete" if c.name in self.summaries else "pending" for c in cases}
        self.hosts: dict[str, Any] = {c.name: None for c in cases}
        self.retries: dict[str, dict] = {}
        self.where = ""
        self.t0 = time.perf_counter()

    def state(self, status: str, extra: dict | None = None) -> dict:
        """sweep.json: the cases, the caller's entries, where and how long, each case's host, wall time, error
        and state, the sweep's status and what each case runs (for ``--resume``)."""
        sums = self.summaries
        return {"cases": [c.name for c in self.cases], **self.info, "wall_time_s": time.perf_counter() - self.t0,
                "executed_on": self.where, **(extra or {}),
                "case_hosts": dict(self.hosts),
                "case_wall_time_s": {n: (sums.get(n) or {}).get("wall_time_s") for n in self.status},
                "errors": {n: sums[n]["error"] for n in self.status if n in sums and sums[n].get("error")},
                "retries": dict(self.retries),
                "status": status, "case_status": dict(self.status), "definitions": self.definitions}

    def save(self, status: str = "running") -> None:
        self.folder.write_state(self.state(status))

    def finished(self, case: Case, res: dict) -> None:
        """A case came back: its files stored, its summary (as stored) kept, sweep.json updated."""
        summary = res["summary"]
        files = res["files"] or {"summary.json": (json.dumps(summary, indent=2) + "\n").encode()}  # why it failed
        self.folder.store(case.name, files)
        if not summary.get("error") and "summary.json" in files:
            summary = json.loads(files["summary.json"])   # as a resumed sweep reads it: the same bits
        self.summaries[case.name] = summary
        self.hosts[case.name] = res.get("host")
        self.status[case.name] = "failed" if summary.get("error") else "complete"
        if res.get("retry"):
            self.retries[case.name] = {**res["retry"], "result": self.status[case.name], "error": summary.get("error")}
        self.save()
        if self.progress:
            done = sum(s in ("complete", "failed") for s in self.status.values())
            self.progress(done, len(self.cases), case, {**res, "summary": summary})

    def stopped(self, why: str) -> None:
        """The sweep ends before its cases: the running ones marked interrupted; sweep.json says ``why``."""
        for n, s in self.status.items():
            if s == "running":
                self.status[n] = "interrupted"
        try:
            self.save(why)
        except OSError:
            pass   # a full disk: the case folders are what is kept

    def run(self, scheduler, workers, serial, client, connect_timeout, finish) -> SweepRun:
        todo = [c for c in self.cases if self.status[c.name] != "complete"]
        with sigterm_as_interrupt():
            try:
                if not todo:
                    self.where = "nothing to run (every case complete)"
                elif serial:
                    self.where = "serial"
                    self.save()
                    with _SignalsSeen() as seen:
                        for c in todo:
                            self.status[c.name] = "running"
                            self.finished(c, run_case(c))
                            if seen.interrupt():   # the case ran to its end: it is kept; the sweep stops
                                raise KeyboardInterrupt(seen.interrupt())
                else:
                    self._on_dask(todo, scheduler, workers, client, connect_timeout)
            except KeyboardInterrupt:
                self.stopped("interrupted")
                kept = sum(st == "complete" for st in self.status.values())
                raise SweepInterrupted(f"interrupted: {kept} of {len(self.cases)} cases complete and kept in "
                                       f"{self.folder.path} (sweep.json: case_status); continue with --resume") \
                    from None
            except BaseException:
                self.stopped("failed")
                raise
        try:
            extra = finish(self.folder.path, self.ordered()) if finish is not None else {}
            _write_csv(self.folder.path / "sweep.csv", self.cases, self.ordered(), self.level_column)
        except OSError as exc:   # every case is stored: a --resume writes the tables
            self.save("failed")
            raise named_os_error(exc, self.folder.path, "writing the sweep's tables") from None
        state = self.state("complete", extra)
        self.folder.write_state(state)
        return SweepRun(self.ordered(), dict(self.hosts), dict(self.status), self.where, state["wall_time_s"], state)

    def ordered(self) -> dict[str, dict]:
        return {c.name: self.summaries[c.name] for c in self.cases}

    def _on_dask(self, todo, scheduler, workers, client, connect_timeout) -> None:
        own = client is None
        cluster = None
        if own:
            client, cluster, self.where = dask_client(scheduler, workers, connect_timeout, len(todo))
        else:
            self.where = f"{client.scheduler.address}, {len(client.scheduler_info().get('workers', {}))} workers"
        address = scheduler or client.scheduler.address
        lost = False
        submitted: set[int] = set()

        def done(i: int, out: Outcome) -> None:
            nonlocal lost
            c = todo[i]
            if out.error is not None and not out.worker_died and _scheduler_gone(client, out.error):
                lost = True
                raise SchedulerLost(self._lost(address))
            self.finished(c, _case_result(c, out))

        for c in todo:
            self.status[c.name] = "running"
        try:
            self.save()
            try:
                run_retried(client, run_case, [(c,) for c in todo], done, submitted=submitted)
            except (OSError, TimeoutError):
                if client.status in ("running", "connecting"):
                    raise
                lost = True
                raise SchedulerLost(self._lost(address)) from None
            except KeyboardInterrupt:
                # the cases not yet sent to a worker go back to pending (only those a worker runs are interrupted)
                for i, c in enumerate(todo):
                    if i not in submitted and self.status[c.name] == "running":
                        self.status[c.name] = "pending"
                raise
        finally:
            if own:
                close_client(client, cluster, quiet=lost)

    def _lost(self, address: str) -> str:
        kept = sum(s == "complete" for s in self.status.values())
        return (f"the Dask scheduler {address} went away: the sweep stopped with {kept} of {len(self.cases)} "
                f"cases complete and kept in {self.folder.path}; start a scheduler and continue with --resume")


def _case_result(case: Case, out: Outcome) -> dict:
    """What a case's task came back with (run_case's result, its retry reported), or a failed case's summary."""
    retry = {"attempt": out.attempts, "died_on": list(out.died_on), "worker": out.worker} if out.died_on else None
    if out.error is None:
        res = out.value
    elif out.worker_died:
        error = (f"{WorkerDied.__name__}: its worker died while running it, {len(out.died_on)} times "
                 f"(retried {out.attempts - 1} time(s))")
        res = {"summary": failed_summary(case, error), "files": {}, "host": None}
    else:
        res = {"summary": failed_summary(case, f"{type(out.error).__name__}: {out.error}"), "files": {},
               "host": None}
    return {**res, "retry": retry} if retry else res


def _scheduler_gone(client, exc: BaseException) -> bool:
    """Whether ``exc`` means the client lost its scheduler (not a failure of the task)."""
    import asyncio
    from concurrent.futures import CancelledError

    if client.status not in ("running", "connecting"):
        return True
    # distributed's FutureCancelledError is a CancelledError
    return isinstance(exc, (CancelledError, asyncio.CancelledError))


def dask_client(scheduler: str | None, workers: int | None, connect_timeout: float, n_cases: int):
    """A Dask client on the running scheduler ``scheduler`` (an address) or on a local cluster of one single-threaded
    worker process per core (at most ``workers``, at most ``n_cases``); returns ``(client, cluster or None, where
    it runs in words)``. An unreachable or malformed address is a ValueError saying so."""
    import dask
    from dask.distributed import Client, LocalCluster

    if scheduler:
        try:
            client = Client(scheduler, timeout=connect_timeout)
        except (OSError, TimeoutError) as exc:
            raise ValueError(f"--scheduler {scheduler}: cannot reach the Dask scheduler ({exc})") from None
        except ValueError as exc:  # not an address (dask: "unknown address scheme ...")
            raise ValueError(f"--scheduler {scheduler}: not a Dask scheduler's address ({exc})") from None
        n = len(client.scheduler_info().get("workers", {}))
        return client, None, f"{scheduler}, {n} workers"
    # one process per worker, each running one case at a time: workers beyond the cases would only start and
    # idle (--workers 100000 spent minutes starting processes, then failed inside Dask)
    n = min(workers or os.cpu_count() or 1, n_cases)
    # Ctrl-C in a terminal reaches every process of its group, the local workers too: they ignore it (each
    # printed a KeyboardInterrupt traceback) and this process ends the sweep and closes them. Ignored while
    # they start (a disposition a started process keeps) and by a plugin in every worker (a restarted one too)
    main = threading.current_thread() is threading.main_thread()
    old = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:
        with warnings.catch_warnings():  # "Port 8787 is already in use" (another cluster's): it takes another one
            warnings.filterwarnings("ignore", message="Port .* is already in use")
            # Dask's own log off: a worker's death, the task run again and a failed case are the sweep's to say,
            # once each (its scheduler logged "Couldn't gather keys" at ERROR while a dead worker's task was rerun)
            # a worker's death reaches the client, which runs the task again (retry.py), not the scheduler itself
            with dask.config.set({"distributed.scheduler.allowed-failures": ALLOWED_FAILURES}):
                cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                                       worker_dashboard_address=None, silence_logs=logging.CRITICAL)
    finally:
        if main:
            signal.signal(signal.SIGINT, old)
    client = Client(cluster)
    client.register_plugin(_IgnoreInterrupt(), name="rotorcosim-ignore-sigint")
    return client, cluster, f"local cluster, {n} workers"


try:
    from distributed.diagnostics.plugin import WorkerPlugin as _WorkerPlugin
except ImportError:  # pragma: no cover  (Dask is needed only off --serial)
    _WorkerPlugin = object


class _IgnoreInterrupt(_WorkerPlugin):
    """A local worker ignores SIGINT: the sweep's own process ends it (see :func:`dask_client`)."""

    def setup(self, worker):
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, signal.SIG_IGN)


def close_client(client, cluster, quiet: bool = False) -> None:
    """Close the client and the local cluster, quietly when the scheduler is gone (Dask logs its failed
    reconnection with tracebacks: the sweep's own one-line error says it)."""
    loggers = [logging.getLogger(n) for n in ("distributed.client", "distributed.core", "distributed.comm")]
    levels = [lg.level for lg in loggers]
    if quiet:
        for lg in loggers:
            lg.setLevel(logging.CRITICAL)
    try:
        client.close(timeout=5)
    except Exception:   # the scheduler already gone: nothing to close cleanly
        pass
    finally:
        for lg, lv in zip(loggers, levels):
            lg.setLevel(lv)
    if cluster is not None:
        try:
            cluster.close(timeout=10)
        except Exception:
            pass


class sigterm_as_interrupt:
    """SIGTERM ends the sweep as Ctrl-C does (in the main thread; elsewhere signals are the caller's)."""

    def __enter__(self):
        self._old = None
        if threading.current_thread() is threading.main_thread():
            self._old = signal.signal(signal.SIGTERM, _raise_interrupt)
        return self

    def __exit__(self, *exc):
        if self._old is not None:
            signal.signal(signal.SIGTERM, self._old)


class _SignalsSeen:
    """Whether SIGINT or SIGTERM arrived while a case ran in this process (serial). A run takes both signals
    over (checkpoint.StopRequest: the first one stops it at its next checkpoint), and one arriving after its
    last checkpoint lets it complete without a word: the signal would be lost to the sweep, which went on. Every
    signal also writes its number to the interpreter's wake-up file descriptor, whichever handler takes it: a
    pipe here, read after each case."""

    def __enter__(self):
        self._old = None
        if threading.current_thread() is threading.main_thread():
            self._r, self._w = os.pipe()
            os.set_blocking(self._r, False)
            os.set_blocking(self._w, False)
            self._old = signal.set_wakeup_fd(self._w, warn_on_full_buffer=False)
        return self

    def interrupt(self) -> str | None:
        """The name of an interrupting signal received since the last call, or None."""
        if self._old is None:
            return None
        try:
            got = os.read(self._r, 512)
        except BlockingIOError:
            return None
        hits = [n for n in got if n in (signal.SIGINT, signal.SIGTERM)]
        return signal.Signals(hits[0]).name if hits else None

    def __exit__(self, *exc):
        if self._old is not None:
            signal.set_wakeup_fd(self._old)
            os.close(self._r)
            os.close(self._w)


def _raise_interrupt(signum, frame):
    raise KeyboardInterrupt(signal.Signals(signum).name)


def _write_csv(path: Path, cases: list[Case], summaries: dict[str, dict], level_column: str = "level") -> None:
    """One row per case: its parameters (its level first, in the column ``level_column``), then
    ``<result>_<group>`` for every numeric result of its summary's ``bearings`` groups (a case's results by
    group), then its error."""
    params = list(dict.fromkeys([level_column] * any(c.level is not None for c in cases)
                                + [r for c in cases for r in c.settings]))
    results = list(dict.fromkeys(f"{key}_{brg}" for s in summaries.values()
                                 for brg, vals in s.get("bearings", {}).items() for key in vals
                                 if isinstance(vals.get(key), (int, float))))
    tmp = path.with_name(path.name + ".part")
    with open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["case", *params, *results, "error"])
        for c in cases:
            s = summaries[c.name]
            row = [c.name] + [c.level if p == level_column else c.settings.get(p, "") for p in params]
            flat = {f"{k}_{b}": v for b, vals in s.get("bearings", {}).items() for k, v in vals.items()}
            row += [flat.get(r, "") for r in results] + [s.get("error") or ""]
            w.writerow(row)
    os.replace(tmp, path)



