"""Bad input to ``rotorcosim calibrate`` and ``rotorcosim uq``: one line naming the mistake, exit status 2, nothing
run and no result written."""
import shutil
from pathlib import Path

import pytest

from rotorcosim.master.cli.program import main

TOY = Path(__file__).resolve().parents[1] / "helpers" / "two_masses.toml"

CAL = '''[calibrate]
scenario = "toy.toml"
targets = "targets.csv"
[calibrate.cases.pushed]
"m1.v0" = 1.0
[[calibrate.parameter]]
name = "m1.k"
lower = 20.0
upper = 80.0
start = 30.0
'''
TARGETS = "case,result,value\n,final_outputs.m1.x,0.05\npushed,final_outputs.m1.x,0.1\n"
UQ = '''[uq]
scenario = "toy.toml"
samples = 8
results = ["final_outputs.m1.x"]
[[uq.parameter]]
name = "m1.x0"
distribution = "normal"
mean = 0.1
std = 0.02
'''


def _run(tmp_path, command, spec_text, targets=TARGETS, capsys=None):
    shutil.copy(TOY, tmp_path / "toy.toml")
    (tmp_path / "targets.csv").write_text(targets)
    spec = tmp_path / "spec.toml"
    spec.write_text(spec_text)
    status = main([command, str(spec), "--out", str(tmp_path / "out"), "--serial", "--quiet"])
    err = capsys.readouterr().err.strip()
    return status, err


@pytest.mark.parametrize("change, words", [
    (("m1.k", "m1.stiffness"), ["m1.stiffness", "no parameter 'stiffness'"]),
    (("name = \"m1.k\"", "name = \"m9.k\""), ["m9.k", "no component 'm9'"]),
    (("start = 30.0", "start = 10.0"), ["m1.k", "start 10 is outside the bounds [20, 80]"]),
    (("lower = 20.0", "lower = 90.0"), ["m1.k", "lower 90 must be below upper 80"]),
    (("scenario = \"toy.toml\"", "scenario = \"nowhere.toml\""), ["'nowhere.toml'", "neither a file"]),
    (("targets = \"targets.csv\"", "targets = \"targets.csv\"\nmax_evaluations = 0"), ["max_evaluations", ">= 1"]),
])
def test_bad_calibration_spec(tmp_path, capsys, change, words):
    status, err = _run(tmp_path, "calibrate", CAL.replace(*change), capsys=capsys)
    assert status == 2, err
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    for w in words:
        assert w in err, err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("targets, words", [
    ("case,result,value\nslow,final_outputs.m1.x,0.05\n", ["case 'slow' is not one of the SPEC's cases", "'pushed'"]),
    ("case,result,value\n,final_outputs.m1.x,-0.05\n", ["log residuals need positive values"]),
    ("case,result\n,final_outputs.m1.x\n", ["no column 'value'"]),
    ("case,result,value,holdout\n,final_outputs.m1.x,0.05,1\n", ["every target is a holdout"]),
    ("case,result,value\n", ["no targets, only its header"]),
    ("case,result,value,value\n,final_outputs.m1.x,0.05,0.06\n", ["column(s) 'value' given twice"]),
])
def test_bad_targets(tmp_path, capsys, targets, words):
    status, err = _run(tmp_path, "calibrate", CAL, targets=targets, capsys=capsys)
    assert status == 2, err
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    for w in words:
        assert w in err, err


def test_a_target_result_no_run_has(tmp_path, capsys):
    """A result path the summary lacks is found at the start point, named, and nothing more is run."""
    status, err = _run(tmp_path, "calibrate", CAL, targets="case,result,value\n,final_outputs.m1.q,0.05\n",
                       capsys=capsys)
    assert status == 2 and "final_outputs.m1.q" in err and len(err.splitlines()) == 1, err


@pytest.mark.parametrize("change, words", [
    (("std = 0.02", "std = -0.02"), ["m1.x0", "std must be > 0"]),
    (("samples = 8", "samples = 0"), ["samples must be an integer >= 2, got 0"]),
    (("samples = 8", "samples = 1"), ["samples must be an integer >= 2, got 1", "one sample has no spread"]),
    (("distribution = \"normal\"", "distribution = \"gamma\""), ["distribution 'gamma'"]),
    (("distribution = \"normal\"", "distribution = \"uniform\""), ["needs lower, upper; lower is missing"]),
    (("name = \"m1.x0\"", "name = \"m1.nothing\""), ["m1.nothing", "no parameter 'nothing'"]),
    (("samples = 8", "samples = 8\nsampler = \"grid\""), ["sampler 'grid'"]),
])
def test_bad_uq_spec(tmp_path, capsys, change, words):
    status, err = _run(tmp_path, "uq", UQ.replace(*change), capsys=capsys)
    assert status == 2, err
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    for w in words:
        assert w in err, err
    assert not (tmp_path / "out").exists()


def test_a_folder_of_another_study_is_refused(tmp_path, capsys):
    """--out holding another SPEC's study (or other files) is refused, not mixed."""
    status, _ = _run(tmp_path, "uq", UQ, capsys=capsys)
    assert status == 0
    status, err = _run(tmp_path, "uq", UQ.replace("std = 0.02", "std = 0.03"), capsys=capsys)
    assert status == 2 and "holds a study of another SPEC" in err, err
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "notes.txt").write_text("mine")
    status = main(["uq", str(tmp_path / "spec.toml"), "--out", str(tmp_path / "other"), "--serial", "--quiet"])
    assert status == 2 and "is not empty" in capsys.readouterr().err


def test_an_unreachable_scheduler_is_one_line_and_writes_nothing(tmp_path, capsys, monkeypatch):
    """--scheduler ADDRESS that nothing listens at: one line naming it, exit status 2, no output folder."""
    from rotorcosim.master.study import evaluate

    monkeypatch.setattr(evaluate, "CONNECT_TIMEOUT_S", 2.0)
    monkeypatch.setattr(evaluate.check_scheduler, "__defaults__", (2.0,))
    shutil.copy(TOY, tmp_path / "toy.toml")
    spec = tmp_path / "spec.toml"
    spec.write_text(UQ)
    status = main(["uq", str(spec), "--out", str(tmp_path / "out"), "--scheduler", "tcp://127.0.0.1:9", "--quiet"])
    err = capsys.readouterr().err.strip()
    assert status == 2 and "tcp://127.0.0.1:9" in err and "cannot reach" in err and len(err.splitlines()) == 1, err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("command, body, words", [
    ("calibrate", '[calibrate]\nscenario = "blade_loss"\ntargets = "targets.csv"\n[[calibrate.parameter]]\n'
                  'name = "bearing0.balls"\nlower = 15\nupper = 25\nstart = 21\n',
     ["parameter bearing0.balls", "takes an integer, not a real number", "[calibrate.cases.NAME]"]),
    ("calibrate", '[calibrate]\nscenario = "blade_loss"\ntargets = "targets.csv"\n[[calibrate.parameter]]\n'
                  'name = "damper0.cavitation"\nlower = 0.0\nupper = 1.0\nstart = 0.5\n',
     ["parameter damper0.cavitation", "takes a Boolean (true/false), not a real number"]),
    ("uq", '[uq]\nscenario = "blade_loss"\nsamples = 8\nresults = ["bearings.0.whirl_amplitude_mm"]\n'
           '[[uq.parameter]]\nname = "bearing0.balls"\ndistribution = "uniform"\nlower = 15\nupper = 25\n',
     ["parameter bearing0.balls", "takes an integer, not a real number", "[uq.set]"]),
    ("uq", '[uq]\nscenario = "blade_loss"\nsamples = 8\nresults = ["bearings.0.whirl_amplitude_mm"]\n'
           '[[uq.parameter]]\nname = "bearing0.inner_motion"\ndistribution = "uniform"\nlower = 0\nupper = 1\n',
     ["parameter bearing0.inner_motion", "takes a string, not a real number"]),
])
def test_a_parameter_that_takes_no_real_number_is_refused(tmp_path, capsys, command, body, words):
    """A study varies real numbers: an integer parameter (a bearing's ball count: its calibration ran, every point
    but the start refused by its runs, and reported 'converged' at the start, exit 0), a Boolean or a string one
    is refused before anything runs, naming it and where such a value goes instead."""
    status, err = _run(tmp_path, command, body, targets="case,result,value\n,bearings.0.whirl_amplitude_mm,0.05\n",
                       capsys=capsys)
    assert status == 2, err
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    for w in words:
        assert w in err, err
    assert not (tmp_path / "out").exists()


def test_a_target_in_another_unit_is_warned_at_the_start(tmp_path):
    """A target a factor 10 or more from ours at the start (m for mm), or a degC result given in kelvin, is named
    in calibration.json's warnings (and on stderr at the start): before, the fit ran on and ended with three
    'not identifiable' warnings that said nothing of the cause."""
    from rotorcosim.master.study.targets import Target, unit_warnings

    ts = [Target("", "bearings.0.whirl_amplitude_mm", 5.8e-5), Target("", "bearings.0.T_sfd_oil_C", 307.1),
          Target("", "bearings.0.drag_power_W", 1400.0), Target("low", "bearings.0.T_ball_C", 35.0)]
    lines = unit_warnings(ts, [0.055, 30.5, 1133.0, 31.0])
    assert len(lines) == 2, lines
    assert "bearings.0.whirl_amplitude_mm: 5.8e-05 is 0.00105 times ours at the start (0.055)" in lines[0]
    assert "(mm)" in lines[0] and "kelvin" in lines[1] and "(degC)" in lines[1]
    shutil.copy(TOY, tmp_path / "toy.toml")
    (tmp_path / "targets.csv").write_text("case,result,value\n,final_outputs.m1.x,50.0\npushed,final_outputs.m1.x,0.1\n")
    (tmp_path / "spec.toml").write_text(CAL.replace('targets = "targets.csv"', 'targets = "targets.csv"\nmax_evaluations = 1'))
    import rotorcosim

    rep = rotorcosim.calibrate(tmp_path / "spec.toml", tmp_path / "out", serial=True, quiet=True)
    assert any(w.startswith("target final_outputs.m1.x: 50 is ") and "times ours at the start" in w
               for w in rep["warnings"]), rep["warnings"]
