"""Plug-ins without packaging (docs/how-to/plugins.md): the worked example runs, and bad plug-ins get clear errors."""
from pathlib import Path

import numpy as np
import pytest

import rotorcosim
from rotorcosim.components.contract import ContractError
from rotorcosim.master.cli import main

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "linear_damper" / "linear_damper.toml"
K, C = 5.254e6, 2.91e3  # the example's parameters


def test_worked_example_composes():
    sc = rotorcosim.load_scenario(EXAMPLE)
    d = sc.components["damper0"]
    assert d.implementation == "linear_damper:LinearDamper" and d.parameters == {"k": K, "c": C}
    assert d.folder == str(EXAMPLE.parent)
    assert "damper0.T_oil" not in [c.dst for c in sc.connections] and len(sc.connections) == 45
    assert sc.components["damper5"].implementation == "damper.fast"  # the rest is the shipped scenario


def test_worked_example_runs_and_follows_the_linear_law(tmp_path):
    """2 ms of the blade-loss system with the plug-in: its recorded force is the linear law of the recorded
    journal and housing motion, sample by sample; the command line writes the usual files."""
    refs = ["damper0.F_journal", "damper0.P_film", "bearing0.X_journal", "bearing0.V_journal",
            "rotor.X_housing0", "rotor.V_housing0"]
    assert main(["run", str(EXAMPLE), "--duration", "0.002", "--quiet", "--no-figures", "--out", str(tmp_path),
                 "--record", ",".join(refs)]) == 0
    import h5py

    with h5py.File(tmp_path / "timeseries.h5") as f:
        d = {r: f[r][:] for r in refs}
    dx = d["bearing0.X_journal"] - d["rotor.X_housing0"]
    dv = d["bearing0.V_journal"] - d["rotor.V_housing0"]
    F = d["damper0.F_journal"]
    assert np.max(np.abs(F)) > 1.0  # the journal moves: the check is not on zeros
    assert np.allclose(F, -K * dx - C * dv, rtol=1e-12, atol=1e-9)
    assert np.allclose(d["damper0.P_film"][:, 0], C * np.sum(dv * dv, axis=1), rtol=1e-12, atol=1e-15)


def test_plugin_module_missing_names_the_file_and_folder(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text('[scenario]\nextends = "blade_loss_2850"\n[components.damper0]\n'
                 'implementation = "no_such_plugin:Damper"\n')
    with pytest.raises(ContractError, match=rf"{p}:\d+: \[components.damper0\] implementation: plug-in "
                                            rf"'no_such_plugin:Damper': no module 'no_such_plugin' in the scenario's "
                                            rf"folder {tmp_path}"):
        rotorcosim.load_scenario(p)


def test_plugin_class_that_breaks_the_contract(tmp_path):
    (tmp_path / "bad_plugin.py").write_text("class NotAComponent:\n    pass\n")
    p = tmp_path / "s.toml"
    p.write_text('[scenario]\nextends = "blade_loss_2850"\n[components.damper0]\n'
                 'implementation = "bad_plugin:NotAComponent"\n')
    with pytest.raises(ContractError, match="does not follow the component contract"):
        rotorcosim.load_scenario(p)


def test_inherited_parameter_not_removed_is_named(tmp_path):
    """A plug-in in a templated component's place drops the values the component took from the engine (the
    plug-in declares none of them); a plain parameter a file gave the component before is named with its file."""
    (tmp_path / "linear_damper.py").write_text((EXAMPLE.parent / "linear_damper.py").read_text())
    p = tmp_path / "s.toml"
    p.write_text('[scenario]\nextends = "blade_loss_2850"\n[components.damper0]\n'
                 'implementation = "linear_damper:LinearDamper"\n')
    assert rotorcosim.load_scenario(p).components["damper0"].parameters == {}
    base = tmp_path / "b.toml"
    base.write_text('[scenario]\nextends = "blade_loss_2850"\n[components.damper0]\nparameters = { n_theta = 64 }\n')
    p.write_text('[scenario]\nextends = "b.toml"\n[components.damper0]\n'
                 'implementation = "linear_damper:LinearDamper"\n')
    with pytest.raises(ContractError, match=r"b.toml:\d+: \[components.damper0\] parameters.n_theta: "
                                            r"linear_damper:LinearDamper has no parameter 'n_theta'"):
        rotorcosim.load_scenario(p)