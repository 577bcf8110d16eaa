"""The cycle a run counts in (master/core/cycle.py, master/scenario/cycle.py): a constant period, or the period of
a speed signal read at the start of each thermo-mechanical interval.

The toy: a spinner (components/testing/spinner.py) whose power fluctuates once a turn, P0 (1 + a cos theta), at
50 Hz in the first TM interval and 25 Hz from the second on, feeding a thermal node. Its held power over a
thermal-only interval is the mean over the last ``hold_cycles`` cycles: exactly P0 over whole turns, off by a
share of ``a`` over a window that is not.
"""
from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from rotorcosim.components import registry
from rotorcosim.components.testing.spinner import Spinner
from rotorcosim.master.core.cycle import ConstantCycle, CycleError, SignalCycle
from rotorcosim.master.core.system import Connection, System
from rotorcosim.master.scenario.build import build_simulation, load_scenario, parse, schedule_of
from rotorcosim.master.scenario.cycle import cycle_of
from rotorcosim.master.simulation import Simulation

P0, A = 100.0, 0.5
W50, W25 = 2 * math.pi * 50.0, 2 * math.pi * 25.0
H = 1e-3      # TM step: 20 steps a turn at 50 Hz, 40 at 25 Hz


def _toy(t_switch=0.2):
    spin = Spinner("spin", {"Omega0": W50, "Omega1": W25, "t_switch": t_switch, "P0": P0, "a": A})
    node = registry.create("testing.thermal_node", "node")
    return System({"spin": spin, "node": node}, [Connection("spin.P", "node.P")])


def _held_after(sim, tm: float) -> float:
    """The power the node receives in the thermal-only interval after a TM interval of ``tm`` seconds."""
    sim.run_interval("TM", tm, H)
    sim.run_interval("TO", 0.5, 0.05)
    return float(sim.system.components["node"].u["P"][0])


def test_a_signal_cycle_follows_the_speed_from_one_interval_to_the_next():
    sim = Simulation(_toy(), order=["spin", "node"], hold="mean", hold_cycles=3,
                     cycle=SignalCycle("spin.Omega"))
    assert _held_after(sim, 0.2) == pytest.approx(P0, rel=1e-12)       # 3 turns at 50 Hz: 60 samples
    assert sim.hold.period == pytest.approx(0.02, rel=1e-12)
    assert sim.hold.handoffs[0].n_cycle == 20
    # the spinner turns at 25 Hz from the second interval on: 3 turns are 120 samples
    assert _held_after(sim, 0.15) == pytest.approx(P0, rel=1e-12)
    assert sim.hold.period == pytest.approx(0.04, rel=1e-12)
    assert sim.hold.handoffs[0].n_cycle == 40


def test_a_constant_cycle_misses_a_changed_speed():
    """The same run with the first speed's period as a constant: the second window holds 1.5 turns at 25 Hz, and
    its mean is off by 2 a / (3 pi) of P0 (the window starts where cos theta is at an extreme)."""
    sim = Simulation(_toy(), order=["spin", "node"], hold="mean", hold_cycles=3, cycle=0.02)
    assert _held_after(sim, 0.2) == pytest.approx(P0, rel=1e-12)
    held = _held_after(sim, 0.15)
    assert abs(held - P0) == pytest.approx(P0 * 2 * A / (3 * math.pi), rel=0.05)


def test_a_signal_in_another_unit_and_a_frequency():
    """rev/min and Hz ports give the same period as rad/s (the port's own unit is used)."""
    class Rpm(Spinner):
        variables = tuple(v if v.name != "Omega" else type(v)("Omega", "output", unit="rev/min")
                          for v in Spinner.variables)

        def _outputs(self):
            super()._outputs()
            self.y["Omega"] = self.y["Omega"] * 30.0 / math.pi

    class Hz(Spinner):
        variables = tuple(v if v.name != "Omega" else type(v)("Omega", "output", unit="Hz")
                          for v in Spinner.variables)

        def _outputs(self):
            super()._outputs()
            self.y["Omega"] = self.y["Omega"] / (2 * math.pi)

    for cls in (Rpm, Hz):
        s = System({"spin": cls("spin", {"Omega0": W50})}, [])
        s.components["spin"].setup()
        assert SignalCycle("spin.Omega").period(s) == pytest.approx(0.02, rel=1e-12)


def test_a_signal_that_cannot_give_a_period_is_refused():
    s = _toy()
    with pytest.raises(CycleError, match=r"spin.theta is in \[rad\]: an angular speed"):
        SignalCycle("spin.theta").check(s)
    with pytest.raises(ValueError, match="has no output 'speed'"):
        SignalCycle("spin.speed").check(s)
    still = System({"spin": Spinner("spin", {"Omega0": 0.0})}, [])
    still.components["spin"].setup()
    with pytest.raises(CycleError, match="spin.Omega is 0 .* no cycle period"):
        SignalCycle("spin.Omega").period(still)
    with pytest.raises(CycleError, match="positive"):
        ConstantCycle(-1.0)

TOY = textwrap.dedent("""
    [scenario]
    name = "spinner"

    [components.spin]
    implementation = "rotorcosim.components.testing.spinner:Spinner"
    parameters = {{ Omega0 = {w50!r}, Omega1 = {w25!r}, t_switch = 0.2, P0 = 100.0, a = 0.5 }}

    [components.node]
    implementation = "testing.thermal_node"

    [[connections]]
    from = "spin.P"
    to = "node.P"

    [schedule]
    kind = "timeline"
    step = 1e-3
    thermal_step = 0.05
    hold_cycles = 3
    {cycle}
    intervals = [{{ phase = "TM", duration = 0.2 }}, {{ phase = "TO", duration = 0.5 }},
                 {{ phase = "TM", duration = 0.15 }}, {{ phase = "TO", duration = 0.5 }}]
    """)


def _scenario(tmp_path, cycle: str):
    f = tmp_path / "spinner.toml"
    f.write_text(TOY.format(w50=W50, w25=W25, cycle=cycle))
    return load_scenario(f)


def test_a_scenario_declares_its_cycle_signal(tmp_path):
    sc = _scenario(tmp_path, 'cycle = { signal = "spin.Omega" }')
    sim = build_simulation(sc)
    assert isinstance(sim.cycle_source, SignalCycle)
    sim.run(schedule_of(sc))
    assert sim.hold.period == pytest.approx(0.04, rel=1e-12)
    assert float(sim.system.components["node"].u["P"][0]) == pytest.approx(P0, rel=1e-12)


def test_speed_rpm_is_a_constant_period_of_60_over_it(tmp_path):
    """The scenario's edge spelling: the period is 60.0 / speed_rpm, bit for bit (results stay the same)."""
    cycle = cycle_of({"speed_rpm": 16000.0})
    assert cycle.constant == 60.0 / 16000.0
    sc = _scenario(tmp_path, "speed_rpm = 3000.0")
    assert build_simulation(sc).cycle_source.constant == 60.0 / 3000.0
    sc = _scenario(tmp_path, "cycle = { period = 0.02 }")
    assert build_simulation(sc).cycle_source.constant == 0.02


@pytest.mark.parametrize("cycle, message", [
    ('cycle = { signal = "spin.Omega" }\n    speed_rpm = 3000.0',
     r"\[schedule\] cycle: give speed_rpm or cycle, not both"),
    ('cycle = { period = 0.02, signal = "spin.Omega" }', r"\[schedule.cycle\]: give exactly one of period"),
    ('cycle = { signal = "spun.Omega" }', r"\[schedule.cycle\] signal: .*spun"),
    ('cycle = { period = 0.02, unit = "s" }', r"\[schedule.cycle\] unit: is the unit of a signal"),
    ('cycle = { period = 1e-4 }', r"\[schedule.cycle\] period: 0.0001 s is less than two thermo-mechanical steps"),
    ('cycle = { signal = "spin.theta" }', r"\[schedule\] cycle: cycle signal spin.theta is in \[rad\]"),
])
def test_a_bad_cycle_is_a_clear_error(tmp_path, cycle, message):
    with pytest.raises(ValueError, match=message):   # SchemaError (the file) or ScenarioError (the system)
        build_simulation(_scenario(tmp_path, cycle))


def test_intervals_in_cycles_need_a_constant_period(tmp_path):
    sc = _scenario(tmp_path, 'cycle = { period = 0.02 }')
    sc.schedule["intervals"] = [{"phase": "TM", "cycles": 10}]
    assert schedule_of(sc).duration == pytest.approx(0.2, rel=1e-12)
    sc.schedule["cycle"] = {"signal": "spin.Omega"}
    with pytest.raises(ValueError, match="an interval in cycles needs a cycle of constant period"):
        schedule_of(sc)
    data = {"components": {"spin": {"implementation": "rotorcosim.components.testing.spinner:Spinner"}},
            "schedule": {"cycle": {"signal": "spin.Omega"}, "intervals": [{"phase": "TM", "cycles": 10}]}}
    with pytest.raises(ValueError, match="an interval in rotor cycles needs schedule.speed_rpm"):
        parse(data)


def test_the_steady_windows_follow_the_signal(tmp_path):
    from rotorcosim.master.observer.observers import SteadyWindows

    sc = _scenario(tmp_path, 'cycle = { signal = "spin.Omega" }')
    obs = SteadyWindows(["spin.P"], cycle_of(sc.schedule), cycles=2)
    sim = build_simulation(sc, [obs])
    sim.run(schedule_of(sc))
    first, second = obs.windows
    assert np.mean(first["spin.P"][1:]) == pytest.approx(P0, rel=1e-12)     # 2 turns at 50 Hz: 40 samples
    assert len(first["t"]) == 41 and len(second["t"]) == 81                 # 2 turns at 25 Hz: 80 samples
    assert np.mean(second["spin.P"][1:]) == pytest.approx(P0, rel=1e-12)
