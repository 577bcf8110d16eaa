"""The figures of a run drawn in worker processes, one figure a task.

Drawing the six blade-loss figures takes a few seconds of matplotlib, about as long as the compiled 2-minute
simulation itself; the simulation uses one core. So the workers start (and import matplotlib) while the run goes,
on the other cores, and draw the figures from the time series file in parallel once it is closed.

Used only where it helps and is safe: at least two cores, in a process that is not itself a worker (a sweep's
cases already fill the cores; daemonic processes cannot have children). Anything that goes wrong with the pool
(it cannot start, a worker dies) falls back to drawing in this process: the figures never depend on it.
"""
from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

WORKERS = 2


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def _warm() -> None:
    import signal

    # Ctrl-C is the parent's to handle (it checkpoints and exits 130); a worker just ends with it
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot  # noqa: F401  (the import is the slow part of the first figure)

    from . import figures_blade_loss  # noqa: F401


def _draw(module: str, job: str, series: str, out: str, ctx) -> list[str]:
    import importlib

    from .series import SeriesFile

    return importlib.import_module(module).draw(job, SeriesFile(series), Path(out), ctx)


class FigurePool:
    """Worker processes for figures, or none (:attr:`usable` False) where they would not help."""

    def __init__(self, workers: int = WORKERS):
        self._pool = None
        if _cores() < 2 or multiprocessing.parent_process() is not None or multiprocessing.current_process().daemon:
            return
        try:
            pool = ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("spawn"),
                                       initializer=_warm)
            # start the workers now, so that their imports overlap the simulation
            self._warming = [pool.submit(os.getpid) for _ in range(workers)]
            self._pool = pool
        except (OSError, RuntimeError, ValueError):
            self._pool = None

    @property
    def usable(self) -> bool:
        return self._pool is not None

    def draw(self, module, jobs, series: Path, out: Path, ctx) -> list[str]:
        """Draw ``jobs`` with ``module.draw(job, SeriesFile(series), out, ctx)``; returns the file names in the
        jobs' order. A job whose worker died is drawn here instead; an error of the drawing itself is raised."""
        from .series import SeriesFile

        futures = {}
        if self._pool is not None:
            try:
                futures = {job: self._pool.submit(_draw, module.__name__, job, str(series), str(out), ctx)
                           for job in jobs}
            except (BrokenProcessPool, RuntimeError):
                futures = {}
        names: list[str] = []
        local = None
        for job in jobs:
            fut = futures.get(job)
            if fut is not None:
                try:
                    names += fut.result()
                    continue
                except BrokenProcessPool:
                    pass
            local = local or SeriesFile(series)
            names += module.draw(job, local, out, ctx)
        return names

    def close(self) -> None:
        if self._pool is not None:
            self._pool.shutdown(wait=False, cancel_futures=True)
            self._pool = None
