"""Bad scenarios and bad connections give clear errors that name the problem."""
import math
import textwrap

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError, Variable
from rotorcosim.components.registry import create
from rotorcosim.master.core.algorithm import SimulationDiverged
from rotorcosim.master.scenario.build import build_simulation, load_scenario, schedule_of
from rotorcosim.master.schedule import Interval, ScheduleError, Timeline, from_spec
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System, SystemError_

GOOD = textwrap.dedent("""
    [components.m1]
    implementation = "testing.mass"
    parameters = { m = 1.0, k = 4.0, x0 = 0.1 }
    [components.m2]
    implementation = "testing.spring"
    [[connections]]
    from = "m1.x"
    to = "m2.x_in"
    [[connections]]
    from = "m1.v"
    to = "m2.v_in"
    [[connections]]
    from = "m2.F"
    to = "m1.F"
    [schedule]
    kind = "monolithic"
    duration = 0.1
    step = 1e-3
""")


def write(tmp_path, text):
    p = tmp_path / "s.toml"
    p.write_text(text)
    return p


def test_good_scenario_runs(tmp_path):
    sc = load_scenario(write(tmp_path, GOOD))
    rep = build_simulation(sc).run(schedule_of(sc))
    assert rep.timeline[0].steps == 100


@pytest.mark.parametrize("edit, message", [
    (lambda s: s.replace('"testing.mass"', '"testing.nope"'), "unknown component implementation 'testing.nope'"),
    (lambda s: s.replace('to = "m2.x_in"', 'to = "m2.x_inn"'), "m2.x_inn"),
    (lambda s: s.replace('from = "m1.x"', 'from = "m3.x"'), "[connections #1] from: 'm3.x': no component 'm3'"),
    (lambda s: s.replace('from = "m1.x"', 'from = "m1.F"'), "m1.F is an input of component 'm1' (Mass), used as an output"),
    (lambda s: s.replace('from = "m1.x"\n', 'from = "m1.v"\n'), "units differ"),
    (lambda s: s.replace('[[connections]]\nfrom = "m2.F"\nto = "m1.F"\n', ''), "inputs left unconnected"),
    (lambda s: s.replace("k = 4.0", "k = nan"), "parameters.k: must be a finite number, got nan"),
    (lambda s: s.replace("k = 4.0", 'k = "stiff"'), "parameters.k: must be a number [N/m], got a string"),
    (lambda s: s.replace("k = 4.0", "kk = 4.0"), "parameters.kk: testing.mass has no parameter 'kk' (did you mean 'k'?)"),
    (lambda s: s.replace("duration = 0.1", "duration = -0.1"), "[schedule] duration: must be a positive number"),
    (lambda s: s.replace('kind = "monolithic"', 'kind = "weekly"'), "[schedule] kind: 'weekly' is not one of"),
    (lambda s: s + '\n[algorithm]\nkind = "newton"\n', "[algorithm] kind: 'newton' is not one of"),
    (lambda s: s + '\n[bogus]\nx = 1\n', "unknown table"),
    (lambda s: s.replace("[components.m2]", "[components.m2]\nfmu = 'x.fmu'"), "exactly one of"),
    (lambda s: s.replace("[[connections]]\nfrom = \"m1.v\"", "[[connections]]\naverage = 'median'\nfrom = \"m1.v\""), "[connections #2] average: 'median' is not one of 'mean', 'rms', 'last' (did you mean 'mean'?)"),
    (lambda s: s + '\n[inputs]\n"m1.F" = 1.0\n', "m1.F has a constant value and is also driven"),
    (lambda s: s + "[[connections]]\nfrom = \"m1.x\"\nto = \"m2.x_in\"\n", "driven twice"),
    (lambda s: s.replace("from = \"m1.x\"", "from = \"m1x\""), "must be written 'component.port'"),
    (lambda s: "not toml [[[", "not valid TOML"),
])
def test_bad_scenarios(tmp_path, edit, message):
    with pytest.raises((ContractError, ValueError)) as info:
        sc = load_scenario(write(tmp_path, edit(GOOD)))
        build_simulation(sc).run(schedule_of(sc))
    assert message in str(info.value)


def test_missing_file():
    with pytest.raises(FileNotFoundError, match="not found"):
        load_scenario("/nonexistent/scenario.toml")


def test_size_mismatch_names_both_ports():
    from rotorcosim.components.contract import Component

    class Vec(Component):
        variables = (Variable("y", "output", size=3, unit="m"),)

    comps = {"a": Vec("a"), "m": create("testing.mass", "m")}
    with pytest.raises(SystemError_, match=r"a.y \(size 3\) -> m.F \(size 1\): sizes differ"):
        System(comps, [Connection("a.y", "m.F")])


def test_timeline_errors():
    with pytest.raises(ScheduleError, match="an interval in cycles needs a cycle of constant period"):
        from_spec({"kind": "timeline", "intervals": [{"phase": "TM", "cycles": 5}]})
    assert from_spec({"kind": "timeline", "intervals": [{"phase": "TM", "cycles": 5}]}, cycle=0.01).duration == 0.05
    with pytest.raises(ScheduleError, match="phase 'XX'"):
        from_spec({"kind": "timeline", "intervals": [{"phase": "XX", "duration": 1}]})
    with pytest.raises(ScheduleError, match="longer than its duration"):
        Interval("TM", 0.1, 1.0)


def test_thermal_only_needs_a_cycle():
    s = System({"m1": create("testing.mass", "m1", {"x0": 0.1})}, [], {"m1.F": 0.0})
    with pytest.raises(ScheduleError, match="thermal-only intervals needs a cycle"):
        Simulation(s).run(Timeline([Interval("TM", 0.1, 1e-3), Interval("TO", 1.0, 0.1)]))


def test_diverging_run_stops_with_clear_error_and_keeps_record(tmp_path):
    """A negative-damping mass grows without bound; the run stops with the time and port, and the recorder
    keeps (and marks incomplete) what it had."""
    import h5py

    from rotorcosim.master.observer.recorder import Recorder

    s = System({"m1": create("testing.mass", "m1", {"x0": 1.0, "c": -2000.0, "k": 1.0})}, [], {"m1.F": 0.0})
    rec = Recorder(tmp_path / "ts.h5", ["m1.x"], record_step=1e-3)
    sim = Simulation(s, observers=[rec])
    with pytest.raises(SimulationDiverged, match=r"m1\.\w+ is not finite at t = "):
        sim.run(Timeline([Interval("TM", 10.0, 1e-3)]))
    with h5py.File(tmp_path / "ts.h5") as f:
        assert f.attrs["complete"] == False  # noqa: E712 - a numpy bool: `is` would not match
        assert f["time"].shape[0] > 10
        assert np.all(np.isfinite(f["m1.x"][:10]))
    assert sim.report.error and "diverged" in sim.report.error


def test_schedule_speed_must_be_the_unbalance_speed():
    """[schedule] speed_rpm (the cycle of the hold windows and the results) against the speed the unbalance turns
    at ([results] speed_parameter, rotor.omega_pt): equal in the shipped scenario, a mismatch a clear error before
    the run."""
    import rotorcosim

    sc = rotorcosim.load_scenario("blade_loss_2850")
    assert sc.extra["results"]["speed_parameter"] == "rotor.omega_pt"
    sc.schedule["speed_rpm"] = 15000.0
    with pytest.raises(ValueError, match=r"speed_rpm = 15000.0 rev/min but rotor.omega_pt = .* \(16000 rev/min\)"):
        rotorcosim.simulate(sc, duration=2e-3, figures=False)
    # both come from the engine's spool speed: setting the rotor's moves the schedule's with it
    sc = rotorcosim.load_scenario("blade_loss_2850").set({"rotor.omega_pt": 15000.0 * math.pi / 30.0})
    assert sc.schedule["speed_rpm"] == pytest.approx(15000.0, rel=1e-15)
    res = rotorcosim.simulate(rotorcosim.load_scenario("blade_loss_2850"), duration=2e-3, figures=False)
    assert res.summary["status"] == "complete"
