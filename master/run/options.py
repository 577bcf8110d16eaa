"""How one run is made, checked once: :class:`RunOptions`, the options of :func:`rotorcosim.simulate` that are
not the scenario, the schedule or the duration.

>>> opts = RunOptions(record=["osc.x"], engine="python")
>>> opts.record, opts.dpi, opts.checkpoint_every
(('osc.x',), 150, 180.0)
>>> RunOptions(engine="fast")
Traceback (most recent call last):
...
ValueError: engine 'fast' not in ('auto', 'python', 'compiled')
"""
from __future__ import annotations

import numbers
import os
from dataclasses import dataclass
from typing import Sequence

from rotorcosim.master.compiled.choice import ENGINES
from rotorcosim.master.run.checkpoint import EVERY_S
from rotorcosim.master.run.outputs import check_dpi


@dataclass(frozen=True)
class RunOptions:
    """The options of one run, each checked when the record is made (a one-line error naming the option).

    ``out``: the output folder (None: in memory; checked when it is taken, master/run/rundir.py); ``record``: the ports to record (None: the scenario's
    ``[outputs] record``); ``figures``, ``progress``; ``overwrite`` / ``resume``: what the folder may hold
    (master/run/rundir.py); ``force``: run beyond the budget's limit; ``checkpoint_every`` [s of wall time] (None:
    no checkpoints); ``step_timeout`` [s] (0: no limit, master/run/watchdog.py); ``engine``: ``"auto"``,
    ``"python"`` or ``"compiled"``; ``dpi``: the figures' resolution (None: the default, stored as the number used).
    """
    out: str | os.PathLike | None = None
    record: Sequence[str] | None = None
    figures: bool = True
    progress: bool = False
    overwrite: bool = False
    resume: bool = False
    force: bool = False
    checkpoint_every: float | None = EVERY_S
    step_timeout: float = 0.0
    engine: str = "auto"
    dpi: float | None = None

    def __post_init__(self):
        record = self.record
        if isinstance(record, (str, bytes)):  # a lone name would be read letter by letter
            raise TypeError(f"record: give a list of 'component.port' names, e.g. record=[{record!r}]")
        if self.engine not in ENGINES:
            raise ValueError(f"engine {self.engine!r} not in {ENGINES}")
        dpi = check_dpi(self.dpi)
        step_timeout = self.step_timeout
        if not (isinstance(step_timeout, numbers.Real) and 0 <= step_timeout < float("inf")):
            raise ValueError(f"step_timeout must be a number of seconds >= 0 (0: no limit), got {step_timeout!r}")
        every = self.checkpoint_every
        if every is not None and not (isinstance(every, numbers.Real) and every > 0):
            raise ValueError(f"checkpoint_every must be a positive number of seconds (or None: no checkpoints), got "
                             f"{every!r}")
        # the checked values in the forms the run uses (frozen: set once, here)
        object.__setattr__(self, "dpi", dpi)
        object.__setattr__(self, "record", None if record is None else tuple(record))

    def signals(self, outputs: dict) -> list[str]:
        """The ports the run records: :attr:`record`, else the scenario's ``[outputs] record`` (``outputs``),
        each written ``component.port`` and listed once."""
        signals = list(outputs.get("record", []) if self.record is None else self.record)
        for i, ref in enumerate(signals):
            if not isinstance(ref, str) or "." not in ref:
                raise ValueError(f"record: {ref!r} must be written 'component.port'")
            if ref in signals[:i]:
                raise ValueError(f"record: {ref!r} is listed twice")
        return signals
