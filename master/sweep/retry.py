"""Tasks on a Dask cluster whose worker may die: the one retry mechanism of sweeps and studies.

:func:`run_retried` sends the calls of a function to a Dask client, no more at once than the cluster runs, and
gives each one's :class:`Outcome` as it ends. A task whose worker died while running it is run again,
:data:`RETRIES` times at most, then reported failed.

Who died under whom is known from two records, neither of which is ever read and written back:

* each start of a call on a worker writes its own entry on the scheduler (``Client.set_metadata`` under
  ``[ATTEMPTS, run, call, a fresh id]``: the worker's address and False) before the call runs, and the same entry
  again (True) when the call ends, returning or raising; so the entries of a call are its starts, in the order
  they arrived whichever scheduler reran it, and the starts that never ended are the workers that died under it;
* a worker's death reaches the client as Dask's :class:`distributed.KilledWorker`; the client then reads the
  call's entries. A task that was only waiting on the dead worker (it never started: a restarting worker leaves
  its neighbours' tasks on the one still up) is sent again without being charged; a call that ended on a worker
  that died before its value was fetched is rerun by Dask itself, and charged nothing either.

The local clusters the project starts (:func:`rotorcosim.master.sweep.engine.dask_client`) let the scheduler rerun
no task itself (``distributed.scheduler.allowed-failures`` :data:`ALLOWED_FAILURES`): each death reaches the
client, which decides. A scheduler given by address keeps its own setting (Dask's default 3): it reruns a task
that many times before the client hears of it, so a task whose worker always dies is reported after
``allowed-failures + 1`` deaths, each one still named; a scheduler started with
``DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES=0`` behaves as the local cluster.
"""
from __future__ import annotations

import uuid
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

#: how often a task whose worker died is run again before it is reported failed
RETRIES = 1
#: the scheduler setting of the local clusters the project starts: every worker's death reaches the client
ALLOWED_FAILURES = 0
#: the scheduler metadata under which the starts of each call are recorded (per run and call)
ATTEMPTS = "rotorcosim-attempts"


@dataclass
class Outcome:
    """How a call ended: ``value`` (what it returned) or ``error`` (what it raised, or the
    :class:`distributed.KilledWorker` of its last start), ``died_on`` (the addresses of the workers that died
    while running it, in order) and ``worker`` (the address of the worker that ran it to its end, or of the last
    one that died under it)."""
    value: Any = None
    error: BaseException | None = None
    died_on: list[str] = field(default_factory=list)
    worker: str | None = None

    @property
    def worker_died(self) -> bool:
        """Whether the call ended because its worker died on every start."""
        from distributed import KilledWorker

        return isinstance(self.error, KilledWorker)

    @property
    def attempts(self) -> int:
        """How often the call was started."""
        return len(self.died_on) + (0 if self.worker_died else 1)


def on_worker(key: list, fn: Callable, *args) -> tuple[str, Any]:
    """What a worker runs: record this start under ``key`` on the scheduler, run ``fn(*args)``, record its end;
    returns the worker's address and the call's value."""
    from distributed import get_client, get_worker

    me, entry, client = get_worker().address, [*key, uuid.uuid4().hex], get_client()
    client.set_metadata(entry, [me, False])
    try:
        return me, fn(*args)
    finally:
        client.set_metadata(entry, [me, True])


def cluster_slots(client) -> int:
    """The tasks the cluster runs at once: the threads of its workers (at least 1)."""
    workers = client.scheduler_info().get("workers", {})
    return max(1, sum(w.get("nthreads", 1) for w in workers.values()))


def run_retried(client, fn: Callable, calls: Sequence[tuple], done: Callable[[int, Outcome], None], *,
                retries: int = RETRIES, submitted: set | None = None) -> None:
    """Run ``fn(*calls[i])`` for each i on ``client`` and call ``done(i, outcome)`` as each ends (in the order
    they end). A call whose worker died under it is run again up to ``retries`` times; any other error ends it.
    ``submitted``: a set this function fills with the indices sent to the cluster (the others had not started
    when ``done`` or the client raised). Whatever ``done`` raises ends the run, the tasks in flight cancelled."""
    from distributed import KilledWorker, as_completed

    run = uuid.uuid4().hex
    waiting = list(range(len(calls)))
    futures: dict = {}
    running = as_completed()

    def submit(i: int) -> None:
        fut = client.submit(on_worker, [ATTEMPTS, run, str(i)], fn, *calls[i], pure=False)
        futures[fut] = i
        if submitted is not None:
            submitted.add(i)
        running.add(fut)

    def died_on(i: int) -> list[str]:
        """The workers that started call i and died before it ended, in order."""
        return [w for w, ended in client.get_metadata([ATTEMPTS, run, str(i)], {}).values() if not ended]

    try:
        for _ in range(min(cluster_slots(client), len(waiting))):
            submit(waiting.pop(0))
        for fut in running:
            i = futures.pop(fut)
            out = Outcome()
            try:
                out.worker, out.value = fut.result()
                out.died_on = died_on(i)
            except KilledWorker as exc:
                out.error = exc
                out.died_on = died_on(i)
                out.worker = out.died_on[-1] if out.died_on else exc.last_worker.address
                if len(out.died_on) <= retries:
                    submit(i)   # into the slot the dead worker's task left
                    continue
            except Exception as exc:  # the call raised, or could not be run or fetched (the scheduler gone: asked
                out.error = exc       # nothing more, the client would wait for it to come back)
            if waiting:
                submit(waiting.pop(0))
            done(i, out)
    finally:
        for fut in futures:
            fut.cancel()
