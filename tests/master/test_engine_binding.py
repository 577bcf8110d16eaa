"""One engine description drives every run (master/scenario/engine.py, components/rotor/engine_parts.py).

* the paper's engine, written with its parts ([bearing.ID], [damper.ID], [rubring.ID], [unbalance]), gives every
  component of the shipped scenarios the parameter values they ran with before the engine described its parts
  (data/paper_engine_parameters.json: ``rotorcosim parameters --json`` of the blade-loss and rundown scenarios
  from the component records ``bearing = 0 | 5``, ``damper = 0 | 5``; the run baselines themselves are not in the
  repository, the bit-identity of the runs is checked with bench/same_results.py);
* one quantity, one name: a damper's clearance moves the damper and its thermal network together, in ``set``, a
  sweep and a UQ (the recorded parameters of both components show the value);
* bad keys of the part tables are one-line errors naming the key.
"""
from __future__ import annotations

import csv
import json
import math
import re
from pathlib import Path

import pytest

import rotorcosim
from rotorcosim.components.rotor import engine_parts, model as fem
from rotorcosim.components.rotor.spool_inertia import polar_inertia
from rotorcosim.master.cli.program import main
from rotorcosim.master.scenario.compose import ScenarioError

TODAY = json.loads((Path(__file__).with_name("data") / "paper_engine_parameters.json").read_text())
#: the parameters that are not values of the machine, or new: the record selectors (now -1, "none": every value
#: comes from the engine), the rotor's model file ('' meant the paper's engine, now named), the journal's radius
#: and length the bearing now takes from its damper (its mass, m_journal, is compared), the spools' inertia
#: (0 meant "compute it from the paper's engine": compared with that computation below)
NEW = ("bearing", "damper", "model_file", "journal_radius", "journal_length", "inertia")


@pytest.mark.parametrize("name", sorted(TODAY))
def test_the_paper_engine_derives_every_parameter_of_today(name):
    sc = rotorcosim.load_scenario(name)
    rows = {f"{r['component']}.{r['name']}": r["value"] for r in sc.parameters()}
    today = TODAY[name]
    compared = 0
    for key, value in today.items():
        if key.rpartition(".")[2] in NEW:
            continue
        assert rows[key] == value, key       # exactly: the runs are bit-identical
        compared += 1
    assert compared > 100
    for spool in (k for k in sc.components if k.startswith("spool_")):
        assert rows[f"{spool}.inertia"] == polar_inertia("", sc.components[spool].parameters["spool"])
    if "speed_rpm" in sc.schedule:
        assert sc.schedule["speed_rpm"] == 16000.0
    assert sc.components["rotor"].parameters["model_file"] == str(fem.DEFAULT_FILE.resolve())


def test_one_name_moves_every_component_built_from_it():
    sc = rotorcosim.load_scenario("blade_loss_2850")
    a = sc.set({"damper0.clearance": 5.0e-4})
    assert a.components["damper0"].parameters["clearance"] == 5.0e-4
    assert a.components["thermal0"].parameters["damper_clearance"] == 5.0e-4
    assert a.components["damper5"].parameters["clearance"] == 6.35e-4       # the other damper is another quantity
    b = sc.set({"thermal0.damper_clearance": 5.5e-4})                       # either spelling names the quantity
    assert b.components["damper0"].parameters["clearance"] == 5.5e-4
    c = sc.set({"bearing0.bore": 0.05})                                     # the bearing's bore is the network's
    assert c.components["thermal0"].parameters["bore"] == 0.05
    d = sc.set({"damper0.radius": 0.09})                                    # the journal's mass follows its radius
    assert d.components["bearing0"].parameters["journal_radius"] == 0.09
    assert d.components["thermal0"].parameters["damper_radius"] == 0.09
    w = 12000.0 * math.pi / 30.0
    e = sc.set({"rotor.omega_pt": w})                                       # one speed: every part on the spool
    for comp in ("bearing0", "bearing5", "thermal0", "rubring5"):
        assert e.components[comp].parameters["omega"] == pytest.approx(w, rel=1e-15)
    assert e.schedule["speed_rpm"] == pytest.approx(12000.0, rel=1e-15)
    assert e.components["rotor"].parameters["omega_gg"] == sc.components["rotor"].parameters["omega_gg"]
    assert sc.components["damper0"].parameters["clearance"] == 6.35e-4     # the original is left as it was
    f = sc.set({"damper0.k_spring": 1.0e7, "rotor.F_unbalance": 5700.0})    # the existing spellings
    assert f.components["damper0"].parameters["k_spring"] == 1.0e7
    assert f.components["rotor"].parameters["F_unbalance"] == 5700.0


def _recorded(summary_file: Path) -> dict:
    p = json.loads(summary_file.read_text())["provenance"]["parameters"]
    return {"damper": p["damper0"]["parameters"]["clearance"], "thermal": p["thermal0"]["parameters"]["damper_clearance"]}


def test_a_sweep_over_a_damper_clearance_moves_its_thermal_network(tmp_path):
    out = tmp_path / "sweep"
    assert main(["sweep", "blade_loss_2850", "--set", "damper0.clearance=5.0e-4,6.0e-4", "--serial", "--quiet",
                 "--duration", "0.002", "--out", str(out)]) == 0
    got = sorted(tuple(_recorded(f).values()) for f in out.glob("*/summary.json"))
    assert got == [(5.0e-4, 5.0e-4), (6.0e-4, 6.0e-4)]


def test_a_uq_over_a_damper_clearance_moves_its_thermal_network(tmp_path):
    spec = tmp_path / "uq.toml"
    spec.write_text('[uq]\nscenario = "blade_loss_2850"\nduration = 0.002\nsamples = 2\nsampler = "lhs"\nseed = 1\n'
                    'results = ["bearings.0.drag_power_W"]\n'
                    '[[uq.parameter]]\nname = "damper0.clearance"\ndistribution = "uniform"\n'
                    'lower = 5.0e-4\nupper = 6.0e-4\n')
    out = tmp_path / "uq"
    assert main(["uq", str(spec), "--out", str(out), "--serial"]) == 0
    report = json.loads((out / "uq.json").read_text())
    assert report["failed"]["count"] == 0
    rows = list(csv.DictReader((out / "samples.csv").open()))
    assert len(rows) == 2
    for r in rows:
        sampled = float(r["damper0.clearance"])
        assert 5.0e-4 <= sampled <= 6.0e-4
        assert float(r["recorded damper0.clearance"]) == float(r["recorded thermal0.damper_clearance"]) == sampled


@pytest.mark.parametrize("edit, message", [
    ("clearance_mm = 0.635", "[damper.0] clearance_mm missing"),
    ("clearance_mm = -0.1", "[damper.0] clearance_mm: must be > 0 (mm), got -0.1"),
    ("clearance_mm = \"big\"", "[damper.0] clearance_mm: must be a finite number (mm), got 'big'"),
])
def test_a_bad_part_key_is_a_one_line_error_naming_it(tmp_path, capsys, edit, message):
    text = fem.DEFAULT_FILE.read_text()
    new = text.replace("clearance_mm = 0.635", edit if "missing" not in message else "", 1)
    if "missing" in message:
        assert new != text
    else:
        new = text.replace("clearance_mm = 0.635", edit, 1)
    engine = tmp_path / "engine.toml"
    engine.write_text(new)
    sc = tmp_path / "s.toml"
    sc.write_text(f'[scenario]\nextends = "blade_loss_2850"\nengine = "{engine}"\n')
    with pytest.raises(ScenarioError) as err:
        rotorcosim.load_scenario(sc)
    assert message in str(err.value)
    assert main(["run", str(sc), "--duration", "0.001", "--out", str(tmp_path / "o")]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and message in lines[0] and "Traceback" not in lines[0]
    assert not (tmp_path / "o").exists()


def test_check_engine_names_an_unknown_or_misplaced_part_key(tmp_path):
    text = fem.DEFAULT_FILE.read_text().replace("clearance_mm = 0.635", "clerance_mm = 0.635", 1)
    text += "\n[bearing.7]\nballs = 9\n"
    data = __import__("tomllib").loads(text)
    lines = engine_parts.problems(data)
    assert any(line.startswith("[damper.0] clerance_mm: unknown key (known: radius_mm") for line in lines)
    assert "[bearing.7]: [attach] has no bearing7 (the part sits at that attachment)" in lines


def test_an_engine_nothing_takes_a_value_from_is_refused(tmp_path, capsys):
    """[scenario] engine = "engine.toml" in a scenario whose components take nothing from it (it extends
    jeffcott_rundown, which runs its own rotor file) was accepted: the Jeffcott rotor ran, and summary.json named
    the engine file as the run's. Now one line, exit 2, no folder."""
    (tmp_path / "engine.toml").write_text((fem.DEFAULT_FILE).read_text())
    s = tmp_path / "s.toml"
    s.write_text('[scenario]\nextends = "jeffcott_rundown"\nname = "mine"\nengine = "engine.toml"\n')
    out = tmp_path / "o"
    assert main(["run", str(s), "--duration", "0.01", "--quiet", "--no-figures", "--out", str(out)]) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert err == [f"rotorcosim run: error: {s}: [scenario] engine = '{tmp_path / 'engine.toml'}', but no component "
                   "takes a value from it (a parameter written \"engine:NAME\"): the run would not be of that "
                   "engine"], err
    assert not out.exists()


@pytest.mark.parametrize("part, value, message", [
    ("bearing0", 1000.0, "bearing0.omega = 1000 rad/s is not the speed of what it is linked to (rotor.X_brg0 -> "
                         "bearing0.X_inner): rotor.omega_pt = 1675.52 rad/s"),
    ("rubring5", 1000.0, "rubring5.omega = 1000 rad/s is not the speed of what it is linked to (rotor.X_rub5"),
    ("thermal5", 1000.0, "thermal5.omega = 1000 rad/s is not the speed of what it is linked to (bearing5.P_drag -> "
                         "thermal5.P_drag): bearing5.omega = 1675.52 rad/s"),
])
def test_a_part_turning_at_another_speed_than_its_spool_is_refused(tmp_path, part, value, message):
    """A constant-speed part given its own omega (a plain value replaces the engine's binding) while its rotor
    node turns at the spool's speed ran without a word, the part at one speed and the rotor at another."""
    from rotorcosim import scenarios
    from rotorcosim.master.scenario.build import build_system

    src = tmp_path / "s.toml"
    src.write_text(f'[scenario]\nextends = "{scenarios.path("blade_loss_2850").as_posix()}"\n'
                   f'name = "s"\n[components.{part}]\nparameters = {{ omega = {value} }}\n')
    with pytest.raises(ScenarioError, match=re.escape(message)):
        build_system(rotorcosim.load_scenario(src))
    # by its name the speed moves the spool and every part on it together: no contradiction
    for comp in build_system(rotorcosim.load_scenario("blade_loss_2850").set({f"{part}.omega": value})).components.values():
        comp.terminate()
