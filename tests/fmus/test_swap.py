"""Swapping a native component for its own exported FMU changes nothing (same code inside): 1e-9 relative.

Two systems, each over a staggered TM / TO / TM sequence so that the FMU's phases (read back from its vendor
annotation) matter too: the toy thermo-mechanical scenario (oscillator + thermal node, both swapped), and the
squeeze film damper between a test journal (a 2-D mass under a rotating force) and a thermal node.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from rotorcosim.components import registry
from rotorcosim.components.contract import Component, Variable
from rotorcosim.master.scenario.build import load_scenario, parse

from tests.helpers.fmus import TOY, max_rel_diff, run_intervals

TOL = 1e-9


class Journal(Component):
    """A 2-D journal mass m under a rotating force F_u (cos wt, sin wt) and the damper's force (test only)."""

    variables = (
        Variable("m", "parameter", unit="kg", start=5.0),
        Variable("F_u", "parameter", unit="N", start=300.0),
        Variable("w", "parameter", unit="rad/s", start=2 * math.pi * 150.0),
        Variable("F", "input", 2, "N"),
        Variable("X", "output", 2, "m"),
        Variable("V", "output", 2, "m/s"),
    )
    preferred_step = 1e-5

    def setup(self, t0=0.0):
        super().setup(t0)
        self.state = {"x": np.zeros(2), "v": np.zeros(2)}

    def do_step(self, t, h):
        p = self.p
        f = self.u["F"] + p["F_u"] * np.array([math.cos(p["w"] * t), math.sin(p["w"] * t)])
        self.state["v"] = self.state["v"] + h * f / p["m"]
        self.state["x"] = self.state["x"] + h * self.state["v"]
        self.y["X"], self.y["V"] = self.state["x"].copy(), self.state["v"].copy()
        self.time = t + h


DAMPER_PARAMS = {"damper": 5, "n_theta": 32, "n_z": 8}   # as the damper_fmu fixture (conftest.py)


def damper_scenario(damper_fmu=None):
    damper = {"fmu": str(damper_fmu)} if damper_fmu else {"implementation": "damper.fast",
                                                           "parameters": DAMPER_PARAMS}
    return parse({
        "components": {
            "journal": {"implementation": "testing_fmus.journal"},
            "damper5": damper,
            "node": {"implementation": "testing.thermal_node", "parameters": {"C": 2.0, "R": 0.5}},
        },
        "connections": [
            {"from": "journal.X", "to": "damper5.X_journal"}, {"from": "journal.V", "to": "damper5.V_journal"},
            {"from": "damper5.F_journal", "to": "journal.F"}, {"from": "damper5.P_film", "to": "node.P"},
            {"from": "node.T", "to": "damper5.T_oil"},
        ],
        "inputs": {"damper5.X_housing": [0.0, 0.0], "damper5.V_housing": [0.0, 0.0]},
        "algorithm": {"kind": "gauss-seidel", "order": ["journal", "damper5", "node"]},
        "schedule": {"kind": "monolithic", "duration": 0.01, "step": 1e-5, "speed_rpm": 9000.0},
    })


STAGGERED_DAMPER = [("TM", 0.01, 1e-5), ("TO", 0.2, 0.02), ("TM", 0.005, 1e-5)]


@pytest.fixture
def journal(monkeypatch):
    """The test journal registered for this test only (other tests iterate over the registry)."""
    monkeypatch.setitem(registry._extra, "testing_fmus.journal", Journal)


def test_damper_swapped_for_its_fmu_gives_the_same_run(damper_fmu, journal):
    native = run_intervals(damper_scenario(), STAGGERED_DAMPER)
    fmu = run_intervals(damper_scenario(damper_fmu), STAGGERED_DAMPER)
    refs = [r for r in native.rows[0] if not r.startswith("journal.")] + ["journal.X", "journal.V"]
    # the run must actually move: a journal orbit of some micrometres and a warming film
    assert np.max(np.abs(native.series("journal.X"))) > 1e-6
    assert np.ptp(native.series("node.T")) > 0.0
    assert max_rel_diff(native, fmu, refs) < TOL


def test_toy_components_swapped_for_their_fmus_give_the_same_run(toy_fmus):
    sc = load_scenario(TOY)
    intervals = [("TM", 0.1, 1e-3), ("TO", 1.0, 0.05), ("TM", 0.1, 1e-3)]
    native = run_intervals(sc, intervals)
    swapped = sc.copy()
    for name, path in toy_fmus.items():
        spec = swapped.components[name]
        spec.implementation, spec.fmu, spec.parameters = None, str(path), {}
    fmu = run_intervals(swapped, intervals)
    refs = list(native.rows[0])
    assert np.max(np.abs(native.series("osc.x"))) > 0 and np.ptp(native.series("node.T")) > 0
    assert max_rel_diff(native, fmu, refs) < TOL


def test_parameters_set_through_fmi_act_as_natively(damper_fmu):
    """The damper derives its geometry from ``damper`` unless set explicitly: setting ``damper = 0`` on the FMU
    exported for damper 5 must give damper 0's film, as the native component does."""
    from rotorcosim.fmus.importer import load_fmu_component

    params = dict(DAMPER_PARAMS, damper=0)
    fmu = load_fmu_component(damper_fmu, "d", {"damper": 0})
    native = registry.create("damper.fast", "d", params)
    other = registry.create("damper.fast", "d", DAMPER_PARAMS)
    inputs = {"X_journal": [2e-4, 1e-4], "V_journal": [0.01, 0.05]}
    try:
        for c in (fmu, native, other):
            c.set_inputs(inputs)
            c.setup(0.0)
            c.do_step(0.0, 1e-5)
        assert not np.allclose(native.y["F_film"], other.y["F_film"])     # the two dampers differ
        np.testing.assert_array_equal(fmu.y["F_film"], native.y["F_film"])
    finally:
        fmu.terminate()


def bearing_scenario(bearing_fmu=None):
    bearing = {"fmu": str(bearing_fmu)} if bearing_fmu else {"implementation": "bearing.hertz",
                                                             "parameters": {"bearing": 5}}
    return parse({
        "components": {
            "bearing5": bearing,
            "node": {"implementation": "testing.thermal_node", "parameters": {"C": 100.0, "R": 0.05}},
        },
        "connections": [{"from": "bearing5.P_drag", "to": "node.P"}, {"from": "node.T", "to": "bearing5.T_oil"}],
        "inputs": {"bearing5.X_inner": [2e-6, -1e-6, 0.0], "bearing5.V_inner": [0.0, 0.0, 0.0],
                   "bearing5.F_journal": [0.0, 0.0], "bearing5.K_journal": [0.0] * 4,
                   "bearing5.C_journal": [0.0] * 4, "bearing5.eps": [0.0, 0.0, 0.0]},
        "algorithm": {"kind": "gauss-seidel", "order": ["bearing5", "node"]},
        "schedule": {"kind": "monolithic", "duration": 0.002, "step": 1e-5, "speed_rpm": 16000.0},
    })


def test_bearing_swapped_for_its_fmu_follows_the_phases(fmu_dir):
    """The bearing decides its phases in its set-up and keeps its drag following the oil temperature in
    thermal-only intervals (``enter_phase``): both must cross the FMU boundary."""
    from rotorcosim.fmus.export import export_component

    fmu_path = export_component("bearing.hertz", fmu_dir / "bearing5.fmu", instance_name="bearing5",
                                parameters={"bearing": 5})
    intervals = [("TM", 0.002, 1e-5), ("TO", 0.5, 0.05), ("TM", 0.001, 1e-5)]
    native = run_intervals(bearing_scenario(), intervals)
    fmu = run_intervals(bearing_scenario(fmu_path), intervals)
    # the thermal-only steps (200 TM steps, then 10 TO steps) change the drag with the warming oil
    drag_to = native.series("bearing5.P_drag")[200:210, 0]
    assert np.ptp(drag_to) > 0.0
    assert max_rel_diff(native, fmu, list(native.rows[0])) < TOL


def test_iterative_coupling_rolls_fmus_back_through_fmu_state(fmu_dir):
    """Gauss-Seidel iterated to convergence: every step is redone from get_state snapshots, which for an FMU
    are fmi2GetFMUstate/fmi2SetFMUstate; the run must equal the native one."""
    from rotorcosim.fmus.export import export_component

    p1 = dict(m=1.0, k=40.0, x0=0.1)
    p2 = dict(m=2.0, k=30.0, kc=100.0, cc=0.5)
    fmus = {"m1": export_component("testing.mass", fmu_dir / "it_m1.fmu", instance_name="m1", parameters=p1),
            "m2": export_component("testing.spring", fmu_dir / "it_m2.fmu", instance_name="m2", parameters=p2)}

    def scenario(use_fmus):
        comps = {"m1": {"implementation": "testing.mass", "parameters": p1},
                 "m2": {"implementation": "testing.spring", "parameters": p2}}
        if use_fmus:
            comps = {n: {"fmu": str(p)} for n, p in fmus.items()}
        return parse({"components": comps,
                      "connections": [{"from": "m1.x", "to": "m2.x_in"}, {"from": "m1.v", "to": "m2.v_in"},
                                      {"from": "m2.F", "to": "m1.F"}],
                      "algorithm": {"kind": "jacobi", "order": ["m1", "m2"], "iterations": 8,
                                    "tolerance": 1e-12}})

    intervals = [("TM", 0.5, 1e-2)]
    native = run_intervals(scenario(False), intervals)
    fmu = run_intervals(scenario(True), intervals)
    assert max_rel_diff(native, fmu, list(native.rows[0])) < TOL
    # iterating changed the run (it is not the plain single-pass Jacobi run)
    single = scenario(False)
    single.algorithm["iterations"] = 1
    plain = run_intervals(single, intervals)
    assert max_rel_diff(native, plain, ["m1.x"]) > 1e-6


@pytest.fixture(scope="module")
def foreign_rubring_fmu(fmu_dir):
    """A rub ring FMU with the rub ring's ports whose parameters are named its own way (another tool's): no
    ``clearance``, ``radius`` or ``omega``, the values the engine gives the native rub ring."""
    from rotorcosim.fmus.export import export_component

    from tests.helpers.fmus import model_description, with_model_description

    src = fmu_dir / "rubring_native.fmu"
    if not src.exists():
        export_component("rubring.contact", src, instance_name="rubring0")
    xml = model_description(src)
    for old, new in (("clearance", "gap"), ("radius", "ring_radius"), ("omega", "spin_speed")):
        assert f'name="{old}"' in xml
        xml = xml.replace(f'name="{old}"', f'name="{new}"')
    return with_model_description(src, fmu_dir / "rubring_foreign.fmu", xml)


def test_an_fmu_in_a_bound_components_place_drops_the_engine_values_it_does_not_declare(foreign_rubring_fmu,
                                                                                       tmp_path, monkeypatch):
    """As for a plug-in: the engine's values a foreign FMU does not declare are dropped (they were passed on,
    and the build failed: "no parameter 'clearance'"), by --swap and by a scenario's ``fmu = ...`` alike."""
    from rotorcosim import scenarios
    base = load_scenario(scenarios.path("blade_loss"))
    assert {"clearance", "radius", "omega"} <= set(base.components["rubring0"].parameters)
    swapped = base.swap("rubring0", str(foreign_rubring_fmu))
    assert not {"clearance", "radius", "omega"} & set(swapped.components["rubring0"].parameters)
    assert "rubring0.clearance" not in swapped.engine.targets
    assert "rubring5.clearance" in swapped.engine.targets          # the other ring keeps its engine values
    assert base.swap("rubring0", str(foreign_rubring_fmu), parameters={"gap": 1e-3}) \
        .components["rubring0"].parameters == {"gap": 1e-3}
    # our own FMU declares them: they stay (its engine values reach it as parameters)
    own = base.swap("rubring0", str(foreign_rubring_fmu.with_name("rubring_native.fmu")))
    assert {"clearance", "radius", "omega"} <= set(own.components["rubring0"].parameters)
    # a scenario file putting the FMU in its place (relative to the file)
    (tmp_path / "rub.fmu").write_bytes(foreign_rubring_fmu.read_bytes())
    sc_file = tmp_path / "foreign.toml"
    sc_file.write_text(f'[scenario]\nextends = "{scenarios.path("blade_loss").as_posix()}"\n'
                       '[components.rubring0]\nfmu = "rub.fmu"\n')
    monkeypatch.chdir(tmp_path.parent)
    sc = load_scenario(sc_file)
    assert not {"clearance", "radius", "omega"} & set(sc.components["rubring0"].parameters)
