"""What made a run (master/run/provenance.py) and what a run leaves in its folder (master/run/rundir.py).

Checked against the command that was given: ``run blade_loss_5700 --unbalance 2850 --set damper0.k_spring=7e6``
must say in summary.json and in the time series file's attributes that it ran the scenario file
blade_loss_5700.toml with those two changes, the parameters each component ran with, and the code's version; the
summary's existing keys keep their values. A finished run's folder holds no lock file; a run refused at set-up
(a value no component starts from, a missing model file) leaves no folder.
"""
import json

import h5py
import pytest

import rotorcosim
from rotorcosim.master.cli import main
from rotorcosim.master.run.provenance import provenance
from rotorcosim.master.run.rundir import LOCK


def test_summary_and_time_series_say_what_made_the_run(tmp_path, capsys):
    out = tmp_path / "run"
    assert main(["run", "blade_loss_5700", "--unbalance", "2850", "--set", "damper0.k_spring=7e6",
                 "--duration", "0.02", "--no-figures", "--quiet", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["scenario"] == "blade_loss_2850"  # an existing key keeps its value (the run's name)
    p = s["provenance"]
    assert p["rotorcosim_version"] == rotorcosim.__version__
    assert p["scenario_file"].endswith("scenarios/blade_loss_5700.toml")
    assert p["scenario_name"] == "blade_loss_5700"
    assert [{k: e[k] for k in e if k != "origin"} for e in p["edits"]] == [
        {"set": "damper0.k_spring", "value": 7e6, "engine_quantity": "damper.0.k_spring"},
        {"unbalance": 2850.0, "parameter": "rotor.F_unbalance"}]
    assert p["parameters"]["damper0"]["parameters"]["k_spring"] == 7e6
    assert p["parameters"]["damper5"]["parameters"]["k_spring"] != 7e6  # only the one that was set
    assert p["parameters"]["rotor"]["parameters"]["F_unbalance"] == 2850.0
    assert p["parameters"]["rotor"]["implementation"] == "rotor.mta"
    # defaults the scenario file does not write are there too: every declared parameter of the bearing
    from rotorcosim.components import registry

    declared = {v.name for v in registry.lookup(p["parameters"]["bearing0"]["implementation"]).variables
                if v.causality == "parameter"}
    assert set(p["parameters"]["bearing0"]["parameters"]) == declared
    with h5py.File(out / "timeseries.h5") as f:
        assert f.attrs["rotorcosim_version"] == rotorcosim.__version__
        assert f.attrs["scenario_name"] == "blade_loss_5700"
        assert f.attrs["scenario_file"] == p["scenario_file"]
        assert json.loads(f.attrs["provenance"]) == p
    assert not (out / LOCK).exists()
    assert sorted(x.name for x in out.iterdir()) == ["summary.json", "timeseries.h5"]


def test_swap_and_api_changes_are_recorded():
    sc = rotorcosim.load_scenario("blade_loss_2850").swap("damper0", "damper.fe").set({"damper0.k_spring": 6e6})
    p = provenance(sc)
    assert p["edits"][0]["swap"] == "damper0" and p["edits"][0]["implementation"] == "damper.fe"
    assert p["edits"][1]["set"] == "damper0.k_spring" and p["edits"][1]["value"] == 6e6
    assert p["parameters"]["damper0"]["implementation"] == "damper.fe"
    assert rotorcosim.load_scenario("blade_loss_2850").edits == []  # loading afresh: no edit


@pytest.mark.parametrize("setting, message", [("damper0.k_spring=-7e6", "damper0.k_spring must be >= 0"),
                                              ("rotor.model_file=nothere.toml", "rotor model file not found")])
def test_a_run_refused_at_set_up_leaves_no_folder(tmp_path, capsys, setting, message):
    out = tmp_path / "new" / "run"
    assert main(["run", "blade_loss_2850", "--set", setting, "--duration", "0.02", "--no-figures", "--quiet",
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0]
    assert not (tmp_path / "new").exists()
    # a folder that was there before is left as it was: empty
    there = tmp_path / "there"
    there.mkdir()
    assert main(["run", "blade_loss_2850", "--set", setting, "--duration", "0.02", "--no-figures", "--quiet",
                 "--out", str(there)]) == 2
    assert list(there.iterdir()) == []


def test_the_lock_is_taken_from_the_file_the_folder_has(tmp_path, monkeypatch):
    """A run that ends removes its lock file while it holds the lock; one that opened the file just before
    must not keep a lock on the removed file (it would exclude no one): it takes the folder's new file."""
    import fcntl
    import os

    from rotorcosim.master.run import rundir

    out = tmp_path / "o"
    out.mkdir()
    stale = os.open(out / LOCK, os.O_RDWR | os.O_CREAT)  # the file as a finishing run left it, then removed
    os.unlink(out / LOCK)
    real_open = os.open
    calls = []

    def open_stale_first(path, *a, **kw):  # the first open returns the removed file, as the race would
        calls.append(path)
        return os.dup(stale) if len(calls) == 1 else real_open(path, *a, **kw)

    monkeypatch.setattr(rundir.os, "open", open_stale_first)
    try:
        with rundir.RunFolder(out) as f:
            assert os.fstat(f._fd).st_ino == os.stat(out / LOCK).st_ino
            assert len(calls) == 2
            fcntl.flock(stale, fcntl.LOCK_SH | fcntl.LOCK_NB)  # the stale file is not what is held
    finally:
        monkeypatch.undo()
        os.close(stale)
    assert not (out / LOCK).exists()
