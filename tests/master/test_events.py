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


def test_a_tolerance_finer_than_a_float64_step_resolves_is_named():
    """Bisection toward 1e-300 s never ended (the bracket stops shrinking at the step's last bits): refused,
    naming the bound, and the finest tolerance allowed still locates the zero."""
    with pytest.raises(ContractError, match=r"w\.event_tolerance: 1e-300 s is below 3\.55e-18 s, the step 0\.001 s "
                                            r"bisected 48 times"):
        _sim(tolerance=1e-300).run(Timeline([Interval("TM", duration=0.01, step=1e-3)]))
    report = _sim(tolerance=1e-3 * 2.0 ** -48).run(Timeline([Interval("TM", duration=0.3, step=1e-3)]))
    assert len(report.events) == 1 and 0.0 <= report.events[0]["t_s"] - math.pi / (2 * W) <= 1e-12


def test_a_live_indicator_of_a_slow_component_is_refused():
    sim = _sim()
    sim.steps = {"w": 2e-3}
    with pytest.raises(ContractError, match="w: a component whose event the master locates must step at the "
                                            "interval's step"):
        sim.run(Timeline([Interval("TM", duration=0.01, step=1e-3)]))


class Switch(ZeroWatch):
    """A power P0 switched on and off at each zero of its input (an event indicator), as a fast producer."""

    variables = ZeroWatch.variables + (Variable("P0", "parameter", unit="W", start=0.0),
                                       Variable("P", "output", unit="W"))

    def setup(self, t0=0.0):
        super().setup(t0)
        self.y["P"] = np.array([self.p["P0"]])

    def do_step(self, t, h):
        super().do_step(t, h)
        self.y["P"] = self.p["P0"] * (1.0 - self.state["n"] % 2.0)

    def update_discrete(self, t, which):
        out = super().update_discrete(t, which)
        self.y["P"] = self.p["P0"] * (1.0 - self.state["n"] % 2.0)
        return out


class Meter(Component):
    """A slow consumer: the energy of its input power, E += P h, P the mean over its step the master delivers."""

    variables = (Variable("P", "input", unit="W"), Variable("E", "output", unit="J"))

    def setup(self, t0=0.0):
        super().setup(t0)
        self.state = {"E": np.zeros(1)}
        self.ends = []

    def do_step(self, t, h):
        self.time = t + h
        self.state["E"] = self.state["E"] + self.u["P"] * h
        self.y["E"] = self.state["E"].copy()
        self.ends.append(t + h)


@pytest.mark.parametrize("mult", [3, 4])
def test_events_located_in_a_multirate_interval(mult):
    """A multi-rate interval with a live indicator: the fast components (the oscillator and a switch on its zeros,
    1 ms) are re-stepped within the base step, a slow consumer (3 or 4 ms; at 3 ms the first zero's base step,
    0.248-0.249 s, ends one of its windows) steps on its own grid, once per window, and the mean power it is handed
    delivers exactly the switch's energy: 1 kW on until the first zero, off to the second, on again, so the meter
    holds P0 (t1 + T - t2) to round-off with the located times, and within 2 P0 x tolerance of the exact zeros
    (pi / 2w, 3 pi / 2w). The oscillator ends where it ends without the switch."""
    T, p0 = 0.996, 1000.0
    comps = {"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1}),
             "w": Switch("w", {"event_tolerance": 1e-7, "P0": p0}), "meter": Meter("meter")}
    sim = Simulation(System(comps, [Connection("m1.x", "w.x"), Connection("w.P", "meter.P")],
                            inputs={"m1.F": np.zeros(1)}), order=list(comps))
    sim.steps = {"meter": mult * 1e-3}
    report = sim.run(Timeline([Interval("TM", duration=T, step=1e-3)]))
    t1, t2 = (e["t_s"] for e in report.events)
    exact = [math.pi / (2 * W), 3 * math.pi / (2 * W)]
    assert 0.0 <= t1 - exact[0] <= 1e-7 and 0.0 <= t2 - exact[1] <= 1e-7
    energy = float(sim.value("meter.E")[0])
    assert energy == pytest.approx(p0 * (t1 + T - t2), rel=1e-12)
    assert abs(energy - p0 * (exact[0] + T - exact[1])) <= 2 * p0 * 1e-7
    # (the ends it saw include the trial steps the event location rolled back: their distinct times)
    ends = sorted(set(comps["meter"].ends))
    assert report.component_steps["meter"] == round(T / (mult * 1e-3)) == len(ends)
    assert ends == pytest.approx([(j + 1) * mult * 1e-3 for j in range(len(ends))], abs=1e-12)
    plain = _sim(watch=False)
    plain.run(Timeline([Interval("TM", duration=T, step=1e-3)]))
    assert float(sim.value("m1.x")[0]) == pytest.approx(float(plain.value("m1.x")[0]), abs=1e-12)


def test_an_event_in_a_held_interval_ends_it_and_a_coupled_one_follows():
    """A component with an event indicator that steps in a held interval: the zero of x0 cos(w t) at pi / (2 w)
    (0.2484 s) falls in the held interval 0.1-0.4 s; the held interval ends there (located within the tolerance
    after the exact zero), the rest of it runs coupled, then the timeline goes on; the held interval is not charged
    to the hold's error estimate (the mechanics after the event are not what the held values stood for)."""
    sim = _sim(cycle=0.01)
    sim.system.components["w"].phases = frozenset({"TM", "TO"})
    sim.system.components["m1"].phases = frozenset({"TM", "TO"})
    report = sim.run(Timeline([Interval("TM", duration=0.1, step=1e-3), Interval("TO", duration=0.3, step=1e-3),
                               Interval("TM", duration=0.1, step=1e-3)]))
    exact = math.pi / (2 * W)
    (ev,) = report.events
    assert 0.0 <= ev["t_s"] - exact <= 1e-7 + 1e-12
    phases = [(iv.phase, iv.reason) for iv in report.timeline]
    assert phases == [("TM", ""), ("TO", "event"), ("TM", "after an event"), ("TM", "")]
    assert report.timeline[1].t_end == ev["t_s"] and report.timeline[2].t_start == ev["t_s"]
    assert report.timeline[2].t_end == pytest.approx(0.4, abs=1e-12)
    assert report.t_end == pytest.approx(0.5, abs=1e-12)
    (held,) = [iv for iv in report.hold.intervals if iv["t_start"] == pytest.approx(0.1)]
    assert held["estimate_pct"] is None and held["event"].startswith("w at")


class Cut(Component):
    """Schedules one change of its own at ``t_cut`` (as the spool's fuel cut) and keeps the ends of its steps."""

    variables = (Variable("t_cut", "parameter", unit="s", start=0.0123, event="the cut"),
                 Variable("x", "input", unit="m"), Variable("ends", "output", unit="1"))

    def setup(self, t0=0.0):
        super().setup(t0)
        self.ends = []

    def do_step(self, t, h):
        self.time = t + h
        self.ends.append(t + h)

    def next_event(self, t):
        return self.p["t_cut"] if self.p["t_cut"] >= t - 1e-9 else None


def test_a_time_event_splits_its_base_step_and_is_recorded():
    """A scheduled change inside a base step (0.0123 s in the step 0.012-0.013 s) is a time event: every component
    steps to it and on from it (the grid of the other steps kept), ``update_discrete(t, [])`` records it (kind
    "time", the parameter's event named) once; one on the grid is recorded without a split."""
    for t_cut, split in ((0.0123, True), (0.012, False)):
        comps = {"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1}),
                 "c": Cut("c", {"t_cut": t_cut})}
        sim = Simulation(System(comps, [Connection("m1.x", "c.x")], inputs={"m1.F": np.zeros(1)}), order=list(comps))
        report = sim.run(Timeline([Interval("TM", duration=0.02, step=1e-3)]))
        (ev,) = report.events
        assert (ev["t_s"], ev["kind"], ev["trigger"], ev["values"]) == (t_cut, "time", "time", {"event": "the cut"})
        ends = comps["c"].ends
        assert (t_cut in ends) and len(ends) == 20 + split
        assert ends[-1] == pytest.approx(0.02, abs=1e-15) and report.component_steps["c"] == 20 + split


class PowerStep(Component):
    """A film power P0 until ``t_off`` (a time event: ``update_discrete`` switches it off, as a damper's oil-supply
    loss does to its film power)."""

    variables = (Variable("t_off", "parameter", unit="s", start=0.0, event="the power off"),
                 Variable("P0", "parameter", unit="W", start=0.0), Variable("P", "output", unit="W"))

    def setup(self, t0=0.0):
        super().setup(t0)
        self.state = {"on": np.ones(1)}
        self.y["P"] = np.array([self.p["P0"]])

    def do_step(self, t, h):
        self.time = t + h
        self.y["P"] = self.p["P0"] * self.state["on"]

    def next_event(self, t):
        return self.p["t_off"] if self.state.get("on", [1.0])[0] and self.p["t_off"] >= t - 1e-9 else None

    def update_discrete(self, t, which):
        self.state["on"] = np.zeros(1)
        self.y["P"] = np.zeros(1)
        return {"kind": "power_off", "values": {}}


def test_a_power_step_at_a_time_event_reaches_the_thermal_network_exactly():
    """A film power of 900 W into bearing #0's thermal network (its P_sfd), switched off at 0.0123 s inside the
    network's 1 ms step: the master splits that step at the event, so the network's node temperatures follow its
    analytic step response, the solution of C dT/dt = -K T + b + S u with u = (0, 900 W, 0) up to 0.0123 s and 0
    after (scipy's expm of the network's matrices, apart from the component's stepping), within 1e-9 K at every
    step to 0.05 s; the film-oil node heats by 0.61 K and turns back at the event."""
    from scipy.linalg import expm

    t_off, p0, h = 0.0123, 900.0, 1e-3
    comps = {"src": PowerStep("src", {"t_off": t_off, "P0": p0}),
             "th": create("thermal.network", "th", {"bearing": 0})}
    inputs = {"th.P_drag": np.zeros(1), "th.P_rub": np.zeros(1)}
    sim = Simulation(System(comps, [Connection("src.P", "th.P_sfd")], inputs=inputs), order=["src", "th"])
    rows = []

    class Watch:
        stride = 1

        def __getattr__(self, name):
            return lambda *a, **k: None

        def block_signals(self, sim):
            return None

        def step(self, sim, t):
            rows.append((t, comps["th"].state["T"].copy()))

    sim.observers.append(Watch())
    report = sim.run(Timeline([Interval("TM", duration=0.05, step=h)]))
    assert [e["t_s"] for e in report.events] == [t_off]
    net = comps["th"].network
    A = -net.K / net.C[:, None]

    def response(T0, u, tau):
        ss = net.steady(u)
        return ss + expm(A * tau) @ (T0 - ss)

    T_init = np.full(net.n, comps["th"].p["T_initial"])
    on, off = np.array([0.0, p0, 0.0]), np.zeros(3)
    T_event = response(T_init, on, t_off)
    sfd = []
    for t, T in rows:
        exact = response(T_init, on, t) if t <= t_off else response(T_event, off, t - t_off)
        assert np.max(np.abs(T - exact)) < 1e-9, t
        sfd.append(T[7])
    rise = np.array(sfd) - T_init[7]
    assert 0.5 < rise.max() < 0.7 and rise[-1] < rise.max()


def test_the_base_step_of_an_event_is_one_sample_of_the_hand_off_window():
    """The hold's hand-off window (the switch's power into a component stepped in the held phase, cycles of 10
    samples at 1 ms) over a coupled interval of 0.3 s with an event at 0.2484 s: the event's base step is sampled once
    (its first, rolled back step's sample is replaced by the completed step's, at the same time): 30 whole cycles,
    none begun; the cycle holding the event has the power on at 8 of its 10 step ends (0.241-0.248 s), mean 800 W."""
    comps = {"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1}),
             "w": Switch("w", {"event_tolerance": 1e-7, "P0": 1000.0}), "meter": Meter("meter")}
    comps["meter"].phases = frozenset({"TM", "TO"})
    sim = Simulation(System(comps, [Connection("m1.x", "w.x"), Connection("w.P", "meter.P")],
                            inputs={"m1.F": np.zeros(1)}), order=list(comps), cycle=0.01)
    report = sim.run(Timeline([Interval("TM", duration=0.3, step=1e-3)]))
    assert [round(e["t_s"], 4) for e in report.events] == [0.2484]
    (ho,) = sim.hold.handoffs
    assert (len(ho.cycles), ho.w.cn) == (30, 0)
    assert [mean for _, mean in ho.cycles[23:26]] == [1000.0, 800.0, 0.0]
