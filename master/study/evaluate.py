"""Runs of one scenario with overrides, many at a time: on a Dask cluster (local by default) or in this process.

A job is ``(name, overrides)``: the scenario with ``{"comp.param": value}`` applied, run for the study's duration
with nothing recorded but its summary (:func:`run_job`). :class:`Evaluator` runs lists of jobs and returns their
summaries (summary.json's dict; a job that failed has ``status`` "failed" and ``error``), calling ``done`` as
each one finishes so that the caller stores it at once.

A worker that dies while running a job (a crash, killed for memory) has its job run once more on another worker;
if that dies too, the job is reported failed (``error`` names it), never dropped.

The Dask side is the sweep engine's (:mod:`rotorcosim.master.sweep.engine`): the same client for a scheduler
address or a local cluster (whose workers leave Ctrl-C to this process), the same retry count, connection
timeout, SIGTERM handling and closing. What differs is what a job returns: a study needs each run's summary only,
in memory, thousands of times (no case folder, time series or figures, which ``run_cases`` writes for a sweep),
and a study can run a stand-in task (its tests do).

>>> with Evaluator("toy_thermomechanical", duration=0.05, serial=True) as ev:
...     [s["status"] for s in ev.map([("a", {"node.C": 20.0}), ("b", {"node.C": 40.0})])]
['complete', 'complete']
"""
from __future__ import annotations

import os
import sys
import time
from typing import Any, Callable, Sequence

# one place for these: the sweep engine's connection timeout [s], its Dask client (local cluster or scheduler
# address), its closing and its SIGTERM-as-Ctrl-C; the retry of a job whose worker died (retry.py)
from rotorcosim.master.sweep.engine import CONNECT_TIMEOUT_S, check_where
from rotorcosim.master.sweep.retry import Outcome, run_retried
from rotorcosim.master.sweep.engine import close_client, dask_client as sweep_client
from rotorcosim.master.sweep.engine import sigterm_as_interrupt as terminate_as_interrupt  # noqa: F401 - used as evaluate.terminate_as_interrupt

Job = tuple[str, dict[str, Any]]


def failed(summary: dict) -> bool:
    """Whether a job's summary is a failure (its run did not complete or stop as asked)."""
    return bool(summary.get("error")) or summary.get("status") not in ("complete", "stopped")


def run_job(scenario: str, overrides: dict[str, Any], duration: float | None) -> dict:
    """Run ``scenario`` (a shipped name or a file) with ``overrides`` for ``duration`` [s] (None: the
    scenario's), recording nothing, without figures; returns its summary. A run that fails (diverges, a value its
    component refuses) returns what it had with ``status`` "failed" and ``error`` rather than raising."""
    from rotorcosim.master.api import load_scenario, simulate

    t0 = time.perf_counter()
    try:
        sc = load_scenario(scenario)
        if overrides:
            sc = sc.set(overrides)
        summary = dict(simulate(sc, duration=duration, record=[], figures=False).summary)
    except Exception as exc:  # one failing job must not lose the others
        partial = getattr(exc, "result", None)
        summary = dict(partial.summary) if partial is not None else {}
        summary.update(status="failed", error=f"{type(exc).__name__}: {' '.join(str(exc).split())}")
    summary.setdefault("wall_time_s", time.perf_counter() - t0)
    return summary


def check_scheduler(scheduler: str | None, connect_timeout: float = CONNECT_TIMEOUT_S) -> int | None:
    """A scheduler address that cannot be reached is an error (ValueError, one line) now, before a study writes
    anything; None (a local cluster or serial) passes. Returns the threads the scheduler's workers offer (None
    without a scheduler)."""
    if scheduler:
        client, cluster, _ = sweep_client(scheduler, None, connect_timeout, 1)
        try:
            return max(1, sum(w.get("nthreads", 1) for w in client.scheduler_info().get("workers", {}).values()))
        finally:
            close_client(client, cluster)
    return None


def slots(scheduler: str | None, workers: int | None, serial: bool) -> int:
    """How many runs a study runs at once: 1 serial, the scheduler's threads, or the local cluster's workers
    (``workers``, default the cores). Checks the scheduler (:func:`check_scheduler`)."""
    check_where(scheduler, workers, serial)
    if serial:
        return 1
    threads = check_scheduler(scheduler)
    return threads if threads is not None else (workers or os.cpu_count() or 1)


def estimate(scenario: str, overrides: list[dict], duration: float | None, runs: int, at_once: int, what: str,
             shorten: str, force: bool) -> dict:
    """The wall time of a study of ``runs`` runs of ``scenario`` for ``duration``, ``at_once`` at a time, each
    priced as ``rotorcosim run`` prices a run (budget.py) at the mean of ``overrides`` (a study's cases, or its
    first sample); refused beyond 24 h unless ``force`` (:func:`rotorcosim.master.schedule.budget.check_many`)."""
    from rotorcosim.master.api import check_run, load_scenario
    from rotorcosim.master.schedule import budget

    base = load_scenario(scenario)
    costs, bound = [], False
    for over in overrides or [{}]:
        est = check_run(base.set(over) if over else base, None, duration, force=force)
        costs.append(est["wall_s"])
        bound = bound or bool(est.get("upper_bound"))
    return budget.check_many(sum(costs) / len(costs), runs, at_once, what, shorten, force, bound)


class Evaluator:
    """Runs jobs of ``scenario`` (a shipped name or a file path) for ``duration`` [s].

    ``scheduler``: the address of a running Dask scheduler; default a local cluster of ``workers`` processes
    (default: the number of cores), started at the first :meth:`map` and kept until :meth:`close`; ``serial``:
    in this process, one after the other. ``task``: the function a job runs, ``task(scenario, overrides,
    duration) -> summary`` (default :func:`run_job`; importable by the workers)."""

    def __init__(self, scenario: str, duration: float | None = None, *, scheduler: str | None = None,
                 workers: int | None = None, serial: bool = False, task: Callable = run_job,
                 connect_timeout: float = CONNECT_TIMEOUT_S):
        check_where(scheduler, workers, serial)
        self.scenario, self.duration, self.task = scenario, duration, task
        self.scheduler, self.workers, self.serial = scheduler, workers, serial
        self.connect_timeout = connect_timeout
        self._client = self._cluster = None
        self.where = "serial" if serial else None

    def __enter__(self) -> "Evaluator":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Stop the local cluster (a running cluster given by address is left running)."""
        if self._client is not None:
            close_client(self._client, self._cluster)
        self._client = self._cluster = None

    def _connect(self):
        if self._client is not None:
            return self._client
        # the local cluster is sized for the workers asked for, not the first batch (a calibration's first batch
        # may be one run)
        self._client, self._cluster, self.where = sweep_client(self.scheduler, self.workers, self.connect_timeout,
                                                               self.workers or os.cpu_count() or 1)
        return self._client

    def map(self, jobs: Sequence[Job], done: Callable[[int, Job, dict], None] | None = None) -> list[dict]:
        """Run ``jobs`` and return their summaries in the same order; ``done(index, job, summary)`` is called as
        each one finishes (in the order they finish)."""
        jobs = list(jobs)
        out: list[dict | None] = [None] * len(jobs)
        if not jobs:
            return []

        def finish(i: int, summary: dict) -> None:
            out[i] = summary
            if done is not None:
                done(i, jobs[i], summary)

        if self.serial:
            for i, (_, over) in enumerate(jobs):
                finish(i, self.task(self.scenario, over, self.duration))
            return out  # type: ignore[return-value]

        def ended(i: int, res: Outcome) -> None:
            if res.error is None:
                summary = res.value
            else:  # its worker died on every attempt (KilledWorker), or the task could not start
                tried = f"{res.attempts} time{'s' if res.attempts > 1 else ''}"
                summary = {"status": "failed",
                           "error": f"{type(res.error).__name__}: {' '.join(str(res.error).split())} (the job's "
                                    f"worker died or could not run it; tried {tried})"}
            finish(i, summary)

        # a job whose worker died is run again retry.RETRIES times at most
        run_retried(self._connect(), self.task, [(self.scenario, over, self.duration) for _, over in jobs], ended)
        return out  # type: ignore[return-value]


class Progress:
    """A line per finished job on ``stream``: how many are done of how many, the elapsed time and the time left
    (from the mean time per job so far and the jobs still to run). ``quiet``: no lines."""

    def __init__(self, total: int, what: str = "runs", stream=None, quiet: bool = False):
        # sys.stderr as it is now (a default argument would keep the stream of the time of import)
        self.total, self.what, self.stream, self.quiet = total, what, stream or sys.stderr, quiet
        self.done = 0
        self.t0 = time.perf_counter()

    def __call__(self, name: str, summary: dict) -> None:
        """Count one finished job ``name`` (its summary says whether it failed)."""
        self.done += 1
        if self.quiet:
            return
        elapsed = time.perf_counter() - self.t0
        left = elapsed / self.done * max(0, self.total - self.done)
        state = f"failed: {summary.get('error')}" if failed(summary) else "ok"
        print(f"[{self.done}/{self.total} {self.what}] {name}: {state}; {_hms(elapsed)} elapsed, "
              f"~{_hms(left)} left", file=self.stream, flush=True)


def _hms(s: float) -> str:
    s = int(round(s))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"
