"""Scenario composition (master/scenario/compose.py): replace, remove, add, and errors that name the file."""
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.master.scenario.compose import compose
from rotorcosim.master.scenario.build import ScenarioError, build_system, load_scenario

BASE = """
[scenario]
name = "base"
[components.osc]
implementation = "testing.damped_oscillator"
parameters = { F0 = 100.0, c0 = 0.5 }
[components.node]
fmu = "node.fmu"
parameters = { C = 10.0, R = 1.0 }
[[connections]]
from = "osc.P"
to = "node.P"
[[connections]]
from = "node.T"
to = "osc.T"
[schedule]
kind = "monolithic"
duration = 0.01
step = 1e-3
"""


def files(tmp_path, child: str, base: str = BASE):
    (tmp_path / "base.toml").write_text(base)
    p = tmp_path / "child.toml"
    p.write_text('[scenario]\nextends = "base.toml"\n' + child)
    return p


def test_implementation_replaces_an_inherited_fmu_and_back(tmp_path):
    p = files(tmp_path, '[components.node]\nimplementation = "testing.thermal_node"\n')
    sc = load_scenario(p)
    assert sc.components["node"].implementation == "testing.thermal_node" and sc.components["node"].fmu is None
    assert sc.components["node"].parameters == {"C": 10.0, "R": 1.0}  # parameters still merge
    build_system(sc)  # runs without the FMU the base named
    q = tmp_path / "grandchild.toml"
    q.write_text('[scenario]\nextends = "child.toml"\n[components.osc]\nfmu = "osc.fmu"\n')
    sc = load_scenario(q)
    assert sc.components["osc"].fmu == str(tmp_path / "osc.fmu") and sc.components["osc"].implementation is None


def test_a_parameter_can_be_removed(tmp_path):
    p = files(tmp_path, '[components.osc]\nremove_parameters = ["c0"]\nparameters = { F0 = 5.0 }\n')
    assert load_scenario(p).components["osc"].parameters == {"F0": 5.0}


def test_removing_a_parameter_the_base_does_not_set_is_an_error(tmp_path):
    p = files(tmp_path, '[components.osc]\nremove_parameters = ["k"]\n')
    with pytest.raises(ScenarioError, match=r"child.toml: \[components.osc\] remove_parameters: 'k' is not an "
                                            r"inherited parameter \(inherited: \['F0', 'c0'\]\)"):
        load_scenario(p)


def test_connections_are_added_not_replaced(tmp_path):
    p = files(tmp_path, '[components.node2]\nimplementation = "testing.thermal_node"\n'
                        '[[connections]]\nfrom = "osc.P"\nto = "node2.P"\n')
    sc = load_scenario(p)
    assert [(c.src, c.dst) for c in sc.connections] == [("osc.P", "node.P"), ("node.T", "osc.T"), ("osc.P", "node2.P")]
    assert sc.connections[0].origin.endswith("base.toml") and sc.connections[2].origin.endswith("child.toml")


def test_a_connection_into_a_driven_input_replaces_the_inherited_one(tmp_path):
    p = files(tmp_path, '[[connections]]\nfrom = "osc.P"\nto = "node.P"\naverage = "rms"\n')
    sc = load_scenario(p)
    assert len(sc.connections) == 2 and sc.connections[0].average == "rms"


@pytest.mark.parametrize("name", ["osc.T", "node.T -> osc.T", "node.T->osc.T"])
def test_connections_are_removed_by_name(tmp_path, name):
    p = files(tmp_path, f'remove_connections = ["{name}"]\n[inputs]\n"osc.T" = 300.0\n')
    sc = load_scenario(p)
    assert [(c.src, c.dst) for c in sc.connections] == [("osc.P", "node.P")]
    assert sc.inputs == {"osc.T": [300.0]}


def test_removing_an_unknown_connection_is_an_error(tmp_path):
    p = files(tmp_path, 'remove_connections = ["osc.X"]\n')
    with pytest.raises(ScenarioError, match=r"child.toml: remove_connections: no inherited connection 'osc.X'"):
        load_scenario(p)


def test_unknown_port_after_composition_names_the_file(tmp_path):
    p = files(tmp_path, '[components.node]\nimplementation = "testing.thermal_node"\n'
                        '[[connections]]\nfrom = "osc.Q"\nto = "node.P"\n')
    with pytest.raises(ContractError, match=r"osc.Q: component 'osc' .* has no output 'Q' .*\(connection from "
                                            r".*child.toml\)"):
        build_system(load_scenario(p))


def test_unconnected_input_after_a_removal_names_the_files(tmp_path):
    p = tmp_path / "child.toml"
    (tmp_path / "base.toml").write_text(BASE)
    p.write_text('[scenario]\nextends = "base.toml"\nremove_connections = ["osc.T"]\n'
                 '[components.node]\nimplementation = "testing.thermal_node"\n')
    with pytest.raises(ContractError, match=r"inputs left unconnected .*: osc.T \(components from .*base.toml\)"):
        build_system(load_scenario(p))


def test_a_bad_parameter_names_the_file_that_set_it(tmp_path):
    p = files(tmp_path, '[components.node]\nimplementation = "testing.thermal_node"\n'
                        '[components.osc]\nparameters = { F00 = 1.0 }\n')
    with pytest.raises(ContractError, match=r"child.toml:6: \[components.osc\] parameters.F00: "
                                            r"testing.damped_oscillator has no parameter 'F00'"):
        load_scenario(p)


def test_an_unknown_implementation_names_the_file_that_chose_it(tmp_path):
    p = files(tmp_path, '[components.node]\nimplementation = "testing.nope"\n')
    with pytest.raises(ContractError, match=r"child.toml:4: \[components.node\] implementation: unknown component "
                                            r"implementation 'testing.nope'"):
        load_scenario(p)


def test_composition_keys_do_not_reach_the_composed_dict(tmp_path):
    p = files(tmp_path, 'remove_connections = ["osc.T"]\n[components.osc]\nremove_parameters = ["c0"]\n')
    data, origins = compose(p)
    assert "extends" not in data["scenario"] and "remove_connections" not in data["scenario"]
    assert "remove_parameters" not in data["components"]["osc"]
    assert origins.parameter("osc", "F0").endswith("base.toml")


def test_directives_without_extends_are_errors(tmp_path):
    p = tmp_path / "x.toml"
    p.write_text(BASE.replace('name = "base"', 'name = "base"\nremove_connections = ["osc.T"]'))
    with pytest.raises(ScenarioError, match="remove_connections needs 'extends'"):
        load_scenario(p)


def test_extends_loop_is_an_error(tmp_path):
    (tmp_path / "a.toml").write_text('[scenario]\nextends = "b.toml"\n')
    (tmp_path / "b.toml").write_text('[scenario]\nextends = "a.toml"\n')
    with pytest.raises(ScenarioError, match="loops back on itself"):
        load_scenario(tmp_path / "a.toml")


def test_shipped_levels_compose_as_before():
    from rotorcosim import scenarios

    sc = load_scenario(scenarios.path("blade_loss_14252"))
    assert sc.components["rotor"].parameters["F_unbalance"] == 14252.0
    assert len(sc.connections) == 46 and sc.components["rotor"].param_origins["F_unbalance"].endswith("14252.toml")
    # the bearing sets come from the template blade_loss.toml instantiates ([templates] bearing = ["0", "5"])
    assert sc.components["damper0"].origin.endswith("templates/bearing.toml")


def test_a_child_s_cycle_replaces_the_base_s_whole(tmp_path):
    """[schedule] cycle is one choice: a child giving a period drops the base's signal, unit and angle (merged key
    by key they made "give exactly one of period or signal" of a file that gave only a period); other schedule
    keys still merge."""
    base = tmp_path / "base.toml"
    base.write_text('[scenario]\nextends = "blade_loss_rundown"\nname = "b"\n')
    child = tmp_path / "child.toml"
    child.write_text(f'[scenario]\nextends = "{base.name}"\nname = "c"\n\n[schedule]\ncycle = {{ period = 0.00375 }}\n')
    data, _ = compose(child)
    base_data, _ = compose(base)
    assert data["schedule"]["cycle"] == {"period": 0.00375}
    assert "signal" in base_data["schedule"]["cycle"]
    assert {k: v for k, v in data["schedule"].items() if k != "cycle"} == \
        {k: v for k, v in base_data["schedule"].items() if k != "cycle"}
    load_scenario(child)
