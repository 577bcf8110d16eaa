"""The staggered scheme's error estimate (master/manipulator/error_estimate.py): the replay that carries a held interval's
input errors through a thermal component, against the analytic response of a lumped node; a held interval that ends
at a component's scheduled change is not charged; the advice when the estimate exceeds the tolerance; the share of a
law's move the mechanics made, at which the replay's loop runs and a driver's part of a power's error counts.
(tests/cases/test_error_estimate.py holds the estimate against monolithic runs.)"""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

import rotorcosim
from rotorcosim.master.manipulator.error_estimate import HoldReport, Pulse, replay
from rotorcosim.master.manipulator.handoff import HandOff, loop_share
from rotorcosim.master.scenario.build import build_simulation, schedule_of


def _node():
    sim = build_simulation(rotorcosim.load_scenario("toy_thermomechanical"), [])
    sim.initialise()
    return sim.system.components["node"]


def test_replay_gives_the_analytic_response_of_a_lumped_node():
    """testing.thermal_node: C dT/dt = P - (T - T_inf) / R, tau = R C = 10 s (scenario's C = 10, R = 1). An input
    error dP over [t0, t1] leaves dT = dP R (1 - exp(-(t1 - t0) / tau)) exp(-(now - t1) / tau) at ``now``; two
    pulses add (the network is linear in its inputs). The node's own step is exact for a constant input."""
    node = _node()
    tau = node.p["R"] * node.p["C"]
    T_before = float(node.y["T"][0])
    one = Pulse(0.0, 4.0, 0.05, {"P": np.array([2.0])})
    two = Pulse(5.0, 7.0, 0.05, {"P": np.array([-1.0])})
    now = 9.0
    got = replay(node, "node", [one, two], node.time + now)   # ``now`` only sets the replay's length after t0
    exact = (2.0 * node.p["R"] * (1 - math.exp(-4.0 / tau)) * math.exp(-(now - 4.0) / tau)
             - 1.0 * node.p["R"] * (1 - math.exp(-2.0 / tau)) * math.exp(-(now - 7.0) / tau))
    assert got["node.T"][0] == pytest.approx(exact, rel=1e-9)
    assert float(node.y["T"][0]) == T_before   # the component's state is restored


def test_replay_with_feedback_gives_the_closed_loop_response_of_a_lumped_node():
    """The same node with its input following its own error, dP = delta + g dT (a power that falls as its node
    warms: g < 0): C dT/dt = delta + g dT - dT / R, a node of resistance R' = R / (1 - g R) and time constant
    R' C, so dT = delta R' (1 - exp(-(t1 - t0) / tau')) exp(-(now - t1) / tau'). The replay closes the loop at
    the end of each step (implicitly): within 1 % at a step 1/130 of tau'."""
    node = _node()
    R, C, g = node.p["R"], node.p["C"], -0.5
    Rc = R / (1.0 - g * R)
    tau = Rc * C
    pulse = Pulse(0.0, 4.0, 0.05, {"P": np.array([2.0])})
    now = 9.0
    got = replay(node, "node", [pulse], node.time + now, [("P", "T", 0, g)])
    exact = 2.0 * Rc * (1 - math.exp(-4.0 / tau)) * math.exp(-(now - 4.0) / tau)
    assert got["node.T"][0] == pytest.approx(exact, rel=1e-2)
    # and not the open-loop response, 1.5 times larger here
    assert got["node.T"][0] < 0.8 * replay(node, "node", [pulse], node.time + now)["node.T"][0]
    # two loops at once (the law's and a weaker one): each output the larger of the two, the weaker loop's here,
    # as each replayed alone gives it
    weak = replay(node, "node", [pulse], node.time + now, [("P", "T", 0, 0.5 * g)])
    both = replay(node, "node", [pulse], node.time + now, [("P", "T", 0, g)], [[("P", "T", 0, 0.5 * g)]])
    assert weak["node.T"][0] > got["node.T"][0]
    assert both["node.T"][0] == pytest.approx(weak["node.T"][0], rel=1e-12)


def test_a_negative_input_error_larger_than_the_input_is_replayed():
    """An error larger than the present power (held far below the mechanics) asks for no negative input: both
    replays are lifted by the same amount."""
    node = _node()
    big = Pulse(0.0, 1.0, 0.05, {"P": np.array([-10.0 * float(node.u["P"][0]) - 5.0])})
    got = replay(node, "node", [big], node.time + 1.0)
    assert got["node.T"][0] < 0.0


def test_a_held_interval_ending_at_a_scheduled_change_is_not_charged():
    """A component declaring a scheduled change (next_event) at the end of the first TO interval (5 s): that
    interval's hand-off error is not measured across the change, the next one is charged as usual."""
    sc = rotorcosim.load_scenario("toy_thermomechanical")
    sim = build_simulation(sc, [])
    sim.initialise()
    osc = sim.system.components["osc"]
    osc.next_event = lambda t: 5.0 if t <= 5.0 else None
    sim.run(schedule_of(sc, "timeline", 10.3))
    first, second = sim.report.hold.intervals
    assert first["event"] == "osc at 5 s" and first["estimate_pct"] is None
    assert second["event"] is None and second["estimate_pct"] > 0.0
    assert [q.t0 for q in sim.hold._pulses["node"]] == [pytest.approx(5.3)]


def test_the_advice_names_the_interval_and_what_to_change():
    rep = HoldReport(intervals=[{"t_start": 0.3, "t_end": 5.0, "estimate_pct": 4.0, "event": None,
                                 "output": "node.T"},
                                {"t_start": 5.3, "t_end": 10.0, "estimate_pct": 1.0, "event": None,
                                 "output": "node.T"}])
    assert rep.advice(1.5, 2.0) is None
    note = rep.advice(4.0, 2.0)
    assert "0.3-5 s" in note and "node.T" in note and "2.35 s instead of 4.7 s" in note
    assert "drift_tolerance" in note


def test_a_run_above_its_tolerance_says_which_interval_and_what_to_change():
    """The toy under the automatic schedule with a tolerance below what its first held interval (to_min long)
    can reach: summary.json's hold.advice names that interval and the settings to change (a scenario without a
    case: the hold's own estimate); at a tolerance above the estimate there is none."""
    sc = rotorcosim.load_scenario("toy_thermomechanical")
    sc.schedule["tolerance"] = 0.5
    s = rotorcosim.simulate(sc, schedule="auto", duration=12.0, figures=False).summary
    hold = s["hold"]
    assert hold["estimated_error_pct"] > 0.5
    first = hold["intervals"][0]
    assert f"{first['t_start']:.6g}-{first['t_end']:.6g} s" in hold["advice"]
    assert "to_min" in hold["advice"] and "drift_tolerance" in hold["advice"]
    sc.schedule["tolerance"] = 99.0
    again = rotorcosim.simulate(sc, schedule="auto", duration=12.0, figures=False).summary["hold"]
    assert again["estimated_error_pct"] < 99.0 and "advice" not in again


def test_the_loop_share_is_the_mechanics_move_against_the_laws():
    """A law that moved -10 W over a held interval with a hand-off error of -4 W (the mechanics at the restart 4 W
    above it): the mechanics moved -6 W, 0.6 of the law's move (with -9 W of error, 0.1). A mechanics that moved
    more than the law (-12 W, or +13 W against +10 W) is credited with no more than the law's own sensitivity (1);
    a law that moved less than its error, or a port of two elements, has no share to measure (1)."""
    assert loop_share(np.array([-10.0]), np.array([-4.0])) == pytest.approx(0.6)
    assert loop_share(np.array([-10.0]), np.array([2.0])) == 1.0
    assert loop_share(np.array([-10.0]), np.array([-9.0])) == pytest.approx(0.1)
    assert loop_share(np.array([5.0]), np.array([5.5])) == 1.0
    assert loop_share(np.array([-10.0, 1.0]), np.array([-4.0, 0.0])) == 1.0
    assert loop_share(np.array([10.0]), np.array([-3.0])) == 1.0
    assert loop_share(np.array([3.0]), np.array([2.9])) == pytest.approx(1.0 - 2.9 / 3.0)


def test_a_drivers_share_of_a_power_error_is_what_the_mechanics_followed():
    """A law of two terms: its producer's own oil (-10 W/K, the frozen state's physics) and a driver, another
    component's oil that trended with the power (-5 W/K). With the oils in error by +0.1 K and +0.3 K and a restart
    that showed the mechanics making 0.2 of the law's move, the power is in error by -10 (0.1) + 0.2 (-5) (0.3)
    = -1.3 W; without a driver both terms count in full (-2.5 W); a value with no estimate is left out."""
    link = SimpleNamespace(src=SimpleNamespace(holds_state_in_TO=True))
    ho = HandOff(link, "mean", ["T_oil"])
    ho.gains = [("bearing", "T_oil", 0, -10.0), ("damper", "T_oil", 0, -5.0)]
    ho.loop_share, ho.driven = 0.2, True
    errors = {("bearing", "T_oil", 0): 0.1, ("damper", "T_oil", 0): 0.3}
    assert ho.power_error(lambda c, p, k: errors.get((c, p, k))) == pytest.approx(-1.3, rel=1e-12)
    ho.driven = False
    assert ho.power_error(lambda c, p, k: errors.get((c, p, k))) == pytest.approx(-2.5, rel=1e-12)
    assert ho.power_error(lambda c, p, k: errors.get((c, p, k)) if c == "damper" else None) == pytest.approx(-1.5)
