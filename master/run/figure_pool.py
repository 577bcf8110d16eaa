"""The figures of a run drawn in worker processes, a few figures each.

Drawing a case's figures takes a few seconds of matplotlib, about as long as the compiled 2-minute
simulation itself, which uses one core. So the workers start (and import matplotlib) while the run goes, on the
other cores, and draw the figures from the time series file in parallel once it is closed.

The workers are fresh interpreters running ``python -m rotorcosim.master.run.figure_worker``, not multiprocessing's
children: those would re-run the user's script (multiprocessing's "spawn" imports ``__main__``), and a forked
copy of a process with threads is not safe. A worker reads one request (JSON on its stdin) and answers on stdout.

Used only where it helps: at least two cores, in a process that is not itself a worker (a sweep's cases already
fill the cores). Anything that goes wrong with a worker (it cannot start, import or draw, it dies) falls back to
drawing in this process: the figures never depend on the workers, and a drawing error is raised from here.
"""
from __future__ import annotations

import json
import multiprocessing
import os
import select
import subprocess
import sys
import threading
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path

WORKERS = 2
#: how long a worker may take for its figures before this process draws them itself [s]
TIMEOUT_S = 300.0


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


class FigurePool:
    """Worker processes for figures, or none (:attr:`usable` False) where they would not help."""

    def __init__(self, workers: int = WORKERS, preload: Sequence[str] = (), after: threading.Event | None = None):
        """``preload``: modules the workers import at start (the figure module the run will use), besides
        matplotlib. ``after``: the workers start once it is set (or the figures are wanted): the simulation's
        ``first_compiled`` event, so that on a fresh machine they do not take a core from the first compilations
        (master/compiled/ahead.py), while the run's steps leave one idle."""
        self._procs: list[subprocess.Popen] = []
        self.by_workers: list[str] = []
        self._lock = threading.Lock()
        self._closing = False
        self._hurry = threading.Event()  # the figures are wanted (or the pool closed): start every worker now
        self._starter: threading.Thread | None = None
        if _cores() < 2 or multiprocessing.parent_process() is not None or os.environ.get("ROTORCOSIM_FIGURE_WORKER"):
            return
        self._cmd = [sys.executable, "-m", "rotorcosim.master.run.figure_worker", *preload]
        self._env = {**os.environ, "ROTORCOSIM_FIGURE_WORKER": "1"}
        if after is not None and not after.is_set():
            self._starter = threading.Thread(target=self._start_after, args=(after, workers), daemon=True)
            self._starter.start()
        elif self._start() and workers > 1:
            # the others one at a time, each when the previous one is ready: two workers importing at once beside
            # the run make three busy processes on two cores, which takes a third of a core from the run
            self._starter = threading.Thread(target=self._start_rest, args=(workers - 1,), daemon=True)
            self._starter.start()

    def _start_after(self, after: threading.Event, workers: int) -> None:
        while not after.wait(0.05) and not self._hurry.is_set():
            pass
        if self._start() and workers > 1:
            self._start_rest(workers - 1)

    def _start(self) -> bool:
        with self._lock:
            if self._closing:
                return False
            try:
                self._procs.append(subprocess.Popen(
                    self._cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                    env=self._env, text=True,
                    start_new_session=True))  # Ctrl-C is the parent's to handle; close() ends the workers
                return True
            except OSError:
                return False

    def _start_rest(self, n: int) -> None:
        for _ in range(n):
            _wait_ready(self._procs[-1], self._hurry)
            if not self._start():
                return

    def _all_started(self) -> None:
        self._hurry.set()
        if self._starter is not None:
            self._starter.join()
            self._starter = None

    @property
    def usable(self) -> bool:
        """True when workers were started (at least two cores, not inside a worker)."""
        return bool(self._procs)

    def draw(self, module, jobs, series: Path, out: Path, ctx) -> list[str]:
        """Draw ``jobs`` with ``module.draw(job, SeriesFile(series), out, ctx)``, shared among the workers;
        returns the file names in the jobs' order. A worker that fails leaves its jobs to this process."""
        from rotorcosim.master.observer.series import SeriesFile

        self._all_started()
        shares = {i: list(jobs[i::len(self._procs)]) for i in range(len(self._procs))} if self._procs else {}
        for i, p in enumerate(self._procs):
            req = {"module": module.__name__, "jobs": shares[i], "series": str(series), "out": str(out),
                   "context": asdict(ctx)}
            try:
                p.stdin.write(json.dumps(req) + "\n")
                p.stdin.flush()  # not closed: communicate() below closes it
            except OSError:  # the worker is gone: its share is drawn here
                pass
        drawn: dict[str, list[str]] = {}
        for i, p in enumerate(self._procs):
            try:
                answer, _ = p.communicate(timeout=TIMEOUT_S)
                if p.returncode == 0:
                    drawn.update(json.loads(answer.strip().splitlines()[-1])["names"])
            except (subprocess.TimeoutExpired, ValueError, KeyError, IndexError, OSError):
                p.kill()
        self._procs = []
        self.by_workers = sorted(drawn)  # which jobs the workers drew (the rest were drawn here)
        local = None
        names: list[str] = []
        for job in jobs:
            if job not in drawn:
                local = local or SeriesFile(series)
                drawn[job] = module.draw(job, local, out, ctx)
            names += drawn[job]
        return names

    def close(self) -> None:
        """End workers that were never given their figures (the run failed or drew none)."""
        with self._lock:
            self._closing = True
        self._all_started()
        for p in self._procs:
            try:
                p.kill()
                p.communicate(timeout=5)
            except (OSError, subprocess.TimeoutExpired, ValueError):
                pass
        self._procs = []


def _wait_ready(p: subprocess.Popen, hurry: threading.Event) -> None:
    """Until worker ``p`` says it is ready (its first line, after its imports), ends, or ``hurry`` is set."""
    while not hurry.is_set():
        try:
            ready, _, _ = select.select([p.stdout], [], [], 0.05)
        except (OSError, ValueError):  # no select on this pipe (not POSIX): start the next one now
            return
        if ready:
            p.stdout.readline()  # the worker's "ready" line ('' if it ended)
            return
