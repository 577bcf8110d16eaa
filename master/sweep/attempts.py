"""A Dask worker that dies while running a sweep's case: how often the case runs again, and how it is named.

A task whose worker dies (killed, out of memory, a crash in native code) is run again by the scheduler on a
restarted or another worker. Each run of a task first counts itself on the scheduler, under the task's key: one
write of a key of its own (never a read, then a write of the sum, which two runs could interleave). A run that finds
more than :data:`RETRIES` runs before it gives up at once: the task is reported failed by name
(:class:`WorkerDied`), as a result and not as a raised error (a worker would log a raised one with its traceback),
and no further worker is put at risk.

Dask's own limit (``distributed.scheduler.allowed-failures``, default 3) stays the scheduler's: it counts the deaths
of every task a worker held, waiting ones too, and a scheduler started elsewhere keeps its own setting; the count
here is the task's own runs, the same on every cluster, and below Dask's default, so it decides first. The studies
(master/study/evaluate.py) still rely on Dask's limit, set to :data:`RETRIES` on their local cluster: counted
this way, a study on a local cluster of one worker waited forever after its first worker death (no worker process
was left; the cause is not found yet), so they keep the mechanism that works there.
"""
from __future__ import annotations

import uuid
from typing import Sequence

#: how many times a task whose worker died is run again before it is reported failed
RETRIES = 1
#: the Dask metadata key under which the runs of a task are counted (then a batch's token, then the task's name)
KEY = "rotorcosim-attempts"


class WorkerDied(RuntimeError):
    """A task (a sweep's case, a study's run) whose worker died on every run."""


def died(runs: int) -> str:
    """The error of a task whose worker died ``runs`` times, as a summary says it."""
    return f"{WorkerDied.__name__}: its worker died while running it, {runs} times (retried {RETRIES} time(s))"


def gave_up(key: Sequence[str]) -> str | None:
    """Count this run of the task ``key`` on the scheduler (called on the worker, first thing); the error to report
    instead of running it when more than :data:`RETRIES` runs came before, else None."""
    from dask.distributed import get_client

    client = get_client()
    client.set_metadata([*key, uuid.uuid4().hex], True)
    before = len(client.get_metadata(list(key), {})) - 1
    return died(before) if before > RETRIES else None


def started(client, batch: Sequence[str]) -> dict:
    """The tasks of ``batch`` (``[KEY, token]``) that a worker has begun to run: name -> its runs."""
    return client.get_metadata(list(batch), {})


def task_error(exc: BaseException) -> str:
    """A failed task's error, as a summary says it: Dask's own give-up after worker deaths (KilledWorker) is a
    :class:`WorkerDied` too."""
    from distributed import KilledWorker

    if isinstance(exc, KilledWorker):
        return f"{WorkerDied.__name__}: its worker died while running it ({exc})"
    return f"{type(exc).__name__}: {' '.join(str(exc).split())}"
