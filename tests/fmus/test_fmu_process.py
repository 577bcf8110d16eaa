"""FMUs out of process: the same results, and a crashing or hanging FMU fails the run cleanly."""
from __future__ import annotations

import os
import signal
import time

import numpy as np
import pytest

from rotorcosim.components.contract import Component, Variable
from rotorcosim.components.registry import create
from rotorcosim.fmus.importer import load_fmu_component
from rotorcosim.fmus.process import ProcessFMU
from rotorcosim.master.core.algorithm import ComponentCrashed, SimulationDiverged, StepTimedOut
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation
from rotorcosim.master.core.system import Connection, System


class Faulty(Component):
    """Outputs t; at t >= 5 ms it crashes the process (SIGSEGV) or never returns, as its name says."""

    variables = (Variable("mode", "parameter", start="crash", type="String"),
                 Variable("y", "output", unit="m"))

    def do_step(self, t, h):
        if t >= 0.005:
            if self.p["mode"] == "crash":
                os.kill(os.getpid(), signal.SIGSEGV)
            time.sleep(3600)
        self.y["y"] = np.array([t + h])
        self.time = t + h


def faulty(path, name, parameters, start):
    return Faulty(name, parameters)


def run_alone(comp, duration=0.01, step=1e-3):
    sim = Simulation(System({"c": comp}, []))
    return sim.run(Timeline([Interval("TM", duration, step)]))


def test_same_results_in_and_out_of_process(mass_fmu):
    def system(m):
        return System({"m": m, "s": create("testing.spring", "s")},
                      [Connection("m.x", "s.x_in"), Connection("m.v", "s.v_in"), Connection("s.F", "m.F")])

    results = []
    for m in (load_fmu_component(mass_fmu, "m", {"k": 40.0}), ProcessFMU(mass_fmu, "m", {"k": 40.0}, timeout=60)):
        sim = Simulation(system(m))
        sim.run(Timeline([Interval("TM", 0.2, 1e-3)]))
        results.append((m.y["x"].copy(), m.y["v"].copy()))
        m.terminate()
    assert np.array_equal(results[0][0], results[1][0]) and np.array_equal(results[0][1], results[1][1])


def test_crashing_fmu_fails_the_run_cleanly():
    comp = ProcessFMU("faulty", "c", {"mode": "crash"}, timeout=60, factory=faulty)
    with pytest.raises(ComponentCrashed, match=r"c failed in do_step at t = 0.005 s: .*process died in "
                                                 r"DoStep\(t = 0.005 s.*killed by SIGSEGV") as err:
        run_alone(comp)
    assert not isinstance(err.value, SimulationDiverged) and err.value.what == "a component's process crashed"


def test_hanging_fmu_is_stopped_at_the_time_limit():
    comp = ProcessFMU("faulty", "c", {"mode": "hang"}, timeout=1.0, factory=faulty)
    t0 = time.perf_counter()
    with pytest.raises(StepTimedOut, match=r"did not return within 1 s \(the FMU step time limit\)") as err:
        run_alone(comp)
    assert not isinstance(err.value, SimulationDiverged)   # it did not diverge: its own first words
    assert err.value.what == "a component's step timed out"
    assert time.perf_counter() - t0 < 30
    assert comp._proc.poll() is not None


def test_state_handles_do_not_go_to_disk(mass_fmu):
    import pickle

    m = ProcessFMU(mass_fmu, "m", {}, timeout=60)
    m.setup(0.0)
    with pytest.raises(TypeError, match="lives in the FMU's process"):
        pickle.dumps(m.get_state())
    m.terminate()


def test_scenario_option(mass_fmu, tmp_path):
    from rotorcosim.master.scenario.build import build_system, parse

    data = {"components": {"m": {"fmu": str(mass_fmu), "step_timeout": 30.0}, "s": {"implementation": "testing.spring"}},
            "connections": [{"from": "m.x", "to": "s.x_in"}, {"from": "m.v", "to": "s.v_in"}, {"from": "s.F", "to": "m.F"}]}
    sys_ = build_system(parse(data))
    assert isinstance(sys_.components["m"], ProcessFMU) and sys_.components["m"].timeout == 30.0
    sys_.components["m"].terminate()
    data["components"]["s"]["process"] = True
    with pytest.raises(ValueError, match=r"\[components.s\] process: applies to FMU components only"):
        parse(data)
