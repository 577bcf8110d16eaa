"""The blade release is a time event (the rotor's ``next_event``, master/core/events.py): a held interval that would
span it ends at it, the unbalance force starts there (its first sample that holds it within one thermo-mechanical
step after ``t_blade_loss``), and it is recorded (summary.json ``events``), for the constant-speed and the
speed-following rotor, in the compiled and the generic loop, with a timeline (the paper's) and the automatic
schedule. A release inside a coupled interval is the rotor's own steps' and is not recorded: the shipped scenarios'
results stay what they were (bench/same_results.py)."""
from __future__ import annotations

import numpy as np
import pytest

import rotorcosim
from rotorcosim.master.api import simulate
from rotorcosim.master.schedule import Interval, Timeline

STEP = 5e-6      # the scenarios' thermo-mechanical step


def _run(name: str, t_release: float, schedule, duration=None, engine="auto"):
    sc = rotorcosim.load_scenario(name).set({"rotor.t_blade_loss": t_release})
    sc.outputs["record_step"] = STEP          # every thermo-mechanical step recorded
    sc.outputs["record"] = [r for r in sc.outputs["record"] if r != "rotor.F_u"] + ["rotor.F_u"]
    return simulate(sc, duration=duration, schedule=schedule, figures=False, engine=engine)


def _check(res, t_release: float, started_by_event: bool = True) -> None:
    (ev,) = [e for e in res.summary["events"] if e.get("component") == "rotor"]
    assert ev["t_s"] == pytest.approx(t_release, abs=1e-9)
    assert (ev["kind"], ev["trigger"], ev["values"]) == ("time", "time", {"event": "the blade loss"})
    # the held interval ends at the release, a coupled one starts there
    timeline = res.summary["timeline"]
    (held,) = [iv for iv in timeline if iv["phase"] == "TO" and iv["t_end"] == pytest.approx(t_release, abs=1e-9)]
    after = timeline[timeline.index(held) + 1]
    assert after["phase"] == "TM" and after["t_start"] == pytest.approx(t_release, abs=1e-9)
    if started_by_event:
        assert held["reason"] == "event" and after["reason"] == "after an event"
    # the force: the residual alone before the release, the blade's from the first step after it
    t, f = res.time, np.hypot(*np.asarray(res["rotor.F_u"]).T[:2])
    big = f > 300.0        # the residual 87 N, the blade's 2 850 N
    first = t[np.argmax(big)]
    assert big.any() and t_release < first <= t_release + STEP * (1 + 1e-6), (first, t_release)
    assert not big[t <= t_release].any()


def test_release_in_a_held_interval_of_the_paper_timeline():
    """blade_loss_2850's timeline, the release at 24.0005 s inside its first thermal-only interval (0.25-24.1 s):
    the held interval ends there and the rest of it runs coupled (the compiled loop). The rest is whole windows of
    the thermal networks' 1 ms step, so it runs 0.5 ms past 24.1 s: the next interval takes that up, and the
    timeline still ends at 24.25 s."""
    res = _run("blade_loss_2850", 24.0005, "scenario", duration=24.25)
    _check(res, 24.0005)
    assert res.summary["engine"] == "compiled"
    assert res.summary["t_end_s"] == pytest.approx(24.25, abs=1e-9)
    assert [iv["phase"] for iv in res.summary["timeline"]] == ["TM", "TO", "TM", "TM", "TO"]


@pytest.mark.parametrize("name", ["blade_loss_2850", "blade_loss_rundown"])
def test_release_in_a_held_interval_both_rotors_generic_loop(name):
    """The constant-speed rotor (blade_loss_2850) and the speed-following one (blade_loss_rundown's
    rotor.mta_spinning), a short timeline, the release at 0.99 s in its held interval 0.03-1.0 s, the generic
    loop."""
    tl = Timeline([Interval("TM", 0.03, STEP), Interval("TO", 0.97, 0.1), Interval("TM", 0.005, STEP)])
    res = _run(name, 0.99, tl, engine="python")
    _check(res, 0.99)
    assert res.summary["engine"] == "python"


def test_release_with_the_automatic_schedule():
    """blade_loss_rundown's automatic schedule (the speed-following rotor, the compiled loop), the release at 5 s:
    the thermal-only interval before it ends there (the schedule's own cut), it is recorded, and the force
    starts with the coupled interval that follows."""
    res = _run("blade_loss_rundown", 5.0, "scenario", duration=6.0)
    _check(res, 5.0, started_by_event=False)


def test_release_in_a_coupled_interval_is_not_recorded():
    """The shipped release at 0.01 s, inside the first coupled interval: the rotor's steps apply it as before,
    nothing is recorded."""
    res = simulate("blade_loss_2850", duration=0.02, figures=False)
    assert not [e for e in res.summary.get("events") or () if e.get("component") == "rotor"]
