"""The plug-in of a sweep's local Dask workers (a module of its own: it imports distributed, which a serial sweep
and the command line's start-up need not load)."""
from __future__ import annotations

import signal
import threading

from distributed.diagnostics.plugin import WorkerPlugin


class IgnoreInterrupt(WorkerPlugin):
    """A local worker ignores SIGINT: the sweep's own process ends it (see engine.py, ``dask_client``)."""

    def setup(self, worker):
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, signal.SIG_IGN)
