"""The rotor component: ports against the scenario, stepping against the reference integrator, unbalance,
state rollback, bad inputs, critical speeds and the ``critical-speeds`` command."""
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.components.registry import create
from rotorcosim.cases.blade_loss.critical_speeds import critical_speeds
from rotorcosim.components.rotor.component import Rotor, full_model, reduced_model
from rotorcosim.components.rotor.newmark import integrate
from rotorcosim.master.cli import main

SCENARIO = Path(__file__).resolve().parents[2] / "scenarios" / "blade_loss.toml"
H = 1e-5
W_PT = 16000 * 2 * math.pi / 60


def _rotor(**params):
    r = create("rotor.mta", "rotor", params)
    r.setup(0.0)
    return r


def test_ports_match_the_blade_loss_scenario():
    """Every rotor.<port> wired in scenarios/blade_loss.toml (its templates instantiated) exists with the right
    causality (output when it is a 'from', input when it is a 'to'), and every rotor input is driven."""
    from rotorcosim.master.scenario.build import load_scenario

    sc = tomllib.loads(SCENARIO.read_text())
    by_name = {v.name: v for v in Rotor.variables}
    driven = set()
    for c in load_scenario(SCENARIO).connections:
        for end, causality in (("src", "output"), ("dst", "input")):
            comp, _, port = getattr(c, end).partition(".")
            if comp == "rotor":
                assert port in by_name and by_name[port].causality == causality, getattr(c, end)
                if causality == "input":
                    driven.add(port)
    assert driven == {v.name for v in Rotor.variables if v.causality == "input"}
    assert set(sc["components"]["rotor"]["parameters"]) <= set(by_name)
    assert Rotor.preferred_step == 1e-5 and Rotor.phases == frozenset({"TM"})


def test_component_steps_like_the_reference_newmark_integrator():
    """With a blade-loss force from t = 0 and no port forces, the component's compiled one-matrix step gives the
    same X_brg0 history as the classical Newmark recursion on the same reduced matrices (1e-9)."""
    r = _rotor(F_residual=0.0, t_blade_loss=0.0, F_unbalance=1000.0, unbalance_phase=0.0)
    red = r.reduced
    full = full_model()
    ux, uy = full.ports["unbalance"]
    pu = red["basis"][[ux, uy]].T
    n = 300
    ref = integrate(red["M"], red["C"], red["K"],
                    lambda t: pu @ np.array([1000.0 * math.cos(W_PT * t), 1000.0 * math.sin(W_PT * t)]),
                    np.zeros(red["n"]), np.zeros(red["n"]), H, n)
    b0 = full.ports["brg0"]
    ref_x = ref @ red["basis"][b0].T
    got = []
    for k in range(n):
        r.do_step(k * H, H)
        got.append(r.y["X_brg0"].copy())
    np.testing.assert_allclose(np.array(got), ref_x[1:], rtol=1e-9, atol=1e-9 * np.max(np.abs(ref_x)))


def test_unbalance_force_residual_then_blade_loss():
    """F_u is the residual unbalance before t_blade_loss and residual + blade loss after (step onset, phase 0),
    rotating forward at omega_pt: |F_u| and its angle W t checked against the definition."""
    r = _rotor(F_residual=100.0, F_unbalance=2850.0, t_blade_loss=0.001, unbalance_phase=0.0)
    for k in range(200):
        t = (k + 1) * H
        r.do_step(k * H, H)
        F = r.y["F_u"]
        amp = 100.0 + (2850.0 if t >= 0.001 - 1e-15 else 0.0)
        assert math.hypot(*F) == pytest.approx(amp, rel=1e-12)
        assert math.atan2(F[1], F[0]) == pytest.approx(math.atan2(math.sin(W_PT * t), math.cos(W_PT * t)), abs=1e-9)


def test_port_wiring_static_flexibility_matches_full_model():
    """Each input port pushes, and each output port reads, the DOFs it names: the reduced model's static
    flexibility from every input (F_brg0 ... F_rub5, unbalance) to every output (X_brg0 ... X_rub5),
    O K~^-1 B_in, equals the full model's K^-1 between the same DOFs (MTA is statically exact at the force
    DOFs), built independently from the port names of model.FullModel."""
    r = _rotor()
    red = r.reduced
    full = full_model()
    S = red["O"] @ np.linalg.solve(red["K"], red["B_in"])
    p = full.ports
    ins = np.concatenate([p["brg0"], p["brg5"], p["housing0"], p["housing0"], p["housing5"], p["housing5"],
                          p["rub0"], p["rub5"], p["unbalance"]])
    outs = np.concatenate([p["brg0"], p["brg5"], p["housing0"], p["housing5"], p["rub0"], p["rub5"]])
    Sf = np.linalg.inv(full.K)[np.ix_(outs, ins)]
    np.testing.assert_allclose(S, Sf, rtol=1e-6, atol=1e-7 * np.max(np.abs(Sf)))


def test_state_rollback_reproduces_the_run():
    """get_state / set_state (FMI get/setFMUstate): stepping again from a snapshot gives identical outputs."""
    r = _rotor(t_blade_loss=0.0)
    for k in range(50):
        r.do_step(k * H, H)
    snap = r.get_state()
    a = []
    for k in range(50, 80):
        r.do_step(k * H, H)
        a.append(r.y["X_rub0"].copy())
    r.set_state(snap)
    b = []
    for k in range(50, 80):
        r.do_step(k * H, H)
        b.append(r.y["X_rub0"].copy())
    np.testing.assert_array_equal(np.array(a), np.array(b))


def test_reduced_model_is_cached_per_process():
    a = reduced_model("", 30, W_PT, 15000 * 2 * math.pi / 60)
    b = reduced_model("", 30, W_PT, 15000 * 2 * math.pi / 60)
    assert a is b and a["n"] == 43  # 31 modes (the 30th and 31st are a degenerate pair, kept whole) + 12


@pytest.mark.parametrize("params,message", [
    ({"n_modes": 0}, "n_modes"),
    ({"F_unbalance": -1.0}, "F_unbalance"),
    ({"omega_pt": 0.0}, "omega_pt"),
    ({"newmark_beta": 0.0}, "Newmark"),
    ({"model_file": "/nonexistent/engine.toml"}, "not found"),
])
def test_bad_parameters(params, message):
    r = create("rotor.mta", "rotor", params)
    with pytest.raises(ContractError, match=message):
        r.setup(0.0)


def test_nan_parameter_rejected():
    with pytest.raises(ContractError, match="not finite"):
        create("rotor.mta", "rotor", {"F_residual": float("nan")})


def test_nan_input_names_the_port():
    r = _rotor()
    r.set_inputs({"F_rub5": [float("nan"), 0.0]})
    with pytest.raises(ContractError, match="F_rub5"):
        r.do_step(0.0, H)


def test_bad_model_file_content(tmp_path):
    """A model file with a negative shaft diameter is refused with a message naming the entry."""
    src = (Path(__file__).resolve().parents[2] / "components" / "rotor" / "data" / "engine.toml").read_text()
    bad = tmp_path / "bad.toml"
    assert "d_in_mm = [95, 95," in src
    bad.write_text(src.replace("d_in_mm = [95, 95,", "d_in_mm = [-95, 95,", 1))
    r = create("rotor.mta", "rotor", {"model_file": str(bad)})
    with pytest.raises(ContractError, match=r"d_in_mm\[0\]"):
        r.setup(0.0)


def test_calibrated_critical_speeds_of_the_shipped_model():
    """Calibration record of data/engine.toml (not a physics check): the lowest two forward synchronous critical
    speeds of the engine with #0/#5 as the co-simulated system linearised (contacts, journal bodies, O-rings) are
    the paper's 8500 and 10 200 rev/min within 3 % (section 4.1), and every critical speed is listed
    once as forward or backward, ascending."""
    out = critical_speeds(count=4)
    fw = out["forward_synchronous_rpm"]
    assert fw == sorted(fw) and out["backward_synchronous_rpm"] == sorted(out["backward_synchronous_rpm"])
    assert fw[0] == pytest.approx(8500, rel=0.03)
    assert fw[1] == pytest.approx(10200, rel=0.03)


def test_critical_speeds_command_json(capsys):
    assert main(["critical-speeds", "--json", "--count", "3"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert len(out["forward_synchronous_rpm"]) == 3 and "backward_synchronous_rpm" in out
    # which support model: the co-simulated system linearised, with its journal bodies and film temperature
    sm = out["support_model"]
    assert sm["kind"] == "coupled" and sm["oil_temperature_C"] == 30.0
    assert set(sm["bearings"]) == {"0", "5"} and sm["bearings"]["0"]["m_journal"] > 0.5


def test_critical_speeds_command_bad_count(capsys):
    assert main(["critical-speeds", "--count", "0"]) == 2
    assert "--count" in capsys.readouterr().err


def test_ports_follow_the_engine_files_attach():
    """Three bearings and one rub ring in [attach] (docs/examples/three_bearings): the component's ports are theirs
    (attach.py), its kernel's port containers plain tuples (numba's cache index then names no class of a layout),
    and a port-tuple class that an older cache index names unpickles to a stand-in instead of failing."""
    import pickle

    from rotorcosim.components import kernels

    engine = Path(__file__).resolve().parents[2] / "docs" / "examples" / "three_bearings" / "engine.toml"
    r = _rotor(model_file=str(engine))
    ins = [v.name for v in r.variables if v.causality == "input"]
    assert ins == ["F_brg1", "F_brg2", "F_brg3", "F_sfd_housing1", "F_sfd_housing2", "F_sfd_housing3",
                   "F_rub_housing1", "F_rub1"]
    assert {"X_brg3", "V_housing2", "X_rub1"} <= set(r.y) and "X_rub2" not in r.y
    u, y = r.kernel_io()
    assert type(u) is tuple and type(y) is tuple and len(u) == 8
    r.do_step(0.0, H)
    assert np.all(np.isfinite(r.y["X_brg2"]))
    stale = kernels.RotorInputs_0123456789
    assert pickle.loads(pickle.dumps(stale)) is stale and stale._fields == ()


def test_no_residual_unbalance_by_default_the_papers_engine_gives_87_N():
    """The rotor component's own default is no residual unbalance (a user's engine gets none unless its file gives
    one); the paper's engine file gives its 87 N (ISO 21940-11 G 2.5), which its scenarios bind."""
    import rotorcosim
    from rotorcosim.components.rotor.component import Rotor

    assert Rotor("rotor").p["F_residual"] == 0.0
    assert rotorcosim.load_scenario("blade_loss_2850").components["rotor"].parameters["F_residual"] == 87.0
