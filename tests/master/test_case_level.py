"""The level a case sweeps is the case's declared parameter (master/case.py ``Level``): the blade-loss case's
``--unbalance`` [N] in ``[results] unbalance_parameter``, the generic ``--level`` in ``[results] level_parameter``;
the case's own ``[results]`` keys are checked when a scenario is loaded."""
from __future__ import annotations

import pytest

import rotorcosim
from rotorcosim.master import case


def test_the_blade_loss_case_declares_its_level():
    level = case.level_of("blade_loss")
    assert (level.results_key, level.option, level.unit, level.summary_key, level.sweep_key, level.folder_prefix) \
        == ("unbalance_parameter", "--unbalance", "N", "unbalance_N", "levels_N", "F_")
    assert case.level_of("rundown") == level          # the rundown of the blade-loss engine: the same level
    assert case.level_of(None) is case.GENERIC and case.GENERIC.option == "--level"
    assert set(case.level_options()) == {"--level", "--unbalance"}
    assert case.schedule_aliases() == {"paper": "scenario"} and case.default_scenario() == "blade_loss"


def test_the_level_is_set_and_recorded_by_its_case_name():
    sc = rotorcosim.load_scenario("blade_loss")
    case.apply_level(sc, 5700.0)
    assert sc.components["rotor"].parameters["F_unbalance"] == 5700.0
    assert sc.edits[-1] == {"unbalance": 5700.0, "parameter": "rotor.F_unbalance", "origin": "--unbalance"}
    toy = rotorcosim.load_scenario("toy_thermomechanical")
    case.apply_level(toy, 12.0)
    assert toy.components["osc"].parameters["F0"] == 12.0 and toy.edits[-1]["level"] == 12.0
    with pytest.raises(ValueError, match=r"^--unbalance must be a finite blade-loss unbalance force >= 0 N, got -1"):
        case.apply_level(rotorcosim.load_scenario("blade_loss"), -1.0)
    with pytest.raises(ValueError, match=r"--level and --set osc.F0=\.\.\. both give the level"):
        case.apply_level(rotorcosim.load_scenario("toy_thermomechanical"), 1.0, ["osc.F0"])


def test_a_cases_results_keys_are_checked_at_load(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('[scenario]\nextends = "blade_loss_2850"\n[results]\nunbalance_paramter = "rotor.F_unbalance"\n')
    with pytest.raises(ValueError, match=r"\[results\] unbalance_paramter: unknown key \(did you mean "
                                         r"'unbalance_parameter'\?\) \(case 'blade_loss'\)"):
        rotorcosim.load_scenario(f)
    f.write_text('[scenario]\nextends = "blade_loss_2850"\n[results]\nunbalance_parameter = "nowhere.F"\n')
    with pytest.raises(ValueError, match=r"\[results\] unbalance_parameter: 'nowhere.F': no component 'nowhere'"):
        rotorcosim.load_scenario(f)
    # a misspelt parameter was accepted: the run reported no level (unbalance_N null)
    f.write_text('[scenario]\nextends = "blade_loss_2850"\n[results]\nunbalance_parameter = "rotor.F_unbalanc"\n')
    with pytest.raises(ValueError, match=r"\[results\] unbalance_parameter: 'rotor.F_unbalanc': component 'rotor' "
                                         r"has no parameter 'F_unbalanc' \(did you mean 'F_unbalance'\?\)$"):
        rotorcosim.load_scenario(f)
    # the generic level of a scenario without a case, the same (a sweep ran every case into its failure)
    f.write_text('[scenario]\nextends = "toy_thermomechanical"\n[results]\nlevel_parameter = "osc.F0x"\n')
    with pytest.raises(ValueError, match=r"\[results\] level_parameter: 'osc.F0x': component 'osc' has no parameter "
                                         r"'F0x' \(did you mean 'F0'\?\)$"):
        rotorcosim.load_scenario(f)
    # without a case, the schema is strict: a case's key is unknown there
    f.write_text('[scenario]\nextends = "toy_thermomechanical"\n[results]\nspools = ["osc"]\n')
    with pytest.raises(Exception, match=r"\[results\] spools: unknown key"):
        rotorcosim.load_scenario(f)
