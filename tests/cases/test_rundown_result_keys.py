"""A rundown's [results] keys that name parts of the run (cases/rundown/results.py ``check``, before the run
starts): ``fatigue_loads`` entries that are no output of the run and an ``airframe`` that is no airframe component
are one-line errors naming the key; the shipped diversion's keys pass."""
from __future__ import annotations

import copy
from types import SimpleNamespace

import pytest

from rotorcosim import scenarios
from rotorcosim.cases.rundown import results
from rotorcosim.master.scenario.build import load_scenario

#: the outputs of the diversion's components that the check reads (a stand-in for the built simulation)
OUTPUTS = {"spool_pt": ["Omega"], "spool_gg": ["Omega"], "rotor": ["X_brg0", "F_u"],
           "airframe": ["F_aft", "F_fwd", "F_engine_aft", "a_flight_deck"]}


@pytest.fixture(scope="module")
def diversion():
    return load_scenario(scenarios.path("blade_loss_diversion"))


def _with(sc, **keys):
    sc = copy.copy(sc)
    sc.extra = copy.deepcopy(sc.extra)
    sc.extra["results"].update(keys)
    return sc


def _sim():
    comps = {n: SimpleNamespace(y={p: 0.0 for p in ports}) for n, ports in OUTPUTS.items()}
    return SimpleNamespace(system=SimpleNamespace(components=comps))


def test_the_shipped_keys_pass(diversion):
    results.check(diversion, _sim())
    results.check(_with(diversion, airframe="airframe"), _sim())


@pytest.mark.parametrize("keys, message", [
    ({"fatigue_loads": ["airframe.F_nope"]},
     "[results] fatigue_loads: 'airframe.F_nope': component 'airframe' has no output 'F_nope' (its outputs: "
     "F_aft, F_engine_aft, F_fwd, a_flight_deck)"),
    ({"fatigue_loads": ["airframe.F_aft", "nocomp.F"]}, "[results] fatigue_loads: 'nocomp.F': no component 'nocomp'"),
    ({"airframe": "nonexistent"}, "[results] airframe: no component 'nonexistent'"),
    ({"airframe": "rotor"}, "[results] airframe: component 'rotor' is a 'rotor.mta_spinning', not an airframe "
                            "('airframe.modal')"),
    # settings nothing reads: they were taken without a word
    ({"sn_cycles": 1e6}, "[results] sn_cycles: given without [results] sn_range_N (the load range of the S-N curve "
                         "it is the cycles of: no Miner damage without it)"),
    ({"fatigue_loads": [], "woehler_exponent": 5.0}, "[results] woehler_exponent: given without [results] "
                                                     "fatigue_loads (the loads it is about)"),
])
def test_a_key_naming_no_part_of_the_run_is_one_line_naming_it(diversion, keys, message):
    with pytest.raises(ValueError) as err:
        results.check(_with(diversion, **keys), _sim())
    assert str(err.value) == message


@pytest.mark.parametrize("keys, message", [
    ({"without_fuse": "no_such_scenario"}, "[results] without_fuse: no shipped scenario 'no_such_scenario'"),
    ({"without_fuse": "blade_loss_rundown", "without_fuse_set": {"rotor.F_unbalnce": 1.0}},
     "[results] without_fuse_set: set rotor.F_unbalnce: rotor.mta_spinning (rotor) has no parameter 'F_unbalnce'"),
    ({"without_fuse": "blade_loss_rundown", "without_fuse_set": {"rotr.F_unbalance": 1.0}},
     "[results] without_fuse_set: scenario 'blade_loss_rundown': no component 'rotr'"),
    ({"without_fuse_set": {"rotor.F_unbalance": 1.0}}, "[results] without_fuse_set: given without [results] "
                                                       "without_fuse"),
])
def test_the_fuse_comparison_is_checked_before_the_run(diversion, keys, message):
    """The comparison's scenario runs after the run: a wrong name would fail the command at the run's end (exit
    2 with the run's files written, minutes or hours later); it is refused before the run starts."""
    with pytest.raises(ValueError) as err:
        results.check(_with(diversion, **keys), _sim())
    assert str(err.value).startswith(message), str(err.value)


def test_a_wrong_comparison_scenario_leaves_no_folder(tmp_path, capsys):
    from rotorcosim.master.cli import main

    sc = tmp_path / "s.toml"
    sc.write_text('[scenario]\nextends = "blade_loss_fuse"\nname = "t"\n[results]\nwithout_fuse = "nope"\n')
    rc = main(["run", str(sc), "--duration", "0.001", "--no-figures", "--quiet", "--out", str(tmp_path / "o")])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and len(err) == 1 and "[results] without_fuse: no shipped scenario 'nope'" in err[0], err
    assert not (tmp_path / "o").exists()


def test_an_s_n_slope_whose_load_powers_overflow_is_refused_before_the_run(tmp_path, capsys):
    """woehler_exponent = 1e6: S^m overflowed, numpy warned and the damage-equivalent loads came out null in
    summary.json after the whole run; refused at the start, naming the key, no folder."""
    from rotorcosim.master.cli import main

    sc = tmp_path / "s.toml"
    sc.write_text('[scenario]\nextends = "blade_loss_diversion"\nname = "t"\n[results]\nwoehler_exponent = 1e6\n')
    rc = main(["run", str(sc), "--duration", "0.001", "--no-figures", "--quiet", "--out", str(tmp_path / "o")])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and len(err) == 1 and "[results] woehler_exponent: must be at most 50" in err[0], err
    assert not (tmp_path / "o").exists()


def test_the_fuse_comparison_takes_what_was_set_on_the_run():
    """blade_loss_fuse with its release moved and another unbalance: the comparison without the fuse ran at the
    shipped release and its own 14 252 N (its without_fuse_set), unlike the run it is set beside; it takes the
    run's settings (after without_fuse_set), those of the fuse itself listed as not carried."""
    from rotorcosim.cases.blade_loss.results import apply_unbalance
    from rotorcosim.cases.rundown import fuse_comparison

    sc = load_scenario(scenarios.path("blade_loss_fuse")).set({"rotor.t_blade_loss": 24.0,
                                                                "fuse0.break_load": 6000.0})
    apply_unbalance(sc, 5700.0)
    plain, carried, lacking = fuse_comparison.comparison_scenario(sc)
    assert carried == {"rotor.t_blade_loss": 24.0, "rotor.F_unbalance": 5700.0} and lacking == ["fuse0.break_load"]
    assert plain.components["rotor"].parameters["t_blade_loss"] == 24.0
    assert plain.components["rotor"].parameters["F_unbalance"] == 5700.0
    # nothing set: the comparison as the scenario names it
    plain, carried, lacking = fuse_comparison.comparison_scenario(load_scenario(scenarios.path("blade_loss_fuse")))
    assert carried == {} and lacking == [] and plain.components["rotor"].parameters["F_unbalance"] == 14252.0
