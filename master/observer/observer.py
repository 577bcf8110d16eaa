"""The observer protocol: what a run calls on whatever watches it (libcosim's split: an observer never changes
the run), and the rows of a compiled-loop block an observer of a given stride sees."""
from __future__ import annotations

import numpy as np


def sampled_rows(ks: np.ndarray, stride: int) -> np.ndarray:
    """The rows of a compiled-loop block (step numbers ``ks``, an integer array) that an observer of ``stride``
    would have seen through ``step()``: the generic loop calls it when ``k % stride == 0``."""
    return np.flatnonzero(np.asarray(ks) % stride == 0)


class Observer:
    """Watches a run without changing it: the simulation calls its hooks (each does nothing by default).

    ``sim`` in every hook is the running :class:`~rotorcosim.master.simulation.Simulation` (``sim.t`` [s],
    ``sim.phase``, ``sim.value("comp.port")``). :attr:`stride`: :meth:`step` is called every ``stride``-th base
    step. An observer that also offers :meth:`block_signals` and :meth:`step_block` lets the compiled engine run
    (it hands over base steps in blocks); one that does not keeps the run on the generic loop.

    >>> class PeakPosition(Observer):
    ...     def __init__(self, ref):
    ...         self.ref, self.peak = ref, 0.0
    ...     def step(self, sim, t):
    ...         self.peak = max(self.peak, abs(float(sim.value(self.ref)[0])))
    >>> from rotorcosim.components.registry import create
    >>> from rotorcosim.master.core.system import Connection, System
    >>> from rotorcosim.master.schedule import Interval, Timeline
    >>> from rotorcosim.master.simulation import Simulation
    >>> system = System({"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1})}, [],
    ...                 inputs={"m1.F": 0.0})
    >>> peak = PeakPosition("m1.x")
    >>> report = Simulation(system, observers=[peak]).run(Timeline([Interval("TM", 1.0, 1e-3)]))
    >>> round(peak.peak, 3)                                          # the initial displacement [m]
    0.1
    """

    #: base steps between two calls of :meth:`step`
    stride = 1

    def start(self, sim, schedule) -> None:
        """The run starts (after the components' set-up); ``schedule`` is the one it runs."""
        pass

    def interval_start(self, sim, phase: str, step: float) -> None:
        """An interval starts at ``sim.t`` with base step ``step`` [s]; ``phase`` is its role (``COUPLED`` or
        ``HELD`` of the component contract; its name is ``sim.phase_name``)."""
        pass

    def step(self, sim, t: float) -> None:
        """A base step ended at time ``t`` [s] (called every :attr:`stride` steps, and at the start)."""
        pass

    def interval_end(self, sim, used) -> None:
        """An interval ended; ``used`` is its :class:`~rotorcosim.master.schedule.timeline.UsedInterval`."""
        pass

    def end(self, sim, error: BaseException | None) -> None:
        """The run ended: ``error`` is what ended it early, or None."""
        pass

    # the compiled engine (master/compiled/runner.py) runs base steps in chunks and hands them over in one call: an
    # observer that offers step_block names the signals it reads; None (the default) keeps the generic loop
    def block_signals(self, sim) -> list[str] | None:
        """The outputs (``"comp.port"``) :meth:`step_block` reads, or None: this observer needs :meth:`step`
        at every base step (the generic loop)."""
        return None

    def step_block(self, sim, ks: np.ndarray, ts: np.ndarray, data: dict) -> None:
        """Base steps ``ks`` (the interval's step counts after each step, an integer array) at times ``ts`` (an
        array): the same calls as
        ``step(sim, t)`` for every k with ``k % stride == 0``. ``data[ref]`` holds one row per base step of each
        signal named by :meth:`block_signals` (rows valid during the call only); the components hold the state
        after the last of them."""
        raise NotImplementedError

    # checkpoints (master/run/checkpoint.py): what the observer needs to continue an interrupted run; components
    # referenced from it are saved by name. The default keeps the observer's attributes.
    def checkpoint_state(self):
        """What this observer needs to continue an interrupted run (picklable; by default its attributes)."""
        return dict(self.__dict__)

    def restore_checkpoint(self, state) -> None:
        """Continue from ``state`` (:meth:`checkpoint_state`'s) of an interrupted run."""
        self.__dict__.update(state)
