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
    assert sim.hold.handoffs[0].w.n_cycle == 20
    # the spinner turns at 25 Hz from the second interval on: 3 turns are 120 samples
    assert _held_after(sim, 0.15) == pytest.approx(P0, rel=1e-12)
    assert sim.hold.period == pytest.approx(0.04, rel=1e-12)
    assert sim.hold.handoffs[0].w.n_cycle == 40


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
    from rotorcosim.master.observer.steady_windows import SteadyWindows

    sc = _scenario(tmp_path, 'cycle = { signal = "spin.Omega" }')
    obs = SteadyWindows(["spin.P"], cycle_of(sc.schedule), cycles=2)
    sim = build_simulation(sc, [obs])
    sim.run(schedule_of(sc))
    first, second = obs.windows
    assert np.mean(first["spin.P"][1:]) == pytest.approx(P0, rel=1e-12)     # 2 turns at 50 Hz: 40 samples
    assert len(first["t"]) == 41 and len(second["t"]) == 81                 # 2 turns at 25 Hz: 80 samples
    assert np.mean(second["spin.P"][1:]) == pytest.approx(P0, rel=1e-12)


# -- windows counted in turns of the cycle's angle ----------------------------------------------------------------
W0, ALPHA = 2 * math.pi * 50.0, 2 * math.pi * 60.0     # 50 Hz at t = 0, falling 60 Hz per second
HR = 1e-4                                              # 200 steps a turn at 50 Hz, 500 at 20 Hz


class FallingSpinner(Spinner):
    """The spinner with a prescribed falling speed Omega(t) = W0 - ALPHA t: its angle is the exact integral,
    theta(t) = W0 t - ALPHA t^2 / 2 (each step adds (Omega(t) - ALPHA h / 2) h)."""

    def _speed(self, t_own):
        return self.p["Omega0"] - ALPHA * t_own

    def do_step(self, t, h):
        self.state["theta"] += (self._speed(self.state["t_own"]) - 0.5 * ALPHA * h) * h
        self.state["t_own"] += h
        self.time = t + h
        self._outputs()


def _theta(t):
    return W0 * t - 0.5 * ALPHA * t * t


def _analytic_began(turns, t_end):
    """The time the last ``turns`` turns before t_end began: theta(t) = theta(t_end) - 2 pi turns, solved."""
    target = _theta(t_end) - 2 * math.pi * turns
    return (W0 - math.sqrt(W0 * W0 - 2.0 * ALPHA * target)) / ALPHA


def _falling(cycle, turns=3.0):
    spin = FallingSpinner("spin", {"Omega0": W0, "P0": P0, "a": A})
    node = registry.create("testing.thermal_node", "node")
    system = System({"spin": spin, "node": node}, [Connection("spin.P", "node.P")])
    from rotorcosim.master.observer.steady_windows import SteadyWindows
    obs = SteadyWindows(["spin.P", "spin.theta"], cycle, cycles=turns)
    return Simulation(system, order=["spin", "node"], hold="mean", hold_cycles=turns, cycle=cycle,
                      observers=[obs]), obs


def test_a_window_counted_in_turns_spans_them_while_the_speed_falls():
    """TM 0.5 s while the speed falls from 50 to 20 Hz, then TO: the hand-off window and the steady window span 3
    turns of the angle at the interval's end (an analytic integral of the speed), where a window of 3 periods
    read at the interval's start (0.06 s) spans 1.3 turns."""
    sim, obs = _falling(SignalCycle("spin.Omega", angle="spin.theta"))
    sim.run_interval("TM", 0.5, HR)
    t_end = sim.t
    counter = sim.revolutions
    # within the error of a linear interpolation of theta between samples: ALPHA h^2 / 8 in angle, over Omega
    interp = ALPHA * HR ** 2 / 8 / (2 * math.pi * 20)
    assert counter.began(3.0) == pytest.approx(_analytic_began(3.0, t_end), abs=interp)
    ho = sim.hold.handoffs[0]
    k = ho.window_samples()
    # the samples of the steps since the turns began: the first one's step contains that time
    t0 = _analytic_began(3.0, t_end)
    assert t_end - k * HR <= t0 < t_end - (k - 1) * HR
    assert ho.window_revolutions() == pytest.approx((_theta(t_end) - _theta(t_end - k * HR)) / (2 * math.pi),
                                                    rel=1e-9)
    assert 3.0 <= ho.window_revolutions() < 3.0 + W0 * HR / (2 * math.pi)
    # the held power is the window's mean, exactly: the samples' P0 (1 + a cos theta) at the analytic angles
    ts = t_end - HR * np.arange(k)[::-1]
    expected = np.mean(P0 * (1.0 + A * np.cos(_theta(ts))))
    sim.run_interval("TO", 0.5, 0.05)
    assert float(sim.system.components["node"].u["P"][0]) == pytest.approx(expected, rel=1e-9)
    assert expected == pytest.approx(P0, rel=0.01)     # whole turns: the fluctuation averages out (nearly)
    rep = sim.report.hold.as_dict()["window_revolutions"]
    assert rep["asked"] == 3.0 and rep["per_interval"] == [pytest.approx(ho_revs := rep["smallest"])]
    assert 3.0 <= ho_revs < 3.02
    # the elasticity fit's cycle means end at each whole turn from the interval's start
    cycles = ho.history[-1]
    assert len(cycles) == int(_theta(t_end) // (2 * math.pi))
    # the steady window (Table 4's): the same turns, and the sample at or before their start
    win = obs.windows[-1]
    assert win["t"][0] <= t0 < win["t"][1] and win["t"][-1] == pytest.approx(t_end)
    assert win["revolutions"] == pytest.approx((_theta(win["t"][-1]) - _theta(win["t"][0])) / (2 * math.pi))


def test_without_the_angle_the_window_is_sized_by_the_starting_period():
    """The same run with the speed's period alone (read at the interval's start): the window is 3 x 20 ms, 600
    samples, 1.3 turns at the end of the rundown, and its held mean is off P0 by a share of a."""
    sim, _ = _falling(SignalCycle("spin.Omega"))
    sim.run_interval("TM", 0.5, HR)
    ho = sim.hold.handoffs[0]
    assert ho.window_samples() == 600 and ho.window_revolutions() is None
    turns = (_theta(sim.t) - _theta(sim.t - 600 * HR)) / (2 * math.pi)
    assert 1.2 < turns < 1.4
    assert "window_revolutions" not in sim.report.hold.as_dict()


def test_at_a_constant_speed_turns_and_periods_give_the_same_window():
    """theta = Omega t: the window counted in turns holds the very samples of the window of 3 periods."""
    sims = {}
    for angle in (None, "spin.theta"):
        spin = Spinner("spin", {"Omega0": W50, "P0": P0, "a": A})
        node = registry.create("testing.thermal_node", "node")
        sim = Simulation(System({"spin": spin, "node": node}, [Connection("spin.P", "node.P")]),
                         order=["spin", "node"], hold="mean", hold_cycles=3, cycle=SignalCycle("spin.Omega",
                                                                                                  angle=angle))
        sim.run_interval("TM", 0.2, H)
        sims[angle] = sim
    a, b = sims[None].hold.handoffs[0], sims["spin.theta"].hold.handoffs[0]
    assert a.window_samples() == b.window_samples() == 60
    assert np.array_equal(np.sort(a._data(), axis=0), np.sort(b._data(), axis=0))
    assert [m for _, m in a.history[-1]] == pytest.approx([m for _, m in b.history[-1]], rel=1e-12)


def test_a_bad_cycle_angle_is_a_clear_error(tmp_path):
    with pytest.raises(ValueError, match=r"cycle angle spin.P: a scalar Real output in \[rad\]"):
        build_simulation(_scenario(tmp_path, 'cycle = { signal = "spin.Omega", angle = "spin.P" }'))
    with pytest.raises(ValueError, match=r"\[schedule.cycle\] angle: .*spun"):
        build_simulation(_scenario(tmp_path, 'cycle = { signal = "spin.Omega", angle = "spun.theta" }'))
    with pytest.raises(ValueError, match=r"\[schedule.cycle\] angle: is the angle of a signal's cycle"):
        build_simulation(_scenario(tmp_path, 'cycle = { period = 0.02, angle = "spin.theta" }'))


def test_a_steady_window_grows_where_the_speed_falls_below_the_margin():
    """One interval of 0.78 s, 50 -> 3.2 Hz (6 % of the starting speed, below 1 / WINDOW_MARGIN): the steady
    window's ring grows and the window still spans the last 3 turns (0.27 s, more than the 0.24 s its ring was
    sized for); the hand-off's ring, fixed in the compiled loop's tables, does not: its window is cut to the ring and
    the turns it spanned say so (fewer than 3)."""
    sim, obs = _falling(SignalCycle("spin.Omega", angle="spin.theta"))
    sim.run_interval("TM", 0.78, HR)
    t_end = sim.t
    win = obs.windows[-1]
    t0 = _analytic_began(3.0, t_end)
    assert t_end - t0 > 0.24
    assert win["t"][0] <= t0 < win["t"][1]
    assert 3.0 <= win["revolutions"] < 3.001
    ho = sim.hold.handoffs[0]
    assert ho.window_samples() == len(ho.ring) == 2400      # 4 x 3 turns of 20 ms at 0.1 ms
    assert 2.0 < ho.window_revolutions() < 3.0
