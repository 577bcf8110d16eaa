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

from rotorcosim.components.contract import HELD
from rotorcosim.components.validity import Tracker, warning_line

from .observer import Observer, sampled_rows


#: sampled rows kept before the checks run on them: the checks cost per call, not per row (~10 us each)
FLUSH_ROWS = 8192


class Validity(Observer):
    """``record_step``: the sampling interval in thermo-mechanical intervals (every step of a thermal-only one),
    the recorder's; ``label`` starts the warning lines (the scenario's name). Samples are buffered and checked
    by the thousand, at the latest at the end of each interval."""

    def __init__(self, record_step: float, label: str = "rotorcosim run"):
        self.record_step = float(record_step)
        self.label = label
        self.tracker: Tracker | None = None
        self._restored: dict | None = None
        self._refs: list = []
        self._clear()

    def _clear(self):
        self._t: list[np.ndarray] = []
        self._rows: dict[str, list[np.ndarray]] = {r: [] for r, *_ in self._refs}
        self._n = 0

    def start(self, sim, schedule):
        comps = sim.system.components
        # a plug-in that is no Component subclass declares nothing either
        self.tracker = Tracker({n: tuple(getattr(c, "validity", tuple)()) for n, c in comps.items()})
        if self._restored is not None:   # a resumed run: what the interrupted one found
            self.tracker.left = {int(k): dict(v) for k, v in self._restored.items()}
        self._inputs = {r for r in self.tracker.ports()
                        if comps[r.partition(".")[0]].variable(r.partition(".")[2]).causality == "input"}
        self._active = set(comps)
        self._taps(sim)
        if sim.resume_point is None:   # a resumed run's start is a state the interrupted run checked already
            self.step(sim, sim.t)
            self._flush()

    def _taps(self, sim):
        """(ref, component, port, is an input) of the ports the active components' checks read."""
        comps = sim.system.components
        self._refs = [(r, comps[r.partition(".")[0]], r.partition(".")[2], r in self._inputs)
                      for r in self.tracker.ports() if r.partition(".")[0] in self._active]
        self._clear()

    def interval_start(self, sim, phase, step):
        self.stride = 1 if phase == HELD else max(1, int(round(min(self.record_step / step, 2.0 ** 62))))
        # the components whose outputs change in this interval
        self._active = {n for n, c in sim.system.components.items() if phase in c.phases and not (
            phase == HELD and c.holds_state_in_TO)}
        self._taps(sim)

    def step(self, sim, t):
        self._t.append(np.array([t]))
        for r, comp, port, is_input in self._refs:
            self._rows[r].append(np.array(comp.u[port] if is_input else comp.y[port], dtype=float)[None])
        self._n += 1
        if self._n >= FLUSH_ROWS:
            self._flush()

    def block_signals(self, sim):
        return [r for r, _, _, is_input in self._refs if not is_input]

    def step_block(self, sim, ks, ts, data):
        rows = sampled_rows(ks, self.stride)
        if not len(rows):
            return
        self._t.append(np.asarray(ts)[rows])
        for r, comp, port, is_input in self._refs:
            if is_input:   # known at the block's end only: the last sampled row gets it, the others NaN (not judged)
                x = np.full((len(rows), len(comp.u[port])), np.nan)
                x[-1] = comp.u[port]
            else:
                x = data[r][rows]
            self._rows[r].append(x)
        self._n += len(rows)
        if self._n >= FLUSH_ROWS:
            self._flush()

    def _flush(self):
        if self._n:
            self.tracker.update(np.concatenate(self._t), {r: np.concatenate(x) for r, x in self._rows.items()},
                                only=self._active)
        self._clear()

    def interval_end(self, sim, used):
        self._flush()

    def end(self, sim, error):
        if self.tracker is None:
            return
        self._flush()
        for entry in self.entries():
            print(warning_line(self.label, entry), file=sys.stderr)

    def entries(self) -> list[dict]:
        """summary.json's ``validity`` list (empty when every check held, or before the run started)."""
        return [] if self.tracker is None else self.tracker.entries()

    def checkpoint_state(self):
        if self.tracker is not None:
            self._flush()
        return {"left": None if self.tracker is None else dict(self.tracker.left)}

    def restore_checkpoint(self, state):
        self._restored = state.get("left")
