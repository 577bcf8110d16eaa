"""Multi-rate energy conservation and the staggered schedule, on the toy thermo-mechanical pair
(components/testing/thermo_toy.py)."""
import numpy as np
import pytest

from rotorcosim.components.registry import create
from rotorcosim.master.schedule import Interval, Timeline, AutoSchedule
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System

CYCLE = 1.0 / 45.0  # the cycle of the holds [s]: one forcing period of the oscillator


def toy(average="mean", thermal=None):
    comps = {"osc": create("testing.damped_oscillator", "osc"),
             "node": create("testing.thermal_node", "node", thermal or {})}
    cons = [Connection("osc.P", "node.P", average=average), Connection("node.T", "osc.T")]
    return System(comps, cons)


def test_multirate_energy_balance():
    """Oscillator at 1 ms, thermal node at 50 ms: the heat the node receives equals the energy the oscillator
    dissipated within 0.1 % (the fast-to-slow mean keeps the energy of a power signal)."""
    s = toy()
    sim = Simulation(s, order=["osc", "node"], steps={"osc": 1e-3, "node": 5e-2})
    sim.run(Timeline([Interval("TM", 2.0, 1e-3)]))
    e_mech = s.components["osc"].y["E"][0]
    e_heat = s.components["node"].y["E_in"][0]
    assert sim.engine.steps_taken == {"osc": 2000, "node": 40}
    assert e_mech > 10.0
    assert abs(e_heat - e_mech) / e_mech < 1e-3


def test_multirate_rms_overestimates_energy():
    """The RMS of a fluctuating power is larger than its mean: with average = "rms" the node gets more heat
    than was dissipated (why the mean is the default across rates)."""
    s = toy("rms")
    sim = Simulation(s, order=["osc", "node"], steps={"osc": 1e-3, "node": 5e-2})
    sim.run(Timeline([Interval("TM", 1.0, 1e-3)]))
    assert s.components["node"].y["E_in"][0] > 1.01 * s.components["osc"].y["E"][0]


def test_hold_linear_extrapolation_slow_to_fast():
    """A slow ramp seen by a fast consumer: linear extrapolation reproduces the ramp at mid-step exactly."""
    from rotorcosim.master.core.algorithm import _Link

    s = toy()
    link = _Link(Connection("node.T", "osc.T", extrapolation="linear"), s.components["node"], s.components["osc"])
    link.mode = _Link.SLOW_TO_FAST
    node = s.components["node"]
    node.y["T"] = np.array([300.0])
    link.produced(0.05, 0.05)
    node.y["T"] = np.array([301.0])
    link.produced(0.05, 0.10)
    assert link.value(0.1005)[0] == pytest.approx(301.0 + 0.0005 / 0.05)


THERMAL = {"C": 10.0, "R": 1.0}  # thermal time constant 10 s >> 22 ms forcing period and ~50 ms settling


def toy_timeline(duration, tm, to, step=1e-3, thermal_step=0.05):
    """TM intervals of ``tm`` s alternating with TO intervals of ``to`` s, ending with a TM interval."""
    sch, t = [], 0.0
    while t < duration - 1e-9:
        sch.append(Interval("TM", min(tm, duration - t), step))
        t += sch[-1].duration
        if t < duration - 1e-9:
            sch.append(Interval("TO", min(to, duration - t), thermal_step))
            t += sch[-1].duration
    return Timeline(sch)


def staggered_vs_monolithic(duration=30.0, tm=0.3, to=4.7):
    mono = toy(thermal=THERMAL)
    rep_m = Simulation(mono, order=["osc", "node"], cycle=CYCLE).run(Timeline([Interval("TM", duration, 1e-3)]))
    stag = toy(thermal=THERMAL)
    sim = Simulation(stag, order=["osc", "node"], cycle=CYCLE, hold="mean", hold_cycles=5)
    rep_s = sim.run(toy_timeline(duration, tm, to))
    return mono, stag, rep_m, rep_s


def test_staggered_matches_monolithic_final_temperature():
    """Toy thermo-mechanical system (damping falls with temperature): staggered (0.3 s TM / 4.7 s TO) and
    monolithic runs over three thermal time constants end within 1 % of each other in temperature rise
    (measured 0.6 %)."""
    mono, stag, rep_m, rep = staggered_vs_monolithic()
    T_m = mono.components["node"].y["T"][0] - 303.15
    T_s = stag.components["node"].y["T"][0] - 303.15
    assert T_m > 20.0
    assert abs(T_s - T_m) / T_m < 0.01
    phases = [u.phase for u in rep.timeline]
    assert phases[:4] == ["TM", "TO", "TM", "TO"]
    assert abs(rep.timeline[-1].t_end - 30.0) < 1e-9


def test_frozen_component_keeps_its_state():
    """In a thermal-only interval the mechanical component is not stepped; its state resumes unchanged."""
    s = toy()
    sim = Simulation(s, order=["osc", "node"], cycle=CYCLE)
    sim.run_interval("TM", 0.1, 1e-3)
    z = s.components["osc"].state["z"].copy()
    n = sim.engine.steps_taken["osc"]
    sim.run_interval("TO", 1.0, 0.1)
    assert sim.engine.steps_taken["osc"] == n
    np.testing.assert_array_equal(s.components["osc"].state["z"], z)
    assert sim.engine.steps_taken["node"] == 100 + 10


def test_auto_schedule_switches_and_reports():
    s = toy(thermal=THERMAL)
    sim = Simulation(s, order=["osc", "node"], cycle=CYCLE)
    sch = AutoSchedule(duration=6.0, step=1e-3, thermal_step=0.05, steady_tolerance=0.02, tm_min=0.1,
                       tm_max=0.5, to_min=0.2, to_max=2.0, drift_tolerance=0.005)
    rep = sim.run(sch)
    phases = [u.phase for u in rep.timeline]
    assert "TO" in phases and phases[0] == "TM" and phases[-1] == "TM"
    assert abs(rep.timeline[-1].t_end - 6.0) < 1e-6
    assert any(u.reason == "steady" for u in rep.timeline if u.phase == "TM")
    # contiguous timeline
    for a, b in zip(rep.timeline, rep.timeline[1:]):
        assert abs(a.t_end - b.t_start) < 1e-12


def test_thermal_only_interval_keeps_its_duration():
    """A thermal-only interval whose duration is not a whole number of thermal steps (23.85 s at 0.1 s) ends at
    exactly its duration, with the nearest smaller step (239 steps of 0.0998 s), and the report says so."""
    s = toy()
    sim = Simulation(s, order=["osc", "node"], cycle=CYCLE)
    sim.run_interval("TM", 0.1, 1e-3)
    used = sim.run_interval("TO", 23.85, 0.1)
    assert used.steps == 239
    assert used.t_end == pytest.approx(0.1 + 23.85, abs=1e-9)
    assert used.step == pytest.approx(23.85 / 239, rel=1e-12) and used.step <= 0.1


def test_linear_end_extrapolation_is_exact_for_a_ramp():
    """extrapolation = "linear-end" on a same-rate link: the consumer sees the producer's value extrapolated to the
    end of its own step, exact for a ramp y = 3 t (hold gives the value at the step start: late by one step)."""
    from rotorcosim.components.contract import Component, Variable

    class Ramp(Component):
        variables = (Variable("y", "output"),)

        def do_step(self, t, h):
            self.y["y"] = np.array([3.0 * (t + h)])

    class Probe(Component):
        variables = (Variable("u", "input"),)

        def setup(self, t0=0.0):
            super().setup(t0)
            self.seen = []

        def do_step(self, t, h):
            self.seen.append((t + h, float(self.u["u"][0])))

    for how, lag in (("linear-end", 0.0), ("hold", 1e-3)):
        s = System({"ramp": Ramp("ramp"), "probe": Probe("probe")},
                   [Connection("ramp.y", "probe.u", extrapolation=how)])
        Simulation(s, order=["probe", "ramp"]).run(Timeline([Interval("TM", 0.01, 1e-3)]))
        seen = s.components["probe"].seen[2:]  # from the third step on, two past values exist
        assert len(seen) == 8
        assert all(abs(u - 3.0 * (t_end - lag)) < 1e-12 for t_end, u in seen), (how, seen)


@pytest.mark.parametrize("restart_cycles", [2.0, 0.0])
def test_restart_ramps_the_thermal_inputs_of_the_frozen_mechanics(restart_cycles):
    """At a TM restart (master/manipulator/restart.py) the oscillator's temperature input goes from its value before the
    TO interval to the node's present one along a half cosine over restart_cycles forcing periods; with 0 it
    jumps (the paper)."""
    s = toy(thermal=THERMAL)
    sim = Simulation(s, order=["osc", "node"], cycle=CYCLE, restart_cycles=restart_cycles)
    osc, node = s.components["osc"], s.components["node"]
    sim.run_interval("TM", 0.3, 1e-3)
    before = float(osc.u["T"][0])
    sim.run_interval("TO", 4.7, 0.05)
    jump = float(node.y["T"][0]) - before
    assert jump > 5.0   # the node warmed while the oscillator was frozen
    sim.run_interval("TM", 1e-3, 1e-3)   # the first step after the restart
    seen = float(osc.u["T"][0]) - before
    if restart_cycles:
        # 1 ms into a 44 ms ramp: (1 - cos(pi/44.4)) / 2 = 0.13 % of the jump (+- the node's own change in a step)
        w = 0.5 * (1.0 - np.cos(np.pi * 1e-3 / CYCLE / 2.0))
        assert abs(seen - w * jump) < 2e-4 * jump
        sim.run_interval("TM", 0.021, 1e-3)   # mid-ramp (22 ms of 44.4 ms): about half the jump
        assert 0.4 * jump < float(osc.u["T"][0]) - before < 0.6 * jump
        sim.run_interval("TM", 0.03, 1e-3)    # past the ramp: the live value
        assert float(osc.u["T"][0]) == float(node.y["T"][0]) or abs(float(osc.u["T"][0] - node.y["T"][0])) < 0.05
    else:
        assert seen == pytest.approx(jump, rel=0.01)
