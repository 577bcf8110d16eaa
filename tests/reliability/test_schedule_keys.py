"""The automatic schedule's keys a user may get wrong, each refused before the run in one line naming the key,
exit status 2, no folder: a tracked output the system does not have (checked when the scenario is built, not
when the first steadiness test reads it, which a short run never reaches), an interval's shortest duration above
its longest, a relative tolerance above 1."""
from __future__ import annotations

import json

import pytest

from rotorcosim.master.cli import main

from tests.reliability.test_cli import one_line_error

TOY = "toy_thermomechanical"


@pytest.mark.parametrize("schedule, says", [
    ('tracked = ["osc.nope"]', "[schedule] tracked: osc.nope: component 'osc'"),
    ('tracked = ["node.C"]', "[schedule] tracked: node.C is a parameter of component 'node'"),
    ('tracked = ["nope.x"]', "[schedule] tracked: unknown component 'nope'"),
    ("tm_min = 0.6\ntm_max = 0.5", "tm_min = 0.6 s is above tm_max = 0.5 s"),
    ("to_min = 2.0\nto_max = 1.0", "to_min = 2 s is above to_max = 1 s"),
    # intervals shorter than their step: each was stretched to a step, and the run went on without end
    ("tm_min = 1e-10\ntm_max = 1e-9", "tm_min = 1e-10 s is shorter than one step (0.001 s)"),
    ("to_min = 0.01", "to_min = 0.01 s is shorter than one thermal_step (0.05 s)"),
    ("thermal_step = 1e-12\nto_min = 1e-12", "thermal_step = 1e-12 s is shorter than the thermo-mechanical step"),
    # relative tolerances given as percentages: a TO interval that no drift ends, a TM one steady at once
    ("drift_tolerance = 2", "drift_tolerance: is a fraction (0.02 = 2 %), at most 1, got 2"),
    ("steady_tolerance = 5.0", "steady_tolerance: is a fraction (0.02 = 2 %), at most 1, got 5.0"),
    ("speed_tolerance = 10", "speed_tolerance: is a fraction (0.02 = 2 %), at most 1, got 10"),
])
@pytest.mark.parametrize("duration", ["0.01", "20"])
def test_auto_schedule_keys_refused_whatever_the_duration(tmp_path, capsys, schedule, says, duration):
    f = tmp_path / "s.toml"
    f.write_text(f'[scenario]\nextends = "{TOY}"\nname = "t"\n\n[schedule]\n{schedule}\n')
    out = tmp_path / "o"
    rc = main(["run", str(f), "--schedule", "auto", "--duration", duration, "--quiet", "--no-figures",
               "--out", str(out)])
    line = one_line_error(capsys.readouterr().err)
    assert rc == 2 and says in line, line
    assert not out.exists()


def test_a_component_step_longer_than_tm_min_is_refused(tmp_path, capsys):
    """The scenario's own schedule is a timeline: the automatic one comes from the command line, and its shortest
    thermo-mechanical interval must hold one step of every component."""
    f = tmp_path / "s.toml"
    f.write_text(f'[scenario]\nextends = "{TOY}"\nname = "t"\n\n[components.node]\nstep = 0.1\n\n'
                 '[schedule]\ntm_min = 0.05\n')
    out = tmp_path / "o"
    rc = main(["run", str(f), "--schedule", "auto", "--duration", "20", "--quiet", "--no-figures", "--out", str(out)])
    line = one_line_error(capsys.readouterr().err)
    assert rc == 2 and "tm_min = 0.05 s is shorter than one communication step of node (0.1 s)" in line, line
    assert not out.exists()


def test_a_relative_tolerance_above_one_is_refused_from_python_too():
    """The automatic schedule made in Python (no scenario file): the same refusal, from the schedule itself."""
    from rotorcosim.master.schedule.auto import AutoSchedule
    from rotorcosim.master.schedule.timeline import ScheduleError

    with pytest.raises(ScheduleError, match="drift_tolerance is a fraction"):
        AutoSchedule(duration=1.0, step=1e-5, thermal_step=0.1, drift_tolerance=2.0)
    assert AutoSchedule(duration=1.0, step=1e-5, thermal_step=0.1, drift_tolerance=1.0).drift_tolerance == 1.0


def test_a_timeline_that_begins_thermal_only(tmp_path, capsys):
    """A thermal-only interval before any thermo-mechanical one holds the mechanics' outputs at the start: with
    the ball bearings' drag law (own engine) it ended in "unexpected AttributeError: 'HandOff' object has no
    attribute 'cycles' ... it may be a bug" (exit 1). The blade release moved into the thermo-mechanical
    interval: at its 0.01 s it would end the thermal-only one there (a time event)."""
    assert main(["new-engine", str(tmp_path / "X")]) == 0
    f = tmp_path / "X" / "first_to.toml"
    f.write_text('[scenario]\nextends = "blade_loss.toml"\nname = "first_to"\n\n[schedule]\n'
                 'intervals = [{ phase = "TO", duration = 0.5 }, { phase = "TM", duration = 0.02 }]\n\n'
                 '[components.rotor]\nparameters = { t_blade_loss = 0.505 }\n')
    out = tmp_path / "o"
    assert main(["run", str(f), "--quiet", "--no-figures", "--out", str(out)]) == 0, capsys.readouterr().err
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "complete" and [i["phase"] for i in s["timeline"]] == ["TO", "TM"]
    assert s["bearings"]["0"]["T_ball_C"] > 30.0          # the first TO interval warmed the bearing
