import os
import signal

import numpy  # noqa: F401  (loads numpy's BLAS before the limit below)
import pytest
import scipy.linalg  # noqa: F401  (and scipy's own)
from threadpoolctl import threadpool_limits

from rotorcosim.master.observer.progress import Progress


def pytest_configure(config):
    """One BLAS thread in every test process. The suite runs one process per core (pytest-xdist, -n auto); a BLAS
    pool of one thread per core in each of them oversubscribes the cores, and the tests that call the linear
    algebra directly (critical speeds, ROSS, the FE damper) then run several times slower than on one thread
    (measured: the shipped engine's critical speeds 14-50 s of CPU against 3.5-5 s on a loaded 2-core machine).
    A run already does the same inside (master/core/threads.py); the subprocesses a test starts are not
    affected."""
    threadpool_limits(limits=1)


@pytest.fixture
def sigint_at(monkeypatch):
    """``sigint_at(t)``: a real SIGINT sent to this process when the run's simulated time first passes ``t``
    (from the progress observer, which every run has)."""

    def arm(t_signal: float):
        original = Progress.step
        fired = []

        def step(self, sim, t):
            if not fired and t >= t_signal:
                fired.append(t)
                os.kill(os.getpid(), signal.SIGINT)
            original(self, sim, t)

        monkeypatch.setattr(Progress, "step", step)
        return fired

    return arm
