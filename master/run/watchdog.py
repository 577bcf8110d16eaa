"""The component step time limit of a run in this process.

A component's ``do_step`` that never returns (an FMU's binary stuck in a loop) cannot be interrupted from Python:
signals wait for the C call to return, so Ctrl-C does nothing. :class:`Watchdog` watches the call in progress
(the master marks it in ``algorithm.CALL``: the component, the time, when it started) from a thread; a call older
than the limit makes it write the run's failure (``on_timeout``: the summary), print one line and end the process
with exit status 1. ``on_timeout`` (the run's session, session.py) also writes the rows still buffered and closes the time series,
marked incomplete (the run's thread is inside the component's step, not in the recorder); if that fails, what was
flushed stays in ``timeseries.h5.part``. A clean failure instead
(the run goes on to close its files) needs the FMU in a process of its own (``--fmu-process``, fmus/process.py).
"""
from __future__ import annotations

import os
import sys
import threading
import time
from typing import Callable

from rotorcosim.master.core import algorithm

#: the default limit on one component step [s]: generous (the slowest step of ours, the FE damper, takes ~0.1 s)
STEP_TIMEOUT_S = 600.0


class Watchdog:
    """A context manager watching the component step in progress (see the module's docstring).

    ``limit_s``: the longest a step may take [s]; ``on_timeout(message)``: called before the process ends;
    ``prog``: the program's name in the one-line message.

    >>> with Watchdog(600.0, on_timeout=write_failure):          # doctest: +SKIP
    ...     sim.run(schedule)
    """

    def __init__(self, limit_s: float, on_timeout: Callable[[str], None] | None = None, prog: str = "rotorcosim"):
        if not (limit_s > 0):
            raise ValueError(f"step time limit must be positive, got {limit_s}")
        self.limit = float(limit_s)
        self.on_timeout = on_timeout
        self.prog = prog
        self._stop = threading.Event()
        self._thread = None

    def __enter__(self) -> "Watchdog":
        algorithm.CALL = [None]
        self._call = algorithm.CALL
        self._thread = threading.Thread(target=self._watch, name="rotorcosim-watchdog", daemon=True)
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        algorithm.CALL = None

    def _watch(self) -> None:
        poll = min(1.0, self.limit / 4)
        while not self._stop.wait(poll):
            cur = self._call[0]
            if cur is None or time.monotonic() - cur[2] <= self.limit:
                continue
            name, t, _ = cur
            msg = (f"{name} did not return from its step at t = {t:.9g} s within {self.limit:g} s (the step time "
                   "limit); the process is ended, as a call inside a component's binary cannot be interrupted "
                   "(--fmu-process runs FMUs where such a run fails cleanly)")
            timed_out = algorithm.StepTimedOut
            try:
                if self.on_timeout is not None:   # the summary's error, as a run's other failures: "Kind: message"
                    self.on_timeout(f"{timed_out.__name__}: {msg}")
            finally:
                print(f"{self.prog}: error: {timed_out.what}: {msg}", file=sys.stderr, flush=True)
                # os._exit runs no atexit handler: an SSP archive's extraction folder would stay in /tmp
                ssp = sys.modules.get("rotorcosim.master.scenario.ssp")
                if ssp is not None:
                    ssp.remove_extracted()
                os._exit(1)
