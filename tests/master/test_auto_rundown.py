"""The automatic schedule in non-stationary operation (master/schedule/auto.py): with a cycle that follows a
speed signal, no thermal-only interval while the speed ramps (coupled intervals follow each other until the
response is steady), thermal-only ones once it is constant; and a held interval ends before a component's event."""
from __future__ import annotations

import pytest

from rotorcosim.master.api import load_scenario, simulate

TURNS = {"signal": "spool.Omega", "unit": "rad/s", "angle": "spool.theta"}


def _auto(sc, **extra):
    sc.schedule.update({"kind": "auto", "thermal_step": 0.05, "tm_min": 0.02, "tm_max": 0.2, "to_min": 0.1,
                        "to_max": 0.5, "steady_tolerance": 0.02, "drift_tolerance": 0.05, **extra})
    return sc


@pytest.mark.parametrize("turns", [False, True])
def test_no_held_interval_during_the_ramp(turns):
    """jeffcott_rundown: the ramp 9000 -> 3000 rev/min lasts 1 s (6000 rev/min/s: 50 % of the speed per to_min);
    every held interval starts after it, and there are some (the response is steady at 3000 rev/min). The same
    with the steadiness test counted in turns of the spool's angle, on the disk's orbit."""
    sc = _auto(load_scenario("jeffcott_rundown"))
    if turns:
        sc.schedule.update(cycle=dict(TURNS), tracked=["rotor.X_brg0"])
    r = simulate(sc, duration=3.0, figures=False)
    held = [iv for iv in r.summary["timeline"] if iv["phase"] == "TO"]
    assert held, r.summary["timeline"]
    assert min(iv["t_start"] for iv in held) >= 1.0
    coupled = [iv for iv in r.summary["timeline"] if iv["phase"] == "TM" and iv["t_start"] < 1.0]
    assert len(coupled) >= 5                      # tm_max 0.2 s: one coupled interval after the other


def test_held_interval_ends_at_a_component_event():
    """A torque-driven spool with its fuel cut at 0.73 s: no held interval spans the cut."""
    sc = _auto(load_scenario("jeffcott_rundown").set({"spool.profile": "torque", "spool.t_fuel_cut": 0.73,
                                                      "spool.inertia": 0.05, "spool.windmill_rpm": 3000.0,
                                                      "spool.aero_torque": 5.0}))
    r = simulate(sc, duration=1.5, figures=False)
    for iv in r.summary["timeline"]:
        if iv["phase"] == "TO":
            assert not (iv["t_start"] < 0.73 < iv["t_end"] - 1e-9), iv


def _drifting(engine="auto"):
    """A torque-driven rundown slow enough to be held (0.5 % of the speed per to_min, under drift_tolerance),
    fast enough to drift out of a held interval: a viscous drag b Omega, b = 2.65e-3 N m s on 0.05 kg m^2, so
    dOmega/dt = -Omega / 18.9 s (-50 rad/s^2 at 9000 rev/min) and 5 % of the speed in about a second; the windows
    and the steadiness test counted in turns."""
    sc = _auto(load_scenario("jeffcott_rundown").set({"spool.profile": "torque", "spool.t_fuel_cut": 0.0,
                                                      "spool.inertia": 0.05, "spool.drag_coefficient": 2.65e-3}),
               to_max=2.0, cycle=dict(TURNS), tracked=["rotor.X_brg0"])
    return simulate(sc, duration=3.0, figures=False, engine=engine)


def test_a_held_interval_ends_when_the_speed_drifts_and_coupled_ones_follow():
    r = _drifting()
    tl = r.summary["timeline"]
    held = [iv for iv in tl if iv["phase"] == "TO"]
    assert held, tl
    drifted = [iv for iv in held if iv["reason"] == "drift of spool.Omega"]
    assert drifted, tl
    for iv in drifted:   # it drifted by more than 5 %, sooner than to_max, and a coupled interval follows it
        assert iv["t_end"] - iv["t_start"] < 2.0 - 1e-9
        nxt = tl[tl.index(iv) + 1] if tl.index(iv) + 1 < len(tl) else None
        assert nxt is None or nxt["phase"] == "TM"
    # the coupled intervals before a held one ended steady (their test, counted in turns, decided)
    assert any(iv["reason"] == "steady" for iv in tl if iv["phase"] == "TM"), tl


@pytest.mark.slow   # ~24 s of CPU time (measured): both loops through the automatic schedule
def test_the_compiled_loop_decides_in_turns_as_the_generic_loop():
    """The steadiness test counted in turns gets each chunk's rows cut at the samples that end a turn: both loops
    end the intervals at the same steps for the same reasons."""
    a, b = _drifting("compiled"), _drifting("python")
    ta = [(iv["phase"], iv["steps"], iv["reason"]) for iv in a.summary["timeline"]]
    assert ta == [(iv["phase"], iv["steps"], iv["reason"]) for iv in b.summary["timeline"]]
    assert a.summary["engine"] == "compiled" and b.summary["engine"] == "python"


@pytest.mark.parametrize("speed_tolerance, held_in_ramp", [(None, True), (0.005, False)])
def test_speed_tolerance_keeps_a_slow_ramp_coupled(speed_tolerance, held_in_ramp):
    """A slow ramp, 9000 -> 3000 rev/min in 6 s (1.1-3.3 % of the speed per to_min of 0.1 s): counted in turns the
    disk's orbit is steady turn to turn, so with the default (drift_tolerance, 5 %) held intervals run during the
    ramp; with speed_tolerance 0.5 % none starts before its end."""
    sc = _auto(load_scenario("jeffcott_rundown").set({"spool.duration": 6.0}), cycle=dict(TURNS),
               tracked=["rotor.X_brg0"], **({} if speed_tolerance is None else {"speed_tolerance": speed_tolerance}))
    r = simulate(sc, duration=6.5, figures=False)
    held = [iv for iv in r.summary["timeline"] if iv["phase"] == "TO"]
    assert any(iv["t_start"] < 6.0 for iv in held) == held_in_ramp, r.summary["timeline"]


def test_turns_are_checked_when_a_turn_is_no_round_number_of_steps():
    """A spool at 3 517 rev/min stepping every 1 ms (50 base steps of 2e-5 s), a turn 853 base steps: the test
    counted in turns is checked about once a turn, not at the common multiple of a turn and the multi-rate
    period (42 650 steps, 0.85 s, longer than tm_max: never checked, every coupled interval ran to tm_max). At a
    constant speed the orbit is steady: the coupled intervals end steady, each after the restart's ramp and the
    hold's window (2 + 5 turns, 0.12 s) and before tm_max."""
    sc = _auto(load_scenario("jeffcott_rundown").set({"spool.speed_rpm": 3517.0, "spool.end_speed_rpm": 3517.0}),
               cycle=dict(TURNS), tracked=["rotor.X_brg0"], tm_max=0.3)
    sc.components["spool"].step = 1e-3
    r = simulate(sc, duration=1.2, figures=False)
    coupled = [iv for iv in r.summary["timeline"] if iv["phase"] == "TM"][:-1]   # (the last one: to the end)
    assert coupled and all(iv["reason"] == "steady" for iv in coupled), r.summary["timeline"]
    turn = 60.0 / 3517.0
    assert all(7 * turn - 1e-3 <= iv["t_end"] - iv["t_start"] < 0.3 - 1e-9 for iv in coupled), r.summary["timeline"]
