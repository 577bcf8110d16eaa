"""The automatic schedule in non-stationary operation (master/schedule/auto.py): with a cycle that follows a
speed signal, no thermal-only interval while the speed ramps (coupled intervals follow each other until the
response is steady), thermal-only ones once it is constant; and a held interval ends before a component's event."""
from __future__ import annotations

from rotorcosim.master.api import load_scenario, simulate


def _auto(sc, **extra):
    sc.schedule.update({"kind": "auto", "thermal_step": 0.05, "tm_min": 0.02, "tm_max": 0.2, "to_min": 0.1,
                        "to_max": 0.5, "steady_tolerance": 0.02, "drift_tolerance": 0.05, **extra})
    return sc


def test_no_held_interval_during_the_ramp():
    """jeffcott_rundown: the ramp 9000 -> 3000 rev/min lasts 1 s (6000 rev/min/s: 50 % of the speed per to_min);
    every held interval starts after it, and there are some (the response is steady at 3000 rev/min)."""
    sc = _auto(load_scenario("jeffcott_rundown"))
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
