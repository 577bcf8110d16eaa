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
                                            rf"'no_such_plugin:Damper': no module 'no_such_plugin' in the folder "
                                            rf"{tmp_path}"):
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

def test_a_swapped_plugin_is_imported_from_the_working_folder(tmp_path, monkeypatch, capsys):
    """``--swap damper0=module:Class`` finds the module in the folder the command is typed in, as it finds a
    swapped FMU there, also when that folder is not on ``sys.path`` (the installed ``rotorcosim`` command: only
    ``python -m`` puts it there); the shipped template damper0 came from has no say. The values damper0 took from
    the engine (radius, clearance...) that the plug-in does not declare are dropped, as for a plug-in a scenario
    file puts in its place."""
    import sys

    # the worked example, with the oil temperature input the shipped template connects (a swap keeps the
    # component's connections; a scenario file drops one with remove_connections)
    text = EXAMPLE.with_name("linear_damper.py").read_text()
    anchor = '        Variable("F_journal", "output"'
    assert anchor in text
    (tmp_path / "my_linear_damper.py").write_text(text.replace(
        anchor, '        Variable("T_oil", "input", 1, "K", "oil temperature (not used)", start=303.15),\n' + anchor, 1))
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", [p for p in sys.path if p not in ("", ".", str(tmp_path))])
    monkeypatch.delitem(sys.modules, "my_linear_damper", raising=False)
    out = tmp_path / "o"
    rc = main(["run", "--swap", "damper0=my_linear_damper:LinearDamper", "--set", "damper0.k=5.254e6",
               "--duration", "0.001", "--quiet", "--no-figures", "--out", str(out)])
    err = capsys.readouterr().err
    assert rc == 0, err
    assert (out / "summary.json").exists()
    # a module that is not there is named with the folder looked in
    rc = main(["run", "--swap", "damper0=no_such_module:Damper", "--duration", "0.001", "--quiet",
               "--no-figures", "--out", str(tmp_path / "o2")])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and len(err) == 1 and f"no module 'no_such_module' in the folder {tmp_path} nor" in err[0], err
    assert not (tmp_path / "o2").exists()


@pytest.mark.parametrize("make", ["file", "folder"])
def test_a_swap_to_a_file_that_is_no_fmu_says_so(tmp_path, capsys, make):
    """It was listed against the registry's names ("unknown component implementation ..."), as if a typo."""
    p = tmp_path / ("damper.txt" if make == "file" else "damper")
    p.write_text("x") if make == "file" else p.mkdir()
    rc = main(["run", "--swap", f"damper0={p}", "--duration", "0.001", "--quiet", "--no-figures",
               "--out", str(tmp_path / "o")])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and err == [f"rotorcosim run: error: swap damper0: {p} is a {make}, not an FMU (a file whose name "
                               "ends in .fmu), a registry name or module:Class"], err
    assert not (tmp_path / "o").exists()


#: the worked example's damper, broken in the ways a plug-in's author may break it
BROKEN = '''
import numpy as np
from linear_damper import LinearDamper


class Init(LinearDamper):
    def __init__(self, name, parameters=None):
        raise RuntimeError("boom in init")


class Setup(LinearDamper):
    def setup(self, t0=0.0):
        raise KeyError("k_missing")


class ListAtSetup(LinearDamper):
    def setup(self, t0=0.0):
        super().setup(t0)
        self.y["F_journal"] = [0.0, 0.0]


class ThreeValues(LinearDamper):
    def do_step(self, t, h):
        super().do_step(t, h)
        self.y["F_journal"] = np.zeros(3)
'''


@pytest.mark.parametrize("cls, rc, line", [
    # were: "unexpected RuntimeError: boom in init (... it may be a bug)", exit 1
    ("Init", 2, "rotorcosim run: error: {s}: [components.damper0]: plug-in 'broken:Init' could not be made: "
                "RuntimeError: boom in init"),
    # was: "error: 'k_missing'", naming nothing
    ("Setup", 2, "rotorcosim run: error: damper0 could not be set up with its parameters: KeyError: 'k_missing'"),
    # was: bearing0's numba typing error over 23 lines
    ("ListAtSetup", 2, "rotorcosim run: error: after its set-up: damper0.F_journal must be a numpy array of 2 "
                       "value(s), got a list ([0.0, 0.0])"),
    # was: "error: could not broadcast input array from shape (3,) into shape (2,)", exit 2
    ("ThreeValues", 1, "rotorcosim run: a component failed: damper0 failed in do_step at t = 0 s: "
                       "damper0.F_journal must be a numpy array of 2 value(s), got 3 value(s); what was recorded is "
                       "in {o} (summary.json has the error)"),
])
def test_a_broken_plugin_is_named_in_one_line(tmp_path, capsys, cls, rc, line):
    (tmp_path / "linear_damper.py").write_text((EXAMPLE.parent / "linear_damper.py").read_text())
    (tmp_path / "broken.py").write_text(BROKEN)
    s = tmp_path / "s.toml"
    s.write_text(EXAMPLE.read_text().replace("linear_damper:LinearDamper", f"broken:{cls}"))
    out = tmp_path / "o"
    assert main(["run", str(s), "--duration", "0.02", "--quiet", "--no-figures", "--out", str(out)]) == rc
    err = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert err == [line.format(s=s, o=out)], err
    assert out.exists() == (rc == 1)


def test_damper_force_of_a_plugin_damper_is_refused_by_name(capsys):
    """damper-force --scenario with damper0 a plug-in gave the plug-in's parameters to the project's damper model:
    'damper0: no variable 'k' (known: ...)'. Now one line naming the plug-in; damper5 (native) still evaluates."""
    argv = ["damper-force", "--scenario", str(EXAMPLE), "--position", "2e-4", "0", "--velocity", "0", "0.05",
            "--temperature", "40", "--damper"]
    assert main([*argv, "0"]) == 2
    err = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert err == [f"rotorcosim damper-force: error: --scenario {EXAMPLE}: damper0 is linear_damper:LinearDamper, not "
                   "one of rotorcosim's damper models (damper.*), which this command evaluates"], err
    assert main([*argv, "5"]) == 0


@pytest.mark.parametrize("command", [["export-fmus", "--component", "damper0", "--out", "{t}/fmus"],
                                     ["export-ssp", "--out", "{t}/s.ssp"]])
def test_exporting_a_plugin_whose_constructor_raises_names_it(tmp_path, capsys, command):
    """export-fmus / export-ssp of a scenario whose plug-in's constructor raises: 'unexpected RuntimeError: boom in
    init (... it may be a bug)', exit 1; now the export's own list of what cannot be exported names it, exit 2."""
    (tmp_path / "linear_damper.py").write_text((EXAMPLE.parent / "linear_damper.py").read_text())
    (tmp_path / "broken.py").write_text(BROKEN)
    s = tmp_path / "s.toml"
    s.write_text(EXAMPLE.read_text().replace("linear_damper:LinearDamper", "broken:Init"))
    assert main([command[0], str(s), *[a.format(t=tmp_path) for a in command[1:]]]) == 2
    err = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert err == [f"rotorcosim {command[0]}: error: scenario 'linear_damper_2850': cannot export component(s): "
                   "damper0 (broken:Init: RuntimeError: boom in init)"], err
    assert not (tmp_path / "fmus").exists() and not (tmp_path / "s.ssp").exists()
