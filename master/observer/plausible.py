"""The plausibility observer: once every component is set up (its parameters passed their own checks), one
warning line on stderr per parameter its user set outside the plausible range the component declares
(components/plausibility.py): a value off by a unit factor, where the component can tell; and an event set at or
after the end of the run (a component's event time, such as a fuel cut), which then never happens in it.

Warned at the start of the run, not when the system is built, so that a value a component refuses (a negative
stiffness) gets the component's error alone, not a warning beside it.
"""
from __future__ import annotations

import sys

from rotorcosim.components import plausibility

from .observer import Observer


class Plausibility(Observer):
    """``label`` starts the warning lines (the scenario's name); :attr:`lines` keeps them."""

    stride = 2 ** 62  # it looks at no step

    def __init__(self, label: str = "rotorcosim run"):
        self.label = label
        self.lines: list[str] = []

    def start(self, sim, schedule) -> None:
        if self.lines:  # a resumed run warned when it started
            return
        duration = getattr(schedule, "duration", None)   # every schedule of the master has one; a caller's may not
        for comp in sim.system.components.values():
            self.lines += plausibility.warnings_of(comp)
            if duration is not None:
                self.lines += plausibility.event_warnings(comp, sim.t + duration)
        for line in self.lines:
            print(f"{self.label}: warning: {line}", file=sys.stderr)

    def block_signals(self, sim):
        return []

    def step_block(self, sim, ks, ts, data) -> None:
        pass
