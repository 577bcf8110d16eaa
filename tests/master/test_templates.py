"""Scenario templates (master/scenario/templates.py): a bearing set and a rub ring written once, instantiated per
id. The reference for the paper's system is the connection list blade_loss.toml carried before templates,
written out here by hand."""
from __future__ import annotations

from pathlib import Path

import pytest

import rotorcosim
from rotorcosim.master.cli import main
from rotorcosim.master.scenario.compose import ScenarioError

ROOT = Path(__file__).resolve().parents[2]

#: one bearing's 23 connections of the paper's system (the 46 of blade_loss.toml before templates, for id k)
PAPER_SET = """
rotor.X_brg{k} bearing{k}.X_inner
rotor.V_brg{k} bearing{k}.V_inner
bearing{k}.F_rotor rotor.F_brg{k} linear-end
bearing{k}.X_journal damper{k}.X_journal
bearing{k}.V_journal damper{k}.V_journal
rotor.X_housing{k} damper{k}.X_housing
rotor.V_housing{k} damper{k}.V_housing
damper{k}.F_journal bearing{k}.F_journal
damper{k}.F_housing rotor.F_sfd_housing{k}
damper{k}.K_film bearing{k}.K_journal
damper{k}.C_film bearing{k}.C_journal
rotor.X_rub{k} rubring{k}.X_rotor
rotor.V_rub{k} rubring{k}.V_rotor
rotor.X_housing{k} rubring{k}.X_housing
rotor.V_housing{k} rubring{k}.V_housing
rubring{k}.F_rotor rotor.F_rub{k}
rubring{k}.F_housing rotor.F_rub_housing{k}
bearing{k}.P_drag thermal{k}.P_drag
damper{k}.P_film thermal{k}.P_sfd
rubring{k}.P_rub thermal{k}.P_rub
thermal{k}.eps bearing{k}.eps
thermal{k}.T_oil bearing{k}.T_oil
thermal{k}.T_sfd_oil damper{k}.T_oil
"""


def _expected(ids) -> set[tuple]:
    out = set()
    for k in ids:
        for line in PAPER_SET.strip().splitlines():
            src, dst, *ex = line.format(k=k).split()
            out.add((src, dst, ex[0] if ex else "hold"))
    return out


def _scenario(tmp_path, text: str) -> Path:
    p = tmp_path / "s.toml"
    p.write_text(text)
    return p


def test_paper_system_expands_to_its_46_connections():
    sc = rotorcosim.load_scenario("blade_loss")
    got = [(c.src, c.dst, c.extrapolation) for c in sc.connections]
    assert len(got) == 46 and set(got) == _expected(("0", "5"))
    assert list(sc.components) == ["rotor", "bearing0", "bearing5", "damper0", "damper5", "thermal0", "thermal5",
                                   "rubring0", "rubring5"]
    for k in (0, 5):   # every value from the engine's records of that id
        assert sc.components[f"bearing{k}"].parameters["balls"] == (21 if k == 0 else 27)
        assert sc.components[f"bearing{k}"].param_origins["balls"].endswith(f"engine.toml [bearing.{k}] balls")
        assert sc.components[f"damper{k}"].parameters["radius"] == (0.08 if k == 0 else 0.1)
        assert sc.components[f"thermal{k}"].parameters["damper_radius"] == sc.components[f"damper{k}"].parameters[
            "radius"] and sc.components[f"thermal{k}"].step == 1e-3
    assert sc.algorithm["order"] == ["rotor", "bearing0", "bearing5", "damper0", "damper5", "rubring0", "rubring5",
                                     "thermal0", "thermal5"]
    assert sc.outputs["record"][:6] == ["rotor.X_brg0", "rotor.X_brg5", "rotor.X_housing0", "rotor.X_housing5",
                                        "rotor.X_rub0", "rotor.X_rub5"]


def test_a_scenario_that_extends_it_with_other_ids():
    """The three-bearing example: its ids replace the base's (no bearing0/5 left), its own tables change the
    instantiated components, and a bearing without a rub ring has no rub connections."""
    sc = rotorcosim.load_scenario(ROOT / "docs/examples/three_bearings/blade_loss.toml")
    names = list(sc.components)
    assert "bearing0" not in names and "rubring5" not in names
    assert [n for n in names if n.startswith("bearing")] == ["bearing1", "bearing2", "bearing3"]
    assert sc.components["bearing3"].parameters["preload"] == 1100.0                 # engine.toml's [bearing.3]
    assert sc.components["bearing3"].parameters["bore"] == 0.0838
    assert sc.components["bearing3"].origin.endswith("templates/bearing.toml")
    assert len(sc.connections) == 3 * 16 + 7
    assert not any("rubring2" in c.src or "rubring2" in c.dst for c in sc.connections)
    assert "rubring1" in sc.algorithm["order"] and "rubring2" not in sc.algorithm["order"]


def test_template_components_can_be_changed_like_inherited_ones(tmp_path):
    """remove_parameters and remove_connections reach the instantiated components (the plug-in example)."""
    sc = rotorcosim.load_scenario(ROOT / "docs/examples/linear_damper/linear_damper.toml")
    assert set(sc.components["damper0"].parameters) == {"k", "c"}    # the film damper's engine values dropped
    assert not any(c.dst == "damper0.T_oil" for c in sc.connections) and len(sc.connections) == 45


@pytest.mark.parametrize("text, message", [
    ('[templates]\nbearings = ["0"]\n', "'bearings' is not a template (shipped: bearing, fuse, mount, rubring)"),
    ('[templates]\nbearing = ["0", "a-b"]\n', "bearing must be a list of ids"),
    ('[templates]\nbearing = ["0", "0"]\n', "lists an id twice"),
    ('[templates]\nbearing = "0"\n', "bearing must be a list of ids"),
    ('[templates]\nbearing = ["0"]\n[outputs]\nrecord = ["bearing{bering}.P_drag"]\n',
     "names template {bering}, which [templates] does not instantiate (it has: bearing)"),
])
def test_bad_templates_are_one_line_errors(tmp_path, capsys, text, message):
    p = _scenario(tmp_path, text)
    with pytest.raises(ScenarioError) as err:
        rotorcosim.load_scenario(p)
    assert message in str(err.value) and str(p) in str(err.value)
    assert main(["run", str(p), "--duration", "0.001", "--out", str(tmp_path / "o")]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and message in lines[0] and "Traceback" not in lines[0]


def test_a_template_of_its_own_file(tmp_path):
    """A scenario with [templates] and no extends: the templates are its base."""
    p = _scenario(tmp_path, '[templates]\nbearing = ["7"]\n[components.rotor]\nimplementation = "rotor.mta"\n'
                            '[components.bearing7]\nparameters = { bearing = 5 }\n')
    from rotorcosim.master.scenario.compose import compose

    data, origins = compose(p)
    assert list(data["components"]) == ["rotor", "bearing7", "damper7", "thermal7"]
    assert data["components"]["bearing7"]["parameters"]["bearing"] == 5
    assert data["components"]["damper7"]["parameters"]["radius"] == "engine:damper.7.radius"   # "{id}" -> 7
    assert len(data["connections"]) == 16 and "templates" not in data
    assert origins.parameter("bearing7", "bearing") == str(p.resolve())
