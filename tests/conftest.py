import os
import signal

import pytest

from rotorcosim.master.observer.progress import Progress


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
