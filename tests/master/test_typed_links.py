"""The master's side of typed ports, unit conversions, stop requests and the first recorded sample,
on small native components (the FMU side is in tests/fmus/test_import_types.py)."""
from __future__ import annotations

import csv

import numpy as np
import pytest

from rotorcosim.components.contract import Component, StopRequested, Variable
from rotorcosim.components.registry import create
from rotorcosim.master.observer.observer import Observer
from rotorcosim.master.observer.recorder import Recorder
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System, SystemError_


class Counter(Component):
    """Outputs k (Integer), k as a Real, and k > 2 (Boolean) after its k-th step; asks to stop at ``stop_at``."""

    variables = (Variable("stop_at", "parameter", start=1e9), Variable("k", "output", type="Integer"),
                 Variable("r", "output", unit="m"), Variable("b", "output", type="Boolean"))

    def setup(self, t0=0.0):
        super().setup(t0)
        self.y["k"][:] = 0

    def do_step(self, t, h):
        if t + h > self.p["stop_at"] + 1e-12:
            raise StopRequested(self.name, t, "asked by the test")
        self.y["k"] = self.y["k"] + 1
        self.y["r"] = self.y["k"].astype(float)
        self.y["b"] = self.y["k"] > 2


class Sink(Component):
    """Keeps every input it receives at each step."""

    variables = (Variable("k", "input", type="Integer"), Variable("r", "input", unit="mm"),
                 Variable("b", "input", type="Boolean"), Variable("seen", "output", unit="mm"))

    def setup(self, t0=0.0):
        super().setup(t0)
        self.log = []

    def do_step(self, t, h):
        self.log.append({k: v.copy() for k, v in self.u.items()})
        self.y["seen"] = self.u["r"].copy()


def _system(sink_step_multiple=1, **counter):
    comps = {"c": Counter("c", counter), "s": Sink("s")}
    cons = [Connection("c.k", "s.k"), Connection("c.r", "s.r"), Connection("c.b", "s.b")]
    return System(comps, cons)


def test_first_recorded_sample_is_after_initialisation(tmp_path):
    """testing.mass computes x = x0 in its set-up (its declared start is 0): the t = 0 row must hold x0."""
    comps = {"m1": create("testing.mass", "m1", {"x0": 0.1, "k": 40.0}),
             "m2": create("testing.spring", "m2", {"x0": -0.05})}
    sys_ = System(comps, [Connection("m1.x", "m2.x_in"), Connection("m1.v", "m2.v_in"), Connection("m2.F", "m1.F")])
    path = tmp_path / "rec.csv"
    sim = Simulation(sys_, observers=[Recorder(path, ["m1.x", "m2.x", "m2.F"], record_step=1e-3)])
    sim.run(Timeline([Interval("TM", 0.002, 1e-3)]))
    rows = list(csv.reader(path.open()))
    first = dict(zip(rows[0], rows[1]))
    assert float(first["time (s)"]) == 0.0
    assert float(first["m1.x (m)"]) == 0.1 and float(first["m2.x (m)"]) == -0.05
    assert float(first["m2.F (N)"]) != 0.0          # the coupling force of the initial positions


def test_integers_and_booleans_are_held_reals_averaged_across_rates():
    """A slow consumer (3 steps of the producer per step) gets the mean of a Real, the last value of an Integer
    and of a Boolean (a mean of 1, 2, 3 would be 2, of an Integer it must not be)."""
    sys_ = _system()
    sim = Simulation(sys_, steps={"s": 3e-3})
    sim.run(Timeline([Interval("TM", 6e-3, 1e-3)]))
    log = sys_.components["s"].log
    assert [int(x["k"][0]) for x in log] == [3, 6]
    assert [x["k"].dtype for x in log] == [np.int64, np.int64]
    assert [bool(x["b"][0]) for x in log] == [True, True]
    # the Real: mean of 1, 2, 3 m (then 4, 5, 6) converted m -> mm
    assert [float(x["r"][0]) for x in log] == [2000.0, 5000.0]


def test_unit_conversion_only_on_links_that_need_it():
    sys_ = _system()
    assert set(sys_.converters) == {"s.r"}                       # m -> mm; the Integer and Boolean links: none
    assert sys_.converters["s.r"](np.array([1.5])).tolist() == [1500.0]


def test_native_unit_checks_still_refuse_other_dimensions():
    comps = {"c": Counter("c"), "m": create("testing.mass", "m")}
    with pytest.raises(SystemError_, match=r"c\.r -> m\.F: units differ, \[m\] \(m\) -> \[N\] \(kg\.m\.s-2\)"):
        System(comps, [Connection("c.r", "m.F")])


def test_typed_links_need_explicit_conversions():
    comps = {"c": Counter("c"), "s": Sink("s")}
    with pytest.raises(SystemError_, match=r'c\.r -> s\.k: a Real output into an Integer input needs an explicit '
                                           r'conversion: add convert = "round"'):
        System(comps, [Connection("c.r", "s.k"), Connection("c.r", "s.r"), Connection("c.b", "s.b")])
    s = System(comps, [Connection("c.r", "s.k", convert="round", unit="m"), Connection("c.k", "s.r", convert="float",
                                                                                        unit="mm"),
                       Connection("c.k", "s.b", convert="nonzero")])
    assert s.converters["s.k"](np.array([2.5, -2.5, 1.4999])).tolist() == [3, -3, 1]
    assert s.converters["s.b"](np.array([0, 3])).tolist() == [False, True]
    assert s.converters["s.r"](np.array([2**40])).tolist() == [float(2**40)]


def test_stop_request_ends_the_run_with_status_stopped():
    class Samples(Observer):
        def __init__(self):
            self.t = []

        def start(self, sim, schedule):
            self.t.append(sim.t)

        def step(self, sim, t):
            self.t.append(t)

    obs = Samples()
    sys_ = _system(stop_at=0.0035)
    sim = Simulation(sys_, order=["c", "s"], observers=[obs])
    report = sim.run(Timeline([Interval("TM", 0.005, 1e-3), Interval("TM", 0.005, 1e-3)]))
    assert report.status == "stopped" and report.stopped["component"] == "c"
    assert report.stopped["t_s"] == pytest.approx(0.003) and report.t_end == pytest.approx(0.003)
    assert obs.t == pytest.approx([0.0, 0.001, 0.002, 0.003, 0.003])
    assert len(report.timeline) == 1 and report.timeline[0].reason == "stopped"
    # the sink, after the counter in the order, is not stepped past the stop (it stays at 0.003)
    assert len(sys_.components["s"].log) == 3


def test_thermal_only_hold_averages_reals_and_holds_the_rest():
    """Across a thermal-only interval the frozen counter's Real output is replaced by its mean over the last 5
    rotor cycles (1 ms each), its Integer and Boolean outputs by their last values (not a mean of integers)."""
    class ThermalSink(Sink):
        phases = frozenset({"TM", "TO"})

    comps = {"c": Counter("c"), "s": ThermalSink("s")}
    sys_ = System(comps, [Connection("c.k", "s.k"), Connection("c.r", "s.r"), Connection("c.b", "s.b")])
    sim = Simulation(sys_, order=["c", "s"], hold="mean", hold_cycles=5, cycle=1e-3)
    sim.run(Timeline([Interval("TM", 0.006, 1e-3), Interval("TO", 0.01, 5e-3)]))
    to = sys_.components["s"].log[6:]
    assert len(to) == 2
    for x in to:
        assert x["k"].tolist() == [6] and x["k"].dtype == np.int64
        assert x["b"].tolist() == [True]
        assert x["r"].tolist() == [4000.0]          # mean of 2..6 m, in mm
