"""Discrete events (master/core/events.py): an event indicator's zero located to its tolerance against the exact
time, the event handed to its component once, the base steps' grid kept, a run without indicators untouched, and
the set-ups the locator refuses."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rotorcosim.components.contract import Component, ContractError, Variable
from rotorcosim.components.registry import create
from rotorcosim.master.core.system import Connection, System
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation

#: the oscillator of testing.mass (m = 1 kg, k = 40 N/m, from x0 = 0.1 m at rest) integrates exactly over a step:
#: x(t) = x0 cos(w t), its zeros at (2 n + 1) pi / (2 w)
W = math.sqrt(40.0)


class ZeroWatch(Component):
    """Watches a displacement: an event at each of its zeros (the indicator is the displacement itself)."""

    variables = (
        Variable("event_tolerance", "parameter", unit="s", start=1e-7),
        Variable("x", "input", unit="m"),
        Variable("crossings", "output", unit="1"),
    )
    event_indicators = ("x",)

    def setup(self, t0=0.0):
        super().setup(t0)
        self.state = {"n": np.zeros(1)}
        self.y["crossings"] = self.state["n"].copy()

    def do_step(self, t, h):
        self.time = t + h
        self.y["crossings"] = self.state["n"].copy()

    def indicators(self):
        return np.array([self.u["x"][0]])

    def update_discrete(self, t, which):
        self.state["n"] = self.state["n"] + 1.0
        self.y["crossings"] = self.state["n"].copy()
        return {"kind": "zero", "values": {"x": float(self.u["x"][0])}}


def _sim(tolerance=1e-7, watch=True, cycle=None):
    comps = {"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1})}
    cons = []
    if watch:
        comps["w"] = ZeroWatch("w", {"event_tolerance": tolerance})
        cons = [Connection("m1.x", "w.x")]
    return Simulation(System(comps, cons, inputs={"m1.F": np.zeros(1)}), order=list(comps), cycle=cycle)


def test_zeros_located_to_the_tolerance():
    """Both zeros of x0 cos(w t) in 1 s found within 0.1 us after the exact ones (the event's time is the end of
    the bisection's bracket), each handed over once, the steps' grid and count those of the run without events."""
    sim = _sim()
    report = sim.run(Timeline([Interval("TM", duration=1.0, step=1e-3)]))
    exact = [math.pi / (2 * W), 3 * math.pi / (2 * W)]
    assert [e["kind"] for e in report.events] == ["zero", "zero"]
    for e, t in zip(report.events, exact):
        assert e["component"] == "w" and e["indicators"] == ["x"]
        assert 0.0 <= e["t_s"] - t <= 1e-7
        assert abs(e["values"]["x"]) < 0.1 * W * 1e-7
    assert float(sim.value("w.crossings")[0]) == 2.0
    plain = _sim(watch=False)
    plain.run(Timeline([Interval("TM", duration=1.0, step=1e-3)]))
    # the grid kept: the mass ends where it ends without the watcher, to round-off of the split steps
    assert float(sim.value("m1.x")[0]) == pytest.approx(float(plain.value("m1.x")[0]), abs=1e-12)
    # a base step split at an event is two steps of each component
    assert report.component_steps["m1"] == 1000 + 2 and report.t_end == pytest.approx(1.0)
    assert plain.report.events is None   # no indicator in the run: no events list at all


def test_tolerance_larger_than_the_step_is_named():
    with pytest.raises(ContractError, match=r"w\.event_tolerance"):
        _sim(tolerance=2e-3).run(Timeline([Interval("TM", duration=0.01, step=1e-3)]))


def test_multirate_interval_with_an_indicator_is_refused():
    sim = _sim()
    sim.steps = {"w": 2e-3}
    with pytest.raises(ContractError, match="every component must step at the interval's step"):
        sim.run(Timeline([Interval("TM", duration=0.01, step=1e-3)]))


def test_an_indicator_in_a_held_interval_is_refused():
    """A component with an event indicator that steps in a held interval: a one-line error naming it and the
    phase (events are located in coupled intervals)."""
    sim = _sim(cycle=0.01)
    sim.system.components["w"].phases = frozenset({"TM", "TO"})
    sim.system.components["m1"].phases = frozenset({"TM", "TO"})
    with pytest.raises(ContractError, match="component w declares event indicators and steps in the held phase TO"):
        sim.run(Timeline([Interval("TM", duration=0.05, step=1e-3), Interval("TO", duration=0.01, step=1e-3)]))
