"""The validity observer: during a run, the components' declared envelopes (``Component.validity()``,
components/validity.py) evaluated at the recorder's sampling; at the end, one warning line per check left and the
``validity`` list of summary.json.

Only the components stepped in an interval are checked in it (a component frozen or held in a thermal-only
interval keeps its outputs). Checks that read an input are evaluated at the last step of each compiled block
(~2 000 steps, the inputs are not in the block's rows) and at every sample of the generic loop.
"""
from __future__ import annotations

import sys

import numpy as np

from rotorcosim.components.validity import Tracker, warning_line

from .observers import Observer, sampled_rows


class Validity(Observer):
    """``record_step``: the sampling interval in thermo-mechanical intervals (every step of a thermal-only one),
    the recorder's; ``label`` starts the warning lines (the scenario's name)."""

    def __init__(self, record_step: float, label: str = "rotorcosim run"):
        self.record_step = float(record_step)
        self.label = label
        self.tracker: Tracker | None = None
        self._restored: dict | None = None

    def start(self, sim, schedule):
        comps = sim.system.components
        self.tracker = Tracker({n: tuple(c.validity()) for n, c in comps.items()})
        if self._restored is not None:   # a resumed run: what the interrupted one found
            self.tracker.left = {int(k): dict(v) for k, v in self._restored.items()}
        self._inputs = {r for r in self.tracker.ports()
                        if comps[r.partition(".")[0]].variable(r.partition(".")[2]).causality == "input"}
        if sim.resume_point is None:   # a resumed run's start is a state the interrupted run checked already
            self._sample(sim, sim.t, comps)

    def interval_start(self, sim, phase, step):
        self.stride = 1 if phase == "TO" else max(1, int(round(min(self.record_step / step, 2.0 ** 62))))
        comps = sim.system.components
        # the components whose outputs change in this interval
        self._active = {n: c for n, c in comps.items() if phase in c.phases and not (
            phase == "TO" and c.holds_state_in_TO)}

    def _sample(self, sim, t, active):
        tr = self.tracker
        rows = {}
        for r in tr.ports():
            comp, _, port = r.partition(".")
            c = sim.system.components[comp]
            rows[r] = np.asarray(c.u[port] if r in self._inputs else c.y[port], dtype=float)[None]
        tr.update(np.array([t]), rows, only=active)

    def step(self, sim, t):
        self._sample(sim, t, self._active)

    def block_signals(self, sim):
        return [r for r in self.tracker.ports() if r not in self._inputs]

    def step_block(self, sim, ks, ts, data):
        rows = sampled_rows(ks, self.stride)
        if not len(rows):
            return
        block = {r: data[r][rows] for r in self.block_signals(sim)}
        comps = sim.system.components
        for r in self._inputs:   # known at the block's end only: the last sampled row gets them, the others NaN
            comp, _, port = r.partition(".")
            x = np.full((len(rows), comps[comp].variable(port).size), np.nan)
            x[-1] = comps[comp].u[port]
            block[r] = x
        self.tracker.update(np.asarray(ts)[rows], block, only=self._active)

    def end(self, sim, error):
        for entry in self.entries():
            print(warning_line(self.label, entry), file=sys.stderr)

    def entries(self) -> list[dict]:
        """summary.json's ``validity`` list (empty when every check held, or before the run started)."""
        return [] if self.tracker is None else self.tracker.entries()

    def checkpoint_state(self):
        return {"left": None if self.tracker is None else dict(self.tracker.left)}

    def restore_checkpoint(self, state):
        self._restored = state.get("left")
