"""Phases are names a scenario declares (``[schedule.phases]``, master/core/phases.py): a scenario that calls its
coupled and held phases otherwise runs the same numbers as one with the default names, and speaks of its phases
by its own names in the timeline, the summary, the time series and ``Result.phase``. Checked against the same
toy system run with the default names (the reference: the same scenario before the renaming)."""
import json

import h5py
import numpy as np
import pytest

import rotorcosim
from rotorcosim.master.cli import main
from rotorcosim.master.core.phases import Phases
from rotorcosim.scenarios import path as path_of

RENAMED = '[schedule.phases]\ncoupled = "mech"\nheld = "heat"\n'


def renamed_toy(tmp_path, extra: str = RENAMED, mapping=(('"TM"', '"mech"'), ('"TO"', '"heat"'))):
    text = path_of("toy_thermomechanical").read_text()
    for a, b in mapping:
        text = text.replace(f"phase = {a}", f"phase = {b}")
    text = text.replace("[outputs]", extra + "\n[outputs]")
    p = tmp_path / "renamed.toml"
    p.write_text(text)
    return p


@pytest.mark.parametrize("schedule, duration", [("scenario", 1.0), ("auto", 12.0)])
def test_renamed_phases_run_the_same_numbers(tmp_path, schedule, duration):
    ref = rotorcosim.simulate("toy_thermomechanical", duration=duration, schedule=schedule, out=tmp_path / "a")
    res = rotorcosim.simulate(str(renamed_toy(tmp_path)), duration=duration, schedule=schedule, out=tmp_path / "b")
    assert np.array_equal(ref.time, res.time) and np.array_equal(ref["node.T"], res["node.T"])
    names = {"TM": "mech", "TO": "heat"}
    assert set(ref.phase) == {"TM", "TO"}
    assert list(res.phase) == [names[p] for p in ref.phase]
    tl_a = json.loads((tmp_path / "a" / "summary.json").read_text())["timeline"]
    tl_b = json.loads((tmp_path / "b" / "summary.json").read_text())["timeline"]
    assert [names[u["phase"]] for u in tl_a] == [u["phase"] for u in tl_b]
    with h5py.File(tmp_path / "b" / "timeseries.h5") as f:
        assert f["phase"].attrs["description"] == "0 = mech (coupled), 1 = heat (held)"
    with h5py.File(tmp_path / "a" / "timeseries.h5") as f:  # the default names keep the files' words
        assert f["phase"].attrs["description"] == "0 = thermo-mechanical (TM), 1 = thermal-only (TO)"


@pytest.mark.parametrize("extra, mapping, words", [
    (RENAMED, (('"TM"', '"mech"'), ('"TO"', '"TO"')), "'TO' is not a phase of the scenario: 'mech' or 'heat'"),
    ('[schedule.phases]\ncoupled = "x"\nheld = "x"\n', (), "coupled and held must differ"),
    ('[schedule.phases]\ncoupled = "TM"\nfrozen = "TO"\n', (), "frozen"),
    ('[schedule.phases]\ncoupled = 3\n', (), "coupled"),
])
def test_bad_phase_declarations_are_one_line_errors(tmp_path, capsys, extra, mapping, words):
    path = renamed_toy(tmp_path, extra, mapping)
    assert main(["run", str(path), "--duration", "0.5", "--out", str(tmp_path / "out"), "--quiet"]) != 0
    err = capsys.readouterr().err.strip()
    assert words in err and "Traceback" not in err and len(err.splitlines()) == 1, err
    assert not (tmp_path / "out" / "summary.json").exists()


def test_phases_record():
    p = Phases.from_spec({"coupled": "mech", "held": "heat"})
    assert p.names == ("mech", "heat") and Phases.code(p.role("heat")) == 1 and Phases.code(p.role("mech")) == 0
    with pytest.raises(Exception, match="not one the scenario declares"):
        p.role("TM")
    assert Phases.from_spec(None) == Phases() and Phases().names == ("TM", "TO")
